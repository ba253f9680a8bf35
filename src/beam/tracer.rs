//! The beam-splitting core: a prepared stone and the depth-first beam loop.

use super::{ExitBeam, Frame, TraceOptions};
use crate::geometry::clip2d;
use crate::geometry::Polyhedron;
use crate::optics::{fresnel, reflect, refract, rotate_stokes, s_axis, Interface, Stokes};
use glam::{DMat3, DVec2, DVec3, DVec4};

/// Facets with `|n · d|` below this are seen edge-on: no beam starts or ends on them.
const GRAZE: f64 = 1e-12;
/// Children with less than this share of their parent's cross-section are rounding slivers
/// along shared edges; they are dropped and their (negligible) share goes to their siblings.
const SLIVER: f64 = 1e-13;

/// Receives exit beams as the tracer produces them.
pub trait ExitSink {
    /// Whether [`ExitSink::exit`] should be given footprints (computing them costs time).
    fn wants_footprints(&self) -> bool {
        false
    }
    /// One exit beam, with its footprint in the frame's image coordinates (empty unless
    /// [`ExitSink::wants_footprints`]).
    fn exit(&mut self, beam: &ExitBeam, footprint: &[DVec2]);
}

/// Power accounting and work counters of one trace. Powers are shares of the whole incoming
/// beam.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TraceStats {
    /// Cross-section of the stone across the incoming direction (its projected area).
    pub area: f64,
    /// Sum of the root beams' power shares: 1 to rounding (0 if the stone has no cross-section).
    pub power_in: f64,
    /// Power of reflected beams not followed (below the threshold or past the depth limit).
    pub cut_off: f64,
    /// Number of internal beams split.
    pub beams: usize,
    /// Number of exit beams produced.
    pub exits: usize,
    /// Narrow beams followed as rays (below the split threshold).
    pub rays: usize,
    /// Facets met by those rays (their segments inside the stone).
    pub ray_segments: usize,
    /// Power that entered narrow-beam (ray) mode: the share of the light whose further path was
    /// found by one ray per narrow beam rather than by exact splitting.
    pub ray_power: f64,
    /// Largest relative difference between a beam's cross-section and the sum of its
    /// children's (the clipping's tiling error; ~1e-15 when all is well).
    pub max_tiling_error: f64,
}

/// A solid prepared for tracing: facet planes, polygons and adjacency in flat arrays.
#[derive(Clone, Debug)]
pub struct Stone {
    normals: Vec<DVec3>,
    offsets: Vec<f64>,
    areas: Vec<f64>,
    vertices: Vec<DVec3>,
    facet_vertices: Vec<u32>,
    facet_range: Vec<(u32, u32)>,
    neighbors: Vec<u32>,
    /// Plane `(normal, offset)` of each entry of `neighbors`, stored alongside for the walk.
    neighbor_planes: Vec<glam::DVec4>,
    neighbor_range: Vec<(u32, u32)>,
    /// Cube map over directions: the facet whose normal is closest to each cell's direction,
    /// where walks toward a ray's exit facet start.
    dir_table: Vec<u32>,
    /// Symmetries of the solid about the z axis (identity first): rotations, then mirrors.
    ops: Vec<SymOp>,
    /// Order of the rotation group about z (1 = none).
    rot_order: usize,
    /// Azimuth (radians) of one mirror plane through the z axis, if any.
    mirror_az: Option<f64>,
    /// Per start facet and cube-map cell: the exit facet of the ray from the facet's centroid
    /// in the cell's central direction (a better start for walks from that facet).
    facet_table: Vec<u32>,
}

/// Cells per cube-map face side of [`Stone::dir_table`].
const CUBE_RES: usize = 8;

/// A symmetry of the solid: an orthogonal map about the z axis and the facet permutation it
/// induces.
#[derive(Clone, Debug)]
struct SymOp {
    m: DMat3,
    mirror: bool,
    perm: Vec<u32>,
}

/// Hands each exit beam of the traced wedge to the real sink once per symmetry, transformed.
struct SymSink<'a, S: ExitSink> {
    inner: &'a mut S,
    ops: Vec<(u16, &'a SymOp, [f64; 4])>,
    foot: Vec<DVec2>,
}

impl<'a, S: ExitSink> SymSink<'a, S> {
    fn new(stone: &'a Stone, group: &[usize], frame: &Frame, inner: &'a mut S) -> Self {
        let ops = group
            .iter()
            .map(|&i| {
                let op = &stone.ops[i];
                let (gu, gv) = (op.m * frame.u, op.m * frame.v);
                (
                    i as u16,
                    op,
                    [
                        gu.dot(frame.u),
                        gv.dot(frame.u),
                        gu.dot(frame.v),
                        gv.dot(frame.v),
                    ],
                )
            })
            .collect();
        SymSink {
            inner,
            ops,
            foot: Vec::new(),
        }
    }
}

