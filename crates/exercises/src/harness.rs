//! The program each exercise's test target runs (`harness = false`): it runs the exercise's checks
//! one by one, catches a `todo!()` or any other panic of the learner's code, and makes one report.
//!
//! The report's first line is the summary:
//!
//! ```text
//! ch02_estimate_pi: failing: 1/2 checks passed: estimate_pi with 1e5 points: estimate 0.785 is ...
//! ```
//!
//! (the state is `done`, `failing` or `not started`), followed by one line per check (`ok`, `FAIL`
//! with what the statistics saw, or `todo`). The program exits 0 exactly when every check passes.
//!
//! Run by hand (`cargo test -p rtl-exercises`) it prints the report. The runner (`cargo exercises`,
//! `rtl exercises`) instead names a file in [`REPORT_ENV`], and the report goes there, where
//! nothing the learner's code prints can end up or pass for it; what the learner's code prints
//! stays on standard output and error, which the runner shows as such. The file is a log of lines
//! written as the checks run, so that a run stopped at the time limit still tells which check and
//! which call of the learner's code were running ([`REPORT_FORMAT`]).
//!
//! With `--features solutions` it checks the reference solution instead of the learner's file, and the
//! shipped stub too, which the checks must reject (a stub's `todo!()`, or a bug-museum exercise's bug):
//! it exits 0 when the solution passes and the stub does not.

use crate::check::CheckResult;
use std::cell::{Cell, RefCell};
use std::fs::File;
use std::io::Write;
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, Once};
use std::time::Duration;

/// The environment variable in which the runner names the file the report goes to.
pub const REPORT_ENV: &str = "RTL_EXERCISES_REPORT";

/// The lines of the report file, in the order they are written (the runner's `report` module reads
/// them): a line of text of the report itself is written as `| TEXT`.
///
/// ```text
/// rtl-exercises report 1
/// checks N          the number of checks
/// start K LABEL     check K (1 to N) starts
/// call TEXT         the call of the learner's code in progress in check K, as a panic report names
///                   it; `call` alone: none (written when it changes, looked at every 100 ms)
/// result K          check K ended; its lines of the report follow
/// report            every check ended; the whole report follows, then `end`
/// end
/// ```
pub const REPORT_FORMAT: &str = "rtl-exercises report 1";

/// How often the call in progress is written to the report file.
const CALL_EVERY: Duration = Duration::from_millis(100);

/// One named check of an exercise.
pub struct Check {
    label: &'static str,
    run: Box<dyn Fn() -> CheckResult>,
}

impl Check {
    /// The check `run`, described to the learner as `label`.
    pub fn new(label: &'static str, run: impl Fn() -> CheckResult + 'static) -> Self {
        Self {
            label,
            run: Box::new(run),
        }
    }
}

/// What one check found.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    Pass,
    /// The check ran and saw this.
    Fail(String),
    /// A `todo!()` was reached; its message.
    Todo(String),
    /// The code under test panicked: message and location.
    Panic(String),
}

/// The state of an exercise from its checks' outcomes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum State {
    Done,
    Failing,
    NotStarted,
}

impl State {
    /// The word the runner reads: `done`, `failing`, `not started`.
    pub fn word(self) -> &'static str {
        match self {
            State::Done => "done",
            State::Failing => "failing",
            State::NotStarted => "not started",
        }
    }
}

thread_local! {
    /// Whether a panic on this thread is a check's to report ([`run_check`] is running one).
    static CAPTURING: Cell<bool> = const { Cell::new(false) };
    /// The report of the last panic captured on this thread.
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Runs one check, turning a panic into an [`Outcome`] instead of a harness's backtrace.
pub fn run_check(check: &Check) -> Outcome {
    install_panic_hook();
    LAST_PANIC.with(|p| p.borrow_mut().take());
    crate::check::forget_call();
    let capturing = CAPTURING.with(|c| c.replace(true));
    let result = panic::catch_unwind(AssertUnwindSafe(|| (check.run)()));
    CAPTURING.with(|c| c.set(capturing));
    match result {
        Ok(Ok(())) => Outcome::Pass,
        Ok(Err(why)) => Outcome::Fail(why),
        Err(_) => {
            let msg = LAST_PANIC
                .with(|p| p.borrow_mut().take())
                .unwrap_or_else(|| "a panic".to_string());
            match msg.split_once("not yet implemented") {
                Some((_, rest)) => Outcome::Todo(rest.trim_start_matches(": ").to_string()),
                None => Outcome::Panic(msg),
            }
        }
    }
}

/// Installs, once, the panic hook that records a check's panic: its message, its place (the
/// learner's file and line) and, when the check recorded it (see [`crate::check::calling`]), the
/// call and input that caused it, instead of printing it. A panic outside [`run_check`] (another
/// test's failing assertion) goes to the hook that was there before.
fn install_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let before = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if CAPTURING.with(Cell::get) {
                let text = panic_report(info);
                LAST_PANIC.with(|p| *p.borrow_mut() = Some(text));
            } else {
                before(info);
            }
        }));
    });
}

