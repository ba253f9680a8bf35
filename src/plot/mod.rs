//! Charts and pictures with plotters: every figure is drawn by one function generic over the
//! backend and written as `STEM.png` and `STEM.svg` (each written to a temporary file and
//! renamed, so a failure leaves no half-written picture). Text uses the bundled DejaVu Sans.
//!
//! * [`face_categories`]: the thesis's bar chart of exit-face categories, one bar per cut;
//! * [`exit_angle_cdf`]: cumulative exit-angle curves, one per cut;
//! * [`rotation`]: the rotation sweep (share through faces < 45° and light return vs angle);
//! * [`photon_paths`]: recorded photon paths seen by an orthographic [`Camera`], coloured by
//!   bounce count or wavelength, with low alpha, the first segment on or off;
//! * [`facet_categories`]: the stone with its facets coloured by normal category.

use crate::error::{Error, Result};
use crate::geometry::{DVec3, Polyhedron};
use crate::optics::color::{cmf, srgb_encode, xyz_to_linear_srgb};
use crate::photon::{face_category, PhotonPath, Tally, CATEGORY_LABELS};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::{Path, PathBuf};
use std::sync::Once;

const FONT: &[u8] = include_bytes!("DejaVuSans.ttf");
static REGISTER: Once = Once::new();

/// Register the bundled DejaVu Sans as `sans-serif` (once per process), so text draws without
/// system fonts.
pub fn register_font() {
    REGISTER.call_once(|| {
        // The bundled font is valid; if registration ever failed, text would fall back to
        // plotters' error path, reported by the drawing calls.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// An orthographic camera looking at the girdle centre from azimuth (from +x toward +y) and
/// elevation (above the girdle plane), degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Azimuth, degrees.
    pub azimuth_deg: f64,
    /// Elevation, degrees.
    pub elevation_deg: f64,
}

impl Camera {
    /// Unit vectors (right, up, toward the camera).
    fn basis(&self) -> (DVec3, DVec3, DVec3) {
        let (a, e) = (
            self.azimuth_deg.to_radians(),
            self.elevation_deg.to_radians(),
        );
        let c = DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin());
        let right = DVec3::new(-a.sin(), a.cos(), 0.0);
        let up = c.cross(right);
        (right, up, c)
    }
    /// Screen coordinates (right, up) of `p`.
    pub fn project(&self, p: DVec3) -> (f64, f64) {
        let (r, u, _) = self.basis();
        (p.dot(r), p.dot(u))
    }
}

/// How path segments are coloured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathColor {
    /// By the number of surface interactions before the segment.
    Bounces,
    /// By the photon's wavelength (its sRGB colour).
    Wavelength,
}

/// Options of [`photon_paths`].
#[derive(Clone, Debug)]
pub struct PathStyle {
    /// The camera.
    pub camera: Camera,
    /// Colouring.
    pub color: PathColor,
    /// Draw the segment from the light to the stone.
    pub first_segment: bool,
    /// Opacity of each path, (0, 1].
    pub alpha: f64,
    /// Draw at most this many paths.
    pub max_paths: usize,
    /// Title.
    pub title: String,
}

/// Colours of the four face categories.
pub const CATEGORY_COLORS: [RGBColor; 4] = [
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(214, 39, 40),
];

/// Series colours (cuts).
const SERIES: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// Colours by interaction count: 0 = light → stone, then after 1, 2, … interactions.
const BOUNCE: [RGBColor; 8] = [
    RGBColor(150, 150, 150),
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(230, 160, 0),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(0, 0, 0),
];

type DrawResult = std::result::Result<(), String>;

fn e<T: std::fmt::Display>(x: T) -> String {
    x.to_string()
}

/// A figure drawable on any backend.
trait Figure {
    fn size(&self) -> (u32, u32);
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult;
}

fn with_ext(stem: &Path, ext: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_owned();
    s.push(".");
    s.push(ext);
    PathBuf::from(s)
}

/// Write `fig` as STEM.png and STEM.svg.
fn save<F: Figure>(fig: &F, stem: &Path) -> Result<()> {
    register_font();
    let png = with_ext(stem, "png");
    let svg = with_ext(stem, "svg");
    let shown = png.display().to_string();
    let dir = stem
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."));
    let name = stem
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_else(|| "plot".into());
    let tmp = dir.join(format!(".{name}.tmp-{}.png", std::process::id()));
    let drawn = {
        let root = BitMapBackend::new(&tmp, fig.size()).into_drawing_area();
        fig.draw(&root).and_then(|_| root.present().map_err(e))
    };
    if let Err(m) = drawn.and_then(|_| std::fs::rename(&tmp, &png).map_err(e)) {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::io(shown, m));
    }
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, fig.size()).into_drawing_area();
        fig.draw(&root)
            .and_then(|_| root.present().map_err(e))
            .map_err(|m| Error::io(svg.display().to_string(), m))?;
    }
    crate::io::write_atomic(&svg, text.as_bytes())
}

