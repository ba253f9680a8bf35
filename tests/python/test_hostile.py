"""No panic crosses into Python: on the inputs the command line rejects (a seeded fuzz of
broken cut files), the package raises facetlab.Error with the command line's message, never
facetlab.InternalError."""

from __future__ import annotations

import _thread
import random
import threading
import time
from pathlib import Path
from typing import Callable, List, Tuple

import facetlab
import pytest

from conftest import Cli

OCTA = (
    "g 96 0.0\nI 2.42\na 41.0 0.5 0 24 48 72 n crown\na 0 0.3 0 n table\n"
    "a -41.0 0.5 0 24 48 72 n pav\n"
)
OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n"
TOML = 'name = "t"\nfamily = "round-brilliant"\n[params]\ntable = 0.57\n'


def mutations(seed: int, n: int) -> List[Tuple[str, bytes]]:
    """``n`` broken files: valid ones with characters replaced, cut short or doubled, and
    random bytes, each under one of the readers' extensions."""
    rng = random.Random(seed)
    out: List[Tuple[str, bytes]] = []
    alphabet = "0123456789 -.eanIgGHF\n\x00xyz{}[]=\"é"
    for k in range(n):
        ext, text = rng.choice([(".asc", OCTA), (".obj", OBJ), (".toml", TOML), (".stl", OBJ)])
        chars = list(text)
        kind = k % 4
        if kind == 0:
            for _ in range(rng.randint(1, 4)):
                chars[rng.randrange(len(chars))] = rng.choice(alphabet)
            data = "".join(chars).encode()
        elif kind == 1:
            data = "".join(chars[: rng.randrange(1, len(chars))]).encode()
        elif kind == 2:
            data = bytes(rng.randrange(256) for _ in range(rng.randint(0, 200)))
        else:
            data = (text.replace("41.0", str(rng.uniform(-200, 200)))).encode()
        out.append((ext, data))
    return out


def test_broken_files_raise_the_command_lines_error_and_never_panic(
    cli: Cli, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)  # both name the file as given
    refused = 0
    for k, (ext, data) in enumerate(mutations(42, 60)):
        path = tmp_path / f"m{k}{ext}"
        path.write_bytes(data)
        p = cli(tmp_path, "info", path.name)
        try:
            facetlab.cut(path.name)
        except facetlab.InternalError as e:  # a panic: a bug
            pytest.fail(f"{path.name} {data!r}: {e}")
        except facetlab.Error as e:
            assert p.returncode == 2, (path.name, p.stdout)
            line = p.stderr.strip().splitlines()[-1]
            assert line == f"facetlab: {e}", (line, str(e))
            refused += 1
        else:
            assert p.returncode == 0, (path.name, p.stderr)
    assert refused >= 20, refused


def test_wrong_types_are_errors_too() -> None:
    with pytest.raises(facetlab.Error, match="expected a Cut, a preset name or a path"):
        facetlab.score(3.5)  # type: ignore[arg-type]
    with pytest.raises(facetlab.Error, match="not a number"):
        facetlab.family("round-brilliant", table="wide")  # type: ignore[arg-type]


# Issue 51 item 8: whole numbers out of range (negative, past 2**64) are the command line's
# error naming the keyword, never Python's OverflowError.
GRID = {"cut": {"family": "round-brilliant"}, "free": {"table": [0.5, 0.6]},
        "score": {"ri": 1.54, "polarization": False}}


def test_whole_numbers_out_of_range_are_the_command_lines_error(cli: Cli, tmp_path: Path) -> None:
    # Typed: a list of lambdas returning different things is inferred from its first one.
    cases: List[Tuple[str, str, Callable[[], object]]] = [
        ("--photons", "-1", lambda: facetlab.trace("tolkowsky", photons=-1)),
        ("--photons", str(2**64), lambda: facetlab.trace("tolkowsky", photons=2**64)),
        ("--seed", "-1", lambda: facetlab.trace("tolkowsky", photons=10, seed=-1)),
        ("--seed", str(2**64), lambda: facetlab.trace("tolkowsky", photons=10, seed=2**64)),
    ]
    for flag, value, call in cases:
        p = cli(tmp_path, "trace", "tolkowsky", flag, value)
        assert p.returncode == 2, p.stderr
        with pytest.raises(facetlab.Error) as e:
            call()
        line = p.stderr.strip()
        # The same line, the keyword where the command line names its flag.
        assert str(e.value) == line[len("facetlab: "):].replace(flag, flag[2:]), (str(e.value), line)
    calls: List[Tuple[Callable[[], object], str]] = [
        (lambda: facetlab.trace("tolkowsky", depth=-1), "depth"),
        (lambda: facetlab.trace("tolkowsky", depth=2**70), "depth"),
        (lambda: facetlab.Grid(GRID, ["table:0.55:0.57:0.01"]).rows([-1]), "indices"),
        (lambda: facetlab.Grid(GRID, ["table:0.55:0.57:0.01"]).rows([2**64]), "indices"),
        (lambda: facetlab.plan("octahedron", size_mm=6, top=2**64), "top"),
        (lambda: facetlab.plan("octahedron", size_mm=6, top=-1), "top"),
        (lambda: facetlab.optimize(GRID, seed=-1), "seed"),
    ]
    for call, keyword in calls:
        with pytest.raises(facetlab.Error) as e:
            call()
        assert str(e.value).startswith(f"{keyword}: `"), str(e.value)
        assert "\n" not in str(e.value)
    # A number of another type is still Python's TypeError, as for any int argument.
    with pytest.raises(TypeError):
        facetlab.trace("tolkowsky", photons=1.5)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        facetlab.trace("tolkowsky", photons=True)


def test_a_bare_str_is_no_list_of_cuts_and_a_write_names_its_path() -> None:
    with pytest.raises(facetlab.Error, match=r"^cuts: `tolkowsky` is one str, not a list of cuts"):
        facetlab.score_many("tolkowsky")
    with pytest.raises(facetlab.Error, match=r"^path: expected a file name"):
        facetlab.cut("tolkowsky").write(None)  # type: ignore[arg-type]


def test_ctrl_c_stops_a_long_trace() -> None:
    # 10**9 photons take minutes; Ctrl-C (here 0.5 s in) stops them within a chunk per thread.
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    t0 = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            facetlab.trace("tolkowsky", photons=10**9)
    finally:
        timer.cancel()
    # Not a timed test: the run stopped, long before its photons were traced.
    assert time.monotonic() - t0 < 60
