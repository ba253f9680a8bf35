//! The `facetlab` binary: parse the command line, run, print one-line errors with exit code 2.

use clap::Parser;

mod cli;

fn main() {
    #[cfg(unix)]
    // SAFETY: called first thing in main, before any other thread exists; SIG_DFL is a valid
    // disposition for SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = cli::Cli::parse();
    if let Err(e) = cli::run(cli) {
        eprintln!("facetlab: {e}");
        std::process::exit(2);
    }
}
