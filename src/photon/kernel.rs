//! The photon tracer (`Tracer`: one light and solid resolved) and what a photon meets at an
//! interface; the lanes and the steps both kernels share are in `lanes.rs`, the singly
//! refractive kernel in `singly.rs`, the birefringent one in `crystal.rs`, and the choice of
//! kernel for a chunk of photons in `chunks.rs`.

use super::config::{ExitWeights, TraceConfig, WavelengthSampling, UNLIMITED_CAP};
use super::crystal_setup::CrystalSetup;
use super::entry_grid::EntryGrid;
use super::light::{Light, LightKind, LightSize};
use super::reach::Reach;
use super::solid::TraceSolid;
use super::tally::Counts;
use crate::error::{Error, Result};
use crate::geometry::DVec3;
use crate::optics::color::{d65, D65_MAX, LAMBDA_MAX, LAMBDA_MIN};
use crate::optics::{fresnel, reflect, rotate_stokes, s_axis, Dispersion, Material, Stokes};
use crate::optics::{Absorption, THESIS_ABSORPTION};
use rand::rngs::SmallRng;
use rand::RngCore;

/// Cells of √(1 − z) ∈ [0, √2] in the exit-angle lookup.
const ANGLE_CELLS: usize = 4096;
const ANGLE_CELLS_PER_U: f64 = ANGLE_CELLS as f64 / std::f64::consts::SQRT_2;

/// Everything the photon loop needs, resolved for one solid and light.
pub(crate) struct Tracer<'a> {
    pub(super) s: &'a TraceSolid,
    kind: LightKind,
    centre: DVec3,
    axis: DVec3,
    u: DVec3,
    v: DVec3,
    half: f64,
    pub(super) max_depth: u32,
    pub(super) absorption: Absorption,
    pub(super) polarization: bool,
    pub(super) material: Material,
    wavelengths: WavelengthSampling,
    pub(super) fixed_n: Option<f64>,
    pub(super) seed: u64,
    entry_grid: Option<EntryGrid>,
    /// Undirected lights: which photons surely miss, from their start and polar angle.
    reach: Option<Reach>,
    /// cos(k°) for k = 0..=180.
    cos_deg: [f64; 181],
    /// For each cell of √(1 − z), the exit-angle bin at the cell's top (largest z), less 1e-9.
    angle_start: Box<[u8; ANGLE_CELLS]>,
    /// Weights of an exit direction, summed into [`Counts::weight_sum`].
    pub(crate) exit_weight: Option<&'a ExitWeights<'a>>,
    /// A birefringent stone's crystal (its photons take the kernel of `crystal.rs`).
    pub(super) crystal: Option<CrystalSetup>,
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

/// Two uniforms in [0, 1) from one 64-bit draw: its high and its low 32 bits, each `k·2⁻³²`
/// (exact in f64). xoshiro256++ scrambles every output bit (its low bits are as good as its
/// high ones), so the halves are independent and uniform. Every use needs no more than 32
/// bits: a roulette `u < p` then fires with probability `p` to within 2⁻³² ≈ 2.3e-10 (far
/// below the ~2e-6 standard error of the largest run, `MAX_PHOTONS`), a
/// photon's start on the light square is placed to 2⁻³¹ of its side and its wavelength to
/// 1e-7 nm; Beer–Lambert's `−ln(1 − u)` is finite (at most 22.2, a 2.3e-10 tail cut).
#[inline(always)]
pub(super) fn two_uniforms(rng: &mut SmallRng) -> (f64, f64) {
    const SCALE: f64 = 1.0 / (1u64 << 32) as f64;
    let x = rng.next_u64();
    ((x >> 32) as f64 * SCALE, (x as u32) as f64 * SCALE)
}

