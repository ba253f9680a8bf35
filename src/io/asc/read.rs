//! The GemCad reader: the bytes of a `.asc` file parsed into an [`AscDesign`] (its `a` lines
//! as [`AscTier`]s, its metadata and its facet planes), and the solid built from it, scaled to
//! W = 1, with the design's [`GemcadRecord`] on the cut.

use super::check::{self, MAX_GEAR, RI_ABOVE, RI_MAX};
use super::decode::{continues, decode, keyword, lines, number};
use super::DEFAULT_GEAR;
use crate::cut::units::outline_size;
use crate::cut::{Cut, GemcadRecord};
use crate::error::{Error, Result};
use crate::geometry::{facet_normal, DVec3, FacetPlane, Plane, Polyhedron};
use std::collections::{BTreeMap, HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};
use std::path::Path;

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
    read_design(path, parse)
}

/// A design file read with `parse` (of a `.asc` or a `.gem`) into a cut named after the file
/// stem; errors name the file.
pub(in crate::io) fn read_design(
    path: &Path,
    parse: fn(&[u8], &str) -> Result<AscDesign>,
) -> Result<Cut> {
    let shown = path.display().to_string();
    let bytes = crate::io::read_bytes(path)?;
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

/// An `a` line being collected: its line number and its tokens with their line numbers.
struct OpenTier<'a> {
    line: usize,
    tokens: Vec<(&'a str, usize)>,
}

/// Why bytes holding a NUL are not a `.asc`.
const BINARY: &str =
    "it holds binary bytes (a GemCad .asc is text); a binary GemCad design is read from a .gem";

/// Parse the bytes of a `.asc` file. `source` names the file in error messages
/// (`design.asc:12: angle "x3" is not a number`).
pub fn parse(text_bytes: &[u8], source: &str) -> Result<AscDesign> {
    // A text file holds no NUL byte; a binary GemCad `.gem` (doubles, whole numbers) does
    // (`crate::io::parse_cut` says so when the bytes read as one).
    if text_bytes.contains(&0) {
        return Err(Error::parse(source, format!("not a GemCad .asc: {BINARY}")));
    }
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
                d.gear = number(g)
                    .filter(|v| *v != 0.0 && v.fract() == 0.0 && v.abs() <= MAX_GEAR)
                    .ok_or_else(|| {
                        Error::parse(
                            at(line),
                            format!("gear {g:?} is not allowed; write `g TEETH OFFSET` with a whole, non-zero tooth count up to {MAX_GEAR} (negative: clockwise), e.g. `g 96 0.0`"),
                        )
                    })?;
                if let Some(o) = it.next() {
                    let v = number(o).ok_or_else(|| {
                        Error::parse(
                            at(line),
                            format!("gear offset {o:?} is not a number; e.g. `g 96 0.0`"),
                        )
                    })?;
                    if let Some(e) = check::offset_problem(v, d.gear) {
                        return Err(Error::parse(at(line), e));
                    }
                    d.gear_offset = v;
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
                // The rule of `--ri`: an index in (1, 10].
                d.ri = Some(
                    number(v)
                        .filter(|n| *n > RI_ABOVE && *n <= RI_MAX)
                        .ok_or_else(|| {
                            Error::parse(
                                at(line),
                                format!("refractive index {v:?} is not allowed; give an index in ({RI_ABOVE}, {RI_MAX}], e.g. `I 1.54`"),
                            )
                        })?,
                );
            }
            'H' => d.title.push(rest.to_string()),
            'F' => d.footnotes.push(rest.to_string()),
            _ => {}
        }
    }
    if let Some(o) = open.take() {
        d.tiers.push(parse_tier(&o, source)?);
    }
    // Indices lie on the gear: from minus the count of teeth (counted back, as GemCad
    // tolerates) to the count.
    let teeth = d.gear.abs();
    for t in &d.tiers {
        if let Some((i, _)) = t
            .indices
            .iter()
            .find(|(i, _)| !(-teeth..=teeth).contains(i))
        {
            return Err(Error::parse(
                at(t.line),
                format!(
                    "index {} is not on the gear; allowed -{teeth} to {teeth} on gear {}",
                    crate::error::shown(*i),
                    d.gear
                ),
            ));
        }
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
pub(in crate::io) fn generated_tier(angle: f64, crown: bool) -> String {
    if angle == 90.0 {
        "girdle".into()
    } else if angle == 0.0 {
        if crown { "table" } else { "culet" }.into()
    } else {
        format!("{}-{angle:.2}", if crown { "crown" } else { "pavilion" })
    }
}

/// One facet of a design before its name is settled: the line (tier) it is on, its plane in
/// the file's units (outward normal, any length; offset along the unit normal) and the name
/// given to it (`n NAME`), if any. Both readers make these: the `.asc` reader from a line's
/// angle, distance and indices, the `.gem` reader from its facet records' plane vectors
/// (`p · x = 1`).
pub(in crate::io) struct RawFacet {
    /// Index of the facet's line in the design's tiers.
    pub line: usize,
    /// Outward normal, of any length: the plane is `normal · x = offset`.
    pub normal: DVec3,
    /// The plane's offset along `normal` (as [`FacetPlane::new`] takes it).
    pub offset: f64,
    /// The facet's own name.
    pub name: Option<String>,
}

/// The tier name of a line: its first name, else the name generated from its angle and side.
pub(in crate::io) fn line_tier(t: &AscTier) -> String {
    let crown = !t.angle.is_sign_negative();
    // A negative distance puts the plane on the other side of the origin.
    let eff_crown = crown != (t.distance < 0.0);
    t.name
        .clone()
        .unwrap_or_else(|| generated_tier(t.angle.abs(), eff_crown))
}

/// Facet planes of all tiers, exact repeats dropped, names made unique; and each line's
/// instructions keyed by the name of its first facet.
fn planes_of(d: &AscDesign) -> (Vec<FacetPlane>, BTreeMap<String, String>) {
    let mut facets = Vec::new();
    for (k, t) in d.tiers.iter().enumerate() {
        let a = t.angle.abs();
        let crown = !t.angle.is_sign_negative();
        // A negative distance puts the plane on the other side of the origin: flip it.
        let flip = t.distance < 0.0;
        for (index, name) in &t.indices {
            let az = -90.0 + 360.0 * (index - d.gear_offset) / d.gear;
            let n = facet_normal(a, az, crown);
            facets.push(RawFacet {
                line: k,
                normal: if flip { -n } else { n },
                offset: t.distance.abs(),
                name: name.clone(),
            });
        }
    }
    assemble(&d.tiers, facets)
}

/// The planes of a design's facets: exact repeats dropped (a repeat cuts nothing; real files
/// have them), each facet named by its own name, else its line's tier name ([`line_tier`]),
/// names made unique; and each line's instructions keyed by the name of its first facet.
/// Repeats are found through a grid on the normals, so a design of thousands of facets is
/// read in linear time.
pub(in crate::io) fn assemble(
    tiers: &[AscTier],
    facets: Vec<RawFacet>,
) -> (Vec<FacetPlane>, BTreeMap<String, String>) {
    let names: Vec<String> = tiers.iter().map(line_tier).collect();
    // The kept facets: plane, line, own name.
    let mut kept: Vec<(Plane, usize, Option<String>)> = Vec::with_capacity(facets.len());
    // Kept planes by their normal's (x, y) on a 1e-6 grid: a repeat (normals within 1e-9)
    // is in the same cell, or in the neighbouring one when it lies within 1e-9 of the cell's
    // edge.
    let cells = |v: f64| {
        let u = v * 1e6;
        let c = u.floor();
        let f = u - c;
        let c = c as i64;
        (c - i64::from(f < 1e-3), c + i64::from(f > 1.0 - 1e-3))
    };
    // Each cell's last kept plane, and each kept plane's predecessor in its cell.
    let mut grid: HashMap<(i64, i64), usize, Fast> =
        HashMap::with_capacity_and_hasher(facets.len(), Fast::default());
    let mut before: Vec<Option<usize>> = Vec::with_capacity(facets.len());
    for f in facets {
        if f.line >= names.len() {
            continue;
        }
        // As `FacetPlane::new`: a plane that is none is kept, to be refused by the solid.
        let plane = Plane::new(f.normal, f.offset).unwrap_or(Plane {
            normal: DVec3::Z,
            offset: f64::NAN,
        });
        let (n, offset) = (plane.normal, plane.offset);
        let ((x0, x1), (y0, y1)) = (cells(n.x), cells(n.y));
        let repeat = (x0..=x1).any(|x| {
            (y0..=y1).any(|y| {
                let mut at = grid.get(&(x, y)).copied();
                while let Some(i) = at {
                    let p = &kept[i].0;
                    if p.normal.distance(n) < 1e-9
                        && (p.offset - offset).abs() < 1e-9 * offset.max(1.0)
                    {
                        return true;
                    }
                    at = before[i];
                }
                false
            })
        });
        if repeat {
            continue;
        }
        let home = ((n.x * 1e6).floor() as i64, (n.y * 1e6).floor() as i64);
        before.push(grid.insert(home, kept.len()));
        kept.push((plane, f.line, f.name));
    }
    let unique = unique_names(
        kept.iter()
            .map(|(_, line, own)| own.as_deref().unwrap_or(&names[*line])),
    );
    let line_of: Vec<usize> = kept.iter().map(|k| k.1).collect();
    let planes: Vec<FacetPlane> = kept
        .into_iter()
        .zip(unique)
        .map(|((plane, line, _), name)| FacetPlane {
            plane,
            name,
            tier: names[line].clone(),
        })
        .collect();
    // The first kept facet of each line.
    let mut first: Vec<Option<usize>> = vec![None; tiers.len()];
    for (i, &l) in line_of.iter().enumerate() {
        first[l].get_or_insert(i);
    }
    let mut instructions = BTreeMap::new();
    for (t, f) in tiers.iter().zip(&first) {
        let Some(text) = t.instructions.as_ref().filter(|s| !s.is_empty()) else {
            continue;
        };
        if let Some(i) = *f {
            instructions.insert(planes[i].name.clone(), text.clone());
        }
    }
    (planes, instructions)
}

/// The hasher of the reader's own maps (the repeat grid's cells, the facet names): one
/// multiply-rotate step per word, as rustc's FxHash does. A design's names and cells need no
/// defence against chosen collisions (a file is read once, its size bounded), and SipHash was
/// a third of the time of reading a large `.gem`.
#[derive(Default)]
struct FastHasher(u64);

type Fast = BuildHasherDefault<FastHasher>;

impl Hasher for FastHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            let mut w = [0u8; 8];
            w.copy_from_slice(c);
            self.write_u64(u64::from_le_bytes(w));
        }
        let mut w = [0u8; 8];
        let rest = chunks.remainder();
        w[..rest.len()].copy_from_slice(rest);
        self.write_u64(u64::from_le_bytes(w) ^ (rest.len() as u64) << 56);
    }
    fn write_u8(&mut self, v: u8) {
        self.write_u64(u64::from(v));
    }
    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(5) ^ v).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    fn write_i64(&mut self, v: i64) {
        self.write_u64(v as u64);
    }
}

