//! The boundary of the free space of a point or disk robot among the world's
//! obstacles, exactly: line segments and circular arcs, linked into cycles
//! (for the Bug planners' boundary following, SPEC 3.9).
//!
//! The C-obstacle of a disk robot of radius r is each obstacle grown by r:
//! a polygon or rect grown is its edges pushed out by r joined by arcs of
//! radius r round its convex vertices, a disk grows into a disk of radius
//! R + r, a segment wall into a stadium (for r = 0 the wall's two sides,
//! a region of no width that nothing may cross). The outside of `bounds`
//! is an obstacle too (not grown: `bounds` limits the reference point).
//!
//! Every curve of every grown obstacle is oriented with its obstacle on the
//! left; the curves are cut where they meet, and a piece is kept when the
//! points just on its right are free: what is left is the boundary of the
//! union of the grown obstacles, touching and overlapping ones merged. The
//! pieces are linked end to start into cycles; where several pieces meet at
//! one point (obstacles touching at a point: a pinch of zero width) each
//! piece continues into the piece that bounds the same free wedge, so the
//! robot goes round touching obstacles as one.
//!
//! Following a cycle forward keeps the obstacle on the robot's left.
//! Tolerances are relative to the world's size: `1e-9` for parameters,
//! `1e-7` for joining pieces, `1e-6` for the free side of a piece.

use std::f64::consts::{PI, TAU};

use super::polygon::distance_point_segment;
use super::{Aabb, Point, Shape, Vector, World};

/// A segment or a counter-clockwise circular arc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Curve {
    /// From `a` to `b`.
    Segment { a: Point, b: Point },
    /// Counter-clockwise round `center` from the angle `start` through
    /// `sweep` radians (0 < sweep ≤ 2π).
    Arc {
        center: Point,
        radius: f64,
        start: f64,
        sweep: f64,
    },
}

impl Curve {
    /// Arc length.
    pub fn length(&self) -> f64 {
        match *self {
            Curve::Segment { a, b } => (b - a).norm(),
            Curve::Arc { radius, sweep, .. } => radius * sweep,
        }
    }

    /// The point at arc length `s` from the start (clamped to the curve).
    pub fn point_at(&self, s: f64) -> Point {
        match *self {
            Curve::Segment { a, b } => {
                let len = (b - a).norm();
                if len == 0.0 {
                    return a;
                }
                let t = (s / len).clamp(0.0, 1.0);
                if t == 1.0 { b } else { a + (b - a) * t }
            }
            Curve::Arc {
                center,
                radius,
                start,
                sweep,
            } => {
                let phi = start + (s / radius).clamp(0.0, sweep);
                center + Vector::new(phi.cos(), phi.sin()) * radius
            }
        }
    }

    pub fn start_point(&self) -> Point {
        self.point_at(0.0)
    }

    pub fn end_point(&self) -> Point {
        match *self {
            Curve::Segment { b, .. } => b,
            _ => self.point_at(self.length()),
        }
    }

    /// The unit tangent at arc length `s`, in the curve's direction.
    pub fn tangent_at(&self, s: f64) -> Vector {
        match *self {
            Curve::Segment { a, b } => unit(b - a),
            Curve::Arc {
                radius,
                start,
                sweep,
                ..
            } => {
                let phi = start + (s / radius).clamp(0.0, sweep);
                Vector::new(-phi.sin(), phi.cos())
            }
        }
    }

    /// The part from arc length `s0` to `s1` (s0 < s1).
    fn sub(&self, s0: f64, s1: f64) -> Curve {
        match *self {
            Curve::Segment { .. } => Curve::Segment {
                a: self.point_at(s0),
                b: self.point_at(s1),
            },
            Curve::Arc {
                center,
                radius,
                start,
                ..
            } => Curve::Arc {
                center,
                radius,
                start: start + s0 / radius,
                sweep: (s1 - s0) / radius,
            },
        }
    }

    /// The arc length of the point of the curve nearest `p` (the closest
    /// one by arc length when `p` is on the curve).
    fn param_of(&self, p: Point) -> f64 {
        match *self {
            Curve::Segment { a, b } => {
                let d = b - a;
                let len2 = d.norm_squared();
                if len2 == 0.0 {
                    return 0.0;
                }
                ((p - a).dot(&d) / len2).clamp(0.0, 1.0) * len2.sqrt()
            }
            Curve::Arc {
                center,
                radius,
                start,
                sweep,
            } => {
                let v = p - center;
                let phi = (v.y.atan2(v.x) - start).rem_euclid(TAU);
                if phi <= sweep {
                    phi * radius
                } else if phi - sweep < TAU - phi {
                    sweep * radius
                } else {
                    0.0
                }
            }
        }
    }

