//! Time (SPEC 2.9): moving obstacles, trajectories, and the validator of a
//! trajectory in space-time.
//!
//! A moving obstacle translates along a route of timed waypoints: at its
//! first point before its first time, straight at constant speed between
//! waypoints, and after its last time it stays there or vanishes (absent
//! from that instant on). A trajectory is a list of `(x, y, θ, t)` with
//! times increasing from 0: between two points the robot moves straight at
//! constant speed, at most its `speed`, or waits; after its last point it
//! stays there forever.
//!
//! # The validator in space-time, exactly
//! [`validate_trajectory`] checks the trajectory's path against the static
//! world with the validator of SPEC 3.0, its timing (times increase from 0,
//! no segment faster than `speed`, relative slack 1e-9), and every moving
//! obstacle exactly. The times at which the robot or an obstacle changes
//! course cut time into intervals in which both move linearly (the last one
//! reaching the moment after which nothing moves, so the parked robot is
//! checked against every obstacle that later drives through it). In one
//! interval the robot's body `B` (it only translates: a timed trajectory
//! turns nowhere, SPEC 2.9) and an obstacle's convex piece `O` overlap at
//! some instant exactly when the piece's motion *relative to the robot*,
//! a straight translation by `d`, sweeps into `B`: `O ⊕ [0, d]`, the convex
//! hull of the piece at the interval's two ends, overlaps `B`. So:
//! - disk robot and disk obstacle: the closest approach of the relative
//!   motion of their centres, in closed form, against the sum of the radii;
//! - a disk (or point) robot and a polygon piece: the distance from the
//!   robot's centre to the swept hull, against the radius (for a point, its
//!   depth inside the hull);
//! - a polygon robot and a disk obstacle: the distance between the robot
//!   polygon and the segment the obstacle's centre sweeps relative to it;
//! - two polygons: separating axes between the robot polygon and the swept
//!   hull (the penetration depth).
//!
//! Touching is allowed: an overlap counts when deeper than `TOUCH_EPS`, as
//! for static obstacles. A collision is located by bisection on the
//! interval (to 1e-9 s): the error names the obstacle, the trajectory's
//! segment and the earliest time found.

use super::polygon::{closest_point_on_segment, convex_decomposition, convex_hull};
use super::proximity::convex_distance;
use super::validator::{DEFAULT_TOLERANCE, ValidationError, validate_path};
use super::{Config, Point, RobotShape, TOUCH_EPS, Vector, World, place};

/// Relative slack on a trajectory's speed (SPEC 2.9).
pub const SPEED_SLACK: f64 = 1e-9;

/// A waypoint of a moving obstacle's route.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Waypoint {
    pub t: f64,
    pub at: Point,
}

/// What a moving obstacle does after its last waypoint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum After {
    Stay,
    Vanish,
}

/// The shape of a moving obstacle, in its own frame (its route's point is
/// the origin).
#[derive(Clone, Debug, PartialEq)]
pub enum MovingShape {
    Disk(f64),
    /// Convex pieces, counter-clockwise.
    Pieces(Vec<Vec<Point>>),
}

impl MovingShape {
    /// A simple polygon (counter-clockwise) as its convex pieces.
    pub fn polygon(outline: &[Point]) -> Self {
        MovingShape::Pieces(
            convex_decomposition(outline)
                .into_iter()
                .map(|p| p.vertices)
                .collect(),
        )
    }
}

/// An obstacle that translates along a route (SPEC 2.9).
#[derive(Clone, Debug, PartialEq)]
pub struct MovingObstacle {
    pub name: String,
    pub shape: MovingShape,
    /// At least one waypoint; times strictly increasing, from 0 or later.
    pub route: Vec<Waypoint>,
    pub after: After,
}

impl MovingObstacle {
    /// Where the obstacle's origin is at `t`, or `None` once it vanished.
    pub fn position(&self, t: f64) -> Option<Point> {
        let first = self.route.first()?;
        let last = self.route.last()?;
        if t >= last.t {
            return match self.after {
                After::Vanish => None,
                After::Stay => Some(last.at),
            };
        }
        if t <= first.t {
            return Some(first.at);
        }
        let k = self.route.partition_point(|w| w.t <= t);
        let (a, b) = (self.route[k - 1], self.route[k]);
        let s = (t - a.t) / (b.t - a.t);
        Some(a.at + (b.at - a.at) * s)
    }

    /// The time after which it neither moves nor vanishes.
    pub fn settles(&self) -> f64 {
        self.route.last().map_or(0.0, |w| w.t)
    }
}

/// A point of a trajectory: the robot's pose at time `t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timed {
    pub pose: Config,
    pub t: f64,
}

