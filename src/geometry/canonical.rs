//! The canonical placement of a solid for scoring, which makes every score depend on the
//! solid only, not on how it is written down.
//!
//! The same stone can reach `metrics::score` as different lists of numbers: moved or scaled
//! (an OBJ exported in millimetres, a design not centred on the girdle), rotated onto itself
//! by one of its symmetries (a round brilliant turned by 45°, or by 90° through a coordinate
//! swap in an OBJ), or with its facets in another order. The tracer's work depends on those
//! numbers in small ways: the fundamental wedge it traces for a symmetric stone starts at a
//! facet it finds first, narrow beams fall differently on differently split beams, and its
//! thresholds are absolute lengths. [`canonical`] therefore rebuilds the solid from its facet
//! planes after three normalisations:
//!
//! * **translation**: the volume centroid goes to the origin (it lies on every symmetry axis);
//! * **scale**: lengths are divided by the diameter of the circle with the face-up outline's
//!   area, so a stone scores the same in any unit (scores are ratios; only the tracer's
//!   absolute tolerances ever saw the size);
//! * **rounding**: normals and offsets are rounded to multiples of 2⁻³⁶ (about 1.5e-11), so
//!   the same solid reached through different arithmetic (a rotated copy whose normals came
//!   from other sines and cosines, a centroid computed from other vertices) becomes the very
//!   same numbers and traces identically;
//! * **facet order**: facets are sorted by a key that is the same for the same set of planes
//!   (tilt, distance from the centroid, azimuth), so the tracer's first facet — and the
//!   symmetry wedge it derives from it — is the same facet of the same solid;
//!
//! Rounding also settles the tracer's choice of symmetry wedge: cuts are drawn with mirror
//! lines on azimuth 0, and the tracer reduces a mirror's azimuth modulo the symmetry's angle;
//! a mirror at ±1e-17 lands on either end of that range and gives one of two wedges (the same
//! light, split differently, so the narrow-beam approximation differed by up to 1e-4).
//! Rounded, a normal on azimuth 0 has a y component of exactly 0.
//!
//! The stone is not turned about its axis: turning it is a different pose (see the module
//! documentation of `metrics` for how the scores average over turning). (Turning it by half
//! a degree away from its mirror lines was tried: it doubled the time of a score.)

use crate::geometry::{FacetPlane, Polyhedron};
use glam::DVec3;

/// Quantum of the sort keys (relative to the canonical size, and radians).
const QUANTUM: f64 = 1e-7;

/// Grid the canonical normals and offsets are rounded to.
const GRID: f64 = 1.0 / (1u64 << 36) as f64;

/// The solid moved, scaled, rounded and with its facets ordered as described in the module
/// documentation; the solid itself (cloned) when it is degenerate.
pub fn canonical(solid: &Polyhedron) -> Polyhedron {
    let c = solid.centroid();
    let area = solid.projected_area(DVec3::Z);
    let size = (4.0 * area / std::f64::consts::PI).sqrt();
    if !(c.is_finite() && size.is_finite() && size > 0.0) {
        return solid.clone();
    }
    let k = 1.0 / size;
    let grid = |x: f64| (x / GRID).round() * GRID;
    let mut keyed: Vec<((i64, i64, i64), FacetPlane)> = solid
        .facet_planes()
        .into_iter()
        .map(|mut f| {
            let n = f.plane.normal;
            let offset = grid((f.plane.offset - n.dot(c)) * k);
            let n = DVec3::new(grid(n.x), grid(n.y), grid(n.z)).normalize();
            f.plane.normal = n;
            f.plane.offset = offset;
            (sort_key(n, offset), f)
        })
        .collect();
    keyed.sort_by_key(|k| k.0);
    let planes: Vec<FacetPlane> = keyed.into_iter().map(|(_, f)| f).collect();
    Polyhedron::from_planes(&planes).unwrap_or_else(|_| solid.clone())
}

/// Quantised (tilt, offset, azimuth in [0, 2π)) of a facet plane; an azimuth a hair below 2π
/// counts as 0, and so does the azimuth of a horizontal facet.
fn sort_key(n: DVec3, offset: f64) -> (i64, i64, i64) {
    let q = |x: f64| (x / QUANTUM).round() as i64;
    let full = q(std::f64::consts::TAU);
    let az = if n.truncate().length() < 1e-9 {
        0
    } else {
        q(n.y.atan2(n.x).rem_euclid(std::f64::consts::TAU)) % full
    };
    (q(n.z), q(offset), az)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::tolkowsky;

    #[test]
    fn canonical_solid_is_centred_unit_and_keeps_its_shape() {
        let s = tolkowsky();
        let moved = s.scaled(3.0);
        let c = canonical(&moved);
        assert!(c.centroid().length() < 1e-10, "{:?}", c.centroid());
        let d = (4.0 * c.projected_area(DVec3::Z) / std::f64::consts::PI).sqrt();
        assert!((d - 1.0).abs() < 1e-10, "{d}");
        assert_eq!(c.facets().len(), s.facets().len());
        // Same shape: volumes in the ratio of the cubed scales.
        let d0 = (4.0 * s.projected_area(DVec3::Z) / std::f64::consts::PI).sqrt();
        assert!((c.volume() * d0.powi(3) - s.volume()).abs() < 1e-10);
        // Sorted by tilt: the first facet is one facing most nearly straight down.
        let lowest = s
            .facets()
            .iter()
            .map(|f| f.plane.normal.z)
            .fold(1.0, f64::min);
        assert!((c.facets()[0].plane.normal.z - lowest).abs() < 1e-9);
    }
}
