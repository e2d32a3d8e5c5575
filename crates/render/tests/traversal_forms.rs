//! The traversal's special forms against the plain definitions they shortcut: a small group's flat
//! form ([`Accel::small`]) against testing every object in turn, and a medium with a sphere for its
//! boundary (both crossings from one quadratic) against the two boundary queries of the general path.
//! Hits must agree bit for bit (t, point, normal, side, material); each checker is also shown to
//! catch a deliberately wrong form.

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
mod hit_bits;
use hit_bits::record;
use rtl_render::material::{Albedo, Material};
use rtl_render::ray::{Interval, Ray};
use rtl_render::sampler::Ctx;
use rtl_render::scene::{GroupId, Object, Scene, SceneBuilder, Transform};
use rtl_render::traversal::{HitTier, HitTierError};
use rtl_render::vec::{Color, Point3, Vec3};

fn unit<R: Rng>(rng: &mut R) -> Vec3 {
    rtl_pdf::warp::sample_uniform_sphere(glam::DVec2::new(rng.random(), rng.random()))
}

fn point<R: Rng>(rng: &mut R, r: f64) -> Point3 {
    Point3::new(
        rng.random_range(-r..r),
        rng.random_range(-r..r),
        rng.random_range(-r..r),
    )
}

/// A small random group `g` (up to twelve quads and up to two other objects: spheres, a rotated box
/// instance, a nested group) in a scene whose world holds it; its box instance flattened into it if
/// `flatten` and it fits ([`rtl_render::flatten`]).
fn small_scene(rng: &mut Xoshiro256PlusPlus, flatten: bool) -> (Scene, GroupId) {
    let mut b = SceneBuilder::new();
    b.flatten = flatten;
    let mats: Vec<_> = (0..3)
        .map(|i| b.material(Material::lambertian(Color::splat(0.2 + 0.3 * i as f64))))
        .collect();
    let g = b.group();
    for _ in 0..rng.random_range(0..=12) {
        let m = mats[rng.random_range(0..3)];
        let (u, v) = (
            unit(rng) * rng.random_range(0.5..6.0),
            unit(rng) * rng.random_range(0.5..6.0),
        );
        b.quad(g, point(rng, 6.0), u, v, m).unwrap();
    }
    for _ in 0..rng.random_range(0..=2) {
        let m = mats[rng.random_range(0..3)];
        match rng.random_range(0..3) {
            0 => b
                .sphere(g, point(rng, 5.0), rng.random_range(0.3..3.0), m)
                .unwrap(),
            1 => {
                let inner = b
                    .box_group(Point3::ZERO, Point3::ONE + point(rng, 1.0).abs() * 3.0, m)
                    .unwrap();
                let tr = Transform::rotate_y(rng.random_range(-180.0..180.0))
                    .then(Transform::translate(point(rng, 4.0)));
                b.instance(g, inner, tr);
            }
            _ => {
                let inner = b.group();
                b.sphere(inner, point(rng, 4.0), rng.random_range(0.3..2.0), m)
                    .unwrap();
                b.quad(inner, point(rng, 4.0), unit(rng) * 3.0, unit(rng) * 2.0, m)
                    .unwrap();
                b.add_to(g, Object::Group(inner));
            }
        }
    }
    b.add(Object::Group(g));
    (b.build().unwrap(), g)
}

/// Rays from outside and from inside the scene, aimed near its middle or anywhere.
fn ray<R: Rng>(rng: &mut R) -> Ray {
    let o = if rng.random::<bool>() {
        unit(rng) * 20.0
    } else {
        point(rng, 6.0)
    };
    let d = if rng.random::<bool>() {
        point(rng, 5.0) - o
    } else {
        unit(rng)
    };
    Ray::new(o, d, 0.0)
}

/// How many of `rays` group `g`'s traversal (the detected path, or any tier the processor runs:
/// portable, AVX2, AVX-512) hits otherwise than testing its objects one by one, and how many hit at
/// all.
fn mismatches(scene: &Scene, g: GroupId, rays: &[Ray]) -> (usize, usize) {
    let mut ctx = Ctx::new();
    let (mut wrong, mut hits) = (0, 0);
    for ray in rays {
        let slow = record(scene.hit_brute_force(g, ray, Interval::FORWARD, &mut ctx));
        let fast = record(scene.hit_group(g, ray, Interval::FORWARD, &mut ctx));
        let portable = record(scene.hit_group_portable(g, ray, Interval::FORWARD, &mut ctx));
        let tiers = HitTier::ALL.map(|t| {
            scene
                .hit_group_in(t, g, ray, Interval::FORWARD, &mut ctx)
                .map(record)
        });
        wrong += (fast != slow
            || portable != slow
            || tiers.iter().any(|t| t.is_some_and(|t| t != slow))) as usize;
        hits += slow.is_some() as usize;
    }
    (wrong, hits)
}

