//! The rotating rod in the apartment at δ = 0.25 with `layers auto`
//! (scenarios/apartment_rod_fine.scen, ≈ 3.1 million lattice
//! configurations): the C-space build alone, and the whole plan (C-space,
//! lattice classification, search with lazily validated edges).
//!
//! `cargo bench --bench astar_rotating`; figures in BENCHMARKS.md.

use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use scen::geometry::RobotShape;
use scen::geometry::cspace::ObstaclePieces;
use scen::planners::astar_rotating;
use scen::planners::lattice::LatticeSpec;

fn bench(c: &mut Criterion) {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/apartment_rod_fine.scen");
    let scenario = scen::load(&file).expect("the scenario loads");
    let plan = &scenario.plans[0];
    let RobotShape::Polygon(robot) = &scenario.robots[plan.robot].shape else {
        panic!("apartment_rod_fine plans for a polygon robot");
    };
    let world = &scenario.world;
    let spec = LatticeSpec::from_params(world, &scenario.robots[plan.robot].shape, &plan.params);
    let once = astar_rotating::plan(world, robot, &plan.params);
    assert!(once.path.is_some(), "the fine apartment has a path");
    eprintln!(
        "apartment_rod_fine: {} configurations ({} × {} × {} layers), {} expanded",
        spec.cells_f64(),
        spec.nx,
        spec.ny,
        spec.layers,
        once.expanded
    );

    let mut group = c.benchmark_group("apartment_rod_fine");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(20));
    group.bench_function("cspace_layers", |b| {
        b.iter(|| ObstaclePieces::new(world).layers(robot, spec.layers))
    });
    group.bench_function("plan_end_to_end", |b| {
        b.iter(|| astar_rotating::plan(world, robot, &plan.params))
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
