//! Scene files written in a test: a camera and two materials to start from ([`HEAD`]), and the
//! loader's reading of a text as the file `some/dir/s.toml` ([`load`]).

use rtl_render::scene_file::{self, SceneFile};
use std::path::Path;

/// A camera, a white Lambertian material `white` and an emitter `lamp`.
pub const HEAD: &str = r#"[camera]
lookfrom = [0, 0, -10]
lookat = [0, 0, 0]

[materials]
white = { type = "lambertian", albedo = 0.5 }
lamp = { type = "light", emit = [4, 4, 4] }
"#;

/// `text` loaded as `some/dir/s.toml`, or the message that refuses it.
pub fn load(text: &str) -> Result<SceneFile, String> {
    scene_file::load_str(text, "some/dir/s.toml", Path::new("some/dir")).map_err(|e| e.to_string())
}
