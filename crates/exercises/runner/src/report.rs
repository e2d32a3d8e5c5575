//! What a test program gives the runner: its report, through a file of its own, and what the
//! learner's code printed, apart from it.
//!
//! The runner names a fresh file in [`REPORT_ENV`]; the test program (`rtl_exercises::harness`)
//! logs each check's start and result there as it runs, the call of the learner's code in progress
//! (looked at every 100 ms), and at the end the whole report. A `println!` in the learner's code goes
//! to standard output, which the runner shows as the learner's own ([`Printed`]): it can neither
//! garble the report nor pass for one. The format is `rtl_exercises::harness::REPORT_FORMAT`:
//!
//! ```text
//! rtl-exercises report 1
//! checks N
//! start K LABEL
//! call TEXT      (or `call` alone: no call in progress)
//! result K
//! | TEXT         (check K's lines of the report)
//! report
//! | TEXT         (the whole report)
//! end
//! ```

use std::collections::VecDeque;
use std::io::Read;

/// The environment variable that names the report file (`rtl_exercises::harness::REPORT_ENV`).
pub const REPORT_ENV: &str = "RTL_EXERCISES_REPORT";

/// The first line of a report file.
pub const FORMAT: &str = "rtl-exercises report 1";

/// What a report file says, as far as it got.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Log {
    /// How many checks the exercise has, once the program said so.
    pub checks: Option<usize>,
    /// The lines of the report of each check that ended, in order.
    pub finished: Vec<String>,
    /// The check that had started and not ended: its number (from 1) and label.
    pub running: Option<(usize, String)>,
    /// The call of the learner's code in progress in that check, when last looked at.
    pub call: Option<String>,
    /// The whole report, once every check ended (the lines between `report` and `end`).
    pub report: Option<String>,
}

/// Reads a report file's text. A last line without its newline (the program was stopped while
/// writing it) is left out; lines not of the format are ignored.
pub fn parse(text: &str) -> Log {
    let mut log = Log::default();
    let complete = match text.rfind('\n') {
        Some(i) => &text[..=i],
        None => "",
    };
    let mut lines = complete.lines();
    if lines.next() != Some(FORMAT) {
        return log;
    }
    // Where `| TEXT` lines go: check K's result, or the report.
    enum Into {
        Nothing,
        Result,
        Report(String),
    }
    let mut into = Into::Nothing;
    for line in lines {
        if let Some(text) = line.strip_prefix("| ").or((line == "|").then_some("")) {
            match &mut into {
                Into::Result => {
                    if let Some(last) = log.finished.last_mut() {
                        *last += text;
                        last.push('\n');
                    }
                }
                Into::Report(r) => {
                    r.push_str(text);
                    r.push('\n');
                }
                Into::Nothing => {}
            }
            continue;
        }
        let (word, rest) = line.split_once(' ').unwrap_or((line, ""));
        // A line of the format ends the block of `| TEXT` lines before it.
        let block = std::mem::replace(&mut into, Into::Nothing);
        match word {
            "checks" => log.checks = rest.parse().ok(),
            "start" => {
                let (k, label) = rest.split_once(' ').unwrap_or((rest, ""));
                log.running = k.parse().ok().map(|k| (k, label.to_string()));
                log.call = None;
            }
            "call" => log.call = (!rest.is_empty()).then(|| rest.to_string()),
            "result" => {
                log.running = None;
                log.call = None;
                log.finished.push(String::new());
                into = Into::Result;
            }
            "report" => into = Into::Report(String::new()),
            "end" => {
                if let Into::Report(r) = block {
                    log.report = Some(r);
                }
            }
            _ => {}
        }
    }
    log
}

/// How many lines of the learner's output are shown from its start, and from its end.
pub const HEAD_LINES: usize = 20;
pub const TAIL_LINES: usize = 5;
/// The longest line shown (in characters); a longer one is cut.
pub const LINE_WIDTH: usize = 200;

/// What the learner's code printed, standard output and error together in the order written:
/// the first [`HEAD_LINES`] lines, the last [`TAIL_LINES`] of the rest, and how many there were.
/// Only these are kept, however much it prints.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Printed {
    pub head: Vec<String>,
    pub tail: VecDeque<String>,
    /// Every line printed, the ones not kept included.
    pub lines: usize,
}

