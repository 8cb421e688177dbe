//! Planners: one file per planner kind, plus the shared lattice code.
//! A planner is a function of (world, robot, parameters) returning a
//! [`PlanOutcome`]; it knows nothing of output. The runner adds the metrics
//! every planner has (length, turn, nodes, collision_free, ...) from the path.

use std::collections::BTreeMap;

use crate::geometry::{Config, Point};

/// A metric value: booleans and numbers are the only types of `expect`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MetricValue {
    Bool(bool),
    Num(f64),
}

impl MetricValue {
    pub fn as_f64(self) -> f64 {
        match self {
            MetricValue::Bool(b) => f64::from(u8::from(b)),
            MetricValue::Num(x) => x,
        }
    }
}

/// Metrics by name, in a stable (sorted) order.
pub type Metrics = BTreeMap<String, MetricValue>;

/// What a planner returns.
#[derive(Clone, Debug, Default)]
pub struct PlanOutcome {
    /// Start to goal, both included; `None` when no path was found.
    pub path: Option<Vec<Config>>,
    /// Whether a limit stopped the planner.
    pub gave_up: bool,
    /// The path's cost in the planner's own metric.
    pub cost: Option<f64>,
    /// Search nodes expanded, or iterations.
    pub expanded: u64,
    /// Planner-specific metrics (`cells`, `free_cells`, ...).
    pub extra: Metrics,
    /// Notes for the report ("the snapped goal could not be connected ...").
    pub notes: Vec<String>,
    /// What sinks may draw.
    pub trace: Trace,
}

/// What a planner leaves for the viewer and the SVG.
#[derive(Clone, Debug, Default)]
pub struct Trace {
    /// Expanded configurations in expansion order.
    pub expansions: Vec<Config>,
    /// Obstacles grown by the robot (C-obstacles of a translating robot),
    /// as closed polygons, for drawing.
    pub grown_obstacles: Vec<Vec<Point>>,
    /// For rotating robots: each θ layer (radians) with the boundaries of
    /// its C-obstacles, for drawing the configuration space in 3D.
    pub cspace_layers: Vec<(f64, Vec<Vec<Point>>)>,
}

/// The most C-obstacle outlines a trace keeps over all layers; beyond it
/// (e.g. large grids) layers are left out of the picture, not the search.
pub const MAX_TRACED_C_OBSTACLES: usize = 200_000;

pub mod astar;
pub mod astar_rotating;
pub mod lattice;
