//! `online` (SPEC 3.2, SEEDS.md §C): a point or disk robot navigating a
//! world it does not know, on the (x, y) lattice of `astar`.
//!
//! The true map is `astar`'s [`GridLattice`] for the same robot (the same
//! free points and the same validated edges). The robot's belief is another
//! lattice of the same shape on which every point is free and every edge
//! open until sensed ([`GridLattice::optimistic`]). At the start and after
//! each move the robot senses every lattice point within `sense` cells
//! (Chebyshev distance): the point's true state, and the true state of each
//! edge between two sensed points. Since `sense` ≥ 1, every edge out of the
//! robot's point is known when it moves, so every executed move is an edge
//! of the true lattice and the trajectory passes the validator.
//!
//! Strategies:
//! - `backtrack` / `shortcut`: A* ([`search_with`]) on the belief, the robot
//!   walking to each node before it is expanded (all the way back to the
//!   start and down again, or only up to the deepest common ancestor).
//!   Since an expanded node's neighbourhood is sensed before it is
//!   relaxed, the expansions are those of offline A* on the true map.
//! - `replan`: A* from the robot's point on the belief; follow the plan
//!   until something sensed blocks its remainder, then plan again.
//! - `dstar_lite`: D* Lite (Koenig & Likhachev 2002, the optimized version
//!   with the key modifier km), repairing the plan after each sensing step
//!   that changed an edge cost.
//!
//! Unknown points are believed free, so costs only ever increase; when the
//! belief proves the goal unreachable every strategy stops with no path.

use std::any::Any;

use crate::contract::schema::{MetricSpec, ParamSpec, RobotKind, Word, at_least, num};
use crate::contract::{Limits, PlanArgs};
use crate::diagnostics::Diag;
use crate::geometry::collide::ObstacleIndex;
use crate::geometry::{Aabb, Config, Point, RobotShape};
use crate::word_enum;

use super::deadline::{Deadline, setup_note};
use super::grid_lattice::{
    CostMetric, GridLattice, Heuristic, SearchBuffers, SearchConfig, grown_obstacles, lattice_path,
    search, search_with, snap_ends, step_costs,
};
use super::lattice::{BitSet, LATTICE_PARAMS, LatticeSpec, check_connect, check_lattice};
use super::search::Tree;
use crate::contract::layers::{self, Colour, Drawing, Layer, Style, Svg, Timeline};
use crate::contract::{Planner, Settings, Task};

mod dstar_lite;
use crate::contract::{MetricValue, PlanOutcome};
use dstar_lite::dstar_lite;

/// `online` in the registry.
pub static PLANNER: Planner = Planner {
    kind: "online",
    summary: "navigation in an unknown world",
    robots: &[RobotKind::Point, RobotKind::Disk],
    params: &[
        LATTICE_PARAMS[0],
        LATTICE_PARAMS[1],
        LATTICE_PARAMS[2],
        ParamSpec::word(
            "strategy",
            Strategy::WORDS,
            "replan",
            "how the robot explores",
        ),
        ParamSpec::new(
            "sense",
            at_least(1.0, true),
            num(1.0, "1"),
            "sensing range in cells (Chebyshev)",
        ),
        ParamSpec::word(
            "heuristic",
            Heuristic::WORDS,
            "lattice",
            "the searches' heuristic: `lattice` (the exact obstacle-free lattice cost), `metric` (the Euclidean distance; not for `dstar_lite`) or `zero`",
        ),
    ],
    metrics: &[
        MetricSpec::num("traveled", "length of the motion actually executed"),
        MetricSpec::num("steps", "lattice moves executed"),
        MetricSpec::num(
            "replans",
            "searches run (A* runs, or D* Lite's ComputeShortestPath calls)",
        ),
        MetricSpec::num("sensed", "lattice points observed"),
    ],
    limits: &["expansions", "steps", "time", "cells"],
    needs_goal: true,
    randomized: false,
    grids: true,
    time: false,
    check,
};

word_enum! {
    /// How the robot explores (SPEC 3.2 `strategy`).
    pub enum Strategy {
        Backtrack = "backtrack",
        Shortcut = "shortcut",
        Replan = "replan",
        DStarLite = "dstar_lite",
    }
}

/// The settings of an `online` plan.
#[derive(Clone, Debug)]
pub struct Online {
    pub lattice: LatticeSpec,
    /// 4 or 8.
    pub connect: u8,
    pub strategy: Strategy,
    /// Sensing range in cells (Chebyshev), at least 1.
    pub sense: usize,
    /// The heuristic of the A* strategies; D* Lite takes `lattice` (its
    /// exact keys) or `zero`.
    pub heuristic: Heuristic,
}

fn check(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    let connect = check_connect(args, false);
    let lattice = check_lattice(args, 1.0)?;
    let strategy = args.word("strategy");
    let heuristic = args.word("heuristic");
    if strategy == Strategy::DStarLite && heuristic == Heuristic::Metric {
        let span = args.span("heuristic");
        args.error(
            Diag::error(
                "scen::analyze::out_of_range",
                "`dstar_lite` does not take `heuristic metric`",
            )
            .at(span, "not with `strategy dstar_lite`")
            .help(
                "D* Lite compares exact lattice lengths (a + b·√2): use `heuristic lattice` (the default) or `zero`",
            ),
        );
        return None;
    }
    Some(Box::new(Online {
        lattice,
        connect: connect?,
        strategy,
        sense: args.num("sense").clamp(1.0, 1e9) as usize,
        heuristic,
    }))
}

