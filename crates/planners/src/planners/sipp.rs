//! `sipp` (SPEC 3.10): safe-interval path planning (Phillips & Likhachev,
//! ICRA 2011) for point and disk robots among moving obstacles, on the
//! (x, y) lattice of `astar`.
//!
//! A lattice trajectory moves between adjacent lattice points at the
//! robot's full speed, along the edges `astar` would use, and waits at
//! lattice points for any time. A point's *safe intervals* are the times
//! at which the robot may stand there; a move's *blocked departures* are
//! the times at which leaving along it would meet a moving obstacle. Both
//! come from the moving obstacles exactly
//! ([`RoundMover`](crate::geometry::timed::departures::RoundMover)), so
//! the search state is a point and one of its safe intervals, reached as
//! early as possible: arriving later in the same interval never helps,
//! since the robot could have waited. A* on those states (the heuristic:
//! the straight-line distance to the goal at full speed) gives the
//! earliest arrival among all lattice trajectories, in continuous time.
//!
//! The plan's start and goal are joined to their nearest lattice points by
//! straight moves at full speed, like `astar`'s; the robot may wait at its
//! start too. The goal is reached in a safe interval that never ends: the
//! robot stays there for good (SPEC 2.9), so a goal that some obstacle
//! later drives through or parks on is not a goal yet.

use std::any::Any;
use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap};

use crate::contract::layers;
use crate::contract::schema::{
    DEFAULT_SPEED, MetricSpec, ParamSpec, RobotKind, ValueSpec, num,
};
use crate::contract::{MetricValue, PlanArgs, PlanOutcome, Planner, Settings, Task};
use crate::geometry::collide::ObstacleIndex;
use crate::geometry::timed::departures::{Intervals, RoundMover, first_free};
use crate::geometry::{Config, Point};

use crate::planners::deadline::{Deadline, setup_note};
use crate::planners::grid_lattice::{GridLattice, grown_obstacles, snap_ends};
use crate::planners::lattice::{LATTICE_PARAMS, LatticeSpec, Sample, check_lattice_of};

/// `sipp` in the registry.
pub static PLANNER: Planner = Planner {
    kind: "sipp",
    summary: "safe-interval path planning among moving obstacles: the earliest arrival on the lattice",
    robots: &[RobotKind::Point, RobotKind::Disk],
    params: &[LATTICE_PARAMS[0], CONNECT],
    metrics: &[
        MetricSpec::num("cells", "lattice points"),
        MetricSpec::num("free_cells", "lattice points where the robot is free of the static obstacles"),
        MetricSpec::num(
            "intervals",
            "safe intervals computed (of the lattice points the search reached)",
        ),
        MetricSpec::num("generated", "(point, safe interval) states put on the open list"),
    ],
    limits: &["expansions", "time", "cells"],
    needs_goal: true,
    randomized: false,
    grids: true,
    time: true,
    check,
};

/// `connect`: the lattice's neighbours (also `prioritized`'s, which plans
/// each agent with `sipp`).
pub const CONNECT: ParamSpec = ParamSpec::new(
    "connect",
    ValueSpec::IntChoice(&[4, 8]),
    num(8.0, "8"),
    "lattice neighbours: 4 or 8",
);

/// A `sipp` plan's settings.
#[derive(Clone, Debug)]
pub struct Sipp {
    pub lattice: LatticeSpec,
    /// 4 or 8.
    pub connect: u8,
}

fn check(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    let connect = args.num("connect") as u8;
    let lattice = check_lattice_of(args, Sample::Center, 1.0)?;
    Some(Box::new(Sipp { lattice, connect }))
}

impl Settings for Sipp {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        plan(task, self)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// A search state: a point and one of its safe intervals.
#[derive(Clone, Copy, Debug)]
struct State {
    node: usize,
    interval: usize,
    /// The earliest arrival found.
    arrival: f64,
    /// The state it came from and when it left it (`usize::MAX`: none).
    parent: usize,
    departed: f64,
    closed: bool,
}

/// An open-list entry: smallest `f`, then latest arrival (deeper first on
/// ties), then the
/// earliest generated state (a deterministic order).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Open {
    f: f64,
    arrival: f64,
    state: usize,
}

