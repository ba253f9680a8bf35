//! The diagram's text block: the proportions, each tier's angle and facet count, and the
//! cutting instructions.

use super::svg::{fixed, pct, text, text_width, INK};
use super::views::tint;
use crate::cut::Cut;
use crate::geometry::DVec2;
use std::fmt::Write as _;

/// The text block, from `top` at x = 720; returns its bottom and its right edge (the page
/// is made as wide as that needs).
pub(super) fn text_block(
    out: &mut String,
    cut: &Cut,
    props: &crate::cut::Proportions,
    summary: &[crate::cut::TierSummary],
    tiers: &[String],
    top: f64,
) -> (f64, f64) {
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
            text(out, DVec2::new(x + 250.0, y), 11.0, "end", "", &short(*v));
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
    // Columns: the step and tier, the angle right-aligned after the widest of them, the
    // indices after it, eight to a line.
    let name_w = c
        .steps
        .iter()
        .map(|st| text_width(&format!("{}. {}", st.step, st.tier), 11.0))
        .fold(0.0, f64::max);
    let angle_x = x + (name_w + 48.0).max(150.0);
    let idx_x = angle_x + 8.0;
    let mut right = x + 250.0;
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
            DVec2::new(angle_x, y),
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
            let line = chunk.join("-");
            right = right.max(idx_x + text_width(&line, 10.0));
            text(out, DVec2::new(idx_x, y), 10.0, "start", grey, &line);
        }
    }
    (y, right)
}

/// A parameter as a person reads it: at most six decimals, trailing zeros dropped (`0.57`,
/// `41.2573`, not `41.25729999999`).
fn short(v: f64) -> String {
    let t = format!("{v:.6}");
    let t = if t.contains('.') {
        t.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        t
    };
    if t == "-0" {
        "0".into()
    } else {
        t
    }
}
