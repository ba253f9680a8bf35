//! Poses written as text: a tilt `DEG[@AZ]` and a rock `DEG:FRAMES` (the stone rocked about its
//! tilt, one picture per frame), as `facetlab render --tilt` and `--rock` take them.

use super::Tilt;
use crate::error::{Error, Result};
use crate::io::text::{count, number};

/// `DEG` or `DEG@AZ`: a tilt in [−90, 90] degrees toward azimuth AZ in [−360, 360] degrees
/// (default 0); the error names `field`.
///
/// ```
/// use facetlab::render::pose::parse_tilt;
/// let t = parse_tilt("--tilt", "10@45").unwrap();
/// assert_eq!((t.tilt_deg, t.azimuth_deg), (10.0, 45.0));
/// assert!(parse_tilt("--tilt", "91").is_err());
/// ```
pub fn parse_tilt(field: &str, s: &str) -> Result<Tilt> {
    let bad = || {
        Error::invalid(
            field,
            format!("`{s}` is not allowed; give DEG or DEG@AZ: a tilt in [-90, 90] degrees toward azimuth AZ in [-360, 360] degrees (10@45)"),
        )
    };
    let (t, az) = match s.split_once('@') {
        Some((t, az)) => (t, az),
        None => (s, "0"),
    };
    let tilt_deg = number(field, t, -90.0, 90.0, "degrees").map_err(|_| bad())?;
    let azimuth_deg = number(field, az, -360.0, 360.0, "degrees").map_err(|_| bad())?;
    Ok(Tilt {
        tilt_deg,
        azimuth_deg,
    })
}

/// `DEG:FRAMES`: a rock of DEG in (0, 60] degrees over FRAMES in 2..=240 frames, as
/// `(DEG, FRAMES)`; the error names `field`.
///
/// ```
/// use facetlab::render::pose::parse_rock;
/// assert_eq!(parse_rock("--rock", "15:24").unwrap(), (15.0, 24));
/// assert!(parse_rock("--rock", "0:24").is_err());
/// ```
pub fn parse_rock(field: &str, s: &str) -> Result<(f64, usize)> {
    let bad = || {
        Error::invalid(
            field,
            format!("`{s}` is not allowed; give DEG:FRAMES with DEG in (0, 60] degrees and FRAMES in 2..=240 (15:24)"),
        )
    };
    let (d, n) = s.split_once(':').ok_or_else(bad)?;
    let deg = number(field, d, 0.0, 60.0, "degrees").map_err(|_| bad())?;
    if deg <= 0.0 {
        return Err(bad());
    }
    let n = count(field, n, 2, 240).map_err(|_| bad())? as usize;
    Ok((deg, n))
}

/// The pose of frame `k` of a rock `(deg, frames)` about `base`: tilted
/// `deg·sin(2πk/frames)` more toward the same azimuth.
pub fn rocked(base: Tilt, (deg, frames): (f64, usize), k: usize) -> Tilt {
    Tilt {
        tilt_deg: base.tilt_deg + deg * (std::f64::consts::TAU * k as f64 / frames as f64).sin(),
        azimuth_deg: base.azimuth_deg,
    }
}
