//! The planners' motion checker: is the straight motion of a robot from
//! configuration `a` to configuration `b` free? (SPEC 3.7: every motion a
//! sampling planner adds is checked here; there is no collision-checking
//! resolution.)
//!
//! # Contract
//! [`MotionChecker::motion_free`] never accepts a motion that the validator
//! ([`super::validator`], SPEC 3.0) rejects at [`DEFAULT_TOLERANCE`]; it
//! rejects more only where the validator's verdict hangs on less than
//! `TOUCH_EPS / 2` of overlap or on the rounding of a hull, where a polygon
//! pokes a few `TOUCH_EPS` into the seam between two blocked grid cells,
//! and (for points) where it touches a segment obstacle. [`MotionChecker::config_free`] likewise
//! never accepts a configuration that [`super::validator::config_collision`]
//! blocks or that lies outside the bounds.
//!
//! The motion is the validator's: x and y linear, θ along the shorter arc
//! ([`angle_diff`]). Bounds are a closed box and convex, so both ends inside
//! means the whole (x, y) path is inside; the validator's margin of
//! `TOUCH_EPS` around the bounds is not granted.
//!
//! # Point and disk robots
//! θ plays no part: [`ObstacleIndex::sweep_free`] decides the swept capsule
//! (the segment for a point) exactly, with the validator's rule, except that
//! a point may not even touch a segment obstacle. The validator lets a point
//! touch a segment as long as its whole path stays on one side of the
//! segments, which one motion alone cannot tell; refusing every contact is
//! sound for any path made of such motions (see [`super::collide`]).
//!
//! # Convex polygon robots
//! The validator cuts the motion into `n` equal sub-steps (1 for a
//! translation, `⌈(|Δxy| + R·|Δθ|) / tolerance⌉` when it rotates, R the
//! robot's [`RobotShape::radius`]) and requires the hull of the bodies at
//! the two ends of each sub-step to overlap no convex obstacle piece deeper
//! than `TOUCH_EPS`. The checker cuts the motion at the same configurations,
//! computed by the same formula, and decides *groups* of consecutive
//! sub-steps at once.
//!
//! ## Groups
//! For a group of sub-steps `k0 .. k1`, let `A_i`, `B_i` be vertex `v_i` of
//! the body at the group's two ends and α the group's rotation. During the
//! group, `v_i` moves on `p(λ) = xy(λ) + Rot(θ(λ))·v_i` with xy and θ linear
//! in λ ∈ [0, 1]. Its deviation from the chord `(1−λ)·A_i + λ·B_i` is
//! `f(λ) = Rot(θ(λ))·v_i − (1−λ)·Rot(θ(0))·v_i − λ·Rot(θ(1))·v_i` (the
//! translation is linear and cancels): `f(0) = f(1) = 0` and
//! `|f''| = α²·|v_i|`, so for every unit u, `|u·f(λ)| ≤ λ(1−λ)·k_i` with
//! `k_i = |v_i|·α²/2`. Hence
//!
//! ```text
//! u·p(λ) ≤ (1−λ)·u·A_i + λ·u·B_i + λ(1−λ)·k_i,
//! ```
//!
//! a parabola in λ whose largest value on [0, 1] ([`bulge`]) is at most
//! `max(u·A_i, u·B_i) + |v_i|·α²/8`, and is exactly `max(u·A_i, u·B_i)`
//! when `|u·B_i − u·A_i| ≥ k_i` (so a robot pivoting on a wall it touches,
//! or turning away from one, is cleared without cutting the motion down to
//! the sub-step where it touches).
//! Every body during the group is a convex polygon, extreme along u at a
//! vertex, so along every unit axis u all of them project into the interval
//! between those bounds for `−u` and `u`, and so does the hull of any two
//! of them: every validator sub-step inside the group. If along some axis
//! that interval and an obstacle piece's projection overlap by at most
//! `TOUCH_EPS / 2` (their *gap* is at least `−TOUCH_EPS / 2`), no sub-step
//! of the group overlaps that piece deeper than `TOUCH_EPS / 2`, since the
//! penetration depth is the smallest overlap over all directions.
//!
//! The axes tried are ±x and ±y (the boxes of both), the edge normals of the
//! hull `H` of the `A_i` and `B_i`, the piece's own edge normals, and for a
//! disk obstacle the direction from its centre's nearest point of `H`. A
//! group none of whose pieces fails passes; the pieces that fail are handed
//! to the two halves of the group (split at a sub-step boundary), since a
//! piece cleared for the group is cleared for every sub-step in it. A single
//! sub-step is decided with `k_i = 0`: then the interval along u is exactly
//! `H`'s projection, the axes are all the separating-axis candidates of the
//! two convex sets (and the exact nearest-point axis for disks), and the
//! largest gap is exactly minus the penetration depth: the validator's test,
//! with the threshold `TOUCH_EPS / 2` instead of `TOUCH_EPS` so that
//! rounding never tips a verdict the wrong way. So the checker accepts what
//! the validator accepts up to that margin, and in free space it needs a
//! handful of group tests (the bound shrinks 4-fold per halving) rather
//! than `n`.
//!
//! ## Obstacle pieces
//! Polygons give their convex pieces, rectangles themselves, segments their
//! two ends (a segment has no interior, but overlapping it deeper than
//! `TOUCH_EPS` is a collision, exactly as for a flat polygon), grids the
//! rectangles of [`super::cspace::grid_rectangles`], disks their exact circle. A merged
//! grid rectangle contains the cells it is made of, so the depth into it is
//! at least the depth into any of them: conservative (see the
//! [`super::cspace`] documentation for the few contacts it refuses). The
//! seams of multi-piece obstacles play no part: a robot with area cannot
//! lie on a seam without overlapping a piece (the validator's rule too).
//!
//! # Cost
//! A uniform bucket grid of the pieces' boxes ([`Buckets`]) gives the pieces
//! near the box of the whole motion; each is reported once (in the first bucket
//! that both boxes meet). A turning motion's box is first taken loosely (each
//! vertex's parabola raised to its worst, a quarter of its curvature above its
//! higher end: no test and no division); most motions meet no piece even by
//! that box, and only the others compute the exact one (the pieces near it are
//! among those found). A motion to (or from) a new state
//! ([`MotionChecker::extension_free`]) tests the new state's body first,
//! against the pieces near that body alone: most extensions that fail end in
//! collision, and then neither the whole motion's bounds and hull nor the
//! pieces near the whole motion are needed. It changes no verdict: a body
//! overlapping a piece deeper than `TOUCH_EPS / 2` lies in the hull of the
//! sub-step it ends, which overlaps the piece at least as deep, so the group
//! search would reject the motion too. The groups are visited depth first, left
//! half first, so a motion that collides late would first have every sub-step
//! before its collision cleared: when the whole motion fails, the bodies at its
//! end, middle and quarters are tested first (a body in collision fails the
//! sub-steps around it anyway, so this changes no verdict beyond rounding; it
//! finds most collisions at once). An extension that meets a piece probes those
//! bodies (its new end, already tested, excepted) before the whole motion's
//! hull is made: growing into the unknown, most such extensions collide (94 %
//! of them for the apartment rod's `rrt_connect`), while most motions between
//! two roadmap states that meet a piece are free. A hull axis's bound (every
//! vertex's bulge) is computed only when a piece lies beyond the hull's own
//! edge along it ([`HullAxis`]): most axes face away from the piece, and an
//! axis skipped is only an axis not tried, so no verdict changes (a single
//! sub-step's bound is its hull's projection, never below the edge's). Nothing
//! is allocated per query once the calling thread has checked one motion (a
//! thread-local scratch), and the checker itself is immutable, hence `Sync`.
//! Figures: BENCHMARKS.md.

use std::cell::RefCell;

use super::angle_diff;
use super::buckets::Buckets;
use super::collide::ObstacleIndex;
use super::cspace::shape_pieces;
use super::minkowski::DISK_SIDES;
use super::polygon::{closest_point_on_segment, convex_hull_into};
use super::validator::DEFAULT_TOLERANCE;
use super::{
    Aabb, Config, ConvexPolygon, Point, RobotShape, Shape, TOUCH_EPS, Vector, World,
    max_of_numbers, min_of_numbers, place, sin_cos_fast,
};

