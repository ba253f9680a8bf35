//! `[cut]`: the cut space (a family) and the start cut.

use super::At;
use crate::cut::{family, CutSpace};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::sync::Arc;

/// `[cut]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCut {
    /// Family name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub family: Option<String>,
    /// Parameters of the start cut (fixed ones and the free ones' start values).
    #[serde(default)]
    pub params: BTreeMap<String, f64>,
}

/// Validate `[cut]`: the cut space and the start cut's full parameter set (defaults filled in).
pub(super) fn validate(rc: &RawCut, at: At) -> Result<(Arc<dyn CutSpace>, BTreeMap<String, f64>)> {
    let fam_name = rc.family.as_deref().ok_or_else(|| {
        Error::invalid(
            at("cut.family"),
            "missing: give `[cut]` with `family = \"round-brilliant\"` (or another family)",
        )
    })?;
    let fam = family(fam_name).map_err(|e| match e {
        Error::Invalid { message, .. } => Error::invalid(at("cut.family"), message),
        other => other,
    })?;
    let space: Arc<dyn CutSpace> = Arc::new(*fam);
    let start = space.complete(&rc.params).map_err(|e| match e {
        Error::Invalid { field, message } => {
            Error::invalid(at(&format!("cut.params.{field}")), message)
        }
        other => other,
    })?;
    Ok((space, start))
}
