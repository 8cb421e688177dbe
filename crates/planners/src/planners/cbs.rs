//! `cbs` (SPEC 3.11): conflict-based search (Sharon, Stern, Felner and
//! Sturtevant, AIJ 2015) for a team under grid MAPF semantics, optimal in
//! the sum of costs.
//!
//! The high level searches a tree of constraint sets, cheapest sum of
//! costs first: each node holds one shortest path per agent that respects
//! the node's constraints. When the paths conflict (two agents on one
//! point at a step, or swapping points in one step), the node splits in
//! two — one agent or the other may not be there then — and only the
//! constrained agent plans again. The first node without a conflict is an
//! optimal solution.
//!
//! The low level is A* in (point, step) with each agent's exact distance
//! to its goal as the heuristic, ties broken by fewer conflicts with the
//! other agents' paths (the conflict-avoidance table), which keeps the
//! tree small. Once a state is past the agent's last constraint, nothing
//! can stop it: the rest of the path is its shortest way to the goal, so
//! the search space is finite and an agent with no way is known at once.
//!
//! With pictures on, the places of the conflicts the tree resolved are a
//! layer `conflicts` (an edge conflict at the middle of its edge).
//!
//! CBS does not know when a team has no solution (two agents swapping in a
//! corridor without a bay): it searches until a limit, or until its tree
//! outgrows [`MAX_STORED`]; `lacam` says when none exists.

use std::any::Any;
use std::cmp::{Ordering, Reverse};
use std::collections::{BinaryHeap, HashMap, HashSet};
use std::sync::Arc;

use crate::contract::layers::{Colour, Drawing, Layer, Style, Svg};
use crate::contract::schema::{MetricSpec, RobotKind};
use crate::contract::{MetricValue, PlanArgs, PlanOutcome, Planner, Settings, Task};
use crate::planners::deadline::Deadline;
use crate::planners::lattice::LatticeSpec;
use crate::planners::mapf::{Graph, MAPF_PARAMS, Node, check_mapf_lattice};

/// `cbs` in the registry.
pub static PLANNER: Planner = Planner {
    kind: "cbs",
    summary: "conflict-based search: a team's optimal sum of costs under grid MAPF",
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

/// A constraint on one agent: not on `to` at step `t` (a vertex
/// constraint, `from` = [`VERTEX`]), or not moving `from` → `to` into step
/// `t` (an edge constraint).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct Constraint {
    agent: u32,
    from: Node,
    to: Node,
    t: u32,
}

const VERTEX: Node = Node::MAX;

/// A node of the constraint tree.
struct CtNode {
    constraints: Arc<Vec<Constraint>>,
    paths: Vec<Arc<Vec<Node>>>,
    cost: u64,
    conflicts: usize,
}

/// A conflict between two agents' paths.
#[derive(Clone, Copy, Debug)]
enum Conflict {
    Vertex { a: u32, b: u32, v: Node, t: u32 },
    Edge { a: u32, b: u32, u: Node, v: Node, t: u32 },
}

fn at(path: &[Node], t: usize) -> Node {
    path[t.min(path.len() - 1)]
}

