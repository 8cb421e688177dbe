//! Paths of car-like robots (SPEC 2.4, 3.0, §5 `"segments"`): a start pose
//! and segments — left arc, straight, right arc, each with a signed arc
//! length of the reference point (negative: driven in reverse) — and their
//! validation.
//!
//! # The validator for cars
//! [`validate_car_path`] is the validator of SPEC 3.0 for such a path. It
//! integrates the segments from the start in closed form
//! ([`Segment::advance`]: arcs exactly, no numerical integration), checks
//! that the path ends on the goal (within [`END_TOLERANCE`] in position and
//! heading), that no segment is driven in reverse by a Dubins car, and
//! sweeps the body along every arc and straight: each segment is cut into
//! sub-steps in which no point of the robot moves more than the tolerance
//! (on an arc of length ℓ and radius ρ a point at distance r ≤ R from the
//! reference point moves at most ℓ·(1 + R/ρ)), and the poses at the
//! sub-steps' ends go through the validator of straight motions, which
//! checks the convex hull of the bodies at both ends of every sub-step —
//! the same rule as for a rotating robot's straight motion. Every arc has
//! radius ρ and the heading is continuous by construction: a segment is
//! only a kind and a length.

use super::motion::MotionChecker;
use super::proximity::Proximity;
use super::steer::{Model, Segment, SteerPath, Steering, Turn};
use super::validator::{
    DEFAULT_TOLERANCE, MAX_SUB_STEPS, ValidationError, Validator, usable_tolerance,
};
use super::{Config, RobotShape, TOUCH_EPS, World, angle_diff};

/// How close to the goal the integrated path must end (position, in world
/// units, and heading, in radians; SPEC 3.0).
pub const END_TOLERANCE: f64 = 1e-9;

/// The arc length between the poses of a car path's `"path"`, for drawing
/// (SPEC §5: the poses at the segment ends and at most every 0.1).
pub const DRAW_STEP: f64 = 0.1;

/// A car robot's path: where it starts, how it steers, and its segments.
#[derive(Clone, Debug, PartialEq)]
pub struct CarPath {
    pub start: Config,
    pub steering: Steering,
    pub segments: Vec<Segment>,
}

impl CarPath {
    /// The shortest steering path from `a` to `b`.
    pub fn shortest(steering: Steering, a: Config, b: Config) -> Self {
        CarPath::from_steer(a, steering, &steering.shortest(a, b))
    }

    /// The steering path `path` from `start` (SPEC 2.4).
    pub fn from_steer(start: Config, steering: Steering, path: &SteerPath) -> Self {
        CarPath {
            start,
            steering,
            segments: path.segments().to_vec(),
        }
    }

    /// The shortest steering paths between consecutive `states`, end to
    /// end, from `start` (a sampling planner's path as a car's).
    pub fn through(start: Config, steering: Steering, states: &[Config]) -> Self {
        let mut segments = Vec::new();
        for w in states.windows(2) {
            segments.extend_from_slice(steering.shortest(w[0], w[1]).segments());
        }
        CarPath {
            start,
            steering,
            segments,
        }
    }

    /// The reference point's arc length (SPEC 3.8 `length`).
    pub fn length(&self) -> f64 {
        self.segments.iter().map(|s| s.length.abs()).sum()
    }

    /// The total absolute heading change, in radians (SPEC 3.8 `turn`).
    pub fn turn(&self) -> f64 {
        self.segments
            .iter()
            .filter(|s| s.turn != Turn::S)
            .map(|s| s.length.abs() / self.steering.radius)
            .sum()
    }

    /// Changes of direction between consecutive segments (`cusps`).
    pub fn cusps(&self) -> usize {
        self.segments
            .windows(2)
            .filter(|w| (w[0].length < 0.0) != (w[1].length < 0.0))
            .count()
    }

    /// The arc length driven in reverse (`reverse_length`).
    pub fn reverse_length(&self) -> f64 {
        self.segments
            .iter()
            .filter(|s| s.length < 0.0)
            .map(|s| -s.length)
            .sum()
    }

