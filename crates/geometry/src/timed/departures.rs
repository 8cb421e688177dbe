//! When a round robot (a point or a disk) may stand at a point, and when it
//! may leave a point for a straight move at constant speed, among moving
//! obstacles: the time-aware planners' checker (SPEC 3.10), exact up to a
//! bisection of the times to about 1e-12 s and a distance margin that makes
//! it stricter than the validator ([`super::validate_trajectory`]).
//!
//! # Why one interval per piece of a route
//! Cut an obstacle's route into pieces in which it moves linearly (standing
//! before its first waypoint, between waypoints, standing after its last
//! unless it vanishes). For a move from `p` to `q` taking `τ` and leaving
//! at `t0`, the obstacle's offset from the robot, `d(t0, t)`, is affine in
//! `(t0, t)` over the convex set `t0 ≤ t ≤ t0 + τ`, `t` in the piece's
//! span; the distance from the robot's centre to the obstacle's shape
//! there is a convex function of `d`, so its minimum over `t`, the move's
//! closest approach `g(t0)`, is convex in `t0`. The departures that meet
//! the piece, `g(t0) < r`, are therefore one open interval: found by a
//! golden-section search for the minimum of `g` and a bisection on each
//! side. Standing at `p` is the move of length 0 (`q = p`, `τ = 0`).

use super::{After, MovingObstacle, MovingShape, point_polygon_distance};
use crate::polygon::{closest_point_on_segment, convex_hull};
use crate::{Point, Vector};

/// A conflict counts when the closest approach is below the robot's reach
/// by less than this margin too: stricter than the validator (which lets
/// bodies touch), so a trajectory built on these intervals passes it.
pub const MARGIN: f64 = 1e-9;

/// A piece of a route in which the obstacle moves linearly.
#[derive(Clone, Debug)]
struct Piece {
    /// Its shape (index into the obstacles).
    obstacle: usize,
    /// Its span `[a, b]` (either end may be infinite: standing before the
    /// first waypoint, or for good after the last).
    a: f64,
    b: f64,
    /// Where it is at `a` and at `b` (the same point when it stands).
    from: Point,
    to: Point,
    /// The radius of a disk around the origin holding the shape, plus the
    /// robot's radius and the margin: the broad phase.
    reach: f64,
}

impl Piece {
    fn position(&self, t: f64) -> Point {
        if self.from == self.to || !self.a.is_finite() || !self.b.is_finite() {
            return self.from;
        }
        let s = ((t - self.a) / (self.b - self.a)).clamp(0.0, 1.0);
        self.from + (self.to - self.from) * s
    }
}

/// The moving obstacles as a round robot of one radius meets them.
#[derive(Clone, Debug)]
pub struct RoundMover<'a> {
    moving: &'a [MovingObstacle],
    radius: f64,
    pieces: Vec<Piece>,
}

/// Open intervals of time, sorted and disjoint.
pub type Intervals = Vec<(f64, f64)>;

impl<'a> RoundMover<'a> {
    /// A robot of radius `radius` (0 for a point) among `moving`.
    pub fn new(moving: &'a [MovingObstacle], radius: f64) -> Self {
        let mut pieces = Vec::new();
        for (k, o) in moving.iter().enumerate() {
            let size = match &o.shape {
                MovingShape::Disk(r) => *r,
                MovingShape::Pieces(ps) => ps
                    .iter()
                    .flatten()
                    .map(|v| v.coords.norm())
                    .fold(0.0, f64::max),
            };
            let reach = size + radius + MARGIN;
            let Some(first) = o.route.first() else {
                continue;
            };
            let mut push = |a: f64, b: f64, from: Point, to: Point| {
                pieces.push(Piece {
                    obstacle: k,
                    a,
                    b,
                    from,
                    to,
                    reach,
                })
            };
            push(f64::NEG_INFINITY, first.t, first.at, first.at);
            for w in o.route.windows(2) {
                push(w[0].t, w[1].t, w[0].at, w[1].at);
            }
            let last = o.route.last().expect("a route has a waypoint");
            if o.after == After::Stay {
                push(last.t, f64::INFINITY, last.at, last.at);
            }
        }
        RoundMover {
            moving,
            radius,
            pieces,
        }
    }