/// The earliest `keep` conflicts, in time order, and how many pairs
/// conflict at all (the tree's tie-break).
fn conflicts(paths: &[Arc<Vec<Node>>], keep: usize) -> (Vec<Conflict>, usize) {
    let horizon = paths.iter().map(|p| p.len()).max().unwrap_or(0);
    let mut first = Vec::new();
    let mut count = 0;
    let mut here: HashMap<Node, u32> = HashMap::with_capacity(paths.len());
    let mut before: HashMap<Node, u32> = HashMap::with_capacity(paths.len());
    for t in 0..horizon {
        std::mem::swap(&mut here, &mut before);
        here.clear();
        for (a, p) in paths.iter().enumerate() {
            let v = at(p, t);
            if let Some(&b) = here.get(&v) {
                count += 1;
                if first.len() < keep {
                    first.push(Conflict::Vertex {
                        a: b,
                        b: a as u32,
                        v,
                        t: t as u32,
                    });
                }
            } else {
                here.insert(v, a as u32);
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
            if let Some(&b) = before.get(&v)
                && b as usize > a
                && at(&paths[b as usize], t) == u
            {
                count += 1;
                if first.len() < keep {
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
    (first, count)
}

/// The most conflicts of a node classified before one is chosen.
const CLASSIFIED: usize = 32;

/// The conflict to split on (Boyarski et al. 2015, "ICBS"): a cardinal one
/// (both children cost more: every shortest path of each agent under its
/// constraints is where the conflict is), else a semi-cardinal one, else
/// the earliest. Splitting on a cardinal conflict raises the tree's lower
/// bound at once, which keeps the tree small.
fn choose(graph: &Graph, dists: &[Vec<u32>], node: &CtNode, found: &[Conflict]) -> Option<Conflict> {
    let first = *found.first()?;
    if found.len() == 1 {
        return Some(first);
    }
    let mut mdds: HashMap<u32, Vec<Vec<Node>>> = HashMap::new();
    let mut mdd_of = |agent: u32| -> Vec<Vec<Node>> {
        mdds.entry(agent)
            .or_insert_with(|| {
                let mine: Vec<Constraint> = node
                    .constraints
                    .iter()
                    .copied()
                    .filter(|c| c.agent == agent)
                    .collect();
                let path = &node.paths[agent as usize];
                mdd(graph, &dists[agent as usize], path[0], *path.last().unwrap_or(&path[0]), path.len() - 1, &mine)
            })
            .clone()
    };
    // Whether every shortest path of `agent` is at `u` then `v` at `t`
    // (`u` = `v` for a vertex).
    let narrow = |levels: &[Vec<Node>], u: Node, v: Node, t: u32| {
        let level = |k: usize| -> &[Node] { levels.get(k).or(levels.last()).map_or(&[], Vec::as_slice) };
        let t = t as usize;
        level(t) == [v] && (u == v || (t > 0 && level(t - 1) == [u]))
    };
    let mut semi = None;
    for &c in found {
        let (a, b, ua, va, ub, vb, t) = match c {
            Conflict::Vertex { a, b, v, t } => (a, b, v, v, v, v, t),
            Conflict::Edge { a, b, u, v, t } => (a, b, u, v, v, u, t),
        };
        let ca = narrow(&mdd_of(a), ua, va, t);
        let cb = narrow(&mdd_of(b), ub, vb, t);
        if ca && cb {
            return Some(c);
        }
        if (ca || cb) && semi.is_none() {
            semi = Some(c);
        }
    }
    Some(semi.unwrap_or(first))
}

/// The multi-valued decision diagram of an agent's shortest paths of
/// `cost` steps under its constraints: for each step, the nodes some such
/// path is at (Sharon et al. 2013), sorted.
fn mdd(graph: &Graph, dist: &[u32], start: Node, goal: Node, cost: usize, mine: &[Constraint]) -> Vec<Vec<Node>> {
    let vertex = |v: Node, t: usize| mine.iter().any(|c| c.from == VERTEX && c.to == v && c.t as usize == t);
    let edge = |u: Node, v: Node, t: usize| mine.iter().any(|c| c.from == u && c.to == v && c.t as usize == t);
    let mut layers: Vec<Vec<Node>> = vec![vec![start]];
    for t in 1..=cost {
        let mut next: Vec<Node> = Vec::new();
        for &v in &layers[t - 1] {
            for w in graph.neighbours(v).chain(std::iter::once(v)) {
                if (dist[w as usize] as usize) <= cost - t && !vertex(w, t) && (w == v || !edge(v, w, t)) {
                    next.push(w);
                }
            }
        }
        next.sort_unstable();
        next.dedup();
        layers.push(next);
    }
    // Backwards from the goal at `cost`: the nodes that lead there.
    let mut keep: Vec<Vec<Node>> = vec![Vec::new(); cost + 1];
    keep[cost] = layers[cost].iter().copied().filter(|&v| v == goal).collect();
    for t in (0..cost).rev() {
        let after = std::mem::take(&mut keep[t + 1]);
        keep[t] = layers[t]
            .iter()
            .copied()
            .filter(|&v| {
                after.iter().any(|&w| {
                    w == v || (graph.neighbours(v).any(|x| x == w) && !edge(v, w, t + 1))
                })
            })
            .collect();
        keep[t + 1] = after;
    }
    keep
}

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

/// The outcome of one agent's search.
enum Low {
    Path(Vec<Node>),
    /// No path respects the constraints.
    None,
    /// A limit was reached.
    Stopped,
}

/// An A* state of the low level.
struct State {
    v: Node,
    t: u32,
    parent: u32,
}

#[derive(PartialEq, Eq)]
struct Open {
    f: u32,
    conflicts: u32,
    t: u32,
    id: u32,
}

impl Ord for Open {
    fn cmp(&self, o: &Self) -> Ordering {
        // Smallest f, then fewest conflicts, then deepest, then oldest.
        o.f.cmp(&self.f)
            .then(o.conflicts.cmp(&self.conflicts))
            .then(self.t.cmp(&o.t))
            .then(o.id.cmp(&self.id))
    }
}

impl PartialOrd for Open {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// The other agents' paths, for counting the conflicts a step would make.
struct Avoid<'a> {
    paths: &'a [Arc<Vec<Node>>],
    agent: usize,
}

impl Avoid<'_> {
    fn count(&self, u: Node, v: Node, t: u32) -> u32 {
        let t = t as usize;
        let mut n = 0;
        for (b, p) in self.paths.iter().enumerate() {
            if b == self.agent {
                continue;
            }
            let w = at(p, t);
            if w == v || (t > 0 && u != v && w == u && at(p, t - 1) == v) {
                n += 1;
            }
        }
        n
    }
}

/// One agent's shortest path from `start` under its constraints, fewest
/// conflicts with `avoid` among the shortest.
fn low_level(
    graph: &Graph,
    dist: &[u32],
    start: Node,
    goal: Node,
    mine: &[Constraint],
    avoid: &Avoid<'_>,
    budget: &mut Budget<'_>,
) -> Low {
    budget.low_level += 1;
    if dist[start as usize] == u32::MAX {
        return Low::None;
    }
    let blocked_vertex: HashSet<(Node, u32)> = mine
        .iter()
        .filter(|c| c.from == VERTEX)
        .map(|c| (c.to, c.t))
        .collect();
    let blocked_edge: HashSet<(Node, Node, u32)> = mine
        .iter()
        .filter(|c| c.from != VERTEX)
        .map(|c| (c.from, c.to, c.t))
        .collect();
    // After its last constraint nothing stops the agent; at its goal it may
    // stop only after the last constraint on the goal.
    let last = mine.iter().map(|c| c.t).max().unwrap_or(0);
    let goal_last = mine
        .iter()
        .filter(|c| c.from == VERTEX && c.to == goal)
        .map(|c| c.t)
        .max();
    let mut states = vec![State {
        v: start,
        t: 0,
        parent: u32::MAX,
    }];
    let mut seen: HashSet<(Node, u32)> = HashSet::from([(start, 0)]);
    let mut open = BinaryHeap::from([Open {
        f: dist[start as usize],
        conflicts: 0,
        t: 0,
        id: 0,
    }]);
    while let Some(Open { id, conflicts: c, .. }) = open.pop() {
        if budget.exhausted() {
            return Low::Stopped;
        }
        budget.expanded += 1;
        let State { v, t, .. } = states[id as usize];
        let done_waiting = goal_last.is_none_or(|g| t > g);
        if t >= last || (v == goal && done_waiting) {
            // Free from here: the shortest way to the goal.
            let mut path = Vec::new();
            let mut k = id;
            while k != u32::MAX {
                path.push(states[k as usize].v);
                k = states[k as usize].parent;
            }
            path.reverse();
            let mut w = v;
            while w != goal {
                w = graph
                    .neighbours(w)
                    .find(|&m| dist[m as usize] + 1 == dist[w as usize])
                    .expect("a node with a finite distance has a neighbour one step nearer");
                path.push(w);
            }
            return Low::Path(path);
        }
        let next = t + 1;
        for w in graph.neighbours(v).chain(std::iter::once(v)) {
            if dist[w as usize] == u32::MAX
                || blocked_vertex.contains(&(w, next))
                || (w != v && blocked_edge.contains(&(v, w, next)))
                || !seen.insert((w, next))
            {
                continue;
            }
            let conflicts = c + avoid.count(v, w, next);
            let nid = states.len() as u32;
            states.push(State {
                v: w,
                t: next,
                parent: id,
            });
            open.push(Open {
                f: next + dist[w as usize],
                conflicts,
                t: next,
                id: nid,
            });
        }
    }
    Low::None
}

/// Runs a `cbs` plan.
pub fn plan(task: &Task<'_>, settings: &Cbs) -> PlanOutcome {
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
    let found = search(task, settings, &mut budget, &mut out, &mut resolved);
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
) -> Option<(Graph, Vec<Arc<Vec<Node>>>)> {
    // Where the resolved conflicts were, once each (for the pictures).
    let mut seen = std::collections::HashSet::new();
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
    // The root: every agent's own shortest path.
    let mut paths: Vec<Arc<Vec<Node>>> = Vec::with_capacity(n);
    for (a, dist) in dists.iter().enumerate() {
        let avoid = Avoid {
            paths: &paths,
            agent: usize::MAX,
        };
        match low_level(&graph, dist, graph.starts[a], graph.goals[a], &[], &avoid, budget) {
            Low::Path(p) => paths.push(Arc::new(p)),
            Low::None => unreachable!("a reachable goal has a path without constraints"),
            Low::Stopped => return stopped(out),
        }
    }
    let (_, count) = conflicts(&paths, 0);
    let mut tree = vec![CtNode {
        constraints: Arc::new(Vec::new()),
        cost: cost_of(&paths),
        paths,
        conflicts: count,
    }];
    let mut open = BinaryHeap::from([Reverse((tree[0].cost, tree[0].conflicts, 0usize))]);
    let mut high = 0u64;
    while let Some(Reverse((_, _, id))) = open.pop() {
        if budget.exhausted() {
            return stopped(out);
        }
        high += 1;
        out.extra
            .insert("high_level".into(), MetricValue::Num(high as f64));
        let (found, _) = conflicts(&tree[id].paths, CLASSIFIED);
        let Some(conflict) = choose(&graph, &dists, &tree[id], &found) else {
            let paths = std::mem::take(&mut tree[id].paths);
            return Some((graph, paths));
        };
        if task.draw && resolved.len() < MAX_DRAWN_CONFLICTS {
            let (u, v) = match conflict {
                Conflict::Vertex { v, .. } => (v, v),
                Conflict::Edge { u, v, .. } => (u.min(v), u.max(v)),
            };
            if seen.insert((u, v)) {
                resolved.push(crate::geometry::Point::from(
                    (graph.point(u).coords + graph.point(v).coords) / 2.0,
                ));
            }
        }
        let split = match conflict {
            Conflict::Vertex { a, b, v, t } => [
                Constraint { agent: a, from: VERTEX, to: v, t },
                Constraint { agent: b, from: VERTEX, to: v, t },
            ],
            Conflict::Edge { a, b, u, v, t } => [
                Constraint { agent: a, from: u, to: v, t },
                Constraint { agent: b, from: v, to: u, t },
            ],
        };
        for c in split {
            let agent = c.agent as usize;
            let mut constraints = (*tree[id].constraints).clone();
            constraints.push(c);
            let mine: Vec<Constraint> = constraints
                .iter()
                .copied()
                .filter(|k| k.agent == c.agent)
                .collect();
            let avoid = Avoid {
                paths: &tree[id].paths,
                agent,
            };
            let path = match low_level(
                &graph,
                &dists[agent],
                graph.starts[agent],
                graph.goals[agent],
                &mine,
                &avoid,
                budget,
            ) {
                Low::Path(p) => p,
                Low::None => continue,
                Low::Stopped => return stopped(out),
            };
            budget.stored += constraints.len() + path.len();
            let mut paths = tree[id].paths.clone();
            paths[agent] = Arc::new(path);
            let (_, count) = conflicts(&paths, 0);
            let node = CtNode {
                cost: cost_of(&paths),
                constraints: Arc::new(constraints),
                paths,
                conflicts: count,
            };
            open.push(Reverse((node.cost, node.conflicts, tree.len())));
            tree.push(node);
        }
        // The expanded node's paths are no longer needed.
        tree[id].paths = Vec::new();
    }
    out.notes
        .push("the constraint tree is exhausted: the team has no solution".into());
    None
}

fn stopped<T>(out: &mut PlanOutcome) -> Option<T> {
    out.gave_up = true;
    out.notes.push(
        "a limit was reached before a conflict-free solution (CBS cannot tell a team without a solution; `lacam` can)"
            .into(),
    );
    None
}

#[cfg(test)]
#[path = "cbs/tests.rs"]
mod tests;
