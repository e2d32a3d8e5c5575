//! `mis`'s forced scattering (a camera ray that would leave the scene through a medium scatters in
//! it on every path, at a point drawn from a mix of the equiangular density and the truncated
//! exponential, weighted `sigma T / p`, the background seen with the rest `T`) against `cosine`
//! (book 2's distance sampling, no light samples) and against `mis` without it, on the mean of every
//! image region (batch means, Welch t-test, family-wise false-failure rate 1e-6). Two deliberately
//! wrong variants must be caught: the vertex's weight without the truncation's `1 - exp(-tau)`, and
//! the background left out.

use rtl_render::Color;
use rtl_render::camera::CameraSettings;
use rtl_render::integrator::{MisVariant, Strategy};
use rtl_render::material::{Albedo, Material};
use rtl_render::render::render;
use rtl_render::scene::{Background, Scene, SceneBuilder};
use rtl_render::vec::{Point3, Vec3};

mod batch_means;
mod variant_batches;

const WIDTH: usize = 24;
const BATCHES: u64 = 32;
const BATCH_SPP: u64 = 16;
/// The image is cut into `GRID x GRID` regions of 6 x 6 pixels.
const GRID: usize = 4;
const MAX_DEPTH: u32 = 50;

/// A floor under a one-sided ceiling lamp and a small two-sided glowing ball, all inside a fog (a
/// ball of radius 8 about the origin, density 0.08, albedo 0.9; optical depth 0.5-1 along a ray from
/// the camera out of it) under a blue sky: the upper half of the image meets nothing but the fog, so
/// its camera rays are forced to scatter, and the sky is seen through the fog.
pub fn fog_under_a_sky() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    let glass = b.material(Material::Dielectric { ior: 1.5 });
    let fog = b.material(Material::Isotropic {
        albedo: Albedo::Constant(Color::splat(0.9)),
    });
    let lamp = b.material(Material::DiffuseLight {
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
    // u x v = (0, -4, 0): shines down
    b.quad(
        w,
        Point3::new(-1.0, 3.5, -1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0),
        lamp,
    )
    .unwrap();
    b.sphere(w, Point3::new(1.5, 0.4, 0.5), 0.3, glow).unwrap();
    let boundary = b.group();
    b.sphere(boundary, Point3::ZERO, 8.0, glass).unwrap();
    b.medium(w, boundary, 0.08, fog).unwrap();
    b.camera = CameraSettings {
        lookfrom: Point3::new(0.0, 1.5, 5.0),
        lookat: Point3::new(0.0, 1.5, 0.0),
        vfov: 60.0,
        ..CameraSettings::default()
    };
    b.background = Background::Solid(Color::new(0.2, 0.3, 0.5));
    b.max_depth = MAX_DEPTH;
    b.build().unwrap()
}

fn batch_means(image: impl Fn(u64) -> Vec<Color>) -> Vec<Vec<f64>> {
    variant_batches::region_means(WIDTH, GRID, BATCHES, 7000, image)
}

fn variant_means(scene: &Scene, variant: MisVariant) -> Vec<Vec<f64>> {
    batch_means(|seed| {
        variant_batches::render_variant(scene, WIDTH, MAX_DEPTH, BATCH_SPP, seed, variant)
    })
}

fn disagreements(a: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<String> {
    variant_batches::disagreements(a, b, GRID)
}

#[test]
fn forced_scattering_agrees_with_cosine_and_without_it_and_the_wrong_variants_are_caught() {
    let scene = fog_under_a_sky();
    let cosine = batch_means(|seed| {
        let settings = variant_batches::settings(WIDTH, MAX_DEPTH, seed, Strategy::Cosine);
        let (acc, stats) = render(&scene, settings, BATCH_SPP);
        assert_eq!(stats.non_finite, 0);
        acc.image()
    });
    let mis = variant_means(&scene, MisVariant::Book);
    let d = disagreements(&cosine, &mis);
    assert!(d.is_empty(), "mis vs cosine:\n{}", d.join("\n"));
    let unforced = variant_means(&scene, MisVariant::NoForcedScattering);
    let d = disagreements(&unforced, &mis);
    assert!(d.is_empty(), "forced vs not forced:\n{}", d.join("\n"));
    let wrong = variant_means(&scene, MisVariant::WrongForcedScatterWeight);
    assert!(
        !disagreements(&cosine, &wrong).is_empty(),
        "forced scattering without its 1 - exp(-tau) went unnoticed"
    );
    let wrong = variant_means(&scene, MisVariant::WrongForcedBackground);
    assert!(
        !disagreements(&cosine, &wrong).is_empty(),
        "the background seen through the fog left out went unnoticed"
    );
}
