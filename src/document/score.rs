//! The score document, as `facetlab score --json` writes it: one cut's [`Scores`] under
//! its name with the [`ScoreConfig`] as understood (`settings`), or several cuts' under one
//! `settings`, each optionally with a `verify` record (the photon tracer's [`Check`]s,
//! `facetlab score --verify`): [`score_json`]. [`scores_json`] is the shape with any `verify`
//! record; [`SettingsJson`] the `settings` object; [`score_table`] the same scores as the
//! table `facetlab score` prints; [`batch_line`] and [`batch_error_line`] the lines of
//! `facetlab score --batch`'s JSON Lines.

use crate::metrics::{ScoreConfig, Scores, Tilt};
use crate::optics::{Dispersion, StoneSize};
use crate::verify::Check;
use serde::Serialize;
use std::collections::BTreeMap;

/// A [`ScoreConfig`] as written to JSON: `material`, `ri` (null unless a fixed index),
/// `polarization`, `head_shadow_deg`, `wavelength_nm`, `bands`, `tilts`,
/// `scintillation_tilts`, `resolution`, `split_threshold`, `fire_split_threshold`,
/// `face_up_split_threshold`, `threshold`, `ray_floor`, `narrow_forks`, and for a coloured
/// stone `colour` (`{name, density, source}`) and `size_mm` (`{width}`, `{length}` or
/// `{length, width}`, as given), and for a uniaxial stone `birefringence`
/// ([`BirefringenceJson`](crate::optics::BirefringenceJson)).
#[derive(Serialize)]
pub struct SettingsJson<'a> {
    material: &'a str,
    ri: Option<f64>,
    polarization: bool,
    head_shadow_deg: f64,
    wavelength_nm: f64,
    bands: usize,
    tilts: &'a [Tilt],
    scintillation_tilts: &'a [f64],
    resolution: usize,
    split_threshold: f64,
    fire_split_threshold: f64,
    face_up_split_threshold: f64,
    threshold: f64,
    ray_floor: f64,
    narrow_forks: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    colour: Option<ColourJson<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    size_mm: Option<BTreeMap<&'static str, f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    birefringence: Option<crate::optics::BirefringenceJson>,
}

/// A body colour as the settings name it.
#[derive(Serialize)]
struct ColourJson<'a> {
    name: &'a str,
    density: f64,
    source: &'a str,
}

impl<'a> SettingsJson<'a> {
    /// The settings of `c`.
    pub fn new(c: &'a ScoreConfig) -> Self {
        SettingsJson {
            material: &c.material.name,
            ri: match c.material.dispersion {
                Dispersion::Constant(n) => Some(n),
                _ => None,
            },
            polarization: c.trace.polarization,
            head_shadow_deg: c.head_shadow_deg,
            wavelength_nm: c.wavelength_nm,
            bands: c.bands,
            tilts: &c.tilts,
            scintillation_tilts: &c.scintillation_tilts,
            resolution: c.resolution,
            split_threshold: c.trace.split_threshold,
            fire_split_threshold: c.fire_split_threshold,
            face_up_split_threshold: c.face_up_split_threshold,
            threshold: c.trace.threshold,
            ray_floor: c.trace.ray_floor,
            narrow_forks: c.trace.narrow_forks,
            colour: c.material.colour.as_ref().map(|b| ColourJson {
                name: &b.name,
                density: b.density,
                source: &b.source,
            }),
            birefringence: c.material.birefringence_json(c.wavelength_nm),
            size_mm: c.material.colour.as_ref().map(|_| match c.size {
                StoneSize::Width(w) => BTreeMap::from([("width", w)]),
                StoneSize::Length(l) => BTreeMap::from([("length", l)]),
                StoneSize::LengthWidth(l, w) => BTreeMap::from([("length", l), ("width", w)]),
            }),
        }
    }
}

/// One cut's object: `cut` (its name), the keys of its [`Scores`], then `settings` and
/// `verify` when given.
#[derive(Serialize)]
struct CutJson<'a, V> {
    cut: &'a str,
    #[serde(flatten)]
    scores: &'a Scores,
    #[serde(skip_serializing_if = "Option::is_none")]
    settings: Option<SettingsJson<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    verify: Option<BTreeMap<&'a str, V>>,
}

#[derive(Serialize)]
struct ManyJson<'a, V> {
    settings: SettingsJson<'a>,
    results: Vec<CutJson<'a, V>>,
}

/// The document for `results` scored with `config` (pretty-printed): one cut is a single
/// object with `settings`; several are `{"settings": {...}, "results": [...]}` in the order
/// given. `verify(i)` gives cut `i`'s `verify` record (figure name → value), if any.
pub fn scores_json<'a, V: Serialize>(
    config: &'a ScoreConfig,
    results: &'a [(String, Scores)],
    mut verify: impl FnMut(usize) -> Option<BTreeMap<&'a str, V>>,
) -> serde_json::Result<String> {
    if let [(name, s)] = results {
        serde_json::to_string_pretty(&CutJson {
            cut: name,
            scores: s,
            settings: Some(SettingsJson::new(config)),
            verify: verify(0),
        })
    } else {
        serde_json::to_string_pretty(&ManyJson {
            settings: SettingsJson::new(config),
            results: results
                .iter()
                .enumerate()
                .map(|(i, (n, s))| CutJson {
                    cut: n,
                    scores: s,
                    settings: None,
                    verify: verify(i),
                })
                .collect(),
        })
    }
}

