use super::estimate::photon_config;
use super::*;
use crate::beam::Stone;
use crate::geometry::Polyhedron;
use crate::metrics::ScoreConfig;
use crate::metrics::{overhead_light_return_with, score, Tilt};
use crate::optics::Material;
use crate::photon::{self, Absorption, Light, TraceConfig, WavelengthSampling};

fn octahedron() -> Polyhedron {
    crate::testkit::octahedron_of(0.5)
}

fn solids() -> Vec<(&'static str, Polyhedron)> {
    vec![
        ("round", crate::io::load_cut("tolkowsky").unwrap().solid),
        ("princess", crate::io::load_cut("princess").unwrap().solid),
        ("octahedron", octahedron()),
    ]
}

/// The two tracers agree on the primitive figure within 4 standard errors: three solids,
/// polarization on and off.
#[test]
fn beam_and_photon_tracers_agree_on_overhead_light_return() {
    for (name, solid) in solids() {
        for polarization in [true, false] {
            let cfg = ScoreConfig::default().polarized(polarization);
            let opts = crate::beam::TraceOptions {
                polarization,
                split_threshold: 1e-5,
                ..Default::default()
            };
            let beam = overhead_light_return_with(
                &Stone::new(&solid),
                &crate::beam::Medium::Isotropic(cfg.material.ri(cfg.wavelength_nm)),
                &opts,
            );
            let mc = overhead_light_return_mc(&solid, &cfg, 150_000, 11).unwrap();
            let z = mc.z(beam);
            eprintln!(
                "{name} pol {polarization}: beam {beam:.5} photon {:.5} ± {:.5} ({z:.2} se)",
                mc.value, mc.stderr
            );
            assert!(
                z.abs() < 4.0,
                "{name} pol {polarization}: beam {beam} vs photon {} ± {} ({z:.2} se)",
                mc.value,
                mc.stderr
            );
            assert!(mc.stderr < 2e-3);
        }
    }
}

/// Coloured stones (issue 25's check 3): the beam tracer's exact absorption and the photon
/// tracer's per-photon Beer–Lambert agree on the light returned upward in every band —
/// the face-up colour is a sum of these, band by band — within 4 standard errors, on
/// three cuts in three published colours (6.5 mm wide).
#[test]
fn beam_and_photon_tracers_agree_on_coloured_light_return() {
    let cuts = [
        ("round", "ruby"),
        ("princess", "emerald"),
        ("octahedron", "blue-sapphire"),
    ];
    for ((name, solid), (_, variety)) in solids().into_iter().zip(cuts) {
        let material = Material::by_name(variety).unwrap();
        let colour = material.colour.clone().unwrap();
        let mm_per_unit = 6.5 / crate::cut::units::outline_size(solid.vertices()).1;
        let stone = Stone::new(&solid);
        for nm in [450.0, 550.0, 650.0] {
            let opts = crate::beam::TraceOptions {
                split_threshold: 1e-5,
                absorption: colour.alpha(nm) * mm_per_unit,
                ..Default::default()
            };
            // Birefringent by default (ruby and sapphire, emerald): the crystal with
            // its absorption per mode; the photons take the same material.
            let axis = material.uniaxial.as_ref().unwrap().axis.vector();
            let medium = crate::beam::Medium::of(&material, nm, axis, mm_per_unit, true);
            let beam = overhead_light_return_with(&stone, &medium, &opts);
            let t = photon::trace(
                &solid,
                &Light::directed(0.0),
                &TraceConfig {
                    absorption: Absorption::Body {
                        width_mm: mm_per_unit,
                    },
                    material: material.clone(),
                    wavelengths: WavelengthSampling::Fixed(nm),
                    polarization: true,
                    ..photon_config(&ScoreConfig::default(), 60_000, 5)
                },
                None,
            )
            .unwrap();
            let (value, stderr) = t.light_return();
            let z = (value - beam) / stderr;
            eprintln!("{name} {variety} {nm} nm: beam {beam:.5} photon {value:.5} ± {stderr:.5} ({z:.2} se)");
            assert!(
                z.abs() < 4.0,
                "{name} {variety} {nm} nm: {beam} vs {value} ± {stderr}"
            );
        }
    }
}

