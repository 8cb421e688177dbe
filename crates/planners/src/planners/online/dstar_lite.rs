//! D* Lite (Koenig & Likhachev, "D* Lite", AAAI 2002, Figure 4: the
//! optimized version with the key modifier km) for the `online` robot:
//! search from the goal on the believed map, repaired incrementally after
//! each sensing step, in exact lattice arithmetic ([`Len`]).

use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashSet};

use super::{End, GridLattice, Heuristic, LatticeSpec, Moves, Rover};

/// A length a + b·√2 in cells, exact: the cost of any walk on the lattice
/// (axis moves cost 1, diagonal moves √2) and of the heuristics below.
/// D* Lite compares keys that equal each other in exact arithmetic all the
/// time (a state on the shortest path and the start); in floating point
/// they differ in the last bits depending on the order of the sums, which
/// reorders the queue and can stop ComputeShortestPath before a state the
/// robot then steps on is consistent (seen on maze512: the robot went back
/// and forth between two stale states). Exact lengths make every
/// comparison, and so every tie, exact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Len {
    a: i64,
    b: i64,
}

impl Len {
    const ZERO: Len = Len { a: 0, b: 0 };
    const INF: Len = Len { a: i64::MAX, b: 0 };

    fn is_inf(self) -> bool {
        self.a == i64::MAX
    }

    fn add(self, o: Len) -> Len {
        if self.is_inf() || o.is_inf() {
            Len::INF
        } else {
            Len {
                a: self.a + o.a,
                b: self.b + o.b,
            }
        }
    }

    fn min(self, o: Len) -> Len {
        if o.cmp(&self) == Ordering::Less {
            o
        } else {
            self
        }
    }
}

impl PartialOrd for Len {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Len {
    /// The sign of (a₁ − a₂) + (b₁ − b₂)·√2, decided on integers.
    fn cmp(&self, o: &Self) -> Ordering {
        match (self.is_inf(), o.is_inf()) {
            (true, true) => return Ordering::Equal,
            (true, false) => return Ordering::Greater,
            (false, true) => return Ordering::Less,
            _ => {}
        }
        let (da, db) = (i128::from(self.a - o.a), i128::from(self.b - o.b));
        match (da.cmp(&0), db.cmp(&0)) {
            (Ordering::Equal, x) | (x, Ordering::Equal) => x,
            (x, y) if x == y => x,
            // Opposite signs: compare |da| with |db|·√2 by their squares
            // (never equal, √2 being irrational).
            (x, _) => {
                if da * da > 2 * db * db {
                    x
                } else {
                    x.reverse()
                }
            }
        }
    }
}

/// A D* Lite priority: `[min(g, rhs) + h(s_start, s) + km, min(g, rhs)]`,
/// compared lexicographically.
type Key = (Len, Len);

/// A queue entry; entries whose key is no longer the node's are stale and
/// skipped (lazy deletion).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Queued {
    key: Key,
    node: u32,
}

impl PartialOrd for Queued {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Queued {
    fn cmp(&self, other: &Self) -> Ordering {
        // A max-heap: the smallest key pops first, then the lowest index.
        other.key.cmp(&self.key).then(other.node.cmp(&self.node))
    }
}

/// What D* Lite keeps for a node: g, rhs, and the key it is queued with.
#[derive(Clone, Copy, Debug)]
struct NodeState {
    g: Len,
    rhs: Len,
    /// The node's current key, valid while `queued`.
    key: Key,
    queued: bool,
}

/// A node the search never touched: g = rhs = ∞, not queued.
const UNTOUCHED: NodeState = NodeState {
    g: Len::INF,
    rhs: Len::INF,
    key: (Len::ZERO, Len::ZERO),
    queued: false,
};

/// 64 nodes of 72 bytes: about one 4 KiB memory page.
const PAGE_BITS: usize = 6;
const PAGE: usize = 1 << PAGE_BITS;

/// The per-node state of the nodes the search touched, in pages allocated
/// when a node of theirs is first written (SPEC 3.2: memory as in 3.1,
/// search state only where touched). A short trip across a large lattice
/// holds a few pages and the page table (an eighth of a byte per node);
/// dense arrays held 65 bytes per node of the lattice.
struct States {
    pages: Vec<Option<Box<[NodeState; PAGE]>>>,
}

impl States {
    fn new(len: usize) -> Self {
        States {
            pages: (0..len.div_ceil(PAGE)).map(|_| None).collect(),
        }
    }

    #[inline]
    fn get(&self, i: usize) -> NodeState {
        match &self.pages[i >> PAGE_BITS] {
            Some(page) => page[i & (PAGE - 1)],
            None => UNTOUCHED,
        }
    }

