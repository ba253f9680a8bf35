//! The bundled studio rigs ([`Rig`]): the lighting setups jewellery photographers use, each as
//! an [`Environment`] whose geometry is stated here. Radiances are linear sRGB relative to
//! the ISO sky (radiance 1 over the upper hemisphere: a white diffuser under it reads 1).
//! Rigs that follow the camera (the tent's port, the ring light around the lens) are built
//! for a view direction; azimuths are counted from the camera's own azimuth, so a rig looks
//! the same from every side until it is turned (`--light-rotation`).

use super::env::{direction, Disc, Environment, Part};
use crate::error::{Error, Result};
use glam::DVec3;

/// A bundled studio rig.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rig {
    /// A light tent (light box) with a bare spark light: the product photographer's
    /// translucent box lit from outside, its fabric brightest overhead (radiance 1 at the
    /// zenith, 0.35 at the horizon) and where two lamps shine through its sides (25° glows
    /// of +0.8 at 20° elevation, left and right of the camera), its white floor in shade
    /// (0.25); the camera looking in through a port (a dark disc of 12° around the lens: the
    /// lens, the camera, the photographer); and one small clear bulb (2° radius, radiance 40,
    /// at 55° elevation, 135° round from the camera) for sparkle. A tent alone makes a
    /// diamond look flat and grey: every facet sees the same white.
    Tent,
    /// Dark-field: point lights on black, the jeweller's "sparkle" setup (as under a
    /// gemmological microscope's dark-field illumination, light from the sides on a black
    /// ground): twelve 3° lights of radiance 25 around the stone, at 20°, 40° and 60°
    /// elevation in turn, every 30° of azimuth from 15°; black everywhere else.
    Darkfield,
    /// Daylight: a clear sky (radiance from 0.75 sRGB-blue-grey at the horizon to deeper
    /// blue at the zenith) with the sun (0.27° radius, warm white, radiance 9·10⁴, so that it
    /// brings about twice the sky's light to a horizontal table) at 45° elevation, 120° round
    /// from the camera; grey ground 0.15 below the horizon.
    Daylight,
    /// An office: a ceiling of panel lights (0.6 × 1.2 ceiling heights each, radiance 5, in
    /// a grid 1.6 × 2.4 ceiling heights apart) over walls of 0.12 and a floor of 0.08: the
    /// light a stone meets at a desk.
    Office,
    /// A jeweller's ring light: a ring around the lens (15°–22° from the line of sight,
    /// radiance 4) in a dim room (0.03): even, shadowless light that shows a stone's
    /// symmetry (its reflections of the ring form a pattern).
    Ring,
}

impl Rig {
    /// Every rig, in the order the command line lists them.
    pub const ALL: [Rig; 5] = [
        Rig::Tent,
        Rig::Darkfield,
        Rig::Daylight,
        Rig::Office,
        Rig::Ring,
    ];

