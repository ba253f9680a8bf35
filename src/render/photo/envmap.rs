//! Equirectangular environment maps ([`EnvMap`]): read from a Radiance `.hdr` or OpenEXR
//! `.exr` picture, or made here (the bundled procedural studio, [`EnvMap::studio`]), and
//! looked up through the camera's aperture: the environments' filter of half-width `h` (the
//! `env` module; ±1° as made, [`EnvMap::at_edge`] for another) or, for a pinhole (`h` = 0),
//! the map's own texels.
//!
//! **Layout.** Row 0 is the zenith, the last row the nadir (rows of equal height in
//! elevation); the middle column looks toward +x and columns to its right turn clockwise
//! seen from above (toward −y), as in a panorama taken standing at the stone and turning
//! right: column `c` of `W` faces azimuth `180° − 360° · (c + ½) / W`.
//!
//! **Filter.** The map is first averaged (weighted by solid angle) onto cells of at least
//! `min(h, 1°)` and at least 180° / 1024 (at most 180 rows for `h` ≥ 1°, an even number, so
//! that the horizon is a row boundary), then seen through the kernel of the environments'
//! filter (`env` module): along elevation exactly, as the sum over the rows within ±`h` of
//! the kernel's integral over each row (the ramp's differences); along azimuth over
//! ±`h` / cos(elevation) (a row near the pole is averaged whole), precomputed at each cell's
//! centre and interpolated linearly between them. A map of 1 above the horizon and 0 below
//! is so the ISO light's horizon ramp of ±`h` exactly (at ±1°, the ISO light).
//!
//! **Pinhole.** With `h` = 0 a direction sees the map's texels themselves, bilinearly
//! between their centres (wrapping round in azimuth, the first and last rows held toward the
//! poles): no filter.

use super::sky::{direction, Rgb};
use crate::error::{Error, Result};
use crate::io::hdr::HdrImage;
use crate::render::lighting::{smoothstep, EDGE_DEG};
use glam::DVec3;
use std::f64::consts::PI;
use std::sync::{Arc, Mutex};

/// Most rows of the filtered grid of a kernel of ±1° or wider (1° cells).
pub const MAX_ROWS: usize = 180;

/// Most rows of the filtered grid of any kernel (cells of 180° / 1024 ≈ 0.18°).
pub const MAX_FINE_ROWS: usize = 1024;

/// The map's own pixels (single precision, as the files hold them), rows from the top.
#[derive(Debug)]
struct Texels {
    width: usize,
    height: usize,
    rgb: Vec<[f32; 3]>,
}

/// An equirectangular map, averaged onto the filter's grid and filtered along azimuth, or
/// looked up texel by texel through a pinhole.
#[derive(Clone, Debug)]
pub struct EnvMap {
    /// The kernel's half-width, degrees (0: a pinhole).
    edge_deg: f64,
    /// Rows of the filtered grid (elevation from +90° at row 0 to −90°); 0 for a pinhole.
    rows: usize,
    /// Columns (azimuth, as the module documentation says).
    cols: usize,
    /// Azimuth-filtered values at each cell's centre, row-major (single precision: a
    /// quarter of the cache a lookup's rows take).
    filtered: Vec<[f32; 3]>,
    grey: bool,
    /// The source's pixels (the pinhole's lookup, other kernels' grids).
    texels: Arc<Texels>,
    /// The same map under other kernels, made once each ([`EnvMap::at_edge`]).
    others: Arc<Mutex<Vec<Arc<EnvMap>>>>,
}

/// The filter's kernel's mass at offsets below `x` degrees (its integral: the ramp), for a
/// kernel of half-width `h` > 0.
#[inline]
fn mass(x: f64, h: f64) -> f64 {
    smoothstep((x + h) / (2.0 * h))
}

/// Rows of the grid for a source `height` rows high under a kernel of half-width `h` > 0.
fn grid_rows(height: usize, h: f64) -> usize {
    let most = if h >= EDGE_DEG {
        MAX_ROWS
    } else {
        ((180.0 / h).ceil() as usize).min(MAX_FINE_ROWS)
    };
    let r = height.clamp(2, most.max(2));
    r - r % 2
}

