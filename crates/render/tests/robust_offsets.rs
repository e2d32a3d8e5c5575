//! TESTING.md "ray offsets": in scenes scaled by 1e-4 and 1e4, a ray spawned from a hit never re-hits
//! the surface at its own origin, and a refracted ray still finds the far side. No fixed t_min.

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_render::hit::Hit;
use rtl_render::ray::{Interval, Ray};
use rtl_render::sampler::Ctx;
use rtl_render::scene::{MaterialId, SceneBuilder, Transform};
use rtl_render::shapes::{Quad, Sphere};
use rtl_render::vec::{Point3, Vec3, reflect};

const SCALES: [f64; 5] = [1e-4, 1e-2, 1.0, 1e2, 1e4];

fn random_unit<R: Rng>(rng: &mut R) -> Vec3 {
    rtl_pdf::warp::sample_uniform_sphere(glam::DVec2::new(rng.random(), rng.random()))
}

/// A random direction on the side of `n` (or against it).
fn on_side<R: Rng>(rng: &mut R, n: Vec3, same: bool) -> Vec3 {
    loop {
        let d = random_unit(rng);
        let c = d.dot(n);
        if (same && c > 1e-9) || (!same && c < -1e-9) {
            return d;
        }
    }
}

#[test]
fn rays_leaving_a_sphere_never_rehit_it_and_refracted_rays_find_the_far_side() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
    for s in SCALES {
        // Off-centre sphere so coordinates are not symmetric around 0.
        let sphere = Sphere::new(Point3::new(3.0, -2.0, 7.0) * s, 1.5 * s, MaterialId(0));
        let mut checked = 0;
        for _ in 0..20_000 {
            let origin =
                sphere.center + random_unit(&mut rng) * (1.5 * s * rng.random_range(1.5..50.0));
            let target = sphere.center + random_unit(&mut rng) * 1.4 * s;
            let ray = Ray::new(origin, target - origin, 0.0);
            let Some(h) = sphere.hit(&ray, Interval::FORWARD) else {
                continue;
            };
            checked += 1;
            // Leaving on the outside (reflection, diffuse scattering): the convex sphere is behind.
            for d in [
                reflect(ray.direction.normalize(), h.normal),
                on_side(&mut rng, h.normal, true),
            ] {
                let out = h.spawn(d, 0.0);
                assert!(
                    sphere.hit(&out, Interval::FORWARD).is_none(),
                    "scale {s}: outgoing ray re-hit its sphere"
                );
            }
            // Entering (refraction): the first hit is the far side, at the chord's length.
            let d = on_side(&mut rng, h.normal, false);
            let inward = h.spawn(d, 0.0);
            let far = sphere
                .hit(&inward, Interval::FORWARD)
                .unwrap_or_else(|| panic!("scale {s}: refracted ray found no far side"));
            let outward_n = (h.p - sphere.center) / sphere.radius;
            let chord = -2.0 * sphere.radius * d.dot(outward_n);
            let travelled = (far.p - h.p).length();
            // The origin sits a hair inside the surface, which shortens a grazing chord noticeably; away
            // from grazing the far side is where the chord says. A re-hit at the origin would give ~0.
            if -d.dot(outward_n) > 1e-3 {
                assert!(
                    (travelled - chord).abs() <= 1e-3 * chord,
                    "scale {s}: far side at {travelled}, chord {chord}"
                );
            } else {
                assert!(
                    travelled > 0.5 * chord,
                    "scale {s}: far side at {travelled}, chord {chord}"
                );
            }
            // From inside, leaving through the far side: the sphere is not hit again.
            let exit = far.spawn(inward.direction, 0.0);
            assert!(
                sphere.hit(&exit, Interval::FORWARD).is_none(),
                "scale {s}: exiting ray re-hit"
            );
        }
        assert!(checked > 5_000, "too few hits to test at scale {s}");
    }
}

