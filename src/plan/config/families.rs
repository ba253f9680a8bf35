//! The families a plan may ask for.

use crate::cut::family;
use crate::error::Error;

/// Families to plan, each a known family named once; the error says which is not.
pub fn check_families(names: &[String]) -> std::result::Result<Vec<String>, String> {
    if names.is_empty() {
        return Err("name at least one family".into());
    }
    for (i, name) in names.iter().enumerate() {
        family(name).map_err(|e| match e {
            Error::Invalid { message, .. } => message,
            other => other.to_string(),
        })?;
        if names[..i].contains(name) {
            return Err(format!(
                "`{name}` is named twice; name each family once (its plans would be written over each other)"
            ));
        }
    }
    Ok(names.to_vec())
}
