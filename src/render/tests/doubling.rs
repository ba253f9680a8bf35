//! Check 6 of issue 41, a measured doubling: a birefringent stone's picture shows an edge
//! behind the table twice, offset by the walk-off of the extraordinary ray.
//!
//! The stone is a zircon block whose bottom is a keel: two facets meeting in an edge along y
//! at depth `t` below a flat top. Seen face-up, every sight line enters the top at normal
//! incidence, so both modes' wave normals run straight down: the ordinary ray stays on its
//! sight line and meets the keel edge under the sight line through the edge; the
//! extraordinary ray walks off by ρ, the angle between its wave normal and its Poynting
//! vector, and meets the edge under a sight line `t·tan ρ` away. A spot light below the
//! right-hand facet lights what leaves through that facet alone, so the picture steps up
//! twice across the edge, once per mode. The closed form written here,
//! `tan θ_ray = (n_o²/n_e²)·tan θ` for a wave normal at θ from the optic axis (Born & Wolf
//! §15.3), gives the offset; the two steps are found in the picture by the centroids of its
//! column-to-column rises, and their distance must be the offset to a pixel.

use super::super::lighting::Spot;
use super::super::pose::picture_half;
use super::{opts, Light, Tilt};
use crate::geometry::canonical::canonical;
use crate::geometry::{DVec3, FacetPlane, Plane, Polyhedron};
use crate::optics::{Material, OpticAxis};

/// The keel block: top z = 0, sides x = ±1 and y = ±0.6, keel facets z = −t + a·|x|.
fn keel(t: f64, a: f64) -> Polyhedron {
    let plane = |n: DVec3, offset: f64, name: &str| {
        let k = n.length();
        FacetPlane {
            plane: Plane {
                normal: n / k,
                offset: offset / k,
            },
            name: name.into(),
            tier: name.into(),
        }
    };
    Polyhedron::from_planes(&[
        plane(DVec3::Z, 0.0, "top"),
        plane(DVec3::X, 1.0, "east"),
        plane(-DVec3::X, 1.0, "west"),
        plane(DVec3::Y, 0.6, "north"),
        plane(-DVec3::Y, 0.6, "south"),
        plane(DVec3::new(a, 0.0, -1.0), t, "keel-east"),
        plane(DVec3::new(-a, 0.0, -1.0), t, "keel-west"),
    ])
    .unwrap()
}

/// Positions (in pixels, along the picture's rows) of the two largest rises of `profile`,
/// each the centroid of the positive differences in a window around its peak, ascending.
fn two_steps(profile: &[f64]) -> [f64; 2] {
    let d: Vec<f64> = profile.windows(2).map(|w| (w[1] - w[0]).max(0.0)).collect();
    let centroid = |peak: usize| {
        let (lo, hi) = (peak.saturating_sub(2), (peak + 3).min(d.len()));
        let (mut s, mut w) = (0.0, 0.0);
        for (k, &v) in d.iter().enumerate().take(hi).skip(lo) {
            s += v * (k as f64 + 1.0); // a rise from pixel k to k + 1 sits at their border
            w += v;
        }
        s / w
    };
    let first = (0..d.len()).max_by(|&i, &j| d[i].total_cmp(&d[j])).unwrap();
    // The other rise: the largest at least 3 pixels from the first.
    let second = (0..d.len())
        .filter(|&k| k.abs_diff(first) >= 3)
        .max_by(|&i, &j| d[i].total_cmp(&d[j]))
        .unwrap();
    let (a, b) = (centroid(first), centroid(second));
    [a.min(b), a.max(b)]
}

/// The mean over `rows` of each column's pixel (its channels summed).
fn column_profile(image: &crate::render::Image, rows: &[usize]) -> Vec<f64> {
    (0..image.size())
        .map(|i| {
            rows.iter()
                .map(|&j| image.pixel(i, j).iter().sum::<f64>())
                .sum::<f64>()
                / rows.len() as f64
        })
        .collect()
}

