//! The canonical placement of a solid for scoring, which makes every score depend on the
//! solid only, not on how it is written down.
//!
//! The same stone can reach `metrics::score` as different lists of numbers: moved or scaled
//! (an OBJ exported in millimetres, a design not centred on the girdle), rotated onto itself
//! by one of its symmetries (a round brilliant turned by 45°, or by 90° through a coordinate
//! swap in an OBJ), or with its facets in another order. The tracer's work depends on those
//! numbers in small ways: the fundamental wedge it traces for a symmetric stone starts at a
//! facet it finds first, narrow beams fall differently on differently split beams, and its
//! thresholds are absolute lengths. [`canonical`] therefore rebuilds the solid from its facet
//! planes after three normalisations:
//!
//! * **translation**: the volume centroid goes to the origin (it lies on every symmetry axis);
//! * **scale**: lengths are divided by the diameter of the circle with the face-up outline's
//!   area, so a stone scores the same in any unit (scores are ratios; only the tracer's
//!   absolute tolerances ever saw the size);
//! * **rounding**: normals and offsets are rounded to multiples of 2⁻³⁶ (about 1.5e-11), so
//!   the same solid reached through different arithmetic (a rotated copy whose normals came
//!   from other sines and cosines, a centroid computed from other vertices) becomes the very
//!   same numbers and traces identically;
//! * **facet order**: facets are sorted by a key that is the same for the same set of planes
//!   (tilt, distance from the centroid, azimuth), so the tracer's first facet — and the
//!   symmetry wedge it derives from it — is the same facet of the same solid;
//!
//! Rounding also settles the tracer's choice of symmetry wedge: cuts are drawn with mirror
//! lines on azimuth 0, and the tracer reduces a mirror's azimuth modulo the symmetry's angle;
//! a mirror at ±1e-17 lands on either end of that range and gives one of two wedges (the same
//! light, split differently, so the narrow-beam approximation differed by up to 1e-4).
//! Rounded, a normal on azimuth 0 has a y component of exactly 0.
//!
//! * **azimuth**: the stone is turned about its axis to a canonical azimuth, so that a stone
//!   turned by any angle scores exactly as it does unturned (see [`azimuth_turn`]). Its
//!   rotation order `k` about the axis is the smallest `m` whose harmonic
//!   `F_m = Σ A·|n_xy|·(2 + n_z)·e^{i·m·φ}` over the facets (area `A`, normal `n` at azimuth
//!   `φ`) is not zero (above 1e-5 of `Σ A·|n_xy|·(2 + n_z)`: a mesh's 32-bit rounding, ~1e-7,
//!   does not break a symmetry). The stone is turned until `F_k` is a real number: negative
//!   for `k = 2` (an oval, marquise or emerald, whose long sides face ±y, lies along x),
//!   positive otherwise (which keeps every bundled preset as it is drawn). Turned copies then
//!   differ only by a turn through `360°/k`, one of the stone's own symmetries, so they are
//!   the same solid. For a stone with mirror symmetry, `F_k` real puts a mirror line on
//!   azimuth 0, as cuts are drawn (and where the tracer's symmetry wedges are cheapest).
//!
//! Turning the stone on the lights is still a different pose: the scores average over it
//! (see the module documentation of `metrics`), and the canonical azimuth only fixes where
//! that average starts.

use crate::geometry::{FacetPlane, Polyhedron};
use glam::{DMat3, DVec2, DVec3};

/// Quantum of the sort keys (relative to the canonical size, and radians).
const QUANTUM: f64 = 1e-7;

/// Grid the canonical normals and offsets are rounded to.
const GRID: f64 = 1.0 / (1u64 << 36) as f64;

/// The solid moved, scaled, rounded and with its facets ordered as described in the module
/// documentation; the solid itself (cloned) when it is degenerate.
pub fn canonical(solid: &Polyhedron) -> Polyhedron {
    let c = solid.centroid();
    let area = solid.projected_area(DVec3::Z);
    let size = (4.0 * area / std::f64::consts::PI).sqrt();
    if !(c.is_finite() && size.is_finite() && size > 0.0) {
        return solid.clone();
    }
    let k = 1.0 / size;
    let grid = |x: f64| (x / GRID).round() * GRID;
    let turn = DMat3::from_rotation_z(azimuth_turn(solid));
    let mut keyed: Vec<((i64, i64, i64), FacetPlane)> = solid
        .facet_planes()
        .into_iter()
        .map(|mut f| {
            let n = f.plane.normal;
            let offset = grid((f.plane.offset - n.dot(c)) * k);
            let n = turn * n;
            let n = DVec3::new(grid(n.x), grid(n.y), grid(n.z)).normalize();
            f.plane.normal = n;
            f.plane.offset = offset;
            (sort_key(n, offset), f)
        })
        .collect();
    keyed.sort_by_key(|k| k.0);
    let planes: Vec<FacetPlane> = keyed.into_iter().map(|(_, f)| f).collect();
    Polyhedron::from_planes(&planes).unwrap_or_else(|_| solid.clone())
}

