//! `facetlab trace CUT...`: the thesis's photon experiments, one command each.
//!
//! ```text
//! facetlab trace tolkowsky gia-reference                       # overhead undirected light
//! facetlab trace tolkowsky --light offset                      # off-centre undirected light
//! facetlab trace tolkowsky --light offset-directed             # off-centre directed light
//! facetlab trace tolkowsky --light directed --angle 0          # parallel beam straight down
//! facetlab trace tolkowsky --light directed --rotate           # rotation sweep 0–180° by 30°
//! facetlab trace tolkowsky --photons 2e7 --json out.json --plots results/plots
//! ```
//!
//! Flags are read as text and validated here into the library's types, so every bad value
//! ends in a one-line error naming the flag and what is allowed.
//!
//! **JSON** (`--json FILE`, written atomically). One cut without `--rotate`: a single object
//! with the keys of a [`Tally`] (`photons_shot`, `photons_hit`,
//! `face_categories.{lt45,45_90,90_135,gt135}`, `thesis_light_return`, `absorbed`, `depth_limited`,
//! `exit_angle_cdf` (181 values), `photons_per_second`, their `*_stderr`, `exits_per_facet`,
//! `cut`, `light`, `light_angle`, … — see [`Tally`]) plus `settings` (the
//! run's flags as understood). Several cuts or `--rotate`: `{"settings": {...}, "results":
//! [one such object per cut and angle]}` in the order cut by cut, angle by angle.
//!
//! **Plots** (`--plots DIR`, PNG and SVG of each): `face_categories`, `exit_angle_cdf`,
//! `rotation` (with `--rotate`), and per cut `paths_<cut>_one`, `paths_<cut>_bounces`,
//! `paths_<cut>_wavelength`, `paths_<cut>_no_first_segment`, `facets_<cut>`.

use super::flags;
use facetlab::document::trace::trace_table;
use facetlab::error::{Error, Result};
use facetlab::metrics::{NoteKind, StoneChoice};
use facetlab::photon::{
    self, Absorption, Light, LightChoice, LightKind, Tally, TraceConfig, WavelengthSampling,
};
use facetlab::plot::trace::{TraceJob, TraceSink};
use facetlab::plot::{self, Camera};
use std::path::{Path, PathBuf};

/// Flags of `facetlab trace`.
#[derive(clap::Args, Debug, Clone)]
pub struct TraceArgs {
    /// Cuts to compare: preset names (tolkowsky, gia-reference) or .toml/.asc/.gem/.obj/.stl files.
    #[arg(required = true, value_name = "CUT")]
    pub cuts: Vec<String>,
    /// Light: overhead (undirected, 1.5 D square 4 D above), offset (moved by (−1, −1) D),
    /// offset-directed (the off-centre square as a parallel beam toward the stone), directed
    /// (a parallel beam just covering the stone, turned by --angle).
    #[arg(
        long,
        default_value = "overhead",
        value_name = "overhead|offset|offset-directed|directed",
        value_parser = TraceLight::parse
    )]
    pub light: TraceLight,
    /// Turn the light around the x axis by this many degrees (0 = from above, 180 = from
    /// below); for --light directed and overhead.
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        value_parser = flags::real("--angle", 0.0, 180.0, "degrees")
    )]
    pub angle: Option<f64>,
    /// Rotation sweep: the light at 0°, 30°, …, 180°, each shot until --photons have hit.
    #[arg(long)]
    pub rotate: bool,
    /// Photons to shoot (with --rotate: photons that must hit, per angle); 2e7 and 20_000_000
    /// are accepted.
    #[arg(
        long,
        default_value = "1000000",
        value_name = "N",
        allow_hyphen_values = true,
        value_parser = flags::whole("--photons", 1, u64::MAX)
    )]
    pub photons: u64,
    /// Surface interactions per photon (the entry counts), or `unlimited`.
    #[arg(
        long,
        default_value = "6",
        value_name = "N|unlimited",
        allow_hyphen_values = true,
        value_parser = Depth::parse
    )]
    pub depth: Depth,
    /// Absorption: none, thesis (flat 0.1 per bounce inside), or beer:K (K per girdle diameter).
    #[arg(
        long,
        default_value = "thesis",
        value_name = "none|thesis|beer:K",
        allow_hyphen_values = true,
        value_parser = flags::parsed("--absorption", Absorption::parse)
    )]
    pub absorption: Absorption,
    /// Track polarization with Stokes vectors and Mueller matrices (on) or use the
    /// unpolarized average (off, the thesis).
    #[arg(long, default_value = "on", value_name = "on|off", action = clap::ArgAction::Set, value_parser = super::flags::on_off_parser("--polarization"))]
    pub polarization: bool,
    #[command(flatten)]
    pub material: super::flags::MaterialArgs,
    #[command(flatten)]
    pub crystal: super::flags::CrystalArgs,
    /// Wavelengths: uniform over 380–780 nm (the thesis), weighted by D65, or one fixed
    /// wavelength in nm.
    #[arg(
        long,
        default_value = "uniform",
        value_name = "uniform|d65|NM",
        allow_hyphen_values = true,
        value_parser = flags::parsed("--spectrum", WavelengthSampling::parse)
    )]
    pub spectrum: WavelengthSampling,
    /// Seed of the random numbers (the same seed gives the same numbers on any thread count).
    #[arg(
        long,
        default_value = "1",
        value_name = "N",
        allow_hyphen_values = true,
        value_parser = flags::seed
    )]
    pub seed: u64,
    /// Write the results as JSON to this file.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Replace an existing output file (an input is never replaced, even with --force).
    #[arg(long)]
    pub force: bool,
    /// Write charts and pictures (PNG and SVG) to this folder (created if missing).
    #[arg(long, value_name = "DIR")]
    pub plots: Option<PathBuf>,
    /// Photon paths recorded per cut for the path pictures.
    #[arg(
        long,
        default_value = "400",
        value_name = "N",
        allow_hyphen_values = true,
        value_parser = flags::whole("--paths", 0, 100_000)
    )]
    pub paths: u64,
    /// Camera of the pictures: azimuth,elevation in degrees.
    #[arg(
        long,
        default_value = "30,20",
        value_name = "AZ,EL",
        allow_hyphen_values = true,
        value_parser = parse_camera
    )]
    pub camera: Camera,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// The flags, validated.
