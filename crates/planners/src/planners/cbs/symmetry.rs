//! How `cbs` splits a conflict: which one first, and with which
//! constraints — the standard split, or the symmetry reasoning of Li,
//! Harabor, Stuckey, Ma, Gange and Koenig ("Pairwise symmetry reasoning
//! for multi-agent path finding search", AIJ 2021) for two conflicts plain
//! CBS splits over and over without raising its bound:
//!
//! - **target**: an agent `a` already resting at its goal when `b` passes
//!   there at `t`. Either `a` arrives there for the last time after `t`,
//!   or it rests there from `t` at the latest and no other agent may be
//!   there then or later — one split instead of one per later step;
//! - **rectangle** (the "R" form, IJCAI 2019): two agents whose whole
//!   paths are Manhattan-optimal and go the same way meet inside the
//!   rectangle their routes span, where every pair of their shortest
//!   paths meets somewhere. The split forbids each agent a *barrier*, a
//!   segment of the rectangle's far side at the steps a Manhattan-optimal
//!   path would cross it; any two paths that both cross their barriers
//!   conflict (the paper's theorem), so every solution is kept by one
//!   child, and one split replaces a split per cell of the rectangle;
//! - **generalised rectangle** (GR, [`overlap`]): the same from the
//!   agents' MDDs when their paths bend round walls, each split checked
//!   by a joint search over the two MDDs before it is used;
//! - **pseudo-corridor** ([`super::corridor`]): two agents crossing one
//!   edge head-on, each on its only way: which reaches its far end later.
//!
//! Conflicts are ranked as in ICBS (Boyarski et al. 2015) — cardinal (both
//! children cost more), then semi-cardinal, then the rest — then target
//! before rectangle or corridor before standard, then earliest.

use std::sync::Arc;

use super::low::{Table, mdd};
use super::corridor::{Crossing, pseudo_corridor};
use super::overlap;
use super::{Cell, Constraint, CtNode, Rule, Team, at, binding, cell, manhattan};
use crate::planners::mapf::{FastMap, Graph, Node};

/// A conflict between two agents' paths.
#[derive(Clone, Copy, Debug)]
pub(super) enum Conflict {
    Vertex { a: u32, b: u32, v: Node, t: u32 },
    Edge { a: u32, b: u32, u: Node, v: Node, t: u32 },
}

/// What a split was, for the counts; in the order conflicts are preferred
/// within a cardinality (the last first).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Standard,
    /// The R form, from the agents' starts and goals.
    Rectangle,
    /// The GR form, from the agents' MDDs ([`overlap`]).
    Generalised,
    /// A head-on crossing of one edge ([`corridor`]).
    Corridor,
    Target,
}

impl Kind {
    /// The preference within a cardinality: the two rectangle forms alike.
    fn preference(self) -> u8 {
        match self {
            Kind::Standard => 0,
            Kind::Rectangle | Kind::Generalised | Kind::Corridor => 1,
            Kind::Target => 2,
        }
    }
}

/// A chosen conflict: the constraints each child adds, and where it was.
pub(super) struct Split {
    pub children: [Vec<Constraint>; 2],
    pub kind: Kind,
    /// 2: cardinal, 1: semi-cardinal, 0: neither.
    pub cardinality: u8,
    pub place: (Node, Node),
}

impl Split {
    /// A split whose children each add one constraint on one agent.
    fn one_each(first: (u32, Rule), second: (u32, Rule), kind: Kind, cardinality: u8, place: (Node, Node)) -> Self {
        let one = |(agent, rule): (u32, Rule)| vec![Constraint { agent, rule }];
        Split {
            children: [one(first), one(second)],
            kind,
            cardinality,
            place,
        }
    }
}

