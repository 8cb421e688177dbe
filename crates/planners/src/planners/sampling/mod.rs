//! The sampling-based planners of SPEC 3.7: `rrt`, `rrt_connect`,
//! `rrt_star` ([`rrt`], [`rrt_connect`]), `prm` and `prm_star` ([`prm`]),
//! for point, disk and polygon robots.
//!
//! They share what this module holds: the parameters of SPEC 3.7's table
//! (each planner's schema lists those it takes), the typed [`Sampling`]
//! settings, the configuration [`space`] (the distance, motions, uniform
//! and informed samples), the nearest-neighbour index ([`nn`]), the
//! narrow-passage samplers, path simplification ([`simplify`]) and what a
//! run reports (metrics, notes, layers).
//!
//! # Soundness
//! Every state and motion added to a tree or a roadmap, and every change
//! of the simplifier, is checked by the [`MotionChecker`], which never
//! accepts what the validator rejects; motions are checked in the direction
//! the path will run (a PRM path that runs an edge backwards has that edge
//! checked again that way before it is returned). `collision_checks`
//! counts every call (states and motions, the simplifier's included).
//!
//! # Randomness
//! One [`SplitMix64`] stream per run, seeded by the plan's `seed`, and no
//! parallel work: the same seed and parameters give the same samples, the
//! same tree and the same path, byte for byte. `limit time` makes where a
//! run stops depend on the machine; the report notes it.
//!
//! # Samplers
//! An iteration draws one sample from the plan's `sampler`:
//! - `uniform`: a configuration uniform in `bounds` × [0, 2π);
//! - `gaussian` (Boor et al.): a uniform configuration and a Gaussian
//!   neighbour of it ([`Space::gaussian_near`], deviation [`SIGMA`] × the
//!   bounds' diagonal) inside the bounds; when exactly one of the two is
//!   free, that one;
//! - `bridge` (Hsu et al.): a blocked uniform configuration and a blocked
//!   Gaussian neighbour of it whose midpoint is free: the midpoint.
//!
//! The two narrow-passage samplers try up to [`NARROW_ATTEMPTS`] times per
//! iteration and then give a uniform sample, so an iteration always ends
//! (in a world without narrow places they degrade to `uniform`, at a cost
//! in `collision_checks`).

pub mod nn;
pub mod prm;
pub mod rrt;
pub mod rrt_connect;
pub mod simplify;
pub mod space;

#[cfg(test)]
mod tests;

use std::time::Instant;

use crate::contract::PlanArgs;
use crate::contract::schema::{
    DefaultValue, MetricSpec, ParamSpec, ValueSpec, Word, YesNo, at_least, num,
};
use crate::diagnostics::Diag;
use crate::geometry::car::{CarChecker, CarPath, DRAW_STEP};
use crate::geometry::cspace::ObstaclePieces;
use crate::geometry::motion::{MotionChecker, NewEnd};
use crate::geometry::path::path_length;
use crate::geometry::steer::Steering;
use crate::geometry::validator::{DEFAULT_TOLERANCE, MAX_SUB_STEPS, sub_step_count};
use crate::geometry::{Config, Point, RobotShape, angle_diff, wrap_angle};
use crate::rng::SplitMix64;
use crate::word_enum;

use super::deadline::Deadline;
use crate::contract::layers::{self, Colour, Drawing, Layer, Style, Svg, Timeline};
use crate::contract::{MetricValue, PlanOutcome, Settings, Task};

use nn::KdTree;
pub use space::Space;

word_enum! {
    /// Where an iteration's sample comes from (SPEC 3.7 `sampler`).
    pub enum Sampler {
        Uniform = "uniform",
        Gaussian = "gaussian",
        Bridge = "bridge",
    }
}

word_enum! {
    /// When a planner returns (SPEC 3.7 `stop`).
    pub enum Stop {
        /// With the first solution.
        First = "first",
        /// At the limit, with the best solution found by then.
        Limit = "limit",
    }
}

word_enum! {
    /// What happens to the path once found (SPEC 3.7 `simplify`).
    pub enum Simplify {
        None = "none",
        /// Waypoints removed and random shortcuts.
        Shortcut = "shortcut",
        /// `shortcut`, then B-spline-style corner cutting.
        Smooth = "smooth",
    }
}

/// The five planners, for the code they share.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Algorithm {
    Rrt,
    RrtConnect,
    RrtStar,
    Prm,
    PrmStar,
}

