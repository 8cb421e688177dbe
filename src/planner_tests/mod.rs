//! The planners' tests that write their worlds and plans as scenario text.
//! They need the language, which sits above the planners, so they live in
//! this crate and reach the planners through their public items; the
//! planners' other unit tests build worlds with fixtures, beside the code
//! (issue 40: the planners become a crate below the language).

use crate::contract::PlanOutcome;
use crate::geometry::validator::{DEFAULT_TOLERANCE, validate_path};
use crate::scenario::Scenario;

mod astar_rotating;
mod hybrid_astar;
mod potential;
mod sampling;

/// Runs every plan of `s`; a found path must start at the start, end at
/// the goal and pass the validator.
fn run_checked(s: &Scenario) -> Vec<PlanOutcome> {
    s.plans
        .iter()
        .map(|p| {
            let robot = &s.robots[p.robot].shape;
            let out = p.settings.plan(&p.task(s));
            if let Some(path) = &out.path {
                assert_eq!(path.first(), Some(&p.params.start));
                assert_eq!(path.last(), p.params.goal.as_ref());
                if let Err(e) = validate_path(&s.world, robot, path, DEFAULT_TOLERANCE) {
                    panic!("plan {}: the path fails the validator: {e:?}", p.name);
                }
            }
            out
        })
        .collect()
}
