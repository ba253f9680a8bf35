//! A brilliant facet layout around any convex girdle outline: the construction shared by the
//! oval, marquise, pear and cushion families.
//!
//! The outline is given by 16 girdle points P0…P15, counter-clockwise from the +x axis. The even
//! ones are the *main points* (where bezels and pavilion mains touch the girdle); the odd ones are
//! the *ridge points* between them (where the upper and lower halves meet the girdle). Each main
//! point also carries the outline's outward normal ν there (at a pointed tip: the bisector).
//! The layout is the round brilliant's, generalised to the outline:
//!
//! - girdle: 16 vertical flats, the chords P_j P_{j+1} (the outline is touched at the 16 points),
//!   from z = −girdle/2 to +girdle/2; none for a knife-edge girdle (girdle = 0);
//! - table: the octagon of main points scaled by `table` about the outline's centre (the point
//!   under the culet), so the table has the outline's shape and is `table` wide across the stone;
//!   its height is set by the two bezels facing across the width (±y), which are cut at
//!   `crown_angle`: crown height = (1 − table)/2 · tan(crown angle), as for the round;
//! - bezels: each runs from its main point on the girdle top up to its table corner. Bezels whose
//!   main point lies farther from the centre are flatter: tan α = tan(crown angle)·(1/2)/s, with s
//!   the distance of the girdle tangent at the main point from the centre — on a marquise of
//!   length 2 the bezels at the points are at about half the crown angle's tangent. (A single
//!   angle for every bezel cannot work at a pointed tip: the bezels next to the tip would cut the
//!   tip bezel off below the table unless the table were very large.) `info` reports the mean
//!   bezel angle, which is therefore below `crown_angle` on elongated shapes;
//! - stars: through two neighbouring table corners and the star tip on the bezel–bezel ridge. The
//!   tip is the ridge point above (the projection of) E + star·(P_ridge − E), E the table-edge
//!   midpoint — exactly the round brilliant's rule, where that point already lies on the ridge.
//!   As on the round, a short star with a large table would put the tips above the table: the
//!   build then names the star lengths that work;
//! - upper halves: through a star tip, its ridge point and one of the two neighbouring main points;
//! - pavilion mains: every main at `pavilion_angle`, facing ν, touching the girdle bottom at its
//!   main point. On an elongated outline the mains do not meet in a point but in a keel (a ridge
//!   along the length), as on real ovals and marquises;
//! - lower halves: through the main–main ridge point a share `lower_half` of the way from the
//!   girdle (the ridge point above the girdle's ridge point) down to the ridge's lower end, its
//!   ridge point and one neighbouring main point — again the round's rule;
//! - culet (optional): a horizontal facet where the keel is `culet` wide across the stone.
//!
//! With all outlines used here the pavilion's lowest point lies tan(pavilion angle)/2 below the
//! girdle (the mains facing ±y are 1/2 from the keel), so the total depth is
//! girdle + ((1 − table)·tan(crown) + tan(pavilion))/2, whatever the length. With a circle this
//! construction gives exactly the round brilliant (with its 16-flat girdle).

use super::construct::{check_solid, cross_lines, lift, plane_through_or};
use super::{ParamDef, Params, Unit};
use crate::error::{Error, Result};
use crate::geometry::{DVec2, DVec3, FacetPlane};

const TOL: f64 = 1e-9;

/// The parameters the brilliants around an outline (marquise, pear, oval) share after their
/// `length_width`; a family changes a field where it differs (`ParamDef { max: …, ..TABLE }`).
pub(super) const TABLE: ParamDef = ParamDef {
    key: "table",
    default: 0.57,
    min: 0.45,
    max: 0.65,
    open: false,
    unit: Unit::Fraction,
    doc: "table width across the stone, as a fraction of the width",
};

pub(super) const CROWN_ANGLE: ParamDef = ParamDef {
    key: "crown_angle",
    default: 34.0,
    min: 20.0,
    max: 45.0,
    open: false,
    unit: Unit::Degrees,
    doc: "angle of every bezel to the girdle plane",
};

pub(super) const PAVILION_ANGLE: ParamDef = ParamDef {
    key: "pavilion_angle",
    default: 41.0,
    min: 35.0,
    max: 50.0,
    open: false,
    unit: Unit::Degrees,
    doc: "angle of every pavilion main to the girdle plane",
};

