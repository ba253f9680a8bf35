//! 3-D convex hull of a point set, returned as facet planes.
//!
//! Quickhull, made robust in three ways:
//! - the points are first moved and scaled into a unit box (the hull does not change under
//!   translation and uniform scaling), so every tolerance is relative to the size of the set;
//! - which faces an apex sees is decided exactly, on copies of the points snapped to a grid of
//!   2⁻⁴⁰ of the size, with integer arithmetic; the triangulation therefore stays convex and
//!   never folds over itself, however many points are (nearly) coplanar;
//! - a point within half the merge tolerance of the hull counts as lying on it and never becomes
//!   a vertex, so rounding noise on a flat facet does not splinter it.
//!
//! The triangles are then merged into one facet per plane (a cube's 12 STL triangles become 6
//! facets; `merge.rs`): facets grow from the largest triangle across shared edges, taking a
//! neighbour when its three corners lie within the merge tolerance of the facet's plane. A
//! facet's normal is the area-weighted mean of its well-aligned triangles' normals, its offset
//! the largest `normal · p` over the hull's vertices (found by climbing the hull's edges, which
//! on a convex solid ends at the top) and the points left on its faces, so every hull vertex
//! lies inside or on every returned plane.
//!
//! Cost: quickhull is O(n log n) on the usual inputs (each point is reassigned a logarithmic
//! number of times), and the merge is linear in the triangles; a scanned rough of 400,000
//! triangles is hulled in well under a second (`cargo bench --bench plan`).
//!
//! [`hull`] can also stop early, at a number of vertices ([`HullOptions::max_vertices`]): the
//! farthest point outside the hull so far is then always added next (a greedy, progressive
//! hull), and the result is the hull of the vertices chosen, inside the full hull, with the
//! farthest point left out reported ([`Hull::left_out`]).

mod convex;
mod merge;
mod quickhull;

use super::DVec3;
pub use convex::{convex_hull, convex_hull_with_tolerance, hull, Hull, HullOptions, MERGE_TOL};
use quickhull::Face;
#[cfg(test)]
use {super::Plane, quickhull::quickhull};

#[cfg(test)]
mod tests;
