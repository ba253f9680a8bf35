//! Optimization configs (`optim/*.toml`): parsed with unknown keys refused, then validated into
//! typed settings. Every error is one line naming the file and the field, e.g.
//! `round.toml: free.table: bounds [0.8, 0.5] are reversed; write [min, max]`.
//!
//! ```toml
//! name = "round-brilliance"          # run folder prefix; default: the file's stem
//! seed = 1                           # every random choice (start design, swarm) follows it
//!
//! [cut]
//! family = "round-brilliant"
//! [cut.params]                       # the start cut; missing keys take the family's defaults
//! girdle = 0.03
//!
//! [free]                             # what the optimizer varies: key = [min, max]
//! crown_angle = [30.0, 38.0]
//! pavilion_angle = [39.0, 42.5]
//!
//! [objective]                        # score = Σ weight · score; cost = −score + penalties
//! brilliance = 1.0
//!
//! [constraints]
//! total_depth = [0.56, 0.64]
//!
//! [method]
//! name = "nelder-mead"
//! starts = 4
//! max_evaluations = 400
//!
//! [verify]
//! winners = 3
//! photons = 100000
//! ```
//!
//! The full list of fields with their defaults is in `OPTIMIZE.md`.

use crate::cut::{family, Cut, Family, Unit};
use crate::error::{Error, Result};
use crate::io::{line_of, read_bytes};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// The config file as written (every field optional where a default exists).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawConfig {
    /// Run name (folder prefix); default: the file's stem.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Free text, copied to the report.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// Seed of every random choice; default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// The cut family and the start cut.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cut: Option<RawCut>,
    /// Free parameters: key = [min, max].
    #[serde(default)]
    pub free: BTreeMap<String, [f64; 2]>,
    /// Objective weights.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub objective: Option<RawObjective>,
    /// Constraints.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub constraints: Option<RawConstraints>,
    /// The search method and budgets.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub method: Option<RawMethod>,
    /// Verification of the winners.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub verify: Option<RawVerify>,
    /// How the cuts are scored (material, lighting).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub score: Option<RawScore>,
}

/// `[score]`: the scoring settings of the beam tracer (and of the photon-tracer checks).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScore {
    /// Material name (diamond, cubic-zirconia, sapphire, glass); default diamond.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// A fixed refractive index instead of a material (no dispersion, no fire).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ri: Option<f64>,
    /// Head-shadow half-angle in degrees, 0–60; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub head_shadow: Option<f64>,
    /// Track polarization; default true.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub polarization: Option<bool>,
}

/// Validated `[score]`.
#[derive(Clone, Debug, PartialEq)]
pub struct ScoreSettings {
    /// The material (from `material` or `ri`).
    pub material: crate::optics::Material,
    /// Whether `ri` was given (for writing the config back).
    pub ri: Option<f64>,
    /// Head-shadow half-angle, degrees.
    pub head_shadow_deg: f64,
    /// Track polarization.
    pub polarization: bool,
}

impl ScoreSettings {
    /// The beam tracer's scoring configuration for these settings.
    pub fn score_config(&self) -> crate::metrics::ScoreConfig {
        crate::metrics::ScoreConfig {
            material: self.material.clone(),
            head_shadow_deg: self.head_shadow_deg,
            polarization: self.polarization,
            ..crate::metrics::ScoreConfig::default()
        }
    }
}

/// `[cut]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCut {
    /// Family name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub family: Option<String>,
    /// Parameters of the start cut (fixed ones and the free ones' start values).
    #[serde(default)]
    pub params: BTreeMap<String, f64>,
}

/// `[objective]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawObjective {
    /// Weight of brilliance (default 1 when no weight is given at all, else 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub brilliance: Option<f64>,
    /// Weight of fire (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fire: Option<f64>,
    /// Weight of scintillation (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scintillation: Option<f64>,
}

/// `[constraints]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawConstraints {
    /// Allowed total depth, [min, max], fractions of the girdle diameter.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub total_depth: Option<[f64; 2]>,
    /// Smallest allowed crown height.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_crown_height: Option<f64>,
    /// Smallest allowed girdle thickness.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_girdle: Option<f64>,
    /// Smallest allowed weight retention from a round rough (volume / containing cylinder).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_weight_retention: Option<f64>,
    /// Cost added per percentage point (0.01) of violation; default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub penalty: Option<f64>,
}

