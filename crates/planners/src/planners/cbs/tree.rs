//! `cbs`'s high level: the constraint tree, grown for the whole team and,
//! for its heuristic, for pairs of agents.
//!
//! The tree is searched best first by f = g + h, g the node's sum of costs
//! and h the WDG heuristic (Li, Felner, Boyarski, Ma and Koenig, IJCAI
//! 2019): for each pair of agents whose paths conflict, how much more the
//! two cost together than apart under the node's constraints (found by
//! growing a tree for the pair alone, remembered by the pair and their
//! constraints), and h the least total extra over the agents that covers
//! every pair's extra (an edge-weighted vertex cover; a lower bound on
//! what the node's subtree must add, so the first node without a conflict
//! is still optimal). A node's h is computed when it is first taken from
//! the open list; until then it carries its parent's f (its subtree is in
//! its parent's).

use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::sync::Arc;

use super::low::{Avoid, Low, Table, low_level};
use super::symmetry::{Kind, MddCache, cached_mdd, choose};
use super::{Budget, Constraint, Counts, CtNode, Team, apart_next, binding, conflicts, cost_of, to_replan};
use crate::planners::mapf::{FastMap, Graph, Node};

/// How growing a tree ended.
pub(super) enum Grown {
    Solved(Vec<Arc<Vec<Node>>>),
    /// The tree is exhausted: no solution respects the root's constraints.
    NoSolution,
    /// A limit was reached; every solution costs at least `bound`.
    Stopped { bound: u64 },
}

/// The most nodes a pair's tree may expand for the heuristic; past it, the
/// tree's lower bound is the pair's extra (CBSH2-RTC stops at 10 too).
const PAIR_NODES: u64 = 10;

/// The most pairs remembered before the memory is cleared (each key holds
/// the pair's constraints: ~64 MB at most for trees 50 constraints deep).
const REMEMBERED: usize = 1 << 16;

/// The places of the conflicts the tree split on, once each (pictures).
pub(super) type Places = std::collections::HashSet<(Node, Node)>;

/// What a tree keeps across its nodes: the pairs' extras, its counts.
pub(super) struct Grower<'a, 'b> {
    pub budget: &'a mut Budget<'b>,
    pub counts: &'a mut Counts,
    /// The extra cost of a pair (with their constraints) together.
    pairs: FastMap<(u32, u32, Vec<Constraint>), Option<u64>>,
    /// The agents' MDDs.
    mdds: MddCache,
    /// Nodes expanded in the team's tree.
    pub high: u64,
}

impl<'a, 'b> Grower<'a, 'b> {
    pub(super) fn new(budget: &'a mut Budget<'b>, counts: &'a mut Counts) -> Self {
        Grower {
            budget,
            counts,
            pairs: FastMap::default(),
            mdds: MddCache::default(),
            high: 0,
        }
    }

