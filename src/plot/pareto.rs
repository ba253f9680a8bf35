//! `pareto.png`/`.svg`: the trade-off front of `[objective] pareto` in the plane of its first
//! two scores, the corners and the knee marked, the family's presets placed on the same axes.

use super::{font, save_to, DrawResult, Figure, SERIES};
use crate::error::Result;
use crate::metrics::ScoreName;
use crate::optimize::ParetoOutcome;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Draw the front (the [`crate::optimize::ParetoChart`] hook).
pub fn pareto(front: &ParetoOutcome, png: &Path, svg: &Path) -> Result<()> {
    save_to(&ParetoFigure(front), png, svg)
}

struct ParetoFigure<'a>(&'a ParetoOutcome);

impl Figure for ParetoFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (900, 700)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let o = self.0;
        let (xn, yn) = (o.scores.first().copied(), o.scores.get(1).copied());
        let (xs, ys) = (
            xn.map_or("", ScoreName::as_str),
            yn.map_or("", ScoreName::as_str),
        );
        let get = |m: &std::collections::BTreeMap<ScoreName, f64>, k: Option<ScoreName>| {
            m.get(&k?).copied()
        };
        let front: Vec<(f64, f64)> = o
            .front
            .iter()
            .filter_map(|p| Some((get(&p.scores, xn)?, get(&p.scores, yn)?)))
            .collect();
        let refs: Vec<(&str, f64, f64)> = o
            .references
            .iter()
            .filter_map(|(n, s)| Some((n.as_str(), get(s, xn)?, get(s, yn)?)))
            .collect();
        let all: Vec<(f64, f64)> = front
            .iter()
            .copied()
            .chain(refs.iter().map(|r| (r.1, r.2)))
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .collect();
        let range = |v: Vec<f64>| {
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            if !lo.is_finite() {
                return (0.0, 1.0);
            }
            let pad = 0.1 * (hi - lo).max(1e-3);
            (lo - pad, hi + pad)
        };
        let (x0, x1) = range(all.iter().map(|p| p.0).collect());
        let (y0, y1) = range(all.iter().map(|p| p.1).collect());
        let title = if o.scores.len() > 2 {
            format!(
                "Trade-off {} (front of three scores, drawn in the first two)",
                crate::metrics::score_name::joined(&o.scores, " – ")
            )
        } else {
            format!("Trade-off: {ys} against {xs}")
        };
        let root = root.titled(&title, font(20))?;
        let mut chart = ChartBuilder::on(&root)
            .margin(20)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .light_line_style(BLACK.mix(0.06))
            .bold_line_style(BLACK.mix(0.12))
            .x_desc(xs)
            .y_desc(ys)
            .label_style(font(14))
            .axis_desc_style(font(16))
            .draw()?;
        let col = SERIES[0];
        let mut line = front.clone();
        line.sort_by(|a, b| a.0.total_cmp(&b.0));
        chart
            .draw_series(LineSeries::new(line.iter().copied(), col.stroke_width(2)))?
            .label("non-dominated cuts found")
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], col.stroke_width(2)));
        chart.draw_series(front.iter().map(|p| Circle::new(*p, 4, col.filled())))?;
        // Corners and knee.
        for (p, pt) in o.front.iter().zip(&front) {
            if p.roles.is_empty() {
                continue;
            }
            let text = p.roles.join(", ");
            // Labels of points on the right half go to their left, inside the chart.
            let dx = if pt.0 > 0.5 * (x0 + x1) {
                -12 - 7 * text.chars().count() as i32
            } else {
                10
            };
            chart.draw_series(std::iter::once(
                EmptyElement::at(*pt)
                    + Circle::new((0, 0), 8, SERIES[1].stroke_width(2))
                    + Text::new(text, (dx, -18), font(13)),
            ))?;
        }
        let rc = SERIES[2];
        chart
            .draw_series(refs.iter().map(|&(n, x, y)| {
                EmptyElement::at((x, y))
                    + TriangleMarker::new((0, 0), 7, rc.filled())
                    + Text::new(n.to_string(), (8, 4), font(13))
            }))?
            .label("bundled presets")
            .legend(move |(x, y)| TriangleMarker::new((x + 9, y), 6, rc.filled()));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK.mix(0.3))
            .label_font(font(14))
            .position(SeriesLabelPosition::LowerLeft)
            .draw()?;
        Ok(())
    }
}