/// The tiers this processor runs, said on the test's output (a tier not run is not tested here).
fn tiers_run() -> Vec<HitTier> {
    let run: Vec<HitTier> = HitTier::ALL.into_iter().filter(|t| t.available()).collect();
    eprintln!(
        "hit tiers tested: {run:?} (detected: {:?})",
        HitTier::detected()
    );
    run
}

#[test]
fn small_groups_find_the_brute_force_hits_bit_for_bit() {
    tiers_run();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(16);
    let (mut hits, mut instances, mut flattened) = (0, 0, 0);
    for i in 0..200 {
        let (scene, g) = small_scene(&mut rng, i % 2 == 0);
        flattened += (scene.groups[g.0 as usize]
            .objects
            .iter()
            .filter(|o| matches!(o, Object::Quad(_)))
            .count()
            > 8) as usize;
        let accel = &scene.groups[g.0 as usize].accel;
        assert!(accel.is_small() || scene.groups[g.0 as usize].objects.len() == 1);
        instances += scene.groups[g.0 as usize]
            .objects
            .iter()
            .any(|o| matches!(o, Object::Instance { .. })) as usize;
        let rays: Vec<Ray> = (0..300).map(|_| ray(&mut rng)).collect();
        let (wrong, h) = mismatches(&scene, g, &rays);
        assert_eq!(wrong, 0);
        hits += h;
    }
    assert!(
        hits > 4_000 && instances > 30 && flattened > 30,
        "{hits} hits, {instances} scenes with instances, {flattened} with a third packet"
    );
}

#[test]
fn the_small_group_check_catches_a_wrong_eight_lane_packet() {
    // Quads lost from the AVX-512 tier's form only (the 4-lane packets and the objects keep them):
    // that tier, where it runs, must be caught.
    if !tiers_run().contains(&HitTier::Avx512) {
        return;
    }
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(18);
    let mut caught = 0;
    for _ in 0..20 {
        let (mut scene, g) = small_scene(&mut rng, true);
        let quads = scene.groups[g.0 as usize].accel.packets.len();
        if quads == 0 {
            continue;
        }
        let rays: Vec<Ray> = (0..300).map(|_| ray(&mut rng)).collect();
        assert_eq!(mismatches(&scene, g, &rays).0, 0);
        let accel = &mut scene.groups[g.0 as usize].accel;
        // One of the 8-lane packets emptied, or the 4-lane tail dropped: their quads are missed by
        // the AVX-512 tier alone.
        let units = accel.packets8.len() + accel.tail4 as usize;
        let k = rng.random_range(0..units);
        if k < accel.packets8.len() {
            accel.packets8[k] = rtl_render::quad8::Quad8::new(&[]);
        } else {
            accel.tail4 = false;
        }
        caught += (mismatches(&scene, g, &rays).0 > 0) as usize;
    }
    assert!(caught >= 10, "{caught}");
}

#[test]
fn the_small_group_check_catches_a_box_that_culls_too_much() {
    // The rotated box's culling box moved off it: rays that hit the box are skipped.
    let mut b = SceneBuilder::new();
    // The instance as placed, behind its culling box.
    b.flatten = false;
    let m = b.material(Material::lambertian(Color::ONE));
    let g = b.group();
    b.quad(
        g,
        Point3::new(-5.0, -5.0, -6.0),
        Vec3::X * 10.0,
        Vec3::Y * 10.0,
        m,
    )
    .unwrap();
    let inner = b.box_group(Point3::ZERO, Point3::ONE * 2.0, m).unwrap();
    b.instance(g, inner, Transform::rotate_y(30.0));
    b.add(Object::Group(g));
    let mut scene = b.build().unwrap();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(17);
    let rays: Vec<Ray> = (0..2_000).map(|_| ray(&mut rng)).collect();
    assert_eq!(mismatches(&scene, g, &rays).0, 0);
    let accel = &mut scene.groups[g.0 as usize].accel;
    assert!(accel.is_small() && accel.other_bounds.len() == 1);
    let shift = Vec3::splat(3.0);
    accel.other_bounds[0].min += shift;
    accel.other_bounds[0].max += shift;
    assert!(mismatches(&scene, g, &rays).0 > 50);
}

