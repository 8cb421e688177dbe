//! One best-first search core (A*, weighted A*, Dijkstra), in the style of
//! the `pathfinding` crate: generic over the successors, the edge costs
//! and the heuristic of a [`Graph`], used by the lattice planners, the
//! online robot's searches and the roadmap's query.
//!
//! # Contract
//! - Nodes are dense indices `0..len`; edge costs are ≥ 0.
//! - The open list pops the lowest f = g + h, ties towards the larger g
//!   (deeper nodes first), then the lowest node index: searches are
//!   deterministic.
//! - Nodes are closed once and never reopened: with a consistent heuristic
//!   (h = 0, or an admissible and consistent one) the path is optimal; with
//!   an inflated one (weighted A*, h = w·h') its cost is at most w times the
//!   optimum.
//! - An edge is checked ([`Graph::usable`]) only when it would improve its
//!   end's g, so that expensive motion checks run for few edges.
//! - Per-node state (g, parent, open/closed) is 16 bytes for the nodes the
//!   search touches: a dense array for small graphs, pages of 256 nodes
//!   allocated on first touch for large ones ([`SearchBuffers`]), so memory
//!   grows with what the search touches, not with the lattice (plus a page
//!   table of 8 bytes per 256 nodes).

use std::collections::BinaryHeap;
use std::time::Instant;

use crate::contract::Limits;

/// A successor candidate: the neighbour, the edge's cost, and the graph's
/// own label for the edge (handed back to [`Graph::usable`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Edge {
    pub to: usize,
    pub cost: f64,
    pub label: u32,
}

/// The edges at `node` of an undirected petgraph graph (the roadmap's and
/// PRM's), as successors costing `cost(weight)`.
pub fn undirected_successors<N, W>(
    graph: &petgraph::graph::UnGraph<N, W>,
    node: usize,
    cost: impl Fn(&W) -> f64,
    out: &mut Vec<Edge>,
) {
    use petgraph::visit::EdgeRef;
    for e in graph.edges(petgraph::graph::NodeIndex::new(node)) {
        // An undirected edge is listed with `node` at either end.
        let to = if e.source().index() == node {
            e.target().index()
        } else {
            e.source().index()
        };
        out.push(Edge {
            to,
            cost: cost(e.weight()),
            label: 0,
        });
    }
}

/// A graph to search.
pub trait Graph {
    /// The number of node indices.
    fn node_count(&self) -> usize;

    /// Appends the successor candidates of `node` to `out` (which is
    /// empty). Candidates may include closed nodes; the core skips them.
    fn successors(&mut self, node: usize, out: &mut Vec<Edge>);

    /// Whether the edge `label` from `from` to `to` may be used: asked only
    /// for edges that would improve `to`, at most once per search and edge
    /// (a lattice checks the robot's motion here).
    fn usable(&mut self, from: usize, label: u32, to: usize) -> bool {
        let _ = (from, label, to);
        true
    }

    /// The heuristic at `node` (already inflated by any weight).
    fn heuristic(&self, node: usize) -> f64;

    /// The heuristic at the end of `edge`, a successor of the node last
    /// passed to [`Graph::successors`]: the same as `heuristic(edge.to)`;
    /// a lattice may compute it from the neighbour's offset instead of
    /// from its index.
    fn edge_heuristic(&self, edge: &Edge) -> f64 {
        self.heuristic(edge.to)
    }

    /// Whether `node` ends the search.
    fn is_goal(&self, node: usize) -> bool;

    /// Called just before `node` is expanded, with the search tree so far
    /// (an online robot walks there and senses). `false` stops the search,
    /// which then gives up.
    fn before_expand(&mut self, node: usize, tree: &Tree<'_>) -> bool {
        let _ = (node, tree);
        true
    }
}

/// The search tree while searching: back-pointers of the nodes reached.
pub struct Tree<'a> {
    states: &'a dyn States,
    stamp: u32,
}

