//! The sampling strategies against each other and against exact answers, with no stored image:
//! - unbiasedness: region means of a small Cornell box agree across uniform, cosine, mixture and mis
//!   (batch means, Welch t-test), and the same machinery catches the biased `light` strategy;
//! - a white furnace: a white Lambertian ball inside a uniformly emitting sphere returns the sphere's
//!   radiance, exactly with cosine sampling and within the standard error with every other strategy;
//! - the book's pitfalls: no lights, a target around the point, a light seen edge-on, a one-sided light
//!   seen from behind, a NaN sample in a pixel.

use rtl_pdf::{QuadTarget, ShapeSampler as _, SphereTarget};
use rtl_render::Color;
use rtl_render::camera::CameraSettings;
use rtl_render::integrator::{MisOptions, Strategy};
use rtl_render::lights::{LightTarget, Lights};
use rtl_render::material::{Albedo, Material};
use rtl_render::render::{RenderSettings, Renderer, render};
use rtl_render::sampler::Ctx;
use rtl_render::scene::{Background, ImportanceTarget, Scene, SceneBuilder};
use rtl_render::scenes;
use rtl_render::shapes::Sphere;
use rtl_render::vec::{Point3, Vec3};

mod batch_means;
use batch_means::{mean_var, welch_p};

fn settings(width: usize, seed: u64, strategy: Strategy) -> RenderSettings {
    weighted(
        width,
        seed,
        strategy,
        rtl_render::render::BOOK_MIXTURE_WEIGHT,
    )
}

/// [`settings`] with `mixture`'s share of directions towards the targets.
fn weighted(width: usize, seed: u64, strategy: Strategy, mixture_weight: f64) -> RenderSettings {
    RenderSettings {
        width,
        max_depth: 50,
        seed,
        strategy,
        mixture_weight,
    }
}

fn cornell() -> Scene {
    (scenes::find("cornell").unwrap().build)(&Default::default())
        .unwrap()
        .scene
}

/// `mis` with its default extras, and with each extra toggled.
fn mis_variants() -> Vec<Strategy> {
    let d = MisOptions::default();
    vec![
        Strategy::Mis(d),
        Strategy::Mis(MisOptions {
            russian_roulette: !d.russian_roulette,
            ..d
        }),
        Strategy::Mis(MisOptions {
            spherical_rectangles: !d.spherical_rectangles,
            ..d
        }),
        Strategy::Mis(MisOptions {
            low_discrepancy: !d.low_discrepancy,
            ..d
        }),
    ]
}

// ---------------------------------------------------------------------------------------------------
// Unbiasedness by batch means

