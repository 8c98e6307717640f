//! A mutational fuzzer that runs on the stable toolchain: every model reader (native JSON,
//! `.bpt`, teaset, IGES, OBJ and auto-detection) in process, and the command line of the
//! `limn` binary as a subprocess.
//!
//! Each input is derived from the run's seed and its index by a small PRNG ([`Rng`],
//! splitmix64), so a run is deterministic given `--seed` and the number of inputs
//! (`Config::max_inputs`); the inputs that give a new kind of result (a new error message,
//! once numbers and quotes are blanked) join the corpus, the only feedback a stable toolchain
//! offers without coverage instrumentation.
//!
//! A reader input runs on a worker thread under `catch_unwind`, watched by the calling thread:
//! one that takes longer than `Config::time_limit` is recorded as slow (and abandoned after
//! `Config::hang_limit`). A failed read must give a [`ReadError`](crate::io::ReadError) of one
//! line that starts with the file name and names a place inside the file. A model that reads
//! is summarised as `limn info` does (`ModelInfo` with the default welding).
//!
//! Every finding (a panic, a slow input, a memory blow-up, a bad message, a bad exit code, a
//! user's file overwritten) is written to `Config::out` (the first three inputs of each kind
//! of finding, the others counted), each input with a `.txt` beside it giving the run's seed,
//! the input's index and the command that replays it ([`replay`]).
//!
//! Run it as `cargo run --release --example fuzz -- TARGET --seconds S [--seed N]`; see
//! `docs/testing.md`.

mod args;
mod argv;
pub mod mutate;
mod readers;

pub use readers::json_sample;

use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// What is fuzzed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Target {
    /// The native JSON reader.
    Json,
    /// Newell's `.bpt` reader.
    Bpt,
    /// The 1991 teaset reader.
    Teaset,
    /// The IGES reader.
    Iges,
    /// The Wavefront OBJ reader.
    Obj,
    /// The STEP (ISO 10303-21) reader.
    Step,
    /// Format detection (`read_model_bytes` with no format), on inputs of every kind.
    Detect,
    /// The command line of the `limn` binary.
    Args,
}

impl Target {
    /// Every target, readers first.
    pub const ALL: [Target; 8] = [
        Target::Json,
        Target::Bpt,
        Target::Teaset,
        Target::Iges,
        Target::Obj,
        Target::Step,
        Target::Detect,
        Target::Args,
    ];

    /// The target's name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Target::Json => "json",
            Target::Bpt => "bpt",
            Target::Teaset => "teaset",
            Target::Iges => "iges",
            Target::Obj => "obj",
            Target::Step => "step",
            Target::Detect => "detect",
            Target::Args => "args",
        }
    }
}

impl fmt::Display for Target {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Target {
    type Err = String;
    fn from_str(s: &str) -> Result<Target, String> {
        Target::ALL
            .into_iter()
            .find(|t| t.name() == s)
            .ok_or_else(|| {
                format!(
                    "unknown fuzz target {s:?} (json, bpt, teaset, iges, obj, step, detect, args)"
                )
            })
    }
}

/// How a run goes.
#[derive(Clone, Debug)]
pub struct Config {
    /// What is fuzzed.
    pub target: Target,
    /// The time budget (wall clock).
    pub seconds: f64,
    /// Stop after this many inputs, whatever the time (with the seed, a reproducible run).
    pub max_inputs: Option<u64>,
    /// The run's seed: the same seed and number of inputs give the same inputs.
    pub seed: u64,
    /// Where findings are written (a folder per target inside it).
    pub out: PathBuf,
    /// An input taking longer than this is recorded as slow.
    pub time_limit: Duration,
    /// A reader input still running after this is abandoned (its thread left behind);
    /// a command line is killed at `time_limit`.
    pub hang_limit: Duration,
    /// A reader input that raises the process's peak memory above this many bytes is recorded.
    pub memory_limit: u64,
    /// The `limn` binary, for [`Target::Args`].
    pub limn: Option<PathBuf>,
    /// Print progress and findings to stderr as they come.
    pub verbose: bool,
}

impl Config {
    /// A run of `target` for `seconds`, seed 1, findings in `target/fuzz-findings`, slow
    /// above 3 s, abandoned after 60 s, memory above 2 GiB recorded.
    pub fn new(target: Target, seconds: f64) -> Config {
        Config {
            target,
            seconds,
            max_inputs: None,
            seed: 1,
            out: PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/target/fuzz-findings")),
            time_limit: Duration::from_secs(3),
            hang_limit: Duration::from_secs(60),
            memory_limit: 2 << 30,
            limn: None,
            verbose: false,
        }
    }
}

/// The kind of a finding.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FindingKind {
    /// A panic (a reader), or a `panicked` message and exit code 101 (the binary).
    Panic,
    /// An input that took longer than the time limit.
    Slow,
    /// A reader input that did not finish within the hang limit (abandoned).
    Hang,
    /// A reader input that raised peak memory above the limit.
    Memory,
    /// An error message that is not one line naming the file and a place.
    BadMessage,
    /// The binary exited with a code other than 0, 1 or 2, or by a signal.
    BadExit,
    /// The binary changed a file it was not asked to overwrite (with `--force`).
    Overwrite,
}

