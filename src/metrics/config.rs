//! What to score and how: [`ScoreConfig`] with its defaults, the quick configuration for
//! searches and the validation of every field, and [`Parts`] (which of the costlier scores to
//! compute).

use crate::beam::TraceOptions;
use crate::error::{shown, Error, Result};
use crate::optics::{Material, StoneSize};
use crate::render::lighting::Spot;
use crate::render::Tilt;

/// Wavelength of the single-wavelength scores: the sodium D line, nm.
pub const REFERENCE_WAVELENGTH_NM: f64 = 589.3;

/// Default half-angle of the viewer's head shadow around the zenith, degrees: the scores
/// count light as a person looking at the stone sees it, with their head blocking the sky
/// within 15° of their line of sight (GemRay's COS pictures and faceters' renders use the
/// same). Without it the scores reward light from straight overhead, where the viewer's head
/// is: a quartz brilliant optimized with no head shadow climbed from brilliance 0.59 to 0.72
/// while its face-up return under a 15° head shadow fell from 22.8 % to 8.1 % (ASET port
/// 7.6 % → 72.8 %), a stone that looks nearly black. 0 gives the open-sky scores.
pub const DEFAULT_HEAD_SHADOW_DEG: f64 = 15.0;

/// A named scoring setting, the one list of them: `[score] setting` in an optimization's
/// config names one ([`ScoreSetting::from_name`]), and [`ScoreSetting::config`] is its
/// configuration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ScoreSetting {
    /// [`ScoreConfig::default`]: the scores as reported everywhere.
    #[default]
    Default,
    /// [`ScoreConfig::smooth`]: the same scores traced finer, smooth on a 0.002° scale.
    Smooth,
}

impl ScoreSetting {
    /// Every setting, in the order of the enum.
    pub const ALL: &'static [ScoreSetting] = &[ScoreSetting::Default, ScoreSetting::Smooth];

    /// Its name, as a config writes it.
    pub const fn name(self) -> &'static str {
        match self {
            ScoreSetting::Default => "default",
            ScoreSetting::Smooth => "smooth",
        }
    }

    /// The setting named `name` ([`ScoreSetting::name`]).
    pub fn from_name(name: &str) -> Option<ScoreSetting> {
        ScoreSetting::ALL.iter().copied().find(|s| s.name() == name)
    }

    /// Its configuration.
    pub fn config(self) -> ScoreConfig {
        match self {
            ScoreSetting::Default => ScoreConfig::default(),
            ScoreSetting::Smooth => ScoreConfig::smooth(),
        }
    }
}

