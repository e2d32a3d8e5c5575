//! `rtl exercises ...`: the learner's loop around the chapter exercises (list, check, hint, watch,
//! reset, solution). The code is `rtl-exercises-runner` (crates/exercises/runner), which
//! `cargo exercises ...` also runs without building the renderer.

use clap::Args;

#[derive(Args)]
#[command(disable_help_flag = true)]
pub struct ExercisesArgs {
    /// list | check NAME... | hint NAME (--level K) | watch (NAME) | reset NAME | solution NAME (--force)
    #[arg(trailing_var_arg = true, allow_hyphen_values = true, num_args = 0..)]
    args: Vec<String>,
}

/// Runs the runner on the arguments; returns its exit code. The commands it suggests are written
/// `rtl exercises ...`, as the learner started it.
pub fn run(args: ExercisesArgs) -> i32 {
    rtl_exercises_runner::run(&args.args, rtl_exercises_runner::Invocation::Rtl)
}
