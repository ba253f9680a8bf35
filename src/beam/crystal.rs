//! Birefringent stones in the beam tracer ([`Medium::Uniaxial`]).
//!
//! At a plane facet every mode of a plane wave in a uniaxial crystal keeps one wave vector
//! and one ray (Poynting) direction across the whole beam ([`crate::optics::crystal`]), so a
//! parallel beam splits into parallel beams: at entry into an ordinary and an extraordinary
//! beam, at every facet met from inside into a light leaving and a reflected beam of each
//! mode. Each beam moves along its ray direction (walk-off), so its footprint is still a
//! polygon cut by the facets projected along that direction, and its path length is still
//! affine over its cross-section; with per-mode absorption the optical depth `Σ αᵢ Lᵢ` is
//! affine too, and Beer–Lambert over a footprint stays exact.
//!
//! Inside the stone a beam is in one mode, so it carries a power, not a Stokes vector; the
//! light leaving gets its Stokes vector from the transmitted field (and the external
//! reflection from the reflected one). With polarization off these are given unpolarized;
//! the split into modes is the physics and stays.
//!
//! Narrow beams (below the split threshold) are followed as rays from their area centroid as
//! in the isotropic tracer, except that each crossing splits a ray into two reflected rays,
//! one per mode: a ray's tree is followed down to its floor (the power threshold, or
//! [`TraceOptions::ray_floor`] of the narrow beam's power), and what falls below is cut off
//! and accounted. Forking discs ([`TraceOptions::narrow_forks`]) are not used here.
//!
//! A selected once per trace: the singly refractive trace ([`Stone::trace_window_into`]) is not
//! touched by any of this.

use super::attenuation::exp_mean_planar;
use super::exit::ExitBeam;
use super::frame::Frame;
use super::mode::{InMode, ModeRay};
use super::options::TraceOptions;
use super::sink::{ExitSink, TraceStats};
use super::stone::Stone;
use super::trace::{Root, Tracer};
use super::work::{Beam, Ctx, Work};
use crate::optics::crystal::{Crystal, RawMeeting, Wave};
use crate::optics::BodyColour;
use crate::optics::Material;
use glam::{DVec3, DVec4};

/// The stone's optics for one trace at one wavelength.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Medium {
    /// Singly refractive (or birefringence off): one index; absorption is
    /// [`TraceOptions::absorption`].
    Isotropic(f64),
    /// A uniaxial crystal, with the absorption of light polarized ⊥ and ∥ to its optic axis
    /// per girdle diameter of path (pleochroism; [`TraceOptions::absorption`] is not used).
    Uniaxial {
        /// Indices and optic axis (stone coordinates).
        crystal: Crystal,
        /// Absorption for E ⊥ ĉ, per girdle diameter.
        alpha_o: f64,
        /// Absorption for E ∥ ĉ, per girdle diameter.
        alpha_e: f64,
    },
}

impl Medium {
    /// The ordinary (or only) index.
    pub fn ri(&self) -> f64 {
        match self {
            Medium::Isotropic(n) => *n,
            Medium::Uniaxial { crystal, .. } => crystal.n_o,
        }
    }
}

impl Medium {
    /// The medium a trace of `material` at `wavelength_nm` sees: a crystal with optic axis
    /// `axis` (in the traced solid's coordinates) when the stone is traced birefringent, its
    /// absorption per mode `mm_per_unit` times the body colour's α per mm (0 when `absorbing`
    /// is false); else the ordinary index alone, whose absorption the caller gives in
    /// [`TraceOptions::absorption`]. A uniaxial stone whose two indices and spectra coincide
    /// at this wavelength is singly refractive there and is traced so.
    pub fn of(
        material: &Material,
        wavelength_nm: f64,
        axis: DVec3,
        mm_per_unit: f64,
        absorbing: bool,
    ) -> Medium {
        let n_o = material.ri(wavelength_nm);
        if !material.birefringent() {
            return Medium::Isotropic(n_o);
        }
        let n_e = material.ri_e(wavelength_nm);
        let alpha = |c: Option<&BodyColour>| {
            if absorbing {
                c.map_or(0.0, |c| c.alpha(wavelength_nm) * mm_per_unit)
            } else {
                0.0
            }
        };
        let (alpha_o, alpha_e) = (alpha(material.colour.as_ref()), alpha(material.colour_e()));
        if n_e == n_o && alpha_o == alpha_e {
            return Medium::Isotropic(n_o);
        }
        Medium::Uniaxial {
            crystal: Crystal::new(n_o, n_e, axis),
            alpha_o,
            alpha_e,
        }
    }
}

