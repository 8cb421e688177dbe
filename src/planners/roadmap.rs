//! Visibility-graph roadmap with Dijkstra (SPEC 3.3).
//!
//! Not implemented yet: the schema marks `roadmap` as not implemented, so the
//! analyzer refuses such plans before this is ever called.

use crate::geometry::{RobotShape, World};
use crate::planners::PlanOutcome;
use crate::scenario::Params;

pub fn plan(_world: &World, _robot: &RobotShape, _params: &Params) -> PlanOutcome {
    PlanOutcome {
        notes: vec!["planner `roadmap` is not implemented yet".into()],
        ..PlanOutcome::default()
    }
}
