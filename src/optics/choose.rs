//! Choosing a material: by name (a table name or alias, or `ri:N[:BG]`), from the command
//! line's or a config's pair of fields ([`Material::choose`]), or as the table material nearest
//! the refractive index a cut was made for ([`Material::for_index`]).

use super::material::{Dispersion, Material, MaterialFields, Optic};
use super::table::{Entry, DIAMOND, TABLE};
use super::varieties::Variety;
use crate::error::{shown, Error, Result};

impl Material {
    /// A fixed refractive index (no dispersion), with diamond's density.
    pub fn constant(n: f64) -> Material {
        Material {
            name: format!("ri-{n}"),
            dispersion: Dispersion::Constant(n),
            density: DIAMOND.density,
            optic: Optic::Isotropic,
            source: "a fixed index: no dispersion, no fire".into(),
            colour: None,
            uniaxial: None,
        }
    }

    /// B–G dispersion per unit of (n_D − 1) that `ri:N` gives: B–G = 0.03 (N − 1). It is the
    /// median of that ratio over the table's stones (0.031; quartz 0.024, sapphire 0.023,
    /// diamond 0.031, zircon 0.042), so a generic stone has typical fire for its index.
    pub const GENERIC_BG_PER_N1: f64 = 0.03;
    /// The largest B–G accepted by `ri:N:BG` (strontium titanate, the most dispersive stone
    /// in the table, has 0.19).
    pub const BG_MAX: f64 = 0.5;

    /// A material by name: a coloured variety ([`Variety`]: `ruby`, `emerald`, … — the host
    /// material with the variety's published body colour, or colourless where none was
    /// found), a table name ([`Material::NAMES`]) or alias (`cz`, `bk7`, …), or `ri:N` (index N at the D line with the generic dispersion
    /// B–G = [`GENERIC_BG_PER_N1`](Material::GENERIC_BG_PER_N1)·(N − 1)) or `ri:N:BG` (index N
    /// with B–G dispersion BG), both as a Cauchy curve. Errors name the `material`.
    pub fn by_name(name: &str) -> Result<Material> {
        let key = name.trim().to_ascii_lowercase();
        if let Some(spec) = key.strip_prefix("ri:") {
            return Material::from_ri_spec(name.trim(), spec);
        }
        if let Some(v) = Variety::by_name(&key) {
            return Ok(v.material());
        }
        TABLE
            .iter()
            .find(|e| e.name == key || e.aliases.contains(&key.as_str()))
            .map(Entry::material)
            .ok_or_else(|| {
                let varieties: Vec<&str> = Variety::all().iter().map(|v| v.name).collect();
                Error::invalid(
                    "material",
                    format!(
                        "unknown material `{name}`; known: {}; coloured varieties: {}; or ri:N[:BG] (an index N with generic or given B–G dispersion)",
                        Material::NAMES.join(", "),
                        varieties.join(", ")
                    ),
                )
            })
    }

