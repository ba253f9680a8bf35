"""facetlab.render against ``facetlab render --bare --json``: the sRGB bytes are the PNG's,
the statistics the document's, and the linear picture's mean the statistics' mean."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any, Dict, List

import facetlab
import numpy as np
import pytest

from conftest import Cli, assert_close, decode_png

SIZE = 64


@pytest.mark.parametrize("light", ["iso", "cos", "aset", "fire"])
def test_srgb_is_the_pngs_pixels_and_stats_the_document(
    cli: Cli, tmp_path: Path, light: str
) -> None:
    p = cli(
        tmp_path, "render", "tolkowsky", "--light", light, "--size", str(SIZE), "--bare",
        "--quiet", "-o", "a.png", "--json", "a.json",
    )
    assert p.returncode == 0, p.stderr
    want = json.loads((tmp_path / "a.json").read_text())
    r = facetlab.render("tolkowsky", light=light, size=SIZE)
    w, h, png = decode_png(tmp_path / "a.png")
    assert (w, h) == (SIZE, SIZE)
    assert r.srgb.dtype == np.uint8 and r.srgb.shape == (SIZE, SIZE, 3)
    assert np.array_equal(r.srgb, png)
    got = r.stats
    for k in ("elapsed_s", "output"):
        got.pop(k)
        want.pop(k)
    assert_close(got, want)


@pytest.mark.parametrize("light", ["iso", "cos"])
def test_the_linear_pictures_mean_is_the_statistics_mean(light: str) -> None:
    r = facetlab.render("tolkowsky", light=light, size=SIZE)
    assert r.linear.dtype == np.float32 and r.linear.shape == (SIZE, SIZE, 3)
    mean = r.stats["mean"]
    # The statistic is tallied from the exit beams; the picture is their footprints summed
    # into pixels (exact area coverage), so the two agree to the rounding of those sums:
    # 1.4e-11 relative measured at 64 px in float64, float32's 1e-7 in the default array.
    r64 = facetlab.render("tolkowsky", light=light, size=SIZE, float64=True)
    m64 = r64.linear[..., 0].sum() / r64.coverage.sum()
    assert abs(m64 - mean) <= 1e-10 * mean, (m64, mean)
    m32 = r.linear[..., 0].astype(np.float64).sum() / r.coverage.sum()
    assert abs(m32 - mean) <= 1e-6 * mean, (m32, mean)
    # Grey lights: the three channels are one value; outside the outline there is no light.
    assert np.array_equal(r.linear[..., 0], r.linear[..., 2])
    assert float(r.linear[r.coverage == 0].max()) == 0.0


def test_a_png_written_by_the_package_decodes_to_its_srgb(tmp_path: Path) -> None:
    r = facetlab.render("gia-reference", light="aset", size=32, tilt="10@45")
    r.write_png(tmp_path / "b.png")
    assert np.array_equal(decode_png(tmp_path / "b.png")[2], r.srgb)
    assert r.stats["tilt_deg"] == 10.0 and r.stats["azimuth_deg"] == 45.0
    with pytest.raises(facetlab.Error, match="^light: `sunset` is not allowed"):
        facetlab.render("tolkowsky", light="sunset")
    with pytest.raises(facetlab.Error, match="^size: "):
        facetlab.render("tolkowsky", size=4)


# Photographs: the same settings through the keyword arguments and through the flags. Each
# keyword is its flag with underscores; True/False are on/off.
PHOTOS = [
    ("tent", {"view": "60@20", "ground": "white", "ground_gap": 0.25}),
    ("darkfield", {"tilt": "10@45", "tone": "clip", "exposure": 2.0, "light_rotation": 30.0}),
    ("studio", {"view": 90, "distance": 60.0, "bands": 3, "material": "ruby"}),
    ("env", {"view": 45, "ground": "black", "polarization": False}),
    ("studio", {"view": 90, "aperture": 0}),
    ("ring", {"view": "50@10", "distance": 80.0, "aperture": 2.5}),
]


def flags(kwargs: Dict[str, Any]) -> List[str]:
    out: List[str] = []
    for k, v in kwargs.items():
        text = ("on" if v else "off") if isinstance(v, bool) else str(v)
        out += ["--" + k.replace("_", "-"), text]
    return out


def write_env_map(path: Path) -> None:
    """A small equirectangular Radiance map written here byte by byte (flat RGBE scanlines):
    a bright warm sky over a dim floor, with one hot patch of light."""
    w, h = 16, 8
    rows = []
    for j in range(h):
        for i in range(w):
            if j == 1 and i in (3, 4):
                px = (250, 240, 200, 132)  # 16× brighter than the sky
            elif j < h // 2:
                px = (200, 190, 170, 129)
            else:
                px = (40, 36, 30, 129)
            rows.append(bytes(px))
    head = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w)
    path.write_bytes(head + b"".join(rows))


def decode_hdr(path: Path) -> np.ndarray:
    """A Radiance file's linear RGB (H×W×3), decoded here independently of facetlab: its
    scanlines flat RGBE, or run-length encoded channel by channel."""
    data = path.read_bytes()
    _, _, rest = data.partition(b"\n\n")
    size, _, body = rest.partition(b"\n")
    _, hs, _, ws = size.split()
    h, w = int(hs), int(ws)
    out = np.zeros((h, w, 4), dtype=np.uint8)
    pos = 0
    for j in range(h):
        if body[pos] == 2 and body[pos + 1] == 2 and (body[pos + 2] << 8 | body[pos + 3]) == w:
            pos += 4
            for c in range(4):
                i = 0
                while i < w:
                    n = body[pos]
                    if n > 128:
                        out[j, i : i + n - 128, c] = body[pos + 1]
                        i, pos = i + n - 128, pos + 2
                    else:
                        out[j, i : i + n, c] = np.frombuffer(body[pos + 1 : pos + 1 + n], np.uint8)
                        i, pos = i + n, pos + 1 + n
        else:
            out[j] = np.frombuffer(body[pos : pos + 4 * w], np.uint8).reshape(w, 4)
            pos += 4 * w
    assert pos == len(body)
    rgbe = out.astype(np.float64)
    scale = np.where(out[..., 3] > 0, np.ldexp(1.0, out[..., 3].astype(int) - 136), 0.0)
    return rgbe[..., :3] * scale[..., None]


@pytest.mark.parametrize("light, kwargs", PHOTOS, ids=[p[0] for p in PHOTOS])
def test_a_photograph_is_the_command_lines(
    cli: Cli, tmp_path: Path, light: str, kwargs: Dict[str, Any]
) -> None:
    if light == "env":
        write_env_map(tmp_path / "sky.hdr")
        light = f"env:{tmp_path / 'sky.hdr'}"
    size = 40
    p = cli(
        tmp_path, "render", "tolkowsky", "--light", light, "--size", str(size), "--bare",
        "--quiet", "-o", "a.png", "--json", "a.json", "--hdr-out", "a.hdr", *flags(kwargs),
    )
    assert p.returncode == 0, p.stderr
    want = json.loads((tmp_path / "a.json").read_text())
    r = facetlab.render("tolkowsky", light=light, size=size, **kwargs)
    # The PNG's bytes: the photograph through its exposure and tone curve.
    assert r.srgb.shape == (size, size, 3)
    assert np.array_equal(r.srgb, decode_png(tmp_path / "a.png")[2])
    # The linear picture: --hdr-out's, to the 8-bit mantissa of its RGBE pixels.
    hdr = decode_hdr(tmp_path / "a.hdr")
    lin = np.maximum(r.linear.astype(np.float64), 0.0)
    assert r.linear.shape == hdr.shape
    assert np.all(np.abs(lin - hdr) <= 2.0**-7 * lin.max(axis=2, keepdims=True) + 1e-30)
    assert float(lin.max()) > 0.0
    # The statistics: the document's, key for key.
    got = r.stats
    assert got["output"] == "" and "hdr_output" not in got
    for d in (got, want):
        d.pop("elapsed_s")
        d.pop("output")
    want.pop("hdr_output")
    assert_close(got, want)
    assert 0.0 < r.coverage.sum() < size * size
    assert repr(r).startswith(f"<Render {got['light']} {size}×{size}, mean ")


def keywords_of(message: str) -> str:
    """A command-line error line with each flag it names written as its keyword argument."""
    return re.sub(r"--([a-z][a-z-]*)", lambda m: m.group(1).replace("-", "_"), message)


# Bad values, each through a keyword and through its flag (a photographic light unless said).
BAD: List[Dict[str, Any]] = [
    {"light": "sunset"},
    {"light": "iso", "view": 30},
    {"light": "iso", "bands": 8},
    {"view": 95},
    {"view": -10, "ground": "white"},
    {"ground": "grass"},
    {"ground_gap": 11},
    {"ground_gap": 0.5},
    {"light_rotation": 400},
    {"tone": "sepia"},
    {"bands": 2},
    {"distance": 10},
    {"aperture": -1},
    {"aperture": float("nan")},
    {"aperture": 500},
    {"distance": 100, "aperture": 50},
    {"light": "iso", "aperture": 0},
    {"exposure": 0.001},
    {"size": 4},
    {"head_shadow": 5},
    {"light": "iso", "head_shadow": 61},
    {"tilt": "95@10"},
]


@pytest.mark.parametrize("kwargs", BAD, ids=lambda k: "-".join(f"{a}={b}" for a, b in k.items()))
def test_a_bad_value_is_the_command_lines_error_naming_the_keyword(
    cli: Cli, tmp_path: Path, kwargs: Dict[str, Any]
) -> None:
    kwargs = {"light": "tent", "size": 16, **kwargs}
    p = cli(tmp_path, "render", "tolkowsky", "-o", "a.png", *flags(kwargs))
    assert p.returncode == 2, p.stderr
    line = p.stderr.strip()
    assert line.startswith("facetlab: ") and "\n" not in line, line
    want = keywords_of(line[len("facetlab: "):])
    with pytest.raises(ValueError) as e:
        facetlab.render("tolkowsky", **kwargs)
    assert isinstance(e.value, facetlab.Error)
    assert str(e.value) == want
    # It names the keyword given, and says what is allowed.
    named = [k for k in kwargs if str(e.value).startswith(k + ":")]
    assert named, str(e.value)
    assert not (tmp_path / "a.png").exists()


def test_an_environment_map_that_is_missing_is_named() -> None:
    with pytest.raises(facetlab.Error, match=r"nowhere\.hdr"):
        facetlab.render("tolkowsky", light="env:/nowhere.hdr", size=16)
