//! What a scene file means, beyond whether it parses: a medium inside a quad (which bounds no volume),
//! a scene without a light, the image files a scene reads (inputs a render must not overwrite), and
//! the words of two messages.

use rtl_render::scene_file::{self, SceneFile};
use std::path::{Path, PathBuf};

const HEAD: &str = r#"[camera]
lookfrom = [0, 0, -10]
lookat = [0, 0, 0]

[materials]
white = { type = "lambertian", albedo = 0.5 }
lamp = { type = "light", emit = [4, 4, 4] }
"#;

fn load(text: &str) -> Result<SceneFile, String> {
    scene_file::load_str(text, "some/dir/s.toml", Path::new("some/dir")).map_err(|e| e.to_string())
}

#[track_caller]
fn refused(text: &str, words: &[&str]) {
    let err = match load(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    };
    for w in words {
        assert!(err.contains(w), "wanted {w:?} in: {err}");
    }
}

/// A ray enters a quad and never leaves it: a medium with a quad for its boundary rendered as
/// nothing at all, without a word. Closed boundaries still load.
#[test]
fn a_medium_inside_a_quad_is_refused_and_closed_boundaries_load() {
    let medium = |boundary: &str| {
        format!(
            "{HEAD}[[objects]]\ntype = \"medium\"\ndensity = 0.5\nalbedo = 0.5\nboundary = {boundary}\n"
        )
    };
    refused(
        &medium(
            "{ type = \"quad\", q = [-1, -1, 0], u = [2, 0, 0], v = [0, 2, 0], material = \"white\" }",
        ),
        &[
            "some/dir/s.toml:12:21",
            "field `objects[0].boundary.type`",
            "must enclose a volume",
            "a quad encloses none",
        ],
    );
    for closed in [
        "{ type = \"sphere\", center = [0, 0, 0], radius = 1, material = \"white\" }",
        "{ type = \"box\", a = [0, 0, 0], b = [1, 1, 1], material = \"white\" }",
    ] {
        load(&medium(closed)).unwrap_or_else(|e| panic!("{closed}: {e}"));
    }
}

/// A scene that can only be black (no emitter, a black background) says so; one with a light or the
/// sky does not.
#[test]
fn a_scene_that_can_only_be_black_says_why() {
    let sphere = |material: &str| {
        format!(
            "[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"{material}\"\n"
        )
    };
    let dark = load(&format!("{HEAD}{}", sphere("white"))).unwrap();
    assert_eq!(dark.built.notices.len(), 1, "{:?}", dark.built.notices);
    assert!(
        dark.built.notices[0].contains("no light") && dark.built.notices[0].contains("black"),
        "{:?}",
        dark.built.notices
    );
    let lit = load(&format!("{HEAD}{}{}", sphere("white"), sphere("lamp"))).unwrap();
    assert!(lit.built.notices.is_empty(), "{:?}", lit.built.notices);
    let sky = load(&format!(
        "[render]\nbackground = \"sky\"\n{HEAD}{}",
        sphere("white")
    ))
    .unwrap();
    assert!(sky.built.notices.is_empty(), "{:?}", sky.built.notices);
}

/// The image files of a scene's textures are reported (as found, relative to the scene file's
/// directory), so that a render refuses outputs that would overwrite them; an empty file name is
/// named as such.
#[test]
fn a_scene_file_names_the_images_it_read() {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let file = scene_file::load_file(&scenes.join("showcase.toml")).unwrap();
    assert_eq!(
        file.texture_files,
        vec![scenes.join("textures/globe.png")],
        "{:?}",
        file.texture_files
    );
    let cornell = scene_file::load_file(&scenes.join("cornell.toml")).unwrap();
    assert_eq!(cornell.texture_files, Vec::<PathBuf>::new());
    refused(
        "[textures]\nt = { type = \"image\", file = \"\" }\n[camera]\nlookfrom = [0, 0, 1]\nlookat = [0, 0, 0]\n",
        &["some/dir/s.toml:2:30", "textures.t.file", "name is empty"],
    );
}

/// "an object", "an importance target": not "a object".
#[test]
fn a_value_that_is_not_a_table_is_named_with_its_article() {
    refused(
        &format!("objects = [1]\n{HEAD}"),
        &["some/dir/s.toml:1:12", "(an object)"],
    );
    refused(
        &format!(
            "lights = [1]\n{HEAD}[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"lamp\"\n"
        ),
        &["(an importance target)"],
    );
    refused(&format!("{HEAD}[textures]\nt = 1\n"), &["(a texture)"]);
}

