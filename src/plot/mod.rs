//! Charts and pictures with plotters. Every figure is a [`Figure`]: drawn by one function generic
//! over the backend and written by [`save`] as `STEM.png` and `STEM.svg` (each written to a
//! temporary file and renamed, so a failure leaves no half-written picture). Text uses the
//! bundled DejaVu Sans; colours come from one palette ([`palette`]: [`TAB10`], and the grounds
//! of stone pictures); legends from [`legend`].
//!
//! The plot floor sits over the optimizer and the planner: it draws from what they return
//! (and from everything below them), and nothing under it calls it; the report and the binary
//! above it do. The rooms:
//!
//! * [`trace`]: the photon tracer's charts — [`face_categories`] (the thesis's bar chart of
//!   exit-face categories, one bar per cut), [`exit_angle_cdf`] (cumulative exit-angle curves,
//!   one per cut) and [`rotation`] (share through faces < 45° and light return vs the light's
//!   angle);
//! * [`paths`]: pictures of the stone — [`photon_paths`] (recorded photon paths seen by an
//!   orthographic [`Camera`], coloured by bounce count or wavelength, with low alpha, the first
//!   segment on or off) and [`facet_categories`] (facets coloured by normal category);
//! * [`optimize`]: the optimizer's charts — [`optimize::convergence`] (a run's cost against
//!   evaluations) and [`optimize::heatmap`] (a sweep's score map with [`contour`] lines and the
//!   optimizer's path). The optimizer draws no charts itself: the binary hands these
//!   functions to a run and a sweep;
//! * [`render`]: sheets of stone pictures — [`render::compose`] puts already-encoded pictures
//!   side by side on a grey ground with their captions and a false-colour legend
//!   ([`render::legend_for`]);
//! * [`diagram`]: a cutter's facet diagram of a cut, as a GemCad-style SVG page
//!   ([`diagram::diagram`]);
//! * [`pareto`]: the trade-off front between two scores, with the reference cuts;
//! * [`plan`]: a rough planned (`facetlab plan`): three views of the rough with the cuts inside
//!   ([`plan::ThreeViews`]);
//! * [`palette`]: every colour handed out here, the grounds of stone pictures included;
//! * [`text`]: text set with its bearings, kerning and baseline ([`text::TextBackend`] wraps
//!   every backend this floor draws on).

pub mod contour;
pub mod diagram;
mod figure;
mod legends;
pub mod optimize;
pub mod palette;
pub mod pareto;
pub mod paths;
pub mod plan;
pub mod render;
pub mod text;
pub mod trace;

pub(crate) use figure::FONT;
pub use figure::{font, font_bytes, register_font, save, save_to, with_ext, DrawResult, Figure};
pub use legends::{box_key, every_30, legend, line_key, LegendStyle};
pub use palette::{SERIES, TAB10};
pub use paths::{
    facet_categories, photon_paths, wavelength_rgb, Camera, PathColor, PathStyle, CATEGORY_COLORS,
};
pub use trace::{exit_angle_cdf, face_categories, rotation};

#[cfg(test)]
mod tests;