    /// The arc length in [`lo`, `hi`] of the point nearest `p`, and its
    /// distance.
    pub fn closest_within(&self, p: Point, lo: f64, hi: f64) -> (f64, f64) {
        let mut best = (lo, (self.point_at(lo) - p).norm());
        let d_hi = (self.point_at(hi) - p).norm();
        if d_hi < best.1 {
            best = (hi, d_hi);
        }
        let s = match *self {
            Curve::Segment { .. } => Some(self.param_of(p)),
            Curve::Arc {
                center,
                radius,
                start,
                ..
            } => {
                let v = p - center;
                (v.norm() > 0.0).then(|| (v.y.atan2(v.x) - start).rem_euclid(TAU) * radius)
            }
        };
        if let Some(s) = s.filter(|s| *s > lo && *s < hi) {
            let d = (self.point_at(s) - p).norm();
            if d < best.1 {
                best = (s, d);
            }
        }
        best
    }

    fn bbox(&self) -> Aabb {
        match *self {
            Curve::Segment { a, b } => Aabb::from_corners(a, b),
            Curve::Arc { center, radius, .. } => Aabb::from_corners(
                center - Vector::new(radius, radius),
                center + Vector::new(radius, radius),
            ),
        }
    }

    /// Whether the angle `theta` (radians) lies on the arc, within `eps`
    /// radians; always for a segment.
    fn spans_angle(&self, theta: f64, eps: f64) -> bool {
        match *self {
            Curve::Segment { .. } => true,
            Curve::Arc { start, sweep, .. } => {
                let phi = (theta - start).rem_euclid(TAU);
                phi <= sweep + eps || phi >= TAU - eps
            }
        }
    }

    /// The points of the curve within `eps` of the line segment `p`–`q`,
    /// as `(t, s)`: `t` in [0, 1] along `p`–`q`, `s` the arc length on the
    /// curve. A stretch along the segment gives its two ends.
    pub fn meet_segment(&self, p: Point, q: Point, eps: f64) -> Vec<(f64, f64)> {
        let line = Curve::Segment { a: p, b: q };
        let len = (q - p).norm();
        if len == 0.0 {
            return Vec::new();
        }
        meet(&line, self, eps)
            .into_iter()
            .map(|x| (line.param_of(x) / len, self.param_of(x)))
            .collect()
    }

    /// The arc lengths of the points where the curve meets the circle of
    /// radius `r` round `c` (within `eps`).
    pub fn meet_circle(&self, c: Point, r: f64, eps: f64) -> Vec<f64> {
        let circle = Curve::Arc {
            center: c,
            radius: r,
            start: 0.0,
            sweep: TAU,
        };
        meet(self, &circle, eps)
            .into_iter()
            .map(|x| self.param_of(x))
            .collect()
    }
}

fn unit(v: Vector) -> Vector {
    let n = v.norm();
    if n > 0.0 { v / n } else { Vector::zeros() }
}

fn cross(a: Vector, b: Vector) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The right-hand normal of a direction.
fn right(v: Vector) -> Vector {
    Vector::new(v.y, -v.x)
}

/// The angle to turn `from` clockwise to reach `to`, in [0, 2π).
fn cw_angle(from: Vector, to: Vector) -> f64 {
    let a = from.y.atan2(from.x) - to.y.atan2(to.x);
    let a = a.rem_euclid(TAU);
    if a >= TAU { 0.0 } else { a }
}

