//! The nearest-neighbour index of the sampling-based planners: a k-d tree
//! over the keys `(x, y)` or `(x, y, c·θ)` whose last axis may be periodic
//! (θ ∈ [0, 2π) scaled by the turn cost c, period 2π·c), so that distances
//! follow θ's wrap-around.
//!
//! # Structure
//! Points are stored in *leaves* of up to [`LEAF`] points; an internal node
//! splits its points at a value of one axis (points with a coordinate ≥ the
//! value go right). A point is inserted into the leaf its coordinates lead
//! to; a full leaf splits at the median of its points along the axis of
//! their widest spread (a leaf of points equal on every axis grows
//! instead). No rebalancing: the samples of a planner come in random order,
//! so the expected depth is O(log n), and the walk uses an explicit stack,
//! so a degenerate insertion order (a chain of collinear extensions) costs
//! time, never the call stack. Leaves make a query scan a few short runs of
//! points rather than visit one tree node per point (a third of the
//! instructions of the one-point-per-node tree on the apartment rod); a
//! leaf holds a copy of each point's key beside its index, so a scan reads
//! one run of memory.
//!
//! # Queries and the wrap-around
//! The distance between keys is Euclidean with the periodic axis'
//! difference taken the shorter way round ([`KdTree::distance2`]). Each
//! node keeps the bounding box of its subtree's points (grown on insertion);
//! the query's distance to a box, along the periodic axis round the circle
//! to the box's arc, is a lower bound of its distance to every point in the
//! subtree. A query descends from the root to the leaf its coordinates
//! lead to, at each split pushing the other child with its box's distance
//! (unless that is already beyond the current k-th candidate), then pops
//! the pushed subtrees, skipping those whose distance now lies beyond the
//! k-th candidate, and descends from each the same way; so the result is
//! exact. Only the far child's box is measured on the way down (the near
//! one holds the query's side of the split), and only once the distance
//! to the split plane, a cheaper lower bound, is within the bound (along
//! the periodic axis, where the way round the circle may be shorter, that
//! distance is taken as 0); on the first descent, before any candidate,
//! nothing can be pruned, so the far children are pushed with that plane
//! distance alone and their boxes measured when popped, if still within
//! the bound. A leaf's own box is measured before its points once there
//! is a candidate, unless the leaf was itself popped (measured then). The
//! box distance computes x and y as one pair of lanes and θ with a spare
//! lane as another (boxes have a fourth coordinate, 0), two lanes per
//! instruction, summed in the order of the point distance so that it
//! stays a lower bound in floating point. The tight boxes (rather than the cells of the splits)
//! prune at once for samples far from the tree, which are most of an
//! RRT's. The wrap-around is a min with the period measured the other way
//! round (`distance2`, `gap2`), the period infinite for keys that do not
//! wrap, so the walk has no branch on the kind of keys (2-dimensional keys
//! have a third coordinate 0); those mins and maxes are plain comparisons
//! (one instruction each) rather than `f64::min`/`max`, whose care for NaN
//! costs several, as nothing the walk compares is NaN. Ties between equal
//! distances go to the lower index: results do not depend on the walk
//! order.

// The walk compares no NaN (keys, queries and boxes are finite, the
// period at most infinite): plain comparisons, one instruction each.
use crate::geometry::{max_of_numbers as max, min_of_numbers as min};

/// "No child": the node is a leaf.
const NONE: u32 = u32::MAX;

/// The tag of a pending subtree on the walk's stack whose bound is only its
/// split plane's distance (its box not yet measured); node indices stay
/// below it (asserted when a node is made).
const UNMEASURED: u32 = 1 << 31;

/// The most points of a leaf (unless they are all equal).
const LEAF: usize = 8;

