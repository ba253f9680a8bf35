//! The API's error reply: a status and `{"error": "field: message", "field": "field"}`, and the
//! mapping of the library's errors about a cut onto the request's fields.

use axum::http::{header, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use facetlab::error::{Error, Setting};
use serde_json::json;

/// An API error: a status and a one-line message naming the field.
#[derive(Debug)]
pub struct ApiError {
    status: StatusCode,
    pub field: String,
    pub message: String,
}

impl ApiError {
    pub fn new(status: StatusCode, field: impl Into<String>, message: impl Into<String>) -> Self {
        ApiError {
            status,
            field: field.into(),
            message: message.into(),
        }
    }
    pub fn bad(field: impl Into<String>, message: impl Into<String>) -> Self {
        Self::new(StatusCode::BAD_REQUEST, field, message)
    }
    /// The same error as a 422: the request was well formed, its content is refused.
    pub fn unprocessable(self) -> Self {
        Self {
            status: StatusCode::UNPROCESSABLE_ENTITY,
            ..self
        }
    }
    /// A library error about the cut or its parameters, named by the request's field.
    pub fn from_cut(e: Error) -> Self {
        match e {
            Error::Invalid { field, message } => {
                let field = field.strip_prefix("--set ").unwrap_or(&field).to_string();
                // Parameter keys are plain identifiers; anything else is about the cut.
                let key = field.rsplit(": ").next().unwrap_or(&field);
                if !key.is_empty()
                    && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
                    && key != "family"
                {
                    Self::new(
                        StatusCode::UNPROCESSABLE_ENTITY,
                        format!("set.{key}"),
                        message,
                    )
                } else {
                    Self::new(
                        StatusCode::UNPROCESSABLE_ENTITY,
                        "cut",
                        format!("{field}: {message}"),
                    )
                }
            }
            Error::Geometry(m) => Self::new(StatusCode::UNPROCESSABLE_ENTITY, "set", m),
            other => Self::from_load(other),
        }
    }
    /// A library error while reading the cut itself (a preset or an uploaded file): about
    /// `cut`, even when the file names a parameter.
    pub fn from_load(e: Error) -> Self {
        match e {
            Error::Invalid { field, message } => Self::new(
                StatusCode::UNPROCESSABLE_ENTITY,
                "cut",
                format!("{field}: {message}"),
            ),
            other => {
                let text = other.to_string();
                let msg = text.strip_prefix("cut:").unwrap_or(&text).trim_start();
                let msg = if msg.starts_with(|c: char| c.is_ascii_digit()) {
                    format!("line {msg}")
                } else {
                    msg.to_string()
                };
                Self::new(StatusCode::UNPROCESSABLE_ENTITY, "cut", msg)
            }
        }
    }
}

/// The request's field for each of the library's settings ([`Setting`], named by the field its
/// errors give; [`ApiError::from_picture`]): the web page's spellings, as `flags::flag` is the
/// command line's. A `match` with no wildcard, so a setting the library adds must be placed
/// here; `None`: no request sends it (its error keeps the library's name).
pub const fn field(s: Setting) -> Option<&'static str> {
    match s {
        Setting::Material => Some("material"),
        Setting::RoughSize => Some("size_mm"),
        Setting::InclusionMesh => Some("inclusions"),
        Setting::PictureLight => Some("light"),
        Setting::PictureSize => Some("size"),
        Setting::PictureTilt => Some("tilt"),
        Setting::PictureHeadShadow => Some("head_shadow"),
        Setting::PictureExposure => Some("exposure"),
        Setting::PictureView => Some("view"),
        Setting::PictureAperture => Some("aperture"),
        Setting::PictureGround => Some("ground"),
        Setting::PictureLightRotation => Some("light_rotation"),
        Setting::LightAngle
        | Setting::PhotonCount
        | Setting::TraceDepth
        | Setting::AbsorptionModel
        | Setting::FixedWavelength
        | Setting::RefractiveIndex
        | Setting::SweepScore
        | Setting::SweepYAxis
        | Setting::SweepGrid
        | Setting::RunFolder
        | Setting::FirstAxis
        | Setting::GridAxes
        | Setting::SlicePoint
        | Setting::MapAxes
        | Setting::ShardFolder
        | Setting::Shard
        | Setting::BatchOutput
        | Setting::ScoreDocument
        | Setting::Output
        | Setting::JsonOutput
        | Setting::HdrOutput
        | Setting::PlotsFolder
        | Setting::Force
        | Setting::PictureRock
        | Setting::PictureTurn
        | Setting::CutParameter
        | Setting::PictureDistance
        | Setting::PictureGroundGap
        | Setting::PictureTone
        | Setting::PictureBands
        | Setting::PictureDiameter => None,
    }
}

impl ApiError {
    /// A render's or a photograph's option refused by the library (its `validate`): a 400
    /// naming the request's field ([`field`]); any other error about `render`.
    pub fn from_picture(e: Error) -> Self {
        match e {
            Error::Invalid { field, message } => {
                // The library's picture settings are named `picture FIELD`; its options' by
                // the field alone.
                let setting = Setting::from_name(&field)
                    .or_else(|| Setting::from_name(&format!("picture {field}")));
                let field = setting
                    .and_then(self::field)
                    .map_or(field.clone(), str::to_string);
                Self::bad(field, message)
            }
            other => Self::bad("render", other.to_string()),
        }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let one_line: String = self
            .message
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
        let body = json!({
            "error": format!("{}: {one_line}", self.field),
            "field": self.field,
        });
        (
            self.status,
            [(header::CACHE_CONTROL, "no-store")],
            axum::Json(body),
        )
            .into_response()
    }
}

pub type ApiResult<T> = std::result::Result<T, ApiError>;

/// `r` with `Cache-Control: no-store` (every API answer is computed afresh).
pub fn no_store(mut r: Response) -> Response {
    r.headers_mut()
        .insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_refused_picture_option_names_the_request_field() {
        let mut lab = facetlab::render::RenderOptions::new(facetlab::render::Light::Iso);
        lab.size = 4;
        let e = ApiError::from_picture(lab.validate().unwrap_err());
        assert_eq!(
            (e.status, e.field.as_str()),
            (StatusCode::BAD_REQUEST, "size")
        );
        assert!(e.message.contains("out of range"), "{}", e.message);
        let mut photo = facetlab::render::photo::PhotoOptions::new(
            facetlab::render::photo::PhotoLight::parse("tent")
                .unwrap()
                .unwrap(),
        );
        photo.light_rotation_deg = f64::NAN;
        let e = ApiError::from_picture(photo.validate().unwrap_err());
        assert_eq!(e.field, "light_rotation");
        let e = ApiError::from_picture(Error::Geometry("no solid".into()));
        assert_eq!(
            (e.field.as_str(), e.message.as_str()),
            ("render", "geometry: no solid")
        );
    }
}
