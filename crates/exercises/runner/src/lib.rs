//! # The learner's loop around the chapter exercises
//!
//! `cargo exercises <command>` (an alias that builds only this small crate) or `rtl exercises
//! <command>` (the same code inside the `rtl` program):
//!
//! - `list`: every exercise with its state and the section of the book that explains it, `k/N done`,
//!   and the next one to do;
//! - `check [NAME...]`: checks one exercise or several (none: the first not done); exit 0 when
//!   they pass. A failure shows your function and what each check saw;
//! - `hint NAME [--level K]`: the exercise's hints, one level at a time;
//! - `watch [NAME]`: checks the current exercise (or NAME) whenever its file is saved, giving up a
//!   check still running when the file is saved again, and moves on when a save makes it pass (`h`
//!   a hint, `q` quits);
//! - `reset NAME`: restores the stub, keeping your version as a backup file;
//! - `solution NAME [--force]`: the reference solution, once your code passes.
//!
//! Each exercise is its own test target of `rtl-exercises` (see [`cargo`]), so one that does not
//! compile never stops another from being checked or listed. Every command the runner suggests is
//! written the way the learner started it ([`Invocation`]), and a closed standard output (`| head`)
//! ends a command quietly ([`out`]).

pub mod cargo;
pub mod info;
pub mod out;
pub mod report;
pub mod status;
pub mod still_running;
pub mod watch;

use cargo::Workspace;
use info::{Exercise, Kind};
use status::{Checked, Status};
use std::fmt;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;
use still_running::StillRunning;

/// How the learner started the runner, so that every command it suggests is one they can type:
/// `cargo exercises ...` works in any clone, `rtl exercises ...` once `rtl` is installed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Invocation {
    /// `cargo exercises ...` (the alias in `.cargo/config.toml`), or the runner's own binary.
    Cargo,
    /// `rtl exercises ...`.
    Rtl,
}

impl Invocation {
    /// The words that start a command: "cargo exercises" or "rtl exercises".
    pub fn prefix(self) -> &'static str {
        match self {
            Invocation::Cargo => "cargo exercises",
            Invocation::Rtl => "rtl exercises",
        }
    }

    /// The other way to run the same commands, for the usage text.
    fn other(self) -> &'static str {
        match self {
            Invocation::Cargo => Invocation::Rtl.prefix(),
            Invocation::Rtl => Invocation::Cargo.prefix(),
        }
    }
}

/// Why a command did not do what was asked.
#[derive(Debug, PartialEq)]
pub enum Error {
    /// The command line is wrong: the message says how (exit 2).
    Usage(String),
    /// No exercise has this name; the names it could have meant, best first (exit 2).
    UnknownExercise {
        given: String,
        did_you_mean: Vec<String>,
    },
    /// More than one exercise starts with this prefix (exit 2).
    Ambiguous {
        given: String,
        candidates: Vec<String>,
    },
    /// The workspace, cargo or a file would not do it: the message says what (exit 2).
    Failed(String),
    /// Standard output was closed (`... | head -3`): stop quietly (exit 0).
    StdoutClosed,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Usage(why) | Error::Failed(why) => f.write_str(why),
            Error::UnknownExercise {
                given,
                did_you_mean,
            } => match did_you_mean.as_slice() {
                [] => write!(
                    f,
                    "no exercise `{given}`; the command `list` names them all"
                ),
                [one] => write!(f, "no exercise `{given}`: did you mean {one}?"),
                [first @ .., last] => write!(
                    f,
                    "no exercise `{given}`: did you mean {} or {last}?",
                    first.join(", ")
                ),
            },
            Error::Ambiguous { given, candidates } => {
                write!(f, "`{given}` could be {}", candidates.join(", "))
            }
            Error::StdoutClosed => f.write_str("standard output is closed"),
        }
    }
}

impl std::error::Error for Error {}

