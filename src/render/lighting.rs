//! Lighting environments, as radiance functions of the direction light arrives *from*
//! (world coordinates, z up, the viewer straight above).
//!
//! Every edge (the horizon, the head shadow's rim, a spot's rim, an ASET band boundary) is a
//! smooth ramp [`EDGE_DEG`] wide on each side rather than a step. A beam's exit direction
//! moves continuously with the cut's proportions; with a step edge its whole power would jump
//! in or out of the light as it crosses, with a ramp it fades. That is what keeps the scores
//! continuous (Lipschitz) in the cut's parameters, which the optimizer relies on.

use glam::DVec3;

/// Half-width of every soft edge, degrees.
pub const EDGE_DEG: f64 = 1.0;

/// C¹ ramp: 0 for `x ≤ 0`, 1 for `x ≥ 1`, `3x² − 2x³` between.
#[inline]
pub fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// 0 well below `edge_deg`, 1 well above, a ramp of ±[`EDGE_DEG`] around it.
#[inline]
pub fn soft_above(value_deg: f64, edge_deg: f64) -> f64 {
    smoothstep((value_deg - edge_deg + EDGE_DEG) / (2.0 * EDGE_DEG))
}

/// A cone of half-angle `deg` around the zenith with a soft rim (±[`EDGE_DEG`]): the share of
/// the light from a direction that falls outside it, `soft_above(90° − elevation, deg)`,
/// decided without an arcsine away from the rim.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone {
    deg: f64,
    /// At or below this z a direction is wholly outside (share exactly 1); NaN: none is.
    out_z: f64,
    /// At or above this z a direction is wholly inside (share exactly 0); NaN: none is.
    in_z: f64,
}

impl Cone {
    /// Both bounds lie 1e-9 (in z) inside the soft rim, far beyond the arcsine's rounding
    /// (~1e-13°), so [`Cone::outside`] gives the very same number as the arcsine everywhere.
    const MARGIN: f64 = 1e-9;

    /// The cone of half-angle `deg` degrees.
    pub fn new(deg: f64) -> Cone {
        let out_z = if deg + EDGE_DEG < 180.0 {
            (deg + EDGE_DEG).to_radians().cos() - Self::MARGIN
        } else {
            f64::NAN // never wholly outside (a comparison with NaN is false)
        };
        let in_z = if deg > EDGE_DEG {
            (deg - EDGE_DEG).to_radians().cos() + Self::MARGIN
        } else {
            f64::NAN // never wholly inside
        };
        Cone { deg, out_z, in_z }
    }

    /// `soft_above(90 − elevation_deg(w), deg)`: 1 outside the cone, 0 inside, a ramp at
    /// the rim (an arcsine only there: the head shadow's took a score 3 % of its
    /// instructions when every exit paid it).
    #[inline]
    pub fn outside(&self, w: DVec3) -> f64 {
        if w.z <= self.out_z {
            1.0
        } else if w.z >= self.in_z {
            0.0
        } else {
            soft_above(90.0 - elevation_deg(w), self.deg)
        }
    }
}

/// Elevation of direction `w` above the horizon, degrees.
#[inline]
pub fn elevation_deg(w: DVec3) -> f64 {
    w.z.clamp(-1.0, 1.0).asin().to_degrees()
}

/// A small round light source of uniform radiance 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spot {
    /// Elevation of its centre above the horizon, degrees.
    pub elevation_deg: f64,
    /// Azimuth of its centre, degrees from +x toward +y.
    pub azimuth_deg: f64,
    /// Angular radius, degrees (the rim is soft by ±[`EDGE_DEG`]).
    pub radius_deg: f64,
}

impl Spot {
    /// Unit vector toward the spot's centre.
    pub fn direction(&self) -> DVec3 {
        let (e, a) = (
            self.elevation_deg.to_radians(),
            self.azimuth_deg.to_radians(),
        );
        DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
    }

    /// The default set for fire and scintillation: seven 5° spots, three at 40° elevation,
    /// three at 60° (turned 60° from the first three) and one at 75°, at azimuths that do not
    /// share a round brilliant's 8-fold symmetry.
    pub fn default_set() -> Vec<Spot> {
        let mut v = Vec::new();
        for k in 0..3 {
            v.push(Spot {
                elevation_deg: 40.0,
                azimuth_deg: 10.0 + 120.0 * k as f64,
                radius_deg: 5.0,
            });
            v.push(Spot {
                elevation_deg: 60.0,
                azimuth_deg: 70.0 + 120.0 * k as f64,
                radius_deg: 5.0,
            });
        }
        v.push(Spot {
            elevation_deg: 75.0,
            azimuth_deg: 205.0,
            radius_deg: 5.0,
        });
        v
    }
}