impl Eq for Open {}

impl Ord for Open {
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .f
            .total_cmp(&self.f)
            .then(self.arrival.total_cmp(&other.arrival))
            .then(other.state.cmp(&self.state))
    }
}

impl PartialOrd for Open {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// The graph `sipp` searches: the lattice's points, then the start and the
/// goal as points of their own, joined to their nearest lattice points.
struct Graph {
    lat: GridLattice,
    index: ObstacleIndex,
    connect: usize,
    start: usize,
    goal: usize,
    start_at: Point,
    goal_at: Point,
    s_node: usize,
    g_node: usize,
}

impl Graph {
    fn point(&self, n: usize) -> Point {
        if n == self.start {
            self.start_at
        } else if n == self.goal {
            self.goal_at
        } else {
            self.lat.spec.point_of(n)
        }
    }

    /// The points one move from `n`.
    fn neighbours(&mut self, n: usize, out: &mut Vec<usize>) {
        out.clear();
        if n == self.start {
            out.push(self.s_node);
            return;
        }
        if n == self.goal {
            return;
        }
        for d in 0..self.connect {
            if let Some(m) = self.lat.neighbour(n, d)
                && self.lat.edge_usable(&self.index, n, d, m)
            {
                out.push(m);
            }
        }
        if n == self.g_node {
            out.push(self.goal);
        }
    }
}

/// Runs a `sipp` plan.
pub fn plan(task: &Task<'_>, settings: &Sipp) -> PlanOutcome {
    let deadline = Deadline::start(&task.limits);
    let radius = task.robot.radius();
    let speed = task.speed.unwrap_or(DEFAULT_SPEED);
    let spec = settings.lattice;
    let mut out = PlanOutcome::default();
    for (name, value) in [
        ("cells", spec.cells_f64()),
        ("free_cells", 0.0),
        ("intervals", 0.0),
        ("generated", 0.0),
    ] {
        out.extra.insert(name.into(), MetricValue::Num(value));
    }
    if task.draw {
        out.layers
            .extend(layers::grown_by_disk(grown_obstacles(task.world, radius)));
    }
    let start = task.start;
    let goal = task.goal.unwrap_or(start);
    let mover = RoundMover::new(task.moving, radius);
    // At the goal already, and left alone there for good: found at once.
    if task.start_is_goal() && mover.safe_intervals(start.xy()) == [(0.0, f64::INFINITY)] {
        return PlanOutcome {
            extra: out.extra,
            layers: out.layers,
            times: Some(vec![0.0]),
            ..PlanOutcome::at_goal(start)
        };
    }
    let index = ObstacleIndex::new(task.world);
    let Some(lat) = GridLattice::build_until(spec, &index, radius, &deadline) else {
        out.gave_up = true;
        out.notes.push(setup_note("classifying the lattice"));
        return out;
    };
    out.extra.insert(
        "free_cells".into(),
        MetricValue::Num(lat.free_count() as f64),
    );
    let (s_node, g_node) = match snap_ends(&lat, &index, start, goal) {
        Ok(ends) => ends,
        Err(note) => {
            out.notes.push(note);
            return out;
        }
    };
    let n = spec.layer_len();
    let mut graph = Graph {
        lat,
        index,
        connect: usize::from(settings.connect),
        start: n,
        goal: n + 1,
        start_at: start.xy(),
        goal_at: goal.xy(),
        s_node,
        g_node,
    };
    let found = search(&mut graph, &mover, speed, task, &deadline, &mut out);
    if let Some(points) = found {
        let mut path = Vec::with_capacity(points.len());
        let mut times = Vec::with_capacity(points.len());
        for (p, t) in points {
            // A wait of no time (leaving a point the instant it is
            // reached) is no point of the trajectory: its times increase.
            if path.last().is_some_and(|q: &Config| q.xy() == p)
                && times.last().is_some_and(|&s: &f64| s >= t)
            {
                continue;
            }
            path.push(Config::new(p.x, p.y, start.theta));
            times.push(t);
        }
        if let Some(last) = path.last_mut() {
            *last = goal;
        }
        no_faster_than(&path, &mut times, speed);
        out.cost = times.last().copied();
        out.path = Some(path);
        out.times = Some(times);
    }
    out
}

/// Times nudged up by a few units in the last place where rounding made a
/// move's duration shorter than its length at full `speed`, or a wait's
/// end no later than its start (after its move was nudged): a move of
/// 5e-9 units at t = 17 s lasts 17.000000005 − 17 in floating point, up
/// to 1e-6 short of 5e-9 s relatively, which the validator reads as a
/// speeding robot.
fn no_faster_than(path: &[Config], times: &mut [f64], speed: f64) {
    for k in 1..times.len().min(path.len()) {
        let length = (path[k].xy() - path[k - 1].xy()).norm();
        while times[k] <= times[k - 1] || (times[k] - times[k - 1]) * speed < length {
            times[k] = times[k].next_up();
        }
    }
}

/// The search; `Some` trajectory (points and times) when found. Fills the
/// outcome's counts, notes and search layer.
fn search(
    graph: &mut Graph,
    mover: &RoundMover<'_>,
    speed: f64,
    task: &Task<'_>,
    deadline: &Deadline,
    out: &mut PlanOutcome,
) -> Option<Vec<(Point, f64)>> {
    // Each point's safe intervals, computed when the search first needs them.
    let mut safe: HashMap<usize, Intervals> = HashMap::new();
    fn intervals_of<'s>(
        safe: &'s mut HashMap<usize, Intervals>,
        mover: &RoundMover<'_>,
        graph: &Graph,
        node: usize,
    ) -> &'s Intervals {
        safe.entry(node)
            .or_insert_with(|| mover.safe_intervals(graph.point(node)))
    }
    let goal_at = graph.goal_at;
    let h = |p: Point| (goal_at - p).norm() / speed;
    let start_safe = intervals_of(&mut safe, mover, graph, graph.start);
    if start_safe.first().is_none_or(|iv| iv.0 > 0.0) {
        out.notes.push(format!(
            "a moving obstacle is on the start at t = 0{}",
            obstacle_named(task, graph.start_at)
        ));
        return None;
    }
    let goal_safe = intervals_of(&mut safe, mover, graph, graph.goal);
    if goal_safe.last().is_none_or(|iv| iv.1.is_finite()) {
        out.notes.push(format!(
            "the goal is never safe for good: a moving obstacle is on it at the end{}",
            obstacle_named(task, graph.goal_at)
        ));
        return None;
    }
    let mut states: Vec<State> = Vec::new();
    let mut ids: HashMap<(usize, usize), usize> = HashMap::new();
    let mut open = BinaryHeap::new();
    let mut expansion_order = Vec::new();
    states.push(State {
        node: graph.start,
        interval: 0,
        arrival: 0.0,
        parent: usize::MAX,
        departed: 0.0,
        closed: false,
    });
    ids.insert((graph.start, 0), 0);
    open.push(Open {
        f: h(graph.start_at),
        arrival: 0.0,
        state: 0,
    });
    let mut neighbours = Vec::new();
    let mut expanded = 0u64;
    let max_expansions = task.limits.expansions.unwrap_or(u64::MAX);
    let mut reached = None;
    while let Some(Open { state: id, .. }) = open.pop() {
        if states[id].closed {
            continue;
        }
        if expanded >= max_expansions || (expanded.is_multiple_of(256) && deadline.passed()) {
            out.gave_up = true;
            out.notes.push("a limit was reached before the goal".into());
            break;
        }
        states[id].closed = true;
        expanded += 1;
        let State {
            node,
            interval,
            arrival,
            ..
        } = states[id];
        if task.draw {
            expansion_order.push(graph.point(node));
        }
        let here = intervals_of(&mut safe, mover, graph, node)[interval];
        if node == graph.goal && here.1 == f64::INFINITY {
            reached = Some(id);
            break;
        }
        let from = graph.point(node);
        graph.neighbours(node, &mut neighbours);
        for &m in &neighbours {
            let to = graph.point(m);
            let tau = (to - from).norm() / speed;
            // Departures from this interval only: leaving at `arrival`
            // at the earliest and by its end.
            let blocked = mover.blocked_departures_within(from, to, tau, arrival, here.1);
            let there = intervals_of(&mut safe, mover, graph, m);
            for (j, &(j_start, j_end)) in there.iter().enumerate() {
                if j_start > here.1 + tau {
                    break;
                }
                if j_end < arrival + tau {
                    continue;
                }
                let Some(leave) = first_free(&blocked, arrival.max(j_start - tau)) else {
                    break;
                };
                if leave > here.1 || leave + tau > j_end {
                    continue;
                }
                let t = leave + tau;
                let next = *ids.entry((m, j)).or_insert_with(|| {
                    states.push(State {
                        node: m,
                        interval: j,
                        arrival: f64::INFINITY,
                        parent: usize::MAX,
                        departed: 0.0,
                        closed: false,
                    });
                    states.len() - 1
                });
                let s = &mut states[next];
                if !s.closed && t < s.arrival {
                    s.arrival = t;
                    s.parent = id;
                    s.departed = leave;
                    open.push(Open {
                        f: t + h(to),
                        arrival: t,
                        state: next,
                    });
                }
            }
        }
    }
    out.expanded = expanded;
    out.extra.insert(
        "generated".into(),
        MetricValue::Num(states.len() as f64),
    );
    out.extra.insert(
        "intervals".into(),
        MetricValue::Num(safe.values().map(Vec::len).sum::<usize>() as f64),
    );
    if task.draw {
        out.layers.extend(layers::search(&expansion_order));
    }
    let Some(goal_state) = reached else {
        if !out.gave_up {
            out.notes.push(
                "no lattice trajectory reaches the goal to stay there: it is sealed off, or the moving obstacles never let the robot through"
                    .into(),
            );
        }
        return None;
    };
    Some(trajectory(graph, &states, goal_state))
}

