//! The beam-splitting core: the depth-first beam loop (roots at the entry facets, exact
//! splitting by the facets a beam reaches, narrow beams followed as rays).

use super::interface::{cross, split, Meet, Origin};
use super::stone::{Stone, GRAZE};
use super::symmetry::{clip_halfspace, SymSink};
use super::{ExitBeam, Frame, TraceOptions};
use crate::geometry::clip2d;
use crate::optics::{fresnel, reflect, refract, s_axis, Stokes};
use glam::{DVec2, DVec3, DVec4};

/// Children with less than this share of their parent's cross-section are rounding slivers
/// along shared edges; they are dropped and their (negligible) share goes to their siblings.
const SLIVER: f64 = 1e-13;

/// Margin (girdle diameters, ~100 times [`clip2d::TOL`]) by which projected bounding boxes
/// must miss each other for [`Stone::clip_facet`] to skip the clip: the clip keeps only points
/// within `TOL` of both polygons, so it would find nothing there.
const BOX_MARGIN: f64 = 1e-10;

/// Receives exit beams as the tracer produces them.
pub(crate) trait ExitSink {
    /// Whether [`ExitSink::exit`] should be given footprints (computing them costs time).
    fn wants_footprints(&self) -> bool {
        false
    }
    /// Whether `beam` or any of the symmetric copies of it that a trace using the stone's
    /// symmetry hands out can change what this sink measures; `false` lets the tracer skip
    /// them all (and transforming their footprints). The copies share the beam's power and
    /// its direction's component along the viewer's axis (the frame's symmetries keep that
    /// axis), so a sink may decide from those. Default: always wanted.
    fn wants_orbit(&self, _beam: &ExitBeam) -> bool {
        true
    }
    /// The symmetries a trace using the stone's symmetry hands each traced exit out under:
    /// per symmetry, the index its copies carry in `ExitBeam::sym` and the 2×2 map
    /// `[a, b, c, d]` of their footprints (`(x, y) ↦ (a x + b y, c x + d y)`). Called once
    /// before the first exit; the copies of one traced exit then arrive one after another,
    /// the identity (index 0) first. Default: ignored.
    fn symmetries(&mut self, _maps: &[(u16, [f64; 4])]) {}
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
    /// Power of narrow beams' rays stopped by [`TraceOptions::ray_floor`](super::TraceOptions::ray_floor)
    /// (part of `cut_off`).
    pub ray_closed: f64,
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

/// Area centroid and area of the planar polygon `poly` (normal `n`): unlike the mean of its
/// vertices, the centroid moves continuously when a clip adds a vertex. The vertex mean (and
/// area 0) for a degenerate polygon.
fn area_centroid(poly: &[DVec3], n: DVec3) -> (DVec3, f64) {
    let mean = poly.iter().copied().sum::<DVec3>() / poly.len().max(1) as f64;
    let (mut a, mut c) = (0.0, DVec3::ZERO);
    for i in 1..poly.len().saturating_sub(1) {
        let (p, q) = (poly[i] - poly[0], poly[i + 1] - poly[0]);
        let ai = n.dot(p.cross(q));
        a += ai;
        c += (p + q) * ai;
    }
    if a != 0.0 && a.is_finite() {
        (poly[0] + c / (3.0 * a), 0.5 * a.abs())
    } else {
        (mean, 0.0)
    }
}

/// Share of a disc beyond a chord at signed distance `u` radii from its centre (1 at
/// `u = −1`, ½ at 0, 0 at 1; continuously differentiable), and the distance of that part's
/// centroid from the centre, in radii.
#[inline]
fn disc_segment(u: f64) -> (f64, f64) {
    let u = u.clamp(-1.0, 1.0);
    let s = (1.0 - u * u).max(0.0).sqrt();
    let f = (u.acos() - u * s) / std::f64::consts::PI;
    let c = if f > 0.0 {
        2.0 * s * s * s / (3.0 * std::f64::consts::PI * f)
    } else {
        1.0
    };
    (f, c)
}

/// `3x² − 2x³`: 0 at 0, 1 at 1, flat at both.
#[inline]
fn smooth(x: f64) -> f64 {
    x * x * (3.0 - 2.0 * x)
}

/// A narrow beam's forks carry at least this share of its starting power; smaller parts
/// beyond a facet edge stay with the main ray (an error of at most this share of a narrow
/// beam, against [`TraceOptions::ray_floor`]'s 5 %).
const FORK_MIN: f64 = 1e-3;

/// Forks onto facets met at a grazing angle fade in over `n · t` ∈ [0, FORK_GRAZE] (a disc
/// is not the beam: near the silhouette it overhangs facets the beam itself does not reach).
const FORK_GRAZE: f64 = 0.02;

/// At most this share of a narrow beam forks off at one crossing (near a corner the disc can
/// overhang several edges).
const FORK_MAX: f64 = 0.95;

/// One part of a narrow beam followed as a ray: at `x` on `facet`'s plane, travelling along
/// `t`, a disc of radius `r` carrying `share` of the narrow beam's cross-section.
#[derive(Clone, Copy, Debug)]
struct Part {
    x: DVec3,
    t: DVec3,
    s: Stokes,
    axis: DVec3,
    facet: u32,
    depth: u32,
    prev: u32,
    r: f64,
    share: f64,
}

/// A narrow beam's ray (or one part of it) about to cross `facet`, travelling along `t` with
/// Stokes vector `s` (reference `axis`) after `depth` reflections, from tree node `prev`;
/// `late` when it has already lost half of its starting power.
#[derive(Clone, Copy, Debug)]
struct RayAt {
    t: DVec3,
    facet: usize,
    s: Stokes,
    axis: DVec3,
    depth: u32,
    prev: u32,
    late: bool,
}

/// A fork of a narrow beam's disc across an edge of its exit facet onto facet `h`: its share
/// `f`, the unit direction `m` (across the beam) toward the edge and its centroid's distance
/// `c` from the disc's centre.
#[derive(Clone, Copy, Debug)]
struct Fork {
    h: u32,
    f: f64,
    m: DVec3,
    c: f64,
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
pub(super) struct Ctx {
    pub(super) ri: f64,
    pub(super) pol: bool,
    threshold: f64,
    split_threshold: f64,
    ray_floor: f64,
    forks: bool,
    max_depth: u32,
    want_fp: bool,
    /// Record the facet-sequence tree (otherwise node ids are `u32::MAX`).
    keep_nodes: bool,
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
    /// Bounding box of `q` (the beam being split, projected).
    qlo: DVec2,
    qhi: DVec2,
    vstamp: Vec<u32>,
    fstamp: Vec<u32>,
    stamp: u32,
    queue: Vec<u32>,
    children: Vec<Child>,
    cpts: Vec<DVec2>,
    foot: Vec<DVec2>,
    nodes: Vec<(u32, u32)>,
    parts: Vec<Part>,
    forks: Vec<Fork>,
}

impl Work {
    /// A new node (parent, facet) of the facet-sequence tree: its id, or `u32::MAX` when the
    /// tree is not kept.
    #[inline]
    fn node(&mut self, cx: &Ctx, parent: u32, facet: usize) -> u32 {
        if !cx.keep_nodes {
            return u32::MAX;
        }
        let node = self.nodes.len() as u32;
        self.nodes.push((parent, facet as u32));
        node
    }
}

impl Stone {
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
            qlo: DVec2::ZERO,
            qhi: DVec2::ZERO,
            vstamp: vec![0; self.vertices.len()],
            fstamp: vec![0; self.normals.len()],
            stamp: 0,
            queue: Vec::with_capacity(self.normals.len()),
            children: Vec::with_capacity(self.normals.len()),
            cpts: Vec::with_capacity(256),
            foot: Vec::with_capacity(32),
            nodes: Vec::with_capacity(4096),
            parts: Vec::with_capacity(32),
            forks: Vec::with_capacity(8),
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
            ray_floor: clean(opts.ray_floor),
            forks: opts.narrow_forks,
            max_depth: opts.max_depth,
            want_fp: sink.wants_footprints(),
            keep_nodes,
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
            let node = w.node(&cx, u32::MAX, f);
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
                late: false,
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
        st.ray_closed *= g;
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
            // From the area centroid, not the vertex mean: clipping adds and drops vertices
            // (rounding slivers along shared edges among them), which moved the vertex mean,
            // and with it the ray's whole path, by a sizeable part of the beam when the solid
            // changed by 1e-10.
            let n = self.normals[beam.facet as usize];
            let (c, area) = area_centroid(&w.cur, n);
            // The disc of the beam's cross-section (kept by mirror reflections).
            let r = (area * n.dot(beam.dir).abs() / std::f64::consts::PI).sqrt();
            self.follow_ray(beam, c, r, cx, w, st, sink);
        }
    }

