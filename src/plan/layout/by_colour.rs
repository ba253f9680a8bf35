//! A layout of a coloured rough ranked by value × colour (`[objective] kind = "colour"` with
//! `stones` above 1, issue 54).
//!
//! Each stone is worth its price-table value (`prices` given; with the `included` factor
//! when it holds an inclusion) or else its carats, times its colour factor: its face-up
//! chroma C*ab (scored as a single plan's colour is, at its own width and optic axis, at the
//! fast score settings: [`crate::plan::colour::face_up_colour`]) over the material's
//! reference chroma ([`crate::plan::colour::reference_chroma`], the most a plain slab of it
//! shows). The factor falls both ways from the best, as C* does: a small or pale stone
//! shows little colour, and a large or "closed" one darkens towards black.
//!
//! The fast path, as for single plans (scoring colour inside the saw search would cost a
//! face-up trace per candidate stone, thousands of them): the layout is planned by value
//! (a table given) or by weight as [`LayoutPlanner::plan`] plans it, saw plan (or laser
//! cells) and all; then in each of its final pieces the candidate stones, the layout's own
//! stone and each family's best `top` plans of a full search in that piece, are scored in
//! colour and the one worth most × colour kept. The pieces stay as they were, so the stones
//! stay apart and off the inclusions, and the layout's total worth × colour is never below
//! the value (or weight) layout's own stones scored by the same measure. What it is not: a
//! saw plan searched for colour (the pieces are cut for value or weight).

use super::{ColourWorth, Layout, LayoutPlanner, Piece, Stone};
use crate::error::{Error, Result};
use crate::plan::colour::{colour_factor, face_up_colour, reference_chroma};
use crate::plan::config::{Objective, PriceTable};
use crate::render::ColourStats;
use rayon::prelude::*;

/// The least reference chroma a material may have to rank a layout by colour: below it a
/// slab of the material is grey at every thickness.
pub const MIN_REFERENCE_CHROMA: f64 = 1.0;

impl LayoutPlanner<'_> {
    /// The layout ranked by worth × colour (see the module documentation), worth by
    /// `prices` when given.
    pub(super) fn coloured(
        &self,
        prices: Option<&PriceTable>,
        tick: &(dyn Fn() + Sync),
    ) -> Result<Layout> {
        let refused = |why: String| Error::invalid("objective.kind", why);
        let Some(material) = self.material else {
            return Err(refused(
                "kind = \"colour\" ranks a layout by the material's colour; none was given".into(),
            ));
        };
        let reference = reference_chroma(material).unwrap_or(0.0);
        if reference < MIN_REFERENCE_CHROMA {
            return Err(refused(format!(
                "kind = \"colour\" needs a coloured material; {} shows chroma C* {reference:.2} at most through any thickness (allowed: at least {MIN_REFERENCE_CHROMA}; or kind = \"weight\" or \"value\")",
                material.name
            )));
        }
        let mut cfg = self.config.clone();
        cfg.objective = prices.map_or(Objective::Weight, |t| Objective::Value(t.clone()));
        let base = LayoutPlanner {
            config: &cfg,
            ..*self
        };
        let planned = base.plan(tick)?;
        // Each piece's candidates: its stone first, then each family's best few.
        let candidates: Vec<Vec<Stone>> = planned
            .stones
            .par_iter()
            .map(|s| {
                let piece = Piece {
                    label: s.piece.clone(),
                    solid: s.piece_solid.clone(),
                };
                let mut all = vec![s.clone()];
                all.extend(base.candidates(&piece, super::Effort::Full, cfg.top));
                all
            })
            .collect();
        if self.stopped() {
            return Err(Error::invalid("plan", "interrupted"));
        }
        // Every candidate's face-up colour, in parallel, gathered in order.
        let flat: Vec<(usize, &Stone)> = candidates
            .iter()
            .enumerate()
            .flat_map(|(k, c)| c.iter().map(move |s| (k, s)))
            .collect();
        let colours: Vec<Option<ColourStats>> = flat
            .par_iter()
            .map(|(_, s)| face_up_colour(&s.plan, material, self.config.c_axis))
            .collect();
        let mut best: Vec<Option<Stone>> = vec![None; candidates.len()];
        for ((k, s), c) in flat.into_iter().zip(colours) {
            let mut s = s.clone();
            let worth = s.plan.objective;
            // No colour (the stone could not be traced): no worth, but the piece keeps a stone.
            let factor = c.as_ref().map_or(0.0, |c| colour_factor(c, reference));
            s.plan.objective = worth * factor;
            s.plan.colour = c;
            s.colour = Some(ColourWorth { worth, factor });
            // Ties keep the earlier candidate (the value layout's own stone first).
            if best[k]
                .as_ref()
                .is_none_or(|b| s.plan.objective > b.plan.objective)
            {
                best[k] = Some(s);
            }
        }
        let stones: Vec<Stone> = best.into_iter().flatten().collect();
        let volume: f64 = stones.iter().map(|s| s.plan.volume_mm3).sum();
        Ok(Layout {
            total: stones.iter().map(|s| s.plan.objective).sum(),
            carats: stones.iter().map(|s| s.plan.carats).sum(),
            yield_fraction: volume / self.rough.volume(),
            colour_reference: Some(reference),
            stones,
            ..planned
        })
    }
}
