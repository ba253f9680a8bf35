//! Command-line subcommands (thin layers over the library).

pub mod score;
