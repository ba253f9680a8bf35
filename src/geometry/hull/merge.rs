//! Merging the hull's triangles into one plane per facet, in time linear in the triangles.
//!
//! Facets grow from the largest triangle over shared edges: a neighbour joins when its corners
//! lie within `tol` of the facet's current plane. Adjacent facets whose planes still agree
//! within `tol` are then joined (a triangle turned away early, before the plane had settled).
//! Each facet's offset is the largest `normal · p` over the hull's vertices, found by climbing
//! the hull's edges from one of its corners (on a convex solid a linear function has no local
//! maximum but the top), and over the points left lying on its triangles and its neighbours'.
//! A facet must span a polygon: the points within `tol` of its plane are gathered by walking
//! the edges from the top vertex (on a convex solid the vertices above any level are
//! connected), and a plane that touches them only in a point or along an edge is dropped.

use super::{DVec3, Face};
use crate::geometry::fast_hash::{fast_map, FastMap};
use std::collections::VecDeque;

/// Smallest facet area kept (in units of the size squared): a facet must be a polygon, not a
/// point or an edge, also for [`crate::geometry::Polyhedron::from_planes`].
const MIN_AREA: f64 = 1e-10;

/// cos 2°: triangles whose normal is within 2° of the facet's set its normal.
const ALIGNED: f64 = 0.99939;

pub(super) struct Cluster {
    pub area: DVec3,
    pub n: DVec3,
    sum: DVec3,
    count: f64,
}

impl Cluster {
    pub fn offset(&self) -> f64 {
        self.n.dot(self.sum / self.count)
    }
    fn add(&mut self, area: DVec3, corners: [DVec3; 3]) {
        // A sliver along an edge may have its corners within the tolerance and its normal far
        // off: it joins the facet without tilting it.
        if area.dot(self.n) >= area.length() * ALIGNED {
            self.area += area;
        }
        self.n = self.area.try_normalize().unwrap_or(self.n);
        self.sum += corners[0] + corners[1] + corners[2];
        self.count += 3.0;
    }
}

/// The hull's vertices and the edges between them (compressed rows, by point index).
struct Graph {
    start: Vec<usize>,
    next: Vec<usize>,
}

impl Graph {
    fn new(points: usize, tris: &[Face]) -> Graph {
        let mut pairs: Vec<(usize, usize)> = tris
            .iter()
            .flat_map(|t| t.edges())
            .flat_map(|(a, b)| [(a, b), (b, a)])
            .collect();
        pairs.sort_unstable();
        pairs.dedup();
        let mut start = vec![0usize; points + 1];
        for &(a, _) in &pairs {
            start[a + 1] += 1;
        }
        for i in 0..points {
            start[i + 1] += start[i];
        }
        Graph {
            start,
            next: pairs.into_iter().map(|(_, b)| b).collect(),
        }
    }
    fn around(&self, v: usize) -> &[usize] {
        &self.next[self.start[v]..self.start[v + 1]]
    }
    /// The vertex with the largest `n · p`, climbing from `v`.
    fn top(&self, pts: &[DVec3], n: DVec3, mut v: usize) -> usize {
        let mut best = n.dot(pts[v]);
        loop {
            let up = self
                .around(v)
                .iter()
                .map(|&w| (w, n.dot(pts[w])))
                .filter(|&(_, h)| h > best)
                .max_by(|a, b| a.1.total_cmp(&b.1));
            match up {
                Some((w, h)) => (v, best) = (w, h),
                None => return v,
            }
        }
    }
}

/// The hull's triangles grouped into facets: the triangle across each directed edge, each
/// triangle's cluster, the clusters, and the union–find forest that joins adjacent clusters
/// whose planes agree.
pub(super) struct Clusters {
    pub edge_tri: FastMap<(usize, usize), usize>,
    pub owner: Vec<usize>,
    pub clusters: Vec<Cluster>,
    parent: Vec<usize>,
}

