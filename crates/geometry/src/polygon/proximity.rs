//! What comes within a small distance of a polygon's edges, in O(n log n):
//! the machinery of the simplicity test ([`super::simplicity`]) and of
//! [`points_near_outline`].
//!
//! A point `p` within `r` of an edge `B` (closest point `q`) is found in
//! one of three ways, none of which looks at every edge:
//!
//! * When `B` slopes by at most 45° and spans `p`'s abscissa, `B` crosses
//!   `p`'s vertical within `√2·r` of `p`, and so does every edge between
//!   them there (edges that do not cross each other keep one order along
//!   that vertical). A sweep from left to right keeps the edges that cross
//!   the sweep line in their order (a Shamos–Hoey status) and, at `p`,
//!   walks up and down it through the edges within `2·r` of `p`.
//! * Steeper edges: the same sweep with x and y exchanged.
//! * When `B` does not span `p`'s abscissa (or, steep, its ordinate), `q` is
//!   within `√2·r` of an end of `B`, so that end is within `(1 + √2)·r` of
//!   `p`: the vertices are hashed into cells of that size.
//!
//! The walks and the cells hold O(1) edges and vertices as long as the
//! edges are farther apart than about `r / 40` (as the edges of a simple
//! polygon are, at the tolerances used here); each walk is also capped.

use std::collections::HashMap;

use super::Point;
use super::orient;
use super::sweep_status::SweepStatus;

/// The most edges a walk visits each way.
const MAX_WALK: usize = 64;

/// What a walk does after visiting an edge.
pub(super) enum Visit {
    /// Goes on to the next edge.
    Walk,
    /// Stops walking from this point.
    Enough,
    /// Stops the sweep: this pair of edges meets.
    Found(usize, usize),
}

#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Event {
    /// An edge's left end: it enters the status.
    Enter,
    /// A point to walk from.
    Probe,
    /// An edge's right end: it leaves.
    Leave,
}

