//! Sheets of stone pictures: already-encoded RGB panels (from
//! [`Image::to_srgb8`](crate::render::Image::to_srgb8)) side by side on a grey ground
//! ([`PICTURE_GROUND`]), each with its caption lines below the picture, and an optional colour
//! legend under them (the ASET and IdealScope false colours, [`legend_for`]). Drawn with
//! plotters on a bitmap buffer in memory; the caller encodes the result ([`crate::io::png`]).
//!
//! Layout of a sheet of `n` panels of `size` pixels ([`Layout`]): each panel is
//! `size + 2·pad` wide (`pad` = [`Layout::pad`]), the picture at the top with `pad` of grey
//! around it, then the caption lines; the legend, when there is one, wraps across the whole
//! width below the captions. The sheet is so `n·(size + 2·pad)` pixels wide, whatever the text,
//! and each picture is exactly `size × size` pixels of it. [`bare`] gives the pictures alone.
//!
//! `facetlab render` is one call here, [`draw`]: the stones chosen, every frame drawn and put
//! on its sheet, the files written, the statistics returned (its progress and notes through
//! [`Progress`]).

mod run;

pub use run::{
    delay_ms, draw, lab_frame, lab_record, photo_frame, photo_record, printed_line, settings_line,
    stats_lines, summary, Drawn, Progress, RenderJob, Silent,
};

use super::palette::{CAPTION_GROUND, PICTURE_GROUND};
use super::{font, register_font};
use crate::error::{Error, Result};
use crate::render::{Light, ASET_COLOURS, IDEALSCOPE_COLOURS};
use plotters::prelude::*;

/// One picture with its caption.
#[derive(Clone, Debug)]
pub struct Panel<'a> {
    /// `size × size` pixels, 8-bit sRGB, rows from the top, 3 bytes per pixel.
    pub rgb: &'a [u8],
    /// Caption lines drawn below the picture (the first one larger: the cut's name).
    pub lines: Vec<String>,
}

/// One legend entry: a colour swatch (sRGB-encoded, 0–1) and its text.
#[derive(Clone, Debug, PartialEq)]
pub struct LegendEntry {
    /// Swatch colour.
    pub colour: [f64; 3],
    /// Text beside the swatch.
    pub label: String,
}

/// The legend of a light's false colours: ASET's bands (the bands' elevations as the viewer's
/// port of `port_deg` about the zenith leaves them; leak and port share one entry, both black
/// in the picture as in the viewer), IdealScope's three; none for the radiance pictures (iso,
/// cos, hearts, arrows, fire).
pub fn legend_for(light: Light, port_deg: f64) -> Vec<LegendEntry> {
    let top = (90.0 - port_deg).clamp(0.0, 90.0);
    let band = |lo: f64, hi: f64, colour: &str| match hi.min(top) {
        hi if hi > lo => format!("{lo:.0}–{hi:.0}° ({colour})"),
        _ => format!("none ({colour}: the port covers it)"),
    };
    let labels: Vec<String> = match light {
        Light::Aset => vec![
            band(75.0, 90.0, "blue"),
            band(45.0, 75.0, "red"),
            band(0.0, 45.0, "green"),
            format!("leak below 0°, port {top:.0}–90° (black)"),
        ],
        Light::IdealScope => ["returned (red)", "leak (white)", "head (black)"]
            .map(String::from)
            .to_vec(),
        _ => Vec::new(),
    };
    let colours: &[[f64; 3]] = match light {
        Light::Aset => &ASET_COLOURS,
        Light::IdealScope => &IDEALSCOPE_COLOURS,
        _ => &[],
    };
    labels
        .into_iter()
        .zip(colours)
        .map(|(label, c)| LegendEntry { colour: *c, label })
        .collect()
}

/// The colour of a laboratory picture's outline ([`outline`]).
pub const OUTLINE: [u8; 3] = [28, 28, 28];

/// The bytes of a laboratory picture's ground, [`PICTURE_GROUND`] (as `to_srgb8` writes it
/// where no stone covers a pixel).
pub fn picture_ground() -> [u8; 3] {
    PICTURE_GROUND.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
}

/// The stone's outline on a laboratory picture of `size` × `size` sRGB pixels on the ground
/// `ground` ([`picture_ground`]): the ground's pixels beside the stone turned to [`OUTLINE`],
/// so a stone whose rim is as grey as the ground (quartz under COS light) keeps its edge. For
/// the captioned sheets and the reports; `render --bare` and the Python package keep the
/// pictures as traced.
pub fn outline(rgb: &mut [u8], size: usize, ground: [u8; 3]) {
    if size < 3 || rgb.len() != size * size * 3 {
        return;
    }
    let at = |i: usize, j: usize| (j * size + i) * 3;
    let is_ground = |i: usize, j: usize| rgb[at(i, j)..at(i, j) + 3] == ground;
    let mut rim = Vec::new();
    for j in 0..size {
        for i in 0..size {
            let beside = [
                (i.wrapping_sub(1), j),
                (i + 1, j),
                (i, j.wrapping_sub(1)),
                (i, j + 1),
            ];
            if is_ground(i, j)
                && beside
                    .into_iter()
                    .any(|(a, b)| a < size && b < size && !is_ground(a, b))
            {
                rim.push(at(i, j));
            }
        }
    }
    for k in rim {
        rgb[k..k + 3].copy_from_slice(&OUTLINE);
    }
}

