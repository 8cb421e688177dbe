//! What a planner is ([`Planner`]: its kind, robots, parameter and metric
//! schemas, limits, and the `check` that builds its typed [`Settings`]) and
//! the problem it is handed ([`Task`]).

use std::any::Any;
use std::fmt;

use crate::geometry::steer::Steering;
use crate::geometry::timed::MovingObstacle;
use crate::geometry::{Config, RobotShape, World};

use super::{Limits, PlanArgs, PlanOutcome};
use crate::contract::schema::{
    CAR_METRICS, COMMON_METRICS, COMMON_PARAMS, MetricSpec, MetricType, ParamSpec, RobotKind,
    TEAM_METRICS, TIME_METRICS,
};

/// What a planner is, for the analyzer, the runner and the tools.
pub struct Planner {
    /// The kind as written in `plan NAME KIND ROBOT { ... }`.
    pub kind: &'static str,
    /// One line for help texts and the docs.
    pub summary: &'static str,
    /// The robots it plans for.
    pub robots: &'static [RobotKind],
    /// Its own parameters (the common ones of SPEC 2.5 come on top).
    pub params: &'static [ParamSpec],
    /// Its own metrics (the common ones of SPEC 3 come on top).
    pub metrics: &'static [MetricSpec],
    /// The `limit` kinds it honours; others are analysis errors.
    pub limits: &'static [&'static str],
    /// Whether a plan must have a `goal`.
    pub needs_goal: bool,
    /// Whether it draws random numbers (from the plan's `seed`): a bench
    /// runs such a planner `runs` times per configuration, others once.
    pub randomized: bool,
    /// Whether it plans in worlds with `grid` obstacles; the analyzer
    /// refuses a plan of a planner that does not in such a world.
    pub grids: bool,
    /// Whether it plans among moving obstacles (SPEC 2.9: it knows time and
    /// returns a trajectory); the analyzer refuses a plan of a planner that
    /// does not in a world with `moving` obstacles.
    pub time: bool,
    /// Reads the validated parameters into the planner's settings. Problems
    /// that involve several parameters, the world or the robot are reported
    /// through [`PlanArgs::error`] with spans; `None` (or any error
    /// reported) means the plan does not run.
    pub check: fn(&mut PlanArgs<'_>) -> Option<Box<dyn Settings>>,
}

impl Planner {
    /// A parameter of this planner, common ones included.
    pub fn param(&self, key: &str) -> Option<&'static ParamSpec> {
        self.all_params().find(|p| p.key == key)
    }

    /// The common parameters, then the planner's own.
    pub fn all_params(&self) -> impl Iterator<Item = &'static ParamSpec> + use<> {
        let own: &'static [ParamSpec] = self.params;
        COMMON_PARAMS.iter().chain(own.iter())
    }

    /// The type of a metric of this planner (common ones included; the
    /// drive metrics are the analyzer's business).
    pub fn metric(&self, name: &str) -> Option<MetricType> {
        self.all_metrics().find(|m| m.name == name).map(|m| m.ty)
    }

    /// The common metrics, a car's (when it plans for cars: reported for
    /// every plan, with no value for a robot that is not a car), a
    /// trajectory's (when it knows time), then the planner's own. A team
    /// planner's are the team metrics, then its own.
    pub fn all_metrics(&self) -> impl Iterator<Item = &'static MetricSpec> + use<> {
        let own: &'static [MetricSpec] = self.metrics;
        let common: &'static [MetricSpec] = if self.plans_teams() {
            TEAM_METRICS
        } else {
            COMMON_METRICS
        };
        let car: &'static [MetricSpec] = if self.plans_for(RobotKind::Car) {
            CAR_METRICS
        } else {
            &[]
        };
        let time: &'static [MetricSpec] = if self.time && !self.plans_teams() {
            TIME_METRICS
        } else {
            &[]
        };
        common.iter().chain(car).chain(time).chain(own.iter())
    }

    /// Whether it plans for teams (SPEC 2.10): then it plans for nothing
    /// else, and its task's [`Task::agents`] are the team's.
    pub fn plans_teams(&self) -> bool {
        self.plans_for(RobotKind::Team)
    }

    /// Whether it plans for robots of this kind.
    pub fn plans_for(&self, robot: RobotKind) -> bool {
        self.robots.contains(&robot)
    }
}

impl fmt::Debug for Planner {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Planner").field("kind", &self.kind).finish()
    }
}

/// One planning problem, as the runner hands it to a planner.
#[derive(Clone, Copy, Debug)]
pub struct Task<'a> {
    pub world: &'a World,
    pub robot: &'a RobotShape,
    pub start: Config,
    /// `None` only for planners that need no goal.
    pub goal: Option<Config>,
    pub limits: Limits,
    pub seed: u64,
    /// How a car robot steers (SPEC 2.4); `None` for other robots.
    pub steering: Option<Steering>,
    /// Whether a sink will draw the outcome's [`layers`](super::layers)
    /// (an SVG or PNG picture, the Rerun viewer). When it will not (a plain
    /// `scen run`, `scen test`, every run of `scen bench`), a planner leaves
    /// its layers empty and skips recording what only they would show
    /// (expansions, tree edges, forces): that work is timed with the plan.
    pub draw: bool,
    /// The runner's referee, lent for what only the validator may say
    /// ([`super::referee`]: a motion too long to return, where a simulated
    /// robot's motion first fails); `None` when the caller lends none.
    pub referee: Option<&'a dyn super::Referee>,
    /// The world's moving obstacles (SPEC 2.9); empty in a static world.
    pub moving: &'a [MovingObstacle],
    /// The robot's largest speed (`speed V`, SPEC 2.9), if it has one.
    pub speed: Option<f64>,
    /// A team plan's agents (SPEC 2.10), each of `robot`'s shape; empty for
    /// one robot. `start` is then the first agent's start.
    pub agents: &'a [crate::contract::Agent],
}

impl Task<'_> {
    /// The robot's motion checker in the task's world: how planners decide
    /// whether a configuration or a straight motion is free. It is the
    /// planners' own, built from the robot's body; the validator, which
    /// judges their answers, stays with the runner (SPEC 3.0).
    pub fn motion_checker(&self) -> crate::geometry::motion::MotionChecker {
        crate::geometry::motion::MotionChecker::new(self.world, self.robot)
    }

    /// A car's checker of steering curves in the task's world (SPEC 2.4),
    /// on the motion checker and the distance query.
    pub fn car_checker(&self) -> crate::geometry::car::CarChecker {
        crate::geometry::car::CarChecker::new(self.world, self.robot)
    }

    /// Whether the start is the goal (SPEC 3: then every planner finds the
    /// path of that one configuration at once): the same (x, y), and for a
    /// robot that rotates the same θ (modulo a turn), exactly, as the
    /// runner's `reaches_goal` would see the start.
    pub fn start_is_goal(&self) -> bool {
        self.goal.is_some_and(|g| {
            let s = self.start;
            s.x == g.x
                && s.y == g.y
                && (!self.robot.rotates() || crate::geometry::angle_diff(s.theta, g.theta) == 0.0)
        })
    }
}

/// A plan's typed settings, built once by its planner's `check`; running
/// the plan is a function of the settings and the [`Task`].
pub trait Settings: fmt::Debug + Send + Sync {
    /// Runs the plan. Planners know nothing of output: they return the path,
    /// their metrics and drawable layers.
    fn plan(&self, task: &Task<'_>) -> PlanOutcome;

    /// For benchmarks and tests that call a planner's own entry points with
    /// its concrete settings.
    fn as_any(&self) -> &dyn Any;
}
