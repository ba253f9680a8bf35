//! The princess cut: a square (or rectangular) brilliant with a chevron pavilion.
//!
//! Outline: width 1 (y), length `length_width` (x), corners bevelled at 45° with legs `corner`
//! (0 = sharp corners). Girdle: 8 vertical facets (4 without corner bevels), `girdle` thick.
//!
//! Crown ("bevelled sides"): one or two tiers (`crown_tiers`) of 4 side facets and 4 corner
//! facets between the girdle and the table, each tier moving in by the same width on all sides;
//! the tier next to the table is cut at `crown_angle` (the crown angle `info` reports); with two
//! tiers the one at the girdle is `crown_step_angle` steeper. The table is `table` wide across the
//! stone, so crown height = (1 − table)/(2·tiers)·Σ tan(tier angles).
//!
//! Pavilion, as seen from below: an "X" of 4 *pavilion mains* — kites running from the girdle
//! corners to the culet, all at `pavilion_angle` — and on each side rows of *chevrons*.
//! The mains alone would make a pyramid with its point (the culet) at depth
//! tan(pavilion angle)·(L/2 + 1/2 − corner)/√2 under the girdle, whatever the length; between two
//! mains they meet in a ridge running from the culet up toward the middle of a side. The chevrons
//! fill the side from the girdle down to a point on that ridge a share `chevron_length` of the
//! (horizontal) way from the side to the culet, like the round's lower halves. On the side's centre line, points
//! A0 (middle of the girdle edge), A1, …, A(n+1) (on the ridge) are spaced evenly and lie on a
//! parabola that leaves the ridge tangentially, so the profile flattens toward the culet and the
//! pavilion stays convex. Every chevron is a triangle from a girdle corner K of the side to two
//! consecutive centre-line points (Ai, Ai+1); its mirror image comes from the other corner, and the
//! pair forms a "V" pointing at the culet. n = `pavilion_chevrons` rows (8 facets each, row 1 next
//! to the mains); the last bit of each side, from the girdle edge to A1, is a triangular
//! `pavilion-side` facet. Facets: table, 8 per crown tier (4 without corner bevels), 8 girdle
//! (4), and 8 + 8n on the pavilion (4 mains, 4 sides, 8n chevrons), plus an optional culet — 41
//! plus 8 girdle facets by default. The pavilion's 24 / 32 / 40 facets for 2 / 3 / 4 chevrons match
//! the trade's princesses; their crowns usually carry more (brilliant-style) facets than this
//! step crown.

use super::construct::{check_solid, plane_through_or};
use super::emerald::{check_corner, step_angles};
use super::steps::{band, girdle, stack, Ring};
use super::{Family, ParamDef, Params, Unit};
use crate::error::Result;
use crate::geometry::{DVec3, FacetPlane};

const PARAMS: &[ParamDef] = &[
    ParamDef { key: "length_width", default: 1.0, min: 1.0, max: 1.5, open: false, unit: Unit::Ratio, doc: "length over width of the outline (1 = square)" },
    ParamDef { key: "table", default: 0.68, min: 0.5, max: 0.85, open: false, unit: Unit::Fraction, doc: "table width across the stone, as a fraction of the width" },
    ParamDef { key: "crown_angle", default: 35.0, min: 20.0, max: 50.0, open: false, unit: Unit::Degrees, doc: "angle of the crown tier next to the table (sides)" },
    ParamDef { key: "crown_tiers", default: 1.0, min: 1.0, max: 2.0, open: false, unit: Unit::Count, doc: "crown tiers between girdle and table (1 or 2)" },
    ParamDef { key: "crown_step_angle", default: 10.0, min: 1.0, max: 15.0, open: false, unit: Unit::Degrees, doc: "with two crown tiers: how much steeper the tier at the girdle is" },
    ParamDef { key: "pavilion_angle", default: 41.0, min: 35.0, max: 48.0, open: false, unit: Unit::Degrees, doc: "angle of the 4 corner-to-culet pavilion mains" },
    ParamDef { key: "pavilion_chevrons", default: 3.0, min: 1.0, max: 4.0, open: false, unit: Unit::Count, doc: "rows of chevron facets on each pavilion side" },
    ParamDef { key: "chevron_length", default: 0.6, min: 0.2, max: 0.8, open: false, unit: Unit::Fraction, doc: "share of the girdle-to-culet distance along the main–main ridge covered by the chevrons" },
    ParamDef { key: "girdle", default: 0.02, min: 0.0, max: 0.1, open: false, unit: Unit::Fraction, doc: "girdle thickness" },
    ParamDef { key: "corner", default: 0.03, min: 0.0, max: 0.15, open: false, unit: Unit::Fraction, doc: "corner bevel leg along each side, as a fraction of the width (0 = sharp corners)" },
    ParamDef { key: "culet", default: 0.0, min: 0.0, max: 0.1, open: false, unit: Unit::Fraction, doc: "culet width, tip to tip along the sides (0 = pointed)" },
];