impl Tree<'_> {
    /// The back-pointer of `node` (`None` for a start and for nodes not
    /// reached yet). Final for nodes already expanded.
    pub fn parent(&self, node: usize) -> Option<usize> {
        let s = self.states.get(node);
        (s.mark >= 2 * self.stamp && s.parent != u32::MAX).then_some(s.parent as usize)
    }
}

/// What one search found.
#[derive(Clone, Debug, Default)]
pub struct SearchResult {
    /// Nodes from a start to the goal reached.
    pub nodes: Option<Vec<usize>>,
    /// g of the goal.
    pub cost: f64,
    pub expanded: u64,
    /// Nodes put on the open list (the starts included).
    pub generated: u64,
    pub gave_up: bool,
    /// Expanded nodes in order (when asked for).
    pub expansion_order: Vec<usize>,
}

/// An open-list entry (of [`best_first`], and of `hybrid_astar`'s
/// holonomic heuristic): lowest f first (by `f64::total_cmp`), then highest
/// g, then lowest node. f and g are mapped to unsigned integers in
/// `total_cmp`'s order, so that the heap's comparisons need no float
/// handling; a max-heap pops the greatest.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct Entry {
    /// `!key(f)`.
    f: u64,
    /// `key(g)`.
    g: u64,
    /// `!node`.
    node: u32,
}

/// `x`'s place in `f64::total_cmp`'s order, as an unsigned integer.
#[inline]
fn key(x: f64) -> u64 {
    let b = x.to_bits();
    // Negative values: all bits flipped; others: the sign bit set.
    b ^ (((b as i64 >> 63) as u64) | (1 << 63))
}

/// The inverse of [`key`].
#[inline]
fn unkey(k: u64) -> f64 {
    f64::from_bits(k ^ ((((!k) as i64 >> 63) as u64) | (1 << 63)))
}

impl Entry {
    #[inline]
    pub fn new(f: f64, g: f64, node: usize) -> Self {
        Entry {
            f: !key(f),
            g: key(g),
            node: !(node as u32),
        }
    }

    #[inline]
    pub fn f(&self) -> f64 {
        unkey(!self.f)
    }

    #[inline]
    pub fn g(&self) -> f64 {
        unkey(self.g)
    }

    #[inline]
    pub fn node(&self) -> usize {
        !self.node as usize
    }
}

/// Per-node search state, packed so that one cache line serves a node.
#[derive(Clone, Copy)]
struct NodeState {
    g: f64,
    parent: u32,
    /// `2·stamp` once seen in the current search, `2·stamp + 1` once
    /// closed; anything smaller is from an earlier search.
    mark: u32,
}

const FRESH: NodeState = NodeState {
    g: f64::INFINITY,
    parent: u32::MAX,
    mark: 0,
};

/// Graphs up to this many nodes keep their state in one array; larger ones
/// in pages allocated when first touched.
const DENSE_LIMIT: usize = 1 << 22;
/// 256 nodes of 16 bytes: one 4 KiB memory page. A search along one path
/// across a wide lattice touches a page or two per row of it (nodes are
/// numbered row by row); on the open 19,999 × 9,999 map, pages of 4,096
/// nodes held ten times what the search used.
const PAGE_BITS: usize = 8;
const PAGE: usize = 1 << PAGE_BITS;

type Page = Box<[NodeState; PAGE]>;

/// Where the per-node state lives.
enum Store {
    Dense(Vec<NodeState>),
    Paged(Vec<Option<Page>>),
}

/// Access to per-node state, for the two layouts (the search loop is
/// compiled once for each, so the dense one pays for no page lookup).
trait States {
    fn get(&self, i: usize) -> NodeState;
    fn set(&mut self, i: usize, s: NodeState);
}

struct Dense<'a>(&'a mut [NodeState]);
struct Paged<'a>(&'a mut Vec<Option<Page>>);

impl States for Dense<'_> {
    #[inline]
    fn get(&self, i: usize) -> NodeState {
        self.0[i]
    }
    #[inline]
    fn set(&mut self, i: usize, s: NodeState) {
        self.0[i] = s;
    }
}