impl Settings for Online {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        // The trace (what the robot knew and planned, step by step) only
        // for a sink that draws it.
        let options = Options {
            traced: task.draw,
            ..Options::default()
        };
        navigate(task, self, options)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// The most points the trace keeps in each of its lists (sensed points,
/// plans summed over steps, expansions summed over searches). Beyond it
/// later steps are left out of the picture (with a note), not the run.
pub const MAX_TRACED_POINTS: usize = 2_000_000;

/// The most moves a run makes when no smaller `limit steps` is given: the
/// executed trajectory is kept in memory (`backtrack` on a large map would
/// otherwise walk billions of steps).
pub const MAX_STEPS: u64 = 4_000_000;

/// How [`navigate`] runs, beyond the plan's parameters (for benchmarks).
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Fill the trace (its plans cost a walk along the plan per step).
    pub traced: bool,
    /// Use the heuristics (`false`: h = 0 in A* and in D* Lite, to compare
    /// the two searches without their different heuristics).
    pub heuristic: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            traced: true,
            heuristic: true,
        }
    }
}

/// Runs an `online` plan with the given options.
pub fn navigate(task: &Task<'_>, settings: &Online, options: Options) -> PlanOutcome {
    let (mut out, log) = navigate_logged(task, settings, options);
    if let Some(log) = log {
        out.layers.extend(knowledge_layers(&log));
    }
    out
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

/// The most batches sensed cells are drawn in: each batch is an entity of
/// its own (`known/free/B`, `known/blocked/B`), logged at the step where it
/// starts, so at step k the viewer shows everything sensed up to k without
/// sending cells again.
const SENSE_BATCHES: usize = 100;

/// The robot's knowledge and plans on timeline `step`: the cells it sensed
/// (`known/free/B`, `known/blocked/B`, cumulative by batches) and the plan
/// it held (`plan`, logged whenever it changes).
fn knowledge_layers(log: &OnlineTrace) -> Vec<Layer> {
    let mut out = Vec::new();
    let batch = log.sensed.len().div_ceil(SENSE_BATCHES).max(1);
    let half = log.cell / 2.0;
    for (b, chunk) in log.sensed.chunks(batch).enumerate() {
        let first = (b * batch) as i64;
        for (blocked, label) in [(false, "free"), (true, "blocked")] {
            let boxes: Vec<Aabb> = chunk
                .iter()
                .flatten()
                .filter(|(_, is_blocked)| *is_blocked == blocked)
                .map(|(p, _)| {
                    Aabb::from_corners(
                        Point::new(p.x - half, p.y - half),
                        Point::new(p.x + half, p.y + half),
                    )
                })
                .collect();
            if boxes.is_empty() {
                continue;
            }
            let style = if blocked {
                Style::new(Colour::Blocked, 0.0, 12.0)
                    .svg(Svg::fill(0.6).key("cells found blocked"))
            } else {
                Style::new(Colour::Free, 0.0, 2.0)
            };
            out.push(
                Layer::new(
                    format!("known/{label}/{b:04}"),
                    Drawing::Boxes(boxes),
                    style,
                )
                .at(Timeline::Step, first),
            );
        }
    }
    let mut previous: Option<&Vec<Point>> = None;
    for (step, plan) in log.plans.iter().enumerate() {
        if previous == Some(plan) {
            continue;
        }
        previous = Some(plan);
        out.push(
            Layer::new(
                "plan",
                Drawing::Polylines(vec![plan.clone()]),
                Style::new(Colour::Plan, 1.0, 25.0),
            )
            .at(Timeline::Step, step as i64),
        );
    }
    out
}

/// [`navigate`], returning what the robot knew step by step instead of
/// drawing it (when `options.traced`).
pub fn navigate_logged(
    task: &Task<'_>,
    settings: &Online,
    options: Options,
) -> (PlanOutcome, Option<OnlineTrace>) {
    let world = task.world;
    let traced = options.traced;
    let radius = match task.robot {
        RobotShape::Point => 0.0,
        RobotShape::Disk(r) => *r,
        RobotShape::Polygon(_) => {
            let out = PlanOutcome {
                notes: vec!["`online` takes point and disk robots".into()],
                ..PlanOutcome::default()
            };
            return (out, None);
        }
    };
    let deadline = Deadline::start(&task.limits);
    let spec = settings.lattice;
    let mut out = PlanOutcome::default();
    // What a run that never moves reports (replaced below by a run's own).
    for m in ["traveled", "steps", "replans", "sensed"] {
        out.extra.insert(m.into(), MetricValue::Num(0.0));
    }
    if traced {
        out.layers
            .extend(layers::grown_by_disk(grown_obstacles(world, radius)));
    }
    if task.start_is_goal() {
        let out = PlanOutcome {
            extra: out.extra,
            layers: out.layers,
            ..PlanOutcome::at_goal(task.start)
        };
        // One step, the robot at the start: nothing sensed, no plan.
        let trace = traced.then(|| OnlineTrace {
            cell: spec.cell,
            sensed: vec![Vec::new()],
            plans: vec![Vec::new()],
        });
        return (out, trace);
    }
    let index = ObstacleIndex::new(world);
    let Some(truth) = GridLattice::build_until(spec, &index, radius, &deadline) else {
        out.gave_up = true;
        out.notes.push(setup_note("classifying the lattice"));
        return (out, None);
    };
    let start = task.start;
    let goal = task.goal.unwrap_or(start);
    let (s_node, g_node) = match snap_ends(&truth, &index, start, goal) {
        Ok(ends) => ends,
        Err(note) => {
            out.notes.push(note);
            return (out, None);
        }
    };
    let heuristic = if options.heuristic {
        settings.heuristic
    } else {
        Heuristic::Zero
    };
    let cfg = SearchConfig::new(
        settings.connect,
        CostMetric::Euclid,
        1.0,
        heuristic,
        task.limits,
    );
    let range = settings.sense;
    let mut rover = Rover::new(truth, &index, cfg, range, s_node, traced, deadline);
    let mut belief = GridLattice::optimistic(spec, radius);
    rover.sense(&mut belief);
    let end = match settings.strategy {
        Strategy::Backtrack => explore(&mut rover, &mut belief, g_node, false),
        Strategy::Shortcut => explore(&mut rover, &mut belief, g_node, true),
        Strategy::Replan => replan(&mut rover, &mut belief, g_node),
        Strategy::DStarLite => dstar_lite(&mut rover, &mut belief, g_node),
    };
    let (s_pt, g_pt) = (spec.point_of(s_node), spec.point_of(g_node));
    let mut traveled = cfg.cost.between(start.xy(), s_pt) + rover.traveled;
    match end {
        End::Reached => {
            traveled += cfg.cost.between(g_pt, goal.xy());
            out.path = Some(lattice_path(&spec, &rover.walk, start, goal));
            out.cost = Some(traveled);
        }
        End::Unreachable => {
            out.trajectory = walked(&spec, &rover.walk, start);
            out.notes
                .push("the goal is unreachable: the sensed map leaves no way to it".into());
        }
        End::GaveUp => {
            out.trajectory = walked(&spec, &rover.walk, start);
            out.gave_up = true;
            out.notes.push(if rover.steps() >= MAX_STEPS {
                format!("stopped after {MAX_STEPS} moves, the most a run makes")
            } else {
                "a limit was reached before the goal".into()
            });
        }
    }
    out.expanded = rover.expanded;
    let metrics = [
        ("traveled", traveled),
        ("steps", rover.steps() as f64),
        ("replans", rover.replans as f64),
        ("sensed", rover.sensed_count as f64),
    ];
    for (m, v) in metrics {
        out.extra.insert(m.into(), MetricValue::Num(v));
    }
    let mut online = None;
    if let Some(mut log) = rover.log.take() {
        if log.truncated {
            out.notes.push(format!(
                "the trace keeps at most {MAX_TRACED_POINTS} points per list; later steps are left out of it"
            ));
        }
        // Step k of the trace is the robot at path[k]: the raw start and
        // goal, when they are not lattice points, are steps of their own.
        if start.xy() != s_pt {
            log.online.sensed.insert(0, Vec::new());
            log.online.plans.insert(0, Vec::new());
        }
        if end == End::Reached && goal.xy() != g_pt {
            log.online.sensed.push(Vec::new());
            log.online.plans.push(Vec::new());
        }
        out.layers.extend(layers::search(&log.expansions));
        online = Some(log.online);
    }
    (out, online)
}

/// The motion of a run that stopped short of the goal: the start, then
/// the lattice points walked.
fn walked(spec: &LatticeSpec, walk: &[usize], start: Config) -> Vec<Config> {
    let mut path = vec![start];
    path.extend(walk.iter().map(|&n| {
        let p = spec.point_of(n);
        Config::new(p.x, p.y, start.theta)
    }));
    path.dedup_by(|a, b| a.x == b.x && a.y == b.y);
    path
}

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum End {
    Reached,
    /// The belief proves that no way leads to the goal.
    Unreachable,
    /// A limit was reached.
    GaveUp,
}

/// The moves of the lattice: how many directions of [`DIRS`](super::astar::DIRS) and their
/// costs.
#[derive(Clone, Copy)]
struct Moves {
    dirs: usize,
    cost: [f64; 8],
}

impl Moves {
    /// The move from `u` in direction `d` on the belief, if it is believed
    /// usable: the neighbour and the cost.
    fn edge(&self, belief: &GridLattice, u: usize, d: usize) -> Option<(usize, f64)> {
        let v = belief.neighbour(u, d)?;
        belief
            .edge_known_usable(u, d, v)
            .then_some((v, self.cost[d]))
    }
}

/// What the trace collects, within [`MAX_TRACED_POINTS`] per list.
struct Log {
    online: OnlineTrace,
    expansions: Vec<Point>,
    sensed_points: usize,
    plan_points: usize,
    truncated: bool,
}

/// The robot: what it knows of the world (except the belief lattice, which
/// searches borrow separately), where it is and where it has been.
struct Rover<'a> {
    truth: GridLattice,
    index: &'a ObstacleIndex,
    spec: LatticeSpec,
    cfg: SearchConfig,
    moves: Moves,
    range: usize,
    /// The lattice points sensed so far, a bit each (SPEC 3.2: the memory
    /// of 3.1).
    sensed: BitSet,
    sensed_count: usize,
    pos: usize,
    /// The lattice points the robot stood on, in order: `walk[k]` is step k.
    walk: Vec<usize>,
    /// Length of the lattice moves so far.
    traveled: f64,
    expanded: u64,
    replans: u64,
    /// The plan's `limit time`, set-up included.
    deadline: Deadline,
    log: Option<Log>,
}

