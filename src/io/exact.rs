//! A cut's exact bytes: every number of the cut bit for bit (its solid's vertices, planes,
//! areas and centroids, its family's parameters, its GemCad record), its names and notes, so
//! that a cut sent to another process ([`cut_bytes`], [`cut_from_bytes`]) gives the same
//! numbers there as here. The cut files do not: `.asc` and `.gem` give angles on the gear's
//! indices and depths to a few decimals, a mesh's reader rebuilds the hull (its planes and
//! areas) from the vertices, and a TOML spec rebuilds the solid from the family's parameters
//! (a rescaled or placed solid then differs in its last bits).
//!
//! Why the solid and not a recipe (a preset's name, a file's bytes, a family's parameters and
//! the `--set` changes, replayed on the other side): every cut has its solid, while a cut a
//! plan placed, or one rescaled, has no recipe that gives it bit for bit; the other side needs
//! no file; and restoring is cheaper than rebuilding (a Tolkowsky: 11.6 kB, restored in 26 µs,
//! 12 times faster than its preset is rebuilt and 77 times faster than its `.asc` is read and
//! re-angled; release build, medians of 9). The price is size: a recipe would be the `.asc`'s
//! 0.5 kB.
//!
//! The layout (little-endian): the magic `facetlab-cut` and a version byte; the name; the
//! family (a flag, then the text); the parameters (a count, then key and value each); the
//! record (a flag, then its fields in order); the vertices (a count, then x, y, z each); the
//! facets (a count, then the plane's normal and offset, name, tier, the polygon's vertex
//! indices, area and centroid each). Text is a length and UTF-8 bytes.

use crate::cut::{Cut, GemcadRecord};
use crate::error::{Error, Result};
use crate::geometry::{DVec3, Facet, Plane, Polyhedron};
use std::collections::BTreeMap;

const MAGIC: &[u8] = b"facetlab-cut";
const VERSION: u8 = 1;

/// The cut's exact bytes (see the module's documentation).
///
/// ```
/// use facetlab::io::{exact, load_cut};
/// let cut = load_cut("tolkowsky").unwrap();
/// let back = exact::cut_from_bytes(&exact::cut_bytes(&cut)).unwrap();
/// assert_eq!(back.solid, cut.solid);
/// assert_eq!((back.name, back.family, back.params), (cut.name, cut.family, cut.params));
/// ```
pub fn cut_bytes(cut: &Cut) -> Vec<u8> {
    // In the order `cut_from_bytes` reads them; its struct literals name every field.
    let Cut {
        name,
        family,
        params,
        solid,
        record,
    } = cut;
    let mut w = Writer(Vec::with_capacity(64 * solid.facets().len() + 256));
    w.0.extend_from_slice(MAGIC);
    w.0.push(VERSION);
    w.text(name);
    w.option(family.as_ref(), |w, f| w.text(f));
    w.count(params.len());
    for (k, v) in params {
        w.text(k);
        w.f64(*v);
    }
    w.option(record.as_ref(), |w, r| w.record(r));
    w.count(solid.vertices().len());
    for v in solid.vertices() {
        w.vec3(*v);
    }
    w.count(solid.facets().len());
    for f in solid.facets() {
        w.vec3(f.plane.normal);
        w.f64(f.plane.offset);
        w.text(&f.name);
        w.text(&f.tier);
        w.count(f.vertices.len());
        for &i in &f.vertices {
            w.count(i);
        }
        w.f64(f.area);
        w.vec3(f.centroid);
    }
    w.0
}

