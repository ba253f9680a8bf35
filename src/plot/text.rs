//! Text set on pictures and charts: the bundled DejaVu Sans laid out glyph by glyph with its
//! advances, side bearings and kerning pairs, on a baseline, and rasterised with exact
//! coverage by [`ab_glyph`] (the rasteriser of `glyph_brush`; the same outlines plotters
//! carries).
//!
//! Why not plotters' own text: its `ab_glyph` drawing places each glyph by its pixel box
//! instead of its outline's origin, so side bearings are lost (letters collide: "Tolkowsky"
//! reads "Tlkowsky") and every glyph sits on its own rounded box (a decimal point rides up to
//! a raised dot, "79·9 %"). [`TextBackend`] wraps any plotters backend and draws every text
//! of a raster backend with [`draw`]; a vector backend (SVG) keeps its `<text>` elements, which
//! the viewer sets with its own font engine. Both measure text with [`width`], so the layout
//! of a chart is the same in its PNG and its SVG.
//!
//! Sizes are plotters' font sizes `s`: the font scaled so that its ascent minus descent is
//! `s` pixels (plotters' own measure). A text anchored at its top has the top of its capitals
//! there; centred, its capitals are centred; at the bottom, its descenders end there. The
//! baseline is put on a whole pixel, so that every glyph of a line shares it to the pixel.

use ab_glyph::{point, Font, FontRef, GlyphId, PxScale, ScaleFont};
use plotters::prelude::*;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind,
};
use std::sync::OnceLock;

/// The bundled font, parsed once.
fn face() -> &'static FontRef<'static> {
    static FACE: OnceLock<FontRef<'static>> = OnceLock::new();
    FACE.get_or_init(|| {
        // The bundled DejaVu Sans is a valid TrueType file (a test reads it).
        FontRef::try_from_slice(super::FONT).expect("bundled DejaVu Sans")
    })
}

/// Vertical metrics at one size, in pixels below (positive) or above (negative) the baseline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Metrics {
    /// Height of the capitals above the baseline (the top of an `H`).
    pub cap: f32,
    /// Depth of the descenders below the baseline (the font's descent).
    pub descent: f32,
}

/// The metrics of text of size `size`.
pub fn metrics(size: f64) -> Metrics {
    let f = face().as_scaled(PxScale::from(size as f32));
    let h = f.glyph_id('H');
    let cap = f
        .font()
        .outline(h)
        .map(|o| o.bounds.min.y * f.v_scale_factor())
        .unwrap_or(0.7 * size as f32);
    Metrics {
        cap,
        descent: -f.descent(),
    }
}

/// One glyph of a laid-out line: its id and the x of its origin on the baseline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placed {
    /// The glyph.
    pub id: GlyphId,
    /// Its origin, pixels from the line's start.
    pub x: f32,
}

/// A line of text laid out at `size`: each glyph after the previous one's advance and the
/// kerning between the two; the returned width is the last glyph's advance end.
pub fn layout(text: &str, size: f64) -> (Vec<Placed>, f32) {
    let f = face().as_scaled(PxScale::from(size as f32));
    let mut out = Vec::with_capacity(text.len());
    let mut x = 0.0f32;
    let mut prev: Option<GlyphId> = None;
    for c in text.chars() {
        let id = f.glyph_id(c);
        if let Some(p) = prev {
            x += f.kern(p, id);
        }
        out.push(Placed { id, x });
        x += f.h_advance(id);
        prev = Some(id);
    }
    (out, x)
}

/// Width in pixels of `text` at `size`.
pub fn width(text: &str, size: f64) -> f32 {
    layout(text, size).1
}

/// Width in pixels of `text` set in DejaVu Sans with an em of `em` pixels (an SVG or CSS
/// `font-size`), for laying out text a viewer will set.
pub fn width_at_em(text: &str, em: f64) -> f64 {
    let f = face();
    let per_em = f64::from(f.height_unscaled()) / f64::from(f.units_per_em().unwrap_or(2048.0));
    f64::from(width(text, em * per_em))
}