/// A birefringent trace's settings beyond [`Ctx`].
struct Optics {
    crystal: Crystal,
    /// [`TraceOptions::mode_floor`], cleaned.
    mode_floor: f64,
    alpha_o: f64,
    alpha_e: f64,
    absorbing: bool,
}

impl Optics {
    /// Absorption per girdle diameter along `wave`'s ray.
    #[inline]
    fn alpha(&self, wave: &Wave) -> f64 {
        if self.absorbing {
            self.crystal.absorption(wave, self.alpha_o, self.alpha_e)
        } else {
            0.0
        }
    }
}

/// Where light crossing a facet leaves ([`ExitSink::exit_at`]'s place).
#[derive(Clone, Copy, Debug)]
enum Place {
    /// An exact beam: through its polygon in `Work::cur`.
    Beam,
    /// A narrow beam's ray: at one point.
    Point(DVec3),
    /// A narrow beam's ray: through its narrow beam's polygon carried along the ray,
    /// `Work::mode_polys[start..start + n]`.
    Polygon(u32, u32),
}

/// Two sibling beams (the two modes one beam splits into) that are both narrow beams: when
/// the weaker carries less than [`TraceOptions::mode_floor`] of the pair's power, one ray in
/// the stronger mode carries both (as a narrow beam's ray keeps its weaker mode's light from
/// then on), and the pair costs one ray instead of two. `None` when they go on apart.
/// `pair` holds the two modes' powers (`None`: not reflected); the result is the mode index
/// (0 ordinary, 1 extraordinary) that carries both and their sum.
#[inline]
fn merged(pair: &[Option<f64>; 2], cx: &Ctx, optics: &Optics) -> Option<(usize, f64)> {
    match *pair {
        [Some(a), Some(b)]
            if a.max(b) < cx.split_threshold && a.min(b) < optics.mode_floor * (a + b) =>
        {
            Some((if a >= b { 0 } else { 1 }, a + b))
        }
        _ => None,
    }
}

/// The modes that go on from a pair of powers: the merged one alone, else each reflected one
/// (ordinary first), as (mode index, power).
#[inline]
fn going_on(pair: [Option<f64>; 2], merge: Option<(usize, f64)>) -> [Option<(usize, f64)>; 2] {
    merge.map_or([pair[0].map(|p| (0, p)), pair[1].map(|p| (1, p))], |m| {
        [Some(m), None]
    })
}

/// The light reflected at a crossing: the meeting (which builds each mode's wave, only for
/// the modes followed) and each mode's power (`None` for a mode that is not reflected).
struct Reflected {
    meeting: RawMeeting,
    power: [Option<f64>; 2],
}

/// The birefringent trace through `optics`' crystal.
struct Birefringent<'a> {
    stone: &'a Stone,
    frame: &'a Frame,
    optics: &'a Optics,
}

impl Tracer for Birefringent<'_> {
    type Light = InMode;

    /// At entry the light splits into the external reflection and a beam in each mode.
    #[inline]
    fn enter<S: ExitSink>(&self, root: Root, cx: &Ctx, w: &mut Work<InMode>, sink: &mut S) {
        let (optics, u) = (self.optics, self.frame.u);
        let unpolarized = DVec4::new(1.0, 0.0, 0.0, 0.0);
        let Some(entry) = optics.crystal.enter(self.frame.dir, root.n, unpolarized, u) else {
            w.st.cut_off += root.p;
            return;
        };
        // Conserve power to rounding: the coefficients add up to 1 within ~1e-14.
        let sum = entry.reflected.x + entry.transmitted[0].1 + entry.transmitted[1].1;
        let scale = root.p / sum;
        let r = entry.reflected * scale;
        let stokes = if cx.pol {
            r
        } else {
            DVec4::new(r.x, 0.0, 0.0, 0.0)
        };
        root.reflect(entry.reflected_dir, stokes, entry.axis, w, sink);
        let transmitted = entry.transmitted.map(|(_, t)| Some(t * scale));
        let merge = merged(&transmitted, cx, optics);
        for (m, t) in going_on(transmitted, merge).into_iter().flatten() {
            let wave = entry.transmitted[m].0;
            let beam = root.beam(InMode {
                wave,
                power: t,
                alpha: optics.alpha(&wave),
            });
            let narrow = merge.is_some();
            self.stone
                .continue_mode_beam(beam, narrow, cx, optics, w, sink);
        }
    }

    #[inline]
    fn split<S: ExitSink>(&self, beam: Beam<InMode>, cx: &Ctx, w: &mut Work<InMode>, sink: &mut S) {
        self.stone.split_mode_beam(beam, cx, self.optics, w, sink);
    }
}

