//! Several emitters of different kinds, one of them one-sided and seen from behind by part of the
//! scene: `cosine`, `mixture` and `mis` must agree on the mean of every image region (batch means,
//! Welch t-test), as on the Cornell box in `strategies.rs`. The Cornell box has one light and hides
//! what goes wrong with several: a light drawn from behind, whose direction then meets the front of
//! another emitter, weighted by a density that does not describe how it was drawn (issue 12).

use rtl_pdf::ShapeSampler as _;
use rtl_render::Color;
use rtl_render::camera::CameraSettings;
use rtl_render::integrator::{MisOptions, Strategy};
use rtl_render::material::{Albedo, Material};
use rtl_render::render::{RenderSettings, render};
use rtl_render::scene::{Background, ImportanceTarget, Scene, SceneBuilder};
use rtl_render::shapes::Sphere;
use rtl_render::vec::{Point3, Vec3};

mod batch_means;
use batch_means::{mean_var, welch_p};

const WIDTH: usize = 24;
const BATCHES: u64 = 32;
const BATCH_SPP: u64 = 16;
/// The image is cut into `GRID x GRID` regions of 6 x 6 pixels.
const GRID: usize = 4;

/// An open room (floor, ceiling, back wall) with four emitters listed as targets:
/// - a one-sided 1 x 1 quad at y = 2 facing down (the floor sees its front);
/// - a one-sided 2 x 2 quad at y = 2.5 right above it, facing up: the floor sees its back, and most
///   directions from the floor towards it pass through the front of the quad below; the ceiling sees
///   its front;
/// - a sphere;
/// - a two-sided quad standing upright.
pub fn three_kinds_of_emitters() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    let one_sided = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(4.0)),
        two_sided: false,
    });
    let two_sided = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(2.0)),
        two_sided: true,
    });
    // floor (y = 0), ceiling (y = 4, facing down), back wall (z = -3)
    b.quad(
        w,
        Point3::new(-4.0, 0.0, 3.0),
        Vec3::new(8.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -6.0),
        white,
    )
    .unwrap();
    b.quad(
        w,
        Point3::new(-4.0, 4.0, 3.0),
        Vec3::new(0.0, 0.0, -6.0),
        Vec3::new(8.0, 0.0, 0.0),
        white,
    )
    .unwrap();
    b.quad(
        w,
        Point3::new(-4.0, 0.0, -3.0),
        Vec3::new(8.0, 0.0, 0.0),
        Vec3::new(0.0, 4.0, 0.0),
        white,
    )
    .unwrap();
    // u x v = (0, -1, 0): faces down
    let lower = b
        .quad(
            w,
            Point3::new(-2.0, 2.0, -0.5),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
            one_sided,
        )
        .unwrap();
    // u x v = (0, +1, 0): faces up
    let upper = b
        .quad(
            w,
            Point3::new(-2.5, 2.5, -1.0),
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::new(2.0, 0.0, 0.0),
            one_sided,
        )
        .unwrap();
    b.sphere(w, Point3::new(1.5, 1.0, -1.0), 0.5, two_sided)
        .unwrap();
    let upright = b
        .quad(
            w,
            Point3::new(3.0, 0.5, -2.0),
            Vec3::new(0.0, 0.0, 1.5),
            Vec3::new(0.0, 1.5, 0.0),
            two_sided,
        )
        .unwrap();
    b.targets.push(ImportanceTarget::Quad(lower));
    b.targets.push(ImportanceTarget::Quad(upper));
    b.targets.push(ImportanceTarget::Sphere(Sphere::new(
        Point3::new(1.5, 1.0, -1.0),
        0.5,
        two_sided,
    )));
    b.targets.push(ImportanceTarget::Quad(upright));
    b.camera = CameraSettings {
        lookfrom: Point3::new(0.0, 2.0, 7.0),
        lookat: Point3::new(0.0, 2.0, 0.0),
        vfov: 60.0,
        ..CameraSettings::default()
    };
    b.background = Background::Solid(Color::ZERO);
    b.max_depth = 50;
    b.build().unwrap()
}

/// A floor, a one-sided ceiling light (listed as the scene's only target) and a box of smoke
/// (constant density 0.6, albedo 0.8) with an emitting ball inside it that no list names: next-event
/// estimation must find the ball by itself and weight shadow rays by the smoke's transmittance.
pub fn medium_and_lights() -> Scene {
    medium_and_lights_with(false)
}

/// [`medium_and_lights`], and if `lamp_facing_up`, a second one-sided lamp between the smoke and the
/// ceiling light, facing up: every point of the smoke sees it from behind (where it offers no
/// direction and has density 0), and it shades part of the ceiling light.
fn medium_and_lights_with(lamp_facing_up: bool) -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    let smoke = b.material(Material::Isotropic {
        albedo: Albedo::Constant(Color::splat(0.8)),
    });
    let ceiling = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(6.0)),
        two_sided: false,
    });
    let glow = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(3.0)),
        two_sided: true,
    });
    b.quad(
        w,
        Point3::new(-4.0, 0.0, 3.0),
        Vec3::new(8.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -6.0),
        white,
    )
    .unwrap();
    let lamp = b
        .quad(
            w,
            Point3::new(-1.0, 4.0, -1.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 2.0),
            ceiling,
        )
        .unwrap();
    b.targets.push(ImportanceTarget::Quad(lamp));
    if lamp_facing_up {
        // u x v points up (+y): its front faces the ceiling light's back.
        b.quad(
            w,
            Point3::new(-0.5, 3.0, -0.5),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 0.0),
            ceiling,
        )
        .unwrap();
    }
    let boundary = b
        .box_group(
            Point3::new(-1.5, 0.5, -1.5),
            Point3::new(1.5, 2.5, 1.5),
            white,
        )
        .unwrap();
    b.medium(w, boundary, 0.6, smoke).unwrap();
    b.sphere(w, Point3::new(0.3, 1.5, 0.0), 0.3, glow).unwrap();
    b.camera = CameraSettings {
        lookfrom: Point3::new(0.0, 2.0, 7.0),
        lookat: Point3::new(0.0, 1.8, 0.0),
        vfov: 55.0,
        ..CameraSettings::default()
    };
    b.background = Background::Solid(Color::ZERO);
    b.max_depth = 50;
    b.build().unwrap()
}

