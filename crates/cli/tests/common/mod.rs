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

/// Runs `holey args`, which must be refused as bad input: status 2 and no
/// panic. Gives the whole output.
pub fn refused_output(args: &[&str]) -> Output {
    let out = holey(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(2),
        "holey {args:?} should be refused as bad input (status 2); stderr: {err}"
    );
    assert!(!err.contains("panicked"), "holey {args:?} panicked: {err}");
    out
}

/// Runs `holey args`, which must be refused as bad input (see
/// [`refused_output`]), and gives its stderr.
pub fn refused(args: &[&str]) -> String {
    String::from_utf8_lossy(&refused_output(args).stderr).into_owned()
}
