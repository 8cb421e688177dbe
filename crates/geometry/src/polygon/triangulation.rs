//! Triangulating a simple polygon in O(n log n): a sweep from top to bottom
//! cuts it into y-monotone pieces with diagonals, and each piece is
//! triangulated with a stack in linear time (de Berg et al., *Computational
//! Geometry*, chapter 3).
//!
//! "Above" is lexicographic — higher y, then lower x — so that vertices at
//! one height are ordered as if the plane were turned by a hair, and no two
//! vertices are level.

use std::collections::HashMap;

use super::sweep_status::SweepStatus;
use super::{Point, ear_clipping, orient, signed_area2};

/// Triangles (vertex indices, counter-clockwise) that tile the polygon; each
/// triangle's vertices are polygon vertices.
///
/// # Arguments
/// * `pts` — a simple polygon, counter-clockwise, at least 3 vertices,
///   without duplicate or collinear vertices (as
///   [`super::normalize_simple_polygon`] returns it).
///
/// # Returns
/// `pts.len() − 2` triangles. A piece that rounding left not monotone (its
/// stack triangulation does not come out as `m − 2` counter-clockwise
/// triangles of its area) is triangulated by ear clipping instead.
pub(super) fn triangulate(pts: &[Point]) -> Vec<[usize; 3]> {
    let diagonals = monotone_diagonals(pts);
    let mut triangles = Vec::with_capacity(pts.len().saturating_sub(2));
    for piece in pieces(pts, &diagonals) {
        match triangulate_monotone(pts, &piece) {
            Some(t) => triangles.extend(t),
            None => {
                let local: Vec<Point> = piece.iter().map(|&v| pts[v]).collect();
                triangles.extend(
                    ear_clipping(&local)
                        .into_iter()
                        .map(|[a, b, c]| [piece[a], piece[b], piece[c]]),
                );
            }
        }
    }
    triangles
}

/// Whether `p` is above `q` (lexicographically: higher, then to the left).
fn above(p: Point, q: Point) -> bool {
    p.y > q.y || (p.y == q.y && p.x < q.x)
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// Both neighbours below, the interior angle less than π.
    Start,
    /// Both neighbours below, the interior angle more than π.
    Split,
    /// Both neighbours above, the interior angle less than π.
    End,
    /// Both neighbours above, the interior angle more than π.
    Merge,
    /// One neighbour above, one below; `true` when the interior is to its
    /// right (the boundary goes down through it).
    Regular(bool),
}

/// Diagonals that cut the polygon into y-monotone pieces: a sweep from top
/// to bottom over the vertices, its status the edges that have the
/// interior to their right (edge `i` from vertex `i` to `i + 1`, going
/// down), each with its helper, the lowest vertex above the sweep line that
/// sees the edge horizontally.
fn monotone_diagonals(pts: &[Point]) -> Vec<(usize, usize)> {
    let n = pts.len();
    let kind = |i: usize| {
        let (p, v, q) = (pts[(i + n - 1) % n], pts[i], pts[(i + 1) % n]);
        let convex = orient(p, v, q) > 0.0;
        match (above(p, v), above(q, v)) {
            (false, false) if convex => Kind::Start,
            (false, false) => Kind::Split,
            (true, true) if convex => Kind::End,
            (true, true) => Kind::Merge,
            (prev_above, _) => Kind::Regular(prev_above),
        }
    };
    let mut sweep = MonotoneSweep {
        pts,
        kinds: (0..n).map(kind).collect(),
        status: SweepStatus::new(n),
        helper: vec![usize::MAX; n],
        diagonals: Vec::new(),
    };
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        pts[b]
            .y
            .total_cmp(&pts[a].y)
            .then(pts[a].x.total_cmp(&pts[b].x))
    });
    for i in order {
        match sweep.kinds[i] {
            Kind::Start => sweep.open(i),
            Kind::End => sweep.close_above(i),
            Kind::Split => {
                sweep.join_left(i, true);
                sweep.open(i);
            }
            Kind::Merge => {
                sweep.close_above(i);
                sweep.join_left(i, false);
            }
            Kind::Regular(true) => {
                sweep.close_above(i);
                sweep.open(i);
            }
            Kind::Regular(false) => sweep.join_left(i, false),
        }
    }
    sweep.diagonals
}

struct MonotoneSweep<'a> {
    pts: &'a [Point],
    kinds: Vec<Kind>,
    status: SweepStatus,
    /// By edge; `usize::MAX` for none.
    helper: Vec<usize>,
    diagonals: Vec<(usize, usize)>,
}