/// The usage text, with the commands written the way the learner started the runner.
pub fn usage(inv: Invocation) -> String {
    format!(
        "usage: {p} <command>     (or: {o} <command>, the same)

  list                     every exercise: state, book section, k/N done, and the next to do
  check [NAME...]          check exercises (none: the current one); exit 0 when they all pass
  hint NAME [--level K]    hint K (default 1) of the exercise
  watch [NAME]             re-check the current exercise (or NAME) on every save; h: hint, q: quit
  reset NAME               restore the stub; your version is kept as NAME.rs.bak
  solution NAME [--force]  the reference solution, once your code passes (--force: peek)

NAME is an exercise's file name without .rs, e.g. ch02_estimate_pi (a unique prefix will do).",
        p = inv.prefix(),
        o = inv.other()
    )
}

/// Runs the command line `args` (without the program name), started as `inv`; returns the exit
/// code: 0 when the command did what was asked (and a check passed), 1 when a check failed, 2 when
/// the command could not run. A closed standard output ends it quietly with 0.
pub fn run(args: &[String], inv: Invocation) -> i32 {
    match dispatch(args, inv) {
        Ok(code) => code,
        Err(Error::StdoutClosed) => 0,
        Err(e) => {
            warn!("error: {e}");
            2
        }
    }
}

/// A command line, read and its exercise names resolved.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    Help,
    List,
    Check(Vec<String>),
    Hint { name: String, level: usize },
    Watch(Option<String>),
    Reset(String),
    Solution { name: String, force: bool },
}

/// Reads the command line `args` against the exercises of `info.toml`.
pub fn parse_command(
    args: &[String],
    exercises: &[Exercise],
    inv: Invocation,
) -> Result<Command, Error> {
    let Some(command) = args.first() else {
        return Err(Error::Usage(format!("which command?\n{}", usage(inv))));
    };
    let rest = &args[1..];
    let name = |rest: &[String]| -> Result<String, Error> {
        let arg = rest.first().ok_or_else(|| {
            Error::Usage(format!(
                "`{command}` needs an exercise, e.g. `{} {command} ch02_estimate_pi`",
                inv.prefix()
            ))
        })?;
        resolve(exercises, arg).map(|e| e.name.clone())
    };
    // The error for an argument after the exercise that the command does not take.
    let extra = |rest: &[String], extra: &str| -> Error {
        if extra.starts_with('-') {
            Error::Usage(format!("{command}: unexpected `{extra}`\n{}", usage(inv)))
        } else {
            Error::Usage(format!(
                "`{command}` takes one exercise at a time (got `{}` and `{extra}`)",
                rest[0]
            ))
        }
    };
    let one_only = |rest: &[String]| -> Result<(), Error> {
        match rest.get(1) {
            None => Ok(()),
            Some(e) => Err(extra(rest, e)),
        }
    };
    match command.as_str() {
        "-h" | "--help" | "help" => Ok(Command::Help),
        "list" => {
            no_more(rest, 0, inv)?;
            Ok(Command::List)
        }
        "check" => {
            let mut names: Vec<String> = Vec::new();
            for arg in rest {
                if arg.starts_with('-') {
                    return Err(Error::Usage(format!(
                        "check: unexpected `{arg}`\n{}",
                        usage(inv)
                    )));
                }
                let n = resolve(exercises, arg)?.name.clone();
                if !names.contains(&n) {
                    names.push(n);
                }
            }
            Ok(Command::Check(names))
        }
        "hint" => {
            let n = name(rest)?;
            let number = |v: &str| {
                v.parse::<usize>()
                    .map_err(|_| Error::Usage(format!("--level {v}: not a whole number")))
            };
            let level = match rest.get(1).map(String::as_str) {
                None => 1,
                Some("--level") => {
                    let v = rest
                        .get(2)
                        .ok_or_else(|| Error::Usage("--level needs a number: --level 2".into()))?;
                    no_more(rest, 3, inv)?;
                    number(v)?
                }
                Some(v) if v.starts_with("--level=") => {
                    no_more(rest, 2, inv)?;
                    number(&v["--level=".len()..])?
                }
                Some(e) => return Err(extra(rest, e)),
            };
            Ok(Command::Hint { name: n, level })
        }
        "watch" => {
            if rest.is_empty() {
                return Ok(Command::Watch(None));
            }
            let n = name(rest)?;
            one_only(rest)?;
            Ok(Command::Watch(Some(n)))
        }
        "reset" => {
            let n = name(rest)?;
            one_only(rest)?;
            Ok(Command::Reset(n))
        }
        "solution" => {
            let n = name(rest)?;
            let force = match rest.get(1).map(String::as_str) {
                None => false,
                Some("--force") => true,
                Some(e) => return Err(extra(rest, e)),
            };
            no_more(rest, if force { 2 } else { 1 }, inv)?;
            Ok(Command::Solution { name: n, force })
        }
        other => {
            let meant = COMMANDS
                .iter()
                .filter(|c| edit_distance(&other.to_ascii_lowercase(), c) <= 2)
                .min_by_key(|c| edit_distance(&other.to_ascii_lowercase(), c));
            Err(Error::Usage(match meant {
                Some(c) => format!(
                    "unknown command `{other}`: did you mean `{} {c}`?",
                    inv.prefix()
                ),
                None => format!("unknown command `{other}`\n{}", usage(inv)),
            }))
        }
    }
}

