//! A convex polyhedron as the intersection of half-spaces.
//!
//! Built by clipping: start from a large box and cut it by every facet plane in turn (each face
//! polygon clipped Sutherland–Hodgman style, the cut closed by a new face made of the crossing
//! points). Vertices are then welded, each facet gets an ordered outward polygon, and edges get
//! the two facets they separate. Problems are reported, never hidden: a plane that never touches
//! the solid, duplicate planes, an unbounded or empty solid.

mod block;
mod cut;
mod parts;

use block::box_faces;
pub use block::Block;

use super::fast_hash::{fast_map, FastMap};
use super::tjunction::split_t_junctions;
use super::{DVec3, FacetPlane, Plane, EPS, WELD};
use crate::error::{Error, Result};
use serde::Serialize;

/// Half-size of the starting box; anything still touching it is unbounded.
const BOX: f64 = 1.0e3;

/// One facet of a [`Polyhedron`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Facet {
    /// Plane with outward unit normal.
    pub plane: Plane,
    /// Facet name.
    pub name: String,
    /// Tier (kind) of the facet.
    pub tier: String,
    /// Indices into [`Polyhedron::vertices`], counter-clockwise seen from outside.
    pub vertices: Vec<usize>,
    /// Area of the facet polygon.
    pub area: f64,
    /// Area centroid of the facet polygon.
    pub centroid: DVec3,
}

/// An edge between two facets.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Edge {
    /// First vertex (index).
    pub a: usize,
    /// Second vertex (index).
    pub b: usize,
    /// The facet whose polygon runs a→b, and the facet whose polygon runs b→a.
    pub facets: [usize; 2],
}

/// A bounded convex polyhedron with derived vertices, facet polygons and adjacency.
///
/// Its parts are read-only: the tracers rely on the solid being convex and closed, with facet
/// polygons, edges and planes that agree, so a `Polyhedron` is only ever made by
/// [`Polyhedron::from_planes`] (or a transform of one) and never edited in place.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Polyhedron {
    vertices: Vec<DVec3>,
    facets: Vec<Facet>,
    edges: Vec<Edge>,
}

/// A face during construction: its plane index (`None` for the starting box), its polygon,
/// and a ball around the polygon (so that a plane far from it skips it at the cost of one dot
/// product).
#[derive(Clone)]
struct Face {
    source: Option<usize>,
    normal: DVec3,
    poly: Vec<DVec3>,
    centre: DVec3,
    radius: f64,
}

impl Face {
    fn new(source: Option<usize>, normal: DVec3, poly: Vec<DVec3>) -> Face {
        let centre = poly.iter().copied().sum::<DVec3>() / poly.len().max(1) as f64;
        let radius = poly.iter().map(|p| p.distance(centre)).fold(0.0, f64::max);
        Face {
            source,
            normal,
            poly,
            // Rounding of the centre and the distances: a little room.
            radius: radius * (1.0 + 1e-12) + 1e-15 * centre.length(),
            centre,
        }
    }
}

/// Point where segment p→q crosses the plane; computed in a canonical endpoint order so that the
/// two faces sharing an edge get the same bits.
fn crossing(plane: &Plane, p: DVec3, q: DVec3) -> DVec3 {
    let (a, b) = if (p.x, p.y, p.z) < (q.x, q.y, q.z) {
        (p, q)
    } else {
        (q, p)
    };
    let (da, db) = (plane.distance(a), plane.distance(b));
    let t = da / (da - db);
    a + (b - a) * t
}

