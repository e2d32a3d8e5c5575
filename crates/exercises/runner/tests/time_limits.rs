//! The time limit of the checks, on stand-in test programs (shell scripts): no cargo, a few seconds.
//! A program that loops for ever is stopped at the limit; several of them cost one limit together,
//! not one each; and a long run is reported while it runs.
#![cfg(unix)]

mod common;

use rtl_exercises_runner::cargo::{self, Ran, Workspace};
use std::path::PathBuf;
use std::time::Duration;

use common::{fresh_dir, script};

#[test]
fn loops_cost_one_time_limit_together_and_a_long_run_is_reported() {
    let dir = fresh_dir("time-limits");
    let ws = Workspace { root: dir.clone() };
    // `exec` so that stopping the script stops the sleep (no grandchild keeps the pipes open).
    // Each loop notes its start in `started`, then sleeps.
    let started = dir.join("started");
    let forever = script(
        &dir,
        "forever",
        &format!("echo x >> '{}'; exec sleep 600", started.display()),
    );
    let honest = script(
        &dir,
        "honest",
        "printf 'rtl-exercises report 1\\nreport\\n| ch02_x: done: 1/1 checks passed\\nend\\n' \
         > \"$RTL_EXERCISES_REPORT\"",
    );
    let dies = script(&dir, "dies", "echo 'stack overflow' >&2; exit 3");
    let programs: Vec<(String, PathBuf)> = vec![
        ("ch02_a".into(), forever.clone()),
        ("ch02_b".into(), honest),
        ("ch02_c".into(), forever.clone()),
        ("ch02_d".into(), forever),
        ("ch02_e".into(), dies),
    ];
    let limit = Duration::from_secs(4);
    let mut notices: Vec<(Vec<String>, Duration)> = Vec::new();
    // How many loops had started, at the last look while the first of them still ran.
    let mut started_while_first_ran = 0;
    let ran = cargo::run_all(&ws, &programs, limit, &mut |names, elapsed| {
        if names.contains(&"ch02_a") {
            started_while_first_ran = std::fs::read_to_string(&started)
                .map(|s| s.lines().count())
                .unwrap_or(0);
        }
        notices.push((names.iter().map(|s| s.to_string()).collect(), elapsed));
    })
    .unwrap();
    let timed_out = |r: &Ran| matches!(r, Ran::TimedOut { limit: l, .. } if *l == limit);
    assert!(timed_out(&ran[0]), "{:?}", ran[0]);
    assert!(
        matches!(&ran[1], Ran::Exited { code: Some(0), log, .. }
            if log.report.as_deref() == Some("ch02_x: done: 1/1 checks passed\n")),
        "{:?}",
        ran[1]
    );
    assert!(timed_out(&ran[2]), "{:?}", ran[2]);
    assert!(timed_out(&ran[3]), "{:?}", ran[3]);
    assert!(
        matches!(&ran[4], Ran::Exited { code: Some(3), log, printed, .. }
            if log.report.is_none() && printed.last() == Some("stack overflow")),
        "{:?}",
        ran[4]
    );
    // One after the other the three loops would take three limits; side by side they cost one
    // together: all three had started while the first still ran (an order of events, not a
    // bound on the wall clock).
    assert_eq!(started_while_first_ran, 3, "{notices:?}");
    // While they ran, the runner said so, naming them.
    assert!(
        notices
            .iter()
            .any(|(names, _)| names.contains(&"ch02_a".to_string())),
        "{notices:?}"
    );
    assert!(
        notices
            .iter()
            .filter(|(names, _)| !names.is_empty())
            .all(|(_, elapsed)| *elapsed >= cargo::NOTICE_AFTER),
        "{notices:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
