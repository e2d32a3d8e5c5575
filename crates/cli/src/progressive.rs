//! The pass loop of a long render: whole passes of samples per pixel, sized to take about a second,
//! until the samples asked for are done, the time budget is spent, or Ctrl-C; checkpoints between
//! passes.
//!
//! A pass adds samples `[k0, k1)` to every pixel, each pixel in the order of `k`, so however the samples
//! are cut into passes (and however often the render is stopped and resumed) the sums are those of one
//! pass over `[start, end)`. A pass that is stopped half-way is thrown away: the render keeps whole
//! passes only.

use anyhow::{Context, Result, bail};
use indicatif::ProgressBar;
use rtl_render::checkpoint::{CheckpointRef, Identity};
use rtl_render::render::{Accumulator, Renderer};
use rtl_render::sampler::Stats;
use rtl_render::tier_race::TierRace;
use std::path::PathBuf;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Set by the first Ctrl-C (or SIGTERM/SIGHUP): stop at the end of the current row band.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// When the first interrupt came.
static FIRST_INTERRUPT: OnceLock<Instant> = OnceLock::new();

/// A second interrupt this soon after the first is the same one delivered twice, not a second
/// Ctrl-C: `timeout -s INT` signals the program and then its whole process group, and a terminal's
/// Ctrl-C reaches every process of the foreground group (`rtl render ... | tee`), so a render was
/// sometimes told twice within microseconds and quit without its image. A person pressing Ctrl-C
/// again to quit takes longer than this.
pub const REPEAT_WINDOW: Duration = Duration::from_millis(500);

/// Catch Ctrl-C: the first asks the render to stop with what it has; a second, at least
/// [`REPEAT_WINDOW`] later, exits at once.
pub fn catch_interrupts() -> Result<()> {
    ctrlc::set_handler(|| {
        let now = Instant::now();
        if INTERRUPTED.swap(true, Ordering::SeqCst) {
            let first = *FIRST_INTERRUPT.get_or_init(|| now);
            if now.duration_since(first) < REPEAT_WINDOW {
                return; // the same interrupt, delivered twice
            }
            eprintln!("\ninterrupted again: exiting without saving");
            std::process::exit(130);
        }
        FIRST_INTERRUPT.get_or_init(|| now);
        eprintln!("\ninterrupted: finishing with the passes done (Ctrl-C again to quit at once)");
    })
    .context("cannot install the Ctrl-C handler")
}

fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}

/// A duration such as `90s`, `2m`, `1h30m`, `500ms`, `1.5h` or plain seconds `90`.
pub fn parse_duration(s: &str) -> Result<Duration, String> {
    let err = || format!("'{s}' is not a duration (examples: 90s, 2m, 1h30m, 500ms, 45)");
    let t = s.trim();
    if t.is_empty() {
        return Err(err());
    }
    // A positive time shorter than the nanosecond a `Duration` counts in would read as 0; one longer
    // than the longest `Duration` (about 5.8e11 years) is that, no deadline at all, as a budget past
    // the end of time is.
    // (a number written out that is too large for a double, `1e400`, reads as infinity: as long a
    // time; the words `inf` and `nan` are no durations)
    let written_out = !t.bytes().any(|b| b"iInN".contains(&b));
    let positive = |secs: f64| {
        if secs < 0.0 {
            return Err(format!("'{s}' is negative: a time is at least 0"));
        }
        let d = match Duration::try_from_secs_f64(secs) {
            Ok(d) => d,
            Err(_) if secs.is_finite() || written_out => Duration::MAX,
            Err(_) => return Err(err()),
        };
        if d.is_zero() && secs > 0.0 {
            Err(format!(
                "'{s}' is shorter than a nanosecond, the shortest time there is here"
            ))
        } else {
            Ok(d)
        }
    };
    if let Ok(secs) = t.parse::<f64>() {
        return positive(secs);
    }
    if t.starts_with('-') {
        return Err(format!("'{s}' is negative: a time is at least 0"));
    }
    let mut total = 0.0;
    let mut rest = t;
    let mut units: Vec<&str> = Vec::new();
    while !rest.is_empty() {
        let num_end = rest
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .ok_or_else(err)?;
        let value: f64 = rest[..num_end].parse().map_err(|_| err())?;
        rest = &rest[num_end..];
        let unit_end = rest
            .find(|c: char| !c.is_ascii_alphabetic())
            .unwrap_or(rest.len());
        let scale = match &rest[..unit_end] {
            "ms" => 1e-3,
            "s" => 1.0,
            "m" | "min" => 60.0,
            "h" => 3600.0,
            "d" => 86400.0,
            _ => return Err(err()),
        };
        let unit = &rest[..unit_end];
        if units.contains(&unit) {
            return Err(format!("'{s}': the unit '{unit}' appears twice (a typo?)"));
        }
        units.push(unit);
        total += value * scale;
        rest = &rest[unit_end..];
    }
    positive(total)
}

