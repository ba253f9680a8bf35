//! The diagram's page: its heading, the three views side by side, the text block and the notes.

use super::side::side_annotations;
use super::svg::{esc, text, wrap, View, DIM, INK};
use super::text_block::text_block;
use super::views::facet_view;
use crate::cut::Cut;
use crate::geometry::DVec2;
use std::fmt::Write as _;

/// The page's least width; wider when the cutting order's indices need it.
const WIDTH: f64 = 1000.0;
const FONT: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";

/// The design's title: its GemCad record's first title line, else the cut's name.
fn title_of(cut: &Cut) -> String {
    cut.record
        .as_ref()
        .and_then(|r| r.title.iter().find(|t| !t.trim().is_empty()))
        .map_or_else(|| cut.name.clone(), |t| t.trim().to_string())
}

/// The page's heading: the title, the further title lines (author, credits), and a line with
/// the design's kind, facets, index, gear and symmetry; returns where the views start and the
/// notes to print under them.
fn heading(out: &mut String, cut: &Cut) -> (f64, Vec<String>) {
    use crate::cut::record::DIAMOND_RI;
    let record = crate::cut::GemcadRecord::for_file(cut, 0, DIAMOND_RI);
    let title = title_of(cut);
    let bold = r#" font-weight="bold""#;
    let grey = r##" fill="#555""##;
    let mut y = 38.0;
    text(out, DVec2::new(30.0, y), 22.0, "start", bold, &title);
    // Further title lines: every one but the first shown (a design's author, credits).
    let mut shown_first = false;
    for t in record
        .title
        .iter()
        .map(|t| t.trim())
        .filter(|t| !t.is_empty())
    {
        if !shown_first && t == title {
            shown_first = true;
            continue;
        }
        y += 19.0;
        text(out, DVec2::new(30.0, y), 13.0, "start", "", t);
    }
    let kind = match (&cut.family, &cut.record) {
        (Some(f), _) => f.clone(),
        (None, Some(_)) => "GemCad design".to_string(),
        (None, None) => "cut".to_string(),
    };
    let mut facts = vec![kind, format!("{} facets", cut.solid.facets().len())];
    if let Some(ri) = record.ri {
        let material = crate::optics::Material::for_index(ri)
            .map(|m| m.name)
            .filter(|n| !n.starts_with("ri:"))
            .map_or(String::new(), |n| format!(" ({n})"));
        facts.push(format!("index {ri}{material}"));
    }
    let gear = if record.gear.fract() == 0.0 {
        format!("{:.0}", record.gear)
    } else {
        record.gear.to_string()
    };
    facts.push(if record.gear_offset == 0.0 {
        format!("gear {gear}")
    } else {
        format!("gear {gear} (offset {})", record.gear_offset)
    });
    facts.push(match (record.symmetry.max(1), record.mirror) {
        (1, false) => "no symmetry".to_string(),
        (1, true) => "mirror symmetry".to_string(),
        (k, m) => format!("{k}-fold symmetry{}", if m { " with mirror" } else { "" }),
    });
    facts.push("lengths in widths W".to_string());
    y += 22.0;
    text(
        out,
        DVec2::new(30.0, y),
        13.0,
        "start",
        grey,
        &facts.join(" · "),
    );
    (y + 18.0, record.footnotes.clone())
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
    let mut body = String::new();
    let out = &mut body;
    let (top, notes) = heading(out, cut);
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

    // Text block, then the notes across the page.
    let (text_bottom, text_right) = text_block(out, cut, &props, &summary, &tiers, top);
    let width = WIDTH.max((text_right + 24.0).ceil());
    let mut y = side_bottom.max(text_bottom) + 36.0;
    if !notes.is_empty() {
        text(
            out,
            DVec2::new(30.0, y),
            13.0,
            "start",
            r#" font-weight="bold""#,
            "Notes",
        );
        for n in &notes {
            for l in wrap(n, 12.0, width - 60.0) {
                y += 17.0;
                text(out, DVec2::new(30.0, y), 12.0, "start", "", &l);
            }
        }
        y += 10.0;
    }
    let height = (y - 6.0).ceil();

    let mut doc = String::new();
    let _ = writeln!(doc, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        doc,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="{FONT}" fill="{INK}">"#
    );
    let _ = writeln!(doc, "<title>{} facet diagram</title>", esc(&title_of(cut)));
    let _ = writeln!(
        doc,
        r#"<defs><marker id="arrow" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" markerHeight="7" orient="auto-start-reverse"><path d="M0,1 L10,5 L0,9 z" fill="{DIM}"/></marker></defs>"#
    );
    let _ = writeln!(doc, r##"<rect width="100%" height="100%" fill="#fff"/>"##);
    doc.push_str(&body);
    doc.push_str("</svg>\n");
    doc
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
    fn imported_mesh_diagram_is_well_formed() {
        let rb = Cut::from_family("rb", "round-brilliant", &Default::default()).unwrap();
        let planes =
            crate::io::mesh::read_obj(crate::io::mesh::write_obj(&rb).as_bytes(), "x.obj").unwrap();
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

    /// The right edge of every text element: its x plus its measured width for a start
    /// anchor (half of it centred, none at the end).
    fn right_edges(svg: &str) -> Vec<(f64, String)> {
        let mut out = Vec::new();
        for part in svg.split("<text ").skip(1) {
            let attr = |k: &str| -> Option<String> {
                let i = part.find(&format!("{k}=\""))? + k.len() + 2;
                Some(part[i..].split('"').next()?.to_string())
            };
            let x: f64 = attr("x").unwrap().parse().unwrap();
            let size: f64 = attr("font-size").unwrap().parse().unwrap();
            let body = part.split('>').nth(1).unwrap().split('<').next().unwrap();
            let body = body
                .replace("&amp;", "&")
                .replace("&lt;", "<")
                .replace("&gt;", ">");
            let w = crate::plot::diagram::svg::text_width(&body, size);
            let right = match attr("text-anchor").as_deref() {
                Some("middle") => x + w / 2.0,
                Some("end") => x,
                _ => x + w,
            };
            out.push((right, body));
        }
        out
    }

    #[test]
    fn a_design_diagram_shows_its_heading_notes_and_every_index() {
        // A round brilliant written on a 120 gear (fractional indices, long lines) and read
        // back as a design with two title lines, an index and a note.
        let rb = Cut::from_family("rb", "round-brilliant", &Default::default()).unwrap();
        let text = crate::io::asc::write(&rb, 120)
            .replace("H rb\n", "H PC 99.001 A Test Brilliant\nH by A. Faceter\n")
            .replace("I 2.417\n", "I 1.54\n")
            + "F Polish the table last; cut the girdle to 3 %.\n";
        let cut = crate::io::asc::parse(text.as_bytes(), "t.asc")
            .unwrap()
            .to_cut("t")
            .unwrap();
        let svg = diagram(&cut);
        check_balanced(&svg).unwrap();
        for want in [
            ">PC 99.001 A Test Brilliant</text>",
            ">by A. Faceter</text>",
            "index 1.54 (quartz) · gear 120 · 8-fold symmetry with mirror",
            ">Notes</text>",
            ">Polish the table last; cut the girdle to 3 %.</text>",
        ] {
            assert!(svg.contains(want), "{want} missing");
        }
        // Every text, every index included, ends inside the page.
        let width: f64 = svg
            .split("<svg ")
            .nth(1)
            .and_then(|t| t.split("width=\"").nth(1))
            .and_then(|t| t.split('"').next())
            .unwrap()
            .parse()
            .unwrap();
        let edges = right_edges(&svg);
        assert!(edges.iter().any(|(_, t)| t.contains("-")), "indices shown");
        for (right, t) in edges {
            assert!(right <= width - 4.0, "`{t}` ends at {right:.0} of {width}");
        }
    }
}
