//! Lighting environments for photographs ([`Environment`]): radiance in linear sRGB as a
//! function of the direction light arrives from, built from parts (a sky, the floor of a
//! room or light box, round lights, rings, ceiling panels, an equirectangular map), turned
//! about the vertical by a rotation, and seen through one stated filter.
//!
//! # The filter
//!
//! An exit beam leaves in one exact direction; a light with a sharp rim would make its whole
//! power jump in or out of a picture as the stone moves by a hair. A camera sees every
//! direction through its aperture: the sight lines reaching its entrance pupil from a point
//! of the stone spread over the angle the pupil subtends. Every edge is therefore seen
//! through a ramp of that half-width `h` ([`Environment::edge_deg`]; as made, the scores'
//! [`EDGE_DEG`], ±1°, [`Environment::with_aperture`] for another): the C¹ ramp `3s² − 2s³`
//! across ±`h` of the rim's angular distance. It is a filter: the radiance is the
//! environment convolved, along the direction across each edge, with the kernel
//! `k(x) = 6s(1 − s) / 2h`, `s = (x + h) / 2h` (whose integral is the ramp), so a picture is
//! Lipschitz in the stone's pose with a constant ∝ 1/h. A round light of angular radius `R`
//! is a disc of radius `max(R, h)` with that ramp at its rim, its radiance scaled so that its
//! power (radiance × solid angle) is the source's: at ±1° the sun (R = 0.27°) is a 1° disc
//! of 0.07 of its radiance. An equirectangular map is filtered by the same kernel along
//! elevation and azimuth ([`EnvMap`]). The sky's horizon is the ISO
//! light's ramp, so that at ±1° a sky of radiance 1 is [`Lighting::iso`](crate::render::lighting::Lighting::iso)
//! and a sky of radiance cos(zenith) is [`Lighting::cos`](crate::render::lighting::Lighting::cos),
//! to the last bit.
//!
//! A pinhole (`h` = 0) has no filter: every edge is a step (half its value on the edge
//! itself), a round light its own disc, a map its own texels (bilinear). Its picture is exact
//! for a pinhole camera, and jumps as a rim crosses a beam's direction.
//!
//! # Light on the ground
//!
//! [`Environment::samples`] splits the light falling on a horizontal plane into directions
//! that each carry a share of its irradiance: every round light its own (up to seven
//! directions spread over its disc), the rest in cells of equal solid angle over the upper
//! hemisphere, each integrated on a grid of the filtered radiance and placed at its
//! irradiance-weighted centre (bright cells split further). The ground's unshadowed irradiance
//! is their sum; each one casts the stone's shadow and its caustics.

use super::envmap::EnvMap;
pub use super::sky::{direction, luminance, Rgb};
use crate::render::lighting::{smoothstep, EDGE_DEG};
use glam::DVec3;
use std::f64::consts::TAU;
use std::sync::Arc;

fn scale(c: Rgb, k: f64) -> Rgb {
    [c[0] * k, c[1] * k, c[2] * k]
}

/// 0 well below `edge_deg`, 1 well above, a ramp of ±`h` around it: for `h` = [`EDGE_DEG`]
/// [`soft_above`](crate::render::lighting::soft_above) to the last bit; for `h` = 0 a step,
/// ½ on the edge.
#[inline]
fn soft(value_deg: f64, edge_deg: f64, h: f64) -> f64 {
    if h > 0.0 {
        smoothstep((value_deg - edge_deg + h) / (2.0 * h))
    } else if value_deg > edge_deg {
        1.0
    } else if value_deg < edge_deg {
        0.0
    } else {
        0.5
    }
}

/// Largest kernel half-width, degrees (a camera's aperture is refused past it).
pub const MAX_EDGE_DEG: f64 = 10.0;

/// The filter of an environment: its kernel's half-width and the height `z` past which no
/// ramp of the horizon reaches (the radiance of the sky and floor is whole).
#[derive(Clone, Copy, Debug)]
struct Filter {
    h: f64,
    far_z: f64,
}

impl Filter {
    fn new(h: f64) -> Filter {
        // sin 5.74° = 0.1: the ±1° filter's bound (as the ISO light's), kept for narrower.
        let far_z = (h * 1.01).to_radians().sin().max(0.1);
        Filter { h, far_z }
    }
}

