"""Shared fixtures of the Python package's tests.

The package is checked against the command line built from the same library: FOR TESTS ONLY
the tests run the ``facetlab`` binary (``$FACETLAB_BIN``, else ``target/debug/facetlab``,
built with ``cargo build`` when missing) and compare its JSON and PNG files with what the
package returns. The package itself never calls the binary.
"""

from __future__ import annotations

import json
import os
import subprocess
import zlib
from pathlib import Path
from typing import Any, Callable, List, Tuple

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


# A cheap sweep config: a fixed index (no spectral bands) without polarization.
TINY = """
name = "tiny"
[cut]
family = "round-brilliant"
[cut.params]
table = 0.57
crown_angle = 34.0
pavilion_angle = 41.0
[free]
crown_angle = [30.0, 38.0]
[score]
ri = 1.54
polarization = false
"""


def binary() -> Path:
    env = os.environ.get("FACETLAB_BIN")
    if env:
        return Path(env)
    path = ROOT / "target" / "debug" / "facetlab"
    if not path.exists():
        subprocess.run(["cargo", "build", "-q"], cwd=ROOT, check=True)
    return path


Cli = Callable[..., "subprocess.CompletedProcess[str]"]


@pytest.fixture(scope="session")
def cli() -> Cli:
    """Run the binary in a folder: ``cli(cwd, "score", "tolkowsky")``."""
    exe = binary()

    def run(cwd: Path, *args: str) -> "subprocess.CompletedProcess[str]":
        return subprocess.run(
            [str(exe), *args], cwd=cwd, capture_output=True, text=True, check=False
        )

    return run


def cli_json(cli: Cli, cwd: Path, *args: str) -> Any:
    """The JSON file the command writes with ``--json out.json``."""
    out = cwd / "out.json"
    p = cli(cwd, *args, "--json", str(out), "--force")
    assert p.returncode == 0, p.stderr
    return json.loads(out.read_text())


def assert_close(a: Any, b: Any, tol: float = 1e-12, path: str = "") -> None:
    """Equal documents, numbers within ``tol`` (absolute and relative)."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and sorted(a) == sorted(b), f"{path}: {sorted(a)} != {sorted(b)}"
        for k in a:
            assert_close(a[k], b[k], tol, f"{path}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), f"{path}: lengths differ"
        for i, (x, y) in enumerate(zip(a, b)):
            assert_close(x, y, tol, f"{path}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        assert abs(a - b) <= tol * max(1.0, abs(a), abs(b)), f"{path}: {a} != {b}"
    else:
        assert a == b, f"{path}: {a!r} != {b!r}"


def decode_png(path: Path) -> Tuple[int, int, np.ndarray]:
    """An 8-bit RGB PNG's pixels (H×W×3), decoded here independently of facetlab."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat = 8, b""
    width = height = 0
    while pos < len(data):
        n = int.from_bytes(data[pos : pos + 4], "big")
        kind = data[pos + 4 : pos + 8]
        body = data[pos + 8 : pos + 8 + n]
        if kind == b"IHDR":
            width = int.from_bytes(body[0:4], "big")
            height = int.from_bytes(body[4:8], "big")
            assert body[8] == 8 and body[9] == 2, "8-bit RGB"
        elif kind == b"IDAT":
            idat += body
        elif kind == b"fcTL" and idat:
            break  # an animation's later frames
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = width * 3
    rows: List[bytearray] = []
    prev = bytearray(stride)
    for j in range(height):
        f = raw[j * (stride + 1)]
        line = bytearray(raw[j * (stride + 1) + 1 : (j + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - 3] if i >= 3 else 0
            b = prev[i]
            c = prev[i - 3] if i >= 3 else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append(line)
        prev = line
    arr = np.frombuffer(b"".join(rows), dtype=np.uint8).reshape(height, width, 3)
    return width, height, arr