    /// The name used on the command line and in files.
    pub fn name(self) -> &'static str {
        match self {
            Rig::Tent => "tent",
            Rig::Darkfield => "darkfield",
            Rig::Daylight => "daylight",
            Rig::Office => "office",
            Rig::Ring => "ring",
        }
    }

    /// A short title for menus ([`crate::render::lights`]).
    pub fn label(self) -> &'static str {
        match self {
            Rig::Tent => "Photo: light tent",
            Rig::Darkfield => "Photo: dark-field",
            Rig::Daylight => "Photo: daylight",
            Rig::Office => "Photo: office",
            Rig::Ring => "Photo: ring light",
        }
    }

    /// What it is, in a few words, for help texts ([`crate::render::lights`]).
    pub fn about(self) -> &'static str {
        match self {
            Rig::Tent => "light box with a spark light",
            Rig::Darkfield => "point lights on black",
            Rig::Daylight => "sky and sun",
            Rig::Office => "ceiling panels",
            Rig::Ring => "ring light round the lens",
        }
    }

    /// The exposure a photograph under it is best first shown at (the daylight's sun and the
    /// tent's bright fabric want less, the ring's dim room more).
    pub fn first_exposure(self) -> f64 {
        match self {
            Rig::Tent => 0.8,
            Rig::Darkfield | Rig::Office => 1.0,
            Rig::Daylight => 0.5,
            Rig::Ring => 1.2,
        }
    }

    /// The rig called `name`.
    pub fn parse(name: &str) -> Result<Rig> {
        Rig::ALL
            .into_iter()
            .find(|r| r.name() == name)
            .ok_or_else(|| {
                Error::invalid(
                    "light",
                    format!(
                        "unknown rig {name:?}; allowed {}",
                        Rig::ALL.map(Rig::name).join(", ")
                    ),
                )
            })
    }

    /// The rig for a camera looking along `view` (world, unit, from the camera to the stone)
    /// from azimuth `camera_az_deg`.
    pub fn environment(self, view: DVec3, camera_az_deg: f64) -> Environment {
        let to_camera = -view;
        let az = |a: f64| camera_az_deg + a;
        let parts = match self {
            Rig::Tent => vec![
                Part::Sky {
                    zenith: [1.0; 3],
                    horizon: [0.35; 3],
                },
                Part::Floor([0.25; 3]),
                Part::Ring {
                    axis: direction(20.0, az(90.0)),
                    inner_deg: 0.0,
                    outer_deg: 25.0,
                    radiance: [0.8; 3],
                },
                Part::Ring {
                    axis: direction(20.0, az(-90.0)),
                    inner_deg: 0.0,
                    outer_deg: 25.0,
                    radiance: [0.8; 3],
                },
                Part::Ring {
                    axis: to_camera,
                    inner_deg: 0.0,
                    outer_deg: 12.0,
                    radiance: [-3.0; 3],
                },
                Part::Disc(Disc::new(direction(55.0, az(135.0)), 2.0, [40.0; 3])),
            ],
            Rig::Darkfield => (0..12)
                .map(|k| {
                    let e = [20.0, 40.0, 60.0][k % 3];
                    Part::Disc(Disc::new(
                        direction(e, az(15.0 + 30.0 * k as f64)),
                        3.0,
                        [25.0; 3],
                    ))
                })
                .collect(),
            Rig::Daylight => vec![
                Part::Sky {
                    zenith: [0.28, 0.42, 0.85],
                    horizon: [0.7, 0.76, 0.88],
                },
                Part::Floor([0.15; 3]),
                Part::Disc(Disc::new(
                    direction(45.0, az(120.0)),
                    0.2665,
                    [9.0e4, 8.6e4, 7.8e4],
                )),
            ],
            Rig::Office => {
                let mut v = vec![
                    Part::Sky {
                        zenith: [0.12; 3],
                        horizon: [0.12; 3],
                    },
                    Part::Floor([0.08; 3]),
                ];
                for i in -4..=4 {
                    for j in -3..=3 {
                        v.push(Part::Panel {
                            centre: [1.6 * i as f64 + 0.4, 2.4 * j as f64 + 0.5],
                            half: [0.3, 0.6],
                            radiance: [5.0, 5.0, 4.8],
                        });
                    }
                }
                v
            }
            Rig::Ring => vec![
                Part::Sky {
                    zenith: [0.03; 3],
                    horizon: [0.03; 3],
                },
                Part::Floor([0.03; 3]),
                Part::Ring {
                    axis: to_camera,
                    inner_deg: 15.0,
                    outer_deg: 22.0,
                    radiance: [4.0; 3],
                },
            ],
        };
        Environment::new(self.name(), parts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tent's port is dark around the lens and the spark light is where its documentation
    /// says; the ring light surrounds the line of sight; names round-trip.
    #[test]
    fn rigs_are_as_documented() {
        let view = -direction(30.0, -90.0);
        let tent = Rig::Tent.environment(view, -90.0);
        assert_eq!(tent.radiance(-view), [0.0; 3]);
        // Overhead: the sky's 1 at the zenith (no glow, port or bulb there).
        assert!((tent.radiance(direction(90.0, 0.0))[0] - 1.0).abs() < 1e-12);
        // A lamp's glow on the tent's side.
        let side = tent.radiance(direction(20.0, 0.0))[0];
        assert!(
            (side - (0.35 + 0.65 * 20f64.to_radians().sin() + 0.8)).abs() < 1e-12,
            "{side}"
        );
        let spark = tent.radiance(direction(55.0, 45.0));
        assert!(spark[0] > 30.0, "{spark:?}");
        let ring = Rig::Ring.environment(view, -90.0);
        let (a, b) = view.any_orthonormal_pair();
        for k in 0..12 {
            let t = std::f64::consts::TAU * k as f64 / 12.0;
            let off = 18.5f64.to_radians();
            let w = (-view * off.cos() + (a * t.cos() + b * t.sin()) * off.sin()).normalize();
            assert!((ring.radiance(w)[0] - 4.03).abs() < 1e-12);
        }
        assert!((ring.radiance(-view)[0] - 0.03).abs() < 1e-15);
        for r in Rig::ALL {
            assert_eq!(Rig::parse(r.name()).unwrap(), r);
        }
        assert!(Rig::parse("disco").is_err());
    }
}