fn add(a: &mut Rgb, b: Rgb) {
    a[0] += b[0];
    a[1] += b[1];
    a[2] += b[2];
}

/// A round light: `radiance` over a disc of angular radius `radius_deg` around `dir`.
#[derive(Clone, Debug, PartialEq)]
pub struct Disc {
    /// Unit vector toward its centre.
    pub dir: DVec3,
    /// Angular radius of the source, degrees.
    pub radius_deg: f64,
    /// Radiance of the source, linear sRGB.
    pub radiance: Rgb,
    /// The filtered disc: its filter's half-width (degrees), the cosines of its inner and
    /// outer ramp ends, the ramp's centre (degrees) and the factor that keeps its power.
    edge_deg: f64,
    inner: f64,
    outer: f64,
    rim_deg: f64,
    gain: f64,
}

/// Solid angle of the filtered disc of rim `rim_deg` (the ramp 1 − smoothstep across
/// ±`edge` of the rim), by Simpson's rule over the polar angle.
fn ramped_solid_angle(rim_deg: f64, edge: f64) -> f64 {
    let (a, b) = ((rim_deg - edge).max(0.0), rim_deg + edge);
    let n = 400;
    let h = (b - a) / n as f64;
    let f = |deg: f64| {
        let v = 1.0 - soft(deg, rim_deg, edge);
        TAU * v * deg.to_radians().sin() * h.to_radians() / 3.0
    };
    let mut s = 0.0;
    for i in 0..=n {
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        s += w * f(a + i as f64 * h);
    }
    // The inside of the ramp's start.
    s + TAU * (1.0 - a.to_radians().cos())
}

impl Disc {
    /// A round light of `radiance` and angular radius `radius_deg` (> 0) toward `dir`, seen
    /// through the ±[`EDGE_DEG`] filter.
    pub fn new(dir: DVec3, radius_deg: f64, radiance: Rgb) -> Disc {
        Disc::filtered(dir, radius_deg, radiance, EDGE_DEG)
    }

    /// [`Disc::new`] seen through a filter of half-width `edge_deg` (0: its own disc).
    pub fn filtered(dir: DVec3, radius_deg: f64, radiance: Rgb, edge_deg: f64) -> Disc {
        let dir = dir.normalize();
        let rim = radius_deg.max(edge_deg);
        let source = TAU * (1.0 - radius_deg.to_radians().cos());
        Disc {
            dir,
            radius_deg,
            radiance,
            edge_deg,
            inner: (rim - edge_deg).max(0.0).to_radians().cos(),
            outer: (rim + edge_deg).to_radians().cos(),
            rim_deg: rim,
            gain: source / ramped_solid_angle(rim, edge_deg),
        }
    }

    /// The filtered share of the disc's radiance seen from `w` (0 outside, `gain` inside).
    #[inline]
    fn weight(&self, w: DVec3) -> f64 {
        let d = w.dot(self.dir);
        if d <= self.outer {
            0.0
        } else if d >= self.inner {
            self.gain
        } else {
            let ang = d.clamp(-1.0, 1.0).acos().to_degrees();
            self.gain * (1.0 - soft(ang, self.rim_deg, self.edge_deg))
        }
    }

    /// Solid angle of the source (sr).
    pub fn solid_angle(&self) -> f64 {
        TAU * (1.0 - self.radius_deg.to_radians().cos())
    }
}

/// One part of an environment.
#[derive(Clone, Debug)]
pub enum Part {
    /// The sky above the horizon: `horizon` at the horizon (soft by ±1°, the ISO light's
    /// ramp) plus `(zenith − horizon) · cos(zenith angle)`: equal colours give a uniform
    /// sky, `horizon` black a cosine sky.
    Sky {
        /// Radiance at the zenith.
        zenith: Rgb,
        /// Radiance at the horizon.
        horizon: Rgb,
    },
    /// Uniform radiance below the horizon (a floor; soft by ±1°).
    Floor(Rgb),
    /// A round light.
    Disc(Disc),
    /// A ring around `axis` between `inner_deg` and `outer_deg` from it (soft edges), of
    /// uniform radiance; a negative radiance darkens (a camera's port in a light tent).
    Ring {
        /// Its axis (unit).
        axis: DVec3,
        /// Inner angular radius, degrees (0: a full disc).
        inner_deg: f64,
        /// Outer angular radius, degrees.
        outer_deg: f64,
        /// Radiance added inside, linear sRGB.
        radiance: Rgb,
    },
    /// A rectangle on the ceiling plane `z = 1` (in units of the ceiling's height above the
    /// stone): `|x − cx| ≤ hx`, `|y − cy| ≤ hy`, soft edges of about ±h.
    Panel {
        /// Centre (cx, cy).
        centre: [f64; 2],
        /// Half-sizes (hx, hy).
        half: [f64; 2],
        /// Radiance, linear sRGB.
        radiance: Rgb,
    },
    /// An equirectangular map.
    Map(Arc<EnvMap>),
}

