//! The photon tracer's charts: where the light leaves (face categories), the cumulative exit
//! angle, and the rotation sweep; and every chart and picture of a trace ([`trace_plots`]).
//! `facetlab trace` is one call here, [`trace`] (its notes, progress and files through
//! [`TraceSink`]).

mod run;

pub use run::{trace, TraceJob, TraceSink};

use super::{
    box_key, every_30, font, legend, line_key, save, DrawResult, Figure, LegendStyle, SERIES,
};
use super::{Camera, PathColor, PathStyle};
use crate::cut::Cut;
use crate::error::Result;
use crate::photon::{LightChoice, Tally, CATEGORY_LABELS};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------------------------------------
// Face categories

struct FaceBars<'a> {
    tallies: &'a [&'a Tally],
    light: &'a str,
}

impl Figure for FaceBars<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 640)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let n = self.tallies.len().max(1);
        let ymax = self
            .tallies
            .iter()
            .flat_map(|t| (0..4).map(|k| 100.0 * (t.category(k).0 + t.category(k).1)))
            .fold(10.0f64, f64::max);
        let ymax = ((ymax * 1.15) / 10.0).ceil() * 10.0;
        let mut chart = ChartBuilder::on(root)
            .caption(format!("Where the light leaves — {}", self.light), font(24))
            .margin(16)
            .x_label_area_size(56)
            .y_label_area_size(70)
            .build_cartesian_2d(0f64..4f64, 0f64..ymax.min(100.0))?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_desc("angle between exit facet's normal and up")
            .y_desc("share of photons that hit the stone (%)")
            .y_label_formatter(&|v| format!("{v:.0}"))
            .x_labels(9)
            .x_label_formatter(&|x| {
                if (x.fract() - 0.5).abs() < 1e-6 {
                    CATEGORY_LABELS[(x.floor() as usize).min(3)].to_string()
                } else {
                    String::new()
                }
            })
            .label_style(font(16))
            .axis_desc_style(font(17))
            .draw()?;
        let w = 0.8 / n as f64;
        for (i, t) in self.tallies.iter().enumerate() {
            let c = SERIES[i % SERIES.len()];
            let bars = (0..4).map(|k| {
                let x0 = k as f64 + 0.1 + i as f64 * w;
                Rectangle::new(
                    [(x0, 0.0), (x0 + w * 0.92, 100.0 * t.category(k).0)],
                    c.filled(),
                )
            });
            chart
                .draw_series(bars)?
                .label(format!("{} ({} photons hit)", t.cut, t.counts.hit))
                .legend(box_key(c.filled(), 14));
            chart.draw_series((0..4).map(|k| {
                let x = k as f64 + 0.1 + (i as f64 + 0.46) * w;
                let (p, se) = t.category(k);
                let (lo, hi) = (100.0 * (p - se).max(0.0), 100.0 * (p + se));
                let dx = 0.12 * w;
                PathElement::new(
                    vec![
                        (x - dx, lo),
                        (x + dx, lo),
                        (x, lo),
                        (x, hi),
                        (x - dx, hi),
                        (x + dx, hi),
                    ],
                    BLACK.stroke_width(1),
                )
            }))?;
            chart.draw_series((0..4).map(|k| {
                let x = k as f64 + 0.1 + (i as f64 + 0.46) * w;
                let p = 100.0 * t.category(k).0;
                Text::new(
                    format!("{p:.1}"),
                    (x, p + ymax * 0.015),
                    font(13).pos(plotters::style::text_anchor::Pos::new(
                        plotters::style::text_anchor::HPos::Center,
                        plotters::style::text_anchor::VPos::Bottom,
                    )),
                )
            }))?;
        }
        legend(
            &mut chart,
            SeriesLabelPosition::UpperRight,
            LegendStyle::Large,
        )
    }
}

