//! Minkowski sums of convex polygons by merging edge directions, and the
//! C-obstacles of a rotating convex robot (SPEC 3.1, SEEDS.md §A).
//!
//! # The C-obstacle
//! A convex robot `A` (in its own frame, rotating about the frame origin)
//! placed at `(x, y, θ)` overlaps a convex obstacle piece `B` exactly when
//! `(x, y)` lies in `CB_θ = B ⊕ (−A(θ))`, where `A(θ)` is `A` rotated by `θ`
//! and `−A(θ)` its reflection through the origin. Moreover the penetration
//! depth of the robot into `B` equals the distance of `(x, y)` from the
//! boundary of `CB_θ`, so "the robot overlaps `B` deeper than `TOUCH_EPS`"
//! is "`(x, y)` lies in `CB_θ` farther than `TOUCH_EPS` from its boundary".
//!
//! # Merging edge directions ("merging circles")
//! The edges of a convex polygon, walked counter-clockwise from its lowest
//! (then leftmost) vertex, have strictly increasing directions in
//! `[0, 2π)`. The sum `P ⊕ Q` has as edges all edges of both, in that order
//! of direction, and its lowest vertex is the sum of the lowest vertices:
//! so one merge of the two edge sequences, emitting the sum of the current
//! vertices after each step, yields the sum in O(n + m). Parallel edges
//! (equal directions) are taken together; nearly parallel ones give
//! (nearly) collinear vertices, which are removed afterwards together with
//! any duplicate, so the result is a valid [`ConvexPolygon`]. A segment is
//! the degenerate convex "polygon" with two vertices and two opposite edges,
//! a point the one with none: the same merge handles them.
//!
//! Directions are compared exactly on the computed edge vectors (half plane,
//! then the sign of the cross product), never through `atan2`.

use super::{ConvexPolygon, Point, Vector};

/// Sides of the polygon that approximates a disk obstacle.
pub const DISK_SIDES: usize = 32;

/// Relative tolerance of the clean-up: vertices closer than this (times the
/// result's size) are one vertex, vertices closer than this to the line of
/// their neighbours are collinear and removed.
const REL_TOL: f64 = 1e-12;

/// The Minkowski sum `a ⊕ b` of two convex polygons.
///
/// # Behaviour
/// O(n + m) merge of the edge directions (see the module documentation);
/// duplicate and (nearly) collinear vertices of the sum are removed: a
/// vertex closer than `1e-12 ×` the result's size (plus rounding of its
/// coordinates) to the line of its neighbours is dropped.
///
/// # Returns
/// A convex polygon, counter-clockwise, starting at its lowest (then
/// leftmost) vertex; every vertex is the sum of a vertex of `a` and one of
/// `b`.
pub fn minkowski_sum(a: &ConvexPolygon, b: &ConvexPolygon) -> ConvexPolygon {
    let vertices = minkowski_sum_points(&a.vertices, &b.vertices);
    debug_assert!(
        vertices.len() >= 3,
        "the sum of two convex polygons with area has area"
    );
    ConvexPolygon { vertices }
}

/// The Minkowski sum of two convex point lists, degenerate ones included.
///
/// # Arguments
/// * `a`, `b` — convex polygons as counter-clockwise vertex lists (any start
///   vertex), or segments (2 points, either order), or single points.
///   Consecutive duplicate vertices are ignored.
///
/// # Returns
/// The sum as a convex point list of the same kind, counter-clockwise from
/// its lowest (then leftmost) vertex, without duplicate or (nearly)
/// collinear vertices:
/// * 3 or more points when the sum has area;
/// * 2 points (its ends, the lowest-then-leftmost first) when the sum is a
///   segment — e.g. two parallel segments, or a point and a segment;
/// * 1 point for two points; nothing when either input is empty.
pub fn minkowski_sum_points(a: &[Point], b: &[Point]) -> Vec<Point> {
    let a = dedup_ring(a);
    let b = dedup_ring(b);
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let (n, m) = (a.len(), b.len());
    let (s, t) = (lowest(&a), lowest(&b));
    // A point has no edge; a segment two (there and back); a polygon n.
    let edges = |k: usize| if k == 1 { 0 } else { k };
    let (ne, me) = (edges(n), edges(m));
    let va = |i: usize| a[(s + i) % n];
    let vb = |j: usize| b[(t + j) % m];
    let ea = |i: usize| va(i + 1) - va(i);
    let eb = |j: usize| vb(j + 1) - vb(j);
    let sum = |p: Point, q: Point| Point::new(p.x + q.x, p.y + q.y);

    let mut out = Vec::with_capacity(ne + me + 1);
    out.push(sum(va(0), vb(0)));
    let (mut i, mut j) = (0, 0);
    while i < ne || j < me {
        let order = if i == ne {
            std::cmp::Ordering::Greater
        } else if j == me {
            std::cmp::Ordering::Less
        } else {
            compare_directions(ea(i), eb(j))
        };
        match order {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                i += 1;
                j += 1;
            }
        }
        if i < ne || j < me {
            out.push(sum(va(i), vb(j)));
        }
    }
    clean_convex_ring(out)
}

