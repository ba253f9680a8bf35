//! A recipe for any design (`facetlab design --from DESIGN`): the tiers in a cutting order a
//! faceter would follow (pavilion and girdle, crown, table last), each placed as a faceter
//! would place it — to the centre point, to meet the vertex it passes through (found, as
//! indicatrix finds it, from the tiers through that vertex), leaving a girdle, to a table
//! width — wherever that placement gives back its depth, else at its depth.

use super::build::Carved;
use super::index::symmetric_indices;
use super::place::table_fraction;
use super::{Angle, Place, Recipe, RecipeTier, Side};
use crate::cut::{Cut, GemcadRecord};
use crate::design::{tiers, Gear};
use crate::error::{Error, Result};
use crate::geometry::Plane;

/// An inferred recipe and what a designer should know about it (meets that were ambiguous,
/// tiers renamed, indices between teeth).
#[derive(Clone, Debug)]
pub struct Inferred {
    /// The recipe; [`Recipe::build`] gives back the design's solid.
    pub recipe: Recipe,
    /// One line each.
    pub notes: Vec<String>,
}

/// One tier of the design: its GemCad line and its planes (in the recipe's units).
struct Line {
    name: String,
    angle: f64,
    flat_pavilion: bool,
    indices: Vec<f64>,
    planes: Vec<Plane>,
}

impl Line {
    fn kind(&self) -> usize {
        // 0 pavilion (and culet) and girdle, 1 crown, 2 table.
        if self.angle.abs() == 90.0 || self.angle < 0.0 || self.flat_pavilion {
            0
        } else if self.angle > 0.0 {
            1
        } else {
            2
        }
    }
}

