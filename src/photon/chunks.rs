//! The choice of kernel for a chunk of photons: the birefringent one (`crystal.rs`) for a
//! crystal, else the singly refractive one (`singly.rs`) with or without polarization, each
//! run through the lanes of `lanes.rs`.

use super::config::CHUNK;
use super::crystal::Birefringent;
use super::kernel::Tracer;
use super::singly::Singly;
use super::tally::{Counts, PhotonPath};

impl Tracer<'_> {
    /// Trace chunk `c` of `n` photons; with `hit_limit`, stop after that many hits.
    pub(crate) fn chunk(&self, c: u64, n: u64, hit_limit: Option<u64>) -> Counts {
        #[cfg(target_arch = "x86_64")]
        if self.s.avx2 {
            // SAFETY: AVX2 and FMA were detected at run time.
            return unsafe { self.chunk_avx2(c, n, hit_limit) };
        }
        self.chunk_impl(c, n, hit_limit)
    }

    /// [`Tracer::chunk`] compiled for AVX2 (the same arithmetic: Rust never fuses or
    /// reorders floating-point operations on its own, so the numbers do not change).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    unsafe fn chunk_avx2(&self, c: u64, n: u64, hit_limit: Option<u64>) -> Counts {
        self.chunk_impl(c, n, hit_limit)
    }

    #[inline(always)]
    fn chunk_impl(&self, c: u64, n: u64, hit_limit: Option<u64>) -> Counts {
        let mut k = Counts::new(self.s.facets);
        let mut none = Vec::new();
        if let Some(cs) = &self.crystal {
            let kernel = Birefringent(cs);
            self.lanes::<_, false>(&kernel, c, n, hit_limit, &mut k, &mut none, 0);
        } else if self.polarization {
            self.lanes::<_, false>(&Singly::<true>, c, n, hit_limit, &mut k, &mut none, 0);
        } else {
            self.lanes::<_, false>(&Singly::<false>, c, n, hit_limit, &mut k, &mut none, 0);
        }
        k
    }

    /// Replay the run's chunks in order (`shot` photons in all; `until_hit`: the run shot until
    /// that many hit, so each chunk is replayed with the same hit limit) and record the paths
    /// of the first `n` photons that hit the stone, in the order they finished.
    pub(crate) fn record_paths(
        &self,
        n: usize,
        shot: u64,
        until_hit: Option<u64>,
    ) -> Vec<PhotonPath> {
        let mut out = Vec::new();
        let (mut done, mut hit, mut c) = (0u64, 0u64, 0u64);
        while done < shot && out.len() < n {
            let (photons, limit) = match until_hit {
                Some(h) => (CHUNK, Some(h - hit)),
                None => (CHUNK.min(shot - done), None),
            };
            let mut k = Counts::new(self.s.facets);
            let (k, out) = (&mut k, &mut out);
            if let Some(cs) = &self.crystal {
                self.lanes::<_, true>(&Birefringent(cs), c, photons, limit, k, out, n);
            } else if self.polarization {
                self.lanes::<_, true>(&Singly::<true>, c, photons, limit, k, out, n);
            } else {
                self.lanes::<_, true>(&Singly::<false>, c, photons, limit, k, out, n);
            }
            done += k.shot;
            hit += k.hit;
            c += 1;
        }
        out.truncate(n);
        out
    }
}
