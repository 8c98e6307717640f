//! Bad input to `limn info`: every malformed file in `tests/corpus/bad/` and every bad
//! argument gives exit code 2 and one line on stderr naming the file, the place and what is
//! wrong, and never a panic.
//!
//! `tests/corpus/bad/EXPECTED.tsv` lists, per file, a substring the message must contain
//! (the place and the problem), so a message that loses its place fails here.

use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The corpus, relative to the crate root (the tests run the binary from there, so the
/// messages name the files as given on the command line).
const CORPUS: &str = "tests/corpus/bad";

/// Longer than any run of `limn info` on a small file should take (a debug build included).
const DEADLINE: Duration = Duration::from_secs(30);

/// What one run of the binary did.
struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

impl Run {
    fn describe(&self) -> String {
        format!(
            "exit code {:?}\n--- stdout ---\n{}\n--- stderr ---\n{}",
            self.code, self.stdout, self.stderr
        )
    }
}

/// Runs `limn` with `args` from the crate root, killing it if it runs past [`DEADLINE`].
fn limn(args: &[&str]) -> Run {
    let mut child = Command::new(env!("CARGO_BIN_EXE_limn"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("RUST_BACKTRACE", "0")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the limn binary starts");
    // Read both pipes on threads so that a large output cannot block the child.
    let mut out = child.stdout.take().expect("piped stdout");
    let mut err = child.stderr.take().expect("piped stderr");
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
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("waiting for limn") {
            break status;
        }
        if start.elapsed() > DEADLINE {
            let _ = child.kill();
            let _ = child.wait();
            panic!("limn {args:?} ran for more than {DEADLINE:?} (a hang?)");
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    Run {
        code: status.code(),
        stdout: String::from_utf8_lossy(&out.join().expect("stdout reader")).into_owned(),
        stderr: String::from_utf8_lossy(&err.join().expect("stderr reader")).into_owned(),
    }
}

/// The problems with a run that should have failed with exit code 2 and exactly one line
/// on stderr starting with `prefix` and containing `needle`; empty if none.
fn one_line_failure(run: &Run, prefix: &str, needle: &str) -> Vec<String> {
    let mut problems = Vec::new();
    if run.stdout.contains("panicked") || run.stderr.contains("panicked") {
        problems.push("it panicked".to_string());
    }
    if run.code != Some(2) {
        problems.push(format!("exit code {:?}, expected 2", run.code));
    }
    if !run.stdout.is_empty() {
        problems.push("it wrote to stdout".to_string());
    }
    let lines: Vec<&str> = run.stderr.lines().collect();
    if lines.len() != 1 || !run.stderr.ends_with('\n') {
        problems.push(format!(
            "stderr has {} lines, expected exactly one",
            lines.len()
        ));
    }
    let first = lines.first().copied().unwrap_or("");
    if !first.starts_with(prefix) {
        problems.push(format!("stderr does not start with {prefix:?}"));
    }
    if !first.contains(needle) {
        problems.push(format!("stderr does not contain {needle:?}"));
    }
    problems
}

/// `EXPECTED.tsv`: file name -> substring. Lines starting with `#` are comments.
fn expected() -> BTreeMap<String, String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(CORPUS)
        .join("EXPECTED.tsv");
    let text = std::fs::read_to_string(&path).expect("EXPECTED.tsv is readable");
    let mut map = BTreeMap::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() || line.starts_with('#') {
            continue;
        }
        let (file, needle) = line
            .split_once('\t')
            .unwrap_or_else(|| panic!("EXPECTED.tsv line {}: no tab in {line:?}", i + 1));
        assert!(
            !needle.trim().is_empty(),
            "EXPECTED.tsv line {}: empty substring for {file}",
            i + 1
        );
        let old = map.insert(file.to_string(), needle.to_string());
        assert!(old.is_none(), "EXPECTED.tsv lists {file} twice");
    }
    map
}

/// The corpus files (every file in the directory but EXPECTED.tsv).
fn corpus_files() -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(CORPUS);
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .expect("the corpus directory exists")
        .map(|e| e.expect("a directory entry"))
        .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != "EXPECTED.tsv")
        .collect();
    names.sort();
    names
}

#[test]
fn expected_tsv_lists_every_corpus_file_and_nothing_else() {
    let files = corpus_files();
    let expected = expected();
    let missing: Vec<&String> = files
        .iter()
        .filter(|f| !expected.contains_key(*f))
        .collect();
    let stale: Vec<&String> = expected.keys().filter(|k| !files.contains(k)).collect();
    assert!(
        missing.is_empty() && stale.is_empty(),
        "corpus files without an EXPECTED.tsv line: {missing:?}; EXPECTED.tsv lines without a file: {stale:?}"
    );
    assert!(
        files.len() >= 50,
        "the corpus has only {} files",
        files.len()
    );
}

