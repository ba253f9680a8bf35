//! The emerald cut: a rectangular step cut with bevelled corners.
//!
//! Outline: a rectangle of width 1 (y) and length `length_width` (x) whose corners are cut at 45°
//! with legs `corner` (a fraction of the width; 0 = sharp corners, a plain rectangular step cut).
//! The girdle is 8 vertical facets (4 without corners) of thickness `girdle`.
//!
//! Crown: `crown_steps` rows ("steps") of 8 facets — 4 sides and 4 corners — between the girdle
//! and the table. Each step moves in by the same width, (1 − table)/2 / steps, on all four sides,
//! so the table is `table` wide across the stone and the side facets of one step share one angle:
//! the step next to the table is cut at `crown_angle` (the crown angle `info` reports), and each
//! step below it `crown_step_angle` steeper (angles must flatten toward the table for the crown
//! to be convex). Corner facets join the bevels of consecutive rows; the bevels shrink with the
//! row's width, so the table's corners are cut like the girdle's, and corner facets lie a little
//! flatter than the sides.
//!
//! Pavilion: `pavilion_steps` rows the same way, each moving in by 1/(2·steps), so the long sides
//! meet in a keel `length_width − 1` long; the step next to the keel is cut at `pavilion_angle`
//! (the pavilion angle `info` reports; it is the flattest, the one most light from the table
//! meets) and each step above it `pavilion_step_angle` steeper, the steepest at the girdle.
//! `culet` > 0 flattens the keel into a narrow culet facet. The ranges keep every step below 90°,
//! so every combination builds.
//! Depths in closed form: crown height = (1 − table)/(2·steps)·Σ tan(step angles), pavilion depth
//! = 1/(2·steps)·Σ tan(step angles) (less the culet's share).

use super::construct::check_solid;
use super::outline;
use super::steps::{band, girdle, stack, Ring};
use super::{Family, ParamDef, Params, Unit};
use crate::error::{Error, Result};
use crate::geometry::{DVec3, FacetPlane};

const PARAMS: &[ParamDef] = &[
    ParamDef {
        key: "length_width",
        default: 1.4,
        min: 1.0,
        max: 2.5,
        open: false,
        unit: Unit::Ratio,
        doc: "length over width of the outline",
    },
    ParamDef {
        key: "table",
        default: 0.64,
        min: 0.4,
        max: 0.8,
        open: false,
        unit: Unit::Fraction,
        doc: "table width across the stone, as a fraction of the width",
    },
    ParamDef {
        key: "crown_angle",
        default: 24.0,
        min: 10.0,
        max: 45.0,
        open: false,
        unit: Unit::Degrees,
        doc: "angle of the crown step next to the table (the flattest)",
    },
    ParamDef {
        key: "crown_steps",
        default: 3.0,
        min: 1.0,
        max: 4.0,
        open: false,
        unit: Unit::Count,
        doc: "number of crown steps (rows of 8 facets)",
    },
    ParamDef {
        key: "crown_step_angle",
        default: 8.0,
        min: 1.0,
        max: 12.0,
        open: false,
        unit: Unit::Degrees,
        doc: "how much steeper each crown step is than the one above it",
    },
    ParamDef {
        key: "pavilion_angle",
        default: 40.0,
        min: 30.0,
        max: 50.0,
        open: false,
        unit: Unit::Degrees,
        doc: "angle of the pavilion step next to the keel (the flattest)",
    },
    ParamDef {
        key: "pavilion_steps",
        default: 3.0,
        min: 1.0,
        max: 4.0,
        open: false,
        unit: Unit::Count,
        doc: "number of pavilion steps (rows of 8 facets)",
    },
    ParamDef {
        key: "pavilion_step_angle",
        default: 5.0,
        min: 1.0,
        max: 10.0,
        open: false,
        unit: Unit::Degrees,
        doc: "how much steeper each pavilion step is than the one below it",
    },
    ParamDef {
        key: "girdle",
        default: 0.02,
        min: 0.0,
        max: 0.1,
        open: false,
        unit: Unit::Fraction,
        doc: "girdle thickness",
    },
    ParamDef {
        key: "corner",
        default: 0.15,
        min: 0.0,
        max: 0.3,
        open: false,
        unit: Unit::Fraction,
        doc: "corner bevel leg along each side, as a fraction of the width (0 = sharp corners)",
    },
    ParamDef {
        doc: "width of the flattened keel (0 = sharp keel)",
        ..outline::CULET
    },
];

