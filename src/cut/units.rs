//! The unit convention, in one place for generated cuts and imports alike (docs/cuts.md's
//! Conventions section): z up, origin at the centre of the girdle plane, lengths in girdle
//! diameters.
//!
//! - **Horizontal**: a facet whose outward normal is within 1° of horizontal
//!   (|n_z| < [`HORIZONTAL`]) is a girdle facet; [`crate::cut::Proportions`] measures the girdle
//!   with it and the mesh import names such facets `girdle`.
//! - **Girdle band**: the heights of the girdle facets' vertices ([`girdle_z`]).
//! - **Width W, the unit of length** ([`outline_size`]): the outline's smaller extent along the
//!   x and y axes (seen from above), its larger extent being the length L. A round's W is its
//!   diameter, a marquise's or an oval's its width across, a princess's its side. Every family
//!   builds its presets with W = 1, and every import (GemCad `.asc`, OBJ/STL) is scaled so that
//!   W = 1, so a preset written to any format reads back at the same size, depths and weight.
//!   Lengths, depths and carat weights are per W (GemCad's ratios L/W, C/W, P/W, H/W, Vol/W³).
//! - **Outline width** ([`outline_width`]): the largest distance between two vertices seen
//!   from above, corner to corner; [`crate::cut::Proportions::table`] is measured against it.
//! - **Girdle frame** ([`girdle_frame`]): where an imported mesh's origin goes (the centre of the
//!   outline's bounding box, at the middle of the girdle band) and its width W.

use crate::geometry::{DVec3, Polyhedron};

/// sin 1°: facets whose normal is closer than this to horizontal (|n_z| below it) are girdle
/// facets.
pub const HORIZONTAL: f64 = 0.0175;

/// Whether a facet with outward unit normal `n` is a girdle facet (within 1° of vertical).
pub fn is_girdle(n: DVec3) -> bool {
    n.z.abs() < HORIZONTAL
}

/// The outline width: the largest horizontal (xy) distance between two of `pts`.
pub fn outline_width(pts: &[DVec3]) -> f64 {
    let mut d: f64 = 0.0;
    for (i, a) in pts.iter().enumerate() {
        for b in &pts[i + 1..] {
            d = d.max((a.truncate() - b.truncate()).length());
        }
    }
    d
}

pub use crate::geometry::outline_size;

/// Heights of the vertices of the girdle facets (see [`is_girdle`]), facet by facet; empty
/// for a knife-edge girdle.
pub fn girdle_z(s: &Polyhedron) -> Vec<f64> {
    s.facets()
        .iter()
        .filter(|f| is_girdle(f.plane.normal))
        .flat_map(|f| f.vertices.iter().map(|&v| s.vertices()[v].z))
        .collect()
}

/// The centre of the girdle plane and the width W ([`outline_size`]) of a solid, for
/// normalising an import:
/// horizontally the centre of the outline's bounding box, vertically the middle of the girdle
/// band or, for a knife-edge girdle, the middle of the heights of the vertices farthest (within
/// 1e-7) from the vertical axis through that centre.
pub fn girdle_frame(s: &Polyhedron) -> (DVec3, f64) {
    let (lo, hi) = s.bounding_box();
    let cx = 0.5 * (lo.x + hi.x);
    let cy = 0.5 * (lo.y + hi.y);
    let girdle = girdle_z(s);
    let zs: Vec<f64> = if girdle.is_empty() {
        let r = |v: &DVec3| (v.x - cx).hypot(v.y - cy);
        let rmax = s.vertices().iter().map(r).fold(0.0, f64::max);
        s.vertices()
            .iter()
            .filter(|v| r(v) >= rmax - 1e-7)
            .map(|v| v.z)
            .collect()
    } else {
        girdle
    };
    let zmin = zs.iter().copied().fold(f64::INFINITY, f64::min);
    let zmax = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let cz = if zmin.is_finite() && zmax.is_finite() {
        0.5 * (zmin + zmax)
    } else {
        0.0
    };
    (DVec3::new(cx, cy, cz), outline_size(s.vertices()).1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brilliant_frame_is_its_own() {
        // A generated round brilliant is already in the frame: origin at the girdle's middle,
        // outline about 1 wide.
        let c = crate::io::load_cut("tolkowsky").unwrap();
        let (o, w) = girdle_frame(&c.solid);
        assert!(o.length() < 1e-9, "{o}");
        assert!(w > 1.0 - 1e-9 && w < 1.01, "{w}");
        let zs = girdle_z(&c.solid);
        let top = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!((top - c.proportions().girdle / 2.0).abs() < 1e-9, "{top}");
        assert!(is_girdle(DVec3::new(1.0, 0.0, 0.017)) && !is_girdle(DVec3::new(1.0, 0.0, 0.018)));
    }
}