/// Names used once stay; names used several times become `NAME-1`, `NAME-2`, … skipping any
/// name already taken.
fn unique_names<'a>(bases: impl Iterator<Item = &'a str> + Clone) -> Vec<String> {
    let mut count: HashMap<&str, usize, Fast> = HashMap::default();
    for b in bases.clone() {
        *count.entry(b).or_default() += 1;
    }
    // A generated `NAME-K` can only meet a name used once: two generated names never meet
    // (the last `-` of one splits it into its base and its number).
    let once: HashSet<&str, Fast> = count
        .iter()
        .filter(|(_, &c)| c == 1)
        .map(|(&b, _)| b)
        .collect();
    let mut next: HashMap<&str, usize, Fast> = HashMap::default();
    bases
        .map(|b| {
            if once.contains(b) {
                return b.to_string();
            }
            let k = next.entry(b).or_default();
            loop {
                *k += 1;
                let cand = format!("{b}-{k}");
                if !once.contains(cand.as_str()) {
                    return cand;
                }
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{facet_angle_deg, facet_azimuth_deg, DVec3};
    use crate::testkit::asc::{messy, same_planes, MINI};

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
        // Table edge midpoints at 0.56 of the girdle radius, on the x and y axes: GemCad's T/W,
        // the table's extent across the width, is flat to flat, 0.56.
        assert!((p.table - 0.56).abs() < 1e-5, "table {}", p.table);
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
