//! The heavy work of a request (building, tracing, scoring) on blocking threads, at most
//! [`jobs`] at a time; a request whose client gives up while waiting for its turn never runs.

use super::design::{Adopted, Designs};
use super::error::{ApiError, ApiResult};
use super::request::{Req, Source};
use super::AppState;
use axum::http::StatusCode;
use facetlab::cut::Cut;
use facetlab::error::Result;
use facetlab::io;
use std::time::Duration;

/// Heavy jobs allowed to run at once: one per core.
pub fn jobs() -> usize {
    std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(2)
        .clamp(1, 8)
}

/// Run `f` on a blocking thread once a job slot is free. A request whose client gives up
/// while waiting is dropped here and never runs.
pub async fn heavy<T, F>(st: &AppState, f: F) -> ApiResult<T>
where
    T: Send + 'static,
    F: FnOnce() -> ApiResult<T> + Send + 'static,
{
    let permit = tokio::time::timeout(Duration::from_secs(60), st.jobs.clone().acquire_owned())
        .await
        .map_err(|_| {
            ApiError::new(
                StatusCode::SERVICE_UNAVAILABLE,
                "server",
                "busy; try again in a moment",
            )
        })?
        .map_err(|_| ApiError::new(StatusCode::SERVICE_UNAVAILABLE, "server", "shutting down"))?;
    let job = tokio::task::spawn_blocking(move || {
        let _permit = permit;
        f()
    });
    match job.await {
        Ok(r) => r,
        Err(_) => Err(ApiError::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            "server",
            "the computation failed (see the server's log)",
        )),
    }
}

/// Build the cut a request names, with its parameter changes: a family's through the family,
/// a design's tier angles through its [`super::design::Design`] (adopted once per design, [`Designs`]).
pub fn build(designs: &Designs, r: &Req) -> ApiResult<Cut> {
    build_design(designs, r, false).map(|(cut, _)| cut)
}

/// [`build`], and for a cut without a family its design adopted (or why it cannot be) when
/// `want` says so or the request sets angles.
pub fn build_design(designs: &Designs, r: &Req, want: bool) -> ApiResult<(Cut, Option<Adopted>)> {
    let (cut, key) = match &r.source {
        Source::Preset(n) => match io::presets::load(n) {
            Some(c) => (
                c.map_err(ApiError::from_load)?,
                [&b"preset\0"[..], n.as_bytes()].concat(),
            ),
            None => return Err(ApiError::bad("cut", "unknown preset")),
        },
        Source::File {
            format,
            bytes,
            name,
        } => (
            load_bytes(format, bytes, name).map_err(ApiError::from_load)?,
            [
                format.as_bytes(),
                &b"\0"[..],
                name.as_bytes(),
                &b"\0"[..],
                bytes,
            ]
            .concat(),
        ),
    };
    if cut.family.is_some() {
        return Ok((cut.with_params(&r.set).map_err(ApiError::from_cut)?, None));
    }
    if r.set.is_empty() && !want {
        return Ok((cut, None));
    }
    let design = designs.get(key, &cut);
    if r.set.is_empty() {
        return Ok((cut, Some(design)));
    }
    match &design {
        Ok(d) => Ok((d.build(&cut.name, &r.set)?, Some(design))),
        Err(e) => Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "set",
            format!("{}: its tier angles cannot turn: {e}", cut.name),
        )),
    }
}

/// Parse a cut file's bytes in memory ([`io::parse_cut`]); `cut` names the source in
/// messages.
fn load_bytes(format: &str, bytes: &[u8], name: &str) -> Result<Cut> {
    io::parse_cut(format, bytes, name, "cut")
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    #[test]
    fn errors_name_the_request_field() {
        let mut v = BTreeMap::new();
        v.insert("crown_angle".to_string(), 75.0);
        let e = io::presets::load("tolkowsky")
            .unwrap()
            .unwrap()
            .with_params(&v)
            .unwrap_err();
        assert_eq!(ApiError::from_cut(e).field, "set.crown_angle");
        let e = load_bytes("asc", b"g 96 0\na x3 1 2\n", "u").unwrap_err();
        let a = ApiError::from_load(e);
        assert_eq!(a.field, "cut", "{a:?}");
        assert!(a.message.starts_with("line 2"), "{a:?}");
        // A parameter out of range inside an uploaded spec is about the upload.
        let spec = b"family = \"round-brilliant\"\n[params]\ncrown_angle = 75.0\n";
        let a = ApiError::from_load(load_bytes("toml", spec, "u").unwrap_err());
        assert_eq!(a.field, "cut", "{a:?}");
        assert!(a.message.contains("crown_angle"), "{a:?}");
    }
}
