//! The optimizer's charts: a run's convergence (best and current cost against evaluations), a
//! sweep's heatmap (a score over two parameters, with contour lines, a colour bar and optionally
//! the optimizer's path) and a one-parameter sweep's profile (every score against x). They
//! reach the optimizer and the sweeps as their hooks ([`crate::optimize::ConvergenceChart`],
//! [`crate::sweep::HeatmapChart`], [`crate::sweep::ProfileChart`]): the binary hands
//! [`convergence`], [`heatmap`] and [`profile`] to a run and a sweep.

use super::contour::{nice_levels, segments};
use super::{box_key, font, legend, line_key, save_to, DrawResult, Figure, LegendStyle, TAB10};
use crate::error::Result;
use crate::optimize::{CutWriter, FnWriter, GemWriter, History, Track, FAILED_COST};
use crate::sweep::{Heatmap, ProfileLines};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use std::path::Path;

/// The files of a run's best cut besides `best.toml` (written by [`crate::optimize::run`]):
/// GemCad's `.asc`, an OBJ mesh and the SVG facet diagram; and GemCad's binary `.gem` when
/// the config's design came as one. The command line and the Python package write these.
pub fn run_writers(config: &crate::optimize::Config) -> Vec<&'static dyn CutWriter> {
    static ASC: FnWriter = FnWriter::new("asc", |c| Ok(crate::io::asc::write(c, 0)));
    static OBJ: FnWriter = FnWriter::new("obj", |c| Ok(crate::io::mesh::write_obj(c)));
    static SVG: FnWriter = FnWriter::new("svg", |c| Ok(super::diagram::diagram(c)));
    static GEM: GemWriter = GemWriter;
    let mut all: Vec<&'static dyn CutWriter> = vec![&ASC, &OBJ, &SVG];
    let gem = config.cut_file.as_ref().is_some_and(|(file, _)| {
        Path::new(file)
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("gem"))
    });
    if gem {
        all.push(&GEM);
    }
    all
}

/// Draw a run's convergence chart under `title` as the PNG `png` and the SVG `svg`: one pair of
/// lines (best so far, thick; each evaluation, thin) per Nelder–Mead start, or the swarm's best
/// with its spread (min–max and quartile bands, median, every particle as a dot).
pub fn convergence(history: &History, title: &str, png: &Path, svg: &Path) -> Result<()> {
    save_to(
        &Convergence {
            history,
            title: title.to_string(),
        },
        png,
        svg,
    )
}

/// Draw a sweep's heatmap as the PNG `png` and the SVG `svg`: Viridis cells (grey where the cut
/// failed), labelled contour lines, a colour bar, and the optimizer's path if the map has one.
pub fn heatmap(map: &Heatmap, png: &Path, svg: &Path) -> Result<()> {
    save_to(&Map(map), png, svg)
}

/// Draw a one-parameter sweep as the PNG `png` and the SVG `svg`: one panel per score, stacked
/// over a shared x axis, each with its own y range, its points, and its highest point marked.
pub fn profile(lines: &ProfileLines, png: &Path, svg: &Path) -> Result<()> {
    save_to(&ProfileFigure(lines), png, svg)
}

/// A profile as a figure.
struct ProfileFigure<'a>(&'a ProfileLines);

/// The finite range of `v` with a margin (a flat line gets a band around it).
fn padded_range(v: &[f64]) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in v.iter().filter(|x| x.is_finite()) {
        lo = lo.min(*x);
        hi = hi.max(*x);
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = if hi > lo {
        0.08 * (hi - lo)
    } else {
        0.05 * lo.abs().max(1e-3)
    };
    (lo - pad, hi + pad)
}