impl FindingKind {
    /// Its name, as in the file names of findings.
    pub fn name(self) -> &'static str {
        match self {
            FindingKind::Panic => "panic",
            FindingKind::Slow => "slow",
            FindingKind::Hang => "hang",
            FindingKind::Memory => "memory",
            FindingKind::BadMessage => "bad-message",
            FindingKind::BadExit => "bad-exit",
            FindingKind::Overwrite => "overwrite",
        }
    }
}

/// Something wrong, with every input that showed it.
#[derive(Clone, Debug)]
pub struct Finding {
    /// What went wrong.
    pub kind: FindingKind,
    /// What groups inputs into one finding (the panic's location, the message's shape).
    pub signature: String,
    /// The first input's details (the panic message, the error, the time taken).
    pub detail: String,
    /// How many inputs showed it.
    pub count: u64,
    /// The index of the first input that showed it.
    pub first_input: u64,
    /// The files written (the first three inputs).
    pub files: Vec<PathBuf>,
}

/// What a run did.
#[derive(Clone, Debug)]
pub struct Summary {
    /// What was fuzzed.
    pub target: Target,
    /// The run's seed.
    pub seed: u64,
    /// Inputs run.
    pub inputs: u64,
    /// Wall-clock time.
    pub elapsed: Duration,
    /// Seed inputs, and the corpus at the end.
    pub corpus: (usize, usize),
    /// Distinct outcomes seen (error shapes, model shapes, exit codes).
    pub outcomes: usize,
    /// The slowest input: its time and index.
    pub slowest: (Duration, u64),
    /// Every finding.
    pub findings: Vec<Finding>,
    /// Why the run stopped before its budget, if it did.
    pub stopped: Option<String>,
    /// Remarks on the run (inputs generated but not run, and why).
    pub notes: Vec<String>,
}

impl Summary {
    /// Inputs per second of wall-clock time.
    pub fn rate(&self) -> f64 {
        self.inputs as f64 / self.elapsed.as_secs_f64().max(1e-9)
    }

    /// The findings of these kinds.
    pub fn of_kinds(&self, kinds: &[FindingKind]) -> Vec<&Finding> {
        self.findings
            .iter()
            .filter(|f| kinds.contains(&f.kind))
            .collect()
    }
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "fuzz {}: {} inputs in {:.1} s ({:.1}/s), seed {}, corpus {} -> {}, {} distinct outcomes, slowest {:.3} s (input {}), {} finding(s)",
            self.target,
            self.inputs,
            self.elapsed.as_secs_f64(),
            self.rate(),
            self.seed,
            self.corpus.0,
            self.corpus.1,
            self.outcomes,
            self.slowest.0.as_secs_f64(),
            self.slowest.1,
            self.findings.len()
        )?;
        if let Some(why) = &self.stopped {
            writeln!(f, "  stopped early: {why}")?;
        }
        for note in &self.notes {
            writeln!(f, "  note: {note}")?;
        }
        for x in &self.findings {
            writeln!(
                f,
                "  {} x{} (first: input {}): {}",
                x.kind.name(),
                x.count,
                x.first_input,
                x.signature
            )?;
            writeln!(f, "    {}", one_line(&x.detail, 400))?;
            for p in &x.files {
                writeln!(f, "    {}", p.display())?;
            }
        }
        Ok(())
    }
}

