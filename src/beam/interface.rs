//! One internal interface crossing, shared by exact beams (`split_beam`) and narrow beams
//! followed as rays (`follow_ray`): the Stokes vector turned into the interface's s–p frame,
//! Fresnel's split, and the transmitted part handed out as an exit beam.

use super::exit::ExitBeam;
use super::sink::{ExitSink, TraceStats};
use super::work::Ctx;
use crate::optics::{fresnel, refract, rotate_stokes, s_axis, Interface, Stokes};
use glam::{DVec2, DVec3, DVec4};

/// Light inside the stone meeting facet `facet` (outward normal `n`) while travelling in
/// direction `t`, with Stokes vector `stokes` in the frame whose reference axis is `axis`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Meet {
    pub t: DVec3,
    pub n: DVec3,
    pub facet: usize,
    pub stokes: Stokes,
    pub axis: DVec3,
    /// Share of the light the transmitted part keeps after absorption on its way here (1
    /// when colourless).
    pub keep: f64,
}

/// What an exit beam leaving at a [`Meet`] records beyond the interface itself: where the
/// light entered, how often it was reflected inside, whether it is a narrow beam's, and its
/// node in the facet-sequence tree.
#[derive(Clone, Copy, Debug)]
pub(super) struct Origin {
    pub entry: usize,
    pub reflections: u32,
    pub narrow: bool,
    pub late: bool,
    pub node: u32,
}

/// Cross the interface at `m`: split by Fresnel (polarized or unpolarized as `cx` says), hand
/// the transmitted part to `sink` as an exit beam with footprint `foot` and its place on the
/// facet `place` (see [`ExitSink::exit_at`]; counted in `st.exits`), and return the reflected Stokes vector with its reference axis (the
/// interface's s axis when polarized). When Fresnel and Snell disagree (only at the critical
/// angle itself) the transmitted power is reflected instead, so power is conserved.
#[inline(always)]
pub(super) fn cross<S: ExitSink>(
    cx: &Ctx,
    m: Meet,
    o: Origin,
    foot: &[DVec2],
    place: &[DVec3],
    st: &mut TraceStats,
    sink: &mut S,
) -> (Stokes, DVec3) {
    let cos = m.n.dot(m.t);
    let fr = fresnel(cos, cx.ri, 1.0);
    let (axis, s_in) = if cx.pol {
        let a = s_axis(m.t, m.n).unwrap_or(m.axis);
        (a, rotate_stokes(m.stokes, m.axis, a, m.t))
    } else {
        (m.axis, m.stokes)
    };
    let (mut sr, mut stt) = split(cx.pol, &fr, s_in);
    if stt.x > 0.0 {
        match transmitted(m, cos, &fr, cx.ri) {
            Some(out) => {
                let unabsorbed = stt.x;
                if m.keep != 1.0 {
                    st.absorbed += stt.x * (1.0 - m.keep);
                    stt *= m.keep;
                }
                let e = ExitBeam {
                    direction: out,
                    power: stt.x,
                    unabsorbed,
                    stokes: stt,
                    axis,
                    entry_facet: o.entry,
                    exit_facet: m.facet,
                    reflections: o.reflections,
                    external: false,
                    narrow: o.narrow,
                    late: o.late,
                    mode: None,
                    node: o.node,
                    sym: 0,
                };
                st.exits += 1;
                sink.exit_at(&e, foot, place);
            }
            None => sr.x += stt.x,
        }
    }
    (sr, axis)
}

/// The direction of the light leaving at `m` into air: `refract(m.t, m.n, ri, 1)`, from the
/// cosines Fresnel's split `fr` already holds where it took the incidence cosine `cos` as it
/// is (`0 < cos ≤ 1`: the very same arithmetic, so the same bits), else by `refract`.
#[inline(always)]
fn transmitted(m: Meet, cos: f64, fr: &Interface, ri: f64) -> Option<DVec3> {
    if cos > 0.0 && cos <= 1.0 {
        if fr.tir {
            return None;
        }
        let eta = ri / 1.0;
        let n = -m.n;
        return Some(eta * m.t + (eta * fr.cos_i - fr.cos_t) * n);
    }
    refract(m.t, m.n, ri, 1.0)
}

/// Reflected and transmitted Stokes vectors for `s` given in the interface's s–p frame.
/// The transmitted intensity is `I − I_r`, so the split conserves power exactly.
#[inline]
pub(super) fn split(polarization: bool, f: &Interface, s: Stokes) -> (Stokes, Stokes) {
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