/// The commands, for a mistyped one's suggestion.
const COMMANDS: [&str; 7] = [
    "list", "check", "hint", "watch", "reset", "solution", "help",
];

fn no_more(rest: &[String], n: usize, inv: Invocation) -> Result<(), Error> {
    match rest.get(n) {
        None => Ok(()),
        Some(extra) => Err(Error::Usage(format!(
            "unexpected argument `{extra}`\n{}",
            usage(inv)
        ))),
    }
}

/// The exercise `arg` names: its exact name, its file name or path, or a unique prefix. Anything
/// else is [`Error::UnknownExercise`] with the names it could have meant: `ch2_estimate_pi` (a
/// chapter without its 0), `estimate_pi` (no chapter), or a name a typo or two away.
pub fn resolve<'a>(exercises: &'a [Exercise], arg: &str) -> Result<&'a Exercise, Error> {
    let want = arg
        .rsplit(['/', '\\'])
        .next()
        .unwrap_or(arg)
        .trim_end_matches(".rs");
    if let Some(e) = exercises.iter().find(|e| e.name == want) {
        return Ok(e);
    }
    let prefixed: Vec<&Exercise> = exercises
        .iter()
        .filter(|e| !want.is_empty() && e.name.starts_with(want))
        .collect();
    match prefixed.as_slice() {
        [one] => return Ok(one),
        [] => {}
        many => {
            return Err(Error::Ambiguous {
                given: want.to_string(),
                candidates: many.iter().map(|e| e.name.clone()).collect(),
            });
        }
    }
    Err(Error::UnknownExercise {
        given: want.to_string(),
        did_you_mean: did_you_mean(exercises, want),
    })
}

/// The exercises `want` may have meant, best first (at most three).
fn did_you_mean(exercises: &[Exercise], want: &str) -> Vec<String> {
    let want = want.to_ascii_lowercase();
    // "ch2_x" -> "ch02_x"
    let padded = match want.strip_prefix("ch") {
        Some(rest) if rest.find('_') == Some(1) && rest.as_bytes()[0].is_ascii_digit() => {
            format!("ch0{rest}")
        }
        _ => want.clone(),
    };
    let mut scored: Vec<(usize, &str)> = Vec::new();
    for e in exercises {
        let topic = e.name.get(5..).unwrap_or("");
        let score = if padded == e.name || want == topic {
            0
        } else if want.len() >= 4 && (topic.contains(&want) || e.name.starts_with(&padded)) {
            1
        } else {
            let d = edit_distance(&padded, &e.name).min(edit_distance(&want, topic) + 1);
            if d > 2.max(want.len() / 5) {
                continue;
            }
            1 + d
        };
        scored.push((score, &e.name));
    }
    scored.sort();
    let best = scored.first().map_or(0, |s| s.0);
    scored
        .into_iter()
        .filter(|s| s.0 == best)
        .take(3)
        .map(|s| s.1.to_string())
        .collect()
}

