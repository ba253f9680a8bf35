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
    // turned into the same one-line error. (A Radiance file through `image`'s generic
    // decoding comes out tone-mapped to 8 bits: its own decoder keeps the radiance.)
    let bad = |msg: String| Error::parse(name, format!("not a readable {what} file{msg}"));
    let decoded = std::panic::catch_unwind(
        || -> std::result::Result<(usize, usize, Vec<[f32; 3]>), String> {
            if exr {
                let img = image::load_from_memory_with_format(bytes, format)
                    .map_err(|e| e.to_string())?;
                let (w, h) = (img.width() as usize, img.height() as usize);
                let px = img.into_rgb32f().pixels().map(|p| p.0).collect();
                Ok((w, h, px))
            } else {
                let dec = image::codecs::hdr::HdrDecoder::new(std::io::Cursor::new(bytes))
                    .map_err(|e| e.to_string())?;
                let m = dec.metadata();
                let px = dec.read_image_hdr().map_err(|e| e.to_string())?;
                Ok((
                    m.width as usize,
                    m.height as usize,
                    px.into_iter().map(|p| p.0).collect(),
                ))
            }
        },
    )
    .map_err(|_| bad(String::new()))?
    .map_err(|e| bad(format!(": {}", e.replace('\n', " "))))?;
    let (width, height, pixels) = decoded;
    if width == 0
        || height == 0
        || width.saturating_mul(height) > MAX_PIXELS
        || pixels.len() != width * height
    {
        return Err(Error::invalid(
            name,
            format!("{width} × {height} pixels; allowed 1 to {MAX_PIXELS} pixels"),
        ));
    }
    let mut rgb = Vec::with_capacity(width * height);
    for (k, c) in pixels.into_iter().enumerate() {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A Radiance file written here byte by byte (flat RGBE scanlines, values RGBE holds
    /// exactly) and an OpenEXR file written by [`write_hdr`] read back to the same radiances;
    /// the Radiance writer's output reads back within RGBE's precision.
    #[test]
    fn files_read_back_to_the_same_radiances() {
        let dir = tempfile::tempdir().unwrap();
        let (w, h) = (5usize, 3usize);
        // Values m · 2^(e − 136) with an 8-bit mantissa m: exact in RGBE.
        let px: Vec<[f32; 3]> = (0..w * h)
            .map(|k| {
                let e = 120 + (k % 9) as i32;
                let m = [17 + k as u32 * 3, 200 - k as u32 * 5, 64 + k as u32];
                let s = 2f32.powi(e - 136);
                [m[0] as f32 * s, m[1] as f32 * s, m[2] as f32 * s]
            })
            .collect();
        let mut bytes =
            format!("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {h} +X {w}\n").into_bytes();
        for (k, p) in px.iter().enumerate() {
            let e = 120 + (k % 9) as i32;
            let s = 2f32.powi(136 - e);
            bytes.extend(p.iter().map(|v| (v * s).round() as u8));
            bytes.push(e as u8);
        }
        let hdr = dir.path().join("sky.hdr");
        std::fs::write(&hdr, &bytes).unwrap();
        let got = read_hdr(&hdr).unwrap();
        assert_eq!((got.width, got.height), (w, h));
        assert_eq!(got.rgb, px);
        // OpenEXR: 32-bit floats, any values.
        let img = HdrImage {
            width: 7,
            height: 4,
            rgb: (0..28)
                .map(|k| [k as f32 * 0.37, 1e4 / (k + 1) as f32, (k as f32).sqrt()])
                .collect(),
        };
        let exr = dir.path().join("sky.exr");
        write_hdr(&exr, &img).unwrap();
        assert_eq!(read_hdr(&exr).unwrap(), img);
        // The Radiance writer: within RGBE's 8-bit mantissa.
        let out = dir.path().join("out.hdr");
        write_hdr(&out, &img).unwrap();
        let back = read_hdr(&out).unwrap();
        for (a, b) in back.rgb.iter().zip(&img.rgb) {
            let m = b.iter().fold(0f32, |x, &y| x.max(y));
            for c in 0..3 {
                assert!((a[c] - b[c]).abs() <= m / 128.0, "{a:?} {b:?}");
            }
        }
    }

    /// A malformed, truncated or misnamed file is a one-line error naming it; nothing panics.
    #[test]
    fn malformed_files_are_one_line_errors() {
        let dir = tempfile::tempdir().unwrap();
        let good = {
            let img = HdrImage {
                width: 4,
                height: 2,
                rgb: vec![[1.0, 2.0, 3.0]; 8],
            };
            (
                encode_hdr(&img, true).unwrap(),
                encode_hdr(&img, false).unwrap(),
            )
        };
        let cases: Vec<(&str, Vec<u8>)> = vec![
            ("garbage.hdr", b"not a picture at all".to_vec()),
            ("garbage.exr", b"not a picture at all".to_vec()),
            ("cut.exr", good.0[..good.0.len() / 2].to_vec()),
            ("cut.hdr", good.1[..good.1.len() - 5].to_vec()),
            ("empty.exr", Vec::new()),
            ("sky.png", good.0.clone()),
        ];
        for (name, bytes) in cases {
            let p = dir.path().join(name);
            std::fs::write(&p, &bytes).unwrap();
            let e = read_hdr(&p).unwrap_err().to_string();
            assert!(e.contains(name), "{name}: {e}");
            assert!(!e.contains('\n'), "{name}: {e}");
        }
        let missing = dir.path().join("missing.exr");
        let e = read_hdr(&missing).unwrap_err().to_string();
        assert!(
            e.contains("missing.exr") && e.contains("no such file"),
            "{e}"
        );
        // A negative radiance is refused.
        let bad = HdrImage {
            width: 2,
            height: 1,
            rgb: vec![[1.0, -1.0, 0.0], [0.0; 3]],
        };
        let p = dir.path().join("negative.exr");
        std::fs::write(&p, encode_hdr(&bad, true).unwrap()).unwrap();
        let e = read_hdr(&p).unwrap_err().to_string();
        assert!(e.contains("negative.exr") && e.contains("negative"), "{e}");
    }
}
