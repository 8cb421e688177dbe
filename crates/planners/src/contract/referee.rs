//! The referee a runner lends a planner (SPEC 3.0: the validator judges;
//! planners search with their own motion checkers).
//!
//! Two planners execute a motion they cannot simply return for the runner
//! to judge afterwards, and are lent the validator through
//! [`Task::referee`](super::Task::referee) for that alone:
//! - `potential` beyond 4 million moves (SPEC 3.4) keeps only every
//!   stride-th pose, so the motion is judged (and its clearance measured)
//!   chunk by chunk as it is made;
//! - `bug` simulates a robot that drives where its sensor leads: where the
//!   boundary tracer's tolerance lets the executed motion graze an
//!   obstacle it did not see, the robot stops there, and the referee says
//!   where.
//!
//! Neither decides a search with it. A planner given no referee (a test
//! building its own task) says so: a long walk is reported as not
//! validated, and a bug run is judged by whoever runs it.

use std::fmt;

use crate::geometry::validator::{DEFAULT_TOLERANCE, ValidationError, Validator};
use crate::geometry::{Config, RobotShape, World};

/// The validator of one robot in one world, as a planner may use it.
pub trait Referee: Sync {
    /// The validator's verdict on `poses` as a path (SPEC 3.0, at the
    /// default tolerance).
    fn validate(&self, poses: &[Config]) -> Result<(), ValidationError>;

    /// The validator's clearance of `poses` as a path (SPEC 3).
    fn clearance(&self, poses: &[Config]) -> f64;
}

impl fmt::Debug for dyn Referee + '_ {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("Referee")
    }
}

/// The runner's referee: the validator, for one robot.
pub struct ValidatorReferee<'w> {
    validator: Validator<'w>,
    robot: &'w RobotShape,
}

impl<'w> ValidatorReferee<'w> {
    pub fn new(world: &'w World, robot: &'w RobotShape) -> Self {
        ValidatorReferee {
            validator: Validator::new(world),
            robot,
        }
    }

    /// The validator itself, for the runner that lent it.
    pub fn validator(&self) -> &Validator<'w> {
        &self.validator
    }
}

impl Referee for ValidatorReferee<'_> {
    fn validate(&self, poses: &[Config]) -> Result<(), ValidationError> {
        self.validator
            .validate_path(self.robot, poses, DEFAULT_TOLERANCE)
    }

    fn clearance(&self, poses: &[Config]) -> f64 {
        self.validator
            .clearance(self.robot, poses, DEFAULT_TOLERANCE)
    }
}
