//! Ctrl-C and SIGTERM (and SIGHUP): the first asks the command to stop and still write what it
//! found, then exit 130; a second one quits at once, writing nothing. One flag per process,
//! shared by `optimize`, `sweep` and `plan`.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Once;

/// Raised by the first signal.
pub static STOP: AtomicBool = AtomicBool::new(false);
static HANDLER: Once = Once::new();

/// Lower the flag, then install the handler (once; ctrlc's `termination` feature makes it
/// catch SIGTERM and SIGHUP too). `what` ends the line printed at the first signal, e.g.
/// "the current iteration and writing what was found".
pub fn install() {
    // Lower the flag before the handler exists: a signal that arrives right after the
    // handler is installed must not be forgotten.
    STOP.store(false, Ordering::SeqCst);
    HANDLER.call_once(|| {
        let _ = ctrlc::set_handler(|| {
            if STOP.swap(true, Ordering::SeqCst) {
                eprintln!("\nfacetlab: interrupted again, quitting without writing");
                std::process::exit(130);
            }
            eprintln!(
                "\nfacetlab: stopping and writing what was found (Ctrl-C again to quit at once)"
            );
        });
    });
}

/// Whether a signal asked to stop.
pub fn stopped() -> bool {
    STOP.load(Ordering::SeqCst)
}

/// Held by each test of this binary that runs a command reading [`STOP`] (optimize, sweep,
/// plan) in process or raises it: the flag is one per process, and tests run side by side (a
/// test raising it once stopped another's sweep).
#[cfg(test)]
pub static TESTS: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// [`TESTS`], taken (a test that failed while holding it leaves it poisoned, not locked).
#[cfg(test)]
pub fn one_at_a_time() -> std::sync::MutexGuard<'static, ()> {
    TESTS.lock().unwrap_or_else(|e| e.into_inner())
}
