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
//! facets): facets grow from the largest triangle across shared edges, taking a neighbour when
//! its three corners lie within the merge tolerance of the facet's plane. A facet's normal is
//! the area-weighted mean of its well-aligned triangles' normals, its offset the largest
//! `normal · p` over all points, so every point lies inside or on every returned plane.

use super::{DVec3, Plane};
use crate::error::{Error, Result};
use std::collections::HashMap;

/// Default merge tolerance of [`convex_hull`]: corners within `1e-7 × size` of a facet's plane
/// belong to that facet (size: the largest side of the points' bounding box).
pub const MERGE_TOL: f64 = 1e-7;

/// Points closer than this (in units of the size) count as the same point or line.
const TINY: f64 = 1e-10;

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
    let tris = quickhull(&pts, rel_tol)?;
    let planes = merge(&pts, &tris, rel_tol);
    // Back to the caller's frame: n·q <= d with q = (p - c)/size.
    Ok(planes
        .into_iter()
        .map(|(n, d)| Plane {
            normal: n,
            offset: d * size + n.dot(centre),
        })
        .collect())
}

#[derive(Clone)]
struct Face {
    v: [usize; 3],
    n: DVec3,
    d: f64,
    outside: Vec<usize>,
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

/// Quickhull on points in a unit box; returns the hull's triangles, outward.
///
/// Which faces an apex sees is decided exactly (on the points snapped to a fine grid), so the
/// triangulation stays convex and the faces an apex sees always form a disk. Tolerances only
/// choose the apexes: a point within `tol / 2` of the hull counts as lying on it and never
/// becomes a hull vertex (the merged facets and their offsets still account for it).
fn quickhull(pts: &[DVec3], tol: f64) -> Result<Vec<Face>> {
    let on_face = 0.5 * tol;
    let grid = snap(pts);
    let s = initial_simplex(pts, tol)?;
    let mut faces: Vec<Face> = Vec::new();
    let mut edge_face: HashMap<(usize, usize), usize> = HashMap::new();
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
    for (i, p) in pts.iter().enumerate() {
        if s.contains(&i) {
            continue;
        }
        if let Some(f) = faces.iter_mut().find(|f| f.dist(*p) > on_face) {
            f.outside.push(i);
        }
    }
    let mut stack: Vec<usize> = (0..faces.len()).collect();
    let mut mark: Vec<usize> = vec![usize::MAX; faces.len()];
    let mut stamp = 0usize;
    let mut rounds = 0usize;
    // Each round adds a hull vertex or drops a point, so the loop ends.
    while let Some(fi) = stack.pop() {
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
            faces[fi].outside.swap_remove(slot);
            stack.push(fi);
            continue;
        }
        let mut orphans = Vec::new();
        for &f in &visible {
            faces[f].alive = false;
            orphans.append(&mut faces[f].outside);
            for e in faces[f].edges() {
                edge_face.remove(&e);
            }
        }
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
        for i in orphans {
            if i == apex {
                continue;
            }
            if let Some(f) = faces[first_new..]
                .iter_mut()
                .find(|f| f.dist(pts[i]) > on_face)
            {
                f.outside.push(i);
            }
        }
        stack.extend(first_new..faces.len());
    }
    Ok(faces.into_iter().filter(|f| f.alive).collect())
}