    /// Whether there is no moving obstacle at all.
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }

    /// The departure times `t0 ≥ 0` at which the robot leaving `p` for `q`
    /// at constant speed, arriving `tau` later, would meet a moving
    /// obstacle (overlap it, or come within the margin). Departing at an
    /// end of an interval is safe.
    pub fn blocked_departures(&self, p: Point, q: Point, tau: f64) -> Intervals {
        let mut out = Vec::new();
        for piece in &self.pieces {
            if !self.near(piece, p, q) {
                continue;
            }
            if let Some(iv) = self.blocked_by(piece, p, q, tau) {
                out.push(iv);
            }
        }
        merge(out)
    }

    /// The times at which the robot may stand at `p`: the closed intervals
    /// between the blocked ones, from 0 (the last one ends at +∞ when `p`
    /// is safe for good).
    pub fn safe_intervals(&self, p: Point) -> Intervals {
        complement(&self.blocked_departures(p, p, 0.0))
    }

    /// The broad phase: whether the piece's swept segment comes within its
    /// reach of the move's segment.
    fn near(&self, piece: &Piece, p: Point, q: Point) -> bool {
        segment_distance(piece.from, piece.to, p, q) < piece.reach
    }

    /// The closest approach minus the reach, for the move leaving at `t0`
    /// over the part of `[t0, t0 + tau]` in the piece's span (which the
    /// caller keeps non-empty).
    fn gap(&self, piece: &Piece, p: Point, q: Point, tau: f64, t0: f64) -> f64 {
        let lo = t0.max(piece.a);
        let hi = (t0 + tau).min(piece.b).max(lo);
        let robot = |t: f64| -> Point {
            if tau <= 0.0 {
                p
            } else {
                p + (q - p) * ((t - t0) / tau).clamp(0.0, 1.0)
            }
        };
        let da: Vector = piece.position(lo) - robot(lo);
        let db: Vector = piece.position(hi) - robot(hi);
        match &self.moving[piece.obstacle].shape {
            MovingShape::Disk(r_o) => {
                let c = closest_point_on_segment(Point::origin(), Point::from(da), Point::from(db));
                c.coords.norm() - (r_o + self.radius)
            }
            MovingShape::Pieces(shapes) => shapes
                .iter()
                .map(|shape| {
                    let mut swept: Vec<Point> = shape.iter().map(|v| v + da).collect();
                    swept.extend(shape.iter().map(|v| v + db));
                    let hull = convex_hull(&swept);
                    hull_distance(&hull) - self.radius
                })
                .fold(f64::INFINITY, f64::min),
        }
    }

    /// The open interval of departures at which the move meets `piece`.
    fn blocked_by(&self, piece: &Piece, p: Point, q: Point, tau: f64) -> Option<(f64, f64)> {
        // Departures whose motion overlaps the piece's span, from 0; after
        // an unending piece's start (and before a piece that stood since
        // forever ends, less the move) the closest approach is constant.
        let lo = (piece.a - tau).max(0.0);
        let hi = if piece.b.is_finite() {
            piece.b
        } else {
            piece.a.max(0.0)
        };
        if hi < lo {
            return None;
        }
        let g = |t0: f64| self.gap(piece, p, q, tau, t0);
        let blocked = |t0: f64| g(t0) < MARGIN;
        let (t_min, g_min) = golden_min(&g, lo, hi);
        if g_min >= MARGIN {
            return None;
        }
        // Invariant of each bisection: `safe` is not blocked, `hit` is.
        let left = if blocked(lo) {
            if lo == 0.0 { f64::NEG_INFINITY } else { lo }
        } else {
            bisect(&blocked, lo, t_min)
        };
        let right = if blocked(hi) {
            if piece.b.is_finite() {
                hi
            } else {
                f64::INFINITY
            }
        } else {
            bisect(&blocked, hi, t_min)
        };
        Some((left, right))
    }
}

/// The distance from the origin to the convex polygon `hull` (0 inside).
fn hull_distance(hull: &[Point]) -> f64 {
    match hull.len() {
        0 => f64::INFINITY,
        1 => hull[0].coords.norm(),
        2 => closest_point_on_segment(Point::origin(), hull[0], hull[1])
            .coords
            .norm(),
        _ => point_polygon_distance(Point::origin(), hull),
    }
}

/// The distance between segments `ab` and `cd`.
fn segment_distance(a: Point, b: Point, c: Point, d: Point) -> f64 {
    if segments_cross(a, b, c, d) {
        return 0.0;
    }
    let to = |x: Point, s: Point, e: Point| (x - closest_point_on_segment(x, s, e)).norm();
    to(a, c, d)
        .min(to(b, c, d))
        .min(to(c, a, b))
        .min(to(d, a, b))
}

