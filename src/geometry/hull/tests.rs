use super::merge::{cluster, dedupe, spans_a_facet};
use super::*;
use crate::geometry::{FacetPlane, Polyhedron};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use std::collections::HashMap;

fn solid(planes: &[Plane]) -> Polyhedron {
    let fps: Vec<FacetPlane> = planes
        .iter()
        .enumerate()
        .map(|(i, p)| FacetPlane {
            plane: *p,
            name: format!("h{i}"),
            tier: "h".into(),
        })
        .collect();
    Polyhedron::from_planes(&fps).unwrap()
}

#[test]
fn random_points_in_a_cube_give_six_facets() {
    let mut rng = SmallRng::seed_from_u64(7);
    let mut pts: Vec<DVec3> = (0..2000)
        .map(|_| DVec3::new(rng.random(), rng.random(), rng.random()))
        .collect();
    for k in 0..8 {
        pts.push(DVec3::new(
            (k & 1) as f64,
            ((k >> 1) & 1) as f64,
            ((k >> 2) & 1) as f64,
        ));
    }
    // Shuffle the corners in among the rest.
    for i in (1..pts.len()).rev() {
        pts.swap(i, rng.random_range(0..=i));
    }
    let planes = convex_hull(&pts).unwrap();
    assert_eq!(planes.len(), 6);
    let s = solid(&planes);
    assert!((s.volume() - 1.0).abs() < 1e-12, "volume {}", s.volume());
    assert_eq!(s.vertices().len(), 8);
}

#[test]
fn cube_triangles_merge_and_points_on_faces_are_ignored() {
    // Corners plus points on faces and edges (coplanar with the hull): still 6 facets.
    let mut pts = Vec::new();
    for i in 0..=4 {
        for j in 0..=4 {
            for k in 0..=4 {
                pts.push(DVec3::new(i as f64, j as f64, k as f64) * 0.25 - 3.0);
            }
        }
    }
    let planes = convex_hull(&pts).unwrap();
    assert_eq!(planes.len(), 6);
    assert!((solid(&planes).volume() - 1.0).abs() < 1e-12);
}

#[test]
fn round_brilliant_vertices_rebuild_the_same_solid() {
    let cut = crate::cut::Cut::from_family("rb", "round-brilliant", &Default::default()).unwrap();
    let planes = convex_hull(cut.solid.vertices()).unwrap();
    assert_eq!(planes.len(), cut.solid.facets().len());
    let s = solid(&planes);
    assert!(
        (s.volume() - cut.solid.volume()).abs() < 1e-9,
        "{} vs {}",
        s.volume(),
        cut.solid.volume()
    );
    for f in cut.solid.facets() {
        let best = planes
            .iter()
            .map(|p| p.normal.distance(f.plane.normal) + (p.offset - f.plane.offset).abs())
            .fold(f64::INFINITY, f64::min);
        assert!(best < 1e-9, "{} off by {best}", f.name);
    }
}

#[test]
fn degenerate_inputs_are_errors() {
    let e = convex_hull(&[DVec3::ZERO, DVec3::X, DVec3::Y])
        .unwrap_err()
        .to_string();
    assert!(e.contains("at least 4"), "{e}");
    let flat: Vec<DVec3> = (0..10)
        .map(|i| DVec3::new(i as f64, (i * i) as f64, 0.0))
        .collect();
    let e = convex_hull(&flat).unwrap_err().to_string();
    assert!(e.contains("one plane"), "{e}");
    let line: Vec<DVec3> = (0..10).map(|i| DVec3::splat(i as f64)).collect();
    assert!(convex_hull(&line)
        .unwrap_err()
        .to_string()
        .contains("one line"));
    assert!(convex_hull(&[DVec3::ONE; 5])
        .unwrap_err()
        .to_string()
        .contains("coincide"));
    let mut bad = flat.clone();
    bad[3].z = f64::NAN;
    assert!(convex_hull(&bad)
        .unwrap_err()
        .to_string()
        .contains("point 4"));
}

