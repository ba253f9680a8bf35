//! Shared helpers for running the `facetlab` binary.

mod designs;
mod foundation;
mod hostile;
mod materials;
mod optimize;
mod photo;
mod plan;
mod recipes;
mod refused;
mod render;
mod safety;
mod serve;
mod shards;
mod sheet;
mod untrusted;

use std::path::Path;
use std::process::{Command, Output};

/// Run facetlab with `args` in `dir`.
pub fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_facetlab"))
        .args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .output()
        .expect("facetlab runs")
}

/// Run and expect success; returns stdout.
pub fn ok(dir: &Path, args: &[&str]) -> String {
    let out = run_in(dir, args);
    assert!(
        out.status.success(),
        "facetlab {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("utf-8 stdout")
}

/// Run and expect the bad-input contract: exit code 2, one line on stderr containing every
/// `needles`, no panic. Returns the line.
pub fn bad(dir: &Path, args: &[&str], needles: &[&str]) -> String {
    let out = run_in(dir, args);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(
        out.status.code(),
        Some(2),
        "facetlab {args:?}: expected exit 2, stderr: {err}"
    );
    assert!(!err.contains("panicked"), "panic: {err}");
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(
        lines.len(),
        1,
        "facetlab {args:?}: expected one line, got: {err}"
    );
    for n in needles {
        assert!(
            lines[0].contains(n),
            "facetlab {args:?}: `{n}` not in: {}",
            lines[0]
        );
    }
    lines[0].to_string()
}

/// Files in `dir` (to check nothing half-written is left behind).
pub fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    v.sort();
    v
}