/// A k-d tree over 2- or 3-dimensional keys (see the module documentation).
#[derive(Clone, Debug)]
pub struct KdTree {
    dims: usize,
    /// The period of the last axis (`dims == 3`), infinite when it does
    /// not wrap (the formulas' `min` with the way round is then a no-op).
    wrap: f64,
    /// Per lane of [`gap2`], the period of its axis: `wrap` for the third,
    /// infinite for the others.
    wraps: [f64; 4],
    /// Point `i`'s key.
    keys: Vec<[f64; 3]>,
    /// Node 0 is the root (once a point exists).
    nodes: Vec<Node>,
    /// The points of each leaf (`Node::leaf` indexes it), each with a copy
    /// of its key (a scan reads them in a row).
    leaves: Vec<Vec<([f64; 3], u32)>>,
    /// Per axis, 1 when the distance to a split plane along it is a lower
    /// bound of the distance to the points beyond, 0 for the periodic axis.
    plane: [f64; 3],
    /// The walk's pending subtrees and their lower bounds.
    stack: Vec<(u32, f64)>,
}

/// A node: the box of its subtree's points (min and max per axis; the third
/// axis (0, 0) for 2-dimensional keys), and either its split and children
/// or its leaf.
#[derive(Clone, Copy, Debug)]
struct Node {
    lo: [f64; 4],
    hi: [f64; 4],
    axis: u32,
    split: f64,
    children: [u32; 2],
    leaf: u32,
}

impl KdTree {
    /// An empty index of `dims` (2 or 3) axes; with 3, the last one wraps
    /// with period `period` when it is positive.
    pub fn new(dims: usize, period: f64) -> Self {
        assert!(dims == 2 || dims == 3, "a k-d tree of 2 or 3 axes");
        let period = if dims == 3 && period > 0.0 {
            period
        } else {
            0.0
        };
        KdTree {
            dims,
            wrap: if period > 0.0 { period } else { f64::INFINITY },
            wraps: [
                f64::INFINITY,
                f64::INFINITY,
                if period > 0.0 { period } else { f64::INFINITY },
                f64::INFINITY,
            ],
            plane: [1.0, 1.0, if period > 0.0 { 0.0 } else { 1.0 }],
            keys: Vec::new(),
            nodes: Vec::new(),
            leaves: Vec::new(),
            stack: Vec::new(),
        }
    }

    pub fn len(&self) -> usize {
        self.keys.len()
    }

    pub fn is_empty(&self) -> bool {
        self.keys.is_empty()
    }

    /// The key of point `i`.
    pub fn point(&self, i: usize) -> [f64; 3] {
        self.keys[i]
    }

    /// A new leaf node holding `points`, its box theirs.
    fn leaf_node(&mut self, points: Vec<([f64; 3], u32)>) -> u32 {
        let (mut lo, mut hi) = EMPTY_BOX;
        for (key, _) in &points {
            grow_box(&mut lo, &mut hi, key);
        }
        self.leaves.push(points);
        self.nodes.push(Node {
            lo,
            hi,
            axis: 0,
            split: 0.0,
            children: [NONE; 2],
            leaf: (self.leaves.len() - 1) as u32,
        });
        (self.nodes.len() - 1) as u32
    }

    /// Adds `key` (its periodic coordinate in [0, period); its third one
    /// ignored for 2 axes); returns its index, the number of points before
    /// it.
    pub fn insert(&mut self, mut key: [f64; 3]) -> usize {
        if self.dims == 2 {
            key[2] = 0.0;
        }
        let index = self.keys.len() as u32;
        self.keys.push(key);
        if index == 0 {
            self.leaf_node(vec![(key, 0)]);
            return 0;
        }
        let mut node = 0usize;
        loop {
            let n = &mut self.nodes[node];
            grow_box(&mut n.lo, &mut n.hi, &key);
            if n.children[0] == NONE {
                break;
            }
            let side = usize::from(key[n.axis as usize] >= n.split);
            node = n.children[side] as usize;
        }
        let leaf = self.nodes[node].leaf as usize;
        self.leaves[leaf].push((key, index));
        if self.leaves[leaf].len() > LEAF {
            self.split(node);
        }
        index as usize
    }