/// The Levenshtein distance between `a` and `b`: the fewest insertions, deletions and
/// substitutions of one character that turn one into the other.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (diagonal + usize::from(ca != cb))
                .min(above + 1)
                .min(row[j] + 1);
            diagonal = above;
        }
    }
    row[b.len()]
}

fn dispatch(args: &[String], inv: Invocation) -> Result<i32, Error> {
    if args.is_empty() {
        warn!("{}", usage(inv));
        return Ok(2);
    }
    if matches!(args[0].as_str(), "-h" | "--help" | "help") {
        sayln!("{}", usage(inv))?;
        return Ok(0);
    }
    let ws = Workspace::find()?;
    let exercises = info::load(&ws.info()).map_err(|e| Error::Failed(e.to_string()))?;
    let command = parse_command(args, &exercises, inv)?;
    let ctx = Context { ws, exercises, inv };
    match command {
        Command::Help => {
            sayln!("{}", usage(inv))?;
            Ok(0)
        }
        Command::List => ctx.list(),
        Command::Check(names) => ctx.check(&names),
        Command::Hint { name, level } => ctx.hint(ctx.exercise(&name), level),
        Command::Watch(name) => watch::watch(&ctx, name.as_deref()),
        Command::Reset(name) => ctx.reset(ctx.exercise(&name)),
        Command::Solution { name, force } => ctx.solution(ctx.exercise(&name), force),
    }
}

/// The workspace, its exercises, and how the learner runs the runner.
pub struct Context {
    pub ws: Workspace,
    pub exercises: Vec<Exercise>,
    pub inv: Invocation,
}

/// The width `list` keeps to: its rows fit a terminal of 100 columns.
pub const LIST_WIDTH: usize = 100;