impl Part {
    /// Radiance from direction `w` (in the environment's own frame) through `filter`.
    #[inline]
    fn radiance(&self, w: DVec3, filter: Filter) -> Rgb {
        let Filter { h, far_z } = filter;
        match self {
            Part::Sky { zenith, horizon } => {
                let ramp = if w.z >= far_z {
                    1.0
                } else if w.z <= -far_z {
                    0.0
                } else {
                    soft(crate::render::lighting::elevation_deg(w), 0.0, h)
                };
                let cz = w.z.max(0.0);
                [0, 1, 2].map(|c| horizon[c] * ramp + (zenith[c] - horizon[c]) * cz)
            }
            Part::Floor(c) => {
                let below = if w.z >= far_z {
                    0.0
                } else if w.z <= -far_z {
                    1.0
                } else {
                    1.0 - soft(crate::render::lighting::elevation_deg(w), 0.0, h)
                };
                scale(*c, below)
            }
            Part::Disc(d) => {
                let k = d.weight(w);
                if k == 0.0 {
                    [0.0; 3]
                } else {
                    scale(d.radiance, k)
                }
            }
            Part::Ring {
                axis,
                inner_deg,
                outer_deg,
                radiance,
            } => {
                let d = w.dot(*axis);
                let far = (outer_deg + h).to_radians().cos();
                if d <= far {
                    return [0.0; 3];
                }
                let ang = d.clamp(-1.0, 1.0).acos().to_degrees();
                let inside = 1.0 - soft(ang, *outer_deg, h);
                let k = if *inner_deg > 0.0 {
                    inside * soft(ang, *inner_deg, h)
                } else {
                    inside
                };
                scale(*radiance, k)
            }
            Part::Panel {
                centre,
                half,
                radiance,
            } => {
                if w.z <= 1e-6 {
                    return [0.0; 3];
                }
                let (x, y) = (w.x / w.z, w.y / w.z);
                // Distance outside the rectangle's edges in the ceiling plane, turned into an
                // angle by the plane's distance along the sight line (1 / w.z) and its
                // obliquity (w.z): about w.z² radians per unit.
                let k = w.z * w.z;
                let ex = ((x - centre[0]).abs() - half[0]) * k;
                let ey = ((y - centre[1]).abs() - half[1]) * k;
                let e = h.to_radians();
                let (fx, fy) = if e > 0.0 {
                    (
                        1.0 - smoothstep((ex + e) / (2.0 * e)),
                        1.0 - smoothstep((ey + e) / (2.0 * e)),
                    )
                } else {
                    (1.0 - soft(ex, 0.0, 0.0), 1.0 - soft(ey, 0.0, 0.0))
                };
                scale(*radiance, fx * fy)
            }
            Part::Map(m) => m.radiance(w),
        }
    }
}

/// A lighting environment: parts added up, turned by `rotation_deg` about the vertical.
#[derive(Clone, Debug)]
pub struct Environment {
    /// The name shown in captions and JSON (`tent`, `env:FILE`, …).
    pub name: String,
    /// The parts, added up.
    pub parts: Vec<Part>,
    /// Rotation about the vertical axis, degrees (counter-clockwise seen from above): the
    /// environment's azimuth 0 faces this azimuth.
    pub rotation_deg: f64,
    /// The filter every part is seen through ([`Environment::with_aperture`]).
    filter: Filter,
}

/// One direction of light on the ground ([`Environment::samples`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Unit vector toward where the light comes from (z > 0).
    pub dir: DVec3,
    /// Irradiance it brings to a horizontal plane, linear sRGB.
    pub irradiance: Rgb,
    /// From a round light (traced in every band for its coloured caustic).
    pub point: bool,
}

