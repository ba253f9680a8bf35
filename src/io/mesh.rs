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
//! Normalisation (DESIGN.md conventions): the stone is assumed to be upright (z up, table on
//! top). The origin moves to the centre of the girdle plane: horizontally to the centre of the
//! outline's bounding box; vertically to the middle of the girdle, i.e. of the near-vertical
//! facets (normals within 1° of horizontal, the same rule [`crate::cut::Proportions`] uses to
//! measure the girdle) or, for a knife-edge girdle, the middle of the vertices at the largest
//! distance from the vertical axis. The solid is then scaled so that its largest horizontal
//! extent (the largest distance between two vertices seen from above, the outline width
//! `Proportions` uses) is 1.
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

use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::geometry::{
    convex_hull_with_tolerance, facet_angle_deg, facet_azimuth_deg, DVec3, FacetPlane, Plane,
    Polyhedron, MERGE_TOL,
};
use std::collections::HashSet;
use std::fmt::Write as _;
use std::path::Path;

/// Largest allowed depth of a mesh vertex inside its convex hull, as a fraction of the size.
pub const CONVEX_TOL: f64 = 1e-3;

/// Largest merge tolerance used for coarse coordinates (fraction of the size).
const MAX_MERGE_TOL: f64 = 1e-4;

/// sin 1°: facets whose normal is closer than this to horizontal are girdle facets.
const HORIZONTAL: f64 = 0.0175;

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
}

