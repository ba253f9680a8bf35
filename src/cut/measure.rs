//! Proportions measured on a solid, the way a cutter or a grading lab reads them.
//!
//! Lengths are in the solid's units: the width W of [`super::units`] (a round's girdle
//! diameter) for generated and imported cuts.
//! - table: the table's largest width over the outline's largest width (corner to corner for a
//!   round brilliant);
//! - girdle: the vertical extent of the girdle facets (normals within 1° of horizontal, see
//!   [`super::units`]), or 0 for a knife-edge girdle, whose plane is then at the widest vertex;
//! - crown height: table plane to the girdle top; pavilion depth: girdle bottom to the lowest
//!   point; total depth: highest to lowest point;
//! - crown angle: the angle of the crown facet that touches the table (or the top) and reaches
//!   the girdle (a bezel), else of those reaching lowest (a step cut's top step), that faces
//!   most squarely across the width (of a fancy shape, the bezel or step on its long side;
//!   the largest of such); pavilion angle: the same among the pavilion facets that touch the
//!   bottom (culet, point or keel) and reach the girdle (a main), else reach highest.
//!   Facets are chosen by geometry alone, never by tier name, so a design measures the same
//!   from a preset, a `.asc`, an `.obj` or an `.stl`. For free-form designs these are
//!   heuristics: read the tier list.

use super::units::{girdle_z, outline_size, outline_width, HORIZONTAL};
use crate::geometry::{facet_angle_deg, Polyhedron};
use serde::Serialize;

/// Measured proportions.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Proportions {
    /// Table width / outline width.
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

/// Measure the proportions of a solid.
pub fn proportions(s: &Polyhedron) -> Proportions {
    let (lo, hi) = s.bounding_box();
    let outline = outline_width(s.vertices()).max(1e-300);
    // Table: the up-facing horizontal facet highest up.
    let table = s
        .facets()
        .iter()
        .enumerate()
        .filter(|(_, f)| f.plane.normal.z > 1.0 - 1e-9)
        .max_by(|a, b| a.1.plane.offset.total_cmp(&b.1.plane.offset))
        .map(|(i, _)| outline_width(&s.facet_polygon(i)) / outline)
        .unwrap_or(0.0);
    let table_z = s
        .facets()
        .iter()
        .filter(|f| f.plane.normal.z > 1.0 - 1e-9)
        .map(|f| f.plane.offset)
        .fold(f64::NEG_INFINITY, f64::max);
    let table_z = if table_z.is_finite() { table_z } else { hi.z };
    // Girdle extent.
    let girdle_z = girdle_z(s);
    let (g_top, g_bot) = if girdle_z.is_empty() {
        let r = s.max_radius();
        let z = s
            .vertices()
            .iter()
            .filter(|v| v.truncate().length() > r - 1e-9)
            .map(|v| v.z)
            .fold(0.0, |a, b| a + b)
            / s.vertices()
                .iter()
                .filter(|v| v.truncate().length() > r - 1e-9)
                .count()
                .max(1) as f64;
        (z, z)
    } else {
        (
            girdle_z.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            girdle_z.iter().copied().fold(f64::INFINITY, f64::min),
        )
    };
    // Main facets, chosen facet by facet (never by tier name, so that a design read from a
    // mesh, whose tiers are only grouped by angle, measures as its source): among the crown
    // facets that touch the table (or the top) and reach the girdle, else those that reach
    // lowest, the one facing most squarely across the width (a bezel; of a fancy shape, the
    // one on its long side), the largest of those; the same for the pavilion facets that touch
    // the bottom (culet, point or keel) and reach the girdle (a main), else reach highest.
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
    // (spans to the girdle, reach, facing, area, angle)
    type Cand = (bool, f64, f64, f64, f64);
    let mut crown: Vec<Cand> = Vec::new();
    let mut pav: Vec<Cand> = Vec::new();
    for f in s.facets() {
        let zs: Vec<f64> = f.vertices.iter().map(|&v| s.vertices()[v].z).collect();
        let zmax = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let zmin = zs.iter().copied().fold(f64::INFINITY, f64::min);
        let n = f.plane.normal;
        let c = |spans: bool, reach: f64| (spans, reach, facing(n), f.area, facet_angle_deg(n));
        match side_of(n.z) {
            "crown" if n.z < 1.0 - 1e-9 && zmax >= table_z - tol => {
                crown.push(c(zmin <= g_top + tol, -zmin));
            }
            "pavilion" if n.z > -1.0 + 1e-9 && zmin <= lo.z + tol => {
                pav.push(c(zmax >= g_bot - tol, zmax));
            }
            _ => {}
        }
    }
    // Spanning to the girdle, else reaching furthest; then facing the width most squarely
    // (within 1e-6), then the largest.
    let main = |c: &[Cand]| -> f64 {
        let spans = c.iter().any(|x| x.0);
        let reach = c.iter().map(|x| x.1).fold(f64::NEG_INFINITY, f64::max);
        let pool: Vec<&Cand> = c
            .iter()
            .filter(|x| if spans { x.0 } else { x.1 >= reach - 1e-6 })
            .collect();
        let best = pool.iter().map(|x| x.2).fold(f64::NEG_INFINITY, f64::max);
        pool.into_iter()
            .filter(|x| x.2 >= best - 1e-6)
            .max_by(|a, b| a.3.total_cmp(&b.3))
            .map_or(0.0, |x| x.4)
    };
    let crown_angle = main(&crown);
    let pavilion_angle = main(&pav);
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
    let (lo, hi) = s.bounding_box();
    let across_x = (hi.x - lo.x) <= (hi.y - lo.y);
    let t = s
        .facets()
        .iter()
        .enumerate()
        .filter(|(_, f)| f.plane.normal.z > 1.0 - 1e-9)
        .max_by(|a, b| a.1.plane.offset.total_cmp(&b.1.plane.offset))
        .map(|(i, _)| {
            let poly = s.facet_polygon(i);
            let (a, b) = poly
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                    let x = if across_x { v.x } else { v.y };
                    (a.min(x), b.max(x))
                });
            (b - a).max(0.0)
        })
        .unwrap_or(0.0);
    let p = proportions(s);
    Ratios {
        l_w: l / w,
        t_w: t / w,
        p_w: p.pavilion_depth / w,
        c_w: p.crown_height / w,
        h_w: p.total_depth / w,
        vol_w3: s.volume() / (w * w * w),
    }
}
