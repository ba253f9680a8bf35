//! A mesh's vertices as read, with where each came from and the text's rounding error.

use crate::geometry::DVec3;
use std::collections::HashSet;

/// Where a mesh vertex came from, for messages.
#[derive(Clone, Copy, Debug)]
pub(super) enum Loc {
    Line(usize),
    Triangle(usize),
}

impl Loc {
    pub(super) fn describe(self) -> String {
        match self {
            Loc::Line(n) => format!("line {n}"),
            Loc::Triangle(n) => format!("triangle {n}"),
        }
    }
}

/// Mesh vertices with their origin and an estimate of the coordinates' rounding error
/// (relative: absolute error / largest absolute coordinate).
pub(super) struct Points {
    pub(super) pts: Vec<DVec3>,
    pub(super) locs: Vec<Loc>,
    pub(super) rel_noise: f64,
    /// Single-precision coordinates (binary STL): corners split by rounding are welded.
    pub(super) single_precision: bool,
}

impl Points {
    pub(super) fn new() -> Points {
        Points {
            pts: Vec::new(),
            locs: Vec::new(),
            rel_noise: 0.0,
            single_precision: false,
        }
    }
    /// Add a point unless the very same point is already there.
    pub(super) fn push(&mut self, p: DVec3, loc: Loc, seen: &mut HashSet<[u64; 3]>) {
        let key = [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits());
        if seen.insert(key) {
            self.pts.push(p);
            self.locs.push(loc);
        }
    }
}
