//! The server: its flags, limits and shared state, the listening address, and the run until
//! Ctrl-C (with the browser opened on request).

use super::routes::app;
use super::{design, plans, runs};
use facetlab::error::{Error, Result};
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
/// The largest head shadow a request may ask for, degrees (as `--head-shadow`).
pub const HEAD_SHADOW_MAX: f64 = 60.0;

/// Shared state: the job limit, the presets' JSON (built once), the optimization and plan runs
/// and the designs adopted lately.
pub(super) struct AppState {
    pub(super) jobs: Arc<Semaphore>,
    pub(super) presets: String,
    pub(super) runs: runs::Runs,
    pub(super) plans: plans::PlanRuns,
    pub(super) designs: Arc<design::Designs>,
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
    let served = rt.block_on(async move {
        let listener = tokio::net::TcpListener::bind((ip, a.port))
            .await
            .map_err(|e| {
                Error::invalid(
                    "--port",
                    format!("cannot listen on {ip} port {}: {e}", a.port),
                )
            })?;
        // The signals are caught from before the URL is printed: a client (or a script)
        // that stops the server as soon as it is up is heard.
        let signals = Signals::new()?;
        let addr = listener.local_addr().map_err(|e| Error::io("serve", e))?;
        let url = format!("http://{addr}/");
        println!("facetlab serve: {url}  (Ctrl-C stops it)");
        use std::io::Write;
        let _ = std::io::stdout().flush();
        if a.open {
            open_browser(&url);
        }
        // At the signal the server stops taking connections and lets the requests under way
        // finish for at most GRACE; those still running then are cut (their connections
        // closed), as is the heavy work behind them, so the process is gone within about
        // GRACE.
        let (signalled, heard) = tokio::sync::oneshot::channel::<()>();
        let server = axum::serve(listener, app()).with_graceful_shutdown(async move {
            signals.first().await;
            let _ = signalled.send(());
        });
        tokio::select! {
            r = server => r.map_err(|e| Error::io("serve", e)),
            _ = async {
                if heard.await.is_ok() {
                    tokio::time::sleep(GRACE).await;
                } else {
                    std::future::pending::<()>().await;
                }
            } => Ok(()),
        }
    });
    // Blocking jobs (a render, an export) are not waited for: the process ends with them.
    rt.shutdown_timeout(std::time::Duration::ZERO);
    served
}

/// How long requests under way may finish after Ctrl-C or SIGTERM before they are cut.
pub const GRACE: std::time::Duration = std::time::Duration::from_millis(300);

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

/// Ctrl-C and SIGTERM, caught from their creation on.
struct Signals {
    #[cfg(unix)]
    interrupt: tokio::signal::unix::Signal,
    #[cfg(unix)]
    terminate: tokio::signal::unix::Signal,
}

impl Signals {
    fn new() -> Result<Signals> {
        #[cfg(unix)]
        {
            use tokio::signal::unix::{signal, SignalKind};
            let caught = |kind| signal(kind).map_err(|e| Error::io("serve", e));
            Ok(Signals {
                interrupt: caught(SignalKind::interrupt())?,
                terminate: caught(SignalKind::terminate())?,
            })
        }
        #[cfg(not(unix))]
        Ok(Signals {})
    }

    /// The first of them.
    async fn first(mut self) {
        #[cfg(unix)]
        tokio::select! {
            _ = self.interrupt.recv() => {},
            _ = self.terminate.recv() => {},
        }
        #[cfg(not(unix))]
        {
            let _ = tokio::signal::ctrl_c().await;
        }
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
