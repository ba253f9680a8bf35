//! [`Absorption`] written as text: `none`, `thesis` or `beer:K`, as `facetlab trace
//! --absorption` takes it.

use super::Absorption;
use crate::error::{Error, Result};
use crate::io::text::number;

impl Absorption {
    /// Read `none`, `thesis` or `beer:K` (K ≥ 0 per girdle diameter; any case); the error
    /// names `field`.
    ///
    /// ```
    /// use facetlab::photon::Absorption;
    /// assert_eq!(Absorption::parse("--absorption", "Beer:0.5").unwrap(), Absorption::Beer(0.5));
    /// assert!(Absorption::parse("--absorption", "some").is_err());
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
            _ => {
                return Err(Error::invalid(
                    field,
                    format!(
                    "`{s}` is not allowed; use none, thesis or beer:K (K >= 0 per girdle diameter)"
                ),
                ))
            }
        })
    }
}
