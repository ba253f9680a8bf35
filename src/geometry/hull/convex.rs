//! The convex hull of a point set: its options, result and entry points ([`hull`],
//! [`convex_hull`]); the triangulation is quickhull's (`quickhull.rs`), the facets `merge.rs`'s.

use super::merge;
use super::quickhull::{quickhull, TINY};
use crate::error::{Error, Result};
use crate::geometry::{DVec3, Plane};

/// Default merge tolerance of [`convex_hull`]: corners within `1e-7 × size` of a facet's plane
/// belong to that facet (size: the largest side of the points' bounding box).
pub const MERGE_TOL: f64 = 1e-7;

/// How [`hull`] works.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HullOptions {
    /// Merge tolerance relative to the size of the point set (see [`convex_hull_with_tolerance`]).
    pub merge_tol: f64,
    /// Stop once the hull has this many vertices (at least 4): the farthest point outside is
    /// always added next, so the hull is the best of its size the greedy order finds. `None`:
    /// the full hull.
    pub max_vertices: Option<usize>,
}

impl Default for HullOptions {
    fn default() -> Self {
        HullOptions {
            merge_tol: MERGE_TOL,
            max_vertices: None,
        }
    }
}

/// A convex hull: its facet planes, and how far the points left out stand outside them.
#[derive(Clone, Debug, PartialEq)]
pub struct Hull {
    /// Outward facet planes, coplanar triangles merged.
    pub planes: Vec<Plane>,
    /// The hull's vertices (points of the set).
    pub vertices: usize,
    /// The farthest any point stands outside the planes, in the points' units: 0 for a full
    /// hull (up to half the merge tolerance), else how much a hull stopped at
    /// [`HullOptions::max_vertices`] leaves out.
    pub left_out: f64,
}

/// The convex hull of `points` as outward facet planes, coplanar triangles merged with the
/// default tolerance [`MERGE_TOL`].
///
/// Errors: fewer than 4 points, a non-finite coordinate, or points that do not span a solid
/// (all equal, on one line, or in one plane).
pub fn convex_hull(points: &[DVec3]) -> Result<Vec<Plane>> {
    convex_hull_with_tolerance(points, MERGE_TOL)
}

/// [`convex_hull`] with a merge tolerance relative to the size of the point set (use a larger
/// one for coarse data, e.g. `1e-6` for single-precision STL coordinates).
pub fn convex_hull_with_tolerance(points: &[DVec3], rel_tol: f64) -> Result<Vec<Plane>> {
    hull(
        points,
        HullOptions {
            merge_tol: rel_tol,
            max_vertices: None,
        },
    )
    .map(|h| h.planes)
}

/// The convex hull of `points` with `options` (a merge tolerance, and perhaps a vertex budget).
///
/// ```
/// use facetlab::geometry::{hull, DVec3, HullOptions};
/// // 2,000 points on a sphere of radius 2: the full hull has them all as vertices; a hull of
/// // 200 vertices leaves the others at most a few hundredths outside.
/// let pts: Vec<DVec3> = (0..2000)
///     .map(|k| {
///         let z = 1.0 - (2 * k + 1) as f64 / 2000.0;
///         let a = 2.399963 * k as f64;
///         let r = (1.0 - z * z).sqrt();
///         2.0 * DVec3::new(r * a.cos(), r * a.sin(), z)
///     })
///     .collect();
/// let full = hull(&pts, HullOptions::default()).unwrap();
/// assert_eq!(full.vertices, 2000);
/// let coarse = hull(&pts, HullOptions { max_vertices: Some(200), ..Default::default() }).unwrap();
/// assert_eq!(coarse.vertices, 200);
/// assert!(coarse.left_out > 0.0 && coarse.left_out < 0.05, "{}", coarse.left_out);
/// ```
pub fn hull(points: &[DVec3], options: HullOptions) -> Result<Hull> {
    if points.len() < 4 {
        return Err(Error::Geometry(format!(
            "a convex hull needs at least 4 points, got {}",
            points.len()
        )));
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(Error::Geometry(format!(
            "point {} has a coordinate that is not a finite number",
            i + 1
        )));
    }
    let rel_tol = options.merge_tol;
    let rel_tol = if rel_tol.is_finite() && rel_tol > TINY {
        rel_tol.min(1e-2)
    } else {
        MERGE_TOL
    };
    let (mut lo, mut hi) = (points[0], points[0]);
    for p in points {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let size = (hi - lo).max_element();
    let centre = 0.5 * (lo + hi);
    if !(size.is_finite() && size > 0.0) {
        return Err(Error::Geometry(
            "all points coincide; a convex hull needs a solid".into(),
        ));
    }
    let pts: Vec<DVec3> = points.iter().map(|p| (*p - centre) / size).collect();
    // A budget no smaller than the points cannot bind: the full hull, in its usual order.
    let budget = options
        .max_vertices
        .map(|m| m.max(4))
        .filter(|&m| m < points.len());
    let tris = quickhull(&pts, rel_tol, budget)?;
    let planes = merge::merge(&pts, &tris.faces, rel_tol);
    // Back to the caller's frame: n·q <= d with q = (p - c)/size.
    Ok(Hull {
        planes: planes
            .into_iter()
            .map(|(n, d)| Plane {
                normal: n,
                offset: d * size + n.dot(centre),
            })
            .collect(),
        vertices: tris.vertices,
        left_out: tris.left_out * size,
    })
}