impl Clusters {
    /// The joined facet (a root cluster) that cluster `i` belongs to.
    pub fn root(&mut self, mut i: usize) -> usize {
        let parent = &mut self.parent;
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
}

/// Grow facets from the largest triangle over shared edges, then join adjacent facets whose
/// planes agree within `tol` (see the module documentation).
pub(super) fn cluster(pts: &[DVec3], tris: &[Face], tol: f64) -> Clusters {
    let corners: Vec<[DVec3; 3]> = tris.iter().map(|t| t.v.map(|k| pts[k])).collect();
    let areas: Vec<DVec3> = corners
        .iter()
        .map(|c| 0.5 * (c[1] - c[0]).cross(c[2] - c[0]))
        .collect();
    let mut edge_tri: FastMap<(usize, usize), usize> = fast_map(3 * tris.len());
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
    let mut queue = VecDeque::new();
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
    let parent: Vec<usize> = (0..clusters.len()).collect();
    let mut c = Clusters {
        edge_tri,
        owner,
        clusters,
        parent,
    };
    for (t, tri) in tris.iter().enumerate() {
        for (a, b) in tri.edges() {
            let Some(&u) = c.edge_tri.get(&(b, a)) else {
                continue;
            };
            let (ci, cj) = (c.root(c.owner[t]), c.root(c.owner[u]));
            if ci == cj {
                continue;
            }
            let (x, y) = (&c.clusters[ci], &c.clusters[cj]);
            if x.n.distance(y.n) + (x.offset() - y.offset()).abs() <= tol {
                c.parent[cj] = ci;
            }
        }
    }
    c
}

/// Merge hull triangles into planes `(unit normal, offset)` (see the module documentation).
pub(super) fn merge(pts: &[DVec3], tris: &[Face], tol: f64) -> Vec<(DVec3, f64)> {
    let mut c = cluster(pts, tris, tol);
    // Per joined facet: its area, a corner to climb from, the points lying on its triangles,
    // and its neighbours (in the order first met, so the result does not depend on hashing).
    struct Joined {
        area: DVec3,
        corner: usize,
        near: Vec<usize>,
        neighbours: Vec<usize>,
    }
    let mut slot: Vec<usize> = vec![usize::MAX; c.clusters.len()];
    let mut joined: Vec<(usize, Joined)> = Vec::new();
    for i in 0..c.clusters.len() {
        let r = c.root(i);
        if slot[r] == usize::MAX {
            slot[r] = joined.len();
            joined.push((
                r,
                Joined {
                    area: DVec3::ZERO,
                    corner: usize::MAX,
                    near: Vec::new(),
                    neighbours: Vec::new(),
                },
            ));
        }
        joined[slot[r]].1.area += c.clusters[i].area;
    }
    for (t, tri) in tris.iter().enumerate() {
        let j = slot[c.root(c.owner[t])];
        let facet = &mut joined[j].1;
        if facet.corner == usize::MAX {
            facet.corner = tri.v[0];
        }
        facet.near.extend_from_slice(&tri.near);
        for (a, b) in tri.edges() {
            let Some(&u) = c.edge_tri.get(&(b, a)) else {
                continue;
            };
            let k = slot[c.root(c.owner[u])];
            if k != j && !joined[j].1.neighbours.contains(&k) {
                joined[j].1.neighbours.push(k);
            }
        }
    }
    let graph = Graph::new(pts.len(), tris);
    let mut seen: Vec<usize> = vec![usize::MAX; pts.len()];
    let planes: Vec<(DVec3, f64)> = joined
        .iter()
        .enumerate()
        .filter_map(|(j, (r, facet))| {
            let n = facet.area.try_normalize().unwrap_or(c.clusters[*r].n);
            let near = || {
                std::iter::once(j)
                    .chain(facet.neighbours.iter().copied())
                    .flat_map(|k| joined[k].1.near.iter().copied())
            };
            let top = graph.top(pts, n, facet.corner);
            let d = near()
                .map(|i| n.dot(pts[i]))
                .fold(n.dot(pts[top]), f64::max);
            // The points within `tol` of the plane: the vertices above `d - tol`, walked to
            // from the top, and the points lying on this facet or its neighbours.
            let mut flat: Vec<DVec3> = Vec::new();
            let mut walk = vec![top];
            seen[top] = j;
            while let Some(v) = walk.pop() {
                flat.push(pts[v]);
                for &w in graph.around(v) {
                    if seen[w] != j && d - n.dot(pts[w]) <= tol {
                        seen[w] = j;
                        walk.push(w);
                    }
                }
            }
            flat.extend(near().map(|i| pts[i]));
            // The climb may stop a rounding short of the top among vertices that tie: the
            // largest over the slab is the largest over every point.
            let d = flat.iter().map(|p| n.dot(*p)).fold(d, f64::max);
            // A facet is a polygon resting on the points; a plane that touches them only in a
            // point or along an edge is a sliver of rounding, and dropping it changes nothing.
            spans_a_facet(&flat, n, d, tol).then_some((n, d))
        })
        .collect();
    dedupe(planes, tol)
}

/// Drop the same plane found twice (parts of one facet kept apart by a dropped sliver): of
/// planes within `tol` of each other, the first is kept.
pub(super) fn dedupe(planes: Vec<(DVec3, f64)>, tol: f64) -> Vec<(DVec3, f64)> {
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

/// Whether the points within `tol` of the plane `n·x = d` span a polygon of at least
/// [`MIN_AREA`].
pub(super) fn spans_a_facet(pts: &[DVec3], n: DVec3, d: f64, tol: f64) -> bool {
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
