//! The reader targets: seeds from `fixtures/` and `tests/corpus/bad/`, a worker thread that
//! reads under `catch_unwind`, and the checks of what a read gives.

use super::mutate::{mutate, MAX_LEN};
use super::{shape, Budget, Config, FindingKind, Recorder, Rng, Summary, Target};
use crate::io::{read_model_bytes, Place, ReadError};
use crate::model::{default_weld, Format, ModelInfo};
use std::cell::RefCell;
use std::collections::HashSet;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::sync::Once;
use std::time::{Duration, Instant};

/// Seed files larger than this are left out (they would slow every mutation).
const MAX_SEED_LEN: usize = 256 * 1024;

/// The most inputs kept in the corpus.
const MAX_CORPUS: usize = 2048;

/// A seed or corpus input: the name it is read under, and its bytes.
#[derive(Clone)]
struct Input {
    name: String,
    bytes: Vec<u8>,
}

/// The format a file of the project is, by its name (`None`: only for detection).
fn kind_of(path: &Path) -> Option<Format> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("json") => Some(Format::Json),
        Some("bpt") => Some(Format::Bpt),
        Some("teaset") => Some(Format::Teaset),
        Some("igs" | "iges") => Some(Format::Iges),
        Some("obj") => Some(Format::Obj),
        Some("stp" | "step") => Some(Format::Step),
        None if path.parent().is_some_and(|p| p.ends_with("newell_teaset"))
            && path.file_name().is_some_and(|n| n != "README") =>
        {
            Some(Format::Teaset)
        }
        _ => None,
    }
}

/// The format a target reads as (`None`: detect).
fn format_of(target: Target) -> Option<Format> {
    match target {
        Target::Json => Some(Format::Json),
        Target::Bpt => Some(Format::Bpt),
        Target::Teaset => Some(Format::Teaset),
        Target::Iges => Some(Format::Iges),
        Target::Obj => Some(Format::Obj),
        Target::Step => Some(Format::Step),
        Target::Detect | Target::Args => None,
    }
}

/// Files under `dir`, recursively, sorted (so that runs are reproducible).
fn files_under(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut paths: Vec<_> = entries.flatten().map(|e| e.path()).collect();
    paths.sort();
    for p in paths {
        if p.is_dir() {
            files_under(&p, out);
        } else {
            out.push(p);
        }
    }
}

/// limn's native JSON with one of each kind of patch: a rational Bézier patch, a NURBS
/// surface with an interior knot, and a patch with the default kind and weights (a seed of
/// the fuzzer, and a fixture of the readers' property tests).
pub fn json_sample() -> String {
    let grid = |nu: usize, nv: usize| -> String {
        let pts: Vec<String> = (0..nu)
            .flat_map(|i| (0..nv).map(move |j| format!("[{i}, {j}, \"{}/3\"]", (i * j) % 5)))
            .collect();
        pts.join(", ")
    };
    format!(
        concat!(
            "{{\"patches\": [\n",
            "  {{\"kind\": \"bezier\", \"degree\": [2, 1],\n",
            "   \"points\": [{}],\n",
            "   \"weights\": [1, 2, \"3/2\", 1, 0.5, 1]}},\n",
            "  {{\"kind\": \"nurbs\", \"degree\": [2, 2],\n",
            "   \"knots_u\": [0, 0, 0, 0.5, 1, 1, 1], \"knots_v\": [0, 0, 0, 1, 1, 1],\n",
            "   \"points\": [{}],\n",
            "   \"weights\": [1, 1, 1, 2, 1, 1, 1, \"1/2\", 1, 1, 1, 1]}},\n",
            "  {{\"degree\": [1, 1], \"points\": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1e-3]]}}\n",
            "]}}\n"
        ),
        grid(3, 2),
        grid(4, 3)
    )
}