/// Rasterise `text` at `size` with its baseline starting at `origin` (pixels; the baseline's
/// height is rounded to a whole pixel), calling `plot(x, y, coverage)` for every pixel a
/// glyph touches (coverage in (0, 1]).
pub fn draw(text: &str, size: f64, origin: (f32, f32), mut plot: impl FnMut(i32, i32, f32)) {
    let scale = PxScale::from(size as f32);
    let f = face();
    let base = origin.1.round();
    for g in layout(text, size).0 {
        let glyph =
            g.id.with_scale_and_position(scale, point(origin.0 + g.x, base));
        if let Some(o) = f.outline_glyph(glyph) {
            let b = o.px_bounds();
            o.draw(|x, y, c| {
                if c > 0.0 {
                    plot(
                        b.min.x as i32 + x as i32,
                        b.min.y as i32 + y as i32,
                        c.min(1.0),
                    );
                }
            });
        }
    }
}

/// The baseline offset from an anchor point, for text of `size` anchored by `v`.
fn baseline_below_anchor(size: f64, v: VPos) -> f32 {
    let m = metrics(size);
    match v {
        VPos::Top => m.cap,
        VPos::Center => m.cap / 2.0,
        VPos::Bottom => -m.descent,
    }
}

/// A plotters backend whose raster text is set by this module (see the
/// [module documentation](self)); everything else goes to the wrapped backend.
pub struct TextBackend<DB> {
    inner: DB,
    raster: bool,
}

impl<DB: DrawingBackend> TextBackend<DB> {
    /// Wrap a raster backend (a bitmap): its text is drawn here.
    pub fn raster(inner: DB) -> Self {
        TextBackend {
            inner,
            raster: true,
        }
    }

    /// Wrap a vector backend (an SVG): it keeps drawing its text as text.
    pub fn vector(inner: DB) -> Self {
        TextBackend {
            inner,
            raster: false,
        }
    }
}

