//! Whether the edges of a closed ring meet, in O(n log n): the test that
//! makes a vertex list a simple polygon ([`super::normalize_simple_polygon`]).
//!
//! Two edges *meet* when they are not adjacent (do not share a vertex of
//! the ring) and come within `tol` of each other — the predicate of the
//! all-pairs test this replaces, [`all_pairs`], kept as the oracle of the
//! tests. Every pair reported is checked with that predicate; the work is
//! in bringing a meeting pair to it without looking at every pair:
//!
//! * **Crossing or touching edges**: a Shamos–Hoey sweep. Edges enter the
//!   sweep status at their left ends and leave at their right ends; two
//!   edges are compared whenever they become neighbours in it. Before the
//!   leftmost point where two edges meet, the status is a consistent order,
//!   and the two edges are neighbours just before it.
//! * **Edges that come within `tol` without touching**: their closest points
//!   are an end `v` of one and a point `q` of the other, `B`. When `B`
//!   slopes by at most 45° and spans `v`'s abscissa, `B` crosses `v`'s
//!   vertical within `√2·tol` of `v`, and so does every edge between them
//!   there (it would cross `v`–`q` otherwise, or end in between, within
//!   `tol` of `B`). So at each vertex the sweep walks the status up and
//!   down through the edges within `2·tol` of it. Steeper edges are found
//!   the same way by a second sweep with x and y exchanged; an edge `B`
//!   that does not span `v`'s abscissa (or ordinate) has an end within
//!   `(1 + √2)·tol` of `v`, found by hashing the vertices into cells of
//!   that size.
//!
//! Each step works on the sweep's neighbours or a cell's vertices, so the
//! whole is O(n log n) (the walks and cells hold O(1) edges while no two
//! meet, and stop at the first pair that does).

use std::collections::HashMap;

use super::sweep_status::SweepStatus;
use super::{Point, distance_segment_segment, orient};

/// How far a walk from a vertex goes at most, each way.
const MAX_WALK: usize = 64;

/// A pair of edges of the closed ring `ring` (edge `i` from `ring[i]` to
/// `ring[i + 1]`, the last back to the first) that meet, smaller index
/// first; `None` when no two edges meet.
///
/// # Arguments
/// * `ring` — the vertices, no two consecutive ones within `tol`;
/// * `tol` — the distance within which non-adjacent edges meet (> 0).
///
/// # Returns
/// The first meeting pair the sweeps come to (always the same for the
/// same input), not necessarily the first in index order.
pub(super) fn meeting_edges(ring: &[Point], tol: f64) -> Option<(usize, usize)> {
    if ring.len() < 4 {
        return None;
    }
    let meet = meets(ring, tol);
    let exchanged: Vec<Point> = ring.iter().map(|p| Point::new(p.y, p.x)).collect();
    sweep(ring, tol, &meet)
        .or_else(|| sweep(&exchanged, tol, &meet))
        .or_else(|| close_vertices(ring, tol, &meet))
        .map(|(i, j)| (i.min(j), i.max(j)))
}

/// Whether edges `i` and `j` of `ring` meet.
fn meets(ring: &[Point], tol: f64) -> impl Fn(usize, usize) -> bool + '_ {
    let n = ring.len();
    move |i, j| {
        let adjacent = i == j || (i + 1) % n == j || (j + 1) % n == i;
        !adjacent
            && distance_segment_segment(ring[i], ring[(i + 1) % n], ring[j], ring[(j + 1) % n])
                <= tol
    }
}

#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Event {
    /// An edge's left end: it enters the status.
    Enter,
    /// A vertex: a walk through the edges near it.
    Vertex,
    /// An edge's right end: it leaves.
    Leave,
}

/// One sweep from left to right over the ring's edges (in the frame of
/// `pts`, the ring or its mirror image; `meet` takes edge indices).
fn sweep(pts: &[Point], tol: f64, meet: &impl Fn(usize, usize) -> bool) -> Option<(usize, usize)> {
    let n = pts.len();
    let lex = |a: &Point, b: &Point| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y));
    // Each edge's ends, left (lexicographically smaller) first.
    let ends: Vec<(Point, Point)> = (0..n)
        .map(|e| {
            let (a, b) = (pts[e], pts[(e + 1) % n]);
            if lex(&a, &b).is_le() { (a, b) } else { (b, a) }
        })
        .collect();
    let mut events: Vec<(Point, Event, usize)> = Vec::with_capacity(3 * n);
    for (e, &(left, right)) in ends.iter().enumerate() {
        events.push((left, Event::Enter, e));
        events.push((pts[e], Event::Vertex, e));
        events.push((right, Event::Leave, e));
    }
    // At one point: edges enter, then the vertex is walked from, then edges
    // leave, so that edges meeting there are in the status together.
    events.sort_by(|a, b| lex(&a.0, &b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));

    let mut status = SweepStatus::new(n);
    for (p, event, e) in events {
        match event {
            Event::Enter => {
                status.insert(e, |t| above(ends[e], ends[t], e, t));
                for t in [status.prev(e), status.next(e)].into_iter().flatten() {
                    if meet(e, t) {
                        return Some((e, t));
                    }
                }
            }
            Event::Leave => {
                let (below, over) = (status.prev(e), status.next(e));
                status.remove(e);
                if let (Some(a), Some(b)) = (below, over)
                    && meet(a, b)
                {
                    return Some((a, b));
                }
            }
            Event::Vertex => {
                let incident = [(e + n - 1) % n, e];
                let (below, over) = status.locate(|t| orient(ends[t].0, ends[t].1, p) > 0.0);
                for (first, up) in [(over, true), (below, false)] {
                    let step = |t| if up { status.next(t) } else { status.prev(t) };
                    let mut at = first;
                    let mut last: Option<usize> = None;
                    for _ in 0..MAX_WALK {
                        let Some(t) = at else {
                            break;
                        };
                        if vertical_gap(ends[t], p) > 2.0 * tol {
                            break;
                        }
                        if let Some(&i) = incident.iter().find(|&&i| meet(i, t)) {
                            return Some((i, t));
                        }
                        // Edges bunched near one vertex meet each other.
                        if let Some(l) = last
                            && meet(l, t)
                        {
                            return Some((l, t));
                        }
                        last = Some(t);
                        at = step(t);
                    }
                }
            }
        }
    }
    None
}

