//! The cutting sheet: one printed A4 page a cutter takes to the machine, as SVG, HTML or PDF,
//! and the cutting mode, one step per screen with the stone drawn as cut so far.
//!
//! The page: GemCad's header (name, further title lines such as the author, the index the
//! angles are for, facets and girdle facets, symmetry, gear; L/W, T/W, P/W, C/W, H/W,
//! Vol/W³ and the weight at a size in a material — the numbers of `facetlab info`, from
//! [`info_json`]), the stone face up, face down and from the side with every facet's name and
//! index, and one row per step in cutting order ([`crate::design::sheet_steps`], or any list
//! of [`SheetStep`]s: a recipe's own). The page is A4 in points (595.28 × 841.89); the PDF is
//! that SVG converted by `svg2pdf` (vector, the text in the bundled DejaVu Sans, one page).
//!
//! `mod.rs` lays out the page; `mode.rs` writes the cutting mode ([`cutting_mode_html`]).

mod mode;
pub use mode::cutting_mode_html;

use crate::cut::Cut;
use crate::design::{sheet_record, step_of_facets, SheetStep};
use crate::document::info::{info_json, InfoJson};
use crate::error::{Error, Result};
use crate::geometry::{DVec2, DVec3, Polyhedron};
use crate::optics::Material;
use crate::report::escape as esc;
use std::fmt::Write as _;

/// A4 in points.
pub const A4: (f64, f64) = (595.28, 841.89);
const MARGIN: f64 = 30.0;
pub(super) const FONT: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";
pub(super) const INK: &str = "#222";

/// What a sheet is drawn for.
#[derive(Clone, Debug)]
pub struct SheetOptions {
    /// The stone's width W in mm: depths in mm and the weight at that size. `None`: depths in
    /// W and the weight at [`DEFAULT_WIDTH_MM`].
    pub size_mm: Option<f64>,
    /// The material of the weight.
    pub material: Material,
}

/// The width the weight is given at when no size is asked (`info`'s default).
pub const DEFAULT_WIDTH_MM: f64 = 6.5;

fn n(x: f64) -> String {
    let s = format!("{x:.2}");
    if s == "-0.00" {
        "0.00".into()
    } else {
        s
    }
}

fn text(out: &mut String, x: f64, y: f64, size: f64, extra: &str, s: &str) {
    let _ = writeln!(
        out,
        r#"<text x="{}" y="{}" font-size="{size:.2}"{extra}>{}</text>"#,
        n(x),
        n(y),
        esc(s)
    );
}

fn width(s: &str, size: f64) -> f64 {
    crate::plot::text::width_at_em(s, size)
}