/// What to score and how.
#[derive(Clone, Debug, PartialEq)]
pub struct ScoreConfig {
    /// The stone's material (a constant index gives no dispersion and no fire), with its
    /// body colour if it has one ([`Material::colour`]; not yet used by the tracers).
    pub material: Material,
    /// The stone's size, for body colour (absorption depends on the path in mm): its width,
    /// or its length (the width following from the cut's L/W). Default a width of
    /// [`StoneSize::DEFAULT_WIDTH_MM`] mm. A colourless stone's scores do not depend on it.
    pub size: StoneSize,
    /// Wavelength of the single-wavelength scores (light return, brilliance, ASET,
    /// scintillation), nm. Default 589.3.
    pub wavelength_nm: f64,
    /// Half-angle of the viewer's head shadow around the zenith, degrees; 0 = none. Default
    /// [`DEFAULT_HEAD_SHADOW_DEG`] (15°). It darkens every light the scores use (the ISO and
    /// COS skies of brilliance, the spot lights of fire and scintillation), as the viewer's
    /// head does; not the ASET shares (their port is the ASET viewer's own) nor overhead
    /// light return.
    pub head_shadow_deg: f64,
    /// Poses averaged for brilliance. Default [`Tilt::default_set`].
    pub tilts: Vec<Tilt>,
    /// Spot lights for fire and scintillation. Default [`Spot::default_set`].
    pub spots: Vec<Spot>,
    /// Wavelength bands for fire (equal bands across 380–780 nm; faint ones share a
    /// neighbour's trace, [`color::traced_bands`]). Default 8.
    ///
    /// [`color::traced_bands`]: crate::optics::color::traced_bands
    pub bands: usize,
    /// Rocking sequence for scintillation: tilts toward each of the
    /// [`ScoreConfig::scintillation_turns`] azimuths, degrees, in order (consecutive images
    /// are compared; a tilt of 0 is the face-up trace, shared). Default 0°, 3°.
    pub scintillation_tilts: Vec<f64>,
    /// Number of evenly spaced azimuths toward which scintillation rocks the stone
    /// ([`scintillation_turns`]), the spot lights turning with it. Default 5.
    ///
    /// [`scintillation_turns`]: super::scintillation_turns
    pub scintillation_turns: usize,
    /// Pixels per side of the fire and scintillation images. Default 64.
    pub resolution: usize,
    /// Placements of the spot lights that fire is averaged over ([`fire_placements`]).
    /// Default 17.
    ///
    /// [`fire_placements`]: super::fire_placements
    pub fire_placements: usize,
    /// Tracer settings, polarization among them (default on; footprints are switched on where
    /// needed). The split threshold is the
    /// tilted poses'; the ray floor ([`ScoreConfig::RAY_FLOOR`] by default) applies to every
    /// trace but the face-up one at the reference wavelength, and the power it stops is handed
    /// back with the narrow exits' mean (brilliance, not the pictures).
    pub trace: TraceOptions,
    /// Split threshold of the face-up traces (fire's bands, and at most this for the face-up
    /// trace at the reference wavelength; see [`TraceOptions::split_threshold`]): fire's spot
    /// images are the most sensitive to the narrow-beam approximation, and face-up traces of
    /// symmetric stones are cheap. Default 3e-6 (see the [module documentation](super) on
    /// fire).
    pub fire_split_threshold: f64,
    /// Split threshold of the face-up trace at the reference wavelength: overhead light
    /// return, ASET, and the face-up pose of brilliance and of scintillation. Default 1e-6,
    /// which puts overhead light return within 0.01 percentage points of the exact reference
    /// (`cargo bench --bench exact`; at 1e-5 it is off by up to 0.035 points, at 1e-4 by up
    /// to 0.23). A face-up trace covers one symmetry wedge, so this fine trace is cheap.
    pub face_up_split_threshold: f64,
    /// Which of the costlier scores to compute (default: all). One left out is NaN in
    /// [`Scores`]. The optimizer leaves out what its objective does not weigh while it
    /// searches, and scores the cuts it reports in full.
    ///
    /// [`Scores`]: super::Scores
    pub parts: Parts,
}

/// Which of fire and scintillation [`score`] computes (brilliance, overhead light return and
/// ASET always are: they share the traces brilliance needs). Fire takes about half of a
/// default score's time (its eight face-up traces: 62 of 127 ms on one thread for tolkowsky),
/// scintillation about a tenth (14 ms).
///
/// [`score`]: super::score
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parts {
    /// Compute fire.
    pub fire: bool,
    /// Compute scintillation.
    pub scintillation: bool,
}

impl Default for Parts {
    fn default() -> Self {
        Parts {
            fire: true,
            scintillation: true,
        }
    }
}

impl Default for ScoreConfig {
    fn default() -> Self {
        ScoreConfig {
            material: Material::diamond(),
            size: StoneSize::default(),
            wavelength_nm: REFERENCE_WAVELENGTH_NM,
            head_shadow_deg: DEFAULT_HEAD_SHADOW_DEG,
            tilts: Tilt::default_set(),
            spots: Spot::default_set(),
            bands: 8,
            scintillation_tilts: vec![0.0, 3.0],
            scintillation_turns: 5,
            resolution: 64,
            fire_placements: 17,
            trace: TraceOptions {
                ray_floor: Self::RAY_FLOOR,
                ..TraceOptions::default()
            },
            fire_split_threshold: 3e-6,
            face_up_split_threshold: 1e-6,
            parts: Parts::default(),
        }
    }
}

impl ScoreConfig {
    /// This configuration with polarization tracked (`true`, the default) or not: the trace
    /// settings' own switch ([`TraceOptions::polarization`]), the one home of that setting.
    pub fn polarized(mut self, on: bool) -> ScoreConfig {
        self.trace.polarization = on;
        self
    }

