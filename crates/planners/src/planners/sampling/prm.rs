//! `prm` (Kavraki et al.'s probabilistic roadmap) and `prm_star` (its
//! asymptotically optimal variant), SPEC 3.7.
//!
//! The roadmap starts with the start and the goal. Each iteration draws one
//! sample from the plan's sampler; a free sample joins the roadmap and tries
//! to connect to its k nearest states (`prm`: k = `neighbors`; `prm_star`:
//! k = ⌈rewire · e · (1 + 1/d) · ln n⌉) that lie within `range`, each by a
//! straight motion that must be free. A union-find of the roadmap's
//! components tells when the start and the goal are connected: then A*
//! ([`best_first`], the distance to the goal as the heuristic, admissible
//! and consistent since edges cost their length) finds the shortest path on
//! the roadmap; with `stop first` (the `prm` default) that is the result,
//! with `stop limit` (the `prm_star` default) the roadmap grows to the
//! limit and is queried again.
//!
//! An edge is checked in the direction it was added; the query may run it
//! backwards, so the path's backward edges are checked that way before the
//! path is returned (a motion whose two directions the checker judges
//! differently, which only rounding or an exact half turn can cause, loses
//! its edge, and the query runs again).
//!
//! The roadmap is drawn as `graph/NNNN` on timeline `iteration`.

use petgraph::graph::{EdgeIndex, NodeIndex, UnGraph};
use petgraph::unionfind::UnionFind;
use petgraph::visit::EdgeRef;

use crate::contract::schema::RobotKind;
use crate::contract::{Limits, PlanArgs};
use crate::contract::{Planner, Settings};
use crate::geometry::Config;
use crate::planners::search::{Edge, Graph, SearchBuffers, best_first, undirected_successors};

use super::space::Space;
use super::{
    Algorithm, DrawnEdge, Ended, Grown, LIMITS, METRICS, NEIGHBORS, RANGE, REWIRE, ROTATE, Run,
    SAMPLER, SIMPLIFY, STOP_FIRST, STOP_LIMIT, Stop, TURN_COST, keep_drawn,
};

/// `prm` in the registry.
pub static PRM: Planner = Planner {
    kind: "prm",
    summary: "Kavraki et al.'s probabilistic roadmap, queried with A* (default `limit iterations 200000`)",
    robots: &[
        RobotKind::Point,
        RobotKind::Disk,
        RobotKind::Polygon,
        RobotKind::Car,
    ],
    params: &[
        RANGE, TURN_COST, SAMPLER, NEIGHBORS, STOP_FIRST, SIMPLIFY, ROTATE,
    ],
    metrics: METRICS,
    limits: LIMITS,
    needs_goal: true,
    randomized: true,
    grids: true,
    time: false,
    check: check_prm,
};

/// `prm_star` in the registry.
pub static PRM_STAR: Planner = Planner {
    kind: "prm_star",
    summary: "PRM* with k = ⌈rewire · e · (1 + 1/d) · ln n⌉ nearest, asymptotically optimal (default `limit iterations 200000`)",
    robots: &[
        RobotKind::Point,
        RobotKind::Disk,
        RobotKind::Polygon,
        RobotKind::Car,
    ],
    params: &[
        RANGE, TURN_COST, SAMPLER, REWIRE, STOP_LIMIT, SIMPLIFY, ROTATE,
    ],
    metrics: METRICS,
    limits: LIMITS,
    needs_goal: true,
    randomized: true,
    grids: true,
    time: false,
    check: check_prm_star,
};

fn check_prm(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    super::check(args, Algorithm::Prm)
}

fn check_prm_star(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    super::check(args, Algorithm::PrmStar)
}

/// The roadmap: states as nodes, edges weighted by their length, with
/// the directions their motion was checked in ([`FORWARD`]: from the
/// lower node index to the higher, [`BACKWARD`]: the other way).
pub struct Roadmap {
    pub graph: UnGraph<Config, (f64, u8)>,
}

const FORWARD: u8 = 1;
const BACKWARD: u8 = 2;

/// The direction bit of the motion from node `from` to node `to`.
fn direction(from: usize, to: usize) -> u8 {
    if from < to { FORWARD } else { BACKWARD }
}

impl Roadmap {
    /// The shortest path from node 0 (the start) to node 1 (the goal):
    /// node indices and cost, `None` when they are not connected.
    pub fn shortest_path(&self, space: &Space) -> Option<(Vec<usize>, f64)> {
        let mut query = Query {
            roadmap: self,
            space,
            goal: self.graph[NodeIndex::new(1)],
        };
        let r = best_first(
            &mut query,
            &[0],
            &Limits::default(),
            false,
            &mut SearchBuffers::default(),
        );
        r.nodes.map(|n| (n, r.cost))
    }
}

/// The roadmap for the search core: A* to node 1.
struct Query<'r> {
    roadmap: &'r Roadmap,
    space: &'r Space,
    goal: Config,
}

impl Graph for Query<'_> {
    fn node_count(&self) -> usize {
        self.roadmap.graph.node_count()
    }

    fn successors(&mut self, node: usize, out: &mut Vec<Edge>) {
        undirected_successors(&self.roadmap.graph, node, |w| w.0, out);
    }

    fn heuristic(&self, node: usize) -> f64 {
        self.space
            .distance(self.roadmap.graph[NodeIndex::new(node)], self.goal)
    }

    fn is_goal(&self, node: usize) -> bool {
        node == 1
    }
}

