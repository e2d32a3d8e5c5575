//! Ray-shape intersections, instances and the BVH.

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_render::material::Material;
use rtl_render::ray::{Interval, Ray};
use rtl_render::sampler::Ctx;
use rtl_render::scene::{MaterialId, SceneBuilder, Transform};
use rtl_render::shapes::{Quad, Sphere};
use rtl_render::vec::{Color, Point3, Vec3};

fn unit<R: Rng>(rng: &mut R) -> Vec3 {
    rtl_pdf::warp::sample_uniform_sphere(glam::DVec2::new(rng.random(), rng.random()))
}

#[test]
fn sphere_hits_lie_on_the_sphere_with_outward_normals() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    let s = Sphere::new(Point3::new(1.0, 2.0, 3.0), 2.0, MaterialId(0));
    let mut hits = 0;
    for _ in 0..10_000 {
        let o = s.center + unit(&mut rng) * rng.random_range(2.5..20.0);
        let aim = s.center + unit(&mut rng) * 2.4 - o;
        let d = aim * rng.random_range(0.1..10.0);
        let ray = Ray::new(o, d, 0.0);
        // A ray misses exactly when its line passes farther than r from the centre or points away.
        let to_c = s.center - o;
        let along = to_c.dot(d) / d.length();
        let dist = (to_c.length_squared() - along * along).max(0.0).sqrt();
        let h = s.hit(&ray, Interval::FORWARD);
        if dist < s.radius * (1.0 - 1e-9) && along > 0.0 {
            let h = h.expect("ray through the sphere must hit");
            hits += 1;
            assert!(((h.p - s.center).length() - s.radius).abs() < 1e-12 * 10.0);
            assert!((ray.at(h.t) - h.p).length() < 1e-9);
            assert!(h.front_face && h.normal.dot(d) < 0.0);
            let (u, v) = h.uv();
            assert!((0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v));
        } else if dist > s.radius * (1.0 + 1e-9) || along < 0.0 {
            assert!(h.is_none());
        }
    }
    assert!(hits > 1000);
}

#[test]
fn quad_hits_are_inside_the_parallelogram_and_uv_recovers_the_point() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(2);
    let q = Quad::new(
        Point3::new(1.0, 0.0, -2.0),
        Vec3::new(3.0, 1.0, 0.0),
        Vec3::new(0.0, 0.5, 2.0),
        MaterialId(0),
    )
    .unwrap();
    for _ in 0..10_000 {
        let (a, b) = (rng.random_range(-0.5..1.5), rng.random_range(-0.5..1.5));
        let target = q.q + a * q.u + b * q.v;
        let o = target + unit(&mut rng) * 5.0;
        let ray = Ray::new(o, target - o, 0.0);
        let h = q.hit(&ray, Interval::FORWARD);
        let inside = (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b);
        let margin = [a, 1.0 - a, b, 1.0 - b]
            .iter()
            .map(|x| x.abs())
            .fold(f64::INFINITY, f64::min);
        if margin < 1e-9 {
            continue;
        }
        assert_eq!(h.is_some(), inside, "a {a}, b {b}");
        if let Some(h) = h {
            let (u, v) = h.uv();
            assert!((u - a).abs() < 1e-9 && (v - b).abs() < 1e-9);
            assert!((h.t - 1.0).abs() < 1e-9);
            assert_eq!(h.front_face, ray.direction.dot(q.normal) < 0.0);
        }
    }
    assert!(
        Quad::new(Point3::ZERO, Vec3::X, Vec3::X * 2.0, MaterialId(0)).is_none(),
        "zero-area quad refused"
    );
    // A ray in the quad's plane misses, it does not divide by zero into a hit.
    let grazing = Ray::new(
        Point3::new(0.0, 0.0, -2.0) + Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(3.0, 1.0, 0.0),
        0.0,
    );
    assert!(
        q.hit(&grazing, Interval::FORWARD).is_none()
            || q.hit(&grazing, Interval::FORWARD).unwrap().t.is_finite()
    );
}

#[test]
fn moving_sphere_is_where_its_time_says() {
    let s = Sphere::moving(
        Point3::new(0.0, 0.0, -5.0),
        Point3::new(2.0, 0.0, -5.0),
        0.5,
        MaterialId(0),
    );
    let ray_at = |t| Ray::new(Point3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 0.0, -1.0), t);
    assert!(s.hit(&ray_at(1.0), Interval::FORWARD).is_some());
    assert!(s.hit(&ray_at(0.0), Interval::FORWARD).is_none());
    assert!(s.bounds().min.x <= -0.5 && s.bounds().max.x >= 2.5);
}

