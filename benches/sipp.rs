//! `sipp` on PythonRobotics' own example (scenarios/time_pythonrobotics.scen,
//! issue 41 item 4): the whole plan (lattice, the obstacles' broad phase,
//! the search), the figure BENCHMARKS.md sets beside PythonRobotics' SIPP.
//!
//! `cargo bench --bench sipp`.

use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};

fn bench(c: &mut Criterion) {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/time_pythonrobotics.scen");
    let scenario = scen::load(&file).expect("the scenario loads");
    let plan = &scenario.plans[0];
    let task = plan.task(&scenario);
    let once = plan.settings.plan(&task);
    assert_eq!(once.cost, Some(37.0), "PythonRobotics' arrival");
    let mut group = c.benchmark_group("sipp_pythonrobotics");
    group.measurement_time(Duration::from_secs(10));
    group.bench_function("plan", |b| b.iter(|| plan.settings.plan(&task)));
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