#[test]
fn rays_leaving_a_quad_never_rehit_it() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(12);
    for s in SCALES {
        let quad = Quad::new(
            Point3::new(-1.0, 2.0, 3.0) * s,
            Vec3::new(2.0, 0.5, 0.0) * s,
            Vec3::new(0.3, 0.1, 1.7) * s,
            MaterialId(0),
        )
        .unwrap();
        let mut checked = 0;
        for _ in 0..20_000 {
            let target = quad.q + rng.random::<f64>() * quad.u + rng.random::<f64>() * quad.v;
            let origin = target + random_unit(&mut rng) * s * rng.random_range(0.01..100.0);
            let ray = Ray::new(origin, target - origin, 0.0);
            let Some(h) = quad.hit(&ray, Interval::FORWARD) else {
                continue;
            };
            checked += 1;
            for same in [true, false] {
                let d = on_side(&mut rng, h.normal, same);
                let out = h.spawn(d, 0.0);
                assert!(
                    quad.hit(&out, Interval::FORWARD).is_none(),
                    "scale {s}: ray spawned from a quad re-hit it"
                );
            }
        }
        assert!(checked > 15_000, "too few hits at scale {s}");
    }
}

#[test]
fn offsets_hold_through_instances() {
    // A rotated, translated unit box far from the origin, at every scale: rays leaving any face on the
    // outside never re-hit the (convex) box.
    // Placed as an instance, and flattened into world space (`rtl_render::flatten`): each flattened
    // quad's error bound must hold in world space.
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(13);
    for (s, flatten) in SCALES.into_iter().flat_map(|s| [(s, false), (s, true)]) {
        let mut b = SceneBuilder::new();
        b.flatten = flatten;
        let m = b.material(rtl_render::material::Material::lambertian(Vec3::ONE));
        let inner = b
            .box_group(Point3::ZERO, Point3::new(1.0, 2.0, 0.5) * s, m)
            .unwrap();
        b.instance(
            b.world(),
            inner,
            Transform::rotate_y(33.0).then(Transform::translate(Vec3::new(40.0, -7.0, 12.0) * s)),
        );
        let scene = b.build().unwrap();
        let placed = scene.groups[0]
            .objects
            .iter()
            .any(|o| matches!(o, rtl_render::scene::Object::Instance { .. }));
        assert_eq!(placed, !flatten);
        let mut ctx = Ctx::new();
        let centre = Transform::rotate_y(33.0).point(Point3::new(0.5, 1.0, 0.25) * s)
            + Vec3::new(40.0, -7.0, 12.0) * s;
        let mut checked = 0;
        for _ in 0..5_000 {
            let origin = centre + random_unit(&mut rng) * s * 20.0;
            let target = centre + random_unit(&mut rng) * s * 0.3;
            let ray = Ray::new(origin, target - origin, 0.0);
            let Some(h): Option<Hit> = scene.hit(&ray, &mut ctx) else {
                continue;
            };
            checked += 1;
            let d = on_side(&mut rng, h.normal, true);
            let out = h.spawn(d, 0.0);
            assert!(
                scene.hit(&out, &mut ctx).is_none(),
                "scale {s}: ray leaving the box re-hit it"
            );
            // Going in, the ray must find another face of the box, at a positive distance.
            let d = on_side(&mut rng, h.normal, false);
            let inside = h.spawn(d, 0.0);
            let far = scene.hit(&inside, &mut ctx).expect("the box is closed");
            assert!((far.p - h.p).length() > 1e-9 * s || far.t > 0.0);
        }
        assert!(checked > 1000);
    }
}

#[test]
fn without_the_offset_the_same_check_sees_self_intersections() {
    // The deliberately wrong method: start the outgoing ray at the computed hit point, t > 0. Rounding
    // puts about half of those origins behind the surface, and the check above must catch that.
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(14);
    let s = 1e4;
    let quad = Quad::new(
        Point3::new(-1.0, 2.0, 3.0) * s,
        Vec3::new(2.0, 0.5, 0.0) * s,
        Vec3::new(0.3, 0.1, 1.7) * s,
        MaterialId(0),
    )
    .unwrap();
    let mut rehits = 0;
    for _ in 0..2_000 {
        let target = quad.q + rng.random::<f64>() * quad.u + rng.random::<f64>() * quad.v;
        let origin = target + random_unit(&mut rng) * s;
        let ray = Ray::new(origin, target - origin, 0.0);
        let Some(h) = quad.hit(&ray, Interval::FORWARD) else {
            continue;
        };
        let out = Ray::new(h.p, on_side(&mut rng, h.normal, true), 0.0);
        rehits += quad.hit(&out, Interval::FORWARD).is_some() as u32;
    }
    assert!(
        rehits > 100,
        "only {rehits} self-intersections without an offset"
    );
}
