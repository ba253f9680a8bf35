//! The trace document, as `facetlab trace --json` writes it: the keys of a photon [`Tally`]
//! per cut and light, and `settings` (the run as understood: [`settings_json`]). One cut under
//! one light is a single object with `settings` among its keys; several cuts or the rotation
//! sweep are `{"settings": {...}, "results": [...]}`, cut by cut, angle by angle
//! ([`trace_json`]); [`trace_table`] is the table `facetlab trace` prints.

use crate::photon::{
    Absorption, LightChoice, Tally, TraceConfig, WavelengthSampling, CATEGORY_LABELS,
    ROTATION_ANGLES,
};
use serde_json::Value;
use std::fmt::Write;

/// The `settings` object: `cuts` (as given), `light` (its label, or `rotation sweep, KIND`),
/// `rotate`, `photons` and what they count (`photons_counted`: `shot`, or `hit per angle` in
/// the sweep), `depth`, `absorption`, `polarization`, `material`, `spectrum`, `seed`.
pub fn settings_json(light: &LightChoice, config: &TraceConfig, cuts: &[String]) -> Value {
    let c = config;
    let rotate = matches!(light, LightChoice::Rotate(_));
    serde_json::json!({
        "cuts": cuts,
        "light": match light {
            LightChoice::Single(l) => l.label.clone(),
            LightChoice::Rotate(k) => format!("rotation sweep, {}", k.name()),
        },
        "rotate": rotate,
        "photons": c.photons,
        "photons_counted": if rotate { "hit per angle" } else { "shot" },
        "depth": c.depth,
        "absorption": c.absorption,
        "polarization": c.polarization,
        "material": c.material.name,
        "spectrum": c.wavelengths,
        "seed": c.seed,
    })
}

/// The document of `results` (`results[cut]`: one tally, or one per angle of the sweep)
/// traced with `light` and `config` from the cuts given as `cuts`.
pub fn trace_json(
    light: &LightChoice,
    config: &TraceConfig,
    cuts: &[String],
    results: &[Vec<Tally>],
) -> serde_json::Result<Value> {
    let flat: Vec<&Tally> = results.iter().flatten().collect();
    let settings = settings_json(light, config, cuts);
    if let [one] = flat.as_slice() {
        let mut v = serde_json::to_value(one)?;
        if let Some(m) = v.as_object_mut() {
            m.insert("settings".into(), settings);
        }
        Ok(v)
    } else {
        Ok(serde_json::json!({ "settings": settings, "results": flat }))
    }
}

fn pct(v: (f64, f64)) -> String {
    format!("{:6.2}% ±{:.2}", 100.0 * v.0, 100.0 * v.1)
}

/// The table `facetlab trace` prints of `results` (`results[cut]`: one tally, or one per
/// angle of the sweep) traced with `light` and `config`: the settings, then per cut the shares
/// of the photons that hit the stone with their standard errors (for the sweep: the top-face
/// share and the light return at each angle).
pub fn trace_table(light: &LightChoice, config: &TraceConfig, results: &[Vec<Tally>]) -> String {
    let mut out = String::new();
    let c = config;
    let depth = c
        .depth
        .map(|d| d.to_string())
        .unwrap_or_else(|| "unlimited".into());
    let absorption = match c.absorption {
        Absorption::None => "none".to_string(),
        Absorption::Thesis => "thesis (0.1 per bounce)".to_string(),
        Absorption::Beer(k) => format!("Beer–Lambert {k}/D"),
        Absorption::Body { width_mm } => format!("body colour, width {width_mm} mm"),
    };
    let spectrum = match c.wavelengths {
        WavelengthSampling::Uniform => "uniform 380–780 nm".to_string(),
        WavelengthSampling::D65 => "D65".to_string(),
        WavelengthSampling::Fixed(l) => format!("{l} nm"),
    };
    let _ = writeln!(
 out,
        "material {}, depth {depth}, absorption {absorption}, polarization {}, spectrum {spectrum}, seed {}",
        c.material.name,
        if c.polarization { "on" } else { "off" },
        c.seed
    );
    let w = results
        .iter()
        .map(|r| r[0].cut.chars().count())
        .max()
        .unwrap_or(0)
        .max(16)
        + 2;
    let header = |label: &str| {
        let mut s = format!("{label:<24}");
        for r in results {
            s += &format!("{:>w$}", r[0].cut);
        }
        s
    };
    match light {
        LightChoice::Single(l) => {
            let _ = writeln!(
                out,
                "light: {}; shares of photons that hit the stone ± standard error",
                l.label
            );
            let _ = writeln!(out, "{}", header(""));
            let mut row = |label: &str, f: &dyn Fn(&Tally) -> String| {
                let mut s = format!("{label:<24}");
                for r in results {
                    s += &format!("{:>w$}", f(&r[0]));
                }
                let _ = writeln!(out, "{s}");
            };
            row("photons shot", &|t| t.counts.shot.to_string());
            row("photons hit", &|t| t.counts.hit.to_string());
            for (k, label) in CATEGORY_LABELS.iter().enumerate() {
                row(&format!("exit faces {label}"), &|t| pct(t.category(k)));
            }
            row("thesis light return (up)", &|t| pct(t.light_return()));
            row("absorbed", &|t| pct(t.absorbed()));
            row("depth-limited", &|t| pct(t.depth_limited()));
            row("median exit angle", &|t| {
                let (cdf, _) = t.exit_angle_cdf();
                cdf.iter()
                    .position(|&v| v >= 0.5)
                    .map(|k| format!("{k}°"))
                    .unwrap_or_else(|| "–".into())
            });
            row("interactions per photon", &|t| {
                format!("{:.2}", t.mean_interactions())
            });
            row("photons per second", &|t| {
                format!("{:.3e}", t.photons_per_second())
            });
        }
        LightChoice::Rotate(k) => {
            let _ = writeln!(
                out,
                "rotation sweep, {} light; {} photons hit per angle; shares ± standard error",
                k.name(),
                c.photons
            );
            for (title, f) in [
                (
                    "exit faces < 45°",
                    &(|t: &Tally| pct(t.category(0))) as &dyn Fn(&Tally) -> String,
                ),
                ("thesis light return (up)", &|t: &Tally| {
                    pct(t.light_return())
                }),
            ] {
                let _ = writeln!(out, "{}", header(title));
                for (i, a) in ROTATION_ANGLES.iter().enumerate() {
                    let mut s = format!("{:<24}", format!("  {a}°"));
                    for r in results {
                        s += &format!("{:>w$}", f(&r[i]));
                    }
                    let _ = writeln!(out, "{s}");
                }
            }
        }
    }
    out
}
