//! Overhead light return: the share of a parallel beam from straight above that leaves into
//! the upper hemisphere (the figure for cross-checks with the photon tracer).

use super::config::ScoreConfig;
use crate::beam::{ExitBeam, ExitSink, Frame, Medium, Stone, TraceOptions};
use crate::geometry::{canonical, Polyhedron};
use crate::optics::Material;
use glam::DVec2;

/// Share of a parallel beam from straight above, over the stone's projected area, that leaves
/// into the upper hemisphere (external reflection included), for `material` at
/// `wavelength_nm`, with the default tracer settings.
pub fn overhead_light_return(
    solid: &Polyhedron,
    material: &Material,
    wavelength_nm: f64,
    polarization: bool,
) -> f64 {
    let opts = TraceOptions {
        polarization,
        split_threshold: ScoreConfig::default().face_up_split_threshold,
        ..Default::default()
    };
    let axis = material.uniaxial.as_ref().map_or(glam::DVec3::Z, |u| {
        canonical::canonical_axis(solid, u.axis.vector())
    });
    let solid = canonical::canonical(solid);
    let medium = crate::beam::Medium::of(material, wavelength_nm, axis, 0.0, false);
    overhead_light_return_with(&Stone::new(&solid), &medium, &opts)
}

/// [`overhead_light_return`] on a prepared stone through `medium` (an index, or a
/// birefringent crystal) with explicit settings.
pub fn overhead_light_return_with(stone: &Stone, medium: &Medium, opts: &TraceOptions) -> f64 {
    struct Up(f64);
    impl ExitSink for Up {
        fn exit(&mut self, e: &ExitBeam, _: &[DVec2]) {
            if e.direction.z > 0.0 {
                self.0 += e.power;
            }
        }
    }
    let mut up = Up(0.0);
    let opts = TraceOptions {
        footprints: false,
        ..*opts
    };
    let (stats, _) = stone.trace_medium_into(&Frame::overhead(), medium, &opts, &mut up, false);
    if stats.power_in > 0.0 {
        up.0 / stats.power_in
    } else {
        0.0
    }
}
