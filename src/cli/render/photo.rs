//! `facetlab render CUT... --light tent|darkfield|daylight|office|ring|studio|env:FILE`:
//! photographs of stones ([`facetlab::render::photo`]), side by side, each captioned; with
//! `--turn FRAMES` (or `--rock`) an animation, as animated PNG or GIF (by `-o`'s extension).
//! The flags are parsed here into [`PhotoOptions`]; the pictures, captions and JSON records
//! come from the library.

use super::RenderArgs;
use crate::cli::flags;
use crate::cli::outputs::{cut_files, refuse_overwrite};
use facetlab::document::render::{PhotoFrame, PhotoRecord};
use facetlab::error::{Error, Result};
use facetlab::plot::render::{bare, compose, Panel, Sheet};
use facetlab::render::photo::{
    self, caption, parse_view, turntable, Ground, GroundKind, PhotoLight, PhotoOptions, Tone, View,
};
use facetlab::render::pose::rocked;
use rayon::prelude::*;
use std::path::PathBuf;
use std::time::Instant;

/// The photographic flags of `render` (they need a photographic `--light`).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct PhotoArgs {
    /// Photographs: where the camera looks from, ELEV degrees above the horizon (90 =
    /// straight above, 0 = a side view, negative = from below) and azimuth AZ (degrees
    /// counter-clockwise from the front); default 30@0.
    #[arg(long, value_name = "ELEV[@AZ]", allow_hyphen_values = true, value_parser = flags::parsed("--view", parse_view))]
    pub view: Option<View>,
    /// Photographs: a perspective camera this many mm from the stone's centre (the stone's
    /// width from --diameter-mm, default 6.5 mm); default: orthographic.
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    pub distance: Option<String>,
    /// Photographs: the ground the stone rests on, culet-down: white (paper), black
    /// (velvet) or none (default), with its shadow and caustics.
    #[arg(
        long,
        value_name = "white|black|none",
        value_parser = flags::parsed("--ground", GroundKind::parse)
    )]
    pub ground: Option<GroundKind>,
    /// Photographs: height of the stone's lowest point above the ground, girdle diameters
    /// (0–10; default 0: resting on it).
    #[arg(long, value_name = "X", allow_hyphen_values = true)]
    pub ground_gap: Option<String>,
    /// Photographs: turn the light about the vertical, degrees (counter-clockwise seen from
    /// above).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub light_rotation: Option<String>,
    /// Photographs: a turntable animation of FRAMES frames (2–360), the stone turned a full
    /// circle under the camera and lights.
    #[arg(long, value_name = "FRAMES", allow_hyphen_values = true)]
    pub turn: Option<String>,
    /// Photographs: the tone curve from linear radiance to the picture: filmic (default) or
    /// clip.
    #[arg(long, value_name = "filmic|clip", value_parser = flags::parsed("--tone", Tone::parse))]
    pub tone: Option<Tone>,
    /// Photographs: also write the linear picture (before exposure and tone) as OpenEXR
    /// (.exr) or Radiance HDR (.hdr); frame 0 of an animation, the first cut.
    #[arg(long, value_name = "FILE.exr")]
    pub hdr_out: Option<PathBuf>,
    /// Photographs: wavelength bands of a dispersive or coloured stone (3–64; default 8).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub bands: Option<String>,
}

impl PhotoArgs {
    /// The first photographic flag given, if any (to refuse it with a laboratory light).
    pub fn first_given(&self) -> Option<&'static str> {
        [
            (self.view.is_some(), "--view"),
            (self.distance.is_some(), "--distance"),
            (self.ground.is_some(), "--ground"),
            (self.ground_gap.is_some(), "--ground-gap"),
            (self.light_rotation.is_some(), "--light-rotation"),
            (self.turn.is_some(), "--turn"),
            (self.tone.is_some(), "--tone"),
            (self.hdr_out.is_some(), "--hdr-out"),
            (self.bands.is_some(), "--bands"),
        ]
        .into_iter()
        .find(|x| x.0)
        .map(|x| x.1)
    }
}

/// The flags, validated.
#[derive(Clone, Debug)]
pub struct Settings {
    /// Options of frame 0.
    pub opts: PhotoOptions,
    /// `--turn`.
    pub turn: Option<usize>,
    /// `--rock`.
    pub rock: Option<(f64, usize)>,
    /// `--exposure`.
    pub exposure: f64,
}