impl Context {
    /// "cargo exercises" or "rtl exercises".
    pub fn cmd(&self) -> &'static str {
        self.inv.prefix()
    }

    /// The exercise of a name that [`resolve`] gave.
    fn exercise(&self, name: &str) -> &Exercise {
        self.exercises
            .iter()
            .find(|e| e.name == name)
            .expect("a resolved name")
    }

    /// The state of each of `exercises`: built together (no time limit), then each one's checks run
    /// under [`status::time_limit`], saying on standard error while a run takes long
    /// ([`StillRunning`]).
    pub fn check_all(&self, exercises: &[&Exercise]) -> Result<Vec<Checked>, Error> {
        let checked = self.check_all_until(exercises, &mut || false)?;
        Ok(checked.expect("never stopped"))
    }

    /// [`Context::check_all`], giving up (`None`) as soon as `stop` says so while the checks run
    /// (it is asked every 10 ms).
    pub fn check_all_until(
        &self,
        exercises: &[&Exercise],
        stop: &mut dyn FnMut() -> bool,
    ) -> Result<Option<Vec<Checked>>, Error> {
        let limit = status::time_limit()?;
        let names: Vec<String> = exercises.iter().map(|e| e.name.clone()).collect();
        let mut shown = false;
        let built = cargo::build(&self.ws, &names, &mut |_what| {
            if !shown {
                warn!("building the exercises (the first time takes a minute) ...");
                shown = true;
            }
        })?;
        let mut programs: Vec<(String, PathBuf)> = Vec::new();
        for e in exercises {
            let b = built
                .get(&e.name)
                .ok_or_else(|| Error::Failed(format!("{}: not built", e.name)))?;
            if let Some(exe) = &b.exe {
                programs.push((e.name.clone(), exe.clone()));
            }
        }
        let stderr = std::io::stderr();
        let terminal = stderr.is_terminal();
        let mut notices = StillRunning::new(stderr, terminal, limit);
        let runs = cargo::run_all_until(
            &self.ws,
            &programs,
            limit,
            &mut |names, oldest| notices.update(names, oldest, Instant::now()),
            stop,
        )?;
        notices.finish();
        let Some(runs) = runs else {
            return Ok(None);
        };
        let mut runs = runs.into_iter();
        let mut out = Vec::new();
        for e in exercises {
            let b = &built[&e.name];
            out.push(match &b.exe {
                None => Checked {
                    status: Status::DoesNotCompile(b.diagnostics.clone()),
                    printed: Default::default(),
                    warnings: String::new(),
                },
                Some(_) => {
                    let ran = runs.next().expect("one run per program");
                    Checked {
                        status: status::from_run(e, &ran),
                        printed: ran.printed().clone(),
                        warnings: b.warnings.clone(),
                    }
                }
            });
        }
        Ok(Some(out))
    }

    /// The state of each of `exercises` ([`Context::check_all`]).
    pub fn statuses(&self, exercises: &[&Exercise]) -> Result<Vec<Status>, Error> {
        Ok(self
            .check_all(exercises)?
            .into_iter()
            .map(|c| c.status)
            .collect())
    }

    fn list(&self) -> Result<i32, Error> {
        let all: Vec<&Exercise> = self.exercises.iter().collect();
        let statuses = self.statuses(&all)?;
        sayln!("{}", list_table(&all, &statuses))?;
        sayln!("{}", progress(&all, &statuses))?;
        match all.iter().zip(&statuses).find(|(_, s)| !s.is_done()) {
            Some((e, _)) => {
                sayln!("next: {}, in chapter {}", e.name, e.chapter)?;
                sayln!("      read first: {}", e.section_words())?;
                sayln!(
                    "      edit {}",
                    self.ws.show(&self.ws.exercise_file(&e.name))
                )?;
                sayln!("      then `{} check {}`", self.cmd(), e.name)?;
                sayln!(
                    "      (or leave `{} watch` running: it checks on every save)",
                    self.cmd()
                )?;
            }
            None => sayln!("every exercise is done: well done!")?,
        }
        Ok(0)
    }

    fn check(&self, names: &[String]) -> Result<i32, Error> {
        if names.is_empty() {
            return self.check_current();
        }
        let exercises: Vec<&Exercise> = names.iter().map(|n| self.exercise(n)).collect();
        let checked = self.check_all(&exercises)?;
        for (i, (e, c)) in exercises.iter().zip(&checked).enumerate() {
            if i > 0 {
                sayln!()?;
            }
            say!("{}", c.explain(&self.ws, e, self.cmd()))?;
        }
        Ok(if checked.iter().all(|c| c.status.is_done()) {
            0
        } else {
            1
        })
    }

    /// `check` without a name: the current exercise, the first not done (all are checked to find
    /// it, as `list` does).
    fn check_current(&self) -> Result<i32, Error> {
        let all: Vec<&Exercise> = self.exercises.iter().collect();
        let checked = self.check_all(&all)?;
        let Some((e, c)) = all.iter().zip(&checked).find(|(_, c)| !c.status.is_done()) else {
            sayln!("every exercise is done: well done!")?;
            return Ok(0);
        };
        sayln!(
            "the current exercise, the first not done ({}/{} done; `{} check NAME` checks another):\n",
            checked.iter().filter(|c| c.status.is_done()).count(),
            all.len(),
            self.cmd()
        )?;
        say!("{}", c.explain(&self.ws, e, self.cmd()))?;
        Ok(1)
    }

    fn hint(&self, e: &Exercise, level: usize) -> Result<i32, Error> {
        let n = e.hints.len();
        if level == 0 || level > n {
            return Err(Error::Usage(format!(
                "{} has hints 1 to {n}; --level {level} is not one of them",
                e.name
            )));
        }
        sayln!("{}: hint {level} of {n}\n", e.name)?;
        sayln!("{}", e.hints[level - 1])?;
        if level < n {
            sayln!(
                "\n(`{} hint {} --level {}` for the next)",
                self.cmd(),
                e.name,
                level + 1
            )?;
        }
        Ok(0)
    }

    fn reset(&self, e: &Exercise) -> Result<i32, Error> {
        let file = self.ws.exercise_file(&e.name);
        let stub = std::fs::read(self.ws.stub_file(&e.name)).map_err(|err| {
            Error::Failed(format!(
                "{}: {err}",
                self.ws.show(&self.ws.stub_file(&e.name))
            ))
        })?;
        let mine = std::fs::read(&file).ok();
        if mine.as_deref() == Some(stub.as_slice()) {
            sayln!(
                "{} is already the stub: nothing to reset",
                self.ws.show(&file)
            )?;
            return Ok(0);
        }
        if mine.is_some() {
            let backup = backup_path(&file);
            std::fs::copy(&file, &backup)
                .map_err(|err| Error::Failed(format!("backup {}: {err}", backup.display())))?;
            sayln!("your version is kept in {}", self.ws.show(&backup))?;
        }
        std::fs::write(&file, &stub)
            .map_err(|err| Error::Failed(format!("{}: {err}", file.display())))?;
        sayln!("{} is the stub again", self.ws.show(&file))?;
        Ok(0)
    }

    fn solution(&self, e: &Exercise, force: bool) -> Result<i32, Error> {
        let s = self.statuses(&[e])?.remove(0);
        if !s.is_done() && !force {
            warn!(
                "{}: {}. The reference solution is shown once your code passes: try \
                 `{} hint {}` first (`{} solution {} --force` peeks anyway).",
                e.name,
                s.one_line(),
                self.cmd(),
                e.name,
                self.cmd(),
                e.name
            );
            return Ok(1);
        }
        if !s.is_done() {
            warn!(
                "warning: {} does not pass yet ({}); here is the reference solution anyway.\n",
                e.name,
                s.one_line()
            );
        }
        let path = self.ws.solution_file(&e.name);
        let text = std::fs::read_to_string(&path)
            .map_err(|err| Error::Failed(format!("{}: {err}", path.display())))?;
        sayln!(
            "{}:\n\n{}",
            self.ws.show(&path),
            as_invoked(&text, self.inv)
        )?;
        Ok(0)
    }
}