#[test]
fn every_point_is_inside_every_plane() {
    let mut rng = SmallRng::seed_from_u64(3);
    // Points on a sphere: many facets, all hull points.
    let pts: Vec<DVec3> = (0..1000)
        .map(|_| {
            let v = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            v.normalize_or(DVec3::X) * 5.0 + DVec3::new(100.0, -40.0, 7.0)
        })
        .collect();
    let planes = convex_hull(&pts).unwrap();
    for p in &planes {
        for q in &pts {
            assert!(p.distance(*q) <= 1e-12 * 100.0);
        }
    }
    let s = solid(
        &planes
            .iter()
            .map(|p| Plane {
                normal: p.normal,
                offset: p.offset - p.normal.dot(DVec3::new(100.0, -40.0, 7.0)),
            })
            .collect::<Vec<_>>(),
    );
    // A sphere of radius 5 sampled with 3000 points holds most of its volume.
    let v = s.volume() / (4.0 / 3.0 * std::f64::consts::PI * 125.0);
    assert!(v > 0.97 && v < 1.0, "{v}");
}

/// A random polytope (planes tangent to a sphere), sampled by its vertices, points on its
/// facets and points inside, optionally disturbed; returns the solid and the points.
fn sampled_polytope(seed: u64, mode: u64) -> Option<(Polyhedron, Vec<DVec3>, f64)> {
    let mut rng = SmallRng::seed_from_u64(seed);
    let unit = |rng: &mut SmallRng| {
        DVec3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        )
    };
    let planes: Vec<FacetPlane> = (0..rng.random_range(8..80))
        .map(|i| {
            FacetPlane::new(
                unit(&mut rng).normalize_or(DVec3::X),
                0.4,
                format!("p{i}"),
                "t",
            )
        })
        .collect();
    let solid = Polyhedron::from_planes(&planes).ok()?;
    let mut pts: Vec<DVec3> = solid.vertices().to_vec();
    for i in 0..solid.facets().len() {
        let poly = solid.facet_polygon(i);
        for _ in 0..rng.random_range(0..30) {
            let w: Vec<f64> = poly.iter().map(|_| rng.random::<f64>()).collect();
            let total: f64 = w.iter().sum();
            pts.push(poly.iter().zip(&w).map(|(p, w)| *p * *w).sum::<DVec3>() / total);
        }
    }
    let c = solid.centroid();
    for _ in 0..200 {
        let v = solid.vertices()[rng.random_range(0..solid.vertices().len())];
        pts.push(c + (v - c) * rng.random_range(0.0..0.99));
    }
    let tol = match mode {
        // Exact.
        0 => 1e-7,
        // Jitter of 1e-9: coplanar points are no longer coplanar.
        1 => {
            for p in &mut pts {
                *p += unit(&mut rng) * 1e-9;
            }
            1e-7
        }
        // Single precision, as in binary STL.
        2 => {
            for p in &mut pts {
                *p = p.as_vec3().as_dvec3();
            }
            1e-6
        }
        // Five decimals, as in a coarse text export.
        _ => {
            for p in &mut pts {
                *p = (*p * 1e5).round() / 1e5;
            }
            1e-4
        }
    };
    for i in (1..pts.len()).rev() {
        pts.swap(i, rng.random_range(0..=i));
    }
    Some((solid, pts, tol))
}

#[test]
fn random_polytopes_are_rebuilt_from_noisy_samples() {
    let mut worst = [0.0f64; 4];
    let mut cases = 0;
    for seed in 0..160u64 {
        let mode = seed % 4;
        let Some((truth, pts, tol)) = sampled_polytope(seed, mode) else {
            continue;
        };
        cases += 1;
        let planes =
            convex_hull_with_tolerance(&pts, tol).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        assert_eq!(
            planes.len(),
            truth.facets().len(),
            "seed {seed} mode {mode}"
        );
        for f in truth.facets() {
            let off = planes
                .iter()
                .map(|p| {
                    p.normal
                        .distance(f.plane.normal)
                        .max((p.offset - f.plane.offset).abs())
                })
                .fold(f64::INFINITY, f64::min);
            worst[mode as usize] = worst[mode as usize].max(off);
        }
        let dv = (solid(&planes).volume() - truth.volume()).abs();
        assert!(
            dv < 100.0 * tol,
            "seed {seed} mode {mode}: volume off by {dv:e}"
        );
    }
    assert!(cases > 100);
    // Planes as good as the data: exact, 1e-9 jitter, f32, five decimals.
    assert!(
        worst[0] < 1e-12 && worst[1] < 1e-7 && worst[2] < 1e-5 && worst[3] < 1e-3,
        "{worst:?}"
    );
}

