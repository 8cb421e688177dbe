//! `cbs` (SPEC 3.11): conflict-based search (Sharon, Stern, Felner and
//! Sturtevant, AIJ 2015) for a team under grid MAPF semantics, optimal in
//! the sum of costs.
//!
//! The high level searches a tree of constraint sets (`cbs/tree.rs`),
//! least f = sum of costs + WDG heuristic first: each node holds one
//! shortest path per agent that respects the node's constraints. When the
//! paths conflict (two agents on one point at a step, or swapping points
//! in one step), the node splits in two (`cbs/symmetry.rs`: the conflict
//! ranked first, split the standard way or by target, rectangle or corridor
//! reasoning) and the agents a child's constraints bind plan again. The
//! first node without a conflict is an optimal solution.
//!
//! The low level (`cbs/low.rs`) is A* in (point, step) with each agent's
//! exact distance to its goal (or the wait its constraints ask, if
//! longer) as the heuristic, ties broken by fewer conflicts with the other
//! agents' paths (the conflict-avoidance table), which keeps the tree
//! small. It is finite, so an agent with no way is known at once.
//!
//! With pictures on, the places of the conflicts the tree resolved are a
//! layer `conflicts` (an edge conflict at the middle of its edge).
//!
//! CBS does not know when a team has no solution (two agents swapping in a
//! corridor without a bay): it searches until a limit, or until its tree
//! outgrows [`MAX_STORED`]; `lacam` says when none exists.

use std::any::Any;
use std::sync::Arc;

use symmetry::Conflict;
use tree::{Grower, Grown, Places};

use crate::contract::layers::{Colour, Drawing, Layer, Style, Svg};
use crate::contract::schema::{MetricSpec, RobotKind};
use crate::contract::{MetricValue, PlanArgs, PlanOutcome, Planner, Settings, Task};
use crate::planners::deadline::Deadline;
use crate::planners::lattice::LatticeSpec;
use crate::planners::mapf::{Graph, MAPF_PARAMS, Node, check_mapf_lattice};

/// `cbs` in the registry.
pub static PLANNER: Planner = Planner {
    kind: "cbs",
    summary: "conflict-based search with symmetry reasoning and the WDG heuristic: a team's optimal sum of costs under grid MAPF",
    robots: &[RobotKind::Team],
    params: &MAPF_PARAMS,
    metrics: &[
        MetricSpec::num("high_level", "constraint-tree nodes expanded"),
        MetricSpec::num("low_level", "single-agent searches run"),
    ],
    limits: &["expansions", "time", "cells"],
    needs_goal: false,
    randomized: false,
    grids: true,
    time: false,
    check,
};

/// A `cbs` plan's settings.
#[derive(Clone, Debug)]
pub struct Cbs {
    pub lattice: LatticeSpec,
}

fn check(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    let lattice = check_mapf_lattice(args)?;
    Some(Box::new(Cbs { lattice }))
}

impl Settings for Cbs {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        plan(task, self)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// The most path steps and constraints the constraint tree may hold in
/// all (about 2 GiB): a team CBS cannot solve within it is given up with a
/// note, not searched until the memory runs out.
pub const MAX_STORED: usize = 1 << 28;

/// The most resolved conflicts drawn (each place once).
const MAX_DRAWN_CONFLICTS: usize = 10_000;

/// A constraint of the tree on one agent.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct Constraint {
    agent: u32,
    rule: Rule,
}

/// What a [`Constraint`] forbids.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Rule {
    /// The agent is not at `v` at step `t`.
    Vertex { v: Node, t: u32 },
    /// The agent does not move `u` → `v` into step `t`.
    Edge { u: Node, v: Node, t: u32 },
    /// The agent arrives at its goal for the last time after step `t`.
    FinishAfter { t: u32 },
    /// The agent rests at its goal `v` from step `t` at the latest, so no
    /// other agent is at `v` at step `t` or later.
    RestsFrom { v: Node, t: u32 },
}

