//! The planners' collision queries for point and disk robots, with a broad
//! phase over all obstacles. (stub: to be implemented)

use super::{Point, World};

/// Obstacles of a world prepared for fast queries by the planners.
pub struct ObstacleIndex {}

impl ObstacleIndex {
    pub fn new(world: &World) -> Self {
        let _ = world;
        todo!()
    }

    /// Whether a disk of radius `r` (0 = a point) centred at `p` stays out of
    /// every obstacle interior (touching allowed, tolerance TOUCH_EPS).
    pub fn disk_free(&self, p: Point, r: f64) -> bool {
        let _ = (p, r);
        todo!()
    }

    /// Whether the disk of radius `r` swept from `p` to `q` stays out of
    /// every obstacle interior and crosses no segment obstacle.
    pub fn sweep_free(&self, p: Point, q: Point, r: f64) -> bool {
        let _ = (p, q, r);
        todo!()
    }
}