/// Radiance functions of the scoring environments, with the head shadow applied.
#[derive(Clone, Debug)]
pub struct Lighting {
    /// The head shadow: a cone of its half-angle around the zenith (the viewer's direction),
    /// degrees; 0 = none.
    head: Cone,
    spots: Vec<(DVec3, f64, f64, f64)>,
}

impl Lighting {
    /// Lighting with a head shadow of `head_shadow_deg` and the given spots.
    pub fn new(head_shadow_deg: f64, spots: &[Spot]) -> Lighting {
        let spots = spots
            .iter()
            .map(|s| {
                let inner = (s.radius_deg - EDGE_DEG).max(0.0).to_radians().cos();
                let outer = (s.radius_deg + EDGE_DEG).to_radians().cos();
                (s.direction(), inner, outer, s.radius_deg)
            })
            .collect();
        Lighting {
            head: Cone::new(head_shadow_deg),
            spots,
        }
    }

    /// The head shadow's half-angle around the zenith, degrees (0 = none).
    pub fn head_shadow_deg(&self) -> f64 {
        self.head.deg
    }

    /// The head shadow's cone, `None` without a head shadow (a half-angle of 0 or less).
    #[inline]
    pub fn head_cone(&self) -> Option<&Cone> {
        let none = self.head.deg <= 0.0;
        (!none).then_some(&self.head)
    }

    /// Share of the light from `w` that the viewer's head lets through: 0 inside the shadow
    /// cone around the zenith, 1 outside, soft at the rim.
    #[inline]
    pub fn head(&self, w: DVec3) -> f64 {
        self.head_cone().map_or(1.0, |c| c.outside(w))
    }

    /// GemRay-style ISO lighting: radiance 1 over the upper hemisphere, 0 below (soft at the
    /// horizon), times the head shadow.
    #[inline]
    pub fn iso(&self, w: DVec3) -> f64 {
        let sky = if w.z >= 0.1 {
            1.0
        } else if w.z <= -0.1 {
            0.0
        } else {
            soft_above(elevation_deg(w), 0.0)
        };
        if sky == 0.0 {
            0.0
        } else {
            sky * self.head(w)
        }
    }

    /// GemRay-style COS lighting: radiance ∝ the cosine of the angle from the zenith (1 at
    /// the zenith, 0 at and below the horizon), times the head shadow.
    #[inline]
    pub fn cos(&self, w: DVec3) -> f64 {
        if w.z <= 0.0 {
            0.0
        } else {
            w.z * self.head(w)
        }
    }

    /// Radiance of the spot lights (each 1, soft rims), times the head shadow.
    #[inline]
    pub fn spots(&self, w: DVec3) -> f64 {
        let mut l = 0.0;
        for &(c, inner, outer, radius) in &self.spots {
            let d = w.dot(c);
            if d <= outer {
                continue;
            }
            l += if d >= inner {
                1.0
            } else {
                1.0 - soft_above(d.clamp(-1.0, 1.0).acos().to_degrees(), radius)
            };
        }
        if l == 0.0 {
            0.0
        } else {
            l * self.head(w)
        }
    }

    /// Radiance of spot `i` alone (soft rim), without the head shadow; 0 for a missing spot.
    #[inline]
    pub fn spot(&self, i: usize, w: DVec3) -> f64 {
        let Some(&(c, inner, outer, radius)) = self.spots.get(i) else {
            return 0.0;
        };
        let d = w.dot(c);
        if d <= outer {
            0.0
        } else if d >= inner {
            1.0
        } else {
            1.0 - soft_above(d.clamp(-1.0, 1.0).acos().to_degrees(), radius)
        }
    }

    /// Whether [`Lighting::spots`] can be non-zero for some direction whose z component is
    /// `z` (any azimuth): the nearest such direction to a spot's centre is at the same
    /// azimuth, where their cosine is `z·c_z + √((1 − z²)(1 − c_z²))`.
    #[inline]
    pub fn spots_reach_z(&self, z: f64) -> bool {
        let s = (1.0 - z * z).max(0.0).sqrt();
        self.spots
            .iter()
            .any(|&(c, _, outer, _)| z * c.z + s * (1.0 - c.z * c.z).max(0.0).sqrt() > outer)
    }

    /// Whether [`Lighting::spots`] can be non-zero for `w` (cheap pre-test).
    #[inline]
    pub fn near_spot(&self, w: DVec3) -> bool {
        self.spots.iter().any(|&(c, _, outer, _)| w.dot(c) > outer)
    }
}