/// Largest rotation order looked for (a round brilliant has 8, some fancy designs 16 or 32).
const MAX_ORDER: usize = 96;

/// Turns smaller than this (radians) are not made.
const SNAP_TURN: f64 = 1e-9;

/// A harmonic smaller than this share of the total weight counts as zero.
const ZERO_HARMONIC: f64 = 1e-5;

/// The angle (radians, counter-clockwise about +z) that turns `solid` to its canonical
/// azimuth (see the module documentation), and 0 when no harmonic up to order 96 stands out
/// (a solid of revolution, or one with no tilted facets).
pub fn azimuth_turn(solid: &Polyhedron) -> f64 {
    turn_and_order(solid).0
}

/// [`azimuth_turn`] and the rotation order it found (1 when none).
fn turn_and_order(solid: &Polyhedron) -> (f64, usize) {
    // Per tilted facet: weight and unit horizontal direction of its normal.
    // Per tilted facet: weight and unit horizontal direction of its normal (normals, unlike
    // vertices, are known to the last bit, so the phase is too).
    let terms: Vec<(f64, DVec2)> = solid
        .facets()
        .iter()
        .filter_map(|f| {
            let n = f.plane.normal;
            let h = n.truncate();
            let r = h.length();
            (r > 1e-9 && f.area > 0.0).then(|| (f.area * r * (2.0 + n.z), h / r))
        })
        .collect();
    let total: f64 = terms.iter().map(|t| t.0).sum();
    if !(total.is_finite() && total > 0.0) {
        return (0.0, 1);
    }
    // Complex powers e^{i m φ} by repeated multiplication, all orders at once.
    let mul = |a: DVec2, b: DVec2| DVec2::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
    let mut pow: Vec<DVec2> = terms.iter().map(|t| t.1).collect();
    for m in 1..=MAX_ORDER {
        let f: DVec2 = terms.iter().zip(&pow).map(|(t, p)| *p * t.0).sum();
        if f.length() > ZERO_HARMONIC * total {
            // Turn by ψ so that F_m · e^{i m ψ} is a negative (m = 2) or positive real
            // number, reduced to the smallest turn (turns through 2π/m differ by a symmetry).
            let target = if m == 2 { std::f64::consts::PI } else { 0.0 };
            let phase = f.y.atan2(f.x);
            let step = std::f64::consts::TAU / m as f64;
            let psi = ((target - phase) / m as f64).rem_euclid(step);
            let psi = if psi > 0.5 * step { psi - step } else { psi };
            // The phase is known to ~1e-13 (the harmonic is a sum of terms that largely
            // cancel): a smaller turn is none, so a stone already at its canonical azimuth,
            // or turned onto itself by a symmetry, keeps its very numbers.
            return (if psi.abs() < SNAP_TURN { 0.0 } else { psi }, m);
        }
        for (p, t) in pow.iter_mut().zip(&terms) {
            *p = mul(*p, t.1);
        }
    }
    (0.0, 1)
}

/// A birefringent stone's optic axis (unit, in `solid`'s coordinates) as it lies in the
/// canonical solid ([`canonical`]), so that a stone turned with its axis scores as it does
/// unturned. The canonical turn takes it along; then, of the turns through 2π/k that the
/// stone's rotation order `k` allows (they leave the canonical solid as it is), the one that
/// brings the axis's azimuth into [0, 2π/k) is taken, and the axis is given pointing up (a
/// uniaxial crystal is the same along ĉ and −ĉ; a horizontal axis's azimuth in [0, π)).
/// Azimuths within 1e-9 radians of the range's end count as 0, so that turned copies do
/// not land on either end by rounding.
pub fn canonical_axis(solid: &Polyhedron, axis: DVec3) -> DVec3 {
    use std::f64::consts::{PI, TAU};
    let (psi, k) = turn_and_order(solid);
    let mut a = DMat3::from_rotation_z(psi) * axis.normalize();
    if a.truncate().length() < 1e-12 {
        return DVec3::Z;
    }
    let horizontal = a.z.abs() < 1e-12;
    if horizontal {
        a.z = 0.0;
    } else if a.z < 0.0 {
        a = -a;
    }
    let k = k.max(1);
    // The azimuths equivalent to the axis's: turns through 2π/k, and for a horizontal axis
    // the half-turn of the line as well (together, turns through π/k when k is odd).
    let period = if horizontal && k % 2 == 1 {
        PI / k as f64
    } else {
        TAU / k as f64
    };
    let mut phi = a.y.atan2(a.x).rem_euclid(period);
    if period - phi < 1e-9 {
        phi = 0.0;
    }
    let r = a.truncate().length();
    DVec3::new(r * phi.cos(), r * phi.sin(), a.z).normalize()
}

