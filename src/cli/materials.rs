//! `facetlab materials`: the table of stones with their dispersion formulas and sources.

use clap::Args;
use facetlab::error::{Error, Result};
use facetlab::optics::Material;
use serde::Serialize;

/// Flags of `facetlab materials`.
#[derive(Debug, Args)]
pub struct MaterialsArgs {
    /// Print a JSON array instead of the table (keys: name, nd, dispersion, formula, source,
    /// ordinary_ray, optic, density, aliases).
    #[arg(long)]
    pub json: bool,
}

/// One material as listed; `dispersion` is the B–G dispersion n(430.8 nm) − n(686.7 nm).
#[derive(Debug, Serialize)]
struct Row {
    name: String,
    nd: f64,
    dispersion: f64,
    ordinary_ray: bool,
    optic: &'static str,
    density: f64,
    aliases: &'static [&'static str],
    formula: String,
    source: String,
}

fn rows() -> Vec<Row> {
    Material::table()
        .into_iter()
        .map(|m| Row {
            nd: m.ri_d(),
            dispersion: m.bg_dispersion(),
            ordinary_ray: m.optic.ordinary_ray(),
            optic: m.optic.label(),
            density: m.density,
            aliases: m.aliases(),
            formula: m.formula(),
            source: m.source.clone(),
            name: m.name,
        })
        .collect()
}

fn text(rows: &[Row]) -> String {
    let mut out = format!(
        "{:<19} {:>6} {:>6} {:>5}  {:<17} {:<9} source\n",
        "name", "nD", "B–G", "SG", "index", "formula"
    );
    for r in rows {
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
         Birefringent stones are traced with one index: uniaxial stones the ordinary ray ω, biaxial stones α.\n\
         --material ri:N: index N with the generic B–G = {} (N − 1); ri:N:BG: index N with B–G dispersion BG (both Cauchy curves).\n\
         --ri N: one fixed index, no dispersion and no fire.\n",
        Material::GENERIC_BG_PER_N1
    );
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
            t.contains("ordinary ray (ω)") && t.contains("ri:N:BG"),
            "{t}"
        );
    }
}