impl MonotoneSweep<'_> {
    /// Whether `p` is right of edge `t` (which goes down from `pts[t]`):
    /// the turn from the edge to `p` is to the left.
    fn right_of(&self, t: usize, p: Point) -> bool {
        let n = self.pts.len();
        orient(self.pts[t], self.pts[(t + 1) % n], p) > 0.0
    }

    fn joins_merge(&mut self, i: usize, e: usize) {
        let h = self.helper[e];
        if h != usize::MAX && h != i && self.kinds[h] == Kind::Merge {
            self.diagonals.push((i, h));
        }
    }

    /// Edge `i` enters the status, vertex `i` its helper.
    fn open(&mut self, i: usize) {
        let (pts, v) = (self.pts, self.pts[i]);
        let n = pts.len();
        self.status
            .insert(i, |t| orient(pts[t], pts[(t + 1) % n], v) > 0.0);
        self.helper[i] = i;
    }

    /// The edge coming down to vertex `i` leaves the status (its helper
    /// joined to `i` if a merge vertex).
    fn close_above(&mut self, i: usize) {
        let e = (i + self.pts.len() - 1) % self.pts.len();
        self.joins_merge(i, e);
        self.status.remove(e);
    }

    /// Vertex `i` becomes the helper of the edge directly left of it,
    /// joined to the old helper if that is a merge vertex (or `always`).
    fn join_left(&mut self, i: usize, always: bool) {
        let v = self.pts[i];
        let Some(e) = self.status.locate(|t| self.right_of(t, v)).0 else {
            return;
        };
        if always {
            let h = self.helper[e];
            if h != usize::MAX && h != i {
                self.diagonals.push((i, h));
            }
        } else {
            self.joins_merge(i, e);
        }
        self.helper[e] = i;
    }
}

/// The pieces the diagonals cut the polygon into, each a counter-clockwise
/// cycle of vertex indices: faces of the plane graph of the edges and the
/// diagonals, walked by turning, at each vertex, to the next edge clockwise.
fn pieces(pts: &[Point], diagonals: &[(usize, usize)]) -> Vec<Vec<usize>> {
    let n = pts.len();
    let mut around: Vec<Vec<usize>> = (0..n).map(|v| vec![(v + n - 1) % n, (v + 1) % n]).collect();
    for &(a, b) in diagonals {
        around[a].push(b);
        around[b].push(a);
    }
    // Each vertex's neighbours counter-clockwise by direction, from the
    // positive x axis: by half-plane, then by angle. (Keys, not a
    // comparison of turns, which rounding could make inconsistent, and a
    // sort may panic on an inconsistent order.)
    for (v, list) in around.iter_mut().enumerate() {
        let o = pts[v];
        let direction = |w: usize| {
            let d = pts[w] - o;
            if d.y > 0.0 || (d.y == 0.0 && d.x > 0.0) {
                (0u8, d.y.atan2(d.x))
            } else if d.y == 0.0 {
                (1, -std::f64::consts::PI)
            } else {
                (1, d.y.atan2(d.x))
            }
        };
        let mut keyed: Vec<(u8, f64, usize)> = list
            .iter()
            .map(|&w| {
                let (half, angle) = direction(w);
                (half, angle, w)
            })
            .collect();
        keyed.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)).then(a.2.cmp(&b.2)));
        *list = keyed.into_iter().map(|(_, _, w)| w).collect();
        list.dedup();
    }
    // Half-edge `v → around[v][k]` is number `first[v] + k`.
    let mut first = vec![0; n + 1];
    for v in 0..n {
        first[v + 1] = first[v] + around[v].len();
    }
    let index: HashMap<(usize, usize), usize> = (0..n)
        .flat_map(|v| {
            let first = &first;
            around[v]
                .iter()
                .enumerate()
                .map(move |(k, &w)| ((v, w), first[v] + k))
        })
        .collect();
    let mut done = vec![false; first[n]];
    // The outside: the polygon's edges walked backwards.
    for v in 0..n {
        if let Some(&h) = index.get(&((v + 1) % n, v)) {
            done[h] = true;
        }
    }
    let mut out = Vec::new();
    for v in 0..n {
        for k in 0..around[v].len() {
            if done[first[v] + k] {
                continue;
            }
            let mut face = Vec::new();
            let (mut from, mut to) = (v, around[v][k]);
            while let Some(&h) = index.get(&(from, to)) {
                if done[h] {
                    break;
                }
                done[h] = true;
                face.push(from);
                // The edge after `to → from` clockwise around `to`.
                let list = &around[to];
                let Some(&back) = index.get(&(to, from)) else {
                    break;
                };
                let at = back - first[to];
                let turn = list[(at + list.len() - 1) % list.len()];
                (from, to) = (to, turn);
            }
            if face.len() >= 3 {
                out.push(face);
            }
        }
    }
    out
}

