//! A rough's mesh as triangles: OBJ (`v`, `f`) and STL (binary or ASCII), kept as they are
//! (no hull, no normalisation: a rough is planned in its own millimetres), with the checks a
//! rough needs: the mesh must be closed (every edge shared by exactly two triangles) so that
//! its own volume, and so what its convex hull adds, is defined.

use crate::error::{Error, Result};
use crate::geometry::DVec3;
use std::collections::HashMap;

/// A triangle mesh: welded vertices (bit-equal coordinates are one vertex) and triangles.
#[derive(Clone, Debug, Default)]
pub struct TriMesh {
    /// Vertices.
    pub vertices: Vec<DVec3>,
    /// Triangles as vertex indices (polygons are split into fans).
    pub triangles: Vec<[usize; 3]>,
    /// Whether the file says its units are not millimetres (a facetlab OBJ export says
    /// `# units: girdle diameters`).
    pub units_not_mm: bool,
}

impl TriMesh {
    fn vertex(&mut self, p: DVec3, index: &mut HashMap<[u64; 3], usize>) -> usize {
        let key = [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits());
        *index.entry(key).or_insert_with(|| {
            self.vertices.push(p);
            self.vertices.len() - 1
        })
    }

    /// The volume the mesh encloses (divergence theorem over its triangles about its first
    /// vertex, so that a mesh far from the origin loses no digits; sign dropped so either
    /// winding works).
    pub fn enclosed_volume(&self) -> f64 {
        let Some(&o) = self.vertices.first() else {
            return 0.0;
        };
        let v: f64 = self
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.vertices[i] - o);
                a.dot(b.cross(c))
            })
            .sum();
        (v / 6.0).abs()
    }

    /// An error naming `source` if some edge is not shared by exactly two triangles, or if
    /// the triangles' windings disagree (the mesh encloses no volume consistently).
    pub fn check_closed(&self, source: &str) -> Result<()> {
        if self.triangles.is_empty() {
            return Err(Error::parse(
                source,
                "the mesh has no triangles; a rough needs a closed triangle mesh (OBJ `f` lines or STL facets)",
            ));
        }
        let mut edges: HashMap<(usize, usize), i64> = HashMap::new();
        for t in &self.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let e = edges.entry((a.min(b), a.max(b))).or_insert(0);
                // Count directed uses: +1 one way, +1000 the other.
                *e += if a < b { 1 } else { 1000 };
            }
        }
        let open = edges.values().filter(|&&c| c != 1001).count();
        if open > 0 {
            return Err(Error::parse(
                source,
                format!(
                    "the mesh is not closed: {open} of its {} edges are not shared by exactly two consistently wound triangles; a rough must be a closed surface",
                    edges.len()
                ),
            ));
        }
        Ok(())
    }
}

/// Read an `.obj` or `.stl` file's bytes as triangles (`source` names it in messages).
pub fn read_triangles(bytes: &[u8], ext: &str, source: &str) -> Result<TriMesh> {
    match ext {
        "obj" => read_obj(bytes, source),
        "stl" => {
            let n = (bytes.len() >= 84)
                .then(|| u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64);
            match n {
                Some(n) if 84 + 50 * n == bytes.len() as u64 => Ok(binary_stl(bytes, n as usize)),
                _ if bytes.trim_ascii_start().starts_with(b"solid") => ascii_stl(bytes, source),
                _ => Err(Error::parse(
                    source,
                    "not an STL file: binary STL is 84 + 50·n bytes, ASCII STL starts with `solid`",
                )),
            }
        }
        _ => Err(Error::parse(
            source,
            format!("unknown rough format `.{ext}`; allowed: .obj, .stl, or a crystal form (octahedron, dodecahedron, cube, macle)"),
        )),
    }
}

fn coords(toks: &mut std::str::SplitWhitespace, source: &str, line: usize) -> Result<DVec3> {
    let mut c = [0.0; 3];
    for slot in &mut c {
        let tok = toks.next().unwrap_or("");
        *slot = match tok.parse::<f64>() {
            Ok(v) if v.is_finite() => v,
            _ => {
                return Err(Error::parse(
                    format!("{source}:{line}"),
                    format!(
                        "`{}` is not a finite number; a vertex has three coordinates",
                        tok.chars().take(24).collect::<String>()
                    ),
                ))
            }
        };
    }
    Ok(DVec3::from_array(c))
}

