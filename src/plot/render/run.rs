//! `facetlab render` as one call ([`draw`]): the stones chosen for the cuts, every frame's
//! pictures drawn (in parallel, each frame on its own and collected in order: the same
//! pictures and statistics on any number of threads), put side by side on a sheet with their
//! captions, written as a PNG (an animated PNG or GIF for several frames), and the statistics
//! of each cut as `render --json` gives them ([`crate::document::render`]), written when
//! asked. A photograph's turntable of symmetric stones traces only the frames up to its period
//! ([`turntable_period`]) and shows them again. The caller sees progress and the stones'
//! notes through [`Progress`].

use super::{bare, compose, legend_for, LegendEntry, Panel, Sheet};
use crate::cut::Cut;
use crate::document::render::{CutJson, FrameJson, PhotoFrame, PhotoRecord};
use crate::error::{Error, Result};
use crate::io::hdr::HdrImage;
use crate::metrics::{ColourNotes, NoteKind, StoneChoice, StoneFields};
use crate::optics::Material;
use crate::plot::palette::PICTURE_GROUND;
use crate::render::photo::{caption, turntable_period, Photo, PhotoOptions, PhotoStats};
use crate::render::pose::describe;
use crate::render::settings::{LabPictures, PhotoPictures, Pictures};
use crate::render::{self, ColourStats, Image, Light, RenderOptions, Stats, Tilt};
use rayon::prelude::*;
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// What shows a render's progress (a progress bar) and says its notes. Called from worker
/// threads.
pub trait Progress: Sync {
    /// A stone's note ([`StoneChoice::stones`]), before any picture is drawn.
    fn note(&self, _kind: NoteKind, _line: String) {}
    /// The pictures to draw (frames traced × cuts).
    fn start(&self, _pictures: u64) {}
    /// One picture drawn.
    fn picture(&self) {}
    /// Every picture drawn; the files are written next.
    fn finish(&self) {}
}

/// No progress shown, no notes said.
pub struct Silent;
impl Progress for Silent {}

/// What `render` draws and where it writes it.
pub struct RenderJob<'a> {
    /// The cuts, side by side in this order.
    pub cuts: &'a [Cut],
    /// Each cut as the user gave it (the JSON's `input`).
    pub inputs: &'a [String],
    /// The stones' material, colour, size and crystal settings.
    pub stone: &'a StoneChoice,
    /// Where the stone's settings were given (named in errors and notes).
    pub fields: &'a StoneFields<'a>,
    /// The pictures.
    pub pictures: &'a Pictures,
    /// The pictures alone: no margin, captions or legend.
    pub bare: bool,
    /// The picture file (.png; a photograph's may be .gif). Errors about it name `output`.
    pub output: &'a Path,
    /// The statistics' JSON file.
    pub json: Option<&'a Path>,
    /// A photograph's linear picture (.exr or .hdr): frame 0 of the first cut.
    pub hdr_out: Option<&'a Path>,
}

/// What `render` drew: each cut's statistics, as its JSON document holds them.
#[derive(Clone, Debug)]
pub enum Drawn {
    /// Laboratory pictures.
    Lab(Vec<CutJson>),
    /// Photographs.
    Photo(Vec<PhotoRecord>),
}

/// Draw the job's pictures and write its files ([`RenderJob`]): the picture, then a
/// photograph's linear picture, then the JSON. The outputs are the caller's to check first.
pub fn draw(job: &RenderJob<'_>, progress: &dyn Progress) -> Result<Drawn> {
    let stones = job
        .stone
        .stones(job.cuts, job.fields, ColourNotes::Traced, &mut |k, l| {
            progress.note(k, l)
        })?;
    let drawn = match job.pictures {
        Pictures::Lab(lab) => Drawn::Lab(draw_lab(job, lab, &stones, progress)?),
        Pictures::Photo(p) => Drawn::Photo(draw_photo(job, p, &stones, progress)?),
    };
    if let Some(j) = job.json {
        match &drawn {
            Drawn::Lab(r) => write_json(j, r)?,
            Drawn::Photo(r) => write_json(j, r)?,
        }
    }
    Ok(drawn)
}

