//! `facetlab render CUT... -o FILE.png`: pictures of stones under the lights cutters use, side
//! by side, each captioned with its statistics; `--rock` makes an animated PNG of the stone
//! rocking.
//!
//! ```text
//! facetlab render tolkowsky -o tolkowsky.png                          # ISO, 512 px, face-up
//! facetlab render tolkowsky princess emerald --light aset -o aset.png
//! facetlab render tolkowsky --light fire --tilt 10@45 --size 400 -o fire.png
//! facetlab render tolkowsky --rock 15:24 --json rock.json -o rock.png  # animated PNG
//! facetlab render tolkowsky --size 200 --bare -o stone.png             # 200 × 200, no captions
//! ```
//!
//! Flags are read as text and validated here into [`RenderOptions`], so every bad value ends
//! in a one-line error naming the flag and what is allowed. The pictures, their sheet
//! (panels, captions, legend), the files and the statistics come from one library call,
//! [`facetlab::plot::render::draw`].
//!
//! **JSON** (`--json FILE`, written atomically): one object per cut (an array of them when
//! several cuts are given, in the order given) with `name` (the cut's name), `input` (CUT as
//! given), `light`, `size` (pixels per side), `mean` (the picture's mean over the stone's
//! outline relative to a white diffuser: the pose's brilliance for iso and cos, the returned
//! share for idealscope, luminance for fire), `aset.{blue,red,green,leak,port}` (ASET shares,
//! summing to 1; aset only), `placement_fire` (saturated light in percent under this one
//! placement of the lights, not `score`'s `fire`, which averages 17; fire only), `tilt_deg`,
//! `azimuth_deg` (the pose), `head_shadow_deg` (in use), `material`, `ri` (null unless
//! `--ri`), `polarization`, `exposure`, `cut_off` (share of light below the tracer's
//! thresholds), `exits` (exit beams drawn), `elapsed_s` (rendering time of this cut, all
//! frames), `output` (the PNG written). With `--rock`: `rock_deg` and `frames`, one object per
//! frame with `frame`, `tilt_deg`, `azimuth_deg`, `mean`, `aset`, `placement_fire`, `cut_off`,
//! `exits`, `elapsed_s`; the top-level statistics are frame 0's (the centre of the rock).

mod photo;

use super::flags;
use super::outputs::{cut_files, refuse_overwrite};
use facetlab::error::{Error, Result};
use facetlab::metrics::{NoteKind, StoneChoice};
use facetlab::plot::render::{draw, printed_line, LabPictures, Pictures, Progress, RenderJob};
use facetlab::render::pose::{parse_rock, parse_tilt};
use facetlab::render::{Light, RenderOptions, Tilt};
use std::path::PathBuf;

/// Flags of `facetlab render`.
#[derive(clap::Args, Debug, Clone)]
pub struct RenderArgs {
    /// Cuts to draw side by side: preset names (tolkowsky, princess) or .toml/.asc/.gem/.obj/.stl
    /// files.
    #[arg(required = true, value_name = "CUT")]
    pub cuts: Vec<String>,
    /// Lighting: iso (uniform sky), cos (cosine sky), aset (false colour by the elevation the
    /// light comes from), idealscope (red returned, white leak), hearts (face-down in the
    /// hearts & arrows viewer), arrows (face-up in it), fire (spectral, under spot lights);
    /// or a photograph under a studio rig: tent (light box with a spark light), darkfield
    /// (point lights on black), daylight (sky and sun), office (ceiling panels), ring (ring
    /// light round the lens), studio (the bundled procedural environment map), or
    /// env:FILE (your equirectangular .hdr or .exr environment map).
    #[arg(
        long,
        default_value = "iso",
        value_name = "iso|cos|aset|idealscope|hearts|arrows|fire|tent|darkfield|daylight|office|ring|studio|env:FILE"
    )]
    pub light: String,
    /// Pixels per side of each stone's picture (8–8192); the captions (and a grey margin)
    /// come outside it unless --bare.
    #[arg(
        long,
        default_value = "512",
        value_name = "PX",
        allow_hyphen_values = true,
        value_parser = flags::whole("--size", 8, 8192)
    )]
    pub size: u64,
    /// Tilt the stone DEG degrees (−90 to 90) toward azimuth AZ (degrees from +x, default 0):
    /// `--tilt 10@45`.
    #[arg(long, value_name = "DEG[@AZ]", allow_hyphen_values = true, value_parser = flags::parsed("--tilt", parse_tilt))]
    pub tilt: Option<Tilt>,
    /// Half-angle of the viewer's head shadow, the ASET port, the IdealScope head or the hearts
    /// & arrows viewer's dark tube, degrees (0–60; default 10 for aset and idealscope, 20 for
    /// arrows, 6 for hearts, 0 otherwise).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub head_shadow: Option<String>,
    #[command(flatten)]
    pub material: super::flags::MaterialArgs,
    #[command(flatten)]
    pub colour: super::flags::ColourArgs,
    #[command(flatten)]
    pub crystal: super::flags::CrystalArgs,
    /// Track polarization (on) or use the unpolarized average (off).
    #[arg(long, default_value = "on", value_name = "on|off", action = clap::ArgAction::Set, value_parser = crate::cli::flags::on_off_parser("--polarization"))]
    pub polarization: bool,
    /// Change a parameter: a family's (`--set crown_angle=34.5`) or a design's tier angle
    /// (`--set P1=41.2`). Repeatable; applied to every CUT.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Animated PNG of the stone rocking: frame k tilted DEG·sin(2πk/FRAMES) more toward the
    /// --tilt azimuth; DEG in (0, 60], FRAMES in 2–240; loops forever.
    #[arg(long, value_name = "DEG:FRAMES", allow_hyphen_values = true, value_parser = flags::parsed("--rock", parse_rock))]
    pub rock: Option<(f64, usize)>,
    /// Brightness factor of the iso, cos, hearts, arrows and fire pictures (0.01–100).
    #[arg(
        long,
        default_value = "1",
        value_name = "X",
        allow_hyphen_values = true,
        value_parser = flags::real("--exposure", 0.01, 100.0, "a factor")
    )]
    pub exposure: f64,
    /// Write the statistics as JSON to this file (keys in the README).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Replace -o and --json files that already exist (an input is never replaced).
    #[arg(long)]
    pub force: bool,
    /// The picture to write (.png).
    #[arg(short = 'o', long = "output", value_name = "FILE.png")]
    pub output: PathBuf,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// The stones' pictures alone: no margin, captions or legend (one cut: exactly PX × PX).
    #[arg(long)]
    pub bare: bool,
    #[command(flatten)]
    pub photo: photo::PhotoArgs,
}

