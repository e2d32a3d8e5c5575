//! The state of one exercise, from its test program's report (see `rtl_exercises::harness`).

use crate::cargo::{self, Built, Ran, Workspace};
use crate::info::{Exercise, Kind};
use std::time::Duration;

/// Where an exercise stands.
#[derive(Clone, Debug, PartialEq)]
pub enum Status {
    Done {
        total: usize,
        details: String,
    },
    /// The checks ran; `why` is the first failure, in one line.
    Failing {
        passed: usize,
        total: usize,
        why: String,
        details: String,
    },
    NotStarted {
        total: usize,
        details: String,
    },
    /// The learner's file does not compile: the compiler's messages.
    DoesNotCompile(String),
    TimedOut(Duration),
    /// The test program died without a report.
    Crashed(String),
}

/// How long one exercise's checks may run (`RTL_EXERCISES_TIMEOUT` seconds, default 120).
pub fn time_limit() -> Duration {
    let secs = std::env::var("RTL_EXERCISES_TIMEOUT")
        .ok()
        .and_then(|s| s.parse::<u64>().ok())
        .unwrap_or(120);
    Duration::from_secs(secs)
}

/// Runs the built exercise `e` and reads its report.
pub fn of(ws: &Workspace, e: &Exercise, built: &Built) -> Result<Status, String> {
    let Some(exe) = &built.exe else {
        return Ok(Status::DoesNotCompile(built.diagnostics.clone()));
    };
    match cargo::run(ws, exe, time_limit())? {
        Ran::TimedOut(d) => Ok(Status::TimedOut(d)),
        Ran::Crashed(why) => Ok(Status::Crashed(why)),
        Ran::Output { stdout, .. } => parse(&e.name, &stdout),
    }
}

/// Parses a report: `NAME: STATE: K/M checks passed[: WHY]`, then the checks' lines.
pub fn parse(name: &str, report: &str) -> Result<Status, String> {
    let (first, details) = report.split_once('\n').unwrap_or((report, ""));
    let details = details.to_string();
    let bad = || format!("{name}: unreadable report from its test program: {first}");
    let rest = first
        .strip_prefix(name)
        .and_then(|r| r.strip_prefix(": "))
        .ok_or_else(bad)?;
    let (state, rest) = rest.split_once(": ").ok_or_else(bad)?;
    let (counts, why) = match rest.split_once(" checks passed") {
        Some((c, w)) => (c, w.strip_prefix(": ").unwrap_or("").to_string()),
        None => return Err(bad()),
    };
    let (p, t) = counts.split_once('/').ok_or_else(bad)?;
    let passed: usize = p.parse().map_err(|_| bad())?;
    let total: usize = t.parse().map_err(|_| bad())?;
    Ok(match state {
        "done" => Status::Done { total, details },
        "not started" => Status::NotStarted { total, details },
        "failing" => Status::Failing {
            passed,
            total,
            why,
            details,
        },
        _ => return Err(bad()),
    })
}

impl Status {
    pub fn is_done(&self) -> bool {
        matches!(self, Status::Done { .. })
    }

    /// (checks passed, checks) when the checks ran.
    pub fn counts(&self) -> Option<(usize, usize)> {
        match self {
            Status::Done { total, .. } => Some((*total, *total)),
            Status::Failing { passed, total, .. } => Some((*passed, *total)),
            Status::NotStarted { total, .. } => Some((0, *total)),
            _ => None,
        }
    }

    /// The state in one line, for `list`.
    pub fn one_line(&self) -> String {
        match self {
            Status::Done { .. } => "done".to_string(),
            Status::NotStarted { .. } => "not started".to_string(),
            Status::Failing {
                passed, total, why, ..
            } => {
                let mut why = why.clone();
                if why.chars().count() > 110 {
                    why = why.chars().take(107).collect::<String>() + "...";
                }
                format!("failing ({passed}/{total} checks): {why}")
            }
            Status::DoesNotCompile(diags) => {
                let first = diags
                    .lines()
                    .find(|l| l.starts_with("error"))
                    .unwrap_or("error");
                format!("does not compile: {first}")
            }
            Status::TimedOut(d) => format!("timed out after {} s", d.as_secs()),
            Status::Crashed(why) => {
                format!("crashed: {}", why.lines().last().unwrap_or("no report"))
            }
        }
    }