#[test]
fn a_facet_must_be_a_polygon() {
    let square = |s: f64| -> Vec<DVec3> {
        vec![
            DVec3::ZERO,
            DVec3::X * s,
            DVec3::new(s, s, 0.0),
            DVec3::Y * s,
            DVec3::new(0.3, 0.2, -1.0),
        ]
    };
    assert!(spans_a_facet(&square(1.0), DVec3::Z, 0.0, 1e-7));
    assert!(!spans_a_facet(&square(1e-6), DVec3::Z, 0.0, 1e-7));
    // Points along a line only.
    let line: Vec<DVec3> = (0..5).map(|i| DVec3::X * i as f64).collect();
    assert!(!spans_a_facet(&line, DVec3::Z, 0.0, 1e-7));
}

#[test]
fn jittered_cube_surface_gives_six_facets() {
    let mut rng = SmallRng::seed_from_u64(5);
    for jitter in [0.0, 1e-13, 1e-11, 1e-9, 1e-8] {
        let mut pts = Vec::new();
        for i in 0..=20 {
            for j in 0..=20 {
                for k in 0..=20 {
                    if [i, j, k].iter().any(|&c| c == 0 || c == 20) {
                        let d = DVec3::new(
                            rng.random_range(-1.0..1.0),
                            rng.random_range(-1.0..1.0),
                            rng.random_range(-1.0..1.0),
                        );
                        pts.push(DVec3::new(i as f64, j as f64, k as f64) / 20.0 + d * jitter);
                    }
                }
            }
        }
        let planes = convex_hull(&pts).unwrap();
        assert_eq!(planes.len(), 6, "jitter {jitter}");
        assert!((solid(&planes).volume() - 1.0).abs() < 1e-7);
    }
}

/// The merge before issue 36, kept as a brute-force reference: each facet's offset is the
/// largest `normal · p` over every point, and the points within `tol` of its plane are found
/// by scanning them all (O(points × facets)). The facets are the merge's own (grown over
/// shared edges and joined, `merge::cluster`), so what it checks is the merge's fast offsets
/// and flatness: the climb over the hull's edges and the walk from the top vertex.
fn reference_merge(pts: &[DVec3], tris: &[Face], tol: f64) -> Vec<(DVec3, f64)> {
    let mut c = cluster(pts, tris, tol);
    let mut joined: HashMap<usize, DVec3> = HashMap::new();
    let mut roots: Vec<usize> = Vec::new();
    for i in 0..c.clusters.len() {
        let r = c.root(i);
        let e = joined.entry(r).or_insert_with(|| {
            roots.push(r);
            DVec3::ZERO
        });
        *e += c.clusters[i].area;
    }
    let planes: Vec<(DVec3, f64)> = roots
        .into_iter()
        .filter_map(|r| {
            let n = joined[&r].try_normalize().unwrap_or(c.clusters[r].n);
            let d = pts
                .iter()
                .map(|p| n.dot(*p))
                .fold(f64::NEG_INFINITY, f64::max);
            // A facet is a polygon resting on the points; a plane that touches them only in a
            // point or along an edge is a sliver of rounding, and dropping it changes nothing.
            spans_a_facet(pts, n, d, tol).then_some((n, d))
        })
        .collect();
    dedupe(planes, tol)
}

