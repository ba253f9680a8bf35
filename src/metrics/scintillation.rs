//! Scintillation: the azimuths toward which the stone is rocked ([`scintillation_turns`]) and
//! the change of its spot-lit images from pose to pose ([`scintillation_of`]).

use super::config::ScoreConfig;
use crate::render::raster::Raster;

/// The azimuths toward which scintillation rocks the stone, degrees:
/// `360° · j / `[`ScoreConfig::scintillation_turns`]; the spot lights turn with them.
pub fn scintillation_turns(cfg: &ScoreConfig) -> Vec<f64> {
    let k = cfg.scintillation_turns.max(1);
    (0..k).map(|j| 360.0 * j as f64 / k as f64).collect()
}

/// `Σⱼ Σₖ Σₚ |Iⱼ,ₖ₊₁ − Iⱼ,ₖ| / Σⱼ Σₖ Σₚ (Iⱼ,ₖ₊₁ + Iⱼ,ₖ)` over sequences `j` of images
/// (consecutive images of each sequence are compared); 0 without light.
pub fn scintillation_of(sequences: &[&[&Raster]]) -> f64 {
    let (mut diff, mut sum) = (0.0, 0.0);
    for images in sequences {
        for pair in images.windows(2) {
            for (a, b) in pair[0].data.iter().zip(&pair[1].data) {
                diff += (a - b).abs();
                sum += a + b;
            }
        }
    }
    if sum > 0.0 {
        (diff / sum).min(1.0)
    } else {
        0.0
    }
}
