//! The lattice of configurations shared by `astar` and `online`: sample
//! points in x and y (SPEC 3.1 `sample`), θ layers, the size computed
//! before anything is allocated, and the parameters and checks both
//! planners share (`cell`, `sample`, `connect`, the size cap).

use crate::contract::schema::{DefaultValue, ParamSpec, ValueSpec, num};
use crate::contract::{DEFAULT_CELL_CAP, PlanArgs};
use crate::diagnostics::Diag;
use crate::geometry::{Config, Point, World};
use crate::word_enum;

use super::deadline::{Deadline, SETUP_CHECK_EVERY};

word_enum! {
    /// Where lattice points sit in each cell.
    pub enum Sample {
        /// x = xmin + (i + ½)δ
        Center = "center",
        /// x = xmin + iδ
        Corner = "corner",
    }
}

word_enum! {
    /// Edge cost metric (SPEC 3.1 `cost`).
    pub enum CostMetric {
        Euclid = "euclid",
        L1 = "l1",
    }
}

word_enum! {
    /// SPEC 3.1 `heuristic`.
    pub enum Heuristic {
        /// The exact cost of the cheapest obstacle-free lattice path
        /// ([`LatticeDistance`]): admissible and consistent, and the
        /// tightest such heuristic that ignores obstacles.
        Lattice = "lattice",
        /// The cost metric to the goal (admissible and consistent, weaker).
        Metric = "metric",
        /// h = 0: Dijkstra.
        Zero = "zero",
    }
}

impl CostMetric {
    pub fn between(self, a: Point, b: Point) -> f64 {
        self.of(b.x - a.x, b.y - a.y, 0.0)
    }

    /// The metric of a displacement (dx, dy) with a rotation part `dt`
    /// (already `turn_cost · |dθ|`).
    pub fn of(self, dx: f64, dy: f64, dt: f64) -> f64 {
        match self {
            CostMetric::Euclid => (dx * dx + dy * dy + dt * dt).sqrt(),
            CostMetric::L1 => dx.abs() + dy.abs() + dt.abs(),
        }
    }
}

/// SPEC 3.1 `heuristic lattice`: the cost of the cheapest lattice path
/// between two configurations when nothing is in the way, in closed form.
///
/// A lattice move advances by one step along each axis of a set S of the
/// axes x, y, θ (a step is `cell` in x and y, one layer in θ) and costs
/// f(S), the cost metric of the step lengths (w_x = w_y = `cell`,
/// w_θ = `turn_cost` · the rotation between neighbouring layers).
/// `connect` says which sets are moves: 4 and 6 only single axes, 8 also
/// {x, y}, 26 every set. A set that is not a move costs the cheapest way to
/// make it of moves ([`LatticeDistance::new`]).
///
/// To advance n_1 ≥ n_2 ≥ n_3 steps along the axes a_1, a_2, a_3 (sorted by
/// their step counts), the cheapest path makes n_3 moves along
/// {a_1, a_2, a_3}, n_2 − n_3 along {a_1, a_2} and n_1 − n_2 along {a_1}:
/// octile distance on an 8-connected euclid lattice, Manhattan on a
/// 4-connected one, the L1 distance itself for `cost l1`. Why it is the
/// cheapest: f is submodular (the square root of a sum of squares, or a
/// sum), so this greedy chain is its Lovász extension, which is convex and
/// equals f on each move; by the triangle inequality no walk of moves,
/// whatever their signs or order, costs less. The same inequality makes the
/// heuristic consistent (h(u) ≤ c(u, v) + h(v)), and the chain's moves stay
/// inside the box between the two ends, so on an obstacle-free lattice the
/// distance is exact. θ counts its steps the shorter way round (θ wraps).
///
/// # Exact ties
/// On an open map many nodes have the same f = g + h in exact arithmetic
/// (every node of every shortest path), and the search core breaks such
/// ties towards the larger g, so that it follows one path instead of
/// widening over all of them. In floating point those f differ in their
/// last bits, depending on the order of the sums, and the ties are lost:
/// octile distance on the open 2,000 × 1,000 map expanded a third of it.
/// So the move costs are rounded to multiples of a power of two
/// ([`LatticeDistance::quantum`], 2⁻²⁸ of the largest move cost): then g,
/// h and f are sums of integer multiples of it, exact while they stay
/// below 2²⁵ times the largest move, and equal f are equal. A search
/// with this heuristic takes its move costs from [`LatticeDistance::step`]
/// (each off by at most half a quantum, 2⁻²⁹ of the largest move) and
/// reports the path's cost in the true metric.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LatticeDistance {
    /// f of every set of axes, by bits (x = 1, y = 2, θ = 4), rounded to
    /// multiples of `quantum`.
    cost: [f64; 8],
    quantum: f64,
}

