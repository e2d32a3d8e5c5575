//! What a scene file means, beyond whether it parses: a medium inside a quad or a group of quads that
//! leaves a gap (which bound no volume), boundaries that close (a box written as six quads),
//! a scene without a light, the image files a scene reads (inputs a render must not overwrite), and
//! the words of two messages.

use rtl_render::closed_surface::{CLOSE, OpenSurface};
use rtl_render::material::{Albedo, Material};
use rtl_render::scene::SceneBuilder;
use rtl_render::scene_file;
use rtl_render::vec::{Color, Point3, Vec3};
use std::path::{Path, PathBuf};

mod scene_text;
use scene_text::{HEAD, load};

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

/// The six faces of the box from `lo` to `hi` as quads, written the way a `box` builds them (each
/// corner and edge as a TOML array of the numbers given), `skip` of them left out.
fn box_faces(lo: [&str; 3], hi: [&str; 3], size: [&str; 3], skip: usize) -> String {
    let [x0, y0, z0] = lo;
    let [x1, y1, z1] = hi;
    let [dx, dy, dz] = size;
    let faces = [
        (
            format!("[{x0}, {y0}, {z1}]"),
            format!("[{dx}, 0, 0]"),
            format!("[0, {dy}, 0]"),
        ),
        (
            format!("[{x1}, {y0}, {z1}]"),
            format!("[0, 0, -{dz}]"),
            format!("[0, {dy}, 0]"),
        ),
        (
            format!("[{x1}, {y0}, {z0}]"),
            format!("[-{dx}, 0, 0]"),
            format!("[0, {dy}, 0]"),
        ),
        (
            format!("[{x0}, {y0}, {z0}]"),
            format!("[0, 0, {dz}]"),
            format!("[0, {dy}, 0]"),
        ),
        (
            format!("[{x0}, {y1}, {z1}]"),
            format!("[{dx}, 0, 0]"),
            format!("[0, 0, -{dz}]"),
        ),
        (
            format!("[{x0}, {y0}, {z0}]"),
            format!("[{dx}, 0, 0]"),
            format!("[0, 0, {dz}]"),
        ),
    ];
    faces[skip..]
        .iter()
        .map(|(q, u, v)| {
            format!(
                "[[objects.boundary.objects]]\ntype = \"quad\"\nq = {q}\nu = {u}\nv = {v}\nmaterial = \"white\"\n"
            )
        })
        .collect()
}

/// A medium whose boundary is the group of `objects` (`[[objects.boundary.objects]]` tables),
/// placed by `transform` (TOML, or empty); its boundary's `type` is at line 13, column 8.
fn medium_in_group(transform: &str, objects: &str) -> String {
    format!(
        "{HEAD}[[objects]]\ntype = \"medium\"\ndensity = 0.5\nalbedo = 0.5\n[objects.boundary]\n\
         type = \"group\"\n{transform}\n{objects}"
    )
}