/// Infer a recipe for `cut`; see the module documentation. Building the recipe gives the same
/// solid (same facet planes, volume within 1e-9 of the width cubed), scaled to width 1.
///
/// ```
/// use facetlab::design::recipe::infer;
/// let cut = facetlab::io::load_cut("tolkowsky").unwrap();
/// let r = infer(&cut).unwrap().recipe;
/// assert!(matches!(r.tiers[0].place, facetlab::design::recipe::Place::Centre));
/// let back = r.build().unwrap().cut;
/// assert!((back.solid.volume() - cut.solid.volume()).abs() < 1e-9);
/// ```
pub fn infer(cut: &Cut) -> Result<Inferred> {
    let mut notes = Vec::new();
    let record = cut
        .record
        .clone()
        .unwrap_or_else(|| GemcadRecord::generated(cut, 0, crate::cut::record::DIAMOND_RI));
    let teeth = record.gear.abs().round().max(3.0);
    let gear = Gear {
        teeth,
        offset: record.gear_offset,
    };
    let lines = tiers(cut, gear, 1.0);
    let by_name = |n: &str| {
        cut.solid
            .facets()
            .iter()
            .find(|f| f.name == n)
            .map(|f| f.plane)
    };
    // The unit: the first pavilion tier through one axis point puts that point at 1.
    let axis_z = |planes: &[Plane]| -> Option<f64> {
        let z0 = planes.first()?.offset / planes[0].normal.z;
        (planes[0].normal.z.abs() > 1e-9
            && planes
                .iter()
                .all(|p| (p.offset / p.normal.z - z0).abs() < 1e-9))
        .then_some(z0)
    };
    let mut raw: Vec<Line> = Vec::new();
    for t in &lines {
        let planes: Vec<Plane> = t.facets.iter().filter_map(|f| by_name(&f.name)).collect();
        let flat_pavilion = t.angle == 0.0 && planes.first().is_some_and(|p| p.normal.z < 0.0);
        raw.push(Line {
            name: t.name.clone(),
            angle: t.angle,
            flat_pavilion,
            indices: t.facets.iter().map(|f| f.index).collect(),
            planes,
        });
    }
    let unit = raw
        .iter()
        .filter(|l| l.angle < 0.0 && l.angle > -90.0)
        .find_map(|l| axis_z(&l.planes).filter(|z| *z < 0.0))
        .map(|z| -z)
        .unwrap_or(1.0);
    for l in &mut raw {
        for p in &mut l.planes {
            p.offset /= unit;
        }
    }
    // Names: kept when every tier has a short one-word name, else P1.., G1.., C1.., T, K.
    let short = |n: &str| {
        !n.is_empty() && n.len() <= 4 && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    };
    let mut seen = std::collections::BTreeSet::new();
    let keep = raw
        .iter()
        .all(|l| short(&l.name) && seen.insert(l.name.clone()));
    if !keep {
        let mut count = [0usize; 5];
        let mut map = Vec::new();
        for l in &mut raw {
            let (k, p) = if l.angle.abs() == 90.0 {
                (1, "G")
            } else if l.flat_pavilion {
                (4, "K")
            } else if l.angle < 0.0 {
                (0, "P")
            } else if l.angle > 0.0 {
                (2, "C")
            } else {
                (3, "T")
            };
            count[k] += 1;
            let new = if p == "T" || p == "K" {
                if count[k] == 1 {
                    p.to_string()
                } else {
                    format!("{p}{}", count[k])
                }
            } else {
                format!("{p}{}", count[k])
            };
            if !l.name.is_empty() {
                map.push(format!("{new}: {}", l.name));
            }
            l.name = new;
        }
        notes.push(format!("tiers renamed GemCad's way ({})", map.join(", ")));
    }
    // Symmetry: the design's, if every tier is closed under it.
    let mut symmetry = record.symmetry.max(1);
    let mut mirror = record.mirror;
    let closed = |s: u32, m: bool| {
        (teeth as u32).is_multiple_of(s)
            && raw.iter().all(|l| {
                l.angle == 0.0 || {
                    let all = symmetric_indices(&l.indices, teeth as u32, gear.offset, s, m);
                    all.len() == l.indices.len()
                }
            })
    };
    if !closed(symmetry, mirror) {
        notes.push(format!(
            "the design's {symmetry}-fold{} symmetry does not hold for every tier; the recipe lists every index",
            if mirror { " mirror" } else { "" }
        ));
        symmetry = 1;
        mirror = false;
    }
    let fractional = raw
        .iter()
        .any(|l| l.indices.iter().any(|x| (x - x.round()).abs() > 1e-9));
    if fractional {
        notes.push(format!(
            "some indices fall between the teeth of the {teeth} gear (fractional = true)"
        ));
    }
    let mut recipe = Recipe::new(
        record
            .title
            .first()
            .map_or(cut.name.as_str(), |t| t.as_str()),
        teeth as u32,
        symmetry,
        mirror,
        record.ri.unwrap_or(crate::cut::record::DIAMOND_RI),
    );
    recipe.offset = gear.offset;
    recipe.fractional = fractional;
    recipe.title = record.title.iter().skip(1).cloned().collect();
    recipe.notes = record.footnotes.clone();
    // Representatives of each tier's indices under the symmetry.
    let reps = |l: &Line| -> Vec<f64> {
        if l.angle == 0.0 {
            return Vec::new();
        }
        let mut out: Vec<f64> = Vec::new();
        let mut covered: Vec<f64> = Vec::new();
        for &x in &l.indices {
            if covered.iter().any(|y| (x - y).abs() < 1e-9) {
                continue;
            }
            out.push(if fractional { x } else { x.round() });
            covered.extend(symmetric_indices(
                &[x],
                teeth as u32,
                gear.offset,
                symmetry,
                mirror,
            ));
        }
        out
    };
    // The cutting order, greedily: within each phase, the first tier a faceter's placement
    // gives back; else a girdle level, else the first tier at its depth.
    let mut c = Carved::new();
    let mut left: Vec<usize> = (0..raw.len()).collect();
    while !left.is_empty() {
        let phase = left.iter().map(|&i| raw[i].kind()).min().unwrap_or(0);
        let pool: Vec<usize> = left
            .iter()
            .copied()
            .filter(|&i| raw[i].kind() == phase)
            .collect();
        let mut chosen: Option<(usize, Place)> = None;
        let mut ambiguous = std::collections::BTreeSet::new();
        for &i in &pool {
            match relative_place(&mut recipe, &raw[i], &reps(&raw[i]), &c) {
                Ok(p) => {
                    chosen = Some((i, p));
                    break;
                }
                Err(true) => {
                    ambiguous.insert(i);
                }
                Err(false) => {}
            }
        }
        let (i, place) = chosen.unwrap_or_else(|| {
            let i = pool
                .iter()
                .copied()
                .find(|&i| raw[i].angle.abs() == 90.0)
                .unwrap_or(pool[0]);
            let d = raw[i].planes[0].offset;
            if ambiguous.contains(&i) {
                notes.push(format!(
                    "tier {}: the meet it passes through is ambiguous (cut to it, the tier would stop first at another vertex of the same tiers); it is placed by its depth",
                    raw[i].name
                ));
            }
            let anchored = recipe
                .tiers
                .iter()
                .any(|t| matches!(t.place, Place::Scale(_)));
            let place = if !anchored {
                Place::Scale(d)
            } else {
                Place::Depth(d)
            };
            (i, place)
        });
        let l = &raw[i];
        let place = match place {
            Place::Depth(x) => Place::Depth(tidy(x)),
            Place::Scale(x) => Place::Scale(tidy(x)),
            Place::Girdle(x) => Place::Girdle(tidy(x)),
            Place::Table(x) => Place::Table(tidy(x)),
            other => other,
        };
        recipe.tiers.push(tier_of(l, reps(l), place));
        let k = recipe.tiers.len() - 1;
        let r = recipe.resolve(k, &c.resolved, None)?;
        let d = recipe.depth(k, &r, &c)?;
        recipe.cut_tier(k, r, d, &mut c, None)?;
        left.retain(|&j| j != i);
    }
    // The promise: the recipe gives back the solid.
    let back = recipe
        .build()
        .map_err(|e| e.context("the inferred recipe"))?;
    let (a, b) = (back.cut.solid.volume(), cut.solid.volume());
    if back.cut.solid.facets().len() != cut.solid.facets().len() || (a - b).abs() > 1e-9 {
        return Err(Error::Geometry(format!(
            "the inferred recipe of {} does not rebuild it ({} facets, volume {a} against {} and {b})",
            cut.name,
            back.cut.solid.facets().len(),
            cut.solid.facets().len()
        )));
    }
    Ok(Inferred { recipe, notes })
}

