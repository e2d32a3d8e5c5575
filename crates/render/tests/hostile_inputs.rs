//! Inputs made to hurt: a few kilobytes of instances of instances that stand for 2^40 shapes, groups
//! nested thousands deep, a small PNG that decodes to gigabytes, a scene path that is `/dev/zero`,
//! and the messages of the scene loader for duplicate keys and names and for numbers too small to
//! print in full. Each is refused before any work, naming the file, line, column and field, and the
//! limits still admit every shipped and built-in scene and 200,000 spheres.

use rtl_render::checkpoint::scene_hash;
use rtl_render::lights::Lights;
use rtl_render::limits::{
    self, MAX_EXPANDED_OBJECTS, MAX_NESTING, MAX_SCENE_FILE_BYTES, MAX_TEXTURE_PIXELS,
};
use rtl_render::material::{Albedo, Material};
use rtl_render::scene::{Object, SceneBuilder, Transform};
use rtl_render::scene_file;
use rtl_render::scenes;
use rtl_render::texture::{ImageData, Texture};
use rtl_render::vec::{Color, Point3, Vec3};
use std::path::{Path, PathBuf};
use std::time::Duration;

mod scene_text;
use scene_text::{HEAD, load};

/// `f()`, run on a thread of its own and given up on after a minute: a guard against a walk that
/// never ends (2^40 places, groups nested 5,000 deep), not a claim about speed, which benchmarks
/// measure. Each of these inputs is refused within milliseconds here.
#[track_caller]
fn finishes<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    let (send, receive) = std::sync::mpsc::channel();
    let walk = std::thread::spawn(move || send.send(f()));
    match receive.recv_timeout(Duration::from_secs(60)) {
        Ok(t) => t,
        // `f` panicked (the sender dropped unsent): its panic, with its own message, is the test's
        Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => match walk.join() {
            Err(payload) => std::panic::resume_unwind(payload),
            Ok(_) => unreachable!("the walk ended without sending its answer"),
        },
        Err(std::sync::mpsc::RecvTimeoutError::Timeout) => panic!("still walking after a minute"),
    }
}

/// A walk that panics fails at once with its own message, not as one that never ended.
#[test]
fn a_walk_that_panics_fails_with_its_own_message() {
    let caught = std::panic::catch_unwind(|| finishes(|| -> () { panic!("accepted: the scene") }))
        .expect_err("the walk's panic");
    let message = caught
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| caught.downcast_ref::<String>().cloned())
        .unwrap_or_default();
    assert_eq!(message, "accepted: the scene");
}

/// The error for `text`, which must start with the file and `line`, and contain each of `words`.
#[track_caller]
fn refused(text: &str, line: usize, words: &[&str]) -> String {
    let err = match load(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    };
    let place = format!("some/dir/s.toml:{line}:");
    assert!(err.starts_with(&place), "wanted {place}, got: {err}");
    for w in words {
        assert!(err.contains(w), "wanted '{w}', got: {err}");
    }
    err
}

/// Group `g0` holds a sphere (of `material`); group `g{k}` two instances of `g{k-1}`, for k = 1 to
/// `depth`, each group placed in the scene too (hostile/gen_laughs.py): 2^depth spheres in `g{depth}`.
fn laughs(depth: usize, material: &str) -> String {
    let mut s = format!(
        "{HEAD}\n[[objects]]\ntype = \"group\"\nname = \"g0\"\n[[objects.objects]]\ntype = \"sphere\"\n\
         center = [0, 0, 0]\nradius = 0.1\nmaterial = \"{material}\"\n"
    );
    for k in 1..=depth {
        s.push_str(&format!(
            "[[objects]]\ntype = \"group\"\nname = \"g{k}\"\ntransform = [{{ translate = [0, 0, 1000] }}]\n\
             [[objects.objects]]\ntype = \"instance\"\nof = \"g{}\"\n\
             [[objects.objects]]\ntype = \"instance\"\nof = \"g{}\"\n\
             transform = [{{ translate = [0.001, 0, 0] }}]\n",
            k - 1,
            k - 1
        ));
    }
    s
}