/// The cut of [`cut_bytes`]' bytes, every number as it was. Bytes that are not such a cut
/// (another version, cut short, or a solid that fails [`Polyhedron::from_parts`]' checks)
/// are an error naming `cut bytes`.
pub fn cut_from_bytes(bytes: &[u8]) -> Result<Cut> {
    let mut r = Reader { bytes, at: 0 };
    if r.take(MAGIC.len())? != MAGIC {
        return Err(r.bad("not a facetlab cut"));
    }
    let version = r.take(1)?[0];
    if version != VERSION {
        return Err(r.bad(&format!(
            "version {version}; this facetlab reads version {VERSION} (use the same facetlab on both sides)"
        )));
    }
    let name = r.text()?;
    let family = r.option(|r| r.text())?;
    let mut params = BTreeMap::new();
    for _ in 0..r.count()? {
        let k = r.text()?;
        params.insert(k, r.f64()?);
    }
    let record = r.option(|r| r.record())?;
    let n = r.count()?;
    let vertices = (0..n).map(|_| r.vec3()).collect::<Result<Vec<_>>>()?;
    let n = r.count()?;
    let mut facets = Vec::with_capacity(n.min(bytes.len()));
    for _ in 0..n {
        let normal = r.vec3()?;
        let offset = r.f64()?;
        let name = r.text()?;
        let tier = r.text()?;
        let k = r.count()?;
        let polygon = (0..k).map(|_| r.index()).collect::<Result<Vec<_>>>()?;
        facets.push(Facet {
            plane: Plane { normal, offset },
            name,
            tier,
            vertices: polygon,
            area: r.f64()?,
            centroid: r.vec3()?,
        });
    }
    if r.at != bytes.len() {
        return Err(r.bad("bytes left over after the cut"));
    }
    let solid = Polyhedron::from_parts(vertices, facets)
        .map_err(|e| Error::invalid("cut bytes", e.to_string()))?;
    Ok(Cut {
        name,
        family,
        params,
        solid,
        record,
    })
}

struct Writer(Vec<u8>);

