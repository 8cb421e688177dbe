//! The planner contract, driven by the registry: every planner, for every
//! robot kind it declares, on two small worlds (16 × 16 cells of a grid, so
//! that `on`-style planners have a grid to work on; the same cells as rects
//! for a planner that does not plan among grids): [`World::Open`], with
//! nothing in the way, and [`World::Detour`], with a block across the
//! straight line from the start to the goal:
//! - the metrics it reports are exactly the common ones of SPEC 3 and the
//!   ones its schema declares, with the declared types;
//! - a path it finds starts at `start`, ends at `goal` (for planners that
//!   have one) and passes the independent validator; in the open world it
//!   finds one for every robot kind it declares, so that these checks are
//!   never vacuous (a planner too simple to go round the block still has
//!   its paths checked there);
//! - the same input and seed give byte-identical JSON (timings aside);
//! - its limits are honoured: a `limit expansions|steps|iterations` below
//!   what a run counts stops it (no path, `gave_up`, at most that many
//!   counted), `limit cells` refuses a lattice at analysis, `limit time`
//!   ends the run;
//! - robots it does not plan for are refused at analysis.
//!
//! A new planner gets all of this by its registry line. What the test
//! cannot exercise fails it with a message rather than passing unchecked:
//! a required parameter of a kind it cannot fill, no path in the open
//! world, a counted limit that a run never reaches more than once.

mod common;

use std::collections::BTreeMap;

use common::TempDir;
use common::planner_cases::{cell_world, required, robot};
use scen::contract::MetricValue;
use scen::contract::Planner;
use scen::contract::schema::{DefaultValue, MetricType, RobotKind};
use scen::geometry::car::validate_car_path;
use scen::geometry::validator::{DEFAULT_TOLERANCE, Validator, validate_path};
use scen::planners::registry::PLANNERS;
use scen::report::json::to_json;
use scen::{Scenario, run_scenario};

/// The worlds of the contract: 16 × 16 unit cells of a grid `G`.
#[derive(Clone, Copy, Debug, PartialEq)]
enum World {
    /// Nothing in the way.
    Open,
    /// A 3 × 3 block across the straight line from [`START`] to [`GOAL`]
    /// (rows 3 to 5 from the top, columns 9 to 11).
    Detour,
}

const WORLDS: [World; 2] = [World::Open, World::Detour];

fn world(planner: &Planner, world: World) -> String {
    let rows: Vec<String> = (0..16)
        .map(|row| {
            (0..16)
                .map(|col| {
                    let blocked = (3..6).contains(&row) && (9..12).contains(&col);
                    if blocked && world == World::Detour {
                        '#'
                    } else {
                        '.'
                    }
                })
                .collect()
        })
        .collect();
    cell_world(planner, &rows)
}

const START: (f64, f64) = (1.5, 1.5);
const GOAL: (f64, f64) = (13.5, 14.5);

fn scenario_text(planner: &Planner, kind: RobotKind, place: World, extra: &str) -> String {
    let goal = if planner.needs_goal {
        format!("goal ({}, {})", GOAL.0, GOAL.1)
    } else {
        String::new()
    };
    format!(
        "scenario \"contract {kind}\"\n{world}robot r {robot}\nplan p {kind} r {{\n  start ({}, {}) {goal} seed 3\n  {}\n  {extra}\n}}\n",
        START.0,
        START.1,
        required(planner).join(" "),
        kind = planner.kind,
        world = world(planner, place),
        robot = robot(kind),
    )
}

/// Loads a scenario written to a temporary file; the diagnostics' codes on
/// failure.
fn load(text: &str) -> Result<Scenario, Vec<String>> {
    let dir = TempDir::new("contract");
    let file = dir.path().join("contract.scen");
    std::fs::write(&file, text).expect("write the scenario");
    scen::load(&file).map_err(|f| f.diags.iter().map(|d| d.code.to_string()).collect())
}

