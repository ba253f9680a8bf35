//! STL, binary and ASCII: reading triangles' vertices, writing each facet as a triangle fan.

use super::normalise::planes_from_points;
use super::{at, number, quote, text_noise, token, Loc, Points};
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::geometry::{DVec3, FacetPlane, Polyhedron};
use std::collections::HashSet;
use std::fmt::Write as _;

/// Read an STL file's bytes, binary or ASCII, as the facet planes of its convex hull,
/// normalised to the conventions (see the module documentation).
///
/// A file is binary when its size is 84 + 50·n bytes with n the triangle count in its header
/// (whatever its first bytes say: some binary files start with `solid` too); otherwise it must
/// be ASCII STL, starting with `solid`.
pub fn read_stl(bytes: &[u8], source: &str) -> Result<Vec<FacetPlane>> {
    read_stl_noted(bytes, source).map(|(planes, _)| planes)
}

/// [`read_stl`], also returning what was welded (see the module documentation).
pub(super) fn read_stl_noted(
    bytes: &[u8],
    source: &str,
) -> Result<(Vec<FacetPlane>, Option<String>)> {
    let points = if let Some(n) = binary_stl_count(bytes) {
        read_binary_stl(bytes, n, source)?
    } else if bytes.trim_ascii_start().starts_with(b"solid") {
        read_ascii_stl(bytes, source)?
    } else {
        let size = if bytes.len() >= 84 {
            let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
            format!("its header says {n} triangles, so {} bytes", 84 + 50 * n)
        } else {
            "at least 84 bytes".to_string()
        };
        return Err(Error::parse(
            source,
            format!(
                "not an STL file: binary STL is 84 + 50·n bytes ({size}, but the file has {}) and ASCII STL starts with `solid`",
                bytes.len()
            ),
        ));
    };
    planes_from_points(&points, source)
}

pub(super) fn binary_stl_count(bytes: &[u8]) -> Option<usize> {
    if bytes.len() < 84 {
        return None;
    }
    let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
    (84 + 50 * n == bytes.len() as u64).then_some(n as usize)
}

fn read_binary_stl(bytes: &[u8], n: usize, source: &str) -> Result<Points> {
    let mut points = Points::new();
    points.rel_noise = f64::from(f32::EPSILON) / 2.0;
    points.single_precision = true;
    let mut seen = HashSet::new();
    for t in 0..n {
        let rec = &bytes[84 + 50 * t..84 + 50 * (t + 1)];
        let f = |k: usize| {
            let o = 12 + 4 * k;
            f64::from(f32::from_le_bytes([
                rec[o],
                rec[o + 1],
                rec[o + 2],
                rec[o + 3],
            ]))
        };
        for v in 0..3 {
            let p = DVec3::new(f(3 * v), f(3 * v + 1), f(3 * v + 2));
            if !p.is_finite() {
                return Err(Error::parse(
                    source,
                    format!(
                        "triangle {} has a vertex coordinate that is not a finite number",
                        t + 1
                    ),
                ));
            }
            points.push(p, Loc::Triangle(t + 1), &mut seen);
        }
    }
    Ok(points)
}

fn read_ascii_stl(bytes: &[u8], source: &str) -> Result<Points> {
    let mut points = Points::new();
    let mut seen = HashSet::new();
    let mut max_sig = 1u32;
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line_no = i + 1;
        let text = String::from_utf8_lossy(raw);
        let mut toks = text.split_whitespace();
        let Some(key) = toks.next() else { continue };
        match key {
            "vertex" => {
                let mut c = [0.0; 3];
                for (k, slot) in c.iter_mut().enumerate() {
                    let Some(tok) = toks.next() else {
                        return Err(Error::parse(
                            at(source, line_no),
                            format!("a vertex needs 3 coordinates (`vertex x y z`), got {k}"),
                        ));
                    };
                    match number(tok) {
                        Some((v, sig)) if v.is_finite() => {
                            max_sig = max_sig.max(sig);
                            *slot = v;
                        }
                        _ => {
                            return Err(Error::parse(
                                at(source, line_no),
                                format!(
                                    "`{}` is not a finite number; a vertex is `vertex x y z`",
                                    quote(tok)
                                ),
                            ))
                        }
                    }
                }
                points.push(DVec3::from_array(c), Loc::Line(line_no), &mut seen);
            }
            "solid" | "facet" | "outer" | "endloop" | "endfacet" | "endsolid" => {}
            other => {
                let shown = quote(other);
                return Err(Error::parse(
                    at(source, line_no),
                    format!(
                        "unexpected `{shown}`; ASCII STL has only solid, facet normal, outer loop, vertex, endloop, endfacet, endsolid lines (binary STL is 84 + 50·n bytes)"
                    ),
                ));
            }
        }
    }
    points.rel_noise = text_noise(max_sig);
    Ok(points)
}

/// Triangles of every facet (fans over the convex facet polygons) with the facet's normal.
fn triangles(s: &Polyhedron) -> Vec<(DVec3, [DVec3; 3])> {
    let mut out = Vec::new();
    for (i, f) in s.facets().iter().enumerate() {
        let p = s.facet_polygon(i);
        for k in 1..p.len().saturating_sub(1) {
            out.push((f.plane.normal, [p[0], p[k], p[k + 1]]));
        }
    }
    out
}

/// The cut as a binary STL: an 80-byte header (not starting with `solid`), the triangle count
/// and each facet triangulated as a fan, in single precision.
pub fn write_stl(cut: &Cut) -> Vec<u8> {
    let tris = triangles(&cut.solid);
    let mut out = Vec::with_capacity(84 + 50 * tris.len());
    let mut header = format!("facetlab binary STL: {}", token(&cut.name, "cut")).into_bytes();
    header.resize(80, 0);
    out.extend_from_slice(&header);
    out.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    for (n, t) in &tris {
        for v in std::iter::once(n).chain(t.iter()) {
            for c in v.to_array() {
                out.extend_from_slice(&(c as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    out
}

/// The cut as an ASCII STL text, each facet triangulated as a fan, in full precision.
pub fn write_stl_ascii(cut: &Cut) -> String {
    let name = token(&cut.name, "cut");
    let mut out = format!("solid {name}\n");
    for (n, t) in triangles(&cut.solid) {
        let _ = writeln!(out, "  facet normal {:e} {:e} {:e}", n.x, n.y, n.z);
        let _ = writeln!(out, "    outer loop");
        for v in t {
            let _ = writeln!(out, "      vertex {:e} {:e} {:e}", v.x, v.y, v.z);
        }
        let _ = writeln!(out, "    endloop");
        let _ = writeln!(out, "  endfacet");
    }
    let _ = writeln!(out, "endsolid {name}");
    out
}
