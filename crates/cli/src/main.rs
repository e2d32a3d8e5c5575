//! `rtl`: render the books' scenes, study what accuracy costs in time, merge partial renders, and
//! watch it all converge live in the lab, compare speed with other renderers, and work through the
//! chapter exercises.

mod bench_cmd;
mod calendar;
mod csv;
mod exercises_cmd;
mod lab;
mod merge_cmd;
mod plot;
mod progressive;
mod render_cmd;
mod study;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "rtl",
    version,
    about = "Ray Tracing: The Rest of Your Life, in Rust"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a built-in scene (see `--list`) or a scene file.
    Render(render_cmd::RenderArgs),
    /// Measure accuracy against time and write a CSV and plots.
    Study(study::StudyArgs),
    /// Merge partial renders (disjoint sample ranges of one scene) into one image.
    Merge(merge_cmd::MergeArgs),
    /// Compare rtl with the book's C++ and Mitsuba 3 on this machine (`rtl bench compare`), measure issue 16's three speed targets (`rtl bench targets`), or two renders' noise (`rtl bench noise`).
    Bench(bench_cmd::BenchArgs),
    /// A local web page: watch estimators, samplers and the Cornell box converge, switch strategies live.
    Lab(lab::LabArgs),
    /// The chapter exercises: list, check NAME, hint NAME, watch, reset NAME, solution NAME.
    Exercises(exercises_cmd::ExercisesArgs),
}

fn main() {
    stop_quietly_when_stdout_is_gone();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render(args) => render_cmd::run(args),
        Command::Study(args) => study::run(args),
        Command::Merge(args) => merge_cmd::run(args),
        Command::Bench(args) => bench_cmd::run(args),
        Command::Lab(args) => lab::run(args),
        Command::Exercises(args) => std::process::exit(exercises_cmd::run(args)),
    };
    if let Err(err) = result {
        eprintln!("error: {}", message(&err));
        std::process::exit(1);
    }
}

/// The exit code of a program whose standard output was closed under it (`rtl render --explain
/// cornell | head -1`): what a shell reports for one killed by SIGPIPE, 128 + 13.
const EXIT_BROKEN_PIPE: i32 = 141;

/// `println!` panics when standard output cannot be written (a pipe whose reader has gone, a full
/// disk, `> /dev/full`), with a backtrace: Rust ignores SIGPIPE. This hook turns that one panic into
/// what a command-line tool does instead: a closed pipe ends the program quietly (exit 141, as
/// SIGPIPE would), any other failure is an error naming standard output (exit 1). Every other
/// panic goes to the default hook.
fn stop_quietly_when_stdout_is_gone() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let payload = info.payload();
        let text = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("");
        if let Some(why) = text.strip_prefix("failed printing to stdout: ") {
            if why.starts_with("Broken pipe") {
                std::process::exit(EXIT_BROKEN_PIPE);
            }
            eprintln!("error: cannot write to standard output: {why}");
            std::process::exit(1);
        }
        default(info)
    }));
}

/// The error and its causes joined by `": "`, as anyhow's `{:#}` joins them, but without a cause
/// whose text its error already ends with (our errors quote their I/O error in their own message
/// and keep it as their source too, which `{:#}` printed twice).
fn message(err: &anyhow::Error) -> String {
    let mut out = String::new();
    for cause in err.chain() {
        let text = cause.to_string();
        if out.is_empty() {
            out = text;
        } else if !out.ends_with(&text) {
            out.push_str(": ");
            out.push_str(&text);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::message;

    #[test]
    fn a_cause_already_quoted_is_not_printed_twice() {
        #[derive(Debug, thiserror::Error)]
        #[error("cannot read a.ck: {source}")]
        struct Quoting {
            source: std::io::Error,
        }
        let io = || std::io::Error::from(std::io::ErrorKind::NotFound);
        let err = anyhow::Error::new(Quoting { source: io() });
        assert_eq!(message(&err), format!("cannot read a.ck: {}", io()));
        // a cause not quoted is still printed, after its context
        let err = anyhow::Error::new(io()).context("reading a.ck");
        assert_eq!(message(&err), format!("reading a.ck: {}", io()));
    }
}