/// Group `g{k}` holds one instance of `g{k-1}`, each placed in the scene (hostile chain*.toml).
fn chain(depth: usize) -> String {
    let mut s = format!(
        "{HEAD}\n[[objects]]\ntype = \"group\"\nname = \"g0\"\n[[objects.objects]]\ntype = \"sphere\"\n\
         center = [0, 0, 0]\nradius = 1\nmaterial = \"lamp\"\n"
    );
    for k in 1..=depth {
        s.push_str(&format!(
            "[[objects]]\ntype = \"group\"\nname = \"g{k}\"\ntransform = [{{ translate = [0, 0, 0] }}]\n\
             [[objects.objects]]\ntype = \"instance\"\nof = \"g{}\"\ntransform = [{{ translate = [0, 0, 0] }}]\n",
            k - 1
        ));
    }
    s
}

/// The line (1-based) of the first occurrence of `needle` in `text`.
fn line_of(text: &str, needle: &str) -> usize {
    let at = text.find(needle).expect("needle in text");
    text[..at].matches('\n').count() + 1
}

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

/// A fresh directory under the system's temporary one.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rtl-hostile-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn exponential_instancing_is_refused_at_once_naming_the_group() {
    for material in ["lamp", "white"] {
        let text = laughs(40, material);
        assert!(text.len() < 12_000, "a small file: {} bytes", text.len());
        let err = finishes({
            let text = text.clone();
            move || load(&text).err().expect("refused")
        });
        // g_k holds c_k = 2 (1 + c_{k-1}) = 3 2^k - 2 objects (two instances of g_{k-1}), and the
        // scene g_0 and an instance of each g_k: 2 + sum (3 2^k - 1), 786411 up to g17. The group
        // that brings it past 2^20 is g18.
        let line = line_of(&text, "name = \"g18\"") - 2;
        assert!(
            err.starts_with(&format!("some/dir/s.toml:{line}:1: field `objects[18]`: ")),
            "{err}"
        );
        for words in [
            "too many objects once instances are expanded",
            "group `g18` (786431 objects)",
            "brings the scene to 1572842",
            &format!("more than the {MAX_EXPANDED_OBJECTS}"),
        ] {
            assert!(err.contains(words), "wanted '{words}': {err}");
        }
    }
}

/// A group without a name is named by its place in the message: "the group at line L:1", not
/// "this the group at ...".
#[test]
fn an_unnamed_group_past_the_limit_is_named_by_its_place() {
    // the scene holds 786411 objects up to g17; an unnamed group of an instance of g17 adds
    // 393216 (g17's 393214, the instance, the group)
    let text = format!(
        "{}[[objects]]\ntype = \"group\"\n[[objects.objects]]\ntype = \"instance\"\nof = \"g17\"\n",
        laughs(17, "white")
    );
    let line = text.matches('\n').count() - 4;
    let err = refused(
        &text,
        line,
        &[
            &format!(
                "too many objects once instances are expanded: the group at line {line}:1 (393216 objects)"
            ),
            "brings the scene to 1179627",
        ],
    );
    assert!(!err.contains("this the group"), "{err}");
}

#[test]
fn instancing_within_the_limit_loads_and_its_walks_see_every_emitter() {
    // g16 holds 2^17 - 1 objects; the scene 2^18 - 19, within 2^20.
    let text = laughs(16, "lamp");
    let file = load(&text).unwrap();
    let scene = &file.built.scene;
    let expanded = limits::expanded_objects(scene);
    assert!(expanded <= MAX_EXPANDED_OBJECTS, "{expanded}");
    let lights = Lights::new(scene, false);
    // Every sphere placed: 2^k in g_k, for k = 0 .. 16.
    assert_eq!(lights.emitters.len(), (1 << 17) - 1);
}

