//! The marquise (navette) brilliant: a brilliant around a pointed vesica outline.
//!
//! The outline is the lens where two circles overlap: width 1 across (y), points at x = ±L/2
//! with L = `length_width`. Each side is an arc of radius ρ = (L² + 1)/4 whose centre lies on the
//! y axis on the far side, so the arcs meet at the tips at an angle. Girdle points: a main point at
//! each tip (its bezel and main face straight along the length), one at each side's widest point,
//! and the others evenly spaced in arc angle between them (main points on the arcs' midpoints,
//! ridge points halfway again). The facets follow the shared brilliant-around-an-outline layout
//! (`outline.rs`): 1 table, 8 bezels, 8 stars, 16 upper halves, 8 pavilion mains meeting in a keel,
//! 16 lower halves (57 facets, 58 with a culet) plus 16 girdle flats, every main at
//! `pavilion_angle` and the bezels reaching the table corners (the bezels facing across the width
//! at `crown_angle`, the ones at the tips flatter). Large tables need long stars on long stones:
//! when the star tips would end above the table the build reports the star lengths that work.

use super::outline::{
    brilliant, Outline, CROWN_ANGLE, CULET, GIRDLE, LOWER_HALF, PAVILION_ANGLE, STAR, TABLE,
};
use super::{Family, ParamDef, Params, Unit};
use crate::error::Result;
use crate::geometry::{DVec2, FacetPlane};

const PARAMS: &[ParamDef] = &[
    ParamDef {
        key: "length_width",
        default: 2.0,
        min: 1.5,
        max: 2.5,
        open: false,
        unit: Unit::Ratio,
        doc: "length (tip to tip) over width",
    },
    TABLE,
    CROWN_ANGLE,
    PAVILION_ANGLE,
    GIRDLE,
    STAR,
    LOWER_HALF,
    CULET,
];

/// The marquise family.
pub const FAMILY: Family = Family {
    name: "marquise",
    doc: "marquise brilliant: pointed vesica outline, 8 bezels (two at the tips), 8 stars, 16 upper halves, 16-flat girdle, 8 pavilion mains meeting in a keel, 16 lower halves, optional culet",
    params: PARAMS,
    build,
};

/// Points of the upper arc through the tip `(tip_x, 0)` and `(cx, 1/2)` (where the arc is
/// horizontal), evenly spaced in arc angle from the tip (j = 0) to the top (j = 4), with the
/// outward normals at j = 0 (the tip's bisector, +x), 2 and 4.
pub(crate) fn pointed_arc(cx: f64, tip_x: f64) -> ([DVec2; 5], [DVec2; 3]) {
    let l = tip_x - cx;
    let rho = l * l + 0.25;
    let centre = DVec2::new(cx, 0.5 - rho);
    let psi_tip = ((rho - 0.5) / rho).asin();
    let psi = |j: usize| psi_tip + (std::f64::consts::FRAC_PI_2 - psi_tip) * j as f64 / 4.0;
    let q: [DVec2; 5] = std::array::from_fn(|j| match j {
        0 => DVec2::new(tip_x, 0.0),
        4 => DVec2::new(cx, 0.5),
        _ => centre + rho * DVec2::new(psi(j).cos(), psi(j).sin()),
    });
    let n = [DVec2::X, DVec2::new(psi(2).cos(), psi(2).sin()), DVec2::Y];
    (q, n)
}

fn build(p: &Params) -> Result<Vec<FacetPlane>> {
    let (q, n) = pointed_arc(0.0, p.get("length_width")? / 2.0);
    brilliant(&Outline::from_quadrant(q, n), p, "marquise")
}

#[cfg(test)]
mod tests {
    use crate::testkit::cuts::*;

    #[test]
    fn marquise_default_facets_symmetry_and_tips() {
        let c = ok("marquise", &[]);
        assert_brilliant_tiers(&c, 0);
        assert_eq!(
            ok("marquise", &[("culet", 0.04)]).solid.facets().len(),
            58 + 16
        );
        assert!(symmetric_under(&c, flip_x) && symmetric_under(&c, flip_y));
        // The tips are single points of the girdle: the vertices at x = ±L/2 lie on the axis.
        let (lo, hi) = c.solid.bounding_box();
        for v in c
            .solid
            .vertices()
            .iter()
            .filter(|v| v.x > hi.x - 1e-9 || v.x < lo.x + 1e-9)
        {
            assert!(v.y.abs() < 1e-9, "tip vertex off the axis: {v:?}");
        }
        // The girdle turns sharply at the tips: the two girdle flats there meet at well under 180°.
        let normal = |name: &str| {
            c.solid
                .facets()
                .iter()
                .find(|f| f.name == name)
                .unwrap()
                .plane
                .normal
        };
        let turn = normal("girdle-1")
            .angle_between(normal("girdle-16"))
            .to_degrees();
        let side = normal("girdle-4")
            .angle_between(normal("girdle-5"))
            .to_degrees();
        assert!(
            turn > 60.0 && side < 15.0,
            "tip turn {turn}°, side turn {side}°"
        );
    }

    #[test]
    fn marquise_measures_match_parameters() {
        for (lw, t, ca, pa) in [
            (2.0, 0.57, 34.0, 41.0),
            (1.5, 0.52, 40.0, 38.0),
            (2.5, 0.62, 28.0, 45.0),
        ] {
            let c = fancy_measured("marquise", lw, t, ca, pa, None);
            // The table is the outline's shape: a pointed table with the stone's proportions of
            // main points, t times smaller.
            let (tlo, thi) = facet_extent(&c, "table");
            assert!(((thi.x - tlo.x) - t * lw).abs() < 1e-9);
        }
    }

    #[test]
    fn marquise_sweeps_and_errors() {
        sweep_main_angles("marquise", 6);
        assert!(sweep_each("marquise", 6) > 40);
        out_of_range_named("marquise");
        let e = cut(
            "marquise",
            &[("length_width", 2.5), ("table", 0.65), ("star", 0.4)],
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.starts_with("star:") && e.contains("use star above 0.5"),
            "{e}"
        );
    }
}
