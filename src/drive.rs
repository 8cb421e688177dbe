//! Driving a path (SPEC 3.6): a simulated differential-drive robot follows
//! any planner's path with a go-to-orientation and a go-to-cell loop.
//! Independent of the planner that made the path.
//!
//! Not implemented yet: the analyzer refuses `drive`, so nothing calls this.

use crate::geometry::Config;

/// A driven trajectory.
#[derive(Clone, Debug, Default)]
pub struct DriveOutcome {
    /// The simulated poses with their times in seconds, from the path's
    /// start; consecutive samples are `dt` apart.
    pub samples: Vec<(f64, Config)>,
    /// Time to reach the path's last point, in seconds.
    pub time: f64,
    /// Largest distance of the driven reference point from the path.
    pub max_deviation: f64,
}