    /// Default [`TraceOptions::ray_floor`] of the scores' traces. Measured on 30 tilted poses
    /// of six presets against traces split down to 1e-6: the ISO light return errs by 4.71e-4
    /// on average (4.84e-4 without a floor) while the rays need 0.48 of their segments; the
    /// default brilliance of tolkowsky, princess and oval is within 7e-5 of the same scores
    /// split down to 2e-6 (within 1.3e-4 without a floor). A default score of tolkowsky takes
    /// 0.67 of its time (CPU time, one thread), brilliance alone 0.65.
    pub const RAY_FLOOR: f64 = 0.05;

    /// A strongly birefringent stone's tilted poses split narrow beams finer, by
    /// `MODE_SPLIT_BIREFRINGENCE / Δn` where its birefringence `Δn = |ε − ω|` (at the reference
    /// wavelength) is above this, so that beams too narrow to split are as rare as the
    /// birefringence is strong ([`ScoreConfig::tilted_split`]). A narrow beam's ray carries its
    /// two reflected modes along the stronger one ([`TraceOptions::mode_floor`]), an error
    /// that grows with the angle between the modes, i.e. with Δn; weakly birefringent stones
    /// (sapphire, quartz, beryl: Δn ≤ 0.009) are traced as before, tourmaline (0.020) split
    /// twice as finely, zircon (0.059) and moissanite (0.053) about 5.5×. Measured with `score
    /// tolkowsky --verify 300000` (brilliance, beam − photon in standard errors of 0.0002):
    /// moissanite +4.06 (optic axis 0) and +4.56 (90) at the shared split, +0.47 and +2.60
    /// split 5× finer (2e-5), +2.75 and +4.32 at 2× (5e-5). The other remedies measured do
    /// worse: rays that split their modes (mode floor 0.3, 0.1) +4.9 to +7.9 se, every mode
    /// followed down to the power threshold −53 and −60 se (the tree doubles at every facet
    /// and falls below it), no ray floor +3.3 and +4.1. The finer split costs a moissanite
    /// score 1.9× its CPU time.
    pub const MODE_SPLIT_BIREFRINGENCE: f64 = 0.01;

    /// The split threshold of the tilted poses' traces (brilliance, scintillation):
    /// [`TraceOptions::split_threshold`], finer for a strongly birefringent stone (see
    /// [`ScoreConfig::MODE_SPLIT_BIREFRINGENCE`]).
    pub fn tilted_split(&self) -> f64 {
        let split = self.trace.split_threshold;
        if !self.material.birefringent() {
            return split;
        }
        let l = self.wavelength_nm;
        let dn = (self.material.ri_e(l) - self.material.ri(l)).abs();
        if dn > Self::MODE_SPLIT_BIREFRINGENCE {
            split * Self::MODE_SPLIT_BIREFRINGENCE / dn
        } else {
            split
        }
    }

    /// A quicker configuration for searches: narrow beams from 1e-3 of the light, 6 bands,
    /// face-up plus five poses at 15°, rocking toward three azimuths, seven placements of the
    /// spot lights for fire, 48 pixels. Brilliance stays within
    /// about 1e-3 of the default configuration; fire and scintillation are much coarser
    /// (tens of percent).
    pub fn fast() -> ScoreConfig {
        ScoreConfig {
            tilts: std::iter::once(Tilt::FACE_UP)
                .chain((0..5).map(|k| Tilt {
                    tilt_deg: 15.0,
                    azimuth_deg: 72.0 * k as f64,
                }))
                .collect(),
            bands: 6,
            scintillation_tilts: vec![0.0, 3.0],
            scintillation_turns: 3,
            resolution: 48,
            fire_placements: 7,
            trace: TraceOptions {
                split_threshold: 1e-3,
                ray_floor: Self::RAY_FLOOR,
                ..TraceOptions::default()
            },
            fire_split_threshold: 1e-4,
            face_up_split_threshold: 1e-4,
            ..ScoreConfig::default()
        }
    }

