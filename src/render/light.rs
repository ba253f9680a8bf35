//! The lights a picture is drawn under ([`Light`]): their names, channels and false-colour
//! palettes, and each one's channel values for light arriving from a direction, over the
//! radiance functions of [`lighting`](super::lighting).

use super::lighting::{self, aset_shares_in, soft_above, Lighting};
use crate::error::{Error, Result};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// The lighting environment of a picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Light {
    /// GemRay's ISO lighting: radiance 1 over the upper hemisphere (grey image).
    Iso,
    /// GemRay's COS lighting: radiance = cos(zenith angle) (grey image).
    Cos,
    /// ASET false colour: blue for light from 75–90° elevation, red 45–75°, green 0–45°,
    /// black for leakage (below the horizon) and for the viewer's dark port at the top.
    Aset,
    /// IdealScope: red for returned light, white for leakage, black for the viewer's head.
    #[serde(rename = "idealscope")]
    IdealScope,
    /// The hearts & arrows viewer face-down: the stone turned over, pavilion to the viewer.
    Hearts,
    /// The hearts & arrows viewer face-up.
    Arrows,
    /// Spectral tracing under the spot lights
    /// ([`Spot::default_set`](super::lighting::Spot::default_set)), shown in sRGB.
    Fire,
}

/// The hearts & arrows viewer, face-up (arrows): half-angle of the dark tube around the line of
/// sight as the stone sees it, degrees. Sight lines that leave the stone within it see the
/// viewer's dark top; between it and [`SCOPE_WALL_DEG`] they see the lit reflector.
///
/// Face-up, a round brilliant's pavilion mains send the sight lines through the table back
/// within 8–20° of the line of sight (the arrows' shafts, 12–20°, and heads, 8–12°): a tube
/// of 20° shows them dark.
pub const SCOPE_TUBE_DEG: f64 = 20.0;

/// The hearts & arrows viewer, face-down (hearts): half-angle of the viewer's dark aperture as
/// the stone sees it, degrees.
///
/// Table-down, a round brilliant returns the sight lines entering its pavilion in two narrow
/// groups (measured on `tolkowsky` and `ags-ideal`, share of the light in brackets): within
/// 0–4° of the line of sight (19 %: the dark eight-pointed star between the hearts) and at
/// 8–12° (18 %: the eight hearts); 4–8° carries 0.3 %. An aperture of 6° separates them. With
/// the arrows' 20° both groups are dark and no heart shows; with 6° face-up the arrows would
/// be lit. No one aperture shows both patterns, and no viewer's dimensions are published that
/// we could find, so each view has its own (`--head-shadow` changes it).
pub const HEARTS_APERTURE_DEG: f64 = 6.0;

/// The hearts & arrows viewer: angle from the line of sight beyond which the stone sees the
/// viewer's dark lower wall and stage instead of its lit reflector, degrees. It keeps the
/// external reflection of the facets (a pavilion main at 41° reflects the line of sight 82°
/// away) dark, as in the viewer, where the patterns are seen on black.
pub const SCOPE_WALL_DEG: f64 = 60.0;

/// Default half-angle of the ASET's dark viewing port and of IdealScope's head obstruction,
/// degrees.
pub const PORT_DEG: f64 = 10.0;

/// ASET's display colours (sRGB-encoded): blue, red, green, leak (black), port (black).
pub const ASET_COLOURS: [[f64; 3]; 5] = [
    [0.10, 0.30, 1.0],
    [0.90, 0.08, 0.08],
    [0.10, 0.72, 0.16],
    [0.0, 0.0, 0.0],
    [0.0, 0.0, 0.0],
];

/// IdealScope's display colours (sRGB-encoded): returned (red), leak (white), head (black).
pub const IDEALSCOPE_COLOURS: [[f64; 3]; 3] =
    [[0.86, 0.10, 0.12], [1.0, 1.0, 1.0], [0.0, 0.0, 0.0]];

impl Light {
    /// Every light, in the order the command line lists them.
    pub const ALL: [Light; 7] = [
        Light::Iso,
        Light::Cos,
        Light::Aset,
        Light::IdealScope,
        Light::Hearts,
        Light::Arrows,
        Light::Fire,
    ];

