//! The independent validator of SPEC 3.0: the referee of every planner's path.
//!
//! It is built on parry2d's shapes and queries and shares no code with the
//! planners' own collision queries ([`super::collide`]), so that a bug in one
//! does not hide in the other.
//!
//! # What counts as a collision
//! Every shape involved is a convex polygonal *core* (a point, a segment or
//! a convex polygon) grown by a radius: the robot's swept region is a point,
//! a segment, a capsule (a segment grown by the disk's radius) or a convex
//! polygon; obstacle pieces are convex polygons, boxes, or a disk's centre
//! grown by its radius. The *depth* of an overlap is the sum of the radii
//! minus the signed distance between the cores (negative: the penetration
//! depth). A swept region collides with an obstacle piece when the depth
//! exceeds [`TOUCH_EPS`]; touching is allowed. A segment obstacle is a core
//! of radius 0, so a robot collides with it when the segment meets its
//! interior deeper than `TOUCH_EPS`, and a point robot only when its motion
//! crosses the segment properly (touching an end, or sliding along the
//! segment, is allowed).
//!
//! Obstacles made of several pieces (a decomposed polygon, the blocked cells
//! of a grid) are solid across the edges where their pieces meet: a point
//! robot sliding along such a *seam*, or sitting on it, is inside the
//! obstacle even though it only touches each piece. For robots of radius at
//! most `TOUCH_EPS` the validator therefore also rejects any contact with the
//! open band of half-width `TOUCH_EPS` around each seam (stopping short of
//! the seam's ends so that it stays at least `TOUCH_EPS` from the obstacle's
//! boundary) and with the square of half-width `2·TOUCH_EPS` around each
//! grid corner whose four cells are blocked. Larger robots cannot reach a
//! seam without overlapping a piece deeper than `TOUCH_EPS`.
//!
//! Signed distances are exact up to rounding: the separating-axis test over
//! the edge normals of both cores (with parry's support maps) gives the
//! penetration depth, and parry's distance query the distance of separated
//! cores. Penetration is never taken from GJK/EPA on rounded shapes, whose
//! results are only accurate to about 1e-9 (and fail on flat shapes).

use nalgebra::Unit;
use parry2d_f64::math::Isometry;
use parry2d_f64::query::{self, sat};
use parry2d_f64::shape::{
    Ball, ConvexPolygon as ParryPolygon, Cuboid, Segment, Shape as ParryShape, SupportMap,
};

use super::{
    Aabb, Config, Grid, Point, RobotShape, Shape, TOUCH_EPS, Vector, World, angle_diff, polygon,
};

/// Why a path failed validation.
#[derive(Clone, Debug, PartialEq)]
pub struct ValidationError {
    /// Index of the path segment (from `path[segment]` to `path[segment+1]`).
    pub segment: usize,
    /// The configuration at the failing sub-step.
    pub at: Config,
    /// The obstacle hit, if any (else the bounds were left).
    pub obstacle: Option<String>,
    pub reason: String,
}

/// Default sub-step tolerance.
pub const DEFAULT_TOLERANCE: f64 = 0.01;

/// Checks a path against the world (SPEC 3.0).
///
/// # Behaviour
/// The path is interpolated linearly in x and y and along the shorter arc in
/// θ, and cut into sub-steps in which no point of the robot moves more than
/// `tolerance`. For each sub-step the swept region (the convex hull of the
/// robot's bodies at both ends) must not collide with any obstacle (see the
/// module documentation), and the reference point must stay in `bounds`
/// (closed, with a margin of [`TOUCH_EPS`]).
///
/// # Arguments
/// * `tolerance` — the largest motion of any point of the robot within one
///   sub-step, in world units; a value that is not finite and positive is
///   replaced by [`DEFAULT_TOLERANCE`].
///
/// # Returns
/// `Ok(())`, or the first failure along the path. An empty path is valid; a
/// path of one configuration is checked at that configuration (`segment` 0).
pub fn validate_path(
    world: &World,
    robot: &RobotShape,
    path: &[Config],
    tolerance: f64,
) -> Result<(), ValidationError> {
    Validator::new(world).validate_path(robot, path, tolerance)
}

/// The index of an obstacle whose interior the robot's body overlaps at `c`
/// (a point robot: the point is inside an obstacle's interior), if any.
///
/// Uses the collision rule of the module documentation with the body at `c`
/// as the swept region: touching is allowed; a segment obstacle never
/// contains a point robot; bounds are not checked. Returns the smallest such
/// index into `world.obstacles`.
pub fn config_collision(world: &World, robot: &RobotShape, c: Config) -> Option<usize> {
    Validator::new(world).config_collision(robot, c)
}

/// A world prepared for validation: the obstacles as parry shapes with their
/// bounding boxes. Build it once to check many paths or configurations.
pub struct Validator<'w> {
    world: &'w World,
    obstacles: Vec<Prepared<'w>>,
}

struct Prepared<'w> {
    /// The obstacle's bounding box, closed.
    aabb: Aabb,
    body: Body<'w>,
}

enum Body<'w> {
    /// Convex pieces, each grown by a radius, and the seam bands where
    /// pieces meet.
    Solid {
        pieces: Vec<(Core, f64)>,
        seams: Vec<Core>,
    },
    /// A segment obstacle.
    Wall(Core),
    Grid(&'w Grid),
}

/// The swept region (or the body) of the robot: a core grown by a radius.
struct Region {
    core: Core,
    radius: f64,
    aabb: Aabb,
}