/// A group of quads that leaves a gap bounds no volume either: a ray leaves through the gap without
/// a second crossing. Refused at the boundary's `type`, naming the quad and its open edge: one quad
/// in a group, three faces of a box, five, a sphere with a stray quad, two quads at one place, a
/// fin on a closed box. Quads that close a surface load: a box written out as six quads (0.1 + 0.7
/// is not 0.8, so their corners meet only to within rounding), rotated and moved, placed by an
/// instance, each turned by a transform of its own, one square turned and moved to each face of a
/// cube; and so do a box, a sphere, a moving sphere, an instance of a rotated box, a group of a
/// sphere and a box.
#[test]
fn a_medium_inside_quads_that_leave_a_gap_is_refused_and_closed_quads_load() {
    let quad = "[[objects.boundary.objects]]\ntype = \"quad\"\nq = [-1, -1, 0]\nu = [2, 0, 0]\n\
                v = [0, 2, 0]\nmaterial = \"white\"\n";
    refused(
        &medium_in_group("", quad),
        &[
            "some/dir/s.toml:13:8:",
            "field `objects[0].boundary.type`",
            "must enclose a volume",
            "the edge of the quad at line 15:1 from [-1, -1, 0] to [1, -1, 0]",
            "is an edge of no other quad of the boundary: the surface is open there",
            "invisible or wrong",
        ],
    );
    let (lo, hi, size) = (
        ["0.1", "0.2", "0.3"],
        ["0.8", "0.9", "1.1"],
        ["0.7", "0.7", "0.8"],
    );
    // three faces of the box (the first three left out), and five (the first one)
    refused(
        &medium_in_group("", &box_faces(lo, hi, size, 3)),
        &[
            "some/dir/s.toml:13:8:",
            "the quad at line 15:1",
            "no other quad",
        ],
    );
    refused(
        &medium_in_group("", &box_faces(lo, hi, size, 1)),
        &[
            "some/dir/s.toml:13:8:",
            "the quad at line 15:1",
            "no other quad",
        ],
    );
    // a sphere and a stray quad: the quad is named (line 20, after the sphere's six lines)
    let sphere = "[[objects.boundary.objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n\
                  material = \"white\"\n";
    refused(
        &medium_in_group("", &format!("{sphere}{quad}")),
        &[
            "some/dir/s.toml:13:8:",
            "the quad at line 20:1",
            "no other quad",
        ],
    );
    // two quads at one place share every edge, and enclose nothing
    refused(
        &medium_in_group("", &format!("{quad}{quad}")),
        &[
            "some/dir/s.toml:13:8:",
            "the quad at line 21:1 lies where another quad of the boundary does",
        ],
    );
    // a fin on the box's edge: three quads meet there
    let fin = "[[objects.boundary.objects]]\ntype = \"quad\"\nq = [0.1, 0.2, 1.1]\nu = [0.7, 0, 0]\n\
               v = [0, -0.5, 0]\nmaterial = \"white\"\n";
    refused(
        &medium_in_group("", &format!("{}{fin}", box_faces(lo, hi, size, 0))),
        &[
            "some/dir/s.toml:13:8:",
            "is an edge of 2 other quads of the boundary: a closed surface has two quads meet",
        ],
    );

    let closed = box_faces(lo, hi, size, 0);
    let moved =
        "transform = [{ rotate_y = 15 }, { rotate_x = -40 }, { translate = [1.3, -0.2, 0.7] }]";
    for (what, text) in [
        ("six quads", medium_in_group("", &closed)),
        ("six quads, rotated", medium_in_group(moved, &closed)),
        // one unit square six times, each turned and moved to a face of the unit cube by a
        // transform of its own: they close a surface only where they are placed (cos 90 degrees
        // is not 0 in doubles)
        (
            "six squares turned into a cube",
            medium_in_group(
                "",
                &[
                    "[]",
                    "[{ translate = [0, 0, 1] }]",
                    "[{ rotate_y = -90 }]",
                    "[{ rotate_y = -90 }, { translate = [1, 0, 0] }]",
                    "[{ rotate_x = 90 }]",
                    "[{ rotate_x = 90 }, { translate = [0, 1, 0] }]",
                ]
                .map(|t| {
                    format!(
                        "[[objects.boundary.objects]]\ntype = \"quad\"\nq = [0, 0, 0]\n\
                         u = [1, 0, 0]\nv = [0, 1, 0]\nmaterial = \"white\"\ntransform = {t}\n"
                    )
                })
                .concat(),
            ),
        ),
        // each quad turned by its own transform: their corners meet only where they are placed
        (
            "six quads, each rotated",
            medium_in_group(
                "",
                &closed.replace(
                    "material = \"white\"\n",
                    &format!("material = \"white\"\n{moved}\n"),
                ),
            ),
        ),
        // the six quads as a named group, placed again by an instance that turns it
        (
            "an instance of six quads",
            format!(
                "{HEAD}[[objects]]\ntype = \"group\"\nname = \"cube\"\n{}{}",
                closed.replace("objects.boundary.objects", "objects.objects"),
                "[[objects]]\ntype = \"medium\"\ndensity = 0.5\nalbedo = 0.5\nboundary = { type = \
                 \"instance\", of = \"cube\", transform = [{ rotate_z = 33 }, { translate = [0.3, \
                 0, 2] }] }\n"
            ),
        ),
        (
            "a sphere and a box",
            medium_in_group(
                "",
                &format!("{sphere}{}", {
                    "[[objects.boundary.objects]]\ntype = \"box\"\na = [2, 0, 0]\nb = [3, 1, 1]\nmaterial = \"white\"\n"
                }),
            ),
        ),
    ] {
        load(&text).unwrap_or_else(|e| panic!("{what}: {e}\n{text}"));
    }
    let medium = |boundary: &str| {
        format!(
            "{HEAD}[[objects]]\ntype = \"medium\"\ndensity = 0.5\nalbedo = 0.5\nboundary = {boundary}\n"
        )
    };
    for boundary in [
        "{ type = \"box\", a = [0.1, 0.2, 0.3], b = [0.8, 0.9, 1.1], material = \"white\" }",
        "{ type = \"box\", a = [0, 0, 0], b = [1, 1, 1], material = \"white\", transform = [{ rotate_y = 15 }, { translate = [0.2, 0, 0.1] }] }",
        "{ type = \"sphere\", center = [0, 0, 0], radius = 1, material = \"white\" }",
        "{ type = \"moving_sphere\", center0 = [0, 0, 0], center1 = [0, 1, 0], radius = 1, material = \"white\" }",
    ] {
        load(&medium(boundary)).unwrap_or_else(|e| panic!("{boundary}: {e}"));
    }
    // an instance of a box, rotated
    let rotated = format!(
        "{HEAD}[[objects]]\ntype = \"box\"\nname = \"b\"\na = [0, 0, 0]\nb = [1, 2, 1]\nmaterial = \"white\"\n\
         [[objects]]\ntype = \"medium\"\ndensity = 0.5\nalbedo = 0.5\nboundary = {{ type = \"instance\", \
         of = \"b\", transform = [{{ rotate_y = 15 }}, {{ translate = [2, 0, 0] }}] }}\n"
    );
    load(&rotated).unwrap_or_else(|e| panic!("{e}"));
    // the shipped scenes with media
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    for name in ["cornell-smoke.toml", "showcase.toml"] {
        let file = scene_file::load_file(&scenes.join(name)).unwrap_or_else(|e| panic!("{e}"));
        assert!(file.built.scene.features.media > 0, "{name}");
    }
}

