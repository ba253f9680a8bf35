//! A cut's tilt performance on the report's page: its brightness pictures
//! ([`super::BRIGHTNESS_LIGHT`]) tipped by the report's tilts
//! ([`row`]), and one chart of every cut's light return against the tilt ([`chart`]), an
//! inline SVG (no script, nothing fetched).

use super::{base64, escape, CutReport};
use crate::error::Result;
use crate::plot::palette::{PICTURE_GROUND, TAB10};
use std::fmt::Write;

/// The row of a cut's tilted brightness pictures, each captioned with its tilt and light
/// return.
pub fn row(c: &CutReport) -> Result<String> {
    let mut h = format!(
        "<div class=\"pics tilts\" style=\"grid-template-columns:repeat({},minmax(0,1fr))\">",
        c.tilted.len().max(1)
    );
    for (t, img) in &c.tilted {
        let n = img.size() as u32;
        let rgb = img.to_srgb8(1.0, PICTURE_GROUND);
        let png = crate::io::png::encode_rgb8(n, n, &[&rgb], 0)?;
        let _ = write!(
            h,
            "<figure><img alt=\"{} picture tilted {t}°\" width=\"{n}\" height=\"{n}\" src=\"data:image/png;base64,{}\"><figcaption>{t}°: {:.1} %</figcaption></figure>",
            super::brightness_caption(),
            base64(&png),
            100.0 * img.stats.mean
        );
    }
    h.push_str("</div>\n");
    Ok(h)
}

/// Chart width and height, pixels.
const W: f64 = 560.0;
const H: f64 = 220.0;
/// Plot area: left, top, right, bottom edges.
const L: f64 = 52.0;
const T: f64 = 12.0;
const R: f64 = 380.0;
const B: f64 = 186.0;

/// Every cut's light return in its brightness pictures (% of a white diffuser) against its tilt, one line per cut,
/// the cuts named on the right.
pub fn chart(cuts: &[CutReport]) -> String {
    let points: Vec<Vec<(f64, f64)>> = cuts
        .iter()
        .map(|c| {
            c.tilted
                .iter()
                .map(|(t, img)| (*t, 100.0 * img.stats.mean))
                .collect()
        })
        .collect();
    let all = points.iter().flatten();
    let (t0, t1) = all
        .clone()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let (y0, y1) = all.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
        (a.min(p.1), b.max(p.1))
    });
    if !(t0.is_finite() && y0.is_finite()) {
        return String::new();
    }
    // The y axis on a 5 % grid around the values.
    let (lo, hi) = (
        (y0 / 5.0).floor() * 5.0,
        ((y1 / 5.0).ceil() * 5.0).max(y0 + 5.0),
    );
    let hi = if hi - lo < 5.0 { lo + 5.0 } else { hi };
    let x = |t: f64| {
        if t1 > t0 {
            L + (R - L) * (t - t0) / (t1 - t0)
        } else {
            (L + R) / 2.0
        }
    };
    let y = |v: f64| B - (B - T) * (v - lo) / (hi - lo);
    let mut s = format!(
        "<svg class=\"tiltchart\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {W} {H}\" width=\"{W}\" height=\"{H}\" font-size=\"11\" font-family=\"system-ui,sans-serif\">\
         <rect x=\"{L}\" y=\"{T}\" width=\"{}\" height=\"{}\" fill=\"#fff\" stroke=\"#ccc\"/>",
        R - L,
        B - T
    );
    let step = if hi - lo > 20.0 { 10.0 } else { 5.0 };
    let mut v = lo;
    while v <= hi + 1e-9 {
        let _ = write!(
            s,
            "<line x1=\"{L}\" x2=\"{R}\" y1=\"{0:.1}\" y2=\"{0:.1}\" stroke=\"#eee\"/><text x=\"{1}\" y=\"{2:.1}\" text-anchor=\"end\" fill=\"#555\">{v:.0} %</text>",
            y(v),
            L - 4.0,
            y(v) + 4.0
        );
        v += step;
    }
    for &(t, _) in points.first().map_or(&[][..], |p| &p[..]) {
        let _ = write!(
            s,
            "<text x=\"{:.1}\" y=\"{}\" text-anchor=\"middle\" fill=\"#555\">{t}°</text>",
            x(t),
            B + 14.0
        );
    }
    let _ = write!(
        s,
        "<text x=\"{:.1}\" y=\"{}\" text-anchor=\"middle\" fill=\"#555\">tilt toward azimuth 0°</text>",
        (L + R) / 2.0,
        H - 4.0
    );
    for (k, (c, p)) in cuts.iter().zip(&points).enumerate() {
        let col = TAB10[k % TAB10.len()];
        let col = format!("rgb({},{},{})", col.0, col.1, col.2);
        let path: Vec<String> = p
            .iter()
            .map(|&(t, v)| format!("{:.1},{:.1}", x(t), y(v)))
            .collect();
        let _ = write!(
            s,
            "<polyline fill=\"none\" stroke=\"{col}\" stroke-width=\"2\" points=\"{}\"/>",
            path.join(" ")
        );
        for &(t, v) in p {
            let _ = write!(
                s,
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"3\" fill=\"{col}\"><title>{}: {t}°, {v:.1} %</title></circle>",
                x(t),
                y(v),
                escape(&c.label)
            );
        }
        let ly = T + 8.0 + 18.0 * k as f64;
        let mut label = c.label.clone();
        if label.chars().count() > 24 {
            label = label.chars().take(23).collect::<String>() + "…";
        }
        let _ = write!(
            s,
            "<line x1=\"{}\" x2=\"{}\" y1=\"{ly}\" y2=\"{ly}\" stroke=\"{col}\" stroke-width=\"3\"/><text x=\"{}\" y=\"{}\" fill=\"#333\">{}</text>",
            R + 12.0,
            R + 30.0,
            R + 36.0,
            ly + 4.0,
            escape(&label)
        );
    }
    s.push_str("</svg>");
    s
}
