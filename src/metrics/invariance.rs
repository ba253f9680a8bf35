//! Invariance and smoothness of the scores: the same solid written down differently scores
//! the same; a stone turned about its axis scores nearly the same; a profile in the pavilion
//! angle is smooth.

use super::*;
use crate::geometry::FacetPlane;
use std::collections::BTreeMap;

fn ags() -> crate::cut::Cut {
    crate::io::load_cut("ags-ideal").unwrap()
}

/// `solid` rotated by `m`, then translated by `t`, then scaled by `k` about the origin, with
/// its facets in reverse order when `reverse` (as a mesh exporter might write them).
fn transformed(solid: &Polyhedron, m: DMat3, t: DVec3, k: f64, reverse: bool) -> Polyhedron {
    let mut planes: Vec<FacetPlane> = solid
        .facet_planes()
        .into_iter()
        .map(|mut f| {
            let n = m * f.plane.normal;
            f.plane.offset = k * (f.plane.offset + n.dot(t));
            f.plane.normal = n;
            f
        })
        .collect();
    if reverse {
        planes.reverse();
    }
    Polyhedron::from_planes(&planes).unwrap()
}

fn fields(s: &Scores) -> [(&'static str, f64); 9] {
    [
        ("overhead_light_return", s.overhead_light_return),
        ("brilliance", s.brilliance),
        ("brilliance_iso", s.brilliance_iso),
        ("brilliance_cos", s.brilliance_cos),
        ("fire", s.fire),
        ("scintillation", s.scintillation),
        ("blue", s.aset.blue),
        ("red", s.aset.red),
        ("leak", s.aset.leak),
    ]
}

/// Largest absolute difference between two score sets (fire in its own unit, percent).
fn max_diff(a: &Scores, b: &Scores) -> (f64, &'static str) {
    fields(a)
        .iter()
        .zip(fields(b))
        .map(|(&(name, x), (_, y))| ((x - y).abs(), name))
        .fold((0.0, ""), |m, d| if d.0 > m.0 { d } else { m })
}

/// The default definitions with cheaper tracing (the definitions, not their resolution, are
/// what is tested).
fn cfg() -> ScoreConfig {
    ScoreConfig {
        bands: 4,
        resolution: 32,
        fire_placements: 7,
        trace: TraceOptions {
            split_threshold: 1e-3,
            threshold: 1e-7,
            ..Default::default()
        },
        fire_split_threshold: 1e-4,
        ..ScoreConfig::default()
    }
}

#[test]
fn same_solid_scores_the_same() {
    let cfg = cfg();
    let s0 = ags().solid;
    let base = score(&s0, &cfg);
    // (x, y, z) → (−y, x, z): exact in floating point, the OBJ coordinate swap.
    let swap = DMat3::from_cols(DVec3::Y, DVec3::NEG_X, DVec3::Z);
    let cases = [
        ("turned 90° (coordinate swap), facets reversed", swap, DVec3::ZERO, 1.0, true),
        (
            "turned 45° (a symmetry)",
            DMat3::from_rotation_z(std::f64::consts::FRAC_PI_4),
            DVec3::ZERO,
            1.0,
            false,
        ),
        (
            "mirrored through the xz plane (a symmetry)",
            DMat3::from_diagonal(DVec3::new(1.0, -1.0, 1.0)),
            DVec3::ZERO,
            1.0,
            true,
        ),
        (
            "translated",
            DMat3::IDENTITY,
            DVec3::new(0.31, -0.17, 0.42),
            1.0,
            false,
        ),
        ("scaled ×2.5", DMat3::IDENTITY, DVec3::ZERO, 2.5, false),
        (
            "scaled ×0.013 (mm → a stone of 13 µm), translated",
            DMat3::IDENTITY,
            DVec3::new(-3.0, 5.0, 1.0),
            0.013,
            true,
        ),
    ];
    for (name, m, t, k, reverse) in cases {
        let s = score(&transformed(&s0, m, t, k, reverse), &cfg);
        let (d, which) = max_diff(&s, &base);
        assert!(d < 1e-7, "{name}: {which} moved by {d:e}\n{s:?}\n{base:?}");
    }
}

#[test]
fn tiny_parameter_changes_move_scores_tinily() {
    let cfg = cfg();
    let cut = ags();
    let base = score(&cut.solid, &cfg);
    for key in ["table", "crown_angle", "pavilion_angle", "girdle", "star", "lower_half"] {
        for eps in [1e-10, -1e-10] {
            let mut v = BTreeMap::new();
            v.insert(key.to_string(), cut.params[key] + eps);
            let s = score(&cut.with_params(&v).unwrap().solid, &cfg);
            let (d, which) = max_diff(&s, &base);
            assert!(d < 1e-7, "{key} {eps:+e}: {which} moved by {d:e}");
        }
    }
}

#[test]
fn turning_the_stone_hardly_moves_its_scores() {
    let cfg = cfg();
    let s0 = ags().solid;
    let base = score(&s0, &cfg);
    for deg in [22.5, 7.0, 13.0, 31.0] {
        let m = DMat3::from_rotation_z(f64::to_radians(deg));
        let s = score(&transformed(&s0, m, DVec3::ZERO, 1.0, false), &cfg);
        for ((name, x), (_, y)) in fields(&s).iter().zip(fields(&base)) {
            assert!((x - y).abs() <= 2e-3, "turned {deg}°: {name} {y} → {x}");
        }
    }
}