/// A gap of at least this along an axis clears a piece: an overlap of at
/// most `TOUCH_EPS / 2`, half the validator's threshold.
const SLACK: f64 = -TOUCH_EPS / 2.0;

/// Where [`PolygonChecker::witness`] looks, in eighths of the motion.
const WITNESSES: [u128; 4] = [8, 4, 2, 6];

/// Up to this many pieces, the broad phase scans their boxes rather than
/// the buckets (a long wall lies in many buckets: the apartment's 11 walls
/// cost more through them).
const SCAN_PIECES: usize = 32;

/// The buckets of the broad phase have at most this many per side.
const MAX_BUCKETS_PER_SIDE: usize = 512;

/// Whether straight motions of one robot in one world are free (see the
/// module documentation). Build it once per plan; queries take `&self`.
pub struct MotionChecker {
    bounds: Aabb,
    robot: Robot,
}

/// Which end of a motion is a new state ([`MotionChecker::extension_free`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NewEnd {
    Start,
    End,
}

enum Robot {
    /// A point (radius 0) or a disk of that radius.
    Round {
        index: ObstacleIndex,
        radius: f64,
    },
    Polygon(PolygonChecker),
}

impl MotionChecker {
    /// Prepares `world` for `robot`: O(size of the obstacles), grids merged
    /// into rectangles for polygon robots.
    pub fn new(world: &World, robot: &RobotShape) -> Self {
        let robot = match robot {
            RobotShape::Point => Robot::Round {
                index: ObstacleIndex::new(world),
                radius: 0.0,
            },
            RobotShape::Disk(r) => Robot::Round {
                index: ObstacleIndex::new(world),
                radius: r.max(0.0),
            },
            RobotShape::Polygon(p) => Robot::Polygon(PolygonChecker::new(world, p)),
        };
        MotionChecker {
            bounds: world.bounds,
            robot,
        }
    }

    /// Whether the robot at `c` is inside the (closed) bounds and its body
    /// overlaps no obstacle interior deeper than `TOUCH_EPS / 2` (a point
    /// also keeps off segment obstacles). `false` for non-finite `c`.
    pub fn config_free(&self, c: Config) -> bool {
        self.in_bounds(c)
            && match &self.robot {
                Robot::Round { index, radius } => index.disk_free(c.xy(), *radius),
                Robot::Polygon(p) => p.body_free(c),
            }
    }

    /// Whether the straight motion from `a` to `b` (θ along the shorter arc)
    /// is free: both ends inside the (closed) bounds, and every validator
    /// sub-step clear of every obstacle piece (see the module
    /// documentation). If it returns `true`, the validator accepts the path
    /// `[a, b]` at [`DEFAULT_TOLERANCE`].
    pub fn motion_free(&self, a: Config, b: Config) -> bool {
        self.motion(a, b, None)
    }

    /// [`MotionChecker::motion_free`], the same verdict, for a motion whose
    /// `new` end is a state no check has seen: that state's body is tested
    /// first.
    pub fn extension_free(&self, a: Config, b: Config, new: NewEnd) -> bool {
        self.motion(a, b, Some(new))
    }

    fn motion(&self, a: Config, b: Config, new: Option<NewEnd>) -> bool {
        self.in_bounds(a)
            && self.in_bounds(b)
            && match &self.robot {
                Robot::Round { index, radius } => index.sweep_free(a.xy(), b.xy(), *radius),
                Robot::Polygon(p) => {
                    let cut = Cut::new(a, b, p.radius);
                    let fresh = new.map(|end| match end {
                        NewEnd::Start => 0,
                        NewEnd::End => cut.steps,
                    });
                    p.free(&cut, fresh)
                }
            }
    }

    /// The world's bounds, where the robot's reference point must stay.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    fn in_bounds(&self, c: Config) -> bool {
        c.theta.is_finite() && c.x.is_finite() && c.y.is_finite() && self.bounds.contains(c.xy())
    }
}

// ------------------------------------------------------------ polygons

/// The obstacle pieces prepared for one convex polygon robot.
struct PolygonChecker {
    /// The robot's vertices in its own frame, counter-clockwise.
    vertices: Vec<Point>,
    /// `|v_i|` for each vertex.
    lever: Vec<f64>,
    /// The robot's outward unit edge normals in its own frame, each with
    /// the body's largest projection on it (see [`Region::ensure_hull`]).
    edge_normals: Vec<(Vector, f64)>,
    /// R, as the validator computes it ([`RobotShape::radius`]).
    radius: f64,
    pieces: Vec<Piece>,
    /// The points of the convex pieces, piece after piece.
    points: Vec<Point>,
    /// The edge normals of the convex pieces, piece after piece.
    axes: Vec<Axis>,
    buckets: Buckets,
}

#[derive(Clone, Copy, Debug)]
struct Piece {
    aabb: Aabb,
    /// The first bucket column and row that `aabb` meets.
    first: (u32, u32),
    kind: Kind,
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    /// `points[points.0 .. points.1]` (1 for a point, 2 for a segment, else
    /// a counter-clockwise convex polygon) and `axes[axes.0 .. axes.1]`.
    Convex {
        points: (u32, u32),
        axes: (u32, u32),
    },
    Disk {
        center: Point,
        radius: f64,
    },
}

/// An outward unit edge normal `n` of a piece, other than ±x and ±y (which
/// the piece's box covers), and the piece's largest projection on it.
#[derive(Clone, Copy, Debug)]
struct Axis {
    n: Vector,
    support: f64,
}

impl PolygonChecker {
    fn new(world: &World, robot: &ConvexPolygon) -> Self {
        let mut pieces = Vec::new();
        let mut points = Vec::new();
        let mut axes = Vec::new();
        for o in &world.obstacles {
            match &o.shape {
                Shape::Disk { center, radius } => {
                    let r = Vector::new(*radius, *radius);
                    pieces.push(Piece {
                        aabb: Aabb {
                            min: center - r,
                            max: center + r,
                        },
                        first: (0, 0),
                        kind: Kind::Disk {
                            center: *center,
                            radius: *radius,
                        },
                    });
                }
                shape => shape_pieces(shape, DISK_SIDES, |pts| {
                    pieces.push(convex_piece(&pts, &mut points, &mut axes));
                }),
            }
        }
        let boxes: Vec<Aabb> = pieces.iter().map(|p| p.aabb).collect();
        let buckets = Buckets::new(world.bounds, &boxes, MAX_BUCKETS_PER_SIDE);
        for piece in &mut pieces {
            let ((c, _), (k, _)) = buckets.range(&piece.aabb);
            piece.first = (c as u32, k as u32);
        }
        let shape = RobotShape::Polygon(robot.clone());
        PolygonChecker {
            vertices: robot.vertices.clone(),
            lever: robot.vertices.iter().map(|v| v.coords.norm()).collect(),
            edge_normals: edge_normals(&robot.vertices).collect(),
            radius: shape.radius(),
            pieces,
            points,
            axes,
            buckets,
        }
    }

    /// Whether the body at `c` is clear of every piece: placed once, its
    /// vertices its own hull. The verdict of the single sub-step from `c`
    /// to `c` (whose hull is that body: the same edges and projections, the
    /// normals rotated rather than normalised, see [`Region::ensure_hull`])
    /// at the cost of one placement.
    fn body_free(&self, c: Config) -> bool {
        with_scratch(|Scratch { region, pending }| {
            self.boundary_free(&Cut::still(c), 0, pending, region)
        })
    }

    /// Whether the body at boundary `k` of `cut` is clear of the pieces
    /// near it; `region` is set to that body.
    fn boundary_free(
        &self,
        cut: &Cut,
        k: usize,
        pending: &mut Vec<u32>,
        region: &mut Region,
    ) -> bool {
        region.set(self, cut, k, k);
        self.near(&region.aabb, pending);
        pending
            .iter()
            .all(|&i| self.clear(&self.pieces[i as usize], region))
    }

