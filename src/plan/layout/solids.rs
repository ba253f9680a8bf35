//! Saw directions and the small solid tests of a layout.

use super::super::fit::largest_copy;
use crate::geometry::{DVec3, FacetPlane, Plane, Polyhedron};
use glam::DQuat;
use rayon::prelude::*;

/// The saw directions of a layout in the rough's frame `frame`: the frame's three axes,
/// their six face diagonals and four body diagonals (one sign each).
pub fn directions(frame: DQuat) -> Vec<DVec3> {
    let e = [frame * DVec3::X, frame * DVec3::Y, frame * DVec3::Z];
    let mut out = vec![e[0], e[1], e[2]];
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        out.push((e[i] + e[j]).normalize());
        out.push((e[i] - e[j]).normalize());
    }
    for (s, t) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
        out.push((e[0] + s * e[1] + t * e[2]).normalize());
    }
    out
}

/// The half-spaces of a solid, each moved in by `by`.
pub(super) fn moved_in(solid: &Polyhedron, by: f64) -> Vec<FacetPlane> {
    solid
        .facet_planes()
        .into_iter()
        .map(|mut f| {
            f.plane.offset -= by;
            f
        })
        .collect()
}

/// Whether the plane `p` has every vertex of `pts` strictly outside.
pub(super) fn all_outside(p: &Plane, pts: &[DVec3]) -> bool {
    pts.iter().all(|v| p.distance(*v) > 1e-9)
}

/// Whether two convex solids are apart by one of their own face planes (a sufficient test;
/// solids it does not part are taken as meeting).
pub(super) fn apart(a: &Polyhedron, b: &Polyhedron) -> bool {
    a.facets()
        .iter()
        .any(|f| all_outside(&f.plane, b.vertices()))
        || b.facets()
            .iter()
            .any(|f| all_outside(&f.plane, a.vertices()))
}

/// The smallest and largest `u·v` over a solid's vertices.
pub(super) fn extent(solid: &Polyhedron, u: DVec3) -> (f64, f64) {
    solid
        .vertices()
        .iter()
        .map(|v| u.dot(*v))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        })
}

/// Of the half-spaces `sides` (`normal·x <= offset`), the one that leaves the largest copy of
/// `proxy` (at its own orientation) in `region` with it, and that copy's scale; `None` when
/// each leaves nothing. Judged in parallel, ties going to the first.
pub(super) fn widest(
    region: &Polyhedron,
    sides: &[Plane],
    proxy: &[DVec3],
) -> Option<(f64, Plane)> {
    let planes: Vec<Plane> = region.facets().iter().map(|f| f.plane).collect();
    let c = region.centroid();
    let fits: Vec<Option<f64>> = sides
        .par_iter()
        .map(|h| {
            let far = region
                .vertices()
                .iter()
                .copied()
                .min_by(|a, b| h.distance(*a).total_cmp(&h.distance(*b)))?;
            if h.distance(far) >= -1e-9 {
                return None;
            }
            // A point inside the region and strictly on the kept side.
            let inside = if h.distance(c) < 0.5 * h.distance(far) {
                c
            } else {
                let (dc, df) = (h.distance(c), h.distance(far));
                let t = (dc - 0.5 * df) / (dc - df);
                c + t * (far - c)
            };
            let mut with = planes.clone();
            with.push(*h);
            largest_copy(&with, proxy, inside).map(|f| f.scale)
        })
        .collect();
    let mut best: Option<(f64, Plane)> = None;
    for (h, s) in sides.iter().zip(fits) {
        if let Some(s) = s {
            if best.is_none_or(|(b, _)| s > b + 1e-12) {
                best = Some((s, *h));
            }
        }
    }
    best
}
