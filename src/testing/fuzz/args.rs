//! The `args` target: the `limn` binary run as a subprocess on command lines built from its
//! commands and flags and then mutated (values replaced by extreme numerals and garbage,
//! flags repeated, dropped, swapped, unknown flags, empty strings, non-UTF-8 bytes).
//!
//! The binary runs in a fresh temporary folder holding tiny models that this fuzzer writes;
//! every path on a generated command line is relative and inside that folder (a command line
//! that could name a file elsewhere is dropped before it runs), and the folder is restored
//! after every run and removed at the end. `limn::cli::run` would run in process, but relative
//! output paths would then resolve against the caller's folder and a long analysis could not
//! be stopped; a subprocess can be killed and is checked as a user sees it (exit code, stdout,
//! stderr).
//!
//! Checks: the exit code is 0, 1 or 2 (never a signal, never a panic's 101); with exit 2 the
//! binary prints exactly one line, on stderr, starting `limn: `, and nothing on stdout; a
//! nonzero exit prints at most one line on stderr; no file of the folder changes unless the
//! command line says `--force` and names it.

use super::argv::{generate, safe, Argv};
use super::{shape, Budget, Config, FindingKind, Recorder, Rng, Summary};
use std::collections::{BTreeMap, HashSet};
use std::ffi::OsString;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The models and files the fuzzer writes into its folder (name, content).
fn files() -> Vec<(&'static str, Vec<u8>)> {
    let text = |s: &str| s.as_bytes().to_vec();
    vec![
        ("quad.bpt", text("1\n1 1\n0 0 0\n0 1 0\n1 0 0\n1 1 0\n")),
        (
            "saddle.bpt",
            text("1\n2 2\n0 0 0\n0 1 1\n0 2 0\n1 0 1\n1 1 0\n1 2 -1\n2 0 0\n2 1 -1\n2 2 0\n"),
        ),
        (
            "tiny.json",
            text("{\"patches\":[{\"kind\":\"bezier\",\"degree\":[2,1],\"points\":[[0,0,0],[0,1,0],[1,0,\"1/2\"],[1,1,1],[2,0,0],[2,1,\"-1/3\"]],\"weights\":[1,2,1,1,\"3/2\",1]}]}"),
        ),
        (
            "mesh.obj",
            text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n"),
        ),
        (
            "tiny.teaset",
            text("1\n1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16\n16\n0,0,0\n0,1,0\n0,2,0\n0,3,0\n1,0,0\n1,1,1\n1,2,1\n1,3,0\n2,0,0\n2,1,1\n2,2,1\n2,3,0\n3,0,0\n3,1,0\n3,2,0\n3,3,0\n"),
        ),
        (
            "tiny.igs",
            include_bytes!("../../../fixtures/iges/forIGES/128-000.igs").to_vec(),
        ),
        ("bad.json", text("{\"patches\": [1]}")),
        ("empty.bpt", Vec::new()),
        ("exists.txt", text("a file the user made: never overwritten without --force\n")),
        ("sub/inner.bpt", text("1\n1 1\n0 0 0\n0 1 0\n1 0 0\n1 1 1\n")),
    ]
}

/// What one run of the binary did.
struct Run {
    code: Option<i32>,
    stdout: Vec<u8>,
    stderr: Vec<u8>,
    time: Duration,
    killed: bool,
}

fn os(arg: &[u8]) -> OsString {
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStringExt;
        OsString::from_vec(arg.to_vec())
    }
    #[cfg(not(unix))]
    {
        OsString::from(String::from_utf8_lossy(arg).into_owned())
    }
}

/// Runs `limn` with `argv` in `dir`, killing it at `limit`.
fn run_limn(limn: &Path, dir: &Path, argv: &Argv, limit: Duration) -> Result<Run, String> {
    let start = Instant::now();
    let mut child = Command::new(limn)
        .args(argv.iter().map(|a| os(a)))
        .current_dir(dir)
        .env("RUST_BACKTRACE", "0")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("{}: {e}", limn.display()))?;
    let mut out = child.stdout.take().ok_or("no stdout")?;
    let mut err = child.stderr.take().ok_or("no stderr")?;
    let out = std::thread::spawn(move || {
        let mut v = Vec::new();
        let _ = out.read_to_end(&mut v);
        v
    });
    let err = std::thread::spawn(move || {
        let mut v = Vec::new();
        let _ = err.read_to_end(&mut v);
        v
    });
    let mut killed = false;
    let mut pause = Duration::from_micros(200);
    let status = loop {
        if let Some(s) = child.try_wait().map_err(|e| e.to_string())? {
            break s;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            killed = true;
            break child.wait().map_err(|e| e.to_string())?;
        }
        std::thread::sleep(pause);
        pause = (pause * 2).min(Duration::from_millis(5));
    };
    let time = start.elapsed();
    Ok(Run {
        code: status.code(),
        stdout: out.join().unwrap_or_default(),
        stderr: err.join().unwrap_or_default(),
        time,
        killed,
    })
}

