//! Charts and pictures with plotters. Every figure is a [`Figure`]: drawn by one function generic
//! over the backend and written by [`save`] as `STEM.png` and `STEM.svg` (each written to a
//! temporary file and renamed, so a failure leaves no half-written picture). Text uses the
//! bundled DejaVu Sans; colours come from one palette ([`palette`]: [`TAB10`], and the grounds
//! of stone pictures); legends from [`legend`].
//!
//! The plot floor sits over the optimizer and the planner: it draws from what they return
//! (and from everything below them), and nothing under it calls it; the report and the binary
//! above it do. The rooms:
//!
//! * [`trace`]: the photon tracer's charts — [`face_categories`] (the thesis's bar chart of
//!   exit-face categories, one bar per cut), [`exit_angle_cdf`] (cumulative exit-angle curves,
//!   one per cut) and [`rotation`] (share through faces < 45° and light return vs the light's
//!   angle);
//! * [`paths`]: pictures of the stone — [`photon_paths`] (recorded photon paths seen by an
//!   orthographic [`Camera`], coloured by bounce count or wavelength, with low alpha, the first
//!   segment on or off) and [`facet_categories`] (facets coloured by normal category);
//! * [`optimize`]: the optimizer's charts — [`optimize::convergence`] (a run's cost against
//!   evaluations) and [`optimize::heatmap`] (a sweep's score map with [`contour`] lines and the
//!   optimizer's path). The optimizer draws no charts itself: the binary hands these
//!   functions to a run and a sweep;
//! * [`render`]: sheets of stone pictures — [`render::compose`] puts already-encoded pictures
//!   side by side on a grey ground with their captions and a false-colour legend
//!   ([`render::legend_for`]);
//! * [`diagram`]: a cutter's facet diagram of a cut, as a GemCad-style SVG page
//!   ([`diagram::diagram`]);
//! * [`pareto`]: the trade-off front between two scores, with the reference cuts;
//! * [`plan`]: a rough planned (`facetlab plan`): three views of the rough with the cuts inside
//!   ([`plan::ThreeViews`]);
//! * [`palette`]: every colour handed out here, the grounds of stone pictures included;
//! * [`text`]: text set with its bearings, kerning and baseline ([`text::TextBackend`] wraps
//!   every backend this floor draws on).

pub mod contour;
pub mod diagram;
pub mod optimize;
pub mod palette;
pub mod pareto;
pub mod paths;
pub mod plan;
pub mod render;
pub mod text;
pub mod trace;

pub use palette::{SERIES, TAB10};
pub use paths::{
    facet_categories, photon_paths, wavelength_rgb, Camera, PathColor, PathStyle, CATEGORY_COLORS,
};
pub use trace::{exit_angle_cdf, face_categories, rotation};

use crate::error::{Error, Result};
use plotters::chart::{ChartContext, SeriesLabelPosition};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::{Path, PathBuf};
use std::sync::Once;

pub(crate) const FONT: &[u8] = include_bytes!("DejaVuSans.ttf");
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

/// Black text in the bundled font, `size` pixels.
pub fn font(size: u32) -> TextStyle<'static> {
    ("sans-serif", size).into_font().color(&BLACK)
}

// ---------------------------------------------------------------------------------------------
// Figures and saving

/// The result of a drawing step on backend `DB`.
pub type DrawResult<DB> =
    std::result::Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// A picture that can be drawn on any plotters backend.
pub trait Figure {
    /// Pixel size (width, height).
    fn size(&self) -> (u32, u32);
    /// Draw on `root`, already filled white.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB>;
}

/// `STEM.EXT` (the extension is appended: a dot in the stem stays).
pub fn with_ext(stem: &Path, ext: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_owned();
    s.push(".");
    s.push(ext);
    PathBuf::from(s)
}

fn draw_err(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::io(path.display().to_string(), format!("could not draw: {e}"))
}

/// Draw `fig` on a white `root` and finish it.
fn draw_on<DB: DrawingBackend>(
    fig: &impl Figure,
    root: DrawingArea<DB, Shift>,
    path: &Path,
) -> Result<()> {
    root.fill(&WHITE).map_err(|e| draw_err(path, e))?;
    fig.draw(&root).map_err(|e| draw_err(path, e))?;
    root.present().map_err(|e| draw_err(path, e))
}

/// Write `fig` as STEM.png and STEM.svg.
pub fn save(fig: &impl Figure, stem: &Path) -> Result<()> {
    save_to(fig, &with_ext(stem, "png"), &with_ext(stem, "svg"))
}

/// Write `fig` as the PNG `png` and the SVG `svg`, each beside its target first and then
/// renamed, so a failure leaves no half-written picture.
pub fn save_to(fig: &impl Figure, png: &Path, svg: &Path) -> Result<()> {
    register_font();
    // Drawn in memory and encoded by the crate's own PNG writer (plotters' file encoder
    // would bring the whole `image` crate into the build for it), written atomically.
    let (w, h) = fig.size();
    let mut rgb = vec![0u8; w as usize * h as usize * 3];
    draw_on(
        fig,
        text::TextBackend::raster(BitMapBackend::with_buffer(&mut rgb, (w, h))).into_drawing_area(),
        png,
    )?;
    let bytes = crate::io::png::encode_rgb8(w, h, &[&rgb], 0)?;
    crate::io::write_atomic(png, &bytes)?;
    let mut text = String::new();
    draw_on(
        fig,
        text::TextBackend::vector(SVGBackend::with_string(&mut text, fig.size()))
            .into_drawing_area(),
        svg,
    )?;
    crate::io::write_atomic(svg, text.as_bytes())
}

// ---------------------------------------------------------------------------------------------
// Legends and axes

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photon::{rotation_sweep, trace_cut, Light, LightKind, TraceConfig};

    struct Cross;

    impl Figure for Cross {
        fn size(&self) -> (u32, u32) {
            (120, 80)
        }
        fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
            let mut chart = ChartBuilder::on(root).build_cartesian_2d(0f64..1f64, 0f64..1f64)?;
            chart
                .draw_series(LineSeries::new([(0.0, 0.0), (1.0, 1.0)], TAB10[0]))?
                .label("key-a")
                .legend(line_key(TAB10[0].stroke_width(2), 20));
            legend(
                &mut chart,
                SeriesLabelPosition::UpperLeft,
                LegendStyle::Compact,
            )
        }
    }

    #[test]
    fn save_writes_png_and_svg_and_no_temporary_files() {
        let dir = tempfile::tempdir().unwrap();
        save(&Cross, &dir.path().join("x.v2")).unwrap();
        let png = std::fs::read(dir.path().join("x.v2.png")).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        let svg = std::fs::read_to_string(dir.path().join("x.v2.svg")).unwrap();
        assert!(svg.contains("<svg") && svg.contains("key-a"), "{svg}");
        let names: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|f| f.unwrap().file_name().to_string_lossy().to_string())
            .collect();
        assert_eq!(names.len(), 2, "{names:?}");
        // A missing folder is a one-line error naming the file, not a panic.
        let bad = dir.path().join("no/such/x");
        let err = save(&Cross, &bad).unwrap_err().to_string();
        assert!(!err.contains('\n') && err.contains("x.png"), "{err}");
    }

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
    fn one_palette() {
        assert!(SERIES.iter().all(|c| TAB10.contains(c)));
        assert!(CATEGORY_COLORS.iter().all(|c| TAB10.contains(c)));
        assert_eq!(every_30(&60.0), "60°");
        assert_eq!(every_30(&50.0), "");
    }
}