impl EnvMap {
    /// A map from linear RGB rows (`width × height`, rows from the top); errors name
    /// `name`.
    pub fn from_image(img: &HdrImage, name: &str) -> Result<EnvMap> {
        let (w, h) = (img.width, img.height);
        if w < 2 || h < 2 || img.rgb.len() != w * h {
            return Err(Error::invalid(
                name,
                format!("a {w} × {h} picture is too small for an environment map (at least 2 × 2)"),
            ));
        }
        let rgb: Vec<Rgb> = img
            .rgb
            .iter()
            .map(|p| [p[0] as f64, p[1] as f64, p[2] as f64])
            .collect();
        Ok(EnvMap::from_rgb(w, h, &rgb))
    }

    /// A map from `width × height` linear RGB values, rows from the top, seen through the
    /// ±1° kernel ([`EnvMap::at_edge`] for another).
    pub fn from_rgb(width: usize, height: usize, rgb: &[Rgb]) -> EnvMap {
        let texels = Arc::new(Texels {
            width,
            height,
            rgb: rgb
                .iter()
                .map(|p| [p[0] as f32, p[1] as f32, p[2] as f32])
                .collect(),
        });
        EnvMap::build(width, height, rgb, EDGE_DEG, texels)
    }

    /// The map of `rgb` (the source, `texels` its copy) under a kernel of half-width `h`.
    fn build(width: usize, height: usize, rgb: &[Rgb], h: f64, texels: Arc<Texels>) -> EnvMap {
        let mut map = EnvMap {
            edge_deg: h,
            rows: 0,
            cols: 0,
            filtered: Vec::new(),
            grey: rgb.iter().all(|c| c[0] == c[1] && c[1] == c[2]),
            texels,
            others: Arc::new(Mutex::new(Vec::new())),
        };
        if map.pinhole() {
            return map;
        }
        let rows = grid_rows(height, h);
        let cols = (2 * rows).min(width.max(2)).max(2);
        // Row weights: the solid angle of each source row (cos of its centre's elevation).
        let src_row = |i: usize| {
            let e = PI / 2.0 - PI * (i as f64 + 0.5) / height as f64;
            e.cos().max(1e-9)
        };
        // Box resampling: each grid cell averages the source pixels it overlaps, by overlap.
        let overlaps = |n_src: usize, n_dst: usize, k: usize| -> Vec<(usize, f64)> {
            let (a, b) = (
                k as f64 * n_src as f64 / n_dst as f64,
                (k + 1) as f64 * n_src as f64 / n_dst as f64,
            );
            let mut v = Vec::new();
            let mut i = a.floor() as usize;
            while (i as f64) < b && i < n_src {
                let lo = (i as f64).max(a);
                let hi = ((i + 1) as f64).min(b);
                if hi > lo {
                    v.push((i, hi - lo));
                }
                i += 1;
            }
            v
        };
        let row_src: Vec<Vec<(usize, f64)>> = (0..rows)
            .map(|r| {
                overlaps(height, rows, r)
                    .into_iter()
                    .map(|(i, f)| (i, f * src_row(i)))
                    .collect()
            })
            .collect();
        let col_src: Vec<Vec<(usize, f64)>> = (0..cols).map(|c| overlaps(width, cols, c)).collect();
        let mut cells = vec![[0.0; 3]; rows * cols];
        for r in 0..rows {
            for c in 0..cols {
                let (mut s, mut wsum) = ([0.0; 3], 0.0);
                for &(i, wi) in &row_src[r] {
                    for &(j, wj) in &col_src[c] {
                        let p = rgb[i * width + j];
                        let k = wi * wj;
                        for q in 0..3 {
                            s[q] += p[q] * k;
                        }
                        wsum += k;
                    }
                }
                cells[r * cols + c] = s.map(|v| if wsum > 0.0 { v / wsum } else { 0.0 });
            }
        }
        // Where every value of the source is the same, the cells are exactly it (the sums
        // above round).
        for r in 0..rows {
            for c in 0..cols {
                let same = row_src[r].iter().all(|&(i, _)| {
                    col_src[c].iter().all(|&(j, _)| {
                        rgb[i * width + j] == rgb[row_src[r][0].0 * width + col_src[c][0].0]
                    })
                });
                if same {
                    cells[r * cols + c] = rgb[row_src[r][0].0 * width + col_src[c][0].0];
                }
            }
        }
        map.grey = cells.iter().all(|c| c[0] == c[1] && c[1] == c[2]);
        map.rows = rows;
        map.cols = cols;
        map.filtered = map
            .filter_azimuth(&cells)
            .into_iter()
            .map(|c| c.map(|v| v as f32))
            .collect();
        map
    }

