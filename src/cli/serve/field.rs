//! A field of a request body as sent, kept to quote it in the error (read by `request.rs`
//! and the other bodies of the API).

use serde::Deserialize;
use serde_json::Value;

/// A field of a body as sent: absent, of the expected JSON type, or anything else (`null`
/// included), kept to quote it in the error.
#[derive(Debug, Default, Deserialize)]
#[serde(untagged)]
pub enum Field<T> {
    /// Of the expected type.
    Given(T),
    /// Of another type.
    Other(Value),
    /// Not in the body (never deserialized: the default).
    #[default]
    #[serde(skip)]
    Absent,
}

impl<T> Field<T> {
    /// `Ok(None)` when absent or `null`, `Ok(Some)` when of the expected type, else the value
    /// sent.
    pub fn given(&self) -> Result<Option<&T>, &Value> {
        match self {
            Field::Absent | Field::Other(Value::Null) => Ok(None),
            Field::Given(t) => Ok(Some(t)),
            Field::Other(v) => Err(v),
        }
    }

    /// Whether the field was sent (of any type but `null`).
    pub fn sent(&self) -> bool {
        !matches!(self.given(), Ok(None))
    }
}