impl LatticeDistance {
    /// The distance on a lattice of `connect` neighbours whose steps are
    /// `cell` in x and y and `turn` (turn cost × the rotation between
    /// neighbouring layers) in θ.
    pub fn new(connect: u8, metric: CostMetric, cell: f64, turn: f64) -> Self {
        let weights = [cell, cell, turn];
        // Every single axis is a move (θ too: a lattice without θ layers
        // never counts a step along it).
        let is_move = |set: usize| {
            set.count_ones() <= 1
                || match connect {
                    8 => set & 4 == 0,
                    26 => true,
                    _ => false,
                }
        };
        let exact = |set: usize| {
            let w = |axis: usize| {
                if set & (1 << axis) != 0 {
                    weights[axis]
                } else {
                    0.0
                }
            };
            metric.of(w(0), w(1), w(2))
        };
        let largest = (1..8)
            .filter(|&set| is_move(set))
            .map(exact)
            .fold(0.0, f64::max);
        let quantum = if largest > 0.0 && largest.is_finite() {
            2f64.powi(largest.log2().ceil() as i32 - 28)
        } else {
            1.0
        };
        // Sets by increasing size: a move's rounded cost, or the cheapest
        // way to make the set of two smaller ones if that is less (always
        // for a set that is not a move; after rounding, a diagonal could
        // otherwise cost a quantum more than its two axis moves, which an
        // `l1` lattice makes equal).
        let mut cost = [0.0; 8];
        for set in [1, 2, 4, 3, 5, 6, 7] {
            let mut c = if is_move(set) {
                // Exact: dividing and multiplying by a power of two.
                (exact(set) / quantum).round() * quantum
            } else {
                f64::INFINITY
            };
            let mut part = (set - 1) & set;
            while part > 0 {
                c = c.min(cost[part] + cost[set ^ part]);
                part = (part - 1) & set;
            }
            cost[set] = c;
        }
        LatticeDistance { cost, quantum }
    }

    /// The cost a search with this heuristic gives a move along the axes
    /// of `set` (bits x = 1, y = 2, θ = 4): the true cost rounded to a
    /// multiple of the quantum.
    #[inline]
    pub fn step(&self, set: usize) -> f64 {
        self.cost[set & 7]
    }

    /// The power of two all costs are multiples of.
    pub fn quantum(&self) -> f64 {
        self.quantum
    }

    /// The cost of `dx` and `dy` steps in x and y (non-negative).
    #[inline]
    pub fn xy(&self, dx: u64, dy: u64) -> f64 {
        let (lo, hi) = if dx < dy { (dx, dy) } else { (dy, dx) };
        lo as f64 * self.cost[3] + (hi - lo) as f64 * self.cost[1]
    }

    /// The cost of `steps` steps along x, y and θ (non-negative; θ already
    /// the shorter way round).
    pub fn xyt(&self, steps: [u64; 3]) -> f64 {
        let mut axes = [0usize, 1, 2];
        axes.sort_by(|&a, &b| steps[b].cmp(&steps[a]));
        let [a1, a2, a3] = axes;
        let (n1, n2, n3) = (steps[a1], steps[a2], steps[a3]);
        let (s1, s2) = (1 << a1, (1 << a1) | (1 << a2));
        n3 as f64 * self.cost[7]
            + (n2 - n3) as f64 * self.cost[s2]
            + (n1 - n2) as f64 * self.cost[s1]
    }
}

