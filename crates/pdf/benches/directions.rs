//! Directions per second for each warp and each `Pdf` type.
//!
//! `cargo bench -p rtl-pdf --bench directions`. Each measurement makes 1024 directions (throughput is
//! reported per direction): warps from precomputed `u` (the warp alone), `Pdf::generate` with
//! Xoshiro256++ (the warp plus two random numbers, as a renderer pays), and `Pdf::value`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use glam::{DVec2, DVec3};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_pdf::warp::{self, SphericalRectangle};
use rtl_pdf::{
    CosinePdf, HemispherePdf, HittablePdf, MixturePdf, Pdf, QuadTarget, SpherePdf, SphereTarget,
};
use std::hint::black_box;

const BATCH: usize = 1024;

fn warps(c: &mut Criterion) {
    let mut r = Xoshiro256PlusPlus::seed_from_u64(1);
    let us: Vec<DVec2> = (0..BATCH)
        .map(|_| DVec2::new(r.random(), r.random()))
        .collect();
    let mut g = c.benchmark_group("warp");
    g.throughput(Throughput::Elements(BATCH as u64));
    let sr = SphericalRectangle::new(
        DVec3::new(0.1, 0.2, 1.0),
        DVec3::new(-1.0, -0.5, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(0.0, 1.5, 0.0),
    )
    .unwrap();
    let (q, e1, e2) = (
        DVec3::new(-1.0, -0.5, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(0.0, 1.5, 0.0),
    );
    let o = DVec3::new(0.1, 0.2, 1.0);
    let n = e1.cross(e2).normalize();
    let area_pdf = warp::parallelogram_pdf(e1, e2);
    macro_rules! bench {
        ($name:expr, $f:expr) => {
            g.bench_function($name, |b| {
                b.iter(|| {
                    let mut acc = DVec3::ZERO;
                    for &u in &us {
                        acc += $f(black_box(u));
                    }
                    acc
                })
            });
        };
    }
    bench!("uniform_sphere", warp::sample_uniform_sphere);
    bench!("uniform_hemisphere", warp::sample_uniform_hemisphere);
    bench!("cosine_hemisphere", warp::sample_cosine_hemisphere);
    bench!("uniform_cone", |u| warp::sample_uniform_cone(u, 0.1));
    bench!("parallelogram_to_solid_angle", |u| {
        let p = warp::sample_parallelogram(u, q, e1, e2);
        let pdf = warp::area_to_solid_angle(area_pdf, o, p, n);
        (p - o).normalize() * pdf
    });
    bench!("spherical_rectangle", |u| sr.sample_direction(u));
    bench!("spherical_rectangle_setup_and_sample", |u| {
        SphericalRectangle::new(o, q, e1, e2)
            .unwrap()
            .sample_direction(u)
    });
    g.finish();
}

fn pdfs(c: &mut Criterion) {
    let n = DVec3::new(0.3, 0.5, 0.8).normalize();
    let origin = DVec3::new(0.1, 0.2, 0.0);
    let sphere = [SphereTarget::new(DVec3::new(0.5, 0.4, 3.0), 0.7)];
    let quad = [QuadTarget::new(
        DVec3::new(-1.0, -0.5, 2.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(0.0, 1.5, 0.0),
    )];
    let rect = [quad[0].with_spherical_rectangles(true)];
    let to_sphere = HittablePdf::new(origin, &sphere).unwrap();
    let to_quad = HittablePdf::new(origin, &quad).unwrap();
    let to_rect = HittablePdf::new(origin, &rect).unwrap();
    let mixture = MixturePdf::new(to_quad, CosinePdf::new(DVec3::Z));

    let mut g = c.benchmark_group("generate");
    g.throughput(Throughput::Elements(BATCH as u64));
    // the baseline: two uniform numbers from Xoshiro256++, what every `generate` draws first
    let mut r = Xoshiro256PlusPlus::seed_from_u64(2);
    g.bench_function("two_uniforms_only", |b| {
        b.iter(|| {
            let mut acc = DVec2::ZERO;
            for _ in 0..BATCH {
                acc += DVec2::new(r.random(), r.random());
            }
            acc
        })
    });
    fn gen_bench<P: Pdf>(
        g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
        name: &str,
        pdf: &P,
    ) {
        let mut r = Xoshiro256PlusPlus::seed_from_u64(2);
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut acc = DVec3::ZERO;
                for _ in 0..BATCH {
                    acc += pdf.generate(&mut r);
                }
                acc
            })
        });
    }
    gen_bench(&mut g, "SpherePdf", &SpherePdf);
    gen_bench(&mut g, "HemispherePdf", &HemispherePdf::new(n));
    gen_bench(&mut g, "CosinePdf", &CosinePdf::new(n));
    gen_bench(&mut g, "HittablePdf_sphere", &to_sphere);
    gen_bench(&mut g, "HittablePdf_quad_area", &to_quad);
    gen_bench(&mut g, "HittablePdf_quad_spherical_rectangle", &to_rect);
    gen_bench(&mut g, "MixturePdf_quad_cosine", &mixture);
    g.finish();

    let mut r = Xoshiro256PlusPlus::seed_from_u64(3);
    let dirs: Vec<DVec3> = (0..BATCH).map(|_| mixture.generate(&mut r)).collect();
    let mut g = c.benchmark_group("value");
    g.throughput(Throughput::Elements(BATCH as u64));
    fn value_bench<P: Pdf>(
        g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
        name: &str,
        pdf: &P,
        dirs: &[DVec3],
    ) {
        g.bench_function(name, |b| {
            b.iter(|| dirs.iter().map(|&d| pdf.value(black_box(d))).sum::<f64>())
        });
    }
    value_bench(&mut g, "CosinePdf", &CosinePdf::new(n), &dirs);
    value_bench(&mut g, "HittablePdf_sphere", &to_sphere, &dirs);
    value_bench(&mut g, "HittablePdf_quad_area", &to_quad, &dirs);
    value_bench(
        &mut g,
        "HittablePdf_quad_spherical_rectangle",
        &to_rect,
        &dirs,
    );
    value_bench(&mut g, "MixturePdf_quad_cosine", &mixture, &dirs);
    g.finish();
}

criterion_group!(benches, warps, pdfs);
criterion_main!(benches);
