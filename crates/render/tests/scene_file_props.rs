//! Properties of the scene-file loader over generated files (a few hundred cases, seconds): whatever
//! numbers stand in any field (NaN, infinities, 1e308, subnormals, zero, negatives), the loader returns
//! without a panic; an error names the file, line and column; and a scene it accepts renders a small
//! image of finite pixels with no sample dropped as non-finite.

use proptest::prelude::*;
use rtl_render::integrator::Strategy as Integrator;
use rtl_render::render::{RenderSettings, render};
use rtl_render::scene_file::load_str;
use std::path::Path;

/// Numbers from every class that broke something once, and ordinary ones.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("1e308".to_string()),
        Just("-1e308".to_string()),
        Just("1e31".to_string()),
        Just("1e30".to_string()),
        Just("5e-324".to_string()),
        Just("1e-310".to_string()),
        Just("1e-31".to_string()),
        Just("0".to_string()),
        Just("-0.0".to_string()),
        Just("-1".to_string()),
        Just("1e-300".to_string()),
        (-1e3f64..1e3).prop_map(|x| format!("{x:e}")),
        (0.01f64..10.0).prop_map(|x| format!("{x}")),
        (0u32..200).prop_map(|x| x.to_string()),
    ]
}

fn vec3() -> impl Strategy<Value = String> {
    (number(), number(), number()).prop_map(|(a, b, c)| format!("[{a}, {b}, {c}]"))
}

/// A scene file whose numeric fields are sane values, each replaced by one of [`number`] one time in
/// sixteen (so that about 40% of the files are accepted and rendered).
fn scene() -> impl Strategy<Value = String> {
    let sane = |s: &'static str| Just(s.to_string());
    (
        (
            prop_oneof![15 => sane("1.0"), 1 => number()],                // aspect
            prop_oneof![15 => sane("40"), 1 => number()],                 // vfov
            prop_oneof![15 => sane("[0, 0, -5]"), 1 => vec3()],           // lookfrom
            prop_oneof![15 => sane("0"), 1 => number()],                  // defocus_angle
            prop_oneof![15 => sane("5"), 1 => number()],                  // focus_dist
            prop_oneof![15 => sane("[0, 1]"), 1 => (number(), number()).prop_map(|(a, b)| format!("[{a}, {b}]"))],
        ),
        (
            prop_oneof![15 => sane("0.5"), 1 => number()],                // albedo
            prop_oneof![15 => sane("1.5"), 1 => number()],                // ior
            prop_oneof![15 => sane("0.1"), 1 => number()],                // fuzz
            prop_oneof![15 => sane("[4, 4, 4]"), 1 => vec3()],            // emit
            prop_oneof![15 => sane("0.5"), 1 => number()],                // checker scale
            prop_oneof![15 => sane("2"), 1 => number()],                  // marble scale
        ),
        (
            prop_oneof![15 => sane("[0, 0, 0]"), 1 => vec3()],            // sphere centre
            prop_oneof![15 => sane("1"), 1 => number()],                  // radius
            prop_oneof![15 => sane("[2, 0, 0]"), 1 => vec3()],            // quad u
            prop_oneof![15 => sane("15"), 1 => number()],                 // rotate_y
            prop_oneof![15 => sane("[0, 0, 1]"), 1 => vec3()],            // translate
            prop_oneof![15 => sane("0.2"), 1 => number()],                // density
        ),
    )
        .prop_map(
            |(
                (aspect, vfov, lookfrom, defocus, focus, shutter),
                (albedo, ior, fuzz, emit, checker, marble),
                (center, radius, u, rot, tr, density),
            )| {
                format!(
                    r#"lights = ["lamp"]
[render]
aspect = {aspect}
max_depth = 4
[camera]
vfov = {vfov}
lookfrom = {lookfrom}
lookat = [0, 0, 0]
defocus_angle = {defocus}
focus_dist = {focus}
shutter = {shutter}
[textures]
tiles = {{ type = "checker", scale = {checker}, even = 0.2, odd = {albedo} }}
stone = {{ type = "marble", scale = {marble} }}
[materials]
white = {{ type = "lambertian", albedo = {albedo} }}
floor = {{ type = "lambertian", albedo = "tiles" }}
rock = {{ type = "lambertian", albedo = "stone" }}
glass = {{ type = "dielectric", ior = {ior} }}
steel = {{ type = "metal", albedo = [0.8, 0.8, 0.8], fuzz = {fuzz} }}
lamp = {{ type = "light", emit = {emit} }}
[[objects]]
type = "sphere"
center = {center}
radius = {radius}
material = "glass"
[[objects]]
type = "quad"
name = "lamp"
q = [-1, 2, -1]
u = {u}
v = [0, 0, 2]
material = "lamp"
[[objects]]
type = "box"
a = [-1, -1, -1]
b = [1, 1, 1]
material = "floor"
transform = [{{ rotate_y = {rot} }}, {{ translate = {tr} }}]
[[objects]]
type = "moving_sphere"
center0 = [0, -3, 0]
center1 = {center}
radius = 0.5
material = "steel"
[[objects]]
type = "medium"
density = {density}
albedo = 0.9
boundary = {{ type = "sphere", center = [3, 0, 0], radius = 1, material = "rock" }}
[[objects]]
type = "sphere"
center = [-3, 0, 0]
radius = 1
material = "rock"
"#
                )
            },
        )
}

proptest! {
    // A fixed seed: the same cases every run.
    #![proptest_config(ProptestConfig {
        cases: 300,
        rng_seed: proptest::test_runner::RngSeed::Fixed(15),
        ..ProptestConfig::default()
    })]

    #[test]
    fn every_generated_file_loads_and_renders_finite_pixels_or_is_an_error_naming_its_place(
        text in scene()
    ) {
        match load_str(&text, "gen.toml", Path::new(".")) {
            Err(e) => {
                let msg = e.to_string();
                let place = e.place().expect("a place in the file");
                prop_assert!(msg.starts_with(&format!("gen.toml:{}:{}: ", place.line, place.col)), "{msg}");
                prop_assert!(place.line >= 1 && place.col >= 1);
            }
            Ok(file) => {
                let settings = RenderSettings {
                    width: 6,
                    max_depth: 4,
                    seed: 1,
                    strategy: Integrator::default(),
                    mixture_weight: rtl_render::render::BOOK_MIXTURE_WEIGHT,
                };
                let (acc, stats) = render(&file.built.scene, settings, 2);
                prop_assert!(acc.image().iter().all(|c| c.is_finite() && c.min_element() >= 0.0));
                prop_assert_eq!(stats.non_finite, 0, "{}", text);
            }
        }
    }

    #[test]
    fn any_text_at_all_is_refused_or_loaded_without_a_panic(text in "\\PC{0,200}") {
        if let Err(e) = load_str(&text, "x.toml", Path::new(".")) {
            prop_assert!(e.to_string().starts_with("x.toml:"));
        }
    }
}