impl Stone {
    /// Trace one direction through a [`Medium`], handing every exit beam to `sink`: the
    /// singly refractive trace ([`Stone::trace_window_into`]) for [`Medium::Isotropic`], the
    /// birefringent one for [`Medium::Uniaxial`] (chosen here, once per trace).
    pub(crate) fn trace_medium_into<S: ExitSink>(
        &self,
        frame: &Frame,
        medium: &Medium,
        opts: &TraceOptions,
        sink: &mut S,
        keep_nodes: bool,
    ) -> (TraceStats, Vec<(u32, u32)>) {
        self.trace_medium_window_into(frame, medium, opts, &[], sink, keep_nodes)
    }

    /// [`Stone::trace_medium_into`] for the part of the cross-section inside `window`, as
    /// [`Stone::trace_window_into`] takes it (the photographs' perspective tiles).
    pub(crate) fn trace_medium_window_into<S: ExitSink>(
        &self,
        frame: &Frame,
        medium: &Medium,
        opts: &TraceOptions,
        window: &[DVec4],
        sink: &mut S,
        keep_nodes: bool,
    ) -> (TraceStats, Vec<(u32, u32)>) {
        match *medium {
            Medium::Isotropic(ri) => {
                self.trace_window_into(frame, ri, opts, window, sink, keep_nodes)
            }
            Medium::Uniaxial {
                crystal,
                alpha_o,
                alpha_e,
            } => {
                let clean = |x: f64| if x.is_finite() { x.max(0.0) } else { 0.0 };
                let (alpha_o, alpha_e) = (clean(alpha_o), clean(alpha_e));
                let optics = Optics {
                    crystal,
                    mode_floor: clean(opts.mode_floor),
                    alpha_o,
                    alpha_e,
                    absorbing: alpha_o > 0.0 || alpha_e > 0.0,
                };
                self.trace_crystal_into(frame, &optics, opts, window, sink, keep_nodes)
            }
        }
    }

    fn trace_crystal_into<S: ExitSink>(
        &self,
        frame: &Frame,
        optics: &Optics,
        opts: &TraceOptions,
        window: &[DVec4],
        sink: &mut S,
        keep_nodes: bool,
    ) -> (TraceStats, Vec<(u32, u32)>) {
        let cr = &optics.crystal;
        if !(cr.n_e.is_finite() && cr.n_e > 0.0 && cr.axis.is_finite()) {
            return (TraceStats::default(), Vec::new());
        }
        let tracer = Birefringent {
            stone: self,
            frame,
            optics,
        };
        let keeping = Some(cr.axis);
        self.trace_roots(
            &tracer, frame, cr.n_o, keeping, opts, window, sink, keep_nodes,
        )
    }

    /// The fate of a beam about to travel inside ([`Stone::settle`]; its footprint in
    /// `w.foot`): split exactly, followed as a narrow beam's ray (always when `narrow`: a
    /// merged pair of narrow beams), or cut off.
    fn continue_mode_beam<S: ExitSink>(
        &self,
        beam: Beam<InMode>,
        narrow: bool,
        cx: &Ctx,
        optics: &Optics,
        w: &mut Work<InMode>,
        sink: &mut S,
    ) {
        let Some((beam, c, _)) = self.settle(beam, narrow, cx, w) else {
            return;
        };
        let light = beam.light;
        let ray = ModeRay {
            x: c,
            wave: light.wave,
            power: light.power,
            alpha: light.alpha,
            tau: if optics.absorbing {
                beam.path.at(c)
            } else {
                0.0
            },
            facet: beam.facet,
            depth: beam.depth,
            node: beam.node,
            poly: 0,
        };
        self.follow_mode_ray(ray, beam.entry, cx, optics, w, sink);
    }

