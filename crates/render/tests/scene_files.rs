//! Scene files: the shipped examples load and render, `scenes/cornell.toml` is the built-in `cornell`
//! exactly, and every kind of bad input is an error naming the file, the line and the field.

use rtl_render::integrator::Strategy;
use rtl_render::render::{RenderSettings, render};
use rtl_render::scene::{Background, ImportanceTarget};
use rtl_render::scene_file::{self, SceneFile};
use rtl_render::scenes;
use rtl_render::vec::{Point3, Vec3};
use std::path::{Path, PathBuf};

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

fn settings(width: usize, seed: u64, max_depth: u32) -> RenderSettings {
    RenderSettings {
        width,
        max_depth,
        seed,
        strategy: Strategy::Cosine,
        mixture_weight: rtl_render::render::BOOK_MIXTURE_WEIGHT,
    }
}

#[test]
fn cornell_toml_is_the_built_in_cornell_box() {
    let file = scene_file::load_file(&scenes_dir().join("cornell.toml")).unwrap();
    let ours = &file.built.scene;
    let builtin = (scenes::find("cornell").unwrap().build)(&Default::default()).unwrap();
    let theirs = &builtin.scene;
    assert_eq!(ours.camera, theirs.camera);
    assert_eq!(ours.background, theirs.background);
    assert_eq!(ours.max_depth, theirs.max_depth);
    assert_eq!(ours.features, theirs.features);
    assert_eq!(ours.targets.len(), 2);
    // The same target shapes (material indices may differ: materials are created in file order).
    for (a, b) in ours.targets.iter().zip(&theirs.targets) {
        match (a, b) {
            (ImportanceTarget::Quad(a), ImportanceTarget::Quad(b)) => {
                assert_eq!((a.q, a.u, a.v, a.normal), (b.q, b.u, b.v, b.normal))
            }
            (ImportanceTarget::Sphere(a), ImportanceTarget::Sphere(b)) => {
                assert_eq!((a.center, a.radius), (b.center, b.radius))
            }
            _ => panic!("targets differ: {a:?} vs {b:?}"),
        }
    }
    assert_eq!(
        ours.groups
            .iter()
            .map(|g| g.objects.len())
            .collect::<Vec<_>>(),
        theirs
            .groups
            .iter()
            .map(|g| g.objects.len())
            .collect::<Vec<_>>()
    );
    assert_eq!((file.width, file.spp), (Some(600), Some(100)));
    // Built in the same order, the two render bit-identical images.
    let st = settings(24, 11, 50);
    let (a, _) = render(ours, st, 4);
    let (b, _) = render(theirs, st, 4);
    assert_eq!(a, b);
}

#[test]
fn the_book_scene_files_render_like_their_built_ins() {
    for name in ["cornell-smoke", "simple-light", "quads"] {
        let file = scene_file::load_file(&scenes_dir().join(format!("{name}.toml"))).unwrap();
        let builtin = (scenes::find(name).unwrap().build)(&Default::default()).unwrap();
        let (ours, theirs) = (&file.built.scene, &builtin.scene);
        assert_eq!(ours.camera, theirs.camera, "{name}");
        assert_eq!(ours.background, theirs.background, "{name}");
        assert_eq!(ours.features, theirs.features, "{name}");
        let st = settings(16, 5, ours.max_depth);
        assert_eq!(render(ours, st, 2).0, render(theirs, st, 2).0, "{name}");
    }
}

#[test]
fn every_shipped_scene_file_loads_and_renders_finite_pixels() {
    let mut n = 0;
    for entry in std::fs::read_dir(scenes_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        n += 1;
        let file = scene_file::load_file(&path).unwrap_or_else(|e| panic!("{e}"));
        let scene = &file.built.scene;
        let (acc, stats) = render(scene, settings(16, 1, scene.max_depth), 2);
        let image = acc.image();
        assert_eq!(stats.samples, (acc.width * acc.height * 2) as u64);
        assert!(
            image.iter().all(|c| c.is_finite()),
            "{}: non-finite pixels",
            path.display()
        );
        let mean: f64 = image.iter().map(|c| c.element_sum()).sum::<f64>() / image.len() as f64;
        assert!(mean > 0.0, "{}: black image", path.display());
    }
    assert!(
        n >= 4,
        "expected at least four example scene files, found {n}"
    );
}

