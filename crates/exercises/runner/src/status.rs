//! The state of one exercise, from what its test program gave (see `rtl_exercises::harness` and
//! [`crate::report`]).

use crate::Error;
use crate::cargo::{Ran, Workspace};
use crate::info::{Exercise, Kind};
use crate::report::{Log, Printed};
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
    /// The checks were stopped at the time limit; `log` says how far they got.
    TimedOut {
        limit: Duration,
        log: Log,
    },
    /// The test program ended without a report: why, in one line, and how far the checks got.
    Crashed {
        why: String,
        log: Log,
    },
}

/// An exercise's state, with what came beside it: what the learner's code printed and the
/// compiler's warnings about the learner's file.
#[derive(Clone, Debug, PartialEq)]
pub struct Checked {
    pub status: Status,
    pub printed: Printed,
    /// The compiler's warnings that point into the learner's file, as rendered.
    pub warnings: String,
}

/// The default time limit of one exercise's checks: 10 s. Every honest check finishes well under
/// a second in the test profile (the slowest exercise, with its stub checked too, takes about 0.1 s
/// on this project's 2-core machine), so 10 s leaves a wide margin for a loaded machine, while a
/// loop for ever in a learner's code is reported after 10 s rather than minutes.
/// `RTL_EXERCISES_TIMEOUT` (seconds) changes it.
pub const DEFAULT_TIME_LIMIT: Duration = Duration::from_secs(10);

/// How long one exercise's checks may run: `RTL_EXERCISES_TIMEOUT` seconds (a positive number,
/// e.g. 30 or 2.5), else [`DEFAULT_TIME_LIMIT`]. Building has no time limit.
pub fn time_limit() -> Result<Duration, Error> {
    parse_time_limit(std::env::var("RTL_EXERCISES_TIMEOUT").ok().as_deref())
}

/// The time limit that `RTL_EXERCISES_TIMEOUT=value` sets (`None`: unset, the default).
pub fn parse_time_limit(value: Option<&str>) -> Result<Duration, Error> {
    let Some(value) = value else {
        return Ok(DEFAULT_TIME_LIMIT);
    };
    match value.trim().parse::<f64>() {
        Ok(secs) if secs > 0.0 && secs.is_finite() && secs < 1e9 => {
            Ok(Duration::from_secs_f64(secs))
        }
        _ => Err(Error::Failed(format!(
            "RTL_EXERCISES_TIMEOUT={value}: expected a number of seconds greater than 0, e.g. 30 \
             (unset, the checks of an exercise may run {} s)",
            DEFAULT_TIME_LIMIT.as_secs()
        ))),
    }
}

/// The state of `e` from what its test program gave. Never an error: a test program that ended
/// without its report, or with one the runner cannot read, is [`Status::Crashed`], and the other
/// exercises are checked and listed as usual.
pub fn from_run(e: &Exercise, ran: &Ran) -> Status {
    match ran {
        Ran::TimedOut { limit, log, .. } => Status::TimedOut {
            limit: *limit,
            log: log.clone(),
        },
        Ran::Exited {
            code,
            how,
            log,
            printed,
        } => {
            let crashed = |why: String| Status::Crashed {
                why,
                log: log.clone(),
            };
            let Some(report) = &log.report else {
                return crashed(match code {
                    None => printed
                        .last()
                        .map_or_else(|| format!("killed ({how})"), str::to_string),
                    Some(c) => format!(
                        "it exited with code {c} before the checks ended, without its report: \
                         does your code call std::process::exit?"
                    ),
                });
            };
            let status = match parse(&e.name, report) {
                Ok(s) => s,
                Err(err) => return crashed(err.to_string()),
            };
            // The program exits 0 exactly when every check passed, after its report.
            let want = i32::from(!status.is_done());
            if *code != Some(want) {
                return crashed(format!(
                    "the checks' program ended ({how}) after a report that says {}: \
                     the report is not taken",
                    status.word()
                ));
            }
            status
        }
    }
}