    #[inline]
    fn at(&mut self, i: usize) -> &mut NodeState {
        let page = self.pages[i >> PAGE_BITS].get_or_insert_with(|| Box::new([UNTOUCHED; PAGE]));
        &mut page[i & (PAGE - 1)]
    }
}

/// D* Lite (Koenig & Likhachev, "D* Lite", AAAI 2002, Figure 4: the
/// optimized version) searching from the goal, so that g(s) estimates the
/// cost from s to the goal and the robot's moves only change the key
/// modifier km. Costs and keys are exact [`Len`]s; the heuristic is the
/// lattice distance without obstacles (octile for 8 neighbours, Manhattan
/// for 4): admissible, consistent, and a metric, as km needs.
struct DStarLite {
    states: States,
    heap: BinaryHeap<Queued>,
    km: Len,
    goal: usize,
    spec: LatticeSpec,
    eight: bool,
    /// `false`: h = 0.
    heuristic: bool,
}

impl DStarLite {
    fn new(spec: LatticeSpec, eight: bool, heuristic: bool, goal: usize, start: usize) -> Self {
        let mut d = DStarLite {
            states: States::new(spec.layer_len()),
            heap: BinaryHeap::new(),
            km: Len::ZERO,
            goal,
            spec,
            eight,
            heuristic,
        };
        d.states.at(goal).rhs = Len::ZERO;
        let k = (d.h(start, goal), Len::ZERO);
        d.insert(goal, k);
        d
    }

    /// The cost of a move in direction `d` of [`DIRS`].
    fn step(d: usize) -> Len {
        if d < 4 {
            Len { a: 1, b: 0 }
        } else {
            Len { a: 0, b: 1 }
        }
    }

    fn h(&self, p: usize, q: usize) -> Len {
        if !self.heuristic {
            return Len::ZERO;
        }
        let ((pi, pj), (qi, qj)) = (self.spec.coords(p), self.spec.coords(q));
        let (dx, dy) = (pi.abs_diff(qi) as i64, pj.abs_diff(qj) as i64);
        if self.eight {
            Len {
                a: dx.max(dy) - dx.min(dy),
                b: dx.min(dy),
            }
        } else {
            Len { a: dx + dy, b: 0 }
        }
    }

    /// The believed cost of the move from `u` in direction `d`, with the
    /// neighbour.
    fn edge(belief: &GridLattice, moves: &Moves, u: usize, d: usize) -> Option<(usize, Len)> {
        moves.edge(belief, u, d).map(|(v, _)| (v, Self::step(d)))
    }

    fn edge_cost(belief: &GridLattice, moves: &Moves, u: usize, d: usize) -> Len {
        Self::edge(belief, moves, u, d).map_or(Len::INF, |(_, c)| c)
    }

    fn g(&self, s: usize) -> Len {
        self.states.get(s).g
    }

    fn rhs(&self, s: usize) -> Len {
        self.states.get(s).rhs
    }

    fn calculate_key(&self, s: usize, start: usize) -> Key {
        let st = self.states.get(s);
        let m = st.g.min(st.rhs);
        (m.add(self.h(start, s)).add(self.km), m)
    }

    fn insert(&mut self, s: usize, k: Key) {
        let st = self.states.at(s);
        st.key = k;
        st.queued = true;
        self.heap.push(Queued {
            key: k,
            node: s as u32,
        });
    }

    /// The smallest valid entry, dropping stale ones.
    fn top(&mut self) -> Option<(Key, usize)> {
        while let Some(&Queued { key, node }) = self.heap.peek() {
            let s = node as usize;
            let st = self.states.get(s);
            if st.queued && st.key == key {
                return Some((key, s));
            }
            self.heap.pop();
        }
        None
    }

    fn update_vertex(&mut self, u: usize, start: usize) {
        let st = self.states.get(u);
        if st.g != st.rhs {
            let k = self.calculate_key(u, start);
            self.insert(u, k);
        } else if st.queued {
            self.states.at(u).queued = false;
        }
    }

    /// min over successors s' of c(s, s') + g(s').
    fn best_successor(&self, belief: &GridLattice, moves: &Moves, s: usize) -> Len {
        (0..moves.dirs)
            .filter_map(|d| Self::edge(belief, moves, s, d))
            .map(|(v, c)| c.add(self.g(v)))
            .fold(Len::INF, Len::min)
    }

    /// ComputeShortestPath. Counts vertex expansions into the rover (and
    /// its trace); `Err` when a limit stops it.
    fn compute(&mut self, belief: &GridLattice, rover: &mut Rover<'_>) -> Result<(), End> {
        let start = rover.pos;
        let moves = rover.moves;
        let max = rover.limits().expansions;
        let mut expanded = Vec::new();
        let result = loop {
            let Some((k_old, u)) = self.top() else {
                break Ok(());
            };
            if !(k_old < self.calculate_key(start, start) || self.rhs(start) > self.g(start)) {
                break Ok(());
            }
            let k_new = self.calculate_key(u, start);
            if k_old < k_new {
                self.insert(u, k_new);
                continue;
            }
            if max.is_some_and(|m| rover.expanded >= m)
                || (rover.expanded.is_multiple_of(256) && rover.out_of_time())
            {
                break Err(End::GaveUp);
            }
            rover.expanded += 1;
            expanded.push(u);
            let st = self.states.get(u);
            if st.g > st.rhs {
                let g_u = st.rhs;
                let at_u = self.states.at(u);
                at_u.g = g_u;
                at_u.queued = false;
                for d in 0..moves.dirs {
                    if let Some((s, c)) = Self::edge(belief, &moves, u, d) {
                        if s != self.goal {
                            let rhs = self.rhs(s).min(c.add(g_u));
                            self.states.at(s).rhs = rhs;
                        }
                        self.update_vertex(s, start);
                    }
                }
            } else {
                let g_old = st.g;
                self.states.at(u).g = Len::INF;
                for d in 0..moves.dirs {
                    if let Some((s, c)) = Self::edge(belief, &moves, u, d) {
                        if self.rhs(s) == c.add(g_old) && s != self.goal {
                            let rhs = self.best_successor(belief, &moves, s);
                            self.states.at(s).rhs = rhs;
                        }
                        self.update_vertex(s, start);
                    }
                }
                // u itself: rhs(u) does not depend on g(u).
                self.update_vertex(u, start);
            }
        };
        rover.log_expansions(expanded);
        result
    }