/// `[method]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMethod {
    /// `nelder-mead` (default) or `particle-swarm`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Iteration budget: per start (Nelder–Mead) or of the swarm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_iterations: Option<u64>,
    /// Evaluation budget of the whole run (split evenly between Nelder–Mead starts).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_evaluations: Option<u64>,
    /// Nelder–Mead: number of starts.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub starts: Option<u64>,
    /// Nelder–Mead: `latin-hypercube` or `halton`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub design: Option<String>,
    /// Nelder–Mead: whether the first start is the configured start cut.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub include_start: Option<bool>,
    /// Nelder–Mead: initial simplex edge as a fraction of each parameter's range.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub simplex_step: Option<f64>,
    /// Nelder–Mead: a start ends when the standard deviation of its simplex's costs falls
    /// below this.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// Particle swarm: number of particles.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub particles: Option<u64>,
    /// Particle swarm: inertia weight.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<f64>,
    /// Particle swarm: pull toward each particle's own best.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cognitive: Option<f64>,
    /// Particle swarm: pull toward the swarm's best.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub social: Option<f64>,
}

/// `[verify]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawVerify {
    /// How many distinct winners to verify (0 = none); the start is verified too.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub winners: Option<u64>,
    /// Photons per verified cut and light.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub photons: Option<u64>,
    /// Smallest distance between two winners, in the unit box of the free parameters.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_distance: Option<f64>,
    /// Disagreement threshold in standard errors; default 4.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma: Option<f64>,
}

/// One free parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct FreeParam {
    /// Family parameter key.
    pub key: String,
    /// Lower bound.
    pub lo: f64,
    /// Upper bound.
    pub hi: f64,
    /// The start value (from `[cut.params]` or the family default).
    pub start: f64,
    /// Unit (for labels).
    pub unit: Unit,
}

impl FreeParam {
    /// Position of `x` in the box, 0 at `lo`, 1 at `hi`.
    pub fn unit_of(&self, x: f64) -> f64 {
        (x - self.lo) / (self.hi - self.lo)
    }
    /// The value at box position `f` (0 → `lo`, 1 → `hi`).
    pub fn at(&self, f: f64) -> f64 {
        self.lo + (self.hi - self.lo) * f
    }
    /// Axis label: the key with its unit.
    pub fn label(&self) -> String {
        axis_label(&self.key, self.unit)
    }
}

/// An axis label for a family parameter: `crown_angle (°)`, `table (× D)`.
pub fn axis_label(key: &str, unit: Unit) -> String {
    match unit {
        Unit::Degrees => format!("{key} (°)"),
        Unit::Fraction => format!("{key} (× girdle diameter)"),
        _ => key.to_string(),
    }
}

/// Objective weights: score = Σ weight · score.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Weights {
    /// Weight of brilliance.
    pub brilliance: f64,
    /// Weight of fire.
    pub fire: f64,
    /// Weight of scintillation.
    pub scintillation: f64,
}

/// Constraints; `None` = not constrained.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Constraints {
    /// Allowed total depth.
    pub total_depth: Option<[f64; 2]>,
    /// Smallest crown height.
    pub min_crown_height: Option<f64>,
    /// Smallest girdle thickness.
    pub min_girdle: Option<f64>,
    /// Smallest weight retention.
    pub min_weight_retention: Option<f64>,
    /// Cost per percentage point of violation.
    pub penalty: f64,
}

/// How Nelder–Mead starts are spread over the box.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Design {
    /// Seeded Latin hypercube: one start per row and column stratum.
    LatinHypercube,
    /// Seeded (randomly shifted) Halton sequence.
    Halton,
}

impl Design {
    /// Name in configs.
    pub fn name(self) -> &'static str {
        match self {
            Design::LatinHypercube => "latin-hypercube",
            Design::Halton => "halton",
        }
    }
}

/// Nelder–Mead settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct NelderMeadSettings {
    /// Number of starts.
    pub starts: usize,
    /// Start design.
    pub design: Design,
    /// Whether start 0 is the configured start cut.
    pub include_start: bool,
    /// Initial simplex edge as a fraction of each range.
    pub simplex_step: f64,
    /// Convergence: standard deviation of the simplex's costs.
    pub tolerance: f64,
}

/// Particle swarm settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SwarmSettings {
    /// Number of particles.
    pub particles: usize,
    /// Inertia weight.
    pub inertia: f64,
    /// Cognitive factor.
    pub cognitive: f64,
    /// Social factor.
    pub social: f64,
}

/// The search method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Multi-start Nelder–Mead in the sigmoid reparametrisation.
    NelderMead(NelderMeadSettings),
    /// argmin's particle swarm in the bounds.
    ParticleSwarm(SwarmSettings),
}

impl Method {
    /// Name in configs.
    pub fn name(&self) -> &'static str {
        match self {
            Method::NelderMead(_) => "nelder-mead",
            Method::ParticleSwarm(_) => "particle-swarm",
        }
    }
}

/// Iteration and evaluation budgets.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Budget {
    /// Iterations per start (Nelder–Mead) or of the swarm.
    pub max_iterations: u64,
    /// Evaluations of the whole run.
    pub max_evaluations: u64,
}

/// Verification settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct VerifySettings {
    /// Distinct winners to verify.
    pub winners: usize,
    /// Photons per cut and light.
    pub photons: u64,
    /// Smallest distance between winners in the unit box.
    pub min_distance: f64,
    /// Disagreement threshold in standard errors.
    pub sigma: f64,
}

