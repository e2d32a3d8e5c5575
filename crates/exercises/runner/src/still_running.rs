//! Saying that checks are still running, the way cargo does: on a terminal, one line rewritten in
//! place as the seconds pass ("still running: ch02_estimate_pi (3 s of the 10 s limit)") and wiped
//! when the checks end, so that the report starts on a clean line; into a pipe or a log (CI, tests,
//! `2> file`), where a rewritten line would pile up, plain lines: one when a check has run
//! [`NOTICE_AFTER`](crate::cargo::NOTICE_AFTER), then one every [`PLAIN_EVERY`], with how to
//! change the limit.

use crate::status;
use std::io::Write;
use std::time::{Duration, Instant};

/// How often a plain line (not on a terminal) repeats that checks are still running.
pub const PLAIN_EVERY: Duration = Duration::from_secs(10);

/// The widest line written on a terminal: it must not wrap, or a carriage return would go back to
/// the start of its last row only.
pub const TERMINAL_WIDTH: usize = 79;

/// The notices of one run of checks, written to `out` (the runner's standard error).
pub struct StillRunning<W: Write> {
    out: W,
    /// Whether `out` is a terminal: rewrite one line, or write plain lines.
    terminal: bool,
    limit: Duration,
    /// On a terminal: the line shown now, if any.
    shown: Option<String>,
    /// In plain lines: the checks named by the last line, and when it was written.
    named: Vec<String>,
    last: Option<Instant>,
}

impl<W: Write> StillRunning<W> {
    /// Notices to `out`, a terminal or not, of checks with a time limit `limit`.
    pub fn new(out: W, terminal: bool, limit: Duration) -> Self {
        Self {
            out,
            terminal,
            limit,
            shown: None,
            named: Vec::new(),
            last: None,
        }
    }

    /// Told at time `now` that `names` have been running for
    /// [`NOTICE_AFTER`](crate::cargo::NOTICE_AFTER) or more (the
    /// longest of them for `oldest`): says so if it is time to. No names ends a line in place.
    pub fn update(&mut self, names: &[&str], oldest: Duration, now: Instant) {
        if names.is_empty() {
            self.finish();
            return;
        }
        let limit = status::seconds(self.limit);
        let ran = status::seconds(Duration::from_secs(oldest.as_secs()));
        let list = names.join(", ");
        if self.terminal {
            let line = status::cut(
                &format!("still running: {list} ({ran} of the {limit} limit)"),
                TERMINAL_WIDTH,
            );
            if self.shown.as_ref() != Some(&line) {
                let wider = self.shown.as_ref().map_or(0, |s| s.chars().count());
                let pad = wider.saturating_sub(line.chars().count());
                let _ = write!(self.out, "\r{line}{}", " ".repeat(pad));
                let _ = self.out.flush();
                self.shown = Some(line);
            }
            return;
        }
        let new_name = names.iter().any(|n| !self.named.iter().any(|m| m == n));
        let due = self
            .last
            .is_none_or(|t| now.duration_since(t) >= PLAIN_EVERY);
        if new_name || due {
            let _ = writeln!(
                self.out,
                "still running: {list} ({ran} of the {limit} limit; RTL_EXERCISES_TIMEOUT=SECONDS \
                 changes it)"
            );
            let _ = self.out.flush();
            self.named = names.iter().map(|n| n.to_string()).collect();
            self.last = Some(now);
        }
    }

    /// The checks have ended: on a terminal, the line shown is wiped and the cursor left at its
    /// start, for the report.
    pub fn finish(&mut self) {
        if let Some(line) = self.shown.take() {
            let _ = write!(self.out, "\r{}\r", " ".repeat(line.chars().count()));
            let _ = self.out.flush();
        }
    }

    /// What was written.
    #[cfg(test)]
    fn into_inner(mut self) -> W
    where
        W: Default,
    {
        self.finish();
        std::mem::take(&mut self.out)
    }
}

