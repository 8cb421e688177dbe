//! The (x, y) lattice of `astar` and `online` (SPEC 3.1, 3.2): which
//! lattice points are free for a point or disk robot, the edges between
//! them (checked lazily, once per edge, with the robot's swept disk), the
//! search on it ([`search`], [`search_with`]) on the best-first core, and
//! the snapping of a plan's start and goal to it.

use crate::contract::Limits;
use crate::contract::layers::Rounded;
use crate::geometry::collide::ObstacleIndex;
use crate::geometry::cspace::shape_pieces;
use crate::geometry::{Config, Point, Shape, World};

use super::deadline::Deadline;
use super::lattice::{BitSet, LatticeDistance, LatticeSpec};
pub use super::lattice::{CostMetric, Heuristic};
use super::search::{Edge, Graph, Tree, best_first};
pub use super::search::{SearchBuffers, SearchResult};

/// Search settings for the (x, y) lattice.
#[derive(Clone, Copy, Debug)]
pub struct SearchConfig {
    /// 4 or 8.
    pub connect: u8,
    pub cost: CostMetric,
    /// Heuristic inflation w ≥ 1 (f = g + w·h).
    pub weight: f64,
    pub heuristic: Heuristic,
    pub limits: Limits,
}

impl SearchConfig {
    /// The search of an `astar` plan (or of `online`'s A*), with `limits`.
    pub fn new(
        connect: u8,
        cost: CostMetric,
        weight: f64,
        heuristic: Heuristic,
        limits: Limits,
    ) -> Self {
        SearchConfig {
            connect,
            cost,
            weight,
            heuristic,
            limits,
        }
    }
}

/// Neighbour offsets (di, dj): the 4 axis moves first, then the diagonals.
pub const DIRS: [(i64, i64); 8] = [
    (1, 0),
    (0, 1),
    (-1, 0),
    (0, -1),
    (1, 1),
    (-1, 1),
    (-1, -1),
    (1, -1),
];

/// The direction opposite to `d` in [`DIRS`].
pub fn opposite(d: usize) -> usize {
    if d < 4 {
        (d + 2) % 4
    } else {
        4 + (d - 4 + 2) % 4
    }
}

/// The (x, y) lattice of one plan: which points are free, and a cache of
/// which edges passed the collision check. Per point one bit and one byte
/// (SPEC 3.1's memory rule): an edge is the same motion both ways, so it
/// is cached once, at the end it leaves in one of the four forward
/// directions E, N, NE, NW.
pub struct GridLattice {
    pub spec: LatticeSpec,
    /// Robot radius (0 for a point robot).
    pub radius: f64,
    pub free: BitSet,
    /// Per point, bit s: its forward edge s was checked; bit 4 + s: it is
    /// free ([`GridLattice::edge_slot`]).
    edges: Vec<u8>,
}

/// Every forward edge checked and free.
const ALL_EDGES_OPEN: u8 = u8::MAX;

impl GridLattice {
    /// Classifies every lattice point (on all cores). The caller has
    /// checked the size cap.
    pub fn build(spec: LatticeSpec, index: &ObstacleIndex, radius: f64) -> Self {
        let free = BitSet::from_fn(spec.layer_len(), |k| {
            index.disk_free(spec.point_of(k), radius)
        });
        Self::with_free(spec, radius, free)
    }

    /// [`GridLattice::build`], or `None` once `deadline` passes.
    pub fn build_until(
        spec: LatticeSpec,
        index: &ObstacleIndex,
        radius: f64,
        deadline: &Deadline,
    ) -> Option<Self> {
        let free = BitSet::from_fn_until(spec.layer_len(), deadline, |k| {
            index.disk_free(spec.point_of(k), radius)
        })?;
        Some(Self::with_free(spec, radius, free))
    }

    fn with_free(spec: LatticeSpec, radius: f64, free: BitSet) -> Self {
        GridLattice {
            spec,
            radius,
            edges: vec![0; free.len()],
            free,
        }
    }

    /// A lattice on which every point is free and every edge open, as if
    /// already checked: what a robot that has not sensed anything believes
    /// ([`super::online`]). Searching it never queries the obstacles; the
    /// robot overwrites what it senses with [`GridLattice::set_edge`] and
    /// `free`.
    pub fn optimistic(spec: LatticeSpec, radius: f64) -> Self {
        let n = spec.layer_len();
        GridLattice {
            spec,
            radius,
            free: BitSet::new(n, true),
            edges: vec![ALL_EDGES_OPEN; n],
        }
    }