/// Where the robot is at `t` on `trajectory` (its last pose after its end).
pub fn robot_at(trajectory: &[Timed], t: f64) -> Config {
    let Some(last) = trajectory.last() else {
        return Config::new(0.0, 0.0, 0.0);
    };
    if t >= last.t {
        return last.pose;
    }
    if t <= trajectory[0].t {
        return trajectory[0].pose;
    }
    let k = trajectory.partition_point(|p| p.t <= t);
    let (a, b) = (trajectory[k - 1], trajectory[k]);
    let s = (t - a.t) / (b.t - a.t);
    Config::new(
        a.pose.x + (b.pose.x - a.pose.x) * s,
        a.pose.y + (b.pose.y - a.pose.y) * s,
        a.pose.theta,
    )
}

/// Validates `trajectory` for `robot` (largest speed `speed`) in `world`
/// among `moving` (see the module documentation).
///
/// # Returns
/// `Ok(())`, or the first failure found: its `segment` is the index of the
/// trajectory's point that starts the segment where it happens (the last
/// point for a collision with the parked robot).
pub fn validate_trajectory(
    world: &World,
    moving: &[MovingObstacle],
    robot: &RobotShape,
    speed: f64,
    trajectory: &[Timed],
) -> Result<(), ValidationError> {
    let fail = |segment: usize, at: Config, obstacle: Option<String>, reason: String| {
        Err(ValidationError {
            segment,
            at,
            obstacle,
            reason,
        })
    };
    let Some(first) = trajectory.first() else {
        return fail(
            0,
            Config::new(0.0, 0.0, 0.0),
            None,
            "the trajectory is empty".into(),
        );
    };
    if first.t != 0.0 {
        return fail(
            0,
            first.pose,
            None,
            format!("the trajectory starts at t = {}, not 0", first.t),
        );
    }
    for (k, w) in trajectory.windows(2).enumerate() {
        let (a, b) = (w[0], w[1]);
        if b.t.partial_cmp(&a.t) != Some(std::cmp::Ordering::Greater) || !b.t.is_finite() {
            return fail(
                k,
                a.pose,
                None,
                format!(
                    "the times do not increase at point {}: {} then {}",
                    k + 1,
                    a.t,
                    b.t
                ),
            );
        }
        let distance = (b.pose.x - a.pose.x).hypot(b.pose.y - a.pose.y);
        if distance > speed * (b.t - a.t) * (1.0 + SPEED_SLACK) {
            return fail(
                k,
                a.pose,
                None,
                format!(
                    "segment {k} is driven at {} units/s, faster than the robot's speed {speed}",
                    distance / (b.t - a.t)
                ),
            );
        }
        if robot.rotates() && a.pose.theta != b.pose.theta {
            return fail(
                k,
                a.pose,
                None,
                format!("the robot turns on segment {k}: a timed trajectory only translates"),
            );
        }
    }
    let poses: Vec<Config> = trajectory.iter().map(|p| p.pose).collect();
    validate_path(world, robot, &poses, DEFAULT_TOLERANCE)?;
    // The moments at which anything changes course.
    let mut cuts: Vec<f64> = trajectory.iter().map(|p| p.t).collect();
    for o in moving {
        cuts.extend(o.route.iter().map(|w| w.t).filter(|t| *t >= 0.0));
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let body = Body::of(robot, trajectory[0].pose.theta);
    for o in moving {
        for w in cuts.windows(2) {
            let (a, b) = (w[0], w[1]);
            if collides_between(&body, o, trajectory, a, b) {
                let t = earliest(&body, o, trajectory, a, b);
                return obstacle_fail(trajectory, o, t);
            }
        }
        // Alone: nothing moves at all (a one-point trajectory among
        // standing obstacles), or after the last cut nothing moves.
        let end = *cuts.last().expect("the trajectory has a time");
        if collides_between(&body, o, trajectory, end, end) {
            return obstacle_fail(trajectory, o, end);
        }
    }
    Ok(())
}

/// Whether `robot` moving straight at constant speed from `from` to `to`
/// (`from.t ≤ to.t`) meets `o` at some instant of `[from.t, to.t]`: the
/// validator's own test, on one segment of a trajectory.
pub fn motion_meets(robot: &RobotShape, o: &MovingObstacle, from: Timed, to: Timed) -> bool {
    let trajectory = [from, to];
    let body = Body::of(robot, from.pose.theta);
    let mut cuts = vec![from.t, to.t];
    cuts.extend(
        o.route
            .iter()
            .map(|w| w.t)
            .filter(|t| *t > from.t && *t < to.t),
    );
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    if cuts.len() == 1 {
        return collides_between(&body, o, &trajectory, from.t, from.t);
    }
    cuts.windows(2)
        .any(|w| collides_between(&body, o, &trajectory, w[0], w[1]))
}

/// The smallest distance between the robot on `trajectory` (parked at its
/// last pose forever after) and the moving obstacles, over every instant
/// each is present: 0 when they touch or overlap, +∞ when none is ever
/// present. Exact (the `clearance` of SPEC 3 in a world that moves):
/// within an interval in which both move linearly, the obstacle relative
/// to the robot sweeps a segment of offsets, and the distance is the one
/// between the robot's body and the obstacle's shape swept along it.
pub fn moving_clearance(
    moving: &[MovingObstacle],
    robot: &RobotShape,
    trajectory: &[Timed],
) -> f64 {
    let Some(first) = trajectory.first() else {
        return f64::INFINITY;
    };
    let mut cuts: Vec<f64> = trajectory.iter().map(|p| p.t).collect();
    for o in moving {
        cuts.extend(o.route.iter().map(|w| w.t).filter(|t| *t >= first.t));
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let end = *cuts.last().expect("the trajectory has a time");
    let body = Body::of(robot, first.pose.theta);
    let mut best = f64::INFINITY;
    for o in moving {
        for w in cuts.windows(2) {
            best = best.min(distance_between(&body, o, trajectory, w[0], w[1]));
        }
        best = best.min(distance_between(&body, o, trajectory, end, end));
    }
    best.max(0.0)
}

/// The offsets of `o`'s origin from the robot's at `a` and `b` (both
/// moving linearly between), or `None` when `o` is absent from the open
/// interval (it vanished); for `a = b`, at that instant.
fn relative_offsets(
    o: &MovingObstacle,
    trajectory: &[Timed],
    a: f64,
    b: f64,
) -> Option<(Vector, Vector)> {
    // Present on the whole closed interval, or on none of it: a vanishing
    // obstacle's last time is a cut, and what holds at that instant holds
    // just before it too.
    let mid = if a == b { a } else { a + (b - a) / 2.0 };
    o.position(mid)?;
    let ends = |t: f64| -> Option<Vector> {
        let at = o.position(t).or_else(|| o.route.last().map(|w| w.at))?;
        let p = robot_at(trajectory, t);
        Some(at - Point::new(p.x, p.y))
    };
    Some((ends(a)?, ends(b)?))
}

/// The smallest distance between the robot and `o` over `[a, b]`, in which
/// both move linearly (negative or 0 when they meet; +∞ when `o` is
/// absent).
fn distance_between(body: &Body, o: &MovingObstacle, trajectory: &[Timed], a: f64, b: f64) -> f64 {
    let Some((da, db)) = relative_offsets(o, trajectory, a, b) else {
        return f64::INFINITY;
    };
    match (&o.shape, body) {
        (MovingShape::Disk(r_o), Body::Round(r)) => {
            let d = closest_point_on_segment(Point::origin(), Point::from(da), Point::from(db));
            d.coords.norm() - r - r_o
        }
        (MovingShape::Disk(r_o), Body::Convex(v)) => {
            segment_polygon_distance(Point::from(da), Point::from(db), v) - r_o
        }
        (MovingShape::Pieces(pieces), body) => pieces
            .iter()
            .map(|piece| {
                let hull = swept(piece, da, db);
                match body {
                    Body::Round(r) => point_polygon_distance(Point::origin(), &hull) - r,
                    Body::Convex(v) => convex_distance(v, &hull),
                }
            })
            .fold(f64::INFINITY, f64::min),
    }
}

/// The convex piece swept by translating it from offset `da` to `db`.
fn swept(piece: &[Point], da: Vector, db: Vector) -> Vec<Point> {
    let mut points: Vec<Point> = piece.iter().map(|p| p + da).collect();
    points.extend(piece.iter().map(|p| p + db));
    convex_hull(&points)
}

fn obstacle_fail(trajectory: &[Timed], o: &MovingObstacle, t: f64) -> Result<(), ValidationError> {
    let segment = trajectory
        .partition_point(|p| p.t <= t)
        .saturating_sub(1)
        .min(trajectory.len() - 1);
    Err(ValidationError {
        segment,
        at: robot_at(trajectory, t),
        obstacle: Some(o.name.clone()),
        reason: format!(
            "the robot meets the moving obstacle `{}` at t = {t:.6} s",
            o.name
        ),
    })
}

/// The robot's body in its own frame at its (fixed) heading.
enum Body {
    Round(f64),
    Convex(Vec<Point>),
}

impl Body {
    fn of(robot: &RobotShape, theta: f64) -> Body {
        match robot {
            RobotShape::Point => Body::Round(0.0),
            RobotShape::Disk(r) => Body::Round(*r),
            RobotShape::Polygon(p) => {
                let (s, c) = theta.sin_cos();
                let origin = Config::new(0.0, 0.0, theta);
                Body::Convex(p.vertices.iter().map(|v| place(origin, s, c, v)).collect())
            }
        }
    }
}

/// Whether the robot and `o` overlap (deeper than `TOUCH_EPS`) at some
/// instant of `[a, b]`, in which both move linearly (or `a = b`).
fn collides_between(body: &Body, o: &MovingObstacle, trajectory: &[Timed], a: f64, b: f64) -> bool {
    let Some((da, db)) = relative_offsets(o, trajectory, a, b) else {
        return false;
    };
    match (&o.shape, body) {
        (MovingShape::Disk(r_o), Body::Round(r)) => {
            let d = closest_point_on_segment(Point::origin(), Point::from(da), Point::from(db));
            d.coords.norm() < r + r_o - TOUCH_EPS
        }
        (MovingShape::Disk(r_o), Body::Convex(v)) => {
            segment_polygon_distance(Point::from(da), Point::from(db), v) < r_o - TOUCH_EPS
        }
        (MovingShape::Pieces(pieces), body) => pieces.iter().any(|piece| {
            let hull = swept(piece, da, db);
            match body {
                Body::Round(r) => {
                    let inside = depth_inside(Point::origin(), &hull);
                    if *r == 0.0 {
                        inside > TOUCH_EPS
                    } else {
                        inside > 0.0
                            || point_polygon_distance(Point::origin(), &hull) < r - TOUCH_EPS
                    }
                }
                Body::Convex(v) => penetration(v, &hull) > TOUCH_EPS,
            }
        }),
    }
}

/// The earliest collision time in `[a, b]`, to 1e-9 s (bisection on
/// [`collides_between`] over the interval's first part).
fn earliest(body: &Body, o: &MovingObstacle, trajectory: &[Timed], a: f64, b: f64) -> f64 {
    // Invariant: no collision on [a, lo]; a collision on [lo, hi].
    let (mut lo, mut hi) = (a, b);
    if collides_between(body, o, trajectory, a, a) {
        return a;
    }
    while hi - lo > 1e-9 {
        let mid = lo + (hi - lo) / 2.0;
        if mid <= lo || mid >= hi {
            break;
        }
        if collides_between(body, o, trajectory, lo, mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// How deep `p` lies inside the convex polygon `v` (counter-clockwise):
/// its distance to the boundary, negative outside (for a hull of fewer
/// than three points, −∞).
fn depth_inside(p: Point, v: &[Point]) -> f64 {
    if v.len() < 3 {
        return f64::NEG_INFINITY;
    }
    (0..v.len())
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % v.len()]);
            let e = b - a;
            (e.x * (p.y - a.y) - e.y * (p.x - a.x)) / e.norm()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The distance from `p` to the convex polygon `v` (0 inside).
fn point_polygon_distance(p: Point, v: &[Point]) -> f64 {
    if depth_inside(p, v) >= 0.0 {
        return 0.0;
    }
    (0..v.len())
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % v.len()]);
            (p - closest_point_on_segment(p, a, b)).norm()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The distance between the segment `pq` and the convex polygon `v` (0
/// when they meet).
fn segment_polygon_distance(p: Point, q: Point, v: &[Point]) -> f64 {
    if penetration(&[p, q], v) >= 0.0 {
        return 0.0;
    }
    let mut best = point_polygon_distance(p, v).min(point_polygon_distance(q, v));
    for &c in v {
        best = best.min((c - closest_point_on_segment(c, p, q)).norm());
    }
    best
}

/// The penetration depth of two convex point sets (a segment has two
/// points): the smallest overlap of their projections over the candidate
/// separating axes (the edge normals of both); negative when an axis
/// separates them.
fn penetration(a: &[Point], b: &[Point]) -> f64 {
    let mut depth = f64::INFINITY;
    for set in [a, b] {
        let n = set.len();
        let edges = if n == 2 { 1 } else { n };
        for i in 0..edges {
            let (p, q) = (set[i], set[(i + 1) % n]);
            let e = q - p;
            let len = e.norm();
            if len == 0.0 {
                continue;
            }
            let axis = Vector::new(-e.y / len, e.x / len);
            let (alo, ahi) = span(a, axis);
            let (blo, bhi) = span(b, axis);
            depth = depth.min(ahi.min(bhi) - alo.max(blo));
        }
    }
    depth
}

fn span(v: &[Point], axis: Vector) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            let x = p.coords.dot(&axis);
            (lo.min(x), hi.max(x))
        })
}

pub mod departures;

#[cfg(test)]
mod tests;
