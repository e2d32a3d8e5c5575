//! Hostile input to `rtl render` and `rtl study render` that earlier reviews missed: outputs that
//! would overwrite a scene file's own textures, a file in the directory named as a built-in scene (the
//! checkpoint of `--checkpoint cornell`), time budgets longer than a `Duration` holds, a scene without
//! a light, and a damaged cached reference. Each is refused before any work with a message naming the
//! problem and the place, or rendered, never a panic or a silently destroyed input.

mod common;

use common::{dir, ok, refused_with, rtl};
use std::path::Path;

/// A 2 x 2 PNG of one grey (a texture).
fn png(path: &Path) {
    let img = image::RgbImage::from_pixel(2, 2, image::Rgb([128, 128, 128]));
    img.save(path).unwrap();
}

/// A scene of one sphere of material `w` under the sky, and `extra` (textures, materials).
fn scene(extra: &str, albedo: &str, background: &str) -> String {
    format!(
        "{extra}\n[render]\nwidth = 8\nspp = 1\nbackground = {background}\n[camera]\n\
         lookfrom = [0, 0, -5]\nlookat = [0, 0, 0]\n[materials]\n\
         w = {{ type = \"lambertian\", albedo = {albedo} }}\n[[objects]]\ntype = \"sphere\"\n\
         center = [0, 0, 0]\nradius = 1\nmaterial = \"w\"\n"
    )
}