/// Small generated models of each format.
fn generated(format: Format) -> Vec<Input> {
    let input = |name: &str, text: String| Input {
        name: name.to_string(),
        bytes: text.into_bytes(),
    };
    match format {
        Format::Json => {
            let teapot = crate::testing::teapot();
            let patches: Vec<_> = teapot
                .patches
                .iter()
                .take(2)
                .map(|p| p.surface.clone())
                .collect();
            vec![
                input("mixed.json", json_sample()),
                input("teapot2.json", crate::io::write_model(&patches)),
                input(
                    "quad.json",
                    "{\"patches\":[{\"degree\":[1,1],\"points\":[[0,0,0],[0,1,0],[1,0,0],[1,1,\"1/7\"]]}]}"
                        .to_string(),
                ),
            ]
        }
        Format::Bpt => vec![
            input("quad.bpt", "1\n1 1\n0 0 0\n0 1 0\n1 0 0\n1 1 0.5\n".into()),
            input("teapot.bpt", crate::TEAPOT.to_string()),
        ],
        Format::Teaset => {
            let idx: Vec<String> = (1..=16).map(|i| i.to_string()).collect();
            let verts: String = (0..16)
                .map(|k| format!("{},{},{}\n", k / 4, k % 4, (k * k) % 3))
                .collect();
            vec![input(
                "one.teaset",
                format!("1\n{}\n16\n{verts}", idx.join(",")),
            )]
        }
        Format::Obj => vec![input(
            "tetra.obj",
            "# a tetrahedron\nv 0 0 0\nv 1 0 0 1\nv 0 1 0 2\nv 0 0 1/3\nvn 0 0 1\nf 1/1/1 2//1 3\nf 1 -1 2\nf 2 3 4\nf 1 3 -1\n"
                .into(),
        )],
        Format::Iges | Format::Step => Vec::new(),
    }
}

/// The seeds of a target: the project's files of its kind (all for detection) and small
/// generated models.
fn seeds(target: Target) -> Vec<Input> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    files_under(&root.join("fixtures"), &mut files);
    files_under(&root.join("tests/corpus/bad"), &mut files);
    let want = format_of(target);
    let mut out = Vec::new();
    for f in files {
        let kind = kind_of(&f);
        let in_bad = f.starts_with(root.join("tests/corpus/bad"));
        let keep = match want {
            Some(w) => kind == Some(w),
            // Detection: every model file, and the bad corpus's files of no known kind.
            None => kind.is_some() || (in_bad && !f.ends_with("EXPECTED.tsv")),
        };
        if !keep {
            continue;
        }
        if let Ok(bytes) = std::fs::read(&f) {
            if bytes.len() <= MAX_SEED_LEN {
                let name = f
                    .file_name()
                    .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
                out.push(Input { name, bytes });
            }
        }
    }
    let formats = match want {
        Some(w) => vec![w],
        None => vec![Format::Json, Format::Bpt, Format::Teaset, Format::Obj],
    };
    for f in formats {
        out.extend(generated(f));
    }
    out
}

/// Tokens of the target's formats, inserted by mutations.
fn dictionary(target: Target) -> Vec<&'static str> {
    let json = [
        "{",
        "}",
        "[",
        "]",
        ",",
        ":",
        "\"",
        "null",
        "true",
        "\"patches\"",
        "\"kind\"",
        "\"nurbs\"",
        "\"bezier\"",
        "\"degree\"",
        "\"points\"",
        "\"weights\"",
        "\"knots_u\"",
        "\"knots_v\"",
        "[0,0,0]",
        "\"1/3\"",
        "\\u0000",
        "\\n",
        "\\u2028",
        "\\ud800",
    ];
    let text = [
        " ", "\n", "\r\n", "\t", ",", "1", "0", "-1", "16", "64", "3 3", "1 1", "\u{a0}",
        "\u{2028}", "\u{feff}",
    ];
    let obj = [
        "v ",
        "f ",
        "vn ",
        "vt ",
        "o ",
        "g ",
        "#",
        "/",
        "//",
        "\nf 1 2 3\n",
        "\nv 0 0 0\n",
        "-1",
        "0/0",
    ];
    let iges = [
        "H",
        "1H,",
        "1H;",
        "3HABC",
        "99H",
        ";",
        ",",
        "128,",
        "124,",
        "144,",
        "510,",
        "       S      1\n",
        "       D      1\n",
        "       P      1\n",
        "       T      1\n",
    ];
    let mut d: Vec<&str> = text.to_vec();
    match target {
        Target::Json => d.extend(json),
        Target::Obj => d.extend(obj),
        Target::Iges => d.extend(iges),
        Target::Detect => {
            d.extend(json);
            d.extend(obj);
            d.extend(iges);
        }
        _ => {}
    }
    d
}