fn segments_cross(a: Point, b: Point, c: Point, d: Point) -> bool {
    let cross = |o: Point, p: Point, q: Point| (p - o).perp(&(q - o));
    let (d1, d2) = (cross(c, d, a), cross(c, d, b));
    let (d3, d4) = (cross(a, b, c), cross(a, b, d));
    ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
}

/// The minimum of the convex `g` on `[lo, hi]` (a point of it, and the
/// value), by golden-section search to the resolution of the floats.
fn golden_min(g: &impl Fn(f64) -> f64, lo: f64, hi: f64) -> (f64, f64) {
    const INV_PHI: f64 = 0.618_033_988_749_894_9;
    let (mut a, mut b) = (lo, hi);
    let mut best = (lo, g(lo));
    let g_hi = g(hi);
    if g_hi < best.1 {
        best = (hi, g_hi);
    }
    if best.1 < MARGIN {
        return best;
    }
    let mut c = b - (b - a) * INV_PHI;
    let mut d = a + (b - a) * INV_PHI;
    let (mut gc, mut gd) = (g(c), g(d));
    for _ in 0..200 {
        if gc.min(gd) < best.1 {
            best = if gc < gd { (c, gc) } else { (d, gd) };
        }
        if best.1 < MARGIN || b - a <= 1e-13 * b.abs().max(1.0) || b.is_nan() {
            break;
        }
        if gc < gd {
            b = d;
            d = c;
            gd = gc;
            c = b - (b - a) * INV_PHI;
            gc = g(c);
        } else {
            a = c;
            c = d;
            gc = gd;
            d = a + (b - a) * INV_PHI;
            gd = g(d);
        }
    }
    best
}

/// Between `safe` (not blocked) and `hit` (blocked): the last safe time
/// found, as close to the boundary as the floats allow.
fn bisect(blocked: &impl Fn(f64) -> bool, mut safe: f64, mut hit: f64) -> f64 {
    for _ in 0..200 {
        let mid = safe + (hit - safe) / 2.0;
        if mid == safe || mid == hit {
            break;
        }
        if blocked(mid) {
            hit = mid;
        } else {
            safe = mid;
        }
    }
    safe
}

/// Sorted, overlapping or touching intervals merged.
fn merge(mut ivs: Intervals) -> Intervals {
    ivs.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut out: Intervals = Vec::with_capacity(ivs.len());
    for (a, b) in ivs {
        match out.last_mut() {
            Some(last) if a <= last.1 => last.1 = last.1.max(b),
            _ => out.push((a, b)),
        }
    }
    out
}

/// The closed intervals of `[0, ∞)` outside the open `blocked` ones.
fn complement(blocked: &Intervals) -> Intervals {
    let mut out = Vec::new();
    let mut from = 0.0f64;
    for &(a, b) in blocked {
        if a >= from {
            out.push((from, a));
        }
        from = from.max(b);
    }
    if from.is_finite() {
        out.push((from, f64::INFINITY));
    }
    out
}

/// The earliest time `t ≥ from` outside every open interval of `blocked`
/// (sorted, disjoint), or `None` when that is never.
pub fn first_free(blocked: &Intervals, from: f64) -> Option<f64> {
    let mut t = from;
    let start = blocked.partition_point(|iv| iv.1 <= t);
    for &(a, b) in &blocked[start..] {
        if t <= a {
            return Some(t);
        }
        if t < b {
            t = b;
        }
    }
    t.is_finite().then_some(t)
}

#[cfg(test)]
mod tests {
    use super::super::{Timed, Waypoint, validate_trajectory};
    use super::*;
    use crate::fixtures::world_in;
    use crate::{Aabb, Config, RobotShape};

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    fn cart(shape: MovingShape, route: &[(f64, f64, f64)], after: After) -> MovingObstacle {
        MovingObstacle {
            name: "cart".into(),
            shape,
            route: route
                .iter()
                .map(|&(t, x, y)| Waypoint { t, at: p(x, y) })
                .collect(),
            after,
        }
    }

