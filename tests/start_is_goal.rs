//! SPEC 3: "A start equal to the goal is found at once, with a path of that
//! one configuration, by every planner." Driven by the registry, so a new
//! planner is covered by its registry line: every planner, for every robot
//! kind it declares, on a lattice point and off it (where a lattice planner
//! snaps), and for a rotating robot at a θ that is no lattice layer.
//!
//! `coverage` has no goal to reach (SPEC 3.5: `goal` is not used): its path
//! is the closed tour from the start whatever the goal says, and this test
//! checks just that (found, valid, back at the start, the same tour as
//! without a goal).

mod common;

use std::collections::BTreeMap;

use common::TempDir;
use common::planner_cases::{block_world, required, robot};
use scen::contract::MetricValue;
use scen::contract::Planner;
use scen::contract::schema::RobotKind;
use scen::geometry::validator::{DEFAULT_TOLERANCE, validate_path};
use scen::planners::registry::PLANNERS;
use scen::{Scenario, run_scenario};

/// 16 × 16 unit cells with a block, as in the contract test.
fn world(planner: &Planner) -> String {
    block_world(planner, 16, 3..6, 9..12)
}

/// A plan whose start and goal are both `pose` (written as in a file).
fn scenario(planner: &Planner, kind: RobotKind, pose: &str, goal: bool) -> Scenario {
    let goal = if goal {
        format!("goal {pose}")
    } else {
        String::new()
    };
    let text = format!(
        "scenario \"start is goal\"\n{world}robot r {robot}\nplan p {kind} r {{\n  start {pose} {goal} seed 3\n  {req}\n  {budget}\n}}\n",
        kind = planner.kind,
        world = world(planner),
        robot = robot(kind),
        req = required(planner).join(" "),
        // A planner that runs to its iteration limit by default must not
        // need it here; a small one keeps a failure quick.
        budget = if planner.limits.contains(&"iterations") {
            "limit iterations 2000"
        } else {
            ""
        },
    );
    let dir = TempDir::new("start-is-goal");
    let file = dir.path().join("p.scen");
    std::fs::write(&file, &text).expect("write the scenario");
    scen::load(&file).unwrap_or_else(|f| {
        let codes: Vec<String> = f.diags.iter().map(|d| d.code.to_string()).collect();
        panic!("{} / {kind:?}: {codes:?}\n{text}", planner.kind)
    })
}

/// Poses to try for a robot kind: a lattice point (cell centres of the
/// default `cell 1`), a point between lattice points, and for a polygon a
/// θ that is no layer of the default lattice.
fn poses(kind: RobotKind) -> Vec<&'static str> {
    let mut out = vec!["(1.5, 1.5)", "(1.3, 1.7)"];
    if kind == RobotKind::Polygon {
        out.push("(1.3, 1.7, 17deg)");
    }
    out
}

fn num(m: &BTreeMap<String, MetricValue>, name: &str) -> f64 {
    m.get(name).map_or(f64::NAN, |v| v.as_f64())
}

