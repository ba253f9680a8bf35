//! Checks of the renderer (the "Checks"):
//!
//! 1. against an independent brute-force backward ray tracer written here (its own
//!    ray–convex-polyhedron intersection, Snell refraction and unpolarized Fresnel reflectance,
//!    a jittered grid of sight lines per pixel, every interface split deterministically);
//! 2. a closed form: the ASET switch of the table centre at the pavilion angle
//!    p* = (180° − asin(sin 45° / n)) / 4;
//! 3. the 8-fold symmetry of a face-up round brilliant (the pixel grid's part of it);
//! 4. energy: ASET shares, per-pixel sums against the outline's coverage, a stone of index 1;
//! 5. the picture's mean equals `stats.mean`.
//!
//! Nothing here calls the beam tracer or `optics::fresnel`: the brute-force tracer only shares
//! the renderer's definitions of the view (pose rotation, frame, picture square) and the
//! lights' radiance functions ([`Light::shade`]).

use super::*;
use crate::geometry::canonical::canonical;
use crate::geometry::Polyhedron;
use glam::{DMat3, DVec3};
use rayon::prelude::*;
use std::collections::BTreeMap;
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

/// Render options of the comparisons: unpolarized, diamond at 589.3 nm.
fn opts(light: Light, size: usize, tilt: Tilt) -> RenderOptions {
    RenderOptions {
        size,
        tilt,
        polarization: false,
        ..RenderOptions::new(light)
    }
}

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

// ---------------------------------------------------------------------------------------------
// 2. Closed form: the ASET switch of the table centre.
// ---------------------------------------------------------------------------------------------

/// Mean red and green of the pixels whose centres lie within `r1` of the picture's centre but
/// not within `r0` (the culet point), and how many of them are more green than red.
fn centre_block(img: &Image, r0: f64, r1: f64) -> (f64, f64, usize, usize) {
    let n = img.size();
    let h = img.coverage.pixel();
    let half = img.coverage.half;
    let (mut red, mut green, mut greener, mut count) = (0.0, 0.0, 0, 0);
    for row in 0..n {
        for col in 0..n {
            let (x, y) = (
                -half + (col as f64 + 0.5) * h,
                -half + (row as f64 + 0.5) * h,
            );
            let r = x.hypot(y);
            if r <= r0 || r > r1 {
                continue;
            }
            let k = row * n + col;
            let (rd, gr) = (img.channels[1].data[k], img.channels[2].data[k]);
            red += rd;
            green += gr;
            greener += usize::from(gr > rd);
            count += 1;
        }
    }
    (red / count as f64, green / count as f64, greener, count)
}

#[test]
fn aset_table_centre_switches_at_the_closed_form_pavilion_angle() {
    // A sight line straight down near the centre of a face-up round brilliant's table enters
    // without bending, meets a pavilion main (normal at the pavilion angle p from −z) and is
    // mirrored; in the vertical plane of that main's normal, with x toward the main,
    // d = (0, −1) becomes d' = (−sin 2p, cos 2p). It crosses to the opposite main (normal
    // (−sin p, −cos p)), whose mirror gives d'' = (−sin 4p, −cos 4p): (both reflections are
    // total: incidence p and 180° − 3p, both beyond the critical angle). It rises at
    // θ = 180° − 4p from the vertical, meets the table at incidence θ and leaves at
    // sin θ_out = n sin θ. It leaves at 45° elevation (θ_out = 45°, the ASET red/green edge)
    // when sin(180° − 4p) = sin 45° / n, i.e. p* = (180° − asin(sin 45° / n)) / 4.
    // A steeper pavilion (p > p*) makes θ smaller, so the sight line leaves more steeply
    // (higher elevation): red (45–75°); a shallower one leaves below 45°: green.
    // dθ_out/dp = 4 n cos θ / cos θ_out ≈ 13, so ±0.05° moves the exit by ±0.65°: inside
    // the ±1° soft edge, but well off its middle (smoothstep ≈ 0.92 vs 0.08).
    let n = Material::diamond().ri(589.3);
    let p_star = (180.0 - (45f64.to_radians().sin() / n).asin().to_degrees()) / 4.0;
    eprintln!("n(589.3 nm) = {n:.5}, p* = {p_star:.4}°");
    assert!((p_star - 40.747).abs() < 0.002, "p* = {p_star}");
    let base = crate::io::load_cut("tolkowsky").unwrap();
    let block = |p: f64| {
        let cut = base
            .with_params(&BTreeMap::from([("pavilion_angle".to_string(), p)]))
            .unwrap();
        let img = render(
            &cut.solid,
            &RenderOptions {
                size: 64,
                head_shadow_deg: Some(0.0),
                ..RenderOptions::new(Light::Aset)
            },
        );
        centre_block(&img, 0.02, 0.06)
    };
    let (red, green, greener, count) = block(p_star - 0.05);
    eprintln!(
        "pavilion {:.3}° (p* − 0.05°): centre block red {red:.3} green {green:.3}, \
         {greener}/{count} pixels greener than red",
        p_star - 0.05
    );
    assert!(count >= 20 && greener * 10 >= count * 9 && green > 2.0 * red);
    let (red, green, greener, count) = block(p_star + 0.05);
    eprintln!(
        "pavilion {:.3}° (p* + 0.05°): centre block red {red:.3} green {green:.3}, \
         {greener}/{count} pixels greener than red",
        p_star + 0.05
    );
    assert!(count >= 20 && greener * 10 <= count && red > 2.0 * green);
}

