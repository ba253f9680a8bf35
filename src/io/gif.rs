//! Animated GIF files (a turntable's frames, for places that show GIF but not animated
//! PNG), written atomically: each frame's 8-bit RGB quantised to its own 256-colour palette
//! (NeuQuant, the `gif` crate's), looping forever.

use super::write_atomic;
use crate::error::{Error, Result};
use std::path::Path;

/// Encode 8-bit RGB frames (`width × height`, rows from the top, 3 bytes per pixel) as an
/// animated GIF that loops forever, each frame shown for `delay_ms` (rounded to GIF's
/// hundredths of a second, at least 2).
pub fn encode_rgb8(width: u16, height: u16, frames: &[&[u8]], delay_ms: u16) -> Result<Vec<u8>> {
    let want = width as usize * height as usize * 3;
    if frames.is_empty() || frames.iter().any(|f| f.len() != want) || want == 0 {
        return Err(Error::invalid(
            "gif",
            format!("every frame must have {want} bytes ({width}×{height} RGB)"),
        ));
    }
    let bad = |e: ::gif::EncodingError| Error::invalid("gif", e.to_string());
    let mut out = Vec::new();
    {
        let mut enc = ::gif::Encoder::new(&mut out, width, height, &[]).map_err(bad)?;
        enc.set_repeat(::gif::Repeat::Infinite).map_err(bad)?;
        for f in frames {
            // Speed 10: the quantiser's default trade of quality for time.
            let mut frame = ::gif::Frame::from_rgb_speed(width, height, f, 10);
            frame.delay = (delay_ms / 10).max(2);
            enc.write_frame(&frame).map_err(bad)?;
        }
    }
    Ok(out)
}

/// [`encode_rgb8`], written to `path` atomically.
pub fn write_rgb8(
    path: &Path,
    width: u16,
    height: u16,
    frames: &[&[u8]],
    delay_ms: u16,
) -> Result<()> {
    let bytes = encode_rgb8(width, height, frames, delay_ms)
        .map_err(|e| e.context(&path.display().to_string()))?;
    write_atomic(path, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Frames decode back with their size, count and delay, and flat colours come back
    /// within the quantiser's error.
    #[test]
    fn round_trip() {
        let (w, h) = (6u16, 4u16);
        let a: Vec<u8> = (0..w as usize * h as usize)
            .flat_map(|_| [200, 40, 10])
            .collect();
        let b: Vec<u8> = (0..w as usize * h as usize)
            .flat_map(|_| [10, 90, 220])
            .collect();
        let bytes = encode_rgb8(w, h, &[&a, &b, &a], 100).unwrap();
        let mut opts = ::gif::DecodeOptions::new();
        opts.set_color_output(::gif::ColorOutput::RGBA);
        let mut dec = opts.read_info(std::io::Cursor::new(bytes)).unwrap();
        let mut n = 0;
        while let Some(f) = dec.read_next_frame().unwrap() {
            assert_eq!((f.width, f.height, f.delay), (w, h, 10));
            let want = if n % 2 == 0 { &a } else { &b };
            for (px, q) in f.buffer.chunks_exact(4).zip(want.chunks_exact(3)) {
                for c in 0..3 {
                    assert!((px[c] as i32 - q[c] as i32).abs() <= 8, "{px:?} {q:?}");
                }
            }
            n += 1;
        }
        assert_eq!(n, 3);
        assert!(encode_rgb8(w, h, &[&a[1..]], 0).is_err());
    }
}
