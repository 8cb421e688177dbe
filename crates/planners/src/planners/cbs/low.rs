//! `cbs`'s low level: one agent's constraints as a table, its shortest
//! path under them (A* in (point, step)), and the diagram of all its
//! shortest paths (MDD) the high level classifies conflicts with.

use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::sync::Arc;

use super::{Budget, Constraint, Rule, cell, manhattan};
use crate::planners::mapf::{FastMap, FastSet, Graph, Node};

/// One agent's constraints, as its searches ask them.
pub(super) struct Table {
    vertex: FastSet<(Node, u32)>,
    edge: FastSet<(Node, Node, u32)>,
    /// Points another agent rests on from a step on: not there then or later.
    from: FastMap<Node, u32>,
    /// The agent's last arrival at its goal is at this step or later …
    min_finish: u32,
    /// … and at this step or earlier.
    max_finish: u32,
    /// The latest step a vertex constraint keeps the agent off its goal.
    goal_last: Option<u32>,
    /// From this step on, nothing but `from` and `max_finish` constrains
    /// the agent.
    horizon: u32,
}

impl Table {
    /// `agent`'s table from all of a node's constraints (a constraint that
    /// an agent rests at its goal binds every other agent).
    pub(super) fn new(agent: u32, goal: Node, constraints: &[Constraint]) -> Self {
        let mut table = Table {
            vertex: FastSet::default(),
            edge: FastSet::default(),
            from: FastMap::default(),
            min_finish: 0,
            max_finish: u32::MAX,
            goal_last: None,
            horizon: 0,
        };
        for c in constraints {
            let mine = c.agent == agent;
            match c.rule {
                Rule::Vertex { v, t } if mine => {
                    table.vertex.insert((v, t));
                    table.horizon = table.horizon.max(t);
                    if v == goal {
                        table.goal_last = table.goal_last.max(Some(t));
                    }
                }
                Rule::Edge { u, v, t } if mine => {
                    table.edge.insert((u, v, t));
                    table.horizon = table.horizon.max(t);
                }
                Rule::FinishAfter { t } if mine => {
                    table.min_finish = table.min_finish.max(t + 1);
                    table.horizon = table.horizon.max(t + 1);
                }
                Rule::RestsFrom { t, .. } if mine => table.max_finish = table.max_finish.min(t),
                Rule::RestsFrom { v, t } => {
                    let f = table.from.entry(v).or_insert(t);
                    *f = (*f).min(t);
                }
                _ => {}
            }
        }
        if let Some(&latest) = table.from.values().max() {
            table.horizon = table.horizon.max(latest);
        }
        table
    }

    /// Whether the agent may be at `v` at step `t`.
    pub(super) fn vertex_ok(&self, v: Node, t: u32) -> bool {
        !self.vertex.contains(&(v, t)) && self.from.get(&v).is_none_or(|&f| t < f)
    }

    /// Whether the agent may move `u` → `v` into step `t` (a wait always).
    pub(super) fn move_ok(&self, u: Node, v: Node, t: u32) -> bool {
        u == v || !self.edge.contains(&(u, v, t))
    }

    /// Whether the agent may arrive at its goal for the last time at `t`.
    fn may_finish(&self, goal: Node, t: u32) -> bool {
        self.goal_last.is_none_or(|g| t > g)
            && t >= self.min_finish
            && t <= self.max_finish
            && !self.from.contains_key(&goal)
    }
}

/// The outcome of one agent's search.
pub(super) enum Low {
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

/// The other agents' paths as a table, for counting the conflicts a step
/// would make (the conflict-avoidance table).
pub(super) struct Avoid {
    /// How many others are at a point at a step before they rest.
    at: FastMap<(Node, u32), u32>,
    /// The moves of the others: (from, to, into step).
    moves: FastSet<(Node, Node, u32)>,
    /// The points others rest on, from which step.
    rests: FastMap<Node, u32>,
}

impl Avoid {
    /// The table of every path but `agent`'s.
    pub(super) fn new(paths: &[Arc<Vec<Node>>], agent: usize) -> Self {
        let steps: usize = paths.iter().map(|p| p.len()).sum();
        let mut avoid = Avoid {
            at: FastMap::with_capacity_and_hasher(steps, Default::default()),
            moves: FastSet::with_capacity_and_hasher(steps, Default::default()),
            rests: FastMap::default(),
        };
        for (b, p) in paths.iter().enumerate() {
            if b != agent {
                avoid.add(p);
            }
        }
        avoid
    }

