//! What a birefringent photon trace needs of its material, set up once per run: read by the
//! kernel (`kernel.rs`), which picks the birefringent chunks of `crystal.rs` when it is there.

use crate::geometry::DVec3;
use crate::optics::{Dispersion, Material};

/// What a birefringent trace needs of the material: both indices' dispersion, the optic
/// axis (in the traced solid's coordinates) and each polarization's absorption.
pub(crate) struct CrystalSetup {
    pub(super) ordinary: Dispersion,
    pub(super) extraordinary: Dispersion,
    pub(super) axis: DVec3,
    pub(super) colour_o: Option<crate::optics::BodyColour>,
    pub(super) colour_e: Option<crate::optics::BodyColour>,
}

impl CrystalSetup {
    /// The setup of a material traced birefringent (`None` otherwise, or when its two
    /// indices are one).
    pub(crate) fn of(m: &Material) -> Option<CrystalSetup> {
        let u = m.uniaxial.as_ref().filter(|u| u.traced)?;
        Some(CrystalSetup {
            ordinary: m.dispersion.clone(),
            extraordinary: u.extraordinary.clone(),
            axis: u.axis.vector(),
            colour_o: m.colour.clone(),
            colour_e: m.colour_e().cloned(),
        })
    }
}
