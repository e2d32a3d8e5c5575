//! Building and running the exercises' test targets through cargo.
//!
//! `cargo test --no-run -p rtl-exercises --test NAME ... --message-format=json` builds exactly the
//! artifacts `cargo test -p rtl-exercises` would (the same profile), and names each test program and
//! each compiler message's target. A target that does not compile is set aside and the others are
//! built again, so that one broken exercise never stops another. Each test program is then run on
//! its own, with a time limit.

use std::collections::BTreeMap;
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The workspace whose `crates/exercises` the runner works on.
#[derive(Clone, Debug)]
pub struct Workspace {
    pub root: PathBuf,
}

impl Workspace {
    /// `RTL_EXERCISES_ROOT` if set, else the nearest directory at or above the current one that holds
    /// `crates/exercises/info.toml`.
    pub fn find() -> Result<Self, String> {
        if let Some(root) = std::env::var_os("RTL_EXERCISES_ROOT") {
            let ws = Self {
                root: PathBuf::from(root),
            };
            return if ws.info().is_file() {
                Ok(ws)
            } else {
                Err(format!(
                    "RTL_EXERCISES_ROOT={}: no crates/exercises/info.toml there",
                    ws.root.display()
                ))
            };
        }
        let cwd = std::env::current_dir().map_err(|e| format!("current directory: {e}"))?;
        for dir in cwd.ancestors() {
            if dir.join("crates/exercises/info.toml").is_file() {
                return Ok(Self {
                    root: dir.to_path_buf(),
                });
            }
        }
        Err(format!(
            "no crates/exercises/info.toml in {} or above it: run this inside the rtl workspace",
            cwd.display()
        ))
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
    /// The compiler's errors and warnings for this target, as rendered for a terminal.
    pub diagnostics: String,
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
) -> Result<BTreeMap<String, Built>, String> {
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
            .map_err(|e| format!("could not run cargo: {e}"))?;
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
                    let rendered = msg["message"]["rendered"].as_str().unwrap_or("");
                    if is_test {
                        if level == "error" && !failed.contains(&target) {
                            failed.push(target.clone());
                        }
                        diags.entry(target).or_default().push_str(rendered);
                    } else if level == "error" {
                        lib_errors.push_str(rendered);
                    }
                }
                _ => {}
            }
        }
        let status = child.wait().map_err(|e| format!("cargo: {e}"))?;
        let stderr_lines = err_thread.join().unwrap_or_default();
        if !lib_errors.is_empty() {
            return Err(format!(
                "the exercises' checkers (crates/exercises/src) do not compile:\n{lib_errors}"
            ));
        }
        let before = done.len();
        for n in &pending {
            if let Some(exe) = exes.get(n) {
                done.insert(
                    n.clone(),
                    Built {
                        exe: Some(exe.clone()),
                        diagnostics: diags.get(n).cloned().unwrap_or_default(),
                    },
                );
            } else if failed.contains(n) {
                done.insert(
                    n.clone(),
                    Built {
                        exe: None,
                        diagnostics: diags.get(n).cloned().unwrap_or_default(),
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
            return Err(format!(
                "cargo could not build {}: {}",
                pending.join(", "),
                tail.iter()
                    .map(|s| s.as_str())
                    .collect::<Vec<_>>()
                    .join("; ")
            ));
        }
    }
    Ok(done)
}

/// What a test program printed, or why it gave nothing.
#[derive(Clone, Debug)]
pub enum Ran {
    /// Its standard output and whether it exited 0.
    Output {
        stdout: String,
        passed: bool,
    },
    TimedOut(Duration),
    /// It died without a report (a stack overflow, an abort): its standard error.
    Crashed(String),
}

/// Runs the test program `exe` with a time limit.
pub fn run(ws: &Workspace, exe: &Path, limit: Duration) -> Result<Ran, String> {
    let mut child = Command::new(exe)
        .current_dir(&ws.root)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("could not run {}: {e}", exe.display()))?;
    let mut out = child.stdout.take().expect("piped");
    let mut err = child.stderr.take().expect("piped");
    let out_thread = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = out.read_to_string(&mut s);
        s
    });
    let err_thread = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = err.read_to_string(&mut s);
        s
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            break status;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return Ok(Ran::TimedOut(limit));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let stdout = out_thread.join().unwrap_or_default();
    let stderr = err_thread.join().unwrap_or_default();
    if status.code().is_none() || stdout.trim().is_empty() {
        return Ok(Ran::Crashed(if stderr.trim().is_empty() {
            format!("exited with {status} and no report")
        } else {
            stderr.trim().to_string()
        }));
    }
    Ok(Ran::Output {
        stdout,
        passed: status.success(),
    })
}
