//! Check 1: the renderer against an independent brute-force backward ray tracer written here.

use super::opts;
use crate::geometry::canonical::canonical;
use crate::geometry::Polyhedron;
use crate::optics::Material;
use crate::render::lighting::Lighting;
use crate::render::{render, Light, Tilt};
use glam::{DMat3, DVec3};
use rayon::prelude::*;
use std::time::Instant;

// ---------------------------------------------------------------------------------------------
// The brute-force tracer.
// ---------------------------------------------------------------------------------------------

/// Lights the brute-force tracer shades every exit with, and their channels' places in its
/// per-pixel value array (iso: 0, cos: 1, aset: 2..7).
const LIGHTS: [Light; 3] = [Light::Iso, Light::Cos, Light::Aset];
/// Number of values per pixel: 1 (iso) + 1 (cos) + 5 (aset), and last the weight left when
/// a sight line's trace stops (below [`MIN_WEIGHT`] or at [`MAX_DEPTH`]).
const NV: usize = 8;
/// Index of the weight cut off in a pixel's values.
const CUT: usize = 7;
/// Offset of `light`'s first channel in a pixel's values.
fn channel_offset(light: Light) -> usize {
    match light {
        Light::Iso => 0,
        Light::Cos => 1,
        Light::Aset => 2,
        _ => unreachable!("not traced by the brute-force tracer"),
    }
}

/// Branches lighter than this (relative to the sight line) are dropped.
const MIN_WEIGHT: f64 = 1e-7;
/// Largest number of internal interface hits followed per sight line (the renderer's
/// `max_depth`: light trapped by total internal reflection circles long before it leaks).
const MAX_DEPTH: usize = 1000;

