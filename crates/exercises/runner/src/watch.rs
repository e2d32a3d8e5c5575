//! `watch [NAME]`: checks the current exercise (the first not done, or NAME) whenever its file is
//! saved, redraws the screen, and moves on to the next exercise when it passes. Keys: `h` shows the
//! next hint, `q` quits (on a terminal the keys act at once; from a pipe, one per line).
//!
//! A save is never lost: the file's stamp is read *before* each check, and a save made while the
//! check ran (the stamp differs after it) checks again at once ([`check_until_unchanged`]). While a
//! check runs, a line "checking NAME ..." says so; the result replaces it.

use crate::info::Exercise;
use crate::status::Checked;
use crate::{Context, Error, say, sayln};
use std::hash::{DefaultHasher, Hash, Hasher};
use std::io::{IsTerminal, Read};
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

/// What identifies a save: modification time, length, and a hash of the contents (so that two saves
/// within the file system's time resolution are still told apart).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Stamp(Option<(SystemTime, u64, u64)>);

/// The stamp of `path` now (`Stamp(None)` if it cannot be read).
pub fn stamp(path: &Path) -> Stamp {
    let read = || {
        let m = std::fs::metadata(path).ok()?;
        let mut h = DefaultHasher::new();
        std::fs::read(path).ok()?.hash(&mut h);
        Some((m.modified().ok()?, m.len(), h.finish()))
    };
    Stamp(read())
}

/// Runs `check` until the file did not change while it ran: reads `stamp` *before* the check and
/// again after it; if they differ (the learner saved during the check), checks again at once.
/// Returns the last result and the stamp it is for: the next save is a change from that stamp, so
/// none is lost. `check` is given the round, 0 for the first check, 1 for the first re-check, ...
pub fn check_until_unchanged<S: PartialEq, T, E>(
    mut stamp: impl FnMut() -> S,
    mut check: impl FnMut(usize) -> Result<T, E>,
) -> Result<(T, S), E> {
    let mut round = 0;
    loop {
        let before = stamp();
        let result = check(round)?;
        if stamp() == before {
            return Ok((result, before));
        }
        round += 1;
    }
}

/// Checks `e` as [`check_until_unchanged`] does, saying "checking NAME ..." while it runs.
fn check_now(ctx: &Context, e: &Exercise) -> Result<(Checked, Stamp), Error> {
    let file = ctx.ws.exercise_file(&e.name);
    check_until_unchanged(
        || stamp(&file),
        |round| {
            if round == 0 {
                sayln!("\nchecking {} ...", e.name)?;
            } else {
                sayln!(
                    "{} changed during the check: checking {} again ...",
                    ctx.ws.show(&file),
                    e.name
                )?;
            }
            Ok(ctx.check_all(&[e])?.remove(0))
        },
    )
}

fn redraw(
    ctx: &Context,
    e: &Exercise,
    s: &Checked,
    done: usize,
    banner: &str,
    hint: usize,
) -> Result<(), Error> {
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
        "{} watch: {done}/{} done; checking {} on every save of {}\n\n",
        ctx.cmd(),
        ctx.exercises.len(),
        e.name,
        ctx.ws.show(&ctx.ws.exercise_file(&e.name))
    );
    out += &s.explain(&ctx.ws, e, ctx.cmd());
    if hint > 0 {
        out += &format!(
            "\nhint {hint} of {}:\n{}\n",
            e.hints.len(),
            e.hints[hint - 1]
        );
    }
    out += "\n[h] hint   [q] quit\n";
    say!("{out}")
}