    /// The name used on the command line and in files.
    pub fn name(self) -> &'static str {
        match self {
            Light::Iso => "iso",
            Light::Cos => "cos",
            Light::Aset => "aset",
            Light::IdealScope => "idealscope",
            Light::Hearts => "hearts",
            Light::Arrows => "arrows",
            Light::Fire => "fire",
        }
    }

    /// A short title for menus ([`crate::render::lights`]).
    pub fn label(self) -> &'static str {
        match self {
            Light::Iso => "ISO (uniform sky)",
            Light::Cos => "COS (cosine sky)",
            Light::Aset => "ASET",
            Light::IdealScope => "IdealScope",
            Light::Hearts => "Hearts (face down)",
            Light::Arrows => "Arrows (face up)",
            Light::Fire => "Fire (spot lights)",
        }
    }

    /// What it is, in a few words, for help texts ([`crate::render::lights`]).
    pub fn about(self) -> &'static str {
        match self {
            Light::Iso => "uniform sky",
            Light::Cos => "cosine sky",
            Light::Aset => "false colour by the elevation the light comes from",
            Light::IdealScope => "red returned, white leak",
            Light::Hearts => "face-down in the hearts & arrows viewer",
            Light::Arrows => "face-up in it",
            Light::Fire => "spectral, under spot lights",
        }
    }

    /// The exposure a picture under it is best first shown at: the ISO sky returns ~0.9 of a
    /// white diffuser from a good stone, so at 1 its picture is nearly white and the contrast
    /// is hard to see; the fire picture is dark flashes on black. `None` for the false colours,
    /// which take no exposure.
    pub fn first_exposure(self) -> Option<f64> {
        match self {
            Light::Iso => Some(0.7),
            Light::Cos | Light::Hearts | Light::Arrows => Some(1.0),
            Light::Fire => Some(1.5),
            Light::Aset | Light::IdealScope => None,
        }
    }

    /// The light called `name` (as [`Light::name`] gives it).
    pub fn parse(name: &str) -> Result<Light> {
        Light::ALL
            .into_iter()
            .find(|l| l.name() == name)
            .ok_or_else(|| {
                Error::invalid(
                    "light",
                    format!(
                        "unknown light {name:?}; allowed {}",
                        Light::ALL.map(Light::name).join(", ")
                    ),
                )
            })
    }

    /// Default head shadow (ISO, COS, fire: none, an open sky; the scores count light under a
    /// 15° head shadow by default, which a picture draws when given it; ASET's port and IdealScope's
    /// head: [`PORT_DEG`]; the hearts & arrows viewer's dark tube: [`SCOPE_TUBE_DEG`] face-up,
    /// [`HEARTS_APERTURE_DEG`] face-down).
    pub fn default_head_shadow_deg(self) -> f64 {
        match self {
            Light::Aset | Light::IdealScope => PORT_DEG,
            Light::Arrows => SCOPE_TUBE_DEG,
            Light::Hearts => HEARTS_APERTURE_DEG,
            _ => 0.0,
        }
    }

    /// Number of channels of the picture: 1 (grey), 3 (fire: linear sRGB, IdealScope:
    /// returned, leak, head) or 5 (ASET: blue, red, green, leak, port).
    pub fn channels(self) -> usize {
        match self {
            Light::Iso | Light::Cos | Light::Hearts | Light::Arrows => 1,
            Light::Fire | Light::IdealScope => 3,
            Light::Aset => 5,
        }
    }

    /// The picture's channel values for light arriving from direction `w` (world coordinates,
    /// z up, the viewer straight above; `light` gives the head shadow), and the value that
    /// counts toward [`Stats::mean`](super::Stats::mean):
    ///
    /// * `iso`, `cos`: the radiance of [`Lighting::iso`] or [`Lighting::cos`];
    /// * `hearts`, `arrows`: radiance 1 from the viewer's lit reflector, 0 within the head
    ///   shadow's angle of the line of sight (the dark tube: by default [`SCOPE_TUBE_DEG`]
    ///   face-up, [`HEARTS_APERTURE_DEG`] face-down) and beyond [`SCOPE_WALL_DEG`] from it,
    ///   soft edges;
    /// * `aset`: the shares of the ASET bins (blue, red, green, leak, port; the port is the
    ///   head shadow's cone), which add up to 1; the mean counts blue, red and green;
    /// * `idealscope`: returned (above the horizon, outside the head), leak (below the
    ///   horizon) and head shares, adding up to 1; the mean counts the returned share.
    ///
    /// Not used for [`Light::Fire`], which is spectral (zeros).
    #[inline]
    pub fn shade(self, light: &Lighting, w: DVec3) -> ([f64; 5], f64) {
        match self {
            Light::Iso => {
                let v = light.iso(w);
                ([v, 0.0, 0.0, 0.0, 0.0], v)
            }
            Light::Cos => {
                let v = light.cos(w);
                ([v, 0.0, 0.0, 0.0, 0.0], v)
            }
            Light::Hearts | Light::Arrows => {
                let zen = 90.0 - lighting::elevation_deg(w);
                let v = soft_above(zen, light.head_shadow_deg())
                    * (1.0 - soft_above(zen, SCOPE_WALL_DEG));
                ([v, 0.0, 0.0, 0.0, 0.0], v)
            }
            Light::Aset => {
                let s = aset_shares_in(w, light.head_cone());
                (s, s[0] + s[1] + s[2])
            }
            Light::IdealScope => {
                let returned = light.iso(w);
                let sky = soft_above(lighting::elevation_deg(w), 0.0);
                let leak = 1.0 - sky;
                (
                    [returned, leak, (sky - returned).max(0.0), 0.0, 0.0],
                    returned,
                )
            }
            Light::Fire => ([0.0; 5], 0.0),
        }
    }

    /// Display colours (sRGB-encoded, 0–1) of the channels of a false-colour picture (ASET,
    /// IdealScope): a pixel shows the mix of these by its channels' shares.
    pub fn false_colours(self) -> &'static [[f64; 3]] {
        match self {
            Light::Aset => &ASET_COLOURS,
            Light::IdealScope => &IDEALSCOPE_COLOURS,
            _ => &[],
        }
    }
}
