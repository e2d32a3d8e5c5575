//! Where book2-final's noise is: the squared difference of two renders with different seeds, in the
//! book's 8-bit gamma-2 display encoding, summed by what each pixel's camera ray first meets.
//! A measurement, not a check: `cargo test --release -p rtl-render --test book2_final_noise --
//! --ignored --nocapture` (env `B2F_WIDTH`, `B2F_SPP`, `B2F_SPH_RECT`).

use rtl_render::integrator::{MisOptions, Strategy};
use rtl_render::media_crossed::MediumMode;
use rtl_render::render::{RenderSettings, Renderer};
use rtl_render::sampler::Ctx;
use rtl_render::scenes;
use rtl_render::{Color, Point3};

/// The book's byte of one channel, `floor(256 clamp(sqrt(x), 0, 0.999))`, as a display value `v / 256`.
fn display(x: f64) -> f64 {
    let x = if x.is_nan() { 0.0 } else { x };
    (256.0 * x.max(0.0).sqrt().min(0.999)).floor() / 256.0
}

const KINDS: [&str; 11] = [
    "ground boxes",
    "light",
    "moving sphere",
    "glass sphere",
    "metal sphere",
    "subsurface sphere",
    "earth",
    "Perlin sphere",
    "1000 spheres",
    "nothing (fog only)",
    "other",
];

/// What a surface point belongs to, from where it is (the glass material is shared).
fn kind(p: Point3, material_name: &str) -> usize {
    let on = |c: Point3, r: f64| ((p - c).length() - r).abs() < 1e-3 * r.max(1.0);
    if material_name == "ground" {
        0
    } else if material_name == "light" {
        1
    } else if on(Point3::new(260.0, 150.0, 45.0), 50.0) {
        3
    } else if on(Point3::new(0.0, 150.0, 145.0), 50.0) {
        4
    } else if on(Point3::new(360.0, 150.0, 145.0), 70.0) {
        5
    } else if on(Point3::new(400.0, 200.0, 400.0), 100.0) {
        6
    } else if on(Point3::new(220.0, 280.0, 300.0), 80.0) {
        7
    } else if material_name == "white" {
        8
    } else if material_name == "orange" {
        2
    } else if p.length() > 4000.0 {
        9
    } else {
        10
    }
}

#[test]
#[ignore = "a measurement: run with --ignored --nocapture"]
fn book2_final_squared_error_by_first_hit() {
    let width: usize = std::env::var("B2F_WIDTH").map_or(200, |s| s.parse().unwrap());
    let spp: u64 = std::env::var("B2F_SPP").map_or(16, |s| s.parse().unwrap());
    let sph = std::env::var("B2F_SPH_RECT").is_ok();
    let built = (scenes::find("book2-final").unwrap().build)(&Default::default()).unwrap();
    let scene = &built.scene;
    let names: Vec<&str> = scene
        .materials
        .iter()
        .map(|m| match m {
            rtl_render::material::Material::Lambertian { albedo } => {
                let c = format!("{albedo:?}");
                if c.contains("0.48") {
                    "ground"
                } else if c.contains("0.73") {
                    "white"
                } else if c.contains("0.7") {
                    "orange"
                } else {
                    "lambertian"
                }
            }
            rtl_render::material::Material::DiffuseLight { .. } => "light",
            _ => "other",
        })
        .collect();
    let strategy = Strategy::Mis(MisOptions {
        spherical_rectangles: sph,
        ..MisOptions::DEFAULT
    });
    let settings = |seed| RenderSettings {
        width,
        max_depth: scene.max_depth,
        seed,
        strategy,
        mixture_weight: 0.5,
    };
    let (r1, r2) = (
        Renderer::new(scene, settings(1)),
        Renderer::new(scene, settings(2)),
    );
    let (w, h) = (r1.camera.width, r1.camera.height);
    let mut ctx = Ctx::new();
    let mut sum = [0.0f64; KINDS.len()];
    let mut pixels = [0usize; KINDS.len()];
    let mut total = 0.0;
    for j in 0..h {
        for i in 0..w {
            // The class: the first surface of the pixel's camera ray (media passed through), by majority.
            let mut votes = [0u32; KINDS.len()];
            for k in 0..4 {
                let ray = r1.camera.ray(i, j, 0, k, &mut ctx);
                ctx.media = MediumMode::Record;
                ctx.crossed.clear();
                let v = match scene.hit(&ray, &mut ctx) {
                    Some(hit) => kind(hit.p, names[hit.material.index()]),
                    None => 9,
                };
                ctx.media = MediumMode::Scatter;
                votes[v] += 1;
            }
            let class = (0..KINDS.len()).max_by_key(|&c| votes[c]).unwrap();
            let mut mean = |r: &Renderer| {
                let mut s = Color::ZERO;
                for k in 0..spp {
                    let v = r.sample(i, j, k, &mut ctx);
                    if v.is_finite() {
                        s += v;
                    }
                }
                s / spp as f64
            };
            let (a, b) = (mean(&r1), mean(&r2));
            let d2: f64 = (0..3)
                .map(|c| (display(a[c]) - display(b[c])).powi(2))
                .sum::<f64>()
                / 3.0;
            sum[class] += d2;
            pixels[class] += 1;
            total += d2;
        }
    }
    let n = (w * h) as f64;
    // c = RMS(a - b) / sqrt(2) * sqrt(spp), in display values.
    let c = |s: f64| (s / n / 2.0 * spp as f64).sqrt();
    println!(
        "book2-final {w}x{h}, {spp} spp, mis (spherical rectangles {sph}): c = {:.3}",
        c(total)
    );
    println!("| first hit | pixels | share of c^2 | c within |");
    println!("|---|---:|---:|---:|");
    let mut order: Vec<usize> = (0..KINDS.len()).filter(|&k| pixels[k] > 0).collect();
    order.sort_by(|&a, &b| sum[b].total_cmp(&sum[a]));
    for k in order {
        println!(
            "| {} | {:.1}% | {:.1}% | {:.3} |",
            KINDS[k],
            100.0 * pixels[k] as f64 / n,
            100.0 * sum[k] / total,
            (sum[k] / pixels[k] as f64 / 2.0 * spp as f64).sqrt()
        );
    }
}