fn tier_of(l: &Line, indices: Vec<f64>, place: Place) -> RecipeTier {
    RecipeTier {
        name: l.name.clone(),
        angle: Angle::Degrees(if l.flat_pavilion { -0.0 } else { tidy(l.angle) }),
        side: None,
        indices,
        place,
        note: None,
    }
}

/// A placement relative to the stone cut so far (centre, meet, girdle, table) that gives
/// back `l`'s depth; else whether a meet it passes through was ambiguous.
fn relative_place(
    recipe: &mut Recipe,
    l: &Line,
    reps: &[f64],
    c: &Carved,
) -> std::result::Result<Place, bool> {
    let d = l.planes[0].offset;
    let tol = 1e-9 * c.size().max(1.0);
    let mut tries: Vec<Place> = Vec::new();
    if c.planes.is_empty() {
        // The first tier: to the centre point when it is one unit below (the unit chosen so).
        tries.push(Place::Centre);
    } else {
        tries.push(Place::Centre);
        // Meets: the tiers through each vertex the tier passes through.
        let mut seen: Vec<Vec<usize>> = Vec::new();
        for (_, p) in c.points() {
            if !l.planes.iter().any(|pl| pl.distance(p).abs() <= tol) {
                continue;
            }
            let mut multi: Vec<usize> = Vec::new();
            for j in 0..recipe.tiers.len() {
                for _ in 0..c.on_tier(j, p, tol) {
                    multi.push(j);
                }
            }
            if multi.len() < 2 {
                continue;
            }
            for cand in sub_multisets(&multi) {
                if !seen.contains(&cand) {
                    seen.push(cand);
                }
            }
        }
        seen.sort_by_key(|m| (m.len(), m.clone()));
        for m in seen {
            tries.push(Place::Meet(
                m.iter().map(|&j| recipe.tiers[j].name.clone()).collect(),
            ));
        }
        let side = if l.angle > 0.0 && l.angle < 90.0 {
            Some(Side::Crown)
        } else if l.angle < 0.0 && l.angle > -90.0 {
            Some(Side::Pavilion)
        } else {
            None
        };
        // A girdle thickness places the first tier of a side ("leave some girdle").
        let first_of_side = !recipe.tiers.iter().enumerate().any(|(j, _)| {
            c.resolved
                .get(j)
                .is_some_and(|r| r.side == side && r.tilt > 0.0)
        });
        if side.is_some() && first_of_side {
            // The girdle thickness that gives this depth: the depth is linear in it.
            let at = |t: f64, recipe: &mut Recipe| depth_for(recipe, l, reps, Place::Girdle(t), c);
            if let (Some(d0), Some(d1)) = (at(0.0, recipe), at(0.5, recipe)) {
                if (d1 - d0).abs() > 1e-12 {
                    let t = 0.5 * (d - d0) / (d1 - d0);
                    if (0.0..1.0).contains(&t) {
                        tries.push(Place::Girdle(t));
                    }
                }
            }
        }
        if l.angle == 0.0 && !l.flat_pavilion {
            tries.push(Place::Table(table_fraction(c, d)));
        }
    }
    let mut meets_failed = false;
    for p in tries {
        match depth_for(recipe, l, reps, p.clone(), c) {
            Some(g) if (g - d).abs() <= tol => return Ok(p),
            _ => meets_failed |= matches!(p, Place::Meet(_)),
        }
    }
    Err(meets_failed)
}