impl Figure for ProfileFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 220 * self.0.series.len().max(1) as u32 + 90)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let p = self.0;
        let root = root.titled(&p.title, font(20))?;
        let n = p.series.len().max(1);
        // A margin of half a step each side, so the end points' markers are whole.
        let half = (p.xs[p.xs.len() - 1] - p.xs[0]) / (2.0 * (p.xs.len() - 1).max(1) as f64);
        let (x0, x1) = (p.xs[0] - half, p.xs[p.xs.len() - 1] + half);
        let panels = root.split_evenly((n, 1));
        for (k, ((name, values), area)) in p.series.iter().zip(panels.iter()).enumerate() {
            let last = k + 1 == n;
            // Room above the line for the legend.
            let (lo, top) = padded_range(values);
            let hi = top + 0.3 * (top - lo);
            let mut chart = ChartBuilder::on(area)
                .margin_left(16)
                .margin_right(24)
                .margin_top(8)
                .x_label_area_size(if last { 48 } else { 22 })
                .y_label_area_size(80)
                .build_cartesian_2d(x0..x1, lo..hi)?;
            let ticks = |v: &f64| tidy(*v, hi - lo);
            let mut mesh = chart.configure_mesh();
            mesh.light_line_style(BLACK.mix(0.06))
                .bold_line_style(BLACK.mix(0.12))
                .y_desc(name.as_str())
                .y_labels(5)
                .y_label_formatter(&ticks)
                .label_style(font(13))
                .axis_desc_style(font(15));
            if last {
                mesh.x_desc(p.x_label.as_str());
            }
            mesh.draw()?;
            let col = TAB10[k % TAB10.len()];
            // A failed cut breaks the line.
            let pts: Vec<(f64, f64)> = p.xs.iter().copied().zip(values.iter().copied()).collect();
            for run in pts.split(|(_, v)| !v.is_finite()) {
                chart.draw_series(LineSeries::new(run.iter().copied(), col.stroke_width(2)))?;
            }
            chart.draw_series(
                pts.iter()
                    .filter(|(_, v)| v.is_finite())
                    .map(|p| Circle::new(*p, 3, col.filled())),
            )?;
            let best = pts
                .iter()
                .filter(|(_, v)| v.is_finite())
                .max_by(|a, b| a.1.total_cmp(&b.1));
            if let Some(&(bx, by)) = best {
                // The legend sits in the room above the line, away from the highest point.
                let at = if bx > (x0 + x1) / 2.0 {
                    SeriesLabelPosition::UpperLeft
                } else {
                    SeriesLabelPosition::UpperRight
                };
                chart
                    .draw_series(std::iter::once(TriangleMarker::new(
                        (bx, by),
                        9,
                        BLACK.filled(),
                    )))?
                    .label(format!(
                        "highest {}: {} at {}",
                        name.split(' ').next().unwrap_or(name),
                        level_label(by),
                        level_label(bx)
                    ))
                    .legend(|(x, y)| TriangleMarker::new((x + 11, y), 6, BLACK.filled()));
                legend(&mut chart, at, LegendStyle::Compact)?;
            }
        }
        Ok(())
    }
}

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

/// Best and current cost against evaluations.
struct Convergence<'a> {
    history: &'a History,
    title: String,
}

impl Convergence<'_> {
    /// The y range `(bottom, cut, top)`: the data from the lowest cost to the highest best cost
    /// each start (or the swarm) has half way through its evaluations, or the start cut's cost
    /// if higher, with a margin — where the searches spend their time; costs above `cut` are
    /// drawn at it with a mark (failed cuts and wild first steps would squeeze the progress
    /// into a few pixels), and the room from `cut` to `top` holds the legend, clear of the lines.
    fn y_range(&self) -> (f64, f64, f64) {
        let ok = |c: f64| c.is_finite() && c < 0.5 * FAILED_COST;
        let rows = &self.history.rows;
        let lo = rows
            .iter()
            .map(|r| r.cost)
            .filter(|c| ok(*c))
            .fold(f64::INFINITY, f64::min);
        if !lo.is_finite() {
            return (-1.0, 0.9, 1.0);
        }
        let mut hi = rows
            .iter()
            .find(|r| ok(r.cost))
            .map_or(lo, |r| r.best_cost.min(r.cost));
        for k in 0..self.history.tracks() {
            let track: Vec<f64> = rows
                .iter()
                .filter(|r| r.track == k && ok(r.best_cost))
                .map(|r| r.best_cost)
                .collect();
            if let Some(&half) = track.get(track.len() / 2) {
                hi = hi.max(half);
            }
        }
        let span = (hi - lo).max(1e-3 * lo.abs().max(1.0));
        (lo - 0.06 * span, hi + 0.06 * span, hi + 0.6 * span)
    }
}

