//! A cutting sheet's steps: a design's tiers in the order a faceter cuts them, each with its
//! angle, indices and the instruction that places it ("cut to centre point", "meet G1-P1",
//! "level girdle", "cut to depth 2.10 mm at 6.50 mm"), and the stone as cut so far.
//!
//! The order is a faceter's: the preform (the first pavilion tier that reaches the centre
//! point, cut to it, and the girdle levelled), the rest of the pavilion, the crown, the table
//! last. The instruction is the design's own (a GemCad `G` line) when it has one, else
//! inferred from the solid cut so far ([`cut_so_far`]): a tier whose plane passes through
//! vertices of that solid meets the tiers there; the first tier to reach the axis is cut to the
//! centre point; any other is cut to its depth.
//!
//! The renderer (`crate::report::sheet`) takes any list of [`SheetStep`]s, so a recipe can
//! bring its own.

use crate::cut::{Cut, GemcadRecord};
use crate::error::Result;
use crate::geometry::{DVec3, FacetPlane, Polyhedron};
use serde::Serialize;

use super::tiers::{tiers, Gear, Tier};

/// Where a step sits on the sheet, in cutting order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Section {
    /// The preform (GemCad's CAM PREFORM): the pavilion's centre point and the girdle.
    Preform,
    /// Pavilion tiers (the culet with them).
    Pavilion,
    /// Girdle tiers cut after the preform.
    Girdle,
    /// Crown tiers.
    Crown,
    /// The table, cut last.
    Table,
}

impl Section {
    /// The heading a sheet prints over the section's rows (the table sits under the crown's).
    pub fn heading(self) -> &'static str {
        match self {
            Section::Preform => "PREFORM (CAM)",
            Section::Pavilion => "PAVILION",
            Section::Girdle => "GIRDLE",
            Section::Crown | Section::Table => "CROWN",
        }
    }
}

/// One row of a cutting sheet: one tier, as it is cut.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SheetStep {
    /// The section it is cut in.
    pub section: Section,
    /// Short name as printed on the sheet and the drawings (at most 3 characters).
    pub name: String,
    /// The tier's name on the cut ([`Tier::name`]).
    pub tier: String,
    /// Angle as [`Tier::angle`] has it, GemCad's signs: positive crown, negative pavilion,
    /// −90 girdle, 0 table and culet. A cutter sets its absolute value.
    pub angle: f64,
    /// Depth as [`Tier::depth`] has it: the facets' distance from the origin in widths W
    /// (negative for a culet).
    pub depth: f64,
    /// The facets' indices on the gear, as a cutter sets them (whole numbers on the gear,
    /// else to 0.01 of a tooth).
    pub indices: Vec<String>,
    /// What to cut to.
    pub instruction: String,
}

/// Tolerance (in W) of a plane passing through a vertex, a vertex on the axis, and a vertex
/// on the uncut block.
const TOL: f64 = 1e-6;

/// Half the margin (in W) of the block a partial solid is clipped by, beyond the stone.
const BLOCK_MARGIN: f64 = 0.12;

/// Tier name of the block's faces in [`cut_so_far`]'s solids: the rough not yet cut.
pub const UNCUT: &str = "(uncut)";

/// The gear a sheet lays `cut` on: its design's, else 96 teeth.
pub fn sheet_gear(cut: &Cut) -> Gear {
    let record = cut.record.clone().unwrap_or_default();
    Gear::for_record(&record, 0)
}

