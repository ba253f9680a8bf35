"""Sweeps and optimization runs from Python against ``facetlab sweep`` and ``facetlab
optimize``: the same CSV byte for byte, the same winners and history; Ctrl-C stops a run
within a second with its folder written."""

from __future__ import annotations

import _thread
import csv
import io
import json
import threading
import time
from pathlib import Path
from typing import Any, Dict, List

import facetlab
import pytest

from conftest import TINY, Cli

AXES = ["crown_angle:33:34:1", "pavilion_angle:40:41:1", "table:0.55:0.56:0.01"]

RUN = """
name = "small"
seed = 3
[cut]
family = "round-brilliant"
[free]
crown_angle = [32.0, 36.0]
pavilion_angle = [40.0, 42.0]
[score]
ri = 1.54
polarization = false
[method]
starts = 1
max_evaluations = 10
[verify]
winners = 0
"""


def toml_dict(text: str) -> Dict[str, Any]:
    tomllib = pytest.importorskip("tomllib")
    return dict(tomllib.loads(text))


def test_a_grids_rows_make_the_sweeps_csv(cli: Cli, tmp_path: Path) -> None:
    (tmp_path / "tiny.toml").write_text(TINY)
    args = ["--x", AXES[0], "--y", AXES[1], "--axis", AXES[2]]
    p = cli(tmp_path, "sweep", "tiny.toml", *args, "--out", "one", "--quiet")
    assert p.returncode == 0, p.stderr
    want = (tmp_path / "one" / "sweep.csv").read_text()
    grid = facetlab.Grid(tmp_path / "tiny.toml", AXES)
    assert len(grid) == 8 and grid.keys == ["crown_angle", "pavilion_angle", "table"]
    rows = grid.rows()
    assert grid.csv(rows) == want
    # Chunks evaluated apart and handed back in any order merge to the same bytes.
    parts: List[Dict[str, Any]] = grid.rows([5, 6, 7]) + grid.rows([0, 1, 2, 3, 4])
    assert grid.csv(parts[::-1]) == want
    # The rows are the CSV's numbers.
    table = list(csv.DictReader(io.StringIO(want)))
    for r, t in zip(rows, table):
        assert r["ok"] and repr(r["brilliance"]) == t["brilliance"]
    # A dict of the TOML's shape is the same config.
    assert facetlab.Grid(toml_dict(TINY), AXES).csv(rows) == want
    with pytest.raises(facetlab.Error, match="give each of the grid's 8 points once"):
        grid.csv(rows[:7])


def test_an_optimize_run_from_a_dict_equals_the_command_lines(
    cli: Cli, tmp_path: Path
) -> None:
    (tmp_path / "small.toml").write_text(RUN)
    p = cli(tmp_path, "optimize", "small.toml", "--out", "cli", "--quiet")
    assert p.returncode == 0, p.stderr
    seen: List[Dict[str, Any]] = []
    report = facetlab.optimize(toml_dict(RUN), out=tmp_path / "py", progress=seen.append)
    assert report["folder"] == str(tmp_path / "py")
    want = json.loads((tmp_path / "cli" / "report.json").read_text())
    for k in ("winners", "start"):
        assert report[k] == want[k], k
    assert (tmp_path / "py" / "history.csv").read_text() == (
        tmp_path / "cli" / "history.csv"
    ).read_text()
    assert (tmp_path / "py" / "best.asc").read_text() == (tmp_path / "cli" / "best.asc").read_text()
    assert seen and seen[-1]["budget"] == 10
    with pytest.raises(facetlab.Error, match="not empty"):
        facetlab.optimize(toml_dict(RUN), out=tmp_path / "py")


def test_a_pareto_run_from_a_dict_equals_the_command_lines(cli: Cli, tmp_path: Path) -> None:
    text = RUN.replace("[method]", "[objective]\npareto = [\"brilliance\", \"fire\"]\npareto_points = 2\n[method]")
    (tmp_path / "tradeoff.toml").write_text(text)
    p = cli(tmp_path, "optimize", "tradeoff.toml", "--out", "cli", "--quiet")
    assert p.returncode == 0, p.stderr
    front = facetlab.optimize(toml_dict(text), out=tmp_path / "py")
    assert front["folder"] == str(tmp_path / "py")
    want = json.loads((tmp_path / "cli" / "pareto.json").read_text())

    def timeless(v: Any) -> Any:
        # Wall-clock seconds (the run's and each verification's) are not numbers to repeat.
        if isinstance(v, dict):
            return {k: timeless(x) for k, x in v.items() if k != "seconds"}
        if isinstance(v, list):
            return [timeless(x) for x in v]
        return v

    for k in ("front", "scores", "searches", "evaluations"):
        assert timeless(front[k]) == timeless(want[k]), k
    assert (tmp_path / "py" / "pareto.csv").read_text() == (
        tmp_path / "cli" / "pareto.csv"
    ).read_text()


