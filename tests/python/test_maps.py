"""Environment maps whose header states a huge size (issue 51): the package raises
facetlab.Error with the command line's line, before any pixel is allocated, where it used to
abort the interpreter (SIGABRT, "memory allocation of 120000000000 bytes failed")."""

from __future__ import annotations

from pathlib import Path

import facetlab
import pytest

from conftest import Cli


@pytest.mark.parametrize(
    "side, data",
    [(100_000, b""), (2_147_483_647, b""), (8_192, b"\x03" * 100), (4_096, b"\x03" * 1000)],
)
def test_a_map_stating_a_huge_size_is_an_error_not_an_abort(
    cli: Cli, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, side: int, data: bytes
) -> None:
    monkeypatch.chdir(tmp_path)  # both name the file as given
    head = f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {side} +X {side + (side == 8_192)}\n"
    (tmp_path / "big.hdr").write_bytes(head.encode() + data)
    with pytest.raises(facetlab.Error) as e:
        facetlab.render("tolkowsky", light="env:big.hdr", size=16)
    assert str(e.value).startswith("big.hdr: ")
    assert "pixels" in str(e.value)
    p = cli(tmp_path, "render", "tolkowsky", "--light", "env:big.hdr", "--size", "16", "-o", "x.png")
    assert p.returncode == 2
    assert p.stderr.strip().splitlines() == [f"facetlab: {e.value}"]
