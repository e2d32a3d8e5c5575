//! Intersection alone: `Scene::hit` for a fixed set of rays in `cornell` (a small top group and a
//! small box instance, both in the flat form) and `book2-final` (4-wide trees, media), through the
//! run-time chosen path (AVX2 where the processor has it) and through the portable one.
//! `cargo bench -p rtl-render --bench hit`; rays/s = elements/s in criterion's report.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_render::ray::{Interval, Ray};
use rtl_render::sampler::Ctx;
use rtl_render::scene::{GroupId, Scene};
use rtl_render::scenes;
use rtl_render::vec::{Point3, Vec3};
use std::hint::black_box;

fn builtin(name: &str) -> Scene {
    (scenes::find(name).unwrap().build)(&Default::default())
        .unwrap()
        .scene
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
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
