//! Powers recomputed from first principles: every exit's footprint times the Fresnel factors
//! along its facet sequence, and the cube at normal incidence in closed form.

use super::{dirs, solids};
use crate::beam::{Frame, Stone, TraceOptions};
use crate::geometry::clip2d;
use crate::optics::{fresnel, reflect, refract};
use crate::testkit::cube;

/// Children tile their parents, and every exit's power is its footprint's share of the
/// stone's cross-section times the Fresnel factors along its facet sequence (recomputed here
/// from the sequence alone, unpolarized).
#[test]
fn footprints_times_path_fresnel_give_powers() {
    for (name, s) in solids() {
        let stone = Stone::new(&s);
        for frame in dirs() {
            let ri = 2.4173;
            let opts = TraceOptions {
                polarization: false,
                footprints: true,
                ..Default::default()
            };
            let tree = stone.trace(&frame, ri, 589.3, &opts);
            let mut external_area = 0.0;
            for (i, e) in tree.exits.iter().enumerate() {
                let fp = tree.footprint(i);
                let a = clip2d::area(fp);
                let seq = tree.sequence(e);
                assert_eq!(seq[0], e.entry_facet);
                assert_eq!(*seq.last().unwrap(), e.exit_facet);
                assert_eq!(
                    seq.len(),
                    if e.external {
                        1
                    } else {
                        e.reflections as usize + 2
                    }
                );
                let d0 = frame.dir;
                let n0 = s.facets()[seq[0]].plane.normal;
                let r0 = fresnel(-n0.dot(d0), 1.0, ri).reflectance();
                let expected = if e.external {
                    external_area += a;
                    a / tree.stats.area * r0
                } else {
                    let mut t = refract(d0, n0, 1.0, ri).unwrap();
                    let mut k = a / tree.stats.area * (1.0 - r0);
                    for (j, &f) in seq.iter().enumerate().skip(1) {
                        let n = s.facets()[f].plane.normal;
                        let r = fresnel(n.dot(t), ri, 1.0).reflectance();
                        if j + 1 == seq.len() {
                            k *= 1.0 - r;
                            let out = refract(t, n, ri, 1.0).unwrap();
                            assert!((out - e.direction).length() < 1e-9, "{name}");
                        } else {
                            k *= r;
                            t = reflect(t, n);
                        }
                    }
                    k
                };
                assert!(
                    (e.power - expected).abs() <= 1e-7 * expected + 1e-14,
                    "{name} {seq:?}: {} vs {expected}",
                    e.power
                );
            }
            // External reflections' footprints are the facets seen from the light: they tile
            // the silhouette.
            assert!((external_area - tree.stats.area).abs() < 1e-12, "{name}");
        }
    }
}

/// A cube lit straight down at normal incidence: the beam bounces between top and bottom
/// only. With R = ((n−1)/(n+1))², T = 1 − R, light leaving upward is
/// R + T·R·T + T·R·R²·T + … = R + T²R/(1 − R²), downward T²/(1 − R²); together 1.
#[test]
fn cube_at_normal_incidence_matches_closed_form() {
    let stone = Stone::new(&cube());
    for ri in [2.4173f64, 1.5, 3.0] {
        let r = ((ri - 1.0) / (ri + 1.0)).powi(2);
        let t = 1.0 - r;
        let up = r + t * t * r / (1.0 - r * r);
        let down = t * t / (1.0 - r * r);
        for pol in [true, false] {
            let opts = TraceOptions {
                polarization: pol,
                threshold: 1e-15,
                max_depth: 200,
                ..TraceOptions::exact(1e-15)
            };
            let tree = stone.trace(&Frame::overhead(), ri, 589.3, &opts);
            let got_up: f64 = tree
                .exits
                .iter()
                .filter(|e| e.direction.z > 0.0)
                .map(|e| e.power)
                .sum();
            let got_down: f64 = tree
                .exits
                .iter()
                .filter(|e| e.direction.z < 0.0)
                .map(|e| e.power)
                .sum();
            assert!((got_up - up).abs() < 1e-9, "ri {ri}: {got_up} vs {up}");
            assert!(
                (got_down - down).abs() < 1e-9,
                "ri {ri}: {got_down} vs {down}"
            );
            assert!(tree.exits.iter().all(|e| e.direction.z.abs() > 1.0 - 1e-12));
        }
    }
}
