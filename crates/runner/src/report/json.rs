//! The JSON document of SPEC 5 (`scen run --json`).
//!
//! The document is built in a fixed order (top-level keys as in SPEC 5,
//! plans in declaration order) and holds nothing that varies between runs
//! except the timings (`time_ms`, and `simplify_ms` of the sampling
//! planners), so the same input gives the same bytes.
//! Object keys keep that order when serde_json's `preserve_order` feature
//! is on; without it serde_json sorts them.

use serde_json::{Map, Number, Value};

use crate::contract::{MetricValue, Metrics};
use crate::geometry::Config;
use crate::run::{CheckOutcome, PlanRun, RunReport};
use crate::scenario::{Plan, Scenario};

/// Whole numbers below this magnitude are exact in an f64 and print as
/// JSON integers (`"expanded": 5786`, not `5786.0`).
const EXACT_INTEGER_LIMIT: f64 = 9_007_199_254_740_992.0; // 2^53

/// At most this many poses of a driven trajectory are listed (evenly
/// spread, the first and the last included).
pub const DRIVE_SAMPLES: usize = 10_000;

/// The SPEC 5 document for one scenario run.
pub fn to_json(report: &RunReport) -> Value {
    let scenario = &report.scenario;
    let mut runs: Vec<&PlanRun> = report.plans.iter().collect();
    runs.sort_by_key(|run| run.plan);
    let plans: Map<String, Value> = runs
        .into_iter()
        .filter_map(|run| {
            let plan = scenario.plans.get(run.plan)?;
            Some((plan.name.clone(), plan_json(scenario, plan, run)))
        })
        .collect();
    let checks = report
        .checks
        .iter()
        .filter_map(|outcome| check_json(scenario, outcome))
        .collect();

    let mut doc = Map::new();
    doc.insert("file".into(), scenario.file.display().to_string().into());
    doc.insert("scenario".into(), scenario.title.clone().into());
    // A family's sample (SPEC 2.8): its number and drawn values.
    if let Some(drawn) = &scenario.family {
        doc.insert("sample".into(), drawn.sample.into());
        doc.insert("family_seed".into(), drawn.family_seed.into());
        let params: Map<String, Value> = drawn
            .params
            .iter()
            .map(|(name, x)| (name.clone(), float_json(*x)))
            .collect();
        doc.insert("params".into(), Value::Object(params));
    }
    doc.insert("plans".into(), Value::Object(plans));
    doc.insert("checks".into(), Value::Array(checks));
    doc.insert("passed".into(), report.passed().into());
    doc.insert("failed".into(), report.failed().into());
    // The checks `--plan` left out (only when there are some).
    if !report.skipped.is_empty() {
        let skipped: Vec<Value> = report
            .skipped
            .iter()
            .map(|&c| {
                let check = &scenario.checks[c];
                serde_json::json!({"line": check.line, "expr": check.text})
            })
            .collect();
        doc.insert("skipped".into(), Value::Array(skipped));
    }
    Value::Object(doc)
}