    /// The smooth setting ([`ScoreSetting::Smooth`]): the default configuration with the
    /// tilted poses split down to [`ScoreConfig::SMOOTH_SPLIT`], fire's face-up traces to
    /// [`ScoreConfig::SMOOTH_FIRE_SPLIT`] and fire traced at [`ScoreConfig::SMOOTH_BANDS`]
    /// wavelength bands, so that brilliance and fire are smooth on the 0.002° scale of
    /// `cargo bench --bench profile` (fine-scale excess of brilliance 0.008 and of fire 0.297,
    /// against 0.352 and 0.847 at the default, 2026-12-06) for about 5.8 times the default's
    /// instructions per cut (cachegrind). For 1-D profiles, maps and the final polish of an optimization; the
    /// numbers are the default's refined, not another score: on those cuts brilliance moves by
    /// at most 4.3e-4 and fire by at most 0.011 (on average +0.003, fire converging from below
    /// as its bands multiply) (see the [module documentation](super) on smoothness).
    pub fn smooth() -> ScoreConfig {
        let d = ScoreConfig::default();
        ScoreConfig {
            trace: TraceOptions {
                split_threshold: Self::SMOOTH_SPLIT,
                ..d.trace
            },
            fire_split_threshold: Self::SMOOTH_FIRE_SPLIT,
            bands: Self::SMOOTH_BANDS,
            ..d
        }
    }

    /// Split threshold of the tilted poses' traces in [`ScoreConfig::smooth`].
    pub const SMOOTH_SPLIT: f64 = 1e-5;
    /// Split threshold of fire's face-up traces in [`ScoreConfig::smooth`].
    pub const SMOOTH_FIRE_SPLIT: f64 = 3e-7;
    /// Fire's wavelength bands in [`ScoreConfig::smooth`]: with the default 8, each of a
    /// dispersed fan's eight beams crosses a spot light's rim on its own, and that sampling of
    /// the spectrum, not the splitting, is most of fire's fine-scale roughness once its traces
    /// are split finely.
    pub const SMOOTH_BANDS: usize = 32;