pub(super) const GIRDLE: ParamDef = ParamDef {
    key: "girdle",
    default: 0.025,
    min: 0.0,
    max: 0.1,
    open: false,
    unit: Unit::Fraction,
    doc: "girdle thickness at the 16 girdle points",
};

pub(super) const STAR: ParamDef = ParamDef {
    key: "star",
    default: 0.5,
    min: 0.4,
    max: 0.8,
    open: false,
    unit: Unit::Fraction,
    doc: "star length: share of the table-edge-to-girdle distance along the bezel ridge",
};

pub(super) const LOWER_HALF: ParamDef = ParamDef {
    key: "lower_half",
    default: 0.75,
    min: 0.5,
    max: 0.9,
    open: false,
    unit: Unit::Fraction,
    doc: "lower-half length: share of the girdle-to-keel distance along the main ridge",
};

pub(super) const CULET: ParamDef = ParamDef {
    key: "culet",
    default: 0.0,
    min: 0.0,
    max: 0.1,
    open: false,
    unit: Unit::Fraction,
    doc: "culet (flattened keel) width across the stone (0 = sharp keel)",
};

/// A convex girdle outline sampled at the 16 points of the 8-main brilliant layout.
#[derive(Clone, Debug)]
pub(crate) struct Outline {
    /// Girdle points, counter-clockwise, P0 on the +x axis; even = main points, odd = ridge points.
    pub points: [DVec2; 16],
    /// Outward unit normals at the main points P0, P2, …, P14.
    pub normals: [DVec2; 8],
    /// A point well inside the outline (the culet's side), used to orient planes.
    pub centre: DVec2,
}

impl Outline {
    /// From the upper half P0…P8 and its normals ν0…ν4 (P0 and P8 on the x axis), mirrored
    /// in y.
    pub fn from_upper_half(p: [DVec2; 9], n: [DVec2; 5], centre: DVec2) -> Outline {
        let mut points = [DVec2::ZERO; 16];
        let mut normals = [DVec2::ZERO; 8];
        for j in 0..16 {
            points[j] = if j <= 8 {
                p[j]
            } else {
                DVec2::new(p[16 - j].x, -p[16 - j].y)
            };
        }
        for k in 0..8 {
            normals[k] = if k <= 4 {
                n[k]
            } else {
                DVec2::new(n[8 - k].x, -n[8 - k].y)
            };
        }
        Outline {
            points,
            normals,
            centre,
        }
    }

    /// From the first quadrant P0…P4 and its normals ν0…ν2 (P0 on the x axis, P4 on the y axis),
    /// mirrored in x and y.
    pub fn from_quadrant(q: [DVec2; 5], n: [DVec2; 3]) -> Outline {
        let mut p = [DVec2::ZERO; 9];
        for j in 0..=4 {
            p[j] = q[j];
            p[8 - j] = DVec2::new(-q[j].x, q[j].y);
        }
        let nn = [
            n[0],
            n[1],
            n[2],
            DVec2::new(-n[1].x, n[1].y),
            DVec2::new(-n[0].x, n[0].y),
        ];
        Outline::from_upper_half(p, nn, DVec2::ZERO)
    }
}

/// Which parameter governs a tier of the brilliant layout (for errors).
pub(crate) fn key_of_tier(tier: &str) -> &'static str {
    match tier {
        "star" | "upper-half" => "star",
        "lower-half" | "pavilion-main" => "lower_half",
        "girdle" => "girdle",
        "culet" => "culet",
        "bezel" | "table" => "table",
        _ => "crown_angle",
    }
}

