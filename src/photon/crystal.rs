//! Birefringent stones in the photon tracer: the same roulette as the singly refractive
//! kernel, over the outcomes the exact boundary conditions of a uniaxial crystal give
//! ([`crate::optics::crystal`]): at entry, reflection or refraction into the ordinary or the
//! extraordinary wave; at every facet met from inside, leaving, or reflection into either
//! mode. A photon inside is in one mode and moves along its ray (Poynting) direction; with
//! body colour it is absorbed at its mode's rate along that ray (pleochroism). It is chosen
//! once per chunk: the singly refractive kernel is not touched.

use super::crystal_setup::CrystalSetup;
use super::kernel::{chunk_seed, end_path, two_uniforms, Tracer};
use super::tally::{Counts, Fate, PhotonPath};
use crate::geometry::DVec3;
use crate::optics::crystal::{Crystal, Wave};
use crate::optics::Absorption;
use crate::optics::Stokes;
use rand::rngs::SmallRng;
use rand::SeedableRng;

/// One lane of a birefringent chunk (see the singly refractive kernel's `Lane`).
struct Lane {
    rng: SmallRng,
    left: u64,
    live: bool,
    p: DVec3,
    wave: Wave,
    crystal: Crystal,
    /// Absorption per girdle diameter for E ⊥ ĉ and E ∥ ĉ at the photon's wavelength
    /// (body colour), and along the current wave's ray.
    alpha: (f64, f64),
    beer: f64,
    lambda: f64,
    inter: u32,
    path: Vec<DVec3>,
}