/// One bit per lattice configuration (free or blocked): the part of a
/// lattice that every configuration needs, so it is kept at a bit each
/// (SPEC 3.1: at most 12 bytes per configuration in all).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BitSet {
    words: Vec<u64>,
    len: usize,
}

impl BitSet {
    /// `len` bits, all `value`.
    pub fn new(len: usize, value: bool) -> Self {
        let mut words = vec![if value { u64::MAX } else { 0 }; len.div_ceil(64)];
        if let Some(last) = words.last_mut()
            && !len.is_multiple_of(64)
        {
            *last &= (1u64 << (len % 64)) - 1;
        }
        BitSet { words, len }
    }

    /// Bit `i` = `bit(i)` for `i` in `0..len`, computed on all cores.
    pub fn from_fn(len: usize, bit: impl Fn(usize) -> bool + Sync) -> Self {
        // A deadline that never passes: always `Some`.
        Self::from_fn_until(len, &Deadline::never(), bit).unwrap_or_default()
    }

    /// [`BitSet::from_fn`], or `None` once `deadline` passes (SPEC 2.5:
    /// classifying a lattice is set-up, which `limit time` counts). The
    /// clock is asked once per [`SETUP_CHECK_EVERY`] bits.
    pub fn from_fn_until(
        len: usize,
        deadline: &Deadline,
        bit: impl Fn(usize) -> bool + Sync,
    ) -> Option<Self> {
        use rayon::prelude::*;
        use std::sync::atomic::{AtomicBool, Ordering};
        const WORDS: usize = SETUP_CHECK_EVERY / 64;
        let stop = AtomicBool::new(false);
        let mut words = vec![0u64; len.div_ceil(64)];
        words
            .par_chunks_mut(WORDS)
            .enumerate()
            .for_each(|(c, chunk)| {
                if stop.load(Ordering::Relaxed) {
                    return;
                }
                if deadline.passed() {
                    stop.store(true, Ordering::Relaxed);
                    return;
                }
                for (k, word) in chunk.iter_mut().enumerate() {
                    let first = (c * WORDS + k) * 64;
                    for b in 0..64.min(len - first) {
                        if bit(first + b) {
                            *word |= 1 << b;
                        }
                    }
                }
            });
        (!stop.into_inner()).then_some(BitSet { words, len })
    }

    #[inline]
    pub fn get(&self, i: usize) -> bool {
        self.words[i >> 6] >> (i & 63) & 1 != 0
    }

    #[inline]
    pub fn set(&mut self, i: usize, value: bool) {
        let (w, bit) = (i >> 6, 1u64 << (i & 63));
        if value {
            self.words[w] |= bit;
        } else {
            self.words[w] &= !bit;
        }
    }

    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The number of bits set.
    pub fn count_ones(&self) -> usize {
        self.words.iter().map(|w| w.count_ones() as usize).sum()
    }

    /// Bytes held (for benchmarks).
    pub fn bytes(&self) -> usize {
        self.words.len() * 8
    }
}

/// `cell`, `sample` and `connect`: the lattice parameters of `astar` and
/// `online`.
pub const LATTICE_PARAMS: [ParamSpec; 3] = [
    ParamSpec::positive("cell", num(1.0, "1"), "lattice spacing δ in x and y"),
    ParamSpec::word(
        "sample",
        <Sample as crate::contract::schema::Word>::WORDS,
        "center",
        "lattice points at cell centres or corners",
    ),
    ParamSpec::new(
        "connect",
        ValueSpec::IntChoice(&[4, 8, 6, 26]),
        DefaultValue::Derived("8 (26 for rotating robots)"),
        "lattice neighbours: 4 or 8 in (x, y), 6 or 26 in (x, y, θ)",
    ),
];