    /// The pose at the end of each segment, from the start's: `ends[k]` is
    /// where segment k ends (headings not wrapped).
    fn ends(&self) -> Vec<Config> {
        let mut c = self.start;
        self.segments
            .iter()
            .map(|s| {
                c = s.end(c, self.steering.radius);
                c
            })
            .collect()
    }

    /// Where the path ends (the start without segments).
    pub fn end(&self) -> Config {
        self.ends().last().copied().unwrap_or(self.start)
    }

    /// Whether the path, integrated from its start in closed form, ends on
    /// `goal`: within [`END_TOLERANCE`] in position and in heading.
    pub fn ends_on(&self, goal: Config) -> bool {
        let end = self.end();
        let off = (end.x - goal.x).hypot(end.y - goal.y);
        off <= END_TOLERANCE && angle_diff(end.theta, goal.theta).abs() <= END_TOLERANCE
    }

    /// The poses at the start, at the segment ends and at most every `step`
    /// of arc length (headings in [0, 2π)): what is drawn and listed as the
    /// plan's `"path"`. At most [`MAX_SUB_STEPS`] poses: a longer path is
    /// drawn with a larger step.
    pub fn poses(&self, step: f64) -> Vec<Config> {
        let step = step.max(self.length() / MAX_SUB_STEPS as f64);
        let mut out = vec![self.start.wrapped()];
        let mut c = self.start;
        for s in &self.segments {
            let n = pieces(s.length.abs(), step);
            for k in 1..=n {
                let part = s.length * k as f64 / n as f64;
                out.push(Segment::advance(c, s.turn, part, self.steering.radius).wrapped());
            }
            c = s.end(c, self.steering.radius);
        }
        out
    }
}

/// Pieces of at most `step` in a length (at least one).
fn pieces(length: f64, step: f64) -> usize {
    if step > 0.0 && length.is_finite() {
        ((length / step).ceil() as usize).max(1)
    } else {
        1
    }
}

/// Checks a car path against the world (SPEC 3.0; see the module
/// documentation): the model's rules, the end on `goal` (when given), and
/// the body swept along every segment with sub-steps in which no point of
/// the robot moves more than `tolerance` (not finite and positive:
/// [`super::validator::DEFAULT_TOLERANCE`]).
///
/// # Returns
/// `Ok(())`, or the first failure; its `segment` is the index of the car
/// path's segment where it happened.
pub fn validate_car_path(
    referee: &Validator<'_>,
    robot: &RobotShape,
    path: &CarPath,
    goal: Option<Config>,
    tolerance: f64,
) -> Result<(), ValidationError> {
    let tolerance = usable_tolerance(tolerance);
    let rho = path.steering.radius;
    let fail = |segment: usize, at: Config, reason: String| ValidationError {
        segment,
        at,
        obstacle: None,
        reason,
    };
    if !(rho.is_finite() && rho > 0.0) {
        return Err(fail(
            0,
            path.start,
            format!("the turning radius {rho} is not positive"),
        ));
    }
    let ends = path.ends();
    let mut from = path.start;
    for (k, s) in path.segments.iter().enumerate() {
        if !s.length.is_finite() {
            return Err(fail(k, from, format!("segment {k} has no finite length")));
        }
        if path.steering.model == Model::Dubins && s.length < 0.0 {
            return Err(fail(
                k,
                from,
                format!("segment {k} is driven in reverse, which a Dubins car cannot"),
            ));
        }
        from = ends[k];
    }
    let end = path.end();
    if let Some(goal) = goal {
        let off = (end.x - goal.x).hypot(end.y - goal.y);
        let turned = angle_diff(end.theta, goal.theta).abs();
        if off > END_TOLERANCE || turned > END_TOLERANCE || !off.is_finite() {
            return Err(fail(
                path.segments.len().saturating_sub(1),
                end,
                format!(
                    "the path ends at ({}, {}, {} rad), not on the goal ({}, {}, {} rad)",
                    end.x, end.y, end.theta, goal.x, goal.y, goal.theta
                ),
            ));
        }
    }
    let (counts, total) = sub_steps(robot, path, tolerance);
    if total > MAX_SUB_STEPS {
        return Err(fail(
            0,
            path.start,
            format!(
                "the path needs more than {MAX_SUB_STEPS} sub-steps at tolerance {tolerance}: too long to validate"
            ),
        ));
    }
    let mut poses = Vec::with_capacity(total + 1);
    // Which car segment each polyline step belongs to.
    let mut owner = Vec::with_capacity(total);
    poses.push(path.start);
    let mut c = path.start;
    for (k, (s, &n)) in path.segments.iter().zip(&counts).enumerate() {
        for j in 1..=n {
            let pose = if j == n {
                ends[k]
            } else {
                Segment::advance(c, s.turn, s.length * j as f64 / n as f64, rho)
            };
            poses.push(pose);
            owner.push(k);
        }
        c = ends[k];
    }
    referee
        .validate_path(robot, &poses, tolerance)
        .map_err(|mut e| {
            e.segment = owner.get(e.segment).copied().unwrap_or(0);
            e
        })
}

