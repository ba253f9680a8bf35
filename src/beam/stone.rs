//! A solid prepared for tracing: facet planes, polygons and adjacency in flat arrays, and the
//! walk that finds the facet a ray inside the stone leaves by.

use super::symmetry::{clipped_share, RootClip, Symmetry};
use crate::geometry::Polyhedron;
use glam::{DVec2, DVec3, DVec4};
use std::sync::atomic::{AtomicU32, Ordering};

/// Facets with `|n · d|` below this are seen edge-on: no beam starts or ends on them.
pub(super) const GRAZE: f64 = 1e-12;

/// A solid prepared for tracing: facet planes, polygons and adjacency in flat arrays.
#[derive(Clone, Debug)]
pub struct Stone {
    pub(super) normals: Vec<DVec3>,
    pub(super) offsets: Vec<f64>,
    pub(super) areas: Vec<f64>,
    pub(super) vertices: Vec<DVec3>,
    pub(super) facet_vertices: Vec<u32>,
    pub(super) facet_range: Vec<(u32, u32)>,
    /// Each facet's neighbours (by their facet index, facet after facet) with their planes,
    /// in one record for the walk, the forks and the flood.
    edges: Vec<WalkEdge>,
    /// Each facet's plane and its range in `edges`, in one record for the walk: a step reads
    /// one record and one contiguous run of edges, not four tables (ten tilted traces 700.1 M
    /// -> 693.2 M instructions, cachegrind).
    walk_facets: Vec<WalkFacet>,
    /// The shared edge's end points of each entry of `edges` (for narrow beams' forks).
    pub(super) neighbor_edges: Vec<(DVec3, DVec3)>,
    /// Cube map over directions: the facet whose normal is closest to each cell's direction,
    /// where walks toward a ray's exit facet start.
    pub(super) dir_table: Vec<u32>,
    /// Facets with an edge much shorter than their longest (see [`Stone::new`]): their
    /// projected polygons are made convex before clipping.
    pub(super) fragile: Vec<bool>,
    /// Symmetries of the solid about the z axis.
    pub(super) symmetry: Symmetry,
    /// Per start facet and cube-map cell: the exit facet of the ray from the facet's centroid
    /// in the cell's central direction (a better start for walks from that facet), found the
    /// first time a walk needs it ([`Stone::table_entry`]): a trace uses few of the cells, and
    /// filling all of them took a score 3 % of its time and every frame of an animation 2 ms.
    facet_table: LazyTable,
    /// Facet centroids (where the facet table's rays start).
    centroids: Vec<DVec3>,
}

/// A neighbour of a facet as the walk reads it: the neighbour's plane `(normal, offset)` and
/// its index.
#[derive(Clone, Copy, Debug)]
pub(super) struct WalkEdge {
    pub(super) plane: DVec4,
    pub(super) facet: u32,
}

/// A facet as the walk reads it: its plane `(normal, offset)` and its neighbours' range in
/// [`Stone::edges`].
#[derive(Clone, Copy, Debug)]
struct WalkFacet {
    plane: DVec4,
    start: u32,
    end: u32,
}

/// A table of `u32` entries filled on first use, shareable between threads: an entry is a
/// pure function of its index, so whichever thread fills it, and however often, the table
/// holds the same values (and a trace the same numbers) on any number of threads.
#[derive(Debug, Default)]
struct LazyTable(Vec<AtomicU32>);

impl LazyTable {
    /// Not yet filled.
    const EMPTY: u32 = u32::MAX;

    fn new(n: usize) -> LazyTable {
        LazyTable((0..n).map(|_| AtomicU32::new(Self::EMPTY)).collect())
    }

    /// Entry `i`, filled by `make` if it is not yet.
    #[inline]
    fn get(&self, i: usize, make: impl FnOnce() -> u32) -> u32 {
        let e = &self.0[i];
        match e.load(Ordering::Relaxed) {
            Self::EMPTY => {
                let v = make();
                e.store(v, Ordering::Relaxed);
                v
            }
            v => v,
        }
    }
}

impl Clone for LazyTable {
    fn clone(&self) -> Self {
        LazyTable(
            self.0
                .iter()
                .map(|e| AtomicU32::new(e.load(Ordering::Relaxed)))
                .collect(),
        )
    }
}

/// Cells per cube-map face side of [`Stone::dir_table`].
pub(super) const CUBE_RES: usize = 8;

