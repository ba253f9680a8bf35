//! What a trace hands out: the [`ExitSink`] every exit beam is given to, and the power
//! accounting and work counters of the whole trace ([`TraceStats`]).

use super::exit::ExitBeam;
use glam::{DVec2, DVec3};

/// Receives exit beams as the tracer produces them.
pub(crate) trait ExitSink {
    /// Whether [`ExitSink::exit`] should be given footprints (computing them costs time).
    fn wants_footprints(&self) -> bool {
        false
    }
    /// Whether `beam` or any of the symmetric copies of it that a trace using the stone's
    /// symmetry hands out can change what this sink measures; `false` lets the tracer skip
    /// them all (and transforming their footprints). The copies share the beam's power and
    /// its direction's component along the viewer's axis (the frame's symmetries keep that
    /// axis), so a sink may decide from those. Default: always wanted.
    fn wants_orbit(&self, _beam: &ExitBeam) -> bool {
        true
    }
    /// The symmetries a trace using the stone's symmetry hands each traced exit out under:
    /// per symmetry, the index its copies carry in `ExitBeam::sym` and the 2×2 map
    /// `[a, b, c, d]` of their footprints (`(x, y) ↦ (a x + b y, c x + d y)`). Called once
    /// before the first exit; the copies of one traced exit then arrive one after another,
    /// the identity (index 0) first. Default: ignored.
    fn symmetries(&mut self, _maps: &[(u16, [f64; 4])]) {}
    /// One exit beam, with its footprint in the frame's image coordinates (empty unless
    /// [`ExitSink::wants_footprints`]).
    fn exit(&mut self, beam: &ExitBeam, footprint: &[DVec2]);
    /// Whether [`ExitSink::exit_at`] should be given where each beam leaves the stone (the
    /// symmetric copies' places are then computed too). Default: no.
    fn wants_exit_places(&self) -> bool {
        false
    }
    /// Whether a narrow beam's ray should give, as its exit's place, its narrow beam's
    /// polygon carried along the ray to the exit facet's plane (slid along each segment,
    /// unclipped: the cross-section it stands for; a birefringent ray's carried along its
    /// own ray direction, mode by mode) instead of one point. Only asked when
    /// [`ExitSink::wants_exit_places`]; traces with
    /// [`TraceOptions::narrow_forks`](super::TraceOptions::narrow_forks) give the point.
    /// Default: no.
    fn wants_narrow_polygons(&self) -> bool {
        false
    }
    /// One exit beam with its footprint and where it leaves the stone (stone coordinates):
    /// the polygon it crosses the exit facet's plane in, vertex for vertex the footprint's
    /// (each footprint vertex's ray leaves there), or one point, where a narrow beam's ray
    /// leaves (its footprint is the whole narrow beam's; its polygon carried there instead
    /// when [`ExitSink::wants_narrow_polygons`]). `place` is empty unless
    /// [`ExitSink::wants_exit_places`]. The tracer hands every exit out through this; by
    /// default it is [`ExitSink::exit`].
    #[inline(always)]
    fn exit_at(&mut self, beam: &ExitBeam, footprint: &[DVec2], place: &[DVec3]) {
        let _ = place;
        self.exit(beam, footprint);
    }
}

/// Power accounting and work counters of one trace. Powers are shares of the whole incoming
/// beam.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TraceStats {
    /// Cross-section of the stone across the incoming direction (its projected area).
    pub area: f64,
    /// Sum of the root beams' power shares: 1 to rounding (0 if the stone has no cross-section).
    pub power_in: f64,
    /// Power of reflected beams not followed (below the threshold or past the depth limit).
    pub cut_off: f64,
    /// Number of internal beams split.
    pub beams: usize,
    /// Number of exit beams produced.
    pub exits: usize,
    /// Narrow beams followed as rays (below the split threshold).
    pub rays: usize,
    /// Facets met by those rays (their segments inside the stone).
    pub ray_segments: usize,
    /// Power that entered narrow-beam (ray) mode: the share of the light whose further path was
    /// found by one ray per narrow beam rather than by exact splitting.
    pub ray_power: f64,
    /// Largest relative difference between a beam's cross-section and the sum of its
    /// children's (the clipping's tiling error; ~1e-15 when all is well).
    pub max_tiling_error: f64,
    /// Power of narrow beams' rays stopped by [`TraceOptions::ray_floor`](super::TraceOptions::ray_floor)
    /// (part of `cut_off`).
    pub ray_closed: f64,
    /// Light absorbed by the body colour ([`TraceOptions::absorption`](super::TraceOptions::absorption))
    /// on the way to the exits: `power_in = Σ exit powers + cut_off + absorbed` to rounding.
    pub absorbed: f64,
}