fn settings(seed: u64, strategy: Strategy) -> RenderSettings {
    RenderSettings {
        width: WIDTH,
        max_depth: 50,
        seed,
        strategy,
        mixture_weight: rtl_render::render::BOOK_MIXTURE_WEIGHT,
    }
}

/// Per region, its mean radiance (channel 0; the scene is grey) in each of `BATCHES` independent
/// renders.
fn batch_means(scene: &Scene, strategy: Strategy) -> Vec<Vec<f64>> {
    let cell = WIDTH / GRID;
    let mut out = vec![Vec::new(); GRID * GRID];
    for b in 0..BATCHES {
        let (acc, stats) = render(scene, settings(2000 + b, strategy), BATCH_SPP);
        assert_eq!(stats.non_finite, 0, "{}", strategy.name());
        let img = acc.image();
        for (r, o) in out.iter_mut().enumerate() {
            let (ci, cj) = (r % GRID, r / GRID);
            let mut sum = 0.0;
            for j in cj * cell..(cj + 1) * cell {
                for i in ci * cell..(ci + 1) * cell {
                    sum += img[j * WIDTH + i].x;
                }
            }
            o.push(sum / (cell * cell) as f64);
        }
    }
    out
}

/// Every region's p-value for `a` against `b`, with a description.
fn compare(a: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<(f64, String)> {
    a.iter()
        .zip(b)
        .enumerate()
        .map(|(r, (x, y))| {
            (
                welch_p(x, y),
                format!(
                    "region ({}, {}): {:.5} vs {:.5}",
                    r % GRID,
                    r / GRID,
                    mean_var(x).0,
                    mean_var(y).0
                ),
            )
        })
        .collect()
}

/// Every pair of `strategies` agrees on every region's mean.
fn agree(scene: &Scene, strategies: &[Strategy]) {
    let means: Vec<_> = strategies.iter().map(|&s| batch_means(scene, s)).collect();
    let pairs = strategies.len() * (strategies.len() - 1) / 2;
    // Family-wise false-failure rate 1e-6, Bonferroni over every comparison.
    let alpha = 1e-6 / (pairs * GRID * GRID) as f64;
    let mut failures = Vec::new();
    for x in 0..strategies.len() {
        for y in x + 1..strategies.len() {
            for (p, what) in compare(&means[x], &means[y]) {
                if p < alpha {
                    failures.push(format!(
                        "{:?} vs {:?}: {what}, p = {p:.2e}",
                        strategies[x], strategies[y]
                    ));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "alpha {alpha:.1e}:\n{}",
        failures.join("\n")
    );
}

#[test]
fn several_emitters_cosine_mixture_and_mis_agree() {
    agree(
        &three_kinds_of_emitters(),
        &[
            Strategy::Cosine,
            Strategy::Mixture,
            Strategy::Mis(MisOptions::default()),
            Strategy::Mis(MisOptions {
                low_discrepancy: false,
                ..MisOptions::default()
            }),
            Strategy::Mis(MisOptions {
                spherical_rectangles: true,
                ..MisOptions::default()
            }),
        ],
    );
}

#[test]
fn a_medium_with_lights_cosine_mixture_and_mis_agree() {
    let scene = medium_and_lights();
    let lights = rtl_render::lights::Lights::new(&scene, false);
    assert_eq!(
        (lights.emitters.len(), lights.listed_emitters),
        (2, 1),
        "the ball in the smoke is found without being listed"
    );
    agree(
        &scene,
        &[
            Strategy::Cosine,
            Strategy::Mixture,
            Strategy::Mis(MisOptions::default()),
            Strategy::Mis(MisOptions {
                low_discrepancy: false,
                russian_roulette: false,
                ..MisOptions::default()
            }),
        ],
    );
}

#[test]
fn a_medium_under_a_lamp_seen_from_behind_cosine_and_mis_agree() {
    // The smoke's light samples (at points on each ray's segment through it, and at surface points)
    // draw among three emitters, one of which every point of the smoke sees from behind.
    let scene = medium_and_lights_with(true);
    let lights = rtl_render::lights::Lights::new(&scene, false);
    assert_eq!(lights.emitters.len(), 3);
    let inside = Point3::new(0.0, 1.5, 0.5);
    let behind = lights
        .emitters
        .iter()
        .filter(|t| t.sample(inside, glam::DVec2::new(0.3, 0.6)).is_none())
        .count();
    assert_eq!(
        behind, 1,
        "one lamp is seen from behind and offers no direction"
    );
    agree(
        &scene,
        &[
            Strategy::Cosine,
            Strategy::Mixture,
            Strategy::Mis(MisOptions::default()),
        ],
    );
}