/// A validated config.
#[derive(Clone, Debug)]
pub struct Config {
    /// Where it came from (file path, used in messages).
    pub source: String,
    /// Run name.
    pub name: String,
    /// Free text.
    pub description: Option<String>,
    /// Seed.
    pub seed: u64,
    /// The family.
    pub family: &'static Family,
    /// The start cut's full parameter set (defaults filled in).
    pub start: BTreeMap<String, f64>,
    /// `[cut.params]` as given.
    pub fixed: BTreeMap<String, f64>,
    /// Free parameters in the family's parameter order.
    pub free: Vec<FreeParam>,
    /// Objective weights.
    pub weights: Weights,
    /// Constraints.
    pub constraints: Constraints,
    /// Method.
    pub method: Method,
    /// Budgets.
    pub budget: Budget,
    /// Verification.
    pub verify: VerifySettings,
    /// Scoring settings.
    pub score: ScoreSettings,
}

/// Defaults (also documented in `OPTIMIZE.md`).
pub mod defaults {
    /// Seed.
    pub const SEED: u64 = 1;
    /// Penalty per percentage point of violation.
    pub const PENALTY: f64 = 1.0;
    /// Nelder–Mead starts.
    pub const STARTS: u64 = 4;
    /// Nelder–Mead iterations per start.
    pub const NM_MAX_ITERATIONS: u64 = 1000;
    /// Evaluation budget.
    pub const MAX_EVALUATIONS: u64 = 400;
    /// Simplex edge.
    pub const SIMPLEX_STEP: f64 = 0.15;
    /// Nelder–Mead convergence tolerance (standard deviation of the simplex's costs).
    pub const TOLERANCE: f64 = 1e-9;
    /// Particles.
    pub const PARTICLES: u64 = 16;
    /// Swarm iterations.
    pub const PSO_MAX_ITERATIONS: u64 = 25;
    /// Inertia (argmin's default, 1/(2 ln 2)).
    pub const INERTIA: f64 = 0.721_347_520_444_481_7;
    /// Cognitive and social factors (argmin's default, 1/2 + ln 2).
    pub const PULL: f64 = 1.193_147_180_559_945_3;
    /// Winners to verify.
    pub const WINNERS: u64 = 3;
    /// Photons per verified cut and light.
    pub const PHOTONS: u64 = 100_000;
    /// Distance between winners.
    pub const MIN_DISTANCE: f64 = 0.05;
    /// Disagreement threshold.
    pub const SIGMA: f64 = 4.0;
}

fn finite(field: &str, v: f64) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::invalid(field, format!("{v} is not a finite number")))
    }
}

impl Config {
    /// Read and validate a config file.
    pub fn load(path: &Path) -> Result<Config> {
        let bytes = read_bytes(path)?;
        let text = String::from_utf8(bytes).map_err(|_| {
            Error::parse(
                path.display().to_string(),
                "not UTF-8 text; a config is TOML",
            )
        })?;
        Config::from_str(&text, &path.display().to_string())
    }

    /// Parse and validate config text; `source` (the file name) prefixes errors.
    #[allow(clippy::should_implement_trait)]
    pub fn from_str(text: &str, source: &str) -> Result<Config> {
        let raw: RawConfig = toml::from_str(text).map_err(|e| {
            let line = e
                .span()
                .map(|s| format!(":{}", line_of(text, s.start)))
                .unwrap_or_default();
            Error::parse(format!("{source}{line}"), e.message().to_string())
        })?;
        Config::from_raw(&raw, source)
    }

