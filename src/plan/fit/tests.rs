//! The containment program against a bisection on the scale with a brute-force containment
//! check (issue 26's check 3).

use super::*;
use crate::cut::Cut;
use crate::geometry::convex_hull;
use glam::DQuat;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::collections::BTreeMap;

/// Whether some translation puts `s·v_i + t` inside every plane, checked over every pair of
/// vertex and plane: the feasible translations are `n_j·t <= c_j` with `c_j` the smallest
/// `d_j − s·n_j·v_i` over all vertices; that region, bounded, is non-empty exactly when one of
/// its corners (three planes meeting) satisfies every pair.
fn fits(rough: &[Plane], verts: &[DVec3], s: f64, tol: f64) -> bool {
    let c: Vec<f64> = rough
        .iter()
        .map(|p| {
            verts
                .iter()
                .map(|v| p.offset - s * p.normal.dot(*v))
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    let m = rough.len();
    for i in 0..m {
        for j in i + 1..m {
            for k in j + 1..m {
                let (a, b, cc) = (rough[i].normal, rough[j].normal, rough[k].normal);
                let det = a.dot(b.cross(cc));
                if det.abs() < 1e-9 {
                    continue;
                }
                let t = (c[i] * b.cross(cc) + c[j] * cc.cross(a) + c[k] * a.cross(b)) / det;
                let ok = rough.iter().all(|p| {
                    verts
                        .iter()
                        .all(|v| p.normal.dot(s * *v + t) <= p.offset + tol)
                });
                if ok {
                    return true;
                }
            }
        }
    }
    false
}

fn random_rough(rng: &mut SmallRng, n: usize) -> Vec<Plane> {
    let pts: Vec<DVec3> = (0..n)
        .map(|_| {
            DVec3::new(
                rng.random_range(-4.0..4.0),
                rng.random_range(-3.0..3.0),
                rng.random_range(-2.0..2.5),
            )
        })
        .collect();
    convex_hull(&pts).unwrap()
}

fn random_turn(rng: &mut SmallRng) -> DQuat {
    let q = DQuat::from_xyzw(
        rng.random_range(-1.0..1.0),
        rng.random_range(-1.0..1.0),
        rng.random_range(-1.0..1.0),
        rng.random_range(-1.0..1.0),
    );
    q.normalize()
}

#[test]
fn scale_matches_a_bisection_with_brute_force_containment() {
    let mut rng = SmallRng::seed_from_u64(26);
    let cuts: Vec<Cut> = ["round-brilliant", "princess", "pear", "emerald"]
        .iter()
        .map(|f| Cut::from_family(f, f, &BTreeMap::new()).unwrap())
        .collect();
    for case in 0..12 {
        let rough = random_rough(&mut rng, 14);
        let turn = random_turn(&mut rng);
        let cut = &cuts[case % cuts.len()];
        let verts: Vec<DVec3> = cut.solid.vertices().iter().map(|v| turn * *v).collect();
        let inside = rough_centre(&rough);
        let fit = largest_copy(&rough, &verts, inside).unwrap();
        // The answer fits (every vertex inside every plane).
        for p in &rough {
            for v in &verts {
                assert!(
                    p.distance(fit.scale * *v + fit.shift) <= 1e-9,
                    "case {case}"
                );
            }
        }
        // Bisection on s with the brute-force check.
        let (mut lo, mut hi) = (0.0, 20.0);
        assert!(!fits(&rough, &verts, hi, 1e-12));
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if fits(&rough, &verts, mid, 1e-12) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        assert!(
            (fit.scale - lo).abs() <= 1e-9 * lo.max(1.0),
            "case {case} ({}): program {} vs bisection {lo}",
            cut.name,
            fit.scale
        );
    }
}

/// The mean of the rough's corners (inside it).
fn rough_centre(rough: &[Plane]) -> DVec3 {
    let fps: Vec<crate::geometry::FacetPlane> = rough
        .iter()
        .enumerate()
        .map(|(i, p)| crate::geometry::FacetPlane {
            plane: *p,
            name: format!("r{i}"),
            tier: "r".into(),
        })
        .collect();
    crate::geometry::Polyhedron::from_planes(&fps)
        .unwrap()
        .centroid()
}

#[test]
fn a_cube_in_a_cube_fills_it() {
    // A unit cube inside a cube of side 3 centred at (1, 2, 3): scale 3, shift the centre.
    let rough: Vec<Plane> = [DVec3::X, DVec3::Y, DVec3::Z]
        .iter()
        .flat_map(|n| {
            let c = DVec3::new(1.0, 2.0, 3.0).dot(*n);
            [
                Plane::new(*n, c + 1.5).unwrap(),
                Plane::new(-*n, -c + 1.5).unwrap(),
            ]
        })
        .collect();
    let verts: Vec<DVec3> = (0..8)
        .map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
        .collect();
    let fit = largest_copy(&rough, &verts, DVec3::new(1.0, 2.0, 3.0)).unwrap();
    assert!((fit.scale - 3.0).abs() < 1e-12, "{fit:?}");
    assert!(
        (fit.shift - DVec3::new(-0.5, 0.5, 1.5)).length() < 1e-12,
        "{fit:?}"
    );
}

/// Constraint generation ([`Containment`]) gives the whole program's scale in roughs of many
/// planes (a scanned pebble's hull, thousands of planes, and random roughs), and its copy lies
/// inside every plane, in every orientation tried.
#[test]
fn containment_by_constraint_generation_is_the_whole_programs() {
    let mut rng = SmallRng::seed_from_u64(36);
    let cuts: Vec<Cut> = ["round-brilliant", "princess", "pear", "emerald", "marquise"]
        .iter()
        .map(|f| Cut::from_family(f, f, &BTreeMap::new()).unwrap())
        .collect();
    let pebble = crate::plan::Rough::from_trimesh(
        "pebble",
        "pebble",
        crate::plan::sample::scanned_pebble(24, 3),
        None,
    )
    .unwrap();
    let mut roughs = vec![pebble.solid.clone()];
    for _ in 0..4 {
        let planes = random_rough(&mut rng, 300);
        let fps: Vec<crate::geometry::FacetPlane> = planes
            .iter()
            .enumerate()
            .map(|(i, p)| crate::geometry::FacetPlane {
                plane: *p,
                name: format!("r{i}"),
                tier: "r".into(),
            })
            .collect();
        roughs.push(crate::geometry::Polyhedron::from_planes(&fps).unwrap());
    }
    assert!(
        roughs[0].facets().len() > 2000,
        "{}",
        roughs[0].facets().len()
    );
    for (r, rough) in roughs.iter().enumerate() {
        let c = Containment::new(rough);
        for case in 0..10 {
            let turn = random_turn(&mut rng);
            let cut = &cuts[case % cuts.len()];
            let verts: Vec<DVec3> = cut.solid.vertices().iter().map(|v| turn * *v).collect();
            let whole = largest_copy(c.planes(), &verts, rough.centroid()).unwrap();
            let fast = c.largest_copy(&verts).unwrap();
            assert!(
                (fast.scale - whole.scale).abs() <= 1e-10 * whole.scale,
                "rough {r} case {case}: {} vs {}",
                fast.scale,
                whole.scale
            );
            for p in c.planes() {
                for v in &verts {
                    assert!(p.distance(fast.scale * *v + fast.shift) <= 1e-9);
                }
            }
        }
    }
}
