//! GemCad `.asc` designs: read them into a [`Cut`], write a [`Cut`] as one.
//!
//! # The format
//!
//! A line-based text file. Each line starts with a keyword letter:
//!
//! - `GemCad 5.0`: the header (ignored);
//! - `g 96 0.0`: the index gear (teeth per turn; negative = indices run clockwise) and the gear
//!   offset, an *index* (see below);
//! - `y 8 y`: symmetry (fold count, mirror `y`/`n`), kept as metadata only: every facet is
//!   listed explicitly in the file;
//! - `I 1.54`: refractive index;
//! - `H text`: header/title lines; `F text`: footnotes;
//! - `a ANGLE DISTANCE INDEX [INDEX …] [n NAME] [G INSTRUCTIONS…]`: facets with one angle and
//!   distance, one facet per index. `n NAME` names the facet of the index just before it (the
//!   first name of the line also names the tier); the token right after `n` is always a name,
//!   even `G`. `G` starts the cutting instructions, which run to the end of the line.
//!
//! # How a facet line becomes planes
//!
//! - ANGLE is the facet's tilt from the girdle plane in degrees: positive (and `0`) = crown,
//!   negative (and `-0`) = pavilion, ±90 = girdle. Allowed range −90…90.
//! - INDEX `i` on a gear of `g` teeth with offset `o` has the azimuth (our convention: degrees
//!   from +x toward +y, counter-clockwise seen from above)
//!   `azimuth = −90° + 360° · (i − o) / g`.
//!   This follows the GemCad manual: the offset is the index drawn at the bottom (6 o'clock) of
//!   the Top View, and with a positive tooth count the indices increase counter-clockwise in
//!   the Top View (seen from above the crown); a negative tooth count runs clockwise. So for
//!   `g 96 0`, index 96 faces −y, 24 faces +x, 48 faces +y and 72 faces −x, and the design is
//!   not mirrored. (The opposite choice would mirror chiral designs in y; symmetric designs
//!   are the same either way.)
//! - DISTANCE is the plane's distance from the origin (the stone's axis point in the girdle
//!   plane). GemCad keeps that point inside the stone, so a *negative* distance puts the plane
//!   on the other side of the origin, facing the other way: `a 0 -0.1 96` is a culet 0.1
//!   below the girdle plane, the same facet as `a -0 0.1 96`.
//! - The facet's outward normal is [`facet_normal`]`(|angle|, azimuth, crown)`, its offset the
//!   distance.
//! - A facet repeating an earlier facet's plane exactly (real files do this) is dropped: it
//!   cuts nothing.
//!
//! Names: a facet is called after its own `n` name, else the first name on its line, else a
//! generated tier name (`table`, `culet`, `girdle`, `crown-34.00`, `pavilion-42.50`). Names
//! shared by several facets get `-1`, `-2`, … so that every facet name in a cut is unique
//! (`A-1` … `A-16`). The tier is the line's first name, or the generated name.
//!
//! # Units
//!
//! [`AscDesign::planes`] are in the file's units. [`AscDesign::to_cut`] scales the solid about
//! the origin so that its width W is 1, like every preset and every other import (the unit
//! convention of [`crate::cut::units`]: W is the outline's smaller extent along x and y, the
//! diameter of a round), and every plane offset is scaled with it; the factor is kept in the design's record
//! ([`GemcadRecord::scale`]), with the index, titles, notes, gear, symmetry and instructions,
//! on [`Cut::record`]. [`write()`] writes a design's distances back in its file's units, a
//! generated cut's in its own.
//!
//! # Tolerated
//!
//! Index lists wrapped onto following lines (a line starting with a number, `n` or `G`
//! continues the open `a` line), fractional and negative indices, negative gears, keywords
//! glued to their number (`g96`, `a-42.5`), a UTF-8 BOM, CR, LF or CRLF line ends, blank and
//! unknown lines (skipped). Bytes that are not UTF-8 are read as Windows-1252 (0x80–0x9F) or
//! Latin-1. A malformed `a`, `g`, `y` or `I` line is an error naming the file and line.

use crate::cut::units::outline_size;
use crate::cut::{Cut, GemcadRecord};
use crate::error::{Error, Result};
use crate::geometry::{facet_normal, FacetPlane, Polyhedron};
use serde::Serialize;
use std::collections::{BTreeMap, HashMap, HashSet};
use std::fmt::Write as _;
use std::path::Path;

/// The index gear used when a file has no `g` line, and by [`write()`] for a cut without a
/// design record.
pub const DEFAULT_GEAR: u32 = 96;

/// One `a` line (with its continuation lines) as written in the file.
#[derive(Clone, Debug, PartialEq)]
pub struct AscTier {
    /// Line number of the `a` keyword (1-based).
    pub line: usize,
    /// Angle as written, degrees: positive crown, negative (including `-0`) pavilion.
    pub angle: f64,
    /// Distance as written, in the file's units (negative: the other side of the origin).
    pub distance: f64,
    /// Each gear index with the name given right after it (`n NAME`), if any.
    pub indices: Vec<(f64, Option<String>)>,
    /// The first name on the line (names the tier), if any.
    pub name: Option<String>,
    /// Cutting instructions after `G`, if any.
    pub instructions: Option<String>,
}

/// A parsed GemCad design: metadata and facet planes in the file's units.
#[derive(Clone, Debug, PartialEq)]
pub struct AscDesign {
    /// The `H` lines, in order (the design's title and credits).
    pub title: Vec<String>,
    /// Index gear teeth (negative: indices run clockwise). 96 when the file has no `g` line.
    pub gear: f64,
    /// Gear offset: the index at 6 o'clock (an index, not degrees).
    pub gear_offset: f64,
    /// Rotational symmetry fold count (metadata only).
    pub symmetry: u32,
    /// Mirror symmetry (metadata only).
    pub mirror: bool,
    /// Refractive index the design was made for, if given.
    pub ri: Option<f64>,
    /// The `a` lines as written.
    pub tiers: Vec<AscTier>,
    /// Facet planes in the file's units, exact repeats dropped, names unique.
    pub planes: Vec<FacetPlane>,
    /// The `F` lines, in order.
    pub footnotes: Vec<String>,
    /// Cutting instructions (`G`) by the name of the first facet of their line.
    pub instructions: BTreeMap<String, String>,
}

impl AscDesign {
    /// Build the solid and scale it so that its width W is 1 (see the module
    /// docs). Errors if the planes do not make a bounded convex solid in which every facet
    /// has an area.
    pub fn to_cut(&self, name: &str) -> Result<Cut> {
        self.build(name, name)
    }

    /// The solid, scaled, with the design's record ([`GemcadRecord`]) attached.
    fn build(&self, name: &str, ctx: &str) -> Result<Cut> {
        let (mut cut, scale) = build_cut(&self.planes, name, ctx)?;
        cut.record = Some(GemcadRecord {
            ri: self.ri,
            title: self.title.clone(),
            footnotes: self.footnotes.clone(),
            gear: self.gear,
            gear_offset: self.gear_offset,
            symmetry: self.symmetry,
            mirror: self.mirror,
            instructions: self.instructions.clone(),
            scale,
        });
        Ok(cut)
    }
}