    /// The same map seen through a kernel of half-width `edge_deg` (0: a pinhole), made from
    /// the map's texels once and kept.
    pub fn at_edge(self: &Arc<Self>, edge_deg: f64) -> Arc<EnvMap> {
        if edge_deg == self.edge_deg {
            return self.clone();
        }
        let mut others = self.others.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(m) = others.iter().find(|m| m.edge_deg == edge_deg) {
            return m.clone();
        }
        let t = &self.texels;
        let rgb: Vec<Rgb> = t.rgb.iter().map(|p| p.map(f64::from)).collect();
        let mut m = EnvMap::build(t.width, t.height, &rgb, edge_deg, t.clone());
        m.others = self.others.clone();
        let m = Arc::new(m);
        others.push(m.clone());
        m
    }

    /// The kernel's half-width, degrees (0: a pinhole).
    pub fn edge_deg(&self) -> f64 {
        self.edge_deg
    }

    /// Whether directions see the texels themselves (a pinhole).
    pub fn pinhole(&self) -> bool {
        self.edge_deg == 0.0
    }

    /// Rows and columns of the filtered grid ((0, 0) for a pinhole).
    pub fn grid(&self) -> (usize, usize) {
        (self.rows, self.cols)
    }

    /// Whether every value is grey.
    pub fn is_grey(&self) -> bool {
        self.grey
    }

    /// Elevation of row `r`'s upper edge, degrees.
    #[inline]
    fn row_top(&self, r: usize) -> f64 {
        90.0 - 180.0 * r as f64 / self.rows as f64
    }

    /// Each cell's row of `cells` filtered along azimuth at its centre.
    fn filter_azimuth(&self, cells: &[Rgb]) -> Vec<Rgb> {
        let (rows, cols) = (self.rows, self.cols);
        let step = 360.0 / cols as f64;
        let mut out = vec![[0.0; 3]; rows * cols];
        for r in 0..rows {
            let e = self.row_top(r) - 90.0 / rows as f64;
            let width = (self.edge_deg / e.to_radians().cos().max(1e-9)).min(180.0);
            let row = &cells[r * cols..(r + 1) * cols];
            // The same value in every column: nothing to filter (and exact).
            if row.iter().all(|c| *c == row[0]) {
                out[r * cols..(r + 1) * cols].fill(row[0]);
                continue;
            }
            // Kernel of half-width `width` degrees: a cell [a, b] (offsets from the centre)
            // weighs ramp(b) − ramp(a), with ramp the kernel's integral.
            let ramp = |x: f64| smoothstep((x + width) / (2.0 * width));
            let reach = (width / step).ceil() as i64 + 1;
            for c in 0..cols {
                let mut s = [0.0; 3];
                for k in -reach..=reach {
                    let (a, b) = ((k as f64 - 0.5) * step, (k as f64 + 0.5) * step);
                    let wgt = ramp(b) - ramp(a);
                    if wgt == 0.0 {
                        continue;
                    }
                    let j = (c as i64 + k).rem_euclid(cols as i64) as usize;
                    for q in 0..3 {
                        s[q] += wgt * row[j][q];
                    }
                }
                out[r * cols + c] = s;
            }
        }
        out
    }

    /// Row `r`'s azimuth-filtered value at fractional column `x` (in cells from column 0's
    /// centre), linearly between the cells' centres (wrapping round).
    #[inline]
    fn row_at(&self, r: usize, x: f64) -> Rgb {
        let cols = self.cols as i64;
        let i0 = x.floor();
        let f = x - i0;
        let i0 = (i0 as i64).rem_euclid(cols) as usize;
        let i1 = (i0 + 1) % self.cols;
        let (a, b) = (
            self.filtered[r * self.cols + i0],
            self.filtered[r * self.cols + i1],
        );
        let (same, a, b) = (a == b, a.map(f64::from), b.map(f64::from));
        if f == 0.0 || same {
            return a;
        }
        [0, 1, 2].map(|q| a[q] + (b[q] - a[q]) * f)
    }

