//! Checks 4 and 5: where the light goes (ASET shares, per-pixel sums against the outline's
//! coverage, a stone of index 1, every footprint's coverage) and the picture's mean against
//! `stats.mean`.

use super::opts;
use crate::geometry::canonical::canonical;
use crate::optics::Material;
use crate::render::{picture_half, raster, render, view_rotation, Light, RenderOptions, Tilt};
use glam::DVec3;

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

/// An accumulator emptied with `reset` and used for other rows gives, bit for bit, what a new
/// one for those rows gives (pictures reuse one per thread from band to band), and
/// `finish_into` writes exactly `finish`'s values.
#[test]
fn a_reset_accumulator_draws_as_a_new_one() {
    use crate::render::raster::Accumulator;
    use glam::DVec2;
    let polys: Vec<Vec<DVec2>> = (0..40)
        .map(|k| {
            let c = DVec2::new((k as f64 * 0.37).sin() * 0.6, (k as f64 * 0.71).cos() * 0.6);
            (0..5)
                .map(|j| {
                    let a = j as f64 * std::f64::consts::TAU / 5.0 + k as f64;
                    c + 0.3 * DVec2::new(a.cos(), a.sin())
                })
                .collect()
        })
        .collect();
    let draw = |acc: &mut Accumulator| {
        for (k, p) in polys.iter().enumerate() {
            acc.add_polygon(p, &[1.0 + k as f64, 0.5 * k as f64]);
        }
    };
    let mut reused = Accumulator::new(50, 1.0, (0, 16), 2);
    draw(&mut reused);
    for rows in [(16, 32), (32, 46), (44, 50), (0, 16)] {
        reused.reset(rows);
        draw(&mut reused);
        let mut fresh = Accumulator::new(50, 1.0, rows, 2);
        draw(&mut fresh);
        let want = fresh.finish();
        assert!(want[0].iter().any(|&x| x > 0.0), "{rows:?}: nothing drawn");
        assert_eq!(reused.finish(), want, "rows {rows:?}");
        let mut out = vec![vec![f64::NAN; want[0].len()]; 2];
        let mut slices: Vec<&mut [f64]> = out.iter_mut().map(|o| o.as_mut_slice()).collect();
        reused.finish_into(&mut slices);
        assert_eq!(out, want, "rows {rows:?}");
    }
}
