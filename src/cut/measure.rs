//! Proportions measured on a solid, the way a cutter or a grading lab reads them.
//!
//! Lengths are in the solid's units (girdle diameters for generated and imported cuts).
//! - table: the table's largest width over the outline's largest width (corner to corner for a
//!   round brilliant);
//! - girdle: the vertical extent of the girdle facets (normals within 1° of horizontal, see
//!   [`super::units`]), or 0 for a knife-edge girdle, whose plane is then at the widest vertex;
//! - crown height: table plane to the girdle top; pavilion depth: girdle bottom to the lowest
//!   point; total depth: highest to lowest point;
//! - crown angle: mean angle of the crown tier that touches the table (or the top) and reaches
//!   lowest (the bezels); pavilion angle: the pavilion tier that touches the bottom (culet or
//!   point) and reaches highest (the mains); a tier that spans all the way to the girdle is
//!   preferred. For free-form imported designs these are heuristics: read the tier list.

use super::units::{girdle_z, outline_width, HORIZONTAL};
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
    let tol = 1e-7;
    // Main tiers: the crown tier that touches the table (or the top) and reaches lowest; the
    // pavilion tier that touches the bottom (culet or point) and reaches highest.
    // Candidates keyed by (spans to the girdle, how far they reach): a tier running from the
    // table to the girdle (or from the culet to the girdle) wins; else the one reaching furthest.
    let mut best_crown: Option<(String, (bool, f64))> = None;
    let mut best_pav: Option<(String, (bool, f64))> = None;
    let better = |k: (bool, f64), cur: &Option<(String, (bool, f64))>| -> bool {
        match cur {
            None => true,
            Some((_, c)) => (k.0 && !c.0) || (k.0 == c.0 && k.1 > c.1 + tol),
        }
    };
    for f in s.facets() {
        let zs: Vec<f64> = f.vertices.iter().map(|&v| s.vertices()[v].z).collect();
        let zmax = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let zmin = zs.iter().copied().fold(f64::INFINITY, f64::min);
        let nz = f.plane.normal.z;
        match side_of(nz) {
            "crown" if nz < 1.0 - 1e-9 && zmax >= table_z - tol => {
                let k = (zmin <= g_top + tol, -zmin);
                if better(k, &best_crown) {
                    best_crown = Some((f.tier.clone(), k));
                }
            }
            "pavilion" if nz > -1.0 + 1e-9 && zmin <= lo.z + tol => {
                let k = (zmax >= g_bot - tol, zmax);
                if better(k, &best_pav) {
                    best_pav = Some((f.tier.clone(), k));
                }
            }
            _ => {}
        }
    }
    let tier_angle = |tier: &Option<(String, (bool, f64))>, crown: bool| -> f64 {
        let Some((name, _)) = tier else { return 0.0 };
        let angles: Vec<f64> = s
            .facets()
            .iter()
            .filter(|f| &f.tier == name && (f.plane.normal.z > 0.0) == crown)
            .map(|f| facet_angle_deg(f.plane.normal))
            .collect();
        angles.iter().sum::<f64>() / angles.len().max(1) as f64
    };
    Proportions {
        table,
        crown_angle: tier_angle(&best_crown, true),
        pavilion_angle: tier_angle(&best_pav, false),
        crown_height: table_z - g_top,
        pavilion_depth: g_bot - lo.z,
        total_depth: hi.z - lo.z,
        girdle: g_top - g_bot,
    }
}