/// Whether edge `s`, entering the status at its left end, goes above edge
/// `t` (both given left end first): by the side of `t`'s line its left end
/// is on, then its right end, then by index.
fn above(s: (Point, Point), t: (Point, Point), si: usize, ti: usize) -> bool {
    let o = orient(t.0, t.1, s.0);
    if o != 0.0 {
        return o > 0.0;
    }
    let o = orient(t.0, t.1, s.1);
    if o != 0.0 {
        return o > 0.0;
    }
    si > ti
}

/// The vertical distance from `p` to the edge `(left, right)` at `p`'s
/// abscissa (clamped to the edge's).
fn vertical_gap((left, right): (Point, Point), p: Point) -> f64 {
    if right.x == left.x {
        let (lo, hi) = (left.y.min(right.y), left.y.max(right.y));
        return (lo - p.y).max(p.y - hi).max(0.0);
    }
    let x = p.x.clamp(left.x, right.x);
    let y = left.y + (right.y - left.y) * ((x - left.x) / (right.x - left.x));
    (p.y - y).abs()
}

/// A meeting pair among the edges at two vertices within `(1 + √2)·tol` of
/// each other, found by hashing the vertices into cells of that size.
fn close_vertices(
    ring: &[Point],
    tol: f64,
    meet: &impl Fn(usize, usize) -> bool,
) -> Option<(usize, usize)> {
    let n = ring.len();
    let r = (1.0 + std::f64::consts::SQRT_2) * tol * (1.0 + 1e-9);
    if !(r > 0.0 && r.is_finite()) {
        return None;
    }
    let origin = ring
        .iter()
        .fold(Point::new(f64::INFINITY, f64::INFINITY), |o, p| {
            Point::new(o.x.min(p.x), o.y.min(p.y))
        });
    // Relative to the lowest corner, a cell index is at most
    // extent / (2.4·1e-10·extent): it fits.
    let cell = |p: &Point| {
        (
            ((p.x - origin.x) / r).floor() as i64,
            ((p.y - origin.y) / r).floor() as i64,
        )
    };
    let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (k, p) in ring.iter().enumerate() {
        let (cx, cy) = cell(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for &j in cells.get(&(cx + dx, cy + dy)).into_iter().flatten() {
                    if (ring[j] - p).norm() > r {
                        continue;
                    }
                    for a in [(k + n - 1) % n, k] {
                        for b in [(j + n - 1) % n, j] {
                            if meet(a, b) {
                                return Some((a, b));
                            }
                        }
                    }
                }
            }
        }
        cells.entry((cx, cy)).or_default().push(k);
    }
    None
}