/// One sweep from left to right over the edges of the closed ring `ring`
/// (edge `i` from `ring[i]` to `ring[i + 1]`, the last back to the first),
/// in the frame the points are given in.
///
/// # Arguments
/// * `meet` — when given, the Shamos–Hoey test: called on every two edges
///   that become neighbours in the status; a pair it accepts ends the sweep.
///   Before the leftmost point where two edges cross or touch, they are
///   neighbours.
/// * `probes` — points at which the status is walked, up and down, through
///   the edges whose vertical gap to the point is at most `window`
///   (`visit(probe, edge, the edge visited before it on this walk)`).
///
/// # Returns
/// The pair of edges that ended the sweep, if one did.
pub(super) fn sweep(
    ring: &[Point],
    meet: Option<&dyn Fn(usize, usize) -> bool>,
    probes: &[Point],
    window: f64,
    visit: &mut dyn FnMut(usize, usize, Option<usize>) -> Visit,
) -> Option<(usize, usize)> {
    let n = ring.len();
    let lex = |a: &Point, b: &Point| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y));
    // Each edge's ends, left (lexicographically smaller) first.
    let ends: Vec<(Point, Point)> = (0..n)
        .map(|e| {
            let (a, b) = (ring[e], ring[(e + 1) % n]);
            if lex(&a, &b).is_le() { (a, b) } else { (b, a) }
        })
        .collect();
    let mut events: Vec<(Point, Event, usize)> = Vec::with_capacity(2 * n + probes.len());
    for (e, &(left, right)) in ends.iter().enumerate() {
        events.push((left, Event::Enter, e));
        events.push((right, Event::Leave, e));
    }
    events.extend(
        probes
            .iter()
            .enumerate()
            .map(|(k, &p)| (p, Event::Probe, k)),
    );
    // At one point: edges enter, then the point is walked from, then edges
    // leave, so that edges that meet there are in the status together.
    events.sort_by(|a, b| lex(&a.0, &b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));

    let mut status = SweepStatus::new(n);
    let meets = |a: usize, b: usize| meet.is_some_and(|m| m(a, b));
    for (p, event, e) in events {
        match event {
            Event::Enter => {
                status.insert(e, |t| above(ends[e], ends[t], e, t));
                for t in [status.prev(e), status.next(e)].into_iter().flatten() {
                    if meets(e, t) {
                        return Some((e, t));
                    }
                }
            }
            Event::Leave => {
                let (below, over) = (status.prev(e), status.next(e));
                status.remove(e);
                if let (Some(a), Some(b)) = (below, over)
                    && meets(a, b)
                {
                    return Some((a, b));
                }
            }
            Event::Probe => {
                let (below, over) = status.locate(|t| orient(ends[t].0, ends[t].1, p) > 0.0);
                'walks: for (first, up) in [(over, true), (below, false)] {
                    let mut at = first;
                    let mut last = None;
                    for _ in 0..MAX_WALK {
                        let Some(t) = at else {
                            break;
                        };
                        if vertical_gap(ends[t], p) > window {
                            break;
                        }
                        match visit(e, t, last) {
                            Visit::Walk => {}
                            Visit::Enough => break 'walks,
                            Visit::Found(a, b) => return Some((a, b)),
                        }
                        last = Some(t);
                        at = if up { status.next(t) } else { status.prev(t) };
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

/// The points with x and y exchanged: the frame of the second sweep.
pub(super) fn exchanged(points: &[Point]) -> Vec<Point> {
    points.iter().map(|p| Point::new(p.y, p.x)).collect()
}

/// Calls `visit(probe, vertex)` for every ring vertex within `radius` of a
/// probe (and maybe a few more), probe by probe, until a visit returns
/// [`Visit::Found`] (returned) or [`Visit::Enough`] (next probe). The
/// vertices are hashed into cells of side `radius`.
pub(super) fn close_vertices(
    ring: &[Point],
    probes: &[Point],
    radius: f64,
    visit: &mut dyn FnMut(usize, usize) -> Visit,
) -> Option<(usize, usize)> {
    if !(radius > 0.0 && radius.is_finite()) {
        return None;
    }
    let origin = ring
        .iter()
        .fold(Point::new(f64::INFINITY, f64::INFINITY), |o, p| {
            Point::new(o.x.min(p.x), o.y.min(p.y))
        });
    // Relative to the ring's lowest corner; saturating casts keep probes
    // far outside in cells no vertex has.
    let cell = |p: &Point| {
        (
            ((p.x - origin.x) / radius).floor() as i64,
            ((p.y - origin.y) / radius).floor() as i64,
        )
    };
    let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (k, p) in ring.iter().enumerate() {
        cells.entry(cell(p)).or_default().push(k);
    }
    for (k, p) in probes.iter().enumerate() {
        let (cx, cy) = cell(p);
        'probe: for dx in -1..=1 {
            for dy in -1..=1 {
                let Some(list) = cells.get(&(cx.saturating_add(dx), cy.saturating_add(dy))) else {
                    continue;
                };
                for &j in list {
                    if (ring[j] - p).norm() > radius {
                        continue;
                    }
                    match visit(k, j) {
                        Visit::Walk => {}
                        Visit::Enough => break 'probe,
                        Visit::Found(a, b) => return Some((a, b)),
                    }
                }
            }
        }
    }
    None
}

/// Whether each of `points` lies within `r` of the outline of a simple
/// polygon, by `distance(point, edge)` (edge `i` from `outline[i]` to
/// `outline[i + 1]`): a distance from a point to a segment, for callers that
/// compute it their own way. O((n + m) log(n + m)) for `n` vertices and `m`
/// points.
pub fn points_near_outline(
    outline: &[Point],
    points: &[Point],
    r: f64,
    distance: impl Fn(Point, usize) -> f64,
) -> Vec<bool> {
    let mut near = vec![false; points.len()];
    if outline.len() < 2 {
        return near;
    }
    let n = outline.len();
    let mut mark = |k: usize, e: usize| {
        if !near[k] && distance(points[k], e) <= r {
            near[k] = true;
        }
        if near[k] { Visit::Enough } else { Visit::Walk }
    };
    sweep(outline, None, points, 2.0 * r, &mut |k, e, _| mark(k, e));
    sweep(
        &exchanged(outline),
        None,
        &exchanged(points),
        2.0 * r,
        &mut |k, e, _| mark(k, e),
    );
    let reach = (1.0 + std::f64::consts::SQRT_2) * r * (1.0 + 1e-9);
    close_vertices(
        outline,
        points,
        reach,
        &mut |k, v| match mark(k, (v + n - 1) % n) {
            Visit::Walk => mark(k, v),
            done => done,
        },
    );
    near
}

/// A polygon's vertices by exact position (−0 and +0 alike, as `==` has
/// them): the first index of each.
pub struct VertexIndex(HashMap<(u64, u64), usize>);

impl VertexIndex {
    fn key(p: Point) -> (u64, u64) {
        ((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits())
    }

    pub fn new(outline: &[Point]) -> Self {
        let mut at = HashMap::with_capacity(outline.len());
        for (k, &v) in outline.iter().enumerate() {
            at.entry(Self::key(v)).or_insert(k);
        }
        VertexIndex(at)
    }

    /// The index of the first vertex at `p`.
    pub fn of(&self, p: Point) -> Option<usize> {
        self.0.get(&Self::key(p)).copied()
    }
}

/// The edges where the convex pieces of a polygon meet: the edges of the
/// pieces whose midpoint is not within `near` of the outline (by
/// `distance`, as in [`points_near_outline`]), once each (either way
/// round), in the order the pieces give them.
///
/// O(n log n) in the outline's and the pieces' vertices: an outline edge
/// is known by its ends ([`VertexIndex`]), the other midpoints are tested
/// together, edges already taken are in a hash set.
pub fn shared_edges<'a>(
    outline: &[Point],
    vertices: &VertexIndex,
    pieces: impl Iterator<Item = &'a [Point]>,
    near: f64,
    distance: impl Fn(Point, usize) -> f64,
) -> Vec<(Point, Point)> {
    let n = outline.len();
    let outline_edge = |a: Point, b: Point| match (vertices.of(a), vertices.of(b)) {
        (Some(i), Some(j)) => (i + 1) % n == j || (j + 1) % n == i,
        _ => false,
    };
    let key = |a: Point, b: Point| (VertexIndex::key(a), VertexIndex::key(b));
    let mut taken = std::collections::HashSet::new();
    let mut edges: Vec<(Point, Point)> = Vec::new();
    for piece in pieces {
        for j in 0..piece.len() {
            let (a, b) = (piece[j], piece[(j + 1) % piece.len()]);
            if !outline_edge(a, b) && !taken.contains(&key(b, a)) && taken.insert(key(a, b)) {
                edges.push((a, b));
            }
        }
    }
    let midpoints: Vec<Point> = edges
        .iter()
        .map(|(a, b)| Point::from((a.coords + b.coords) / 2.0))
        .collect();
    let on_outline = points_near_outline(outline, &midpoints, near, distance);
    edges
        .into_iter()
        .zip(on_outline)
        .filter_map(|(edge, on)| (!on).then_some(edge))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::{distance_point_segment, normalize_simple_polygon};
    use super::*;
    use proptest::prelude::*;

    fn brute_force(outline: &[Point], points: &[Point], r: f64) -> Vec<bool> {
        let n = outline.len();
        points
            .iter()
            .map(|&p| {
                (0..n).any(|i| distance_point_segment(p, outline[i], outline[(i + 1) % n]) <= r)
            })
            .collect()
    }

    fn near(outline: &[Point], points: &[Point], r: f64) -> Vec<bool> {
        let n = outline.len();
        points_near_outline(outline, points, r, |p, i| {
            distance_point_segment(p, outline[i], outline[(i + 1) % n])
        })
    }

    /// Points on, just inside and just outside `r` of each edge, near its
    /// ends and its middle, and near each vertex.
    fn probes_around(outline: &[Point], r: f64, offsets: &[f64]) -> Vec<Point> {
        let n = outline.len();
        let mut out = Vec::new();
        for i in 0..n {
            let (a, b) = (outline[i], outline[(i + 1) % n]);
            let d = (b - a).normalize();
            let across = super::super::Vector::new(-d.y, d.x);
            for t in [0.0, 1e-9, 0.5, 1.0 - 1e-9, 1.0] {
                for &o in offsets {
                    out.push(a + (b - a) * t + across * (o * r));
                }
            }
            for &o in offsets {
                out.push(a - d * (o * r));
                out.push(a + (-d + across) * (o * r / 2f64.sqrt()));
            }
        }
        out
    }

    #[test]
    fn slanted_teeth_and_a_hundred_thousand_probes() {
        // Long parallel slanted teeth: every edge's box holds many others.
        let teeth = 2000;
        let w = 4.0 / teeth as f64;
        let mut v = vec![Point::new(1.0, 1.0), Point::new(5.0, 1.0)];
        for t in (0..teeth).rev() {
            let x = 1.0 + t as f64 * w;
            v.extend([
                Point::new(x + w, 1.5),
                Point::new(x + w + 4.0, 9.0),
                Point::new(x + w / 2.0 + 4.0, 9.0),
                Point::new(x + w / 2.0, 1.5),
            ]);
        }
        v.push(Point::new(1.0, 1.5));
        let outline = normalize_simple_polygon(&v).unwrap();
        let r = 1e-9 * 8.0;
        let probes = probes_around(&outline, r, &[0.0, 0.5, 0.99, 1.01, 2.0, 40.0]);
        assert!(probes.len() > 100_000);
        let got = near(&outline, &probes, r);
        assert_eq!(got, brute_force_by_buckets(&outline, &probes, r));
        assert!(got.iter().any(|&b| b) && got.iter().any(|&b| !b));
    }

    /// The brute force, sped up for many probes by testing each probe only
    /// against the edges whose boxes are within `r` (exactly the same
    /// answer).
    fn brute_force_by_buckets(outline: &[Point], probes: &[Point], r: f64) -> Vec<bool> {
        let n = outline.len();
        let mut order: Vec<usize> = (0..probes.len()).collect();
        order.sort_by(|&a, &b| probes[a].x.total_cmp(&probes[b].x));
        let xs: Vec<f64> = order.iter().map(|&k| probes[k].x).collect();
        let mut out = vec![false; probes.len()];
        for i in 0..n {
            let (a, b) = (outline[i], outline[(i + 1) % n]);
            let (lo, hi) = (a.x.min(b.x) - r, a.x.max(b.x) + r);
            let from = xs.partition_point(|&x| x < lo);
            for &k in &order[from..] {
                if probes[k].x > hi {
                    break;
                }
                if !out[k] && distance_point_segment(probes[k], a, b) <= r {
                    out[k] = true;
                }
            }
        }
        out
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        #[test]
        fn agrees_with_brute_force_on_lattice_polygons(
            v in prop::collection::vec((0..6i32, 0..6i32), 3..14),
            turn in 0.0..std::f64::consts::TAU,
        ) {
            let (s, c) = turn.sin_cos();
            let input: Vec<Point> = v
                .iter()
                .map(|&(x, y)| Point::new(c * x as f64 - s * y as f64, s * x as f64 + c * y as f64))
                .collect();
            if let Ok(outline) = normalize_simple_polygon(&input) {
                let r = 1e-9 * 6.0;
                let probes = probes_around(&outline, r, &[0.0, 0.3, 0.999, 1.001, 1.5, 3.0]);
                prop_assert_eq!(near(&outline, &probes, r), brute_force(&outline, &probes, r));
            }
        }
    }
}
