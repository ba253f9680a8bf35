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

/// A message on one line, any setting named inside it ([`setting`]) left unspelled by its
/// face written as the setting's own name.
fn one_line(s: &str) -> String {
    spell_settings(s, &|_| None)
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// A setting named inside a message (`⟨rough size⟩`), for the face that shows the message to
/// spell its own way: the command line's flag (`--size-mm`), the Python package's keyword
/// argument (`size_mm`); unspelled, the message shows the setting's name (`rough size`).
pub fn setting(name: &str) -> String {
    format!("⟨{name}⟩")
}

/// `text` with every setting named inside it ([`setting`]) spelled by `spell`, or by its own
/// name where `spell` knows none.
///
/// ```
/// use facetlab::error::{setting, spell_settings};
/// let text = format!("give {} L", setting("rough size"));
/// let keyword = |s: &str| (s == "rough size").then(|| "size_mm".to_string());
/// assert_eq!(spell_settings(&text, &keyword), "give size_mm L");
/// assert_eq!(spell_settings(&text, &|_| None), "give rough size L");
/// ```
pub fn spell_settings(text: &str, spell: &dyn Fn(&str) -> Option<String>) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find('⟨') {
        out.push_str(&rest[..i]);
        let after = &rest[i + '⟨'.len_utf8()..];
        match after.find('⟩') {
            Some(j) => {
                let name = &after[..j];
                out.push_str(&spell(name).unwrap_or_else(|| name.to_string()));
                rest = &after[j + '⟩'.len_utf8()..];
            }
            None => {
                out.push_str(&rest[i..]);
                rest = "";
            }
        }
    }
    out.push_str(rest);
    out
}

impl Error {
    /// The error with the settings named inside its message spelled by `spell`
    /// ([`spell_settings`]).
    pub fn spell_settings(self, spell: &dyn Fn(&str) -> Option<String>) -> Error {
        match self {
            Error::Io { path, message } => Error::Io {
                path,
                message: spell_settings(&message, spell),
            },
            Error::Parse { source, message } => Error::Parse {
                source,
                message: spell_settings(&message, spell),
            },
            Error::Invalid { field, message } => Error::Invalid {
                field,
                message: spell_settings(&message, spell),
            },
            Error::Geometry(m) => Error::Geometry(spell_settings(&m, spell)),
        }
    }
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