/// Largest animation: frames × cuts × size² pixels (about 1.2 GB of 8-bit RGB in memory).
pub const MAX_ANIMATION_PIXELS: f64 = 400e6;

/// Refuse a rock that would tip the stone past 90° from its `--tilt`.
fn check_rock(tilt: Tilt, rock: Option<(f64, usize)>) -> Result<()> {
    if let Some((deg, _)) = rock {
        if tilt.tilt_deg.abs() + deg > 90.0 {
            return Err(Error::invalid(
                "--rock",
                format!(
                    "rocking {deg}° about the --tilt of {}° would pass 90°; keep |tilt| + DEG <= 90",
                    tilt.tilt_deg
                ),
            ));
        }
    }
    Ok(())
}

/// Validate the flags into the library's types: the pictures and the stones.
pub fn settings(a: &RenderArgs) -> Result<(LabPictures, StoneChoice)> {
    let light = Light::parse(a.light.trim().to_ascii_lowercase().as_str()).map_err(|_| {
        Error::invalid(
            "--light",
            format!(
                "`{}` is not allowed; use {}, {} or env:FILE",
                a.light,
                Light::ALL.map(Light::name).join(", "),
                facetlab::render::photo::PhotoLight::names().join(", ")
            ),
        )
    })?;
    let mut opts = RenderOptions::new(light);
    opts.size = a.size as usize;
    if let Some(t) = a.tilt {
        opts.tilt = t;
    }
    opts.head_shadow_deg = a
        .head_shadow
        .as_deref()
        .map(|h| {
            flags::number(
                "--head-shadow",
                h,
                0.0,
                60.0,
                "a half-angle in degrees (0 = none)",
            )
        })
        .transpose()?;
    let mut stone = flags::stone_choice(a.material.material()?, &a.material, &a.colour, None)?;
    opts.material = stone.material.clone();
    opts.polarization = a.polarization;
    let rock = a.rock;
    check_rock(opts.tilt, rock)?;
    if let Some((_, n)) = rock {
        // Every frame of the animation is held in memory until the file is written.
        let pixels = (n * a.cuts.len()) as f64 * (opts.size as f64).powi(2);
        if pixels > MAX_ANIMATION_PIXELS {
            return Err(Error::invalid(
                "--rock",
                format!(
                    "{n} frames of {} picture(s) of {} px would hold {:.0} million pixels; allowed {:.0} million: use fewer frames or a smaller --size",
                    a.cuts.len(),
                    opts.size,
                    pixels / 1e6,
                    MAX_ANIMATION_PIXELS / 1e6
                ),
            ));
        }
    }
    let exposure = a.exposure;
    opts.validate()
        .map_err(|e| flags::picture_to_flags(e, &a.material))?;
    stone.crystal = Some(a.crystal.choice(opts.wavelength_nm));
    Ok((
        LabPictures {
            opts,
            rock,
            exposure,
        },
        stone,
    ))
}

