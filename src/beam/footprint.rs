//! Footprints: the affine map taking a point inside the stone to the spot of the incoming
//! cross-section (the frame's image coordinates) whose ray reaches it, carried along each beam
//! and slid along its direction at every facet it meets.

use glam::{DVec2, DVec3};

/// Affine map from a point in the stone to its footprint in the frame's image coordinates:
/// `(a1 · x + b.x, a2 · x + b.y)`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Affine {
    pub(super) a1: DVec3,
    pub(super) a2: DVec3,
    pub(super) b: DVec2,
}

/// Path length inside the stone, from the entry facet, of the ray reaching a point `x` on the
/// plane of the facet a beam sits on: `h · x + l` (affine over the beam's cross-section, the
/// stone being convex and the rays parallel). Slid along the beam like [`Affine`].
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct PathLength {
    pub(super) h: DVec3,
    pub(super) l: f64,
}

impl PathLength {
    #[inline]
    pub(super) fn at(&self, x: DVec3) -> f64 {
        self.h.dot(x) + self.l
    }
    /// The path length at points reached by travelling along `t` (unit) from the plane
    /// `n · x = o` (where this one applies): the length there plus the stretch travelled,
    /// `s = (n · y − o) / (n · t)`.
    #[inline]
    pub(super) fn slide(&self, t: DVec3, n: DVec3, o: f64) -> PathLength {
        let k = (1.0 - self.h.dot(t)) / n.dot(t);
        PathLength {
            h: self.h + n * k,
            l: self.l - o * k,
        }
    }
}

impl PathLength {
    /// [`PathLength::slide`] for a weighted length: each unit of path travelled along `t`
    /// adds `a` (an optical depth `Σ αᵢ Lᵢ`, a birefringent stone's per-mode absorption
    /// times each segment's length: still affine over a beam's cross-section).
    #[inline]
    pub(super) fn slide_weighted(&self, t: DVec3, n: DVec3, o: f64, a: f64) -> PathLength {
        let k = (a - self.h.dot(t)) / n.dot(t);
        PathLength {
            h: self.h + n * k,
            l: self.l - o * k,
        }
    }
}

impl Affine {
    #[inline]
    pub(super) fn apply(&self, x: DVec3) -> DVec2 {
        DVec2::new(self.a1.dot(x) + self.b.x, self.a2.dot(x) + self.b.y)
    }
    /// The map for points reached by travelling along `t` from the plane `n · x = o` (where
    /// this map applies): first slide back along `t` onto that plane.
    #[inline]
    pub(super) fn slide(&self, t: DVec3, n: DVec3, o: f64) -> Affine {
        let k = n.dot(t);
        let at = DVec2::new(self.a1.dot(t), self.a2.dot(t));
        Affine {
            a1: self.a1 - n * (at.x / k),
            a2: self.a2 - n * (at.y / k),
            b: self.b + at * (o / k),
        }
    }
}
