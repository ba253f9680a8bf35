//! The round brilliant from the industry's proportions (docs/cuts.md, "The round brilliant").
//!
//! Radius R = 0.5 (girdle diameter 1). Table corners lie at the main azimuths k·45° at radius
//! t·R, so crown height = (1 − t)/2 · tan(crown angle). Bezels and pavilion mains touch the
//! girdle circle at azimuths k·45°, at z = ±girdle/2. Star tips sit on the bezel–bezel ridge
//! (azimuth 22.5° + k·45°) at radius ρs·R with ρs = ρe + star·(1 − ρe), ρe = t·cos 22.5°.
//! Upper halves (azimuths 11.25° + k·22.5°) pass through a star tip and the girdle point at
//! the ridge's azimuth; lower halves pass through the main–main ridge point at radius
//! (1 − lower_half)·R and the girdle point at the ridge's azimuth. The girdle: with
//! `girdle_facets = 0`, 16 flat facets whose corners are the 16 points (the outline touches the
//! circle there only); with N = 16, 32, 64, … N vertical facets tangent to the circle at
//! azimuths k·360°/N. A girdle of thickness 0 is a knife edge: no girdle facets at all.

use super::{Family, ParamDef, Params, Unit};
use crate::error::{Error, Result};
use crate::geometry::{facet_normal, DVec3, FacetPlane};

const R: f64 = 0.5;

const PARAMS: &[ParamDef] = &[
    ParamDef {
        key: "table",
        default: 0.57,
        min: 0.2,
        max: 0.95,
        open: false,
        unit: Unit::Fraction,
        doc: "table width corner to corner",
    },
    ParamDef {
        key: "crown_angle",
        default: 34.0,
        min: 5.0,
        max: 60.0,
        open: false,
        unit: Unit::Degrees,
        doc: "bezel angle to the girdle plane",
    },
    ParamDef {
        key: "pavilion_angle",
        default: 40.75,
        min: 25.0,
        max: 60.0,
        open: false,
        unit: Unit::Degrees,
        doc: "pavilion main angle to the girdle plane",
    },
    ParamDef {
        key: "girdle",
        default: 0.025,
        min: 0.0,
        max: 0.15,
        open: false,
        unit: Unit::Fraction,
        doc: "girdle thickness at the bezel/main points",
    },
    ParamDef {
        key: "star",
        default: 0.5,
        min: 0.0,
        max: 1.0,
        open: true,
        unit: Unit::Fraction,
        doc: "star length: share of the table-edge-to-girdle distance along the bezel ridge",
    },
    ParamDef {
        key: "lower_half",
        default: 0.75,
        min: 0.0,
        max: 1.0,
        open: true,
        unit: Unit::Fraction,
        doc: "lower-half length: share of the girdle-to-centre distance along the main ridge",
    },
    ParamDef {
        key: "culet",
        default: 0.0,
        min: 0.0,
        max: 0.3,
        open: false,
        unit: Unit::Fraction,
        doc: "culet width across the mains (0 = pointed)",
    },
    ParamDef {
        key: "girdle_facets",
        default: 0.0,
        min: 0.0,
        max: 256.0,
        open: false,
        unit: Unit::Count,
        doc: "girdle facets: 0 = 16 flats through the 16 points, else a multiple of 16",
    },
];

/// The round brilliant family.
pub const FAMILY: Family = Family {
    name: "round-brilliant",
    doc: "round brilliant: table, 8 bezels, 8 stars, 16 upper halves, girdle, 8 pavilion mains, 16 lower halves, optional culet",
    params: PARAMS,
    build,
};

fn at(r: f64, az_deg: f64, z: f64) -> DVec3 {
    let a = az_deg.to_radians();
    DVec3::new(r * a.cos(), r * a.sin(), z)
}

