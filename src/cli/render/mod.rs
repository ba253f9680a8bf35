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
//! in a one-line error naming the flag and what is allowed. The pictures are made by
//! [`facetlab::render::render`]; the sheet (panels, captions, legend) by
//! [`facetlab::plot::render::compose`].
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
use facetlab::document::render::{CutJson, FrameJson};
use facetlab::error::{Error, Result};
use facetlab::optics::Dispersion;
use facetlab::plot::palette::PICTURE_GROUND;
use facetlab::plot::render::{bare, compose, legend_for, Panel, Sheet};
use facetlab::render::pose::{parse_rock, parse_tilt, rocked};
use facetlab::render::{self, Light, RenderOptions, Stats, Tilt};
use rayon::prelude::*;
use std::path::PathBuf;
use std::time::Instant;

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

/// The flags, validated.
#[derive(Clone, Debug)]
pub struct Settings {
    /// Options of the face-up (or `--tilt`) picture.
    pub opts: RenderOptions,
    /// `--rock`: amplitude in degrees and number of frames.
    pub rock: Option<(f64, usize)>,
    /// `--exposure`.
    pub exposure: f64,
}

impl Settings {
    /// The pose of frame `k`: the `--tilt` pose rocked by `DEG·sin(2πk/FRAMES)` toward its
    /// azimuth.
    pub fn frame_tilt(&self, k: usize) -> Tilt {
        match self.rock {
            None => self.opts.tilt,
            Some(rock) => rocked(self.opts.tilt, rock, k),
        }
    }

    /// Number of frames (1 without `--rock`).
    pub fn frames(&self) -> usize {
        self.rock.map_or(1, |r| r.1)
    }
}

/// Largest animation: frames × cuts × size² pixels (about 1.2 GB of 8-bit RGB in memory).
pub const MAX_ANIMATION_PIXELS: f64 = 400e6;

/// Validate the flags into the library's types.
pub fn settings(a: &RenderArgs) -> Result<Settings> {
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
    opts.material = a.material.material()?;
    opts.material.colour = a.colour.colour_for(&opts.material)?;
    a.colour.size()?;
    opts.polarization = a.polarization;
    let rock = a.rock;
    if let Some((deg, _)) = rock {
        if opts.tilt.tilt_deg.abs() + deg > 90.0 {
            return Err(Error::invalid(
                "--rock",
                format!(
                    "rocking {deg}° about the --tilt of {}° would pass 90°; keep |tilt| + DEG <= 90",
                    opts.tilt.tilt_deg
                ),
            ));
        }
    }
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
    Ok(Settings {
        opts,
        rock,
        exposure,
    })
}

fn pct(v: f64) -> String {
    format!("{:.1} %", 100.0 * v)
}

/// The share darker than L* 20 under its name: the extinction in the scores' face-up ISO
/// view, the dark share of any other picture.
fn dark_text(c: &facetlab::render::ColourStats, extinction: &str, dark: &str) -> String {
    match c.extinction {
        Some(e) => format!("{extinction} {}", pct(e)),
        None => format!("{dark} {}", pct(c.dark())),
    }
}

/// The statistics as caption lines (after the name).
pub fn stats_lines(light: Light, s: &Stats) -> Vec<String> {
    let mut lines = stats_lines_of_light(light, s);
    if let Some(c) = s.colour {
        lines.push(format!(
            "L* {:.0} C* {:.0} h {:.0}°, {}, window {}",
            c.l,
            c.c,
            c.h_deg,
            dark_text(&c, "extinct", "dark"),
            pct(c.windowing)
        ));
    }
    lines
}

fn stats_lines_of_light(light: Light, s: &Stats) -> Vec<String> {
    match (light, s.aset, s.fire) {
        (Light::Aset, Some(a), _) => vec![
            format!(
                "blue {:.1}, red {:.1}, green {:.1} %",
                100.0 * a.blue,
                100.0 * a.red,
                100.0 * a.green
            ),
            format!("leak {:.1}, port {:.1} %", 100.0 * a.leak, 100.0 * a.port),
        ],
        (Light::Fire, _, Some(f)) => {
            vec![format!("placement fire {f:.2}, mean {}", pct(s.mean))]
        }
        (Light::IdealScope, _, _) => vec![format!("returned {}", pct(s.mean))],
        (l, _, _) => vec![format!("{} mean {}", l.name(), pct(s.mean))],
    }
}

