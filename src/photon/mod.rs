//! The photon tracer: the thesis's forward Monte Carlo from the light.
//!
//! Photons leave a square [`Light`] (directed: all parallel to the light's axis; undirected:
//! uniform over the hemisphere in front of it), get a wavelength ([`WavelengthSampling`]) and
//! the material's refractive index at it, and meet the stone's facets. At every surface
//! Fresnel's equations choose reflection or refraction by roulette (with the photon's Stokes
//! vector and Mueller matrices when [`TraceConfig::polarization`] is on, else the unpolarized
//! average); Snell's law gives the new direction; total internal reflection reflects.
//! [`Absorption`] removes photons inside the stone; a depth limit stops the rest.
//!
//! Photons carry unit weight, so the bookkeeping is exact in whole numbers
//! (see [`Counts::check`]):
//!
//! * shot = missed + hit,
//! * hit = exited + absorbed + depth-limited,
//! * exited = the sum over the four face categories = the sum over facets.
//!
//! **Depth.** The surface interactions of a photon are counted, the first hit on the stone
//! included. With `depth: Some(n)` a photon that is still inside the stone after its n-th
//! interaction is counted as depth-limited (the thesis: 6). `depth: None` is "unlimited", with a
//! safety cap of [`UNLIMITED_CAP`] interactions (photons trapped by total internal reflection
//! in a loop would otherwise never end); photons reaching it are also counted as
//! depth-limited.
//!
//! **Determinism.** Work is split into chunks of [`CHUNK`] photons. A chunk traces its photons
//! eight at a time in lanes (one batched exit search serves all eight, so their dependent
//! chains overlap); lane `l` of chunk `c` draws from its own RNG seeded from `(seed, c, l)`
//! (each 64-bit draw giving two 32-bit uniforms), so the order in which its photons finish
//! follows from those streams alone. Tallies are integer counts, so their sum does not depend
//! on the order or the thread count: the same seed gives the same numbers on any number of
//! threads. Chunks are traced in parallel a wave at a time and their counts added in chunk
//! order as each wave finishes (so the float sums of [`trace_weighted`] are the same on any
//! thread count too, and memory does not grow with the photon count). At most
//! [`MAX_PHOTONS`] photons per run.
//!
//! ```
//! use facetlab::photon::{trace, Light, TraceConfig};
//! let cut = facetlab::io::load_cut("tolkowsky").unwrap();
//! let cfg = TraceConfig { photons: 2_000, ..TraceConfig::thesis() };
//! let t = trace(&cut.solid, &Light::directed(0.0), &cfg, None).unwrap();
//! assert_eq!(t.counts.shot, 2_000);
//! assert!(t.light_return().0 > 0.3);
//! ```

mod absorption;
mod beam;
mod crystal;
mod crystal_setup;
mod kernel;
mod reach;
mod solid;
mod tally;
#[cfg(test)]
mod tests;

pub use crate::optics::{Absorption, THESIS_ABSORPTION};
pub use solid::{face_category, TraceSolid};
pub use tally::{share, Counts, Fate, PhotonPath, Tally, CATEGORY_KEYS, CATEGORY_LABELS};

use crate::error::{shown, Error, Result};
use crate::geometry::{DVec3, Polyhedron};
use crate::optics::color::{LAMBDA_MAX, LAMBDA_MIN};
use crate::optics::Material;
use rayon::prelude::*;
use std::time::Instant;

/// Photons per deterministic chunk.
pub const CHUNK: u64 = 8192;

/// The cell of a grid of `cells` cells that `x` (in cell units from the grid's edge) falls
/// in; points on or past the edges (and NaN) fall in the edge cells. The photon kernel's
/// lookups (entry grid, sure-miss cells, exit-angle cells) find their cells with it: `as i32`
/// converts in one instruction and a check, where `as usize` needs more on x86.
#[inline(always)]
fn grid_cell(x: f64, cells: usize) -> usize {
    (x as i32).clamp(0, cells as i32 - 1) as usize
}
/// Interaction cap of the "unlimited" depth mode.
pub const UNLIMITED_CAP: u32 = 100_000;
/// Most photons one run may shoot (or, with `until_hit`, need to hit): 1e11. At the few
/// million photons per second a core traces, that is already hours of work, and the standard
/// error of a share is below 2e-6, far under any difference between cuts that matters.
pub const MAX_PHOTONS: u64 = 100_000_000_000;
/// Chunks traced in parallel before their counts are added (in chunk order) to the total, so
/// memory stays bounded whatever the photon count.
const WAVE: u64 = 1024;
/// The angles of the thesis's rotation sweep, degrees.
pub const ROTATION_ANGLES: [f64; 7] = [0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0];
/// Distance of the thesis's lights from the girdle centre, girdle diameters.
pub const LIGHT_DISTANCE: f64 = 4.0;
/// Side of the thesis's square light, girdle diameters.
pub const LIGHT_SIDE: f64 = 1.5;

