//! Step-cut rings shared by the emerald cut and the princess's crown.
//!
//! A *ring* is a horizontal octagon at height z: a rectangle of half-length a (x) and half-width
//! b (y) whose four corners are bevelled at 45° with legs c (c = 0: sharp corners). A *band*
//! of facets joins an outer ring to the next inner one (higher on the crown, lower on the
//! pavilion): one trapezoid per side, and one per bevelled corner, each the plane through the
//! two rings' parallel edges. A stack of nested rings whose side profile and corner profile both
//! flatten toward the centre is convex and every band facet appears. Insets are applied equally to
//! all four sides, so the side facets of one band share one angle; corner legs shrink in
//! proportion to the ring's width, so the rings (and the table) keep the girdle's corner shape.

use crate::geometry::{DVec3, FacetPlane};

/// One horizontal ring of a step stack.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ring {
    /// Half-length (x).
    pub a: f64,
    /// Half-width (y).
    pub b: f64,
    /// Corner bevel leg along each side (0 = sharp corner).
    pub c: f64,
    /// Height.
    pub z: f64,
}

/// The two sign flips that carry the +x+y quadrant to the corner at `45° + 90°·k`.
const QUADRANTS: [(f64, f64); 4] = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)];

/// Append the band of facets between `outer` and `inner`, in azimuth order (+x side, +x+y corner,
/// +y side, …). Side facets get tier `side_tier`, corner facets `corner_tier` (skipped when both
/// rings have sharp corners).
pub(crate) fn band(
    outer: &Ring,
    inner: &Ring,
    side_tier: &str,
    corner_tier: &str,
    out: &mut Vec<FacetPlane>,
) {
    let wz = inner.z - outer.z;
    // +x side: contains the y direction and (Δa, 0, Δz).
    let wa = inner.a - outer.a;
    let nx = DVec3::new(wz, 0.0, -wa);
    let nx = if nx.x < 0.0 { -nx } else { nx }.normalize();
    let ox = nx.dot(DVec3::new(outer.a, 0.0, outer.z));
    let wb = inner.b - outer.b;
    let ny = DVec3::new(0.0, wz, -wb);
    let ny = if ny.y < 0.0 { -ny } else { ny }.normalize();
    let oy = ny.dot(DVec3::new(0.0, outer.b, outer.z));
    // +x+y corner: contains the bevel direction (−1, 1, 0) and the step between bevel midpoints.
    let mid = |r: &Ring| DVec3::new(r.a - r.c / 2.0, r.b - r.c / 2.0, r.z);
    let t = DVec3::new(-1.0, 1.0, 0.0);
    let nc = t.cross(mid(inner) - mid(outer));
    let nc = if nc.x + nc.y < 0.0 { -nc } else { nc }.normalize();
    let oc = nc.dot(mid(outer));
    let corners = outer.c > 0.0 || inner.c > 0.0;
    for (k, (sx, sy)) in QUADRANTS.iter().enumerate() {
        let side = match k {
            0 => FacetPlane::new(nx, ox, format!("{side_tier}-1"), side_tier),
            1 => FacetPlane::new(ny, oy, format!("{side_tier}-2"), side_tier),
            2 => FacetPlane::new(
                DVec3::new(-nx.x, 0.0, nx.z),
                ox,
                format!("{side_tier}-3"),
                side_tier,
            ),
            _ => FacetPlane::new(
                DVec3::new(0.0, -ny.y, ny.z),
                oy,
                format!("{side_tier}-4"),
                side_tier,
            ),
        };
        out.push(side);
        if corners {
            let n = DVec3::new(sx * nc.x, sy * nc.y, nc.z);
            out.push(FacetPlane::new(
                n,
                oc,
                format!("{corner_tier}-{}", k + 1),
                corner_tier,
            ));
        }
    }
}

/// The vertical girdle of `ring` (sides and bevelled corners), tier `girdle`.
pub(crate) fn girdle(ring: &Ring, out: &mut Vec<FacetPlane>) {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let sides = [
        (DVec3::X, ring.a),
        (DVec3::Y, ring.b),
        (DVec3::NEG_X, ring.a),
        (DVec3::NEG_Y, ring.b),
    ];
    let mut i = 0;
    for (k, (sx, sy)) in QUADRANTS.iter().enumerate() {
        i += 1;
        out.push(FacetPlane::new(
            sides[k].0,
            sides[k].1,
            format!("girdle-{i}"),
            "girdle",
        ));
        if ring.c > 0.0 {
            i += 1;
            let n = DVec3::new(sx * s, sy * s, 0.0);
            out.push(FacetPlane::new(
                n,
                (ring.a + ring.b - ring.c) * s,
                format!("girdle-{i}"),
                "girdle",
            ));
        }
    }
}

/// Rings of a stack: `n` equal insets from `start` (inset `inset` in total), each step's height
/// change `inset / n · tan(angle_i)` upward (`up`) or downward; corner legs follow the width.
pub(crate) fn stack(start: Ring, corner: f64, inset: f64, angles: &[f64], up: bool) -> Vec<Ring> {
    let n = angles.len();
    let w = inset / n as f64;
    let mut rings = vec![start];
    let mut z = start.z;
    for (i, ang) in angles.iter().enumerate() {
        let dz = w * ang.to_radians().tan();
        z += if up { dz } else { -dz };
        let d = w * (i + 1) as f64;
        let b = (start.b - d).max(0.0);
        rings.push(Ring {
            a: start.a - d,
            b,
            c: corner * 2.0 * b,
            z,
        });
    }
    rings
}
