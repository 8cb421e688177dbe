//! When a round robot (a point or a disk) may stand at a point, and when it
//! may leave a point for a straight move at constant speed, among moving
//! obstacles: the time-aware planners' checker (SPEC 3.10), exact (in
//! closed form, to the floats' rounding) and stricter than the validator
//! ([`super::validate_trajectory`]) by a distance margin.
//!
//! # Why one interval per convex piece of a route
//! Cut an obstacle's route into pieces in which it moves linearly (standing
//! before its first waypoint, between waypoints, standing after its last
//! unless it vanishes). For a move from `p` to `q` taking `τ` and leaving
//! at `t0`, the obstacle's offset from the robot, `d(t0, t)`, is affine in
//! `(t0, t)` over the convex set `t0 ≤ t ≤ t0 + τ`, `t` in the piece's
//! span. The robot's centre comes within its radius of a convex shape for
//! `d` in a convex set, so the meetings `(t0, t)` are a convex set and the
//! departures that meet the piece one open interval: its ends are the
//! extreme `t0` of that set, computed exactly ([`Frame`]). A shape that is
//! not convex is met on one interval per convex piece. Standing at `p` is
//! the move of length 0 (`q = p`, `τ = 0`).
//!
//! The tests check the closed forms against a search that needs only the
//! convexity: the closest approach `g(t0)`, a minimum over `t` of a convex
//! function, is convex in `t0`, so a golden-section search for its minimum
//! and a root finder on each side find the same interval.

#[cfg(test)]
use super::point_polygon_distance;
use super::{After, MovingObstacle, MovingShape};
use crate::buckets::Buckets;
#[cfg(test)]
use crate::polygon::closest_point_on_segment;
#[cfg(test)]
use crate::polygon::convex_hull;
use crate::polygon::distance_segment_segment;
use crate::{Aabb, Point, Vector};

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
    #[cfg(test)]
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
    /// The pieces' swept boxes (grown by their reach), by bucket: the
    /// broad phase of a query.
    buckets: Option<Buckets>,
    /// The boxes of `buckets` and the piece of each.
    boxes: Vec<Aabb>,
    owners: Vec<u32>,
}

