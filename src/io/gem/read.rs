//! The `.gem` reader: facet records, the trailer and its strings, each value read at a known
//! byte offset and checked against the bytes left, into an [`AscDesign`].

use super::{snap_angle, END_OF_FACETS, TEXT_SLOTS};
use crate::cut::Cut;
use crate::design::Gear;
use crate::error::{Error, Result};
use crate::geometry::DVec3;
use crate::io::asc::check::{gear_problem, offset_problem, ri_problem};
use crate::io::asc::decode::byte_char;
use crate::io::asc::{assemble, read_design, AscDesign, AscTier, RawFacet};
use std::collections::HashMap;
use std::path::Path;

/// Bytes read in order, each read naming what it reads and failing with the byte offset.
struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
    source: &'a str,
}

impl<'a> Cursor<'a> {
    fn error(&self, at: usize, message: impl Into<String>) -> Error {
        Error::parse(format!("{}: byte {at}", self.source), message)
    }

    fn left(&self) -> usize {
        self.bytes.len() - self.pos
    }

    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8]> {
        if self.left() < n {
            return Err(self.error(
                self.pos,
                format!(
                    "the file ends inside {what} ({n} bytes needed, {} left); the .gem is cut short",
                    self.left()
                ),
            ));
        }
        let out = &self.bytes[self.pos..self.pos + n];
        self.pos += n;
        Ok(out)
    }

    fn array<const N: usize>(&mut self, what: &str) -> Result<[u8; N]> {
        let mut a = [0u8; N];
        a.copy_from_slice(self.take(N, what)?);
        Ok(a)
    }

    fn f64(&mut self, what: &str) -> Result<f64> {
        Ok(f64::from_le_bytes(self.array(what)?))
    }

    fn i32(&mut self, what: &str) -> Result<i32> {
        Ok(i32::from_le_bytes(self.array(what)?))
    }

    fn u16(&mut self, what: &str) -> Result<u16> {
        Ok(u16::from_le_bytes(self.array(what)?))
    }

    fn u32(&mut self, what: &str) -> Result<u32> {
        Ok(u32::from_le_bytes(self.array(what)?))
    }

    /// A length-prefixed Windows-1252 string (see the module docs for the long lengths); the
    /// length is checked against the bytes left before it is read.
    fn string(&mut self, what: &str) -> Result<String> {
        Ok(text(self.string_bytes(what)?))
    }

    /// The bytes of a length-prefixed string.
    fn string_bytes(&mut self, what: &str) -> Result<&'a [u8]> {
        let at = self.pos;
        let mut n = usize::from(self.array::<1>(what)?[0]);
        if n == 0xFF {
            n = usize::from(self.u16(what)?);
            if n == 0xFFFE {
                return Err(self.error(
                    at,
                    format!("{what} is marked as a Unicode string, which GemCad does not write"),
                ));
            }
            if n == 0xFFFF {
                n = usize::try_from(self.u32(what)?).unwrap_or(usize::MAX);
            }
        }
        if n > self.left() {
            return Err(self.error(
                at,
                format!(
                    "{what} of {n} bytes runs past the end of the file ({} bytes left); the .gem is cut short or garbled",
                    self.left()
                ),
            ));
        }
        self.take(n, what)
    }
}

/// Windows-1252 bytes as text.
fn text(bytes: &[u8]) -> String {
    bytes.iter().map(|&b| byte_char(b)).collect()
}

/// One facet record as read: where it starts, its plane vector (in facetlab's frame), its tier
/// number, its own name and its instructions' bytes.
struct Record<'a> {
    at: usize,
    p: DVec3,
    tier: i32,
    name: String,
    instructions: &'a [u8],
}

