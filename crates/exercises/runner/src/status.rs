//! The state of one exercise, from its test program's report (see `rtl_exercises::harness`).

use crate::Error;
use crate::cargo::{Ran, Workspace};
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

/// The state of `e` from what its test program gave.
pub fn from_run(e: &Exercise, ran: Ran) -> Result<Status, Error> {
    match ran {
        Ran::TimedOut(d) => Ok(Status::TimedOut(d)),
        Ran::Crashed(why) => Ok(Status::Crashed(why)),
        Ran::Output { stdout, .. } => parse(&e.name, &stdout),
    }
}

/// Parses a report: `NAME: STATE: K/M checks passed[: WHY]`, then the checks' lines.
pub fn parse(name: &str, report: &str) -> Result<Status, Error> {
    let (first, details) = report.split_once('\n').unwrap_or((report, ""));
    let details = details.to_string();
    let bad = || {
        Error::Failed(format!(
            "{name}: unreadable report from its test program: {first}"
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
            Status::TimedOut(_) => "timed out".to_string(),
            Status::Crashed(_) => "crashed".to_string(),
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
            Status::TimedOut(d) => Some(format!(
                "the checks did not finish in {}: does the code loop for ever?",
                seconds(*d)
            )),
            Status::Crashed(why) => Some(why.lines().last().unwrap_or("no report").to_string()),
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
            Status::TimedOut(d) => format!("timed out after {}", seconds(*d)),
            Status::Crashed(_) => format!("crashed: {}", self.why().unwrap_or_default()),
            _ => self.word(),
        }
    }

    /// The full account for `check`: the state, the learner's function, what each check saw.
    /// `cmd` is how the learner runs the runner ("cargo exercises" or "rtl exercises").
    pub fn explain(&self, ws: &Workspace, e: &Exercise, cmd: &str) -> String {
        let file = ws.exercise_file(&e.name);
        let mut out = format!("{} ({}): {}\n", e.name, e.label(), self.one_line());
        match self {
            Status::Done { details, .. } => {
                out += details;
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
            Status::TimedOut(d) => {
                out += &format!(
                    "\nthe checks did not finish in {}: does your code loop for ever? \
                     (RTL_EXERCISES_TIMEOUT=SECONDS sets the limit)\n",
                    seconds(*d)
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
            "\nthe book explains it in {}; {what}? `{cmd} hint {}` (one level at a time: \
             --level 2, ...)\n",
            e.section_words(),
            e.name
        );
        out
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