/// "your code panicked in f(u = 0.5) at crates/exercises/exercises/ch03_x.rs:12:5: MESSAGE"; a
/// `todo!()`'s message as it is.
fn panic_report(info: &panic::PanicHookInfo) -> String {
    let payload = info.payload();
    let msg = payload
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_else(|| "a panic".to_string());
    let during = crate::check::call_in_progress()
        .map(|call| format!(" in {call}"))
        .unwrap_or_default();
    match info.location() {
        Some(_) if msg.starts_with("not yet implemented") => msg,
        Some(l) => format!(
            "your code panicked{during} at {}:{}:{}: {msg}",
            l.file().replace("/tests/../", "/"),
            l.line(),
            l.column()
        ),
        None => format!("your code panicked{during}: {msg}"),
    }
}

/// The report of a check that must panic: `run` is a check fed a deliberately panicking
/// implementation. Panics (fails the test) if the check passes, fails or reaches a `todo!()`.
#[cfg(test)]
pub(crate) fn panic_of(run: impl Fn() -> CheckResult + 'static) -> String {
    match run_check(&Check::new("panics", run)) {
        Outcome::Panic(report) => report,
        other => panic!("expected a panic report, got {other:?}"),
    }
}

/// The outcomes of all of an exercise's checks.
pub struct Report {
    pub outcomes: Vec<(&'static str, Outcome)>,
}

impl Report {
    /// Runs every check.
    pub fn run(checks: &[Check]) -> Self {
        Self {
            outcomes: checks.iter().map(|c| (c.label, run_check(c))).collect(),
        }
    }

    pub fn passed(&self) -> usize {
        self.outcomes
            .iter()
            .filter(|(_, o)| *o == Outcome::Pass)
            .count()
    }

    pub fn state(&self) -> State {
        if self.passed() == self.outcomes.len() {
            State::Done
        } else if self
            .outcomes
            .iter()
            .all(|(_, o)| matches!(o, Outcome::Todo(_)))
        {
            State::NotStarted
        } else {
            State::Failing
        }
    }

    /// The report: the summary line, then one line (or an indented block) per check.
    pub fn render(&self, name: &str) -> String {
        let state = self.state();
        let mut out = format!(
            "{name}: {}: {}/{} checks passed",
            state.word(),
            self.passed(),
            self.outcomes.len()
        );
        let first = self.outcomes.iter().find_map(|(label, o)| match o {
            Outcome::Fail(why) | Outcome::Panic(why) => Some(format!("{label}: {why}")),
            Outcome::Todo(what) if state != State::NotStarted => {
                Some(format!("{label}: still todo!() ({what})"))
            }
            _ => None,
        });
        if let Some(first) = first {
            out += ": ";
            out += first.lines().next().unwrap_or("");
        }
        out.push('\n');
        for (label, o) in &self.outcomes {
            out += &render_outcome(label, o);
        }
        out
    }
}

/// One check's lines of the report: `  ok    LABEL`, or `  FAIL  LABEL` and what it saw, indented.
pub fn render_outcome(label: &str, outcome: &Outcome) -> String {
    let (tag, text) = match outcome {
        Outcome::Pass => ("ok  ", String::new()),
        Outcome::Fail(why) | Outcome::Panic(why) => ("FAIL", why.clone()),
        Outcome::Todo(what) => ("todo", format!("todo!(\"{what}\") reached")),
    };
    let mut out = format!("  {tag}  {label}\n");
    for l in text.lines() {
        out += &format!("          {l}\n");
    }
    out
}

/// The report file the runner named ([`REPORT_ENV`]), written line by line as the checks run
/// ([`REPORT_FORMAT`]).
struct ReportFile {
    file: Mutex<File>,
}

impl ReportFile {
    /// The file named by [`REPORT_ENV`], if it is set.
    fn from_env() -> Option<Self> {
        let path = std::env::var_os(REPORT_ENV)?;
        let file = File::create(&path).unwrap_or_else(|e| {
            eprintln!("{REPORT_ENV}={}: {e}", path.to_string_lossy());
            std::process::exit(2)
        });
        let r = Self {
            file: Mutex::new(file),
        };
        r.write(&format!("{REPORT_FORMAT}\n"));
        Some(r)
    }

    /// Writes `text` whole, in one write.
    fn write(&self, text: &str) {
        let mut file = self.file.lock().unwrap_or_else(|e| e.into_inner());
        // Nowhere to say that the file cannot be written: the runner then finds no report.
        let _ = file.write_all(text.as_bytes());
    }