#[test]
fn the_sum_of_the_expansions_is_refused_where_it_crosses_the_limit() {
    // A group of 1024 spheres placed, then 1023 instances of it: each place counts the group's
    // 1024 objects and itself, 1025 (1 + j) objects after j instances, past 2^20 at the 1023rd.
    let mut text = format!("{HEAD}\n[[objects]]\ntype = \"group\"\nname = \"many\"\n");
    for i in 0..1024 {
        text.push_str(&format!(
            "[[objects.objects]]\ntype = \"sphere\"\ncenter = [{i}, 0, 0]\nradius = 0.4\nmaterial = \"white\"\n"
        ));
    }
    for j in 0..1023 {
        text.push_str(&format!(
            "[[objects]]\ntype = \"instance\"\nof = \"many\"\ntransform = [{{ translate = [0, {j}, 0] }}]\n"
        ));
    }
    let cut = text.rfind("[[objects]]").unwrap();
    refused(
        &text,
        text[..cut].matches('\n').count() + 1,
        &[
            "field `objects[1023]`",
            "this instance of `many` (1025 objects) brings the scene to 1049600",
        ],
    );
    // One instance fewer loads.
    let file = load(&text[..cut]).unwrap();
    assert_eq!(limits::expanded_objects(&file.built.scene), 1025 * 1023);
}

/// A medium's boundary is checked for a closed surface by walking its quads where its instances put
/// them: the most a scene may hold, 2^18 quads from instances of instances in one boundary (each
/// nested group open by itself, so walked again), is refused in well under seconds, naming the quad.
#[test]
fn an_open_boundary_of_instances_of_instances_is_refused_quickly() {
    let mut text = format!(
        "{HEAD}\n[[objects]]\ntype = \"medium\"\ndensity = 0.5\nalbedo = 0.5\n[objects.boundary]\n\
         type = \"group\"\n[[objects.boundary.objects]]\ntype = \"group\"\nname = \"g0\"\n\
         [[objects.boundary.objects.objects]]\ntype = \"quad\"\nq = [0, 0, 0]\nu = [1, 0, 0]\n\
         v = [0, 1, 0]\nmaterial = \"white\"\n"
    );
    for k in 1..=17 {
        text.push_str(&format!(
            "[[objects.boundary.objects]]\ntype = \"group\"\nname = \"g{k}\"\n\
             transform = [{{ translate = [0, 0, 1000] }}]\n\
             [[objects.boundary.objects.objects]]\ntype = \"instance\"\nof = \"g{}\"\n\
             [[objects.boundary.objects.objects]]\ntype = \"instance\"\nof = \"g{}\"\n\
             transform = [{{ translate = [0.001, 0, 0] }}]\n",
            k - 1,
            k - 1
        ));
    }
    let quad_line = line_of(&text, "type = \"quad\"") - 1;
    let line = line_of(&text, "type = \"group\"\n[[objects.boundary.objects]]");
    finishes(move || {
        refused(
            &text,
            line,
            &[
                "field `objects[0].boundary.type`",
                &format!("the edge of the quad at line {quad_line}:1"),
                "is an edge of no other quad",
            ],
        )
    });
}

#[test]
fn groups_nested_past_the_limit_are_refused() {
    // chain(k): g_k nests k + 1 levels in the scene.
    assert!(load(&chain(MAX_NESTING as usize - 1)).is_ok());
    let text = chain(5000);
    let line = line_of(&text, "name = \"g64\"") - 2;
    finishes(move || {
        refused(
            &text,
            line,
            &[
                "field `objects[64]`",
                "groups nest too deep: this group `g64` puts 65 levels",
                "more than the 64 allowed",
            ],
        )
    });
}

