//! `watch`: checks the current exercise whenever its file is saved, redraws the screen, and moves on
//! to the next exercise when it passes. Keys: `h` shows the next hint, `q` quits (on a terminal the
//! keys act at once; from a pipe, one per line).

use crate::Context;
use crate::info::Exercise;
use crate::status::Status;
use std::io::{IsTerminal, Read, Write};
use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, SystemTime};

/// Puts the terminal in non-canonical mode (keys without Enter) while it lives, through `stty`
/// (no terminal library needed); echo stays on, so an interrupted watch leaves a usable terminal.
struct KeysAtOnce {
    saved: Option<String>,
}

impl KeysAtOnce {
    fn start() -> Self {
        if !std::io::stdin().is_terminal() {
            return Self { saved: None };
        }
        let saved = Command::new("stty")
            .arg("-g")
            .stdin(Stdio::inherit())
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string());
        if saved.is_some() {
            let _ = Command::new("stty")
                .args(["-icanon", "min", "1"])
                .stdin(Stdio::inherit())
                .status();
        }
        Self { saved }
    }
}

impl Drop for KeysAtOnce {
    fn drop(&mut self) {
        if let Some(saved) = &self.saved {
            let _ = Command::new("stty")
                .arg(saved)
                .stdin(Stdio::inherit())
                .status();
        }
    }
}

/// Key presses, read by a thread from standard input.
fn keys() -> Receiver<u8> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut stdin = std::io::stdin();
        let mut b = [0u8; 1];
        while let Ok(1) = stdin.read(&mut b) {
            if tx.send(b[0]).is_err() {
                break;
            }
        }
    });
    rx
}

/// What identifies a save: modification time and length.
fn stamp(path: &Path) -> Option<(SystemTime, u64)> {
    let m = std::fs::metadata(path).ok()?;
    Some((m.modified().ok()?, m.len()))
}

fn redraw(ctx: &Context, e: &Exercise, s: &Status, done: usize, banner: &str, hint: usize) {
    let mut out = String::new();
    if std::io::stdout().is_terminal() {
        out += "\x1b[2J\x1b[H";
    } else {
        out += &format!("{}\n", "=".repeat(72));
    }
    if !banner.is_empty() {
        out += banner;
        out += "\n\n";
    }
    out += &format!(
        "rtl exercises watch: {done}/{} done; checking {} on every save of {}\n\n",
        ctx.exercises.len(),
        e.name,
        ctx.ws.show(&ctx.ws.exercise_file(&e.name))
    );
    out += &s.explain(&ctx.ws, e);
    if hint > 0 {
        out += &format!(
            "\nhint {hint} of {}:\n{}\n",
            e.hints.len(),
            e.hints[hint - 1]
        );
    }
    out += "\n[h] hint   [q] quit\n";
    let mut stdout = std::io::stdout().lock();
    let _ = stdout.write_all(out.as_bytes());
    let _ = stdout.flush();
}

/// Runs watch mode until `q` (or until every exercise is done).
pub fn watch(ctx: &Context) -> Result<i32, String> {
    let all: Vec<&Exercise> = ctx.exercises.iter().collect();
    let mut statuses = ctx.statuses(&all)?;
    let Some(mut current) = statuses.iter().position(|s| !s.is_done()) else {
        println!("every exercise is done: well done!");
        return Ok(0);
    };
    let _raw = KeysAtOnce::start();
    let mut keys = Some(keys());
    let mut banner = String::new();
    let mut status = statuses[current].clone();
    loop {
        let e = all[current];
        let file = ctx.ws.exercise_file(&e.name);
        let done = statuses.iter().filter(|s| s.is_done()).count();
        if status.is_done() {
            let next = (1..all.len())
                .map(|k| (current + k) % all.len())
                .find(|&j| !statuses[j].is_done());
            match next {
                Some(j) => {
                    banner = format!(
                        "{} passes! On to {} ({}).",
                        e.name, all[j].name, all[j].chapter
                    );
                    current = j;
                    status = ctx.statuses(&[all[j]])?.remove(0);
                    statuses[j] = status.clone();
                    continue;
                }
                None => {
                    redraw(ctx, e, &status, done, "", 0);
                    println!(
                        "\n{} passes, and every exercise is done: well done!",
                        e.name
                    );
                    return Ok(0);
                }
            }
        }
        let mut hint = 0;
        redraw(ctx, e, &status, done, &banner, hint);
        let before = stamp(&file);
        loop {
            let key = match &keys {
                Some(rx) => match rx.recv_timeout(Duration::from_millis(200)) {
                    Ok(k) => Some(k),
                    Err(RecvTimeoutError::Timeout) => None,
                    Err(RecvTimeoutError::Disconnected) => {
                        keys = None;
                        None
                    }
                },
                None => {
                    std::thread::sleep(Duration::from_millis(200));
                    None
                }
            };
            match key {
                Some(b'q' | b'Q') => {
                    println!();
                    return Ok(0);
                }
                Some(b'h' | b'H') => {
                    hint = hint % e.hints.len() + 1;
                    redraw(ctx, e, &status, done, &banner, hint);
                }
                _ => {}
            }
            if stamp(&file) != before {
                break;
            }
        }
        banner = format!("{} saved: checked again.", ctx.ws.show(&file));
        status = ctx.statuses(&[e])?.remove(0);
        statuses[current] = status.clone();
    }
}
