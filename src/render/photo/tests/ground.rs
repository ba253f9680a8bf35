//! Check 4: the ground's caustics and shadow. Power is conserved to rounding, the shadow's
//! area is the stone's projected outline, and the caustic's pattern agrees with the photon
//! tracer's hits on the same plane within 4 standard errors per cell.

use super::super::env::{direction, LightSample};
use super::super::ground::{land, GroundField, GroundPlane, Lit, LitTrace};
use crate::beam::{Frame, Medium, Stone, TraceOptions};
use crate::geometry::canonical::canonical;
use crate::optics::Material;
use crate::photon::{self, Fate, LightKind, LightSize, TraceConfig, WavelengthSampling};
use crate::testkit::{princess, tolkowsky};
use glam::{DMat3, DVec2};

/// The ground under `solid` (canonical, resting on its lowest point) lit from `w` with
/// horizontal irradiance 1 at index `ri`, on a raster of `n` cells over ±`half`.
fn field(
    solid: &crate::geometry::Polyhedron,
    w: glam::DVec3,
    ri: f64,
    half: f64,
    n: usize,
) -> (GroundField, f64) {
    field_in(solid, w, Medium::Isotropic(ri), half, n)
}

/// [`field`] through any medium (a uniaxial crystal traced through both of its rays).
fn field_in(
    solid: &crate::geometry::Polyhedron,
    w: glam::DVec3,
    medium: Medium,
    half: f64,
    n: usize,
) -> (GroundField, f64) {
    let opts = TraceOptions {
        split_threshold: 1e-5,
        threshold: 1e-10,
        ..TraceOptions::default()
    };
    field_traced(solid, w, medium, half, n, &opts)
}

/// [`field_in`] traced with `opts`.
fn field_traced(
    solid: &crate::geometry::Polyhedron,
    w: glam::DVec3,
    medium: Medium,
    half: f64,
    n: usize,
    opts: &TraceOptions,
) -> (GroundField, f64) {
    let stone = Stone::new(solid);
    let z = solid
        .vertices()
        .iter()
        .map(|v| v.z)
        .fold(f64::INFINITY, f64::min);
    let lights = [Lit {
        sample: LightSample {
            dir: w,
            irradiance: [1.0; 3],
            point: true,
        },
        traces: vec![LitTrace {
            medium,
            alpha: 0.0,
            bands: vec![(0, 1.0, 1.0)],
        }],
    }];
    let g = GroundField::new(
        &stone,
        DMat3::IDENTITY,
        GroundPlane { z, half, n },
        &[0.8],
        &lights,
        &|v: &[f64]| v[0],
        opts,
    );
    (g, z)
}

/// Power in = caustic on the ground (inside and beyond the raster) + escaping upward +
/// absorbed + cut off, to 1e-9; the light intercepted is the projected outline's area over
/// the light's cosine; the caustic's and the escaping light are the beam tree's downward and
/// upward exits (traced again here); the shadow's area is the projected outline's.
#[test]
fn caustic_power_and_shadow_area() {
    for (name, solid) in [("tolkowsky", tolkowsky()), ("princess", princess())] {
        let solid = canonical(&solid);
        for (elev, az) in [(50.0, 30.0), (70.0, -100.0), (30.0, 200.0)] {
            let w = direction(elev, az);
            let (g, _) = field(&solid, w, 2.4173, 3.0, 256);
            let st = g.stats;
            let a_perp = solid.projected_area(w);
            let phi = a_perp / w.z;
            assert!((st.intercepted - phi).abs() < 1e-12 * phi, "{name}");
            let sum = st.caustic + st.caustic_outside + st.escaped + st.absorbed + st.cut_off;
            assert!(
                (sum - st.intercepted).abs() < 1e-9 * phi,
                "{name} {elev}: {st:?}"
            );
            assert!(st.cut_off < 1e-4 * phi && st.absorbed.abs() < 1e-12);
            // The beam tree, traced again: down and up.
            let stone = Stone::new(&solid);
            let tree = stone.trace(
                &Frame::new(-w).unwrap(),
                2.4173,
                589.3,
                &TraceOptions {
                    split_threshold: 1e-5,
                    threshold: 1e-10,
                    ..TraceOptions::default()
                },
            );
            let (mut up, mut down) = (0.0, 0.0);
            for e in &tree.exits {
                if e.direction.z >= 0.0 {
                    up += e.power;
                } else {
                    down += e.power;
                }
            }
            assert!((st.escaped - phi * up).abs() < 1e-9 * phi, "{name}");
            assert!(
                (st.caustic + st.caustic_outside - phi * down).abs() < 1e-9 * phi,
                "{name}"
            );
            // The raster's integral is the caustic inside it.
            let h = g.cell();
            let inside: f64 = g.caustic[0].iter().sum::<f64>() * h * h;
            assert!((inside - st.caustic).abs() < 1e-12 * phi);
            // Shadow: the raster loses the irradiance (1) over the projected outline.
            let shadow: f64 = g.shadow[0].iter().sum::<f64>() * h * h;
            assert!((shadow - phi).abs() < 1e-9 * phi, "{name}: {shadow} {phi}");
            assert!((st.shadow_area - phi).abs() < 1e-9 * phi);
        }
    }
}

