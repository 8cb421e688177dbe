//! `hybrid_astar` (SPEC 3.8; Dolgov, Thrun, Montemerlo & Diebel 2008):
//! A* for car robots over (x, y, θ) cells of `cell` × `cell` × 2π/`layers`,
//! each cell keeping one continuous pose (the cheapest that reached it).
//!
//! # Search
//! - A node's successors are the arcs of the turning radius and the
//!   straight (`L`, `S`, `R`) of arc length `step`, forward, and for a
//!   Reeds–Shepp car in reverse too. Cost: the length, times `reverse_cost`
//!   in reverse, plus `switch_cost` at each change of direction (a cusp).
//! - A successor's motion is checked by the motion checker for curves
//!   ([`car_path_free`]: never accepts what the validator for cars
//!   rejects), only when it would improve its cell.
//! - Heuristic: the larger of the steering length to the goal ignoring
//!   obstacles (times the cheapest direction's cost factor, 1) and the
//!   holonomic shortest path with obstacles: 8-connected Dijkstra from the
//!   goal over the (x, y) cells whose centre is not inside an obstacle,
//!   less one cell diagonal for the discretisation. Hybrid A* makes no
//!   optimality claim; the heuristic guides it.
//! - Analytic expansion: every `analytic` expansions, and at every expansion
//!   within 3 turning radii of the goal, the steering path from the node's
//!   pose to the goal is tried; the search ends when one is free. It is the
//!   only way the search reaches the goal exactly.
//! - The search is the search core's ([`best_first`]): a node is a cell,
//!   numbered when first reached, holding the pose of the cheapest arc
//!   into it; the core keeps g, the parents and the open list, and closes
//!   a cell once.
//! - Limits: `expansions`, `time` (set-up included), and at most
//!   [`MAX_NODES`] cells (about 60 bytes each); the holonomic grid is
//!   skipped beyond [`MAX_HOLONOMIC_CELLS`] cells (a note says so).
//!
//! The path is the chain of arcs from the start (consecutive arcs of the
//! same kind and direction merged) and the last steering path, validated as
//! a whole before it is returned.

use std::any::Any;
use std::collections::{BinaryHeap, HashMap};
use std::f64::consts::TAU;

use crate::contract::layers::{Colour, Drawing, Layer, Style, Svg};
use crate::contract::schema::{
    DefaultValue, MetricSpec, ParamSpec, RobotKind, ValueSpec, at_least, num, positive,
};
use crate::contract::{MetricValue, PlanArgs, PlanOutcome, Planner, Settings, Task};
use crate::geometry::car::{CarChecker, CarPath, DRAW_STEP};
use crate::geometry::steer::{Model, Segment, Steering, Turn};
use crate::geometry::collide::ObstacleIndex;
use crate::geometry::{Config, Point};
use crate::planners::deadline::Deadline;
use crate::contract::Limits;
use crate::planners::search::{Edge, Entry, Graph, SearchBuffers, Tree, best_first};

/// The most (x, y, θ) cells the search reaches (each keeping one
/// continuous pose, about 60 bytes with the core's state).
pub const MAX_NODES: usize = 4_000_000;

/// The most (x, y) cells of the holonomic heuristic's grid.
pub const MAX_HOLONOMIC_CELLS: usize = 4_000_000;

/// The most search edges drawn.
const MAX_DRAWN: usize = 20_000;

pub static PLANNER: Planner = Planner {
    kind: "hybrid_astar",
    summary: "hybrid A* for cars: arcs of the turning radius between (x, y, θ) cells that keep one continuous pose each",
    robots: &[RobotKind::Car],
    params: &[
        ParamSpec::new("cell", positive(false), num(1.0, "1"), "side of an (x, y) cell"),
        ParamSpec::new("layers", positive(true), num(72.0, "72"), "θ cells per turn"),
        ParamSpec::new(
            "step",
            positive(false),
            DefaultValue::Derived("√2 · cell"),
            "arc length of one successor",
        ),
        ParamSpec::new(
            "reverse_cost",
            at_least(1.0, false),
            num(2.0, "2"),
            "factor on the length driven in reverse (≥ 1)",
        ),
        ParamSpec::new(
            "switch_cost",
            at_least(0.0, false),
            DefaultValue::Derived("the turning radius"),
            "cost added at each change of direction (a cusp)",
        ),
        ParamSpec::new(
            "analytic",
            ValueSpec::Number {
                min: 1.0,
                min_open: false,
                max: 1e9,
                integer: true,
            },
            num(10.0, "10"),
            "every how many expansions the steering path to the goal is tried",
        ),
    ],
    metrics: &[
        MetricSpec::num("generated", "poses put on the open list"),
        MetricSpec::num("analytic_tries", "steering paths to the goal tried"),
    ],
    limits: &["expansions", "time"],
    needs_goal: true,
    randomized: false,
    grids: true,
    time: false,
    check,
};