/// Every frame's sheet of the cuts' pictures, frames `0..n` in parallel; `picture(k, c)` draws
/// cut `c` in frame `k`: its sRGB bytes, its caption and its statistics.
fn sheets<T: Send>(
    n: usize,
    cuts: usize,
    size: usize,
    panels: Option<&[LegendEntry]>,
    progress: &dyn Progress,
    picture: impl Fn(usize, usize) -> (Vec<u8>, Vec<String>, T) + Sync,
) -> Result<Vec<(Sheet, Vec<T>)>> {
    (0..n)
        .into_par_iter()
        .map(|k| {
            let mut pictures = Vec::with_capacity(cuts);
            let mut stats = Vec::with_capacity(cuts);
            for c in 0..cuts {
                let (rgb, lines, t) = picture(k, c);
                pictures.push((rgb, lines));
                stats.push(t);
                progress.picture();
            }
            let panel: Vec<Panel> = pictures
                .iter()
                .map(|(rgb, lines)| Panel {
                    rgb,
                    lines: lines.clone(),
                })
                .collect();
            let sheet = match panels {
                None => bare(&panel, size as u32),
                Some(legend) => compose(&panel, size as u32, legend),
            }?;
            Ok((sheet, stats))
        })
        .collect()
}

/// Frame delay of an animation: a turn takes about 4.8 s, a rock 2.4 s.
pub fn delay_ms(frames: usize, turn: bool) -> u16 {
    let whole = if turn { 4800 } else { 2400 };
    (whole / frames.max(1)).clamp(20, 1000) as u16
}

/// Write the sheets as one picture or an animation: a GIF when `output` ends in .gif, else a
/// PNG.
fn write_sheets(output: &Path, sheets: &[Sheet], delay: u16) -> Result<()> {
    let (w, h) = (sheets[0].width, sheets[0].height);
    let frames: Vec<&[u8]> = sheets.iter().map(|f| f.rgb.as_slice()).collect();
    let gif = output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gif"));
    if gif {
        if w > u16::MAX as u32 || h > u16::MAX as u32 {
            return Err(Error::invalid(
                "output",
                format!("a GIF is at most 65535 pixels wide; this sheet is {w} × {h}"),
            ));
        }
        crate::io::gif::write_rgb8(output, w as u16, h as u16, &frames, delay)
    } else {
        crate::io::png::write_rgb8(output, w, h, &frames, delay)
    }
}

/// Write `records` as JSON: one object for one cut, an array for several.
fn write_json<T: Serialize>(path: &Path, records: &[T]) -> Result<()> {
    let text = if let [one] = records {
        serde_json::to_string_pretty(one)
    } else {
        serde_json::to_string_pretty(records)
    }
    .map_err(|e| Error::io(path.display().to_string(), e))?;
    crate::io::write_atomic(path, text.as_bytes())
}

fn draw_lab(
    job: &RenderJob<'_>,
    s: &LabPictures,
    stones: &crate::metrics::Stones,
    progress: &dyn Progress,
) -> Result<Vec<CutJson>> {
    let (materials, widths) = (&stones.materials, &stones.widths);
    let cuts = job.cuts;
    let light = s.opts.light;
    let size = s.opts.size;
    let nframes = s.frames();
    // Every frame has the same caption lines (an animation's frames share one size).
    let show_tilt = s.rock.is_some() || s.opts.tilt.tilt_deg != 0.0;
    let note = settings_line(&s.opts, s.exposure);
    let legend = legend_for(light, s.opts.head_shadow());
    progress.start((nframes * cuts.len()) as u64);
    let drawn = sheets(
        nframes,
        cuts.len(),
        size,
        (!job.bare).then_some(legend.as_slice()),
        progress,
        |k, c| {
            let tilt = s.frame_tilt(k);
            let (img, frame) = lab_frame(s, &cuts[c].solid, materials[c].clone(), widths[c], k);
            let mut rgb = img.to_srgb8(s.exposure, PICTURE_GROUND);
            if !job.bare {
                super::outline(&mut rgb, size, super::picture_ground());
            }
            let mut lines = vec![cuts[c].name.clone()];
            lines.extend(stats_lines(light, &img.stats));
            lines.extend(note.clone());
            if show_tilt {
                lines.push(describe(light, tilt));
            }
            (rgb, lines, frame)
        },
    )?;
    // stats[cut] = per-frame statistics.
    let mut stats: Vec<Vec<FrameJson>> = vec![Vec::with_capacity(nframes); cuts.len()];
    let mut all = Vec::with_capacity(nframes);
    for (sheet, frame_stats) in drawn {
        all.push(sheet);
        for (c, f) in frame_stats.into_iter().enumerate() {
            stats[c].push(f);
        }
    }
    progress.finish();
    write_sheets(job.output, &all, delay_ms(nframes, false))?;
    let out = job.output.display().to_string();
    Ok(cuts
        .iter()
        .zip(job.inputs)
        .zip(stats)
        .enumerate()
        .map(|(c, ((cut, input), fr))| CutJson {
            output: out.clone(),
            ..lab_record(s, (&cut.name, input), materials[c].clone(), widths[c], fr)
        })
        .collect())
}

