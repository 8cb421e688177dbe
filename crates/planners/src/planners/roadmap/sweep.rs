//! Visibility among the arrangement's points by a rotational plane sweep
//! (Lee's algorithm): O(n log n + n·k) per node, k the segments crossing a
//! ray (a handful in scattered worlds, at most n).
//!
//! Around a node `v`, the other points are visited in counter-clockwise
//! order (then by distance), except those hidden between two boundary
//! pieces that face away from `v` (neither visible nor events); a sorted
//! list ([`Status`]) holds the segments
//! that cross the current ray, ordered by their distance along it. The
//! segments of the arrangement never cross, so that order does not change
//! while a segment is in the list. At each ray (the points exactly on it,
//! nearest first):
//! 1. the segments ending on the ray and lying clockwise of it leave the
//!    list;
//! 2. the nearest segment left in the list crosses the ray properly: every
//!    point beyond it is hidden;
//! 3. the points are walked outwards, as a straight motion from `v` would
//!    meet them ([`Chain`]): it may not enter a polygon's interior at `v`,
//!    at a point it passes or at the point it reaches, nor pass from one
//!    side of the walls to the other;
//! 4. the segments starting on the ray and lying counter-clockwise of it
//!    enter the list.

use std::cmp::Ordering;

use super::arrangement::{Arrangement, Sides, Way, ccw_cmp, orient, upper_half};
use crate::geometry::{Point, Vector};

/// A visibility edge between points `a < b`, and the sectors it links:
/// pairs (sector at `a`, sector at `b`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Visible {
    pub a: u32,
    pub b: u32,
    pub links: Vec<(u32, u32)>,
}

/// A straight motion from `v` in direction `d`, met point by point.
pub struct Chain {
    /// Per starting sector at `v`: the sides still open.
    starts: Vec<(u32, Sides)>,
    d: Vector,
    blocked: bool,
}

impl Chain {
    pub fn new(arr: &Arrangement, v: u32, d: Vector) -> Self {
        let n = arr.sector_count(v);
        let starts = match arr.classify(v, d) {
            Way::Sector(m) => vec![(m as u32, Sides::BOTH)],
            Way::Ray(i) => vec![
                (
                    i as u32,
                    Sides {
                        left: true,
                        right: false,
                    },
                ),
                (
                    ((i + n - 1) % n) as u32,
                    Sides {
                        left: false,
                        right: true,
                    },
                ),
            ],
        };
        Chain {
            starts,
            d,
            blocked: arr.into_interior(v, d),
        }
    }

    /// Reaching point `p`: the sector pairs linked, if `p` can be reached
    /// (and `wanted`); then moves on past `p` (which may block the chain).
    pub fn reach(&mut self, arr: &Arrangement, p: u32, wanted: bool) -> Vec<(u32, u32)> {
        let mut links = Vec::new();
        if self.blocked {
            return links;
        }
        if arr.into_interior(p, -self.d) {
            self.blocked = true;
            return links;
        }
        if wanted {
            let n = arr.sector_count(p);
            let (left, right) = match arr.classify(p, -self.d) {
                Way::Sector(m) => (m, m),
                // Arriving along ray i: the left of the motion is the
                // sector clockwise of the ray.
                Way::Ray(i) => ((i + n - 1) % n, i),
            };
            for &(s, sides) in &self.starts {
                if sides.left {
                    links.push((s, left as u32));
                }
                if sides.right {
                    links.push((s, right as u32));
                }
            }
            links.sort_unstable();
            links.dedup();
        }
        if arr.into_interior(p, self.d) {
            self.blocked = true;
        } else {
            for s in self.starts.iter_mut() {
                s.1 = s.1.pass(arr, p, self.d);
            }
            self.blocked = self.starts.iter().all(|s| !s.1.open());
        }
        links
    }

    pub fn block(&mut self) {
        self.blocked = true;
    }

    pub fn is_blocked(&self) -> bool {
        self.blocked
    }
}

// ----------------------------------------------------------------- status

const NIL: u32 = u32::MAX;

/// The segments crossing the ray, nearest first, ordered by a comparator
/// given to each call: a sorted `Vec`. Along a ray through a world of
/// scattered obstacles only a handful of segments cross it, where binary
/// search and a short move beat a balanced tree by far; an update costs
/// O(log k) comparisons and a move of O(k) ids, k the segments crossing.
struct Status {
    items: Vec<u32>,
}

impl Status {
    fn new(n: usize) -> Self {
        Status {
            items: Vec::with_capacity(n.min(1024)),
        }
    }

