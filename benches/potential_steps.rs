//! Steps per second of the `potential` planner (issue 6: ≥ 1 million steps/s
//! with 10 segment obstacles, ≥ 100 000 with 1 000).
//!
//! The world is a strip 1 000 long with N vertical segment walls ("rungs")
//! from y = 0.5 to y = 3.5, evenly spaced along it (N = 10 or 1 000); the
//! robot walks from (1, 7) to (999, 7) with ρ0 = 4, so with 1 000 rungs
//! every step feels about four of them (and the bucket it reads lists about
//! a dozen). The rungs push up, the goal pulls along: ≈ 20 000 steps of
//! 0.05, no local minimum (asserted). A plan is timed whole: building the
//! field and collision indexes, then the walk (not the runner's
//! validation).
//!
//! Run: `cargo bench --bench potential_steps`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use scen::planners::potential;

/// The scenario text with `rungs` segment obstacles.
fn strip(rungs: usize) -> String {
    let spacing = 1000.0 / rungs as f64;
    let mut text = String::from("world {\n  bounds (0, 0) (1000, 10)\n");
    for k in 0..rungs {
        let x = (k as f64 + 0.5) * spacing;
        text += &format!("  segment ({x}, 0.5) ({x}, 3.5)\n");
    }
    text += "}\nrobot p point\nplan walk potential p {\n  start (1, 7)\n  goal (999, 7)\n  influence 4\n}\n";
    text
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("potential_strip");
    for rungs in [10, 1000] {
        let dir = std::env::temp_dir().join(format!("scen-bench-potential-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary folder");
        let file = dir.join(format!("strip_{rungs}.scen"));
        std::fs::write(&file, strip(rungs)).expect("write the scenario");
        let scenario = scen::load(&file).expect("the strip loads");
        let _ = std::fs::remove_dir_all(&dir);
        let plan = &scenario.plans[0];
        let task = plan.task(&scenario);
        let settings = plan
            .settings
            .as_any()
            .downcast_ref::<potential::Potential>()
            .expect("a potential plan");
        let once = potential::plan(&task, settings);
        assert!(once.path.is_some(), "the walk reaches its goal");
        let steps = once.expanded;
        let minima = once.extra["minima"].as_f64();
        assert_eq!(minima, 0.0, "a straight walk");
        eprintln!("{rungs} segments: {steps} steps per plan");
        group.throughput(Throughput::Elements(steps));
        group.bench_function(format!("{rungs}_segments"), |b| {
            b.iter(|| black_box(potential::plan(&task, settings)))
        });
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = bench
}
criterion_main!(benches);