/// Points where two curves meet (within `eps`); where they overlap, the
/// ends of the overlap.
fn meet(c1: &Curve, c2: &Curve, eps: f64) -> Vec<Point> {
    let mut out = Vec::new();
    match (*c1, *c2) {
        (Curve::Segment { a, b }, Curve::Segment { a: c, b: d }) => {
            let (r, s) = (b - a, d - c);
            let (lr, ls) = (r.norm(), s.norm());
            if lr == 0.0 || ls == 0.0 {
                return out;
            }
            let denom = cross(r, s);
            if denom.abs() <= 1e-12 * lr * ls {
                // Parallel: collinear when c is on the line of a-b.
                if cross(r, c - a).abs() / lr > eps {
                    return out;
                }
                for (x, (p0, p1)) in [(a, (c, d)), (b, (c, d)), (c, (a, b)), (d, (a, b))] {
                    if distance_point_segment(x, p0, p1) <= eps {
                        out.push(x);
                    }
                }
                return out;
            }
            let t = cross(c - a, s) / denom;
            let u = cross(c - a, r) / denom;
            let (et, eu) = (eps / lr, eps / ls);
            if t >= -et && t <= 1.0 + et && u >= -eu && u <= 1.0 + eu {
                out.push(a + r * t.clamp(0.0, 1.0));
            }
        }
        (Curve::Segment { a, b }, arc @ Curve::Arc { center, radius, .. })
        | (arc @ Curve::Arc { center, radius, .. }, Curve::Segment { a, b }) => {
            let d = b - a;
            let len = d.norm();
            if len == 0.0 {
                return out;
            }
            let u = d / len;
            // Foot of the centre on the line, and the half chord.
            let tf = (center - a).dot(&u);
            let foot = a + u * tf;
            let h = (center - foot).norm();
            if h > radius + eps {
                return out;
            }
            let half = (radius * radius - h * h).max(0.0).sqrt();
            let ts: Vec<f64> = if half <= eps {
                vec![tf]
            } else {
                vec![tf - half, tf + half]
            };
            for t in ts {
                if t < -eps || t > len + eps {
                    continue;
                }
                let x = a + u * t.clamp(0.0, len);
                let v = x - center;
                if arc.spans_angle(v.y.atan2(v.x), eps / radius) {
                    out.push(x);
                }
            }
        }
        (
            a1 @ Curve::Arc {
                center: c1,
                radius: r1,
                ..
            },
            a2 @ Curve::Arc {
                center: c2,
                radius: r2,
                ..
            },
        ) => {
            let v = c2 - c1;
            let dc = v.norm();
            if dc <= eps && (r1 - r2).abs() <= eps {
                // The same circle: the ends of each arc on the other.
                for (x, other) in [
                    (a1.start_point(), a2),
                    (a1.end_point(), a2),
                    (a2.start_point(), a1),
                    (a2.end_point(), a1),
                ] {
                    let w = x - c1;
                    if other.spans_angle(w.y.atan2(w.x), eps / r1) {
                        out.push(x);
                    }
                }
                return out;
            }
            if dc <= eps || dc > r1 + r2 + eps || dc < (r1 - r2).abs() - eps {
                return out;
            }
            let along = (r1 * r1 - r2 * r2 + dc * dc) / (2.0 * dc);
            let h = (r1 * r1 - along * along).max(0.0).sqrt();
            let u = v / dc;
            let base = c1 + u * along;
            let perp = Vector::new(-u.y, u.x);
            let xs = if h <= eps {
                vec![base]
            } else {
                vec![base + perp * h, base - perp * h]
            };
            for x in xs {
                let (w1, w2) = (x - c1, x - c2);
                if a1.spans_angle(w1.y.atan2(w1.x), eps / r1)
                    && a2.spans_angle(w2.y.atan2(w2.x), eps / r2)
                {
                    out.push(x);
                }
            }
        }
    }
    out
}

/// A grown obstacle, for telling which side of a piece is free.
#[derive(Clone, Debug)]
enum Body {
    /// A simple counter-clockwise polygon grown by `r`.
    Polygon {
        outline: Vec<Point>,
        r: f64,
    },
    Disk {
        center: Point,
        radius: f64,
    },
    /// A segment grown by `r` (a stadium; no interior when r = 0).
    Wall {
        a: Point,
        b: Point,
        r: f64,
    },
    /// Everything outside `bounds`.
    Outside(Aabb),
}

impl Body {
    /// How deep `p` lies inside (negative outside).
    fn depth(&self, p: Point) -> f64 {
        match self {
            Body::Polygon { outline, r } => {
                let n = outline.len();
                let mut dist = f64::INFINITY;
                let mut inside = false;
                for i in 0..n {
                    let (a, b) = (outline[i], outline[(i + 1) % n]);
                    dist = dist.min(distance_point_segment(p, a, b));
                    if (a.y > p.y) != (b.y > p.y) {
                        let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
                        if p.x < x {
                            inside = !inside;
                        }
                    }
                }
                if inside { dist + r } else { r - dist }
            }
            Body::Disk { center, radius } => radius - (p - center).norm(),
            Body::Wall { a, b, r } => r - distance_point_segment(p, *a, *b),
            Body::Outside(b) => (b.min.x - p.x)
                .max(p.x - b.max.x)
                .max(b.min.y - p.y)
                .max(p.y - b.max.y),
        }
    }

    fn bbox(&self) -> Aabb {
        let grow = |b: Aabb, r: f64| Aabb {
            min: b.min - Vector::new(r, r),
            max: b.max + Vector::new(r, r),
        };
        match self {
            Body::Polygon { outline, r } => grow(Aabb::around(outline), *r),
            Body::Disk { center, radius } => grow(Aabb::around(&[*center]), *radius),
            Body::Wall { a, b, r } => grow(Aabb::from_corners(*a, *b), *r),
            Body::Outside(_) => Aabb {
                min: Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
                max: Point::new(f64::INFINITY, f64::INFINITY),
            },
        }
    }
}

