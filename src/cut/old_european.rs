//! The old European cut: the round brilliant of about 1890–1930, before Tolkowsky.
//!
//! Same facet layout and parameter meanings as `round-brilliant` (table, 8 bezels, 8 stars,
//! 16 upper halves, girdle, 8 pavilion mains, 16 lower halves, culet), built by the round
//! brilliant's own construction; only the defaults and allowed ranges differ, chosen for what
//! distinguishes the style: a small table (≈ 0.40–0.45), a high crown (≈ 40°), a deep pavilion
//! (≈ 42°), short lower halves and a large, visible culet (≈ 0.1–0.15 of the diameter). The
//! ranges are chosen so that every combination inside them gives every facet (in particular
//! `girdle_facets` is 0 or 16: with 32 or more tangent girdle flats the round construction loses
//! girdle facets on thin girdles); the build still checks the solid and names the parameter if a
//! facet would vanish.

use super::construct::check_solid;
use super::{round, Family, ParamDef, Params, Unit};
use crate::error::Result;
use crate::geometry::FacetPlane;

const PARAMS: &[ParamDef] = &[
    ParamDef {
        key: "table",
        default: 0.43,
        min: 0.3,
        max: 0.6,
        open: false,
        unit: Unit::Fraction,
        doc: "table width corner to corner",
    },
    ParamDef {
        key: "crown_angle",
        default: 40.0,
        min: 25.0,
        max: 45.0,
        open: false,
        unit: Unit::Degrees,
        doc: "bezel angle to the girdle plane",
    },
    ParamDef {
        key: "pavilion_angle",
        default: 42.0,
        min: 36.0,
        max: 48.0,
        open: false,
        unit: Unit::Degrees,
        doc: "pavilion main angle to the girdle plane",
    },
    ParamDef {
        key: "girdle",
        default: 0.02,
        min: 0.0,
        max: 0.1,
        open: false,
        unit: Unit::Fraction,
        doc: "girdle thickness at the bezel/main points",
    },
    ParamDef {
        key: "star",
        default: 0.5,
        min: 0.3,
        max: 0.8,
        open: false,
        unit: Unit::Fraction,
        doc: "star length: share of the table-edge-to-girdle distance along the bezel ridge",
    },
    ParamDef {
        key: "lower_half",
        default: 0.55,
        min: 0.4,
        max: 0.75,
        open: false,
        unit: Unit::Fraction,
        doc: "lower-half length: share of the girdle-to-centre distance along the main ridge",
    },
    ParamDef {
        key: "culet",
        default: 0.12,
        min: 0.0,
        max: 0.2,
        open: false,
        unit: Unit::Fraction,
        doc: "culet width across the mains (0 = pointed)",
    },
    ParamDef {
        key: "girdle_facets",
        default: 0.0,
        min: 0.0,
        max: 16.0,
        open: false,
        unit: Unit::Count,
        doc:
            "girdle facets: 0 = 16 flats through the 16 points, 16 = 16 flats tangent to the circle",
    },
];

/// The old European cut family.
pub const FAMILY: Family = Family {
    name: "old-european",
    doc: "old European cut: round brilliant layout with a small table, high crown, deep pavilion and large culet",
    params: PARAMS,
    build,
};

fn key_of_tier(tier: &str) -> &'static str {
    match tier {
        "star" | "upper-half" => "star",
        "lower-half" | "pavilion-main" => "lower_half",
        "girdle" => "girdle_facets",
        "culet" => "culet",
        "bezel" | "table" => "table",
        _ => "crown_angle",
    }
}

fn build(p: &Params) -> Result<Vec<FacetPlane>> {
    let planes = round::build(p)?;
    check_solid("old-european", &planes, p, key_of_tier)?;
    Ok(planes)
}

#[cfg(test)]
mod tests {
    use crate::testkit::cuts::*;

    #[test]
    fn old_european_defaults_are_the_style() {
        let c = ok("old-european", &[]);
        assert_brilliant_tiers(&c, 1);
        let p = c.proportions();
        assert!(
            (p.table - 0.43).abs() < 1e-9
                && (p.crown_angle - 40.0).abs() < 1e-9
                && (p.pavilion_angle - 42.0).abs() < 1e-9
        );
        // High crown, deep stone, culet 0.12 across the mains.
        let want_crown = (1.0 - 0.43) / 2.0 * 40f64.to_radians().tan();
        assert!((p.crown_height - want_crown).abs() < 1e-9 && p.crown_height > 0.2);
        let (lo, hi) = facet_extent(&c, "culet");
        assert!(
            ((hi.y - lo.y) - 0.12).abs() < 1e-9,
            "culet across the mains {}",
            hi.y - lo.y
        );
        assert!(symmetric_under(&c, flip_x) && symmetric_under(&c, flip_y));
        // Same construction as the round brilliant with the same numbers.
        let kv = [
            ("table", 0.43),
            ("crown_angle", 40.0),
            ("pavilion_angle", 42.0),
            ("girdle", 0.02),
            ("star", 0.5),
            ("lower_half", 0.55),
            ("culet", 0.12),
        ];
        let r = ok("round-brilliant", &kv);
        assert!((r.solid.volume() - c.solid.volume()).abs() < 1e-15);
    }

    #[test]
    fn old_european_sweeps_and_errors() {
        sweep_main_angles("old-european", 6);
        assert!(sweep_each("old-european", 6) > 40);
        out_of_range_named("old-european");
        let e = cut("old-european", &[("girdle_facets", 8.0)])
            .expect_err("8 girdle facets")
            .to_string();
        assert!(
            e.starts_with("girdle_facets:") && e.contains("multiple of 16"),
            "{e}"
        );
        // Tangent girdle flats survive even a hairline girdle at the extreme angles.
        for (ca, pa) in [(25.0, 36.0), (45.0, 48.0), (25.0, 48.0), (45.0, 36.0)] {
            ok(
                "old-european",
                &[
                    ("girdle_facets", 16.0),
                    ("girdle", 0.0005),
                    ("crown_angle", ca),
                    ("pavilion_angle", pa),
                ],
            );
        }
    }
}