/// Triangulates a y-monotone piece (a counter-clockwise cycle of vertex
/// indices) with a stack, top to bottom; `None` when the piece is not
/// monotone after all (rounding) or the triangles do not tile it.
fn triangulate_monotone(pts: &[Point], piece: &[usize]) -> Option<Vec<[usize; 3]>> {
    let m = piece.len();
    if m == 3 {
        let t = [piece[0], piece[1], piece[2]];
        return (orient(pts[t[0]], pts[t[1]], pts[t[2]]) > 0.0).then_some(vec![t]);
    }
    let higher = |a: &usize, b: &usize| {
        if above(pts[*a], pts[*b]) {
            std::cmp::Ordering::Greater
        } else {
            std::cmp::Ordering::Less
        }
    };
    let top = (0..m).max_by(|&a, &b| higher(&piece[a], &piece[b]))?;
    // Counter-clockwise from the top, the left chain goes down to the
    // bottom; the right chain comes back up. Merge them top to bottom.
    let walk: Vec<usize> = (0..m).map(|k| piece[(top + k) % m]).collect();
    let bottom = (0..m).min_by(|&a, &b| higher(&walk[a], &walk[b]))?;
    let left: Vec<usize> = walk[..bottom].to_vec();
    let right: Vec<usize> = walk[bottom..].iter().rev().copied().collect();
    if left.windows(2).any(|w| !above(pts[w[0]], pts[w[1]]))
        || right.windows(2).any(|w| !above(pts[w[0]], pts[w[1]]))
    {
        return None;
    }
    let mut sorted: Vec<(usize, bool)> = Vec::with_capacity(m);
    let (mut a, mut b) = (0, 0);
    while a < left.len() || b < right.len() {
        let take_left = b == right.len() || (a < left.len() && above(pts[left[a]], pts[right[b]]));
        if take_left {
            sorted.push((left[a], true));
            a += 1;
        } else {
            sorted.push((right[b], false));
            b += 1;
        }
    }

    let mut triangles = Vec::with_capacity(m - 2);
    // A triangle with its vertices put counter-clockwise.
    let mut emit = |a: usize, b: usize, c: usize| {
        if orient(pts[a], pts[b], pts[c]) > 0.0 {
            triangles.push([a, b, c]);
        } else {
            triangles.push([a, c, b]);
        }
    };
    let mut stack: Vec<(usize, bool)> = vec![sorted[0], sorted[1]];
    for &(u, on_left) in &sorted[2..m - 1] {
        let &(_, top_left) = stack.last()?;
        if top_left != on_left {
            for w in stack.windows(2) {
                emit(u, w[0].0, w[1].0);
            }
            let last = *stack.last()?;
            stack = vec![last, (u, on_left)];
        } else {
            let mut last = stack.pop()?;
            while let Some(&s) = stack.last() {
                // The diagonal from `u` to `s` is inside when `last` bulges
                // outwards between them.
                let ccw = if on_left {
                    orient(pts[s.0], pts[last.0], pts[u])
                } else {
                    orient(pts[u], pts[last.0], pts[s.0])
                };
                if ccw <= 0.0 {
                    break;
                }
                emit(u, last.0, s.0);
                last = stack.pop()?;
            }
            stack.push(last);
            stack.push((u, on_left));
        }
    }
    let (u, _) = sorted[m - 1];
    for w in stack.windows(2) {
        emit(u, w[0].0, w[1].0);
    }
    // Tiles the piece: m − 2 proper triangles of its area.
    let areas: Vec<f64> = triangles
        .iter()
        .map(|t| orient(pts[t[0]], pts[t[1]], pts[t[2]]))
        .collect();
    let whole = signed_area2(&piece.iter().map(|&v| pts[v]).collect::<Vec<_>>());
    let total: f64 = areas.iter().sum();
    (triangles.len() == m - 2
        && areas.iter().all(|&a| a > 0.0)
        && (total - whole).abs() <= 1e-9 * whole.abs())
    .then_some(triangles)
}

