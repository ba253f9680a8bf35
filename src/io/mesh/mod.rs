//! Triangle meshes in and out: Wavefront OBJ and STL (ASCII and binary).
//!
//! Reading: a mesh is taken as the convex hull of its vertices (the vertices its faces use, or
//! every `v` when an OBJ file has no faces), but only if the mesh is convex: every vertex must
//! lie on the hull's surface within [`CONVEX_TOL`] of the size (the largest side of the
//! vertices' bounding box). A vertex deeper inside is a dent, and the file is refused with the
//! largest depth found. The hull's coplanar triangles are merged into one facet per plane, with
//! a tolerance of `1e-7` of the size, widened for coarse coordinates (single-precision binary
//! STL, or text printed with few digits) to eight times their rounding error, at most `1e-4`.
//!
//! Welding (binary STL only): single-precision coordinates split a point where many facets meet
//! (a pointed culet, the girdle corners) into a cluster of vertices with tiny edges between
//! them. After normalisation, vertices joined by an edge shorter than 16 times the merge
//! tolerance, at most `1e-5` (of the solid's largest bounding-box side, about 4e-6 girdle
//! diameters for a binary STL), are welded into their cluster's mean point: a facet touching
//! one cluster is moved parallel to itself through it, one touching several is fitted again
//! through its welded corners, facets left with fewer than three corners are dropped, and this
//! is repeated (at most 8 rounds) while corners are still split. [`read_with_note`] says what
//! was welded (`facetlab info` prints it on standard error).
//!
//! Normalisation (docs/cuts.md's Conventions section: z up, origin at the centre of the girdle
//! plane, girdle diameter 1): the stone is assumed to be upright (z up, table on
//! top). The origin moves to the centre of the girdle plane: horizontally to the centre of the
//! outline's bounding box; vertically to the middle of the girdle, i.e. of the near-vertical
//! facets (normals within 1° of horizontal, the same rule [`crate::cut::Proportions`] uses to
//! measure the girdle) or, for a knife-edge girdle, the middle of the vertices at the largest
//! distance from the vertical axis. The solid is then scaled so that its width W (the outline's
//! smaller extent along x and y, the unit every preset is built in, [`crate::cut::units`]) is 1.
//!
//! Facets are named `f-1`, `f-2`, … in the order table, crown, girdle, pavilion, culet (then by
//! angle and azimuth), and their tier is that side: `table` and `culet` are the horizontal
//! facets, `girdle` the ones within 1° of vertical, `crown` and `pavilion` the rest above and
//! below.
//!
//! Writing: OBJ with the solid's welded vertices and one polygon per facet (a `g` group named
//! after the facet), and STL (binary, or ASCII with [`write_stl_ascii`]) with each facet
//! triangulated as a fan. Coordinates are written in full precision (binary STL: single
//! precision, as the format has it).
//!
//! Files: `obj.rs` reads and writes OBJ, `stl.rs` STL; `normalise.rs` turns the vertices into
//! named facet planes (hull, convexity check, girdle frame, tiers).

mod normalise;
mod obj;
mod points;
mod read;
mod stl;
#[cfg(test)]
mod tests;
mod tokens;

pub use normalise::CONVEX_TOL;
pub use obj::{read_obj, write_obj, write_obj_objects};
use points::{Loc, Points};
pub use read::{read, read_with_note};
pub use stl::{read_stl, write_stl, write_stl_ascii};
use tokens::{at, hull_error, number, quote, sig2, text_noise, token};
