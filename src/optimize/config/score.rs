//! `[score]`: how the cuts are scored (material, lighting).

use super::fields::{finite, At};
use crate::error::{shown, Error, Result};
use serde::{Deserialize, Serialize};

/// `[score]`: the scoring settings of the beam tracer (and of the photon-tracer checks).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScore {
    /// Material: a name from `facetlab materials` or `ri:N[:BG]`; default diamond.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// A fixed refractive index instead of a material (no dispersion, no fire).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ri: Option<f64>,
    /// Head-shadow half-angle in degrees, 0–60; default
    /// [`DEFAULT_HEAD_SHADOW_DEG`](crate::metrics::DEFAULT_HEAD_SHADOW_DEG), 15 (0 = none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub head_shadow: Option<f64>,
    /// Track polarization; default true.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub polarization: Option<bool>,
    /// The named setting the other fields start from: `"default"` or `"smooth"`
    /// ([`ScoreSetting`](crate::metrics::ScoreSetting): split thresholds 1e-5 and 3e-7 and 32
    /// bands for fire, smooth on a 0.002° scale and slower); default `"default"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub setting: Option<String>,
    /// Split threshold of the tilted poses' traces (brilliance, scintillation); default 1e-4
    /// (the setting's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub split_threshold: Option<f64>,
    /// Split threshold of fire's face-up traces; default 3e-6 (the setting's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fire_split_threshold: Option<f64>,
    /// Share of its starting power below which a narrow beam's ray stops (its rest handed
    /// back with the narrow exits' mean); default 0.05, 0 = follow every ray to 1e-8.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ray_floor: Option<f64>,
    /// Follow narrow beams as discs that fork at facet edges (smoother scores, slower, and
    /// brilliance up to 4e-4 off); default false.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub narrow_forks: Option<bool>,
    /// The stone's colour seen through a path under D65, `#rrggbb[@Nmm]` or
    /// `lab(L,a,b)[@Nmm]` (like `--colour`); default the material's own (none, or a coloured
    /// variety's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub colour: Option<String>,
    /// A factor on the body colour's absorption (like `--colour-density`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub colour_density: Option<f64>,
    /// The stone's size in mm for body colour: its length L (a number, or "L"), or "LxW"
    /// (like `--size-mm`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size_mm: Option<RawSize>,
    /// The stone's width W in mm for body colour (like `--diameter-mm`); default 6.5.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diameter_mm: Option<f64>,
    /// Trace a uniaxial stone birefringent (like `--birefringence`); default true for those
    /// stones.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub birefringence: Option<bool>,
    /// A uniaxial stone's optic axis, `"DEG[@AZ]"` or a number of degrees from the table's
    /// normal (like `--optic-axis`); default as cutters orient the material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub optic_axis: Option<RawAxis>,
    /// A uniaxial stone's E ∥ c colour (like `--colour-e`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub colour_e: Option<String>,
}

/// A number or text as a config writes it (`optic_axis`, `size_mm`): anything else is
/// refused saying what is expected (`expecting`), not as a data type's own name.
struct NumberOrText(&'static str);

impl serde::de::Visitor<'_> for NumberOrText {
    type Value = std::result::Result<f64, String>;
    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.0)
    }
    fn visit_f64<E>(self, v: f64) -> std::result::Result<Self::Value, E> {
        Ok(Ok(v))
    }
    fn visit_i64<E>(self, v: i64) -> std::result::Result<Self::Value, E> {
        Ok(Ok(v as f64))
    }
    fn visit_u64<E>(self, v: u64) -> std::result::Result<Self::Value, E> {
        Ok(Ok(v as f64))
    }
    fn visit_str<E>(self, v: &str) -> std::result::Result<Self::Value, E> {
        Ok(Err(v.to_string()))
    }
}

impl<'de> Deserialize<'de> for RawAxis {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        d.deserialize_any(NumberOrText(
            "a number of degrees from the table's normal or text \"DEG@AZ\" (e.g. 30 or \"90@0\")",
        ))
        .map(|v| v.map_or_else(RawAxis::Text, RawAxis::Number))
    }
}

impl<'de> Deserialize<'de> for RawSize {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        d.deserialize_any(NumberOrText(
            "a length in mm or text \"LxW\" (e.g. 8 or \"10x5\")",
        ))
        .map(|v| v.map_or_else(RawSize::Text, RawSize::Number))
    }
}

