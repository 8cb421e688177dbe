//! The nearest-neighbour index of the sampling-based planners: a k-d tree
//! over the keys `(x, y)` or `(x, y, c·θ)` whose last axis may be periodic
//! (θ ∈ [0, 2π) scaled by the turn cost c, period 2π·c), so that distances
//! follow θ's wrap-around.
//!
//! # Structure
//! Points are stored in *leaves*; an internal node splits its points at a
//! value of one axis (points with a smaller coordinate lie left, a larger
//! one right, an equal one on either side). The tree is *built* balanced
//! over every point whenever their number has doubled since the last build
//! (from 16 points): each node splits at the median by position of the
//! axis of its points' widest spread (so both sides hold points, however
//! many are equal), down to leaves of at most [`LEAF`] points, and the
//! nodes are laid out depth first (a left child right after its parent).
//! Between builds a point is inserted into the leaf its coordinates lead
//! to (the boxes on the way grown); each leaf owns a fixed slot of [`SLOT`]
//! points in one array (slots in leaf order as built), so a leaf grows in
//! place, and a full one splits at its median in two (the right half in a
//! new slot, the two new nodes at the end). A build costs O(n log n) once
//! per doubling, O(log n) per insertion; a slot holds at least 8 points
//! (unless the tree holds fewer),
//! a node is one cache line of 64 bytes, so the tree's memory stays within
//! a constant factor of its points'. The walk uses an explicit stack, so a
//! degenerate insertion order (a chain of collinear extensions, or equal
//! points) costs time, never the call stack. Leaves make a query scan a few
//! short runs of points rather than visit one tree node per point; a leaf
//! holds a copy of its points' keys, in groups of four stored axis by axis
//! ([`Slot`]), so a scan reads a few cache lines and computes four
//! distances at a time, then offers its points one by one only if the
//! nearest of them is within the bound (one test per leaf rather than one
//! per point). On a processor with AVX2 the walk is compiled for it (four
//! lanes an instruction; the same operations, so the same results to the
//! bit). The compact layout (against the former tree of 96-byte
//! nodes grown by insertion alone, with a `Vec` per leaf) and a walk with
//! fewer unpredictable branches (the near child picked by index, a subtree
//! pushed by writing past the stack's top and moving the top only if it
//! is kept) take a fifth off the apartment rod's `rrt_connect` wall time
//! (BENCHMARKS.md, issue 22); the leaves' layout by axis and the AVX2
//! walk another tenth.
//!
//! # Queries and the wrap-around
//! The distance between keys is Euclidean with the periodic axis'
//! difference taken the shorter way round ([`KdTree::distance2`]). Each
//! node keeps the bounding box of its subtree's points (set when built,
//! grown on insertion);
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
//! lane as another (the query and the box given a fourth coordinate, 0),
//! two lanes per
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

/// The tag of a pending subtree on the walk's stack whose bound is only its
/// split plane's distance (its box not yet measured); node indices stay
/// below [`AXIS_SHIFT`]'s bit (asserted when a node is made).
const UNMEASURED: u32 = 1 << 31;

/// In an internal node's [`Node::b`], the split's axis sits above this bit
/// and the right child below.
const AXIS_SHIFT: u32 = 30;

/// In [`Node::a`], marks a leaf (its point count in the low bits).
const LEAF_BIT: u32 = 1 << 31;

/// The most points of a leaf as built (with the leaves scanned four
/// points at a time, 16 and slots of 32 beat 8 and 16, 12 and 24, 16 and
/// 24 or 24 and 48 on the apartment rod's `rrt_connect` and `prm`:
/// BENCHMARKS.md).
const LEAF: usize = 16;

/// The tree is built again whenever its points have doubled since the
/// last build, first at twice this many.
const REBUILT: usize = 8;

