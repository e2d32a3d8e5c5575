//! Writing to the terminal without panicking: `cargo exercises list | head -3` closes standard output
//! after three lines, and `println!` would then panic ("failed printing to stdout: Broken pipe",
//! exit 101). Every line the runner prints goes through [`out`], which turns a closed standard
//! output into [`Error::StdoutClosed`], and the command stops quietly (exit 0, see [`crate::run`]).
//! Messages on standard error go through [`err`], which ignores a closed standard error.

use crate::Error;
use std::fmt;
use std::io::{ErrorKind, Write};

/// Writes `args` to standard output and flushes it (a progress line without a newline shows at
/// once). A closed pipe is [`Error::StdoutClosed`]; any other failure is named.
pub fn out(args: fmt::Arguments) -> Result<(), Error> {
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_fmt(args)
        .and_then(|()| stdout.flush())
        .map_err(|e| {
            if e.kind() == ErrorKind::BrokenPipe {
                Error::StdoutClosed
            } else {
                Error::Failed(format!("could not write to standard output: {e}"))
            }
        })
}

/// Writes `args` to standard error; a closed standard error is ignored (there is nowhere left to
/// say anything).
pub fn err(args: fmt::Arguments) {
    let mut stderr = std::io::stderr().lock();
    let _ = stderr.write_fmt(args).and_then(|()| stderr.flush());
}

/// `say!(...)`: `print!` that returns [`Error::StdoutClosed`] instead of panicking.
#[macro_export]
macro_rules! say {
    ($($t:tt)*) => { $crate::out::out(format_args!($($t)*)) };
}

/// `sayln!(...)`: `println!` that returns [`Error::StdoutClosed`] instead of panicking.
#[macro_export]
macro_rules! sayln {
    () => { $crate::out::out(format_args!("\n")) };
    ($($t:tt)*) => { $crate::out::out(format_args!("{}\n", format_args!($($t)*))) };
}

/// `warn!(...)`: `eprintln!` that never panics.
#[macro_export]
macro_rules! warn {
    ($($t:tt)*) => { $crate::out::err(format_args!("{}\n", format_args!($($t)*))) };
}