/// How photons leave the light.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LightKind {
    /// All parallel to the light's axis.
    Directed,
    /// Uniform over the hemisphere in front of the light (uniform in solid angle).
    Undirected,
}

impl LightKind {
    /// `directed` or `undirected`.
    pub fn name(self) -> &'static str {
        match self {
            LightKind::Directed => "directed",
            LightKind::Undirected => "undirected",
        }
    }
}

/// What `facetlab trace` shines on a stone: one light, or the thesis's rotation sweep
/// ([`rotation_sweep`]) of a kind of light.
#[derive(Clone, Debug, PartialEq)]
pub enum LightChoice {
    /// One light.
    Single(Light),
    /// The rotation sweep with this kind of light.
    Rotate(LightKind),
}

/// Size of the square light.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LightSize {
    /// A square of this side (girdle diameters), centred on [`Light::centre`].
    Side(f64),
    /// The smallest square (in the light's plane, sides along its axes) that covers the
    /// stone's shadow along the light's axis; its centre is moved within the light's plane to
    /// the shadow's centre. Used for directed light: every photon is then aimed at the stone.
    CoverStone,
}

/// A square light.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Light {
    /// Directed or undirected.
    pub kind: LightKind,
    /// Centre of the square.
    pub centre: DVec3,
    /// The direction the light faces (unit; normalised when resolved).
    pub axis: DVec3,
    /// Size of the square.
    pub size: LightSize,
    /// Rotation angle of the sweep (degrees), when the light is one of its positions.
    pub angle: Option<f64>,
    /// Short description for tables and JSON.
    pub label: String,
}

impl Light {
    /// The thesis's overhead light: undirected, a square of side 1.5 D, 4 D above the girdle
    /// centre, facing down.
    pub fn overhead() -> Light {
        Light {
            kind: LightKind::Undirected,
            centre: DVec3::new(0.0, 0.0, LIGHT_DISTANCE),
            axis: DVec3::NEG_Z,
            size: LightSize::Side(LIGHT_SIDE),
            angle: None,
            label: "overhead undirected".into(),
        }
    }

    /// The thesis's off-centre light: the overhead square moved by (−1 D, −1 D) horizontally,
    /// still facing down, undirected.
    pub fn offset() -> Light {
        Light {
            centre: DVec3::new(-1.0, -1.0, LIGHT_DISTANCE),
            label: "off-centre undirected".into(),
            ..Light::overhead()
        }
    }

    /// The thesis's off-centre directed light: the off-centre square, turned to face the
    /// stone's centre (the girdle centre), every photon parallel to that axis.
    pub fn offset_directed() -> Light {
        let centre = DVec3::new(-1.0, -1.0, LIGHT_DISTANCE);
        Light {
            kind: LightKind::Directed,
            centre,
            axis: (-centre).normalize(),
            size: LightSize::Side(LIGHT_SIDE),
            angle: None,
            label: "off-centre directed".into(),
        }
    }

    /// A directed light at position `angle_deg` of the rotation sweep: a parallel beam
    /// covering the stone's shadow. `directed(0.0)` is a beam straight down over the whole
    /// stone, `directed(180.0)` straight up.
    pub fn directed(angle_deg: f64) -> Light {
        Light::rotated(LightKind::Directed, angle_deg)
    }

    /// The light of the rotation sweep at `angle_deg`: it starts straight above the stone and
    /// turns around the x axis (through the girdle centre) toward −y; at 180° it is straight
    /// below. Directed: a beam just covering the stone's shadow. Undirected: the overhead
    /// square (side 1.5 D, 4 D from the girdle centre) turned with it.
    pub fn rotated(kind: LightKind, angle_deg: f64) -> Light {
        let a = angle_deg.to_radians();
        let up = DVec3::new(0.0, -a.sin(), a.cos());
        let (size, name) = match kind {
            LightKind::Directed => (LightSize::CoverStone, "directed"),
            LightKind::Undirected => (LightSize::Side(LIGHT_SIDE), "undirected"),
        };
        Light {
            kind,
            centre: up * LIGHT_DISTANCE,
            axis: -up,
            size,
            angle: Some(angle_deg),
            label: format!("{name} at {angle_deg}°"),
        }
    }

