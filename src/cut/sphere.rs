//! The thesis's control stone: a faceted sphere.
//!
//! `facets` planes tangent to the sphere of diameter 1 centred at the origin, at the points of a
//! Fibonacci (golden-angle) spiral: point i of N has height z = 1 − (2i + 1)/N (times the radius)
//! and azimuth i·π(3 − √5). The points are spread almost evenly, so every facet is a roughly
//! regular polygon of about the same area (a geodesic-like ball), and the heights are symmetric
//! about z = 0, so the girdle plane is the equator. Every tangent plane touches the solid at its
//! tangent point, so every facet exists for any N; the solid circumscribes the sphere, so its
//! volume is above π/6 and approaches it as N grows. All facets are in the tier `sphere`.
//!
//! Like every family, the ball is then scaled so that its width W (the outline's smaller extent
//! along x and y, [`super::units`]) is 1: the tangent sphere's diameter is 1/W₀, where W₀ ≈ 1.02
//! (120 facets) is the width of the ball around the unit sphere, and tends to 1 as N grows.

use super::{Family, ParamDef, Params, Unit};
use crate::error::Result;
use crate::geometry::{DVec3, FacetPlane, Polyhedron};

const PARAMS: &[ParamDef] = &[ParamDef {
    key: "facets",
    default: 120.0,
    min: 20.0,
    max: 1000.0,
    open: false,
    unit: Unit::Count,
    doc: "number of facets (tangent planes) on the sphere",
}];

/// The sphere family.
pub const FAMILY: Family = Family {
    name: "sphere",
    doc: "faceted sphere: N planes tangent to a sphere at Fibonacci-spiral points, width 1",
    params: PARAMS,
    build,
};

fn build(p: &Params) -> Result<Vec<FacetPlane>> {
    let n = p.get("facets")? as usize;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let mut planes: Vec<FacetPlane> = (0..n)
        .map(|i| {
            let z = 1.0 - (2 * i + 1) as f64 / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * i as f64;
            let normal = DVec3::new(r * phi.cos(), r * phi.sin(), z);
            FacetPlane::new(normal, 0.5, format!("sphere-{}", i + 1), "sphere")
        })
        .collect();
    // Scale to width 1 (the unit convention).
    if let Ok(s) = Polyhedron::from_planes(&planes) {
        let w = super::units::outline_size(s.vertices()).1;
        if w.is_finite() && w > 0.0 {
            for p in &mut planes {
                p.plane.offset /= w;
            }
        }
    }
    Ok(planes)
}

#[cfg(test)]
mod tests {
    use crate::testkit::cuts::*;
    use std::f64::consts::PI;

    #[test]
    fn sphere_circumscribes_and_converges() {
        let c = ok("sphere", &[]);
        assert_eq!((c.solid.facets().len(), count(&c, "sphere")), (120, 120));
        let mut last = f64::INFINITY;
        for n in [20.0, 50.0, 200.0, 800.0] {
            let c = ok("sphere", &[("facets", n)]);
            // Width 1; the tangent sphere's radius r = the common offset.
            let (_, w) = crate::cut::units::outline_size(c.solid.vertices());
            assert!((w - 1.0).abs() < 1e-9, "{n}: width {w}");
            let r = c.solid.facets()[0].plane.offset;
            assert!(r < 0.5 && r > 0.4, "{n}: {r}");
            // Volume per tangent-sphere diameter cubed.
            let v = c.solid.volume() / (2.0 * r).powi(3);
            assert!(v > PI / 6.0, "{n}: {v}");
            assert!(
                v < last,
                "volume should shrink toward π/6 as facets grow: {n}: {v}"
            );
            last = v;
            // Tangent planes: every vertex is at least the radius away from the centre, every
            // facet touches the sphere (offset 1/2) and the solid stays centred on the girdle plane.
            assert!(c.solid.vertices().iter().all(|p| p.length() >= r - 1e-12));
            assert!(c
                .solid
                .facets()
                .iter()
                .all(|f| (f.plane.offset - r).abs() < 1e-12));
            assert!(c.solid.centroid().length() < 0.3 / n);
        }
        assert!(
            last - PI / 6.0 < 0.005 * PI / 6.0,
            "800 facets within 0.5 %: {last}"
        );
        out_of_range_named("sphere");
        assert!(cut("sphere", &[("facets", 100.5)])
            .unwrap_err()
            .to_string()
            .starts_with("facets:"));
    }
}