impl<'a> Rover<'a> {
    fn new(
        truth: GridLattice,
        index: &'a ObstacleIndex,
        cfg: SearchConfig,
        range: usize,
        start: usize,
        traced: bool,
        deadline: Deadline,
    ) -> Self {
        let spec = truth.spec;
        let dirs = if cfg.connect == 4 { 4 } else { 8 };
        let cost = step_costs(cfg.cost, spec.cell);
        let log = traced.then(|| Log {
            online: OnlineTrace {
                cell: spec.cell,
                sensed: vec![Vec::new()],
                plans: vec![Vec::new()],
            },
            expansions: Vec::new(),
            sensed_points: 0,
            plan_points: 0,
            truncated: false,
        });
        Rover {
            sensed: BitSet::new(spec.layer_len(), false),
            truth,
            index,
            spec,
            cfg,
            moves: Moves { dirs, cost },
            range,
            sensed_count: 0,
            pos: start,
            walk: vec![start],
            traveled: 0.0,
            expanded: 0,
            replans: 0,
            deadline,
            log,
        }
    }

    fn steps(&self) -> u64 {
        self.walk.len() as u64 - 1
    }

    fn limits(&self) -> Limits {
        self.cfg.limits
    }

    fn out_of_time(&self) -> bool {
        self.deadline.passed()
    }

