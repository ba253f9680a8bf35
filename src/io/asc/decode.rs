//! Bytes to lines for the reader: UTF-8 where valid, else Windows-1252 or Latin-1; LF, CRLF or
//! lone CR line ends; the keywords read and the lines that continue an open `a` line.

/// Windows-1252 0x80–0x9F; the five undefined bytes keep their Latin-1 (C1) code points.
const CP1252_HIGH: [char; 32] = [
    '\u{20AC}', '\u{0081}', '\u{201A}', '\u{0192}', '\u{201E}', '\u{2026}', '\u{2020}', '\u{2021}',
    '\u{02C6}', '\u{2030}', '\u{0160}', '\u{2039}', '\u{0152}', '\u{008D}', '\u{017D}', '\u{008F}',
    '\u{0090}', '\u{2018}', '\u{2019}', '\u{201C}', '\u{201D}', '\u{2022}', '\u{2013}', '\u{2014}',
    '\u{02DC}', '\u{2122}', '\u{0161}', '\u{203A}', '\u{0153}', '\u{009D}', '\u{017E}', '\u{0178}',
];

/// The character of one Windows-1252 byte (Latin-1 outside 0x80–0x9F).
pub(in crate::io) fn byte_char(b: u8) -> char {
    match b {
        0x80..=0x9F => CP1252_HIGH
            .get(usize::from(b - 0x80))
            .copied()
            .unwrap_or('\u{FFFD}'),
        _ => char::from(b),
    }
}

/// `text` as Windows-1252 bytes (what GemCad writes): ASCII and Latin-1 as themselves, the
/// characters of 0x80–0x9F (€, ‘ ’ “ ”, – —, …) as their bytes, anything else as `?`.
pub(in crate::io) fn encode_cp1252(text: &str) -> Vec<u8> {
    text.chars()
        .map(|c| match u32::from(c) {
            0..=0x7F | 0xA0..=0xFF => u8::try_from(u32::from(c)).unwrap_or(b'?'),
            _ => CP1252_HIGH
                .iter()
                .position(|&h| h == c)
                .and_then(|i| u8::try_from(0x80 + i).ok())
                .unwrap_or(b'?'),
        })
        .collect()
}

/// UTF-8 where valid, Windows-1252/Latin-1 for the other bytes; a BOM is dropped.
pub(super) fn decode(bytes: &[u8]) -> String {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let mut s = String::with_capacity(bytes.len());
    for chunk in bytes.utf8_chunks() {
        s.push_str(chunk.valid());
        s.extend(chunk.invalid().iter().map(|&b| byte_char(b)));
    }
    s
}

/// Split on LF, CRLF or lone CR.
pub(super) fn lines(text: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find(['\r', '\n']) {
        out.push(&rest[..i]);
        let skip = if rest[i..].starts_with("\r\n") { 2 } else { 1 };
        rest = &rest[i + skip..];
    }
    if !rest.is_empty() {
        out.push(rest);
    }
    out
}

/// The keyword letter of a line and the text after it, for the keywords we read. `a`, `g`,
/// `y`, `I` may be glued to a number (`g96`); `H` and `F` need a space after them.
pub(super) fn keyword(t: &str) -> Option<(char, &str)> {
    let c = t.chars().next()?;
    let rest = t.get(c.len_utf8()..)?;
    let next = rest.chars().next();
    let spaced = next.is_none_or(char::is_whitespace);
    let glued = next.is_some_and(starts_number);
    match c {
        'a' | 'g' | 'y' | 'I' if spaced || glued => Some((c, rest.trim())),
        'H' | 'F' if spaced => Some((c, rest.trim())),
        _ => None,
    }
}

fn starts_number(c: char) -> bool {
    c.is_ascii_digit() || matches!(c, '-' | '+' | '.')
}

/// Whether a line continues an open `a` line (wrapped index list, names or instructions).
pub(super) fn continues(t: &str) -> bool {
    let mut cs = t.chars();
    match cs.next() {
        Some(c) if starts_number(c) => true,
        Some('n' | 'G') => cs.next().is_none_or(char::is_whitespace),
        _ => false,
    }
}

pub(super) fn number(s: &str) -> Option<f64> {
    s.parse::<f64>().ok().filter(|v| v.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_1252_both_ways() {
        let all: Vec<u8> = (1..=255).collect();
        let text: String = all.iter().map(|&b| byte_char(b)).collect();
        assert_eq!(encode_cp1252(&text), all);
        assert_eq!(
            encode_cp1252("Caf\u{e9} \u{2013} \u{20ac}5 \u{4e2d}"),
            b"Caf\xe9 \x96 \x805 ?"
        );
    }
}
