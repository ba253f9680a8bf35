"""facetlab.render against ``facetlab render --bare --json``: the sRGB bytes are the PNG's,
the statistics the document's, and the linear picture's mean the statistics' mean."""

from __future__ import annotations

import json
from pathlib import Path

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