/// Why the boundary could not be built.
#[derive(Clone, Debug, PartialEq)]
pub enum BoundaryError {
    /// The world has a `grid` obstacle (SPEC 3.9: not for `bug`).
    Grid(String),
    /// More curves than [`MAX_CURVES`].
    TooLarge(usize),
    /// The time limit passed while building it.
    TimeUp,
}

/// The most curves (grown edges, arcs, walls) a boundary is built from: the
/// construction compares every pair of nearby curves.
pub const MAX_CURVES: usize = 20_000;

/// One piece of the boundary.
#[derive(Clone, Debug)]
pub struct Piece {
    pub curve: Curve,
    pub len: f64,
    /// The cycle it belongs to and its index there (`None`: the pieces
    /// could not be linked into a cycle here).
    pub cycle: Option<(usize, usize)>,
}

/// A closed chain of pieces, followed forward with the obstacle on the left.
#[derive(Clone, Debug)]
pub struct Cycle {
    /// Indices into [`FreeBoundary::pieces`].
    pub pieces: Vec<usize>,
    /// Arc length from the cycle's start to the start of each piece, and
    /// the whole length last.
    pub offsets: Vec<f64>,
}

impl Cycle {
    pub fn length(&self) -> f64 {
        self.offsets.last().copied().unwrap_or(0.0)
    }

    /// The index of the piece at arc length `sigma` (in [0, length)).
    fn index_at(&self, sigma: f64) -> usize {
        let k = self.offsets.partition_point(|&o| o <= sigma);
        k.saturating_sub(1).min(self.pieces.len().saturating_sub(1))
    }
}

/// A place on the boundary: a cycle and the arc length along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pos {
    pub cycle: usize,
    pub sigma: f64,
}

/// Where a straight motion first enters an obstacle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Entry {
    /// Along the motion, in [0, 1].
    pub t: f64,
    pub point: Point,
    /// Where on the boundary (`None` on a piece outside every cycle).
    pub pos: Option<Pos>,
}

/// The boundary of the free space of a robot of radius `radius`.
#[derive(Clone, Debug)]
pub struct FreeBoundary {
    pub radius: f64,
    pub pieces: Vec<Piece>,
    pub cycles: Vec<Cycle>,
    /// The world's size, for tolerances.
    pub scale: f64,
    bodies: Vec<Body>,
}

/// The oriented curves of one grown obstacle.
fn grown_curves(shape: &Shape, r: f64, curves: &mut Vec<Curve>) -> Option<Body> {
    let polygon = |outline: &[Point], curves: &mut Vec<Curve>| {
        let n = outline.len();
        for i in 0..n {
            let (a, b) = (outline[i], outline[(i + 1) % n]);
            let nr = right(unit(b - a)) * r;
            curves.push(Curve::Segment {
                a: a + nr,
                b: b + nr,
            });
            if r > 0.0 {
                let c = outline[(i + 2) % n];
                let (e0, e1) = (b - a, c - b);
                if cross(e0, e1) > 0.0 {
                    let (n0, n1) = (right(e0), right(e1));
                    let start = n0.y.atan2(n0.x);
                    let sweep = (n1.y.atan2(n1.x) - start).rem_euclid(TAU);
                    if sweep > 0.0 && sweep < PI {
                        curves.push(Curve::Arc {
                            center: b,
                            radius: r,
                            start,
                            sweep,
                        });
                    }
                }
            }
        }
    };
    match shape {
        Shape::Polygon { outline, .. } => {
            polygon(outline, curves);
            Some(Body::Polygon {
                outline: outline.clone(),
                r,
            })
        }
        Shape::Rect(b) => {
            let corners = b.corners().to_vec();
            polygon(&corners, curves);
            Some(Body::Polygon {
                outline: corners,
                r,
            })
        }
        Shape::Disk { center, radius } => {
            curves.push(Curve::Arc {
                center: *center,
                radius: radius + r,
                start: 0.0,
                sweep: TAU,
            });
            Some(Body::Disk {
                center: *center,
                radius: radius + r,
            })
        }
        Shape::Segment(a, b) => {
            let (a, b) = (*a, *b);
            let d = unit(b - a);
            if d == Vector::zeros() {
                if r > 0.0 {
                    curves.push(Curve::Arc {
                        center: a,
                        radius: r,
                        start: 0.0,
                        sweep: TAU,
                    });
                }
            } else if r > 0.0 {
                let nr = right(d) * r;
                curves.push(Curve::Segment {
                    a: a + nr,
                    b: b + nr,
                });
                curves.push(Curve::Arc {
                    center: b,
                    radius: r,
                    start: nr.y.atan2(nr.x),
                    sweep: PI,
                });
                curves.push(Curve::Segment {
                    a: b - nr,
                    b: a - nr,
                });
                curves.push(Curve::Arc {
                    center: a,
                    radius: r,
                    start: (-nr.y).atan2(-nr.x),
                    sweep: PI,
                });
            } else {
                curves.push(Curve::Segment { a, b });
                curves.push(Curve::Segment { a: b, b: a });
            }
            Some(Body::Wall { a, b, r })
        }
        Shape::Grid(_) => None,
    }
}