/// The settings of a `hybrid_astar` plan.
#[derive(Clone, Debug)]
pub struct HybridAstar {
    pub cell: f64,
    pub layers: u32,
    pub step: f64,
    pub reverse_cost: f64,
    /// `None`: the turning radius.
    pub switch_cost: Option<f64>,
    pub analytic: u64,
}

fn check(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    let cell = args.num("cell");
    Some(Box::new(HybridAstar {
        cell,
        layers: args.num("layers") as u32,
        step: args
            .opt_num("step")
            .unwrap_or(std::f64::consts::SQRT_2 * cell),
        reverse_cost: args.num("reverse_cost"),
        switch_cost: args.opt_num("switch_cost"),
        analytic: args.num("analytic") as u64,
    }))
}

impl Settings for HybridAstar {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        let (Some(steering), Some(goal)) = (task.steering, task.goal) else {
            return PlanOutcome {
                notes: vec!["`hybrid_astar` plans for car robots, to a goal".into()],
                ..PlanOutcome::default()
            };
        };
        if task.start_is_goal() {
            let mut out = PlanOutcome::at_goal(task.start);
            out.extra.insert("generated".into(), MetricValue::Num(1.0));
            out.extra
                .insert("analytic_tries".into(), MetricValue::Num(0.0));
            out.car = Some(CarPath {
                start: task.start,
                steering,
                segments: Vec::new(),
            });
            return out;
        }
        Search::new(self, task, steering, goal).run()
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// The search graph of the search core ([`best_first`]): a node is an
/// (x, y, θ) cell, numbered in the order the search first reaches it, and
/// holds one continuous pose — the one of the cheapest arc into it so far
/// (the core keeps g and the parents, and never updates a closed cell).
struct Search<'a> {
    s: &'a HybridAstar,
    task: &'a Task<'a>,
    steering: Steering,
    goal: Config,
    checker: CarChecker,
    deadline: Deadline,
    holonomic: Option<Holonomic>,
    /// The number of each cell reached.
    ids: HashMap<u64, u32>,
    /// Per cell: its pose and the arc into it (length 0 for the start).
    poses: Vec<Config>,
    arcs: Vec<Segment>,
    /// The successors of the node being expanded: their pose and arc.
    candidates: Vec<(Config, Segment)>,
    switch_cost: f64,
    expanded: u64,
    generated: u64,
    analytic_tries: u64,
    /// The node whose steering path to the goal is free, and that path.
    found: Option<(usize, CarPath)>,
    /// Why the search stopped early (the core gives up on a `false` from
    /// `before_expand`).
    stopped: Option<String>,
    /// More cells than [`MAX_NODES`] were reached.
    full: bool,
    drawn: Vec<Vec<Point>>,
    notes: Vec<String>,
}

impl<'a> Search<'a> {
    fn new(s: &'a HybridAstar, task: &'a Task<'a>, steering: Steering, goal: Config) -> Self {
        let deadline = Deadline::start(&task.limits);
        let mut notes = Vec::new();
        let holonomic = Holonomic::new(task, s.cell, goal, &deadline);
        if holonomic.is_none() && !deadline.passed() {
            notes.push(format!(
                "the holonomic heuristic was skipped: the world has more than {MAX_HOLONOMIC_CELLS} cells of {}",
                s.cell
            ));
        }
        Search {
            s,
            task,
            steering,
            goal,
            checker: task.car_checker(),
            deadline,
            holonomic,
            ids: HashMap::new(),
            poses: Vec::new(),
            arcs: Vec::new(),
            candidates: Vec::new(),
            switch_cost: s.switch_cost.unwrap_or(steering.radius),
            expanded: 0,
            generated: 0,
            analytic_tries: 0,
            found: None,
            stopped: None,
            full: false,
            drawn: Vec::new(),
            notes,
        }
    }

