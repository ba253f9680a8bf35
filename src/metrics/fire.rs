//! Fire's placements of the spot lights ([`fire_placements`]: turned about the zenith and
//! raised or lowered, with their weights) and the lookup that finds, for an exit direction,
//! the placements whose spots can light it ([`FireLattice`]).

use super::config::ScoreConfig;
use crate::render::lighting::{self, Lighting, Spot};
use crate::render::raster;
use glam::DVec3;

/// One placement of the spot lights for fire, and its weight in the average.
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    /// The spots, turned about the zenith and raised or lowered.
    pub spots: Vec<Spot>,
    /// How far they were turned, degrees.
    pub turn_deg: f64,
    /// How far they were raised (negative: lowered), degrees.
    pub lift_deg: f64,
    /// Weight in fire's average (the weights need not add up to 1).
    pub weight: f64,
}

/// Fire's placements arranged for a quick lookup: for a direction, only the placements whose
/// turned and lifted spots can reach it are visited (equal turn steps make them a short
/// range of indices per spot), so the cost hardly grows with the number of placements.
pub(super) struct FireLattice<'a> {
    pub(super) lightings: &'a [Lighting],
    /// Per spot of the base set, what [`FireLattice::for_each`] needs of it.
    spots: Vec<SpotReach>,
    /// Per spot `i` and placement `k` (at `i · P + k`): the sines of the lowest and highest
    /// elevations that spot reaches there (so that no arcsine is needed per exit).
    zband: Vec<(f64, f64)>,
    /// The lowest `z_lo` and highest `z_hi` of all spots (see [`FireLattice::reaches`]).
    z_range: (f64, f64),
    step: f64,
}

/// One spot of fire's base set, hoisted out of [`FireLattice::for_each`].
#[derive(Clone, Copy, Debug)]
struct SpotReach {
    /// Azimuth of its centre at the first placement, degrees.
    azimuth: f64,
    /// Smallest cosine of its elevation over the lifts.
    cos_top: f64,
    /// Sines of the elevations below and above which no placement's spot reaches.
    z_lo: f64,
    z_hi: f64,
    /// `1 − cos(reach)`, the reach being the angular radius with the soft rim.
    one_minus_cos_reach: f64,
}

/// The sine of an elevation in degrees, clamped to the sphere.
fn sin_deg(e: f64) -> f64 {
    e.clamp(-90.0, 90.0).to_radians().sin()
}

/// An upper bound of `acos(1 − x)` for `x` in [0, 2], in radians, without the arc-cosine:
/// `√(2x) · (1 + 0.3x)` (the series is `√(2x) · (1 + x/12 + …)`; the bound is tight at 0 and
/// 2% above π at 2).
#[inline]
fn acos_one_minus_upper(x: f64) -> f64 {
    (2.0 * x).sqrt() * (1.0 + 0.3 * x)
}

