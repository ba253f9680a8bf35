"""Several stones in one rough from Python (issue 54): ``facetlab.plan(..., stones=,
kerf=, allowance=, inclusions=, margin=)`` plans the layout ``facetlab plan --stones N``
plans and writes the same folder; bad values are refused naming the keyword."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any, Callable, List, Tuple

import facetlab
import pytest

from conftest import Cli

# A short search: two starts, few iterations, three saw offsets per direction.
CONFIG = "seed = 3\n[search]\nstarts = 2\nmax_iterations = 40\nsaw_offsets = 3\n"


def speck(path: Path, centre: tuple[float, float, float], r: float) -> Path:
    """A closed tetrahedron of size ``r`` mm at ``centre`` (an inclusion)."""
    x, y, z = centre
    corners = [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]
    lines = [f"v {x + r * a} {y + r * b} {z + r * c}" for a, b, c in corners]
    lines += ["f 1 2 3", "f 1 3 4", "f 1 4 2", "f 2 4 3"]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_plan_with_stones_is_the_command_lines_layout(cli: Cli, tmp_path: Path) -> None:
    (tmp_path / "plan.toml").write_text(CONFIG)
    inc = speck(tmp_path / "speck.obj", (0.3, 0.2, 0.4), 0.15)
    p = cli(
        tmp_path, "plan", "octahedron", "--size-mm", "6", "--family", "round-brilliant",
        "--stones", "2", "--kerf", "0.25", "--allowance", "0.15", "--inclusion", "speck.obj",
        "--margin", "0.2", "--config", "plan.toml", "--quiet", "-o", "cli",
    )
    assert p.returncode == 0, p.stderr
    want = json.loads((tmp_path / "cli" / "summary.json").read_text())
    got = facetlab.plan(
        "octahedron", size_mm=6, families=["round-brilliant"], config=tmp_path / "plan.toml",
        stones=2, kerf=0.25, allowance=0.15, inclusions=[inc], margin=0.2, out=tmp_path / "py",
    )
    layout = want["layout"]
    assert (layout["kerf_mm"], layout["allowance_mm"], layout["inclusion_margin_mm"]) == (
        0.25, 0.15, 0.2,
    )
    stones = got["plans"]
    assert len(stones) == len(want["stones"]) == layout["stones"]
    for g, w in zip(stones, want["stones"]):
        assert (g["family"], g["piece"], g["carats"]) == (w["family"], w["piece"], w["carats"])
        assert g["holds"] == w["holds"] == []
        assert len(g["centre_mm"]) == 3
    assert got["layout"]["carats"] == pytest.approx(layout["total_carats"], rel=1e-12)
    assert got["layout"]["kerf_loss_mm3"] > 0.0
    saw = [(c["piece"], c["normal"], c["offset_mm"]) for c in got["layout"]["saw_plan"]]
    assert saw == [(c["piece"], c["normal"], c["offset_mm"]) for c in want["saw_plan"]]
    # The same folder, file for file (the run's seconds aside).
    names = sorted(f.name for f in (tmp_path / "cli").iterdir())
    assert sorted(f.name for f in (tmp_path / "py").iterdir()) == names
    x = json.loads((tmp_path / "py" / "summary.json").read_text())
    assert x.pop("elapsed_s") >= 0 and want.pop("elapsed_s") >= 0
    assert x == want
    # Without out: the stones alone, the same ones.
    again = facetlab.plan(
        "octahedron", size_mm=6, families=["round-brilliant"], config=tmp_path / "plan.toml",
        stones=2, kerf=0.25, allowance=0.15, inclusions=[str(inc)], margin=0.2,
    )
    assert [s["carats"] for s in again] == [s["carats"] for s in stones]


def test_a_laser_layout_is_the_command_lines(cli: Cli, tmp_path: Path) -> None:
    (tmp_path / "plan.toml").write_text(CONFIG)
    p = cli(
        tmp_path, "plan", "octahedron", "--size-mm", "6", "--family", "round-brilliant",
        "--stones", "2", "--cutter", "laser", "--config", "plan.toml", "--quiet", "-o", "cli",
    )
    assert p.returncode == 0, p.stderr
    want = json.loads((tmp_path / "cli" / "summary.json").read_text())
    got = facetlab.plan(
        "octahedron", size_mm=6, families=["round-brilliant"], config=tmp_path / "plan.toml",
        stones=2, cutter="laser", out=tmp_path / "py",
    )
    assert want["layout"]["cutter"] == got["layout"]["cutter"] == "laser"
    pairs = got["layout"]["pairs"]
    assert [q["stones"] for q in pairs] == [[0, 1]] * (len(got["plans"]) - 1)
    assert [q["offset_mm"] for q in pairs] == [q["offset_mm"] for q in want["layout"]["pairs"]]
    assert got["layout"]["carats"] == pytest.approx(want["layout"]["total_carats"], rel=1e-12)


def test_bad_layout_keywords_are_refused_by_name(tmp_path: Path) -> None:
    cases: List[Tuple[Callable[[], Any], str]] = [
        (lambda: facetlab.plan("octahedron", size_mm=6, stones=0), "stones"),
        (lambda: facetlab.plan("octahedron", size_mm=6, stones=9), "stones"),
        (lambda: facetlab.plan("octahedron", size_mm=6, kerf=-0.1), "kerf"),
        (lambda: facetlab.plan("octahedron", size_mm=6, allowance=float("nan")), "allowance"),
        (lambda: facetlab.plan("octahedron", size_mm=6, margin=11.0), "margin"),
        (lambda: facetlab.plan("octahedron", size_mm=6, cutter="wire"), "cutter"),
    ]
    for call, name in cases:
        with pytest.raises(facetlab.Error, match=f"^{name}: "):
            call()
    with pytest.raises(facetlab.Error, match="missing.obj"):
        facetlab.plan("octahedron", size_mm=6, inclusions=[tmp_path / "missing.obj"])
    (tmp_path / "open.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n")
    with pytest.raises(facetlab.Error, match="open.obj"):
        facetlab.plan("octahedron", size_mm=6, inclusions=[tmp_path / "open.obj"], out=tmp_path / "o")
    assert not (tmp_path / "o").exists()


def test_a_colour_layout_is_the_command_lines(cli: Cli, tmp_path: Path) -> None:
    """``[objective] kind = "colour"`` with two stones: the layout ranked by value × colour,
    each stone's ``worth`` × ``colour_factor`` its ``objective``, as ``summary.json`` has it."""
    (tmp_path / "plan.toml").write_text(
        'material = "ruby"\n[objective]\nkind = "colour"\n[rough]\nc_axis = [0.3, -0.2, 0.9]\n'
        + CONFIG.replace("seed = 3\n", "")
    )
    p = cli(
        tmp_path, "plan", "octahedron", "--size-mm", "5", "--family", "oval", "--top", "1",
        "--stones", "2", "--config", "plan.toml", "--quiet", "-o", "cli",
    )
    assert p.returncode == 0, p.stderr
    want = json.loads((tmp_path / "cli" / "summary.json").read_text())
    got = facetlab.plan(
        "octahedron", size_mm=5, families=["oval"], top=1, stones=2,
        config=tmp_path / "plan.toml", out=tmp_path / "py",
    )
    assert want["objective"] == "colour"
    layout = got["layout"]
    assert layout["colour_reference"] == want["layout"]["colour_reference_c"] > 0.0
    assert layout["total_worth"] == pytest.approx(want["layout"]["total_worth"], rel=1e-12)
    assert len(got["plans"]) == len(want["stones"])
    for g, w in zip(got["plans"], want["stones"]):
        assert (g["worth"], g["colour_factor"]) == (w["worth"], w["colour_factor"])
        assert g["objective"] == pytest.approx(g["worth"] * g["colour_factor"], rel=1e-12)
        assert g["colour"]["c"] == w["colour"]["c"]