/// Grows the roadmap and queries it (see the module documentation).
pub fn grow(run: &mut Run<'_>) -> Grown {
    let star = run.settings.algorithm == Algorithm::PrmStar;
    let stop_first = run.settings.stop == Stop::First;
    let range = run.settings.range;
    let mut roadmap = Roadmap {
        graph: UnGraph::default(),
    };
    let mut components: UnionFind<u32> = UnionFind::new(0);
    let mut index = run.index();
    for c in [run.start, run.goal] {
        roadmap.graph.add_node(c);
        components.new_set();
        index.insert(run.space.key(c));
    }
    let mut drawn = Vec::new();
    let mut near = Vec::new();
    let (mut first_iteration, mut first_cost) = (None, None);
    let mut path = None;
    let mut iteration = 0;
    // The iteration from which a query may run (after a query that found
    // no path although the components said connected: see `query`).
    let mut next_query = 0;
    // The start and the goal try each other first (as any new state would).
    if run.space.distance(run.start, run.goal) <= range {
        connect(
            run,
            &mut roadmap,
            &mut components,
            1,
            &[(0.0, 0)],
            0,
            &mut drawn,
        );
    }
    let ended = loop {
        if path.is_none() && iteration >= next_query && components.equiv(0, 1) {
            path = query(run, &mut roadmap);
            match &path {
                Some((_, cost)) => {
                    first_iteration = Some(iteration);
                    first_cost = Some(*cost);
                    if stop_first {
                        break Ended::Solved;
                    }
                }
                None => next_query = iteration + 256,
            }
        }
        if let Some(why) = run.should_stop(iteration + 1, roadmap.graph.node_count()) {
            break why;
        }
        iteration += 1;
        let q = run.sample();
        if !run.config_free(q) {
            continue;
        }
        let n = roadmap.graph.node_count();
        let k = if star {
            run.k_star(n + 1)
        } else {
            run.settings.neighbors
        };
        let graph = &roadmap.graph;
        run.k_nearest(
            &mut index,
            |i| graph[NodeIndex::new(i)],
            q,
            k,
            true,
            &mut near,
        );
        // A state already in the roadmap is not added twice (its nearest
        // neighbour is itself, at distance 0: no query of its own).
        if near.first().is_some_and(|&(d2, _)| d2 == 0.0) {
            continue;
        }
        let range2 = range * range;
        near.retain(|&(d2, _)| d2 <= range2);
        let v = roadmap.graph.add_node(q).index();
        components.new_set();
        index.insert(run.space.key(q));
        connect(
            run,
            &mut roadmap,
            &mut components,
            v,
            &near,
            iteration,
            &mut drawn,
        );
    };
    if path.is_some() && !stop_first {
        // Grown on after the first solution: query the final roadmap.
        path = query(run, &mut roadmap).or(path);
    }
    let states = roadmap.graph.node_count();
    let edges = roadmap.graph.edge_count();
    Grown {
        path: path.map(|(p, _)| p),
        iterations: iteration,
        ended,
        first_iteration,
        first_cost,
        states,
        edges,
        drawn,
        entity: "graph",
    }
}

/// Connects node `v` to the nodes `near` (squared distance, index) whose
/// motion from `v` is free.
fn connect(
    run: &mut Run<'_>,
    roadmap: &mut Roadmap,
    components: &mut UnionFind<u32>,
    v: usize,
    near: &[(f64, u32)],
    iteration: u64,
    drawn: &mut Vec<DrawnEdge>,
) {
    let a = roadmap.graph[NodeIndex::new(v)];
    for &(_, u) in near {
        let b = roadmap.graph[NodeIndex::new(u as usize)];
        if !run.motion_free(a, b) {
            continue;
        }
        let w = run.space.distance(a, b);
        let checked = direction(v, u as usize);
        roadmap
            .graph
            .add_edge(NodeIndex::new(v), NodeIndex::new(u as usize), (w, checked));
        components.union(v as u32, u);
        if run.task.draw {
            keep_drawn(drawn, DrawnEdge { a, b, iteration });
        }
    }
}

/// The shortest roadmap path from the start to the goal and its cost, with
/// every edge checked in the direction the path runs it (see the module
/// documentation); `None` when they are not connected.
fn query(run: &mut Run<'_>, roadmap: &mut Roadmap) -> Option<(Vec<Config>, f64)> {
    loop {
        let (nodes, cost) = roadmap.shortest_path(&run.space)?;
        let mut dropped = false;
        for w in nodes.windows(2) {
            let (from, to) = (NodeIndex::new(w[0]), NodeIndex::new(w[1]));
            let Some(e) = cheapest_edge(roadmap, from, to) else {
                continue;
            };
            let way = direction(w[0], w[1]);
            if roadmap.graph[e].1 & way != 0 {
                continue; // checked this way already
            }
            let (a, b) = (roadmap.graph[from], roadmap.graph[to]);
            if run.motion_free(a, b) {
                roadmap.graph[e].1 |= way;
            } else {
                roadmap.graph.remove_edge(e);
                dropped = true;
                break;
            }
        }
        if !dropped {
            let path = nodes
                .iter()
                .map(|&i| roadmap.graph[NodeIndex::new(i)])
                .collect();
            return Some((run.exact_ends(path), cost));
        }
    }
}

/// The cheapest edge between two nodes.
fn cheapest_edge(roadmap: &Roadmap, a: NodeIndex, b: NodeIndex) -> Option<EdgeIndex> {
    roadmap
        .graph
        .edges_connecting(a, b)
        .min_by(|x, y| x.weight().0.total_cmp(&y.weight().0))
        .map(|e| e.id())
}