/// Check the outputs before any work: not an input, -o a .png, not a folder, existing files
/// only with --force, folders present and writable.
fn check_outputs(a: &RenderArgs) -> Result<()> {
    let mut outs = vec![("-o", a.output.clone())];
    if let Some(j) = &a.json {
        outs.push(("--json", j.clone()));
    }
    refuse_overwrite(&outs, &cut_files(&a.cuts))?;
    let is_png = a
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return Err(Error::invalid(
            "-o",
            format!(
                "{} does not end in .png; the picture is a PNG (an animated PNG with --rock)",
                a.output.display()
            ),
        ));
    }
    if let Some(j) = &a.json {
        if super::outputs::resolved(j) == super::outputs::resolved(&a.output) {
            return Err(Error::invalid(
                "--json",
                format!("{} is also the -o picture; give another file", j.display()),
            ));
        }
    }
    for (flag, p) in &outs {
        super::outputs::check_new_file(flag, p, a.force)?;
    }
    Ok(())
}

/// The progress bar of `render` (drawn once the stones' notes are said) and those notes.
struct Bar {
    quiet: bool,
    template: &'static str,
    bar: std::sync::OnceLock<indicatif::ProgressBar>,
}

impl Progress for Bar {
    fn note(&self, kind: NoteKind, line: String) {
        flags::say(kind, line)
    }
    fn start(&self, pictures: u64) {
        let _ = self
            .bar
            .set(super::progress::bar(pictures, self.quiet, self.template));
    }
    fn picture(&self) {
        if let Some(b) = self.bar.get() {
            b.inc(1)
        }
    }
    fn finish(&self) {
        if let Some(b) = self.bar.get() {
            b.finish_and_clear()
        }
    }
}

