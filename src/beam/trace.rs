//! The traversal of one trace: the root beams at the facets facing the light (external
//! reflection and refraction at entry, the symmetry's wedge), then the depth-first loop over
//! the beams waiting to be split.

use super::exit::ExitBeam;
use super::footprint::{Affine, PathLength};
use super::frame::Frame;
use super::interface::split;
use super::options::TraceOptions;
use super::sink::{ExitSink, TraceStats};
use super::stone::{Stone, GRAZE};
use super::symmetry::{RootClip, SymSink};
use super::work::{Beam, Ctx};
use crate::optics::{fresnel, reflect, refract, s_axis};
use glam::{DVec2, DVec3, DVec4};

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
        let mut w = self.work();
        w.st = st;
        let map0 = Affine {
            a1: frame.u,
            a2: frame.v,
            b: DVec2::ZERO,
        };
        // Symmetry: trace a fundamental wedge and hand out every exit once per symmetry.
        let (group, wedge) = if opts.symmetry && window.is_empty() {
            self.symmetry.frame_symmetry(d0)
        } else {
            (vec![0], vec![])
        };
        let mut sym = SymSink::new(&self.symmetry, &group, frame, sink);
        let mut piece: Vec<DVec3> = Vec::with_capacity(32);
        let clip = RootClip {
            wedge: &wedge,
            window,
            total,
        };

        // Entry: external reflection and refraction at every facet facing the light.
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
                unabsorbed: sr.x,
                stokes: sr,
                axis,
                entry_facet: f,
                exit_facet: f,
                reflections: 0,
                external: true,
                narrow: false,
                late: false,
                mode: None,
                node,
                sym: 0,
            };
            w.st.exits += 1;
            sym.exit_at(&ext, &w.foot, &w.cur);
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
                    path: PathLength::default(),
                },
                // Below the critical angle from outside (ri < 1): everything was reflected.
                _ => {
                    w.st.cut_off += stt.x;
                    continue;
                }
            };
            // `w.cur` holds the polygon, `w.foot` its footprint.
            self.continue_beam(beam, &cx, &mut w, &mut sym);
            // Depth-first from this root; roots go in facet order, so the walk order (and the
            // exit order) is deterministic.
            while let Some(beam) = w.stack.pop() {
                self.split_beam(beam, &cx, &mut w, &mut sym);
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