    /// Grows the team's tree from `base`; with `heuristic`, f = g + WDG;
    /// stops after `max_nodes` expansions. The places split on go to
    /// `places` when given.
    pub(super) fn grow(
        &mut self,
        team: &Team<'_>,
        base: Vec<Constraint>,
        heuristic: bool,
        max_nodes: u64,
        mut places: Option<&mut Places>,
    ) -> Grown {
        let graph = team.graph;
        let nodes = graph.adj.len();
        // The root: every agent's own shortest path under `base`.
        // Each avoids the conflicts with those planned before it.
        let mut paths: Vec<Arc<Vec<Node>>> = Vec::with_capacity(team.starts.len());
        let mut avoid = Avoid::new(&[], usize::MAX);
        for a in 0..team.starts.len() {
            let table = Table::new(a as u32, team.goals[a], &base);
            match low_level(graph, team.dists[a], team.starts[a], team.goals[a], &table, &avoid, self.budget) {
                Low::Path(p) => {
                    avoid.add(&p);
                    paths.push(Arc::new(p));
                }
                Low::None => return Grown::NoSolution,
                Low::Stopped => return Grown::Stopped { bound: 0 },
            }
        }
        let found = conflicts(&paths, nodes);
        let mut tree = vec![CtNode {
            constraints: Arc::new(base),
            cost: cost_of(&paths),
            paths,
            found,
            h: 0,
            h_known: !heuristic,
        }];
        let mut open = BinaryHeap::from([Reverse((tree[0].cost, tree[0].found.count, 0, Reverse(0usize)))]);
        let mut expanded = 0u64;
        while let Some(Reverse((f, _, _, Reverse(id)))) = open.pop() {
            if self.budget.exhausted() || expanded >= max_nodes {
                return Grown::Stopped { bound: f };
            }
            if !tree[id].h_known {
                tree[id].h_known = true;
                match self.heuristic(team, &tree[id]) {
                    None => {
                        // A pair without a solution: nor has the subtree.
                        tree[id].paths = Vec::new();
                        continue;
                    }
                    Some(h) => tree[id].h = tree[id].h.max(h),
                }
                if self.budget.exhausted() {
                    return Grown::Stopped { bound: f };
                }
                let node = &tree[id];
                if node.cost + node.h > f {
                    open.push(Reverse((node.cost + node.h, node.found.count, node.h, Reverse(id))));
                    continue;
                }
            }
            // Expands `id`; a child as cheap with fewer conflicts replaces the
            // node's paths (bypass, Boyarski et al. 2015) and the node is
            // expanded again.
            let children = 'expand: loop {
                if self.budget.exhausted() || expanded >= max_nodes {
                    return Grown::Stopped { bound: f };
                }
                expanded += 1;
                if places.is_some() {
                    self.high += 1;
                }
                let Some(split) = choose(team, &tree[id], &tree[id].found.first, &mut self.mdds) else {
                    return Grown::Solved(std::mem::take(&mut tree[id].paths));
                };
                match split.kind {
                    Kind::Standard => self.counts.standard += 1,
                    Kind::Rectangle => self.counts.rectangle += 1,
                    Kind::Generalised => self.counts.generalised += 1,
                    Kind::Corridor => self.counts.corridor += 1,
                    Kind::Target => self.counts.target += 1,
                }
                if let Some(places) = places.as_deref_mut() {
                    places.insert(split.place);
                }
                let mut children = Vec::with_capacity(2);
                'child: for added in split.children {
                    let parent = &tree[id];
                    let mut constraints = (*parent.constraints).clone();
                    constraints.extend_from_slice(&added);
                    let mut paths = parent.paths.clone();
                    for agent in to_replan(&added, &parent.paths) {
                        let table = Table::new(agent as u32, team.goals[agent], &constraints);
                        let avoid = Avoid::new(&paths, agent);
                        let (start, goal) = (team.starts[agent], team.goals[agent]);
                        match low_level(graph, team.dists[agent], start, goal, &table, &avoid, self.budget) {
                            Low::Path(p) => {
                                self.budget.stored += p.len();
                                paths[agent] = Arc::new(p);
                            }
                            Low::None => continue 'child,
                            Low::Stopped => return Grown::Stopped { bound: f },
                        }
                    }
                    self.budget.stored += constraints.len();
                    let cost = cost_of(&paths);
                    let found = conflicts(&paths, nodes);
                    if cost == parent.cost && found.count < parent.found.count {
                        self.counts.bypasses += 1;
                        let node = &mut tree[id];
                        node.paths = paths;
                        node.found = found;
                        continue 'expand;
                    }
                    // Its subtree is in its parent's: f at least the parent's.
                    let h = (parent.cost + parent.h).saturating_sub(cost);
                    children.push(CtNode {
                        cost,
                        constraints: Arc::new(constraints),
                        paths,
                        found,
                        h,
                        h_known: !heuristic,
                    });
                }
                break children;
            };
            for node in children {
                open.push(Reverse((node.cost + node.h, node.found.count, node.h, Reverse(tree.len()))));
                tree.push(node);
            }
            // The expanded node's paths and conflicts are no longer needed.
            tree[id].paths = Vec::new();
            tree[id].found = Default::default();
        }
        Grown::NoSolution
    }

    /// The node's WDG heuristic; `None` when a pair of its agents has no
    /// solution under its constraints.
    fn heuristic(&mut self, team: &Team<'_>, node: &CtNode) -> Option<u64> {
        let mut edges: Vec<(u32, u32, u64)> = Vec::new();
        for &(i, j) in &node.found.pairs {
            let extra = self.pair_extra(team, node, i, j)?;
            if extra > 0 {
                edges.push((i, j, extra));
            }
            if self.budget.exhausted() {
                break;
            }
        }
        Some(edge_weighted_cover(&edges))
    }

    /// How much more agents `i` and `j` cost together than apart under the
    /// node's constraints (a lower bound when their tree stops at its
    /// limit); `None` when they have no solution together.
    fn pair_extra(&mut self, team: &Team<'_>, node: &CtNode, i: u32, j: u32) -> Option<u64> {
        let key = (i, j, binding(&node.constraints, &[i, j]));
        if let Some(&known) = self.pairs.get(&key) {
            return known;
        }
        let apart = (node.paths[i as usize].len() + node.paths[j as usize].len() - 2) as u64;
        // Two shortest paths that do not conflict: the pair adds nothing.
        let graph = team.graph;
        let mdd_i = cached_mdd(graph, team.dists[i as usize], node, i, &mut self.mdds);
        let mdd_j = cached_mdd(graph, team.dists[j as usize], node, j, &mut self.mdds);
        if !dependent(graph, &mdd_i, &mdd_j) {
            self.remember(key, Some(0));
            return Some(0);
        }
        let pair = Team {
            graph: team.graph,
            starts: vec![team.starts[i as usize], team.starts[j as usize]],
            goals: vec![team.goals[i as usize], team.goals[j as usize]],
            dists: vec![team.dists[i as usize], team.dists[j as usize]],
        };
        // The pair's tree is dropped once grown: its storage is not the run's.
        let stored = self.budget.stored;
        let grown = self.grow(&pair, key.2.clone(), false, PAIR_NODES, None);
        self.budget.stored = stored;
        // Stopped by the run's limit, not the pair's: a bound, not remembered.
        let run_stopped = matches!(grown, Grown::Stopped { .. }) && self.budget.exhausted();
        let extra = match grown {
            Grown::Solved(paths) => Some(cost_of(&paths).saturating_sub(apart)),
            Grown::NoSolution => None,
            // Dependent: at least one more.
            Grown::Stopped { bound } => Some(bound.saturating_sub(apart).max(1)),
        };
        if !run_stopped {
            self.remember(key, extra);
        }
        extra
    }

    fn remember(&mut self, key: (u32, u32, Vec<Constraint>), extra: Option<u64>) {
        if self.pairs.len() >= REMEMBERED {
            self.pairs.clear();
        }
        self.pairs.insert(key, extra);
    }
}

