//! Helpers shared by the CLI tests: run the `limn` binary, a scratch folder per test file, and
//! a small model with a closed-form answer.

use std::path::PathBuf;
use std::process::Command;

/// Runs `limn` with these arguments in the crate's folder: (exit code, stdout, stderr).
pub fn limn(args: &[&str]) -> (Option<i32>, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_limn"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run limn");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A path in a scratch folder of the test target's own (created).
pub fn tmp(folder: &str, name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(folder);
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The square [0,2]² at z = 0 and the square [1,3]² at z = 1 above it, written to the test
/// file's scratch folder.
#[allow(dead_code)] // not every test file that shares this module draws squares
pub fn two_squares(folder: &str) -> PathBuf {
    let path = tmp(folder, "two_squares.json");
    let square = |x0: i64, z: i64| {
        let x1 = x0 + 2;
        format!(
            r#"{{"kind":"bezier","degree":[1,1],"points":[[{x0},{x0},{z}],[{x0},{x1},{z}],[{x1},{x0},{z}],[{x1},{x1},{z}]]}}"#
        )
    };
    let text = format!(r#"{{"patches":[{},{}]}}"#, square(0, 0), square(1, 1));
    // Tests run in parallel and share the file: write a private copy and rename it into place
    // (atomic), so that no test ever reads a half-written file.
    let private = path.with_extension(format!("{:?}.part", std::thread::current().id()));
    std::fs::write(&private, text).unwrap();
    std::fs::rename(&private, &path).unwrap();
    path
}

/// Runs `limn` with a time limit already among `args` and JSON output: the run succeeds, is
/// not certified, and every unresolved entry names the time limit. Returns the report.
#[allow(dead_code)] // not every test file that shares this module runs out of time
pub fn time_limited(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = limn(args);
    assert_eq!(code, Some(0), "{args:?}: {err}");
    let r: serde_json::Value = serde_json::from_str(&out).expect("a JSON report");
    assert_eq!(r["certified"], false);
    let unresolved = r["unresolved"].as_array().expect("an unresolved list");
    assert!(!unresolved.is_empty());
    assert!(unresolved
        .iter()
        .all(|u| u["reason"].as_str().unwrap_or("").contains("time limit")));
    r
}
