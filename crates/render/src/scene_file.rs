//! Scene files: the objects of the built-in scenes described in TOML, so users write scenes without
//! recompiling (`rtl render path/to/scene.toml`).
//!
//! A file reads like the books' `main` functions: named textures and materials in tables, objects in an
//! array of tables, each with a `type`, and an optional list of transform steps applied in order.
//!
//! ```toml
//! description = "a glass ball in a white box"   # top-level keys come before the first [table]
//! lights = ["lamp", "ball"]                      # importance targets: named objects or inline shapes
//!
//! [render]                   # defaults the command line may override
//! width = 400                # --width
//! aspect = 1.0               # or "16:9"
//! spp = 64                   # --spp
//! max_depth = 50             # --max-depth
//! background = [0, 0, 0]     # or "sky" (book 1's gradient)
//!
//! [camera]
//! vfov = 40
//! lookfrom = [278, 278, -800]
//! lookat = [278, 278, 0]
//! vup = [0, 1, 0]            # default [0, 1, 0]
//! defocus_angle = 0          # degrees; 0 is a pinhole
//! focus_dist = 10
//! shutter = [0, 1]           # the times the shutter opens and closes
//!
//! [textures]
//! tiles = { type = "checker", scale = 0.32, even = [0.2, 0.3, 0.1], odd = 0.9 }
//!
//! [materials]
//! white = { type = "lambertian", albedo = 0.73 }
//! floor = { type = "lambertian", albedo = "tiles" }
//! glass = { type = "dielectric", ior = 1.5 }
//! lamp = { type = "light", emit = [15, 15, 15] }   # one-sided unless two_sided = true
//!
//! [[objects]]
//! type = "quad"
//! name = "lamp"
//! q = [213, 554, 227]
//! u = [130, 0, 0]
//! v = [0, 0, 105]
//! material = "lamp"
//!
//! [[objects]]
//! type = "box"
//! a = [0, 0, 0]
//! b = [165, 330, 165]
//! material = "white"
//! transform = [{ rotate_y = 15 }, { translate = [265, 0, 295] }]
//! ```
//!
//! Object types: `sphere` (center, radius), `moving_sphere` (center0 at time 0, center1 at time 1,
//! radius), `quad` (q, u, v), `box` (opposite corners a, b), `group` (its own
//! `[[objects.objects]]`, with its own BVH), `instance` (`of` = the name of a group or box, placed
//! again) and `medium` (a constant-density medium: `density`, `albedo`, and a `boundary` object,
//! which must enclose a volume: a sphere, a moving sphere, a box, a group or instance of them, or
//! quads each of whose edges is an edge of exactly one other quad, as
//! [`SceneBuilder::open_quad`](crate::builder::SceneBuilder::open_quad) decides; an open one is
//! refused at its `type`, naming its first open quad; so are pieces of it that overlap or touch,
//! [`crate::boundary_pieces`]). Textures: `solid`, `checker`, `marble`,
//! `image` (`file`, relative to the scene file). Materials: `lambertian`, `metal`, `dielectric`,
//! `light`, `isotropic`.
//!
//! Every error names the place: `FILE:LINE:COL: field objects[2].radius: message`.
//!
//! Values obey the rules of [`crate::limits`], the same as the command line's: finite numbers of
//! magnitude at most 1e30, positive quantities at least 1e-30, albedos in [0, 1], `max_depth` 1 to
//! 10 000, aspect ratios within [1/65536, 65536]. A scene holds at most
//! [`MAX_EXPANDED_OBJECTS`](crate::limits::MAX_EXPANDED_OBJECTS) objects once its instances are
//! expanded and nests groups at most [`MAX_NESTING`](crate::limits::MAX_NESTING) deep, counted as each
//! object is read (an instance counts again every object of the group it places), so that a few
//! kilobytes of instances of instances are refused at the object that crosses the limit, before
//! anything is expanded; scene and texture files are regular files of bounded size, a scene file one
//! the TOML reader can hold within 2 GiB and the memory available (bounded from its text), and an image
//! texture's size is read from its header before it is decoded. [`load_str`] is the entry point
//! without the file system (the fuzz target's); [`load_file`] reads a file. The parts: `doc.rs` (the document's serde
//! types), `span.rs` (places and the typed [`SceneFileError`]), `values.rs` (numbers, vectors,
//! colours), `loader.rs` (the top-level tables) and `objects.rs` (one function per object kind).