/// Corners a rounding apart are one corner even where a cell of the grid that finds them ends
/// between them (the grid's cells are 16 CLOSE times the largest coordinate): a box from
/// [x, 0, 0] to [2, 1, 1] whose face x = x has its corners at x, and the four faces along x theirs
/// one double below, with x chosen so that the two lie in neighbouring cells, closes; moved off by
/// 1e-6 (5e-7 of the box's largest coordinate), the face is named.
#[test]
fn corners_a_rounding_apart_across_a_cell_of_the_grid_are_one_corner() {
    let cell = 16.0 * CLOSE * 2.0;
    let mut x = 1000.0 * cell;
    while (x / cell).floor() == (x.next_down() / cell).floor() {
        x = x.next_up();
    }
    let below = x.next_down();
    let faces = |left: f64| {
        let mut b = SceneBuilder::new();
        let m = b.material(Material::Lambertian {
            albedo: Albedo::Constant(Color::splat(0.5)),
        });
        let g = b.group();
        let (w, y, z) = (2.0 - below, Vec3::Y, Vec3::Z);
        let xw = Vec3::new(w, 0.0, 0.0);
        for (q, u, v) in [
            (Point3::new(left, 0.0, 0.0), y, z),
            (Point3::new(2.0, 0.0, 0.0), y, z),
            (Point3::new(below, 0.0, 0.0), xw, y),
            (Point3::new(below, 0.0, 1.0), xw, y),
            (Point3::new(below, 0.0, 0.0), xw, z),
            (Point3::new(below, 1.0, 0.0), xw, z),
        ] {
            b.quad(g, q, u, v, m).unwrap();
        }
        b.open_quad(g)
    };
    assert_eq!(faces(x), None);
    let open = faces(x + 1e-6).expect("open");
    assert_eq!(open.index, 0, "{open:?}");
    assert!(
        matches!(open.problem, OpenSurface::Edge { others: 0, .. }),
        "{open:?}"
    );
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
/// edge 16,000 off (at 1e16, 2), the image silently another. Refused, naming the object. So is a
/// floor so large that the rays leaving it start too far off it (4 error bounds of 2^-36 of its
/// size: 1e12 across, 175 above it), even with its edges far away; a floor 1e6 across is not.
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
        ("[-1e8, 0, -1e8]", "[2e8, 0, 0]", "[0, 0, 2e8]"),
    ] {
        refused(
            &floor(q, u, v),
            &[
                "some/dir/s.toml:6:1",
                "field `objects[0]`",
                "a quad (or box face) reaching",
                "is too large for this camera: rays leave its surface from",
            ],
        );
    }
    for (q, u, v) in [
        ("[-1e6, 0, -1e6]", "[2e6, 0, 0]", "[0, 0, 2e6]"),
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
    refused(
        &boxed("[-1e12, -1, -1e12]", "[0, 0, 1e12]"),
        &["box face", "is too large for this camera"],
    );
    for (a, b) in [
        ("[-10, -1, -10]", "[0, 0, 10]"),
        ("[-1e6, -1, -1e6]", "[0, 0, 1e6]"),
        ("[1e29, 1e29, 1e29]", "[2e29, 2e29, 2e29]"),
    ] {
        load(&boxed(a, b)).unwrap_or_else(|e| panic!("{a} {b}: {e}"));
    }
}