/// Tick label of degrees: only multiples of 30°.
fn every_30(x: &f64) -> String {
    let r = x.round();
    if (x - r).abs() < 1e-6 && (r as i64) % 30 == 0 {
        format!("{r}°")
    } else {
        String::new()
    }
}

fn font(size: u32) -> TextStyle<'static> {
    ("sans-serif", size).into_font().color(&BLACK)
}

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
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        root.fill(&WHITE).map_err(e)?;
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
            .build_cartesian_2d(0f64..4f64, 0f64..ymax.min(100.0))
            .map_err(e)?;
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
            .draw()
            .map_err(e)?;
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
                .draw_series(bars)
                .map_err(e)?
                .label(format!("{} ({} photons hit)", t.cut, t.counts.hit))
                .legend(move |(x, y)| Rectangle::new([(x, y - 6), (x + 14, y + 6)], c.filled()));
            chart
                .draw_series((0..4).map(|k| {
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
                }))
                .map_err(e)?;
            chart
                .draw_series((0..4).map(|k| {
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
                }))
                .map_err(e)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .label_font(font(16))
            .draw()
            .map_err(e)?;
        Ok(())
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
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        root.fill(&WHITE).map_err(e)?;
        let mut chart = ChartBuilder::on(root)
            .caption(format!("Cumulative exit angle — {}", self.light), font(24))
            .margin(16)
            .x_label_area_size(56)
            .y_label_area_size(70)
            .build_cartesian_2d(0f64..180f64, 0f64..100f64)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc("angle between exit direction and up (°)")
            .x_labels(19)
            .x_label_formatter(&every_30)
            .y_desc("exited photons within that angle (%)")
            .y_label_formatter(&|v| format!("{v:.0}"))
            .label_style(font(16))
            .axis_desc_style(font(17))
            .draw()
            .map_err(e)?;
        for (i, t) in self.tallies.iter().enumerate() {
            let c = SERIES[i % SERIES.len()];
            let (cdf, _) = t.exit_angle_cdf();
            chart
                .draw_series(LineSeries::new(
                    cdf.iter().enumerate().map(|(k, v)| (k as f64, 100.0 * v)),
                    c.stroke_width(3),
                ))
                .map_err(e)?
                .label(format!("{} ({} exited)", t.cut, t.counts.exited()))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(3))
                });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .label_font(font(16))
            .draw()
            .map_err(e)?;
        Ok(())
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
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        root.fill(&WHITE).map_err(e)?;
        let mut chart = ChartBuilder::on(root)
            .caption(
                format!("Light turned around the stone — {} light", self.kind),
                font(24),
            )
            .margin(16)
            .x_label_area_size(56)
            .y_label_area_size(70)
            .build_cartesian_2d(-5f64..185f64, 0f64..100f64)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc("light angle from straight above (°)")
            .x_labels(19)
            .x_label_formatter(&every_30)
            .y_desc("share of photons that hit the stone (%)")
            .y_label_formatter(&|v| format!("{v:.0}"))
            .label_style(font(16))
            .axis_desc_style(font(17))
            .draw()
            .map_err(e)?;
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
                .draw_series(LineSeries::new(top.clone(), c.stroke_width(3)))
                .map_err(e)?
                .label(format!("{name}: exit faces < 45°"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(3))
                });
            chart
                .draw_series(top.iter().map(|p| Circle::new(*p, 5, c.filled())))
                .map_err(e)?;
            chart
                .draw_series(DashedLineSeries::new(ret.clone(), 10, 6, c.stroke_width(2)))
                .map_err(e)?
                .label(format!("{name}: light return (upward)"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 8, y)], c.stroke_width(2))
                });
            chart
                .draw_series(ret.iter().map(|p| TriangleMarker::new(*p, 6, c.filled())))
                .map_err(e)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .label_font(font(16))
            .draw()
            .map_err(e)?;
        Ok(())
    }
}

/// The rotation sweep: share through faces < 45° (solid, circles) and light return (dashed,
/// triangles) against the light's angle, per cut.
pub fn rotation(sweeps: &[(&str, &[Tally])], kind: &str, stem: &Path) -> Result<()> {
    save(&Rotation { sweeps, kind }, stem)
}

// ---------------------------------------------------------------------------------------------
// Pictures of the stone