/// `−a`: the polygon reflected through the origin (a rotation by π, so
/// still counter-clockwise).
pub fn reflect(a: &ConvexPolygon) -> ConvexPolygon {
    ConvexPolygon {
        vertices: a.vertices.iter().map(|v| Point::new(-v.x, -v.y)).collect(),
    }
}

/// The robot's body at orientation `theta` with its frame origin at the
/// world origin: every vertex rotated by `theta` counter-clockwise about
/// the origin (the same formula as [`super::RobotShape::placed_vertices`]).
pub fn place(robot_vertices: &[Point], theta: f64) -> ConvexPolygon {
    let (s, c) = theta.sin_cos();
    ConvexPolygon {
        vertices: robot_vertices
            .iter()
            .map(|v| Point::new(c * v.x - s * v.y, s * v.x + c * v.y))
            .collect(),
    }
}

/// The C-obstacle `B ⊕ (−A(θ))` of the convex obstacle piece `B` for the
/// convex robot `A` at orientation `theta` (see the module documentation).
pub fn c_obstacle(
    obstacle_piece: &ConvexPolygon,
    robot: &ConvexPolygon,
    theta: f64,
) -> ConvexPolygon {
    ConvexPolygon {
        vertices: c_obstacle_points(&obstacle_piece.vertices, robot, theta),
    }
}

/// [`c_obstacle`] for a convex point list `B` of any size (a segment
/// obstacle is 2 points, a point 1): since the robot has area, the result
/// is a convex polygon.
pub fn c_obstacle_points(obstacle: &[Point], robot: &ConvexPolygon, theta: f64) -> Vec<Point> {
    let (s, c) = theta.sin_cos();
    let minus_a: Vec<Point> = robot
        .vertices
        .iter()
        .map(|v| Point::new(-(c * v.x - s * v.y), -(s * v.x + c * v.y)))
        .collect();
    minkowski_sum_points(obstacle, &minus_a)
}

/// A convex polygon with `sides` sides (at least 3) circumscribed about the
/// disk of `radius` around `center`: it contains the disk, so the
/// C-obstacle computed from it contains the disk's true C-obstacle (a
/// conservative approximation, off by at most `radius · (1/cos(π/sides) − 1)`
/// ≈ 0.48 % of the radius for 32 sides).
///
/// The vertices lie at distance `radius / cos(π/sides)` (enlarged by a few
/// ulps so that rounding cannot cut into the disk), at angles
/// `(k + ½)·2π/sides`, so that the polygon has sides facing the axes when
/// `sides` is a multiple of 4. A radius of at most 0 gives the centre alone.
pub fn disk_polygon(center: Point, radius: f64, sides: usize) -> Vec<Point> {
    if radius.is_nan() || radius <= 0.0 {
        return vec![center];
    }
    let sides = sides.max(3);
    let step = std::f64::consts::TAU / sides as f64;
    let r = radius / (step / 2.0).cos() * (1.0 + 8.0 * f64::EPSILON);
    (0..sides)
        .map(|k| {
            let (s, c) = ((k as f64 + 0.5) * step).sin_cos();
            Point::new(center.x + r * c, center.y + r * s)
        })
        .collect()
}