fn plan_json(scenario: &Scenario, plan: &Plan, run: &PlanRun) -> Value {
    let robot = scenario.robots.get(plan.robot);
    // A car's heading matters whatever its shape.
    let rotates = robot.is_some_and(|r| r.shape.rotates() || r.steering.is_some());
    let path = match &run.outcome.path {
        Some(path) => Value::Array(path.iter().map(|&c| config_json(c, rotates)).collect()),
        None => Value::Null,
    };
    let mut obj = Map::new();
    obj.insert("kind".into(), plan.kind().into());
    obj.insert("robot".into(), robot.map(|r| r.name.clone()).into());
    obj.insert("metrics".into(), metrics_json(&run.metrics));
    // A team's plan (SPEC 2.10): each agent's path, one point per step,
    // instead of one robot's path (`null` when none was found).
    if let Some(team) = plan.team(scenario) {
        // Under grid semantics a point per step; a continuous team's
        // agents (`prioritized`) have trajectories `[x, y, θ, t]`.
        let times = run.outcome.agent_times.as_deref();
        let agents = match &run.outcome.agents {
            Some(paths) => Value::Array(
                team.iter()
                    .zip(paths)
                    .enumerate()
                    .map(|(k, (a, path))| match times.and_then(|t| t.get(k)) {
                        Some(t) => {
                            let points: Vec<Value> = path
                                .iter()
                                .zip(t)
                                .map(|(p, &t)| {
                                    serde_json::json!([
                                        float_json(p.x),
                                        float_json(p.y),
                                        0.0,
                                        float_json(t)
                                    ])
                                })
                                .collect();
                            serde_json::json!({"name": a.name, "trajectory": points})
                        }
                        None => {
                            let points: Vec<Value> = path
                                .iter()
                                .map(|p| serde_json::json!([float_json(p.x), float_json(p.y)]))
                                .collect();
                            serde_json::json!({"name": a.name, "path": points})
                        }
                    })
                    .collect(),
            ),
            None => Value::Null,
        };
        obj.insert("agents".into(), agents);
        return Value::Object(obj);
    }
    obj.insert("path".into(), path);
    // A car robot's path as segments (SPEC §5), what the validator checks.
    if robot.is_some_and(|r| r.steering.is_some()) {
        let segments = match (&run.outcome.car, &run.outcome.path) {
            (Some(car), Some(_)) => Value::Array(
                car.segments
                    .iter()
                    .map(|s| serde_json::json!([s.turn.letter(), float_json(s.length)]))
                    .collect(),
            ),
            _ => Value::Null,
        };
        obj.insert("segments".into(), segments);
    }
    // A time-aware plan's trajectory (SPEC 2.9): `[x, y, θ, t]` per point
    // (no key without one: `"trajectory"` alone, beside no path, is the
    // motion a run executed before it stopped short).
    if let Some(trajectory) = run.outcome.timed() {
        let points = trajectory
            .iter()
            .map(|p| {
                let c = p.pose;
                Value::Array(
                    [c.x, c.y, c.theta, p.t]
                        .into_iter()
                        .map(float_json)
                        .collect(),
                )
            })
            .collect();
        obj.insert("trajectory".into(), Value::Array(points));
    }
    // A run that stopped short of the goal: the motion it executed (SPEC 3).
    let trajectory = &run.outcome.trajectory;
    if run.outcome.path.is_none() && !trajectory.is_empty() {
        let poses = trajectory
            .iter()
            .map(|&c| config_json(c, rotates))
            .collect();
        obj.insert("trajectory".into(), Value::Array(poses));
    }
    // A plan with `drive`: its driven trajectory, `[t, x, y, θ]` per pose
    // (seconds, radians), thinned like the viewer's; null without a path.
    if plan.params.get("drive").is_some() {
        let drive = run.drive.as_ref().map_or(Value::Null, |d| {
            Value::Array(
                d.thinned(DRIVE_SAMPLES)
                    .map(|(t, c)| {
                        Value::Array(
                            vec![t, c.x, c.y, c.theta]
                                .into_iter()
                                .map(float_json)
                                .collect(),
                        )
                    })
                    .collect(),
            )
        });
        obj.insert("drive".into(), drive);
    }
    Value::Object(obj)
}

/// `None` for an outcome whose check index is out of range. A check that
/// aggregated series also lists each series' size, min and max.
pub(crate) fn check_json(scenario: &Scenario, outcome: &CheckOutcome) -> Option<Value> {
    let check = scenario.checks.get(outcome.check)?;
    let mut obj = Map::new();
    obj.insert("line".into(), check.line.into());
    obj.insert("expr".into(), check.text.clone().into());
    obj.insert("passed".into(), outcome.passed.into());
    obj.insert("values".into(), metrics_json(&outcome.values));
    if !outcome.series.is_empty() {
        let series = outcome
            .series
            .iter()
            .map(|(name, s)| {
                let mut o = Map::new();
                o.insert("runs".into(), s.runs.into());
                o.insert("min".into(), float_json(s.min));
                o.insert("max".into(), float_json(s.max));
                (name.clone(), Value::Object(o))
            })
            .collect();
        obj.insert("series".into(), Value::Object(series));
    }
    Some(Value::Object(obj))
}

pub(crate) fn metrics_json(metrics: &Metrics) -> Value {
    Value::Object(
        metrics
            .iter()
            .map(|(name, &value)| (name.clone(), metric_json(value)))
            .collect(),
    )
}

/// Booleans as JSON booleans; numbers as integers when whole and exact,
/// else as floats; NaN and infinities (which JSON lacks) as `null`.
fn metric_json(value: MetricValue) -> Value {
    match value {
        MetricValue::Bool(b) => Value::Bool(b),
        MetricValue::Num(x) if x.fract() == 0.0 && x.abs() < EXACT_INTEGER_LIMIT => {
            // Exact: |x| < 2^53 fits an i64 and the cast does not round.
            Value::Number(Number::from(x as i64))
        }
        MetricValue::Num(x) => float_json(x),
    }
}

