//! Body colour in the beam tracer (`TraceOptions::absorption`): a slab at normal incidence in
//! closed form, every exit's power against path lengths recomputed ray by ray along its facet
//! sequence, and the power accounting with the absorbed light.

use super::{dirs, solids};
use crate::beam::attenuation::tests::subdivided;
use crate::beam::{Frame, Stone, TraceOptions};
use crate::geometry::clip2d;
use crate::optics::{reflect, refract};
use crate::testkit::slab;
use glam::DVec2;

/// A slab of thickness d lit straight down: light crossing it once, three times, … keeps
/// e^(−αd) per crossing, so with R = ((n−1)/(n+1))², T = 1 − R, k = e^(−αd) the light leaving
/// downward is T² k / (1 − R² k²) and upward R + T² R k² / (1 − R² k²) (issue 25's check 1,
/// the beam tracer's half), to 1e-9.
#[test]
fn an_absorbing_slab_at_normal_incidence_matches_its_closed_form() {
    for (d, alpha) in [(0.3, 2.5), (1.0, 0.3), (0.05, 40.0)] {
        let stone = Stone::new(&slab(0.5, 0.5 * d));
        for ri in [2.4173f64, 1.5] {
            let r = ((ri - 1.0) / (ri + 1.0)).powi(2);
            let t = 1.0 - r;
            let k = f64::exp(-alpha * d);
            let down = t * t * k / (1.0 - r * r * k * k);
            let up = r + t * t * r * k * k / (1.0 - r * r * k * k);
            for pol in [true, false] {
                let opts = TraceOptions {
                    polarization: pol,
                    max_depth: 400,
                    absorption: alpha,
                    ..TraceOptions::exact(1e-15)
                };
                let tree = stone.trace(&Frame::overhead(), ri, 589.3, &opts);
                let sum = |down: bool| -> f64 {
                    tree.exits
                        .iter()
                        .filter(|e| (e.direction.z < 0.0) == down)
                        .map(|e| e.power)
                        .sum()
                };
                assert!((sum(true) - down).abs() < 1e-9, "d {d} α {alpha} ri {ri}");
                assert!((sum(false) - up).abs() < 1e-9, "d {d} α {alpha} ri {ri}");
                let absorbed = 1.0 - down - up;
                assert!((tree.stats.absorbed - absorbed).abs() < 1e-9);
                assert!(tree.balance().abs() < 1e-12);
            }
        }
    }
}

/// Path length inside the stone of the ray entering at footprint point `q` (frame `frame`)
/// and following facet sequence `seq` of `stone`, recomputed plane by plane.
fn path_length(stone: &Stone, frame: &Frame, ri: f64, seq: &[usize], q: DVec2) -> f64 {
    let (n0, o0) = (stone.normals[seq[0]], stone.offsets[seq[0]]);
    let base = frame.u * q.x + frame.v * q.y;
    let mut x = base + frame.dir * ((o0 - n0.dot(base)) / n0.dot(frame.dir));
    let mut t = refract(frame.dir, n0, 1.0, ri).expect("refracted");
    let mut len = 0.0;
    for (j, &f) in seq.iter().enumerate().skip(1) {
        let (n, o) = (stone.normals[f], stone.offsets[f]);
        let s = (o - n.dot(x)) / n.dot(t);
        len += s;
        x += t * s;
        if j + 1 < seq.len() {
            t = reflect(t, n);
        }
    }
    len
}

/// Every exact exit's power is its footprint's share of the cross-section, times the Fresnel
/// factors along its facet sequence, times the mean over its footprint of e^(−αL), with the
/// path length L of each point recomputed by following its own ray plane by plane and the
/// mean by a fine subdivision of the footprint (independent of the tracer's divided
/// differences), to 1e-7.
#[test]
fn exit_powers_are_the_footprints_mean_transmittance() {
    let alpha = 1.7;
    let ri = 2.4173;
    for (name, s) in solids() {
        let stone = Stone::new(&s);
        for frame in dirs() {
            let opts = TraceOptions {
                polarization: false,
                footprints: true,
                absorption: alpha,
                ..Default::default()
            };
            let tree = stone.trace(&frame, ri, 589.3, &opts);
            let clear = stone.trace(
                &frame,
                ri,
                589.3,
                &TraceOptions {
                    absorption: 0.0,
                    ..opts
                },
            );
            assert_eq!(tree.exits.len(), clear.exits.len(), "{name}");
            let mut checked = 0;
            for (i, (e, c)) in tree.exits.iter().zip(&clear.exits).enumerate() {
                let seq = tree.sequence(e);
                assert_eq!(seq, clear.sequence(c));
                // The same exits as the colourless trace's, carrying its power too.
                assert_eq!(e.direction, c.direction, "{name}");
                assert_eq!(e.unabsorbed.to_bits(), c.power.to_bits(), "{name}");
                assert_eq!(c.unabsorbed.to_bits(), c.power.to_bits(), "{name}");
                if e.external {
                    assert_eq!(
                        e.power, c.power,
                        "{name}: external reflection is not absorbed"
                    );
                    continue;
                }
                assert!(e.power <= c.power && e.power >= 0.0, "{name}");
                if e.narrow {
                    continue;
                }
                let fp = tree.footprint(i);
                let a = clip2d::area(fp);
                if a < 1e-9 {
                    continue;
                }
                let p0 = fp[0];
                let integral: f64 = fp[1..]
                    .windows(2)
                    .map(|w| {
                        let phi = |q: DVec2| -alpha * path_length(&stone, &frame, ri, &seq, q);
                        subdivided([p0, w[0], w[1]], &phi, 6)
                    })
                    .sum();
                let expected = c.power * (integral.abs() / a);
                assert!(
                    (e.power - expected).abs() <= 1e-7 * expected + 1e-14,
                    "{name} {seq:?}: {} vs {expected}",
                    e.power
                );
                checked += 1;
            }
            assert!(checked > 0, "{name}");
        }
    }
}

/// Power in = out + cut off + absorbed on every solid and direction; more absorption keeps
/// less light; with absorption 0 the trace is bit for bit the colourless one.
#[test]
fn absorbed_light_is_accounted() {
    for (name, s) in solids() {
        let stone = Stone::new(&s);
        for frame in dirs() {
            let base = TraceOptions {
                footprints: true,
                ..Default::default()
            };
            let mut last = f64::INFINITY;
            for alpha in [0.0, 0.2, 1.0, 5.0] {
                let opts = TraceOptions {
                    absorption: alpha,
                    ..base
                };
                let tree = stone.trace(&frame, 2.4173, 589.3, &opts);
                assert!(tree.balance().abs() < 1e-12, "{name} α {alpha}");
                let out = tree.power_out();
                assert!(out < last, "{name} α {alpha}: {out} ≥ {last}");
                last = out;
                if alpha == 0.0 {
                    let plain = stone.trace(&frame, 2.4173, 589.3, &base);
                    assert_eq!(tree.stats, plain.stats);
                    assert!(tree
                        .exits
                        .iter()
                        .zip(&plain.exits)
                        .all(|(a, b)| a.power.to_bits() == b.power.to_bits()
                            && a.direction == b.direction));
                    assert_eq!(tree.footprints, plain.footprints);
                } else {
                    assert!(tree.stats.absorbed > 0.0);
                }
            }
        }
    }
}