/// Read a GemCad `.asc` file into a cut named after the file stem, with the design's record
/// (index, titles, notes, gear, symmetry, instructions) in [`Cut::record`].
pub fn read(path: &Path) -> Result<Cut> {
    let shown = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| Error::io(&shown, e))?;
    let design = parse(&bytes, &shown)?;
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "design".into());
    design.build(&stem, &shown)
}

/// The solid of `planes`, scaled to the unit convention, and the length of one cut unit in
/// the planes' units.
fn build_cut(planes: &[FacetPlane], name: &str, ctx: &str) -> Result<(Cut, f64)> {
    // Pre-scale so the largest distance is 1: the solid then fits the clipping box whatever
    // the file's units.
    let big = planes
        .iter()
        .map(|p| p.plane.offset.abs())
        .fold(0.0, f64::max);
    let pre = if big.is_finite() && big > 0.0 {
        1.0 / big
    } else {
        1.0
    };
    let scaled: Vec<FacetPlane> = planes
        .iter()
        .map(|p| {
            let mut q = p.clone();
            q.plane.offset *= pre;
            q
        })
        .collect();
    let solid = Polyhedron::from_planes(&scaled).map_err(|e| e.context(ctx))?;
    let width = outline_size(solid.vertices()).1;
    if !(width.is_finite() && width > 1e-12) {
        return Err(Error::Geometry(format!(
            "{ctx}: the solid has no horizontal extent, so its girdle outline cannot be scaled to width 1"
        )));
    }
    let cut = Cut {
        name: name.to_string(),
        family: None,
        params: BTreeMap::new(),
        solid: solid.scaled(1.0 / width),
        record: None,
    };
    Ok((cut, width / pre))
}

// ---------------------------------------------------------------------------------------------
// Decoding and lines

/// Windows-1252 0x80–0x9F; the five undefined bytes keep their Latin-1 (C1) code points.
const CP1252_HIGH: [char; 32] = [
    '\u{20AC}', '\u{0081}', '\u{201A}', '\u{0192}', '\u{201E}', '\u{2026}', '\u{2020}', '\u{2021}',
    '\u{02C6}', '\u{2030}', '\u{0160}', '\u{2039}', '\u{0152}', '\u{008D}', '\u{017D}', '\u{008F}',
    '\u{0090}', '\u{2018}', '\u{2019}', '\u{201C}', '\u{201D}', '\u{2022}', '\u{2013}', '\u{2014}',
    '\u{02DC}', '\u{2122}', '\u{0161}', '\u{203A}', '\u{0153}', '\u{009D}', '\u{017E}', '\u{0178}',
];

fn byte_char(b: u8) -> char {
    match b {
        0x80..=0x9F => CP1252_HIGH
            .get(usize::from(b - 0x80))
            .copied()
            .unwrap_or('\u{FFFD}'),
        _ => char::from(b),
    }
}

/// UTF-8 where valid, Windows-1252/Latin-1 for the other bytes; a BOM is dropped.
fn decode(bytes: &[u8]) -> String {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let mut s = String::with_capacity(bytes.len());
    for chunk in bytes.utf8_chunks() {
        s.push_str(chunk.valid());
        s.extend(chunk.invalid().iter().map(|&b| byte_char(b)));
    }
    s
}

