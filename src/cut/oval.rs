//! The oval brilliant: the round brilliant's 57/58 facets around an ellipse.
//!
//! The girdle outline is the ellipse with width 1 (across, y) and length `length_width` (x). Its
//! 16 girdle points are the round brilliant's points stretched along the length: parameter angle
//! 22.5°·j, P = (L/2·cos θ, 1/2·sin θ). The facets follow the shared brilliant-around-an-outline
//! layout (see `outline.rs`). Which angles stretch:
//! - the crown (table, bezels, stars, upper halves) and the girdle are *exactly* the round
//!   brilliant's stretched by the affine map x → L·x (plane normals map by the inverse transpose):
//!   the table is the round's table stretched, `crown_angle` is the angle of the two bezels facing
//!   across the width, and the bezels toward the ends are flatter (tan α shrinks by up to 1/L);
//! - the pavilion is *not* stretched: every main is cut at `pavilion_angle`, so the mains meet in a
//!   keel L − 1 long instead of a point (a stretched round pavilion would keep a point and flatten
//!   the end mains).
//!
//! With `length_width` = 1 this is exactly the round brilliant with its 16-flat girdle.

use super::outline::{
    brilliant, Outline, CROWN_ANGLE, CULET, GIRDLE, LOWER_HALF, PAVILION_ANGLE, STAR, TABLE,
};
use super::{Family, ParamDef, Params, Unit};
use crate::error::Result;
use crate::geometry::{DVec2, FacetPlane};

const PARAMS: &[ParamDef] = &[
    ParamDef {
        key: "length_width",
        default: 1.4,
        min: 1.0,
        max: 2.0,
        open: false,
        unit: Unit::Ratio,
        doc: "length over width of the elliptical outline",
    },
    ParamDef {
        default: 0.56,
        max: 0.75,
        ..TABLE
    },
    CROWN_ANGLE,
    PAVILION_ANGLE,
    GIRDLE,
    ParamDef { min: 0.3, ..STAR },
    LOWER_HALF,
    CULET,
];

/// The oval brilliant family.
pub const FAMILY: Family = Family {
    name: "oval",
    doc: "oval brilliant: elliptical outline, 8 bezels, 8 stars, 16 upper halves, 16-flat girdle, 8 pavilion mains meeting in a keel, 16 lower halves, optional culet",
    params: PARAMS,
    build,
};

/// The elliptical outline of length `lw` and width 1.
pub(crate) fn outline(lw: f64) -> Outline {
    let (a, b) = (lw / 2.0, 0.5);
    let q: [DVec2; 5] = std::array::from_fn(|j| {
        let th = (22.5 * j as f64).to_radians();
        DVec2::new(a * th.cos(), b * th.sin())
    });
    let n: [DVec2; 3] = std::array::from_fn(|k| {
        let th = (45.0 * k as f64).to_radians();
        DVec2::new(b * th.cos(), a * th.sin()).normalize()
    });
    Outline::from_quadrant(q, n)
}

fn build(p: &Params) -> Result<Vec<FacetPlane>> {
    brilliant(&outline(p.get("length_width")?), p, "oval")
}

#[cfg(test)]
mod tests {
    use crate::testkit::cuts::*;

    #[test]
    fn oval_default_facets_and_symmetry() {
        let c = ok("oval", &[]);
        assert_brilliant_tiers(&c, 0);
        assert_eq!(c.tiers().len(), 7);
        assert!(symmetric_under(&c, flip_x) && symmetric_under(&c, flip_y));
        // Not rotationally symmetric: the ellipse is longer than wide.
        assert!(!symmetric_under(&c, |v| crate::geometry::DVec3::new(
            -v.y, v.x, v.z
        )));
        assert_eq!(ok("oval", &[("culet", 0.05)]).solid.facets().len(), 58 + 16);
        assert_eq!(ok("oval", &[("girdle", 0.0)]).solid.facets().len(), 57);
    }