/// Central direction of cube-map cell (i, j) of `face`.
pub(super) fn cube_dir(face: usize, i: usize, j: usize) -> DVec3 {
    let u = (i as f64 + 0.5) / CUBE_RES as f64 * 2.0 - 1.0;
    let v = (j as f64 + 0.5) / CUBE_RES as f64 * 2.0 - 1.0;
    let s = if face.is_multiple_of(2) { 1.0 } else { -1.0 };
    match face / 2 {
        0 => DVec3::new(s, u, v),
        1 => DVec3::new(u, s, v),
        _ => DVec3::new(u, v, s),
    }
    .normalize()
}

/// Cube-map cell of a direction.
#[inline]
pub(super) fn cube_cell(t: DVec3) -> usize {
    let a = t.abs();
    let (face, u, v, m) = if a.x >= a.y && a.x >= a.z {
        (if t.x > 0.0 { 0 } else { 1 }, t.y, t.z, a.x)
    } else if a.y >= a.z {
        (if t.y > 0.0 { 2 } else { 3 }, t.x, t.z, a.y)
    } else {
        (if t.z > 0.0 { 4 } else { 5 }, t.x, t.y, a.z)
    };
    // One division: c / m ∈ [−1, 1] maps to [0, CUBE_RES].
    let h = 0.5 * CUBE_RES as f64;
    let s = h / m;
    // Through i32, a cheaper conversion than to usize (the value is in [0, CUBE_RES]).
    let cell = |c: f64| ((c * s + h) as i32).clamp(0, CUBE_RES as i32 - 1) as usize;
    (face * CUBE_RES + cell(u)) * CUBE_RES + cell(v)
}

impl Stone {
    /// Prepare `solid` for tracing.
    pub fn new(solid: &Polyhedron) -> Stone {
        let nf = solid.facets().len();
        let mut facet_vertices = Vec::new();
        let mut facet_range = Vec::with_capacity(nf);
        for f in solid.facets() {
            let a = facet_vertices.len() as u32;
            facet_vertices.extend(f.vertices.iter().map(|&v| v as u32));
            facet_range.push((a, facet_vertices.len() as u32));
        }
        let mut adj: Vec<Vec<u32>> = vec![Vec::new(); nf];
        let mut edge_of = std::collections::HashMap::new();
        for e in solid.edges() {
            let [a, b] = e.facets;
            adj[a].push(b as u32);
            adj[b].push(a as u32);
            edge_of.insert((a.min(b), a.max(b)), (e.a, e.b));
        }
        let mut neighbors = Vec::new();
        let mut neighbor_range = Vec::with_capacity(nf);
        for mut l in adj {
            l.sort_unstable();
            l.dedup();
            let a = neighbors.len() as u32;
            neighbors.extend(l);
            neighbor_range.push((a, neighbors.len() as u32));
        }
        let neighbor_edges = neighbor_range
            .iter()
            .enumerate()
            .flat_map(|(f, &(a, b))| {
                let edge_of = &edge_of;
                neighbors[a as usize..b as usize].iter().map(move |&h| {
                    let h = h as usize;
                    let (u, v) = edge_of[&(f.min(h), f.max(h))];
                    (solid.vertices()[u], solid.vertices()[v])
                })
            })
            .collect();
        let normals: Vec<DVec3> = solid.facets().iter().map(|f| f.plane.normal).collect();
        let mut dir_table = vec![0u32; 6 * CUBE_RES * CUBE_RES];
        for face in 0..6 {
            for i in 0..CUBE_RES {
                for j in 0..CUBE_RES {
                    let t = cube_dir(face, i, j);
                    let best = (0..nf)
                        .max_by(|&a, &b| normals[a].dot(t).total_cmp(&normals[b].dot(t)))
                        .unwrap_or(0);
                    dir_table[cube_cell(t)] = best as u32;
                }
            }
        }
        let centroids: Vec<DVec3> = solid.facets().iter().map(|f| f.centroid).collect();
        let cells = 6 * CUBE_RES * CUBE_RES;
        // A solid rebuilt from rounded planes (a mesh import, the canonical placement) can have
        // corners split into vertex pairs ~1e-7 apart, a few 1e-8 off their planes. Projected
        // along a beam, such a short edge can turn the wrong way by a hair, and its line then
        // sliced a large part off every beam clipped against the facet (0.07 percentage points
        // of the overhead light return of a pear read from STL, and a tiling error of 100 %).
        let fragile = solid
            .facets()
            .iter()
            .map(|f| {
                let k = f.vertices.len();
                let len = |j: usize| {
                    (solid.vertices()[f.vertices[(j + 1) % k]] - solid.vertices()[f.vertices[j]])
                        .length()
                };
                let longest = (0..k).map(len).fold(0.0, f64::max);
                (0..k).any(|j| len(j) < 1e-4 * longest)
            })
            .collect();
        let offsets: Vec<f64> = solid.facets().iter().map(|f| f.plane.offset).collect();
        let symmetry = Symmetry::find(&normals, &offsets);
        let mut stone = Stone {
            fragile,
            symmetry,
            dir_table,
            facet_table: LazyTable::new(nf * cells),
            centroids,
            normals,
            offsets,
            areas: solid.facets().iter().map(|f| f.area).collect(),
            vertices: solid.vertices().to_vec(),
            facet_vertices,
            facet_range,
            edges: Vec::new(),
            walk_facets: Vec::new(),
            neighbor_edges,
        };
        let plane = |f: usize| stone.normals[f].extend(stone.offsets[f]);
        stone.edges = neighbors
            .iter()
            .map(|&h| WalkEdge {
                plane: plane(h as usize),
                facet: h,
            })
            .collect();
        stone.walk_facets = (0..nf)
            .map(|f| {
                let (start, end) = neighbor_range[f];
                WalkFacet {
                    plane: plane(f),
                    start,
                    end,
                }
            })
            .collect();
        stone
    }