/// An instance places its group's quads again, and they are held to the same rule where it puts them:
/// a floor reaching 1e20, accepted in a group placed 1e14 below the camera (its rays leave it
/// 2.3e10 off it, below 1e14 / 1024), is refused where an instance puts it at the camera's feet; an
/// instance that leaves it far away loads.
#[test]
fn an_instance_whose_quads_cannot_be_placed_is_refused() {
    let scene = |up: &str| {
        format!(
            "[camera]\nlookfrom = [2, 1, 0]\nlookat = [0, 0, 0]\n[materials]\n\
             w = {{ type = \"lambertian\", albedo = 0.5 }}\n\
             [[objects]]\ntype = \"group\"\nname = \"g\"\n\
             transform = [{{ translate = [0, -1e14, 0] }}]\n\
             [[objects.objects]]\ntype = \"quad\"\nq = [-1e20, 0, -1e20]\nu = [1e20, 0, 0]\n\
             v = [0, 0, 2e20]\nmaterial = \"w\"\n\
             [[objects]]\ntype = \"instance\"\nof = \"g\"\n\
             transform = [{{ translate = [0, {up}, 0] }}]\n"
        )
    };
    load(&scene("-2e14")).unwrap_or_else(|e| panic!("{e}"));
    refused(
        &scene("0"),
        &[
            "some/dir/s.toml:16:1",
            "objects[1]",
            "cannot have its edges placed",
        ],
    );
}

/// A quad whose u and v are parallel to within a part in 1e9 (so not refused as zero-area) has two
/// of its own corners within CLOSE of each other: one corner. Its four edges then pair off with
/// each other, each "an edge of exactly one other", and the sliver alone passed for a closed
/// surface: a medium inside it loaded, invisible. Refused, naming the quad.
#[test]
fn a_sliver_quad_whose_corners_meet_is_no_closed_surface() {
    let sliver = "[[objects.boundary.objects]]\ntype = \"quad\"\nq = [0, 0, 0]\nu = [1, 0, 0]\n\
                  v = [1, 1e-12, 0]\nmaterial = \"white\"\n";
    refused(
        &medium_in_group("", sliver),
        &[
            "some/dir/s.toml:13:8:",
            "must enclose a volume",
            "two corners of the quad at line 15:1 are one corner",
        ],
    );
}