// ------------------------------------------------------------ parameters

/// `range` (every planner).
pub const RANGE: ParamSpec = ParamSpec::positive(
    "range",
    DefaultValue::Derived("0.2 × the diagonal of `bounds`"),
    "longest single extension (`rrt*`) or roadmap edge (`prm*`), in the distance √(dx² + dy² + (c·dθ)²)",
);

/// `turn_cost` (every planner).
pub const TURN_COST: ParamSpec = ParamSpec::new(
    "turn_cost",
    at_least(0.0, false),
    DefaultValue::Derived("R of the robot"),
    "c in the distance √(dx² + dy² + (c·dθ)²), dθ the shorter arc in radians",
);

/// `goal_bias` (`rrt`, `rrt_star`).
pub const GOAL_BIAS: ParamSpec = ParamSpec::new(
    "goal_bias",
    ValueSpec::Fraction { min: 0.0, max: 1.0 },
    num(0.05, "5%"),
    "probability that an iteration samples the goal",
);

/// `sampler` (every planner).
pub const SAMPLER: ParamSpec = ParamSpec::word(
    "sampler",
    Sampler::WORDS,
    "uniform",
    "`uniform`, `gaussian` (free samples near obstacles) or `bridge` (free midpoints of blocked pairs)",
);

/// `neighbors` (`prm`).
pub const NEIGHBORS: ParamSpec = ParamSpec::new(
    "neighbors",
    ValueSpec::Number {
        min: 1.0,
        min_open: false,
        max: 1000.0,
        integer: true,
    },
    num(10.0, "10"),
    "k: each new roadmap state tries to connect to its k nearest",
);

/// `rewire` (`rrt_star`, `prm_star`).
pub const REWIRE: ParamSpec = ParamSpec::new(
    "rewire",
    ValueSpec::Number {
        min: 1.0,
        min_open: false,
        max: 100.0,
        integer: false,
    },
    num(1.1, "1.1"),
    "factor on k = ⌈rewire · e · (1 + 1/d) · ln n⌉ nearest (d = 2, or 3 when θ is sampled)",
);

/// `informed` (`rrt_star`).
pub const INFORMED: ParamSpec = ParamSpec::word(
    "informed",
    YesNo::WORDS,
    "no",
    "once a solution exists, sample only where a shorter path could pass (Gammell et al.)",
);

/// `stop` defaulting to `first`.
pub const STOP_FIRST: ParamSpec = ParamSpec::word(
    "stop",
    Stop::WORDS,
    "first",
    "`first`: return the first solution; `limit`: keep improving until a limit",
);

/// `stop` defaulting to `limit` (the asymptotically optimal planners).
pub const STOP_LIMIT: ParamSpec = ParamSpec::word(
    "stop",
    Stop::WORDS,
    "limit",
    "`first`: return the first solution; `limit`: keep improving until a limit",
);

/// `simplify` (every planner).
pub const SIMPLIFY: ParamSpec = ParamSpec::word(
    "simplify",
    Simplify::WORDS,
    "none",
    "`none`, `shortcut` (drop waypoints, random shortcuts) or `smooth` (`shortcut`, then corner cutting)",
);

/// `rotate` (every planner).
pub const ROTATE: ParamSpec = ParamSpec::new(
    "rotate",
    ValueSpec::Word(YesNo::WORDS),
    DefaultValue::Derived("yes for polygons"),
    "sample θ too; `no`: translate at the start's θ",
);

/// The metrics of every sampling-based planner (SPEC 3.7).
pub const METRICS: &[MetricSpec] = &[
    MetricSpec::num("iterations", "samples drawn"),
    MetricSpec::num("graph_states", "states of the tree(s) or the roadmap"),
    MetricSpec::num("graph_edges", "edges of the tree(s) or the roadmap"),
    MetricSpec::num(
        "collision_checks",
        "states and motions checked, the simplifier's included",
    ),
    MetricSpec::num(
        "first_iteration",
        "the iteration at which the first solution appeared (+∞ without one)",
    ),
    MetricSpec::num(
        "first_cost",
        "the cost of the first solution (+∞ without one)",
    ),
    MetricSpec::num(
        "raw_length",
        "(x, y) length of the path before `simplify` (+∞ without a path)",
    ),
    MetricSpec::num("raw_nodes", "configurations of the path before `simplify`"),
    MetricSpec::num(
        "simplify_ms",
        "wall time of `simplify`, in milliseconds (a timing: varies run to run)",
    ),
];