/// Image regions of the 24 x 24 Cornell box, as pixel ranges `(i0..i1, j0..j1)` (j from the top). All
/// lie on diffuse surfaces lit directly and indirectly. Left out: the glass sphere and the floor under
/// it, where the caustic (light -> glass -> floor) is found only by material sampling of the floor and
/// is heavy-tailed for every strategy, so a t-test there would need far more batches to mean anything.
/// A named region: columns `i0..i1`, rows `j0..j1`.
type Region = (&'static str, (usize, usize), (usize, usize));
const REGIONS: [Region; 6] = [
    ("ceiling with the light", (6, 18), (0, 4)),
    ("left wall", (0, 3), (4, 18)),
    ("right wall", (21, 24), (4, 18)),
    ("back wall above the box", (8, 16), (5, 9)),
    ("front of the tall box", (8, 11), (13, 20)),
    ("floor by the left wall", (1, 6), (21, 24)),
];
const WIDTH: usize = 24;
const BATCHES: u64 = 32;
const BATCH_SPP: u64 = 16;

/// Per region, the region's mean radiance in each of `BATCHES` independent renders (seeds 1000 + b).
fn batch_means(scene: &Scene, strategy: Strategy) -> Vec<Vec<Color>> {
    batch_means_weighted(scene, strategy, rtl_render::render::BOOK_MIXTURE_WEIGHT)
}

/// [`batch_means`] with `mixture`'s weight.
fn batch_means_weighted(scene: &Scene, strategy: Strategy, w: f64) -> Vec<Vec<Color>> {
    let mut out = vec![Vec::new(); REGIONS.len()];
    for b in 0..BATCHES {
        let (acc, stats) = render(scene, weighted(WIDTH, 1000 + b, strategy, w), BATCH_SPP);
        assert_eq!(
            stats.non_finite,
            0,
            "{}: non-finite samples",
            strategy.name()
        );
        let img = acc.image();
        for (r, (_, (i0, i1), (j0, j1))) in REGIONS.iter().enumerate() {
            let mut sum = Color::ZERO;
            for j in *j0..*j1 {
                for i in *i0..*i1 {
                    sum += img[j * WIDTH + i];
                }
            }
            out[r].push(sum / ((i1 - i0) * (j1 - j0)) as f64);
        }
    }
    out
}

/// Every comparison (region x channel) of strategy `a` against `b`: the smallest p-value and where.
fn compare(a: &[Vec<Color>], b: &[Vec<Color>]) -> Vec<(f64, String)> {
    let mut out = Vec::new();
    for (r, (name, ..)) in REGIONS.iter().enumerate() {
        for c in 0..3 {
            let xa: Vec<f64> = a[r].iter().map(|v| v[c]).collect();
            let xb: Vec<f64> = b[r].iter().map(|v| v[c]).collect();
            out.push((
                welch_p(&xa, &xb),
                format!(
                    "{name}, channel {c}: {:.5} vs {:.5}",
                    mean_var(&xa).0,
                    mean_var(&xb).0
                ),
            ));
        }
    }
    out
}

// ANCHOR: unbiased
#[test]
fn every_unbiased_strategy_gives_the_same_region_means() {
    let scene = cornell();
    // (strategy, mixture weight): the weight matters to `mixture` only.
    let strategies = [
        (Strategy::Uniform, 0.5),
        (Strategy::Cosine, 0.5),
        (Strategy::Mixture, 0.5),
        (Strategy::Mixture, 0.2),
        (Strategy::Mis(MisOptions::default()), 0.5),
    ];
    let means: Vec<_> = strategies
        .iter()
        .map(|&(s, w)| batch_means_weighted(&scene, s, w))
        .collect();
    let name = |(s, w): (Strategy, f64)| match s {
        Strategy::Mixture => format!("mixture w={w}"),
        s => s.name().to_string(),
    };
    let pairs = strategies.len() * (strategies.len() - 1) / 2;
    let comparisons = pairs * REGIONS.len() * 3;
    // Family-wise false-failure rate 1e-6, Bonferroni over every comparison.
    let alpha = 1e-6 / comparisons as f64;
    for x in 0..strategies.len() {
        for y in x + 1..strategies.len() {
            for (p, what) in compare(&means[x], &means[y]) {
                assert!(
                    p >= alpha,
                    "{} vs {}: {what}, p = {p:.2e} < {alpha:.1e}",
                    name(strategies[x]),
                    name(strategies[y])
                );
            }
        }
    }
}
// ANCHOR_END: unbiased

#[test]
fn the_mixture_weight_is_used() {
    // Towards the targets most of the time or hardly ever: other directions, so other images (both
    // unbiased: the batch-means test above and the furnace test below).
    let scene = cornell();
    let image = |w: f64| {
        render(&scene, weighted(12, 1, Strategy::Mixture, w), 4)
            .0
            .image()
    };
    let (near_one, near_zero, even) = (image(0.95), image(0.05), image(0.5));
    assert_ne!(near_one, near_zero);
    assert_ne!(near_one, even);
    // Only `mixture` reads it.
    let cosine = |w: f64| {
        render(&scene, weighted(12, 1, Strategy::Cosine, w), 4)
            .0
            .image()
    };
    assert_eq!(cosine(0.95), cosine(0.5));
}

#[test]
fn the_mixture_weight_is_checked() {
    use rtl_render::render::check_mixture_weight;
    for w in [0.5, 1e-9, 0.999] {
        assert_eq!(check_mixture_weight(w), Ok(w));
    }
    for w in [0.0, 1.0, -0.1, 1.5, f64::NAN, f64::INFINITY] {
        let e = check_mixture_weight(w).unwrap_err();
        assert!(e.to_string().contains("mixture weight"), "{e}");
    }
}

#[test]
fn the_batch_means_test_catches_the_biased_light_strategy() {
    // `light` never samples directions that miss the targets, so it loses the indirect light: the same
    // test must reject it against `mis` (against `cosine`, whose batches are noisier, too: 2 of the 18
    // comparisons at this size).
    let scene = cornell();
    let reference = batch_means(&scene, Strategy::Mis(MisOptions::default()));
    let light = batch_means(&scene, Strategy::Light);
    let comparisons = REGIONS.len() * 3;
    let alpha = 1e-6 / comparisons as f64;
    let results = compare(&reference, &light);
    for (p, what) in &results {
        eprintln!("p = {p:.2e}: {what}");
    }
    let rejected = results.iter().filter(|(p, _)| *p < alpha).count();
    assert!(rejected >= 12, "only {rejected} comparisons saw the bias");
}

#[test]
fn mis_extras_change_no_region_mean() {
    // `mis` with each extra toggled must agree with its default.
    let scene = cornell();
    let variants = mis_variants();
    let means: Vec<_> = variants.iter().map(|&s| batch_means(&scene, s)).collect();
    let comparisons = (variants.len() - 1) * REGIONS.len() * 3;
    let alpha = 1e-6 / comparisons as f64;
    for (k, m) in means.iter().enumerate().skip(1) {
        for (p, what) in compare(&means[0], m) {
            assert!(p >= alpha, "{:?}: {what}, p = {p:.2e}", variants[k]);
        }
    }
}

// ---------------------------------------------------------------------------------------------------
// White furnace

const FURNACE: f64 = 0.5;

/// A white Lambertian ball of radius 1 at the origin inside a sphere of radius 100 that emits
/// radiance 0.5 inwards (and outwards) and reflects nothing; the enclosure is the scene's only target.
fn furnace() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::ONE));
    let glow = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(FURNACE)),
        two_sided: true,
    });
    b.sphere(w, Point3::ZERO, 1.0, white).unwrap();
    b.sphere(w, Point3::ZERO, 100.0, glow).unwrap();
    b.targets.push(ImportanceTarget::Sphere(Sphere::new(
        Point3::ZERO,
        100.0,
        glow,
    )));
    b.camera = CameraSettings {
        lookfrom: Point3::new(0.0, 0.0, 4.0),
        lookat: Point3::ZERO,
        vfov: 40.0,
        ..CameraSettings::default()
    };
    b.background = Background::Solid(Color::ZERO);
    b.build().unwrap()
}

