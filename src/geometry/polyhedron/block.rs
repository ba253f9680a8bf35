//! [`Block`]: the clipping box carved plane by plane, open solids and vanished planes allowed.

use super::{clip, Face, BOX};
use crate::geometry::{DVec3, Plane};

/// A block being carved plane by plane: the large box (half-size 1000) cut by half-spaces in
/// turn, each plane's face kept as a polygon. Unlike [`Polyhedron::from_planes`](super::Polyhedron::from_planes), a plane
/// that leaves no face is not an error and the block may stay open: a design being cut tier by
/// tier is open until its last tiers and may lose facets, and its author wants to know which
/// ([`crate::design`]'s recipes). Carving is incremental (a plane costs one pass over the
/// faces), and a block is cheap to clone for a trial cut.
///
/// ```
/// use facetlab::geometry::{Block, DVec3, Plane};
///
/// // Two half-spaces, z <= 0.5 and x <= 0.2: two real faces, four box faces still open.
/// let mut b = Block::new();
/// b.cut(Plane::new(DVec3::Z, 0.5).unwrap());
/// b.cut(Plane::new(DVec3::X, 0.2).unwrap());
/// assert!(b.face(0).len() >= 3 && b.face(1).len() >= 3);
/// assert_eq!(b.open().len(), 4);
/// // A plane outside the block cuts nothing and gets no face.
/// b.cut(Plane::new(DVec3::X, 5.0).unwrap());
/// assert!(b.face(2).is_empty());
/// ```
#[derive(Clone)]
pub struct Block {
    faces: Vec<Face>,
    planes: usize,
    buffer: Vec<f64>,
}

impl Default for Block {
    fn default() -> Self {
        Block::new()
    }
}

impl Block {
    /// The uncut box.
    pub fn new() -> Block {
        Block {
            faces: box_faces(),
            planes: 0,
            buffer: Vec::new(),
        }
    }

    /// Cut by the half-space `plane.normal · x <= plane.offset`; returns the plane's number
    /// (0 for the first plane cut).
    pub fn cut(&mut self, plane: Plane) -> usize {
        let k = self.planes;
        clip(&mut self.faces, &plane, k, &mut self.buffer);
        self.planes += 1;
        k
    }

    /// Planes cut so far.
    pub fn planes(&self) -> usize {
        self.planes
    }

    /// The face polygon plane `k` leaves (counter-clockwise seen from outside); empty when the
    /// plane cut nothing or later planes cut its face away.
    pub fn face(&self, k: usize) -> &[DVec3] {
        self.faces
            .iter()
            .find(|f| f.source == Some(k))
            .map_or(&[], |f| f.poly.as_slice())
    }

    /// Every plane's face polygon, by plane number (see [`Block::face`]).
    pub fn faces(&self) -> Vec<&[DVec3]> {
        let mut out: Vec<&[DVec3]> = vec![&[]; self.planes];
        for f in &self.faces {
            if let Some(k) = f.source {
                out[k] = &f.poly;
            }
        }
        out
    }

    /// Outward normals of the box faces still showing (±x, ±y, ±z): empty when the planes
    /// enclose a bounded solid.
    pub fn open(&self) -> Vec<DVec3> {
        self.faces
            .iter()
            .filter(|f| f.source.is_none())
            .map(|f| f.normal)
            .collect()
    }

    /// Whether a point is on the box, not on a plane's face (farther than 999 from the origin
    /// along an axis).
    pub fn on_box(p: DVec3) -> bool {
        p.abs().max_element() > 0.999 * BOX
    }
}

pub(super) fn box_faces() -> Vec<Face> {
    let b = BOX;
    let c = |x: f64, y: f64, z: f64| DVec3::new(x * b, y * b, z * b);
    // Each face counter-clockwise seen from outside.
    let quads: [(DVec3, [DVec3; 4]); 6] = [
        (
            DVec3::X,
            [
                c(1., -1., -1.),
                c(1., 1., -1.),
                c(1., 1., 1.),
                c(1., -1., 1.),
            ],
        ),
        (
            DVec3::NEG_X,
            [
                c(-1., -1., -1.),
                c(-1., -1., 1.),
                c(-1., 1., 1.),
                c(-1., 1., -1.),
            ],
        ),
        (
            DVec3::Y,
            [
                c(-1., 1., -1.),
                c(-1., 1., 1.),
                c(1., 1., 1.),
                c(1., 1., -1.),
            ],
        ),
        (
            DVec3::NEG_Y,
            [
                c(-1., -1., -1.),
                c(1., -1., -1.),
                c(1., -1., 1.),
                c(-1., -1., 1.),
            ],
        ),
        (
            DVec3::Z,
            [
                c(-1., -1., 1.),
                c(1., -1., 1.),
                c(1., 1., 1.),
                c(-1., 1., 1.),
            ],
        ),
        (
            DVec3::NEG_Z,
            [
                c(-1., -1., -1.),
                c(-1., 1., -1.),
                c(1., 1., -1.),
                c(1., -1., -1.),
            ],
        ),
    ];
    quads
        .iter()
        .map(|(n, q)| Face::new(None, *n, q.to_vec()))
        .collect()
}