    /// The search settings for one more A* run: the limits that remain.
    fn search_cfg(&self) -> SearchConfig {
        let mut cfg = self.cfg;
        cfg.limits = self.deadline.remaining(cfg.limits);
        cfg.limits.expansions = cfg
            .limits
            .expansions
            .map(|m| m.saturating_sub(self.expanded));
        cfg
    }

    /// The lattice points within range of the robot not sensed yet, in
    /// index order.
    fn scan(&self) -> Vec<usize> {
        if self.sensed_count == self.sensed.len() {
            return Vec::new();
        }
        let (i, j) = self.spec.coords(self.pos);
        let r = self.range;
        let (i0, i1) = (
            i.saturating_sub(r),
            i.saturating_add(r).min(self.spec.nx - 1),
        );
        let (j0, j1) = (
            j.saturating_sub(r),
            j.saturating_add(r).min(self.spec.ny - 1),
        );
        let mut found = Vec::new();
        for jj in j0..=j1 {
            for ii in i0..=i1 {
                let n = self.spec.index(ii, jj);
                if !self.sensed.get(n) {
                    found.push(n);
                }
            }
        }
        found
    }

    /// Learns the true state of `nodes` and of every edge between two
    /// sensed points among them and their neighbours. Returns whether
    /// anything turned out blocked (a point or an edge).
    fn reveal(&mut self, belief: &mut GridLattice, nodes: &[usize]) -> bool {
        let mut blocked = false;
        for &n in nodes {
            self.sensed.set(n, true);
            self.sensed_count += 1;
            let free = self.truth.free.get(n);
            belief.free.set(n, free);
            blocked |= !free;
            if let Some(log) = &mut self.log {
                if log.sensed_points < MAX_TRACED_POINTS {
                    log.sensed_points += 1;
                    if let Some(step) = log.online.sensed.last_mut() {
                        step.push((self.spec.point_of(n), !free));
                    }
                } else {
                    log.truncated = true;
                }
            }
        }
        for &n in nodes {
            if !self.truth.free.get(n) {
                continue;
            }
            for d in 0..self.moves.dirs {
                let Some(m) = self.truth.neighbour(n, d) else {
                    continue;
                };
                if self.sensed.get(m) && self.truth.free.get(m) {
                    let ok = self.truth.edge_free(self.index, n, d, m);
                    belief.set_edge(n, d, m, ok);
                    blocked |= !ok;
                }
            }
        }
        blocked
    }

    /// Senses around the robot; returns whether anything new is blocked.
    fn sense(&mut self, belief: &mut GridLattice) -> bool {
        let nodes = self.scan();
        self.reveal(belief, &nodes)
    }

    /// Moves to the adjacent point `to` along a believed-usable edge (one
    /// the robot has sensed, so a true one), unless a limit stops it.
    fn advance(&mut self, belief: &GridLattice, to: usize) -> Result<(), End> {
        let max = self.limits().steps.unwrap_or(MAX_STEPS).min(MAX_STEPS);
        if self.steps() >= max || self.out_of_time() {
            return Err(End::GaveUp);
        }
        let d = (0..self.moves.dirs)
            .find(|&d| belief.neighbour(self.pos, d) == Some(to))
            .expect("moves join lattice neighbours");
        debug_assert!(belief.edge_known_usable(self.pos, d, to));
        self.traveled += self.moves.cost[d];
        self.pos = to;
        self.walk.push(to);
        if let Some(log) = &mut self.log {
            log.online.sensed.push(Vec::new());
            log.online.plans.push(Vec::new());
        }
        Ok(())
    }

    /// Whether the trace still takes plans.
    fn wants_plan(&self) -> bool {
        self.log
            .as_ref()
            .is_some_and(|l| l.plan_points < MAX_TRACED_POINTS)
    }

    /// Sets the plan held at the current step (points from the robot on).
    fn hold_plan(&mut self, plan: impl IntoIterator<Item = usize>) {
        let spec = self.spec;
        let Some(log) = &mut self.log else {
            return;
        };
        if log.plan_points >= MAX_TRACED_POINTS {
            log.truncated = true;
            return;
        }
        let points: Vec<Point> = plan
            .into_iter()
            .take(MAX_TRACED_POINTS - log.plan_points)
            .map(|n| spec.point_of(n))
            .collect();
        log.plan_points += points.len();
        if let Some(step) = log.online.plans.last_mut() {
            *step = points;
        }
    }