    /// A disk cart crossing the robot's cell: standing there is unsafe
    /// exactly while the centres are closer than the radii's sum.
    #[test]
    fn standing_in_a_carts_way_is_unsafe_while_it_passes() {
        // The cart (radius 0.5) goes up x = 5 at 1 unit/s from y = 0.
        let c = [cart(
            MovingShape::Disk(0.5),
            &[(0.0, 5.0, 0.0), (20.0, 5.0, 20.0)],
            After::Stay,
        )];
        let mover = RoundMover::new(&c, 0.5);
        let safe = mover.safe_intervals(p(5.0, 5.0));
        assert_eq!(safe.len(), 2, "{safe:?}");
        assert_eq!(safe[0].0, 0.0);
        assert!((safe[0].1 - 4.0).abs() < 1e-8, "{safe:?}");
        assert!((safe[1].0 - 6.0).abs() < 1e-8, "{safe:?}");
        assert_eq!(safe[1].1, f64::INFINITY);
        // Beside its path, always safe; on its last point, never again.
        assert_eq!(
            mover.safe_intervals(p(7.0, 5.0)),
            vec![(0.0, f64::INFINITY)]
        );
        let parked = mover.safe_intervals(p(5.0, 20.0));
        assert_eq!(parked.len(), 1);
        assert!((parked[0].1 - 19.0).abs() < 1e-8, "{parked:?}");
    }

    /// The blocked departures of a move across the cart's path, against
    /// the validator on departures just inside and just outside.
    #[test]
    fn blocked_departures_agree_with_the_validator() {
        let world = world_in(
            Aabb::from_corners(p(-50.0, -50.0), p(50.0, 50.0)),
            Vec::new(),
        );
        let square = vec![p(-0.5, -0.5), p(0.5, -0.5), p(0.5, 0.5), p(-0.5, 0.5)];
        for shape in [MovingShape::Disk(0.5), MovingShape::Pieces(vec![square])] {
            let c = [cart(
                shape,
                &[(0.0, 5.0, 0.0), (10.0, 5.0, 10.0), (14.0, 1.0, 10.0)],
                After::Vanish,
            )];
            for radius in [0.0, 0.3] {
                let robot = if radius == 0.0 {
                    RobotShape::Point
                } else {
                    RobotShape::Disk(radius)
                };
                let mover = RoundMover::new(&c, radius);
                let (from, to) = (p(4.0, 5.0), p(6.0, 5.0));
                let tau = 2.0;
                let blocked = mover.blocked_departures(from, to, tau);
                assert_eq!(blocked.len(), 1, "{blocked:?}");
                let (a, b) = blocked[0];
                let valid = |t0: f64| {
                    let tr = [
                        Timed {
                            pose: Config::new(4.0, 5.0, 0.0),
                            t: 0.0,
                        },
                        Timed {
                            pose: Config::new(4.0, 5.0, 0.0),
                            t: t0,
                        },
                        Timed {
                            pose: Config::new(6.0, 5.0, 0.0),
                            t: t0 + tau,
                        },
                        Timed {
                            pose: Config::new(6.0, 5.0, 0.0),
                            t: t0 + tau + 30.0,
                        },
                        Timed {
                            pose: Config::new(-20.0, 5.0, 0.0),
                            t: t0 + tau + 60.0,
                        },
                    ];
                    validate_trajectory(&world, &c, &robot, 1.0, &tr).is_ok()
                };
                assert!(a > 0.5 && b < 10.0, "{blocked:?}");
                assert!(valid(b) && valid(a), "ends of {blocked:?} are safe");
                assert!(!valid(a + 1e-6) && !valid(b - 1e-6), "{blocked:?}");
                assert!(!valid((a + b) / 2.0));
            }
        }
    }

    #[test]
    fn first_free_skips_the_blocked_intervals() {
        let blocked = vec![(1.0, 2.0), (2.0, 3.0), (5.0, f64::INFINITY)];
        assert_eq!(first_free(&blocked, 0.5), Some(0.5));
        assert_eq!(first_free(&blocked, 1.0), Some(1.0));
        // Open intervals: the instant between two is free.
        assert_eq!(first_free(&blocked, 1.5), Some(2.0));
        assert_eq!(first_free(&merge(blocked.clone()), 1.5), Some(3.0));
        assert_eq!(first_free(&blocked, 4.0), Some(4.0));
        assert_eq!(first_free(&blocked, 5.5), None);
        assert_eq!(
            merge(blocked.clone()),
            vec![(1.0, 3.0), (5.0, f64::INFINITY)]
        );
        assert_eq!(complement(&merge(blocked)), vec![(0.0, 1.0), (3.0, 5.0)]);
    }
}
