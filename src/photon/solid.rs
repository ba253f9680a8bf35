//! The stone in the layout the tracer's inner loops want: the facet planes as structure-of-
//! arrays (normals' x, y, z and offsets), padded to a multiple of [`LANES`] with planes that no
//! ray can leave through, so the exit search is a fixed-width, branch-free loop.

use crate::error::{Error, Result};
use crate::geometry::{DVec3, Polyhedron};

/// The face category (index into [`CATEGORY_KEYS`](super::CATEGORY_KEYS)) of a facet with
/// outward normal `n`: the angle θ between `n` and up in [0, 45), [45, 90], (90, 135],
/// (135, 180] degrees (snapped to 1e-9° so vertical girdle facets are 90° exactly).
pub fn face_category(n: DVec3) -> u8 {
    let th = n.z.clamp(-1.0, 1.0).acos().to_degrees();
    let th = (th * 1e9).round() / 1e9;
    if th < 45.0 {
        0
    } else if th <= 90.0 {
        1
    } else if th <= 135.0 {
        2
    } else {
        3
    }
}

/// Width of the padded facet arrays.
pub const LANES: usize = 8;

/// A convex stone prepared for photon tracing. Its arrays are the tracer's own (crate-private);
/// build one with [`TraceSolid::new`].
#[derive(Clone, Debug)]
pub struct TraceSolid {
    /// Facet count (without padding).
    pub(crate) facets: usize,
    /// Normal x components, padded with zeros.
    pub(crate) nx: Vec<f64>,
    /// Normal y components, padded with zeros.
    pub(crate) ny: Vec<f64>,
    /// Normal z components, padded with zeros.
    pub(crate) nz: Vec<f64>,
    /// Plane offsets, padded with ones.
    pub(crate) off: Vec<f64>,
    /// f32 copies for the fast exit search.
    pub(crate) f: [Vec<f32>; 4],
    /// Outward unit normals.
    pub(crate) normals: Vec<DVec3>,
    /// Face category (0: < 45°, 1: 45–90°, 2: 90–135°, 3: > 135° from up) of each facet.
    pub(crate) category: Vec<u8>,
    /// Facet names.
    pub(crate) names: Vec<String>,
    /// Facet tiers.
    pub(crate) tiers: Vec<String>,
    /// Vertices (for lights that cover the stone's shadow).
    pub(crate) vertices: Vec<DVec3>,
    /// Each facet's polygon as indices into `vertices`.
    pub(crate) facet_vertices: Vec<Vec<usize>>,
    /// Centre of the bounding sphere.
    pub(crate) centre: DVec3,
    /// Radius of the bounding sphere (slightly enlarged).
    pub(crate) radius: f64,
    /// Whether the CPU has AVX2 and FMA (checked once).
    pub(crate) avx2: bool,
}

impl TraceSolid {
    /// Facet count (without padding).
    pub fn facet_count(&self) -> usize {
        self.facets
    }

    /// Prepare `p` for tracing.
    pub fn new(p: &Polyhedron) -> Result<TraceSolid> {
        let n = p.facets().len();
        if n < 4 || p.vertices().is_empty() {
            return Err(Error::Geometry(
                "the solid has too few facets to trace".into(),
            ));
        }
        let padded = n.div_ceil(2 * LANES) * (2 * LANES);
        let mut nx = vec![0.0; padded];
        let mut ny = vec![0.0; padded];
        let mut nz = vec![0.0; padded];
        let mut off = vec![1.0; padded];
        for (i, f) in p.facets().iter().enumerate() {
            let m = f.plane.normal;
            if !(m.is_finite() && f.plane.offset.is_finite()) {
                return Err(Error::Geometry(format!(
                    "facet {} has a non-finite plane",
                    f.name
                )));
            }
            nx[i] = m.x;
            ny[i] = m.y;
            nz[i] = m.z;
            off[i] = f.plane.offset;
        }
        let (lo, hi) = p.bounding_box();
        let centre = 0.5 * (lo + hi);
        let radius = p
            .vertices()
            .iter()
            .map(|v| v.distance(centre))
            .fold(0.0, f64::max)
            * (1.0 + 1e-9)
            + 1e-12;
        // The f32 search works relative to the bounding-sphere centre (smaller numbers).
        let f = [
            nx.iter().map(|&v| v as f32).collect(),
            ny.iter().map(|&v| v as f32).collect(),
            nz.iter().map(|&v| v as f32).collect(),
            (0..padded)
                .map(|i| {
                    if i < n {
                        (off[i] - DVec3::new(nx[i], ny[i], nz[i]).dot(centre)) as f32
                    } else {
                        1.0
                    }
                })
                .collect(),
        ];
        Ok(TraceSolid {
            facets: n,
            nx,
            ny,
            nz,
            off,
            f,
            normals: p.facets().iter().map(|f| f.plane.normal).collect(),
            category: p
                .facets()
                .iter()
                .map(|f| face_category(f.plane.normal))
                .collect(),
            names: p.facets().iter().map(|f| f.name.clone()).collect(),
            tiers: p.facets().iter().map(|f| f.tier.clone()).collect(),
            vertices: p.vertices().to_vec(),
            facet_vertices: p.facets().iter().map(|f| f.vertices.clone()).collect(),
            centre,
            radius,
            avx2: has_avx2(),
        })
    }