/// A quad's edges are placed only as finely as doubles are spaced at its largest coordinate: a floor
/// with its corner q at [-1e20, 0, 1e20] and an edge through the origin, seen from 5 away, had that
/// edge 16,000 off (at 1e16, 2), the image silently another. Refused, naming the object; a large
/// quad whose edges are all far from the camera is not, nor one at 1e12 (edges 1e-4 off).
#[test]
fn a_quad_whose_edges_cannot_be_placed_for_the_camera_is_refused() {
    let floor = |q: &str, u: &str, v: &str| {
        format!(
            "[camera]\nlookfrom = [0, 2, 5]\nlookat = [0, 0, 0]\n[materials]\n\
             w = {{ type = \"lambertian\", albedo = 0.5 }}\n[[objects]]\ntype = \"quad\"\n\
             q = {q}\nu = {u}\nv = {v}\nmaterial = \"w\"\n"
        )
    };
    for s in ["1e16", "1e20", "1e30"] {
        refused(
            &floor(
                &format!("[-{s}, 0, {s}]"),
                &format!("[{s}, 0, 0]"),
                &format!("[0, 0, -{s}]"),
            ),
            &[
                "some/dir/s.toml:6:1",
                "field `objects[0]`",
                "cannot have its edges placed finely enough",
            ],
        );
    }
    // the same through a translation that brings it from far away
    refused(
        &floor("[-1e20, 0, 1e20]", "[1e20, 0, 0]", "[0, 0, -1e20]").replace(
            "material = \"w\"\n",
            "material = \"w\"\ntransform = [{ translate = [0, 0, 0] }]\n",
        ),
        &["cannot have its edges placed"],
    );
    for (q, u, v) in [
        ("[-1e12, 0, 1e12]", "[1e12, 0, 0]", "[0, 0, -1e12]"),
        ("[-1e29, 0, -1e29]", "[2e29, 0, 0]", "[0, 0, 2e29]"),
        ("[-1, 0, 1]", "[1, 0, 0]", "[0, 0, -1]"),
    ] {
        load(&floor(q, u, v)).unwrap_or_else(|e| panic!("{q} {u} {v}: {e}"));
    }
}

/// A box is six quads, and its faces are held to the same rule (a review found the face of a box
/// reaching 1e20 with an edge through the view accepted and its edge 16,000 off); boxes of ordinary
/// size, and a large one whose faces are all far from the camera, load.
#[test]
fn a_box_whose_face_edges_cannot_be_placed_is_refused() {
    let boxed = |a: &str, b: &str| {
        format!(
            "[camera]\nlookfrom = [2, 1, 0]\nlookat = [0, 0, 0]\n[materials]\n\
             w = {{ type = \"lambertian\", albedo = 0.5 }}\n[[objects]]\ntype = \"box\"\n\
             a = {a}\nb = {b}\nmaterial = \"w\"\n"
        )
    };
    refused(
        &boxed("[-1e20, -1, -1e20]", "[0, 0, 1e20]"),
        &[
            "some/dir/s.toml:6:1",
            "box's face",
            "cannot have its edges placed",
        ],
    );
    for (a, b) in [
        ("[-10, -1, -10]", "[0, 0, 10]"),
        ("[-1e12, -1, -1e12]", "[0, 0, 1e12]"),
        ("[1e29, 1e29, 1e29]", "[2e29, 2e29, 2e29]"),
    ] {
        load(&boxed(a, b)).unwrap_or_else(|e| panic!("{a} {b}: {e}"));
    }
}

/// An instance places its group's quads again, and they are held to the same rule where it puts them:
/// a floor reaching 1e20, accepted in a group placed 1e8 below the camera, is refused where an
/// instance puts it at the camera's feet; an instance that leaves it far away loads.
#[test]
fn an_instance_whose_quads_cannot_be_placed_is_refused() {
    let scene = |up: &str| {
        format!(
            "[camera]\nlookfrom = [2, 1, 0]\nlookat = [0, 0, 0]\n[materials]\n\
             w = {{ type = \"lambertian\", albedo = 0.5 }}\n\
             [[objects]]\ntype = \"group\"\nname = \"g\"\n\
             transform = [{{ translate = [0, -1e8, 0] }}]\n\
             [[objects.objects]]\ntype = \"quad\"\nq = [-1e20, 0, -1e20]\nu = [1e20, 0, 0]\n\
             v = [0, 0, 2e20]\nmaterial = \"w\"\n\
             [[objects]]\ntype = \"instance\"\nof = \"g\"\n\
             transform = [{{ translate = [0, {up}, 0] }}]\n"
        )
    };
    load(&scene("-2e8")).unwrap_or_else(|e| panic!("{e}"));
    refused(
        &scene("0"),
        &[
            "some/dir/s.toml:16:1",
            "objects[1]",
            "cannot have its edges placed",
        ],
    );
}