fn index_text(i: f64) -> String {
    if (i - i.round()).abs() < 1e-6 {
        format!("{:.0}", i.round())
    } else {
        let t = format!("{i:.2}");
        t.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// A facet's (angle, depth) as [`tiers()`] writes them.
fn facet_key(n: DVec3, offset: f64) -> (f64, f64) {
    let h = n.x.hypot(n.y);
    let tilt = h.atan2(n.z.abs()).to_degrees();
    if h <= 1e-12 && n.z <= 1e-12 {
        (0.0, -offset)
    } else if n.z > 1e-12 {
        (tilt, offset)
    } else {
        (-tilt, offset)
    }
}

/// Which step each of `cut`'s facets belongs to (its angle, depth and gear index are the
/// step's), or `None`.
pub fn step_of_facets(cut: &Cut, steps: &[SheetStep]) -> Vec<Option<usize>> {
    step_of_facets_of(cut, &cut.solid, steps)
}

fn section_of(t: &Tier) -> Section {
    if (t.angle.abs() - 90.0).abs() < 1e-6 {
        Section::Girdle
    } else if t.angle < 0.0 || (t.angle == 0.0 && t.depth < 0.0) {
        Section::Pavilion
    } else if t.angle == 0.0 {
        Section::Table
    } else {
        Section::Crown
    }
}

/// Where `t`'s facets reach the axis when cut first: the one point where its planes cross the
/// axis, `Some(true)` when it is a vertex of the finished stone (the centre point), `Some(false)`
/// when only a flat culet cuts it away (a temporary centre point, GemCad's TCP).
fn axis_point(cut: &Cut, t: &Tier) -> Option<bool> {
    let mut z0: Option<f64> = None;
    let mine = |name: &str| t.facets.iter().any(|tf| tf.name == name);
    for f in cut.solid.facets().iter().filter(|f| mine(&f.name)) {
        let n = f.plane.normal;
        if n.z.abs() < 1e-9 || n.x.hypot(n.y) < 1e-9 {
            return None;
        }
        let z = f.plane.offset / n.z;
        match z0 {
            Some(a) if (a - z).abs() > TOL => return None,
            _ => z0 = Some(z),
        }
    }
    let p = DVec3::new(0.0, 0.0, z0?);
    if cut.solid.vertices().iter().any(|v| v.distance(p) < 1e-5) {
        return Some(true);
    }
    // Inside every other facet but a flat culet: the tier reaches it until the culet is cut.
    let culet = |n: DVec3| n.x.hypot(n.y) < 1e-9 && n.z < 0.0;
    let culet_cuts = cut
        .solid
        .facets()
        .iter()
        .any(|f| culet(f.plane.normal) && f.plane.normal.dot(p) > f.plane.offset + TOL);
    let inside = cut.solid.facets().iter().all(|f| {
        mine(&f.name) || culet(f.plane.normal) || f.plane.normal.dot(p) <= f.plane.offset + TOL
    });
    (culet_cuts && inside).then_some(false)
}

/// The steps of `cut`'s cutting sheet, in cutting order. Instructions are the design's own
/// (its GemCad record's `G` lines) where it has them, else inferred (see the module's
/// notes); a depth is given in mm for a stone `size_mm` wide, else in widths W.
///
/// ```
/// use facetlab::design::{sheet_steps, Section};
///
/// let cut = facetlab::io::load_cut("tolkowsky").unwrap();
/// let steps = sheet_steps(&cut, Some(6.5));
/// assert_eq!(steps[0].section, Section::Preform);
/// assert_eq!(steps[0].instruction, "cut to centre point");
/// assert_eq!(steps.last().unwrap().section, Section::Table);
/// ```
pub fn sheet_steps(cut: &Cut, size_mm: Option<f64>) -> Vec<SheetStep> {
    let gear = sheet_gear(cut);
    let all = tiers(cut, gear, 1.0);
    // Cutting order: the first pavilion tier through the centre point, the girdle, the rest
    // of the pavilion (the culet last), the crown, the table.
    let centre = all.iter().position(|t| {
        section_of(t) == Section::Pavilion && t.angle != 0.0 && axis_point(cut, t).is_some()
    });
    let mut order: Vec<(Section, usize)> = Vec::new();
    if let Some(c) = centre {
        order.push((Section::Preform, c));
    }
    for (i, t) in all.iter().enumerate() {
        if section_of(t) == Section::Girdle {
            order.push((Section::Preform, i));
        }
    }
    let mut rest: Vec<(Section, usize)> = all
        .iter()
        .enumerate()
        .filter(|(i, t)| Some(*i) != centre && section_of(t) != Section::Girdle)
        .map(|(i, t)| (section_of(t), i))
        .collect();
    // Stable: the design's order within a section, a culet after the pavilion's tiers.
    rest.sort_by_key(|&(s, i)| (s, all[i].angle == 0.0));
    order.extend(rest);

    let names = short_names(&all, &order);
    let record = cut.record.as_ref();
    let mut steps: Vec<SheetStep> = Vec::new();
    for (k, &(section, i)) in order.iter().enumerate() {
        let t = &all[i];
        let noted = record.and_then(|r| {
            t.facets
                .iter()
                .find_map(|f| r.instructions.get(&f.name).cloned())
        });
        let mut step = SheetStep {
            section,
            name: names[k].clone(),
            tier: t.name.clone(),
            angle: t.angle,
            depth: t.depth,
            indices: {
                let mut i: Vec<f64> = t.facets.iter().map(|f| f.index).collect();
                i.sort_by(f64::total_cmp);
                i.into_iter().map(index_text).collect()
            },
            instruction: String::new(),
        };
        step.instruction = match noted {
            Some(n) if !n.trim().is_empty() => n.trim().to_string(),
            _ => infer(cut, &steps, &step, t, size_mm),
        };
        steps.push(step);
    }
    steps
}

/// Short names: the design's own when at most 3 characters and not yet used, else `P1`,
/// `G1`, `C1` … by section, `T` for a table, `Cu` for a culet.
fn short_names(all: &[Tier], order: &[(Section, usize)]) -> Vec<String> {
    let own: Vec<&str> = all.iter().map(|t| t.name.as_str()).collect();
    let mut used: Vec<String> = Vec::new();
    let mut counters = [0usize; 3];
    for &(_, i) in order {
        let t = &all[i];
        let name = t.name.as_str();
        if !name.is_empty() && name.chars().count() <= 3 && !used.iter().any(|u| u == name) {
            used.push(name.to_string());
            continue;
        }
        let s = section_of(t);
        let (prefix, c) = match s {
            Section::Girdle => ("G", 0),
            Section::Pavilion if t.angle == 0.0 => ("Cu", 9),
            Section::Pavilion | Section::Preform => ("P", 1),
            Section::Table => ("T", 9),
            Section::Crown => ("C", 2),
        };
        let mut made;
        let mut n = 0;
        loop {
            made = if c == 9 && n == 0 {
                prefix.to_string()
            } else if c == 9 {
                format!("{prefix}{n}")
            } else {
                counters[c] += 1;
                format!("{prefix}{}", counters[c])
            };
            n += 1;
            if !used.contains(&made) && !own.contains(&made.as_str()) {
                break;
            }
        }
        used.push(made);
    }
    used
}

/// The instruction of `step` (tier `t`) after `done`, inferred from the solid cut so far.
fn infer(
    cut: &Cut,
    done: &[SheetStep],
    step: &SheetStep,
    t: &Tier,
    size_mm: Option<f64>,
) -> String {
    if (step.angle.abs() - 90.0).abs() < 1e-6 {
        return "level girdle".to_string();
    }
    if let Ok(solid) = cut_so_far(cut, done) {
        let planes: Vec<(DVec3, f64)> = cut
            .solid
            .facets()
            .iter()
            .filter(|f| t.facets.iter().any(|tf| tf.name == f.name))
            .map(|f| (f.plane.normal, f.plane.offset))
            .collect();
        let owners = step_of_facets_of(cut, &solid, done);
        for (n, d) in planes {
            let mut labels: Vec<String> = Vec::new();
            for (vi, v) in solid.vertices().iter().enumerate() {
                if (n.dot(*v) - d).abs() > TOL {
                    continue;
                }
                let mut tiers_here: Vec<usize> = Vec::new();
                let mut on_block = false;
                for (fi, f) in solid.facets().iter().enumerate() {
                    if !f.vertices.contains(&vi) {
                        continue;
                    }
                    match owners[fi] {
                        Some(s) if !tiers_here.contains(&s) => tiers_here.push(s),
                        Some(_) => {}
                        None => on_block = true,
                    }
                }
                if on_block || tiers_here.is_empty() {
                    continue;
                }
                tiers_here.sort_unstable();
                let mut label = tiers_here
                    .iter()
                    .map(|&s| done[s].name.as_str())
                    .collect::<Vec<_>>()
                    .join("-");
                if v.x.hypot(v.y) < 1e-5 {
                    label.push_str(" at centre point");
                }
                if !labels.contains(&label) {
                    labels.push(label);
                }
            }
            if !labels.is_empty() {
                labels.truncate(2);
                return format!("meet {}", labels.join(", "));
            }
        }
    }
    match axis_point(cut, t) {
        Some(true) if step.angle != 0.0 => return "cut to centre point".to_string(),
        Some(false) if step.angle != 0.0 => {
            return "cut to temporary centre point (TCP)".to_string()
        }
        _ => {}
    }
    let d = step.depth.abs();
    match size_mm {
        Some(s) => format!("cut to depth {:.2} mm at {} mm", d * s, trim_mm(s)),
        None => format!("cut to depth {d:.4} W"),
    }
}

fn trim_mm(s: f64) -> String {
    let t = format!("{s:.2}");
    t.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// For each facet of a partial solid from [`cut_so_far`], the step it belongs to (`None`:
/// the block).
fn step_of_facets_of(cut: &Cut, solid: &Polyhedron, steps: &[SheetStep]) -> Vec<Option<usize>> {
    let gear = sheet_gear(cut);
    solid
        .facets()
        .iter()
        .map(|f| {
            if f.tier == UNCUT {
                return None;
            }
            let (a, d) = facet_key(f.plane.normal, f.plane.offset);
            let idx = index_text(gear.index(f.plane.normal));
            steps.iter().position(|s| {
                (s.angle - a).abs() < 1e-6
                    && (s.depth - d).abs() < 1e-6 * (1.0 + d.abs())
                    && s.indices.contains(&idx)
            })
        })
        .collect()
}

/// The stone after the tiers of `done` are cut: their facets' planes clipped by a block a
/// little larger than the finished stone (its faces' tier is [`UNCUT`]). With no steps, the
/// block.
pub fn cut_so_far(cut: &Cut, done: &[SheetStep]) -> Result<Polyhedron> {
    let owner = step_of_facets(cut, done);
    let planes: Vec<FacetPlane> = cut
        .solid
        .facets()
        .iter()
        .zip(&owner)
        .filter(|(_, o)| o.is_some())
        .map(|(f, _)| FacetPlane {
            plane: f.plane,
            name: f.name.clone(),
            tier: f.tier.clone(),
        })
        .collect();
    let (lo, hi) = cut.solid.bounding_box();
    let m = BLOCK_MARGIN * (hi - lo).max_element().max(1e-9);
    let sides = [
        (DVec3::X, hi.x + m, "+x"),
        (DVec3::NEG_X, -(lo.x - m), "-x"),
        (DVec3::Y, hi.y + m, "+y"),
        (DVec3::NEG_Y, -(lo.y - m), "-y"),
        (DVec3::Z, hi.z + m, "+z"),
        (DVec3::NEG_Z, -(lo.z - m), "-z"),
    ];
    let mut block: Vec<FacetPlane> = sides
        .iter()
        .map(|(n, d, s)| FacetPlane::new(*n, *d, format!("{UNCUT} {s}"), UNCUT))
        .collect();
    // Block faces the cut tiers remove entirely are dropped, one at a time (a solid must not
    // have a plane that never touches it).
    loop {
        let all: Vec<FacetPlane> = planes
            .iter()
            .cloned()
            .chain(block.iter().cloned())
            .collect();
        match Polyhedron::from_planes(&all) {
            Ok(p) => return Ok(p),
            Err(e) => {
                // The error names the first plane that does not touch; a block face is dropped
                // and the solid built again (at most six times), any other error is the cut's.
                let text = e.to_string();
                let Some(k) = block.iter().position(|b| text.contains(&b.name)) else {
                    return Err(e);
                };
                block.remove(k);
            }
        }
    }
}

/// The record a sheet's header reads: the design's own, else a generated cut's for index `ri`.
pub fn sheet_record(cut: &Cut, ri: f64) -> GemcadRecord {
    GemcadRecord::for_file(cut, 0, ri)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small brilliant with the designer's instructions on three of its lines.
    const MINI: &str = "GemCad 5.0
g 96 0.0
y 8 y
I 1.54
H Mini
H by a tester
a -90.000000 1.000000 3 n G 9 15 21 27 33 39 45 51 57 63 69 75 81 87 93
a -41.000000 0.691553 96 n P 12 24 36 48 60 72 84 G Cut to TCP
a 0.000000 -0.900000 96 n K G Small culet
a 34.000000 0.595019 96 n B 12 24 36 48 60 72 84 G Leave some girdle
a 0.000000 0.332598 96 n T
";

    fn rank(s: Section) -> u8 {
        s as u8
    }

    #[test]
    fn a_round_is_cut_preform_pavilion_crown_table_with_inferred_instructions() {
        let cut = crate::io::load_cut("tolkowsky").unwrap();
        let steps = sheet_steps(&cut, Some(6.5));
        let got: Vec<(Section, &str, usize, &str)> = steps
            .iter()
            .map(|s| {
                (
                    s.section,
                    s.tier.as_str(),
                    s.indices.len(),
                    s.instruction.as_str(),
                )
            })
            .collect();
        assert_eq!(
            got[..3],
            [
                (Section::Preform, "pavilion-main", 8, "cut to centre point"),
                (Section::Preform, "girdle", 16, "level girdle"),
                (Section::Pavilion, "lower-half", 16, "meet P1-G1"),
            ],
            "{steps:#?}"
        );
        assert_eq!(steps.last().unwrap().section, Section::Table);
        assert!(steps
            .windows(2)
            .all(|w| rank(w[0].section) <= rank(w[1].section)));
        // Every facet is on exactly one step, and the names are short and distinct.
        let owner = step_of_facets(&cut, &steps);
        assert!(owner.iter().all(Option::is_some));
        let total: usize = steps.iter().map(|s| s.indices.len()).sum();
        assert_eq!(total, cut.solid.facets().len());
        for (k, s) in steps.iter().enumerate() {
            assert!(s.name.chars().count() <= 3, "{}", s.name);
            assert!(steps[..k].iter().all(|t| t.name != s.name));
        }
        // The bezel: 34.5° as the preset says, its depth in mm at 6.5 mm.
        let bezel = steps.iter().find(|s| s.tier == "bezel").unwrap();
        assert!((bezel.angle - 34.5).abs() < 1e-9);
        assert_eq!(
            bezel.instruction,
            format!("cut to depth {:.2} mm at 6.5 mm", bezel.depth * 6.5)
        );
        // Without a size, in W.
        let w = sheet_steps(&cut, None);
        assert!(w[3].instruction.ends_with(" W"), "{}", w[3].instruction);
        // Indices ascending, as a cutter reads them.
        assert_eq!(
            steps[0].indices,
            ["12", "24", "36", "48", "60", "72", "84", "96"]
        );
    }

    #[test]
    fn a_designs_own_instructions_and_names_are_kept() {
        let cut = crate::io::asc::parse(MINI.as_bytes(), "mini")
            .unwrap()
            .to_cut("mini")
            .unwrap();
        let steps = sheet_steps(&cut, None);
        let got: Vec<(&str, Section, &str)> = steps
            .iter()
            .map(|s| (s.name.as_str(), s.section, s.instruction.as_str()))
            .collect();
        assert_eq!(
            got,
            [
                ("P", Section::Preform, "Cut to TCP"),
                ("G", Section::Preform, "level girdle"),
                ("K", Section::Pavilion, "Small culet"),
                ("B", Section::Crown, "Leave some girdle"),
                ("T", Section::Table, "cut to depth 0.1631 W"),
            ]
        );
    }

    #[test]
    fn the_stone_cut_so_far_grows_tier_by_tier_to_the_finished_stone() {
        for name in ["tolkowsky", "emerald", "princess", "oval"] {
            let cut = crate::io::load_cut(name).unwrap();
            let steps = sheet_steps(&cut, None);
            let mut last = 0;
            let mut volume = f64::INFINITY;
            for k in 0..=steps.len() {
                let solid = cut_so_far(&cut, &steps[..k]).unwrap();
                let real = solid.facets().iter().filter(|f| f.tier != UNCUT).count();
                assert!(
                    k == 0 || real > last,
                    "{name} step {k}: {real} facets after {last}"
                );
                assert!(solid.volume() <= volume + 1e-12, "{name} step {k}");
                (last, volume) = (real, solid.volume());
            }
            assert_eq!(last, cut.solid.facets().len(), "{name}");
            assert!((volume - cut.solid.volume()).abs() < 1e-9, "{name}");
        }
    }
}