    /// Splits leaf `node` at the median of its points along the axis of
    /// their widest spread; leaves it whole when they are all equal.
    fn split(&mut self, node: usize) {
        let n = self.nodes[node];
        let Some(axis) = (0..self.dims)
            .filter(|&a| n.hi[a] > n.lo[a])
            .max_by(|&a, &b| (n.hi[a] - n.lo[a]).total_cmp(&(n.hi[b] - n.lo[b])))
        else {
            return;
        };
        let points = std::mem::take(&mut self.leaves[n.leaf as usize]);
        let mut values: Vec<f64> = points.iter().map(|(key, _)| key[axis]).collect();
        values.sort_by(f64::total_cmp);
        // The median, moved up past equal values so that both sides hold a
        // point (the widest spread is positive: some value is larger).
        let mut split = values[values.len() / 2];
        if split == values[0] {
            split = values
                .iter()
                .copied()
                .find(|&v| v > values[0])
                .unwrap_or(values[0]);
        }
        let (right, left): (Vec<_>, Vec<_>) =
            points.iter().partition(|(key, _)| key[axis] >= split);
        // The left half keeps the leaf's slot.
        self.leaves[n.leaf as usize] = left;
        self.nodes.push(Node {
            children: [NONE; 2],
            ..n
        });
        let l = (self.nodes.len() - 1) as u32;
        self.refit(l);
        let r = self.leaf_node(right);
        assert!(r < UNMEASURED, "fewer than 2³¹ nodes");
        let parent = &mut self.nodes[node];
        parent.axis = axis as u32;
        parent.split = split;
        parent.children = [l, r];
    }

    /// Sets a leaf's box to its points'.
    fn refit(&mut self, node: u32) {
        let n = &mut self.nodes[node as usize];
        let (mut lo, mut hi) = EMPTY_BOX;
        for (key, _) in &self.leaves[n.leaf as usize] {
            grow_box(&mut lo, &mut hi, key);
        }
        n.lo = lo;
        n.hi = hi;
    }

    /// The squared distance between two keys, the periodic axis the shorter
    /// way round (the third coordinates ignored for 2 axes).
    #[inline]
    pub fn distance2(&self, a: &[f64; 3], b: &[f64; 3]) -> f64 {
        if self.dims == 2 {
            distance2(&[a[0], a[1], 0.0], &[b[0], b[1], 0.0], self.wrap)
        } else {
            distance2(a, b, self.wrap)
        }
    }

    /// The nearest point to `q` and its squared distance (`None` when
    /// empty); ties to the lower index.
    ///
    /// The walk of [`KdTree::k_nearest`] with k = 1, keeping the best
    /// candidate in place of an ordered list (the planners' most frequent query).
    pub fn nearest(&mut self, q: &[f64; 3]) -> Option<(usize, f64)> {
        if self.keys.is_empty() {
            return None;
        }
        let mut best = Candidate(f64::INFINITY, u32::MAX);
        self.walk(q, |candidate| {
            // The walk offers only candidates no farther than the best: one
            // nearer, or as near with a lower index, wins.
            if candidate.0 < best.0 || candidate.1 < best.1 {
                best = candidate;
            }
            best.0
        });
        Some((best.1 as usize, best.0))
    }

    /// The `k` nearest points to `q` into `out` as (squared distance,
    /// index), nearest first, ties to the lower index (fewer when the index
    /// holds fewer).
    pub fn k_nearest(&mut self, q: &[f64; 3], k: usize, out: &mut Vec<(f64, u32)>) {
        out.clear();
        if k == 0 || self.keys.is_empty() {
            return;
        }
        // `out` holds the best so far in order, at most k: a candidate
        // is inserted in place (k is small), the worst dropped past k.
        let mut worst = f64::INFINITY;
        self.walk(q, |c| {
            // The walk offers only candidates no farther than the worst.
            let before = |o: &(f64, u32)| c.0 < o.0 || (c.0 == o.0 && c.1 < o.1);
            if out.len() == k {
                if !before(&out[k - 1]) {
                    return worst;
                }
                out.pop();
            }
            let mut i = out.len();
            while i > 0 && before(&out[i - 1]) {
                i -= 1;
            }
            out.insert(i, (c.0, c.1));
            if out.len() == k {
                worst = out[k - 1].0;
            }
            worst
        });
    }