    /// A line of the protocol, then `body`'s lines as `| TEXT`.
    fn record(&self, line: &str, body: &str) -> String {
        let mut text = format!("{}\n", line.replace('\n', " "));
        for l in body.lines() {
            text += &format!("| {l}\n");
        }
        text
    }

    /// Writes, every [`CALL_EVERY`] until `stop`, the call in progress when it changed.
    fn watch_calls(self: &Arc<Self>, stop: &Arc<AtomicBool>) {
        let (me, stop) = (Arc::clone(self), Arc::clone(stop));
        std::thread::spawn(move || {
            let mut last: Option<String> = None;
            while !stop.load(Ordering::Relaxed) {
                std::thread::sleep(CALL_EVERY);
                // The file is locked while the call is read: a call line then always follows the
                // `start` line of its own check (a check's end forgets its call before writing).
                let mut file = me.file.lock().unwrap_or_else(|e| e.into_inner());
                let now = crate::check::published_call();
                if now != last {
                    let line = match &now {
                        Some(call) => format!("call {}\n", call.replace('\n', " ")),
                        None => "call\n".to_string(),
                    };
                    let _ = file.write_all(line.as_bytes());
                    last = now;
                }
            }
        });
    }
}

/// Runs `checks` as [`Report::run`] does, recording each check's start and result in `file`.
fn run_into(file: &Arc<ReportFile>, checks: &[Check]) -> Report {
    file.write(&format!("checks {}\n", checks.len()));
    let stop = Arc::new(AtomicBool::new(false));
    crate::check::publish_calls(true);
    file.watch_calls(&stop);
    let mut outcomes = Vec::new();
    for (k, c) in checks.iter().enumerate() {
        file.write(&format!("start {} {}\n", k + 1, c.label.replace('\n', " ")));
        let outcome = run_check(c);
        crate::check::forget_call();
        file.write(&file.record(
            &format!("result {}", k + 1),
            &render_outcome(c.label, &outcome),
        ));
        outcomes.push((c.label, outcome));
    }
    stop.store(true, Ordering::Relaxed);
    crate::check::publish_calls(false);
    Report { outcomes }
}

/// What the test target was asked to do by `cargo test ... -- ARGS`.
enum Mode {
    Run,
    List,
    Skip,
}

fn mode(name: &str) -> Mode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut filters = Vec::new();
    let (mut exact, mut list) = (false, false);
    let mut i = 0;
    while i < args.len() {
        let a = args[i].as_str();
        match a {
            "--list" => list = true,
            "--exact" => exact = true,
            // There are no ignored checks: `-- --ignored` runs none of them.
            "--ignored" => return Mode::Skip,
            "--skip" => {
                i += 1;
                if args.get(i).is_some_and(|s| name.contains(s.as_str())) {
                    return Mode::Skip;
                }
            }
            "--test-threads" | "--color" | "--format" | "--logfile" | "-Z" => i += 1,
            _ if a.starts_with('-') => {}
            _ => filters.push(a.to_string()),
        }
        i += 1;
    }
    let selected = filters.is_empty()
        || filters.iter().any(|f| {
            if exact {
                name == f
            } else {
                name.contains(f.as_str())
            }
        });
    match (selected, list) {
        (false, _) => Mode::Skip,
        (true, true) => Mode::List,
        (true, false) => Mode::Run,
    }
}

/// The `main` of an exercise's test target: checks the learner's code (`learner`), or with the
/// `solutions` feature the reference solution (`learner`) and the shipped stub (`stub`).
pub fn main(name: &str, learner: Vec<Check>, stub: Option<Vec<Check>>) -> ! {
    match mode(name) {
        Mode::Skip => std::process::exit(0),
        Mode::List => {
            println!("{name}: test");
            std::process::exit(0)
        }
        Mode::Run => {}
    }
    let code = match stub {
        None => match ReportFile::from_env() {
            Some(file) => {
                let file = Arc::new(file);
                let report = run_into(&file, &learner);
                // What the learner's code printed without a newline is not lost at the exit.
                let _ = std::io::stdout().flush();
                file.write(&(file.record("report", &report.render(name)) + "end\n"));
                i32::from(report.state() != State::Done)
            }
            None => {
                let report = Report::run(&learner);
                print!("{}", report.render(name));
                i32::from(report.state() != State::Done)
            }
        },
        Some(stub) => {
            let report = Report::run(&learner);
            let solution_ok = report.state() == State::Done;
            print!("{}", report.render(&format!("{name} (reference solution)")));
            let stubbed = Report::run(&stub);
            let stub_rejected = stubbed.state() != State::Done;
            print!("{}", stubbed.render(&format!("{name} (shipped stub)")));
            println!(
                "{name}: the reference solution {}; the shipped stub {}",
                if solution_ok {
                    "passes every check"
                } else {
                    "FAILS"
                },
                if stub_rejected {
                    "is rejected, as it must be"
                } else {
                    "PASSES: a check that cannot fail"
                }
            );
            i32::from(!(solution_ok && stub_rejected))
        }
    };
    std::process::exit(code)
}

