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
mod exit;
mod footprint;
mod frame;
mod interface;
mod mode;
mod narrow;
mod options;
pub mod reference;
mod sink;
mod stone;
mod symmetry;
mod trace;
mod tree;
mod work;

#[cfg(test)]
pub(crate) mod tests;

pub use crystal::Medium;
pub use exit::ExitBeam;
pub use frame::Frame;
pub use options::TraceOptions;
pub(crate) use sink::ExitSink;
pub use sink::TraceStats;
pub use stone::Stone;
pub(crate) use symmetry::mirror_matrix;
pub use tree::{trace, BeamTree};
