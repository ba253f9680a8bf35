//! Geometry: planes, convex polyhedra built from half-spaces, facet polygons, 2-D convex
//! clipping and convex hulls.
//!
//! Conventions (docs/cuts.md, "Conventions"): right-handed, z up, origin at the centre of the girdle plane,
//! lengths in girdle diameters (D = 1). A facet is the half-space `normal · x <= offset` with an
//! outward unit normal.

pub mod axial;
pub mod canonical;
pub mod clip2d;
pub(crate) mod fast_hash;
mod hull;
mod outline;
mod plane;
mod polyhedron;
mod tjunction;

pub use glam::{DVec2, DVec3};
pub use hull::{convex_hull, convex_hull_with_tolerance, hull, Hull, HullOptions, MERGE_TOL};
pub use outline::outline_size;
pub use plane::{facet_angle_deg, facet_azimuth_deg, facet_normal, FacetPlane, Plane, EPS, WELD};
pub use polyhedron::{Block, Edge, Facet, Polyhedron};