    /// Validate a parsed config; errors are `SOURCE: FIELD: message`.
    pub fn from_raw(raw: &RawConfig, source: &str) -> Result<Config> {
        let at = |field: &str| format!("{source}: {field}");
        let stem = Path::new(source)
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_else(|| "run".to_string());
        let name = raw.name.clone().unwrap_or(stem);
        if name.trim().is_empty()
            || name
                .chars()
                .any(|c| !(c.is_alphanumeric() || "-_.".contains(c)))
        {
            return Err(Error::invalid(
                at("name"),
                format!("`{name}` is not allowed; use letters, digits, `-`, `_` or `.` (it names the run folder)"),
            ));
        }
        let seed = raw.seed.unwrap_or(defaults::SEED);

        // Cut and start.
        let rc = raw.cut.clone().unwrap_or_default();
        let fam_name = rc.family.as_deref().ok_or_else(|| {
            Error::invalid(
                at("cut.family"),
                "missing: give `[cut]` with `family = \"round-brilliant\"` (or another family)",
            )
        })?;
        let fam = family(fam_name).map_err(|e| match e {
            Error::Invalid { message, .. } => Error::invalid(at("cut.family"), message),
            other => other,
        })?;
        let start = fam
            .params(&rc.params)
            .map_err(|e| match e {
                Error::Invalid { field, message } => {
                    Error::invalid(at(&format!("cut.params.{field}")), message)
                }
                other => other,
            })?
            .values()
            .clone();

        // Free parameters.
        if raw.free.is_empty() {
            return Err(Error::invalid(
                at("free"),
                format!(
                    "no free parameters; give at least one as `key = [min, max]`; {} has: {}",
                    fam.name,
                    fam.keys().join(", ")
                ),
            ));
        }
        let mut free = Vec::new();
        for def in fam.params {
            let Some(&[lo, hi]) = raw.free.get(def.key) else {
                continue;
            };
            let field = at(&format!("free.{}", def.key));
            if !(lo.is_finite() && hi.is_finite()) {
                return Err(Error::invalid(
                    field,
                    format!("bounds [{lo}, {hi}] must be finite numbers"),
                ));
            }
            if lo > hi {
                return Err(Error::invalid(
                    field,
                    format!("bounds [{lo}, {hi}] are reversed; write [min, max]"),
                ));
            }
            if lo == hi {
                return Err(Error::invalid(
                    field,
                    format!("bounds [{lo}, {hi}] are empty; fix the value in [cut.params] instead"),
                ));
            }
            if def.unit == Unit::Count {
                return Err(Error::invalid(
                    field,
                    "a whole-number parameter cannot be optimized; fix it in [cut.params]",
                ));
            }
            let (l, r) = if def.open { ("(", ")") } else { ("[", "]") };
            let inside = |v: f64| {
                if def.open {
                    v > def.min && v < def.max
                } else {
                    v >= def.min && v <= def.max
                }
            };
            if !(inside(lo) && inside(hi)) {
                return Err(Error::invalid(
                    field,
                    format!(
                        "bounds [{lo}, {hi}] leave the family's allowed range {l}{}, {}{r} {}",
                        def.min,
                        def.max,
                        def.unit.label()
                    ),
                ));
            }
            let s = start[def.key];
            if !(lo..=hi).contains(&s) {
                let from = if rc.params.contains_key(def.key) {
                    "cut.params"
                } else {
                    "the family default"
                };
                return Err(Error::invalid(
                    field,
                    format!("the start value {s} (from {from}) lies outside the bounds [{lo}, {hi}]; widen them or set `{}` in [cut.params]", def.key),
                ));
            }
            free.push(FreeParam {
                key: def.key.to_string(),
                lo,
                hi,
                start: s,
                unit: def.unit,
            });
        }
        if let Some(k) = raw.free.keys().find(|k| fam.param(k).is_none()) {
            return Err(Error::invalid(
                at(&format!("free.{k}")),
                format!(
                    "unknown parameter of {}; allowed: {}",
                    fam.name,
                    fam.keys().join(", ")
                ),
            ));
        }

        // Objective.
        let ro = raw.objective.clone().unwrap_or_default();
        let any = ro.brilliance.is_some() || ro.fire.is_some() || ro.scintillation.is_some();
        let w = |field: &str, v: Option<f64>, dflt: f64| -> Result<f64> {
            let v = finite(&at(field), v.unwrap_or(dflt))?;
            if v < 0.0 {
                return Err(Error::invalid(
                    at(field),
                    format!("{v} is negative; weights are >= 0 (higher scores are better)"),
                ));
            }
            Ok(v)
        };
        let weights = Weights {
            brilliance: w(
                "objective.brilliance",
                ro.brilliance,
                if any { 0.0 } else { 1.0 },
            )?,
            fire: w("objective.fire", ro.fire, 0.0)?,
            scintillation: w("objective.scintillation", ro.scintillation, 0.0)?,
        };
        if weights.brilliance + weights.fire + weights.scintillation <= 0.0 {
            return Err(Error::invalid(
                at("objective"),
                "every weight is 0; give brilliance, fire or scintillation a positive weight",
            ));
        }

        // Constraints.
        let rk = raw.constraints.clone().unwrap_or_default();
        let frac = |field: &str, v: Option<f64>, max: f64| -> Result<Option<f64>> {
            match v {
                None => Ok(None),
                Some(v) => {
                    let v = finite(&at(field), v)?;
                    if !(0.0..=max).contains(&v) {
                        let hint = if v > 1.0 {
                            " (fractions: 0.12, not 12)"
                        } else {
                            ""
                        };
                        return Err(Error::invalid(
                            at(field),
                            format!("{v} is out of range; allowed [0, {max}]{hint}"),
                        ));
                    }
                    Ok(Some(v))
                }
            }
        };
        let total_depth = match rk.total_depth {
            None => None,
            Some([lo, hi]) => {
                let f = "constraints.total_depth";
                frac(f, Some(lo), 2.0)?;
                frac(f, Some(hi), 2.0)?;
                if lo > hi {
                    return Err(Error::invalid(
                        at(f),
                        format!("range [{lo}, {hi}] is reversed; write [min, max]"),
                    ));
                }
                Some([lo, hi])
            }
        };
        let penalty = finite(
            &at("constraints.penalty"),
            rk.penalty.unwrap_or(defaults::PENALTY),
        )?;
        if penalty <= 0.0 {
            return Err(Error::invalid(
                at("constraints.penalty"),
                format!("{penalty} is not allowed; give a positive cost per percentage point of violation"),
            ));
        }
        let constraints = Constraints {
            total_depth,
            min_crown_height: frac("constraints.min_crown_height", rk.min_crown_height, 1.0)?,
            min_girdle: frac("constraints.min_girdle", rk.min_girdle, 1.0)?,
            min_weight_retention: frac(
                "constraints.min_weight_retention",
                rk.min_weight_retention,
                1.0,
            )?,
            penalty,
        };

        // Method.
        let rm = raw.method.clone().unwrap_or_default();
        let mname = rm.name.as_deref().unwrap_or("nelder-mead");
        let nm_only: [(&str, bool); 5] = [
            ("starts", rm.starts.is_some()),
            ("design", rm.design.is_some()),
            ("include_start", rm.include_start.is_some()),
            ("simplex_step", rm.simplex_step.is_some()),
            ("tolerance", rm.tolerance.is_some()),
        ];
        let pso_only: [(&str, bool); 4] = [
            ("particles", rm.particles.is_some()),
            ("inertia", rm.inertia.is_some()),
            ("cognitive", rm.cognitive.is_some()),
            ("social", rm.social.is_some()),
        ];
        let refuse = |keys: &[(&str, bool)], only: &str| -> Result<()> {
            if let Some((k, _)) = keys.iter().find(|(_, given)| *given) {
                return Err(Error::invalid(
                    at(&format!("method.{k}")),
                    format!("only for method `{only}`, not `{mname}`"),
                ));
            }
            Ok(())
        };
        let count = |field: &str, v: u64, lo: u64, hi: u64| -> Result<u64> {
            if !(lo..=hi).contains(&v) {
                return Err(Error::invalid(
                    at(field),
                    format!("{v} is out of range; allowed {lo} to {hi}"),
                ));
            }
            Ok(v)
        };
        let (method, default_iters) = match mname {
            "nelder-mead" => {
                refuse(&pso_only, "particle-swarm")?;
                let design = match rm.design.as_deref().unwrap_or("latin-hypercube") {
                    "latin-hypercube" => Design::LatinHypercube,
                    "halton" => Design::Halton,
                    other => {
                        return Err(Error::invalid(
                            at("method.design"),
                            format!("unknown design `{other}`; allowed: latin-hypercube, halton"),
                        ))
                    }
                };
                let step = finite(
                    &at("method.simplex_step"),
                    rm.simplex_step.unwrap_or(defaults::SIMPLEX_STEP),
                )?;
                if !(step > 0.0 && step <= 0.5) {
                    return Err(Error::invalid(
                        at("method.simplex_step"),
                        format!("{step} is out of range; allowed (0, 0.5] (a fraction of each parameter's range)"),
                    ));
                }
                let tolerance = finite(
                    &at("method.tolerance"),
                    rm.tolerance.unwrap_or(defaults::TOLERANCE),
                )?;
                if tolerance < 0.0 {
                    return Err(Error::invalid(
                        at("method.tolerance"),
                        format!("{tolerance} is negative; give 0 (never converge: run to the budget) or a small positive number"),
                    ));
                }
                (
                    Method::NelderMead(NelderMeadSettings {
                        tolerance,
                        starts: count(
                            "method.starts",
                            rm.starts.unwrap_or(defaults::STARTS),
                            1,
                            1000,
                        )? as usize,
                        design,
                        include_start: rm.include_start.unwrap_or(true),
                        simplex_step: step,
                    }),
                    defaults::NM_MAX_ITERATIONS,
                )
            }
            "particle-swarm" => {
                refuse(&nm_only, "nelder-mead")?;
                let factor = |field: &str, v: Option<f64>, dflt: f64| -> Result<f64> {
                    let v = finite(&at(field), v.unwrap_or(dflt))?;
                    if !(0.0..=4.0).contains(&v) {
                        return Err(Error::invalid(
                            at(field),
                            format!("{v} is out of range; allowed [0, 4]"),
                        ));
                    }
                    Ok(v)
                };
                (
                    Method::ParticleSwarm(SwarmSettings {
                        particles: count(
                            "method.particles",
                            rm.particles.unwrap_or(defaults::PARTICLES),
                            2,
                            10_000,
                        )? as usize,
                        inertia: factor("method.inertia", rm.inertia, defaults::INERTIA)?,
                        cognitive: factor("method.cognitive", rm.cognitive, defaults::PULL)?,
                        social: factor("method.social", rm.social, defaults::PULL)?,
                    }),
                    defaults::PSO_MAX_ITERATIONS,
                )
            }
            other => {
                return Err(Error::invalid(
                    at("method.name"),
                    format!("unknown method `{other}`; allowed: nelder-mead, particle-swarm"),
                ))
            }
        };
        let budget = Budget {
            max_iterations: count(
                "method.max_iterations",
                rm.max_iterations.unwrap_or(default_iters),
                1,
                1_000_000,
            )?,
            max_evaluations: count(
                "method.max_evaluations",
                rm.max_evaluations.unwrap_or(defaults::MAX_EVALUATIONS),
                1,
                100_000_000,
            )?,
        };
        match method {
            Method::NelderMead(nm) => {
                let need = (nm.starts * (free.len() + 1)) as u64;
                if budget.max_evaluations < need {
                    return Err(Error::invalid(
                        at("method.max_evaluations"),
                        format!(
                            "{} cannot even build the {} starting simplexes ({need} evaluations); raise it or lower method.starts",
                            budget.max_evaluations, nm.starts
                        ),
                    ));
                }
            }
            Method::ParticleSwarm(s) => {
                if budget.max_evaluations < s.particles as u64 {
                    return Err(Error::invalid(
                        at("method.max_evaluations"),
                        format!(
                            "{} is less than one swarm of {} particles",
                            budget.max_evaluations, s.particles
                        ),
                    ));
                }
            }
        }

        // Verification.
        let rv = raw.verify.clone().unwrap_or_default();
        let min_distance = finite(
            &at("verify.min_distance"),
            rv.min_distance.unwrap_or(defaults::MIN_DISTANCE),
        )?;
        if !(0.0..=1.0).contains(&min_distance) {
            return Err(Error::invalid(
                at("verify.min_distance"),
                format!("{min_distance} is out of range; allowed [0, 1] (a distance in the unit box of the free parameters)"),
            ));
        }
        let sigma = finite(&at("verify.sigma"), rv.sigma.unwrap_or(defaults::SIGMA))?;
        if sigma <= 0.0 {
            return Err(Error::invalid(
                at("verify.sigma"),
                format!("{sigma} is not allowed; give a positive number of standard errors"),
            ));
        }
        let verify = VerifySettings {
            winners: count(
                "verify.winners",
                rv.winners.unwrap_or(defaults::WINNERS),
                0,
                100,
            )? as usize,
            photons: count(
                "verify.photons",
                rv.photons.unwrap_or(defaults::PHOTONS),
                1,
                10_000_000_000,
            )?,
            min_distance,
            sigma,
        };

        let rs = raw.score.clone().unwrap_or_default();
        let material = match (&rs.material, rs.ri) {
            (Some(_), Some(_)) => {
                return Err(Error::invalid(
                    at("score.ri"),
                    "give either score.material or score.ri, not both",
                ))
            }
            (None, Some(n)) => {
                let n = finite(&at("score.ri"), n)?;
                if !(n > 1.0 && n <= 10.0) {
                    return Err(Error::invalid(
                        at("score.ri"),
                        format!("{n} is out of range; allowed (1, 10]"),
                    ));
                }
                crate::optics::Material::constant(n)
            }
            (Some(m), None) => crate::optics::Material::by_name(m).map_err(|e| match e {
                Error::Invalid { message, .. } => Error::invalid(at("score.material"), message),
                other => other,
            })?,
            (None, None) => crate::optics::Material::diamond(),
        };
        let head_shadow_deg = finite(&at("score.head_shadow"), rs.head_shadow.unwrap_or(0.0))?;
        if !(0.0..=60.0).contains(&head_shadow_deg) {
            return Err(Error::invalid(
                at("score.head_shadow"),
                format!("{head_shadow_deg} is out of range; allowed [0, 60] degrees (0 = none)"),
            ));
        }
        let score = ScoreSettings {
            material,
            ri: rs.ri,
            head_shadow_deg,
            polarization: rs.polarization.unwrap_or(true),
        };

        Ok(Config {
            source: source.to_string(),
            name,
            description: raw.description.clone(),
            seed,
            family: fam,
            start,
            fixed: rc.params.clone(),
            free,
            weights,
            constraints,
            method,
            budget,
            verify,
            score,
        })
    }

