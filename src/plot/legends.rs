//! Legends and axes: the two legend looks, legend keys and degree tick labels.

use super::{font, DrawResult};
use plotters::chart::{ChartContext, SeriesLabelPosition};
use plotters::prelude::*;
/// The two legend looks: the photon tracer's larger one, and the optimizer's compact one (its
/// charts carry more entries over busier backgrounds).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LegendStyle {
    /// 16 px labels in a black frame.
    Large,
    /// 13 px labels in a grey frame.
    Compact,
}

/// Draw the legend of every labelled series of `chart` at `at`.
pub fn legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    at: SeriesLabelPosition,
    style: LegendStyle,
) -> DrawResult<DB> {
    let (background, border, size) = match style {
        LegendStyle::Large => (WHITE.mix(0.9), BLACK.mix(1.0), 16),
        LegendStyle::Compact => (WHITE.mix(0.85), BLACK.mix(0.5), 13),
    };
    chart
        .configure_series_labels()
        .position(at)
        .background_style(background)
        .border_style(border)
        .label_font(font(size))
        .draw()
}

/// A legend key: a horizontal line `len` pixels long.
pub fn line_key(style: ShapeStyle, len: i32) -> impl Fn((i32, i32)) -> PathElement<(i32, i32)> {
    move |(x, y)| PathElement::new(vec![(x, y), (x + len, y)], style)
}

/// A legend key: a box `width` pixels wide, 12 high.
pub fn box_key(style: ShapeStyle, width: i32) -> impl Fn((i32, i32)) -> Rectangle<(i32, i32)> {
    move |(x, y)| Rectangle::new([(x, y - 6), (x + width, y + 6)], style)
}

/// Tick label of degrees: only multiples of 30°.
pub fn every_30(x: &f64) -> String {
    let r = x.round();
    if (x - r).abs() < 1e-6 && (r as i64) % 30 == 0 {
        format!("{r}°")
    } else {
        String::new()
    }
}
