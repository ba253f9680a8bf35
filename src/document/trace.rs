//! The trace document, as `facetlab trace --json` writes it: the keys of a photon [`Tally`]
//! per cut and light, and `settings` (the run as understood: [`settings_json`]). One cut under
//! one light is a single object with `settings` among its keys; several cuts or the rotation
//! sweep are `{"settings": {...}, "results": [...]}`, cut by cut, angle by angle.

use crate::photon::{LightChoice, Tally, TraceConfig};
use serde_json::Value;

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