/// What one read gave.
pub(crate) enum Verdict {
    /// A model: its shape (patches, meshes, warnings).
    Model(String),
    /// An error.
    Error(ReadError),
    /// A panic: where (reading or summarising) and its message and location.
    Panic(&'static str, String),
}

struct Job {
    name: String,
    bytes: Vec<u8>,
    format: Option<Format>,
}

struct Done {
    verdict: Verdict,
    read: Duration,
    total: Duration,
}

thread_local! {
    /// On a worker thread: the last panic's message and location.
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
    static IS_WORKER: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Installs (once) a panic hook that keeps quiet on worker threads and records the panic's
/// message and location there; other threads' panics go to the previous hook.
fn install_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if IS_WORKER.with(std::cell::Cell::get) {
                let payload = info.payload();
                let msg = payload
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_default();
                let place = info
                    .location()
                    .map(|l| format!("{}:{}", l.file(), l.line()))
                    .unwrap_or_default();
                LAST_PANIC.with(|p| *p.borrow_mut() = Some(format!("{msg} at {place}")));
            } else {
                previous(info);
            }
        }));
    });
}

/// Reads, then summarises as `limn info` does, catching panics.
fn execute(job: Job) -> Done {
    let start = Instant::now();
    let caught = |stage: &'static str| {
        let what = LAST_PANIC
            .with(|p| p.borrow_mut().take())
            .unwrap_or_default();
        Verdict::Panic(stage, what)
    };
    let read = catch_unwind(AssertUnwindSafe(|| {
        read_model_bytes(&job.name, &job.bytes, job.format)
    }));
    let read_time = start.elapsed();
    let verdict = match read {
        Err(_) => caught("read"),
        Ok(Err(e)) => Verdict::Error(e),
        Ok(Ok(model)) => {
            let summary = catch_unwind(AssertUnwindSafe(|| {
                let info = ModelInfo::of(&job.name, &model, default_weld(&model));
                drop(info);
            }));
            match summary {
                Err(_) => caught("summarise (ModelInfo::of)"),
                Ok(()) => {
                    let mut warnings: Vec<String> =
                        model.warnings.iter().map(|w| shape(&w.message)).collect();
                    warnings.sort();
                    warnings.dedup();
                    Verdict::Model(format!(
                        "{:?}: {} patches, {} meshes; {}",
                        model.format,
                        model.patches.len().next_power_of_two(),
                        model.meshes.len(),
                        warnings.join("; ")
                    ))
                }
            }
        }
    };
    Done {
        verdict,
        read: read_time,
        total: start.elapsed(),
    }
}

/// A worker thread that runs jobs.
struct Worker {
    jobs: Sender<Job>,
    done: Receiver<Done>,
}

impl Worker {
    fn spawn() -> Result<Worker, String> {
        install_hook();
        let (jobs, job_rx) = mpsc::channel::<Job>();
        let (done_tx, done) = mpsc::channel();
        std::thread::Builder::new()
            .name("limn-fuzz-worker".into())
            // Deep structures must not overflow a small stack before a reader's own limit.
            .stack_size(256 << 20)
            .spawn(move || {
                IS_WORKER.with(|w| w.set(true));
                for job in job_rx {
                    if done_tx.send(execute(job)).is_err() {
                        break;
                    }
                }
            })
            .map_err(|e| format!("cannot start a worker thread: {e}"))?;
        Ok(Worker { jobs, done })
    }
}

