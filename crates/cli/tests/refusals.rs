//! Hostile and extreme input to `rtl render` and `rtl merge`: every value is either rendered or refused
//! before any work with a message that names the flag (or the scene file's place), the value and the
//! limit; never a panic, an abort, a hang or a silently wrong image.

use rtl_render::checkpoint::Checkpoint;
use rtl_render::vec::Color;
mod common;

use common::{dir, ok, refused_with, rtl};
use std::path::Path;
use std::process::{Command, Output};

/// Run `rtl` expecting a refusal (exit code 1, no panic) whose message contains every one of `words`.
#[track_caller]
fn refused(d: &Path, args: &[&str], words: &[&str]) {
    refused_with(d, 1, args, words);
}

fn render<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut v = vec!["render", "cornell", "--width", "16", "--spp", "2"];
    v.extend_from_slice(extra);
    v
}

/// Nothing but the files the test made itself.
fn files(d: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// A small scene file with `render` in its `[render]` table.
fn scene(render: &str) -> String {
    format!(
        "[render]\n{render}\n[camera]\nlookfrom = [0, 0, -5]\nlookat = [0, 0, 0]\n[materials]\n\
         w = {{ type = \"lambertian\", albedo = 0.5 }}\n[[objects]]\ntype = \"sphere\"\n\
         center = [0, 0, 0]\nradius = 1\nmaterial = \"w\"\n"
    )
}

#[test]
fn max_depth_zero_is_refused_on_the_command_line_as_in_a_scene_file() {
    let d = dir("depth");
    refused(
        &d,
        &render(&["--max-depth", "0"]),
        &["--max-depth 0", "at least 1"],
    );
    refused(
        &d,
        &render(&["--max-depth", "4000000000"]),
        &["--max-depth 4000000000", "at most 10000"],
    );
    std::fs::write(d.join("s.toml"), scene("max_depth = 0")).unwrap();
    refused(
        &d,
        &["render", "s.toml"],
        &["s.toml:", "field `render.max_depth`", "at least 1"],
    );
    assert_eq!(files(&d), ["s.toml"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn thread_counts_past_the_limit_are_refused_instead_of_hanging() {
    let d = dir("threads");
    refused(
        &d,
        &render(&["--threads", "100000"]),
        &["--threads 100000", "1 to 1024"],
    );
    refused(&d, &render(&["--threads", "0"]), &["--threads 0"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn an_image_past_the_side_limit_or_the_memory_is_refused_before_allocation() {
    let d = dir("width");
    refused(
        &d,
        &["render", "cornell", "--width", "100000"],
        &["--width 100000", "65536"],
    );
    // 60000 x 60000 pixels need 572 GB.
    refused(
        &d,
        &["render", "cornell", "--width", "60000"],
        &["--width 60000", "60000x60000", "MemAvailable"],
    );
    assert!(files(&d).is_empty());
    let _ = std::fs::remove_dir_all(&d);
}

/// Run `rtl args` in `d` under `ulimit` (`limit`, e.g. `-v 1500000`: KiB of address space).
fn rtl_under_ulimit(d: &Path, limit: &str, args: &[&str]) -> Output {
    common::rtl_under_ulimit(d, limit, &[], args)
}

#[test]
fn an_image_past_the_processs_own_memory_limit_is_refused_not_aborted() {
    // 2200 x 2200 pixels need 426 MB (88 bytes a pixel): the machine has them, a process under
    // `ulimit -v 400000` (or `-d`) has not. Only MemAvailable was asked, and the render aborted on
    // allocation. (A limit this low is surely the least of the limits, so the refusal names it on
    // any machine a test runs on; two threads keep the pool's stacks within it. Past `ulimit -v`,
    // memory_limits.rs.)
    let d = dir("ulimit");
    let quads = |width: &'static str| {
        [
            "render",
            "quads",
            "--width",
            width,
            "--spp",
            "1",
            "--threads",
            "2",
            "-o",
            "q.png",
        ]
    };
    for (limit, words) in [("-v 400000", "ulimit -v"), ("-d 400000", "ulimit -d")] {
        let out = rtl_under_ulimit(&d, limit, &quads("2200"));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "ulimit {limit}: {err}");
        for w in ["--width 2200", "2200x2200", words] {
            assert!(err.contains(w), "ulimit {limit}: wanted {w:?} in: {err}");
        }
        assert!(files(&d).is_empty());
    }
    // within the limit, the same process renders
    let out = rtl_under_ulimit(&d, "-v 400000", &quads("64"));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn extreme_aspect_ratios_in_a_scene_file_are_refused_with_their_place() {
    let d = dir("aspect");
    for aspect in ["1e-300", "\"1:1e300\"", "1e300", "0"] {
        std::fs::write(d.join("a.toml"), scene(&format!("aspect = {aspect}"))).unwrap();
        refused(
            &d,
            &["render", "a.toml", "--width", "4", "--spp", "1"],
            &["a.toml:", "field `render.aspect`"],
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// A medium whose boundary is a group of quads that leaves a gap (three faces of a box) is refused
/// with the boundary's place before any rendering, and writes nothing; the same group closed by the
/// other three faces renders.
#[test]
fn a_medium_in_an_open_group_of_quads_is_refused_before_rendering() {
    let d = dir("open-medium");
    let face = |q: &str, u: &str, v: &str| {
        format!(
            "[[objects.boundary.objects]]\ntype = \"quad\"\nq = {q}\nu = {u}\nv = {v}\n\
             material = \"w\"\n"
        )
    };
    let half = [
        face("[0, 0, 0]", "[1, 0, 0]", "[0, 1, 0]"),
        face("[0, 0, 0]", "[0, 0, 1]", "[0, 1, 0]"),
        face("[0, 0, 0]", "[1, 0, 0]", "[0, 0, 1]"),
    ]
    .concat();
    let other = [
        face("[1, 1, 1]", "[-1, 0, 0]", "[0, -1, 0]"),
        face("[1, 1, 1]", "[0, 0, -1]", "[0, -1, 0]"),
        face("[1, 1, 1]", "[-1, 0, 0]", "[0, 0, -1]"),
    ]
    .concat();
    let file = |faces: &str| {
        format!(
            "{}[[objects]]\ntype = \"medium\"\ndensity = 1\nalbedo = 0.5\n[objects.boundary]\n\
             type = \"group\"\n{faces}",
            scene("background = \"sky\"")
        )
    };
    std::fs::write(d.join("open.toml"), file(&half)).unwrap();
    refused(
        &d,
        &[
            "render",
            "open.toml",
            "--width",
            "8",
            "--spp",
            "1",
            "-o",
            "open.png",
        ],
        &[
            "open.toml:18:8:",
            "field `objects[1].boundary.type`",
            "must enclose a volume",
            "the quad at line 19:1",
            "no other quad",
        ],
    );
    assert_eq!(files(&d), ["open.toml"]);
    std::fs::write(d.join("closed.toml"), file(&format!("{half}{other}"))).unwrap();
    ok(
        &d,
        &[
            "render",
            "closed.toml",
            "--width",
            "8",
            "--spp",
            "1",
            "-o",
            "closed.png",
        ],
    );
    assert!(d.join("closed.png").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn outputs_are_checked_before_any_rendering() {
    let d = dir("outputs");
    // The render below would take minutes: a refusal in seconds shows it came first.
    let slow = |extra: &[&'static str]| {
        let mut v = vec!["render", "cornell", "--width", "600", "--spp", "100000"];
        v.extend_from_slice(extra);
        v
    };
    refused(
        &d,
        &slow(&["-o", "missing/dir/x.png"]),
        &["-o missing/dir/x.png", "does not exist"],
    );
    refused(
        &d,
        &slow(&["--linear", "x.tiff"]),
        &["--linear x.tiff", ".pfm or .exr"],
    );
    refused(&d, &slow(&["-o", "x.jpg"]), &["-o x.jpg", ".png"]);
    // a name that is all extension is a hidden file's, with none (it was told to end in .png)
    refused(
        &d,
        &slow(&["-o", ".png"]),
        &["-o .png: the file name needs a name before its extension"],
    );
    refused(
        &d,
        &slow(&["--linear", ".pfm"]),
        &["--linear .pfm: the file name needs a name"],
    );
    refused(
        &d,
        &slow(&["--linear", "missing/x.pfm"]),
        &["--linear missing/x.pfm", "does not exist"],
    );
    refused(
        &d,
        &slow(&["--linear", "a.pfm", "--checkpoint", "./a.pfm"]),
        &["--linear and --checkpoint both name"],
    );
    refused(
        &d,
        &slow(&["-o", "x.png", "--part", "x.png"]),
        &["-o and --checkpoint both name"],
    );
    std::fs::create_dir(d.join("sub.png")).unwrap();
    refused(&d, &slow(&["-o", "sub.png"]), &["-o sub.png", "directory"]);
    assert_eq!(files(&d), ["sub.png"]);
    let _ = std::fs::remove_dir_all(&d);
}

/// A checkpoint given where the scene goes was refused as "not UTF-8 text ... save it as UTF-8";
/// it is named for what it is, with the two commands that take it.
#[test]
fn a_checkpoint_given_as_the_scene_says_how_to_use_it() {
    let d = dir("ck-as-scene");
    ok(&d, &render(&["--part", "p.ck"]));
    refused(
        &d,
        &["render", "p.ck", "--width", "16", "--spp", "1"],
        &[
            "p.ck is a checkpoint of rtl (a part), not a scene file",
            "--resume p.ck",
            "rtl merge p.ck",
        ],
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A scene file's width too large for the memory is refused at its place in the file, as every
/// other value of a scene file is (it was "the scene's width and the scene's aspect ratio: ..."
/// with no file, line or column); `--width` overrides it.
#[test]
fn a_scene_files_width_past_the_memory_is_refused_at_its_place() {
    let d = dir("file-width");
    std::fs::write(d.join("wide.toml"), scene("width = 60000")).unwrap();
    refused(
        &d,
        &["render", "wide.toml", "--spp", "1"],
        &[
            "wide.toml:2:9: field `render.width`: the width 60000",
            "60000x60000",
        ],
    );
    ok(&d, &["render", "wide.toml", "--spp", "1", "--width", "8"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn durations_of_zero_are_refused_and_a_budget_past_the_end_of_time_is_no_deadline() {
    let d = dir("time");
    refused(&d, &render(&["--time", "0"]), &["--time 0", "positive"]);
    refused(
        &d,
        &render(&["--checkpoint-every", "0s", "--part", "p"]),
        &["--checkpoint-every 0"],
    );
    // an interval of saving with nothing to save was ignored without a word
    refused(
        &d,
        &render(&["--checkpoint-every", "1s"]),
        &["--checkpoint-every: there is no checkpoint to save"],
    );
    ok(&d, &render(&["--checkpoint-every", "1s", "--part", "p"]));
    ok(&d, &render(&["--time", "100000000000000d"]));
    // Resumed and saved where it is read, however the two are written (`p` and `./p`): it was
    // refused as writing an input, while `--resume p --checkpoint p` went through.
    ok(
        &d,
        &[
            "render",
            "cornell",
            "--width",
            "16",
            "--spp",
            "4",
            "--resume",
            "p",
            "--checkpoint",
            "./p",
        ],
    );
    assert_eq!(Checkpoint::read(&d.join("p")).unwrap().spp(), 4);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_time_budget_that_ends_before_the_first_pass_writes_no_black_image() {
    let d = dir("nopass");
    // One pass of 1000x1000 pixels takes far longer than a millisecond.
    refused(
        &d,
        &[
            "render", "cornell", "--width", "1000", "--time", "1ms", "-o", "x.png",
        ],
        &["no pass finished", "no image written"],
    );
    assert!(!d.join("x.png").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn sample_offsets_past_2_to_the_32_are_carried_exactly_and_overflow_is_refused() {
    let d = dir("offset");
    let k = 1u64 << 32;
    let (k0, k1) = (k.to_string(), (k + 2).to_string());
    ok(&d, &render(&["--sample-offset", &k0, "--part", "a"]));
    ok(&d, &render(&["--sample-offset", &k1, "--part", "b"]));
    let a = Checkpoint::read(&d.join("a")).unwrap();
    assert_eq!((a.start, a.acc.samples), (k, k + 2));
    let out = ok(&d, &["merge", "a", "b", "-o", "m.png", "--part", "m"]);
    assert!(out.contains(&format!("samples {k}..{}", k + 4)), "{out}");
    let m = Checkpoint::read(&d.join("m")).unwrap();
    assert_eq!((m.start, m.acc.samples, m.spp()), (k, k + 4, 4));
    let top = (u64::MAX - 1).to_string();
    refused(
        &d,
        &render(&["--sample-offset", &top]),
        &["--sample-offset 18446744073709551614 plus --spp 2"],
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Write `ck` with pixel 3's sum replaced by `sum`: the checksum is valid, the content is not.
fn lying_copy(ck: &Checkpoint, sum: Color, path: &Path) {
    let mut c = ck.clone();
    c.acc.sum[3] = sum;
    c.write(path).unwrap();
}

/// A checkpoint's strings (its scene's name, the version of rtl that wrote it, its settings) are
/// printed in notes and refusals: a forged one (valid checksum) with an escape sequence in them had
/// it act on the terminal (`merged 1 part(s) of cornell ESC[2J ESC[31mPWNED`), and a settings
/// string of 200 KB was echoed whole. Now each is written out (`\u{001B}`) and cut short.
#[test]
fn a_checkpoints_strings_are_shown_not_sent_to_the_terminal() {
    let d = dir("ck-strings");
    ok(&d, &render(&["--part", "good"]));
    let good = Checkpoint::read(&d.join("good")).unwrap();
    let mut forged = good.clone();
    forged.identity.scene = "cornell\u{1b}[2J\u{1b}[31mPWNED".into();
    forged.rtl_version = "9.9.9\u{1b}[31m".into();
    forged.write(&d.join("forged")).unwrap();
    let out = rtl(&d, &["merge", "forged", "-o", "m.png"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(!err.contains('\u{1b}'), "{err:?}");
    assert!(
        err.contains("of cornell\\u{001B}[2J\\u{001B}[31mPWNED"),
        "{err}"
    );
    // (merge notes another version as --resume does)
    assert!(
        err.contains("note: forged was written by rtl 9.9.9\\u{001B}[31m"),
        "{err}"
    );
    // resumed: the version's note
    let mut resumable = good.clone();
    resumable.rtl_version = "9.9.9\u{1b}[31m".into();
    resumable.write(&d.join("old")).unwrap();
    let out = rtl(
        &d,
        &[
            "render", "cornell", "--width", "16", "--spp", "4", "--resume", "old",
        ],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(!err.contains('\u{1b}'), "{err:?}");
    assert!(err.contains("written by rtl 9.9.9\\u{001B}[31m"), "{err}");
    // a settings string of 200 KB, refused as another render, is shown cut short
    let mut long = good.clone();
    long.identity.settings = "x".repeat(200_000);
    long.write(&d.join("long")).unwrap();
    let out = rtl(&d, &["merge", "good", "long", "-o", "m.png"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.len() < 5_000, "{} bytes: {}", err.len(), &err[..300]);
    assert!(err.contains("more characters)"), "{err}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn checkpoints_with_a_valid_checksum_but_lying_sums_are_refused_by_merge_and_resume() {
    let d = dir("lying");
    ok(&d, &render(&["--part", "good"]));
    let good = Checkpoint::read(&d.join("good")).unwrap();
    for (name, sum, why) in [
        ("nan", Color::new(f64::NAN, 0.0, 0.0), "must be finite"),
        ("inf", Color::splat(f64::INFINITY), "must be finite"),
        ("neg", Color::new(0.0, -1.0, 0.0), "never negative"),
    ] {
        lying_copy(&good, sum, &d.join(name));
        refused(
            &d,
            &["merge", name, "-o", "m.png"],
            &[name, "is corrupt", "pixel 3", why],
        );
        refused(
            &d,
            &[
                "render", "cornell", "--width", "16", "--spp", "4", "--resume", name,
            ],
            &["is corrupt", why],
        );
    }
    assert!(!d.join("m.png").exists());
    // Finite sums whose total overflows: refused, not written as a NaN image with "0 non-finite".
    ok(&d, &render(&["--sample-offset", "2", "--part", "next"]));
    let next = Checkpoint::read(&d.join("next")).unwrap();
    lying_copy(&good, Color::splat(1e308), &d.join("big0"));
    lying_copy(&next, Color::splat(1e308), &d.join("big1"));
    refused(
        &d,
        &["merge", "big0", "big1", "-o", "m.png"],
        &["overflows"],
    );
    assert!(!d.join("m.png").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn merge_checks_its_outputs_before_reading_and_never_overwrites_a_part() {
    let d = dir("mergeout");
    ok(&d, &render(&["--part", "p0"]));
    ok(&d, &render(&["--sample-offset", "2", "--part", "p1"]));
    refused(
        &d,
        &["merge", "p0", "p1", "-o", "nowhere/m.png"],
        &["-o nowhere/m.png", "does not exist"],
    );
    refused(
        &d,
        &["merge", "p0", "p1", "--linear", "m.bmp"],
        &["--linear m.bmp"],
    );
    refused(
        &d,
        &["merge", "p0", "p1", "--part", "p1"],
        &["--part p1 is also an input (the part p1)"],
    );
    refused(
        &d,
        &[
            "merge", "p0", "p1", "-o", "m.png", "--linear", "m.pfm", "--part", "m.pfm",
        ],
        &["--linear and --part both name m.pfm"],
    );
    assert_eq!(files(&d), ["cornell.png", "p0", "p1"]);
    ok(&d, &["merge", "p0", "p1", "-o", "m.png"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_mixture_weight_outside_0_to_1_or_without_the_mixture_is_refused() {
    let d = dir("mixture-weight");
    for w in ["0", "1", "1.5", "NaN", "inf", "-0.25"] {
        let flag = format!("--mixture-weight={w}");
        refused(
            &d,
            &render(&["--strategy", "mixture", &flag]),
            &["--mixture-weight", "not strictly between 0 and 1"],
        );
    }
    refused(
        &d,
        &render(&["--mixture-weight", "0.3"]),
        &["--mixture-weight 0.3", "only the 'mixture' strategy"],
    );
    // a tiny number is shown short, not in three hundred digits
    refused(
        &d,
        &render(&["--strategy", "mixture", "--mixture-weight=-1e-300"]),
        &["--mixture-weight -1e-300: the mixture weight is -1e-300, not strictly"],
    );
    // a scene without importance targets has nothing to mix: the weight would be ignored
    refused(
        &d,
        &[
            "render",
            "quads",
            "--width",
            "16",
            "--spp",
            "1",
            "--strategy",
            "mixture",
            "--mixture-weight",
            "0.3",
        ],
        &["--mixture-weight 0.3: quads lists no importance targets"],
    );
    assert!(files(&d).is_empty(), "{:?}", files(&d));
    let _ = std::fs::remove_dir_all(&d);
}

/// `mixture` and `light` aim at the importance targets; on a scene that lists none they sample the
/// material alone, the image `cosine`'s bit for bit, which was rendered without a word. Now a note
/// says so; a scene with targets gets no such note.
#[test]
fn a_strategy_of_targets_on_a_scene_without_them_says_it_is_cosine() {
    let d = dir("no-targets");
    for s in ["mixture", "light"] {
        let err = ok(
            &d,
            &[
                "render",
                "quads",
                "--width",
                "16",
                "--spp",
                "1",
                "--strategy",
                s,
            ],
        );
        assert!(
            err.contains(&format!(
                "note: this scene lists no importance targets (`lights`), so '{s}' samples the \
                 material's density alone: the image is the 'cosine' strategy's"
            )),
            "{err}"
        );
    }
    let err = ok(&d, &render(&["--strategy", "mixture"]));
    assert!(!err.contains("no importance targets"), "{err}");
    let _ = std::fs::remove_dir_all(&d);
}

/// A one-sided quad light turned away from everything (u and v swapped: it shines up, at nothing)
/// rendered a black image with exit code 0 and no word. Now a note says every pixel is black and
/// why that may be; the same light turned down gets no note.
#[test]
fn an_image_black_in_every_pixel_of_a_lit_scene_says_so() {
    let d = dir("all-black");
    let lamp = |u: &str, v: &str| {
        format!(
            "[camera]\nlookfrom = [0, 1, -5]\nlookat = [0, 1, 0]\n[materials]\n\
             white = {{ type = \"lambertian\", albedo = 0.7 }}\n\
             lamp = {{ type = \"light\", emit = 10 }}\n\
             [[objects]]\ntype = \"quad\"\nq = [-3, 0, -3]\nu = [6, 0, 0]\nv = [0, 0, 6]\n\
             material = \"white\"\n\
             [[objects]]\ntype = \"quad\"\nq = [-1, 2.5, -1]\nu = {u}\nv = {v}\n\
             material = \"lamp\"\n"
        )
    };
    let note = "note: every pixel is black: no light reached the camera";
    std::fs::write(d.join("up.toml"), lamp("[0, 0, 2]", "[2, 0, 0]")).unwrap();
    let err = ok(&d, &["render", "up.toml", "--width", "16", "--spp", "2"]);
    assert!(err.contains(note), "{err}");
    std::fs::write(d.join("down.toml"), lamp("[2, 0, 0]", "[0, 0, 2]")).unwrap();
    let err = ok(&d, &["render", "down.toml", "--width", "16", "--spp", "2"]);
    assert!(!err.contains(note), "{err}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_resume_with_another_mixture_weight_is_refused() {
    let d = dir("identity-weight");
    // The book's weight is left out of the record: a checkpoint of the default resumes as before.
    ok(
        &d,
        &render(&["--strategy", "mixture", "--checkpoint", "ck"]),
    );
    let resume = |extra: &[&'static str]| {
        let mut v = vec![
            "render",
            "cornell",
            "--width",
            "16",
            "--spp",
            "4",
            "--resume",
            "ck",
            "--strategy",
            "mixture",
        ];
        v.extend_from_slice(extra);
        v
    };
    refused(
        &d,
        &resume(&["--mixture-weight", "0.2"]),
        &["mixture_weight: absent in the checkpoint, 0.2 in this render"],
    );
    ok(&d, &resume(&["--mixture-weight", "0.5"]));
    ok(
        &d,
        &render(&[
            "--strategy",
            "mixture",
            "--mixture-weight",
            "0.25",
            "--checkpoint",
            "ck2",
        ]),
    );
    refused(
        &d,
        &[
            "render",
            "cornell",
            "--width",
            "16",
            "--spp",
            "4",
            "--resume",
            "ck2",
            "--strategy",
            "mixture",
            "--mixture-weight",
            "0.75",
        ],
        &["mixture_weight: 0.25 in the checkpoint, 0.75 in this render"],
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_resume_with_other_settings_names_the_serialised_field_that_differs() {
    let d = dir("identity");
    ok(&d, &render(&["--checkpoint", "ck"]));
    refused(
        &d,
        &[
            "render", "cornell", "--width", "16", "--spp", "4", "--resume", "ck", "--no-rr",
        ],
        &["strategy.Mis.russian_roulette: true in the checkpoint, false in this render"],
    );
    refused(
        &d,
        &[
            "render",
            "cornell",
            "--width",
            "16",
            "--spp",
            "4",
            "--resume",
            "ck",
            "--strategy",
            "cosine",
        ],
        &[
            "strategy: {\"Mis\":",
            "in the checkpoint, \"Cosine\" in this render",
        ],
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn study_render_refuses_a_sweep_past_u64_and_an_image_past_the_memory() {
    let d = dir("study");
    // 4^31: the sweep 1, 4, 16, ... would overflow u64 and never end.
    refused(
        &d,
        &[
            "study",
            "render",
            "--out",
            "o",
            "--quick",
            "--max-spp",
            "4611686018427387904",
        ],
        &["--max-spp 4611686018427387904", "at most"],
    );
    refused(
        &d,
        &[
            "study", "render", "--out", "o", "--quick", "--width", "100000",
        ],
        &["--width 100000", "65536"],
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_time_budget_from_the_last_sample_index_is_refused_not_an_empty_render() {
    let d = dir("lastindex");
    let last = u64::MAX.to_string();
    refused(
        &d,
        &[
            "render",
            "cornell",
            "--width",
            "8",
            "--time",
            "1s",
            "--sample-offset",
            &last,
        ],
        &[
            "--sample-offset 18446744073709551615",
            "no sample index is left",
        ],
    );
    // Just below it, a time budget renders the one sample there is.
    let below = (u64::MAX - 1).to_string();
    ok(
        &d,
        &[
            "render",
            "cornell",
            "--width",
            "8",
            "--time",
            "5s",
            "--sample-offset",
            &below,
            "--part",
            "p",
        ],
    );
    let p = Checkpoint::read(&d.join("p")).unwrap();
    assert_eq!((p.start, p.acc.samples), (u64::MAX - 1, u64::MAX));
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn parts_larger_than_the_memory_are_refused_before_they_are_read() {
    let d = dir("mergemem");
    // A sparse file: 1.1 TB by its length, nothing on disk.
    let f = std::fs::File::create(d.join("huge")).unwrap();
    f.set_len(1 << 40).unwrap();
    refused(
        &d,
        &["merge", "huge", "-o", "m.png"],
        &["the 1 part(s) hold 1.1 TB", "MemAvailable"],
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_hit_tier_changes_nothing_but_the_speed_and_one_not_run_is_refused() {
    let d = dir("hit-tier");
    // Every tier this processor runs gives the same image, bit for bit, and `--explain` names it.
    let tiers: Vec<_> = rtl_render::traversal::HitTier::ALL
        .into_iter()
        .filter(|t| t.available())
        .collect();
    assert!(!tiers.is_empty());
    let mut images = Vec::new();
    for t in &tiers {
        let pfm = format!("{}.pfm", t.key());
        ok(&d, &render(&["--hit-tier", t.key(), "--linear", &pfm]));
        images.push(std::fs::read(d.join(&pfm)).unwrap());
        let out = rtl(&d, &render(&["--hit-tier", t.key(), "--explain"]));
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains(t.name()), "{t:?}: {text}");
    }
    assert!(images.windows(2).all(|w| w[0] == w[1]), "{tiers:?} differ");
    // Without the flag the preferred tier runs (on an Intel processor with AVX-512, AVX2 and
    // AVX-512 race), and `--explain` says so on its intersection line.
    let out = rtl(&d, &render(&["--explain"]));
    let text = String::from_utf8_lossy(&out.stdout);
    let preferred = rtl_render::traversal::HitTier::preferred();
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with("intersection"))
        .unwrap_or_else(|| panic!("no intersection line: {text}"));
    if rtl_render::tier_race::TierRace::on_this_processor(false).is_some() {
        assert!(line.contains("whichever is faster"), "{line}");
    } else {
        assert!(line.contains(preferred.name()), "{preferred:?}: {line}");
    }
    assert!(
        !line.contains("--hit-tier;"),
        "no --hit-tier was given: {line}"
    );
    // An unknown tier, or one this processor does not run, is refused by clap (exit 2) naming the
    // flag and the value, before anything is written.
    let not_run = rtl_render::traversal::HitTier::ALL
        .into_iter()
        .find(|t| !t.available())
        .map(|t| t.key());
    for bad in ["avx9"].into_iter().chain(not_run) {
        let out = rtl(&d, &render(&["--hit-tier", bad, "-o", "bad.png"]));
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{bad}: {err}");
        assert!(err.contains("--hit-tier") && err.contains(bad), "{err}");
        if bad == "avx9" {
            // the refusal lists what is accepted, the race included
            assert!(err.contains("avx512 or auto"), "{err}");
        }
        assert!(!err.contains("panicked"), "{err}");
        assert!(!d.join("bad.png").exists());
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn hit_tier_auto_races_the_tiers_and_changes_nothing_but_the_speed() {
    use rtl_render::traversal::HitTier;
    let d = dir("hit-tier-auto");
    // 40 spp at this size is passes of 1 sample per pixel while the race lasts (five passes, each
    // at most a thirty-second of the render), then 2, 4, 8, 16 and 3, which the winner runs.
    let args = |tier: &'static str, pfm: &'static str| {
        let mut v = vec!["render", "cornell", "--width", "24", "--spp", "40"];
        v.extend(["--strategy", "mixture", "--hit-tier", tier, "--linear", pfm]);
        v
    };
    let err = ok(&d, &args("auto", "auto.pfm"));
    let fixed = HitTier::preferred().key();
    ok(&d, &args(fixed, "fixed.pfm"));
    let read = |f: &str| std::fs::read(d.join(f)).unwrap();
    assert_eq!(read("auto.pfm"), read("fixed.pfm"), "auto against {fixed}");
    let explain = rtl(
        &d,
        &args("auto", "x.pfm")
            .into_iter()
            .chain(["--explain"])
            .collect::<Vec<_>>(),
    );
    let text = String::from_utf8_lossy(&explain.stdout);
    if HitTier::detected() == HitTier::Avx512 {
        // Both tiers run here: the race is run, and its outcome told.
        assert!(
            err.contains("intersection: avx") && err.contains("as fast as avx"),
            "{err}"
        );
        assert!(text.contains("whichever is faster"), "{text}");
    } else {
        // Nothing to race: the one tier runs, and nothing is said of a race.
        assert!(!err.contains("intersection:"), "{err}");
        assert!(!text.contains("whichever is faster"), "{text}");
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn no_lanes_changes_nothing_but_the_speed_and_explain_says_how_paths_go() {
    let d = dir("no-lanes");
    // The book's mixture with eight paths side by side (where the processor runs them) and one at a
    // time: the same image, bit for bit.
    let mixture = |extra: &[&'static str]| {
        let mut v = render(&["--strategy", "mixture"]);
        v.extend_from_slice(extra);
        v
    };
    ok(&d, &mixture(&["--linear", "lanes.pfm"]));
    ok(&d, &mixture(&["--no-lanes", "--linear", "one.pfm"]));
    let read = |f: &str| std::fs::read(d.join(f)).unwrap();
    assert_eq!(read("lanes.pfm"), read("one.pfm"));
    let paths = |args: &[&str]| {
        let out = rtl(&d, args);
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        text.lines()
            .find(|l| l.trim_start().starts_with("paths"))
            .unwrap_or_else(|| panic!("no paths line: {text}"))
            .to_string()
    };
    let avx = rtl_render::traversal::HitTier::current() != rtl_render::traversal::HitTier::Portable;
    let line = paths(&mixture(&["--explain"]));
    assert_eq!(line.contains("32 side by side"), avx, "{line}");
    assert!(paths(&mixture(&["--explain", "--no-lanes"])).contains("--no-lanes"));
    // mis takes the lanes too (the same image: crates/render/tests/paths8.rs), but not through media
    let line = paths(&render(&["--explain"]));
    assert_eq!(line.contains("32 side by side"), avx, "{line}");
    assert!(line.contains("shadow ray"), "{line}");
    let smoke = paths(&["render", "cornell-smoke", "--explain"]);
    assert!(
        smoke.contains("one at a time (mis through media"),
        "{smoke}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn explain_says_through_which_glass_the_manifold_connections_go() {
    let d = dir("manifold-explain");
    let line = |args: &[&str]| {
        let out = rtl(&d, args);
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        text.lines()
            .find(|l| l.trim_start().starts_with("manifold connections"))
            .unwrap_or_else(|| panic!("no manifold line: {text}"))
            .to_string()
    };
    // The Cornell box's glass ball holds nothing, but a connection can cross it.
    let cornell = line(&["render", "cornell", "--explain"]);
    assert!(
        cornell.contains("used") && cornell.contains("across 1 clear glass sphere,"),
        "{cornell}"
    );
    assert!(!cornell.contains("holding"), "{cornell}");
    // Book 2's final scene: out of the blue sphere (and of the fogged glass ball), across the ball.
    let b2 = line(&["render", "book2-final", "--explain"]);
    assert!(b2.contains("out of 2 glass spheres holding media"), "{b2}");
    assert!(b2.contains("across 1 clear glass sphere,"), "{b2}");
    // Off by the flag, and nothing to do without glass or without emitters.
    let off = line(&["render", "cornell", "--no-manifold", "--explain"]);
    assert!(off.contains("off (--no-manifold)"), "{off}");
    assert!(line(&["render", "quads", "--explain"]).contains("skipped"));
    assert!(line(&["render", "book1-final", "--explain"]).contains("skipped"));
    let mixture = line(&["render", "cornell", "--strategy", "mixture", "--explain"]);
    assert!(mixture.contains("not used"), "{mixture}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_merge_whose_mean_a_32_bit_float_cannot_hold_writes_no_linear_file() {
    let d = dir("beyond-f32");
    ok(&d, &render(&["--part", "good"]));
    let good = Checkpoint::read(&d.join("good")).unwrap();
    // a finite sum (1e300 over 2 samples) whose mean is far beyond f32::MAX
    lying_copy(&good, Color::new(0.0, 1e300, 0.0), &d.join("huge"));
    let out = rtl(&d, &["merge", "huge", "-o", "m.png", "--linear", "m.pfm"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("pixel (x 3, y 0)") && err.contains("32-bit float"),
        "{err}"
    );
    assert!(!d.join("m.pfm").exists(), "no PFM of infinities");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_device_or_a_directory_is_no_checkpoint_and_is_not_read() {
    let d = dir("not-a-file");
    // /dev/zero would give bytes without end; a directory none
    for what in ["/dev/zero", "."] {
        refused(
            &d,
            &["merge", what, "-o", "m.png"],
            &[what, "not a regular file"],
        );
    }
    refused(
        &d,
        &render(&["--resume", "/dev/zero"]),
        &["/dev/zero", "not a regular file"],
    );
    refused(&d, &render(&["--resume", "."]), &[".", "a directory"]);
    // a pipe is refused without waiting for a writer (opening it would)
    let fifo = d.join("ck.fifo");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    refused(
        &d,
        &["merge", "ck.fifo", "-o", "m.png"],
        &["ck.fifo", "not a regular file"],
    );
    refused(
        &d,
        &render(&["--resume", "ck.fifo"]),
        &["ck.fifo", "not a regular file"],
    );
    // an I/O error is quoted once, not twice
    let out = rtl(&d, &["merge", "missing.ck", "-o", "m.png"]);
    let err = String::from_utf8_lossy(&out.stderr);
    let io = std::io::Error::from(std::io::ErrorKind::NotFound).to_string();
    assert_eq!(err.matches("os error 2").count(), 1, "{err} ({io})");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn switches_of_another_strategy_and_a_texture_no_scene_takes_are_refused() {
    let d = dir("ignored-flags");
    for flag in ["--no-rr", "--sph-rect", "--no-lds", "--no-manifold"] {
        refused(
            &d,
            &render(&["--strategy", "cosine", flag]),
            &[flag, "only the 'mis' strategy", "'cosine'"],
        );
    }
    // with mis (the default) they are taken
    ok(&d, &render(&["--no-rr", "--no-lds", "-o", "a.png"]));
    refused(
        &d,
        &render(&["--texture", "nonexistent.jpg"]),
        &[
            "--texture nonexistent.jpg",
            "`earth` and `book2-final`",
            "'cornell'",
        ],
    );
    assert!(!d.join("cornell.png").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn study_render_refuses_zero_repeats_and_a_file_as_its_directory_leaving_nothing() {
    let d = dir("study-flags");
    refused(
        &d,
        &[
            "study", "render", "--quick", "--repeat", "0", "--out", "out",
        ],
        &["--repeat 0"],
    );
    refused(
        &d,
        &["study", "render", "--quick", "--width", "0", "--out", "out"],
        &["--width 0"],
    );
    assert!(
        !d.join("out").exists(),
        "a refused study leaves no directory"
    );
    std::fs::write(d.join("afile"), "x").unwrap();
    refused(
        &d,
        &["study", "samples", "--out", "afile"],
        &["--out afile", "a file, not a directory"],
    );
    // (2^64 - 1 samples a histogram ran for ever)
    refused(
        &d,
        &[
            "study",
            "samples",
            "--samples",
            "18446744073709551615",
            "--out",
            "s",
        ],
        &["--samples 18446744073709551615: must be 1,000 to 100,000,000"],
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn time_budgets_shorter_than_a_nanosecond_are_quoted_as_given() {
    let d = dir("tiny-time");
    // (a value the flag's parser refuses is a usage error: clap's exit code 2)
    for (args, words) in [
        (render(&["--time", "1e-300"]), ["'1e-300'", "nanosecond"]),
        (
            render(&["--checkpoint-every", "1e-300"]),
            ["'1e-300'", "nanosecond"],
        ),
        (render(&["--time", "1h1h"]), ["'1h1h'", "appears twice"]),
    ] {
        let out = rtl(&d, &args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        for w in words {
            assert!(err.contains(w), "{args:?}: wanted {w:?} in {err}");
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// A scene path that is not UTF-8 is refused by name (the argument parser said only "invalid UTF-8
/// was detected in one or more arguments", naming none).
#[cfg(unix)]
#[test]
fn a_scene_path_that_is_not_utf8_is_refused_by_name() {
    use std::os::unix::ffi::OsStrExt;
    let d = dir("not-utf8");
    let bad = std::ffi::OsStr::from_bytes(b"sc\xffne.toml");
    std::fs::write(d.join(bad), scene("")).unwrap();
    let out = Command::new(common::RTL)
        .current_dir(&d)
        .arg("render")
        .arg(bad)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("SCENE 'sc\u{FFFD}ne.toml'") && err.contains("not UTF-8"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}