/// [`hull`] with the reference merge: the same normalisation and triangles, every facet's
/// offset and flatness from all the points.
fn reference_hull(points: &[DVec3], tol: f64) -> Vec<Plane> {
    let (mut lo, mut hi) = (points[0], points[0]);
    for p in points {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let size = (hi - lo).max_element();
    let centre = 0.5 * (lo + hi);
    let pts: Vec<DVec3> = points.iter().map(|p| (*p - centre) / size).collect();
    let tris = quickhull(&pts, tol, None).unwrap();
    reference_merge(&pts, &tris.faces, tol)
        .into_iter()
        .map(|(n, d)| Plane {
            normal: n,
            offset: d * size + n.dot(centre),
        })
        .collect()
}

/// Point sets of the tests: every preset's vertices, the example rough's, points on a sphere,
/// and sampled polytopes (exact, jittered, single precision, five decimals).
fn test_meshes() -> Vec<(String, Vec<DVec3>, f64)> {
    let mut out = Vec::new();
    for name in crate::io::presets::names() {
        let cut = crate::io::presets::load(name).unwrap().unwrap();
        out.push((name.to_string(), cut.solid.vertices().to_vec(), MERGE_TOL));
    }
    for n in [4, 8, 16] {
        let rough = crate::plan::sample::distorted_octahedron(n);
        out.push((format!("example rough n = {n}"), rough.vertices, 1e-6));
    }
    let mut rng = SmallRng::seed_from_u64(11);
    let sphere: Vec<DVec3> = (0..3000)
        .map(|_| {
            let v = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            v.normalize_or(DVec3::X) * 3.0 + DVec3::new(1.0, 2.0, -3.0)
        })
        .collect();
    out.push(("sphere".into(), sphere, MERGE_TOL));
    for seed in 0..40u64 {
        if let Some((_, pts, tol)) = sampled_polytope(seed, seed % 4) {
            out.push((format!("polytope {seed}"), pts, tol));
        }
    }
    out
}

#[test]
fn the_linear_merge_gives_the_reference_merges_planes() {
    let mut worst = 0.0f64;
    for (name, pts, tol) in test_meshes() {
        let fast = hull(
            &pts,
            HullOptions {
                merge_tol: tol,
                max_vertices: None,
            },
        )
        .unwrap();
        let slow = reference_hull(&pts, tol);
        assert_eq!(fast.planes.len(), slow.len(), "{name}");
        assert_eq!(fast.left_out, 0.0, "{name}");
        let (lo, hi) = pts.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let size = (hi - lo).max_element();
        for (a, b) in fast.planes.iter().zip(&slow) {
            // Same order, same normal; the offset from the vertices and the points left on
            // the facets rather than from every point: within half the tolerance, in fact
            // equal to rounding.
            assert_eq!(a.normal, b.normal, "{name}");
            let off = (a.offset - b.offset).abs() / size;
            assert!(off <= 0.5 * tol, "{name}: offset off by {off:e}");
            worst = worst.max(off);
        }
    }
    // Points inside a facet's triangles that rounding lifts above the merged plane.
    assert!(worst < 1e-13, "offsets equal to rounding: {worst:e}");
}

#[test]
fn a_hull_stopped_at_a_budget_lies_inside_and_says_what_it_leaves_out() {
    let mut rng = SmallRng::seed_from_u64(5);
    // An ellipsoid sampled as a scan would be: every point a vertex of the full hull.
    let pts: Vec<DVec3> = (0..4_000)
        .map(|_| {
            let v = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
            .normalize_or(DVec3::X);
            DVec3::new(4.0 * v.x, 3.3 * v.y, 2.6 * v.z)
        })
        .collect();
    let full = hull(&pts, HullOptions::default()).unwrap();
    assert_eq!(full.vertices, pts.len());
    let full_volume = solid(&full.planes).volume();
    let mut last = f64::INFINITY;
    for budget in [100, 400, 1600] {
        let h = hull(
            &pts,
            HullOptions {
                max_vertices: Some(budget),
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(h.vertices, budget);
        // Brute force: the farthest point outside the planes.
        let brute = pts
            .iter()
            .map(|p| h.planes.iter().map(|q| q.distance(*p)).fold(0.0, f64::max))
            .fold(0.0, f64::max);
        assert!(
            (h.left_out - brute).abs() <= 1e-9 * brute,
            "{budget}: reported {} against {brute}",
            h.left_out
        );
        assert!(h.left_out < last, "{budget}");
        last = h.left_out;
        // Inside the full hull: its volume is smaller, by about the area times what is left out.
        let v = solid(&h.planes).volume();
        assert!(v < full_volume, "{budget}");
        assert!(
            full_volume - v < 120.0 * h.left_out,
            "{budget}: {v} {full_volume}"
        );
    }
}