/// What is wrong with an error, if anything: one line, starting with the file name, a
/// nonempty message, a place inside the file.
pub(crate) fn message_problem(name: &str, bytes: &[u8], e: &ReadError) -> Option<String> {
    let text = e.to_string();
    let lines = 1 + bytes.iter().filter(|&&b| b == b'\n').count();
    if !text.starts_with(&format!("{name}: ")) {
        return Some("does not start with the file name".into());
    }
    if e.message.trim().is_empty() {
        return Some("an empty message".into());
    }
    if let Some(c) = text
        .chars()
        .find(|&c| c.is_control() || c == '\u{2028}' || c == '\u{2029}')
    {
        return Some(format!("not one line (it holds {c:?})"));
    }
    let n = text.chars().count();
    if n >= 1000 {
        return Some(format!("{n} characters long"));
    }
    match &e.place {
        Place::Line(l) | Place::LineColumn(l, _) if *l == 0 || *l > lines => {
            Some(format!("line {l} of a file of {lines} lines"))
        }
        Place::LineColumn(_, 0) => Some("column 0".into()),
        Place::Entity { de: 0, .. } => Some("directory entry 0".into()),
        Place::Named(s) if s.trim().is_empty() => Some("an empty place".into()),
        _ => None,
    }
}

/// What a verdict is, as a key of the corpus's feedback.
fn outcome(verdict: &Verdict) -> String {
    match verdict {
        Verdict::Model(s) => format!("ok: {s}"),
        Verdict::Error(e) => {
            let place = match &e.place {
                Place::File => "file",
                Place::Line(_) => "line",
                Place::LineColumn(..) => "line-column",
                Place::Entity { .. } => "entity",
                Place::Instance { .. } => "instance",
                Place::Patch { .. } => "patch",
                Place::Named(_) => "named",
            };
            format!("error {place}: {}", shape(&e.message))
        }
        Verdict::Panic(stage, m) => format!("panic {stage}: {}", shape(m)),
    }
}

/// The reader targets' loop.
pub(crate) fn run(config: &Config) -> Result<Summary, String> {
    let target = config.target;
    let format = format_of(target);
    let mut corpus = seeds(target);
    if corpus.is_empty() {
        return Err(format!("no seeds for {target}"));
    }
    let n_seeds = corpus.len();
    let dict = dictionary(target);
    let mut recorder = Recorder::new(config)?;
    let mut worker = Worker::spawn()?;
    let mut seen: HashSet<String> = HashSet::new();
    let mut slowest = (Duration::ZERO, 0);
    let mut abandoned = 0;
    let mut stopped = None;
    let mut peak = super::peak_memory().unwrap_or(0);
    let budget = Budget::new(config);
    let mut index = 0u64;
    while budget.allows(index) {
        let mut rng = Rng::for_input(config.seed, index);
        let base = &corpus[rng.below(corpus.len())];
        let name = base.name.clone();
        let mut bytes = base.bytes.clone();
        let other = &corpus[rng.below(corpus.len())].bytes;
        let iges = target == Target::Iges || (target == Target::Detect && name.contains(".igs"));
        let most = if rng.chance(1, 4) { 16 } else { 4 };
        let count = 1 + rng.below(most);
        for _ in 0..count {
            mutate(&mut rng, &mut bytes, other, &dict, iges);
        }
        let input = bytes.clone();
        if worker
            .jobs
            .send(Job {
                name: name.clone(),
                bytes,
                format,
            })
            .is_err()
        {
            return Err("the worker thread ended".into());
        }
        let done = match worker.done.recv_timeout(config.time_limit) {
            Ok(d) => Some(d),
            Err(RecvTimeoutError::Disconnected) => return Err("the worker thread died".into()),
            Err(RecvTimeoutError::Timeout) => {
                let rest = config.hang_limit.saturating_sub(config.time_limit);
                let late = worker.done.recv_timeout(rest).ok();
                if late.is_none() {
                    recorder.record(
                        FindingKind::Hang,
                        format!("a read of {name} that did not finish"),
                        format!(
                            "read_model_bytes({name:?}, {} bytes, {format:?}) ran for more than {:?}; abandoned",
                            input.len(),
                            config.hang_limit
                        ),
                        index,
                        &input,
                        "bin",
                    );
                    abandoned += 1;
                    worker = Worker::spawn()?;
                    if abandoned >= 3 {
                        stopped =
                            Some("three inputs hung (their threads are still running)".into());
                        break;
                    }
                }
                late
            }
        };
        if let Some(done) = done {
            if done.total > slowest.0 {
                slowest = (done.total, index);
            }
            let key = outcome(&done.verdict);
            if done.total > config.time_limit {
                recorder.record(
                    FindingKind::Slow,
                    format!("slow ({}): {key}", if done.read > config.time_limit { "read" } else { "summary" }),
                    format!(
                        "read_model_bytes({name:?}, {} bytes, {format:?}): read {:.2} s, read and summarised {:.2} s: {key}",
                        input.len(),
                        done.read.as_secs_f64(),
                        done.total.as_secs_f64()
                    ),
                    index,
                    &input,
                    "bin",
                );
            }
            if index % 256 == 0 || done.total > Duration::from_millis(20) {
                if let Some(now) = super::peak_memory() {
                    if now > config.memory_limit && peak <= config.memory_limit {
                        recorder.record(
                            FindingKind::Memory,
                            format!("peak memory above {} MiB", config.memory_limit >> 20),
                            format!(
                                "after read_model_bytes({name:?}, {} bytes, {format:?}) the process's peak memory is {} MiB: {key}",
                                input.len(),
                                now >> 20
                            ),
                            index,
                            &input,
                            "bin",
                        );
                    }
                    peak = peak.max(now);
                }
            }
            match &done.verdict {
                Verdict::Panic(stage, what) => recorder.record(
                    FindingKind::Panic,
                    format!("panic in {stage}: {}", panic_place(what)),
                    format!(
                        "read_model_bytes({name:?}, {} bytes, {format:?}) panicked in {stage}: {what}",
                        input.len()
                    ),
                    index,
                    &input,
                    "bin",
                ),
                Verdict::Error(e) => {
                    if let Some(problem) = message_problem(&name, &input, e) {
                        recorder.record(
                            FindingKind::BadMessage,
                            format!("{problem}: {key}"),
                            format!("{problem}: {:?}", e.to_string()),
                            index,
                            &input,
                            "bin",
                        );
                    }
                }
                Verdict::Model(_) => {}
            }
            if seen.insert(key) && input.len() <= MAX_LEN / 2 {
                let new = Input { name, bytes: input };
                if corpus.len() < MAX_CORPUS {
                    corpus.push(new);
                } else {
                    let k = n_seeds + rng.below(MAX_CORPUS - n_seeds);
                    corpus[k] = new;
                }
            }
        }
        index += 1;
    }
    Ok(Summary {
        target,
        seed: config.seed,
        inputs: index,
        elapsed: budget.elapsed(),
        corpus: (n_seeds, corpus.len()),
        outcomes: seen.len(),
        slowest,
        findings: recorder.into_findings(),
        stopped,
        notes: Vec::new(),
    })
}

