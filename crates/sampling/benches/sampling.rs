//! Throughput of one interpolated sample (bin search + lerp + pdf) for random queries, single thread:
//! binary search, guide table, Eytzinger layout and alias table, on the book's e^(-x/2π) sin² x
//! tabulated in N bins.
//!
//! `cargo bench -p rtl-sampling -- --measurement-time 2 --warm-up-time 1`

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_sampling::targets::BookSinSquared;
use rtl_sampling::{AliasPiecewise, EytzingerCdf, GuideTable, Sample, TabulatedCdf};
use std::hint::black_box;

/// Samples per iteration.
const BATCH: u64 = 4096;

fn run(rng: &mut Xoshiro256PlusPlus, sample: impl Fn(f64) -> Sample) -> f64 {
    let mut acc = 0.0;
    for _ in 0..BATCH {
        let s = sample(rng.random::<f64>());
        acc += s.x + s.pdf;
    }
    acc
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("sample");
    group.throughput(Throughput::Elements(BATCH));
    for n in [1_000usize, 100_000, 10_000_000] {
        let table =
            TabulatedCdf::from_density(BookSinSquared::unnormalised, 0.0, std::f64::consts::TAU, n)
                .unwrap();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
        group.bench_with_input(BenchmarkId::new("binary_search", n), &table, |b, t| {
            b.iter(|| black_box(run(&mut rng, |u| t.sample(u))))
        });
        let guide = GuideTable::new(table.clone()).unwrap();
        group.bench_with_input(BenchmarkId::new("guide_table", n), &guide, |b, g| {
            b.iter(|| black_box(run(&mut rng, |u| g.sample(u))))
        });
        let eytzinger = EytzingerCdf::new(&table);
        group.bench_with_input(BenchmarkId::new("eytzinger", n), &eytzinger, |b, e| {
            b.iter(|| black_box(run(&mut rng, |u| e.sample(u))))
        });
        let alias = AliasPiecewise::from_tabulated(&table).unwrap();
        group.bench_with_input(BenchmarkId::new("alias", n), &alias, |b, a| {
            b.iter(|| black_box(run(&mut rng, |u| a.sample(u))))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