/// The limits they honour.
pub const LIMITS: &[&str] = &["iterations", "time"];

/// Iterations allowed when the plan sets no `limit iterations`.
pub const DEFAULT_ITERATIONS: u64 = 200_000;

/// The most states a tree or roadmap holds (memory: about 100 bytes each,
/// plus a roadmap's edges); a run reaching it stops as at a limit.
pub const MAX_STATES: usize = 2_000_000;

/// The Gaussian samplers' deviation, as a fraction of the bounds' diagonal.
pub const SIGMA: f64 = 0.05;

/// Tries of a narrow-passage sampler per iteration before a uniform sample.
pub const NARROW_ATTEMPTS: usize = 100;

/// The most tree or roadmap edges drawn (in 2D, and again in (x, y, θ)).
pub const MAX_DRAWN_EDGES: usize = 50_000;

/// θ layers of the C-space drawn for a rotating robot.
pub const CSPACE_LAYERS: usize = 24;

/// The arc length between the drawn points of a car's tree or roadmap edge.
const CAR_EDGE_STEP: f64 = 0.25;

/// The time limit is looked at every this many iterations.
const CLOCK_EVERY: u64 = 16;

// ------------------------------------------------------------ settings

/// The settings of a sampling-based plan.
#[derive(Clone, Debug, PartialEq)]
pub struct Sampling {
    pub algorithm: Algorithm,
    /// θ is sampled (a polygon robot without `rotate no`).
    pub rotating: bool,
    pub range: f64,
    pub turn_cost: f64,
    /// 0 for the planners without `goal_bias`.
    pub goal_bias: f64,
    pub sampler: Sampler,
    /// k of `prm`.
    pub neighbors: usize,
    /// The factor on k of `rrt_star` and `prm_star`.
    pub rewire: f64,
    pub informed: bool,
    pub stop: Stop,
    pub simplify: Simplify,
}

/// Reads a plan's parameters into [`Sampling`] for `algorithm` (the
/// `check` of each of the five planners).
pub fn check(args: &mut PlanArgs<'_>, algorithm: Algorithm) -> Option<Box<dyn Settings>> {
    let planner = args.planner();
    let declares = |key: &str| planner.param(key).is_some();
    let shape = &args.robot.shape;
    let car = args.robot.steering.is_some();
    if car {
        refuse_for_cars(args, algorithm);
    }
    // A car always has a heading: θ is sampled whatever its shape.
    let rotating = car || (shape.rotates() && args.opt_word::<YesNo>("rotate") != Some(YesNo::No));
    let bounds = args.world.bounds;
    let range = args
        .opt_num("range")
        .unwrap_or(0.2 * bounds.width().hypot(bounds.height()));
    let turn_cost = if car {
        0.0
    } else {
        args.opt_num("turn_cost").unwrap_or_else(|| shape.radius())
    };
    if shape.rotates()
        && !rotating
        && let Some(goal) = args.params.goal
        && angle_diff(args.params.start.theta, goal.theta).abs() > 1e-12
    {
        let span = args.params.goal_span.unwrap_or(args.head);
        args.error(
            Diag::error(
                "scen::analyze::goal_theta",
                "with `rotate no` the robot keeps the start's θ, and the goal's differs",
            )
            .at(span, "a different θ")
            .help(format!(
                "give the goal the start's θ ({}deg), or let the robot rotate",
                args.params.start.theta.to_degrees()
            )),
        );
    }
    let settings = Sampling {
        algorithm,
        rotating,
        range,
        turn_cost,
        goal_bias: if declares("goal_bias") {
            args.num("goal_bias")
        } else {
            0.0
        },
        sampler: args.word("sampler"),
        neighbors: if declares("neighbors") {
            args.num("neighbors") as usize
        } else {
            0
        },
        rewire: if declares("rewire") {
            args.num("rewire")
        } else {
            1.0
        },
        informed: declares("informed") && args.word::<YesNo>("informed") == YesNo::Yes,
        stop: args.word("stop"),
        simplify: args.word("simplify"),
    };
    Some(Box::new(settings))
}

