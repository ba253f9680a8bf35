//! The photon tracer as referee of the beam tracer: the one place where both tracers meet.
//!
//! The tracers know nothing of scores and nothing of each other; this module sits above both
//! (and above [`metrics`](crate::metrics), whose scores it re-measures) and below the
//! optimizer and the command line, which only call it:
//!
//! * [`overhead_light_return_mc`]: directed light straight down over the whole stone, no
//!   absorption, unlimited depth, the scores' wavelength and polarization: the share of photons
//!   that hit the stone and leave upward. The beam tracer's `overhead_light_return` measures
//!   the same thing exactly.
//! * [`brilliance_mc`]: for each pose of
//!   [`ScoreConfig::tilts`](crate::metrics::ScoreConfig::tilts) the stone is turned into the
//!   world, photons come straight down from the viewer's side over the whole stone, and each
//!   photon that leaves in direction `w` scores the environment's radiance from `w`
//!   ([`Lighting::iso`](crate::metrics::lighting::Lighting::iso),
//!   [`Lighting::cos`](crate::metrics::lighting::Lighting::cos), head shadow included). By
//!   reciprocity this is the light the viewer sees, the quantity the beam tracer's brilliance
//!   computes exactly.
//! * [`verify_scores`]: those figures as [`Check`] rows against a cut's beam
//!   [`Scores`](crate::metrics::Scores) (`facetlab score --verify`), flagged beyond [`SIGMA`]
//!   standard errors.
//! * [`photon_report`]: the optimizer's verification of a winner, a [`VerifyReport`]: the
//!   thesis's top-face shares ([`thesis_rows`]: top-45° and top-90° under overhead and
//!   off-centre undirected light, top-45° under the directed light rotated 0–180°), which have
//!   no beam value, and the Monte Carlo overhead light return and brilliance, which carry the
//!   beam value; [`VerifyReport::disagreements`] names the rows beyond a threshold.
//! * [`Verifier`] (in `verifier.rs`): what a check of one cut is, as the optimizer calls it on
//!   its winners (the real one is [`photon_report`] under a config's settings; tests pass
//!   functions), and [`Verification`], its result as a run reports it: the rows, the names
//!   flagged beyond a threshold, the time taken, the verifier's error.
//!
//! Each figure comes with its standard error, so a disagreement can be stated in standard
//! errors. Every call to the photon tracer is in `estimate.rs` (the scores' settings) and
//! `report.rs` (the thesis's).

mod check;
mod estimate;
mod report;
mod verifier;

pub use check::{verify_scores, Check, SIGMA};
pub use estimate::{brilliance_mc, overhead_light_return_mc, BrillianceMc, Estimate};
pub use report::{
    photon_report, photon_report_given, thesis_rows, z_score, VerifyReport, VerifyRow,
};
pub use verifier::{Verification, Verifier};

#[cfg(test)]
mod tests;