    /// Where `x` goes: after the prefix that orders before it.
    fn position(&self, x: u32, cmp: &impl Fn(u32, u32) -> Ordering) -> usize {
        self.items.partition_point(|&e| cmp(e, x) == Ordering::Less)
    }

    fn insert(&mut self, x: u32, cmp: &impl Fn(u32, u32) -> Ordering) {
        let i = self.position(x, cmp);
        self.items.insert(i, x);
    }

    /// Removes `x`, found by its id: a scan of the k ids costs no more than
    /// the move that follows, and no geometry (nor rounding) is involved.
    fn remove(&mut self, x: u32) {
        if let Some(i) = self.items.iter().position(|&e| e == x) {
            self.items.remove(i);
        }
    }

    fn first(&self) -> Option<u32> {
        self.items.first().copied()
    }

    fn clear(&mut self) {
        self.items.clear();
    }
}

// ------------------------------------------------------------------ sweep

/// Reusable buffers of one sweeping thread.
pub struct SweepBuffers {
    keyed: Vec<(u64, u32)>,
    group_of: Vec<u32>,
    groups: Vec<(usize, usize)>,
    /// The segments that may block: (segment, group of its first end,
    /// group of its last end).
    blocking: Vec<(u32, u32, u32)>,
    order: Vec<u32>,
    /// Per group, the segments entering the list there (`enter[enter_at[g]
    /// ..enter_at[g + 1]]`), and likewise those leaving it.
    enter_at: Vec<u32>,
    enter: Vec<u32>,
    leave_at: Vec<u32>,
    leave: Vec<u32>,
    /// Per segment: its end points and `(a, b - a)`, contiguous for the
    /// comparisons of the list.
    lines: Vec<Line>,
    /// Per point: its two boundary pieces, when it has exactly two and
    /// neither is a wall (`[NIL, NIL]` otherwise).
    pieces: Vec<[u32; 2]>,
    /// Per segment: whether it faces away from the swept node.
    back: Vec<bool>,
    status: Status,
}

/// A segment's ends and the vector along it, as [`ray_t`] reads them.
#[derive(Clone, Copy)]
struct Line {
    a: u32,
    b: u32,
    pa: Point,
    ab: Vector,
}

impl SweepBuffers {
    pub fn new(arr: &Arrangement) -> Self {
        SweepBuffers {
            keyed: Vec::with_capacity(arr.points.len()),
            group_of: Vec::with_capacity(arr.points.len()),
            groups: Vec::with_capacity(arr.points.len()),
            blocking: Vec::with_capacity(arr.segs.len()),
            order: Vec::with_capacity(arr.points.len()),
            enter_at: Vec::with_capacity(arr.points.len() + 1),
            enter: Vec::with_capacity(arr.segs.len()),
            leave_at: Vec::with_capacity(arr.points.len() + 1),
            leave: Vec::with_capacity(arr.segs.len()),
            lines: arr
                .segs
                .iter()
                .map(|g| {
                    let (pa, pb) = (arr.points[g.a as usize], arr.points[g.b as usize]);
                    Line {
                        a: g.a,
                        b: g.b,
                        pa,
                        ab: pb - pa,
                    }
                })
                .collect(),
            pieces: arr
                .incident
                .iter()
                .map(|inc| match inc[..] {
                    [s, t] if !arr.segs[s as usize].wall && !arr.segs[t as usize].wall => [s, t],
                    _ => [NIL, NIL],
                })
                .collect(),
            back: Vec::with_capacity(arr.segs.len()),
            status: Status::new(arr.segs.len()),
        }
    }
}

/// Buckets the segments by group: `at[g]..at[g + 1]` indexes `out` for the
/// segments whose `group(s)` is `g` (in increasing segment order).
fn bucket(
    groups: usize,
    segs: impl Iterator<Item = (u32, u32)> + Clone,
    at: &mut Vec<u32>,
    out: &mut Vec<u32>,
) {
    at.clear();
    at.resize(groups + 1, 0);
    for (_, g) in segs.clone() {
        at[g as usize + 1] += 1;
    }
    for g in 0..groups {
        at[g + 1] += at[g];
    }
    out.clear();
    out.resize(at[groups] as usize, 0);
    // Fill each bucket from its start, which moves `at[g]` to the start of
    // bucket `g + 1`; then shift the starts back into place.
    for (s, g) in segs {
        out[at[g as usize] as usize] = s;
        at[g as usize] += 1;
    }
    at.copy_within(0..groups, 1);
    at[0] = 0;
}