    /// The walk both queries share: depth first, the query's side of each
    /// split first, skipping every subtree whose box is farther than the
    /// bound. `visit`
    /// sees each point reached as a candidate and returns the bound after
    /// it (the squared distance beyond which nothing is wanted).
    fn walk(&mut self, q: &[f64; 3], mut visit: impl FnMut(Candidate) -> f64) {
        let mut q = *q;
        if self.dims == 2 {
            q[2] = 0.0;
        }
        let wrap = self.wrap;
        let wraps = self.wraps;
        let q4 = [q[0], q[1], q[2], 0.0];
        let plane = self.plane;
        let mut stack = std::mem::take(&mut self.stack);
        stack.clear();
        let mut limit = f64::INFINITY;
        let mut node = 0u32;
        // The first descent, before any candidate: nothing is pruned yet,
        // so each far side is pushed with the distance to its split plane
        // and its box is measured only if that bound is within the bound
        // when it is popped (most are beyond it by then).
        loop {
            let n = &self.nodes[node as usize];
            if n.children[0] == NONE {
                break;
            }
            let axis = n.axis as usize;
            let side = usize::from(q[axis] >= n.split);
            let d = q[axis] - n.split;
            stack.push((n.children[1 - side] | UNMEASURED, d * d * plane[axis]));
            node = n.children[side];
        }
        // Whether `node`'s box was measured against the bound (popped, or
        // the first leaf, which nothing bounds yet).
        let mut measured = true;
        loop {
            let n = &self.nodes[node as usize];
            if n.children[0] != NONE {
                let axis = n.axis as usize;
                let side = usize::from(q[axis] >= n.split);
                let far = n.children[1 - side];
                let d = q[axis] - n.split;
                if d * d * plane[axis] <= limit {
                    let f = &self.nodes[far as usize];
                    let g = gap2(&q4, &f.lo, &f.hi, &wraps);
                    if g <= limit {
                        stack.push((far, g));
                    }
                }
                node = n.children[side];
                measured = false;
                continue;
            }
            // A leaf reached below a popped subtree may lie beyond the
            // bound: its box is measured before its points.
            if measured || gap2(&q4, &n.lo, &n.hi, &wraps) <= limit {
                for &(key, p) in &self.leaves[n.leaf as usize] {
                    let d = distance2(&q, &key, wrap);
                    if d <= limit {
                        limit = visit(Candidate(d, p));
                    }
                }
            }
            loop {
                let Some((next, bound)) = stack.pop() else {
                    self.stack = stack;
                    return;
                };
                if bound <= limit {
                    node = next & !UNMEASURED;
                    if next & UNMEASURED != 0 {
                        let n = &self.nodes[node as usize];
                        if gap2(&q4, &n.lo, &n.hi, &wraps) > limit {
                            continue;
                        }
                    }
                    measured = true;
                    break;
                }
            }
        }
    }
}

/// The squared distance between keys `a` and `b` whose last axis wraps
/// with period `wrap` (infinite when it does not: the same formula).
#[inline]
fn distance2(a: &[f64; 3], b: &[f64; 3], wrap: f64) -> f64 {
    let (dx, dy) = (a[0] - b[0], a[1] - b[1]);
    let dt = (a[2] - b[2]).abs();
    let dt = min(dt, wrap - dt);
    dx * dx + dy * dy + dt * dt
}