#[test]
fn walks_over_a_built_scene_that_expands_past_the_limit_stop() {
    // Built without a file (so not counted at load): g_k holds g_{k-1} twice, 40 deep, with an
    // emitter and glass in every g_0, and the world holds g_40 and a glass ball: 2^40 places.
    let mut b = SceneBuilder::new();
    let lamp = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(4.0)),
        two_sided: false,
    });
    let glass = b.material(Material::Dielectric { ior: 1.5 });
    let g0 = b.group();
    b.sphere(g0, Point3::new(0.0, 3.0, 0.0), 0.1, lamp).unwrap();
    b.sphere(g0, Point3::ZERO, 1.0, glass).unwrap();
    let mut g = g0;
    for k in 0..40 {
        let next = b.group();
        b.add_to(next, Object::Group(g));
        b.instance(
            next,
            g,
            Transform::translate(Vec3::new(0.001 * k as f64, 0.0, 0.0)),
        );
        g = next;
    }
    b.add(Object::Group(g));
    b.sphere(b.world(), Point3::ZERO, 1.0, glass).unwrap();
    let scene = b.build().unwrap();
    assert!(limits::expanded_objects(&scene) > 1 << 40);
    let lights = finishes(move || Lights::new(&scene, false));
    assert!(!lights.emitters.is_empty());
    assert!(lights.emitters.len() as u64 <= MAX_EXPANDED_OBJECTS);
}

#[test]
fn every_shipped_and_built_in_scene_is_within_the_limits() {
    let mut largest = (0, String::new());
    for entry in std::fs::read_dir(scenes_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let file = scene_file::load_file(&path).unwrap();
            let n = limits::expanded_objects(&file.built.scene);
            if n > largest.0 {
                largest = (n, path.display().to_string());
            }
        }
    }
    for b in scenes::BUILT_INS {
        let built = (b.build)(&Default::default()).unwrap();
        let n = limits::expanded_objects(&built.scene);
        if n > largest.0 {
            largest = (n, b.name.to_string());
        }
    }
    eprintln!("the largest scene: {} ({} objects)", largest.1, largest.0);
    assert!(largest.0 <= MAX_EXPANDED_OBJECTS / 100, "{largest:?}");
}

#[test]
fn two_hundred_thousand_spheres_load() {
    let mut text = String::from(HEAD);
    for i in 0..200_000 {
        text.push_str(&format!(
            "[[objects]]\ntype = \"sphere\"\ncenter = [{}, {}, 0]\nradius = 0.3\nmaterial = \"white\"\n",
            i % 447,
            i / 447
        ));
    }
    assert!(text.len() as u64 <= MAX_SCENE_FILE_BYTES);
    // the bound of the reader's memory admits a file of spheres as large as a file may be
    let scale = MAX_SCENE_FILE_BYTES as f64 / text.len() as f64;
    assert!(
        limits::toml_read_bytes(&text) as f64 * scale <= limits::MAX_SCENE_READ_BYTES as f64,
        "{}",
        limits::toml_read_bytes(&text)
    );
    let file = load(&text).unwrap();
    assert_eq!(limits::expanded_objects(&file.built.scene), 200_000);
}

#[test]
fn a_file_of_long_dotted_keys_is_refused_before_it_is_read() {
    // 200,000 keys of 16 parts (8.3 MB): each part a table of its own, 3.8 GB for the reader,
    // which the bound once took for 150 MB.
    let text: String = (0..200_000)
        .map(|i| format!("k{i}.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a = 1\n"))
        .collect();
    assert!(limits::toml_read_bytes(&text) > 3_770_000_000);
    let e = load(&text).err().expect("refused");
    assert!(
        e.contains("cannot read scene file") && e.contains("more than the 2.1 GB"),
        "{e}"
    );
}

#[test]
fn a_file_the_toml_reader_would_take_gigabytes_to_hold_is_refused_before_it_is_read() {
    // 7.2 MB of one-key inline tables, within the 32 MiB a scene file may be: the reader took 1.4 kB
    // for each (1.7 GB here; 32 MiB of them took 8 GB, which aborted or was killed where the memory
    // was short, after seconds of reading).
    let text = format!("lights = [{}]\n", vec!["{a=1}"; 1_200_000].join(","));
    assert!(text.len() as u64 <= MAX_SCENE_FILE_BYTES);
    let e = load(&text).err().expect("refused");
    assert!(
        e.starts_with("some/dir/s.toml: cannot read scene file: its 7.2 MB of text")
            && e.contains("more than the 2.1 GB a scene file may take")
            && e.contains("inline tables"),
        "{e}"
    );
    // so are long lists of arrays and of numbers, at their own costs
    for item in ["[[1]]", "0"] {
        let n = (limits::MAX_SCENE_READ_BYTES / limits::toml_read_bytes(&format!("{item},"))) + 1;
        let text = format!("x = [{}]", vec![item; n as usize].join(","));
        assert!(text.len() as u64 <= MAX_SCENE_FILE_BYTES, "{item}");
        let e = load(&text).err().expect("refused");
        assert!(e.contains("cannot read scene file"), "{e}");
    }
}