    /// The map's texels at direction `w` (unit, the map's frame), bilinearly between their
    /// centres: the pinhole's lookup.
    #[inline]
    fn texel_radiance(&self, w: DVec3) -> Rgb {
        let t = &*self.texels;
        let e = w.z.clamp(-1.0, 1.0).asin().to_degrees();
        let az = w.y.atan2(w.x).to_degrees();
        // Texel (i, j)'s centre: elevation 90° − 180° (i + ½) / H, azimuth
        // 180° − 360° (j + ½) / W.
        let y = ((90.0 - e) * t.height as f64 / 180.0 - 0.5).clamp(0.0, (t.height - 1) as f64);
        let x = (180.0 - az) * t.width as f64 / 360.0 - 0.5;
        let (i0, fy) = (y.floor(), y - y.floor());
        let i0 = i0 as usize;
        let i1 = (i0 + 1).min(t.height - 1);
        let (j0, fx) = (x.floor(), x - x.floor());
        let j0 = (j0 as i64).rem_euclid(t.width as i64) as usize;
        let j1 = (j0 + 1) % t.width;
        let at = |i: usize, j: usize| t.rgb[i * t.width + j].map(f64::from);
        let (a, b, c, d) = (at(i0, j0), at(i0, j1), at(i1, j0), at(i1, j1));
        [0, 1, 2].map(|q| {
            let top = a[q] + (b[q] - a[q]) * fx;
            let bottom = c[q] + (d[q] - c[q]) * fx;
            top + (bottom - top) * fy
        })
    }

    /// Radiance from direction `w` (unit, the map's frame) through the map's kernel (the
    /// texels themselves through a pinhole).
    pub fn radiance(&self, w: DVec3) -> Rgb {
        if self.rows == 0 {
            return self.texel_radiance(w);
        }
        let edge = self.edge_deg;
        let e = w.z.clamp(-1.0, 1.0).asin().to_degrees();
        let az = w.y.atan2(w.x).to_degrees();
        // Column coordinate from azimuth: c + ½ = (180° − az) W / 360°.
        let x = (180.0 - az) * self.cols as f64 / 360.0 - 0.5;
        // The rows the kernel reaches, [e − edge, e + edge]; row r spans
        // [top(r + 1), top(r)], the first reaching up past the zenith and the last down past
        // the nadir. Each weighs the kernel's mass inside it, mass(top − e) − mass(bottom − e),
        // a row's bottom being the next one's top.
        let h = 180.0 / self.rows as f64;
        let last = self.rows as i64 - 1;
        let r0 = (((90.0 - e - edge) / h).floor() as i64).clamp(0, last);
        let r1 = (((90.0 - e + edge) / h).floor() as i64).clamp(0, last);
        let mut out = [0.0; 3];
        let mut top = if r0 == 0 {
            1.0
        } else {
            mass(self.row_top(r0 as usize) - e, edge)
        };
        for r in r0..=r1 {
            let bottom = if r == last {
                0.0
            } else {
                mass(self.row_top(r as usize + 1) - e, edge)
            };
            let wgt = top - bottom;
            top = bottom;
            if wgt <= 0.0 {
                continue;
            }
            let v = self.row_at(r as usize, x);
            for q in 0..3 {
                out[q] += wgt * v[q];
            }
        }
        out
    }