#[test]
fn the_showcase_uses_every_feature() {
    let file = scene_file::load_file(&scenes_dir().join("showcase.toml")).unwrap();
    let f = file.built.scene.features;
    assert!(f.defocus && f.motion, "{f:?}");
    assert_eq!(f.media, 1);
    assert_eq!(f.textures, 3, "checker, marble and image");
    assert_eq!(f.targets, 2);
    assert!(f.one_sided_emitters);
    assert_eq!(file.built.scene.background, Background::Sky);
}

const BASE: &str = r#"[camera]
lookfrom = [0, 0, 5]
lookat = [0, 0, 0]

[materials]
white = { type = "lambertian", albedo = 0.73 }

[[objects]]
type = "sphere"
name = "ball"
center = [0, 0, 0]
radius = 1
material = "white"
"#;

fn load(text: &str) -> Result<SceneFile, String> {
    scene_file::load_str(text, "some/dir/bad.toml", Path::new("some/dir"))
        .map_err(|e| e.to_string())
}

/// The error for `text`, which must name the file, `line` and `field`, and contain `words`.
#[track_caller]
fn error_at(text: &str, line: usize, field: &str, words: &str) {
    let err = match load(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    };
    let place = format!("some/dir/bad.toml:{line}:");
    assert!(err.starts_with(&place), "wanted {place}, got: {err}");
    if !field.is_empty() {
        assert!(
            err.contains(&format!("field `{field}`: ")),
            "wanted field {field}, got: {err}"
        );
    }
    assert!(err.contains(words), "wanted '{words}', got: {err}");
}

#[test]
fn the_base_scene_loads() {
    let f = load(BASE).unwrap();
    assert_eq!(f.built.scene.groups[0].objects.len(), 1);
    assert_eq!((f.width, f.spp, f.description), (None, None, None));
}

#[test]
fn a_syntax_error_names_the_line() {
    error_at("not = a [scene\n", 1, "", "");
    error_at(&format!("{BASE}radius = = 2\n"), 14, "", "");
}

#[test]
fn an_unknown_material_lists_the_known_ones() {
    error_at(
        &BASE.replace("material = \"white\"", "material = \"whit\""),
        13,
        "objects[0].material",
        "unknown material `whit`; known materials: `white`",
    );
}

/// A name that reads like a known one but holds a character that shows as nothing (a zero-width
/// joiner, a byte-order mark) is written out in the message, the known names too: otherwise
/// "unknown material `marble`; known materials: `marble`" reads as a contradiction.
#[test]
fn invisible_characters_in_names_are_written_out_in_messages() {
    error_at(
        &BASE.replace("material = \"white\"", "material = \"wh\\u200Dite\""),
        13,
        "objects[0].material",
        "unknown material `wh\\u{200D}ite`; known materials: `white`",
    );
    let twice = BASE.replace("white = {", "\"white\\uFEFF\" = {");
    error_at(
        &twice,
        13,
        "objects[0].material",
        "unknown material `white`; known materials: `white\\u{FEFF}`",
    );
    let Err(err) = load(&format!(
        "{BASE}[[objects]]\ntype = \"instance\"\nof = \"bo\\u200Bx\"\n"
    )) else {
        panic!("an instance of an unknown group loaded");
    };
    assert!(
        err.contains("`bo\\u{200B}x` is not a group or box"),
        "{err}"
    );
    assert!(!err.contains('\u{200B}'), "{err}");
}

#[test]
fn an_unknown_texture_is_an_error() {
    error_at(
        &BASE.replace("albedo = 0.73", "albedo = \"tiles\""),
        6,
        "materials.white.albedo",
        "unknown texture `tiles`",
    );
}

#[test]
fn a_negative_or_zero_radius_is_an_error() {
    for r in ["-1", "0", "-0.0"] {
        error_at(
            &BASE.replace("radius = 1", &format!("radius = {r}")),
            12,
            "objects[0].radius",
            "radius must be positive",
        );
    }
}