/// A PNG of `width x height` 8-bit RGB pixels as far as its header says (the signature, the IHDR
/// chunk, and an IDAT chunk of a few bytes that are not its pixels): what a texture's size is read
/// from before decoding.
fn png_header(width: u32, height: u32) -> Vec<u8> {
    fn crc32(bytes: &[u8]) -> u32 {
        let mut c = !0u32;
        for &b in bytes {
            c ^= b as u32;
            for _ in 0..8 {
                c = if c & 1 != 0 {
                    0xedb8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
            }
        }
        !c
    }
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend_from_slice(&width.to_be_bytes());
    ihdr.extend_from_slice(&height.to_be_bytes());
    ihdr.extend_from_slice(&[8, 2, 0, 0, 0]);
    let idat = b"IDAT\x78\x9c\x00\x00\x00\xff\xff".to_vec();
    for chunk in [ihdr, idat, b"IEND".to_vec()] {
        png.extend_from_slice(&(chunk.len() as u32 - 4).to_be_bytes());
        png.extend_from_slice(&chunk);
        png.extend_from_slice(&crc32(&chunk).to_be_bytes());
    }
    png
}

fn textured(file: &str) -> String {
    HEAD.replace(
        "[materials]",
        &format!("[textures]\nimg = {{ type = \"image\", file = \"{file}\" }}\n\n[materials]"),
    )
    .replace("albedo = 0.5", "albedo = \"img\"")
        + "\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"white\"\n"
}

#[test]
fn a_texture_too_large_is_refused_from_its_header_before_decoding() {
    const _: () = assert!(MAX_TEXTURE_PIXELS >= 8192 * 4096 && MAX_TEXTURE_PIXELS >= 1024 * 512);
    let dir = temp_dir("bomb");
    std::fs::write(dir.join("bomb.png"), png_header(12_000, 12_000)).unwrap();
    let scene = dir.join("bomb.toml");
    std::fs::write(&scene, textured("bomb.png")).unwrap();
    let err = finishes({
        let scene = scene.clone();
        move || scene_file::load_file(&scene).err().unwrap().to_string()
    });
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(
        err.starts_with(&format!(
            "{}:6:32: field `textures.img.file`: ",
            scene.display()
        )),
        "{err}"
    );
    assert!(
        err.contains("12000 x 12000 = 144000000 pixels, more than the 33554432 (8192 x 4096)"),
        "{err}"
    );
    // A row of 2^31 - 1 pixels: the image crate's own limits refused its header as "Memory limit
    // exceeded", which named no size; the same message as above names it.
    let dir = temp_dir("row");
    std::fs::write(dir.join("row.png"), png_header(2_147_483_647, 1)).unwrap();
    std::fs::write(dir.join("row.toml"), textured("row.png")).unwrap();
    let err = scene_file::load_file(&dir.join("row.toml"))
        .err()
        .unwrap()
        .to_string();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(
        err.contains("2147483647 x 1 = 2147483647 pixels, more than the 33554432"),
        "{err}"
    );
}

#[test]
fn a_texture_identity_is_its_digest_and_changes_with_its_pixels() {
    let dir = temp_dir("identity");
    let img = |dot: u8| {
        image::RgbImage::from_fn(16, 8, |x, y| {
            image::Rgb([
                x as u8 * 10,
                y as u8 * 20,
                if (x, y) == (3, 5) { dot } else { 7 },
            ])
        })
    };
    img(7).save(dir.join("a.png")).unwrap();
    img(7).save(dir.join("same.png")).unwrap();
    img(8).save(dir.join("b.png")).unwrap();
    let hash = |file: &str| {
        let path = dir.join(format!("{file}.toml"));
        std::fs::write(&path, textured(&format!("{file}.png"))).unwrap();
        scene_hash(&scene_file::load_file(&path).unwrap().built.scene)
    };
    let (a, same, b) = (hash("a"), hash("same"), hash("b"));
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(a, same, "the same pixels from another file");
    assert_ne!(a, b, "one component of one pixel differs");

    // The digest, not the pixels, is what the identity hashes: a 4096 x 2048 texture serialises in
    // a few bytes (byte by byte through the hasher it cost 0.9 s a render).
    let pixels = vec![[0.25f32, 0.5, 0.75]; 4096 * 2048];
    let image = ImageData::new(4096, 2048, pixels.clone());
    let mut b = SceneBuilder::new();
    let t = b.texture(Texture::Image(Box::new(image)));
    let m = b.material(Material::Lambertian {
        albedo: Albedo::Texture(t),
    });
    b.sphere(b.world(), Point3::ZERO, 1.0, m).unwrap();
    let scene = b.build().unwrap();
    assert!(serde_json::to_vec(&scene).unwrap().len() < 4000);
    assert_eq!(rtl_render::texture::texture_bytes(&scene), 4096 * 2048 * 12);
    let mut changed = pixels;
    changed[4096 * 2048 - 1][2] = 0.7500001;
    assert_ne!(
        ImageData::new(4096, 2048, changed).digest(),
        ImageData::new(4096, 2048, vec![[0.25f32, 0.5, 0.75]; 4096 * 2048]).digest()
    );
    // The same pixels in another shape are another image.
    assert_ne!(
        ImageData::new(2, 1, vec![[0.0; 3]; 2]).digest(),
        ImageData::new(1, 2, vec![[0.0; 3]; 2]).digest()
    );
}

#[test]
fn files_that_are_not_regular_files_or_too_large_are_refused() {
    let dir = temp_dir("files");
    let zero = dir.join("zero.toml");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let err = scene_file::load_file(&zero).err().unwrap().to_string();
    assert!(
        err.starts_with(&zero.display().to_string()) && err.contains("not a regular file"),
        "{err}"
    );
    let err = scene_file::load_file(&dir).err().unwrap().to_string();
    assert!(err.contains("not a regular file"), "{err}");

    // A texture that is /dev/zero.
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.png")).unwrap();
    let scene = dir.join("tex.toml");
    std::fs::write(&scene, textured("zero.png")).unwrap();
    let err = scene_file::load_file(&scene).err().unwrap().to_string();
    assert!(
        err.starts_with(&format!(
            "{}:6:32: field `textures.img.file`: ",
            scene.display()
        )) && err.contains("zero.png: cannot read texture file: it is not a regular file"),
        "{err}"
    );

    // A scene file one byte over the limit (sparse: nothing is written).
    let big = dir.join("big.toml");
    std::fs::File::create(&big)
        .unwrap()
        .set_len(MAX_SCENE_FILE_BYTES + 1)
        .unwrap();
    let err = scene_file::load_file(&big).err().unwrap().to_string();
    assert!(
        err.starts_with(&big.display().to_string())
            && err.contains(&format!(
                "({} bytes), more than the 33.6 MB ({MAX_SCENE_FILE_BYTES} bytes) a scene file may be",
                MAX_SCENE_FILE_BYTES + 1
            )),
        "{err}"
    );

    // Bytes that are not UTF-8, named by line and column as a syntax error (it was "byte 40").
    let latin1 = dir.join("latin1.toml");
    std::fs::write(
        &latin1,
        b"# a scene\ndescription = \"caf\xe9 \xe0 Paris\"\n",
    )
    .unwrap();
    let e = scene_file::load_file(&latin1).err().unwrap();
    assert_eq!(e.place().map(|p| (p.line, p.col)), Some((2, 19)), "{e}");
    let e = e.to_string();
    assert!(
        e.starts_with(&format!(
            "{}:2:19: not UTF-8 text: byte 28 (0xe9)",
            latin1.display()
        )),
        "{e}"
    );
    // a byte-order mark and CRLF line ends are UTF-8 TOML like any other
    let bom = dir.join("bom.toml");
    let text = format!(
        "\u{feff}{HEAD}[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"white\"\n"
    );
    std::fs::write(&bom, text.replace('\n', "\r\n")).unwrap();
    assert!(scene_file::load_file(&bom).is_ok());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn duplicate_keys_name_the_key_its_table_and_the_first() {
    let text = format!("{HEAD}\n[camera]\nvfov = 3\n");
    refused(
        &text,
        9,
        &["9:2: duplicate key `camera`: the table [camera] is defined twice (first at line 1:1)"],
    );
    let text = format!(
        "{HEAD}\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nradius = 2\nmaterial = \"white\"\n"
    );
    refused(
        &text,
        13,
        &["13:1: duplicate key `radius` in [[objects]] (first at line 12:1)"],
    );
    let text = HEAD.replace("albedo = 0.5 }", "albedo = 0.5, albedo = 0.2 }")
        + "\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"white\"\n";
    refused(
        &text,
        6,
        &["duplicate key `albedo` in `materials.white` (first at line 6:32)"],
    );
    let text = format!("description = \"a\"\ndescription = \"b\"\n{HEAD}");
    refused(
        &text,
        2,
        &["duplicate key `description` at the top level of the file (first at line 1:1)"],
    );
}

#[test]
fn a_duplicate_name_gives_the_first_by_line_and_column() {
    let sphere = "[[objects]]\ntype = \"sphere\"\nname = \"x\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"white\"\n";
    let text = format!("{HEAD}\n{sphere}{sphere}");
    refused(
        &text,
        17,
        &["field `objects[1].name`: the name `x` is already used (first at line 11:8)"],
    );
}

#[test]
fn tiny_and_huge_numbers_print_short() {
    let quad = "[[objects]]\ntype = \"quad\"\nq = [0, 0, 0]\nu = [1e-70, 0, 0]\nv = [0, 1e-100, 0]\nmaterial = \"white\"\n";
    let err = refused(
        &format!("{HEAD}\n{quad}"),
        12,
        &["zero-area quad: u x v = 0 (u = [1e-70, 0, 0], v = [0, 1e-100, 0] are parallel or zero)"],
    );
    assert!(!err.contains("0.0000"), "{err}");
    // a box too small for its faces' areas to be numbers: the builder's message, short too
    let tiny = "[[objects]]\ntype = \"box\"\na = [1e-300, 1e-300, -1e-300]\nb = [2e-300, 2e-300, 1e-300]\nmaterial = \"white\"\n";
    let err = refused(
        &format!("{HEAD}\n{tiny}"),
        9,
        &[
            "field `objects[0]`: the box with corners [1e-300, 1e-300, -1e-300] and [2e-300, 2e-300, \
             1e-300] is flat, or too small for its faces to have an area",
        ],
    );
    assert!(!err.contains("0.0000"), "{err}");
    let text = HEAD.replace("lookfrom = [0, 0, -10]", "lookfrom = [1e-300, 0, 0]")
        + "\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 1]\nradius = 1\nmaterial = \"white\"\n";
    refused(
        &text,
        3,
        &["lookfrom and lookat are only 1e-300 apart: they must be at least 1e-30 apart"],
    );
    // Ordinary numbers still print as written.
    let text = HEAD.replace("lookat = [0, 0, 0]", "lookat = [0, 0, -10]")
        + "\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 1]\nradius = 1\nmaterial = \"white\"\n";
    refused(&text, 3, &["lookfrom and lookat are the same point"]);
    let flat =
        "[[objects]]\ntype = \"box\"\na = [0, 0, 0]\nb = [1.5, 0, 2]\nmaterial = \"white\"\n";
    refused(&format!("{HEAD}\n{flat}"), 12, &["(size 1.5 x 0 x 2)"]);
}
