//! Intersection alone: `Scene::hit` for a fixed set of rays in `cornell` (a small top group in the flat
//! form, its rotated box flattened into it) and `book2-final` (4-wide trees, media), through the
//! run-time chosen path (AVX2 where the processor has it) and through the portable one; and book 3's
//! Cornell box built by hand with its box flattened (`cornell-flat`) and placed as an instance
//! (`cornell-placed`), side by side.
//! `cargo bench -p rtl-render --bench hit`; rays/s = elements/s in criterion's report.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_render::material::{Albedo, Material};
use rtl_render::ray::{Interval, Ray};
use rtl_render::sampler::Ctx;
use rtl_render::scene::{GroupId, Scene, SceneBuilder, Transform};
use rtl_render::scenes;
use rtl_render::vec::Color;
use rtl_render::vec::{Point3, Vec3};
use std::hint::black_box;

fn builtin(name: &str) -> Scene {
    (scenes::find(name).unwrap().build)(&Default::default())
        .unwrap()
        .scene
}

/// Book 3's Cornell box as `scenes::cornell` builds it (five walls, the light, the box rotated by 15
/// degrees, the glass sphere), its box flattened into the room or placed as an instance.
fn cornell_by_hand(flatten: bool) -> Scene {
    let mut b = SceneBuilder::new();
    b.flatten = flatten;
    let w = b.world();
    let red = b.material(Material::lambertian(Color::new(0.65, 0.05, 0.05)));
    let white = b.material(Material::lambertian(Color::splat(0.73)));
    let green = b.material(Material::lambertian(Color::new(0.12, 0.45, 0.15)));
    let light = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(15.0)),
        two_sided: false,
    });
    let v = Vec3::new;
    for (q, u, w2, m) in [
        (
            v(555.0, 0.0, 0.0),
            v(0.0, 0.0, 555.0),
            v(0.0, 555.0, 0.0),
            green,
        ),
        (
            v(0.0, 0.0, 555.0),
            v(0.0, 0.0, -555.0),
            v(0.0, 555.0, 0.0),
            red,
        ),
        (
            v(0.0, 555.0, 0.0),
            v(555.0, 0.0, 0.0),
            v(0.0, 0.0, 555.0),
            white,
        ),
        (
            v(0.0, 0.0, 555.0),
            v(555.0, 0.0, 0.0),
            v(0.0, 0.0, -555.0),
            white,
        ),
        (
            v(555.0, 0.0, 555.0),
            v(-555.0, 0.0, 0.0),
            v(0.0, 555.0, 0.0),
            white,
        ),
        (
            v(213.0, 554.0, 227.0),
            v(130.0, 0.0, 0.0),
            v(0.0, 0.0, 105.0),
            light,
        ),
    ] {
        b.quad(w, q, u, w2, m).unwrap();
    }
    let inner = b
        .box_group(Point3::ZERO, v(165.0, 330.0, 165.0), white)
        .unwrap();
    b.instance(
        w,
        inner,
        Transform::rotate_y(15.0).then(Transform::translate(v(265.0, 0.0, 295.0))),
    );
    let glass = b.material(Material::Dielectric { ior: 1.5 });
    b.sphere(w, Point3::new(190.0, 90.0, 190.0), 90.0, glass)
        .unwrap();
    b.build().unwrap()
}

/// Rays from points uniform in the box `[lo, hi]`, in directions uniform on the sphere: what the
/// scattered rays of a path look like.
fn rays(lo: Point3, hi: Point3, n: usize) -> Vec<Ray> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(16);
    (0..n)
        .map(|_| {
            let o = lo + (hi - lo) * Vec3::new(rng.random(), rng.random(), rng.random());
            let d = loop {
                let v = Vec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                if v.length_squared() > 1e-6 && v.length_squared() <= 1.0 {
                    break v;
                }
            };
            Ray::new(o, d, 0.0)
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("hit");
    for (label, name, lo, hi) in [
        (
            "cornell",
            "cornell",
            Point3::splat(1.0),
            Point3::splat(554.0),
        ),
        (
            "book2-final",
            "book2-final",
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(600.0, 600.0, 600.0),
        ),
    ] {
        let scene = builtin(name);
        let rays = rays(lo, hi, 4096);
        g.throughput(Throughput::Elements(rays.len() as u64));
        let mut ctx = Ctx::new();
        g.bench_function(label, |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| scene.hit(black_box(r), &mut ctx).is_some())
                    .count()
            })
        });
        g.bench_function(format!("{label}-portable"), |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| {
                        scene
                            .hit_group_portable(
                                GroupId(0),
                                black_box(r),
                                Interval::FORWARD,
                                &mut ctx,
                            )
                            .is_some()
                    })
                    .count()
            })
        });
    }
    // The flattened box against the placed one, on the same rays, in one run.
    let rays = rays(Point3::splat(1.0), Point3::splat(554.0), 4096);
    for (label, flatten) in [("cornell-flat", true), ("cornell-placed", false)] {
        let scene = cornell_by_hand(flatten);
        let placed = scene.groups[0]
            .objects
            .iter()
            .any(|o| matches!(o, rtl_render::scene::Object::Instance { .. }));
        assert_eq!(placed, !flatten);
        let mut ctx = Ctx::new();
        g.bench_function(label, |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| scene.hit(black_box(r), &mut ctx).is_some())
                    .count()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