#[derive(Clone, Debug)]
pub struct Settings {
    /// The light or the sweep.
    pub light: LightChoice,
    /// Tracer settings.
    pub config: TraceConfig,
    /// Camera of the pictures.
    pub camera: Camera,
}

/// `--light` of `trace`: the thesis's four lights.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TraceLight {
    /// Undirected, the 1.5 D square 4 D above.
    Overhead,
    /// The undirected square moved by (−1, −1) D.
    Offset,
    /// The off-centre square as a parallel beam toward the stone.
    OffsetDirected,
    /// A parallel beam just covering the stone.
    Directed,
}

impl TraceLight {
    /// The value parser of `--light`: a name in any case, else the one-line error naming the
    /// four.
    pub fn parse(s: &str) -> Result<TraceLight> {
        Ok(match s.trim().to_ascii_lowercase().as_str() {
            "overhead" => TraceLight::Overhead,
            "offset" => TraceLight::Offset,
            "offset-directed" => TraceLight::OffsetDirected,
            "directed" => TraceLight::Directed,
            _ => {
                return Err(Error::invalid(
                    "--light",
                    format!(
                        "`{s}` is not allowed; use overhead, offset, offset-directed or directed"
                    ),
                ))
            }
        })
    }
}

/// `--depth`: surface interactions per photon, `None` for `unlimited`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Depth(pub Option<u32>);

impl Depth {
    /// The value parser of `--depth`: a whole number in 1..=[`photon::UNLIMITED_CAP`], or
    /// `unlimited` (also `none`, `inf`).
    pub fn parse(s: &str) -> Result<Depth> {
        Ok(Depth(match s.trim().to_ascii_lowercase().as_str() {
            "unlimited" | "none" | "inf" => None,
            t => Some(
                flags::count("--depth", t, 1, photon::UNLIMITED_CAP as u64).map_err(|_| {
                    Error::invalid(
                        "--depth",
                        format!(
                            "`{s}` is not allowed; give a whole number in 1..={} or `unlimited`",
                            photon::UNLIMITED_CAP
                        ),
                    )
                })? as u32,
            ),
        }))
    }
}