/// A scene file's image textures are inputs: `-o textures/globe.png` had overwritten the scene's own
/// texture with the render (exit code 0), as `--checkpoint` would have too; only the scene file and
/// `--texture` were checked.
#[test]
fn no_output_overwrites_a_texture_the_scene_file_reads() {
    let d = dir("texture");
    std::fs::create_dir_all(d.join("textures")).unwrap();
    png(&d.join("textures/globe.png"));
    let before = std::fs::read(d.join("textures/globe.png")).unwrap();
    let text = scene(
        "[textures]\nglobe = { type = \"image\", file = \"textures/globe.png\" }",
        "\"globe\"",
        "\"sky\"",
    );
    std::fs::write(d.join("s.toml"), text).unwrap();
    ok(&d, &["render", "s.toml", "-o", "out.png"]);
    for (flag, path) in [
        ("-o", "textures/globe.png"),
        ("-o", "./textures/../textures/globe.png"),
        ("--checkpoint", "textures/globe.png"),
    ] {
        let mut args = vec!["render", "s.toml"];
        if flag != "-o" {
            args.extend(["-o", "x.png"]);
        }
        args.extend([flag, path]);
        refused_with(
            &d,
            1,
            &args,
            &[
                &format!("{flag} {path} is also an input"),
                "the scene's texture textures/globe.png",
            ],
        );
    }
    assert_eq!(std::fs::read(d.join("textures/globe.png")).unwrap(), before);
    // an empty file name is named as such, not "texture file  not found"
    let text = scene(
        "[textures]\nglobe = { type = \"image\", file = \"\" }",
        "\"globe\"",
        "\"sky\"",
    );
    std::fs::write(d.join("empty.toml"), text).unwrap();
    refused_with(
        &d,
        1,
        &["render", "empty.toml"],
        &["empty.toml:2:34", "textures.globe.file", "name is empty"],
    );
    // (and an object that is not a table is "an object", not "a object")
    let text = "objects = [1]\n[camera]\nlookfrom = [0, 0, -5]\nlookat = [0, 0, 0]\n";
    std::fs::write(d.join("one.toml"), text).unwrap();
    refused_with(
        &d,
        1,
        &["render", "one.toml"],
        &["one.toml:1:12", "(an object)"],
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A built-in scene's bare name is the built-in even where a file of that name is in the directory:
/// `rtl render cornell --checkpoint cornell` and then `--resume cornell` had read the checkpoint as
/// the scene file (`cornell:1:13: not UTF-8 text`). `./NAME` still names the file, and a file that
/// is not one of the render's own is pointed out.
#[test]
fn a_built_in_name_is_the_built_in_even_beside_a_file_of_that_name() {
    let d = dir("name");
    let small = ["--width", "8", "--spp", "1"];
    let mut first = vec!["render", "cornell", "--checkpoint", "cornell"];
    first.extend(small);
    ok(&d, &first);
    let err = ok(
        &d,
        &[
            "render", "cornell", "--width", "8", "--spp", "2", "--resume", "cornell",
        ],
    );
    assert!(err.contains("resuming cornell at 1 spp"), "{err}");
    assert!(!err.contains("note: 'cornell'"), "{err}");
    // the same checkpoint written `./cornell`: still one's own, no note (a review found the note)
    let err = ok(
        &d,
        &[
            "render",
            "cornell",
            "--width",
            "8",
            "--spp",
            "3",
            "--resume",
            "./cornell",
        ],
    );
    assert!(!err.contains("note: 'cornell'"), "{err}");
    // a scene file named as a built-in: the built-in, with a note; ./quads is the file
    std::fs::write(d.join("quads"), scene("", "0.5", "\"sky\"")).unwrap();
    let mut args = vec!["render", "quads", "-o", "a.png"];
    args.extend(small);
    let err = ok(&d, &args);
    assert!(
        err.contains("note: 'quads' is the built-in scene") && err.contains("./quads"),
        "{err}"
    );
    let mut args = vec!["render", "./quads", "-o", "b.png"];
    args.extend(small);
    let err = ok(&d, &args);
    assert!(!err.contains("note:"), "{err}");
    assert_ne!(
        std::fs::read(d.join("a.png")).unwrap(),
        std::fs::read(d.join("b.png")).unwrap()
    );
    // (--texture goes with the built-in earth, not with a file that happens to be named earth)
    std::fs::write(d.join("earth"), "not a scene").unwrap();
    png(&d.join("t.png"));
    let mut args = vec!["render", "earth", "--texture", "t.png", "-o", "e.png"];
    args.extend(small);
    ok(&d, &args);
    // and its error names the flag
    refused_with(
        &d,
        1,
        &["render", "earth", "--texture", "nope.png"],
        &["--texture nope.png: cannot read texture file"],
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A time longer than a `Duration` holds is no deadline, as shorter ones past the end of time are
/// (it had been refused as "not a duration"); a negative one says so.
#[test]
fn time_budgets_past_what_a_duration_holds_are_no_deadline_and_negative_ones_are_named() {
    let d = dir("time");
    for long in ["18446744073709551615", "1e30", "1000000000000000d"] {
        ok(
            &d,
            &[
                "render", "cornell", "--width", "8", "--spp", "1", "--time", long,
            ],
        );
    }
    refused_with(
        &d,
        2,
        &["render", "cornell", "--width", "8", "--time=-5"],
        &["'-5' is negative"],
    );
    refused_with(
        &d,
        2,
        &[
            "render",
            "cornell",
            "--width",
            "8",
            "--checkpoint-every=-1s",
        ],
        &["'-1s' is negative"],
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A scene file with no emitter under a black background renders black, as it should, but says why.
#[test]
fn a_scene_without_a_light_says_its_image_is_black() {
    let d = dir("dark");
    std::fs::write(d.join("dark.toml"), scene("", "0.5", "[0, 0, 0]")).unwrap();
    let err = ok(&d, &["render", "dark.toml"]);
    assert!(
        err.contains("note: the scene has no light") && err.contains("the image is black"),
        "{err}"
    );
    std::fs::write(d.join("sky.toml"), scene("", "0.5", "\"sky\"")).unwrap();
    let err = ok(&d, &["render", "sky.toml"]);
    assert!(!err.contains("no light"), "{err}");
    let _ = std::fs::remove_dir_all(&d);
}

/// A damaged cached reference of `rtl study render` (and the lab) is refused, naming the file and
/// the problem: a header of 2^31 x 2^31 pixels had panicked (capacity overflow, exit 101), and a
/// reference of NaN had been trusted, every RMSE against it NaN.
#[test]
fn a_damaged_cached_reference_is_refused_not_a_panic() {
    let d = dir("reference");
    let name = "render-reference-cornell-48-1024.pfm";
    let mut nan = b"PF\n48 48\n-1.0\n".to_vec();
    for _ in 0..48 * 48 * 3 {
        nan.extend_from_slice(&f32::NAN.to_le_bytes());
    }
    for (bytes, words) in [
        (
            b"PF\n2147483648 2147483648\n-1.0\n".to_vec(),
            &["pixel data where 2147483648 x 2147483648 pixels take"][..],
        ),
        (nan, &["pixel (x 0, y 47) is NaN", "finite"][..]),
    ] {
        std::fs::write(d.join(name), bytes).unwrap();
        let mut w = vec![name, "damaged reference"];
        w.extend(words);
        refused_with(&d, 1, &["study", "render", "--quick", "--out", "."], &w);
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// An output named with a trailing `/` is refused before the render: `-o out.png/` had passed the
/// checks (its file name is `out.png`), rendered, and failed on renaming the image into place (`Not a
/// directory`); with `--linear out.pfm/` the PNG was written and the PFM not.
#[test]
fn an_output_whose_name_ends_in_a_slash_is_refused_before_the_render() {
    let d = dir("slash");
    let render = |extra: &[&'static str]| {
        let mut v = vec!["render", "cornell", "--width", "8", "--spp", "1"];
        v.extend_from_slice(extra);
        v
    };
    for (args, flag) in [
        (render(&["-o", "out.png/"]), "-o out.png/"),
        (
            render(&["-o", "o.png", "--linear", "o.pfm/"]),
            "--linear o.pfm/",
        ),
        (
            render(&["-o", "o.png", "--checkpoint", "ck/"]),
            "--checkpoint ck/",
        ),
        // (a review found these: the file name of `out.png/.` reads `out.png`)
        (render(&["-o", "out.png/."]), "-o out.png/."),
        (
            render(&["-o", "o.png", "--linear", "o.pfm/.."]),
            "--linear o.pfm/..",
        ),
    ] {
        refused_with(&d, 1, &args, &[flag, "names a directory"]);
    }
    assert!(std::fs::read_dir(&d).unwrap().next().is_none());
    ok(&d, &render(&["--part", "p.ck", "-o", "p.png"]));
    refused_with(
        &d,
        1,
        &["merge", "p.ck", "-o", "m.png", "--linear", "m.pfm/"],
        &["--linear m.pfm/", "names a directory"],
    );
    assert!(!d.join("m.png").exists());
    let _ = std::fs::remove_dir_all(&d);
}

/// `rtl lab --reference-dir` naming a file (or a path under one) is refused at the start: the lab had
/// started, rendered a reference for the page and shown `no reference: File exists (os error 17)`.
#[test]
fn the_lab_refuses_a_reference_dir_that_is_a_file() {
    let d = dir("labdir");
    std::fs::write(d.join("f"), "").unwrap();
    for (arg, file) in [("f", "f"), ("f/refs", "f"), ("/dev/null", "/dev/null")] {
        refused_with(
            &d,
            1,
            &["lab", "--port", "0", "--reference-dir", arg],
            &[
                &format!("--reference-dir {arg}: {file} is not a directory"),
                "caches its references",
            ],
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// `rtl bench noise` given one render twice measured its noise against itself: c = 0, as if the
/// renderer had none. The same file is refused; two equal files are measured, with a note.
#[test]
fn bench_noise_refuses_one_render_twice() {
    let d = dir("noise");
    ok(
        &d,
        &[
            "render", "cornell", "--width", "8", "--spp", "2", "-o", "a.png", "--linear", "a.pfm",
        ],
    );
    refused_with(
        &d,
        1,
        &["bench", "noise", "--spp", "2", "a.pfm", "./a.pfm"],
        &["a.pfm", "the same file twice"],
    );
    std::fs::copy(d.join("a.pfm"), d.join("b.pfm")).unwrap();
    let out = rtl(&d, &["bench", "noise", "--spp", "2", "a.pfm", "b.pfm"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("c 0.0000") && text.contains("equal"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&d);
}