/// The source location in a panic description (`message at file:line`).
fn panic_place(what: &str) -> String {
    what.rsplit_once(" at ")
        .map_or_else(|| shape(what), |(_, place)| place.to_string())
}

/// Runs one input with every check, on a worker thread.
pub(crate) fn replay(config: &Config, bytes: &[u8]) -> String {
    let format = format_of(config.target);
    let name = format!("replay.{}", config.target);
    let worker = match Worker::spawn() {
        Ok(w) => w,
        Err(e) => return e,
    };
    let job = Job {
        name: name.clone(),
        bytes: bytes.to_vec(),
        format,
    };
    if worker.jobs.send(job).is_err() {
        return "the worker thread ended".into();
    }
    match worker.done.recv_timeout(config.hang_limit) {
        Err(_) => format!("hang: no result within {:?}", config.hang_limit),
        Ok(done) => {
            let time = format!(
                "read {:.3} s, read and summarised {:.3} s",
                done.read.as_secs_f64(),
                done.total.as_secs_f64()
            );
            let slow = if done.total > config.time_limit {
                " (slow)"
            } else {
                ""
            };
            match done.verdict {
                Verdict::Model(s) => format!("model: {s}; {time}{slow}"),
                Verdict::Panic(stage, what) => format!("panic in {stage}: {what}; {time}{slow}"),
                Verdict::Error(e) => {
                    let problem = message_problem(&name, bytes, &e)
                        .map_or(String::new(), |p| format!(" (bad message: {p})"));
                    format!("error: {:?}{problem}; {time}{slow}", e.to_string())
                }
            }
        }
    }
}
