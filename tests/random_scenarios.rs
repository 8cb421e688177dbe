//! Random scenarios through the whole interpreter, as a fuzzer would write
//! them: random worlds (rects, disks, segments, convex polygons, grids),
//! robots and plans of every planner kind with random parameters. Whatever
//! the input, loading either succeeds or reports diagnostics, and every
//! path a planner returns passes the validator (SPEC 3.0): `run_scenario`
//! validates each one, and a failure shows up as `validation`.
//!
//! The first bug this found: coverage toured straight through obstacles
//! that were not grid cells.

mod common;

use common::TempDir;
use common::random::scenario;
use proptest::prelude::*;
use scen::contract::MetricValue;
use scen::{load, run_scenario};

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_scenarios_load_or_explain_and_every_path_validates(seed in any::<u64>()) {
        let text = scenario(seed);
        let dir = TempDir::new("random");
        let file = dir.path().join("random.scen");
        std::fs::write(&file, &text).expect("write");
        let scenario = match load(&file) {
            Ok(s) => s,
            Err(fail) => {
                // Refused: with at least one diagnostic, each with a code.
                prop_assert!(!fail.diags.is_empty(), "refused without a word:\n{text}");
                return Ok(());
            }
        };
        let report = run_scenario(scenario, &[]);
        for run in &report.plans {
            prop_assert!(
                run.validation.is_none(),
                "{:?}\n{text}",
                run.validation
            );
            if run.outcome.path.is_some() {
                prop_assert_eq!(
                    run.metrics.get("collision_free"),
                    Some(&MetricValue::Bool(true)),
                    "{}", text
                );
            }
        }
    }
}

#[test]
fn the_generator_reaches_every_planner_with_plans_that_run() {
    // Among the first seeds, every planner kind loads and finds a path at
    // least once: the property above is not vacuous.
    let mut found = std::collections::BTreeSet::new();
    for seed in 0..400 {
        let text = scenario(seed);
        let dir = TempDir::new("random-cover");
        let file = dir.path().join("random.scen");
        std::fs::write(&file, &text).expect("write");
        let Ok(s) = load(&file) else { continue };
        let report = run_scenario(s, &[]);
        if report.plans[0].outcome.path.is_some() {
            found.insert(report.plan(&report.plans[0]).kind());
        }
        if found.len() == 5 {
            break;
        }
    }
    assert_eq!(
        found.into_iter().collect::<Vec<_>>(),
        ["astar", "coverage", "online", "potential", "roadmap"]
    );
}