/// Frame `k` of a laboratory picture of `solid` in `material`, `width_mm` wide: the picture
/// and its frame's statistics as `render --json` records them.
pub fn lab_frame(
    s: &LabPictures,
    solid: &crate::geometry::Polyhedron,
    material: Material,
    width_mm: f64,
    k: usize,
) -> (Image, FrameJson) {
    let t0 = Instant::now();
    let tilt = s.frame_tilt(k);
    let opts = RenderOptions {
        tilt,
        material,
        width_mm,
        ..s.opts.clone()
    };
    let img = render::render(solid, &opts);
    let frame = FrameJson::new(k, tilt, &img.stats, t0.elapsed().as_secs_f64());
    (img, frame)
}

/// A cut's record in `render --json` (`name` and `input`, as the user gave it) of laboratory
/// pictures whose frames are `frames` ([`lab_frame`]); its `output` is empty, the caller's to
/// fill.
pub fn lab_record(
    s: &LabPictures,
    name: (&str, &str),
    material: Material,
    width_mm: f64,
    frames: Vec<FrameJson>,
) -> CutJson {
    let opts = RenderOptions {
        material,
        width_mm,
        ..s.opts.clone()
    };
    CutJson::new(name, &opts, s.exposure, frames, s.rock.map(|r| r.0))
}

/// Least common multiple.
fn lcm(a: usize, b: usize) -> usize {
    let gcd = |mut a: usize, mut b: usize| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    a / gcd(a, b) * b
}

/// A photograph's frame: its record, statistics and (frame 0, first cut) linear picture.
type PhotoShot = (PhotoFrame, PhotoStats, Option<HdrImage>);

fn draw_photo(
    job: &RenderJob<'_>,
    s: &PhotoPictures,
    stones: &crate::metrics::Stones,
    progress: &dyn Progress,
) -> Result<Vec<PhotoRecord>> {
    let (materials, widths) = (&stones.materials, &stones.widths);
    let cuts = job.cuts;
    let size = s.opts.size;
    let nframes = s.frames();
    // A turntable of symmetric stones repeats itself: trace the frames up to its period
    // (every cut's period divides it), then show them again.
    let period = match s.turn {
        Some(n) => cuts
            .iter()
            .zip(materials)
            .map(|(cut, m)| {
                let opts = PhotoOptions {
                    material: m.clone(),
                    ..s.opts.clone()
                };
                turntable_period(&cut.solid, &opts, n)
            })
            .fold(1, lcm),
        None => nframes,
    };
    progress.start((period * cuts.len()) as u64);
    let mut drawn: Vec<(Sheet, Vec<PhotoShot>)> = sheets(
        period,
        cuts.len(),
        size,
        (!job.bare).then_some(&[][..]),
        progress,
        |k, c| {
            let (opts, p, frame) =
                photo_frame(s, &cuts[c].solid, materials[c].clone(), widths[c], k);
            let rgb = p.to_srgb8(s.exposure, opts.tone);
            let hdr = (k == 0 && c == 0 && job.hdr_out.is_some()).then(|| p.to_hdr());
            let mut lines = vec![cuts[c].name.clone()];
            lines.extend(caption(&opts, &p.stats));
            if s.exposure != 1.0 {
                lines.push(format!("exposure ×{}", s.exposure));
            }
            (rgb, lines, (frame, p.stats, hdr))
        },
    )?;
    for k in period..nframes {
        let (sheet, stats) = &drawn[k % period];
        let turn = s.frame(k);
        let stats = stats
            .iter()
            .map(|(f, st, _)| {
                let frame = PhotoFrame {
                    frame: k,
                    turn_deg: turn.turn_deg,
                    tilt_deg: turn.tilt.tilt_deg,
                    elapsed_s: 0.0,
                    same_as: Some(f.frame),
                    ..f.clone()
                };
                (frame, st.clone(), None)
            })
            .collect();
        drawn.push((sheet.clone(), stats));
    }
    progress.finish();
    let mut per_cut: Vec<Vec<(PhotoFrame, PhotoStats)>> = vec![Vec::new(); cuts.len()];
    let mut all = Vec::with_capacity(nframes);
    let mut hdr = None;
    for (sheet, stats) in drawn {
        all.push(sheet);
        for (c, (f, st, h)) in stats.into_iter().enumerate() {
            hdr = hdr.or(h);
            per_cut[c].push((f, st));
        }
    }
    write_sheets(job.output, &all, delay_ms(nframes, s.turn.is_some()))?;
    if let (Some(path), Some(img)) = (job.hdr_out, &hdr) {
        crate::io::hdr::write_hdr(path, img)?;
    }
    let out = job.output.display().to_string();
    let hdr_out = job.hdr_out.map(|p| p.display().to_string());
    Ok(cuts
        .iter()
        .zip(job.inputs)
        .zip(per_cut)
        .enumerate()
        .map(|(c, ((cut, input), fr))| {
            let st = fr[0].1.clone();
            let frames = fr.into_iter().map(|f| f.0).collect();
            photo_record(
                s,
                (&cut.name, input),
                materials[c].clone(),
                widths[c],
                &st,
                frames,
            )
            .written(&out, if c == 0 { hdr_out.as_deref() } else { None })
        })
        .collect())
}