/// `score.optic_axis` as written: a number (the angle from the table's normal) or text
/// (`"90@0"`).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum RawAxis {
    /// Degrees from the table's normal, toward azimuth 0.
    Number(f64),
    /// `DEG[@AZ]`.
    Text(String),
}

impl RawAxis {
    /// As `--optic-axis` takes it.
    pub fn text(&self) -> String {
        match self {
            RawAxis::Number(x) => x.to_string(),
            RawAxis::Text(t) => t.clone(),
        }
    }
}

/// `score.size_mm` as written: a number (the length) or text (`"10"`, `"10x5"`).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum RawSize {
    /// A length in mm.
    Number(f64),
    /// `L` or `LxW` in mm.
    Text(String),
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
    /// The named setting the scoring configuration starts from.
    pub setting: crate::metrics::ScoreSetting,
    /// Split threshold of the tilted poses' traces.
    pub split_threshold: f64,
    /// Split threshold of fire's face-up traces.
    pub fire_split_threshold: f64,
    /// The narrow beams' ray floor ([`crate::beam::TraceOptions::ray_floor`]).
    pub ray_floor: f64,
    /// Narrow beams as forking discs ([`crate::beam::TraceOptions::narrow_forks`]).
    pub narrow_forks: bool,
    /// The user's colour (`colour`, upsampled, times `colour_density`), which also colours a
    /// design traced in its own material.
    pub user_colour: Option<crate::optics::BodyColour>,
    /// `colour`, `colour_density`, `size_mm`, `diameter_mm` as given (for writing the config
    /// back).
    pub colour_fields: (Option<String>, Option<f64>, Option<RawSize>, Option<f64>),
    /// The stone's size for body colour.
    pub size: crate::optics::StoneSize,
    /// `birefringence`, `optic_axis`, `colour_e` as given (applied to the material, also to
    /// a design's own).
    pub crystal_fields: (Option<bool>, Option<RawAxis>, Option<String>),
}

impl ScoreSettings {
    /// Apply `birefringence`, `optic_axis` and `colour_e` to `material` (a design's own
    /// material, or the config's); errors name the field under `at`.
    pub fn apply_crystal(
        &self,
        material: &mut crate::optics::Material,
        at: &dyn Fn(&str) -> String,
    ) -> Result<()> {
        let (on, axis, colour_e) = &self.crystal_fields;
        let axis_field = at("score.optic_axis");
        let axis = axis
            .as_ref()
            .map(|a| crate::optics::OpticAxis::parse(&a.text(), &axis_field))
            .transpose()?;
        material.choose_crystal(
            *on,
            axis,
            colour_e.as_deref(),
            self.colour_fields.1,
            crate::optics::CrystalFields {
                birefringence: &at("score.birefringence"),
                optic_axis: &axis_field,
                colour_e: &at("score.colour_e"),
            },
        )
    }
}

impl ScoreSettings {
    /// The beam tracer's scoring configuration for these settings.
    pub fn score_config(&self) -> crate::metrics::ScoreConfig {
        let base = self.setting.config();
        crate::metrics::ScoreConfig {
            material: self.material.clone(),
            size: self.size,
            head_shadow_deg: self.head_shadow_deg,
            fire_split_threshold: self.fire_split_threshold,
            trace: crate::beam::TraceOptions {
                polarization: self.polarization,
                split_threshold: self.split_threshold,
                ray_floor: self.ray_floor,
                narrow_forks: self.narrow_forks,
                ..base.trace
            },
            ..base
        }
    }
}

