//! A turntable of a symmetric stone repeats itself ([`turntable_period`]): the frames it does
//! not trace are the ones it shows again, pixel for pixel.

use super::*;
use crate::optics::Material;
use crate::testkit::princess;

/// Options of a small photograph of a princess under dark-field lights from 45° above, on a
/// white ground (its shadow and caustics turn with the stone).
fn options() -> PhotoOptions {
    let mut o = PhotoOptions::new(PhotoLight::Rig(Rig::Darkfield));
    o.size = 24;
    o.material = Material::constant(2.4173);
    o.view = View {
        elevation_deg: 45.0,
        azimuth_deg: 10.0,
    };
    o.ground.kind = GroundKind::White;
    o.ground_cells = 4;
    o
}

/// The largest difference of two photographs' pixels (X, Y, Z, the ground's included).
fn largest_difference(a: &Photo, b: &Photo) -> f64 {
    (0..3)
        .flat_map(|c| {
            a.xyz[c]
                .data
                .iter()
                .zip(&b.xyz[c].data)
                .map(|(x, y)| (x - y).abs())
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_turntable_repeats_with_the_stones_own_symmetry() {
    let solid = princess();
    let o = options();
    // Four-fold: 12 frames of 30° repeat every 3 (a turn of 90°).
    assert_eq!(turntable_period(&solid, &o, 12), 3);
    let frame = |k| photo(&solid, &turntable(&o, 12, k));
    let (f1, f2, f4) = (frame(1), frame(2), frame(4));
    let same = largest_difference(&f1, &f4);
    let other = largest_difference(&f1, &f2);
    eprintln!("frame 1 against 4 (a symmetry apart): {same:.2e}; against 2: {other:.2e}");
    assert!(same < 1e-9, "{same}");
    // The test could fail: a turn that is no symmetry changes the picture.
    assert!(other > 1e-2, "{other}");
}

#[test]
fn a_turntable_is_traced_whole_when_the_pose_or_the_optic_axis_breaks_the_symmetry() {
    let solid = princess();
    let mut o = options();
    o.tilt = crate::render::Tilt {
        tilt_deg: 10.0,
        azimuth_deg: 0.0,
    };
    assert_eq!(turntable_period(&solid, &o, 12), 12);
    // Turned over (the hearts pose) the axis is still vertical.
    o.tilt = crate::render::Tilt {
        tilt_deg: 180.0,
        azimuth_deg: 0.0,
    };
    assert_eq!(turntable_period(&solid, &o, 12), 3);
    o.tilt = crate::render::Tilt::FACE_UP;
    let mut zircon = Material::by_name("zircon").unwrap();
    for (axis, period) in [("0", 3), ("90@0", 12), ("35@20", 12)] {
        zircon.uniaxial.as_mut().unwrap().axis =
            crate::optics::OpticAxis::parse(axis, "test").unwrap();
        o.material = zircon.clone();
        assert_eq!(turntable_period(&solid, &o, 12), period, "axis {axis}");
    }
    // With birefringence off, the axis does not matter.
    zircon.uniaxial.as_mut().unwrap().traced = false;
    o.material = zircon;
    assert_eq!(turntable_period(&solid, &o, 12), 3);
}
