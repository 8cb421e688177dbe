//! Planners: one file per planner kind, plus the shared lattice code.
//! A planner is a function of (world, robot, parameters) returning a
//! [`PlanOutcome`]; it knows nothing of output. The runner adds the metrics
//! every planner has (length, turn, nodes, collision_free, ...) from the path.

use std::collections::BTreeMap;

use crate::geometry::{Aabb, Config, Point, Vector};

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
    /// For rotating robots: each θ layer of the configuration space, for
    /// drawing it in 3D.
    pub cspace_layers: Vec<CLayerTrace>,
    /// The motion executed before the planner stopped short of the goal
    /// (a potential-field run stuck in a minimum or out of steps, an online
    /// robot that proved the goal unreachable); empty when a path was found.
    /// Drawn, never validated or measured: it is not a path to the goal.
    pub unfinished: Vec<Config>,
    /// Roadmap: the visibility edges (entity `plans/NAME/roadmap`).
    pub roadmap_edges: Vec<(Point, Point)>,
    /// Online navigation: what the robot sensed and planned, step by step.
    pub online: Option<OnlineTrace>,
    /// Potential field: forces, local minima and escapes.
    pub field: Option<FieldTrace>,
    /// Coverage: mega-cells and the spanning tree.
    pub coverage: Option<CoverageTrace>,
}

/// One θ layer of a rotating robot's configuration space, for drawing.
#[derive(Clone, Debug, Default)]
pub struct CLayerTrace {
    /// θ in radians.
    pub theta: f64,
    /// The boundary of the union of the layer's C-obstacles, as segments.
    pub boundary: Vec<(Point, Point)>,
    /// Each C-obstacle (closed, counter-clockwise) with the index of the
    /// world obstacle it comes from.
    pub c_obstacles: Vec<(usize, Vec<Point>)>,
}

/// What an online robot knew and intended at each step. Step `k` is the
/// robot standing at `path[k]` (the executed trajectory).
#[derive(Clone, Debug, Default)]
pub struct OnlineTrace {
    /// Side of a lattice cell: sensed cells are drawn as squares this size
    /// centred on their lattice points.
    pub cell: f64,
    /// `sensed[k]`: the lattice points first observed at step `k`, with
    /// `true` when the point is blocked on the true map.
    pub sensed: Vec<Vec<(Point, bool)>>,
    /// `plans[k]`: the plan the robot held at step `k`, from its position
    /// (empty when the strategy has none, e.g. while backtracking).
    pub plans: Vec<Vec<Point>>,
}

/// One sampled step of a potential-field run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForceSample {
    /// Index into the path.
    pub step: usize,
    pub at: Point,
    pub attract: Vector,
    pub repulse: Vector,
    pub total: Vector,
}

/// What a potential-field run leaves for the viewer.
#[derive(Clone, Debug, Default)]
pub struct FieldTrace {
    /// Forces at sampled steps (not every step: at most a few thousand).
    pub forces: Vec<ForceSample>,
    /// Local minima detected: the path index and the position.
    pub minima: Vec<(usize, Point)>,
    /// Escape jumps taken: the path index where the jump starts, from, to.
    pub escapes: Vec<(usize, Point, Point)>,
}

/// What spanning tree coverage leaves for the viewer.
#[derive(Clone, Debug, Default)]
pub struct CoverageTrace {
    /// The side D of a D-cell.
    pub tool: f64,
    /// The free mega-cells of the tree (squares of side 2D).
    pub mega_cells: Vec<Aabb>,
    /// Free D-cells that STC cannot cover (in partly blocked mega-cells).
    pub uncovered: Vec<Aabb>,
    /// Spanning-tree edges between mega-cell centres.
    pub tree: Vec<(Point, Point)>,
}

/// The most C-obstacle outlines a trace keeps over all layers; beyond it
/// (e.g. large grids) layers are left out of the picture, not the search.
pub const MAX_TRACED_C_OBSTACLES: usize = 200_000;

pub mod astar;
pub mod astar_rotating;
pub mod coverage;
pub mod lattice;
pub mod online;
pub mod potential;
pub mod roadmap;
