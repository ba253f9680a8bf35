//! Checks 2 and 3: the ASET switch of the table centre at the closed-form pavilion angle, and
//! the 8-fold symmetry of a face-up round brilliant on the pixel grid.

use super::opts;
use crate::optics::Material;
use crate::render::{render, Image, Light, RenderOptions, Tilt};
use std::collections::BTreeMap;

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