/// ASET-style shares of one direction: light from 75–90° elevation (`blue`), 45–75° (`red`),
/// 0–45° (`green`) and below the horizon (`leak`), each boundary soft by ±[`EDGE_DEG`]. The
/// four always add up to 1.
#[inline]
pub fn aset_bins(w: DVec3) -> [f64; 4] {
    // Away from the soft boundaries (±1° around 75°, 45° and 0°) no arcsine is needed.
    const S76: f64 = 0.970_295_726_275_996_5;
    const S74: f64 = 0.961_261_695_938_318_9;
    const S46: f64 = 0.719_339_800_338_651_1;
    const S44: f64 = 0.694_658_370_458_997_3;
    const S1: f64 = 0.017_452_406_437_283_51;
    let z = w.z;
    if z >= S76 {
        [1.0, 0.0, 0.0, 0.0]
    } else if (S46..=S74).contains(&z) {
        [0.0, 1.0, 0.0, 0.0]
    } else if (S1..=S44).contains(&z) {
        [0.0, 0.0, 1.0, 0.0]
    } else if z <= -S1 {
        [0.0, 0.0, 0.0, 1.0]
    } else {
        aset_bins_exact(w)
    }
}

/// The ASET's five shares of one direction, as its picture and the scores both count them:
/// [`aset_bins`] with the viewer's dark port (a cone of half-angle `port_deg` around the
/// zenith, soft by ±[`EDGE_DEG`]) taken out of the sky's bins: blue, red, green, leak, port.
/// They add up to 1; with no port (`port_deg` ≤ 0) blue is all of 75–90°.
#[inline]
pub fn aset_shares(w: DVec3, port_deg: f64) -> [f64; 5] {
    let none = port_deg <= 0.0;
    aset_shares_in(w, (!none).then(|| Cone::new(port_deg)).as_ref())
}

/// [`aset_shares`] with the port given as its cone (`None`: no port), for a caller that
/// keeps one (a [`Lighting`]'s head shadow, [`Lighting::head_cone`]; the scores' port).
#[inline]
pub fn aset_shares_in(w: DVec3, port: Option<&Cone>) -> [f64; 5] {
    let b = aset_bins(w);
    let lit = port.map_or(1.0, |c| c.outside(w));
    [
        b[0] * lit,
        b[1] * lit,
        b[2] * lit,
        b[3],
        (1.0 - lit) * (1.0 - b[3]),
    ]
}