    /// `ri:N` or `ri:N:BG` (the part after `ri:` is `spec`).
    fn from_ri_spec(whole: &str, spec: &str) -> Result<Material> {
        let allowed = format!(
            "use ri:N or ri:N:BG with N in ({}, {}] and BG in [0, {}]",
            Material::RI_ABOVE,
            Material::RI_MAX,
            Material::BG_MAX
        );
        let bad =
            |what: String| Error::invalid("material", format!("`{whole}`: {what}; {allowed}"));
        let parts: Vec<&str> = spec.split(':').collect();
        if parts.len() > 2 {
            return Err(bad("too many fields".into()));
        }
        let num = |s: &str, what: &str| -> Result<f64> {
            s.trim()
                .parse::<f64>()
                .map_err(|_| bad(format!("{what} `{s}` is not a number")))
        };
        let n = num(parts[0], "N")?;
        if !(n > Material::RI_ABOVE && n <= Material::RI_MAX) {
            return Err(bad(format!("N = {} is out of range", shown(n))));
        }
        let (bg, name) = match parts.get(1) {
            None => (Material::GENERIC_BG_PER_N1 * (n - 1.0), format!("ri:{n}")),
            Some(s) => {
                let bg = num(s, "BG")?;
                if !(0.0..=Material::BG_MAX).contains(&bg) {
                    return Err(bad(format!("BG = {} is out of range", shown(bg))));
                }
                (bg, format!("ri:{n}:{bg}"))
            }
        };
        let dispersion = Dispersion::cauchy_through(n, bg);
        let m = Material {
            name,
            dispersion,
            density: DIAMOND.density,
            optic: Optic::Isotropic,
            source: if parts.len() == 1 {
                format!("Cauchy through n_D = {n} with the generic B–G = 0.03 (n_D − 1) = {bg:.4}")
            } else {
                format!("Cauchy through n_D = {n} with the given B–G = {bg}")
            },
            colour: None,
            uniaxial: None,
        };
        let red = m.ri(780.0);
        if red <= 1.0 {
            return Err(bad(format!(
                "with that dispersion the index at 780 nm would be {red:.4}, not above 1"
            )));
        }
        // The index at every traced wavelength must be one the tracers accept, as a fixed index.
        let blue = m.ri(380.0);
        if blue > Material::RI_MAX {
            return Err(bad(format!(
                "with that dispersion the index at 380 nm would be {blue:.4}, above {}",
                Material::RI_MAX
            )));
        }
        Ok(m)
    }