impl<S: ExitSink> ExitSink for SymSink<'_, S> {
    fn wants_footprints(&self) -> bool {
        self.inner.wants_footprints()
    }
    fn exit(&mut self, e: &ExitBeam, fp: &[DVec2]) {
        for &(i, op, m2) in &self.ops {
            if i == 0 {
                self.inner.exit(e, fp);
                continue;
            }
            let mut stokes = e.stokes;
            if op.mirror {
                // A mirror turns the s–p frame's handedness: U and V change sign.
                stokes.z = -stokes.z;
                stokes.w = -stokes.w;
            }
            let t = ExitBeam {
                direction: op.m * e.direction,
                axis: op.m * e.axis,
                stokes,
                entry_facet: op.perm[e.entry_facet] as usize,
                exit_facet: op.perm[e.exit_facet] as usize,
                sym: i,
                ..*e
            };
            self.foot.clear();
            self.foot.extend(
                fp.iter()
                    .map(|p| DVec2::new(m2[0] * p.x + m2[1] * p.y, m2[2] * p.x + m2[3] * p.y)),
            );
            self.inner.exit(&t, &self.foot);
        }
    }
}

/// Mirror across the vertical plane at azimuth `phi` (radians).
fn mirror_matrix(phi: f64) -> DMat3 {
    let m = DVec3::new(-phi.sin(), phi.cos(), 0.0);
    DMat3::IDENTITY - 2.0 * DMat3::from_cols(m * m.x, m * m.y, m * m.z)
}

/// The facet permutation of `m` if it maps every facet plane onto a facet plane.
fn facet_permutation(normals: &[DVec3], offsets: &[f64], m: &DMat3) -> Option<Vec<u32>> {
    let tol = 1e-9;
    let mut perm = Vec::with_capacity(normals.len());
    for (n, o) in normals.iter().zip(offsets) {
        let mn = *m * *n;
        let j = (0..normals.len()).find(|&j| {
            normals[j].distance_squared(mn) < tol * tol && (offsets[j] - o).abs() < tol
        })?;
        perm.push(j as u32);
    }
    Some(perm)
}

/// Clip a convex planar polygon by the half-space `n · x <= 0`.
fn clip_halfspace(poly: &[DVec3], n: DVec3, out: &mut Vec<DVec3>) {
    out.clear();
    let k = poly.len();
    for i in 0..k {
        let (p, q) = (poly[i], poly[(i + 1) % k]);
        let (dp, dq) = (n.dot(p), n.dot(q));
        if dp <= 0.0 {
            out.push(p);
        }
        if (dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0) {
            out.push(p + (q - p) * (dp / (dp - dq)));
        }
    }
    if out.len() < 3 {
        out.clear();
    }
}