    /// Where a ray from `p` (inside or on the solid) in unit direction `d` leaves it: the
    /// smallest `t = (offset − n·p)/(n·d)` over facets with `n·d > 0`, and that facet.
    ///
    /// The facet is chosen in f32 (8 facets at a time with AVX2 where the CPU has it, else
    /// the same arithmetic lane by lane, so both give the same facet); `t` is then computed in
    /// f64 on that facet's plane. Only rays within ~1e-6 D of an edge can pick the neighbour
    /// of the f64 choice, and they leave at (nearly) the same point.
    #[inline(always)]
    pub fn exit(&self, p: DVec3, d: DVec3) -> (f64, usize) {
        let q = p - self.centre;
        let pf = [q.x as f32, q.y as f32, q.z as f32];
        let df = [d.x as f32, d.y as f32, d.z as f32];
        #[cfg(target_arch = "x86_64")]
        let j = if self.avx2 {
            // SAFETY: AVX2 was detected at run time when this solid was built.
            unsafe { exit_index_avx2(&self.f, pf, df) }
        } else {
            exit_index_scalar(&self.f, pf, df)
        };
        #[cfg(not(target_arch = "x86_64"))]
        let j = exit_index_scalar(&self.f, pf, df);
        self.exit_on(p, d, j)
    }

    /// [`TraceSolid::exit`] for [`LANES`] rays `(p, d)` at once (those with `live` false are
    /// skipped: their result is meaningless). The same facets and distances as ray by ray:
    /// with AVX2 each lane of the f32 search is one ray, computing its `t`s with the same fused
    /// operations and keeping the first smallest, as the one-ray search does.
    #[cfg(test)]
    pub(crate) fn exits(
        &self,
        rays: &[(DVec3, DVec3); LANES],
        live: &[bool; LANES],
    ) -> [(f64, usize); LANES] {
        self.exits_by(|l| rays[l], live)
    }