fn loaded(planner: &Planner, kind: RobotKind, place: World, extra: &str) -> Scenario {
    let text = scenario_text(planner, kind, place, extra);
    load(&text).unwrap_or_else(|codes| {
        panic!("{} / {kind:?} / {place:?}: {codes:?}\n{text}", planner.kind)
    })
}

/// The JSON document without its timings.
fn json(scenario: &Scenario) -> String {
    let report = run_scenario(scenario.clone(), &[]);
    let mut doc = to_json(&report);
    for plan in doc["plans"].as_object_mut().expect("plans").values_mut() {
        // Timings: `time_ms` and the other `*_ms` metrics.
        plan["metrics"]
            .as_object_mut()
            .expect("metrics")
            .retain(|k, _| !k.ends_with("_ms"));
    }
    doc.to_string()
}

/// What the contract runs a planner with: its defaults, but for a planner
/// that counts iterations at most 5 000 of them — the asymptotically
/// optimal ones run to their limit by default (200 000 iterations, a minute
/// on this small world), and the contract is about what a run reports, not
/// about how far it converges.
fn budget(planner: &Planner) -> &'static str {
    if planner.limits.contains(&"iterations") {
        "limit iterations 5000"
    } else {
        ""
    }
}

#[test]
fn the_detour_world_blocks_the_straight_line() {
    // Else a planner that only tries the straight line would pass the
    // detour case by finding it.
    let astar = scen::planners::registry::planner("astar").expect("astar");
    for (place, blocked) in [(World::Open, false), (World::Detour, true)] {
        let scenario = loaded(astar, RobotKind::Point, place, "");
        let params = &scenario.plans[0].params;
        let line = [params.start, params.goal.expect("a goal")];
        let robot = &scenario.robots[0].shape;
        let verdict = validate_path(&scenario.world, robot, &line, DEFAULT_TOLERANCE);
        assert_eq!(verdict.is_err(), blocked, "{place:?}: {verdict:?}");
    }
}

