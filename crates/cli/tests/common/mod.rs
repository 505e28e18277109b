//! Helpers shared by the command-line tests: running the binary, and what every refusal must
//! look like (docs/conventions.md §5: one clear line on stderr, a non-zero exit, no panic).

#![allow(dead_code)]

use std::path::Path;
use std::process::{Command, Output};

/// Runs `cuticle ARGS` with its memory capped at `CUTICLE_MEMORY_LIMIT` = 4 GB, so that what a
/// request needs is compared with the same figure on every machine.
pub fn cuticle(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cuticle"))
        .args(args)
        .env("CUTICLE_MEMORY_LIMIT", "4000000000")
        .output()
        .expect("the binary runs")
}

pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// `args` fail with one clear error containing `needle`: a non-zero exit, no panic, and (for
/// the command's own errors, exit 1) exactly one line on stderr. Flag syntax the parser
/// refuses (exit 2) may add its usage lines.
pub fn assert_refused(args: &[&str], needle: &str) -> String {
    let out = cuticle(args);
    let err = stderr(&out);
    assert!(!out.status.success(), "{args:?} succeeded: {err}");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert!(
        lines.first().is_some_and(|l| l.starts_with("error: ")),
        "{args:?}: {err}"
    );
    if out.status.code() == Some(1) {
        assert_eq!(lines.len(), 1, "{args:?} wrote more than one line: {err}");
    } else {
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    }
    assert!(
        err.to_lowercase().contains(&needle.to_lowercase()),
        "{args:?}: expected {needle:?} in {err}"
    );
    err
}

/// `args` succeed; returns stdout.
pub fn assert_runs(args: &[&str]) -> String {
    let out = cuticle(args);
    assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The names in a folder, sorted.
pub fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// The small render the issue attacks with: `B` of issue 9.
pub const B: [&str; 10] = [
    "--strands",
    "20",
    "--width",
    "32",
    "--height",
    "24",
    "--supersampling",
    "1",
    "--lights",
    "4",
];
