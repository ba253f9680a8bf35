//! The photon tracer's charts: where the light leaves (face categories), the cumulative exit
//! angle, and the rotation sweep.

use super::{
    box_key, every_30, font, legend, line_key, save, DrawResult, Figure, LegendStyle, SERIES,
};
use crate::error::Result;
use crate::photon::{Tally, CATEGORY_LABELS};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

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