#[test]
fn a_zero_area_quad_is_an_error() {
    let text = format!(
        "{BASE}\n[[objects]]\ntype = \"quad\"\nq = [0, 0, 0]\nu = [1, 0, 0]\nv = [-2, 0, 0]\nmaterial = \"white\"\n"
    );
    error_at(&text, 18, "objects[1].u", "zero-area quad: u x v = 0");
    let text = text.replace("v = [-2, 0, 0]", "v = [0, 0, 0]");
    error_at(&text, 19, "objects[1].v", "zero-area quad");
}

#[test]
fn nan_and_infinite_values_are_errors() {
    error_at(
        &BASE.replace("radius = 1", "radius = nan"),
        12,
        "objects[0].radius",
        "not a finite number",
    );
    error_at(
        &BASE.replace("center = [0, 0, 0]", "center = [0, -inf, 0]"),
        11,
        "objects[0].center[1]",
        "-inf is not a finite number",
    );
    error_at(
        &BASE.replace("albedo = 0.73", "albedo = [0.5, nan, 0.5]"),
        6,
        "materials.white.albedo[1]",
        "not a finite number",
    );
}

#[test]
fn a_missing_texture_file_is_an_error_relative_to_the_scene_file() {
    let text = BASE.replace(
        "[materials]",
        "[textures]\nmap = { type = \"image\", file = \"maps/earth.png\" }\n\n[materials]",
    );
    error_at(&text, 6, "textures.map.file", "not found");
    let err = load(&text).err().unwrap();
    assert!(
        err.contains(&format!(
            "{}",
            Path::new("some/dir").join("maps/earth.png").display()
        )),
        "{err}"
    );
}