/// Sizes of a sheet, from the panel size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    /// Pixels per side of each picture.
    pub size: u32,
    /// Grey margin around each picture.
    pub pad: u32,
    /// Caption text height (the first line is 1.2× larger).
    pub text: u32,
}

impl Layout {
    /// The layout for pictures of `size` pixels: `pad = max(4, size/32)`, text
    /// `clamp(size/22, 11, 24)` pixels.
    pub fn new(size: u32) -> Layout {
        Layout {
            size,
            pad: (size / 32).max(4),
            text: (size / 22).clamp(11, 24),
        }
    }

    /// Width of one panel.
    pub fn panel_width(&self) -> u32 {
        self.size + 2 * self.pad
    }

    fn line_height(&self, first: bool) -> u32 {
        let t = if first { self.text * 6 / 5 } else { self.text };
        t + t / 3 + 1
    }
}

/// A finished sheet: 8-bit sRGB, rows from the top, 3 bytes per pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Sheet {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The pixels.
    pub rgb: Vec<u8>,
}

fn srgb8(c: [f64; 3]) -> RGBColor {
    let b = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    RGBColor(b(c[0]), b(c[1]), b(c[2]))
}

/// `line` set at `text` pixels, broken after its commas into lines no wider than `width`
/// pixels (a part wider than that alone keeps its own line).
fn wrap(line: &str, text: u32, width: u32) -> Vec<String> {
    let fits = |s: &str| super::text::width(s, text as f64) <= width as f32;
    if fits(line) {
        return vec![line.to_string()];
    }
    let mut out: Vec<String> = Vec::new();
    let mut cur = String::new();
    for part in line.split_inclusive(", ") {
        let joined = format!("{cur}{part}");
        if cur.is_empty() || fits(joined.trim_end()) {
            cur = joined;
        } else {
            out.push(cur.trim_end().to_string());
            cur = part.to_string();
        }
    }
    if !cur.is_empty() {
        out.push(cur.trim_end().to_string());
    }
    out
}

/// Side of a legend swatch: 1.3 times the label's capital height.
fn swatch_side(lay: &Layout) -> i32 {
    (super::text::metrics(lay.text as f64).cap * 1.3).round() as i32
}

/// Legend rows: each a list of (x offset, entry index), wrapped to `width` (every entry,
/// swatch and label, inside the sheet's margins).
fn legend_rows(entries: &[LegendEntry], lay: &Layout, width: u32) -> Vec<Vec<(u32, usize)>> {
    let swatch = swatch_side(lay) as u32;
    let gap = lay.text;
    let mut rows: Vec<Vec<(u32, usize)>> = Vec::new();
    let mut x = lay.pad;
    let mut row = Vec::new();
    for (i, e) in entries.iter().enumerate() {
        let tw = super::text::width(&e.label, lay.text as f64).ceil() as u32;
        let w = swatch + lay.text / 3 + tw;
        if !row.is_empty() && x + w > width.saturating_sub(lay.pad) {
            rows.push(std::mem::take(&mut row));
            x = lay.pad;
        }
        row.push((x, i));
        x += w + gap;
    }
    if !row.is_empty() {
        rows.push(row);
    }
    rows
}

