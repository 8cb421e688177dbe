//! `drive pure_pursuit` (SPEC 3.8): classic pure pursuit (Coulter 1992).
//!
//! The path is cut at its cusps into *pieces*, each driven one way (a
//! Reeds–Shepp car's reverse segments backwards; every other path is one
//! forward piece). Every step of `dt`:
//! 1. **Projection.** The robot's reference point is projected on the
//!    piece, searching forward from the previous projection, never
//!    backward, within a window of `lookahead + speed·dt` of arc length and
//!    at most [`WINDOW_SEGMENTS`] segments: the cost of a step is bounded,
//!    and a path that comes back near itself is not skipped. The distance
//!    to that projection is the step's deviation.
//! 2. **Target.** The point `lookahead` further along the piece (its end
//!    when closer), at distance `ld` from the robot, at angle α from the
//!    heading (θ, or θ + π in reverse).
//! 3. **Steering.** κ = 2·sin(α)/ld, the arc through the target tangent to
//!    the heading (`ld` = `lookahead` on a straight path); a target behind
//!    (|α| > 90°) turns as hard as a target abeam, κ = ±2/ld. |κ| is
//!    clamped at `max_curvature` (for a car at most 1/R).
//! 4. **Speed.** `speed` · min(1, √(s / lookahead)), s the arc length left
//!    to the piece's end: full speed, then constant deceleration over the
//!    last `lookahead` (to a stop at the end, 2·lookahead/speed seconds
//!    after the braking began). The piece is done when s ≤ `reach`.
//! 5. **Euler.** x += ±v·cos θ·dt, y += ±v·sin θ·dt, θ += v·κ·dt.
//!
//! A robot without a curvature bound (not a car, no `max_curvature`) turns
//! in place when the target is more than [`ROTATE_ABOVE`] (45°, Nav2's
//! regulated pure pursuit's `rotate_to_heading_min_angle`) off its heading
//! (at the start when the path leaves sideways or behind, at a sharp
//! corner), at 2·speed/lookahead rad/s (the rate of the tightest
//! pure-pursuit arc at full speed), until it faces the target; then it
//! drives on. A robot with a bound cannot and drives its tightest arc.

use std::collections::BTreeMap;

use super::{DriveOutcome, MAX_DRIVE_STEPS, block_value, unfinished};
use crate::contract::Param;
use crate::contract::schema::PURE_PURSUIT_PARAMS;
use crate::geometry::car::{CarPath, DRAW_STEP};
use crate::geometry::steer::{Model, Segment};
use crate::geometry::{Config, Point, angle_diff};

/// The heading error above which a robot without a curvature bound turns
/// in place (until it faces the target).
pub const ROTATE_ABOVE: f64 = std::f64::consts::FRAC_PI_4;

/// The most path segments the projection examines in one step.
pub const WINDOW_SEGMENTS: usize = 1024;

/// The most points a car's path is sampled into (16 bytes each).
const MAX_CAR_POINTS: usize = 1_000_000;

/// Settings of `drive pure_pursuit { ... }`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PurePursuit {
    pub lookahead: f64,
    pub speed: f64,
    pub dt: f64,
    pub reach: f64,
    /// The user's bound on |κ| (a car's is also at most 1/R).
    pub max_curvature: Option<f64>,
}

impl PurePursuit {
    /// The settings of a validated `drive pure_pursuit { ... }` block: each
    /// key as given, or its default in [`PURE_PURSUIT_PARAMS`].
    pub fn from_block(block: &BTreeMap<&'static str, Param>) -> Self {
        let get = |key: &str| {
            block_value(PURE_PURSUIT_PARAMS, block, key)
                .unwrap_or_else(|| panic!("drive key `{key}` has no numeric default"))
        };
        PurePursuit {
            lookahead: get("lookahead"),
            speed: get("speed"),
            dt: get("dt"),
            reach: get("reach"),
            max_curvature: block_value(PURE_PURSUIT_PARAMS, block, "max_curvature"),
        }
    }
}

impl Default for PurePursuit {
    /// Every key at its default.
    fn default() -> Self {
        PurePursuit::from_block(&BTreeMap::new())
    }
}

/// A part of the path driven one way: its points (no two consecutive
/// equal) and their arc lengths from the first.
struct Piece {
    points: Vec<Point>,
    arc: Vec<f64>,
    /// +1 forward, −1 in reverse.
    dir: f64,
}

