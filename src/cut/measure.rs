//! Proportions measured on a solid, the way a cutter or a grading lab reads them, and the
//! ratios GemCad prints under a design.
//!
//! Lengths are in the solid's units: the width W of [`super::units`] (a round's girdle
//! diameter) for generated and imported cuts.
//! - table: GemCad's T/W, the table's extent across the width over W (corner to corner for a
//!   round brilliant, whose corners lie on x; the `table` of every family). The table is the
//!   facet holding the stone's top when it is within 2° of level, with the level facets
//!   joined to it (a split or slightly tilted table); a cut whose top is a point or a steeper
//!   tier has none (0);
//! - girdle: the girdle facets' (normals within 1° of horizontal, see [`super::units`])
//!   vertical extent at their thinnest point around the outline (where a lab measures a
//!   round's girdle, between bezel and main: every family's `girdle`), or 0 for a knife-edge
//!   girdle, whose plane is then at the widest vertex;
//! - crown height: the top to the girdle's top, at that thinnest point; pavilion depth: the
//!   girdle's bottom there to the lowest point; total depth: highest to lowest point (the
//!   three add up to it);
//! - crown angle: the angle of the crown facet that touches the table (or the top) and meets
//!   the girdle (a bezel); else, with a table, of those touching it that reach lowest (a step
//!   cut's table step); else, with no table, of those meeting the girdle that reach highest
//!   (the tier under a pointed or checkered top) — among them the one facing most squarely
//!   across the width (of a fancy shape, the bezel or step on its long side; the largest of
//!   such); pavilion angle: the same among the pavilion facets that touch the bottom (culet,
//!   point or keel) and meet the girdle (a main), else reach highest. Facets steeper than 80°
//!   are not mains (they stand with the girdle). Facets are chosen by geometry alone, never
//!   by tier name, so a design measures the same from a preset, a `.asc`, an `.obj` or an
//!   `.stl`. For free-form designs these are heuristics: read the tier list.

use super::units::{is_girdle, outline_size, HORIZONTAL};
use crate::geometry::{facet_angle_deg, Polyhedron};
use serde::Serialize;

/// Measured proportions.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Proportions {
    /// Table width across the width / the width W (GemCad's T/W).
    pub table: f64,
    /// Crown main angle, degrees.
    pub crown_angle: f64,
    /// Pavilion main angle, degrees.
    pub pavilion_angle: f64,
    /// Crown height / girdle diameter.
    pub crown_height: f64,
    /// Pavilion depth / girdle diameter.
    pub pavilion_depth: f64,
    /// Total depth / girdle diameter.
    pub total_depth: f64,
    /// Girdle thickness / girdle diameter.
    pub girdle: f64,
}

/// One tier: its name, mean facet angle (degrees from the girdle plane) and facet count.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TierSummary {
    /// Tier name.
    pub name: String,
    /// Mean facet angle to the girdle plane, degrees (table 0°, girdle 90°).
    pub angle: f64,
    /// Number of facets.
    pub count: usize,
    /// `crown`, `girdle` or `pavilion`.
    pub side: &'static str,
}

fn side_of(nz: f64) -> &'static str {
    if nz.abs() < HORIZONTAL {
        "girdle"
    } else if nz > 0.0 {
        "crown"
    } else {
        "pavilion"
    }
}

/// Tiers in order of first appearance.
pub fn tiers(s: &Polyhedron) -> Vec<TierSummary> {
    let mut out: Vec<(TierSummary, f64)> = Vec::new();
    for f in s.facets() {
        let a = facet_angle_deg(f.plane.normal);
        let side = side_of(f.plane.normal.z);
        match out
            .iter_mut()
            .find(|(t, _)| t.name == f.tier && t.side == side)
        {
            Some((t, sum)) => {
                t.count += 1;
                *sum += a;
            }
            None => out.push((
                TierSummary {
                    name: f.tier.clone(),
                    angle: 0.0,
                    count: 1,
                    side,
                },
                a,
            )),
        }
    }
    out.into_iter()
        .map(|(mut t, sum)| {
            t.angle = sum / t.count as f64;
            t
        })
        .collect()
}

