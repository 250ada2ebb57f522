//! Running the `knotlab` binary from the end-to-end tests.
#![allow(dead_code)]

use std::io::{BufRead, BufReader};
use std::net::SocketAddr;
use std::process::{Child, ChildStdout, Command, Stdio};

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

/// An emulator command started in the background (`knotlab ARGS`, binding port 0): the child, its
/// stdout after the first line, that line ("listening on ADDR ..."), and ADDR.
pub fn emulator(args: &[&str]) -> (Child, BufReader<ChildStdout>, String, SocketAddr) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_knotlab"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    let mut stdout = BufReader::new(child.stdout.take().expect("stdout"));
    let mut first = String::new();
    stdout.read_line(&mut first).expect("the listening line");
    let addr = first
        .strip_prefix("listening on ")
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|addr| addr.parse().ok())
        .unwrap_or_else(|| panic!("no address in {first:?}"));
    (child, stdout, first, addr)
}