impl Region {
    fn new(core: Core, radius: f64) -> Self {
        let aabb = grow(core.aabb(), radius);
        Region { core, radius, aabb }
    }

    /// Whether the region is so thin that it can lie on a seam without
    /// overlapping the pieces on either side.
    fn is_thin(&self) -> bool {
        self.radius <= TOUCH_EPS && !matches!(self.core, Core::Polygon(_))
    }
}

impl<'w> Validator<'w> {
    /// Prepares `world`'s obstacles. Polygons without pieces are decomposed
    /// here.
    pub fn new(world: &'w World) -> Self {
        let obstacles = world.obstacles.iter().map(|o| prepare(&o.shape)).collect();
        Validator { world, obstacles }
    }

    /// See [`validate_path`].
    pub fn validate_path(
        &self,
        robot: &RobotShape,
        path: &[Config],
        tolerance: f64,
    ) -> Result<(), ValidationError> {
        let tolerance = if tolerance.is_finite() && tolerance > 0.0 {
            tolerance
        } else {
            DEFAULT_TOLERANCE
        };
        match path {
            [] => Ok(()),
            [c] => {
                self.check_config_in_bounds(0, *c)?;
                match self.config_collision(robot, *c) {
                    Some(i) => Err(self.obstacle_error(0, *c, i)),
                    None => Ok(()),
                }
            }
            _ => {
                self.check_config_in_bounds(0, path[0])?;
                for (segment, pair) in path.windows(2).enumerate() {
                    self.check_motion(robot, segment, pair[0], pair[1], tolerance)?;
                }
                Ok(())
            }
        }
    }

    /// See [`config_collision`].
    pub fn config_collision(&self, robot: &RobotShape, c: Config) -> Option<usize> {
        let body = body_region(robot, c, c);
        self.first_hit(&body)
    }

    fn check_motion(
        &self,
        robot: &RobotShape,
        segment: usize,
        a: Config,
        b: Config,
        tolerance: f64,
    ) -> Result<(), ValidationError> {
        self.check_config_in_bounds(segment, b)?;
        let dtheta = if robot.rotates() {
            angle_diff(a.theta, b.theta)
        } else {
            0.0
        };
        // A translating convex body sweeps exactly the hull of its two end
        // bodies, so the union of sub-step hulls is that same hull: one
        // sub-step is exact. Rotation needs sub-steps in which no point moves
        // more than `tolerance` (|Δxy| + R·|Δθ| bounds every point's motion).
        let steps = if dtheta == 0.0 {
            1
        } else {
            let motion = (b.xy() - a.xy()).norm() + robot.radius() * dtheta.abs();
            ((motion / tolerance).ceil() as usize).max(1)
        };
        let at = |k: usize| -> Config {
            if k == 0 {
                a
            } else if k == steps {
                b
            } else {
                let t = k as f64 / steps as f64;
                Config::new(
                    a.x * (1.0 - t) + b.x * t,
                    a.y * (1.0 - t) + b.y * t,
                    a.theta + t * dtheta,
                )
            }
        };
        // Bounds are convex: both ends inside means the whole motion is.
        for k in 0..steps {
            let (c0, c1) = (at(k), at(k + 1));
            let region = body_region(robot, c0, c1);
            if let Some(i) = self.first_hit(&region) {
                // Name the start if the robot is already in collision there.
                let culprit = if k == 0 && self.config_collision(robot, c0).is_some() {
                    c0
                } else {
                    c1
                };
                return Err(self.obstacle_error(segment, culprit, i));
            }
        }
        Ok(())
    }

    fn check_config_in_bounds(&self, segment: usize, c: Config) -> Result<(), ValidationError> {
        if !(c.x.is_finite() && c.y.is_finite() && c.theta.is_finite()) {
            return Err(ValidationError {
                segment,
                at: c,
                obstacle: None,
                reason: "the configuration is not finite".to_string(),
            });
        }
        let b = &self.world.bounds;
        let inside = c.x >= b.min.x - TOUCH_EPS
            && c.x <= b.max.x + TOUCH_EPS
            && c.y >= b.min.y - TOUCH_EPS
            && c.y <= b.max.y + TOUCH_EPS;
        if inside {
            Ok(())
        } else {
            Err(ValidationError {
                segment,
                at: c,
                obstacle: None,
                reason: format!(
                    "the reference point ({}, {}) is outside the bounds",
                    c.x, c.y
                ),
            })
        }
    }

    fn obstacle_error(&self, segment: usize, at: Config, i: usize) -> ValidationError {
        let o = &self.world.obstacles[i];
        let reason = match o.shape {
            Shape::Segment(..) => format!("the robot crosses the segment `{}`", o.name),
            _ => format!("the robot overlaps the interior of `{}`", o.name),
        };
        ValidationError {
            segment,
            at,
            obstacle: Some(o.name.clone()),
            reason,
        }
    }

    /// The smallest index of an obstacle that `region` collides with.
    fn first_hit(&self, region: &Region) -> Option<usize> {
        let reach = grow(region.aabb, 2.0 * TOUCH_EPS);
        self.obstacles
            .iter()
            .position(|o| aabbs_meet(&o.aabb, &reach) && collides(region, &o.body))
    }
}