/// The depth `place` gives tier `l` on `c` (the tier appended to `recipe` for the asking).
fn depth_for(recipe: &mut Recipe, l: &Line, reps: &[f64], place: Place, c: &Carved) -> Option<f64> {
    recipe.tiers.push(tier_of(l, reps.to_vec(), place));
    let k = recipe.tiers.len() - 1;
    let out = recipe
        .resolve(k, &c.resolved, None)
        .and_then(|r| recipe.depth(k, &r, c))
        .ok();
    recipe.tiers.pop();
    out
}

/// The sub-multisets of `m` (sorted) with at least two members: the meets a vertex offers.
fn sub_multisets(m: &[usize]) -> Vec<Vec<usize>> {
    let mut m = m.to_vec();
    m.sort_unstable();
    let n = m.len().min(6);
    let mut out: Vec<Vec<usize>> = Vec::new();
    for mask in 1u32..(1 << n) {
        if mask.count_ones() < 2 {
            continue;
        }
        let s: Vec<usize> = (0..n)
            .filter(|b| mask & (1 << b) != 0)
            .map(|b| m[b])
            .collect();
        // A meet names at least two different tiers or one tier twice.
        if !out.contains(&s) {
            out.push(s);
        }
    }
    out
}

/// `x` rounded to the fewest decimals (up to 10) that move it by at most 1e-11 of its size:
/// 40.75 rather than 40.750000000000014, which a solid's normals give back.
fn tidy(x: f64) -> f64 {
    for k in 0..=10 {
        let f = 10f64.powi(k);
        let r = (x * f).round() / f;
        if (r - x).abs() <= 1e-11 * x.abs().max(1.0) {
            return r;
        }
    }
    x
}
