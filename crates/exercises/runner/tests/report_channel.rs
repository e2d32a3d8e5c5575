//! The report comes through a file of its own, never through what the learner's code prints: on
//! stand-in test programs (shell scripts) that print, forge a report, or loop for ever in a check.
//! No cargo, a few seconds.
#![cfg(unix)]

mod common;

use rtl_exercises_runner::cargo::{self, Ran, Workspace};
use rtl_exercises_runner::info;
use rtl_exercises_runner::status::{self, Checked, Status};
use std::path::{Path, PathBuf};
use std::time::Duration;

use common::{fresh_dir, script};

/// The report file of a program whose check 1 passed and check 2 failed, as the harness writes
/// it, as shell commands.
const REPORT: &str = r#"R="$RTL_EXERCISES_REPORT"
printf 'rtl-exercises report 1\nchecks 2\nstart 1 first check\nresult 1\n|   ok    first check\n' > "$R"
printf 'start 2 second check\nresult 2\n|   FAIL  second check\n|           saw 3, expected 4\n' >> "$R"
printf 'report\n| ch02_x: failing: 1/2 checks passed: second check: saw 3, expected 4\n' >> "$R"
printf '|   ok    first check\n|   FAIL  second check\n|           saw 3, expected 4\nend\n' >> "$R""#;

fn exercise() -> info::Exercise {
    info::parse(
        "[[exercise]]\nname = \"ch02_x\"\nchapter = \"2 C\"\nsection = \"2 S\"\nkind = \"write\"\n\
         hints = [\"a\", \"b\"]\n",
    )
    .unwrap()
    .remove(0)
}

/// Runs the scripts `(name, body)` as the runner runs test programs; what each gave, with the
/// account `check` would print.
fn run(dir: &Path, scripts: &[(&str, &str)], limit: Duration) -> Vec<(Ran, Checked, String)> {
    let ws = Workspace {
        root: dir.to_path_buf(),
    };
    let programs: Vec<(String, PathBuf)> = scripts
        .iter()
        .map(|(name, body)| (name.to_string(), script(dir, name, body)))
        .collect();
    let e = exercise();
    cargo::run_all(&ws, &programs, limit, &mut |_, _| {})
        .unwrap()
        .into_iter()
        .map(|ran| {
            let checked = Checked {
                status: status::from_run(&e, &ran),
                printed: ran.printed().clone(),
                warnings: String::new(),
            };
            let text = checked.explain(&ws, &e, "cargo exercises");
            (ran, checked, text)
        })
        .collect()
}

#[test]
fn what_the_learners_code_prints_is_shown_beside_the_results() {
    let dir = fresh_dir("report-channel-prints");
    let prints = format!(
        "echo 'debug: estimate_pi called with n = 0'\necho 'to stderr' >&2\n{REPORT}\n\
         echo 'debug: estimate_pi called with n = 100000'\nexit 1"
    );
    let out = run(&dir, &[("prints", &prints)], Duration::from_secs(10));
    let (_, checked, text) = &out[0];
    assert_eq!(checked.status.word(), "failing 1/2", "{text}");
    assert!(
        text.contains("  ok    first check\n  FAIL  second check\n          saw 3, expected 4\n"),
        "{text}"
    );
    assert!(
        text.contains(
            "your code printed (3 lines):\n  | debug: estimate_pi called with n = 0\n  | to stderr\n  \
             | debug: estimate_pi called with n = 100000\n"
        ),
        "standard output and error, in the order written: {text}"
    );
    assert!(!text.contains("unreadable"), "{text}");
}

#[test]
fn a_report_printed_by_the_learners_code_is_not_taken() {
    let dir = fresh_dir("report-channel-forged");
    // The summary line, and a whole report file's text, printed; then exit 0.
    let forged_line = "echo 'ch02_x: done: 2/2 checks passed'\nexit 0";
    let forged_file = "printf 'rtl-exercises report 1\\nreport\\n| ch02_x: done: 2/2 checks passed\\nend\\n'\nexit 0";
    // A real report, then an exit code that is not the report's.
    let wrong_exit = format!("{REPORT}\nexit 0");
    let out = run(
        &dir,
        &[
            ("forged_line", forged_line),
            ("forged_file", forged_file),
            ("wrong_exit", &wrong_exit),
        ],
        Duration::from_secs(10),
    );
    for (ran, checked, text) in &out[..2] {
        assert!(
            matches!(&checked.status, Status::Crashed { why, .. }
                if why.contains("it exited with code 0 before the checks ended, without its report")
                && why.contains("std::process::exit")),
            "{ran:?}\n{text}"
        );
        assert!(!checked.status.is_done(), "{text}");
        assert!(
            text.contains("your code printed (1 line):\n  | ")
                || text.contains("your code printed (4 lines):"),
            "{text}"
        );
    }
    let (_, checked, text) = &out[2];
    assert!(
        matches!(&checked.status, Status::Crashed { why, .. } if why.contains("after a report that says failing")),
        "{text}"
    );
}

#[test]
fn a_check_stopped_at_the_limit_is_named_with_its_call_and_the_checks_before_it() {
    let dir = fresh_dir("report-channel-timeout");
    let body = r#"R="$RTL_EXERCISES_REPORT"
printf 'rtl-exercises report 1\nchecks 3\nstart 1 first check\nresult 1\n|   ok    first check\n' > "$R"
printf 'start 2 second check\ncall f(u = 0.5)\n' >> "$R"
echo 'debug: in f'
exec sleep 600"#;
    let limit = Duration::from_secs(2);
    let out = run(&dir, &[("loops", body)], limit);
    let (_, checked, text) = &out[0];
    assert!(matches!(checked.status, Status::TimedOut { .. }), "{text}");
    assert!(
        text.starts_with("ch02_x (2 C: S): timed out after 2 s in check 2 of 3\n"),
        "{text}"
    );
    assert!(
        text.contains(
            "the checks did not finish in 2 s in check 2 of 3 (\"second check\"), in the call \
             f(u = 0.5): does your code loop for ever?"
        ),
        "{text}"
    );
    assert!(
        text.contains(
            "what the checks saw before they were stopped:\n  ok    first check\n  ....  second \
             check\n          still running after 2 s\n  (and 1 check not reached)\n"
        ),
        "{text}"
    );
    assert!(text.contains("  | debug: in f\n"), "{text}");
    let why = checked.status.why().unwrap();
    assert!(
        why.contains("in check 2 of 3, in the call f(u = 0.5)"),
        "{why}"
    );
}