/// The region swept by the robot from `c0` to `c1`: the hull of its bodies
/// at both ends (the body itself when `c0 == c1`).
fn body_region(robot: &RobotShape, c0: Config, c1: Config) -> Region {
    let (p, q) = (c0.xy(), c1.xy());
    let path_core = || {
        if p == q {
            Core::Point(p)
        } else {
            Core::Segment(Segment::new(p, q))
        }
    };
    match robot {
        RobotShape::Point => Region::new(path_core(), 0.0),
        RobotShape::Disk(r) => Region::new(path_core(), r.max(0.0)),
        RobotShape::Polygon(_) => {
            let mut vertices = robot.placed_vertices(c0);
            if c1 != c0 {
                vertices.extend(robot.placed_vertices(c1));
            }
            Region::new(convex_core(&vertices), 0.0)
        }
    }
}

fn collides(region: &Region, body: &Body) -> bool {
    match body {
        Body::Solid { pieces, seams } => {
            pieces
                .iter()
                .any(|(core, radius)| overlaps(&region.core, core, region.radius + radius))
                || (region.is_thin() && seams.iter().any(|zone| meets_interior(&region.core, zone)))
        }
        Body::Wall(wall) => overlaps(&region.core, wall, region.radius),
        Body::Grid(grid) => grid_collides(region, grid),
    }
}

/// Blocked cells whose squares meet the region's box, and (for thin
/// regions) the seams between blocked cells and the corners of four.
fn grid_collides(region: &Region, grid: &Grid) -> bool {
    let (cols, rows) = grid.cells_overlapping(&grow(region.aabb, 2.0 * TOUCH_EPS));
    let thin = region.is_thin();
    let e = TOUCH_EPS;
    for row in rows {
        for col in cols.clone() {
            if !grid.is_blocked(col, row) {
                continue;
            }
            let cell = grid.cell_box(col, row);
            if overlaps(&region.core, &Core::from_aabb(&cell), region.radius) {
                return true;
            }
            if !thin {
                continue;
            }
            // Row 0 is the top row: the cell above is row - 1.
            let right = col + 1 < grid.width && grid.is_blocked(col + 1, row);
            let above = row > 0 && grid.is_blocked(col, row - 1);
            let (lo, hi) = (cell.min, cell.max);
            let band = |x0: f64, y0: f64, x1: f64, y1: f64| {
                let zone = Aabb {
                    min: Point::new(x0, y0),
                    max: Point::new(x1, y1),
                };
                meets_interior(&region.core, &Core::from_aabb(&zone))
            };
            if right && band(hi.x - e, lo.y + e, hi.x + e, hi.y - e) {
                return true;
            }
            if above && band(lo.x + e, hi.y - e, hi.x - e, hi.y + e) {
                return true;
            }
            if right
                && above
                && grid.is_blocked(col + 1, row - 1)
                && band(
                    hi.x - 2.0 * e,
                    hi.y - 2.0 * e,
                    hi.x + 2.0 * e,
                    hi.y + 2.0 * e,
                )
            {
                return true;
            }
        }
    }
    false
}

fn prepare(shape: &Shape) -> Prepared<'_> {
    match shape {
        Shape::Polygon { outline, pieces } => {
            let decomposed;
            let pieces = if pieces.is_empty() {
                decomposed = polygon::convex_decomposition(outline);
                &decomposed
            } else {
                pieces
            };
            let cores = pieces
                .iter()
                .map(|p| (convex_core(&p.vertices), 0.0))
                .collect();
            let seams = seam_zones(outline, pieces.iter().map(|p| p.vertices.as_slice()));
            Prepared {
                aabb: aabb_of(outline),
                body: Body::Solid {
                    pieces: cores,
                    seams,
                },
            }
        }
        Shape::Rect(r) => Prepared {
            aabb: *r,
            body: Body::Solid {
                pieces: vec![(Core::from_aabb(r), 0.0)],
                seams: Vec::new(),
            },
        },
        Shape::Disk { center, radius } => Prepared {
            aabb: grow(
                Aabb {
                    min: *center,
                    max: *center,
                },
                *radius,
            ),
            body: Body::Solid {
                pieces: vec![(Core::Point(*center), *radius)],
                seams: Vec::new(),
            },
        },
        Shape::Segment(a, b) => {
            let core = if a == b {
                Core::Point(*a)
            } else {
                Core::Segment(Segment::new(*a, *b))
            };
            Prepared {
                aabb: Aabb::from_corners(*a, *b),
                body: Body::Wall(core),
            }
        }
        Shape::Grid(g) => Prepared {
            aabb: g.extent(),
            body: Body::Grid(g),
        },
    }
}

