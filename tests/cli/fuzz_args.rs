//! The stable-toolchain fuzzer (`limn::testing::fuzz`, `examples/fuzz.rs`) on the command
//! line of the `limn` binary for a short budget: every run exits 0, 1 or 2 (never a signal or
//! a panic), exit 2 prints one line on stderr, and no file is overwritten without `--force`.
//! 6 s by default; `LIMN_FUZZ_SECONDS=S` for longer, `LIMN_FUZZ_SEED=N` for another seed.
//!
//! A command line that runs past the limit (an analysis of a model without `--time-limit` may
//! legitimately take long, `limn demo --format svg` takes some seconds) is killed and
//! reported, not failed.

use limn::testing::fuzz::{run, Config, FindingKind, Target};
use std::time::Duration;

#[test]
fn fuzz_command_line() {
    let seconds = std::env::var("LIMN_FUZZ_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(6.0);
    let mut config = Config::new(Target::Args, seconds);
    config.seed = std::env::var("LIMN_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    config.out = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz-findings");
    config.limn = Some(env!("CARGO_BIN_EXE_limn").into());
    config.time_limit = Duration::from_secs(5);
    let summary = run(&config).expect("the fuzzer starts");
    println!("{summary}");
    assert!(summary.inputs > 0, "no command line ran");
    let bad = summary.of_kinds(&[
        FindingKind::Panic,
        FindingKind::BadExit,
        FindingKind::BadMessage,
        FindingKind::Overwrite,
    ]);
    assert!(bad.is_empty(), "{summary}");
}