/// Validate `[score]`.
pub(super) fn validate(rs: &RawScore, at: At) -> Result<ScoreSettings> {
    let mut material = crate::optics::Material::choose(
        rs.material.as_deref(),
        rs.ri,
        crate::optics::MaterialFields {
            material: &at("score.material"),
            ri: &at("score.ri"),
        },
    )?;
    // A finite number within `range`, or a one-line error naming the field and what is
    // allowed (`allowed`: the range as printed, and what it means).
    let ranged = |field: &str,
                  value: Option<f64>,
                  default: f64,
                  range: std::ops::RangeInclusive<f64>,
                  allowed: &str|
     -> Result<f64> {
        let x = finite(&at(field), value.unwrap_or(default))?;
        if !range.contains(&x) {
            return Err(Error::invalid(
                at(field),
                format!("{} is out of range; allowed {allowed}", shown(x)),
            ));
        }
        Ok(x)
    };
    let setting = match rs.setting.as_deref() {
        None => crate::metrics::ScoreSetting::default(),
        Some(name) => crate::metrics::ScoreSetting::from_name(name).ok_or_else(|| {
            let names: Vec<&str> = crate::metrics::ScoreSetting::ALL
                .iter()
                .map(|s| s.name())
                .collect();
            Error::invalid(
                at("score.setting"),
                format!("`{name}` is not a setting; allowed {}", names.join(", ")),
            )
        })?,
    };
    let defaults = setting.config();
    let split = |field: &str, value: Option<f64>, default: f64| -> Result<f64> {
        ranged(
            field,
            value,
            default,
            1e-9..=1e-2,
            "[1e-9, 1e-2] (a share of the light; smaller is smoother and slower)",
        )
    };
    material.colour = crate::optics::BodyColour::choose(
        material.colour.as_ref(),
        rs.colour.as_deref(),
        rs.colour_density,
        crate::optics::ColourFields {
            colour: &at("score.colour"),
            density: &at("score.colour_density"),
        },
    )?;
    let user_colour = rs.colour.as_ref().and(material.colour.clone());
    let size = match (&rs.size_mm, rs.diameter_mm) {
        (Some(_), Some(_)) => {
            return Err(Error::invalid(
                at("score.diameter_mm"),
                "give either score.size_mm or score.diameter_mm, not both",
            ))
        }
        (Some(RawSize::Number(l)), None) => {
            crate::optics::StoneSize::parse_length(&l.to_string(), &at("score.size_mm"))?
        }
        (Some(RawSize::Text(t)), None) => {
            crate::optics::StoneSize::parse_length(t, &at("score.size_mm"))?
        }
        (None, Some(w)) => crate::optics::StoneSize::width(w, &at("score.diameter_mm"))?,
        (None, None) => crate::optics::StoneSize::default(),
    };
    let mut score = ScoreSettings {
        crystal_fields: (rs.birefringence, rs.optic_axis.clone(), rs.colour_e.clone()),
        user_colour,
        colour_fields: (
            rs.colour.clone(),
            rs.colour_density,
            rs.size_mm.clone(),
            rs.diameter_mm,
        ),
        size,
        material,
        ri: rs.ri,
        head_shadow_deg: ranged(
            "score.head_shadow",
            rs.head_shadow,
            defaults.head_shadow_deg,
            0.0..=60.0,
            "[0, 60] degrees (0 = none)",
        )?,
        polarization: rs.polarization.unwrap_or(true),
        setting,
        split_threshold: split(
            "score.split_threshold",
            rs.split_threshold,
            defaults.trace.split_threshold,
        )?,
        fire_split_threshold: split(
            "score.fire_split_threshold",
            rs.fire_split_threshold,
            defaults.fire_split_threshold,
        )?,
        ray_floor: ranged(
            "score.ray_floor",
            rs.ray_floor,
            defaults.trace.ray_floor,
            0.0..=0.5,
            "[0, 0.5] (a share of a narrow beam's power; 0 follows every ray to the end)",
        )?,
        narrow_forks: rs.narrow_forks.unwrap_or(defaults.trace.narrow_forks),
    };
    let mut material = score.material.clone();
    score.apply_crystal(&mut material, at)?;
    score.material = material;
    Ok(score)
}

#[cfg(test)]
mod tests {
    use crate::optimize::Config;

    const BASE: &str =
        "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30, 38]\n[score]\n";

    fn config(score: &str) -> crate::error::Result<Config> {
        Config::from_str(&format!("{BASE}{score}"), "c.toml")
    }

