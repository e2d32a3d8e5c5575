//! # The learner's loop around the chapter exercises
//!
//! `rtl exercises <command>` (or `cargo exercises <command>`, which builds only this small crate):
//!
//! - `list`: every exercise with its chapter and state, `k/N done`, and the next one to do;
//! - `check NAME`: checks one exercise; exit 0 when it passes. A failure shows your function and what
//!   each check saw;
//! - `hint NAME [--level K]`: the exercise's hints, one level at a time;
//! - `watch`: checks the current exercise whenever its file is saved and moves on when it passes
//!   (`h` a hint, `q` quits);
//! - `reset NAME`: restores the stub, keeping your version as a backup file;
//! - `solution NAME [--force]`: the reference solution, once your code passes.
//!
//! Each exercise is its own test target of `rtl-exercises` (see [`cargo`]), so one that does not
//! compile never stops another from being checked or listed.

pub mod cargo;
pub mod info;
pub mod status;
pub mod watch;

use cargo::Workspace;
use info::{Exercise, Kind};
use status::Status;
use std::path::PathBuf;

const USAGE: &str = "\
usage: rtl exercises <command>     (or: cargo exercises <command>)

  list                     every exercise: chapter, state, k/N done, and the next to do
  check NAME               check one exercise (exit 0 when it passes)
  hint NAME [--level K]    hint K (default 1) of the exercise
  watch                    re-check the current exercise on every save; h: hint, q: quit
  reset NAME               restore the stub; your version is kept as NAME.rs.bak
  solution NAME [--force]  the reference solution, once your code passes (--force: peek)

NAME is an exercise's file name without .rs, e.g. ch02_estimate_pi (a unique prefix will do).";

/// Runs the command line `args` (without the program name); returns the exit code.
pub fn run(args: &[String]) -> i32 {
    match dispatch(args) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            2
        }
    }
}

fn dispatch(args: &[String]) -> Result<i32, String> {
    let Some(command) = args.first() else {
        println!("{USAGE}");
        return Ok(2);
    };
    let rest = &args[1..];
    if matches!(command.as_str(), "-h" | "--help" | "help") {
        println!("{USAGE}");
        return Ok(0);
    }
    let ws = Workspace::find()?;
    let exercises = info::load(&ws.info()).map_err(|e| e.to_string())?;
    let ctx = Context { ws, exercises };
    match command.as_str() {
        "list" => {
            no_more(rest, 0)?;
            ctx.list()
        }
        "check" => {
            let e = ctx.named(rest)?;
            no_more(rest, 1)?;
            ctx.check(e)
        }
        "hint" => {
            let e = ctx.named(rest)?;
            let level = match rest.get(1).map(String::as_str) {
                None => 1,
                Some("--level") => {
                    let v = rest.get(2).ok_or("--level needs a number: --level 2")?;
                    no_more(rest, 3)?;
                    v.parse::<usize>()
                        .map_err(|_| format!("--level {v}: not a whole number"))?
                }
                Some(v) if v.starts_with("--level=") => {
                    no_more(rest, 2)?;
                    let v = &v["--level=".len()..];
                    v.parse::<usize>()
                        .map_err(|_| format!("--level {v}: not a whole number"))?
                }
                Some(other) => return Err(format!("hint: unexpected `{other}`; {USAGE}")),
            };
            ctx.hint(e, level)
        }
        "watch" => {
            no_more(rest, 0)?;
            watch::watch(&ctx)
        }
        "reset" => {
            let e = ctx.named(rest)?;
            no_more(rest, 1)?;
            ctx.reset(e)
        }
        "solution" => {
            let e = ctx.named(rest)?;
            let force = match rest.get(1).map(String::as_str) {
                None => false,
                Some("--force") => true,
                Some(other) => return Err(format!("solution: unexpected `{other}`")),
            };
            no_more(rest, if force { 2 } else { 1 })?;
            ctx.solution(e, force)
        }
        other => Err(format!("unknown command `{other}`\n{USAGE}")),
    }
}

fn no_more(rest: &[String], n: usize) -> Result<(), String> {
    match rest.get(n) {
        None => Ok(()),
        Some(extra) => Err(format!("unexpected argument `{extra}`\n{USAGE}")),
    }
}

/// The workspace and its exercises.
pub struct Context {
    pub ws: Workspace,
    pub exercises: Vec<Exercise>,
}