/// The bands around the edges where two pieces meet (edges of a piece that
/// are not on the outline), each as an open rectangle of half-width
/// `TOUCH_EPS` around the edge. A band stops short of the edge's ends where
/// it would come within `TOUCH_EPS` of the outline, so that a robot moving
/// along the outline never meets it.
fn seam_zones<'a>(outline: &[Point], pieces: impl Iterator<Item = &'a [Point]>) -> Vec<Core> {
    let n = outline.len();
    let bounds = aabb_of(outline);
    let scale = bounds.width().max(bounds.height());
    let on_outline = |p: Point| {
        (0..n).any(|i| {
            let edge = Segment::new(outline[i], outline[(i + 1) % n]);
            parry2d_f64::query::PointQuery::distance_to_point(
                &edge,
                &Isometry::identity(),
                &p,
                true,
            ) <= 1e-9 * scale
        })
    };
    // How far from its end `a` a band along `a → b` must start: a point at
    // distance u along it and within ε of it is at least
    // u·sin α − ε·|cos α| from an outline edge leaving `a` at angle α.
    let end_margin = |a: Point, b: Point| -> f64 {
        let Some(k) = outline.iter().position(|v| *v == a) else {
            return 2.0 * TOUCH_EPS;
        };
        let d = (b - a).normalize();
        [outline[(k + n - 1) % n], outline[(k + 1) % n]]
            .iter()
            .map(|&v| {
                let e = (v - a).normalize();
                let (sin, cos) = (d.perp(&e).abs(), d.dot(&e));
                TOUCH_EPS * (1.0 + cos.abs()) / sin
            })
            .fold(TOUCH_EPS, f64::max)
            * 1.01
    };
    let mut seams: Vec<(Point, Point)> = Vec::new();
    for piece in pieces {
        for i in 0..piece.len() {
            let (a, b) = (piece[i], piece[(i + 1) % piece.len()]);
            if on_outline(Point::from((a.coords + b.coords) / 2.0))
                || seams.contains(&(b, a))
                || seams.contains(&(a, b))
            {
                continue;
            }
            seams.push((a, b));
        }
    }
    seams
        .into_iter()
        .filter_map(|(a, b)| {
            let length = (b - a).norm();
            let (ma, mb) = (end_margin(a, b), end_margin(b, a));
            // (Also drops the band when a margin is NaN or infinite.)
            if ma + mb >= length || ma.is_nan() || mb.is_nan() {
                return None;
            }
            let d = (b - a) / length;
            let n = Vector::new(-d.y, d.x) * TOUCH_EPS;
            let (a, b) = (a + d * ma, b - d * mb);
            ParryPolygon::from_convex_polyline_unmodified(vec![a - n, b - n, b + n, a + n])
                .map(Core::Polygon)
        })
        .collect()
}

// ------------------------------------------------------------------ cores

/// A convex polygonal set, possibly flat, in world coordinates.
enum Core {
    Point(Point),
    Segment(Segment),
    Polygon(ParryPolygon),
    Box { center: Point, half: Cuboid },
}

impl Core {
    fn from_aabb(b: &Aabb) -> Core {
        let center = Point::from((b.min.coords + b.max.coords) / 2.0);
        Core::Box {
            center,
            half: Cuboid::new((b.max - b.min) / 2.0),
        }
    }

    fn aabb(&self) -> Aabb {
        match self {
            Core::Point(p) => Aabb { min: *p, max: *p },
            Core::Segment(s) => Aabb::from_corners(s.a, s.b),
            Core::Polygon(p) => aabb_of(p.points()),
            Core::Box { center, half } => Aabb {
                min: center - half.half_extents,
                max: center + half.half_extents,
            },
        }
    }

    /// Calls `f` with each outward edge normal (both normals of a segment;
    /// none for a point).
    fn for_each_normal(&self, mut f: impl FnMut(Unit<Vector>)) {
        match self {
            Core::Point(_) => {}
            Core::Segment(s) => {
                if let Some(n) = s.normal() {
                    f(n);
                    f(-n);
                }
            }
            Core::Polygon(p) => p.normals().iter().for_each(|n| f(*n)),
            Core::Box { .. } => {
                for n in [Vector::x_axis(), Vector::y_axis()] {
                    f(n);
                    f(-n);
                }
            }
        }
    }

    /// Runs `f` on the core as a parry shape and its position.
    fn with_shape<R>(&self, f: impl FnOnce(&Isometry<f64>, &dyn ParryShape) -> R) -> R {
        match self {
            Core::Point(p) => f(&Isometry::translation(p.x, p.y), &Ball::new(0.0)),
            Core::Segment(s) => f(&Isometry::identity(), s),
            Core::Polygon(p) => f(&Isometry::identity(), p),
            Core::Box { center, half } => f(&Isometry::translation(center.x, center.y), half),
        }
    }
}

impl SupportMap for Core {
    fn local_support_point(&self, dir: &Vector) -> Point {
        match self {
            Core::Point(p) => *p,
            Core::Segment(s) => s.local_support_point(dir),
            Core::Polygon(p) => p.local_support_point(dir),
            Core::Box { center, half } => center + half.local_support_point(dir).coords,
        }
    }
}

/// The largest gap between `a` and `b` along the edge normals of both (the
/// separating-axis test), or `None` when neither has an edge. For convex
/// polygonal cores a negative gap is exactly minus the penetration depth;
/// a non-negative gap means the cores are disjoint or touch.
fn largest_gap(a: &Core, b: &Core) -> Option<f64> {
    let id = Isometry::identity();
    let mut gap: Option<f64> = None;
    let mut keep = |g: f64| gap = Some(gap.map_or(g, |h: f64| h.max(g)));
    a.for_each_normal(|u| {
        keep(sat::support_map_support_map_compute_separation(
            a, b, &id, &u,
        ))
    });
    b.for_each_normal(|n| {
        keep(sat::support_map_support_map_compute_separation(
            a, b, &id, &-n,
        ))
    });
    gap
}

/// Whether `a` grown by `radius` overlaps `b` deeper than [`TOUCH_EPS`]:
/// `radius − signed_distance(a, b) > TOUCH_EPS`.
fn overlaps(a: &Core, b: &Core, radius: f64) -> bool {
    let gap = largest_gap(a, b);
    match gap {
        Some(g) if g >= radius - TOUCH_EPS => return false,
        Some(g) if g < 0.0 => return true,
        _ => {}
    }
    // Disjoint or touching cores: their distance decides. Parry's distance
    // is exact for these polygonal pairs (point projections and GJK on
    // polytopes).
    let distance = a.with_shape(|pa, sa| b.with_shape(|pb, sb| query::distance(pa, sa, pb, sb)));
    // `Unsupported` cannot happen for these shapes; count it as contact.
    let distance = distance.unwrap_or(0.0).max(gap.unwrap_or(0.0));
    radius - distance > TOUCH_EPS
}

