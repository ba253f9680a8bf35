//! Cuts: parametric families (round brilliant, princess, …) and the [`Cut`] type, a named convex
//! polyhedron that remembers the family and parameters it came from.
//!
//! Every family declares its parameters ([`ParamDef`]: key, default, allowed range, unit). The
//! same keys are used in TOML specs, in `--set key=value`, by `info` and by the optimizer.
//! Lengths are fractions of the girdle diameter (0.57, not 57), angles are degrees.

mod construct;
mod cushion;
mod emerald;
mod families;
pub mod grade;
mod marquise;
mod measure;
mod named;
mod old_european;
mod outline;
mod oval;
mod param;
mod pear;
pub mod plausible;
mod princess;
pub mod record;
pub mod retarget;
mod round;
pub mod space;
mod sphere;
mod steps;
pub mod units;

pub use families::{families, family, Family};
pub use measure::{Proportions, Ratios, TierSummary};
pub use named::Cut;
pub use param::{ParamDef, Params, Unit};
pub use record::GemcadRecord;
pub use space::{CutSpace, ParamRange};

#[cfg(test)]
mod tests;