/// Compose `panels` (each `size × size`) side by side with their captions and `legend` below;
/// see the [module documentation](self) for the layout. An error names `panels` when a panel
/// has the wrong number of bytes, or says what could not be drawn.
pub fn compose(panels: &[Panel], size: u32, legend: &[LegendEntry]) -> Result<Sheet> {
    let want = size as usize * size as usize * 3;
    if panels.is_empty() || size == 0 || panels.iter().any(|p| p.rgb.len() != want) {
        return Err(Error::invalid(
            "panels",
            format!("give at least one panel of {want} bytes ({size}×{size} RGB)"),
        ));
    }
    register_font();
    let lay = Layout::new(size);
    let pw = lay.panel_width();
    let width = pw * panels.len() as u32;
    // Each panel's caption, its lines wrapped to the panel (the first, the title, at its
    // larger size).
    let captions: Vec<Vec<(bool, String)>> = panels
        .iter()
        .map(|p| {
            p.lines
                .iter()
                .enumerate()
                .flat_map(|(i, line)| {
                    let text = if i == 0 { lay.text * 6 / 5 } else { lay.text };
                    wrap(line, text, size).into_iter().map(move |l| (i == 0, l))
                })
                .collect()
        })
        .collect();
    let caption = captions
        .iter()
        .map(|c| match c.len() {
            0 => 0,
            _ => lay.pad + c.iter().map(|l| lay.line_height(l.0)).sum::<u32>() + lay.pad / 2,
        })
        .max()
        .unwrap_or(0);
    let top = size + 2 * lay.pad;
    let rows = legend_rows(legend, &lay, width);
    let legend_h = if rows.is_empty() {
        0
    } else {
        rows.len() as u32 * lay.line_height(false) + lay.pad
    };
    let height = top + caption + legend_h;
    let (w, h) = (width as usize, height as usize);
    // The grounds and the pictures, straight into the buffer.
    let grey = srgb8(PICTURE_GROUND);
    let mut buf = vec![0u8; w * h * 3];
    for y in 0..h {
        let c = if y < top as usize {
            [grey.0, grey.1, grey.2]
        } else {
            CAPTION_GROUND
        };
        for px in buf[y * w * 3..(y + 1) * w * 3].chunks_exact_mut(3) {
            px.copy_from_slice(&c);
        }
    }
    let s = size as usize;
    for (k, p) in panels.iter().enumerate() {
        let x0 = k * pw as usize + lay.pad as usize;
        let y0 = lay.pad as usize;
        for j in 0..s {
            let dst = ((y0 + j) * w + x0) * 3;
            buf[dst..dst + s * 3].copy_from_slice(&p.rgb[j * s * 3..(j + 1) * s * 3]);
        }
    }
    let draw_err =
        |e: &dyn std::fmt::Display| Error::invalid("picture", format!("could not draw: {e}"));
    {
        let root =
            super::text::TextBackend::raster(BitMapBackend::with_buffer(&mut buf, (width, height)))
                .into_drawing_area();
        let big = font(lay.text * 6 / 5);
        let small = font(lay.text).color(&RGBColor(40, 40, 40));
        for (k, caption) in captions.iter().enumerate() {
            let x = (k as u32 * pw + lay.pad) as i32;
            let mut y = (top + lay.pad) as i32;
            for (first, line) in caption {
                let style = if *first { &big } else { &small };
                root.draw_text(line, style, (x, y))
                    .map_err(|e| draw_err(&e))?;
                y += lay.line_height(*first) as i32;
            }
        }
        // A swatch is a square as tall as the label's capitals and a little more, centred on
        // them: its middle at the capitals' middle, the text beside it.
        let cap = super::text::metrics(lay.text as f64).cap;
        let sw = swatch_side(&lay);
        for (r, row) in rows.iter().enumerate() {
            let y = (top + caption + r as u32 * lay.line_height(false)) as i32;
            let mid = y as f32 + cap / 2.0;
            let sy = (mid - sw as f32 / 2.0).round() as i32;
            for &(x, i) in row {
                let e = &legend[i];
                let x = x as i32;
                root.draw(&Rectangle::new(
                    [(x, sy), (x + sw, sy + sw)],
                    srgb8(e.colour).filled(),
                ))
                .map_err(|e| draw_err(&e))?;
                root.draw(&Rectangle::new(
                    [(x, sy), (x + sw, sy + sw)],
                    RGBColor(60, 60, 60).stroke_width(1),
                ))
                .map_err(|e| draw_err(&e))?;
                root.draw_text(&e.label, &small, (x + sw + lay.text as i32 / 3, y))
                    .map_err(|e| draw_err(&e))?;
            }
        }
        root.present().map_err(|e| draw_err(&e))?;
    }
    Ok(Sheet {
        width,
        height,
        rgb: buf,
    })
}

