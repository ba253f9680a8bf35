//! [`Frame`]: the incoming direction and the image coordinates across it.

use glam::{DMat3, DVec3};

/// The incoming direction and the image coordinates across it.
///
/// `dir` is the direction the light travels (for a viewer traced backwards: from the eye into
/// the stone). `u` and `v` are unit vectors perpendicular to `dir` with `u × v = −dir`: the
/// image's right and up as seen by someone looking along `dir`. Footprints are given as
/// `(x · u, x · v)` for points `x` on the entry facet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Direction of travel (unit).
    pub dir: DVec3,
    /// Image right (unit, ⊥ `dir`).
    pub u: DVec3,
    /// Image up (unit, ⊥ `dir` and `u`).
    pub v: DVec3,
}

impl Frame {
    /// A frame for direction `dir` (normalised here) with an arbitrary image rotation; `None`
    /// for a zero or non-finite direction.
    pub fn new(dir: DVec3) -> Option<Frame> {
        let d = dir.try_normalize()?;
        let u = d.any_orthonormal_vector();
        Some(Frame {
            dir: d,
            u,
            v: u.cross(d),
        })
    }

    /// Light (or a viewer's gaze) straight down, with image axes x and y.
    pub fn overhead() -> Frame {
        Frame {
            dir: DVec3::NEG_Z,
            u: DVec3::X,
            v: DVec3::Y,
        }
    }

    /// The frame of a viewer straight above a stone that has been turned by `rot` (stone
    /// coordinates → world coordinates): the gaze is world −z, the image axes world x and y,
    /// all expressed in the stone's coordinates.
    pub fn viewer(rot: DMat3) -> Frame {
        Frame {
            dir: rot.transpose_mul_vec3(DVec3::NEG_Z),
            u: rot.transpose_mul_vec3(DVec3::X),
            v: rot.transpose_mul_vec3(DVec3::Y),
        }
    }
}
