//! Building and running the exercises' test targets through cargo.
//!
//! `cargo test --no-run -p rtl-exercises --test NAME ... --message-format=json` builds exactly the
//! artifacts `cargo test -p rtl-exercises` would (the same profile), and names each test program and
//! each compiler message's target. A target that does not compile is set aside and the others are
//! built again, so that one broken exercise never stops another. Building has no time limit (the
//! first build compiles the dependencies, minutes on a slow machine). Then the test programs run
//! under a time limit of their own ([`run_all`]), one after the other, except that one still running
//! after [`PATIENCE`] is left to run to its limit beside the next: so several exercises that loop
//! for ever cost one time limit together, not one each.

use crate::Error;
use crate::report::{self, Log, Printed};
use std::collections::BTreeMap;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// The workspace whose `crates/exercises` the runner works on.
#[derive(Clone, Debug)]
pub struct Workspace {
    pub root: PathBuf,
}

impl Workspace {
    /// `RTL_EXERCISES_ROOT` if set, else the nearest directory at or above the current one that holds
    /// `crates/exercises/info.toml`.
    pub fn find() -> Result<Self, Error> {
        if let Some(root) = std::env::var_os("RTL_EXERCISES_ROOT") {
            let ws = Self {
                root: PathBuf::from(root),
            };
            return if ws.info().is_file() {
                Ok(ws)
            } else {
                Err(Error::Failed(format!(
                    "RTL_EXERCISES_ROOT={}: no crates/exercises/info.toml there",
                    ws.root.display()
                )))
            };
        }
        let cwd = std::env::current_dir()
            .map_err(|e| Error::Failed(format!("current directory: {e}")))?;
        for dir in cwd.ancestors() {
            if dir.join("crates/exercises/info.toml").is_file() {
                return Ok(Self {
                    root: dir.to_path_buf(),
                });
            }
        }
        Err(Error::Failed(format!(
            "no crates/exercises/info.toml in {} or above it: run this inside the rtl workspace",
            cwd.display()
        )))
    }

    pub fn crate_dir(&self) -> PathBuf {
        self.root.join("crates/exercises")
    }
    pub fn info(&self) -> PathBuf {
        self.crate_dir().join("info.toml")
    }
    /// The file the learner edits.
    pub fn exercise_file(&self, name: &str) -> PathBuf {
        self.crate_dir()
            .join("exercises")
            .join(format!("{name}.rs"))
    }
    /// The reference solution.
    pub fn solution_file(&self, name: &str) -> PathBuf {
        self.crate_dir()
            .join("solutions")
            .join(format!("{name}.rs"))
    }
    /// The pristine copy of the learner's file, for `reset`.
    pub fn stub_file(&self, name: &str) -> PathBuf {
        self.crate_dir()
            .join("solutions/stubs")
            .join(format!("{name}.rs"))
    }
    /// `path` relative to the workspace root, for messages.
    pub fn show(&self, path: &Path) -> String {
        path.strip_prefix(&self.root)
            .unwrap_or(path)
            .display()
            .to_string()
    }
}

/// What building one exercise's test target gave.
#[derive(Clone, Debug)]
pub struct Built {
    /// The test program, or `None` when the target does not compile.
    pub exe: Option<PathBuf>,
    /// The compiler's errors and warnings for this target, as rendered for a terminal, with the
    /// learner's file named by its own path (see [`plain_paths`]).
    pub diagnostics: String,
    /// Of those, the warnings that point into the learner's file (`exercises/NAME.rs`).
    pub warnings: String,
}

/// Whether a compiler message's main place is in the learner's file of exercise `name`.
fn in_learners_file(msg: &serde_json::Value, name: &str) -> bool {
    let file = format!("exercises/{name}.rs");
    msg["message"]["spans"].as_array().is_some_and(|spans| {
        spans.iter().any(|s| {
            s["is_primary"] == true
                && s["file_name"]
                    .as_str()
                    .is_some_and(|f| plain_paths(f).ends_with(&file))
        })
    })
}

