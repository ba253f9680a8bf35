//! 3-D convex hull of a point set, returned as facet planes.
//!
//! Quickhull with a tolerance: the points are first moved and scaled into a unit box (the hull
//! does not change under translation and uniform scaling, and every tolerance becomes relative
//! to the size of the point set). A point within `1e-10` of a face counts as lying on it. The
//! hull's triangles are then merged into one facet per plane: triangles are taken largest first,
//! and a triangle joins an existing facet when all three of its corners lie within the merge
//! tolerance of that facet's plane (so a cube's 12 STL triangles become 6 facets). Each facet's
//! normal is the area-weighted mean of its triangles' normals and its offset is the largest
//! `normal · p` over all points, so every point lies inside or on every returned plane.

use super::{DVec3, Plane};
use crate::error::{Error, Result};
use std::collections::HashMap;

/// Default merge tolerance of [`convex_hull`]: corners within `1e-7 × size` of a facet's plane
/// belong to that facet (size: the largest side of the points' bounding box).
pub const MERGE_TOL: f64 = 1e-7;

/// A point this close to a face (in units of the size) lies on it, not outside.
const ON_FACE: f64 = 1e-10;

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
    let rel_tol = if rel_tol.is_finite() && rel_tol > ON_FACE {
        rel_tol
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
    if best.sqrt() <= ON_FACE {
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
    if best <= ON_FACE {
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

/// Quickhull on points in a unit box; returns the hull's triangles, outward.
fn quickhull(pts: &[DVec3], flat_tol: f64) -> Result<Vec<Face>> {
    let s = initial_simplex(pts, flat_tol)?;
    let inner = s.iter().map(|&i| pts[i]).sum::<DVec3>() / 4.0;
    let mut faces: Vec<Face> = Vec::new();
    let mut edge_face: HashMap<(usize, usize), usize> = HashMap::new();
    for (a, b, c) in [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)] {
        let mut v = [s[a], s[b], s[c]];
        let f = Face::new(pts, v).ok_or_else(degenerate)?;
        if f.dist(inner) > 0.0 {
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
        if let Some(f) = faces.iter_mut().find(|f| f.dist(*p) > ON_FACE) {
            f.outside.push(i);
        }
    }
    let mut stack: Vec<usize> = (0..faces.len()).collect();
    let mut mark: Vec<usize> = vec![usize::MAX; faces.len()];
    let mut round = 0usize;
    // Each round adds one hull vertex, so the loop ends after at most len() rounds.
    while let Some(fi) = stack.pop() {
        if !faces[fi].alive || faces[fi].outside.is_empty() {
            continue;
        }
        round += 1;
        if round > pts.len() + 8 {
            return Err(degenerate());
        }
        let face = &faces[fi];
        let apex = face
            .outside
            .iter()
            .copied()
            .max_by(|&a, &b| face.dist(pts[a]).total_cmp(&face.dist(pts[b])))
            .ok_or_else(degenerate)?;
        let p = pts[apex];
        // Visible faces: connected to fi, apex strictly above them.
        let mut visible = vec![fi];
        mark[fi] = round;
        let mut k = 0;
        while k < visible.len() {
            let f = visible[k];
            k += 1;
            for (a, b) in faces[f].edges() {
                let g = *edge_face.get(&(b, a)).ok_or_else(degenerate)?;
                if mark[g] != round && faces[g].alive && faces[g].dist(p) > ON_FACE {
                    mark[g] = round;
                    visible.push(g);
                }
            }
        }
        let mut horizon = Vec::new();
        for &f in &visible {
            for (a, b) in faces[f].edges() {
                let g = *edge_face.get(&(b, a)).ok_or_else(degenerate)?;
                if mark[g] != round {
                    horizon.push((a, b));
                }
            }
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
                .find(|f| f.dist(pts[i]) > ON_FACE)
            {
                f.outside.push(i);
            }
        }
        stack.extend(first_new..faces.len());
    }
    Ok(faces.into_iter().filter(|f| f.alive).collect())
}

/// Merge hull triangles into planes `(unit normal, offset)`.
fn merge(pts: &[DVec3], tris: &[Face], tol: f64) -> Vec<(DVec3, f64)> {
    struct Cluster {
        area: DVec3,
        n: DVec3,
        sum: DVec3,
        count: f64,
    }
    let mut order: Vec<(f64, usize)> = tris
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let [a, b, c] = t.v.map(|k| pts[k]);
            ((b - a).cross(c - a).length(), i)
        })
        .collect();
    order.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
    let mut clusters: Vec<Cluster> = Vec::new();
    for (_, ti) in order {
        let t = &tris[ti];
        let corners = t.v.map(|k| pts[k]);
        let area = 0.5 * (corners[1] - corners[0]).cross(corners[2] - corners[0]);
        let mut best: Option<(usize, f64)> = None;
        for (ci, c) in clusters.iter().enumerate() {
            if area.dot(c.n) < 0.0 {
                continue;
            }
            let d = c.n.dot(c.sum / c.count);
            let dev = corners
                .iter()
                .map(|p| (c.n.dot(*p) - d).abs())
                .fold(0.0, f64::max);
            if dev <= tol && best.is_none_or(|(_, b)| dev < b) {
                best = Some((ci, dev));
            }
        }
        match best {
            Some((ci, _)) => {
                let c = &mut clusters[ci];
                c.area += area;
                c.n = c.area.try_normalize().unwrap_or(c.n);
                c.sum += corners[0] + corners[1] + corners[2];
                c.count += 3.0;
            }
            None => clusters.push(Cluster {
                area,
                n: t.n,
                sum: corners[0] + corners[1] + corners[2],
                count: 3.0,
            }),
        }
    }
    let mut out: Vec<(DVec3, f64)> = Vec::with_capacity(clusters.len());
    for c in clusters {
        let n = c.n;
        let d = pts
            .iter()
            .map(|p| n.dot(*p))
            .fold(f64::NEG_INFINITY, f64::max);
        if !out
            .iter()
            .any(|(m, e)| m.distance(n) <= tol && (e - d).abs() <= tol)
        {
            out.push((n, d));
        }
    }
    out
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
        assert_eq!(s.vertices.len(), 8);
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
        let planes = convex_hull(&cut.solid.vertices).unwrap();
        assert_eq!(planes.len(), cut.solid.facets.len());
        let s = solid(&planes);
        assert!(
            (s.volume() - cut.solid.volume()).abs() < 1e-9,
            "{} vs {}",
            s.volume(),
            cut.solid.volume()
        );
        for f in &cut.solid.facets {
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
}