    /// [`TraceSolid::exits`] with ray `l` given by `ray(l)` (read where it lies, not copied
    /// into an array first).
    #[inline(always)]
    pub(crate) fn exits_by(
        &self,
        ray: impl Fn(usize) -> (DVec3, DVec3),
        live: &[bool; LANES],
    ) -> [(f64, usize); LANES] {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            let mut pf = [[0f32; LANES]; 3];
            let mut df = [[0f32; LANES]; 3];
            for l in 0..LANES {
                let (p, d) = ray(l);
                let q = p - self.centre;
                for (k, (x, y)) in [(q.x, d.x), (q.y, d.y), (q.z, d.z)].into_iter().enumerate() {
                    pf[k][l] = x as f32;
                    df[k][l] = y as f32;
                }
            }
            // SAFETY: AVX2 was detected at run time when this solid was built.
            let js = unsafe { exit_index8_avx2(&self.f, self.facets, &pf, &df) };
            let mut out = [(f64::INFINITY, 0); LANES];
            for l in 0..LANES {
                if live[l] {
                    let (p, d) = ray(l);
                    out[l] = self.exit_on(p, d, js[l] as usize);
                }
            }
            return out;
        }
        std::array::from_fn(|l| {
            if live[l] {
                let (p, d) = ray(l);
                self.exit(p, d)
            } else {
                (f64::INFINITY, 0)
            }
        })
    }

    /// The exit by facet `j` the f32 search chose: `t` in f64 on its plane (or the f64 search
    /// when f64 finds the ray parallel to it).
    #[inline(always)]
    fn exit_on(&self, p: DVec3, d: DVec3, j: usize) -> (f64, usize) {
        let nd = self.nx[j] * d.x + self.ny[j] * d.y + self.nz[j] * d.z;
        let np = self.nx[j] * p.x + self.ny[j] * p.y + self.nz[j] * p.z;
        if nd > 0.0 {
            ((self.off[j] - np) / nd, j)
        } else {
            // f32 said "leaving", f64 says "parallel": fall back to the exact search.
            self.exit_f64(p, d)
        }
    }

    /// [`TraceSolid::exit`] entirely in f64 (the reference).
    pub fn exit_f64(&self, p: DVec3, d: DVec3) -> (f64, usize) {
        let mut best = [f64::INFINITY; LANES];
        let mut idx = [0usize; LANES];
        let chunks = self.nx.len() / LANES;
        for c in 0..chunks {
            let b = c * LANES;
            for l in 0..LANES {
                let i = b + l;
                let nd = self.nx[i] * d.x + self.ny[i] * d.y + self.nz[i] * d.z;
                let np = self.nx[i] * p.x + self.ny[i] * p.y + self.nz[i] * p.z;
                let t = if nd > 0.0 {
                    (self.off[i] - np) / nd
                } else {
                    f64::INFINITY
                };
                if t < best[l] {
                    best[l] = t;
                    idx[l] = i;
                }
            }
        }
        let mut bt = best[0];
        let mut bi = idx[0];
        for l in 1..LANES {
            if best[l] < bt || (best[l] == bt && idx[l] < bi) {
                bt = best[l];
                bi = idx[l];
            }
        }
        (bt, bi)
    }

    /// Where a ray from `o` (outside) in unit direction `d` enters the solid: `(t, facet)`,
    /// or `None` if it misses. Tests the bounding sphere first.
    #[inline]
    pub fn entry(&self, o: DVec3, d: DVec3) -> Option<(f64, usize)> {
        let oc = self.centre - o;
        let b = oc.dot(d);
        let r2 = self.radius * self.radius;
        let c2 = oc.length_squared();
        if c2 - b * b > r2 || (b < 0.0 && c2 > r2) {
            return None;
        }
        let mut t_in = f64::NEG_INFINITY;
        let mut f_in = usize::MAX;
        let mut t_out = f64::INFINITY;
        for i in 0..self.facets {
            let nd = self.nx[i] * d.x + self.ny[i] * d.y + self.nz[i] * d.z;
            let num = self.off[i] - (self.nx[i] * o.x + self.ny[i] * o.y + self.nz[i] * o.z);
            if nd < 0.0 {
                let t = num / nd;
                if t > t_in {
                    t_in = t;
                    f_in = i;
                }
            } else if nd > 0.0 {
                t_out = t_out.min(num / nd);
            } else if num < 0.0 {
                return None;
            }
        }
        if f_in == usize::MAX || t_in > t_out || t_in < 0.0 {
            return None;
        }
        Some((t_in, f_in))
    }
}

fn has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// The f32 time to facet `i`'s plane, or infinity when the ray does not move toward it.
#[inline(always)]
fn t32(f: &[Vec<f32>; 4], i: usize, p: [f32; 3], d: [f32; 3]) -> f32 {
    let nd = f[0][i].mul_add(d[0], f[1][i].mul_add(d[1], f[2][i] * d[2]));
    let np = f[0][i].mul_add(p[0], f[1][i].mul_add(p[1], f[2][i] * p[2]));
    let t = (f[3][i] - np) / nd;
    if nd > 0.0 {
        t
    } else {
        f32::INFINITY
    }
}

