//! The sampling planners' own invariants, through scenarios written as text
//! (the registry's contract test covers metrics, validity of paths,
//! determinism of the JSON and limits).

use crate::contract::PlanOutcome;
use crate::geometry::Config;
use crate::geometry::validator::{DEFAULT_TOLERANCE, validate_path};
use crate::scenario::{Scenario, load_text};

/// A room with a wall and a gap 3 wide; the rod must turn to pass it.
fn world() -> &'static str {
    "world {
  bounds (0, 0) (20, 20)
  rect L (0, 9.5) (8.5, 10.5)
  rect R (11.5, 9.5) (20, 10.5)
  disk D (15, 4) 1.5
}
robot rod polygon [(0,0), (6,0), (6,1), (0,1)]
robot dot point
"
}

fn scenario(kind: &str, robot: &str, extra: &str) -> Scenario {
    seeded(kind, robot, extra, 5)
}

fn seeded(kind: &str, robot: &str, extra: &str, seed: u64) -> Scenario {
    load_text(&format!(
        "{}plan p {kind} {robot} {{\n  start (3, 3, 0deg)\n  goal (3, 16, 0deg)\n  seed {seed}\n  {extra}\n}}\n",
        world()
    ))
}

/// Asserts that one of `out`'s notes contains `part` (`what`: the case).
fn assert_noted(out: &PlanOutcome, part: &str, what: &str) {
    assert!(
        out.notes.iter().any(|n| n.contains(part)),
        "{what}: no note with {part:?} in {:?}",
        out.notes
    );
}

fn run(s: &Scenario) -> PlanOutcome {
    let plan = &s.plans[0];
    plan.settings.plan(&plan.task(s))
}

/// A run that is not drawn (a bench, a plain `scen run`) builds no layers
/// and records no edges, and finds the same path with the same metrics as
/// a drawn one: drawing never changes the result.
#[test]
fn undrawn_runs_build_no_layers_and_find_the_same_path() {
    for kind in ["rrt", "rrt_connect", "rrt_star", "prm", "prm_star"] {
        for robot in ["rod", "dot"] {
            let s = scenario(kind, robot, "limit iterations 1500 simplify shortcut");
            let plan = &s.plans[0];
            let drawn_task = plan.task(&s);
            assert!(drawn_task.draw);
            let mut task = plan.task(&s);
            task.draw = false;
            let (drawn, undrawn) = (plan.settings.plan(&drawn_task), plan.settings.plan(&task));
            assert!(drawn.path.is_some(), "{kind} / {robot} found no path");
            assert!(!drawn.layers.is_empty(), "{kind} / {robot}");
            assert!(undrawn.layers.is_empty(), "{kind} / {robot}");
            assert_eq!(drawn.path, undrawn.path, "{kind} / {robot}");
            assert_eq!(drawn.cost, undrawn.cost, "{kind} / {robot}");
            let metrics = |o: &PlanOutcome| {
                let mut m = o.extra.clone();
                m.remove("simplify_ms");
                m
            };
            assert_eq!(metrics(&drawn), metrics(&undrawn), "{kind} / {robot}");
        }
    }
}

#[test]
fn same_seed_same_tree_and_path() {
    for kind in ["rrt", "rrt_connect", "rrt_star", "prm", "prm_star"] {
        let s = scenario(kind, "rod", "limit iterations 3000 simplify shortcut");
        let (a, b) = (run(&s), run(&s));
        assert!(a.path.is_some(), "{kind} found no path");
        assert_eq!(a.path, b.path, "{kind}");
        assert_eq!(a.layers, b.layers, "{kind}");
        let metrics = |o: &PlanOutcome| {
            let mut m = o.extra.clone();
            m.remove("simplify_ms");
            m
        };
        assert_eq!(metrics(&a), metrics(&b), "{kind}");
        // Another seed, another tree.
        let other = seeded(kind, "rod", "limit iterations 3000 simplify shortcut", 6);
        assert_ne!(run(&other).layers, a.layers, "{kind}");
    }
}