/// Every sample of a `w x w` render at `spp`, channel 0 (the scene is grey).
fn samples(scene: &Scene, strategy: Strategy, w: usize, spp: u64) -> Vec<f64> {
    samples_weighted(
        scene,
        strategy,
        rtl_render::render::BOOK_MIXTURE_WEIGHT,
        w,
        spp,
    )
}

/// [`samples`] with `mixture`'s weight.
fn samples_weighted(scene: &Scene, strategy: Strategy, mw: f64, w: usize, spp: u64) -> Vec<f64> {
    let r = Renderer::new(scene, weighted(w, 7, strategy, mw));
    let mut ctx = Ctx::new();
    let mut out = Vec::new();
    for j in 0..r.camera.height {
        for i in 0..w {
            for k in 0..spp {
                out.push(r.sample(i, j, k, &mut ctx).x);
            }
        }
    }
    out
}

// ANCHOR: furnace
#[test]
fn white_furnace_cosine_is_exact() {
    // Cosine sampling of a white Lambertian: s / p = 1, and every bounce off the convex ball meets the
    // enclosure: every sample is exactly the enclosure's radiance.
    for v in samples(&furnace(), Strategy::Cosine, 16, 16) {
        assert!(
            (v - FURNACE).abs() <= 4.0 * f64::EPSILON * FURNACE,
            "sample {v}"
        );
    }
}