impl States for Paged<'_> {
    #[inline]
    fn get(&self, i: usize) -> NodeState {
        match &self.0[i >> PAGE_BITS] {
            Some(page) => page[i & (PAGE - 1)],
            None => FRESH,
        }
    }
    #[inline]
    fn set(&mut self, i: usize, s: NodeState) {
        let page = self.0[i >> PAGE_BITS].get_or_insert_with(|| Box::new([FRESH; PAGE]));
        page[i & (PAGE - 1)] = s;
    }
}

/// Reusable search state, so that many searches on one graph allocate
/// once; after a search it holds that search's tree.
pub struct SearchBuffers {
    store: Store,
    /// Pages whatever the graph's size: for graphs that number their nodes
    /// as they reach them and announce only a cap ([`SearchBuffers::paged`]).
    always_paged: bool,
    len: usize,
    stamp: u32,
    heap: BinaryHeap<Entry>,
    successors: Vec<Edge>,
}

impl Default for SearchBuffers {
    fn default() -> Self {
        SearchBuffers {
            store: Store::Dense(Vec::new()),
            always_paged: false,
            len: 0,
            stamp: 0,
            heap: BinaryHeap::new(),
            successors: Vec::new(),
        }
    }
}

impl SearchBuffers {
    /// Buffers that keep per-node state in pages allocated on first touch
    /// even for a small node count: memory grows with the nodes reached,
    /// not with [`Graph::node_count`].
    pub fn paged() -> Self {
        SearchBuffers {
            always_paged: true,
            ..SearchBuffers::default()
        }
    }

    fn state(&self, node: usize) -> NodeState {
        match &self.store {
            Store::Dense(v) => v.get(node).copied().unwrap_or(FRESH),
            Store::Paged(pages) => match pages.get(node >> PAGE_BITS) {
                Some(Some(page)) => page[node & (PAGE - 1)],
                _ => FRESH,
            },
        }
    }

    /// The back-pointer of `node` in the last search (`None` for its
    /// starts and for nodes it did not reach). Final for nodes already
    /// expanded.
    pub fn parent(&self, node: usize) -> Option<usize> {
        let s = self.state(node);
        (s.mark >= 2 * self.stamp && s.parent != u32::MAX).then_some(s.parent as usize)
    }

    /// Bytes held for per-node state (for benchmarks).
    pub fn state_bytes(&self) -> usize {
        let node = std::mem::size_of::<NodeState>();
        match &self.store {
            Store::Dense(v) => v.len() * node,
            Store::Paged(pages) => {
                pages.iter().flatten().count() * PAGE * node
                    + pages.len() * std::mem::size_of::<Option<Page>>()
            }
        }
    }

    /// Starts a search on a graph of `len` nodes.
    fn reset(&mut self, len: usize) {
        if self.len != len {
            self.store = if len <= DENSE_LIMIT && !self.always_paged {
                Store::Dense(vec![FRESH; len])
            } else {
                Store::Paged((0..len.div_ceil(PAGE)).map(|_| None).collect())
            };
            self.len = len;
            self.stamp = 0;
        }
        self.stamp += 1;
        if self.stamp >= u32::MAX / 2 {
            match &mut self.store {
                Store::Dense(v) => v.fill(FRESH),
                Store::Paged(pages) => pages.iter_mut().for_each(|p| *p = None),
            }
            self.stamp = 1;
        }
        self.heap.clear();
    }
}