impl FreeBoundary {
    /// The boundary of the free space of a disk robot of radius `radius`
    /// (0: a point) in `world`. `time_up` is asked now and then.
    pub fn build(
        world: &World,
        radius: f64,
        time_up: &dyn Fn() -> bool,
    ) -> Result<Self, BoundaryError> {
        let b = world.bounds;
        let mut scale = b.width().max(b.height()).max(1.0);
        scale = scale
            .max(b.min.coords.abs().max())
            .max(b.max.coords.abs().max());
        let mut curves = Vec::new();
        let mut bodies = Vec::new();
        for o in &world.obstacles {
            match grown_curves(&o.shape, radius, &mut curves) {
                Some(body) => bodies.push(body),
                None => return Err(BoundaryError::Grid(o.name.clone())),
            }
            if curves.len() > MAX_CURVES {
                return Err(BoundaryError::TooLarge(curves.len()));
            }
        }
        // The outside of the bounds, clockwise (inside on the right).
        let [c0, c1, c2, c3] = b.corners();
        for (p, q) in [(c0, c3), (c3, c2), (c2, c1), (c1, c0)] {
            curves.push(Curve::Segment { a: p, b: q });
        }
        bodies.push(Body::Outside(b));
        let eps = 1e-9 * scale;
        let link = 1e-7 * scale;
        let side = 1e-6 * scale;

        // Cut every curve where another meets it.
        let boxes: Vec<Aabb> = curves.iter().map(Curve::bbox).collect();
        let mut cuts: Vec<Vec<f64>> = curves.iter().map(|c| vec![0.0, c.length()]).collect();
        for i in 0..curves.len() {
            if i % 64 == 0 && time_up() {
                return Err(BoundaryError::TimeUp);
            }
            let bi = grow(&boxes[i], link);
            for j in i + 1..curves.len() {
                if !bi.meets(&boxes[j]) {
                    continue;
                }
                for x in meet(&curves[i], &curves[j], eps) {
                    cuts[i].push(curves[i].param_of(x));
                    cuts[j].push(curves[j].param_of(x));
                }
            }
        }
        let body_boxes: Vec<Aabb> = bodies.iter().map(Body::bbox).collect();
        let mut pieces: Vec<Piece> = Vec::new();
        for (i, curve) in curves.iter().enumerate() {
            if i % 64 == 0 && time_up() {
                return Err(BoundaryError::TimeUp);
            }
            let mut s = std::mem::take(&mut cuts[i]);
            s.sort_by(f64::total_cmp);
            s.dedup_by(|x, y| (*x - *y).abs() <= eps);
            for w in s.windows(2) {
                if w[1] - w[0] <= link {
                    continue;
                }
                let sub = curve.sub(w[0], w[1]);
                let len = sub.length();
                let m = sub.point_at(len / 2.0);
                let q = m + right(sub.tangent_at(len / 2.0)) * side;
                let covered = bodies
                    .iter()
                    .zip(&body_boxes)
                    .any(|(body, bb)| bb.contains(q) && body.depth(q) > side / 2.0);
                let duplicate = pieces.iter().any(|p| same_piece(&p.curve, &sub, link));
                if !covered && !duplicate {
                    pieces.push(Piece {
                        curve: sub,
                        len,
                        cycle: None,
                    });
                }
            }
        }

        // Link each piece to the one bounding the same free wedge.
        let n = pieces.len();
        let chord = 1e-4 * scale;
        let mut next: Vec<Option<usize>> = vec![None; n];
        for i in 0..n {
            if i % 256 == 0 && time_up() {
                return Err(BoundaryError::TimeUp);
            }
            let end = pieces[i].curve.end_point();
            let back = direction_back(&pieces[i], chord);
            let mut best: Option<(f64, usize)> = None;
            for (j, pj) in pieces.iter().enumerate() {
                if (pj.curve.start_point() - end).norm() > link {
                    continue;
                }
                let out = direction_out(pj, chord);
                // Counter-clockwise from the way back: the first piece
                // bounds the free wedge on the right of piece i.
                let mut a = cw_angle(out, back);
                if a <= 1e-12 {
                    a = TAU;
                }
                if best.is_none_or(|(b, _)| a < b) {
                    best = Some((a, j));
                }
            }
            next[i] = best.map(|(_, j)| j);
        }
        let mut cycles = Vec::new();
        let mut state = vec![0u8; n]; // 0 new, 1 on the current walk, 2 done
        for first in 0..n {
            if state[first] != 0 {
                continue;
            }
            let mut walk = vec![first];
            state[first] = 1;
            let mut at = first;
            let closed = loop {
                match next[at] {
                    Some(j) if j == first => break true,
                    Some(j) if state[j] == 0 => {
                        state[j] = 1;
                        walk.push(j);
                        at = j;
                    }
                    _ => break false,
                }
            };
            for &k in &walk {
                state[k] = 2;
            }
            if closed {
                let c = cycles.len();
                let mut offsets = Vec::with_capacity(walk.len() + 1);
                let mut total = 0.0;
                for (idx, &k) in walk.iter().enumerate() {
                    pieces[k].cycle = Some((c, idx));
                    offsets.push(total);
                    total += pieces[k].len;
                }
                offsets.push(total);
                cycles.push(Cycle {
                    pieces: walk,
                    offsets,
                });
            }
        }
        Ok(FreeBoundary {
            radius,
            pieces,
            cycles,
            scale,
            bodies,
        })
    }

