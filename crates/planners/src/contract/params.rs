//! A plan's validated parameters ([`Params`], as written, with spans), its
//! limits ([`Limits`]) and the robot it is for ([`Robot`]): what the
//! analyzer produces and a planner's `check` reads.

use std::collections::BTreeMap;

use crate::contract::schema::RobotKind;
use crate::diagnostics::Span;
use crate::geometry::steer::Steering;
use crate::geometry::{Config, Point, RobotShape};

#[derive(Clone, Debug)]
pub struct Robot {
    pub name: String,
    pub shape: RobotShape,
    /// `steer MODEL RADIUS`: a car-like robot (SPEC 2.4).
    pub steering: Option<Steering>,
    /// `speed V`: the largest speed of its reference point (SPEC 2.9).
    pub speed: Option<f64>,
    /// For a `team` (SPEC 2.10): its agents, each of this shape.
    pub team: Option<std::sync::Arc<[Agent]>>,
    pub span: Span,
}

/// One agent of a team (SPEC 2.10): its name, start and goal.
#[derive(Clone, Debug, PartialEq)]
pub struct Agent {
    pub name: String,
    pub start: Point,
    pub goal: Point,
    /// Its row in the team's block or `.scen` file, for diagnostics.
    pub span: Span,
}

impl Robot {
    /// What it is for the planners' robot tables: a car when it steers,
    /// else its shape's kind.
    pub fn kind(&self) -> RobotKind {
        if self.team.is_some() {
            RobotKind::Team
        } else if self.steering.is_some() {
            RobotKind::Car
        } else {
            RobotKind::of(&self.shape)
        }
    }
}

/// Validated parameters of a plan, as written: keys not given by the user
/// are absent (the planner's `check` reads the schema's defaults through
/// [`PlanArgs`]).
#[derive(Clone, Debug)]
pub struct Params {
    pub start: Config,
    pub start_span: Span,
    pub goal: Option<Config>,
    pub goal_span: Option<Span>,
    pub limits: Limits,
    pub seed: u64,
    pub values: BTreeMap<&'static str, Param>,
}

impl Params {
    pub fn get(&self, key: &str) -> Option<&ParamValue> {
        self.values.get(key).map(|p| &p.value)
    }
}

/// Limits of SPEC 2.5 (`limit expansions N`, `limit time 2s`, ...).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Limits {
    pub expansions: Option<u64>,
    pub steps: Option<u64>,
    /// Seconds.
    pub time: Option<f64>,
    /// Lattice-size cap (default [`DEFAULT_CELL_CAP`]).
    pub cells: Option<u64>,
    /// Samples drawn, for the sampling-based planners.
    pub iterations: Option<u64>,
}

impl Limits {
    /// Both sets of limits: the smaller of each kind holds.
    pub fn and(self, other: Limits) -> Limits {
        fn min<T: PartialOrd>(a: Option<T>, b: Option<T>) -> Option<T> {
            match (a, b) {
                (Some(a), Some(b)) => Some(if b < a { b } else { a }),
                (a, b) => a.or(b),
            }
        }
        Limits {
            expansions: min(self.expansions, other.expansions),
            steps: min(self.steps, other.steps),
            time: min(self.time, other.time),
            cells: min(self.cells, other.cells),
            iterations: min(self.iterations, other.iterations),
        }
    }
}

/// The default cap on lattice sizes (SPEC 3.1).
pub const DEFAULT_CELL_CAP: u64 = 200_000_000;

#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    pub value: ParamValue,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ParamValue {
    Num(f64),
    Word(String),
    Str(String),
    Point(Point),
    Pose(Config),
    /// A word with nested parameters (`drive unicycle { dt 0.02 }`).
    Block(String, BTreeMap<&'static str, Param>),
}