#[cfg(test)]
mod tests {
    use super::super::normalize_simple_polygon;
    use super::*;
    use proptest::prelude::*;

    /// The monotone partition's pieces are monotone (triangulated by the
    /// stack, without falling back to ear clipping) and together with
    /// their triangles tile the polygon.
    fn partition_is_monotone_and_tiles(poly: &[Point]) -> Result<(), TestCaseError> {
        let area =
            |cycle: &[usize]| signed_area2(&cycle.iter().map(|&v| poly[v]).collect::<Vec<_>>());
        let whole = signed_area2(poly);
        let pieces = pieces(poly, &monotone_diagonals(poly));
        let mut triangles = 0;
        let mut pieces_area = 0.0;
        for piece in &pieces {
            let t = triangulate_monotone(poly, piece);
            prop_assert!(t.is_some(), "piece {:?} of {:?}", piece, poly);
            triangles += t.map_or(0, |t| t.len());
            pieces_area += area(piece);
        }
        prop_assert_eq!(triangles, poly.len() - 2);
        prop_assert!(
            (pieces_area - whole).abs() <= 1e-9 * whole,
            "{} vs {}",
            pieces_area,
            whole
        );
        let t = triangulate(poly);
        prop_assert_eq!(t.len(), poly.len() - 2);
        let total: f64 = t.iter().map(|t| area(t)).sum();
        prop_assert!((total - whole).abs() <= 1e-9 * whole);
        Ok(())
    }

    fn comb(teeth: usize) -> Vec<Point> {
        let mut v = vec![Point::new(0.0, 0.0), Point::new(2.0 * teeth as f64, 0.0)];
        for k in (0..teeth).rev() {
            let x = 2.0 * k as f64;
            v.extend([
                Point::new(x + 2.0, 10.0),
                Point::new(x + 1.0, 10.0),
                Point::new(x + 1.0, 1.0),
            ]);
            if k > 0 {
                v.push(Point::new(x, 1.0));
            }
        }
        v.push(Point::new(0.0, 10.0));
        v
    }

    #[test]
    fn combs_and_stars_are_cut_into_monotone_pieces() {
        let comb = normalize_simple_polygon(&comb(50)).unwrap();
        partition_is_monotone_and_tiles(&comb).unwrap();
        // Teeth pointing down: every tooth's bottom is a split vertex... of
        // the comb turned upside down.
        let flipped: Vec<Point> = comb.iter().map(|p| Point::new(-p.x, -p.y)).collect();
        partition_is_monotone_and_tiles(&flipped).unwrap();
        let sideways: Vec<Point> = comb.iter().map(|p| Point::new(p.y, -p.x)).collect();
        partition_is_monotone_and_tiles(&sideways).unwrap();
    }

    #[test]
    fn a_hundred_thousand_vertices() {
        let n = 100_000;
        let star = crate::fixtures::star(n, 4.0, 1.0);
        partition_is_monotone_and_tiles(&star).unwrap();
        partition_is_monotone_and_tiles(&normalize_simple_polygon(&comb(n / 4)).unwrap()).unwrap();
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// Lattice polygons: level edges and vertices at one height, where
        /// the lexicographic order decides.
        #[test]
        fn lattice_polygons(v in prop::collection::vec((0..6i32, 0..6i32), 3..14)) {
            let input: Vec<Point> = v.iter().map(|&(x, y)| Point::new(x as f64, y as f64)).collect();
            if let Ok(poly) = normalize_simple_polygon(&input) {
                partition_is_monotone_and_tiles(&poly)?;
            }
        }

        /// Star-shaped polygons with random radii, and the same turned.
        #[test]
        fn star_polygons(
            v in prop::collection::vec((0.0..1.0f64, 0.1..3.0f64), 3..40),
            turn in 0.0..std::f64::consts::TAU,
        ) {
            let n = v.len();
            let poly: Vec<Point> = v
                .iter()
                .enumerate()
                .map(|(k, &(jitter, r))| {
                    let a = turn + (k as f64 + 0.8 * jitter) * std::f64::consts::TAU / n as f64;
                    Point::new(r * a.cos(), r * a.sin())
                })
                .collect();
            if let Ok(poly) = normalize_simple_polygon(&poly) {
                partition_is_monotone_and_tiles(&poly)?;
            }
        }
    }
}
