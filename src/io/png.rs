//! PNG files: still pictures and animated PNGs (APNG), written atomically.

use super::write_atomic;
use crate::error::{Error, Result};
use std::path::Path;

/// Encode an 8-bit RGB picture (`width × height`, rows from the top, 3 bytes per pixel) as
/// PNG bytes; with more than one frame, an animated PNG that loops forever, each frame shown
/// for `delay_ms`.
pub fn encode_rgb8(width: u32, height: u32, frames: &[&[u8]], delay_ms: u16) -> Result<Vec<u8>> {
    let want = width as usize * height as usize * 3;
    if frames.is_empty() || frames.iter().any(|f| f.len() != want) {
        return Err(Error::invalid(
            "png",
            format!("every frame must have {want} bytes ({width}×{height} RGB)"),
        ));
    }
    let mut out = Vec::new();
    {
        let mut enc = ::png::Encoder::new(&mut out, width, height);
        enc.set_color(::png::ColorType::Rgb);
        enc.set_depth(::png::BitDepth::Eight);
        enc.set_source_srgb(::png::SrgbRenderingIntent::Perceptual);
        // Speed is what the user waits for: the fast level (fdeflate) with the Paeth filter
        // writes an 800² picture of a stone in a small part of the time miniz's best level
        // with adaptive filtering took (45 % of a whole `render` process), for files about
        // 1.5 times as large (tolkowsky's 800² ISO picture: 255 kB against 163 kB).
        enc.set_compression(::png::Compression::Fast);
        enc.set_adaptive_filter(::png::AdaptiveFilterType::NonAdaptive);
        enc.set_filter(::png::FilterType::Paeth);
        let bad = |e: ::png::EncodingError| Error::invalid("png", e.to_string());
        if frames.len() > 1 {
            enc.set_animated(frames.len() as u32, 0).map_err(bad)?;
            enc.set_frame_delay(delay_ms, 1000).map_err(bad)?;
        }
        let mut w = enc.write_header().map_err(bad)?;
        for f in frames {
            w.write_image_data(f).map_err(bad)?;
        }
        w.finish().map_err(bad)?;
    }
    Ok(out)
}

/// [`encode_rgb8`], written to `path` atomically (a temporary file, then a rename).
pub fn write_rgb8(
    path: &Path,
    width: u32,
    height: u32,
    frames: &[&[u8]],
    delay_ms: u16,
) -> Result<()> {
    let bytes = encode_rgb8(width, height, frames, delay_ms)?;
    write_atomic(path, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Still and animated pictures decode back to the same pixels.
    #[test]
    fn round_trip() {
        let (w, h) = (5u32, 3u32);
        let a: Vec<u8> = (0..w * h * 3).map(|i| (i * 7 % 256) as u8).collect();
        let b: Vec<u8> = a.iter().map(|v| 255 - v).collect();
        for frames in [vec![a.as_slice()], vec![a.as_slice(), b.as_slice()]] {
            let bytes = encode_rgb8(w, h, &frames, 50).unwrap();
            let dec = ::png::Decoder::new(std::io::Cursor::new(bytes));
            let mut r = dec.read_info().unwrap();
            let animated = r.info().animation_control().map(|c| c.num_frames);
            assert_eq!(animated, (frames.len() > 1).then_some(frames.len() as u32));
            let mut buf = vec![0; r.output_buffer_size()];
            for f in &frames {
                let info = r.next_frame(&mut buf).unwrap();
                assert_eq!((info.width, info.height), (w, h));
                assert_eq!(&buf[..info.buffer_size()], *f);
            }
        }
        assert!(encode_rgb8(w, h, &[&a[1..]], 0).is_err());
    }
}
