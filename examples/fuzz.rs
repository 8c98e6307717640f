//! The fuzzer of the model readers and of the `limn` command line (`limn::testing::fuzz`), on
//! the stable toolchain. See docs/testing.md.
//!
//! ```text
//! cargo build --release    # the args target runs target/release/limn
//! cargo run --release --example fuzz -- TARGET --seconds S [--seed N] [--out DIR]
//!     [--inputs N] [--time-limit S] [--hang-limit S] [--limn PATH] [--replay FILE] [-v]
//! ```
//!
//! TARGET is json, bpt, teaset, iges, obj, detect or args. Exit code 0 if nothing was found,
//! 1 if something was (the findings are in DIR/TARGET, default target/fuzz-findings), 2 on a
//! bad command line.

use limn::testing::fuzz::{self, Config, Target};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

const USAGE: &str = "usage: fuzz TARGET --seconds S [--seed N] [--out DIR] [--inputs N] [--time-limit S] [--hang-limit S] [--limn PATH] [--replay FILE] [-v]  (TARGET: json, bpt, teaset, iges, obj, detect, args)";

fn parse() -> Result<(Config, Option<PathBuf>), String> {
    let mut args = std::env::args().skip(1);
    let target: Target = args.next().ok_or("no target")?.parse()?;
    let mut config = Config::new(target, 60.0);
    let mut replay = None;
    while let Some(flag) = args.next() {
        if flag == "-v" || flag == "--verbose" {
            config.verbose = true;
            continue;
        }
        let value = args.next().ok_or_else(|| format!("{flag}: no value"))?;
        let number = |v: &str| -> Result<f64, String> {
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite() && *x >= 0.0)
                .ok_or_else(|| format!("{flag}: expected a number of seconds, found {v:?}"))
        };
        let count = |v: &str| -> Result<u64, String> {
            v.parse::<u64>()
                .map_err(|_| format!("{flag}: expected a whole number, found {v:?}"))
        };
        match flag.as_str() {
            "--seconds" => config.seconds = number(&value)?,
            "--seed" => config.seed = count(&value)?,
            "--inputs" => config.max_inputs = Some(count(&value)?),
            "--out" => config.out = PathBuf::from(value),
            "--time-limit" => config.time_limit = Duration::from_secs_f64(number(&value)?),
            "--hang-limit" => config.hang_limit = Duration::from_secs_f64(number(&value)?),
            "--limn" => config.limn = Some(PathBuf::from(value)),
            "--replay" => replay = Some(PathBuf::from(value)),
            _ => return Err(format!("unknown option {flag:?}")),
        }
    }
    config.hang_limit = config.hang_limit.max(config.time_limit);
    Ok((config, replay))
}

fn main() -> ExitCode {
    let (config, replay) = match parse() {
        Ok(c) => c,
        Err(e) => {
            eprintln!("fuzz: {e}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    if let Some(file) = replay {
        return match fuzz::replay(&config, &file) {
            Ok(text) => {
                println!("{text}");
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("fuzz: {e}");
                ExitCode::from(2)
            }
        };
    }
    let cpu_before = fuzz::cpu_time();
    match fuzz::run(&config) {
        Ok(summary) => {
            print!("{summary}");
            if let (Some((own0, kids0)), Some((own1, kids1))) = (cpu_before, fuzz::cpu_time()) {
                println!(
                    "  cpu: {:.1} s in the fuzzer, {:.1} s in child processes",
                    (own1 - own0).as_secs_f64(),
                    (kids1 - kids0).as_secs_f64()
                );
            }
            if summary.findings.is_empty() {
                ExitCode::SUCCESS
            } else {
                println!(
                    "  findings in {}",
                    config.out.join(config.target.name()).display()
                );
                ExitCode::from(1)
            }
        }
        Err(e) => {
            eprintln!("fuzz: {e}");
            ExitCode::from(2)
        }
    }
}