/// Clip segment a→b to the rectangle; `None` if outside (Liang–Barsky).
fn clip(
    a: (f64, f64),
    b: (f64, f64),
    lo: (f64, f64),
    hi: (f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - lo.0),
        (dx, hi.0 - a.0),
        (-dy, a.1 - lo.1),
        (dy, hi.1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then_some({
        (
            (a.0 + t0 * dx, a.1 + t0 * dy),
            (a.0 + t1 * dx, a.1 + t1 * dy),
        )
    })
}

/// Square view window (lo, hi) around the stone's projection, `pad` times its size.
fn window(solid: &Polyhedron, cam: Camera, pad: f64) -> ((f64, f64), (f64, f64)) {
    let pts: Vec<(f64, f64)> = solid.vertices.iter().map(|v| cam.project(*v)).collect();
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let h = 0.5 * (x1 - x0).max(y1 - y0) * pad;
    ((cx - h, cy - h), (cx + h, cy + h))
}

/// Draw the stone's edges: front edges dark, back edges light.
fn draw_edges<DB: DrawingBackend, CT: plotters::coord::CoordTranslate<From = (f64, f64)>>(
    area: &DrawingArea<DB, CT>,
    solid: &Polyhedron,
    cam: Camera,
    front: RGBAColor,
    back: RGBAColor,
) -> DrawResult {
    let (_, _, toward) = cam.basis();
    for edge in &solid.edges {
        let visible = edge
            .facets
            .iter()
            .any(|&f| solid.facets[f].plane.normal.dot(toward) > 1e-12);
        let a = cam.project(solid.vertices[edge.a]);
        let b = cam.project(solid.vertices[edge.b]);
        let style = if visible {
            front.stroke_width(1)
        } else {
            back.stroke_width(1)
        };
        area.draw(&PathElement::new(vec![a, b], style)).map_err(e)?;
    }
    Ok(())
}

/// sRGB colour of a wavelength (saturated, brightness normalised). Wavelengths beyond
/// 400–670 nm take the colour of the nearer end: out there the colour-matching fit's tails,
/// not the hue, would decide the normalised colour.
pub fn wavelength_rgb(nm: f64) -> RGBColor {
    let l = xyz_to_linear_srgb(cmf(nm.clamp(400.0, 670.0)));
    let l = DVec3::new(l.x.max(0.0), l.y.max(0.0), l.z.max(0.0));
    let m = l.max_element().max(1e-9);
    let c = l / m;
    let f = |v: f64| (srgb_encode(v) * 255.0).round() as u8;
    RGBColor(f(c.x), f(c.y), f(c.z))
}

struct Paths<'a> {
    solid: &'a Polyhedron,
    paths: &'a [PhotonPath],
    style: &'a PathStyle,
}

