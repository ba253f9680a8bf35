//! The cushion brilliant: a brilliant around a rounded square (or rounded rectangle).
//!
//! The outline is the superellipse |2x/L|^p + |2y|^p = 1 (width 1, length L = `length_width`)
//! with exponent p = 2 / `corner_rounding`: 1 gives an ellipse (a circle when L = 1), 0.5 the
//! classic "squircle" cushion (p = 4), 0.2 an almost sharp-cornered rectangle (p = 10). Girdle
//! points at superellipse parameter 22.5°·j, x = L/2·sgn(cos θ)|cos θ|^(2/p), y likewise with sin:
//! main points in the middle of each side and on the corner diagonals. The facets follow the
//! shared brilliant-around-an-outline layout (`outline.rs`, 57 facets, 58 with a culet, plus 16
//! girdle flats): every main at `pavilion_angle` (meeting in a keel when the outline is longer
//! than wide), the bezels reaching the table corners — those facing across the width at
//! `crown_angle`, the corner and end bezels a little flatter.

use super::outline::{brilliant, Outline};
use super::{Family, ParamDef, Params, Unit};
use crate::error::Result;
use crate::geometry::{DVec2, FacetPlane};

const PARAMS: &[ParamDef] = &[
    ParamDef { key: "length_width", default: 1.0, min: 1.0, max: 1.6, open: false, unit: Unit::Ratio, doc: "length over width of the outline" },
    ParamDef { key: "corner_rounding", default: 0.5, min: 0.2, max: 1.0, open: false, unit: Unit::Ratio, doc: "roundness of the corners: superellipse exponent 2/corner_rounding (1 = ellipse, 0.2 = nearly square)" },
    ParamDef { key: "table", default: 0.58, min: 0.45, max: 0.75, open: false, unit: Unit::Fraction, doc: "table width across the stone, as a fraction of the width" },
    ParamDef { key: "crown_angle", default: 35.0, min: 20.0, max: 45.0, open: false, unit: Unit::Degrees, doc: "angle of every bezel to the girdle plane" },
    ParamDef { key: "pavilion_angle", default: 41.0, min: 35.0, max: 50.0, open: false, unit: Unit::Degrees, doc: "angle of every pavilion main to the girdle plane" },
    ParamDef { key: "girdle", default: 0.025, min: 0.0, max: 0.1, open: false, unit: Unit::Fraction, doc: "girdle thickness at the 16 girdle points" },
    ParamDef { key: "star", default: 0.5, min: 0.3, max: 0.8, open: false, unit: Unit::Fraction, doc: "star length: share of the table-edge-to-girdle distance along the bezel ridge" },
    ParamDef { key: "lower_half", default: 0.75, min: 0.5, max: 0.9, open: false, unit: Unit::Fraction, doc: "lower-half length: share of the girdle-to-keel distance along the main ridge" },
    ParamDef { key: "culet", default: 0.0, min: 0.0, max: 0.1, open: false, unit: Unit::Fraction, doc: "culet width across the stone (0 = pointed)" },
];

/// The cushion family.
pub const FAMILY: Family = Family {
    name: "cushion",
    doc: "cushion brilliant: rounded-square superellipse outline, 8 bezels, 8 stars, 16 upper halves, 16-flat girdle, 8 pavilion mains, 16 lower halves, optional culet",
    params: PARAMS,
    build,
};

/// The superellipse outline of length `lw`, width 1 and exponent `2 / rounding`.
pub(crate) fn outline(lw: f64, rounding: f64) -> Outline {
    let (a, b, e) = (lw / 2.0, 0.5, 2.0 / rounding);
    let q: [DVec2; 5] = std::array::from_fn(|j| match j {
        0 => DVec2::new(a, 0.0),
        4 => DVec2::new(0.0, b),
        _ => {
            let th = (22.5 * j as f64).to_radians();
            DVec2::new(a * th.cos().powf(2.0 / e), b * th.sin().powf(2.0 / e))
        }
    });
    // Normal ∝ gradient of |x/a|^e + |y/b|^e; on the diagonal (θ = 45°) that is (1/a, 1/b).
    let n = [DVec2::X, DVec2::new(1.0 / a, 1.0 / b).normalize(), DVec2::Y];
    Outline::from_quadrant(q, n)
}

