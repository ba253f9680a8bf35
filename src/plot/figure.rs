//! Figures and saving: the bundled font, the [`Figure`] trait every chart implements, and
//! [`save`], which writes a figure as PNG and SVG atomically.

use super::text;
use crate::error::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::{Path, PathBuf};
use std::sync::Once;

/// The bundled DejaVu Sans.
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
/// The bundled DejaVu Sans, the text of every picture and page (for drawing elsewhere, e.g. a PDF).
pub fn font_bytes() -> &'static [u8] {
    FONT
}

/// Plotters' text style of the bundled font at `size`, black.
pub fn font(size: u32) -> TextStyle<'static> {
    ("sans-serif", size).into_font().color(&BLACK)
}

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