/// The agent number, in a constraint, of any agent but the ones a table,
/// an MDD or a pair's tree is for (another agent resting at its goal binds
/// them all).
const OTHER: u32 = u32::MAX;

/// The constraints of `constraints` that bind `agents` — their own,
/// renumbered by their place in `agents`, and every agent's rest at its
/// goal, the others' as [`OTHER`]'s — which, with their starts, goals and
/// costs, determine their searches.
fn binding(constraints: &[Constraint], agents: &[u32]) -> Vec<Constraint> {
    constraints
        .iter()
        .filter_map(|c| {
            let agent = match agents.iter().position(|&a| a == c.agent) {
                Some(k) => k as u32,
                None if matches!(c.rule, Rule::RestsFrom { .. }) => OTHER,
                None => return None,
            };
            Some(Constraint { agent, rule: c.rule })
        })
        .collect()
}

/// The agents a tree is grown for.
struct Team<'a> {
    pub graph: &'a Graph,
    pub starts: Vec<Node>,
    pub goals: Vec<Node>,
    pub dists: Vec<&'a [u32]>,
}

/// A node of the constraint tree.
struct CtNode {
    constraints: Arc<Vec<Constraint>>,
    paths: Vec<Arc<Vec<Node>>>,
    cost: u64,
    found: Found,
    /// The heuristic: what the subtree adds at least to `cost` …
    h: u64,
    /// … once computed (until then, what its parent's f implies).
    h_known: bool,
}

/// The conflicts of a node's paths.
#[derive(Default)]
struct Found {
    /// The first [`CLASSIFIED`], in time order.
    first: Vec<Conflict>,
    /// How many in all (the tree's tie-break).
    count: usize,
    /// Every pair of agents that conflict, once.
    pairs: Vec<(u32, u32)>,
}

fn at(path: &[Node], t: usize) -> Node {
    path[t.min(path.len() - 1)]
}

/// A point's lattice cell.
type Cell = (i64, i64);

fn cell(graph: &Graph, v: Node) -> Cell {
    let (i, j) = graph.spec.coords(v as usize);
    (i as i64, j as i64)
}

fn manhattan(p: Cell, q: Cell) -> i64 {
    (p.0 - q.0).abs() + (p.1 - q.1).abs()
}

/// Whether `u` and `v` are one move (or a wait) apart.
fn adjacent(graph: &Graph, u: Node, v: Node) -> bool {
    u == v || graph.neighbours(u).any(|w| w == v)
}

/// From the pairs of points `here` two agents are at, the pairs they can
/// be at a step later, one in `next_a` and one in `next_b`, each a move
/// or a wait away, without meeting (one point, or a swap along an edge);
/// sorted, each once. The step of the joint searches over two MDDs.
fn apart_next(graph: &Graph, here: &[(Node, Node)], next_a: &[Node], next_b: &[Node]) -> Vec<(Node, Node)> {
    let mut next: Vec<(Node, Node)> = Vec::new();
    for &(u, v) in here {
        for &x in next_a.iter().filter(|&&x| adjacent(graph, u, x)) {
            for &y in next_b.iter().filter(|&&y| adjacent(graph, v, y)) {
                if x != y && !(x == v && y == u) {
                    next.push((x, y));
                }
            }
        }
    }
    next.sort_unstable();
    next.dedup();
    next
}