    /// `[score] colour`, `colour_density`, `size_mm` and `diameter_mm` reach the scoring
    /// configuration, survive writing the config back, and are one-line errors when wrong;
    /// without them the configuration is today's (colourless, width 6.5 mm).
    #[test]
    fn colour_and_size_fields_round_trip_and_default_to_colourless() {
        let plain = config("").unwrap().score.score_config();
        assert_eq!(plain, crate::metrics::ScoreConfig::default());
        assert!(plain.material.colour.is_none());

        let c = config("material = \"ruby\"\ncolour_density = 0.5\nsize_mm = \"8\"\n").unwrap();
        let sc = c.score.score_config();
        let ruby = sc.material.colour.as_ref().unwrap();
        assert_eq!((ruby.name.as_str(), ruby.density), ("ruby", 0.5));
        assert_eq!(sc.size, crate::optics::StoneSize::Length(8.0));
        let again = Config::from_raw(&c.as_used(), "again.toml").unwrap();
        assert_eq!(again.score.score_config(), sc);

        let c =
            config("material = \"quartz\"\ncolour = \"#7a3fa0@10mm\"\ndiameter_mm = 9\n").unwrap();
        let sc = c.score.score_config();
        assert_eq!(sc.material.colour.as_ref().unwrap().name, "#7a3fa0@10mm");
        assert_eq!(sc.size, crate::optics::StoneSize::Width(9.0));
        let again = Config::from_raw(&c.as_used(), "again.toml").unwrap();
        assert_eq!(again.score.score_config(), sc);

        for (body, needle) in [
            (
                "colour = \"purple\"",
                "c.toml: score.colour: `purple` is not a colour",
            ),
            (
                "colour_density = 2",
                "c.toml: score.colour_density: there is no colour",
            ),
            (
                "material = \"ruby\"\ncolour_density = -1",
                "score.colour_density: -1 is out of range",
            ),
            ("size_mm = \"10x\"", "c.toml: score.size_mm:"),
            ("diameter_mm = 0", "c.toml: score.diameter_mm:"),
            ("size_mm = 8\ndiameter_mm = 6", "not both"),
        ] {
            let e = config(body).unwrap_err().to_string();
            assert!(e.contains(needle) && !e.contains('\n'), "{body}: {e}");
        }
    }

    /// `[score] setting = "smooth"` scores with [`ScoreConfig::smooth`] (its split thresholds
    /// overridable field by field), survives writing the config back, and a name that is no
    /// setting is a one-line error naming the field and the settings allowed.
    ///
    /// [`ScoreConfig::smooth`]: crate::metrics::ScoreConfig::smooth
    #[test]
    fn the_smooth_setting_is_named_in_score() {
        use crate::metrics::ScoreConfig;
        let c = config("setting = \"smooth\"\n").unwrap();
        assert_eq!(c.score.score_config(), ScoreConfig::smooth());
        let again = Config::from_raw(&c.as_used(), "again.toml").unwrap();
        assert_eq!(again.score.score_config(), ScoreConfig::smooth());
        let c = config("setting = \"default\"\n").unwrap();
        assert_eq!(c.score.score_config(), ScoreConfig::default());
        assert!(c.as_used().score.unwrap().setting.is_none());
        let c = config("setting = \"smooth\"\nfire_split_threshold = 1e-6\n").unwrap();
        let sc = c.score.score_config();
        assert_eq!(
            (sc.fire_split_threshold, sc.bands, sc.trace.split_threshold),
            (1e-6, ScoreConfig::smooth().bands, ScoreConfig::SMOOTH_SPLIT)
        );
        let e = config("setting = \"fine\"\n").unwrap_err().to_string();
        assert!(
            e.contains("c.toml: score.setting: `fine` is not a setting; allowed default, smooth")
                && !e.contains('\n'),
            "{e}"
        );
    }

    /// A design's note `F Material: …` sets the material a config scores it in, unless
    /// `[score] material` says otherwise; a bad note is an error naming the file.
    #[test]
    fn a_design_note_names_the_scored_material() {
        let d = tempfile::tempdir().unwrap();
        let asc = crate::io::asc::write(&crate::io::load_cut("tolkowsky").unwrap(), 96);
        let with_note = |note: &str| format!("{}\nF {note}\n", asc.trim_end());
        std::fs::write(d.path().join("ruby.asc"), with_note("Material: ruby")).unwrap();
        std::fs::write(d.path().join("bad.asc"), with_note("Material: kryptonite")).unwrap();
        let text = |file: &str, score: &str| {
            format!(
                "[cut]\nfile = \"{file}\"\n[free]\npavilion-main = [40, 41.4]\n[score]\n{score}"
            )
        };
        let path = d.path().join("c.toml");
        let load =
            |file: &str, score: &str| Config::from_str(&text(file, score), path.to_str().unwrap());
        let c = load("ruby.asc", "").unwrap();
        assert_eq!(c.score.material.name, "ruby");
        assert!(c.score.material.colour.is_some());
        let c = load("ruby.asc", "material = \"diamond\"").unwrap();
        assert_eq!(c.score.material.name, "diamond");
        let e = load("bad.asc", "").unwrap_err().to_string();
        assert!(e.contains("cut.file: ") && e.contains("kryptonite"), "{e}");
    }
}
