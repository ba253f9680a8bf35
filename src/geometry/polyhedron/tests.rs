//! Tests of the polyhedron built from planes: volumes, topology and its errors.

use super::*;

use crate::testkit::{cube_planes, octahedron_planes};

#[test]
fn cube_volume_area_topology() {
    let p = Polyhedron::from_planes(&cube_planes(0.5)).unwrap();
    assert_eq!(p.vertices.len(), 8);
    assert_eq!(p.edges.len(), 12);
    assert!((p.volume() - 1.0).abs() < 1e-12);
    assert!((p.surface_area() - 6.0).abs() < 1e-12);
    assert!((p.projected_area(DVec3::new(1.0, 1.0, 1.0)) - 3f64.sqrt()).abs() < 1e-12);
    for f in &p.facets {
        assert_eq!(f.vertices.len(), 4);
        assert_eq!(
            p.neighbors(p.facets.iter().position(|g| g == f).unwrap())
                .len(),
            4
        );
    }
    assert!(p.centroid().length() < 1e-12);
}

#[test]
fn octahedron_euler_and_volume() {
    let planes = octahedron_planes(1.0);
    let p = Polyhedron::from_planes(&planes).unwrap();
    // |x|+|y|+|z| <= 1: volume 4/3, 6 vertices, 12 edges.
    assert_eq!(p.vertices.len(), 6);
    assert_eq!(p.edges.len(), 12);
    assert!((p.volume() - 4.0 / 3.0).abs() < 1e-12);
    assert_eq!(p.vertices.len() + p.facets.len(), p.edges.len() + 2);
}

#[test]
fn reports_redundant_unbounded_duplicate_empty() {
    let mut planes = cube_planes(0.5);
    planes.push(FacetPlane::new(DVec3::new(1.0, 1.0, 0.0), 5.0, "far", "x"));
    let e = Polyhedron::from_planes(&planes).unwrap_err().to_string();
    assert!(e.contains("far") && e.contains("never touches"), "{e}");

    let planes = cube_planes(0.5)[..5].to_vec();
    let e = Polyhedron::from_planes(&planes).unwrap_err().to_string();
    assert!(e.contains("unbounded"), "{e}");

    let mut planes = cube_planes(0.5);
    planes.push(planes[2].clone());
    let e = Polyhedron::from_planes(&planes).unwrap_err().to_string();
    assert!(e.contains("same plane"), "{e}");

    let mut planes = cube_planes(0.5);
    planes.push(FacetPlane::new(DVec3::Z, -0.7, "below", "x"));
    let e = Polyhedron::from_planes(&planes).unwrap_err().to_string();
    assert!(e.contains("empty"), "{e}");
}

#[test]
fn plane_through_a_vertex_only_is_reported() {
    let mut planes = cube_planes(0.5);
    planes.push(FacetPlane::new(
        DVec3::new(1.0, 1.0, 1.0),
        1.5,
        "corner",
        "x",
    ));
    let e = Polyhedron::from_planes(&planes).unwrap_err().to_string();
    assert!(e.contains("corner"), "{e}");
}

#[test]
fn hundreds_of_tangent_planes_in_azimuth_order() {
    // A sphere of tangent planes added ring by ring: many nearly-degenerate vertices.
    let mut planes = Vec::new();
    let rings = 24;
    for i in 0..rings {
        let z = -1.0 + (2.0 * i as f64 + 1.0) / rings as f64;
        let r = (1.0 - z * z).sqrt();
        let m = 40;
        for j in 0..m {
            let a = std::f64::consts::TAU * j as f64 / m as f64 + 0.1 * i as f64;
            let n = DVec3::new(r * a.cos(), r * a.sin(), z);
            planes.push(FacetPlane::new(n, 0.5, format!("s{i}-{j}"), "sphere"));
        }
    }
    planes.push(FacetPlane::new(DVec3::Z, 0.5, "top", "top"));
    planes.push(FacetPlane::new(DVec3::NEG_Z, 0.5, "bottom", "bottom"));
    let p = Polyhedron::from_planes(&planes).unwrap();
    assert_eq!(p.facets.len(), planes.len());
    assert_eq!(p.vertices.len() + p.facets.len(), p.edges.len() + 2);
    let ball = std::f64::consts::PI / 6.0;
    assert!(
        p.volume() > ball && p.volume() < ball * 1.05,
        "{}",
        p.volume()
    );
}

#[test]
fn truncated_cube_facets_are_outward_and_ccw() {
    let mut planes = cube_planes(0.5);
    planes.push(FacetPlane::new(
        DVec3::new(1.0, 1.0, 1.0),
        1.2,
        "corner",
        "x",
    ));
    let p = Polyhedron::from_planes(&planes).unwrap();
    assert_eq!(p.facets.len(), 7);
    for (i, f) in p.facets.iter().enumerate() {
        let poly = p.facet_polygon(i);
        assert!(area_vector(&poly).dot(f.plane.normal) > 0.0);
        for v in &poly {
            assert!(f.plane.distance(*v).abs() < 1e-9);
        }
    }
    // Cube minus the corner tetrahedron with legs 0.3.
    let legs: f64 = 1.5 - 1.2;
    assert!((p.volume() - (1.0 - legs.powi(3) / 6.0)).abs() < 1e-12);
    assert_eq!(p.vertices.len() + p.facets.len(), p.edges.len() + 2);
}