/// `connect` as given, checked against the lattice: 4 or 8 on an (x, y)
/// lattice, 6 or 26 on a rotating robot's (x, y, θ) lattice; the default
/// is 8, or 26 when `rotating`. `None` after reporting a bad value.
pub fn check_connect(args: &mut PlanArgs<'_>, rotating: bool) -> Option<u8> {
    let Some(x) = args.opt_num("connect") else {
        return Some(if rotating { 26 } else { 8 });
    };
    let polygon = args.robot.shape.rotates();
    let (ok, list, lattice, help) = match (rotating, polygon) {
        (true, _) => (
            x == 6.0 || x == 26.0,
            "`6` or `26`",
            " for a rotating robot's (x, y, θ) lattice",
            "use `connect 6` or `connect 26`, or add `rotate no` to plan in (x, y) at the start's θ"
                .to_string(),
        ),
        (false, true) => (
            x == 4.0 || x == 8.0,
            "`4` or `8`",
            " with `rotate no` (an (x, y) lattice at the start's θ)",
            "use `connect 4` or `connect 8`, or remove `rotate no`".to_string(),
        ),
        (false, false) => (
            x == 4.0 || x == 8.0,
            "`4` or `8`",
            " for an (x, y) lattice",
            format!("`connect`: {}", args.spec("connect").help),
        ),
    };
    if ok {
        return Some(x as u8);
    }
    let span = args.span("connect");
    args.error(
        Diag::error(
            "scen::analyze::out_of_range",
            format!("`connect` must be {list}{lattice}, got {x}"),
        )
        .at(span, "not accepted")
        .help(help),
    );
    None
}

/// The lattice a plan asks for (`cell`, `sample`, `layers` θ layers over
/// the world's bounds), refused before anything is allocated when it
/// exceeds the cap (`limit cells N`, default [`DEFAULT_CELL_CAP`]).
pub fn check_lattice(args: &mut PlanArgs<'_>, layers: f64) -> Option<LatticeSpec> {
    let sample = args.word("sample");
    check_lattice_of(args, sample, layers)
}

/// [`check_lattice`] with the points sampled as `sample` says (for a
/// planner without the `sample` parameter).
pub fn check_lattice_of(
    args: &mut PlanArgs<'_>,
    sample: Sample,
    layers: f64,
) -> Option<LatticeSpec> {
    let spec = LatticeSpec::new(args.world, args.num("cell"), sample, layers);
    let cap = args.params.limits.cells.unwrap_or(DEFAULT_CELL_CAP);
    let cells = spec.cells_f64();
    if cells > cap as f64 {
        let at = args.span("cell");
        let plan = args.plan;
        args.error(
            Diag::error(
                "scen::analyze::lattice_too_large",
                format!(
                    "the lattice of plan `{plan}` would have {cells:.3e} cells, over the cap of {cap}"
                ),
            )
            .at(at, format!("{} × {} × {} layers", spec.nx, spec.ny, spec.layers))
            .help("use a larger `cell` (or fewer `layers`), or raise the cap with `limit cells N`"),
        );
        return None;
    }
    Some(spec)
}

/// The shape of a lattice: spacing, sampling and counts per axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LatticeSpec {
    pub cell: f64,
    pub sample: Sample,
    pub x0: f64,
    pub y0: f64,
    pub nx: usize,
    pub ny: usize,
    pub layers: usize,
    /// The exact counts as floats (before any cast), for the size cap.
    nx_f: f64,
    ny_f: f64,
}

impl LatticeSpec {
    pub fn new(world: &World, cell: f64, sample: Sample, layers: f64) -> Self {
        let b = world.bounds;
        let count = |extent: f64| -> f64 {
            // Points i = 0, 1, ... while x ≤ xmax (with a little slack for
            // rounding, so that 32 / 1 gives 33 corner points).
            let span = extent / cell + 1e-9;
            match sample {
                Sample::Center if span >= 0.5 => (span - 0.5).floor() + 1.0,
                Sample::Center => 0.0,
                Sample::Corner => span.floor() + 1.0,
            }
        };
        let nx_f = count(b.width());
        let ny_f = count(b.height());
        let off = match sample {
            Sample::Center => 0.5 * cell,
            Sample::Corner => 0.0,
        };
        let clamp = |v: f64| {
            if v.is_finite() && v < 1e15 {
                v as usize
            } else {
                usize::MAX
            }
        };
        LatticeSpec {
            cell,
            sample,
            x0: b.min.x + off,
            y0: b.min.y + off,
            nx: clamp(nx_f),
            ny: clamp(ny_f),
            layers: clamp(layers),
            nx_f,
            ny_f,
        }
    }

