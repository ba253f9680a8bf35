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

/// Largest picture read or written: 64 Mi pixels, 67108864 (768 MiB as linear RGB in
/// memory). A map's header is checked against it, and against the bytes after the header
/// ([`min_scanline_bytes`], [`MAX_EXR_RATIO`]), before any of its pixels is allocated.
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
/// `name`. The size the header states is checked before any pixel is allocated: at most
/// [`MAX_PIXELS`], and no more than the bytes after the header can hold (for Radiance
/// [`min_scanline_bytes`] per row, for OpenEXR [`MAX_EXR_RATIO`]).
pub fn decode_hdr(bytes: &[u8], exr: bool, name: &str) -> Result<HdrImage> {
    let (width, height, pixels) = if exr {
        decode_exr(bytes, name)?
    } else {
        decode_radiance(bytes, name)?
    };
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

/// Refuse a stated size of `width × height` pixels beyond [`MAX_PIXELS`] (or empty).
fn check_size(width: u64, height: u64, name: &str) -> Result<usize> {
    match width.checked_mul(height) {
        Some(n) if n >= 1 && n <= MAX_PIXELS as u64 => Ok(n as usize),
        _ => Err(Error::invalid(
            name,
            format!(
                "{width} × {height} pixels; allowed 1 to {MAX_PIXELS} pixels ({} MiB as linear RGB)",
                (MAX_PIXELS * 12) >> 20
            ),
        )),
    }
}

/// The fewest bytes a Radiance scanline of `width` pixels can take, whatever its encoding:
/// 4 + 4k, k the least with 256^k ≥ `width`. A flat or old-style run-length scanline starts
/// with one whole RGBE pixel (4 bytes) and repeats the pixel before with 4-byte markers; `k`
/// markers in a row repeat it at most 255 · (1 + 256 + … + 256^(k−1)) = 256^k − 1 times. A
/// new-style scanline (8 to 32767 pixels: k ≤ 2) takes more: a 4-byte marker and four
/// channels of at least 2 bytes per run of at most 127 equal values, 12 bytes or more.
/// So a map of `H` rows needs `H` times this after its header (16 bytes a row at 100000
/// pixels: the 58-byte header stating 100000 × 100000 is refused, not allocated).
pub fn min_scanline_bytes(width: u64) -> u64 {
    let mut k = 0u64;
    while 256u128.pow(k as u32) < u128::from(width) {
        k += 1;
    }
    4 + 4 * k
}

/// A Radiance (RGBE) file's pixels: the `#?` signature line, header lines up to an empty
/// line (`FORMAT` must be `32-bit_rle_rgbe`), the size line `-Y H +X W`, and `H` scanlines,
/// each flat, old-style run-length or new-style run-length encoded. RGBE (r, g, b, e) is
/// (r, g, b) · 2^(e − 136), 0 when e = 0.
fn decode_radiance(bytes: &[u8], name: &str) -> Result<(usize, usize, Vec<[f32; 3]>)> {
    let bad = |msg: String| Error::parse(name, format!("not a readable Radiance HDR file: {msg}"));
    let mut at = 0usize;
    let mut line = || -> Option<&[u8]> {
        let rest = bytes.get(at..).filter(|r| !r.is_empty())?;
        let end = rest.iter().position(|&b| b == b'\n');
        at += end.map_or(rest.len(), |e| e + 1);
        Some(&rest[..end.unwrap_or(rest.len())])
    };
    if !line().is_some_and(|l| l.starts_with(b"#?")) {
        return Err(bad("no `#?RADIANCE` signature on its first line".into()));
    }
    loop {
        let Some(l) = line() else {
            return Err(bad("the header ends before its empty line".into()));
        };
        if l.is_empty() {
            break;
        }
        let l = String::from_utf8_lossy(l);
        if let Some(v) = l.strip_prefix("FORMAT=") {
            if v.trim() != "32-bit_rle_rgbe" {
                let v: String = v.trim().chars().take(24).collect();
                return Err(bad(format!(
                    "format {v:?}; the reader takes 32-bit_rle_rgbe"
                )));
            }
        }
    }
    let size = line().map(String::from_utf8_lossy).unwrap_or_default();
    let words: Vec<&str> = size.split_whitespace().collect();
    let (height, width) = match words[..] {
        ["-Y", h, "+X", w] => match (h.parse::<u64>(), w.parse::<u64>()) {
            (Ok(h), Ok(w)) => (h, w),
            _ => {
                return Err(bad(format!(
                    "size line {:?}; e.g. `-Y 512 +X 1024`",
                    short(&size)
                )))
            }
        },
        _ => {
            return Err(bad(format!(
                "size line {:?}; the reader takes rows from the top, `-Y H +X W`",
                short(&size)
            )))
        }
    };
    let count = check_size(width, height, name)?;
    let left = (bytes.len() - at) as u64;
    let need = min_scanline_bytes(width).saturating_mul(height);
    if need > left {
        return Err(bad(format!(
            "{width} × {height} pixels need at least {need} bytes of scanlines, the file has {left} after its header"
        )));
    }
    let (w, mut data) = (width as usize, &bytes[at..]);
    let mut row = vec![[0u8; 4]; w];
    let mut out = Vec::with_capacity(count);
    for y in 0..height {
        read_scanline(&mut data, &mut row).map_err(|m| bad(format!("scanline {y}: {m}")))?;
        out.extend(row.iter().map(|&[r, g, b, e]| {
            if e == 0 {
                [0.0; 3]
            } else {
                let s = f32::exp2(f32::from(e) - 136.0);
                [f32::from(r) * s, f32::from(g) * s, f32::from(b) * s]
            }
        }));
    }
    Ok((w, height as usize, out))
}

/// At most 40 characters of `s`, for an error line.
fn short(s: &str) -> String {
    s.chars().take(40).collect()
}

/// Take `n` bytes from the front of `data`.
fn take<'a>(data: &mut &'a [u8], n: usize) -> std::result::Result<&'a [u8], String> {
    if data.len() < n {
        return Err("the file ends inside it".into());
    }
    let (a, b) = data.split_at(n);
    *data = b;
    Ok(a)
}