/// Whether `a` meets the interior of the 2D convex `zone`.
fn meets_interior(a: &Core, zone: &Core) -> bool {
    largest_gap(a, zone).is_some_and(|g| g < 0.0)
}

/// The convex hull of `points` as a core. Hull vertices closer than
/// `1e-12` relative to the coordinates are merged (parry refuses edges
/// shorter than machine epsilon).
fn convex_core(points: &[Point]) -> Core {
    let mut hull = polygon::convex_hull(points);
    let scale = hull
        .iter()
        .fold(1.0f64, |s, p| s.max(p.x.abs()).max(p.y.abs()));
    let mut merged: Vec<Point> = Vec::with_capacity(hull.len());
    for p in hull.drain(..) {
        if merged.last().is_none_or(|q| (p - q).norm() > 1e-12 * scale) {
            merged.push(p);
        }
    }
    while merged.len() > 1 && (merged[merged.len() - 1] - merged[0]).norm() <= 1e-12 * scale {
        merged.pop();
    }
    match merged.len() {
        0 => Core::Point(Point::origin()),
        1 => Core::Point(merged[0]),
        2 => Core::Segment(Segment::new(merged[0], merged[1])),
        _ => match ParryPolygon::from_convex_polyline_unmodified(merged.clone()) {
            Some(p) => Core::Polygon(p),
            None => Core::Segment(Segment::new(merged[0], merged[merged.len() / 2])),
        },
    }
}

// ------------------------------------------------------------------ boxes

fn aabb_of(points: &[Point]) -> Aabb {
    let first = points.first().copied().unwrap_or_else(Point::origin);
    points.iter().fold(
        Aabb {
            min: first,
            max: first,
        },
        |b, p| Aabb {
            min: Point::new(b.min.x.min(p.x), b.min.y.min(p.y)),
            max: Point::new(b.max.x.max(p.x), b.max.y.max(p.y)),
        },
    )
}

fn grow(b: Aabb, by: f64) -> Aabb {
    let v = Vector::new(by, by);
    Aabb {
        min: b.min - v,
        max: b.max + v,
    }
}

