//! Pictures of runs and sweeps (plotters): the convergence plot and the score heatmap. Each is a
//! [`Figure`] drawn by one function generic over the backend, saved as PNG and SVG.
//!
//! Text uses a bundled DejaVu Sans (registered once as `sans-serif`), so no system fonts are
//! needed.

use super::contour::{nice_levels, segments};
use super::history::{History, Track};
use super::problem::FAILED_COST;
use crate::error::{Error, Result};
use crate::io::write_atomic;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use std::path::{Path, PathBuf};

/// Register the bundled font as `sans-serif` (once per process; shared with [`crate::plot`]).
pub fn ensure_font() {
    crate::plot::register_font();
}

/// The result of a drawing step on backend `DB`.
pub type DrawResult<DB> =
    std::result::Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// A picture that can be drawn on any plotters backend.
pub trait Figure {
    /// Pixel size (width, height).
    fn size(&self) -> (u32, u32);
    /// Draw on a white `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB>;
}

fn plot_err(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::io(path.display().to_string(), format!("could not draw: {e}"))
}

/// Save `fig` as a PNG (written beside the target and renamed, like every output).
pub fn save_png(fig: &impl Figure, path: &Path) -> Result<()> {
    ensure_font();
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_else(|| "plot.png".into());
    let tmp = dir.join(format!(".{name}.tmp-{}.png", std::process::id()));
    let drawn = (|| {
        let root = BitMapBackend::new(&tmp, fig.size()).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_err(path, e))?;
        fig.draw(&root).map_err(|e| plot_err(path, e))?;
        root.present().map_err(|e| plot_err(path, e))
    })();
    let done = drawn.and_then(|_| {
        std::fs::rename(&tmp, path).map_err(|e| Error::io(path.display().to_string(), e))
    });
    if done.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    done
}

/// The SVG text of `fig`.
pub fn svg_string(fig: &impl Figure) -> Result<String> {
    ensure_font();
    let mut s = String::new();
    {
        let root = SVGBackend::with_string(&mut s, fig.size()).into_drawing_area();
        let p = Path::new("figure.svg");
        root.fill(&WHITE).map_err(|e| plot_err(p, e))?;
        fig.draw(&root).map_err(|e| plot_err(p, e))?;
        root.present().map_err(|e| plot_err(p, e))?;
    }
    Ok(s)
}

/// Save `fig` as `<stem>.png` and `<stem>.svg`.
pub fn save_both(fig: &impl Figure, png: &Path, svg: &Path) -> Result<()> {
    save_png(fig, png)?;
    write_atomic(svg, svg_string(fig)?.as_bytes())
}

/// Tableau's ten colours, for one line per start.
pub const TAB10: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let pos = q * (sorted.len() - 1) as f64;
    let (i, f) = (pos.floor() as usize, pos.fract());
    if i + 1 < sorted.len() {
        sorted[i] * (1.0 - f) + sorted[i + 1] * f
    } else {
        sorted[i]
    }
}

/// One swarm iteration's spread of costs.
struct Band {
    x: f64,
    min: f64,
    q1: f64,
    median: f64,
    q3: f64,
    max: f64,
    best: f64,
}

/// Best and current cost against evaluations: one pair of lines per Nelder–Mead start, or the
/// swarm's best with its spread (min–max and quartile bands, median, every particle as a dot).
pub struct Convergence<'a> {
    /// The history.
    pub history: &'a History,
    /// Title.
    pub title: String,
}

impl Convergence<'_> {
    /// The y range: from the lowest cost to the 90th percentile of the costs of cuts that could
    /// be built (failed cuts and wild starts would flatten the picture), with a margin.
    fn y_range(&self) -> (f64, f64) {
        let mut c: Vec<f64> = self
            .history
            .rows
            .iter()
            .map(|r| r.cost)
            .filter(|c| c.is_finite() && *c < 0.5 * FAILED_COST)
            .collect();
        c.sort_by(f64::total_cmp);
        if c.is_empty() {
            return (-1.0, 1.0);
        }
        let lo = c[0];
        let mut hi = quantile(&c, 0.9);
        if let Some(first) = self
            .history
            .rows
            .iter()
            .find(|r| r.cost < 0.5 * FAILED_COST)
        {
            hi = hi.max(first.best_cost.min(c[c.len() - 1]));
        }
        let span = (hi - lo).max(1e-3 * lo.abs().max(1.0));
        (lo - 0.06 * span, lo + 1.06 * span)
    }
}