/// The emerald cut family.
pub const FAMILY: Family = Family {
    name: "emerald",
    doc: "emerald cut: rectangular step cut with bevelled corners, 3 crown steps and 3 pavilion steps of 8 facets, keel, optional culet",
    params: PARAMS,
    build,
};

/// Step angles from the girdle inward: `n` steps ending at `inner` (next to the table or the
/// keel), each step toward the girdle `step` degrees steeper.
pub(crate) fn step_angles(inner: f64, step: f64, n: usize) -> Vec<f64> {
    (0..n).map(|i| inner + step * (n - 1 - i) as f64).collect()
}

/// Checks the `corner` bevel: 0, or large enough to be a real facet.
pub(crate) fn check_corner(corner: f64) -> Result<()> {
    if corner > 0.0 && corner < 0.005 {
        return Err(Error::invalid(
            "corner",
            format!("{corner} is too small to cut; use 0 (sharp corners) or at least 0.005"),
        ));
    }
    Ok(())
}

fn key_of_tier(tier: &str) -> &'static str {
    if tier.starts_with("crown") || tier == "table" {
        "crown_step_angle"
    } else if tier.starts_with("pavilion") {
        "pavilion_step_angle"
    } else if tier == "culet" {
        "culet"
    } else {
        "corner"
    }
}