/// Monte Carlo brilliance under the same lighting and poses agrees with the beam tracer's,
/// under the default head shadow (both tracers see the same light: the check's photons are
/// weighted by the head-shadowed skies of the configuration).
#[test]
fn beam_and_photon_brilliance_agree() {
    let solid = crate::io::load_cut("tolkowsky").unwrap().solid;
    let cfg = ScoreConfig {
        tilts: vec![
            Tilt::FACE_UP,
            Tilt {
                tilt_deg: 15.0,
                azimuth_deg: 30.0,
            },
        ],
        ..ScoreConfig::default()
    };
    assert_eq!(cfg.head_shadow_deg, crate::metrics::DEFAULT_HEAD_SHADOW_DEG);
    let s = score(&solid, &cfg);
    let checks = verify_scores(&solid, &cfg, &s, 60_000, 5).unwrap();
    for c in &checks {
        eprintln!(
            "{}: beam {:.5} photon {:.5} ± {:.5} ({:.2} se)",
            c.name, c.beam, c.photon, c.stderr, c.z
        );
        assert!(c.z.abs() < 4.0, "{c:?}");
    }
    // A different material changes the figures: the check is not vacuous.
    let glass = ScoreConfig {
        material: Material::glass(),
        ..cfg.clone()
    };
    let g = brilliance_mc(&solid, &glass, 20_000, 5).unwrap();
    assert!(
        g.brilliance.value < s.brilliance - 10.0 * g.brilliance.stderr,
        "{g:?}"
    );
    // So does the head shadow: photons under an open sky find more light than the beam
    // tracer's shadowed figure, far beyond their error.
    let open = ScoreConfig {
        head_shadow_deg: 0.0,
        ..cfg.clone()
    };
    let o = brilliance_mc(&solid, &open, 20_000, 5).unwrap();
    assert!(
        o.brilliance.value > s.brilliance + 10.0 * o.brilliance.stderr,
        "{o:?} vs {}",
        s.brilliance
    );
}

/// The report given the beam scores is the report that computes them, row for row, and
/// the optimizer's verifier finds them in an evaluator's score map.
#[test]
fn a_report_given_the_beam_scores_is_the_same_report() {
    let cut = crate::io::load_cut("tolkowsky").unwrap();
    let cfg = ScoreConfig {
        tilts: vec![Tilt::FACE_UP],
        ..ScoreConfig::default()
    };
    let s = score(&cut.solid, &cfg);
    let full = photon_report(&cut, &cfg, 1500, 3).unwrap();
    let given = photon_report_given(
        &cut,
        &cfg,
        1500,
        3,
        Some((s.overhead_light_return, s.brilliance)),
    )
    .unwrap();
    assert_eq!(full, given);
    assert_eq!(full.rows.last().unwrap().beam, Some(s.brilliance));
    // Other beam values would show: the given ones are used.
    let other = photon_report_given(&cut, &cfg, 1500, 3, Some((0.5, 0.25))).unwrap();
    assert_eq!(other.rows.last().unwrap().beam, Some(0.25));
}

#[test]
fn flags_beyond_four_standard_errors() {
    let r = VerifyRow::new("brilliance_mc", 0.50, 0.01);
    assert_eq!(r.z(), None);
    assert!(!r.disagrees(4.0), "no beam value, nothing to compare");
    let ok = r.clone().with_beam(0.539);
    assert!((ok.z().unwrap() - 3.9).abs() < 1e-9);
    assert!(!ok.disagrees(4.0));
    let edge = r.clone().with_beam(0.54);
    assert!(!edge.disagrees(4.0 + 1e-9) && edge.disagrees(3.99));
    let bad = r.clone().with_beam(0.46 - 1e-6);
    assert!(bad.disagrees(4.0));
    // Zero standard error: equal (within rounding) is fine, different is flagged.
    let exact = VerifyRow::new("x", 0.3, 0.0).with_beam(0.1 + 0.2);
    assert_eq!(exact.z(), Some(0.0));
    assert!(!exact.disagrees(4.0));
    assert!(VerifyRow::new("x", 0.3, 0.0).with_beam(0.31).disagrees(4.0));
    // NaN never passes.
    assert!(VerifyRow::new("x", f64::NAN, 0.1)
        .with_beam(0.3)
        .disagrees(4.0));
    assert!(VerifyRow::new("x", 0.3, f64::NAN)
        .with_beam(0.3 + 1e-3)
        .disagrees(4.0));
    let rep = VerifyReport {
        photons: 10,
        rows: vec![ok, bad, VerifyRow::new("top45", 0.7, 0.01)],
    };
    assert_eq!(rep.disagreements(4.0), vec!["brilliance_mc".to_string()]);
}

