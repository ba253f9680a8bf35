//! The `facetlab` binary: parse the command line, run, print one-line errors with exit code 2.

use clap::Parser;

fn main() {
    let cli = facetlab::cli::Cli::parse();
    if let Err(e) = facetlab::cli::run(cli) {
        eprintln!("facetlab: {e}");
        std::process::exit(2);
    }
}
