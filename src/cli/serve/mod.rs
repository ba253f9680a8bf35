//! `facetlab serve`: the cutter's workbench in the browser. A local web server with one page
//! (embedded, no build step, no network) over a small JSON API; the page uses only the API.
//!
//! ```text
//! facetlab serve                      # http://127.0.0.1:8737/
//! facetlab serve --port 0 --open      # any free port, open the default browser
//! ```
//!
//! API (see the README's "serve" section):
//!
//! - `GET /api/presets`: presets, families with their parameters and ranges, lights, limits.
//! - `POST /api/cut`: the cut's `info --json` record plus `svg` (the diagram), and for a cut
//!   without a family `design_space`: its tier angles as sliders ([`design`]).
//! - `POST /api/score`: the keys of `score --json` (`"quick": true` uses
//!   [`ScoreConfig::fast`](facetlab::metrics::ScoreConfig::fast)).
//! - `POST /api/render`: `image/png` of the face-up (or tilted) picture.
//! - `POST /api/export`: the cut as `.asc`, `.gem`, `.obj`, `.stl` or `.toml` bytes.
//! - `POST /api/plan`, `GET /api/plan`: plans from an uploaded rough ([`plans`]).
//!
//! Every body is a JSON object: `cut` (a preset name, or the text of a file with `format`),
//! `set` (parameter changes: a family's parameters, or a design's tier angles), and per endpoint `light`, `size`, `tilt`, `exposure`, `quick`, `to`, and the stone's `material`, `colour`, `colour_density`, `diameter_mm` or `size_mm` (cut, score, render). Errors are
//! 4xx JSON `{"error": "field: message", "field": "field"}`. Bodies over
//! [`BODY_LIMIT`] bytes are refused. Uploads are parsed in memory; nothing a client sends
//! becomes a file path. Heavy work (building, tracing, scoring) runs on blocking threads, at
//! most [`jobs::jobs`] at a time; a request waiting for its turn that the client gives up on never
//! starts.
//!
//! This file holds the flags, the listening and the shared state; the rooms:
//! [`routes`] (the router and the cut endpoints), [`request`] (request bodies, validated),
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
mod request;
mod routes;
mod runs;

use facetlab::error::{Error, Result};
pub use routes::app;
use std::net::IpAddr;
use std::sync::Arc;
use tokio::sync::Semaphore;

/// Flags of `facetlab serve`.
#[derive(clap::Args, Debug, Clone)]
pub struct ServeArgs {
    /// Port to listen on; 0 picks a free one (the printed URL says which).
    #[arg(long, default_value_t = DEFAULT_PORT, value_name = "N")]
    pub port: u16,
    /// Address to listen on. Anything but loopback (127.0.0.1, ::1) lets other machines use
    /// the workbench (a warning is printed).
    #[arg(long, default_value = "127.0.0.1", value_name = "ADDR")]
    pub bind: String,
    /// Open the page in the default browser (xdg-open); failing to is only a note.
    #[arg(long)]
    pub open: bool,
}

/// Default port.
pub const DEFAULT_PORT: u16 = 8737;
/// Largest request body, bytes.
pub const BODY_LIMIT: usize = 5 * 1024 * 1024;
/// Allowed picture sizes, pixels per side.
pub const SIZE_RANGE: (u64, u64) = (16, 1024);
/// Allowed tilt of the picture, degrees.
pub const TILT_LIMIT: f64 = 45.0;
/// Largest exposure factor of a picture.
pub const EXPOSURE_MAX: f64 = 16.0;

/// Shared state: the job limit, the presets' JSON (built once), the optimization and plan runs
/// and the designs adopted lately.
struct AppState {
    jobs: Arc<Semaphore>,
    presets: String,
    runs: runs::Runs,
    plans: plans::PlanRuns,
    designs: Arc<design::Designs>,
}

/// The address in `--bind`: an IP address or `localhost`.
fn bind_addr(s: &str) -> Result<IpAddr> {
    if s.eq_ignore_ascii_case("localhost") {
        return Ok(IpAddr::from([127, 0, 0, 1]));
    }
    s.trim().parse().map_err(|_| {
        Error::invalid(
            "--bind",
            format!("`{s}` is not an IP address; give e.g. 127.0.0.1 (default), ::1 or 0.0.0.0"),
        )
    })
}

/// Run `facetlab serve` until Ctrl-C or SIGTERM.
pub fn run(a: &ServeArgs) -> Result<()> {
    let ip = bind_addr(&a.bind)?;
    if !ip.is_loopback() {
        eprintln!(
            "facetlab serve: warning: listening on {ip}, not loopback: anyone who can reach this address can use the workbench and its CPU (there is no login)"
        );
    }
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(|e| Error::io("serve", e))?;
    rt.block_on(async move {
        let listener = tokio::net::TcpListener::bind((ip, a.port))
            .await
            .map_err(|e| {
                Error::invalid(
                    "--port",
                    format!("cannot listen on {ip} port {}: {e}", a.port),
                )
            })?;
        let addr = listener.local_addr().map_err(|e| Error::io("serve", e))?;
        let url = format!("http://{addr}/");
        println!("facetlab serve: {url}  (Ctrl-C stops it)");
        use std::io::Write;
        let _ = std::io::stdout().flush();
        if a.open {
            open_browser(&url);
        }
        axum::serve(listener, app())
            .with_graceful_shutdown(shutdown())
            .await
            .map_err(|e| Error::io("serve", e))
    })
}

/// Try to open `url` in the default browser; a failure is a note, never an error.
fn open_browser(url: &str) {
    match std::process::Command::new("xdg-open")
        .arg(url)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
    {
        Ok(mut child) => {
            // Reap it in the background so it never lingers as a zombie.
            std::thread::spawn(move || {
                if let Ok(s) = child.wait() {
                    if !s.success() {
                        eprintln!("facetlab serve: could not open a browser (xdg-open failed); open the URL yourself");
                    }
                }
            });
        }
        Err(e) => eprintln!(
            "facetlab serve: could not open a browser (xdg-open: {e}); open the URL yourself"
        ),
    }
}

async fn shutdown() {
    let ctrl_c = async {
        let _ = tokio::signal::ctrl_c().await;
    };
    #[cfg(unix)]
    let term = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut s) => {
                s.recv().await;
            }
            Err(_) => std::future::pending::<()>().await,
        }
    };
    #[cfg(not(unix))]
    let term = std::future::pending::<()>();
    tokio::select! {
        _ = ctrl_c => {},
        _ = term => {},
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bind_addresses() {
        assert!(bind_addr("example").is_err());
        assert!(bind_addr("localhost").unwrap().is_loopback());
    }
}