#[test]
fn white_furnace_every_strategy_within_its_standard_error() {
    let scene = furnace();
    let mut strategies = vec![Strategy::Uniform, Strategy::Light, Strategy::Mixture];
    strategies.extend(mis_variants());
    let mut runs: Vec<(Strategy, f64)> = strategies.into_iter().map(|s| (s, 0.5)).collect();
    runs.extend([(Strategy::Mixture, 0.05), (Strategy::Mixture, 0.95)]);
    for (s, w) in runs {
        let x = samples_weighted(&scene, s, w, 16, 64);
        let (m, v) = mean_var(&x);
        let se = (v / x.len() as f64).sqrt();
        assert!(se > 0.0, "{s:?} w={w}: no spread at all?");
        let z = (m - FURNACE) / se;
        // two-sided false-failure rate 1e-6
        assert!(
            z.abs() < 4.89,
            "{s:?} w={w}: mean {m} vs {FURNACE}, z = {z}"
        );
    }
}
// ANCHOR_END: furnace

// ---------------------------------------------------------------------------------------------------
// The book's pitfalls

#[test]
fn pitfall_empty_lights_list() {
    // Without targets, `mixture` and `light` have nothing to aim at and fall back to the material's
    // density: the very image of `cosine`; `mis` has no emitter to sample and renders finite values.
    let mut scene = cornell();
    scene.targets.clear();
    assert!(Lights::new(&scene, true).all.is_empty());
    let (cosine, _) = render(&scene, settings(12, 3, Strategy::Cosine), 4);
    for s in [Strategy::Mixture, Strategy::Light] {
        let (acc, _) = render(&scene, settings(12, 3, s), 4);
        assert_eq!(acc.sum, cosine.sum, "{}", s.name());
    }
    for s in mis_variants() {
        let (acc, stats) = render(&scene, settings(12, 3, s), 4);
        assert_eq!(stats.non_finite, 0);
        assert!(acc.image().iter().all(|c| c.is_finite()));
    }
}

#[test]
fn pitfall_a_target_the_point_is_inside() {
    // Inside (or on) a target sphere every direction meets it: the density is the uniform sphere's.
    let t = LightTarget::Sphere(SphereTarget::new(Point3::ZERO, 100.0));
    for o in [
        Point3::ZERO,
        Point3::new(0.0, 99.0, 0.0),
        Point3::new(0.0, 100.0, 0.0),
    ] {
        for d in [Vec3::X, -Vec3::Y, Vec3::new(0.6, 0.0, 0.8)] {
            let p = t.pdf_value(o, d);
            assert_eq!(
                p,
                1.0 / (4.0 * std::f64::consts::PI),
                "from {o} towards {d}"
            );
        }
    }
    // And the furnace, whose ball lies inside its target, is right with mixture (checked above within
    // its standard error); here: no sample is lost or non-finite.
    let (acc, stats) = render(&furnace(), settings(8, 1, Strategy::Mixture), 16);
    assert_eq!(stats.non_finite, 0);
    assert!(acc.count.iter().all(|&c| c == 16));
}

/// A white floor `[-1, 1]^2` at y = 0 and a square light beside it in the same plane (edge-on from
/// every floor point), facing up, plus a grey background so the floor is lit.
fn edge_on_scene() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.5)));
    let light = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(4.0)),
        two_sided: false,
    });
    b.quad(
        w,
        Point3::new(-1.0, 0.0, 1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -2.0),
        white,
    )
    .unwrap();
    let q = b
        .quad(
            w,
            Point3::new(1.5, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, -2.0),
            light,
        )
        .unwrap();
    b.targets.push(ImportanceTarget::Quad(q));
    b.camera = CameraSettings {
        lookfrom: Point3::new(0.0, 3.0, 3.0),
        lookat: Point3::ZERO,
        vfov: 50.0,
        ..CameraSettings::default()
    };
    b.background = Background::Solid(Color::splat(0.25));
    b.build().unwrap()
}