// ---------------------------------------------------------------------------------------------
// 3. Symmetry.
// ---------------------------------------------------------------------------------------------

/// A map of the pixel grid onto itself: (column, row, last index) → (column, row).
type PixelMap = fn(usize, usize, usize) -> (usize, usize);

#[test]
fn face_up_round_brilliant_has_the_pixel_grids_symmetries() {
    // The round brilliant is symmetric under the 16 maps of the dihedral group of order 16
    // (turns by k·45°, mirrors every 22.5°); the 8 of them that map the square pixel grid
    // onto itself (turns by k·90°, mirrors across the axes and the diagonals) are checked as
    // exact pixel permutations. The 45° turns and the 22.5° mirrors do not map pixels onto
    // pixels and are skipped.
    let size = 96;
    let img = render(
        &crate::testkit::tolkowsky(),
        &opts(Light::Iso, size, Tilt::FACE_UP),
    );
    let d = &img.channels[0].data;
    let last = size - 1;
    // (col, row) → image of the pixel under the map.
    let maps: [(&str, PixelMap); 7] = [
        ("turn 90°", |c, r, l| (l - r, c)),
        ("turn 180°", |c, r, l| (l - c, l - r)),
        ("turn 270°", |c, r, l| (r, l - c)),
        ("mirror x axis", |c, r, l| (c, l - r)),
        ("mirror y axis", |c, r, l| (l - c, r)),
        ("mirror diagonal", |c, r, _| (r, c)),
        ("mirror anti-diagonal", |c, r, l| (l - r, l - c)),
    ];
    let peak = d.iter().fold(0.0f64, |a, &b| a.max(b));
    assert!(peak > 0.5, "peak {peak}");
    for (name, map) in maps {
        let mut worst = 0.0f64;
        for r in 0..size {
            for c in 0..size {
                let (c2, r2) = map(c, r, last);
                worst = worst.max((d[r * size + c] - d[r2 * size + c2]).abs());
            }
        }
        eprintln!("{name}: largest pixel difference {worst:.2e}");
        assert!(worst <= 1e-9, "{name}: {worst}");
    }
}

// ---------------------------------------------------------------------------------------------
// 4. Energy.
// ---------------------------------------------------------------------------------------------

/// ASET shares add up to 1, and the channels of every pixel to the stone's coverage less the
/// light cut off (1e-4 per pixel on average).
fn check_aset_energy(tilt: Tilt) {
    let solid = crate::testkit::tolkowsky();
    {
        let img = render(&solid, &opts(Light::Aset, 64, tilt));
        let a = img.stats.aset.expect("aset shares");
        let total = a.blue + a.red + a.green + a.leak + a.port;
        assert!((total - 1.0).abs() <= 1e-9, "shares add up to {total}");
        let h = img.coverage.pixel();
        let (mut abs, mut lost) = (0.0, 0.0);
        for k in 0..img.coverage.data.len() {
            let sum: f64 = img.channels.iter().map(|c| c.data[k]).sum();
            abs += (sum - img.coverage.data[k]).abs();
            lost += img.coverage.data[k] - sum;
        }
        let area: f64 = img.coverage.data.iter().sum::<f64>() * h * h;
        let mean_abs = abs / img.coverage.data.len() as f64;
        let lost = lost * h * h / area;
        eprintln!(
            "tilt {:?}: shares {a:?} (sum − 1 = {:.1e}); mean |Σ channels − coverage| \
             {mean_abs:.2e}, light missing {lost:.2e} vs cut off {:.2e}",
            tilt,
            total - 1.0,
            img.stats.cut_off
        );
        assert!(mean_abs <= 1e-4, "{mean_abs}");
    }
}