#[test]
fn groups_that_may_draw_random_numbers_keep_the_tree() {
    let mut b = SceneBuilder::new();
    let m = b.material(Material::lambertian(Color::ONE));
    let fog = b.material(Material::Isotropic {
        albedo: Albedo::Constant(Color::ONE),
    });
    let boundary = b.box_group(Point3::ZERO, Point3::ONE, m).unwrap();
    let smoke = b.group();
    b.medium(smoke, boundary, 0.5, fog).unwrap();
    b.quad(smoke, Point3::ZERO, Vec3::X, Vec3::Y, m).unwrap();
    let placed = b.group();
    b.instance(placed, smoke, Transform::translate(Vec3::X));
    b.quad(placed, Point3::ZERO, Vec3::X, Vec3::Z, m).unwrap();
    let scene = b.build().unwrap();
    let small = |g: GroupId| scene.groups[g.0 as usize].accel.is_small();
    assert!(small(boundary));
    assert!(!small(smoke) && !small(placed));
}

/// A scene with a medium in a sphere: the sphere itself as the boundary's one object if `direct`, or
/// nested one group deeper (the general path: two queries of the boundary group).
fn fog_scene(direct: bool, radius: f64) -> Scene {
    let mut b = SceneBuilder::new();
    let m = b.material(Material::lambertian(Color::ONE));
    let fog = b.material(Material::Isotropic {
        albedo: Albedo::Constant(Color::ONE),
    });
    let sphere = b.group();
    b.sphere(sphere, Point3::new(0.5, -0.25, 1.0), radius, m)
        .unwrap();
    let boundary = if direct {
        sphere
    } else {
        let outer = b.group();
        b.add_to(outer, Object::Group(sphere));
        outer
    };
    b.medium(b.world(), boundary, 0.3, fog).unwrap();
    b.quad(
        b.world(),
        Point3::new(-9.0, -9.0, -9.0),
        Vec3::X * 18.0,
        Vec3::Y * 18.0,
        m,
    )
    .unwrap();
    b.build().unwrap()
}

/// How many rays the two scenes answer differently (hit, or the random numbers drawn after it).
fn medium_mismatches(a: &Scene, b: &Scene) -> (usize, usize) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(18);
    let (mut ca, mut cb) = (Ctx::new(), Ctx::new());
    let (mut wrong, mut scattered) = (0, 0);
    for _ in 0..20_000 {
        let r = ray(&mut rng);
        let (ha, hb) = (record(a.hit(&r, &mut ca)), record(b.hit(&r, &mut cb)));
        wrong += (ha != hb || ca.uniform().to_bits() != cb.uniform().to_bits()) as usize;
        scattered += ha.is_some_and(|h| h.4 == 1) as usize;
    }
    (wrong, scattered)
}

#[test]
fn a_sphere_boundary_crossed_in_one_solve_matches_the_two_queries() {
    let (wrong, scattered) = medium_mismatches(&fog_scene(true, 4.0), &fog_scene(false, 4.0));
    assert_eq!(wrong, 0);
    assert!(scattered > 2_000, "{scattered}");
    // The check sees a boundary one ulp larger.
    let bigger = fog_scene(false, f64::from_bits(4.0f64.to_bits() + 1));
    assert!(medium_mismatches(&fog_scene(true, 4.0), &bigger).0 > 0);
}

#[test]
fn a_tier_is_chosen_by_its_key_and_refused_where_it_does_not_run() {
    for t in HitTier::ALL {
        assert_eq!(t.key().parse::<HitTier>(), Ok(t));
    }
    assert_eq!(
        "avx9".parse::<HitTier>(),
        Err(HitTierError::Unknown("avx9".into()))
    );
    assert!("AVX2".parse::<HitTier>().is_err(), "keys are lower case");
    let detected = HitTier::detected();
    for t in HitTier::ALL {
        match t.select() {
            Ok(()) => {
                assert!(t.available(), "{t:?} selected where it does not run");
                assert_eq!(HitTier::current(), t);
            }
            Err(e) => {
                assert!(!t.available(), "{t:?} refused where it runs: {e}");
                assert_eq!(
                    e,
                    HitTierError::Unavailable {
                        tier: t.key(),
                        best: detected.key()
                    }
                );
                assert_ne!(HitTier::current(), t);
            }
        }
    }
    // The other tests of this file may run meanwhile: every tier finds the same hits.
    detected.select().unwrap();
    assert_eq!(HitTier::current(), detected);
}

#[test]
fn the_default_tier_runs_here_and_is_avx2_on_an_intel_processor_with_avx512() {
    let (preferred, detected) = (HitTier::preferred(), HitTier::detected());
    assert!(preferred.available(), "{preferred:?} is not run here");
    let intel = std::fs::read_to_string("/proc/cpuinfo")
        .map(|s| {
            s.lines()
                .any(|l| l.starts_with("vendor_id") && l.ends_with("GenuineIntel"))
        })
        .unwrap_or(false);
    let expected = match detected {
        HitTier::Avx512 if intel => HitTier::Avx2,
        t => t,
    };
    eprintln!("detected {detected:?}, preferred {preferred:?} (Intel: {intel})");
    assert_eq!(preferred, expected);
}