pub(super) fn chunk_seed(seed: u64, chunk: u64) -> u64 {
    // SplitMix64 finaliser of a combination of the two.
    let mut z =
        seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ chunk.wrapping_add(0x632B_E59B_D9B4_E019);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A photon that enters the stone ([`Tracer::next_entry`]): where it left the light, its
/// direction, the distance to the stone and the facet it enters by, its wavelength (nm) and
/// the uniform of the entry's roulette.
pub(super) struct Entry {
    pub o: DVec3,
    pub d: DVec3,
    pub t: f64,
    pub f: usize,
    pub lambda: f64,
    pub x: f64,
}

/// Polarization state: Stokes vector (I = 1) and its reference axis.
pub(super) struct Pol {
    pub(super) s: Stokes,
    pub(super) e: DVec3,
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
                (c, half)
            }
        };
        // A light covering the stone must be in front of the whole stone.
        let ahead = s
            .vertices
            .iter()
            .map(|p| (*p - centre).dot(axis))
            .fold(f64::INFINITY, f64::min);
        if light.size == LightSize::CoverStone && ahead <= 0.0 {
            return Err(Error::invalid(
                "light",
                "the light's plane cuts through the stone; move it further away",
            ));
        }
        let fixed_n = match (&cfg.material.dispersion, cfg.wavelengths) {
            (Dispersion::Constant(n), _) => Some(*n),
            (_, WavelengthSampling::Fixed(l)) => Some(cfg.material.ri(l)),
            _ => None,
        };
        let cos_deg: [f64; 181] = std::array::from_fn(|k| (k as f64).to_radians().cos());
        let w = s.centre - centre;
        let to_sphere = DVec3::new(axis.dot(w), u.dot(w), v.dot(w));
        Ok(Tracer {
            reach: (light.kind == LightKind::Undirected)
                .then(|| Reach::new(half, to_sphere, s.radius)),
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
            angle_start: Box::new(std::array::from_fn(|c| {
                let u = c as f64 / ANGLE_CELLS_PER_U;
                let z = (1.0 - u * u + 1e-9).min(1.0);
                cos_deg[1..180].partition_point(|&t| z <= t) as u8
            })),
            cos_deg,
            entry_grid: (light.kind == LightKind::Directed)
                .then(|| EntryGrid::new(s, centre, axis, u, v, half)),
            exit_weight: None,
            crystal: CrystalSetup::of(&cfg.material),
        })
    }

    pub(crate) fn facet_count(&self) -> usize {
        self.s.facets
    }

    /// A photon's wavelength from the uniform `u` (and, for D65's rejection sampling, as many
    /// more draws as it takes: each candidate from a fresh uniform, its acceptance another).
    #[inline(always)]
    pub(super) fn wavelength(&self, u: f64, rng: &mut SmallRng) -> f64 {
        let span = LAMBDA_MAX - LAMBDA_MIN;
        match self.wavelengths {
            WavelengthSampling::Uniform => LAMBDA_MIN + span * u,
            WavelengthSampling::Fixed(l) => l,
            WavelengthSampling::D65 => {
                let mut u = u;
                loop {
                    let l = LAMBDA_MIN + span * u;
                    let (accept, next) = two_uniforms(rng);
                    if accept * D65_MAX < d65(l) {
                        break l;
                    }
                    u = next;
                }
            }
        }
    }

    /// The exit-angle bin of a direction with z component `z`: bin k holds angles in
    /// [k°, k+1°), so the bin is the count of thresholds cos(k°), k = 1..179, that z does not
    /// exceed. The table gives a count no larger than that for z's cell of √(1 − z)
    /// (near-linear in the angle); a step or two finishes it.
    #[inline(always)]
    fn angle_bin(&self, z: f64) -> usize {
        let u = (1.0 - z).max(0.0).sqrt() * ANGLE_CELLS_PER_U;
        let mut bin = self.angle_start[super::entry_grid::grid_cell(u, ANGLE_CELLS)] as usize;
        while bin < 179 && z <= self.cos_deg[bin + 1] {
            bin += 1;
        }
        bin
    }

    #[inline(always)]
    pub(super) fn tally_exit(&self, k: &mut Counts, facet: usize, d: DVec3) {
        k.categories[self.s.category[facet] as usize] += 1;
        k.per_facet[facet] += 1;
        let bin = self.angle_bin(d.z);
        k.angle_hist[bin] += 1;
        k.light_return += (d.z > 0.0) as u64;
        if let Some(w) = self.exit_weight {
            for (i, x) in w(d).into_iter().enumerate() {
                k.weight_sum[i] += x;
                k.weight_sq[i] += x * x;
            }
        }
    }

    /// Choose reflection or transmission (by the uniform `x`) at facet normal `m` (outward)
    /// for a photon moving in `d` from index `n1` into `n2`; `m_in` is the normal facing
    /// against `d`. Returns the new direction and whether it was transmitted.
    #[inline(always)]
    pub(super) fn interface<const POL: bool>(
        &self,
        x: f64,
        pol: &mut Pol,
        d: DVec3,
        m_in: DVec3,
        n1: f64,
        n2: f64,
    ) -> (DVec3, bool) {
        let cos_i = -m_in.dot(d);
        let eta = n1 / n2;
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

    /// Shoot a lane's next photons (`left` of them remain) until one enters the stone, and draw
    /// its wavelength and the entry roulette's uniform (one draw for both); `None`, the lane
    /// emptied, when it has none left or the hit limit is reached. The start of a photon in
    /// both kernels, the singly refractive and the birefringent.
    #[inline(always)]
    pub(super) fn next_entry(
        &self,
        rng: &mut SmallRng,
        left: &mut u64,
        k: &mut Counts,
        limit: u64,
    ) -> Option<Entry> {
        let (o, d, t, f) = loop {
            if *left == 0 || k.hit >= limit {
                *left = 0;
                return None;
            }
            *left -= 1;
            if let Some(entry) = self.shoot(rng, k) {
                break entry;
            }
        };
        k.hit += 1;
        let (u, x) = two_uniforms(rng);
        let lambda = self.wavelength(u, rng);
        Some(Entry {
            o,
            d,
            t,
            f,
            lambda,
            x,
        })
    }

    /// One photon leaves the light: its start, direction, and where it enters the stone
    /// (`None` if it misses).
    #[inline(always)]
    pub(super) fn shoot(
        &self,
        rng: &mut SmallRng,
        k: &mut Counts,
    ) -> Option<(DVec3, DVec3, f64, usize)> {
        k.shot += 1;
        let (ua, ub) = two_uniforms(rng);
        let a = (2.0 * ua - 1.0) * self.half;
        let b = (2.0 * ub - 1.0) * self.half;
        let o = self.centre + self.u * a + self.v * b;
        let d = match self.kind {
            LightKind::Directed => self.axis,
            LightKind::Undirected => {
                let (c, uphi) = two_uniforms(rng);
                let phi = std::f64::consts::TAU * uphi;
                if self.reach.as_ref().is_some_and(|r| r.misses(a, b, c)) {
                    // Counted exactly as the miss the full test below would find, after the
                    // same random draws: only the trigonometry and the entry test are saved.
                    return None;
                }
                let s = (1.0 - c * c).max(0.0).sqrt();
                let (sp, cp) = phi.sin_cos();
                self.axis * c + self.u * (s * cp) + self.v * (s * sp)
            }
        };
        let (t, f) = match &self.entry_grid {
            Some(grid) => {
                let f = grid.entry(a, b)?;
                let n = self.s.normals[f];
                let t = (self.s.off[f] - n.dot(o)) / n.dot(d);
                if t < 0.0 {
                    // The light's square passes through the stone here: no photon.
                    return None;
                }
                (t, f)
            }
            None => self.s.entry(o, d)?,
        };
        Some((o, d, t, f))
    }

    /// Where along the next `t` of its path a photon is absorbed, given the uniform `u` drawn for
    /// it and its Beer–Lambert coefficient `beer` (per girdle diameter): the thesis's flat
    /// chance per bounce (at the facet), an exponential free path, or never. Both kernels.
    #[inline(always)]
    pub(super) fn absorbed_within(&self, u: f64, t: f64, beer: f64) -> Option<f64> {
        match self.absorption {
            Absorption::None => None,
            Absorption::Thesis => (u < THESIS_ABSORPTION).then_some(t),
            Absorption::Beer(_) | Absorption::Body { .. } => {
                let s = -(1.0 - u).ln() / beer;
                (s < t).then_some(s)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng;
    use rand::SeedableRng;

    /// The kernel's own unpolarized Fresnel reflectance and refraction are the library's
    /// (`optics::fresnel`, `optics::refract`): same reflectance, refraction cosine, total
    /// internal reflection and refracted direction, into and out of the stone.
    #[test]
    fn kernel_fresnel_and_refraction_match_optics() {
        use crate::optics::refract;
        let pairs = [
            (1.0, 2.4173),
            (2.4173, 1.0),
            (1.0, 1.5),
            (1.77, 1.0),
            (1.33, 1.0),
        ];
        let mut tir = 0;
        for (n1, n2) in pairs {
            let eta = n1 / n2;
            for k in 0..=200 {
                let cos_i = k as f64 / 200.0;
                let lib = fresnel(cos_i, n1, n2);
                let (r, cos_t) = reflectance(cos_i, eta);
                assert!(
                    (r - lib.reflectance()).abs() < 1e-12,
                    "{n1}->{n2} cos {cos_i}: {r}"
                );
                assert_eq!(cos_t == 0.0, lib.tir, "{n1}->{n2} cos {cos_i}");
                if lib.tir {
                    tir += 1;
                    assert_eq!(r, 1.0);
                    continue;
                }
                assert!((cos_t - lib.cos_t).abs() < 1e-12);
                // A direction with this incidence cosine on the plane z = 0, normal +z.
                let m = DVec3::Z;
                let sin_i = (1.0 - cos_i * cos_i).sqrt();
                let d = DVec3::new(sin_i, 0.0, -cos_i);
                let mine = refracted(d, m, cos_i, cos_t, eta);
                let want = refract(d, m, n1, n2).expect("not TIR");
                assert!(mine.distance(want) < 1e-12, "{mine} vs {want}");
                assert!((mine.length() - 1.0).abs() < 1e-12);
            }
        }
        assert!(tir > 100, "{tir}");
    }

    /// The undirected lights' early rejection (`reach.rs`) never drops a photon that reaches
    /// the stone's bounding sphere (so none that hits the stone), and it rejects most of
    /// those that miss.
    #[test]
    fn undirected_rejection_only_drops_misses() {
        let cut = crate::io::load_cut("tolkowsky").unwrap();
        let s = TraceSolid::new(&cut.solid).unwrap();
        let close = Light {
            centre: DVec3::new(0.2, -0.1, 0.9),
            ..Light::overhead()
        };
        let turned = Light::rotated(LightKind::Undirected, 120.0);
        for light in [Light::overhead(), Light::offset(), turned, close] {
            let tr = Tracer::new(&s, &light, &TraceConfig::thesis()).unwrap();
            let mut rng = SmallRng::seed_from_u64(9);
            let (mut sphere, mut missed, mut rejected) = (0, 0, 0);
            for _ in 0..200_000 {
                let a = (2.0 * rng.random::<f64>() - 1.0) * tr.half;
                let b = (2.0 * rng.random::<f64>() - 1.0) * tr.half;
                let c = rng.random::<f64>();
                let phi = std::f64::consts::TAU * rng.random::<f64>();
                let sn = (1.0 - c * c).sqrt();
                let o = tr.centre + tr.u * a + tr.v * b;
                let d = tr.axis * c + tr.u * (sn * phi.cos()) + tr.v * (sn * phi.sin());
                // The bounding sphere's own test, without the facets.
                let w = s.centre - o;
                let bd = w.dot(d);
                let r2 = s.radius * s.radius;
                let reaches =
                    !(w.length_squared() - bd * bd > r2 || (bd < 0.0 && w.length_squared() > r2));
                let rej = tr.reach.as_ref().unwrap().misses(a, b, c);
                assert!(
                    !(rej && reaches),
                    "{}: a {a} b {b} c {c} phi {phi}",
                    light.label
                );
                assert!(!rej || s.entry(o, d).is_none());
                sphere += reaches as u32;
                missed += !reaches as u32;
                rejected += rej as u32;
            }
            assert!(sphere > 200, "{}: {sphere}", light.label);
            eprintln!(
                "{}: {rejected} of {missed} misses rejected early",
                light.label
            );
            if light.centre.length() > 2.0 {
                assert!(rejected as f64 > 0.8 * missed as f64, "{}", light.label);
            }
        }
    }

    /// The table-started exit-angle bin is the binary search's on every threshold, its
    /// neighbouring floats, the ends and random z.
    #[test]
    fn angle_bins_match_the_binary_search() {
        let s = TraceSolid::new(&crate::io::load_cut("tolkowsky").unwrap().solid).unwrap();
        let tr = Tracer::new(&s, &Light::directed(0.0), &TraceConfig::thesis()).unwrap();
        let search = |z: f64| tr.cos_deg[1..180].partition_point(|&c| z <= c);
        let mut zs = vec![-1.0, 1.0, 0.0, -0.0, f64::NAN];
        for &c in &tr.cos_deg {
            zs.extend([c, c.next_up(), c.next_down()]);
        }
        let mut rng = SmallRng::seed_from_u64(2);
        zs.extend((0..100_000).map(|_| 2.0 * rng.random::<f64>() - 1.0));
        zs.extend((0..10_000).map(|_| 1.0 - 1e-3 * rng.random::<f64>()));
        zs.extend((0..10_000).map(|_| -1.0 + 1e-3 * rng.random::<f64>()));
        for z in zs {
            if (-1.0..=1.0).contains(&z) || z.is_nan() {
                assert_eq!(tr.angle_bin(z), search(z), "z = {z}");
            }
        }
        assert_eq!(tr.angle_bin(-1.0), 179);
        assert_eq!(tr.angle_bin(1.0), 0);
    }

    #[test]
    fn beam_grid_entry_matches_the_general_entry() {
        let cut = crate::io::load_cut("tolkowsky").unwrap();
        let s = TraceSolid::new(&cut.solid).unwrap();
        for light in [
            Light::directed(0.0),
            Light::directed(60.0),
            Light::directed(90.0),
            Light::offset_directed(),
        ] {
            let cfg = TraceConfig::thesis();
            let tr = Tracer::new(&s, &light, &cfg).unwrap();
            let grid = tr.entry_grid.as_ref().unwrap();
            let mut rng = SmallRng::seed_from_u64(5);
            let (mut hits, mut differ) = (0, 0);
            for _ in 0..20_000 {
                let a = (2.0 * rng.random::<f64>() - 1.0) * tr.half;
                let b = (2.0 * rng.random::<f64>() - 1.0) * tr.half;
                let o = tr.centre + tr.u * a + tr.v * b;
                let fast = grid.entry(a, b);
                let general = s.entry(o, tr.axis).map(|(_, f)| f);
                hits += general.is_some() as u32;
                differ += (fast != general) as u32;
            }
            assert!(hits > 5_000, "{}", light.label);
            assert_eq!(differ, 0, "{}", light.label);
        }
    }
}
