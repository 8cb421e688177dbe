//! Shortest-path lengths per second of the steering functions
//! (`geometry::steer`, issue 23's target: ≥ 5 M Reeds–Shepp lengths per
//! second per core), and the full paths (segments built) for comparison.
//!
//! A fixed seeded sample of 10,000 pairs with turning radius 1: starts and
//! goals uniform in [−10, 10]² with headings uniform in [−π, π) — the
//! distances a sampling planner asks for in a room of 20 turning radii.
//! One iteration computes every pair once.
//!
//! `cargo bench --no-default-features --bench steer`; figures in
//! BENCHMARKS.md.

use std::f64::consts::PI;
use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use scen::geometry::Config;
use scen::geometry::steer::{Model, Steering};
use scen::rng::SplitMix64;

const PAIRS: usize = 10_000;

fn sample() -> Vec<(Config, Config)> {
    let mut rng = SplitMix64::new(5);
    let mut c = || {
        Config::new(
            rng.range(-10.0, 10.0),
            rng.range(-10.0, 10.0),
            rng.range(-PI, PI),
        )
    };
    (0..PAIRS).map(|_| (c(), c())).collect()
}

fn steering(c: &mut Criterion) {
    let pairs = sample();
    let mut group = c.benchmark_group("steer");
    group.throughput(Throughput::Elements(PAIRS as u64));
    for (name, model) in [
        ("reeds_shepp", Model::ReedsShepp),
        ("dubins", Model::Dubins),
    ] {
        let s = Steering::new(model, 1.0);
        // The lengths of one pass, to set beside scripts/ompl_steer.cpp's.
        let one: f64 = pairs.iter().map(|&(a, g)| s.distance(a, g)).sum();
        println!("scen {name:<11} lengths of one pass {one:.6}");
        group.bench_function(format!("{name}_length"), |b| {
            b.iter(|| {
                let mut sum = 0.0;
                for &(a, g) in &pairs {
                    sum += s.distance(black_box(a), black_box(g));
                }
                sum
            })
        });
        group.bench_function(format!("{name}_path"), |b| {
            b.iter(|| {
                let mut n = 0usize;
                for &(a, g) in &pairs {
                    n += s.shortest(black_box(a), black_box(g)).segments().len();
                }
                n
            })
        });
    }
    group.finish();
}

criterion_group!(benches, steering);
criterion_main!(benches);
