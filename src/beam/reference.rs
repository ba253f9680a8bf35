//! An exact reference for the beam tracer, independent of its code: jittered grids of parallel
//! rays straight down over the stone's shadow, each ray split deterministically at every
//! interface (the transmitted part leaves with its exact Fresnel share, the reflected part goes
//! on) until almost none of its power is left.
//!
//! It shares nothing with the tracer but the optics (`crate::optics`: Fresnel, Snell, Stokes and
//! Mueller algebra) and the solid's facet planes: ray–solid intersection is a plain scan of the
//! planes. Its only error is the grids' sampling of the footprint tiling's edges; it is
//! estimated from the spread of independent grids (each turned, shifted and jittered by its own
//! seed), and shrinks as the grids get finer. Used by `benches/exact.rs` (millions of rays) and
//! by the tests (a few hundred thousand).

use crate::geometry::Polyhedron;
use crate::optics::{fresnel, reflect, refract, rotate_stokes, s_axis, Stokes};
use glam::{DVec3, DVec4};
use rayon::prelude::*;

/// Settings of [`overhead_light_return`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridOptions {
    /// Cells per grid side over the square of side `2r` around the stone (`r` its largest
    /// radius); each grid shoots `(n + 1)²` rays, one jittered in each cell, to cover any shift.
    pub n: usize,
    /// Independent grids (at least 2, for the error estimate).
    pub grids: usize,
    /// Seed of the first grid; grid `k` uses `seed + k`.
    pub seed: u64,
    /// Track polarization (Stokes vectors and Mueller matrices); off: unpolarized reflectance.
    pub polarization: bool,
    /// Largest number of internal reflections followed; the rest of a ray's power is counted
    /// in [`GridEstimate::lost`].
    pub max_depth: usize,
    /// A ray is dropped when less than this share of its power is left (counted as lost).
    pub min_power: f64,
}

impl Default for GridOptions {
    fn default() -> Self {
        GridOptions {
            n: 1000,
            grids: 4,
            seed: 1000,
            polarization: false,
            max_depth: 100_000,
            min_power: 1e-9,
        }
    }
}

/// A reference figure with its error estimate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridEstimate {
    /// Mean over the grids of the share of the entering power that leaves upward (z > 0).
    pub value: f64,
    /// Standard error of `value`: the grids' spread over √grids.
    pub stderr: f64,
    /// Largest share of the power, over the grids, dropped by the depth or power limit.
    pub lost: f64,
    /// Rays that hit the stone, over all grids.
    pub rays: u64,
}

