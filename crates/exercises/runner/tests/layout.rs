//! Fast checks of the exercises' layout against `info.toml`, and of the commands that need no build.

use rtl_exercises_runner::info;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn crate_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

#[test]
fn every_exercise_has_its_files_its_test_target_and_two_hints() {
    let dir = crate_dir();
    let exercises = info::load(&dir.join("info.toml")).unwrap();
    assert!(exercises.len() >= 20, "{} exercises", exercises.len());
    let bugs = exercises
        .iter()
        .filter(|e| e.kind == info::Kind::Bug)
        .count();
    assert!(bugs >= 6, "{bugs} bug-museum exercises");
    let manifest = read(&dir.join("Cargo.toml"));
    for e in &exercises {
        let n = &e.name;
        let stub = read(&dir.join(format!("solutions/stubs/{n}.rs")));
        read(&dir.join(format!("solutions/{n}.rs")));
        let glue = read(&dir.join(format!("tests/{n}.rs")));
        assert!(
            glue.contains(&format!("exercise_main!(\"{n}\"")),
            "tests/{n}.rs"
        );
        assert!(
            manifest.contains(&format!(
                "name = \"{n}\"\npath = \"tests/{n}.rs\"\nharness = false"
            )),
            "Cargo.toml has no harness = false test target {n}"
        );
        assert!(
            dir.join(format!("exercises/{n}.rs")).is_file(),
            "exercises/{n}.rs"
        );
        // The shipped file holds no solution and, for a stub, a todo!() to replace.
        assert!(
            !stub.contains("cfg(feature") && !stub.contains("mod solution"),
            "{n}"
        );
        assert_eq!(
            stub.lines().any(|l| l.trim_start().starts_with("todo!(")),
            e.kind == info::Kind::Write,
            "{n}: a stub to write has a todo!(), a bug to fix has none"
        );
        assert!(
            stub.contains("// ANCHOR: exercise") && stub.contains("// ANCHOR_END: exercise"),
            "{n}: the book includes the anchor `exercise`"
        );
        let chapter: u32 = n[2..4].parse().unwrap();
        assert!(
            e.chapter.starts_with(&format!("{chapter} ")),
            "{n}: {}",
            e.chapter
        );
        assert!(e.hints.len() >= 2, "{n}");
    }
    let tests = std::fs::read_dir(dir.join("tests")).unwrap().count();
    assert_eq!(
        tests,
        exercises.len(),
        "one test target per exercise in info.toml"
    );
}

/// No hint contains a line of code of the reference solution.
#[test]
fn no_hint_is_a_line_of_the_solution() {
    let dir = crate_dir();
    for e in info::load(&dir.join("info.toml")).unwrap() {
        let solution = read(&dir.join(format!("solutions/{}.rs", e.name)));
        let squash = |s: &str| s.chars().filter(|c| !c.is_whitespace()).collect::<String>();
        for line in solution.lines().map(str::trim) {
            let code = squash(line);
            if code.len() < 14
                || line.starts_with("//")
                || line.starts_with("pub fn")
                || line.starts_with("fn ")
                || line.starts_with("use ")
                || line.starts_with("impl")
            {
                continue;
            }
            for (k, h) in e.hints.iter().enumerate() {
                assert!(
                    !squash(h).contains(&code),
                    "{} hint {}: gives away the solution's line `{line}`",
                    e.name,
                    k + 1
                );
            }
        }
    }
}