/// Decode one scanline of `row.len()` RGBE pixels from the front of `data`.
fn read_scanline(data: &mut &[u8], row: &mut [[u8; 4]]) -> std::result::Result<(), String> {
    let w = row.len();
    let first: [u8; 4] = take(data, 4)?.try_into().unwrap_or_default();
    if (8..=0x7fff).contains(&w) && first[0] == 2 && first[1] == 2 && first[2] < 128 {
        let stated = usize::from(first[2]) << 8 | usize::from(first[3]);
        if stated != w {
            return Err(format!(
                "its run-length marker says {stated} pixels, not {w}"
            ));
        }
        for c in 0..4 {
            let mut x = 0;
            while x < w {
                let code = usize::from(take(data, 1)?[0]);
                let (n, run) = if code > 128 {
                    (code - 128, true)
                } else {
                    (code, false)
                };
                if x + n > w {
                    return Err(format!("a run past its {w} pixels"));
                }
                if run {
                    let v = take(data, 1)?[0];
                    row[x..x + n].iter_mut().for_each(|p| p[c] = v);
                } else {
                    let vs = take(data, n)?;
                    row[x..x + n]
                        .iter_mut()
                        .zip(vs)
                        .for_each(|(p, &v)| p[c] = v);
                }
                x += n;
            }
        }
        return Ok(());
    }
    // Flat or old-style run-length: (1, 1, 1, n) repeats the pixel before n << shift times,
    // the shift growing by 8 with each marker in a row.
    let mut pixel = first;
    let (mut x, mut shift) = (0usize, 0u32);
    loop {
        if pixel[..3] == [1, 1, 1] {
            if x == 0 {
                return Err("it starts with a run-length marker".into());
            }
            let n = (u64::from(pixel[3]) << shift) as usize;
            if shift > 24 || x + n > w {
                return Err(format!("a run past its {w} pixels"));
            }
            let prev = row[x - 1];
            row[x..x + n].fill(prev);
            x += n;
            shift += 8;
        } else {
            row[x] = pixel;
            x += 1;
            shift = 0;
        }
        if x == w {
            return Ok(());
        }
        pixel = take(data, 4)?.try_into().unwrap_or_default();
    }
}

