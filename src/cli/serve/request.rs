//! Request bodies of the cut endpoints, read into [`Body`] (derived) and validated into
//! [`Req`]: every field's type, range and allowed values, each error naming the field. The cut
//! itself is built later, on a blocking thread ([`super::jobs::build`]).

use super::error::{ApiError, ApiResult};
use super::{BODY_LIMIT, EXPOSURE_MAX, HEAD_SHADOW_MAX, SIZE_RANGE, TILT_LIMIT};
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::http::StatusCode;
use base64::engine::general_purpose::GeneralPurpose;
use base64::engine::{DecodePaddingMode, GeneralPurposeConfig};
use base64::Engine;
use facetlab::io;
use facetlab::optics::{ColourFields, Material, MaterialFields, StoneSize};
use facetlab::render::photo::{GroundKind, PhotoLight, View};
use facetlab::render::{Light, LightChoice, PictureSettings, Tilt};
use serde::Deserialize;
use serde_json::{Number, Value};
use std::collections::BTreeMap;

mod stone;
use stone::stone;
pub use stone::stone_for;

/// File formats accepted as `format` and produced as `to`.
pub const FORMATS: [&str; 5] = ["asc", "gem", "obj", "stl", "toml"];

/// What `POST /api/export` writes: the cut's files, and `html`, its one-page report
/// ([`facetlab::report`]).
pub const EXPORTS: [&str; 6] = ["asc", "gem", "obj", "stl", "toml", "html"];

/// Where a cut comes from.
#[derive(Clone, Debug)]
pub enum Source {
    Preset(String),
    File {
        format: &'static str,
        bytes: Vec<u8>,
        name: String,
    },
}

/// A request body, validated (the cut itself is built later, on a blocking thread).
#[derive(Clone, Debug)]
pub struct Req {
    pub source: Source,
    pub set: BTreeMap<String, f64>,
    /// The picture's settings (`light`, `size`, `tilt` toward azimuth 0, `exposure`,
    /// `head_shadow`; a photograph's `view` and `view_az`, `light_rotation`, `ground` and
    /// `aperture`, read at 250 mm, 0 a pinhole), the library's own, within the page's caps;
    /// `head_shadow` is the scores' too (`None`: the light's and scores' own).
    pub picture: PictureSettings,
    pub quick: bool,
    pub to: Option<&'static str>,
    /// The stones ([`stone_for`]): the material sent (else a design's own, as every command
    /// traces it), its body colour, the size and the crystal settings.
    pub stone: facetlab::metrics::StoneChoice,
}

pub use super::field::Field;

/// A body of the cut endpoints as sent; [`parse_req`] validates it into a [`Req`].
#[derive(Debug, Default, Deserialize)]
#[serde(default)]
struct Body {
    cut: Field<String>,
    format: Field<String>,
    encoding: Field<String>,
    name: Field<String>,
    set: Field<BTreeMap<String, Field<Number>>>,
    light: Field<String>,
    size: Field<Number>,
    tilt: Field<Number>,
    exposure: Field<Number>,
    head_shadow: Field<Number>,
    quick: Field<bool>,
    to: Field<String>,
    material: Field<String>,
    colour: Field<String>,
    colour_density: Field<Number>,
    diameter_mm: Field<Number>,
    size_mm: Field<String>,
    view: Field<Number>,
    view_az: Field<Number>,
    light_rotation: Field<Number>,
    ground: Field<String>,
    aperture: Field<Number>,
    optic_axis: Field<Number>,
    birefringence: Field<bool>,
    colour_e: Field<String>,
}

/// The keys of a photograph (`render` with a photographic light).
pub const PHOTO: [&str; 5] = ["view", "view_az", "light_rotation", "ground", "aperture"];

/// A number field within `[lo, hi]` (default `default`), the error naming `field` and `what`.
fn bounded(
    f: &Field<Number>,
    field: &str,
    lo: f64,
    hi: f64,
    default: f64,
    what: &str,
) -> ApiResult<f64> {
    let bad = |sent: String| {
        ApiError::bad(
            field,
            format!(
                "{} is not allowed; give {what} from {lo} to {hi}",
                short(&sent)
            ),
        )
    };
    match f.given() {
        Ok(None) => Ok(default),
        Ok(Some(n)) => match n.as_f64() {
            Some(x) if (lo..=hi).contains(&x) => Ok(x),
            _ => Err(bad(n.to_string())),
        },
        Err(v) => Err(bad(v.to_string())),
    }
}

/// Which keys an endpoint takes beyond `cut`, `format`, `encoding`, `name`, `set`.
const COMMON: [&str; 5] = ["cut", "format", "encoding", "name", "set"];

/// The keys of a stone's material, body colour and size (`score`, `render`, `cut`).
pub const STONE: [&str; 8] = [
    "material",
    "colour",
    "colour_density",
    "diameter_mm",
    "size_mm",
    "optic_axis",
    "birefringence",
    "colour_e",
];