    /// Whether every validator sub-step of `cut` is clear of every piece.
    /// `fresh`: a boundary whose body a planner has not checked (a new
    /// state), tested first against the pieces near it alone.
    fn free(&self, cut: &Cut, fresh: Option<usize>) -> bool {
        with_scratch(|Scratch { region, pending }| {
            if let Some(k) = fresh
                && !self.boundary_free(cut, k, pending, region)
            {
                return false;
            }
            // Most motions meet no piece even by their loose box.
            region.set(self, cut, 0, cut.steps);
            self.near(&region.aabb, pending);
            if pending.is_empty() {
                return true;
            }
            if region.loose {
                // The pieces near the exact box are among those near the
                // loose one.
                region.tighten();
                pending.retain(|&i| box_gap(&self.pieces[i as usize].aabb, &region.aabb) < SLACK);
            }
            if let Some(k) = fresh {
                // An extension that meets a piece mostly collides (it grows
                // into the unknown): the bodies along it are probed before
                // the whole motion's hull is made, its new end excepted.
                if self.witness(cut, pending, region, Some(k)) {
                    return false;
                }
                region.set(self, cut, 0, cut.steps);
                region.tighten();
            }
            self.decide(cut, 0, cut.steps, pending, region, fresh.is_none())
        })
    }

    /// The pieces whose boxes share a bucket with `aabb` into `pending`,
    /// each once; in a world of at most [`SCAN_PIECES`] pieces, those whose
    /// boxes overlap `aabb` by more than [`SLACK`] (every other piece is
    /// cleared by its box at once, in every group: the same verdicts).
    fn near(&self, aabb: &Aabb, pending: &mut Vec<u32>) {
        pending.clear();
        if self.pieces.len() <= SCAN_PIECES {
            for (i, piece) in self.pieces.iter().enumerate() {
                if box_gap(&piece.aabb, aabb) < SLACK {
                    pending.push(i as u32);
                }
            }
            return;
        }
        let ((c0, c1), (k0, k1)) = self.buckets.range(aabb);
        for k in k0..=k1 {
            for c in c0..=c1 {
                for &item in self.buckets.items(c, k) {
                    let (pc, pk) = self.pieces[item as usize].first;
                    if (pc as usize).max(c0) == c && (pk as usize).max(k0) == k {
                        pending.push(item);
                    }
                }
            }
        }
    }

    /// Whether sub-steps `k0 .. k1` of `cut` are clear of the pieces
    /// `pending`; `region` is set to that group. Reorders `pending`.
    /// `probe`: for the whole motion, whether the pieces it does not clear
    /// are first looked for along it ([`PolygonChecker::witness`]).
    fn decide(
        &self,
        cut: &Cut,
        k0: usize,
        k1: usize,
        pending: &mut [u32],
        region: &mut Region,
        probe: bool,
    ) -> bool {
        // The pieces the group does not clear go to the front; one is enough
        // to fail a single sub-step.
        let single = k1 - k0 == 1;
        let mut failing = 0;
        for i in 0..pending.len() {
            if !self.clear(&self.pieces[pending[i] as usize], region) {
                if single {
                    return false;
                }
                pending.swap(i, failing);
                failing += 1;
            }
        }
        if failing == 0 {
            return true;
        }
        let pending = &mut pending[..failing];
        if probe && k1 - k0 == cut.steps && self.witness(cut, pending, region, None) {
            return false;
        }
        let mid = k0 + (k1 - k0) / 2;
        region.set(self, cut, k0, mid);
        region.tighten();
        if !self.decide(cut, k0, mid, pending, region, false) {
            return false;
        }
        region.set(self, cut, mid, k1);
        region.tighten();
        self.decide(cut, mid, k1, pending, region, false)
    }

    /// Whether the body at one of a few sub-step boundaries (the end first,
    /// then the middle, then the quarters and eighths) overlaps one of the
    /// pieces `pending` deeper than `TOUCH_EPS / 2`. Then the sub-steps on
    /// either side of it fail too (their hulls hold that body), but a
    /// colliding motion is found without first clearing every sub-step
    /// before its collision. `known`: a boundary already found clear.
    fn witness(
        &self,
        cut: &Cut,
        pending: &[u32],
        region: &mut Region,
        known: Option<usize>,
    ) -> bool {
        WITNESSES.iter().any(|&j| {
            let k = (cut.steps as u128 * j / 8) as usize;
            if known == Some(k) {
                return false;
            }
            region.set(self, cut, k, k);
            pending
                .iter()
                .any(|&i| !self.clear(&self.pieces[i as usize], region))
        })
    }

    /// Whether some axis shows every body of the region's group at most
    /// `TOUCH_EPS / 2` into `piece` (see the module documentation).
    fn clear(&self, piece: &Piece, region: &mut Region) -> bool {
        if box_gap(&piece.aabb, &region.aabb) >= SLACK {
            return true;
        }
        match piece.kind {
            Kind::Convex { points, axes } => {
                let own = &self.axes[axes.0 as usize..axes.1 as usize];
                if own.iter().any(|a| region.low(a.n) - a.support >= SLACK) {
                    return true;
                }
                region.ensure_hull(&self.edge_normals);
                let pts = &self.points[points.0 as usize..points.1 as usize];
                (0..region.normals.len()).any(|j| {
                    let n = region.normals[j].n;
                    let low = pts
                        .iter()
                        .map(|p| n.dot(&p.coords))
                        .fold(f64::INFINITY, min_of_numbers);
                    region.axis_clears(j, low)
                })
            }
            Kind::Disk { center, radius } => {
                region.ensure_hull(&self.edge_normals);
                let c = center.coords;
                if (0..region.normals.len()).any(|j| {
                    let low = region.normals[j].n.dot(&c) - radius;
                    region.axis_clears(j, low)
                }) {
                    return true;
                }
                // The direction from the hull's nearest point: for a single
                // sub-step its gap is exactly the distance minus the radius.
                let hull = &region.hull;
                let h = hull.len();
                let nearest = (0..h)
                    .map(|i| closest_point_on_segment(center, hull[i], hull[(i + 1) % h]))
                    .min_by(|p, q| {
                        (p - center)
                            .norm_squared()
                            .total_cmp(&(q - center).norm_squared())
                    });
                let Some(q) = nearest else {
                    return false;
                };
                let d = center - q;
                let len = d.norm();
                if len == 0.0 {
                    return false;
                }
                let u = d / len;
                u.dot(&c) - radius - region.high(u) >= SLACK
            }
        }
    }
}

/// The largest gap between two boxes along ±x and ±y (negative: they
/// overlap by that much along every axis).
#[inline]
fn box_gap(b: &Aabb, w: &Aabb) -> f64 {
    let max = max_of_numbers;
    max(
        max(b.min.x - w.max.x, w.min.x - b.max.x),
        max(b.min.y - w.max.y, w.min.y - b.max.y),
    )
}

/// The piece of the convex `pts` (see [`Kind::Convex`]), its points and
/// axes appended to `points` and `axes`.
fn convex_piece(pts: &[Point], points: &mut Vec<Point>, axes: &mut Vec<Axis>) -> Piece {
    let (p0, a0) = (points.len() as u32, axes.len() as u32);
    points.extend_from_slice(pts);
    // ±x and ±y are the piece's box's.
    axes.extend(
        edge_normals(pts)
            .filter(|(n, _)| n.x != 0.0 && n.y != 0.0)
            .map(|(n, support)| Axis { n, support }),
    );
    Piece {
        aabb: Aabb::around(pts),
        first: (0, 0),
        kind: Kind::Convex {
            points: (p0, points.len() as u32),
            axes: (a0, axes.len() as u32),
        },
    }
}

/// A motion cut into sub-steps exactly as `Validator::check_motion` cuts it.
#[derive(Clone, Copy, Debug)]
struct Cut {
    a: Config,
    b: Config,
    /// The rotation, along the shorter arc, in radians.
    dtheta: f64,
    steps: usize,
}

