//! The thesis's square [`Light`]: its kind (directed or undirected), size, placement and
//! rotation, and what `facetlab trace` shines ([`LightChoice`]).

use crate::error::{Error, Result};
use crate::geometry::DVec3;

/// The angles of the thesis's rotation sweep, degrees.
pub const ROTATION_ANGLES: [f64; 7] = [0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0];
/// Distance of the thesis's lights from the girdle centre, girdle diameters.
pub const LIGHT_DISTANCE: f64 = 4.0;
/// Side of the thesis's square light, girdle diameters.
pub const LIGHT_SIDE: f64 = 1.5;

/// How photons leave the light.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LightKind {
    /// All parallel to the light's axis.
    Directed,
    /// Uniform over the hemisphere in front of the light (uniform in solid angle).
    Undirected,
}

impl LightKind {
    /// `directed` or `undirected`.
    pub fn name(self) -> &'static str {
        match self {
            LightKind::Directed => "directed",
            LightKind::Undirected => "undirected",
        }
    }
}

/// What `facetlab trace` shines on a stone: one light, or the thesis's rotation sweep
/// ([`rotation_sweep`](super::rotation_sweep)) of a kind of light.
#[derive(Clone, Debug, PartialEq)]
pub enum LightChoice {
    /// One light.
    Single(Light),
    /// The rotation sweep with this kind of light.
    Rotate(LightKind),
}

/// Size of the square light.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LightSize {
    /// A square of this side (girdle diameters), centred on [`Light::centre`].
    Side(f64),
    /// The smallest square (in the light's plane, sides along its axes) that covers the
    /// stone's shadow along the light's axis; its centre is moved within the light's plane to
    /// the shadow's centre. Used for directed light: every photon is then aimed at the stone.
    CoverStone,
}

/// A square light.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Light {
    /// Directed or undirected.
    pub kind: LightKind,
    /// Centre of the square.
    pub centre: DVec3,
    /// The direction the light faces (unit; normalised when resolved).
    pub axis: DVec3,
    /// Size of the square.
    pub size: LightSize,
    /// Rotation angle of the sweep (degrees), when the light is one of its positions.
    pub angle: Option<f64>,
    /// Short description for tables and JSON.
    pub label: String,
}

impl Light {
    /// The thesis's overhead light: undirected, a square of side 1.5 D, 4 D above the girdle
    /// centre, facing down.
    pub fn overhead() -> Light {
        Light {
            kind: LightKind::Undirected,
            centre: DVec3::new(0.0, 0.0, LIGHT_DISTANCE),
            axis: DVec3::NEG_Z,
            size: LightSize::Side(LIGHT_SIDE),
            angle: None,
            label: "overhead undirected".into(),
        }
    }

    /// The thesis's off-centre light: the overhead square moved by (−1 D, −1 D) horizontally,
    /// still facing down, undirected.
    pub fn offset() -> Light {
        Light {
            centre: DVec3::new(-1.0, -1.0, LIGHT_DISTANCE),
            label: "off-centre undirected".into(),
            ..Light::overhead()
        }
    }

    /// The thesis's off-centre directed light: the off-centre square, turned to face the
    /// stone's centre (the girdle centre), every photon parallel to that axis.
    pub fn offset_directed() -> Light {
        let centre = DVec3::new(-1.0, -1.0, LIGHT_DISTANCE);
        Light {
            kind: LightKind::Directed,
            centre,
            axis: (-centre).normalize(),
            size: LightSize::Side(LIGHT_SIDE),
            angle: None,
            label: "off-centre directed".into(),
        }
    }

    /// A directed light at position `angle_deg` of the rotation sweep: a parallel beam
    /// covering the stone's shadow. `directed(0.0)` is a beam straight down over the whole
    /// stone, `directed(180.0)` straight up.
    pub fn directed(angle_deg: f64) -> Light {
        Light::rotated(LightKind::Directed, angle_deg)
    }

    /// The light of the rotation sweep at `angle_deg`: it starts straight above the stone and
    /// turns around the x axis (through the girdle centre) toward −y; at 180° it is straight
    /// below. Directed: a beam just covering the stone's shadow. Undirected: the overhead
    /// square (side 1.5 D, 4 D from the girdle centre) turned with it.
    pub fn rotated(kind: LightKind, angle_deg: f64) -> Light {
        let a = angle_deg.to_radians();
        let up = DVec3::new(0.0, -a.sin(), a.cos());
        let (size, name) = match kind {
            LightKind::Directed => (LightSize::CoverStone, "directed"),
            LightKind::Undirected => (LightSize::Side(LIGHT_SIDE), "undirected"),
        };
        Light {
            kind,
            centre: up * LIGHT_DISTANCE,
            axis: -up,
            size,
            angle: Some(angle_deg),
            label: format!("{name} at {angle_deg}°"),
        }
    }

    /// Check the light's numbers (finite centre and axis, positive side).
    pub fn validate(&self) -> Result<()> {
        if !(self.centre.is_finite() && self.axis.is_finite() && self.axis.length() > 1e-12) {
            return Err(Error::invalid(
                "light",
                "centre and axis must be finite, axis non-zero",
            ));
        }
        if let LightSize::Side(s) = self.size {
            if !(s.is_finite() && s > 0.0) {
                return Err(Error::invalid(
                    "light",
                    format!("side {s} must be a positive number"),
                ));
            }
        }
        if let Some(a) = self.angle {
            if !a.is_finite() {
                return Err(Error::invalid("light angle", "must be a number of degrees"));
            }
        }
        Ok(())
    }
}
