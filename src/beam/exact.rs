//! Exact beams: the fate of a beam about to travel inside (split exactly, followed as a
//! narrow beam, or cut off) and its exact split by the facets it reaches, each child crossing
//! its facet's interface.

use super::attenuation::exp_mean_planar;
use super::interface::{cross, Meet, Origin};
use super::sink::ExitSink;
use super::stone::{Stone, GRAZE};
use super::work::{Beam, Child, Ctx, Light, Polarized, Work};
use crate::geometry::clip2d;
use crate::optics::reflect;
use glam::{DVec2, DVec3};

/// Children with less than this share of their parent's cross-section are rounding slivers
/// along shared edges; they are dropped and their (negligible) share goes to their siblings.
const SLIVER: f64 = 1e-13;

/// Margin (girdle diameters, ~100 times [`clip2d::TOL`]) by which projected bounding boxes
/// must miss each other for [`Stone::clip_facet`] to skip the clip: the clip keeps only points
/// within `TOL` of both polygons, so it would find nothing there.
const BOX_MARGIN: f64 = 1e-10;

/// Area centroid and area of the planar polygon `poly` (normal `n`): unlike the mean of its
/// vertices, the centroid moves continuously when a clip adds a vertex. The vertex mean (and
/// area 0) for a degenerate polygon.
pub(super) fn area_centroid(poly: &[DVec3], n: DVec3) -> (DVec3, f64) {
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

impl Stone {
    /// The fate of a beam about to travel inside (its polygon in `w.cur`, on `beam.facet`'s
    /// plane), in either tracer: cut off (no power, below the threshold or past the depth
    /// limit), or split exactly (its polygon onto the point stack, the beam onto the stack),
    /// or handed back, with its polygon's area centroid and area, to be followed as a narrow
    /// beam's ray from the centroid (always when `narrow`).
    #[inline(always)]
    pub(super) fn settle<L: Light>(
        &self,
        beam: Beam<L>,
        narrow: bool,
        cx: &Ctx,
        w: &mut Work<L>,
    ) -> Option<(Beam<L>, DVec3, f64)> {
        let p = beam.light.power();
        if p.is_nan() || p <= 0.0 || p < cx.threshold || beam.depth > cx.max_depth {
            w.st.cut_off += p.max(0.0);
        } else if p >= cx.split_threshold && !narrow {
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
            let (c, area) = area_centroid(&w.cur, self.normals[beam.facet as usize]);
            return Some((beam, c, area));
        }
        None
    }

    /// The fate of a singly refractive beam about to travel inside ([`Stone::settle`]); its
    /// footprint, when footprints are wanted, is in `w.foot`.
    pub(super) fn continue_beam<S: ExitSink>(
        &self,
        beam: Beam<Polarized>,
        cx: &Ctx,
        w: &mut Work<Polarized>,
        sink: &mut S,
    ) {
        let Some((beam, c, area)) = self.settle(beam, false, cx, w) else {
            return;
        };
        // The disc of the beam's cross-section (kept by mirror reflections).
        let n = self.normals[beam.facet as usize];
        let r = (area * n.dot(beam.light.dir).abs() / std::f64::consts::PI).sqrt();
        self.follow_ray(beam, c, r, cx, w, sink);
    }

    /// Split one internal beam by the facets it reaches.
    pub(super) fn split_beam<S: ExitSink>(
        &self,
        beam: Beam<Polarized>,
        cx: &Ctx,
        w: &mut Work<Polarized>,
        sink: &mut S,
    ) {
        w.st.beams += 1;
        let light = beam.light;
        let t = light.dir;
        let Some((e1, e2, sum)) = self.tile(beam.start, beam.len, t, beam.facet, w) else {
            w.st.cut_off += light.stokes.x;
            return;
        };

        let f = beam.facet as usize;
        let map = beam.map.slide(t, self.normals[f], self.offsets[f]);
        let path = if cx.alpha > 0.0 {
            beam.path.slide(t, self.normals[f], self.offsets[f])
        } else {
            beam.path
        };
        let nchildren = w.children.len();
        for ci in 0..nchildren {
            let ch = w.children[ci];
            let g = ch.facet as usize;
            let n = self.normals[g];
            let o = self.offsets[g];
            w.lift(ch, e1, e2, t, n, o);
            w.foot.clear();
            if cx.want_fp {
                w.foot.extend(w.cur.iter().map(|&x| map.apply(x)));
            }
            let node = w.node(cx, beam.node, g);
            let keep = if cx.alpha > 0.0 {
                w.phi.clear();
                w.phi.extend(w.cur.iter().map(|&x| -cx.alpha * path.at(x)));
                exp_mean_planar(&w.cur, n, &w.phi)
            } else {
                1.0
            };
            let meet = Meet {
                t,
                n,
                facet: g,
                stokes: light.stokes * (ch.area / sum),
                axis: light.axis,
                keep,
            };
            let origin = Origin {
                entry: beam.entry as usize,
                reflections: beam.depth,
                narrow: false,
                late: false,
                node,
            };
            let (sr, axis) = cross(cx, meet, origin, &w.foot, &w.cur, &mut w.st, sink);
            let next = Beam {
                light: Polarized {
                    dir: reflect(t, n),
                    stokes: sr,
                    axis,
                },
                facet: g as u32,
                entry: beam.entry,
                depth: beam.depth + 1,
                node,
                start: 0,
                len: 0,
                map,
                path,
            };
            self.continue_beam(next, cx, w, sink);
        }
    }

    /// Take the beam's polygon (`pts[start..start + len]`, on top of the point stack, on
    /// `facet`'s plane) off the stack into `w.cur` and tile its cross-section across
    /// direction `t` by the facets it reaches: their pieces (projected on `(e1, e2)`) go to
    /// `w.children`, and the sum of their areas is returned with `e1, e2`. `None` when the
    /// beam has no cross-section or reaches no facet (its power is then the caller's to cut
    /// off).
    pub(super) fn tile<L>(
        &self,
        start: u32,
        len: u32,
        t: DVec3,
        facet: u32,
        w: &mut Work<L>,
    ) -> Option<(DVec3, DVec3, f64)> {
        // Take the beam's polygon off the point stack (it is on top).
        w.cur.clear();
        let (a, b) = (start as usize, (start + len) as usize);
        w.cur.extend_from_slice(&w.pts[a..b]);
        w.pts.truncate(a);

        let (e1, e2) = t.any_orthonormal_pair();
        w.q.clear();
        w.q.extend(w.cur.iter().map(|x| DVec2::new(x.dot(e1), x.dot(e2))));
        let aq = clip2d::area(&w.q);
        if aq.is_nan() || aq <= 0.0 {
            return None;
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
        let (seed, _) = self.exit_facet(c, t, facet as usize)?;
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
                for h in self.facet_edges(g).iter().map(|e| e.facet) {
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
        w.st.max_tiling_error = w.st.max_tiling_error.max((sum - aq).abs() / aq);
        if sum.is_nan() || sum <= 0.0 {
            return None;
        }
        Some((e1, e2, sum))
    }

    /// Clip the current beam (`w.q`) by facet `g` projected on (e1, e2); append a child if the
    /// overlap exceeds `keep_area` (a sliver otherwise). Returns the overlap's area.
    #[inline]
    fn clip_facet<L>(
        &self,
        g: usize,
        e1: DVec3,
        e2: DVec3,
        w: &mut Work<L>,
        keep_area: f64,
    ) -> f64 {
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
