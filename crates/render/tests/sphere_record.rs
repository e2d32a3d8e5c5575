//! The sphere's hit record without the normalisation (a change of rounding, see
//! `Sphere::hit_at`): against the projected record it replaced (`Sphere::hit_at_projected`) on random
//! and hostile rays (grazing, far, tiny and huge spheres, origins on the surface, moving spheres), the
//! point lies within its bound `err` of the sphere and within both bounds of the projected point, and
//! the normal within `err / |r|` of the unit normal. The same check fails for a root off by 2^-30,
//! for the projected point's bound without the ray's term, and for a normal scaled by the radius
//! instead of divided.

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_render::hit::Hit;
use rtl_render::ray::{Interval, Ray};
use rtl_render::shapes::{Sphere, UNIT_NORMAL};
use rtl_render::vec::{Point3, Vec3};

fn random_unit<R: Rng>(rng: &mut R) -> Vec3 {
    rtl_pdf::warp::sample_uniform_sphere(glam::DVec2::new(rng.random(), rng.random()))
}

/// A unit vector perpendicular to `n`.
fn perpendicular<R: Rng>(rng: &mut R, n: Vec3) -> Vec3 {
    loop {
        let v = random_unit(rng).cross(n);
        if v.length_squared() > 1e-4 {
            return v.normalize();
        }
    }
}

/// The number of records `build` makes that break the bounds, of the hits found: `(bad, fast, slow)`,
/// `fast` the hits whose bound allows the unprojected point (`err <= 2^-20 |r|`), `slow` the others.
fn violations(
    sphere: &Sphere,
    rays: &[Ray],
    build: &dyn Fn(&Sphere, &Ray, f64) -> Hit,
) -> (usize, usize, usize) {
    violations_and_margin(sphere, rays, build).0
}

/// [`violations`], and the largest ratio of a point's distance from the sphere to its bound.
fn violations_and_margin(
    sphere: &Sphere,
    rays: &[Ray],
    build: &dyn Fn(&Sphere, &Ray, f64) -> Hit,
) -> ((usize, usize, usize), f64) {
    let (mut bad, mut fast, mut slow) = (0, 0, 0);
    let mut worst: f64 = 0.0;
    for ray in rays {
        let Some(t) = sphere.hit_t(ray, Interval::FORWARD) else {
            continue;
        };
        let new = build(sphere, ray, t);
        let old = sphere.hit_at_projected(ray, t);
        let r = sphere.radius.abs();
        if sphere.point_error(ray, t) > UNIT_NORMAL * r {
            // A sphere small beside the ray's terms keeps the projected record, bit for bit.
            slow += 1;
            let same = new.p == old.p
                && new.normal == old.normal
                && new.front_face == old.front_face
                && new.err == old.err;
            bad += !same as usize;
            continue;
        }
        fast += 1;
        let c = sphere.center_at(ray.time);
        // The distance of the point from the sphere, in f64: |p - c| rounds by a few ulps of |c| +
        // |r|, 2^-16 of the bound it is compared with.
        let off_surface = ((new.p - c).length() - r).abs();
        worst = worst.max(off_surface / new.err);
        let near_old = (new.p - old.p).length();
        // (p - c) / r against (p - c) / |p - c| (times the radius' sign): their difference is
        // | |p - c| / |r| - 1 |, within err / |r|, plus a few ulps of the division and the square root.
        let normal_off = (new.normal - old.normal).length();
        let normal_bound = new.err / r + 8.0 * f64::EPSILON;
        // The faces agree unless the ray meets the surface within the normals' difference of grazing.
        let faces_ok = new.front_face == old.front_face
            || ray.direction.normalize().dot(old.normal).abs() <= normal_bound;
        let ok = off_surface <= new.err
            && near_old <= new.err + old.err
            && normal_off <= normal_bound
            && (new.normal.length() - 1.0).abs() <= normal_bound
            && faces_ok
            && new.t == t
            && new.material == old.material;
        bad += !ok as usize;
    }
    ((bad, fast, slow), worst)
}

/// Rays at a sphere of centre `c` and radius `r`, in the hostile families: from near and far,
/// grazing its silhouette from 1e-3 to 1e-12 inside it, from points of the surface outwards and
/// inwards, and along the surface's tangent.
fn rays<R: Rng>(rng: &mut R, c: Point3, r: f64, far: f64, time: f64) -> Vec<Ray> {
    let mut rays = Vec::new();
    for _ in 0..2_000 {
        let n = random_unit(rng);
        let origin = c + n * (r * rng.random_range(1.01..far));
        // At a random point inside the sphere.
        let target = c + random_unit(rng) * (r * rng.random_range(0.0..0.999));
        rays.push(Ray::new(
            origin,
            (target - origin) * rng.random_range(0.1..10.0),
            time,
        ));
        // Grazing: at a point just inside the silhouette seen from the origin.
        let side = perpendicular(rng, n);
        let inset = 10f64.powi(-rng.random_range(3..=12));
        let graze = c + side * (r * (1.0 - inset));
        rays.push(Ray::new(origin, graze - origin, time));
        // From the surface itself: out of it (a diffuse bounce), into it (a refraction), and along
        // its tangent plane.
        let on = c + n * r;
        let out = (n + random_unit(rng)).normalize();
        rays.push(Ray::new(on, out, time));
        rays.push(Ray::new(on, -out, time));
        rays.push(Ray::new(on, side + n * 1e-9, time));
        // From inside, to the far side.
        let inside = c + random_unit(rng) * (r * rng.random_range(0.0..0.99));
        rays.push(Ray::new(inside, random_unit(rng), time));
    }
    rays
}