    /// Check the light's numbers (finite centre and axis, positive side).
    pub fn validate(&self) -> Result<()> {
        if !(self.centre.is_finite() && self.axis.is_finite() && self.axis.length() > 1e-12) {
            return Err(Error::invalid(
                "light",
                "centre and axis must be finite, axis non-zero",
            ));
        }
        if let LightSize::Side(s) = self.size {
            if !(s.is_finite() && s > 0.0) {
                return Err(Error::invalid(
                    "light",
                    format!("side {s} must be a positive number"),
                ));
            }
        }
        if let Some(a) = self.angle {
            if !a.is_finite() {
                return Err(Error::invalid("light angle", "must be a number of degrees"));
            }
        }
        Ok(())
    }
}

/// How each photon's wavelength is chosen.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum WavelengthSampling {
    /// Uniform over 380–780 nm (the thesis).
    Uniform,
    /// Weighted by the CIE D65 illuminant over 380–780 nm.
    D65,
    /// Every photon at this wavelength, nm.
    Fixed(f64),
}

impl WavelengthSampling {
    /// `uniform`, `d65` or a wavelength in 380–780 nm (`550`, `550nm`); an error names
    /// `field`.
    ///
    /// ```
    /// use facetlab::photon::WavelengthSampling;
    /// assert_eq!(WavelengthSampling::parse("spectrum", "550nm").unwrap(), WavelengthSampling::Fixed(550.0));
    /// assert!(WavelengthSampling::parse("spectrum", "900").is_err());
    /// ```
    pub fn parse(field: &str, text: &str) -> crate::error::Result<WavelengthSampling> {
        match text.trim().to_ascii_lowercase().as_str() {
            "uniform" => Ok(WavelengthSampling::Uniform),
            "d65" => Ok(WavelengthSampling::D65),
            s => match s.trim_end_matches("nm").parse::<f64>() {
                Ok(l) if (380.0..=780.0).contains(&l) => Ok(WavelengthSampling::Fixed(l)),
                _ => Err(crate::error::Error::invalid(
                    field,
                    format!(
                        "`{text}` is not allowed; use uniform, d65, or a wavelength in 380–780 nm"
                    ),
                )),
            },
        }
    }
}

/// What to trace and how.
#[derive(Clone, Debug)]
pub struct TraceConfig {
    /// Photons to shoot, or (with `until_hit`) photons that must hit the stone.
    pub photons: u64,
    /// Shoot until exactly `photons` have hit the stone (the rotation sweep's rule).
    pub until_hit: bool,
    /// Surface interactions per photon (entry included); `None` is unlimited (capped at
    /// [`UNLIMITED_CAP`]).
    pub depth: Option<u32>,
    /// Absorption model.
    pub absorption: Absorption,
    /// Carry a Stokes vector and use Mueller matrices (true), or the unpolarized average.
    pub polarization: bool,
    /// The stone's material ([`Material::constant`] for a fixed index).
    pub material: Material,
    /// Wavelength sampling.
    pub wavelengths: WavelengthSampling,
    /// Seed of the random numbers.
    pub seed: u64,
    /// Record the paths of the first this-many photons that hit the stone (for pictures).
    pub record_paths: usize,
}

impl TraceConfig {
    /// The thesis's experiment: 1 000 000 photons, depth 6, the flat 0.1 absorption roulette,
    /// diamond with wavelengths uniform over 380–780 nm, seed 1 — with polarization on.
    pub fn thesis() -> TraceConfig {
        TraceConfig {
            photons: 1_000_000,
            until_hit: false,
            depth: Some(6),
            absorption: Absorption::Thesis,
            polarization: true,
            material: Material::diamond(),
            wavelengths: WavelengthSampling::Uniform,
            seed: 1,
            record_paths: 0,
        }
    }