/// Run `facetlab render`.
pub fn run(a: &RenderArgs) -> Result<()> {
    let (pictures, stone) = match facetlab::render::photo::PhotoLight::parse(&a.light)? {
        Some(light) => {
            let (p, stone) = photo::settings(a, light)?;
            photo::check_outputs(a)?;
            if p.frames() > 1 && a.photo.hdr_out.is_some() && a.cuts.len() > 1 {
                eprintln!("note: --hdr-out writes frame 0 of the first cut");
            }
            (Pictures::Photo(p), stone)
        }
        None => {
            if let Some(flag) = a.photo.first_given() {
                return Err(Error::invalid(
                    flag,
                    format!(
                        "is for photographs; give a photographic --light ({} or env:FILE)",
                        facetlab::render::photo::PhotoLight::names().join(", ")
                    ),
                ));
            }
            let (p, stone) = settings(a)?;
            check_outputs(a)?;
            (Pictures::Lab(p), stone)
        }
    };
    let cuts = a
        .cuts
        .iter()
        .map(|c| super::cuts::load_with_sets(c, &a.set))
        .collect::<Result<Vec<_>>>()?;
    let bar = Bar {
        quiet: a.quiet,
        template: match pictures {
            Pictures::Lab(_) => "{spinner} rendering [{bar:30}] {pos}/{len} pictures, eta {eta}",
            Pictures::Photo(_) => {
                "{spinner} photographing [{bar:30}] {pos}/{len} pictures, eta {eta}"
            }
        },
        bar: std::sync::OnceLock::new(),
    };
    let job = RenderJob {
        cuts: &cuts,
        inputs: &a.cuts,
        stone: &stone,
        fields: &flags::STONE_FIELDS,
        pictures: &pictures,
        bare: a.bare,
        output: &a.output,
        json: a.json.as_deref(),
        hdr_out: a.photo.hdr_out.as_deref(),
    };
    let drawn = draw(&job, &bar).map_err(|e| match e {
        Error::Invalid { field, message } if field == "output" => Error::invalid("-o", message),
        other => other,
    })?;
    for c in 0..drawn.len() {
        println!("{}", printed_line(&pictures, &drawn, c));
    }
    if let Some(h) = &a.photo.hdr_out {
        if matches!(pictures, Pictures::Photo(_)) {
            println!("linear picture → {}", h.display());
        }
    }
    if let Some(j) = &a.json {
        println!("statistics → {}", j.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;
    use facetlab::plot::render::{delay_ms, settings_line, stats_lines};
    use facetlab::render::{self, Stats};

    #[derive(clap::Parser)]
    struct Cli {
        #[command(flatten)]
        args: RenderArgs,
    }

    fn parse(extra: &[&str]) -> RenderArgs {
        let mut v = vec!["render", "tolkowsky", "-o", "x.png"];
        v.extend_from_slice(extra);
        Cli::try_parse_from(v).unwrap().args
    }

    /// The line a user sees for `extra`: a typed flag's refusal, else the settings' error.
    fn first_error(extra: &[&str]) -> String {
        let mut v = vec!["render", "tolkowsky", "-o", "x.png"];
        v.extend_from_slice(extra);
        match Cli::try_parse_from(v) {
            Err(e) => crate::cli::flags::refused_value(&e).unwrap(),
            Ok(c) => settings(&c.args).unwrap_err().to_string(),
        }
    }

    #[test]
    fn defaults_and_flags_become_render_options() {
        let (s, _) = settings(&parse(&[])).unwrap();
        assert_eq!(s.opts.light, Light::Iso);
        assert_eq!(s.opts.size, 512);
        assert_eq!(s.opts.tilt, Tilt::FACE_UP);
        assert_eq!((s.exposure, s.frames()), (1.0, 1));
        let (s, _) = settings(&parse(&[
            "--light",
            "ASET",
            "--size",
            "64",
            "--tilt",
            "10@45",
            "--rock",
            "15:24",
            "--head-shadow",
            "12",
            "--ri",
            "1.54",
            "--polarization",
            "off",
        ]))
        .unwrap();
        assert_eq!(s.opts.light, Light::Aset);
        assert_eq!(
            s.opts.tilt,
            Tilt {
                tilt_deg: 10.0,
                azimuth_deg: 45.0
            }
        );
        assert_eq!(s.rock, Some((15.0, 24)));
        assert_eq!(s.opts.head_shadow(), 12.0);
        assert!(!s.opts.polarization && s.opts.material.ri(500.0) == 1.54);
        // A quarter period in: the full amplitude on top of the base tilt.
        assert!((s.frame_tilt(6).tilt_deg - 25.0).abs() < 1e-9);
        assert!((s.frame_tilt(18).tilt_deg + 5.0).abs() < 1e-9);
        assert_eq!(s.frame_tilt(0).azimuth_deg, 45.0);
        assert_eq!(delay_ms(24, false), 100);
    }

    #[test]
    fn bad_flags_are_one_line_naming_the_flag() {
        for (extra, flag) in [
            (&["--light", "sun"][..], "--light"),
            (&["--size", "4"], "--size"),
            (&["--size", "big"], "--size"),
            (&["--tilt", "x"], "--tilt"),
            (&["--tilt", "95"], "--tilt"),
            (&["--tilt", "10@"], "--tilt"),
            (&["--tilt", "10@45@3"], "--tilt"),
            (&["--tilt", "NaN"], "--tilt"),
            (&["--rock", "0:10"], "--rock"),
            (&["--rock", "61:10"], "--rock"),
            (&["--rock", "10:1"], "--rock"),
            (&["--rock", "10:241"], "--rock"),
            (&["--rock", "10"], "--rock"),
            (&["--rock", "40:10", "--tilt", "60"], "--rock"),
            (&["--rock", "10:240", "--size", "2048"], "--rock"),
            (&["--head-shadow", "70"], "--head-shadow"),
            (&["--ri", "0.5"], "--ri"),
            (&["--material", "kryptonite"], "--material"),
            (&["--polarization", "maybe"], "--polarization"),
            (&["--exposure", "0"], "--exposure"),
            (&["--colour", "teal"], "--colour"),
            (&["--colour-density", "2"], "--colour-density"),
            (&["--size-mm", "0"], "--size-mm"),
        ] {
            let e = first_error(extra);
            assert!(e.starts_with(flag), "{extra:?}: {e}");
            assert!(!e.contains('\n'), "{e}");
        }
    }

    #[test]
    fn captions_carry_the_statistics() {
        let s = Stats {
            mean: 0.5,
            aset: Some(render::AsetShares {
                blue: 0.4,
                red: 0.3,
                green: 0.1,
                leak: 0.15,
                port: 0.05,
            }),
            ..Stats::default()
        };
        let l = stats_lines(Light::Aset, &s);
        assert!(
            l[0].contains("blue 40.0") && l[1].contains("port 5.0"),
            "{l:?}"
        );
        assert_eq!(stats_lines(Light::Iso, &s), vec!["iso mean 50.0 %"]);
        let f = Stats {
            fire: Some(0.75),
            ..s
        };
        assert!(stats_lines(Light::Fire, &f)[0].starts_with("placement fire 0.75"));
        let (s, _) = settings(&parse(&[
            "--light",
            "cos",
            "--head-shadow",
            "15",
            "--exposure",
            "2",
        ]))
        .unwrap();
        assert_eq!(
            settings_line(&s.opts, s.exposure).as_deref(),
            Some("head shadow 15°, exposure ×2")
        );
        let (s, _) = settings(&parse(&["--light", "aset", "--exposure", "2"])).unwrap();
        assert_eq!(settings_line(&s.opts, s.exposure), None);
    }
}
