//! Early rejection for undirected lights: most of their photons miss the stone (~99 % for the
//! thesis's overhead light), and this finds most of those from the photon's start and polar
//! angle alone, before any trigonometry or facet test.
//!
//! The light square is divided into cells. For a cell with centre `o_c`, a photon leaving any
//! point of it (within δ, the cell's half-diagonal) that hits the stone's bounding sphere
//! (radius r, centre C) travels on a line that passes within `R = r + δ` of C as seen from
//! `o_c`, forward (the backward case needs `|C − o_c|` within about 2δ of R, and such cells are
//! never rejected). Its direction then lies within `α = asin(R / |C − o_c|)` of `C − o_c`, so
//! its polar angle θ from the light's axis is within α of that of `C − o_c`: `cos θ` lies in
//! an interval that is stored per cell (widened by 1e-9). A photon whose `cos θ` lies outside
//! it misses the stone whatever its azimuth.

use crate::geometry::DVec3;

/// Cells per side.
const CELLS: usize = 64;

/// Per-cell intervals of `cos θ` that can reach the stone.
pub(crate) struct Reach {
    half: f64,
    /// Cells per unit of `a` and `b`: `CELLS / (2 half)`.
    scale: f64,
    /// (lowest, highest) reachable `cos θ` of each cell, row-major in (a, b).
    bounds: Vec<(f64, f64)>,
}

impl Reach {
    /// The intervals for a square light of half-side `half`, whose centre sees the bounding
    /// sphere's centre at `to_sphere` (components along the light's axis, u and v), radius `r`.
    pub(crate) fn new(half: f64, to_sphere: DVec3, r: f64) -> Reach {
        let step = 2.0 * half / CELLS as f64;
        let delta = 0.5 * step * std::f64::consts::SQRT_2 * (1.0 + 1e-9);
        let big = r + delta;
        let mut bounds = Vec::with_capacity(CELLS * CELLS);
        for i in 0..CELLS {
            for j in 0..CELLS {
                let a = -half + (i as f64 + 0.5) * step;
                let b = -half + (j as f64 + 0.5) * step;
                let (wa, wu, wv) = (to_sphere.x, to_sphere.y - a, to_sphere.z - b);
                let q = (wu * wu + wv * wv).sqrt();
                let l = (wa * wa + q * q).sqrt();
                let k2 = l * l - big * big;
                if !(k2 > 4.0 * delta * delta * (1.0 + 1e-6) && l > big) {
                    bounds.push((f64::NEG_INFINITY, f64::INFINITY));
                    continue;
                }
                let theta = q.atan2(wa);
                let alpha = (big / l).asin();
                let lo = (theta + alpha).min(std::f64::consts::PI).cos() - 1e-9;
                let hi = if theta - alpha <= 0.0 {
                    f64::INFINITY
                } else {
                    (theta - alpha).cos() + 1e-9
                };
                bounds.push((lo, hi));
            }
        }
        Reach {
            half,
            scale: CELLS as f64 / (2.0 * half),
            bounds,
        }
    }

    /// Whether the photon leaving at `(a, b)` (in the square) with polar-angle cosine `c`
    /// surely misses the stone.
    #[inline(always)]
    pub(crate) fn misses(&self, a: f64, b: f64, c: f64) -> bool {
        let cell = |x: f64| super::entry_grid::grid_cell((x + self.half) * self.scale, CELLS);
        let (i, j) = (cell(a), cell(b));
        let (lo, hi) = self.bounds[i * CELLS + j];
        c < lo || c > hi
    }
}
