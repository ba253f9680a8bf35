//! Adapting a design to another refractive index, as GemCad and BOG users do: the tangent
//! ratio.
//!
//! A tangent ratio `k` applied to one side of the girdle (crown or pavilion) multiplies the
//! tangent of every facet angle on that side by `k` (the angle from the girdle plane). It is
//! the vertical stretch `z' = z₀ + (z − z₀)·k` of that side about the girdle's edge `z₀`: an
//! affine map, so every meet point of the design stays a meet point, no facet appears or
//! vanishes, and azimuths and the girdle outline are kept. [`tangent_ratio`] applies one ratio
//! to the crown and one to the pavilion.
//!
//! The ratio for a new index ([`pavilion_ratio_for`]): a sight line straight down through
//! the table meets a pavilion main at incidence `p` (the pavilion angle) and, after reflecting,
//! the opposite main at `3p − 90°`; both must exceed the critical angle `c = asin(1/n)` for the
//! light to come back, and the second is the binding one, `p ≥ (90° + c)/3`. Retargeting keeps
//! the design's margin above that bound: `p' = p + (c' − c)/3` (diamond's 40.75° becomes
//! 46.1° in quartz). The crown is kept (ratio 1). The rule is a starting point only: by the
//! scores of [`crate::metrics`] a diamond round brilliant in quartz returns less light with
//! the rule's 46° pavilion (0.51) than unchanged (0.70), so `facetlab retarget` lets an
//! optimizer adjust both ratios to restore the design's light return at the new index.

use super::Cut;
use crate::error::{Error, Result};
use crate::geometry::{FacetPlane, Plane, Polyhedron};
use glam::DVec3;

/// Normals within this of horizontal count as girdle facets (vertical planes).
const VERTICAL: f64 = 1e-6;

/// `cut` with the tangent of every crown facet's angle multiplied by `k_crown` and every
/// pavilion facet's by `k_pavilion` (each side stretched vertically about the girdle's edge).
pub fn tangent_ratio(cut: &Cut, k_crown: f64, k_pavilion: f64) -> Result<Cut> {
    for (name, k) in [("crown ratio", k_crown), ("pavilion ratio", k_pavilion)] {
        if !(k.is_finite() && (0.05..=20.0).contains(&k)) {
            return Err(Error::invalid(
                name,
                format!("{k} is out of range; allowed 0.05 to 20"),
            ));
        }
    }
    let s = &cut.solid;
    // The girdle's top and bottom edges: the highest and lowest points of its vertical facets
    // (0, the girdle plane, when it has none).
    let (mut top, mut bottom) = (f64::NEG_INFINITY, f64::INFINITY);
    for (i, f) in s.facets().iter().enumerate() {
        if f.plane.normal.z.abs() < VERTICAL {
            for p in s.facet_polygon(i) {
                top = top.max(p.z);
                bottom = bottom.min(p.z);
            }
        }
    }
    if !top.is_finite() {
        (top, bottom) = (0.0, 0.0);
    }
    let planes: Vec<FacetPlane> = s
        .facet_planes()
        .into_iter()
        .map(|mut f| {
            let n = f.plane.normal;
            let (k, z0) = if n.z > VERTICAL {
                (k_crown, top)
            } else if n.z < -VERTICAL {
                (k_pavilion, bottom)
            } else {
                return f;
            };
            // n·x = d with z = z0 + (z' − z0)/k.
            let m = DVec3::new(n.x, n.y, n.z / k);
            let d = f.plane.offset - n.z * z0 * (1.0 - 1.0 / k);
            let len = m.length();
            f.plane = Plane {
                normal: m / len,
                offset: d / len,
            };
            f
        })
        .collect();
    let solid = Polyhedron::from_planes(&planes)?;
    Ok(Cut {
        name: cut.name.clone(),
        family: None,
        params: Default::default(),
        solid,
        record: cut.record.clone(),
    })
}

/// Critical angle of index `n`, degrees.
pub fn critical_angle_deg(n: f64) -> f64 {
    (1.0 / n).clamp(-1.0, 1.0).asin().to_degrees()
}

/// The pavilion's tangent ratio that moves a design cut for index `from` to index `to` (see
/// the module documentation): `tan(p + (c_to − c_from)/3) / tan p` for the design's pavilion
/// angle `p`, degrees.
pub fn pavilion_ratio_for(pavilion_deg: f64, from: f64, to: f64) -> f64 {
    let shift = (critical_angle_deg(to) - critical_angle_deg(from)) / 3.0;
    let p = pavilion_deg.clamp(1.0, 89.0);
    let q = (p + shift).clamp(1.0, 89.0);
    q.to_radians().tan() / p.to_radians().tan()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tangent ratio stretches one side exactly: every pavilion facet's tangent is scaled
    /// by k, the crown and the girdle are untouched, and no facet is lost.
    #[test]
    fn tangent_ratio_scales_tangents_and_keeps_every_facet() {
        let cut = crate::io::load_cut("gia-reference").unwrap();
        let k = 1.25;
        let out = tangent_ratio(&cut, 1.0, k).unwrap();
        assert_eq!(out.solid.facets().len(), cut.solid.facets().len());
        let p0 = cut.proportions();
        let p1 = out.proportions();
        let t = |a: f64| a.to_radians().tan();
        assert!((t(p1.pavilion_angle) / t(p0.pavilion_angle) - k).abs() < 1e-9);
        assert!((p1.crown_angle - p0.crown_angle).abs() < 1e-9);
        assert!((p1.table - p0.table).abs() < 1e-9);
        assert!((p1.pavilion_depth / p0.pavilion_depth - k).abs() < 1e-9);
        // Every facet's tangent on the pavilion side scaled alike.
        for (a, b) in cut.solid.facets().iter().zip(out.solid.facets()) {
            let (na, nb) = (a.plane.normal, b.plane.normal);
            if na.z < -VERTICAL {
                let ta = na.truncate().length() / -na.z;
                let tb = nb.truncate().length() / -nb.z;
                assert!((tb / ta - k).abs() < 1e-9);
            } else {
                assert!((na - nb).length() < 1e-12);
            }
        }
        assert!(tangent_ratio(&cut, 0.0, 1.0).is_err());
    }

    #[test]
    fn pavilion_ratio_keeps_the_margin_above_the_second_reflection_bound() {
        // Diamond (2.417) → quartz (1.544): 40.75° → 40.75° + (40.37° − 24.43°)/3.
        let k = pavilion_ratio_for(40.75, 2.417, 1.544);
        let p = (k * 40.75f64.to_radians().tan()).atan().to_degrees();
        let want = 40.75 + (critical_angle_deg(1.544) - critical_angle_deg(2.417)) / 3.0;
        assert!((p - want).abs() < 1e-9 && (p - 46.06).abs() < 0.05, "{p}");
        assert_eq!(pavilion_ratio_for(42.0, 1.76, 1.76), 1.0);
    }
}