/// Runs watch mode on `start` (or the first exercise not done) until `q`, or until every exercise
/// is done.
pub fn watch(ctx: &Context, start: Option<&str>) -> Result<i32, Error> {
    let all: Vec<&Exercise> = ctx.exercises.iter().collect();
    let file = |e: &Exercise| ctx.ws.exercise_file(&e.name);
    sayln!("checking every exercise, to see where you are ...")?;
    // The stamps before the check: a save during it is seen as a change below.
    let stamps: Vec<Stamp> = all.iter().map(|e| stamp(&file(e))).collect();
    let mut checked_all = ctx.check_all(&all)?;
    let mut statuses: Vec<_> = checked_all.iter().map(|c| c.status.clone()).collect();
    let mut current = match start {
        Some(name) => all
            .iter()
            .position(|e| e.name == name)
            .ok_or_else(|| Error::Failed(format!("no exercise `{name}`")))?,
        None => match statuses.iter().position(|s| !s.is_done()) {
            Some(i) => i,
            None => {
                sayln!("every exercise is done: well done!")?;
                return Ok(0);
            }
        },
    };
    let _raw = KeysAtOnce::start();
    let mut keys = Some(keys());
    let mut banner = String::new();
    let mut status = checked_all.swap_remove(current);
    let mut checked = stamps[current];
    loop {
        let e = all[current];
        let done = statuses.iter().filter(|s| s.is_done()).count();
        if status.status.is_done() {
            let next = (1..all.len())
                .map(|k| (current + k) % all.len())
                .find(|&j| !statuses[j].is_done());
            match next {
                Some(j) => {
                    banner = format!(
                        "{} passes! On to {} ({}).",
                        e.name,
                        all[j].name,
                        all[j].label()
                    );
                    current = j;
                    (status, checked) = check_now(ctx, all[j])?;
                    statuses[j] = status.status.clone();
                    continue;
                }
                None => {
                    redraw(ctx, e, &status, done, "", 0)?;
                    sayln!(
                        "\n{} passes, and every exercise is done: well done!",
                        e.name
                    )?;
                    return Ok(0);
                }
            }
        }
        let mut hint = 0;
        redraw(ctx, e, &status, done, &banner, hint)?;
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
                    sayln!()?;
                    return Ok(0);
                }
                Some(b'h' | b'H') => {
                    hint = hint % e.hints.len() + 1;
                    redraw(ctx, e, &status, done, &banner, hint)?;
                }
                _ => {}
            }
            if stamp(&file(e)) != checked {
                break;
            }
        }
        banner = format!("{} saved: checked again.", ctx.ws.show(&file(e)));
        (status, checked) = check_now(ctx, e)?;
        statuses[current] = status.status.clone();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    #[test]
    fn a_save_during_the_check_is_checked_again_at_once() {
        // The file's stamp is a counter; the first check "saves" (bumps it) while it runs.
        let saves = Cell::new(0);
        let checks = Cell::new(0);
        let (result, stamp) = check_until_unchanged(
            || saves.get(),
            |round| {
                checks.set(checks.get() + 1);
                if round == 0 {
                    saves.set(saves.get() + 1);
                }
                Ok::<_, ()>(format!("check of save {}", saves.get()))
            },
        )
        .unwrap();
        assert_eq!(checks.get(), 2, "checked again after the save");
        assert_eq!(result, "check of save 1");
        // The stamp returned is the one the last check saw: the next save differs from it.
        assert_eq!(stamp, 1);
        // Without a save during it, one check.
        checks.set(0);
        let (_, stamp) = check_until_unchanged(
            || saves.get(),
            |_| {
                checks.set(checks.get() + 1);
                Ok::<_, ()>(())
            },
        )
        .unwrap();
        assert_eq!((checks.get(), stamp), (1, 1));
    }

    #[test]
    fn stamps_tell_two_saves_of_the_same_length_apart() {
        let dir = std::env::temp_dir().join(format!("rtl-watch-stamp-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("x.rs");
        std::fs::write(&f, "fn a() {}\n").unwrap();
        let first = stamp(&f);
        std::fs::write(&f, "fn b() {}\n").unwrap();
        assert_ne!(stamp(&f), first);
        assert_eq!(stamp(&dir.join("missing.rs")), Stamp(None));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