/// The faces connected to `seed` that the point `apex` lies strictly above (decided exactly),
/// and the boundary of that region (edges of those faces whose other face is not seen). Empty
/// if the apex does not see `seed` itself.
#[allow(clippy::type_complexity)]
fn visible_region(
    faces: &[Face],
    edge_face: &HashMap<(usize, usize), usize>,
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

/// Whether directed edges form exactly one closed loop through distinct vertices.
fn is_simple_loop(edges: &[(usize, usize)]) -> bool {
    let mut next: HashMap<usize, usize> = HashMap::with_capacity(edges.len());
    for &(a, b) in edges {
        if next.insert(a, b).is_some() {
            return false;
        }
    }
    let Some(&(start, _)) = edges.first() else {
        return false;
    };
    let mut v = start;
    for steps in 1..=edges.len() {
        match next.get(&v) {
            Some(&w) => v = w,
            None => return false,
        }
        if v == start {
            return steps == edges.len();
        }
    }
    false
}

/// Merge hull triangles into planes `(unit normal, offset)`.
///
/// Facets grow from the largest triangle over shared edges: a neighbour joins when its corners
/// lie within `tol` of the facet's current plane. Adjacent facets whose planes still agree
/// within `tol` are then joined (a triangle turned away early, before the plane had settled).
fn merge(pts: &[DVec3], tris: &[Face], tol: f64) -> Vec<(DVec3, f64)> {
    struct Cluster {
        area: DVec3,
        n: DVec3,
        sum: DVec3,
        count: f64,
    }
    impl Cluster {
        fn offset(&self) -> f64 {
            self.n.dot(self.sum / self.count)
        }
        fn add(&mut self, area: DVec3, corners: [DVec3; 3]) {
            // A sliver along an edge may have its corners within the tolerance and its normal
            // far off: it joins the facet without tilting it.
            if area.dot(self.n) >= area.length() * ALIGNED {
                self.area += area;
            }
            self.n = self.area.try_normalize().unwrap_or(self.n);
            self.sum += corners[0] + corners[1] + corners[2];
            self.count += 3.0;
        }
    }
    /// cos 2°: triangles whose normal is within 2° of the facet's set its normal.
    const ALIGNED: f64 = 0.99939;
    let corners: Vec<[DVec3; 3]> = tris.iter().map(|t| t.v.map(|k| pts[k])).collect();
    let areas: Vec<DVec3> = corners
        .iter()
        .map(|c| 0.5 * (c[1] - c[0]).cross(c[2] - c[0]))
        .collect();
    let mut edge_tri: HashMap<(usize, usize), usize> = HashMap::with_capacity(3 * tris.len());
    for (i, t) in tris.iter().enumerate() {
        for e in t.edges() {
            edge_tri.insert(e, i);
        }
    }
    let mut order: Vec<usize> = (0..tris.len()).collect();
    order.sort_by(|&a, &b| {
        areas[b]
            .length()
            .total_cmp(&areas[a].length())
            .then(a.cmp(&b))
    });
    let mut owner = vec![usize::MAX; tris.len()];
    let mut clusters: Vec<Cluster> = Vec::new();
    let mut queue = std::collections::VecDeque::new();
    for seed in order {
        if owner[seed] != usize::MAX {
            continue;
        }
        let id = clusters.len();
        let mut c = Cluster {
            area: DVec3::ZERO,
            n: tris[seed].n,
            sum: DVec3::ZERO,
            count: 0.0,
        };
        c.add(areas[seed], corners[seed]);
        owner[seed] = id;
        queue.push_back(seed);
        while let Some(t) = queue.pop_front() {
            for (a, b) in tris[t].edges() {
                let Some(&u) = edge_tri.get(&(b, a)) else {
                    continue;
                };
                // Orientation is not checked: among nearly coplanar points rounding can fold a
                // few triangles over; their area then counts negative, as it should.
                if owner[u] != usize::MAX {
                    continue;
                }
                let d = c.offset();
                if corners[u].iter().all(|p| (c.n.dot(*p) - d).abs() <= tol) {
                    owner[u] = id;
                    c.add(areas[u], corners[u]);
                    queue.push_back(u);
                }
            }
        }
        clusters.push(c);
    }
    // Join adjacent clusters whose planes agree (union–find over shared edges).
    let mut parent: Vec<usize> = (0..clusters.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for (t, tri) in tris.iter().enumerate() {
        for (a, b) in tri.edges() {
            let Some(&u) = edge_tri.get(&(b, a)) else {
                continue;
            };
            let (ci, cj) = (root(&mut parent, owner[t]), root(&mut parent, owner[u]));
            if ci == cj {
                continue;
            }
            let (x, y) = (&clusters[ci], &clusters[cj]);
            if x.n.distance(y.n) + (x.offset() - y.offset()).abs() <= tol {
                parent[cj] = ci;
            }
        }
    }
    let mut joined: HashMap<usize, DVec3> = HashMap::new();
    let mut roots: Vec<usize> = Vec::new();
    for (i, c) in clusters.iter().enumerate() {
        let r = root(&mut parent, i);
        let e = joined.entry(r).or_insert_with(|| {
            roots.push(r);
            DVec3::ZERO
        });
        *e += c.area;
    }
    let planes: Vec<(DVec3, f64)> = roots
        .into_iter()
        .filter_map(|r| {
            let n = joined[&r].try_normalize().unwrap_or(clusters[r].n);
            let d = pts
                .iter()
                .map(|p| n.dot(*p))
                .fold(f64::NEG_INFINITY, f64::max);
            // A facet is a polygon resting on the points; a plane that touches them only in a
            // point or along an edge is a sliver of rounding, and dropping it changes nothing.
            spans_a_facet(pts, n, d, tol).then_some((n, d))
        })
        .collect();
    // The same plane twice (parts of one facet kept apart by a dropped sliver): keep one.
    let mut order: Vec<usize> = (0..planes.len()).collect();
    order.sort_by(|&a, &b| planes[a].0.x.total_cmp(&planes[b].0.x));
    let mut keep = vec![true; planes.len()];
    for (k, &i) in order.iter().enumerate() {
        if !keep[i] {
            continue;
        }
        for &j in &order[k + 1..] {
            if planes[j].0.x - planes[i].0.x > tol {
                break;
            }
            let (a, b) = (planes[i], planes[j]);
            if a.0.distance(b.0) + (a.1 - b.1).abs() <= tol {
                keep[j] = false;
            }
        }
    }
    planes
        .into_iter()
        .zip(keep)
        .filter_map(|(p, k)| k.then_some(p))
        .collect()
}

/// Smallest facet area kept (in units of the size squared): a facet must be a polygon, not a
/// point or an edge, also for [`super::Polyhedron::from_planes`].
const MIN_AREA: f64 = 1e-10;

/// Whether the points within `tol` of the plane `n·x = d` span a polygon of at least
/// [`MIN_AREA`].
fn spans_a_facet(pts: &[DVec3], n: DVec3, d: f64, tol: f64) -> bool {
    let (u, v) = n.any_orthonormal_pair();
    let mut flat: Vec<(f64, f64)> = pts
        .iter()
        .filter(|p| d - n.dot(**p) <= tol)
        .map(|p| (u.dot(*p), v.dot(*p)))
        .collect();
    if flat.len() < 3 {
        return false;
    }
    flat.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    // Monotone chain: lower and upper hulls, then the shoelace area.
    let mut hull: Vec<(f64, f64)> = Vec::with_capacity(2 * flat.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(f64, f64)>> = if pass == 0 {
            Box::new(flat.iter())
        } else {
            Box::new(flat.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    let area: f64 = (0..hull.len())
        .map(|i| {
            let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
            a.0 * b.1 - a.1 * b.0
        })
        .sum::<f64>()
        / 2.0;
    area > MIN_AREA
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{FacetPlane, Polyhedron};
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    fn solid(planes: &[Plane]) -> Polyhedron {
        let fps: Vec<FacetPlane> = planes
            .iter()
            .enumerate()
            .map(|(i, p)| FacetPlane {
                plane: *p,
                name: format!("h{i}"),
                tier: "h".into(),
            })
            .collect();
        Polyhedron::from_planes(&fps).unwrap()
    }

    #[test]
    fn random_points_in_a_cube_give_six_facets() {
        let mut rng = SmallRng::seed_from_u64(7);
        let mut pts: Vec<DVec3> = (0..2000)
            .map(|_| DVec3::new(rng.random(), rng.random(), rng.random()))
            .collect();
        for k in 0..8 {
            pts.push(DVec3::new(
                (k & 1) as f64,
                ((k >> 1) & 1) as f64,
                ((k >> 2) & 1) as f64,
            ));
        }
        // Shuffle the corners in among the rest.
        for i in (1..pts.len()).rev() {
            pts.swap(i, rng.random_range(0..=i));
        }
        let planes = convex_hull(&pts).unwrap();
        assert_eq!(planes.len(), 6);
        let s = solid(&planes);
        assert!((s.volume() - 1.0).abs() < 1e-12, "volume {}", s.volume());
        assert_eq!(s.vertices().len(), 8);
    }

    #[test]
    fn cube_triangles_merge_and_points_on_faces_are_ignored() {
        // Corners plus points on faces and edges (coplanar with the hull): still 6 facets.
        let mut pts = Vec::new();
        for i in 0..=4 {
            for j in 0..=4 {
                for k in 0..=4 {
                    pts.push(DVec3::new(i as f64, j as f64, k as f64) * 0.25 - 3.0);
                }
            }
        }
        let planes = convex_hull(&pts).unwrap();
        assert_eq!(planes.len(), 6);
        assert!((solid(&planes).volume() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn round_brilliant_vertices_rebuild_the_same_solid() {
        let cut =
            crate::cut::Cut::from_family("rb", "round-brilliant", &Default::default()).unwrap();
        let planes = convex_hull(cut.solid.vertices()).unwrap();
        assert_eq!(planes.len(), cut.solid.facets().len());
        let s = solid(&planes);
        assert!(
            (s.volume() - cut.solid.volume()).abs() < 1e-9,
            "{} vs {}",
            s.volume(),
            cut.solid.volume()
        );
        for f in cut.solid.facets() {
            let best = planes
                .iter()
                .map(|p| p.normal.distance(f.plane.normal) + (p.offset - f.plane.offset).abs())
                .fold(f64::INFINITY, f64::min);
            assert!(best < 1e-9, "{} off by {best}", f.name);
        }
    }

    #[test]
    fn degenerate_inputs_are_errors() {
        let e = convex_hull(&[DVec3::ZERO, DVec3::X, DVec3::Y])
            .unwrap_err()
            .to_string();
        assert!(e.contains("at least 4"), "{e}");
        let flat: Vec<DVec3> = (0..10)
            .map(|i| DVec3::new(i as f64, (i * i) as f64, 0.0))
            .collect();
        let e = convex_hull(&flat).unwrap_err().to_string();
        assert!(e.contains("one plane"), "{e}");
        let line: Vec<DVec3> = (0..10).map(|i| DVec3::splat(i as f64)).collect();
        assert!(convex_hull(&line)
            .unwrap_err()
            .to_string()
            .contains("one line"));
        assert!(convex_hull(&[DVec3::ONE; 5])
            .unwrap_err()
            .to_string()
            .contains("coincide"));
        let mut bad = flat.clone();
        bad[3].z = f64::NAN;
        assert!(convex_hull(&bad)
            .unwrap_err()
            .to_string()
            .contains("point 4"));
    }

    #[test]
    fn every_point_is_inside_every_plane() {
        let mut rng = SmallRng::seed_from_u64(3);
        // Points on a sphere: many facets, all hull points.
        let pts: Vec<DVec3> = (0..1000)
            .map(|_| {
                let v = DVec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                v.normalize_or(DVec3::X) * 5.0 + DVec3::new(100.0, -40.0, 7.0)
            })
            .collect();
        let planes = convex_hull(&pts).unwrap();
        for p in &planes {
            for q in &pts {
                assert!(p.distance(*q) <= 1e-12 * 100.0);
            }
        }
        let s = solid(
            &planes
                .iter()
                .map(|p| Plane {
                    normal: p.normal,
                    offset: p.offset - p.normal.dot(DVec3::new(100.0, -40.0, 7.0)),
                })
                .collect::<Vec<_>>(),
        );
        // A sphere of radius 5 sampled with 3000 points holds most of its volume.
        let v = s.volume() / (4.0 / 3.0 * std::f64::consts::PI * 125.0);
        assert!(v > 0.97 && v < 1.0, "{v}");
    }

    /// A random polytope (planes tangent to a sphere), sampled by its vertices, points on its
    /// facets and points inside, optionally disturbed; returns the solid and the points.
    fn sampled_polytope(seed: u64, mode: u64) -> Option<(Polyhedron, Vec<DVec3>, f64)> {
        let mut rng = SmallRng::seed_from_u64(seed);
        let unit = |rng: &mut SmallRng| {
            DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
        };
        let planes: Vec<FacetPlane> = (0..rng.random_range(8..80))
            .map(|i| {
                FacetPlane::new(
                    unit(&mut rng).normalize_or(DVec3::X),
                    0.4,
                    format!("p{i}"),
                    "t",
                )
            })
            .collect();
        let solid = Polyhedron::from_planes(&planes).ok()?;
        let mut pts: Vec<DVec3> = solid.vertices().to_vec();
        for i in 0..solid.facets().len() {
            let poly = solid.facet_polygon(i);
            for _ in 0..rng.random_range(0..30) {
                let w: Vec<f64> = poly.iter().map(|_| rng.random::<f64>()).collect();
                let total: f64 = w.iter().sum();
                pts.push(poly.iter().zip(&w).map(|(p, w)| *p * *w).sum::<DVec3>() / total);
            }
        }
        let c = solid.centroid();
        for _ in 0..200 {
            let v = solid.vertices()[rng.random_range(0..solid.vertices().len())];
            pts.push(c + (v - c) * rng.random_range(0.0..0.99));
        }
        let tol = match mode {
            // Exact.
            0 => 1e-7,
            // Jitter of 1e-9: coplanar points are no longer coplanar.
            1 => {
                for p in &mut pts {
                    *p += unit(&mut rng) * 1e-9;
                }
                1e-7
            }
            // Single precision, as in binary STL.
            2 => {
                for p in &mut pts {
                    *p = p.as_vec3().as_dvec3();
                }
                1e-6
            }
            // Five decimals, as in a coarse text export.
            _ => {
                for p in &mut pts {
                    *p = (*p * 1e5).round() / 1e5;
                }
                1e-4
            }
        };
        for i in (1..pts.len()).rev() {
            pts.swap(i, rng.random_range(0..=i));
        }
        Some((solid, pts, tol))
    }

    #[test]
    fn random_polytopes_are_rebuilt_from_noisy_samples() {
        let mut worst = [0.0f64; 4];
        let mut cases = 0;
        for seed in 0..160u64 {
            let mode = seed % 4;
            let Some((truth, pts, tol)) = sampled_polytope(seed, mode) else {
                continue;
            };
            cases += 1;
            let planes = convex_hull_with_tolerance(&pts, tol)
                .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
            assert_eq!(
                planes.len(),
                truth.facets().len(),
                "seed {seed} mode {mode}"
            );
            for f in truth.facets() {
                let off = planes
                    .iter()
                    .map(|p| {
                        p.normal
                            .distance(f.plane.normal)
                            .max((p.offset - f.plane.offset).abs())
                    })
                    .fold(f64::INFINITY, f64::min);
                worst[mode as usize] = worst[mode as usize].max(off);
            }
            let dv = (solid(&planes).volume() - truth.volume()).abs();
            assert!(
                dv < 100.0 * tol,
                "seed {seed} mode {mode}: volume off by {dv:e}"
            );
        }
        assert!(cases > 100);
        // Planes as good as the data: exact, 1e-9 jitter, f32, five decimals.
        assert!(
            worst[0] < 1e-12 && worst[1] < 1e-7 && worst[2] < 1e-5 && worst[3] < 1e-3,
            "{worst:?}"
        );
    }

    #[test]
    fn a_facet_must_be_a_polygon() {
        let square = |s: f64| -> Vec<DVec3> {
            vec![
                DVec3::ZERO,
                DVec3::X * s,
                DVec3::new(s, s, 0.0),
                DVec3::Y * s,
                DVec3::new(0.3, 0.2, -1.0),
            ]
        };
        assert!(spans_a_facet(&square(1.0), DVec3::Z, 0.0, 1e-7));
        assert!(!spans_a_facet(&square(1e-6), DVec3::Z, 0.0, 1e-7));
        // Points along a line only.
        let line: Vec<DVec3> = (0..5).map(|i| DVec3::X * i as f64).collect();
        assert!(!spans_a_facet(&line, DVec3::Z, 0.0, 1e-7));
    }

    #[test]
    fn jittered_cube_surface_gives_six_facets() {
        let mut rng = SmallRng::seed_from_u64(5);
        for jitter in [0.0, 1e-13, 1e-11, 1e-9, 1e-8] {
            let mut pts = Vec::new();
            for i in 0..=20 {
                for j in 0..=20 {
                    for k in 0..=20 {
                        if [i, j, k].iter().any(|&c| c == 0 || c == 20) {
                            let d = DVec3::new(
                                rng.random_range(-1.0..1.0),
                                rng.random_range(-1.0..1.0),
                                rng.random_range(-1.0..1.0),
                            );
                            pts.push(DVec3::new(i as f64, j as f64, k as f64) / 20.0 + d * jitter);
                        }
                    }
                }
            }
            let planes = convex_hull(&pts).unwrap();
            assert_eq!(planes.len(), 6, "jitter {jitter}");
            assert!((solid(&planes).volume() - 1.0).abs() < 1e-7);
        }
    }
}