/// The princess family.
pub const FAMILY: Family = Family {
    name: "princess",
    doc: "princess cut: square or rectangular brilliant, step crown, 4 corner-to-culet pavilion mains and rows of chevrons",
    params: PARAMS,
    build,
};

fn key_of_tier(tier: &str) -> &'static str {
    if tier.starts_with("crown") || tier == "table" {
        "crown_angle"
    } else if tier.starts_with("chevron") || tier == "pavilion-side" {
        "chevron_length"
    } else if tier == "culet" {
        "culet"
    } else if tier == "girdle" {
        "corner"
    } else {
        "pavilion_angle"
    }
}

/// Depth of the pavilion (girdle bottom to the pointed culet) for these proportions.
pub(crate) fn pavilion_depth(lw: f64, corner: f64, pavilion_angle: f64) -> f64 {
    pavilion_angle.to_radians().tan() * (lw / 2.0 + 0.5 - corner) * std::f64::consts::FRAC_1_SQRT_2
}

fn build(p: &Params) -> Result<Vec<FacetPlane>> {
    let lw = p.get("length_width")?;
    let t = p.get("table")?;
    let g = p.get("girdle")?;
    let c = p.get("corner")?;
    let culet = p.get("culet")?;
    let beta = p.get("pavilion_angle")?.to_radians();
    let n = p.get("pavilion_chevrons")? as usize;
    let cl = p.get("chevron_length")?;
    check_corner(c)?;
    let tiers = p.get("crown_tiers")? as usize;
    let crown = step_angles(p.get("crown_angle")?, p.get("crown_step_angle")?, tiers);
    let zg = g / 2.0;
    let (a, b) = (lw / 2.0, 0.5);
    let top = Ring { a, b, c, z: zg };
    let rings = stack(top, c, (1.0 - t) / 2.0, &crown, true);
    let inside = DVec3::ZERO;

    let mut out = Vec::with_capacity(1 + 8 * tiers + 8 + 8 + 8 * n + 1);
    out.push(FacetPlane::new(DVec3::Z, rings[tiers].z, "table", "table"));
    for i in 0..tiers {
        let names = (
            format!("crown-tier-{}", i + 1),
            format!("crown-corner-{}", i + 1),
        );
        band(&rings[i], &rings[i + 1], &names.0, &names.1, &mut out);
    }
    if g > 0.0 {
        girdle(&top, &mut out);
    }
    // Mains: through the corner bevel at the girdle bottom, facing the corner.
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let culet_z = -zg - pavilion_depth(lw, c, p.get("pavilion_angle")?);
    for (k, (sx, sy)) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
        .iter()
        .enumerate()
    {
        let nrm = DVec3::new(sx * s * beta.sin(), sy * s * beta.sin(), -beta.cos());
        let off = nrm.dot(DVec3::new(sx * a, sy * (b - c), -zg));
        out.push(FacetPlane::new(
            nrm,
            off,
            format!("pavilion-main-{}", k + 1),
            "pavilion-main",
        ));
    }
    // Sides in a local frame: u out along the side's normal, v along the side, z up.
    let slope = beta.tan() * s;
    let mut sides = Vec::new();
    let mut chevrons = vec![Vec::new(); n];
    for side in 0..4 {
        let (half, along) = if side % 2 == 0 { (a, b) } else { (b, a) };
        let (cs, sn) = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)][side];
        let to_global = |u: f64, v: f64, z: f64| DVec3::new(u * cs - v * sn, u * sn + v * cs, z);
        let ridge = |u: f64| -zg - slope * (half + along - c - u);
        let ur = (1.0 - cl) * half;
        let k = (-zg - ridge(half)) / (half - ur).powi(2);
        let pts: Vec<DVec3> = (0..=n + 1)
            .map(|i| {
                let u = half - i as f64 * (half - ur) / (n + 1) as f64;
                to_global(u, 0.0, ridge(ur) + slope * (u - ur) + k * (u - ur).powi(2))
            })
            .collect();
        let kp = to_global(half, along - c, -zg);
        let km = to_global(half, -(along - c), -zg);
        sides.push(plane_through_or(
            [kp, km, pts[1]],
            inside,
            format!("pavilion-side-{}", side + 1),
            "pavilion-side",
            "chevron_length",
        )?);
        for (row, list) in chevrons.iter_mut().enumerate() {
            let i = n - row;
            let tier = format!("chevron-{}", row + 1);
            let name_p = format!("{tier}-{}", 2 * side + 1);
            let name_m = format!("{tier}-{}", if side == 0 { 8 } else { 2 * side });
            list.push(plane_through_or(
                [kp, pts[i], pts[i + 1]],
                inside,
                name_p,
                &tier,
                "chevron_length",
            )?);
            list.push(plane_through_or(
                [km, pts[i], pts[i + 1]],
                inside,
                name_m,
                &tier,
                "chevron_length",
            )?);
        }
    }
    out.extend(sides);
    for list in chevrons {
        out.extend(list);
    }
    if culet > 0.0 {
        out.push(FacetPlane::new(
            DVec3::NEG_Z,
            -(culet_z + culet / 2.0 * slope),
            "culet",
            "culet",
        ));
    }
    check_solid("princess", &out, p, key_of_tier)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::pavilion_depth;
    use crate::geometry::DVec3;
    use crate::testkit::cuts::*;

    #[test]
    fn princess_default_facets_and_symmetry() {
        let c = ok("princess", &[]);
        let want = [
            ("table", 1),
            ("crown-tier-1", 4),
            ("crown-corner-1", 4),
            ("girdle", 8),
            ("pavilion-main", 4),
            ("pavilion-side", 4),
            ("chevron-1", 8),
            ("chevron-2", 8),
            ("chevron-3", 8),
            ("chevron-4", 0),
        ];
        for (tier, n) in want {
            assert_eq!(count(&c, tier), n, "{tier}");
        }
        assert_eq!(c.solid.facets().len(), 9 + 8 + 32);
        for f in [flip_x, flip_y] {
            assert!(symmetric_under(&c, f));
        }
        assert!(
            symmetric_under(&c, |v| DVec3::new(-v.y, v.x, v.z)),
            "square: quarter-turn symmetric"
        );
        let rect = ok("princess", &[("length_width", 1.3)]);
        assert!(symmetric_under(&rect, flip_x) && symmetric_under(&rect, flip_y));
        assert!(!symmetric_under(&rect, |v| DVec3::new(-v.y, v.x, v.z)));
        // Pavilion facets 24 / 32 / 40 for 2 / 3 / 4 chevrons, as in the trade.
        for n in 1..=4 {
            let c = ok("princess", &[("pavilion_chevrons", n as f64)]);
            let pav = c
                .solid
                .facets()
                .iter()
                .filter(|f| f.plane.normal.z < -1e-9)
                .count();
            assert_eq!(pav, 8 + 8 * n);
        }
        let two = ok(
            "princess",
            &[("crown_tiers", 2.0), ("corner", 0.0), ("culet", 0.05)],
        );
        assert_eq!(
            (
                count(&two, "crown-tier-2"),
                count(&two, "crown-corner-1"),
                count(&two, "girdle"),
                count(&two, "culet")
            ),
            (4, 0, 4, 1)
        );
    }

    #[test]
    fn princess_chevrons_are_vs_pointing_at_the_culet() {
        let c = ok("princess", &[]);
        // Each chevron row on the +x side: its two facets meet on the side's centre line (y = 0),
        // and each reaches the girdle only at its corner.
        for row in 1..=3 {
            let (lo_p, hi_p) = facet_extent(&c, &format!("chevron-{row}-1"));
            let (lo_m, hi_m) = facet_extent(&c, &format!("chevron-{row}-8"));
            assert!(
                lo_p.y.abs() < 1e-12 && hi_m.y.abs() < 1e-12,
                "row {row} meets on the centre line"
            );
            assert!((hi_p.y - (0.5 - 0.03)).abs() < 1e-9 && (lo_m.y + (0.5 - 0.03)).abs() < 1e-9);
            assert!(hi_p.z < -0.01 + 1e-9 && lo_p.x > 0.0);
        }
        // Rows nearer the mains reach deeper.
        let depth = |row: usize| facet_extent(&c, &format!("chevron-{row}-1")).0.z;
        assert!(depth(1) < depth(2) && depth(2) < depth(3));
    }

    #[test]
    fn princess_measures_match_parameters() {
        let cases = [
            (1.0, 0.68, 35.0, 41.0, 0.02, 0.03, 1.0),
            (1.5, 0.5, 50.0, 35.0, 0.0, 0.15, 2.0),
            (1.2, 0.85, 20.0, 48.0, 0.1, 0.0, 2.0),
        ];
        for (lw, t, ca, pa, g, corner, tiers) in cases {
            let kv = [
                ("length_width", lw),
                ("table", t),
                ("crown_angle", ca),
                ("pavilion_angle", pa),
                ("girdle", g),
                ("corner", corner),
                ("crown_tiers", tiers),
            ];
            let c = ok("princess", &kv);
            assert!((bbox_ratio(&c) - lw).abs() < 1e-9);
            assert!((table_width(&c) - t).abs() < 1e-9);
            let p = c.proportions();
            assert!((p.crown_angle - ca).abs() < 1e-9 && (p.pavilion_angle - pa).abs() < 1e-9);
            // The tier at the girdle: the crown angle, or 10° (the default step) steeper.
            let lower = if tiers == 1.0 { ca } else { ca + 10.0 };
            for side in ["crown-tier-1-1", "crown-tier-1-2"] {
                assert!((angle_of(&c, side) - lower).abs() < 1e-9, "{side}");
            }
            let tan = |a: f64| a.to_radians().tan();
            let crown =
                (1.0 - t) / (2.0 * tiers) * (tan(ca) + if tiers == 1.0 { 0.0 } else { tan(lower) });
            let want = g + crown + pavilion_depth(lw, corner, pa);
            assert!(
                (p.total_depth - want).abs() < 1e-9,
                "depth {} vs {want}",
                p.total_depth
            );
            // The mains meet in one point under the centre, also on a rectangle.
            let low = c
                .solid
                .vertices()
                .iter()
                .copied()
                .fold(DVec3::ZERO, |a, v| if v.z < a.z { v } else { a });
            assert!(low.truncate().length() < 1e-9);
        }
    }

    #[test]
    fn princess_sweeps_and_errors() {
        sweep_main_angles("princess", 6);
        assert!(sweep_each("princess", 6) > 50);
        out_of_range_named("princess");
        let e = cut("princess", &[("corner", 0.002)])
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("corner:"), "{e}");
    }
}
