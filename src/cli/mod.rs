//! The command line (the lead wires the subcommands into `main`).

pub mod trace;
