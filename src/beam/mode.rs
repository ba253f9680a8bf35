//! The beams and rays of a birefringent trace, each in one mode of the crystal: what the
//! work stack holds (`work.rs`) and the crystal's trace (`crystal.rs`) splits.

use super::footprint::{Affine, PathLength};
use crate::optics::crystal::Wave;
use glam::DVec3;

/// A beam in one mode waiting to be split; its polygon (on `facet`'s plane) is
/// `pts[start..start + len]` of the point stack.
#[derive(Clone, Copy, Debug)]
pub(super) struct ModeBeam {
    pub(super) wave: Wave,
    /// Power (before absorption).
    pub(super) power: f64,
    /// Absorption per girdle diameter along this beam.
    pub(super) alpha: f64,
    pub(super) facet: u32,
    pub(super) entry: u32,
    pub(super) depth: u32,
    pub(super) node: u32,
    pub(super) start: u32,
    pub(super) len: u32,
    pub(super) map: Affine,
    /// Optical depth `Σ αᵢ Lᵢ` from the entry facet over the polygon.
    pub(super) tau: PathLength,
}

/// A narrow beam's ray (or one of the rays it splits into) at `x` on `facet`.
#[derive(Clone, Copy, Debug)]
pub(super) struct ModeRay {
    pub(super) x: DVec3,
    pub(super) wave: Wave,
    pub(super) power: f64,
    pub(super) alpha: f64,
    pub(super) tau: f64,
    pub(super) facet: u32,
    pub(super) depth: u32,
    pub(super) node: u32,
    /// Where its narrow beam's polygon, carried along to `facet`'s plane, starts in
    /// `Work::mode_polys` (when the sink wants it, [`super::ExitSink::wants_narrow_polygons`]).
    pub(super) poly: u32,
}