/// Central direction of cube-map cell (i, j) of `face`.
fn cube_dir(face: usize, i: usize, j: usize) -> DVec3 {
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
fn cube_cell(t: DVec3) -> usize {
    let a = t.abs();
    let (face, u, v, m) = if a.x >= a.y && a.x >= a.z {
        (if t.x > 0.0 { 0 } else { 1 }, t.y, t.z, a.x)
    } else if a.y >= a.z {
        (if t.y > 0.0 { 2 } else { 3 }, t.x, t.z, a.y)
    } else {
        (if t.z > 0.0 { 4 } else { 5 }, t.x, t.y, a.z)
    };
    let cell = |c: f64| (((c / m + 1.0) * 0.5 * CUBE_RES as f64) as usize).min(CUBE_RES - 1);
    (face * CUBE_RES + cell(u)) * CUBE_RES + cell(v)
}

/// Affine map from a point in the stone to its footprint in the frame's image coordinates:
/// `(a1 · x + b.x, a2 · x + b.y)`.
#[derive(Clone, Copy, Debug)]
struct Affine {
    a1: DVec3,
    a2: DVec3,
    b: DVec2,
}

impl Affine {
    #[inline]
    fn apply(&self, x: DVec3) -> DVec2 {
        DVec2::new(self.a1.dot(x) + self.b.x, self.a2.dot(x) + self.b.y)
    }
    /// The map for points reached by travelling along `t` from the plane `n · x = o` (where
    /// this map applies): first slide back along `t` onto that plane.
    #[inline]
    fn slide(&self, t: DVec3, n: DVec3, o: f64) -> Affine {
        let k = n.dot(t);
        let at = DVec2::new(self.a1.dot(t), self.a2.dot(t));
        Affine {
            a1: self.a1 - n * (at.x / k),
            a2: self.a2 - n * (at.y / k),
            b: self.b + at * (o / k),
        }
    }
}

/// A beam waiting to be split.
#[derive(Clone, Copy, Debug)]
struct Beam {
    dir: DVec3,
    stokes: Stokes,
    axis: DVec3,
    facet: u32,
    entry: u32,
    depth: u32,
    node: u32,
    /// Its polygon (on `facet`'s plane) is `pts[start..start + len]` of the point stack.
    start: u32,
    len: u32,
    map: Affine,
}

#[derive(Clone, Copy, Debug)]
struct Child {
    facet: u32,
    start: u32,
    len: u32,
    area: f64,
}

/// Settings of one trace, cleaned.
struct Ctx {
    ri: f64,
    pol: bool,
    threshold: f64,
    split_threshold: f64,
    max_depth: u32,
    want_fp: bool,
}

/// Working memory of one trace, reused across beams.
struct Work {
    pts: Vec<DVec3>,
    stack: Vec<Beam>,
    cur: Vec<DVec3>,
    q: Vec<DVec2>,
    g: Vec<DVec2>,
    clip: Vec<DVec2>,
    scratch: Vec<DVec2>,
    proj: Vec<DVec2>,
    vstamp: Vec<u32>,
    fstamp: Vec<u32>,
    stamp: u32,
    queue: Vec<u32>,
    children: Vec<Child>,
    cpts: Vec<DVec2>,
    foot: Vec<DVec2>,
    nodes: Vec<(u32, u32)>,
}

/// Reflected and transmitted Stokes vectors for `s` given in the interface's s–p frame.
/// The transmitted intensity is `I − I_r`, so the split conserves power exactly.
#[inline]
fn split(polarization: bool, f: &Interface, s: Stokes) -> (Stokes, Stokes) {
    if f.tir {
        // Total internal reflection: all power reflected (with the s–p phase if polarized).
        let r = if polarization {
            f.mueller_reflect().apply(s)
        } else {
            DVec4::new(s.x, 0.0, 0.0, 0.0)
        };
        (DVec4::new(s.x, r.y, r.z, r.w), DVec4::ZERO)
    } else if polarization {
        let r = f.mueller_reflect().apply(s);
        let mut t = f.mueller_transmit().apply(s);
        t.x = (s.x - r.x).max(0.0);
        (r, t)
    } else {
        let r = s.x * f.reflectance();
        (
            DVec4::new(r, 0.0, 0.0, 0.0),
            DVec4::new(s.x - r, 0.0, 0.0, 0.0),
        )
    }
}

impl Stone {
    /// Prepare `solid` for tracing.
    pub fn new(solid: &Polyhedron) -> Stone {
        let nf = solid.facets.len();
        let mut facet_vertices = Vec::new();
        let mut facet_range = Vec::with_capacity(nf);
        for f in &solid.facets {
            let a = facet_vertices.len() as u32;
            facet_vertices.extend(f.vertices.iter().map(|&v| v as u32));
            facet_range.push((a, facet_vertices.len() as u32));
        }
        let mut adj: Vec<Vec<u32>> = vec![Vec::new(); nf];
        for e in &solid.edges {
            let [a, b] = e.facets;
            adj[a].push(b as u32);
            adj[b].push(a as u32);
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
        let normals: Vec<DVec3> = solid.facets.iter().map(|f| f.plane.normal).collect();
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
        let centroids: Vec<DVec3> = solid.facets.iter().map(|f| f.centroid).collect();
        let cells = 6 * CUBE_RES * CUBE_RES;
        let mut stone = Stone {
            ops: Vec::new(),
            rot_order: 1,
            mirror_az: None,
            dir_table,
            facet_table: Vec::new(),
            normals: solid.facets.iter().map(|f| f.plane.normal).collect(),
            offsets: solid.facets.iter().map(|f| f.plane.offset).collect(),
            areas: solid.facets.iter().map(|f| f.area).collect(),
            vertices: solid.vertices.clone(),
            facet_vertices,
            facet_range,
            neighbor_planes: Vec::new(),
            neighbors,
            neighbor_range,
        };
        stone.neighbor_planes = stone
            .neighbors
            .iter()
            .map(|&h| stone.normals[h as usize].extend(stone.offsets[h as usize]))
            .collect();
        let mut facet_table = vec![0u32; nf * cells];
        for f in 0..nf {
            for face in 0..6 {
                for i in 0..CUBE_RES {
                    for j in 0..CUBE_RES {
                        let t = cube_dir(face, i, j);
                        let c = cube_cell(t);
                        facet_table[f * cells + c] = if stone.normals[f].dot(t) < 0.0 {
                            stone
                                .walk(stone.dir_table[c] as usize, centroids[f], t, f)
                                .map_or(stone.dir_table[c], |(g, _)| g as u32)
                        } else {
                            stone.dir_table[c]
                        };
                    }
                }
            }
        }
        stone.facet_table = facet_table;
        stone.find_symmetry();
        stone
    }

    /// Find the rotations about the z axis and the mirrors through it that map the solid onto
    /// itself (the ones a face-up view shares).
    fn find_symmetry(&mut self) {
        let (normals, offsets) = (&self.normals, &self.offsets);
        let rot = |k: usize| DMat3::from_rotation_z(std::f64::consts::TAU / k as f64);
        let k = [64, 48, 32, 24, 16, 12, 10, 9, 8, 7, 6, 5, 4, 3, 2]
            .into_iter()
            .find(|&k| facet_permutation(normals, offsets, &rot(k)).is_some())
            .unwrap_or(1);
        // Mirror candidates: bisectors between a tilted facet's normal and its look-alikes.
        let mut mirror = None;
        if let Some(f0) = (0..normals.len()).find(|&f| normals[f].truncate().length() > 1e-6) {
            let a0 = normals[f0].y.atan2(normals[f0].x);
            for j in 0..normals.len() {
                if (normals[j].z - normals[f0].z).abs() < 1e-9
                    && (offsets[j] - offsets[f0]).abs() < 1e-9
                {
                    let aj = normals[j].y.atan2(normals[j].x);
                    let phi = 0.5 * (a0 + aj);
                    for cand in [phi, phi + std::f64::consts::FRAC_PI_2] {
                        if facet_permutation(normals, offsets, &mirror_matrix(cand)).is_some() {
                            mirror = Some(cand.rem_euclid(std::f64::consts::PI / k as f64));
                            break;
                        }
                    }
                }
                if mirror.is_some() {
                    break;
                }
            }
        }
        let mut ops = Vec::new();
        for j in 0..k {
            let m = DMat3::from_rotation_z(std::f64::consts::TAU * j as f64 / k as f64);
            if let Some(perm) = facet_permutation(normals, offsets, &m) {
                ops.push(SymOp {
                    m,
                    mirror: false,
                    perm,
                });
            }
        }
        if let Some(phi0) = mirror {
            for j in 0..k {
                let m = mirror_matrix(phi0 + std::f64::consts::PI * j as f64 / k as f64);
                if let Some(perm) = facet_permutation(normals, offsets, &m) {
                    ops.push(SymOp {
                        m,
                        mirror: true,
                        perm,
                    });
                }
            }
        }
        // Keep the symmetry only if the whole group was found consistently.
        if ops.len() == k * if mirror.is_some() { 2 } else { 1 } {
            self.ops = ops;
            self.rot_order = k;
            self.mirror_az = mirror;
        } else {
            self.ops = vec![SymOp {
                m: DMat3::IDENTITY,
                mirror: false,
                perm: (0..normals.len() as u32).collect(),
            }];
            self.rot_order = 1;
            self.mirror_az = None;
        }
    }

    /// Facet permutation of symmetry `i` (for facet sequences of replicated exit beams).
    pub(crate) fn permutation(&self, i: usize) -> &[u32] {
        &self.ops[i].perm
    }

    /// Number of symmetries of the solid about the z axis (1 = none; 16 for a round brilliant).
    pub fn symmetry_order(&self) -> usize {
        self.ops.len()
    }

    /// The symmetries that fix direction `d` (indices into `ops`), and the half-spaces
    /// `n · x <= 0` (planes through the z axis) cutting out a fundamental wedge whose images
    /// under them tile space.
    fn frame_symmetry(&self, d: DVec3) -> (Vec<usize>, Vec<DVec3>) {
        use std::f64::consts::{PI, TAU};
        let k = self.rot_order;
        let side = |a: f64| DVec3::new(a.sin(), -a.cos(), 0.0); // n·x <= 0: left of azimuth a
        if d.truncate().length() < 1e-12 {
            let all: Vec<usize> = (0..self.ops.len()).collect();
            let wedge = match self.mirror_az {
                Some(p0) if k == 1 => vec![side(p0)],
                Some(p0) => vec![side(p0), -side(p0 + PI / k as f64)],
                None if k == 1 => vec![],
                None if k == 2 => vec![side(0.0)],
                None => vec![side(0.0), -side(TAU / k as f64)],
            };
            return (all, wedge);
        }
        // A tilted direction keeps at most the mirror through it.
        let psi = d.y.atan2(d.x);
        if let Some(p0) = self.mirror_az {
            let step = PI / k as f64;
            let x = (psi - p0) / step;
            if (x - x.round()).abs() < 1e-9 {
                let j = (x.round() as i64).rem_euclid(k as i64) as usize;
                let idx = k + j;
                if idx < self.ops.len() && self.ops[idx].mirror {
                    return (vec![0, idx], vec![side(psi)]);
                }
            }
        }
        (vec![0], vec![])
    }

    /// Number of facets.
    pub fn facet_count(&self) -> usize {
        self.normals.len()
    }

    /// Outward unit normal of facet `i`.
    pub fn normal(&self, i: usize) -> DVec3 {
        self.normals[i]
    }

    /// The facet through which the ray `x + s·t` (from a point `x` inside or on the solid)
    /// leaves, and the distance `s`, found by walking over adjacent facets from a cube-map
    /// guess: each step moves to the neighbour whose plane the ray crosses first, so the
    /// distance falls strictly and the walk ends. `exclude` is the facet `x` lies on.
    #[inline]
    pub(crate) fn exit_facet(&self, x: DVec3, t: DVec3, exclude: usize) -> Option<(usize, f64)> {
        let cell = cube_cell(t);
        let g = if exclude < self.facet_count() && !self.facet_table.is_empty() {
            self.facet_table[exclude * 6 * CUBE_RES * CUBE_RES + cell]
        } else {
            self.dir_table[cell]
        } as usize;
        self.walk(g, x, t, exclude)
    }

    /// The walk of [`Stone::exit_facet`] from facet `g`.
    #[inline]
    fn walk(&self, mut g: usize, x: DVec3, t: DVec3, exclude: usize) -> Option<(usize, f64)> {
        let nf = self.facet_count();
        let mut k = self.normals[g].dot(t);
        if g == exclude || k <= GRAZE {
            return self.exit_facet_scan(x, t, exclude);
        }
        for _ in 0..nf {
            let s = (self.offsets[g] - self.normals[g].dot(x)) / k;
            let p = (x + t * s).extend(-1.0);
            let (mut worst, mut next) = (1e-13, usize::MAX);
            let (a, b) = self.neighbor_range[g];
            let (a, b) = (a as usize, b as usize);
            for (pl, &h) in self.neighbor_planes[a..b].iter().zip(&self.neighbors[a..b]) {
                let v = pl.dot(p);
                if v > worst {
                    let h = h as usize;
                    if h != exclude && self.normals[h].dot(t) > GRAZE {
                        worst = v;
                        next = h;
                    }
                }
            }
            if next == usize::MAX {
                return Some((g, s));
            }
            g = next;
            k = self.normals[g].dot(t);
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

    #[inline]
    fn facet_verts(&self, f: usize) -> &[u32] {
        let (a, b) = self.facet_range[f];
        &self.facet_vertices[a as usize..b as usize]
    }

    #[inline]
    fn facet_neighbors(&self, f: usize) -> &[u32] {
        let (a, b) = self.neighbor_range[f];
        &self.neighbors[a as usize..b as usize]
    }

    fn work(&self) -> Work {
        Work {
            pts: Vec::with_capacity(1024),
            stack: Vec::with_capacity(128),
            cur: Vec::with_capacity(32),
            q: Vec::with_capacity(32),
            g: Vec::with_capacity(32),
            clip: Vec::with_capacity(32),
            scratch: Vec::with_capacity(32),
            proj: vec![DVec2::ZERO; self.vertices.len()],
            vstamp: vec![0; self.vertices.len()],
            fstamp: vec![0; self.normals.len()],
            stamp: 0,
            queue: Vec::with_capacity(self.normals.len()),
            children: Vec::with_capacity(self.normals.len()),
            cpts: Vec::with_capacity(256),
            foot: Vec::with_capacity(32),
            nodes: Vec::with_capacity(4096),
        }
    }

    /// Trace one direction at refractive index `ri`, handing every exit beam to `sink`.
    /// Returns the power accounting and, when `keep_nodes`, the facet-sequence tree (parent,
    /// facet) that [`ExitBeam`]s index into.
    pub(crate) fn trace_into<S: ExitSink>(
        &self,
        frame: &Frame,
        ri: f64,
        opts: &TraceOptions,
        sink: &mut S,
        keep_nodes: bool,
    ) -> (TraceStats, Vec<(u32, u32)>) {
        let mut st = TraceStats::default();
        let d0 = frame.dir;
        if !(ri.is_finite() && ri > 0.0 && d0.is_finite()) {
            return (st, Vec::new());
        }
        let total: f64 = (0..self.facet_count())
            .map(|f| {
                let c = -self.normals[f].dot(d0);
                if c > GRAZE {
                    c * self.areas[f]
                } else {
                    0.0
                }
            })
            .sum();
        st.area = total;
        if total.is_nan() || total <= 0.0 {
            return (st, Vec::new());
        }
        let clean = |x: f64| if x.is_finite() { x.max(0.0) } else { 0.0 };
        let cx = Ctx {
            ri,
            pol: opts.polarization,
            threshold: clean(opts.threshold),
            split_threshold: clean(opts.split_threshold),
            max_depth: opts.max_depth,
            want_fp: sink.wants_footprints(),
        };
        let mut w = self.work();
        let map0 = Affine {
            a1: frame.u,
            a2: frame.v,
            b: DVec2::ZERO,
        };
        // Symmetry: trace a fundamental wedge and hand out every exit once per symmetry.
        let (group, wedge) = if opts.symmetry {
            self.frame_symmetry(d0)
        } else {
            (vec![0], vec![])
        };
        let mut sym = SymSink::new(self, &group, frame, sink);
        let mut piece: Vec<DVec3> = Vec::with_capacity(32);

        // Entry: external reflection and refraction at every facet facing the light.
        for f in 0..self.facet_count() {
            let n = self.normals[f];
            let c = -n.dot(d0);
            if c <= GRAZE {
                continue;
            }
            let verts = self.facet_verts(f);
            w.cur.clear();
            w.cur
                .extend(verts.iter().map(|&v| self.vertices[v as usize]));
            let mut p = c * self.areas[f] / total;
            if !wedge.is_empty() {
                for h in &wedge {
                    clip_halfspace(&w.cur, *h, &mut piece);
                    std::mem::swap(&mut w.cur, &mut piece);
                    if w.cur.is_empty() {
                        break;
                    }
                }
                if w.cur.is_empty() {
                    continue;
                }
                let fp: Vec<DVec2> = w.cur.iter().map(|&x| map0.apply(x)).collect();
                p = clip2d::area(&fp) / total;
                if p <= 0.0 {
                    continue;
                }
            }
            st.power_in += p;
            let node = w.nodes.len() as u32;
            w.nodes.push((u32::MAX, f as u32));
            let fr = fresnel(c, 1.0, ri);
            let axis = s_axis(d0, n).unwrap_or(frame.u);
            let (sr, stt) = split(cx.pol, &fr, DVec4::new(p, 0.0, 0.0, 0.0));
            w.foot.clear();
            if cx.want_fp {
                w.foot.extend(w.cur.iter().map(|&x| map0.apply(x)));
            }
            let ext = ExitBeam {
                direction: reflect(d0, n),
                power: sr.x,
                stokes: sr,
                axis,
                entry_facet: f,
                exit_facet: f,
                reflections: 0,
                external: true,
                narrow: false,
                node,
                sym: 0,
            };
            st.exits += 1;
            sym.exit(&ext, &w.foot);
            let beam = match refract(d0, n, 1.0, ri) {
                Some(t) if stt.x > 0.0 => Beam {
                    dir: t,
                    stokes: stt,
                    axis,
                    facet: f as u32,
                    entry: f as u32,
                    depth: 0,
                    node,
                    start: 0,
                    len: 0,
                    map: map0,
                },
                // Below the critical angle from outside (ri < 1): everything was reflected.
                _ => {
                    st.cut_off += stt.x;
                    continue;
                }
            };
            // `w.cur` holds the polygon, `w.foot` its footprint.
            self.continue_beam(beam, &cx, &mut w, &mut st, &mut sym);
            // Depth-first from this root; roots go in facet order, so the walk order (and the
            // exit order) is deterministic.
            while let Some(beam) = w.stack.pop() {
                self.split_beam(beam, &cx, &mut w, &mut st, &mut sym);
            }
        }
        let g = group.len() as f64;
        st.power_in *= g;
        st.cut_off *= g;
        st.exits *= group.len();
        let nodes = if keep_nodes {
            std::mem::take(&mut w.nodes)
        } else {
            Vec::new()
        };
        (st, nodes)
    }

    /// Decide the fate of a beam about to travel inside: split exactly (pushed on the stack),
    /// followed as a narrow beam, or cut off. Its polygon is in `w.cur` (on `beam.facet`'s
    /// plane) and, when footprints are wanted, its footprint in `w.foot`.
    fn continue_beam<S: ExitSink>(
        &self,
        beam: Beam,
        cx: &Ctx,
        w: &mut Work,
        st: &mut TraceStats,
        sink: &mut S,
    ) {
        let p = beam.stokes.x;
        if p.is_nan() || p <= 0.0 || p < cx.threshold || beam.depth > cx.max_depth {
            st.cut_off += p.max(0.0);
        } else if p >= cx.split_threshold {
            let start = w.pts.len() as u32;
            w.pts.extend_from_slice(&w.cur);
            w.stack.push(Beam {
                start,
                len: w.cur.len() as u32,
                ..beam
            });
        } else {
            let c = w.cur.iter().copied().sum::<DVec3>() / w.cur.len() as f64;
            self.follow_ray(beam, c, cx, w, st, sink);
        }
    }

    /// Follow a narrow beam as one ray from `x` (on `beam.facet`) with exact expected-value
    /// Fresnel branching: at each facet the transmitted part leaves (an exit beam with the
    /// narrow beam's footprint, `w.foot`), the reflected part goes on until it is below the
    /// threshold or past the depth limit.
    fn follow_ray<S: ExitSink>(
        &self,
        beam: Beam,
        mut x: DVec3,
        cx: &Ctx,
        w: &mut Work,
        st: &mut TraceStats,
        sink: &mut S,
    ) {
        st.rays += 1;
        st.ray_power += beam.stokes.x;
        let (mut t, mut s, mut axis, mut facet, mut depth, mut prev) = (
            beam.dir,
            beam.stokes,
            beam.axis,
            beam.facet as usize,
            beam.depth,
            beam.node,
        );
        loop {
            let Some((g, best)) = self.exit_facet(x, t, facet) else {
                st.cut_off += s.x;
                return;
            };
            st.ray_segments += 1;
            x += t * best.max(0.0);
            let n = self.normals[g];
            let fr = fresnel(n.dot(t), cx.ri, 1.0);
            let (ax, s_in) = if cx.pol {
                let a = s_axis(t, n).unwrap_or(axis);
                (a, rotate_stokes(s, axis, a, t))
            } else {
                (axis, s)
            };
            let (mut sr, stt) = split(cx.pol, &fr, s_in);
            let node = w.nodes.len() as u32;
            w.nodes.push((prev, g as u32));
            prev = node;
            if stt.x > 0.0 {
                match refract(t, n, cx.ri, 1.0) {
                    Some(out) => {
                        let e = ExitBeam {
                            direction: out,
                            power: stt.x,
                            stokes: stt,
                            axis: ax,
                            entry_facet: beam.entry as usize,
                            exit_facet: g,
                            reflections: depth,
                            external: false,
                            narrow: true,
                            node,
                            sym: 0,
                        };
                        st.exits += 1;
                        sink.exit(&e, &w.foot);
                    }
                    None => sr.x += stt.x,
                }
            }
            depth += 1;
            if sr.x.is_nan() || sr.x <= 0.0 || sr.x < cx.threshold || depth > cx.max_depth {
                st.cut_off += sr.x.max(0.0);
                return;
            }
            t = reflect(t, n);
            s = sr;
            axis = ax;
            facet = g;
        }
    }

    /// Split one internal beam by the facets it reaches.
    fn split_beam<S: ExitSink>(
        &self,
        beam: Beam,
        cx: &Ctx,
        w: &mut Work,
        st: &mut TraceStats,
        sink: &mut S,
    ) {
        st.beams += 1;
        let t = beam.dir;
        // Take the beam's polygon off the point stack (it is on top).
        w.cur.clear();
        let (a, b) = (beam.start as usize, (beam.start + beam.len) as usize);
        w.cur.extend_from_slice(&w.pts[a..b]);
        w.pts.truncate(a);

        let (e1, e2) = t.any_orthonormal_pair();
        w.q.clear();
        w.q.extend(w.cur.iter().map(|x| DVec2::new(x.dot(e1), x.dot(e2))));
        let aq = clip2d::area(&w.q);
        if aq.is_nan() || aq <= 0.0 {
            st.cut_off += beam.stokes.x;
            return;
        }
        w.stamp = w.stamp.wrapping_add(1);
        if w.stamp == 0 {
            w.vstamp.iter_mut().for_each(|s| *s = 0);
            w.fstamp.iter_mut().for_each(|s| *s = 0);
            w.stamp = 1;
        }
        let stamp = w.stamp;

        // Seed: the facet the ray through the polygon's vertex mean leaves by.
        let c = w.cur.iter().copied().sum::<DVec3>() / w.cur.len() as f64;
        let Some((seed, _)) = self.exit_facet(c, t, beam.facet as usize) else {
            st.cut_off += beam.stokes.x;
            return;
        };
        let seed = seed as u32;

        // Flood over adjacent facets from the seed: the facets the beam reaches form a
        // connected patch of the silhouette's tiling.
        w.queue.clear();
        w.children.clear();
        w.cpts.clear();
        w.queue.push(seed);
        w.fstamp[seed as usize] = stamp;
        let min_area = aq * SLIVER;
        let mut sum = 0.0;
        let mut qi = 0;
        while qi < w.queue.len() {
            let g = w.queue[qi] as usize;
            qi += 1;
            let a = self.clip_facet(g, e1, e2, w, min_area);
            if a > min_area {
                sum += a;
                for &h in self.facet_neighbors(g) {
                    if w.fstamp[h as usize] != stamp && self.normals[h as usize].dot(t) > GRAZE {
                        w.fstamp[h as usize] = stamp;
                        w.queue.push(h);
                    }
                }
            }
        }
        if sum < aq * (1.0 - 1e-9) {
            // Robustness net (never needed on sound solids): try every facet not yet tried.
            for h in 0..self.facet_count() {
                if w.fstamp[h] != stamp && self.normals[h].dot(t) > GRAZE {
                    w.fstamp[h] = stamp;
                    let a = self.clip_facet(h, e1, e2, w, min_area);
                    if a > min_area {
                        sum += a;
                    }
                }
            }
        }
        st.max_tiling_error = st.max_tiling_error.max((sum - aq).abs() / aq);
        if sum.is_nan() || sum <= 0.0 {
            st.cut_off += beam.stokes.x;
            return;
        }

        let f = beam.facet as usize;
        let map = beam.map.slide(t, self.normals[f], self.offsets[f]);
        let nchildren = w.children.len();
        for ci in 0..nchildren {
            let ch = w.children[ci];
            let g = ch.facet as usize;
            let n = self.normals[g];
            let o = self.offsets[g];
            let cos_i = n.dot(t);
            let s_in = beam.stokes * (ch.area / sum);
            let fr = fresnel(cos_i, cx.ri, 1.0);
            let (axis, s_in) = if cx.pol {
                let s = s_axis(t, n).unwrap_or(beam.axis);
                (s, rotate_stokes(s_in, beam.axis, s, t))
            } else {
                (beam.axis, s_in)
            };
            let (mut sr, stt) = split(cx.pol, &fr, s_in);
            // Lift the child's polygon onto facet g's plane.
            w.cur.clear();
            for p in &w.cpts[ch.start as usize..(ch.start + ch.len) as usize] {
                let x = e1 * p.x + e2 * p.y;
                w.cur.push(x + t * ((o - n.dot(x)) / cos_i));
            }
            w.foot.clear();
            if cx.want_fp {
                w.foot.extend(w.cur.iter().map(|&x| map.apply(x)));
            }
            let node = w.nodes.len() as u32;
            w.nodes.push((beam.node, g as u32));
            if stt.x > 0.0 {
                match refract(t, n, cx.ri, 1.0) {
                    Some(out) => {
                        let e = ExitBeam {
                            direction: out,
                            power: stt.x,
                            stokes: stt,
                            axis,
                            entry_facet: beam.entry as usize,
                            exit_facet: g,
                            reflections: beam.depth,
                            external: false,
                            narrow: false,
                            node,
                            sym: 0,
                        };
                        st.exits += 1;
                        sink.exit(&e, &w.foot);
                    }
                    // Fresnel and Snell disagree only at the critical angle itself.
                    None => sr.x += stt.x,
                }
            }
            let next = Beam {
                dir: reflect(t, n),
                stokes: sr,
                axis,
                facet: g as u32,
                entry: beam.entry,
                depth: beam.depth + 1,
                node,
                start: 0,
                len: 0,
                map,
            };
            self.continue_beam(next, cx, w, st, sink);
        }
    }

    /// Clip the current beam (`w.q`) by facet `g` projected on (e1, e2); append a child if the
    /// overlap exceeds `keep_area` (a sliver otherwise). Returns the overlap's area.
    #[inline]
    fn clip_facet(&self, g: usize, e1: DVec3, e2: DVec3, w: &mut Work, keep_area: f64) -> f64 {
        let stamp = w.stamp;
        w.g.clear();
        for &v in self.facet_verts(g) {
            let v = v as usize;
            if w.vstamp[v] != stamp {
                w.vstamp[v] = stamp;
                let x = self.vertices[v];
                w.proj[v] = DVec2::new(x.dot(e1), x.dot(e2));
            }
            w.g.push(w.proj[v]);
        }
        clip2d::clip_convex_into(&w.q, &w.g, &mut w.clip, &mut w.scratch);
        let a = clip2d::area(&w.clip);
        if a > keep_area {
            let start = w.cpts.len() as u32;
            w.cpts.extend_from_slice(&w.clip);
            w.children.push(Child {
                facet: g as u32,
                start,
                len: w.clip.len() as u32,
                area: a,
            });
        }
        a
    }
}
