//! Narrow beams (below the split threshold) followed as one ray each, with exact
//! expected-value Fresnel branching at every facet the ray meets, or, with
//! [`TraceOptions::narrow_forks`](super::TraceOptions::narrow_forks), as a disc that forks
//! across facet edges ([`disc`](super::disc)).

use super::disc::{Part, FORK_MAX};
use super::interface::{cross, Meet, Origin};
use super::sink::ExitSink;
use super::stone::Stone;
use super::work::{Beam, Ctx, Polarized, Work};
use crate::optics::{reflect, Stokes};
use glam::DVec3;

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
    /// Path length inside the stone from the entry facet to this crossing.
    path: f64,
    /// Where the ray meets the facet.
    x: DVec3,
    /// The exit's place is the narrow beam's polygon carried along (`Work::ray_poly`), not
    /// the point `x` ([`ExitSink::wants_narrow_polygons`]).
    poly: bool,
}

impl Stone {
    /// Follow a narrow beam as one ray from `x` (on `beam.facet`) with exact expected-value
    /// Fresnel branching: at each facet the transmitted part leaves (an exit beam with the
    /// narrow beam's footprint, `w.foot`), the reflected part goes on until it is below the
    /// floor or past the depth limit. With
    /// [`TraceOptions::narrow_forks`](super::TraceOptions::narrow_forks) the ray stands for a
    /// disc of radius `r` (the beam's cross-section; see [`Stone::follow_disc`]).
    pub(super) fn follow_ray<S: ExitSink>(
        &self,
        beam: Beam<Polarized>,
        mut x: DVec3,
        r: f64,
        cx: &Ctx,
        w: &mut Work<Polarized>,
        sink: &mut S,
    ) {
        w.st.rays += 1;
        let p0 = beam.light.stokes.x;
        w.st.ray_power += p0;
        let floor = cx.threshold.max(cx.ray_floor * p0);
        if cx.forks && r.is_finite() && r > 0.0 {
            return self.follow_disc(beam, x, r, cx, w, sink);
        }
        let (mut t, mut s, mut axis, mut facet, mut depth, mut prev) = (
            beam.light.dir,
            beam.light.stokes,
            beam.light.axis,
            beam.facet as usize,
            beam.depth,
            beam.node,
        );
        let mut path = if cx.alpha > 0.0 { beam.path.at(x) } else { 0.0 };
        // The narrow beam's polygon (in `w.cur`, on its facet's plane), carried along.
        let poly = sink.wants_exit_places() && sink.wants_narrow_polygons();
        w.ray_poly.clear();
        if poly {
            w.ray_poly.extend_from_slice(&w.cur);
        }
        loop {
            let Some((g, best)) = self.exit_facet(x, t, facet) else {
                w.st.cut_off += s.x;
                return;
            };
            x += t * best.max(0.0);
            path += best.max(0.0);
            if poly {
                // Slid along the ray onto facet g's plane (unclipped).
                let (n, o) = (self.normals[g], self.offsets[g]);
                let cos = n.dot(t);
                for p in w.ray_poly.iter_mut() {
                    *p += t * ((o - n.dot(*p)) / cos);
                }
            }
            let at = RayAt {
                path,
                x,
                t,
                facet: g,
                s,
                axis,
                depth,
                prev,
                late: s.x <= 0.5 * p0,
                poly,
            };
            let Some((sr, ax, node)) = self.ray_cross(beam.entry, at, floor, cx, w, sink) else {
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
    #[inline(always)]
    fn ray_cross<S: ExitSink>(
        &self,
        entry: u32,
        at: RayAt,
        floor: f64,
        cx: &Ctx,
        w: &mut Work<Polarized>,
        sink: &mut S,
    ) -> Option<(Stokes, DVec3, u32)> {
        w.st.ray_segments += 1;
        let node = w.node(cx, at.prev, at.facet);
        let meet = Meet {
            t: at.t,
            n: self.normals[at.facet],
            facet: at.facet,
            stokes: at.s,
            axis: at.axis,
            keep: if cx.alpha > 0.0 {
                (-cx.alpha * at.path).exp()
            } else {
                1.0
            },
        };
        let origin = Origin {
            entry: entry as usize,
            reflections: at.depth,
            narrow: true,
            late: at.late,
            node,
        };
        let one = [at.x];
        let place: &[DVec3] = if at.poly { &w.ray_poly } else { &one };
        let (sr, ax) = cross(cx, meet, origin, &w.foot, place, &mut w.st, sink);
        let depth = at.depth + 1;
        if sr.x.is_nan() || sr.x <= 0.0 || sr.x < floor || depth > cx.max_depth {
            w.st.cut_off += sr.x.max(0.0);
            if sr.x >= cx.threshold && depth <= cx.max_depth {
                w.st.ray_closed += sr.x;
            }
            return None;
        }
        Some((sr, ax, node))
    }

    /// [`Stone::follow_ray`] with
    /// [`TraceOptions::narrow_forks`](super::TraceOptions::narrow_forks): the ray stands for a
    /// disc of radius `r`. Where the disc overhangs an edge of the facet the ray meets, the
    /// overhanging segment forks off onto the neighbouring facet as a ray of its own (from the
    /// segment's centroid, with its share of the power and a disc of its area) and the rest
    /// goes on from its own centroid, so that a beam sliding across an edge hands its light
    /// over continuously instead of all at once.
    fn follow_disc<S: ExitSink>(
        &self,
        beam: Beam<Polarized>,
        x: DVec3,
        r: f64,
        cx: &Ctx,
        w: &mut Work<Polarized>,
        sink: &mut S,
    ) {
        let p0 = beam.light.stokes.x;
        let floor = cx.threshold.max(cx.ray_floor * p0);
        w.parts.clear();
        w.parts.push(Part {
            x,
            t: beam.light.dir,
            s: beam.light.stokes,
            axis: beam.light.axis,
            facet: beam.facet,
            depth: beam.depth,
            prev: beam.node,
            r,
            share: 1.0,
            path: if cx.alpha > 0.0 { beam.path.at(x) } else { 0.0 },
        });
        while let Some(part) = w.parts.pop() {
            let t = part.t;
            let Some((g, best)) = self.exit_facet(part.x, t, part.facet as usize) else {
                w.st.cut_off += part.s.x;
                continue;
            };
            let p = part.x + t * best.max(0.0);
            let path = part.path + best.max(0.0);
            self.disc_forks(g, p, &part, p0, &mut w.forks);
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
                let along = (self.offsets[h] - nh.dot(y)) / nh.dot(t);
                let y = y + t * along;
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
                    path: path + along,
                    x: y,
                    poly: false,
                };
                if let Some((sr, axis, node)) = self.ray_cross(beam.entry, at, floor, cx, w, sink) {
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
                        path: path + along,
                    });
                }
            }
        }
    }
}