/// Facets within this angle of level that hold the stone's top form its table (a table cut
/// in two or tilted a degree or two, as some designs do, is still the table).
const TABLE_TILT_DEG: f64 = 2.0;

/// Crown and pavilion facets steeper than this are not mains: they belong with the girdle's
/// band (a design's nearly vertical facets beside its girdle).
const MAIN_MAX_DEG: f64 = 80.0;

/// How close two facets' vertices must come for the facets to touch, in W: a design read from
/// a file leaves the corners where several of its rounded planes meet a little apart (~1e-8).
const TOUCH: f64 = 1e-6;

/// Whether facets `a` and `b` touch: a vertex of one within [`TOUCH`] of a vertex of the other.
fn touch(s: &Polyhedron, a: usize, b: usize) -> bool {
    let (fa, fb) = (&s.facets()[a], &s.facets()[b]);
    fa.vertices.iter().any(|&u| {
        fb.vertices
            .iter()
            .any(|&v| s.vertices()[u].distance(s.vertices()[v]) <= TOUCH)
    })
}

/// Whether point `p` is within [`TOUCH`] of a corner of facet `f`.
fn at_corner(s: &Polyhedron, f: usize, p: crate::geometry::DVec3) -> bool {
    s.facets()[f]
        .vertices
        .iter()
        .any(|&k| s.vertices()[k].distance(p) <= TOUCH)
}

/// The table: the facets within [`TABLE_TILT_DEG`] of level connected (by touching corners) to
/// the one that holds the stone's highest vertex; empty when that facet is steeper (a cut
/// with no table: a point or a ridge on top).
fn table_facets(s: &Polyhedron) -> Vec<usize> {
    let (_, hi) = s.bounding_box();
    let level = |i: usize| facet_angle_deg(s.facets()[i].plane.normal) <= TABLE_TILT_DEG;
    let touches_top = |i: usize| {
        s.facets()[i]
            .vertices
            .iter()
            .any(|&v| s.vertices()[v].z >= hi.z - 1e-9)
    };
    let mut table: Vec<usize> = (0..s.facets().len())
        .filter(|&i| s.facets()[i].plane.normal.z > 0.0 && level(i) && touches_top(i))
        .collect();
    // Grow by shared vertices over level facets.
    let mut k = 0;
    while k < table.len() {
        let t = table[k];
        for j in 0..s.facets().len() {
            if !table.contains(&j)
                && s.facets()[j].plane.normal.z > 0.0
                && level(j)
                && touch(s, t, j)
            {
                table.push(j);
            }
        }
        k += 1;
    }
    table
}

/// The vertical extent of the girdle facets `girdle` with a corner at `p` (within
/// [`TOUCH`]), on the vertical line through it (each such facet's polygon cut by that line; a
/// vertical edge counts whole), as (bottom, top).
fn band_at(s: &Polyhedron, p: crate::geometry::DVec3, girdle: &[usize]) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &j in girdle {
        if !at_corner(s, j, p) {
            continue;
        }
        let f = &s.facets()[j];
        let n = f.plane.normal;
        let t = crate::geometry::DVec2::new(-n.y, n.x).normalize_or_zero();
        let at = t.dot(p.truncate());
        let pts: Vec<(f64, f64)> = f
            .vertices
            .iter()
            .map(|&k| (t.dot(s.vertices()[k].truncate()), s.vertices()[k].z))
            .collect();
        for k in 0..pts.len() {
            let (a, b) = (pts[k], pts[(k + 1) % pts.len()]);
            let (s0, s1) = (a.0.min(b.0), a.0.max(b.0));
            if at < s0 - 1e-9 || at > s1 + 1e-9 {
                continue;
            }
            let zs = if s1 - s0 < 1e-9 {
                [a.1, b.1]
            } else {
                let z = a.1 + (b.1 - a.1) * (at - a.0) / (b.0 - a.0);
                [z, z]
            };
            lo = lo.min(zs[0].min(zs[1]));
            hi = hi.max(zs[0].max(zs[1]));
        }
    }
    (hi >= lo).then_some((lo, hi))
}