/// The parameters and planners that have no meaning for a car (a located
/// error each): `turn_cost` and `rotate` (its distance is the steering
/// length, its θ always sampled), `informed yes` (the informed set is that
/// of the Euclidean distance in (x, y, c·θ)), and a Dubins car on `prm` or
/// `prm_star` (a roadmap's edges run both ways; a Dubins path does not).
fn refuse_for_cars(args: &mut PlanArgs<'_>, algorithm: Algorithm) {
    for key in ["turn_cost", "rotate"] {
        if args.given(key) {
            let span = args.span(key);
            args.error(
                Diag::error(
                    "scen::analyze::car_param",
                    format!("`{key}` has no meaning for a car"),
                )
                .at(span, "a car robot")
                .help("a car's distance is the length of its steering path and its θ is always sampled; remove the parameter"),
            );
        }
    }
    if args.planner().param("informed").is_some()
        && args.opt_word::<YesNo>("informed") == Some(YesNo::Yes)
    {
        let span = args.span("informed");
        args.error(
            Diag::error(
                "scen::analyze::car_param",
                "`informed yes` is not implemented for cars",
            )
            .at(span, "a car robot")
            .help("remove `informed yes`: informed sampling needs the Euclidean distance, and a car's is its steering length"),
        );
    }
    if args.opt_word::<Simplify>("simplify") == Some(Simplify::Smooth) {
        let span = args.span("simplify");
        args.error(
            Diag::error(
                "scen::analyze::car_param",
                "`simplify smooth` is not implemented for cars",
            )
            .at(span, "a car robot")
            .help("use `simplify shortcut`: corner cutting moves waypoints in straight lines, which a car's paths turn into cusps"),
        );
    }
    let dubins = args
        .robot
        .steering
        .is_some_and(|s| s.model == crate::geometry::steer::Model::Dubins);
    if dubins && matches!(algorithm, Algorithm::Prm | Algorithm::PrmStar) {
        let head = args.head;
        args.error(
            Diag::error(
                "scen::analyze::car_param",
                format!(
                    "`{}` needs a car that drives both ways: a roadmap's edges are travelled in either direction",
                    args.planner().kind
                ),
            )
            .at(head, "a Dubins car (forward only)")
            .help("plan a Dubins car with `rrt`, `rrt_connect`, `rrt_star`, `hybrid_astar` or `steer`, or make it `steer reeds_shepp`"),
        );
    }
}

impl Settings for Sampling {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        let mut run = Run::new(self, task);
        if task.start_is_goal() {
            // Found at once (SPEC 3): nothing is sampled, nothing built.
            let grown = Grown {
                path: Some(vec![task.start]),
                iterations: 0,
                ended: Ended::Solved,
                first_iteration: Some(0),
                first_cost: Some(0.0),
                states: 0,
                edges: 0,
                drawn: Vec::new(),
                entity: match self.algorithm {
                    Algorithm::Prm | Algorithm::PrmStar => "graph",
                    _ => "tree",
                },
            };
            return run.finish(grown);
        }
        let grown = match self.algorithm {
            Algorithm::Rrt | Algorithm::RrtStar => rrt::grow(&mut run),
            Algorithm::RrtConnect => rrt_connect::grow(&mut run),
            Algorithm::Prm | Algorithm::PrmStar => prm::grow(&mut run),
        };
        run.finish(grown)
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}

/// k = ⌈rewire · e · (1 + 1/d) · ln n⌉ of SPEC 3.7 for `n` states, at
/// least 1.
pub fn k_nearest_count(rewire: f64, dims: usize, n: usize) -> usize {
    let ln = (n.max(1) as f64).ln();
    let k = (rewire * std::f64::consts::E * (1.0 + 1.0 / dims as f64) * ln).ceil();
    (k as usize).max(1)
}

// ------------------------------------------------------------ a run

/// Why a run stopped growing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ended {
    /// `stop first` and a solution.
    Solved,
    /// The iteration limit.
    Iterations,
    /// `limit time`.
    Time,
    /// [`MAX_STATES`].
    States,
}

/// One edge for the picture: its ends and the iteration that added it.
#[derive(Clone, Copy, Debug)]
pub struct DrawnEdge {
    pub a: Config,
    pub b: Config,
    pub iteration: u64,
}

/// What a planner's growth left: the raw path, the counts, the graph.
#[derive(Clone, Debug)]
pub struct Grown {
    /// Start to goal (both exactly), before simplification.
    pub path: Option<Vec<Config>>,
    pub iterations: u64,
    pub ended: Ended,
    pub first_iteration: Option<u64>,
    pub first_cost: Option<f64>,
    pub states: usize,
    pub edges: usize,
    /// Edges to draw, in the order they appeared (at most
    /// [`MAX_DRAWN_EDGES`]).
    pub drawn: Vec<DrawnEdge>,
    /// `tree` or `graph` (SPEC §6).
    pub entity: &'static str,
}