/// Best-first search from `starts` (each at g = 0) until a node for which
/// [`Graph::is_goal`] holds is expanded, the open list is empty, or a limit
/// is reached (`limits.expansions`; `limits.time` in seconds from the call,
/// checked every 256 expansions). With `record`, the expansion order is
/// kept.
pub fn best_first<G: Graph>(
    graph: &mut G,
    starts: &[usize],
    limits: &Limits,
    record: bool,
    buf: &mut SearchBuffers,
) -> SearchResult {
    let len = graph.node_count();
    buf.reset(len);
    let mut store = std::mem::replace(&mut buf.store, Store::Dense(Vec::new()));
    let out = match &mut store {
        Store::Dense(v) => run(graph, starts, limits, record, buf, &mut Dense(v)),
        Store::Paged(p) => run(graph, starts, limits, record, buf, &mut Paged(p)),
    };
    buf.store = store;
    out
}

fn run<G: Graph, S: States>(
    graph: &mut G,
    starts: &[usize],
    limits: &Limits,
    record: bool,
    buf: &mut SearchBuffers,
    states: &mut S,
) -> SearchResult {
    let began = Instant::now();
    let (seen, closed) = (2 * buf.stamp, 2 * buf.stamp + 1);
    let mut out = SearchResult::default();
    for &s in starts {
        if s >= buf.len || states.get(s).mark == seen {
            continue;
        }
        states.set(
            s,
            NodeState {
                g: 0.0,
                parent: u32::MAX,
                mark: seen,
            },
        );
        buf.heap.push(Entry::new(graph.heuristic(s), 0.0, s));
        out.generated += 1;
    }
    let mut successors = std::mem::take(&mut buf.successors);
    while let Some(entry) = buf.heap.pop() {
        let (g, node) = (entry.g(), entry.node());
        let state = states.get(node);
        if state.mark == closed || g > state.g {
            continue; // a stale entry
        }
        if limits.expansions.is_some_and(|max| out.expanded >= max) {
            out.gave_up = true;
            break;
        }
        if let Some(t) = limits.time
            && out.expanded % 256 == 0
            && began.elapsed().as_secs_f64() > t
        {
            out.gave_up = true;
            break;
        }
        let tree = Tree {
            states: &*states,
            stamp: buf.stamp,
        };
        if !graph.before_expand(node, &tree) {
            out.gave_up = true;
            break;
        }
        states.set(
            node,
            NodeState {
                mark: closed,
                ..state
            },
        );
        out.expanded += 1;
        if record {
            out.expansion_order.push(node);
        }
        if graph.is_goal(node) {
            let mut nodes = vec![node];
            let mut cur = states.get(node).parent;
            while cur != u32::MAX {
                nodes.push(cur as usize);
                cur = states.get(cur as usize).parent;
            }
            nodes.reverse();
            out.cost = g;
            out.nodes = Some(nodes);
            break;
        }
        successors.clear();
        graph.successors(node, &mut successors);
        for e in &successors {
            let to = states.get(e.to);
            if to.mark == closed {
                continue;
            }
            let ng = g + e.cost;
            if to.mark == seen && ng >= to.g {
                continue;
            }
            if !graph.usable(node, e.label, e.to) {
                continue;
            }
            if to.mark != seen {
                out.generated += 1;
            }
            states.set(
                e.to,
                NodeState {
                    g: ng,
                    parent: node as u32,
                    mark: seen,
                },
            );
            buf.heap
                .push(Entry::new(ng + graph.edge_heuristic(e), ng, e.to));
        }
    }
    buf.successors = successors;
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A line of `n` nodes, edges both ways of cost 1 (and an expensive
    /// shortcut 0 → n-1), h = 0.
    struct Line {
        n: usize,
        goal: usize,
        checked: Vec<(usize, usize)>,
    }

    impl Graph for Line {
        fn node_count(&self) -> usize {
            self.n
        }
        fn successors(&mut self, node: usize, out: &mut Vec<Edge>) {
            if node + 1 < self.n {
                out.push(Edge {
                    to: node + 1,
                    cost: 1.0,
                    label: 0,
                });
            }
            if node > 0 {
                out.push(Edge {
                    to: node - 1,
                    cost: 1.0,
                    label: 1,
                });
            }
            if node == 0 {
                out.push(Edge {
                    to: self.n - 1,
                    cost: 1e9,
                    label: 2,
                });
            }
        }
        fn usable(&mut self, from: usize, _: u32, to: usize) -> bool {
            self.checked.push((from, to));
            true
        }
        fn heuristic(&self, _: usize) -> f64 {
            0.0
        }
        fn is_goal(&self, node: usize) -> bool {
            node == self.goal
        }
    }

    #[test]
    fn finds_the_cheapest_path_and_checks_each_improving_edge_once() {
        let mut g = Line {
            n: 6,
            goal: 5,
            checked: Vec::new(),
        };
        let mut buf = SearchBuffers::default();
        let r = best_first(&mut g, &[0], &Limits::default(), true, &mut buf);
        assert_eq!(r.nodes, Some(vec![0, 1, 2, 3, 4, 5]));
        assert_eq!(r.cost, 5.0);
        assert_eq!(r.expansion_order, vec![0, 1, 2, 3, 4, 5]);
        // Back edges to closed nodes are never checked.
        assert!(
            g.checked.iter().all(|&(a, b)| b > a || b == 5),
            "{:?}",
            g.checked
        );
        assert_eq!(buf.parent(3), Some(2));
        assert_eq!(buf.parent(0), None);
    }

    #[test]
    fn entries_order_as_their_floats_do() {
        let xs = [
            f64::NEG_INFINITY,
            -2.5,
            -0.0,
            0.0,
            1e-300,
            1.0,
            1.0 + f64::EPSILON,
            2.5,
            f64::INFINITY,
            f64::NAN,
        ];
        // The order by floats: "greater" pops first.
        let order = |a: &(f64, f64, u32), b: &(f64, f64, u32)| {
            b.0.total_cmp(&a.0)
                .then(a.1.total_cmp(&b.1))
                .then(b.2.cmp(&a.2))
        };
        let opens: Vec<(f64, f64, u32)> = xs
            .iter()
            .flat_map(|&f| xs.iter().map(move |&g| (f, g)))
            .flat_map(|(f, g)| [3u32, 7].map(|node| (f, g, node)))
            .collect();
        for a in &opens {
            assert_eq!(unkey(key(a.1)).to_bits(), a.1.to_bits());
            let ea = Entry::new(a.0, a.1, a.2 as usize);
            assert_eq!(
                (ea.f().to_bits(), ea.g().to_bits(), ea.node()),
                (a.0.to_bits(), a.1.to_bits(), a.2 as usize)
            );
            for b in &opens {
                let eb = Entry::new(b.0, b.1, b.2 as usize);
                assert_eq!(ea.cmp(&eb), order(a, b));
            }
        }
    }

    #[test]
    fn limits_stop_the_search() {
        let mut g = Line {
            n: 100,
            goal: 99,
            checked: Vec::new(),
        };
        let limits = Limits {
            expansions: Some(10),
            ..Limits::default()
        };
        let r = best_first(&mut g, &[0], &limits, false, &mut SearchBuffers::default());
        assert!(r.gave_up && r.nodes.is_none());
        assert_eq!(r.expanded, 10);
    }

    #[test]
    fn paged_and_dense_state_give_the_same_search() {
        let n = DENSE_LIMIT + 10;
        let mut big = Line {
            n,
            goal: 40,
            checked: Vec::new(),
        };
        let mut buf = SearchBuffers::default();
        let r = best_first(&mut big, &[30], &Limits::default(), true, &mut buf);
        assert_eq!(r.nodes, Some((30..=40).collect()));
        assert!(matches!(buf.store, Store::Paged(_)));
        // Only the touched page was allocated.
        let table = n.div_ceil(PAGE) * std::mem::size_of::<Option<Page>>();
        assert_eq!(
            buf.state_bytes(),
            PAGE * std::mem::size_of::<NodeState>() + table
        );
        // A second search on the same buffers starts afresh.
        big.goal = 20;
        let r = best_first(&mut big, &[30], &Limits::default(), false, &mut buf);
        assert_eq!(r.nodes, Some((20..=30).rev().collect()));
    }
}