/// Where segment `s` meets the ray `pv + t·d`, as `t`.
fn ray_t(arr: &Arrangement, s: u32, pv: Point, d: Vector) -> f64 {
    let seg = arr.segs[s as usize];
    let (a, b) = (arr.points[seg.a as usize], arr.points[seg.b as usize]);
    line_t(a, b - a, pv, d)
}

/// Where the line `a + u·ab` meets the ray `pv + t·d`, as `t`.
#[inline]
fn line_t(a: Point, ab: Vector, pv: Point, d: Vector) -> f64 {
    let den = d.perp(&ab);
    if den == 0.0 {
        return f64::INFINITY;
    }
    (a - pv).perp(&ab) / den
}

/// Inserts segment `x` in the list ordered by [`seg_cmp`] along the ray
/// `pv + t·d`: the distance of `x` is computed once, and [`seg_cmp`] itself
/// is called only for segments sharing an end with `x` (the only case where
/// it does not compare distances).
#[allow(clippy::too_many_arguments)]
fn insert(
    arr: &Arrangement,
    status: &mut Status,
    lines: &[Line],
    pv: Point,
    d: Vector,
    after: bool,
    on_ray: impl Fn(u32) -> bool + Copy,
    x: u32,
) {
    let lx = lines[x as usize];
    // x's distance is nx / dx as line_t computes it.
    let (nx, dx) = ((lx.pa - pv).perp(&lx.ab), d.perp(&lx.ab));
    let cmp = |e: u32, x: u32| {
        if e == x {
            return Ordering::Equal;
        }
        let le = lines[e as usize];
        if le.a == lx.a || le.a == lx.b || le.b == lx.a || le.b == lx.b {
            return seg_cmp(arr, pv, d, after, on_ray, e, x);
        }
        let (ne, de) = ((le.pa - pv).perp(&le.ab), d.perp(&le.ab));
        if let Some(ord) = quotient_cmp(ne, de, nx, dx) {
            return ord;
        }
        line_t(le.pa, le.ab, pv, d)
            .total_cmp(&line_t(lx.pa, lx.ab, pv, d))
            .then(e.cmp(&x))
    };
    status.insert(x, &cmp);
}

/// Compares `ne / de` with `nx / dx` without dividing, when the products
/// decide it with a wide margin: the quotients then differ by far more than
/// their rounding, so `f64::total_cmp` of the rounded quotients agrees.
/// `None` when a term is zero (signed zeros, infinite quotients), the
/// margin is too thin or not a number.
#[inline]
fn quotient_cmp(ne: f64, de: f64, nx: f64, dx: f64) -> Option<Ordering> {
    if ne == 0.0 || de == 0.0 || nx == 0.0 || dx == 0.0 {
        return None;
    }
    let (p, q) = (ne * dx, nx * de);
    let gap = (p - q).abs();
    if gap.is_nan() || gap <= 1e-9 * (p.abs() + q.abs()) {
        return None;
    }
    // ne/de < nx/dx  ⇔  ne·dx < nx·de when de·dx > 0, reversed otherwise.
    let less = (p < q) == ((de > 0.0) == (dx > 0.0));
    Some(if less {
        Ordering::Less
    } else {
        Ordering::Greater
    })
}

/// Orders the segments crossing the ray `pv + t·d` by distance; two
/// segments meeting at a point of the ray (`on_ray`) are ordered as they
/// are just before the ray (`after == false`) or just after it.
fn seg_cmp(
    arr: &Arrangement,
    pv: Point,
    d: Vector,
    after: bool,
    on_ray: impl Fn(u32) -> bool,
    s1: u32,
    s2: u32,
) -> Ordering {
    if s1 == s2 {
        return Ordering::Equal;
    }
    let (g1, g2) = (arr.segs[s1 as usize], arr.segs[s2 as usize]);
    for p in [g1.a, g1.b] {
        if (p != g2.a && p != g2.b) || !on_ray(p) {
            continue;
        }
        let pp = arr.points[p as usize];
        let a = arr.points[if g1.a == p { g1.b } else { g1.a } as usize];
        let b = arr.points[if g2.a == p { g2.b } else { g2.a } as usize];
        let c = (a - pp).perp(&(b - pp));
        let ord = if c > 0.0 {
            Ordering::Less
        } else if c < 0.0 {
            Ordering::Greater
        } else {
            return s1.cmp(&s2);
        };
        return if after { ord.reverse() } else { ord };
    }
    ray_t(arr, s1, pv, d)
        .total_cmp(&ray_t(arr, s2, pv, d))
        .then(s1.cmp(&s2))
}

