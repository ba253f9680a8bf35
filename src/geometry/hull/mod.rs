//! 3-D convex hull of a point set, returned as facet planes.
//!
//! Quickhull, made robust in three ways:
//! - the points are first moved and scaled into a unit box (the hull does not change under
//!   translation and uniform scaling), so every tolerance is relative to the size of the set;
//! - which faces an apex sees is decided exactly, on copies of the points snapped to a grid of
//!   2⁻⁴⁰ of the size, with integer arithmetic; the triangulation therefore stays convex and
//!   never folds over itself, however many points are (nearly) coplanar;
//! - a point within half the merge tolerance of the hull counts as lying on it and never becomes
//!   a vertex, so rounding noise on a flat facet does not splinter it.
//!
//! The triangles are then merged into one facet per plane (a cube's 12 STL triangles become 6
//! facets; `merge.rs`): facets grow from the largest triangle across shared edges, taking a
//! neighbour when its three corners lie within the merge tolerance of the facet's plane. A
//! facet's normal is the area-weighted mean of its well-aligned triangles' normals, its offset
//! the largest `normal · p` over the hull's vertices (found by climbing the hull's edges, which
//! on a convex solid ends at the top) and the points left on its faces, so every hull vertex
//! lies inside or on every returned plane.
//!
//! Cost: quickhull is O(n log n) on the usual inputs (each point is reassigned a logarithmic
//! number of times), and the merge is linear in the triangles; a scanned rough of 400,000
//! triangles is hulled in well under a second (`cargo bench --bench plan`).
//!
//! [`hull`] can also stop early, at a number of vertices ([`HullOptions::max_vertices`]): the
//! farthest point outside the hull so far is then always added next (a greedy, progressive
//! hull), and the result is the hull of the vertices chosen, inside the full hull, with the
//! farthest point left out reported ([`Hull::left_out`]).

mod merge;

use super::fast_hash::{fast_map, FastMap};
use super::{DVec3, Plane};
use crate::error::{Error, Result};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Default merge tolerance of [`convex_hull`]: corners within `1e-7 × size` of a facet's plane
/// belong to that facet (size: the largest side of the points' bounding box).
pub const MERGE_TOL: f64 = 1e-7;

/// Points closer than this (in units of the size) count as the same point or line.
const TINY: f64 = 1e-10;

/// How [`hull`] works.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HullOptions {
    /// Merge tolerance relative to the size of the point set (see [`convex_hull_with_tolerance`]).
    pub merge_tol: f64,
    /// Stop once the hull has this many vertices (at least 4): the farthest point outside is
    /// always added next, so the hull is the best of its size the greedy order finds. `None`:
    /// the full hull.
    pub max_vertices: Option<usize>,
}

impl Default for HullOptions {
    fn default() -> Self {
        HullOptions {
            merge_tol: MERGE_TOL,
            max_vertices: None,
        }
    }
}

/// A convex hull: its facet planes, and how far the points left out stand outside them.
#[derive(Clone, Debug, PartialEq)]
pub struct Hull {
    /// Outward facet planes, coplanar triangles merged.
    pub planes: Vec<Plane>,
    /// The hull's vertices (points of the set).
    pub vertices: usize,
    /// The farthest any point stands outside the planes, in the points' units: 0 for a full
    /// hull (up to half the merge tolerance), else how much a hull stopped at
    /// [`HullOptions::max_vertices`] leaves out.
    pub left_out: f64,
}

/// The convex hull of `points` as outward facet planes, coplanar triangles merged with the
/// default tolerance [`MERGE_TOL`].
///
/// Errors: fewer than 4 points, a non-finite coordinate, or points that do not span a solid
/// (all equal, on one line, or in one plane).
pub fn convex_hull(points: &[DVec3]) -> Result<Vec<Plane>> {
    convex_hull_with_tolerance(points, MERGE_TOL)
}

/// [`convex_hull`] with a merge tolerance relative to the size of the point set (use a larger
/// one for coarse data, e.g. `1e-6` for single-precision STL coordinates).
pub fn convex_hull_with_tolerance(points: &[DVec3], rel_tol: f64) -> Result<Vec<Plane>> {
    hull(
        points,
        HullOptions {
            merge_tol: rel_tol,
            max_vertices: None,
        },
    )
    .map(|h| h.planes)
}

