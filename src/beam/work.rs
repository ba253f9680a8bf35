//! The state of one trace, in either tracer: its cleaned settings ([`Ctx`]), a beam waiting
//! to be split ([`Beam`]) and the working memory reused across beams ([`Work`]).

use super::disc::{Fork, Part};
use super::footprint::{Affine, PathLength};
use super::mode::{InMode, ModeRay};
use super::sink::TraceStats;
use super::stone::Stone;
use crate::optics::Stokes;
use glam::{DVec2, DVec3};

/// A beam waiting to be split, in either tracer: where it is and what it came from, and the
/// light `L` it carries ([`Polarized`] in the singly refractive trace,
/// [`InMode`](super::mode::InMode) in the birefringent one).
#[derive(Clone, Copy, Debug)]
pub(super) struct Beam<L> {
    pub(super) light: L,
    pub(super) facet: u32,
    pub(super) entry: u32,
    pub(super) depth: u32,
    pub(super) node: u32,
    /// Its polygon (on `facet`'s plane) is `pts[start..start + len]` of the point stack.
    pub(super) start: u32,
    pub(super) len: u32,
    pub(super) map: Affine,
    /// From the entry facet over the polygon (used when absorbing): the path length in the
    /// singly refractive trace, the optical depth `Σ αᵢ Lᵢ` in the birefringent one.
    pub(super) path: PathLength,
}

/// The light a beam carries, as far as the fate they share needs it.
pub(super) trait Light: Copy {
    /// Its power (before absorption).
    fn power(&self) -> f64;
}

/// A singly refractive trace's beam's light: its direction and Stokes vector (reference
/// `axis`).
#[derive(Clone, Copy, Debug)]
pub(super) struct Polarized {
    pub(super) dir: DVec3,
    pub(super) stokes: Stokes,
    pub(super) axis: DVec3,
}

impl Light for Polarized {
    #[inline(always)]
    fn power(&self) -> f64 {
        self.stokes.x
    }
}

impl Light for InMode {
    #[inline(always)]
    fn power(&self) -> f64 {
        self.power
    }
}

/// A piece of the beam being split: the facet it meets, its projected polygon
/// (`cpts[start..start + len]`) and that polygon's area.
#[derive(Clone, Copy, Debug)]
pub(super) struct Child {
    pub(super) facet: u32,
    pub(super) start: u32,
    pub(super) len: u32,
    pub(super) area: f64,
}

/// Settings of one trace, cleaned.
pub(super) struct Ctx {
    pub(super) ri: f64,
    pub(super) pol: bool,
    pub(super) threshold: f64,
    pub(super) split_threshold: f64,
    pub(super) ray_floor: f64,
    pub(super) forks: bool,
    pub(super) max_depth: u32,
    /// Absorption per girdle diameter (0: colourless).
    pub(super) alpha: f64,
    pub(super) want_fp: bool,
    /// Record the facet-sequence tree (otherwise node ids are `u32::MAX`).
    pub(super) keep_nodes: bool,
}

impl Ctx {
    /// The settings of a trace at index `ri` under `opts` (negative and non-finite powers
    /// read as 0).
    pub(super) fn new(
        ri: f64,
        opts: &super::options::TraceOptions,
        want_fp: bool,
        keep_nodes: bool,
    ) -> Ctx {
        let clean = |x: f64| if x.is_finite() { x.max(0.0) } else { 0.0 };
        Ctx {
            ri,
            pol: opts.polarization,
            threshold: clean(opts.threshold),
            split_threshold: clean(opts.split_threshold),
            ray_floor: clean(opts.ray_floor),
            forks: opts.narrow_forks,
            max_depth: opts.max_depth,
            alpha: clean(opts.absorption),
            want_fp,
            keep_nodes,
        }
    }
}

/// Working memory of one trace whose beams carry light `L`, reused across beams.
pub(super) struct Work<L> {
    pub(super) pts: Vec<DVec3>,
    /// The beams waiting to be split.
    pub(super) stack: Vec<Beam<L>>,
    pub(super) cur: Vec<DVec3>,
    pub(super) q: Vec<DVec2>,
    pub(super) g: Vec<DVec2>,
    pub(super) clip: Vec<DVec2>,
    pub(super) scratch: Vec<DVec2>,
    pub(super) proj: Vec<DVec2>,
    /// Bounding box of `q` (the beam being split, projected).
    pub(super) qlo: DVec2,
    pub(super) qhi: DVec2,
    pub(super) vstamp: Vec<u32>,
    pub(super) fstamp: Vec<u32>,
    pub(super) stamp: u32,
    pub(super) queue: Vec<u32>,
    pub(super) children: Vec<Child>,
    pub(super) cpts: Vec<DVec2>,
    pub(super) foot: Vec<DVec2>,
    /// A narrow beam's polygon carried along its ray (when the sink wants it as the place).
    pub(super) ray_poly: Vec<DVec3>,
    /// Exponents `−α L` at the vertices of `cur` (when absorbing).
    pub(super) phi: Vec<f64>,
    pub(super) nodes: Vec<(u32, u32)>,
    pub(super) parts: Vec<Part>,
    pub(super) forks: Vec<Fork>,
    /// A birefringent narrow beam's rays.
    pub(super) mode_rays: Vec<ModeRay>,
    /// The polygons of a birefringent narrow beam's rays, each carried to the facet its ray
    /// is on ([`ModeRay::poly`]), all of the narrow beam's vertex count.
    pub(super) mode_polys: Vec<DVec3>,
    /// The trace's accounting so far.
    pub(super) st: TraceStats,
}

impl<L> Work<L> {
    /// Lift child `ch`'s polygon (projected on `(e1, e2)`, in `cpts`) along `t` onto the
    /// plane `n · x = o` of the facet it meets, into `cur`.
    #[inline]
    pub(super) fn lift(&mut self, ch: Child, e1: DVec3, e2: DVec3, t: DVec3, n: DVec3, o: f64) {
        // Lift the child's polygon onto facet g's plane.
        let cos_i = n.dot(t);
        self.cur.clear();
        for p in &self.cpts[ch.start as usize..(ch.start + ch.len) as usize] {
            let x = e1 * p.x + e2 * p.y;
            self.cur.push(x + t * ((o - n.dot(x)) / cos_i));
        }
    }

    /// A new node (parent, facet) of the facet-sequence tree: its id, or `u32::MAX` when the
    /// tree is not kept.
    #[inline]
    pub(super) fn node(&mut self, cx: &Ctx, parent: u32, facet: usize) -> u32 {
        if !cx.keep_nodes {
            return u32::MAX;
        }
        let node = self.nodes.len() as u32;
        self.nodes.push((parent, facet as u32));
        node
    }
}

impl Stone {
    pub(super) fn work<L>(&self) -> Work<L> {
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
            ray_poly: Vec::new(),
            phi: Vec::with_capacity(32),
            nodes: Vec::with_capacity(4096),
            parts: Vec::with_capacity(32),
            forks: Vec::with_capacity(8),
            mode_rays: Vec::new(),
            mode_polys: Vec::new(),
            st: TraceStats::default(),
        }
    }
}