impl Piece {
    fn new(dir: f64, first: Point) -> Self {
        Piece {
            points: vec![first],
            arc: vec![0.0],
            dir,
        }
    }

    fn push(&mut self, p: Point) {
        let last = self.points[self.points.len() - 1];
        let d = (p - last).norm();
        if d > 0.0 {
            self.arc.push(self.arc[self.arc.len() - 1] + d);
            self.points.push(p);
        }
    }

    fn length(&self) -> f64 {
        self.arc[self.arc.len() - 1]
    }

    /// The point at arc length `s` (clamped to the piece).
    fn at(&self, s: f64) -> Point {
        let n = self.points.len();
        if n == 1 || s <= 0.0 {
            return self.points[0];
        }
        if s >= self.length() {
            return self.points[n - 1];
        }
        // The segment k with arc[k] ≤ s < arc[k + 1].
        let k = self.arc.partition_point(|&a| a <= s).clamp(1, n - 1) - 1;
        let t = (s - self.arc[k]) / (self.arc[k + 1] - self.arc[k]);
        self.points[k] + (self.points[k + 1] - self.points[k]) * t
    }

    /// The projection of `p` from arc length `from` (on segment `seg`)
    /// forward within `window`: (arc length, segment, distance), the first
    /// closest point on ties.
    fn project(&self, p: Point, from: f64, seg: usize, window: f64) -> (f64, usize, f64) {
        let mut best = (from, seg, (p - self.at(from)).norm());
        let last = (self.points.len() - 1).min(seg + WINDOW_SEGMENTS);
        for k in seg..last {
            if self.arc[k] > from + window {
                break;
            }
            let (a, b) = (self.points[k], self.points[k + 1]);
            let len = self.arc[k + 1] - self.arc[k];
            let t_min = ((from - self.arc[k]) / len).clamp(0.0, 1.0);
            let t = ((p - a).dot(&(b - a)) / (len * len)).clamp(t_min, 1.0);
            let q = a + (b - a) * t;
            let d = (p - q).norm();
            if d < best.2 {
                best = (self.arc[k] + t * len, k, d);
            }
        }
        best
    }
}

/// The pieces of a path given by its poses: one forward piece.
fn pieces_of_poses(path: &[Config]) -> Vec<Piece> {
    let mut piece = Piece::new(1.0, path[0].xy());
    for c in &path[1..] {
        piece.push(c.xy());
    }
    vec![piece]
}

/// The pieces of a car's path: its segments sampled at most `step` apart
/// (exactly at their ends), cut where the direction changes. A Dubins
/// car's pieces are all forward.
fn pieces_of_car(car: &CarPath, step: f64) -> Vec<Piece> {
    let steering = car.steering;
    let step = step.max(car.length() / MAX_CAR_POINTS as f64);
    let reverses = steering.model == Model::ReedsShepp;
    let mut pieces: Vec<Piece> = Vec::new();
    let mut c = car.start;
    for s in &car.segments {
        if s.length == 0.0 || !s.length.is_finite() {
            continue;
        }
        let dir = if s.length < 0.0 && reverses {
            -1.0
        } else {
            1.0
        };
        match pieces.last_mut() {
            Some(p) if p.dir == dir => {}
            _ => pieces.push(Piece::new(dir, c.xy())),
        }
        let piece = pieces.last_mut().expect("a piece was pushed");
        let n = ((s.length.abs() / step).ceil() as usize).max(1);
        for k in 1..=n {
            let part = s.length * k as f64 / n as f64;
            piece.push(Segment::advance(c, s.turn, part, steering.radius).xy());
        }
        c = s.end(c, steering.radius);
    }
    pieces
}