/// `[x, y]`, or `[x, y, θ]` (radians) for a robot whose body rotates.
fn config_json(c: Config, rotates: bool) -> Value {
    let mut xs = vec![float_json(c.x), float_json(c.y)];
    if rotates {
        xs.push(float_json(c.theta));
    }
    Value::Array(xs)
}

pub fn float_json(x: f64) -> Value {
    Number::from_f64(x).map_or(Value::Null, Value::Number)
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use super::*;
    use crate::contract::PlanOutcome;
    use crate::contract::Robot;
    use crate::diagnostics::{SourceMap, Span};
    use crate::geometry::{Aabb, ConvexPolygon, Point, RobotShape, World};
    use crate::scenario::Check;
    use crate::syntax::ast::{Expr, ExprKind};

    fn robot(name: &str, shape: RobotShape) -> Robot {
        Robot {
            name: name.into(),
            shape,
            steering: None,
            speed: None,
            team: None,
            span: Span::default(),
        }
    }

    /// A plan of the `k`-th planner of the registry.
    fn plan(name: &str, k: usize, robot: usize) -> Plan {
        let planner = crate::planners::registry::PLANNERS[k];
        let (start, goal) = (Config::new(0.0, 0.0, 0.0), Config::new(4.0, 2.0, 0.0));
        Plan::fixture(name, planner, robot, start, Some(goal))
    }

    fn metrics(entries: &[(&str, MetricValue)]) -> Metrics {
        entries.iter().map(|(k, v)| (k.to_string(), *v)).collect()
    }

    /// Two plans declared as `zeta` (a rod, found) then `alpha` (a disk,
    /// not found), run in the opposite order; two checks, one failed.
    fn report() -> RunReport {
        let rod = ConvexPolygon {
            vertices: vec![
                Point::new(-1.0, -0.1),
                Point::new(1.0, -0.1),
                Point::new(1.0, 0.1),
                Point::new(-1.0, 0.1),
            ],
        };
        let scenario = Scenario {
            benches: Vec::new(),
            file: PathBuf::from("scenarios/demo.scen"),
            title: Some("Demo \"quoted\"".into()),
            world: World {
                bounds: Aabb::from_corners(Point::new(0.0, 0.0), Point::new(10.0, 5.0)),
                obstacles: Vec::new(),
            },
            obstacle_spans: Vec::new(),
            moving: Vec::new(),
            moving_spans: Vec::new(),
            family: None,
            template: None,
            robots: vec![
                robot("rod", RobotShape::Polygon(rod)),
                robot("disk", RobotShape::Disk(0.5)),
            ],
            plans: vec![plan("zeta", 0, 0), plan("alpha", 2, 1)],
            checks: vec![
                Check {
                    bench: false,
                    expr: Expr {
                        kind: ExprKind::Bool(true),
                        span: Span::default(),
                    },
                    text: "zeta.cost <= 90".into(),
                    line: 23,
                    span: Span::default(),
                },
                Check {
                    bench: false,
                    expr: Expr {
                        kind: ExprKind::Bool(true),
                        span: Span::default(),
                    },
                    text: "alpha.found".into(),
                    line: 24,
                    span: Span::default(),
                },
            ],
            sources: SourceMap::default(),
        };
        let zeta = PlanRun {
            plan: 0,
            outcome: PlanOutcome {
                path: Some(vec![Config::new(0.0, 0.0, 0.0), Config::new(4.0, 2.0, 1.5)]),
                ..PlanOutcome::default()
            },
            metrics: metrics(&[
                ("found", MetricValue::Bool(true)),
                ("cost", MetricValue::Num(79.1)),
                ("expanded", MetricValue::Num(5786.0)),
                ("turn", MetricValue::Num(f64::INFINITY)),
                ("skew", MetricValue::Num(f64::NAN)),
                ("offset", MetricValue::Num(-3.0)),
            ]),
            validation: None,
            drive: None,
        };
        let alpha = PlanRun {
            plan: 1,
            outcome: PlanOutcome::default(),
            metrics: metrics(&[("found", MetricValue::Bool(false))]),
            validation: None,
            drive: None,
        };
        RunReport {
            bench_runs: Vec::new(),
            skipped: Vec::new(),
            scenario,
            plans: vec![alpha, zeta],
            checks: vec![
                CheckOutcome {
                    series: Default::default(),
                    check: 0,
                    passed: true,
                    values: [("zeta.cost".to_string(), MetricValue::Num(79.1))].into(),
                },
                CheckOutcome {
                    series: Default::default(),
                    check: 1,
                    passed: false,
                    values: [("alpha.found".to_string(), MetricValue::Bool(false))].into(),
                },
            ],
        }
    }

    #[test]
    fn document_has_the_spec_5_shape() {
        let doc = to_json(&report());
        let kind = |k: usize| crate::planners::registry::PLANNERS[k].kind;
        let expected = serde_json::json!({
            "file": "scenarios/demo.scen",
            "scenario": "Demo \"quoted\"",
            "plans": {
                "zeta": {
                    "kind": kind(0), "robot": "rod",
                    "metrics": {
                        "found": true, "cost": 79.1, "expanded": 5786,
                        "turn": null, "skew": null, "offset": -3
                    },
                    "path": [[0.0, 0.0, 0.0], [4.0, 2.0, 1.5]]
                },
                "alpha": {
                    "kind": kind(2), "robot": "disk",
                    "metrics": {"found": false},
                    "path": null
                }
            },
            "checks": [
                {"line": 23, "expr": "zeta.cost <= 90", "passed": true,
                 "values": {"zeta.cost": 79.1}},
                {"line": 24, "expr": "alpha.found", "passed": false,
                 "values": {"alpha.found": false}}
            ],
            "passed": 1, "failed": 1
        });
        assert_eq!(doc, expected);
    }

    #[test]
    fn whole_numbers_print_as_integers_and_paths_as_floats() {
        let text = serde_json::to_string(&to_json(&report())).unwrap_or_default();
        assert!(text.contains(r#""expanded":5786,"#), "{text}");
        assert!(text.contains(r#""offset":-3,"#), "{text}");
        assert!(text.contains("[[0.0,0.0,0.0],[4.0,2.0,1.5]]"), "{text}");
    }

    #[test]
    fn non_rotating_robots_have_two_coordinates() {
        let mut report = report();
        report.plans[0].outcome.path = Some(vec![Config::new(1.0, 2.0, 0.7)]);
        let doc = to_json(&report);
        assert_eq!(
            doc["plans"]["alpha"]["path"],
            serde_json::json!([[1.0, 2.0]])
        );
    }

    #[test]
    fn a_run_that_stopped_short_lists_its_trajectory() {
        let mut report = report();
        let walked = vec![Config::new(0.0, 0.0, 0.0), Config::new(0.5, 0.25, 0.0)];
        report.plans[0].outcome.trajectory = walked;
        let doc = to_json(&report);
        let alpha = &doc["plans"]["alpha"];
        assert_eq!(alpha["path"], Value::Null);
        assert_eq!(
            alpha["trajectory"],
            serde_json::json!([[0.0, 0.0], [0.5, 0.25]])
        );
        // Plans with a path, or without any motion, have no such key.
        assert!(doc["plans"]["zeta"].get("trajectory").is_none());
        assert!(
            to_json(&self::report())["plans"]["alpha"]
                .get("trajectory")
                .is_none()
        );
    }

    #[test]
    fn missing_title_is_null() {
        let mut report = report();
        report.scenario.title = None;
        assert_eq!(to_json(&report)["scenario"], Value::Null);
    }

    #[test]
    fn same_report_gives_identical_bytes() {
        let a = serde_json::to_string(&to_json(&report())).unwrap_or_default();
        let b = serde_json::to_string(&to_json(&report())).unwrap_or_default();
        assert!(!a.is_empty());
        assert_eq!(a, b);
    }

    #[test]
    fn plans_follow_declaration_order_when_maps_keep_insertion_order() {
        let mut probe = Map::new();
        probe.insert("b".into(), Value::Null);
        probe.insert("a".into(), Value::Null);
        let keeps_order = probe.keys().next().is_some_and(|k| k == "b");
        let doc = to_json(&report());
        let names: Vec<&String> = doc["plans"]
            .as_object()
            .map(|plans| plans.keys().collect())
            .unwrap_or_default();
        if keeps_order {
            assert_eq!(names, ["zeta", "alpha"]);
            let keys: Vec<&String> = doc
                .as_object()
                .map(|d| d.keys().collect())
                .unwrap_or_default();
            assert_eq!(
                keys,
                ["file", "scenario", "plans", "checks", "passed", "failed"]
            );
        } else {
            assert_eq!(names, ["alpha", "zeta"]);
        }
    }
}