/// The fuzzer's folder: the files it wrote, to check and restore after each run.
struct Folder {
    dir: PathBuf,
    files: BTreeMap<PathBuf, Vec<u8>>,
}

impl Folder {
    fn create(limn: &Path, seed: u64) -> Result<Folder, String> {
        let base = std::env::temp_dir();
        let dir = (0..100)
            .map(|k| base.join(format!("limn-fuzz-args-{}-{seed}-{k}", std::process::id())))
            .find(|d| !d.exists())
            .ok_or("no free temporary folder name")?;
        std::fs::create_dir_all(dir.join("sub")).map_err(|e| format!("{}: {e}", dir.display()))?;
        let mut files = BTreeMap::new();
        for (name, content) in self::files() {
            let p = dir.join(name);
            std::fs::write(&p, &content).map_err(|e| format!("{}: {e}", p.display()))?;
            files.insert(PathBuf::from(name), content);
        }
        // A certificate for `limn check`, made by the binary itself.
        let argv: Argv = [
            "silhouette",
            "saddle.bpt",
            "--dir",
            "1,2,3",
            "--certificate",
            "cert.json",
        ]
        .iter()
        .map(|s| s.as_bytes().to_vec())
        .collect();
        let _ = run_limn(limn, &dir, &argv, Duration::from_secs(60))?;
        let cert = std::fs::read(dir.join("cert.json")).unwrap_or_else(|_| b"{}".to_vec());
        std::fs::write(dir.join("cert.json"), &cert).map_err(|e| e.to_string())?;
        files.insert(PathBuf::from("cert.json"), cert);
        Ok(Folder { dir, files })
    }