impl Figure for Convergence<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 620)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let h = self.history;
        let (ylo, cut, yhi) = self.y_range();
        let clamp = |v: f64| v.clamp(ylo, cut);
        let xmax = h.rows.last().map(|r| r.evaluations).unwrap_or(1).max(1) as f64;
        let root = root.titled(&self.title, font(20))?;
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
            .label_style(font(14))
            .axis_desc_style(font(16))
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
                            .legend(line_key(col.stroke_width(3), 22));
                    }
                    // Costs above the chart's range: a mark at its top edge.
                    chart.draw_series(rows.iter().filter(|r| r.cost > cut).map(|r| {
                        TriangleMarker::new((r.evaluations as f64, cut), 4, col.mix(0.6).filled())
                    }))?;
                }
                // Legend entry for the thin lines.
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        Vec::<(f64, f64)>::new(),
                        BLACK.mix(0.35),
                    )))?
                    .label("cost of each evaluation (thin)")
                    .legend(line_key(BLACK.mix(0.35).stroke_width(1), 22));
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
                    .legend(box_key(blue.mix(0.12).filled(), 22));
                chart
                    .draw_series(std::iter::once(Polygon::new(
                        poly(|b| b.q1, |b| b.q3),
                        blue.mix(0.3).filled(),
                    )))?
                    .label("swarm: quartiles")
                    .legend(box_key(blue.mix(0.3).filled(), 22));
                chart
                    .draw_series(LineSeries::new(
                        band.iter().map(|b| (b.x, clamp(b.median))),
                        blue.stroke_width(1),
                    ))?
                    .label("swarm: median")
                    .legend(line_key(blue.stroke_width(1), 22));
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
                    .legend(line_key(red.stroke_width(3), 22));
            }
        }
        if h.rows.iter().any(|r| r.cost > cut) {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(0.0, cut), (xmax * 1.01, cut)],
                    BLACK.mix(0.3),
                )))?
                .label("▲ cost above the chart (drawn at its edge)")
                .legend(|(x, y)| TriangleMarker::new((x + 11, y), 4, BLACK.mix(0.6).filled()));
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
        legend(
            &mut chart,
            SeriesLabelPosition::UpperRight,
            LegendStyle::Compact,
        )?;
        Ok(())
    }
}

/// A sweep's map as a figure.
struct Map<'a>(&'a Heatmap);