impl Figure for Paths<'_> {
    fn size(&self) -> (u32, u32) {
        (900, 900)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        let st = self.style;
        let bg = RGBColor(255, 255, 255);
        root.fill(&bg).map_err(e)?;
        let cam = st.camera;
        let (lo, hi) = window(self.solid, cam, 2.6);
        let titled = root
            .margin(8, 0, 0, 0)
            .titled(&st.title, font(22))
            .map_err(e)?;
        let (main, foot) = titled.split_vertically(titled.dim_in_pixel().1 - 60);
        let mut chart = ChartBuilder::on(&main)
            .margin(10)
            .build_cartesian_2d(lo.0..hi.0, lo.1..hi.1)
            .map_err(e)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .disable_axes()
            .draw()
            .map_err(e)?;
        let area = chart.plotting_area();
        draw_edges(area, self.solid, cam, BLACK.mix(0.9), BLACK.mix(0.3))?;
        let n = st.max_paths.min(self.paths.len());
        let alpha = st.alpha.clamp(0.01, 1.0);
        for p in &self.paths[..n] {
            let pts: Vec<(f64, f64)> = p.points.iter().map(|q| cam.project(*q)).collect();
            for (k, w) in pts.windows(2).enumerate() {
                if k == 0 && !st.first_segment {
                    continue;
                }
                let c = match st.color {
                    PathColor::Bounces => BOUNCE[k.min(BOUNCE.len() - 1)],
                    PathColor::Wavelength => wavelength_rgb(p.wavelength),
                };
                if let Some((a, b)) = clip(w[0], w[1], lo, hi) {
                    let width = if n == 1 { 2 } else { 1 };
                    area.draw(&PathElement::new(
                        vec![a, b],
                        c.mix(alpha).stroke_width(width),
                    ))
                    .map_err(e)?;
                }
            }
            if n == 1 {
                for q in &pts[1..pts.len() - 1] {
                    area.draw(&Circle::new(*q, 3, BLACK.filled())).map_err(e)?;
                }
            }
        }
        // Legend / caption strip.
        let line = format!(
            "{} photon path{} · camera azimuth {}°, elevation {}° (orthographic) · window {:.2} D wide",
            n,
            if n == 1 { "" } else { "s" },
            cam.azimuth_deg,
            cam.elevation_deg,
            hi.0 - lo.0
        );
        foot.draw(&Text::new(line, (12, 4), font(15))).map_err(e)?;
        match st.color {
            PathColor::Bounces => {
                let labels = ["light → stone", "after 1", "2", "3", "4", "5", "6", "7+"];
                let mut x = 12;
                for (k, l) in labels.iter().enumerate() {
                    if k == 0 && !st.first_segment {
                        continue;
                    }
                    foot.draw(&Rectangle::new([(x, 30), (x + 22, 42)], BOUNCE[k].filled()))
                        .map_err(e)?;
                    foot.draw(&Text::new(l.to_string(), (x + 27, 28), font(15)))
                        .map_err(e)?;
                    x += 37 + 9 * l.chars().count() as i32;
                }
                foot.draw(&Text::new(
                    "interactions before the segment".to_string(),
                    (x + 8, 28),
                    font(15),
                ))
                .map_err(e)?;
            }
            PathColor::Wavelength => {
                let x0 = 12;
                for (i, nm) in (380..=780).step_by(4).enumerate() {
                    let x = x0 + 3 * i as i32;
                    foot.draw(&Rectangle::new(
                        [(x, 30), (x + 3, 44)],
                        wavelength_rgb(nm as f64).filled(),
                    ))
                    .map_err(e)?;
                }
                foot.draw(&Text::new(
                    "380 – 780 nm (colour of each photon's wavelength)".to_string(),
                    (x0 + 3 * 101 + 12, 28),
                    font(15),
                ))
                .map_err(e)?;
            }
        }
        Ok(())
    }
}

/// Photon paths seen from `style.camera` over the stone's edges (back edges faint), coloured
/// by bounce count or wavelength, each with opacity `style.alpha`; the segment from the light
/// is drawn only with `style.first_segment`. The window is 2.6× the stone's projected size;
/// longer segments are clipped at its border.
pub fn photon_paths(
    solid: &Polyhedron,
    paths: &[PhotonPath],
    style: &PathStyle,
    stem: &Path,
) -> Result<()> {
    save(
        &Paths {
            solid,
            paths,
            style,
        },
        stem,
    )
}

struct Facets<'a> {
    solid: &'a Polyhedron,
    cam: Camera,
    title: &'a str,
}

impl Facets<'_> {
    fn panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        cam: Camera,
        caption: &str,
    ) -> DrawResult {
        let (lo, hi) = window(self.solid, cam, 1.1);
        let mut chart = ChartBuilder::on(area)
            .caption(caption, font(18))
            .margin(10)
            .build_cartesian_2d(lo.0..hi.0, lo.1..hi.1)
            .map_err(e)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .disable_axes()
            .draw()
            .map_err(e)?;
        let plot = chart.plotting_area();
        let (_, _, toward) = cam.basis();
        for (i, f) in self.solid.facets.iter().enumerate() {
            let facing = f.plane.normal.dot(toward);
            if facing <= 1e-9 {
                continue;
            }
            let c = CATEGORY_COLORS[face_category(f.plane.normal) as usize];
            // Shade by facing so neighbouring facets of one category stay distinguishable.
            let s = 0.55 + 0.45 * facing;
            let shaded = RGBColor(
                (c.0 as f64 * s) as u8,
                (c.1 as f64 * s) as u8,
                (c.2 as f64 * s) as u8,
            );
            let poly: Vec<(f64, f64)> = self
                .solid
                .facet_polygon(i)
                .iter()
                .map(|v| cam.project(*v))
                .collect();
            plot.draw(&Polygon::new(poly, shaded.filled())).map_err(e)?;
        }
        draw_edges(plot, self.solid, cam, BLACK.mix(1.0), TRANSPARENT)?;
        Ok(())
    }
}