fn runner(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_exercises"))
        .args(args)
        .env("RTL_EXERCISES_ROOT", crate_dir().join("../.."))
        .env_remove("RTL_EXERCISES_TIMEOUT")
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn hints_come_one_level_at_a_time_and_bad_input_is_named() {
    let (code, out, _) = runner(&["hint", "ch03_tabulated_inverse_cdf"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("hint 1 of 3")
            && out.contains("`cargo exercises hint ch03_tabulated_inverse_cdf --level 2`"),
        "the next command as the learner types it (cargo exercises, not rtl): {out}"
    );
    let (code, out, _) = runner(&["hint", "ch03_tab", "--level", "3"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("hint 3 of 3") && !out.contains("--level 4"),
        "{out}"
    );
    let (code, _, err) = runner(&["hint", "ch03_tab", "--level", "9"]);
    assert_eq!(code, 2);
    assert!(err.contains("hints 1 to 3"), "{err}");
    let (code, _, err) = runner(&["check", "ch99_nothing"]);
    assert_eq!(code, 2);
    assert!(err.contains("no exercise `ch99_nothing`"), "{err}");
    for typed in ["ch2_estimate_pi", "estimate_pi"] {
        let (code, _, err) = runner(&["check", typed]);
        assert_eq!(code, 2);
        assert_eq!(
            err.trim_end(),
            format!("error: no exercise `{typed}`: did you mean ch02_estimate_pi?")
        );
        let (code, _, err) = runner(&["watch", typed]);
        assert_eq!(code, 2);
        assert!(err.contains("did you mean ch02_estimate_pi?"), "{err}");
    }
    let (code, _, err) = runner(&["reset", "ch02_estimate_pi", "ch02_jittered_pi"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("`reset` takes one exercise at a time"),
        "{err}"
    );
    let (code, _, err) = runner(&["check", "ch02"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("could be ch02_estimate_pi, ch02_jittered_pi"),
        "{err}"
    );
    let (code, _, err) = runner(&["frobnicate"]);
    assert_eq!(code, 2);
    assert!(err.contains("unknown command `frobnicate`"), "{err}");
    let (code, _, err) = runner(&["chek", "ch02_estimate_pi"]);
    assert_eq!(code, 2);
    assert_eq!(
        err.trim_end(),
        "error: unknown command `chek`: did you mean `cargo exercises check`?"
    );
}

/// A bad `RTL_EXERCISES_TIMEOUT` is named before anything is built.
#[test]
fn a_bad_time_limit_is_named() {
    let out = Command::new(env!("CARGO_BIN_EXE_exercises"))
        .args(["check", "ch02_estimate_pi"])
        .env("RTL_EXERCISES_ROOT", crate_dir().join("../.."))
        .env("RTL_EXERCISES_TIMEOUT", "ten")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("RTL_EXERCISES_TIMEOUT=ten: expected a number of seconds greater than 0"),
        "{err}"
    );
}

/// Runs the runner with a standard output whose reading end is already closed, as `| head -3`
/// leaves it once head has its lines: (exit code, stderr).
fn with_closed_stdout(root: &Path, args: &[&str]) -> (Option<i32>, String) {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(env!("CARGO_BIN_EXE_exercises"))
        .args(args)
        .env("RTL_EXERCISES_ROOT", root)
        .stdin(Stdio::null())
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `... | head` closes standard output: the commands that need no build end quietly with 0
/// instead of panicking ("failed printing to stdout: Broken pipe", exit 101). (`list`, `check`,
/// `watch` and `solution`, which build, are driven the same way in learners_loop.rs.)
#[test]
fn a_closed_stdout_ends_every_command_quietly() {
    let repo = crate_dir().join("../..");
    // reset writes files: it works on a copy of the exercises.
    let copy = Path::new(env!("CARGO_TARGET_TMPDIR")).join("closed-stdout-ws");
    let _ = std::fs::remove_dir_all(&copy);
    let ex = copy.join("crates/exercises");
    std::fs::create_dir_all(ex.join("exercises")).unwrap();
    std::fs::create_dir_all(ex.join("solutions/stubs")).unwrap();
    std::fs::copy(crate_dir().join("info.toml"), ex.join("info.toml")).unwrap();
    let stub = crate_dir().join("solutions/stubs/ch02_estimate_pi.rs");
    std::fs::copy(&stub, ex.join("solutions/stubs/ch02_estimate_pi.rs")).unwrap();
    std::fs::write(ex.join("exercises/ch02_estimate_pi.rs"), "// mine\n").unwrap();
    for (root, args) in [
        (&repo, vec!["help"]),
        (
            &repo,
            vec!["hint", "ch03_tabulated_inverse_cdf", "--level", "3"],
        ),
        (&copy, vec!["reset", "ch02_estimate_pi"]),
    ] {
        let (code, err) = with_closed_stdout(root, &args);
        assert_eq!(code, Some(0), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

/// The headings of `book/src/*.md`, without backticks, by file.
fn book_pages() -> Vec<(String, String)> {
    let book = crate_dir().join("../../book/src");
    let summary = read(&book.join("SUMMARY.md"));
    summary
        .split("](")
        .skip(1)
        .filter_map(|s| s.split(')').next())
        .filter(|f| f.starts_with("ch") && f.ends_with(".md"))
        .map(|f| (f.to_string(), read(&book.join(f))))
        .collect()
}

/// The chapter number of a page: 3 for `ch03-inverse-transform-sampling.md`.
fn page_number(file: &str) -> u32 {
    file[2..4].parse().unwrap()
}

fn headings(text: &str) -> Vec<String> {
    text.lines()
        .filter(|l| l.starts_with('#'))
        .map(|l| l.trim_start_matches('#').trim().replace('`', ""))
        .collect()
}

/// info.toml lists the exercises in the order the book shows them (SUMMARY.md's order of pages,
/// then each page's Exercises section), each with the page that holds it as its chapter ("N Title",
/// the page's `# Title`) and, as its section, a heading of this book ("M Heading"), not of the
/// original book's.
#[test]
fn exercises_follow_the_book_and_name_its_headings() {
    let exercises = info::load(&crate_dir().join("info.toml")).unwrap();
    let pages = book_pages();
    let mut in_book: Vec<(String, String)> = Vec::new();
    for (file, text) in &pages {
        let title = text
            .lines()
            .next()
            .unwrap()
            .trim_start_matches("# ")
            .to_string();
        for l in text.lines() {
            let l = l.trim_start_matches('#');
            if let Some(name) = l.trim().strip_prefix('`').and_then(|n| n.strip_suffix('`'))
                && exercises.iter().any(|e| e.name == name)
            {
                in_book.push((name.to_string(), format!("{} {title}", page_number(file))));
            }
        }
    }
    let order: Vec<&str> = exercises.iter().map(|e| e.name.as_str()).collect();
    let book_order: Vec<&str> = in_book.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(order, book_order, "info.toml's order against the book's");
    for (e, (_, chapter)) in exercises.iter().zip(&in_book) {
        assert_eq!(
            &e.chapter, chapter,
            "{}: its chapter is the page that holds it",
            e.name
        );
        let (n, heading) = e.section.split_once(' ').unwrap();
        let found = pages.iter().any(|(file, text)| {
            page_number(file) == n.parse::<u32>().unwrap()
                && headings(text).iter().any(|h| h == heading)
        });
        assert!(
            found,
            "{}: `{heading}` is no heading of chapter {n}",
            e.name
        );
        // The stub sends the learner to that section.
        let stub = read(&crate_dir().join(format!("exercises/{}.rs", e.name))).replace('`', "");
        assert!(
            stub.contains(&format!("\"{heading}\"")),
            "{}: the stub names the section \"{heading}\"",
            e.name
        );
    }
    // ch03_importance_x_sq is on the one-dimensional MC page, before the inverse-transform page.
    let at = |n: &str| order.iter().position(|&x| x == n).unwrap();
    assert!(at("ch03_importance_x_sq") < at("ch03_inverse_x_sq"));
}

/// The formulas that are the answers are in the last hint, and in no file a learner edits: the
/// stubs state the task, the book derives the formula, and the last hint gives it.
#[test]
fn stubs_leave_the_formulas_to_the_last_hint() {
    let answers: &[(&str, &[&str])] = &[
        ("ch02_estimate_pi", &["4 * inside / n"]),
        ("ch03_importance_x_sq", &["sum f(x_k) / p(x_k)"]),
        ("ch03_inverse_x_sq", &["2 sqrt(u)", "2 cbrt(u)"]),
        ("ch03_tabulated_inverse_cdf", &["x = x_i + (u - c_i)"]),
        ("ch04_sphere_integral", &["z = 1 - 2 u1", "phi = 2 pi u2"]),
        ("ch05_lambertian_pdf", &["max(0, n . d) / pi"]),
        ("ch06_scatter_weight", &["L_e + A s(d) L_i(d) / p(d)"]),
        (
            "ch07_cosine_direction",
            &["z = sqrt(1 - u2)", "r = sqrt(u2)"],
        ),
        (
            "ch08_onb",
            &["a = -1 / (s + w.z)", "u = (1 + s w.x^2 a, s b, -s w.x)"],
        ),
        ("ch09_quad_pdf_value", &["r^2 / (|cos theta| A)"]),
        ("ch10_mixture_pdf", &["w a(d) + (1 - w) b(d)"]),
        (
            "ch12_sphere_pdf_value",
            &["sin^2 theta_max / (1 + cos theta_max)"],
        ),
        ("ch12_nan_guard", &["mean += (x - mean)"]),
    ];
    let exercises = info::load(&crate_dir().join("info.toml")).unwrap();
    let squash = |s: &str| s.split_whitespace().collect::<Vec<_>>().join(" ");
    let stubs: Vec<(String, String)> = exercises
        .iter()
        .map(|e| {
            let text = read(&crate_dir().join(format!("exercises/{}.rs", e.name)));
            (e.name.clone(), squash(&text))
        })
        .collect();
    for (name, formulas) in answers {
        let e = exercises.iter().find(|e| e.name == *name).unwrap();
        let last = squash(e.hints.last().unwrap());
        for f in *formulas {
            assert!(
                last.contains(f),
                "{name}: the last hint gives `{f}`: {last}"
            );
            for (stub_name, stub) in &stubs {
                assert!(
                    !stub.contains(f),
                    "exercises/{stub_name}.rs gives away `{f}`"
                );
            }
        }
    }
}
