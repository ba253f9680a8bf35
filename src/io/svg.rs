//! A cutter's facet diagram as SVG, in the manner of a GemCad printout.
//!
//! One page with four parts, all views orthographic and drawn at one scale:
//! - face up (crown, seen from above): every upward facet outlined and tinted by tier, the
//!   outline drawn heavier, one label per tier;
//! - face down (pavilion, seen from below, so left and right are mirrored);
//! - side view (seen from the front, −y): the facets facing the viewer, the silhouette, the
//!   girdle plane, crown and pavilion angles, and dimension lines for the table width, crown
//!   height, pavilion depth and total depth;
//! - a text block with the proportions, each tier's angle and facet count, and the cutting
//!   instructions ([`crate::io::asc::cutting_instructions`]: each tier in cutting order,
//!   pavilion first, with its angle at 0.01° and its indices on the design's gear).
//!
//! The SVG is written by hand (no drawing library) and every name is escaped, so the output is
//! well-formed XML.

use crate::cut::Cut;
use crate::geometry::{DVec2, DVec3, Polyhedron};
use std::fmt::Write as _;

const WIDTH: f64 = 1000.0;
const FONT: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";
const INK: &str = "#222";
const DIM: &str = "#1f4e8c";

/// Light tints for tiers, in order of appearance (the girdle gets grey).
const TINTS: &[&str] = &[
    "#fbe3a6", "#cfe6fa", "#d6f2cf", "#f8d2df", "#e2dafa", "#fbdcc0", "#cdeeed", "#eeeec4",
    "#e6d3c4", "#dfe6f2",
];