    /// Tolerance on arc lengths and distances.
    pub fn eps(&self) -> f64 {
        1e-9 * self.scale
    }

    /// The piece at `pos` and the arc length on it.
    pub fn piece_at(&self, pos: Pos) -> (usize, f64) {
        let c = &self.cycles[pos.cycle];
        let k = c.index_at(pos.sigma);
        (
            c.pieces[k],
            (pos.sigma - c.offsets[k]).clamp(0.0, self.pieces[c.pieces[k]].len),
        )
    }

    pub fn point(&self, pos: Pos) -> Point {
        let (p, s) = self.piece_at(pos);
        self.pieces[p].curve.point_at(s)
    }

    /// The unit normal at `pos` pointing into the free space: the side of
    /// the boundary `pos` is on (a wall of no thickness has a position on
    /// each side of each of its points, with opposite normals).
    pub fn free_normal(&self, pos: Pos) -> Vector {
        let (p, s) = self.piece_at(pos);
        unit(right(self.pieces[p].curve.tangent_at(s)))
    }

    /// `pos` moved by `by` along its cycle (negative: backward), wrapped.
    pub fn moved(&self, pos: Pos, by: f64) -> Pos {
        let len = self.cycles[pos.cycle].length();
        let mut sigma = (pos.sigma + by).rem_euclid(len.max(f64::MIN_POSITIVE));
        if sigma >= len {
            sigma = 0.0;
        }
        Pos {
            cycle: pos.cycle,
            sigma,
        }
    }

    /// The position of arc length `s` on piece `p` (if it is on a cycle).
    pub fn pos_of(&self, p: usize, s: f64) -> Option<Pos> {
        let (c, k) = self.pieces[p].cycle?;
        let sigma = self.cycles[c].offsets[k] + s;
        Some(self.moved(Pos { cycle: c, sigma }, 0.0))
    }

    /// Whether leaving the boundary at `pos` in direction `d` moves into
    /// free space (or along the boundary) rather than into the obstacle.
    pub fn departs_freely(&self, pos: Pos, d: Vector) -> bool {
        let c = &self.cycles[pos.cycle];
        let k = c.index_at(pos.sigma);
        let s = pos.sigma - c.offsets[k];
        let here = c.pieces[k];
        let eps = self.eps();
        let n = c.pieces.len();
        if s <= eps {
            self.wedge_free(c.pieces[(k + n - 1) % n], here, d)
        } else if s >= self.pieces[here].len - eps {
            self.wedge_free(here, c.pieces[(k + 1) % n], d)
        } else {
            let normal = right(self.pieces[here].curve.tangent_at(s));
            unit(d).dot(&normal) >= -1e-9
        }
    }

    /// Whether a ray arriving at `pos` in direction `d` goes on into the
    /// open free space, not along the boundary: `pos` is then a
    /// discontinuity of a range sensor's readings (a silhouette point).
    pub fn ray_passes(&self, pos: Pos, d: Vector) -> bool {
        let c = &self.cycles[pos.cycle];
        let k = c.index_at(pos.sigma);
        let s = pos.sigma - c.offsets[k];
        let here = c.pieces[k];
        let eps = self.eps();
        let n = c.pieces.len();
        let (a, b) = if s <= eps {
            (c.pieces[(k + n - 1) % n], here)
        } else if s >= self.pieces[here].len - eps {
            (here, c.pieces[(k + 1) % n])
        } else {
            let normal = right(self.pieces[here].curve.tangent_at(s));
            return unit(d).dot(&normal) > 1e-9;
        };
        let chord = 1e-4 * self.scale;
        let out = direction_out(&self.pieces[b], chord);
        let back = direction_back(&self.pieces[a], chord);
        let (wedge, turn) = (cw_angle(out, back), cw_angle(out, d));
        turn > 1e-7 && turn < wedge - 1e-7
    }

