//! Numbers read from text (command-line flags, request fields): a value in a range or a whole
//! number, each error one line naming the field and what is allowed.

use crate::error::{Error, Result};

/// A number in `[lo, hi]` read from `s`; `what` describes it in the error, which names
/// `field`.
///
/// ```
/// use facetlab::io::text::number;
/// assert_eq!(number("angle", " 30 ", 0.0, 180.0, "an angle").unwrap(), 30.0);
/// let e = number("angle", "200", 0.0, 180.0, "an angle").unwrap_err().to_string();
/// assert_eq!(e, "angle: `200` is not allowed; give an angle in [0, 180]");
/// ```
pub fn number(field: &str, s: &str, lo: f64, hi: f64, what: &str) -> Result<f64> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= lo && v <= hi => Ok(v),
        _ => Err(Error::invalid(
            field,
            format!("`{s}` is not allowed; give {what} in [{lo}, {hi}]"),
        )),
    }
}

/// A whole number in `min..=max` read from `s`; `2e7` and `20_000_000` are accepted.
///
/// ```
/// use facetlab::io::text::count;
/// assert_eq!(count("photons", "2e7", 1, u64::MAX).unwrap(), 20_000_000);
/// let e = count("top", "0", 1, 50).unwrap_err().to_string();
/// assert_eq!(e, "top: `0` is not allowed; give a whole number from 1 to 50");
/// ```
pub fn count(field: &str, s: &str, min: u64, max: u64) -> Result<u64> {
    let t = s.trim().replace('_', "");
    let v = match t.parse::<u64>() {
        Ok(v) => Some(v),
        Err(_) => match t.parse::<f64>() {
            // `u64::MAX as f64` is 2^64, one past the largest u64: below it only.
            Ok(f) if f.is_finite() && f >= 0.0 && f.fract() == 0.0 && f < u64::MAX as f64 => {
                Some(f as u64)
            }
            _ => None,
        },
    };
    match v {
        Some(v) if (min..=max).contains(&v) => Ok(v),
        _ => {
            // Spellings of large numbers only where large numbers are allowed.
            let forms = if max >= 20_000_000 {
                " (2e7 and 20_000_000 work)"
            } else {
                ""
            };
            Err(Error::invalid(
                field,
                format!("`{s}` is not allowed; give a whole number from {min} to {max}{forms}"),
            ))
        }
    }
}
