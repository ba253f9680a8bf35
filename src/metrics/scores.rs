//! What a score returns: [`Scores`], with each pose's light return ([`PoseScore`]) and the
//! ASET-style shares ([`Aset`]).

use serde::{Deserialize, Serialize};

/// ASET-style shares of the face-up view, as the ASET picture ([`crate::render::Light::Aset`])
/// counts them with its default port ([`crate::render::PORT_DEG`], 10°); they add up to 1.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Aset {
    /// Light from 75–80° elevation (75–90° outside the viewer's port).
    pub blue: f64,
    /// Light from 45–75° elevation.
    pub red: f64,
    /// Light from 0–45° elevation.
    pub green: f64,
    /// Light from below the horizon (seen through the stone).
    pub leak: f64,
    /// The viewer's dark port: light from within [`crate::render::PORT_DEG`] of the zenith,
    /// which a real ASET shows black (blue + port is all of 75–90°).
    #[serde(default)]
    pub port: f64,
}

/// Light return of one pose of the brilliance average: the mean of the pose's ISO and COS
/// pictures ([`crate::render::Stats::mean`]). A pose that one of the stone's symmetries maps
/// onto another (10° toward 72° and toward 27° on a round brilliant) returns the same light,
/// and both are traced once, at the representative of [`symmetric_pose`]'s rule: the picture
/// drawn of that representative is the pose's exactly; the pose's own picture agrees to the
/// tracer's narrow-beam approximation (about 1e-4).
///
/// [`symmetric_pose`]: super::symmetric_pose
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseScore {
    /// Tilt of the pose, degrees.
    pub tilt_deg: f64,
    /// Azimuth the table tips toward, degrees.
    pub azimuth_deg: f64,
    /// Light return under ISO lighting, [0, 1].
    pub iso: f64,
    /// Light return under COS lighting, [0, 1].
    pub cos: f64,
}

/// The scores of one cut (see the [module documentation](super) for definitions and
/// ranges).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Scores {
    /// Share of overhead parallel light leaving upward, [0, 1].
    pub overhead_light_return: f64,
    /// (ISO + COS) / 2, [0, 1].
    pub brilliance: f64,
    /// Light return under ISO lighting, averaged over poses, [0, 1].
    pub brilliance_iso: f64,
    /// Light return under COS lighting, averaged over poses, [0, 1].
    pub brilliance_cos: f64,
    /// Luminance-weighted CIELAB chroma per unit face-up area under spot lights, ≥ 0.
    pub fire: f64,
    /// Change of the spot-light pattern while rocking, [0, 1].
    pub scintillation: f64,
    /// ASET-style shares of the face-up view.
    pub aset: Aset,
    /// The poses of the brilliance average, in [`ScoreConfig::tilts`] order, each with its
    /// ISO and COS light return (brilliance_iso and brilliance_cos are their means).
    ///
    /// [`ScoreConfig::tilts`]: super::ScoreConfig::tilts
    #[serde(default)]
    pub poses: Vec<PoseScore>,
    /// A coloured stone's face-up colour (its material has a body colour): L*, C*, h°, the
    /// L* spread, extinction and windowing of its face-up ISO picture drawn in colour on the
    /// colour grid ([`crate::render::COLOUR_GRID`], whatever the resolution) at fire's split
    /// threshold ([`crate::render::ColourStats`]); absent when colourless.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub colour: Option<crate::render::ColourStats>,
}