    /// Whether direction `d` from the joint where piece `a` ends and `b`
    /// starts lies in the free wedge between them.
    fn wedge_free(&self, a: usize, b: usize, d: Vector) -> bool {
        let chord = 1e-4 * self.scale;
        let (pa, pb) = (&self.pieces[a], &self.pieces[b]);
        let out = direction_out(pb, chord);
        let back = direction_back(pa, chord);
        let wedge = cw_angle(out, back);
        let turn = cw_angle(out, d);
        let straight = |p: &Piece| matches!(p.curve, Curve::Segment { .. });
        if wedge <= 1e-9 && straight(pa) && straight(pb) {
            // The tip of a wall of no width: free all round.
            return true;
        }
        turn <= wedge + 1e-9 || turn >= TAU - 1e-9
    }

    /// Where the straight motion from `p` to `q` first enters an obstacle
    /// (touching and sliding along the boundary do not count); `from` is
    /// `p`'s place on the boundary when the robot stands on it.
    pub fn first_entry(&self, p: Point, from: Option<Pos>, q: Point) -> Option<Entry> {
        let d = q - p;
        let len = d.norm();
        if len <= self.eps() {
            return None;
        }
        if let Some(pos) = from
            && !self.departs_freely(pos, d)
        {
            return Some(Entry {
                t: 0.0,
                point: self.point(pos),
                pos: Some(pos),
            });
        }
        let eps = self.eps();
        let skip = if from.is_some() {
            1e-7 * self.scale / len
        } else {
            -1.0
        };
        let mbox = grow(&Aabb::from_corners(p, q), 1e-7 * self.scale);
        let mut best: Option<Entry> = None;
        for (i, piece) in self.pieces.iter().enumerate() {
            if !mbox.meets(&piece.curve.bbox()) {
                continue;
            }
            for (t, s) in piece.curve.meet_segment(p, q, eps) {
                if t <= skip || t >= 1.0 - eps / len || best.is_some_and(|b| b.t <= t) {
                    continue;
                }
                let entering = match self.pos_of(i, s) {
                    Some(pos) => !self.departs_freely(pos, d),
                    None => unit(d).dot(&right(piece.curve.tangent_at(s))) < -1e-9,
                };
                if entering {
                    best = Some(Entry {
                        t,
                        point: piece.curve.point_at(s),
                        pos: self.pos_of(i, s),
                    });
                }
            }
        }
        best
    }

    /// Whether `p` lies strictly inside a grown obstacle (deeper than
    /// `margin`) or outside the bounds.
    pub fn blocked(&self, p: Point, margin: f64) -> bool {
        self.bodies.iter().any(|b| b.depth(p) > margin)
    }
}

fn grow(b: &Aabb, by: f64) -> Aabb {
    Aabb {
        min: b.min - Vector::new(by, by),
        max: b.max + Vector::new(by, by),
    }
}

/// The direction from a piece's start to a point a little along it (the
/// chord shows on which side an arc bends when tangents agree).
fn direction_out(p: &Piece, chord: f64) -> Vector {
    let s = chord.min(p.len / 2.0);
    unit(p.curve.point_at(s) - p.curve.start_point())
}

/// The direction from a piece's end back to a point a little before it.
fn direction_back(p: &Piece, chord: f64) -> Vector {
    let s = chord.min(p.len / 2.0);
    unit(p.curve.point_at(p.len - s) - p.curve.end_point())
}

fn same_piece(a: &Curve, b: &Curve, tol: f64) -> bool {
    let ends = (a.start_point() - b.start_point()).norm() <= tol
        && (a.end_point() - b.end_point()).norm() <= tol;
    ends && match (a, b) {
        (Curve::Segment { .. }, Curve::Segment { .. }) => true,
        (
            Curve::Arc {
                center: c1,
                radius: r1,
                ..
            },
            Curve::Arc {
                center: c2,
                radius: r2,
                ..
            },
        ) => (c1 - c2).norm() <= tol && (r1 - r2).abs() <= tol,
        _ => false,
    }
}