    /// Adds expanded nodes to the trace.
    fn log_expansions(&mut self, nodes: impl IntoIterator<Item = usize>) {
        let spec = self.spec;
        let Some(log) = &mut self.log else {
            return;
        };
        for n in nodes {
            if log.expansions.len() >= MAX_TRACED_POINTS {
                log.truncated = true;
                return;
            }
            let p = spec.point_of(n);
            log.expansions.push(p);
        }
    }
}

/// `backtrack` (`shortcut: false`) and `shortcut`: one A* on the belief,
/// the robot walking to each node before it is expanded and sensing on the
/// way.
fn explore(rover: &mut Rover<'_>, belief: &mut GridLattice, goal: usize, shortcut: bool) -> End {
    let mut buf = SearchBuffers::default();
    let cfg = rover.search_cfg();
    let start = rover.pos;
    let index = rover.index;
    let traced = rover.log.is_some();
    let mut chain = Vec::new();
    let r = search_with(
        belief,
        index,
        start,
        goal,
        &cfg,
        traced,
        &mut buf,
        |node, tree, belief| {
            let route = walk_between(rover.pos, node, tree, shortcut, &mut chain);
            for k in 0..route.len() {
                rover.hold_plan(std::iter::once(rover.pos).chain(route[k..].iter().copied()));
                if rover.advance(belief, route[k]).is_err() {
                    return false;
                }
                rover.sense(belief);
            }
            true
        },
    );
    rover.expanded = r.expanded;
    rover.replans = 1;
    rover.log_expansions(r.expansion_order);
    match r.nodes {
        Some(_) => End::Reached,
        None if r.gave_up => End::GaveUp,
        None => End::Unreachable,
    }
}

/// The points to walk from `from` to `to` in the search `tree`
/// (excluding `from`): up the back-pointers to the start and down to `to`,
/// or with `shortcut` only up to their deepest common ancestor. `chain` is
/// scratch space.
fn walk_between(
    from: usize,
    to: usize,
    tree: &Tree<'_>,
    shortcut: bool,
    chain: &mut Vec<usize>,
) -> Vec<usize> {
    let ancestors = |mut n: usize, out: &mut Vec<usize>| {
        out.clear();
        out.push(n);
        while let Some(p) = tree.parent(n) {
            out.push(p);
            n = p;
        }
    };
    // Both chains end at the search's start.
    let mut up = Vec::new();
    ancestors(from, &mut up);
    ancestors(to, chain);
    // Drop the common tail: with `shortcut` all of it but the deepest
    // common ancestor, without it only the start (walked through once).
    let mut common = 1;
    if shortcut {
        while common < up.len().min(chain.len())
            && up[up.len() - 1 - common] == chain[chain.len() - 1 - common]
        {
            common += 1;
        }
    }
    let turn = up.len() - common;
    let mut route: Vec<usize> = up[1..=turn].to_vec();
    route.extend(chain[..chain.len() - common].iter().rev());
    route
}

/// `replan`: A* from the robot on the belief; follow the plan while it is
/// not blocked by what was sensed, else plan again.
fn replan(rover: &mut Rover<'_>, belief: &mut GridLattice, goal: usize) -> End {
    let mut buf = SearchBuffers::default();
    loop {
        if rover.pos == goal {
            return End::Reached;
        }
        let cfg = rover.search_cfg();
        let record = rover
            .log
            .as_ref()
            .is_some_and(|l| l.expansions.len() < MAX_TRACED_POINTS);
        let r = search(belief, rover.index, rover.pos, goal, &cfg, record, &mut buf);
        rover.expanded += r.expanded;
        rover.replans += 1;
        rover.log_expansions(r.expansion_order);
        let plan = match r.nodes {
            Some(nodes) => nodes,
            None if r.gave_up => return End::GaveUp,
            None => return End::Unreachable,
        };
        let mut k = 0;
        loop {
            rover.hold_plan(plan[k..].iter().copied());
            if k + 1 == plan.len() {
                return End::Reached;
            }
            if let Err(end) = rover.advance(belief, plan[k + 1]) {
                return end;
            }
            k += 1;
            if rover.sense(belief) && !plan_usable(belief, &rover.moves, &plan[k..]) {
                break;
            }
        }
    }
}

/// Whether every move of `plan` is believed usable.
fn plan_usable(belief: &GridLattice, moves: &Moves, plan: &[usize]) -> bool {
    plan.windows(2).all(|w| {
        (0..moves.dirs).any(|d| moves.edge(belief, w[0], d).is_some_and(|(v, _)| v == w[1]))
    })
}