// ------------------------------------------------------------------ helpers

/// The points without consecutive (cyclic) exact duplicates.
fn dedup_ring(points: &[Point]) -> Vec<Point> {
    let mut out: Vec<Point> = Vec::with_capacity(points.len());
    for &p in points {
        if out.last() != Some(&p) {
            out.push(p);
        }
    }
    while out.len() > 1 && out.last() == out.first() {
        out.pop();
    }
    out
}

/// Index of the lowest (then leftmost) point.
fn lowest(points: &[Point]) -> usize {
    let mut best = 0;
    for (i, p) in points.iter().enumerate() {
        let q = points[best];
        if p.y < q.y || (p.y == q.y && p.x < q.x) {
            best = i;
        }
    }
    best
}

fn cross(u: Vector, v: Vector) -> f64 {
    u.x * v.y - u.y * v.x
}

/// Orders non-zero directions by their angle in `[0, 2π)`: the upper half
/// plane (angle in `[0, π)`) first, then by the sign of the cross product.
fn compare_directions(u: Vector, v: Vector) -> std::cmp::Ordering {
    let half = |w: Vector| usize::from(!(w.y > 0.0 || (w.y == 0.0 && w.x > 0.0)));
    match half(u).cmp(&half(v)) {
        std::cmp::Ordering::Equal => {
            let c = cross(u, v);
            if c > 0.0 {
                std::cmp::Ordering::Less
            } else if c < 0.0 {
                std::cmp::Ordering::Greater
            } else {
                std::cmp::Ordering::Equal
            }
        }
        other => other,
    }
}

/// Whether `a → b → c` turns left by more than `tol`: the far end of the
/// shorter edge lies farther than `tol` from the longer edge's line, on its
/// left.
fn turns_left(a: Point, b: Point, c: Point, tol: f64) -> bool {
    let (e1, e2) = (b - a, c - b);
    let longer = e1.norm().max(e2.norm());
    longer > tol && cross(e1, e2) > tol * longer
}

/// The length tolerance of the clean-up for `points`: `REL_TOL` times their
/// extent, plus the rounding of their coordinates.
fn tolerance(points: &[Point]) -> f64 {
    let (mut lo, mut hi) = (points[0], points[0]);
    let mut big = 0.0f64;
    for p in points {
        lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
        big = big.max(p.x.abs()).max(p.y.abs());
    }
    REL_TOL * (hi.x - lo.x).max(hi.y - lo.y) + 16.0 * f64::EPSILON * big
}

/// Turns the merged vertex sums (counter-clockwise, sorted by edge
/// direction, starting at an extreme vertex) into a clean convex ring:
/// duplicates and vertices that do not turn left by more than the tolerance
/// are dropped. A flat result becomes its two extreme points.
fn clean_convex_ring(ring: Vec<Point>) -> Vec<Point> {
    if ring.len() <= 1 {
        return ring;
    }
    let tol = tolerance(&ring);
    let mut stack: Vec<Point> = Vec::with_capacity(ring.len());
    for &p in &ring {
        if stack.last().is_some_and(|q| (p - q).norm() <= tol) {
            continue;
        }
        while stack.len() >= 2
            && !turns_left(stack[stack.len() - 2], stack[stack.len() - 1], p, tol)
        {
            stack.pop();
        }
        stack.push(p);
    }
    // Close the ring: the last vertices against the first, and the first
    // against its neighbours, until nothing changes.
    loop {
        let mut changed = false;
        while stack.len() >= 2 && (stack[stack.len() - 1] - stack[0]).norm() <= tol {
            stack.pop();
            changed = true;
        }
        while stack.len() >= 3
            && !turns_left(
                stack[stack.len() - 2],
                stack[stack.len() - 1],
                stack[0],
                tol,
            )
        {
            stack.pop();
            changed = true;
        }
        if stack.len() >= 3 && !turns_left(stack[stack.len() - 1], stack[0], stack[1], tol) {
            stack.remove(0);
            changed = true;
        }
        if !changed || stack.len() < 3 {
            break;
        }
    }
    if stack.len() >= 3 {
        // Start at the lowest (then leftmost) vertex.
        let s = lowest(&stack);
        stack.rotate_left(s);
        return stack;
    }
    extremes(&ring, tol)
}