/// The length of route that one box of the broad phase covers.
const CHUNK: f64 = 4.0;

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
        // A long route's box would be listed in many buckets it never
        // crosses: each piece goes in as chunks of about a bucket's side.
        let mut boxes: Vec<Aabb> = Vec::new();
        let mut owners: Vec<u32> = Vec::new();
        for (k, p) in pieces.iter().enumerate() {
            let chunks = ((p.to - p.from).norm() / CHUNK).ceil().max(1.0) as usize;
            let r = Vector::new(p.reach, p.reach);
            for c in 0..chunks {
                let at = |s: f64| p.from + (p.to - p.from) * s;
                let b = Aabb::from_corners(
                    at(c as f64 / chunks as f64),
                    at((c + 1) as f64 / chunks as f64),
                );
                boxes.push(Aabb {
                    min: b.min - r,
                    max: b.max + r,
                });
                owners.push(k as u32);
            }
        }
        let buckets = boxes.first().map(|first| Buckets::new(*first, &boxes, 256));
        RoundMover {
            moving,
            radius,
            pieces,
            buckets,
            boxes,
            owners,
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
        self.blocked_departures_within(p, q, tau, f64::NEG_INFINITY, f64::INFINITY)
    }

    /// [`RoundMover::blocked_departures`] where they matter for departures
    /// in `[lo, hi]`: every blocked interval that meets `[lo, hi]` is
    /// there, whole; intervals wholly outside may be left out (the pieces
    /// of routes that end before `lo`, or begin after the move would end
    /// leaving at `hi`, are not looked at).
    pub fn blocked_departures_within(
        &self,
        p: Point,
        q: Point,
        tau: f64,
        lo: f64,
        hi: f64,
    ) -> Intervals {
        let Some(buckets) = &self.buckets else {
            return Vec::new();
        };
        let span = Aabb::from_corners(p, q);
        let ((c0, c1), (r0, r1)) = buckets.range(&span);
        let mut candidates: Vec<u32> = Vec::new();
        for k in r0..=r1 {
            for c in c0..=c1 {
                candidates.extend(
                    buckets
                        .items(c, k)
                        .iter()
                        .filter(|&&b| self.boxes[b as usize].meets(&span))
                        .map(|&b| self.owners[b as usize]),
                );
            }
        }
        candidates.sort_unstable();
        candidates.dedup();
        let mut out = Vec::new();
        for &i in &candidates {
            let piece = &self.pieces[i as usize];
            // A piece meets departures in (a − τ, b) at most.
            if piece.b < lo || piece.a - tau > hi || !self.near(piece, p, q) {
                continue;
            }
            self.blocked_by(piece, p, q, tau, &mut out);
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
        distance_segment_segment(piece.from, piece.to, p, q) < piece.reach
    }

    /// The closest approach minus the reach, for the move leaving at `t0`
    /// over the part of `[t0, t0 + tau]` in the piece's span (which the
    /// caller keeps non-empty).
    #[cfg(test)]
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
    fn blocked_by(&self, piece: &Piece, p: Point, q: Point, tau: f64, out: &mut Intervals) {
        let frame = Frame::new(piece, p, q, tau);
        let reach = self.radius + MARGIN;
        match &self.moving[piece.obstacle].shape {
            MovingShape::Disk(r_o) => {
                out.extend(
                    frame
                        .disk(Vector::zeros(), r_o + reach)
                        .and_then(|(lo, hi)| open_from_zero(lo, hi)),
                );
            }
            // Each convex piece of a polygon is met on one interval; a
            // shape that is not convex may be met on several.
            // A point robot meets a polygon where its centre enters the
            // closed polygon: the ends of the interval are the touching
            // departures, which the validator lets pass.
            MovingShape::Pieces(shapes) => {
                for shape in shapes {
                    let range = if self.radius > 0.0 {
                        frame.rounded_polygon(shape, reach)
                    } else {
                        frame.polygon(shape)
                    };
                    out.extend(range.and_then(|(lo, hi)| open_from_zero(lo, hi)));
                }
            }
        }
    }

    /// [`RoundMover::blocked_by`] for any convex shape: by the convexity of
    /// the closest approach in the departure time (see the module's
    /// documentation), a golden-section search and a root finder.
    #[cfg(test)]
    fn blocked_by_search(&self, piece: &Piece, p: Point, q: Point, tau: f64) -> Option<(f64, f64)> {
        // Departures whose motion overlaps the piece's span, from 0; after
        // an unending piece's start (and before a piece that stood since
        // forever ends, less the move) the closest approach is constant.
        let (mut a, mut b) = (piece.a, piece.b);
        // A moving piece comes near the move only while its centre is
        // within its reach of the move's segment: within the reach plus
        // half the move of the move's middle.
        if a.is_finite() && b.is_finite() && piece.from != piece.to {
            let v = (piece.to - piece.from) / (b - a);
            let w = piece.from - v * a - Point::from((p.coords + q.coords) / 2.0);
            let rho = piece.reach + (q - p).norm() / 2.0;
            let (qa, qb, qc) = (v.norm_squared(), w.dot(&v), w.norm_squared() - rho * rho);
            let disc = qb * qb - qa * qc;
            if disc < 0.0 {
                return None;
            }
            let root = disc.sqrt();
            a = a.max((-qb - root) / qa);
            b = b.min((-qb + root) / qa);
            if b < a {
                return None;
            }
        }
        let lo = (a - tau).max(0.0);
        let hi = if b.is_finite() { b } else { a.max(0.0) };
        if hi < lo {
            return None;
        }
        let g = |t0: f64| self.gap(piece, p, q, tau, t0) - MARGIN;
        // The closest approach changes no faster than the robot and the
        // obstacle move: the ends of the relative segment do.
        let moving = piece.a.is_finite() && piece.b.is_finite();
        let lipschitz = if moving {
            (piece.to - piece.from).norm() / (piece.b - piece.a)
        } else {
            0.0
        } + if tau > 0.0 { (q - p).norm() / tau } else { 0.0 };
        let (g_lo, g_hi) = (g(lo), g(hi));
        let (t_min, g_min) = golden_min(&g, lo, hi, g_lo, g_hi, lipschitz * (1.0 + 1e-9));
        if g_min >= 0.0 {
            return None;
        }
        let left = if g_lo < 0.0 {
            if lo == 0.0 { f64::NEG_INFINITY } else { lo }
        } else {
            last_safe(&g, lo, g_lo, t_min, g_min)
        };
        let right = if g_hi < 0.0 {
            if piece.b.is_finite() {
                hi
            } else {
                f64::INFINITY
            }
        } else {
            last_safe(&g, hi, g_hi, t_min, g_min)
        };
        Some((left, right))
    }
}