#[test]
fn pitfall_a_light_seen_edge_on() {
    // From a point in the light's plane the light has no solid angle: density 0 (a miss), not infinity,
    // and generated directions stay finite.
    let quad = QuadTarget::new(
        Point3::new(1.5, 0.0, 1.0),
        Vec3::X,
        Vec3::new(0.0, 0.0, -2.0),
    );
    for spherical in [false, true] {
        let t = LightTarget::Quad {
            quad: quad.with_spherical_rectangles(spherical),
            one_sided: true,
        };
        let o = Point3::new(0.2, 0.0, 0.3);
        let mut rng = <rand_xoshiro::Xoshiro256PlusPlus as rand::SeedableRng>::seed_from_u64(1);
        for _ in 0..100 {
            let d = t.random(o, &mut rng);
            assert!(d.is_finite());
            assert_eq!(t.pdf_value(o, d), 0.0);
        }
    }
    // Rendered, every strategy keeps every sample finite.
    let scene = edge_on_scene();
    for s in Strategy::ALL.iter().copied().chain(mis_variants()) {
        let (acc, stats) = render(&scene, settings(12, 2, s), 8);
        assert_eq!(stats.non_finite, 0, "{}", s.name());
        assert!(acc.image().iter().all(|c| c.is_finite()));
    }
}

#[test]
fn pitfall_a_one_sided_light_seen_from_behind() {
    // A light at y = 0 facing down, a white ceiling at y = 1 above it: the ceiling sees only the
    // light's back, which emits nothing, so the image is black with every strategy; `mis` knows the
    // light has no directions from behind and spends no shadow rays on it.
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::ONE));
    let light = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(10.0)),
        two_sided: false,
    });
    b.quad(
        w,
        Point3::new(-5.0, 1.0, -5.0),
        Vec3::new(10.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 10.0),
        white,
    )
    .unwrap();
    // u x v = (0, -1, 0) * area: emits downwards.
    let q = b
        .quad(
            w,
            Point3::new(-0.5, 0.0, -0.5),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
            light,
        )
        .unwrap();
    b.targets.push(ImportanceTarget::Quad(q));
    b.camera = CameraSettings {
        lookfrom: Point3::new(0.0, 0.5, 0.0),
        lookat: Point3::new(0.0, 1.0, 0.0),
        vup: Vec3::Z,
        vfov: 90.0,
        ..CameraSettings::default()
    };
    let scene = b.build().unwrap();
    let lights = Lights::new(&scene, true);
    let from_above = Point3::new(0.0, 0.5, 0.0);
    assert_eq!(lights.emitters[0].pdf_value(from_above, -Vec3::Y), 0.0);
    assert!(
        lights.all[0].pdf_value(from_above, -Vec3::Y) > 0.0,
        "the book's quad is two-sided"
    );
    for s in Strategy::ALL.iter().copied().chain(mis_variants()) {
        let (acc, stats) = render(&scene, settings(8, 4, s), 8);
        assert_eq!(stats.non_finite, 0);
        assert!(
            acc.image().iter().all(|c| *c == Color::ZERO),
            "{}",
            s.name()
        );
    }
}

#[test]
fn pitfall_a_nan_sample_in_a_pixel() {
    // A tiny sphere that "emits" NaN, smaller than a pixel, in front of a background of 0.5: the samples
    // that hit it are dropped and counted; every pixel is the mean of its finite samples, exactly 0.5.
    let mut b = SceneBuilder::new();
    let w = b.world();
    let nan = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(f64::NAN)),
        two_sided: true,
    });
    b.sphere(w, Point3::new(0.0, 0.0, -1.0), 0.02, nan).unwrap();
    b.background = Background::Solid(Color::splat(FURNACE));
    let scene = b.build().unwrap();
    for s in Strategy::ALL.iter().copied().chain(mis_variants()) {
        let (acc, stats) = render(&scene, settings(8, 5, s), 64);
        assert!(stats.non_finite > 0 && acc.total_dropped() == stats.non_finite);
        for c in acc.image() {
            assert_eq!(c, Color::splat(FURNACE), "{}", s.name());
        }
    }
}