/// `s` broken at `sep` into lines at most `max` points wide at `size`.
fn wrap(s: &str, sep: char, size: f64, max: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut cur = String::new();
    for w in s.split(sep).filter(|w| !w.is_empty()) {
        let next = if cur.is_empty() {
            w.to_string()
        } else {
            format!("{cur}{sep}{w}")
        };
        if !cur.is_empty() && width(&next, size) > max {
            lines.push(format!("{cur}{}", if sep == '-' { "-" } else { "" }));
            cur = w.to_string();
        } else {
            cur = next;
        }
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    lines
}

pub(super) fn padded(indices: &[String]) -> String {
    indices
        .iter()
        .map(|i| {
            if i.len() == 1 {
                format!("0{i}")
            } else {
                i.clone()
            }
        })
        .collect::<Vec<_>>()
        .join("-")
}

/// The header's lines: (id, text), as the sheet prints them.
pub fn header_lines(
    cut: &Cut,
    o: &SheetOptions,
) -> (String, Vec<(&'static str, String)>, InfoJson) {
    let width_mm = o.size_mm.unwrap_or(DEFAULT_WIDTH_MM);
    let info = info_json(cut, width_mm, &o.material);
    let record = sheet_record(cut, o.material.ri(589.3));
    let title = record
        .title
        .iter()
        .map(|t| t.trim())
        .find(|t| !t.is_empty())
        .map_or_else(|| cut.name.clone(), str::to_string);
    let mut lines: Vec<(&'static str, String)> = Vec::new();
    for t in record
        .title
        .iter()
        .map(|t| t.trim())
        .filter(|t| !t.is_empty())
        .skip(1)
    {
        lines.push(("title", t.to_string()));
    }
    let facets = cut.solid.facets();
    let girdle = facets
        .iter()
        .filter(|f| f.plane.normal.z.abs() < 1e-9)
        .count();
    let ri = record.ri.unwrap_or_else(|| o.material.ri(589.3));
    let sym = match (record.symmetry.max(1), record.mirror) {
        (1, false) => "no symmetry".to_string(),
        (1, true) => "mirror-image symmetry".to_string(),
        (k, false) => format!("{k}-fold symmetry"),
        (k, true) => format!("{k}-fold, mirror-image symmetry"),
    };
    let gear = record.gear.abs();
    let gear = if gear.fract() == 0.0 {
        format!("{gear:.0}")
    } else {
        gear.to_string()
    };
    lines.push((
        "design",
        format!(
            "Angles for R.I. = {ri:.3}; {} facets + {girdle} facets on girdle = {}; {sym}; {gear} index",
            facets.len() - girdle,
            facets.len()
        ),
    ));
    let r = &info.ratios;
    lines.push((
        "ratios",
        format!(
            "L/W {:.3} · T/W {:.3} · P/W {:.3} · C/W {:.3} · H/W {:.3} · Vol/W³ {:.4}",
            r.l_w, r.t_w, r.p_w, r.c_w, r.h_w, r.vol_w3
        ),
    ));
    let z = &info.size_mm;
    let depths = match o.size_mm {
        Some(_) => "depths in mm at this size".to_string(),
        None => "depths in widths W".to_string(),
    };
    lines.push((
        "size",
        format!(
            "Size {:.2} × {:.2} × {:.2} mm (L × W × D) · weight {:.3} ct in {} · {depths}",
            z.length, z.width, z.depth, info.carats, info.material
        ),
    ));
    (title, lines, info)
}

/// Maps a view's model coordinates to page points.
#[derive(Clone, Copy)]
struct View {
    centre: DVec2,
    origin: DVec2,
    scale: f64,
}

impl View {
    fn px(&self, p: DVec2) -> DVec2 {
        let d = (p - self.origin) * self.scale;
        DVec2::new(self.centre.x + d.x, self.centre.y - d.y)
    }
}

fn points(pts: &[DVec2]) -> String {
    pts.iter()
        .map(|p| format!("{},{}", n(p.x), n(p.y)))
        .collect::<Vec<_>>()
        .join(" ")
}

fn polygon_area(p: &[DVec2]) -> f64 {
    let mut a = 0.0;
    for i in 0..p.len() {
        let (u, v) = (p[i], p[(i + 1) % p.len()]);
        a += u.x * v.y - v.x * u.y;
    }
    0.5 * a.abs()
}

/// How a view draws each facet: its fill, and its label (name, index) if any.
pub(super) struct Look<'a> {
    pub(super) fill: &'a dyn Fn(usize) -> &'static str,
    pub(super) label: &'a dyn Fn(usize) -> Option<(String, String)>,
}

/// One view of `solid`: the facets `facing` selects, projected by `proj`, with labels.
fn view(
    out: &mut String,
    solid: &Polyhedron,
    v: View,
    facing: impl Fn(DVec3) -> bool,
    proj: impl Fn(DVec3) -> DVec2,
    look: &Look,
) {
    let mut labels: Vec<(DVec2, f64, String, String)> = Vec::new();
    for (i, f) in solid.facets().iter().enumerate() {
        if !facing(f.plane.normal) {
            continue;
        }
        let pts: Vec<DVec2> = solid
            .facet_polygon(i)
            .into_iter()
            .map(|p| v.px(proj(p)))
            .collect();
        let _ = writeln!(
            out,
            r#"<polygon points="{}" fill="{}" stroke="{INK}" stroke-width="0.5" stroke-linejoin="round"/>"#,
            points(&pts),
            (look.fill)(i)
        );
        if let Some((name, index)) = (look.label)(i) {
            let area = polygon_area(&pts);
            let c = pts.iter().fold(DVec2::ZERO, |a, p| a + *p) / pts.len().max(1) as f64;
            let size = (area / 9.0).sqrt().clamp(1.8, 6.5);
            labels.push((c, size, name, index));
        }
    }
    let outline = crate::geometry::clip2d::convex_hull(
        solid.vertices().iter().map(|p| v.px(proj(*p))).collect(),
    );
    let _ = writeln!(
        out,
        r#"<polygon points="{}" fill="none" stroke="{INK}" stroke-width="1.2" stroke-linejoin="round"/>"#,
        points(&outline)
    );
    for (c, size, name, index) in labels {
        let _ = writeln!(
            out,
            r##"<text x="{}" y="{}" font-size="{size:.2}" text-anchor="middle" class="facet">{}<tspan x="{}" dy="{:.2}" font-size="{:.2}" fill="#555">{}</tspan></text>"##,
            n(c.x),
            n(c.y - 0.1 * size),
            esc(&name),
            n(c.x),
            0.95 * size,
            0.85 * size,
            esc(&index)
        );
    }
}

pub(super) const DONE: &str = "#dbe8f6";
pub(super) const NOW: &str = "#f6c453";
pub(super) const ROUGH: &str = "#eeeeee";
const GIRDLE: &str = "#e4e4e4";

/// Facet names and indices of `cut`'s facets: its step's short name and the facet's index.
fn facet_labels(cut: &Cut, steps: &[SheetStep]) -> Vec<Option<(String, String)>> {
    let gear = crate::design::sheet_gear(cut);
    step_of_facets(cut, steps)
        .into_iter()
        .zip(cut.solid.facets())
        .map(|(s, f)| {
            let s = s?;
            let i = gear.index(f.plane.normal);
            let idx = if (i - i.round()).abs() < 1e-6 {
                format!("{:02.0}", i.round())
            } else {
                format!("{i:.2}")
            };
            Some((steps[s].name.clone(), idx))
        })
        .collect()
}

/// Three views of a solid laid out in a box from `top` of height `h`; returns the SVG.
pub(super) fn three_views(
    out: &mut String,
    solid: &Polyhedron,
    frame: (f64, f64, f64, f64),
    look: &Look,
    headings: bool,
) {
    let (x0, top, w, h) = frame;
    let (lo, hi) = solid.bounding_box();
    let (ex, ey, ez) = (
        (hi.x - lo.x).max(1e-9),
        (hi.y - lo.y).max(1e-9),
        (hi.z - lo.z).max(1e-9),
    );
    let head = if headings { 14.0 } else { 2.0 };
    // Face up and face down side by side, the side view under them, one scale.
    let scale = ((w - 20.0) / (2.0 * ex))
        .min((h - 2.0 * head - 16.0) / (ey + ez))
        .min(260.0 / ex.max(ey));
    let mid = 0.5 * (lo + hi);
    let row = top + head + 0.5 * ey * scale;
    let up = View {
        centre: DVec2::new(x0 + 0.25 * w, row),
        origin: mid.truncate(),
        scale,
    };
    let down = View {
        centre: DVec2::new(x0 + 0.75 * w, row),
        origin: DVec2::new(-mid.x, mid.y),
        scale,
    };
    let side_top = top + head + ey * scale + 10.0 + head;
    let side = View {
        centre: DVec2::new(x0 + 0.5 * w, side_top + 0.5 * ez * scale),
        origin: DVec2::new(mid.x, mid.z),
        scale,
    };
    if headings {
        let b = r#" text-anchor="middle" font-weight="bold""#;
        text(out, up.centre.x, top + 9.0, 8.0, b, "Crown (face up)");
        text(
            out,
            down.centre.x,
            top + 9.0,
            8.0,
            b,
            "Pavilion (face down, mirrored)",
        );
        text(
            out,
            side.centre.x,
            side_top - 6.0,
            8.0,
            b,
            "Side (from the front)",
        );
    }
    view(out, solid, up, |n| n.z > 1e-9, |p| p.truncate(), look);
    view(
        out,
        solid,
        down,
        |n| n.z < -1e-9,
        |p| DVec2::new(-p.x, p.y),
        look,
    );
    view(
        out,
        solid,
        side,
        |n| n.y < -0.3,
        |p| DVec2::new(p.x, p.z),
        look,
    );
}

/// The sheet's rows from `y`: section headings and one row per step. Returns the SVG's rows
/// and their height; `size` is the font size.
fn rows(steps: &[SheetStep], size: f64) -> (String, f64) {
    let mut out = String::new();
    let line = 1.3 * size;
    let (xs, xn, xa, xi, xt) = (
        MARGIN,
        MARGIN + 16.0,
        MARGIN + 82.0,
        MARGIN + 94.0,
        MARGIN + 310.0,
    );
    let (wi, wt) = (xt - xi - 10.0, A4.0 - MARGIN - xt);
    let mut y = 0.0;
    let b = r#" font-weight="bold""#;
    text(&mut out, xs, y + size, size, b, "#");
    text(&mut out, xn, y + size, size, b, "Name");
    text(
        &mut out,
        xa,
        y + size,
        size,
        &format!("{b} text-anchor=\"end\""),
        "Angle",
    );
    text(&mut out, xi, y + size, size, b, "Index");
    text(&mut out, xt, y + size, size, b, "Instruction");
    y += line + 2.0;
    let mut heading = "";
    for (k, s) in steps.iter().enumerate() {
        if s.section.heading() != heading {
            heading = s.section.heading();
            y += 2.0;
            let _ = writeln!(
                out,
                r##"<rect x="{}" y="{}" width="{}" height="{}" fill="#eef2f6"/>"##,
                n(MARGIN - 2.0),
                n(y),
                n(A4.0 - 2.0 * MARGIN + 4.0),
                n(line)
            );
            text(&mut out, xs, y + size, size, b, heading);
            y += line;
        }
        let idx = wrap(&padded(&s.indices), '-', size, wi);
        let ins = wrap(&s.instruction, ' ', size, wt);
        let lines = idx.len().max(ins.len()).max(1);
        let _ = writeln!(
            out,
            r#"<g class="step" data-step="{}" data-section="{}" data-name="{}" data-angle="{:.2}" data-facets="{}">"#,
            k + 1,
            section_id(s.section),
            esc(&s.name),
            s.angle.abs(),
            s.indices.len()
        );
        text(&mut out, xs, y + size, size, "", &(k + 1).to_string());
        text(&mut out, xn, y + size, size, b, &s.name);
        text(
            &mut out,
            xa,
            y + size,
            size,
            r#" text-anchor="end""#,
            &format!("{:.2}°", s.angle.abs()),
        );
        for (j, l) in idx.iter().enumerate() {
            text(&mut out, xi, y + size + j as f64 * line, size, "", l);
        }
        for (j, l) in ins.iter().enumerate() {
            text(&mut out, xt, y + size + j as f64 * line, size, "", l);
        }
        out.push_str("</g>\n");
        y += lines as f64 * line;
        let _ = writeln!(
            out,
            r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#ccc" stroke-width="0.4"/>"##,
            n(MARGIN),
            n(y + 0.3 * size),
            n(A4.0 - MARGIN),
            n(y + 0.3 * size)
        );
        y += 0.5 * size;
    }
    (out, y)
}

fn section_id(s: crate::design::Section) -> &'static str {
    use crate::design::Section::*;
    match s {
        Preform => "preform",
        Pavilion => "pavilion",
        Girdle => "girdle",
        Crown => "crown",
        Table => "table",
    }
}

/// The sheet's body (everything inside `<svg>`), A4 in points.
fn body(cut: &Cut, steps: &[SheetStep], o: &SheetOptions) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        r##"<rect x="0" y="0" width="{}" height="{}" fill="#fff"/>"##,
        A4.0, A4.1
    );
    let (title, lines, _) = header_lines(cut, o);
    let mut y = MARGIN + 14.0;
    text(
        &mut out,
        MARGIN,
        y,
        15.0,
        r#" font-weight="bold" id="title""#,
        &title,
    );
    y += 4.0;
    for (id, l) in &lines {
        y += 11.5;
        let extra = if *id == "title" {
            String::new()
        } else {
            format!(r#" id="{id}""#)
        };
        text(&mut out, MARGIN, y, 8.5, &extra, l);
    }
    y += 8.0;
    // Rows: as large as fits, the drawings get what is left (at least 220 pt).
    let bottom = A4.1 - MARGIN - 12.0;
    let mut size = 7.5;
    let (mut table, mut th) = rows(steps, size);
    while size > 4.5 && bottom - y - th < 220.0 {
        size -= 0.5;
        (table, th) = rows(steps, size);
    }
    let views_h = (bottom - y - th - 10.0).min(430.0);
    let labels = facet_labels(cut, steps);
    let owner = step_of_facets(cut, steps);
    let fill = |i: usize| match owner[i] {
        _ if cut.solid.facets()[i].plane.normal.z.abs() < 1e-9 => GIRDLE,
        Some(s) => TINTS[s % TINTS.len()],
        None => ROUGH,
    };
    let label = |i: usize| labels[i].clone();
    three_views(
        &mut out,
        &cut.solid,
        (MARGIN, y, A4.0 - 2.0 * MARGIN, views_h),
        &Look {
            fill: &fill,
            label: &label,
        },
        true,
    );
    y += views_h + 10.0;
    let _ = writeln!(out, r#"<g id="rows" transform="translate(0 {})">"#, n(y));
    out.push_str(&table);
    out.push_str("</g>\n");
    let foot = format!(
        "facetlab sheet · lengths per width W = 1 · angles to the girdle plane · {} steps",
        steps.len()
    );
    text(
        &mut out,
        MARGIN,
        A4.1 - MARGIN + 6.0,
        6.5,
        r##" fill="#777""##,
        &foot,
    );
    out
}

const TINTS: &[&str] = &[
    "#fbe3a6", "#cfe6fa", "#d6f2cf", "#f8d2df", "#e2dafa", "#fbdcc0", "#cdeeed", "#eeeec4",
    "#e6d3c4", "#dfe6f2",
];

fn svg_open(physical: bool) -> String {
    let (w, h) = if physical {
        ("210mm".to_string(), "297mm".to_string())
    } else {
        (A4.0.to_string(), A4.1.to_string())
    };
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {} {}" font-family="{FONT}" fill="{INK}">"#,
        A4.0, A4.1
    )
}