#[test]
fn aset_shares_and_channels_account_for_the_light_face_up() {
    check_aset_energy(Tilt::FACE_UP);
}

#[test]
fn aset_shares_and_channels_account_for_the_light_tilted() {
    check_aset_energy(Tilt {
        tilt_deg: 15.0,
        azimuth_deg: 30.0,
    });
}

#[test]
fn light_missing_from_the_aset_picture_is_the_light_cut_off() {
    let solid = crate::testkit::tolkowsky();
    for tilt in [
        Tilt::FACE_UP,
        Tilt {
            tilt_deg: 15.0,
            azimuth_deg: 30.0,
        },
    ] {
        let img = render(&solid, &opts(Light::Aset, 64, tilt));
        let h = img.coverage.pixel();
        let mut lost = 0.0;
        for k in 0..img.coverage.data.len() {
            let sum: f64 = img.channels.iter().map(|c| c.data[k]).sum();
            lost += img.coverage.data[k] - sum;
        }
        let area: f64 = img.coverage.data.iter().sum::<f64>() * h * h;
        let lost = lost * h * h / area;
        eprintln!(
            "tilt {tilt:?}: light missing from the picture {lost:.3e}, cut off {:.3e}",
            img.stats.cut_off
        );
        assert!(
            (lost - img.stats.cut_off).abs() <= 1e-7,
            "{lost} vs {}",
            img.stats.cut_off
        );
    }
}

/// A bug these tests found, on its own: a small polygon inside one pixel column, straddling
/// the line between rows 31 and 32 (where a fill in bands of 32 rows splits the picture),
/// must be counted once over the two bands.
#[test]
fn band_coverage_counts_a_small_polygon_once() {
    use crate::geometry::clip2d;
    use glam::DVec2;
    let r = raster::Raster::new(64, 0.5);
    let h = r.pixel();
    let x0 = -0.5 + 10.25 * h;
    // Row 32 starts at y = −0.5 + 32 h = 0.
    let poly = [
        DVec2::new(x0, -0.3 * h),
        DVec2::new(x0 + 0.5 * h, -0.3 * h),
        DVec2::new(x0, 0.4 * h),
    ];
    let mut cov = raster::Coverage::default();
    let mut total = 0.0;
    for band in [(0, 32), (32, 64)] {
        r.coverage_rows_into(&poly, band, &mut cov);
        eprintln!("rows {band:?}: cells {:?}", cov.cells);
        total += cov.cells.iter().map(|c| c.1).sum::<f64>();
    }
    r.coverage_into(&poly, &mut cov);
    let whole: f64 = cov.cells.iter().map(|c| c.1).sum();
    let area = clip2d::area(&poly);
    eprintln!("area {area:.6e}: whole image {whole:.6e}, two bands {total:.6e}");
    assert!((whole - area).abs() <= 1e-12 * area);
    assert!((total - area).abs() <= 1e-12 * area, "{total} vs {area}");
}