impl Figure for Convergence<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 620)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let h = self.history;
        let (ylo, yhi) = self.y_range();
        let clamp = |v: f64| v.clamp(ylo, yhi);
        let xmax = h.rows.last().map(|r| r.evaluations).unwrap_or(1).max(1) as f64;
        let root = root.titled(&self.title, ("sans-serif", 20))?;
        let mut chart = ChartBuilder::on(&root)
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(80)
            .build_cartesian_2d(0f64..xmax * 1.01, ylo..yhi)?;
        chart
            .configure_mesh()
            .x_desc("evaluations")
            .y_desc("cost = −(weighted score) + penalties")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| tidy(*v, yhi - ylo))
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()?;
        match h.track {
            Track::Start => {
                for k in 0..h.tracks() {
                    let col = TAB10[k % TAB10.len()];
                    let rows: Vec<_> = h.rows.iter().filter(|r| r.track == k).collect();
                    chart.draw_series(LineSeries::new(
                        rows.iter().map(|r| (r.evaluations as f64, clamp(r.cost))),
                        col.mix(0.35).stroke_width(1),
                    ))?;
                    let best = chart.draw_series(LineSeries::new(
                        rows.iter()
                            .map(|r| (r.evaluations as f64, clamp(r.best_cost))),
                        col.stroke_width(3),
                    ))?;
                    if k < 10 {
                        let last = rows.last().map(|r| r.best_cost).unwrap_or(f64::NAN);
                        best.label(format!("start {k}: best {last:.4}"))
                            .legend(move |(x, y)| {
                                PathElement::new(vec![(x, y), (x + 22, y)], col.stroke_width(3))
                            });
                    }
                }
                // Legend entry for the thin lines.
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        Vec::<(f64, f64)>::new(),
                        BLACK.mix(0.35),
                    )))?
                    .label("cost of each evaluation (thin)")
                    .legend(|(x, y)| {
                        PathElement::new(vec![(x, y), (x + 22, y)], BLACK.mix(0.35).stroke_width(1))
                    });
            }
            Track::Particle => {
                let iters = h.rows.iter().map(|r| r.iteration).max().unwrap_or(0);
                let mut band: Vec<Band> = Vec::new();
                for it in 0..=iters {
                    let rows: Vec<_> = h.rows.iter().filter(|r| r.iteration == it).collect();
                    if rows.is_empty() {
                        continue;
                    }
                    let mut c: Vec<f64> = rows.iter().map(|r| r.cost).collect();
                    c.sort_by(f64::total_cmp);
                    band.push(Band {
                        x: rows.iter().map(|r| r.evaluations).max().unwrap_or(0) as f64,
                        min: c[0],
                        q1: quantile(&c, 0.25),
                        median: quantile(&c, 0.5),
                        q3: quantile(&c, 0.75),
                        max: c[c.len() - 1],
                        best: rows.last().map(|r| r.best_cost).unwrap_or(f64::NAN),
                    });
                }
                let poly = |lo: fn(&Band) -> f64, hi: fn(&Band) -> f64| {
                    let mut pts: Vec<(f64, f64)> =
                        band.iter().map(|b| (b.x, clamp(hi(b)))).collect();
                    pts.extend(band.iter().rev().map(|b| (b.x, clamp(lo(b)))));
                    pts
                };
                let blue = TAB10[0];
                chart
                    .draw_series(std::iter::once(Polygon::new(
                        poly(|b| b.min, |b| b.max),
                        blue.mix(0.12).filled(),
                    )))?
                    .label("swarm: min–max of the iteration")
                    .legend(move |(x, y)| {
                        Rectangle::new([(x, y - 6), (x + 22, y + 6)], blue.mix(0.12).filled())
                    });
                chart
                    .draw_series(std::iter::once(Polygon::new(
                        poly(|b| b.q1, |b| b.q3),
                        blue.mix(0.3).filled(),
                    )))?
                    .label("swarm: quartiles")
                    .legend(move |(x, y)| {
                        Rectangle::new([(x, y - 6), (x + 22, y + 6)], blue.mix(0.3).filled())
                    });
                chart
                    .draw_series(LineSeries::new(
                        band.iter().map(|b| (b.x, clamp(b.median))),
                        blue.stroke_width(1),
                    ))?
                    .label("swarm: median")
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 22, y)], blue.stroke_width(1))
                    });
                chart
                    .draw_series(h.rows.iter().map(|r| {
                        Circle::new(
                            (r.evaluations as f64, clamp(r.cost)),
                            2,
                            BLACK.mix(0.25).filled(),
                        )
                    }))?
                    .label("each particle (dot)")
                    .legend(|(x, y)| Circle::new((x + 11, y), 2, BLACK.mix(0.4).filled()));
                let red = TAB10[3];
                let last = band.last().map(|b| b.best).unwrap_or(f64::NAN);
                chart
                    .draw_series(LineSeries::new(
                        band.iter().map(|b| (b.x, clamp(b.best))),
                        red.stroke_width(3),
                    ))?
                    .label(format!("swarm best: {last:.4}"))
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 22, y)], red.stroke_width(3))
                    });
            }
        }
        if let Some(b) = h.best_row() {
            chart
                .draw_series(std::iter::once(Cross::new(
                    (b.evaluations as f64, clamp(b.cost)),
                    7,
                    BLACK.stroke_width(2),
                )))?
                .label(format!("best of the run: {:.4}", b.cost))
                .legend(|(x, y)| Cross::new((x + 11, y), 5, BLACK.stroke_width(2)));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.5))
            .label_font(("sans-serif", 13))
            .draw()?;
        Ok(())
    }
}