#[inline]
fn aset_bins_exact(w: DVec3) -> [f64; 4] {
    let e = elevation_deg(w);
    let a = soft_above(e, 75.0);
    let b = soft_above(e, 45.0);
    let c = soft_above(e, 0.0);
    [a, b - a, c - b, 1.0 - c]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `spots_reach_z` holds wherever a spot lights a direction of that z (on a fine grid
    /// of directions), is tight (the grid finds a lit direction within 0.2° of every z it
    /// allows) and refuses the elevations between and beyond the default spots.
    #[test]
    fn spots_reach_z_bounds_the_spots() {
        let light = Lighting::new(0.0, &Spot::default_set());
        for i in 0..=1800 {
            let elev = -90.0 + 0.1 * i as f64;
            let z = elev.to_radians().sin();
            let lit = (0..3600).any(|k| light.spots(dir(elev, 0.1 * k as f64)) > 0.0);
            if lit {
                assert!(light.spots_reach_z(z), "elevation {elev}");
            }
            if light.spots_reach_z(z) {
                let near = (-2..=2).any(|d| {
                    let e = elev + 0.1 * d as f64;
                    (0..3600).any(|k| light.spots(dir(e, 0.1 * k as f64)) > 0.0)
                });
                assert!(near, "elevation {elev} allowed, nothing lit near it");
            }
        }
        for elev in [-10.0, 20.0, 50.0, 88.0] {
            assert!(
                !light.spots_reach_z(f64::sin(f64::to_radians(elev))),
                "{elev}"
            );
        }
    }

    /// The cone's arcsine-free shortcut gives the arcsine's very number (bit for bit) for
    /// every direction: on a fine grid of z over the whole sphere and densely around each
    /// bound (where a shortcut taken a hair too early would differ), for cones narrower and
    /// wider than the rim, the head shadow's and the ASET port's among them.
    #[test]
    fn cone_shortcut_is_the_arcsine_bit_for_bit() {
        for deg in [
            0.0,
            0.5,
            1.0,
            2.0,
            crate::render::PORT_DEG,
            15.0,
            40.0,
            89.0,
            179.5,
        ] {
            let cone = Cone::new(deg);
            let mut zs: Vec<f64> = (0..=200_000).map(|i| -1.0 + i as f64 * 1e-5).collect();
            let bounds = [cone.out_z, cone.in_z, (deg + EDGE_DEG).to_radians().cos()];
            for b in bounds.into_iter().filter(|b| !b.is_nan()) {
                zs.extend((-2000..=2000).map(|k| b + k as f64 * 1e-12));
            }
            zs.extend([
                1.0 + 1e-15,
                -1.0 - 1e-15,
                2.0,
                -2.0,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ]);
            for z in zs {
                let w = DVec3::new((1.0 - z * z).max(0.0).sqrt(), 0.0, z);
                let want = soft_above(90.0 - elevation_deg(w), deg);
                assert_eq!(
                    cone.outside(w).to_bits(),
                    want.to_bits(),
                    "cone {deg}, z {z}"
                );
            }
        }
        // A lighting's head cone is the port of the same angle (the ASET picture's port is
        // the head shadow), none without a head shadow.
        for deg in [0.0, crate::render::PORT_DEG, 15.0] {
            let light = Lighting::new(deg, &[]);
            assert_eq!(light.head_cone().is_some(), deg > 0.0);
            for i in 0..=2000 {
                let w = dir(-90.0 + 0.09 * i as f64, 0.0);
                assert_eq!(aset_shares_in(w, light.head_cone()), aset_shares(w, deg));
            }
        }
        // The shortcuts are taken: the rim is all that needs an arcsine.
        let head = Cone::new(15.0);
        assert!(head.out_z > 0.96 && head.out_z < 16f64.to_radians().cos());
        assert!(head.in_z < 0.98 && head.in_z > 14f64.to_radians().cos());
    }

    fn dir(elev: f64, az: f64) -> DVec3 {
        Spot {
            elevation_deg: elev,
            azimuth_deg: az,
            radius_deg: 1.0,
        }
        .direction()
    }

    #[test]
    fn iso_cos_head() {
        let l = Lighting::new(0.0, &[]);
        assert_eq!(l.iso(dir(30.0, 10.0)), 1.0);
        assert_eq!(l.iso(dir(-30.0, 10.0)), 0.0);
        assert!((l.iso(dir(0.0, 0.0)) - 0.5).abs() < 1e-12);
        assert!((l.cos(dir(30.0, 0.0)) - 0.5).abs() < 1e-12);
        assert_eq!(l.cos(dir(-5.0, 0.0)), 0.0);
        let h = Lighting::new(15.0, &[]);
        assert_eq!(h.iso(dir(89.0, 0.0)), 0.0);
        assert_eq!(h.iso(dir(60.0, 0.0)), 1.0);
        assert!((h.iso(dir(75.0, 0.0)) - 0.5).abs() < 1e-9);
    }

    #[test]
    fn spots_and_rims() {
        let s = Spot {
            elevation_deg: 40.0,
            azimuth_deg: 10.0,
            radius_deg: 5.0,
        };
        let l = Lighting::new(0.0, &[s]);
        assert_eq!(l.spots(s.direction()), 1.0);
        assert_eq!(l.spots(dir(40.0, 30.0)), 0.0);
        assert!((l.spots(dir(45.0, 10.0)) - 0.5).abs() < 1e-6);
        assert!(l.near_spot(dir(44.5, 10.0)) && !l.near_spot(dir(46.5, 10.0)));
        // The ramp is monotone and continuous.
        let mut prev = 1.0;
        for k in 0..=400 {
            let v = l.spots(dir(40.0 + k as f64 * 0.02, 10.0));
            assert!(v <= prev + 1e-12 && prev - v < 0.02);
            prev = v;
        }
    }

    #[test]
    fn aset_bins_partition() {
        for k in -90..=90 {
            let b = aset_bins(dir(k as f64 + 0.3, 0.0));
            assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            assert!(b.iter().all(|&x| (0.0..=1.0).contains(&x)));
        }
        assert_eq!(aset_bins(dir(80.0, 0.0)), [1.0, 0.0, 0.0, 0.0]);
        assert_eq!(aset_bins(dir(60.0, 0.0)), [0.0, 1.0, 0.0, 0.0]);
        assert_eq!(aset_bins(dir(20.0, 0.0)), [0.0, 0.0, 1.0, 0.0]);
        assert_eq!(aset_bins(dir(-20.0, 0.0)), [0.0, 0.0, 0.0, 1.0]);
        // The shortcut agrees with the arcsine form everywhere.
        for k in 0..=18000 {
            let w = dir(-90.0 + k as f64 * 0.01, 0.0);
            let (a, b) = (aset_bins(w), aset_bins_exact(w));
            for i in 0..4 {
                assert!((a[i] - b[i]).abs() < 1e-9, "{k}: {a:?} {b:?}");
            }
        }
    }
}