/// How the loop ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ending {
    /// Every sample asked for is done.
    Done,
    /// The time budget would not fit another pass.
    OutOfTime,
    /// Ctrl-C.
    Interrupted,
}

/// Where and how often to save the accumulation.
pub struct Saving {
    pub path: PathBuf,
    pub every: Duration,
    pub identity: Identity,
}

impl Saving {
    /// Write `acc` (samples `[start, acc.samples)`) to the checkpoint, streamed from the borrow: the
    /// passes run on this thread and wait for it, so the accumulation cannot change while it is
    /// written, and no copy of it (40 bytes a pixel) is made.
    pub fn save(&self, acc: &Accumulator, start: u64) -> Result<()> {
        let ck = CheckpointRef {
            identity: &self.identity,
            rtl_version: env!("CARGO_PKG_VERSION"),
            start,
            acc,
        };
        ck.write(&self.path)
            .with_context(|| format!("cannot write the checkpoint {}", self.path.display()))
    }
}

/// What to render: samples `[acc.samples, end)`, within `budget` if there is one.
pub struct Plan {
    pub start: u64,
    pub end: u64,
    pub budget: Option<Duration>,
    pub saving: Option<Saving>,
    /// The longest a pass should take (a stopped render loses at most about this much).
    pub pass_time: Duration,
    /// The progress bar counts the budget's milliseconds (a time budget and no sample count), not
    /// samples.
    pub progress_by_time: bool,
}