impl Settings {
    /// Number of frames.
    pub fn frames(&self) -> usize {
        self.turn.or(self.rock.map(|r| r.1)).unwrap_or(1)
    }

    /// Options of frame `k`.
    pub fn frame(&self, k: usize) -> PhotoOptions {
        match (self.turn, self.rock) {
            (Some(n), _) => turntable(&self.opts, n, k),
            (None, Some(rock)) => PhotoOptions {
                tilt: rocked(self.opts.tilt, rock, k),
                ..self.opts.clone()
            },
            _ => self.opts.clone(),
        }
    }
}

/// Largest animation: frames × cuts × size² pixels.
const MAX_ANIMATION_PIXELS: f64 = 400e6;

/// Validate the flags into the library's options.
pub fn settings(a: &RenderArgs, light: PhotoLight) -> Result<Settings> {
    let p = &a.photo;
    let mut o = PhotoOptions::new(light);
    o.size = a.size as usize;
    if let Some(v) = p.view {
        o.view = v;
    }
    if let Some(t) = a.tilt {
        o.tilt = t;
    }
    if a.head_shadow.is_some() {
        return Err(Error::invalid(
            "--head-shadow",
            "is for the laboratory lights; a photograph's camera casts no head shadow",
        ));
    }
    o.material = a.material.material()?;
    o.material.colour = a.colour.colour_for(&o.material)?;
    a.colour.size()?;
    o.polarization = a.polarization;
    if let Some(kind) = p.ground {
        o.ground = Ground { kind, gap: 0.0 };
    }
    if let Some(g) = &p.ground_gap {
        o.ground.gap = flags::number("--ground-gap", g, 0.0, 10.0, "girdle diameters")?;
    }
    if let Some(r) = &p.light_rotation {
        o.light_rotation_deg = flags::number("--light-rotation", r, -360.0, 360.0, "degrees")?;
    }
    if let Some(t) = p.tone {
        o.tone = t;
    }
    if let Some(b) = &p.bands {
        o.bands = flags::count("--bands", b, 3, 64)? as usize;
    }
    if let Some(d) = &p.distance {
        o.distance_mm = Some(flags::number("--distance", d, 0.0, 1e5, "millimetres")?);
    }
    let turn = p
        .turn
        .as_deref()
        .map(|t| flags::count("--turn", t, 2, 360).map(|n| n as usize))
        .transpose()?;
    let rock = a.rock;
    if turn.is_some() && rock.is_some() {
        return Err(Error::invalid(
            "--turn",
            "give either --turn (a turntable) or --rock, not both",
        ));
    }
    if let Some((deg, _)) = rock {
        if o.tilt.tilt_deg.abs() + deg > 90.0 {
            return Err(Error::invalid(
                "--rock",
                format!(
                    "rocking {deg}° about the --tilt of {}° would pass 90°; keep |tilt| + DEG <= 90",
                    o.tilt.tilt_deg
                ),
            ));
        }
    }
    let frames = turn.or(rock.map(|r| r.1)).unwrap_or(1);
    let pixels = (frames * a.cuts.len()) as f64 * (o.size as f64).powi(2);
    if frames > 1 && pixels > MAX_ANIMATION_PIXELS {
        return Err(Error::invalid(
            if turn.is_some() { "--turn" } else { "--rock" },
            format!(
                "{frames} frames of {} picture(s) of {} px would hold {:.0} million pixels; allowed {:.0} million: use fewer frames or a smaller --size",
                a.cuts.len(),
                o.size,
                pixels / 1e6,
                MAX_ANIMATION_PIXELS / 1e6
            ),
        ));
    }
    let exposure = a.exposure;
    // The width the stone is seen at (for a perspective camera and absorption).
    if let facetlab::optics::StoneSize::Width(w) = a.colour.size()? {
        o.width_mm = w;
    }
    o.validate()
        .map_err(|e| flags::picture_to_flags(e, &a.material))?;
    Ok(Settings {
        opts: o,
        turn,
        rock,
        exposure,
    })
}