/// The validator's sub-steps per segment, and their total: every point of
/// the body moves at most `tolerance` in one. A translating convex body
/// sweeps exactly the hull of its two ends: a straight needs no sub-steps
/// for soundness, only pieces of about the body's size so that a failure
/// is located.
fn sub_steps(robot: &RobotShape, path: &CarPath, tolerance: f64) -> (Vec<usize>, usize) {
    let reach = robot.radius();
    let rho = path.steering.radius;
    let mut counts = Vec::with_capacity(path.segments.len());
    let mut total = 0usize;
    for s in &path.segments {
        let (travel, step) = match s.turn {
            Turn::S => (s.length.abs(), reach.max(tolerance)),
            Turn::L | Turn::R => (s.length.abs() * (1.0 + reach / rho), tolerance),
        };
        let n = if travel == 0.0 {
            1
        } else {
            let n = (travel / step).ceil();
            if n > MAX_SUB_STEPS as f64 {
                MAX_SUB_STEPS + 1
            } else {
                (n as usize).max(1)
            }
        };
        total = total.saturating_add(n);
        counts.push(n);
    }
    (counts, total)
}

/// The planners' motion checker for curves: the straight-motion checker
/// ([`MotionChecker`]) and the distance query ([`Proximity`]) of one robot
/// in one world. Build it once per plan; queries take `&self`.
pub struct CarChecker {
    robot: RobotShape,
    motion: MotionChecker,
    proximity: Proximity,
}

impl CarChecker {
    pub fn new(world: &World, robot: &RobotShape) -> Self {
        CarChecker {
            robot: robot.clone(),
            motion: MotionChecker::new(world, robot),
            proximity: Proximity::new(world),
        }
    }

    /// The checker of straight motions it holds.
    pub fn motion(&self) -> &MotionChecker {
        &self.motion
    }

    /// Where the car path is first blocked: the segment and the pose that
    /// starts the first of the validator's sub-steps that
    /// [`MotionChecker::motion_free`] refuses (every sub-step is checked:
    /// for a planner's note, not for a search). `None` when the path is
    /// free by that check (or not drivable at all: see
    /// [`CarChecker::path_free`]).
    pub fn first_blocked(&self, path: &CarPath) -> Option<(usize, Config)> {
        let rho = path.steering.radius;
        let (counts, total) = sub_steps(&self.robot, path, DEFAULT_TOLERANCE);
        if !(rho.is_finite() && rho > 0.0) || total > MAX_SUB_STEPS {
            return None;
        }
        let ends = path.ends();
        let mut from = path.start;
        for (k, s) in path.segments.iter().enumerate() {
            let n = counts[k];
            let pose = |j: usize| {
                if j == n {
                    ends[k]
                } else {
                    Segment::advance(from, s.turn, s.length * j as f64 / n as f64, rho)
                }
            };
            if let Some(j) = (0..n).find(|&j| !self.motion.motion_free(pose(j), pose(j + 1))) {
                return Some((k, pose(j)));
            }
            from = ends[k];
        }
        None
    }

