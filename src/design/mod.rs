//! A design as tiers: the tiers of a GemCad design (one line: an angle, indices on the gear,
//! a depth), its meets, and the depth solve that keeps them when tiers turn.
//!
//! A faceter's design is a list of tiers. A tier is one line of a GemCad `.asc` file: one
//! angle to the girdle plane, a set of indices on the index gear (one facet per index) and one
//! depth (the facets' distance from the stone's axis point). [`tiers()`] groups a cut's facets
//! that way, on a [`Gear`] (the design's own, from its [`GemcadRecord`], or another); the
//! `.asc` writer ([`crate::io::asc::write`]) and the cutting instructions
//! ([`crate::io::asc::cutting_instructions`]) print these tiers.
//!
//! A design's **meets** — points where four or more facets pass within a tolerance of one
//! point, what "cut to the meet point" leaves behind — are what must survive when a tier's
//! angle changes ([`meets::find_meets`]). For fixed facet normals every meet is a set of
//! linear equations in the tiers' depths, so the depths for new angles come from one linear
//! least-squares solve ([`meets::solve_depths`]), with the girdle fixing the scale and its
//! thickness; [`reangle::TierModel`] turns tiers, solves, and says how far each meet is from
//! kept. [`DesignSpace`] makes the tier angles of any design the parameters of a
//! [`crate::cut::CutSpace`], so the optimizer, sweeps and `--set` work on a faceter's design
//! as on a family.
//!
//! `design` sits above [`crate::cut`] and below [`crate::io`]: it may import
//! [`crate::geometry`], [`crate::cut`] and [`crate::error`].
//!
//! - `tiers.rs`: [`Gear`], [`Tier`], [`TierFacet`] and [`tiers()`], a cut's facets grouped
//!   into GemCad lines.
//! - `meets.rs`: meets of a solid, the depth solve, a small dense least-squares solver.
//! - `reangle.rs`: tiers turned to new angles with the meets kept (or reported open).
//! - `space.rs`: [`DesignSpace`], a design's tier angles as a cut space; [`with_set`].
//! - `sheet.rs`: a cutting sheet's steps ([`SheetStep`], [`sheet_steps`]): the tiers in cutting
//!   order with their instructions, and the stone as cut so far ([`cut_so_far`]).
//! - `ties.rs`: tied tiers ([`Tie`]: `P1+P2` turned by one change, `C1=C2` set to one angle),
//!   the smallest tie that keeps a refused tier's meets, and the walk of free ranges before a
//!   search ([`Breach`]).
//!
//! [`GemcadRecord`]: crate::cut::GemcadRecord

pub mod meets;
pub mod reangle;
pub mod recipe;
mod sheet;
mod space;
#[cfg(test)]
pub(crate) mod tests;
mod tie_key;
mod tiers;
mod ties;

pub use meets::{find_meets, Meet};
pub use reangle::{TierModel, MEET_TOL};
pub use sheet::{
    cut_so_far, sheet_gear, sheet_record, sheet_steps, step_of_facets, Section, SheetStep, UNCUT,
};
pub use space::{with_set, DesignSpace, OpenMeets, OpenedMeet, CUT_PARAMETER, KEPT};
pub use tie_key::{Breach, Tie, TieKind};
pub use tiers::{fixed, tiers, token, Gear, Tier, TierFacet, ANGLE_DECIMALS, DEPTH_DECIMALS};
