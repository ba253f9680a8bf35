//! Triangle meshes in and out: Wavefront OBJ and STL (ASCII and binary).
//!
//! Reading: a mesh is taken as the convex hull of its vertices (the vertices its faces use, or
//! every `v` when an OBJ file has no faces), but only if the mesh is convex: every vertex must
//! lie on the hull's surface within [`CONVEX_TOL`] of the size (the largest side of the
//! vertices' bounding box). A vertex deeper inside is a dent, and the file is refused with the
//! largest depth found. The hull's coplanar triangles are merged into one facet per plane, with
//! a tolerance of `1e-7` of the size, widened for coarse coordinates (single-precision binary
//! STL, or text printed with few digits) to eight times their rounding error, at most `1e-4`.
//!
//! Welding (binary STL only): single-precision coordinates split a point where many facets meet
//! (a pointed culet, the girdle corners) into a cluster of vertices with tiny edges between
//! them. After normalisation, vertices joined by an edge shorter than 16 times the merge
//! tolerance, at most `1e-5` (of the solid's largest bounding-box side, about 4e-6 girdle
//! diameters for a binary STL), are welded into their cluster's mean point: a facet touching
//! one cluster is moved parallel to itself through it, one touching several is fitted again
//! through its welded corners, facets left with fewer than three corners are dropped, and this
//! is repeated (at most 8 rounds) while corners are still split. [`read_with_note`] says what
//! was welded (`facetlab info` prints it on standard error).
//!
//! Normalisation (the README's Conventions section: z up, origin at the centre of the girdle
//! plane, girdle diameter 1): the stone is assumed to be upright (z up, table on
//! top). The origin moves to the centre of the girdle plane: horizontally to the centre of the
//! outline's bounding box; vertically to the middle of the girdle, i.e. of the near-vertical
//! facets (normals within 1° of horizontal, the same rule [`crate::cut::Proportions`] uses to
//! measure the girdle) or, for a knife-edge girdle, the middle of the vertices at the largest
//! distance from the vertical axis. The solid is then scaled so that its width W (the outline's
//! smaller extent along x and y, the unit every preset is built in, [`crate::cut::units`]) is 1.
//!
//! Facets are named `f-1`, `f-2`, … in the order table, crown, girdle, pavilion, culet (then by
//! angle and azimuth), and their tier is that side: `table` and `culet` are the horizontal
//! facets, `girdle` the ones within 1° of vertical, `crown` and `pavilion` the rest above and
//! below.
//!
//! Writing: OBJ with the solid's welded vertices and one polygon per facet (a `g` group named
//! after the facet), and STL (binary, or ASCII with [`write_stl_ascii`]) with each facet
//! triangulated as a fan. Coordinates are written in full precision (binary STL: single
//! precision, as the format has it).
//!
//! Files: `obj.rs` reads and writes OBJ, `stl.rs` STL; `normalise.rs` turns the vertices into
//! named facet planes (hull, convexity check, girdle frame, tiers).

mod normalise;
mod obj;
mod stl;
#[cfg(test)]
mod tests;

pub use obj::{read_obj, write_obj, write_obj_objects};
pub use stl::{read_stl, write_stl, write_stl_ascii};

use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::geometry::{DVec3, FacetPlane, Polyhedron};
use std::collections::HashSet;
use std::path::Path;

/// Largest allowed depth of a mesh vertex inside its convex hull, as a fraction of the size.
pub const CONVEX_TOL: f64 = 1e-3;

/// Where a mesh vertex came from, for messages.
#[derive(Clone, Copy, Debug)]
enum Loc {
    Line(usize),
    Triangle(usize),
}

impl Loc {
    fn describe(self) -> String {
        match self {
            Loc::Line(n) => format!("line {n}"),
            Loc::Triangle(n) => format!("triangle {n}"),
        }
    }
}

/// Mesh vertices with their origin and an estimate of the coordinates' rounding error
/// (relative: absolute error / largest absolute coordinate).
struct Points {
    pts: Vec<DVec3>,
    locs: Vec<Loc>,
    rel_noise: f64,
    /// Single-precision coordinates (binary STL): corners split by rounding are welded.
    single_precision: bool,
}

impl Points {
    fn new() -> Points {
        Points {
            pts: Vec::new(),
            locs: Vec::new(),
            rel_noise: 0.0,
            single_precision: false,
        }
    }
    /// Add a point unless the very same point is already there.
    fn push(&mut self, p: DVec3, loc: Loc, seen: &mut HashSet<[u64; 3]>) {
        let key = [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits());
        if seen.insert(key) {
            self.pts.push(p);
            self.locs.push(loc);
        }
    }
}

/// Parse a decimal number and count its significant digits.
fn number(tok: &str) -> Option<(f64, u32)> {
    let v: f64 = tok.parse().ok()?;
    let mantissa = tok.split(['e', 'E']).next().unwrap_or("");
    let digits = mantissa.trim_start_matches(['+', '-', '0', '.']);
    let sig = digits.chars().filter(|c| c.is_ascii_digit()).count() as u32;
    Some((v, sig))
}

/// Relative rounding error of text written with at most `sig` significant digits.
fn text_noise(max_sig: u32) -> f64 {
    0.5 * 10f64.powi(1 - max_sig.clamp(1, 30) as i32)
}

/// Two significant digits, for messages.
fn sig2(x: f64) -> String {
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
fn quote(tok: &str) -> String {
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

fn at(source: &str, line: usize) -> String {
    format!("{source}:{line}")
}

fn hull_error(e: Error, source: &str) -> Error {
    match e {
        Error::Geometry(m) => Error::parse(source, format!("convex hull of the mesh: {m}")),
        other => other,
    }
}

/// Read a mesh file (`.obj` or `.stl`, by extension) as a cut named after the file stem.
pub fn read(path: impl AsRef<Path>) -> Result<Cut> {
    read_with_note(path).map(|(cut, _)| cut)
}

/// [`read`], also returning a one-line note of what was welded, if anything (see the module
/// documentation).
pub fn read_with_note(path: impl AsRef<Path>) -> Result<(Cut, Option<String>)> {
    let path = path.as_ref();
    let shown = path.display().to_string();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    type Reader = fn(&[u8], &str) -> Result<(Vec<FacetPlane>, Option<String>)>;
    let reader: Reader = match ext.as_str() {
        "obj" => obj::read_obj_noted,
        "stl" => stl::read_stl_noted,
        _ => {
            return Err(Error::parse(
                shown,
                format!("unknown mesh format `.{ext}`; allowed: .obj, .stl"),
            ))
        }
    };
    let bytes = std::fs::read(path).map_err(|e| Error::io(&shown, e))?;
    let (planes, note) = reader(&bytes, &shown)?;
    let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("mesh");
    let solid = Polyhedron::from_planes(&planes).map_err(|e| hull_error(e, &shown))?;
    let cut = Cut {
        name: name.to_string(),
        family: None,
        params: Default::default(),
        solid,
        record: None,
    };
    Ok((cut, note))
}

/// A name usable as one OBJ/STL token: whitespace and control characters become `_`.
fn token(name: &str, fallback: &str) -> String {
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