fn read_obj(bytes: &[u8], source: &str) -> Result<TriMesh> {
    let mut raw: Vec<DVec3> = Vec::new();
    let mut mesh = TriMesh::default();
    let mut index = HashMap::new();
    let mut map: Vec<usize> = Vec::new();
    for (i, line) in String::from_utf8_lossy(bytes).lines().enumerate() {
        let line_no = i + 1;
        let lower = line.trim().to_ascii_lowercase();
        if lower.starts_with("# units:") && !lower.contains("mm") && !lower.contains("millimet") {
            mesh.units_not_mm = true;
        }
        let text = line.split('#').next().unwrap_or("");
        let mut toks = text.split_whitespace();
        match toks.next() {
            Some("v") => {
                let p = coords(&mut toks, source, line_no)?;
                raw.push(p);
                map.push(mesh.vertex(p, &mut index));
            }
            Some("f") => {
                let mut face = Vec::new();
                for tok in toks {
                    let k: i64 = tok.split('/').next().unwrap_or("").parse().unwrap_or(0);
                    let r = if k < 0 { raw.len() as i64 + k } else { k - 1 };
                    if r < 0 || r as usize >= raw.len() {
                        return Err(Error::parse(
                            format!("{source}:{line_no}"),
                            format!("face vertex `{}` is out of range; indices run from 1 to the {} vertices defined so far", tok.chars().take(24).collect::<String>(), raw.len()),
                        ));
                    }
                    face.push(map[r as usize]);
                }
                if face.len() < 3 {
                    return Err(Error::parse(
                        format!("{source}:{line_no}"),
                        "a face needs at least 3 vertices",
                    ));
                }
                for k in 1..face.len() - 1 {
                    mesh.triangles.push([face[0], face[k], face[k + 1]]);
                }
            }
            _ => {}
        }
    }
    Ok(mesh)
}

fn binary_stl(bytes: &[u8], n: usize) -> TriMesh {
    let mut mesh = TriMesh::default();
    let mut index = HashMap::new();
    for rec in bytes[84..84 + 50 * n].chunks_exact(50) {
        // 12 bytes of normal, then three corners of three little-endian f32 each.
        let c: Vec<f64> = rec[12..48]
            .chunks_exact(4)
            .map(|w| f64::from(f32::from_le_bytes([w[0], w[1], w[2], w[3]])))
            .collect();
        let tri = [0, 3, 6].map(|o| mesh.vertex(DVec3::new(c[o], c[o + 1], c[o + 2]), &mut index));
        mesh.triangles.push(tri);
    }
    mesh
}

fn ascii_stl(bytes: &[u8], source: &str) -> Result<TriMesh> {
    let mut mesh = TriMesh::default();
    let mut index = HashMap::new();
    let mut corners = Vec::new();
    for (i, line) in String::from_utf8_lossy(bytes).lines().enumerate() {
        let mut toks = line.split_whitespace();
        match toks.next() {
            Some("vertex") => {
                let p = coords(&mut toks, source, i + 1)?;
                corners.push(mesh.vertex(p, &mut index));
            }
            Some("endfacet") => {
                if corners.len() != 3 {
                    return Err(Error::parse(
                        format!("{source}:{}", i + 1),
                        format!("a facet needs 3 vertices, got {}", corners.len()),
                    ));
                }
                mesh.triangles.push([corners[0], corners[1], corners[2]]);
                corners.clear();
            }
            _ => {}
        }
    }
    Ok(mesh)
}

impl TriMesh {
    /// The mesh as OBJ text, `comment` on the first line.
    pub fn to_obj(&self, comment: &str) -> String {
        let mut out = format!("# {comment}\n# units: mm\n");
        for v in &self.vertices {
            out.push_str(&format!("v {} {} {}\n", v.x, v.y, v.z));
        }
        for t in &self.triangles {
            out.push_str(&format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1));
        }
        out
    }
}