/// `text` (a file of the exercises, whose comments write commands as `` `cargo exercises ...` ``)
/// with its commands written the way the learner started the runner.
pub fn as_invoked(text: &str, inv: Invocation) -> String {
    text.replace(
        &format!("`{} ", Invocation::Cargo.prefix()),
        &format!("`{} ", inv.prefix()),
    )
}

/// `list`'s table: one row per exercise (number, name, state, the section of the book that explains
/// it), and for one not done, why, on a second, indented line; every line within [`LIST_WIDTH`].
pub fn list_table(exercises: &[&Exercise], statuses: &[Status]) -> String {
    let wn = exercises
        .iter()
        .map(|e| e.name.len())
        .max()
        .unwrap_or(8)
        .max(8);
    let ws = statuses
        .iter()
        .map(|s| s.word().len())
        .max()
        .unwrap_or(5)
        .max(5);
    let section_width = LIST_WIDTH.saturating_sub(4 + wn + 2 + ws + 2);
    let mut out = format!(
        "{:>2}  {:<wn$}  {:<ws$}  where the book explains it\n",
        "#", "exercise", "state"
    );
    for (i, (e, s)) in exercises.iter().zip(statuses).enumerate() {
        out += &format!(
            "{:>2}  {:<wn$}  {:<ws$}  {}\n",
            i + 1,
            e.name,
            s.word(),
            status::cut(&e.section, section_width)
        );
        if let Some(why) = s.why() {
            out += &format!("      {}\n", status::cut(&why, LIST_WIDTH - 6));
        }
    }
    if exercises.iter().any(|e| e.kind == Kind::Bug) {
        out +=
            "\n(chNN_bug_*: the bug museum, code that runs and is wrong: find and fix the bug)\n";
    }
    out
}