/// The visibility edges from node `v` to the nodes of higher index.
pub fn sweep(arr: &Arrangement, v: u32, buf: &mut SweepBuffers, out: &mut Vec<Visible>) {
    let pv = arr.points[v as usize];
    let x_axis = Vector::new(1.0, 0.0);
    let angle_cmp = |a: &u32, b: &u32| {
        let (wa, wb) = (arr.points[*a as usize] - pv, arr.points[*b as usize] - pv);
        ccw_cmp(x_axis, wa, wb).then_with(|| wa.norm_squared().total_cmp(&wb.norm_squared()))
    };
    // The polygon pieces facing away from v: v lies strictly on their
    // interior side. They never block first: a ray from v (outside every
    // interior) first crosses the boundary where it enters the union,
    // through a piece whose interior faces away from the ray's origin.
    buf.back.clear();
    buf.back.extend(
        arr.segs.iter().map(|g| {
            !g.wall && orient(arr.points[g.a as usize], arr.points[g.b as usize], pv) > 0.0
        }),
    );
    let back = &buf.back;
    // A point between two pieces facing away is hidden: v lies on the
    // interior side of both, so the direction from the point to v points
    // into the interior there (whether the corner is convex, flat or
    // reflex), and a motion from v arrives from the interior. The sweep
    // leaves it out: it is no event (its pieces never enter the list),
    // cannot be reached, and a ray through it was blocked before it, where
    // it entered the interior (a proper crossing or a point kept here).
    let hidden = |p: u32| {
        let [s, t] = buf.pieces[p as usize];
        s != NIL && back[s as usize] && back[t as usize]
    };
    // Sort by a pseudo-angle (monotone in the angle), then fix the order
    // exactly with an insertion pass (the sequence is nearly sorted).
    buf.keyed.clear();
    buf.keyed.extend(
        (0..arr.points.len() as u32)
            .filter(|&p| p != v && !hidden(p))
            .map(|p| {
                let w = arr.points[p as usize] - pv;
                let r = w.x.abs() + w.y.abs();
                let q = if r > 0.0 { w.x / r } else { 1.0 };
                // q runs 1 → −1 over the upper half plane, −1 → 1 over the lower.
                let key = if upper_half(w) { 1.0 - q } else { 3.0 + q };
                // The key is non-negative: its bits order as it does.
                (key.to_bits(), p)
            }),
    );
    // Equal keys (one direction) by distance, which keeps the insertion
    // pass linear on the many collinear points of axis-aligned worlds.
    let dist = |p: u32| (arr.points[p as usize] - pv).norm_squared();
    buf.keyed
        .sort_unstable_by(|a, b| a.0.cmp(&b.0).then_with(|| dist(a.1).total_cmp(&dist(b.1))));
    buf.order.clear();
    buf.order.extend(buf.keyed.iter().map(|k| k.1));
    let order = &mut buf.order;
    for i in 1..order.len() {
        let mut j = i;
        while j > 0 && angle_cmp(&order[j - 1], &order[j]) == Ordering::Greater {
            order.swap(j - 1, j);
            j -= 1;
        }
    }
    // Group the points by exact direction; each segment enters the list at
    // its counter-clockwise-first end's group and leaves at the other's
    // (one decision per segment, so rounding cannot make them disagree).
    let order = &buf.order;
    let group_of = &mut buf.group_of;
    group_of.clear();
    group_of.resize(arr.points.len(), u32::MAX);
    let groups = &mut buf.groups;
    groups.clear();
    let mut i = 0;
    while i < order.len() {
        let mut j = i + 1;
        while j < order.len()
            && ccw_cmp(
                x_axis,
                arr.points[order[i] as usize] - pv,
                arr.points[order[j] as usize] - pv,
            ) == Ordering::Equal
        {
            j += 1;
        }
        for &p in &order[i..j] {
            group_of[p as usize] = groups.len() as u32;
        }
        groups.push((i, j));
        i = j;
    }
    // The segments that may block, with the groups of their first and last
    // ends counter-clockwise as seen from v: decided once per sweep, so
    // rounding cannot make the entry and the exit disagree.
    let blocking = &mut buf.blocking;
    blocking.clear();
    for (s, g) in arr.segs.iter().enumerate() {
        if back[s] || g.a == v || g.b == v {
            continue;
        }
        let (a, b) = (arr.points[g.a as usize], arr.points[g.b as usize]);
        let o = (a - pv).perp(&(b - pv));
        let (f, l) = if o > 0.0 {
            (g.a, g.b)
        } else if o < 0.0 {
            (g.b, g.a)
        } else {
            continue;
        };
        let (gf, gl) = (group_of[f as usize], group_of[l as usize]);
        // Seen from v a segment spans less than half a turn, so one whose
        // first end comes later in the order than its last must cross the
        // x axis: its first end below it, its last above. Otherwise the
        // segment is collinear with v but for rounding (the sign of `o`
        // and the order of its ends disagree), and like an exactly
        // collinear one it blocks nothing properly: its ends are walked.
        let below = |p: u32| !upper_half(arr.points[p as usize] - pv);
        let crosses_x_axis = below(f) && !below(l);
        if gf > gl && !crosses_x_axis {
            continue;
        }
        if gf != gl {
            blocking.push((s as u32, gf, gl));
        }
    }
    let blocking = &*blocking;
    let group_of = &*group_of;
    // The segments entering and leaving the list, bucketed by group.
    bucket(
        groups.len(),
        blocking.iter().map(|&(s, gf, _)| (s, gf)),
        &mut buf.enter_at,
        &mut buf.enter,
    );
    bucket(
        groups.len(),
        blocking.iter().map(|&(s, _, gl)| (s, gl)),
        &mut buf.leave_at,
        &mut buf.leave,
    );
    let lines = &buf.lines;
    let status = &mut buf.status;
    status.clear();
    let on_first = |p: u32| group_of[p as usize] == 0;
    for &(s, gf, gl) in blocking {
        if gf > gl {
            insert(arr, status, lines, pv, x_axis, false, on_first, s);
        }
    }

    for (gi, &(i, j)) in groups.iter().enumerate() {
        let group = &order[i..j];
        let d = arr.points[group[0] as usize] - pv;
        let on_ray = |p: u32| group_of[p as usize] == gi as u32;
        // 1. Segments ending here (their last end) leave.
        for &s in &buf.leave[buf.leave_at[gi] as usize..buf.leave_at[gi + 1] as usize] {
            status.remove(s);
        }
        // 2. The nearest proper crossing.
        let t_min = status
            .first()
            .map_or(f64::INFINITY, |s| ray_t(arr, s, pv, d));
        // 3. Walk the points outwards (unless the nearest is hidden).
        let dd = d.norm_squared();
        let t_of = |p: u32| (arr.points[p as usize] - pv).dot(&d) / dd;
        let wanted_any = group.iter().any(|&p| p > v && arr.is_node[p as usize]);
        if arr.is_node[v as usize] && wanted_any && t_min >= t_of(group[0]) {
            let mut chain = Chain::new(arr, v, d);
            for &p in group {
                if t_min < t_of(p) {
                    chain.block();
                }
                if chain.is_blocked() {
                    break;
                }
                let wanted = p > v && arr.is_node[p as usize];
                let links = chain.reach(arr, p, wanted);
                if !links.is_empty() {
                    out.push(Visible { a: v, b: p, links });
                }
            }
        }
        // 4. Segments starting here (their first end) enter.
        for &s in &buf.enter[buf.enter_at[gi] as usize..buf.enter_at[gi + 1] as usize] {
            insert(arr, status, lines, pv, d, true, on_ray, s);
        }
    }
}