impl<W: Write> Drop for StillRunning<W> {
    /// A run that ended early (an error) leaves no line behind either.
    fn drop(&mut self) {
        self.finish();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cargo::NOTICE_AFTER;

    const LIMIT: Duration = Duration::from_secs(30);

    /// Feeds `reporter` what `run_all` would say every 0.5 s from 0 to `until` seconds: `names(t)`
    /// are running long at t seconds, the oldest since 0.
    fn drive(
        reporter: &mut StillRunning<Vec<u8>>,
        until: f64,
        names: impl Fn(f64) -> Vec<&'static str>,
    ) {
        let start = Instant::now();
        let mut t = 0.0;
        while t <= until {
            let long = if t >= NOTICE_AFTER.as_secs_f64() {
                names(t)
            } else {
                Vec::new()
            };
            let at = start + Duration::from_secs_f64(t);
            reporter.update(&long, Duration::from_secs_f64(t), at);
            t += 0.5;
        }
    }

    #[test]
    fn in_a_pipe_a_line_when_a_check_runs_long_then_one_every_10_s() {
        let mut r = StillRunning::new(Vec::new(), false, LIMIT);
        // ch02_a runs long from 2 s; ch03_b joins it at 5 s; both until 27 s.
        drive(&mut r, 27.0, |t| {
            if t >= 5.0 {
                vec!["ch02_a", "ch03_b"]
            } else {
                vec!["ch02_a"]
            }
        });
        r.update(&[], Duration::ZERO, Instant::now());
        let text = String::from_utf8(r.into_inner()).unwrap();
        let hint = "of the 30 s limit; RTL_EXERCISES_TIMEOUT=SECONDS changes it)";
        assert_eq!(
            text,
            format!(
                "still running: ch02_a (2 s {hint}\n\
                 still running: ch02_a, ch03_b (5 s {hint}\n\
                 still running: ch02_a, ch03_b (15 s {hint}\n\
                 still running: ch02_a, ch03_b (25 s {hint}\n"
            )
        );
        assert!(!text.contains('\r'), "{text:?}");
    }

    #[test]
    fn in_a_pipe_nothing_is_said_of_checks_that_end_in_time() {
        let mut r = StillRunning::new(Vec::new(), false, LIMIT);
        drive(&mut r, 10.0, |_| Vec::new());
        assert_eq!(r.into_inner(), b"");
    }

    #[test]
    fn on_a_terminal_one_line_is_rewritten_each_second_and_wiped_at_the_end() {
        let mut r = StillRunning::new(Vec::new(), true, LIMIT);
        drive(&mut r, 4.0, |_| vec!["ch02_a"]);
        r.finish();
        let text = String::from_utf8(r.into_inner()).unwrap();
        let line = |s: u32| format!("still running: ch02_a ({s} s of the 30 s limit)");
        let wipe = format!("\r{}\r", " ".repeat(line(4).len()));
        assert_eq!(
            text,
            format!("\r{}\r{}\r{}{wipe}", line(2), line(3), line(4)),
            "{text:?}"
        );
        assert!(!text.contains('\n'), "{text:?}");
        // A shorter line covers what is left of a longer one.
        let mut r = StillRunning::new(Vec::new(), true, LIMIT);
        let now = Instant::now();
        r.update(&["ch02_a", "ch03_b"], Duration::from_secs(3), now);
        r.update(&["ch03_b"], Duration::from_secs(3), now);
        let text = String::from_utf8(r.into_inner()).unwrap();
        assert!(
            text.contains(&format!(
                "\rstill running: ch03_b (3 s of the 30 s limit){}",
                " ".repeat("ch02_a, ".len())
            )),
            "{text:?}"
        );
    }

    #[test]
    fn a_terminal_line_never_wraps() {
        let mut r = StillRunning::new(Vec::new(), true, LIMIT);
        let names = [
            "ch12_bug_light_list_pdf",
            "ch12_bug_cone_cos_theta_max",
            "ch12_nan_guard",
        ];
        r.update(&names, Duration::from_secs(3), Instant::now());
        let text = String::from_utf8(r.into_inner()).unwrap();
        for line in text.split('\r') {
            assert!(line.chars().count() <= TERMINAL_WIDTH, "{line:?}");
        }
    }
}
