//! What every test of the `holey` binary needs: running it, and running
//! it where it must succeed. Each test binary uses what it needs.
#![allow(dead_code)]

use std::process::{Command, Output};

/// Runs `holey args`.
pub fn holey(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_holey"))
        .args(args)
        .output()
        .expect("the holey binary runs")
}

/// Runs `holey args`, which must succeed, and gives its stdout.
pub fn ok(args: &[&str]) -> String {
    let out = holey(args);
    assert!(
        out.status.success(),
        "holey {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8 output")
}