    /// The number of lattice configurations, as a float (never overflows).
    pub fn cells_f64(&self) -> f64 {
        self.nx_f * self.ny_f * self.layers as f64
    }

    /// The number of (x, y) points of one layer. Only call after the size
    /// cap was checked.
    pub fn layer_len(&self) -> usize {
        self.nx * self.ny
    }

    pub fn index(&self, i: usize, j: usize) -> usize {
        j * self.nx + i
    }

    pub fn coords(&self, index: usize) -> (usize, usize) {
        (index % self.nx, index / self.nx)
    }

    pub fn point(&self, i: usize, j: usize) -> Point {
        Point::new(
            self.x0 + i as f64 * self.cell,
            self.y0 + j as f64 * self.cell,
        )
    }

    /// The point of a node index of one layer.
    pub fn point_of(&self, index: usize) -> Point {
        let (i, j) = self.coords(index);
        self.point(i, j)
    }

    /// The nearest lattice point to `c`, if the lattice is not empty.
    pub fn snap(&self, c: Config) -> Option<(usize, usize)> {
        if self.nx == 0 || self.ny == 0 {
            return None;
        }
        let fi = ((c.x - self.x0) / self.cell)
            .round()
            .clamp(0.0, (self.nx - 1) as f64);
        let fj = ((c.y - self.y0) / self.cell)
            .round()
            .clamp(0.0, (self.ny - 1) as f64);
        Some((fi as usize, fj as usize))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Aabb;

    fn world(w: f64, h: f64) -> World {
        World {
            bounds: Aabb::from_corners(Point::new(0.0, 0.0), Point::new(w, h)),
            obstacles: vec![],
        }
    }

    #[test]
    fn counts_follow_the_sampling_rule() {
        let c = LatticeSpec::new(&world(32.0, 30.0), 1.0, Sample::Center, 1.0);
        assert_eq!((c.nx, c.ny), (32, 30));
        assert_eq!(c.point(0, 0), Point::new(0.5, 0.5));
        let k = LatticeSpec::new(&world(32.0, 30.0), 1.0, Sample::Corner, 1.0);
        assert_eq!((k.nx, k.ny), (33, 31));
        let f = LatticeSpec::new(&world(32.0, 30.0), 1.0 / 1.5, Sample::Center, 1.0);
        assert_eq!((f.nx, f.ny), (48, 45));
    }

    #[test]
    fn huge_lattices_do_not_overflow() {
        let c = LatticeSpec::new(&world(1e6, 1e6), 1e-3, Sample::Center, 1.0);
        assert!(c.cells_f64() > 1e17);
    }

    #[test]
    fn snapping_picks_the_nearest_point() {
        let c = LatticeSpec::new(&world(10.0, 10.0), 1.0, Sample::Center, 1.0);
        assert_eq!(c.snap(Config::new(4.4, 2.6, 0.0)), Some((4, 2)));
        assert_eq!(c.snap(Config::new(-3.0, 99.0, 0.0)), Some((0, 9)));
    }

    /// Dijkstra on an obstacle-free box lattice of `n = [nx, ny, layers]`
    /// from the origin: every move of `connect` (θ wrapping; for two layers
    /// +1 and −1 are one move), costs in `metric` with steps `cell`,
    /// `cell` and `turn`. Written independently of `LatticeDistance`.
    fn dijkstra(n: [usize; 3], connect: u8, metric: CostMetric, cell: f64, turn: f64) -> Vec<f64> {
        use std::cmp::Reverse;
        let len = n[0] * n[1] * n[2];
        let at = |i: usize, j: usize, k: usize| (k * n[1] + j) * n[0] + i;
        let mut moves = Vec::new();
        for dk in -1i64..=1 {
            for dy in -1i64..=1 {
                for dx in -1i64..=1 {
                    let axes = [dx, dy, dk].iter().filter(|d| **d != 0).count();
                    let ok = match connect {
                        4 | 6 => axes == 1,
                        8 => axes >= 1 && dk == 0,
                        _ => axes >= 1,
                    };
                    if ok && (dk == 0 || n[2] >= 2) {
                        let c =
                            metric.of(dx as f64 * cell, dy as f64 * cell, dk.abs() as f64 * turn);
                        moves.push((dx, dy, dk, c));
                    }
                }
            }
        }
        let mut dist = vec![f64::INFINITY; len];
        let mut heap = std::collections::BinaryHeap::new();
        dist[0] = 0.0;
        heap.push(Reverse((0u64, 0usize)));
        while let Some(Reverse((d, u))) = heap.pop() {
            let d = f64::from_bits(d);
            if d > dist[u] {
                continue;
            }
            let (i, j, k) = (u % n[0], u / n[0] % n[1], u / (n[0] * n[1]));
            for &(dx, dy, dk, c) in &moves {
                let (ni, nj) = (i as i64 + dx, j as i64 + dy);
                if ni < 0 || nj < 0 || ni >= n[0] as i64 || nj >= n[1] as i64 {
                    continue;
                }
                let nk = (k as i64 + dk).rem_euclid(n[2] as i64) as usize;
                let v = at(ni as usize, nj as usize, nk);
                if d + c < dist[v] {
                    dist[v] = d + c;
                    // Non-negative floats order as their bits.
                    heap.push(Reverse(((d + c).to_bits(), v)));
                }
            }
        }
        dist
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(400))]

