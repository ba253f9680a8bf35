//! The diagram's SVG primitives, written by hand: escaping, number formats, the map from a
//! view's model coordinates to page pixels, and text, labels, lines and dimension lines.

use crate::geometry::DVec2;
use std::fmt::Write as _;

/// Ink of lines and text.
pub(super) const INK: &str = "#222";
/// Colour of dimension lines and angle marks.
pub(super) const DIM: &str = "#1f4e8c";

/// Escape text for XML content and attribute values.
pub(super) fn esc(s: &str) -> String {
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
pub(super) fn fixed(x: f64, dec: usize) -> String {
    let s = format!("{x:.dec$}");
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// A fraction as a percentage with one decimal.
pub(super) fn pct(v: f64) -> String {
    format!("{}%", fixed(100.0 * v, 1))
}

/// Maps model coordinates of one view to page pixels.
#[derive(Clone, Copy)]
pub(super) struct View {
    /// Page position of the model point `origin`.
    pub(super) centre: DVec2,
    /// The model point drawn at `centre`.
    pub(super) origin: DVec2,
    /// Page pixels per model unit.
    pub(super) scale: f64,
}

impl View {
    /// The page position of model point `p`.
    pub(super) fn px(&self, p: DVec2) -> DVec2 {
        let d = (p - self.origin) * self.scale;
        DVec2::new(self.centre.x + d.x, self.centre.y - d.y)
    }
}

pub(super) fn points_attr(pts: &[DVec2]) -> String {
    pts.iter()
        .map(|p| format!("{:.2},{:.2}", p.x, p.y))
        .collect::<Vec<_>>()
        .join(" ")
}

pub(super) fn text(out: &mut String, p: DVec2, size: f64, anchor: &str, extra: &str, s: &str) {
    let _ = writeln!(
        out,
        r#"<text x="{:.1}" y="{:.1}" font-size="{size}" text-anchor="{anchor}"{extra}>{}</text>"#,
        p.x,
        p.y,
        esc(s)
    );
}

/// Width in pixels of `s` at font size `size` (DejaVu Sans, the page's first font).
pub(super) fn text_width(s: &str, size: f64) -> f64 {
    crate::plot::text::width_at_em(s, size)
}

/// `s` broken at spaces into lines at most `max` pixels wide at font size `size` (a word
/// wider than that stands alone on its line).
pub(super) fn wrap(s: &str, size: f64, max: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut cur = String::new();
    for w in s.split_whitespace() {
        let next = if cur.is_empty() {
            w.to_string()
        } else {
            format!("{cur} {w}")
        };
        if !cur.is_empty() && text_width(&next, size) > max {
            lines.push(std::mem::replace(&mut cur, w.to_string()));
        } else {
            cur = next;
        }
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    lines
}

/// A label with a white halo, readable over facet lines.
pub(super) fn label(out: &mut String, p: DVec2, size: f64, anchor: &str, s: &str) {
    text(
        out,
        p,
        size,
        anchor,
        r##" fill="#111" stroke="#fff" stroke-width="3" stroke-linejoin="round" paint-order="stroke""##,
        s,
    );
}

pub(super) fn line(out: &mut String, a: DVec2, b: DVec2, attrs: &str) {
    let _ = writeln!(
        out,
        r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" {attrs}/>"#,
        a.x, a.y, b.x, b.y
    );
}

/// A dimension line with arrow heads from `a` to `b` (page pixels).
pub(super) fn dimension(out: &mut String, a: DVec2, b: DVec2) {
    let attrs = format!(
        r#"stroke="{DIM}" stroke-width="1" marker-start="url(#arrow)" marker-end="url(#arrow)""#
    );
    line(out, a, b, &attrs);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_never_show_negative_zero() {
        assert_eq!(fixed(-1e-17, 1), "0.0");
        assert_eq!(fixed(-0.04, 1), "0.0");
        assert_eq!(fixed(-0.06, 1), "-0.1");
        assert_eq!(pct(0.5712), "57.1%");
        assert_eq!(esc("a<b>&\"'\n"), "a&lt;b&gt;&amp;&quot;&apos; ");
    }
}