/// A score over a grid of two parameters, with contour lines, a colour bar, and optionally the
/// optimizer's path.
pub struct Heatmap {
    /// Title.
    pub title: String,
    /// Grid x values (at least 2, increasing).
    pub xs: Vec<f64>,
    /// Grid y values (at least 2, increasing).
    pub ys: Vec<f64>,
    /// `z[j][i]` at `(xs[i], ys[j])`; NaN where the cut failed (drawn grey).
    pub z: Vec<Vec<f64>>,
    /// x axis label.
    pub x_label: String,
    /// y axis label.
    pub y_label: String,
    /// Colour bar label.
    pub z_label: String,
    /// The optimizer's path (best point so far), in (x, y).
    pub path: Option<Vec<(f64, f64)>>,
}

impl Heatmap {
    /// The finite range of `z`.
    pub fn z_range(&self) -> (f64, f64) {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in self.z.iter().flatten().filter(|v| v.is_finite()) {
            lo = lo.min(*v);
            hi = hi.max(*v);
        }
        if !lo.is_finite() {
            return (0.0, 1.0);
        }
        if hi <= lo {
            return (lo - 0.5, hi + 0.5);
        }
        (lo, hi)
    }

    /// The contour levels drawn.
    pub fn levels(&self) -> Vec<f64> {
        let (lo, hi) = self.z_range();
        nice_levels(lo, hi, 8)
    }
}

fn half_steps(v: &[f64]) -> Vec<(f64, f64)> {
    (0..v.len())
        .map(|i| {
            let l = if i > 0 {
                (v[i] - v[i - 1]) / 2.0
            } else {
                (v[1] - v[0]) / 2.0
            };
            let r = if i + 1 < v.len() {
                (v[i + 1] - v[i]) / 2.0
            } else {
                l
            };
            (v[i] - l, v[i] + r)
        })
        .collect()
}

/// A tick label with as many decimals as the axis span needs, and no `-0`.
fn tidy(v: f64, span: f64) -> String {
    let d = (1.0 - span.abs().max(1e-12).log10().floor()).clamp(0.0, 8.0) as usize;
    let s = format!("{v:.d$}");
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        s.trim_start_matches('-').to_string()
    } else {
        s
    }
}

