//! Parsing of flag values shared by the subcommands; every error is one line naming the flag
//! and what is allowed.

use facetlab::error::{Error, Result};
use facetlab::optics::{Material, MaterialFields};

pub use facetlab::io::text::{count, number};

/// `on`/`off` (also `true`/`false`, `yes`/`no`).
pub fn on_off(flag: &str, s: &str) -> Result<bool> {
    match s.trim().to_ascii_lowercase().as_str() {
        "on" | "true" | "yes" => Ok(true),
        "off" | "false" | "no" => Ok(false),
        _ => Err(Error::invalid(
            flag,
            format!("`{s}` is not allowed; use on or off"),
        )),
    }
}

/// `--material` and `--ri`, shared by the commands that trace (`score`, `render`, `report`,
/// `trace`).
#[derive(Clone, Debug, Default, clap::Args)]
pub struct MaterialArgs {
    /// Material: diamond (default), a name from `facetlab materials`, or ri:N[:BG].
    #[arg(long, value_name = "NAME")]
    pub material: Option<String>,
    /// A fixed refractive index instead of the material's dispersion curve (no fire).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub ri: Option<String>,
}

impl MaterialArgs {
    /// The material the flags name ([`material`]).
    pub fn material(&self) -> Result<Material> {
        material(self.ri.as_deref(), self.material.as_deref())
    }

    /// Whether the user chose a material (else a design is traced in its own).
    pub fn chosen(&self) -> bool {
        self.ri.is_some() || self.material.is_some()
    }

    /// The flag that chose it (`--ri` over `--material`).
    pub fn flag(&self) -> &'static str {
        if self.ri.is_some() {
            "--ri"
        } else {
            "--material"
        }
    }
}

/// The material from `--ri N` or `--material NAME` (diamond when neither is given), chosen by
/// [`Material::choose`] like a config's `score.material`/`score.ri`.
pub fn material(ri: Option<&str>, name: Option<&str>) -> Result<Material> {
    let ri = match ri {
        None => None,
        Some(r) => Some(r.trim().parse::<f64>().map_err(|_| {
            Error::invalid(
                "--ri",
                format!("`{r}` is not a number; give a refractive index"),
            )
        })?),
    };
    Material::choose(
        name,
        ri,
        MaterialFields {
            material: "--material",
            ri: "--ri",
        },
    )
}

/// The material each cut is traced in, and a line (for stderr) per cut traced in its design's
/// material. When the user chose a material (`chosen`), every cut gets `default`; otherwise a
/// design read from a file with an index (GemCad's `I` line) is traced in the material of that
/// index ([`Material::for_index`]: the listed stone within ±0.005, else `ri:N`),
/// and any other cut in `default`.
pub fn design_materials(
    cuts: &[facetlab::cut::Cut],
    default: &Material,
    chosen: bool,
) -> (Vec<Material>, Vec<String>) {
    let mut notes = Vec::new();
    let materials = cuts
        .iter()
        .map(|c| {
            let own = (!chosen)
                .then(|| c.design_ri())
                .flatten()
                .and_then(|n| Material::for_index(n).map(|m| (n, m)));
            match own {
                Some((n, m)) => {
                    notes.push(format!(
                        "{}: {}; --material or --ri overrides",
                        c.name,
                        m.for_index_note(n)
                    ));
                    m
                }
                None => default.clone(),
            }
        })
        .collect();
    (materials, notes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flags_parse_or_name_the_flag() {
        assert_eq!(count("--photons", "2e7", 1, u64::MAX).unwrap(), 20_000_000);
        assert_eq!(
            count("--photons", "20_000_000", 1, u64::MAX).unwrap(),
            20_000_000
        );
        assert!(count("--photons", "1.5", 1, 10)
            .unwrap_err()
            .to_string()
            .starts_with("--photons:"));
        assert!(count("--photons", "0", 1, 10).is_err());
        assert_eq!(
            number("--angle", " 30 ", 0.0, 180.0, "an angle").unwrap(),
            30.0
        );
        assert!(number("--angle", "NaN", 0.0, 180.0, "an angle").is_err());
        assert!(
            !on_off("--polarization", "OFF").unwrap() && on_off("--polarization", "yes").unwrap()
        );
        assert!(on_off("--polarization", "maybe")
            .unwrap_err()
            .to_string()
            .contains("on or off"));
        assert_eq!(material(Some("2.0"), None).unwrap().ri(500.0), 2.0);
        assert!(material(Some("2.0"), Some("cz")).is_err());
        assert!(material(Some("0.9"), None)
            .unwrap_err()
            .to_string()
            .starts_with("--ri:"));
        assert_eq!(material(None, Some("cz")).unwrap().name, "cubic-zirconia");
    }

    #[test]
    fn flag_and_config_accept_the_same_indices() {
        let config = |ri: &str| {
            let text = format!(
                "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30, 38]\n[score]\nri = {ri}\n"
            );
            facetlab::optimize::Config::from_str(&text, "c.toml").map(|c| c.score.material)
        };
        for ri in [
            "0.5", "1", "1.00001", "1.0001", "2.4", "10", "10.0001", "11", "nan", "inf",
        ] {
            let flag = material(Some(ri), None);
            let conf = config(ri);
            assert_eq!(flag.is_ok(), conf.is_ok(), "{ri}: {flag:?} vs {conf:?}");
            match (flag, conf) {
                (Ok(a), Ok(b)) => assert_eq!(a, b, "{ri}"),
                (Err(a), Err(b)) => {
                    let (a, b) = (a.to_string(), b.to_string());
                    assert!(a.starts_with("--ri: "), "{a}");
                    assert!(b.starts_with("c.toml: score.ri: "), "{b}");
                    assert_eq!(
                        a.split_once(": ").unwrap().1,
                        b.split_once("score.ri: ").unwrap().1
                    );
                }
                _ => unreachable!(),
            }
        }
        let e = material(Some("abc"), None).unwrap_err().to_string();
        assert!(e.starts_with("--ri: `abc` is not a number"), "{e}");
    }

    #[test]
    fn design_index_is_mentioned_only_when_it_differs_and_nothing_was_chosen() {
        let mut quartz = facetlab::io::load_cut("tolkowsky").unwrap();
        quartz.record = Some(facetlab::cut::GemcadRecord {
            ri: Some(1.54),
            ..Default::default()
        });
        let mut dia = quartz.clone();
        dia.record = Some(facetlab::cut::GemcadRecord {
            ri: Some(2.418),
            ..Default::default()
        });
        let plain = facetlab::io::load_cut("gia-reference").unwrap();
        let cuts = [quartz, dia, plain];
        let (m, notes) = design_materials(&cuts, &Material::diamond(), false);
        let names: Vec<&str> = m.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["quartz", "diamond", "diamond"]);
        assert_eq!(notes.len(), 2, "{notes:?}");
        assert!(notes[0].contains("traced as quartz (the design's index 1.54)"));
        let (m, notes) = design_materials(&cuts, &Material::cubic_zirconia(), true);
        assert!(notes.is_empty() && m.iter().all(|m| m.name == "cubic-zirconia"));
    }
}