/// The two extreme points of a (nearly) collinear point set, the lowest
/// (then leftmost) first; one point when all coincide within `tol`.
fn extremes(points: &[Point], tol: f64) -> Vec<Point> {
    let p0 = points[0];
    let far = points
        .iter()
        .copied()
        .max_by(|p, q| (p - p0).norm_squared().total_cmp(&(q - p0).norm_squared()))
        .unwrap_or(p0);
    let d = far - p0;
    if d.norm() <= tol {
        return vec![p0];
    }
    let key = |p: &Point| (p - p0).dot(&d);
    let lo = points
        .iter()
        .copied()
        .min_by(|p, q| key(p).total_cmp(&key(q)))
        .unwrap_or(p0);
    let hi = points
        .iter()
        .copied()
        .max_by(|p, q| key(p).total_cmp(&key(q)))
        .unwrap_or(p0);
    if hi.y < lo.y || (hi.y == lo.y && hi.x < lo.x) {
        vec![hi, lo]
    } else {
        vec![lo, hi]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon::{convex_hull, is_convex, signed_area2};
    use proptest::prelude::*;
    use std::f64::consts::{FRAC_PI_2, PI, TAU};

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    fn poly(v: &[(f64, f64)]) -> ConvexPolygon {
        ConvexPolygon {
            vertices: v.iter().map(|&(x, y)| p(x, y)).collect(),
        }
    }

    fn rod() -> ConvexPolygon {
        poly(&[(0.0, 0.0), (8.0, 0.0), (8.0, 1.0), (0.0, 1.0)])
    }

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> ConvexPolygon {
        poly(&[(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
    }

    /// Distance from `q` to the boundary of the ring (a point or segment
    /// for 1 or 2 points).
    fn boundary_dist(ring: &[Point], q: Point) -> f64 {
        let n = ring.len();
        if n == 1 {
            return (q - ring[0]).norm();
        }
        (0..n)
            .map(|i| crate::polygon::distance_point_segment(q, ring[i], ring[(i + 1) % n]))
            .fold(f64::INFINITY, f64::min)
    }

    /// Checks the shape of a merge result: ccw from its lowest vertex, every
    /// vertex a strict left turn, no duplicates, convex.
    fn assert_clean(v: &[Point]) {
        if v.len() >= 3 {
            assert!(signed_area2(v) > 0.0, "not ccw: {v:?}");
            assert!(is_convex(v), "not convex: {v:?}");
            let n = v.len();
            for i in 0..n {
                let (a, b, c) = (v[(i + n - 1) % n], v[i], v[(i + 1) % n]);
                assert!(b != a, "duplicate vertex in {v:?}");
                assert!(
                    cross(b - a, c - b) > 0.0,
                    "vertex {i} does not turn left: {v:?}"
                );
            }
        } else if v.len() == 2 {
            assert!(v[0] != v[1]);
        }
        if !v.is_empty() {
            assert_eq!(lowest(v), 0, "does not start at the lowest vertex: {v:?}");
        }
    }

    /// The merged sum must equal the hull of all vertex sums: its vertices
    /// are vertex sums (bitwise), both boundaries lie within `1e-9` of each
    /// other, and the areas agree.
    fn assert_equals_hull(a: &[Point], b: &[Point], merged: &[Point]) {
        let sums: Vec<Point> = a
            .iter()
            .flat_map(|p| b.iter().map(move |q| Point::new(p.x + q.x, p.y + q.y)))
            .collect();
        let hull = convex_hull(&sums);
        assert_clean(merged);
        for v in merged {
            assert!(sums.contains(v), "{v:?} is not a vertex sum");
            assert!(
                boundary_dist(&hull, *v) <= 1e-9,
                "{v:?} not on the hull {hull:?}"
            );
        }
        for h in &hull {
            assert!(
                boundary_dist(merged, *h) <= 1e-9,
                "hull vertex {h:?} not on the merged sum {merged:?}"
            );
        }
        if merged.len() >= 3 && hull.len() >= 3 {
            let (am, ah) = (signed_area2(merged), signed_area2(&hull));
            assert!(
                (am - ah).abs() <= 1e-9 * (1.0 + ah.abs()),
                "areas {am} vs {ah}"
            );
        }
        assert!(merged.len() <= hull.len().max(1));
    }

    #[test]
    fn rectangles_add_up() {
        let s = minkowski_sum(&rect(0.0, 0.0, 2.0, 1.0), &rect(-1.0, -1.0, 1.0, 1.0));
        assert_eq!(s, rect(-1.0, -1.0, 3.0, 2.0));
    }

    #[test]
    fn triangle_plus_its_reflection_is_a_hexagon() {
        let t = poly(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]);
        let s = minkowski_sum(&t, &reflect(&t));
        assert_eq!(
            s.vertices,
            vec![
                p(0.0, -1.0),
                p(1.0, -1.0),
                p(1.0, 0.0),
                p(0.0, 1.0),
                p(-1.0, 1.0),
                p(-1.0, 0.0)
            ]
        );
    }

    #[test]
    fn any_start_vertex_and_rotation() {
        let mut t = poly(&[(3.0, 1.0), (5.0, 2.0), (4.0, 4.0), (2.0, 3.0)]);
        let a = minkowski_sum(&t, &rod());
        t.vertices.rotate_left(2);
        let b = minkowski_sum(&t, &rod());
        assert_eq!(a, b);
        assert_equals_hull(&t.vertices, &rod().vertices, &a.vertices);
    }

    #[test]
    fn degenerate_inputs() {
        let pt = [p(1.0, 2.0)];
        let s1 = [p(0.0, 0.0), p(2.0, 1.0)];
        let s2 = [p(4.0, 2.0), p(0.0, 0.0)]; // parallel, other order
        let s3 = [p(0.0, 0.0), p(0.0, 3.0)];
        assert_eq!(minkowski_sum_points(&pt, &pt), vec![p(2.0, 4.0)]);
        assert_eq!(
            minkowski_sum_points(&pt, &s1),
            vec![p(1.0, 2.0), p(3.0, 3.0)]
        );
        assert_eq!(
            minkowski_sum_points(&s1, &s2),
            vec![p(0.0, 0.0), p(6.0, 3.0)]
        );
        assert_eq!(
            minkowski_sum_points(&s1, &s3),
            vec![p(0.0, 0.0), p(2.0, 1.0), p(2.0, 4.0), p(0.0, 3.0)]
        );
        // Anti-parallel directions are parallel too.
        let s4 = [p(0.0, 0.0), p(-2.0, -1.0)];
        assert_eq!(
            minkowski_sum_points(&s1, &s4),
            vec![p(-2.0, -1.0), p(2.0, 1.0)]
        );
        // A segment plus a triangle; a point plus a triangle.
        let t = [p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)];
        let st = minkowski_sum_points(&s3, &t);
        assert_eq!(st, vec![p(0.0, 0.0), p(1.0, 0.0), p(1.0, 3.0), p(0.0, 4.0)]);
        assert_eq!(
            minkowski_sum_points(&t, &pt),
            vec![p(1.0, 2.0), p(2.0, 2.0), p(1.0, 3.0)]
        );
        assert!(minkowski_sum_points(&[], &t).is_empty());
        // Duplicates in the input are ignored.
        let td = [
            p(0.0, 0.0),
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(0.0, 1.0),
            p(0.0, 0.0),
        ];
        assert_eq!(
            minkowski_sum_points(&td, &pt),
            minkowski_sum_points(&t, &pt)
        );
        let sd = [p(2.0, 1.0), p(2.0, 1.0), p(0.0, 0.0)];
        assert_eq!(
            minkowski_sum_points(&sd, &pt),
            vec![p(1.0, 2.0), p(3.0, 3.0)]
        );
    }

    #[test]
    fn reflect_and_place() {
        let r = reflect(&rod());
        assert!(signed_area2(&r.vertices) > 0.0);
        assert_eq!(r.vertices[2], p(-8.0, -1.0));
        let q = place(&rod().vertices, FRAC_PI_2);
        assert!((q.vertices[1] - p(0.0, 8.0)).norm() < 1e-12);
        assert!((q.vertices[2] - p(-1.0, 8.0)).norm() < 1e-12);
        assert!(signed_area2(&q.vertices) > 0.0);
    }

    /// The rod at θ = 0 against a rectangle: [x0 − 8, x1] × [y0 − 1, y1].
    #[test]
    fn rod_against_a_rectangle_at_zero() {
        let b = rect(10.0, 19.0, 12.0, 20.0);
        let c = c_obstacle(&b, &rod(), 0.0);
        assert_eq!(c, rect(2.0, 18.0, 12.0, 20.0));
    }

    /// SEEDS §A: 4 vertices at multiples of 90°, 8 otherwise.
    #[test]
    fn rod_against_a_rectangle_vertex_counts() {
        let b = rect(10.0, 19.0, 12.0, 20.0);
        for theta in [0.0, FRAC_PI_2, PI, 3.0 * FRAC_PI_2, TAU] {
            assert_eq!(
                c_obstacle(&b, &rod(), theta).vertices.len(),
                4,
                "θ = {theta}"
            );
        }
        for n in [4usize, 8, 32, 51, 70, 76, 203, 360] {
            for k in 0..n {
                let theta = k as f64 * TAU / n as f64;
                let c = c_obstacle(&b, &rod(), theta);
                assert_clean(&c.vertices);
                let right = (4 * k) % n == 0;
                assert_eq!(
                    c.vertices.len(),
                    if right { 4 } else { 8 },
                    "θ = {k}·2π/{n}"
                );
                assert_equals_hull(
                    &b.vertices,
                    &reflect(&place(&rod().vertices, theta)).vertices,
                    &c.vertices,
                );
            }
        }
    }

    #[test]
    fn disk_polygon_contains_the_disk() {
        let c = p(3.0, -2.0);
        for sides in [3usize, 4, 7, 32] {
            let v = disk_polygon(c, 1.5, sides);
            assert_eq!(v.len(), sides);
            assert_clean(&minkowski_sum_points(&v, &[p(0.0, 0.0)]));
            // Every edge's line is at distance >= radius from the centre.
            for i in 0..sides {
                let (a, b) = (v[i], v[(i + 1) % sides]);
                let d = cross(b - a, c - a) / (b - a).norm();
                assert!(d >= 1.5, "edge {i} at {d}");
                assert!(d <= 1.5 * (1.0 + 1e-12));
            }
        }
        assert_eq!(disk_polygon(c, 0.0, 32), vec![c]);
    }

    // ---------------------------------------------------------- properties

    /// Convex polygons as hulls of random points, with tiny and nearly
    /// parallel edges mixed in.
    fn convex_points() -> impl Strategy<Value = Vec<Point>> {
        let hull_of_random = prop::collection::vec((-50.0..50.0f64, -50.0..50.0f64), 3..14)
            .prop_map(|v| convex_hull(&v.iter().map(|&(x, y)| p(x, y)).collect::<Vec<_>>()));
        // A regular polygon, rotated and scaled, with vertices nudged by tiny
        // amounts (nearly parallel edges to other such polygons).
        let nudged_regular = (
            3usize..10,
            0.0..TAU,
            0.1..30.0f64,
            prop::collection::vec(-1.0..1.0f64, 20),
            -12i32..-5,
        )
            .prop_map(|(k, rot, r, noise, e)| {
                let eps = 10f64.powi(e);
                let pts: Vec<Point> = (0..k)
                    .map(|i| {
                        let a = rot + i as f64 * TAU / k as f64;
                        p(
                            r * a.cos() + eps * noise[2 * i],
                            r * a.sin() + eps * noise[2 * i + 1],
                        )
                    })
                    .collect();
                convex_hull(&pts)
            });
        // Axis-aligned boxes (exactly parallel edges), possibly with a tiny
        // extra edge cut off a corner.
        let boxes = (
            -20.0..20.0f64,
            -20.0..20.0f64,
            0.01..20.0f64,
            0.01..20.0f64,
            any::<bool>(),
            -13i32..-3,
        )
            .prop_map(|(x, y, w, h, cut, e)| {
                let mut v = vec![p(x, y), p(x + w, y), p(x + w, y + h), p(x, y + h)];
                if cut {
                    let d = 10f64.powi(e);
                    v[2] = p(x + w, y + h - d);
                    v.insert(3, p(x + w - d, y + h));
                }
                convex_hull(&v)
            });
        // A random hull with a point inserted a tiny distance off a vertex
        // (a tiny edge).
        let tiny_edge = (
            prop::collection::vec((-10.0..10.0f64, -10.0..10.0f64), 3..8),
            0.0..TAU,
            -14i32..-6,
        )
            .prop_map(|(v, a, e)| {
                let mut pts: Vec<Point> = v.iter().map(|&(x, y)| p(x, y)).collect();
                let d = 10f64.powi(e);
                pts.push(pts[0] + Vector::new(a.cos(), a.sin()) * d);
                convex_hull(&pts)
            });
        prop_oneof![hull_of_random, nudged_regular, boxes, tiny_edge]
            .prop_filter("area", |v| v.len() >= 3)
    }

    fn rotated(v: &[Point], theta: f64, eps_rot: f64) -> Vec<Point> {
        place(v, theta + eps_rot).vertices
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4000))]

        #[test]
        fn merged_sum_is_the_hull_of_vertex_sums(a in convex_points(), b in convex_points(), start in 0usize..20) {
            let mut a2 = a.clone();
            let k = start % a2.len();
            a2.rotate_left(k);
            let s = minkowski_sum_points(&a2, &b);
            assert!(s.len() >= 3);
            assert_equals_hull(&a2, &b, &s);
        }

        /// Nearly parallel edges: B against −B rotated by a tiny angle, and
        /// B against a copy of itself turned by a multiple of 90° plus a
        /// tiny angle.
        #[test]
        fn nearly_parallel_edges(a in convex_points(), e in -16i32..-4, quarter in 0u8..4, sign in any::<bool>()) {
            let eps = if sign { 1.0 } else { -1.0 } * 10f64.powi(e);
            let b = rotated(&a, quarter as f64 * FRAC_PI_2, eps);
            let s = minkowski_sum_points(&a, &b);
            assert_equals_hull(&a, &b, &s);
            let minus: Vec<Point> = b.iter().map(|q| p(-q.x, -q.y)).collect();
            let s = minkowski_sum_points(&a, &minus);
            assert_equals_hull(&a, &minus, &s);
        }

        /// Segments and points against polygons and each other.
        #[test]
        fn degenerate_pieces(a in convex_points(), s in ((-20.0..20.0f64, -20.0..20.0f64), (-20.0..20.0f64, -20.0..20.0f64)), pick in 0u8..4, e in -15i32..-3) {
            let (s0, s1) = (p((s.0).0, (s.0).1), p((s.1).0, (s.1).1));
            let seg = vec![s0, s1];
            let r = minkowski_sum_points(&seg, &a);
            assert!(r.len() >= 3);
            assert_equals_hull(&seg, &a, &r);
            let other = match pick {
                0 => vec![s1, s0],
                1 => vec![p(0.0, 0.0), Point::from(s1 - s0)],
                2 => vec![p(1.0, 1.0), p(1.0, 1.0) + (s1 - s0) * 0.5 + Vector::new(-(s1 - s0).y, (s1 - s0).x) * 10f64.powi(e)],
                _ => vec![p(3.0, -1.0)],
            };
            let r = minkowski_sum_points(&seg, &other);
            assert_equals_hull(&seg, &other, &r);
            if pick <= 1 && s0 != s1 {
                assert_eq!(r.len(), 2, "parallel segments sum to a segment: {r:?}");
            }
        }

        #[test]
        fn c_obstacle_is_b_plus_minus_a(a in convex_points(), b in convex_points(), theta in 0.0..TAU) {
            let pa = ConvexPolygon { vertices: a.clone() };
            let pb = ConvexPolygon { vertices: b.clone() };
            let c = c_obstacle(&pb, &pa, theta);
            let minus = reflect(&place(&a, theta));
            assert_equals_hull(&b, &minus.vertices, &c.vertices);
        }
    }
}