    /// Split one beam by the facets it reaches: at each, the light leaving is an exit beam
    /// and the light reflected goes on in each mode.
    fn split_mode_beam<S: ExitSink>(
        &self,
        beam: Beam<InMode>,
        cx: &Ctx,
        optics: &Optics,
        w: &mut Work<InMode>,
        sink: &mut S,
    ) {
        w.st.beams += 1;
        let light = beam.light;
        let t = light.wave.ray;
        let Some((e1, e2, sum)) = self.tile(beam.start, beam.len, t, beam.facet, w) else {
            w.st.cut_off += light.power;
            return;
        };
        let f = beam.facet as usize;
        let (nf, of) = (self.normals[f], self.offsets[f]);
        let map = beam.map.slide(t, nf, of);
        let tau = if optics.absorbing {
            beam.path.slide_weighted(t, nf, of, light.alpha)
        } else {
            beam.path
        };
        for ci in 0..w.children.len() {
            let ch = w.children[ci];
            let g = ch.facet as usize;
            let n = self.normals[g];
            w.lift(ch, e1, e2, t, n, self.offsets[g]);
            w.foot.clear();
            if cx.want_fp {
                w.foot.extend(w.cur.iter().map(|&x| map.apply(x)));
            }
            let node = w.node(cx, beam.node, g);
            let keep = if optics.absorbing {
                w.phi.clear();
                w.phi.extend(w.cur.iter().map(|&x| -tau.at(x)));
                exp_mean_planar(&w.cur, n, &w.phi)
            } else {
                1.0
            };
            let pc = light.power * (ch.area / sum);
            let Some(reflected) = self.cross_mode(
                &light.wave,
                g,
                pc,
                keep,
                (beam.entry, beam.depth, false, false, node),
                Place::Beam,
                cx,
                optics,
                w,
                sink,
            ) else {
                continue;
            };
            let merge = merged(&reflected.power, cx, optics);
            for (m, pr) in going_on(reflected.power, merge).into_iter().flatten() {
                let wave = reflected.meeting.wave(m);
                let next = Beam {
                    light: InMode {
                        wave,
                        power: pr,
                        alpha: optics.alpha(&wave),
                    },
                    facet: g as u32,
                    entry: beam.entry,
                    depth: beam.depth + 1,
                    node,
                    start: 0,
                    len: 0,
                    map,
                    path: tau,
                };
                self.continue_mode_beam(next, merge.is_some(), cx, optics, w, sink);
            }
        }
    }