    /// The bundled procedural studio (no photograph: drawn here from a few shapes, for tests,
    /// the gallery and comparisons), `width × width/2` linear RGB: a dim grey room with a
    /// lighter floor, a large soft box overhead, two tall strip lights left and right and a
    /// warm key light at 35° elevation.
    pub fn studio_rgb(width: usize) -> (usize, usize, Vec<Rgb>) {
        let (w, h) = (width.max(8), (width / 2).max(4));
        let mut v = vec![[0.0; 3]; w * h];
        for r in 0..h {
            let e = 90.0 - 180.0 * (r as f64 + 0.5) / h as f64;
            for c in 0..w {
                let az = 180.0 - 360.0 * (c as f64 + 0.5) / w as f64;
                let mut p = if e >= 0.0 {
                    // Walls and ceiling: a little lighter toward the top.
                    let g = 0.06 + 0.08 * (e / 90.0);
                    [g, g, g * 1.05]
                } else {
                    // A pale floor.
                    [0.22, 0.21, 0.2]
                };
                // Soft box overhead: elevation above 62°, centred slightly off the zenith.
                let d = direction(e, az);
                let top = direction(80.0, 200.0);
                if d.dot(top) > 18f64.to_radians().cos() {
                    p = [3.0, 3.0, 3.0];
                }
                // Strip lights: 10° wide, from 5° to 55° elevation, at azimuths ±100°.
                for centre in [100.0, -100.0f64] {
                    let da = ((az - centre + 540.0) % 360.0 - 180.0).abs();
                    if da < 5.0 && (5.0..55.0).contains(&e) {
                        p = [2.2, 2.3, 2.5];
                    }
                }
                // Warm key light: a 6° disc at 35° elevation, azimuth 30°.
                let key = direction(35.0, 30.0);
                if d.dot(key) > 6f64.to_radians().cos() {
                    p = [12.0, 10.0, 7.5];
                }
                v[r * w + c] = p;
            }
        }
        (w, h, v)
    }