    /// The full account for `check`: the state, the learner's function, what each check saw.
    pub fn explain(&self, ws: &Workspace, e: &Exercise) -> String {
        let file = ws.exercise_file(&e.name);
        let mut out = format!("{} ({}): {}\n", e.name, e.chapter, self.one_line());
        match self {
            Status::Done { details, .. } => {
                out += details;
                out += &format!(
                    "\n{} passes. `rtl exercises solution {}` shows the reference solution, to compare.\n",
                    e.name, e.name
                );
                return out;
            }
            Status::DoesNotCompile(diags) => {
                out += &format!("\n{} does not compile:\n\n{diags}", ws.show(&file));
                return out;
            }
            Status::TimedOut(d) => {
                out += &format!(
                    "\nthe checks did not finish in {} s: does your code loop for ever? \
                     (RTL_EXERCISES_TIMEOUT=secs sets the limit)\n",
                    d.as_secs()
                );
            }
            Status::Crashed(why) => out += &format!("\nthe checks' program died:\n{why}\n"),
            Status::Failing { details, .. } | Status::NotStarted { details, .. } => {
                out += &format!("\nyour code ({}):\n", ws.show(&file));
                out += &learners_function(&file);
                out += "\nwhat the checks saw:\n";
                out += details;
            }
        }
        let what = if e.kind == Kind::Bug {
            "find the bug"
        } else {
            "stuck"
        };
        out += &format!(
            "\n{what}? `rtl exercises hint {}` (one level at a time: --level 2, ...)\n",
            e.name
        );
        out
    }
}

/// The learner's code between `// ANCHOR: exercise` and `// ANCHOR_END: exercise` (the whole file
/// if the markers are gone), without doc comments, with line numbers.
pub fn learners_function(file: &std::path::Path) -> String {
    let Ok(text) = std::fs::read_to_string(file) else {
        return format!("  ({} cannot be read)\n", file.display());
    };
    let lines: Vec<&str> = text.lines().collect();
    let start = lines.iter().position(|l| l.contains("ANCHOR: exercise"));
    let end = lines
        .iter()
        .position(|l| l.contains("ANCHOR_END: exercise"));
    let (a, b) = match (start, end) {
        (Some(a), Some(b)) if a < b => (a + 1, b),
        _ => (0, lines.len()),
    };
    let mut out = String::new();
    let mut shown = 0;
    for (i, l) in lines.iter().enumerate().take(b).skip(a) {
        if l.trim_start().starts_with("///") {
            continue;
        }
        if shown == 60 {
            out += "      | ...\n";
            break;
        }
        out += &format!("{:>5} | {l}\n", i + 1);
        shown += 1;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_three_states_and_refuses_a_garbled_report() {
        let f = parse(
            "ch02_x",
            "ch02_x: failing: 1/2 checks passed: value: 40 standard errors off\n  ok  a\n",
        )
        .unwrap();
        assert_eq!(f.counts(), Some((1, 2)));
        assert!(
            f.one_line().contains("40 standard errors"),
            "{}",
            f.one_line()
        );
        assert!(
            parse("ch02_x", "ch02_x: done: 2/2 checks passed\n")
                .unwrap()
                .is_done()
        );
        assert_eq!(
            parse("ch02_x", "ch02_x: not started: 0/3 checks passed\n")
                .unwrap()
                .counts(),
            Some((0, 3))
        );
        assert!(parse("ch02_x", "thread main panicked").is_err());
        assert!(parse("ch02_x", "ch02_y: done: 2/2 checks passed").is_err());
    }
}