    /// Follow a narrow beam as one ray from `x` (on `beam.facet`) with exact expected-value
    /// Fresnel branching: at each facet the transmitted part leaves (an exit beam with the
    /// narrow beam's footprint, `w.foot`), the reflected part goes on until it is below the
    /// floor or past the depth limit. With [`TraceOptions::narrow_forks`] the ray stands for a
    /// disc of radius `r` (the beam's cross-section; see [`Stone::follow_disc`]).
    #[allow(clippy::too_many_arguments)]
    fn follow_ray<S: ExitSink>(
        &self,
        beam: Beam,
        mut x: DVec3,
        r: f64,
        cx: &Ctx,
        w: &mut Work,
        st: &mut TraceStats,
        sink: &mut S,
    ) {
        st.rays += 1;
        let p0 = beam.stokes.x;
        st.ray_power += p0;
        let floor = cx.threshold.max(cx.ray_floor * p0);
        if cx.forks && r.is_finite() && r > 0.0 {
            return self.follow_disc(beam, x, r, floor, cx, w, st, sink);
        }
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
            x += t * best.max(0.0);
            let at = RayAt {
                t,
                facet: g,
                s,
                axis,
                depth,
                prev,
                late: s.x <= 0.5 * p0,
            };
            let Some((sr, ax, node)) = self.ray_cross(beam.entry, at, floor, cx, w, st, sink)
            else {
                return;
            };
            t = reflect(t, self.normals[g]);
            s = sr;
            axis = ax;
            facet = g;
            depth += 1;
            prev = node;
        }
    }

    /// One crossing of a narrow beam's ray (or of one of its parts) at `at.facet`: the
    /// transmitted part leaves as an exit beam, and the reflected part with its polarization
    /// axis and node is returned unless it falls below `floor` (stopped: accounted in
    /// `cut_off`, and in `ray_closed` when above the threshold) or past the depth limit.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn ray_cross<S: ExitSink>(
        &self,
        entry: u32,
        at: RayAt,
        floor: f64,
        cx: &Ctx,
        w: &mut Work,
        st: &mut TraceStats,
        sink: &mut S,
    ) -> Option<(Stokes, DVec3, u32)> {
        st.ray_segments += 1;
        let node = w.node(cx, at.prev, at.facet);
        let meet = Meet {
            t: at.t,
            n: self.normals[at.facet],
            facet: at.facet,
            stokes: at.s,
            axis: at.axis,
        };
        let origin = Origin {
            entry: entry as usize,
            reflections: at.depth,
            narrow: true,
            late: at.late,
            node,
        };
        let (sr, ax) = cross(cx, meet, origin, &w.foot, st, sink);
        let depth = at.depth + 1;
        if sr.x.is_nan() || sr.x <= 0.0 || sr.x < floor || depth > cx.max_depth {
            st.cut_off += sr.x.max(0.0);
            if sr.x >= cx.threshold && depth <= cx.max_depth {
                st.ray_closed += sr.x;
            }
            return None;
        }
        Some((sr, ax, node))
    }

    /// [`Stone::follow_ray`] with [`TraceOptions::narrow_forks`]: the ray stands for a disc of
    /// radius `r`. Where the disc overhangs an edge of the facet the ray meets, the overhanging
    /// segment forks off onto the neighbouring facet as a ray of its own (from the segment's
    /// centroid, with its share of the power and a disc of its area) and the rest goes on from
    /// its own centroid, so that a beam sliding across an edge hands its light over
    /// continuously instead of all at once.
    #[allow(clippy::too_many_arguments)]
    fn follow_disc<S: ExitSink>(
        &self,
        beam: Beam,
        x: DVec3,
        r: f64,
        floor: f64,
        cx: &Ctx,
        w: &mut Work,
        st: &mut TraceStats,
        sink: &mut S,
    ) {
        let p0 = beam.stokes.x;
        w.parts.clear();
        w.parts.push(Part {
            x,
            t: beam.dir,
            s: beam.stokes,
            axis: beam.axis,
            facet: beam.facet,
            depth: beam.depth,
            prev: beam.node,
            r,
            share: 1.0,
        });
        while let Some(part) = w.parts.pop() {
            let t = part.t;
            let Some((g, best)) = self.exit_facet(part.x, t, part.facet as usize) else {
                st.cut_off += part.s.x;
                continue;
            };
            let p = part.x + t * best.max(0.0);
            self.disc_forks(g, p, &part, p0, w);
            let total: f64 = w.forks.iter().map(|k| k.f).sum();
            let scale = if total > FORK_MAX {
                FORK_MAX / total
            } else {
                1.0
            };
            let main = 1.0 - total * scale;
            let mut shift = DVec3::ZERO;
            for k in &w.forks {
                shift -= k.m * (k.c * k.f * scale / main);
            }
            let nforks = w.forks.len();
            for i in 0..=nforks {
                // The main part last (it is followed first).
                let (h, f, y) = if i < nforks {
                    let k = w.forks[i];
                    (k.h as usize, k.f * scale, p + k.m * k.c)
                } else {
                    (g, main, p + shift)
                };
                let nh = self.normals[h];
                let y = y + t * ((self.offsets[h] - nh.dot(y)) / nh.dot(t));
                let share = part.share * f;
                let s_in = part.s * f;
                let at = RayAt {
                    t,
                    facet: h,
                    s: s_in,
                    axis: part.axis,
                    depth: part.depth,
                    prev: part.prev,
                    late: s_in.x <= 0.5 * share * p0,
                };
                if let Some((sr, axis, node)) =
                    self.ray_cross(beam.entry, at, floor, cx, w, st, sink)
                {
                    w.parts.push(Part {
                        x: y,
                        t: reflect(t, nh),
                        s: sr,
                        axis,
                        facet: h as u32,
                        depth: part.depth + 1,
                        prev: node,
                        r: part.r * f.sqrt(),
                        share,
                    });
                }
            }
        }
    }

    /// The segments of `part`'s disc beyond the edges of facet `g`, which its ray meets at
    /// `p`, into `w.forks` (`p0`: the narrow beam's starting power).
    fn disc_forks(&self, g: usize, p: DVec3, part: &Part, p0: f64, w: &mut Work) {
        w.forks.clear();
        let t = part.t;
        let ng = self.normals[g];
        let kg = ng.dot(t);
        let (a, b) = self.neighbor_range[g];
        let (a, b) = (a as usize, b as usize);
        for (j, (pl, &h)) in self.neighbor_planes[a..b]
            .iter()
            .zip(&self.neighbors[a..b])
            .enumerate()
        {
            let nh = pl.truncate();
            let kh = nh.dot(t);
            if kh <= GRAZE {
                continue;
            }
            // The plane through the edge along t: m · y = 0 there, m ⊥ t.
            let m = nh - ng * (kh / kg);
            let ml = m.length();
            if ml.is_nan() || ml <= 0.0 {
                continue;
            }
            let d = (pl.w - nh.dot(p)) / ml;
            if d >= part.r {
                continue;
            }
            let u = d / part.r;
            let (f, c) = disc_segment(u);
            // Only the stretch of the chord that the edge itself spans overhangs onto h (a
            // short edge's line may cross the disc far from the edge).
            let (ea, eb) = self.neighbor_edges[a + j];
            let e = (eb - ea).reject_from_normalized(t);
            let el = e.length();
            let half = part.r * (1.0 - u * u).max(0.0).sqrt();
            let span = if el > 0.0 && half > 0.0 {
                let e = e / el;
                let (sa, sb) = ((ea - p).dot(e), (eb - p).dot(e));
                (sa.max(sb).min(half) - sa.min(sb).max(-half)).max(0.0) / (2.0 * half)
            } else {
                0.0
            };
            let fade = (kh / FORK_GRAZE).min(1.0);
            // Small forks fade out (between FORK_MIN and twice that share of the narrow
            // beam) rather than stop at once.
            let small = (f * span * part.s.x / (FORK_MIN * p0) - 1.0).clamp(0.0, 1.0);
            let f = f * span * smooth(fade) * smooth(small);
            if f.is_nan() || f <= 0.0 {
                continue;
            }
            w.forks.push(Fork {
                h,
                f,
                m: m / ml,
                c: c * part.r,
            });
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
        let (mut lo, mut hi) = (w.q[0], w.q[0]);
        for &p in &w.q[1..] {
            lo = lo.min(p);
            hi = hi.max(p);
        }
        // Widened far beyond the clip's tolerance (TOL): facets whose projected bounding box
        // misses this one overlap the beam in nothing the clip would keep.
        w.qlo = lo - DVec2::splat(BOX_MARGIN);
        w.qhi = hi + DVec2::splat(BOX_MARGIN);
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
            let node = w.node(cx, beam.node, g);
            let meet = Meet {
                t,
                n,
                facet: g,
                stokes: beam.stokes * (ch.area / sum),
                axis: beam.axis,
            };
            let origin = Origin {
                entry: beam.entry as usize,
                reflections: beam.depth,
                narrow: false,
                late: false,
                node,
            };
            let (sr, axis) = cross(cx, meet, origin, &w.foot, st, sink);
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
        let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
        for &v in self.facet_verts(g) {
            let v = v as usize;
            if w.vstamp[v] != stamp {
                w.vstamp[v] = stamp;
                let x = self.vertices[v];
                w.proj[v] = DVec2::new(x.dot(e1), x.dot(e2));
            }
            let p = w.proj[v];
            lo = lo.min(p);
            hi = hi.max(p);
            w.g.push(p);
        }
        if lo.x > w.qhi.x || lo.y > w.qhi.y || hi.x < w.qlo.x || hi.y < w.qlo.y {
            // Disjoint bounding boxes: nothing to clip.
            return 0.0;
        }
        if self.fragile[g] {
            clip2d::make_convex(&mut w.g);
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
