//! Renders and merges under a process's address-space limit (`ulimit -v`): refused before any work
//! when what they need does not fit, and done when it does, never aborted on allocation ("memory
//! allocation of N bytes failed", SIGABRT, exit 134) after the check let them through.
//!
//! Each case is run at two limits a few megabytes either side of what the check says it needs
//! (`rtl_render::limits::render_need` and `merge_need`, with what the process has mapped when it
//! checks, learnt from a refusal's message): below, refused with a message that names the limit;
//! above, done. The accounting had left out the threads' stacks and malloc arenas (64 MiB of
//! address space each), a checkpoint's copy and its doubling vector, and a merge's merged copy and
//! its checkpoint's bytes, and those runs aborted.

mod common;

use common::{RTL, dir, rtl_under_ulimit};
use rtl_render::checkpoint::Checkpoint;
use rtl_render::limits::{merge_need, render_need};
use std::path::Path;
use std::process::{Command, Output};

/// Run `rtl args` in `d` with its address space limited to `kib` KiB (`ulimit -v`).
fn rtl_under_ulimit_v(d: &Path, kib: u64, args: &[&str]) -> Output {
    rtl_under_ulimit_v_with(d, kib, &[], args)
}

/// [`rtl_under_ulimit_v`] with environment variables `env` set.
fn rtl_under_ulimit_v_with(d: &Path, kib: u64, env: &[(&str, &str)], args: &[&str]) -> Output {
    rtl_under_ulimit(d, &format!("-v {kib}"), env, args)
}

/// Bytes in a number the way rtl writes them: `244.8 MB`.
fn bytes_in(text: &str) -> Option<f64> {
    let mut words = text.split_whitespace();
    let number: f64 = words.next()?.parse().ok()?;
    let unit = match words.next()? {
        "B" => 1.0,
        "kB" => 1e3,
        "MB" => 1e6,
        "GB" => 1e9,
        _ => return None,
    };
    Some(number * unit)
}

/// What the process had mapped when it checked, in bytes: from a refusal under `ulimit -v kib`
/// ("this process may map only 244.8 MB more"), to within 0.05 MB.
fn mapped_at_the_check(d: &Path, kib: u64, env: &[(&str, &str)], args: &[&str]) -> f64 {
    let out = rtl_under_ulimit_v_with(d, kib, env, args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(
        out.status.code(),
        Some(1),
        "{args:?} under {kib} KiB: {err}"
    );
    let more = err
        .split("may map only ")
        .nth(1)
        .and_then(|rest| bytes_in(rest.split(" more").next()?))
        .unwrap_or_else(|| panic!("no 'may map only' in: {err}"));
    (kib * 1024) as f64 - more
}

/// The limits in KiB a few megabytes below and above what `args` need (`need` bytes of address
/// space, besides what the process has mapped when it checks, found by a refusal at `probe_kib`).
fn limits_around(
    d: &Path,
    probe_kib: u64,
    env: &[(&str, &str)],
    args: &[&str],
    need: u64,
) -> (u64, u64) {
    let at = mapped_at_the_check(d, probe_kib, env, args) + need as f64;
    let margin = 3e6;
    let below = ((at - margin) / 1024.0) as u64;
    let above = ((at + margin) / 1024.0) as u64;
    assert!(
        probe_kib < below,
        "probe {probe_kib} KiB, below {below} KiB"
    );
    (below, above)
}

/// Refused (exit 1) with a message holding every one of `words`, nothing aborted or written.
#[track_caller]
fn refused(out: &Output, what: &str, words: &[&str]) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{what}: {err}");
    assert!(!err.contains("memory allocation"), "{what}: {err}");
    for w in words {
        assert!(err.contains(w), "{what}: wanted {w:?} in: {err}");
    }
}

#[track_caller]
fn done(out: &Output, what: &str) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{what}: {:?}: {err}", out.status);
}

/// `rtl render quads` at `width` with `threads` threads and one sample per pixel (`--spp` in
/// `extra` says otherwise: the last one given counts), cheaply.
fn quads<'a>(width: &'a str, threads: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut v = vec![
        "render",
        "quads",
        "--width",
        width,
        "--max-depth",
        "2",
        "--threads",
        threads,
        "-o",
        "q.png",
    ];
    if !extra.contains(&"--spp") {
        v.extend_from_slice(&["--spp", "1"]);
    }
    v.extend_from_slice(extra);
    v
}

