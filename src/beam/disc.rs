//! A narrow beam's disc (see [`TraceOptions::narrow_forks`](super::TraceOptions::narrow_forks)):
//! the part of a narrow beam followed as a ray ([`Part`]), and the segments of its disc that
//! overhang the edges of the facet its ray meets and fork off onto the neighbours ([`Fork`]).

use super::stone::{Stone, GRAZE};
use crate::optics::Stokes;
use glam::DVec3;

/// Share of a disc beyond a chord at signed distance `u` radii from its centre (1 at
/// `u = −1`, ½ at 0, 0 at 1; continuously differentiable), and the distance of that part's
/// centroid from the centre, in radii.
#[inline]
pub(super) fn disc_segment(u: f64) -> (f64, f64) {
    let u = u.clamp(-1.0, 1.0);
    let s = (1.0 - u * u).max(0.0).sqrt();
    let f = (u.acos() - u * s) / std::f64::consts::PI;
    let c = if f > 0.0 {
        2.0 * s * s * s / (3.0 * std::f64::consts::PI * f)
    } else {
        1.0
    };
    (f, c)
}

/// `3x² − 2x³`: 0 at 0, 1 at 1, flat at both.
#[inline]
pub(super) fn smooth(x: f64) -> f64 {
    x * x * (3.0 - 2.0 * x)
}

/// A narrow beam's forks carry at least this share of its starting power; smaller parts
/// beyond a facet edge stay with the main ray (an error of at most this share of a narrow
/// beam, against [`TraceOptions::ray_floor`](super::TraceOptions::ray_floor)'s 5 %).
const FORK_MIN: f64 = 1e-3;

/// Forks onto facets met at a grazing angle fade in over `n · t` ∈ [0, FORK_GRAZE] (a disc
/// is not the beam: near the silhouette it overhangs facets the beam itself does not reach).
const FORK_GRAZE: f64 = 0.02;

/// At most this share of a narrow beam forks off at one crossing (near a corner the disc can
/// overhang several edges).
pub(super) const FORK_MAX: f64 = 0.95;

/// One part of a narrow beam followed as a ray: at `x` on `facet`'s plane, travelling along
/// `t`, a disc of radius `r` carrying `share` of the narrow beam's cross-section.
#[derive(Clone, Copy, Debug)]
pub(super) struct Part {
    pub(super) x: DVec3,
    pub(super) t: DVec3,
    pub(super) s: Stokes,
    pub(super) axis: DVec3,
    pub(super) facet: u32,
    pub(super) depth: u32,
    pub(super) prev: u32,
    pub(super) r: f64,
    pub(super) share: f64,
    /// Path length inside the stone from the entry facet to `x`.
    pub(super) path: f64,
}

/// A fork of a narrow beam's disc across an edge of its exit facet onto facet `h`: its share
/// `f`, the unit direction `m` (across the beam) toward the edge and its centroid's distance
/// `c` from the disc's centre.
#[derive(Clone, Copy, Debug)]
pub(super) struct Fork {
    pub(super) h: u32,
    pub(super) f: f64,
    pub(super) m: DVec3,
    pub(super) c: f64,
}

impl Stone {
    /// The segments of `part`'s disc beyond the edges of facet `g`, which its ray meets at
    /// `p`, into `w.forks` (`p0`: the narrow beam's starting power).
    pub(super) fn disc_forks(
        &self,
        g: usize,
        p: DVec3,
        part: &Part,
        p0: f64,
        forks: &mut Vec<Fork>,
    ) {
        forks.clear();
        let t = part.t;
        let ng = self.normals[g];
        let kg = ng.dot(t);
        let a = self.facet_edge_start(g);
        for (j, e) in self.facet_edges(g).iter().enumerate() {
            let (pl, h) = (e.plane, e.facet);
            let nh = pl.truncate();
            let kh = nh.dot(t);
            if kh <= GRAZE {
                continue;
            }
            // The plane through the edge along t: m · y = 0 there, m ⊥ t.
            let m = nh - ng * (kh / kg);
            let ml = m.length();
            if ml.is_nan() || ml <= 0.0 {
                continue;
            }
            let d = (pl.w - nh.dot(p)) / ml;
            if d >= part.r {
                continue;
            }
            let u = d / part.r;
            let (f, c) = disc_segment(u);
            // Only the stretch of the chord that the edge itself spans overhangs onto h (a
            // short edge's line may cross the disc far from the edge).
            let (ea, eb) = self.neighbor_edges[a + j];
            let e = (eb - ea).reject_from_normalized(t);
            let el = e.length();
            let half = part.r * (1.0 - u * u).max(0.0).sqrt();
            let span = if el > 0.0 && half > 0.0 {
                let e = e / el;
                let (sa, sb) = ((ea - p).dot(e), (eb - p).dot(e));
                (sa.max(sb).min(half) - sa.min(sb).max(-half)).max(0.0) / (2.0 * half)
            } else {
                0.0
            };
            let fade = (kh / FORK_GRAZE).min(1.0);
            // Small forks fade out (between FORK_MIN and twice that share of the narrow
            // beam) rather than stop at once.
            let small = (f * span * part.s.x / (FORK_MIN * p0) - 1.0).clamp(0.0, 1.0);
            let f = f * span * smooth(fade) * smooth(small);
            if f.is_nan() || f <= 0.0 {
                continue;
            }
            forks.push(Fork {
                h,
                f,
                m: m / ml,
                c: c * part.r,
            });
        }
    }
}