/// Order points lying on a plane with normal `n` counter-clockwise seen from outside, dropping
/// near-duplicates.
pub(crate) fn order_on_plane(n: DVec3, pts: &mut Vec<DVec3>) {
    if pts.is_empty() {
        return;
    }
    let c = pts.iter().copied().sum::<DVec3>() / pts.len() as f64;
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    pts.sort_by(|p, q| {
        let (a, b) = (*p - c, *q - c);
        let ta = a.dot(v).atan2(a.dot(u));
        let tb = b.dot(v).atan2(b.dot(u));
        ta.total_cmp(&tb)
    });
    let mut out: Vec<DVec3> = Vec::with_capacity(pts.len());
    for p in pts.drain(..) {
        if out.last().is_none_or(|l: &DVec3| l.distance(p) > WELD) {
            out.push(p);
        }
    }
    while out.len() > 1 && out[0].distance(*out.last().unwrap()) <= WELD {
        out.pop();
    }
    *pts = out;
}

/// Area vector (normal × area) of a closed polygon.
fn area_vector(poly: &[DVec3]) -> DVec3 {
    let mut s = DVec3::ZERO;
    for i in 0..poly.len() {
        s += poly[i].cross(poly[(i + 1) % poly.len()]);
    }
    0.5 * s
}

/// Area centroid of a planar polygon.
fn polygon_centroid(poly: &[DVec3], n: DVec3) -> DVec3 {
    let o = poly[0];
    let mut acc = DVec3::ZERO;
    let mut total = 0.0;
    for i in 1..poly.len().saturating_sub(1) {
        let (b, c) = (poly[i], poly[i + 1]);
        let a = 0.5 * (b - o).cross(c - o).dot(n);
        acc += a * (o + b + c) / 3.0;
        total += a;
    }
    if total.abs() > 0.0 {
        acc / total
    } else {
        poly.iter().copied().sum::<DVec3>() / poly.len() as f64
    }
}

/// The box's faces clipped by `planes` in the order given, each plane first passed to `check`
/// (its index and itself); an error as soon as a plane cuts away everything left.
fn clipped(
    planes: &[FacetPlane],
    check: impl Fn(usize, &FacetPlane) -> Result<()>,
) -> Result<Vec<Face>> {
    let mut faces = box_faces();
    let mut buffer = Vec::new();
    for (k, fp) in planes.iter().enumerate() {
        check(k, fp)?;
        clip(&mut faces, &fp.plane, k, &mut buffer);
        if faces.is_empty() {
            return Err(Error::Geometry(format!(
                "the solid is empty: facet {} ({}) cuts away everything left",
                k + 1,
                fp.name
            )));
        }
    }
    Ok(faces)
}

/// Cut the faces by one plane (index `k`), in place and in order. Returns whether the plane
/// cut anything off. `d` is a buffer for the distances.
fn clip(faces: &mut Vec<Face>, plane: &Plane, k: usize, d: &mut Vec<f64>) -> bool {
    let mut cap: Vec<DVec3> = Vec::new();
    let mut cut = false;
    let mut dropped = false;
    for face in faces.iter_mut() {
        // Every corner more than EPS inside: kept whole, and nothing on the plane.
        if plane.distance(face.centre) + face.radius < -EPS {
            continue;
        }
        d.clear();
        d.extend(face.poly.iter().map(|p| plane.distance(*p)));
        let max = d.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let min = d.iter().copied().fold(f64::INFINITY, f64::min);
        if max > EPS {
            cut = true;
        }
        if max <= EPS || min >= -EPS {
            // Inside (kept), or entirely outside or lying in the plane (dropped).
            for (p, &di) in face.poly.iter().zip(d.iter()) {
                if di.abs() <= EPS {
                    cap.push(*p);
                }
            }
            if max > EPS {
                face.poly.clear();
                dropped = true;
            }
            continue;
        }
        let n = face.poly.len();
        let mut out = Vec::with_capacity(n + 2);
        for i in 0..n {
            let (p, q) = (face.poly[i], face.poly[(i + 1) % n]);
            let (dp, dq) = (d[i], d[(i + 1) % n]);
            let p_in = dp <= EPS;
            if p_in {
                out.push(p);
                if dp.abs() <= EPS {
                    cap.push(p);
                }
            }
            if (dp < -EPS && dq > EPS) || (dp > EPS && dq < -EPS) {
                let x = crossing(plane, p, q);
                out.push(x);
                cap.push(x);
            }
        }
        if out.len() >= 3 {
            *face = Face::new(face.source, face.normal, out);
        } else {
            face.poly.clear();
            dropped = true;
        }
    }
    if dropped {
        faces.retain(|f| !f.poly.is_empty());
    }
    if cut {
        order_on_plane(plane.normal, &mut cap);
        if cap.len() >= 3 {
            faces.push(Face::new(Some(k), plane.normal, cap));
        }
    }
    cut
}

