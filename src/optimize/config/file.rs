//! The config file as a whole: [`RawConfig`], the file as written, and [`Config`], what it
//! validates into ([`Config::from_raw`] runs the sections' validators in the file's order),
//! with loading from disk and the config as used written back ([`Config::as_used_toml`]).

use super::constraints::{self, Constraints, RawConstraints};
use super::cut::{self, RawCut};
use super::fields::defaults;
use super::free::{self, FreeParam};
use super::meets;
use super::method::{self, Budget, Method, RawMethod};
use super::objective::{self, ParetoSpec, RawObjective, Weights};
use super::score::{self, RawScore, ScoreSettings};
use super::search_box::SearchBox;
use super::verify::{self, RawVerify, VerifySettings};
use crate::cut::{Cut, CutSpace};
use crate::design::{DesignSpace, OpenedMeet};
use crate::error::{Error, Result};
use crate::io::{line_of, read_bytes};
use crate::metrics::ScoreName;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

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
    /// The cut space searched (`[cut] family`): every cut of the run is built through it.
    pub space: Arc<dyn CutSpace>,
    /// The start cut's full parameter set (defaults filled in).
    pub start: BTreeMap<String, f64>,
    /// `[cut.params]` as given.
    pub fixed: BTreeMap<String, f64>,
    /// Free parameters in the space's parameter order.
    pub free: Vec<FreeParam>,
    /// Objective weights.
    pub weights: Weights,
    /// `[objective] pareto`: trace a trade-off instead of one weighted search.
    pub pareto: Option<ParetoSpec>,
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
    /// The design, when the space is a design's tier angles (`[cut] file`).
    pub design: Option<Arc<DesignSpace>>,
    /// `[cut] file` as given, and the path it was read from (`None` for a preset's name).
    pub cut_file: Option<(String, Option<PathBuf>)>,
    /// The design's meets the free angles cannot keep (only with `open_meets = "allow"`;
    /// otherwise such a config is refused).
    pub open_meets: Vec<OpenedMeet>,
    /// `[cut] facet_changes = "skip"`: free ranges in which the design changes were not
    /// refused.
    pub skip_changes: bool,
}

/// A colour weight as the written config gives it (left out when 0).
fn colour_weight(w: f64) -> Option<f64> {
    (w != 0.0).then_some(w)
}

impl Config {
    /// The files this config reads besides itself (its `[cut] file` design), as found: an
    /// output must never replace one of them.
    pub fn inputs(&self) -> Vec<PathBuf> {
        self.cut_file
            .iter()
            .filter_map(|(_, path)| path.clone())
            .collect()
    }

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

    /// Parse and validate config text from a client that may name no file (the workbench's
    /// `config_text`): its `[cut] file` may be a preset's name or a design `designs` gives
    /// (an upload, read in memory); anything else is refused without opening, or even looking
    /// for, a file, and the error repeats nothing of the name given.
    ///
    /// ```
    /// use facetlab::optimize::Config;
    /// let text = "[cut]\nfile = \"/etc/hostname.asc\"\n[free]\nC1 = [30, 40]\n";
    /// let e = Config::from_str_without_files(text, "c.toml", &|_| None).unwrap_err();
    /// assert!(!e.to_string().contains("hostname"), "{e}");
    /// ```
    pub fn from_str_without_files(
        text: &str,
        source: &str,
        designs: &dyn Fn(&str) -> Option<Result<Cut>>,
    ) -> Result<Config> {
        let raw = Config::raw_of(text, source)?;
        Config::from_raw_in(&raw, source, cut::Designs::Only(designs))
    }

    fn raw_of(text: &str, source: &str) -> Result<RawConfig> {
        toml::from_str(text).map_err(|e| {
            let line = e
                .span()
                .map(|s| format!(":{}", line_of(text, s.start)))
                .unwrap_or_default();
            Error::parse(format!("{source}{line}"), e.message().to_string())
        })
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
        Config::from_raw_in(raw, source, cut::Designs::Files)
    }