/// A move against one piece of a route in the plane of (departure `t0`,
/// time since departure `s`): the obstacle's offset from the robot's
/// centre is `c + v·t0 + w·s` (`v` the obstacle's velocity, `w = v − u`,
/// `u` the robot's) over the parallelogram `0 ≤ s ≤ τ`, `a ≤ t0 + s ≤ b`.
/// A standing piece (`v = 0`, its span possibly unbounded) depends on `s`
/// alone: the meetings are an interval `S` of `s`, and the departures those
/// `t0` with `t0 + s` in `[a, b]` for some `s` in `S`.
///
/// The obstacle's shape is cut into convex regions, each met on a convex
/// set of the plane: the inside of an ellipse (a disk region, whose offset
/// must stay within its radius) or of a polygon (a polygon region, whose
/// half-planes are linear in `(t0, s)`). The extreme departures of a convex
/// set cut by the parallelogram are exact: for a polygon, the corners of
/// the clipped polygon; for an ellipse, the parallelogram's corners inside
/// it, its edges' crossings of it, and the two points of the ellipse whose
/// tangent is along `s`.
struct Frame {
    c: Vector,
    v: Vector,
    w: Vector,
    a: f64,
    b: f64,
    tau: f64,
    standing: bool,
}

impl Frame {
    fn new(piece: &Piece, p: Point, q: Point, tau: f64) -> Frame {
        let u = if tau > 0.0 {
            (q - p) / tau
        } else {
            Vector::zeros()
        };
        let standing = piece.from == piece.to || !piece.a.is_finite() || !piece.b.is_finite();
        let v = if standing {
            Vector::zeros()
        } else {
            (piece.to - piece.from) / (piece.b - piece.a)
        };
        let c = if standing {
            piece.from - p
        } else {
            piece.from - v * piece.a - p
        };
        Frame {
            c,
            v,
            w: v - u,
            a: piece.a,
            b: piece.b,
            tau,
            standing,
        }
    }

    /// The departures of a standing piece met for `s` in `[s_lo, s_hi]`.
    fn shifted(&self, s_lo: f64, s_hi: f64) -> Option<(f64, f64)> {
        (s_lo <= s_hi).then_some((self.a - s_hi, self.b - s_lo))
    }