    /// Whether the car path is free: it never accepts what
    /// [`validate_car_path`] rejects at [`DEFAULT_TOLERANCE`] (without a
    /// goal), and decides most paths far faster. It is the planners' own
    /// code: the validator judges the path afterwards.
    ///
    /// The validator cuts each segment into sub-steps (at most the tolerance
    /// of any body point's motion on an arc; pieces of the body's size on a
    /// straight, whose sweep is exact) and checks the hull of the bodies at
    /// the two ends of each. Here:
    /// 1. the body at poses every [`QUICK_STEP`] of arc: one that is not
    ///    free ([`MotionChecker::config_free`]) ends the check, "not free";
    /// 2. conservative advancement: at a pose whose body is `d` from every
    ///    obstacle ([`Proximity::distance`]), no body point moves more than
    ///    `s · (1 + R/ρ)` along an arc of length `s` (R the body's reach;
    ///    `s` along a straight). On an arc each validator hull lies within
    ///    the tolerance of the body at its first end, so every sub-step
    ///    starting in the stretch `(d − tolerance − ε) / (1 + R/ρ)` is free;
    ///    on a straight the hull is the swept body, free over `d − ε`; the
    ///    reference point stays inside the bounds over its distance to their
    ///    edge;
    /// 3. where a stretch would be shorter than one sub-step (the body within
    ///    [`NEAR`] tolerances of an obstacle, or the reference point near the
    ///    bounds), the validator's sub-steps there, [`BATCH`] at a time, each
    ///    through [`MotionChecker::motion_free`], which cuts a motion at the
    ///    validator's configurations and applies its rule with half its
    ///    contact threshold.
    pub fn path_free(&self, path: &CarPath) -> bool {
        let tolerance = DEFAULT_TOLERANCE;
        let robot = &self.robot;
        let rho = path.steering.radius;
        if !(rho.is_finite() && rho > 0.0) || path.segments.iter().any(|s| !s.length.is_finite()) {
            return false;
        }
        if path.steering.model == Model::Dubins && path.segments.iter().any(|s| s.length < 0.0) {
            return false;
        }
        // Too long for the validator: rejected there, so here.
        let (counts, total) = sub_steps(robot, path, tolerance);
        if total > MAX_SUB_STEPS {
            return false;
        }
        if path
            .poses(QUICK_STEP)
            .into_iter()
            .any(|c| !self.motion.config_free(c))
        {
            return false;
        }
        let bounds = self.motion.bounds();
        let reach = robot.radius();
        let margin = 4.0 * TOUCH_EPS;
        let ends = path.ends();
        let mut from = path.start;
        for (k, s) in path.segments.iter().enumerate() {
            let n = counts[k];
            let length = s.length.abs();
            let h = length / n as f64;
            // The validator's sub-step ends on this segment.
            let pose = |j: usize| {
                if j == n {
                    ends[k]
                } else {
                    Segment::advance(from, s.turn, s.length * j as f64 / n as f64, rho)
                }
            };
            let (factor, slack) = match s.turn {
                Turn::S => (1.0, 0.0),
                Turn::L | Turn::R => (1.0 + reach / rho, tolerance),
            };
            let mut at = 0.0;
            loop {
                let c = Segment::advance(from, s.turn, s.length.signum() * at, rho);
                let d = self.proximity.distance(robot, c);
                let inside = (c.x - bounds.min.x)
                    .min(bounds.max.x - c.x)
                    .min(c.y - bounds.min.y)
                    .min(bounds.max.y - c.y);
                let advance = ((d - slack - margin) / factor).min(inside);
                if d >= NEAR * tolerance && advance >= h && length > 0.0 {
                    at += advance;
                } else {
                    // The validator's own sub-steps from the one holding `at`.
                    let j0 = ((at / h).floor() as usize).min(n - 1);
                    let j1 = (j0 + BATCH).min(n);
                    if (j0..j1).any(|j| !self.motion.motion_free(pose(j), pose(j + 1))) {
                        return false;
                    }
                    at = j1 as f64 * h;
                    if j1 == n {
                        break;
                    }
                }
                if at >= length {
                    break;
                }
            }
            from = ends[k];
        }
        true
    }
}