/// One splitmix64 step: a portable, seedable source of uniform numbers in [0, 1).
fn uniform(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// One ray straight down through `p0` (above the stone): whether it hits, the power leaving
/// upward and the power lost to the limits (shares of the ray's power).
fn ray(planes: &[(DVec3, f64)], ri: f64, p0: DVec3, o: &GridOptions) -> (bool, f64, f64) {
    let d = DVec3::NEG_Z;
    let (mut tin, mut tout, mut fin) = (f64::NEG_INFINITY, f64::INFINITY, usize::MAX);
    for (k, &(n, off)) in planes.iter().enumerate() {
        let (nd, dist) = (n.dot(d), off - n.dot(p0));
        if nd < 0.0 {
            if dist / nd > tin {
                tin = dist / nd;
                fin = k;
            }
        } else if nd > 0.0 {
            tout = tout.min(dist / nd);
        } else if dist < 0.0 {
            return (false, 0.0, 0.0);
        }
    }
    if fin == usize::MAX || tin >= tout {
        return (false, 0.0, 0.0);
    }
    let n0 = planes[fin].0;
    let f0 = fresnel(-n0.dot(d), 1.0, ri);
    let mut axis = s_axis(d, n0).unwrap_or(DVec3::X);
    // Unpolarized light in; unpolarized tracing uses only the intensity.
    let (r0, mut s) = if o.polarization {
        let s_in = DVec4::new(1.0, 0.0, 0.0, 0.0);
        let r = f0.mueller_reflect().apply(s_in);
        let mut t = f0.mueller_transmit().apply(s_in);
        t.x = 1.0 - r.x;
        (r.x, t)
    } else {
        let r = f0.reflectance();
        (r, DVec4::new(1.0 - r, 0.0, 0.0, 0.0))
    };
    let mut up = if reflect(d, n0).z > 0.0 { r0 } else { 0.0 };
    let Some(mut t) = refract(d, n0, 1.0, ri) else {
        return (true, up, 0.0);
    };
    let mut x = p0 + d * tin;
    let mut last = fin;
    for _ in 0..=o.max_depth {
        let (mut best, mut g) = (f64::INFINITY, usize::MAX);
        for (k, &(n, off)) in planes.iter().enumerate() {
            let nt = n.dot(t);
            if nt > 0.0 && k != last {
                let sd = (off - n.dot(x)) / nt;
                if sd < best {
                    best = sd;
                    g = k;
                }
            }
        }
        if g == usize::MAX {
            return (true, up, s.x);
        }
        x += t * best.max(0.0);
        let n = planes[g].0;
        let f = fresnel(n.dot(t), ri, 1.0);
        let (tr, mut sr): (f64, Stokes) = if o.polarization {
            let a = s_axis(t, n).unwrap_or(axis);
            let si = rotate_stokes(s, axis, a, t);
            axis = a;
            let r = f.mueller_reflect().apply(si);
            ((si.x - r.x).max(0.0), r)
        } else {
            let r = f.reflectance();
            (s.x * (1.0 - r), DVec4::new(s.x * r, 0.0, 0.0, 0.0))
        };
        match refract(t, n, ri, 1.0) {
            Some(out) if out.z > 0.0 => up += tr,
            Some(_) => {}
            None => sr.x += tr,
        }
        s = sr;
        if s.x < o.min_power {
            return (true, up, s.x);
        }
        t = reflect(t, n);
        last = g;
    }
    (true, up, s.x)
}

/// One jittered grid: (upward share, rays that hit, lost share).
fn grid(
    planes: &[(DVec3, f64)],
    solid: &Polyhedron,
    ri: f64,
    seed: u64,
    o: &GridOptions,
) -> (f64, u64, f64) {
    let mut st = seed;
    let (sa, ca) = (uniform(&mut st) * std::f64::consts::TAU).sin_cos();
    let r = solid.max_radius() * 1.01;
    let n = o.n.max(1);
    let h = 2.0 * r / n as f64;
    let (ox, oy) = (uniform(&mut st) * h, uniform(&mut st) * h);
    let top = solid.bounding_box().1.z + 1.0;
    // n + 1 rows and columns from -r - ox: the grid covers the square [-r, r]² for any shift.
    let rows: Vec<(f64, u64, f64)> = (0..=n)
        .into_par_iter()
        .map(|i| {
            let mut st = seed ^ (i as u64 + 1).wrapping_mul(0xD6E8_FEB8_6659_FD93);
            let (mut up, mut hits, mut lost) = (0.0, 0u64, 0.0);
            for j in 0..=n {
                let a = -r - ox + (i as f64 + uniform(&mut st)) * h;
                let b = -r - oy + (j as f64 + uniform(&mut st)) * h;
                let p0 = DVec3::new(ca * a - sa * b, sa * a + ca * b, top);
                let (hit, u, l) = ray(planes, ri, p0, o);
                if hit {
                    hits += 1;
                    up += u;
                    lost += l;
                }
            }
            (up, hits, lost)
        })
        .collect();
    let (up, hits, lost) = rows
        .iter()
        .fold((0.0, 0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2));
    let k = hits.max(1) as f64;
    (up / k, hits, lost / k)
}

/// Overhead light return of `solid` at index `ri` under straight-down parallel light: the
/// share of the power entering its shadow that leaves upward, from jittered ray grids.
/// Deterministic for given options (the rows run in parallel, their sums are added in order).
pub fn overhead_light_return(solid: &Polyhedron, ri: f64, o: &GridOptions) -> GridEstimate {
    let planes: Vec<(DVec3, f64)> = solid
        .facets()
        .iter()
        .map(|f| (f.plane.normal, f.plane.offset))
        .collect();
    let k = o.grids.max(2);
    let figs: Vec<(f64, u64, f64)> = (0..k)
        .map(|i| grid(&planes, solid, ri, o.seed + i as u64, o))
        .collect();
    let m = figs.iter().map(|f| f.0).sum::<f64>() / k as f64;
    let var = figs.iter().map(|f| (f.0 - m).powi(2)).sum::<f64>() / (k - 1) as f64;
    GridEstimate {
        value: m,
        stderr: (var / k as f64).sqrt(),
        lost: figs.iter().map(|f| f.2).fold(0.0, f64::max),
        rays: figs.iter().map(|f| f.1).sum(),
    }
}
