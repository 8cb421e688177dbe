//! The independent validator of SPEC 3.0. (stub: to be implemented)

use super::{Config, RobotShape, World};

/// Why a path failed validation.
#[derive(Clone, Debug, PartialEq)]
pub struct ValidationError {
    /// Index of the path segment (from `path[segment]` to `path[segment+1]`).
    pub segment: usize,
    /// The configuration at the failing sub-step.
    pub at: Config,
    /// The obstacle hit, if any (else the bounds were left).
    pub obstacle: Option<String>,
    pub reason: String,
}

/// Default sub-step tolerance.
pub const DEFAULT_TOLERANCE: f64 = 0.01;

pub fn validate_path(
    world: &World,
    robot: &RobotShape,
    path: &[Config],
    tolerance: f64,
) -> Result<(), ValidationError> {
    let _ = (world, robot, path, tolerance);
    todo!()
}

/// The index of an obstacle whose interior the robot's body overlaps at `c`
/// (a point robot: the point is inside an obstacle's interior), if any.
pub fn config_collision(world: &World, robot: &RobotShape, c: Config) -> Option<usize> {
    let _ = (world, robot, c);
    todo!()
}