/// One [`Check`] as written: the beam tracer's value, the photon tracer's estimate and its
/// standard error, (beam − photon)/stderr, and the photons per figure and pose.
#[derive(Serialize)]
struct CheckJson {
    beam: f64,
    photon: f64,
    stderr: f64,
    z: f64,
    photons: u64,
}

/// The scores document ([`scores_json`]) with, per cut, its checks (`checks[i]` for cut `i`;
/// none when `checks` is empty) made with `photons` photons per figure.
pub fn score_json(
    config: &ScoreConfig,
    results: &[(String, Scores)],
    checks: &[Vec<Check>],
    photons: u64,
) -> serde_json::Result<String> {
    scores_json(config, results, |i| {
        checks.get(i).map(|cs| {
            cs.iter()
                .map(|c| {
                    (
                        c.name.as_str(),
                        CheckJson {
                            beam: c.beam,
                            photon: c.photon,
                            stderr: c.stderr,
                            z: c.z,
                            photons,
                        },
                    )
                })
                .collect()
        })
    })
}

/// The table printed by `facetlab score`: one row per score, one column per cut.
pub fn score_table(config: &ScoreConfig, results: &[(String, Scores)]) -> String {
    type Row = (&'static str, fn(&Scores) -> f64);
    let rows: [Row; 11] = [
        ("overhead light return", |s| s.overhead_light_return),
        ("brilliance (ISO+COS)/2", |s| s.brilliance),
        ("  brilliance ISO", |s| s.brilliance_iso),
        ("  brilliance COS", |s| s.brilliance_cos),
        ("fire", |s| s.fire),
        ("scintillation", |s| s.scintillation),
        ("ASET blue 75–80°", |s| s.aset.blue),
        ("ASET red 45–75°", |s| s.aset.red),
        ("ASET green 0–45°", |s| s.aset.green),
        ("ASET leak <0°", |s| s.aset.leak),
        ("ASET port 80–90°", |s| s.aset.port),
    ];
    let label_w = rows.iter().map(|r| r.0.chars().count()).max().unwrap_or(0);
    let col_w = results
        .iter()
        .map(|(n, _)| n.chars().count())
        .max()
        .unwrap_or(0)
        .max(8);
    let c = config;
    let mut out = format!(
        "{}, {}, polarization {}, head shadow {}°, {} poses, {} bands\n",
        c.material.name,
        match c.material.dispersion {
            Dispersion::Constant(n) => format!("n = {n}"),
            _ => format!(
                "n = {:.4} at {} nm",
                c.material.ri(c.wavelength_nm),
                c.wavelength_nm
            ),
        },
        if c.trace.polarization { "on" } else { "off" },
        c.head_shadow_deg,
        c.tilts.len(),
        c.bands
    );
    out.push_str(&format!("{:label_w$}", ""));
    for (n, _) in results {
        out.push_str(&format!("  {n:>col_w$}"));
    }
    out.push('\n');
    for (label, f) in rows {
        let pad = label_w - label.chars().count();
        out.push_str(label);
        out.push_str(&" ".repeat(pad));
        for (_, s) in results {
            out.push_str(&format!("  {:>col_w$.4}", f(s)));
        }
        out.push('\n');
    }
    if results.iter().any(|(_, s)| s.colour.is_some()) {
        type ColourRow = (&'static str, fn(&crate::render::ColourStats) -> f64);
        let colour_rows: [ColourRow; 6] = [
            ("colour L*", |c| c.l),
            ("colour C*", |c| c.c),
            ("colour h°", |c| c.h_deg),
            ("  L* spread", |c| c.l_spread),
            ("extinction (L* < 20)", |c| c.dark()),
            ("windowing", |c| c.windowing),
        ];
        for (label, f) in colour_rows {
            out.push_str(&format!("{label:label_w$}"));
            for (_, s) in results {
                match &s.colour {
                    Some(c) => out.push_str(&format!("  {:>col_w$.4}", f(c))),
                    None => out.push_str(&format!("  {:>col_w$}", "-")),
                }
            }
            out.push('\n');
        }
    }
    out
}

/// A scored cut as a line of `facetlab score --batch`'s JSON Lines (without its newline):
/// `line` (its number in the batch file), `input` (the line), `cut` (its name) and the keys of
/// its [`Scores`], as in the score document's per-cut object.
pub fn batch_line(
    line: usize,
    input: &str,
    cut: &str,
    scores: &Scores,
) -> serde_json::Result<String> {
    #[derive(Serialize)]
    struct Scored<'a> {
        line: usize,
        input: &'a str,
        cut: &'a str,
        #[serde(flatten)]
        scores: &'a Scores,
    }
    serde_json::to_string(&Scored {
        line,
        input,
        cut,
        scores,
    })
}

/// A cut that could not be loaded or scored, as a line of `facetlab score --batch`'s JSON
/// Lines: `line`, `input`, `cut` (the line's first word) and `error`.
pub fn batch_error_line(
    line: usize,
    input: &str,
    cut: &str,
    error: &str,
) -> serde_json::Result<String> {
    #[derive(Serialize)]
    struct Failed<'a> {
        line: usize,
        input: &'a str,
        cut: &'a str,
        error: &'a str,
    }
    serde_json::to_string(&Failed {
        line,
        input,
        cut,
        error,
    })
}