/// A caption line with the settings that change the picture from the light's defaults: a head
/// shadow (or port/head half-angle) other than the light's default, an exposure other than 1.
pub fn settings_line(opts: &RenderOptions, exposure: f64) -> Option<String> {
    let mut parts = Vec::new();
    let light = opts.light;
    let head = opts.head_shadow();
    if head != light.default_head_shadow_deg() {
        parts.push(match light {
            Light::Aset => format!("port {head}°"),
            Light::IdealScope => format!("head {head}°"),
            _ => format!("head shadow {head}°"),
        });
    }
    if exposure != 1.0 && light.false_colours().is_empty() {
        parts.push(format!("exposure ×{exposure}"));
    }
    (!parts.is_empty()).then(|| parts.join(", "))
}

/// The one-line summary printed per cut.
fn summary(light: Light, s: &Stats) -> String {
    match (light, s.aset, s.fire) {
        (Light::Aset, Some(a), _) => format!(
            "aset blue {} red {} green {} leak {} port {}",
            pct(a.blue),
            pct(a.red),
            pct(a.green),
            pct(a.leak),
            pct(a.port)
        ),
        (Light::Fire, _, Some(f)) => format!("placement fire {f:.3}, mean {}", pct(s.mean)),
        (Light::IdealScope, _, _) => format!("idealscope returned {}", pct(s.mean)),
        (l, _, _) => match s.colour {
            Some(c) => format!(
                "{} mean {}, colour L* {:.1} C* {:.1} h {:.0}°, {}, windowing {}",
                l.name(),
                pct(s.mean),
                c.l,
                c.c,
                c.h_deg,
                dark_text(&c, "extinction", "dark share"),
                pct(c.windowing)
            ),
            None => format!("{} mean {}", l.name(), pct(s.mean)),
        },
    }
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

/// Frame delay of the animation: the whole rock takes about 2.4 s.
fn delay_ms(frames: usize) -> u16 {
    (2400 / frames.max(1)).clamp(20, 1000) as u16
}

/// Run `facetlab render`.
pub fn run(a: &RenderArgs) -> Result<()> {
    if let Some(light) = facetlab::render::photo::PhotoLight::parse(&a.light)? {
        return photo::run(a, light);
    }
    if let Some(flag) = a.photo.first_given() {
        return Err(Error::invalid(
            flag,
            format!(
                "is for photographs; give a photographic --light ({} or env:FILE)",
                facetlab::render::photo::PhotoLight::names().join(", ")
            ),
        ));
    }
    let s = settings(a)?;
    check_outputs(a)?;
    let cuts = a
        .cuts
        .iter()
        .map(|c| super::cuts::load_with_sets(c, &a.set))
        .collect::<Result<Vec<_>>>()?;
    let chosen = a.material.chosen();
    // A design is traced in its own material (GemCad's `I` index) unless one was chosen.
    let (mut materials, notes) = flags::design_materials(&cuts, &s.opts.material, chosen);
    for note in notes {
        eprintln!("{note}");
    }
    let (colour_notes, widths) = a.colour.apply_traced(&cuts, &mut materials, true)?;
    for note in colour_notes {
        eprintln!("{note}");
    }
    let density = a.colour.colour_density;
    for note in a
        .crystal
        .apply(&cuts, &mut materials, density, s.opts.wavelength_nm)?
    {
        eprintln!("{note}");
    }
    let light = s.opts.light;
    let size = s.opts.size;
    let nframes = s.frames();
    // Every frame has the same caption lines (an animation's frames share one size).
    let show_tilt = s.rock.is_some() || s.opts.tilt.tilt_deg != 0.0;
    let note = settings_line(&s.opts, s.exposure);
    let legend = legend_for(light);
    let bar = super::progress::bar(
        (nframes * cuts.len()) as u64,
        a.quiet,
        "{spinner} rendering [{bar:30}] {pos}/{len} pictures, eta {eta}",
    );
    // Frames in parallel (each drawn on its own and collected in order: the same pictures
    // and statistics on any number of threads); an animation's frames are independent.
    let drawn: Vec<(Sheet, Vec<FrameJson>)> = (0..nframes)
        .into_par_iter()
        .map(|k| {
            let tilt = s.frame_tilt(k);
            let mut pictures = Vec::with_capacity(cuts.len());
            let mut frame_stats = Vec::with_capacity(cuts.len());
            for (c, cut) in cuts.iter().enumerate() {
                let t0 = Instant::now();
                let opts = RenderOptions {
                    tilt,
                    material: materials[c].clone(),
                    width_mm: widths[c],
                    ..s.opts.clone()
                };
                let img = render::render(&cut.solid, &opts);
                let rgb = img.to_srgb8(s.exposure, PICTURE_GROUND);
                frame_stats.push(FrameJson::new(
                    k,
                    tilt,
                    &img.stats,
                    t0.elapsed().as_secs_f64(),
                ));
                let mut lines = vec![cut.name.clone()];
                lines.extend(stats_lines(light, &img.stats));
                lines.extend(note.clone());
                if show_tilt {
                    lines.push(render::pose::describe(light, tilt));
                }
                pictures.push((rgb, lines));
                bar.inc(1);
            }
            let panels: Vec<Panel> = pictures
                .iter()
                .map(|(rgb, lines)| Panel {
                    rgb,
                    lines: lines.clone(),
                })
                .collect();
            let sheet = if a.bare {
                bare(&panels, size as u32)
            } else {
                compose(&panels, size as u32, &legend)
            }?;
            Ok((sheet, frame_stats))
        })
        .collect::<Result<Vec<_>>>()?;
    // frames[cut] = per-frame statistics.
    let mut stats: Vec<Vec<FrameJson>> = vec![Vec::with_capacity(nframes); cuts.len()];
    let mut sheets = Vec::with_capacity(nframes);
    for (sheet, frame_stats) in drawn {
        sheets.push(sheet);
        for (c, f) in frame_stats.into_iter().enumerate() {
            stats[c].push(f);
        }
    }
    bar.finish_and_clear();
    let (w, h) = (sheets[0].width, sheets[0].height);
    let frames: Vec<&[u8]> = sheets.iter().map(|f| f.rgb.as_slice()).collect();
    facetlab::io::png::write_rgb8(&a.output, w, h, &frames, delay_ms(nframes))?;
    let out = a.output.display().to_string();
    let ri = match s.opts.material.dispersion {
        Dispersion::Constant(n) => Some(n),
        _ => None,
    };
    let records: Vec<CutJson> = cuts
        .iter()
        .zip(&a.cuts)
        .zip(stats)
        .enumerate()
        .map(|(c, ((cut, input), fr))| {
            let f0 = &fr[0];
            CutJson {
                name: cut.name.clone(),
                input: input.clone(),
                light: light.name(),
                size,
                mean: f0.mean,
                aset: f0.aset,
                fire: f0.fire,
                colour: f0.colour,
                width_mm: materials[c].colour.is_some().then_some(widths[c]),
                tilt_deg: f0.tilt_deg,
                azimuth_deg: f0.azimuth_deg,
                head_shadow_deg: s.opts.head_shadow(),
                material: s.opts.material.name.clone(),
                ri,
                polarization: s.opts.polarization,
                exposure: s.exposure,
                cut_off: f0.cut_off,
                exits: f0.exits,
                elapsed_s: fr.iter().map(|f| f.elapsed_s).sum(),
                output: out.clone(),
                rock_deg: s.rock.map(|r| r.0),
                frames: s.rock.is_some().then_some(fr),
            }
        })
        .collect();
    for r in &records {
        let stats = Stats {
            mean: r.mean,
            aset: r.aset,
            fire: r.fire,
            colour: r.colour,
            ..Stats::default()
        };
        let pose = render::pose::describe(
            light,
            Tilt {
                tilt_deg: r.tilt_deg,
                azimuth_deg: r.azimuth_deg,
            },
        );
        let rock = match (&r.frames, s.rock) {
            (Some(fr), Some((deg, n))) => {
                let lo = fr.iter().map(|f| f.mean).fold(f64::INFINITY, f64::min);
                let hi = fr.iter().map(|f| f.mean).fold(f64::NEG_INFINITY, f64::max);
                format!(
                    ", rocking ±{deg}° toward {}° in {n} frames (mean {}–{})",
                    r.azimuth_deg,
                    pct(lo),
                    pct(hi)
                )
            }
            _ => String::new(),
        };
        println!(
            "{}: {}, {pose}{rock}, {size} px, {:.2} s → {out}",
            r.name,
            summary(light, &stats),
            r.elapsed_s
        );
    }
    if let Some(j) = &a.json {
        let text = if let [one] = records.as_slice() {
            serde_json::to_string_pretty(one)
        } else {
            serde_json::to_string_pretty(&records)
        }
        .map_err(|e| Error::io(j.display().to_string(), e))?;
        facetlab::io::write_atomic(j, text.as_bytes())?;
        println!("statistics → {}", j.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

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
        let s = settings(&parse(&[])).unwrap();
        assert_eq!(s.opts.light, Light::Iso);
        assert_eq!(s.opts.size, 512);
        assert_eq!(s.opts.tilt, Tilt::FACE_UP);
        assert_eq!((s.exposure, s.frames()), (1.0, 1));
        let s = settings(&parse(&[
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
        assert_eq!(delay_ms(24), 100);
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
        let s = settings(&parse(&[
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
        let s = settings(&parse(&["--light", "aset", "--exposure", "2"])).unwrap();
        assert_eq!(settings_line(&s.opts, s.exposure), None);
    }
}