/// The thesis's bar chart: share of hit photons leaving through facets < 45°, 45–90°,
/// 90–135°, > 135° from up, one bar per cut, with standard-error bars. Writes STEM.png/.svg.
pub fn face_categories(tallies: &[&Tally], light: &str, stem: &Path) -> Result<()> {
    save(&FaceBars { tallies, light }, stem)
}

// ---------------------------------------------------------------------------------------------
// Exit-angle CDF

struct Cdf<'a> {
    tallies: &'a [&'a Tally],
    light: &'a str,
}

impl Figure for Cdf<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 640)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let mut chart = ChartBuilder::on(root)
            .caption(format!("Cumulative exit angle — {}", self.light), font(24))
            .margin(16)
            .x_label_area_size(56)
            .y_label_area_size(70)
            .build_cartesian_2d(0f64..180f64, 0f64..100f64)?;
        chart
            .configure_mesh()
            .x_desc("angle between exit direction and up (°)")
            .x_labels(19)
            .x_label_formatter(&every_30)
            .y_desc("exited photons within that angle (%)")
            .y_label_formatter(&|v| format!("{v:.0}"))
            .label_style(font(16))
            .axis_desc_style(font(17))
            .draw()?;
        for (i, t) in self.tallies.iter().enumerate() {
            let c = SERIES[i % SERIES.len()];
            let (cdf, _) = t.exit_angle_cdf();
            chart
                .draw_series(LineSeries::new(
                    cdf.iter().enumerate().map(|(k, v)| (k as f64, 100.0 * v)),
                    c.stroke_width(3),
                ))?
                .label(format!("{} ({} exited)", t.cut, t.counts.exited()))
                .legend(line_key(c.stroke_width(3), 20));
        }
        legend(
            &mut chart,
            SeriesLabelPosition::LowerRight,
            LegendStyle::Large,
        )
    }
}

/// Cumulative distribution of the angle between exit direction and up, one curve per cut.
pub fn exit_angle_cdf(tallies: &[&Tally], light: &str, stem: &Path) -> Result<()> {
    save(&Cdf { tallies, light }, stem)
}

// ---------------------------------------------------------------------------------------------
// Rotation sweep

struct Rotation<'a> {
    sweeps: &'a [(&'a str, &'a [Tally])],
    kind: &'a str,
}

impl Figure for Rotation<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 640)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!("Light turned around the stone — {} light", self.kind),
                font(24),
            )
            .margin(16)
            .x_label_area_size(56)
            .y_label_area_size(70)
            .build_cartesian_2d(-5f64..185f64, 0f64..100f64)?;
        chart
            .configure_mesh()
            .x_desc("light angle from straight above (°)")
            .x_labels(19)
            .x_label_formatter(&every_30)
            .y_desc("share of photons that hit the stone (%)")
            .y_label_formatter(&|v| format!("{v:.0}"))
            .label_style(font(16))
            .axis_desc_style(font(17))
            .draw()?;
        for (i, (name, ts)) in self.sweeps.iter().enumerate() {
            let c = SERIES[i % SERIES.len()];
            let pts = |f: &dyn Fn(&Tally) -> f64| -> Vec<(f64, f64)> {
                ts.iter()
                    .map(|t| (t.light_angle.unwrap_or(0.0), 100.0 * f(t)))
                    .collect()
            };
            let top = pts(&|t| t.category(0).0);
            let ret = pts(&|t| t.light_return().0);
            chart
                .draw_series(LineSeries::new(top.clone(), c.stroke_width(3)))?
                .label(format!("{name}: exit faces < 45°"))
                .legend(line_key(c.stroke_width(3), 20));
            chart.draw_series(top.iter().map(|p| Circle::new(*p, 5, c.filled())))?;
            chart
                .draw_series(DashedLineSeries::new(ret.clone(), 10, 6, c.stroke_width(2)))?
                .label(format!("{name}: thesis light return (up)"))
                .legend(line_key(c.stroke_width(2), 8));
            chart.draw_series(ret.iter().map(|p| TriangleMarker::new(*p, 6, c.filled())))?;
        }
        legend(
            &mut chart,
            SeriesLabelPosition::UpperRight,
            LegendStyle::Large,
        )
    }
}