    /// The (x, y, θ) cell of a pose.
    fn key(&self, c: Config) -> u64 {
        let b = &self.task.world.bounds;
        let ix = ((c.x - b.min.x) / self.s.cell).floor().max(0.0) as u64;
        let iy = ((c.y - b.min.y) / self.s.cell).floor().max(0.0) as u64;
        let layers = u64::from(self.s.layers);
        let k = ((c.theta.rem_euclid(TAU) / TAU * layers as f64).round() as u64) % layers;
        (ix.min(0x1f_ffff) << 42) | (iy.min(0x1f_ffff) << 21) | k.min(0x1f_ffff)
    }

    /// The number of the cell of `pose`, numbering it (with `pose` as its
    /// pose) when first reached; `None` once [`MAX_NODES`] cells are.
    fn cell(&mut self, pose: Config, arc: Segment) -> Option<usize> {
        let key = self.key(pose);
        if let Some(&id) = self.ids.get(&key) {
            return Some(id as usize);
        }
        if self.poses.len() >= MAX_NODES {
            self.full = true;
            return None;
        }
        let id = self.poses.len();
        self.ids.insert(key, id as u32);
        self.poses.push(pose);
        self.arcs.push(arc);
        Some(id)
    }

    fn h(&self, c: Config) -> f64 {
        let steer = self.steering.distance(c, self.goal);
        let hol = self.holonomic.as_ref().map_or(0.0, |h| h.at(c));
        steer.max(hol)
    }

    fn run(mut self) -> PlanOutcome {
        let start = self.task.start;
        let mut out = PlanOutcome::default();
        let none = Segment {
            turn: Turn::S,
            length: 0.0,
        };
        let Some(first) = self.cell(start, none) else {
            unreachable!("the first cell always gets a number")
        };
        self.generated = 1;
        // The time limit is the plan's deadline, asked in `before_expand`
        // (it counts the holonomic grid's set-up too).
        let limits = Limits {
            expansions: self.task.limits.expansions,
            ..Limits::default()
        };
        let result = best_first(
            &mut self,
            &[first],
            &limits,
            false,
            &mut SearchBuffers::paged(),
        );
        out.expanded = result.expanded;
        out.extra.insert(
            "generated".into(),
            MetricValue::Num(self.generated as f64),
        );
        out.extra.insert(
            "analytic_tries".into(),
            MetricValue::Num(self.analytic_tries as f64),
        );
        out.notes = std::mem::take(&mut self.notes);
        if self.task.draw && !self.drawn.is_empty() {
            out.layers.push(Layer::new(
                "search",
                Drawing::Polylines(std::mem::take(&mut self.drawn)),
                Style::new(Colour::Faint, 0.5, 16.0).svg(Svg::line(0.3).key("search arcs")),
            ));
        }
        match (result.nodes, self.found.take()) {
            (Some(nodes), Some((_, tail))) => {
                let car = self.path_to(&nodes, &tail);
                // The pieces were checked one by one; the whole, integrated
                // from the start, is checked again before it is returned.
                if self.checker.path_free(&car) && car.ends_on(self.goal) {
                    let mut poses = car.poses(DRAW_STEP);
                    if let Some(last) = poses.last_mut() {
                        *last = self.goal;
                    }
                    out.cost = Some(self.cost_of(&car));
                    out.path = Some(poses);
                    out.car = Some(car);
                } else {
                    out.notes.push(
                        "the path found failed the motion check when checked whole (a touching contact, to rounding); no path is returned".into(),
                    );
                }
            }
            _ if result.gave_up => {
                out.gave_up = true;
                out.notes.push(self.stopped.take().unwrap_or_else(|| {
                    format!(
                        "the expansion limit ({}) was reached without a path",
                        limits.expansions.unwrap_or(u64::MAX)
                    )
                }));
            }
            _ => {
                let mut note = "every cell reachable from the start was expanded: no path (at this cell size and step)".to_string();
                let turn = self.s.step / self.steering.radius;
                if !self
                    .steering
                    .distance(self.task.start, self.goal)
                    .is_finite()
                {
                    // So tiny a radius that no steering length is finite:
                    // the radius, not the step, is what to change.
                    note.push_str("; ");
                    note.push_str(&self.steering.too_far_note());
                } else if turn > std::f64::consts::PI {
                    // Arcs of more than half a turn end near their own
                    // start (and one of a vast angle is too long to
                    // validate): the search can only go straight.
                    note.push_str(&format!(
                        "; an arc of `step` ({:.4}) turns {turn:.3e} rad at the turning radius {:e}, more than half a turn: lower `step` below π times the radius",
                        self.s.step, self.steering.radius
                    ));
                }
                out.notes.push(note);
            }
        }
        out
    }

