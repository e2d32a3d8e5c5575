//! `watch [NAME]`: checks the current exercise (the first not done, or NAME) whenever its file is
//! saved, redraws the screen, and moves on to the next exercise when a save makes it pass. An
//! exercise that already passes when `watch NAME` starts is watched all the same ([`next`]). Keys:
//! `h` shows the next hint, `q` quits (on a terminal the keys act at once; from a pipe, one per
//! line).
//!
//! A save is never lost: the file's stamp is read *before* each check, and a save made while the
//! check runs gives that check up (a loop for ever need not reach the time limit) and checks again
//! at once ([`check_until_unchanged`]). While a check runs, a line "checking NAME ..." says so; the
//! result replaces it.

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
/// gives the check a question, "has the file changed since?", which it asks while it runs; a check
/// that gives up on a change (`None`), or a change seen after it, checks again at once. Returns the
/// last result and the stamp it is for: the next save is a change from that stamp, so none is
/// lost. `check` is given the round, 0 for the first check, 1 for the first re-check, ...
pub fn check_until_unchanged<S: PartialEq, T, E>(
    mut stamp: impl FnMut() -> S,
    mut check: impl FnMut(usize, &mut dyn FnMut() -> bool) -> Result<Option<T>, E>,
) -> Result<(T, S), E> {
    let mut round = 0;
    loop {
        let before = stamp();
        let result = check(round, &mut || stamp() != before)?;
        if let Some(result) = result
            && stamp() == before
        {
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
        |round, changed| {
            if round == 0 {
                sayln!("\nchecking {} ...", e.name)?;
            } else {
                sayln!(
                    "{} changed during the check: checking {} again ...",
                    ctx.ws.show(&file),
                    e.name
                )?;
            }
            Ok(ctx.check_all_until(&[e], changed)?.map(|mut c| c.remove(0)))
        },
    )
}

/// What `watch` does after a check of exercise `current`: the states of all exercises, with
/// `current`'s new one, and whether `current` was done before this check.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Next {
    /// Keep watching `current`: it does not pass, or it passed already (`watch NAME` on an
    /// exercise done before keeps watching it).
    Stay,
    /// It passes now, after a save: on to this exercise, the next one not done.
    MoveTo(usize),
    /// It passes now and every exercise is done.
    AllDone,
}

/// See [`Next`].
pub fn next(done: &[bool], current: usize, was_done: bool) -> Next {
    if !done[current] || was_done {
        return Next::Stay;
    }
    match (1..done.len())
        .map(|k| (current + k) % done.len())
        .find(|&j| !done[j])
    {
        Some(j) => Next::MoveTo(j),
        None => Next::AllDone,
    }
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

/// Runs watch mode on `start` (or the first exercise not done) until `q`, or until a save makes
/// the last exercise not done pass.
pub fn watch(ctx: &Context, start: Option<&str>) -> Result<i32, Error> {
    let all: Vec<&Exercise> = ctx.exercises.iter().collect();
    let file = |e: &Exercise| ctx.ws.exercise_file(&e.name);
    sayln!("checking every exercise, to see where you are ...")?;
    // The stamps before the check: a save during it is seen as a change below.
    let stamps: Vec<Stamp> = all.iter().map(|e| stamp(&file(e))).collect();
    let mut first = ctx.check_all(&all)?;
    let mut done: Vec<bool> = first.iter().map(|c| c.status.is_done()).collect();
    let mut banner = String::new();
    let mut current = match start {
        Some(name) => {
            let i = all
                .iter()
                .position(|e| e.name == name)
                .ok_or_else(|| Error::Failed(format!("no exercise `{name}`")))?;
            if done[i] {
                banner = format!("{name} passes already; watch keeps checking it on every save.");
            }
            i
        }
        None => match done.iter().position(|d| !d) {
            Some(i) => i,
            None => {
                sayln!("every exercise is done: well done!")?;
                return Ok(0);
            }
        },
    };
    let _raw = KeysAtOnce::start();
    let mut keys = Some(keys());
    let mut status = first.swap_remove(current);
    let mut checked = stamps[current];
    loop {
        let e = all[current];
        let mut hint = 0;
        let n_done = done.iter().filter(|&&d| d).count();
        redraw(ctx, e, &status, n_done, &banner, hint)?;
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
                    redraw(ctx, e, &status, n_done, &banner, hint)?;
                }
                _ => {}
            }
            if stamp(&file(e)) != checked {
                break;
            }
        }
        banner = format!("{} saved: checked again.", ctx.ws.show(&file(e)));
        (status, checked) = check_now(ctx, e)?;
        let was_done = done[current];
        done[current] = status.status.is_done();
        // On to the next exercise not done, as often as a fresh check finds one passing already.
        let mut next_step = next(&done, current, was_done);
        while let Next::MoveTo(j) = next_step {
            let from = all[current];
            banner = format!(
                "{} passes! On to {} ({}).",
                from.name,
                all[j].name,
                all[j].label()
            );
            current = j;
            (status, checked) = check_now(ctx, all[j])?;
            done[j] = status.status.is_done();
            next_step = next(&done, j, false);
        }
        if next_step == Next::AllDone {
            let e = all[current];
            redraw(ctx, e, &status, done.len(), "", 0)?;
            sayln!(
                "\n{} passes, and every exercise is done: well done!",
                e.name
            )?;
            return Ok(0);
        }
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
            |round, _| {
                checks.set(checks.get() + 1);
                if round == 0 {
                    saves.set(saves.get() + 1);
                }
                Ok::<_, ()>(Some(format!("check of save {}", saves.get())))
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
            |_, _| {
                checks.set(checks.get() + 1);
                Ok::<_, ()>(Some(()))
            },
        )
        .unwrap();
        assert_eq!((checks.get(), stamp), (1, 1));
    }

    #[test]
    fn a_check_that_sees_a_save_gives_up_and_the_new_version_is_checked() {
        // The first check runs until it sees the save (as a check that loops for ever would, had
        // it no time limit), and gives up; the second finishes.
        let saves = Cell::new(0);
        let rounds = Cell::new(0);
        let (result, stamp) = check_until_unchanged(
            || saves.get(),
            |round, changed| {
                rounds.set(round + 1);
                if round == 0 {
                    for look in 0.. {
                        if look == 3 {
                            saves.set(1);
                        }
                        if changed() {
                            return Ok::<_, ()>(None);
                        }
                    }
                }
                assert!(!changed(), "nothing changed since round {round} began");
                Ok(Some(format!("check of save {}", saves.get())))
            },
        )
        .unwrap();
        assert_eq!(
            (result.as_str(), stamp, rounds.get()),
            ("check of save 1", 1, 2)
        );
    }

    #[test]
    fn watch_moves_on_only_when_a_save_makes_the_exercise_pass() {
        // Failing: stay.
        assert_eq!(next(&[true, false, false], 1, false), Next::Stay);
        // Passing already when `watch NAME` started, or before this save: stay.
        assert_eq!(next(&[true, false, false], 0, true), Next::Stay);
        // A save made it pass: the next one not done, round the end of the list.
        assert_eq!(next(&[false, true, false], 1, false), Next::MoveTo(2));
        assert_eq!(next(&[false, false, true], 2, false), Next::MoveTo(0));
        assert_eq!(next(&[true, true, true], 1, false), Next::AllDone);
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