/// The polyline a robot drives along `curve` from arc length `s0` to `s1`
/// (`s1 < s0`: backward), its first point left out. A segment is its end;
/// an arc is the polygon circumscribed about it, whose every chord is
/// tangent to the arc, so the robot never comes nearer the arc's centre
/// than the arc's radius (it touches, as on the arc): vertices every at
/// most 5°, on the radius enlarged by 1/cos(half the step). The polyline is
/// a little longer than the arc; the planners report the arc's length.
pub fn drive_along(curve: &Curve, s0: f64, s1: f64, out: &mut Vec<Point>) {
    match *curve {
        Curve::Segment { .. } => out.push(curve.point_at(s1)),
        Curve::Arc {
            center,
            radius,
            start,
            ..
        } => {
            let (a0, a1) = (start + s0 / radius, start + s1 / radius);
            let turn = a1 - a0;
            let n = (turn.abs() / 5f64.to_radians()).ceil().max(1.0) as usize;
            let step = turn / n as f64;
            let outer = radius / (step.abs() / 2.0).cos();
            for k in 0..n {
                let phi = a0 + step * (k as f64 + 0.5);
                out.push(center + Vector::new(phi.cos(), phi.sin()) * outer);
            }
            out.push(curve.point_at(s1));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::world_in;

    fn world(obstacles: Vec<Shape>) -> World {
        world_in(
            Aabb::from_corners(Point::new(-10.0, -10.0), Point::new(30.0, 30.0)),
            obstacles,
        )
    }

    fn square(x0: f64, y0: f64, side: f64) -> Shape {
        Shape::Rect(Aabb::from_corners(
            Point::new(x0, y0),
            Point::new(x0 + side, y0 + side),
        ))
    }

    fn lengths(b: &FreeBoundary) -> Vec<f64> {
        let mut l: Vec<f64> = b.cycles.iter().map(Cycle::length).collect();
        l.sort_by(f64::total_cmp);
        l
    }

    #[test]
    fn a_square_grown_by_a_disk_is_its_perimeter_plus_a_circle() {
        let w = world(vec![square(0.0, 0.0, 4.0)]);
        let b = FreeBoundary::build(&w, 0.5, &|| false).expect("built");
        let l = lengths(&b);
        // The bounds and the grown square.
        assert_eq!(l.len(), 2, "{l:?}");
        assert!((l[0] - (16.0 + TAU * 0.5)).abs() < 1e-9, "{l:?}");
        assert!((l[1] - 160.0).abs() < 1e-9, "{l:?}");
    }

    #[test]
    fn overlapping_and_touching_obstacles_merge() {
        // Two squares sharing an edge and a disk touching the second.
        let w = world(vec![
            square(0.0, 0.0, 2.0),
            square(2.0, 0.0, 2.0),
            Shape::Disk {
                center: Point::new(5.0, 1.0),
                radius: 1.0,
            },
        ]);
        let b = FreeBoundary::build(&w, 0.0, &|| false).expect("built");
        let l = lengths(&b);
        assert_eq!(l.len(), 2, "{l:?}");
        // 4 × 2 rectangle (12) minus the touching point, plus the circle.
        assert!((l[0] - (12.0 + TAU)).abs() < 1e-9, "{l:?}");
    }

    #[test]
    fn a_wall_without_thickness_has_two_sides() {
        let w = world(vec![Shape::Segment(
            Point::new(0.0, 0.0),
            Point::new(3.0, 4.0),
        )]);
        let b = FreeBoundary::build(&w, 0.0, &|| false).expect("built");
        assert!((lengths(&b)[0] - 10.0).abs() < 1e-9);
        // Nothing crosses it; sliding along it is free.
        let e = b
            .first_entry(Point::new(0.0, 2.0), None, Point::new(3.0, 2.0))
            .expect("the wall stops the motion");
        assert!((e.point - Point::new(1.5, 2.0)).norm() < 1e-9);
        assert!(
            b.first_entry(Point::new(-3.0, -4.0), None, Point::new(6.0, 8.0))
                .is_none()
        );
    }

    #[test]
    fn a_non_convex_polygon_keeps_its_reflex_corner() {
        // An L: 3×3 minus the top-right 2×2.
        let outline = vec![
            Point::new(0.0, 0.0),
            Point::new(3.0, 0.0),
            Point::new(3.0, 1.0),
            Point::new(1.0, 1.0),
            Point::new(1.0, 3.0),
            Point::new(0.0, 3.0),
        ];
        let w = world(vec![Shape::Polygon {
            outline,
            pieces: Vec::new(),
        }]);
        let r = 0.25;
        let b = FreeBoundary::build(&w, r, &|| false).expect("built");
        // The perimeter 12, less r on each side of the reflex corner, plus
        // arcs round the convex corners: 5 quarter turns.
        let l = lengths(&b);
        assert!(
            (l[0] - (12.0 - 2.0 * r + 2.5 * PI * r)).abs() < 1e-9,
            "{l:?}"
        );
    }
}
