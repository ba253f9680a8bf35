//! `facetlab materials`: the table of stones with their dispersion formulas and sources.

use clap::Args;
use facetlab::document::materials::{rows, Row, SEEN_MM};
use facetlab::error::{Error, Result};
use facetlab::optics::Material;
#[cfg(test)]
use facetlab::optics::Variety;

/// Flags of `facetlab materials`.
#[derive(Debug, Args)]
pub struct MaterialsArgs {
    /// Print a JSON array instead of the table (keys: name, nd, dispersion, formula, source,
    /// ordinary_ray, optic, density, aliases; coloured varieties follow with variety_of,
    /// chromophores and colour — {source, seen_through_mm, hex, lab} or null with
    /// no_spectrum saying why — and, uniaxial ones, colour_e, the E∥c colour in the same form
    /// or null with no_spectrum_e saying why).
    #[arg(long)]
    pub json: bool,
}

fn text(rows: &[Row]) -> String {
    let mut out = format!(
        "{:<19} {:>6} {:>6} {:>5}  {:<17} {:<9} source\n",
        "name", "nD", "B–G", "SG", "index", "formula"
    );
    for r in rows.iter().filter(|r| r.variety.is_none()) {
        let also = if r.aliases.is_empty() {
            String::new()
        } else {
            format!(" [also: {}]", r.aliases.join(", "))
        };
        out += &format!(
            "{:<19} {:>6.4} {:>6.4} {:>5.2}  {:<17} {:<9} {}{also}\n",
            r.name,
            r.nd,
            r.dispersion,
            r.density,
            r.optic,
            r.formula.split_whitespace().next().unwrap_or(""),
            r.source
        );
    }
    out += &format!(
        "\nnD at 589.3 nm; B–G = n(430.8 nm) − n(686.7 nm); SG is the handbook density (carat weights).\n\
         Uniaxial stones are traced birefringent, the ordinary ray ω and the extraordinary ray ε (--birefringence off: the ordinary ray alone); biaxial stones with one index, α.\n\
         --material ri:N: index N with the generic B–G = {} (N − 1); ri:N:BG: index N with B–G dispersion BG (both Cauchy curves).\n\
         --ri N: one fixed index, no dispersion and no fire.\n",
        Material::GENERIC_BG_PER_N1
    );
    out += &format!(
        "\nColoured varieties (--material NAME: the host's index with the variety's body colour; seen through {SEEN_MM} mm under D65):\n"
    );
    for r in rows {
        let Some(v) = &r.variety else { continue };
        match &v.colour {
            Some(c) => {
                out += &format!(
                    "{:<17} {:<11} {}  L* {:>5.1} a* {:>6.1} b* {:>6.1}  {}\n{:<17} {:<11} spectrum: {}\n",
                    r.name, v.variety_of, c.hex, c.lab[0], c.lab[1], c.lab[2], v.chromophores, "", "", c.source
                );
            }
            None => {
                out += &format!(
                    "{:<17} {:<11} no published spectrum: traced colourless (give --colour); {}; {}\n",
                    r.name, v.variety_of, v.no_spectrum, v.chromophores
                );
            }
        }
        match &v.colour_e {
            Some(Some(c)) => {
                out += &format!(
                    "{:<17} {:<11} E∥c {}  L* {:>5.1} a* {:>6.1} b* {:>6.1}  spectrum: {}\n",
                    "", "", c.hex, c.lab[0], c.lab[1], c.lab[2], c.source
                );
            }
            Some(None) => {
                out += &format!("{:<17} {:<11} {}\n", "", "", v.no_spectrum_e);
            }
            None => {}
        }
    }
    out += "Spectra: polarized absorbance of one stone each (the ray the model traces), 10 nm bins, baseline (smallest absorbance) removed, α = ln 10 · A / thickness; --colour-density scales them.\n\
            Uniaxial varieties: the first colour is E⊥c (the ordinary ray ω), the E∥c line the extraordinary ray's (pleochroism: --optic-axis turns the stone between them); without one the e-ray takes the E⊥c spectrum (--colour-e gives one).\n";
    out
}

/// `facetlab materials`.
pub fn run(a: &MaterialsArgs) -> Result<()> {
    let rows = rows();
    if a.json {
        let s = serde_json::to_string_pretty(&rows)
            .map_err(|e| Error::invalid("--json", e.to_string()))?;
        println!("{s}");
    } else {
        print!("{}", text(&rows));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_lists_every_material_with_its_ray() {
        let t = text(&rows());
        for n in Material::NAMES {
            assert!(t.contains(n), "{n}");
        }
        assert!(
            t.contains("the ordinary ray ω and the extraordinary ray ε") && t.contains("ri:N:BG"),
            "{t}"
        );
        // Every coloured variety is listed, with its spectrum's source or the reason it has
        // none.
        for v in Variety::all() {
            let line = t.lines().rfind(|l| l.starts_with(v.name)).unwrap();
            assert!(
                line.contains('#') || line.contains("no published spectrum"),
                "{line}"
            );
        }
        assert!(t.contains("Caltech Mineral Spectroscopy Server"), "{t}");
        // Which uniaxial varieties have an E∥c spectrum, and why the others have none.
        let block = |name: &str| -> Vec<&str> {
            t.lines()
                .skip_while(|l| !l.starts_with(name))
                .take(3)
                .collect()
        };
        for v in ["ruby", "blue-sapphire", "emerald"] {
            assert!(
                block(v).iter().any(|l| l.contains("E∥c #")),
                "{v}: {:?}",
                block(v)
            );
        }
        for v in ["amethyst", "green-tourmaline", "pink-tourmaline"] {
            assert!(
                block(v).iter().any(|l| l.contains("no E∥c")),
                "{v}: {:?}",
                block(v)
            );
        }
        let json = serde_json::to_value(rows()).unwrap();
        let ruby = json
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["name"] == "ruby")
            .unwrap();
        assert_eq!(ruby["variety_of"], "sapphire");
        assert!(ruby["colour"]["hex"].as_str().unwrap().starts_with('#'));
        assert!(ruby["colour_e"]["source"].as_str().unwrap().contains("GIA"));
        let find = |n: &str| {
            json.as_array()
                .unwrap()
                .iter()
                .find(|r| r["name"] == n)
                .unwrap()
        };
        assert!(find("green-tourmaline")["colour_e"].is_null());
        assert!(find("green-tourmaline")["no_spectrum_e"]
            .as_str()
            .unwrap()
            .contains("E∥c"));
        assert!(find("peridot").get("colour_e").is_none()); // biaxial: no such ray
        let diamond = &json[Material::NAMES.len() - 2];
        assert_eq!(diamond["name"], "diamond");
        assert!(diamond.get("variety_of").is_none());
    }
}