/// Whether two agents' MDDs hold no pair of paths without a conflict
/// (their shortest paths all meet: Li et al.'s DG), by a search over their
/// joint MDD, each resting at its goal after its last step. The MDDs'
/// moves are taken as every move between adjacent levels, which may add a
/// move an edge constraint forbids: then a pair may look independent that
/// is not, and the heuristic is lower, never higher.
pub(super) fn dependent(graph: &Graph, a: &[Vec<Node>], b: &[Vec<Node>]) -> bool {
    fn level(m: &[Vec<Node>], t: usize) -> &[Node] {
        m.get(t).or(m.last()).map_or(&[], Vec::as_slice)
    }
    let last = a.len().max(b.len()).saturating_sub(1);
    // An empty MDD says nothing: independent (the lower heuristic).
    let (Some(&sa), Some(&sb)) = (level(a, 0).first(), level(b, 0).first()) else {
        return false;
    };
    if sa == sb {
        return true;
    }
    let mut here: Vec<(Node, Node)> = vec![(sa, sb)];
    for t in 1..=last {
        let next = apart_next(graph, &here, level(a, t), level(b, t));
        if next.is_empty() {
            return true;
        }
        here = next;
    }
    false
}

/// The least sum of values x over the agents with x_i + x_j ≥ w for every
/// edge (i, j, w): exact per connected part of up to [`EXACT`] agents
/// (branch and bound), the weight of a greedy matching (a lower bound) for
/// a larger part.
pub(super) fn edge_weighted_cover(edges: &[(u32, u32, u64)]) -> u64 {
    if edges.is_empty() {
        return 0;
    }
    // The connected parts, by union–find over the agents named.
    let mut agents: Vec<u32> = edges.iter().flat_map(|&(i, j, _)| [i, j]).collect();
    agents.sort_unstable();
    agents.dedup();
    let index = |a: u32| agents.binary_search(&a).expect("an agent of an edge");
    let mut root: Vec<usize> = (0..agents.len()).collect();
    fn find(root: &mut [usize], mut x: usize) -> usize {
        while root[x] != x {
            root[x] = root[root[x]];
            x = root[x];
        }
        x
    }
    for &(i, j, _) in edges {
        let (a, b) = (find(&mut root, index(i)), find(&mut root, index(j)));
        root[a] = b;
    }
    let mut parts: FastMap<usize, Vec<(usize, usize, u64)>> = FastMap::default();
    for &(i, j, w) in edges {
        let r = find(&mut root, index(i));
        parts.entry(r).or_default().push((index(i), index(j), w));
    }
    let mut parts: Vec<Vec<(usize, usize, u64)>> = parts.into_values().collect();
    parts.sort();
    parts.iter().map(|part| part_cover(part)).sum()
}