/// Whether `path` ends in `ext` (any case).
fn has_ext(path: &std::path::Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// Check the outputs before any work.
fn check_outputs(a: &RenderArgs) -> Result<()> {
    let mut outs = vec![("-o", a.output.clone())];
    if let Some(j) = &a.json {
        outs.push(("--json", j.clone()));
    }
    if let Some(h) = &a.photo.hdr_out {
        outs.push(("--hdr-out", h.clone()));
    }
    refuse_overwrite(&outs, &cut_files(&a.cuts))?;
    if !(has_ext(&a.output, "png") || has_ext(&a.output, "gif")) {
        return Err(Error::invalid(
            "-o",
            format!(
                "{} does not end in .png or .gif; a photograph is a PNG, an animation an animated PNG or GIF",
                a.output.display()
            ),
        ));
    }
    if let Some(h) = &a.photo.hdr_out {
        if !facetlab::io::hdr::is_hdr_path(h) {
            return Err(Error::invalid(
                "--hdr-out",
                format!("{} does not end in .exr or .hdr", h.display()),
            ));
        }
    }
    for (i, (fa, pa)) in outs.iter().enumerate() {
        for (fb, pb) in &outs[i + 1..] {
            if crate::cli::outputs::resolved(pa) == crate::cli::outputs::resolved(pb) {
                return Err(Error::invalid(
                    *fb,
                    format!("{} is also the {fa} file; give another file", pb.display()),
                ));
            }
        }
    }
    for (flag, p) in &outs {
        crate::cli::outputs::check_new_file(flag, p, a.force)?;
    }
    Ok(())
}

/// Frame delay: a turn takes about 4.8 s, a rock 2.4 s.
fn lcm(a: usize, b: usize) -> usize {
    let gcd = |mut a: usize, mut b: usize| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    a / gcd(a, b) * b
}

fn delay_ms(frames: usize, turn: bool) -> u16 {
    let whole = if turn { 4800 } else { 2400 };
    (whole / frames.max(1)).clamp(20, 1000) as u16
}

/// Run `facetlab render` with a photographic light.
pub fn run(a: &RenderArgs, light: PhotoLight) -> Result<()> {
    let s = settings(a, light)?;
    check_outputs(a)?;
    if s.frames() > 1 && a.photo.hdr_out.is_some() && a.cuts.len() > 1 {
        eprintln!("note: --hdr-out writes frame 0 of the first cut");
    }
    let cuts = a
        .cuts
        .iter()
        .map(|c| crate::cli::cuts::load_with_sets(c, &a.set))
        .collect::<Result<Vec<_>>>()?;
    let chosen = a.material.chosen();
    let (mut materials, notes) = flags::design_materials(&cuts, &s.opts.material, chosen);
    for note in notes {
        eprintln!("{note}");
    }
    let (colour_notes, widths) = a.colour.apply_traced(&cuts, &mut materials, true)?;
    for note in colour_notes {
        eprintln!("{note}");
    }
    let size = s.opts.size;
    let nframes = s.frames();
    type Drawn = (
        Sheet,
        Vec<(PhotoFrame, photo::PhotoStats)>,
        Option<facetlab::io::hdr::HdrImage>,
    );
    // A turntable of symmetric stones repeats itself: trace the frames up to its period
    // (every cut's period divides it), then show them again.
    let period = match s.turn {
        Some(n) => cuts
            .iter()
            .zip(&materials)
            .map(|(cut, m)| {
                let opts = PhotoOptions {
                    material: m.clone(),
                    ..s.opts.clone()
                };
                photo::turntable_period(&cut.solid, &opts, n)
            })
            .fold(1, lcm),
        None => nframes,
    };
    let bar = crate::cli::progress::bar(
        (period * cuts.len()) as u64,
        a.quiet,
        "{spinner} photographing [{bar:30}] {pos}/{len} pictures, eta {eta}",
    );
    let mut drawn: Vec<Drawn> = (0..period)
        .into_par_iter()
        .map(|k| {
            let mut pictures = Vec::with_capacity(cuts.len());
            let mut stats = Vec::with_capacity(cuts.len());
            let mut hdr = None;
            for (c, cut) in cuts.iter().enumerate() {
                let t0 = Instant::now();
                let opts = PhotoOptions {
                    material: materials[c].clone(),
                    width_mm: widths[c],
                    ..s.frame(k)
                };
                let p = photo::photo(&cut.solid, &opts);
                let rgb = p.to_srgb8(s.exposure, opts.tone);
                if k == 0 && c == 0 && a.photo.hdr_out.is_some() {
                    hdr = Some(p.to_hdr());
                }
                let mut lines = vec![cut.name.clone()];
                lines.extend(caption(&opts, &p.stats));
                if s.exposure != 1.0 {
                    lines.push(format!("exposure ×{}", s.exposure));
                }
                pictures.push((rgb, lines));
                stats.push((
                    PhotoFrame::new(k, &opts, &p.stats, t0.elapsed().as_secs_f64()),
                    p.stats,
                ));
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
                compose(&panels, size as u32, &[])
            }?;
            Ok((sheet, stats, hdr))
        })
        .collect::<Result<Vec<_>>>()?;
    for k in period..nframes {
        let (sheet, stats, _) = &drawn[k % period];
        let stats = stats
            .iter()
            .map(|(f, st)| {
                let turn = s.frame(k);
                let frame = PhotoFrame {
                    frame: k,
                    turn_deg: turn.turn_deg,
                    tilt_deg: turn.tilt.tilt_deg,
                    elapsed_s: 0.0,
                    same_as: Some(f.frame),
                    ..f.clone()
                };
                (frame, st.clone())
            })
            .collect();
        drawn.push((sheet.clone(), stats, None));
    }
    bar.finish_and_clear();
    let mut per_cut: Vec<Vec<(PhotoFrame, photo::PhotoStats)>> = vec![Vec::new(); cuts.len()];
    let mut sheets = Vec::with_capacity(nframes);
    let mut hdr = None;
    for (sheet, stats, h) in drawn {
        sheets.push(sheet);
        hdr = hdr.or(h);
        for (c, f) in stats.into_iter().enumerate() {
            per_cut[c].push(f);
        }
    }
    let (w, h) = (sheets[0].width, sheets[0].height);
    let frames: Vec<&[u8]> = sheets.iter().map(|f| f.rgb.as_slice()).collect();
    let delay = delay_ms(nframes, s.turn.is_some());
    if has_ext(&a.output, "gif") {
        if w > u16::MAX as u32 || h > u16::MAX as u32 {
            return Err(Error::invalid(
                "-o",
                format!("a GIF is at most 65535 pixels wide; this sheet is {w} × {h}"),
            ));
        }
        facetlab::io::gif::write_rgb8(&a.output, w as u16, h as u16, &frames, delay)?;
    } else {
        facetlab::io::png::write_rgb8(&a.output, w, h, &frames, delay)?;
    }
    if let (Some(path), Some(img)) = (&a.photo.hdr_out, &hdr) {
        facetlab::io::hdr::write_hdr(path, img)?;
    }
    let out = a.output.display().to_string();
    let hdr_out = a.photo.hdr_out.as_ref().map(|p| p.display().to_string());
    let records: Vec<PhotoRecord> = cuts
        .iter()
        .zip(&a.cuts)
        .zip(per_cut)
        .enumerate()
        .map(|(c, ((cut, input), fr))| {
            let opts = PhotoOptions {
                material: materials[c].clone(),
                width_mm: widths[c],
                ..s.opts.clone()
            };
            let st = fr[0].1.clone();
            PhotoRecord::new(
                &cut.name,
                input,
                &opts,
                &st,
                s.exposure,
                fr.into_iter().map(|f| f.0).collect(),
                s.turn,
            )
            .written(&out, if c == 0 { hdr_out.as_deref() } else { None })
        })
        .collect();
    for r in &records {
        let anim = match (&r.frames, s.turn, s.rock) {
            (Some(f), Some(n), _) => format!(
                ", turntable of {n} frames ({} traced)",
                f.iter().filter(|f| f.same_as.is_none()).count()
            ),
            (Some(_), None, Some((deg, n))) => format!(", rocking ±{deg}° in {n} frames"),
            _ => String::new(),
        };
        let ground = match &r.ground_light {
            Some(g) => format!(
                ", ground: {} light directions, caustics {:.3} of the light the stone intercepts",
                g.directions,
                if g.intercepted > 0.0 {
                    (g.caustic + g.caustic_outside) / g.intercepted
                } else {
                    0.0
                }
            ),
            None => String::new(),
        };
        println!(
            "{}: {} photograph, mean {:.1} %{ground}{anim}, {size} px, {:.2} s → {out}",
            r.name,
            r.light,
            100.0 * r.mean,
            r.elapsed_s
        );
    }
    if let Some(h) = &hdr_out {
        println!("linear picture → {h}");
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