impl Points {
    fn new() -> Points {
        Points {
            pts: Vec::new(),
            locs: Vec::new(),
            rel_noise: 0.0,
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

/// Read an OBJ file's bytes (`source` names it in messages) as the facet planes of its convex
/// hull, normalised to the conventions (see the module documentation).
///
/// `v x y z` lines give vertices, `f a b c …` lines faces (indices from 1, negative ones count
/// back from the last vertex, `a/t/n` forms allowed); every other line is ignored.
pub fn read_obj(bytes: &[u8], source: &str) -> Result<Vec<FacetPlane>> {
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

/// Read an STL file's bytes, binary or ASCII, as the facet planes of its convex hull,
/// normalised to the conventions (see the module documentation).
///
/// A file is binary when its size is 84 + 50·n bytes with n the triangle count in its header
/// (whatever its first bytes say: some binary files start with `solid` too); otherwise it must
/// be ASCII STL, starting with `solid`.
pub fn read_stl(bytes: &[u8], source: &str) -> Result<Vec<FacetPlane>> {
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

fn binary_stl_count(bytes: &[u8]) -> Option<usize> {
    if bytes.len() < 84 {
        return None;
    }
    let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as u64;
    (84 + 50 * n == bytes.len() as u64).then_some(n as usize)
}

fn read_binary_stl(bytes: &[u8], n: usize, source: &str) -> Result<Points> {
    let mut points = Points::new();
    points.rel_noise = f64::from(f32::EPSILON) / 2.0;
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

/// Hull, convexity check, normalisation and naming.
fn planes_from_points(points: &Points, source: &str) -> Result<Vec<FacetPlane>> {
    let pts = &points.pts;
    if pts.len() < 4 {
        return Err(Error::parse(
            source,
            format!(
                "a stone needs at least 4 distinct vertices, the mesh has {}",
                pts.len()
            ),
        ));
    }
    let (mut lo, mut hi) = (pts[0], pts[0]);
    for p in pts {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let size = (hi - lo).max_element();
    let largest = lo.abs().max(hi.abs()).max_element();
    if !size.is_finite() || largest > 1e150 {
        return Err(Error::parse(
            source,
            format!("vertex coordinates up to {largest:e} are too large; allowed up to 1e150"),
        ));
    }
    if !(size.is_finite() && size > 0.0) {
        return Err(Error::parse(
            source,
            "all vertices coincide; a stone needs a solid",
        ));
    }
    let tol = (8.0 * points.rel_noise * largest / size).clamp(MERGE_TOL, MAX_MERGE_TOL);
    let hull = convex_hull_with_tolerance(pts, tol).map_err(|e| hull_error(e, source))?;

    // Convexity: the deepest vertex inside the hull.
    let mut deepest = (0.0, 0usize);
    for (i, p) in pts.iter().enumerate() {
        let depth = hull
            .iter()
            .map(|h| -h.distance(*p))
            .fold(f64::INFINITY, f64::min);
        if depth > deepest.0 {
            deepest = (depth, i);
        }
    }
    if deepest.0 > CONVEX_TOL * size {
        let (depth, i) = deepest;
        return Err(Error::parse(
            source,
            format!(
                "mesh is not convex: a vertex ({}) lies {} ({}% of the size) inside its convex hull; allowed {}%",
                points.locs[i].describe(),
                sig2(depth),
                sig2(100.0 * depth / size),
                100.0 * CONVEX_TOL
            ),
        ));
    }

    // Into a unit frame first (Polyhedron works in a bounded box), then to the girdle frame.
    let centre = 0.5 * (lo + hi);
    let unit: Vec<Plane> = hull
        .iter()
        .map(|h| Plane {
            normal: h.normal,
            offset: (h.offset - h.normal.dot(centre)) / size,
        })
        .collect();
    let solid = Polyhedron::from_planes(&named(&unit)).map_err(|e| hull_error(e, source))?;
    let (origin, width) = girdle_frame(&solid);
    if width <= 1e-9 {
        return Err(Error::parse(
            source,
            "the mesh has no horizontal extent; the stone must stand upright, z up",
        ));
    }
    let mut planes: Vec<Plane> = unit
        .iter()
        .map(|h| Plane {
            normal: h.normal,
            offset: (h.offset - h.normal.dot(origin)) / width,
        })
        .collect();
    planes.sort_by(|a, b| {
        let key = |p: &Plane| (side(p.normal).1, (facet_angle_deg(p.normal) * 1e3).round());
        let (ka, kb) = (key(a), key(b));
        ka.0.cmp(&kb.0)
            .then(ka.1.total_cmp(&kb.1))
            .then(facet_azimuth_deg(a.normal).total_cmp(&facet_azimuth_deg(b.normal)))
    });
    let mut out = named(&planes);
    for f in &mut out {
        f.tier = side(f.plane.normal).0.to_string();
    }
    split_tiers_by_angle(&mut out);
    Ok(out)
}

/// Crown and pavilion facets grouped into tiers by angle: angles within 0.05° of their
/// neighbour in sorted order form one tier, named by side and mean angle (`crown-34.50`), so
/// that `info` reports a mesh's bezels and mains as a cutter would.
fn split_tiers_by_angle(facets: &mut [FacetPlane]) {
    for sidename in ["crown", "pavilion"] {
        let mut idx: Vec<(usize, f64)> = facets
            .iter()
            .enumerate()
            .filter(|(_, f)| f.tier == sidename)
            .map(|(i, f)| (i, facet_angle_deg(f.plane.normal)))
            .collect();
        idx.sort_by(|a, b| a.1.total_cmp(&b.1));
        let mut start = 0;
        while start < idx.len() {
            let mut end = start + 1;
            while end < idx.len() && idx[end].1 - idx[end - 1].1 <= 0.05 {
                end += 1;
            }
            let mean = idx[start..end].iter().map(|x| x.1).sum::<f64>() / (end - start) as f64;
            for &(i, _) in &idx[start..end] {
                facets[i].tier = format!("{sidename}-{mean:.2}");
            }
            start = end;
        }
    }
}

fn named(planes: &[Plane]) -> Vec<FacetPlane> {
    planes
        .iter()
        .enumerate()
        .map(|(i, p)| FacetPlane {
            plane: *p,
            name: format!("f-{}", i + 1),
            tier: String::new(),
        })
        .collect()
}

/// The side (tier) of a facet from its outward normal, with its rank in the facet order.
fn side(n: DVec3) -> (&'static str, u8) {
    let flat = facet_angle_deg(n) < 0.01;
    if n.z.abs() < HORIZONTAL {
        ("girdle", 2)
    } else if n.z > 0.0 {
        if flat {
            ("table", 0)
        } else {
            ("crown", 1)
        }
    } else if flat {
        ("culet", 4)
    } else {
        ("pavilion", 3)
    }
}

/// The centre of the girdle plane and the largest horizontal extent of a solid.
fn girdle_frame(s: &Polyhedron) -> (DVec3, f64) {
    let (lo, hi) = s.bounding_box();
    let cx = 0.5 * (lo.x + hi.x);
    let cy = 0.5 * (lo.y + hi.y);
    let girdle_z: Vec<f64> = s
        .facets
        .iter()
        .filter(|f| f.plane.normal.z.abs() < HORIZONTAL)
        .flat_map(|f| f.vertices.iter().map(|&v| s.vertices[v].z))
        .collect();
    let zs: Vec<f64> = if girdle_z.is_empty() {
        let r = |v: &DVec3| (v.x - cx).hypot(v.y - cy);
        let rmax = s.vertices.iter().map(r).fold(0.0, f64::max);
        s.vertices
            .iter()
            .filter(|v| r(v) >= rmax - 1e-7)
            .map(|v| v.z)
            .collect()
    } else {
        girdle_z
    };
    let zmin = zs.iter().copied().fold(f64::INFINITY, f64::min);
    let zmax = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let cz = if zmin.is_finite() && zmax.is_finite() {
        0.5 * (zmin + zmax)
    } else {
        0.0
    };
    let mut width: f64 = 0.0;
    for (i, a) in s.vertices.iter().enumerate() {
        for b in &s.vertices[i + 1..] {
            width = width.max((a.truncate() - b.truncate()).length());
        }
    }
    (DVec3::new(cx, cy, cz), width)
}

fn hull_error(e: Error, source: &str) -> Error {
    match e {
        Error::Geometry(m) => Error::parse(source, format!("convex hull of the mesh: {m}")),
        other => other,
    }
}

/// Read a mesh file (`.obj` or `.stl`, by extension) as a cut named after the file stem.
pub fn read(path: impl AsRef<Path>) -> Result<Cut> {
    let path = path.as_ref();
    let shown = path.display().to_string();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let reader: fn(&[u8], &str) -> Result<Vec<FacetPlane>> = match ext.as_str() {
        "obj" => read_obj,
        "stl" => read_stl,
        _ => {
            return Err(Error::parse(
                shown,
                format!("unknown mesh format `.{ext}`; allowed: .obj, .stl"),
            ))
        }
    };
    let bytes = std::fs::read(path).map_err(|e| Error::io(&shown, e))?;
    let planes = reader(&bytes, &shown)?;
    let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("mesh");
    let solid = Polyhedron::from_planes(&planes).map_err(|e| hull_error(e, &shown))?;
    Ok(Cut {
        name: name.to_string(),
        family: None,
        params: Default::default(),
        solid,
        design_ri: None,
    })
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
        s.vertices.len(),
        s.facets.len()
    );
    let _ = writeln!(out, "o {}", token(&cut.name, "cut"));
    for v in &s.vertices {
        let _ = writeln!(out, "v {} {} {}", v.x, v.y, v.z);
    }
    for f in &s.facets {
        let _ = writeln!(out, "g {}", token(&f.name, "facet"));
        let idx: Vec<String> = f.vertices.iter().map(|i| (i + 1).to_string()).collect();
        let _ = writeln!(out, "f {}", idx.join(" "));
    }
    out
}

/// Triangles of every facet (fans over the convex facet polygons) with the facet's normal.
fn triangles(s: &Polyhedron) -> Vec<(DVec3, [DVec3; 3])> {
    let mut out = Vec::new();
    for (i, f) in s.facets.iter().enumerate() {
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

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    fn brilliant() -> Cut {
        Cut::from_family("rb", "round-brilliant", &Default::default()).unwrap()
    }

    /// Every facet plane of `a` has a plane in `b` within `tol` (normal and offset), and the
    /// counts and volumes agree. `a` is first scaled to a largest horizontal extent of 1, as
    /// the readers do (a round brilliant with N tangent girdle facets is 1/cos(180°/N) wide).
    fn assert_same(a: &Cut, b: &[FacetPlane], tol: f64, vol_tol: f64) {
        let a = a.solid.scaled(1.0 / girdle_frame(&a.solid).1);
        assert_eq!(b.len(), a.facets.len());
        for f in &a.facets {
            let best = b
                .iter()
                .map(|p| {
                    p.plane
                        .normal
                        .distance(f.plane.normal)
                        .max((p.plane.offset - f.plane.offset).abs())
                })
                .fold(f64::INFINITY, f64::min);
            assert!(best < tol, "{} off by {best:e}", f.name);
        }
        let s = Polyhedron::from_planes(b).unwrap();
        let (va, vb) = (a.volume(), s.volume());
        assert!((va - vb).abs() < vol_tol, "volume {va} vs {vb}");
    }

    #[test]
    fn obj_round_trip_keeps_every_plane() {
        let c = brilliant();
        let text = write_obj(&c);
        assert!(text.starts_with("# facetlab"));
        let planes = read_obj(text.as_bytes(), "rb.obj").unwrap();
        assert_same(&c, &planes, 1e-7, 1e-9);
        // Tiers by side and angle, table first.
        assert_eq!(planes[0].tier, "table");
        let count = |t: &str| {
            planes
                .iter()
                .filter(|p| p.tier.split('-').next() == Some(t))
                .count()
        };
        let tiers = |t: &str| {
            let mut v: Vec<&str> = planes
                .iter()
                .filter(|p| p.tier.starts_with(t))
                .map(|p| p.tier.as_str())
                .collect();
            v.dedup();
            v.len()
        };
        // Bezels, stars, upper halves; mains, lower halves.
        assert_eq!((tiers("crown"), tiers("pavilion")), (3, 2));
        assert!(
            planes.iter().any(|p| p.tier == "pavilion-40.75"),
            "{:?}",
            planes.iter().map(|p| &p.tier).collect::<Vec<_>>()
        );
        assert_eq!(
            (
                count("table"),
                count("crown"),
                count("girdle"),
                count("pavilion")
            ),
            (1, 32, 16, 24)
        );
        assert!(planes
            .iter()
            .enumerate()
            .all(|(i, p)| p.name == format!("f-{}", i + 1)));
    }

    #[test]
    fn stl_round_trips_ascii_and_binary() {
        let mut v = std::collections::BTreeMap::new();
        v.insert("culet".to_string(), 0.03);
        v.insert("girdle_facets".to_string(), 64.0);
        for c in [
            brilliant(),
            Cut::from_family("rb64", "round-brilliant", &v).unwrap(),
        ] {
            let ascii = write_stl_ascii(&c);
            let planes = read_stl(ascii.as_bytes(), "rb.stl").unwrap();
            assert_same(&c, &planes, 1e-7, 1e-9);
            let bin = write_stl(&c);
            assert_eq!(bin.len(), 84 + 50 * binary_stl_count(&bin).unwrap());
            assert!(!bin.starts_with(b"solid"));
            // Single precision: coordinates carry ~3e-8 of rounding.
            let planes = read_stl(&bin, "rb.stl").unwrap();
            assert_same(&c, &planes, 1e-6, 1e-7);
        }
    }

    #[test]
    fn coarse_coordinates_still_merge_into_facets() {
        // A 6.5 mm stone written with 6 and with 4 decimals, as many exporters do.
        let c = brilliant();
        for decimals in [6, 4] {
            let mut obj = String::new();
            for v in &c.solid.vertices {
                let w = *v * 6.5 + DVec3::new(1.0, 2.0, 3.0);
                obj += &format!(
                    "v {:.*} {:.*} {:.*}\n",
                    decimals, w.x, decimals, w.y, decimals, w.z
                );
            }
            for f in &c.solid.facets {
                for k in 1..f.vertices.len() - 1 {
                    let t = [f.vertices[0], f.vertices[k], f.vertices[k + 1]];
                    obj += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
                }
            }
            let planes = read_obj(obj.as_bytes(), "mm.obj").unwrap();
            let tol = if decimals == 6 { 1e-5 } else { 1e-3 };
            assert_same(&c, &planes, tol, 100.0 * tol);
        }
    }

    #[test]
    fn binary_stl_starting_with_solid_is_read_as_binary() {
        let mut bin = write_stl(&brilliant());
        bin[..6].copy_from_slice(b"solid ");
        assert_eq!(read_stl(&bin, "x.stl").unwrap().len(), 73);
    }

    #[test]
    fn moved_and_scaled_mesh_is_normalised() {
        let c = brilliant();
        let mut text = String::new();
        for v in &c.solid.vertices {
            let w = *v * 6.5 + DVec3::new(10.0, -3.0, 2.0);
            text += &format!("v {} {} {}\n", w.x, w.y, w.z);
        }
        // No faces: every vertex counts (a point cloud).
        let planes = read_obj(text.as_bytes(), "cloud.obj").unwrap();
        assert_same(&c, &planes, 1e-9, 1e-9);
    }

    #[test]
    fn dented_obj_is_refused_with_the_depth() {
        // A cube of side 2 with one face's centre pushed 0.2 inwards (10% of the size).
        let mut obj = String::from("# dented cube\n");
        for k in 0..8 {
            let c = |b: usize| if k >> b & 1 == 1 { 1.0 } else { -1.0 };
            obj += &format!("v {} {} {}\n", c(0), c(1), c(2));
        }
        obj += "v 0 0 0.8\n";
        obj += "f 1 3 4 2\nf 5 6 9\nf 6 8 9\nf 8 7 9\nf 7 5 9\nf 1 2 6 5\nf 2 4 8 6\nf 4 3 7 8\nf 3 1 5 7\n";
        let e = read_obj(obj.as_bytes(), "stone.obj")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("stone.obj: mesh is not convex"), "{e}");
        assert!(
            e.contains("lies 0.20 (10% of the size)") && e.contains("line 10"),
            "{e}"
        );
        assert!(!e.contains('\n'));
        // 0.05% is within the tolerance.
        let ok = obj.replace("v 0 0 0.8", "v 0 0 0.999");
        assert_eq!(read_obj(ok.as_bytes(), "stone.obj").unwrap().len(), 6);
    }

    #[test]
    fn malformed_obj_names_file_and_line() {
        let e = read_obj(b"v 0 0 0\nv 1 x 2\n", "bad.obj")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("bad.obj:2:") && e.contains("`x` is not a number"),
            "{e}"
        );
        let e = read_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "bad.obj")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("bad.obj:4:") && e.contains("out of range") && e.contains("3 vertices"),
            "{e}"
        );
        let e = read_obj(b"v 0 0 0\nf -2 1 1\n", "bad.obj")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("bad.obj:2:") && e.contains("-2"), "{e}");
        let e = read_obj(b"v 0 0 0\nf 0 1 1\n", "bad.obj")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("bad.obj:2:"), "{e}");
        let e = read_obj(b"v 0 0\n", "bad.obj").unwrap_err().to_string();
        assert!(
            e.starts_with("bad.obj:1:") && e.contains("3 coordinates"),
            "{e}"
        );
        let e = read_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n", "flat.obj")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("flat.obj:") && e.contains("one plane"), "{e}");
    }

    #[test]
    fn obj_face_forms_and_negative_indices() {
        let obj = "mtllib x.mtl\no cube\nv -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\n\
                   v -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\nvn 0 0 1\nvt 0 0\nusemtl m\ns off\n\
                   f 1/1/1 3/1/1 4/1/1 2/1/1\nf -4//1 -3//1 -1//1 -2//1\nf 1/1 2/1 6/1 5/1\n\
                   f 2 4 8 6\nf 4 3 7 8\nf 3 1 5 7\n";
        let planes = read_obj(obj.as_bytes(), "cube.obj").unwrap();
        assert_eq!(planes.len(), 6);
        let s = Polyhedron::from_planes(&planes).unwrap();
        // Largest horizontal extent (the square's diagonal) is 1.
        assert!(
            (s.volume() - 0.5f64.powf(1.5)).abs() < 1e-12,
            "{}",
            s.volume()
        );
        assert_eq!(planes[0].tier, "table");
        assert_eq!(planes[5].tier, "culet");
    }

    #[test]
    fn stl_errors_are_one_line() {
        let e = read_stl(b"hello", "x.stl").unwrap_err().to_string();
        assert!(e.starts_with("x.stl: not an STL file"), "{e}");
        let e = read_stl(b"solid a\nfacet normal 0 0 1\nvertex 1 2 nan\n", "x.stl")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("x.stl:3:"), "{e}");
        let e = read_stl(b"solid a\nbanana\n", "x.stl")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("x.stl:2:") && e.contains("banana"), "{e}");
        let mut bin = write_stl(&brilliant());
        bin[84 + 12..84 + 16].copy_from_slice(&f32::NAN.to_le_bytes());
        let e = read_stl(&bin, "x.stl").unwrap_err().to_string();
        assert!(e.contains("triangle 1"), "{e}");
    }

    #[test]
    fn random_bytes_never_panic() {
        let mut rng = SmallRng::seed_from_u64(42);
        let base = write_stl(&brilliant());
        for round in 0..300 {
            let bytes: Vec<u8> = match round % 3 {
                // Pure noise of any length.
                0 => (0..rng.random_range(0..400))
                    .map(|_| rng.random())
                    .collect(),
                // Noise with a consistent binary size.
                1 => {
                    let n = rng.random_range(0..12u32);
                    let mut b: Vec<u8> = (0..84 + 50 * n as usize).map(|_| rng.random()).collect();
                    b[80..84].copy_from_slice(&n.to_le_bytes());
                    b
                }
                // A real binary STL with some bytes flipped.
                _ => {
                    let mut b = base.clone();
                    for _ in 0..rng.random_range(1..20) {
                        let i = rng.random_range(84..b.len());
                        b[i] = rng.random();
                    }
                    b
                }
            };
            if let Err(e) = read_stl(&bytes, "fuzz.stl") {
                assert!(!e.to_string().contains('\n'));
            }
            let mut text = b"solid x\n".to_vec();
            text.extend_from_slice(&bytes);
            let _ = read_stl(&text, "fuzz.stl");
            let _ = read_obj(&bytes, "fuzz.obj");
        }
    }

    #[test]
    fn random_obj_text_never_panics() {
        // Mostly well-formed files with odd values (huge, tiny, repeated, flat, a stray word),
        // so that most reach the hull, the convexity check and the normalisation.
        let mut rng = SmallRng::seed_from_u64(9);
        let odd = [
            "0", "1e300", "-1e-300", "nan", "1e400", "x", "5e-324", "1", "1",
        ];
        let (mut reached, mut ok) = (0, 0);
        for _ in 0..400 {
            let mut text = String::new();
            let scale: f64 = [1.0, 1e-9, 1e9, 1e140][rng.random_range(0..4)];
            let flat = rng.random_bool(0.1);
            let on_sphere = rng.random_bool(0.3);
            let nv = rng.random_range(0..30);
            for k in 0..nv {
                let mut c: Vec<String> = if on_sphere {
                    // Convex: every vertex on a sphere.
                    let d = DVec3::new(
                        rng.random_range(-1.0..1.0),
                        rng.random_range(-1.0..1.0),
                        rng.random_range(-1.0..1.0),
                    );
                    (d.normalize_or(DVec3::Z) * scale)
                        .to_array()
                        .iter()
                        .map(|x| format!("{x}"))
                        .collect()
                } else {
                    (0..3)
                        .map(|_| {
                            format!(
                                "{}",
                                (rng.random_range(-1.0..1.0f64) * 8.0).round() / 8.0 * scale
                            )
                        })
                        .collect()
                };
                if flat {
                    c[2] = "0".into();
                }
                if rng.random_bool(0.03) {
                    c[rng.random_range(0..3)] = odd[rng.random_range(0..odd.len())].to_string();
                }
                if rng.random_bool(0.02) {
                    c.pop();
                }
                text += &format!("v {}\n", c.join(" "));
                if k > 3 && rng.random_bool(0.3) {
                    let n = if rng.random_bool(0.02) {
                        2
                    } else {
                        rng.random_range(3..6)
                    };
                    let idx: Vec<String> = (0..n)
                        .map(|_| {
                            let i = rng.random_range(1..=k as i64 + 1);
                            if rng.random_bool(0.2) {
                                format!("{}/1/1", -i)
                            } else {
                                i.to_string()
                            }
                        })
                        .collect();
                    text += &format!("f {}\n# note \u{7}\n", idx.join(" "));
                }
            }
            if nv > 2 && rng.random_bool(0.8) {
                let all: Vec<String> = (1..=nv).map(|i| i.to_string()).collect();
                text += &format!("f {}\n", all.join(" "));
            }
            match read_obj(text.as_bytes(), "fuzz.obj") {
                Ok(planes) => {
                    reached += 1;
                    ok += 1;
                    assert!(Polyhedron::from_planes(&planes).is_ok());
                }
                Err(e) => {
                    let m = e.to_string();
                    assert!(m.starts_with("fuzz.obj") && !m.contains('\n'), "{m}");
                    if m.contains("not convex") || m.contains("hull") {
                        reached += 1;
                    }
                }
            }
        }
        assert!(reached > 150 && ok > 20, "{reached} {ok}");
    }

    #[test]
    fn many_facets_in_azimuth_order_still_make_a_solid() {
        // 300 points on a sphere: ~600 facets, named in azimuth order (clipping in that order
        // leaves many near-degenerate vertices and T-junctions for from_planes to mend).
        let mut rng = SmallRng::seed_from_u64(2);
        let mut text = String::new();
        for _ in 0..300 {
            let d = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            let d = d.normalize_or(DVec3::Z);
            text += &format!("v {} {} {}\n", d.x, d.y, d.z);
        }
        let planes = read_obj(text.as_bytes(), "ball.obj").unwrap();
        let s = Polyhedron::from_planes(&planes).unwrap();
        assert_eq!(s.facets.len(), planes.len());
        for (f, p) in s.facets.iter().zip(&planes) {
            assert_eq!((&f.name, f.plane), (&p.name, p.plane));
        }
        for e in &s.edges {
            for k in e.facets {
                let poly = &s.facets[k].vertices;
                assert!(poly.contains(&e.a) && poly.contains(&e.b));
            }
        }
        assert_eq!(s.vertices.len() + s.facets.len(), s.edges.len() + 2);
        let ball = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
        assert!(s.volume() > 0.9 * ball && s.volume() < ball);
    }

    #[test]
    fn read_by_extension() {
        let dir = std::env::temp_dir().join(format!("facetlab-mesh-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let c = brilliant();
        let obj = dir.join("gem.obj");
        std::fs::write(&obj, write_obj(&c)).unwrap();
        let stl = dir.join("gem.STL");
        std::fs::write(&stl, write_stl(&c)).unwrap();
        let a = read(&obj).unwrap();
        assert_eq!(a.name, "gem");
        assert!((a.solid.volume() - c.solid.volume()).abs() < 1e-9);
        assert_eq!(read(&stl).unwrap().solid.facets.len(), 73);
        let e = read(dir.join("gem.ply")).unwrap_err().to_string();
        assert!(e.contains("allowed: .obj, .stl"), "{e}");
        let e = read(dir.join("missing.obj")).unwrap_err().to_string();
        assert!(e.contains("missing.obj"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
