//! The prepared stone: tracing a symmetry's fundamental wedge changes nothing, and the
//! exit-facet walk agrees with a scan.

use crate::beam::{BeamTree, Frame, Stone, TraceOptions};
use crate::geometry::clip2d;
use crate::testkit::{cube, octahedron, princess, tolkowsky};
use glam::DVec3;

/// Tracing a fundamental wedge and handing out each exit once per symmetry gives the same
/// light as tracing everything: with a finite exact tree (depth limit, no threshold) the two
/// agree to rounding in power, in where it goes and in its polarization.
#[test]
fn symmetry_reduction_changes_nothing() {
    assert_eq!(Stone::new(&tolkowsky()).symmetry_order(), 16);
    assert_eq!(Stone::new(&princess()).symmetry_order(), 8);
    assert_eq!(Stone::new(&octahedron()).symmetry_order(), 8);
    let mut v = std::collections::BTreeMap::new();
    v.insert("pavilion_angle".to_string(), 41.0);
    for (name, s) in [
        ("tolkowsky", tolkowsky()),
        ("princess", princess()),
        ("octahedron", octahedron()),
    ] {
        let stone = Stone::new(&s);
        let frames = [
            Frame::overhead(),
            // Tilted within a mirror plane of all three solids (the x–z plane): one mirror left.
            Frame::new(DVec3::new(0.3, 0.0, -1.0)).unwrap(),
            Frame::new(DVec3::new(0.3, 0.1, -1.0)).unwrap(),
        ];
        for frame in frames {
            for pol in [false, true] {
                let opts = TraceOptions {
                    max_depth: 4,
                    polarization: pol,
                    footprints: true,
                    ..TraceOptions::exact(0.0)
                };
                let full = stone.trace(
                    &frame,
                    2.4173,
                    589.3,
                    &TraceOptions {
                        symmetry: false,
                        ..opts
                    },
                );
                let sym = stone.trace(&frame, 2.4173, 589.3, &opts);
                assert!(
                    sym.balance().abs() < 1e-12 && (sym.stats.power_in - 1.0).abs() < 1e-12,
                    "{name}"
                );
                // Smooth test functions of direction and polarization.
                let moments = |t: &BeamTree| {
                    let mut m = [0.0; 8];
                    for e in &t.exits {
                        let d = e.direction;
                        let q = [1.0, d.x, d.y, d.z, d.x * d.y, d.z * d.z * d.x];
                        for (k, x) in q.iter().enumerate() {
                            m[k] += e.power * x;
                        }
                        // Degree of polarization (frame-independent).
                        m[6] += (e.stokes.y.powi(2) + e.stokes.z.powi(2)).sqrt();
                        m[7] += e.stokes.w.abs();
                    }
                    m
                };
                let (a, b) = (moments(&full), moments(&sym));
                for k in 0..8 {
                    assert!(
                        (a[k] - b[k]).abs() < 1e-12,
                        "{name} {frame:?} pol {pol} moment {k}: {} vs {}",
                        a[k],
                        b[k]
                    );
                }
                let area = |t: &BeamTree| {
                    (0..t.exits.len())
                        .filter(|&i| t.exits[i].external)
                        .map(|i| clip2d::area(t.footprint(i)))
                        .sum::<f64>()
                };
                assert!((area(&full) - area(&sym)).abs() < 1e-12);
            }
        }
    }
}

/// The facet walk finds the same exit as scanning every facet, from points on every facet in
/// many directions.
#[test]
fn exit_facet_walk_agrees_with_scan() {
    for s in [tolkowsky(), princess(), octahedron(), cube()] {
        let stone = Stone::new(&s);
        let mut k = 0u64;
        for f in 0..s.facets().len() {
            let poly = s.facet_polygon(f);
            let c = s.facets()[f].centroid;
            for (vi, v) in poly.iter().enumerate() {
                let x = c + (*v - c) * 0.9;
                for j in 0..12 {
                    k += 1;
                    // A deterministic spread of directions into the stone.
                    let a = (k as f64 * 2.399_963) % std::f64::consts::TAU;
                    let z = ((k * 7919 + vi as u64 * 31 + j) % 1000) as f64 / 500.0 - 1.0;
                    let t = DVec3::new(
                        (1.0 - z * z).sqrt() * a.cos(),
                        (1.0 - z * z).sqrt() * a.sin(),
                        z,
                    );
                    let t = if t.dot(s.facets()[f].plane.normal) > 0.0 {
                        -t
                    } else {
                        t
                    };
                    if t.dot(s.facets()[f].plane.normal) > -1e-3 {
                        continue;
                    }
                    let (gw, dw) = stone.exit_facet(x, t, f).unwrap();
                    let (gs, ds) = stone.exit_facet_scan(x, t, f).unwrap();
                    assert!(
                        (dw - ds).abs() < 1e-12,
                        "facet {f}: walk {gw} {dw} scan {gs} {ds}"
                    );
                }
            }
        }
    }
}

/// The facet table is filled lazily from a cell's index: each cell's central direction falls
/// in that very cell, so an entry is what a table filled cell by cell from the directions
/// held.
#[test]
fn every_cube_cell_holds_its_own_central_direction() {
    use crate::beam::stone::{cube_cell, cube_dir, CUBE_RES};
    for face in 0..6 {
        for i in 0..CUBE_RES {
            for j in 0..CUBE_RES {
                assert_eq!(
                    cube_cell(cube_dir(face, i, j)),
                    (face * CUBE_RES + i) * CUBE_RES + j,
                    "face {face} cell ({i}, {j})"
                );
            }
        }
    }
}