/// The room of a leaf's slot: a leaf grows by insertion up to this many
/// points, then splits in two.
const SLOT: usize = 32;

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
    /// Node 0 is the root (once a point exists); as built, depth first (a
    /// node's left child the node after it), then the nodes of later
    /// leaf splits.
    nodes: Vec<Node>,
    /// The leaves' points with copies of their keys: leaf slot `s` holds
    /// its points (as built, slots in leaf order).
    slots: Vec<Slot>,
    /// The number of points at the last build.
    built: usize,
    /// Per axis, 1 when the distance to a split plane along it is a lower
    /// bound of the distance to the points beyond, 0 for the periodic axis.
    plane: [f64; 3],
    /// The walk's pending subtrees and their lower bounds.
    stack: Vec<(u32, f64)>,
}

/// A node, one cache line: the box of its subtree's points (min and max
/// per axis; the third axis (0, 0) for 2-dimensional keys), and either its
/// split (value `split`; `a` the left child, `b` the right child and the
/// axis above [`AXIS_SHIFT`]) or its points (`a` = [`LEAF_BIT`] + their
/// count, `b` their slot).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct Node {
    lo: [f64; 3],
    hi: [f64; 3],
    split: f64,
    a: u32,
    b: u32,
}

/// A leaf's room: the keys of its points in groups of [`LANES`], each
/// group axis by axis (so that a scan computes a group's distances a few
/// instructions at a time, and a leaf of few points reads few cache lines),
/// and their indices; the entries past the leaf's count are
/// [`Slot::EMPTY`]'s (an infinite x, whose distance to any query is
/// infinite).
#[derive(Clone, Debug)]
#[repr(C, align(64))]
struct Slot {
    keys: [[[f64; LANES]; 3]; SLOT / LANES],
    index: [u32; SLOT],
}

impl Slot {
    const EMPTY: Slot = Slot {
        keys: [[[f64::INFINITY; LANES], [0.0; LANES], [0.0; LANES]]; SLOT / LANES],
        index: [u32::MAX; SLOT],
    };

    /// A slot holding `points` (at most [`SLOT`]).
    fn of(points: &[([f64; 3], u32)]) -> Slot {
        let mut slot = Slot::EMPTY;
        for (i, &(key, index)) in points.iter().enumerate() {
            slot.set(i, key, index);
        }
        slot
    }

    fn set(&mut self, i: usize, key: [f64; 3], index: u32) {
        let group = &mut self.keys[i / LANES];
        for (axis, lanes) in group.iter_mut().enumerate() {
            lanes[i % LANES] = key[axis];
        }
        self.index[i] = index;
    }

    fn get(&self, i: usize) -> ([f64; 3], u32) {
        let [x, y, t] = &self.keys[i / LANES];
        let j = i % LANES;
        ([x[j], y[j], t[j]], self.index[i])
    }
}

/// The distances a leaf scan computes together: its count is rounded up to
/// a multiple of this.
const LANES: usize = 4;

impl Node {
    fn leaf(points: &[([f64; 3], u32)], slot: usize) -> Node {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for (key, _) in points {
            grow_box(&mut lo, &mut hi, key);
        }
        Node {
            lo,
            hi,
            split: 0.0,
            a: LEAF_BIT | points.len() as u32,
            b: slot as u32,
        }
    }
}

/// The axis of the widest spread of the box [lo, hi] among the first
/// `dims` (the first of equal ones).
fn widest(lo: &[f64; 3], hi: &[f64; 3], dims: usize) -> usize {
    let mut axis = 0;
    for a in 1..dims {
        if hi[a] - lo[a] > hi[axis] - lo[axis] {
            axis = a;
        }
    }
    axis
}

