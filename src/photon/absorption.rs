//! [`Absorption`] written as text: `none`, `thesis`, `beer:K` or `colour[:W]`, as `facetlab
//! trace --absorption` takes it.

use crate::error::{Error, Result};
use crate::io::text::number;
use crate::optics::Absorption;

impl Absorption {
    /// Read `none`, `thesis`, `beer:K` (K ≥ 0 per girdle diameter) or `colour[:W]` (the
    /// material's body colour in a stone W mm wide, default 6.5; also `color`), any case; the
    /// error names `field`.
    ///
    /// ```
    /// use facetlab::photon::Absorption;
    /// assert_eq!(Absorption::parse("absorption", "Beer:0.5").unwrap(), Absorption::Beer(0.5));
    /// assert!(Absorption::parse("absorption", "some").is_err());
    /// assert_eq!(
    ///     Absorption::parse("absorption", "colour:8").unwrap(),
    ///     Absorption::Body { width_mm: 8.0 }
    /// );
    /// ```
    pub fn parse(field: &str, s: &str) -> Result<Absorption> {
        Ok(match s.trim().to_ascii_lowercase().as_str() {
            "none" => Absorption::None,
            "thesis" => Absorption::Thesis,
            t if t.starts_with("beer:") => Absorption::Beer(number(
                field,
                &t[5..],
                0.0,
                1e6,
                "beer:K with K (per girdle diameter)",
            )?),
            "colour" | "color" => Absorption::Body {
                width_mm: crate::optics::StoneSize::DEFAULT_WIDTH_MM,
            },
            t if t.starts_with("colour:") || t.starts_with("color:") => Absorption::Body {
                width_mm: number(
                    field,
                    t.split_once(':').map_or("", |p| p.1),
                    1e-3,
                    999.0,
                    "colour:W with the stone's width W in mm",
                )?,
            },
            _ => {
                return Err(Error::invalid(
                    field,
                    format!(
                    "`{s}` is not allowed; use none, thesis, beer:K (K >= 0 per girdle diameter) or colour[:W] (the material's body colour, a stone W mm wide, default 6.5)"
                ),
                ))
            }
        })
    }
}