impl Environment {
    /// An environment of parts, unrotated.
    pub fn new(name: &str, parts: Vec<Part>) -> Environment {
        Environment {
            name: name.to_string(),
            parts,
            rotation_deg: 0.0,
            filter: Filter::new(EDGE_DEG),
        }
    }

    /// The environment seen through an aperture whose sight lines spread over ±`edge_deg`
    /// (0 to [`MAX_EDGE_DEG`]; 0: a pinhole, no filter): every part's edges ramped over
    /// ±`edge_deg`, round lights filtered so, maps through that kernel (made once per map
    /// and kept). At [`EDGE_DEG`] it is the environment as made, to the last bit.
    pub fn with_aperture(mut self, edge_deg: f64) -> Environment {
        let h = edge_deg.clamp(0.0, MAX_EDGE_DEG);
        if h == self.filter.h {
            return self;
        }
        self.filter = Filter::new(h);
        for p in &mut self.parts {
            match p {
                Part::Disc(d) => *d = Disc::filtered(d.dir, d.radius_deg, d.radiance, h),
                Part::Map(m) => *m = m.at_edge(h),
                _ => {}
            }
        }
        self
    }

    /// The half-width of the filter every part is seen through, degrees (0: a pinhole).
    pub fn edge_deg(&self) -> f64 {
        self.filter.h
    }

    /// Radiance 1 from every direction (the white furnace).
    pub fn uniform() -> Environment {
        Environment::new(
            "uniform",
            vec![
                Part::Sky {
                    zenith: [1.0; 3],
                    horizon: [1.0; 3],
                },
                Part::Floor([1.0; 3]),
            ],
        )
    }

    /// The direction `w` (world) in the environment's own frame.
    #[inline]
    fn local(&self, w: DVec3) -> DVec3 {
        if self.rotation_deg == 0.0 {
            return w;
        }
        let (s, c) = (-self.rotation_deg).to_radians().sin_cos();
        DVec3::new(c * w.x - s * w.y, s * w.x + c * w.y, w.z)
    }

    /// The direction `w` of the environment's frame in the world.
    fn world(&self, w: DVec3) -> DVec3 {
        let (s, c) = self.rotation_deg.to_radians().sin_cos();
        DVec3::new(c * w.x - s * w.y, s * w.x + c * w.y, w.z)
    }

    /// Filtered radiance (linear sRGB) seen looking along `w` (world, unit): the light
    /// arriving from `w`. Never negative.
    #[inline]
    pub fn radiance(&self, w: DVec3) -> Rgb {
        let l = self.local(w);
        let mut c = [0.0; 3];
        for p in &self.parts {
            add(&mut c, p.radiance(l, self.filter));
        }
        c.map(|v| v.max(0.0))
    }

    /// Radiance of every part but the round lights (what the hemisphere's cells integrate).
    fn diffuse(&self, l: DVec3) -> Rgb {
        let mut c = [0.0; 3];
        for p in &self.parts {
            if !matches!(p, Part::Disc(_)) {
                add(&mut c, p.radiance(l, self.filter));
            }
        }
        c
    }

