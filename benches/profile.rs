//! Smoothness profile of the scores (not a timing benchmark): the round-brilliance start cut
//! of `optim/round-brilliance.toml` (table 0.57, crown 34.0°, girdle 0.025, star 0.5,
//! lower half 0.8) with the pavilion angle swept 40.0° → 41.0° in 0.002° steps (501 cuts),
//! scored with the default [`ScoreConfig`]. Run: `cargo bench --bench profile`.
//!
//! Prints, for brilliance, fire and scintillation (and the other scores), the total variation
//! over the range (`Σ|f(k+1) − f(k)| / (max − min)`: 1 for a monotone profile, large for a
//! noisy one) and the median absolute second difference (`|f(k+1) − 2f(k) + f(k−1)|`: the
//! roughness an optimizer sees on a 0.002° scale), and the total variation over the same range
//! of every 5th and every 25th cut only (`TV@0.01°`, `TV@0.05°`): the profile's own rises and
//! falls at those spacings. A score that genuinely rises and falls over the degree has a
//! total variation above 1 however smooth it is; what the 0.002° figure adds to the 0.05°
//! one is the fine-scale roughness, printed as `excess`. Writes every cut's scores to the CSV file
//! named by the environment variable `FACETLAB_PROFILE_CSV`, or to `target/profile.csv`.
//! `FACETLAB_PROFILE_STEPS` (default 500) sets the number of steps over the same degree, and
//! `FACETLAB_PROFILE_SPLIT` the split threshold of the tilted poses' traces,
//! `FACETLAB_PROFILE_FIRE_SPLIT` that of fire's face-up traces, `FACETLAB_PROFILE_FLOOR` the
//! ray floor, `FACETLAB_PROFILE_FORKS=1` follows narrow beams as forking discs,
//! `FACETLAB_PROFILE_PARTS=brilliance` leaves fire and scintillation out,
//! `FACETLAB_PROFILE_FACE_UP_SPLIT` the face-up trace's split threshold (it splits down to the
//! smallest of this, fire's and the tilted poses'),
//! `FACETLAB_PROFILE_TILTS=face-up` scores the face-up pose only,
//! `FACETLAB_PROFILE_HEAD_SHADOW` sets the viewer's head shadow (default 15°, 0 the open-sky
//! scores), `FACETLAB_PROFILE_BANDS` fire's wavelength bands, `FACETLAB_PROFILE_PLACEMENTS`
//! fire's placements of the spot lights, `FACETLAB_PROFILE_RESOLUTION` the images' pixels per
//! side, `FACETLAB_PROFILE_START` the first pavilion angle (default 40°) and
//! `FACETLAB_PROFILE_DEGREES` the profile's width (default 1°) (for experiments).
//! `FACETLAB_PROFILE_SPLIT=1e-5 FACETLAB_PROFILE_FIRE_SPLIT=3e-7 FACETLAB_PROFILE_BANDS=32` is
//! the smooth setting, `ScoreConfig::smooth`.
//!
//! Then, per pose of the brilliance average, the same two figures for its light return
//! (`(ISO + COS) / 2`). Split finer and finer, a pose's profile converges to the exact one's
//! (consecutive splits' second differences correlate), which is itself rough on this scale:
//! the beam tree's powers are continuous in the cut, but Fresnel's reflectance has an infinite
//! slope at the critical angle, and a beam crosses it at some pavilion angle for each of
//! thousands of facet sequences.

use facetlab::cut::Cut;
use facetlab::metrics::{score, ScoreConfig, Scores};
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::time::Instant;

fn cut(pavilion: f64) -> Cut {
    let v: BTreeMap<String, f64> = [
        ("table", 0.57),
        ("crown_angle", 34.0),
        ("pavilion_angle", pavilion),
        ("girdle", 0.025),
        ("star", 0.5),
        ("lower_half", 0.8),
    ]
    .iter()
    .map(|(k, v)| (k.to_string(), *v))
    .collect();
    Cut::from_family("profile", "round-brilliant", &v).expect("round brilliant")
}

/// Total variation over the range of `f` (all of it) of every `every`-th value of `f`: the
/// profile's own rises and falls at that spacing, without what happens in between.
fn tv_sampled(f: &[f64], every: usize) -> f64 {
    let (lo, hi) = f
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let g: Vec<f64> = f.iter().step_by(every.max(1)).copied().collect();
    let tv: f64 = g.windows(2).map(|w| (w[1] - w[0]).abs()).sum();
    if hi > lo {
        tv / (hi - lo)
    } else {
        0.0
    }
}

