//! `drive unicycle` (SPEC 3.6) on the paths of different planners: the
//! driven trajectory follows the path point by point, is validated like a
//! path, and its metrics reach `expect`.

mod common;

use common::TempDir;
use scen::contract::MetricValue;
use scen::geometry::validator::{DEFAULT_TOLERANCE, validate_path};
use scen::{load, run_scenario};

const WORLD: &str = r#"
world {
  bounds (0, 0) (8, 6)
  grid G cell 1 origin (0, 0) {
    "........"
    "..##...."
    "..##...."
    "......##"
    "......##"
    "........"
  }
}
robot dot disk 0.4
"#;

fn run(text: &str) -> scen::RunReport {
    let dir = TempDir::new("drive");
    let file = dir.path().join("t.scen");
    std::fs::write(&file, format!("{WORLD}\n{text}")).unwrap();
    let scenario = load(&file).unwrap_or_else(|e| panic!("{:?}", e.diags));
    run_scenario(scenario, &[])
}

/// Checks what every driven plan must satisfy and returns its drive time.
fn check_driven(report: &scen::RunReport, name: &str) -> f64 {
    let run = report
        .plans
        .iter()
        .find(|r| report.plan(r).name == name)
        .unwrap();
    let path = run.outcome.path.as_ref().expect("a path");
    let drive = run.drive.as_ref().expect("a drive");
    assert!(drive.completed);
    // It starts at the path's start and passes every path point within
    // the default reach, in order.
    assert_eq!(drive.samples[0].1, path[0]);
    let mut k = 0;
    for p in path {
        let reach = 0.0009 + 1e-12;
        while (drive.samples[k].1.xy() - p.xy()).norm() > reach {
            k += 1;
            assert!(k < drive.samples.len(), "never reached {p:?}");
        }
    }
    // The same validator as for paths, on the driven poses.
    let poses: Vec<_> = drive.samples.iter().map(|s| s.1).collect();
    let robot = &report.scenario.robots[report.plan(run).robot].shape;
    let world = &report.scenario.world;
    assert!(validate_path(world, robot, &poses, DEFAULT_TOLERANCE).is_ok());
    let m = &run.metrics;
    assert_eq!(m["drive_collision_free"], MetricValue::Bool(true));
    assert_eq!(m["drive_time"], MetricValue::Num(drive.time));
    assert!(m["drive_max_deviation"].as_f64() < 0.01);
    drive.time
}

#[test]
fn an_astar_path_is_driven() {
    let report = run(
        "plan a astar dot { start (0.5, 0.5) goal (7.5, 5.5) drive unicycle }\n\
         expect a.drive_collision_free and a.drive_time > 0",
    );
    check_driven(&report, "a");
    assert_eq!(report.failed(), 0);
}

#[test]
fn a_coverage_tour_is_driven() {
    let report = run(
        "plan c coverage dot { start (0.5, 0.5) on G drive unicycle { max_speed 2 } }\n\
         expect c.drive_collision_free and c.drive_max_deviation < 0.01",
    );
    check_driven(&report, "c");
    assert_eq!(report.failed(), 0);
}

#[test]
fn a_faster_robot_arrives_sooner() {
    let slow = run(
        "plan a astar dot { start (0.5, 0.5) goal (7.5, 5.5) drive unicycle { max_speed 0.5 } }",
    );
    let fast =
        run("plan a astar dot { start (0.5, 0.5) goal (7.5, 5.5) drive unicycle { max_speed 2 } }");
    assert!(check_driven(&fast, "a") < check_driven(&slow, "a"));
}

#[test]
fn plans_without_drive_have_no_drive_metrics() {
    let report = run("plan a astar dot { start (0.5, 0.5) goal (7.5, 5.5) }");
    assert!(report.plans[0].drive.is_none());
    assert!(!report.plans[0].metrics.contains_key("drive_time"));
}

#[test]
fn a_plan_without_a_path_has_nothing_to_drive() {
    // A limit stops the search: no path, so the drive metrics fail.
    let report = run(
        "plan a astar dot { start (0.5, 0.5) goal (7.5, 0.5) limit expansions 3 drive unicycle }",
    );
    let m = &report.plans[0].metrics;
    assert_eq!(m["drive_collision_free"], MetricValue::Bool(false));
    assert_eq!(m["drive_time"], MetricValue::Num(f64::INFINITY));
}

#[test]
fn json_lists_the_driven_trajectory() {
    let report = run(
        "plan a astar dot { start (0.5, 0.5) goal (7.5, 5.5) drive unicycle }\n\
         plan b astar dot { start (0.5, 0.5) goal (7.5, 5.5) }\n\
         plan c astar dot { start (0.5, 0.5) goal (7.5, 0.5) limit expansions 3 drive unicycle }",
    );
    let doc = scen::report::json::to_json(&report);
    let plans = &doc["plans"];
    let drive = report.plans[0].drive.as_ref().unwrap();
    let listed = plans["a"]["drive"].as_array().expect("a's trajectory");
    assert!(listed.len() >= 2 && listed.len() <= scen::report::json::DRIVE_SAMPLES);
    let pose = |v: &serde_json::Value| -> Vec<f64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (t0, c0) = drive.samples[0];
    assert_eq!(pose(&listed[0]), vec![t0, c0.x, c0.y, c0.theta]);
    let (tn, cn) = *drive.samples.last().unwrap();
    assert_eq!(pose(listed.last().unwrap()), vec![tn, cn.x, cn.y, cn.theta]);
    assert!(
        listed.windows(2).all(|w| pose(&w[0])[0] < pose(&w[1])[0]),
        "times increase"
    );
    // No `drive`: no key; a drive without a path: null.
    assert!(plans["b"].get("drive").is_none());
    assert!(plans["c"]["drive"].is_null());
}