/// A birefringent stone's caustic lands too (both rays' exits leaving downward, exact beams
/// as polygons and narrow beams' rays over their cross-sections, as the singly refractive
/// trace's): in the isotropic limit (n_e = n_o + 1e-9, so traced as a crystal) the ground is
/// the singly refractive stone's within the narrow-beam approximation (caustic and escaping
/// light to 1e-3, the pattern on 16 × 16 blocks to 6 % in L1: 4.2 % at split 1e-5, 4.5 %
/// when the crystal's narrow beams landed on dots; the rest is the two traces' different
/// narrow beams, each beam split into two modes), and a zircon
/// with a tilted axis conserves power on the ground to 1e-9 and sends a caustic within a
/// few per cent of its ordinary ray's alone.
#[test]
fn birefringent_caustic_lands_on_the_ground() {
    use crate::optics::crystal::Crystal;
    let solid = canonical(&tolkowsky());
    let w = direction(60.0, 30.0);
    let phi = solid.projected_area(w) / w.z;
    let crystal = |n_o: f64, n_e: f64, axis: glam::DVec3| Medium::Uniaxial {
        crystal: Crystal::new(n_o, n_e, axis.normalize()),
        alpha_o: 0.0,
        alpha_e: 0.0,
    };
    let (iso, _) = field(&solid, w, 2.0, 3.0, 128);
    let (lim, _) = field_in(
        &solid,
        w,
        crystal(2.0, 2.0 + 1e-9, glam::DVec3::Z),
        3.0,
        128,
    );
    let (a, b) = (iso.stats, lim.stats);
    assert!(a.caustic > 0.1 * phi, "{a:?}");
    // The crystal's trace splits each beam into two modes, so its narrow beams (followed as
    // rays below the split threshold) are not the singly refractive trace's: the two agree to
    // the narrow-beam approximation, not to rounding.
    assert!((a.caustic - b.caustic).abs() < 1e-3 * phi, "{a:?} vs {b:?}");
    assert!((a.escaped - b.escaped).abs() < 1e-3 * phi, "{a:?} vs {b:?}");
    // The pattern on a coarse grid (16 × 16 blocks of 8 × 8 cells): cell by cell the two
    // differ where their narrow beams' rays differ.
    let h = iso.cell();
    let blocks = |f: &GroundField| {
        let mut b = vec![0.0; 256];
        for (k, v) in f.caustic[0].iter().enumerate() {
            let (i, j) = (k % 128 / 8, k / 128 / 8);
            b[j * 16 + i] += v * h * h;
        }
        b
    };
    let l1: f64 = blocks(&iso)
        .iter()
        .zip(blocks(&lim))
        .map(|(x, y)| (x - y).abs())
        .sum();
    assert!(
        l1 < 0.06 * a.caustic,
        "pattern differs by {l1} of {}",
        a.caustic
    );
    let axis = direction(55.0, 20.0);
    let (zircon, _) = field_in(&solid, w, crystal(1.9254, 1.9841, axis), 3.0, 128);
    let (ordinary, _) = field(&solid, w, 1.9254, 3.0, 128);
    let (z, o) = (zircon.stats, ordinary.stats);
    let sum = z.caustic + z.caustic_outside + z.escaped + z.absorbed + z.cut_off;
    assert!((sum - z.intercepted).abs() < 1e-9 * phi, "{z:?}");
    let (cz, co) = (z.caustic + z.caustic_outside, o.caustic + o.caustic_outside);
    assert!(
        (cz - co).abs() < 0.05 * co,
        "zircon {cz} vs its ordinary ray {co}"
    );
}

