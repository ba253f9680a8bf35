//! The report's HTML page: a header naming the material and the tracer's settings, then per cut
//! its three pictures (PNG, base64-embedded), the facet diagram inline, the proportions with
//! the grade estimate, every score with one line on what it means, and the photon tracer's
//! checks; one style sheet, no script, nothing fetched.

use super::tilt;
use super::{CutReport, ReportOptions};
use crate::cut::grade::{self, Grade};
use crate::error::Result;
use crate::metrics::ScoreName;
use crate::plot::diagram::diagram;
use crate::plot::palette::PICTURE_GROUND;
use crate::render::Light;
use std::fmt::Write;

/// Exposure of each picture in the report (fire's flashes are small: brighter).
fn exposure(light: Light) -> f64 {
    if light == Light::Fire {
        3.0
    } else {
        1.0
    }
}

/// Standard base64 (RFC 4648, with padding).
pub fn base64(bytes: &[u8]) -> String {
    use base64::Engine;
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

/// `text` with HTML's special characters escaped.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The scores a cut's table shows, in this order, each with its meaning from
/// [`crate::metrics::SCORES`].
pub const SCORE_LINES: [ScoreName; 6] = [
    ScoreName::Brilliance,
    ScoreName::BrillianceIso,
    ScoreName::BrillianceCos,
    ScoreName::Fire,
    ScoreName::Scintillation,
    ScoreName::OverheadLightReturn,
];

/// The page for `cuts` (side by side when several).
pub fn html(cuts: &[CutReport], o: &ReportOptions) -> Result<String> {
    let mut h = String::new();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
         <title>{}</title><style>{STYLE}</style></head><body>\n<h1>{}</h1>\n",
        escape(&o.title),
        escape(&o.title)
    );
    let m = &o.score.material;
    let _ = writeln!(
        h,
        "<p class=\"sub\">{} cut{} in {} (n<sub>D</sub> = {:.4}); scores by facetlab's beam tracer at {} nm, polarization {}.</p>",
        cuts.len(),
        if cuts.len() == 1 { "" } else { "s" },
        escape(&m.name),
        m.ri_d(),
        o.score.wavelength_nm,
        if o.score.trace.polarization { "on" } else { "off" }
    );
    for (heading, body) in &o.sections {
        let _ = writeln!(
            h,
            "<section class=\"note\"><h2>{}</h2>\n{body}</section>",
            escape(heading)
        );
    }
    if cuts.iter().any(|c| !c.tilted.is_empty()) {
        let _ = writeln!(
            h,
            "<section class=\"note\"><h2>Tilt performance</h2><p class=\"sub\">Light returned under {} (% of a white diffuser) as the stone tips toward azimuth 0°; each cut's pictures are below its face-up ones.</p>{}</section>",
            super::brightness_caption(),
            tilt::chart(cuts)
        );
    }
    h.push_str("<div class=\"cuts\">\n");
    for c in cuts {
        h.push_str("<section class=\"cut\">\n");
        // A cut without a family: a GemCad design (it has a record), else a mesh.
        let fam = c
            .cut
            .family
            .as_deref()
            .unwrap_or(if c.cut.record.is_some() {
                "design"
            } else {
                "mesh"
            });
        let _ = writeln!(
            h,
            "<h2>{}</h2><p class=\"sub\">{} · {} facets</p>",
            escape(&c.label),
            escape(fam),
            c.cut.solid.facets().len()
        );
        h.push_str("<div class=\"pics\">");
        for (light, img) in &c.pictures {
            let n = img.size() as u32;
            let mut rgb = img.to_srgb8(exposure(*light), PICTURE_GROUND);
            crate::plot::render::outline(
                &mut rgb,
                n as usize,
                crate::plot::render::picture_ground(),
            );
            let png = crate::io::png::encode_rgb8(n, n, &[&rgb], 0)?;
            let caption = match light {
                Light::Iso | Light::Cos => format!(
                    "{}: {:.1} % of a white diffuser",
                    if *light == super::BRIGHTNESS_LIGHT.0 {
                        super::brightness_caption()
                    } else {
                        format!("{} light", light.name().to_uppercase())
                    },
                    100.0 * img.stats.mean
                ),
                Light::Aset => {
                    let a = img.stats.aset.unwrap_or_default();
                    format!(
                        "ASET: blue {:.1} %, red {:.1} %, green {:.1} %, leak {:.1} %, port {:.1} %",
                        100.0 * a.blue,
                        100.0 * a.red,
                        100.0 * a.green,
                        100.0 * a.leak,
                        100.0 * a.port
                    )
                }
                _ => format!(
                    "One placement of the spot lights (exposure ×{}): placement fire {:.2} (fire, over {} placements: {:.2})",
                    exposure(*light),
                    img.stats.fire.unwrap_or(0.0),
                    o.score.fire_placements,
                    c.scores.fire
                ),
            };
            let _ = write!(
                h,
                "<figure><img alt=\"{} picture\" width=\"{n}\" height=\"{n}\" src=\"data:image/png;base64,{}\"><figcaption>{}</figcaption></figure>",
                light.name(),
                base64(&png),
                escape(&caption)
            );
        }
        h.push_str("</div>\n<p class=\"legend\"><span style=\"background:#1a4dff\"></span>75–80° <span style=\"background:#e61414\"></span>45–75° <span style=\"background:#1ab829\"></span>0–45° <span style=\"background:#000\"></span>leak (below the horizon) or port (80–90°), both black as in the viewer (ASET)</p>\n");
        if !c.tilted.is_empty() {
            let _ = write!(h, "<h3>Tilted ({})</h3>", super::brightness_caption());
            h.push_str(&tilt::row(c)?);
        }
        // The diagram, inline.
        let svg = diagram(&c.cut);
        let svg = svg
            .find("<svg")
            .map(|i| svg[i..].to_string())
            .unwrap_or(svg);
        let _ = writeln!(h, "<div class=\"diagram\">{svg}</div>");
        // Proportions.
        let p = c.cut.proportions();
        h.push_str("<h3>Proportions</h3><table>");
        for (k, v) in [
            ("table", format!("{:.1} %", 100.0 * p.table)),
            ("crown angle", format!("{:.2}°", p.crown_angle)),
            ("pavilion angle", format!("{:.2}°", p.pavilion_angle)),
            ("crown height", format!("{:.1} %", 100.0 * p.crown_height)),
            (
                "pavilion depth",
                format!("{:.1} %", 100.0 * p.pavilion_depth),
            ),
            ("total depth", format!("{:.1} %", 100.0 * p.total_depth)),
            ("girdle", format!("{:.1} %", 100.0 * p.girdle)),
        ] {
            let _ = write!(h, "<tr><th>{k}</th><td>{v}</td></tr>");
        }
        h.push_str("</table>\n");
        if let Some(g) = grade::estimate(&c.cut) {
            let cls = if g.estimate <= Grade::VeryGood {
                "ok"
            } else {
                "warn"
            };
            let limit = if g.limiting.is_empty() {
                String::new()
            } else {
                format!(", limited by {}", g.limiting.join(", "))
            };
            let _ = writeln!(
                h,
                "<p class=\"{cls}\">Grade estimate: <b>{}</b>{} — {}.</p>",
                g.estimate.name(),
                escape(&limit),
                g.note
            );
        }
        // Scores.
        h.push_str("<h3>Scores</h3><table>");
        for name in SCORE_LINES {
            let _ = write!(
                h,
                "<tr><th>{name}</th><td class=\"num\">{:.4}</td><td class=\"what\">{}</td></tr>",
                name.of(&c.scores).unwrap_or(f64::NAN),
                escape(name.info().meaning)
            );
        }
        h.push_str("</table>\n");
        if !c.checks.is_empty() {
            let _ = write!(
                h,
                "<h3>Verification</h3><p class=\"sub\">The photon tracer ({} photons) re-measures the beam tracer's numbers; z is (beam − photon) / standard error, and a difference beyond {} standard errors is flagged.</p><table><tr><th></th><th>beam</th><th>photon</th><th>z</th></tr>",
                o.verify_photons, o.sigma
            );
            for k in &c.checks {
                let cls = if k.beyond(o.sigma) { "warn" } else { "ok" };
                let _ = write!(
                    h,
                    "<tr class=\"{cls}\"><th>{}</th><td class=\"num\">{:.4}</td><td class=\"num\">{:.4} ± {:.4}</td><td class=\"num\">{:+.1}</td></tr>",
                    escape(&k.name),
                    k.beam,
                    k.photon,
                    k.stderr,
                    k.z
                );
            }
            h.push_str("</table>\n");
        }
        h.push_str("</section>\n");
    }
    h.push_str("</div>\n<p class=\"foot\">Made by facetlab. Pictures: orthographic face-up views, each pixel the exact mean of the light over its square. The grade estimate comes from published proportion ranges and is not a laboratory grade.</p>\n</body></html>\n");
    Ok(h)
}

