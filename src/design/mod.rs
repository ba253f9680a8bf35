//! A design as tiers: the tiers of a GemCad design (one line: an angle, indices on the gear,
//! a depth), and next the meets and the depth solve.
//!
//! A faceter's design is a list of tiers. A tier is one line of a GemCad `.asc` file: one
//! angle to the girdle plane, a set of indices on the index gear (one facet per index) and one
//! depth (the facets' distance from the stone's axis point). [`tiers()`] groups a cut's facets
//! that way, on a [`Gear`] (the design's own, from its [`GemcadRecord`], or another); the
//! `.asc` writer ([`crate::io::asc::write`]) and the cutting instructions
//! ([`crate::io::asc::cutting_instructions`]) print these tiers.
//!
//! What lands here next, to make any design a parametric one: the design's meets (vertices
//! where four or more facets meet, within a tolerance of W), the depth solve (for new tier
//! angles, the depths that keep the meets: a linear solve, least squares where
//! over-determined, with the width W = 1 fixing the scale), and re-angling a tier.
//!
//! `design` sits above [`crate::cut`] and below [`crate::io`]: it may import
//! [`crate::geometry`], [`crate::cut`] and [`crate::error`].
//!
//! - `tiers.rs`: [`Gear`], [`Tier`], [`TierFacet`] and [`tiers()`], a cut's facets grouped
//!   into GemCad lines.
//!
//! [`GemcadRecord`]: crate::cut::GemcadRecord

mod tiers;

pub use tiers::{fixed, tiers, token, Gear, Tier, TierFacet, ANGLE_DECIMALS, DEPTH_DECIMALS};
