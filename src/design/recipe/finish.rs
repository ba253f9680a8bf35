//! A carved recipe made a cut: the open sides refused, the solid scaled to width 1, its
//! steps and instructions, the findings, and a sheet's steps.

use super::build::{facet_name, shown, Built, Carved, Finding, FindingKind, Resolved, Step};
use super::{Place, Recipe, RecipeTier, Side, SMALL_FACET};
use crate::cut::{Cut, GemcadRecord};
use crate::error::{Error, Result};
use crate::geometry::{outline_size, FacetPlane, Polyhedron};
use std::collections::BTreeMap;

impl Recipe {
    pub(super) fn finish(&self, c: Carved) -> Result<Built> {
        let mut open = c.block.open();
        // A stone open at the side is told so first (it is open above or below too).
        open.sort_by(|a, b| a.z.abs().total_cmp(&b.z.abs()));
        if let Some(n) = open.first() {
            let msg = if n.z > 0.5 {
                "the stone is open above: no tier closes the crown (add a table, or cut a crown tier to the centre point)"
            } else if n.z < -0.5 {
                "the stone is open below: no tier closes the pavilion (cut a pavilion tier to the centre point, or add a culet)"
            } else {
                "the stone is open at the side: the tiers do not close the outline (a girdle or tier whose indices do not go all around?)"
            };
            return Err(Error::invalid("design", msg));
        }
        let mut planes = Vec::new();
        let mut steps = Vec::new();
        let mut k = 0;
        for (i, r) in c.resolved.iter().enumerate() {
            let n = r.normals.len();
            let mut facets = Vec::new();
            for j in 0..n {
                let f = facet_name(&self.tiers[i].name, j, n);
                planes.push(FacetPlane {
                    plane: c.planes[k],
                    name: f.clone(),
                    tier: self.tiers[i].name.clone(),
                });
                facets.push(f);
                k += 1;
            }
            steps.push((i, facets));
        }
        let solid = Polyhedron::from_planes(&planes).map_err(|e| e.context("design"))?;
        let w = outline_size(solid.vertices()).1;
        if !(w.is_finite() && w > 1e-12) {
            return Err(Error::invalid("design", "the stone has no width"));
        }
        let solid = solid.scaled(1.0 / w);
        let steps: Vec<Step> = steps
            .into_iter()
            .map(|(i, facets)| {
                let r = &c.resolved[i];
                let depth = c.depths[i] / w;
                Step {
                    tier: self.tiers[i].name.clone(),
                    angle: r.signed(),
                    indices: r.indices.clone(),
                    depth,
                    instruction: instruction(&self.tiers[i], r, depth),
                    facets,
                }
            })
            .collect();
        let findings = self.findings(&solid, &c);
        let record = GemcadRecord {
            ri: Some(self.index),
            title: std::iter::once(self.name.clone())
                .chain(self.title.iter().cloned())
                .filter(|t| !t.is_empty())
                .collect(),
            footnotes: self.notes.clone(),
            gear: f64::from(self.gear),
            gear_offset: self.offset,
            symmetry: self.symmetry,
            mirror: self.mirror,
            instructions: steps
                .iter()
                .filter_map(|s| Some((s.facets.first()?.clone(), s.instruction.clone())))
                .collect(),
            scale: w,
        };
        Ok(Built {
            cut: Cut {
                name: self.name.clone(),
                family: None,
                params: BTreeMap::new(),
                solid,
                record: Some(record),
            },
            steps,
            findings,
        })
    }

    fn findings(&self, solid: &Polyhedron, c: &Carved) -> Vec<Finding> {
        let mut out = Vec::new();
        for (i, t) in self.tiers.iter().enumerate() {
            let mut smallest: Option<(f64, &str)> = None;
            for (fi, f) in solid.facets().iter().enumerate() {
                if f.tier != t.name {
                    continue;
                }
                let poly = solid.facet_polygon(fi);
                let mut dia: f64 = 0.0;
                for a in &poly {
                    for b in &poly {
                        dia = dia.max(a.distance(*b));
                    }
                }
                if dia < SMALL_FACET && smallest.is_none_or(|(s, _)| dia < s) {
                    smallest = Some((dia, &f.name));
                }
            }
            if let Some((dia, f)) = smallest {
                out.push(Finding {
                    tier: t.name.clone(),
                    kind: FindingKind::SmallFacet,
                    message: format!(
                        "tier {}: facet {f} is {:.2} % of the width, under the {:.0} % a faceter can cut and see",
                        t.name,
                        dia * 100.0,
                        SMALL_FACET * 100.0
                    ),
                });
            }
            let r = &c.resolved[i];
            let critical = (1.0 / self.index).asin().to_degrees();
            if r.side == Some(Side::Pavilion) && r.tilt > 0.0 && r.tilt < critical {
                let fix = (critical * 10.0).floor() / 10.0 + 0.1;
                out.push(Finding {
                    tier: t.name.clone(),
                    kind: FindingKind::BelowCritical,
                    message: format!(
                        "tier {}: {:.2}° is below the critical angle {critical:.2}° for RI {}: light from the table leaks through it; steepen {} to {fix:.1}° or more",
                        t.name, r.tilt, self.index, t.name
                    ),
                });
            }
        }
        out
    }
}