/// Unpolarized Fresnel reflectance `(Rs + Rp)/2` from index `n1` into `n2` at an angle of
/// incidence with cosine `cos_i` (≥ 0), and the cosine of the refraction angle; total internal
/// reflection (and grazing incidence) gives `(1, 0)`.
fn reflectance(n1: f64, n2: f64, cos_i: f64) -> (f64, f64) {
    let eta = n1 / n2;
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 || cos_i <= 0.0 {
        return (1.0, 0.0);
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    (0.5 * (rs * rs + rp * rp), cos_t)
}

/// Mirror `d` in the plane of unit normal `n`.
fn reflect(d: DVec3, n: DVec3) -> DVec3 {
    d - 2.0 * d.dot(n) * n
}

/// Snell: refract unit `d` through an interface whose unit normal `toward` points back to the
/// side `d` comes from (`toward · d = −cos_i < 0`), with `eta = n_from / n_to` and the
/// refraction angle's cosine `cos_t`.
fn refract(d: DVec3, toward: DVec3, eta: f64, cos_i: f64, cos_t: f64) -> DVec3 {
    (eta * d + (eta * cos_i - cos_t) * toward).normalize()
}

/// Sight lines of a pixel's first grid that differ by no more than this in every channel
/// agree: the pixel is not refined. (Deep, faint branches split almost everywhere; only
/// differences that can move the pixel's mean noticeably call for the finer grid.)
const AGREE: f64 = 1e-3;

/// A deterministic small generator (64-bit LCG, top 53 bits), seeded per pixel.
struct Lcg(u64);

impl Lcg {
    fn new(seed: u64) -> Lcg {
        let mut g = Lcg(seed
            .wrapping_mul(0x9E37_79B9_7F4A_7C15)
            .wrapping_add(0xD1B5_4A32_D192_ED03));
        g.next();
        g.next();
        g
    }

    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A brute-force backward tracer of one pose of one canonical solid.
struct Brute {
    /// Facet planes (outward unit normal, offset) of the canonical solid.
    planes: Vec<(DVec3, f64)>,
    /// Refractive index of the stone.
    n: f64,
    /// Stone → world rotation.
    rot: DMat3,
    /// Viewing direction (stone coordinates) and the picture's right and up.
    dir: DVec3,
    u: DVec3,
    v: DVec3,
    /// Half the side of the picture square.
    half: f64,
    /// The lights' radiance functions, in the order of [`LIGHTS`].
    lightings: Vec<Lighting>,
}

impl Brute {
    /// The tracer of `solid` (put in canonical placement, as the renderer does) in pose
    /// `tilt`, with the frame and picture square recomputed from the renderer's definitions.
    fn new(solid: &Polyhedron, tilt: Tilt, n: f64) -> Brute {
        let solid = canonical(solid);
        let rot = tilt.rotation();
        // The viewer looks down the world's −z; the picture's right and up are the world's x
        // and y, all taken to stone coordinates by the inverse (transposed) rotation.
        let (dir, u, v) = (
            rot.transpose() * DVec3::NEG_Z,
            rot.transpose() * DVec3::X,
            rot.transpose() * DVec3::Y,
        );
        // The picture spans the canonical stone's largest radius + 0.1 % (`picture_half`).
        let half = 1.001
            * solid
                .vertices()
                .iter()
                .map(|p| p.length())
                .fold(0.0, f64::max);
        let lightings = LIGHTS
            .iter()
            .map(|l| Lighting::new(l.default_head_shadow_deg(), &[]))
            .collect();
        Brute {
            planes: solid
                .facets()
                .iter()
                .map(|f| (f.plane.normal, f.plane.offset))
                .collect(),
            n,
            rot,
            dir,
            u,
            v,
            half,
            lightings,
        }
    }

    /// Add `weight` × every light's channels for light leaving the stone along `w` (stone
    /// coordinates).
    fn add(&self, acc: &mut [f64; NV], weight: f64, w: DVec3) {
        let w = self.rot * w;
        for (l, lt) in LIGHTS.iter().zip(&self.lightings) {
            let (s, _) = l.shade(lt, w);
            let o = channel_offset(*l);
            for c in 0..l.channels() {
                acc[o + c] += weight * s[c];
            }
        }
    }

    /// Trace the sight line from `o` along unit `d` backwards through the stone, splitting at
    /// every interface, and add what leaves to `acc`. A sight line that misses adds nothing.
    fn trace(&self, o: DVec3, d: DVec3, acc: &mut [f64; NV]) {
        // Entry: the slab intersection of the half-spaces; the ray enters through the plane
        // it crosses last on the way in.
        let (mut t0, mut t1, mut entry) = (f64::NEG_INFINITY, f64::INFINITY, usize::MAX);
        for (k, &(nrm, off)) in self.planes.iter().enumerate() {
            let nd = nrm.dot(d);
            let s = off - nrm.dot(o);
            if nd < 0.0 {
                let t = s / nd;
                if t > t0 {
                    t0 = t;
                    entry = k;
                }
            } else if nd > 0.0 {
                t1 = t1.min(s / nd);
            } else if s < 0.0 {
                return;
            }
        }
        if entry == usize::MAX || t0 >= t1 {
            return;
        }
        let nrm = self.planes[entry].0;
        let cos_i = -nrm.dot(d);
        let (r, cos_t) = reflectance(1.0, self.n, cos_i);
        // External reflection leaves at once (a convex solid cannot be hit again).
        if r > 0.0 {
            self.add(acc, r, reflect(d, nrm));
        }
        if r >= 1.0 {
            return;
        }
        let mut w = 1.0 - r;
        let mut p = o + d * t0;
        let mut d = refract(d, nrm, 1.0 / self.n, cos_i, cos_t);
        for _ in 0..MAX_DEPTH {
            if w < MIN_WEIGHT {
                break;
            }
            // Inside a convex solid the ray leaves through the plane with n·d > 0 it meets
            // first.
            let (mut best, mut k) = (f64::INFINITY, usize::MAX);
            for (j, &(nrm, off)) in self.planes.iter().enumerate() {
                let nd = nrm.dot(d);
                if nd > 0.0 {
                    let t = (off - nrm.dot(p)) / nd;
                    if t < best {
                        best = t;
                        k = j;
                    }
                }
            }
            if k == usize::MAX {
                break;
            }
            p += d * best.max(0.0);
            let nrm = self.planes[k].0;
            let cos_i = nrm.dot(d);
            let (r, cos_t) = reflectance(self.n, 1.0, cos_i);
            if r < 1.0 {
                self.add(acc, w * (1.0 - r), refract(d, -nrm, self.n, cos_i, cos_t));
            }
            w *= r;
            d = reflect(d, nrm);
        }
        acc[CUT] += w;
    }

    /// The mean over an `m`×`m` jittered grid of sight lines across pixel (`col`, `row`) of
    /// every light's channels, and whether all sight lines agreed (within [`AGREE`]).
    fn grid(&self, col: usize, row: usize, size: usize, m: usize, seed: u64) -> ([f64; NV], bool) {
        let h = 2.0 * self.half / size as f64;
        let mut g = Lcg::new(seed);
        let mut acc = [0.0; NV];
        let mut first = None;
        let mut uniform = true;
        for a in 0..m {
            for b in 0..m {
                let x = -self.half + h * (col as f64 + (a as f64 + g.next()) / m as f64);
                let y = -self.half + h * (row as f64 + (b as f64 + g.next()) / m as f64);
                let o = self.u * x + self.v * y - self.dir * 10.0;
                let mut one = [0.0; NV];
                self.trace(o, self.dir, &mut one);
                match first {
                    None => first = Some(one),
                    Some(f) => uniform &= f.iter().zip(&one).all(|(p, q)| (p - q).abs() <= AGREE),
                }
                for (s, v) in acc.iter_mut().zip(one) {
                    *s += v;
                }
            }
        }
        (acc.map(|x| x / (m * m) as f64), uniform)
    }

    /// The picture at `size`² pixels: per pixel (row 0 at the bottom, as `Raster::data`) the
    /// mean of every light's channels over an `m`×`m` jittered grid of sight lines, or over a
    /// finer `fine`×`fine` grid (a fresh one) where the first grid's sight lines do not all
    /// agree (pixels an edge of the picture crosses).
    fn image(&self, size: usize, m: usize, fine: usize) -> Vec<[f64; NV]> {
        (0..size)
            .into_par_iter()
            .flat_map_iter(|row| {
                (0..size).map(move |col| {
                    let k = (row * size + col) as u64;
                    let (v, uniform) = self.grid(col, row, size, m, k);
                    if uniform || fine <= m {
                        v
                    } else {
                        self.grid(col, row, size, fine, k ^ 0x5555_5555_0000_0000).0
                    }
                })
            })
            .collect()
    }
}

// ---------------------------------------------------------------------------------------------
// 1. The renderer against the brute-force tracer.
// ---------------------------------------------------------------------------------------------

/// Mean absolute difference over the pixels covered by the stone, mean absolute difference
/// over all pixels, and the difference of the image means (renderer − brute force).
fn compare(got: &[f64], want: &[f64], coverage: &[f64]) -> (f64, f64, f64) {
    let n = got.len() as f64;
    let (mut abs_in, mut cnt_in, mut abs_all, mut diff) = (0.0, 0usize, 0.0, 0.0);
    for ((g, w), c) in got.iter().zip(want).zip(coverage) {
        let e = (g - w).abs();
        abs_all += e;
        diff += g - w;
        if *c > 0.0 {
            abs_in += e;
            cnt_in += 1;
        }
    }
    (abs_in / cnt_in.max(1) as f64, abs_all / n, diff / n)
}

#[test]
fn render_matches_brute_force_ray_tracer() {
    const SIZE: usize = 128;
    // 3×3 sight lines per pixel, 6×6 where those disagree (an edge crosses the pixel): the
    // pixels' sampling error is most of what the mean absolute difference measures (on the
    // princess 4×4 everywhere gives 0.012, 4×4/8×8 0.0068, 3×3/6×6 0.0086, 4×4/12×12 0.0055;
    // the tolkowsky and emerald stay below 0.0075). The means agree within 7e-4.
    let (m, fine) = (3, 6);
    let n = Material::diamond().ri(589.3);
    let cuts = [
        ("tolkowsky", crate::testkit::tolkowsky()),
        ("princess", crate::io::load_cut("princess").unwrap().solid),
        ("emerald", crate::io::load_cut("emerald").unwrap().solid),
    ];
    let poses = [
        ("face-up", Tilt::FACE_UP),
        (
            "15° toward 30°",
            Tilt {
                tilt_deg: 15.0,
                azimuth_deg: 30.0,
            },
        ),
    ];
    let mut failures = Vec::new();
    for (name, solid) in &cuts {
        for (pose, tilt) in poses {
            let t = Instant::now();
            let brute = Brute::new(solid, tilt, n).image(SIZE, m, fine);
            let t_brute = t.elapsed().as_secs_f64();
            let cut: f64 = brute.iter().map(|p| p[CUT]).sum::<f64>() / brute.len() as f64;
            eprintln!("{name:9} {pose:15} brute force {m}x{m} (edges {fine}x{fine}): mean weight cut off {cut:.2e}");
            for light in LIGHTS {
                let t = Instant::now();
                let img = render(solid, &opts(light, SIZE, tilt));
                let t_render = t.elapsed().as_secs_f64();
                let o = channel_offset(light);
                for c in 0..light.channels() {
                    let want: Vec<f64> = brute.iter().map(|p| p[o + c]).collect();
                    let (mad_in, mad_all, dmean) =
                        compare(&img.channels[c].data, &want, &img.coverage.data);
                    eprintln!(
                        "{name:9} {pose:15} {:4} ch{c}: MAD(stone) {mad_in:.5}  MAD(all) {mad_all:.5}  \
                         mean diff {dmean:+.2e}  (render {t_render:.2} s, brute {t_brute:.2} s)",
                        light.name()
                    );
                    if !(mad_in <= 0.01 && dmean.abs() <= 1e-3) {
                        failures.push(format!(
                            "{name} {pose} {} ch{c}: MAD {mad_in} mean diff {dmean}",
                            light.name()
                        ));
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