/// Frame `k` of a photograph of `solid` in `material`, `width_mm` wide: its options, the
/// photograph, and its frame's record in `render --json`.
pub fn photo_frame(
    s: &PhotoPictures,
    solid: &crate::geometry::Polyhedron,
    material: Material,
    width_mm: f64,
    k: usize,
) -> (PhotoOptions, Photo, PhotoFrame) {
    let t0 = Instant::now();
    let opts = PhotoOptions {
        material,
        width_mm,
        ..s.frame(k)
    };
    let p = render::photo::photo(solid, &opts);
    let frame = PhotoFrame::new(k, &opts, &p.stats, t0.elapsed().as_secs_f64());
    (opts, p, frame)
}

/// A cut's record in `render --json` (`name` and `input`, as the user gave it) of photographs
/// whose frames are `frames` ([`photo_frame`]), `stats` the first's statistics; nothing
/// written (the caller adds its files with `written`).
pub fn photo_record(
    s: &PhotoPictures,
    name: (&str, &str),
    material: Material,
    width_mm: f64,
    stats: &PhotoStats,
    frames: Vec<PhotoFrame>,
) -> PhotoRecord {
    let opts = PhotoOptions {
        material,
        width_mm,
        ..s.opts.clone()
    };
    PhotoRecord::new(name.0, name.1, &opts, stats, s.exposure, frames, s.turn)
}

fn pct(v: f64) -> String {
    format!("{:.1} %", 100.0 * v)
}

/// The share darker than L* 20 under its name: the extinction in the scores' face-up ISO
/// view, the dark share of any other picture.
fn dark_text(c: &ColourStats, extinction: &str, dark: &str) -> String {
    match c.extinction {
        Some(e) => format!("{extinction} {}", pct(e)),
        None => format!("{dark} {}", pct(c.dark())),
    }
}

/// A laboratory picture's statistics as caption lines (after the name).
pub fn stats_lines(light: Light, s: &Stats) -> Vec<String> {
    let mut lines = match (light, s.aset, s.fire) {
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
    };
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

/// The line `render` prints for a laboratory picture's cut (before its pose).
pub fn summary(light: Light, s: &Stats) -> String {
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

/// The line `render` prints for a cut: its statistics, pose and rock or turntable, size,
/// time and the file written.
pub fn printed_line(pictures: &Pictures, drawn: &Drawn, c: usize) -> String {
    match (pictures, drawn) {
        (Pictures::Lab(s), Drawn::Lab(records)) => {
            let r = &records[c];
            let light = s.opts.light;
            let stats = Stats {
                mean: r.mean,
                aset: r.aset,
                fire: r.fire,
                colour: r.colour,
                ..Stats::default()
            };
            let pose = describe(
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
            let time = traced_time(r.frames.is_some(), r.elapsed_s);
            format!(
                "{}: {}, {pose}{rock}, {} px, {time} → {}",
                r.name,
                summary(light, &stats),
                r.size,
                r.output
            )
        }
        (Pictures::Photo(s), Drawn::Photo(records)) => {
            let r = &records[c];
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
            let time = traced_time(r.frames.is_some(), r.elapsed_s);
            format!(
                "{}: {} photograph, mean {:.1} %{ground}{anim}, {} px, {time} → {}",
                r.name,
                r.light,
                100.0 * r.mean,
                r.size,
                r.output
            )
        }
        _ => String::new(),
    }
}

impl Drawn {
    /// Number of cuts drawn.
    pub fn len(&self) -> usize {
        match self {
            Drawn::Lab(r) => r.len(),
            Drawn::Photo(r) => r.len(),
        }
    }

    /// Whether no cut was drawn.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A picture's tracing time for its printed line. An animation's frames are traced side by
/// side: their times add up to more than the wall time, so the line says which it is.
fn traced_time(animation: bool, elapsed_s: f64) -> String {
    if animation {
        format!("{elapsed_s:.2} s of tracing over the frames (traced in parallel)")
    } else {
        format!("{elapsed_s:.2} s")
    }
}