/// The conflict to split on among `found` (in time order), with its
/// split; `None` when there is none.
pub(super) fn choose(team: &Team<'_>, node: &CtNode, found: &[Conflict], cache: &mut MddCache) -> Option<Split> {
    let graph = team.graph;
    let mut mdds = Mdds::new(graph, &team.dists, node, cache);
    if found.len() == 1 {
        // Nothing to rank: still a target or rectangle split when it is one.
        return Some(classify(graph, node, found[0], &mut mdds, false));
    }
    let mut best: Option<Split> = None;
    for &c in found {
        let split = classify(graph, node, c, &mut mdds, true);
        let better = best
            .as_ref()
            .is_none_or(|b| (split.cardinality, split.kind.preference()) > (b.cardinality, b.kind.preference()));
        if better {
            let top = split.cardinality == 2 && split.kind == Kind::Target;
            best = Some(split);
            if top {
                break;
            }
        }
    }
    best
}

/// The MDDs the trees have built, by the agent's start and goal, its cost
/// and the constraints that bind it (as agent 0, [`binding`]): what
/// determines the MDD, in the team's tree as in a pair's, whose agents are
/// numbered apart.
pub(super) type MddCache = FastMap<(Node, Node, usize, Vec<Constraint>), Arc<Vec<Vec<Node>>>>;

/// The most MDDs remembered before the memory is cleared.
const REMEMBERED: usize = 1 << 14;

/// Each agent's MDD at its current cost, built when first asked.
struct Mdds<'a> {
    graph: &'a Graph,
    dists: &'a [&'a [u32]],
    node: &'a CtNode,
    built: FastMap<u32, Arc<Vec<Vec<Node>>>>,
    cache: &'a mut MddCache,
}

