//! [`ExitBeam`]: one beam leaving the stone.

use crate::optics::crystal::WaveMode;
use crate::optics::Stokes;
use glam::DVec3;

/// One beam leaving the stone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExitBeam {
    /// Direction of travel after leaving (unit, stone coordinates).
    pub direction: DVec3,
    /// Share of the total incoming power (the Stokes intensity), after the body colour's
    /// absorption ([`TraceOptions::absorption`](super::TraceOptions::absorption)).
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
    /// Left a narrow beam that was followed as one ray (see [`TraceOptions`](super::TraceOptions)): its power and
    /// direction are those of the ray through the narrow beam's centre, and its footprint is
    /// the whole narrow beam's, so it is less exact than the others where the narrow beam
    /// would have straddled an edge.
    pub narrow: bool,
    /// From a narrow beam's ray that had already lost at least half of its starting power
    /// before this crossing: the light most like what [`TraceOptions::ray_floor`](super::TraceOptions::ray_floor) stops (its
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