/// The conflicts of `paths` on a graph of `nodes` points.
fn conflicts(paths: &[Arc<Vec<Node>>], nodes: usize) -> Found {
    let horizon = paths.iter().map(|p| p.len()).max().unwrap_or(0);
    let mut first = Vec::new();
    let mut count = 0;
    let mut pairs = Vec::new();
    // Who is at each point at the step (the step + 1 in the high half, so
    // a stale entry is never read as this step's).
    let mut here = vec![0u64; nodes];
    let mut before = vec![0u64; nodes];
    let owner = |slots: &[u64], v: Node, t: usize| {
        let s = slots[v as usize];
        ((s >> 32) as usize == t + 1).then_some(s as u32)
    };
    for t in 0..horizon {
        std::mem::swap(&mut here, &mut before);
        for (a, p) in paths.iter().enumerate() {
            let v = at(p, t);
            if let Some(b) = owner(&here, v, t) {
                count += 1;
                pairs.push((b.min(a as u32), b.max(a as u32)));
                if first.len() < CLASSIFIED {
                    first.push(Conflict::Vertex {
                        a: b,
                        b: a as u32,
                        v,
                        t: t as u32,
                    });
                }
            } else {
                here[v as usize] = ((t as u64 + 1) << 32) | a as u64;
            }
        }
        if t == 0 {
            continue;
        }
        for (a, p) in paths.iter().enumerate() {
            let (u, v) = (at(p, t - 1), at(p, t));
            if u == v {
                continue;
            }
            if let Some(b) = owner(&before, v, t - 1)
                && b as usize > a
                && at(&paths[b as usize], t) == u
            {
                count += 1;
                pairs.push((a as u32, b));
                if first.len() < CLASSIFIED {
                    first.push(Conflict::Edge {
                        a: a as u32,
                        b,
                        u,
                        v,
                        t: t as u32,
                    });
                }
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    Found { first, count, pairs }
}

/// The most conflicts of a node classified before one is chosen (ranking
/// them all, not only the earliest, halved the nodes expanded on
/// random-32-32-10 with 80 agents).
const CLASSIFIED: usize = 4096;

/// The sum of costs: each path's length minus one (paths end at their last
/// arrival).
fn cost_of(paths: &[Arc<Vec<Node>>]) -> u64 {
    paths.iter().map(|p| p.len() as u64 - 1).sum()
}

/// What the search is allowed, and what it has spent.
struct Budget<'a> {
    deadline: &'a Deadline,
    max_expansions: u64,
    expanded: u64,
    low_level: u64,
    stored: usize,
}

impl Budget<'_> {
    fn exhausted(&self) -> bool {
        self.expanded >= self.max_expansions
            || self.stored > MAX_STORED
            || (self.expanded.is_multiple_of(1024) && self.deadline.passed())
    }
}

/// How many splits of each kind the tree made, and how many children it
/// adopted in place of their parent (for the tests and the benchmarks).
#[derive(Clone, Copy, Debug, Default)]
pub struct Counts {
    pub standard: u64,
    pub rectangle: u64,
    pub generalised: u64,
    pub corridor: u64,
    pub target: u64,
    pub bypasses: u64,
}

/// The agents a child must plan again: those whose paths break one of the
/// constraints it adds.
fn to_replan(added: &[Constraint], paths: &[Arc<Vec<Node>>]) -> Vec<usize> {
    let mut agents: Vec<usize> = Vec::new();
    for c in added {
        match c.rule {
            Rule::RestsFrom { v, t } => {
                for (x, p) in paths.iter().enumerate() {
                    if x != c.agent as usize && p.iter().skip(t as usize).any(|&w| w == v) {
                        agents.push(x);
                    }
                }
            }
            _ => agents.push(c.agent as usize),
        }
    }
    agents.sort_unstable();
    agents.dedup();
    agents
}

/// Runs a `cbs` plan.
pub fn plan(task: &Task<'_>, settings: &Cbs) -> PlanOutcome {
    plan_counted(task, settings, &mut Counts::default())
}

/// Runs a `cbs` plan and counts its splits into `counts`.
pub fn plan_counted(task: &Task<'_>, settings: &Cbs, counts: &mut Counts) -> PlanOutcome {
    let deadline = Deadline::start(&task.limits);
    let mut out = PlanOutcome::default();
    let mut budget = Budget {
        deadline: &deadline,
        max_expansions: task.limits.expansions.unwrap_or(u64::MAX),
        expanded: 0,
        low_level: 0,
        stored: 0,
    };
    let mut resolved = Vec::new();
    let found = search(task, settings, &mut budget, &mut out, &mut resolved, counts);
    if task.draw && !resolved.is_empty() {
        out.layers.push(Layer::new(
            "conflicts",
            Drawing::Points(resolved),
            Style::new(Colour::Red, 4.0, 45.0).svg(Svg::fill(0.8).key("conflicts resolved")),
        ));
    }
    out.expanded = budget.expanded;
    out.extra.insert(
        "low_level".into(),
        MetricValue::Num(budget.low_level as f64),
    );
    out.extra
        .entry("high_level".into())
        .or_insert(MetricValue::Num(0.0));
    if let Some((graph, paths)) = found {
        out.cost = Some(cost_of(&paths) as f64);
        out.agents = Some(
            paths
                .iter()
                .map(|p| p.iter().map(|&v| graph.point(v)).collect())
                .collect(),
        );
    }
    out
}

fn search(
    task: &Task<'_>,
    settings: &Cbs,
    budget: &mut Budget<'_>,
    out: &mut PlanOutcome,
    resolved: &mut Vec<crate::geometry::Point>,
    counts: &mut Counts,
) -> Option<(Graph, Vec<Arc<Vec<Node>>>)> {
    let graph = match Graph::build(task, settings.lattice, budget.deadline) {
        Ok(g) => g,
        Err(note) => {
            out.gave_up = budget.deadline.passed();
            out.notes.push(note);
            return None;
        }
    };
    let n = task.agents.len();
    if let Some(note) = crate::planners::mapf::too_many_distances(&graph, n) {
        out.gave_up = true;
        out.notes.push(note);
        return None;
    }
    let dists: Vec<Vec<u32>> = graph.goals.iter().map(|&g| graph.distances_to(g)).collect();
    for (a, agent) in task.agents.iter().enumerate() {
        if dists[a][graph.starts[a] as usize] == u32::MAX {
            out.notes.push(format!(
                "agent `{}` cannot reach its goal: no team has a solution",
                agent.name
            ));
            return None;
        }
    }
    let team = Team {
        graph: &graph,
        starts: graph.starts.clone(),
        goals: graph.goals.clone(),
        dists: dists.iter().map(Vec::as_slice).collect(),
    };
    let mut places = Places::new();
    let mut grower = Grower::new(budget, counts);
    let grown = grower.grow(&team, Vec::new(), true, u64::MAX, Some(&mut places));
    out.extra
        .insert("high_level".into(), MetricValue::Num(grower.high as f64));
    if task.draw {
        let mut places: Vec<(Node, Node)> = places.into_iter().collect();
        places.sort_unstable();
        resolved.extend(places.into_iter().take(MAX_DRAWN_CONFLICTS).map(|(u, v)| {
            crate::geometry::Point::from((graph.point(u).coords + graph.point(v).coords) / 2.0)
        }));
    }
    match grown {
        Grown::Solved(paths) => Some((graph, paths)),
        Grown::NoSolution => {
            out.notes
                .push("the constraint tree is exhausted: the team has no solution".into());
            None
        }
        Grown::Stopped { .. } => stopped(out),
    }
}

fn stopped<T>(out: &mut PlanOutcome) -> Option<T> {
    out.gave_up = true;
    out.notes.push(
        "a limit was reached before a conflict-free solution (CBS cannot tell a team without a solution; `lacam` can)"
            .into(),
    );
    None
}

#[path = "cbs/corridor.rs"]
mod corridor;
#[path = "cbs/low.rs"]
mod low;
#[path = "cbs/overlap.rs"]
mod overlap;
#[path = "cbs/symmetry.rs"]
mod symmetry;
#[path = "cbs/tree.rs"]
mod tree;
#[cfg(test)]
#[path = "cbs/tests.rs"]
mod tests;