/// The compiler names the learner's file as the test target includes it,
/// `crates/exercises/tests/../exercises/ch02_x.rs`; this names it as the learner knows it,
/// `crates/exercises/exercises/ch02_x.rs`.
pub fn plain_paths(rendered: &str) -> String {
    rendered.replace("/tests/../", "/")
}

fn cargo() -> Command {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    Command::new(cargo)
}

/// Builds the test targets `names`. `progress` is shown cargo's "Compiling ..." lines.
pub fn build(
    ws: &Workspace,
    names: &[String],
    progress: &mut dyn FnMut(&str),
) -> Result<BTreeMap<String, Built>, Error> {
    let mut done: BTreeMap<String, Built> = BTreeMap::new();
    let mut pending: Vec<String> = names.to_vec();
    while !pending.is_empty() {
        let mut cmd = cargo();
        cmd.current_dir(&ws.root)
            .args([
                "test",
                "--no-run",
                "-p",
                "rtl-exercises",
                "--message-format=json",
                "--color",
                "never",
            ])
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        for n in &pending {
            cmd.args(["--test", n]);
        }
        let mut child = cmd
            .spawn()
            .map_err(|e| Error::Failed(format!("could not run cargo: {e}")))?;
        let stderr = child.stderr.take().expect("piped");
        let err_thread = std::thread::spawn(move || {
            let mut lines = Vec::new();
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                lines.push(line);
            }
            lines
        });
        let mut exes: BTreeMap<String, PathBuf> = BTreeMap::new();
        let mut diags: BTreeMap<String, String> = BTreeMap::new();
        let mut warnings: BTreeMap<String, String> = BTreeMap::new();
        let mut failed: Vec<String> = Vec::new();
        let mut lib_errors = String::new();
        let stdout = child.stdout.take().expect("piped");
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            let Ok(msg) = serde_json::from_str::<serde_json::Value>(&line) else {
                continue;
            };
            let target = msg["target"]["name"].as_str().unwrap_or("").to_string();
            let is_test = msg["target"]["kind"]
                .as_array()
                .is_some_and(|k| k.iter().any(|k| k == "test"));
            match msg["reason"].as_str() {
                Some("compiler-artifact") if is_test => {
                    if let Some(exe) = msg["executable"].as_str() {
                        exes.insert(target, PathBuf::from(exe));
                    }
                }
                Some("compiler-artifact") if msg["fresh"] == false => progress(&target),
                Some("compiler-message") => {
                    let level = msg["message"]["level"].as_str().unwrap_or("");
                    let rendered = plain_paths(msg["message"]["rendered"].as_str().unwrap_or(""));
                    if is_test {
                        if level == "error" && !failed.contains(&target) {
                            failed.push(target.clone());
                        }
                        if level == "warning" && in_learners_file(&msg, &target) {
                            warnings
                                .entry(target.clone())
                                .or_default()
                                .push_str(&rendered);
                        }
                        diags.entry(target).or_default().push_str(&rendered);
                    } else if level == "error" {
                        lib_errors.push_str(&rendered);
                    }
                }
                _ => {}
            }
        }
        let status = child
            .wait()
            .map_err(|e| Error::Failed(format!("cargo: {e}")))?;
        let stderr_lines = err_thread.join().unwrap_or_default();
        if !lib_errors.is_empty() {
            return Err(Error::Failed(format!(
                "the exercises' checkers (crates/exercises/src) do not compile:\n{lib_errors}"
            )));
        }
        let before = done.len();
        for n in &pending {
            if let Some(exe) = exes.get(n) {
                done.insert(
                    n.clone(),
                    Built {
                        exe: Some(exe.clone()),
                        diagnostics: diags.get(n).cloned().unwrap_or_default(),
                        warnings: warnings.get(n).cloned().unwrap_or_default(),
                    },
                );
            } else if failed.contains(n) {
                done.insert(
                    n.clone(),
                    Built {
                        exe: None,
                        diagnostics: diags.get(n).cloned().unwrap_or_default(),
                        warnings: warnings.get(n).cloned().unwrap_or_default(),
                    },
                );
            }
        }
        pending.retain(|n| !done.contains_key(n));
        if !pending.is_empty() && (done.len() == before || status.success()) {
            let tail: Vec<&String> = stderr_lines
                .iter()
                .filter(|l| l.starts_with("error"))
                .collect();
            return Err(Error::Failed(format!(
                "cargo could not build {}: {}",
                pending.join(", "),
                tail.iter()
                    .map(|s| s.as_str())
                    .collect::<Vec<_>>()
                    .join("; ")
            )));
        }
    }
    Ok(done)
}