    fn from_raw_in(raw: &RawConfig, source: &str, designs: cut::Designs<'_>) -> Result<Config> {
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

        let raw_cut = raw.cut.clone().unwrap_or_default();
        let section = cut::validate(&raw_cut, source, &at, designs)?;
        let (space, mut start) = (section.space, section.start);
        let rc_params = raw_cut.params.clone();
        let free = free::validate(&raw.free, space.as_ref(), &start, &rc_params, &at)?;
        // A free key the start does not name (a design's tie) starts at its default.
        for f in &free {
            start.entry(f.key.clone()).or_insert(f.start);
        }
        let open_meets = match &section.design {
            Some(d) => meets::check(d, &free, &start, section.skip_changes, &at)?,
            None => Vec::new(),
        };
        let weights = objective::validate(&raw.objective.clone().unwrap_or_default(), &at)?;
        let pareto = objective::validate_pareto(&raw.objective.clone().unwrap_or_default(), &at)?;
        let constraints = constraints::validate(&raw.constraints.clone().unwrap_or_default(), &at)?;
        if constraints.grade.is_some() && space.name() != "round-brilliant" {
            return Err(Error::invalid(
                at("constraints.grade"),
                format!(
                    "grade estimates exist for the round-brilliant family only, not {}",
                    space.name()
                ),
            ));
        }
        let (method, budget) =
            method::validate(&raw.method.clone().unwrap_or_default(), free.len(), &at)?;
        let verify = verify::validate(&raw.verify.clone().unwrap_or_default(), &at)?;
        let raw_score = raw.score.clone().unwrap_or_default();
        let mut score = score::validate(&raw_score, &at)?;
        // A design is scored in its own material (its file's index) unless the config says.
        let own = section.record.as_ref().and_then(|r| r.ri);
        if let (None, None, Some(n)) = (&raw_score.material, raw_score.ri, own) {
            if let Some(m) = crate::optics::Material::for_index(n) {
                score.material = m;
                // The user's colour colours the design's own material too.
                score.material.colour = score.user_colour.clone();
            }
        }
        // A design whose notes name its material (`F Material: ruby`) is scored in it.
        let record = section.record.clone();
        if let (None, None, Some(r)) = (&raw_score.material, raw_score.ri, record) {
            let lines = r.title.iter().chain(&r.footnotes);
            let named = crate::optics::Material::from_design_notes(lines, &score.material)
                .map_err(|e| Error::invalid(at("cut.file"), e.to_string()))?;
            if let Some(m) = named {
                let user = score.user_colour.clone();
                score.material = m;
                if user.is_some() {
                    score.material.colour = user;
                }
            }
        }
        // The birefringence settings apply to the material chosen last (a design's own too).
        let mut material = score.material.clone();
        score.apply_crystal(&mut material, &at)?;
        score.material = material;
        // `[free] optic_axis`: the c-axis's angle from the table's normal, varied by the
        // optimizer; it starts at the material's own.
        let mut free = free;
        if let Some(f) = free.iter_mut().find(|f| f.key == free::OPTIC_AXIS) {
            let Some(u) = score.material.uniaxial.as_ref() else {
                return Err(Error::invalid(
                    at("free.optic_axis"),
                    format!(
                        "{} is not uniaxial: the optic axis orients uniaxial stones only (quartz, beryl, tourmaline, sapphire and ruby, zircon, moissanite and their varieties)",
                        score.material.name
                    ),
                ));
            };
            let s = u.axis.tilt_deg;
            if !(f.lo..=f.hi).contains(&s) {
                return Err(Error::invalid(
                    at("free.optic_axis"),
                    format!(
                        "the start value {s}° (the material's optic axis; set [score] optic_axis) lies outside the bounds [{}, {}]",
                        f.lo, f.hi
                    ),
                ));
            }
            f.start = s;
        }
        let colour_weights = raw.objective.clone().unwrap_or_default().colour();
        for (name, set) in ScoreName::COLOUR.iter().zip(colour_weights) {
            if set.is_some() && score.material.colour.is_none() {
                return Err(Error::invalid(
                    at(&format!("objective.{name}")),
                    "the stone has no body colour to weigh; give [score] colour or a coloured material (facetlab materials)",
                ));
            }
        }
        for (field, set) in [
            ("constraints.max_extinction", constraints.max_extinction),
            ("constraints.max_windowing", constraints.max_windowing),
        ] {
            if set.is_some() && score.material.colour.is_none() {
                return Err(Error::invalid(
                    at(field),
                    "the stone has no body colour to limit; give [score] colour or a coloured material (facetlab materials)",
                ));
            }
        }

        Ok(Config {
            source: source.to_string(),
            name,
            description: raw.description.clone(),
            seed,
            space,
            start,
            fixed: rc_params,
            free,
            weights,
            pareto,
            constraints,
            method,
            budget,
            verify,
            score,
            design: section.design,
            cut_file: section.file,
            open_meets,
            skip_changes: section.skip_changes,
        })
    }