/// A plan in progress: the settings, the space, the motion checker, the
/// random stream and the counters every planner keeps.
pub struct Run<'a> {
    pub settings: &'a Sampling,
    pub task: &'a Task<'a>,
    pub space: Space,
    pub checker: MotionChecker,
    pub rng: SplitMix64,
    pub start: Config,
    /// The goal with θ that of the space for a robot that does not rotate;
    /// the path ends at the task's goal itself.
    pub goal: Config,
    pub max_iterations: u64,
    /// Calls of the motion checker.
    pub checks: u64,
    deadline: Deadline,
    sigma: f64,
    /// A car's motions are checked along their curves.
    car: Option<CarChecker>,
}

impl<'a> Run<'a> {
    pub fn new(settings: &'a Sampling, task: &'a Task<'a>) -> Self {
        // Before the set-up (the motion checker), which `limit time` counts.
        let deadline = Deadline::start(&task.limits);
        let bounds = task.world.bounds;
        let space = Space {
            bounds,
            rotating: settings.rotating,
            theta: task.start.theta,
            turn_cost: settings.turn_cost,
            steering: task.steering,
        };
        let goal = task.goal.unwrap_or(task.start);
        let goal = if settings.rotating {
            goal
        } else {
            Config::new(goal.x, goal.y, task.start.theta)
        };
        Run {
            settings,
            task,
            space,
            checker: task.motion_checker(),
            rng: SplitMix64::new(task.seed),
            start: task.start,
            goal,
            max_iterations: task.limits.iterations.unwrap_or(DEFAULT_ITERATIONS),
            checks: 0,
            deadline,
            sigma: SIGMA * bounds.width().hypot(bounds.height()),
            car: task.steering.map(|_| task.car_checker()),
        }
    }

    /// Whether the robot at `c` is free (counted).
    pub fn config_free(&mut self, c: Config) -> bool {
        self.checks += 1;
        self.checker.config_free(c)
    }

    /// Whether the motion from `a` to `b` is free, in that direction
    /// (counted).
    pub fn motion_free(&mut self, a: Config, b: Config) -> bool {
        self.motion(a, b, None)
    }

    /// [`Run::motion_free`] for a motion whose `new` end is a state not
    /// checked yet (the same verdict; that state is tested first).
    pub fn extension_free(&mut self, a: Config, b: Config, new: NewEnd) -> bool {
        self.motion(a, b, Some(new))
    }

    fn motion(&mut self, a: Config, b: Config, new: Option<NewEnd>) -> bool {
        self.checks += 1;
        match (self.space.steering, &self.car, new) {
            (Some(steering), Some(car), _) => car.path_free(&CarPath::shortest(steering, a, b)),
            (_, _, Some(new)) => self.checker.extension_free(a, b, new),
            (_, _, None) => self.checker.motion_free(a, b),
        }
    }

    /// The `k` states nearest to `q` in the space's distance into `out`, as
    /// (squared distance, index), nearest first, ties to the lower index.
    /// `state(i)` is state `i` of `index`. `to_q`: the distance from each
    /// state to `q` (a tree growing towards `q`), else from `q` to each
    /// (they differ for a Dubins car only).
    ///
    /// Without steering this is the index's own query. For a car the index
    /// holds the reference points: their Euclidean distance bounds every
    /// steering length from below, so the states are measured nearest by it
    /// first until one is farther by it than the k-th length found; a state
    /// whose heading change alone (at the turning radius) is farther is
    /// passed over unmeasured ([`nn::k_nearest_bounded`]).
    pub fn k_nearest(
        &self,
        index: &mut KdTree,
        state: impl Fn(usize) -> Config,
        q: Config,
        k: usize,
        to_q: bool,
        out: &mut Vec<(f64, u32)>,
    ) {
        let key = self.space.key(q);
        let Some(steering) = self.space.steering else {
            index.k_nearest(&key, k, out);
            return;
        };
        let turn = |i: usize| steering.turn_bound(state(i), q);
        nn::k_nearest_bounded(index, &key, k, out, turn, |i| {
            let c = state(i);
            if to_q {
                self.space.distance(c, q)
            } else {
                self.space.distance(q, c)
            }
        });
    }