    /// The cheapest move from `s`: argmin c(s, s') + g(s'), the first
    /// direction on ties; `None` when every move costs ∞.
    fn next_move(&self, belief: &GridLattice, moves: &Moves, s: usize) -> Option<usize> {
        let mut best: Option<(Len, usize)> = None;
        for d in 0..moves.dirs {
            if let Some((v, c)) = Self::edge(belief, moves, s, d) {
                let f = c.add(self.g(v));
                if !f.is_inf() && best.is_none_or(|(b, _)| f < b) {
                    best = Some((f, v));
                }
            }
        }
        best.map(|(_, v)| v)
    }

    /// The plan the robot holds: the greedy descent from `s` (for the
    /// trace), at most `cap` points.
    fn plan_from(&self, belief: &GridLattice, moves: &Moves, s: usize, cap: usize) -> Vec<usize> {
        let mut plan = vec![s];
        let mut cur = s;
        while cur != self.goal && plan.len() < cap {
            match self.next_move(belief, moves, cur) {
                Some(v) => {
                    plan.push(v);
                    cur = v;
                }
                None => break,
            }
        }
        plan
    }
}

/// `dstar_lite`: the main loop of D* Lite, with the robot sensing after
/// each move and the changed edges repaired incrementally.
pub(super) fn dstar_lite(rover: &mut Rover<'_>, belief: &mut GridLattice, goal: usize) -> End {
    let spec = rover.spec;
    let moves = rover.moves;
    let mut ds = DStarLite::new(
        spec,
        moves.dirs == 8,
        rover.cfg.heuristic != Heuristic::Zero,
        goal,
        rover.pos,
    );
    let mut last = rover.pos;
    rover.replans = 1;
    if let Err(end) = ds.compute(belief, rover) {
        return end;
    }
    // Nodes whose out-edges may have changed, in the order first met.
    let mut seen = HashSet::new();
    loop {
        if rover.pos == goal {
            return End::Reached;
        }
        if ds.rhs(rover.pos).is_inf() {
            return End::Unreachable;
        }
        if rover.wants_plan() {
            let plan = ds.plan_from(belief, &moves, rover.pos, spec.layer_len());
            rover.hold_plan(plan);
        }
        let Some(next) = ds.next_move(belief, &moves, rover.pos) else {
            return End::Unreachable;
        };
        if let Err(end) = rover.advance(belief, next) {
            return end;
        }
        let fresh = rover.scan();
        if fresh.is_empty() {
            continue;
        }
        // The edges a sensed point can change join points within one cell
        // of it (its own edges and the diagonals that cut its corner).
        seen.clear();
        let mut touched = Vec::new();
        for &n in &fresh {
            for u in std::iter::once(n).chain((0..8).filter_map(|d| belief.neighbour(n, d))) {
                if seen.insert(u) {
                    touched.push(u);
                }
            }
        }
        let mut edges = Vec::new();
        for &u in &touched {
            for d in 0..moves.dirs {
                if let Some(v) = belief.neighbour(u, d) {
                    edges.push((u, d, v, DStarLite::edge_cost(belief, &moves, u, d)));
                }
            }
        }
        rover.reveal(belief, &fresh);
        let mut changed = false;
        for (u, d, v, c_old) in edges {
            let c_new = DStarLite::edge_cost(belief, &moves, u, d);
            if c_new == c_old {
                continue;
            }
            if !changed {
                changed = true;
                ds.km = ds.km.add(ds.h(last, rover.pos));
                last = rover.pos;
            }
            if c_old > c_new {
                if u != goal {
                    let rhs = ds.rhs(u).min(c_new.add(ds.g(v)));
                    ds.states.at(u).rhs = rhs;
                }
            } else if ds.rhs(u) == c_old.add(ds.g(v)) && u != goal {
                let rhs = ds.best_successor(belief, &moves, u);
                ds.states.at(u).rhs = rhs;
            }
            ds.update_vertex(u, rover.pos);
        }
        if changed {
            rover.replans += 1;
            if let Err(end) = ds.compute(belief, rover) {
                return end;
            }
        }
    }
}
