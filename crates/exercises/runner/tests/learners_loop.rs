//! The runner driven as a learner would, on a copy of the exercises in a workspace of its own (the
//! learner's real files are never touched), with a target directory of its own: the first run builds
//! rand, statrs and glam there (about a minute on 2 cores), later runs reuse them.
//!
//! Ignored by default, as they drive cargo; `.ci/run` runs them:
//! `cargo test -p rtl-exercises-runner --test learners_loop -- --ignored --test-threads 1`.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../..")
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let path = entry.path();
        if path.is_dir() {
            copy_dir(&path, &to.join(entry.file_name()));
        } else {
            std::fs::copy(&path, to.join(entry.file_name())).unwrap();
        }
    }
}

/// A workspace holding only crates/exercises, its learner's files the pristine stubs.
fn workspace(name: &str) -> PathBuf {
    let ws = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&ws);
    let ex = ws.join("crates/exercises");
    for sub in ["src", "tests", "solutions"] {
        copy_dir(&repo().join("crates/exercises").join(sub), &ex.join(sub));
    }
    copy_dir(
        &repo().join("crates/exercises/solutions/stubs"),
        &ex.join("exercises"),
    );
    for f in ["Cargo.toml", "info.toml"] {
        std::fs::copy(repo().join("crates/exercises").join(f), ex.join(f)).unwrap();
    }
    let root = std::fs::read_to_string(repo().join("Cargo.toml")).unwrap();
    let manifest: String = root
        .lines()
        .filter(|l| !(l.starts_with("rtl-") && l.contains("path =")))
        .map(|l| {
            if l.starts_with("members = ") {
                "members = [\"crates/exercises\"]".to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(ws.join("Cargo.toml"), manifest).unwrap();
    std::fs::copy(repo().join("Cargo.lock"), ws.join("Cargo.lock")).unwrap();
    ws
}

fn target() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("learners-loop-target")
}

fn runner(ws: &Path) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_exercises"));
    c.current_dir(ws)
        .env_remove("RTL_EXERCISES_ROOT")
        .env_remove("RTL_EXERCISES_TIMEOUT")
        .env("CARGO_TARGET_DIR", target())
        .env("CARGO_NET_OFFLINE", "true");
    c
}

/// Runs the runner in `ws`: (exit code, stdout + stderr).
fn run(ws: &Path, args: &[&str]) -> (i32, String) {
    let out = runner(ws).args(args).stdin(Stdio::null()).output().unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.code().unwrap_or(-1), text)
}

fn solve(ws: &Path, name: &str) {
    let ex = ws.join("crates/exercises");
    std::fs::copy(
        ex.join(format!("solutions/{name}.rs")),
        ex.join(format!("exercises/{name}.rs")),
    )
    .unwrap();
}

fn edit(ws: &Path, name: &str, f: impl FnOnce(String) -> String) {
    let p = ws.join(format!("crates/exercises/exercises/{name}.rs"));
    let text = std::fs::read_to_string(&p).unwrap();
    std::fs::write(&p, f(text)).unwrap();
}