/// "3/21 exercises done; 13 of their 46 checks pass", and which exercises' checks are not counted
/// because they did not run (they do not compile, timed out or crashed), so that the total never
/// silently shrinks.
pub fn progress(exercises: &[&Exercise], statuses: &[Status]) -> String {
    let done = statuses.iter().filter(|s| s.is_done()).count();
    let (passed, total) = statuses
        .iter()
        .filter_map(Status::counts)
        .fold((0, 0), |(p, t), (a, b)| (p + a, t + b));
    let missing: Vec<String> = exercises
        .iter()
        .zip(statuses)
        .filter(|(_, s)| s.counts().is_none())
        .map(|(e, s)| format!("{} ({})", e.name, s.word()))
        .collect();
    let mut out = format!(
        "{done}/{} exercises done; {passed} of {total} checks pass",
        exercises.len()
    );
    if !missing.is_empty() {
        out += &format!(
            ", not counting the checks of {}, which did not run",
            missing.join(", ")
        );
    }
    out
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

#[cfg(test)]
mod tests {
    use super::*;

    fn exercises() -> Vec<Exercise> {
        let text = [
            ("ch02_estimate_pi", "write"),
            ("ch02_jittered_pi", "write"),
            ("ch03_inverse_x_sq", "write"),
            ("ch12_bug_nan_average", "bug"),
        ]
        .iter()
        .map(|(n, k)| {
            format!(
                "[[exercise]]\nname = \"{n}\"\nchapter = \"{c} C\"\nsection = \"{c} S\"\nkind = \"{k}\"\nhints = [\"a\", \"b\"]\n",
                c = &n[2..4]
            )
        })
        .collect::<String>();
        info::parse(&text).unwrap()
    }

    fn args(s: &str) -> Vec<String> {
        s.split_whitespace().map(str::to_string).collect()
    }

    fn parse(s: &str) -> Result<Command, Error> {
        parse_command(&args(s), &exercises(), Invocation::Cargo)
    }

    #[test]
    fn check_takes_several_exercises_and_watch_takes_one() {
        assert_eq!(
            parse("check ch02_estimate_pi ch03").unwrap(),
            Command::Check(vec!["ch02_estimate_pi".into(), "ch03_inverse_x_sq".into()])
        );
        assert_eq!(
            parse("check ch02_estimate_pi crates/exercises/exercises/ch02_estimate_pi.rs").unwrap(),
            Command::Check(vec!["ch02_estimate_pi".into()]),
            "the same exercise twice is checked once"
        );
        assert_eq!(
            parse("watch ch03_inverse_x_sq").unwrap(),
            Command::Watch(Some("ch03_inverse_x_sq".into()))
        );
        assert_eq!(parse("watch").unwrap(), Command::Watch(None));
        let err = parse("reset ch02_estimate_pi ch02_jittered_pi").unwrap_err();
        assert_eq!(
            err.to_string(),
            "`reset` takes one exercise at a time (got `ch02_estimate_pi` and `ch02_jittered_pi`)"
        );
        assert_eq!(parse("check").unwrap(), Command::Check(Vec::new()));
        assert_eq!(
            parse("hint ch02_j --level 2").unwrap(),
            Command::Hint {
                name: "ch02_jittered_pi".into(),
                level: 2
            }
        );
    }

    #[test]
    fn a_mistyped_name_gets_the_names_it_could_mean() {
        for typed in [
            "ch2_estimate_pi",
            "estimate_pi",
            "ch02_estimate_pl",
            "ch02_estmate_pi",
        ] {
            let err = parse(&format!("check {typed}")).unwrap_err();
            assert_eq!(
                err.to_string(),
                format!("no exercise `{typed}`: did you mean ch02_estimate_pi?"),
                "{typed}"
            );
        }
        let err = parse("check ch3_inverse").unwrap_err();
        assert_eq!(
            err.to_string(),
            "no exercise `ch3_inverse`: did you mean ch03_inverse_x_sq?"
        );
        let err = parse("watch nan_average").unwrap_err();
        assert!(
            err.to_string()
                .ends_with("did you mean ch12_bug_nan_average?"),
            "{err}"
        );
        for (typed, meant) in [
            ("chek", "check"),
            ("lsit", "list"),
            ("Watch", "watch"),
            ("hnit", "hint"),
        ] {
            let err = parse(&format!("{typed} ch02_estimate_pi")).unwrap_err();
            assert_eq!(
                err.to_string(),
                format!("unknown command `{typed}`: did you mean `cargo exercises {meant}`?")
            );
        }
        assert!(
            parse("frobnicate")
                .unwrap_err()
                .to_string()
                .starts_with("unknown command `frobnicate`\nusage: ")
        );
        let err = parse("check frobnicate").unwrap_err();
        assert_eq!(
            err.to_string(),
            "no exercise `frobnicate`; the command `list` names them all"
        );
        let err = parse("check ch02").unwrap_err();
        assert_eq!(
            err.to_string(),
            "`ch02` could be ch02_estimate_pi, ch02_jittered_pi"
        );
        assert_eq!(edit_distance("ch2_estimate_pi", "ch02_estimate_pi"), 1);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
    }

    #[test]
    fn usage_and_suggestions_are_written_the_way_the_runner_was_started() {
        assert!(usage(Invocation::Cargo).starts_with("usage: cargo exercises <command>"));
        assert!(usage(Invocation::Rtl).starts_with("usage: rtl exercises <command>"));
        let ws = Workspace {
            root: PathBuf::from("/nonexistent"),
        };
        let e = &exercises()[0];
        let failing = Checked {
            status: Status::Failing {
                passed: 0,
                total: 1,
                why: "w".into(),
                details: String::new(),
            },
            printed: Default::default(),
            warnings: String::new(),
        };
        // A solution's header, as `solution` prints it.
        let header = "//! exercise first (`cargo exercises solution ch02_x` shows it once ...).";
        assert_eq!(as_invoked(header, Invocation::Cargo), header);
        assert_eq!(
            as_invoked(header, Invocation::Rtl),
            "//! exercise first (`rtl exercises solution ch02_x` shows it once ...)."
        );
        for inv in [Invocation::Cargo, Invocation::Rtl] {
            let text = failing.explain(&ws, e, inv.prefix());
            assert!(
                text.contains(&format!("`{} hint ch02_estimate_pi`", inv.prefix())),
                "{text}"
            );
            let other = if inv == Invocation::Cargo {
                "rtl exercises hint"
            } else {
                "cargo exercises hint"
            };
            assert!(!text.contains(other), "{text}");
        }
    }

    #[test]
    fn list_rows_fit_100_columns_and_the_total_names_what_did_not_run() {
        let all = exercises();
        let refs: Vec<&Exercise> = all.iter().collect();
        let statuses = vec![
            Status::Done {
                total: 2,
                details: String::new(),
            },
            Status::DoesNotCompile("error[E0425]: cannot find value `x` in this scope".into()),
            Status::Failing {
                passed: 1,
                total: 2,
                why: "sample_linear: the samples do not follow the density ".repeat(8),
                details: String::new(),
            },
            Status::TimedOut {
                limit: std::time::Duration::from_secs(10),
                log: Default::default(),
            },
        ];
        let table = list_table(&refs, &statuses);
        for line in table.lines() {
            assert!(
                line.chars().count() <= 100,
                "{} columns: {line}",
                line.len()
            );
        }
        assert!(table.contains("\n      error[E0425]"), "{table}");
        assert!(table.contains("failing 1/2"), "{table}");
        let p = progress(&refs, &statuses);
        assert_eq!(
            p,
            "1/4 exercises done; 3 of 4 checks pass, not counting the checks of ch02_jittered_pi \
             (does not compile), ch12_bug_nan_average (timed out), which did not run"
        );
    }
}
