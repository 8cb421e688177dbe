//! The settings of an `astar` plan, shared by the (x, y) lattice search
//! ([`super::astar`]) and the (x, y, θ) one ([`super::astar_rotating`]),
//! so that neither imports the other.

use super::lattice::{CostMetric, Heuristic, LatticeSpec};

/// The settings of an `astar` plan.
#[derive(Clone, Debug)]
pub struct Astar {
    /// The lattice (θ layers included for a rotating robot).
    pub lattice: LatticeSpec,
    /// Whether the lattice has θ layers: a polygon robot without `rotate no`.
    pub rotating: bool,
    /// 4 or 8 on an (x, y) lattice, 6 or 26 on an (x, y, θ) lattice.
    pub connect: u8,
    pub cost: CostMetric,
    /// Cost of one radian of rotation.
    pub turn_cost: f64,
    /// Heuristic inflation w ≥ 1.
    pub weight: f64,
    pub heuristic: Heuristic,
}