const STYLE: &str = "body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:24px;color:#222;background:#fafafa}\
h1{font-size:22px;margin:0 0 4px}h2{font-size:18px;margin:0}h3{font-size:14px;margin:14px 0 4px;color:#555}\
.sub{color:#666;font-size:13px;margin:2px 0 8px}.cuts{display:flex;flex-wrap:wrap;gap:24px}\
.cut{background:#fff;border:1px solid #ddd;border-radius:6px;padding:16px;flex:1 1 560px;max-width:1040px}\
.pics{display:grid;grid-template-columns:repeat(3,minmax(0,1fr));gap:8px}figure{margin:0}figure img{display:block;width:100%;height:auto;border-radius:3px}\
figcaption{font-size:12px;color:#555}.legend{font-size:12px;color:#555}\
.legend span{display:inline-block;width:10px;height:10px;margin:0 3px 0 8px;vertical-align:middle}\
.diagram svg{width:100%;height:auto}table{border-collapse:collapse;font-size:13px}\
th{text-align:left;font-weight:600;padding:2px 10px 2px 0}td{padding:2px 10px 2px 0}.num{text-align:right;font-variant-numeric:tabular-nums}\
.note{background:#fff;border:1px solid #ddd;border-radius:6px;padding:12px 16px;margin:0 0 16px;max-width:1040px}\
.note svg{max-width:100%;height:auto}.tilts{margin-top:4px}\
.what{color:#666}.ok{color:#1b6e20}.warn{color:#a33}.foot{color:#888;font-size:12px;margin-top:20px}";

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::ScoreConfig;
    use crate::report::measure;

    #[test]
    fn base64_matches_the_rfc_examples() {
        for (plain, enc) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), enc);
        }
    }

    /// A report is one self-contained page: three pictures per cut, embedded; the diagram;
    /// the grade estimate of a round brilliant; every score; no external address.
    #[test]
    fn page_is_self_contained_and_complete() {
        let o = ReportOptions {
            score: ScoreConfig::fast(),
            size: 48,
            ..Default::default()
        };
        let cuts: Vec<CutReport> = ["tolkowsky", "princess"]
            .iter()
            .map(|n| measure(n, &crate::io::load_cut(n).unwrap(), &o).unwrap())
            .collect();
        let page = html(&cuts, &o).unwrap();
        assert_eq!(page.matches("data:image/png;base64,").count(), 6);
        assert_eq!(page.matches("<svg").count(), 2);
        assert!(page.contains("Grade estimate: <b>excellent</b>"));
        for name in SCORE_LINES {
            assert_eq!(
                page.matches(&format!("<th>{name}</th>")).count(),
                2,
                "{name}"
            );
        }
        // Nothing fetched from elsewhere (the SVG's xmlns is a name, not a download).
        for external in ["src=\"http", "href=\"http", "url(http", "<link", "<script"] {
            assert!(!page.contains(external), "{external}");
        }
        assert!(page.ends_with("</html>\n"));
    }
}
