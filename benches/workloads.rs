//! Criterion benchmarks of the workloads of `bench/WORKLOADS.md`, in-process.
//! `cargo bench --bench workloads` (a few minutes). The cross-tool comparison, one
//! process per cell, is `python3 bench/compare.py`.

mod common;

use common::*;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::time::Duration;

fn w1(c: &mut Criterion) {
    let w = w1_prepare();
    let r = w1_run(&w);
    assert!(r.1.is_empty(), "W1 failed checks: {:?}", r.1);
    let mut g = c.benchmark_group("W1");
    g.bench_function("suite", |b| b.iter(|| w1_run(&w)));
    g.bench_function("check_derivations", |b| b.iter(w1check_run));
    g.finish();
}

fn w2(c: &mut Criterion) {
    let mut g = c.benchmark_group("W2");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for n in [4u32, 8, 12, 20] {
        let p = w2_prepare(n);
        g.bench_with_input(BenchmarkId::from_parameter(n), &p, |b, p| {
            b.iter(|| w2_run(p))
        });
    }
    g.finish();
}

fn w3(c: &mut Criterion) {
    let mut g = c.benchmark_group("W3");
    g.sample_size(10).measurement_time(Duration::from_secs(3));
    for kind in ["chain", "tri", "dense"] {
        for n in [4usize, 6] {
            let p = w3_prepare(kind, n);
            g.bench_with_input(BenchmarkId::new(kind, n), &p, |b, p| b.iter(|| w3_run(p)));
        }
    }
    g.finish();
}

fn w4(c: &mut Criterion) {
    let w = w4_prepare();
    let d = w4_run(&w);
    let fp = w4_fingerprint(&w, &d);
    assert_eq!(fp["mismatches"], 0, "W4: {fp}");
    let mut g = c.benchmark_group("W4");
    g.sample_size(10).measurement_time(Duration::from_secs(5));
    g.bench_function("1000_pairs", |b| b.iter(|| w4_run(&w)));
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_secs(1)).measurement_time(Duration::from_secs(3));
    targets = w1, w2, w3, w4
}
criterion_main!(benches);