/// The convex hull of `points` with `options` (a merge tolerance, and perhaps a vertex budget).
///
/// ```
/// use facetlab::geometry::{hull, DVec3, HullOptions};
/// // 2,000 points on a sphere of radius 2: the full hull has them all as vertices; a hull of
/// // 200 vertices leaves the others at most a few hundredths outside.
/// let pts: Vec<DVec3> = (0..2000)
///     .map(|k| {
///         let z = 1.0 - (2 * k + 1) as f64 / 2000.0;
///         let a = 2.399963 * k as f64;
///         let r = (1.0 - z * z).sqrt();
///         2.0 * DVec3::new(r * a.cos(), r * a.sin(), z)
///     })
///     .collect();
/// let full = hull(&pts, HullOptions::default()).unwrap();
/// assert_eq!(full.vertices, 2000);
/// let coarse = hull(&pts, HullOptions { max_vertices: Some(200), ..Default::default() }).unwrap();
/// assert_eq!(coarse.vertices, 200);
/// assert!(coarse.left_out > 0.0 && coarse.left_out < 0.05, "{}", coarse.left_out);
/// ```
pub fn hull(points: &[DVec3], options: HullOptions) -> Result<Hull> {
    if points.len() < 4 {
        return Err(Error::Geometry(format!(
            "a convex hull needs at least 4 points, got {}",
            points.len()
        )));
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(Error::Geometry(format!(
            "point {} has a coordinate that is not a finite number",
            i + 1
        )));
    }
    let rel_tol = options.merge_tol;
    let rel_tol = if rel_tol.is_finite() && rel_tol > TINY {
        rel_tol.min(1e-2)
    } else {
        MERGE_TOL
    };
    let (mut lo, mut hi) = (points[0], points[0]);
    for p in points {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    let size = (hi - lo).max_element();
    let centre = 0.5 * (lo + hi);
    if !(size.is_finite() && size > 0.0) {
        return Err(Error::Geometry(
            "all points coincide; a convex hull needs a solid".into(),
        ));
    }
    let pts: Vec<DVec3> = points.iter().map(|p| (*p - centre) / size).collect();
    // A budget no smaller than the points cannot bind: the full hull, in its usual order.
    let budget = options
        .max_vertices
        .map(|m| m.max(4))
        .filter(|&m| m < points.len());
    let tris = quickhull(&pts, rel_tol, budget)?;
    let planes = merge::merge(&pts, &tris.faces, rel_tol);
    // Back to the caller's frame: n·q <= d with q = (p - c)/size.
    Ok(Hull {
        planes: planes
            .into_iter()
            .map(|(n, d)| Plane {
                normal: n,
                offset: d * size + n.dot(centre),
            })
            .collect(),
        vertices: tris.vertices,
        left_out: tris.left_out * size,
    })
}

#[derive(Clone)]
struct Face {
    v: [usize; 3],
    n: DVec3,
    d: f64,
    /// Points more than the tolerance above: candidate apexes.
    outside: Vec<usize>,
    /// Points above by less than the tolerance: on the face, kept for the offsets.
    near: Vec<usize>,
    alive: bool,
}

impl Face {
    fn new(pts: &[DVec3], v: [usize; 3]) -> Option<Face> {
        let [a, b, c] = v.map(|i| pts[i]);
        let n = (b - a).cross(c - a).try_normalize()?;
        Some(Face {
            v,
            n,
            d: n.dot(a),
            outside: Vec::new(),
            near: Vec::new(),
            alive: true,
        })
    }
    fn dist(&self, p: DVec3) -> f64 {
        self.n.dot(p) - self.d
    }
    fn edges(&self) -> [(usize, usize); 3] {
        let [a, b, c] = self.v;
        [(a, b), (b, c), (c, a)]
    }
}

fn degenerate() -> Error {
    Error::Geometry("the convex hull failed on numerically degenerate points".into())
}

/// The four corners of a starting tetrahedron as large as practical.
fn initial_simplex(pts: &[DVec3], flat_tol: f64) -> Result<[usize; 4]> {
    let mut ext = [0usize; 6];
    for (i, p) in pts.iter().enumerate() {
        for axis in 0..3 {
            if p[axis] < pts[ext[2 * axis]][axis] {
                ext[2 * axis] = i;
            }
            if p[axis] > pts[ext[2 * axis + 1]][axis] {
                ext[2 * axis + 1] = i;
            }
        }
    }
    let (mut i0, mut i1, mut best) = (0, 0, -1.0);
    for &a in &ext {
        for &b in &ext {
            let d = pts[a].distance_squared(pts[b]);
            if d > best {
                (i0, i1, best) = (a, b, d);
            }
        }
    }
    if best.sqrt() <= TINY {
        return Err(Error::Geometry(
            "all points coincide; a convex hull needs a solid".into(),
        ));
    }
    let axis = (pts[i1] - pts[i0]).normalize();
    let (mut i2, mut best) = (0, -1.0);
    for (i, p) in pts.iter().enumerate() {
        let r = *p - pts[i0];
        let d = (r - axis * r.dot(axis)).length();
        if d > best {
            (i2, best) = (i, d);
        }
    }
    if best <= TINY {
        return Err(Error::Geometry(
            "all points lie on one line; a convex hull needs a solid".into(),
        ));
    }
    let n = (pts[i1] - pts[i0]).cross(pts[i2] - pts[i0]).normalize();
    let (mut i3, mut best) = (0, -1.0);
    for (i, p) in pts.iter().enumerate() {
        let d = n.dot(*p - pts[i0]).abs();
        if d > best {
            (i3, best) = (i, d);
        }
    }
    if best <= flat_tol {
        return Err(Error::Geometry(format!(
            "all points lie in one plane (within {:.1e} of the size); a convex hull needs a solid",
            best
        )));
    }
    Ok([i0, i1, i2, i3])
}

/// Snapped copies of points in the unit box, on a grid of 2⁻⁴⁰, for exact orientation tests.
fn snap(pts: &[DVec3]) -> Vec<[i64; 3]> {
    const GRID: f64 = (1u64 << 40) as f64;
    pts.iter()
        .map(|p| p.to_array().map(|c| (c * GRID).round() as i64))
        .collect()
}

/// Exact sign of the volume of (a, b, c, p): positive when `p` lies above the triangle a, b, c
/// (counter-clockwise seen from above). Coordinates are at most 2³⁹ in size, so every product
/// fits in an `i128`.
fn orient(g: &[[i64; 3]], a: usize, b: usize, c: usize, p: usize) -> i128 {
    let d = |i: usize| [0, 1, 2].map(|k| i128::from(g[i][k] - g[a][k]));
    let (u, v, w) = (d(b), d(c), d(p));
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    n[0] * w[0] + n[1] * w[1] + n[2] * w[2]
}

/// What [`quickhull`] returns: the hull's triangles, how many vertices they have, and the
/// farthest a point left out (by a vertex budget) stands outside its triangles' planes.
struct Triangles {
    faces: Vec<Face>,
    vertices: usize,
    left_out: f64,
}

/// The order in which faces with points outside are taken: last made first (the full hull), or
/// the face with the farthest point first (a hull stopped at a vertex budget).
enum Frontier {
    Stack(Vec<usize>),
    Heap(BinaryHeap<(Far, usize)>),
}

/// A distance ordered for the heap (never NaN: the points are finite).
#[derive(Clone, Copy, PartialEq)]
struct Far(f64);

impl Eq for Far {}

impl PartialOrd for Far {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Far {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}

impl Frontier {
    fn push(&mut self, faces: &[Face], pts: &[DVec3], f: usize) {
        match self {
            Frontier::Stack(s) => s.push(f),
            Frontier::Heap(h) => {
                let face = &faces[f];
                if let Some(far) = face
                    .outside
                    .iter()
                    .map(|&i| face.dist(pts[i]))
                    .max_by(f64::total_cmp)
                {
                    h.push((Far(far), f));
                }
            }
        }
    }
    fn pop(&mut self) -> Option<usize> {
        match self {
            Frontier::Stack(s) => s.pop(),
            Frontier::Heap(h) => h.pop().map(|(_, f)| f),
        }
    }
}

/// Give point `i` to the first of `faces` it stands more than `on_face` above (a candidate
/// apex), else to the first it stands above at all (a point on that face, kept for the
/// offsets), else drop it (inside).
fn assign<'f>(faces: impl Iterator<Item = &'f mut Face>, pts: &[DVec3], i: usize, on_face: f64) {
    let mut near: Option<&mut Face> = None;
    for f in faces {
        let d = f.dist(pts[i]);
        if d > on_face {
            f.outside.push(i);
            return;
        }
        if d > 0.0 && near.is_none() {
            near = Some(f);
        }
    }
    if let Some(f) = near {
        f.near.push(i);
    }
}

/// Quickhull on points in a unit box; returns the hull's triangles, outward.
///
/// Which faces an apex sees is decided exactly (on the points snapped to a fine grid), so the
/// triangulation stays convex and the faces an apex sees always form a disk. Tolerances only
/// choose the apexes: a point within `tol / 2` of the hull counts as lying on it and never
/// becomes a hull vertex (it is kept with the face it stands on, and the merged facets'
/// offsets account for it). With a vertex `budget`, the face whose farthest point is the
/// farthest of all is grown first, and the growing stops at the budget.
fn quickhull(pts: &[DVec3], tol: f64, budget: Option<usize>) -> Result<Triangles> {
    let on_face = 0.5 * tol;
    let grid = snap(pts);
    let s = initial_simplex(pts, tol)?;
    let mut faces: Vec<Face> = Vec::new();
    let mut edge_face: FastMap<(usize, usize), usize> = fast_map(6 * pts.len().min(1 << 20));
    for (a, b, c, d) in [(0, 1, 2, 3), (0, 1, 3, 2), (0, 2, 3, 1), (1, 2, 3, 0)] {
        let mut v = [s[a], s[b], s[c]];
        if orient(&grid, v[0], v[1], v[2], s[d]) > 0 {
            v.swap(1, 2);
        }
        let f = Face::new(pts, v).ok_or_else(degenerate)?;
        for e in f.edges() {
            edge_face.insert(e, faces.len());
        }
        faces.push(f);
    }
    for i in 0..pts.len() {
        if !s.contains(&i) {
            assign(faces.iter_mut(), pts, i, on_face);
        }
    }
    let mut frontier = match budget {
        None => Frontier::Stack(Vec::new()),
        Some(_) => Frontier::Heap(BinaryHeap::new()),
    };
    for f in 0..faces.len() {
        frontier.push(&faces, pts, f);
    }
    let mut vertices = 4;
    let mut mark: Vec<usize> = vec![usize::MAX; faces.len()];
    let mut stamp = 0usize;
    let mut rounds = 0usize;
    // Each round adds a hull vertex or drops a point, so the loop ends.
    while budget.is_none_or(|b| vertices < b) {
        let Some(fi) = frontier.pop() else {
            break;
        };
        if !faces[fi].alive || faces[fi].outside.is_empty() {
            continue;
        }
        rounds += 1;
        if rounds > 2 * pts.len() + 8 {
            return Err(degenerate());
        }
        let face = &faces[fi];
        let (slot, apex) = face
            .outside
            .iter()
            .copied()
            .enumerate()
            .max_by(|a, b| face.dist(pts[a.1]).total_cmp(&face.dist(pts[b.1])))
            .ok_or_else(degenerate)?;
        stamp += 1;
        let (visible, horizon) =
            visible_region(&faces, &edge_face, &grid, fi, apex, &mut mark, stamp)?;
        if visible.is_empty() || !is_simple_loop(&horizon) {
            // Only possible when snapping moved the apex onto the hull: it is within the
            // tolerance, and the final planes still enclose it.
            let i = faces[fi].outside.swap_remove(slot);
            faces[fi].near.push(i);
            frontier.push(&faces, pts, fi);
            continue;
        }
        let mut orphans = Vec::new();
        for &f in &visible {
            faces[f].alive = false;
            orphans.append(&mut faces[f].outside);
            orphans.append(&mut faces[f].near);
            for e in faces[f].edges() {
                edge_face.remove(&e);
            }
        }
        // The visible faces' corners off the horizon are no longer on the hull.
        let mut rim: Vec<usize> = horizon.iter().map(|e| e.0).collect();
        rim.sort_unstable();
        let mut inner: Vec<usize> = visible
            .iter()
            .flat_map(|&f| faces[f].v)
            .filter(|v| rim.binary_search(v).is_err())
            .collect();
        inner.sort_unstable();
        inner.dedup();
        let first_new = faces.len();
        for (a, b) in horizon {
            let f = Face::new(pts, [a, b, apex]).ok_or_else(degenerate)?;
            for e in f.edges() {
                if edge_face.insert(e, faces.len()).is_some() {
                    return Err(degenerate());
                }
            }
            faces.push(f);
            mark.push(usize::MAX);
        }
        vertices = vertices + 1 - inner.len();
        for i in orphans {
            if i != apex {
                assign(faces[first_new..].iter_mut(), pts, i, on_face);
            }
        }
        for f in first_new..faces.len() {
            frontier.push(&faces, pts, f);
        }
    }
    // Points left out by the budget: how far each stands outside the hull's triangles (the
    // largest over the faces, found by climbing from the face it was given to).
    let mut left_out = 0.0f64;
    for (fi, face) in faces.iter().enumerate() {
        if !face.alive {
            continue;
        }
        for &i in &face.outside {
            let p = pts[i];
            let (mut at, mut d) = (fi, face.dist(p));
            loop {
                let better = faces[at].edges().iter().find_map(|&(a, b)| {
                    let g = *edge_face.get(&(b, a))?;
                    let dg = faces[g].dist(p);
                    (dg > d).then_some((g, dg))
                });
                match better {
                    Some((g, dg)) => (at, d) = (g, dg),
                    None => break,
                }
            }
            left_out = left_out.max(d);
        }
    }
    Ok(Triangles {
        faces: faces.into_iter().filter(|f| f.alive).collect(),
        vertices,
        left_out,
    })
}

/// The faces connected to `seed` that the point `apex` lies strictly above (decided exactly),
/// and the boundary of that region (edges of those faces whose other face is not seen). Empty
/// if the apex does not see `seed` itself.
#[allow(clippy::type_complexity)]
fn visible_region(
    faces: &[Face],
    edge_face: &FastMap<(usize, usize), usize>,
    grid: &[[i64; 3]],
    seed: usize,
    apex: usize,
    mark: &mut [usize],
    stamp: usize,
) -> Result<(Vec<usize>, Vec<(usize, usize)>)> {
    let sees = |f: &Face| orient(grid, f.v[0], f.v[1], f.v[2], apex) > 0;
    if !sees(&faces[seed]) {
        return Ok((Vec::new(), Vec::new()));
    }
    let mut visible = vec![seed];
    mark[seed] = stamp;
    let mut k = 0;
    while k < visible.len() {
        let f = visible[k];
        k += 1;
        for (a, b) in faces[f].edges() {
            let g = *edge_face.get(&(b, a)).ok_or_else(degenerate)?;
            if mark[g] != stamp && faces[g].alive && sees(&faces[g]) {
                mark[g] = stamp;
                visible.push(g);
            }
        }
    }
    let mut horizon = Vec::new();
    for &f in &visible {
        for (a, b) in faces[f].edges() {
            let g = *edge_face.get(&(b, a)).ok_or_else(degenerate)?;
            if mark[g] != stamp {
                horizon.push((a, b));
            }
        }
    }
    Ok((visible, horizon))
}

/// Whether directed edges form exactly one closed loop through distinct vertices (the
/// horizon is short: a sort and binary searches, no map).
fn is_simple_loop(edges: &[(usize, usize)]) -> bool {
    let mut next: Vec<(usize, usize)> = edges.to_vec();
    next.sort_unstable();
    if next.windows(2).any(|w| w[0].0 == w[1].0) {
        return false;
    }
    let Some(&(start, _)) = edges.first() else {
        return false;
    };
    let mut v = start;
    for steps in 1..=edges.len() {
        match next.binary_search_by_key(&v, |e| e.0) {
            Ok(k) => v = next[k].1,
            Err(_) => return false,
        }
        if v == start {
            return steps == edges.len();
        }
    }
    false
}

#[cfg(test)]
mod tests;
