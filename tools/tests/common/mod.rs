//! Helpers shared by the integration tests that run the `blueshift-tools` binary.
#![allow(dead_code)] // each test file uses its own subset

use std::path::Path;
use std::process::{Command, Output};

pub fn tools(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_blueshift-tools"))
        .args(args)
        .output()
        .expect("spawning blueshift-tools")
}

pub fn ok(args: &[&str]) -> String {
    let o = tools(args);
    assert!(
        o.status.success(),
        "{args:?} failed:\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

pub fn fails(args: &[&str], needle: &str) {
    let o = tools(args);
    assert!(!o.status.success(), "{args:?} should fail");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains(needle),
        "{args:?}: stderr lacks {needle:?}:\n{err}"
    );
    assert!(!err.contains("panicked"), "{args:?} panicked:\n{err}");
}

pub fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 temp path")
}