/// The trajectory that reaches `goal_state`: each point at its arrival,
/// and again at its departure after a wait; zero-length moves (a start or
/// goal on its lattice point) and repeated waits folded.
fn trajectory(graph: &Graph, states: &[State], goal_state: usize) -> Vec<(Point, f64)> {
    let mut chain = Vec::new();
    let mut id = goal_state;
    loop {
        chain.push(id);
        let parent = states[id].parent;
        if parent == usize::MAX {
            break;
        }
        id = parent;
    }
    chain.reverse();
    let mut points: Vec<(Point, f64)> = Vec::new();
    let mut push = |p: Point, t: f64| {
        if let Some(&(q, s)) = points.last() {
            if q == p && s == t {
                return;
            }
            // A wait after a wait at the same point: one wait.
            if points.len() >= 2 && q == p && points[points.len() - 2].0 == p {
                points.last_mut().expect("a point").1 = t;
                return;
            }
        }
        points.push((p, t));
    };
    for (k, &id) in chain.iter().enumerate() {
        let s = states[id];
        let p = graph.point(s.node);
        push(p, s.arrival);
        if let Some(&next) = chain.get(k + 1) {
            push(p, states[next].departed);
        }
    }
    points
}

/// ` (`NAME`)`: the moving obstacle that makes `at` unsafe at the start or
/// for good, for a note; empty when it cannot be told apart.
fn obstacle_named(task: &Task<'_>, at: Point) -> String {
    let radius = task.robot.radius();
    for o in task.moving {
        let alone = RoundMover::new(std::slice::from_ref(o), radius);
        let safe = alone.safe_intervals(at);
        if safe.first().is_none_or(|iv| iv.0 > 0.0) || safe.last().is_none_or(|iv| iv.1.is_finite())
        {
            return format!(" (`{}`)", o.name);
        }
    }
    String::new()
}

#[cfg(test)]
#[path = "sipp/tests.rs"]
mod tests;