impl Cut {
    /// `radius`: R of the robot.
    fn new(a: Config, b: Config, radius: f64) -> Self {
        let dtheta = angle_diff(a.theta, b.theta);
        // The validator's count, to the bit: a group boundary must be one of
        // its sub-step boundaries.
        let steps = if dtheta == 0.0 {
            1
        } else {
            let motion = (b.xy() - a.xy()).norm() + radius * dtheta.abs();
            ((motion / DEFAULT_TOLERANCE).ceil() as usize).max(1)
        };
        Cut {
            a,
            b,
            dtheta,
            steps,
        }
    }

    /// The robot standing at `c`.
    fn still(c: Config) -> Self {
        Cut {
            a: c,
            b: c,
            dtheta: 0.0,
            steps: 1,
        }
    }

    /// The configuration after `k` sub-steps (the validator's formula).
    fn at(&self, k: usize) -> Config {
        let (a, b) = (self.a, self.b);
        if k == 0 {
            a
        } else if k == self.steps {
            b
        } else {
            let t = k as f64 / self.steps as f64;
            Config::new(
                a.x * (1.0 - t) + b.x * t,
                a.y * (1.0 - t) + b.y * t,
                a.theta + t * self.dtheta,
            )
        }
    }
}

/// How many boundaries [`Region`] keeps: the bisection sets `k0 .. mid`
/// then `mid .. k1`, so the boundaries of the last few groups come back.
const TURNS: usize = 4;

/// The bodies of one group of sub-steps, in a reusable buffer.
struct Region {
    /// Vertex i at the group's first configuration, then at its last:
    /// `ends[2i]`, `ends[2i + 1]`.
    ends: Vec<Point>,
    /// `|v_i|·α²/2`, the bound on the second derivative of vertex i's
    /// deviation from its chord (see [`bulge`]); not kept when `flat`.
    curvature: Vec<f64>,
    /// α = 0 (a single sub-step or one configuration): every curvature is
    /// 0.
    flat: bool,
    /// The angles of the last few boundaries placed (their bits; NaN's
    /// at first, which no placed angle has) with their sine and cosine,
    /// from one motion to the next: the bisection comes back to its
    /// boundaries, and a planner's motions share their ends (PRM's new
    /// state starts up to k motions, RRT-Connect's greedy steps each start
    /// where the last ended). `next_turn` is the oldest.
    turns: [(u64, f64, f64); TURNS],
    next_turn: usize,
    /// The box of every body during the group: after [`Region::set`], for
    /// a turning group, a loose one (each vertex's bound raised to its
    /// parabola's worst), until [`Region::tighten`].
    aabb: Aabb,
    /// `aabb` is the loose box.
    loose: bool,
    /// The hull of `ends` (counter-clockwise), and its edge normals other
    /// than ±x, ±y (see [`HullAxis`]); valid when `hull_ready`.
    hull: Vec<Point>,
    normals: Vec<HullAxis>,
    hull_ready: bool,
    /// The group is one configuration: its body is its own hull.
    still: bool,
    /// That configuration and the sine and cosine of its angle, when
    /// `still`.
    pose: (Config, f64, f64),
    /// Scratch for the hull.
    sorted: Vec<Point>,
}

impl Region {
    fn new() -> Self {
        Region {
            ends: Vec::new(),
            curvature: Vec::new(),
            flat: true,
            turns: [(u64::MAX, f64::NAN, f64::NAN); TURNS],
            next_turn: 0,
            aabb: Aabb::around(&[]),
            loose: false,
            hull: Vec::new(),
            normals: Vec::new(),
            hull_ready: false,
            still: false,
            pose: (Config::new(0.0, 0.0, 0.0), 0.0, 1.0),
            sorted: Vec::new(),
        }
    }