/// A JSON object from a request's body, or the error about `body` (too large, not JSON, not
/// an object: `not_object` says what was expected).
pub fn json_object(
    body: std::result::Result<Bytes, BytesRejection>,
    not_object: &str,
) -> ApiResult<serde_json::Map<String, Value>> {
    let body = body.map_err(|r| {
        let status = r.status();
        let msg = if status == StatusCode::PAYLOAD_TOO_LARGE {
            format!(
                "the request is larger than {} MB",
                BODY_LIMIT / (1024 * 1024)
            )
        } else {
            r.body_text()
        };
        ApiError::new(status, "body", msg)
    })?;
    let v: Value = serde_json::from_slice(&body)
        .map_err(|e| ApiError::bad("body", format!("not JSON: {e}")))?;
    let Value::Object(m) = v else {
        return Err(ApiError::bad("body", not_object.to_string()));
    };
    Ok(m)
}

/// Validate a body of a cut endpoint that takes the keys [`COMMON`] and `extra`.
pub fn parse_req(
    body: std::result::Result<Bytes, BytesRejection>,
    extra: &[&str],
) -> ApiResult<Req> {
    let m = json_object(body, "expected a JSON object like {\"cut\": \"tolkowsky\"}")?;
    for k in m.keys() {
        if !COMMON.contains(&k.as_str()) && !extra.contains(&k.as_str()) {
            let mut allowed: Vec<&str> = COMMON.to_vec();
            allowed.extend_from_slice(extra);
            return Err(ApiError::bad(
                short(k),
                format!("unknown field; allowed: {}", allowed.join(", ")),
            ));
        }
    }
    let b =
        Body::deserialize(Value::Object(m)).map_err(|e| ApiError::bad("body", e.to_string()))?;
    // A number out of range, or not a number: `sent` is its JSON text.
    let bad_size = |sent: String| {
        ApiError::bad(
            "size",
            format!(
                "{} is not allowed; give whole pixels from {} to {}",
                short(&sent),
                SIZE_RANGE.0,
                SIZE_RANGE.1
            ),
        )
    };
    let bad_tilt = |sent: String| {
        ApiError::bad(
            "tilt",
            format!(
                "{} is not allowed; give degrees from {} to {}",
                short(&sent),
                -TILT_LIMIT,
                TILT_LIMIT
            ),
        )
    };
    let bad_exposure = |sent: String| {
        ApiError::bad(
            "exposure",
            format!(
                "{} is not allowed; give a factor in (0, {EXPOSURE_MAX}] (1 = a white diffuser shows white)",
                short(&sent)
            ),
        )
    };
    let stone = stone(&b)?;
    // The light, read once by the library (a map file is for the command line: nothing a
    // client sends becomes a path).
    let unknown = |s: &str| {
        ApiError::bad(
            "light",
            format!(
                "unknown light {:?}; allowed {}, {}",
                short(s),
                Light::ALL.map(Light::name).join(", "),
                PhotoLight::names().join(", ")
            ),
        )
    };
    let light = match b.light.given() {
        Ok(None) => LightChoice::default(),
        Ok(Some(l)) if l.trim().starts_with("env:") => return Err(unknown(l)),
        Ok(Some(l)) => LightChoice::parse("light", l).map_err(|_| unknown(l))?,
        Err(_) => return Err(ApiError::bad("light", "must be a string such as \"iso\"")),
    };
    let view = View {
        elevation_deg: bounded(
            &b.view,
            "view",
            -90.0,
            90.0,
            30.0,
            "the camera's elevation in degrees",
        )?,
        azimuth_deg: bounded(
            &b.view_az,
            "view_az",
            -360.0,
            360.0,
            0.0,
            "the camera's azimuth in degrees",
        )?,
    };
    let light_rotation = bounded(
        &b.light_rotation,
        "light_rotation",
        -360.0,
        360.0,
        0.0,
        "degrees",
    )?;
    let ground = match b.ground.given() {
        Ok(None) => GroundKind::None,
        Ok(Some(g)) => GroundKind::ALL
            .into_iter()
            .find(|k| k.name() == g.trim())
            .ok_or_else(|| {
                ApiError::bad(
                    "ground",
                    format!("{:?} is not allowed; give none, white or black", short(g)),
                )
            })?,
        Err(_) => {
            return Err(ApiError::bad(
                "ground",
                "must be a string: none, white or black",
            ))
        }
    };
    let aperture = match b.aperture.given() {
        Ok(None) => None,
        _ => Some(bounded(
            &b.aperture,
            "aperture",
            0.0,
            88.0,
            0.0,
            "the entrance pupil in mm (0 = a pinhole, read at 250 mm)",
        )?),
    };
    let is_photo = light.is_photo();
    // A photograph's settings with a laboratory light would be ignored: refused, as the
    // command line and Python refuse them.
    let sent = [
        b.view.sent(),
        b.view_az.sent(),
        b.light_rotation.sent(),
        b.ground.sent(),
        b.aperture.sent(),
    ];
    if let (false, Some((key, _))) = (is_photo, PHOTO.iter().zip(sent).find(|(_, s)| *s)) {
        return Err(ApiError::bad(
            *key,
            format!(
                "is for photographs; give a photographic light ({})",
                PhotoLight::names().join(", ")
            ),
        ));
    }
    let size = match b.size.given() {
        Ok(None) => 512,
        Ok(Some(n)) => match n.as_u64() {
            Some(k) if (SIZE_RANGE.0..=SIZE_RANGE.1).contains(&k) => k as usize,
            _ => return Err(bad_size(n.to_string())),
        },
        Err(v) => return Err(bad_size(v.to_string())),
    };
    let tilt = match b.tilt.given() {
        Ok(None) => 0.0,
        Ok(Some(n)) => match n.as_f64() {
            Some(t) if t.abs() <= TILT_LIMIT => t,
            _ => return Err(bad_tilt(n.to_string())),
        },
        Err(v) => return Err(bad_tilt(v.to_string())),
    };
    let exposure = match b.exposure.given() {
        Ok(None) => 1.0,
        Ok(Some(n)) => match n.as_f64() {
            Some(x) if x > 0.0 && x <= EXPOSURE_MAX => x,
            _ => return Err(bad_exposure(n.to_string())),
        },
        Err(v) => return Err(bad_exposure(v.to_string())),
    };
    let head_shadow = match b.head_shadow.given() {
        Ok(None) => None,
        _ => Some(bounded(
            &b.head_shadow,
            "head_shadow",
            0.0,
            HEAD_SHADOW_MAX,
            0.0,
            "degrees",
        )?),
    };
    // The library's picture settings: the photograph's only with a photographic light (the
    // scores read the head shadow whatever the light).
    let picture = PictureSettings {
        size: Some(size),
        tilt: Some(Tilt {
            tilt_deg: tilt,
            azimuth_deg: 0.0,
        }),
        exposure: Some(exposure),
        head_shadow,
        view: is_photo.then_some(view),
        light_rotation: is_photo.then_some(light_rotation),
        ground: is_photo.then_some(ground),
        aperture,
        ..PictureSettings::new(light)
    };
    Ok(Req {
        picture,
        stone,
        source: source(&b)?,
        set: set(&b)?,
        quick: match b.quick.given() {
            Ok(q) => q.copied().unwrap_or(false),
            Err(_) => return Err(ApiError::bad("quick", "must be true or false")),
        },
        to: match b.to.given() {
            Ok(None) => None,
            Ok(Some(s)) => Some(export_of(s).ok_or_else(|| {
                ApiError::bad(
                    "to",
                    format!(
                        "cannot write {:?}; allowed: {}",
                        short(s),
                        EXPORTS.join(", ")
                    ),
                )
            })?),
            Err(_) => {
                return Err(ApiError::bad(
                    "to",
                    "must be one of asc, obj, stl, toml, html",
                ))
            }
        },
    })
}

