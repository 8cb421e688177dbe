//! Planners: one file per planner kind ([`registry`] lists them), plus the
//! shared lattice code. A planner is a function of (world, robot, typed
//! settings) returning a [`PlanOutcome`]; it knows nothing of output: it
//! leaves drawable [`layers`]. The runner adds the metrics every planner
//! has (length, turn, nodes, collision_free, ...) from the path.

pub mod astar;
pub mod astar_rotating;
mod astar_settings;
pub mod coverage;
pub mod deadline;
pub mod grid_lattice;
pub mod lattice;
pub mod mapf;
pub mod online;
pub mod potential;
pub mod registry;
pub mod roadmap;
pub mod sampling;
pub mod search;
