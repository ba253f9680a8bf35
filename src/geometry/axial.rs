//! The symmetry of a solid about the z axis (through the origin): its rotation order and its
//! mirror lines, found from the facet planes (a turn or a mirror is a symmetry when it maps
//! every facet plane onto a facet plane). What a GemCad file's `y` line says and what a plan's
//! copies share.
//!
//! The candidates are read off one tilted facet: a symmetry maps it onto a facet of the same
//! tilt and distance, so the turns to try are the azimuth differences to those facets, and the
//! mirror lines the bisectors of their azimuths (each tried, smallest turn first).

use super::Polyhedron;
use glam::{DMat3, DVec3};
use std::f64::consts::{PI, TAU};

/// A solid's symmetry about the z axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxialSymmetry {
    /// Order of its rotations about z: it maps onto itself turned by 360°/`order` (1: none).
    pub order: u32,
    /// Azimuth (radians, in [0, π/order)) of one of its mirror planes through the z axis, if
    /// it has any; the others follow every π/`order`.
    pub mirror: Option<f64>,
}

impl AxialSymmetry {
    /// Whether the vertical plane at azimuth `phi` (radians) is one of its mirrors, to `tol`
    /// radians.
    pub fn mirrors_at(&self, phi: f64, tol: f64) -> bool {
        self.mirror.is_some_and(|m| {
            let step = PI / f64::from(self.order.max(1));
            let r = (phi - m).rem_euclid(step);
            r < tol || step - r < tol
        })
    }
}

/// Whether `m` maps every plane `(normal, offset)` onto one of them, within `tol` (normals and
/// offsets alike).
fn maps_onto_itself(planes: &[(DVec3, f64)], m: &DMat3, tol: f64) -> bool {
    planes.iter().all(|&(n, o)| {
        let mn = *m * n;
        planes
            .iter()
            .any(|&(q, p)| (q - mn).abs().max_element() <= tol && (p - o).abs() <= tol)
    })
}

/// The symmetry of `solid` about the z axis, planes compared to `tol` (1e-7 suits a design
/// read from a file: its rounded depths are good to ~1e-8 of the width).
pub fn axial_symmetry(solid: &Polyhedron, tol: f64) -> AxialSymmetry {
    let planes: Vec<(DVec3, f64)> = solid
        .facets()
        .iter()
        .map(|f| (f.plane.normal, f.plane.offset))
        .collect();
    // The most tilted facet away from the axis has the fewest look-alikes' rounding issues.
    let Some(&(n0, o0)) = planes
        .iter()
        .filter(|(n, _)| n.truncate().length() > 1e-6)
        .max_by(|a, b| a.0.truncate().length().total_cmp(&b.0.truncate().length()))
    else {
        // Only horizontal facets: no tilted facet to read a symmetry from.
        return AxialSymmetry {
            order: 1,
            mirror: None,
        };
    };
    let a0 = n0.y.atan2(n0.x);
    let alike: Vec<f64> = planes
        .iter()
        .filter(|(n, o)| (n.z - n0.z).abs() <= tol && (o - o0).abs() <= tol)
        .map(|(n, _)| n.y.atan2(n.x))
        .collect();
    // The smallest turn that maps the solid onto itself generates its rotations.
    let mut turns: Vec<f64> = alike
        .iter()
        .map(|a| (a - a0).rem_euclid(TAU))
        .filter(|t| *t > 1e-6 && *t < TAU - 1e-6)
        .collect();
    turns.sort_by(f64::total_cmp);
    let order = turns
        .iter()
        .find(|&&t| maps_onto_itself(&planes, &DMat3::from_rotation_z(t), tol))
        .map_or(1, |t| (TAU / t).round().max(1.0) as u32);
    let step = PI / f64::from(order);
    let mirror = alike
        .iter()
        .map(|a| (0.5 * (a0 + a)).rem_euclid(step))
        .find(|&phi| maps_onto_itself(&planes, &mirror_at(phi), tol));
    AxialSymmetry { order, mirror }
}

/// The reflection across the vertical plane at azimuth `phi`.
fn mirror_at(phi: f64) -> DMat3 {
    let (s, c) = (2.0 * phi).sin_cos();
    DMat3::from_cols(DVec3::new(c, s, 0.0), DVec3::new(s, -c, 0.0), DVec3::Z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::FacetPlane;

    /// A pyramid frustum: `k` sides at azimuths `start + j·360°/k`, with a table and a base.
    fn prism(k: usize, start: f64, extra: Option<f64>) -> Polyhedron {
        let mut planes = vec![
            FacetPlane::new(DVec3::Z, 0.3, "t", "t"),
            FacetPlane::new(-DVec3::Z, 0.5, "b", "b"),
        ];
        for j in 0..k {
            let a = start + TAU * j as f64 / k as f64;
            let n = DVec3::new(a.cos(), a.sin(), 0.6);
            planes.push(FacetPlane::new(n, 0.5 * n.length(), format!("s{j}"), "s"));
        }
        if let Some(a) = extra {
            planes.push(FacetPlane::new(
                DVec3::new(a.cos(), a.sin(), 0.0),
                0.48,
                "x",
                "x",
            ));
        }
        Polyhedron::from_planes(&planes).unwrap()
    }

    #[test]
    fn orders_and_mirrors_of_regular_frusta() {
        for k in [3usize, 4, 5, 8, 16] {
            let s = axial_symmetry(&prism(k, 0.0, None), 1e-9);
            assert_eq!(s.order, k as u32, "{k}");
            // A regular k-gon has mirrors through its sides' normals: azimuth 0 is one.
            assert!(s.mirrors_at(0.0, 1e-9), "{k}: {s:?}");
            assert!(s.mirrors_at(PI / k as f64, 1e-9), "{k}: {s:?}");
            assert!(
                !s.mirrors_at(PI / (2 * k) as f64 + 0.01, 1e-9),
                "{k}: {s:?}"
            );
        }
        // Turned by 10°: the mirrors turn with it.
        let s = axial_symmetry(&prism(8, 10f64.to_radians(), None), 1e-9);
        assert_eq!(s.order, 8);
        assert!(s.mirrors_at(10f64.to_radians(), 1e-9));
        assert!(!s.mirrors_at(0.0, 1e-6));
    }

    #[test]
    fn a_cut_facet_breaks_the_symmetry_it_breaks() {
        // An extra vertical facet at azimuth 0 keeps only the mirror through it.
        let s = axial_symmetry(&prism(8, 0.0, Some(0.0)), 1e-9);
        assert_eq!(s.order, 1);
        assert!(s.mirrors_at(0.0, 1e-9) && s.mirrors_at(PI, 1e-9));
        assert!(!s.mirrors_at(PI / 2.0, 1e-6));
        // At 5°, between the sides' mirrors: no symmetry left.
        let s = axial_symmetry(&prism(8, 0.0, Some(5f64.to_radians())), 1e-9);
        assert_eq!((s.order, s.mirror), (1, None));
    }
}