    /// The state nearest to `q` (see [`Run::k_nearest`]) and its squared
    /// distance.
    pub fn nearest(
        &self,
        index: &mut KdTree,
        state: impl Fn(usize) -> Config,
        q: Config,
        to_q: bool,
    ) -> Option<(usize, f64)> {
        if self.space.steering.is_none() {
            return index.nearest(&self.space.key(q));
        }
        let mut out = Vec::with_capacity(1);
        self.k_nearest(index, state, q, 1, to_q, &mut out);
        out.first().map(|&(d2, i)| (i as usize, d2))
    }

    /// Why the run must stop before `iteration` (1-based), if it must.
    pub fn should_stop(&self, iteration: u64, states: usize) -> Option<Ended> {
        if iteration > self.max_iterations {
            return Some(Ended::Iterations);
        }
        self.should_stop_within(iteration, states)
    }

    /// Why a loop must stop before its `step`-th step (1-based), if it
    /// must, iterations aside: the state cap, or the time limit (read at
    /// step 1 and every [`CLOCK_EVERY`] steps after). The iterations' loop
    /// ([`Run::should_stop`]) and a loop inside one iteration (RRT-Connect's
    /// greedy connection, which may take many steps towards a far state).
    pub fn should_stop_within(&self, step: u64, states: usize) -> Option<Ended> {
        if states >= MAX_STATES {
            return Some(Ended::States);
        }
        if step % CLOCK_EVERY == 1 && self.deadline.passed() {
            return Some(Ended::Time);
        }
        None
    }

    /// Whether the plan's `limit time` is up.
    pub fn time_up(&self) -> bool {
        self.deadline.passed()
    }

    /// The nearest-neighbour index for this space.
    pub fn index(&self) -> KdTree {
        KdTree::new(self.space.dims(), self.space.period())
    }

    /// k of `rrt_star` and `prm_star` for `n` states.
    pub fn k_star(&self, n: usize) -> usize {
        k_nearest_count(self.settings.rewire, self.space.dims(), n)
    }

    /// One sample of the plan's sampler (see the module documentation).
    pub fn sample(&mut self) -> Config {
        match self.settings.sampler {
            Sampler::Uniform => {}
            Sampler::Gaussian => {
                for _ in 0..NARROW_ATTEMPTS {
                    let a = self.space.uniform(&mut self.rng);
                    let b = self.space.gaussian_near(a, self.sigma, &mut self.rng);
                    if !self.space.bounds.contains(b.xy()) {
                        continue;
                    }
                    match (self.config_free(a), self.config_free(b)) {
                        (true, false) => return a,
                        (false, true) => return b,
                        _ => {}
                    }
                }
            }
            Sampler::Bridge => {
                for _ in 0..NARROW_ATTEMPTS {
                    let a = self.space.uniform(&mut self.rng);
                    let b = self.space.gaussian_near(a, self.sigma, &mut self.rng);
                    if !self.space.bounds.contains(b.xy()) || self.config_free(a) {
                        continue;
                    }
                    if self.config_free(b) {
                        continue;
                    }
                    let m = self.space.interpolate(a, b, 0.5);
                    if self.config_free(m) {
                        return m;
                    }
                }
            }
        }
        self.space.uniform(&mut self.rng)
    }

    /// The path's cost: its length in the distance of SPEC 3.7.
    pub fn cost(&self, path: &[Config]) -> f64 {
        path.windows(2)
            .map(|w| self.space.distance(w[0], w[1]))
            .sum()
    }

    /// The path with the task's exact start and goal at its ends.
    pub fn exact_ends(&self, mut path: Vec<Config>) -> Vec<Config> {
        if let Some(first) = path.first_mut() {
            *first = self.task.start;
        }
        if let (Some(last), Some(goal)) = (path.last_mut(), self.task.goal) {
            *last = goal;
        }
        path
    }