/// The most agents of a connected part solved exactly.
const EXACT: usize = 10;

fn part_cover(edges: &[(usize, usize, u64)]) -> u64 {
    let mut vertices: Vec<usize> = edges.iter().flat_map(|&(i, j, _)| [i, j]).collect();
    vertices.sort_unstable();
    vertices.dedup();
    let matching = greedy_matching(edges);
    if vertices.len() > EXACT {
        return matching;
    }
    let k = vertices.len();
    let local = |v: usize| vertices.binary_search(&v).expect("a vertex of the part");
    let mut weight = vec![vec![0u64; k]; k];
    for &(i, j, w) in edges {
        let (a, b) = (local(i), local(j));
        weight[a][b] = weight[a][b].max(w);
        weight[b][a] = weight[a][b];
    }
    let most: Vec<u64> = weight.iter().map(|row| row.iter().copied().max().unwrap_or(0)).collect();
    let mut search = Branch {
        weight,
        most,
        best: u64::MAX,
        floor: matching,
        steps: 0,
    };
    let mut x = vec![0u64; k];
    search.branch(0, 0, &mut x);
    if search.steps > BRANCH_STEPS {
        // Not finished: the best found may be above the least.
        return matching;
    }
    search.best
}

/// The most assignments the exact cover tries before it falls back to the
/// matching's bound.
const BRANCH_STEPS: u64 = 100_000;

struct Branch {
    weight: Vec<Vec<u64>>,
    most: Vec<u64>,
    best: u64,
    floor: u64,
    steps: u64,
}

impl Branch {
    /// Assigns x to vertex `v` on, each from the least its assigned
    /// neighbours require to the most any of its edges weighs.
    fn branch(&mut self, v: usize, sum: u64, x: &mut [u64]) {
        self.steps += 1;
        if sum >= self.best || self.best == self.floor || self.steps > BRANCH_STEPS {
            return;
        }
        if v == x.len() {
            self.best = sum;
            return;
        }
        let least = (0..v).map(|u| self.weight[v][u].saturating_sub(x[u])).max().unwrap_or(0);
        for value in least..=self.most[v].max(least) {
            x[v] = value;
            self.branch(v + 1, sum + value, x);
        }
        x[v] = 0;
    }
}

/// The weight of a matching taken heaviest edge first: no two of its edges
/// share an agent, so any cover pays at least its weight.
fn greedy_matching(edges: &[(usize, usize, u64)]) -> u64 {
    let mut sorted = edges.to_vec();
    sorted.sort_by_key(|&(i, j, w)| (Reverse(w), i, j));
    let mut used: Vec<usize> = Vec::new();
    let mut total = 0;
    for (i, j, w) in sorted {
        if !used.contains(&i) && !used.contains(&j) {
            used.extend([i, j]);
            total += w;
        }
    }
    total
}