/// The same edges as [`sweep`] over all nodes, by testing every pair of
/// nodes against every segment and point: O(n³), for tests.
#[cfg(test)]
pub fn brute_force(arr: &Arrangement) -> Vec<Visible> {
    let n = arr.points.len() as u32;
    let mut out = Vec::new();
    for v in 0..n {
        if !arr.is_node[v as usize] {
            continue;
        }
        for w in v + 1..n {
            if !arr.is_node[w as usize] {
                continue;
            }
            let (pv, pw) = (arr.points[v as usize], arr.points[w as usize]);
            let d = pw - pv;
            let crossed = arr.segs.iter().any(|g| {
                if g.a == v || g.b == v || g.a == w || g.b == w {
                    return false;
                }
                let (a, b) = (arr.points[g.a as usize], arr.points[g.b as usize]);
                orient(pv, pw, a) * orient(pv, pw, b) < 0.0
                    && orient(a, b, pv) * orient(a, b, pw) < 0.0
            });
            if crossed {
                continue;
            }
            let mut between: Vec<(f64, u32)> = (0..n)
                .filter(|&p| p != v && p != w)
                .filter_map(|p| {
                    let q = arr.points[p as usize];
                    let t = (q - pv).dot(&d);
                    (orient(pv, pw, q) == 0.0 && t > 0.0 && t < d.norm_squared()).then_some((t, p))
                })
                .collect();
            between.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut chain = Chain::new(arr, v, d);
            for &(_, p) in &between {
                chain.reach(arr, p, false);
            }
            let links = chain.reach(arr, w, true);
            if !links.is_empty() {
                out.push(Visible { a: v, b: w, links });
            }
        }
    }
    out
}
