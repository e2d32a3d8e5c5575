//! What the command-line tests share: a fresh directory per test, `rtl` run in it under a time limit,
//! and the two outcomes they check, success and a refusal with a given exit code and message.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub const RTL: &str = env!("CARGO_BIN_EXE_rtl");

/// A fresh directory for test `name` of this test file.
pub fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "rtl-{}-{}-{name}",
        env!("CARGO_CRATE_NAME"),
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `rtl args` in `d`, killed after two minutes (a hang fails the test rather than stalling it).
pub fn rtl(d: &Path, args: &[&str]) -> Output {
    Command::new("timeout")
        .arg("120")
        .arg(RTL)
        .current_dir(d)
        .args(args)
        .output()
        .expect("rtl runs")
}

/// Run `rtl` expecting success; its standard error.
#[track_caller]
pub fn ok(d: &Path, args: &[&str]) -> String {
    let out = rtl(d, args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "rtl {args:?} failed: {err}");
    err
}

/// Run `rtl` expecting exit code `code` (1: refused by rtl, 2: by the argument parser), no panic,
/// and a message that holds every one of `words`.
#[track_caller]
pub fn refused_with(d: &Path, code: i32, args: &[&str], words: &[&str]) {
    let out = rtl(d, args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(
        out.status.code(),
        Some(code),
        "rtl {args:?} was not refused: {err}"
    );
    assert!(!err.contains("panicked"), "rtl {args:?} panicked: {err}");
    for w in words {
        assert!(err.contains(w), "rtl {args:?}: wanted {w:?} in: {err}");
    }
}

/// `rtl args` in `d` under `ulimit LIMIT` (`-v 250000`: KiB of address space; `-d`: of data), with
/// environment variables `env` set, killed after two minutes.
pub fn rtl_under_ulimit(d: &Path, limit: &str, env: &[(&str, &str)], args: &[&str]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit {limit} && exec timeout 120 \"$0\" \"$@\""))
        .arg(RTL)
        .args(args)
        .envs(env.iter().copied())
        .current_dir(d)
        .output()
        .expect("sh runs")
}