impl Figure for Facets<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 680)
    }
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        root.fill(&WHITE).map_err(e)?;
        let titled = root
            .margin(8, 0, 0, 0)
            .titled(self.title, font(24))
            .map_err(e)?;
        let (main, foot) = titled.split_vertically(titled.dim_in_pixel().1 - 40);
        let panels = main.split_evenly((1, 2));
        let below = Camera {
            azimuth_deg: self.cam.azimuth_deg,
            elevation_deg: -self.cam.elevation_deg,
        };
        self.panel(
            &panels[0],
            self.cam,
            &format!(
                "from above: azimuth {}°, elevation {}°",
                self.cam.azimuth_deg, self.cam.elevation_deg
            ),
        )?;
        self.panel(
            &panels[1],
            below,
            &format!(
                "from below: azimuth {}°, elevation {}°",
                below.azimuth_deg, below.elevation_deg
            ),
        )?;
        let mut x = 20;
        foot.draw(&Text::new(
            "facet normal from up:".to_string(),
            (x, 8),
            font(17),
        ))
        .map_err(e)?;
        x += 185;
        for (k, l) in CATEGORY_LABELS.iter().enumerate() {
            foot.draw(&Rectangle::new(
                [(x, 8), (x + 24, 26)],
                CATEGORY_COLORS[k].filled(),
            ))
            .map_err(e)?;
            foot.draw(&Text::new(l.to_string(), (x + 30, 8), font(17)))
                .map_err(e)?;
            x += 130;
        }
        Ok(())
    }
}

/// The stone seen from `camera` and from the mirrored camera below, facets filled with the
/// colour of their normal category (< 45°, 45–90°, 90–135°, > 135° from up), shaded by how
/// squarely they face the camera.
pub fn facet_categories(
    solid: &Polyhedron,
    camera: Camera,
    title: &str,
    stem: &Path,
) -> Result<()> {
    save(
        &Facets {
            solid,
            cam: camera,
            title,
        },
        stem,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photon::{rotation_sweep, trace_cut, Light, LightKind, TraceConfig};

    #[test]
    fn every_figure_is_written_as_png_and_svg() {
        let dir = std::env::temp_dir().join(format!("facetlab-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let cut = crate::io::load_cut("tolkowsky").unwrap();
        let cfg = TraceConfig {
            photons: 3_000,
            record_paths: 30,
            ..TraceConfig::thesis()
        };
        let t = trace_cut(&cut.solid, &cut.name, &Light::directed(0.0), &cfg, None).unwrap();
        let sweep = rotation_sweep(
            &cut.solid,
            &cut.name,
            LightKind::Directed,
            &TraceConfig {
                photons: 300,
                ..cfg.clone()
            },
            None,
        )
        .unwrap();
        let cam = Camera {
            azimuth_deg: 30.0,
            elevation_deg: 20.0,
        };
        face_categories(&[&t, &t], "test", &dir.join("bars")).unwrap();
        exit_angle_cdf(&[&t], "test", &dir.join("cdf")).unwrap();
        rotation(&[("tolkowsky", &sweep)], "directed", &dir.join("rot")).unwrap();
        facet_categories(&cut.solid, cam, "facets", &dir.join("facets")).unwrap();
        for color in [PathColor::Bounces, PathColor::Wavelength] {
            let style = PathStyle {
                camera: cam,
                color,
                first_segment: false,
                alpha: 0.3,
                max_paths: 30,
                title: "paths".into(),
            };
            photon_paths(&cut.solid, &t.paths, &style, &dir.join("paths")).unwrap();
        }
        for stem in ["bars", "cdf", "rot", "facets", "paths"] {
            let png = std::fs::read(dir.join(format!("{stem}.png"))).unwrap();
            assert_eq!(&png[1..4], b"PNG", "{stem}");
            let svg = std::fs::read_to_string(dir.join(format!("{stem}.svg"))).unwrap();
            assert!(svg.contains("<svg") && svg.len() > 1000, "{stem}");
        }
        // No temporary files are left behind.
        assert!(std::fs::read_dir(&dir).unwrap().all(|f| !f
            .unwrap()
            .file_name()
            .to_string_lossy()
            .starts_with('.')));
        // A missing folder is a one-line error, not a panic.
        let err = face_categories(&[&t], "x", &dir.join("no/such/dir/bars"))
            .unwrap_err()
            .to_string();
        assert!(!err.contains('\n'), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn camera_projects_up_to_screen_up() {
        let cam = Camera {
            azimuth_deg: 0.0,
            elevation_deg: 0.0,
        };
        assert_eq!(cam.project(DVec3::Z), (0.0, 1.0));
        assert_eq!(cam.project(DVec3::Y), (1.0, 0.0));
        assert!(
            clip((-2.0, 0.0), (2.0, 0.0), (-1.0, -1.0), (1.0, 1.0))
                == Some(((-1.0, 0.0), (1.0, 0.0)))
        );
        assert!(clip((-2.0, 5.0), (2.0, 5.0), (-1.0, -1.0), (1.0, 1.0)).is_none());
    }
}
