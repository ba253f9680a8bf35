//! Tests of the beam tracer: power accounting, tiling, footprints against path products, a
//! closed form (the cube), and an independent deterministic ray-grid tracer.
//!
//! By subject: [`accounting`] (power in = out + cut off, thresholds, depth, ray floor, forks,
//! tiling), [`closed_form`] (footprints against path products, the cube), [`grids`] (against
//! independent ray grids) and [`stone`] (symmetry reduction, the exit-facet walk).

use super::Frame;
use crate::geometry::Polyhedron;
use crate::testkit::{cube, octahedron, princess, tolkowsky};
use glam::DVec3;

mod absorption;
mod accounting;
mod closed_form;
mod crystal;
mod grids;
mod places;
mod stone;

fn solids() -> Vec<(&'static str, Polyhedron)> {
    vec![
        ("tolkowsky", tolkowsky()),
        ("princess", princess()),
        ("octahedron", octahedron()),
        ("cube", cube()),
    ]
}

fn dirs() -> Vec<Frame> {
    vec![
        Frame::overhead(),
        Frame::new(DVec3::new(0.3, -0.2, -1.0)).unwrap(),
        Frame::new(DVec3::new(-1.0, 0.4, -0.3)).unwrap(),
        Frame::new(DVec3::new(0.1, 0.2, 1.0)).unwrap(),
    ]
}