    /// Check every number; errors name the setting (`photon count`, `trace depth`, …; the
    /// binary says which flag sets it).
    pub fn validate(&self) -> Result<()> {
        check_photons(self.photons)?;
        if let Some(d) = self.depth {
            if d == 0 || d > UNLIMITED_CAP {
                return Err(Error::invalid(
                    "trace depth",
                    format!("{d} is out of range; allowed 1..={UNLIMITED_CAP} or `unlimited`"),
                ));
            }
        }
        if let Absorption::Body { width_mm } = self.absorption {
            if !(width_mm.is_finite() && width_mm > 0.0) {
                return Err(Error::invalid(
                    "absorption model",
                    format!("colour:{width_mm}: the stone's width must be a number of mm > 0"),
                ));
            }
            if self.material.colour.is_none() {
                return Err(Error::invalid(
                    "absorption model",
                    format!(
                        "colour: {} has no body colour; choose a coloured material (--material ruby, …) or give --colour",
                        self.material.name
                    ),
                ));
            }
        }
        if let Absorption::Beer(k) = self.absorption {
            if !(k.is_finite() && k >= 0.0) {
                return Err(Error::invalid("absorption model", format!("beer:{k}: the coefficient must be a finite number >= 0 (per girdle diameter)")));
            }
        }
        if let WavelengthSampling::Fixed(l) = self.wavelengths {
            if !(LAMBDA_MIN..=LAMBDA_MAX).contains(&l) {
                return Err(Error::invalid(
                    "fixed wavelength",
                    format!("{l} nm is out of range; allowed 380–780 nm"),
                ));
            }
        }
        for l in [LAMBDA_MIN, LAMBDA_MAX] {
            let n = self.material.ri(l);
            if !(n.is_finite() && n > 1.0 && n <= 10.0) {
                return Err(Error::invalid(
                    "refractive index",
                    format!(
                        "refractive index {} is out of range; allowed (1, 10]",
                        shown(n)
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Check a photon count: at least 1, at most [`MAX_PHOTONS`]; the error names the `photon
/// count` and says why.
pub fn check_photons(photons: u64) -> Result<()> {
    if photons == 0 {
        return Err(Error::invalid("photon count", "must be at least 1"));
    }
    if photons > MAX_PHOTONS {
        return Err(Error::invalid(
            "photon count",
            format!(
                "{photons} is too many; allowed at most {MAX_PHOTONS} (1e11): at a few million photons per second that is already hours, and shares are then known to ±2e-6"
            ),
        ));
    }
    Ok(())
}

/// Trace `cfg.photons` photons from `light` through `solid`. `progress`, if given, is called
/// once per finished chunk with the photons it accounts for (photons shot, or photons hit
/// with `until_hit`), so a caller can drive a progress bar.
pub fn trace(
    solid: &Polyhedron,
    light: &Light,
    cfg: &TraceConfig,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Tally> {
    cfg.validate()?;
    light.validate()?;
    let ts = TraceSolid::new(solid)?;
    let tracer = kernel::Tracer::new(&ts, light, cfg)?;
    let start = Instant::now();
    let counts = if cfg.until_hit {
        run_until_hit(&tracer, cfg.photons, progress)?
    } else {
        run_shot(&tracer, cfg.photons, progress)
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

/// How many exit weights [`trace_weights`] sums at once.
pub const WEIGHTS: usize = 3;

/// Exit weights: [`WEIGHTS`] functions of the exit direction, computed together.
pub type ExitWeights<'a> = dyn Fn(DVec3) -> [f64; WEIGHTS] + Sync + 'a;

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
        run_until_hit(&tracer, cfg.photons, None)?
    } else {
        run_shot(&tracer, cfg.photons, None)
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
    let mut t = trace(solid, light, cfg, progress).map_err(|e| e.context(name))?;
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
    let cfg = TraceConfig {
        until_hit: true,
        ..cfg.clone()
    };
    ROTATION_ANGLES
        .iter()
        .map(|&a| trace_cut(solid, name, &Light::rotated(kind, a), &cfg, progress))
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

fn run_shot(
    tracer: &kernel::Tracer,
    photons: u64,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Counts {
    run_shot_waves(tracer, photons, progress, WAVE)
}

/// [`run_shot`] with `wave` chunks per wave (tests vary it).
fn run_shot_waves(
    tracer: &kernel::Tracer,
    photons: u64,
    progress: Option<&(dyn Fn(u64) + Sync)>,
    wave: u64,
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
) -> Result<Counts> {
    let mut total = Counts::new(tracer.facet_count());
    let mut next = 0u64;
    let mut wave = 1u64;
    loop {
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