/// Parses a report: `NAME: STATE: K/M checks passed[: WHY]`, then the checks' lines.
pub fn parse(name: &str, report: &str) -> Result<Status, Error> {
    let (first, details) = report.split_once('\n').unwrap_or((report, ""));
    let details = details.to_string();
    let bad = || {
        Error::Failed(format!(
            "{name}: unreadable report from its test program: {}",
            cut(first, 80)
        ))
    };
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

/// Cuts `text` to at most `width` characters, with "..." where it was cut.
pub fn cut(text: &str, width: usize) -> String {
    if text.chars().count() <= width {
        text.to_string()
    } else {
        text.chars()
            .take(width.saturating_sub(3))
            .collect::<String>()
            + "..."
    }
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

    /// The state in a few words, for `list`'s column: "done", "failing 1/3", "not started",
    /// "does not compile", "timed out", "crashed".
    pub fn word(&self) -> String {
        match self {
            Status::Done { .. } => "done".to_string(),
            Status::NotStarted { .. } => "not started".to_string(),
            Status::Failing { passed, total, .. } => format!("failing {passed}/{total}"),
            Status::DoesNotCompile(_) => "does not compile".to_string(),
            Status::TimedOut { .. } => "timed out".to_string(),
            Status::Crashed { .. } => "crashed".to_string(),
        }
    }

    /// Why it is not done, in one line (none when done or not started).
    pub fn why(&self) -> Option<String> {
        match self {
            Status::Done { .. } | Status::NotStarted { .. } => None,
            Status::Failing { why, .. } => Some(why.clone()),
            Status::DoesNotCompile(diags) => Some(
                diags
                    .lines()
                    .find(|l| l.starts_with("error"))
                    .unwrap_or("error")
                    .to_string(),
            ),
            Status::TimedOut { limit, log } => Some(format!(
                "the checks did not finish in {}{}: does the code loop for ever?",
                seconds(*limit),
                running_where(log, false)
            )),
            Status::Crashed { why, .. } => Some(why.clone()),
        }
    }

    /// The state in one line: "failing (1/3 checks): WHY".
    pub fn one_line(&self) -> String {
        match self {
            Status::Failing {
                passed, total, why, ..
            } => format!("failing ({passed}/{total} checks): {}", cut(why, 110)),
            Status::DoesNotCompile(_) => {
                format!("does not compile: {}", self.why().unwrap_or_default())
            }
            Status::TimedOut { limit, log } => match (&log.running, log.checks) {
                (Some((k, _)), Some(n)) => {
                    format!("timed out after {} in check {k} of {n}", seconds(*limit))
                }
                _ => format!("timed out after {}", seconds(*limit)),
            },
            Status::Crashed { why, .. } => format!("crashed: {}", cut(why, 110)),
            _ => self.word(),
        }
    }
}

/// Where the checks were when they stopped: " in check 2 of 3 (\"LABEL\"), in the call
/// f(u = 0.5)", or "" before the first check; the label only when `label`.
fn running_where(log: &Log, label: bool) -> String {
    let Some((k, name)) = &log.running else {
        return String::new();
    };
    let mut out = format!(" in check {k}");
    if let Some(n) = log.checks {
        out += &format!(" of {n}");
    }
    if label {
        out += &format!(" (\"{name}\")");
    }
    if let Some(call) = &log.call {
        out += &format!(", in the call {call}");
    }
    out
}

/// How far the checks got before they stopped: the lines of each check that ended, and the one
/// that was running (`stopped` says how it ended), then those not reached.
fn checks_so_far(log: &Log, stopped: &str) -> String {
    let mut out = String::new();
    for f in &log.finished {
        out += f;
    }
    if let Some((k, label)) = &log.running {
        out += &format!("  ....  {label}\n          {stopped}\n");
        if let Some(n) = log.checks.filter(|n| n > k) {
            out += &format!(
                "  (and {} check{} not reached)\n",
                n - k,
                if n - k == 1 { "" } else { "s" }
            );
        }
    }
    out
}

impl Checked {
    /// The full account for `check`: the state, the learner's function, what each check saw,
    /// what the learner's code printed and the compiler's warnings about it.
    /// `cmd` is how the learner runs the runner ("cargo exercises" or "rtl exercises").
    pub fn explain(&self, ws: &Workspace, e: &Exercise, cmd: &str) -> String {
        let file = ws.exercise_file(&e.name);
        let mut out = format!("{} ({}): {}\n", e.name, e.label(), self.status.one_line());
        let yours = |out: &mut String| {
            *out += &format!("\nyour code ({}):\n", ws.show(&file));
            *out += &learners_function(&file);
        };
        match &self.status {
            Status::Done { details, .. } => {
                out += details;
                out += &self.printed_text();
                out += &format!(
                    "\n{} passes. `{cmd} solution {}` shows the reference solution, to compare.\n",
                    e.name, e.name
                );
                return out;
            }
            Status::DoesNotCompile(diags) => {
                out += &format!("\n{} does not compile:\n\n{diags}", ws.show(&file));
                return out;
            }
            Status::TimedOut { limit, log } => {
                out += &format!(
                    "\nthe checks did not finish in {}{}: does your code loop for ever? \
                     (RTL_EXERCISES_TIMEOUT=SECONDS sets the limit)\n",
                    seconds(*limit),
                    running_where(log, true)
                );
                yours(&mut out);
                out += "\nwhat the checks saw before they were stopped:\n";
                out += &checks_so_far(log, &format!("still running after {}", seconds(*limit)));
            }
            Status::Crashed { why, log } => {
                out += &format!(
                    "\nthe checks' program ended without its report{}: {why}\n",
                    running_where(log, true)
                );
                yours(&mut out);
                if !log.finished.is_empty() || log.running.is_some() {
                    out += "\nwhat the checks saw before:\n";
                    out += &checks_so_far(log, "running when the program ended");
                }
            }
            Status::Failing { details, .. } | Status::NotStarted { details, .. } => {
                yours(&mut out);
                out += "\nwhat the checks saw:\n";
                out += details;
            }
        }
        out += &self.printed_text();
        if !self.warnings.is_empty() {
            out += &format!(
                "\nthe compiler warns about {}:\n\n{}\n",
                ws.show(&file),
                self.warnings.trim_end()
            );
        }
        let what = if e.kind == Kind::Bug {
            "find the bug"
        } else {
            "stuck"
        };
        out += &format!(
            "\nthe book explains it in {}; {what}? `{cmd} hint {}` (one level at a time: \
             --level 2, ...)\n",
            e.section_words(),
            e.name
        );
        out
    }

    /// "your code printed (N lines):" and the lines kept, or nothing.
    fn printed_text(&self) -> String {
        if self.printed.is_empty() {
            return String::new();
        }
        let n = self.printed.lines;
        format!(
            "\nyour code printed ({n} line{}):\n{}",
            if n == 1 { "" } else { "s" },
            self.printed.show()
        )
    }
}

/// A duration in seconds as a reader would write it: "10 s", "2.5 s".
pub fn seconds(d: Duration) -> String {
    let s = d.as_secs_f64();
    if s.fract() == 0.0 {
        format!("{s} s")
    } else {
        format!("{s:.1} s")
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
        assert_eq!(f.word(), "failing 1/2");
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

    #[test]
    fn the_time_limit_is_10_s_unless_set_and_a_bad_value_is_named() {
        assert_eq!(parse_time_limit(None).unwrap(), Duration::from_secs(10));
        assert_eq!(
            parse_time_limit(Some("2.5")).unwrap(),
            Duration::from_millis(2500)
        );
        for bad in ["abc", "0", "-3", "", "inf", "NaN"] {
            let err = parse_time_limit(Some(bad)).unwrap_err().to_string();
            assert!(
                err.starts_with(&format!("RTL_EXERCISES_TIMEOUT={bad}: expected a number")),
                "{err}"
            );
        }
        assert_eq!(seconds(Duration::from_secs(10)), "10 s");
        assert_eq!(seconds(Duration::from_millis(2500)), "2.5 s");
    }
}
