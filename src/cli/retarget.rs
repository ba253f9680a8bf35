//! `facetlab retarget CUT --ri N [--material NAME] -o OUT` (either flag alone, or both when they agree): adapt a design to another index,
//! by the tangent-ratio rule and by an optimized pair of ratios that restores the design's
//! light return at the new index ([`facetlab::optimize::retarget`], a search over the ratios
//! of [`facetlab::cut::retarget`]); a design without a family also gets an optimized-tiers
//! variant (every tier angle that can turn alone searched with the meets kept). All are
//! reported; the better optimized one is written (the rule's with `--tangent-only`).

use super::flags;
use facetlab::error::{Error, Result};
use facetlab::io;
use facetlab::io::guard::{check_new_file, cut_files, refuse_overwrite, setting};
use facetlab::metrics::ScoreConfig;
use facetlab::optics::Material;
use std::path::PathBuf;

/// Flags of `facetlab retarget`.
#[derive(clap::Args, Debug, Clone)]
pub struct RetargetArgs {
    /// The design: a preset name or a .toml/.asc/.gem/.obj/.stl file.
    #[arg(value_name = "CUT")]
    // A String on purpose: a preset's name or a file's path.
    pub cut: String,
    /// The new refractive index (n_D, 1–10), with a generic dispersion (as `ri:N`).
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = flags::real("--ri", 1.0001, 10.0, "a refractive index"))]
    pub ri: Option<f64>,
    /// The new material by name (see `facetlab materials`).
    #[arg(long, value_name = "NAME")]
    // A String on purpose: with --ri, the material must have that index (checked together).
    pub material: Option<String>,
    /// The index the design was cut for (default: the file's `I` index, else diamond's).
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = flags::real("--from", 1.0001, 10.0, "a refractive index"))]
    pub from: Option<f64>,
    /// Write the tangent-ratio variant instead of the better optimized one (ratios, or a
    /// design's tiers).
    #[arg(long)]
    pub tangent_only: bool,
    /// Replace -o if it exists (an input is never replaced).
    #[arg(long)]
    pub force: bool,
    /// The retargeted design (.asc, .gem, .toml, .obj, .stl or .svg, by extension).
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub output: PathBuf,
    #[command(flatten)]
    pub head: flags::HeadShadowArgs,
}

/// Run `facetlab retarget`.
pub fn run(a: &RetargetArgs) -> Result<()> {
    let to = match (a.ri, &a.material) {
        (Some(n), None) => Material::by_name(&format!("ri:{n}"))
            .map_err(|e| Error::invalid("--ri", e.to_string()))?,
        (None, Some(m)) => Material::by_name(m)?,
        (Some(n), Some(m)) => {
            // Both: the material, which must have that index.
            let mat = Material::by_name(m)?;
            if (mat.ri_d() - n).abs() > 0.01 {
                return Err(Error::invalid(
                        "--ri",
                        format!(
                            "{n} is not the index of {} (n_D {:.4}); give one of --ri and --material, or matching ones",
                            mat.name,
                            mat.ri_d()
                        ),
                    ));
            }
            mat
        }
        (None, None) => {
            return Err(Error::invalid(
                "--ri",
                "give the new index with --ri N, a material with --material NAME, or both",
            ))
        }
    };
    refuse_overwrite(
        &[(setting::OUTPUT, a.output.clone())],
        &cut_files(std::slice::from_ref(&a.cut)),
    )?;
    let ext = a
        .output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if !(ext == "svg" || io::CUT_FORMATS.contains(&ext.as_str())) {
        return Err(Error::invalid(
            "-o",
            format!(
                "cannot write `.{ext}`; allowed extensions: .asc, .gem, .toml, .obj, .stl, .svg"
            ),
        ));
    }
    check_new_file(setting::OUTPUT, &a.output, a.force)?;
    let cut = super::cuts::load_with_sets(&a.cut, &[])?;
    let from = match a.from {
        Some(f) => f,
        None => cut
            .design_ri()
            .unwrap_or_else(|| Material::diamond().ri_d()),
    };
    let full = ScoreConfig {
        head_shadow_deg: a.head.head_shadow,
        ..ScoreConfig::default()
    };
    let r = facetlab::optimize::retarget(&cut, from, &to, &full)?;
    println!(
        "{}: cut for n = {from:.4}, retargeted to {} (n = {:.4}); brilliance at the new index:",
        cut.name, r.material, r.to_ri
    );
    for v in &r.variants {
        println!(
            "  {:<15} crown {:6.2}°  pavilion {:6.2}°  tangent ratios {:.4} / {:.4}  brilliance {:.4}",
            v.label, v.crown_angle, v.pavilion_angle, v.k_crown, v.k_pavilion, v.brilliance
        );
    }
    if let Some(t) = &r.tiers {
        if let Some(why) = &t.skipped {
            println!("  (no optimized-tiers variant: {why})");
        } else {
            let turned: Vec<String> = t
                .free
                .iter()
                .map(|k| format!("{k} {:.2}°", t.angles[k]))
                .collect();
            println!(
                "  optimized-tiers: from the {} angles, {} quick scores; searched {}",
                t.start,
                t.evaluations,
                if turned.is_empty() {
                    "none".to_string()
                } else {
                    turned.join(", ")
                }
            );
            // One line per reason: the tiers it holds.
            let mut whys: Vec<(&str, Vec<&str>)> = Vec::new();
            for f in &t.fixed {
                match whys.iter_mut().find(|(w, _)| *w == f.why) {
                    Some((_, tiers)) => tiers.push(&f.tier),
                    None => whys.push((&f.why, vec![&f.tier])),
                }
            }
            for (why, tiers) in whys {
                println!("    left fixed: {} ({why})", tiers.join(", "));
            }
        }
    }
    let chosen = if a.tangent_only {
        &r.variants[1]
    } else {
        r.best()
    };
    for w in r.warnings(chosen) {
        eprintln!("warning: {w}");
    }
    let out = r.file_cut(chosen);
    let bytes: Vec<u8> = match ext.as_str() {
        "svg" => facetlab::plot::diagram::diagram(&out).into_bytes(),
        e => io::write_cut(&out, e)?,
    };
    io::write_atomic(&a.output, &bytes)?;
    println!(
        "wrote {} (the {} variant)\n  its note: {}",
        a.output.display(),
        chosen.label,
        r.footnote(chosen)
    );
    Ok(())
}