/// The all-pairs test the sweeps replace: the first meeting pair in index
/// order.
#[cfg(test)]
pub(super) fn all_pairs(ring: &[Point], tol: f64) -> Option<(usize, usize)> {
    let n = ring.len();
    for i in 0..n {
        // Edges i and i+1 (and n-1 and 0) share a vertex.
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            let (c, d) = (ring[j], ring[(j + 1) % n]);
            if distance_segment_segment(a, b, c, d) <= tol {
                return Some((i, j));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn ring_of(v: &[(f64, f64)]) -> Vec<Point> {
        v.iter().map(|&(x, y)| Point::new(x, y)).collect()
    }

    /// The ring with consecutive duplicates dropped (as the sweep expects).
    fn without_repeats(mut ring: Vec<Point>) -> Vec<Point> {
        ring.dedup();
        while ring.len() > 1 && ring.first() == ring.last() {
            ring.pop();
        }
        ring
    }

    fn tol_of(ring: &[Point]) -> f64 {
        let (lo, hi) = ring.iter().fold(
            (
                Point::new(f64::INFINITY, f64::INFINITY),
                Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
            ),
            |(lo, hi), p| {
                (
                    Point::new(lo.x.min(p.x), lo.y.min(p.y)),
                    Point::new(hi.x.max(p.x), hi.y.max(p.y)),
                )
            },
        );
        1e-10 * (hi.x - lo.x).max(hi.y - lo.y)
    }

    /// Sweep and oracle agree on whether two edges meet, and the sweep's
    /// pair meets.
    fn agree(ring: &[Point]) -> Result<(), TestCaseError> {
        let tol = tol_of(ring);
        let n = ring.len();
        let found = meeting_edges(ring, tol);
        prop_assert_eq!(
            found.is_some(),
            all_pairs(ring, tol).is_some(),
            "{:?}",
            ring
        );
        if let Some((i, j)) = found {
            prop_assert!(i < j && j < n);
            prop_assert!(
                j != i + 1 && !(i == 0 && j == n - 1),
                "adjacent {} {}",
                i,
                j
            );
            let d =
                distance_segment_segment(ring[i], ring[(i + 1) % n], ring[j], ring[(j + 1) % n]);
            prop_assert!(d <= tol, "edges {} and {} are {} apart", i, j, d);
        }
        Ok(())
    }

    #[test]
    fn crossings_touchings_and_near_misses() {
        // A bow tie.
        let ring = ring_of(&[(0.0, 0.0), (2.0, 2.0), (2.0, 0.0), (0.0, 2.0)]);
        assert_eq!(meeting_edges(&ring, tol_of(&ring)), Some((0, 2)));
        // A vertex on a vertical edge, and a hair (1e-13) off it: the
        // oracle's tolerance (2e-10 here) counts both as touching.
        for dx in [0.0, 1e-13, -1e-13] {
            let ring = ring_of(&[
                (0.0, 0.0),
                (2.0, 0.0),
                (2.0, 2.0),
                (1.0, 2.0),
                (2.0 + dx, 1.0),
                (0.0, 2.0),
            ]);
            let tol = tol_of(&ring);
            assert!(all_pairs(&ring, tol).is_some());
            assert!(meeting_edges(&ring, tol).is_some(), "dx = {dx}");
        }
        // Two vertices a hair apart, their edges leaving in opposite
        // directions (no edge spans the other's abscissa).
        let ring = ring_of(&[
            (0.0, 0.0),
            (4.0, 0.0),
            (4.0, 4.0),
            (2.0 + 1e-13, 2.0),
            (3.0, 3.0),
            (2.0, 2.0),
            (0.0, 4.0),
        ]);
        let tol = tol_of(&ring);
        assert!(all_pairs(&ring, tol).is_some());
        assert!(meeting_edges(&ring, tol).is_some());
        assert!(close_vertices(&ring, tol, &meets(&ring, tol)).is_some());
        // A square: nothing meets.
        let square = ring_of(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]);
        assert_eq!(meeting_edges(&square, tol_of(&square)), None);
    }

    #[test]
    fn a_hundred_thousand_vertices() {
        // A star: long spikes whose boxes overlap many others'.
        let n = 100_000;
        let star: Vec<Point> = (0..n)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / n as f64;
                let r = if k % 2 == 0 { 4.0 } else { 0.5 };
                Point::new(r * a.cos(), r * a.sin())
            })
            .collect();
        assert_eq!(meeting_edges(&star, tol_of(&star)), None);
        // One spike bent across its neighbour.
        let mut bent = star.clone();
        bent[500] = star[504];
        assert!(meeting_edges(&bent, tol_of(&bent)).is_some());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// Small lattice rings: crossings, touchings, overlaps are common.
        #[test]
        fn the_sweep_agrees_with_all_pairs_on_lattice_rings(
            v in prop::collection::vec((0..5i32, 0..5i32), 4..12)
        ) {
            let ring = without_repeats(v.iter().map(|&(x, y)| Point::new(x as f64, y as f64)).collect());
            agree(&ring)?;
        }

        /// The same, every vertex moved by up to 1e-12 (under the
        /// tolerance): touchings become near misses, found all the same.
        #[test]
        fn the_sweep_agrees_with_all_pairs_on_jittered_lattice_rings(
            v in prop::collection::vec((0..5i32, 0..5i32, -1.0..1.0f64, -1.0..1.0f64), 4..12)
        ) {
            let ring = without_repeats(v.iter().map(|&(x, y, _, _)| Point::new(x as f64, y as f64)).collect());
            let jitter: Vec<Point> = ring
                .iter()
                .zip(&v)
                .map(|(p, &(_, _, dx, dy))| Point::new(p.x + 1e-12 * dx, p.y + 1e-12 * dy))
                .collect();
            agree(&jitter)?;
        }

        /// Random rings in general position.
        #[test]
        fn the_sweep_agrees_with_all_pairs_on_random_rings(
            v in prop::collection::vec((-10.0..10.0f64, -10.0..10.0f64), 4..16)
        ) {
            agree(&without_repeats(ring_of(&v)))?;
        }
    }
}