fn aabbs_meet(a: &Aabb, b: &Aabb) -> bool {
    a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{ConvexPolygon, Obstacle};
    use proptest::prelude::*;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    fn c(x: f64, y: f64) -> Config {
        Config::new(x, y, 0.0)
    }

    fn world(obstacles: Vec<(&str, Shape)>) -> World {
        World {
            bounds: Aabb {
                min: p(0.0, 0.0),
                max: p(10.0, 10.0),
            },
            obstacles: obstacles
                .into_iter()
                .map(|(n, shape)| Obstacle {
                    name: n.to_string(),
                    shape,
                })
                .collect(),
        }
    }

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Shape {
        Shape::Rect(Aabb::from_corners(p(x0, y0), p(x1, y1)))
    }

    fn polygon_shape(v: &[(f64, f64)]) -> Shape {
        let pts: Vec<Point> = v.iter().map(|&(x, y)| p(x, y)).collect();
        let outline = polygon::normalize_simple_polygon(&pts).unwrap();
        let pieces = polygon::convex_decomposition(&outline);
        Shape::Polygon { outline, pieces }
    }

    /// A grid from rows of `#` (blocked) and `.` (free), top row first.
    fn grid(cell: f64, origin: Point, rows: &[&str]) -> Shape {
        let cells = rows
            .iter()
            .flat_map(|r| r.chars().map(|ch| if ch == '#' { 0 } else { 1 }))
            .collect();
        Shape::Grid(Grid {
            cell,
            origin,
            width: rows[0].len(),
            height: rows.len(),
            cells,
        })
    }

    fn rod() -> RobotShape {
        RobotShape::Polygon(ConvexPolygon {
            vertices: vec![p(0.0, 0.0), p(2.0, 0.0), p(2.0, 0.5), p(0.0, 0.5)],
        })
    }

    fn ok(w: &World, robot: &RobotShape, path: &[Config]) -> bool {
        validate_path(w, robot, path, DEFAULT_TOLERANCE).is_ok()
    }

    #[test]
    fn empty_and_single_configuration_paths() {
        let w = world(vec![("B", rect(4.0, 4.0, 6.0, 6.0))]);
        assert!(ok(&w, &RobotShape::Point, &[]));
        assert!(ok(&w, &RobotShape::Point, &[c(1.0, 1.0)]));
        let e = validate_path(&w, &RobotShape::Point, &[c(5.0, 5.0)], 0.01).unwrap_err();
        assert_eq!((e.segment, e.obstacle.as_deref()), (0, Some("B")));
        let e = validate_path(&w, &RobotShape::Point, &[c(11.0, 5.0)], 0.01).unwrap_err();
        assert_eq!(e.obstacle, None);
    }

    #[test]
    fn leaving_the_bounds_fails_and_names_no_obstacle() {
        let w = world(vec![]);
        let e = validate_path(
            &w,
            &RobotShape::Point,
            &[c(1.0, 1.0), c(5.0, 5.0), c(5.0, 10.5)],
            0.01,
        )
        .unwrap_err();
        assert_eq!((e.segment, e.at, e.obstacle), (1, c(5.0, 10.5), None));
        // The boundary itself is inside.
        assert!(ok(
            &w,
            &RobotShape::Point,
            &[c(0.0, 0.0), c(10.0, 0.0), c(10.0, 10.0)]
        ));
    }

    #[test]
    fn point_through_a_rect_fails_and_along_its_edge_passes() {
        let w = world(vec![("B", rect(4.0, 4.0, 6.0, 6.0))]);
        let e =
            validate_path(&w, &RobotShape::Point, &[c(1.0, 5.0), c(9.0, 5.0)], 0.01).unwrap_err();
        assert_eq!((e.segment, e.obstacle.as_deref()), (0, Some("B")));
        assert!(ok(&w, &RobotShape::Point, &[c(1.0, 6.0), c(9.0, 6.0)]));
        assert!(ok(&w, &RobotShape::Point, &[c(4.0, 1.0), c(4.0, 9.0)]));
        // Through its corner (4, 6) only.
        assert!(ok(&w, &RobotShape::Point, &[c(2.0, 4.0), c(6.0, 8.0)]));
    }

    #[test]
    fn a_shallow_overlap_within_touch_eps_is_allowed() {
        let w = world(vec![("B", rect(4.0, 4.0, 6.0, 6.0))]);
        assert!(ok(
            &w,
            &RobotShape::Point,
            &[c(1.0, 6.0 - 0.5e-9), c(9.0, 6.0 - 0.5e-9)]
        ));
        assert!(!ok(
            &w,
            &RobotShape::Point,
            &[c(1.0, 6.0 - 1e-8), c(9.0, 6.0 - 1e-8)]
        ));
    }

    #[test]
    fn polygon_robot_scraping_a_wall_along_its_edge() {
        // The rod's bottom edge slides along the rect's top edge.
        let w = world(vec![("B", rect(2.0, 2.0, 8.0, 4.0))]);
        assert!(ok(&w, &rod(), &[c(1.0, 4.0), c(7.0, 4.0)]));
        assert!(!ok(&w, &rod(), &[c(1.0, 3.99), c(7.0, 3.99)]));
        // And its top edge along the rect's bottom edge.
        assert!(ok(&w, &rod(), &[c(1.0, 1.5), c(7.0, 1.5)]));
    }

    #[test]
    fn disk_between_two_walls_exactly_its_width_apart() {
        let w = world(vec![
            ("lo", rect(0.0, 0.0, 10.0, 2.0)),
            ("hi", rect(0.0, 3.0, 10.0, 5.0)),
        ]);
        let disk = RobotShape::Disk(0.5);
        assert!(ok(&w, &disk, &[c(1.0, 2.5), c(9.0, 2.5)]));
        assert!(!ok(
            &w,
            &RobotShape::Disk(0.5 + 1e-8),
            &[c(1.0, 2.5), c(9.0, 2.5)]
        ));
        // The same with segment walls and a disk obstacle touching from above.
        let w = world(vec![
            ("lo", Shape::Segment(p(0.0, 2.0), p(10.0, 2.0))),
            ("hi", Shape::Segment(p(0.0, 3.0), p(10.0, 3.0))),
            (
                "d",
                Shape::Disk {
                    center: p(5.0, 4.0),
                    radius: 0.5,
                },
            ),
        ]);
        assert!(ok(&w, &disk, &[c(1.0, 2.5), c(9.0, 2.5)]));
        assert!(!ok(&w, &disk, &[c(1.0, 2.5 + 1e-8), c(9.0, 2.5 + 1e-8)]));
    }

    #[test]
    fn point_robot_and_segment_walls() {
        let w = world(vec![("W", Shape::Segment(p(5.0, 2.0), p(5.0, 8.0)))]);
        let pt = RobotShape::Point;
        // Crossing properly fails.
        let e = validate_path(&w, &pt, &[c(1.0, 5.0), c(9.0, 5.0)], 0.01).unwrap_err();
        assert_eq!(e.obstacle.as_deref(), Some("W"));
        assert!(e.reason.contains("crosses"));
        // Along the wall, onto it, and through its end are touching.
        assert!(ok(&w, &pt, &[c(5.0, 0.0), c(5.0, 10.0)]));
        assert!(ok(&w, &pt, &[c(1.0, 5.0), c(5.0, 5.0), c(1.0, 6.0)]));
        assert!(ok(&w, &pt, &[c(1.0, 8.0), c(9.0, 8.0)]));
        // A point never collides with a wall, even sitting on it.
        assert_eq!(config_collision(&w, &pt, c(5.0, 5.0)), None);
        // A disk sitting on it does.
        assert_eq!(
            config_collision(&w, &RobotShape::Disk(0.1), c(5.0, 5.0)),
            Some(0)
        );
        assert_eq!(
            config_collision(&w, &RobotShape::Disk(0.1), c(5.1, 5.0)),
            None
        );
    }

    #[test]
    fn rotating_rod_hits_what_its_end_sweeps_over() {
        // The rod turns about its first vertex from 0 to 90°; a small box at
        // distance 1.5 on the diagonal is in the way, one at distance 2.5 is not.
        let near = world(vec![("N", rect(1.0, 1.0, 1.2, 1.2))]);
        let far = world(vec![("F", rect(2.0, 2.0, 2.2, 2.2))]);
        let path = [
            Config::new(5.0, 5.0, 0.0),
            Config::new(5.0, 5.0, std::f64::consts::FRAC_PI_2),
        ];
        let shift = |w: &World| World {
            obstacles: w
                .obstacles
                .iter()
                .map(|o| match &o.shape {
                    Shape::Rect(b) => Obstacle {
                        name: o.name.clone(),
                        shape: Shape::Rect(Aabb {
                            min: b.min + Vector::new(5.0, 5.0),
                            max: b.max + Vector::new(5.0, 5.0),
                        }),
                    },
                    _ => o.clone(),
                })
                .collect(),
            ..w.clone()
        };
        assert!(!ok(&shift(&near), &rod(), &path));
        assert!(ok(&shift(&far), &rod(), &path));
        // The shorter arc: from 350° to 10° turns through 0°, not through 180°.
        let behind = world(vec![("B", rect(2.0, 4.0, 4.0, 6.0))]);
        let wrap = [
            Config::new(5.0, 5.0, 350f64.to_radians()),
            Config::new(5.0, 5.0, 10f64.to_radians()),
        ];
        assert!(ok(&behind, &rod(), &wrap));
    }

    #[test]
    fn the_failing_configuration_is_where_the_collision_happens() {
        let w = world(vec![("B", rect(4.0, 0.0, 6.0, 10.0))]);
        // Turning at (1, 5) is free; moving to (3, 5) brings the rod's end
        // to x = 3 + 2·cos 1 > 4.
        let path = [
            Config::new(1.0, 5.0, 0.0),
            Config::new(1.0, 5.0, 1.0),
            Config::new(3.0, 5.0, 1.0),
        ];
        let e = validate_path(&w, &rod(), &path, 0.01).unwrap_err();
        assert_eq!(e.segment, 1);
        // A start in collision is named as such.
        let e = validate_path(
            &w,
            &RobotShape::Disk(0.5),
            &[c(4.2, 5.0), c(1.0, 5.0)],
            0.01,
        )
        .unwrap_err();
        assert_eq!(e.at, c(4.2, 5.0));
    }

    #[test]
    fn grid_diagonal_through_the_corner_of_two_blocked_cells() {
        // Cells (1,0) and (0,1) of a 2x2 grid at the origin are blocked.
        let w = world(vec![("G", grid(1.0, p(0.0, 0.0), &["#.", ".#"]))]);
        // Row 0 is the top: blocked cells cover [0,1]x[1,2] and [1,2]x[0,1].
        assert!(ok(&w, &RobotShape::Point, &[c(0.5, 0.5), c(1.5, 1.5)]));
        assert!(!ok(&w, &RobotShape::Point, &[c(0.5, 0.5), c(1.5, 0.5)]));
        assert!(!ok(&w, &RobotShape::Point, &[c(0.5, 0.5), c(1.6, 1.4)]));
    }

    #[test]
    fn grid_cells_form_a_solid_wall() {
        // Two blocked cells side by side: the line between them is inside.
        let w = world(vec![("G", grid(1.0, p(2.0, 2.0), &["...", "##.", "..."]))]);
        let pt = RobotShape::Point;
        // Blocked: [2,3]x[3,4] and [3,4]x[3,4]; the seam is x = 3.
        assert!(!ok(&w, &pt, &[c(3.0, 2.5), c(3.0, 4.5)]));
        assert_eq!(config_collision(&w, &pt, c(3.0, 3.5)), Some(0));
        // The outer boundary of the wall is touching.
        assert!(ok(
            &w,
            &pt,
            &[c(2.0, 3.0), c(4.0, 3.0), c(4.0, 4.0), c(2.0, 4.0)]
        ));
        assert_eq!(config_collision(&w, &pt, c(4.0, 3.5)), None);
        // A 2x2 block: its centre is inside.
        let w = world(vec![("G", grid(1.0, p(0.0, 0.0), &["##", "##"]))]);
        assert_eq!(config_collision(&w, &pt, c(1.0, 1.0)), Some(0));
        assert_eq!(config_collision(&w, &pt, c(2.0, 2.0)), None);
        // A free diagonal neighbour keeps the corner on the boundary.
        let w = world(vec![("G", grid(1.0, p(0.0, 0.0), &["#.", "##"]))]);
        assert_eq!(config_collision(&w, &pt, c(1.0, 1.0)), None);
        assert!(ok(&w, &pt, &[c(1.5, 1.5), c(1.0, 1.0)]));
    }

    #[test]
    fn a_point_cannot_slide_along_a_polygon_diagonal() {
        let l = polygon_shape(&[
            (0.0, 0.0),
            (4.0, 0.0),
            (4.0, 2.0),
            (2.0, 2.0),
            (2.0, 4.0),
            (0.0, 4.0),
        ]);
        let w = world(vec![("L", l)]);
        let Shape::Polygon { outline, pieces } = &w.obstacles[0].shape else {
            unreachable!()
        };
        assert!(pieces.len() >= 2);
        // Every seam's midpoint is inside, and a motion along it collides.
        let seams: Vec<(Point, Point)> = pieces
            .iter()
            .flat_map(|pc| {
                (0..pc.vertices.len())
                    .map(move |i| (pc.vertices[i], pc.vertices[(i + 1) % pc.vertices.len()]))
            })
            .filter(|(a, b)| {
                let k = outline.iter().position(|v| v == a).unwrap();
                let n = outline.len();
                outline[(k + 1) % n] != *b && outline[(k + n - 1) % n] != *b
            })
            .collect();
        assert!(!seams.is_empty());
        for (a, b) in seams {
            let m = Point::from((a.coords + b.coords) / 2.0);
            assert_eq!(
                config_collision(&w, &RobotShape::Point, Config::new(m.x, m.y, 0.0)),
                Some(0)
            );
            assert!(!ok(
                &w,
                &RobotShape::Point,
                &[Config::new(a.x, a.y, 0.0), Config::new(b.x, b.y, 0.0)]
            ));
        }
        // Its outline is touching.
        let path: Vec<Config> = outline.iter().map(|v| Config::new(v.x, v.y, 0.0)).collect();
        assert!(ok(&w, &RobotShape::Point, &path));
    }

    #[test]
    fn point_moving_along_a_rect_edge_and_a_disk_tangent() {
        let w = world(vec![
            ("B", rect(4.0, 4.0, 6.0, 6.0)),
            (
                "D",
                Shape::Disk {
                    center: p(2.0, 2.0),
                    radius: 1.0,
                },
            ),
        ]);
        assert!(ok(&w, &RobotShape::Point, &[c(4.0, 1.0), c(4.0, 7.0)]));
        assert!(ok(&w, &RobotShape::Point, &[c(0.0, 3.0), c(4.0, 3.0)]));
        assert!(!ok(&w, &RobotShape::Point, &[c(0.0, 2.9), c(4.0, 2.9)]));
        assert_eq!(
            config_collision(&w, &RobotShape::Point, c(2.0, 2.0)),
            Some(1)
        );
    }

    #[test]
    fn config_collision_names_the_first_obstacle() {
        let w = world(vec![
            ("A", rect(0.0, 0.0, 5.0, 5.0)),
            ("B", rect(0.0, 0.0, 5.0, 5.0)),
        ]);
        assert_eq!(
            config_collision(&w, &RobotShape::Disk(0.5), c(5.2, 2.0)),
            Some(0)
        );
        assert_eq!(config_collision(&w, &rod(), c(5.0, 2.0)), None);
        assert_eq!(
            config_collision(&w, &rod(), Config::new(5.0, 2.0, 3.0)),
            Some(0)
        );
    }

    #[test]
    fn a_long_translation_over_a_big_grid_is_checked_once() {
        let mut rows = vec![".".repeat(512); 512];
        rows[100] = format!("{}#{}", ".".repeat(300), ".".repeat(211));
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        let g = grid(1.0 / 64.0, p(1.0, 1.0), &refs);
        let w = world(vec![("G", g)]);
        // The blocked cell is at x ∈ [1 + 300/64, 1 + 301/64], row 100 from the top.
        let y = 1.0 + (511.0 - 100.0 + 0.5) / 64.0;
        assert!(!ok(&w, &RobotShape::Point, &[c(1.0, y), c(9.0, y)]));
        assert!(ok(
            &w,
            &RobotShape::Point,
            &[c(1.0, y + 1.0 / 64.0), c(9.0, y + 1.0 / 64.0)]
        ));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// A translation is exactly as safe as its finest subdivision.
        #[test]
        fn subdividing_a_translation_changes_nothing(
            x0 in 0.5..9.5f64, y0 in 0.5..9.5f64, x1 in 0.5..9.5f64, y1 in 0.5..9.5f64, theta in 0.0..6.3f64,
        ) {
            let w = world(vec![
                ("B", rect(3.0, 3.0, 4.0, 7.0)),
                ("W", Shape::Segment(p(6.0, 1.0), p(8.0, 5.0))),
                ("D", Shape::Disk { center: p(7.0, 8.0), radius: 1.0 }),
            ]);
            let (a, b) = (Config::new(x0, y0, theta), Config::new(x1, y1, theta));
            let whole = ok(&w, &rod(), &[a, b]);
            let pieces: Vec<Config> = (0..=50)
                .map(|k| {
                    let t = k as f64 / 50.0;
                    Config::new(x0 + t * (x1 - x0), y0 + t * (y1 - y0), theta)
                })
                .collect();
            // Subdividing can only lose precision at contact; away from it
            // the verdicts agree.
            let parts = ok(&w, &rod(), &pieces);
            if whole {
                prop_assert!(parts);
            }
        }

        /// The body overlaps a rect exactly when a vertex is inside it or an
        /// edge crosses it (an independent check of the polygon case).
        #[test]
        fn rotated_box_against_rect(x in 2.0..8.0f64, y in 2.0..8.0f64, theta in 0.0..6.3f64) {
            let w = world(vec![("B", rect(4.0, 4.0, 6.0, 6.0))]);
            let robot = rod();
            let verts = robot.placed_vertices(Config::new(x, y, theta));
            let inside = |q: &Point| q.x > 4.0 && q.x < 6.0 && q.y > 4.0 && q.y < 6.0;
            let corner_inside = [p(4.0, 4.0), p(6.0, 4.0), p(6.0, 6.0), p(4.0, 6.0)].iter().all(|q| {
                (0..4).all(|i| {
                    let (a, b) = (verts[i], verts[(i + 1) % 4]);
                    (b - a).perp(&(q - a)) > 0.0
                })
            });
            let expected = verts.iter().any(inside) || corner_inside || {
                // an edge passing through the rect's interior: sample it
                (0..4).any(|i| (1..100).any(|k| {
                    let t = k as f64 / 100.0;
                    inside(&(verts[i] + (verts[(i + 1) % 4] - verts[i]) * t))
                }))
            };
            let got = config_collision(&w, &robot, Config::new(x, y, theta)).is_some();
            // Sampling can miss a shallow cut of a corner; it never invents one.
            if expected {
                prop_assert!(got);
            }
        }
    }
}
