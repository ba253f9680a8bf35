//! High-dynamic-range pictures: Radiance `.hdr` (RGBE) and OpenEXR `.exr` read into linear RGB
//! ([`read_hdr`]), and linear RGB written as either ([`write_hdr`]), atomically. Environment
//! maps come in this way (`render --light env:FILE`), and `render --hdr-out` writes the
//! linear picture. The codecs are the `image` crate's (pure Rust; OpenEXR through the `exr`
//! crate).

use crate::error::{Error, Result};
use image::{ImageEncoder, ImageFormat};
use std::path::Path;

/// A linear RGB picture, rows from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct HdrImage {
    /// Pixels per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// `width × height` pixels, row by row from the top, linear RGB.
    pub rgb: Vec<[f32; 3]>,
}

/// Largest picture read or written: 64 million pixels (768 MB as linear RGB in memory).
pub const MAX_PIXELS: usize = 64 << 20;

/// The format of `path` by its extension: `.hdr` (also `.pic`, `.rgbe`) or `.exr`.
fn format_of(path: &Path) -> Option<ImageFormat> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "hdr" | "pic" | "rgbe" => Some(ImageFormat::Hdr),
        "exr" => Some(ImageFormat::OpenExr),
        _ => None,
    }
}

/// Whether `path` names a file [`read_hdr`] reads and [`write_hdr`] writes (by extension).
pub fn is_hdr_path(path: &Path) -> bool {
    format_of(path).is_some()
}

/// Read a Radiance `.hdr` or OpenEXR `.exr` file (by extension) as linear RGB. A missing,
/// unreadable or malformed file, or one with a non-finite or negative value, is an error
/// naming the file.
pub fn read_hdr(path: &Path) -> Result<HdrImage> {
    let shown = path.display().to_string();
    let format = format_of(path).ok_or_else(|| {
        Error::invalid(
            &shown,
            "is neither a Radiance .hdr nor an OpenEXR .exr file (by its extension)",
        )
    })?;
    let bytes = super::read_bytes(path)?;
    decode_hdr(&bytes, format == ImageFormat::OpenExr, &shown)
}

/// Decode the bytes of a Radiance `.hdr` (`exr` false) or OpenEXR `.exr` file; errors name
/// `name`.
pub fn decode_hdr(bytes: &[u8], exr: bool, name: &str) -> Result<HdrImage> {
    let format = if exr {
        ImageFormat::OpenExr
    } else {
        ImageFormat::Hdr
    };
    let what = if exr { "OpenEXR" } else { "Radiance HDR" };
    // The decoders return errors for the malformed files we know of; a panic inside one is
    // turned into the same one-line error.
    let decoded = std::panic::catch_unwind(|| image::load_from_memory_with_format(bytes, format))
        .map_err(|_| Error::parse(name, format!("not a readable {what} file")))?
        .map_err(|e| {
            let msg = e.to_string().replace('\n', " ");
            Error::parse(name, format!("not a readable {what} file: {msg}"))
        })?;
    let (width, height) = (decoded.width() as usize, decoded.height() as usize);
    if width == 0 || height == 0 || width.saturating_mul(height) > MAX_PIXELS {
        return Err(Error::invalid(
            name,
            format!("{width} × {height} pixels; allowed 1 to {MAX_PIXELS} pixels"),
        ));
    }
    let buf = decoded.into_rgb32f();
    let mut rgb = Vec::with_capacity(width * height);
    for (k, p) in buf.pixels().enumerate() {
        let c = p.0;
        if !c.iter().all(|v| v.is_finite() && *v >= 0.0) {
            return Err(Error::invalid(
                name,
                format!(
                    "pixel ({}, {}) is {:?}: radiance must be finite and not negative",
                    k % width,
                    k / width,
                    c
                ),
            ));
        }
        rgb.push(c);
    }
    Ok(HdrImage { width, height, rgb })
}

/// Write `img` to `path` as OpenEXR (32-bit float RGB) or Radiance `.hdr` (RGBE), by
/// extension, atomically (a temporary file renamed).
pub fn write_hdr(path: &Path, img: &HdrImage) -> Result<()> {
    let shown = path.display().to_string();
    let format = format_of(path).ok_or_else(|| {
        Error::invalid(
            &shown,
            "must end in .exr or .hdr (the linear picture is OpenEXR or Radiance HDR)",
        )
    })?;
    let bytes = encode_hdr(img, format == ImageFormat::OpenExr)
        .map_err(|e| Error::io(&shown, e.replace('\n', " ")))?;
    super::write_atomic(path, &bytes)
}

/// The bytes of `img` as OpenEXR (`exr`) or Radiance `.hdr`.
pub fn encode_hdr(img: &HdrImage, exr: bool) -> std::result::Result<Vec<u8>, String> {
    let (w, h) = (img.width, img.height);
    if w == 0 || h == 0 || img.rgb.len() != w * h || w * h > MAX_PIXELS {
        return Err(format!(
            "a {w} × {h} picture needs {} pixels, has {}",
            w * h,
            img.rgb.len()
        ));
    }
    let mut out = std::io::Cursor::new(Vec::new());
    if exr {
        let raw: Vec<u8> = img
            .rgb
            .iter()
            .flat_map(|p| p.iter().flat_map(|v| v.to_le_bytes()))
            .collect();
        // The encoder takes native-endian f32 bytes.
        let raw: Vec<u8> = if cfg!(target_endian = "little") {
            raw
        } else {
            img.rgb
                .iter()
                .flat_map(|p| p.iter().flat_map(|v| v.to_ne_bytes()))
                .collect()
        };
        image::codecs::openexr::OpenExrEncoder::new(&mut out)
            .write_image(&raw, w as u32, h as u32, image::ColorType::Rgb32F)
            .map_err(|e| e.to_string())?;
    } else {
        let px: Vec<image::Rgb<f32>> = img.rgb.iter().map(|&c| image::Rgb(c)).collect();
        image::codecs::hdr::HdrEncoder::new(&mut out)
            .encode(&px, w, h)
            .map_err(|e| e.to_string())?;
    }
    Ok(out.into_inner())
}
