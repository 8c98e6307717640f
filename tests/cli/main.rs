//! The `limn` command as a user runs it: every fixture, every command, bad input.
//!
//! One test binary per group (each links GMP and MPFR): the modules below were separate
//! binaries before.

#[allow(dead_code)]
#[path = "../common/mod.rs"]
mod common;

mod bad_input;
mod cli_curves;
mod cli_fixtures;
mod cli_hlr;
mod cli_silhouette;
mod cli_visible;
mod fuzz_args;
