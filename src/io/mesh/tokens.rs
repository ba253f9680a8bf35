//! Tokens of a mesh file: numbers with their significant digits, tokens quoted in messages,
//! names written as tokens, and errors located in the file.

use crate::error::Error;

/// Parse a decimal number and count its significant digits.
pub(super) fn number(tok: &str) -> Option<(f64, u32)> {
    let v: f64 = tok.parse().ok()?;
    let mantissa = tok.split(['e', 'E']).next().unwrap_or("");
    let digits = mantissa.trim_start_matches(['+', '-', '0', '.']);
    let sig = digits.chars().filter(|c| c.is_ascii_digit()).count() as u32;
    Some((v, sig))
}

/// Relative rounding error of text written with at most `sig` significant digits.
pub(super) fn text_noise(max_sig: u32) -> f64 {
    0.5 * 10f64.powi(1 - max_sig.clamp(1, 30) as i32)
}

/// Two significant digits, for messages.
pub(super) fn sig2(x: f64) -> String {
    if !(x.is_finite() && x > 0.0) {
        return format!("{x}");
    }
    // The exponent after rounding to two digits (9.96 → 1.0e1).
    let e = format!("{x:.1e}");
    let exp: i32 = e
        .split('e')
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    let dec = (1 - exp).max(0) as usize;
    format!("{x:.dec$}")
}

/// A token from the file as shown in a message: at most 24 characters, control characters and
/// undecodable bytes as `?`.
pub(super) fn quote(tok: &str) -> String {
    let mut out: String = tok
        .chars()
        .take(24)
        .map(|c| {
            if c.is_control() || c == '\u{FFFD}' {
                '?'
            } else {
                c
            }
        })
        .collect();
    if tok.chars().count() > 24 {
        out.push('…');
    }
    out
}

pub(super) fn at(source: &str, line: usize) -> String {
    format!("{source}:{line}")
}

pub(super) fn hull_error(e: Error, source: &str) -> Error {
    match e {
        Error::Geometry(m) => Error::parse(source, format!("convex hull of the mesh: {m}")),
        other => other,
    }
}

/// A name usable as one OBJ/STL token: whitespace and control characters become `_`.
pub(super) fn token(name: &str, fallback: &str) -> String {
    let t: String = name
        .chars()
        .map(|c| {
            if c.is_whitespace() || c.is_control() {
                '_'
            } else {
                c
            }
        })
        .collect();
    if t.is_empty() {
        fallback.to_string()
    } else {
        t
    }
}