    pub fn free_count(&self) -> usize {
        self.free.count_ones()
    }

    /// Bytes held per lattice point (for benchmarks).
    pub fn bytes(&self) -> usize {
        self.free.bytes() + self.edges.len()
    }

    /// The neighbour of `node` in direction `d` of [`DIRS`], if it lies
    /// inside the lattice.
    pub fn neighbour(&self, node: usize, d: usize) -> Option<usize> {
        let (i, j) = self.spec.coords(node);
        let (dx, dy) = DIRS[d];
        let (ni, nj) = (i as i64 + dx, j as i64 + dy);
        (ni >= 0 && nj >= 0 && (ni as usize) < self.spec.nx && (nj as usize) < self.spec.ny)
            .then(|| self.spec.index(ni as usize, nj as usize))
    }

    /// Whether the search may use edge (node, d) to `to`: both ends free, no
    /// corner cut (a diagonal needs both orthogonally adjacent points free)
    /// and the motion collision-free. The same rule as [`search`].
    pub fn edge_usable(&mut self, index: &ObstacleIndex, node: usize, d: usize, to: usize) -> bool {
        self.ends_and_corners_free(node, d, to) && self.edge_free(index, node, d, to)
    }

    /// [`GridLattice::edge_usable`] from what is already known, without
    /// querying the obstacles: an edge not checked yet counts as blocked.
    pub fn edge_known_usable(&self, node: usize, d: usize, to: usize) -> bool {
        let (at, slot) = Self::edge_slot(node, d, to);
        self.ends_and_corners_free(node, d, to) && self.edges[at] & (0x10 << slot) != 0
    }

    /// Where edge (node, d) to `to` is cached: the point it leaves in a
    /// forward direction (E, N, NE, NW: directions 0, 1, 4, 5 of [`DIRS`])
    /// and that direction's slot 0–3.
    #[inline]
    fn edge_slot(node: usize, d: usize, to: usize) -> (usize, u8) {
        const SLOT: [u8; 8] = [0, 1, 0, 1, 2, 3, 2, 3];
        let at = if matches!(d, 0 | 1 | 4 | 5) { node } else { to };
        (at, SLOT[d])
    }

    fn ends_and_corners_free(&self, node: usize, d: usize, to: usize) -> bool {
        if !self.free.get(node) || !self.free.get(to) {
            return false;
        }
        if d >= 4 {
            let nx = self.spec.nx as i64;
            let (dx, dy) = DIRS[d];
            let a = (node as i64 + dx) as usize;
            let b = (node as i64 + dy * nx) as usize;
            return self.free.get(a) && self.free.get(b);
        }
        true
    }

    /// Records whether the motion along edge (node, d) to `to` is free, for
    /// both directions (e.g. once a robot has sensed both ends).
    pub fn set_edge(&mut self, node: usize, d: usize, to: usize, ok: bool) {
        let (at, slot) = Self::edge_slot(node, d, to);
        let e = &mut self.edges[at];
        *e |= 1 << slot;
        if ok {
            *e |= 0x10 << slot;
        } else {
            *e &= !(0x10 << slot);
        }
    }

    /// Whether the motion along edge (node, d) is collision-free; `to` is
    /// the neighbour. Checked once per edge and cached for both directions.
    pub fn edge_free(&mut self, index: &ObstacleIndex, node: usize, d: usize, to: usize) -> bool {
        let (at, slot) = Self::edge_slot(node, d, to);
        if self.edges[at] & (1 << slot) == 0 {
            let ok = index.sweep_free(
                self.spec.point_of(node),
                self.spec.point_of(to),
                self.radius,
            );
            self.set_edge(node, d, to, ok);
        }
        self.edges[at] & (0x10 << slot) != 0
    }
}

/// A* from `start` to `goal` on the lattice. With w = 1 and the metric
/// heuristic (admissible and consistent for both cost metrics on this
/// lattice) the path is optimal; nodes are never reopened.
pub fn search(
    lat: &mut GridLattice,
    index: &ObstacleIndex,
    start: usize,
    goal: usize,
    cfg: &SearchConfig,
    record: bool,
    buf: &mut SearchBuffers,
) -> SearchResult {
    search_with(lat, index, start, goal, cfg, record, buf, |_, _, _| true)
}

