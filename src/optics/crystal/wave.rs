//! What a beam carries inside the crystal: a propagating [`Wave`] in one of the two modes
//! ([`WaveMode`]).

use glam::DVec3;

/// The two modes of a plane wave in a uniaxial crystal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum WaveMode {
    /// The ordinary wave: E ⊥ ĉ, index n_o in every direction.
    Ordinary,
    /// The extraordinary wave: index between n_o and n_e, walking off its wave vector.
    Extraordinary,
}

impl WaveMode {
    /// Both modes, ordinary first (the order of every two-mode array here).
    pub const BOTH: [WaveMode; 2] = [WaveMode::Ordinary, WaveMode::Extraordinary];
    /// 0 for ordinary, 1 for extraordinary.
    #[inline]
    pub fn index(self) -> usize {
        self as usize
    }
    /// `o` or `e`.
    pub fn letter(self) -> &'static str {
        match self {
            WaveMode::Ordinary => "o",
            WaveMode::Extraordinary => "e",
        }
    }
}

/// A propagating wave inside the crystal: what a beam carries between facets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wave {
    /// Its mode.
    pub mode: WaveMode,
    /// Wave vector (units of k₀; `|k|` is the mode's index along it).
    pub k: DVec3,
    /// Ray direction: the unit Poynting vector, along which the beam moves.
    pub ray: DVec3,
    /// Unit electric field (real for a propagating wave in a lossless crystal).
    pub field: DVec3,
}
