//! The lanes of a chunk and the steps of a photon both kernels share (the singly refractive
//! one of `kernel.rs`, the birefringent one of `crystal.rs`): a photon's start where it
//! enters the stone, its way to the next facet (absorbed on the way or not), its exit and
//! its end. Each kernel adds its own interactions ([`Kernel`]).

use super::kernel::{chunk_seed, two_uniforms, Entry, Tracer};
use super::tally::{Counts, Fate, PhotonPath};
use crate::geometry::DVec3;
use rand::rngs::SmallRng;
use rand::SeedableRng;

/// Photons in flight per chunk (see `Tracer::lanes`): one per lane of the batched exit search.
const LANES: usize = super::solid::LANES;

/// One lane of a chunk, in either kernel: its random stream, the photons it has still to
/// shoot, and its photon in flight (what the kernel's photon carries beyond what both
/// kernels' do: `own`).
pub(super) struct Lane<M> {
    pub(super) rng: SmallRng,
    pub(super) left: u64,
    /// Whether a photon is inside the stone.
    pub(super) live: bool,
    pub(super) p: DVec3,
    /// Beer–Lambert coefficient (per girdle diameter) at the photon's wavelength, along its
    /// path.
    pub(super) beer: f64,
    pub(super) lambda: f64,
    /// Surface interactions so far.
    pub(super) inter: u32,
    /// The path's points (when recording).
    pub(super) path: Vec<DVec3>,
    pub(super) own: M,
}

/// One kernel's own steps: the singly refractive one in `kernel.rs`, the birefringent one in
/// `crystal.rs`. Both share the lanes ([`Tracer::lanes`]), a photon's start
/// ([`Tracer::enter`]), its way to the next facet ([`Tracer::advance`]) and its end.
pub(super) trait Kernel {
    /// What a photon carries beyond its place (its direction among it).
    type Own;
    /// A lane's own before its first photon.
    fn blank(&self) -> Self::Own;
    /// The photon's direction of travel.
    fn dir(own: &Self::Own) -> DVec3;
    /// Shoot the lane's next photons until one enters the stone (then do its first
    /// interaction) or the lane has none left or the hit limit is reached.
    fn start<const REC: bool>(
        &self,
        tr: &Tracer<'_>,
        l: &mut Lane<Self::Own>,
        k: &mut Counts,
        limit: u64,
        out: &mut Vec<PhotonPath>,
    );
    /// The lane's photon inside the stone meets its next facet (`j`, at distance `t`):
    /// absorbed on the way, or leaves, or is reflected back in (and is then depth-limited if
    /// it has no interactions left).
    fn bounce<const REC: bool>(
        &self,
        tr: &Tracer<'_>,
        l: &mut Lane<Self::Own>,
        t: f64,
        j: usize,
        k: &mut Counts,
        out: &mut Vec<PhotonPath>,
    );
}