#[test]
fn rotate_y_matches_the_book_and_instances_move_hits() {
    let t = Transform::rotate_y(15.0);
    let (s, c) = 15f64.to_radians().sin_cos();
    let p = Point3::new(1.0, 2.0, 3.0);
    let expected = Point3::new(c * p.x + s * p.z, p.y, -s * p.x + c * p.z);
    assert!((t.point(p) - expected).length() < 1e-12);
    assert!((t.inverse_point(t.point(p)) - p).length() < 1e-12);
    let full = Transform::rotate_y(15.0).then(Transform::translate(Vec3::new(265.0, 0.0, 295.0)));
    assert!((full.point(p) - (expected + Vec3::new(265.0, 0.0, 295.0))).length() < 1e-9);

    // A unit box rotated 90 degrees (x -> -z) and translated: hit from above where the rotation puts it.
    let mut b = SceneBuilder::new();
    let m = b.material(Material::lambertian(Color::ONE));
    let inner = b
        .box_group(Point3::ZERO, Point3::new(2.0, 1.0, 1.0), m)
        .unwrap();
    b.instance(
        b.world(),
        inner,
        Transform::rotate_y(90.0).then(Transform::translate(Vec3::new(10.0, 0.0, 0.0))),
    );
    let scene = b.build().unwrap();
    let mut ctx = Ctx::new();
    let down = |x: f64, z: f64| Ray::new(Point3::new(x, 5.0, z), Vec3::new(0.0, -1.0, 0.0), 0.0);
    // The box's x extent [0, 2] becomes z in [-2, 0]; its z extent [0, 1] becomes x in [0, 1] (+10).
    let h = scene
        .hit(&down(10.5, -1.5), &mut ctx)
        .expect("inside the rotated footprint");
    assert!((h.t - 4.0).abs() < 1e-9 && (h.normal - Vec3::Y).length() < 1e-9 && h.front_face);
    assert!(scene.hit(&down(11.5, -1.5), &mut ctx).is_none());
    assert!(scene.hit(&down(10.5, 0.5), &mut ctx).is_none());
}

#[test]
fn bvh_finds_the_same_closest_hit_as_brute_force() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
    for trial in 0..5 {
        let mut b = SceneBuilder::new();
        let m = b.material(Material::lambertian(Color::ONE));
        let g = b.group();
        for _ in 0..(50 + 150 * trial) {
            let c = Point3::new(
                rng.random_range(-10.0..10.0),
                rng.random_range(-10.0..10.0),
                rng.random_range(-10.0..10.0),
            );
            if rng.random::<f64>() < 0.5 {
                b.sphere(g, c, rng.random_range(0.05..1.5), m).unwrap();
            } else {
                b.quad(
                    g,
                    c,
                    unit(&mut rng) * rng.random_range(0.1..3.0),
                    unit(&mut rng) * rng.random_range(0.1..3.0),
                    m,
                )
                .unwrap();
            }
        }
        // Also an instance inside the tested list.
        let boxg = b.box_group(Point3::ZERO, Point3::ONE * 2.0, m).unwrap();
        b.instance(
            g,
            boxg,
            Transform::rotate_y(40.0).then(Transform::translate(Vec3::new(1.0, 2.0, 3.0))),
        );
        b.add(rtl_render::scene::Object::Group(g));
        let scene = b.build().unwrap();
        let mut ctx = Ctx::new();
        let mut hits = 0;
        for _ in 0..5_000 {
            let o = unit(&mut rng) * 25.0;
            let target = Point3::new(
                rng.random_range(-10.0..10.0),
                rng.random_range(-10.0..10.0),
                rng.random_range(-10.0..10.0),
            );
            let ray = Ray::new(o, target - o, 0.0);
            let fast = scene.hit_group(g, &ray, Interval::FORWARD, &mut ctx);
            let slow = scene.hit_brute_force(g, &ray, Interval::FORWARD, &mut ctx);
            assert_eq!(fast.map(|h| h.t), slow.map(|h| h.t));
            // The path of processors without AVX2 finds exactly the same hit.
            let portable = scene.hit_group_portable(g, &ray, Interval::FORWARD, &mut ctx);
            assert_eq!(
                portable.map(|h| (h.t.to_bits(), h.p.to_array().map(f64::to_bits))),
                fast.map(|h| (h.t.to_bits(), h.p.to_array().map(f64::to_bits)))
            );
            assert_eq!(
                scene.hit(&ray, &mut ctx).map(|h| h.t),
                slow.map(|h| h.t),
                "through the top level"
            );
            hits += fast.is_some() as u32;
        }
        assert!(hits > 500);
    }
}