    /// How many copies of each traced exit a trace along `frame` hands out (the symmetries
    /// it uses, see [`TraceOptions::symmetry`](super::TraceOptions::symmetry)): it traces
    /// about that fraction of the cross-section.
    pub fn frame_symmetries(&self, frame: &super::frame::Frame) -> usize {
        self.symmetry.frame_symmetry(frame.dir).0.len()
    }

    /// Number of facets.
    pub fn facet_count(&self) -> usize {
        self.normals.len()
    }

    /// The solid's symmetry about the z axis: the order of its rotation group (1 = none) and
    /// the azimuth (radians, in [0, π/order)) of one of its mirror lines through the axis, if
    /// it has any.
    pub fn symmetry(&self) -> (usize, Option<f64>) {
        self.symmetry.rotations_and_mirror()
    }

    /// [`Stone::symmetry`] of a birefringent stone with optic axis `axis` (stone
    /// coordinates): only the symmetries that also map the axis onto itself or its opposite
    /// (for an axis along z all of them, for one in the table at most the half-turn and the
    /// mirrors through and across it, for a tilted one at most the mirror through it), in the
    /// same form. Two poses one of these maps onto the other see the same crystal.
    pub fn symmetry_keeping(&self, axis: DVec3) -> (usize, Option<f64>) {
        self.symmetry.rotations_and_mirror_keeping(axis)
    }

    /// Number of symmetries of the solid about the z axis (1 = none; 16 for a round brilliant).
    pub fn symmetry_order(&self) -> usize {
        self.symmetry.order()
    }

    /// Facet permutation of symmetry `i` (for facet sequences of replicated exit beams).
    pub(crate) fn permutation(&self, i: usize) -> &[u32] {
        self.symmetry.permutation(i)
    }

    /// The solid's vertices.
    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    /// Outward unit normal of facet `i`.
    pub fn normal(&self, i: usize) -> DVec3 {
        self.normals[i]
    }

    /// The facet through which the ray `x + s·t` (from a point `x` inside or on the solid)
    /// leaves, and the distance `s`, found by walking over adjacent facets from a cube-map
    /// guess: each step moves to the neighbour whose plane the ray crosses first, so the
    /// distance falls strictly and the walk ends. `exclude` is the facet `x` lies on.
    ///
    /// Measured against it and dropped (2026-12-03): every facet tested four at a time with
    /// AVX, without branches (and without dividing, in two independent chains), took 1.13 times
    /// the CPU time of ten tilted traces, and a branch-free neighbour loop here gained nothing
    /// measurable: the walk tests about 2 × 7 planes where a scan tests all of them. Four walks
    /// in lockstep, one per AVX2 lane (2026-12-06): the same bits, but 1.37 times the
    /// instructions and about twice the time (docs/benchmarks.md).
    #[inline]
    pub(crate) fn exit_facet(&self, x: DVec3, t: DVec3, exclude: usize) -> Option<(usize, f64)> {
        let cell = cube_cell(t);
        let g = if exclude < self.facet_count() {
            self.facet_table
                .get(exclude * 6 * CUBE_RES * CUBE_RES + cell, || {
                    self.table_entry(exclude, cell)
                })
        } else {
            self.dir_table[cell]
        } as usize;
        self.walk(g, x, t, exclude)
    }

    /// The facet table's entry for start facet `f` and cube-map cell `cell`: where the ray from
    /// `f`'s centroid in the cell's central direction leaves (the cell's closest facet when
    /// the direction leaves `f` outward, or no facet is found).
    #[cold]
    fn table_entry(&self, f: usize, cell: usize) -> u32 {
        let (face, i, j) = (
            cell / (CUBE_RES * CUBE_RES),
            cell / CUBE_RES % CUBE_RES,
            cell % CUBE_RES,
        );
        let t = cube_dir(face, i, j);
        let c = cube_cell(t);
        if self.normals[f].dot(t) < 0.0 {
            self.walk(self.dir_table[c] as usize, self.centroids[f], t, f)
                .map_or(self.dir_table[c], |(g, _)| g as u32)
        } else {
            self.dir_table[c]
        }
    }