fn build(p: &Params) -> Result<Vec<FacetPlane>> {
    let lw = p.get("length_width")?;
    let t = p.get("table")?;
    let g = p.get("girdle")?;
    let corner = p.get("corner")?;
    let culet = p.get("culet")?;
    check_corner(corner)?;
    let nc = p.get("crown_steps")? as usize;
    let np = p.get("pavilion_steps")? as usize;
    let crown = step_angles(p.get("crown_angle")?, p.get("crown_step_angle")?, nc);
    let pav = step_angles(p.get("pavilion_angle")?, p.get("pavilion_step_angle")?, np);
    let zg = g / 2.0;
    let top = Ring {
        a: lw / 2.0,
        b: 0.5,
        c: corner,
        z: zg,
    };
    let bottom = Ring { z: -zg, ..top };
    let crown_rings = stack(top, corner, (1.0 - t) / 2.0, &crown, true);
    let pav_rings = stack(bottom, corner, 0.5, &pav, false);

    let mut out = Vec::with_capacity(1 + 8 * (nc + np + 1) + 1);
    let table = crown_rings[nc];
    out.push(FacetPlane::new(DVec3::Z, table.z, "table", "table"));
    for i in 0..nc {
        let tiers = (
            format!("crown-step-{}", i + 1),
            format!("crown-corner-{}", i + 1),
        );
        band(
            &crown_rings[i],
            &crown_rings[i + 1],
            &tiers.0,
            &tiers.1,
            &mut out,
        );
    }
    if g > 0.0 {
        girdle(&top, &mut out);
    }
    for i in 0..np {
        let tiers = (
            format!("pavilion-step-{}", i + 1),
            format!("pavilion-corner-{}", i + 1),
        );
        band(
            &pav_rings[i],
            &pav_rings[i + 1],
            &tiers.0,
            &tiers.1,
            &mut out,
        );
    }
    if culet > 0.0 {
        let keel = pav_rings[np].z;
        out.push(FacetPlane::new(
            DVec3::NEG_Z,
            -(keel + culet / 2.0 * pav[np - 1].to_radians().tan()),
            "culet",
            "culet",
        ));
    }
    check_solid("emerald", &out, p, key_of_tier)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use crate::testkit::cuts::*;

    /// Closed-form total depth: girdle + crown height + pavilion depth (sharp keel), with step
    /// angles listed from the girdle inward.
    fn depth(t: f64, g: f64, crown: &[f64], pav: &[f64]) -> f64 {
        let tan = |a: &f64| a.to_radians().tan();
        g + (1.0 - t) / (2.0 * crown.len() as f64) * crown.iter().map(tan).sum::<f64>()
            + 1.0 / (2.0 * pav.len() as f64) * pav.iter().map(tan).sum::<f64>()
    }

    #[test]
    fn emerald_default_facets_and_symmetry() {
        let c = ok("emerald", &[]);
        for i in 1..=3 {
            for tier in [
                "crown-step",
                "crown-corner",
                "pavilion-step",
                "pavilion-corner",
            ] {
                assert_eq!(count(&c, &format!("{tier}-{i}")), 4, "{tier}-{i}");
            }
        }
        let fixed = (count(&c, "table"), count(&c, "girdle"), count(&c, "culet"));
        assert_eq!(fixed, (1, 8, 0));
        // 25 crown + 24 pavilion facets + 8 girdle facets: the classic 57 + girdle.
        assert_eq!(c.solid.facets().len(), 49 + 8);
        assert!(symmetric_under(&c, flip_x) && symmetric_under(&c, flip_y));
        let sharp = ok("emerald", &[("corner", 0.0)]);
        assert_eq!(sharp.solid.facets().len(), 1 + 12 + 4 + 12);
        let kv = [
            ("crown_steps", 4.0),
            ("pavilion_steps", 2.0),
            ("culet", 0.05),
        ];
        assert_eq!(ok("emerald", &kv).solid.facets().len(), 1 + 32 + 8 + 16 + 1);
    }

    #[test]
    fn emerald_measures_match_parameters() {
        let cases = [
            (1.4, 0.64, 24.0, 8.0, 40.0, 5.0, 0.02, 0.15),
            (1.0, 0.4, 45.0, 12.0, 50.0, 10.0, 0.0, 0.3),
            (2.5, 0.8, 10.0, 1.0, 30.0, 1.0, 0.1, 0.0),
        ];
        for (lw, t, ca, cs, pa, ps, g, corner) in cases {
            let kv = [
                ("length_width", lw),
                ("table", t),
                ("crown_angle", ca),
                ("crown_step_angle", cs),
                ("pavilion_angle", pa),
                ("pavilion_step_angle", ps),
                ("girdle", g),
                ("corner", corner),
            ];
            let c = ok("emerald", &kv);
            assert!((bbox_ratio(&c) - lw).abs() < 1e-9);
            assert!((table_width(&c) - t).abs() < 1e-9);
            // `info` reads the step next to the table and the one next to the keel.
            let p = c.proportions();
            assert!((p.crown_angle - ca).abs() < 1e-9, "crown {}", p.crown_angle);
            assert!(
                (p.pavilion_angle - pa).abs() < 1e-9,
                "pavilion {}",
                p.pavilion_angle
            );
            assert!((p.girdle - g).abs() < 1e-9);
            // Every side facet of a step has the step's angle, on the long and the short sides;
            // steps get steeper toward the girdle.
            let crown = [ca + 2.0 * cs, ca + cs, ca];
            let pav = [pa + 2.0 * ps, pa + ps, pa];
            for side in 1..=4 {
                for i in 0..3 {
                    let cf = format!("crown-step-{}-{side}", i + 1);
                    let pf = format!("pavilion-step-{}-{side}", i + 1);
                    assert!((angle_of(&c, &cf) - crown[i]).abs() < 1e-9, "{cf}");
                    assert!((angle_of(&c, &pf) - pav[i]).abs() < 1e-9, "{pf}");
                }
            }
            let want = depth(t, g, &crown, &pav);
            assert!(
                (p.total_depth - want).abs() < 1e-9,
                "depth {} vs {want}",
                p.total_depth
            );
            // The keel is as long as the stone is longer than wide.
            let low = c.solid.bounding_box().0.z;
            let keel: Vec<f64> = c
                .solid
                .vertices()
                .iter()
                .filter(|v| v.z < low + 1e-9)
                .map(|v| v.x)
                .collect();
            let len = keel.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                - keel.iter().copied().fold(f64::INFINITY, f64::min);
            assert!((len - (lw - 1.0)).abs() < 1e-9, "keel {len}");
        }
    }

    #[test]
    fn emerald_sweeps_and_errors() {
        sweep_main_angles("emerald", 6);
        assert!(sweep_each("emerald", 6) > 50);
        out_of_range_named("emerald");
        // The steepest corner of the ranges still builds: 45° + 3·12° and 50° + 3·10° steps.
        let steep = [
            ("crown_angle", 45.0),
            ("crown_step_angle", 12.0),
            ("crown_steps", 4.0),
            ("pavilion_angle", 50.0),
            ("pavilion_step_angle", 10.0),
            ("pavilion_steps", 4.0),
            ("table", 0.4),
            ("corner", 0.3),
            ("culet", 0.1),
        ];
        ok("emerald", &steep);
        let e = cut("emerald", &[("corner", 0.001)])
            .expect_err("tiny corner")
            .to_string();
        assert!(e.starts_with("corner:") && e.contains("0.005"), "{e}");
    }
}