fn build(p: &Params) -> Result<Vec<FacetPlane>> {
    brilliant(
        &outline(p.get("length_width")?, p.get("corner_rounding")?),
        p,
        "cushion",
    )
}

#[cfg(test)]
mod tests {
    use crate::geometry::DVec3;
    use crate::testkit::cuts::*;

    #[test]
    fn cushion_default_facets_and_symmetry() {
        let c = ok("cushion", &[]);
        assert_brilliant_tiers(&c, 0);
        assert!(symmetric_under(&c, flip_x) && symmetric_under(&c, flip_y));
        // A square cushion is symmetric under the quarter turn and the diagonal mirror.
        assert!(symmetric_under(&c, |v| DVec3::new(-v.y, v.x, v.z)));
        assert!(symmetric_under(&c, |v| DVec3::new(v.y, v.x, v.z)));
        let long = ok("cushion", &[("length_width", 1.3)]);
        assert!(!symmetric_under(&long, |v| DVec3::new(-v.y, v.x, v.z)));
    }

    #[test]
    fn round_cushion_is_the_round_brilliant() {
        let c = ok(
            "cushion",
            &[
                ("corner_rounding", 1.0),
                ("table", 0.57),
                ("crown_angle", 34.0),
                ("pavilion_angle", 40.75),
            ],
        );
        let r = ok(
            "round-brilliant",
            &[
                ("table", 0.57),
                ("crown_angle", 34.0),
                ("pavilion_angle", 40.75),
            ],
        );
        assert!((c.solid.volume() - r.solid.volume()).abs() < 1e-12);
        assert!(symmetric_under(&c, |v| v) && c.solid.facets().len() == r.solid.facets().len());
    }

    #[test]
    fn cushion_corners_fill_out_as_rounding_drops() {
        // Smaller corner_rounding pushes the corners out toward the square: more volume.
        let vols: Vec<f64> = [1.0, 0.7, 0.5, 0.3, 0.2]
            .iter()
            .map(|&r| ok("cushion", &[("corner_rounding", r)]).solid.volume())
            .collect();
        assert!(vols.windows(2).all(|w| w[1] > w[0]), "{vols:?}");
        let (lo, hi) = ok("cushion", &[("corner_rounding", 0.2)])
            .solid
            .bounding_box();
        assert!((hi.x - lo.x - 1.0).abs() < 1e-9);
    }

    #[test]
    fn cushion_measures_match_parameters() {
        for (lw, cr, t, ca, pa) in [
            (1.0, 0.5, 0.58, 35.0, 41.0),
            (1.4, 0.3, 0.52, 30.0, 44.0),
            (1.6, 0.8, 0.66, 40.0, 38.0),
        ] {
            let c = ok(
                "cushion",
                &[
                    ("length_width", lw),
                    ("corner_rounding", cr),
                    ("table", t),
                    ("crown_angle", ca),
                    ("pavilion_angle", pa),
                ],
            );
            assert!((bbox_ratio(&c) - lw).abs() < 1e-9);
            assert!((table_width(&c) - t).abs() < 1e-9);
            assert!((angle_of(&c, "bezel-3") - ca).abs() < 1e-9);
            let p = c.proportions();
            assert!((p.pavilion_angle - pa).abs() < 1e-9);
            let depth = 0.025 + ((1.0 - t) * ca.to_radians().tan() + pa.to_radians().tan()) / 2.0;
            assert!(
                (p.total_depth - depth).abs() < 1e-9,
                "depth {} vs {depth}",
                p.total_depth
            );
        }
    }

    #[test]
    fn cushion_sweeps_and_errors() {
        sweep_main_angles("cushion", 6);
        assert!(sweep_each("cushion", 6) > 40);
        out_of_range_named("cushion");
    }
}