/// Every edge of the tree or roadmap drawn is a motion the validator
/// accepts, in the direction it was checked (from the older state).
#[test]
fn every_tree_and_roadmap_edge_passes_the_validator() {
    for kind in ["rrt", "rrt_star", "prm", "prm_star"] {
        for robot in ["rod", "dot"] {
            let s3 = scenario(kind, robot, "limit iterations 1500 stop limit");
            let shape = &s3.robots[s3.plans[0].robot].shape;
            let plan = &s3.plans[0];
            let task = plan.task(&s3);
            let settings = plan
                .settings
                .as_any()
                .downcast_ref::<crate::planners::sampling::Sampling>()
                .expect("sampling settings");
            let mut run = crate::planners::sampling::Run::new(settings, &task);
            let grown = match settings.algorithm {
                crate::planners::sampling::Algorithm::Prm
                | crate::planners::sampling::Algorithm::PrmStar => {
                    crate::planners::sampling::prm::grow(&mut run)
                }
                _ => crate::planners::sampling::rrt::grow(&mut run),
            };
            assert!(!grown.drawn.is_empty(), "{kind} / {robot}: no edges");
            for e in &grown.drawn {
                assert!(
                    validate_path(&s3.world, shape, &[e.a, e.b], DEFAULT_TOLERANCE).is_ok(),
                    "{kind} / {robot}: the edge {:?} → {:?} fails the validator",
                    e.a,
                    e.b
                );
            }
        }
    }
}

#[test]
fn rrt_star_cost_never_rises_with_more_iterations() {
    let mut last = f64::INFINITY;
    for n in [300, 600, 1200, 2400, 4800] {
        let s = scenario("rrt_star", "dot", &format!("limit iterations {n}"));
        let out = run(&s);
        let cost = out.cost.expect("a path");
        assert!(cost <= last + 1e-9, "{n} iterations: {cost} > {last}");
        last = cost;
    }
}

#[test]
fn simplified_paths_are_valid_and_no_longer() {
    for how in ["shortcut", "smooth"] {
        let s = scenario("rrt_connect", "rod", &format!("simplify {how}"));
        let out = run(&s);
        let path = out.path.expect("a path");
        let shape = &s.robots[s.plans[0].robot].shape;
        assert!(validate_path(&s.world, shape, &path, DEFAULT_TOLERANCE).is_ok());
        let raw = out.extra["raw_length"].as_f64();
        assert!(
            crate::geometry::path::path_length(&path) <= raw + 1e-9,
            "{how}"
        );
        assert_eq!(path[0], s.plans[0].params.start);
        assert_eq!(path.last().copied(), s.plans[0].params.goal);
    }
}

#[test]
fn a_limit_time_run_is_noted() {
    let s = scenario("prm", "dot", "limit time 10s");
    let out = run(&s);
    assert_noted(&out, "machine", "");
}

/// PRM's query (A* through the search core) against petgraph's Dijkstra on
/// random roadmaps.
/// In a world of 1e9 (a fuzzed scenario) PRM connects the start and the
/// goal through states 1e8 apart: rotating motions the validator would cut
/// into ~1e10 sub-steps. Such a path is not returned (a note says why), so
/// that the run ends in the plan's time and never reports an unchecked
/// path; its own motions were checked by the motion checker, which
/// bisects.
#[test]
fn paths_too_long_to_validate_are_not_returned() {
    let s = load_text(
        "world {
  bounds (-1e9, 0) (20, 30)
  rect L (0, 14.5) (9.2, 15.5)
  rect R (10.8, 14.5) (20, 15.5)
}
robot rod polygon [(0, 0), (8, 0), (8, 1), (0, 1)]
plan p prm rod { start (4, 4, 0deg) goal (4, 24, 0deg) seed 1 limit iterations 2000 }
",
    );
    let out = run(&s);
    assert!(out.path.is_none() && out.cost.is_none());
    assert_noted(&out, "sub-steps to validate", "");
}