/// Total variation over range, median |second difference|, range.
fn roughness(f: &[f64]) -> (f64, f64, f64) {
    let (lo, hi) = f
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let tv: f64 = f.windows(2).map(|w| (w[1] - w[0]).abs()).sum();
    let mut d2: Vec<f64> = f
        .windows(3)
        .map(|w| (w[2] - 2.0 * w[1] + w[0]).abs())
        .collect();
    d2.sort_by(f64::total_cmp);
    let med = if d2.is_empty() { 0.0 } else { d2[d2.len() / 2] };
    let range = hi - lo;
    (if range > 0.0 { tv / range } else { 0.0 }, med, range)
}

fn main() {
    let steps: usize = std::env::var("FACETLAB_PROFILE_STEPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(500);
    let mut cfg = ScoreConfig::default();
    // Experiments: `FACETLAB_PROFILE_SPLIT` overrides the tilted poses' split threshold.
    if let Some(x) = std::env::var("FACETLAB_PROFILE_SPLIT")
        .ok()
        .and_then(|s| s.parse().ok())
    {
        cfg.trace.split_threshold = x;
    }
    // `FACETLAB_PROFILE_FIRE_SPLIT`: fire's face-up traces' split threshold.
    if let Some(x) = std::env::var("FACETLAB_PROFILE_FIRE_SPLIT")
        .ok()
        .and_then(|s| s.parse().ok())
    {
        cfg.fire_split_threshold = x;
    }
    // `FACETLAB_PROFILE_FLOOR`: the ray floor of the tilted poses' and fire's traces.
    if let Some(x) = std::env::var("FACETLAB_PROFILE_FLOOR")
        .ok()
        .and_then(|s| s.parse().ok())
    {
        cfg.trace.ray_floor = x;
    }
    // `FACETLAB_PROFILE_FORKS=1`: narrow beams followed as forking discs.
    if std::env::var("FACETLAB_PROFILE_FORKS").as_deref() == Ok("1") {
        cfg.trace.narrow_forks = true;
    }
    // `FACETLAB_PROFILE_PARTS=brilliance`: brilliance (and the face-up scores) only.
    if std::env::var("FACETLAB_PROFILE_PARTS").as_deref() == Ok("brilliance") {
        cfg.parts.fire = false;
        cfg.parts.scintillation = false;
    }
    // `FACETLAB_PROFILE_FACE_UP_SPLIT`: the face-up trace's split threshold.
    if let Some(x) = std::env::var("FACETLAB_PROFILE_FACE_UP_SPLIT")
        .ok()
        .and_then(|s| s.parse().ok())
    {
        cfg.face_up_split_threshold = x;
    }
    // `FACETLAB_PROFILE_HEAD_SHADOW`: the viewer's head shadow in degrees (default 15; 0 for
    // the open-sky scores).
    if let Some(x) = std::env::var("FACETLAB_PROFILE_HEAD_SHADOW")
        .ok()
        .and_then(|s| s.parse().ok())
    {
        cfg.head_shadow_deg = x;
    }
    // `FACETLAB_PROFILE_BANDS`, `FACETLAB_PROFILE_PLACEMENTS`, `FACETLAB_PROFILE_RESOLUTION`:
    // fire's wavelength bands, its placements of the spot lights and the images' pixels.
    let count = |name: &str| {
        std::env::var(name)
            .ok()
            .and_then(|s| s.parse::<usize>().ok())
    };
    if let Some(x) = count("FACETLAB_PROFILE_BANDS") {
        cfg.bands = x;
    }
    if let Some(x) = count("FACETLAB_PROFILE_PLACEMENTS") {
        cfg.fire_placements = x;
    }
    if let Some(x) = count("FACETLAB_PROFILE_RESOLUTION") {
        cfg.resolution = x;
    }
    // `FACETLAB_PROFILE_TILTS=face-up`: the face-up pose only.
    if std::env::var("FACETLAB_PROFILE_TILTS").as_deref() == Ok("face-up") {
        cfg.tilts = vec![facetlab::metrics::Tilt::FACE_UP];
    }
    // `FACETLAB_PROFILE_DEGREES`: the width of the profile (default 1°, from 40.0°).
    let degrees: f64 = std::env::var("FACETLAB_PROFILE_DEGREES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1.0);
    // `FACETLAB_PROFILE_START`: the profile's first pavilion angle (default 40°).
    let start: f64 = std::env::var("FACETLAB_PROFILE_START")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(40.0);
    let angles: Vec<f64> = (0..=steps)
        .map(|k| start + degrees * k as f64 / steps as f64)
        .collect();
    let t0 = Instant::now();
    let scores: Vec<Scores> = angles
        .par_iter()
        .map(|&p| score(&cut(p).solid, &cfg))
        .collect();
    let dt = t0.elapsed().as_secs_f64();
    println!(
        "profile: pavilion {start:.3}° → {:.3}°, {} cuts, split {:e} (fire {:e}, face-up {:e}), {:.1} s ({:.1} ms/cut on {} threads)",
        start + degrees,
        angles.len(),
        cfg.trace.split_threshold,
        cfg.fire_split_threshold,
        cfg.face_up_split_threshold
            .min(cfg.fire_split_threshold)
            .min(cfg.trace.split_threshold),
        dt,
        dt * 1e3 / angles.len() as f64,
        rayon::current_num_threads()
    );
    type Get = fn(&Scores) -> f64;
    let columns: [(&str, Get); 8] = [
        ("brilliance", |s| s.brilliance),
        ("fire", |s| s.fire),
        ("scintillation", |s| s.scintillation),
        ("brilliance_iso", |s| s.brilliance_iso),
        ("brilliance_cos", |s| s.brilliance_cos),
        ("overhead_light_return", |s| s.overhead_light_return),
        ("aset_blue", |s| s.aset.blue),
        ("aset_leak", |s| s.aset.leak),
    ];
    // The same total variation from every k-th cut only, k such that they are 0.01° and
    // 0.05° apart (when the steps allow): what the profile itself does at those spacings.
    let step_deg = degrees / steps.max(1) as f64;
    let coarse: Vec<(String, Option<usize>)> = [0.01, 0.05]
        .iter()
        .map(|&d: &f64| {
            let k = (d / step_deg).round() as usize;
            (
                format!("TV@{d}°"),
                (k >= 1 && k * 2 <= steps && ((k as f64) * step_deg - d).abs() < 1e-9).then_some(k),
            )
        })
        .collect();
    println!(
        "{:<22} {:>10} {:>10} {:>10} {:>10} {:>12} {:>10} {:>10} {:>8}",
        "score", "min", "max", "range", "TV/range", "med|d2|", coarse[0].0, coarse[1].0, "excess"
    );
    for (name, get) in columns {
        let f: Vec<f64> = scores.iter().map(get).collect();
        if f.iter().all(|x| x.is_nan()) {
            println!("{name:<22} (not computed)");
            continue;
        }
        let (tv, med, range) = roughness(&f);
        let lo = f.iter().copied().fold(f64::INFINITY, f64::min);
        let c: Vec<String> = coarse
            .iter()
            .map(|(_, k)| k.map_or("-".into(), |k| format!("{:.3}", tv_sampled(&f, k))))
            .collect();
        // The fine-scale excess: what the 0.002° total variation adds to the 0.05° one.
        let excess = coarse[1]
            .1
            .map_or("-".into(), |k| format!("{:.3}", tv - tv_sampled(&f, k)));
        println!(
            "{name:<22} {lo:>10.6} {:>10.6} {range:>10.3e} {tv:>10.3} {med:>12.3e} {:>10} {:>10} {excess:>8}",
            lo + range,
            c[0],
            c[1]
        );
    }
    for (i, pose) in scores[0].poses.iter().enumerate() {
        let f: Vec<f64> = scores
            .iter()
            .map(|s| s.poses.get(i).map_or(f64::NAN, |p| 0.5 * (p.iso + p.cos)))
            .collect();
        let (tv, med, range) = roughness(&f);
        println!(
            "pose {:>4.1}° toward {:>5.1}°: range {range:.3e}, TV/range {tv:.3}, med|d2| {med:.3e}",
            pose.tilt_deg, pose.azimuth_deg
        );
    }
    let mut csv = String::from("pavilion_angle");
    for (name, _) in columns {
        let _ = write!(csv, ",{name}");
    }
    csv.push('\n');
    for (p, s) in angles.iter().zip(&scores) {
        let _ = write!(csv, "{p:.4}");
        for (_, get) in columns {
            let _ = write!(csv, ",{:.9}", get(s));
        }
        csv.push('\n');
    }
    let path = std::env::var("FACETLAB_PROFILE_CSV").unwrap_or_else(|_| {
        let dir = std::env::var("CARGO_TARGET_DIR").unwrap_or_else(|_| "target".into());
        format!("{dir}/profile.csv")
    });
    match std::fs::write(&path, csv) {
        Ok(()) => println!("wrote {path}"),
        Err(e) => println!("could not write {path}: {e}"),
    }
}
