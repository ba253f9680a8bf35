//! The per-photon loop.

use super::solid::TraceSolid;
use super::tally::{Counts, Fate, PhotonPath};
use super::{
    Absorption, Light, LightKind, LightSize, TraceConfig, WavelengthSampling, CHUNK,
    THESIS_ABSORPTION, UNLIMITED_CAP,
};
use crate::error::{Error, Result};
use crate::geometry::DVec3;
use crate::optics::color::{d65, D65_MAX, LAMBDA_MAX, LAMBDA_MIN};
use crate::optics::{fresnel, reflect, rotate_stokes, s_axis, Dispersion, Material, Stokes};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

/// Everything the photon loop needs, resolved for one solid and light.
pub(crate) struct Tracer<'a> {
    s: &'a TraceSolid,
    kind: LightKind,
    centre: DVec3,
    axis: DVec3,
    u: DVec3,
    v: DVec3,
    half: f64,
    max_depth: u32,
    absorption: Absorption,
    polarization: bool,
    material: Material,
    wavelengths: WavelengthSampling,
    fixed_n: Option<f64>,
    seed: u64,
}

/// Unpolarized Fresnel reflectance for incidence cosine `cos_i` and index ratio
/// `eta = n_i / n_t`; also the refraction cosine (0 under total internal reflection, where the
/// reflectance is 1).
#[inline(always)]
fn reflectance(cos_i: f64, eta: f64) -> (f64, f64) {
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return (1.0, 0.0);
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    (0.5 * (rs * rs + rp * rp), cos_t)
}

/// Refracted direction for unit `d`, normal `n` facing against `d` (n·d < 0), cosines and
/// index ratio.
#[inline(always)]
fn refracted(d: DVec3, n: DVec3, cos_i: f64, cos_t: f64, eta: f64) -> DVec3 {
    eta * d + (eta * cos_i - cos_t) * n
}

