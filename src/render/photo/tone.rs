//! From linear radiance to display values ([`Tone`]): the photograph's exposure and tone
//! curve, and its 8-bit sRGB and linear HDR forms.

use super::Photo;
use crate::error::{Error, Result};
use crate::io::hdr::HdrImage;
use crate::optics::color;
use glam::DVec3;
use rayon::prelude::*;

/// How linear radiance (relative to a white diffuser under the ISO sky) becomes display
/// values, after multiplying by the exposure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Tone {
    /// Linear sRGB clipped to [0, 1], then sRGB-encoded (what the laboratory pictures do).
    Clip,
    /// A film-like curve: each linear sRGB channel `x` becomes
    /// `x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14)` (Narkowicz's 2015 fit of the ACES
    /// reference rendering transform), clipped to [0, 1], then sRGB-encoded: highlights
    /// roll off instead of clipping (a white diffuser at exposure 1 shows 0.80 linear),
    /// and very bright sparks go white as on film.
    Filmic,
}

impl Tone {
    /// Every curve, in the order the command line lists them.
    pub const ALL: [Tone; 2] = [Tone::Filmic, Tone::Clip];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Tone::Clip => "clip",
            Tone::Filmic => "filmic",
        }
    }

    /// The curve called `name`; the error names `field`.
    pub fn parse(field: &str, name: &str) -> Result<Tone> {
        let n = name.trim().to_ascii_lowercase();
        Tone::ALL
            .into_iter()
            .find(|t| t.name() == n)
            .ok_or_else(|| {
                Error::invalid(
                    field,
                    format!("`{name}` is not allowed; use filmic or clip"),
                )
            })
    }

    /// The display value (linear, [0, 1]) of linear value `x`.
    #[inline]
    pub fn curve(self, x: f64) -> f64 {
        let x = x.max(0.0);
        match self {
            Tone::Clip => x.min(1.0),
            Tone::Filmic => {
                ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0)
            }
        }
    }
}

impl Photo {
    /// Linear sRGB of pixel `k` (row-major from the bottom).
    #[inline]
    pub fn linear_rgb(&self, k: usize) -> DVec3 {
        color::xyz_to_linear_srgb(DVec3::new(
            self.xyz[0].data[k],
            self.xyz[1].data[k],
            self.xyz[2].data[k],
        ))
    }

    /// 8-bit sRGB, rows from the top, 3 bytes per pixel: linear sRGB times `exposure`
    /// through `tone`, sRGB-encoded.
    pub fn to_srgb8(&self, exposure: f64, tone: Tone) -> Vec<u8> {
        let n = self.size();
        let mut out = vec![0u8; n * n * 3];
        out.par_chunks_mut((n * 3).max(1))
            .enumerate()
            .for_each(|(j, row)| {
                for (i, px) in row.chunks_exact_mut(3).enumerate() {
                    let k = (n - 1 - j) * n + i;
                    let c = self.linear_rgb(k) * exposure;
                    for (x, v) in px.iter_mut().zip([c.x, c.y, c.z]) {
                        *x = color::srgb8(tone.curve(v));
                    }
                }
            });
        out
    }

    /// The linear picture (linear sRGB radiance relative to a white diffuser under the ISO
    /// sky, before exposure and tone), rows from the top, for `--hdr-out`.
    pub fn to_hdr(&self) -> HdrImage {
        let n = self.size();
        let mut rgb = Vec::with_capacity(n * n);
        for j in 0..n {
            for i in 0..n {
                let c = self.linear_rgb((n - 1 - j) * n + i).max(DVec3::ZERO);
                rgb.push([c.x as f32, c.y as f32, c.z as f32]);
            }
        }
        HdrImage {
            width: n,
            height: n,
            rgb,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The filmic curve rises from 0, rolls off smoothly and never passes 1; clip is the
    /// identity on [0, 1].
    #[test]
    fn curves() {
        let mut prev = -1.0;
        for k in 0..=10000 {
            let x = k as f64 * 0.002;
            let y = Tone::Filmic.curve(x);
            assert!(y >= prev && (0.0..=1.0).contains(&y));
            prev = y;
        }
        assert_eq!(Tone::Filmic.curve(0.0), 0.0);
        assert!((Tone::Filmic.curve(1.0) - 0.8037).abs() < 1e-3);
        assert_eq!(Tone::Clip.curve(0.5), 0.5);
        assert_eq!(Tone::Clip.curve(3.0), 1.0);
        assert_eq!(Tone::parse("tone", "FILMIC").unwrap(), Tone::Filmic);
        assert!(Tone::parse("tone", "hdr").is_err());
    }
}