/// The first pair of planes `(j, i)`, `j < i`, that are the same plane (normals within 1e-9
/// and offsets within 1e-9), lowest `i` first: found among neighbours in the order of the
/// normals' x components, so in O(n log n) for planes of distinct normals.
fn first_duplicate(planes: &[FacetPlane]) -> Option<(usize, usize)> {
    let mut order: Vec<usize> = (0..planes.len()).collect();
    order.sort_by(|&a, &b| {
        planes[a]
            .plane
            .normal
            .x
            .total_cmp(&planes[b].plane.normal.x)
    });
    let mut best: Option<(usize, usize)> = None;
    for (k, &a) in order.iter().enumerate() {
        let p = &planes[a].plane;
        for &b in &order[k + 1..] {
            let q = &planes[b].plane;
            if q.normal.x - p.normal.x >= 1e-9 {
                break;
            }
            if p.normal.distance(q.normal) < 1e-9 && (p.offset - q.offset).abs() < 1e-9 {
                let pair = (a.min(b), a.max(b));
                if best.is_none_or(|(j, i)| (pair.1, pair.0) < (i, j)) {
                    best = Some(pair);
                }
            }
        }
    }
    best
}

/// The planes of `faces` that [`Polyhedron::from_planes_pruned`] keeps: those whose face has
/// an area above `1e-10` of the faces' squared size, in order.
fn kept_planes(faces: &[Face]) -> Vec<usize> {
    let scale = faces
        .iter()
        .flat_map(|f| f.poly.iter())
        .map(|p| p.length())
        .fold(0.0, f64::max)
        .max(1e-300);
    let mut keep: Vec<usize> = faces
        .iter()
        .filter(|f| area_vector(&f.poly).length() > 1e-10 * scale * scale)
        .filter_map(|f| f.source)
        .collect();
    keep.sort_unstable();
    keep.dedup();
    keep
}

/// The solid of `faces` (clipped by `planes`, each face's source its plane's index), welded
/// at the finest tolerance that pairs every edge: exact designs weld at WELD; planes read from
/// rounded mesh coordinates miss their common points by more and leave clusters of nearly
/// coincident vertices, welded at a coarser tolerance.
fn welded(faces: &[Face], planes: &[FacetPlane]) -> Result<Polyhedron> {
    let mut first_err = None;
    for weld in [WELD, 10.0 * WELD, 100.0 * WELD, 1000.0 * WELD] {
        match assemble(faces, planes, weld) {
            Ok(p) => return Ok(p),
            Err(Assembly::Final(e)) => return Err(first_err.unwrap_or(e)),
            Err(Assembly::Unpaired(e)) => {
                first_err.get_or_insert(e);
            }
        }
    }
    Err(first_err.unwrap_or_else(|| Error::Geometry("degenerate solid".into())))
}

impl Polyhedron {
    /// Welded vertices.
    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    /// Facets, in the order of the planes given (every plane becomes one facet).
    pub fn facets(&self) -> &[Facet] {
        &self.facets
    }

    /// Every edge once.
    pub fn edges(&self) -> &[Edge] {
        &self.edges
    }