    /// Adds a path to the table.
    pub(super) fn add(&mut self, p: &[Node]) {
        let last = p.len() - 1;
        for (t, &v) in p[..last].iter().enumerate() {
            *self.at.entry((v, t as u32)).or_insert(0) += 1;
            if t > 0 && p[t - 1] != v {
                self.moves.insert((p[t - 1], v, t as u32));
            }
        }
        if last > 0 && p[last - 1] != p[last] {
            self.moves.insert((p[last - 1], p[last], last as u32));
        }
        self.rests.insert(p[last], last as u32);
    }

    fn count(&self, u: Node, v: Node, t: u32) -> u32 {
        let mut n = self.at.get(&(v, t)).copied().unwrap_or(0);
        n += u32::from(self.rests.get(&v).is_some_and(|&from| t >= from));
        n += u32::from(u != v && self.moves.contains(&(v, u, t)));
        n
    }
}

/// One agent's shortest path from `start` under its table, fewest
/// conflicts with `avoid` among the shortest.
///
/// Past the table's horizon only the points other agents rest on still
/// constrain the agent: without such points the rest of the way is its
/// shortest path to the goal, and with them the states of later steps
/// are one state per point, so the search is finite either way and an
/// agent with no way is known.
pub(super) fn low_level(
    graph: &Graph,
    dist: &[u32],
    start: Node,
    goal: Node,
    table: &Table,
    avoid: &Avoid,
    budget: &mut Budget<'_>,
) -> Low {
    budget.low_level += 1;
    if dist[start as usize] == u32::MAX || dist[start as usize] > table.max_finish || !table.vertex_ok(start, 0) {
        return Low::None;
    }
    let free_after = table.from.is_empty();
    // The agent rests at its goal at this step at the earliest: the
    // heuristic is the more of that wait and the distance.
    let finish_from = table.min_finish.max(table.goal_last.map_or(0, |g| g + 1));
    // The earliest step each state was reached at; past the horizon, one
    // state per point.
    let key = |v: Node, t: u32| (v, t.min(table.horizon + 1));
    let mut states = vec![State {
        v: start,
        t: 0,
        parent: u32::MAX,
    }];
    let mut seen: FastMap<(Node, u32), u32> = FastMap::default();
    seen.insert(key(start, 0), 0);
    let mut open = BinaryHeap::from([Open {
        f: dist[start as usize].max(finish_from),
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
        let free = free_after && t >= table.horizon;
        if free || (v == goal && table.may_finish(goal, t)) {
            let mut path = Vec::new();
            let mut k = id;
            while k != u32::MAX {
                path.push(states[k as usize].v);
                k = states[k as usize].parent;
            }
            path.reverse();
            // Free from here: the shortest way to the goal.
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
            let d = dist[w as usize];
            if d == u32::MAX
                || next.saturating_add(d) > table.max_finish
                || !table.vertex_ok(w, next)
                || !table.move_ok(v, w, next)
                || seen.get(&key(w, next)).is_some_and(|&earlier| earlier <= next)
            {
                continue;
            }
            seen.insert(key(w, next), next);
            let conflicts = c + avoid.count(v, w, next);
            let nid = states.len() as u32;
            states.push(State {
                v: w,
                t: next,
                parent: id,
            });
            open.push(Open {
                f: next + d.max(finish_from.saturating_sub(next)),
                conflicts,
                t: next,
                id: nid,
            });
        }
    }
    Low::None
}

/// The multi-valued decision diagram of an agent's paths of `cost` steps
/// that end at its goal under its table: for each step, the nodes some
/// such path is at (Sharon et al. 2013). The high level reads it only to
/// rank conflicts and to tell dependent pairs, never to prune.
pub(super) fn mdd(graph: &Graph, dist: &[u32], start: Node, goal: Node, cost: usize, table: &Table) -> Vec<Vec<Node>> {
    // `mark[v]` = t: `v` is in the level of step t, being built (forwards);
    // = cost + 1 + t: `v` is kept at step t + 1 (backwards).
    let mut mark = vec![0u32; graph.adj.len()];
    let mut layers: Vec<Vec<Node>> = vec![vec![start]];
    for t in 1..=cost {
        let stamp = t as u32;
        let mut next: Vec<Node> = Vec::new();
        for &v in &layers[t - 1] {
            for w in graph.neighbours(v).chain(std::iter::once(v)) {
                if mark[w as usize] != stamp
                    && (dist[w as usize] as usize) <= cost - t
                    && table.vertex_ok(w, t as u32)
                    && table.move_ok(v, w, t as u32)
                {
                    mark[w as usize] = stamp;
                    next.push(w);
                }
            }
        }
        layers.push(next);
    }
    // Backwards from the goal at `cost`: the nodes that lead there.
    let mut keep: Vec<Vec<Node>> = vec![Vec::new(); cost + 1];
    keep[cost] = layers[cost].iter().copied().filter(|&v| v == goal).collect();
    for t in (0..cost).rev() {
        let stamp = (cost + 1 + t) as u32;
        for &w in &keep[t + 1] {
            mark[w as usize] = stamp;
        }
        keep[t] = layers[t]
            .iter()
            .copied()
            .filter(|&v| {
                mark[v as usize] == stamp
                    || graph
                        .neighbours(v)
                        .any(|w| mark[w as usize] == stamp && table.move_ok(v, w, t as u32 + 1))
            })
            .collect();
    }
    keep
}

/// The earliest step at which an agent from `start` can be at `target`
/// under its table, never using the edge `without` (either way) when one
/// is given; `None` when it cannot before `upper`. A* in (point, step)
/// with the Manhattan distance as its heuristic; past the table's horizon
/// nothing changes with the step, so a point's later steps are one state
/// that keeps its earliest step (reopened when an earlier one is found),
/// and the search ends.
pub(super) fn arrival(
    graph: &Graph,
    table: &Table,
    start: Node,
    target: Node,
    without: Option<(Node, Node)>,
    upper: u32,
) -> Option<u32> {
    let goal = cell(graph, target);
    let h = |v: Node| manhattan(cell(graph, v), goal) as u32;
    if !table.vertex_ok(start, 0) {
        return None;
    }
    let blocked = |u: Node, v: Node| without.is_some_and(|(x, y)| (u, v) == (x, y) || (u, v) == (y, x));
    let key = |v: Node, t: u32| (v, t.min(table.horizon + 1));
    let mut earliest: FastMap<(Node, u32), u32> = FastMap::default();
    let mut open: BinaryHeap<std::cmp::Reverse<(u32, u32, Node)>> = BinaryHeap::new();
    open.push(std::cmp::Reverse((h(start), 0, start)));
    earliest.insert(key(start, 0), 0);
    while let Some(std::cmp::Reverse((_, t, v))) = open.pop() {
        if v == target {
            return Some(t);
        }
        if earliest.get(&key(v, t)).is_some_and(|&e| e < t) {
            continue;
        }
        let next = t + 1;
        for w in graph.neighbours(v).chain(std::iter::once(v)) {
            if next + h(w) >= upper || blocked(v, w) || !table.vertex_ok(w, next) || !table.move_ok(v, w, next) {
                continue;
            }
            let e = earliest.entry(key(w, next)).or_insert(u32::MAX);
            if next < *e {
                *e = next;
                open.push(std::cmp::Reverse((next + h(w), next, w)));
            }
        }
    }
    None
}