    /// The walk of [`Stone::exit_facet`] from facet `g` (always inlined there: a call per
    /// ray segment cost a narrow-ray segment about 10 instructions, cachegrind).
    #[inline(always)]
    pub(super) fn walk(
        &self,
        mut g: usize,
        x: DVec3,
        t: DVec3,
        exclude: usize,
    ) -> Option<(usize, f64)> {
        let mut f = &self.walk_facets[g];
        let mut k = f.plane.truncate().dot(t);
        if g == exclude || k <= GRAZE {
            return self.exit_facet_scan(x, t, exclude);
        }
        for _ in 0..self.walk_facets.len() {
            let s = (f.plane.w - f.plane.truncate().dot(x)) / k;
            let p = (x + t * s).extend(-1.0);
            let (mut worst, mut next, mut next_k) = (1e-13, usize::MAX, 0.0);
            for e in &self.edges[f.start as usize..f.end as usize] {
                let v = e.plane.dot(p);
                if v > worst {
                    let h = e.facet as usize;
                    // The neighbour's normal is its plane's (the same bits as `normals[h]`).
                    let kh = e.plane.truncate().dot(t);
                    if h != exclude && kh > GRAZE {
                        (worst, next, next_k) = (v, h, kh);
                    }
                }
            }
            if next == usize::MAX {
                return Some((g, s));
            }
            g = next;
            k = next_k;
            f = &self.walk_facets[g];
        }
        self.exit_facet_scan(x, t, exclude)
    }

    /// [`Stone::exit_facet`] by scanning every facet.
    pub(crate) fn exit_facet_scan(
        &self,
        x: DVec3,
        t: DVec3,
        exclude: usize,
    ) -> Option<(usize, f64)> {
        let (mut best, mut g) = (f64::INFINITY, usize::MAX);
        for (h, n) in self.normals.iter().enumerate() {
            let k = n.dot(t);
            if k > GRAZE && h != exclude {
                let d = (self.offsets[h] - n.dot(x)) / k;
                if d < best {
                    best = d;
                    g = h;
                }
            }
        }
        (g != usize::MAX).then_some((g, best))
    }

    /// The stone's cross-section seen along `d` (unit): the facets facing the light
    /// (`−n · d > GRAZE`), each weighted by its cosine. A trace's powers are shares of it.
    pub(super) fn cross_section(&self, d: DVec3) -> f64 {
        (0..self.facet_count())
            .map(|f| {
                let c = -self.normals[f].dot(d);
                if c > GRAZE {
                    c * self.areas[f]
                } else {
                    0.0
                }
            })
            .sum()
    }

    /// Root facet `f` (lit at incidence cosine `c`) gathered into `cur` and clipped to
    /// `clip` ([`clipped_share`]; `piece` is scratch, `map` takes a point to the traced
    /// frame's plane): its share of the light, `None` when nothing of it is left. Both
    /// traces enter a stone through it.
    pub(super) fn root_share(
        &self,
        f: usize,
        c: f64,
        clip: &RootClip<'_>,
        cur: &mut Vec<DVec3>,
        piece: &mut Vec<DVec3>,
        map: impl Fn(DVec3) -> DVec2,
    ) -> Option<f64> {
        cur.clear();
        cur.extend(
            self.facet_verts(f)
                .iter()
                .map(|&v| self.vertices[v as usize]),
        );
        let full = c * self.areas[f] / clip.total;
        clipped_share(cur, clip.wedge, clip.window, piece, map, clip.total, full)
    }

    #[inline]
    pub(super) fn facet_verts(&self, f: usize) -> &[u32] {
        let (a, b) = self.facet_range[f];
        &self.facet_vertices[a as usize..b as usize]
    }

    /// Facet `f`'s neighbours with their planes; their shared edges are `neighbor_edges`
    /// from [`Stone::facet_edge_start`] on.
    #[inline]
    pub(super) fn facet_edges(&self, f: usize) -> &[WalkEdge] {
        let w = &self.walk_facets[f];
        &self.edges[w.start as usize..w.end as usize]
    }

    /// Where facet `f`'s neighbours start in `neighbor_edges` (and in `edges`).
    #[inline]
    pub(super) fn facet_edge_start(&self, f: usize) -> usize {
        self.walk_facets[f].start as usize
    }
}