    /// Intersect the half-spaces of `planes`. Every plane must end up as a facet of positive
    /// area; the solid must be bounded and non-empty; no two planes may coincide.
    ///
    /// ```
    /// use facetlab::geometry::{DVec3, FacetPlane, Polyhedron};
    ///
    /// // The unit cube: six half-spaces `normal · x <= 0.5`.
    /// let normals = [DVec3::X, DVec3::NEG_X, DVec3::Y, DVec3::NEG_Y, DVec3::Z, DVec3::NEG_Z];
    /// let planes: Vec<FacetPlane> = normals
    ///     .iter()
    ///     .enumerate()
    ///     .map(|(i, n)| FacetPlane::new(*n, 0.5, format!("f{i}"), "side"))
    ///     .collect();
    /// let cube = Polyhedron::from_planes(&planes).unwrap();
    /// assert_eq!((cube.vertices().len(), cube.edges().len(), cube.facets().len()), (8, 12, 6));
    /// assert!((cube.volume() - 1.0).abs() < 1e-12);
    ///
    /// // A plane that never touches the solid is an error naming the facet.
    /// let mut more = planes.clone();
    /// more.push(FacetPlane::new(DVec3::new(1.0, 1.0, 0.0), 5.0, "far", "x"));
    /// let e = Polyhedron::from_planes(&more).unwrap_err().to_string();
    /// assert!(e.contains("far") && e.contains("never touches"), "{e}");
    /// ```
    pub fn from_planes(planes: &[FacetPlane]) -> Result<Polyhedron> {
        if planes.len() < 4 {
            return Err(Error::Geometry(format!(
                "a solid needs at least 4 facet planes, got {}",
                planes.len()
            )));
        }
        // The first bad plane, in the order given: one without a valid plane, or one that
        // repeats an earlier plane (a plane is checked before it is compared).
        let invalid = planes.iter().position(|fp| {
            let p = &fp.plane;
            !(p.normal.is_finite() && p.offset.is_finite())
                || (p.normal.length() - 1.0).abs() > 1e-6
        });
        let valid = &planes[..invalid.unwrap_or(planes.len())];
        match (invalid, first_duplicate(valid)) {
            (_, Some((j, i))) => {
                return Err(Error::Geometry(format!(
                    "facets {} ({}) and {} ({}) are the same plane",
                    j + 1,
                    planes[j].name,
                    i + 1,
                    planes[i].name
                )))
            }
            (Some(i), None) => {
                return Err(Error::Geometry(format!(
                    "facet {} ({}) has no valid plane (normal must be finite and non-zero, offset finite)",
                    i + 1,
                    planes[i].name
                )))
            }
            (None, None) => {}
        }
        let faces = clipped(planes, |_, _| Ok(()))?;
        if faces.iter().any(|f| f.source.is_none()) {
            return Err(Error::Geometry(
                "the solid is unbounded: the facet planes do not enclose a finite volume".into(),
            ));
        }
        welded(&faces, planes)
    }

    /// The solid of the half-spaces `planes`, those that do not touch it left out (a
    /// rough's piece cut by a saw plane: the rough's planes beyond the cut bound nothing).
    /// The planes kept are the ones whose face has an area above `1e-12` of the box's after
    /// clipping, in the order given; the solid is then [`Polyhedron::from_planes`] of those.
    pub fn from_planes_pruned(planes: &[FacetPlane]) -> Result<Polyhedron> {
        let faces = clipped(planes, |k, fp| {
            if fp.plane.normal.is_finite() && fp.plane.offset.is_finite() {
                Ok(())
            } else {
                Err(Error::Geometry(format!(
                    "facet {} ({}) has no valid plane",
                    k + 1,
                    fp.name
                )))
            }
        })?;
        let kept: Vec<FacetPlane> = kept_planes(&faces)
            .iter()
            .map(|&k| planes[k].clone())
            .collect();
        Polyhedron::from_planes(&kept)
    }

    /// The facet planes of this solid (the input of [`Polyhedron::from_planes`]).
    pub fn facet_planes(&self) -> Vec<FacetPlane> {
        self.facets
            .iter()
            .map(|f| FacetPlane {
                plane: f.plane,
                name: f.name.clone(),
                tier: f.tier.clone(),
            })
            .collect()
    }