/// A client's string as shown in a message: at most 40 characters, one line.
pub fn short(s: &str) -> String {
    let mut out: String = s
        .chars()
        .take(40)
        .map(|c| if c.is_control() { '?' } else { c })
        .collect();
    if s.chars().count() > 40 {
        out.push('…');
    }
    out
}

fn export_of(s: &str) -> Option<&'static str> {
    let s = s.trim().trim_start_matches('.').to_ascii_lowercase();
    EXPORTS.into_iter().find(|f| *f == s)
}

fn format_of(s: &str) -> Option<&'static str> {
    let s = s.trim().trim_start_matches('.').to_ascii_lowercase();
    FORMATS.into_iter().find(|f| *f == s)
}

fn source(b: &Body) -> ApiResult<Source> {
    let cut = match b.cut.given() {
        Ok(Some(s)) => s,
        Ok(None) => {
            return Err(ApiError::bad(
                "cut",
                "missing; give a preset name or the contents of a .asc, .gem, .obj, .stl or .toml file with \"format\" (binary files base64 with \"encoding\")",
            ))
        }
        Err(_) => return Err(ApiError::bad("cut", "must be a string")),
    };
    let format = match b.format.given() {
        Ok(None) => None,
        Ok(Some(s)) => Some(format_of(s).ok_or_else(|| {
            ApiError::bad(
                "format",
                format!(
                    "unknown format {:?}; allowed: {}",
                    short(s),
                    FORMATS.join(", ")
                ),
            )
        })?),
        Err(_) => return Err(ApiError::bad("format", "must be a string")),
    };
    let base64 = match b.encoding.given() {
        Ok(None) => false,
        Ok(Some(s)) if s == "text" => false,
        Ok(Some(s)) if s == "base64" => true,
        _ => return Err(ApiError::bad("encoding", "allowed: \"text\" or \"base64\"")),
    };
    let name = match b.name.given() {
        Ok(n) => n.map(|s| clean_name(s)),
        Err(_) => return Err(ApiError::bad("name", "must be a string")),
    };
    let Some(format) = format else {
        if base64 {
            return Err(ApiError::bad(
                "encoding",
                "only with \"format\" (a file's contents)",
            ));
        }
        if io::presets::names().contains(&cut.as_str()) {
            return Ok(Source::Preset(cut.clone()));
        }
        return Err(ApiError::bad(
            "cut",
            format!(
                "unknown preset {:?}{}; presets: {}; or send a file's text with \"format\"",
                short(cut),
                io::presets::suggestion(cut),
                io::presets::names().join(", ")
            ),
        ));
    };
    let bytes = if base64 {
        decode_base64(cut).ok_or_else(|| ApiError::bad("cut", "is not valid base64"))?
    } else {
        cut.as_bytes().to_vec()
    };
    let name = name
        .filter(|n| !n.is_empty())
        .unwrap_or_else(|| "upload".to_string());
    Ok(Source::File {
        format,
        bytes,
        name,
    })
}

