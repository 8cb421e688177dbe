//! The visibility roadmap over random worlds of 100, 1,000 and 3,000 convex
//! obstacles (5–8 vertices each, overlapping freely, in a square whose side
//! grows as √n so that the density stays the same), for a point robot:
//! the roadmap's construction (union boundary + rotational sweep from every
//! node + graph) and one Dijkstra query corner to corner.
//!
//! `cargo bench --bench roadmap`; figures in BENCHMARKS.md. The single
//! timed run of each size (with node and edge counts) goes to stderr.

use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use scen::geometry::polygon::convex_hull;
use scen::geometry::{Aabb, Point};
use scen::planners::roadmap::Roadmap;
use scen::planners::roadmap::arrangement::Grown;
use scen::rng::SplitMix64;

/// `n` convex polygons of 5–8 vertices (regular polygons of radius 0.5–1
/// with jittered angles) in a square of side 4·√n.
fn world(n: usize, seed: u64) -> (Vec<Grown>, Aabb) {
    let mut rng = SplitMix64::new(seed);
    let side = 4.0 * (n as f64).sqrt();
    let mut polys = Vec::with_capacity(n);
    while polys.len() < n {
        let (cx, cy) = (rng.next_f64() * side, rng.next_f64() * side);
        let k = 5 + (rng.next_f64() * 4.0) as usize;
        let r = 0.5 + 0.5 * rng.next_f64();
        let rot = rng.next_f64() * std::f64::consts::TAU;
        let pts: Vec<Point> = (0..k)
            .map(|i| {
                let a = rot
                    + (i as f64 + 0.4 * (rng.next_f64() - 0.5)) * std::f64::consts::TAU / k as f64;
                Point::new(cx + r * a.cos(), cy + r * a.sin())
            })
            .collect();
        let hull = convex_hull(&pts);
        if hull.len() == k {
            polys.push(Grown {
                vertices: hull,
                obstacle: polys.len(),
            });
        }
    }
    let bounds = Aabb::from_corners(Point::new(-2.0, -2.0), Point::new(side + 2.0, side + 2.0));
    (polys, bounds)
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("roadmap");
    group.sample_size(10);
    // ROADMAP_BENCH_N=1000 measures one size only (for profiling).
    let only: Option<usize> = std::env::var("ROADMAP_BENCH_N")
        .ok()
        .and_then(|s| s.parse().ok());
    for n in [100usize, 1000, 3000] {
        if only.is_some_and(|m| m != n) {
            continue;
        }
        let (polys, bounds) = world(n, 42);
        let (start, goal) = (bounds.min, bounds.max);
        let t = Instant::now();
        let rm = Roadmap::build(&polys, &[], start, goal, bounds, None).expect("built");
        let build = t.elapsed();
        let t = Instant::now();
        let path = rm.shortest_path(None).expect("no limit");
        let query = t.elapsed();
        let vertices: usize = polys.iter().map(|p| p.vertices.len()).sum();
        eprintln!(
            "n = {n}: {vertices} vertices, {} nodes, {} edges, build {:.3} s, query {:.3} ms, path {}",
            rm.graph.node_count(),
            rm.graph.edge_count(),
            build.as_secs_f64(),
            query.as_secs_f64() * 1e3,
            path.map_or("none".into(), |p| format!("{:.3}", p.1)),
        );
        // 3,000 obstacles take tens of seconds per build: timed once above,
        // measured by criterion only with ROADMAP_BENCH_3000=1.
        if n == 3000 && std::env::var_os("ROADMAP_BENCH_3000").is_none() {
            continue;
        }
        group.measurement_time(Duration::from_secs(if n >= 1000 { 60 } else { 5 }));
        group.bench_function(format!("build_{n}"), |b| {
            b.iter(|| Roadmap::build(&polys, &[], start, goal, bounds, None))
        });
        group.bench_function(format!("query_{n}"), |b| b.iter(|| rm.shortest_path(None)));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