/// Parse the bytes of a `.gem` file into a design (its planes in the file's units, in
/// facetlab's frame). `source` names the file in errors (`design.gem: byte 1234: …`).
pub fn parse(bytes: &[u8], source: &str) -> Result<AscDesign> {
    let mut c = Cursor {
        bytes,
        pos: 0,
        source,
    };
    let mut records = Vec::new();
    loop {
        let at = c.pos;
        let x = c.f64("a facet record's plane vector (or the end of the facets)")?;
        if x == END_OF_FACETS {
            break;
        }
        let y = c.f64("a facet record's plane vector")?;
        let z = c.f64("a facet record's plane vector")?;
        let p = DVec3::new(x, y, z);
        if !(p.is_finite() && p.length() > 0.0 && p.length().is_finite()) {
            return Err(c.error(
                at,
                format!("facet record: the plane vector ({x}, {y}, {z}) is not a plane (finite, not zero); the .gem is garbled"),
            ));
        }
        let tier = c.i32("a facet record's tier number")?;
        let label = c.string_bytes("a facet's name and instructions")?;
        loop {
            let m_at = c.pos;
            match c.i32("a facet's vertex marker")? {
                0 => break,
                1 => {
                    c.take(24, "a facet's vertex")?;
                }
                other => {
                    return Err(c.error(
                        m_at,
                        format!("expected a vertex marker, 1 (a vertex follows) or 0 (the facet's last vertex), found {other}; the .gem is garbled"),
                    ))
                }
            }
        }
        let (name, instructions) = match label.iter().position(|&b| b == b'\t') {
            Some(k) => (&label[..k], &label[k + 1..]),
            None => (label, &label[label.len()..]),
        };
        records.push(Record {
            at,
            // GemCad's y is facetlab's −y (see the module docs).
            p: DVec3::new(p.x, -p.y, p.z),
            tier,
            name: if name.is_empty() {
                String::new()
            } else {
                text(name).trim().to_string()
            },
            instructions,
        });
    }
    let at = c.pos;
    let symmetry = c.i32("the symmetry")?;
    let symmetry = u32::try_from(symmetry).map_err(|_| {
        c.error(
            at,
            format!("symmetry {symmetry} is not allowed; a fold count is not negative (the .gem is garbled)"),
        )
    })?;
    let at = c.pos;
    let mirror = match c.i32("the mirror flag")? {
        0 => false,
        1 => true,
        other => {
            return Err(c.error(
                at,
                format!("mirror flag {other} is not allowed; 0 or 1 (the .gem is garbled)"),
            ))
        }
    };
    let at = c.pos;
    let gear = f64::from(c.i32("the gear")?);
    if let Some(e) = gear_problem(gear) {
        return Err(c.error(at, e));
    }
    let at = c.pos;
    let ri = c.f64("the refractive index")?;
    if let Some(e) = ri_problem(ri) {
        return Err(c.error(at, e));
    }
    c.u32("the trailer's constant")?;
    let at = c.pos;
    let gear_offset = c.f64("the gear offset")?;
    if let Some(e) = offset_problem(gear_offset, gear) {
        return Err(c.error(at, e));
    }
    let mut text = Vec::with_capacity(2 * TEXT_SLOTS);
    for k in 0..2 * TEXT_SLOTS {
        let what = if k < TEXT_SLOTS {
            "a title line"
        } else {
            "a footnote"
        };
        text.push(c.string(what)?);
    }
    if c.left() > 0 {
        let at = c.pos;
        let next = c.string("the data after the footnotes").ok();
        if !next.is_some_and(|s| s.eq_ignore_ascii_case("preform")) {
            return Err(c.error(
                at,
                format!(
                    "{} bytes after the footnotes that are not a preform; the .gem is garbled",
                    bytes.len() - at
                ),
            ));
        }
    }
    let footnotes = lines(&text[TEXT_SLOTS..]);
    let title = lines(&text[..TEXT_SLOTS]);
    let header = AscDesign {
        title,
        gear,
        gear_offset,
        symmetry,
        mirror,
        ri: Some(ri),
        tiers: Vec::new(),
        planes: Vec::new(),
        footnotes,
        instructions: Default::default(),
    };
    Ok(design(records, header))
}

/// Text slots as lines: trimmed (as the `.asc` reader trims `H` and `F` lines), the empty
/// slots at the end dropped.
fn lines(slots: &[String]) -> Vec<String> {
    let mut out: Vec<String> = slots.iter().map(|s| s.trim().to_string()).collect();
    while out.last().is_some_and(String::is_empty) {
        out.pop();
    }
    out
}

/// The design of the records under `header` (the file's titles, notes, gear, symmetry and
/// index, no tiers yet): one line per tier number (in order of first appearance), its angle,
/// distance, indices, name and instructions derived from its facets.
fn design(records: Vec<Record>, header: AscDesign) -> AscDesign {
    let g = Gear {
        teeth: header.gear,
        offset: header.gear_offset,
    };
    let mut line_of: HashMap<i32, usize> = HashMap::new();
    let mut tiers: Vec<AscTier> = Vec::new();
    let mut facets: Vec<RawFacet> = Vec::with_capacity(records.len());
    for r in records {
        let n = r.p / r.p.length();
        let line = *line_of.entry(r.tier).or_insert_with(|| {
            let tilt = snap_angle(n.x.hypot(n.y).atan2(n.z.abs()).to_degrees());
            tiers.push(AscTier {
                line: r.at,
                // GemCad's sign: negative on the pavilion (a culet `-0`), the girdle −90.
                angle: if n.z < 0.0 { -tilt } else { tilt },
                distance: 1.0 / r.p.length(),
                indices: Vec::new(),
                name: None,
                instructions: None,
            });
            tiers.len() - 1
        });
        let t = &mut tiers[line];
        let own = (!r.name.is_empty()).then_some(r.name);
        if t.name.is_none() {
            t.name.clone_from(&own);
        }
        if t.instructions.is_none() && !r.instructions.trim_ascii().is_empty() {
            // Words joined by one space, as the `.asc` reader joins a `G` line's.
            let words = text(r.instructions);
            t.instructions = Some(words.split_whitespace().collect::<Vec<_>>().join(" "));
        }
        t.indices.push((g.index(n), own.clone()));
        facets.push(RawFacet {
            line,
            normal: r.p,
            offset: 1.0,
            name: own,
        });
    }
    let (planes, instructions) = assemble(&tiers, facets);
    AscDesign {
        tiers,
        planes,
        instructions,
        ..header
    }
}

/// Read a GemCad `.gem` file into a cut named after the file stem, with the design's record
/// (index, titles, notes, gear, symmetry, instructions) in [`Cut::record`], scaled to W = 1 as
/// a `.asc` is.
pub fn read(path: &Path) -> Result<Cut> {
    read_design(path, parse)
}