    /// The material a design is traced in when nobody chose one: the material of its index
    /// (GemCad's `I` line, [`Material::for_index`]), or `default`; then the material or colour
    /// its notes name ([`Material::from_design_notes`]). With the lines saying so
    /// (`traced as quartz (the design's index 1.54)`, `traced as ruby (the design's notes)`,
    /// or a malformed note, ignored). The commands and the workbench both choose this way.
    ///
    /// ```
    /// use facetlab::optics::Material;
    /// let (m, notes) = Material::of_design(Some(1.54), [], &Material::diamond());
    /// assert_eq!(m.name, "quartz");
    /// assert_eq!(notes, ["traced as quartz (the design's index 1.54)"]);
    /// let ruby = "Material: ruby".to_string();
    /// let (m, _) = Material::of_design(None, [&ruby], &Material::diamond());
    /// assert_eq!(m.name, "ruby");
    /// assert_eq!(Material::of_design(None, [], &Material::diamond()).0.name, "diamond");
    /// ```
    pub fn of_design<'a>(
        index: Option<f64>,
        notes: impl IntoIterator<Item = &'a String>,
        default: &Material,
    ) -> (Material, Vec<String>) {
        let mut said = Vec::new();
        let base = match index.and_then(|n| Material::for_index(n).map(|m| (n, m))) {
            Some((n, m)) => {
                said.push(m.for_index_note(n));
                m
            }
            None => default.clone(),
        };
        match Material::from_design_notes(notes, &base) {
            Ok(Some(m)) => {
                said.push(format!("traced as {} (the design's notes)", m.name));
                (m, said)
            }
            Ok(None) => (base, said),
            Err(e) => {
                said.push(format!("{e}; ignored"));
                (base, said)
            }
        }
    }

    /// The material a design's notes name, if any: a GemCad title or footnote line
    /// `material: NAME` (a name of [`Material::by_name`], e.g. `F Material: pink-tourmaline`)
    /// and/or `colour: COLOUR` (or `color:`; a user colour as `--colour` takes it, e.g.
    /// `F Colour: #7a3fa0@10mm`), case ignored. A colour note without a material note
    /// colours `base` (the material the design's index gives). `None` when no line names
    /// either; an error (naming the note) when one is malformed. A line `optic axis: DEG[@AZ]`
    /// (`F Optic axis: 90@0`, see [`OpticAxis::parse`](super::OpticAxis::parse)) orients a
    /// uniaxial material's c-axis in the design (and is ignored for any other).
    pub fn from_design_notes<'a>(
        lines: impl IntoIterator<Item = &'a String>,
        base: &Material,
    ) -> Result<Option<Material>> {
        let mut name = None;
        let mut colour = None;
        let mut axis = None;
        for line in lines {
            let t = line.trim();
            let Some((key, value)) = t.split_once(':') else {
                continue;
            };
            match key.trim().to_ascii_lowercase().as_str() {
                "material" if name.is_none() => name = Some(value.trim().to_string()),
                "colour" | "color" if colour.is_none() => colour = Some(value.trim().to_string()),
                "optic axis" | "optic-axis" | "c-axis" if axis.is_none() => {
                    axis = Some(value.trim().to_string())
                }
                _ => {}
            }
        }
        if name.is_none() && colour.is_none() && axis.is_none() {
            return Ok(None);
        }
        let mut m = match &name {
            Some(n) => Material::by_name(n).map_err(|e| match e {
                Error::Invalid { message, .. } => {
                    Error::invalid(format!("the design's note `material: {n}`"), message)
                }
                other => other,
            })?,
            None => base.clone(),
        };
        if let Some(c) = &colour {
            let field = format!("the design's note `colour: {c}`");
            m.choose_colour(
                Some(c),
                None,
                super::body_colour::ColourFields {
                    colour: &field,
                    density: &field,
                },
            )?;
        }
        if let Some(a) = &axis {
            let field = format!("the design's note `optic axis: {a}`");
            let parsed = super::OpticAxis::parse(a, &field)?;
            if let Some(u) = m.uniaxial.as_mut() {
                u.axis = parsed;
            }
        }
        Ok(Some(m))
    }

    /// A fixed refractive index must be above this (1 is vacuum: nothing would refract).
    pub const RI_ABOVE: f64 = 1.0;
    /// The largest fixed refractive index accepted.
    pub const RI_MAX: f64 = 10.0;

    /// The one chooser of a material, for the command line (`--material`, `--ri`) and the
    /// config (`score.material`, `score.ri`): a material by name ([`Material::by_name`]), or a
    /// fixed index in ([`RI_ABOVE`](Material::RI_ABOVE), [`RI_MAX`](Material::RI_MAX)], or
    /// diamond when neither is given. Errors name `fields.material` or `fields.ri`.
    pub fn choose(
        name: Option<&str>,
        ri: Option<f64>,
        fields: MaterialFields<'_>,
    ) -> Result<Material> {
        match (name, ri) {
            (Some(_), Some(_)) => Err(Error::invalid(
                fields.ri,
                format!("give either {} or {}, not both", fields.material, fields.ri),
            )),
            (None, Some(n)) => {
                if n > Material::RI_ABOVE && n <= Material::RI_MAX {
                    Ok(Material::constant(n))
                } else {
                    Err(Error::invalid(
                        fields.ri,
                        format!(
                            "{} is out of range; allowed ({}, {}] (a refractive index)",
                            shown(n),
                            Material::RI_ABOVE,
                            Material::RI_MAX
                        ),
                    ))
                }
            }
            (Some(m), None) => Material::by_name(m).map_err(|e| match e {
                Error::Invalid { message, .. } => Error::invalid(fields.material, message),
                other => other,
            }),
            (None, None) => Ok(Material::diamond()),
        }
    }

    /// How far a table material's n_D may be from a cut's index and still be taken for it
    /// ([`Material::for_index`]).
    pub const FOR_INDEX_TOL: f64 = 0.005;

    /// The material a cut made for refractive index `n` (GemCad's `I` line) is traced in by
    /// default: the table material ([`Material::table`]) whose indices at the D line come
    /// closest to `n`, if within [`FOR_INDEX_TOL`](Material::FOR_INDEX_TOL) (1.54 → quartz,
    /// 1.72 → spinel, 1.77 → sapphire), else `ri:N` (index N with the generic dispersion of
    /// [`Material::by_name`]). A uniaxial stone's indices are those from its ε to its ω: GemCad
    /// gives corundum 1.76, sapphire's ε (1.7600; ω 1.7681), so a design for 1.76 is traced as
    /// sapphire. Of two stones as close, the one whose n_D is closer. `None` for an index `ri:N`
    /// does not accept (N ≤ 1 or above 10).
    ///
    /// ```
    /// use facetlab::optics::Material;
    /// assert_eq!(Material::for_index(1.54).unwrap().name, "quartz");
    /// assert_eq!(Material::for_index(1.76).unwrap().name, "sapphire");
    /// assert_eq!(Material::for_index(1.61).unwrap().name, "ri:1.61");
    /// assert!(Material::for_index(0.9).is_none());
    /// ```
    pub fn for_index(n: f64) -> Option<Material> {
        let listed = Material::table()
            .into_iter()
            .map(|m| (m.index_distance(n), (m.ri_d() - n).abs(), m))
            .filter(|(d, ..)| *d <= Material::FOR_INDEX_TOL + 1e-12)
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)))
            .map(|(.., m)| m);
        listed.or_else(|| Material::by_name(&format!("ri:{n}")).ok())
    }

    /// How far `n` is from this stone's indices at the D line: from n_D, or for a uniaxial
    /// stone from the range between its ε and ω.
    fn index_distance(&self, n: f64) -> f64 {
        let o = self.ri_d();
        let e = self
            .uniaxial
            .as_ref()
            .map_or(o, |u| u.extraordinary.at(super::material::LINE_D_NM));
        let (lo, hi) = (o.min(e), o.max(e));
        (lo - n).max(n - hi).max(0.0)
    }

    /// The line saying how a cut made for index `n` is traced in this material (found by
    /// [`Material::for_index`]): `traced as quartz (the design's index 1.54)`, and when `n` is
    /// further than [`FOR_INDEX_TOL`](Material::FOR_INDEX_TOL) from its n_D (ω), which of its
    /// indices it is: `traced as sapphire (the design's index 1.76: sapphire's ε 1.7600; ω
    /// 1.7681)`.
    pub fn for_index_note(&self, n: f64) -> String {
        let o = self.ri_d();
        match &self.uniaxial {
            Some(u) if (o - n).abs() > Material::FOR_INDEX_TOL + 1e-12 => format!(
                "traced as {} (the design's index {n}: {}'s ε {:.4}; ω {o:.4})",
                self.name,
                self.name,
                u.extraordinary.at(super::material::LINE_D_NM)
            ),
            _ => format!("traced as {} (the design's index {n})", self.name),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_chooser_for_name_index_or_default() {
        let f = MaterialFields {
            material: "material",
            ri: "refractive index",
        };
        assert_eq!(Material::choose(None, None, f).unwrap().name, "diamond");
        assert_eq!(
            Material::choose(Some("cz"), None, f).unwrap().name,
            "cubic-zirconia"
        );
        assert_eq!(
            Material::choose(None, Some(10.0), f).unwrap().ri(500.0),
            10.0
        );
        for bad in [1.0, 0.5, 10.001, f64::NAN, f64::INFINITY] {
            let e = Material::choose(None, Some(bad), f)
                .unwrap_err()
                .to_string();
            assert!(
                e.starts_with("refractive index: ") && e.contains("allowed (1, 10]"),
                "{e}"
            );
        }
        let e = Material::choose(Some("cz"), Some(2.0), f)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("refractive index: give either material or refractive index"),
            "{e}"
        );
        let e = Material::choose(Some("kryptonite"), None, f)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("material: unknown material"), "{e}");
    }

    #[test]
    fn ri_with_generic_or_given_dispersion_round_trips() {
        let m = Material::by_name("ri:1.54").unwrap();
        assert_eq!(m.name, "ri:1.54");
        assert!((m.ri_d() - 1.54).abs() < 1e-12);
        assert!((m.bg_dispersion() - 0.03 * 0.54).abs() < 1e-12);
        let m = Material::by_name("ri:1.76:0.018").unwrap();
        assert_eq!(m.name, "ri:1.76:0.018");
        assert!((m.ri_d() - 1.76).abs() < 1e-12);
        assert!((m.bg_dispersion() - 0.018).abs() < 1e-12);
        assert_eq!(Material::by_name("ri:2:0").unwrap().bg_dispersion(), 0.0);
        // Through the chooser (a config's score.material), errors name the field.
        let f = MaterialFields {
            material: "score.material",
            ri: "score.ri",
        };
        assert_eq!(
            Material::choose(Some("ri:2.0"), None, f).unwrap().ri_d(),
            2.0
        );
        for (bad, needle) in [
            ("ri:", "N `` is not a number"),
            ("ri:abc", "N `abc` is not a number"),
            ("ri:1.0", "N = 1 is out of range"),
            ("ri:11", "out of range"),
            ("ri:1.5:x", "BG `x` is not a number"),
            ("ri:1.5:-0.01", "BG = -0.01 is out of range"),
            ("ri:1.5:0.6", "out of range"),
            ("ri:1.5:0.1:3", "too many fields"),
            ("ri:1.01:0.5", "at 780 nm"),
        ] {
            let e = Material::choose(Some(bad), None, f)
                .unwrap_err()
                .to_string();
            assert!(
                e.starts_with("score.material: ") && e.contains(needle) && e.contains("ri:N:BG"),
                "{bad}: {e}"
            );
        }
    }

    #[test]
    fn unknown_names_list_the_allowed_ones() {
        let e = Material::by_name("unobtainium").unwrap_err().to_string();
        for n in Material::NAMES {
            assert!(e.contains(n), "{n} missing from: {e}");
        }
        assert!(e.contains("ri:N[:BG]"), "{e}");
        assert_eq!(Material::constant(2.0).bg_dispersion(), 0.0);
    }

    #[test]
    fn cut_indices_find_their_stones() {
        for (n, want) in [
            (1.54, "quartz"),
            (1.544, "quartz"),
            (1.72, "spinel"),
            (1.77, "sapphire"),
            (2.42, "diamond"),
        ] {
            assert_eq!(Material::for_index(n).unwrap().name, want, "{n}");
        }
        let m = Material::for_index(1.61).unwrap();
        assert_eq!(m.name, "ri:1.61");
        assert!((m.ri_d() - 1.61).abs() < 1e-9 && m.bg_dispersion() > 0.0);
        assert_eq!(
            Material::for_index(1.54).unwrap().for_index_note(1.54),
            "traced as quartz (the design's index 1.54)"
        );
    }

    #[test]
    fn design_notes_name_a_coloured_material() {
        let lines = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        let base = Material::by_name("quartz").unwrap();
        assert_eq!(
            Material::from_design_notes(
                &lines(&["Designed by A. Cutter", "Angles for quartz"]),
                &base
            )
            .unwrap(),
            None
        );
        let m = Material::from_design_notes(&lines(&["Material: Ruby"]), &base)
            .unwrap()
            .unwrap();
        assert_eq!(m.name, "ruby");
        assert!(m.colour.is_some());
        let m = Material::from_design_notes(&lines(&["colour: #7a3fa0@10mm"]), &base)
            .unwrap()
            .unwrap();
        assert_eq!(m.name, "quartz");
        assert_eq!(m.colour.unwrap().name, "#7a3fa0@10mm");
        let e = Material::from_design_notes(&lines(&["material: kryptonite"]), &base)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("the design's note `material: kryptonite`: unknown material"),
            "{e}"
        );
        let m =
            Material::from_design_notes(&lines(&["Material: ruby", "Optic axis: 90@30"]), &base)
                .unwrap()
                .unwrap();
        let axis = m.uniaxial.unwrap().axis;
        assert_eq!((axis.tilt_deg, axis.azimuth_deg), (90.0, 30.0));
        let e = Material::from_design_notes(&lines(&["Optic axis: 120"]), &base)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("the design's note `optic axis: 120`: "),
            "{e}"
        );
        let e = Material::from_design_notes(&lines(&["Color: mauve"]), &base)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("the design's note `colour: mauve`: "), "{e}");
    }
}
