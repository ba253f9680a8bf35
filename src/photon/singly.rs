//! The singly refractive kernel of the photon tracer ([`Singly`]): a photon's direction,
//! index and polarization through the lanes of `lanes.rs`, its interfaces
//! ([`Tracer::interface`]) in `kernel.rs`.

use super::kernel::{Pol, Tracer};
use super::lanes::{Kernel, Lane};
use super::tally::{Counts, PhotonPath};
use crate::geometry::DVec3;
use crate::optics::Stokes;

/// The singly refractive kernel, with polarization when `POL`.
pub(super) struct Singly<const POL: bool>;

/// A singly refractive photon's own: its direction, the refractive index at its wavelength
/// and its polarization.
pub(super) struct Ray {
    d: DVec3,
    n: f64,
    pol: Pol,
}

impl<const POL: bool> Kernel for Singly<POL> {
    type Own = Ray;

    #[inline(always)]
    fn blank(&self) -> Ray {
        Ray {
            d: DVec3::ZERO,
            n: 1.0,
            pol: Pol {
                s: Stokes::new(1.0, 0.0, 0.0, 0.0),
                e: DVec3::X,
            },
        }
    }

    #[inline(always)]
    fn dir(own: &Ray) -> DVec3 {
        own.d
    }

    #[inline(always)]
    fn start<const REC: bool>(
        &self,
        tr: &Tracer<'_>,
        l: &mut Lane<Ray>,
        k: &mut Counts,
        limit: u64,
        out: &mut Vec<PhotonPath>,
    ) {
        let Some(e) = tr.enter::<Ray, REC>(l, k, limit) else {
            return;
        };
        let (d, f) = (e.d, e.f);
        l.own.n = tr.fixed_n.unwrap_or_else(|| tr.material.ri(e.lambda));
        // Beer–Lambert coefficient per unit of path at this photon's wavelength (0 unless the
        // model is Beer–Lambert).
        l.beer = tr
            .absorption
            .beer_per_width(tr.material.colour.as_ref(), e.lambda)
            .unwrap_or(0.0);
        if POL {
            l.own.pol = Pol {
                s: Stokes::new(1.0, 0.0, 0.0, 0.0),
                e: d.any_orthonormal_vector(),
            };
        }
        let m = tr.s.normals[f];
        let (nd, transmitted) = tr.interface::<POL>(e.x, &mut l.own.pol, d, m, 1.0, l.own.n);
        l.own.d = nd;
        if !transmitted {
            tr.exit::<Ray, REC>(l, k, f, nd, out);
        } else if !tr.depth_limited::<Ray, REC>(l, k, out) {
            l.live = true;
        }
    }

    #[inline(always)]
    fn bounce<const REC: bool>(
        &self,
        tr: &Tracer<'_>,
        l: &mut Lane<Ray>,
        t: f64,
        j: usize,
        k: &mut Counts,
        out: &mut Vec<PhotonPath>,
    ) {
        let d = l.own.d;
        let Some(x) = tr.advance::<Ray, REC>(l, t, d, k, out) else {
            return;
        };
        let m = tr.s.normals[j];
        let (nd, transmitted) = tr.interface::<POL>(x, &mut l.own.pol, d, -m, l.own.n, 1.0);
        l.own.d = nd;
        if transmitted {
            tr.exit::<Ray, REC>(l, k, j, nd, out);
        } else {
            tr.depth_limited::<Ray, REC>(l, k, out);
        }
    }
}