    /// The group of sub-steps `k0 .. k1` of `cut`.
    fn set(&mut self, robot: &PolygonChecker, cut: &Cut, k0: usize, k1: usize) {
        // A single sub-step is the validator's own hull: no deviation.
        let alpha = if k1 - k0 <= 1 {
            0.0
        } else {
            cut.dtheta.abs() * (k1 - k0) as f64 / cut.steps as f64
        };
        let spread = alpha * alpha / 2.0;
        // As `RobotShape::placed_vertices` (a still body's ends are one
        // placement) but with [`sin_cos_fast`], within two ulps of libm's
        // sine and cosine: the placed vertices move by a few ulps of their
        // coordinates, far inside the `TOUCH_EPS / 2` that every verdict
        // keeps from the validator's. A boundary's configuration and sine
        // and cosine are taken from the last few placed (the same values).
        let (c0, s0, co0) = self.turn(cut, k0);
        let (c1, s1, co1) = self.turn(cut, k1);
        // The buffers keep their length from one group to the next (one
        // robot per checker): written in place, not pushed.
        let n = robot.vertices.len();
        self.ends.resize(2 * n, Point::origin());
        let (mut lo, mut hi) = (
            Point::new(f64::INFINITY, f64::INFINITY),
            Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        // The placed coordinates are finite (so are the configurations and
        // the vertices): plain comparisons for the bounds.
        let (min, max) = (min_of_numbers, max_of_numbers);
        self.flat = spread == 0.0;
        let ends = self.ends.chunks_exact_mut(2).zip(&robot.vertices);
        if k0 == k1 {
            // One placement: both ends it, its bounds its own (the flat
            // bounds below with p = q).
            for (e, v) in ends {
                let p = place(c0, s0, co0, v);
                e[0] = p;
                e[1] = p;
                lo.x = min(lo.x, p.x);
                lo.y = min(lo.y, p.y);
                hi.x = max(hi.x, p.x);
                hi.y = max(hi.y, p.y);
            }
        } else if self.flat {
            // `lever · 0 = 0`: the bounds below with k = 0. A loop of its
            // own: with the constant 0, `bulge` folds to a max (one loop for
            // both cost 3 % more instructions on the apartment rod's
            // rrt_connect).
            for (e, v) in ends {
                let p = place(c0, s0, co0, v);
                let q = place(c1, s1, co1, v);
                e[0] = p;
                e[1] = q;
                lo.x = min(lo.x, -bulge(-p.x, -q.x, 0.0));
                lo.y = min(lo.y, -bulge(-p.y, -q.y, 0.0));
                hi.x = max(hi.x, bulge(p.x, q.x, 0.0));
                hi.y = max(hi.y, bulge(p.y, q.y, 0.0));
            }
        } else {
            // The loose box: each parabola's top at most k/4 above its
            // higher end (see `bulge`), without a test or a division;
            // `tighten` gives the exact one.
            self.curvature.resize(n, 0.0);
            for ((e, v), (lever, curvature)) in
                ends.zip(robot.lever.iter().zip(&mut self.curvature))
            {
                let p = place(c0, s0, co0, v);
                let q = place(c1, s1, co1, v);
                let k = lever * spread;
                e[0] = p;
                e[1] = q;
                *curvature = k;
                let top = k / 4.0;
                lo.x = min(lo.x, min(p.x, q.x) - top);
                lo.y = min(lo.y, min(p.y, q.y) - top);
                hi.x = max(hi.x, max(p.x, q.x) + top);
                hi.y = max(hi.y, max(p.y, q.y) + top);
            }
        }
        self.loose = !self.flat;
        self.aabb = Aabb { min: lo, max: hi };
        self.hull_ready = false;
        self.still = k0 == k1;
        self.pose = (c0, s0, co0);
        #[cfg(test)]
        if k0 != k1 {
            GROUPS.set(GROUPS.get() + 1);
        }
    }

    /// Sets `aabb` to the exact box of the group's bodies: the largest
    /// value of each vertex's parabola (see [`Region::set`]).
    fn tighten(&mut self) {
        if !self.loose {
            return;
        }
        let (min, max) = (min_of_numbers, max_of_numbers);
        let (mut lo, mut hi) = (
            Point::new(f64::INFINITY, f64::INFINITY),
            Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for (e, &k) in self.ends.chunks_exact(2).zip(&self.curvature) {
            let (p, q) = (e[0], e[1]);
            lo.x = min(lo.x, -bulge(-p.x, -q.x, k));
            lo.y = min(lo.y, -bulge(-p.y, -q.y, k));
            hi.x = max(hi.x, bulge(p.x, q.x, k));
            hi.y = max(hi.y, bulge(p.y, q.y, k));
        }
        self.aabb = Aabb { min: lo, max: hi };
        self.loose = false;
    }

    /// Boundary `k` of `cut`, with the sine and cosine of its angle: kept
    /// from a recent placement at that angle (the same values) or computed
    /// (over the oldest).
    #[inline]
    fn turn(&mut self, cut: &Cut, k: usize) -> (Config, f64, f64) {
        let c = cut.at(k);
        let bits = c.theta.to_bits();
        for &(b, s, co) in &self.turns {
            if b == bits {
                return (c, s, co);
            }
        }
        let (s, co) = sin_cos_fast(c.theta);
        self.turns[self.next_turn] = (bits, s, co);
        self.next_turn = (self.next_turn + 1) % TURNS;
        (c, s, co)
    }

    /// The largest projection on the unit `u` of any body during the group.
    #[inline(always)]
    fn high(&self, u: Vector) -> f64 {
        let ends = self.ends.chunks_exact(2);
        if self.still {
            // Both ends one placement: `bulge(a, a, 0) = a`.
            ends.map(|e| u.dot(&e[0].coords))
                .fold(f64::NEG_INFINITY, max_of_numbers)
        } else if self.flat {
            ends.map(|e| bulge(u.dot(&e[0].coords), u.dot(&e[1].coords), 0.0))
                .fold(f64::NEG_INFINITY, max_of_numbers)
        } else {
            ends.zip(&self.curvature)
                .map(|(e, &k)| bulge(u.dot(&e[0].coords), u.dot(&e[1].coords), k))
                .fold(f64::NEG_INFINITY, max_of_numbers)
        }
    }

    /// Whether hull axis `j` clears a piece whose smallest projection on
    /// it is `low` (a gap of at least `SLACK`). The group's largest
    /// projection is computed, once, only if the edge's does not already
    /// rule the axis out: it is at least the edge's (see [`HullAxis`]).
    #[inline(always)]
    fn axis_clears(&mut self, j: usize, low: f64) -> bool {
        let axis = self.normals[j];
        if low - axis.edge < SLACK {
            return false;
        }
        if axis.high.is_nan() {
            self.normals[j].high = self.high(axis.n);
        }
        low - self.normals[j].high >= SLACK
    }

    /// The smallest projection on the unit `u` of any body during the group.
    #[inline]
    fn low(&self, u: Vector) -> f64 {
        -self.high(-u)
    }

    /// Sets `hull` and `normals` (once per group). `edge_normals`: the
    /// robot's ([`PolygonChecker::edge_normals`]).
    fn ensure_hull(&mut self, edge_normals: &[(Vector, f64)]) {
        if self.hull_ready {
            return;
        }
        self.normals.clear();
        if self.still {
            // The robot's vertices are counter-clockwise, and so is any
            // placement of them. Its edge normals are the robot's own
            // rotated, and its largest projection on one is the robot's own
            // plus the position's: `m·(R·v + t) = n·v + m·t` for `m = R·n`.
            // The same axes and bounds as from the placed edges but for
            // rounding (a few ulps of the coordinates, far below the
            // `TOUCH_EPS / 2` that the verdicts keep from the validator's),
            // without a square root and a division per edge.
            self.hull.clear();
            self.hull.extend(self.ends.iter().step_by(2));
            let (c, s, co) = self.pose;
            for &(n, support) in edge_normals {
                let m = Vector::new(co * n.x - s * n.y, s * n.x + co * n.y);
                if m.x != 0.0 && m.y != 0.0 {
                    let high = support + (m.x * c.x + m.y * c.y);
                    self.normals.push(HullAxis {
                        n: m,
                        edge: high,
                        high,
                    });
                }
            }
            self.hull_ready = true;
            return;
        }
        self.sorted.clear();
        self.sorted.extend_from_slice(&self.ends);
        convex_hull_into(&mut self.sorted, &mut self.hull);
        let h = self.hull.len();
        for i in 0..h {
            let d = self.hull[(i + 1) % h] - self.hull[i];
            let len = d.norm();
            if len == 0.0 {
                continue;
            }
            let n = Vector::new(d.y, -d.x) / len;
            if n.x != 0.0 && n.y != 0.0 {
                self.normals.push(HullAxis {
                    n,
                    edge: n.dot(&self.hull[i].coords),
                    high: f64::NAN,
                });
            }
        }
        self.hull_ready = true;
    }
}

/// An edge normal `n` of a region's hull, with the projection `edge` of
/// the edge's first end on it (one of the group's end bodies' vertices: no
/// more than the group's largest projection on `n`), and that largest
/// projection `high` ([`Region::high`]), NaN until a piece needs it: an
/// axis along which a piece reaches below `edge` cannot clear it, and
/// most do.
#[derive(Clone, Copy, Debug)]
struct HullAxis {
    n: Vector,
    edge: f64,
    high: f64,
}

/// The outward unit edge normals of the counter-clockwise convex polygon
/// `vertices` (edges of length 0 skipped), each with the largest
/// projection of any vertex on it (over all vertices, not the edge's own:
/// safe even if rounding made the polygon slightly non-convex).
pub fn edge_normals(vertices: &[Point]) -> impl Iterator<Item = (Vector, f64)> + '_ {
    let n = vertices.len();
    (0..n).filter_map(move |i| {
        let d = vertices[(i + 1) % n] - vertices[i];
        let len = d.norm();
        (len != 0.0).then(|| {
            let normal = Vector::new(d.y, -d.x) / len;
            let support = vertices
                .iter()
                .map(|v| normal.dot(&v.coords))
                .fold(f64::NEG_INFINITY, max_of_numbers);
            (normal, support)
        })
    })
}

/// The largest value over λ ∈ [0, 1] of `(1−λ)·a + λ·b + k·λ(1−λ)`
/// (`k ≥ 0`): a bound on `u·p(λ)` for a vertex whose projections at the
/// group's ends are `a` and `b`, with `k = |v|·α²/2` (see the module
/// documentation). `max(a, b)` for `k = 0`, and at most `max(a, b) + k/4`.
#[inline]
fn bulge(a: f64, b: f64, k: f64) -> f64 {
    let d = b - a;
    if d.abs() < k {
        // The parabola's top lies inside (0, 1), at λ = (d + k) / 2k.
        a + (d + k) * (d + k) / (4.0 * k)
    } else {
        max_of_numbers(a, b)
    }
}

struct Scratch {
    region: Region,
    /// The pieces a motion still has to clear.
    pending: Vec<u32>,
}

#[cfg(test)]
thread_local! {
    /// Groups of sub-steps tested on this thread, witnesses not counted
    /// (see the tests).
    static GROUPS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch {
        region: Region::new(),
        pending: Vec::new(),
    });
}

/// Runs `f` with this thread's scratch (a fresh one if it is in use).
fn with_scratch<R>(f: impl FnOnce(&mut Scratch) -> R) -> R {
    SCRATCH.with(|cell| match cell.try_borrow_mut() {
        Ok(mut s) => f(&mut s),
        Err(_) => f(&mut Scratch {
            region: Region::new(),
            pending: Vec::new(),
        }),
    })
}

// ------------------------------------------------------------ C-space

