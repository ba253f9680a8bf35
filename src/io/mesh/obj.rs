//! Wavefront OBJ: reading vertices and faces, writing one polygon per facet.

use super::normalise::planes_from_points;
use super::{at, number, quote, text_noise, token, Loc, Points};
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::geometry::{DVec3, FacetPlane, Polyhedron};
use std::collections::HashSet;
use std::fmt::Write as _;

/// Read an OBJ file's bytes (`source` names it in messages) as the facet planes of its convex
/// hull, normalised to the conventions (see the module documentation).
///
/// `v x y z` lines give vertices, `f a b c …` lines faces (indices from 1, negative ones count
/// back from the last vertex, `a/t/n` forms allowed); every other line is ignored.
pub fn read_obj(bytes: &[u8], source: &str) -> Result<Vec<FacetPlane>> {
    read_obj_noted(bytes, source).map(|(planes, _)| planes)
}

/// [`read_obj`], also returning what was welded (see the module documentation).
pub(super) fn read_obj_noted(
    bytes: &[u8],
    source: &str,
) -> Result<(Vec<FacetPlane>, Option<String>)> {
    let mut verts: Vec<(DVec3, usize)> = Vec::new();
    let mut refs: Vec<(usize, usize)> = Vec::new(); // (0-based vertex, line)
    let mut max_sig = 1u32;
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line_no = i + 1;
        let text = String::from_utf8_lossy(raw);
        let text = text.split('#').next().unwrap_or("");
        let mut toks = text.split_whitespace();
        match toks.next() {
            Some("v") => {
                let mut c = [0.0; 3];
                for (k, slot) in c.iter_mut().enumerate() {
                    let Some(tok) = toks.next() else {
                        return Err(Error::parse(
                            at(source, line_no),
                            format!("a vertex needs 3 coordinates (`v x y z`), got {k}"),
                        ));
                    };
                    let Some((v, sig)) = number(tok) else {
                        return Err(Error::parse(
                            at(source, line_no),
                            format!(
                                "`{}` is not a number; a vertex is `v x y z` with decimal numbers",
                                quote(tok)
                            ),
                        ));
                    };
                    if !v.is_finite() {
                        return Err(Error::parse(
                            at(source, line_no),
                            format!(
                                "`{}` is not a finite number; vertex coordinates must be finite",
                                quote(tok)
                            ),
                        ));
                    }
                    max_sig = max_sig.max(sig);
                    *slot = v;
                }
                verts.push((DVec3::from_array(c), line_no));
            }
            Some("f") => {
                let mut n = 0;
                for tok in toks {
                    let idx = tok.split('/').next().unwrap_or("");
                    let Ok(k) = idx.parse::<i64>() else {
                        return Err(Error::parse(
                            at(source, line_no),
                            format!("`{}` is not a vertex index; a face is `f a b c …` with indices from 1 (or negative, counting back)", quote(tok)),
                        ));
                    };
                    let resolved = if k > 0 {
                        k - 1
                    } else if k < 0 {
                        verts.len() as i64 + k
                    } else {
                        -1
                    };
                    if resolved < 0 {
                        return Err(Error::parse(
                            at(source, line_no),
                            format!(
                                "face vertex {k} is out of range; indices run from 1 (or back from -1) and {} vertices are defined so far",
                                verts.len()
                            ),
                        ));
                    }
                    refs.push((resolved as usize, line_no));
                    n += 1;
                }
                if n < 3 {
                    return Err(Error::parse(
                        at(source, line_no),
                        format!("a face needs at least 3 vertices, got {n}"),
                    ));
                }
            }
            _ => {}
        }
    }
    let mut points = Points::new();
    points.rel_noise = text_noise(max_sig);
    let mut seen = HashSet::new();
    if refs.is_empty() {
        for (p, line) in &verts {
            points.push(*p, Loc::Line(*line), &mut seen);
        }
    } else {
        for &(k, line) in &refs {
            let Some((p, vline)) = verts.get(k) else {
                return Err(Error::parse(
                    at(source, line),
                    format!(
                        "face vertex {} is out of range; the file has {} vertices",
                        k + 1,
                        verts.len()
                    ),
                ));
            };
            points.push(*p, Loc::Line(*vline), &mut seen);
        }
    }
    planes_from_points(&points, source)
}

/// Solids as named OBJ objects in one file, without a header: for each, `o NAME`, its
/// vertices (`v x y z`, as they are) and one polygon per facet (`f …`), the vertex numbers
/// running on from the objects before it.
pub fn write_obj_objects(objects: &[(&str, &Polyhedron)]) -> String {
    let mut out = String::new();
    let mut base = 0;
    for (name, s) in objects {
        let _ = writeln!(out, "o {name}");
        for v in s.vertices() {
            let _ = writeln!(out, "v {} {} {}", v.x, v.y, v.z);
        }
        for f in s.facets() {
            let idx: Vec<String> = f
                .vertices
                .iter()
                .map(|i| (i + 1 + base).to_string())
                .collect();
            let _ = writeln!(out, "f {}", idx.join(" "));
        }
        base += s.vertices().len();
    }
    out
}

/// The cut as a Wavefront OBJ text: a comment header, the solid's vertices and one polygon face
/// per facet (counter-clockwise seen from outside), each in a group named after the facet.
pub fn write_obj(cut: &Cut) -> String {
    let s = &cut.solid;
    let mut out = String::new();
    let _ = writeln!(out, "# facetlab {} OBJ export", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(out, "# cut: {}", token(&cut.name, "cut"));
    if let Some(f) = &cut.family {
        let params: Vec<String> = cut.params.iter().map(|(k, v)| format!("{k}={v}")).collect();
        let _ = writeln!(out, "# family: {} {}", token(f, "family"), params.join(" "));
    }
    let _ = writeln!(
        out,
        "# units: girdle diameters (D = 1), z up, origin at the centre of the girdle plane"
    );
    let _ = writeln!(
        out,
        "# {} vertices, {} facets (one polygon each, counter-clockwise seen from outside)",
        s.vertices().len(),
        s.facets().len()
    );
    let _ = writeln!(out, "o {}", token(&cut.name, "cut"));
    for v in s.vertices() {
        let _ = writeln!(out, "v {} {} {}", v.x, v.y, v.z);
    }
    for f in s.facets() {
        let _ = writeln!(out, "g {}", token(&f.name, "facet"));
        let idx: Vec<String> = f.vertices.iter().map(|i| (i + 1).to_string()).collect();
        let _ = writeln!(out, "f {}", idx.join(" "));
    }
    out
}
