//! Power accounting: power in = out + cut off, the threshold and depth limit, a solid with
//! split corners, the ray floor, and narrow beams' forks.

use super::{dirs, solids};
use crate::beam::{BeamTree, Frame, Stone, TraceOptions};
use crate::geometry::Polyhedron;
use crate::testkit::tolkowsky;
use glam::DVec3;

#[test]
fn power_in_equals_out_plus_cut_off() {
    for (name, s) in solids() {
        let stone = Stone::new(&s);
        for frame in dirs() {
            for pol in [true, false] {
                for ri in [2.4173, 1.5] {
                    let opts = TraceOptions {
                        polarization: pol,
                        ..Default::default()
                    };
                    let tree = stone.trace(&frame, ri, 589.3, &opts);
                    assert!((tree.stats.power_in - 1.0).abs() < 1e-12, "{name}");
                    assert!(
                        tree.balance().abs() < 1e-12,
                        "{name} pol {pol} ri {ri}: balance {}",
                        tree.balance()
                    );
                    assert!(
                        tree.stats.cut_off < 1e-3,
                        "{name}: cut off {}",
                        tree.stats.cut_off
                    );
                    assert!(
                        tree.stats.max_tiling_error < 1e-9,
                        "{name}: tiling {}",
                        tree.stats.max_tiling_error
                    );
                    assert!((tree.stats.area - s.projected_area(-frame.dir)).abs() < 1e-12);
                    for e in &tree.exits {
                        assert!(e.power >= 0.0 && (e.direction.length() - 1.0).abs() < 1e-12);
                        // A physical Stokes vector: degree of polarization at most 1.
                        let p =
                            (e.stokes.y.powi(2) + e.stokes.z.powi(2) + e.stokes.w.powi(2)).sqrt();
                        assert!(
                            p <= e.stokes.x * (1.0 + 1e-9) + 1e-300,
                            "{name}: {:?}",
                            e.stokes
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn depth_limit_and_threshold_are_accounted() {
    let s = tolkowsky();
    let stone = Stone::new(&s);
    for (thr, depth) in [(0.0, 2), (1e-3, 64), (0.05, 64), (0.0, 0), (1e-6, 5)] {
        let opts = TraceOptions {
            threshold: thr,
            max_depth: depth,
            ..Default::default()
        };
        let tree = stone.trace(&Frame::overhead(), 2.4173, 589.3, &opts);
        assert!(tree.balance().abs() < 1e-12);
        assert!(tree.exits.iter().all(|e| e.reflections <= depth));
        assert!(tree.stats.cut_off > 0.0);
    }
    // Deeper tracing shrinks the cut-off, with narrow beams and without.
    let cut = |o: TraceOptions| {
        stone
            .trace(&Frame::overhead(), 2.4173, 589.3, &o)
            .stats
            .cut_off
    };
    for exact in [false, true] {
        let o = |thr: f64| {
            if exact {
                TraceOptions::exact(thr)
            } else {
                TraceOptions {
                    threshold: thr,
                    ..Default::default()
                }
            }
        };
        assert!(
            cut(o(1e-7)) < cut(o(1e-5)) && cut(o(1e-5)) < cut(o(1e-3)),
            "exact {exact}"
        );
    }
    // Trapped light: exact splitting cut off at 1e-5 loses far more than narrow beams do.
    assert!(cut(TraceOptions::exact(1e-5)) > 100.0 * cut(TraceOptions::default()));
}

/// A pear read back from binary STL, put in the canonical placement, has corners split into
/// vertex pairs ~1e-7 apart, a few 1e-8 off their planes; its facets must still tile every
/// beam (the facets are clipped as convex polygons), and its overhead light return is the
/// preset's. Before, a short edge turning the wrong way cut beams along its line: a tiling
/// error of 100 % and 6.9e-4 of the light return lost.
#[test]
fn a_solid_with_split_corners_still_tiles_every_beam() {
    let cut = crate::io::load_cut("pear").unwrap();
    let planes = crate::io::mesh::read_stl(&crate::io::mesh::write_stl(&cut), "p.stl").unwrap();
    let stl = crate::geometry::canonical::canonical(&Polyhedron::from_planes(&planes).unwrap());
    let preset = crate::geometry::canonical::canonical(&cut.solid);
    let ri = 2.4173;
    let olr = |s: &Polyhedron| {
        let opts = TraceOptions {
            polarization: false,
            symmetry: false,
            split_threshold: 1e-5,
            ..Default::default()
        };
        let tree = Stone::new(s).trace(&Frame::overhead(), ri, 589.3, &opts);
        let up: f64 = tree
            .exits
            .iter()
            .filter(|e| e.direction.z > 0.0)
            .map(|e| e.power)
            .sum();
        (up, tree.stats.max_tiling_error)
    };
    let ((a, ta), (b, tb)) = (olr(&preset), olr(&stl));
    // The split corners leave gaps of a few 1e-8 between facets: up to 1e-5 of a small beam.
    assert!(ta < 1e-6 && tb < 1e-4, "tiling errors {ta:e} {tb:e}");
    assert!((a - b).abs() < 1e-4, "preset {a} vs STL {b}");
}

/// The ray floor stops narrow beams' rays once they have lost 95 % of their power: power is
/// still accounted for exactly (what it stopped is in `cut_off` and `ray_closed`), the rays
/// take far fewer segments, the light before the stop is the same light, and only narrow
/// exits are late.
#[test]
fn ray_floor_stops_rays_and_accounts_their_power() {
    let stone = Stone::new(&tolkowsky());
    // Tilted 10° toward azimuth 30°: no symmetry left.
    let a = 30f64.to_radians();
    let frame = Frame::viewer(glam::DMat3::from_axis_angle(
        DVec3::new(-a.sin(), a.cos(), 0.0),
        10f64.to_radians(),
    ));
    let full = stone.trace(&frame, 2.4173, 589.3, &TraceOptions::default());
    let opts = TraceOptions {
        ray_floor: 0.05,
        ..Default::default()
    };
    let cut = stone.trace(&frame, 2.4173, 589.3, &opts);
    for t in [&full, &cut] {
        assert!(t.balance().abs() < 1e-12, "balance {}", t.balance());
        assert!(t.stats.ray_closed <= t.stats.cut_off);
        assert!(t.exits.iter().all(|e| e.narrow || !e.late));
    }
    assert_eq!(full.stats.ray_closed, 0.0);
    assert!(cut.stats.ray_closed > 1e-3, "{}", cut.stats.ray_closed);
    assert_eq!(
        (full.stats.beams, full.stats.rays),
        (cut.stats.beams, cut.stats.rays)
    );
    let ratio = cut.stats.ray_segments as f64 / full.stats.ray_segments as f64;
    assert!(ratio < 0.6, "segments {ratio}");
    assert!(cut.exits.iter().any(|e| e.late));
    // What left before a stop left the same way: the stopped trace's exits are the full
    // trace's, in order, with only the stopped rays' later exits missing.
    let mut rest = full.exits.iter();
    for e in &cut.exits {
        assert!(
            rest.any(|f| f.power == e.power && f.direction == e.direction && f.late == e.late),
            "an exit of the stopped trace is not in the full one"
        );
    }
}

/// Narrow beams followed as forking discs ([`TraceOptions::narrow_forks`]) conserve power
/// exactly, hand their light from facet to facet continuously as the pose turns (one ray per
/// narrow beam jumps), and are closer to the exactly split trace than single rays.
#[test]
fn narrow_forks_are_continuous_and_conserve_power() {
    let stone = Stone::new(&tolkowsky());
    let frame = |deg: f64| {
        let a = 30f64.to_radians();
        Frame::viewer(glam::DMat3::from_axis_angle(
            DVec3::new(-a.sin(), a.cos(), 0.0),
            deg.to_radians(),
        ))
    };
    // A smooth functional of the exits: the power sent toward the viewer, weighted by the
    // squared cosine (continuous in the directions).
    let seen = |t: &BeamTree, f: &Frame| -> f64 {
        t.exits
            .iter()
            .map(|e| e.power * (-e.direction.dot(f.dir)).max(0.0).powi(2))
            .sum()
    };
    let opts = |forks: bool| TraceOptions {
        split_threshold: 3e-3,
        ray_floor: 0.02,
        narrow_forks: forks,
        ..Default::default()
    };
    let exact = TraceOptions::exact(1e-7);
    let (mut jump, mut err) = ([0.0f64; 2], [0.0f64; 2]);
    let mut prev = [f64::NAN; 2];
    for k in 0..=60 {
        let deg = 10.0 + 0.002 * k as f64;
        let f = frame(deg);
        for (i, forks) in [false, true].into_iter().enumerate() {
            let t = stone.trace(&f, 2.4173, 589.3, &opts(forks));
            assert!(t.balance().abs() < 1e-12, "balance {}", t.balance());
            assert!(t.stats.ray_closed <= t.stats.cut_off);
            let v = seen(&t, &f);
            if k > 0 {
                jump[i] = jump[i].max((v - prev[i]).abs());
            }
            prev[i] = v;
            if k % 20 == 0 {
                let e = seen(&stone.trace(&f, 2.4173, 589.3, &exact), &f);
                err[i] += (v - e).abs();
            }
        }
    }
    eprintln!(
        "largest step: rays {:e}, forks {:e}; error: rays {:e}, forks {:e}",
        jump[0], jump[1], err[0], err[1]
    );
    assert!(jump[1] < 0.3 * jump[0], "largest steps {jump:?}");
    assert!(err[1] < err[0], "errors {err:?}");
}