/// The pictures of `panels` (each `size × size`) alone, side by side with nothing between
/// or around them and no captions or legend: `n·size × size` pixels (`size × size` for one).
/// The same error as [`compose`] for a panel of the wrong number of bytes.
pub fn bare(panels: &[Panel], size: u32) -> Result<Sheet> {
    let want = size as usize * size as usize * 3;
    if panels.is_empty() || size == 0 || panels.iter().any(|p| p.rgb.len() != want) {
        return Err(Error::invalid(
            "panels",
            format!("give at least one panel of {want} bytes ({size}×{size} RGB)"),
        ));
    }
    let s = size as usize;
    let w = s * panels.len();
    let mut rgb = vec![0u8; w * s * 3];
    for (k, p) in panels.iter().enumerate() {
        for j in 0..s {
            let dst = (j * w + k * s) * 3;
            rgb[dst..dst + s * 3].copy_from_slice(&p.rgb[j * s * 3..(j + 1) * s * 3]);
        }
    }
    Ok(Sheet {
        width: w as u32,
        height: size,
        rgb,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn panels_sit_side_by_side_with_captions_and_legend_below() {
        let size = 40u32;
        let red: Vec<u8> = [200u8, 10, 10].repeat((size * size) as usize);
        let blue: Vec<u8> = [10u8, 10, 200].repeat((size * size) as usize);
        let panels = [
            Panel {
                rgb: &red,
                lines: vec!["Tolkowsky".into(), "mean 78.0 %".into()],
            },
            Panel {
                rgb: &blue,
                lines: vec!["Princess".into()],
            },
        ];
        let plain = compose(&panels, size, &[]).unwrap();
        let lay = Layout::new(size);
        assert_eq!(plain.width, 2 * lay.panel_width());
        assert!(plain.height > size + 2 * lay.pad);
        assert_eq!(plain.rgb.len(), (plain.width * plain.height * 3) as usize);
        let px = |s: &Sheet, x: u32, y: u32| {
            let k = ((y * s.width + x) * 3) as usize;
            [s.rgb[k], s.rgb[k + 1], s.rgb[k + 2]]
        };
        // The pictures are copied unchanged, the ground around them is grey.
        let c = lay.pad + size / 2;
        assert_eq!(px(&plain, c, c), [200, 10, 10]);
        assert_eq!(px(&plain, lay.panel_width() + c, c), [10, 10, 200]);
        assert_eq!(px(&plain, 0, 0), [102, 102, 102]);
        // Text was drawn in the caption strip.
        let strip = (size + 2 * lay.pad) as usize;
        let dark = plain.rgb[strip * plain.width as usize * 3..]
            .chunks_exact(3)
            .filter(|p| p[0] < 100)
            .count();
        assert!(dark > 10, "{dark}");
        let with = compose(&panels, size, &legend_for(Light::Aset, 10.0)).unwrap();
        assert_eq!(with.width, plain.width);
        assert!(with.height > plain.height);
        let aset: Vec<String> = legend_for(Light::Aset, 10.0)
            .into_iter()
            .map(|e| e.label)
            .collect();
        assert_eq!(
            aset,
            [
                "75–80° (blue)",
                "45–75° (red)",
                "0–45° (green)",
                "leak below 0°, port 80–90° (black)"
            ]
        );
        // A wider port takes the top of the bands.
        assert_eq!(legend_for(Light::Aset, 20.0)[1].label, "45–70° (red)");
        assert_eq!(legend_for(Light::IdealScope, 10.0).len(), 3);
        assert!(legend_for(Light::Iso, 10.0).is_empty());
        assert!(compose(&panels, size + 1, &[]).is_err());
        // Bare: the pictures alone, side by side.
        let b = bare(&panels, size).unwrap();
        assert_eq!((b.width, b.height), (2 * size, size));
        assert_eq!(px(&b, 0, 0), [200, 10, 10]);
        assert_eq!(px(&b, size - 1, size - 1), [200, 10, 10]);
        assert_eq!(px(&b, size, 0), [10, 10, 200]);
        let one = bare(&panels[..1], size).unwrap();
        assert_eq!((one.width, one.height), (size, size));
        assert_eq!(one.rgb, red);
        assert!(bare(&panels, size + 1).is_err());
        assert!(compose(&[], size, &[]).is_err());
    }

    /// A caption line wider than its panel is broken after its commas, each line inside the
    /// panel; the sheet grows by the added lines; a line that fits is left whole.
    #[test]
    fn long_caption_lines_wrap_after_commas_inside_the_panel() {
        let size = 200u32;
        let lay = Layout::new(size);
        let long = "L* 31 C* 14 h 153°, dark share 61.7 %, windowing 0.2 %, face-up";
        assert!(super::super::text::width(long, lay.text as f64) > size as f32);
        let parts = wrap(long, lay.text, size);
        assert!(parts.len() >= 2, "{parts:?}");
        for p in &parts {
            assert!(
                super::super::text::width(p, lay.text as f64) <= size as f32,
                "{p}"
            );
        }
        assert_eq!(parts.join(" "), long);
        assert_eq!(
            wrap("mean 6.6 %", lay.text, size),
            vec!["mean 6.6 %".to_string()]
        );
        let grey: Vec<u8> = [90u8, 90, 90].repeat((size * size) as usize);
        let sheet = |line: &str| {
            compose(
                &[Panel {
                    rgb: &grey,
                    lines: vec!["Tolkowsky".into(), line.into()],
                }],
                size,
                &[],
            )
            .unwrap()
        };
        let (short, wrapped) = (sheet("mean 6.6 %"), sheet(long));
        assert_eq!(
            wrapped.height - short.height,
            (parts.len() as u32 - 1) * lay.line_height(false)
        );
    }
}