#[test]
fn every_malformed_file_gets_exit_2_and_one_line_naming_file_and_place() {
    let expected = expected();
    let files = corpus_files();
    // Spread the runs over a few threads; each is a separate process.
    let chunks: Vec<Vec<String>> = files.chunks(16).map(<[String]>::to_vec).collect();
    let failures: Vec<String> = std::thread::scope(|s| {
        let handles: Vec<_> = chunks
            .iter()
            .map(|chunk| {
                let expected = &expected;
                s.spawn(move || {
                    let mut failures = Vec::new();
                    for name in chunk {
                        let path = format!("{CORPUS}/{name}");
                        let run = limn(&["info", &path]);
                        let needle = expected.get(name).map_or("", String::as_str);
                        let problems = one_line_failure(&run, &format!("limn: {path}: "), needle);
                        if !problems.is_empty() {
                            failures.push(format!(
                                "{path}: {}\n{}",
                                problems.join("; "),
                                run.describe()
                            ));
                        }
                    }
                    failures
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("a corpus thread"))
            .collect()
    });
    assert!(
        failures.is_empty(),
        "{} of {} corpus files failed:\n\n{}",
        failures.len(),
        files.len(),
        failures.join("\n\n")
    );
}

#[test]
fn json_output_format_does_not_change_the_error() {
    // The error path is the same whatever output format is asked for.
    let path = format!("{CORPUS}/json_bezier_zero_weight.json");
    let run = limn(&["info", "--format", "json", &path]);
    let problems = one_line_failure(&run, &format!("limn: {path}: "), "patch 0, weights[2]");
    assert!(problems.is_empty(), "{problems:?}\n{}", run.describe());
}

#[test]
fn a_missing_file_is_one_line_naming_it() {
    let path = "tests/corpus/no-such-model.bpt";
    let run = limn(&["info", path]);
    let problems = one_line_failure(&run, &format!("limn: {path}: "), "file: cannot read");
    assert!(problems.is_empty(), "{problems:?}\n{}", run.describe());
}

#[test]
fn a_directory_given_as_the_model_is_one_line_naming_it() {
    let run = limn(&["info", CORPUS]);
    let problems = one_line_failure(&run, &format!("limn: {CORPUS}: "), "file: cannot read");
    assert!(problems.is_empty(), "{problems:?}\n{}", run.describe());
}

#[test]
fn a_bad_weld_value_is_one_line() {
    // `--weld=VALUE` reaches limn's own check (a bare `--weld -1` is taken by the argument
    // parser as an unknown flag; see `argument_parser_errors_are_exit_2_and_clear`).
    for value in ["-1", "0", "abc", "nan", "inf", "1e999", ""] {
        let arg = format!("--weld={value}");
        let run = limn(&["info", &arg, "fixtures/bezier/teapot.bpt"]);
        let problems = one_line_failure(
            &run,
            "limn: --weld: ",
            &format!("expected \"exact\" or a positive distance, found {value:?}"),
        );
        assert!(
            problems.is_empty(),
            "{arg}: {problems:?}\n{}",
            run.describe()
        );
    }
}

#[test]
fn argument_parser_errors_are_exit_2_and_clear() {
    // (args, what the first line must contain)
    let cases: [(&[&str], &str); 5] = [
        (
            &["info"],
            "the following required arguments were not provided",
        ),
        (
            &["info", "--bogus", "fixtures/bezier/teapot.bpt"],
            "unexpected argument '--bogus'",
        ),
        (
            &["info", "--weld", "-1", "fixtures/bezier/teapot.bpt"],
            "--weld: expected \"exact\" or a positive distance, found \"-1\"",
        ),
        (
            &["info", "--format", "xml", "fixtures/bezier/teapot.bpt"],
            "invalid value 'xml' for '--format <FORMAT>'",
        ),
        (&["frobnicate"], "unrecognized subcommand 'frobnicate'"),
    ];
    for (args, needle) in cases {
        let run = limn(args);
        let first = run.stderr.lines().next().unwrap_or("");
        assert!(
            !run.stderr.contains("panicked") && !run.stdout.contains("panicked"),
            "limn {args:?} panicked\n{}",
            run.describe()
        );
        assert_eq!(run.code, Some(2), "limn {args:?}\n{}", run.describe());
        assert!(
            first.starts_with("limn: ") && first.contains(needle),
            "limn {args:?}: the first line of stderr should be \"limn: ...{needle}...\"\n{}",
            run.describe()
        );
        assert!(run.stdout.is_empty(), "limn {args:?}\n{}", run.describe());
    }
}

#[test]
fn no_subcommand_is_exit_2_with_one_line() {
    // One line naming the commands, not clap's whole help.
    let run = limn(&[]);
    assert!(!run.stderr.contains("panicked"), "{}", run.describe());
    assert_eq!(run.code, Some(2), "{}", run.describe());
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.describe());
    assert!(
        run.stderr.contains("no command given"),
        "{}",
        run.describe()
    );
}

/// The contract of `src/cli.rs` is one line on stderr for any bad argument too; the argument
/// parser's messages (clap) add a usage block and a tip on further lines.
#[test]
fn argument_parser_errors_are_exactly_one_line() {
    for args in [
        &["info"][..],
        &["info", "--bogus", "fixtures/bezier/teapot.bpt"],
        &["info", "--weld", "-1", "fixtures/bezier/teapot.bpt"],
        &["info", "--format", "xml", "fixtures/bezier/teapot.bpt"],
        &["frobnicate"],
        &[],
    ] {
        let run = limn(args);
        let problems = one_line_failure(&run, "limn: ", "");
        assert!(
            problems.is_empty(),
            "limn {args:?}: {problems:?}\n{}",
            run.describe()
        );
    }
}

/// A copy of `fixtures/iges/forIGES/128-000.igs` with one control point coordinate moved
/// to 10^20: a valid file, which `limn info` should describe (exit 0).
fn iges_with_far_point() -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/iges/forIGES/128-000.igs");
    let text = std::fs::read_to_string(src).expect("the fixture is readable");
    let mut out = String::new();
    for line in text.split_inclusive('\n') {
        if line.len() >= 80 && &line[72..80] == "P      4" {
            // Columns 1-64 hold the data: "9.5,1.,8.5,..." -> "1D20,1.,8.5,...".
            let data = line[..64].replacen("9.5,", "1D20,", 1);
            let data = format!("{:<64}", data.trim_end());
            assert_eq!(data.len(), 64);
            out.push_str(&data);
            out.push_str(&line[64..]);
        } else {
            out.push_str(line);
        }
    }
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("far_point_128.igs");
    std::fs::write(&path, out).expect("the temporary file is writable");
    path
}

/// A valid model far from the origin (or a tiny `--weld`) makes the welding grid in
/// `src/model/topology.rs` (`Welder::cell`, then `c[0] + dx`) overflow an `i64`: a panic
/// in debug builds, a silent wrap in release builds.
#[test]
fn far_points_and_tiny_welds_do_not_panic() {
    let far = iges_with_far_point();
    let far = far.to_str().expect("a UTF-8 path");
    for args in [
        vec!["info", far],
        vec!["info", "--weld=1e-300", "fixtures/bezier/teapot.bpt"],
    ] {
        let run = limn(&args);
        assert!(
            !run.stderr.contains("panicked") && run.code == Some(0),
            "limn {args:?}\n{}",
            run.describe()
        );
    }
}

/// Output paths are checked before any work (issue 26): a missing folder, a plain file as
/// the folder, a folder as the file, and one file under two spellings are exit 2 with one
/// line, quickly, and nothing is written.
#[test]
fn output_paths_are_checked_before_the_work() {
    let dir = std::env::temp_dir().join(format!("limn-outputs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let plain = dir.join("plain");
    std::fs::write(&plain, "mine").unwrap();
    let missing = dir.join("no-such-folder").join("out.json");
    let under_file = plain.join("out.json");
    let s = |p: &PathBuf| p.display().to_string();
    let teapot = "fixtures/bezier/teapot.bpt";
    for (out, needle) in [
        (s(&missing), "is not a folder"),
        (s(&under_file), "is not a folder"),
        (s(&dir), "is a folder"),
    ] {
        let start = Instant::now();
        let run = limn(&["hlr", teapot, "--dir", "1,2,3", "-o", &out]);
        let problems = one_line_failure(&run, &format!("limn: {out}"), needle);
        assert!(problems.is_empty(), "{problems:?}\n{}", run.describe());
        assert!(
            start.elapsed() < Duration::from_secs(5),
            "checked after the work?"
        );
    }
    // -o and --certificate naming one file two ways.
    let a = s(&dir.join("same.json"));
    let b = format!("{}/./same.json", dir.display());
    let run = limn(&[
        "silhouette",
        teapot,
        "--dir",
        "1,2,3",
        "-o",
        &a,
        "--certificate",
        &b,
    ]);
    let problems = one_line_failure(&run, &format!("limn: {a}"), "name the same file");
    assert!(problems.is_empty(), "{problems:?}\n{}", run.describe());
    assert!(!dir.join("same.json").exists());
    assert_eq!(std::fs::read_to_string(&plain).unwrap(), "mine");
    // The time limit's bound is the one the message states.
    let run = limn(&["hlr", teapot, "--dir", "1,2,3", "--time-limit", "1e9"]);
    let problems = one_line_failure(&run, "limn: --time-limit", "below 1e9");
    assert!(problems.is_empty(), "{problems:?}\n{}", run.describe());
    let _ = std::fs::remove_dir_all(&dir);
}