    /// The light on a horizontal plane, as directions carrying shares of its irradiance (see
    /// the module documentation): every round light above the horizon in up to seven
    /// directions over its disc, and the rest in about `cells` cells of equal solid angle
    /// over the upper hemisphere (cells with over 8 % of the light split in four, twice at
    /// most). Their sum is the unshadowed irradiance.
    pub fn samples(&self, cells: usize) -> Vec<LightSample> {
        let mut out = Vec::new();
        for p in &self.parts {
            let Part::Disc(d) = p else { continue };
            // The source's own disc (its power), in one direction when small, else seven.
            let spread = d.radius_deg.max(0.0);
            let dirs: Vec<DVec3> = if spread < 1.5 {
                vec![d.dir]
            } else {
                let (a, b) = d.dir.any_orthonormal_pair();
                let r = (0.6 * spread).to_radians();
                let mut v = vec![d.dir];
                for k in 0..6 {
                    let t = TAU * k as f64 / 6.0;
                    v.push((d.dir + (a * t.cos() + b * t.sin()) * r.tan()).normalize());
                }
                v
            };
            let n = dirs.len() as f64;
            for w in dirs {
                if w.z <= 0.0 {
                    continue;
                }
                let e = d.solid_angle() * w.z / n;
                out.push(LightSample {
                    dir: self.world(w),
                    irradiance: scale(d.radiance, e),
                    point: true,
                });
            }
        }
        // Cells of equal solid angle: bands of equal height in z, each cut in azimuth.
        let bands = ((cells as f64 / 2.0).sqrt().round() as usize).max(1);
        let mut queue: Vec<(f64, f64, f64, f64, u32)> = Vec::new();
        for i in 0..bands {
            let (z0, z1) = (i as f64 / bands as f64, (i + 1) as f64 / bands as f64);
            let na = (2 * bands).max(1);
            for j in 0..na {
                let (a0, a1) = (TAU * j as f64 / na as f64, TAU * (j + 1) as f64 / na as f64);
                queue.push((z0, z1, a0, a1, 0));
            }
        }
        let mut cells_out: Vec<(Rgb, DVec3)> = Vec::new();
        // The whole diffuse light first, so that "bright" means the same for every cell.
        let top: Vec<(Rgb, DVec3)> = queue
            .iter()
            .map(|&(z0, z1, a0, a1, _)| self.cell(z0, z1, a0, a1))
            .collect();
        let total: f64 = top.iter().map(|c| luminance(c.0)).sum();
        for (&cell, &(e, w)) in queue.iter().zip(&top) {
            let mut stack = vec![(cell, e, w)];
            while let Some(((z0, z1, a0, a1, depth), e, w)) = stack.pop() {
                let y = luminance(e);
                if depth < 2 && y > 0.08 * total && y > 0.0 {
                    let (zm, am) = (0.5 * (z0 + z1), 0.5 * (a0 + a1));
                    for c in [
                        (z0, zm, a0, am, depth + 1),
                        (z0, zm, am, a1, depth + 1),
                        (zm, z1, a0, am, depth + 1),
                        (zm, z1, am, a1, depth + 1),
                    ] {
                        let (e, w) = self.cell(c.0, c.1, c.2, c.3);
                        stack.push((c, e, w));
                    }
                    continue;
                }
                if y > 0.0 {
                    cells_out.push((e, w));
                }
            }
        }
        // Deterministic order: by direction.
        cells_out.sort_by(|a, b| {
            (a.1.z, a.1.y, a.1.x)
                .partial_cmp(&(b.1.z, b.1.y, b.1.x))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        for (e, w) in cells_out {
            out.push(LightSample {
                dir: self.world(w),
                irradiance: e,
                point: false,
            });
        }
        out
    }

    /// Irradiance on a horizontal plane from the diffuse parts over the cell
    /// `z ∈ [z0, z1]`, `azimuth ∈ [a0, a1]` (a 6 × 6 grid of its radiance, each point
    /// weighted by its solid angle and cosine), and its luminance-weighted centre direction
    /// (environment frame).
    fn cell(&self, z0: f64, z1: f64, a0: f64, a1: f64) -> (Rgb, DVec3) {
        let n = 6;
        let d_omega = (z1 - z0) * (a1 - a0) / (n * n) as f64;
        let (mut e, mut centre, mut wsum) = ([0.0; 3], DVec3::ZERO, 0.0);
        for i in 0..n {
            let z = z0 + (z1 - z0) * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            for j in 0..n {
                let a = a0 + (a1 - a0) * (j as f64 + 0.5) / n as f64;
                let w = DVec3::new(r * a.cos(), r * a.sin(), z);
                let c = self.diffuse(w);
                let k = z * d_omega;
                add(&mut e, scale(c, k));
                let y = luminance(c).max(0.0) * k;
                centre += w * y;
                wsum += y;
            }
        }
        let mid = {
            let (z, a) = (0.5 * (z0 + z1), 0.5 * (a0 + a1));
            let r = (1.0 - z * z).max(0.0).sqrt();
            DVec3::new(r * a.cos(), r * a.sin(), z)
        };
        let w = if wsum > 0.0 {
            centre.try_normalize().unwrap_or(mid)
        } else {
            mid
        };
        (e.map(|v| v.max(0.0)), w)
    }

    /// Whether every part is grey (equal R, G and B), so that a colourless stone without
    /// dispersion is seen in grey.
    pub fn is_grey(&self) -> bool {
        let grey = |c: &Rgb| c[0] == c[1] && c[1] == c[2];
        self.parts.iter().all(|p| match p {
            Part::Sky { zenith, horizon } => grey(zenith) && grey(horizon),
            Part::Floor(c) => grey(c),
            Part::Disc(d) => grey(&d.radiance),
            Part::Ring { radiance, .. } | Part::Panel { radiance, .. } => grey(radiance),
            Part::Map(m) => m.is_grey(),
        })
    }
}

/// Solid angle of a cap of angular radius `deg`.
pub fn cap(deg: f64) -> f64 {
    TAU * (1.0 - deg.to_radians().cos())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::lighting::Lighting;
    use std::f64::consts::PI;

    /// A uniform sky is the ISO light and a cosine sky the COS light, bit for bit.
    #[test]
    fn skies_are_the_iso_and_cos_lights() {
        let l = Lighting::new(0.0, &[]);
        let iso = Environment::new(
            "iso",
            vec![Part::Sky {
                zenith: [1.0; 3],
                horizon: [1.0; 3],
            }],
        );
        let cos = Environment::new(
            "cos",
            vec![Part::Sky {
                zenith: [1.0; 3],
                horizon: [0.0; 3],
            }],
        );
        for k in 0..=3600 {
            let w = direction(-90.0 + 0.05 * k as f64, 0.7 * k as f64);
            assert_eq!(iso.radiance(w)[0], l.iso(w));
            assert_eq!(cos.radiance(w)[1], l.cos(w));
        }
    }

    /// A round light keeps its power whatever its size (the filter only spreads it), and
    /// its radiance changes continuously with the direction.
    #[test]
    fn discs_keep_their_power() {
        for r in [0.27, 1.0, 2.5, 8.0] {
            let d = Disc::new(DVec3::Z, r, [3.0, 2.0, 1.0]);
            // ∫ radiance dΩ over the cap around the axis, numerically.
            let n = 20000;
            let top = (r.max(1.0) + 1.0).to_radians();
            let mut p = 0.0;
            for i in 0..n {
                let t = top * (i as f64 + 0.5) / n as f64;
                let w = DVec3::new(t.sin(), 0.0, t.cos());
                p += d.weight(w) * TAU * t.sin() * top / n as f64;
            }
            assert!(
                (p - d.solid_angle()).abs() < 1e-6 * d.solid_angle(),
                "{r}: {p}"
            );
        }
        let d = Disc::new(DVec3::Z, 3.0, [1.0; 3]);
        let mut prev = d.weight(DVec3::Z);
        for k in 1..=2000 {
            let t = (k as f64 * 0.0025).to_radians();
            let v = d.weight(DVec3::new(t.sin(), 0.0, t.cos()));
            assert!((v - prev).abs() < 0.01, "{k}");
            prev = v;
        }
    }

    /// The samples add up to the irradiance on a horizontal plane: π for a uniform sky,
    /// 2π/3 for a cosine sky, a round light's power times its cosine.
    #[test]
    fn samples_add_up_to_the_irradiance() {
        let sum =
            |env: &Environment| -> f64 { env.samples(64).iter().map(|s| s.irradiance[0]).sum() };
        let iso = Environment::new(
            "iso",
            vec![Part::Sky {
                zenith: [1.0; 3],
                horizon: [1.0; 3],
            }],
        );
        // The horizon's ramp takes half of the ±1° band: a few 1e-4 of π.
        assert!((sum(&iso) - PI).abs() < 2e-3 * PI, "{}", sum(&iso));
        let cos = Environment::new(
            "cos",
            vec![Part::Sky {
                zenith: [1.0; 3],
                horizon: [0.0; 3],
            }],
        );
        assert!((sum(&cos) - TAU / 3.0).abs() < 2e-3, "{}", sum(&cos));
        let sun = direction(40.0, 30.0);
        let env = Environment::new("sun", vec![Part::Disc(Disc::new(sun, 0.27, [5.0; 3]))]);
        let s = env.samples(64);
        assert_eq!(s.len(), 1);
        let want = 5.0 * cap(0.27) * sun.z;
        assert!((s[0].irradiance[0] - want).abs() < 1e-12 * want);
        // Turned, the light comes from the turned direction.
        let mut turned = env.clone();
        turned.rotation_deg = 90.0;
        let t = turned.samples(64);
        assert!((t[0].dir - direction(40.0, 120.0)).length() < 1e-12);
        assert!(turned.radiance(direction(40.0, 120.0))[0] > 0.0);
    }
}