    /// The steering path from `pose` to the goal, when it is tried now and
    /// free.
    fn analytic(&mut self, pose: Config) -> Option<CarPath> {
        let near = (pose.x - self.goal.x).hypot(pose.y - self.goal.y) <= 3.0 * self.steering.radius;
        if !(near || self.expanded % self.s.analytic == 1 || self.s.analytic == 1) {
            return None;
        }
        self.analytic_tries += 1;
        let curve = self.steering.shortest(pose, self.goal);
        if !curve.length().is_finite() {
            return None;
        }
        let tail = CarPath::from_steer(pose, self.steering, &curve);
        self.checker.path_free(&tail).then_some(tail)
    }

    /// The car path along the cells `nodes` (from the start), then `tail`,
    /// with consecutive segments of the same kind and direction merged.
    fn path_to(&self, nodes: &[usize], tail: &CarPath) -> CarPath {
        let arcs = nodes[1..].iter().map(|&n| self.arcs[n]);
        let mut merged: Vec<Segment> = Vec::new();
        for a in arcs.chain(tail.segments.iter().copied()) {
            if a.length == 0.0 {
                continue;
            }
            match merged.last_mut() {
                Some(m) if m.turn == a.turn && (m.length < 0.0) == (a.length < 0.0) => {
                    m.length += a.length;
                }
                _ => merged.push(a),
            }
        }
        CarPath {
            start: self.task.start,
            steering: self.steering,
            segments: merged,
        }
    }

    /// The path's cost in the search's terms: reverse length weighted,
    /// switches charged.
    fn cost_of(&self, car: &CarPath) -> f64 {
        let reverse = car.reverse_length();
        let forward = car.length() - reverse;
        forward + self.s.reverse_cost * reverse + self.switch_cost * car.cusps() as f64
    }
}

impl Graph for Search<'_> {
    fn node_count(&self) -> usize {
        MAX_NODES
    }

    /// The arcs of the turning radius and the straight of length `step`,
    /// forward and (Reeds–Shepp) in reverse; a change of direction costs
    /// `switch_cost` more.
    fn successors(&mut self, node: usize, out: &mut Vec<Edge>) {
        let (pose, into) = (self.poses[node], self.arcs[node]);
        let directions: &[f64] = match self.steering.model {
            Model::Dubins => &[1.0],
            Model::ReedsShepp => &[1.0, -1.0],
        };
        self.candidates.clear();
        for &dir in directions {
            for turn in [Turn::L, Turn::S, Turn::R] {
                let arc = Segment {
                    turn,
                    length: dir * self.s.step,
                };
                let end = arc.end(pose, self.steering.radius).wrapped();
                let Some(to) = self.cell(end, arc) else {
                    return;
                };
                let mut cost = self.s.step * if dir < 0.0 { self.s.reverse_cost } else { 1.0 };
                if node != 0 && (into.length < 0.0) != (dir < 0.0) {
                    cost += self.switch_cost;
                }
                out.push(Edge {
                    to,
                    cost,
                    label: self.candidates.len() as u32,
                });
                self.candidates.push((end, arc));
            }
        }
    }

    /// The arc's motion, checked by the motion checker for curves; a free
    /// arc gives its end pose to the cell.
    fn usable(&mut self, from: usize, label: u32, to: usize) -> bool {
        let (end, arc) = self.candidates[label as usize];
        let piece = CarPath {
            start: self.poses[from],
            steering: self.steering,
            segments: vec![arc],
        };
        if !self.checker.path_free(&piece) {
            return false;
        }
        self.poses[to] = end;
        self.arcs[to] = arc;
        self.generated += 1;
        if self.task.draw && self.drawn.len() < MAX_DRAWN {
            self.drawn
                .push(piece.poses(DRAW_STEP).iter().map(Config::xy).collect());
        }
        true
    }

    fn heuristic(&self, node: usize) -> f64 {
        self.h(self.poses[node])
    }

    fn is_goal(&self, node: usize) -> bool {
        self.found.as_ref().is_some_and(|(n, _)| *n == node)
    }

    /// Stops at the deadline or the cell cap; tries the analytic expansion
    /// (the only way the goal is reached exactly).
    fn before_expand(&mut self, node: usize, _tree: &Tree<'_>) -> bool {
        if self.full {
            self.stopped = Some(format!(
                "the search reached its cap of {MAX_NODES} poses without a path"
            ));
            return false;
        }
        if self.deadline.passed() {
            self.stopped = Some("the time limit was reached without a path".into());
            return false;
        }
        self.expanded += 1;
        if let Some(tail) = self.analytic(self.poses[node]) {
            self.found = Some((node, tail));
        }
        true
    }
}

