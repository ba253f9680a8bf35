//! `facetlab serve`: the cutter's workbench in the browser. A local web server with one page
//! (embedded, no build step, no network) over a small JSON API; the page uses only the API.
//!
//! ```text
//! facetlab serve                      # http://127.0.0.1:8737/
//! facetlab serve --port 0 --open      # any free port, open the default browser
//! ```
//!
//! API (see docs/serve.md):
//!
//! - `GET /api/presets`: presets, families with their parameters and ranges, lights, limits.
//! - `POST /api/cut`: the cut's `info --json` record plus `svg` (the diagram), and for a cut
//!   without a family `design_space`: its tier angles as sliders ([`design`]).
//! - `POST /api/score`: the keys of `score --json` (`"quick": true` uses
//!   [`ScoreConfig::fast`](facetlab::metrics::ScoreConfig::fast)).
//! - `POST /api/render`: `image/png` of the face-up (or tilted) picture.
//! - `POST /api/export`: the cut as `.asc`, `.gem`, `.obj`, `.stl` or `.toml` bytes.
//! - `POST /api/plan`, `GET /api/plan`: plans from an uploaded rough ([`plans`]).
//! - `POST /api/recipe/build`, `/api/recipe/infer`: the tier editor's recipe built, and the
//!   recipe of the current cut ([`recipes`]).
//!
//! Every body is a JSON object: `cut` (a preset name, or the text of a file with `format`),
//! `set` (parameter changes: a family's parameters, or a design's tier angles), and per endpoint `light`, `size`, `tilt`, `exposure`, `quick`, `to`, and the stone's `material`, `colour`, `colour_density`, `diameter_mm` or `size_mm` (cut, score, render). Errors are
//! 4xx JSON `{"error": "field: message", "field": "field"}`. Bodies over
//! [`BODY_LIMIT`] bytes are refused. Uploads are parsed in memory; nothing a client sends
//! becomes a file path. Heavy work (building, tracing, scoring) runs on blocking threads, at
//! most [`jobs::jobs`] at a time; a request waiting for its turn that the client gives up on never
//! starts.
//!
//! The rooms: [`server`] (the flags, the listening and the shared state), [`routes`] (the router and the cut endpoints), [`request`] (request bodies, validated),
//! [`error`] (the API's error replies), [`jobs`] (the heavy work on blocking threads),
//! [`design`] (a design's tier angles as sliders, adopted once per design),
//! [`runs`] (optimization runs in the background), [`plans`] (plans from a rough in the
//! background), [`page`] (the embedded page).

mod design;
mod error;
mod field;
mod jobs;
mod page;
mod plans;
mod recipes;
mod request;
mod routes;
mod runs;
mod server;

use server::AppState;
pub use server::{
    run, ServeArgs, BODY_LIMIT, EXPOSURE_MAX, HEAD_SHADOW_MAX, SIZE_RANGE, TILT_LIMIT,
};
