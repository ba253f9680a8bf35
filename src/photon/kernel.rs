//! The per-photon loop.

use super::reach::Reach;
use super::solid::TraceSolid;
use super::tally::{Counts, Fate, PhotonPath};
use super::{
    Absorption, ExitWeights, Light, LightKind, LightSize, TraceConfig, WavelengthSampling, CHUNK,
    THESIS_ABSORPTION, UNLIMITED_CAP,
};
use crate::error::{Error, Result};
use crate::geometry::DVec3;
use crate::optics::color::{d65, D65_MAX, LAMBDA_MAX, LAMBDA_MIN};
use crate::optics::{fresnel, reflect, rotate_stokes, s_axis, Dispersion, Material, Stokes};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

/// A directed light's entry test, precomputed: for the photon leaving the light at
/// `centre + a·u + b·v`, facet i's plane is met at `t_i = c0_i + a·cu_i + b·cv_i`. The photon
/// enters through the facet with the largest `t` among those facing the light if that is no
/// larger than the smallest `t` among those facing away, and it is inside every facet
/// parallel to the beam (`g0 − a·gu − b·gv ≥ 0`).
///
/// A grid of cells over the light square speeds this up: a cell no front facet's projected
/// bounding box touches is outside the stone's shadow; a cell whose four corners are inside
/// the (convex) shadow is wholly inside, and there the entry facet is the best of the few
/// front facets whose projected bounding boxes touch the cell. Only cells on the shadow's
/// border run the full test.
struct Beam {
    front: [Vec<f64>; 3],
    front_facet: Vec<usize>,
    back: [Vec<f64>; 3],
    parallel: Vec<[f64; 3]>,
    half: f64,
    /// Each cell packed in 4 bytes (the grid then mostly stays in cache): [`MISS`],
    /// [`BORDER`], or an inside cell's candidates `start | len << 24`.
    cells: Vec<u32>,
    candidates: Vec<u32>,
}

/// A cell outside the shadow.
const MISS: u32 = u32::MAX;
/// A cell on the shadow's border (or an inside cell too big to pack: the full test is exact
/// everywhere).
const BORDER: u32 = u32::MAX - 1;

const BL: usize = 4;
/// Cells of √(1 − z) ∈ [0, √2] in the exit-angle lookup.
const ANGLE_CELLS: usize = 4096;
const ANGLE_CELLS_PER_U: f64 = ANGLE_CELLS as f64 / std::f64::consts::SQRT_2;
/// Cells per side of the beam grid.
const GRID: usize = 128;