/// The rotation sweep: share through faces < 45° (solid, circles) and light return (dashed,
/// triangles) against the light's angle, per cut.
pub fn rotation(sweeps: &[(&str, &[Tally])], kind: &str, stem: &Path) -> Result<()> {
    save(&Rotation { sweeps, kind }, stem)
}

/// A file-name-safe form of a cut name.
fn slug(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() {
        "cut".into()
    } else {
        s
    }
}

/// Every chart and picture of `facetlab trace --plots DIR` into `dir` (made if missing) for
/// `cuts` traced under `light` (`results[cut]`: one tally, or one per angle of the sweep), the
/// pictures seen through `camera`: `face_categories`, `exit_angle_cdf`, `rotation` (the sweep),
/// and per cut `facets_<cut>` and, with recorded paths, `paths_<cut>_one`, `_bounces`,
/// `_wavelength` and `_no_first_segment`. Returns their stems (each written as STEM.png and
/// STEM.svg).
pub fn trace_plots(
    dir: &Path,
    light: &LightChoice,
    camera: Camera,
    cuts: &[Cut],
    results: &[Vec<Tally>],
) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)
        .map_err(|e| crate::error::Error::io(dir.display().to_string(), e))?;
    let firsts: Vec<&Tally> = results.iter().map(|r| &r[0]).collect();
    let label = match light {
        LightChoice::Single(l) => l.label.clone(),
        LightChoice::Rotate(k) => format!("{} light from above (0°)", k.name()),
    };
    let mut stems = Vec::new();
    let stem = dir.join("face_categories");
    face_categories(&firsts, &label, &stem)?;
    stems.push(stem);
    let stem = dir.join("exit_angle_cdf");
    exit_angle_cdf(&firsts, &label, &stem)?;
    stems.push(stem);
    if let LightChoice::Rotate(k) = *light {
        let sweeps: Vec<(&str, &[Tally])> = results
            .iter()
            .map(|r| (r[0].cut.as_str(), r.as_slice()))
            .collect();
        let stem = dir.join("rotation");
        rotation(&sweeps, k.name(), &stem)?;
        stems.push(stem);
    }
    for (cut, r) in cuts.iter().zip(results) {
        let s = slug(&cut.name);
        let t = &r[0];
        let stem = dir.join(format!("facets_{s}"));
        super::facet_categories(
            &cut.solid,
            camera,
            &format!("{}: facets by normal category", cut.name),
            &stem,
        )?;
        stems.push(stem);
        if t.paths.is_empty() {
            continue;
        }
        let style = |color, first_segment, alpha, n: usize, what: &str| PathStyle {
            camera,
            color,
            first_segment,
            alpha,
            max_paths: n,
            title: format!("{}: {what} ({})", cut.name, t.light),
        };
        let variants = [
            (
                "one",
                style(PathColor::Bounces, true, 1.0, 1, "one photon path"),
            ),
            (
                "bounces",
                style(
                    PathColor::Bounces,
                    true,
                    0.25,
                    usize::MAX,
                    "photon paths by bounce count",
                ),
            ),
            (
                "wavelength",
                style(
                    PathColor::Wavelength,
                    true,
                    0.25,
                    usize::MAX,
                    "photon paths by wavelength",
                ),
            ),
            (
                "no_first_segment",
                style(
                    PathColor::Bounces,
                    false,
                    0.25,
                    usize::MAX,
                    "paths inside and out, light segment hidden",
                ),
            ),
        ];
        for (name, st) in variants {
            let stem = dir.join(format!("paths_{s}_{name}"));
            super::photon_paths(&cut.solid, &t.paths, &st, &stem)?;
            stems.push(stem);
        }
    }
    Ok(stems)
}
