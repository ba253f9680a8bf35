//! Integration tests: the CLI as a user runs it. One test binary (`autotests = false`) so it
//! links once.

mod cli;
mod layout;
mod names;
mod readme;