/// The pieces of a boundary must lie apart: a medium takes the stretches between its boundary's
/// crossings in pairs, in and out, which is its inside only where the pieces neither overlap nor
/// touch. Refused at the boundary's `type`, naming both pieces: two balls that overlap, a ball
/// inside another, a ball that reaches into a box, two boxes face to face, a ball placed by an
/// instance onto another, two moving spheres that meet halfway, a ball reaching into a closed
/// surface of quads or inside one. Pieces apart load, also where their bounding boxes meet (two
/// balls on a diagonal, a ball beside a box's corner or a closed surface of quads' corner, a turned
/// box beside a ball or a box, moving spheres whose paths cross at different times) and two closed
/// groups of quads apart.
#[test]
fn a_medium_whose_pieces_overlap_or_touch_is_refused_and_pieces_apart_load() {
    let ball = |c: &str, r: &str| {
        format!(
            "[[objects.boundary.objects]]\ntype = \"sphere\"\ncenter = {c}\nradius = {r}\n\
             material = \"white\"\n"
        )
    };
    let cube = |a: &str, b: &str| {
        format!(
            "[[objects.boundary.objects]]\ntype = \"box\"\na = {a}\nb = {b}\nmaterial = \"white\"\n"
        )
    };
    // a unit cube turned 45 degrees about y and moved to `at`, a face towards the origin when `at`
    // is on the diagonal of x and z
    let turned = |at: &str| {
        cube("[-0.5, -0.5, -0.5]", "[0.5, 0.5, 0.5]").replace(
            "material = \"white\"\n",
            &format!(
                "material = \"white\"\ntransform = [{{ rotate_y = 45 }}, {{ translate = {at} }}]\n"
            ),
        )
    };
    let moving = |c0: &str, c1: &str, r: &str| {
        format!(
            "[[objects.boundary.objects]]\ntype = \"moving_sphere\"\ncenter0 = {c0}\ncenter1 = {c1}\n\
             radius = {r}\nmaterial = \"white\"\n"
        )
    };
    // 2.1 along that diagonal: the face 1.6 from the origin, the corner of its bounding box 1.1
    let diagonal = 2.1 / 2f64.sqrt();
    let place = ["some/dir/s.toml:13:8:", "must lie apart"];
    for (what, objects, words) in [
        (
            "two balls that overlap",
            ball("[0, 0, 0]", "1") + &ball("[1.5, 0, 0]", "1"),
            &[
                "the sphere at [0, 0, 0] of radius 1 and the sphere at [1.5, 0, 0] of radius 1",
                "overlap or touch",
                "give each a medium of its own",
            ][..],
        ),
        (
            "a ball inside another",
            ball("[0, 0, 0]", "3") + &ball("[1, 0, 0]", "0.5"),
            &["the sphere at [1, 0, 0] of radius 0.5"][..],
        ),
        (
            "two balls that touch",
            ball("[0, 0, 0]", "1") + &ball("[2, 0, 0]", "1"),
            &["overlap or touch"][..],
        ),
        (
            "a ball reaching into a box",
            ball("[0, 0, 0]", "1") + &cube("[0.5, -1, -1]", "[2, 1, 1]"),
            &[
                "the box within [0.5, -1, -1] to [2, 1, 1]",
                "overlap or touch",
            ][..],
        ),
        (
            "a turned box reaching into a ball",
            ball("[0, 0, 0]", "1.65") + &turned(&format!("[{diagonal}, 0, {diagonal}]")),
            &[
                "the sphere at [0, 0, 0] of radius 1.65",
                "the turned box of size [1, 1, 1] centred at [1.48",
                "overlap or touch",
            ][..],
        ),
        (
            "two moving spheres that meet halfway",
            moving("[-2, 0, 0]", "[2, 0, 0]", "1") + &moving("[0, -2, 0]", "[0, 2, 0]", "1"),
            &[
                "the sphere of radius 1 moving from [-2, 0, 0] to [2, 0, 0]",
                "the sphere of radius 1 moving from [0, -2, 0] to [0, 2, 0]",
                "overlap or touch",
            ][..],
        ),
        (
            "a ball reaching into a closed surface of quads",
            ball("[0, 0, 0]", "1")
                + &box_faces(["0.5", "-1", "-1"], ["2", "1", "1"], ["1.5", "2", "2"], 0),
            &[
                "the quads within [0.5, -1, -1] to [2, 1, 1]",
                "overlap or touch",
            ][..],
        ),
        (
            "a ball inside a closed surface of quads",
            ball("[0, 0, 0]", "0.5")
                + &box_faces(["-1", "-1", "-1"], ["1", "1", "1"], ["2", "2", "2"], 0),
            &[
                "the quads within [-1, -1, -1] to [1, 1, 1]",
                "overlap or touch",
            ][..],
        ),
        (
            "boxes face to face",
            cube("[0, 0, 0]", "[1, 1, 1]") + &cube("[0, 1, 0]", "[1, 2, 1]"),
            &["the box within"][..],
        ),
        (
            "a ball placed by a transform onto another",
            ball("[0, 0, 0]", "1")
                + &ball("[5, 0, 0]", "1").replace(
                    "material = \"white\"\n",
                    "material = \"white\"\ntransform = [{ translate = [-4.5, 0, 0] }]\n",
                ),
            &["the sphere at [0.5, 0, 0] of radius 1"][..],
        ),
    ] {
        let text = medium_in_group("", &objects);
        let err = load(&text)
            .err()
            .unwrap_or_else(|| panic!("{what}: accepted"));
        for w in place.iter().chain(words) {
            assert!(err.contains(w), "{what}: wanted {w:?} in: {err}");
        }
    }
    let d = 2.0 / 3f64.sqrt() + 1e-3;
    for (what, objects) in [
        (
            "two balls on a diagonal",
            ball("[0, 0, 0]", "1") + &ball(&format!("[{d}, {d}, {d}]"), "0.999"),
        ),
        (
            "a ball beside a box's corner",
            ball("[0, 0, 0]", "1") + &cube("[0.6, 0.6, 0.6]", "[2, 2, 2]"),
        ),
        (
            "two boxes apart",
            cube("[0, 0, 0]", "[1, 1, 1]") + &cube("[0, 1.01, 0]", "[1, 2, 1]"),
        ),
        (
            "a ball beside the corner of a closed surface of quads, within its bounding box's reach",
            ball("[0, 0, 0]", "1")
                + &box_faces(
                    ["0.6", "0.6", "0.6"],
                    ["2", "2", "2"],
                    ["1.4", "1.4", "1.4"],
                    0,
                ),
        ),
        (
            "two moving spheres whose paths cross at different times",
            moving("[-2, 0, 0]", "[2, 0, 0]", "0.5") + &moving("[0, -4, 0]", "[0, 0, 0]", "0.5"),
        ),
        (
            "a ball and a box apart",
            ball("[0, 0, 0]", "1") + &cube("[2, 0, 0]", "[3, 1, 1]"),
        ),
        (
            "a turned box beside a ball, within its bounding box's reach",
            ball("[0, 0, 0]", "1.5") + &turned(&format!("[{diagonal}, 0, {diagonal}]")),
        ),
        (
            "a turned box's face 0.01 from a box's edge, within its bounding box's reach",
            cube("[-0.5, -0.5, -0.5]", "[0.5, 0.5, 0.5]")
                + &turned(&format!("[{e}, 0, {e}]", e = 0.5 + 0.51 / 2f64.sqrt())),
        ),
    ] {
        load(&medium_in_group("", &objects)).unwrap_or_else(|e| panic!("{what}: {e}"));
    }
}

