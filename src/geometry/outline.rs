//! The extents of a solid's outline seen from above.

use super::{DVec2, DVec3};

/// The outline's extents along x and y, as (length, width): the larger and the smaller.
pub fn outline_size(pts: &[DVec3]) -> (f64, f64) {
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for p in pts {
        lo = lo.min(p.truncate());
        hi = hi.max(p.truncate());
    }
    let e = hi - lo;
    if !(e.x.is_finite() && e.y.is_finite()) {
        return (0.0, 0.0);
    }
    (e.x.max(e.y), e.x.min(e.y))
}