/// Facet planes of a brilliant crown and pavilion around a round outline. Shared with the
/// elongated brilliants, which stretch this solid.
pub(crate) fn build(p: &Params) -> Result<Vec<FacetPlane>> {
    let t = p.get("table")?;
    let crown = p.get("crown_angle")?;
    let pav = p.get("pavilion_angle")?;
    let g = p.get("girdle")?;
    let star = p.get("star")?;
    let lh = p.get("lower_half")?;
    let culet = p.get("culet")?;
    let nf = p.get("girdle_facets")? as usize;
    if nf != 0 && !nf.is_multiple_of(16) {
        return Err(Error::invalid(
            "girdle_facets",
            format!("{nf} is not allowed; use 0 or a multiple of 16 (16, 32, 64, …)"),
        ));
    }
    let (tc, tp) = (crown.to_radians().tan(), pav.to_radians().tan());
    let zg = g / 2.0;
    let crown_height = (1.0 - t) * R * tc;
    let ztable = zg + crown_height;
    // Height of the bezel at azimuth 0 above a point at radius r, azimuth phi.
    let bezel_z = |r: f64, phi: f64| zg + (R - r * phi.to_radians().cos()) * tc;
    let main_z = |r: f64, phi: f64| -zg - (R - r * phi.to_radians().cos()) * tp;

    let mut out = Vec::with_capacity(74 + nf);
    out.push(FacetPlane::new(DVec3::Z, ztable, "table", "table"));
    for k in 0..8 {
        let az = 45.0 * k as f64;
        let n = facet_normal(crown, az, true);
        out.push(FacetPlane::new(
            n,
            n.dot(at(R, az, zg)),
            format!("bezel-{}", k + 1),
            "bezel",
        ));
    }
    // Stars: through the table edge midpoint (radius ρe) and the star tip on the bezel ridge.
    let rho_e = t * 22.5f64.to_radians().cos();
    let rho_s = rho_e + star * (1.0 - rho_e);
    // The bezel–bezel ridge crosses the table plane at radius t/cos 22.5°: a star tip inside
    // that would stand above the table.
    let rho_ridge = t / 22.5f64.to_radians().cos();
    let star_min = (rho_ridge - rho_e) / (1.0 - rho_e);
    if star <= star_min + 1e-6 {
        return Err(Error::invalid(
            "star",
            format!(
                "{star} is too short for table {t}: the star tip would stand above the table; allowed ({:.4}, 1) at this table",
                star_min + 1e-6
            ),
        ));
    }
    let tip_z = bezel_z(rho_s * R, 22.5);
    let star_angle = ((ztable - tip_z) / ((rho_s - rho_e) * R))
        .atan()
        .to_degrees();
    for k in 0..8 {
        let az = 22.5 + 45.0 * k as f64;
        let n = facet_normal(star_angle, az, true);
        out.push(FacetPlane::new(
            n,
            n.dot(at(rho_e * R, az, ztable)),
            format!("star-{}", k + 1),
            "star",
        ));
    }
    // Upper halves: through the star tip and the girdle point at the ridge azimuth.
    let c1125 = 11.25f64.to_radians().cos();
    let uh_angle = ((tip_z - zg) / ((R - rho_s * R) * c1125))
        .atan()
        .to_degrees();
    for k in 0..16 {
        let az = 11.25 + 22.5 * k as f64;
        let n = facet_normal(uh_angle, az, true);
        let ridge = 22.5 * (2 * (k / 2) + 1) as f64;
        out.push(FacetPlane::new(
            n,
            n.dot(at(R, ridge, zg)),
            format!("upper-half-{}", k + 1),
            "upper-half",
        ));
    }
    if g > 0.0 {
        girdle(&mut out, nf);
    }
    for k in 0..8 {
        let az = 45.0 * k as f64;
        let n = facet_normal(pav, az, false);
        out.push(FacetPlane::new(
            n,
            n.dot(at(R, az, -zg)),
            format!("pavilion-main-{}", k + 1),
            "pavilion-main",
        ));
    }
    // Lower halves: through the main–main ridge point at radius (1 − lh)·R and the girdle point.
    let r_tip = (1.0 - lh) * R;
    // The culet's corners lie on the main–main ridges at radius (culet/2)/cos 22.5°.
    let culet_corner = culet / 2.0 / 22.5f64.to_radians().cos();
    if culet > 0.0 && r_tip <= culet_corner + 1e-6 {
        return Err(Error::invalid(
            "lower_half",
            format!(
                "{lh} is too long for culet {culet}: the lower halves would reach into the culet; allowed (0, {:.4}) at this culet",
                1.0 - (culet_corner + 1e-6) / R
            ),
        ));
    }
    let tip = main_z(r_tip, 22.5);
    let lh_angle = ((-zg - tip) / ((R - r_tip) * c1125)).atan().to_degrees();
    for k in 0..16 {
        let az = 11.25 + 22.5 * k as f64;
        let n = facet_normal(lh_angle, az, false);
        let ridge = 22.5 * (2 * (k / 2) + 1) as f64;
        out.push(FacetPlane::new(
            n,
            n.dot(at(R, ridge, -zg)),
            format!("lower-half-{}", k + 1),
            "lower-half",
        ));
    }
    if culet > 0.0 {
        let zc = main_z(culet / 2.0, 0.0);
        out.push(FacetPlane::new(DVec3::NEG_Z, -zc, "culet", "culet"));
    }
    Ok(out)
}

/// Vertical girdle facets around the circle of radius R: 16 chords through the 16 points
/// (`n = 0`) or `n` tangent flats.
pub(crate) fn girdle(out: &mut Vec<FacetPlane>, n: usize) {
    let (count, start, offset) = if n == 0 {
        (16, 11.25, R * 11.25f64.to_radians().cos())
    } else {
        (n, 0.0, R)
    };
    for k in 0..count {
        let az = start + 360.0 * k as f64 / count as f64;
        out.push(FacetPlane::new(
            facet_normal(90.0, az, true),
            offset,
            format!("girdle-{}", k + 1),
            "girdle",
        ));
    }
}