    /// Simplifies the raw path and writes the outcome: metrics, notes and
    /// layers.
    fn finish(mut self, grown: Grown) -> PlanOutcome {
        use MetricValue::Num;
        let mut out = PlanOutcome {
            expanded: grown.iterations,
            ..PlanOutcome::default()
        };
        let (raw_length, raw_nodes) = grown.path.as_ref().map_or((f64::INFINITY, 0.0), |p| {
            // A car's length is its steering paths' (the reference point's
            // arc length), not the polyline's.
            let length = if self.space.steering.is_some() {
                self.cost(p)
            } else {
                path_length(p)
            };
            (length, p.len() as f64)
        });
        let began = Instant::now();
        let mut simplify_stopped = false;
        let path = grown.path.clone().map(|raw| match self.settings.simplify {
            Simplify::None => raw,
            how => {
                let (p, stopped) = simplify::simplify(&mut self, raw, how == Simplify::Smooth);
                simplify_stopped = stopped;
                self.exact_ends(p)
            }
        });
        let simplify_ms = if self.settings.simplify == Simplify::None || path.is_none() {
            0.0
        } else {
            (began.elapsed().as_secs_f64() * 1e6).round() / 1e3
        };
        let inf = f64::INFINITY;
        for (name, value) in [
            ("iterations", grown.iterations as f64),
            ("graph_states", grown.states as f64),
            ("graph_edges", grown.edges as f64),
            ("collision_checks", self.checks as f64),
            (
                "first_iteration",
                grown.first_iteration.map_or(inf, |i| i as f64),
            ),
            ("first_cost", grown.first_cost.unwrap_or(inf)),
            ("raw_length", raw_length),
            ("raw_nodes", raw_nodes),
            ("simplify_ms", simplify_ms),
        ] {
            out.extra.insert(name.into(), Num(value));
        }
        if self.task.limits.time.is_some() {
            out.notes.push(
                "`limit time`: where the run stopped, and so its result, depends on the machine's speed"
                    .into(),
            );
        }
        if simplify_stopped {
            out.notes.push(
                "the time limit stopped `simplify`: the path is simplified as far as it got".into(),
            );
        }
        if grown.path.is_none() {
            // Every motion of a car is a steering path: none joins poses
            // too many turning radii apart (a radius tiny for the world).
            if let Some(steering) = self.space.steering
                && !self.space.distance(self.start, self.goal).is_finite()
            {
                out.notes.push(steering.too_far_note());
            }
            out.gave_up = true;
            out.notes.push(match grown.ended {
                Ended::Time => "the time limit was reached without a path".into(),
                Ended::States => {
                    format!("the graph reached its cap of {MAX_STATES} states without a path")
                }
                Ended::Iterations | Ended::Solved => format!(
                    "the iteration limit ({}) was reached without a path",
                    grown.iterations
                ),
            });
        } else if grown.ended == Ended::States {
            out.notes.push(format!(
                "the graph reached its cap of {MAX_STATES} states: the path is the best found by then"
            ));
        }
        if self.task.draw {
            out.layers = self.layers(&grown, path.as_deref());
        }
        out.cost = path.as_deref().map(|p| self.cost(p));
        match (self.space.steering, path) {
            (Some(steering), Some(states)) => self.car_path(steering, &states, &mut out),
            // A path the validator would not sweep (rotating motions across
            // a vast world) is not returned as found.
            (None, Some(states))
                if sub_step_count(self.task.robot, &states, DEFAULT_TOLERANCE) > MAX_SUB_STEPS =>
            {
                out.cost = None;
                out.notes.push(format!(
                    "the path found needs more than {MAX_SUB_STEPS} sub-steps to validate at tolerance {DEFAULT_TOLERANCE} (long rotating motions: the world is large for the robot); no path is returned"
                ));
            }
            (_, path) => out.path = path,
        }
        out
    }

    /// A car's path from its states: the steering path between each two,
    /// as segments integrated from the start (`out.car`) and the poses
    /// drawn (`out.path`), the last the goal exactly. Each motion was
    /// checked from the state the planner held; the whole, integrated in
    /// closed form, is checked again: a path that fails (rounding at a
    /// touching contact) is not returned, and a note says so.
    fn car_path(&self, steering: Steering, states: &[Config], out: &mut PlanOutcome) {
        let car = CarPath::through(self.task.start, steering, states);
        let checker = self.car.as_ref().expect("a car's run has a car checker");
        let on_goal = self.task.goal.is_none_or(|g| car.ends_on(g));
        if checker.path_free(&car) && on_goal {
            let mut poses = car.poses(DRAW_STEP);
            if let (Some(last), Some(goal)) = (poses.last_mut(), self.task.goal) {
                *last = goal;
            }
            out.path = Some(poses);
            out.car = Some(car);
        } else {
            out.cost = None;
            out.notes.push(
                "the path found failed the motion check when integrated whole (a touching contact, to rounding); no path is returned".into(),
            );
        }
    }