// ------------------------------------------------------------------ D* Lite

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::validator::{DEFAULT_TOLERANCE, validate_path};
    use crate::geometry::{Aabb, Grid, Obstacle, Shape, World};
    use crate::planners::astar::Astar;
    use crate::planners::lattice::Sample;
    use proptest::prelude::{ProptestConfig, any, prop_assert, prop_assert_eq, proptest};
    use proptest::strategy::Strategy as Generator;
    use std::cmp::Ordering;
    use std::collections::BinaryHeap;

    /// A random grid world: `w × h` cells of side 1 from the origin, a
    /// start and a goal at free cell centres.
    #[derive(Clone, Debug)]
    struct Case {
        w: usize,
        h: usize,
        /// Row-major from the bottom row (lattice order): blocked cells.
        blocked: Vec<bool>,
        start: (usize, usize),
        goal: (usize, usize),
        disk: bool,
        connect: u8,
        sense: usize,
    }

    impl Case {
        fn draw(w: usize, h: usize, seed: u64, density: f64, disk: bool, eight: bool) -> Case {
            let mut rng = crate::rng::SplitMix64::new(seed);
            let mut unit = || rng.next_f64();
            let mut blocked: Vec<bool> = (0..w * h).map(|_| unit() < density).collect();
            let mut pick = |blocked: &mut Vec<bool>| {
                let k = ((unit() * (w * h) as f64) as usize).min(w * h - 1);
                blocked[k] = false;
                (k % w, k / w)
            };
            let start = pick(&mut blocked);
            let goal = pick(&mut blocked);
            let sense = 1 + (unit() * 3.0) as usize;
            Case {
                w,
                h,
                blocked,
                start,
                goal,
                disk,
                connect: if eight { 8 } else { 4 },
                sense,
            }
        }

        fn world(&self) -> World {
            // Grid rows run from the top.
            let cells = (0..self.h)
                .rev()
                .flat_map(|j| (0..self.w).map(move |i| (i, j)))
                .map(|(i, j)| u8::from(!self.blocked[j * self.w + i]))
                .collect();
            World {
                bounds: Aabb::from_corners(
                    Point::new(0.0, 0.0),
                    Point::new(self.w as f64, self.h as f64),
                ),
                obstacles: vec![Obstacle {
                    name: "G".into(),
                    shape: Shape::Grid(Grid {
                        cell: 1.0,
                        origin: Point::new(0.0, 0.0),
                        width: self.w,
                        height: self.h,
                        cells,
                    }),
                }],
            }
        }

        fn robot(&self) -> RobotShape {
            if self.disk {
                RobotShape::Disk(0.5)
            } else {
                RobotShape::Point
            }
        }

        fn ends(&self) -> (Config, Config) {
            let centre = |(i, j): (usize, usize)| Config::new(i as f64 + 0.5, j as f64 + 0.5, 0.0);
            (centre(self.start), centre(self.goal))
        }

        /// Runs one strategy (with the case's `sense`); the path, when
        /// found, must start and end where asked and pass the validator.
        fn run(&self, strategy: &str) -> Ran {
            self.run_with(strategy, self.sense, Limits::default())
        }

        fn run_with(&self, strategy: &str, sense: usize, limits: Limits) -> Ran {
            let (world, robot) = (self.world(), self.robot());
            let (start, goal) = self.ends();
            let out = online(
                &world,
                &robot,
                start,
                goal,
                strategy,
                self.connect,
                sense,
                limits,
            );
            if let Some(path) = &out.path {
                assert_eq!(path.first(), Some(&start));
                assert_eq!(path.last(), Some(&goal));
                if let Err(e) = validate_path(&world, &robot, path, DEFAULT_TOLERANCE) {
                    panic!("{strategy}: the trajectory fails the validator: {e:?}");
                }
                let trace = &out.trace;
                assert_eq!(trace.sensed.len(), path.len());
                assert_eq!(trace.plans.len(), path.len());
                assert_eq!(num(&out, "steps") as usize + 1, path.len());
                let length: f64 = path
                    .windows(2)
                    .map(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y))
                    .sum();
                assert!((num(&out, "traveled") - length).abs() < 1e-9);
            }
            out
        }

        /// Offline `astar` on the same lattice.
        fn offline(&self) -> PlanOutcome {
            let (world, robot) = (self.world(), self.robot());
            let (start, goal) = self.ends();
            let settings = Astar {
                lattice: LatticeSpec::new(&world, 1.0, Sample::Center, 1.0),
                rotating: false,
                connect: self.connect,
                cost: CostMetric::Euclid,
                turn_cost: 0.0,
                weight: 1.0,
                heuristic: Heuristic::Lattice,
            };
            settings.plan(&task(&world, &robot, start, goal, Limits::default()))
        }

        fn index(&self, (i, j): (usize, usize)) -> usize {
            j * self.w + i
        }

        fn cell_of(&self, p: Point) -> usize {
            self.index((p.x.floor() as usize, p.y.floor() as usize))
        }

        /// Cost from every cell to the goal (Dijkstra), on a map where
        /// `blocked(c)` says which cells are blocked: the lattice's rule
        /// for a grid world, written independently (moves between free
        /// cells, diagonals only between two free orthogonal cells).
        fn distances(&self, blocked: &dyn Fn(usize) -> bool) -> Vec<f64> {
            let n = self.w * self.h;
            let mut dist = vec![f64::INFINITY; n];
            let mut done = vec![false; n];
            let goal = self.index(self.goal);
            if blocked(goal) {
                return dist;
            }
            dist[goal] = 0.0;
            let moves =
                &crate::planners::grid_lattice::DIRS[..if self.connect == 4 { 4 } else { 8 }];
            let free = |i: i64, j: i64| {
                i >= 0
                    && j >= 0
                    && (i as usize) < self.w
                    && (j as usize) < self.h
                    && !blocked(j as usize * self.w + i as usize)
            };
            let mut heap = BinaryHeap::new();
            heap.push((std::cmp::Reverse(Dist(0.0)), goal));
            while let Some((std::cmp::Reverse(Dist(du)), u)) = heap.pop() {
                if done[u] {
                    continue;
                }
                done[u] = true;
                let (i, j) = ((u % self.w) as i64, (u / self.w) as i64);
                for &(dx, dy) in moves {
                    let (ni, nj) = (i + dx, j + dy);
                    if !free(ni, nj)
                        || (dx != 0 && dy != 0 && !(free(i + dx, j) && free(i, j + dy)))
                    {
                        continue;
                    }
                    let v = nj as usize * self.w + ni as usize;
                    let c = ((dx * dx + dy * dy) as f64).sqrt();
                    if du + c < dist[v] {
                        dist[v] = du + c;
                        heap.push((std::cmp::Reverse(Dist(dist[v])), v));
                    }
                }
            }
            dist
        }
    }

    /// An `f64` with a total order, for the test's Dijkstra.
    #[derive(Clone, Copy, PartialEq)]
    struct Dist(f64);
    impl Eq for Dist {}
    impl PartialOrd for Dist {
        fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
            Some(self.cmp(other))
        }
    }
    impl Ord for Dist {
        fn cmp(&self, other: &Self) -> Ordering {
            self.0.total_cmp(&other.0)
        }
    }

    /// Each move of `path` starts a shortest path to the goal on the map
    /// as the robot believed it at that step (rebuilt from the trace).
    fn check_believed_shortest(
        c: &Case,
        out: &Ran,
        path: &[Config],
    ) -> Result<(), proptest::test_runner::TestCaseError> {
        let trace = &out.trace;
        let mut known = vec![None; c.w * c.h];
        for (k, w) in path.windows(2).enumerate() {
            for &(p, blocked) in &trace.sensed[k] {
                known[c.cell_of(p)] = Some(blocked);
            }
            let belief = c.distances(&|n| known[n] == Some(true));
            let (a, b) = (c.cell_of(w[0].xy()), c.cell_of(w[1].xy()));
            let step = (w[1].x - w[0].x).hypot(w[1].y - w[0].y);
            prop_assert!(
                (belief[a] - (step + belief[b])).abs() < 1e-9,
                "step {} from {:?} is not on a believed shortest path",
                k,
                w[0]
            );
        }
        Ok(())
    }

    fn task<'a>(
        world: &'a World,
        robot: &'a RobotShape,
        start: Config,
        goal: Config,
        limits: Limits,
    ) -> Task<'a> {
        Task {
            world,
            robot,
            start,
            goal: Some(goal),
            limits,
            seed: 0,
            steering: None,
            draw: true,
            referee: None,
            moving: &[],
            speed: None,
            agents: &[],
        }
    }

    /// An `online` plan on the unit lattice of cell centres.
    #[allow(clippy::too_many_arguments)]
    fn online(
        world: &World,
        robot: &RobotShape,
        start: Config,
        goal: Config,
        strategy: &str,
        connect: u8,
        sense: usize,
        limits: Limits,
    ) -> Ran {
        let strategy = Strategy::WORDS
            .iter()
            .position(|w| *w == strategy)
            .and_then(Strategy::from_index)
            .expect("a strategy");
        let settings = Online {
            lattice: LatticeSpec::new(world, 1.0, Sample::Center, 1.0),
            connect,
            strategy,
            sense,
            heuristic: Heuristic::Lattice,
        };
        let (out, trace) = navigate_logged(
            &task(world, robot, start, goal, limits),
            &settings,
            Options::default(),
        );
        Ran {
            out,
            trace: trace.unwrap_or_default(),
        }
    }

    /// An `online` run and what the robot knew step by step.
    struct Ran {
        out: PlanOutcome,
        trace: OnlineTrace,
    }

    impl std::ops::Deref for Ran {
        type Target = PlanOutcome;
        fn deref(&self) -> &PlanOutcome {
            &self.out
        }
    }

    /// The expansions as drawn.
    fn searched(out: &PlanOutcome) -> Vec<&Layer> {
        out.layers_of("search").collect()
    }

    fn num(out: &PlanOutcome, metric: &str) -> f64 {
        match out.extra.get(metric) {
            Some(MetricValue::Num(x)) => *x,
            other => panic!("metric {metric}: {other:?}"),
        }
    }

    fn case() -> impl Generator<Value = Case> {
        (
            3usize..14,
            3usize..14,
            any::<u64>(),
            0.0..0.45f64,
            any::<bool>(),
            any::<bool>(),
        )
            .prop_map(|(w, h, seed, density, disk, eight)| {
                Case::draw(w, h, seed, density, disk, eight)
            })
    }

    /// Larger maps, where long runs of sensing and repairs accumulate.
    fn large_case() -> impl Generator<Value = Case> {
        (
            30usize..70,
            30usize..70,
            any::<u64>(),
            0.2..0.4f64,
            any::<bool>(),
        )
            .prop_map(|(w, h, seed, density, eight)| Case::draw(w, h, seed, density, false, eight))
    }

    const STRATEGIES: [&str; 4] = ["backtrack", "shortcut", "replan", "dstar_lite"];

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// `shortcut` expands exactly what `backtrack` expands, in the same
        /// order (offline A*'s order on the true map), and never travels
        /// more.
        #[test]
        fn shortcut_walks_less_over_the_same_expansions(c in case()) {
            let back = c.run("backtrack");
            let short = c.run("shortcut");
            let offline = c.offline();
            prop_assert_eq!(searched(&back), searched(&short));
            prop_assert_eq!(searched(&back), searched(&offline));
            prop_assert_eq!(back.expanded, short.expanded);
            prop_assert_eq!(back.path.is_some(), offline.path.is_some());
            prop_assert_eq!(short.path.is_some(), offline.path.is_some());
            prop_assert!(num(&short, "traveled") <= num(&back, "traveled") + 1e-9);
            prop_assert!(num(&short, "steps") <= num(&back, "steps"));
        }

        /// `replan` and `dstar_lite` reach the goal exactly when it is
        /// reachable, and each of their moves starts a shortest path on
        /// the map as believed at that step; with `sense` covering the
        /// whole map both travel the offline optimum.
        #[test]
        fn replan_and_dstar_lite_move_along_believed_shortest_paths(c in case()) {
            let offline = c.offline();
            let truth = c.distances(&|k| c.blocked[k]);
            if let Some(cost) = offline.cost {
                prop_assert!((cost - truth[c.index(c.start)]).abs() < 1e-9);
            }
            for strategy in ["replan", "dstar_lite"] {
                let out = c.run(strategy);
                prop_assert_eq!(out.path.is_some(), offline.path.is_some(), "{}", strategy);
                prop_assert!(!out.gave_up);
                let Some(path) = &out.path else { continue };
                check_believed_shortest(&c, &out, path)?;
                let full = c.run_with(strategy, c.w.max(c.h), Limits::default());
                let length = |o: &PlanOutcome| num(o, "traveled");
                prop_assert!((length(&full) - truth[c.index(c.start)]).abs() < 1e-9, "{}", strategy);
            }
        }

        /// A goal walled in: every strategy ends with no path, without
        /// giving up.
        #[test]
        fn walled_in_goals_are_unreachable_for_every_strategy(c in case()) {
            let mut c = c;
            let (gi, gj) = c.goal;
            for j in gj.saturating_sub(1)..=(gj + 1).min(c.h - 1) {
                for i in gi.saturating_sub(1)..=(gi + 1).min(c.w - 1) {
                    c.blocked[j * c.w + i] = (i, j) != c.goal;
                }
            }
            let s = c.index(c.start);
            c.blocked[s] = false;
            if c.start == c.goal || c.offline().path.is_some() {
                // The start was inside the wall.
                return Ok(());
            }
            for strategy in STRATEGIES {
                let out = c.run(strategy);
                prop_assert!(out.path.is_none(), "{}", strategy);
                prop_assert!(!out.gave_up, "{}", strategy);
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        /// On larger maps too, `dstar_lite` and `replan` reach the goal
        /// exactly when it is reachable, along believed shortest paths.
        #[test]
        fn large_maps_are_crossed_along_believed_shortest_paths(c in large_case()) {
            let offline = c.offline();
            for strategy in ["replan", "dstar_lite"] {
                let out = c.run(strategy);
                prop_assert_eq!(out.path.is_some(), offline.path.is_some(), "{}", strategy);
                prop_assert!(!out.gave_up);
                if let Some(path) = &out.path {
                    check_believed_shortest(&c, &out, path)?;
                }
            }
        }
    }

    /// A room split by a segment wall with a door: lattice points on both
    /// sides are free, but edges across the wall are not; the robot only
    /// learns which edges cross it by sensing.
    #[test]
    fn segment_walls_are_sensed_as_blocked_edges() {
        let world = World {
            bounds: Aabb::from_corners(Point::new(0.0, 0.0), Point::new(12.0, 12.0)),
            obstacles: vec![Obstacle {
                name: "W".into(),
                shape: Shape::Segment(Point::new(6.0, 0.0), Point::new(6.0, 10.0)),
            }],
        };
        for strategy in STRATEGIES {
            for connect in [4, 8] {
                let out = online(
                    &world,
                    &RobotShape::Point,
                    Config::new(1.5, 1.5, 0.0),
                    Config::new(10.5, 1.5, 0.0),
                    strategy,
                    connect,
                    1,
                    Limits::default(),
                );
                let path = out.path.as_ref().expect("a way through the door");
                validate_path(&world, &RobotShape::Point, path, DEFAULT_TOLERANCE)
                    .unwrap_or_else(|e| panic!("{strategy}: {e:?}"));
                assert!(
                    path.iter().any(|c| c.y > 10.0),
                    "{strategy} went through the door"
                );
            }
        }
    }

    #[test]
    fn limits_end_a_run() {
        let c = Case::draw(12, 12, 7, 0.2, false, true);
        for strategy in STRATEGIES {
            let steps = Limits {
                steps: Some(3),
                ..Limits::default()
            };
            let out = c.run_with(strategy, 1, steps);
            if out.path.is_none() {
                assert!(out.gave_up, "{strategy}");
                assert_eq!(num(&out, "steps"), 3.0, "{strategy}");
            }
            let expansions = Limits {
                expansions: Some(2),
                ..Limits::default()
            };
            let out = c.run_with(strategy, 1, expansions);
            assert!(out.path.is_none() && out.gave_up, "{strategy}");
            assert!(out.expanded <= 2, "{strategy}");
            let time = Limits {
                time: Some(0.0),
                ..Limits::default()
            };
            let out = c.run_with(strategy, 1, time);
            assert!(out.path.is_none() && out.gave_up, "{strategy}");
        }
    }

    #[test]
    fn runs_are_deterministic() {
        let c = Case::draw(13, 11, 42, 0.3, true, true);
        for strategy in STRATEGIES {
            let (a, b) = (c.run(strategy), c.run(strategy));
            assert_eq!(a.path, b.path);
            assert_eq!(a.extra, b.extra);
            assert_eq!(a.expanded, b.expanded);
            assert_eq!(searched(&a), searched(&b));
        }
    }
}
