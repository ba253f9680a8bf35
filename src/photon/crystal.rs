//! Birefringent stones in the photon tracer: the same roulette as the singly refractive
//! kernel, over the outcomes the exact boundary conditions of a uniaxial crystal give
//! ([`crate::optics::crystal`]): at entry, reflection or refraction into the ordinary or the
//! extraordinary wave; at every facet met from inside, leaving, or reflection into either
//! mode. A photon inside is in one mode and moves along its ray (Poynting) direction; with
//! body colour it is absorbed at its mode's rate along that ray (pleochroism). It is chosen
//! once per chunk: the singly refractive kernel is not touched. The lanes, a photon's start,
//! its way to the next facet and its end are the kernel's (`kernel.rs`).

use super::crystal_setup::CrystalSetup;
use super::kernel::Tracer;
use super::lanes::{Kernel, Lane};
use super::tally::{Counts, Fate, PhotonPath};
use crate::geometry::DVec3;
use crate::optics::crystal::{Crystal, Wave, WaveMode};
use crate::optics::Absorption;
use crate::optics::Stokes;

/// The birefringent kernel, of the tracer's crystal.
pub(super) struct Birefringent<'a>(pub(super) &'a CrystalSetup);

/// A birefringent photon's own: its mode's wave, the crystal at its wavelength and the
/// absorption per girdle diameter for E ⊥ ĉ and E ∥ ĉ there (body colour).
pub(super) struct InMode {
    wave: Wave,
    crystal: Crystal,
    alpha: (f64, f64),
}

impl Birefringent<'_> {
    /// Absorption per girdle diameter along `wave` (0 without Beer–Lambert absorption).
    #[inline(always)]
    fn mode_beer(tr: &Tracer<'_>, own: &InMode, wave: &Wave) -> f64 {
        match tr.absorption {
            Absorption::Beer(k) => k,
            Absorption::Body { .. } => own.crystal.absorption(wave, own.alpha.0, own.alpha.1),
            Absorption::None | Absorption::Thesis => 0.0,
        }
    }

    /// The lane's photon leaves through facet `f` along `dir`, from mode `mode` (`None` for
    /// an external reflection).
    #[inline(always)]
    fn exit<const REC: bool>(
        tr: &Tracer<'_>,
        l: &mut Lane<InMode>,
        k: &mut Counts,
        f: usize,
        dir: DVec3,
        mode: Option<usize>,
        out: &mut Vec<PhotonPath>,
    ) {
        if let Some(m) = mode {
            k.mode_exits[m] += 1;
            k.mode_return[m] += u64::from(dir.z > 0.0);
        }
        tr.exit::<InMode, REC>(l, k, f, dir, out);
    }
}

impl Kernel for Birefringent<'_> {
    type Own = InMode;

    fn blank(&self) -> InMode {
        let blank = Crystal::new(1.5, 1.5, DVec3::Z);
        InMode {
            wave: blank.wave_along(DVec3::Z, WaveMode::Ordinary),
            crystal: blank,
            alpha: (0.0, 0.0),
        }
    }

    #[inline(always)]
    fn dir(own: &InMode) -> DVec3 {
        own.wave.ray
    }

    fn start<const REC: bool>(
        &self,
        tr: &Tracer<'_>,
        l: &mut Lane<InMode>,
        k: &mut Counts,
        limit: u64,
        out: &mut Vec<PhotonPath>,
    ) {
        let cs = self.0;
        let Some(e) = tr.enter::<InMode, REC>(l, k, limit) else {
            return;
        };
        let (d, f, lambda) = (e.d, e.f, e.lambda);
        let (n_o, n_e) = match tr.fixed_n {
            Some(n) => (
                n,
                n + (cs.extraordinary.at(lambda) - cs.ordinary.at(lambda)),
            ),
            None => (cs.ordinary.at(lambda), cs.extraordinary.at(lambda)),
        };
        l.own.crystal = Crystal::new(n_o, n_e, cs.axis);
        l.own.alpha = match tr.absorption {
            Absorption::Body { width_mm } => (
                cs.colour_o.as_ref().map_or(0.0, |c| c.alpha(lambda)) * width_mm,
                cs.colour_e.as_ref().map_or(0.0, |c| c.alpha(lambda)) * width_mm,
            ),
            _ => (0.0, 0.0),
        };
        let m = tr.s.normals[f];
        let unpolarized = Stokes::new(1.0, 0.0, 0.0, 0.0);
        let Some(entry) = l
            .own
            .crystal
            .enter(d, m, unpolarized, d.any_orthonormal_vector())
        else {
            // Grazing: reflected.
            return Self::exit::<REC>(tr, l, k, f, d - 2.0 * d.dot(m) * m, None, out);
        };
        let total = entry.reflected.x + entry.transmitted[0].1 + entry.transmitted[1].1;
        let x = e.x * total;
        if x < entry.reflected.x {
            return Self::exit::<REC>(tr, l, k, f, entry.reflected_dir, None, out);
        }
        let m = usize::from(x >= entry.reflected.x + entry.transmitted[0].1);
        l.own.wave = entry.transmitted[m].0;
        l.beer = Self::mode_beer(tr, &l.own, &l.own.wave);
        if !tr.depth_limited::<InMode, REC>(l, k, out) {
            l.live = true;
        }
    }

    fn bounce<const REC: bool>(
        &self,
        tr: &Tracer<'_>,
        l: &mut Lane<InMode>,
        t: f64,
        j: usize,
        k: &mut Counts,
        out: &mut Vec<PhotonPath>,
    ) {
        let d = l.own.wave.ray;
        let Some(x) = tr.advance::<InMode, REC>(l, t, d, k, out) else {
            return;
        };
        let m = tr.s.normals[j];
        let Some(meet) = l.own.crystal.meet(&l.own.wave, m) else {
            // Grazing: nothing leaves; kept in its mode, mirrored.
            k.depth_limited += 1;
            return tr.finish::<InMode, REC>(l, k, Fate::DepthLimited, out);
        };
        let (ro, re) = (meet.reflected[0].1, meet.reflected[1].1);
        let x = x * (ro + re + meet.exit_power);
        if x < meet.exit_power {
            let mode = l.own.wave.mode;
            return Self::exit::<REC>(tr, l, k, j, meet.exit_dir, Some(mode.index()), out);
        }
        let m = usize::from(x >= meet.exit_power + ro);
        l.own.wave = meet.reflected[m].0;
        l.beer = Self::mode_beer(tr, &l.own, &l.own.wave);
        tr.depth_limited::<InMode, REC>(l, k, out);
    }
}