    /// The picture (SPEC §6): the tree or roadmap growing on timeline
    /// `iteration` in at most [`layers::BATCHES`] pieces (`tree/NNNN`,
    /// `graph/NNNN`; lightly in the SVG), for a rotating robot the same in
    /// (x, y, θ) (`cspace/tree`) and the C-space layers, and the raw path
    /// when it was simplified (`raw_path`, dashed in the SVG).
    fn layers(&self, grown: &Grown, path: Option<&[Config]>) -> Vec<Layer> {
        let mut out = Vec::new();
        let drawn = &grown.drawn;
        if !drawn.is_empty() {
            let key = if grown.entity == "graph" {
                "roadmap edges"
            } else {
                "tree edges"
            };
            let style = Style::new(Colour::Faint, 0.5, 16.0).svg(Svg::line(0.3).key(key));
            let batch = drawn.len().div_ceil(layers::BATCHES);
            for (b, chunk) in drawn.chunks(batch).enumerate() {
                let drawing = match self.space.steering {
                    // A car's edges are its curves.
                    Some(steering) => Drawing::Polylines(
                        chunk
                            .iter()
                            .map(|e| {
                                CarPath::shortest(steering, e.a, e.b)
                                    .poses(CAR_EDGE_STEP)
                                    .iter()
                                    .map(Config::xy)
                                    .collect()
                            })
                            .collect(),
                    ),
                    None => Drawing::Segments(chunk.iter().map(|e| (e.a.xy(), e.b.xy())).collect()),
                };
                let last = chunk.last().map_or(0, |e| e.iteration);
                out.push(
                    Layer::new(format!("{}/{b:04}", grown.entity), drawing, style)
                        .at(Timeline::Iteration, last as i64),
                );
            }
        }
        if self.space.rotating && self.space.steering.is_none() {
            let strips = drawn.iter().flat_map(|e| cspace_edge(e.a, e.b)).collect();
            out.push(Layer::new(
                "cspace/tree",
                Drawing::Polylines3D(strips),
                Style::new(Colour::Faint, 0.0, 16.0),
            ));
            if let RobotShape::Polygon(robot) = self.task.robot {
                let c_layers = ObstaclePieces::new(self.task.world).layers(robot, CSPACE_LAYERS);
                out.extend(layers::cspace(self.task.world, &c_layers));
            }
        }
        if self.settings.simplify != Simplify::None
            && let (Some(raw), Some(_)) = (&grown.path, path)
        {
            let xy: Vec<Point> = match self.space.steering {
                Some(steering) => CarPath::through(raw[0], steering, raw)
                    .poses(DRAW_STEP)
                    .iter()
                    .map(Config::xy)
                    .collect(),
                None => raw.iter().map(Config::xy).collect(),
            };
            out.push(Layer::new(
                "raw_path",
                Drawing::Polylines(vec![xy]),
                Style::new(Colour::Plan, 1.0, 25.0)
                    .svg(Svg::line(0.6).dashed().key("path before simplifying")),
            ));
        }
        out
    }
}

/// The motion from `a` to `b` in (x, y, θ) for the viewer: one strip, or
/// two where θ crosses 2π (θ along the shorter arc, in [0, 2π)).
fn cspace_edge(a: Config, b: Config) -> Vec<Vec<[f64; 3]>> {
    let ta = wrap_angle(a.theta);
    let d = angle_diff(a.theta, b.theta);
    let tb = ta + d;
    let tau = std::f64::consts::TAU;
    let cross = if tb >= tau {
        Some(tau)
    } else if tb < 0.0 {
        Some(0.0)
    } else {
        None
    };
    match cross {
        None => vec![vec![[a.x, a.y, ta], [b.x, b.y, tb]]],
        Some(edge) => {
            let t = if d == 0.0 { 0.0 } else { (edge - ta) / d };
            let (x, y) = (a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
            let other = tau - edge;
            vec![
                vec![[a.x, a.y, ta], [x, y, edge]],
                vec![[x, y, other], [b.x, b.y, tb - edge + other]],
            ]
        }
    }
}

/// The edges to draw: the first [`MAX_DRAWN_EDGES`].
pub fn keep_drawn(drawn: &mut Vec<DrawnEdge>, edge: DrawnEdge) {
    if drawn.len() < MAX_DRAWN_EDGES {
        drawn.push(edge);
    }
}
