//! The scene-file loader on arbitrary text: it returns a scene or an error, never panics or hangs.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let _ = rtl_render::scene_file::load_str(text, "fuzz.toml", std::path::Path::new("."));
});