#[test]
fn an_image_texture_is_found_next_to_the_scene_file() {
    let dir = std::env::temp_dir().join(format!("rtl-scene-file-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("maps")).unwrap();
    let img = image::RgbImage::from_fn(4, 2, |x, _| image::Rgb([x as u8 * 60, 100, 200]));
    img.save(dir.join("maps/tiny.png")).unwrap();
    let text = BASE
        .replace(
            "[materials]",
            "[textures]\nmap = { type = \"image\", file = \"maps/tiny.png\" }\n\n[materials]",
        )
        .replace("albedo = 0.73", "albedo = \"map\"");
    let path = dir.join("scene.toml");
    std::fs::write(&path, &text).unwrap();
    let file = scene_file::load_file(&path);
    std::fs::remove_dir_all(&dir).unwrap();
    let file = file.unwrap();
    assert_eq!(file.built.scene.features.textures, 1);
    let (acc, _) = render(&file.built.scene, settings(8, 1, 8), 1);
    assert!(acc.image().iter().all(|c| c.is_finite()));
}

#[test]
fn wrong_types_are_errors() {
    error_at(
        &BASE.replace("radius = 1", "radius = \"big\""),
        12,
        "objects[0].radius",
        "invalid type: string \"big\", expected a finite number",
    );
    error_at(
        &BASE.replace("center = [0, 0, 0]", "center = [0, 0]"),
        11,
        "objects[0].center",
        "3 numbers",
    );
    error_at(
        &BASE.replace("lookat = [0, 0, 0]", "lookat = \"origin\""),
        3,
        "camera.lookat",
        "expected a vector [x, y, z]",
    );
    error_at(
        &BASE.replace("material = \"white\"", "material = 3"),
        13,
        "objects[0].material",
        "invalid type",
    );
}

#[test]
fn unknown_object_types_and_fields_are_errors() {
    error_at(
        &BASE.replace("type = \"sphere\"", "type = \"cone\""),
        9,
        "objects[0].type",
        "unknown object type `cone`; known types: sphere, moving_sphere, quad, box",
    );
    error_at(
        &BASE.replace("radius = 1", "radius = 1\nradios = 2"),
        13,
        "objects[0].radios",
        "unknown field `radios`",
    );
    error_at(
        &BASE.replace("type = \"lambertian\"", "type = \"lambertain\""),
        6,
        "materials.white.type",
        "unknown material type `lambertain`",
    );
    error_at(
        &format!("{BASE}\n[stuff]\nx = 1\n"),
        15,
        "stuff",
        "unknown field `stuff`",
    );
    error_at(
        &format!("{BASE}lights = [\"ball\"]\n"),
        14,
        "objects[0].lights",
        "top-level keys must come before the first [table]",
    );
}

#[test]
fn missing_fields_are_named() {
    error_at(
        &BASE.replace("radius = 1\n", ""),
        8,
        "objects[0].radius",
        "missing field `radius`",
    );
    error_at(
        &BASE.replace("type = \"sphere\"\n", ""),
        8,
        "objects[0].type",
        "missing field `type`",
    );
}

#[test]
fn an_empty_scene_is_an_error() {
    let without_objects = &BASE[..BASE.find("[[objects]]").unwrap()];
    error_at(without_objects, 1, "", "the scene has no objects");
    error_at(
        &format!("objects = []\n{without_objects}"),
        1,
        "objects",
        "the scene has no objects",
    );
}

#[test]
fn a_bad_camera_is_an_error() {
    error_at(
        &BASE.replace("lookat = [0, 0, 0]", "lookat = [0, 0, 5]"),
        3,
        "camera.lookat",
        "lookfrom and lookat are the same point",
    );
    error_at(
        &BASE.replace("lookat = [0, 0, 0]", "lookat = [0, 0, 0]\nvup = [0, 0, -3]"),
        4,
        "camera.vup",
        "parallel to the view direction",
    );
    error_at(
        &BASE.replace("[camera]", "[camera]\nvfov = 180"),
        2,
        "camera.vfov",
        "vfov must lie in (0, 180)",
    );
    // A focus distance below 1e-30, like every quantity that must be positive: its rays' squared
    // lengths would underflow (it was taken down to 5e-324, and the image was the background).
    for (focus, words) in [
        ("1e-31", "focus_dist must be at least 1e-30, got 1e-31"),
        ("5e-324", "focus_dist must be at least 1e-30"),
        ("-0.0", "focus_dist must be positive"),
    ] {
        error_at(
            &BASE.replace("[camera]", &format!("[camera]\nfocus_dist = {focus}")),
            2,
            "camera.focus_dist",
            words,
        );
    }
    error_at(
        &BASE.replace("[camera]", "[camera]\nshutter = [1, 0.5]"),
        2,
        "camera.shutter",
        "closes",
    );
    error_at(
        &BASE.replace("[camera]\n", "[view]\n"),
        1,
        "view",
        "unknown field `view`",
    );
    error_at(
        &BASE.replace("lookfrom = [0, 0, 5]\n", ""),
        1,
        "camera.lookfrom",
        "missing field `lookfrom`",
    );
}

#[test]
fn bad_render_defaults_are_errors() {
    error_at(
        &format!("[render]\nspp = 0\n{BASE}"),
        2,
        "render.spp",
        "spp must be at least 1",
    );
    error_at(
        &format!("[render]\nwidth = -4\n{BASE}"),
        2,
        "render.width",
        "invalid value",
    );
    error_at(
        &format!("[render]\naspect = \"16:0\"\n{BASE}"),
        2,
        "render.aspect",
        "ratio",
    );
    error_at(
        &format!("[render]\nbackground = \"dusk\"\n{BASE}"),
        2,
        "render.background",
        "\"sky\" or a colour",
    );
}

#[test]
fn bad_references_between_objects_are_errors() {
    error_at(
        &format!("lights = [\"lamp\"]\n{BASE}"),
        1,
        "lights[0]",
        "no object is named `lamp`; known named spheres and quads: `ball`",
    );
    error_at(
        &format!("{BASE}\n[[objects]]\ntype = \"instance\"\nof = \"ball\"\n"),
        17,
        "objects[1].of",
        "`ball` is not a group or box",
    );
    error_at(
        &format!(
            "{BASE}\n[[objects]]\ntype = \"sphere\"\nname = \"ball\"\ncenter = [3, 0, 0]\nradius = 1\nmaterial = \"white\"\n"
        ),
        17,
        "objects[1].name",
        "the name `ball` is already used",
    );
    error_at(
        &format!("{BASE}\n[[objects]]\ntype = \"group\"\n"),
        15,
        "objects[1]",
        "a group needs at least one object",
    );
    error_at(
        &format!("{BASE}\n[[objects]]\ntype = \"medium\"\ndensity = 1\nalbedo = 1\n"),
        15,
        "objects[1].boundary",
        "missing field `boundary`",
    );
    error_at(
        &format!(
            "{BASE}\n[[objects]]\ntype = \"medium\"\ndensity = 0\nalbedo = 1\nboundary = {{ type = \"sphere\", center = [0, 0, 0], radius = 1, material = \"white\" }}\n"
        ),
        17,
        "objects[1].density",
        "density must be positive",
    );
    error_at(
        &format!(
            "{BASE}\n[[objects]]\ntype = \"box\"\na = [0, 0, 0]\nb = [1, 0, 1]\nmaterial = \"white\"\n"
        ),
        18,
        "objects[1].b",
        "the box is flat",
    );
    error_at(
        &format!("{BASE}transform = [{{ rotate_w = 3 }}]\n"),
        14,
        "objects[0].transform[0].rotate_w",
        "unknown variant `rotate_w`",
    );
}

#[test]
fn transforms_apply_in_order_and_reach_the_importance_targets() {
    let text = BASE.replace(
        "[[objects]]",
        "[[objects]]\ntype = \"quad\"\nname = \"lamp\"\nq = [1, 0, 0]\nu = [1, 0, 0]\nv = [0, 0, 1]\nmaterial = \"white\"\ntransform = [{ rotate_y = 90 }, { translate = [0, 5, 0] }]\n\n[[objects]]",
    );
    let text = format!("lights = [\"lamp\", \"ball\"]\n{text}");
    let scene = load(&text).unwrap().built.scene;
    let ImportanceTarget::Quad(q) = scene.targets[0] else {
        panic!("{:?}", scene.targets[0])
    };
    // rotate_y(90) takes x to -z; then up by 5.
    let close = |a: Vec3, b: Vec3| (a - b).length() < 1e-12;
    assert!(close(q.q, Point3::new(0.0, 5.0, -1.0)), "{:?}", q.q);
    assert!(close(q.u, Vec3::new(0.0, 0.0, -1.0)), "{:?}", q.u);
    assert!(close(q.v, Vec3::new(1.0, 0.0, 0.0)), "{:?}", q.v);
    assert!(matches!(scene.targets[1], ImportanceTarget::Sphere(s) if s.radius == 1.0));
}

#[test]
fn the_shutter_maps_motion_onto_the_cameras_time_interval() {
    let moving = BASE.replace(
        "type = \"sphere\"\nname = \"ball\"\ncenter = [0, 0, 0]",
        "type = \"moving_sphere\"\ncenter0 = [0, 0, 0]\ncenter1 = [2, 0, 0]",
    );
    let scene = load(&moving).unwrap().built.scene;
    assert!(scene.features.motion);
    // Open for no time at all: nothing moves, and no time samples are drawn.
    let still = moving.replace("[camera]", "[camera]\nshutter = [0.5, 0.5]");
    let scene = load(&still).unwrap().built.scene;
    assert!(!scene.features.motion);
    let half = moving.replace("[camera]", "[camera]\nshutter = [0.5, 1]");
    let scene = load(&half).unwrap().built.scene;
    let rtl_render::scene::Object::Sphere(s) = scene.groups[0].objects[0] else {
        panic!()
    };
    assert_eq!(s.center_at(0.0), Point3::new(1.0, 0.0, 0.0));
    assert_eq!(s.center_at(1.0), Point3::new(2.0, 0.0, 0.0));
}

#[test]
fn no_error_panics_on_garbage() {
    // Every prefix of a valid file either loads or is an error naming the file.
    let text = std::fs::read_to_string(scenes_dir().join("showcase.toml")).unwrap();
    let path = scenes_dir().join("showcase.toml");
    for end in (0..text.len()).step_by(7) {
        if !text.is_char_boundary(end) {
            continue;
        }
        if let Err(e) =
            scene_file::load_str(&text[..end], &path.display().to_string(), &scenes_dir())
        {
            assert!(
                e.to_string().starts_with(&path.display().to_string()),
                "{e}"
            );
        }
    }
}

#[test]
fn an_inline_target_is_never_an_emitter_whatever_material_comes_first() {
    // The first material declared is a light: an inline target (a shape only to aim at) must not take
    // it for its own, or `mis` would aim shadow rays at a glass ball.
    let text = BASE.replace(
        "[materials]\n",
        "[materials]\nlamp = { type = \"light\", emit = [4, 4, 4] }\n",
    );
    let text =
        format!("lights = [{{ type = \"sphere\", center = [0, 0, 0], radius = 1 }}]\n{text}");
    let scene = load(&text).unwrap().built.scene;
    let lights = rtl_render::lights::Lights::new(&scene, false);
    assert_eq!(
        (lights.all.len(), lights.emitters.len(), lights.others.len()),
        (1, 0, 1)
    );
}

#[test]
fn the_scene_hash_is_of_the_content_not_of_the_text() {
    use rtl_render::checkpoint::scene_hash;
    let text = std::fs::read_to_string(scenes_dir().join("cornell.toml")).unwrap();
    let a = scene_hash(&load(&text).unwrap().built.scene);
    // Comments and blank lines are not content; a moved light is.
    let commented = format!("# a comment\n\n{text}");
    assert_eq!(scene_hash(&load(&commented).unwrap().built.scene), a);
    let builtin = (scenes::find("cornell").unwrap().build)(&Default::default()).unwrap();
    assert_eq!(scene_hash(&builtin.scene), a);
    let moved = text.replacen("213", "214", 1);
    assert_ne!(moved, text);
    assert_ne!(scene_hash(&load(&moved).unwrap().built.scene), a);
}

#[test]
fn nesting_past_the_toml_readers_limit_is_an_error_not_a_stack_overflow() {
    let mut text = BASE.to_string();
    let mut path = String::from("objects");
    for _ in 0..400 {
        text.push_str(&format!("[[{path}]]\ntype = \"group\"\n"));
        path.push_str(".objects");
    }
    let e = load(&text).err().expect("refused");
    assert!(
        e.starts_with("some/dir/bad.toml:") && e.contains("deeper"),
        "{e}"
    );
    // Inline nesting too.
    let inline = format!("{BASE}\nx = {}1{}\n", "[".repeat(5000), "]".repeat(5000));
    assert!(load(&inline).is_err());
}

#[test]
fn albedos_above_one_are_refused_where_they_stand() {
    // Above 1 a path's throughput grows with every bounce until it overflows to non-finite samples.
    error_at(
        &BASE.replace("albedo = 0.73", "albedo = 1e30"),
        6,
        "materials.white.albedo",
        "[0, 1]",
    );
    let metal = BASE.replace(
        "white = { type = \"lambertian\", albedo = 0.73 }",
        "white = { type = \"metal\", albedo = [0.5, 2, 0.5] }",
    );
    error_at(&metal, 6, "materials.white.albedo", "[0, 1]");
    let checker = BASE
        .replace(
            "[materials]",
            "[textures]\nt = { type = \"checker\", scale = 1, even = 0.5, odd = 3 }\n\n[materials]",
        )
        .replace("albedo = 0.73", "albedo = \"t\"");
    assert!(load(&checker).err().unwrap().contains("[0, 1]; got 3"));
    // Emission is not a reflectance.
    let bright = BASE.replace(
        "[materials]\n",
        "[materials]\nlamp = { type = \"light\", emit = [1e6, 1e6, 1e6] }\n",
    );
    assert!(load(&bright).is_ok());
}

#[test]
fn a_control_character_in_a_name_or_description_is_an_error() {
    // An escape sequence in a description would act on the terminal `--explain` prints it to.
    error_at(
        &format!("description = \"red \\u001b[31m\"\n{BASE}"),
        1,
        "description",
        "control character (U+001B)",
    );
    // In a key (quoted), at any depth, and in a name: the same.
    let lines = BASE.lines().count();
    error_at(
        &format!("{BASE}\"ra\\u009bdius\" = 1\n"),
        lines + 1,
        "",
        "control character (U+009B) in a key",
    );
    // The refusal names the key's field without sending what it refuses to the terminal: an
    // escape sequence in a key of an object was printed raw in `field `objects[1].ESC[2J``.
    let keyed = format!(
        "{BASE}\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n\
         material = \"white\"\n\"\\u001b[2J\" = 1\n"
    );
    let Err(e) = load(&keyed) else {
        panic!("a key with an escape sequence loaded")
    };
    assert!(!e.chars().any(|c| c == '\u{1b}'), "{e:?}");
    assert!(e.contains("field `objects[1].\\u{001B}[2J`"), "{e}");
    // A right-to-left override reorders how the rest of a line reads ("Trojan Source"): refused
    // like a control character.
    error_at(
        &format!("description = \"abc \\u202E fed\"\n{BASE}"),
        1,
        "description",
        "a bidirectional control (U+202E) in a string",
    );
    // Tabs and line ends are text.
    load(&format!(
        "description = \"\"\"two\tlines\r\nof it\"\"\"\n{BASE}"
    ))
    .unwrap();
}

#[test]
fn a_sphere_too_large_to_place_for_the_camera_is_an_error() {
    // A floor of radius 1e17 under a camera 5 from what it looks at: doubles there are 16 apart, and
    // the image came out black. Refused, at the radius.
    let floor = |r: &str| {
        format!(
            "{BASE}\n[[objects]]\ntype = \"sphere\"\ncenter = [0, -{r}, 0]\nradius = {r}\nmaterial = \"white\"\n"
        )
    };
    let line = BASE.lines().count() + 5;
    error_at(
        &floor("1e17"),
        line,
        "objects[1].radius",
        "cannot be placed finely enough",
    );
    // A floor of radius 1e11 there: doubles 1.5e-5 apart, but the rays leaving it start 4 error
    // bounds (2^-36 of its size each) off it, 12 above it, over any lamp near it; it rendered
    // black in every strategy. Refused too, at the radius, saying how far off; 1e8 (0.012 off, more
    // than 5/1024) as well.
    for r in ["1e11", "1e8"] {
        error_at(
            &floor(r),
            line,
            "objects[1].radius",
            "is too large for this camera: rays leave its surface from",
        );
    }
    // The book's floor (radius 1000) and one of 1e7 (0.0012 off) are fine; so is a sphere of
    // radius 1e20 seen from its own scale.
    load(&floor("1000")).unwrap();
    load(&floor("1e7")).unwrap();
    let far = BASE
        .replace("lookfrom = [0, 0, 5]", "lookfrom = [0, 0, 5e20]")
        .replace("radius = 1\n", "radius = 1e20\n");
    load(&far).unwrap();
    // The scale is where the camera stands, not only where it looks: a lookat 1e-13 ahead of a
    // camera 5 from a unit ball is fine, and so is the 1e17 floor seen from 1e16 above it (looking 1
    // ahead).
    load(&BASE.replace("lookat = [0, 0, 0]", "lookat = [0, 0, 4.9999999999999]")).unwrap();
    let high = floor("1e17")
        .replace("lookfrom = [0, 0, 5]", "lookfrom = [0, 1e16, 5]")
        .replace("lookat = [0, 0, 0]", "lookat = [1, 1e16, 5]");
    load(&high).unwrap();
}

/// A sphere's hits are computed in its group's coordinates, and its rays leave it from an error
/// bound of those: the book's floor written 1e11 off in a group translated back was accepted (its
/// world place is ordinary) and rendered black; the same floor placed by an instance 1e11 away,
/// with the camera beside it, likewise (an instance re-checked only its quads). Both refused now.
#[test]
fn a_sphere_far_off_in_its_own_group_or_placed_far_by_an_instance_is_refused() {
    let camera = "[camera]\nlookfrom = [0, 3, 3]\nlookat = [0, 0, 0]\n";
    let rest = "[materials]\nwhite = { type = \"lambertian\", albedo = 0.7 }\n\
                lamp = { type = \"light\", emit = 10 }\n";
    let moved = format!(
        "{camera}{rest}[[objects]]\ntype = \"group\"\ntransform = [{{ translate = [0, 1e11, 0] }}]\n\
         [[objects.objects]]\ntype = \"sphere\"\ncenter = [0, -100000001000, 0]\nradius = 1000\n\
         material = \"white\"\n"
    );
    let e = load(&moved).err().unwrap_or_else(|| panic!("accepted"));
    assert!(e.contains("field `objects[0].objects[0].radius`"), "{e}");
    assert!(
        e.contains("is too large for this camera: rays leave its surface"),
        "{e}"
    );
    // the same floor written where it is: accepted
    load(&format!(
        "{camera}{rest}[[objects]]\ntype = \"sphere\"\ncenter = [0, -1000, 0]\nradius = 1000\n\
         material = \"white\"\n"
    ))
    .unwrap();
    let far = camera
        .replace("[0, 3, 3]", "[1e11, 3, 3]")
        .replace("lookat = [0, 0, 0]", "lookat = [1e11, 0, 0]");
    let group = "[[objects]]\ntype = \"group\"\nname = \"g\"\n\
                 [[objects.objects]]\ntype = \"sphere\"\ncenter = [0, -1000, 0]\nradius = 1000\n\
                 material = \"white\"\n";
    let placed = |at: &str| {
        format!(
            "{far}{rest}{group}[[objects]]\ntype = \"instance\"\nof = \"g\"\n\
             transform = [{{ translate = [{at}, 0, 0] }}]\n"
        )
    };
    let e = load(&placed("1e11"))
        .err()
        .unwrap_or_else(|| panic!("accepted"));
    assert!(e.contains("field `objects[1]`"), "{e}");
    assert!(
        e.contains("is too large for this camera: rays leave its surface"),
        "{e}"
    );
    // placed 1e5 away instead, where the camera (at 1e11) sees it from afar: accepted
    load(&placed("1e5")).unwrap();
}

/// The largest sphere floor accepted under a lamp (radius 1e7, its rays leaving it 0.0012 off it,
/// the camera 5 from what it looks at) is lit as the book's floor of radius 1000 is: the same
/// numbers make the same paths, so the lower half of the image (the floor) comes out within 1% of
/// it, where a floor whose rays left it from above the lamp (radius 1e11, now refused) came out
/// black.
#[test]
fn the_largest_floor_accepted_is_lit_like_a_small_one() {
    let scene = |r: &str| {
        format!(
            "[camera]\nlookfrom = [0, 1, -5]\nlookat = [0, 1, 0]\n[materials]\n\
             white = {{ type = \"lambertian\", albedo = 0.7 }}\n\
             lamp = {{ type = \"light\", emit = 10 }}\n\
             [[objects]]\ntype = \"sphere\"\ncenter = [0, -{r}, 0]\nradius = {r}\n\
             material = \"white\"\n\
             [[objects]]\ntype = \"quad\"\nq = [-1, 2.5, -1]\nu = [2, 0, 0]\nv = [0, 0, 2]\n\
             material = \"lamp\"\n"
        )
    };
    let floor = |r: &str| {
        let file = load(&scene(r)).unwrap_or_else(|e| panic!("{e}"));
        let (acc, _) = render(&file.built.scene, settings(32, 5, 8), 16);
        let image = acc.image();
        let lower = &image[image.len() / 2..];
        lower.iter().map(|c| c.element_sum()).sum::<f64>() / lower.len() as f64
    };
    let (small, large) = (floor("1000"), floor("1e7"));
    assert!(small > 0.05, "{small}");
    assert!((large / small - 1.0).abs() < 0.01, "{large} vs {small}");
}

#[test]
fn a_target_listed_twice_is_an_error() {
    error_at(
        &format!("lights = [\"ball\", \"ball\"]\n{BASE}"),
        1,
        "lights[1]",
        "`ball` is already in `lights` (at line 1:11)",
    );
    load(&format!("lights = [\"ball\"]\n{BASE}")).unwrap();
    // The same shape written out twice, or written out beside the name of the same shape: 200,000
    // copies of one sphere made a 32 x 32 render take 10 s instead of a few milliseconds.
    let ball = "{ type = \"sphere\", center = [0, 0, 0], radius = 1 }";
    error_at(
        &format!("lights = [{ball}, {ball}]\n{BASE}"),
        1,
        "lights[1]",
        "this target is already in `lights` (at line 1:11), the same shape",
    );
    error_at(
        &format!("lights = [\"ball\", {ball}]\n{BASE}"),
        1,
        "lights[1]",
        "the same shape",
    );
    // (`-0` is `0`) but another radius is another target
    let minus = "{ type = \"sphere\", center = [-0.0, 0, 0], radius = 1 }";
    error_at(
        &format!("lights = [{ball}, {minus}]\n{BASE}"),
        1,
        "lights[1]",
        "the same shape",
    );
    let other = "{ type = \"sphere\", center = [0, 0, 0], radius = 2 }";
    load(&format!("lights = [{ball}, {other}]\n{BASE}")).unwrap();
    let quad = "{ type = \"quad\", q = [0, 2, 0], u = [1, 0, 0], v = [0, 0, 1] }";
    error_at(
        &format!("lights = [{quad}, {quad}]\n{BASE}"),
        1,
        "lights[1]",
        "the same shape",
    );
}