/// The squared distance from `q` to the box [lo, hi] (along an axis that
/// wraps, round the circle to its arc): a lower bound of the distance to
/// each point in it. Two pairs of lanes, (x, y) and (θ, a fourth lane 0 in
/// `q` and the box, which adds 0), each pair of one formula so that the
/// compiler computes it two lanes per instruction; `wraps` the period of
/// the second pair's lanes (infinite: the `min` with the way round is a
/// no-op). The sum in [`distance2`]'s order, so the bound holds in floating
/// point too.
#[inline]
fn gap2(q: &[f64; 4], lo: &[f64; 4], hi: &[f64; 4], wraps: &[f64; 4]) -> f64 {
    let mut g = [0.0; 4];
    for a in 0..2 {
        let out = max(max(lo[a] - q[a], q[a] - hi[a]), 0.0);
        g[a] = out * out;
    }
    for a in 2..4 {
        let out = max(max(lo[a] - q[a], q[a] - hi[a]), 0.0);
        let v = min(out, wraps[a] - (max(hi[a], q[a]) - min(lo[a], q[a])));
        g[a] = v * v;
    }
    g[0] + g[1] + g[2] + g[3]
}

/// The box of no point (its fourth lane, unused, 0: see [`gap2`]).
const EMPTY_BOX: ([f64; 4], [f64; 4]) = (
    [f64::INFINITY, f64::INFINITY, f64::INFINITY, 0.0],
    [f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY, 0.0],
);

/// Grows the box [lo, hi] to hold `key`.
fn grow_box(lo: &mut [f64; 4], hi: &mut [f64; 4], key: &[f64; 3]) {
    for axis in 0..3 {
        lo[axis] = lo[axis].min(key[axis]);
        hi[axis] = hi[axis].max(key[axis]);
    }
}

/// A candidate neighbour: squared distance and index (results are in
/// that order, ties to the lower index).
#[derive(Clone, Copy, Debug)]
struct Candidate(f64, u32);