impl<'a> FireLattice<'a> {
    pub(super) fn new(placements: &[Placement], lightings: &'a [Lighting]) -> FireLattice<'a> {
        let lifts: Vec<f64> = placements.iter().map(|p| p.lift_deg).collect();
        let (lo, hi) = lifts
            .iter()
            .fold((0.0f64, 0.0f64), |(a, b), &l| (a.min(l), b.max(l)));
        // Per spot: elevation at lift 0, azimuth, reach (degrees) and its SpotReach.
        let base: Vec<(f64, f64, SpotReach)> = placements.first().map_or_else(Vec::new, |p0| {
            p0.spots
                .iter()
                .map(|s| {
                    let base = s.elevation_deg - p0.lift_deg;
                    let reach = s.radius_deg + lighting::EDGE_DEG + 1e-6;
                    let top = (base + hi)
                        .clamp(1.0, 89.0)
                        .max((base + lo).clamp(1.0, 89.0));
                    let spot = SpotReach {
                        azimuth: s.azimuth_deg - p0.turn_deg,
                        cos_top: top.to_radians().cos(),
                        z_lo: sin_deg((base + lo).clamp(1.0, 89.0) - reach),
                        z_hi: sin_deg((base + hi).clamp(1.0, 89.0) + reach),
                        one_minus_cos_reach: 1.0 - reach.to_radians().cos(),
                    };
                    (base, reach, spot)
                })
                .collect()
        });
        let zband = base
            .iter()
            .flat_map(|&(base, reach, _)| {
                lifts.iter().map(move |&lift| {
                    let ek = (base + lift).clamp(1.0, 89.0);
                    (sin_deg(ek - reach), sin_deg(ek + reach))
                })
            })
            .collect();
        let z_range = base
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), b| {
                (lo.min(b.2.z_lo), hi.max(b.2.z_hi))
            });
        FireLattice {
            lightings,
            spots: base.iter().map(|b| b.2).collect(),
            zband,
            z_range,
            step: 360.0 / placements.len().max(1) as f64,
        }
    }

    /// Whether some placement's spots can light a direction whose z component is `z` (the
    /// same test [`FireLattice::for_each`] makes per spot: `false` means it visits nothing).
    #[inline]
    pub(super) fn reaches(&self, z: f64) -> bool {
        let z = z.clamp(-1.0, 1.0);
        !self.lightings.is_empty() && z >= self.z_range.0 && z <= self.z_range.1
    }

    /// What [`FireLattice::for_each`] needs of a direction's elevation alone, into `out`:
    /// the head shadow and the spots within reach, each with the half-width of the azimuths
    /// it reaches there. The copies of a face-up exit share their elevation, so one `Reach`
    /// serves the whole orbit.
    pub(super) fn reach_into(&self, w: DVec3, out: &mut Reach) {
        out.spots.clear();
        // Elevations are compared through their sines (sin e = w.z), with the reach's margin
        // of 1e-6° far above rounding: the same placements are visited as with the angles.
        let z = w.z.clamp(-1.0, 1.0);
        out.head = self.lightings.first().map_or(0.0, |l| l.head(w));
        if out.head == 0.0 {
            return;
        }
        let mut cos_e: Option<f64> = None;
        for (i, sp) in self.spots.iter().enumerate() {
            if z < sp.z_lo || z > sp.z_hi {
                continue;
            }
            let cos_e = *cos_e.get_or_insert_with(|| (1.0 - z * z).sqrt());
            // 1 − cos Δa ≤ (1 − cos ρ) / (cos e · cos ε): the azimuths within reach (an upper
            // bound of the arc-cosine visits a few more placements, whose light is 0).
            let x = sp.one_minus_cos_reach / (cos_e * sp.cos_top).max(1e-300);
            let half = if x >= 2.0 {
                180.0
            } else {
                acos_one_minus_upper(x).to_degrees().min(180.0)
            };
            out.spots.push((i, half));
        }
    }

    /// Calls `f(k, radiance)` for every placement `k` whose spots light direction `w`
    /// (each spot separately, head shadow applied), `reach` being [`FireLattice::reach_into`]
    /// of `w` or of any direction with the same elevation. `az`, when given, is `w`'s azimuth
    /// in degrees (any turn of it; it only picks the placements to look at, each of which is
    /// then evaluated at `w` itself).
    #[inline]
    pub(super) fn for_each(
        &self,
        w: DVec3,
        az: Option<f64>,
        reach: &Reach,
        mut f: impl FnMut(usize, f64),
    ) {
        let n = self.lightings.len();
        if n == 0 || reach.spots.is_empty() {
            return;
        }
        let z = w.z.clamp(-1.0, 1.0);
        let az = az.unwrap_or_else(|| w.y.atan2(w.x).to_degrees());
        let ni = n as i64;
        for &(i, half) in &reach.spots {
            let sp = &self.spots[i];
            let t0 = az - sp.azimuth;
            let (k0, k1) = if half >= 180.0 {
                (0, ni - 1)
            } else {
                (
                    raster::ceil_i64((t0 - half) / self.step),
                    raster::floor_i64((t0 + half) / self.step),
                )
            };
            // Placements k0, k0 + 1, … (at most all n once), taken modulo n.
            let mut k = k0.rem_euclid(ni) as usize;
            for _ in k0..=k1.min(k0 + ni - 1) {
                let (lo, hi) = self.zband[i * n + k];
                if z >= lo && z <= hi {
                    let l = self.lightings[k].spot(i, w);
                    if l > 0.0 {
                        f(k, l * reach.head);
                    }
                }
                k += 1;
                if k == n {
                    k = 0;
                }
            }
        }
    }
}

/// The part of fire's placement lookup that depends on a direction's elevation only
/// ([`FireLattice::reach_into`]).
#[derive(Debug, Default)]
pub(super) struct Reach {
    /// The head shadow's share at that elevation.
    head: f64,
    /// The spots within reach, with the half-width (degrees) of the azimuths each reaches.
    spots: Vec<(usize, f64)>,
}

/// Largest raising or lowering of the spot lights in fire's average, degrees.
pub const FIRE_LIFT_DEG: f64 = 8.0;

/// The placements of the spot lights over which fire is averaged: the expectation over the
/// ways a face-up stone meets the lights, as a rank-1 lattice of `P =`
/// [`ScoreConfig::fire_placements`] points in (turn, lift). Placement k turns the set
/// about the zenith by `360° · k / P` (turning the stone under fixed lights is turning the
/// lights the other way: the face-up trace does not change) and raises it by
/// `lift = FIRE_LIFT_DEG · (2 (m + ½) / P − 1)`, m = 7k mod P (a stone rocked by a few degrees
/// sees each light higher or lower by about as much), with the smooth weight
/// `(1 + cos(π · lift / FIRE_LIFT_DEG)) / 2`. Equal turn steps make fire exactly the same for a
/// stone turned by a multiple of `360° / P`; an odd `P` shares no factor with the usual 4-, 8-
/// or 16-fold symmetries, so the turns sample every phase of the stone's symmetry evenly.
pub fn fire_placements(cfg: &ScoreConfig) -> Vec<Placement> {
    let p = cfg.fire_placements.max(1);
    (0..p)
        .map(|k| {
            let turn = 360.0 * k as f64 / p as f64;
            let m = (7 * k) % p;
            let lift = if p == 1 {
                0.0
            } else {
                FIRE_LIFT_DEG * (2.0 * (m as f64 + 0.5) / p as f64 - 1.0)
            };
            let weight = if p == 1 {
                1.0
            } else {
                0.5 * (1.0 + (std::f64::consts::PI * lift / FIRE_LIFT_DEG).cos())
            };
            Placement {
                spots: turned(&cfg.spots, turn, lift),
                turn_deg: turn,
                lift_deg: lift,
                weight,
            }
        })
        .collect()
}

/// `spots` turned about the zenith by `turn_deg` and raised by `lift_deg` (elevations kept
/// within 1°–89°).
pub(super) fn turned(spots: &[Spot], turn_deg: f64, lift_deg: f64) -> Vec<Spot> {
    spots
        .iter()
        .map(|s| Spot {
            elevation_deg: (s.elevation_deg + lift_deg).clamp(1.0, 89.0),
            azimuth_deg: (s.azimuth_deg + turn_deg).rem_euclid(360.0),
            radius_deg: s.radius_deg,
        })
        .collect()
}
