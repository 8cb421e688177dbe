//! What a planner returns: the path, its own metrics, notes and drawable
//! layers ([`PlanOutcome`]); the runner adds the metrics every planner has.

use std::collections::BTreeMap;

use crate::geometry::Config;
use crate::geometry::car::CarPath;
use crate::geometry::timed::Timed;
use crate::geometry::validator::ValidationError;

use super::layers::Layer;

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
    /// The motion executed before the planner stopped short of the goal
    /// (a potential-field run stuck in a minimum or out of steps, an online
    /// robot that proved the goal unreachable); empty when a path was found.
    pub trajectory: Vec<Config>,
    /// What the sinks draw ([`layers`]).
    pub layers: Vec<Layer>,
    /// Set when `path` or `trajectory` is thinned: the planner measured
    /// and validated the whole motion as it made it, and the runner reports
    /// these measures instead of measuring the list.
    pub measured: Option<MeasuredMotion>,
    /// A car robot's path as segments (SPEC §5 `"segments"`): what the
    /// runner validates; `path` is then its poses for drawing.
    pub car: Option<CarPath>,
    /// A time-aware planner's trajectory (SPEC 2.9): the time of each pose
    /// of `path`, from 0, increasing; the runner validates the path with
    /// these times in space-time.
    pub times: Option<Vec<f64>>,
    /// A team planner's paths (SPEC 2.10), one per agent in the team's
    /// order, one lattice point per step; `None` when it found none.
    pub agents: Option<Vec<Vec<crate::geometry::Point>>>,
    /// A continuous team planner's times (SPEC 2.10: `prioritized`): for
    /// each agent, the time of each point of its path; `None` under grid
    /// semantics (a point per step).
    pub agent_times: Option<Vec<Vec<f64>>>,
}

/// The measures of a motion too long to return in full (SPEC 3.4: a
/// potential-field walk beyond 4 million moves), taken by its planner as
/// it went, exactly as the runner takes them from a path.
#[derive(Clone, Debug, PartialEq)]
pub struct MeasuredMotion {
    /// Configurations in the whole motion.
    pub poses: u64,
    /// Euclidean length of its (x, y) polyline.
    pub length: f64,
    /// Total absolute rotation.
    pub turn: f64,
    pub smoothness: f64,
    /// Over the validator's sub-steps of the whole motion.
    pub clearance: f64,
    /// The validator's verdict on the whole motion (the segment counts its
    /// moves).
    pub validation: Option<ValidationError>,
    /// The list keeps every `stride`-th configuration and the last.
    pub stride: u64,
}

impl PlanOutcome {
    /// Found at once: the path of the one configuration `start`, which is
    /// the goal (SPEC 3), at cost 0. The planner adds its own metrics.
    pub fn at_goal(start: Config) -> Self {
        PlanOutcome {
            path: Some(vec![start]),
            cost: Some(0.0),
            ..PlanOutcome::default()
        }
    }

    /// The trajectory (SPEC 2.9): each pose of `path` with its time, when
    /// the outcome has both, one time per pose.
    pub fn timed(&self) -> Option<Vec<Timed>> {
        let (path, times) = (self.path.as_ref()?, self.times.as_ref()?);
        (path.len() == times.len()).then(|| {
            path.iter()
                .zip(times)
                .map(|(&pose, &t)| Timed { pose, t })
                .collect()
        })
    }

    /// The layers of one entity, in order.
    pub fn layers_of<'a>(&'a self, entity: &'a str) -> impl Iterator<Item = &'a Layer> + 'a {
        self.layers.iter().filter(move |l| l.entity == entity)
    }

    /// The first layer of an entity.
    pub fn layer(&self, entity: &str) -> Option<&Layer> {
        self.layers.iter().find(|l| l.entity == entity)
    }
}