/// The `k` points nearest to `q` in a distance `exact(i)` that the index's
/// own distance never exceeds (a car's steering length over the Euclidean
/// distance of the reference points), into `out` as (squared exact
/// distance, index), nearest first, ties to the lower index.
///
/// The m nearest by the index's distance (m growing ×4) hold the k nearest
/// by `exact` once the k-th exact distance found is no more than the m-th
/// index distance: every point left out is at least that far by the index,
/// so at least that far exactly.
pub fn k_nearest_bounded(
    index: &mut KdTree,
    q: &[f64; 3],
    k: usize,
    out: &mut Vec<(f64, u32)>,
    exact: impl Fn(usize) -> f64,
) {
    let n = index.len();
    let mut m = (2 * k).max(8).min(n);
    let mut candidates = Vec::new();
    loop {
        index.k_nearest(q, m, &mut candidates);
        out.clear();
        out.extend(candidates.iter().map(|&(_, i)| {
            let d = exact(i as usize);
            (d * d, i)
        }));
        out.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        out.truncate(k);
        let reach2 = candidates.last().map_or(0.0, |&(d2, _)| d2);
        let kth2 = if out.len() == k {
            out[k - 1].0
        } else {
            f64::INFINITY
        };
        if m >= n || kth2 <= reach2 {
            return;
        }
        m = (m * 4).min(n);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;
    use proptest::prelude::*;

    /// The k nearest by a scan of every point, ties to the lower index.
    fn brute(tree: &KdTree, q: &[f64; 3], k: usize) -> Vec<(f64, u32)> {
        let mut all: Vec<(f64, u32)> = (0..tree.len())
            .map(|i| (tree.distance2(q, &tree.point(i)), i as u32))
            .collect();
        all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        all.truncate(k);
        all
    }

    proptest! {
        #[test]
        fn k_nearest_agrees_with_a_scan(
            seed in 0u64..1_000_000,
            n in 1usize..400,
            k in 1usize..20,
            dims in 2usize..=3,
            period in prop_oneof![Just(0.0), 0.5f64..20.0],
            // Coarse coordinates give many equal distances (ties).
            coarse in any::<bool>(),
        ) {
            let mut rng = SplitMix64::new(seed);
            let mut tree = KdTree::new(dims, period);
            let wrap = if dims == 3 && period > 0.0 { period } else { 10.0 };
            let draw = |rng: &mut SplitMix64, hi: f64| {
                let x = rng.range(0.0, hi);
                if coarse { (x * 2.0).floor() / 2.0 } else { x }
            };
            for _ in 0..n {
                let key = [draw(&mut rng, 10.0), draw(&mut rng, 10.0), draw(&mut rng, wrap) % wrap];
                tree.insert(key);
            }
            let mut out = Vec::new();
            for _ in 0..20 {
                let q = [draw(&mut rng, 10.0), draw(&mut rng, 10.0), draw(&mut rng, wrap) % wrap];
                tree.k_nearest(&q, k, &mut out);
                let expected = brute(&tree, &q, k);
                prop_assert_eq!(&out, &expected);
                let nearest = tree.nearest(&q);
                prop_assert_eq!(nearest, Some((expected[0].1 as usize, expected[0].0)));
            }
        }
    }

    proptest! {
        /// For a car: the k nearest by steering length (Dubins: either
        /// way), found through the Euclidean index, are those of a scan.
        #[test]
        fn k_nearest_by_steering_length_agrees_with_a_scan(
            seed in 0u64..1_000_000,
            n in 1usize..300,
            k in 1usize..20,
            radius in 0.3f64..5.0,
            dubins in any::<bool>(),
            to_q in any::<bool>(),
        ) {
            use crate::geometry::Config;
            use crate::geometry::steer::{Model, Steering};
            let model = if dubins { Model::Dubins } else { Model::ReedsShepp };
            let steering = Steering::new(model, radius);
            let mut rng = SplitMix64::new(seed);
            let mut draw = || Config::new(rng.range(0.0, 20.0), rng.range(0.0, 20.0), rng.range(0.0, std::f64::consts::TAU));
            let states: Vec<Config> = (0..n).map(|_| draw()).collect();
            let mut tree = KdTree::new(3, 0.0);
            for c in &states {
                tree.insert([c.x, c.y, 0.0]);
            }
            let mut out = Vec::new();
            for _ in 0..10 {
                let q = draw();
                let exact = |i: usize| if to_q { steering.distance(states[i], q) } else { steering.distance(q, states[i]) };
                k_nearest_bounded(&mut tree, &[q.x, q.y, 0.0], k, &mut out, exact);
                let mut all: Vec<(f64, u32)> = (0..n).map(|i| (exact(i).powi(2), i as u32)).collect();
                all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                all.truncate(k);
                prop_assert_eq!(&out, &all);
            }
        }
    }

    #[test]
    fn the_nearest_across_the_wrap_is_found() {
        let tau = std::f64::consts::TAU;
        let mut tree = KdTree::new(3, tau);
        tree.insert([0.0, 0.0, 3.0]);
        tree.insert([0.0, 0.0, tau - 0.1]);
        // From θ = 0.05 the point at 2π − 0.1 is 0.15 away, not 6.13.
        let (i, d2) = tree.nearest(&[0.0, 0.0, 0.05]).expect("a point");
        assert_eq!(i, 1);
        assert!((d2 - 0.15f64.powi(2)).abs() < 1e-12);
    }

    #[test]
    fn a_leaf_of_many_equal_points_grows_and_splits() {
        let mut tree = KdTree::new(3, 4.0);
        for i in 0..40 {
            tree.insert([1.0, 2.0, 3.0]);
            if i % 7 == 0 {
                tree.insert([1.0 + f64::from(i) * 0.1, 2.0, 0.5]);
            }
        }
        let mut out = Vec::new();
        for q in [[1.0, 2.0, 3.0], [1.5, 2.0, 0.4], [0.0, 0.0, 3.9]] {
            tree.k_nearest(&q, 20, &mut out);
            let expected = brute(&tree, &q, 20);
            assert_eq!(out, expected);
            assert_eq!(
                tree.nearest(&q),
                Some((expected[0].1 as usize, expected[0].0))
            );
        }
    }

    #[test]
    fn a_chain_of_collinear_points_is_searched_without_recursion() {
        let mut tree = KdTree::new(2, 0.0);
        for i in 0..5_000 {
            tree.insert([f64::from(i), f64::from(i), 0.0]);
        }
        assert_eq!(tree.nearest(&[1e9, 1e9, 0.0]).map(|n| n.0), Some(4_999));
    }
}