/// Runs the fuzzer as `config` says.
///
/// # Errors
/// A message if the run cannot start (no seeds, no `limn` binary, an unwritable folder).
pub fn run(config: &Config) -> Result<Summary, String> {
    match config.target {
        Target::Args => args::run(config),
        _ => readers::run(config),
    }
}

/// Runs one saved input (a finding's file) under `target` with every check, and describes
/// what happened (one line per problem, or what the input gave).
///
/// # Errors
/// A message if the file cannot be read, or (for [`Target::Args`]) the `limn` binary is
/// missing.
pub fn replay(config: &Config, file: &Path) -> Result<String, String> {
    let bytes = std::fs::read(file).map_err(|e| format!("{}: {e}", file.display()))?;
    match config.target {
        Target::Args => args::replay(config, &bytes),
        _ => Ok(readers::replay(config, &bytes)),
    }
}

/// A small deterministic pseudo-random generator (splitmix64): fast, 64 bits of state, and
/// the same sequence on every machine.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    /// The generator of input `index` of a run with seed `seed`.
    pub fn for_input(seed: u64, index: u64) -> Rng {
        let mut r = Rng(seed ^ index.wrapping_mul(0xD1B5_4A32_D192_ED03));
        Rng(r.next_u64())
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in `0..n` (0 if `n` is 0).
    pub fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next_u64() % n as u64) as usize
        }
    }

    /// True with probability `num / den`.
    pub fn chance(&mut self, num: u64, den: u64) -> bool {
        self.next_u64() % den < num
    }

    /// One element of a nonempty slice.
    pub fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[self.below(xs.len())]
    }
}

/// The findings of a run, and the files they are written to.
pub(crate) struct Recorder {
    dir: PathBuf,
    target: Target,
    seed: u64,
    findings: Vec<Finding>,
    by_signature: HashMap<(FindingKind, String), usize>,
    verbose: bool,
}

/// How many inputs of one finding are written.
const FILES_PER_FINDING: usize = 3;

impl Recorder {
    pub(crate) fn new(config: &Config) -> Result<Recorder, String> {
        let dir = config.out.join(config.target.name());
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        Ok(Recorder {
            dir,
            target: config.target,
            seed: config.seed,
            findings: Vec::new(),
            by_signature: HashMap::new(),
            verbose: config.verbose,
        })
    }

    /// Records a finding of input `index`; `input` is written (with extension `ext`) if it is
    /// among the first inputs of its finding.
    pub(crate) fn record(
        &mut self,
        kind: FindingKind,
        signature: String,
        detail: String,
        index: u64,
        input: &[u8],
        ext: &str,
    ) {
        let key = (kind, signature.clone());
        let slot = match self.by_signature.get(&key) {
            Some(&i) => i,
            None => {
                self.findings.push(Finding {
                    kind,
                    signature: signature.clone(),
                    detail: detail.clone(),
                    count: 0,
                    first_input: index,
                    files: Vec::new(),
                });
                self.by_signature.insert(key, self.findings.len() - 1);
                self.findings.len() - 1
            }
        };
        let finding = &mut self.findings[slot];
        finding.count += 1;
        if finding.files.len() >= FILES_PER_FINDING {
            return;
        }
        let stem = format!(
            "{}-{:08x}-seed{}-input{}",
            kind.name(),
            hash(&signature) as u32,
            self.seed,
            index
        );
        let file = self.dir.join(format!("{stem}.{ext}"));
        let note = format!(
            "target: {}\nkind: {}\nsignature: {}\nrun seed: {} (input {} of the run; `--seed {} --inputs {}` replays the run up to it)\nreplay: cargo run --release --example fuzz -- {} --replay {}\n\n{}\n",
            self.target,
            kind.name(),
            signature,
            self.seed,
            index,
            self.seed,
            index + 1,
            self.target,
            file.display(),
            detail
        );
        let written = std::fs::write(&file, input)
            .and_then(|()| std::fs::write(self.dir.join(format!("{stem}.txt")), note));
        match written {
            Ok(()) => finding.files.push(file),
            Err(e) => eprintln!("fuzz: cannot write {}: {e}", file.display()),
        }
        if self.verbose {
            eprintln!(
                "fuzz {}: input {index}: {}: {signature}",
                self.target,
                kind.name()
            );
        }
    }