/// A stone of index 1 lets the viewer see straight through it: the ground (black under iso,
/// all leak under ASET).
fn check_index_one(tilt_deg: f64) {
    let solid = crate::testkit::tolkowsky();
    {
        let tilt = Tilt {
            tilt_deg,
            azimuth_deg: 0.0,
        };
        let base = |light| RenderOptions {
            material: Material::constant(1.0),
            ..opts(light, 48, tilt)
        };
        let iso = render(&solid, &base(Light::Iso));
        let iso_max = iso.channels[0]
            .data
            .iter()
            .fold(0.0f64, |a, &b| a.max(b.abs()));
        let aset = render(&solid, &base(Light::Aset));
        let mut worst = [0.0f64; 5];
        for k in 0..aset.coverage.data.len() {
            for (c, w) in worst.iter_mut().enumerate() {
                let want = if c == 3 { aset.coverage.data[k] } else { 0.0 };
                *w = w.max((aset.channels[c].data[k] - want).abs());
            }
        }
        let covered: f64 = aset.coverage.data.iter().sum();
        eprintln!(
            "index 1, tilt {tilt_deg}°: iso max {iso_max:.1e}, stats.mean {:.1e}; aset largest \
             |channel − expected| {worst:?} (leak expected = coverage, {covered:.1} pixels)",
            iso.stats.mean
        );
        assert!(covered > 100.0);
        assert!(iso_max <= 1e-12 && iso.stats.mean.abs() <= 1e-12);
        // To the beam tracer's geometric precision (its tiling error is a few 1e-8).
        assert!(worst.iter().all(|&w| w <= 1e-7), "{worst:?}");
        let a = aset.stats.aset.expect("aset shares");
        assert!((a.leak - 1.0).abs() <= 1e-9, "{a:?}");
    }
}

#[test]
fn a_stone_of_index_one_shows_the_ground_face_up() {
    check_index_one(0.0);
}

#[test]
fn a_stone_of_index_one_shows_the_ground_tilted() {
    check_index_one(30.0);
}

// ---------------------------------------------------------------------------------------------
// 5. The picture's mean is stats.mean.
// ---------------------------------------------------------------------------------------------

#[test]
fn image_integral_over_outline_is_stats_mean() {
    let cuts = [
        ("tolkowsky", crate::testkit::tolkowsky()),
        ("princess", crate::io::load_cut("princess").unwrap().solid),
    ];
    for (name, solid) in &cuts {
        for tilt in [
            Tilt::FACE_UP,
            Tilt {
                tilt_deg: 20.0,
                azimuth_deg: 50.0,
            },
        ] {
            for light in [Light::Iso, Light::Cos] {
                let img = render(solid, &opts(light, 64, tilt));
                let h = img.coverage.pixel();
                let area: f64 = img.coverage.data.iter().sum::<f64>() * h * h;
                let rot = view_rotation(light, tilt);
                let projected = canonical(solid).projected_area(rot.transpose() * DVec3::NEG_Z);
                let integral: f64 = img.channels[0].data.iter().sum::<f64>() * h * h;
                let mean = integral / area;
                eprintln!(
                    "{name} {tilt:?} {}: image mean over outline {mean:.12}, stats.mean {:.12} \
                     (outline area {area:.12}, projected {projected:.12})",
                    light.name(),
                    img.stats.mean
                );
                assert!((area - projected).abs() <= 1e-9 * projected);
                assert!(
                    (mean - img.stats.mean).abs() <= 1e-9,
                    "{mean} vs {}",
                    img.stats.mean
                );
            }
        }
    }
}

/// Every exit beam's footprint, accumulated alone, covers exactly its area. Princess
/// footprints have near-vertical edges lying on a pixel column line to within 1e-16, where an
/// accumulation that shared a row's height by the edge's overall slope instead of the row's
/// own x-range lost 1.6e-7 of the picture's light (found by the test above).
#[test]
fn every_footprint_accumulates_to_its_area() {
    use crate::beam::{Frame, Stone, TraceOptions};
    use crate::geometry::clip2d;
    for name in ["princess", "tolkowsky", "emerald"] {
        let solid = canonical(&crate::io::load_cut(name).unwrap().solid);
        let stone = Stone::new(&solid);
        let o = TraceOptions {
            footprints: true,
            split_threshold: 1e-4,
            ..Default::default()
        };
        let t = stone.trace(&Frame::viewer(Tilt::FACE_UP.rotation()), 2.417, 589.3, &o);
        let half = picture_half(&solid);
        let h = 2.0 * half / 64.0;
        let mut err = 0.0;
        for (i, e) in t.exits.iter().enumerate() {
            let fp = t.footprint(i);
            let a = clip2d::area(fp);
            let mut acc = raster::Accumulator::new(64, half, (0, 64), 1);
            acc.add_polygon(fp, &[1.0]);
            let cov: f64 = acc.finish()[0].iter().sum::<f64>() * h * h;
            // The light this footprint would misplace.
            err += (cov - a).abs() * e.power / a.max(1e-300);
        }
        assert!(err < 1e-12, "{name}: {err}");
    }
}