impl Printed {
    /// Everything `from` gives until it ends, keeping what is shown.
    pub fn read(mut from: impl Read) -> Self {
        let mut printed = Printed::default();
        let mut line: Vec<u8> = Vec::new();
        let mut chunk = [0u8; 8192];
        loop {
            let n = match from.read(&mut chunk) {
                Ok(0) | Err(_) => break,
                Ok(n) => n,
            };
            for &b in &chunk[..n] {
                if b == b'\n' {
                    printed.push(&line);
                    line.clear();
                } else if line.len() < 4 * LINE_WIDTH {
                    line.push(b);
                }
            }
        }
        if !line.is_empty() {
            printed.push(&line);
        }
        printed
    }

    fn push(&mut self, bytes: &[u8]) {
        let text = String::from_utf8_lossy(bytes);
        let text = crate::status::cut(text.trim_end_matches('\r'), LINE_WIDTH);
        self.lines += 1;
        if self.head.len() < HEAD_LINES {
            self.head.push(text);
        } else {
            if self.tail.len() == TAIL_LINES {
                self.tail.pop_front();
            }
            self.tail.push_back(text);
        }
    }

    pub fn is_empty(&self) -> bool {
        self.lines == 0
    }

    /// The last line printed, if any.
    pub fn last(&self) -> Option<&str> {
        self.tail.back().or(self.head.last()).map(String::as_str)
    }

    /// The lines kept, each as `  | TEXT`, with a line saying how many were left out between.
    pub fn show(&self) -> String {
        let mut out = String::new();
        for l in &self.head {
            out += &format!("  | {l}\n");
        }
        let left_out = self.lines - self.head.len() - self.tail.len();
        if left_out > 0 {
            out += &format!("  | ... ({left_out} more lines) ...\n");
        }
        for l in &self.tail {
            out += &format!("  | {l}\n");
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_whole_log_gives_the_report_and_a_cut_one_the_check_and_call_running() {
        let whole = "rtl-exercises report 1\nchecks 2\nstart 1 first\nresult 1\n|   ok    first\n\
                     start 2 second\ncall f(u = 0.5)\nresult 2\n|   FAIL  second\n|           why\n\
                     report\n| x: failing: 1/2 checks passed: second: why\n|   ok    first\n\
                     |   FAIL  second\n|           why\nend\n";
        let log = parse(whole);
        assert_eq!(log.checks, Some(2));
        assert_eq!(
            log.finished,
            ["  ok    first\n", "  FAIL  second\n          why\n"]
        );
        assert_eq!((log.running, log.call), (None, None));
        assert_eq!(
            log.report.as_deref(),
            Some(
                "x: failing: 1/2 checks passed: second: why\n  ok    first\n  FAIL  second\n          why\n"
            )
        );
        // Stopped in check 2, in a call: no report, the check and the call that were running.
        let cut = &whole[..whole.find("result 2").unwrap()];
        let log = parse(cut);
        assert_eq!(log.report, None);
        assert_eq!(log.finished, ["  ok    first\n"]);
        assert_eq!(log.running, Some((2, "second".to_string())));
        assert_eq!(log.call.as_deref(), Some("f(u = 0.5)"));
        // The call ended (`call` alone), and a line cut in the middle is left out.
        let log = parse(&format!("{cut}call\ncall g(u = 0"));
        assert_eq!(log.call, None);
        // A report without its `end` is no report; a file of another format says nothing.
        let log = parse(&whole.replace("end\n", ""));
        assert_eq!(log.report, None);
        assert_eq!(parse("x: done: 2/2 checks passed\n"), Log::default());
    }

    #[test]
    fn printed_output_keeps_its_first_and_last_lines_and_counts_the_rest() {
        let text: String = (1..=100).map(|i| format!("line {i}\n")).collect();
        let p = Printed::read(text.as_bytes());
        assert_eq!(p.lines, 100);
        let shown = p.show();
        assert!(shown.starts_with("  | line 1\n  | line 2\n"), "{shown}");
        assert!(
            shown.contains("  | line 20\n  | ... (75 more lines) ...\n  | line 96\n"),
            "{shown}"
        );
        assert!(shown.ends_with("  | line 100\n"), "{shown}");
        assert_eq!(p.last(), Some("line 100"));
        // A last line without a newline, and a very long line, cut.
        let p = Printed::read(format!("{}\nno newline", "x".repeat(5000)).as_bytes());
        assert_eq!(p.lines, 2);
        assert_eq!(p.head[0].chars().count(), LINE_WIDTH);
        assert!(p.head[0].ends_with("..."));
        assert_eq!(p.last(), Some("no newline"));
        assert!(Printed::read(&b""[..]).is_empty());
    }
}