    pub(crate) fn into_findings(self) -> Vec<Finding> {
        self.findings
    }
}

/// A 64-bit FNV-1a hash (names of finding files).
pub(crate) fn hash(s: &str) -> u64 {
    s.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// A message with its numbers and quoted parts blanked: what groups messages into kinds.
pub(crate) fn shape(message: &str) -> String {
    let mut out = String::new();
    let mut chars = message.chars().peekable();
    while let Some(c) = chars.next() {
        if c.is_ascii_digit() {
            while chars.peek().is_some_and(char::is_ascii_digit) {
                chars.next();
            }
            out.push('N');
        } else if c == '"' {
            // A quoted part, with escapes.
            let mut escaped = false;
            for d in chars.by_ref() {
                if escaped {
                    escaped = false;
                } else if d == '\\' {
                    escaped = true;
                } else if d == '"' {
                    break;
                }
            }
            out.push('Q');
        } else {
            out.push(c);
        }
        if out.len() > 160 {
            break;
        }
    }
    out
}

/// `s` on one line, cut to `max` characters.
pub(crate) fn one_line(s: &str, max: usize) -> String {
    let line: String = s
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .take(max)
        .collect();
    if s.chars().count() > max {
        format!("{line}...")
    } else {
        line
    }
}

/// The CPU time of this process and of its waited-for children (Linux `/proc/self/stat`, in
/// ticks of 1/100 s), if known.
pub fn cpu_time() -> Option<(Duration, Duration)> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    let after = &stat[stat.rfind(')')? + 2..];
    let f: Vec<u64> = after
        .split_whitespace()
        .skip(11)
        .take(4)
        .map(|x| x.parse().unwrap_or(0))
        .collect();
    if f.len() < 4 {
        return None;
    }
    let ticks = |t: u64| Duration::from_millis(t * 10);
    Some((ticks(f[0] + f[1]), ticks(f[2] + f[3])))
}

/// The peak resident memory of this process in bytes (Linux `VmHWM`), if known.
pub(crate) fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// The run's clock: the time budget and the input budget.
pub(crate) struct Budget {
    start: Instant,
    seconds: f64,
    max_inputs: Option<u64>,
}

impl Budget {
    pub(crate) fn new(config: &Config) -> Budget {
        Budget {
            start: Instant::now(),
            seconds: config.seconds,
            max_inputs: config.max_inputs,
        }
    }

    /// Whether input `index` may run.
    pub(crate) fn allows(&self, index: u64) -> bool {
        match self.max_inputs {
            Some(n) => index < n,
            None => self.start.elapsed().as_secs_f64() < self.seconds,
        }
    }

    pub(crate) fn elapsed(&self) -> Duration {
        self.start.elapsed()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_generator_is_deterministic() {
        let a: Vec<u64> = (0..4).map(|i| Rng::for_input(7, i).next_u64()).collect();
        let b: Vec<u64> = (0..4).map(|i| Rng::for_input(7, i).next_u64()).collect();
        assert_eq!(a, b);
        assert_ne!(a[0], a[1]);
    }

    #[test]
    fn shapes_blank_numbers_and_quotes() {
        assert_eq!(
            shape("line 12: patch 3: not a number: \"x\\\"y\""),
            "line N: patch N: not a number: Q"
        );
    }
}