/// The most bytes of pixels an OpenEXR file may unpack from one byte of its pixel data:
/// deflate (ZIP, ZIPS) packs at most about 1032 bytes into one (PXR24, which also drops a
/// float's lowest 8 bits, 1376), run-length (RLE) 64, PIZ's Huffman runs about 450, B44 about
/// 11; an uncompressed file unpacks 1 from 1. A header whose pixels would need more is refused
/// before they are allocated.
pub const MAX_EXR_RATIO: u64 = 2048;

/// An OpenEXR file's RGB pixels (the first layer with R, G and B channels, its largest
/// resolution, inside its display window), after its header's size is checked: every
/// layer's data window and the display window at most [`MAX_PIXELS`], and the layer's
/// unpacked pixels at most [`MAX_EXR_RATIO`] times the file's bytes (once if uncompressed).
fn decode_exr(bytes: &[u8], name: &str) -> Result<(usize, usize, Vec<[f32; 3]>)> {
    let bad = |msg: String| {
        Error::parse(
            name,
            format!("not a readable OpenEXR file: {}", msg.replace('\n', " ")),
        )
    };
    let meta =
        exr::meta::MetaData::read_from_buffered(bytes, false).map_err(|e| bad(e.to_string()))?;
    for h in &meta.headers {
        let (w, ht) = (h.layer_size.width() as u64, h.layer_size.height() as u64);
        check_size(w, ht, name)?;
        let d = h.shared_attributes.display_window.size;
        check_size(d.width() as u64, d.height() as u64, name)?;
        let per_pixel: u64 = h
            .channels
            .list
            .iter()
            .map(|c| c.sample_type.bytes_per_sample() as u64)
            .sum();
        let ratio = if h.compression == exr::compression::Compression::Uncompressed {
            1
        } else {
            MAX_EXR_RATIO
        };
        let unpacked = w * ht * per_pixel;
        let file = bytes.len() as u64;
        if unpacked > file.saturating_mul(ratio) {
            return Err(bad(format!(
                "{w} × {ht} pixels of {per_pixel} bytes ({unpacked} bytes, {:?}) cannot come from a file of {file} bytes",
                h.compression
            )));
        }
    }
    // The codec returns errors for the malformed files we know of (the fuzz tests mutate
    // files to find others); should it panic all the same, the read is still a one-line
    // error, not the end of the program or of a server's worker.
    let (w, h, px) = std::panic::catch_unwind(|| {
        let img = image::load_from_memory_with_format(bytes, ImageFormat::OpenExr)
            .map_err(|e| bad(e.to_string()))?;
        let (w, h) = (img.width() as usize, img.height() as usize);
        let px: Vec<[f32; 3]> = img.into_rgb32f().pixels().map(|p| p.0).collect();
        Ok((w, h, px))
    })
    .map_err(|_| bad("the OpenEXR decoder failed on it".into()))??;
    if w == 0 || h == 0 || px.len() != w * h {
        return Err(bad(format!("{w} × {h} pixels, {} decoded", px.len())));
    }
    Ok((w, h, px))
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

    /// The Radiance header of a `w × h` map.
    fn radiance_header(w: u64, h: u64) -> Vec<u8> {
        format!("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {h} +X {w}\n").into_bytes()
    }

    /// Issue 51: a header stating more pixels than the limit, or than the bytes after it can
    /// hold, is refused before its pixels are allocated, in one line giving the reason (the
    /// header-only 100000² file took 7.7 GB or aborted; 2³¹−1 square panicked with "capacity
    /// overflow"; 8192 × 8193 with 100 bytes took 800 MB).
    #[test]
    fn a_huge_stated_size_is_refused_before_allocating() {
        let big = radiance_header(100_000, 100_000);
        let e = decode_hdr(&big, false, "big.hdr").unwrap_err().to_string();
        assert!(
            e.starts_with("big.hdr: ")
                && e.contains("100000 × 100000 pixels; allowed 1 to 67108864 pixels (768 MiB"),
            "{e}"
        );
        let e = decode_hdr(&radiance_header(2147483647, 2147483647), false, "huge.hdr")
            .unwrap_err()
            .to_string();
        assert!(e.contains("2147483647 × 2147483647 pixels; allowed"), "{e}");
        let mut b = radiance_header(8193, 8192);
        b.extend([7u8; 100]);
        let e = decode_hdr(&b, false, "b.hdr").unwrap_err().to_string();
        assert!(e.contains("8193 × 8192 pixels") && !e.contains('\n'), "{e}");
        // Within the pixel limit but beyond the bytes: 4096² needs 12 bytes a row at least.
        let mut b = radiance_header(4096, 4096);
        b.extend(vec![0u8; 4096 * 12 - 1]);
        let e = decode_hdr(&b, false, "short.hdr").unwrap_err().to_string();
        assert!(
            e.contains("need at least 49152 bytes of scanlines, the file has 49151"),
            "{e}"
        );
        for (w, h) in [(0, 5), (5, 0)] {
            let e = decode_hdr(&radiance_header(w, h), false, "z.hdr")
                .unwrap_err()
                .to_string();
            assert!(e.contains("allowed 1 to"), "{e}");
        }
    }

    /// The bound is honest: for each width, a scanline of exactly [`min_scanline_bytes`]
    /// bytes exists and decodes (a whole pixel and a chain of old-style run markers, or
    /// new-style runs of 127), so no readable file is refused by it.
    #[test]
    fn the_fewest_bytes_a_scanline_takes_are_reachable() {
        for w in [
            1u64, 2, 7, 8, 127, 200, 255, 256, 257, 4000, 32767, 65536, 65537, 100_000,
        ] {
            // Old style: pixel, then markers repeating it: counts n_j << 8j, greedy from the top.
            let mut old = vec![10u8, 20, 30, 130];
            let left = w - 1;
            let mut k = 0;
            while 256u64.pow(k) <= left {
                k += 1;
            }
            // Markers j = 0..k with digits of `left` in base 256 (a 0 digit repeats 0 times).
            for j in 0..k {
                old.extend([1, 1, 1, ((left >> (8 * j)) & 255) as u8]);
            }
            let mut new = vec![2u8, 2, (w >> 8) as u8, (w & 255) as u8];
            for _ in 0..4 {
                let mut x = 0;
                while x < w {
                    let n = (w - x).min(127);
                    new.extend([128 + n as u8, 77]);
                    x += n;
                }
            }
            let shortest = if (8..=0x7fff).contains(&w) && new.len() < old.len() {
                &new
            } else {
                &old
            };
            assert_eq!(shortest.len() as u64, min_scanline_bytes(w), "width {w}");
            let mut file = radiance_header(w, 2);
            file.extend(shortest.iter().chain(shortest.iter()));
            let img = decode_hdr(&file, false, "m.hdr").unwrap();
            assert_eq!((img.width, img.height), (w as usize, 2));
            let first = img.rgb[0];
            assert!(img.rgb.iter().all(|p| *p == first), "width {w}");
            // One byte fewer is refused before decoding.
            file.pop();
            assert!(decode_hdr(&file, false, "m.hdr").is_err());
        }
    }

    /// An OpenEXR header stating a huge picture is refused before its pixels are allocated:
    /// its windows patched in a file written here.
    #[test]
    fn a_huge_exr_header_is_refused_before_allocating() {
        let img = HdrImage {
            width: 4,
            height: 2,
            rgb: vec![[1.0, 2.0, 3.0]; 8],
        };
        let good = encode_hdr(&img, true).unwrap();
        let patch = |side: i32| {
            let mut b = good.clone();
            for key in [&b"dataWindow\0box2i\0"[..], &b"displayWindow\0box2i\0"[..]] {
                let at = b.windows(key.len()).position(|w| w == key).unwrap() + key.len() + 4;
                b[at + 8..at + 12].copy_from_slice(&(side - 1).to_le_bytes());
                b[at + 12..at + 16].copy_from_slice(&(side - 1).to_le_bytes());
            }
            b
        };
        let e = decode_hdr(&patch(100_000), true, "big.exr")
            .unwrap_err()
            .to_string();
        assert!(e.contains("100000 × 100000 pixels; allowed 1 to"), "{e}");
        let e = decode_hdr(&patch(4000), true, "wide.exr")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("wide.exr: not a readable OpenEXR file") && !e.contains('\n'),
            "{e}"
        );
        assert_eq!(decode_hdr(&good, true, "good.exr").unwrap(), img);
    }

    /// The map readers under a seeded, bounded fuzz: Radiance files (flat, old-style and
    /// new-style run-length) and an OpenEXR file, 150 mutations each (flips, deletions,
    /// repeats, hostile numbers in the header, truncation). Each read is one line naming the
    /// file, not a caught panic, or a picture that writes and reads back at its size.
    #[test]
    fn fuzz_the_map_readers() {
        use rand::{Rng, SeedableRng};
        let img = HdrImage {
            width: 9,
            height: 3,
            rgb: (0..27)
                .map(|k| [k as f32, 0.5, 1e3 / (k + 1) as f32])
                .collect(),
        };
        let mut flat = radiance_header(3, 2);
        flat.extend([9, 9, 9, 130, 1, 1, 1, 2, 50, 60, 70, 128, 1, 1, 1, 2]);
        let seeds: Vec<(bool, Vec<u8>)> = vec![
            (false, encode_hdr(&img, false).unwrap()),
            (false, flat),
            (true, encode_hdr(&img, true).unwrap()),
        ];
        let mut rng = rand::rngs::SmallRng::seed_from_u64(51);
        let (mut read, mut refused) = (0, 0);
        for k in 0..450 {
            let (exr, seed) = &seeds[k % 3];
            let mut b = seed.clone();
            for _ in 0..rng.random_range(1..4) {
                let at = rng.random_range(0..b.len());
                match rng.random_range(0..5) {
                    0 => b[at] = rng.random(),
                    1 => {
                        b.remove(at);
                    }
                    2 => {
                        let t = ["99999", "4294967295", "-1", "1e9", "\n", "\0"]
                            [rng.random_range(0..6)];
                        b.splice(at..at, t.bytes());
                    }
                    3 => {
                        let end = (at + rng.random_range(1..16)).min(b.len());
                        let piece = b[at..end].to_vec();
                        b.splice(at..at, piece);
                    }
                    _ => b.truncate(at.max(1)),
                }
            }
            let name = format!("m{k}");
            match decode_hdr(&b, *exr, &name) {
                Err(e) => {
                    let e = e.to_string();
                    assert!(e.starts_with(&name) && !e.contains('\n'), "{e}");
                    assert!(!e.contains("decoder failed"), "a caught panic: {e}");
                    refused += 1;
                }
                Ok(got) => {
                    read += 1;
                    let again = encode_hdr(&got, *exr).unwrap();
                    let back = decode_hdr(&again, *exr, "again").unwrap();
                    assert_eq!((back.width, back.height), (got.width, got.height));
                }
            }
        }
        assert!(read > 20 && refused > 100, "read {read}, refused {refused}");
    }
}
