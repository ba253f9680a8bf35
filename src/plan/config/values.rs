//! Reading a plan config's TOML values with errors naming the field.

use crate::error::{shown, Error, Result};

/// A value as a message quotes it: at most 40 characters of its TOML text, one line.
pub(super) fn quote(v: &toml::Value) -> String {
    let t = match v {
        toml::Value::Float(f) => shown(*f),
        other => other.to_string(),
    };
    let mut out: String = t
        .chars()
        .take(40)
        .map(|c| if c.is_control() { '?' } else { c })
        .collect();
    if t.chars().count() > 40 {
        out.push('…');
    }
    out
}

/// A number (an integer or a float) from a TOML value.
pub(super) fn as_number(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Integer(i) => Some(*i as f64),
        toml::Value::Float(f) => Some(*f),
        _ => None,
    }
}

/// A whole number in `lo..=hi` named `field`.
pub(super) fn whole(field: String, v: &toml::Value, lo: u64, hi: u64, what: &str) -> Result<u64> {
    match v {
        toml::Value::Integer(i) if *i >= 0 && (lo..=hi).contains(&(*i as u64)) => Ok(*i as u64),
        _ => Err(Error::invalid(
            field,
            format!(
                "{} is not allowed; give {what}, a whole number from {lo} to {hi}",
                quote(v)
            ),
        )),
    }
}

/// A number in `[lo, hi]` named `field`.
pub(super) fn ranged(field: String, v: &toml::Value, lo: f64, hi: f64, what: &str) -> Result<f64> {
    match as_number(v) {
        Some(x) if x.is_finite() && x >= lo && x <= hi => Ok(x),
        _ => Err(Error::invalid(
            field,
            format!(
                "{} is not allowed; give {what}, a number from {} to {}",
                quote(v),
                shown(lo),
                shown(hi)
            ),
        )),
    }
}

/// A string named `field`.
pub(super) fn string<'v>(field: String, v: &'v toml::Value, example: &str) -> Result<&'v str> {
    v.as_str().ok_or_else(|| {
        Error::invalid(
            field,
            format!("{} is not allowed; give a string, e.g. {example}", quote(v)),
        )
    })
}