impl Tracer<'_> {
    /// Trace chunk `c`'s `n` photons, `LANES` in flight at once. Lane `l` shoots its share of
    /// the chunk (`n / LANES`, one more for the first `n % LANES` lanes) from its own random
    /// stream, seeded from the seed, the chunk and the lane. Each round refills the lanes
    /// whose photon has ended (shooting until one is inside the stone), finds the exits of all
    /// the lanes' photons in one batched search and advances each by one surface interaction:
    /// the photons' long dependent chains (exit search, Fresnel, roulette) then overlap. With
    /// a hit limit no photon is shot once that many have hit (those in flight finish). With
    /// `REC`, the paths of finished photons that hit are pushed to `out` until it holds `want`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn lanes<K: Kernel, const REC: bool>(
        &self,
        kernel: &K,
        c: u64,
        n: u64,
        hit_limit: Option<u64>,
        k: &mut Counts,
        out: &mut Vec<PhotonPath>,
        want: usize,
    ) {
        let limit = hit_limit.unwrap_or(u64::MAX);
        let base = chunk_seed(self.seed, c);
        let mut lanes: [Lane<K::Own>; LANES] = std::array::from_fn(|l| {
            let l = l as u64;
            Lane {
                rng: SmallRng::seed_from_u64(chunk_seed(base, l)),
                left: n / LANES as u64 + u64::from(l < n % LANES as u64),
                live: false,
                p: DVec3::ZERO,
                beer: 0.0,
                lambda: 0.0,
                inter: 0,
                path: Vec::new(),
                own: kernel.blank(),
            }
        });
        loop {
            for l in lanes.iter_mut() {
                while !l.live && l.left > 0 {
                    kernel.start::<REC>(self, l, k, limit, out);
                }
            }
            let live = lanes.each_ref().map(|l| l.live);
            if !live.contains(&true) || (REC && out.len() >= want) {
                break;
            }
            let exits = self
                .s
                .exits_by(|l| (lanes[l].p, K::dir(&lanes[l].own)), &live);
            for (l, &(t, j)) in lanes.iter_mut().zip(&exits) {
                if l.live {
                    kernel.bounce::<REC>(self, l, t, j, k, out);
                }
            }
        }
    }

    /// A photon's start, in both kernels: shoot the lane's next photons until one enters
    /// the stone ([`Tracer::next_entry`]) and place it where it enters (its wavelength set,
    /// its path begun, its first interaction counted). The entry, for the kernel's own first
    /// interaction; `None`, the lane emptied, when it has none left or the hit limit is
    /// reached.
    #[inline(always)]
    pub(super) fn enter<M, const REC: bool>(
        &self,
        l: &mut Lane<M>,
        k: &mut Counts,
        limit: u64,
    ) -> Option<Entry> {
        let e = self.next_entry(&mut l.rng, &mut l.left, k, limit)?;
        l.lambda = e.lambda;
        l.p = e.o + e.t * e.d;
        if REC {
            l.path.clear();
            l.path.push(e.o);
            l.path.push(l.p);
        }
        l.inter = 1;
        Some(e)
    }

    /// The lane's photon travels along `d` to its next facet, at distance `t`, in both
    /// kernels: absorbed on the way, or there (one interaction more). The uniform of the
    /// facet's roulette, `None` when the photon has ended.
    #[inline(always)]
    pub(super) fn advance<M, const REC: bool>(
        &self,
        l: &mut Lane<M>,
        t: f64,
        d: DVec3,
        k: &mut Counts,
        out: &mut Vec<PhotonPath>,
    ) -> Option<f64> {
        if t >= f64::INFINITY || t.is_nan() {
            // Numerically impossible for a bounded solid; counted, never a panic.
            k.depth_limited += 1;
            self.finish::<M, REC>(l, k, Fate::DepthLimited, out);
            return None;
        }
        // One draw for the absorption and the surface's roulette.
        let (u, x) = two_uniforms(&mut l.rng);
        if let Some(s) = self.absorbed_within(u, t, l.beer) {
            k.absorbed += 1;
            if REC {
                l.path.push(l.p + s * d);
            }
            self.finish::<M, REC>(l, k, Fate::Absorbed, out);
            return None;
        }
        l.p += t * d;
        l.inter += 1;
        if REC {
            l.path.push(l.p);
        }
        Some(x)
    }

    /// The lane's photon leaves through facet `f` along `dir`, in both kernels.
    #[inline(always)]
    pub(super) fn exit<M, const REC: bool>(
        &self,
        l: &mut Lane<M>,
        k: &mut Counts,
        f: usize,
        dir: DVec3,
        out: &mut Vec<PhotonPath>,
    ) {
        self.tally_exit(k, f, dir);
        if REC {
            l.path.push(l.p + dir);
        }
        self.finish::<M, REC>(l, k, Fate::Exited(f), out);
    }

    /// The lane's photon, left inside by an interaction, ends depth-limited when it has no
    /// interactions left, in both kernels; whether it did.
    #[inline(always)]
    pub(super) fn depth_limited<M, const REC: bool>(
        &self,
        l: &mut Lane<M>,
        k: &mut Counts,
        out: &mut Vec<PhotonPath>,
    ) -> bool {
        if l.inter >= self.max_depth {
            k.depth_limited += 1;
            self.finish::<M, REC>(l, k, Fate::DepthLimited, out);
            true
        } else {
            false
        }
    }

    /// The lane's photon has ended with `fate`, in both kernels.
    #[inline(always)]
    pub(super) fn finish<M, const REC: bool>(
        &self,
        l: &mut Lane<M>,
        k: &mut Counts,
        fate: Fate,
        out: &mut Vec<PhotonPath>,
    ) {
        l.live = false;
        k.interactions += l.inter as u64;
        if REC {
            out.push(PhotonPath {
                wavelength: l.lambda,
                points: std::mem::take(&mut l.path),
                fate,
            });
        }
    }
}