/// Splits `points` (at least 2) at the median by position along `axis`:
/// returns the split value, every point before the median no larger and
/// every point from it no smaller (both halves hold points, whatever the
/// equal values).
fn median_split(points: &mut [([f64; 3], u32)], axis: usize) -> (usize, f64) {
    let mid = points.len() / 2;
    points.select_nth_unstable_by(mid, |a, b| a.0[axis].total_cmp(&b.0[axis]));
    (mid, points[mid].0[axis])
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
            slots: Vec::new(),
            built: 0,
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

    /// Adds `key` (its periodic coordinate in [0, period); its third one
    /// ignored for 2 axes); returns its index, the number of points before
    /// it.
    pub fn insert(&mut self, mut key: [f64; 3]) -> usize {
        if self.dims == 2 {
            key[2] = 0.0;
        }
        let index = self.keys.len();
        self.keys.push(key);
        if self.nodes.is_empty() || self.keys.len() >= 2 * self.built.max(REBUILT) {
            self.build();
            return index;
        }
        let mut node = 0usize;
        loop {
            let n = &mut self.nodes[node];
            grow_box(&mut n.lo, &mut n.hi, &key);
            if n.a >= LEAF_BIT {
                break;
            }
            let axis = (n.b >> AXIS_SHIFT) as usize;
            node = if key[axis] >= n.split {
                (n.b & !(3 << AXIS_SHIFT)) as usize
            } else {
                n.a as usize
            };
        }
        let n = self.nodes[node];
        let count = (n.a & !LEAF_BIT) as usize;
        let slot = n.b as usize;
        if count < SLOT {
            self.slots[slot].set(count, key, index as u32);
            self.nodes[node].a += 1;
            return index;
        }
        // A full leaf: its points and the new one split at their median
        // along the widest axis of their box (the node's, grown), the left
        // half in its slot, the right half in a new one.
        let mut points = [(key, index as u32); SLOT + 1];
        for (i, point) in points[..SLOT].iter_mut().enumerate() {
            *point = self.slots[slot].get(i);
        }
        let axis = widest(&n.lo, &n.hi, self.dims);
        let (mid, split) = median_split(&mut points, axis);
        let right_slot = self.slots.len();
        self.slots[slot] = Slot::of(&points[..mid]);
        self.slots.push(Slot::of(&points[mid..]));
        let left = self.nodes.len();
        assert!(left + 1 < 1 << AXIS_SHIFT, "fewer than 2³⁰ nodes");
        self.nodes.push(Node::leaf(&points[..mid], slot));
        self.nodes.push(Node::leaf(&points[mid..], right_slot));
        let n = &mut self.nodes[node];
        n.split = split;
        n.a = left as u32;
        n.b = (left + 1) as u32 | (axis as u32) << AXIS_SHIFT;
        index
    }

    /// Builds the tree again over every point: balanced, depth first, each
    /// leaf at most [`LEAF`] points in the next slot.
    fn build(&mut self) {
        let n = self.keys.len();
        let mut points: Vec<([f64; 3], u32)> = self
            .keys
            .iter()
            .enumerate()
            .map(|(i, &key)| (key, i as u32))
            .collect();
        self.nodes.clear();
        self.slots.clear();
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for key in &self.keys {
            grow_box(&mut lo, &mut hi, key);
        }
        self.build_range(&mut points, lo, hi);
        assert!(self.nodes.len() < 1 << AXIS_SHIFT, "fewer than 2³⁰ nodes");
        self.built = n;
    }

    /// Adds the subtree of `points` (at least one), depth first, and
    /// returns its root. `lo`, `hi` hold the points (the parent's box cut
    /// at its split: it chooses the axis); each leaf's box is its points',
    /// each internal node's its children's.
    fn build_range(&mut self, points: &mut [([f64; 3], u32)], lo: [f64; 3], hi: [f64; 3]) -> u32 {
        let id = self.nodes.len();
        if points.len() <= LEAF {
            let slot = self.slots.len();
            self.slots.push(Slot::of(points));
            self.nodes.push(Node::leaf(points, slot));
            return id as u32;
        }
        self.nodes.push(Node {
            lo: [0.0; 3],
            hi: [0.0; 3],
            split: 0.0,
            a: 0,
            b: 0,
        });
        let axis = widest(&lo, &hi, self.dims);
        let (mid, split) = median_split(points, axis);
        let (left_points, right_points) = points.split_at_mut(mid);
        let (mut left_hi, mut right_lo) = (hi, lo);
        left_hi[axis] = split;
        right_lo[axis] = split;
        let left = self.build_range(left_points, lo, left_hi) as usize;
        let right = self.build_range(right_points, right_lo, hi);
        let (l, r) = (self.nodes[left], self.nodes[right as usize]);
        let n = &mut self.nodes[id];
        for a in 0..3 {
            n.lo[a] = l.lo[a].min(r.lo[a]);
            n.hi[a] = l.hi[a].max(r.hi[a]);
        }
        n.split = split;
        n.a = left as u32;
        n.b = right | (axis as u32) << AXIS_SHIFT;
        id as u32
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
        let mut best = Best(Candidate(f64::INFINITY, u32::MAX));
        self.walk(q, &mut best);
        let Best(best) = best;
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
        self.walk(
            q,
            &mut KBest {
                k,
                out,
                worst: f64::INFINITY,
            },
        );
    }

    /// The walk both queries share: depth first, the query's side of each
    /// split first, skipping every subtree whose box is farther than the
    /// bound. `visit` sees each point reached as a candidate and returns
    /// the bound after it (the squared distance beyond which nothing is
    /// wanted).
    fn walk(&mut self, q: &[f64; 3], visit: &mut impl Visit) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: this processor has AVX2 (checked just above).
            return unsafe { self.walk_avx2(q, visit) };
        }
        self.walk_body(q, visit)
    }

    /// [`KdTree::walk`] compiled for AVX2: the same operations (no fused
    /// multiply-adds), four lanes at a time.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn walk_avx2(&mut self, q: &[f64; 3], visit: &mut impl Visit) {
        self.walk_body(q, visit)
    }

    #[inline(always)]
    fn walk_body(&mut self, q: &[f64; 3], visit: &mut impl Visit) {
        let mut q = *q;
        if self.dims == 2 {
            q[2] = 0.0;
        }
        let wrap = self.wrap;
        let wraps = self.wraps;
        let q4 = [q[0], q[1], q[2], 0.0];
        let plane = self.plane;
        let nodes = &self.nodes[..];
        // The pending subtrees, `stack[..top]`: pushed by writing past the
        // top and moving the top only if kept (no branch); a node is
        // pushed at most once, so the node count bounds them.
        let mut stack = std::mem::take(&mut self.stack);
        if stack.len() < nodes.len() {
            stack.resize(nodes.len(), (0, 0.0));
        }
        let mut top = 0;
        let mut limit = f64::INFINITY;
        let mut node = 0u32;
        // Internal node `n`'s split axis, then its near and far children
        // for the query.
        let split = |n: &Node| {
            let axis = (n.b >> AXIS_SHIFT) as usize;
            let children = [n.a, n.b & !(3 << AXIS_SHIFT)];
            let side = usize::from(q[axis] >= n.split);
            (axis, children[side], children[1 - side])
        };
        // The first descent, before any candidate: nothing is pruned yet,
        // so each far side is pushed with the distance to its split plane
        // and its box is measured only if that bound is within the bound
        // when it is popped (most are beyond it by then).
        loop {
            let n = &nodes[node as usize];
            if n.a >= LEAF_BIT {
                break;
            }
            let (axis, near, far) = split(n);
            let d = q[axis] - n.split;
            stack[top] = (far | UNMEASURED, d * d * plane[axis]);
            top += 1;
            node = near;
        }
        // Whether `node`'s box was measured against the bound (popped, or
        // the first leaf, which nothing bounds yet).
        let mut measured = true;
        loop {
            let n = &nodes[node as usize];
            if n.a < LEAF_BIT {
                let (axis, near, far) = split(n);
                let d = q[axis] - n.split;
                if d * d * plane[axis] <= limit {
                    let f = &nodes[far as usize];
                    let g = gap2(&q4, &f.lo, &f.hi, &wraps);
                    stack[top] = (far, g);
                    top += usize::from(g <= limit);
                }
                node = near;
                measured = false;
                continue;
            }
            // A leaf reached below a popped subtree may lie beyond the
            // bound: its box is measured before its points.
            if measured || gap2(&q4, &n.lo, &n.hi, &wraps) <= limit {
                let slot = &self.slots[n.b as usize];
                let count = (n.a & !LEAF_BIT) as usize;
                let (d, nearest) = slot_distances(slot, count, &q, wrap);
                // One test per leaf; its points are offered only if one
                // of them may be.
                if nearest <= limit {
                    for (&d, &p) in d[..count].iter().zip(&slot.index) {
                        if d <= limit {
                            limit = visit.visit(Candidate(d, p));
                        }
                    }
                }
            }
            loop {
                if top == 0 {
                    self.stack = stack;
                    return;
                }
                top -= 1;
                let (next, bound) = stack[top];
                if bound <= limit {
                    node = next & !UNMEASURED;
                    if next & UNMEASURED != 0 {
                        let n = &nodes[node as usize];
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

/// The squared distances ([`distance2`]) from `q` to the first
/// `count` points of `slot` (and to a few [`Slot::EMPTY`] entries after
/// them, up to a multiple of [`LANES`]: infinite), with the smallest.
#[inline(always)]
fn slot_distances(slot: &Slot, count: usize, q: &[f64; 3], wrap: f64) -> ([f64; SLOT], f64) {
    let mut d = [f64::INFINITY; SLOT];
    let mut nearest = [f64::INFINITY; LANES];
    let groups = count.div_ceil(LANES);
    for ([x, y, t], out) in slot.keys[..groups].iter().zip(d.chunks_exact_mut(LANES)) {
        for j in 0..LANES {
            out[j] = distance2(q, &[x[j], y[j], t[j]], wrap);
            nearest[j] = min(nearest[j], out[j]);
        }
    }
    (d, nearest.into_iter().fold(f64::INFINITY, min))
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
fn gap2(q: &[f64; 4], lo: &[f64; 3], hi: &[f64; 3], wraps: &[f64; 4]) -> f64 {
    let lo = [lo[0], lo[1], lo[2], 0.0];
    let hi = [hi[0], hi[1], hi[2], 0.0];
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

/// Grows the box [lo, hi] to hold `key`.
fn grow_box(lo: &mut [f64; 3], hi: &mut [f64; 3], key: &[f64; 3]) {
    for axis in 0..3 {
        lo[axis] = lo[axis].min(key[axis]);
        hi[axis] = hi[axis].max(key[axis]);
    }
}

/// A candidate neighbour: squared distance and index (results are in
/// that order, ties to the lower index).
#[derive(Clone, Copy, Debug)]
struct Candidate(f64, u32);

/// What a walk keeps of the candidates it offers (a trait rather than a
/// closure, so that its method is inlined into each compilation of the
/// walk).
trait Visit {
    /// Sees a candidate no farther than the bound; returns the bound after
    /// it (the squared distance beyond which nothing is wanted).
    fn visit(&mut self, c: Candidate) -> f64;
}

/// The nearest candidate ([`KdTree::nearest`]).
struct Best(Candidate);

impl Visit for Best {
    #[inline(always)]
    fn visit(&mut self, c: Candidate) -> f64 {
        // The walk offers only candidates no farther than the best: one
        // nearer, or as near with a lower index, wins.
        if c.0 < self.0.0 || c.1 < self.0.1 {
            self.0 = c;
        }
        self.0.0
    }
}

/// The `k` nearest candidates ([`KdTree::k_nearest`]): `out` holds the
/// best so far in order, at most k (a candidate is inserted in place, k is
/// small; the worst dropped past k), `worst` the k-th's distance once
/// there are k.
struct KBest<'a> {
    k: usize,
    out: &'a mut Vec<(f64, u32)>,
    worst: f64,
}

impl Visit for KBest<'_> {
    #[inline(always)]
    fn visit(&mut self, c: Candidate) -> f64 {
        let (k, out) = (self.k, &mut *self.out);
        // The walk offers only candidates no farther than the worst.
        let before = |o: &(f64, u32)| c.0 < o.0 || (c.0 == o.0 && c.1 < o.1);
        if out.len() == k {
            if !before(&out[k - 1]) {
                return self.worst;
            }
            out.pop();
        }
        let mut i = out.len();
        while i > 0 && before(&out[i - 1]) {
            i -= 1;
        }
        out.insert(i, (c.0, c.1));
        if out.len() == k {
            self.worst = out[k - 1].0;
        }
        self.worst
    }
}

/// The `k` points nearest to `q` in a distance `exact(i)` that the index's
/// own distance never exceeds (a car's steering length over the Euclidean
/// distance of the reference points), into `out` as (squared exact
/// distance, index), nearest first, ties to the lower index.
///
/// The m nearest by the index's distance (m growing ×4) are taken in that
/// order and measured exactly until one is farther by the index than the
/// k-th exact distance found: it and every point after it, in this round or
/// beyond, are at least that far exactly, so the k found are the k nearest.
/// A round that measures all m without stopping so is followed by the next,
/// whose first m points are this round's (the m nearest by (distance,
/// index) are the first m of the 4m nearest), measured once. A point whose
/// `lower(i)`, a second lower bound of `exact(i)` (a car's heading change
/// at its turning radius), is already beyond the k-th exact distance is
/// passed over unmeasured. The bounds are compared with a relative slack of
/// 1e-9, so that a steering length rounded below the Euclidean distance of
/// its ends (a straight motion, to the last bit) cannot end the search early.
pub fn k_nearest_bounded(
    index: &mut KdTree,
    q: &[f64; 3],
    k: usize,
    out: &mut Vec<(f64, u32)>,
    lower: impl Fn(usize) -> f64,
    exact: impl Fn(usize) -> f64,
) {
    out.clear();
    let n = index.len();
    if k == 0 || n == 0 {
        return;
    }
    let mut m = (2 * k).max(8).min(n);
    let mut candidates = Vec::new();
    // The exact distances measured in earlier rounds, by position (NaN:
    // passed over).
    let mut measured: Vec<(u32, f64)> = Vec::new();
    let slack = 1.0 + 1e-9;
    loop {
        index.k_nearest(q, m, &mut candidates);
        let mut best = KBest {
            k,
            out: &mut *out,
            worst: f64::INFINITY,
        };
        best.out.clear();
        for (p, &(e2, i)) in candidates.iter().enumerate() {
            if e2 > best.worst * slack {
                return;
            }
            let d = match measured.get(p) {
                Some(&(j, d)) if j == i && !d.is_nan() => d,
                _ => {
                    let l = lower(i as usize);
                    if l * l > best.worst * slack {
                        continue;
                    }
                    let d = exact(i as usize);
                    if measured.len() <= p {
                        measured.resize(p + 1, (u32::MAX, f64::NAN));
                    }
                    measured[p] = (i, d);
                    d
                }
            };
            let d2 = d * d;
            if d2 <= best.worst {
                best.visit(Candidate(d2, i));
            }
        }
        let reach2 = candidates.last().map_or(0.0, |&(d2, _)| d2);
        if m >= n || best.worst * slack <= reach2 {
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
            // Every state on one line with one heading: each length is its
            // Euclidean distance, to rounding either way.
            line in any::<bool>(),
        ) {
            use crate::geometry::Config;
            use crate::geometry::steer::{Model, Steering};
            let model = if dubins { Model::Dubins } else { Model::ReedsShepp };
            let steering = Steering::new(model, radius);
            let mut rng = SplitMix64::new(seed);
            let mut draw = || {
                if line {
                    // On a grid of half steps: many states as far as others.
                    let t = rng.range(0.0, 40.0).floor() / 2.0;
                    Config::new(3.0 + 0.6 * t, 1.0 + 0.8 * t, 0.8f64.atan2(0.6))
                } else {
                    Config::new(rng.range(0.0, 20.0), rng.range(0.0, 20.0), rng.range(0.0, std::f64::consts::TAU))
                }
            };
            let states: Vec<Config> = (0..n).map(|_| draw()).collect();
            let mut tree = KdTree::new(3, 0.0);
            for c in &states {
                tree.insert([c.x, c.y, 0.0]);
            }
            let mut out = Vec::new();
            for _ in 0..10 {
                let q = draw();
                let exact = |i: usize| if to_q { steering.distance(states[i], q) } else { steering.distance(q, states[i]) };
                let turn = |i: usize| steering.turn_bound(states[i], q);
                k_nearest_bounded(&mut tree, &[q.x, q.y, 0.0], k, &mut out, turn, exact);
                let mut all: Vec<(f64, u32)> = (0..n).map(|i| (exact(i).powi(2), i as u32)).collect();
                all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                all.truncate(k);
                prop_assert_eq!(&out, &all);
            }
        }
    }

    proptest! {
        /// After every insertion, through the leaf splits of full slots
        /// and the rebuilds (the tree then holds 16, 32, 64, ... points),
        /// the queries agree with a scan and `insert` returns the count
        /// before it; few distinct coordinates give many equal points
        /// (one value: all equal), which fill and split slots too.
        #[test]
        fn queries_agree_with_a_scan_after_every_insertion(
            seed in 0u64..1_000_000,
            n in 1usize..300,
            k in 1usize..12,
            dims in 2usize..=3,
            period in prop_oneof![Just(0.0), 0.5f64..20.0],
            // 0: any coordinates; otherwise this many values per axis.
            values in prop_oneof![Just(0u32), 1u32..4],
        ) {
            let mut rng = SplitMix64::new(seed);
            let mut tree = KdTree::new(dims, period);
            let wrap = if dims == 3 && period > 0.0 { period } else { 10.0 };
            let draw = |rng: &mut SplitMix64, hi: f64| {
                let x = rng.range(0.0, 1.0);
                if values == 0 {
                    x * hi
                } else {
                    (x * f64::from(values)).floor() * hi / f64::from(values)
                }
            };
            let mut out = Vec::new();
            for i in 0..n {
                let key = [draw(&mut rng, 10.0), draw(&mut rng, 10.0), draw(&mut rng, wrap) % wrap];
                prop_assert_eq!(tree.insert(key), i);
                for _ in 0..2 {
                    let q = [rng.range(-1.0, 11.0), rng.range(-1.0, 11.0), rng.range(0.0, wrap)];
                    tree.k_nearest(&q, k, &mut out);
                    let expected = brute(&tree, &q, k);
                    prop_assert_eq!(&out, &expected);
                    prop_assert_eq!(tree.nearest(&q), Some((expected[0].1 as usize, expected[0].0)));
                    // The walk as compiled without AVX2 (the query above
                    // took the AVX2 one where the processor has it).
                    let mut plain = Vec::new();
                    tree.walk_body(&q, &mut KBest { k, out: &mut plain, worst: f64::INFINITY });
                    prop_assert_eq!(&plain, &expected);
                }
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
    fn many_equal_points_fill_and_split_their_slots() {
        let mut tree = KdTree::new(3, 4.0);
        // Enough equal points to fill a slot after the last build.
        for i in 0..(3 * SLOT) as i32 {
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