/// A car whose turning radius is tiny for its world (fuzzer seed 777006:
/// `steer reeds_shepp 1e-300`): every steering length overflows, so every
/// step towards a sample goes nowhere. No planner adds a state that
/// repeats its parent (RRT-Connect's connection used to add the same state
/// until the cap of states, past its time limit) and each says why nothing
/// was found.
#[test]
fn cars_too_small_for_the_world_add_no_motion_and_say_why() {
    for kind in ["rrt", "rrt_connect", "rrt_star", "prm", "prm_star"] {
        let s = load_text(&format!(
            "world {{ bounds (0, 0) (30, 12) }}
robot car polygon [(-1, -0.9), (3.5, -0.9), (3.5, 0.9), (-1, 0.9)] steer reeds_shepp 1e-300
plan p {kind} car {{ start (2, 7, 0deg) goal (11.5, 2.2, 0deg) seed 1 limit iterations 500 }}
"
        ));
        let out = run(&s);
        assert!(out.path.is_none(), "{kind}");
        let number = |name: &str| match out.extra.get(name) {
            Some(crate::contract::MetricValue::Num(v)) => *v,
            other => panic!("{kind}: {name} = {other:?}"),
        };
        assert_eq!(number("graph_edges"), 0.0, "{kind}");
        if kind.starts_with("rrt") {
            // The roots only: every step went nowhere.
            let roots = if kind == "rrt_connect" { 2.0 } else { 1.0 };
            assert_eq!(number("graph_states"), roots, "{kind}");
        }
        assert_noted(&out, "turning radii", kind);
    }
}

/// RRT-Connect's greedy connection reads the clock as it steps: across a
/// world 1e9 wide with a range of 1e-3 it would need ~1e12 steps (and stop
/// only at the cap of states, seconds later), so the run ends at its time
/// limit, inside the connection.
#[test]
fn a_long_connection_stops_at_the_time_limit() {
    let s = load_text(
        "world { bounds (0, 0) (1e9, 10) }
robot dot point
plan p rrt_connect dot { start (1, 5) goal (999999999, 5) range 0.001 seed 1 limit time 0.2s }
",
    );
    let out = run(&s);
    assert!(out.path.is_none());
    assert_noted(&out, "the time limit was reached without a path", "");
}

/// `limit time` covers `simplify`: with the time already up, the path comes
/// back as it went in, and the run is told so; with time left (or no limit)
/// the same path is simplified.
#[test]
fn simplify_stops_at_the_time_limit() {
    let s = scenario("rrt", "dot", "simplify smooth");
    let plan = &s.plans[0];
    let settings = plan
        .settings
        .as_any()
        .downcast_ref::<crate::planners::sampling::Sampling>()
        .expect("sampling settings");
    // A zigzag in the free lower left of the room (x up to 10.75).
    let path: Vec<Config> = (0..40)
        .map(|i| {
            Config::new(
                1.0 + 0.25 * i as f64,
                if i % 2 == 0 { 2.0 } else { 3.0 },
                0.0,
            )
        })
        .collect();
    let mut task = plan.task(&s);
    task.limits.time = Some(0.0);
    let mut run = crate::planners::sampling::Run::new(settings, &task);
    let (kept, stopped) =
        crate::planners::sampling::simplify::simplify(&mut run, path.clone(), true);
    assert!(stopped);
    assert_eq!(kept, path);
    let task = plan.task(&s);
    let mut run = crate::planners::sampling::Run::new(settings, &task);
    let (simplified, stopped) =
        crate::planners::sampling::simplify::simplify(&mut run, path.clone(), false);
    assert!(!stopped);
    assert!(simplified.len() < path.len(), "{}", simplified.len());
}