/// Escape text for XML content and attribute values.
fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if (c as u32) < 0x20 && c != '\t' => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// `x` with `dec` decimals, never `-0.0`.
fn fixed(x: f64, dec: usize) -> String {
    let s = format!("{x:.dec$}");
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// A fraction as a percentage with one decimal.
fn pct(v: f64) -> String {
    format!("{}%", fixed(100.0 * v, 1))
}

/// Maps model coordinates of one view to page pixels.
#[derive(Clone, Copy)]
struct View {
    /// Page position of the model point `origin`.
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

fn points_attr(pts: &[DVec2]) -> String {
    pts.iter()
        .map(|p| format!("{:.2},{:.2}", p.x, p.y))
        .collect::<Vec<_>>()
        .join(" ")
}

/// Convex hull of 2-D points, counter-clockwise (monotone chain).
fn hull2(mut pts: Vec<DVec2>) -> Vec<DVec2> {
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup_by(|a, b| a.distance(*b) < 1e-12);
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut lower: Vec<DVec2> = Vec::new();
    for &p in &pts {
        while lower.len() >= 2 && cross(lower[lower.len() - 2], lower[lower.len() - 1], p) <= 0.0 {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<DVec2> = Vec::new();
    for &p in pts.iter().rev() {
        while upper.len() >= 2 && cross(upper[upper.len() - 2], upper[upper.len() - 1], p) <= 0.0 {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

fn text(out: &mut String, p: DVec2, size: f64, anchor: &str, extra: &str, s: &str) {
    let _ = writeln!(
        out,
        r#"<text x="{:.1}" y="{:.1}" font-size="{size}" text-anchor="{anchor}"{extra}>{}</text>"#,
        p.x,
        p.y,
        esc(s)
    );
}

/// A label with a white halo, readable over facet lines.
fn label(out: &mut String, p: DVec2, size: f64, anchor: &str, s: &str) {
    text(
        out,
        p,
        size,
        anchor,
        r##" fill="#111" stroke="#fff" stroke-width="3" stroke-linejoin="round" paint-order="stroke""##,
        s,
    );
}

fn line(out: &mut String, a: DVec2, b: DVec2, attrs: &str) {
    let _ = writeln!(
        out,
        r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" {attrs}/>"#,
        a.x, a.y, b.x, b.y
    );
}

/// A dimension line with arrow heads from `a` to `b` (page pixels).
fn dimension(out: &mut String, a: DVec2, b: DVec2) {
    let attrs = format!(
        r#"stroke="{DIM}" stroke-width="1" marker-start="url(#arrow)" marker-end="url(#arrow)""#
    );
    line(out, a, b, &attrs);
}

fn tint(tiers: &[String], tier: &str) -> &'static str {
    if tier == "girdle" {
        return "#e4e4e4";
    }
    let i = tiers
        .iter()
        .filter(|t| t.as_str() != "girdle")
        .position(|t| t == tier)
        .unwrap_or(0);
    TINTS[i % TINTS.len()]
}

/// Draw the facets selected by `facing` projected by `proj` and their outline in a view, and
/// with `labels` one label per tier.
fn facet_view(
    out: &mut String,
    solid: &Polyhedron,
    tiers: &[String],
    view: View,
    facing: impl Fn(DVec3) -> bool,
    proj: impl Fn(DVec3) -> DVec2,
    labels: bool,
) {
    let mut shown: Vec<usize> = Vec::new();
    for (i, f) in solid.facets().iter().enumerate() {
        if !facing(f.plane.normal) {
            continue;
        }
        shown.push(i);
        let pts: Vec<DVec2> = solid
            .facet_polygon(i)
            .into_iter()
            .map(|p| view.px(proj(p)))
            .collect();
        let _ = writeln!(
            out,
            r#"<polygon points="{}" fill="{}" stroke="{INK}" stroke-width="0.7" stroke-linejoin="round"><title>{} ({})</title></polygon>"#,
            points_attr(&pts),
            tint(tiers, &f.tier),
            esc(&f.name),
            esc(&f.tier)
        );
    }
    let outline = hull2(solid.vertices().iter().map(|p| view.px(proj(*p))).collect());
    let _ = writeln!(
        out,
        r#"<polygon points="{}" fill="none" stroke="{INK}" stroke-width="1.8" stroke-linejoin="round"/>"#,
        points_attr(&outline)
    );
    if !labels {
        return;
    }
    // One label per tier, spread around the view: the facet nearest a target direction.
    let mut k = 0;
    for tier in tiers {
        let members: Vec<usize> = shown
            .iter()
            .copied()
            .filter(|&i| &solid.facets()[i].tier == tier)
            .collect();
        if members.is_empty() {
            continue;
        }
        let centre = |i: usize| view.px(proj(solid.facets()[i].centroid));
        let at = if members.len() == 1 {
            centre(members[0])
        } else {
            let target = (100.0 + 67.0 * k as f64).to_radians();
            let dir = DVec2::new(target.cos(), -target.sin());
            k += 1;
            let best = members
                .iter()
                .copied()
                .max_by(|&a, &b| {
                    let score = |i: usize| {
                        let d = centre(i) - view.centre;
                        d.normalize_or_zero().dot(dir)
                    };
                    score(a).total_cmp(&score(b))
                })
                .unwrap_or(members[0]);
            centre(best)
        };
        label(out, at + DVec2::new(0.0, 3.5), 10.5, "middle", tier);
    }
}

/// The facet diagram of a cut as a standalone SVG document.
pub fn diagram(cut: &Cut) -> String {
    let solid = &cut.solid;
    let props = cut.proportions();
    let summary = cut.tiers();
    let mut tiers: Vec<String> = Vec::new();
    for t in &summary {
        if !tiers.contains(&t.name) {
            tiers.push(t.name.clone());
        }
    }
    let (lo, hi) = solid.bounding_box();
    let (ex, ey, ez) = (
        (hi.x - lo.x).max(1e-9),
        (hi.y - lo.y).max(1e-9),
        (hi.z - lo.z).max(1e-9),
    );
    let scale = (250.0 / ex.max(ey)).min(440.0 / ex).min(230.0 / ez);
    let mid = 0.5 * (lo + hi);

    // Layout.
    let top = 78.0;
    let up = View {
        centre: DVec2::new(190.0, top + 170.0),
        origin: mid.truncate(),
        scale,
    };
    let down = View {
        centre: DVec2::new(530.0, top + 170.0),
        origin: DVec2::new(-mid.x, mid.y),
        scale,
    };
    let side_top = top + 330.0;
    let side = View {
        centre: DVec2::new(360.0, side_top + 78.0 + scale * (hi.z - lo.z) / 2.0),
        origin: DVec2::new(mid.x, mid.z),
        scale,
    };
    let side_bottom = side_top + 78.0 + scale * ez;

    let mut body = String::new();
    let out = &mut body;

    // Title.
    text(
        out,
        DVec2::new(30.0, 38.0),
        22.0,
        "start",
        r#" font-weight="bold""#,
        &cut.name,
    );
    let mut sub = match &cut.family {
        Some(f) => format!("{f} · "),
        None => String::new(),
    };
    sub += &format!(
        "{} facets · lengths in girdle diameters",
        solid.facets().len()
    );
    text(
        out,
        DVec2::new(30.0, 60.0),
        13.0,
        "start",
        r##" fill="#555""##,
        &sub,
    );

    // Face-up and face-down views.
    text(
        out,
        DVec2::new(up.centre.x, top + 12.0),
        13.0,
        "middle",
        r#" font-weight="bold""#,
        "Crown — face up",
    );
    facet_view(
        out,
        solid,
        &tiers,
        up,
        |n| n.z > 1e-9,
        |p| p.truncate(),
        true,
    );
    text(
        out,
        DVec2::new(down.centre.x, top + 12.0),
        13.0,
        "middle",
        r#" font-weight="bold""#,
        "Pavilion — face down",
    );
    facet_view(
        out,
        solid,
        &tiers,
        down,
        |n| n.z < -1e-9,
        |p| DVec2::new(-p.x, p.y),
        true,
    );
    text(
        out,
        DVec2::new(down.centre.x, top + 28.0),
        11.0,
        "middle",
        r##" fill="#555""##,
        "seen from below (mirrored)",
    );

    // Side view.
    text(
        out,
        DVec2::new(side.centre.x, side_top + 12.0),
        13.0,
        "middle",
        r#" font-weight="bold""#,
        "Side view",
    );
    text(
        out,
        DVec2::new(side.centre.x, side_top + 28.0),
        11.0,
        "middle",
        r##" fill="#555""##,
        "seen from the front",
    );
    facet_view(
        out,
        solid,
        &tiers,
        side,
        |n| n.y < -1e-9,
        |p| DVec2::new(p.x, p.z),
        false,
    );
    side_annotations(out, solid, &props, side, lo, hi);

    // Text block.
    let text_bottom = text_block(out, cut, &props, &summary, &tiers, top);
    let height = (side_bottom.max(text_bottom) + 30.0).ceil();

    let mut doc = String::new();
    let _ = writeln!(doc, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        doc,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{height}" viewBox="0 0 {WIDTH} {height}" font-family="{FONT}" fill="{INK}">"#
    );
    let _ = writeln!(doc, "<title>{} facet diagram</title>", esc(&cut.name));
    let _ = writeln!(
        doc,
        r#"<defs><marker id="arrow" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" markerHeight="7" orient="auto-start-reverse"><path d="M0,1 L10,5 L0,9 z" fill="{DIM}"/></marker></defs>"#
    );
    let _ = writeln!(doc, r##"<rect width="100%" height="100%" fill="#fff"/>"##);
    doc.push_str(&body);
    doc.push_str("</svg>\n");
    doc
}

fn side_annotations(
    out: &mut String,
    solid: &Polyhedron,
    props: &crate::cut::Proportions,
    side: View,
    lo: DVec3,
    hi: DVec3,
) {
    let z_bot = lo.z;
    let g_bot = z_bot + props.pavilion_depth;
    let g_top = g_bot + props.girdle;
    let z_table = g_top + props.crown_height;
    let px = |x: f64, z: f64| side.px(DVec2::new(x, z));
    let thin = r##"stroke="#8aa4c8" stroke-width="0.6" stroke-dasharray="3,3""##;
    // Girdle plane across the stone.
    let gz = 0.5 * (g_top + g_bot);
    line(out, px(lo.x - 0.06, gz), px(hi.x + 0.06, gz), thin);
    // Right: crown height and pavilion depth. Left: total depth.
    let xr = px(hi.x, 0.0).x + 28.0;
    let xl = px(lo.x, 0.0).x - 110.0;
    for z in [z_table, g_top, g_bot, z_bot] {
        line(
            out,
            DVec2::new(px(hi.x, 0.0).x + 4.0, px(0.0, z).y),
            DVec2::new(xr + 6.0, px(0.0, z).y),
            thin,
        );
    }
    for z in [hi.z, lo.z] {
        line(
            out,
            DVec2::new(xl - 6.0, px(0.0, z).y),
            DVec2::new(px(lo.x, 0.0).x - 4.0, px(0.0, z).y),
            thin,
        );
    }
    // A vertical dimension at x = xr between heights a and b, labelled to its right.
    let side_dimension = |out: &mut String, a: f64, b: f64, text: String| {
        dimension(
            out,
            DVec2::new(xr, px(0.0, a).y),
            DVec2::new(xr, px(0.0, b).y),
        );
        let y = px(0.0, 0.5 * (a + b)).y + 4.0;
        label(out, DVec2::new(xr + 8.0, y), 12.0, "start", &text);
    };
    if props.crown_height > 1e-9 {
        side_dimension(
            out,
            g_top,
            z_table,
            format!("crown height {}", pct(props.crown_height)),
        );
    }
    if props.pavilion_depth > 1e-9 {
        side_dimension(
            out,
            g_bot,
            z_bot,
            format!("pavilion depth {}", pct(props.pavilion_depth)),
        );
    }
    dimension(
        out,
        DVec2::new(xl, px(0.0, hi.z).y),
        DVec2::new(xl, px(0.0, lo.z).y),
    );
    let y = px(0.0, 0.5 * (hi.z + lo.z)).y;
    label(
        out,
        DVec2::new(xl - 8.0, y - 3.0),
        12.0,
        "end",
        "total depth",
    );
    label(
        out,
        DVec2::new(xl - 8.0, y + 13.0),
        12.0,
        "end",
        &pct(props.total_depth),
    );
    // Table width above the stone, from the table facet's extent in x.
    if let Some(ti) = solid
        .facets()
        .iter()
        .enumerate()
        .filter(|(_, f)| f.plane.normal.z > 1.0 - 1e-9)
        .max_by(|a, b| a.1.plane.offset.total_cmp(&b.1.plane.offset))
        .map(|(i, _)| i)
    {
        let xs: Vec<f64> = solid.facet_polygon(ti).iter().map(|p| p.x).collect();
        let (x0, x1) = (
            xs.iter().copied().fold(f64::INFINITY, f64::min),
            xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        );
        let y = px(0.0, hi.z).y - 18.0;
        for x in [x0, x1] {
            line(
                out,
                DVec2::new(px(x, 0.0).x, y - 5.0),
                DVec2::new(px(x, 0.0).x, px(0.0, hi.z).y - 3.0),
                thin,
            );
        }
        dimension(
            out,
            DVec2::new(px(x0, 0.0).x, y),
            DVec2::new(px(x1, 0.0).x, y),
        );
        label(
            out,
            DVec2::new(px(0.5 * (x0 + x1), 0.0).x, y - 5.0),
            12.0,
            "middle",
            &format!("table {}", pct(props.table)),
        );
    }
    // Crown and pavilion angles at the left girdle corner.
    let corner_top = px(lo.x, g_top);
    let corner_bot = px(lo.x, g_bot);
    let arc = |out: &mut String, c: DVec2, deg: f64, up: bool, name: &str| {
        if !(deg > 0.5 && deg < 89.5) {
            return;
        }
        let r = 40.0;
        let a = deg.to_radians();
        let sign = if up { -1.0 } else { 1.0 };
        let end = c + DVec2::new(r * a.cos(), sign * r * a.sin());
        let sweep = if up { 0 } else { 1 };
        line(
            out,
            c,
            c + DVec2::new(r + 8.0, 0.0),
            &format!(r#"stroke="{DIM}" stroke-width="1""#),
        );
        let _ = writeln!(
            out,
            r#"<path d="M{:.2},{:.2} A{r},{r} 0 0 {sweep} {:.2},{:.2}" fill="none" stroke="{DIM}" stroke-width="1.3"/>"#,
            c.x + r,
            c.y,
            end.x,
            end.y
        );
        // The value outside the stone, left of the corner, above or below the girdle.
        let at = c + DVec2::new(-8.0, if up { -8.0 } else { 17.0 });
        let _ = writeln!(
            out,
            r##"<text x="{:.1}" y="{:.1}" font-size="11.5" text-anchor="end" fill="{DIM}" stroke="#fff" stroke-width="3" stroke-linejoin="round" paint-order="stroke">{name} {deg:.2}°</text>"##,
            at.x, at.y
        );
    };
    arc(out, corner_top, props.crown_angle, true, "crown");
    arc(out, corner_bot, props.pavilion_angle, false, "pavilion");
}

fn text_block(
    out: &mut String,
    cut: &Cut,
    props: &crate::cut::Proportions,
    summary: &[crate::cut::TierSummary],
    tiers: &[String],
    top: f64,
) -> f64 {
    let x = 720.0;
    let mut y = top + 12.0;
    let bold = r#" font-weight="bold""#;
    text(out, DVec2::new(x, y), 13.0, "start", bold, "Proportions");
    y += 22.0;
    let rows = [
        ("table", pct(props.table)),
        ("crown angle", format!("{}°", fixed(props.crown_angle, 2))),
        (
            "pavilion angle",
            format!("{}°", fixed(props.pavilion_angle, 2)),
        ),
        ("crown height", pct(props.crown_height)),
        ("pavilion depth", pct(props.pavilion_depth)),
        ("girdle", pct(props.girdle)),
        ("total depth", pct(props.total_depth)),
    ];
    for (k, v) in rows {
        text(out, DVec2::new(x, y), 12.0, "start", "", k);
        text(out, DVec2::new(x + 250.0, y), 12.0, "end", "", &v);
        y += 18.0;
    }
    y += 16.0;
    text(out, DVec2::new(x, y), 13.0, "start", bold, "Tiers");
    let grey = r##" fill="#555""##;
    text(out, DVec2::new(x + 190.0, y), 11.0, "end", grey, "angle");
    text(out, DVec2::new(x + 250.0, y), 11.0, "end", grey, "count");
    y += 20.0;
    for t in summary {
        let _ = writeln!(
            out,
            r#"<rect x="{:.1}" y="{:.1}" width="11" height="11" fill="{}" stroke="{INK}" stroke-width="0.6"/>"#,
            x,
            y - 10.0,
            tint(tiers, &t.name)
        );
        text(out, DVec2::new(x + 18.0, y), 12.0, "start", "", &t.name);
        text(
            out,
            DVec2::new(x + 190.0, y),
            12.0,
            "end",
            "",
            &format!("{}°", fixed(t.angle, 2)),
        );
        text(
            out,
            DVec2::new(x + 250.0, y),
            12.0,
            "end",
            "",
            &t.count.to_string(),
        );
        y += 18.0;
    }
    y += 16.0;
    let s = &cut.solid;
    text(
        out,
        DVec2::new(x, y),
        11.0,
        "start",
        grey,
        &format!(
            "{} facets, {} vertices",
            s.facets().len(),
            s.vertices().len()
        ),
    );
    y += 16.0;
    text(
        out,
        DVec2::new(x, y),
        11.0,
        "start",
        grey,
        &format!("volume {:.4} W³", s.volume()),
    );
    if !cut.params.is_empty() {
        y += 26.0;
        text(out, DVec2::new(x, y), 13.0, "start", bold, "Parameters");
        y += 20.0;
        for (k, v) in &cut.params {
            text(out, DVec2::new(x, y), 11.0, "start", "", k);
            text(
                out,
                DVec2::new(x + 250.0, y),
                11.0,
                "end",
                "",
                &format!("{v}"),
            );
            y += 16.0;
        }
    }
    // Cutting instructions: tiers in cutting order, pavilion first, angles at 0.01°, indices
    // on the design's gear (96 for generated cuts), eight to a line.
    let c = crate::io::asc::cutting_instructions(cut, 0);
    y += 26.0;
    let gear = if c.gear.fract() == 0.0 {
        format!("{:.0}", c.gear)
    } else {
        format!("{}", c.gear)
    };
    text(
        out,
        DVec2::new(x, y),
        13.0,
        "start",
        bold,
        &format!("Cutting order (gear {gear})"),
    );
    let mut side = "";
    for st in &c.steps {
        if st.side != side {
            side = st.side;
            y += 18.0;
            text(
                out,
                DVec2::new(x, y),
                11.0,
                "start",
                grey,
                &side.to_uppercase(),
            );
        }
        y += 15.0;
        text(
            out,
            DVec2::new(x, y),
            11.0,
            "start",
            "",
            &format!("{}. {}", st.step, st.tier),
        );
        text(
            out,
            DVec2::new(x + 150.0, y),
            11.0,
            "end",
            "",
            &format!("{:.2}°", st.angle),
        );
        // Two digits, as GemCad prints them (03-09-15).
        let idx = st.padded_indices();
        for (k, chunk) in idx.chunks(8).enumerate() {
            if k > 0 {
                y += 13.0;
            }
            text(
                out,
                DVec2::new(x + 158.0, y),
                10.0,
                "start",
                grey,
                &chunk.join("-"),
            );
        }
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Element names open and closed in order; self-closing tags, the XML declaration and
    /// comments skipped. Returns an error at the first mismatch.
    fn check_balanced(svg: &str) -> std::result::Result<usize, String> {
        let mut stack: Vec<String> = Vec::new();
        let mut count = 0;
        let mut rest = svg;
        while let Some(i) = rest.find('<') {
            rest = &rest[i..];
            let end = rest.find('>').ok_or("unclosed tag")?;
            let tag = &rest[1..end];
            rest = &rest[end + 1..];
            if tag.starts_with('?') || tag.starts_with('!') {
                continue;
            }
            if tag.contains('<') {
                return Err(format!("`<` inside tag {tag}"));
            }
            if let Some(name) = tag.strip_prefix('/') {
                let open = stack.pop().ok_or(format!("stray </{name}>"))?;
                if open != name.trim() {
                    return Err(format!("<{open}> closed by </{name}>"));
                }
            } else if !tag.ends_with('/') {
                stack.push(tag.split_whitespace().next().unwrap_or("").to_string());
                count += 1;
            } else {
                count += 1;
            }
        }
        if !stack.is_empty() {
            return Err(format!("unclosed {stack:?}"));
        }
        // Text outside tags must not hold a bare `&` that is not an entity.
        for (i, _) in svg.match_indices('&') {
            let ent = &svg[i..svg.len().min(i + 7)];
            if !["&amp;", "&lt;", "&gt;", "&quot;", "&apos;"]
                .iter()
                .any(|e| ent.starts_with(e))
            {
                return Err(format!("bare & at {i}"));
            }
        }
        Ok(count)
    }

    #[test]
    fn round_brilliant_diagram_is_well_formed_and_complete() {
        let cut =
            Cut::from_family("GIA <ideal> & co", "round-brilliant", &Default::default()).unwrap();
        let svg = diagram(&cut);
        assert!(svg.contains("<svg") && svg.trim_end().ends_with("</svg>"));
        let elements = check_balanced(&svg).unwrap();
        assert!(elements > cut.solid.facets().len(), "{elements}");
        for t in cut.tiers() {
            assert!(
                svg.contains(&format!(">{}</text>", t.name)),
                "tier {} missing",
                t.name
            );
        }
        assert!(svg.contains("GIA &lt;ideal&gt; &amp; co"));
        // Proportions in the text block and on the side view.
        let p = cut.proportions();
        assert!(svg.contains(&format!("{:.2}°", p.crown_angle)));
        // The cutting instructions: tiers in cutting order with their indices on gear 96.
        assert!(svg.contains("Cutting order (gear 96)") && svg.contains(">PAVILION<"));
        assert!(
            svg.contains(">24-36-48-60-72-84-96-12<"),
            "bezel/main indices"
        );
        assert!(svg.contains(&format!("crown height {:.1}%", 100.0 * p.crown_height)));
        assert!(svg.contains(&format!("table {:.1}%", 100.0 * p.table)));
        // One polygon per facet shown in each view: crown (33) + pavilion (24) + front half.
        assert!(svg.matches("<polygon").count() > 33 + 24 + 3);
    }

    #[test]
    fn numbers_never_show_negative_zero() {
        assert_eq!(fixed(-1e-17, 1), "0.0");
        assert_eq!(fixed(-0.04, 1), "0.0");
        assert_eq!(fixed(-0.06, 1), "-0.1");
        assert_eq!(pct(0.5712), "57.1%");
        assert_eq!(esc("a<b>&\"'\n"), "a&lt;b&gt;&amp;&quot;&apos; ");
    }

    #[test]
    fn imported_mesh_diagram_is_well_formed() {
        let rb = Cut::from_family("rb", "round-brilliant", &Default::default()).unwrap();
        let planes =
            super::super::mesh::read_obj(super::super::mesh::write_obj(&rb).as_bytes(), "x.obj")
                .unwrap();
        let cut = Cut::from_planes("imported \"stone\"", &planes).unwrap();
        let svg = diagram(&cut);
        check_balanced(&svg).unwrap();
        for t in ["table", "girdle"] {
            assert!(svg.contains(&format!(">{t}</text>")), "{t}");
        }
        for t in &cut.tiers() {
            assert!(svg.contains(&format!(">{}</text>", t.name)), "{}", t.name);
        }
        assert!(svg.contains("imported &quot;stone&quot;"));
    }
}
