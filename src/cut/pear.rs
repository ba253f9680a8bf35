//! The pear (pendeloque) brilliant: half a circle at one end, a point at the other.
//!
//! Outline (width 1 across, y; length L = `length_width` along x, centred on its bounding box):
//! the rounded end is a half circle of diameter 1 centred at x0 = 1/2 − L/2; the pointed half is
//! half a marquise — two arcs that leave the circle's widest points horizontally and meet at the
//! tip (L/2, 0), each of radius ρ = (L − 1/2)² + 1/4. Girdle points: a main point at the tip, at
//! the two widest points, at the far end of the round and at 135°/225° on the circle; the main
//! points between tip and widest point sit at the arcs' midpoints. The facets follow the shared
//! brilliant-around-an-outline layout (`outline.rs`, 57 facets, 58 with a culet, plus 16 girdle
//! flats), every main at `pavilion_angle`, the bezels reaching the table corners (those facing
//! across the width at `crown_angle`). The pavilion bottoms out under the centre of the round end,
//! from where the keel runs toward the point. The shape is symmetric only about the length axis
//! (y → −y).

use super::marquise::pointed_arc;
use super::outline::{
    brilliant, Outline, CROWN_ANGLE, CULET, GIRDLE, LOWER_HALF, PAVILION_ANGLE, STAR, TABLE,
};
use super::{Family, ParamDef, Params, Unit};
use crate::error::Result;
use crate::geometry::{DVec2, FacetPlane};

const PARAMS: &[ParamDef] = &[
    ParamDef {
        key: "length_width",
        default: 1.6,
        min: 1.25,
        max: 2.0,
        open: false,
        unit: Unit::Ratio,
        doc: "length (round end to tip) over width",
    },
    TABLE,
    CROWN_ANGLE,
    PAVILION_ANGLE,
    GIRDLE,
    STAR,
    LOWER_HALF,
    ParamDef {
        doc: "culet width across the stone (0 = sharp)",
        ..CULET
    },
];

/// The pear family.
pub const FAMILY: Family = Family {
    name: "pear",
    doc: "pear brilliant: round end and pointed end, 8 bezels, 8 stars, 16 upper halves, 16-flat girdle, 8 pavilion mains, 16 lower halves, optional culet",
    params: PARAMS,
    build,
};

/// The pear outline of length `lw` and width 1.
pub(crate) fn outline(lw: f64) -> Outline {
    let x0 = 0.5 - lw / 2.0;
    let (q, nq) = pointed_arc(x0, lw / 2.0);
    let circle = |deg: f64| {
        let a = deg.to_radians();
        DVec2::new(a.cos(), a.sin())
    };
    let p: [DVec2; 9] = std::array::from_fn(|j| {
        if j <= 4 {
            q[j]
        } else {
            DVec2::new(x0, 0.0) + 0.5 * circle(90.0 + 22.5 * (j - 4) as f64)
        }
    });
    let n = [nq[0], nq[1], nq[2], circle(135.0), DVec2::NEG_X];
    Outline::from_upper_half(p, n, DVec2::new(x0, 0.0))
}

fn build(p: &Params) -> Result<Vec<FacetPlane>> {
    brilliant(&outline(p.get("length_width")?), p, "pear")
}

#[cfg(test)]
mod tests {
    use crate::testkit::cuts::*;

    #[test]
    fn pear_default_facets_and_symmetry() {
        let c = ok("pear", &[]);
        assert_brilliant_tiers(&c, 0);
        assert_eq!(ok("pear", &[("culet", 0.04)]).solid.facets().len(), 58 + 16);
        assert!(
            symmetric_under(&c, flip_y),
            "pear is symmetric about its length"
        );
        assert!(
            !symmetric_under(&c, flip_x),
            "pear has a round end and a point"
        );
        // The round end: its 5 main points lie on the circle of diameter 1 around x0.
        let x0 = 0.5 - 1.6 / 2.0;
        let (lo, _) = c.solid.bounding_box();
        assert!((lo.x - (x0 - 0.5)).abs() < 1e-9);
    }

    #[test]
    fn pear_measures_match_parameters() {
        for (lw, t, ca, pa) in [
            (1.6, 0.57, 34.0, 41.0),
            (1.25, 0.5, 38.0, 39.0),
            (2.0, 0.62, 30.0, 46.0),
        ] {
            let c = fancy_measured("pear", lw, t, ca, pa, None);
            // The bezel at the round end is as far from the centre as the sides: same angle.
            assert!((angle_of(&c, "bezel-5") - ca).abs() < 1e-9);
            // The lowest point lies under the centre of the round end.
            let x0 = 0.5 - lw / 2.0;
            let low = c
                .solid
                .vertices()
                .iter()
                .copied()
                .fold(c.solid.vertices()[0], |a, v| {
                    if v.z < a.z - 1e-12 || (v.z < a.z + 1e-12 && v.x < a.x) {
                        v
                    } else {
                        a
                    }
                });
            assert!((low.x - x0).abs() < 1e-9 && low.y.abs() < 1e-9, "{low:?}");
        }
    }

    #[test]
    fn pear_sweeps_and_errors() {
        sweep_main_angles("pear", 6);
        assert!(sweep_each("pear", 6) > 40);
        out_of_range_named("pear");
    }
}
