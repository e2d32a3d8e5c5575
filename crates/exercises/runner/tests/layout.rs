//! Fast checks of the exercises' layout against `info.toml`, and of the commands that need no build.

use rtl_exercises_runner::info;
use std::path::{Path, PathBuf};
use std::process::Command;

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
        out.contains("hint 1 of 3") && out.contains("--level 2"),
        "{out}"
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
    let (code, _, err) = runner(&["check", "ch02"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("could be ch02_estimate_pi, ch02_jittered_pi"),
        "{err}"
    );
    let (code, _, err) = runner(&["frobnicate"]);
    assert_eq!(code, 2);
    assert!(err.contains("unknown command `frobnicate`"), "{err}");
}