/// Measure the proportions of a solid.
pub fn proportions(s: &Polyhedron) -> Proportions {
    let (lo, hi) = s.bounding_box();
    let table_set = table_facets(s);
    let table = table_extent(s, &table_set);
    // The table's height: its highest point (the stone's top; a level table's plane).
    let table_z = hi.z;
    // A knife-edge girdle's plane: at the widest vertices.
    let knife = {
        let r = s.max_radius();
        let widest: Vec<f64> = s
            .vertices()
            .iter()
            .filter(|v| v.truncate().length() > r - 1e-9)
            .map(|v| v.z)
            .collect();
        widest.iter().sum::<f64>() / widest.len().max(1) as f64
    };
    let girdle_set: Vec<usize> = (0..s.facets().len())
        .filter(|&i| is_girdle(s.facets()[i].plane.normal))
        .collect();
    let shares = |i: usize, set: &[usize]| set.iter().any(|&j| touch(s, i, j));
    // Main facets, chosen facet by facet (never by tier name, so that a design read from a
    // mesh, whose tiers are only grouped by angle, measures as its source). Crown: the facets
    // that touch the table (or reach the top) and meet the girdle (a bezel); else, with a
    // table, those touching it that reach lowest (a step cut's table step, the families'
    // `crown_angle`); else, with no table, those meeting the girdle that reach highest (the
    // tier under a pointed or checkered top). Pavilion: those touching the bottom (culet,
    // point or keel) and meeting the girdle (a main), else those reaching highest. Among
    // them, the one facing most squarely across the width (a fancy shape's bezel on its long
    // side), the largest of those.
    let tol = 1e-7;
    let (ex, ey) = (hi.x - lo.x, hi.y - lo.y);
    let square = (ex - ey).abs() <= 1e-6 * ex.max(ey);
    // How squarely a facet faces across the width: |cos| of its azimuth to the width axis
    // (x when the stone is narrower in x, y when narrower in y, either for a square outline).
    let facing = |n: crate::geometry::DVec3| -> f64 {
        let h = n.x.hypot(n.y).max(1e-300);
        let (cx, cy) = ((n.x / h).abs(), (n.y / h).abs());
        if square {
            cx.max(cy)
        } else if ex < ey {
            cx
        } else {
            cy
        }
    };
    // (touches the table or bottom, meets the girdle, reach, facing, area, angle, facet)
    type Cand = (bool, bool, f64, f64, f64, f64, usize);
    let mut crown: Vec<Cand> = Vec::new();
    let mut pav: Vec<Cand> = Vec::new();
    for (i, f) in s.facets().iter().enumerate() {
        let zs: Vec<f64> = f.vertices.iter().map(|&v| s.vertices()[v].z).collect();
        let zmax = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let zmin = zs.iter().copied().fold(f64::INFINITY, f64::min);
        let n = f.plane.normal;
        let angle = facet_angle_deg(n);
        if angle > MAIN_MAX_DEG || table_set.contains(&i) {
            continue;
        }
        let meets = if girdle_set.is_empty() {
            (zmin - knife).abs() <= tol || (zmax - knife).abs() <= tol
        } else {
            shares(i, &girdle_set)
        };
        match side_of(n.z) {
            "crown" if n.z < 1.0 - 1e-9 => {
                let top = if table_set.is_empty() {
                    zmax >= hi.z - tol
                } else {
                    shares(i, &table_set)
                };
                crown.push((top, meets, zmin, facing(n), f.area, angle, i));
            }
            "pavilion" if n.z > -1.0 + 1e-9 => {
                pav.push((zmin <= lo.z + tol, meets, zmax, facing(n), f.area, angle, i));
            }
            _ => {}
        }
    }
    // The pool: both ends; else the fallback of the doc comment above (`low`: the end
    // touched, chosen by reaching lowest; else the girdle's, by reaching highest).
    let main = |c: &[Cand], table: bool| -> Option<Cand> {
        let both: Vec<&Cand> = c.iter().filter(|x| x.0 && x.1).collect();
        let pool: Vec<&Cand> = if !both.is_empty() {
            both
        } else {
            // Reach: crown candidates store their lowest z, pavilion ones their highest.
            let (ends, lowest): (Vec<&Cand>, bool) = if table {
                (c.iter().filter(|x| x.0).collect(), true)
            } else {
                (c.iter().filter(|x| x.1).collect(), false)
            };
            let key = |x: &&Cand| if lowest { -x.2 } else { x.2 };
            let reach = ends.iter().map(key).fold(f64::NEG_INFINITY, f64::max);
            ends.into_iter()
                .filter(|x| key(x) >= reach - 1e-6)
                .collect()
        };
        let best = pool.iter().map(|x| x.3).fold(f64::NEG_INFINITY, f64::max);
        pool.into_iter()
            .filter(|x| x.3 >= best - 1e-6)
            .max_by(|a, b| a.4.total_cmp(&b.4))
            .copied()
    };
    // A step cut's crown falls back to its table step; a tableless crown to the girdle's tier.
    let crown_main = main(&crown, !table_set.is_empty());
    // The pavilion falls back to the facets touching the bottom that reach highest.
    let pavilion_angle = {
        let flipped: Vec<Cand> = pav
            .iter()
            .map(|x| (x.0, x.1, -x.2, x.3, x.4, x.5, x.6))
            .collect();
        main(&flipped, true).map_or(0.0, |x| x.5)
    };
    // The girdle where the crown meets it: at the lowest vertex the crown main shares with a
    // girdle facet (a round's bezel–main point, where a lab measures its girdle and its crown
    // height; every family's `girdle`), or, when the main does not reach the girdle (a step
    // cut's table step), of the crown facet meeting it that a main would be chosen from; the
    // girdle's extent on the vertical line there. A knife-edge girdle is a plane.
    let meeting: Vec<Cand> = crown.iter().filter(|x| x.1).copied().collect();
    let at = crown_main
        .filter(|x| x.1)
        .or_else(|| main(&meeting, false))
        .and_then(|x| {
            s.facets()[x.6]
                .vertices
                .iter()
                .map(|&v| s.vertices()[v])
                .filter(|p| girdle_set.iter().any(|&j| at_corner(s, j, *p)))
                .min_by(|a, b| a.z.total_cmp(&b.z))
        });
    let (g_bot, g_top) = at
        .and_then(|p| band_at(s, p, &girdle_set))
        .unwrap_or((knife, knife));
    let crown_angle = crown_main.map_or(0.0, |x| x.5);
    Proportions {
        table,
        crown_angle,
        pavilion_angle,
        crown_height: table_z - g_top,
        pavilion_depth: g_bot - lo.z,
        total_depth: hi.z - lo.z,
        girdle: g_top - g_bot,
    }
}