/// [`search`] with a hook called just before each node is expanded, with
/// the node, the search tree so far (for [`Tree::parent`]) and the lattice,
/// which the hook may update for points and edges the search has not used
/// yet (an online robot walks to the node and senses there). The hook
/// returns `false` to stop the search (it then ends with `gave_up`).
#[allow(clippy::too_many_arguments)]
pub fn search_with(
    lat: &mut GridLattice,
    index: &ObstacleIndex,
    start: usize,
    goal: usize,
    cfg: &SearchConfig,
    record: bool,
    buf: &mut SearchBuffers,
    before_expand: impl FnMut(usize, &Tree<'_>, &mut GridLattice) -> bool,
) -> SearchResult {
    if !lat.free.get(start) || !lat.free.get(goal) {
        return SearchResult::default();
    }
    let spec = lat.spec;
    let nx = spec.nx as i64;
    let true_cost = step_costs(cfg.cost, spec.cell);
    let distance = LatticeDistance::new(cfg.connect, cfg.cost, spec.cell, 0.0);
    // With the lattice heuristic the search runs on its rounded costs
    // (exact ties, see `LatticeDistance`).
    let step_cost = match cfg.heuristic {
        Heuristic::Lattice => {
            DIRS.map(|(dx, dy)| distance.step(usize::from(dx != 0) | usize::from(dy != 0) << 1))
        }
        Heuristic::Metric | Heuristic::Zero => true_cost,
    };
    let (gi, gj) = spec.coords(goal);
    let mut graph = XyGraph {
        lat,
        index,
        goal,
        goal_pt: spec.point_of(goal),
        goal_ij: (gi as i64, gj as i64),
        distance,
        cfg,
        dirs: if cfg.connect == 4 { 4 } else { 8 },
        step_cost,
        // Index offsets of the neighbours, so that no division is needed
        // per neighbour; bounds are checked on (i, j).
        delta: DIRS.map(|(dx, dy)| dx + dy * nx),
        from: (0, 0),
        hook: before_expand,
    };
    let mut r = best_first(&mut graph, &[start], &cfg.limits, record, buf);
    if let Some(nodes) = &r.nodes {
        // The cost in the true metric, summed in path order (for the
        // other heuristics the same sum as g, bit for bit).
        r.cost = nodes.windows(2).fold(0.0, |sum, w| {
            let ((i, j), (k, l)) = (spec.coords(w[0]), spec.coords(w[1]));
            sum + true_cost[if i != k && j != l { 4 } else { 0 }]
        });
    }
    r
}

/// The cost of one move in each direction of [`DIRS`] on a lattice of
/// spacing `cell`.
pub fn step_costs(cost: CostMetric, cell: f64) -> [f64; 8] {
    DIRS.map(|(dx, dy)| {
        cost.between(
            Point::origin(),
            Point::new(dx as f64 * cell, dy as f64 * cell),
        )
    })
}

/// The (x, y) lattice as a graph for the search core: free neighbours, no
/// corner cutting, motions checked lazily ([`GridLattice::edge_free`]).
struct XyGraph<'a, F> {
    lat: &'a mut GridLattice,
    index: &'a ObstacleIndex,
    goal: usize,
    goal_pt: Point,
    goal_ij: (i64, i64),
    distance: LatticeDistance,
    cfg: &'a SearchConfig,
    dirs: usize,
    step_cost: [f64; 8],
    delta: [i64; 8],
    /// The lattice coordinates of the node whose successors were listed
    /// last (the neighbours' heuristic needs no division).
    from: (i64, i64),
    hook: F,
}

impl<F> XyGraph<'_, F> {
    /// h at lattice coordinates (i, j), inflated by the weight.
    #[inline]
    fn h(&self, i: i64, j: i64) -> f64 {
        let h = match self.cfg.heuristic {
            Heuristic::Lattice => self.distance.xy(
                (i - self.goal_ij.0).unsigned_abs(),
                (j - self.goal_ij.1).unsigned_abs(),
            ),
            Heuristic::Metric => {
                let spec = &self.lat.spec;
                let p = Point::new(
                    spec.x0 + i as f64 * spec.cell,
                    spec.y0 + j as f64 * spec.cell,
                );
                self.cfg.cost.between(p, self.goal_pt)
            }
            Heuristic::Zero => return 0.0,
        };
        self.cfg.weight * h
    }
}

