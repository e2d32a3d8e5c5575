//! `exercises`: the learner's loop around the chapter exercises. `cargo exercises list` runs it
//! (the alias in `.cargo/config.toml`); `rtl exercises list` runs the same code from the `rtl` binary.
//! Every command it suggests is written as `cargo exercises ...`, which works in any clone.

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    std::process::exit(rtl_exercises_runner::run(
        &args,
        rtl_exercises_runner::Invocation::Cargo,
    ));
}
