//! The exact area-sampling beam tracer.
//!
//! For one incoming direction (a parallel beam of light, or an orthographic viewer traced
//! backwards) and one wavelength, light meets a convex stone as a set of *beams*: convex
//! polygons of parallel rays. Every facet facing the light starts one, whose cross-section is
//! the facet's polygon seen along the light. At the entry facet the external part is reflected
//! (recorded as an exit beam) and the rest refracts inside. Inside, a beam travelling in
//! direction `t` reaches the facets with `n · t > 0`; projected along `t` onto the plane
//! perpendicular to it, those facets tile the stone's silhouette (the stone is convex), so
//! clipping the beam's projected polygon against each of them splits it into children that
//! tile it exactly. Each child meets one facet at one incidence angle: Fresnel's equations
//! (with polarization as Stokes vectors and Mueller matrices, or the unpolarized average)
//! divide it into a transmitted child, recorded as an exit beam, and a reflected child, which
//! continues. Beams below a split threshold continue as narrow beams (one ray each), and light
//! below a power threshold (a share of the whole incoming power) or past a depth limit is cut
//! off with its power accounted (see [`TraceOptions`]).
//!
//! Power is tracked directly: the root beams share the incoming power in proportion to their
//! cross-sections; a child gets its parent's power times its share of the parent's
//! cross-section (measured perpendicular to the parent's direction, where the split happens),
//! then Fresnel's R or T (the power transmittance already includes the change of beam width on
//! refraction). So `power_in = Σ exit powers + cut_off` holds to rounding.
//!
//! Every exit beam carries its direction, power share, Stokes vector (with its reference axis),
//! entry and exit facets, the facet sequence, and, on request, its footprint: the part of the
//! incoming cross-section (in the [`Frame`]'s image coordinates, as the light or the viewer
//! sees the stone) whose rays leave in it. Footprints of all exit beams (plus the cut-off
//! ones) tile the stone's silhouette; they make images and the scintillation pattern.
//!
//! The tracer knows nothing of lighting or scores; see [`crate::metrics`].

pub mod attenuation;
mod crystal;
mod disc;
mod exact;
mod footprint;
mod interface;
mod mode;
mod narrow;
pub mod reference;
mod sink;
mod stone;
mod symmetry;
mod trace;
mod work;

#[cfg(test)]
pub(crate) mod tests;

pub use crystal::Medium;
pub(crate) use sink::ExitSink;
pub use sink::TraceStats;
pub use stone::Stone;
pub(crate) use symmetry::mirror_matrix;

use crate::geometry::Polyhedron;
use crate::optics::crystal::WaveMode;
use crate::optics::{Material, Stokes};
use glam::{DMat3, DVec2, DVec3};

/// How far the tracer follows light, and what it records.
///
/// Beams with at least `split_threshold` of the incoming power are split exactly. Smaller
/// ones (narrow beams) are followed as one ray each, from their polygon's area centroid, with the
/// same expected-value Fresnel branching: their exit beams carry the narrow beam's footprint
/// and exact power bookkeeping, but the narrow beam is no longer divided where it straddles
/// facet edges. Light below `threshold`, or past `max_depth` internal reflections, is cut off
/// and accounted in [`TraceStats::cut_off`]. Setting `split_threshold <= threshold` gives the
/// purely exact tracer (everything below the threshold is cut off).
///
/// Why not split everything: in a round brilliant a few tenths of a percent of the light stays
/// trapped by total internal reflection for more than 64 bounces, and the exact beam tree of
/// that tail has hundreds of thousands of beams; cut off at 1e-6 it still loses about 0.8 % of
/// the light. Narrow beams keep that tail's power in play at the cost of one ray each.
///
/// What that costs in exactness (measured against [`reference`](mod@reference), `cargo bench --bench exact`,
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
    /// is accounted in [`TraceStats::ray_closed`] (and in [`TraceStats::cut_off`]), for a
    /// caller that integrates over the exits to hand back with the narrow exits' mean: the
    /// scores do (`ScoreConfig::trace`, with the mean of the [`ExitBeam::late`] exits),
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
    /// ([`attenuation`](mod@attenuation)); a narrow beam's ray takes its own path's. The light
    /// absorbed on the way out is [`TraceStats::absorbed`]; beams that are cut off keep the
    /// power they had before absorption in [`TraceStats::cut_off`].
    pub absorption: f64,
    /// Birefringent stones ([`Medium::Uniaxial`]): a narrow beam's ray splits into a ray per
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

/// One beam leaving the stone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExitBeam {
    /// Direction of travel after leaving (unit, stone coordinates).
    pub direction: DVec3,
    /// Share of the total incoming power (the Stokes intensity), after the body colour's
    /// absorption ([`TraceOptions::absorption`]).
    pub power: f64,
    /// The same share without the absorption: the colourless stone's exit power. A trace's
    /// splits and cut-offs follow this power (the light before absorption), so a coloured
    /// trace has the colourless trace's exits, each with both powers; equal to `power` when
    /// nothing absorbs.
    pub unabsorbed: f64,
    /// Stokes vector `(I, Q, U, V)` with `I = power`, in the frame whose reference axis is
    /// [`ExitBeam::axis`].
    pub stokes: Stokes,
    /// Reference axis of [`ExitBeam::stokes`] (unit, ⊥ `direction`).
    pub axis: DVec3,
    /// Facet where the light entered (or was externally reflected).
    pub entry_facet: usize,
    /// Facet the beam leaves through (the entry facet for external reflection).
    pub exit_facet: usize,
    /// Number of internal reflections (0 for external reflection and straight-through light).
    pub reflections: u32,
    /// External reflection at the entry facet (never went inside).
    pub external: bool,
    /// Left a narrow beam that was followed as one ray (see [`TraceOptions`]): its power and
    /// direction are those of the ray through the narrow beam's centre, and its footprint is
    /// the whole narrow beam's, so it is less exact than the others where the narrow beam
    /// would have straddled an edge.
    pub narrow: bool,
    /// From a narrow beam's ray that had already lost at least half of its starting power
    /// before this crossing: the light most like what [`TraceOptions::ray_floor`] stops (its
    /// mean is that light's closure; the narrow exits as a whole leave brighter).
    pub late: bool,
    /// The mode a birefringent stone's light travelled in before it left
    /// ([`WaveMode::Ordinary`] or [`WaveMode::Extraordinary`]); `None` for an external
    /// reflection and for a singly refractive trace.
    pub mode: Option<WaveMode>,
    pub(crate) node: u32,
    /// Index of the symmetry that maps the traced beam to this one (0 = identity).
    pub(crate) sym: u16,
}