/// Split on LF, CRLF or lone CR.
fn lines(text: &str) -> Vec<&str> {
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
fn keyword(t: &str) -> Option<(char, &str)> {
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
fn continues(t: &str) -> bool {
    let mut cs = t.chars();
    match cs.next() {
        Some(c) if starts_number(c) => true,
        Some('n' | 'G') => cs.next().is_none_or(char::is_whitespace),
        _ => false,
    }
}

fn number(s: &str) -> Option<f64> {
    s.parse::<f64>().ok().filter(|v| v.is_finite())
}

// ---------------------------------------------------------------------------------------------
// Parsing

/// An `a` line being collected: its line number and its tokens with their line numbers.
struct OpenTier<'a> {
    line: usize,
    tokens: Vec<(&'a str, usize)>,
}

/// Parse the bytes of a `.asc` file. `source` names the file in error messages
/// (`design.asc:12: angle "x3" is not a number`).
pub fn parse(text_bytes: &[u8], source: &str) -> Result<AscDesign> {
    let text = decode(text_bytes);
    let at = |line: usize| format!("{source}:{line}");
    let mut d = AscDesign {
        title: Vec::new(),
        gear: f64::from(DEFAULT_GEAR),
        gear_offset: 0.0,
        symmetry: 1,
        mirror: false,
        ri: None,
        tiers: Vec::new(),
        planes: Vec::new(),
        footnotes: Vec::new(),
        instructions: BTreeMap::new(),
    };
    let mut open: Option<OpenTier> = None;
    for (i, raw) in lines(&text).into_iter().enumerate() {
        let line = i + 1;
        let t = raw.trim().trim_start_matches('\u{FEFF}');
        if t.is_empty() {
            continue;
        }
        if let Some(o) = open.as_mut() {
            if continues(t) {
                o.tokens.extend(t.split_whitespace().map(|w| (w, line)));
                continue;
            }
        }
        if let Some(o) = open.take() {
            d.tiers.push(parse_tier(&o, source)?);
        }
        let Some((kw, rest)) = keyword(t) else {
            continue;
        };
        match kw {
            'a' => {
                open = Some(OpenTier {
                    line,
                    tokens: rest.split_whitespace().map(|w| (w, line)).collect(),
                })
            }
            'g' => {
                let mut it = rest.split_whitespace();
                let g = it.next().unwrap_or("");
                d.gear = number(g).filter(|v| *v != 0.0).ok_or_else(|| {
                    Error::parse(
                        at(line),
                        format!("gear {g:?} is not allowed; write `g TEETH OFFSET` with a non-zero tooth count, e.g. `g 96 0.0`"),
                    )
                })?;
                if let Some(o) = it.next() {
                    d.gear_offset = number(o).ok_or_else(|| {
                        Error::parse(
                            at(line),
                            format!("gear offset {o:?} is not a number; e.g. `g 96 0.0`"),
                        )
                    })?;
                }
            }
            'y' => {
                let digits = rest
                    .find(|c: char| !c.is_ascii_digit())
                    .unwrap_or(rest.len());
                let (count, flag) = rest.split_at(digits);
                d.symmetry = count.parse::<u32>().map_err(|_| {
                    Error::parse(at(line), format!("symmetry {rest:?} is not allowed; write `y FOLDS MIRROR`, e.g. `y 8 y`"))
                })?;
                d.mirror = match flag.trim() {
                    "y" | "Y" => true,
                    "n" | "N" | "" => false,
                    other => {
                        return Err(Error::parse(
                            at(line),
                            format!("symmetry mirror flag {other:?} is not allowed; use y or n, e.g. `y 8 y`"),
                        ))
                    }
                };
            }
            'I' => {
                let v = rest.split_whitespace().next().unwrap_or("");
                d.ri = Some(number(v).filter(|n| *n > 0.0).ok_or_else(|| {
                    Error::parse(
                        at(line),
                        format!("refractive index {v:?} is not a positive number, e.g. `I 1.54`"),
                    )
                })?);
            }
            'H' => d.title.push(rest.to_string()),
            'F' => d.footnotes.push(rest.to_string()),
            _ => {}
        }
    }
    if let Some(o) = open.take() {
        d.tiers.push(parse_tier(&o, source)?);
    }
    let (planes, instructions) = planes_of(&d);
    d.planes = planes;
    d.instructions = instructions;
    Ok(d)
}

fn parse_tier(o: &OpenTier, source: &str) -> Result<AscTier> {
    let at = |line: usize| format!("{source}:{line}");
    let usage = "expected `a ANGLE DISTANCE INDEX [INDEX …] [n NAME] [G INSTRUCTIONS]`";
    let mut toks = o.tokens.iter().copied();
    let (a, la) = toks
        .next()
        .ok_or_else(|| Error::parse(at(o.line), format!("facet line has no angle; {usage}")))?;
    let angle = number(a)
        .ok_or_else(|| Error::parse(at(la), format!("angle {a:?} is not a number; {usage}")))?;
    if angle.abs() > 90.0 {
        return Err(Error::parse(
            at(la),
            format!("angle {a} is out of range; allowed -90 to 90 degrees (positive crown, negative pavilion, ±90 girdle)"),
        ));
    }
    let (s, ls) = toks
        .next()
        .ok_or_else(|| Error::parse(at(la), format!("facet line has no distance; {usage}")))?;
    let distance = number(s)
        .ok_or_else(|| Error::parse(at(ls), format!("distance {s:?} is not a number; {usage}")))?;
    let mut tier = AscTier {
        line: o.line,
        angle,
        distance,
        indices: Vec::new(),
        name: None,
        instructions: None,
    };
    while let Some((t, lt)) = toks.next() {
        match t {
            "n" => {
                let (name, _) = toks.next().ok_or_else(|| {
                    Error::parse(at(lt), "`n` must be followed by a facet name, e.g. `n A`")
                })?;
                if let Some(last) = tier.indices.last_mut() {
                    if last.1.is_none() {
                        last.1 = Some(name.to_string());
                    }
                }
                if tier.name.is_none() {
                    tier.name = Some(name.to_string());
                }
            }
            "G" => {
                let words: Vec<&str> = toks.by_ref().map(|(w, _)| w).collect();
                tier.instructions = Some(words.join(" "));
            }
            _ => {
                let i = number(t).ok_or_else(|| {
                    Error::parse(at(lt), format!("index {t:?} is not a number; expected gear indices, `n NAME` or `G INSTRUCTIONS`"))
                })?;
                tier.indices.push((i, None));
            }
        }
    }
    if tier.indices.is_empty() {
        return Err(Error::parse(
            at(o.line),
            format!("facet line at angle {angle} has no gear index; give at least one index after the distance"),
        ));
    }
    Ok(tier)
}

/// Generated tier name for unnamed facets, from the facet's effective side and angle.
fn generated_tier(angle: f64, crown: bool) -> String {
    if angle == 90.0 {
        "girdle".into()
    } else if angle == 0.0 {
        if crown { "table" } else { "culet" }.into()
    } else {
        format!("{}-{angle:.2}", if crown { "crown" } else { "pavilion" })
    }
}

/// Facet planes of all tiers, exact repeats dropped, names made unique; and each line's
/// instructions keyed by the name of its first facet.
fn planes_of(d: &AscDesign) -> (Vec<FacetPlane>, BTreeMap<String, String>) {
    let mut planes: Vec<FacetPlane> = Vec::new();
    let mut line_of: Vec<usize> = Vec::new();
    for (k, t) in d.tiers.iter().enumerate() {
        let a = t.angle.abs();
        let crown = !t.angle.is_sign_negative();
        // A negative distance puts the plane on the other side of the origin: flip it.
        let flip = t.distance < 0.0;
        let offset = t.distance.abs();
        let eff_crown = crown != flip;
        let tier = t
            .name
            .clone()
            .unwrap_or_else(|| generated_tier(a, eff_crown));
        for (index, name) in &t.indices {
            let az = -90.0 + 360.0 * (index - d.gear_offset) / d.gear;
            let n = facet_normal(a, az, crown);
            let normal = if flip { -n } else { n };
            let repeat = planes.iter().any(|p| {
                p.plane.normal.distance(normal) < 1e-9
                    && (p.plane.offset - offset).abs() < 1e-9 * offset.max(1.0)
            });
            if repeat {
                continue;
            }
            let base = name.clone().unwrap_or_else(|| tier.clone());
            planes.push(FacetPlane::new(normal, offset, base, tier.clone()));
            line_of.push(k);
        }
    }
    let names = unique_names(planes.iter().map(|p| p.name.as_str()));
    for (p, n) in planes.iter_mut().zip(names) {
        p.name = n;
    }
    let mut instructions = BTreeMap::new();
    for (k, t) in d.tiers.iter().enumerate() {
        let Some(text) = t.instructions.as_ref().filter(|s| !s.is_empty()) else {
            continue;
        };
        if let Some(i) = line_of.iter().position(|&l| l == k) {
            instructions.insert(planes[i].name.clone(), text.clone());
        }
    }
    (planes, instructions)
}

/// Names used once stay; names used several times become `NAME-1`, `NAME-2`, … skipping any
/// name already taken.
fn unique_names<'a>(bases: impl Iterator<Item = &'a str> + Clone) -> Vec<String> {
    let mut count: HashMap<&str, usize> = HashMap::new();
    for b in bases.clone() {
        *count.entry(b).or_default() += 1;
    }
    let once = |b: &str| count.get(b).copied().unwrap_or(0) <= 1;
    let mut used: HashSet<String> = bases
        .clone()
        .filter(|b| once(b))
        .map(str::to_string)
        .collect();
    let mut next: HashMap<&str, usize> = HashMap::new();
    bases
        .map(|b| {
            if once(b) {
                return b.to_string();
            }
            let k = next.entry(b).or_default();
            loop {
                *k += 1;
                let cand = format!("{b}-{k}");
                if used.insert(cand.clone()) {
                    return cand;
                }
            }
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Writing

/// A name as one `.asc` token.
fn token(name: &str) -> String {
    name.split_whitespace().collect::<Vec<_>>().join("_")
}

/// A number with at most `max` decimals: the fewest (at least `min`) that come within `tol`
/// of `x`, else `max`. `-0` is written `0`.
fn fmt_short(x: f64, min: usize, max: usize, tol: f64) -> String {
    let x = if x == 0.0 { 0.0 } else { x };
    for d in min..max {
        let t = format!("{x:.d$}");
        if t.parse::<f64>().is_ok_and(|v| (v - x).abs() <= tol) {
            return tidy(t);
        }
    }
    tidy(format!("{x:.max$}"))
}

/// No `-0`, `-0.00` …
fn tidy(t: String) -> String {
    if t.starts_with('-') && t.trim_start_matches(['-', '0', '.']).is_empty() {
        t[1..].to_string()
    } else {
        t
    }
}

/// A gear index: a whole number when the azimuth is on the gear (within 1e-6 of a tooth),
/// else the fewest decimals (up to 10) that give the azimuth within 1e-9 of a tooth.
fn fmt_index(i: f64) -> String {
    let r = i.round();
    if (i - r).abs() < 1e-6 {
        format!("{r:.0}")
    } else {
        fmt_short(i, 1, 10, 1e-9)
    }
}

/// The tier name the reader generates for an unnamed line (see [`generated_tier`]), for the
/// angle and distance as written.
fn reader_tier(angle: &str, dist: &str) -> String {
    let a: f64 = angle.parse().unwrap_or(0.0);
    let d: f64 = dist.parse().unwrap_or(0.0);
    let crown = !a.is_sign_negative() && !angle.starts_with('-');
    generated_tier(a.abs(), crown != (d < 0.0))
}

/// Whether `name` is what the reader makes of an unnamed facet of tier `tier` (`tier` or
/// `tier-K`).
fn derived_name(name: &str, tier: &str) -> bool {
    name == tier
        || name
            .strip_prefix(tier)
            .and_then(|r| r.strip_prefix('-'))
            .is_some_and(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()))
}

/// One `a` line being assembled: tier, angle and distance as written, and the facets'
/// (index text, facet name).
struct Line {
    tier: String,
    angle: String,
    dist: String,
    facets: Vec<(String, String)>,
}

/// The design record to write with, the gear teeth and offset, and the `a` lines.
fn gear_lines(cut: &Cut, gear: u32) -> (GemcadRecord, f64, f64, Vec<Line>) {
    let design = cut.record.clone().unwrap_or_default();
    let (g, offset) = if gear == 0 || f64::from(gear) == design.gear.abs() {
        (design.gear, design.gear_offset)
    } else {
        (f64::from(gear), 0.0)
    };
    let teeth = g.abs();
    let scale = if design.scale.is_finite() && design.scale > 0.0 {
        design.scale
    } else {
        1.0
    };
    let mut lines: Vec<Line> = Vec::new();
    for f in cut.solid.facets() {
        let n = f.plane.normal;
        let h = n.x.hypot(n.y);
        let tilt = h.atan2(n.z.abs()).to_degrees();
        let crown = n.z > 1e-12;
        let d = f.plane.offset * scale;
        let (angle, dist) = if h <= 1e-12 && !crown {
            (0.0, -d) // culet: `a 0 -d`
        } else if crown {
            (tilt, d)
        } else {
            (-tilt, d)
        };
        let index = if h <= 1e-12 {
            let i = offset.rem_euclid(teeth);
            fmt_index(if i == 0.0 { teeth } else { i })
        } else {
            let az = n.y.atan2(n.x).to_degrees();
            let i = (offset + g * (az + 90.0) / 360.0).rem_euclid(teeth);
            let i = if i.round() == 0.0 || i.round() == teeth && (i - teeth).abs() < 1e-6 {
                teeth
            } else {
                i
            };
            fmt_index(i)
        };
        let angle = tidy(format!("{angle:.6}"));
        let dist = tidy(format!("{dist:.8}"));
        let tier = token(&f.tier);
        match lines
            .iter_mut()
            .find(|l| l.tier == tier && l.angle == angle && l.dist == dist)
        {
            Some(l) => l.facets.push((index, f.name.clone())),
            None => lines.push(Line {
                tier,
                angle,
                dist,
                facets: vec![(index, f.name.clone())],
            }),
        }
    }
    (design, g, offset, lines)
}

/// Write `cut` as a GemCad `.asc` design on a gear of `gear` teeth; `0` means the design's
/// own gear (and offset) when the cut came from a design file ([`Cut::record`]), else 96.
///
/// A design read from a file keeps its record: `I` (index), `H` (titles), `F` (footnotes),
/// `y` (symmetry and mirror), `g` (gear and offset) and each line's `G` instructions, and its
/// distances are written back in the file's own units ([`GemcadRecord::scale`]). A generated cut is
/// written with `g 96 0.0`, `y 1 n`, its name as the title, no `I` line, distances in girdle
/// widths (W = 1).
///
/// Facets are grouped into one `a` line per (tier, angle, distance) as written, in order of
/// first appearance; a tier's angle is written once, with 6 decimals as GemCad does (pavilion
/// negative, girdle −90; a culet GemCad's way, as angle 0 with a negative distance),
/// distances with 8. Each azimuth becomes an index (`i = offset + g · (azimuth + 90°) /
/// 360°`, index 0 written as the tooth count): a whole number when the azimuth is on the gear,
/// else the fewest decimals that keep it (a fractional index, as GemCad allows). The tier is
/// written as `n TIER` after the first index unless it is the name the reader would generate
/// anyway (`table`, `girdle`, `crown-34.00` …); a facet with a name of its own (not `TIER` or
/// `TIER-K`) gets `n NAME` after its index. Planes with a negative offset (the origin outside
/// the solid) cannot be expressed in GemCad's convention and do not read back the same.
///
/// A round trip through the text:
///
/// ```
/// use facetlab::io::{asc, load_cut};
///
/// let cut = load_cut("gia-reference").unwrap();
/// let text = asc::write(&cut, 96);
/// assert!(text.starts_with("GemCad"));
/// let back = asc::parse(text.as_bytes(), "gia.asc").unwrap().to_cut("gia").unwrap();
/// assert_eq!(back.solid.facets().len(), cut.solid.facets().len());
/// assert!((back.proportions().crown_angle - 34.0).abs() < 1e-6);
/// ```
pub fn write(cut: &Cut, gear: u32) -> String {
    let (design, g, offset, lines) = gear_lines(cut, gear);
    let mut out = String::new();
    let _ = writeln!(out, "GemCad 5.0");
    let _ = writeln!(
        out,
        "g {} {}",
        fmt_short(g, 0, 6, 1e-9),
        fmt_short(offset, 1, 6, 1e-9)
    );
    let _ = writeln!(
        out,
        "y {} {}",
        design.symmetry.max(1),
        if design.mirror { "y" } else { "n" }
    );
    if let Some(ri) = design.ri {
        let _ = writeln!(out, "I {}", fmt_short(ri, 2, 6, 1e-9));
    }
    if cut.record.is_some() {
        for t in &design.title {
            let _ = writeln!(out, "H {t}");
        }
    } else {
        let title = cut.name.split_whitespace().collect::<Vec<_>>().join(" ");
        if !title.is_empty() {
            let _ = writeln!(out, "H {title}");
        }
    }
    for l in &lines {
        let _ = write!(out, "a {} {}", l.angle, l.dist);
        let generated = l.tier.is_empty() || l.tier == reader_tier(&l.angle, &l.dist);
        for (k, (index, name)) in l.facets.iter().enumerate() {
            let _ = write!(out, " {index}");
            if generated {
                continue;
            }
            if k == 0 {
                let _ = write!(out, " n {}", l.tier);
            } else if !derived_name(name, &l.tier) {
                let _ = write!(out, " n {}", token(name));
            }
        }
        if let Some(text) = l
            .facets
            .iter()
            .find_map(|(_, name)| design.instructions.get(name))
        {
            let _ = write!(out, " G {text}");
        }
        out.push('\n');
    }
    for f in &design.footnotes {
        let _ = writeln!(out, "F {f}");
    }
    out
}

/// One tier of the cutting instructions: one `a` line of the design.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CuttingStep {
    /// Place in the cutting order, from 1.
    pub step: usize,
    /// `pavilion` (girdle and culet included, as GemCad prints them) or `crown`.
    pub side: &'static str,
    /// Tier name.
    pub tier: String,
    /// Angle to the girdle plane in degrees, at 0.01° (girdle 90, table and culet 0).
    pub angle: f64,
    /// The facets' gear indices, as a cutter sets them: whole numbers when on the gear, else
    /// to 0.01 of a tooth.
    pub indices: Vec<String>,
    /// The design's instruction for the line (`G`), if any.
    pub note: Option<String>,
}

impl CuttingStep {
    /// The indices with two digits at least, as GemCad prints them (03-09-15).
    pub fn padded_indices(&self) -> Vec<String> {
        self.indices
            .iter()
            .map(|i| {
                if i.len() == 1 {
                    format!("0{i}")
                } else {
                    i.clone()
                }
            })
            .collect()
    }
}

/// Cutting instructions: the gear, the design's index and the tiers in cutting order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CuttingInstructions {
    /// Gear teeth (negative: clockwise).
    pub gear: f64,
    /// Gear offset (the index at 6 o'clock).
    pub gear_offset: f64,
    /// The design's refractive index, if it names one.
    pub ri: Option<f64>,
    /// Pavilion first, then crown, each in the design's order.
    pub steps: Vec<CuttingStep>,
}

/// The cutting instructions of `cut` on its design's gear (or `gear`, as [`write()`]): each
/// tier (one line of the `.asc` file) with its angle at 0.01°, its indices on the gear and its
/// instruction, pavilion first (girdle and culet with it), then crown, as GemCad prints them;
/// within a side the design's order (for a generated cut its facet order, the table and the
/// culet last).
///
/// ```
/// let cut = facetlab::io::load_cut("tolkowsky").unwrap();
/// let c = facetlab::io::asc::cutting_instructions(&cut, 0);
/// assert_eq!(c.gear, 96.0);
/// assert_eq!(c.steps[0].side, "pavilion");
/// let bezel = c.steps.iter().find(|s| s.tier == "bezel").unwrap();
/// assert_eq!((bezel.angle, bezel.indices.len()), (34.5, 8));
/// ```
pub fn cutting_instructions(cut: &Cut, gear: u32) -> CuttingInstructions {
    let (design, g, offset, lines) = gear_lines(cut, gear);
    let mut steps: Vec<CuttingStep> = Vec::new();
    for want in ["pavilion", "crown"] {
        for l in &lines {
            let angle: f64 = l.angle.parse().unwrap_or(0.0);
            let dist: f64 = l.dist.parse().unwrap_or(0.0);
            let pavilion = l.angle.starts_with('-') || (angle == 0.0 && dist < 0.0);
            let side = if pavilion { "pavilion" } else { "crown" };
            if side != want {
                continue;
            }
            let tier = if l.tier.is_empty() {
                reader_tier(&l.angle, &l.dist)
            } else {
                l.tier.clone()
            };
            steps.push(CuttingStep {
                step: steps.len() + 1,
                side,
                tier,
                angle: (angle.abs() * 100.0).round() / 100.0,
                // Off-gear indices at 0.01 of a tooth: what a cutter can set with a cheater.
                indices: l
                    .facets
                    .iter()
                    .map(|(i, _)| match i.parse::<f64>() {
                        Ok(v) if i.contains('.') => fmt_short(v, 1, 2, 1e-9),
                        _ => i.clone(),
                    })
                    .collect(),
                note: l
                    .facets
                    .iter()
                    .find_map(|(_, name)| design.instructions.get(name).cloned()),
            });
        }
    }
    if cut.record.is_none() {
        // A generated cut lists its table first; a cutter polishes the table and the culet
        // last on their side.
        let flat = |s: &CuttingStep| s.angle == 0.0;
        steps.sort_by_key(|s| (s.side == "crown", flat(s)));
        for (k, s) in steps.iter_mut().enumerate() {
            s.step = k + 1;
        }
    }
    CuttingInstructions {
        gear: g,
        gear_offset: offset,
        ri: design.ri,
        steps,
    }
}

impl CuttingInstructions {
    /// The instructions as a cutter reads them: a header with the gear and index, then one
    /// line per tier: step, tier, angle (0.01°), indices joined by `-` (two digits, as GemCad
    /// prints them), instruction.
    pub fn text(&self) -> String {
        let mut o = String::new();
        let ri = self.ri.map(|n| format!(", index {n}")).unwrap_or_default();
        let _ = writeln!(
            o,
            "Cutting instructions: gear {} (offset {}){ri}; pavilion first, then crown",
            fmt_short(self.gear, 0, 6, 1e-9),
            fmt_short(self.gear_offset, 0, 6, 1e-9)
        );
        let mut side = "";
        for s in &self.steps {
            if s.side != side {
                side = s.side;
                let _ = writeln!(o, "{}", side.to_uppercase());
            }
            let idx = s.padded_indices();
            let note = s
                .note
                .as_deref()
                .map(|n| format!("  {n}"))
                .unwrap_or_default();
            let _ = writeln!(
                o,
                "  {:>3}  {:<14} {:>6.2}°  {}{note}",
                s.step,
                s.tier,
                s.angle,
                idx.join("-")
            );
        }
        o
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{facet_angle_deg, facet_azimuth_deg, DVec3};

    /// A small brilliant on a 96 gear: 16 girdle facets (tier named `G`), 8 pavilion mains,
    /// 8 bezels, table, culet. Girdle radius 1 (GemCad units), girdle 0.06 thick at the mains.
    const MINI: &str = "GemCad 5.0
g 96 0.0
y 8 y
I 2.42
H Mini brilliant
H test design
a -90.000000 1.000000 3 n G 9 15 21 27 33 39 45 51 57 63 69 75 81 87 93
a -41.000000 0.691553 96 n P 12 24 36 48 60 72 84 G Cut to a point
a 0.000000 -0.900000 96 n K G Small culet
a 34.000000 0.595019 96 n B 12 24 36 48 60 72 84 G Level girdle.
a 0.000000 0.332598 96 n T
F Footnote one
";

    /// The same design the hard way: BOM, CRLF and a lone CR, a Windows-1252 en dash in a
    /// title, glued `g96` and `a-41`, the girdle's index list wrapped over three lines, a
    /// fractional table index, negative and out-of-turn bezel indices, the culet as `a -0`,
    /// unknown lines and blank lines, a repeated facet.
    fn messy() -> Vec<u8> {
        let mut b: Vec<u8> =
            b"\xEF\xBB\xBFGemCad 5.0\r\ng96 0.0\r\ny8y\r\nI 2.42\r\nH Mini brilliant \x96 test\r\n"
                .to_vec();
        b.extend_from_slice(b"Hello world\r\n\r\nQ 1 2 3\r\n");
        b.extend_from_slice(
            b"a -90 1.0 3 n G 9 15 21\r\n   27 33 39 45 51 57\r\n63 69 75 81 87 93\r\n",
        );
        b.extend_from_slice(b"a-41.0 0.691553 96 n P 12 24 36 48 60 72 84 G Cut to a point\r");
        b.extend_from_slice(b"a -0 0.9 96 n K\r\n");
        b.extend_from_slice(b"a 34 0.595019 0 n B -84 120 36 48 60 72 -12\r\n");
        b.extend_from_slice(b"a -41.0 0.691553 12\r\n");
        b.extend_from_slice(b"a 0 0.332598 1.5 n T\r\n\r\nF Footnote one\r\n");
        b
    }

    fn same_planes(
        a: &[FacetPlane],
        b: &[FacetPlane],
        tol: f64,
    ) -> std::result::Result<(), String> {
        if a.len() != b.len() {
            return Err(format!("{} planes vs {}", a.len(), b.len()));
        }
        let mut used = vec![false; b.len()];
        for p in a {
            let hit = b.iter().enumerate().position(|(j, q)| {
                !used[j]
                    && p.plane.normal.distance(q.plane.normal) < tol
                    && (p.plane.offset - q.plane.offset).abs() < tol
            });
            match hit {
                Some(j) => used[j] = true,
                None => return Err(format!("no match for {} {:?}", p.name, p.plane)),
            }
        }
        Ok(())
    }

    #[test]
    fn asc_parses_hand_written_brilliant() {
        let d = parse(MINI.as_bytes(), "mini.asc").unwrap();
        assert_eq!(d.gear, 96.0);
        assert_eq!((d.symmetry, d.mirror, d.ri), (8, true, Some(2.42)));
        assert_eq!(d.title, vec!["Mini brilliant", "test design"]);
        assert_eq!(d.footnotes, vec!["Footnote one"]);
        assert_eq!(d.tiers.len(), 5);
        assert_eq!(d.tiers[1].instructions.as_deref(), Some("Cut to a point"));
        assert_eq!(d.planes.len(), 16 + 8 + 1 + 8 + 1);
        // `n G` is a name, not the instructions keyword.
        let girdle: Vec<&FacetPlane> = d.planes.iter().filter(|p| p.tier == "G").collect();
        assert_eq!(girdle.len(), 16);
        assert_eq!(girdle[0].name, "G-1");
        assert_eq!(girdle[15].name, "G-16");
        let names: HashSet<&str> = d.planes.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names.len(), d.planes.len(), "facet names must be unique");
        assert!(names.contains("T") && names.contains("K") && names.contains("B-8"));

        let cut = d.to_cut("mini").unwrap();
        assert_eq!(cut.name, "mini");
        assert_eq!(cut.solid.facets().len(), 34);
        assert!(cut.solid.volume() > 0.0);
        let w = outline_size(cut.solid.vertices()).1;
        assert!((w - 1.0).abs() < 1e-12, "outline width {w}");
        for f in cut.solid.facets() {
            let a = facet_angle_deg(f.plane.normal);
            let want = match f.tier.as_str() {
                "G" => 90.0,
                "P" => 41.0,
                "B" => 34.0,
                "T" | "K" => 0.0,
                t => panic!("unexpected tier {t}"),
            };
            assert!((a - want).abs() < 1e-9, "{} at {a}", f.name);
            match f.tier.as_str() {
                "P" | "K" => assert!(f.plane.normal.z < 0.0, "{} must face down", f.name),
                "B" | "T" => assert!(f.plane.normal.z > 0.0, "{} must face up", f.name),
                _ => {}
            }
        }
        let p = cut.proportions();
        assert!(
            (p.crown_angle - 34.0).abs() < 1e-9 && (p.pavilion_angle - 41.0).abs() < 1e-9,
            "{p:?}"
        );
        // Table edge midpoints at 0.56 of the girdle radius: 0.56 / cos 22.5° corner to corner.
        assert!(
            (p.table - 0.56 / 22.5f64.to_radians().cos()).abs() < 1e-5,
            "table {}",
            p.table
        );
        assert!(p.total_depth > 0.5 && p.total_depth < 0.8, "{p:?}");
    }

    #[test]
    fn asc_index_direction_and_gear_offset() {
        let src = "g 96 0\na 45 1 24 48 72 96 1.5\n";
        let d = parse(src.as_bytes(), "dir.asc").unwrap();
        let az: Vec<f64> = d
            .planes
            .iter()
            .map(|p| facet_azimuth_deg(p.plane.normal))
            .collect();
        // Index 96 at 6 o'clock (−y), counter-clockwise seen from above.
        let want = [0.0, 90.0, 180.0, 270.0, 270.0 + 5.625];
        for (a, w) in az.iter().zip(want) {
            assert!((a - w).abs() < 1e-9, "{az:?}");
        }
        // A negative gear runs the other way; the offset names the index at 6 o'clock.
        let d = parse(b"g -96 12\na 45 1 36", "dir.asc").unwrap();
        assert!((facet_azimuth_deg(d.planes[0].plane.normal) - 180.0).abs() < 1e-9);
    }

    #[test]
    fn asc_messy_file_parses_to_the_clean_solid() {
        let clean = parse(MINI.as_bytes(), "mini.asc").unwrap();
        let bytes = messy();
        let d = parse(&bytes, "messy.asc").unwrap();
        assert_eq!(d.title[0], "Mini brilliant \u{2013} test");
        assert_eq!(d.gear, 96.0);
        assert_eq!((d.symmetry, d.mirror), (8, true));
        assert_eq!(d.tiers[0].indices.len(), 16, "wrapped index list");
        assert_eq!(d.tiers.len(), 6);
        same_planes(&clean.planes, &d.planes, 1e-12).unwrap();
        let (a, b) = (clean.to_cut("a").unwrap(), d.to_cut("b").unwrap());
        assert!((a.solid.volume() - b.solid.volume()).abs() < 1e-12);
        same_planes(&a.solid.facet_planes(), &b.solid.facet_planes(), 1e-12).unwrap();
        // The culet faces straight down whichever way it is written.
        let k = b.solid.facets().iter().find(|f| f.tier == "K").unwrap();
        assert!(k.plane.normal.distance(DVec3::NEG_Z) < 1e-15 && k.plane.offset > 0.0);
        let k2 = parse(b"a 0 -0.9 96", "x").unwrap();
        assert_eq!(k2.planes[0].tier, "culet");
        assert!(k2.planes[0].plane.normal.distance(DVec3::NEG_Z) < 1e-15);
        // Latin-1 bytes and UTF-8 both decode.
        assert_eq!(parse(b"H Caf\xE9\n", "x").unwrap().title[0], "Caf\u{e9}");
        assert_eq!(
            parse("H Café\n".as_bytes(), "x").unwrap().title[0],
            "Caf\u{e9}"
        );
    }

    fn round_trip(gear: u32) {
        let cut = Cut::from_family("r", "round-brilliant", &BTreeMap::new()).unwrap();
        let text = write(&cut, gear);
        let back = parse(text.as_bytes(), "r.asc")
            .unwrap()
            .to_cut("r")
            .unwrap();
        let s = 1.0 / outline_size(cut.solid.vertices()).1;
        let want: Vec<FacetPlane> = cut
            .solid
            .facet_planes()
            .into_iter()
            .map(|mut p| {
                p.plane.offset *= s;
                p
            })
            .collect();
        same_planes(&want, &back.solid.facet_planes(), 1e-7)
            .unwrap_or_else(|e| panic!("gear {gear}: {e}\n{text}"));
        // Tiers survive.
        let tiers: HashSet<&str> = back
            .solid
            .facets()
            .iter()
            .map(|f| f.tier.as_str())
            .collect();
        for t in [
            "table",
            "bezel",
            "star",
            "upper-half",
            "girdle",
            "pavilion-main",
            "lower-half",
        ] {
            assert!(tiers.contains(t), "tier {t} lost");
        }
    }

    #[test]
    fn asc_write_read_round_trip() {
        round_trip(96);
        // On an 80 gear the halves sit between teeth: fractional indices.
        round_trip(80);
        let cut = Cut::from_family("r", "round-brilliant", &BTreeMap::new()).unwrap();
        let text = write(&cut, 80);
        assert!(text.contains(" 22.5"), "{text}");
        let text = write(&cut, 96);
        assert!(text.starts_with("GemCad 5.0\ng 96 0.0\n"), "{text}");
        assert!(text.contains("a 0.000000 "), "{text}");
    }

    /// A gear-80 design of our own with every kind of metadata GemCad writes.
    const STAR80: &str = "GemCad 5.0
g 80 0.0
y 5 y
I 1.61
H Test Star 80
H by facetlab tests
a -41.000000 0.66000000 80 n P 16 32 48 64 G Cut to a point
a -90.000000 1.00000000 80 n G 16 32 48 64 8 24 40 56 72 G Size stone
a -43.000000 0.68000000 8 n Q 24 40 56 72 G Meet P, G
a 40.000000 0.80000000 80 n A 16 32 48 64 8 24 40 56 72 G Set girdle thickness
a 0.000000 0.55000000 80 n T
F Leave the table polished
";

    #[test]
    fn asc_design_keeps_its_record_and_comes_back_byte_for_byte() {
        let d = parse(STAR80.as_bytes(), "star80.asc").unwrap();
        let cut = d.to_cut("star80").unwrap();
        let rec = cut.record.as_ref().unwrap();
        assert_eq!((rec.gear, rec.gear_offset), (80.0, 0.0));
        assert_eq!((rec.symmetry, rec.mirror, rec.ri), (5, true, Some(1.61)));
        assert_eq!(rec.title, vec!["Test Star 80", "by facetlab tests"]);
        assert_eq!(rec.footnotes, vec!["Leave the table polished"]);
        assert_eq!(
            rec.instructions.get("P-1").map(String::as_str),
            Some("Cut to a point")
        );
        assert_eq!(rec.instructions.len(), 4);
        assert_eq!(cut.design_ri(), Some(1.61));
        // Its own gear, whole indices, its own distances, one line per tier: the same text.
        assert_eq!(write(&cut, 0), STAR80);
        // Asked for another gear, the azimuths keep their places: 80-gear index 8 is 9.6 on 96.
        let on96 = write(&cut, 96);
        assert!(
            on96.contains("g 96 0.0") && on96.contains(" 9.6 n Q"),
            "{on96}"
        );
        let back = parse(on96.as_bytes(), "x").unwrap();
        same_planes(&d.planes, &back.planes, 1e-9).unwrap();
    }

    #[test]
    fn asc_designs_survive_asc_to_asc() {
        // MINI (gear 96, a culet written `a 0 -d`, `n G` as a name), the messy variant and a
        // design on a gear with an offset and a fractional index.
        let shifted = "g 64 64.0\ny 1 n\nI 1.54\nH Shifted\na -90.00 1.00000 16 48\n\
                       a -90.00 0.9 0 32\na -42 0.75 0 16 32 48\na 0.00 -0.6 0\n\
                       a 38.5 0.85 0 16 32 48 8.5\na 0 0.4 0\nF note\n";
        for (name, bytes) in [
            ("mini", MINI.as_bytes().to_vec()),
            ("messy", messy()),
            ("shifted", shifted.as_bytes().to_vec()),
        ] {
            let d = parse(&bytes, name).unwrap();
            let cut = d.to_cut(name).unwrap();
            let text = write(&cut, 0);
            let e = parse(text.as_bytes(), name).unwrap();
            same_planes(&d.planes, &e.planes, 1e-7)
                .unwrap_or_else(|m| panic!("{name}: {m}\n{text}"));
            assert_eq!(
                (&d.title, &d.footnotes, d.ri, d.gear, d.symmetry, d.mirror),
                (&e.title, &e.footnotes, e.ri, e.gear, e.symmetry, e.mirror),
                "{name}"
            );
            assert_eq!(
                d.gear_offset.rem_euclid(d.gear),
                e.gear_offset.rem_euclid(e.gear)
            );
            let tiers = |x: &AscDesign| {
                let mut t: Vec<String> = x.planes.iter().map(|p| p.tier.clone()).collect();
                t.sort();
                t.dedup();
                t
            };
            assert_eq!(tiers(&d), tiers(&e), "{name}");
            assert_eq!(d.instructions, e.instructions, "{name}");
            let names: Vec<&str> = d.planes.iter().map(|p| p.name.as_str()).collect();
            let names2: Vec<&str> = e.planes.iter().map(|p| p.name.as_str()).collect();
            let (mut a, mut b) = (names.clone(), names2.clone());
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b, "{name}");
            // Written again: the same text.
            assert_eq!(write(&e.to_cut(name).unwrap(), 0), text, "{name}");
        }
    }

    #[test]
    fn asc_tier_angle_written_once_at_cutters_precision() {
        for preset in [
            "tolkowsky",
            "gia-reference",
            "princess",
            "marquise",
            "emerald",
        ] {
            let cut = crate::io::load_cut(preset).unwrap();
            let text = write(&cut, 0);
            let mut seen: Vec<(String, String, String)> = Vec::new();
            for l in text.lines().filter(|l| l.starts_with("a ")) {
                let w: Vec<&str> = l.split_whitespace().collect();
                let decimals = w[1].split('.').nth(1).map_or(0, str::len);
                assert!(decimals <= 6, "{preset}: {l}");
                let tier = l
                    .split(" n ")
                    .nth(1)
                    .map_or("", |t| t.split(' ').next().unwrap_or(""));
                let key = (tier.to_string(), w[1].to_string(), w[2].to_string());
                assert!(!seen.contains(&key), "{preset}: tier split: {l}");
                seen.push(key);
            }
            if preset == "tolkowsky" || preset == "gia-reference" {
                // One line per tier: one angle, one distance.
                for t in ["bezel", "star", "upper-half", "pavilion-main", "lower-half"] {
                    assert_eq!(seen.iter().filter(|k| k.0 == t).count(), 1, "{t}\n{text}");
                }
            }
            // Indices on the gear are whole numbers.
            if preset == "tolkowsky" {
                assert!(!text.contains(".5 ") && text.contains(" 93"), "{text}");
            }
        }
    }

    #[test]
    fn asc_cutting_instructions_pavilion_first_at_cutters_precision() {
        let cut = parse(STAR80.as_bytes(), "s").unwrap().to_cut("s").unwrap();
        let c = cutting_instructions(&cut, 0);
        assert_eq!((c.gear, c.ri), (80.0, Some(1.61)));
        let order: Vec<(&str, &str, f64)> = c
            .steps
            .iter()
            .map(|s| (s.side, s.tier.as_str(), s.angle))
            .collect();
        assert_eq!(
            order,
            [
                ("pavilion", "P", 41.0),
                ("pavilion", "G", 90.0),
                ("pavilion", "Q", 43.0),
                ("crown", "A", 40.0),
                ("crown", "T", 0.0)
            ]
        );
        assert_eq!(c.steps[2].indices, ["8", "24", "40", "56", "72"]);
        assert_eq!(c.steps[2].note.as_deref(), Some("Meet P, G"));
        let text = c.text();
        assert!(text.contains("gear 80 (offset 0), index 1.61"), "{text}");
        assert!(
            text.contains("  43.00°  08-24-40-56-72  Meet P, G"),
            "{text}"
        );
        assert!(text.find("PAVILION") < text.find("CROWN"), "{text}");
        // A preset: angles at 0.01°, no long decimals anywhere.
        let cut = crate::io::load_cut("marquise").unwrap();
        let c = cutting_instructions(&cut, 0);
        for s in &c.steps {
            assert_eq!(s.angle, (s.angle * 100.0).round() / 100.0);
        }
        assert!(
            c.text().lines().all(|l| !l.contains("00000")),
            "{}",
            c.text()
        );
    }

    #[test]
    fn asc_culet_round_trips_as_gemcad_writes_it() {
        let mut v = BTreeMap::new();
        v.insert("culet".to_string(), 0.03);
        let cut = Cut::from_family("r", "round-brilliant", &v).unwrap();
        let text = write(&cut, 96);
        // The culet is written GemCad's way, `a 0 -d`, and named `culet` again when read.
        let culet = text.lines().find(|l| l.starts_with("a 0.000000 -"));
        assert!(culet.is_some(), "{text}");
        let back = parse(text.as_bytes(), "r.asc")
            .unwrap()
            .to_cut("r")
            .unwrap();
        assert_eq!(back.solid.facets().len(), cut.solid.facets().len());
    }

    #[test]
    fn asc_broken_lines_name_file_and_line() {
        let bad = "GemCad 5.0\ng 96 0.0\n\na 34 0.5 3 9\na x3 0.5 3\n";
        let e = parse(bad.as_bytes(), "design.asc").unwrap_err().to_string();
        assert_eq!(e, "design.asc:5: angle \"x3\" is not a number; expected `a ANGLE DISTANCE INDEX [INDEX …] [n NAME] [G INSTRUCTIONS]`");
        // A bad index on a continuation line names that line.
        let e = parse(b"a 34 0.5 3 9\n15 2x\n", "d.asc")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("d.asc:2: index \"2x\""), "{e}");
        for (src, want) in [
            ("a 34\n", "d.asc:1: facet line has no distance"),
            (
                "a 34 0.5\n",
                "d.asc:1: facet line at angle 34 has no gear index",
            ),
            ("a 95 0.5 3\n", "d.asc:1: angle 95 is out of range"),
            ("a 34 nan 3\n", "d.asc:1: distance \"nan\" is not a number"),
            ("a 34 0.5 3 n\n", "d.asc:1: `n` must be followed"),
            ("g 0 0\n", "d.asc:1: gear \"0\" is not allowed"),
            ("y x\n", "d.asc:1: symmetry"),
            ("I -1\n", "d.asc:1: refractive index"),
        ] {
            let e = parse(src.as_bytes(), "d.asc").unwrap_err().to_string();
            assert!(e.starts_with(want), "{src:?} gave {e}");
            assert!(!e.contains('\n'));
        }
    }

    #[test]
    fn asc_facet_off_the_solid_is_an_error() {
        let src = format!("{MINI}a 20.000000 5.000000 7 n X\n");
        let d = parse(src.as_bytes(), "far.asc").unwrap();
        let e = d.to_cut("far").unwrap_err().to_string();
        assert!(
            e.contains("far") && e.contains("X") && e.contains("never touches"),
            "{e}"
        );
        // Not enough planes for a solid.
        assert!(parse(b"a 34 1 3 9", "x").unwrap().to_cut("x").is_err());
    }

    #[test]
    fn asc_read_names_cut_after_file_and_reports_missing_file() {
        let dir = std::env::temp_dir().join(format!("facetlab-asc-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("mini brilliant.asc");
        std::fs::write(&p, MINI).unwrap();
        let cut = read(&p).unwrap();
        assert_eq!(cut.name, "mini brilliant");
        assert_eq!(cut.solid.facets().len(), 34);
        let e = read(&dir.join("missing.asc")).unwrap_err().to_string();
        assert!(e.contains("missing.asc"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// No-panic test: every prefix of a messy file, and the file with each byte garbled, either
    /// parses or fails with one line naming the file (and the cut, for the solid's errors).
    #[test]
    fn asc_no_panic_on_truncated_or_garbled_input() {
        let check = |bytes: &[u8]| -> bool {
            match parse(bytes, "garbled.asc") {
                Ok(d) => match d.to_cut("garbled-cut") {
                    Ok(_) => true,
                    Err(e) => {
                        let e = e.to_string();
                        assert!(!e.contains('\n') && e.contains("garbled-cut"), "{e}");
                        false
                    }
                },
                Err(e) => {
                    let e = e.to_string();
                    assert!(!e.contains('\n') && e.starts_with("garbled.asc"), "{e}");
                    false
                }
            }
        };
        let bytes = messy();
        let (mut built, mut failed) = (0, 0);
        for n in 0..=bytes.len() {
            let mut g = bytes.clone();
            if let Some(b) = g.get_mut(n) {
                *b = b.wrapping_mul(7).wrapping_add(0x81);
            }
            for ok in [check(&bytes[..n]), check(&g)] {
                if ok {
                    built += 1;
                } else {
                    failed += 1;
                }
            }
        }
        // Both outcomes occur: the loop exercised the error paths and the builder.
        assert!(built > 0 && failed > 0, "{built} built, {failed} failed");
    }
}
