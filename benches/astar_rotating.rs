//! The rotating rod in the apartment at δ = 0.25 with `layers auto`
//! (scenarios/apartment_rod_fine.scen, ≈ 3.1 million lattice
//! configurations): the C-space build alone, and the whole plan (C-space,
//! lattice classification, search with lazily validated edges).
//!
//! It also prints where the time of one plan goes (C-space build, display
//! trace, classification, search and the edge validation inside it).
//!
//! `cargo bench --bench astar_rotating`; figures in BENCHMARKS.md.

use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use scen::geometry::RobotShape;
use scen::geometry::cspace::ObstaclePieces;
use scen::planners::astar::Astar;
use scen::planners::astar_rotating;

fn bench(c: &mut Criterion) {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/apartment_rod_fine.scen");
    let scenario = scen::load(&file).expect("the scenario loads");
    let plan = &scenario.plans[0];
    let RobotShape::Polygon(robot) = &scenario.robots[plan.robot].shape else {
        panic!("apartment_rod_fine plans for a polygon robot");
    };
    let world = &scenario.world;
    let task = plan.task(&scenario);
    let settings = plan
        .settings
        .as_any()
        .downcast_ref::<Astar>()
        .expect("an astar plan");
    let spec = settings.lattice;
    let once = astar_rotating::plan(&task, settings, robot);
    assert!(once.path.is_some(), "the fine apartment has a path");
    eprintln!(
        "apartment_rod_fine: {} configurations ({} × {} × {} layers), {} expanded",
        spec.cells_f64(),
        spec.nx,
        spec.ny,
        spec.layers,
        once.expanded
    );

    // The split of one plan, measured (edge checks timed one by one) over
    // a few runs; the median run by total time is printed.
    let mut runs: Vec<_> = (0..7)
        .map(|_| astar_rotating::plan_profiled(&task, settings, robot).1)
        .collect();
    runs.sort_by_key(|p| p.cspace + p.trace + p.classify + p.search);
    let p = runs[runs.len() / 2];
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    eprintln!(
        "split (median of 7): C-space build {:.1} ms, display trace {:.1} ms, \
         classification {:.1} ms ({:.1} M configurations/s), search {:.1} ms \
         ({:.2} M expansions/s) of which edge validation {:.1} ms ({} edges)",
        ms(p.cspace),
        ms(p.trace),
        ms(p.classify),
        spec.cells_f64() / p.classify.as_secs_f64() / 1e6,
        ms(p.search),
        once.expanded as f64 / p.search.as_secs_f64() / 1e6,
        ms(p.edge_validation),
        p.edges_checked,
    );

    let mut group = c.benchmark_group("apartment_rod_fine");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(20));
    group.bench_function("cspace_layers", |b| {
        b.iter(|| ObstaclePieces::new(world).layers(robot, spec.layers))
    });
    group.bench_function("plan_end_to_end", |b| {
        b.iter(|| astar_rotating::plan(&task, settings, robot))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
