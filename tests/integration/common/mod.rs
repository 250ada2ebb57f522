//! Running the `knotlab` binary from the end-to-end tests.
#![allow(dead_code)]

use std::process::Command;

use serde_json::Value;

/// Runs `knotlab ARGS`: exit code, stdout, stderr.
pub fn knotlab(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_knotlab")).args(args).output().expect("run knotlab");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Runs `knotlab ARGS` and parses its stdout as JSON.
pub fn json(args: &[&str]) -> (i32, Value) {
    let (code, stdout, stderr) = knotlab(args);
    let value =
        serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("not JSON ({e}): {stdout}\n{stderr}"));
    (code, value)
}