/// Quantised (tilt, offset, azimuth in [0, 2π)) of a facet plane; an azimuth a hair below 2π
/// counts as 0, and so does the azimuth of a horizontal facet.
fn sort_key(n: DVec3, offset: f64) -> (i64, i64, i64) {
    let q = |x: f64| (x / QUANTUM).round() as i64;
    let full = q(std::f64::consts::TAU);
    let az = if n.truncate().length() < 1e-9 {
        0
    } else {
        q(n.y.atan2(n.x).rem_euclid(std::f64::consts::TAU)) % full
    };
    (q(n.z), q(offset), az)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::tolkowsky;

    #[test]
    fn canonical_solid_is_centred_unit_and_keeps_its_shape() {
        let s = tolkowsky();
        let moved = s.scaled(3.0);
        let c = canonical(&moved);
        assert!(c.centroid().length() < 1e-10, "{:?}", c.centroid());
        let d = (4.0 * c.projected_area(DVec3::Z) / std::f64::consts::PI).sqrt();
        assert!((d - 1.0).abs() < 1e-10, "{d}");
        assert_eq!(c.facets().len(), s.facets().len());
        // Same shape: volumes in the ratio of the cubed scales.
        let d0 = (4.0 * s.projected_area(DVec3::Z) / std::f64::consts::PI).sqrt();
        assert!((c.volume() * d0.powi(3) - s.volume()).abs() < 1e-10);
        // Sorted by tilt: the first facet is one facing most nearly straight down.
        let lowest = s
            .facets()
            .iter()
            .map(|f| f.plane.normal.z)
            .fold(1.0, f64::min);
        assert!((c.facets()[0].plane.normal.z - lowest).abs() < 1e-9);
    }

    /// A stone turned by any angle comes back to the same canonical solid (to ~1e-12); the
    /// presets are already at their canonical azimuth; a marquise lies along x.
    #[test]
    fn canonical_azimuth_undoes_any_turn() {
        let s = tolkowsky();
        assert_eq!(azimuth_turn(&s), 0.0);
        let c0 = canonical(&s);
        for deg in [7.0, 13.0, 22.5, 31.0, 200.0] {
            let m = glam::DMat3::from_rotation_z(f64::to_radians(deg));
            let planes: Vec<FacetPlane> = s
                .facet_planes()
                .into_iter()
                .map(|mut f| {
                    f.plane.normal = m * f.plane.normal;
                    f
                })
                .collect();
            let turned = Polyhedron::from_planes(&planes).unwrap();
            let t = azimuth_turn(&turned).to_degrees();
            // Back by the turn, up to the round brilliant's 45° symmetry.
            let r = (t + deg).rem_euclid(45.0);
            assert!(r.min(45.0 - r) < 1e-9, "{deg}°: turned back by {t}°");
            let c = canonical(&turned);
            assert_eq!(c.facets().len(), c0.facets().len());
            for (a, b) in c.facets().iter().zip(c0.facets()) {
                let d = (a.plane.normal - b.plane.normal).length();
                assert!(d < 1e-10, "{deg}°: normal moved by {d:e}");
                assert!((a.plane.offset - b.plane.offset).abs() < 1e-10);
            }
        }
        for name in [
            "princess",
            "marquise",
            "emerald",
            "oval",
            "pear",
            "gia-reference",
        ] {
            let cut = crate::io::load_cut(name).unwrap();
            assert_eq!(azimuth_turn(&cut.solid), 0.0, "{name}");
        }
        // The marquise's long axis (its widest extent) is along x.
        let m = canonical(&crate::io::load_cut("marquise").unwrap().solid);
        let (mut wx, mut wy) = (0.0f64, 0.0f64);
        for v in m.vertices() {
            wx = wx.max(v.x.abs());
            wy = wy.max(v.y.abs());
        }
        assert!(wx > 1.5 * wy, "{wx} {wy}");
    }
}