/// The table's extent across the width (the outline's narrower axis, x or y) over the width W:
/// GemCad's T/W; 0 without a table.
fn table_extent(s: &Polyhedron, table: &[usize]) -> f64 {
    let (_, w) = outline_size(s.vertices());
    let (lo, hi) = s.bounding_box();
    let across_x = (hi.x - lo.x) <= (hi.y - lo.y);
    let (a, b) = table
        .iter()
        .flat_map(|&i| s.facets()[i].vertices.iter())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            let p = s.vertices()[v];
            let x = if across_x { p.x } else { p.y };
            (a.min(x), b.max(x))
        });
    if b > a {
        (b - a) / w.max(1e-300)
    } else {
        0.0
    }
}

/// The ratios GemCad prints under a design, each over the width W (the outline's smaller
/// extent along x and y, [`super::units`]).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Ratios {
    /// Length / width: the outline's larger extent along x and y over its smaller (≥ 1).
    pub l_w: f64,
    /// Table / width: the table's extent along the width's axis over W.
    pub t_w: f64,
    /// Pavilion depth (girdle bottom to the lowest point) / width.
    pub p_w: f64,
    /// Crown height (girdle top to the table) / width.
    pub c_w: f64,
    /// Total height (top to bottom) / width.
    pub h_w: f64,
    /// Volume / width³.
    pub vol_w3: f64,
}

/// GemCad's ratios of a solid (see [`Ratios`]).
pub fn ratios(s: &Polyhedron) -> Ratios {
    let (l, w) = outline_size(s.vertices());
    let w = w.max(1e-300);
    let p = proportions(s);
    let t = p.table * w;
    Ratios {
        l_w: l / w,
        t_w: t / w,
        p_w: p.pavilion_depth / w,
        c_w: p.crown_height / w,
        h_w: p.total_depth / w,
        vol_w3: s.volume() / (w * w * w),
    }
}