#[test]
fn every_planner_finds_a_start_equal_to_its_goal_at_once() {
    let mut problems = Vec::new();
    for planner in PLANNERS.iter().filter(|p| p.needs_goal) {
        for &kind in planner.robots.iter().filter(|&&k| k != RobotKind::Team) {
            for pose in poses(kind) {
                let label = format!("{} / {kind:?} at {pose}", planner.kind);
                let sc = scenario(planner, kind, pose, true);
                let start = sc.plans[0].params.start;
                let report = run_scenario(sc.clone(), &[]);
                let run = &report.plans[0];
                let m = &run.metrics;
                let declared: Vec<&str> = {
                    let mut v: Vec<&str> = planner.all_metrics().map(|m| m.name).collect();
                    v.sort_unstable();
                    v
                };
                let reported: Vec<&str> = m.keys().map(String::as_str).collect();
                if reported != declared {
                    problems.push(format!(
                        "{label}: metrics {reported:?}, declared {declared:?}"
                    ));
                }
                let Some(path) = &run.outcome.path else {
                    problems.push(format!(
                        "{label}: not found (gave_up {}, notes {:?})",
                        run.outcome.gave_up, run.outcome.notes
                    ));
                    continue;
                };
                if path.as_slice() != [start] {
                    problems.push(format!("{label}: the path is {path:?}, not [start]"));
                }
                let robot = &sc.robots[0].shape;
                if let Err(e) = validate_path(&sc.world, robot, path, DEFAULT_TOLERANCE) {
                    problems.push(format!("{label}: fails the validator: {e:?}"));
                }
                for flag in ["found", "collision_free", "reaches_goal"] {
                    if m.get(flag) != Some(&MetricValue::Bool(true)) {
                        problems.push(format!("{label}: {flag} is {:?}", m.get(flag)));
                    }
                }
                if m.get("gave_up") != Some(&MetricValue::Bool(false)) {
                    problems.push(format!("{label}: gave_up is {:?}", m.get("gave_up")));
                }
                // At once: nothing searched, sampled or walked.
                for (metric, want) in [
                    ("length", 0.0),
                    ("cost", 0.0),
                    ("nodes", 1.0),
                    ("expanded", 0.0),
                ] {
                    if num(m, metric) != want {
                        problems.push(format!("{label}: {metric} = {}", num(m, metric)));
                    }
                }
            }
        }
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}

/// Planners without a goal (`coverage`): a goal equal to the start changes
/// nothing; the path is the closed tour from the start.
#[test]
fn planners_without_a_goal_ignore_one_equal_to_the_start() {
    let mut checked = 0;
    for planner in PLANNERS.iter().filter(|p| !p.needs_goal) {
        for &kind in planner.robots.iter().filter(|&&k| k != RobotKind::Team) {
            let label = format!("{} / {kind:?}", planner.kind);
            let with = scenario(planner, kind, "(1.5, 1.5)", true);
            let without = scenario(planner, kind, "(1.5, 1.5)", false);
            let a = run_scenario(with.clone(), &[]);
            let b = run_scenario(without, &[]);
            let path = a.plans[0].outcome.path.as_ref().expect(&label);
            assert_eq!(Some(path), b.plans[0].outcome.path.as_ref(), "{label}");
            assert!(path.len() > 1, "{label}: a tour, not one configuration");
            assert_eq!(path.first(), path.last(), "{label}: a closed tour");
            assert_eq!(path.first(), Some(&with.plans[0].params.start), "{label}");
            let robot = &with.robots[0].shape;
            validate_path(&with.world, robot, path, DEFAULT_TOLERANCE)
                .unwrap_or_else(|e| panic!("{label}: {e:?}"));
            let m = &a.plans[0].metrics;
            assert_eq!(
                m.get("reaches_goal"),
                Some(&MetricValue::Bool(true)),
                "{label}"
            );
            checked += 1;
        }
    }
    assert!(
        checked > 0,
        "no planner without a goal: the test is vacuous"
    );
}

/// "At once": before any set-up, so even a plan whose time is already up
/// finds it.
#[test]
fn a_start_equal_to_the_goal_needs_no_time() {
    let mut problems = Vec::new();
    for planner in PLANNERS.iter().filter(|p| p.needs_goal) {
        for &kind in planner.robots.iter().filter(|&&k| k != RobotKind::Team) {
            let sc = scenario(planner, kind, "(1.3, 1.7)", true);
            let plan = &sc.plans[0];
            let mut task = plan.task(&sc);
            task.limits.time = Some(0.0);
            let out = plan.settings.plan(&task);
            if out.path.as_deref() != Some(&[task.start][..]) || out.gave_up {
                problems.push(format!(
                    "{} / {kind:?}: path {:?}, gave_up {}, notes {:?}",
                    planner.kind, out.path, out.gave_up, out.notes
                ));
            }
        }
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}