    /// The start cut.
    pub fn start_cut(&self) -> Result<Cut> {
        self.build(&self.name, &self.start)
            .map_err(|e| e.context(&format!("{}: start cut", self.source)))
    }

    /// The box the search moves in: the free parameters and the space that builds their cuts.
    pub fn search_box(&self) -> SearchBox<'_> {
        SearchBox {
            name: &self.name,
            space: &*self.space,
            start: &self.start,
            free: &self.free,
        }
    }

    /// The cut of the config's space with parameters `params` (see [`SearchBox::build`]).
    pub fn build(&self, label: &str, params: &BTreeMap<String, f64>) -> Result<Cut> {
        self.search_box().build(label, params)
    }

    /// The space's parameters with the free ones set to `x` (in [`Config::free`] order).
    pub fn params_at(&self, x: &[f64]) -> BTreeMap<String, f64> {
        self.search_box().params_at(x)
    }

    /// The free parameters' start values.
    pub fn start_x(&self) -> Vec<f64> {
        self.search_box().start_x()
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
            cut: Some(match (&self.design, &self.cut_file) {
                (Some(d), Some((given, path))) => RawCut {
                    family: None,
                    // The design file by its full path, so the written config runs anywhere.
                    file: Some(full_path(given, path)),
                    open_meets: Some(d.open_meets().name().to_string()),
                    facet_changes: Some(
                        if self.skip_changes { "skip" } else { "refuse" }.to_string(),
                    ),
                    meet_tol: Some(d.model().meet_tol()),
                    params: self.start.clone(),
                },
                // A recipe: its file by its full path, its meets its own.
                (None, Some((given, path))) => RawCut {
                    family: None,
                    file: Some(full_path(given, path)),
                    params: self.start.clone(),
                    ..RawCut::default()
                },
                _ => RawCut {
                    family: Some(self.space.name().to_string()),
                    params: self.start.clone(),
                    ..RawCut::default()
                },
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
                colour_l: colour_weight(self.weights.colour[0]),
                colour_c: colour_weight(self.weights.colour[1]),
                extinction: colour_weight(self.weights.colour[2]),
                windowing: colour_weight(self.weights.colour[3]),
                pareto: self
                    .pareto
                    .as_ref()
                    .map(|p| p.scores.iter().map(ScoreName::to_string).collect()),
                pareto_points: self.pareto.as_ref().map(|p| p.points as u64),
            }),
            constraints: Some(RawConstraints {
                total_depth: c.total_depth,
                min_crown_height: c.min_crown_height,
                min_girdle: c.min_girdle,
                min_weight_retention: c.min_weight_retention,
                grade: c.grade.map(|g| g.name().to_string()),
                max_extinction: c.max_extinction,
                max_windowing: c.max_windowing,
                penalty: Some(c.penalty),
            }),
            method: Some(RawMethod {
                name: Some(self.method.name().to_string()),
                max_iterations: Some(self.budget.max_iterations),
                max_evaluations: Some(self.budget.max_evaluations),
                starts: nm.map(|n| n.starts as u64),
                design: nm.map(|n| n.sampling.name().to_string()),
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
                setting: (self.score.setting != crate::metrics::ScoreSetting::Default)
                    .then(|| self.score.setting.name().to_string()),
                split_threshold: Some(self.score.split_threshold),
                fire_split_threshold: Some(self.score.fire_split_threshold),
                ray_floor: Some(self.score.ray_floor),
                narrow_forks: Some(self.score.narrow_forks),
                colour: self.score.colour_fields.0.clone(),
                colour_density: self.score.colour_fields.1,
                size_mm: self.score.colour_fields.2.clone(),
                diameter_mm: self.score.colour_fields.3,
                birefringence: self.score.material.uniaxial.as_ref().map(|u| u.traced),
                optic_axis: self
                    .score
                    .material
                    .uniaxial
                    .as_ref()
                    .map(|u| score::RawAxis::Text(u.axis.label())),
                colour_e: self.score.crystal_fields.2.clone(),
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

/// A design file (`[cut] file`) by its full path when it was found, so a written config runs
/// anywhere; else as the config gave it.
fn full_path(given: &str, path: &Option<std::path::PathBuf>) -> String {
    path.as_ref().map_or(given.to_string(), |p| {
        std::path::absolute(p)
            .unwrap_or_else(|_| p.clone())
            .display()
            .to_string()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimize::config::method::Sampling;

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
            matches!(c.method, Method::NelderMead(n) if n.starts == 3 && n.sampling == Sampling::Halton)
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
            &format!("{GOOD}\n[score]\nmaterial = \"cz\"\nhead_shadow = 25\n"),
            "round.toml",
        )
        .unwrap();
        let sc = c.score.score_config();
        assert_eq!(sc.material.name, "cubic-zirconia");
        assert_eq!(sc.head_shadow_deg, 25.0);
        // The head shadow: the scores' default when not given, off with 0 (written back too).
        let head = |s: &str| {
            Config::from_str(&format!("{GOOD}\n[score]\n{s}"), "round.toml")
                .unwrap()
                .score
                .score_config()
                .head_shadow_deg
        };
        assert_eq!(head(""), crate::metrics::DEFAULT_HEAD_SHADOW_DEG);
        assert_eq!(head("head_shadow = 0\n"), 0.0);
        let off =
            Config::from_str(&format!("{GOOD}\n[score]\nhead_shadow = 0\n"), "r.toml").unwrap();
        let back = Config::from_str(&off.as_used_toml(), "back.toml").unwrap();
        assert_eq!(back.score.head_shadow_deg, 0.0);
        assert!(sc.trace.polarization);
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
        // The split thresholds: defaults, or the config's, and back; polarization is the trace
        // settings' own.
        let d = crate::metrics::ScoreConfig::default();
        assert_eq!(
            c.score.score_config().trace,
            d.clone().polarized(false).trace
        );
        assert_eq!(
            c.score.score_config().fire_split_threshold,
            d.fire_split_threshold
        );
        let c = Config::from_str(
            &format!(
                "{GOOD}\n[score]\nsplit_threshold = 1e-5\nfire_split_threshold = 1e-6\n\
                 ray_floor = 0\nnarrow_forks = true\n"
            ),
            "round.toml",
        )
        .unwrap();
        let sc = c.score.score_config();
        assert_eq!(
            (
                sc.trace.split_threshold,
                sc.fire_split_threshold,
                sc.trace.ray_floor,
                sc.trace.narrow_forks
            ),
            (1e-5, 1e-6, 0.0, true)
        );
        assert_eq!(sc.trace.threshold, d.trace.threshold);
        let back = Config::from_str(&c.as_used_toml(), "back.toml").unwrap();
        assert_eq!(back.score, c.score);
        for (extra, needle) in [
            (
                "material = \"unobtainium\"",
                "round.toml: score.material: unknown material",
            ),
            ("material = \"diamond\"\nri = 2.4", "score.ri: give either"),
            ("ri = 0.5", "score.ri: 0.5 is out of range"),
            ("head_shadow = 75", "score.head_shadow: 75 is out of range"),
            (
                "split_threshold = 0.5",
                "round.toml: score.split_threshold: 0.5 is out of range; allowed [1e-9, 1e-2]",
            ),
            (
                "fire_split_threshold = 0",
                "score.fire_split_threshold: 0 is out of range",
            ),
            (
                "ray_floor = 0.7",
                "score.ray_floor: 0.7 is out of range; allowed [0, 0.5]",
            ),
            ("colour = 1", "expected a string"),
            ("tint = 1", "tint"),
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
