//! Standard output that cannot be written: a pipe whose reader has gone (`rtl render --explain
//! cornell | head -1`) ends `rtl` quietly, as SIGPIPE ends other tools; a full device is an error
//! naming standard output. Neither is a panic with a backtrace, which `println!` gave before.

mod common;

use common::{RTL, dir};
use std::process::Command;

/// Exit code for a closed pipe: what a shell shows for a program killed by SIGPIPE (128 + 13).
const BROKEN_PIPE: i32 = 141;

#[test]
fn a_closed_pipe_ends_rtl_quietly_and_a_full_device_is_an_error() {
    let d = dir("pipe");
    // The reader is gone before `rtl` starts (as `head -1` is gone after one line of a longer
    // page): its first write fails. (The read end is closed before the spawn: closed after it,
    // `rtl` sometimes wrote first.)
    for args in [
        &[
            "render",
            "--explain",
            "cornell",
            "--width",
            "16",
            "--spp",
            "1",
        ][..],
        &["render", "--list"][..],
    ] {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let out = Command::new(RTL)
            .current_dir(&d)
            .args(args)
            .stdout(writer)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(BROKEN_PIPE), "rtl {args:?}: {err}");
        assert!(err.is_empty(), "rtl {args:?}: {err}");
    }

    // A full device: an error naming standard output.
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .expect("Linux has /dev/full");
    let out = Command::new(RTL)
        .current_dir(&d)
        .args(["render", "--list"])
        .stdout(full)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        err.contains("error: cannot write to standard output: No space left on device"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&d);
}