/// The `main` of an exercise's test target. `exercise_main!("NAME", e => { "label" => check, ... })`
/// runs each `check`, an expression that calls the exercise's functions through the module alias `e`:
/// `exercise` (the learner's file, or with `--features solutions` the reference solution) and, with
/// `solutions`, `stub` (the shipped stub) as well.
#[macro_export]
macro_rules! exercise_main {
    ($name:literal, $m:ident => { $( $label:literal => $check:expr ),+ $(,)? }) => {
        fn main() {
            fn checks() -> ::std::vec::Vec<$crate::harness::Check> {
                use self::exercise as $m;
                ::std::vec![$( $crate::harness::Check::new($label, move || $check) ),+]
            }
            #[cfg(feature = "solutions")]
            fn stub_checks() -> ::std::option::Option<::std::vec::Vec<$crate::harness::Check>> {
                use self::stub as $m;
                ::std::option::Option::Some(
                    ::std::vec![$( $crate::harness::Check::new($label, move || $check) ),+]
                )
            }
            #[cfg(not(feature = "solutions"))]
            fn stub_checks() -> ::std::option::Option<::std::vec::Vec<$crate::harness::Check>> {
                ::std::option::Option::None
            }
            $crate::harness::main($name, checks(), stub_checks())
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_report_file_logs_each_check_and_the_call_in_progress() {
        let _one_at_a_time = crate::check::PUBLISHING_TEST
            .lock()
            .unwrap_or_else(|e| e.into_inner());
        let path = std::env::temp_dir().join(format!("rtl-harness-log-{}", std::process::id()));
        let file = Arc::new(ReportFile {
            file: Mutex::new(File::create(&path).unwrap()),
        });
        let checks = vec![
            Check::new("quick", || Ok(())),
            Check::new("slow", || {
                crate::check::calling("f", &[("u", 0.5.into())], || {
                    std::thread::sleep(4 * CALL_EVERY);
                    Ok(())
                })
            }),
            Check::new("fails", || Err("saw 3\nexpected 4".into())),
        ];
        let report = run_into(&file, &checks);
        assert_eq!(report.passed(), 2);
        let text = std::fs::read_to_string(&path).unwrap();
        let _ = std::fs::remove_file(&path);
        let at = |line: &str| {
            text.find(line)
                .unwrap_or_else(|| panic!("no `{line}` in:\n{text}"))
        };
        assert!(text.starts_with("checks 3\nstart 1 quick\nresult 1\n|   ok    quick\n"));
        assert!(at("start 2 slow\n") < at("call f(u = 0.5)\n"), "{text}");
        assert!(at("call f(u = 0.5)\n") < at("result 2\n"), "{text}");
        assert!(
            text.ends_with(
                "result 3\n|   FAIL  fails\n|           saw 3\n|           expected 4\n"
            ),
            "{text}"
        );
    }

    #[test]
    fn states_and_the_summary_line() {
        let checks = vec![
            Check::new("passes", || Ok(())),
            Check::new("fails", || Err("saw 3, expected 4\nmore".into())),
            Check::new("todo", || todo!("write f")),
        ];
        let r = Report::run(&checks);
        assert_eq!(r.state(), State::Failing);
        let text = r.render("x");
        assert!(
            text.starts_with("x: failing: 1/3 checks passed: fails: saw 3, expected 4\n"),
            "{text}"
        );
        assert!(text.contains("todo!(\"write f\") reached"), "{text}");
        let todo = Report::run(&[Check::new("t", || todo!("write g"))]);
        assert_eq!(todo.state(), State::NotStarted);
        assert!(
            todo.render("y")
                .starts_with("y: not started: 0/1 checks passed\n")
        );
        let panics = Report::run(&[Check::new("p", || {
            let v: Vec<u8> = Vec::new();
            let i = v.len() + 2;
            Err(format!("{}", v[i]))
        })]);
        let text = panics.render("z");
        assert!(text.contains("your code panicked at"), "{text}");
        assert!(text.contains("index out of bounds"), "{text}");
        // A panic inside a recorded call names the input that caused it.
        let with_input = Report::run(&[Check::new("p", || {
            crate::check::calling("f", &[("u", 0.25.into())], || {
                let v: Vec<u8> = Vec::new();
                Err(format!("{}", v[v.len() + 3]))
            })
        })]);
        let text = with_input.render("w");
        assert!(
            text.contains("your code panicked in f(u = 0.25) at "),
            "{text}"
        );
    }
}
