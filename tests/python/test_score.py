"""facetlab.score against ``facetlab score --json``: five kinds of cut to 1e-12, score_many
in order, and errors as the command line's one-line messages."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Dict, List, Union

import facetlab
import pytest

from conftest import Cli, assert_close, cli_json


def test_a_preset_scores_as_the_command_line_does(cli: Cli, tmp_path: Path) -> None:
    want = cli_json(cli, tmp_path, "score", "tolkowsky")
    got = facetlab.score("tolkowsky")
    assert_close(got.to_dict(), want)
    assert got.brilliance == want["brilliance"] and got.fire == want["fire"]
    assert got.aset == want["aset"]
    assert got.cut == want["cut"] == "Tolkowsky"


def test_a_family_with_parameters(cli: Cli, tmp_path: Path) -> None:
    c = facetlab.family("round-brilliant", table=0.56, crown_angle=34.5, pavilion_angle=40.9)
    assert c.params["table"] == 0.56 and c.family == "round-brilliant"
    c.write(tmp_path / "f.toml")
    want = cli_json(cli, tmp_path, "score", "f.toml")
    # The in-memory cut, never written or read back, gives the file's numbers.
    assert_close(facetlab.score(c).to_dict(), want)


def test_a_gemcad_design_with_set_keeps_its_meets(cli: Cli, tmp_path: Path) -> None:
    facetlab.cut("tolkowsky").write(tmp_path / "t.asc")
    want = cli_json(cli, tmp_path, "score", "t.asc", "--set", "pavilion-main=41.2")
    design = facetlab.cut(tmp_path / "t.asc").with_set({"pavilion-main": 41.2})
    assert_close(facetlab.score(design).to_dict(), want)
    plain = facetlab.score(tmp_path / "t.asc")
    assert plain.brilliance != want["brilliance"]


def test_a_coloured_stone(cli: Cli, tmp_path: Path) -> None:
    want = cli_json(
        cli, tmp_path, "score", "tolkowsky", "--material", "ruby", "--size-mm", "7.2"
    )
    got = facetlab.score("tolkowsky", material="ruby", size_mm=7.2).to_dict()
    assert "colour" in got and got["settings"]["colour"]["name"]
    assert_close(got, want)
    want = cli_json(cli, tmp_path, "score", "tolkowsky", "--colour", "#7a3fa0@10mm")
    assert_close(facetlab.score("tolkowsky", colour="#7a3fa0@10mm").to_dict(), want)


def test_an_obj_mesh(cli: Cli, tmp_path: Path) -> None:
    facetlab.cut("gia-reference").write(tmp_path / "g.obj")
    want = cli_json(cli, tmp_path, "score", "g.obj")
    assert_close(facetlab.score(str(tmp_path / "g.obj")).to_dict(), want)


def test_score_many_keeps_the_order_and_the_numbers() -> None:
    cuts: List[Union[str, facetlab.Cut]] = [
        "tolkowsky",
        facetlab.family("round-brilliant", table=0.6),
        "gia-reference",
    ]
    many = facetlab.score_many(cuts, polarization=False)
    assert [s.cut for s in many] == ["Tolkowsky", "round-brilliant", "GIA reference"]
    for c, s in zip(cuts, many):
        assert s.to_dict() == facetlab.score(c, polarization=False).to_dict()


@pytest.mark.parametrize(
    "kwargs, flag",
    [
        ({"material": "unobtainium"}, ["--material", "unobtainium"]),
        ({"colour": "#12345"}, ["--colour", "#12345"]),
        ({"colour_density": -1.0}, ["--colour-density", "-1"]),
        ({"head_shadow": 75.0}, ["--head-shadow", "75"]),
        ({"size_mm": "5x"}, ["--size-mm", "5x"]),
    ],
)
def test_bad_input_is_the_command_lines_one_line_error(
    cli: Cli, tmp_path: Path, kwargs: Dict[str, Any], flag: List[str]
) -> None:
    p = cli(tmp_path, "score", "tolkowsky", *flag)
    assert p.returncode == 2
    line = p.stderr.strip().splitlines()[-1]
    with pytest.raises(facetlab.Error) as e:
        facetlab.score("tolkowsky", **kwargs)
    msg = str(e.value)
    assert isinstance(e.value, ValueError) and "\n" not in msg
    # The same message; the command line names the flag, Python the keyword argument.
    field, _, rest = msg.partition(": ")
    assert line.endswith(rest), (line, msg)
    assert field.replace("_", "-") in line


def test_with_set_and_family_errors_name_the_field(tmp_path: Path) -> None:
    with pytest.raises(facetlab.Error, match=r"^crown_angle: 75 is out of range"):
        facetlab.family("round-brilliant", crown_angle=75)
    with pytest.raises(facetlab.Error, match=r"^with_set "):
        facetlab.cut("tolkowsky").with_set(nonsense=1.0)
    with pytest.raises(facetlab.Error, match="exists; pass overwrite=True"):
        facetlab.cut("tolkowsky").write(tmp_path / "a.toml")
        facetlab.cut("tolkowsky").write(tmp_path / "a.toml")


def test_info_is_the_info_document(cli: Cli, tmp_path: Path) -> None:
    p = cli(tmp_path, "info", "tolkowsky", "--json", "--meets")
    assert p.returncode == 0, p.stderr
    import json

    assert_close(facetlab.cut("tolkowsky").info(meets=True), json.loads(p.stdout))


def test_materials_are_the_materials_document(cli: Cli, tmp_path: Path) -> None:
    import json

    p = cli(tmp_path, "materials", "--json")
    assert p.returncode == 0, p.stderr
    got = facetlab.materials()
    assert got == json.loads(p.stdout)
    ruby = next(m for m in got if m["name"] == "ruby")
    assert ruby["variety_of"] == "sapphire" and ruby["colour"]["hex"].startswith("#")
    assert "round-brilliant" in facetlab.families() and "tolkowsky" in facetlab.presets()


def test_the_gil_is_released_while_tracing() -> None:
    import threading

    ticks = 0
    done = threading.Event()

    def work() -> None:
        facetlab.score_many(["tolkowsky"] * 3)
        done.set()

    t = threading.Thread(target=work)
    t.start()
    while not done.is_set():  # pure Python: runs only while the tracer does not hold the GIL
        ticks += 1
    t.join()
    assert ticks > 1000, ticks