impl Beam {
    fn new(s: &TraceSolid, centre: DVec3, axis: DVec3, u: DVec3, v: DVec3, half: f64) -> Beam {
        let mut front: [Vec<f64>; 3] = Default::default();
        let mut back: [Vec<f64>; 3] = Default::default();
        let mut front_facet = Vec::new();
        let mut parallel = Vec::new();
        for (i, n) in s.normals.iter().enumerate() {
            let nd = n.dot(axis);
            let g0 = s.off[i] - n.dot(centre);
            let (gu, gv) = (n.dot(u), n.dot(v));
            if nd.abs() < 1e-12 {
                parallel.push([g0, gu, gv]);
                continue;
            }
            let c = [g0 / nd, -gu / nd, -gv / nd];
            let dst = if nd < 0.0 { &mut front } else { &mut back };
            for k in 0..3 {
                dst[k].push(c[k]);
            }
            if nd < 0.0 {
                front_facet.push(i);
            }
        }
        let n_front = front_facet.len();
        // Pad to whole lanes with planes that never decide anything.
        while !front[0].len().is_multiple_of(BL) {
            front[0].push(f64::NEG_INFINITY);
            front[1].push(0.0);
            front[2].push(0.0);
            front_facet.push(usize::MAX);
        }
        while !back[0].len().is_multiple_of(BL) {
            back[0].push(f64::INFINITY);
            back[1].push(0.0);
            back[2].push(0.0);
        }
        let mut beam = Beam {
            front,
            front_facet,
            back,
            parallel,
            half,
            cells: Vec::new(),
            candidates: Vec::new(),
        };
        // The grid.
        let step = 2.0 * half / GRID as f64;
        let corner = |i: usize| -half + i as f64 * step;
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); GRID * GRID];
        for (k, &f) in beam.front_facet[..n_front].iter().enumerate() {
            let (mut alo, mut ahi, mut blo, mut bhi) = (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            );
            for &vi in &s.facet_vertices[f] {
                let r = s.vertices[vi] - centre;
                let (a, b) = (r.dot(u), r.dot(v));
                alo = alo.min(a);
                ahi = ahi.max(a);
                blo = blo.min(b);
                bhi = bhi.max(b);
            }
            let pad = 1e-9 * (1.0 + half);
            let cell = |x: f64| (((x + half) / step).floor().max(0.0) as usize).min(GRID - 1);
            if ahi < -half - pad || alo > half + pad || bhi < -half - pad || blo > half + pad {
                continue;
            }
            for i in cell(alo - pad)..=cell(ahi + pad) {
                for j in cell(blo - pad)..=cell(bhi + pad) {
                    lists[i * GRID + j].push(k as u32);
                }
            }
        }
        let inside: Vec<bool> = (0..(GRID + 1) * (GRID + 1))
            .map(|c| {
                beam.entry_full(corner(c / (GRID + 1)), corner(c % (GRID + 1)))
                    .is_some()
            })
            .collect();
        for (c, list) in lists.iter().enumerate() {
            let (i, j) = (c / GRID, c % GRID);
            let corners = [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)];
            let start = beam.candidates.len();
            let cell = if list.is_empty() {
                MISS
            } else if corners.iter().all(|&(x, y)| inside[x * (GRID + 1) + y])
                && list.len() < 255
                && start + list.len() < 1 << 24
            {
                beam.candidates.extend_from_slice(list);
                start as u32 | (list.len() as u32) << 24
            } else {
                BORDER
            };
            beam.cells.push(cell);
        }
        beam
    }

    /// The entry facet of the photon at (a, b), or `None` if it misses.
    #[inline(always)]
    fn entry(&self, a: f64, b: f64) -> Option<usize> {
        let step = 2.0 * self.half / GRID as f64;
        let i = (((a + self.half) / step) as usize).min(GRID - 1);
        let j = (((b + self.half) / step) as usize).min(GRID - 1);
        match self.cells[i * GRID + j] {
            MISS => None,
            BORDER => self.entry_full(a, b),
            cell => {
                let (start, len) = ((cell & 0xFF_FFFF) as usize, (cell >> 24) as usize);
                let f = &self.front;
                let mut best = (f64::NEG_INFINITY, usize::MAX);
                for &k in &self.candidates[start..start + len] {
                    let k = k as usize;
                    let t = f[0][k] + a * f[1][k] + b * f[2][k];
                    if t > best.0 {
                        best = (t, k);
                    }
                }
                Some(self.front_facet[best.1])
            }
        }
    }

    /// The full entry test (every facet).
    #[inline(always)]
    fn entry_full(&self, a: f64, b: f64) -> Option<usize> {
        let mut tin = [f64::NEG_INFINITY; BL];
        let mut fin = [0usize; BL];
        let f = &self.front;
        for c in (0..f[0].len()).step_by(BL) {
            for l in 0..BL {
                let i = c + l;
                let t = f[0][i] + a * f[1][i] + b * f[2][i];
                if t > tin[l] {
                    tin[l] = t;
                    fin[l] = i;
                }
            }
        }
        let mut tout = [f64::INFINITY; BL];
        let k = &self.back;
        for c in (0..k[0].len()).step_by(BL) {
            for (l, o) in tout.iter_mut().enumerate() {
                let i = c + l;
                let t = k[0][i] + a * k[1][i] + b * k[2][i];
                *o = if t < *o { t } else { *o };
            }
        }
        let (mut t_in, mut f_in) = (tin[0], fin[0]);
        for l in 1..BL {
            if tin[l] > t_in || (tin[l] == t_in && fin[l] < f_in) {
                t_in = tin[l];
                f_in = fin[l];
            }
        }
        let t_out = tout.iter().copied().fold(f64::INFINITY, f64::min);
        if t_in > t_out
            || self
                .parallel
                .iter()
                .any(|g| g[0] - a * g[1] - b * g[2] < 0.0)
        {
            return None;
        }
        let facet = self.front_facet[f_in];
        (facet != usize::MAX).then_some(facet)
    }
}

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
    beam: Option<Beam>,
    /// Undirected lights: which photons surely miss, from their start and polar angle.
    reach: Option<Reach>,
    /// cos(k°) for k = 0..=180.
    cos_deg: Vec<f64>,
    /// For each cell of √(1 − z), the exit-angle bin at the cell's top (largest z), less 1e-9.
    angle_start: Vec<u8>,
    /// Weights of an exit direction, summed into [`Counts::weight_sum`].
    pub(crate) exit_weight: Option<&'a ExitWeights<'a>>,
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
        let cos_deg: Vec<f64> = (0..=180).map(|k| (k as f64).to_radians().cos()).collect();
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
            angle_start: (0..ANGLE_CELLS)
                .map(|c| {
                    let u = c as f64 / ANGLE_CELLS_PER_U;
                    let z = (1.0 - u * u + 1e-9).min(1.0);
                    cos_deg[1..180].partition_point(|&t| z <= t) as u8
                })
                .collect(),
            cos_deg,
            beam: (light.kind == LightKind::Directed)
                .then(|| Beam::new(s, centre, axis, u, v, half)),
            exit_weight: None,
        })
    }

    pub(crate) fn facet_count(&self) -> usize {
        self.s.facets
    }

    /// Trace chunk `c` of `n` photons; with `hit_limit`, stop after that many hits.
    pub(crate) fn chunk(&self, c: u64, n: u64, hit_limit: Option<u64>) -> Counts {
        #[cfg(target_arch = "x86_64")]
        if self.s.avx2 {
            // SAFETY: AVX2 and FMA were detected at run time.
            return unsafe { self.chunk_avx2(c, n, hit_limit) };
        }
        self.chunk_impl(c, n, hit_limit)
    }

    /// [`Tracer::chunk`] compiled for AVX2 (the same arithmetic: Rust never fuses or
    /// reorders floating-point operations on its own, so the numbers do not change).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn chunk_avx2(&self, c: u64, n: u64, hit_limit: Option<u64>) -> Counts {
        self.chunk_impl(c, n, hit_limit)
    }

    #[inline(always)]
    fn chunk_impl(&self, c: u64, n: u64, hit_limit: Option<u64>) -> Counts {
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

    /// The exit-angle bin of a direction with z component `z`: bin k holds angles in
    /// [k°, k+1°), so the bin is the count of thresholds cos(k°), k = 1..179, that z does not
    /// exceed. The table gives a count no larger than that for z's cell of √(1 − z)
    /// (near-linear in the angle); a step or two finishes it.
    #[inline(always)]
    fn angle_bin(&self, z: f64) -> usize {
        let u = (1.0 - z).max(0.0).sqrt() * ANGLE_CELLS_PER_U;
        let mut bin = self.angle_start[(u as usize).min(ANGLE_CELLS - 1)] as usize;
        while bin < 179 && z <= self.cos_deg[bin + 1] {
            bin += 1;
        }
        bin
    }

    #[inline(always)]
    fn tally_exit(&self, k: &mut Counts, facet: usize, d: DVec3) {
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
        let a = (2.0 * rng.random::<f64>() - 1.0) * self.half;
        let b = (2.0 * rng.random::<f64>() - 1.0) * self.half;
        let o = self.centre + self.u * a + self.v * b;
        let mut d = match self.kind {
            LightKind::Directed => self.axis,
            LightKind::Undirected => {
                let c = rng.random::<f64>();
                let phi = std::f64::consts::TAU * rng.random::<f64>();
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
        let (t, f) = match &self.beam {
            Some(beam) => {
                let f = beam.entry(a, b)?;
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
        k.hit += 1;
        let lambda = self.wavelength(rng);
        let n = self.fixed_n.unwrap_or_else(|| self.material.ri(lambda));
        // Beer–Lambert coefficient per unit of path at this photon's wavelength (0 unless the
        // model is Beer–Lambert).
        let beer = self
            .absorption
            .beer_per_width(self.material.colour.as_ref(), lambda)
            .unwrap_or(0.0);
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
                    Absorption::Beer(_) | Absorption::Body { .. } => {
                        let u: f64 = rng.random();
                        let s = -(1.0 - u).ln() / beer;
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

#[cfg(test)]
mod tests {
    use super::*;

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
            let beam = tr.beam.as_ref().unwrap();
            let mut rng = SmallRng::seed_from_u64(5);
            let (mut hits, mut differ) = (0, 0);
            for _ in 0..20_000 {
                let a = (2.0 * rng.random::<f64>() - 1.0) * tr.half;
                let b = (2.0 * rng.random::<f64>() - 1.0) * tr.half;
                let o = tr.centre + tr.u * a + tr.v * b;
                let fast = beam.entry(a, b);
                let general = s.entry(o, tr.axis).map(|(_, f)| f);
                hits += general.is_some() as u32;
                differ += (fast != general) as u32;
            }
            assert!(hits > 5_000, "{}", light.label);
            assert_eq!(differ, 0, "{}", light.label);
        }
    }
}