#[test]
fn a_zircons_keel_edge_is_seen_twice_offset_by_the_walk_off() {
    let (t, a) = (1.0, 0.3);
    let solid = keel(t, a);
    let tilt_deg = 45.0;
    let mut material = Material::by_name("zircon").unwrap();
    material.uniaxial.as_mut().unwrap().axis = OpticAxis {
        tilt_deg,
        azimuth_deg: 0.0,
    };
    let size = 512;
    let mut o = opts(Light::Fire, size, Tilt::FACE_UP);
    o.material = material.clone();
    o.head_shadow_deg = Some(0.0);
    // Light leaving the east keel facet runs ~17° west of straight down (refraction bends it
    // away from the facet's normal); the west's, east. The spot lights the east facet's.
    o.spots = vec![Spot {
        elevation_deg: -73.0,
        azimuth_deg: 180.0,
        radius_deg: 12.0,
    }];
    let image = super::super::render(&solid, &o);

    // The picture's scale: it spans ±half of the canonical solid, whose unit is the block's
    // size sqrt(4·area/π) (the file's units over it).
    let canon = canonical(&solid);
    let file_size = (4.0 * solid.projected_area(DVec3::Z) / std::f64::consts::PI).sqrt();
    let pixel = 2.0 * picture_half(&canon) * file_size / size as f64;

    // Rows through the middle of the block, away from its north and south walls.
    let rows: Vec<usize> = (size / 2 - 40..size / 2 + 40).collect();
    let profile = column_profile(&image, &rows);
    let [s0, s1] = two_steps(&profile);
    let measured = (s1 - s0) * pixel;

    // The closed form, at the middle of the visible spectrum (the picture sums 8 bands; the
    // birefringence changes by a few per cent across them, a fraction of a pixel here).
    let (n_o, n_e) = (material.ri(555.0), material.ri_e(555.0));
    let theta = tilt_deg.to_radians(); // the wave normal (straight down) from the axis' line
    let rho = ((n_o * n_o) / (n_e * n_e) * theta.tan()).atan() - theta;
    let predicted = t * rho.tan().abs();
    assert!(
        predicted / pixel > 4.0,
        "the offset ({:.2} px) should be well resolved",
        predicted / pixel
    );
    // The issue asks for a pixel; the exact area sampling finds the steps to a few hundredths
    // (measured 6.18 px against 6.20 at 512 px), so a quarter pixel is asked here.
    assert!(
        (measured - predicted).abs() < 0.25 * pixel,
        "edges at {s0:.2} and {s1:.2} px: {:.2} px apart, the walk-off predicts {:.2} px",
        measured / pixel,
        predicted / pixel
    );

    // The ordinary ray goes straight down: its step is the keel's own sight line, the
    // picture's middle column border (the block is symmetric about x = 0, its centroid).
    let keel_column = size as f64 / 2.0;
    assert!(
        (s0 - keel_column).abs() < 0.25 || (s1 - keel_column).abs() < 0.25,
        "neither step ({s0:.2}, {s1:.2}) is at the keel's sight line ({keel_column})"
    );

    // Birefringence off: one step (the ordinary ray's), where the ordinary ray put it.
    o.material.uniaxial.as_mut().unwrap().traced = false;
    let single = super::super::render(&solid, &o);
    let profile_off = column_profile(&single, &rows);
    let rises: Vec<f64> = profile_off
        .windows(2)
        .map(|w| (w[1] - w[0]).max(0.0))
        .collect();
    let top = rises.iter().copied().fold(0.0, f64::max);
    let peak = rises.iter().position(|&r| r == top).unwrap() as f64 + 1.0;
    let near = |s: f64| (s - peak).abs() < 1.0;
    assert!(
        near(s0) || near(s1),
        "the ordinary ray's edge ({peak:.1} px) is one of the two ({s0:.2}, {s1:.2})"
    );
    // Away from its one edge the single-index picture has no second step.
    let far_rise = rises
        .iter()
        .enumerate()
        .filter(|(k, _)| (*k as f64 + 1.0 - peak).abs() >= 3.0)
        .map(|(_, &r)| r)
        .fold(0.0, f64::max);
    assert!(
        far_rise < 0.1 * top,
        "a second rise {far_rise} beside the edge's {top} with birefringence off"
    );
}
