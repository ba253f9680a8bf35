//! Invariance and smoothness of the scores: the same solid written down differently scores
//! the same; a stone turned about its axis scores nearly the same; a profile in the pavilion
//! angle is smooth.

use super::super::*;
use crate::beam::TraceOptions;
use crate::geometry::{FacetPlane, Polyhedron};
use glam::{DMat3, DVec3};
use rayon::prelude::*;
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
        face_up_split_threshold: 1e-4,
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
        (
            "turned 90° (coordinate swap), facets reversed",
            swap,
            DVec3::ZERO,
            1.0,
            true,
        ),
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
    ];
    for (name, m, t, k, reverse) in cases {
        let s = score(&transformed(&s0, m, t, k, reverse), &cfg);
        let (d, which) = max_diff(&s, &base);
        assert!(d < 1e-7, "{name}: {which} moved by {d:e}\n{s:?}\n{base:?}");
    }
}

/// Largest change of any score when one parameter of ags-ideal moves by ±1e-10.
fn perturbation_response() -> (f64, String) {
    let cfg = cfg();
    let cut = ags();
    let base = score(&cut.solid, &cfg);
    let mut worst = (0.0, String::new());
    for key in [
        "table",
        "crown_angle",
        "pavilion_angle",
        "girdle",
        "star",
        "lower_half",
    ] {
        for eps in [1e-10, -1e-10] {
            let mut v = BTreeMap::new();
            v.insert(key.to_string(), cut.params[key] + eps);
            let s = score(&cut.with_params(&v).unwrap().solid, &cfg);
            let (d, which) = max_diff(&s, &base);
            if d > worst.0 {
                worst = (d, format!("{key} {eps:+e}: {which}"));
            }
        }
    }
    worst
}

/// Same solid, same numbers: a 1e-10 change of a parameter moves no score by more than 1e-7
/// (measured: under 3e-9 with the default configuration on ags-ideal, tolkowsky and the
/// princess). Narrow beams start their ray at the beam's area centroid, which moves
/// continuously; from the mean of its vertices (which jumps when a clip adds a rounding sliver's
/// vertex) the same change moved fire by up to 7.7e-4 and brilliance by 1.5e-5.
#[test]
fn tiny_parameter_changes_move_scores_tinily() {
    let (d, what) = perturbation_response();
    assert!(d < 1e-7, "{what} moved by {d:e}");
}

/// Scores of ags-ideal turned about its axis by a few angles, and unturned.
fn turned_scores() -> (Scores, Vec<(f64, Scores)>) {
    let cfg = cfg();
    let s0 = ags().solid;
    let base = score(&s0, &cfg);
    let turned = [22.5, 7.0, 13.0, 31.0]
        .iter()
        .map(|&deg| {
            let m = DMat3::from_rotation_z(f64::to_radians(deg));
            (
                deg,
                score(&transformed(&s0, m, DVec3::ZERO, 1.0, false), &cfg),
            )
        })
        .collect();
    (base, turned)
}

/// A stone turned about its axis by any angle is placed at the same canonical azimuth
/// (`geometry::canonical`), so every score, fire and scintillation included, stays within the
/// issue's 2e-3 (in fact the turned solids agree to ~1e-13, so the scores agree to the
/// tracer's response to such a change).
#[test]
fn turning_the_stone_moves_no_score_by_more_than_2e_3() {
    let (base, turned) = turned_scores();
    for (deg, s) in &turned {
        let (d, which) = max_diff(s, &base);
        eprintln!("turned {deg}°: largest change {d:.2e} ({which})");
        assert!(d <= 2e-3, "turned {deg}°: {which} moved by {d:e}");
    }
}

/// A coarse profile (pavilion angle 40.0° → 41.0° in 0.025° steps on the start cut of
/// `optim/round-brilliance.toml`): total variation over range of brilliance, fire and
/// scintillation stays near 1 (a monotone or single-humped profile) rather than showing
/// flash-by-flash zig-zags. (`benches/profile.rs` measures the fine 0.002° profile.)
#[test]
fn coarse_profile_is_smooth() {
    let cfg = cfg();
    let scores: Vec<Scores> = (0..=40)
        .into_par_iter()
        .map(|k| {
            let cut = crate::testkit::gia_round("p", 40.0 + 0.025 * k as f64);
            score(&cut.solid, &cfg)
        })
        .collect();
    let tv_over_range = |f: fn(&Scores) -> f64| {
        let v: Vec<f64> = scores.iter().map(f).collect();
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        v.windows(2).map(|w| (w[1] - w[0]).abs()).sum::<f64>() / (hi - lo)
    };
    let (b, f, s) = (
        tv_over_range(|s| s.brilliance),
        tv_over_range(|s| s.fire),
        tv_over_range(|s| s.scintillation),
    );
    eprintln!("TV/range over 41 cuts: brilliance {b:.3}, fire {f:.3}, scintillation {s:.3}");
    assert!(b < 1.6 && f < 3.6 && s < 2.1, "{b} {f} {s}");
}