    /// The polygon of facet `i` as points, counter-clockwise seen from outside.
    pub fn facet_polygon(&self, i: usize) -> Vec<DVec3> {
        self.facets[i]
            .vertices
            .iter()
            .map(|&v| self.vertices[v])
            .collect()
    }

    /// Volume (girdle diameters cubed).
    pub fn volume(&self) -> f64 {
        self.facets
            .iter()
            .map(|f| f.area * f.plane.offset)
            .sum::<f64>()
            / 3.0
    }

    /// Total surface area.
    pub fn surface_area(&self) -> f64 {
        self.facets.iter().map(|f| f.area).sum()
    }

    /// Area of the solid's shadow on a plane perpendicular to `dir` (any length).
    pub fn projected_area(&self, dir: DVec3) -> f64 {
        let u = dir.normalize();
        self.facets
            .iter()
            .map(|f| (f.area * f.plane.normal.dot(u)).max(0.0))
            .sum()
    }

    /// Axis-aligned bounding box (min, max).
    pub fn bounding_box(&self) -> (DVec3, DVec3) {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for v in &self.vertices {
            lo = lo.min(*v);
            hi = hi.max(*v);
        }
        (lo, hi)
    }

    /// Centroid of the solid's volume.
    pub fn centroid(&self) -> DVec3 {
        let o = self.vertices.iter().copied().sum::<DVec3>() / self.vertices.len() as f64;
        let mut acc = DVec3::ZERO;
        let mut vol = 0.0;
        for i in 0..self.facets.len() {
            let p = self.facet_polygon(i);
            for i in 1..p.len() - 1 {
                let v = (p[0] - o).dot((p[i] - o).cross(p[i + 1] - o)) / 6.0;
                acc += v * (o + p[0] + p[i] + p[i + 1]) / 4.0;
                vol += v;
            }
        }
        acc / vol
    }

    /// Whether `p` is inside or on the solid, within `tol`.
    pub fn contains(&self, p: DVec3, tol: f64) -> bool {
        self.facets.iter().all(|f| f.plane.distance(p) <= tol)
    }