/// Validate the flags into the library's types.
pub fn settings(a: &TraceArgs) -> Result<Settings> {
    let photons = a.photons;
    photon::check_photons(photons)?;
    let depth = a.depth.0;
    let absorption = a.absorption;
    let polarization = a.polarization;
    let material = a.material.material()?;
    let wavelengths = a.spectrum;
    let seed = a.seed;
    let record_paths = a.paths as usize;
    let camera = a.camera;
    let angle = a.angle;
    let light = match (a.light, a.rotate) {
        (TraceLight::Overhead, true) | (TraceLight::Directed, true) if angle.is_some() => {
            return Err(Error::invalid(
                "--angle",
                "--rotate sweeps 0–180° itself; drop --angle",
            ))
        }
        (TraceLight::Overhead, true) => LightChoice::Rotate(LightKind::Undirected),
        (TraceLight::Directed, true) => LightChoice::Rotate(LightKind::Directed),
        (TraceLight::Overhead, false) => match angle {
            None => LightChoice::Single(Light::overhead()),
            Some(x) => LightChoice::Single(Light::rotated(LightKind::Undirected, x)),
        },
        (TraceLight::Directed, false) => LightChoice::Single(Light::directed(angle.unwrap_or(0.0))),
        (offset @ (TraceLight::Offset | TraceLight::OffsetDirected), _) => {
            if a.rotate {
                return Err(Error::invalid(
                    "--rotate",
                    "the rotation sweep is for --light overhead or directed",
                ));
            }
            if angle.is_some() {
                return Err(Error::invalid(
                    "--angle",
                    "is for --light overhead or directed",
                ));
            }
            LightChoice::Single(if offset == TraceLight::Offset {
                Light::offset()
            } else {
                Light::offset_directed()
            })
        }
    };
    let record_paths = if a.plots.is_some() { record_paths } else { 0 };
    let config = TraceConfig {
        photons,
        until_hit: false,
        depth,
        absorption,
        polarization,
        material,
        wavelengths,
        seed,
        record_paths,
    };
    config.validate()?;
    Ok(Settings {
        light,
        config,
        camera,
    })
}

fn parse_camera(s: &str) -> Result<Camera> {
    let parts: Vec<&str> = s.split(',').collect();
    let bad = || {
        Error::invalid("--camera", format!("`{s}` is not allowed; give AZ,EL in degrees, azimuth in [-360, 360], elevation in [-90, 90]"))
    };
    if parts.len() != 2 {
        return Err(bad());
    }
    let az = flags::number("--camera", parts[0], -360.0, 360.0, "degrees").map_err(|_| bad())?;
    let el = flags::number("--camera", parts[1], -90.0, 90.0, "degrees").map_err(|_| bad())?;
    Ok(Camera {
        azimuth_deg: az,
        elevation_deg: el,
    })
}

/// Run `facetlab trace`.
pub fn run(args: &TraceArgs) -> Result<()> {
    let set = settings(args)?;
    facetlab::io::guard::check_document_outputs(
        args.json.as_deref(),
        args.plots.as_deref(),
        &facetlab::io::guard::cut_files(&args.cuts),
        args.force,
    )?;
    let cuts = args
        .cuts
        .iter()
        .map(|c| facetlab::io::load_cut(c))
        .collect::<Result<Vec<_>>>()?;
    // A design is traced in its own material unless the user chose one.
    let mut stone = StoneChoice::new(
        set.config.material.clone(),
        args.material.chosen(),
        None,
        None,
        flags::STONE_FIELDS.colour,
    )?;
    stone.crystal = Some(args.crystal.choice(589.3));
    let job = TraceJob {
        cuts: &cuts,
        inputs: &args.cuts,
        stone: &stone,
        fields: &flags::STONE_FIELDS,
        light: &set.light,
        config: &set.config,
        camera: set.camera,
        json: args.json.as_deref(),
        plots: args.plots.as_deref(),
    };
    let sink = Bar {
        quiet: args.quiet,
        bar: std::sync::OnceLock::new(),
    };
    for stem in plot::trace::trace(&job, &sink)? {
        println!(
            "plot → {} (and .svg)",
            plot::with_ext(&stem, "png").display()
        );
    }
    Ok(())
}

/// The progress bar of `trace` (drawn once the stones' notes are said), the notes, the table
/// and the files written.
struct Bar {
    quiet: bool,
    bar: std::sync::OnceLock<indicatif::ProgressBar>,
}

impl TraceSink for Bar {
    fn note(&self, kind: NoteKind, line: String) {
        flags::say(kind, line)
    }
    fn start(&self, total: u64, unit: &str) {
        let template = format!("{{spinner}} tracing [{{bar:30}}] {{percent:>3}}% {{human_pos}}/{{human_len}} {unit}, eta {{eta}}");
        let _ = self
            .bar
            .set(super::progress::bar(total, self.quiet, &template));
    }
    fn traced(&self, n: u64) {
        if let Some(b) = self.bar.get() {
            b.inc(n)
        }
    }
    fn done(&self, light: &LightChoice, config: &TraceConfig, results: &[Vec<Tally>]) {
        if let Some(b) = self.bar.get() {
            b.finish_and_clear()
        }
        print!("{}", trace_table(light, config, results));
    }
    fn wrote_json(&self, path: &Path) {
        println!("results → {}", path.display());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(clap::Parser)]
    struct Cli {
        #[command(flatten)]
        args: TraceArgs,
    }