    /// The start cut.
    pub fn start_cut(&self) -> Result<Cut> {
        Cut::from_family(&self.name, self.family.name, &self.start)
            .map_err(|e| e.context(&format!("{}: start cut", self.source)))
    }

    /// The family parameters with the free ones set to `x` (in [`Config::free`] order).
    pub fn params_at(&self, x: &[f64]) -> BTreeMap<String, f64> {
        let mut p = self.start.clone();
        for (f, v) in self.free.iter().zip(x) {
            p.insert(f.key.clone(), *v);
        }
        p
    }

    /// The free parameters' start values.
    pub fn start_x(&self) -> Vec<f64> {
        self.free.iter().map(|f| f.start).collect()
    }

    /// The config as used: every default written out, TOML.
    pub fn as_used(&self) -> RawConfig {
        let (nm, pso) = match self.method {
            Method::NelderMead(n) => (Some(n), None),
            Method::ParticleSwarm(s) => (None, Some(s)),
        };
        let c = &self.constraints;
        RawConfig {
            name: Some(self.name.clone()),
            description: self.description.clone(),
            seed: Some(self.seed),
            cut: Some(RawCut {
                family: Some(self.family.name.to_string()),
                params: self.start.clone(),
            }),
            free: self
                .free
                .iter()
                .map(|f| (f.key.clone(), [f.lo, f.hi]))
                .collect(),
            objective: Some(RawObjective {
                brilliance: Some(self.weights.brilliance),
                fire: Some(self.weights.fire),
                scintillation: Some(self.weights.scintillation),
            }),
            constraints: Some(RawConstraints {
                total_depth: c.total_depth,
                min_crown_height: c.min_crown_height,
                min_girdle: c.min_girdle,
                min_weight_retention: c.min_weight_retention,
                penalty: Some(c.penalty),
            }),
            method: Some(RawMethod {
                name: Some(self.method.name().to_string()),
                max_iterations: Some(self.budget.max_iterations),
                max_evaluations: Some(self.budget.max_evaluations),
                starts: nm.map(|n| n.starts as u64),
                design: nm.map(|n| n.design.name().to_string()),
                include_start: nm.map(|n| n.include_start),
                simplex_step: nm.map(|n| n.simplex_step),
                tolerance: nm.map(|n| n.tolerance),
                particles: pso.map(|s| s.particles as u64),
                inertia: pso.map(|s| s.inertia),
                cognitive: pso.map(|s| s.cognitive),
                social: pso.map(|s| s.social),
            }),
            verify: Some(RawVerify {
                winners: Some(self.verify.winners as u64),
                photons: Some(self.verify.photons),
                min_distance: Some(self.verify.min_distance),
                sigma: Some(self.verify.sigma),
            }),
            score: Some(RawScore {
                material: self
                    .score
                    .ri
                    .is_none()
                    .then(|| self.score.material.name.clone()),
                ri: self.score.ri,
                head_shadow: Some(self.score.head_shadow_deg),
                polarization: Some(self.score.polarization),
            }),
        }
    }