impl Map<'_> {
    /// The finite range of `z`.
    fn z_range(&self) -> (f64, f64) {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in self.0.z.iter().flatten().filter(|v| v.is_finite()) {
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
    fn levels(&self) -> Vec<f64> {
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

/// The map's start marker: a white ring with a dark rim (visible on the map's colours and on
/// the legend's white), at `$at`. A macro, so that the map and its legend draw the very same
/// composite element (its type depends on the backend).
macro_rules! start_marker {
    ($at:expr) => {
        EmptyElement::at($at)
            + Circle::new((0, 0), 8, BLACK.mix(0.8).stroke_width(5))
            + Circle::new((0, 0), 8, WHITE.stroke_width(3))
    };
}

/// The map's end marker: a `$colour` triangle in a white rim (plotters fills every triangle:
/// the rim is a larger white one beneath), at `$at`.
macro_rules! end_marker {
    ($at:expr, $colour:expr) => {
        EmptyElement::at($at)
            + TriangleMarker::new((0, 0), 12, WHITE.filled())
            + TriangleMarker::new((0, 0), 9, $colour.filled())
    };
}

fn level_label(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

impl Figure for Map<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 760)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let (zlo, zhi) = self.z_range();
        let levels = self.levels();
        let root = root.titled(&self.0.title, font(20))?;
        let (w, _) = root.dim_in_pixel();
        let (left, right) = root.split_horizontally(w.saturating_sub(150));
        let xc = half_steps(&self.0.xs);
        let yc = half_steps(&self.0.ys);
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
            .x_desc(self.0.x_label.as_str())
            .y_desc(self.0.y_label.as_str())
            .label_style(font(14))
            .axis_desc_style(font(16))
            .draw()?;
        let grey = RGBColor(190, 190, 190);
        chart.draw_series(self.0.ys.iter().enumerate().flat_map(|(j, _)| {
            let (xc, yc) = (&xc, &yc);
            self.0.xs.iter().enumerate().map(move |(i, _)| {
                let v = self.0.z[j][i];
                let style = if v.is_finite() {
                    ViridisRGB::get_color_normalized(v, zlo, zhi).filled()
                } else {
                    grey.filled()
                };
                Rectangle::new([(xc[i].0, yc[j].0), (xc[i].1, yc[j].1)], style)
            })
        }))?;
        for (k, lv) in levels.iter().enumerate() {
            let segs = segments(&self.0.xs, &self.0.ys, &self.0.z, *lv);
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
                    font(12).color(&WHITE),
                )))?;
            }
        }
        if let Some(path) = self.0.path.as_ref().filter(|p| !p.is_empty()) {
            let red = RGBColor(240, 40, 40);
            chart
                .draw_series(LineSeries::new(path.iter().copied(), red.stroke_width(2)))?
                .label("optimizer: best point so far")
                .legend(line_key(red.stroke_width(2), 22));
            chart.draw_series(path.iter().map(|p| Circle::new(*p, 2, red.filled())))?;
            // The legend's keys are the very markers of the map.
            chart
                .draw_series(std::iter::once(start_marker!(path[0])))?
                .label("start")
                .legend(|(x, y)| start_marker!((x + 11, y)));
            let end = path[path.len() - 1];
            chart
                .draw_series(std::iter::once(end_marker!(end, red)))?
                .label("end (best)")
                .legend(move |(x, y)| end_marker!((x + 11, y), red));
            legend(
                &mut chart,
                SeriesLabelPosition::UpperRight,
                LegendStyle::Compact,
            )?;
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
            .y_desc(self.0.z_label.as_str())
            .label_style(font(13))
            .axis_desc_style(font(15))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimize::Row;

    fn history(track: Track, costs: &[(usize, f64)]) -> History {
        let mut h = History::new(track, vec!["a".into(), "b".into()]);
        let mut best = f64::INFINITY;
        for (k, &(t, cost)) in costs.iter().enumerate() {
            best = best.min(cost);
            h.rows.push(Row {
                track: t,
                iteration: k as u64 / 3,
                evaluations: k as u64 + 1,
                cost,
                best_cost: best,
                x: vec![k as f64, 1.0],
            });
        }
        h
    }

    #[test]
    fn convergence_keeps_the_progress_in_view_and_marks_what_it_cuts() {
        // Two starts near -0.86, the second from a wild -0.39: the range follows the progress,
        // the wild costs are cut and marked, and the legend's room is above the cut.
        let mut costs: Vec<(usize, f64)> = (0..20).map(|k| (0, -0.85 - 0.001 * k as f64)).collect();
        costs.extend([(1, -0.39), (1, -0.39), (1, -0.6)]);
        costs.extend((0..17).map(|k| (1, -0.84 - 0.001 * k as f64)));
        let h = history(Track::Start, &costs);
        let c = Convergence {
            history: &h,
            title: "t".into(),
        };
        let (lo, cut, top) = c.y_range();
        assert!(lo < -0.869 && cut > -0.85 && cut < -0.8, "{lo} {cut}");
        assert!(top > cut + 0.3 * (cut - lo), "{cut} {top}");
        let dir = tempfile::tempdir().unwrap();
        let (png, svg) = (dir.path().join("c.png"), dir.path().join("c.svg"));
        convergence(&h, "t", &png, &svg).unwrap();
        assert!(std::fs::read_to_string(&svg)
            .unwrap()
            .contains("cost above the chart"));
    }

    #[test]
    fn convergence_draws_starts_swarms_and_runs_where_every_cut_failed() {
        let dir = tempfile::tempdir().unwrap();
        let ok: Vec<(usize, f64)> = (0..12).map(|k| (k % 2, -0.5 - 0.01 * k as f64)).collect();
        let failed: Vec<(usize, f64)> = (0..6).map(|k| (k % 3, FAILED_COST)).collect();
        for (name, h) in [
            ("nm", history(Track::Start, &ok)),
            ("pso", history(Track::Particle, &ok)),
            ("failed", history(Track::Start, &failed)),
            ("failed_pso", history(Track::Particle, &failed)),
        ] {
            let (png, svg) = (dir.path().join("c.png"), dir.path().join("c.svg"));
            convergence(&h, name, &png, &svg).unwrap();
            assert_eq!(&std::fs::read(&png).unwrap()[1..4], b"PNG", "{name}");
            let text = std::fs::read_to_string(&svg).unwrap();
            assert!(text.contains("best of the run"), "{name}");
            let swarm = text.contains("swarm best");
            assert_eq!(swarm, h.track == Track::Particle, "{name}");
        }
    }

    #[test]
    fn heatmap_draws_contours_grey_cells_and_the_path() {
        let xs: Vec<f64> = (0..9).map(|i| 30.0 + i as f64).collect();
        let ys: Vec<f64> = (0..7).map(|j| 39.0 + 0.5 * j as f64).collect();
        let mut z: Vec<Vec<f64>> = ys
            .iter()
            .map(|y| {
                xs.iter()
                    .map(|x| -((x - 34.0) / 3.0).powi(2) - (y - 40.5).powi(2))
                    .collect()
            })
            .collect();
        z[0][0] = f64::NAN;
        let mut map = Heatmap {
            title: "t".into(),
            xs,
            ys,
            z,
            x_label: "crown".into(),
            y_label: "pavilion".into(),
            z_label: "score".into(),
            path: Some(vec![(31.0, 39.5), (34.0, 40.5)]),
        };
        let m = Map(&map);
        let (lo, hi) = m.z_range();
        assert!(lo < -2.0 && hi == 0.0, "{lo} {hi}");
        assert!(m.levels().iter().all(|l| *l > lo && *l < hi));
        let dir = tempfile::tempdir().unwrap();
        let (png, svg) = (dir.path().join("m.png"), dir.path().join("m.svg"));
        heatmap(&map, &png, &svg).unwrap();
        assert_eq!(&std::fs::read(&png).unwrap()[1..4], b"PNG");
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.contains("end (best)") && text.contains("score"));
        map.path = None;
        heatmap(&map, &png, &svg).unwrap();
        assert!(!std::fs::read_to_string(&svg)
            .unwrap()
            .contains("end (best)"));
    }

    #[test]
    fn profile_draws_one_panel_per_score_with_its_highest_point() {
        let xs: Vec<f64> = (0..11).map(|i| 30.0 + i as f64).collect();
        let bump: Vec<f64> = xs
            .iter()
            .map(|x| (-((x - 34.0) / 3.0).powi(2)).exp())
            .collect();
        let mut fire: Vec<f64> = xs.iter().map(|x| x / 100.0).collect();
        fire[3] = f64::NAN;
        let lines = ProfileLines {
            title: "profile of t".into(),
            xs,
            x_label: "crown angle (°)".into(),
            series: vec![
                ("brilliance".into(), bump),
                ("fire".into(), fire),
                ("scintillation".into(), vec![0.2; 11]),
            ],
        };
        assert_eq!(padded_range(&[f64::NAN]), (0.0, 1.0));
        let (lo, hi) = padded_range(&[0.2, 0.2]);
        assert!(lo < 0.2 && hi > 0.2);
        let dir = tempfile::tempdir().unwrap();
        let (png, svg) = (dir.path().join("p.png"), dir.path().join("p.svg"));
        profile(&lines, &png, &svg).unwrap();
        assert_eq!(&std::fs::read(&png).unwrap()[1..4], b"PNG");
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.contains("profile of t") && text.contains("crown angle"));
        assert!(
            text.contains("highest brilliance: 1 at 34"),
            "the peak is marked"
        );
        assert!(text.contains("highest fire: 0.4 at 40"));
    }
}
