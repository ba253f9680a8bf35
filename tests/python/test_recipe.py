"""facetlab.Recipe: a design written tier by tier, built by the library as the binary builds a
recipe file (``facetlab design``), its errors naming the tier, its TOML form and the recipe of
an existing design."""

from __future__ import annotations

from pathlib import Path

import facetlab
import pytest

from conftest import Cli

SIMPLE = """[design]
name = "simple"
gear = 96
symmetry = 8
mirror = true
index = 1.54

[[tier]]
name = "P1"
angle = -42
indices = [96]
centre = true

[[tier]]
name = "G1"
angle = 90
indices = [96]
depth = 0.9

[[tier]]
name = "C1"
angle = 38
indices = "96"
girdle = 0.03

[[tier]]
name = "T"
angle = 0
table = 0.55
"""


def simple() -> facetlab.Recipe:
    r = facetlab.Recipe(name="simple", gear=96, symmetry=8, mirror=True, index=1.54)
    r.add_tier("P1", -42, [96], centre=True)
    r.add_tier("G1", 90, [96], depth=0.9)
    r.add_tier("C1", 38, "96", girdle=0.03)
    r.add_tier("T", 0, table=0.55)
    return r


def test_a_recipe_built_in_python_is_the_recipe_file_loaded(tmp_path: Path, cli: Cli) -> None:
    path = tmp_path / "simple.toml"
    path.write_text(SIMPLE)
    built = simple().build()
    loaded = facetlab.cut(str(path))
    assert built.facets == loaded.facets == 25
    a, b = built.info(), loaded.info()
    assert abs(a["volume"] - b["volume"]) < 1e-12, (a["volume"], b["volume"])
    assert a["ratios"] == b["ratios"]
    # And the binary's build of the same file: the same design written.
    p = cli(tmp_path, "design", "simple.toml", "-o", "simple.asc")
    assert p.returncode == 0, p.stderr
    built.write(tmp_path / "py.asc")
    assert (tmp_path / "py.asc").read_text() == (tmp_path / "simple.asc").read_text()
    assert facetlab.Recipe.from_toml(SIMPLE) == simple()


def test_steps_and_findings_name_each_tier() -> None:
    steps = simple().steps()
    assert [s["tier"] for s in steps] == ["P1", "G1", "C1", "T"]
    assert steps[0]["instruction"] == "cut to centre point"
    assert len(steps[0]["indices"]) == 8 and steps[0]["angle"] == -42.0
    assert simple().findings() == []
    r = facetlab.Recipe(symmetry=8, mirror=True, index=1.54)
    r.add_tier("P1", -38, [96], centre=True)
    r.add_tier("G1", 90, [96], depth=0.9)
    r.add_tier("C1", 38, [96], girdle=0.03)
    r.add_tier("T", 0, table=0.55)
    f = r.findings()
    assert [(x["tier"], x["kind"]) for x in f] == [("P1", "below-critical")]
    assert "P1" in f[0]["message"]


def test_errors_name_the_tier() -> None:
    r = facetlab.Recipe(symmetry=8, mirror=True)
    with pytest.raises(facetlab.Error, match=r"^tier P1: give exactly one of meet, centre"):
        r.add_tier("P1", -42, [96])
    with pytest.raises(facetlab.Error, match=r"^tier P1: give exactly one .*; got centre and depth"):
        r.add_tier("P1", -42, [96], centre=True, depth=1.0)
    with pytest.raises(facetlab.Error, match=r"^tier P1: angle `steep`"):
        r.add_tier("P1", "steep", [96], centre=True)
    with pytest.raises(facetlab.Error, match=r"^tier P1: side `up`"):
        r.add_tier("P1", -42, [96], centre=True, side="up")
    with pytest.raises(facetlab.Error, match=r"^tier P1: indices"):
        r.add_tier("P1", -42, "3:0:9", centre=True)
    assert len(r) == 0
    # A tier off the gear, a meet of tiers that do not exist: refused at build, naming it.
    r.add_tier("P1", -42, [96.5], centre=True)
    with pytest.raises(facetlab.Error, match=r"^tier P1: index 96.5 is off the 96 gear"):
        r.build()
    r = simple()
    r.add_tier("S", 30, [3], meet=["C1", "NOPE"])
    with pytest.raises(facetlab.Error, match=r"^tier S: "):
        r.build()
    with pytest.raises(facetlab.Error, match=r"^gear: "):
        facetlab.Recipe(gear=-1)
    with pytest.raises(facetlab.Error, match=r"^text: tier P2: "):
        facetlab.Recipe.from_toml('[[tier]]\nname = "P2"\nangle = 40\n')


def test_the_toml_form_round_trips() -> None:
    r = simple()
    r.add_tier("S", "=C1-8", "3-9", meet="C1-T", note="stars")
    back = facetlab.Recipe.from_toml(r.to_toml())
    assert back == r and back.to_toml() == r.to_toml()
    assert back.tiers == ["P1", "G1", "C1", "T", "S"]
    assert back != simple()


def test_the_recipe_of_a_design_builds_it_again() -> None:
    cut = facetlab.cut("tolkowsky")
    for design in (cut, "tolkowsky"):
        r = facetlab.Recipe.from_design(design)
        back = r.build()
        assert back.facets == cut.facets
        assert abs(back.info()["volume"] - cut.info()["volume"]) < 1e-9
    assert facetlab.Recipe.from_toml(r.to_toml()).build().facets == cut.facets
    with pytest.raises(facetlab.Error, match=r"^cut: "):
        facetlab.Recipe.from_design(3)  # type: ignore[arg-type]
