//! The light of a birefringent trace's beams and rays, each in one mode of the crystal: what
//! the work stack holds (`work.rs`) and the crystal's trace (`crystal.rs`) splits.

use crate::optics::crystal::Wave;
use glam::DVec3;

/// A birefringent trace's beam's light ([`Beam`](super::work::Beam)`<InMode>`): one mode's
/// wave, its power and its absorption.
#[derive(Clone, Copy, Debug)]
pub(super) struct InMode {
    pub(super) wave: Wave,
    /// Power (before absorption).
    pub(super) power: f64,
    /// Absorption per girdle diameter along this beam.
    pub(super) alpha: f64,
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