        /// On obstacle-free lattices of every `connect` and both metrics the
        /// lattice distance equals the true cheapest-path cost (Dijkstra),
        /// up to the rounding of move costs to the quantum, and is
        /// consistent along every move.
        #[test]
        fn lattice_distance_is_the_obstacle_free_lattice_cost(
            nx in 1usize..7,
            ny in 1usize..7,
            layers in 1usize..9,
            connect in proptest::sample::select(vec![4u8, 8, 6, 26]),
            l1 in proptest::bool::ANY,
            cell in 0.05f64..3.0,
            turn_cost in 0.0f64..6.0,
        ) {
            let metric = if l1 { CostMetric::L1 } else { CostMetric::Euclid };
            let rotating = matches!(connect, 6 | 26);
            let layers = if rotating { layers } else { 1 };
            let step = std::f64::consts::TAU / layers as f64;
            let turn = turn_cost * step.min(std::f64::consts::TAU - step);
            let truth = dijkstra([nx, ny, layers], connect, metric, cell, turn);
            let h = LatticeDistance::new(connect, metric, cell, turn);
            let at = |i: usize, j: usize, k: usize| (k * ny + j) * nx + i;
            let tol = h.quantum() * (nx + ny + layers) as f64;
            for k in 0..layers {
                for j in 0..ny {
                    for i in 0..nx {
                        let dk = k.min(layers - k) as u64;
                        let est = h.xyt([i as u64, j as u64, dk]);
                        let d = truth[at(i, j, k)];
                        proptest::prop_assert!(est <= d + tol, "h {est} above the lattice cost {d} at {:?}", (i, j, k));
                        proptest::prop_assert!((est - d).abs() <= tol, "h {est}, lattice cost {d} at {:?}", (i, j, k));
                        if k == 0 {
                            proptest::prop_assert_eq!(est, h.xy(i as u64, j as u64));
                        }
                    }
                }
            }
            // Consistency: h(u) ≤ c(u, v) + h(v) for every move of the
            // search's (rounded) costs, towards the goal at the origin.
            let step_of = |dx: i64, dy: i64, dk: i64| {
                h.step(usize::from(dx != 0) | usize::from(dy != 0) << 1 | usize::from(dk != 0) << 2)
            };
            for (i, j) in [(0i64, 0i64), (1, 2), (3, 1)] {
                for (dx, dy) in [(1i64, 0i64), (0, 1), (1, 1), (-1, 1)] {
                    if connect == 4 && dx != 0 && dy != 0 {
                        continue;
                    }
                    let (ni, nj) = (i + dx, j + dy);
                    if ni < 0 || nj < 0 {
                        continue;
                    }
                    let hu = h.xy(i as u64, j as u64);
                    let hv = h.xy(ni as u64, nj as u64);
                    proptest::prop_assert!(hv <= step_of(dx, dy, 0) + hu && hu <= step_of(dx, dy, 0) + hv);
                }
            }
        }
    }
}
