//! Lists every exercise with its status: done, failing (and why) or not started.
//!
//! `cargo run -p rtl-exercises --example status` checks your code;
//! `cargo run -p rtl-exercises --example status --features solutions` checks the reference solutions.

use rtl_exercises::EXERCISES;
use std::panic::{self, AssertUnwindSafe};

/// The outcome of one exercise's checks.
enum Status {
    Done,
    Failing(String),
    /// A `todo!()` was reached; its message names the function still to write.
    NotStarted(String),
}

/// Runs `check`, turning a `todo!()` panic into "not started" and any other panic into a failure.
fn run(check: fn() -> Result<(), String>) -> Status {
    match panic::catch_unwind(AssertUnwindSafe(check)) {
        Ok(Ok(())) => Status::Done,
        Ok(Err(why)) => Status::Failing(why),
        Err(payload) => {
            let msg = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "a panic".to_string());
            if let Some(rest) = msg.strip_prefix("not yet implemented") {
                Status::NotStarted(rest.trim_start_matches(": ").to_string())
            } else {
                Status::Failing(format!("panicked: {msg}"))
            }
        }
    }
}

fn main() {
    // The checks' panics are reported in the table, not on stderr.
    panic::set_hook(Box::new(|_| {}));
    let build = if cfg!(feature = "solutions") {
        "reference solutions"
    } else {
        "your code"
    };
    println!("Exercises of rtl-exercises, checking {build}:\n");
    let width = EXERCISES.iter().map(|e| e.name.len()).max().unwrap_or(0);
    let cwidth = EXERCISES.iter().map(|e| e.chapter.len()).max().unwrap_or(0);
    println!(
        "{:<width$}  {:<cwidth$}  status",
        "exercise", "book chapter: section"
    );
    println!("{}", "-".repeat(width + cwidth + 20));
    let (mut done, mut failing, mut todo) = (0, 0, 0);
    for e in EXERCISES {
        let status = match run(e.check) {
            Status::Done => {
                done += 1;
                "done".to_string()
            }
            Status::NotStarted(what) => {
                todo += 1;
                match what.split(':').next() {
                    Some(f) if !f.is_empty() => format!("not started (todo!: {f})"),
                    _ => "not started".to_string(),
                }
            }
            Status::Failing(why) => {
                failing += 1;
                let first = why.lines().next().unwrap_or("");
                format!("FAILING: {first}")
            }
        };
        println!("{:<width$}  {:<cwidth$}  {status}", e.name, e.chapter);
    }
    println!(
        "\n{done} done, {failing} failing, {todo} not started, of {}.",
        EXERCISES.len()
    );
    if todo + failing > 0 {
        println!(
            "Each exercise is src/<exercise>.rs under crates/exercises; its doc comment states the task."
        );
        println!("Run one exercise's tests with `cargo test -p rtl-exercises <exercise>`.");
    }
}
