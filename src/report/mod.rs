//! One-page cut reports: a self-contained HTML page (pictures embedded, no network) per cut or
//! comparing cuts side by side — what a cutter sends a client.
//!
//! For each cut: face-up pictures under COS light with a 15° head shadow ([`BRIGHTNESS_LIGHT`];
//! an even ISO sky shows a good stone nearly uniformly white, while the cosine sky and the
//! viewer's head give the contrast a cutter looks at), in ASET false colour and under the spot
//! lights for fire ([`crate::render`]), the facet diagram ([`crate::plot::diagram`]), the
//! proportions with the grade estimate for round brilliants ([`crate::cut::grade`]), every
//! score with one line on what it means ([`crate::metrics`]), and, when asked, the photon
//! tracer's check of the beam tracer's numbers ([`crate::verify`]) and its tilt performance:
//! the same brightness pictures of the stone tipped by a few angles, and a chart of its light return against
//! the tilt, every cut of the page on one chart ([`ReportOptions::tilts`]).
//!
//! The rooms: `cut_report.rs` measures a cut for a report ([`measure`]: scores, pictures, checks);
//! `page.rs` writes the page ([`html`]); `tilt.rs` its tilt performance (the pictures' row and the
//! chart, an inline SVG); `run.rs` makes an optimizer run's `report.html` from
//! what the run returned ([`run_page`], the [`RunPage`](crate::optimize::RunPage) the binary
//! hands to a run); `plan.rs` a rough plan's page ([`plan_page`]) and the pictures of its run folder
//! ([`PlanDrawings`]); `sheet.rs` the cutting sheet and the cutting mode ([`sheet::sheet_svg`],
//! [`sheet::cutting_mode_html`]). The report sits on top of the library: it may import every floor below it
//! (the optimizer, the plots and everything under them); nothing in the library imports it.

mod cut_report;
mod page;
mod plan;
mod run;
pub mod sheet;
mod tilt;

pub use cut_report::{
    brightness_caption, measure, measure_scored, CutReport, ReportOptions, BRIGHTNESS_LIGHT,
};
pub use page::{base64, escape, html, SCORE_LINES};
pub use plan::{plan_page, PlanDrawings};
pub use run::run_page;