/// The penetration depth of the segment `p`–`q` into the convex polygon
/// `poly` (counter-clockwise, at least 3 vertices): the smallest
/// translation that separates them, over the separating axes (the
/// polygon's edge normals and the segment's normal). ≤ 0 when they are
/// apart or touch.
///
/// With `poly` the C-obstacle `B ⊕ (−A(θ))` of a piece `B` and `p`, `q`
/// two positions of the robot `A(θ)`, this is the depth of the translating
/// robot's swept hull into `B`: the validator's measure.
pub fn segment_depth(p: Point, q: Point, poly: &[Point]) -> f64 {
    let mut depth = f64::INFINITY;
    let mut axis = |nx: f64, ny: f64| {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in poly {
            let s = nx * v.x + ny * v.y;
            lo = lo.min(s);
            hi = hi.max(s);
        }
        let (a, b) = (nx * p.x + ny * p.y, nx * q.x + ny * q.y);
        let d = (hi - a.min(b)).min(a.max(b) - lo);
        depth = depth.min(d);
    };
    for i in 0..poly.len() {
        let d = poly[(i + 1) % poly.len()] - poly[i];
        let len = d.norm();
        if len > 0.0 {
            axis(d.y / len, -d.x / len);
        }
    }
    let d = q - p;
    let len = d.norm();
    if len > 0.0 {
        axis(d.y / len, -d.x / len);
    }
    depth
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, PI, TAU};

    use proptest::prelude::*;
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;

    use super::*;
    use crate::fixtures::random::random_world;
    use crate::fixtures::{grid, polygon_shape, rect, world};
    use crate::rng::SplitMix64;
    use crate::validator::{Validator, config_collision};
    use crate::{Grid, polygon};

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    fn c(x: f64, y: f64, theta: f64) -> Config {
        Config::new(x, y, theta)
    }

    fn polygon_robot(v: &[(f64, f64)]) -> RobotShape {
        RobotShape::Polygon(ConvexPolygon {
            vertices: v.iter().map(|&(x, y)| p(x, y)).collect(),
        })
    }

    /// The 8 × 1 rod of SEEDS §A, its frame origin at a corner.
    fn rod() -> RobotShape {
        polygon_robot(&[(0.0, 0.0), (8.0, 0.0), (8.0, 1.0), (0.0, 1.0)])
    }

    fn valid(v: &Validator, robot: &RobotShape, a: Config, b: Config) -> bool {
        v.validate_path(robot, &[a, b], DEFAULT_TOLERANCE).is_ok()
    }

    // ------------------------------------------------ known cases

    #[test]
    fn the_checker_is_sync() {
        fn sync<T: Sync + Send>() {}
        sync::<MotionChecker>();
    }

    #[test]
    fn bounds_and_non_finite_configurations() {
        let w = world(vec![rect(4.0, 4.0, 6.0, 6.0)]);
        for robot in [RobotShape::Point, RobotShape::Disk(0.5), rod()] {
            let m = MotionChecker::new(&w, &robot);
            assert!(
                m.config_free(c(0.0, 0.0, 0.0)),
                "{robot:?}: the closed bounds"
            );
            assert!(!m.config_free(c(-0.1, 1.0, 0.0)));
            assert!(!m.config_free(c(1.0, f64::NAN, 0.0)));
            assert!(!m.config_free(c(1.0, 1.0, f64::INFINITY)));
            assert!(m.motion_free(c(1.0, 1.0, 0.0), c(1.0, 2.0, 0.0)));
            assert!(!m.motion_free(c(1.0, 1.0, 0.0), c(1.0, 10.5, 0.0)));
            assert!(!m.motion_free(c(1.0, 1.0, 0.0), c(1.0, 2.0, f64::NAN)));
        }
    }

    #[test]
    fn a_rod_pivoting_on_a_wall_it_touches_is_free() {
        // The rod's frame origin (a corner) sits on the wall x = 1 and the
        // rod turns a quarter from hanging down to lying right of it: it
        // touches the wall at the pivot all along, and its next vertex
        // comes to rest on the wall. Bounds that know where each vertex
        // is extreme clear that without cutting the motion down to its
        // 1 000-odd sub-steps.
        let mut w = world(vec![rect(-1.0, -20.0, 1.0, 20.0)]);
        w.bounds = Aabb::from_corners(p(-20.0, -20.0), p(20.0, 20.0));
        let (a, b) = (c(1.0, 0.0, -FRAC_PI_2), c(1.0, 0.0, 0.0));
        let m = MotionChecker::new(&w, &rod());
        assert!(valid(&Validator::new(&w), &rod(), a, b));
        assert_eq!(Cut::new(a, b, 65f64.sqrt()).steps, 1267);
        GROUPS.set(0);
        assert!(m.motion_free(a, b));
        assert!(m.motion_free(b, a));
        // Each motion: the whole, then its two halves.
        assert_eq!(GROUPS.get(), 6);
        // Turning on, up from the wall, sweeps into it.
        assert!(!m.motion_free(b, c(1.0, 0.0, FRAC_PI_2)));
    }

    #[test]
    fn disk_obstacles_are_exact_circles() {
        // 1e-6 from the unit disk: a circumscribed 32-gon would be 4.8e-3
        // too big there.
        let mut w = world(vec![Shape::Disk {
            center: p(5.0, 5.0),
            radius: 1.0,
        }]);
        w.bounds = Aabb::from_corners(p(-20.0, -20.0), p(20.0, 20.0));
        let square = polygon_robot(&[(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]);
        let m = MotionChecker::new(&w, &square);
        let d = 1.0 + 0.5 + 1e-6;
        assert!(m.motion_free(c(5.0 - d, 0.0, 0.0), c(5.0 - d, 10.0, 0.0)));
        assert!(!m.motion_free(c(5.0 - d + 2e-6, 0.0, 0.0), c(5.0 - d + 2e-6, 10.0, 0.0)));
        // A corner passing the disk diagonally, and the square turning
        // beside it (its corners reach 0.5·√2 from its centre).
        let q = 1.0 + 0.5 * 2f64.sqrt() + 1e-6;
        assert!(m.config_free(c(5.0 + q / 2f64.sqrt(), 5.0 + q / 2f64.sqrt(), PI / 4.0)));
        assert!(m.motion_free(c(5.0 + q, 5.0, 0.0), c(5.0 + q, 5.0, PI / 2.0)));
        assert!(!m.motion_free(
            c(5.0 + q - 1e-5, 5.0, 0.0),
            c(5.0 + q - 1e-5, 5.0, PI / 2.0)
        ));
    }

    #[test]
    fn a_polygon_may_touch_but_not_cross_a_segment() {
        let mut w = world(vec![Shape::Segment(p(0.0, 5.0), p(10.0, 5.0))]);
        w.bounds = Aabb::from_corners(p(-20.0, -20.0), p(20.0, 20.0));
        let m = MotionChecker::new(&w, &rod());
        // Sliding along it, below and above.
        assert!(m.motion_free(c(1.0, 4.0, 0.0), c(2.0, 4.0, 0.0)));
        assert!(m.motion_free(c(1.0, 5.0, 0.0), c(2.0, 5.0, 0.0)));
        // Across it, and turning through it.
        assert!(!m.motion_free(c(1.0, 3.0, 0.0), c(1.0, 6.0, 0.0)));
        assert!(!m.motion_free(c(1.0, 2.0, 0.0), c(1.0, 2.0, FRAC_PI_2)));
        // Its end: a rod standing beside the end turns freely below it.
        assert!(m.motion_free(c(10.5, 5.0, -FRAC_PI_2), c(10.5, 5.0, -PI)));
    }

    #[test]
    fn grids_block_polygons_like_their_cells() {
        let mut w = world(vec![grid(
            1.0,
            p(0.0, 0.0),
            &["..........", "..####....", "..........", "......#..."],
        )]);
        w.bounds = Aabb::from_corners(p(-20.0, -20.0), p(20.0, 20.0));
        let box1 = polygon_robot(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]);
        let m = MotionChecker::new(&w, &box1);
        // Row 1 (y from 2 to 3) is blocked from x = 2 to 6; row 3 (y from 0
        // to 1) at x = 6.
        assert!(m.motion_free(c(0.0, 1.0, 0.0), c(9.0, 1.0, 0.0)));
        assert!(m.motion_free(c(0.0, 3.0, 0.0), c(9.0, 3.0, 0.0)));
        assert!(!m.motion_free(c(0.0, 1.5, 0.0), c(9.0, 1.5, 0.0)));
        assert!(!m.config_free(c(6.5, 0.5, 0.0)));
        assert!(m.config_free(c(6.0, 1.0, 0.0)));
    }

    #[test]
    fn segment_depth_known_cases() {
        let sq = [p(0.0, 0.0), p(2.0, 0.0), p(2.0, 2.0), p(0.0, 2.0)];
        // Through the middle: 1 either way.
        assert_eq!(segment_depth(p(-1.0, 1.0), p(3.0, 1.0), &sq), 1.0);
        // Along an edge: touching.
        assert_eq!(segment_depth(p(-1.0, 0.0), p(3.0, 0.0), &sq), 0.0);
        // Apart.
        assert!(segment_depth(p(-1.0, 3.0), p(3.0, 3.0), &sq) < 0.0);
        // Cutting the corner at (2, 2) at distance d from it along the
        // diagonal: every point is at most d/√2 deep, the segment d.
        let d = 0.1;
        let k = 2.0 - d / 2f64.sqrt();
        let depth = segment_depth(p(k - 1.0, k + 1.0), p(k + 1.0, k - 1.0), &sq);
        assert!((depth - d).abs() < 1e-12, "{depth}");
    }

    // ------------------------------------------------ against the validator

    /// Point, disk, the rod, and small random convex polygons around (or
    /// off) their frame origin.
    fn robot_strategy() -> impl Strategy<Value = RobotShape> {
        let convex = (
            prop::collection::vec((-1.5..1.5f64, -1.5..1.5f64), 3..7),
            (-1.0..1.0f64, -1.0..1.0f64),
        )
            .prop_filter_map("flat", |(v, (ox, oy))| {
                let pts: Vec<Point> = v.iter().map(|&(x, y)| p(x + ox, y + oy)).collect();
                let hull = polygon::convex_hull(&pts);
                (hull.len() >= 3 && polygon::signed_area2(&hull) > 1e-3)
                    .then_some(RobotShape::Polygon(ConvexPolygon { vertices: hull }))
            });
        prop_oneof![
            1 => Just(RobotShape::Point),
            1 => (0.01..1.5f64).prop_map(RobotShape::Disk),
            2 => Just(rod()),
            3 => convex,
        ]
    }

    /// Translations, pure rotations up to π either way, and both at once,
    /// from anywhere in and around the bounds [-1, 11]².
    fn motion_strategy() -> impl Strategy<Value = (Config, Config)> {
        let start = || (-2.0..12.0f64, -2.0..12.0f64, 0.0..TAU);
        prop_oneof![
            (start(), -4.0..4.0f64, -4.0..4.0f64)
                .prop_map(|((x, y, t), dx, dy)| (c(x, y, t), c(x + dx, y + dy, t))),
            (start(), -PI..=PI).prop_map(|((x, y, t), dt)| (c(x, y, t), c(x, y, t + dt))),
            (start(), -3.0..3.0f64, -3.0..3.0f64, -PI..=PI)
                .prop_map(|((x, y, t), dx, dy, dt)| { (c(x, y, t), c(x + dx, y + dy, t + dt)) }),
        ]
    }

    fn with_bounds(mut w: World) -> World {
        w.bounds = Aabb::from_corners(p(-1.0, -1.0), p(11.0, 11.0));
        w
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// The contract: nothing the checker accepts fails the validator.
        #[test]
        fn never_accepts_what_the_validator_rejects(
            w in random_world(),
            robot in robot_strategy(),
            (a, b) in motion_strategy(),
        ) {
            let w = with_bounds(w);
            let checker = MotionChecker::new(&w, &robot);
            let v = Validator::new(&w);
            if checker.motion_free(a, b) {
                prop_assert!(valid(&v, &robot, a, b), "{:?}: {:?} → {:?}", robot, a, b);
            }
            if checker.config_free(a) {
                prop_assert!(w.bounds.contains(a.xy()));
                prop_assert!(config_collision(&w, &robot, a).is_none(), "{:?} at {:?}", robot, a);
            }
        }

        /// Testing a new end first changes no verdict.
        #[test]
        fn an_extension_is_decided_as_the_motion(
            w in random_world(),
            robot in robot_strategy(),
            (a, b) in motion_strategy(),
        ) {
            let checker = MotionChecker::new(&with_bounds(w), &robot);
            let whole = checker.motion_free(a, b);
            prop_assert_eq!(checker.extension_free(a, b, NewEnd::End), whole);
            prop_assert_eq!(checker.extension_free(a, b, NewEnd::Start), whole);
        }
    }

    /// The kind of robot, for the figures.
    fn kind(robot: &RobotShape) -> usize {
        match robot {
            RobotShape::Point => 0,
            RobotShape::Disk(_) => 1,
            RobotShape::Polygon(_) => 2,
        }
    }

    /// Not vacuous: over a fixed sample of the property test's worlds,
    /// robots and motions, the checker accepts nearly every motion the
    /// validator accepts (points lose the ones that touch a segment).
    #[test]
    fn accepts_nearly_all_that_the_validator_accepts() {
        let mut runner = TestRunner::deterministic();
        let (worlds, robots, motions) = (random_world(), robot_strategy(), motion_strategy());
        // Per kind: validator accepts, checker accepts too, checker alone.
        let mut counts = [[0usize; 3]; 3];
        // Polygon motions that turn: validator accepts, checker accepts too.
        let mut turning = [0usize; 2];
        let mut configs = [0usize; 2];
        let mut drawn = 0;
        while drawn < 3000 {
            let (Ok(w), Ok(robot), Ok(ab)) = (
                worlds.new_tree(&mut runner),
                robots.new_tree(&mut runner),
                motions.new_tree(&mut runner),
            ) else {
                continue;
            };
            drawn += 1;
            let (w, robot, (a, b)) = (with_bounds(w.current()), robot.current(), ab.current());
            let checker = MotionChecker::new(&w, &robot);
            let (ours, referee) = (
                checker.motion_free(a, b),
                valid(&Validator::new(&w), &robot, a, b),
            );
            let k = &mut counts[kind(&robot)];
            k[0] += usize::from(referee);
            k[1] += usize::from(ours && referee);
            k[2] += usize::from(ours && !referee);
            if kind(&robot) == 2 && angle_diff(a.theta, b.theta) != 0.0 {
                turning[0] += usize::from(referee);
                turning[1] += usize::from(ours && referee);
            }
            let free = w.bounds.contains(a.xy()) && config_collision(&w, &robot, a).is_none();
            configs[0] += usize::from(free);
            configs[1] += usize::from(free && checker.config_free(a));
        }
        for (name, k) in ["point", "disk", "polygon"].iter().zip(&counts) {
            eprintln!(
                "{name}: the checker accepts {} of the {} motions the validator accepts ({:.2} %)",
                k[1],
                k[0],
                100.0 * k[1] as f64 / k[0].max(1) as f64
            );
            assert_eq!(k[2], 0, "{name}: accepted what the validator rejects");
        }
        eprintln!(
            "of which turning polygons: {} of {}; configurations: {} of {} free ones",
            turning[1], turning[0], configs[1], configs[0]
        );
        let [_, disk, polygon] = counts;
        assert!(
            polygon[0] >= 200 && turning[0] >= 100 && disk[0] >= 100,
            "too few free motions: {counts:?}, {turning:?}"
        );
        assert!(polygon[1] as f64 >= 0.95 * polygon[0] as f64, "{polygon:?}");
        assert!(disk[1] as f64 >= 0.95 * disk[0] as f64, "{disk:?}");
        assert!(configs[1] as f64 >= 0.95 * configs[0] as f64, "{configs:?}");
    }

    /// Convex polygon robots only, turning (with or without a translation).
    fn turning_polygon() -> impl Strategy<Value = (RobotShape, (Config, Config))> {
        let motion = motion_strategy().prop_filter("turns", |(a, b)| a.theta != b.theta);
        (
            robot_strategy().prop_filter("polygon", |r| kind(r) == 2),
            motion,
        )
    }

    /// The motion `(a, b)` moved by `s` along `d`.
    fn shifted((a, b): (Config, Config), d: Vector, s: f64) -> (Config, Config) {
        let m = |q: Config| c(q.x + s * d.x, q.y + s * d.y, q.theta);
        (m(a), m(b))
    }

    /// Where along `d` (within 4 units) the validator's verdict on the
    /// moved motion flips: a shift it accepts and one it rejects, a few
    /// ulps apart.
    fn flip(
        v: &Validator,
        robot: &RobotShape,
        ab: (Config, Config),
        d: Vector,
    ) -> Option<(f64, f64)> {
        let accepts = |s: f64| {
            let (a, b) = shifted(ab, d, s);
            valid(v, robot, a, b)
        };
        let (mut ok, mut bad) = match (accepts(0.0), accepts(4.0)) {
            (true, false) => (0.0, 4.0),
            (false, true) => (4.0, 0.0),
            _ => return None,
        };
        loop {
            let mid = 0.5 * (ok + bad);
            if mid == ok || mid == bad {
                return Some((ok, bad));
            }
            if accepts(mid) {
                ok = mid;
            } else {
                bad = mid;
            }
        }
    }

    fn far_bounds(mut w: World) -> World {
        w.bounds = Aabb::from_corners(p(-100.0, -100.0), p(100.0, 100.0));
        w
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Turning motions moved right up to the validator's limit, where a
        /// sub-step grazes an obstacle: the checker refuses the first
        /// motion the validator refuses.
        #[test]
        fn grazing_turns_are_sound(
            w in random_world(),
            (robot, ab) in turning_polygon(),
            phi in 0.0..TAU,
        ) {
            let w = far_bounds(w);
            let v = Validator::new(&w);
            let d = Vector::new(phi.cos(), phi.sin());
            if let Some((ok, bad)) = flip(&v, &robot, ab, d) {
                let checker = MotionChecker::new(&w, &robot);
                let (a, b) = shifted(ab, d, bad);
                prop_assert!(!checker.motion_free(a, b), "{:?}: {:?} → {:?}", robot, a, b);
                let (a, b) = shifted(ab, d, ok);
                if checker.motion_free(a, b) {
                    prop_assert!(valid(&v, &robot, a, b));
                }
            }
        }
    }

    /// And not much stricter there: 1e-7 short of the validator's limit,
    /// the checker accepts too, nearly always.
    #[test]
    fn grazing_turns_are_accepted_just_short_of_the_limit() {
        let mut runner = TestRunner::deterministic();
        let (worlds, motions) = (random_world(), turning_polygon());
        let (mut tried, mut accepted) = (0, 0);
        let mut drawn = 0;
        while drawn < 400 {
            let (Ok(w), Ok(m), Ok(phi)) = (
                worlds.new_tree(&mut runner),
                motions.new_tree(&mut runner),
                (0.0..TAU).new_tree(&mut runner),
            ) else {
                continue;
            };
            drawn += 1;
            let (w, (robot, ab), phi) = (far_bounds(w.current()), m.current(), phi.current());
            let v = Validator::new(&w);
            let d = Vector::new(phi.cos(), phi.sin());
            let Some((ok, bad)) = flip(&v, &robot, ab, d) else {
                continue;
            };
            let (a, b) = shifted(ab, d, ok - 1e-7 * (bad - ok).signum());
            if valid(&v, &robot, a, b) {
                tried += 1;
                accepted += usize::from(MotionChecker::new(&w, &robot).motion_free(a, b));
            }
        }
        eprintln!(
            "grazing turns 1e-7 short of the validator's limit: {accepted} of {tried} accepted"
        );
        assert!(tried >= 100, "{tried}");
        assert!(
            accepted as f64 >= 0.95 * tried as f64,
            "{accepted} of {tried}"
        );
    }

    /// A world on the integer lattice: rects, triangles, segments, a disk
    /// and a grid of unit cells, all in [0, 12]².
    fn lattice_world(rng: &mut SplitMix64) -> World {
        let mut int = |lo: i32, hi: i32| lo + (rng.next_f64() * f64::from(hi - lo + 1)) as i32;
        let mut shapes = Vec::new();
        for _ in 0..int(2, 5) {
            let (x, y) = (int(0, 10), int(0, 10));
            let (w, h) = (int(1, 4), int(1, 4));
            shapes.push(rect(x.into(), y.into(), (x + w).into(), (y + h).into()));
        }
        for _ in 0..int(0, 2) {
            let (x, y) = (int(0, 9), int(0, 9));
            let q = |dx: i32, dy: i32| p(f64::from(x + dx), f64::from(y + dy));
            if let Some(s) = polygon_shape(&[q(0, 0), q(int(1, 3), 0), q(int(0, 3), int(1, 3))]) {
                shapes.push(s);
            }
        }
        for _ in 0..int(0, 2) {
            let (x, y) = (int(0, 12), int(0, 12));
            shapes.push(Shape::Segment(
                p(x.into(), y.into()),
                p(int(0, 12).into(), int(0, 12).into()),
            ));
        }
        if int(0, 1) == 1 {
            shapes.push(Shape::Disk {
                center: p(int(1, 11).into(), int(1, 11).into()),
                radius: int(1, 2).into(),
            });
        }
        if int(0, 1) == 1 {
            let (width, height) = (4, 4);
            let cells = (0..width * height)
                .map(|_| if int(0, 2) == 0 { 0 } else { 1 })
                .collect();
            shapes.push(Shape::Grid(Grid {
                cell: 1.0,
                origin: p(int(0, 8).into(), int(0, 8).into()),
                width,
                height,
                cells,
            }));
        }
        let mut w = world(shapes);
        w.bounds = Aabb::from_corners(p(0.0, 0.0), p(12.0, 12.0));
        w
    }

    /// Exact contacts: axis-aligned robots with half-integer sides at
    /// half-integer positions translate among lattice obstacles, so that
    /// their edges lie on obstacle edges, their corners on cell corners.
    /// There the checker and the validator agree on every motion.
    #[test]
    fn translations_agree_exactly_with_the_validator_at_contacts() {
        let mut rng = SplitMix64::new(20261122);
        let (mut agreed, mut touching) = (0, 0);
        for _ in 0..300 {
            let w = lattice_world(&mut rng);
            let v = Validator::new(&w);
            let half =
                |rng: &mut SplitMix64, lo: f64, hi: f64| (rng.range(lo, hi) * 2.0).floor() / 2.0;
            let robot = if rng.coin() {
                rod()
            } else {
                let (x0, y0) = (half(&mut rng, -1.0, 0.5), half(&mut rng, -1.0, 0.5));
                let (wd, ht) = (half(&mut rng, 0.5, 3.0), half(&mut rng, 0.5, 2.0));
                polygon_robot(&[(x0, y0), (x0 + wd, y0), (x0 + wd, y0 + ht), (x0, y0 + ht)])
            };
            let checker = MotionChecker::new(&w, &robot);
            // A slightly larger robot: it collides where this one touches.
            let RobotShape::Polygon(body) = &robot else {
                unreachable!("polygon robots only");
            };
            let grown = RobotShape::Polygon(ConvexPolygon {
                vertices: body
                    .vertices
                    .iter()
                    .map(|v| p(v.x * 1.001, v.y * 1.001))
                    .collect(),
            });
            for _ in 0..20 {
                let theta = [0.0, FRAC_PI_2, PI, 3.0 * FRAC_PI_2][(rng.next_f64() * 4.0) as usize];
                let (x, y) = (half(&mut rng, 0.0, 12.0), half(&mut rng, 0.0, 12.0));
                let (dx, dy) = (half(&mut rng, -3.0, 3.5), half(&mut rng, -3.0, 3.5));
                let (a, b) = (c(x, y, theta), c(x + dx, y + dy, theta));
                let referee = valid(&v, &robot, a, b);
                assert_eq!(
                    checker.motion_free(a, b),
                    referee,
                    "{robot:?}: {a:?} → {b:?} in {w:?}"
                );
                let free = config_collision(&w, &robot, a).is_none();
                assert_eq!(checker.config_free(a), free, "{robot:?} at {a:?} in {w:?}");
                agreed += 1;
                touching += usize::from(referee && !valid(&v, &grown, a, b));
            }
        }
        eprintln!("{agreed} translations agree, {touching} of them accepted in contact");
        assert!(touching >= 200, "too few contacts: {touching}");
    }
}