def test_ctrl_c_stops_a_run_within_a_second_with_its_folder_written(tmp_path: Path) -> None:
    long = RUN.replace("max_evaluations = 10", "max_evaluations = 100000\ntolerance = 0")
    timer = threading.Timer(1.5, _thread.interrupt_main)
    timer.start()
    t0 = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            facetlab.optimize(toml_dict(long), out=tmp_path / "stopped", verify=False)
    finally:
        timer.cancel()
    waited = time.monotonic() - t0 - 1.5
    assert waited < 1.0, f"stopped {waited:.2f} s after Ctrl-C"
    folder = tmp_path / "stopped"
    assert (folder / "report.json").is_file() and (folder / "best.toml").is_file()
    report = json.loads((folder / "report.json").read_text())
    assert report["search"]["evaluations"] < 100000


# A small plan: two families, two plans each, a short search.
FAMILIES = ["round-brilliant", "oval"]


def cli_plan(cli: Cli, tmp_path: Path, out: str) -> Path:
    """``facetlab plan`` of :data:`FAMILIES` with the config ``plan.toml`` (written here) into
    ``out``."""
    (tmp_path / "plan.toml").write_text("seed = 3\n[search]\nstarts = 2\nmax_iterations = 60\n")
    p = cli(
        tmp_path, "plan", "octahedron", "--size-mm", "6", "--family", "round-brilliant",
        "--family", "oval", "--top", "2", "--config", "plan.toml", "--quiet", "-o", out,
    )
    assert p.returncode == 0, p.stderr
    return tmp_path / out


def test_plan_finds_the_command_lines_plans(cli: Cli, tmp_path: Path) -> None:
    want = json.loads((cli_plan(cli, tmp_path, "run") / "summary.json").read_text())["plans"]
    got = facetlab.plan(
        "octahedron", config=tmp_path / "plan.toml", families=FAMILIES, size_mm=6, top=2
    )
    assert [(g["family"], g["rank"]) for g in got] == [(w["family"], w["rank"]) for w in want]
    for g, w in zip(got, want):
        assert g["carats"] == w["carats"] and g["width_mm"] == w["width_mm"]
        assert g["yield_fraction"] == w["yield"] and g["grade"] == w["grade"]
        assert g["cut"].params == w["params"]
    with pytest.raises(facetlab.Error, match="^families: "):
        facetlab.plan("octahedron", families=["trillion-ish"])


def test_plan_writes_the_command_lines_folder(cli: Cli, tmp_path: Path) -> None:
    cli_plan(cli, tmp_path, "cli")
    got = facetlab.plan(
        "octahedron", config=tmp_path / "plan.toml", families=FAMILIES, size_mm=6, top=2,
        out=tmp_path / "py",
    )
    assert got["folder"] == str(tmp_path / "py")
    assert [g["family"] for g in got["plans"]] == ["round-brilliant"] * 2 + ["oval"] * 2
    cli_files = sorted(f.name for f in (tmp_path / "cli").iterdir())
    assert sorted(f.name for f in (tmp_path / "py").iterdir()) == cli_files
    assert {"summary.json", "report.html", "overview.png", "oval-1.asc"} <= set(cli_files)
    for name in cli_files:
        a, b = (tmp_path / "py" / name).read_bytes(), (tmp_path / "cli" / name).read_bytes()
        if name == "summary.json":
            # The run's wall-clock seconds are the one number not to repeat.
            x, y = json.loads(a), json.loads(b)
            assert x.pop("elapsed_s") >= 0 and y.pop("elapsed_s") >= 0
            assert x == y
        else:
            assert a == b, name
    # Refused as the command line refuses: a folder holding files, an input.
    with pytest.raises(facetlab.Error, match="^out: .* exists and is not an empty folder"):
        facetlab.plan("octahedron", size_mm=6, out=tmp_path / "py")
    with pytest.raises(facetlab.Error, match="^out: .* would overwrite the input"):
        facetlab.plan("octahedron", size_mm=6, config=tmp_path / "plan.toml",
                      out=tmp_path / "plan.toml")
    p = cli(tmp_path, "plan", "octahedron", "--size-mm", "6", "-o", "py")
    assert p.returncode == 2 and "--out: " in p.stderr and "not an empty folder" in p.stderr


def test_plan_gives_each_plans_colour_and_optic_axis_as_summary_json(
    cli: Cli, tmp_path: Path
) -> None:
    # A ruby rough with its c-axis, ranked by face-up colour (issue 41's objective).
    (tmp_path / "plan.toml").write_text(
        'seed = 3\nmaterial = "ruby"\n[objective]\nkind = "colour"\n'
        "[rough]\nc_axis = [0.3, -0.2, 0.9]\n[search]\nstarts = 2\nmax_iterations = 40\n"
    )
    p = cli(
        tmp_path, "plan", "octahedron", "--size-mm", "6", "--family", "oval",
        "--config", "plan.toml", "--quiet", "-o", "run",
    )
    assert p.returncode == 0, p.stderr
    want = json.loads((tmp_path / "run" / "summary.json").read_text())["plans"]
    got = facetlab.plan("octahedron", config=tmp_path / "plan.toml", families=["oval"], size_mm=6)
    assert len(got) == len(want) > 0
    for g, w in zip(got, want):
        assert g["optic_axis"] == w["optic_axis"]
        assert g["colour"] == w["colour"] and g["objective"] == w["objective"]
        assert g["colour"]["c"] == g["objective"] > 0
    # A colourless plan by weight has neither.
    plain = facetlab.plan("octahedron", families=["oval"], size_mm=6, top=1)
    assert plain[0]["colour"] is None and plain[0]["optic_axis"] is None
