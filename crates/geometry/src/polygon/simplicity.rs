//! Whether the edges of a closed ring meet, in O(n log n): the test that
//! makes a vertex list a simple polygon ([`super::normalize_simple_polygon`]).
//!
//! Two edges *meet* when they are not adjacent (do not share a vertex of
//! the ring) and come within `tol` of each other — the predicate of the
//! all-pairs test this replaces, [`all_pairs`], kept as the oracle of the
//! tests. Every pair reported is checked with that predicate; the work is
//! in bringing a meeting pair to it without looking at every pair
//! ([`super::proximity`]):
//!
//! * **Crossing or touching edges**: a Shamos–Hoey sweep compares edges as
//!   they become neighbours in the sweep status; before the leftmost point
//!   where two edges meet, they are neighbours.
//! * **Edges that come within `tol` without touching**: their closest points
//!   are an end `v` of one and a point of the other, found from `v` by the
//!   sweeps' walks (in two frames) or the hash of close vertices.
//!
//! Each step stops at the first pair that meets, and while none does the
//! walks and cells hold O(1) edges: O(n log n).

use super::proximity::{Visit, close_vertices, exchanged, sweep};
use super::{Point, distance_segment_segment};

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
    let n = ring.len();
    if n < 4 {
        return None;
    }
    let meet = meets(ring, tol);
    let meet_dyn: &dyn Fn(usize, usize) -> bool = &meet;
    // Walking from vertex `k`: an edge that meets one of the vertex's two
    // edges, or the edge walked before it (edges bunched near one vertex
    // meet each other).
    let mut at_vertex = |k: usize, t: usize, last: Option<usize>| {
        for i in [(k + n - 1) % n, k] {
            if meet(i, t) {
                return Visit::Found(i, t);
            }
        }
        match last {
            Some(l) if meet(l, t) => Visit::Found(l, t),
            _ => Visit::Walk,
        }
    };
    let turned = exchanged(ring);
    let reach = (1.0 + std::f64::consts::SQRT_2) * tol * (1.0 + 1e-9);
    sweep(ring, Some(meet_dyn), ring, 2.0 * tol, &mut at_vertex)
        .or_else(|| sweep(&turned, Some(meet_dyn), &turned, 2.0 * tol, &mut at_vertex))
        .or_else(|| {
            close_vertices(ring, ring, reach, &mut |k, j| {
                for a in [(k + n - 1) % n, k] {
                    for b in [(j + n - 1) % n, j] {
                        if meet(a, b) {
                            return Visit::Found(a, b);
                        }
                    }
                }
                Visit::Walk
            })
        })
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
        // A square: nothing meets.
        let square = ring_of(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]);
        assert_eq!(meeting_edges(&square, tol_of(&square)), None);
    }

    #[test]
    fn a_hundred_thousand_vertices() {
        // A star: long spikes whose boxes overlap many others'.
        let star = crate::fixtures::star(100_000, 4.0, 0.5);
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