    fn parse(extra: &[&str]) -> TraceArgs {
        let mut v = vec!["trace", "tolkowsky"];
        v.extend_from_slice(extra);
        Cli::try_parse_from(v).unwrap().args
    }

    fn err(extra: &[&str]) -> String {
        let mut v = vec!["trace", "tolkowsky"];
        v.extend_from_slice(extra);
        // A typed flag's refusal, else the settings' error, as the user sees either.
        let e = match Cli::try_parse_from(v) {
            Err(e) => crate::cli::flags::refused_value(&e).unwrap(),
            Ok(c) => crate::cli::flags::to_flags(settings(&c.args).unwrap_err()).to_string(),
        };
        assert!(!e.contains('\n'), "one line: {e}");
        e
    }

    #[test]
    fn defaults_are_the_thesis_setup() {
        let s = settings(&parse(&[])).unwrap();
        assert_eq!(s.light, LightChoice::Single(Light::overhead()));
        assert_eq!(s.config.depth, Some(6));
        assert_eq!(s.config.absorption, Absorption::Thesis);
        assert!(s.config.polarization);
        let s = settings(&parse(&[
            "--photons",
            "2e7",
            "--light",
            "directed",
            "--rotate",
            "--depth",
            "unlimited",
            "--absorption",
            "beer:0.5",
            "--ri",
            "2.4",
            "--spectrum",
            "589.3",
        ]))
        .unwrap();
        assert_eq!(s.config.photons, 20_000_000);
        assert_eq!(s.light, LightChoice::Rotate(LightKind::Directed));
        assert_eq!(s.config.depth, None);
        assert_eq!(s.config.absorption, Absorption::Beer(0.5));
        assert_eq!(s.config.wavelengths, WavelengthSampling::Fixed(589.3));
        let s = settings(&parse(&["--absorption", "colour:8", "--material", "ruby"])).unwrap();
        assert_eq!(s.config.absorption, Absorption::Body { width_mm: 8.0 });
        assert!(s.config.material.colour.is_some());
    }

    #[test]
    fn bad_flags_are_rejected_with_one_line_naming_the_flag() {
        for (flags, flag) in [
            (&["--photons", "0"][..], "--photons"),
            (&["--photons", "-5"], "--photons"),
            (&["--photons", "lots"], "--photons"),
            (&["--photons", "1.5"], "--photons"),
            (&["--photons", "1e12"], "--photons"),
            (&["--depth", "0"], "--depth"),
            (&["--depth", "NaN"], "--depth"),
            (&["--absorption", "beer:-1"], "--absorption"),
            (&["--absorption", "some"], "--absorption"),
            (&["--absorption", "colour"], "--absorption"),
            (
                &["--absorption", "colour:0", "--material", "ruby"],
                "--absorption",
            ),
            (&["--polarization", "maybe"], "--polarization"),
            (&["--ri", "0.9"], "--ri"),
            (&["--ri", "nan"], "--ri"),
            (&["--ri", "2.4", "--material", "glass"], "--ri"),
            (&["--material", "unobtainium"], "--material"),
            (&["--angle", "200", "--light", "directed"], "--angle"),
            (&["--angle", "30", "--light", "offset"], "--angle"),
            (&["--angle", "30", "--rotate"], "--angle"),
            (&["--rotate", "--light", "offset"], "--rotate"),
            (&["--light", "sun"], "--light"),
            (&["--spectrum", "200"], "--spectrum"),
            (&["--seed", "x"], "--seed"),
            (&["--camera", "30"], "--camera"),
        ] {
            let e = err(flags);
            assert!(e.starts_with(flag), "{flags:?}: {e}");
        }
    }

    #[test]
    fn unknown_cut_is_an_error_and_writes_nothing() {
        let dir = std::env::temp_dir().join(format!("facetlab-trace-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let json = dir.join("out.json");
        let mut a = parse(&["--photons", "100", "--quiet"]);
        a.cuts = vec!["no-such-cut".into()];
        a.json = Some(json.clone());
        assert!(run(&a).unwrap_err().to_string().contains("no-such-cut"));
        assert!(!json.exists());
        let mut a = parse(&["--photons", "3000", "--quiet", "--light", "directed"]);
        a.json = Some(json.clone());
        run(&a).unwrap();
        let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
        assert_eq!(v["photons_shot"], 3000);
        assert_eq!(v["exit_angle_cdf"].as_array().unwrap().len(), 181);
        for k in ["lt45", "45_90", "90_135", "gt135"] {
            assert!(v["face_categories"][k].as_f64().is_some(), "{k}");
        }
        for k in [
            "photons_hit",
            "thesis_light_return",
            "absorbed",
            "depth_limited",
            "photons_per_second",
        ] {
            assert!(v[k].as_f64().is_some(), "{k}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
