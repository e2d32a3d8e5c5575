//! Cost per sample of each estimator: `cargo bench -p rtl-mc --bench estimators`. Criterion reports
//! throughput in samples per second; each iteration evaluates the integrand `N` times.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::densities::{linear_pdf, perfect_pdf, sample_linear, sample_perfect};
use rtl_mc::{
    Interval, Rect, RunningStats, importance, jittered, jittered_2d, plain, plain_2d, sobol,
    sobol_2d,
};
use std::hint::black_box;

const N: u64 = 1 << 14;

fn x_sq(x: f64) -> f64 {
    x * x
}

fn in_circle(p: [f64; 2]) -> f64 {
    if p[0] * p[0] + p[1] * p[1] < 1.0 {
        1.0
    } else {
        0.0
    }
}

fn estimators(c: &mut Criterion) {
    let line = Interval::new(0.0, 2.0).unwrap();
    let square = Rect::new(-1.0, 1.0, -1.0, 1.0).unwrap();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    let mut g = c.benchmark_group("per_sample");
    g.throughput(Throughput::Elements(N));
    g.bench_function("running_stats_push", |b| {
        b.iter(|| {
            let mut s = RunningStats::new();
            for i in 0..N {
                s.push(black_box(i as f64));
            }
            s
        })
    });
    g.bench_function("plain_x_sq", |b| {
        b.iter(|| plain(x_sq, line, N, &mut rng).unwrap())
    });
    g.bench_function("jittered_x_sq", |b| {
        b.iter(|| jittered(x_sq, line, N / 16, 16, &mut rng).unwrap())
    });
    g.bench_function("sobol_x_sq", |b| {
        b.iter(|| sobol(x_sq, line, N / 16, 16, &mut rng).unwrap())
    });
    g.bench_function("importance_linear_x_sq", |b| {
        let s = |r: &mut Xoshiro256PlusPlus| sample_linear(r.random::<f64>());
        b.iter(|| importance(x_sq, s, linear_pdf, N, &mut rng).unwrap())
    });
    g.bench_function("importance_perfect_x_sq", |b| {
        let s = |r: &mut Xoshiro256PlusPlus| sample_perfect(r.random::<f64>());
        b.iter(|| importance(x_sq, s, perfect_pdf, N, &mut rng).unwrap())
    });
    g.bench_function("plain_2d_pi", |b| {
        b.iter(|| plain_2d(in_circle, square, N, &mut rng).unwrap())
    });
    g.bench_function("jittered_2d_pi", |b| {
        b.iter(|| jittered_2d(in_circle, square, (32, 32), 16, &mut rng).unwrap())
    });
    g.bench_function("sobol_2d_pi", |b| {
        b.iter(|| sobol_2d(in_circle, square, N / 16, 16, &mut rng).unwrap())
    });
    g.finish();
}

criterion_group!(benches, estimators);
criterion_main!(benches);