/// The instruction a cutter reads for tier `t` (`depth` in widths).
fn instruction(t: &RecipeTier, r: &Resolved, depth: f64) -> String {
    let girdle = r.side.is_none();
    let what = match &t.place {
        Place::Centre => "cut to centre point".to_string(),
        Place::Meet(m) => format!("meet {}", m.join("-")),
        Place::Depth(_) if girdle => "level girdle".to_string(),
        Place::Depth(_) => format!("cut to depth {:.4} W", depth),
        Place::Scale(_) if girdle => "level girdle (sets the size)".to_string(),
        Place::Scale(_) => format!("cut to depth {:.4} W (sets the size)", depth),
        Place::Girdle(th) => format!("leave a girdle of {:.2} % of the width", th * 100.0),
        Place::Table(w) => format!("cut the table to {:.2} % of the width", w * 100.0),
    };
    match &t.note {
        Some(n) if !n.trim().is_empty() => format!("{what}; {}", n.trim()),
        _ => what,
    }
}

impl Built {
    /// The cutting sheet's steps of the built recipe: the recipe's own order and
    /// instructions (a depth in mm at a width of `size_mm` when given), with the sheet's
    /// sections, short names and indices ([`crate::design::sheet_steps`]).
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cuts/recipes/brilliant.toml");
    /// let text = std::fs::read_to_string(path).unwrap();
    /// let built = facetlab::io::recipe::parse(&text, path, "b").unwrap().build().unwrap();
    /// let steps = built.sheet_steps(Some(6.5));
    /// let names: Vec<&str> = steps.iter().map(|s| s.tier.as_str()).collect();
    /// assert_eq!(names, ["P1", "G1", "P2", "C1", "C2", "C3", "T"]);
    /// assert_eq!(steps[2].instruction, "meet P1-G1");
    /// ```
    pub fn sheet_steps(&self, size_mm: Option<f64>) -> Vec<crate::design::SheetStep> {
        let mut sheet = crate::design::sheet_steps(&self.cut, size_mm);
        let mut out = Vec::new();
        for s in &self.steps {
            let Some(k) = sheet.iter().position(|t| t.tier == s.tier) else {
                continue;
            };
            let mut step = sheet.remove(k);
            step.instruction = match (s.instruction.starts_with("cut to depth"), size_mm) {
                (true, Some(mm)) => {
                    format!("cut to depth {:.2} mm at {} mm", s.depth * mm, shown(mm))
                }
                _ => s.instruction.clone(),
            };
            out.push(step);
        }
        // Tiers the sheet groups apart (none for a recipe's own tiers) keep their place.
        out.extend(sheet);
        // Sections in the recipe's order: the preform (CAM) is the tiers up to the first
        // girdle tier when they are cut to the centre point or are the girdle; then each
        // tier's side.
        use crate::design::Section;
        let preform = self
            .steps
            .iter()
            .position(|s| s.angle.abs() == 90.0)
            .filter(|&g| {
                self.steps[..g]
                    .iter()
                    .all(|s| s.instruction.starts_with("cut to centre point"))
            });
        for (k, step) in out.iter_mut().enumerate() {
            let a = step.angle;
            step.section = if preform.is_some_and(|g| k <= g) {
                Section::Preform
            } else if a.abs() == 90.0 {
                Section::Girdle
            } else if a < 0.0 || (a == 0.0 && step.depth < 0.0) {
                Section::Pavilion
            } else if a == 0.0 {
                Section::Table
            } else {
                Section::Crown
            };
        }
        out
    }
}
