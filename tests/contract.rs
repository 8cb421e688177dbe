//! The planner contract, driven by the registry: every planner, for every
//! robot kind it declares, on a small world (a grid with a block, so that
//! `on`-style planners have a grid to work on):
//! - the metrics it reports are exactly the common ones of SPEC 3 and the
//!   ones its schema declares, with the declared types;
//! - a path it finds starts at `start`, ends at `goal` (for planners that
//!   have one) and passes the independent validator;
//! - the same input and seed give byte-identical JSON (timings aside);
//! - its limits are honoured: a tiny `limit expansions|steps|iterations`
//!   stops it (no path, `gave_up`, at most that many counted), `limit cells`
//!   refuses a lattice at analysis, `limit time` ends the run;
//! - robots it does not plan for are refused at analysis.
//!
//! A new planner gets all of this by its registry line; a required
//! parameter of a kind this test cannot fill makes the test say so.

mod common;

use std::collections::BTreeMap;

use common::TempDir;
use scen::contract::MetricValue;
use scen::contract::Planner;
use scen::contract::schema::{COMMON_METRICS, DefaultValue, MetricType, RobotKind, ValueSpec};
use scen::geometry::validator::{DEFAULT_TOLERANCE, validate_path};
use scen::planners::registry::PLANNERS;
use scen::report::json::to_json;
use scen::{Scenario, run_scenario};

/// 16 × 16 unit cells; a 3 × 3 block off the diagonal between the start
/// and the goal.
const WORLD: &str = r#"world {
  bounds (0, 0) (16, 16)
  grid G cell 1 origin (0, 0) {
    "................"
    "................"
    "................"
    ".........###...."
    ".........###...."
    ".........###...."
    "................"
    "................"
    "................"
    "................"
    "................"
    "................"
    "................"
    "................"
    "................"
    "................"
  }
}
"#;

const START: (f64, f64) = (1.5, 1.5);
const GOAL: (f64, f64) = (13.5, 14.5);

fn robot(kind: RobotKind) -> &'static str {
    match kind {
        RobotKind::Point => "point",
        RobotKind::Disk => "disk 0.4",
        // Centred on its frame origin, so that it fits a unit D-cell too.
        RobotKind::Polygon => "polygon [(-0.4, -0.3), (0.4, -0.3), (0.4, 0.3), (-0.4, 0.3)]",
    }
}

/// The plan's required parameters, filled for this world.
fn required(planner: &Planner) -> Vec<String> {
    planner
        .params
        .iter()
        .filter(|p| p.default == DefaultValue::None)
        .map(|p| match p.value {
            ValueSpec::ObstacleName => format!("{} G", p.key),
            other => panic!(
                "the contract test cannot fill the required `{}` of `{}` ({other:?}): teach it",
                p.key, planner.kind
            ),
        })
        .collect()
}

