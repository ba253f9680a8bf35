//! The traversal of one trace, in either tracer: the root beams at the facets facing the
//! light (the symmetry's wedge or a window clipped off, each root's share of the light), then
//! the depth-first loop over the beams waiting to be split. The singly refractive trace's
//! entry (external reflection and refraction) is here; the birefringent one's is in
//! `crystal.rs`.

use super::exit::ExitBeam;
use super::footprint::{Affine, PathLength};
use super::frame::Frame;
use super::interface::split;
use super::options::TraceOptions;
use super::sink::{ExitSink, TraceStats};
use super::stone::{Stone, GRAZE};
use super::symmetry::{RootClip, SymSink};
use super::work::{Beam, Ctx, Light, Polarized, Work};
use crate::optics::{fresnel, reflect, refract, s_axis, Stokes};
use glam::{DVec2, DVec3, DVec4};

/// A root of a trace: facet `f` (outward normal `n`) facing the light at incidence cosine
/// `c`, with share `p` of the light and tree node `node`; its polygon is in `Work::cur`, its
/// footprint (when wanted) in `Work::foot`, and `map` takes a point to the frame's plane.
#[derive(Clone, Copy, Debug)]
pub(super) struct Root {
    pub(super) f: usize,
    pub(super) n: DVec3,
    pub(super) c: f64,
    pub(super) p: f64,
    pub(super) node: u32,
    pub(super) map: Affine,
}

impl Root {
    /// The beam that enters at this root, carrying `light`.
    #[inline]
    pub(super) fn beam<L>(&self, light: L) -> Beam<L> {
        Beam {
            light,
            facet: self.f as u32,
            entry: self.f as u32,
            depth: 0,
            node: self.node,
            start: 0,
            len: 0,
            map: self.map,
            path: PathLength::default(),
        }
    }

    /// The light reflected outside at this root (Stokes vector `stokes`, reference `axis`,
    /// along `direction`): an exit beam through the root's polygon.
    #[inline]
    pub(super) fn reflect<L, S: ExitSink>(
        &self,
        direction: DVec3,
        stokes: Stokes,
        axis: DVec3,
        w: &mut Work<L>,
        sink: &mut S,
    ) {
        let ext = ExitBeam {
            direction,
            power: stokes.x,
            unabsorbed: stokes.x,
            stokes,
            axis,
            entry_facet: self.f,
            exit_facet: self.f,
            reflections: 0,
            external: true,
            narrow: false,
            late: false,
            mode: None,
            node: self.node,
            sym: 0,
        };
        w.st.exits += 1;
        sink.exit_at(&ext, &w.foot, &w.cur);
    }
}

/// How one tracer's light enters at a root and how its beams split: what
/// [`Stone::trace_roots`] leaves to the tracer.
pub(super) trait Tracer {
    /// The light its beams carry.
    type Light: Light;
    /// The light entering at `root`: the external reflection handed to `sink`, each beam
    /// going inside settled ([`Stone::settle`]).
    fn enter<S: ExitSink>(&self, root: Root, cx: &Ctx, w: &mut Work<Self::Light>, sink: &mut S);
    /// Split one beam waiting on the stack.
    fn split<S: ExitSink>(
        &self,
        beam: Beam<Self::Light>,
        cx: &Ctx,
        w: &mut Work<Self::Light>,
        sink: &mut S,
    );
}

/// The singly refractive trace at index `ri`.
struct Singly<'a> {
    stone: &'a Stone,
    frame: &'a Frame,
    ri: f64,
}

impl Tracer for Singly<'_> {
    type Light = Polarized;

    #[inline]
    fn enter<S: ExitSink>(&self, root: Root, cx: &Ctx, w: &mut Work<Polarized>, sink: &mut S) {
        let (d0, n) = (self.frame.dir, root.n);
        let fr = fresnel(root.c, 1.0, self.ri);
        let axis = s_axis(d0, n).unwrap_or(self.frame.u);
        let (sr, stt) = split(cx.pol, &fr, DVec4::new(root.p, 0.0, 0.0, 0.0));
        root.reflect(reflect(d0, n), sr, axis, w, sink);
        let beam = match refract(d0, n, 1.0, self.ri) {
            Some(t) if stt.x > 0.0 => root.beam(Polarized {
                dir: t,
                stokes: stt,
                axis,
            }),
            // Below the critical angle from outside (ri < 1): everything was reflected.
            _ => {
                w.st.cut_off += stt.x;
                return;
            }
        };
        // `w.cur` holds the polygon, `w.foot` its footprint.
        self.stone.continue_beam(beam, cx, w, sink);
    }

    #[inline]
    fn split<S: ExitSink>(
        &self,
        beam: Beam<Polarized>,
        cx: &Ctx,
        w: &mut Work<Polarized>,
        sink: &mut S,
    ) {
        self.stone.split_beam(beam, cx, w, sink);
    }
}

