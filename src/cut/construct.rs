//! Small construction helpers shared by the families: planes through meet points, and the final
//! check that every facet of a generated design really appears on the solid (reported as an
//! error naming the parameter to change, never as a silently missing facet).

use super::Params;
use crate::error::{Error, Result};
use crate::geometry::{DVec2, DVec3, FacetPlane, Polyhedron};

/// A point of the girdle outline lifted to height `z`.
pub(crate) fn lift(p: DVec2, z: f64) -> DVec3 {
    DVec3::new(p.x, p.y, z)
}

/// The plane through `a`, `b`, `c`, with its normal pointing away from `inside`. `None` when the
/// points are (nearly) collinear.
pub(crate) fn plane_through(
    a: DVec3,
    b: DVec3,
    c: DVec3,
    inside: DVec3,
    name: String,
    tier: &str,
) -> Option<FacetPlane> {
    let n = (b - a).cross(c - a);
    let len = n.length();
    if !(len.is_finite() && len > 1e-14) {
        return None;
    }
    let mut n = n / len;
    if n.dot(inside - a) > 0.0 {
        n = -n;
    }
    Some(FacetPlane::new(n, n.dot(a), name, tier))
}

/// Like [`plane_through`], with an error naming `key` when the points are collinear.
pub(crate) fn plane_through_or(
    pts: [DVec3; 3],
    inside: DVec3,
    name: String,
    tier: &str,
    key: &str,
) -> Result<FacetPlane> {
    let shown = name.clone();
    plane_through(pts[0], pts[1], pts[2], inside, name, tier).ok_or_else(|| {
        Error::invalid(
            key,
            format!("facet {shown} degenerates to a line with these proportions; change {key}"),
        )
    })
}

/// Solve the 2×2 system `n1·x = c1`, `n2·x = c2` (the crossing of two lines in the plane).
pub(crate) fn cross_lines(n1: DVec2, c1: f64, n2: DVec2, c2: f64) -> Option<DVec2> {
    let det = n1.x * n2.y - n1.y * n2.x;
    if det.abs() < 1e-14 {
        return None;
    }
    Some(DVec2::new(
        (c1 * n2.y - c2 * n1.y) / det,
        (n1.x * c2 - n2.x * c1) / det,
    ))
}

/// Build the solid once and turn a vanished or degenerate facet into an error naming the
/// parameter that governs its tier (`key_of(tier)`), with the values that were used.
pub(crate) fn check_solid(
    family: &str,
    planes: &[FacetPlane],
    p: &Params,
    key_of: fn(&str) -> &'static str,
) -> Result<()> {
    let Err(e) = Polyhedron::from_planes(planes) else {
        return Ok(());
    };
    let msg = e.to_string();
    let culprit = planes
        .iter()
        .find(|f| msg.contains(&format!("({}, tier ", f.name)));
    let key = culprit
        .map(|f| key_of(&f.tier))
        .unwrap_or_else(|| key_of(""));
    let what = match culprit {
        Some(f) => format!("facet {} vanishes", f.name),
        None => "the facets do not close into a valid solid".to_string(),
    };
    Err(Error::invalid(
        key,
        format!(
            "{} {} is not possible here: {what} ({}); allowed combinations need a different {key}",
            family,
            summary(p),
            msg.trim_start_matches("geometry: ")
        ),
    ))
}

/// `key=value` list of a parameter set, for error messages.
pub(crate) fn summary(p: &Params) -> String {
    let parts: Vec<String> = p.values().iter().map(|(k, v)| format!("{k}={v}")).collect();
    format!("with {}", parts.join(" "))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cut::family;
    use std::collections::BTreeMap;

    #[test]
    fn vanished_facet_is_reported_on_its_key() {
        let p = family("sphere").unwrap().params(&BTreeMap::new()).unwrap();
        let mut planes: Vec<FacetPlane> = [
            DVec3::X,
            DVec3::NEG_X,
            DVec3::Y,
            DVec3::NEG_Y,
            DVec3::Z,
            DVec3::NEG_Z,
        ]
        .iter()
        .enumerate()
        .map(|(i, n)| FacetPlane::new(*n, 0.5, format!("side-{i}"), "side"))
        .collect();
        assert!(check_solid("box", &planes, &p, |_| "facets").is_ok());
        planes.push(FacetPlane::new(
            DVec3::new(1.0, 1.0, 0.0).normalize(),
            2.0,
            "star-1",
            "star",
        ));
        let key_of = |tier: &str| if tier == "star" { "star" } else { "other" };
        let e = check_solid("box", &planes, &p, key_of)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("star:") && e.contains("star-1 vanishes") && e.contains("facets=120"),
            "{e}"
        );
        assert!(!e.contains('\n'));
        let collinear = [DVec3::ZERO, DVec3::X, 2.0 * DVec3::X];
        let e = plane_through_or(collinear, DVec3::Z, "f".into(), "t", "lower_half")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("lower_half:"), "{e}");
        assert_eq!(
            cross_lines(DVec2::X, 1.0, DVec2::Y, 2.0),
            Some(DVec2::new(1.0, 2.0))
        );
        assert_eq!(cross_lines(DVec2::X, 1.0, DVec2::X, 2.0), None);
    }
}
