//! Quickhull on points in a unit box: faces, the starting simplex, exact orientation on snapped
//! copies of the points, and the frontier of the farthest points outside.

use crate::error::{Error, Result};
use crate::geometry::fast_hash::{fast_map, FastMap};
use crate::geometry::DVec3;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Points closer than this (in units of the size) count as the same point or line.
pub(super) const TINY: f64 = 1e-10;

#[derive(Clone)]
pub(super) struct Face {
    pub(super) v: [usize; 3],
    pub(super) n: DVec3,
    pub(super) d: f64,
    /// Points more than the tolerance above: candidate apexes.
    pub(super) outside: Vec<usize>,
    /// Points above by less than the tolerance: on the face, kept for the offsets.
    pub(super) near: Vec<usize>,
    pub(super) alive: bool,
}

impl Face {
    pub(super) fn new(pts: &[DVec3], v: [usize; 3]) -> Option<Face> {
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
    pub(super) fn dist(&self, p: DVec3) -> f64 {
        self.n.dot(p) - self.d
    }
    pub(super) fn edges(&self) -> [(usize, usize); 3] {
        let [a, b, c] = self.v;
        [(a, b), (b, c), (c, a)]
    }
}

pub(super) fn degenerate() -> Error {
    Error::Geometry("the convex hull failed on numerically degenerate points".into())
}

/// The four corners of a starting tetrahedron as large as practical.
pub(super) fn initial_simplex(pts: &[DVec3], flat_tol: f64) -> Result<[usize; 4]> {
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
pub(super) fn snap(pts: &[DVec3]) -> Vec<[i64; 3]> {
    const GRID: f64 = (1u64 << 40) as f64;
    pts.iter()
        .map(|p| p.to_array().map(|c| (c * GRID).round() as i64))
        .collect()
}

/// Exact sign of the volume of (a, b, c, p): positive when `p` lies above the triangle a, b, c
/// (counter-clockwise seen from above). Coordinates are at most 2³⁹ in size, so every product
/// fits in an `i128`.
pub(super) fn orient(g: &[[i64; 3]], a: usize, b: usize, c: usize, p: usize) -> i128 {
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
pub(super) struct Triangles {
    pub(super) faces: Vec<Face>,
    pub(super) vertices: usize,
    pub(super) left_out: f64,
}

/// The order in which faces with points outside are taken: last made first (the full hull), or
/// the face with the farthest point first (a hull stopped at a vertex budget).
pub(super) enum Frontier {
    Stack(Vec<usize>),
    Heap(BinaryHeap<(Far, usize)>),
}

/// A distance ordered for the heap (never NaN: the points are finite).
#[derive(Clone, Copy, PartialEq)]
pub(super) struct Far(f64);

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
pub(super) fn assign<'f>(
    faces: impl Iterator<Item = &'f mut Face>,
    pts: &[DVec3],
    i: usize,
    on_face: f64,
) {
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
pub(super) fn quickhull(pts: &[DVec3], tol: f64, budget: Option<usize>) -> Result<Triangles> {
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
pub(super) fn visible_region(
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
pub(super) fn is_simple_loop(edges: &[(usize, usize)]) -> bool {
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