/// Render passes into `acc` until the plan says stop, saving it between passes; returns the counters of
/// the passes kept. The caller saves the end state (after writing the image). Where `race` holds a
/// race of intersection tiers, each pass runs the tier it names and is timed for it (the image is the
/// same with either).
pub fn run(
    renderer: &Renderer,
    pool: &rayon::ThreadPool,
    acc: &mut Accumulator,
    plan: &Plan,
    bar: &ProgressBar,
    race: &mut Option<TierRace>,
) -> Result<(Stats, Ending)> {
    if acc.samples < plan.start {
        bail!("internal: accumulation before its first sample");
    }
    let began = Instant::now();
    // A budget past the end of time (`--time 100000000000d`) is no deadline at all.
    let deadline = plan.budget.and_then(|b| began.checked_add(b));
    let h = acc.height as u64;
    let mut stats = Stats::default();
    // Save once before the first pass, so an unwritable path shows at once, not after the work.
    if let Some(s) = &plan.saving {
        s.save(acc, plan.start)?;
    }
    let mut next = acc.clone();
    let mut last_save = Instant::now();
    // Seconds one sample per pixel takes, measured on the passes so far.
    let mut secs_per_spp: Option<f64> = None;
    let mut n = 1u64;
    let stop = || interrupted() || deadline.is_some_and(|d| Instant::now() >= d);
    let ending = loop {
        if acc.samples >= plan.end {
            break Ending::Done;
        }
        if interrupted() {
            break Ending::Interrupted;
        }
        if let (Some(d), Some(t)) = (deadline, secs_per_spp) {
            let left = d.saturating_duration_since(Instant::now()).as_secs_f64();
            let fit = (left / t).floor() as u64;
            if fit == 0 {
                break Ending::OutOfTime;
            }
            n = n.min(fit);
        }
        // A race's passes take at most a thirty-second of the render each (with no end in sight,
        // as long as any), so that a short render runs mostly on the faster tier.
        let pass = match race {
            Some(r) if r.racing() => n.min((plan.end.saturating_sub(plan.start) / 32).max(1)),
            _ => n,
        };
        let (k0, k1) = (acc.samples, acc.samples.saturating_add(pass).min(plan.end));
        next.clone_from(acc);
        // (both of a race's tiers are ones this processor runs)
        if let Some(r) = race {
            r.tier().select().context("the intersection tiers' race")?;
        }
        let t0 = Instant::now();
        let on_row = || {
            if plan.progress_by_time {
                bar.set_position(began.elapsed().as_millis() as u64);
            } else {
                bar.inc(k1 - k0);
            }
        };
        let pass = pool.install(|| renderer.render_pass_until(&mut next, k0, k1, &on_row, &stop));
        let Some(s) = pass else {
            break if interrupted() {
                Ending::Interrupted
            } else {
                Ending::OutOfTime
            };
        };
        std::mem::swap(acc, &mut next);
        stats = stats + s;
        let secs = t0.elapsed().as_secs_f64();
        if let Some(r) = race {
            r.record(secs, k1 - k0);
        }
        let t = secs / (k1 - k0) as f64;
        secs_per_spp = Some(t);
        bar.set_message(format!("{} spp", acc.samples - plan.start));
        if !plan.progress_by_time {
            bar.set_position(h * (acc.samples - plan.start));
        }
        if let Some(s) = &plan.saving
            && last_save.elapsed() >= s.every
            && acc.samples < plan.end
        {
            if let Err(e) = s.save(acc, plan.start) {
                eprintln!("warning: {e:#}");
            }
            last_save = Instant::now();
        }
        // The next pass: about `pass_time` long, at most twice the last (a cheap start misleads).
        let fit = (plan.pass_time.as_secs_f64() / t.max(1e-12)).floor() as u64;
        n = fit.clamp(1, (k1 - k0).saturating_mul(2));
    };
    Ok((stats, ending))
}

#[cfg(test)]
mod tests {
    use super::parse_duration;
    use std::time::Duration;

    #[test]
    fn durations() {
        let s = |x: &str| parse_duration(x).unwrap();
        assert_eq!(s("90s"), Duration::from_secs(90));
        assert_eq!(s("90"), Duration::from_secs(90));
        assert_eq!(s("2m"), Duration::from_secs(120));
        assert_eq!(s("1h"), Duration::from_secs(3600));
        assert_eq!(s("1h30m"), Duration::from_secs(5400));
        assert_eq!(s("1.5s"), Duration::from_millis(1500));
        assert_eq!(s("250ms"), Duration::from_millis(250));
        for bad in ["", "s", "5x", "-3", "1h-", "inf", "nan", "-3s", "+inf"] {
            assert!(parse_duration(bad).is_err(), "{bad}");
        }
        for negative in ["-3", "-3s", "-1m30s"] {
            let e = parse_duration(negative).unwrap_err();
            assert!(e.contains(&format!("'{negative}' is negative")), "{e}");
        }
        // longer than a `Duration` holds (u64::MAX seconds, written as plain seconds or in days) is
        // the longest one, no deadline, as shorter budgets past the end of time are; it had been
        // refused as "not a duration"
        for long in [
            "18446744073709551615",
            "1e30",
            "1000000000000000d",
            "99999999999999999999h",
            "1e400",
        ] {
            assert_eq!(s(long), Duration::MAX, "{long}");
        }
        // zero is zero (the callers refuse it by name); a positive time is never read as zero
        assert_eq!(s("0"), Duration::ZERO);
        for tiny in ["1e-300", "0.0000000001s"] {
            let e = parse_duration(tiny).unwrap_err();
            assert!(e.contains(tiny) && e.contains("nanosecond"), "{e}");
        }
        let e = parse_duration("1h1h").unwrap_err();
        assert!(e.contains("'h' appears twice"), "{e}");
    }
}