/// The f32 exit search, one facet at a time: the facet with the smallest `t` (the first on
/// ties). [`exit_index_avx2`] computes the same `t`s (same fused operations) and gives the
/// same facet.
fn exit_index_scalar(f: &[Vec<f32>; 4], p: [f32; 3], d: [f32; 3]) -> usize {
    let mut best = f32::INFINITY;
    let mut idx = 0;
    for i in 0..f[0].len() {
        let t = t32(f, i, p, d);
        if t < best {
            best = t;
            idx = i;
        }
    }
    idx
}

/// The f32 exit search of [`LANES`] rays at once, one ray per lane (positions relative to the
/// centre and directions, coordinate by coordinate), over the first `n` facets: each lane's
/// facet is [`exit_index_scalar`]'s for its ray. Facets go in two independent chains (even
/// and odd); each keeps its first smallest `t`, and the two are merged to the smaller `t`,
/// the smaller facet on ties.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
#[inline]
unsafe fn exit_index8_avx2(
    f: &[Vec<f32>; 4],
    n: usize,
    p: &[[f32; LANES]; 3],
    d: &[[f32; LANES]; 3],
) -> [i32; LANES] {
    use std::arch::x86_64::*;
    // The padded arrays hold whole pairs of facets.
    let n = n.next_multiple_of(2);
    let pairs = |k: usize| f[k][..n].as_chunks::<2>().0;
    // SAFETY: each array holds LANES f32s.
    let ([px, py, pz], [dx, dy, dz]) = unsafe {
        (
            p.map(|v| _mm256_loadu_ps(v.as_ptr())),
            d.map(|v| _mm256_loadu_ps(v.as_ptr())),
        )
    };
    let inf = _mm256_set1_ps(f32::INFINITY);
    let zero = _mm256_setzero_ps();
    let t_of = |x: f32, y: f32, z: f32, o: f32| {
        let (nx, ny, nz, off) = (
            _mm256_set1_ps(x),
            _mm256_set1_ps(y),
            _mm256_set1_ps(z),
            _mm256_set1_ps(o),
        );
        let nd = _mm256_fmadd_ps(nx, dx, _mm256_fmadd_ps(ny, dy, _mm256_mul_ps(nz, dz)));
        let np = _mm256_fmadd_ps(nx, px, _mm256_fmadd_ps(ny, py, _mm256_mul_ps(nz, pz)));
        let t = _mm256_div_ps(_mm256_sub_ps(off, np), nd);
        _mm256_blendv_ps(inf, t, _mm256_cmp_ps(nd, zero, _CMP_GT_OQ))
    };
    let keep = |t: __m256, i: usize, best: &mut __m256, idx: &mut __m256i| {
        let lt = _mm256_cmp_ps(t, *best, _CMP_LT_OQ);
        *best = _mm256_blendv_ps(*best, t, lt);
        *idx = _mm256_castps_si256(_mm256_blendv_ps(
            _mm256_castsi256_ps(*idx),
            _mm256_castsi256_ps(_mm256_set1_epi32(i as i32)),
            lt,
        ));
    };
    let (mut b0, mut b1) = (inf, inf);
    let (mut i0, mut i1) = (_mm256_setzero_si256(), _mm256_setzero_si256());
    let (fx, fy, fz, fo) = (pairs(0), pairs(1), pairs(2), pairs(3));
    for (k, (((x, y), z), o)) in fx.iter().zip(fy).zip(fz).zip(fo).enumerate() {
        keep(t_of(x[0], y[0], z[0], o[0]), 2 * k, &mut b0, &mut i0);
        keep(t_of(x[1], y[1], z[1], o[1]), 2 * k + 1, &mut b1, &mut i1);
    }
    // The odd chain wins where its t is smaller, or equal with a smaller facet (it holds
    // facet 0 only while it found nothing, where the even chain's facet is the answer).
    let smaller = _mm256_cmp_ps(b1, b0, _CMP_LT_OQ);
    let tie = _mm256_and_ps(
        _mm256_cmp_ps(b1, b0, _CMP_EQ_OQ),
        _mm256_castsi256_ps(_mm256_cmpgt_epi32(i0, i1)),
    );
    let i = _mm256_castps_si256(_mm256_blendv_ps(
        _mm256_castsi256_ps(i0),
        _mm256_castsi256_ps(i1),
        _mm256_or_ps(smaller, tie),
    ));
    let mut out = [0i32; LANES];
    // SAFETY: out holds LANES i32s.
    unsafe { _mm256_storeu_si256(out.as_mut_ptr() as *mut __m256i, i) };
    out
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
#[inline]
unsafe fn exit_index_avx2(f: &[Vec<f32>; 4], p: [f32; 3], d: [f32; 3]) -> usize {
    use std::arch::x86_64::*;
    let n = f[0].len();
    let (dx, dy, dz) = (
        _mm256_set1_ps(d[0]),
        _mm256_set1_ps(d[1]),
        _mm256_set1_ps(d[2]),
    );
    let (px, py, pz) = (
        _mm256_set1_ps(p[0]),
        _mm256_set1_ps(p[1]),
        _mm256_set1_ps(p[2]),
    );
    let inf = _mm256_set1_ps(f32::INFINITY);
    let zero = _mm256_setzero_ps();
    let step = _mm256_set1_epi32(2 * LANES as i32);
    // Two independent (best, index) accumulators: even and odd blocks of 8 facets.
    let mut best = [inf, inf];
    let mut bidx = [_mm256_setzero_si256(), _mm256_setzero_si256()];
    let mut idx = [
        _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7),
        _mm256_setr_epi32(8, 9, 10, 11, 12, 13, 14, 15),
    ];
    let mut b = 0;
    while b < n {
        for k in 0..2 {
            let o = b + k * LANES;
            // SAFETY: every array has length n, a multiple of 2·LANES, and o + 8 <= n.
            let (nx, ny, nz, off) = unsafe {
                (
                    _mm256_loadu_ps(f[0].as_ptr().add(o)),
                    _mm256_loadu_ps(f[1].as_ptr().add(o)),
                    _mm256_loadu_ps(f[2].as_ptr().add(o)),
                    _mm256_loadu_ps(f[3].as_ptr().add(o)),
                )
            };
            let nd = _mm256_fmadd_ps(nx, dx, _mm256_fmadd_ps(ny, dy, _mm256_mul_ps(nz, dz)));
            let np = _mm256_fmadd_ps(nx, px, _mm256_fmadd_ps(ny, py, _mm256_mul_ps(nz, pz)));
            let t = _mm256_div_ps(_mm256_sub_ps(off, np), nd);
            let t = _mm256_blendv_ps(inf, t, _mm256_cmp_ps(nd, zero, _CMP_GT_OQ));
            let lt = _mm256_cmp_ps(t, best[k], _CMP_LT_OQ);
            best[k] = _mm256_blendv_ps(best[k], t, lt);
            bidx[k] = _mm256_castps_si256(_mm256_blendv_ps(
                _mm256_castsi256_ps(bidx[k]),
                _mm256_castsi256_ps(idx[k]),
                lt,
            ));
            idx[k] = _mm256_add_epi32(idx[k], step);
        }
        b += 2 * LANES;
    }
    // Branch-free reduction: the smallest t over all 16 lanes, then the smallest index
    // among the lanes holding it.
    let m = _mm256_min_ps(best[0], best[1]);
    let m = _mm256_min_ps(m, _mm256_permute2f128_ps(m, m, 1));
    let m = _mm256_min_ps(m, _mm256_shuffle_ps(m, m, 0b01_00_11_10));
    let m = _mm256_min_ps(m, _mm256_shuffle_ps(m, m, 0b10_11_00_01));
    let none = _mm256_set1_epi32(i32::MAX);
    let pick = |b: __m256, i: __m256i| {
        _mm256_castps_si256(_mm256_blendv_ps(
            _mm256_castsi256_ps(none),
            _mm256_castsi256_ps(i),
            _mm256_cmp_ps(b, m, _CMP_EQ_OQ),
        ))
    };
    let i = _mm256_min_epi32(pick(best[0], bidx[0]), pick(best[1], bidx[1]));
    let i = _mm256_min_epi32(i, _mm256_permute2x128_si256(i, i, 1));
    let i = _mm256_min_epi32(i, _mm256_shuffle_epi32(i, 0b01_00_11_10));
    let i = _mm256_min_epi32(i, _mm256_shuffle_epi32(i, 0b10_11_00_01));
    let i = _mm256_cvtsi256_si32(i);
    if i == i32::MAX {
        // Every t is NaN (a NaN direction): the scalar search says facet 0.
        0
    } else {
        i as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::SmallRng;
    use rand::{Rng, SeedableRng};

    fn random_dir(rng: &mut SmallRng) -> DVec3 {
        loop {
            let v = DVec3::new(
                rng.random::<f64>() * 2.0 - 1.0,
                rng.random::<f64>() * 2.0 - 1.0,
                rng.random::<f64>() * 2.0 - 1.0,
            );
            if v.length_squared() > 1e-3 && v.length_squared() <= 1.0 {
                return v.normalize();
            }
        }
    }

    #[test]
    fn fast_exit_search_matches_the_f64_reference() {
        let cut = crate::io::load_cut("tolkowsky").unwrap();
        let s = TraceSolid::new(&cut.solid).unwrap();
        let mut rng = SmallRng::seed_from_u64(3);
        let mut differ = 0;
        for _ in 0..20_000 {
            // A point on a random facet's plane inside the stone, moving inward or along.
            let p = s.centre + 0.3 * random_dir(&mut rng) * rng.random::<f64>();
            let d = random_dir(&mut rng);
            let (t, j) = s.exit(p, d);
            let (t64, j64) = s.exit_f64(p, d);
            assert!((t - t64).abs() < 1e-5, "{t} vs {t64}");
            differ += (j != j64) as u32;
            let pf = {
                let q = p - s.centre;
                [q.x as f32, q.y as f32, q.z as f32]
            };
            let df = [d.x as f32, d.y as f32, d.z as f32];
            let scalar = exit_index_scalar(&s.f, pf, df);
            #[cfg(target_arch = "x86_64")]
            if s.avx2 {
                // SAFETY: AVX2 and FMA detected.
                assert_eq!(scalar, unsafe { exit_index_avx2(&s.f, pf, df) });
            }
            assert_eq!(scalar, j);
        }
        assert!(differ <= 2, "{differ} exits chose another facet than f64");
    }

    /// The batched search gives every live lane the one-ray search's facet and distance, to
    /// the bit, whatever the other lanes hold.
    #[test]
    fn exits_of_eight_rays_are_those_of_each_ray() {
        let cut = crate::io::load_cut("tolkowsky").unwrap();
        let s = TraceSolid::new(&cut.solid).unwrap();
        let mut rng = SmallRng::seed_from_u64(4);
        for round in 0..5_000 {
            let rays: [(DVec3, DVec3); LANES] = std::array::from_fn(|_| {
                let p = s.centre + 0.3 * random_dir(&mut rng) * rng.random::<f64>();
                (p, random_dir(&mut rng))
            });
            let live: [bool; LANES] = std::array::from_fn(|l| round % 7 != l);
            let got = s.exits(&rays, &live);
            for l in 0..LANES {
                if live[l] {
                    let (t, j) = s.exit(rays[l].0, rays[l].1);
                    assert_eq!((got[l].0.to_bits(), got[l].1), (t.to_bits(), j));
                }
            }
        }
    }

    #[test]
    fn entry_finds_the_facet_facing_the_ray() {
        let cut = crate::io::load_cut("tolkowsky").unwrap();
        let s = TraceSolid::new(&cut.solid).unwrap();
        let (t, f) = s.entry(DVec3::new(0.01, 0.02, 3.0), DVec3::NEG_Z).unwrap();
        assert_eq!(cut.solid.facets()[f].tier, "table");
        assert!((3.0 - t - cut.solid.bounding_box().1.z).abs() < 1e-12);
        assert!(s.entry(DVec3::new(0.8, 0.0, 3.0), DVec3::NEG_Z).is_none());
        assert!(s.entry(DVec3::new(0.0, 0.0, 3.0), DVec3::Z).is_none());
    }
}