#[test]
fn the_reviewers_render_under_ulimit_v_is_refused_for_its_threads_arenas_not_aborted() {
    // 600 x 600 pixels on two threads: 57 MB of buffers by the old count, which passed under
    // 250,000 KiB; but the threads' malloc arenas and stacks took some 200 MB more of address
    // space, and the render aborted.
    let d = dir("reviewer");
    let args = [
        "render",
        "cornell",
        "--width",
        "600",
        "--spp",
        "1",
        "--threads",
        "2",
        "-o",
        "c.png",
    ];
    let out = rtl_under_ulimit_v(&d, 250_000, &args);
    refused(
        &out,
        "cornell 600 under 250000 KiB",
        &[
            "--width 600",
            "--threads 2",
            "600x600",
            "of address space",
            "malloc arenas",
            "ulimit -v",
        ],
    );
    assert!(!d.join("c.png").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_render_just_past_ulimit_v_is_refused_and_one_just_within_it_is_done() {
    // The threads' arenas are made when a thread first allocates, if they fit (if not, glibc
    // shares one: no harm); they took the room the pass's copy of the accumulation needed after
    // (at 1800 x 1800 pixels, 40 bytes a pixel is 130 MB: room for two arenas before it), and the
    // render aborted. Seven threads at 700 x 700 pixels: more arenas, and the per-thread count.
    let d = dir("render");
    // (workers, and the Ctrl-C handler's thread besides)
    for (width, threads, others) in [(1800u64, "2", 3), (700, "6", 7)] {
        let w = width.to_string();
        let args = quads(&w, threads, &[]);
        let need = render_need(width * width, others, 0).address_space;
        let (below, above) = limits_around(&d, 50_000, &[], &args, need);
        let what = format!("{w} wide on {threads} threads under {below} KiB");
        refused(
            &rtl_under_ulimit_v(&d, below, &args),
            &what,
            &[&format!("{w}x{w}"), "malloc arenas", "ulimit -v"],
        );
        assert!(!d.join("q.png").exists(), "{what}");
        done(
            &rtl_under_ulimit_v(&d, above, &args),
            &format!("{w} wide on {threads} threads under {above} KiB"),
        );
        assert!(d.join("q.png").exists());
        std::fs::remove_file(d.join("q.png")).unwrap();
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_render_with_a_checkpoint_just_within_ulimit_v_writes_it_and_resumes_it() {
    // The checkpoint had been copied whole and then built in a vector that doubled past its
    // first guess (its header is longer than the 128 bytes it kept): 120 bytes a pixel beyond
    // what the check counted, between passes, and `Checkpoint::write` aborted. Now it is
    // streamed. Without malloc
    // arenas (`MALLOC_ARENA_MAX=1`: the main thread's serves every thread) the margin of the
    // threads' allowance is out of the way, and a copy of the accumulation (40 bytes a pixel,
    // 48 MB here) would not fit in what is left of the margin: this run would abort.
    let d = dir("checkpoint");
    let width = 1100u64;
    let env = [("MALLOC_ARENA_MAX", "1")];
    // (three samples a pixel in two passes at least, saved between them, when the pass's copy is
    // there too)
    let args = quads(
        "1100",
        "2",
        &[
            "--spp",
            "3",
            "--checkpoint",
            "c.ck",
            "--checkpoint-every",
            "1ms",
        ],
    );
    let mut need = render_need(width * width, 3, 0).address_space;
    let arenas = rtl_render::limits::malloc_arenas(3) as u64;
    if arenas > 0 {
        // (this process's count, without the variable: the arenas and one being made)
        need -= (arenas + 1) * rtl_render::limits::MALLOC_ARENA_BYTES;
    }
    let (below, above) = limits_around(&d, 50_000, &env, &args, need);
    refused(
        &rtl_under_ulimit_v_with(&d, below, &env, &args),
        "--checkpoint, below",
        &["1100x1100", "ulimit -v"],
    );
    assert!(!d.join("c.ck").exists());
    done(
        &rtl_under_ulimit_v_with(&d, above, &env, &args),
        "--checkpoint, above",
    );
    let ck = Checkpoint::read(&d.join("c.ck")).unwrap();
    assert_eq!((ck.acc.width, ck.acc.height, ck.spp()), (1100, 1100, 3));
    // and resumed within the same limit: the file's bytes and the accumulation read from them
    let resume = quads("1100", "2", &["--resume", "c.ck", "--spp", "4"]);
    done(
        &rtl_under_ulimit_v_with(&d, above, &env, &resume),
        "--resume, above",
    );
    assert_eq!(Checkpoint::read(&d.join("c.ck")).unwrap().spp(), 4);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_merge_just_past_ulimit_v_is_refused_and_one_just_within_it_writes_its_part() {
    // Two parts of 1000 x 1000 pixels (40 MB each): the old check counted twice the parts, but
    // the merge held them, the merged copy, its image and the merged part's bytes in a vector
    // that doubled, and aborted in `Checkpoint::write`.
    let d = dir("merge");
    for (part, offset) in [("p0.ck", "0"), ("p1.ck", "1")] {
        let out = Command::new("timeout")
            .arg("120")
            .arg(RTL)
            .args(quads(
                "1000",
                "2",
                &["--sample-offset", offset, "--part", part],
            ))
            .current_dir(&d)
            .output()
            .unwrap();
        done(&out, part);
    }
    let sizes: Vec<u64> = ["p0.ck", "p1.ck"]
        .iter()
        .map(|p| std::fs::metadata(d.join(p)).unwrap().len())
        .collect();
    let args = ["merge", "p0.ck", "p1.ck", "-o", "m.png", "--part", "m.ck"];
    let need = merge_need(&sizes).address_space;
    let (below, above) = limits_around(&d, 30_000, &[], &args, need);
    refused(
        &rtl_under_ulimit_v(&d, below, &args),
        "merge, below",
        &[
            "the 2 part(s) hold 80.0 MB",
            "of address space",
            "ulimit -v",
        ],
    );
    assert!(!d.join("m.ck").exists() && !d.join("m.png").exists());
    done(&rtl_under_ulimit_v(&d, above, &args), "merge, above");
    let m = Checkpoint::read(&d.join("m.ck")).unwrap();
    assert_eq!((m.start, m.acc.samples, m.acc.width), (0, 2, 1000));
    assert!(d.join("m.png").exists());
    let _ = std::fs::remove_dir_all(&d);
}

/// `rtl lab` under `ulimit -v 100000` started, then aborted half-way through an allocation when
/// its page asked for a 600-pixel render. It is refused at the start now, saying what it may come
/// to need, before it listens on any port.
#[test]
fn the_lab_is_refused_at_its_start_under_too_tight_a_limit() {
    let d = dir("lab");
    let out = rtl_under_ulimit(
        &d,
        "-v 300000",
        &[],
        &["lab", "--port", "0", "--reference-dir", "refs"],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(err.contains("the lab may need"), "{err}");
    assert!(err.contains("ulimit -v"), "{err}");
    assert!(!err.contains("open http"), "{err}");
    let _ = std::fs::remove_dir_all(&d);
}
