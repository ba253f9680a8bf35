//! The viewer's head shadow in the scores (issue 50): what it takes and what it keeps, against
//! closed forms and sums written out here.

use super::super::*;
use super::lean;
use crate::beam::{Frame, Stone, TraceOptions};
use crate::optics::Material;
use crate::testkit::tolkowsky;

/// A slab seen face-up returns only light from straight overhead (its top and bottom faces
/// send the line of sight back along itself), the light a viewer's head blocks. Under an open
/// sky (head shadow 0) its brilliance is the incoherent slab's reflectance `2R / (1 + R)`,
/// `R = ((n − 1)/(n + 1))²` (the top face's `R` plus `(1 − R)² R / (1 − R²)` from the bottom
/// face's reflections), under ISO and COS alike (the zenith's radiance is 1 in both); under
/// the default head shadow it is 0: the scores no longer count that light.
#[test]
fn a_slab_returns_only_overhead_light_which_the_default_head_shadow_blocks() {
    let n = 1.5;
    let cfg = ScoreConfig {
        material: Material::constant(n),
        tilts: vec![Tilt::FACE_UP],
        parts: Parts {
            fire: false,
            scintillation: false,
        },
        ..ScoreConfig::default()
    };
    assert_eq!(cfg.head_shadow_deg, DEFAULT_HEAD_SHADOW_DEG);
    let slab = crate::testkit::slab(1.0, 0.2);
    let open = score(
        &slab,
        &ScoreConfig {
            head_shadow_deg: 0.0,
            ..cfg.clone()
        },
    );
    let shadowed = score(&slab, &cfg);
    let r = ((n - 1.0) / (n + 1.0)).powi(2);
    let want = 2.0 * r / (1.0 + r);
    for (what, got) in [("iso", open.brilliance_iso), ("cos", open.brilliance_cos)] {
        assert!((got - want).abs() < 1e-6, "open {what}: {got} vs {want}");
    }
    assert_eq!(shadowed.brilliance_iso, 0.0, "{shadowed:?}");
    assert_eq!(shadowed.brilliance_cos, 0.0, "{shadowed:?}");
    // The same light, counted by ASET as the port's (within 10° of the zenith).
    assert!((open.aset.port - want).abs() < 1e-6, "{:?}", open.aset);
    assert_eq!(shadowed.aset, open.aset);
}

/// The face-up brilliance of a round brilliant under the default head shadow, and under an
/// open sky, is the sum over the beam tree's exits of their power times the skies written
/// out here (not [`Lighting`](crate::render::lighting::Lighting)'s): radiance 1 (ISO) or the
/// cosine of the zenith angle (COS) above the horizon, both times a head shadow that is 0
/// within 15° − 1° of the zenith and 1 beyond 15° + 1°, `3x² − 2x³` between, and the horizon
/// soft by ±1° likewise. The shadow takes light the open sky counts (more than 0.03 of the
/// face-up pose's ISO return).
#[test]
fn face_up_brilliance_under_the_head_shadow_is_the_exits_sum() {
    let solid = crate::geometry::canonical::canonical(&tolkowsky());
    let cfg = ScoreConfig {
        tilts: vec![Tilt::FACE_UP],
        parts: Parts {
            fire: false,
            scintillation: false,
        },
        ..ScoreConfig::default()
    };
    let ramp = |x: f64| {
        let x = x.clamp(0.0, 1.0);
        x * x * (3.0 - 2.0 * x)
    };
    let tree = Stone::new(&solid).trace(
        &Frame::viewer(Tilt::FACE_UP.rotation()),
        cfg.material.ri(REFERENCE_WAVELENGTH_NM),
        REFERENCE_WAVELENGTH_NM,
        &TraceOptions {
            split_threshold: cfg.face_up_split_threshold,
            ..cfg.trace
        },
    );
    let by_hand = |head_deg: f64| {
        let (mut iso, mut cos) = (0.0, 0.0);
        for e in &tree.exits {
            let elevation = e.direction.z.clamp(-1.0, 1.0).asin().to_degrees();
            let zenith = 90.0 - elevation;
            let head = if head_deg > 0.0 {
                ramp((zenith - head_deg + 1.0) / 2.0)
            } else {
                1.0
            };
            iso += e.power * ramp((elevation + 1.0) / 2.0) * head;
            cos += e.power * e.direction.z.max(0.0) * head;
        }
        let p = tree.stats.power_in;
        (iso / p, cos / p)
    };
    let mut seen = Vec::new();
    for head in [DEFAULT_HEAD_SHADOW_DEG, 0.0] {
        let s = score(
            &solid,
            &ScoreConfig {
                head_shadow_deg: head,
                ..cfg.clone()
            },
        );
        let (iso, cos) = by_hand(head);
        eprintln!(
            "head shadow {head}°: score iso {:.6} cos {:.6}, by hand {iso:.6} {cos:.6}",
            s.brilliance_iso, s.brilliance_cos
        );
        assert!(
            (s.brilliance_iso - iso).abs() < 1e-4,
            "{head}: {s:?} vs {iso}"
        );
        assert!(
            (s.brilliance_cos - cos).abs() < 1e-4,
            "{head}: {s:?} vs {cos}"
        );
        seen.push(s);
    }
    assert!(
        seen[0].brilliance_iso < seen[1].brilliance_iso - 0.03,
        "{seen:?}"
    );
}

#[test]
fn head_shadow_darkens_brilliance() {
    let s = tolkowsky();
    let open = score(
        &s,
        &ScoreConfig {
            head_shadow_deg: 0.0,
            ..lean()
        },
    );
    let shadow = score(
        &s,
        &ScoreConfig {
            head_shadow_deg: 20.0,
            ..lean()
        },
    );
    assert!(
        shadow.brilliance_iso < open.brilliance_iso - 0.02,
        "{} {}",
        shadow.brilliance_iso,
        open.brilliance_iso
    );
    assert!(shadow.brilliance_cos < open.brilliance_cos);
    assert_eq!(shadow.aset, open.aset);
}
