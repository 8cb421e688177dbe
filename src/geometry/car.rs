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

use super::steer::{Model, Segment, SteerPath, Steering, Turn};
use super::validator::{DEFAULT_TOLERANCE, ValidationError, Validator};
use super::{Config, RobotShape, angle_diff};

/// How close to the goal the integrated path must end (position, in world
/// units, and heading, in radians; SPEC 3.0).
pub const END_TOLERANCE: f64 = 1e-9;

/// The most sub-steps a car path is swept in (24 bytes each): a longer
/// path at this tolerance is reported as too long to validate, never
/// accepted unchecked.
pub const MAX_SUB_STEPS: usize = 4_000_000;

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
    /// The steering path `path` from `start` (SPEC 2.4).
    pub fn from_steer(start: Config, steering: Steering, path: &SteerPath) -> Self {
        CarPath {
            start,
            steering,
            segments: path.segments().to_vec(),
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

    /// The poses at the start, at the segment ends and at most every `step`
    /// of arc length (headings in [0, 2π)): what is drawn and listed as the
    /// plan's `"path"`. At most [`MAX_SUB_STEPS`] poses: a longer path is
    /// drawn with a larger step.
    pub fn poses(&self, step: f64) -> Vec<Config> {
        let step = step.max(self.length() / MAX_SUB_STEPS as f64);
        let mut out = vec![wrapped(self.start)];
        let mut c = self.start;
        for s in &self.segments {
            let n = pieces(s.length.abs(), step);
            for k in 1..=n {
                let part = s.length * k as f64 / n as f64;
                out.push(wrapped(Segment::advance(
                    c,
                    s.turn,
                    part,
                    self.steering.radius,
                )));
            }
            c = s.end(c, self.steering.radius);
        }
        out
    }
}

/// `theta` in [0, 2π).
fn wrapped(c: Config) -> Config {
    let t = c.theta.rem_euclid(std::f64::consts::TAU);
    Config::new(c.x, c.y, if t >= std::f64::consts::TAU { 0.0 } else { t })
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
/// [`DEFAULT_TOLERANCE`]).
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
    let tolerance = if tolerance.is_finite() && tolerance > 0.0 {
        tolerance
    } else {
        DEFAULT_TOLERANCE
    };
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
    // The sub-steps: every point of the body moves at most `tolerance`.
    let reach = robot.radius();
    let mut counts = Vec::with_capacity(path.segments.len());
    let mut total = 0usize;
    for s in &path.segments {
        // A translating convex body sweeps exactly the hull of its two
        // ends: a straight needs no sub-steps for soundness, only pieces of
        // about the body's size so that a failure is located.
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
    use crate::geometry::steer::Model;
    use crate::geometry::validator::validate_path;
    use crate::geometry::{ConvexPolygon, Point};
    use crate::scenario::world_of_text;

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
        let world = world_of_text("world { bounds (0, 0) (30, 30)\ndisk (8.6, 23) 0.4 }");
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
        let far = world_of_text("world { bounds (0, 0) (30, 30)\ndisk (9.7, 23) 0.4 }");
        let referee = Validator::new(&far);
        assert!(validate_car_path(&referee, &cart(), &path, Some(goal), DEFAULT_TOLERANCE).is_ok());
    }

    #[test]
    fn the_end_must_be_the_goal_and_a_dubins_car_never_reverses() {
        let world = world_of_text("world { bounds (0, 0) (30, 30) }");
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
        let world = world_of_text("world { bounds (0, 0) (7.5, 30) }");
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
}
