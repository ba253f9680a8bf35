//! Cutting instructions: each tier of a design (one `a` line, with its `G` note) with its angle
//! at 0.01° and its indices on the gear, pavilion first, then crown, as GemCad prints them.

use super::write::{fmt_short, gear_lines, reader_tier};
use crate::cut::Cut;
use serde::Serialize;
use std::fmt::Write as _;

/// One tier of the cutting instructions: one `a` line of the design.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CuttingStep {
    /// Place in the cutting order, from 1.
    pub step: usize,
    /// `pavilion` (girdle and culet included, as GemCad prints them) or `crown`.
    pub side: &'static str,
    /// Tier name.
    pub tier: String,
    /// Angle to the girdle plane in degrees, at 0.01° (girdle 90, table and culet 0).
    pub angle: f64,
    /// The facets' gear indices, as a cutter sets them: whole numbers when on the gear, else
    /// to 0.01 of a tooth.
    pub indices: Vec<String>,
    /// The design's instruction for the line (`G`), if any.
    pub note: Option<String>,
}

impl CuttingStep {
    /// The indices with two digits at least, as GemCad prints them (03-09-15).
    pub fn padded_indices(&self) -> Vec<String> {
        self.indices
            .iter()
            .map(|i| {
                if i.len() == 1 {
                    format!("0{i}")
                } else {
                    i.clone()
                }
            })
            .collect()
    }
}

/// Cutting instructions: the gear, the design's index and the tiers in cutting order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CuttingInstructions {
    /// Gear teeth (negative: clockwise).
    pub gear: f64,
    /// Gear offset (the index at 6 o'clock).
    pub gear_offset: f64,
    /// The design's refractive index, if it names one.
    pub ri: Option<f64>,
    /// Pavilion first, then crown, each in the design's order.
    pub steps: Vec<CuttingStep>,
}

/// The cutting instructions of `cut` on its design's gear (or `gear`, as [`write()`](super::write())): each
/// tier (one line of the `.asc` file) with its angle at 0.01°, its indices on the gear and its
/// instruction, pavilion first (girdle and culet with it), then crown, as GemCad prints them;
/// within a side the design's order (for a generated cut its facet order, the table and the
/// culet last).
///
/// ```
/// let cut = facetlab::io::load_cut("tolkowsky").unwrap();
/// let c = facetlab::io::asc::cutting_instructions(&cut, 0);
/// assert_eq!(c.gear, 96.0);
/// assert_eq!(c.steps[0].side, "pavilion");
/// let bezel = c.steps.iter().find(|s| s.tier == "bezel").unwrap();
/// assert_eq!((bezel.angle, bezel.indices.len()), (34.5, 8));
/// ```
pub fn cutting_instructions(cut: &Cut, gear: u32) -> CuttingInstructions {
    let (record, gear, lines) = gear_lines(cut, gear, crate::cut::record::DIAMOND_RI);
    let mut steps: Vec<CuttingStep> = Vec::new();
    for want in ["pavilion", "crown"] {
        for l in &lines {
            let angle: f64 = l.angle.parse().unwrap_or(0.0);
            let dist: f64 = l.dist.parse().unwrap_or(0.0);
            let pavilion = l.angle.starts_with('-') || (angle == 0.0 && dist < 0.0);
            let side = if pavilion { "pavilion" } else { "crown" };
            if side != want {
                continue;
            }
            let tier = if l.tier.is_empty() {
                reader_tier(&l.angle, &l.dist)
            } else {
                l.tier.clone()
            };
            steps.push(CuttingStep {
                step: steps.len() + 1,
                side,
                tier,
                angle: (angle.abs() * 100.0).round() / 100.0,
                // Off-gear indices at 0.01 of a tooth: what a cutter can set with a cheater.
                indices: l
                    .facets
                    .iter()
                    .map(|(i, _)| match i.parse::<f64>() {
                        Ok(v) if i.contains('.') => fmt_short(v, 1, 2, 1e-9),
                        _ => i.clone(),
                    })
                    .collect(),
                note: l
                    .facets
                    .iter()
                    .find_map(|(_, name)| record.instructions.get(name).cloned()),
            });
        }
    }
    if cut.record.is_none() || cut.family.is_some() {
        // A generated cut (a family's, even with a record for its files) lists its table first; a cutter polishes the table and the culet
        // last on their side.
        let flat = |s: &CuttingStep| s.angle == 0.0;
        steps.sort_by_key(|s| (s.side == "crown", flat(s)));
        for (k, s) in steps.iter_mut().enumerate() {
            s.step = k + 1;
        }
    }
    CuttingInstructions {
        gear: gear.teeth,
        gear_offset: gear.offset,
        ri: record.ri,
        steps,
    }
}

impl CuttingInstructions {
    /// The instructions as a cutter reads them: a header with the gear and index, then one
    /// line per tier: step, tier, angle (0.01°), indices joined by `-` (two digits, as GemCad
    /// prints them), instruction.
    pub fn text(&self) -> String {
        let mut o = String::new();
        let ri = self.ri.map(|n| format!(", index {n}")).unwrap_or_default();
        let _ = writeln!(
            o,
            "Cutting instructions: gear {} (offset {}){ri}; pavilion first, then crown",
            fmt_short(self.gear, 0, 6, 1e-9),
            fmt_short(self.gear_offset, 0, 6, 1e-9)
        );
        let mut side = "";
        for s in &self.steps {
            if s.side != side {
                side = s.side;
                let _ = writeln!(o, "{}", side.to_uppercase());
            }
            let idx = s.padded_indices();
            let note = s
                .note
                .as_deref()
                .map(|n| format!("  {n}"))
                .unwrap_or_default();
            let _ = writeln!(
                o,
                "  {:>3}  {:<14} {:>6.2}°  {}{note}",
                s.step,
                s.tier,
                s.angle,
                idx.join("-")
            );
        }
        o
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::asc::parse;
    use crate::testkit::asc::STAR80;

    #[test]
    fn asc_cutting_instructions_pavilion_first_at_cutters_precision() {
        let cut = parse(STAR80.as_bytes(), "s").unwrap().to_cut("s").unwrap();
        let c = cutting_instructions(&cut, 0);
        assert_eq!((c.gear, c.ri), (80.0, Some(1.61)));
        let order: Vec<(&str, &str, f64)> = c
            .steps
            .iter()
            .map(|s| (s.side, s.tier.as_str(), s.angle))
            .collect();
        assert_eq!(
            order,
            [
                ("pavilion", "P", 41.0),
                ("pavilion", "G", 90.0),
                ("pavilion", "Q", 43.0),
                ("crown", "A", 40.0),
                ("crown", "T", 0.0)
            ]
        );
        assert_eq!(c.steps[2].indices, ["8", "24", "40", "56", "72"]);
        assert_eq!(c.steps[2].note.as_deref(), Some("Meet P, G"));
        let text = c.text();
        assert!(text.contains("gear 80 (offset 0), index 1.61"), "{text}");
        assert!(
            text.contains("  43.00°  08-24-40-56-72  Meet P, G"),
            "{text}"
        );
        assert!(text.find("PAVILION") < text.find("CROWN"), "{text}");
        // A preset: angles at 0.01°, no long decimals anywhere.
        let cut = crate::io::load_cut("marquise").unwrap();
        let c = cutting_instructions(&cut, 0);
        for s in &c.steps {
            assert_eq!(s.angle, (s.angle * 100.0).round() / 100.0);
        }
        assert!(
            c.text().lines().all(|l| !l.contains("00000")),
            "{}",
            c.text()
        );
    }
}