/// Strongly birefringent stones (issue 50): the two tracers' brilliance agrees within 4
/// standard errors for zircon and moissanite rounds with the optic axis up (0), tilted in a
/// mirror plane (45@0), in the table (90) and tilted off every mirror (30@40), at a tilted
/// pose that the round's own symmetry maps onto another (20° toward 108°: a symmetry that
/// does not keep the axis must not be used). Two faults made them disagree: the photon
/// tracer kept the optic axis fixed in the world while the stone was turned into the pose,
/// and the beam tracer traced a pose's symmetric image under the stone's symmetry whether or
/// not it kept the axis. With the fix the largest distance here is 2.6 se (moissanite axis
/// 0 ISO); how far off the old code was at this photon count is not measured here (with
/// 300000 photons over the 11 default poses it was +27 se for zircon axis 0, +49 for 45@0
/// and +12 for moissanite axis 0).
#[test]
fn beam_and_photon_brilliance_agree_on_strongly_birefringent_stones() {
    use crate::metrics::Parts;
    use crate::optics::OpticAxis;
    let solid = crate::io::load_cut("tolkowsky").unwrap().solid;
    let mut worst = 0.0f64;
    for name in ["zircon", "moissanite"] {
        for axis in ["0", "45@0", "90", "30@40"] {
            let mut material = Material::by_name(name).unwrap();
            material.uniaxial.as_mut().unwrap().axis = OpticAxis::parse(axis, "axis").unwrap();
            let cfg = ScoreConfig {
                material,
                tilts: vec![Tilt {
                    tilt_deg: 20.0,
                    azimuth_deg: 108.0,
                }],
                parts: Parts {
                    fire: false,
                    scintillation: false,
                },
                face_up_split_threshold: 1e-3,
                fire_split_threshold: 1e-3,
                ..ScoreConfig::default()
            };
            let s = score(&solid, &cfg);
            let mc = brilliance_mc(&solid, &cfg, 40_000, 7).unwrap();
            for (what, beam, e) in [
                ("iso", s.brilliance_iso, mc.brilliance_iso),
                ("cos", s.brilliance_cos, mc.brilliance_cos),
            ] {
                let z = e.z(beam);
                eprintln!(
                    "{name} axis {axis} {what}: beam {beam:.5} photon {:.5} ± {:.5} ({z:+.2} se)",
                    e.value, e.stderr
                );
                worst = worst.max(z.abs());
                assert!(z.abs() < 4.0, "{name} axis {axis} {what}: {beam} vs {e:?}");
            }
        }
    }
    eprintln!("largest disagreement {worst:.2} standard errors");
}

/// Why strongly birefringent stones split finer (issue 50): a narrow beam's ray carries its
/// two reflected modes along the stronger one, an error that grows with the birefringence.
/// Against the same tilted pose split 25× finer than the scores' default (the exact part of
/// the trace doing nearly all the work), moissanite's brilliance at the default split is
/// closer than at the split shared with singly refractive stones (the photon tracer agrees:
/// `score tolkowsky --material moissanite --optic-axis 90 --verify 300000`, +4.56 → +2.02
/// standard errors).
#[test]
fn a_strongly_birefringent_stone_splits_finer_toward_the_exact_trace() {
    use crate::metrics::Parts;
    use crate::optics::OpticAxis;
    let solid = crate::io::load_cut("tolkowsky").unwrap().solid;
    let mut material = Material::by_name("moissanite").unwrap();
    material.uniaxial.as_mut().unwrap().axis = OpticAxis::parse("90", "axis").unwrap();
    let cfg = ScoreConfig {
        material,
        tilts: vec![Tilt {
            tilt_deg: 20.0,
            azimuth_deg: 108.0,
        }],
        parts: Parts {
            fire: false,
            scintillation: false,
        },
        head_shadow_deg: 0.0,
        ..ScoreConfig::default()
    };
    let factor = cfg.tilted_split() / cfg.trace.split_threshold;
    let at = |effective: f64| {
        let mut c = cfg.clone();
        c.trace.split_threshold = effective / factor;
        assert!((c.tilted_split() - effective).abs() < 1e-12 * effective);
        let s = score(&solid, &c);
        (s.brilliance_iso, s.brilliance_cos)
    };
    let shared = at(cfg.trace.split_threshold);
    let default = at(cfg.tilted_split());
    let fine = at(cfg.tilted_split() / 25.0);
    eprintln!("factor {factor:.3}: shared {shared:?}, default {default:?}, 25x finer {fine:?}");
    // Measured: ISO 0.81068, 0.81013, 0.80953; COS 0.56845, 0.56766, 0.56755 (the default's
    // error 0.53× and 0.12× the shared split's).
    for (what, s, d, f) in [
        ("iso", shared.0, default.0, fine.0),
        ("cos", shared.1, default.1, fine.1),
    ] {
        assert!(
            (d - f).abs() < 0.75 * (s - f).abs(),
            "{what}: shared {s}, default {d}, finer {f}"
        );
    }
}