/// Everything one trace produced: exit beams, power accounting, footprints.
#[derive(Clone, Debug)]
pub struct BeamTree {
    /// The incoming direction and image axes.
    pub frame: Frame,
    /// Refractive index used (a birefringent stone's ordinary index).
    pub ri: f64,
    /// The medium traced (its indices, optic axis and per-mode absorption).
    pub medium: Medium,
    /// Wavelength in nm (as given; informative when the index was fixed).
    pub wavelength_nm: f64,
    /// Whether polarization was tracked.
    pub polarization: bool,
    /// Power accounting and work done.
    pub stats: TraceStats,
    /// Every exit beam, in tracing order.
    pub exits: Vec<ExitBeam>,
    nodes: Vec<(u32, u32)>,
    perms: Vec<Vec<u32>>,
    footprints: Vec<DVec2>,
    footprint_ranges: Vec<(u32, u32)>,
}

impl BeamTree {
    /// Total power of the exit beams.
    pub fn power_out(&self) -> f64 {
        self.exits.iter().map(|e| e.power).sum()
    }

    /// `power_in − power_out − cut_off − absorbed`: zero to rounding.
    pub fn balance(&self) -> f64 {
        self.stats.power_in - self.power_out() - self.stats.cut_off - self.stats.absorbed
    }

    /// Facet indices the beam met, from the entry facet to the exit facet.
    pub fn sequence(&self, e: &ExitBeam) -> Vec<usize> {
        let mut out = Vec::new();
        let mut k = e.node;
        while k != u32::MAX {
            let (parent, facet) = self.nodes[k as usize];
            out.push(facet as usize);
            k = parent;
        }
        out.reverse();
        if e.sym != 0 {
            if let Some(p) = self.perms.get(e.sym as usize) {
                for f in &mut out {
                    *f = p[*f] as usize;
                }
            }
        }
        out
    }

    /// Footprint of exit beam number `i` (an index into [`BeamTree::exits`]) in the frame's image
    /// coordinates; empty unless traced with [`TraceOptions::footprints`].
    pub fn footprint(&self, i: usize) -> &[DVec2] {
        match self.footprint_ranges.get(i) {
            Some(&(a, b)) => &self.footprints[a as usize..b as usize],
            None => &[],
        }
    }
}

struct Collect {
    exits: Vec<ExitBeam>,
    footprints: Vec<DVec2>,
    ranges: Vec<(u32, u32)>,
    want: bool,
}

impl ExitSink for Collect {
    fn wants_footprints(&self) -> bool {
        self.want
    }
    fn exit(&mut self, beam: &ExitBeam, footprint: &[DVec2]) {
        self.exits.push(*beam);
        if self.want {
            let a = self.footprints.len() as u32;
            self.footprints.extend_from_slice(footprint);
            self.ranges.push((a, self.footprints.len() as u32));
        }
    }
}

impl Stone {
    /// Trace one direction at one refractive index and collect the whole result.
    pub fn trace(
        &self,
        frame: &Frame,
        ri: f64,
        wavelength_nm: f64,
        opts: &TraceOptions,
    ) -> BeamTree {
        self.trace_medium(frame, &Medium::Isotropic(ri), wavelength_nm, opts)
    }

    /// Trace one direction through `medium` (singly refractive, or a birefringent crystal)
    /// and collect the whole result.
    pub fn trace_medium(
        &self,
        frame: &Frame,
        medium: &Medium,
        wavelength_nm: f64,
        opts: &TraceOptions,
    ) -> BeamTree {
        let mut sink = Collect {
            exits: Vec::new(),
            footprints: Vec::new(),
            ranges: Vec::new(),
            want: opts.footprints,
        };
        let (stats, nodes) = self.trace_medium_into(frame, medium, opts, &mut sink, true);
        let perms = (0..self.symmetry_order())
            .map(|i| self.permutation(i).to_vec())
            .collect();
        BeamTree {
            perms,
            frame: *frame,
            ri: medium.ri(),
            medium: *medium,
            wavelength_nm,
            polarization: opts.polarization,
            stats,
            exits: sink.exits,
            nodes,
            footprints: sink.footprints,
            footprint_ranges: sink.ranges,
        }
    }
}

/// Trace `solid` made of `material` at `wavelength_nm` for light arriving as `frame` says.
/// Convenience over [`Stone::new`] + [`Stone::trace`]; prepare a [`Stone`] once when tracing
/// many directions.
pub fn trace(
    solid: &Polyhedron,
    frame: &Frame,
    material: &Material,
    wavelength_nm: f64,
    opts: &TraceOptions,
) -> BeamTree {
    Stone::new(solid).trace(frame, material.ri(wavelength_nm), wavelength_nm, opts)
}