impl<DB: DrawingBackend> DrawingBackend for TextBackend<DB> {
    type ErrorType = DB::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.inner.get_size()
    }
    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.ensure_prepared()
    }
    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.present()
    }
    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_pixel(point, color)
    }
    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_line(from, to, style)
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_rect(upper_left, bottom_right, style, fill)
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_path(path, style)
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_circle(center, radius, style, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.fill_polygon(vert, style)
    }
    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        (iw, ih): (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.blit_bitmap(pos, (iw, ih), src)
    }

    fn estimate_text_size<TStyle: BackendTextStyle>(
        &self,
        text: &str,
        style: &TStyle,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        let m = metrics(style.size());
        Ok((
            width(text, style.size()).ceil() as u32,
            (m.cap + m.descent).ceil() as u32,
        ))
    }

    fn draw_text<TStyle: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &TStyle,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        if !self.raster {
            return self.inner.draw_text(text, style, pos);
        }
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        let size = style.size();
        let w = width(text, size);
        let dx = match style.anchor().h_pos {
            HPos::Left => 0.0,
            HPos::Center => -w / 2.0,
            HPos::Right => -w,
        };
        let dy = baseline_below_anchor(size, style.anchor().v_pos);
        let trans = style.transform();
        let (bw, bh) = self.inner.get_size();
        let mut pixels = Vec::new();
        // Laid out about the anchor, then turned with the text's transform (a turned axis
        // label) and moved to the anchor.
        draw(text, size, (dx, dy), |x, y, c| pixels.push((x, y, c)));
        for (x, y, c) in pixels {
            let (x, y) = trans.transform(x, y);
            let (x, y) = (pos.0 + x, pos.1 + y);
            if x >= 0 && y >= 0 && (x as u32) < bw && (y as u32) < bh {
                let px = BackendColor {
                    alpha: color.alpha * c as f64,
                    rgb: color.rgb,
                };
                self.inner.draw_pixel((x, y), px)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pixels of `text` at `size` drawn at baseline y = 100: (x range, y range) of the ink.
    fn ink(text: &str, size: f64) -> Vec<(i32, i32, f32)> {
        let mut v = Vec::new();
        draw(text, size, (10.0, 100.0), |x, y, c| v.push((x, y, c)));
        v
    }

    #[test]
    fn the_bundled_font_kerns_and_measures() {
        let f = face().as_scaled(PxScale::from(20.0));
        // DejaVu Sans kerns "To" and "AV" (its `kern` table); an unkerned pair stays apart.
        let kern = |a: char, b: char| f.kern(f.glyph_id(a), f.glyph_id(b));
        assert!(kern('T', 'o') < -0.5, "T-o kern {}", kern('T', 'o'));
        assert!(kern('A', 'V') < -0.5, "A-V kern {}", kern('A', 'V'));
        // The laid-out width is the advances plus the kerning.
        let adv = |c: char| f.h_advance(f.glyph_id(c));
        let w = width("To", 20.0);
        assert!((w - (adv('T') + adv('o') + kern('T', 'o'))).abs() < 1e-4);
        let m = metrics(20.0);
        assert!(
            m.cap > 11.0 && m.cap < 14.0 && m.descent > 3.0 && m.descent < 5.0,
            "{m:?}"
        );
    }

    #[test]
    fn a_decimal_point_sits_on_the_baseline_and_letters_do_not_collide() {
        let size = 24.0;
        // The point of "9.9": the ink in the columns of its advance sits on the baseline (its
        // bottom within a pixel of it) and stays low (its top well under the digits' middle).
        let (glyphs, _) = layout("9.9", size);
        let (from, to) = (10.0 + glyphs[1].x, 10.0 + glyphs[2].x);
        let dotted = ink("9.9", size);
        let dot: Vec<_> = dotted
            .iter()
            .filter(|p| (p.0 as f32) >= from.ceil() && (p.0 as f32) < to.floor() && p.2 > 0.5)
            .collect();
        assert!(!dot.is_empty(), "no point between the digits");
        let (top, bottom) = (
            dot.iter().map(|p| p.1).min().unwrap(),
            dot.iter().map(|p| p.1).max().unwrap(),
        );
        assert!((99..=100).contains(&bottom), "point bottom at {bottom}");
        let cap = metrics(size).cap;
        assert!((top as f32) > 100.0 - cap / 3.0, "point top at {top}");
        // "To": the o tucks under the T's bar (kerning) but its ink never overlaps the T's
        // stem: the o's leftmost ink is right of the stem's right edge.
        let t = ink("T", size);
        let stem_right = t
            .iter()
            .filter(|p| p.1 > 100 - 6 && p.2 > 0.5)
            .map(|p| p.0)
            .max()
            .unwrap();
        let to = ink("To", size);
        let o_left = to
            .iter()
            .filter(|p| p.1 > 100 - 6 && p.0 > stem_right && p.2 > 0.5)
            .map(|p| p.0)
            .min()
            .unwrap();
        assert!(
            o_left > stem_right + 1,
            "o at {o_left}, T stem to {stem_right}"
        );
        // No two neighbouring letters of "Tolkowsky" share a pixel of solid ink: each drawn
        // alone where the line puts it.
        let word = "Tolkowsky";
        let (glyphs, _) = layout(word, size);
        let solid = |c: char, x: f32| {
            let mut v = std::collections::HashSet::new();
            draw(&c.to_string(), size, (10.0 + x, 100.0), |px, py, cov| {
                if cov > 0.5 {
                    v.insert((px, py));
                }
            });
            v
        };
        let inks: Vec<_> = word
            .chars()
            .zip(&glyphs)
            .map(|(c, g)| solid(c, g.x))
            .collect();
        for (k, pair) in inks.windows(2).enumerate() {
            let shared = pair[0].intersection(&pair[1]).count();
            assert_eq!(shared, 0, "letters {k} and {} touch", k + 1);
        }
    }

    #[test]
    fn anchored_text_has_its_capitals_at_the_anchor() {
        // A raster backend over a small buffer: "H" anchored at its top-left corner.
        let (w, h) = (60u32, 40u32);
        let mut buf = vec![255u8; (w * h * 3) as usize];
        {
            let root = TextBackend::raster(BitMapBackend::with_buffer(&mut buf, (w, h)))
                .into_drawing_area();
            let style = ("sans-serif", 20).into_font().color(&BLACK);
            root.draw_text("H", &style, (10, 10)).unwrap();
            root.present().unwrap();
        }
        let dark: Vec<(u32, u32)> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| buf[((y * w + x) * 3) as usize] < 128)
            .collect();
        let top = dark.iter().map(|p| p.1).min().unwrap();
        let left = dark.iter().map(|p| p.0).min().unwrap();
        assert!((9..=11).contains(&top), "top {top}");
        assert!((10..=13).contains(&left), "left {left}");
    }
}