/// The holonomic heuristic: the 8-connected distance from each (x, y) cell
/// to the goal's, over cells whose centre is free for a point.
struct Holonomic {
    min: Point,
    cell: f64,
    nx: usize,
    ny: usize,
    dist: Vec<f64>,
}

impl Holonomic {
    fn new(task: &Task<'_>, cell: f64, goal: Config, deadline: &Deadline) -> Option<Self> {
        let b = task.world.bounds;
        let nx = ((b.max.x - b.min.x) / cell).ceil().max(1.0);
        let ny = ((b.max.y - b.min.y) / cell).ceil().max(1.0);
        if nx * ny > MAX_HOLONOMIC_CELLS as f64 {
            return None;
        }
        let (nx, ny) = (nx as usize, ny as usize);
        let points = ObstacleIndex::new(task.world);
        let mut free = vec![false; nx * ny];
        for j in 0..ny {
            if deadline.passed() {
                return None;
            }
            for i in 0..nx {
                let c = Config::new(
                    b.min.x + (i as f64 + 0.5) * cell,
                    b.min.y + (j as f64 + 0.5) * cell,
                    0.0,
                );
                free[j * nx + i] = points.disk_free(c.xy(), 0.0);
            }
        }
        let mut h = Holonomic {
            min: b.min,
            cell,
            nx,
            ny,
            dist: vec![f64::INFINITY; nx * ny],
        };
        let g = h.index(goal);
        h.dist[g] = 0.0;
        free[g] = true;
        let mut open = BinaryHeap::new();
        open.push(Entry::new(0.0, 0.0, g));
        while let Some(entry) = open.pop() {
            let (f, u) = (entry.f(), entry.node());
            if f > h.dist[u] {
                continue;
            }
            let (ux, uy) = ((u % nx) as i64, (u / nx) as i64);
            for (dx, dy) in [
                (1, 0),
                (-1, 0),
                (0, 1),
                (0, -1),
                (1, 1),
                (1, -1),
                (-1, 1),
                (-1, -1),
            ] {
                let (vx, vy) = (ux + dx, uy + dy);
                if vx < 0 || vy < 0 || vx >= nx as i64 || vy >= ny as i64 {
                    continue;
                }
                let v = vy as usize * nx + vx as usize;
                if !free[v] {
                    continue;
                }
                let step = if dx != 0 && dy != 0 {
                    std::f64::consts::SQRT_2
                } else {
                    1.0
                } * cell;
                let d = f + step;
                if d < h.dist[v] {
                    h.dist[v] = d;
                    open.push(Entry::new(d, d, v));
                }
            }
        }
        Some(h)
    }

    fn index(&self, c: Config) -> usize {
        let i = (((c.x - self.min.x) / self.cell).floor().max(0.0) as usize).min(self.nx - 1);
        let j = (((c.y - self.min.y) / self.cell).floor().max(0.0) as usize).min(self.ny - 1);
        j * self.nx + i
    }

    /// The distance less one cell diagonal (the discretisation's slack);
    /// 0 where the goal cannot be reached on the grid (the car may still
    /// find a way the grid does not see).
    fn at(&self, c: Config) -> f64 {
        let d = self.dist[self.index(c)];
        if d.is_finite() {
            (d - std::f64::consts::SQRT_2 * self.cell).max(0.0)
        } else {
            0.0
        }
    }
}