    /// Check every field; the error names the field and what is allowed.
    pub fn validate(&self) -> Result<()> {
        let w = self.wavelength_nm;
        if !(380.0..=780.0).contains(&w) {
            return Err(Error::invalid(
                "wavelength",
                format!(
                    "{} nm is outside the visible range; allowed [380, 780] nm",
                    shown(w)
                ),
            ));
        }
        for (what, l) in [("wavelength", w), ("bands", 380.0), ("bands", 780.0)] {
            let n = self.material.ri(l);
            if !(n.is_finite() && n > 1.0 && n <= 10.0) {
                return Err(Error::invalid(
                    what,
                    format!(
                        "material {} has refractive index {n} at {l} nm; allowed (1, 10]",
                        self.material.name
                    ),
                ));
            }
        }
        let h = self.head_shadow_deg;
        if !(0.0..=60.0).contains(&h) {
            return Err(Error::invalid(
                "head-shadow",
                format!(
                    "{}° is out of range; allowed [0, 60] degrees (0 = no head shadow)",
                    shown(h)
                ),
            ));
        }
        if self.tilts.is_empty() {
            return Err(Error::invalid("tilts", "at least one pose is needed"));
        }
        for t in &self.tilts {
            if !(t.tilt_deg.abs() <= 60.0 && t.azimuth_deg.is_finite()) {
                return Err(Error::invalid(
                    "tilts",
                    format!("{t:?}: tilts must be within ±60°"),
                ));
            }
        }
        for s in &self.spots {
            if !(s.elevation_deg.abs() <= 90.0
                && s.azimuth_deg.is_finite()
                && s.radius_deg > 0.0
                && s.radius_deg <= 45.0)
            {
                return Err(Error::invalid(
                    "spots",
                    format!("{s:?}: elevation within ±90°, radius in (0, 45]°"),
                ));
            }
        }
        if !(1..=64).contains(&self.bands) {
            return Err(Error::invalid(
                "bands",
                format!("{} is out of range; allowed 1 to 64", self.bands),
            ));
        }
        if self.scintillation_tilts.len() < 2
            || self
                .scintillation_tilts
                .iter()
                .any(|t| t.is_nan() || t.abs() > 60.0)
        {
            return Err(Error::invalid(
                "scintillation-tilts",
                "at least two tilts, each within ±60°",
            ));
        }
        if !(1..=64).contains(&self.scintillation_turns) {
            return Err(Error::invalid(
                "scintillation-turns",
                format!(
                    "{} is out of range; allowed 1 to 64",
                    self.scintillation_turns
                ),
            ));
        }
        if !(1..=256).contains(&self.fire_placements) {
            return Err(Error::invalid(
                "fire-placements",
                format!("{} is out of range; allowed 1 to 256", self.fire_placements),
            ));
        }
        if !(8..=1024).contains(&self.resolution) {
            return Err(Error::invalid(
                "resolution",
                format!(
                    "{} is out of range; allowed 8 to 1024 pixels",
                    self.resolution
                ),
            ));
        }
        let t = &self.trace;
        if !(t.threshold >= 0.0
            && t.threshold < 1.0
            && self.fire_split_threshold >= 0.0
            && self.fire_split_threshold < 1.0
            && self.face_up_split_threshold >= 0.0
            && self.face_up_split_threshold < 1.0
            && t.split_threshold >= 0.0
            && t.split_threshold < 1.0
            && t.ray_floor >= 0.0
            && t.ray_floor < 1.0)
        {
            return Err(Error::invalid(
                "threshold",
                "power thresholds must be in [0, 1)",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::score;
    use crate::metrics::tests::lean;
    use crate::testkit::octahedron;

    #[test]
    fn config_validation_names_the_field() {
        assert!(ScoreConfig::default().validate().is_ok());
        assert!(ScoreConfig::fast().validate().is_ok());
        assert!(ScoreConfig::smooth().validate().is_ok());
        let bad = |c: ScoreConfig, field: &str| {
            let e = c.validate().unwrap_err().to_string();
            assert!(e.starts_with(field), "{e}");
        };
        bad(
            ScoreConfig {
                head_shadow_deg: -1.0,
                ..Default::default()
            },
            "head-shadow",
        );
        bad(
            ScoreConfig {
                head_shadow_deg: f64::NAN,
                ..Default::default()
            },
            "head-shadow",
        );
        bad(
            ScoreConfig {
                wavelength_nm: 1000.0,
                ..Default::default()
            },
            "wavelength",
        );
        bad(
            ScoreConfig {
                material: Material::constant(0.9),
                ..Default::default()
            },
            "wavelength",
        );
        bad(
            ScoreConfig {
                bands: 0,
                ..Default::default()
            },
            "bands",
        );
        bad(
            ScoreConfig {
                resolution: 2,
                ..Default::default()
            },
            "resolution",
        );
        bad(
            ScoreConfig {
                tilts: vec![],
                ..Default::default()
            },
            "tilts",
        );
        bad(
            ScoreConfig {
                scintillation_tilts: vec![0.0],
                ..Default::default()
            },
            "scintillation-tilts",
        );
        bad(
            ScoreConfig {
                scintillation_turns: 0,
                ..Default::default()
            },
            "scintillation-turns",
        );
        bad(
            ScoreConfig {
                fire_placements: 0,
                ..Default::default()
            },
            "fire-placements",
        );
    }

    /// The named settings map as documented: `default` is [`ScoreConfig::default`], `smooth`
    /// the default with only its splits and fire's bands refined; names read back.
    #[test]
    fn named_settings_map_as_documented() {
        for &s in ScoreSetting::ALL {
            assert_eq!(ScoreSetting::from_name(s.name()), Some(s));
        }
        assert_eq!(ScoreSetting::from_name("Smooth"), None);
        assert_eq!(ScoreSetting::default().config(), ScoreConfig::default());
        let (d, s) = (ScoreConfig::default(), ScoreSetting::Smooth.config());
        assert_eq!(s, ScoreConfig::smooth());
        assert!(s.trace.split_threshold < d.trace.split_threshold);
        assert!(s.fire_split_threshold < d.fire_split_threshold);
        assert!(s.bands > d.bands);
        let back = ScoreConfig {
            trace: d.trace,
            fire_split_threshold: d.fire_split_threshold,
            bands: d.bands,
            ..s
        };
        assert_eq!(back, d, "the smooth setting changes only splits and bands");
    }

    #[test]
    fn unvalidated_configs_no_panic_scores_stay_finite() {
        let s = octahedron();
        let weird = ScoreConfig {
            tilts: vec![],
            bands: 0,
            resolution: 0,
            scintillation_tilts: vec![f64::NAN],
            head_shadow_deg: f64::NAN,
            material: Material::constant(0.5),
            ..lean()
        };
        let sc = score(&s, &weird);
        assert!(sc.brilliance.is_finite() && sc.fire.is_finite());
    }
}