/// The cutting sheet as a standalone SVG document, one A4 page (210 × 297 mm).
pub fn sheet_svg(cut: &Cut, steps: &[SheetStep], o: &SheetOptions) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n{}\n{}</svg>\n",
        svg_open(true),
        body(cut, steps, o)
    )
}

/// The cutting sheet as an HTML page that prints on one A4 page.
pub fn sheet_html(cut: &Cut, steps: &[SheetStep], o: &SheetOptions) -> String {
    let (title, _, _) = header_lines(cut, o);
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{} — cutting sheet</title>\n<style>@page {{ size: A4; margin: 0 }} html, body {{ margin: 0; background: #888 }} svg {{ display: block; margin: 0 auto; background: #fff; width: 210mm; height: 297mm }} @media print {{ html, body {{ background: #fff }} }}</style></head>\n<body>\n{}\n{}</svg>\n</body></html>\n",
        esc(&title),
        svg_open(true),
        body(cut, steps, o)
    )
}

/// The cutting sheet as a one-page A4 PDF (595.28 × 841.89 pt), vector, its text in the
/// bundled DejaVu Sans.
pub fn sheet_pdf(cut: &Cut, steps: &[SheetStep], o: &SheetOptions) -> Result<Vec<u8>> {
    let svg = format!("{}\n{}</svg>\n", svg_open(false), body(cut, steps, o));
    svg_to_pdf(&svg)
}

/// An SVG document (its size in points) as a one-page PDF.
pub fn svg_to_pdf(svg: &str) -> Result<Vec<u8>> {
    use svg2pdf::usvg;
    let mut opt = usvg::Options {
        font_family: "DejaVu Sans".to_string(),
        ..Default::default()
    };
    opt.fontdb_mut()
        .load_font_data(crate::plot::font_bytes().to_vec());
    let tree = usvg::Tree::from_str(svg, &opt).map_err(|e| Error::Invalid {
        field: "sheet".into(),
        message: format!("the page's SVG did not parse: {e}"),
    })?;
    svg2pdf::to_pdf(
        &tree,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions::default(),
    )
    .map_err(|e| Error::Invalid {
        field: "sheet".into(),
        message: format!("PDF conversion failed: {e}"),
    })
}