    /// [`EnvMap::studio_rgb`] as a map (512 × 256).
    pub fn studio() -> EnvMap {
        let (w, h, v) = EnvMap::studio_rgb(512);
        EnvMap::from_rgb(w, h, &v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::lighting::Lighting;

    /// A map of 1 above the horizon and 0 below is the ISO light to rounding, at any
    /// resolution whose rows put the horizon on a row boundary (and averaged down from a
    /// finer one).
    #[test]
    fn a_horizon_map_is_the_iso_light() {
        let l = Lighting::new(0.0, &[]);
        for (w, h) in [(64, 32), (128, 64), (2048, 1024), (720, 360)] {
            let rgb: Vec<Rgb> = (0..w * h)
                .map(|k| if k / w < h / 2 { [1.0; 3] } else { [0.0; 3] })
                .collect();
            let m = EnvMap::from_rgb(w, h, &rgb);
            for k in 0..=3600 {
                let d = direction(-90.0 + 0.05 * k as f64, 1.3 * k as f64);
                let got = m.radiance(d);
                assert!((got[0] - l.iso(d)).abs() < 1e-12, "{w}×{h} {k}: {got:?}");
            }
        }
    }

    /// Filtering keeps a map's power: the filtered map integrated over the sphere is the map
    /// averaged (to the quadrature's error); a bright small spot spreads but keeps its power.
    #[test]
    fn filtering_keeps_power() {
        let (w, h, rgb) = EnvMap::studio_rgb(256);
        let m = EnvMap::from_rgb(w, h, &rgb);
        let mut raw = 0.0;
        for r in 0..h {
            let e = PI / 2.0 - PI * (r as f64 + 0.5) / h as f64;
            for c in 0..w {
                raw += rgb[r * w + c][1] * e.cos() * (PI / h as f64) * (2.0 * PI / w as f64);
            }
        }
        let n = 720;
        let mut filtered = 0.0;
        for i in 0..n {
            let z = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
            for j in 0..2 * n {
                let a = 2.0 * PI * (j as f64 + 0.5) / (2 * n) as f64;
                let s = (1.0 - z * z).sqrt();
                let v = m.radiance(DVec3::new(s * a.cos(), s * a.sin(), z));
                filtered += v[1] * 4.0 * PI / (2 * n * n) as f64;
            }
        }
        assert!((filtered - raw).abs() < 0.01 * raw, "{filtered} {raw}");
    }

    /// Through a pinhole a direction sees the texels themselves: at a texel's centre its
    /// value, halfway between two centres their mean, and no light from a texel one away
    /// (no filter); a map of 1 is 1 everywhere.
    #[test]
    fn a_pinhole_sees_the_texels() {
        let (w, h) = (36, 18);
        let rgb: Vec<Rgb> = (0..w * h)
            .map(|k| [(k % 7) as f64, (k % 5) as f64, 0.25 * (k % 3) as f64])
            .collect();
        let m = Arc::new(EnvMap::from_rgb(w, h, &rgb)).at_edge(0.0);
        assert!(m.pinhole() && m.grid() == (0, 0));
        let centre = |i: usize, j: f64| {
            direction(
                90.0 - 180.0 * (i as f64 + 0.5) / h as f64,
                180.0 - 360.0 * (j + 0.5) / w as f64,
            )
        };
        for i in 0..h {
            for j in 0..w {
                let got = m.radiance(centre(i, j as f64));
                for q in 0..3 {
                    assert!((got[q] - rgb[i * w + j][q]).abs() < 1e-9, "{i} {j}");
                }
                let mid = m.radiance(centre(i, j as f64 + 0.5))[0];
                let want = 0.5 * (rgb[i * w + j][0] + rgb[i * w + (j + 1) % w][0]);
                assert!((mid - want).abs() < 1e-9, "{i} {j}: {mid} {want}");
            }
        }
        let ones = Arc::new(EnvMap::from_rgb(w, h, &vec![[1.0; 3]; w * h])).at_edge(0.0);
        for k in 0..=3600 {
            let d = direction(-90.0 + 0.05 * k as f64, 1.3 * k as f64);
            assert_eq!(ones.radiance(d), [1.0; 3]);
        }
    }

    /// A finite kernel narrower than ±1° keeps the map's power too (cells of its
    /// half-width), and a map of 1 above the horizon and 0 below is its horizon ramp.
    #[test]
    fn a_narrow_kernel_keeps_power_and_the_horizon() {
        let (w, h, rgb) = EnvMap::studio_rgb(512);
        let m = Arc::new(EnvMap::from_rgb(w, h, &rgb)).at_edge(0.4);
        assert_eq!(m.grid(), (256, 512));
        let mut raw = 0.0;
        for r in 0..h {
            let e = PI / 2.0 - PI * (r as f64 + 0.5) / h as f64;
            for c in 0..w {
                raw += rgb[r * w + c][1] * e.cos() * (PI / h as f64) * (2.0 * PI / w as f64);
            }
        }
        let n = 720;
        let mut filtered = 0.0;
        for i in 0..n {
            let z = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
            for j in 0..2 * n {
                let a = 2.0 * PI * (j as f64 + 0.5) / (2 * n) as f64;
                let s = (1.0 - z * z).sqrt();
                filtered += m.radiance(DVec3::new(s * a.cos(), s * a.sin(), z))[1] * 4.0 * PI
                    / (2 * n * n) as f64;
            }
        }
        assert!((filtered - raw).abs() < 0.01 * raw, "{filtered} {raw}");
        let (w, h) = (720, 360);
        let rgb: Vec<Rgb> = (0..w * h)
            .map(|k| if k / w < h / 2 { [1.0; 3] } else { [0.0; 3] })
            .collect();
        let m = Arc::new(EnvMap::from_rgb(w, h, &rgb)).at_edge(0.4);
        for k in 0..=2000 {
            let e = -1.0 + 0.001 * k as f64;
            let want = smoothstep((e + 0.4) / 0.8);
            let got = m.radiance(direction(e, 0.37 * k as f64))[0];
            assert!((got - want).abs() < 1e-6, "{e}: {got} {want}");
        }
    }

    /// The layout: the middle column faces +x, a quarter of the way in faces +y.
    #[test]
    fn columns_face_their_azimuths() {
        let (w, h) = (72, 36);
        let mut rgb = vec![[0.0; 3]; w * h];
        // A bright column block around azimuth 90° (+y), at the horizon rows.
        for r in 0..h {
            for c in 0..w {
                let az = 180.0 - 360.0 * (c as f64 + 0.5) / w as f64;
                if (az - 90.0).abs() < 10.0 {
                    rgb[r * w + c] = [1.0; 3];
                }
            }
        }
        let m = EnvMap::from_rgb(w, h, &rgb);
        assert!(m.radiance(direction(10.0, 90.0))[0] > 0.99);
        assert!(m.radiance(direction(10.0, -90.0))[0] < 1e-12);
        assert!(m.radiance(direction(10.0, 0.0))[0] < 1e-12);
    }
}