/// What a test program gave: its report file as far as it got ([`Log`]) and what the learner's
/// code printed ([`Printed`]), once it exited or was stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum Ran {
    /// It exited: with `code`, or killed by a signal (`code` is `None`; `how` says which).
    Exited {
        code: Option<i32>,
        how: String,
        log: Log,
        printed: Printed,
    },
    /// Still running at the time limit, and stopped.
    TimedOut {
        limit: Duration,
        log: Log,
        printed: Printed,
    },
}

impl Ran {
    /// What the learner's code printed.
    pub fn printed(&self) -> &Printed {
        match self {
            Ran::Exited { printed, .. } | Ran::TimedOut { printed, .. } => printed,
        }
    }
}

/// How long a test program runs alone before the next one starts beside it. Every honest check
/// finishes well within it (the slowest exercise's checks take about 0.1 s here), so in the usual
/// case the programs run one at a time, and only one that runs long shares the processor.
pub const PATIENCE: Duration = Duration::from_secs(1);

/// How long a program runs before it is reported as still running ([`crate::still_running`]).
pub const NOTICE_AFTER: Duration = Duration::from_secs(2);

/// A test program running, with the thread that reads its output and the file of its report.
struct Running {
    index: usize,
    child: Child,
    started: Instant,
    printed: Option<JoinHandle<Printed>>,
    report: PathBuf,
}

impl Running {
    /// Starts `exe`, its report going to `report` ([`report::REPORT_ENV`]), its standard output and
    /// error into one pipe, so that what the learner's code prints is read in the order written.
    fn start(ws: &Workspace, index: usize, exe: &Path, report: PathBuf) -> Result<Self, Error> {
        let failed =
            |e: std::io::Error| Error::Failed(format!("could not run {}: {e}", exe.display()));
        let (reader, writer) = std::io::pipe().map_err(failed)?;
        let mut cmd = Command::new(exe);
        cmd.current_dir(&ws.root)
            .env(report::REPORT_ENV, &report)
            .stdin(Stdio::null())
            .stdout(writer.try_clone().map_err(failed)?)
            .stderr(writer);
        let child = cmd.spawn().map_err(failed)?;
        // The runner's copies of the pipe's writing end go with `cmd`: the reader sees the end of
        // the output when the program's copies close.
        drop(cmd);
        let printed = std::thread::spawn(move || Printed::read(reader));
        Ok(Self {
            index,
            child,
            started: Instant::now(),
            printed: Some(printed),
            report,
        })
    }

    /// What it printed, and its report file as far as it got (which is then removed).
    fn collect(&mut self) -> (Log, Printed) {
        let printed = self
            .printed
            .take()
            .and_then(|t| t.join().ok())
            .unwrap_or_default();
        let log = report::parse(&std::fs::read_to_string(&self.report).unwrap_or_default());
        let _ = std::fs::remove_file(&self.report);
        (log, printed)
    }

    /// What it gave, once it has exited with `status`.
    fn finish(&mut self, status: ExitStatus) -> Ran {
        let (log, printed) = self.collect();
        Ran::Exited {
            code: status.code(),
            how: status.to_string(),
            log,
            printed,
        }
    }

    /// Stops it at the time limit `limit`.
    fn stop(&mut self, limit: Duration) -> Ran {
        let _ = self.child.kill();
        let _ = self.child.wait();
        // The pipe closes with the process: the reader ends.
        let (log, printed) = self.collect();
        Ran::TimedOut {
            limit,
            log,
            printed,
        }
    }
}