impl Tracer<'_> {
    /// [`Tracer::lanes`](super::kernel) for a birefringent stone (the tracer's crystal; none:
    /// nothing is traced): chunk `c`'s `n` photons, the lanes seeded as there.
    pub(crate) fn lanes_crystal<const REC: bool>(
        &self,
        c: u64,
        n: u64,
        hit_limit: Option<u64>,
        k: &mut Counts,
        out: &mut Vec<PhotonPath>,
        want: usize,
    ) {
        const LANES: usize = super::solid::LANES;
        let Some(cs) = self.crystal.as_ref() else {
            return;
        };
        let limit = hit_limit.unwrap_or(u64::MAX);
        let base = chunk_seed(self.seed, c);
        let blank = Crystal::new(1.5, 1.5, DVec3::Z);
        let mut lanes: [Lane; LANES] = std::array::from_fn(|l| {
            let l = l as u64;
            Lane {
                rng: SmallRng::seed_from_u64(chunk_seed(base, l)),
                left: n / LANES as u64 + u64::from(l < n % LANES as u64),
                live: false,
                p: DVec3::ZERO,
                wave: blank.wave_along(DVec3::Z, crate::optics::crystal::WaveMode::Ordinary),
                crystal: blank,
                alpha: (0.0, 0.0),
                beer: 0.0,
                lambda: 0.0,
                inter: 0,
                path: Vec::new(),
            }
        });
        loop {
            for l in lanes.iter_mut() {
                while !l.live && l.left > 0 {
                    self.start_crystal::<REC>(cs, l, k, limit, out);
                }
            }
            let live = lanes.each_ref().map(|l| l.live);
            if !live.contains(&true) || (REC && out.len() >= want) {
                break;
            }
            let exits = self.s.exits_by(|l| (lanes[l].p, lanes[l].wave.ray), &live);
            for (l, &(t, j)) in lanes.iter_mut().zip(&exits) {
                if l.live {
                    self.bounce_crystal::<REC>(l, t, j, k, out);
                }
            }
        }
    }

    /// Absorption per girdle diameter along `wave` (0 without Beer–Lambert absorption).
    #[inline(always)]
    fn mode_beer(&self, l: &Lane, wave: &Wave) -> f64 {
        match self.absorption {
            Absorption::Beer(k) => k,
            Absorption::Body { .. } => l.crystal.absorption(wave, l.alpha.0, l.alpha.1),
            Absorption::None | Absorption::Thesis => 0.0,
        }
    }

    /// Shoot the lane's next photons until one enters (see the singly refractive `start`).
    fn start_crystal<const REC: bool>(
        &self,
        cs: &CrystalSetup,
        l: &mut Lane,
        k: &mut Counts,
        limit: u64,
        out: &mut Vec<PhotonPath>,
    ) {
        let Some(e) = self.next_entry(&mut l.rng, &mut l.left, k, limit) else {
            return;
        };
        let (o, d, t, f, lambda, x) = (e.o, e.d, e.t, e.f, e.lambda, e.x);
        l.lambda = lambda;
        let (n_o, n_e) = match self.fixed_n {
            Some(n) => (
                n,
                n + (cs.extraordinary.at(lambda) - cs.ordinary.at(lambda)),
            ),
            None => (cs.ordinary.at(lambda), cs.extraordinary.at(lambda)),
        };
        l.crystal = Crystal::new(n_o, n_e, cs.axis);
        l.alpha = match self.absorption {
            Absorption::Body { width_mm } => (
                cs.colour_o.as_ref().map_or(0.0, |c| c.alpha(lambda)) * width_mm,
                cs.colour_e.as_ref().map_or(0.0, |c| c.alpha(lambda)) * width_mm,
            ),
            _ => (0.0, 0.0),
        };
        l.p = o + t * d;
        if REC {
            l.path.clear();
            l.path.push(o);
            l.path.push(l.p);
        }
        l.inter = 1;
        let m = self.s.normals[f];
        let unpolarized = Stokes::new(1.0, 0.0, 0.0, 0.0);
        let Some(e) = l
            .crystal
            .enter(d, m, unpolarized, d.any_orthonormal_vector())
        else {
            // Grazing: reflected.
            self.exit_crystal::<REC>(l, k, f, d - 2.0 * d.dot(m) * m, None, out);
            return;
        };
        let total = e.reflected.x + e.transmitted[0].1 + e.transmitted[1].1;
        let x = x * total;
        if x < e.reflected.x {
            self.exit_crystal::<REC>(l, k, f, e.reflected_dir, None, out);
            return;
        }
        let m = usize::from(x >= e.reflected.x + e.transmitted[0].1);
        l.wave = e.transmitted[m].0;
        let wave = l.wave;
        l.beer = self.mode_beer(l, &wave);
        if l.inter >= self.max_depth {
            k.depth_limited += 1;
            self.finish_crystal::<REC>(l, k, Fate::DepthLimited, out);
        } else {
            l.live = true;
        }
    }

    /// The lane's photon meets its next facet `j` at distance `t` (see the singly refractive
    /// `bounce`).
    fn bounce_crystal<const REC: bool>(
        &self,
        l: &mut Lane,
        t: f64,
        j: usize,
        k: &mut Counts,
        out: &mut Vec<PhotonPath>,
    ) {
        let d = l.wave.ray;
        if t >= f64::INFINITY || t.is_nan() {
            k.depth_limited += 1;
            return self.finish_crystal::<REC>(l, k, Fate::DepthLimited, out);
        }
        let (u, x) = two_uniforms(&mut l.rng);
        if let Some(s) = self.absorbed_within(u, t, l.beer) {
            k.absorbed += 1;
            if REC {
                l.path.push(l.p + s * d);
            }
            return self.finish_crystal::<REC>(l, k, Fate::Absorbed, out);
        }
        l.p += t * d;
        l.inter += 1;
        if REC {
            l.path.push(l.p);
        }
        let m = self.s.normals[j];
        let Some(meet) = l.crystal.meet(&l.wave, m) else {
            // Grazing: nothing leaves; kept in its mode, mirrored.
            k.depth_limited += 1;
            return self.finish_crystal::<REC>(l, k, Fate::DepthLimited, out);
        };
        let (ro, re) = (meet.reflected[0].1, meet.reflected[1].1);
        let x = x * (ro + re + meet.exit_power);
        if x < meet.exit_power {
            let mode = l.wave.mode;
            self.exit_crystal::<REC>(l, k, j, meet.exit_dir, Some(mode.index()), out);
            return;
        }
        let m = usize::from(x >= meet.exit_power + ro);
        l.wave = meet.reflected[m].0;
        let wave = l.wave;
        l.beer = self.mode_beer(l, &wave);
        if l.inter >= self.max_depth {
            k.depth_limited += 1;
            self.finish_crystal::<REC>(l, k, Fate::DepthLimited, out);
        }
    }

    /// The lane's photon leaves through facet `f` along `dir`, from mode `mode` (`None` for
    /// an external reflection).
    fn exit_crystal<const REC: bool>(
        &self,
        l: &mut Lane,
        k: &mut Counts,
        f: usize,
        dir: DVec3,
        mode: Option<usize>,
        out: &mut Vec<PhotonPath>,
    ) {
        self.tally_exit(k, f, dir);
        if let Some(m) = mode {
            k.mode_exits[m] += 1;
            k.mode_return[m] += u64::from(dir.z > 0.0);
        }
        if REC {
            l.path.push(l.p + dir);
        }
        self.finish_crystal::<REC>(l, k, Fate::Exited(f), out);
    }

    fn finish_crystal<const REC: bool>(
        &self,
        l: &mut Lane,
        k: &mut Counts,
        fate: Fate,
        out: &mut Vec<PhotonPath>,
    ) {
        l.live = false;
        end_path::<REC>(k, l.inter, l.lambda, &mut l.path, fate, out);
    }
}
