//! The runs: [`trace`] and its weighted forms, a named stone ([`trace_cut`]), the rotation
//! sweep; chunks of [`CHUNK`](super::CHUNK) photons traced a wave at a time and added in chunk order.

use super::config::{ExitWeights, TraceConfig, CHUNK, WEIGHTS};
use super::kernel;
use super::light::{Light, LightChoice, LightKind, ROTATION_ANGLES};
use super::solid::TraceSolid;
use super::tally::{Counts, Tally};
use crate::error::{Error, Result};
use crate::geometry::{DVec3, Polyhedron};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// Chunks traced in parallel before their counts are added (in chunk order) to the total, so
/// memory stays bounded whatever the photon count.
pub(super) const WAVE: u64 = 1024;

/// Trace `cfg.photons` photons from `light` through `solid`. `progress`, if given, is called
/// once per finished chunk with the photons it accounts for (photons shot, or photons hit
/// with `until_hit`), so a caller can drive a progress bar.
pub fn trace(
    solid: &Polyhedron,
    light: &Light,
    cfg: &TraceConfig,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Tally> {
    traced(solid, light, cfg, progress, None)
}

/// [`trace`], stopped within a chunk's photons once `stop` is raised (an error then).
fn traced(
    solid: &Polyhedron,
    light: &Light,
    cfg: &TraceConfig,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    stop: Option<&AtomicBool>,
) -> Result<Tally> {
    cfg.validate()?;
    light.validate()?;
    let ts = TraceSolid::new(solid)?;
    let tracer = kernel::Tracer::new(&ts, light, cfg)?;
    let start = Instant::now();
    let counts = if cfg.until_hit {
        run_until_hit(&tracer, cfg.photons, progress, stop)?
    } else {
        run_shot(&tracer, cfg.photons, progress, stop)?
    };
    let elapsed = start.elapsed().as_secs_f64();
    let paths = if cfg.record_paths > 0 {
        tracer.record_paths(
            cfg.record_paths,
            counts.shot,
            cfg.until_hit.then_some(counts.hit),
        )
    } else {
        Vec::new()
    };
    Ok(Tally::new(
        String::new(),
        light,
        &ts,
        counts,
        elapsed,
        paths,
    ))
}

/// The mean exit weight of a [`trace_weighted`] run, per photon that hit the stone.
#[derive(Clone, Debug)]
pub struct WeightedTally {
    /// The ordinary tally (its counts carry the weight sums).
    pub tally: Tally,
    /// Σ weight / photons hit: absorbed and depth-limited photons count as weight 0.
    pub mean: f64,
    /// Standard error of `mean`.
    pub stderr: f64,
}

/// The mean exit weights of a [`trace_weights`] run, per photon that hit the stone.
#[derive(Clone, Debug)]
pub struct WeightsTally {
    /// The ordinary tally (its counts carry the weight sums).
    pub tally: Tally,
    /// Σ weight / photons hit, for each weight: absorbed and depth-limited photons count as 0.
    pub mean: [f64; WEIGHTS],
    /// Standard errors of `mean`.
    pub stderr: [f64; WEIGHTS],
}

/// [`trace`], also summing `weight(d)` over the exit directions `d` of the photons that leave
/// the stone (external reflections included). With directed light from a viewer this is a
/// Monte Carlo estimate of what the viewer sees under an environment of radiance `weight`
/// (reciprocity), the independent check of the beam tracer's brilliance.
pub fn trace_weighted(
    solid: &Polyhedron,
    light: &Light,
    cfg: &TraceConfig,
    weight: &(dyn Fn(DVec3) -> f64 + Sync),
) -> Result<WeightedTally> {
    let t = trace_weights(solid, light, cfg, &|d| [weight(d), 0.0, 0.0])?;
    Ok(WeightedTally {
        tally: t.tally,
        mean: t.mean[0],
        stderr: t.stderr[0],
    })
}

/// [`trace_weighted`] with [`WEIGHTS`] weights summed over the same photons in one run: each
/// mean is what [`trace_weighted`] gives for that weight alone with the same seed, to the bit.
pub fn trace_weights(
    solid: &Polyhedron,
    light: &Light,
    cfg: &TraceConfig,
    weight: &ExitWeights<'_>,
) -> Result<WeightsTally> {
    cfg.validate()?;
    light.validate()?;
    let ts = TraceSolid::new(solid)?;
    let mut tracer = kernel::Tracer::new(&ts, light, cfg)?;
    tracer.exit_weight = Some(weight);
    let start = Instant::now();
    let counts = if cfg.until_hit {
        run_until_hit(&tracer, cfg.photons, None, None)?
    } else {
        run_shot(&tracer, cfg.photons, None, None)?
    };
    let elapsed = start.elapsed().as_secs_f64();
    let n = counts.hit as f64;
    let (mut mean, mut stderr) = ([0.0; WEIGHTS], [0.0; WEIGHTS]);
    if counts.hit > 0 {
        for w in 0..WEIGHTS {
            let m = counts.weight_sum[w] / n;
            let var = (counts.weight_sq[w] / n - m * m).max(0.0);
            (mean[w], stderr[w]) = (m, (var / n).sqrt());
        }
    }
    let tally = Tally::new(String::new(), light, &ts, counts, elapsed, Vec::new());
    Ok(WeightsTally {
        tally,
        mean,
        stderr,
    })
}

/// [`trace`] a named stone (a cut's solid and name); the tally carries the name, and errors
/// start with it.
pub fn trace_cut(
    solid: &Polyhedron,
    name: &str,
    light: &Light,
    cfg: &TraceConfig,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Tally> {
    trace_cut_until(solid, name, light, cfg, progress, None)
}

fn trace_cut_until(
    solid: &Polyhedron,
    name: &str,
    light: &Light,
    cfg: &TraceConfig,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    stop: Option<&AtomicBool>,
) -> Result<Tally> {
    let mut t = traced(solid, light, cfg, progress, stop).map_err(|e| e.context(name))?;
    t.cut = name.to_string();
    Ok(t)
}

/// The thesis's rotation sweep of a named stone: the light at each of [`ROTATION_ANGLES`] (see
/// [`Light::rotated`]), shooting until `cfg.photons` photons have hit the stone at each angle
/// (`cfg.until_hit` is forced on).
pub fn rotation_sweep(
    solid: &Polyhedron,
    name: &str,
    kind: LightKind,
    cfg: &TraceConfig,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Vec<Tally>> {
    sweep_until(solid, name, kind, cfg, progress, None)
}

fn sweep_until(
    solid: &Polyhedron,
    name: &str,
    kind: LightKind,
    cfg: &TraceConfig,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    stop: Option<&AtomicBool>,
) -> Result<Vec<Tally>> {
    let cfg = TraceConfig {
        until_hit: true,
        ..cfg.clone()
    };
    ROTATION_ANGLES
        .iter()
        .map(|&a| trace_cut_until(solid, name, &Light::rotated(kind, a), &cfg, progress, stop))
        .collect()
}

/// A named stone under `light`: one tally for one light ([`trace_cut`]), one per angle of
/// the rotation sweep ([`rotation_sweep`]).
pub fn trace_choice(
    solid: &Polyhedron,
    name: &str,
    light: &LightChoice,
    cfg: &TraceConfig,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Vec<Tally>> {
    match light {
        LightChoice::Single(l) => Ok(vec![trace_cut(solid, name, l, cfg, progress)?]),
        LightChoice::Rotate(k) => rotation_sweep(solid, name, *k, cfg, progress),
    }
}

/// [`trace_choice`] that stops once `stop` is raised (another thread's interrupt): every
/// chunk not yet begun is skipped, so it returns within about one chunk's time per thread,
/// with the error [`STOPPED`] names.
pub fn trace_choice_until(
    solid: &Polyhedron,
    name: &str,
    light: &LightChoice,
    cfg: &TraceConfig,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    stop: &AtomicBool,
) -> Result<Vec<Tally>> {
    match light {
        LightChoice::Single(l) => Ok(vec![trace_cut_until(
            solid,
            name,
            l,
            cfg,
            progress,
            Some(stop),
        )?]),
        LightChoice::Rotate(k) => sweep_until(solid, name, *k, cfg, progress, Some(stop)),
    }
}

/// The setting a stopped run's error names ([`trace_choice_until`]).
pub const STOPPED: &str = "photon run";

/// Whether `stop` is raised.
fn raised(stop: Option<&AtomicBool>) -> bool {
    stop.is_some_and(|s| s.load(Ordering::Relaxed))
}

/// The error of a run stopped by its flag.
fn stopped() -> Error {
    Error::invalid(STOPPED, "stopped before its photons were traced")
}

fn run_shot(
    tracer: &kernel::Tracer,
    photons: u64,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    stop: Option<&AtomicBool>,
) -> Result<Counts> {
    let counts = run_shot_waves(tracer, photons, progress, WAVE, stop);
    if raised(stop) {
        return Err(stopped());
    }
    Ok(counts)
}

/// [`run_shot`] with `wave` chunks per wave (tests vary it); a raised `stop` skips the chunks
/// not yet begun (the counts are then short).
pub(super) fn run_shot_waves(
    tracer: &kernel::Tracer,
    photons: u64,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    wave: u64,
    stop: Option<&AtomicBool>,
) -> Counts {
    let chunks = photons.div_ceil(CHUNK);
    let mut total = Counts::new(tracer.facet_count());
    // Waves of chunks traced in parallel; each wave's counts are added in chunk order as soon
    // as it finishes, so the float sums (exit weights) come out the same on any thread count
    // and at most one wave of counts is held at a time.
    let mut first = 0;
    while first < chunks {
        let last = chunks.min(first + wave);
        let wave: Vec<Counts> = (first..last)
            .into_par_iter()
            .map(|c| {
                if raised(stop) {
                    return Counts::new(tracer.facet_count());
                }
                let n = CHUNK.min(photons - c * CHUNK);
                let counts = tracer.chunk(c, n, None);
                if let Some(p) = progress {
                    p(n);
                }
                counts
            })
            .collect();
        for c in &wave {
            total.add(c);
        }
        if raised(stop) {
            break;
        }
        first = last;
    }
    total
}

/// Shots before giving up on a light that never reaches the stone.
const MISS_GIVE_UP: u64 = 2_000_000;

fn run_until_hit(
    tracer: &kernel::Tracer,
    hits: u64,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    stop: Option<&AtomicBool>,
) -> Result<Counts> {
    let mut total = Counts::new(tracer.facet_count());
    let mut next = 0u64;
    let mut wave = 1u64;
    loop {
        if raised(stop) {
            return Err(stopped());
        }
        let results: Vec<Counts> = (next..next + wave)
            .into_par_iter()
            .map(|c| tracer.chunk(c, CHUNK, None))
            .collect();
        for (i, r) in results.into_iter().enumerate() {
            let need = hits - total.hit;
            if r.hit >= need {
                // The chunk that crosses the target is traced again, stopping at the target.
                let last = tracer.chunk(next + i as u64, CHUNK, Some(need));
                total.add(&last);
                if let Some(p) = progress {
                    p(need);
                }
                return Ok(total);
            }
            if let Some(p) = progress {
                p(r.hit);
            }
            total.add(&r);
        }
        next += wave;
        if total.hit == 0 && total.shot >= MISS_GIVE_UP {
            return Err(Error::invalid(
                "light",
                format!(
                    "no photon hit the stone in {} shots; the light does not face the stone",
                    total.shot
                ),
            ));
        }
        // Size the next wave from the hit rate so far (deterministic: results only).
        let rate = (total.hit.max(1) as f64) / total.shot as f64;
        let want = ((hits - total.hit) as f64 / rate / CHUNK as f64).ceil() as u64;
        wave = want.clamp(1, 64);
    }
}