impl Stone {
    /// Trace one direction at refractive index `ri`, handing every exit beam to `sink`, for
    /// the part of the cross-section inside `window`: the points
    /// `x` of the facets facing the light with `n · x <= c` for every `(n, c)` in it (a
    /// convex window; empty: the whole stone). Powers stay shares of the whole stone's
    /// incoming light (`power_in` is the window's share of it), and the stone's symmetry is
    /// not used (a window breaks it). Tiles of a picture traced this way add up to the whole.
    /// Returns the power accounting and, when `keep_nodes`, the facet-sequence tree (parent,
    /// facet) that [`ExitBeam`]s index into.
    pub(crate) fn trace_window_into<S: ExitSink>(
        &self,
        frame: &Frame,
        ri: f64,
        opts: &TraceOptions,
        window: &[DVec4],
        sink: &mut S,
        keep_nodes: bool,
    ) -> (TraceStats, Vec<(u32, u32)>) {
        let tracer = Singly {
            stone: self,
            frame,
            ri,
        };
        self.trace_roots(&tracer, frame, ri, None, opts, window, sink, keep_nodes)
    }

    /// The root pass of a trace at (ordinary) index `ri`, either tracer's: every facet facing
    /// the light, clipped to the symmetry's fundamental wedge (the symmetries that also keep
    /// the optic axis `keeping`, when given) or to `window`, enters by `tracer` in facet
    /// order, and the beams it leaves on the stack are split depth-first before the next
    /// root (so the walk order, and the exit order, is deterministic). The accounting is
    /// scaled back up to the whole stone.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub(super) fn trace_roots<T: Tracer, S: ExitSink>(
        &self,
        tracer: &T,
        frame: &Frame,
        ri: f64,
        keeping: Option<DVec3>,
        opts: &TraceOptions,
        window: &[DVec4],
        sink: &mut S,
        keep_nodes: bool,
    ) -> (TraceStats, Vec<(u32, u32)>) {
        let mut st = TraceStats::default();
        let d0 = frame.dir;
        if !(ri.is_finite() && ri > 0.0 && d0.is_finite()) {
            return (st, Vec::new());
        }
        let total = self.cross_section(d0);
        st.area = total;
        if total.is_nan() || total <= 0.0 {
            return (st, Vec::new());
        }
        let cx = Ctx::new(ri, opts, sink.wants_footprints(), keep_nodes);
        let mut w = self.work::<T::Light>();
        w.st = st;
        let map0 = Affine {
            a1: frame.u,
            a2: frame.v,
            b: DVec2::ZERO,
        };
        // Symmetry: trace a fundamental wedge and hand out every exit once per symmetry.
        let (group, wedge) = match keeping {
            _ if !(opts.symmetry && window.is_empty()) => (vec![0], vec![]),
            None => self.symmetry.frame_symmetry(d0),
            Some(axis) => self.symmetry.frame_symmetry_keeping(d0, axis),
        };
        let mut sym = SymSink::new(&self.symmetry, &group, frame, sink);
        let mut piece: Vec<DVec3> = Vec::with_capacity(32);
        let clip = RootClip {
            wedge: &wedge,
            window,
            total,
        };
        for f in 0..self.facet_count() {
            let n = self.normals[f];
            let c = -n.dot(d0);
            if c <= GRAZE {
                continue;
            }
            let map = |x: DVec3| map0.apply(x);
            let Some(p) = self.root_share(f, c, &clip, &mut w.cur, &mut piece, map) else {
                continue;
            };
            w.st.power_in += p;
            let node = w.node(&cx, u32::MAX, f);
            w.foot.clear();
            if cx.want_fp {
                w.foot.extend(w.cur.iter().map(|&x| map0.apply(x)));
            }
            let root = Root {
                f,
                n,
                c,
                p,
                node,
                map: map0,
            };
            tracer.enter(root, &cx, &mut w, &mut sym);
            while let Some(beam) = w.stack.pop() {
                tracer.split(beam, &cx, &mut w, &mut sym);
            }
        }
        let g = group.len() as f64;
        w.st.power_in *= g;
        w.st.cut_off *= g;
        w.st.ray_closed *= g;
        w.st.absorbed *= g;
        w.st.exits *= group.len();
        let nodes = if keep_nodes {
            std::mem::take(&mut w.nodes)
        } else {
            Vec::new()
        };
        (w.st, nodes)
    }
}