impl<'a> Mdds<'a> {
    fn new(graph: &'a Graph, dists: &'a [&'a [u32]], node: &'a CtNode, cache: &'a mut MddCache) -> Self {
        Mdds {
            graph,
            dists,
            node,
            built: FastMap::default(),
            cache,
        }
    }

    /// Whether every shortest path of `agent` is at `u` at `t − 1` and at
    /// `v` at `t` (`u` = `v` for a vertex).
    fn narrow(&mut self, agent: u32, u: Node, v: Node, t: u32) -> bool {
        let levels = self.levels(agent);
        let level = |k: usize| -> &[Node] { levels.get(k).or(levels.last()).map_or(&[], Vec::as_slice) };
        let t = t as usize;
        level(t) == [v] && (u == v || (t > 0 && level(t - 1) == [u]))
    }

    /// `agent`'s MDD, built when first asked.
    fn levels(&mut self, agent: u32) -> Arc<Vec<Vec<Node>>> {
        let (graph, dists, node) = (self.graph, self.dists, self.node);
        let cache = &mut *self.cache;
        self.built
            .entry(agent)
            .or_insert_with(|| cached_mdd(graph, dists[agent as usize], node, agent, cache))
            .clone()
    }
}

/// `agent`'s MDD at its cost in `node`, from `cache` when it is there.
pub(super) fn cached_mdd(graph: &Graph, dist: &[u32], node: &CtNode, agent: u32, cache: &mut MddCache) -> Arc<Vec<Vec<Node>>> {
    let path = &node.paths[agent as usize];
    let goal = *path.last().unwrap_or(&path[0]);
    let key = (path[0], goal, path.len(), binding(&node.constraints, &[agent]));
    if let Some(known) = cache.get(&key) {
        return known.clone();
    }
    let table = Table::new(0, goal, &key.3);
    let built = Arc::new(mdd(graph, dist, path[0], goal, path.len() - 1, &table));
    if cache.len() >= REMEMBERED {
        cache.clear();
    }
    cache.insert(key, built.clone());
    built
}

fn classify(graph: &Graph, node: &CtNode, c: Conflict, mdds: &mut Mdds<'_>, rank: bool) -> Split {
    let paths = &node.paths;
    let rests = |a: u32, t: u32| t as usize + 1 >= paths[a as usize].len();
    match c {
        Conflict::Vertex { a, b, v, t } if rests(a, t) || rests(b, t) => {
            let (a, b) = if rests(a, t) { (a, b) } else { (b, a) };
            // `a` costs more in the first child always; `b` in the
            // second when all its shortest paths are at `v` then.
            let cardinality = 1 + u8::from(rank && mdds.narrow(b, v, v, t));
            let finish_after = (a, Rule::FinishAfter { t });
            Split::one_each(finish_after, (a, Rule::RestsFrom { v, t }), Kind::Target, cardinality, (v, v))
        }
        Conflict::Vertex { a, b, v, t } => {
            let cardinality = if rank {
                u8::from(mdds.narrow(a, v, v, t)) + u8::from(mdds.narrow(b, v, v, t))
            } else {
                0
            };
            // Head-on through `v`: `a` from `u` on to `w`, `b` from `w` on to `u`,
            // each on its only way: a pseudo-corridor on the edge `v`–`w`.
            let (pa, pb) = (&paths[a as usize], &paths[b as usize]);
            let (t_, k) = (t as usize, t as usize + 1);
            if t > 0 && k < pa.len() && k < pb.len() {
                let (u, w) = (pa[t_ - 1], pa[k]);
                let head_on = pb[t_ - 1] == w && pb[k] == u && u != v && w != v;
                if head_on
                    && mdds.narrow(a, u, v, t)
                    && mdds.narrow(a, v, w, t + 1)
                    && mdds.narrow(b, w, v, t)
                    && mdds.narrow(b, v, u, t + 1)
                {
                    let into_w = Crossing { agent: a, from: v, into: w, step: t + 1 };
                    let into_v = Crossing { agent: b, from: w, into: v, step: t };
                    if let Some(children) = pseudo_corridor(graph, node, &into_w, &into_v) {
                        return Split {
                            children,
                            kind: Kind::Corridor,
                            cardinality,
                            place: (v, v),
                        };
                    }
                }
            }
            if cardinality < 2 {
                let found = rectangle(graph, paths, a, b).map(|found| (found, Kind::Rectangle)).or_else(|| {
                    let (mdd_a, mdd_b) = (mdds.levels(a), mdds.levels(b));
                    overlap::generalised(graph, (a, pa, &mdd_a), (b, pb, &mdd_b), v, t)
                        .map(|found| (found, Kind::Generalised))
                });
                if let Some(((barrier_a, barrier_b, cardinality), kind)) = found {
                    return Split {
                        children: [barrier_a, barrier_b],
                        kind,
                        cardinality,
                        place: (v, v),
                    };
                }
            }
            let vertex = Rule::Vertex { v, t };
            Split::one_each((a, vertex), (b, vertex), Kind::Standard, cardinality, (v, v))
        }
        Conflict::Edge { a, b, u, v, t } => {
            let (only_a, only_b) = (mdds.narrow(a, u, v, t), mdds.narrow(b, v, u, t));
            let cardinality = if rank { u8::from(only_a) + u8::from(only_b) } else { 0 };
            // Each on its only way across the edge: a pseudo-corridor.
            if only_a && only_b {
                let into_v = Crossing { agent: a, from: u, into: v, step: t };
                let into_u = Crossing { agent: b, from: v, into: u, step: t };
                if let Some(children) = pseudo_corridor(graph, node, &into_v, &into_u) {
                    return Split {
                        children,
                        kind: Kind::Corridor,
                        cardinality,
                        place: (u.min(v), u.max(v)),
                    };
                }
            }
            let (there, back) = (Rule::Edge { u, v, t }, Rule::Edge { u: v, v: u, t });
            Split::one_each((a, there), (b, back), Kind::Standard, cardinality, (u.min(v), u.max(v)))
        }
    }
}

/// The rectangle split of two agents that conflict before either rests,
/// when it is one: each agent's barrier as vertex constraints, and the
/// split's cardinality. Both agents' current paths cross their barriers,
/// so both children change a path.
pub(super) fn rectangle(graph: &Graph, paths: &[Arc<Vec<Node>>], a: u32, b: u32) -> Option<(Vec<Constraint>, Vec<Constraint>, u8)> {
    let (pa, pb) = (&paths[a as usize], &paths[b as usize]);
    let (mut s1, mut g1, mut s2, mut g2) = (
        cell(graph, pa[0]),
        cell(graph, *pa.last()?),
        cell(graph, pb[0]),
        cell(graph, *pb.last()?),
    );
    // Both whole paths Manhattan-optimal.
    if manhattan(s1, g1) != pa.len() as i64 - 1 || manhattan(s2, g2) != pb.len() as i64 - 1 {
        return None;
    }
    // The formulas below want the starts apart along the first axis.
    let transposed = s1.0 == s2.0;
    if transposed {
        for p in [&mut s1, &mut g1, &mut s2, &mut g2] {
            *p = (p.1, p.0);
        }
    }
    let not_rectangle = s1 == s2
        || s1 == g1
        || s2 == g2
        || (s1.0 - g1.0) * (s2.0 - g2.0) < 0
        || (s1.1 - g1.1) * (s2.1 - g2.1) < 0
        || ((s2.0 - s1.0) * (s1.0 - g1.0) < 0 && (s2.1 - s1.1) * (s1.1 - g1.1) < 0)
        || ((s1.0 - s2.0) * (s2.0 - g2.0) < 0 && (s1.1 - s2.1) * (s2.1 - g2.1) < 0)
        || (s1.0 == g1.0 && s2.1 == g2.1)
        || (s1.1 == g1.1 && s2.0 == g2.0);
    if not_rectangle {
        return None;
    }
    // The corner of the rectangle where the first agent leaves it.
    let toward = |s: i64, g: i64, lo: i64, hi: i64| {
        if s == g {
            lo
        } else if s < g {
            lo.min(hi)
        } else {
            lo.max(hi)
        }
    };
    let rg = (toward(s1.0, g1.0, g1.0, g2.0), toward(s1.1, g1.1, g1.1, g2.1));
    let rg_t = manhattan(rg, s1);
    let (r1, r2) = if (s1.0 - s2.0) * (s2.0 - rg.0) >= 0 {
        ((rg.0, s1.1), (s2.0, rg.1))
    } else {
        ((s1.0, rg.1), (rg.0, s2.1))
    };
    let node = |p: Cell| -> Option<Node> {
        let (i, j) = if transposed { (p.1, p.0) } else { p };
        let (nx, ny) = (graph.spec.nx as i64, graph.spec.ny as i64);
        (0..nx).contains(&i).then_some(())?;
        (0..ny).contains(&j).then_some(())?;
        Some(graph.spec.index(i as usize, j as usize) as Node)
    };
    // A barrier: the segment from `r` to `rg`, each cell at the step a
    // Manhattan-optimal path from its start reaches it.
    let barrier = |agent: u32, r: Cell| -> Vec<Constraint> {
        let step = ((r.0 - rg.0).signum(), (r.1 - rg.1).signum());
        let len = manhattan(r, rg).min(rg_t);
        (0..=len)
            .filter_map(|i| {
                let v = node((rg.0 + i * step.0, rg.1 + i * step.1))?;
                Some(Constraint {
                    agent,
                    rule: Rule::Vertex {
                        v,
                        t: (rg_t - i) as u32,
                    },
                })
            })
            .collect()
    };
    let (b1, b2) = (barrier(a, r1), barrier(b, r2));
    let crosses = |path: &[Node], barrier: &[Constraint]| {
        barrier.iter().any(|c| match c.rule {
            Rule::Vertex { v, t } => at(path, t as usize) == v,
            _ => false,
        })
    };
    if !crosses(pa, &b1) || !crosses(pb, &b2) {
        return None;
    }
    let cardinality =
        u8::from((s1.0 - s2.0) * (g1.0 - g2.0) <= 0) + u8::from((s1.1 - s2.1) * (g1.1 - g2.1) <= 0);
    Some((b1, b2, cardinality))
}
