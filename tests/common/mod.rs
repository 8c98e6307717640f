//! Helpers shared by the CLI tests: run the `limn` binary, and a scratch folder per test file.

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