    /// Light of power `p` in `wave` crossing facet `g`: the light leaving (times `keep`, the
    /// share left after absorption) handed to `sink` with footprint `w.foot`, and the
    /// reflected light of each mode returned (`None` when the crossing is not solved: its
    /// power is cut off).
    /// `origin` is (entry facet, reflections so far, narrow, late, node); the light leaves
    /// where `place` says: the exit's place ([`ExitSink::exit_at`]).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn cross_mode<S: ExitSink>(
        &self,
        wave: &Wave,
        g: usize,
        p: f64,
        keep: f64,
        origin: (u32, u32, bool, bool, u32),
        place: Place,
        cx: &Ctx,
        optics: &Optics,
        w: &mut Work<InMode>,
        sink: &mut S,
    ) -> Option<Reflected> {
        let (entry, depth, narrow, late, node) = origin;
        let Some(m) = optics.crystal.meet_raw(wave, self.normals[g]) else {
            w.st.cut_off += p;
            return None;
        };
        let scale = p / (m.reflected[0].2 + m.reflected[1].2 + m.exit_power);
        if m.exit_power > 0.0 {
            let unabsorbed = m.exit_power * scale;
            let power = unabsorbed * keep;
            w.st.absorbed += unabsorbed - power;
            let stokes = if cx.pol {
                m.exit * (scale * keep)
            } else {
                DVec4::new(power, 0.0, 0.0, 0.0)
            };
            let e = ExitBeam {
                direction: m.exit_dir,
                power,
                unabsorbed,
                stokes,
                axis: m.axis,
                entry_facet: entry as usize,
                exit_facet: g,
                reflections: depth,
                external: false,
                narrow,
                late,
                mode: Some(wave.mode),
                node,
                sym: 0,
            };
            w.st.exits += 1;
            match place {
                Place::Beam => sink.exit_at(&e, &w.foot, &w.cur),
                Place::Point(x) => sink.exit_at(&e, &w.foot, &[x]),
                Place::Polygon(start, n) => {
                    let (a, b) = (start as usize, (start + n) as usize);
                    sink.exit_at(&e, &w.foot, &w.mode_polys[a..b])
                }
            }
        }
        let power = m.reflected.map(|(_, _, r)| (r > 0.0).then_some(r * scale));
        Some(Reflected { meeting: m, power })
    }

    /// Follow a narrow beam as rays from `ray.x`: at each facet the light leaving is an exit
    /// beam with the narrow beam's footprint (`w.foot`), and each mode's reflected ray goes on
    /// until its power falls below the floor (the threshold, or the ray floor of the narrow
    /// beam's power) or past the depth limit, where it is cut off.
    fn follow_mode_ray<S: ExitSink>(
        &self,
        ray: ModeRay,
        entry: u32,
        cx: &Ctx,
        optics: &Optics,
        w: &mut Work<InMode>,
        sink: &mut S,
    ) {
        w.st.rays += 1;
        let p0 = ray.power;
        w.st.ray_power += p0;
        let floor = cx.threshold.max(cx.ray_floor * p0);
        w.mode_rays.clear();
        // The narrow beam's polygon (in `w.cur`, on its facet's plane), carried along each
        // ray when the sink wants it as the exit's place.
        let polys = sink.wants_exit_places() && sink.wants_narrow_polygons();
        let nv = w.cur.len() as u32;
        w.mode_polys.clear();
        if polys {
            w.mode_polys.extend_from_slice(&w.cur);
        }
        // The ray followed next: the ordinary reflected ray goes on at once, the
        // extraordinary one waits on the stack (the order a stack of both would give).
        let mut next = Some(ray);
        while let Some(r) = next.take().or_else(|| w.mode_rays.pop()) {
            let t = r.wave.ray;
            let Some((g, s)) = self.exit_facet(r.x, t, r.facet as usize) else {
                w.st.cut_off += r.power;
                continue;
            };
            let s = s.max(0.0);
            let x = r.x + t * s;
            let tau = r.tau + r.alpha * s;
            w.st.ray_segments += 1;
            let place = if polys {
                // Slid along the ray onto facet g's plane (unclipped).
                let (n, o) = (self.normals[g], self.offsets[g]);
                let cos = n.dot(t);
                let start = w.mode_polys.len() as u32;
                for k in r.poly..r.poly + nv {
                    let p = w.mode_polys[k as usize];
                    w.mode_polys.push(p + t * ((o - n.dot(p)) / cos));
                }
                Place::Polygon(start, nv)
            } else {
                Place::Point(x)
            };
            let node = w.node(cx, r.node, g);
            let keep = if optics.absorbing { (-tau).exp() } else { 1.0 };
            let origin = (entry, r.depth, true, r.power <= 0.5 * p0, node);
            let Some(reflected) = self.cross_mode(
                &r.wave, g, r.power, keep, origin, place, cx, optics, w, sink,
            ) else {
                continue;
            };
            let depth = r.depth + 1;
            // A mode too weak to be followed on its own stays with the other mode's ray (its
            // power added, its path that ray's): the ray's tree keeps at most 1/mode_floor
            // branches.
            let going = match reflected.power {
                [Some(a), Some(b)] if a.min(b) < optics.mode_floor * p0 => {
                    if a >= b {
                        [Some((0, a + b)), None]
                    } else {
                        [None, Some((1, a + b))]
                    }
                }
                [a, b] => [a.map(|p| (0, p)), b.map(|p| (1, p))],
            };
            // The extraordinary ray first: the ordinary one is followed first.
            for (m, pr) in going.into_iter().rev().flatten() {
                if pr.is_nan() || pr < floor || depth > cx.max_depth {
                    w.st.cut_off += pr.max(0.0);
                    if pr >= cx.threshold && depth <= cx.max_depth {
                        w.st.ray_closed += pr;
                    }
                    continue;
                }
                let wave = reflected.meeting.wave(m);
                let ray = ModeRay {
                    x,
                    wave,
                    power: pr,
                    alpha: optics.alpha(&wave),
                    tau,
                    facet: g as u32,
                    depth,
                    node,
                    poly: match place {
                        Place::Polygon(start, _) => start,
                        _ => 0,
                    },
                };
                if m == 0 {
                    next = Some(ray);
                } else {
                    w.mode_rays.push(ray);
                }
            }
        }
    }
}