impl Writer {
    fn f64(&mut self, x: f64) {
        self.0.extend_from_slice(&x.to_bits().to_le_bytes());
    }
    fn vec3(&mut self, v: DVec3) {
        for x in v.to_array() {
            self.f64(x);
        }
    }
    fn count(&mut self, n: usize) {
        self.0.extend_from_slice(&(n as u64).to_le_bytes());
    }
    fn text(&mut self, s: &str) {
        self.count(s.len());
        self.0.extend_from_slice(s.as_bytes());
    }
    fn option<T>(&mut self, x: Option<T>, f: impl FnOnce(&mut Self, T)) {
        self.0.push(u8::from(x.is_some()));
        if let Some(x) = x {
            f(self, x);
        }
    }
    /// The record's fields in the order [`Reader::record`] builds them (its struct literal
    /// names every field, so a field added to the record cannot be left out unnoticed).
    fn record(&mut self, r: &GemcadRecord) {
        self.option(r.ri.as_ref(), |w, x| w.f64(*x));
        for lines in [&r.title, &r.footnotes] {
            self.count(lines.len());
            for l in lines {
                self.text(l);
            }
        }
        self.f64(r.gear);
        self.f64(r.gear_offset);
        self.count(r.symmetry as usize);
        self.0.push(u8::from(r.mirror));
        self.count(r.instructions.len());
        for (k, v) in &r.instructions {
            self.text(k);
            self.text(v);
        }
        self.f64(r.scale);
    }
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn bad(&self, what: &str) -> Error {
        Error::invalid("cut bytes", format!("{what} (at byte {})", self.at))
    }
    fn take(&mut self, n: usize) -> Result<&[u8]> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        let Some(end) = end else {
            return Err(self.bad("cut short"));
        };
        let out = &self.bytes[self.at..end];
        self.at = end;
        Ok(out)
    }
    fn u64(&mut self) -> Result<u64> {
        let b = self.take(8)?;
        Ok(u64::from_le_bytes(b.try_into().expect("8 bytes")))
    }
    fn f64(&mut self) -> Result<f64> {
        Ok(f64::from_bits(self.u64()?))
    }
    fn vec3(&mut self) -> Result<DVec3> {
        Ok(DVec3::new(self.f64()?, self.f64()?, self.f64()?))
    }
    /// A count, at most the bytes left (every counted item takes at least one byte).
    fn count(&mut self) -> Result<usize> {
        let n = self.u64()?;
        match usize::try_from(n) {
            Ok(n) if n <= self.bytes.len() - self.at => Ok(n),
            _ => Err(self.bad("a count beyond the bytes given")),
        }
    }
    /// A vertex's index (checked against the vertices by [`Polyhedron::from_parts`]).
    fn index(&mut self) -> Result<usize> {
        let n = self.u64()?;
        usize::try_from(n).map_err(|_| self.bad("an index beyond any vertex"))
    }
    fn text(&mut self) -> Result<String> {
        let n = self.count()?;
        let b = self.take(n)?.to_vec();
        String::from_utf8(b).map_err(|_| self.bad("text that is not UTF-8"))
    }
    fn option<T>(&mut self, f: impl FnOnce(&mut Self) -> Result<T>) -> Result<Option<T>> {
        match self.take(1)?[0] {
            0 => Ok(None),
            1 => f(self).map(Some),
            _ => Err(self.bad("a flag that is neither 0 nor 1")),
        }
    }
    fn record(&mut self) -> Result<GemcadRecord> {
        let ri = self.option(|r| r.f64())?;
        let mut lines = [Vec::new(), Vec::new()];
        for l in &mut lines {
            for _ in 0..self.count()? {
                l.push(self.text()?);
            }
        }
        let [title, footnotes] = lines;
        let gear = self.f64()?;
        let gear_offset = self.f64()?;
        let symmetry =
            u32::try_from(self.count()?).map_err(|_| self.bad("a symmetry too large"))?;
        let mirror = self.option(|_| Ok(()))?.is_some();
        let mut instructions = BTreeMap::new();
        for _ in 0..self.count()? {
            let k = self.text()?;
            instructions.insert(k, self.text()?);
        }
        Ok(GemcadRecord {
            ri,
            title,
            footnotes,
            gear,
            gear_offset,
            symmetry,
            mirror,
            instructions,
            scale: self.f64()?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Cuts made every way: a preset, a family with parameters, a GemCad design re-angled
    /// with its meets kept, a mesh read back, and a rescaled solid (whose vertices a rebuild
    /// from its planes would not give bit for bit).
    fn cuts() -> Vec<Cut> {
        let preset = crate::io::load_cut("tolkowsky").unwrap();
        let params = BTreeMap::from([("table".to_string(), 0.56)]);
        let family = Cut::from_family("mine", "round-brilliant", &params).unwrap();
        let asc = crate::io::asc::write(&preset, 0);
        let design = crate::io::parse_cut("asc", asc.as_bytes(), "t", "t.asc").unwrap();
        let set = BTreeMap::from([("pavilion-main".to_string(), 41.2)]);
        let reangled = crate::design::with_set(&design, &set).unwrap();
        let obj = crate::io::mesh::write_obj(&preset);
        let mesh = crate::io::parse_cut("obj", obj.as_bytes(), "m", "m.obj").unwrap();
        let mut scaled = family.clone();
        scaled.solid = scaled.solid.scaled(std::f64::consts::PI);
        vec![preset, family, design, reangled, mesh, scaled]
    }

    #[test]
    fn every_number_comes_back_bit_for_bit() {
        for cut in cuts() {
            let bytes = cut_bytes(&cut);
            let back = cut_from_bytes(&bytes).unwrap();
            // The same bytes again: every f64 the same bits (== would let -0.0 pass for 0.0).
            assert_eq!(cut_bytes(&back), bytes, "{}", cut.name);
            assert_eq!(back.solid, cut.solid);
            assert_eq!(back.record, cut.record);
            assert_eq!(back.solid.edges(), cut.solid.edges());
        }
    }

    #[test]
    fn broken_bytes_are_an_error_naming_them_never_a_panic() {
        let bytes = cut_bytes(&crate::io::load_cut("gia-reference").unwrap());
        for n in (0..bytes.len()).step_by(97) {
            let e = cut_from_bytes(&bytes[..n]).unwrap_err().to_string();
            assert!(e.starts_with("cut bytes: "), "{e}");
        }
        let mut longer = bytes.clone();
        longer.push(0);
        assert!(cut_from_bytes(&longer)
            .unwrap_err()
            .to_string()
            .contains("left over"));
        // A vertex moved off its facets' planes, and a byte flipped anywhere.
        let mut moved = bytes.clone();
        let at = bytes.len() / 3;
        moved[at] ^= 0x40;
        let _ = cut_from_bytes(&moved);
        let mut state = 1u64;
        for _ in 0..300 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let mut b = bytes.clone();
            let k = (state >> 33) as usize % b.len();
            b[k] ^= 1 << ((state >> 29) % 8);
            let _ = cut_from_bytes(&b);
        }
        let e = cut_from_bytes(b"facetlab-cut\x09").unwrap_err().to_string();
        assert!(e.contains("version 9"), "{e}");
    }
}