impl Context {
    /// The exercise named by `rest[0]`: its exact name, its file name, or a unique prefix.
    fn named(&self, rest: &[String]) -> Result<&Exercise, String> {
        let arg = rest
            .first()
            .ok_or("which exercise? e.g. ch02_estimate_pi")?;
        let want = arg
            .rsplit('/')
            .next()
            .unwrap_or(arg)
            .trim_end_matches(".rs");
        if let Some(e) = self.exercises.iter().find(|e| e.name == want) {
            return Ok(e);
        }
        let matches: Vec<&Exercise> = self
            .exercises
            .iter()
            .filter(|e| e.name.starts_with(want))
            .collect();
        match matches.as_slice() {
            [one] => Ok(one),
            [] => Err(format!(
                "no exercise `{want}`; `rtl exercises list` names them all"
            )),
            many => Err(format!(
                "`{want}` could be {}",
                many.iter()
                    .map(|e| e.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        }
    }

    /// The state of each of `exercises` (built together, then run one by one).
    pub fn statuses(&self, exercises: &[&Exercise]) -> Result<Vec<Status>, String> {
        let names: Vec<String> = exercises.iter().map(|e| e.name.clone()).collect();
        let mut shown = false;
        let built = cargo::build(&self.ws, &names, &mut |what| {
            if !shown {
                eprintln!("building the exercises (the first time takes a minute) ...");
                shown = true;
            }
            let _ = what;
        })?;
        let mut out = Vec::new();
        for e in exercises {
            let b = built
                .get(&e.name)
                .ok_or_else(|| format!("{}: not built", e.name))?;
            out.push(status::of(&self.ws, e, b)?);
        }
        Ok(out)
    }

    fn list(&self) -> Result<i32, String> {
        let all: Vec<&Exercise> = self.exercises.iter().collect();
        let statuses = self.statuses(&all)?;
        let wn = all.iter().map(|e| e.name.len()).max().unwrap_or(8).max(8);
        let wc = all
            .iter()
            .map(|e| e.chapter.len())
            .max()
            .unwrap_or(7)
            .min(58);
        println!(
            "{:<3} {:<wn$}  {:<wc$}  state",
            "#", "exercise", "book chapter: section"
        );
        let mut done = 0;
        let mut next: Option<&Exercise> = None;
        let (mut checks_passed, mut checks) = (0, 0);
        for (i, (e, s)) in all.iter().zip(&statuses).enumerate() {
            if s.is_done() {
                done += 1;
            } else if next.is_none() {
                next = Some(e);
            }
            if let Some((p, t)) = s.counts() {
                checks_passed += p;
                checks += t;
            }
            let mut chapter = e.chapter.clone();
            if chapter.len() > wc {
                chapter.truncate(wc - 3);
                chapter += "...";
            }
            let tag = if e.kind == Kind::Bug { " [bug]" } else { "" };
            println!(
                "{:<3} {:<wn$}  {:<wc$}  {}{tag}",
                i + 1,
                e.name,
                chapter,
                s.one_line()
            );
        }
        println!();
        println!(
            "{done}/{} done ({checks_passed} of the {checks} checks of the exercises that build pass)",
            all.len()
        );
        match next {
            Some(e) => println!(
                "next: {} ({}): edit {}, then `rtl exercises check {}` (or `rtl exercises watch`)",
                e.name,
                e.chapter,
                self.ws.show(&self.ws.exercise_file(&e.name)),
                e.name
            ),
            None => println!("every exercise is done: well done!"),
        }
        Ok(0)
    }

    fn check(&self, e: &Exercise) -> Result<i32, String> {
        let s = self.statuses(&[e])?.remove(0);
        print!("{}", s.explain(&self.ws, e));
        Ok(if s.is_done() { 0 } else { 1 })
    }

    fn hint(&self, e: &Exercise, level: usize) -> Result<i32, String> {
        let n = e.hints.len();
        if level == 0 || level > n {
            return Err(format!(
                "{} has hints 1 to {n}; --level {level} is not one of them",
                e.name
            ));
        }
        println!("{}: hint {level} of {n}\n", e.name);
        println!("{}", e.hints[level - 1]);
        if level < n {
            println!(
                "\n(`rtl exercises hint {} --level {}` for the next)",
                e.name,
                level + 1
            );
        }
        Ok(0)
    }

    fn reset(&self, e: &Exercise) -> Result<i32, String> {
        let file = self.ws.exercise_file(&e.name);
        let stub = std::fs::read(self.ws.stub_file(&e.name))
            .map_err(|err| format!("{}: {err}", self.ws.show(&self.ws.stub_file(&e.name))))?;
        let mine = std::fs::read(&file).ok();
        if mine.as_deref() == Some(stub.as_slice()) {
            println!(
                "{} is already the stub: nothing to reset",
                self.ws.show(&file)
            );
            return Ok(0);
        }
        if mine.is_some() {
            let backup = backup_path(&file);
            std::fs::copy(&file, &backup)
                .map_err(|err| format!("backup {}: {err}", backup.display()))?;
            println!("your version is kept in {}", self.ws.show(&backup));
        }
        std::fs::write(&file, &stub).map_err(|err| format!("{}: {err}", file.display()))?;
        println!("{} is the stub again", self.ws.show(&file));
        Ok(0)
    }

    fn solution(&self, e: &Exercise, force: bool) -> Result<i32, String> {
        let s = self.statuses(&[e])?.remove(0);
        if !s.is_done() && !force {
            eprintln!(
                "{}: {}. The reference solution is shown once your code passes: try \
                 `rtl exercises hint {}` first (`rtl exercises solution {} --force` peeks anyway).",
                e.name,
                s.one_line(),
                e.name,
                e.name
            );
            return Ok(1);
        }
        if !s.is_done() {
            eprintln!(
                "warning: {} does not pass yet ({}); here is the reference solution anyway.\n",
                e.name,
                s.one_line()
            );
        }
        let path = self.ws.solution_file(&e.name);
        let text =
            std::fs::read_to_string(&path).map_err(|err| format!("{}: {err}", path.display()))?;
        println!("{}:\n\n{text}", self.ws.show(&path));
        Ok(0)
    }
}

/// `file.bak`, or `file.bak2`, `file.bak3`, ... if taken: a backup never overwrites another.
fn backup_path(file: &std::path::Path) -> PathBuf {
    let base = file.as_os_str().to_string_lossy().to_string();
    let mut candidate = PathBuf::from(format!("{base}.bak"));
    let mut k = 2;
    while candidate.exists() {
        candidate = PathBuf::from(format!("{base}.bak{k}"));
        k += 1;
    }
    candidate
}