/// Drives `path` from its first configuration (heading = its θ); a car's
/// path (`car`: its segments and steering) is followed along its segments,
/// with its curvature bound and its cusps.
pub fn drive(path: &[Config], car: Option<&CarPath>, pp: &PurePursuit) -> DriveOutcome {
    let Some(first) = path.first() else {
        return DriveOutcome {
            completed: true,
            ..DriveOutcome::default()
        };
    };
    let pieces = match car {
        Some(car) => pieces_of_car(car, DRAW_STEP.min(pp.lookahead / 8.0)),
        None => pieces_of_poses(path),
    };
    let max_curvature = match (car, pp.max_curvature) {
        (Some(car), user) => {
            let bound = 1.0 / car.steering.radius;
            Some(user.map_or(bound, |k| k.min(bound)))
        }
        (None, user) => user,
    };
    let (l, v_max, dt) = (pp.lookahead, pp.speed, pp.dt);
    let turn_rate = 2.0 * v_max / l;
    let window = l + v_max * dt;
    let mut state = *first;
    let mut samples = vec![(0.0, state)];
    let mut steps = 0usize;
    let mut max_dev = 0.0f64;
    let mut rotating = false;
    for piece in &pieces {
        let (mut s, mut seg) = (0.0, 0usize);
        let end = piece.length();
        loop {
            let (s_new, seg_new, dev) = piece.project(state.xy(), s, seg, window);
            (s, seg) = (s_new, seg_new);
            max_dev = max_dev.max(dev);
            let left = end - s;
            if left <= pp.reach {
                break;
            }
            if steps >= MAX_DRIVE_STEPS {
                return unfinished(samples, max_dev);
            }
            let to = piece.at(s + l) - state.xy();
            let ld = to.norm();
            let heading = if piece.dir < 0.0 {
                state.theta + std::f64::consts::PI
            } else {
                state.theta
            };
            let alpha = if ld > 0.0 {
                angle_diff(heading, to.y.atan2(to.x))
            } else {
                0.0
            };
            let behind = alpha.abs() > std::f64::consts::FRAC_PI_2;
            rotating =
                max_curvature.is_none() && alpha != 0.0 && (rotating || alpha.abs() > ROTATE_ABOVE);
            if rotating {
                // Turn in place until facing the target.
                state.theta += alpha.signum() * (turn_rate * dt).min(alpha.abs());
            } else {
                let v = v_max * (left / l).sqrt().min(1.0);
                let mut kappa = match ld > 0.0 {
                    false => 0.0,
                    true if behind => 2.0 * alpha.signum() / ld,
                    true => 2.0 * alpha.sin() / ld,
                };
                if let Some(k) = max_curvature {
                    kappa = kappa.clamp(-k, k);
                }
                let (sin, cos) = state.theta.sin_cos();
                state.x += piece.dir * v * cos * dt;
                state.y += piece.dir * v * sin * dt;
                state.theta += v * kappa * dt;
            }
            steps += 1;
            samples.push((steps as f64 * dt, state));
        }
    }
    DriveOutcome {
        samples,
        time: steps as f64 * dt,
        max_deviation: max_dev,
        completed: true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::steer::{Steering, Turn};
    use std::f64::consts::PI;

    fn line(length: f64) -> Vec<Config> {
        vec![Config::new(0.0, 0.0, 0.0), Config::new(length, 0.0, 0.0)]
    }

    #[test]
    fn a_straight_line_takes_its_length_over_the_speed_plus_the_stop() {
        let pp = PurePursuit {
            speed: 2.0,
            ..PurePursuit::default()
        };
        let length = 10.0;
        let out = drive(&line(length), None, &pp);
        assert!(out.completed);
        // Straight on: no deviation, no turn, never beyond the end.
        for (_, c) in &out.samples {
            assert_eq!((c.y, c.theta), (0.0, 0.0));
            assert!(c.x <= length);
        }
        assert!(out.max_deviation < 1e-12, "{}", out.max_deviation);
        // Full speed until `lookahead` from the end, exactly.
        let braking = out
            .samples
            .iter()
            .position(|(_, c)| length - c.x < pp.lookahead)
            .unwrap();
        let cruise = out.samples[braking].0;
        let expected = (length - pp.lookahead) / pp.speed;
        assert!((cruise - expected).abs() <= pp.dt + 1e-9, "{cruise}");
        // Then constant deceleration to `reach`: 2·(L − √(L·reach))/V in
        // continuous time.
        let stop = 2.0 * (pp.lookahead - (pp.lookahead * pp.reach).sqrt()) / pp.speed;
        assert!(
            (out.time - expected - stop).abs() <= 2.0 * pp.dt,
            "{} vs {}",
            out.time,
            expected + stop
        );
        let last = out.samples.last().unwrap().1;
        assert!(length - last.x <= pp.reach && length - last.x >= 0.0);
        assert_eq!(out.time, out.samples.last().unwrap().0);
    }

    /// A circle of radius `r` from (r, 0) counter-clockwise, as `n` chords.
    fn circle(r: f64, n: usize) -> Vec<Config> {
        (0..=n)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / n as f64;
                Config::new(r * a.cos(), r * a.sin(), a + PI / 2.0)
            })
            .collect()
    }

    #[test]
    fn a_circle_wider_than_the_lookahead_is_followed_closely() {
        let r = 3.0;
        let pp = PurePursuit::default();
        assert!(r > pp.lookahead);
        let out = drive(&circle(r, 720), None, &pp);
        assert!(out.completed);
        assert!(out.max_deviation < 0.01, "{}", out.max_deviation);
        // Around once at full speed, then the stop.
        let around = 2.0 * PI * r / pp.speed;
        assert!(out.time > around && out.time < around + 2.0 * pp.lookahead / pp.speed);
        let last = out.samples.last().unwrap().1;
        assert!((last.xy() - Point::new(r, 0.0)).norm() < 0.01);
    }

    #[test]
    fn a_target_off_the_heading_turns_in_place_first() {
        // Heading east, the path goes west: turn round where it stands.
        let path = [Config::new(0.0, 0.0, 0.0), Config::new(-5.0, 0.0, 0.0)];
        let pp = PurePursuit::default();
        let out = drive(&path, None, &pp);
        assert!(out.completed);
        assert!(out.max_deviation < 1e-9, "{}", out.max_deviation);
        // Half a turn at 2·speed/lookahead rad/s, then the line.
        let turning = out.samples.iter().take_while(|(_, c)| c.x == 0.0).count();
        assert_eq!(turning as f64, (PI / (2.0 * pp.dt)).ceil() + 1.0);
        // A bounded curvature cannot: it drives the tightest arc.
        let bounded = drive(
            &path,
            None,
            &PurePursuit {
                max_curvature: Some(0.5),
                ..pp
            },
        );
        assert!(bounded.completed);
        assert!(bounded.max_deviation > 1.0, "{}", bounded.max_deviation);
        for w in bounded.samples.windows(2) {
            let (a, b) = (w[0].1, w[1].1);
            let ds = (b.xy() - a.xy()).norm();
            assert!((b.theta - a.theta).abs() <= 0.5 * ds + 1e-12);
        }
    }

    fn car(segments: &[(Turn, f64)], radius: f64, model: Model) -> CarPath {
        CarPath {
            start: Config::new(0.0, 0.0, 0.0),
            steering: Steering { model, radius },
            segments: segments
                .iter()
                .map(|&(turn, length)| Segment { turn, length })
                .collect(),
        }
    }

    #[test]
    fn a_car_never_turns_tighter_than_its_radius() {
        // A polyline corner of 90° would need an infinite curvature; a car
        // of radius 2 rounds it, never turning more than ds / 2.
        let path = car(
            &[(Turn::S, 4.0), (Turn::L, PI), (Turn::S, 4.0)],
            2.0,
            Model::Dubins,
        );
        let poses = path.poses(0.1);
        let out = drive(&poses, Some(&path), &PurePursuit::default());
        assert!(out.completed);
        let mut tightest = 0.0f64;
        for w in out.samples.windows(2) {
            let (a, b) = (w[0].1, w[1].1);
            let ds = (b.xy() - a.xy()).norm();
            assert!((b.theta - a.theta).abs() <= ds / 2.0 + 1e-12);
            if ds > 0.0 {
                tightest = tightest.max((b.theta - a.theta).abs() / ds);
            }
        }
        // The clamp was active (the lookahead point on the arc asks for
        // 1/R or more while entering it).
        assert!((tightest - 0.5).abs() < 1e-9, "{tightest}");
        assert!(out.max_deviation < 0.1, "{}", out.max_deviation);
        // Without the clamp (a point robot on the same poses) it cuts the
        // corner tighter than the car can.
        let free = drive(&poses, None, &PurePursuit::default());
        let sharpest = free
            .samples
            .windows(2)
            .filter_map(|w| {
                let ds = (w[1].1.xy() - w[0].1.xy()).norm();
                (ds > 0.0).then(|| (w[1].1.theta - w[0].1.theta).abs() / ds)
            })
            .fold(0.0, f64::max);
        assert!(sharpest > 0.5, "{sharpest}");
    }

    #[test]
    fn a_car_reverses_at_its_cusps() {
        // Forward 3, back 3 on a left arc, forward 2: two cusps.
        let path = car(
            &[(Turn::S, 3.0), (Turn::L, -3.0), (Turn::S, 2.0)],
            2.0,
            Model::ReedsShepp,
        );
        let pieces = pieces_of_car(&path, 0.1);
        assert_eq!(
            pieces.iter().map(|p| p.dir).collect::<Vec<_>>(),
            [1.0, -1.0, 1.0]
        );
        let poses = path.poses(0.1);
        let out = drive(&poses, Some(&path), &PurePursuit::default());
        assert!(out.completed);
        assert!(out.max_deviation < 0.05, "{}", out.max_deviation);
        // The robot moved backwards (against its heading) for a while.
        let backwards = out.samples.windows(2).any(|w| {
            let (a, b) = (w[0].1, w[1].1);
            (b.x - a.x) * a.theta.cos() + (b.y - a.y) * a.theta.sin() < -1e-6
        });
        assert!(backwards);
        let end = path.end();
        let last = out.samples.last().unwrap().1;
        assert!((last.xy() - end.xy()).norm() < 0.01, "{last:?} vs {end:?}");
        assert!(angle_diff(last.theta, end.theta).abs() < 0.05);
        // A Dubins car's pieces are all forward.
        let dubins = CarPath {
            steering: Steering {
                model: Model::Dubins,
                radius: 2.0,
            },
            ..path
        };
        assert!(pieces_of_car(&dubins, 0.1).iter().all(|p| p.dir == 1.0));
    }

    #[test]
    fn a_step_cap_stops_a_hopeless_drive() {
        let pp = PurePursuit {
            dt: 1e-6,
            speed: 1e-3,
            ..PurePursuit::default()
        };
        let out = drive(&line(10.0), None, &pp);
        assert!(!out.completed);
        assert!(out.time.is_infinite());
        assert_eq!(out.samples.len(), MAX_DRIVE_STEPS + 1);
    }

    #[test]
    fn the_projection_never_goes_back_nor_beyond_its_window() {
        // Out along x and back: near the start the robot is also near the
        // end, which the projection must not jump to.
        let path: Vec<Config> = [(0.0, 0.0), (5.0, 0.0), (5.0, 0.2), (0.0, 0.2)]
            .iter()
            .map(|&(x, y)| Config::new(x, y, 0.0))
            .collect();
        let pieces = pieces_of_poses(&path);
        let piece = &pieces[0];
        let (s, _, d) = piece.project(Point::new(0.0, 0.15), 0.0, 0, 1.0);
        assert!(s <= 1.0 && (d - 0.15).abs() < 1e-12, "{s} {d}");
        // From s = 2 a point behind projects at 2, not back.
        let (s, seg, _) = piece.project(Point::new(1.0, 0.0), 2.0, 0, 1.0);
        assert_eq!((s, seg), (2.0, 0));
        let out = drive(&path, None, &PurePursuit::default());
        assert!(out.completed);
        let last = out.samples.last().unwrap().1;
        assert!(last.x < 0.01 && (last.y - 0.2).abs() < 0.05, "{last:?}");
    }

    #[test]
    fn an_empty_or_single_point_path_needs_no_driving() {
        let pp = PurePursuit::default();
        assert!(drive(&[], None, &pp).completed);
        let one = drive(&[Config::new(1.0, 2.0, 0.3)], None, &pp);
        assert!(one.completed);
        assert_eq!((one.time, one.samples.len()), (0.0, 1));
    }

    #[test]
    fn the_defaults_are_the_ones_the_schema_writes() {
        let block: Vec<String> = PURE_PURSUIT_PARAMS
            .iter()
            .filter(|p| matches!(p.default, crate::contract::schema::DefaultValue::Num(..)))
            .map(|p| format!("{} {}", p.key, p.default.text()))
            .collect();
        let text = format!(
            "world {{ bounds (0, 0) (4, 4) }}\nrobot r point\n\
             plan a astar r {{ start (1, 1) goal (3, 3) drive pure_pursuit {{ {} }} }}\n",
            block.join(" ")
        );
        let scenario = crate::scenario::load_text(&text);
        let Some(crate::contract::ParamValue::Block(model, given)) =
            scenario.plans[0].params.get("drive")
        else {
            panic!("no drive block");
        };
        assert_eq!(model, "pure_pursuit");
        assert_eq!(given.len(), PURE_PURSUIT_PARAMS.len() - 1);
        assert_eq!(PurePursuit::from_block(given), PurePursuit::default());
        let d = PurePursuit::default();
        assert_eq!(
            (d.lookahead, d.speed, d.dt, d.reach),
            (1.0, 1.0, 0.01, 0.0009)
        );
        assert_eq!(d.max_curvature, None);
    }
}