mod doc;
mod loader;
mod objects;
mod span;
mod values;

pub use span::{Field, Place, SceneFileError, line_col};

use crate::scenes::Built;
use loader::Loader;
use std::path::{Path, PathBuf};
use toml::de::DeTable;

/// A scene read from a file, with the render defaults the file asks for.
pub struct SceneFile {
    pub built: Built,
    /// `[render] width`, if given.
    pub width: Option<usize>,
    /// Where `width` is written (line, column), for a message about the image it makes.
    pub width_at: Option<(usize, usize)>,
    /// `[render] spp`, if given.
    pub spp: Option<u64>,
    /// The top-level `description`, if given.
    pub description: Option<String>,
    /// The image files its textures were read from, as found (relative to the scene file's
    /// directory): inputs, which a render's outputs must not overwrite.
    pub texture_files: Vec<PathBuf>,
}

/// Load the scene in the file at `path`, with its render defaults; image textures are found relative to
/// the file's directory.
///
/// The file must be a regular file (not a directory, a device such as `/dev/zero` or a pipe) of at
/// most [`MAX_SCENE_FILE_BYTES`](crate::limits::MAX_SCENE_FILE_BYTES), in UTF-8.
pub fn load_file(path: &Path) -> Result<SceneFile, SceneFileError> {
    let read_error = |message: String| SceneFileError::Read {
        path: path.to_path_buf(),
        message,
    };
    let checkpoint = || {
        read_error(format!(
            "{} is a checkpoint of rtl (a part), not a scene file: continue it with `rtl render \
             SCENE --resume {0}`, or make its image with `rtl merge {0}`",
            path.display()
        ))
    };
    let bytes =
        crate::limits::read_regular_file(path, "scene file", crate::limits::MAX_SCENE_FILE_BYTES)
            .map_err(|m| {
            if is_checkpoint(path) {
                checkpoint()
            } else {
                read_error(m)
            }
        })?;
    if bytes.starts_with(crate::checkpoint::MAGIC) {
        return Err(checkpoint());
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        // The place of the first byte that is not UTF-8, as a syntax error's (the text before it is)
        let at = e.utf8_error().valid_up_to();
        let bytes = e.as_bytes();
        let before = std::str::from_utf8(&bytes[..at]).unwrap_or_default();
        let (line, col) = line_col(before, at);
        SceneFileError::Syntax {
            place: Place {
                file: path.to_path_buf(),
                line,
                col,
            },
            message: format!(
                "not UTF-8 text: byte {at} (0x{:02x}) is not part of a UTF-8 character (a scene \
                 file is TOML, which is UTF-8: save it as UTF-8)",
                bytes[at]
            ),
        }
    })?;
    let dir = path.parent().unwrap_or(Path::new(""));
    let name = path.display().to_string();
    reading_fits(&text, &name, crate::limits::available_memory())?;
    load_str(&text, &name, dir)
}

/// Whether the regular file at `path` begins as a checkpoint does ([`crate::checkpoint::MAGIC`]),
/// read no further than that (a checkpoint may be larger than a scene file may be).
fn is_checkpoint(path: &Path) -> bool {
    use std::io::Read;
    let mut head = [0u8; 8];
    std::fs::metadata(path).is_ok_and(|m| m.is_file())
        && std::fs::File::open(path).is_ok_and(|mut f| f.read_exact(&mut head).is_ok())
        && &head == crate::checkpoint::MAGIC
}