    /// Indices of the facets sharing an edge with facet `i`.
    pub fn neighbors(&self, i: usize) -> Vec<usize> {
        let mut out: Vec<usize> = self
            .edges
            .iter()
            .filter_map(|e| {
                if e.facets[0] == i {
                    Some(e.facets[1])
                } else if e.facets[1] == i {
                    Some(e.facets[0])
                } else {
                    None
                }
            })
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Largest distance of any vertex from the z axis (half the girdle outline's width for a
    /// centred stone).
    pub fn max_radius(&self) -> f64 {
        self.vertices
            .iter()
            .map(|v| v.truncate().length())
            .fold(0.0, f64::max)
    }

    /// The same solid scaled by `s` about the origin.
    pub fn scaled(&self, s: f64) -> Polyhedron {
        let mut out = self.clone();
        for v in &mut out.vertices {
            *v *= s;
        }
        for f in &mut out.facets {
            f.plane.offset *= s;
            f.area *= s * s;
            f.centroid *= s;
        }
        out
    }
}

/// Why assembling welded faces failed: a final error, or edges left unpaired (worth another
/// try at a coarser weld).
enum Assembly {
    Final(Error),
    Unpaired(Error),
}

/// Weld the clipped faces' points at tolerance `weld`, mend T-junctions, build facets and edges.
fn assemble(
    faces: &[Face],
    planes: &[FacetPlane],
    weld: f64,
) -> std::result::Result<Polyhedron, Assembly> {
    let mut vertices: Vec<DVec3> = Vec::new();
    // The first vertex within `weld` of a point, found among the points of the neighbouring
    // cells of a grid of side `weld` (the same vertex a scan of all of them in order finds).
    let mut grid: FastMap<[i64; 3], Vec<usize>> = fast_map(0);
    let cell = |p: DVec3| (p / weld).floor().to_array().map(|c| c as i64);
    let mut index_of = |p: DVec3, vertices: &mut Vec<DVec3>| -> usize {
        let c = cell(p);
        let mut first: Option<usize> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(there) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) else {
                        continue;
                    };
                    for &i in there {
                        if first.is_none_or(|f| i < f) && vertices[i].distance(p) <= weld {
                            first = Some(i);
                        }
                    }
                }
            }
        }
        first.unwrap_or_else(|| {
            vertices.push(p);
            grid.entry(c).or_default().push(vertices.len() - 1);
            vertices.len() - 1
        })
    };
    let mut polys: Vec<Option<Vec<usize>>> = vec![None; planes.len()];
    for face in faces {
        let mut idx: Vec<usize> = Vec::with_capacity(face.poly.len());
        for p in &face.poly {
            let i = index_of(*p, &mut vertices);
            if idx.last() != Some(&i) {
                idx.push(i);
            }
        }
        while idx.len() > 1 && idx.first() == idx.last() {
            idx.pop();
        }
        let src = face.source.expect("box faces rejected above");
        if idx.len() >= 3 {
            polys[src] = Some(idx);
        }
    }
    for idx in polys.iter_mut().flatten() {
        // A coarse weld can pinch a polygon: keep the first visit of each vertex.
        let mut seen = Vec::with_capacity(idx.len());
        idx.retain(|v| {
            let fresh = !seen.contains(v);
            seen.push(*v);
            fresh
        });
    }
    split_t_junctions(&mut polys, &vertices, weld);
    let mut facets = Vec::with_capacity(planes.len());
    for (k, fp) in planes.iter().enumerate() {
        let Some(idx) = polys[k].take() else {
            return Err(Assembly::Final(Error::Geometry(format!(
                "facet {} ({}, tier {}) never touches the solid: its plane lies outside the other facets",
                k + 1,
                fp.name,
                fp.tier
            ))));
        };
        let poly: Vec<DVec3> = idx.iter().map(|&i| vertices[i]).collect();
        let area = area_vector(&poly).dot(fp.plane.normal);
        if area <= 1e-12 {
            return Err(Assembly::Final(Error::Geometry(format!(
                "facet {} ({}, tier {}) touches the solid only in an edge or a point",
                k + 1,
                fp.name,
                fp.tier
            ))));
        }
        let centroid = polygon_centroid(&poly, fp.plane.normal);
        facets.push(Facet {
            plane: fp.plane,
            name: fp.name.clone(),
            tier: fp.tier.clone(),
            vertices: idx,
            area,
            centroid,
        });
    }
    let edges = build_edges(&facets).map_err(Assembly::Unpaired)?;
    Ok(Polyhedron {
        vertices,
        facets,
        edges,
    })
}

fn build_edges(facets: &[Facet]) -> Result<Vec<Edge>> {
    let mut half: FastMap<(usize, usize), usize> = fast_map(0);
    for (fi, f) in facets.iter().enumerate() {
        let n = f.vertices.len();
        for i in 0..n {
            half.insert((f.vertices[i], f.vertices[(i + 1) % n]), fi);
        }
    }
    // In facet order, so that an error names the same facet every time.
    let mut edges = Vec::new();
    for (f0, f) in facets.iter().enumerate() {
        let n = f.vertices.len();
        for i in 0..n {
            let (a, b) = (f.vertices[i], f.vertices[(i + 1) % n]);
            match half.get(&(b, a)) {
                Some(&f1) if a < b && half.get(&(a, b)) == Some(&f0) => edges.push(Edge {
                    a,
                    b,
                    facets: [f0, f1],
                }),
                Some(_) => {}
                None => {
                    return Err(Error::Geometry(format!(
                        "facet {} has an edge no other facet shares (numerically degenerate solid)",
                        facets[f0].name
                    )))
                }
            }
        }
    }
    edges.sort_by_key(|e| (e.a, e.b));
    Ok(edges)
}

#[cfg(test)]
mod tests;