    /// The extreme departures at which the offset, moved by `k`, is within
    /// `r` of the origin: the robot's centre within `r` of the obstacle's
    /// point `k`.
    fn disk(&self, k: Vector, r: f64) -> Option<(f64, f64)> {
        let r2 = r * r;
        let c = self.c + k;
        let (v, w, tau) = (self.v, self.w, self.tau);
        if self.standing {
            let (s_lo, s_hi) = if tau > 0.0 {
                let (lo, hi) = quadratic_below(w.norm_squared(), c.dot(&w), c.norm_squared() - r2)?;
                (lo.max(0.0), hi.min(tau))
            } else if c.norm_squared() < r2 {
                (0.0, 0.0)
            } else {
                return None;
            };
            return self.shifted(s_lo, s_hi);
        }
        let (a, b) = (self.a, self.b);
        let offset = |t0: f64, s: f64| c + v * t0 + w * s;
        let inside =
            |t0: f64, s: f64| -> bool { (0.0..=tau).contains(&s) && t0 + s >= a && t0 + s <= b };
        let corners = [(a, 0.0), (b, 0.0), (b - tau, tau), (a - tau, tau)];
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut take = |t0: f64| {
            lo = lo.min(t0);
            hi = hi.max(t0);
        };
        for k in 0..4 {
            let (t_a, s_a) = corners[k];
            let (t_b, s_b) = corners[(k + 1) % 4];
            let d_a = offset(t_a, s_a);
            if d_a.norm_squared() < r2 {
                take(t_a);
            }
            // The edge's crossings of the ellipse: |d_a + λ·e|² = r².
            let e = offset(t_b, s_b) - d_a;
            if let Some((l1, l2)) =
                quadratic_below(e.norm_squared(), d_a.dot(&e), d_a.norm_squared() - r2)
            {
                for l in [l1, l2] {
                    if (0.0..=1.0).contains(&l) {
                        take(t_a + (t_b - t_a) * l);
                    }
                }
            }
        }
        // Where the tangent is along s: the part of the offset across w is r.
        let w2 = w.norm_squared();
        let across = Vector::new(-w.y, w.x);
        let rate = across.dot(&v);
        if w2 > 0.0 && rate != 0.0 {
            for sign in [-1.0, 1.0] {
                let t0 = (sign * r * w2.sqrt() - across.dot(&c)) / rate;
                let s = -w.dot(&(c + v * t0)) / w2;
                if inside(t0, s) {
                    take(t0);
                }
            }
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// The extreme departures at which the robot's centre is inside the
    /// convex polygon `shape` (counter-clockwise, in the obstacle's frame):
    /// minus the offset inside it, one linear inequality per edge.
    fn polygon(&self, shape: &[Point]) -> Option<(f64, f64)> {
        let n = shape.len();
        if n < 3 {
            return None;
        }
        // Clockwise (as a shape may come), the normals point inwards.
        let twice_area: f64 = (0..n)
            .map(|i| shape[i].coords.perp(&shape[(i + 1) % n].coords))
            .sum();
        let flip = if twice_area < 0.0 { -1.0 } else { 1.0 };
        // Each edge: −n·(c + v·t0 + w·s) ≤ h, i.e. α·t0 + β·s ≤ γ.
        let planes = (0..n).filter_map(|i| {
            let (p0, p1) = (shape[i], shape[(i + 1) % n]);
            let e = p1 - p0;
            let len = e.norm();
            (len > 0.0).then(|| {
                let normal = Vector::new(e.y, -e.x) / len * flip;
                let h = normal.dot(&p0.coords);
                (
                    -normal.dot(&self.v),
                    -normal.dot(&self.w),
                    h + normal.dot(&self.c),
                )
            })
        });
        if self.standing {
            let (mut s_lo, mut s_hi) = (0.0f64, self.tau);
            for (_, beta, gamma) in planes {
                if beta > 0.0 {
                    s_hi = s_hi.min(gamma / beta);
                } else if beta < 0.0 {
                    s_lo = s_lo.max(gamma / beta);
                } else if gamma < 0.0 {
                    return None;
                }
            }
            return self.shifted(s_lo, s_hi);
        }
        let (a, b, tau) = (self.a, self.b, self.tau);
        let mut poly = vec![(a, 0.0), (b, 0.0), (b - tau, tau), (a - tau, tau)];
        for (alpha, beta, gamma) in planes {
            poly = clip(&poly, alpha, beta, gamma);
            if poly.is_empty() {
                return None;
            }
        }
        let lo = poly.iter().map(|v| v.0).fold(f64::INFINITY, f64::min);
        let hi = poly.iter().map(|v| v.0).fold(f64::NEG_INFINITY, f64::max);
        Some((lo, hi))
    }

    /// The extreme departures at which the robot's centre comes within `r`
    /// of the convex polygon `shape`: the polygon, each edge's band of
    /// width `r` outside it, and a disk of radius `r` at each corner.
    fn rounded_polygon(&self, shape: &[Point], r: f64) -> Option<(f64, f64)> {
        let n = shape.len();
        let twice_area: f64 = (0..n)
            .map(|i| shape[i].coords.perp(&shape[(i + 1) % n].coords))
            .sum();
        let orientation = if twice_area < 0.0 { -1.0 } else { 1.0 };
        let mut range: Option<(f64, f64)> = None;
        let mut add = |part: Option<(f64, f64)>| {
            if let Some((lo, hi)) = part {
                range = Some(range.map_or((lo, hi), |(l, h)| (l.min(lo), h.max(hi))));
            }
        };
        add(self.polygon(shape));
        for i in 0..n {
            let (p0, p1) = (shape[i], shape[(i + 1) % n]);
            let e = p1 - p0;
            let len = e.norm();
            if len > 0.0 {
                // Out from p0, along, and back in (counter-clockwise for a
                // counter-clockwise shape; `polygon` takes either).
                let out = Vector::new(e.y, -e.x) / len * r * orientation;
                add(self.polygon(&[p0, p0 + out, p1 + out, p1]));
            }
            add(self.disk(p0.coords, r));
        }
        range
    }
}

/// The convex polygon `poly` cut by the half-plane `α·x + β·y ≤ γ`
/// (Sutherland–Hodgman).
fn clip(poly: &[(f64, f64)], alpha: f64, beta: f64, gamma: f64) -> Vec<(f64, f64)> {
    let side = |p: (f64, f64)| alpha * p.0 + beta * p.1 - gamma;
    let mut out = Vec::with_capacity(poly.len() + 1);
    for i in 0..poly.len() {
        let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
        let (sp, sq) = (side(p), side(q));
        if sp <= 0.0 {
            out.push(p);
        }
        if (sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0) {
            let l = sp / (sp - sq);
            out.push((p.0 + (q.0 - p.0) * l, p.1 + (q.1 - p.1) * l));
        }
    }
    out
}

/// The open interval `(lo, hi)` of departures, from 0 on: `None` when it
/// ends by 0 or is empty; from −∞ when it holds 0 (the move is blocked at
/// once).
fn open_from_zero(lo: f64, hi: f64) -> Option<(f64, f64)> {
    if hi <= 0.0 || hi <= lo {
        return None;
    }
    Some((if lo < 0.0 { f64::NEG_INFINITY } else { lo }, hi))
}

/// The roots of `A·x² + 2B·x + C` (A ≥ 0) around where it is negative, or
/// `None` when it never is; for `A = 0` the whole line or nothing.
fn quadratic_below(qa: f64, qb: f64, qc: f64) -> Option<(f64, f64)> {
    if qa == 0.0 {
        if qb == 0.0 {
            return (qc < 0.0).then_some((f64::NEG_INFINITY, f64::INFINITY));
        }
        let x = -qc / (2.0 * qb);
        return Some(if qb > 0.0 {
            (f64::NEG_INFINITY, x)
        } else {
            (x, f64::INFINITY)
        });
    }
    let disc = qb * qb - qa * qc;
    if disc <= 0.0 {
        return None;
    }
    let root = disc.sqrt();
    // The stable pair of roots.
    let q = -(qb + qb.signum() * root);
    let (x1, x2) = if q == 0.0 {
        (0.0, 0.0)
    } else {
        (q / qa, qc / q)
    };
    Some((x1.min(x2), x1.max(x2)))
}

/// The distance from the origin to the convex polygon `hull` (0 inside).
#[cfg(test)]
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

/// A point of `[lo, hi]` where the convex `g` (Lipschitz constant
/// `lipschitz`; `g_lo`, `g_hi` its values at the ends) is negative, or its
/// minimum when it is nowhere negative (then only as precise as needed to
/// tell: a golden-section search that stops once the bracket is too short
/// for `g` to get below 0 in it, or at the floats' resolution).
#[cfg(test)]
fn golden_min(
    g: &impl Fn(f64) -> f64,
    lo: f64,
    hi: f64,
    g_lo: f64,
    g_hi: f64,
    lipschitz: f64,
) -> (f64, f64) {
    const INV_PHI: f64 = 0.618_033_988_749_894_9;
    let mut best = if g_hi < g_lo { (hi, g_hi) } else { (lo, g_lo) };
    if best.1 < 0.0 || hi <= lo {
        return best;
    }
    let (mut a, mut b) = (lo, hi);
    let mut c = b - (b - a) * INV_PHI;
    let mut d = a + (b - a) * INV_PHI;
    let (mut gc, mut gd) = (g(c), g(d));
    for _ in 0..300 {
        if gc.min(gd) < best.1 {
            best = if gc < gd { (c, gc) } else { (d, gd) };
        }
        // The minimum lies in [a, b], within b − a of c and of d.
        if best.1 < 0.0
            || gc.min(gd) - lipschitz * (b - a) >= 0.0
            || b - a <= 1e-13 * b.abs().max(1.0)
        {
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

/// Between `safe` (`g_safe ≥ 0`) and `hit` (`g_hit < 0`) on a convex `g`:
/// the last point found with `g ≥ 0`, as close to the crossing as the
/// floats allow (regula falsi with the Illinois correction, falling back to
/// halving when a step stalls).
#[cfg(test)]
fn last_safe(
    g: &impl Fn(f64) -> f64,
    mut safe: f64,
    mut g_safe: f64,
    mut hit: f64,
    mut g_hit: f64,
) -> f64 {
    let mut side = 0i8;
    for k in 0..200 {
        if (hit - safe).abs() <= 1e-13 * safe.abs().max(1.0) {
            break;
        }
        let mut x = safe + (hit - safe) * (g_safe / (g_safe - g_hit));
        // Every fourth step, or when the secant leaves the bracket or
        // lands on an end: halve.
        let inside = x > safe.min(hit) && x < safe.max(hit);
        if k % 4 == 3 || !inside {
            x = safe + (hit - safe) / 2.0;
        }
        if x == safe || x == hit {
            break;
        }
        let gx = g(x);
        if gx < 0.0 {
            hit = x;
            g_hit = gx;
            if side == -1 {
                g_safe /= 2.0;
            }
            side = -1;
        } else {
            safe = x;
            g_safe = gx;
            if side == 1 {
                g_hit /= 2.0;
            }
            side = 1;
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

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(500))]
        /// A window leaves out only what cannot matter: from any departure
        /// in `[lo, hi]`, the first free one at most `hi` is the same as
        /// with every blocked interval (three carts zigzagging through a
        /// move, a point or a disk robot, random moves and windows).
        #[test]
        fn a_window_changes_no_departure_within_it(
            waypoints in proptest::collection::vec((0.0..10.0f64, 0.0..10.0f64), 3..12),
            from in (0.0..10.0f64, 0.0..10.0f64),
            to in (0.0..10.0f64, 0.0..10.0f64),
            radius in proptest::prop_oneof![proptest::strategy::Just(0.0), 0.1..0.8f64],
            lo in 0.0..30.0f64,
            width in 0.0..20.0f64,
        ) {
            let square = vec![p(-0.5, -0.5), p(0.5, -0.5), p(0.5, 0.5), p(-0.5, 0.5)];
            let route = |shift: f64| -> Vec<(f64, f64, f64)> {
                waypoints
                    .iter()
                    .enumerate()
                    .map(|(k, &(x, y))| (k as f64 * 3.0 + shift, x, y))
                    .collect()
            };
            let carts = [
                cart(MovingShape::Disk(0.6), &route(0.0), After::Stay),
                cart(MovingShape::Pieces(vec![square.clone()]), &route(1.5), After::Vanish),
                cart(MovingShape::Pieces(vec![square]), &route(4.0), After::Stay),
            ];
            let mover = RoundMover::new(&carts, radius);
            let (a, b) = (p(from.0, from.1), p(to.0, to.1));
            let tau = (b - a).norm();
            let hi = lo + width;
            let all = mover.blocked_departures(a, b, tau);
            let some = mover.blocked_departures_within(a, b, tau, lo, hi);
            for k in 0..=20 {
                let t = lo + width * k as f64 / 20.0;
                let full = first_free(&all, t).filter(|&x| x <= hi);
                let windowed = first_free(&some, t).filter(|&x| x <= hi);
                proptest::prop_assert_eq!(full, windowed, "from {}", t);
            }
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(3000))]
        /// The closed forms (disks, and convex polygons: rectangles and
        /// triangles, either way round) agree with the search that needs only convexity, on
        /// random moves and route pieces (standing for good, or moving
        /// between two waypoints), for point and disk robots.
        #[test]
        fn closed_forms_agree_with_the_search(
            kind in 0usize..4,
            size in (0.1..2.0f64, 0.1..2.0f64),
            apex in (-1.0..1.0f64, 0.1..2.0f64),
            from in (0.0..10.0f64, 0.0..10.0f64),
            to in (0.0..10.0f64, 0.0..10.0f64),
            a in 0.0..10.0f64,
            span in 0.1..10.0f64,
            p in (0.0..10.0f64, 0.0..10.0f64),
            step in (-1i32..=1, -1i32..=1),
            speed in 0.2..3.0f64,
            r_o in 0.1..2.0f64,
            radius in proptest::prop_oneof![proptest::strategy::Just(0.0), 0.0..1.0f64],
            stays in proptest::bool::ANY,
        ) {
            let mut route = vec![Waypoint { t: a, at: Point::new(from.0, from.1) }];
            if !stays {
                route.push(Waypoint { t: a + span, at: Point::new(to.0, to.1) });
            }
            let shape = match kind {
                0 => MovingShape::Disk(r_o),
                1 => MovingShape::polygon(&[
                    Point::new(-size.0 / 2.0, -size.1 / 2.0),
                    Point::new(size.0 / 2.0, -size.1 / 2.0),
                    Point::new(size.0 / 2.0, size.1 / 2.0),
                    Point::new(-size.0 / 2.0, size.1 / 2.0),
                ]),
                2 => MovingShape::polygon(&[
                    Point::new(-size.0, -0.3),
                    Point::new(size.1, -0.2),
                    Point::new(apex.0, apex.1),
                ]),
                // Clockwise, as the analyzer may give a piece.
                _ => MovingShape::Pieces(vec![vec![
                    Point::new(apex.0, apex.1),
                    Point::new(size.1, -0.2),
                    Point::new(-size.0, -0.3),
                ]]),
            };
            let c = [MovingObstacle {
                name: "c".into(),
                shape,
                route,
                after: After::Stay,
            }];
            let mover = RoundMover::new(&c, radius);
            let p = Point::new(p.0, p.1);
            let q = p + Vector::new(f64::from(step.0), f64::from(step.1));
            let tau = (q - p).norm() / speed;
            for piece in &mover.pieces {
                let mut found = Vec::new();
                mover.blocked_by(piece, p, q, tau, &mut found);
                proptest::prop_assert!(found.len() <= 1, "a convex shape: {found:?}");
                let closed = found.first().copied();
                let search = mover.blocked_by_search(piece, p, q, tau);
                let close = |x: f64, y: f64| x == y || (x - y).abs() <= 1e-6 * x.abs().max(1.0);
                match (closed, search) {
                    (Some(x), Some(y)) => proptest::prop_assert!(
                        close(x.0, y.0) && close(x.1, y.1),
                        "closed form {x:?}, search {y:?} for {piece:?}"
                    ),
                    (None, None) => {}
                    // A grazing meeting: a vanishing interval on one side.
                    (Some(x), None) | (None, Some(x)) => proptest::prop_assert!(
                        x.1 - x.0 < 1e-4,
                        "only one finds {x:?} for {piece:?}"
                    ),
                }
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
