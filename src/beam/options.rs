//! [`TraceOptions`]: how far the tracer follows light, and what it records.

/// How far the tracer follows light, and what it records.
///
/// Beams with at least `split_threshold` of the incoming power are split exactly. Smaller
/// ones (narrow beams) are followed as one ray each, from their polygon's area centroid, with the
/// same expected-value Fresnel branching: their exit beams carry the narrow beam's footprint
/// and exact power bookkeeping, but the narrow beam is no longer divided where it straddles
/// facet edges. Light below `threshold`, or past `max_depth` internal reflections, is cut off
/// and accounted in [`TraceStats::cut_off`](super::TraceStats::cut_off). Setting `split_threshold <= threshold` gives the
/// purely exact tracer (everything below the threshold is cut off).
///
/// Why not split everything: in a round brilliant a few tenths of a percent of the light stays
/// trapped by total internal reflection for more than 64 bounces, and the exact beam tree of
/// that tail has hundreds of thousands of beams; cut off at 1e-6 it still loses about 0.8 % of
/// the light. Narrow beams keep that tail's power in play at the cost of one ray each.
///
/// What that costs in exactness (measured against [`reference`](mod@super::reference), `cargo bench --bench exact`,
/// overhead light return of tolkowsky, gia-reference, princess and an octahedron): each narrow
/// beam's ray samples its beam at one point (its area centroid), so its light goes all one way
/// where the beam would have straddled facet edges. Over a trace these errors add like noise
/// (the largest narrow beams dominate), and face-up a symmetric stone repeats them in every
/// wedge: the overhead light return is off by −0.18 to −0.016 percentage points at the default
/// split threshold, by −0.012 to +0.055 at 1e-5 and by −0.006 to +0.008 at 1e-6 (the split
/// threshold of the scores' face-up trace, `ScoreConfig::face_up_split_threshold`).
///
/// A narrow beam's ray changes its path only where the ray crosses a facet edge, so a trace
/// is piecewise continuous in the solid: a 1e-10 change of a cut's proportions moves no score
/// by more than a few 1e-9 (`metrics` tests), though a change large enough to move a narrow
/// beam's ray across an edge moves the result by up to that beam's power.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceOptions {
    /// Track polarization with Stokes vectors and Mueller matrices (default). Off: every
    /// interface uses the unpolarized reflectance (Rs + Rp)/2 and light stays unpolarized.
    pub polarization: bool,
    /// Beams with at least this share of the incoming power are split exactly; smaller ones
    /// continue as narrow beams. Default [`TraceOptions::SPLIT_THRESHOLD`].
    pub split_threshold: f64,
    /// Light with less than this share of the incoming power is cut off (and accounted as
    /// cut off). Default 1e-8: against 1e-9 it moves brilliance by under 1e-5 and overhead
    /// light return by under 2e-5 on the presets, and saves a sixth of a score's time.
    pub threshold: f64,
    /// Largest number of internal reflections followed. Default 1000.
    pub max_depth: u32,
    /// Compute each exit beam's footprint polygon (needed for images and patterns; costs a
    /// little time). Default off.
    pub footprints: bool,
    /// Use the stone's symmetry (default on): when rotations about the z axis or mirrors
    /// through it map the stone and the incoming direction onto themselves, only a
    /// fundamental wedge of the cross-section is traced and every exit beam is handed out once
    /// per symmetry, transformed (direction, polarization frame, footprint, facets). A face-up
    /// round brilliant has 16 symmetries. The result is the same light, split along the
    /// wedge's edges too.
    pub symmetry: bool,
    /// A narrow beam's ray stops once its power falls below this share of the power it
    /// started with (default 0: it goes on down to `threshold`). The power it still carries
    /// is accounted in [`TraceStats::ray_closed`](super::TraceStats::ray_closed) (and in [`TraceStats::cut_off`](super::TraceStats::cut_off)), for a
    /// caller that integrates over the exits to hand back with the narrow exits' mean: the
    /// scores do (`ScoreConfig::trace`, with the mean of the [`ExitBeam::late`](super::ExitBeam::late) exits),
    /// pictures do not. Most of a ray's segments are spent in its last few percent of power,
    /// bouncing by total internal reflection: at 0.05 a tilted pose's rays need 0.48 of
    /// their segments, and with that closure the ISO light return of 30 tilted poses of six
    /// presets errs by 4.71e-4 on average against a trace split down to 1e-6 (4.84e-4
    /// without a floor).
    pub ray_floor: f64,
    /// Follow a narrow beam as a disc of its cross-section's area around its ray (default
    /// off; `[score] narrow_forks` in a config): where the disc overhangs an edge of the
    /// facet the ray meets, the overhanging segment (the stretch the edge spans) forks off
    /// onto the neighbouring facet with its share of the power, as a ray and disc of its own.
    /// Off: one ray carries the whole narrow beam to whichever facet it meets, so a narrow
    /// beam's light jumps from one facet to the next as the cut changes. Forks cost segments:
    /// about 3× at a ray floor of 0.02, and without a floor they multiply (a tilted pose's
    /// rays take 24× the segments), so use them with a floor. Their smoothness and their
    /// error are measured in the `metrics` module's documentation.
    pub narrow_forks: bool,
    /// Absorption coefficient of the stone's body colour at this trace's wavelength, per
    /// girdle diameter (Beer–Lambert: a ray keeps `exp(−absorption · L)` of its light after a
    /// path `L` inside). Default 0, colourless: the trace is then the very same as without
    /// it. Every exit beam's power is its light times the mean of `exp(−absorption · L)` over
    /// its footprint, exact because `L` is affine over a beam's cross-section
    /// ([`attenuation`](mod@super::attenuation)); a narrow beam's ray takes its own path's. The light
    /// absorbed on the way out is [`TraceStats::absorbed`](super::TraceStats::absorbed); beams that are cut off keep the
    /// power they had before absorption in [`TraceStats::cut_off`](super::TraceStats::cut_off).
    pub absorption: f64,
    /// Birefringent stones ([`Medium::Uniaxial`](super::Medium::Uniaxial)): a narrow beam's ray splits into a ray per
    /// reflected mode only where each carries at least this share of the narrow beam's
    /// starting power; a weaker mode's light stays with the other mode's ray (its power
    /// added, its path that ray's). A ray then branches into at most `1/mode_floor` rays
    /// instead of doubling at every facet (see the module documentation of `beam::crystal`
    /// for what it costs and leaves out). Default [`TraceOptions::MODE_FLOOR`]; 0 follows
    /// every mode down to the other floors.
    pub mode_floor: f64,
}

impl TraceOptions {
    /// Default [`TraceOptions::mode_floor`].
    pub const MODE_FLOOR: f64 = 1.0;

    /// Default split threshold.
    pub const SPLIT_THRESHOLD: f64 = 1e-4;

    /// The purely exact tracer: every beam above `threshold` is split; nothing is followed
    /// as a ray.
    pub fn exact(threshold: f64) -> TraceOptions {
        TraceOptions {
            split_threshold: threshold,
            threshold,
            ..Default::default()
        }
    }
}

impl Default for TraceOptions {
    fn default() -> Self {
        TraceOptions {
            polarization: true,
            split_threshold: Self::SPLIT_THRESHOLD,
            threshold: 1e-8,
            max_depth: 1000,
            footprints: false,
            symmetry: true,
            ray_floor: 0.0,
            narrow_forks: false,
            absorption: 0.0,
            mode_floor: Self::MODE_FLOOR,
        }
    }
}