fn scenario_text(planner: &Planner, kind: RobotKind, extra: &str) -> String {
    let goal = if planner.needs_goal {
        format!("goal ({}, {})", GOAL.0, GOAL.1)
    } else {
        String::new()
    };
    format!(
        "scenario \"contract {kind}\"\n{WORLD}robot r {robot}\nplan p {kind} r {{\n  start ({}, {}) {goal} seed 3\n  {}\n  {extra}\n}}\n",
        START.0,
        START.1,
        required(planner).join(" "),
        kind = planner.kind,
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

fn loaded(planner: &Planner, kind: RobotKind, extra: &str) -> Scenario {
    let text = scenario_text(planner, kind, extra);
    load(&text).unwrap_or_else(|codes| panic!("{} / {kind:?}: {codes:?}\n{text}", planner.kind))
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
fn every_planner_honours_its_contract() {
    let mut problems = Vec::new();
    let mut found_any: BTreeMap<&str, bool> = BTreeMap::new();
    for planner in PLANNERS {
        for &kind in planner.robots {
            let label = format!("{} / {kind:?}", planner.kind);
            let scenario = loaded(planner, kind, budget(planner));
            let report = run_scenario(scenario.clone(), &[]);
            let run = &report.plans[0];

            // Exactly the declared metrics, with their types.
            let declared: BTreeMap<&str, MetricType> = COMMON_METRICS
                .iter()
                .chain(planner.metrics)
                .map(|m| (m.name, m.ty))
                .collect();
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
                *found_any.entry(planner.kind).or_default() = true;
                let robot = &scenario.robots[0].shape;
                let first = path.first().map(|c| (c.x, c.y));
                if first != Some(START) {
                    problems.push(format!("{label}: the path starts at {first:?}"));
                }
                let last = path.last().map(|c| (c.x, c.y));
                if planner.needs_goal && last != Some(GOAL) {
                    problems.push(format!("{label}: the path ends at {last:?}"));
                }
                if let Err(e) = validate_path(&scenario.world, robot, path, DEFAULT_TOLERANCE) {
                    problems.push(format!("{label}: the path fails the validator: {e:?}"));
                }
                if run.metrics.get("collision_free") != Some(&MetricValue::Bool(true)) {
                    problems.push(format!("{label}: a valid path without collision_free"));
                }
            } else {
                found_any.entry(planner.kind).or_default();
            }

            // Deterministic: the same input gives the same bytes.
            let (a, b) = (json(&scenario), json(&scenario));
            if a != b {
                problems.push(format!("{label}: two runs differ:\n{a}\n{b}"));
            }
        }
    }
    for (kind, found) in found_any {
        if !found {
            problems.push(format!(
                "{kind}: no robot kind found a path, the contract is vacuous"
            ));
        }
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}

#[test]
fn every_planner_honours_its_limits() {
    let mut problems = Vec::new();
    for planner in PLANNERS {
        let kind = planner.robots[0];
        for &limit in planner.limits {
            let label = format!("{} / limit {limit}", planner.kind);
            match limit {
                "time" => {
                    // The run ends (no hang) and a path found in time is
                    // still a path, else the run says it gave up.
                    let scenario = loaded(planner, kind, "limit time 1ms");
                    let report = run_scenario(scenario, &[]);
                    let run = &report.plans[0];
                    if run.outcome.path.is_none() && !run.outcome.gave_up {
                        problems.push(format!("{label}: stopped without a path nor gave_up"));
                    }
                }
                "cells" => match load(&scenario_text(planner, kind, "limit cells 10")) {
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
                    let scenario = loaded(planner, kind, &format!("limit {counted} 3"));
                    let report = run_scenario(scenario, &[]);
                    let run = &report.plans[0];
                    if run.outcome.path.is_some() || !run.outcome.gave_up {
                        problems.push(format!(
                            "{label}: 3 was not enough for this world, yet: found {}, gave_up {}",
                            run.outcome.path.is_some(),
                            run.outcome.gave_up
                        ));
                    }
                    // What the limit counts stays within it.
                    let metric = match counted {
                        "expansions" => "expanded",
                        other if planner.metric(other).is_some() => other,
                        _ => "expanded",
                    };
                    let n = run.metrics.get(metric).map_or(f64::NAN, |v| v.as_f64());
                    if n.is_nan() || n > 3.0 {
                        problems.push(format!(
                            "{label}: `{metric}` = {n} after `limit {counted} 3`"
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
        for kind in [RobotKind::Point, RobotKind::Disk, RobotKind::Polygon] {
            if planner.plans_for(kind) {
                continue;
            }
            match load(&scenario_text(planner, kind, "")) {
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
/// default's value, for every planner's parameters and the `drive` block's.
#[test]
fn written_defaults_read_as_their_values() {
    use scen::contract::ParamValue;
    use scen::contract::schema::DRIVE_PARAMS;
    let mut problems = Vec::new();
    for planner in PLANNERS {
        let numeric: Vec<(&str, f64, &str)> = planner
            .params
            .iter()
            .filter_map(|p| match p.default {
                DefaultValue::Num(x, written) => Some((p.key, x, written)),
                _ => None,
            })
            .collect();
        let given: Vec<String> = numeric.iter().map(|(k, _, w)| format!("{k} {w}")).collect();
        let drive: Vec<String> = DRIVE_PARAMS
            .iter()
            .map(|p| format!("{} {}", p.key, p.default.text()))
            .collect();
        let extra = format!(
            "{} drive unicycle {{ {} }}",
            given.join(" "),
            drive.join(" ")
        );
        let scenario = loaded(planner, planner.robots[0], &extra);
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
        for p in DRIVE_PARAMS {
            let DefaultValue::Num(x, written) = p.default else {
                continue;
            };
            match block.get(p.key).map(|p| &p.value) {
                Some(ParamValue::Num(v)) if (*v - x).abs() <= 1e-15 * x.abs() => {}
                other => problems.push(format!(
                    "drive.{}: `{written}` reads as {other:?}, the default is {x}",
                    p.key
                )),
            }
        }
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}