fn level_label(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

impl Figure for Heatmap {
    fn size(&self) -> (u32, u32) {
        (1000, 760)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let (zlo, zhi) = self.z_range();
        let levels = self.levels();
        let root = root.titled(&self.title, ("sans-serif", 20))?;
        let (w, _) = root.dim_in_pixel();
        let (left, right) = root.split_horizontally(w.saturating_sub(150));
        let xc = half_steps(&self.xs);
        let yc = half_steps(&self.ys);
        let (x0, x1) = (xc[0].0, xc[xc.len() - 1].1);
        let (y0, y1) = (yc[0].0, yc[yc.len() - 1].1);
        let mut chart = ChartBuilder::on(&left)
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(72)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .draw()?;
        let grey = RGBColor(190, 190, 190);
        chart.draw_series(self.ys.iter().enumerate().flat_map(|(j, _)| {
            let (xc, yc) = (&xc, &yc);
            self.xs.iter().enumerate().map(move |(i, _)| {
                let v = self.z[j][i];
                let style = if v.is_finite() {
                    ViridisRGB::get_color_normalized(v, zlo, zhi).filled()
                } else {
                    grey.filled()
                };
                Rectangle::new([(xc[i].0, yc[j].0), (xc[i].1, yc[j].1)], style)
            })
        }))?;
        for (k, lv) in levels.iter().enumerate() {
            let segs = segments(&self.xs, &self.ys, &self.z, *lv);
            chart
                .draw_series(segs.iter().map(|(a, b)| {
                    PathElement::new(vec![*a, *b], WHITE.mix(0.75).stroke_width(1))
                }))?;
            // Spread the labels: level k sits at a different place along its line.
            let at = ((k as f64 + 0.5) / levels.len() as f64 * segs.len() as f64) as usize;
            if let Some((a, b)) = segs.get(at) {
                let mid = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
                chart.draw_series(std::iter::once(Text::new(
                    level_label(*lv),
                    mid,
                    ("sans-serif", 12).into_font().color(&WHITE),
                )))?;
            }
        }
        if let Some(path) = self.path.as_ref().filter(|p| !p.is_empty()) {
            let red = RGBColor(240, 40, 40);
            chart
                .draw_series(LineSeries::new(path.iter().copied(), red.stroke_width(2)))?
                .label("optimizer: best point so far")
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 22, y)], red.stroke_width(2))
                });
            chart.draw_series(path.iter().map(|p| Circle::new(*p, 2, red.filled())))?;
            chart
                .draw_series(std::iter::once(Circle::new(
                    path[0],
                    8,
                    WHITE.stroke_width(3),
                )))?
                .label("start")
                .legend(|(x, y)| Circle::new((x + 11, y), 6, BLACK.stroke_width(2)));
            let end = path[path.len() - 1];
            chart
                .draw_series(std::iter::once(TriangleMarker::new(end, 10, red.filled())))?
                .label("end (best)")
                .legend(move |(x, y)| TriangleMarker::new((x + 11, y), 7, red.filled()));
            chart.draw_series(std::iter::once(TriangleMarker::new(
                end,
                10,
                WHITE.stroke_width(1),
            )))?;
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.5))
                .label_font(("sans-serif", 13))
                .draw()?;
        }
        // Colour bar.
        let mut bar = ChartBuilder::on(&right)
            .margin_top(16)
            .margin_bottom(64)
            .margin_right(40)
            .y_label_area_size(70)
            .build_cartesian_2d(0f64..1f64, zlo..zhi)?;
        bar.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc(self.z_label.as_str())
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 15))
            .y_labels(8)
            .y_label_formatter(&|v| tidy(*v, zhi - zlo))
            .draw()?;
        let n = 200;
        bar.draw_series((0..n).map(|k| {
            let a = zlo + (zhi - zlo) * k as f64 / n as f64;
            let b = zlo + (zhi - zlo) * (k + 1) as f64 / n as f64;
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                ViridisRGB::get_color_normalized((a + b) / 2.0, zlo, zhi).filled(),
            )
        }))?;
        bar.draw_series(levels.iter().map(|lv| {
            PathElement::new(vec![(0.0, *lv), (1.0, *lv)], WHITE.mix(0.9).stroke_width(1))
        }))?;
        Ok(())
    }
}