/// The caustic's pattern against the photon tracer's hits on the same plane: a directed
/// light over the stone, each photon that leaves downward landed on the plane; per cell of
/// an 8 × 8 grid, the beam tracer's share of the intercepted power within 4 standard
/// errors of the photons' share (plus 1e-4 for the narrow beams' rays).
#[test]
fn caustic_agrees_with_the_photon_tracer() {
    let solid = canonical(&tolkowsky());
    let w = direction(55.0, 20.0);
    let ri = 2.4173;
    let half = 1.2;
    let (g, z) = field(&solid, w, ri, half, 256);
    let phi = g.stats.intercepted;
    let grid = 8;
    let per = 256 / grid;
    let h = g.cell();
    let mut beam = vec![0.0; grid * grid];
    for j in 0..256 {
        for i in 0..256 {
            beam[(j / per) * grid + i / per] += g.caustic[0][j * 256 + i] * h * h / phi;
        }
    }
    let light = photon::Light {
        kind: LightKind::Directed,
        centre: w * photon::LIGHT_DISTANCE,
        axis: -w,
        size: LightSize::CoverStone,
        angle: None,
        label: "directed".into(),
    };
    let n = 60_000usize;
    let cfg = TraceConfig {
        photons: n as u64,
        until_hit: true,
        depth: None,
        absorption: crate::optics::Absorption::None,
        polarization: true,
        material: Material::constant(ri),
        wavelengths: WavelengthSampling::Fixed(589.3),
        seed: 7,
        record_paths: n,
    };
    let t = photon::trace(&solid, &light, &cfg, None).unwrap();
    assert_eq!(t.paths.len(), n);
    let mut hits = vec![0usize; grid * grid];
    for p in &t.paths {
        if !matches!(p.fate, Fate::Exited(_)) {
            continue;
        }
        let k = p.points.len();
        let (x, end) = (p.points[k - 2], p.points[k - 1]);
        let d = end - x;
        if d.z >= 0.0 {
            continue;
        }
        let at: DVec2 = land(x, d.normalize(), z);
        let (fx, fy) = ((at.x + half) / (2.0 * half), (at.y + half) / (2.0 * half));
        if !(0.0..1.0).contains(&fx) || !(0.0..1.0).contains(&fy) {
            continue;
        }
        hits[(fy * grid as f64) as usize * grid + (fx * grid as f64) as usize] += 1;
    }
    let mut worst: f64 = 0.0;
    for c in 0..grid * grid {
        let p = hits[c] as f64 / n as f64;
        let se = (p.max(1.0 / n as f64) * (1.0 - p) / n as f64).sqrt();
        let z = (beam[c] - p).abs() / (4.0 * se + 1e-4);
        worst = worst.max(z);
        assert!(z <= 1.0, "cell {c}: beam {} photons {p} ± {se}", beam[c]);
    }
    let lit = beam.iter().filter(|&&b| b > 0.003).count();
    let total: f64 = beam.iter().sum();
    eprintln!(
        "caustic against photons: worst cell at {worst:.2} of its allowance; {lit} cells over 0.3 %, {total:.3} of the light in the grid"
    );
    // The pattern is not trivially empty.
    assert!(lit >= 3 && total > 0.1, "{beam:?}");
}

/// Narrow beams land over their own cross-sections (their polygons carried along their rays
/// to the exit facet, slid onto the plane), not on dots of half a cell, so a coarse trace's
/// caustic has no speckle: one directional light, split at 1e-3 against split at 1e-7 (128
/// cells over ±1.5), the worst cell differs by under 0.2 of the brightest (measured 0.11;
/// 0.35 with dots) and the L1 difference per cell stays under 0.55 of the caustic
/// (measured 0.47; dots 0.77; the rest is the rays' one direction per narrow beam: 0.17,
/// 0.05 and 0.008 at splits 1e-4, 1e-5 and 1e-6).
#[test]
fn coarse_caustic_is_the_fine_one() {
    let solid = canonical(&tolkowsky());
    let w = direction(55.0, 20.0);
    let traced = |split: f64| {
        let opts = TraceOptions {
            split_threshold: split,
            threshold: 1e-9,
            ..TraceOptions::default()
        };
        field_traced(&solid, w, Medium::Isotropic(2.4173), 1.5, 128, &opts).0
    };
    let (fine, coarse) = (traced(1e-7), traced(1e-3));
    let (f, c) = (&fine.caustic[0], &coarse.caustic[0]);
    let h2 = fine.cell() * fine.cell();
    let l1: f64 = f.iter().zip(c).map(|(a, b)| (a - b).abs()).sum::<f64>() * h2;
    let peak = f.iter().fold(0.0f64, |m, &a| m.max(a));
    let worst = f
        .iter()
        .zip(c)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let caustic = fine.stats.caustic;
    eprintln!(
        "coarse against fine: L1 {:.4} of the caustic, worst cell {:.3} of the peak",
        l1 / caustic,
        worst / peak
    );
    assert!(caustic > 0.1 * fine.stats.intercepted, "{:?}", fine.stats);
    assert!(l1 < 0.55 * caustic, "L1 {l1} of {caustic}");
    assert!(worst < 0.2 * peak, "worst cell {worst} of the peak {peak}");
}