/// The arc length between the poses [`CarChecker::path_free`] checks first.
pub const QUICK_STEP: f64 = 0.25;

/// Below this many tolerances of clearance [`CarChecker::path_free`] checks the
/// validator's own sub-steps.
pub const NEAR: f64 = 2.0;

/// The validator's sub-steps [`CarChecker::path_free`] checks at a time.
pub const BATCH: usize = 16;

/// The poses the validator sweeps, for measuring clearance along the same
/// sub-steps: at most every `tolerance` of any body point's motion.
pub fn swept_poses(robot: &RobotShape, path: &CarPath, tolerance: f64) -> Vec<Config> {
    let rho = path.steering.radius;
    let step = tolerance / (1.0 + robot.radius() / rho);
    path.poses(step)
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;
    use crate::fixtures::world_in;
    use crate::steer::Model;
    use crate::validator::validate_path;
    use crate::{Aabb, Shape};
    use crate::{ConvexPolygon, Point};

    /// A world within (0, 0) … (w, h) of `shapes`.
    fn world_of(w: f64, h: f64, shapes: Vec<Shape>) -> crate::World {
        world_in(
            Aabb::from_corners(Point::new(0.0, 0.0), Point::new(w, h)),
            shapes,
        )
    }

    fn disk(x: f64, y: f64, r: f64) -> Shape {
        Shape::Disk {
            center: Point::new(x, y),
            radius: r,
        }
    }

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Shape {
        Shape::Rect(Aabb::from_corners(Point::new(x0, y0), Point::new(x1, y1)))
    }

    fn cart() -> RobotShape {
        RobotShape::Polygon(ConvexPolygon {
            vertices: vec![
                Point::new(-0.5, -0.5),
                Point::new(1.0, -0.5),
                Point::new(1.0, 0.5),
                Point::new(-0.5, 0.5),
            ],
        })
    }

    /// A left half-turn of radius 3 from (5, 20) facing +x to (5, 26)
    /// facing −x: its rightmost point is (8, 23).
    fn half_turn(model: Model) -> CarPath {
        CarPath {
            start: Config::new(5.0, 20.0, 0.0),
            steering: Steering::new(model, 3.0),
            segments: vec![Segment {
                turn: Turn::L,
                length: 3.0 * PI,
            }],
        }
    }

    #[test]
    fn the_arc_is_swept_where_the_chord_is_not() {
        // A disk beside the arc's bulge: the straight motion from start to
        // end passes far from it, the arc through it.
        let world = world_of(30.0, 30.0, vec![disk(8.6, 23.0, 0.4)]);
        let referee = Validator::new(&world);
        let path = half_turn(Model::Dubins);
        let goal = Config::new(5.0, 26.0, PI);
        let chord = [path.start, goal];
        assert!(validate_path(&world, &cart(), &chord, DEFAULT_TOLERANCE).is_ok());
        let e = validate_car_path(&referee, &cart(), &path, Some(goal), DEFAULT_TOLERANCE)
            .expect_err("the arc runs into the disk");
        assert_eq!(e.segment, 0);
        assert!(e.at.x > 7.0, "{e:?}");
        // Away from the bulge, the same arc is free.
        let far = world_of(30.0, 30.0, vec![disk(9.7, 23.0, 0.4)]);
        let referee = Validator::new(&far);
        assert!(validate_car_path(&referee, &cart(), &path, Some(goal), DEFAULT_TOLERANCE).is_ok());
    }

    #[test]
    fn the_end_must_be_the_goal_and_a_dubins_car_never_reverses() {
        let world = world_of(30.0, 30.0, Vec::new());
        let referee = Validator::new(&world);
        let path = half_turn(Model::ReedsShepp);
        let goal = Config::new(5.0, 26.0, PI);
        assert!(validate_car_path(&referee, &cart(), &path, Some(goal), DEFAULT_TOLERANCE).is_ok());
        let beside = Config::new(5.0, 26.0 + 1e-6, PI);
        let e = validate_car_path(&referee, &cart(), &path, Some(beside), DEFAULT_TOLERANCE)
            .expect_err("not on the goal");
        assert!(e.reason.contains("not on the goal"), "{e:?}");
        let turned = Config::new(5.0, 26.0, PI + 1e-6);
        assert!(
            validate_car_path(&referee, &cart(), &path, Some(turned), DEFAULT_TOLERANCE).is_err()
        );
        // Backwards along a straight: Reeds–Shepp may, Dubins may not.
        let back = |model| CarPath {
            start: Config::new(10.0, 10.0, 0.0),
            steering: Steering::new(model, 2.0),
            segments: vec![Segment {
                turn: Turn::S,
                length: -4.0,
            }],
        };
        let goal = Config::new(6.0, 10.0, 0.0);
        let rs = back(Model::ReedsShepp);
        assert!(validate_car_path(&referee, &cart(), &rs, Some(goal), DEFAULT_TOLERANCE).is_ok());
        assert_eq!(
            (rs.reverse_length(), rs.cusps(), rs.length()),
            (4.0, 0, 4.0)
        );
        let e = validate_car_path(
            &referee,
            &cart(),
            &back(Model::Dubins),
            Some(goal),
            DEFAULT_TOLERANCE,
        )
        .expect_err("a Dubins car in reverse");
        assert!(e.reason.contains("reverse"), "{e:?}");
    }

    #[test]
    fn the_reference_point_stays_in_bounds_along_the_arc() {
        // The half-turn's bulge reaches x = 8; bounds up to x = 7.5 contain
        // both ends but not the arc.
        let world = world_of(7.5, 30.0, Vec::new());
        let referee = Validator::new(&world);
        let goal = Config::new(5.0, 26.0, PI);
        assert!(
            validate_car_path(
                &referee,
                &RobotShape::Disk(0.1),
                &half_turn(Model::Dubins),
                Some(goal),
                DEFAULT_TOLERANCE
            )
            .is_err()
        );
    }

    #[test]
    fn poses_and_measures_follow_the_segments() {
        let path = CarPath {
            start: Config::new(0.0, 0.0, 0.0),
            steering: Steering::new(Model::ReedsShepp, 2.0),
            segments: vec![
                Segment {
                    turn: Turn::L,
                    length: PI,
                },
                Segment {
                    turn: Turn::S,
                    length: -1.0,
                },
                Segment {
                    turn: Turn::R,
                    length: 0.5,
                },
            ],
        };
        assert_eq!(path.cusps(), 2);
        assert!((path.length() - (PI + 1.5)).abs() < 1e-12);
        assert!((path.turn() - (PI / 2.0 + 0.25)).abs() < 1e-12);
        assert_eq!(path.reverse_length(), 1.0);
        let poses = path.poses(DRAW_STEP);
        // The start, every 0.1 or less, the segment ends.
        assert_eq!(poses[0], path.start);
        for w in poses.windows(2) {
            assert!((w[1].xy() - w[0].xy()).norm() <= DRAW_STEP + 1e-12);
        }
        let end = path.end();
        let last = poses[poses.len() - 1];
        assert!((last.x - end.x).abs() < 1e-12 && (last.y - end.y).abs() < 1e-12);
        // A quarter circle left of radius 2 ends at (2, 2) facing +y.
        let quarter = Segment {
            turn: Turn::L,
            length: PI,
        }
        .end(path.start, 2.0);
        assert!((quarter.x - 2.0).abs() < 1e-12 && (quarter.y - 2.0).abs() < 1e-12);
        assert!((quarter.theta - PI / 2.0).abs() < 1e-12);
    }

    /// A random world of rects and disks in (0, 0) (20, 20), a car body and
    /// steering, and the steering path between two random poses.
    fn case() -> impl proptest::strategy::Strategy<Value = (crate::World, RobotShape, CarPath)> {
        use proptest::prelude::*;
        let obstacle = (
            0.0..18.0f64,
            0.0..18.0f64,
            0.2..4.0f64,
            0.2..4.0f64,
            any::<bool>(),
        )
            .prop_map(|(x, y, w, h, is_disk)| {
                if is_disk {
                    disk(x, y, w / 2.0)
                } else {
                    rect(x, y, x + w, y + h)
                }
            });
        let pose = (0.0..20.0f64, 0.0..20.0f64, -PI..PI).prop_map(|(x, y, t)| Config::new(x, y, t));
        (
            proptest::collection::vec(obstacle, 0..7),
            (0.2..1.5f64, 0.3..3.0f64, any::<bool>()),
            (0.5..5.0f64, any::<bool>()),
            pose.clone(),
            pose,
        )
            .prop_map(|(obstacles, (half, front, disk), (radius, rs), a, b)| {
                let world = world_of(20.0, 20.0, obstacles);
                let robot = if disk {
                    RobotShape::Disk(half)
                } else {
                    RobotShape::Polygon(ConvexPolygon {
                        vertices: vec![
                            Point::new(-half, -half),
                            Point::new(front, -half),
                            Point::new(front, half),
                            Point::new(-half, half),
                        ],
                    })
                };
                let model = if rs { Model::ReedsShepp } else { Model::Dubins };
                let steering = Steering::new(model, radius);
                let path = CarPath::shortest(steering, a, b);
                (world, robot, path)
            })
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(600))]

        /// The motion checker for curves never accepts a path the validator
        /// rejects.
        #[test]
        fn the_motion_checker_never_accepts_what_the_validator_rejects((world, robot, path) in case()) {
            let referee = Validator::new(&world);
            if CarChecker::new(&world, &robot).path_free(&path) {
                let verdict = validate_car_path(&referee, &robot, &path, None, DEFAULT_TOLERANCE);
                proptest::prop_assert!(verdict.is_ok(), "accepted, the validator says {verdict:?}");
            }
        }
    }

    /// Not vacuous, and close to the validator: over a fixed sample the two
    /// agree on nearly every path, and both verdicts occur.
    #[test]
    fn the_motion_checker_agrees_with_the_validator_on_a_sample() {
        use proptest::strategy::{Strategy, ValueTree};
        use proptest::test_runner::{Config as RunnerConfig, RngAlgorithm, TestRng, TestRunner};
        let mut runner = TestRunner::new_with_rng(
            RunnerConfig::default(),
            TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]),
        );
        let (mut free, mut blocked, mut stricter) = (0, 0, 0);
        for _ in 0..400 {
            let (world, robot, path) = case().new_tree(&mut runner).unwrap().current();
            let referee = Validator::new(&world);
            let ours = CarChecker::new(&world, &robot).path_free(&path);
            let theirs =
                validate_car_path(&referee, &robot, &path, None, DEFAULT_TOLERANCE).is_ok();
            assert!(
                !ours || theirs,
                "accepted what the validator rejects: {path:?}"
            );
            match (ours, theirs) {
                (true, _) => free += 1,
                (false, false) => blocked += 1,
                (false, true) => stricter += 1,
            }
        }
        assert!(
            free >= 40 && blocked >= 40,
            "free {free}, blocked {blocked}"
        );
        assert!(
            stricter <= 4,
            "rejected {stricter} paths the validator accepts"
        );
    }

    /// Grazing: a straight that touches a wall all along, and an arc that
    /// touches a disk at one point, are what the validator says.
    #[test]
    fn grazing_paths_get_the_validators_verdict() {
        let world = world_of(30.0, 30.0, vec![rect(0.0, 0.0, 30.0, 9.5)]);
        let referee = Validator::new(&world);
        // The cart's body spans y ± 0.5: at y = 10 it touches the wall.
        for (y, free) in [(10.0, true), (10.0 - 1e-6, false), (10.0 + 1e-6, true)] {
            let path = CarPath {
                start: Config::new(2.0, y, 0.0),
                steering: Steering::new(Model::ReedsShepp, 3.0),
                segments: vec![Segment {
                    turn: Turn::S,
                    length: 20.0,
                }],
            };
            let theirs =
                validate_car_path(&referee, &cart(), &path, None, DEFAULT_TOLERANCE).is_ok();
            assert_eq!(theirs, free, "validator at y = {y}");
            assert_eq!(
                CarChecker::new(&world, &cart()).path_free(&path),
                free,
                "checker at y = {y}"
            );
        }
    }
}