impl Drop for Running {
    /// A program left behind (the runner gave up with an error) does not outlive the runner.
    fn drop(&mut self) {
        if self.printed.is_some() {
            self.stop(Duration::ZERO);
        }
    }
}

/// A directory of its own for the report files of one [`run_all`], removed with it.
struct ReportDir(PathBuf);

impl ReportDir {
    fn new() -> Result<Self, Error> {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.subsec_nanos());
        let dir =
            std::env::temp_dir().join(format!("rtl-exercises-{}-{nanos}", std::process::id()));
        std::fs::create_dir_all(&dir)
            .map_err(|e| Error::Failed(format!("{}: {e}", dir.display())))?;
        Ok(Self(dir))
    }
}

impl Drop for ReportDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Runs each test program of `programs` (name, executable) and returns what each gave, in order.
///
/// Each has `limit` to finish (then it is stopped: [`Ran::TimedOut`]). They start one after the
/// other; one still running after [`PATIENCE`] keeps running to its own limit while the next
/// starts, so `k` programs that loop for ever take about `limit + k PATIENCE`, not `k limit`.
/// `still_running` is told, at every look at them (every 10 ms), which programs have been running
/// for [`NOTICE_AFTER`] or more (none, most of the time) and for how long the oldest of them has
/// run; it decides what to say, and when ([`crate::still_running::StillRunning`]).
pub fn run_all(
    ws: &Workspace,
    programs: &[(String, PathBuf)],
    limit: Duration,
    still_running: &mut dyn FnMut(&[&str], Duration),
) -> Result<Vec<Ran>, Error> {
    let runs = run_all_until(ws, programs, limit, still_running, &mut || false)?;
    Ok(runs.expect("never stopped"))
}

/// [`run_all`], asking `stop` at every look at the programs (every 10 ms) whether to give up:
/// then every program still running is stopped and the result is `None` (`watch` gives up a check
/// when its file is saved again).
pub fn run_all_until(
    ws: &Workspace,
    programs: &[(String, PathBuf)],
    limit: Duration,
    still_running: &mut dyn FnMut(&[&str], Duration),
    stop: &mut dyn FnMut() -> bool,
) -> Result<Option<Vec<Ran>>, Error> {
    let mut results: Vec<Option<Ran>> = vec![None; programs.len()];
    let dir = ReportDir::new()?;
    let mut running: Vec<Running> = Vec::new();
    let mut next = 0;
    loop {
        let mut i = 0;
        while i < running.len() {
            let r = &mut running[i];
            let exited = r
                .child
                .try_wait()
                .map_err(|e| Error::Failed(format!("{}: {e}", programs[r.index].0)))?;
            if let Some(status) = exited {
                results[r.index] = Some(r.finish(status));
                running.swap_remove(i);
            } else if r.started.elapsed() > limit {
                results[r.index] = Some(r.stop(limit));
                running.swap_remove(i);
            } else {
                i += 1;
            }
        }
        if next < programs.len() && running.iter().all(|r| r.started.elapsed() >= PATIENCE) {
            let report = dir.0.join(format!("{next}.log"));
            running.push(Running::start(ws, next, &programs[next].1, report)?);
            next += 1;
            continue;
        }
        if next == programs.len() && running.is_empty() {
            break;
        }
        let long: Vec<&Running> = running
            .iter()
            .filter(|r| r.started.elapsed() >= NOTICE_AFTER)
            .collect();
        let mut names: Vec<&str> = long.iter().map(|r| programs[r.index].0.as_str()).collect();
        names.sort_unstable();
        let oldest = long
            .iter()
            .map(|r| r.started.elapsed())
            .max()
            .unwrap_or_default();
        still_running(&names, oldest);
        if stop() {
            // Dropping them stops them.
            return Ok(None);
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    Ok(Some(
        results
            .into_iter()
            .map(|r| r.expect("every program ran"))
            .collect(),
    ))
}