    /// The folder's files (relative paths) other than its own, and its own changed:
    /// then restores it.
    fn restore(&self) -> (Vec<PathBuf>, Vec<PathBuf>) {
        let mut changed = Vec::new();
        for (name, content) in &self.files {
            let p = self.dir.join(name);
            if std::fs::read(&p).ok().as_deref() != Some(content.as_slice()) {
                changed.push(name.clone());
                if p.is_dir() {
                    let _ = std::fs::remove_dir_all(&p);
                }
                let _ = std::fs::write(&p, content);
            }
        }
        let mut new = Vec::new();
        for sub in [PathBuf::new(), PathBuf::from("sub")] {
            let Ok(entries) = std::fs::read_dir(self.dir.join(&sub)) else {
                continue;
            };
            for e in entries.flatten() {
                let rel = sub.join(e.file_name());
                if rel == Path::new("sub") || self.files.contains_key(&rel) {
                    continue;
                }
                let p = e.path();
                if p.is_dir() {
                    let _ = std::fs::remove_dir_all(&p);
                } else {
                    let _ = std::fs::remove_file(&p);
                }
                new.push(rel);
            }
        }
        if !self.dir.join("sub").is_dir() {
            let _ = std::fs::remove_file(self.dir.join("sub"));
            let _ = std::fs::create_dir_all(self.dir.join("sub"));
            for (name, content) in &self.files {
                if name.starts_with("sub") {
                    let _ = std::fs::write(self.dir.join(name), content);
                }
            }
        }
        (changed, new)
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// The `limn` binary: as configured, or `LIMN_BIN`, or beside the running executable
/// (`target/release/limn` for `target/release/examples/fuzz`).
fn find_limn(config: &Config) -> Result<PathBuf, String> {
    if let Some(p) = &config.limn {
        return Ok(p.clone());
    }
    if let Some(p) = std::env::var_os("LIMN_BIN") {
        return Ok(PathBuf::from(p));
    }
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let name = format!("limn{}", std::env::consts::EXE_SUFFIX);
    let candidates: Vec<PathBuf> = exe
        .ancestors()
        .skip(1)
        .take(3)
        .map(|d| d.join(&name))
        .collect();
    candidates.into_iter().find(|p| p.is_file()).ok_or_else(|| {
        "no limn binary beside the fuzzer: build it (`cargo build --release`), or give --limn PATH or LIMN_BIN".to_string()
    })
}

/// The argument as text, for messages.
fn show(argv: &Argv) -> String {
    let parts: Vec<String> = argv
        .iter()
        .map(|a| {
            let s = String::from_utf8_lossy(a);
            let s: String = if s.chars().count() > 60 {
                format!(
                    "{}...({} bytes)",
                    s.chars().take(40).collect::<String>(),
                    a.len()
                )
            } else {
                s.into_owned()
            };
            if s.is_empty() || s.contains([' ', '\'', '"', ';', '&', '|', '*', '?', '$']) {
                format!("'{}'", s.replace('\'', "'\\''"))
            } else {
                s
            }
        })
        .collect();
    format!("limn {}", parts.join(" "))
}

/// The argv as JSON: an array of strings, or of byte arrays where not UTF-8.
fn to_json(argv: &Argv) -> Vec<u8> {
    let items: Vec<serde_json::Value> = argv
        .iter()
        .map(|a| match std::str::from_utf8(a) {
            Ok(s) => serde_json::Value::from(s),
            Err(_) => serde_json::Value::from(a.clone()),
        })
        .collect();
    serde_json::to_vec(&items).unwrap_or_default()
}

fn from_json(bytes: &[u8]) -> Result<Argv, String> {
    let v: Vec<serde_json::Value> = serde_json::from_slice(bytes).map_err(|e| e.to_string())?;
    v.into_iter()
        .map(|x| match x {
            serde_json::Value::String(s) => Ok(s.into_bytes()),
            serde_json::Value::Array(b) => b
                .iter()
                .map(|n| {
                    n.as_u64()
                        .and_then(|n| u8::try_from(n).ok())
                        .ok_or("not a byte")
                })
                .collect::<Result<Vec<u8>, _>>()
                .map_err(str::to_string),
            _ => Err("expected strings or byte arrays".to_string()),
        })
        .collect()
}

/// The problems with one run: (kind, signature, detail).
fn problems(
    argv: &Argv,
    run: &Run,
    changed: &[PathBuf],
    limit: Duration,
) -> Vec<(FindingKind, String, String)> {
    let command = argv
        .first()
        .map(|a| String::from_utf8_lossy(a).into_owned())
        .unwrap_or_default();
    let stderr = String::from_utf8_lossy(&run.stderr);
    let lines: Vec<&str> = stderr.lines().collect();
    let first = lines.first().copied().unwrap_or("");
    let said = format!(
        "{}: exit {:?} after {:.2} s; stderr: {:?}; stdout: {} bytes",
        show(argv),
        run.code,
        run.time.as_secs_f64(),
        super::one_line(&stderr, 600),
        run.stdout.len()
    );
    let mut out = Vec::new();
    if run.killed {
        let limited = argv.iter().any(|a| a.starts_with(b"--time-limit"));
        out.push((
            FindingKind::Slow,
            format!(
                "{command} ran past {:?}{}",
                limit,
                if limited { " (with --time-limit)" } else { "" }
            ),
            said.clone(),
        ));
        return out;
    }
    if stderr.contains("panicked") || run.code == Some(101) {
        let place = stderr
            .split("panicked at ")
            .nth(1)
            .and_then(|s| s.split(':').next())
            .unwrap_or("?")
            .to_string();
        let line = stderr
            .split("panicked at ")
            .nth(1)
            .and_then(|s| s.split(':').nth(1))
            .unwrap_or("");
        out.push((
            FindingKind::Panic,
            format!("panic at {place}:{line}"),
            said.clone(),
        ));
    }
    match run.code {
        None => out.push((
            FindingKind::BadExit,
            format!("{command}: killed by a signal"),
            said.clone(),
        )),
        Some(0..=2) => {}
        Some(c) if c != 101 => out.push((
            FindingKind::BadExit,
            format!("{command}: exit {c}"),
            said.clone(),
        )),
        Some(_) => {}
    }
    if run.code == Some(2) {
        let problem = if lines.len() != 1 || !stderr.ends_with('\n') {
            Some(format!("exit 2 with {} lines on stderr", lines.len()))
        } else if !first.starts_with("limn: ") {
            Some("exit 2 with stderr not starting `limn: `".to_string())
        } else if !run.stdout.is_empty() {
            Some("exit 2 with output on stdout".to_string())
        } else {
            None
        };
        if let Some(p) = problem {
            out.push((
                FindingKind::BadMessage,
                format!("{p}: {}", shape(first)),
                said.clone(),
            ));
        }
    } else if run.code.is_some_and(|c| c != 0) && lines.len() > 1 {
        out.push((
            FindingKind::BadMessage,
            format!(
                "exit {:?} with {} lines on stderr: {}",
                run.code,
                lines.len(),
                shape(first)
            ),
            said.clone(),
        ));
    }
    let forced = argv.iter().any(|a| a.starts_with(b"--force"));
    for name in changed {
        let named = argv.iter().any(|a| {
            let a = String::from_utf8_lossy(a);
            a.ends_with(&*name.to_string_lossy())
        });
        if !(forced && named) {
            out.push((
                FindingKind::Overwrite,
                format!(
                    "{command} changed {} without --force naming it",
                    name.display()
                ),
                said.clone(),
            ));
        }
    }
    out
}

pub(crate) fn run(config: &Config) -> Result<Summary, String> {
    let limn = find_limn(config)?;
    let folder = Folder::create(&limn, config.seed)?;
    let mut recorder = Recorder::new(config)?;
    let mut seen: HashSet<String> = HashSet::new();
    let mut slowest = (Duration::ZERO, 0);
    let budget = Budget::new(config);
    let mut index = 0u64;
    let mut skipped = 0u64;
    while budget.allows(index) {
        let mut rng = Rng::for_input(config.seed, index);
        let argv = generate(&mut rng);
        if !safe(&argv) {
            skipped += 1;
            index += 1;
            continue;
        }
        let run = run_limn(&limn, &folder.dir, &argv, config.time_limit)?;
        let (changed, _new) = folder.restore();
        if run.time > slowest.0 {
            slowest = (run.time, index);
        }
        for (kind, signature, detail) in problems(&argv, &run, &changed, config.time_limit) {
            recorder.record(kind, signature, detail, index, &to_json(&argv), "json");
        }
        let first = String::from_utf8_lossy(&run.stderr)
            .lines()
            .next()
            .map(shape)
            .unwrap_or_default();
        seen.insert(format!("{:?} {first}", run.code));
        index += 1;
    }
    let notes = if skipped > 0 {
        vec![format!("{skipped} of the {index} command lines generated could name a path outside the folder and were not run")]
    } else {
        Vec::new()
    };
    Ok(Summary {
        target: config.target,
        seed: config.seed,
        inputs: index - skipped,
        elapsed: budget.elapsed(),
        corpus: (0, 0),
        outcomes: seen.len(),
        slowest,
        findings: recorder.into_findings(),
        stopped: None,
        notes,
    })
}

pub(crate) fn replay(config: &Config, bytes: &[u8]) -> Result<String, String> {
    let argv = from_json(bytes)?;
    if !safe(&argv) {
        return Err(format!(
            "{}: could name a path outside the folder; not run",
            show(&argv)
        ));
    }
    let limn = find_limn(config)?;
    let folder = Folder::create(&limn, config.seed)?;
    let run = run_limn(&limn, &folder.dir, &argv, config.time_limit)?;
    let (changed, _) = folder.restore();
    let found = problems(&argv, &run, &changed, config.time_limit);
    let mut text = format!(
        "{}: exit {:?} after {:.3} s\nstdout ({} bytes): {}\nstderr: {}",
        show(&argv),
        run.code,
        run.time.as_secs_f64(),
        run.stdout.len(),
        super::one_line(&String::from_utf8_lossy(&run.stdout), 300),
        String::from_utf8_lossy(&run.stderr)
    );
    for (kind, signature, _) in found {
        text.push_str(&format!("\n{}: {signature}", kind.name()));
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unsafe_paths_are_refused() {
        let argv = |xs: &[&str]| -> Argv { xs.iter().map(|s| s.as_bytes().to_vec()).collect() };
        assert!(safe(&argv(&["info", "sub/inner.bpt", "-o", "out.json"])));
        for bad in [
            "/etc/x",
            "--output=/x",
            "-o/x",
            "../x",
            "sub/../../x",
            "~/x",
            "a\0b",
        ] {
            assert!(!safe(&argv(&["info", bad])), "{bad}");
        }
    }

    #[test]
    fn argv_round_trips_through_json() {
        let a: Argv = vec![b"info".to_vec(), b"\xff\xfe".to_vec(), Vec::new()];
        assert_eq!(from_json(&to_json(&a)).unwrap(), a);
    }
}