/// A display name from a client: a file stem without its extension, at most 64 characters
/// of letters, digits, `-`, `_`, `.` and spaces.
fn clean_name(s: &str) -> String {
    let stem = s.rsplit(['/', '\\']).next().unwrap_or(s);
    let stem = match stem.rsplit_once('.') {
        Some((a, e)) if format_of(e).is_some() => a,
        _ => stem,
    };
    stem.chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | '.' | ' '))
        .take(64)
        .collect::<String>()
        .trim()
        .to_string()
}

/// A library error about a value of the right type (an unknown material, a colour that is
/// not one, a size out of range): a 422 naming the field the library names.
fn invalid(e: facetlab::error::Error) -> ApiError {
    match e {
        facetlab::error::Error::Invalid { field, message } => {
            ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, field, message)
        }
        other => ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "colour",
            other.to_string(),
        ),
    }
}

fn set(b: &Body) -> ApiResult<BTreeMap<String, f64>> {
    let mut out = BTreeMap::new();
    match b.set.given() {
        Ok(None) => {}
        Ok(Some(o)) => {
            for (k, v) in o {
                let field = format!("set.{}", short(k));
                let x = match v {
                    Field::Given(n) => n.as_f64(),
                    _ => None,
                };
                let x = x.ok_or_else(|| {
                    let sent = match v {
                        Field::Given(n) => n.to_string(),
                        Field::Other(v) => v.to_string(),
                        Field::Absent => Value::Null.to_string(),
                    };
                    ApiError::bad(&field, format!("{} is not a number", short(&sent)))
                })?;
                out.insert(k.clone(), x);
            }
        }
        Err(_) => {
            return Err(ApiError::bad(
                "set",
                "must be an object of parameter values, e.g. {\"pavilion_angle\": 40.9}",
            ))
        }
    }
    Ok(out)
}

/// Decode standard base64 as the page sends it, leniently: padding optional, whitespace
/// ignored, the URL-safe `-` and `_` taken for `+` and `/`, and the bits of an incomplete
/// last character dropped.
pub fn decode_base64(s: &str) -> Option<Vec<u8>> {
    const LENIENT: GeneralPurpose = GeneralPurpose::new(
        &base64::alphabet::STANDARD,
        GeneralPurposeConfig::new()
            .with_decode_padding_mode(DecodePaddingMode::Indifferent)
            .with_decode_allow_trailing_bits(true),
    );
    let mut clean: Vec<u8> = Vec::with_capacity(s.len());
    for c in s.bytes() {
        match c {
            b'=' | b' ' | b'\n' | b'\r' | b'\t' => {}
            b'-' => clean.push(b'+'),
            b'_' => clean.push(b'/'),
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'+' | b'/' => clean.push(c),
            _ => return None,
        }
    }
    // A lone last character carries under 8 bits: no byte.
    if clean.len() % 4 == 1 {
        clean.pop();
    }
    LENIENT.decode(&clean).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_and_names() {
        assert_eq!(decode_base64("aGVsbG8=").unwrap(), b"hello");
        assert_eq!(decode_base64("aGVsbG8").unwrap(), b"hello");
        assert!(decode_base64("a*b").is_none());
        assert_eq!(clean_name("../../etc/passwd"), "passwd");
        assert_eq!(clean_name("my cut.asc"), "my cut");
        assert_eq!(clean_name("a<script>.toml"), "ascript");
    }
}