    #[test]
    fn oval_of_length_one_is_the_round_brilliant() {
        let kv = [
            ("table", 0.6),
            ("crown_angle", 33.0),
            ("pavilion_angle", 41.2),
            ("star", 0.45),
            ("lower_half", 0.8),
            ("culet", 0.03),
        ];
        let oval = ok("oval", &[kv.as_slice(), &[("length_width", 1.0)]].concat());
        let round = ok("round-brilliant", &kv);
        assert_eq!(oval.solid.facets().len(), round.solid.facets().len());
        for f in round.solid.facets() {
            let g = oval
                .solid
                .facets()
                .iter()
                .find(|g| g.name == f.name)
                .unwrap_or_else(|| panic!("{}", f.name));
            assert!(
                g.plane.normal.distance(f.plane.normal) < 1e-9
                    && (g.plane.offset - f.plane.offset).abs() < 1e-9,
                "{}",
                f.name
            );
            assert_eq!(g.tier, f.tier);
        }
    }

    #[test]
    fn oval_crown_is_the_stretched_round_crown() {
        use crate::geometry::DVec3;
        let lw = 1.45;
        let kv = [("table", 0.58), ("crown_angle", 35.0), ("star", 0.55)];
        let oval = ok("oval", &[kv.as_slice(), &[("length_width", lw)]].concat());
        let round = ok("round-brilliant", &kv);
        let crown = ["table", "bezel", "star", "upper-half", "girdle"];
        let mut n = 0;
        for f in round
            .solid
            .facets()
            .iter()
            .filter(|f| crown.contains(&f.tier.as_str()))
        {
            // The plane n·x = d maps under x → (L x, y, z) to (n.x / L, n.y, n.z)·x = d.
            let m = DVec3::new(f.plane.normal.x / lw, f.plane.normal.y, f.plane.normal.z);
            let (normal, offset) = (m / m.length(), f.plane.offset / m.length());
            let g = oval
                .solid
                .facets()
                .iter()
                .find(|g| g.name == f.name)
                .unwrap();
            assert!(g.plane.normal.distance(normal) < 1e-9, "{}", f.name);
            assert!((g.plane.offset - offset).abs() < 1e-9, "{}", f.name);
            n += 1;
        }
        assert_eq!(n, 1 + 8 + 8 + 16 + 16);
        // The pavilion is not stretched: all mains keep the pavilion angle.
        for k in 1..=8 {
            assert!((angle_of(&oval, &format!("pavilion-main-{k}")) - 41.0).abs() < 1e-9);
        }
    }

    #[test]
    fn oval_measures_match_parameters() {
        for (lw, t, ca, pa, g) in [
            (1.4, 0.56, 34.0, 41.0, 0.025),
            (1.8, 0.62, 30.0, 43.0, 0.01),
            (1.15, 0.5, 38.0, 39.0, 0.0),
        ] {
            let c = fancy_measured("oval", lw, t, ca, pa, Some(g));
            // The bezels facing across the width carry the crown angle; every main the pavilion's.
            assert!((angle_of(&c, "bezel-7") - ca).abs() < 1e-9);
            assert!(angle_of(&c, "bezel-1") < ca - 1.0, "end bezels are flatter");
            let p = c.proportions();
            let tc = ca.to_radians().tan();
            assert!((p.crown_height - (1.0 - t) / 2.0 * tc).abs() < 1e-9);
        }
    }

    #[test]
    fn oval_sweeps_and_errors() {
        sweep_main_angles("oval", 6);
        assert!(sweep_each("oval", 6) > 40);
        out_of_range_named("oval");
        let e = cut("oval", &[("table", 0.75), ("star", 0.3)])
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("star:") && e.contains("too short") && e.contains("use star above 0.3"),
            "{e}"
        );
        let e = cut("oval", &[("culet", 0.1), ("lower_half", 0.9)])
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("lower_half:") && e.contains("culet"), "{e}");
    }
}