/// The facet planes of a brilliant around `o`, from the keys `table`, `crown_angle`,
/// `pavilion_angle`, `girdle`, `star`, `lower_half`, `culet`. `family` names the shape in errors.
pub(crate) fn brilliant(o: &Outline, p: &Params, family: &str) -> Result<Vec<FacetPlane>> {
    let t = p.get("table")?;
    let crown = p.get("crown_angle")?.to_radians();
    let pav = p.get("pavilion_angle")?.to_radians();
    let g = p.get("girdle")?;
    let star = p.get("star")?;
    let lh = p.get("lower_half")?;
    let culet = p.get("culet")?;
    let pts = &o.points;
    let nu = &o.normals;
    let inside = lift(o.centre, 0.0);
    let zg = g / 2.0;
    let c = o.centre;
    // Distance of each main point's girdle tangent from the centre.
    let reach: Vec<f64> = (0..8).map(|k| nu[k].dot(pts[2 * k] - c)).collect();
    let height = (1.0 - t) * reach[2] * crown.tan();
    let zt = zg + height;
    let h: Vec<f64> = (0..8).map(|k| nu[k].dot(pts[2 * k])).collect();
    let mut out = Vec::with_capacity(74);

    // Table corners (the main points scaled about the centre); each must stay its bezel's top.
    let tc: Vec<DVec2> = (0..8).map(|k| c + t * (pts[2 * k] - c)).collect();
    // Inset of each bezel's table edge from its girdle tangent, and the bezel's angle.
    let inset: Vec<f64> = (0..8).map(|k| (1.0 - t) * reach[k]).collect();
    for k in 0..8 {
        for j in 0..8 {
            if j != k && nu[k].dot(tc[j]) > nu[k].dot(tc[k]) - TOL {
                return Err(Error::invalid(
                    "table",
                    format!(
                        "{t} is not possible for this {family} outline: at the table the bezels would cut off the table's corners"
                    ),
                ));
            }
        }
    }
    out.push(FacetPlane::new(DVec3::Z, zt, "table", "table"));
    let bezel: Vec<DVec3> = (0..8)
        .map(|k| {
            let a = height.atan2(inset[k]);
            DVec3::new(a.sin() * nu[k].x, a.sin() * nu[k].y, a.cos())
        })
        .collect();
    for k in 0..8 {
        out.push(FacetPlane::new(
            bezel[k],
            bezel[k].dot(lift(pts[2 * k], zg)),
            format!("bezel-{}", k + 1),
            "bezel",
        ));
    }
    // Star tips on the bezel–bezel ridges. The tip's height below the table is linear in `star`;
    // every ridge gives an interval of stars whose tips lie between the table and the girdle.
    let mut ridge_pts = Vec::with_capacity(8);
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for k in 0..8 {
        let k1 = (k + 1) % 8;
        let q =
            cross_lines(nu[k], h[k] - inset[k], nu[k1], h[k1] - inset[k1]).ok_or_else(|| {
                Error::invalid(
                    "table",
                    format!("bezels {} and {} are parallel", k + 1, k1 + 1),
                )
            })?;
        let r = bezel[k].cross(bezel[k1]);
        let rxy = r.truncate();
        let e = (tc[k] + tc[k1]) / 2.0;
        let along = |x: DVec2| (x - q).dot(rxy) / rxy.length_squared();
        let (le, lp) = (along(e), along(pts[2 * k + 1]));
        // Drop below the table at star = s: −(le + s (lp − le)) r.z.
        let (f0, slope) = (-le * r.z, -(lp - le) * r.z);
        if slope.is_nan() || slope <= 1e-12 {
            return Err(Error::invalid(
                "star",
                format!("the star tips of this {family} cannot be placed with table {t}"),
            ));
        }
        lo = lo.max((TOL - f0) / slope);
        hi = hi.min((zt - zg - TOL - f0) / slope);
        ridge_pts.push((q, r, le, lp));
    }
    if !(star > lo && star < hi) {
        let (a, b) = (
            (lo * 1000.0).ceil() / 1000.0,
            (hi * 1000.0).floor() / 1000.0,
        );
        let why = if star <= lo {
            "short: the star tips would lie above the table"
        } else {
            "long: the star tips would reach the girdle"
        };
        let allowed = if a >= b {
            "no star length works; change table".to_string()
        } else if b >= 1.0 {
            format!("use star above {a}")
        } else {
            format!("use star between {a} and {b}")
        };
        return Err(Error::invalid(
            "star",
            format!("{star} is too {why} (table {t} on this {family}); {allowed}"),
        ));
    }
    let tips: Vec<DVec3> = ridge_pts
        .iter()
        .map(|(q, r, le, lp)| lift(*q, zt) + (le + star * (lp - le)) * *r)
        .collect();
    for k in 0..8 {
        let k1 = (k + 1) % 8;
        let pl = [lift(tc[k], zt), lift(tc[k1], zt), tips[k]];
        out.push(plane_through_or(
            pl,
            inside,
            format!("star-{}", k + 1),
            "star",
            "star",
        )?);
    }
    for k in 0..8 {
        let ridge = lift(pts[2 * k + 1], zg);
        for (i, main) in [2 * k, (2 * k + 2) % 16].into_iter().enumerate() {
            let pl = [tips[k], ridge, lift(pts[main], zg)];
            out.push(plane_through_or(
                pl,
                inside,
                format!("upper-half-{}", 2 * k + i + 1),
                "upper-half",
                "star",
            )?);
        }
    }
    if g > 0.0 {
        for j in 0..16 {
            let (a, b) = (pts[j], pts[(j + 1) % 16]);
            let e = b - a;
            let n = DVec2::new(e.y, -e.x).normalize();
            out.push(FacetPlane::new(
                lift(n, 0.0),
                n.dot(a),
                format!("girdle-{}", j + 1),
                "girdle",
            ));
        }
    }
    // Pavilion mains.
    let main: Vec<DVec3> = (0..8)
        .map(|k| DVec3::new(pav.sin() * nu[k].x, pav.sin() * nu[k].y, -pav.cos()))
        .collect();
    let main_off: Vec<f64> = (0..8).map(|k| main[k].dot(lift(pts[2 * k], -zg))).collect();
    for k in 0..8 {
        out.push(FacetPlane::new(
            main[k],
            main_off[k],
            format!("pavilion-main-{}", k + 1),
            "pavilion-main",
        ));
    }
    // Main–main ridges: upper reference point U (above the girdle's ridge point) and lower end V.
    let mut ridges = Vec::with_capacity(8);
    for k in 0..8 {
        let k1 = (k + 1) % 8;
        let q = cross_lines(nu[k], h[k], nu[k1], h[k1]).ok_or_else(|| {
            Error::invalid(
                "pavilion_angle",
                format!("mains {} and {} are parallel", k + 1, k1 + 1),
            )
        })?;
        let mut m = main[k].cross(main[k1]);
        if m.z > 0.0 {
            m = -m;
        }
        let mxy = m.truncate();
        let u = lift(q, -zg) + ((pts[2 * k + 1] - q).dot(mxy) / mxy.length_squared()) * m;
        let mut end = f64::INFINITY;
        for j in (0..8).filter(|&j| j != k && j != k1) {
            let s = main[j].dot(m);
            if s > 1e-12 {
                end = end.min((main_off[j] - main[j].dot(u)) / s);
            }
        }
        if !end.is_finite() || end <= TOL {
            return Err(Error::invalid(
                "lower_half",
                format!("the pavilion mains of this {family} do not form ridges between their girdle points (ridge {})", k + 1),
            ));
        }
        ridges.push((u, u + end * m));
    }
    let bottom = ridges
        .iter()
        .map(|(_, v)| v.z)
        .fold(f64::INFINITY, f64::min);
    let z_culet = bottom + culet / 2.0 * pav.tan();
    let mut lows = Vec::with_capacity(8);
    for &(u, v) in &ridges {
        let l = v + (1.0 - lh) * (u - v);
        if l.z.is_nan() || l.z >= -zg - TOL {
            return Err(Error::invalid(
                "lower_half",
                format!("{lh} is too short for this {family}: the lower-half tips would not be below the girdle"),
            ));
        }
        if culet > 0.0 && l.z <= z_culet + TOL {
            let most = ((1.0 - (z_culet - v.z) / (u.z - v.z)) * 1000.0).floor() / 1000.0;
            return Err(Error::invalid(
                "lower_half",
                format!("{lh} is too long for culet {culet} on this {family}: the lower-half tips would reach the culet; use lower_half below {most} or a smaller culet"),
            ));
        }
        lows.push(l);
    }
    for k in 0..8 {
        let ridge = lift(pts[2 * k + 1], -zg);
        for (i, m) in [2 * k, (2 * k + 2) % 16].into_iter().enumerate() {
            let pl = [lows[k], ridge, lift(pts[m], -zg)];
            out.push(plane_through_or(
                pl,
                inside,
                format!("lower-half-{}", 2 * k + i + 1),
                "lower-half",
                "lower_half",
            )?);
        }
    }
    if culet > 0.0 {
        out.push(FacetPlane::new(DVec3::NEG_Z, -z_culet, "culet", "culet"));
    }
    check_solid(family, &out, p, key_of_tier)?;
    Ok(out)
}