/// A medium inside another's boundary would make its scattering points the boundary's crossings:
/// refused at the boundary's `type`.
#[test]
fn a_medium_in_a_boundary_is_refused() {
    let inner = "[[objects.boundary.objects]]\ntype = \"medium\"\ndensity = 2\nalbedo = 0.5\n\
                 boundary = { type = \"sphere\", center = [0, 0, 5], radius = 1, material = \"white\" }\n";
    let ball = "[[objects.boundary.objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n\
                material = \"white\"\n";
    refused(
        &medium_in_group("", &format!("{ball}{inner}")),
        &[
            "some/dir/s.toml:13:8:",
            "a medium's boundary is surfaces alone, and this one holds a medium",
        ],
    );
    load(&medium_in_group("", ball)).unwrap();
}

/// A face split in two beside whole faces closes the volume: the halves' edges meet the whole
/// faces' edges along part of their length (T-junctions), and each whole edge is taken in the
/// pieces the halves' corners cut it into. Loads: the face at z = 1 in halves, the bottom too (cut
/// at x = 0.4, so that the cuts along their shared edge differ), the bottom's halves joined by the
/// back face's whole edge. Refused: a half missing (open where it was), two halves that overlap
/// (three quads meet along the overlap), a half 1e-6 off the face (a gap).
#[test]
fn a_face_split_beside_whole_faces_closes_a_boundary() {
    let quad = |q: &str, u: &str, v: &str| {
        format!(
            "[[objects.boundary.objects]]\ntype = \"quad\"\nq = {q}\nu = {u}\nv = {v}\nmaterial = \"white\"\n"
        )
    };
    let (right, back, left, top) = (
        quad("[1, 0, 1]", "[0, 0, -1]", "[0, 1, 0]"),
        quad("[1, 0, 0]", "[-1, 0, 0]", "[0, 1, 0]"),
        quad("[0, 0, 0]", "[0, 0, 1]", "[0, 1, 0]"),
        quad("[0, 1, 1]", "[1, 0, 0]", "[0, 0, -1]"),
    );
    // the face at z = 1 as two quads from x = 0 to `cut` and from `from` to 1
    let front = |cut: &str, from: &str| {
        quad("[0, 0, 1]", &format!("[{cut}, 0, 0]"), "[0, 1, 0]")
            + &quad(
                &format!("[{from}, 0, 1]"),
                &format!("[{}, 0, 0]", 1.0 - from.parse::<f64>().unwrap()),
                "[0, 1, 0]",
            )
    };
    let bottom = quad("[0, 0, 0]", "[0.4, 0, 0]", "[0, 0, 1]")
        + &quad("[0.4, 0, 0]", "[0.6, 0, 0]", "[0, 0, 1]");
    let cube =
        |front: &str| medium_in_group("", &format!("{front}{right}{back}{left}{top}{bottom}"));
    load(&cube(&front("0.5", "0.5"))).unwrap_or_else(|e| panic!("halves: {e}"));
    // one half only: the open edge is the kept half's edge at x = 0.5 (line 15 is its quad)
    let one = quad("[0, 0, 1]", "[0.5, 0, 0]", "[0, 1, 0]");
    refused(
        &cube(&one),
        &[
            "some/dir/s.toml:13:8:",
            "the edge of the quad at line 15:1 from [0.5, 0, 1] to [0.5, 1, 1]",
            "is an edge of no other quad",
        ],
    );
    // (the second half's edge along the bottom is the bottom's second half's, corner to corner;
    // the first half's stretch from 0.4 to 0.6 along it is left over)
    refused(
        &cube(&front("0.6", "0.4")),
        &[
            "the edge of the quad at line 15:1 from [0.4, 0, 1] to [0.6, 0, 1]",
            "runs along part of an edge of the quad at line 21:1",
            "do not pair up",
            "open there or overlaps itself",
        ],
    );
    let off = front("0.5", "0.5").replacen("q = [0, 0, 1]", "q = [0, 0, 1.000001]", 1);
    refused(&cube(&off), &["is an edge of no other quad"]);
}

/// Quads written one by one are sorted into the closed surfaces they form (joined by shared
/// edges), each a piece: two hand-made cubes that cross each other are refused, two apart load.
#[test]
fn closed_surfaces_of_loose_quads_are_pieces_of_their_own() {
    let cube = |lo: [&str; 3], hi: [&str; 3]| box_faces(lo, hi, ["1", "1", "1"], 0);
    let crossing = cube(["0", "0", "0"], ["1", "1", "1"])
        + &cube(["0.5", "0.5", "0.5"], ["1.5", "1.5", "1.5"]);
    refused(
        &medium_in_group("", &crossing),
        &[
            "some/dir/s.toml:13:8:",
            "the quads within [0, 0, 0] to [1, 1, 1] and the quads within [0.5, 0.5, 0.5] to [1.5, 1.5, 1.5]",
        ],
    );
    let apart = cube(["0", "0", "0"], ["1", "1", "1"]) + &cube(["2", "0", "0"], ["3", "1", "1"]);
    load(&medium_in_group("", &apart)).unwrap();
}