impl<F: FnMut(usize, &Tree<'_>, &mut GridLattice) -> bool> Graph for XyGraph<'_, F> {
    fn node_count(&self) -> usize {
        self.lat.spec.layer_len()
    }

    fn successors(&mut self, node: usize, out: &mut Vec<Edge>) {
        let spec = &self.lat.spec;
        let (nx, ny) = (spec.nx, spec.ny);
        let (i, j) = (node % nx, node / nx);
        self.from = (i as i64, j as i64);
        let free = &self.lat.free;
        // Each neighbour read once: the four axis ones (inside the lattice
        // and free), then a diagonal one only where both axis moves beside
        // it are open (no corner cutting; it is then inside the lattice).
        let east = i + 1 < nx && free.get(node + 1);
        let north = j + 1 < ny && free.get(node + nx);
        let west = i > 0 && free.get(node - 1);
        let south = j > 0 && free.get(node - nx);
        let mut open = [east, north, west, south, false, false, false, false];
        if self.dirs > 4 {
            open[4] = east && north && free.get(node + nx + 1);
            open[5] = west && north && free.get(node + nx - 1);
            open[6] = west && south && free.get(node - nx - 1);
            open[7] = east && south && free.get(node - nx + 1);
        }
        for (d, _) in open.iter().enumerate().take(self.dirs).filter(|(_, o)| **o) {
            out.push(Edge {
                to: (node as i64 + self.delta[d]) as usize,
                cost: self.step_cost[d],
                label: d as u32,
            });
        }
    }

    fn usable(&mut self, from: usize, label: u32, to: usize) -> bool {
        self.lat.edge_free(self.index, from, label as usize, to)
    }

    fn heuristic(&self, node: usize) -> f64 {
        let (i, j) = self.lat.spec.coords(node);
        self.h(i as i64, j as i64)
    }

    fn edge_heuristic(&self, edge: &Edge) -> f64 {
        let (dx, dy) = DIRS[edge.label as usize];
        self.h(self.from.0 + dx, self.from.1 + dy)
    }

    fn is_goal(&self, node: usize) -> bool {
        node == self.goal
    }

    fn before_expand(&mut self, node: usize, tree: &Tree<'_>) -> bool {
        (self.hook)(node, tree, self.lat)
    }
}

/// The lattice points nearest to `start` and `goal` (SPEC 3.1), or a note
/// saying which end cannot be connected to its point: the point must be
/// free and the straight motion to it collision-free.
pub fn snap_ends(
    lat: &GridLattice,
    index: &ObstacleIndex,
    start: Config,
    goal: Config,
) -> Result<(usize, usize), String> {
    let spec = &lat.spec;
    let (Some(s), Some(g)) = (spec.snap(start), spec.snap(goal)) else {
        return Err("the lattice is empty: `cell` is larger than the bounds".into());
    };
    let (s_node, g_node) = (spec.index(s.0, s.1), spec.index(g.0, g.1));
    let (s_pt, g_pt) = (spec.point(s.0, s.1), spec.point(g.0, g.1));
    let mut blocked_end = None;
    if !lat.free.get(s_node) || !index.sweep_free(start.xy(), s_pt, lat.radius) {
        blocked_end = Some("start");
    } else if !lat.free.get(g_node) || !index.sweep_free(g_pt, goal.xy(), lat.radius) {
        blocked_end = Some("goal");
    }
    match blocked_end {
        Some(end) => Err(format!(
            "the {end} could not be connected to its nearest lattice point: make `cell` smaller or move the {end}"
        )),
        None => Ok((s_node, g_node)),
    }
}

/// The path start → lattice `nodes` → goal at the start's θ, without
/// repeated points, ending with the goal pose as given.
pub fn lattice_path(
    spec: &LatticeSpec,
    nodes: &[usize],
    start: Config,
    goal: Config,
) -> Vec<Config> {
    let mut path = vec![start];
    for &n in nodes {
        let p = spec.point_of(n);
        path.push(Config::new(p.x, p.y, start.theta));
    }
    path.push(Config::new(goal.x, goal.y, start.theta));
    path.dedup_by(|a, b| a.x == b.x && a.y == b.y);
    // The goal pose itself ends the path (its θ as given).
    if let Some(last) = path.last_mut() {
        *last = goal;
    }
    path
}

/// Obstacles grown by a disk robot's radius, for drawing: each convex
/// piece exactly (a disk grown by a disk is a disk of the summed radii);
/// grids excluded, their cells are drawn as they are.
pub fn grown_obstacles(world: &World, radius: f64) -> Vec<Rounded> {
    if radius <= 0.0 {
        return Vec::new();
    }
    let mut out = Vec::new();
    for o in &world.obstacles {
        match &o.shape {
            Shape::Disk { center, radius: r } => out.push(Rounded::new(&[*center], r + radius)),
            Shape::Grid(_) => {}
            shape => shape_pieces(shape, 0, |points| out.push(Rounded::new(&points, radius))),
        }
    }
    out
}