/// Refuse `text` (the file `name`) if the TOML reader would take more memory to hold it than
/// [`MAX_SCENE_READ_BYTES`](crate::limits::MAX_SCENE_READ_BYTES) or than is `available`, as
/// [`toml_read_bytes`](crate::limits::toml_read_bytes) bounds it: before it is read, rather than
/// abort (or be killed) on an allocation half-way.
fn reading_fits(
    text: &str,
    name: &str,
    available: Option<crate::limits::Available>,
) -> Result<(), SceneFileError> {
    use crate::limits::{Bytes, MAX_SCENE_READ_BYTES, toml_read_bytes};
    let needed = toml_read_bytes(text);
    let beyond = if needed > MAX_SCENE_READ_BYTES {
        format!(
            "more than the {} a scene file may take (its tables, arrays, keys and list elements \
             cost memory, inline tables most: about 1.3 kB each)",
            Bytes(MAX_SCENE_READ_BYTES)
        )
    } else {
        match available {
            Some(a) if needed > a.bytes => format!("but {a}"),
            _ => return Ok(()),
        }
    };
    Err(SceneFileError::Read {
        path: name.into(),
        message: format!(
            "{name}: cannot read scene file: its {} of text would take the TOML reader up to {} of \
             memory, {beyond}",
            Bytes(text.len() as u64),
            Bytes(needed)
        ),
    })
}

/// Build the scene described by `text`. `name` names the file in errors (`name:line:col: ...`), and
/// image textures are read relative to `base_dir`, the only files this touches. The entry point of the
/// scene-file fuzz target: whatever `text` is, this returns, without a panic.
pub fn load_str(text: &str, name: &str, base_dir: &Path) -> Result<SceneFile, SceneFileError> {
    let file = Path::new(name);
    reading_fits(text, name, None)?;
    let root = DeTable::parse(text).map_err(|e| SceneFileError::syntax(file, text, &e))?;
    Loader::new(base_dir.to_path_buf(), text)
        .load(root)
        .map_err(|f| {
            // The document again, to name the field (it parsed once, so it parses again), rather
            // than a copy of it kept through the whole load for errors alone
            let tree = DeTable::parse(text)
                .map(|t| t.into_inner())
                .unwrap_or_default();
            f.locate(file, text, &tree)
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_syntax_error_names_file_line_and_column() {
        let err = load_str("ok = 1\nnot = a [scene\n", "bad.toml", Path::new(""))
            .err()
            .unwrap();
        assert!(err.to_string().starts_with("bad.toml:2:"), "{err}");
        assert_eq!(err.place().map(|p| p.line), Some(2));
    }

    #[test]
    fn a_file_is_read_only_within_the_memory_available() {
        use crate::limits::{Available, MemoryLimit, toml_read_bytes};
        let text = "[camera]\nlookfrom = [0, 0, 5]\nlookat = [0, 0, 0]\n";
        let needed = toml_read_bytes(text);
        let left = |bytes| {
            Some(Available {
                bytes,
                limit: MemoryLimit::AddressSpace,
            })
        };
        assert!(reading_fits(text, "s.toml", left(needed)).is_ok());
        assert!(reading_fits(text, "s.toml", None).is_ok());
        let e = reading_fits(text, "s.toml", left(needed - 1))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("s.toml: cannot read scene file: its 49 B of text")
                && e.contains("ulimit -v"),
            "{e}"
        );
    }

    #[test]
    fn field_paths_follow_the_document() {
        let text = "[[objects]]\ntype = \"sphere\"\nradius = 3\n";
        let root = DeTable::parse(text).unwrap();
        let at = text.find('3').unwrap();
        assert_eq!(
            span::field_at(root.get_ref(), &(at..at + 1)),
            "objects[0].radius"
        );
    }
}