#[test]
fn every_planner_honours_its_contract() {
    let mut problems = Vec::new();
    let mut detours_found = 0;
    for planner in PLANNERS {
        for &kind in planner.robots.iter().filter(|&&k| k != RobotKind::Team) {
            for place in WORLDS {
                let label = format!("{} / {kind:?} / {place:?}", planner.kind);
                let scenario = loaded(planner, kind, place, budget(planner));
                let report = run_scenario(scenario.clone(), &[]);
                let run = &report.plans[0];

                // Exactly the declared metrics, with their types.
                let declared: BTreeMap<&str, MetricType> =
                    planner.all_metrics().map(|m| (m.name, m.ty)).collect();
                let reported: Vec<&str> = run.metrics.keys().map(String::as_str).collect();
                let expected: Vec<&str> = declared.keys().copied().collect();
                if reported != expected {
                    problems.push(format!(
                        "{label}: metrics {reported:?}, declared {expected:?}"
                    ));
                }
                for (name, value) in &run.metrics {
                    let ok = matches!(
                        (declared.get(name.as_str()), value),
                        (Some(MetricType::Bool), MetricValue::Bool(_))
                            | (Some(MetricType::Num), MetricValue::Num(_))
                    );
                    if !ok {
                        problems.push(format!(
                            "{label}: metric `{name}` = {value:?} has the wrong type"
                        ));
                    }
                }

                // A found path: from start to goal, valid.
                if let Some(path) = &run.outcome.path {
                    detours_found += usize::from(place == World::Detour);
                    let robot = &scenario.robots[0].shape;
                    let first = path.first().map(|c| (c.x, c.y));
                    if first != Some(START) {
                        problems.push(format!("{label}: the path starts at {first:?}"));
                    }
                    let last = path.last().map(|c| (c.x, c.y));
                    if planner.needs_goal && last != Some(GOAL) {
                        problems.push(format!("{label}: the path ends at {last:?}"));
                    }
                    // A car's path is its segments (SPEC 3.0).
                    let verdict = match &run.outcome.car {
                        Some(car) => validate_car_path(
                            &Validator::new(&scenario.world),
                            robot,
                            car,
                            scenario.plans[0].params.goal,
                            DEFAULT_TOLERANCE,
                        ),
                        None if kind == RobotKind::Car => {
                            problems.push(format!("{label}: a car's path without segments"));
                            Ok(())
                        }
                        None => validate_path(&scenario.world, robot, path, DEFAULT_TOLERANCE),
                    };
                    if let Err(e) = verdict {
                        problems.push(format!("{label}: the path fails the validator: {e:?}"));
                    }
                    if run.metrics.get("collision_free") != Some(&MetricValue::Bool(true)) {
                        problems.push(format!("{label}: a valid path without collision_free"));
                    }
                } else if place == World::Open {
                    problems.push(format!(
                        "{label}: no path with nothing in the way (gave_up {}, notes {:?}): the path checks would be vacuous",
                        run.outcome.gave_up, run.outcome.notes
                    ));
                }

                // Deterministic: the same input gives the same bytes.
                let (a, b) = (json(&scenario), json(&scenario));
                if a != b {
                    problems.push(format!("{label}: two runs differ:\n{a}\n{b}"));
                }
            }
        }
    }
    if detours_found == 0 {
        problems.push("no planner found a path round the block: the validator's check of paths near obstacles is vacuous".into());
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}

/// The metric that shows what `limit KIND` counts.
fn counted_metric(planner: &Planner, counted: &'static str) -> &'static str {
    match counted {
        "expansions" => "expanded",
        other if planner.metric(other).is_some() => other,
        _ => "expanded",
    }
}

fn metric(metrics: &BTreeMap<String, MetricValue>, name: &str) -> f64 {
    metrics.get(name).map_or(f64::NAN, |v| v.as_f64())
}

#[test]
fn every_planner_honours_its_limits() {
    let mut problems = Vec::new();
    for planner in PLANNERS.iter().filter(|p| !p.plans_teams()) {
        let kind = planner.robots[0];
        for &limit in planner.limits {
            let label = format!("{} / limit {limit}", planner.kind);
            match limit {
                "time" => {
                    // The run ends (no hang) and a path found in time is
                    // still a path, else the run says it gave up.
                    let scenario = loaded(planner, kind, World::Open, "limit time 1ms");
                    let report = run_scenario(scenario, &[]);
                    let run = &report.plans[0];
                    if run.outcome.path.is_none() && !run.outcome.gave_up {
                        problems.push(format!("{label}: stopped without a path nor gave_up"));
                    }
                }
                "cells" => match load(&scenario_text(
                    planner,
                    kind,
                    World::Detour,
                    "limit cells 10",
                )) {
                    Err(codes)
                        if codes
                            .iter()
                            .any(|c| c == "scen::analyze::lattice_too_large") => {}
                    other => problems.push(format!(
                        "{label}: a 10-cell cap did not refuse the lattice: {:?}",
                        other.err()
                    )),
                },
                counted => {
                    // A cap below what a whole run counts, so that it
                    // must stop the run short of the goal.
                    let metric_name = counted_metric(planner, counted);
                    let whole =
                        run_scenario(loaded(planner, kind, World::Detour, budget(planner)), &[]);
                    let used = metric(&whole.plans[0].metrics, metric_name);
                    if used.is_nan() || used < 2.0 {
                        problems.push(format!(
                            "{label}: a whole run on the detour world counts {used} `{metric_name}`: no cap can stop it short (teach the contract a harder case)"
                        ));
                        continue;
                    }
                    let cap = (used - 1.0).min(3.0);
                    let scenario = loaded(
                        planner,
                        kind,
                        World::Detour,
                        &format!("limit {counted} {cap}"),
                    );
                    let report = run_scenario(scenario, &[]);
                    let run = &report.plans[0];
                    if run.outcome.path.is_some() || !run.outcome.gave_up {
                        problems.push(format!(
                            "{label}: {cap} (of the {used} a whole run counts) did not stop it: found {}, gave_up {}",
                            run.outcome.path.is_some(),
                            run.outcome.gave_up
                        ));
                    }
                    // What the limit counts stays within it.
                    let n = metric(&run.metrics, metric_name);
                    if n.is_nan() || n > cap {
                        problems.push(format!(
                            "{label}: `{metric_name}` = {n} after `limit {counted} {cap}`"
                        ));
                    }
                    // Stopped short: `collision_free` says whether the
                    // motion executed so far, if any, passed the validator
                    // (SPEC 3).
                    let executed = &run.outcome.trajectory;
                    let robot = &report.scenario.robots[0].shape;
                    let world = &report.scenario.world;
                    let valid = !executed.is_empty()
                        && validate_path(world, robot, executed, DEFAULT_TOLERANCE).is_ok();
                    if run.metrics.get("collision_free") != Some(&MetricValue::Bool(valid)) {
                        problems.push(format!(
                            "{label}: collision_free {:?}, the executed motion of {} poses {}",
                            run.metrics.get("collision_free"),
                            executed.len(),
                            if valid { "passes" } else { "does not pass" }
                        ));
                    }
                }
            }
        }
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}

#[test]
fn robots_a_planner_does_not_declare_are_refused() {
    let mut problems = Vec::new();
    for planner in PLANNERS {
        for kind in [
            RobotKind::Point,
            RobotKind::Disk,
            RobotKind::Polygon,
            RobotKind::Car,
        ] {
            if planner.plans_for(kind) {
                continue;
            }
            match load(&scenario_text(planner, kind, World::Open, "")) {
                Err(codes) if codes.iter().any(|c| c == "scen::analyze::robot_kind") => {}
                other => problems.push(format!(
                    "{} / {kind:?}: not refused as `robot_kind`: {:?}",
                    planner.kind,
                    other.err()
                )),
            }
        }
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}

/// A numeric default is written once, in the schema, with the form a user
/// would type (`10ms`, `0.5deg`): written in a plan, that form reads as the
/// default's value, for every planner's parameters and every `drive` model's.
#[test]
fn written_defaults_read_as_their_values() {
    use scen::contract::ParamValue;
    use scen::contract::schema::DRIVE;
    let mut problems = Vec::new();
    for planner in PLANNERS.iter().filter(|p| !p.plans_teams()) {
        let numeric: Vec<(&str, f64, &str)> = planner
            .params
            .iter()
            .filter_map(|p| match p.default {
                DefaultValue::Num(x, written) => Some((p.key, x, written)),
                _ => None,
            })
            .collect();
        let given: Vec<String> = numeric.iter().map(|(k, _, w)| format!("{k} {w}")).collect();
        // Each planner with one model, in turn.
        let model = &DRIVE[planner.kind.len() % DRIVE.len()];
        let drive: Vec<String> = model
            .params
            .iter()
            .filter(|p| matches!(p.default, DefaultValue::Num(..)))
            .map(|p| format!("{} {}", p.key, p.default.text()))
            .collect();
        let extra = format!(
            "{} drive {} {{ {} }}",
            given.join(" "),
            model.name,
            drive.join(" ")
        );
        let scenario = loaded(planner, planner.robots[0], World::Open, &extra);
        let values = &scenario.plans[0].params.values;
        for (key, x, written) in numeric {
            match values.get(key).map(|p| &p.value) {
                Some(ParamValue::Num(v)) if *v == x => {}
                other => problems.push(format!(
                    "{}.{key}: `{written}` reads as {other:?}, the default is {x}",
                    planner.kind
                )),
            }
        }
        let Some(ParamValue::Block(_, block)) = values.get("drive").map(|p| &p.value) else {
            problems.push(format!("{}: no drive block", planner.kind));
            continue;
        };
        for p in model.params {
            let DefaultValue::Num(x, written) = p.default else {
                continue;
            };
            match block.get(p.key).map(|p| &p.value) {
                Some(ParamValue::Num(v)) if (*v - x).abs() <= 1e-15 * x.abs() => {}
                other => problems.push(format!(
                    "drive {}.{}: `{written}` reads as {other:?}, the default is {x}",
                    model.name, p.key
                )),
            }
        }
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}
