//! Potential field with random-walk escape (SPEC 3.4).
//!
//! Not implemented yet: the schema marks `potential` as not implemented, so the
//! analyzer refuses such plans before this is ever called.

use crate::geometry::{RobotShape, World};
use crate::planners::PlanOutcome;
use crate::scenario::Params;

pub fn plan(_world: &World, _robot: &RobotShape, _params: &Params) -> PlanOutcome {
    PlanOutcome {
        notes: vec!["planner `potential` is not implemented yet".into()],
        ..PlanOutcome::default()
    }
}