/// Spheres of every scale, placed near and far from the origin, static and moving.
fn spheres<R: Rng>(rng: &mut R) -> Vec<(Sphere, f64)> {
    let mut out = Vec::new();
    for scale in [1e-3, 1.0, 555.0, 1e4] {
        for placed in [0.0, 3.0, 1e3] {
            let c = random_unit(rng) * (scale * placed) + Vec3::new(0.3, -0.2, 0.1) * scale;
            let r = scale * rng.random_range(0.01..1.0);
            out.push((Sphere::new(c, r, rtl_render::scene::MaterialId(0)), 0.0));
            // Book 1's hollow sphere: a negative radius, the normal inwards.
            out.push((Sphere::new(c, -r, rtl_render::scene::MaterialId(1)), 0.0));
            let moved = c + random_unit(rng) * r;
            let moving = Sphere::moving(c, moved, r, rtl_render::scene::MaterialId(2));
            out.push((moving, rng.random()));
        }
    }
    out
}

#[test]
fn the_unprojected_sphere_record_stays_within_its_bound() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(41);
    let (mut fast, mut slow) = (0, 0);
    let mut worst: f64 = 0.0;
    for (sphere, time) in spheres(&mut rng) {
        let c = sphere.center_at(time);
        let r = sphere.radius.abs();
        for far in [50.0, 1e4, 1e8] {
            let rays = rays(&mut rng, c, r, far, time);
            let ((bad, f, s), w) =
                violations_and_margin(&sphere, &rays, &|s, ray, t| s.hit_at(ray, t));
            worst = worst.max(w);
            assert_eq!(bad, 0, "{sphere:?} from up to {far} radii");
            // `Sphere::hit` is the same record.
            for ray in &rays[..200] {
                if let (Some(a), Some(t)) = (
                    sphere.hit(ray, Interval::FORWARD),
                    sphere.hit_t(ray, Interval::FORWARD),
                ) {
                    let b = sphere.hit_at(ray, t);
                    assert!(a.p == b.p && a.normal == b.normal && a.err == b.err);
                }
            }
            fast += f;
            slow += s;
        }
    }
    eprintln!("{fast} unprojected, {slow} projected; distance / bound at most {worst:e}");
    // Both paths are exercised: the far origins (1e8 radii) make the bound exceed 2^-20 r.
    assert!(
        fast > 300_000 && slow > 10_000,
        "{fast} fast, {slow} projected"
    );
}

#[test]
fn the_check_catches_a_root_off_by_two_to_the_minus_30_and_a_wrong_normal() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(42);
    let sphere = Sphere::new(
        Point3::new(190.0, 90.0, 190.0),
        90.0,
        rtl_render::scene::MaterialId(0),
    );
    let near_rays = rays(&mut rng, sphere.center, 90.0, 6.0, 0.0);
    assert_eq!(
        violations(&sphere, &near_rays, &|s, ray, t| s.hit_at(ray, t)).0,
        0
    );
    // The point one 2^-30 of t further along the ray: off the surface by more than its bound.
    let late = |s: &Sphere, ray: &Ray, t: f64| {
        let mut h = s.hit_at(ray, t);
        h.p = ray.at(t * (1.0 + 1.0 / 1_073_741_824.0));
        h
    };
    let (bad, fast, _) = violations(&sphere, &near_rays, &late);
    eprintln!("a root off by 2^-30: {bad} of {fast} records out of bounds");
    assert!(bad > fast / 2, "{bad} of {fast}");
    // The projected point's bound, without the ray's term, for rays from afar (up to 1e6 radii).
    let near_origin = Sphere::new(
        Point3::new(0.5, -0.2, 0.1),
        1.0,
        rtl_render::scene::MaterialId(0),
    );
    let far_rays = rays(&mut rng, near_origin.center, 1.0, 1e6, 0.0);
    assert_eq!(
        violations(&near_origin, &far_rays, &|s, ray, t| s.hit_at(ray, t)).0,
        0
    );
    let sphere_only = |s: &Sphere, ray: &Ray, t: f64| {
        let mut h = s.hit_at(ray, t);
        h.err = s.hit_error(ray.time);
        h
    };
    let (bad, fast, _) = violations(&near_origin, &far_rays, &sphere_only);
    eprintln!("without the ray's term: {bad} of {fast} records out of bounds");
    assert!(bad > fast / 20, "{bad} of {fast}");
    // The normal (p - c) r instead of (p - c) / r.
    let scaled = |s: &Sphere, ray: &Ray, t: f64| {
        let mut h = s.hit_at(ray, t);
        h.normal *= s.radius * s.radius;
        h
    };
    let (bad, fast, _) = violations(&sphere, &near_rays, &scaled);
    assert_eq!(bad, fast);
}