fn chunk_seed(seed: u64, chunk: u64) -> u64 {
    // SplitMix64 finaliser of a combination of the two.
    let mut z =
        seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ chunk.wrapping_add(0x632B_E59B_D9B4_E019);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Polarization state: Stokes vector (I = 1) and its reference axis.
struct Pol {
    s: Stokes,
    e: DVec3,
}

impl<'a> Tracer<'a> {
    pub(crate) fn new(s: &'a TraceSolid, light: &Light, cfg: &TraceConfig) -> Result<Tracer<'a>> {
        let axis = light.axis.normalize();
        let helper = if axis.x.abs() < 0.9 {
            DVec3::X
        } else {
            DVec3::Y
        };
        let u = (helper - helper.dot(axis) * axis).normalize();
        let v = axis.cross(u);
        let (centre, half) = match light.size {
            LightSize::Side(side) => (light.centre, 0.5 * side),
            LightSize::CoverStone => {
                let (mut ulo, mut uhi, mut vlo, mut vhi) = (
                    f64::INFINITY,
                    f64::NEG_INFINITY,
                    f64::INFINITY,
                    f64::NEG_INFINITY,
                );
                for p in &s.vertices {
                    let r = *p - light.centre;
                    let (a, b) = (r.dot(u), r.dot(v));
                    ulo = ulo.min(a);
                    uhi = uhi.max(a);
                    vlo = vlo.min(b);
                    vhi = vhi.max(b);
                }
                let c = light.centre + u * 0.5 * (ulo + uhi) + v * 0.5 * (vlo + vhi);
                let half = 0.5 * (uhi - ulo).max(vhi - vlo) * (1.0 + 1e-9);
                // The light plane must be in front of the whole stone.
                let behind = s
                    .vertices
                    .iter()
                    .map(|p| (*p - light.centre).dot(axis))
                    .fold(f64::INFINITY, f64::min);
                if behind <= 0.0 {
                    return Err(Error::invalid(
                        "light",
                        "the light's plane cuts through the stone; move it further away",
                    ));
                }
                (c, half)
            }
        };
        let fixed_n = match (&cfg.material.dispersion, cfg.wavelengths) {
            (Dispersion::Constant(n), _) => Some(*n),
            (_, WavelengthSampling::Fixed(l)) => Some(cfg.material.ri(l)),
            _ => None,
        };
        Ok(Tracer {
            s,
            kind: light.kind,
            centre,
            axis,
            u,
            v,
            half,
            max_depth: cfg.depth.unwrap_or(UNLIMITED_CAP),
            absorption: cfg.absorption,
            polarization: cfg.polarization,
            material: cfg.material.clone(),
            wavelengths: cfg.wavelengths,
            fixed_n,
            seed: cfg.seed,
        })
    }

    pub(crate) fn facet_count(&self) -> usize {
        self.s.facets
    }

    /// Trace chunk `c` of `n` photons; with `hit_limit`, stop after that many hits.
    pub(crate) fn chunk(&self, c: u64, n: u64, hit_limit: Option<u64>) -> Counts {
        let mut rng = SmallRng::seed_from_u64(chunk_seed(self.seed, c));
        let mut k = Counts::new(self.s.facets);
        let limit = hit_limit.unwrap_or(u64::MAX);
        let mut sink = Vec::new();
        for _ in 0..n {
            if k.hit >= limit {
                break;
            }
            if self.polarization {
                self.photon::<true, false>(&mut rng, &mut k, &mut sink);
            } else {
                self.photon::<false, false>(&mut rng, &mut k, &mut sink);
            }
        }
        k
    }

    /// Replay the run's first `shot` photons in order and record the paths of the first `n`
    /// that hit the stone.
    pub(crate) fn record_paths(&self, n: usize, shot: u64) -> Vec<PhotonPath> {
        let mut out = Vec::new();
        let mut done = 0u64;
        let mut c = 0u64;
        while done < shot && out.len() < n {
            let mut rng = SmallRng::seed_from_u64(chunk_seed(self.seed, c));
            let mut k = Counts::new(self.s.facets);
            for _ in 0..CHUNK.min(shot - done) {
                let mut pts = Vec::new();
                let r = if self.polarization {
                    self.photon::<true, true>(&mut rng, &mut k, &mut pts)
                } else {
                    self.photon::<false, true>(&mut rng, &mut k, &mut pts)
                };
                if let Some((fate, wavelength)) = r {
                    out.push(PhotonPath {
                        wavelength,
                        points: pts,
                        fate,
                    });
                    if out.len() >= n {
                        break;
                    }
                }
            }
            done += CHUNK;
            c += 1;
        }
        out
    }

    #[inline(always)]
    fn wavelength(&self, rng: &mut SmallRng) -> f64 {
        match self.wavelengths {
            WavelengthSampling::Uniform => {
                LAMBDA_MIN + (LAMBDA_MAX - LAMBDA_MIN) * rng.random::<f64>()
            }
            WavelengthSampling::Fixed(l) => l,
            WavelengthSampling::D65 => loop {
                let l = LAMBDA_MIN + (LAMBDA_MAX - LAMBDA_MIN) * rng.random::<f64>();
                if rng.random::<f64>() * D65_MAX < d65(l) {
                    break l;
                }
            },
        }
    }

    #[inline(always)]
    fn tally_exit(&self, k: &mut Counts, facet: usize, d: DVec3) {
        k.categories[self.s.category[facet] as usize] += 1;
        k.per_facet[facet] += 1;
        let deg = d.z.clamp(-1.0, 1.0).acos().to_degrees();
        k.angle_hist[(deg as usize).min(179)] += 1;
        k.light_return += (d.z > 0.0) as u64;
    }

    /// Choose reflection or transmission at facet normal `m` (outward) for a photon moving in
    /// `d` from index `n1` into `n2`; `m_in` is the normal facing against `d`. Returns the new
    /// direction and whether it was transmitted.
    #[inline(always)]
    fn interface<const POL: bool>(
        &self,
        rng: &mut SmallRng,
        pol: &mut Pol,
        d: DVec3,
        m_in: DVec3,
        n1: f64,
        n2: f64,
    ) -> (DVec3, bool) {
        let cos_i = -m_in.dot(d);
        let eta = n1 / n2;
        let x: f64 = rng.random();
        if POL {
            let es = s_axis(d, m_in).unwrap_or(pol.e);
            let s1 = rotate_stokes(pol.s, pol.e, es, d);
            let f = fresnel(cos_i, n1, n2);
            let sr = f.mueller_reflect().apply(s1);
            pol.e = es;
            if f.tir || x * s1.x < sr.x {
                pol.s = sr / sr.x;
                (reflect(d, m_in), false)
            } else {
                let st = f.mueller_transmit().apply(s1);
                pol.s = st / st.x;
                (refracted(d, m_in, f.cos_i, f.cos_t, eta), true)
            }
        } else {
            let (r, cos_t) = reflectance(cos_i, eta);
            if x < r {
                (reflect(d, m_in), false)
            } else {
                (refracted(d, m_in, cos_i, cos_t, eta), true)
            }
        }
    }

    /// One photon. Returns its fate and wavelength if it hit the stone. With `REC`, pushes
    /// the path's points to `rec`.
    #[inline(always)]
    fn photon<const POL: bool, const REC: bool>(
        &self,
        rng: &mut SmallRng,
        k: &mut Counts,
        rec: &mut Vec<DVec3>,
    ) -> Option<(Fate, f64)> {
        k.shot += 1;
        let a = 2.0 * rng.random::<f64>() - 1.0;
        let b = 2.0 * rng.random::<f64>() - 1.0;
        let o = self.centre + self.u * (a * self.half) + self.v * (b * self.half);
        let mut d = match self.kind {
            LightKind::Directed => self.axis,
            LightKind::Undirected => {
                let c = rng.random::<f64>();
                let phi = std::f64::consts::TAU * rng.random::<f64>();
                let s = (1.0 - c * c).max(0.0).sqrt();
                let (sp, cp) = phi.sin_cos();
                self.axis * c + self.u * (s * cp) + self.v * (s * sp)
            }
        };
        let (t, f) = self.s.entry(o, d)?;
        k.hit += 1;
        let lambda = self.wavelength(rng);
        let n = self.fixed_n.unwrap_or_else(|| self.material.ri(lambda));
        let mut pol = Pol {
            s: Stokes::new(1.0, 0.0, 0.0, 0.0),
            e: if POL {
                d.any_orthonormal_vector()
            } else {
                DVec3::X
            },
        };
        let mut p = o + t * d;
        if REC {
            rec.push(o);
            rec.push(p);
        }
        let mut inter = 1u32;
        let m = self.s.normals[f];
        let (nd, transmitted) = self.interface::<POL>(rng, &mut pol, d, m, 1.0, n);
        d = nd;
        let fate = if !transmitted {
            self.tally_exit(k, f, d);
            if REC {
                rec.push(p + d);
            }
            Fate::Exited(f)
        } else {
            loop {
                if inter >= self.max_depth {
                    k.depth_limited += 1;
                    break Fate::DepthLimited;
                }
                let (t, j) = self.s.exit(p, d);
                if t >= f64::INFINITY || t.is_nan() {
                    // Numerically impossible for a bounded solid; counted, never a panic.
                    k.depth_limited += 1;
                    break Fate::DepthLimited;
                }
                match self.absorption {
                    Absorption::None => {}
                    Absorption::Thesis => {
                        if rng.random::<f64>() < THESIS_ABSORPTION {
                            k.absorbed += 1;
                            if REC {
                                rec.push(p + t * d);
                            }
                            break Fate::Absorbed;
                        }
                    }
                    Absorption::Beer(kk) => {
                        let u: f64 = rng.random();
                        let s = -(1.0 - u).ln() / kk;
                        if s < t {
                            k.absorbed += 1;
                            if REC {
                                rec.push(p + s * d);
                            }
                            break Fate::Absorbed;
                        }
                    }
                }
                p += t * d;
                inter += 1;
                if REC {
                    rec.push(p);
                }
                let m = self.s.normals[j];
                let (nd, transmitted) = self.interface::<POL>(rng, &mut pol, d, -m, n, 1.0);
                d = nd;
                if transmitted {
                    self.tally_exit(k, j, d);
                    if REC {
                        rec.push(p + d);
                    }
                    break Fate::Exited(j);
                }
            }
        };
        k.interactions += inter as u64;
        Some((fate, lambda))
    }
}
