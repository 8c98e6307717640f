//! The stable-toolchain fuzzer (`limn::testing::fuzz`, `examples/fuzz.rs`) on every model
//! reader for a short budget: no panic, no slow or hanging read, no memory blow-up, and every
//! error one line naming the file and a place. 2 s per target by default;
//! `LIMN_FUZZ_SECONDS=S` for longer, `LIMN_FUZZ_SEED=N` for another seed. Findings are
//! written to `target/tmp/fuzz-findings/TARGET` with the command that replays each.

use limn::testing::fuzz::{run, Config, Target};
use std::time::Duration;

/// The per-target budget: `LIMN_FUZZ_SECONDS`, or 2 s.
pub(crate) fn budget() -> f64 {
    std::env::var("LIMN_FUZZ_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2.0)
}

/// The seed: `LIMN_FUZZ_SEED`, or 1 (CI runs the same inputs every time, as far as the budget
/// reaches).
pub(crate) fn seed() -> u64 {
    std::env::var("LIMN_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1)
}

fn fuzz(target: Target) {
    let mut config = Config::new(target, budget());
    config.seed = seed();
    config.out = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz-findings");
    // A debug build on a loaded CI machine is slower than the release campaign's 3 s.
    config.time_limit = Duration::from_secs(10);
    config.hang_limit = Duration::from_secs(60);
    let summary = run(&config).expect("the fuzzer starts");
    println!("{summary}");
    assert!(summary.inputs > 0, "no input ran");
    assert!(summary.findings.is_empty(), "{summary}");
}

#[test]
fn fuzz_json_reader() {
    fuzz(Target::Json);
}

#[test]
fn fuzz_bpt_reader() {
    fuzz(Target::Bpt);
}

#[test]
fn fuzz_teaset_reader() {
    fuzz(Target::Teaset);
}

#[test]
fn fuzz_iges_reader() {
    fuzz(Target::Iges);
}

#[test]
fn fuzz_obj_reader() {
    fuzz(Target::Obj);
}

#[test]
fn fuzz_step_reader() {
    fuzz(Target::Step);
}

#[test]
fn fuzz_format_detection() {
    fuzz(Target::Detect);
}
