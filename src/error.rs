//! The crate's error type: every message is one line that names the file, field or flag and
//! says what is allowed. The binary prints it and exits with code 2.

use std::fmt;

/// A user-facing error. `Display` gives a single line.
#[derive(Debug, Clone, PartialEq)]
pub enum Error {
    /// Reading or writing a file failed (missing, unreadable, not writable).
    Io {
        /// The file.
        path: String,
        /// What went wrong.
        message: String,
    },
    /// A file or value could not be parsed; `source` names the file (and line) or flag.
    Parse {
        /// File (with `:line` when known) or flag name.
        source: String,
        /// What went wrong and what is allowed.
        message: String,
    },
    /// A value is out of its allowed range or otherwise invalid; `field` names it.
    Invalid {
        /// Field, key or flag.
        field: String,
        /// What went wrong and what is allowed.
        message: String,
    },
    /// The facet planes do not make a valid convex solid.
    Geometry(String),
}

impl Error {
    /// Shorthand for [`Error::Invalid`].
    pub fn invalid(field: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Invalid {
            field: field.into(),
            message: message.into(),
        }
    }
    /// Shorthand for [`Error::Parse`].
    pub fn parse(source: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Parse {
            source: source.into(),
            message: message.into(),
        }
    }
    /// Shorthand for [`Error::Io`].
    pub fn io(path: impl Into<String>, err: impl fmt::Display) -> Self {
        Error::Io {
            path: path.into(),
            message: err.to_string(),
        }
    }
    /// Prefix the message with a context (a file name, a cut name).
    pub fn context(self, ctx: &str) -> Self {
        match self {
            Error::Geometry(m) => Error::Geometry(format!("{ctx}: {m}")),
            Error::Invalid { field, message } => Error::Invalid {
                field: format!("{ctx}: {field}"),
                message,
            },
            other => other,
        }
    }
}

fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Io { path, message } => write!(f, "{path}: {}", one_line(message)),
            Error::Parse { source, message } => write!(f, "{source}: {}", one_line(message)),
            Error::Invalid { field, message } => write!(f, "{field}: {}", one_line(message)),
            Error::Geometry(m) => write!(f, "geometry: {}", one_line(m)),
        }
    }
}

impl std::error::Error for Error {}

/// Result with the crate's [`Error`].
pub type Result<T> = std::result::Result<T, Error>;

/// A number as a message shows it: the shortest form that reads back to the same value, in
/// exponent form when that is shorter than the digits (`1e308`, `1e-308`, `2.5e-9`), never
/// the hundreds of digits `{}` prints for them.
///
/// ```
/// use facetlab::error::shown;
/// assert_eq!(shown(0.57), "0.57");
/// assert_eq!(shown(40.0), "40");
/// assert_eq!(shown(1e308), "1e308");
/// assert_eq!(shown(-1e-308), "-1e-308");
/// assert_eq!(shown(123456.0), "123456");
/// assert_eq!(shown(f64::INFINITY), "inf");
/// ```
pub fn shown(v: f64) -> String {
    let plain = format!("{v}");
    let exp = format!("{v:e}");
    if exp.len() < plain.len() {
        exp
    } else {
        plain
    }
}
