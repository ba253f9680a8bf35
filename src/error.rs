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

/// Declares [`Setting`] from one list, so its variants, [`Setting::ALL`] and its names cannot
/// disagree.
macro_rules! settings {
    ($($(#[doc = $doc:literal])* $v:ident => $name:literal,)*) => {
        /// Every setting the library names in its errors and notes (an error's field, or a
        /// setting inside its text by [`setting`]), each by its own name ([`Setting::name`]).
        /// Each face spells every one its own way by a `match` over this enum with no wildcard
        /// arm (the command line's flags, the web page's request fields, the Python package's
        /// keyword arguments), so a setting added here without a spelling in a face does not
        /// compile.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Setting {
            $($(#[doc = $doc])* $v,)*
        }

        impl Setting {
            /// Every setting, in the order of the enum.
            pub const ALL: &'static [Setting] = &[$(Setting::$v,)*];

            /// Its name, as the library's errors and notes give it.
            pub const fn name(self) -> &'static str {
                match self {
                    $(Setting::$v => $name,)*
                }
            }
        }
    };
}

settings! {
    /// The angle of a trace's light.
    LightAngle => "light angle",
    /// A trace's photon count.
    PhotonCount => "photon count",
    /// How many interactions a ray is followed through.
    TraceDepth => "trace depth",
    /// How a stone's absorption is traced.
    AbsorptionModel => "absorption model",
    /// A trace at one wavelength.
    FixedWavelength => "fixed wavelength",
    /// A material given by its refractive index.
    RefractiveIndex => "refractive index",
    /// A material given by its name.
    Material => "material",
    /// A rough's largest extent, mm.
    RoughSize => "rough size",
    /// A rough's inclusion, a mesh.
    InclusionMesh => "inclusion mesh",
    /// The score a sweep maps.
    SweepScore => "sweep score",
    /// A sweep's second axis.
    SweepYAxis => "sweep y axis",
    /// A sweep's grid (both axes).
    SweepGrid => "sweep grid",
    /// A run's folder.
    RunFolder => "run folder",
    /// A grid's first axis.
    FirstAxis => "first axis",
    /// A grid's axes.
    GridAxes => "grid axes",
    /// The point a slice of a grid is taken at.
    SlicePoint => "slice point",
    /// The axes of a map of a grid.
    MapAxes => "map axes",
    /// The folder a shard writes.
    ShardFolder => "shard folder",
    /// Which shard of a sweep a run is.
    Shard => "shard",
    /// A batch's lines of output.
    BatchOutput => "batch output",
    /// A score's JSON document.
    ScoreDocument => "score document",
    /// The file a command writes (a picture, a page, a cut).
    Output => "output",
    /// The JSON document written beside the output or the printed table.
    JsonOutput => "json output",
    /// A photograph's linear radiance (OpenEXR or Radiance HDR).
    HdrOutput => "hdr output",
    /// The folder of a trace's charts.
    PlotsFolder => "plots folder",
    /// Replacing existing files.
    Force => "force",
    /// A laboratory picture rocked back and forth (an animated PNG).
    PictureRock => "picture rock",
    /// A photograph's turntable animation (an animated PNG or GIF).
    PictureTurn => "picture turn",
    /// A cut's parameter or a design's tier, `KEY=VALUE`.
    CutParameter => "cut parameter",
    /// A picture's light (a laboratory light, a photographic rig, `studio` or `env:FILE`).
    PictureLight => "picture light",
    /// A picture's pixels per side.
    PictureSize => "picture size",
    /// The stone's tilt, `DEG[@AZ]`.
    PictureTilt => "picture tilt",
    /// A laboratory picture's head shadow, degrees.
    PictureHeadShadow => "picture head-shadow",
    /// A picture's brightness factor.
    PictureExposure => "picture exposure",
    /// A photograph's camera direction, `ELEV[@AZ]`.
    PictureView => "picture view",
    /// A photograph's camera distance, mm.
    PictureDistance => "picture distance",
    /// A photograph's entrance pupil, mm (0: a pinhole).
    PictureAperture => "picture aperture",
    /// A photograph's ground.
    PictureGround => "picture ground",
    /// A photograph's gap under the stone, girdle diameters.
    PictureGroundGap => "picture ground-gap",
    /// A photograph's light turned about the vertical, degrees.
    PictureLightRotation => "picture light-rotation",
    /// A photograph's tone curve.
    PictureTone => "picture tone",
    /// A photograph's wavelength bands.
    PictureBands => "picture bands",
    /// The stone's width, mm (checked by a photograph against its camera distance).
    PictureDiameter => "picture diameter-mm",
}

impl Setting {
    /// The setting named `name` ([`Setting::name`]).
    pub fn from_name(name: &str) -> Option<Setting> {
        Setting::ALL.iter().copied().find(|s| s.name() == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_setting_is_listed_once_by_a_name_of_its_own() {
        for (i, &s) in Setting::ALL.iter().enumerate() {
            assert_eq!(s as usize, i, "{s:?}");
            assert!(
                Setting::ALL[..i].iter().all(|o| o.name() != s.name()),
                "{s:?}"
            );
            assert_eq!(Setting::from_name(s.name()), Some(s));
            assert!(!s.name().starts_with('-') && s.name() == s.name().trim());
        }
        assert_eq!(Setting::from_name("no such setting"), None);
    }
}