#[test]
#[ignore = "drives cargo on a copy of the exercises (a minute the first time); .ci/run runs it"]
fn list_check_reset_and_solution_on_stubs_solved_exercises_and_a_broken_neighbour() {
    let ws = workspace("loop-ws");
    let total = std::fs::read_dir(ws.join("crates/exercises/tests"))
        .unwrap()
        .count();

    // Untouched stubs: nothing done, every exercise listed, the first one next, in the book's order,
    // every row within 100 columns.
    let (code, out) = run(&ws, &["list"]);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.contains(&format!("0/{total} exercises done; ")),
        "{out}"
    );
    assert!(out.contains("next: ch02_estimate_pi"), "{out}");
    assert!(
        out.contains("`cargo exercises check ch02_estimate_pi`"),
        "{out}"
    );
    assert!(!out.contains("rtl exercises"), "{out}");
    assert!(out.contains("the bug museum"), "{out}");
    let row = |name: &str| out.find(&format!("  {name}  ")).unwrap();
    assert!(
        row("ch03_importance_x_sq") < row("ch03_inverse_x_sq"),
        "{out}"
    );
    assert!(out.contains("3 Importance sampling"), "{out}");
    for line in out.lines() {
        assert!(line.chars().count() <= 100, "{line}");
    }
    // `list | head -3`: a closed standard output ends it quietly.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let closed = runner(&ws)
        .arg("list")
        .stdin(Stdio::null())
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&closed.stderr);
    assert_eq!(closed.status.code(), Some(0), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    let (code, out) = run(&ws, &["check", "ch02_estimate_pi"]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("not started") && out.contains("your code"),
        "{out}"
    );

    // A wrong implementation: the learner's function and what the statistics saw.
    edit(&ws, "ch03_inverse_x_sq", |t| {
        t.replacen(
            "let _ = u;\n    todo!(\"ch03 sample_linear: a sample of the density x/2 on [0, 2], by inverse transform\")",
            "2.0 * u",
            1,
        )
    });
    let (code, out) = run(&ws, &["check", "ch03_inverse_x_sq"]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("failing (0/2 checks)"), "{out}");
    assert!(
        out.contains("|     2.0 * u"),
        "shows the learner's function: {out}"
    );
    assert!(out.contains("FAIL  sample_linear"), "{out}");
    assert!(
        out.contains("sample_linear(u = P(0.5) = 0.0625): got 0.125, expected 0.5"),
        "{out}"
    );
    assert!(
        out.contains("`cargo exercises hint ch03_inverse_x_sq`"),
        "{out}"
    );
    assert!(
        !out.contains("unwrap") && !out.contains("panicked at"),
        "{out}"
    );

    // Two exercises at once: both reported, exit 1 while one fails.
    let (code, out) = run(&ws, &["check", "ch03_inverse_x_sq", "ch02_estimate_pi"]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains(
            "ch03_inverse_x_sq (3 Inverse Transform Sampling: Choosing our samples): failing"
        ) && out.contains(
            "ch02_estimate_pi (2 A Simple Monte Carlo Program: Estimating π): not started"
        ),
        "{out}"
    );

    // Solved: done, exit 0, and the progress moves on.
    solve(&ws, "ch02_estimate_pi");
    let (code, out) = run(&ws, &["check", "ch02_estimate_pi"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("ch02_estimate_pi passes"), "{out}");
    let (_, out) = run(&ws, &["list"]);
    assert!(out.contains(&format!("1/{total} exercises done")), "{out}");
    assert!(out.contains("next: ch02_jittered_pi"), "{out}");
    // check without a name: the current exercise, the first not done.
    let (code, out) = run(&ws, &["check"]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.starts_with(&format!(
            "the current exercise, the first not done (1/{total} done; `cargo exercises check \
             NAME` checks another):\n\nch02_jittered_pi ("
        )),
        "{out}"
    );

    // A compile error in one exercise stops no other from being checked or listed.
    edit(&ws, "ch02_jittered_pi", |t| {
        t + "fn this_does_not_compile( {\n"
    });
    let (code, out) = run(&ws, &["check", "ch02_estimate_pi"]);
    assert_eq!(code, 0, "{out}");
    assert!(
        !out.contains("ch02_jittered_pi") && !out.contains("could not compile"),
        "{out}"
    );
    let (code, out) = run(&ws, &["list"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("does not compile"), "{out}");
    assert!(out.contains(&format!("1/{total} exercises done")), "{out}");
    assert!(
        out.contains("not counting the checks of ch02_jittered_pi (does not compile)"),
        "the total says what it leaves out: {out}"
    );
    assert!(
        out.contains("ch12_bug_cone_cos_theta_max"),
        "the exercises after it are listed: {out}"
    );
    let (code, out) = run(&ws, &["check", "ch02_jittered_pi"]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("does not compile")
            && out.contains("crates/exercises/exercises/ch02_jittered_pi.rs:"),
        "{out}"
    );
    assert!(
        !out.contains("tests/../"),
        "the learner's path, plainly: {out}"
    );

    // reset restores the stub and keeps the learner's version.
    let file = ws.join("crates/exercises/exercises/ch02_jittered_pi.rs");
    let mine = std::fs::read_to_string(&file).unwrap();
    let (code, out) = run(&ws, &["reset", "ch02_jittered_pi"]);
    assert_eq!(code, 0, "{out}");
    let backup = file.with_extension("rs.bak");
    assert_eq!(std::fs::read_to_string(&backup).unwrap(), mine);
    assert_eq!(
        std::fs::read(&file).unwrap(),
        std::fs::read(ws.join("crates/exercises/solutions/stubs/ch02_jittered_pi.rs")).unwrap()
    );
    edit(&ws, "ch02_jittered_pi", |t| t + "// a second try\n");
    run(&ws, &["reset", "ch02_jittered_pi"]);
    assert!(
        file.with_extension("rs.bak2").is_file(),
        "a second backup never overwrites the first"
    );
    let (_, out) = run(&ws, &["reset", "ch02_jittered_pi"]);
    assert!(out.contains("already the stub"), "{out}");

    // solution: refused before the exercise passes, shown after (or with --force and a warning).
    let (code, out) = run(&ws, &["solution", "ch03_inverse_x_sq"]);
    assert_eq!(code, 1, "{out}");
    assert!(!out.contains("u.cbrt()"), "the solution leaked: {out}");
    assert!(out.contains("--force"), "{out}");
    let (code, out) = run(&ws, &["solution", "ch03_inverse_x_sq", "--force"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("warning") && out.contains("u.cbrt()"), "{out}");
    let (code, out) = run(&ws, &["solution", "ch02_estimate_pi"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("4.0 * inside as f64"), "{out}");
    assert!(
        out.contains("(`cargo exercises solution ch02_estimate_pi` shows it")
            && !out.contains("rtl exercises"),
        "the header as the learner runs the runner: {out}"
    );
}

#[test]
#[ignore = "drives cargo on a copy of the exercises (a minute the first time); .ci/run runs it"]
fn what_the_learners_code_prints_is_shown_and_can_neither_break_nor_forge_a_report() {
    let ws = workspace("printing-ws");
    let total = std::fs::read_dir(ws.join("crates/exercises/tests"))
        .unwrap()
        .count();
    // A working estimate_pi with a debugging line on standard output and one on standard error.
    solve(&ws, "ch02_estimate_pi");
    edit(&ws, "ch02_estimate_pi", |t| {
        t.replacen(
            "    if n == 0 {",
            "    println!(\"debug: estimate_pi called with n = {n}\");\n    \
             eprintln!(\"to stderr: n = {n}\");\n    if n == 0 {",
            1,
        )
    });
    let (code, out) = run(&ws, &["check", "ch02_estimate_pi"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("ch02_estimate_pi passes"), "{out}");
    assert!(
        out.contains("  ok    1e5 points: z-test against pi"),
        "{out}"
    );
    // 7 calls (n = 0, 1, 2, 3, 10, 1000, 100000), two lines each, in the order printed.
    assert!(
        out.contains(
            "your code printed (14 lines):\n  | debug: estimate_pi called with n = 0\n  \
             | to stderr: n = 0\n  | debug: estimate_pi called with n = 1\n"
        ),
        "{out}"
    );
    assert!(!out.contains("unreadable"), "{out}");
    // list is not blocked, and counts it done.
    let (code, out) = run(&ws, &["list"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains(&format!("1/{total} exercises done")), "{out}");
    assert!(out.contains("ch12_bug_cone_cos_theta_max"), "{out}");

    // A forged report: printed, then exit(0) before the checks end. Not taken.
    edit(&ws, "ch02_jittered_pi", |t| {
        t.replacen(
            "todo!(",
            "println!(\"ch02_jittered_pi: done: 2/2 checks passed\");\n    \
             std::process::exit(0);\n    #[allow(unreachable_code)]\n    todo!(",
            1,
        )
    });
    let (code, out) = run(&ws, &["check", "ch02_jittered_pi"]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("crashed: it exited with code 0 before the checks ended, without its report"),
        "{out}"
    );
    assert!(
        out.contains("your code printed (1 line):\n  | ch02_jittered_pi: done: 2/2 checks passed"),
        "{out}"
    );
    let (code, out) = run(&ws, &["solution", "ch02_jittered_pi"]);
    assert_eq!(code, 1, "the solution stays hidden: {out}");
    let (code, out) = run(&ws, &["list"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains(&format!("1/{total} exercises done")), "{out}");

    // A function that calls itself: the stack overflows, and the compiler's warning about the
    // learner's file is shown with the crash.
    edit(&ws, "ch02_estimate_pi", |t| {
        t.replacen(
            "    if n == 0 {",
            "    let _ = estimate_pi(n, rng);\n    if n == 0 {",
            1,
        )
    });
    let (code, out) = run(&ws, &["check", "ch02_estimate_pi"]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("crashed: "), "{out}");
    assert!(out.contains("stack overflow"), "{out}");
    assert!(
        out.contains("the compiler warns about crates/exercises/exercises/ch02_estimate_pi.rs:")
            && out.contains("function cannot return without recursing")
            && out.contains("crates/exercises/exercises/ch02_estimate_pi.rs:"),
        "{out}"
    );
}

#[test]
#[ignore = "drives cargo on a copy of the exercises (a minute the first time); .ci/run runs it"]
fn loops_for_ever_are_stopped_at_the_limit_and_cost_it_once() {
    let ws = workspace("timeout-ws");
    // Two exercises whose code loops for ever.
    for name in ["ch02_estimate_pi", "ch03_inverse_x_sq"] {
        edit(&ws, name, |t| {
            t.replacen(
                "todo!(",
                "loop { std::hint::black_box(0); }\n    #[allow(unreachable_code)]\n    todo!(",
                1,
            )
        });
    }
    // Warm the build, so that the times below measure the runs.
    run(&ws, &["list"]);
    let limit = 4;
    let started = Instant::now();
    let out = runner(&ws)
        .args(["check", "ch02_estimate_pi"])
        .env("RTL_EXERCISES_TIMEOUT", limit.to_string())
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let took = started.elapsed();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(
        text.contains("timed out after 4 s in check 1 of 2"),
        "{text}"
    );
    // The check and the call that were running.
    assert!(
        text.contains(
            "the checks did not finish in 4 s in check 1 of 2 (\"n = 0 gives None; an estimate is \
             a count of points scaled by a constant\"), in the call estimate_pi(n = 0, rng = \
             rtl_exercises::check::seeded(3)): does your code loop for ever?"
        ),
        "{text}"
    );
    assert!(
        text.contains("still running: ch02_estimate_pi ("),
        "said while it ran: {text}"
    );
    assert!(
        took < Duration::from_secs(limit + 10),
        "took {took:?}: {text}"
    );
    // list: both loops together cost about one limit, not two.
    let started = Instant::now();
    let out = runner(&ws)
        .arg("list")
        .env("RTL_EXERCISES_TIMEOUT", limit.to_string())
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let took = started.elapsed();
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(text.matches("  timed out  ").count(), 2, "{text}");
    assert!(
        took < Duration::from_secs(2 * limit),
        "took {took:?}, two limits or more: {text}"
    );
}

/// Reads a child's output into a shared buffer; waits for text to appear in it.
struct Screen(Arc<Mutex<String>>);

impl Screen {
    fn start(mut from: impl Read + Send + 'static) -> Self {
        let buf = Arc::new(Mutex::new(String::new()));
        let b = buf.clone();
        std::thread::spawn(move || {
            let mut chunk = [0u8; 4096];
            while let Ok(n) = from.read(&mut chunk) {
                if n == 0 {
                    break;
                }
                b.lock()
                    .unwrap()
                    .push_str(&String::from_utf8_lossy(&chunk[..n]));
            }
        });
        Self(buf)
    }

    /// Waits (at most `secs`) until `text` appears after byte `from`; returns where it ends.
    fn wait_for(&self, text: &str, from: usize, secs: u64) -> usize {
        let start = Instant::now();
        loop {
            {
                let s = self.0.lock().unwrap();
                if let Some(i) = s.get(from..).and_then(|t| t.find(text)) {
                    return from + i + text.len();
                }
            }
            if start.elapsed() > Duration::from_secs(secs) {
                let s = self.0.lock().unwrap();
                panic!(
                    "no `{text}` within {secs} s; the screen so far:\n{}",
                    &s[from.min(s.len())..]
                );
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

#[test]
#[ignore = "drives cargo and a pseudo-terminal (script(1)); .ci/run runs it"]
fn watch_rechecks_on_save_moves_on_when_it_passes_and_obeys_h_and_q() {
    if Command::new("script").arg("--version").output().is_err() {
        eprintln!("script(1) (util-linux) is not installed: no pseudo-terminal to drive watch in");
        return;
    }
    let ws = workspace("watch-ws");
    // Warm the build first, so that the time limits below measure the loop, not the first build.
    run(&ws, &["list"]);
    let exe = env!("CARGO_BIN_EXE_exercises");
    let mut child = Command::new("script")
        .args(["-qfec", &format!("{exe} watch"), "/dev/null"])
        .current_dir(&ws)
        .env_remove("RTL_EXERCISES_ROOT")
        .env("CARGO_TARGET_DIR", target())
        .env("CARGO_NET_OFFLINE", "true")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut keys = child.stdin.take().unwrap();
    let screen = Screen::start(child.stdout.take().unwrap());
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let at = screen.wait_for("cargo exercises watch: 0/", 0, 120);
        let at = screen.wait_for("checking ch02_estimate_pi on every save", at, 120);
        let at = screen.wait_for("[h] hint   [q] quit", at, 60);
        // A save re-runs the check, saying so while it runs, and redraws (clearing the screen).
        edit(&ws, "ch02_estimate_pi", |t| t + "// saved\n");
        let at = screen.wait_for("checking ch02_estimate_pi ...", at, 120);
        let at = screen.wait_for("saved: checked again", at, 120);
        let at = screen.wait_for("\x1b[2J", at.saturating_sub(400), 5);
        let at = screen.wait_for("not started", at, 60);
        // Solved: it moves on to the next exercise.
        solve(&ws, "ch02_estimate_pi");
        let at = screen.wait_for("ch02_estimate_pi passes! On to ch02_jittered_pi", at, 120);
        let at = screen.wait_for("[h] hint", at, 60);
        keys.write_all(b"h").unwrap();
        keys.flush().unwrap();
        let at = screen.wait_for("hint 1 of", at, 30);
        keys.write_all(b"q").unwrap();
        keys.flush().unwrap();
        let _ = at;
        let start = Instant::now();
        loop {
            if let Some(status) = child.try_wait().unwrap() {
                assert!(status.success(), "watch exited with {status}");
                break;
            }
            assert!(
                start.elapsed() < Duration::from_secs(20),
                "q did not quit watch"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }));
    let _ = child.kill();
    let _ = child.wait();
    if let Err(e) = result {
        std::panic::resume_unwind(e);
    }
}

#[test]
#[ignore = "drives cargo on a copy of the exercises (a minute the first time); .ci/run runs it"]
fn watch_name_starts_at_that_exercise_and_a_closed_stdout_ends_watch() {
    let ws = workspace("watch-name-ws");
    run(&ws, &["list"]);
    let mut child = runner(&ws)
        .args(["watch", "ch03_inverse_x_sq"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let screen = Screen::start(child.stdout.take().unwrap());
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        screen.wait_for("checking ch03_inverse_x_sq on every save", 0, 120);
    }));
    let _ = child.kill();
    let _ = child.wait();
    if let Err(e) = result {
        std::panic::resume_unwind(e);
    }

    // An exercise that passes already: watch NAME keeps watching it, through saves.
    solve(&ws, "ch02_estimate_pi");
    let mut child = runner(&ws)
        .args(["watch", "ch02_estimate_pi"])
        .env("RTL_EXERCISES_TIMEOUT", "60")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let screen = Screen::start(child.stdout.take().unwrap());
    let notices = Screen::start(child.stderr.take().unwrap());
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let at = screen.wait_for(
            "ch02_estimate_pi passes already; watch keeps checking it on every save.",
            0,
            120,
        );
        let at = screen.wait_for("checking ch02_estimate_pi on every save", at, 10);
        let at = screen.wait_for("[h] hint   [q] quit", at, 10);
        edit(&ws, "ch02_estimate_pi", |t| t + "// saved\n");
        let at = screen.wait_for("saved: checked again.", at, 120);
        let at = screen.wait_for("checking ch02_estimate_pi on every save", at, 10);
        let at = screen.wait_for("ch02_estimate_pi passes.", at, 10);
        assert!(
            !screen.0.lock().unwrap().contains("On to"),
            "watch moved on from the exercise it was asked to watch"
        );
        // A save while a check loops for ever gives that check up at once, not at the limit.
        edit(&ws, "ch02_estimate_pi", |t| {
            t.replacen(
                "    if n == 0 {",
                "    loop { std::hint::black_box(0); }\n    #[allow(unreachable_code)]\n    if n == 0 {",
                1,
            )
        });
        let at = screen.wait_for("checking ch02_estimate_pi ...", at, 60);
        notices.wait_for("still running: ch02_estimate_pi", 0, 120);
        let saved = Instant::now();
        solve(&ws, "ch02_estimate_pi");
        let at = screen.wait_for(
            "changed during the check: checking ch02_estimate_pi again ...",
            at,
            60,
        );
        assert!(
            saved.elapsed() < Duration::from_secs(30),
            "the check waited for its limit of 60 s: {:?}",
            saved.elapsed()
        );
        screen.wait_for("ch02_estimate_pi passes.", at, 120);
    }));
    let _ = child.kill();
    let _ = child.wait();
    if let Err(e) = result {
        std::panic::resume_unwind(e);
    }

    // Standard output closed: watch ends quietly, without a panic.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = runner(&ws)
        .arg("watch")
        .stdin(Stdio::piped())
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}