    /// TOML text of [`Config::as_used`], with a header naming the source.
    pub fn as_used_toml(&self) -> String {
        let body = toml::to_string(&self.as_used())
            .unwrap_or_else(|e| format!("# could not serialise: {e}\n"));
        format!(
            "# The config as used, every default written out (from {}).\n# `facetlab optimize` accepts this file as it is.\n\n{body}",
            self.source
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
        name = "t"
        seed = 3
        [cut]
        family = "round-brilliant"
        [cut.params]
        girdle = 0.03
        [free]
        pavilion_angle = [39.0, 42.5]
        crown_angle = [30, 38]
        [objective]
        brilliance = 1.0
        fire = 0.5
        [constraints]
        total_depth = [0.55, 0.65]
        [method]
        name = "nelder-mead"
        starts = 3
        design = "halton"
    "#;

    fn err(text: &str) -> String {
        Config::from_str(text, "round.toml")
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn good_config_validates_with_defaults() {
        let c = Config::from_str(GOOD, "round.toml").unwrap();
        assert_eq!(c.name, "t");
        let keys: Vec<&str> = c.free.iter().map(|f| f.key.as_str()).collect();
        assert_eq!(keys, ["crown_angle", "pavilion_angle"], "family order");
        assert_eq!(c.start["girdle"], 0.03);
        assert_eq!(c.free[0].start, 34.0);
        assert_eq!(c.weights.scintillation, 0.0);
        assert_eq!(c.verify.winners, 3);
        assert!(
            matches!(c.method, Method::NelderMead(n) if n.starts == 3 && n.design == Design::Halton)
        );
        // The config as used parses back to the same settings.
        let again = Config::from_str(&c.as_used_toml(), "used.toml").unwrap();
        assert_eq!(again.free, c.free);
        assert_eq!(again.method, c.method);
        assert_eq!(again.budget, c.budget);
        assert_eq!(again.start, c.start);
    }

    #[test]
    fn bad_configs_name_the_field() {
        let cases: &[(&str, &str, &str)] = &[
            (
                "crown_angle = [30, 38]",
                "crown_angle = [38, 30]",
                "round.toml: free.crown_angle: bounds [38, 30] are reversed",
            ),
            (
                "crown_angle = [30, 38]",
                "crown_angle = [3, 38]",
                "free.crown_angle: bounds [3, 38] leave the family's allowed range [5, 60]",
            ),
            (
                "crown_angle = [30, 38]",
                "crown_angle = [30, 38]\ntabel = [0.5, 0.6]",
                "free.tabel: unknown parameter",
            ),
            (
                "crown_angle = [30, 38]",
                "crown_angle = [35, 38]",
                "free.crown_angle: the start value 34 (from the family default) lies outside",
            ),
            (
                "crown_angle = [30, 38]",
                "girdle_facets = [16, 32]",
                "free.girdle_facets: a whole-number parameter",
            ),
            (
                "fire = 0.5",
                "fire = -0.5",
                "round.toml: objective.fire: -0.5 is negative",
            ),
            ("brilliance = 1.0\n", "brillance = 1.0\n", "round.toml:"),
            (
                "total_depth = [0.55, 0.65]",
                "total_depth = [0.65, 0.55]",
                "constraints.total_depth: range [0.65, 0.55] is reversed",
            ),
            (
                "total_depth = [0.55, 0.65]",
                "min_crown_height = 12",
                "constraints.min_crown_height: 12 is out of range",
            ),
            (
                "name = \"nelder-mead\"",
                "name = \"simplex\"",
                "method.name: unknown method `simplex`; allowed: nelder-mead, particle-swarm",
            ),
            (
                "design = \"halton\"",
                "design = \"sobol\"",
                "method.design: unknown design `sobol`",
            ),
            (
                "starts = 3",
                "starts = 3\nparticles = 4",
                "method.particles: only for method `particle-swarm`",
            ),
            (
                "starts = 3",
                "starts = 0",
                "method.starts: 0 is out of range",
            ),
            (
                "family = \"round-brilliant\"",
                "family = \"rund\"",
                "round.toml: cut.family: unknown family `rund`",
            ),
            (
                "girdle = 0.03",
                "girdle = 0.9",
                "round.toml: cut.params.girdle: 0.9 is out of range",
            ),
            ("seed = 3", "seed = -3", "round.toml:"),
        ];
        for (from, to, want) in cases {
            assert!(GOOD.contains(from), "{from}");
            let e = err(&GOOD.replacen(from, to, 1));
            assert!(e.contains(want), "{to}: got `{e}`, want `{want}`");
            assert!(!e.contains('\n'), "one line: {e}");
        }
        let e = err(&GOOD.replace("brilliance = 1.0\n", "brillance = 1.0\n"));
        assert!(e.contains("brillance"), "{e}");
        let e = err("[cut]\nfamily = \"round-brilliant\"\n");
        assert!(e.contains("round.toml: free: no free parameters"), "{e}");
        let e = err("[free]\ntable = [0.5, 0.6]\n");
        assert!(e.contains("round.toml: cut.family: missing"), "{e}");
        let e = err(&GOOD
            .replace("fire = 0.5", "fire = 0.0")
            .replace("brilliance = 1.0", "brilliance = 0.0"));
        assert!(e.contains("objective: every weight is 0"), "{e}");
    }

    #[test]
    fn score_section_sets_material_and_lighting() {
        let c = Config::from_str(
            &format!("{GOOD}\n[score]\nmaterial = \"cz\"\nhead_shadow = 15\n"),
            "round.toml",
        )
        .unwrap();
        let sc = c.score.score_config();
        assert_eq!(sc.material.name, "cubic-zirconia");
        assert_eq!(sc.head_shadow_deg, 15.0);
        assert!(sc.polarization);
        // Written back and read again, the settings survive.
        let back = Config::from_str(&c.as_used_toml(), "back.toml").unwrap();
        assert_eq!(back.score, c.score);
        let c = Config::from_str(
            &format!("{GOOD}\n[score]\nri = 2.0\npolarization = false\n"),
            "round.toml",
        )
        .unwrap();
        assert_eq!(c.score.score_config().material.ri(400.0), 2.0);
        assert!(!c.score.polarization);
        for (extra, needle) in [
            (
                "material = \"unobtainium\"",
                "round.toml: score.material: unknown material",
            ),
            ("material = \"diamond\"\nri = 2.4", "score.ri: give either"),
            ("ri = 0.5", "score.ri: 0.5 is out of range"),
            ("head_shadow = 75", "score.head_shadow: 75 is out of range"),
            ("colour = 1", "colour"),
        ] {
            let e = Config::from_str(&format!("{GOOD}\n[score]\n{extra}\n"), "round.toml")
                .unwrap_err()
                .to_string();
            assert!(e.contains(needle), "{extra}: {e}");
        }
    }

    #[test]
    fn swarm_settings() {
        let t = GOOD
            .replace("name = \"nelder-mead\"", "name = \"particle-swarm\"")
            .replace("starts = 3", "particles = 8")
            .replace("design = \"halton\"", "");
        let c = Config::from_str(&t, "p.toml").unwrap();
        assert!(matches!(c.method, Method::ParticleSwarm(s) if s.particles == 8));
        assert_eq!(c.budget.max_iterations, defaults::PSO_MAX_ITERATIONS);
        let e = err(&t.replace("particles = 8", "particles = 8\nstarts = 2"));
        assert!(
            e.contains("method.starts: only for method `nelder-mead`"),
            "{e}"
        );
    }
}
