//! `online` on the MovingAI maze512-32-9 map (SPEC 3.2, issue 4): a point
//! robot that does not know the maze, `sense 1`, 8 neighbours, from the
//! start to the goal of sampled MovingAI queries, with `replan` (an A* from
//! scratch each time the plan is blocked) and `dstar_lite` (one D* Lite
//! search repaired incrementally).
//!
//! First, once, a summary over [`SUMMARY_ROWS`]: total expansions, moves,
//! searches and wall time of both strategies on the same runs, and the
//! expansion ratio; then again with h = 0 in both searches on
//! [`BLIND_ROWS`] (A* uses the Euclidean heuristic of SPEC 3.1, D* Lite the
//! exact octile distance, so the first ratio also contains the heuristics'
//! difference). Then criterion times one query ([`TIMED_ROW`]) per strategy.
//! Traces are off (`Options::traced = false`).
//!
//! Run: `cargo bench --bench online_maze512`.

use std::hint::black_box;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use criterion::{Criterion, SamplingMode, criterion_group, criterion_main};
use scen::contract::MetricValue;
use scen::planners::online::{Online, Options, navigate};
use scen::scenario::Scenario;

const MAP: &str = "maze512-32-9.map";
const SCEN: &str = "maze512-32-9.map.scen";
/// Rows of the `.scen` file (0-based, after `version 1`): buckets 50 to 750.
const SUMMARY_ROWS: [usize; 5] = [500, 1500, 3500, 5500, 7500];
const BLIND_ROWS: [usize; 2] = [500, 1500];
const TIMED_ROW: usize = 500;

/// `../shared/data/movingai` next to the repository (or, from a worktree
/// under `wt/`, two levels up).
fn data_dir() -> PathBuf {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let near = root.join("../shared/data/movingai");
    if near.is_dir() {
        near
    } else {
        root.join("../../shared/data/movingai")
    }
}

/// A scenario with one `replan` and one `dstar_lite` plan per row, loaded
/// through scen (plans named `replan_ROW` and `dstar_ROW`).
fn load(rows: &[usize]) -> Scenario {
    let dir = data_dir();
    let map = dir.join(MAP);
    assert!(
        map.is_file(),
        "the MovingAI data is missing: {}",
        map.display()
    );
    let queries = std::fs::read_to_string(dir.join(SCEN)).expect("a readable .scen file");
    let lines: Vec<&str> = queries.lines().skip(1).collect();
    // The map beside the scenario: a scenario reads only files inside its
    // folder (SPEC 2.2).
    let mut text = "world {\n  bounds (0, 0) (512, 512)\n  grid G \"maze.map\" cell 1 origin (0, 0)\n}\nrobot p point\n".to_string();
    for &row in rows {
        let f: Vec<&str> = lines[row].split('\t').collect();
        let int = |s: &str| s.trim().parse::<f64>().expect("a coordinate");
        // MovingAI cell (x, y), row 0 on top → the centre of lattice point
        // (x, 511 − y).
        let (sx, sy) = (int(f[4]) + 0.5, 512.0 - int(f[5]) - 0.5);
        let (gx, gy) = (int(f[6]) + 0.5, 512.0 - int(f[7]) - 0.5);
        for (name, strategy) in [("replan", "replan"), ("dstar", "dstar_lite")] {
            text += &format!(
                "plan {name}_{row} online p {{ start ({sx}, {sy}) goal ({gx}, {gy}) strategy {strategy} }}\n"
            );
        }
    }
    let tmp = std::env::temp_dir().join(format!("scen-online-bench-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).expect("a temporary folder");
    let file = tmp.join("maze.scen");
    std::fs::copy(&map, tmp.join("maze.map")).expect("copying the map");
    std::fs::write(&file, text).expect("writing the scenario");
    let loaded = scen::load(&file);
    let _ = std::fs::remove_dir_all(&tmp);
    match loaded {
        Ok(s) => s,
        Err(f) => panic!("{}", scen::diagnostics::render_diags(&f.diags, &f.sources)),
    }
}

fn run(s: &Scenario, name: &str, options: Options) -> scen::contract::PlanOutcome {
    let plan = s.plans.iter().find(|p| p.name == name).expect("a plan");
    let settings = plan
        .settings
        .as_any()
        .downcast_ref::<Online>()
        .expect("an online plan");
    navigate(&plan.task(s), settings, options)
}

fn metric(out: &scen::contract::PlanOutcome, m: &str) -> f64 {
    match out.extra.get(m) {
        Some(MetricValue::Num(x)) => *x,
        _ => f64::NAN,
    }
}

/// Totals of one strategy over some runs.
#[derive(Default)]
struct Totals {
    expanded: u64,
    steps: f64,
    searches: f64,
    traveled: f64,
    time: Duration,
}

fn summary(s: &Scenario, rows: &[usize], heuristic: bool) {
    let options = Options {
        traced: false,
        heuristic,
    };
    let (mut re, mut ds) = (Totals::default(), Totals::default());
    eprintln!("\n{} (h {}):", MAP, if heuristic { "on" } else { "= 0" });
    eprintln!(
        "row | replan: expanded, searches, moves, time | dstar_lite: expanded, repairs, moves, time | ratio"
    );
    for &row in rows {
        let mut line = format!("{row}");
        let mut expanded = [0u64; 2];
        for (k, (strategy, totals)) in [("replan", &mut re), ("dstar", &mut ds)]
            .into_iter()
            .enumerate()
        {
            let t = Instant::now();
            let out = run(s, &format!("{strategy}_{row}"), options);
            let time = t.elapsed();
            assert!(
                out.path.is_some(),
                "{strategy} row {row}: the goal was not reached"
            );
            totals.expanded += out.expanded;
            totals.steps += metric(&out, "steps");
            totals.searches += metric(&out, "replans");
            totals.traveled += metric(&out, "traveled");
            totals.time += time;
            expanded[k] = out.expanded;
            line += &format!(
                " | {} {} {} {:.2?}",
                out.expanded,
                metric(&out, "replans"),
                metric(&out, "steps"),
                time
            );
        }
        eprintln!("{line} | {:.1}", expanded[0] as f64 / expanded[1] as f64);
    }
    for (name, t) in [("replan", &re), ("dstar_lite", &ds)] {
        eprintln!(
            "total {name}: {} expansions, {} searches, {} moves, traveled {:.1}, {:.2?}",
            t.expanded, t.searches, t.steps, t.traveled, t.time
        );
    }
    eprintln!(
        "expansions replan / dstar_lite = {:.1}, time = {:.1}",
        re.expanded as f64 / ds.expanded as f64,
        re.time.as_secs_f64() / ds.time.as_secs_f64()
    );
}

fn benches(c: &mut Criterion) {
    let s = load(&SUMMARY_ROWS);
    summary(&s, &SUMMARY_ROWS, true);
    summary(&s, &BLIND_ROWS, false);

    let options = Options {
        traced: false,
        heuristic: true,
    };
    let mut group = c.benchmark_group("maze512_online");
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    for strategy in ["replan", "dstar"] {
        let name = format!("{strategy}_{TIMED_ROW}");
        group.bench_function(&name, |b| {
            b.iter(|| black_box(run(&s, &name, options).expanded))
        });
    }
    group.finish();
}

criterion_group!(online_maze512, benches);
criterion_main!(online_maze512);
