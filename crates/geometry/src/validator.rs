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
//! A point robot (radius at most `TOUCH_EPS`) may touch segment obstacles,
//! but it may not pass from one side of the set of segments to the other:
//! through a vertex shared by several segments, through a path vertex lying
//! on a segment, or along a run on the segments. Each segment alone cannot
//! tell that, so [`Validator::validate_path`] also checks the whole polyline
//! against all segment obstacles (see [`Validator::check_wall_crossings`]).
//!
//! Signed distances are exact up to rounding: the separating-axis test over
//! the edge normals of both cores (with parry's support maps) gives the
//! penetration depth, and parry's distance query the distance of separated
//! cores. Penetration is never taken from GJK/EPA on rounded shapes, whose
//! results are only accurate to about 1e-9 (and fail on flat shapes).

use nalgebra::Unit;
use parry2d_f64::math::Isometry;
use parry2d_f64::query;
use parry2d_f64::query::Unsupported;
use parry2d_f64::query::gjk::VoronoiSimplex;
use parry2d_f64::query::point::local_point_projection_on_support_map;
use parry2d_f64::shape::{
    Ball, ConvexPolygon as ParryPolygon, Cuboid, Segment, Shape as ParryShape, SupportMap,
};
use parry2d_f64::utils::{ccw_face_normal, point_cloud_support_point};

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

/// The most sub-steps a path is swept in (a translation is one, a rotating
/// motion `⌈(|Δxy| + R·|Δθ|) / tolerance⌉`; for a car, its integrated
/// poses): a path that needs more is reported as too long to validate,
/// never accepted unchecked, so that validating one takes seconds (a
/// rotating motion across a world of 1e9 would need 1e11).
pub const MAX_SUB_STEPS: usize = 4_000_000;

/// The sub-steps of each motion of `robot`'s `path` at `tolerance`, as
/// [`Validator::validate_path`] cuts them.
fn sub_steps_per_motion<'p>(
    robot: &'p RobotShape,
    path: &'p [Config],
    tolerance: f64,
) -> impl Iterator<Item = usize> + 'p {
    let tolerance = usable_tolerance(tolerance);
    path.windows(2)
        .map(move |pair| SubSteps::new(robot, pair[0], pair[1], tolerance).count)
}

/// The number of sub-steps `robot`'s `path` is swept in at `tolerance`
/// (saturating).
pub fn sub_step_count(robot: &RobotShape, path: &[Config], tolerance: f64) -> usize {
    sub_steps_per_motion(robot, path, tolerance).fold(0, usize::saturating_add)
}

/// `Err` when `path` needs more than [`MAX_SUB_STEPS`] sub-steps: the
/// segment where the count passes it.
fn check_sub_steps(
    robot: &RobotShape,
    path: &[Config],
    tolerance: f64,
) -> Result<(), ValidationError> {
    let mut total = 0usize;
    for (segment, count) in sub_steps_per_motion(robot, path, tolerance).enumerate() {
        total = total.saturating_add(count);
        if total > MAX_SUB_STEPS {
            return Err(ValidationError {
                segment,
                at: path[segment],
                obstacle: None,
                reason: format!(
                    "the path needs more than {MAX_SUB_STEPS} sub-steps at tolerance {}: too long to validate",
                    usable_tolerance(tolerance)
                ),
            });
        }
    }
    Ok(())
}

/// `tolerance` when it is finite and positive, else [`DEFAULT_TOLERANCE`].
pub fn usable_tolerance(tolerance: f64) -> f64 {
    if tolerance.is_finite() && tolerance > 0.0 {
        tolerance
    } else {
        DEFAULT_TOLERANCE
    }
}

/// Checks a path against the world (SPEC 3.0).
///
/// # Behaviour
/// The path is interpolated linearly in x and y and along the shorter arc in
/// θ, and cut into sub-steps in which no point of the robot moves more than
/// `tolerance`. For each sub-step the swept region (the convex hull of the
/// robot's bodies at both ends) must not collide with any obstacle (see the
/// module documentation), and the reference point must stay in `bounds`
/// (closed, with a margin of [`TOUCH_EPS`]). A point robot (radius at most
/// `TOUCH_EPS`) must moreover not pass from one side of the segment
/// obstacles to the other anywhere along the path
/// ([`Validator::check_wall_crossings`]), reported as "the point crosses the
/// wall at (x, y)".
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
    /// The segment obstacles of non-zero length, for the point robot's
    /// polyline test.
    walls: Vec<Wall>,
}

/// A segment obstacle `a → b` (`a != b`) and the index of its obstacle.
struct Wall {
    a: Point,
    b: Point,
    obstacle: usize,
    aabb: Aabb,
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
        self.radius <= TOUCH_EPS && !matches!(self.core, Core::Polygon(_) | Core::Hull(_))
    }
}

/// The buffers of a walk over sub-steps, reused from one to the next so
/// that building a polygon robot's swept region allocates nothing: the
/// bodies placed at the sub-step's ends (the end of one sub-step is the
/// start of the next, placed once), the points and hull of the two, and
/// the hull's vertices and normals lent to the region ([`Sweep::recycle`]
/// takes them back).
#[derive(Default)]
struct Sweep {
    /// The bits of the configuration `start` is placed at, if any.
    placed: Option<[u64; 3]>,
    start: Vec<Point>,
    end: Vec<Point>,
    points: Vec<Point>,
    hull: Vec<Point>,
    vertices: Vec<Point>,
    normals: Vec<Unit<Vector>>,
}

/// The finite vertices of the robot's body placed at `c`, sorted by
/// [`polygon::lex_cmp`] (as [`polygon::convex_hull`] filters and sorts
/// them; the order of a body's vertices does not change its hull).
fn place_sorted(robot: &RobotShape, c: Config, out: &mut Vec<Point>) {
    robot.place_into(c, out);
    out.retain(|p| p.x.is_finite() && p.y.is_finite());
    out.sort_unstable_by(polygon::lex_cmp);
}

/// The points of two sorted runs into `out` (cleared first), sorted.
fn merge_sorted(a: &[Point], b: &[Point], out: &mut Vec<Point>) {
    out.clear();
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        if polygon::lex_cmp(&b[j], &a[i]).is_lt() {
            out.push(b[j]);
            j += 1;
        } else {
            out.push(a[i]);
            i += 1;
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
}

fn config_bits(c: Config) -> [u64; 3] {
    [c.x.to_bits(), c.y.to_bits(), c.theta.to_bits()]
}

impl Sweep {
    /// The region swept by the robot from `c0` to `c1`: [`body_region`],
    /// the same core to the bit (a polygon's hull as a [`Core::Hull`]).
    fn region(&mut self, robot: &RobotShape, c0: Config, c1: Config) -> Region {
        if !matches!(robot, RobotShape::Polygon(_)) {
            return body_region(robot, c0, c1);
        }
        if self.placed != Some(config_bits(c0)) {
            place_sorted(robot, c0, &mut self.start);
        }
        if c1 != c0 {
            place_sorted(robot, c1, &mut self.end);
            merge_sorted(&self.start, &self.end, &mut self.points);
            std::mem::swap(&mut self.start, &mut self.end);
            self.placed = Some(config_bits(c1));
        } else {
            self.points.clear();
            self.points.extend_from_slice(&self.start);
            self.placed = Some(config_bits(c0));
        }
        polygon::convex_hull_of_sorted_into(&mut self.points, &mut self.hull);
        merge_close_vertices(&self.hull, &mut self.vertices);
        let core = match self.vertices.len() {
            0..=2 => core_of_few(&self.vertices),
            n => {
                // As `ParryPolygon::from_convex_polyline_unmodified`.
                let v = &self.vertices;
                self.normals.clear();
                let normals = (0..n).map(|i| ccw_face_normal([&v[i], &v[(i + 1) % n]]));
                for normal in normals {
                    match normal {
                        Some(normal) => self.normals.push(normal),
                        None => break,
                    }
                }
                if self.normals.len() == n {
                    Core::Hull(Hull {
                        points: std::mem::take(&mut self.vertices),
                        normals: std::mem::take(&mut self.normals),
                    })
                } else {
                    Core::Segment(Segment::new(v[0], v[n / 2]))
                }
            }
        };
        Region::new(core, 0.0)
    }

    /// Takes back the buffers lent to `region`.
    fn recycle(&mut self, region: Region) {
        if let Core::Hull(hull) = region.core {
            self.vertices = hull.points;
            self.normals = hull.normals;
        }
    }
}

impl<'w> Validator<'w> {
    /// Prepares `world`'s obstacles. Polygons without pieces are decomposed
    /// here.
    pub fn new(world: &'w World) -> Self {
        let obstacles = world.obstacles.iter().map(|o| prepare(&o.shape)).collect();
        let walls = world
            .obstacles
            .iter()
            .enumerate()
            .filter_map(|(obstacle, o)| match o.shape {
                Shape::Segment(a, b) if a != b => Some(Wall {
                    a,
                    b,
                    obstacle,
                    aabb: Aabb::from_corners(a, b),
                }),
                _ => None,
            })
            .collect();
        Validator {
            world,
            obstacles,
            walls,
        }
    }

    /// See [`validate_path`].
    pub fn validate_path(
        &self,
        robot: &RobotShape,
        path: &[Config],
        tolerance: f64,
    ) -> Result<(), ValidationError> {
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
                check_sub_steps(robot, path, tolerance)?;
                self.check_motions(robot, path, tolerance, &mut |region, _| {
                    (self.first_hit(region), 0)
                })?;
                self.check_walls(robot, path)
            }
        }
    }

    /// [`Validator::validate_path`] and [`Validator::clearance`] of one
    /// path in one pass over its sub-steps (each swept hull built once):
    /// the same verdict and the same clearance as the two calls, to the
    /// bit. The pass starts from the distances of a few of the sub-steps
    /// ([`Validator::seed_clearance`]) and leaves out the sub-steps that
    /// can be shown from a neighbour's distance to be farther than the
    /// smallest found ([`Validator::measure_hit_and_skip`]): on the rod's
    /// paths in the apartment, a sixteenth of the instructions of measuring
    /// every sub-step (BENCHMARKS.md).
    pub fn validate_and_measure(
        &self,
        robot: &RobotShape,
        path: &[Config],
        tolerance: f64,
    ) -> (Result<(), ValidationError>, f64) {
        if path.len() < 2 {
            return (
                self.validate_path(robot, path, tolerance),
                self.clearance(robot, path, tolerance),
            );
        }
        if let Err(e) = check_sub_steps(robot, path, tolerance) {
            // Too long to sweep: no verdict and no clearance.
            return (Err(e), f64::NAN);
        }
        let mut best = self.seed_clearance(robot, path, tolerance);
        let motions = self.check_motions(robot, path, tolerance, &mut |region, step| {
            if best > TOUCH_EPS {
                self.measure_hit_and_skip(region, step, &mut best)
            } else {
                (self.first_hit(region), 0)
            }
        });
        match motions {
            // The walk stopped at the failure: the rest is measured apart.
            Err(e) => (Err(e), self.clearance(robot, path, tolerance)),
            Ok(()) => (
                self.check_walls(robot, path),
                if best <= TOUCH_EPS { 0.0 } else { best },
            ),
        }
    }

    /// The smallest distance to the obstacles of every [`SEED_STRIDE`]-th
    /// sub-step of every motion of `path`: some of the sub-steps whose
    /// minimum is the clearance, measured as the walk measures them (the
    /// same regions, the same distances), so that starting the walk's
    /// minimum there changes none of its bits. With a minimum near the
    /// final one from the start, [`Validator::measure_hit_and_skip`] skips
    /// most of the way rather than only past the narrowest place.
    fn seed_clearance(&self, robot: &RobotShape, path: &[Config], tolerance: f64) -> f64 {
        let tolerance = usable_tolerance(tolerance);
        let mut best = f64::INFINITY;
        let mut sweep = Sweep::default();
        for pair in path.windows(2) {
            let steps = SubSteps::new(robot, pair[0], pair[1], tolerance);
            for k in (0..steps.count).step_by(SEED_STRIDE) {
                let region = sweep.region(robot, steps.at(k), steps.at(k + 1));
                self.measure(&region, &mut best);
                sweep.recycle(region);
                if best <= TOUCH_EPS {
                    return best;
                }
            }
        }
        best
    }

    /// The bounds at the start and every motion of a path of two or more
    /// configurations, each sub-step's swept region checked by `hit`
    /// ([`Validator::first_hit`], or a function that finds the same), which
    /// is also given the sub-step's [`SubSteps::step`] and may answer that
    /// the next sub-steps of the motion need no check (see
    /// [`Validator::measure_hit_and_skip`]). Its callers have checked that
    /// the path is not too long to sweep ([`check_sub_steps`]).
    fn check_motions(
        &self,
        robot: &RobotShape,
        path: &[Config],
        tolerance: f64,
        hit: &mut dyn FnMut(&Region, f64) -> Checked,
    ) -> Result<(), ValidationError> {
        let tolerance = usable_tolerance(tolerance);
        self.check_config_in_bounds(0, path[0])?;
        let mut sweep = Sweep::default();
        for (segment, pair) in path.windows(2).enumerate() {
            self.check_motion(robot, segment, pair[0], pair[1], tolerance, &mut sweep, hit)?;
        }
        Ok(())
    }

    /// A point robot's path may not cross a segment obstacle.
    fn check_walls(&self, robot: &RobotShape, path: &[Config]) -> Result<(), ValidationError> {
        if robot.radius() <= TOUCH_EPS && !self.walls.is_empty() {
            self.check_wall_crossings(path)
        } else {
            Ok(())
        }
    }

    /// See [`config_collision`].
    pub fn config_collision(&self, robot: &RobotShape, c: Config) -> Option<usize> {
        let body = body_region(robot, c, c);
        self.first_hit(&body)
    }

    #[allow(clippy::too_many_arguments)]
    fn check_motion(
        &self,
        robot: &RobotShape,
        segment: usize,
        a: Config,
        b: Config,
        tolerance: f64,
        sweep: &mut Sweep,
        hit: &mut dyn FnMut(&Region, f64) -> Checked,
    ) -> Result<(), ValidationError> {
        self.check_config_in_bounds(segment, b)?;
        let steps = SubSteps::new(robot, a, b, tolerance);
        // Bounds are convex: both ends inside means the whole motion is.
        let mut k = 0;
        while k < steps.count {
            let (c0, c1) = (steps.at(k), steps.at(k + 1));
            let region = sweep.region(robot, c0, c1);
            let (first, skip) = hit(&region, steps.step);
            sweep.recycle(region);
            #[cfg(test)]
            CHECKED.set(CHECKED.get() + 1);
            if let Some(i) = first {
                // Name the start if the robot is already in collision there.
                let culprit = if k == 0 && self.config_collision(robot, c0).is_some() {
                    c0
                } else {
                    c1
                };
                return Err(self.obstacle_error(segment, culprit, i));
            }
            k = k.saturating_add(1).saturating_add(skip);
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

    /// The polyline test for point robots: the path may touch the segment
    /// obstacles but not pass from one side of them to the other.
    ///
    /// # Formulation
    /// Points and directions are compared with the tolerance
    /// `δ = TOUCH_EPS` (a point within δ of a segment is on it). The path's
    /// (x, y) polyline, without steps shorter than δ, is cut at its *contact
    /// points*: its vertices, the points where a segment endpoint lies on it
    /// and the points where it crosses a segment; contact points closer than δ
    /// along a path segment merge. At a contact point C the segments through
    /// C give *rays* from C (one for a segment ending at C, two opposite ones
    /// for a segment passing through C; rays in the same direction merge),
    /// which cut the circle of directions around C into *sectors*. The path
    /// arrives at C along a direction (pointing back along the path) and
    /// leaves along another; each lies in a sector, or exactly on a ray
    /// (within an angle of `ALIGN`), where it moves along a segment.
    ///
    /// Walking the contact points in order, the path is *allowed* in a set of
    /// sectors at each: every sector where the path starts, the sector it
    /// arrives from, or (arriving along a ray) the sectors beside that ray
    /// on the sides it kept while moving along the segments. It must leave
    /// into an allowed sector, or along a ray that has an allowed sector on
    /// at least one side, and then keeps those sides (left or right of its
    /// motion) until the next contact point. Anything else passes from one
    /// side of the segments to the other: the path crosses the wall at C.
    /// The path may end anywhere, and the tip of a lone segment (one ray, one
    /// sector) never separates anything.
    pub fn check_wall_crossings(&self, path: &[Config]) -> Result<(), ValidationError> {
        // The polyline without steps of at most δ (turns on the spot,
        // repeated configurations): each kept point with the index of the
        // last configuration merged into it.
        let mut verts: Vec<(Point, usize)> = Vec::with_capacity(path.len());
        for (i, c) in path.iter().enumerate() {
            let p = c.xy();
            match verts.last_mut() {
                Some(last) if (p - last.0).norm() <= WALL_EPS => last.1 = i,
                _ => verts.push((p, i)),
            }
        }
        if verts.len() < 2 {
            return Ok(());
        }
        let segments = verts.len() - 1;
        let dirs: Vec<Vector> = verts
            .windows(2)
            .map(|w| (w[1].0 - w[0].0).normalize())
            .collect();
        // Contact points inside each path segment (distance along it and
        // half-extent of the merged cluster), and the extent of the clusters
        // merged into each vertex.
        let mut vertex_extent = vec![0.0f64; verts.len()];
        let mut inner: Vec<Vec<(f64, f64)>> = vec![Vec::new(); segments];
        let mut params: Vec<f64> = Vec::new();
        for k in 0..segments {
            let (u, v, d) = (verts[k].0, verts[k + 1].0, dirs[k]);
            let length = (v - u).norm();
            let reach = grow(Aabb::from_corners(u, v), 2.0 * WALL_EPS);
            params.clear();
            for w in self.walls.iter().filter(|w| aabbs_meet(&w.aabb, &reach)) {
                for e in [w.a, w.b] {
                    if point_segment_distance(e, u, v) <= WALL_EPS {
                        params.push((e - u).dot(&d).clamp(0.0, length));
                    }
                }
                let (o1, o2) = ((v - u).perp(&(w.a - u)), (v - u).perp(&(w.b - u)));
                let (o3, o4) = ((w.b - w.a).perp(&(u - w.a)), (w.b - w.a).perp(&(v - w.a)));
                if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
                    params.push((length * o3 / (o3 - o4)).clamp(0.0, length));
                }
            }
            params.sort_by(f64::total_cmp);
            let mut i = 0;
            while i < params.len() {
                let (lo, mut hi) = (params[i], params[i]);
                i += 1;
                while i < params.len() && params[i] - hi <= WALL_EPS {
                    hi = params[i];
                    i += 1;
                }
                let (at_start, at_end) = (lo <= WALL_EPS, hi >= length - WALL_EPS);
                if at_start {
                    vertex_extent[k] = vertex_extent[k].max(hi);
                }
                if at_end {
                    vertex_extent[k + 1] = vertex_extent[k + 1].max(length - lo);
                }
                if !at_start && !at_end {
                    inner[k].push(((lo + hi) / 2.0, (hi - lo) / 2.0));
                }
            }
        }
        // Walk the contact points in order. `along`: while the path moves
        // along segments, whether it may be on their left and on their right.
        let mut along: Option<[bool; 2]> = None;
        let mut check = |c: Point,
                         extent: f64,
                         arriving: Option<Vector>,
                         leaving: Option<Vector>,
                         segment: usize,
                         at: Config|
         -> Result<(), ValidationError> {
            let carried = along.take();
            let rays = self.rays_at(c, extent);
            if rays.is_empty() {
                return Ok(());
            }
            let n = rays.len();
            // Sector i lies counter-clockwise of ray i, up to ray i + 1.
            let ccw = |i: usize| i;
            let cw = |i: usize| (i + n - 1) % n;
            let mut allowed = vec![false; n];
            match arriving {
                None => allowed.fill(true),
                Some(d) => match classify(&rays, -d) {
                    Way::Sector(m) => allowed[m] = true,
                    Way::Ray(i) => {
                        // Arriving along ray i: its left is the sector
                        // clockwise of the ray, its right the one
                        // counter-clockwise.
                        let [left, right] = carried.unwrap_or_else(|| {
                            // The previous contact point did not see the
                            // path move along a segment: the exact side.
                            let s = rays[i].dir.perp(&-d);
                            [s <= 0.0, s >= 0.0]
                        });
                        allowed[cw(i)] |= left;
                        allowed[ccw(i)] |= right;
                    }
                },
            }
            let Some(d) = leaving else {
                return Ok(());
            };
            let crossed = match classify(&rays, d) {
                Way::Sector(m) => !allowed[m],
                Way::Ray(i) => {
                    let sides = [allowed[ccw(i)], allowed[cw(i)]];
                    along = Some(sides);
                    sides == [false, false]
                }
            };
            if !crossed {
                return Ok(());
            }
            let wall = rays.iter().map(|r| r.obstacle).min().unwrap_or(0);
            Err(ValidationError {
                segment,
                at,
                obstacle: Some(self.world.obstacles[wall].name.clone()),
                reason: format!("the point crosses the wall at ({}, {})", c.x, c.y),
            })
        };
        for k in 0..verts.len() {
            let (c, index) = verts[k];
            let arriving = k.checked_sub(1).map(|j| dirs[j]);
            let leaving = dirs.get(k).copied();
            let segment = index.min(path.len() - 2);
            check(c, vertex_extent[k], arriving, leaving, segment, path[index])?;
            if k < segments {
                for &(t, extent) in &inner[k] {
                    let c = c + dirs[k] * t;
                    let at = Config::new(c.x, c.y, path[index].theta);
                    check(c, extent, Some(dirs[k]), Some(dirs[k]), segment, at)?;
                }
            }
        }
        Ok(())
    }

    /// The rays of the segment obstacles from the contact point `c` (the
    /// segments within `WALL_EPS + extent` of `c`), sorted by angle, rays in
    /// the same direction merged.
    fn rays_at(&self, c: Point, extent: f64) -> Vec<Ray> {
        let r = WALL_EPS + extent;
        let near = grow(Aabb { min: c, max: c }, r);
        let mut rays: Vec<Ray> = Vec::new();
        for w in self.walls.iter().filter(|w| aabbs_meet(&w.aabb, &near)) {
            if point_segment_distance(c, w.a, w.b) > r {
                continue;
            }
            let (at_a, at_b) = ((w.a - c).norm() <= r, (w.b - c).norm() <= r);
            let u = (w.b - w.a).normalize();
            let mut push = |dir: Vector, end: Point| {
                rays.push(Ray {
                    dir,
                    angle: dir.y.atan2(dir.x),
                    length: (end - c).norm(),
                    obstacle: w.obstacle,
                })
            };
            // A segment both of whose ends are at `c` is a point there.
            if !at_b {
                push(u, w.b);
            }
            if !at_a {
                push(-u, w.a);
            }
        }
        rays.sort_by(|x, y| x.angle.total_cmp(&y.angle));
        let same = |x: &Ray, y: &Ray| {
            let s = x.dir.perp(&y.dir).abs();
            x.dir.dot(&y.dir) > 0.0 && (s <= ALIGN || s * x.length.min(y.length) <= WALL_EPS)
        };
        let mut merged: Vec<Ray> = Vec::with_capacity(rays.len());
        for ray in rays {
            match merged.last_mut() {
                Some(last) if same(last, &ray) => {
                    last.obstacle = last.obstacle.min(ray.obstacle);
                    last.length = last.length.max(ray.length);
                }
                _ => merged.push(ray),
            }
        }
        if merged.len() > 1 && same(&merged[0], &merged[merged.len() - 1]) {
            let last = merged.pop().unwrap();
            merged[0].obstacle = merged[0].obstacle.min(last.obstacle);
        }
        merged
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

    /// The clearance of a path (SPEC 3): the smallest distance between the
    /// robot and any obstacle over the sub-steps of [`Validator::validate_path`]
    /// — the distance of each sub-step's swept hull, which for a
    /// translation is exactly the smallest distance along the motion and for
    /// a rotation is within the sub-step's deviation from the swept arcs
    /// (far less than `tolerance`) of it.
    ///
    /// # Returns
    /// The distance in world units: 0 when the robot touches (within
    /// [`TOUCH_EPS`]) or overlaps an obstacle, +∞ for a world without
    /// obstacles or an empty path. Distances to a disk robot are measured
    /// from its boundary, to segment obstacles from the segment.
    pub fn clearance(&self, robot: &RobotShape, path: &[Config], tolerance: f64) -> f64 {
        if check_sub_steps(robot, path, tolerance).is_err() {
            return f64::NAN; // too long to sweep (see `MAX_SUB_STEPS`)
        }
        let tolerance = usable_tolerance(tolerance);
        let mut best = f64::INFINITY;
        match path {
            [] => return f64::INFINITY,
            [c] => self.measure(&body_region(robot, *c, *c), &mut best),
            _ => {
                for pair in path.windows(2) {
                    let steps = SubSteps::new(robot, pair[0], pair[1], tolerance);
                    for k in 0..steps.count {
                        self.measure(&body_region(robot, steps.at(k), steps.at(k + 1)), &mut best);
                        if best <= TOUCH_EPS {
                            return 0.0;
                        }
                    }
                }
            }
        }
        if best <= TOUCH_EPS { 0.0 } else { best }
    }

    /// Lowers `best` to the distance from `region` to the nearest obstacle
    /// when that is smaller.
    fn measure(&self, region: &Region, best: &mut f64) {
        for o in &self.obstacles {
            if aabb_distance_below(&region.aabb, &o.aabb, *best) {
                *best = best.min(body_distance(region, &o.body, *best));
            }
        }
    }

    /// The distance between the robot's body at `c` and the nearest
    /// obstacle (0 or less when they meet; +∞ without obstacles). The bounds
    /// are not obstacles.
    pub fn body_clearance(&self, robot: &RobotShape, c: Config) -> f64 {
        let region = body_region(robot, c, c);
        let mut best = f64::INFINITY;
        for o in &self.obstacles {
            if aabb_distance(&region.aabb, &o.aabb) < best {
                best = best.min(body_distance(&region, &o.body, best));
            }
        }
        best
    }

    /// The world's bounds.
    pub fn bounds(&self) -> Aabb {
        self.world.bounds
    }

    /// [`Validator::measure`] and [`Validator::first_hit`] in one pass over
    /// the obstacles: the same hit, and when there is none, the same `best`
    /// (after a hit, `best` is left part-measured). An obstacle that is
    /// measured tells whether it collides from the same gaps and distances
    /// ([`core_distance_and_overlap`]); the others are tested as
    /// `first_hit` tests them.
    ///
    /// Also how many of the motion's next sub-steps need no check, given
    /// `step` ([`SubSteps::step`]; 0: none). Every point of the body moves
    /// at most `step` from one sub-step's end to the next, so every point
    /// of the hull swept `j` sub-steps later lies within `j·step` of this
    /// one (it is a convex combination of body points, each within `j·step`
    /// of the same body point here, and so of a point of this hull). If
    /// this region is at least `low` from every obstacle, that one is at
    /// least `low − j·step` away: while that exceeds `best` by a margin, it
    /// can neither lower `best` nor overlap an obstacle, and its check
    /// would change nothing. To know `low` beyond `best`, the obstacles up
    /// to [`SKIP_REACH`] steps beyond it are measured exactly
    /// ([`body_distance`] is exact below its bound, whatever the bound, so
    /// `best` comes out the same); grids only up to `best`, as before (so
    /// next to a grid nothing is skipped).
    fn measure_hit_and_skip(&self, region: &Region, step: f64, best: &mut f64) -> Checked {
        let reach = grow(region.aabb, 2.0 * TOUCH_EPS);
        // Only a polygon's hull: the other cores are not that hull (a thin
        // hull's segment lies inside it), so their distance bounds nothing.
        let skipping = step > 0.0 && matches!(region.core, Core::Hull(_));
        let cap = if skipping {
            *best + SKIP_REACH * step
        } else {
            *best
        };
        // A lower bound of the distance to every obstacle: an obstacle not
        // measured is at least its `limit` away.
        let mut low = f64::INFINITY;
        for (i, o) in self.obstacles.iter().enumerate() {
            let near = aabbs_meet(&o.aabb, &reach);
            let limit = if matches!(o.body, Body::Grid(_)) {
                *best
            } else {
                cap
            };
            let mut known = None;
            if aabb_distance_below(&region.aabb, &o.aabb, limit) {
                let (d, overlap) = body_distance_and_overlap(region, &o.body, limit);
                *best = best.min(d);
                low = low.min(d.min(limit));
                known = overlap;
            } else {
                low = low.min(limit);
            }
            if near && known.unwrap_or_else(|| collides(region, &o.body)) {
                return (Some(i), 0);
            }
        }
        if !skipping {
            return (None, 0);
        }
        // What the rounding of placements, hulls (`merge_close_vertices`)
        // and distances could hide, with room to spare.
        let a = &region.aabb;
        let scale = a
            .min
            .x
            .abs()
            .max(a.min.y.abs())
            .max(a.max.x.abs())
            .max(a.max.y.abs());
        let margin = 1e-9 * (1.0 + scale);
        let skip = ((low - *best - margin) / (step * (1.0 + 1e-9))).floor();
        // Negative or NaN (no obstacle measured yet: ∞ − ∞) is 0; +∞ (no
        // obstacle at all) saturates.
        (None, if skip > 0.0 { skip as usize } else { 0 })
    }

    /// The smallest index of an obstacle that `region` collides with.
    fn first_hit(&self, region: &Region) -> Option<usize> {
        let reach = grow(region.aabb, 2.0 * TOUCH_EPS);
        self.obstacles
            .iter()
            .position(|o| aabbs_meet(&o.aabb, &reach) && collides(region, &o.body))
    }
}

/// What checking one sub-step found: the obstacle it hits, if any, and how
/// many of the motion's next sub-steps need no check.
type Checked = (Option<usize>, usize);

#[cfg(test)]
thread_local! {
    /// Sub-steps checked by a walk on this thread (see the tests).
    static CHECKED: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// Every how many sub-steps [`Validator::seed_clearance`] measures one.
const SEED_STRIDE: usize = 128;

/// How many sub-steps beyond `best` [`Validator::measure_hit_and_skip`]
/// measures obstacles exactly, so as to skip up to that many.
const SKIP_REACH: f64 = 32.0;

/// The sub-steps of a motion from `a` to `b`. A translating convex body
/// sweeps exactly the hull of its two end bodies, so the union of sub-step
/// hulls is that same hull: one sub-step is exact. Rotation needs sub-steps
/// in which no point moves more than `tolerance` (|Δxy| + R·|Δθ| bounds
/// every point's motion).
struct SubSteps {
    a: Config,
    b: Config,
    dtheta: f64,
    count: usize,
    /// How far any point of the body moves from one sub-step's end to the
    /// next at most (the motion bound over `count`; 0 for one sub-step).
    step: f64,
}

impl SubSteps {
    fn new(robot: &RobotShape, a: Config, b: Config, tolerance: f64) -> Self {
        let dtheta = if robot.rotates() {
            angle_diff(a.theta, b.theta)
        } else {
            0.0
        };
        let (count, step) = if dtheta == 0.0 {
            (1, 0.0)
        } else {
            let motion = (b.xy() - a.xy()).norm() + robot.radius() * dtheta.abs();
            let count = ((motion / tolerance).ceil() as usize).max(1);
            (
                count,
                if count > 1 {
                    motion / count as f64
                } else {
                    0.0
                },
            )
        };
        SubSteps {
            a,
            b,
            dtheta,
            count,
            step,
        }
    }

    /// The configuration at the end of sub-step `k` (0: the start).
    fn at(&self, k: usize) -> Config {
        let (a, b) = (self.a, self.b);
        if k == 0 {
            a
        } else if k == self.count {
            b
        } else {
            let t = k as f64 / self.count as f64;
            Config::new(
                a.x * (1.0 - t) + b.x * t,
                a.y * (1.0 - t) + b.y * t,
                a.theta + t * self.dtheta,
            )
        }
    }
}

/// The distance from `region` to `body`, or anything ≥ `best` when that is
/// smaller than the distance (the caller keeps the minimum).
fn body_distance(region: &Region, body: &Body, best: f64) -> f64 {
    match body {
        Body::Solid { pieces, .. } => pieces
            .iter()
            .map(|(core, radius)| {
                core_distance(&region.core, core, best + region.radius + radius)
                    - region.radius
                    - radius
            })
            .fold(f64::INFINITY, f64::min),
        Body::Wall(wall) => core_distance(&region.core, wall, best + region.radius) - region.radius,
        Body::Grid(grid) => grid_distance(region, grid, best),
    }
}

/// [`body_distance`], and whether `region` collides with `body`
/// ([`collides`]) when that follows from the same computations (not for
/// grids).
fn body_distance_and_overlap(region: &Region, body: &Body, best: f64) -> (f64, Option<bool>) {
    match body {
        Body::Solid { pieces, seams } => {
            let mut distance = f64::INFINITY;
            let mut overlap = false;
            for (core, radius) in pieces {
                let (d, o) = core_distance_and_overlap(
                    &region.core,
                    core,
                    best + region.radius + radius,
                    region.radius + radius,
                );
                distance = distance.min(d - region.radius - radius);
                overlap |= o;
            }
            let collides = overlap
                || (region.is_thin()
                    && seams.iter().any(|zone| meets_interior(&region.core, zone)));
            (distance, Some(collides))
        }
        Body::Wall(wall) => {
            let (d, o) =
                core_distance_and_overlap(&region.core, wall, best + region.radius, region.radius);
            (d - region.radius, Some(o))
        }
        Body::Grid(grid) => (grid_distance(region, grid, best), None),
    }
}

/// `(core_distance(a, b, beyond), overlaps(a, b, radius))`, the gap and
/// the distance computed once for both.
fn core_distance_and_overlap(a: &Core, b: &Core, beyond: f64, radius: f64) -> (f64, bool) {
    let gap = largest_gap(a, b);
    let early_distance = match gap {
        Some(g) if g >= beyond => Some(g),
        Some(g) if g < 0.0 => Some(0.0),
        _ => None,
    };
    let early_overlap = match gap {
        Some(g) if g >= radius - TOUCH_EPS => Some(false),
        Some(g) if g < 0.0 => Some(true),
        _ => None,
    };
    let full = || distance(a, b).unwrap_or(0.0).max(gap.unwrap_or(0.0));
    match (early_distance, early_overlap) {
        (Some(d), Some(o)) => (d, o),
        (Some(d), None) => (d, radius - full() > TOUCH_EPS),
        (None, Some(o)) => (full(), o),
        (None, None) => {
            let d = full();
            (d, radius - d > TOUCH_EPS)
        }
    }
}

/// The distance between two cores, or a lower bound of it that is at least
/// `beyond` (when the separating axes already show they are that far apart).
fn core_distance(a: &Core, b: &Core, beyond: f64) -> f64 {
    let gap = largest_gap(a, b);
    match gap {
        Some(g) if g >= beyond => return g,
        Some(g) if g < 0.0 => return 0.0,
        _ => {}
    }
    distance(a, b).unwrap_or(0.0).max(gap.unwrap_or(0.0))
}

/// The distance from `region` to the blocked cells of `grid` (or anything
/// ≥ `best`): cells in a window around the region, widened by doubling
/// until a blocked cell is found inside it (the region's box includes its
/// radius, so cells outside a window of margin m are farther than m).
fn grid_distance(region: &Region, grid: &Grid, best: f64) -> f64 {
    let extent = grid.extent();
    let mut r = grid.cell;
    loop {
        let margin = r.min(best);
        let window = grow(region.aabb, margin);
        let (cols, rows) = grid.cells_overlapping(&window);
        let mut d = f64::INFINITY;
        for row in rows {
            for col in cols.clone() {
                if grid.is_blocked(col, row) {
                    let cell = Core::from_aabb(&grid.cell_box(col, row));
                    d = d
                        .min(core_distance(&region.core, &cell, d + region.radius) - region.radius);
                }
            }
        }
        let covers = window.min.x <= extent.min.x
            && window.min.y <= extent.min.y
            && window.max.x >= extent.max.x
            && window.max.y >= extent.max.y;
        if d <= margin || r >= best || covers {
            return d;
        }
        r *= 2.0;
    }
}

/// The distance between two boxes (0 when they meet).
fn aabb_distance(a: &Aabb, b: &Aabb) -> f64 {
    let dx = (b.min.x - a.max.x).max(a.min.x - b.max.x).max(0.0);
    let dy = (b.min.y - a.max.y).max(a.min.y - b.max.y).max(0.0);
    dx.hypot(dy)
}

/// `aabb_distance(a, b) < bound`, most often without its `hypot`: boxes
/// that meet are at 0, and boxes apart by more than `bound` along an axis
/// are not below it (`hypot` is within an ulp of the true distance, which
/// is at least the gap along either axis; the margin of 1e-9 covers the
/// ulp).
fn aabb_distance_below(a: &Aabb, b: &Aabb, bound: f64) -> bool {
    let dx = (b.min.x - a.max.x).max(a.min.x - b.max.x).max(0.0);
    let dy = (b.min.y - a.max.y).max(a.min.y - b.max.y).max(0.0);
    if dx == 0.0 && dy == 0.0 {
        0.0 < bound
    } else if dx.max(dy) > bound * (1.0 + 1e-9) {
        false
    } else {
        dx.hypot(dy) < bound
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
///
/// An edge is on the outline when its midpoint is within `1e-9 ×` the
/// outline's size of an outline edge (by parry's point projection), found
/// in O(n log n) ([`polygon::proximity::shared_edges`]).
fn seam_zones<'a>(outline: &[Point], pieces: impl Iterator<Item = &'a [Point]>) -> Vec<Core> {
    use polygon::proximity::{VertexIndex, shared_edges};

    let n = outline.len();
    let bounds = aabb_of(outline);
    let scale = bounds.width().max(bounds.height());
    let vertices = VertexIndex::new(outline);
    let seams = shared_edges(outline, &vertices, pieces, 1e-9 * scale, |p, i| {
        let edge = Segment::new(outline[i], outline[(i + 1) % n]);
        parry2d_f64::query::PointQuery::distance_to_point(&edge, &Isometry::identity(), &p, true)
    });
    // How far from its end `a` a band along `a → b` must start: a point at
    // distance u along it and within ε of it is at least
    // u·sin α − ε·|cos α| from an outline edge leaving `a` at angle α.
    let end_margin = |a: Point, b: Point| -> f64 {
        let Some(k) = vertices.of(a) else {
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
    /// A convex polygon as [`Core::Polygon`] would hold it, in buffers
    /// that a [`Sweep`] reuses.
    Hull(Hull),
    Box {
        center: Point,
        half: Cuboid,
    },
}

/// The vertices (counter-clockwise, at least 3) and edge normals of a
/// convex polygon, as `ParryPolygon::from_convex_polyline_unmodified`
/// makes them: it behaves as that polygon to the bit.
struct Hull {
    points: Vec<Point>,
    normals: Vec<Unit<Vector>>,
}

impl SupportMap for Hull {
    fn local_support_point(&self, dir: &Vector) -> Point {
        // As `ParryPolygon`'s.
        point_cloud_support_point(dir, &self.points)
    }
}

/// parry's distance between the cores (`query::distance` of their shapes),
/// a [`Core::Hull`] first taken as the polygon it stands for: the same
/// dispatch and the same arithmetic, without building that polygon.
fn distance(a: &Core, b: &Core) -> Result<f64, Unsupported> {
    let Core::Hull(hull) = a else {
        return a.with_shape(|pa, sa| b.with_shape(|pb, sb| query::distance(pa, sa, pb, sb)));
    };
    if matches!(b, Core::Hull(_)) {
        return a.with_shape(|pa, sa| b.with_shape(|pb, sb| query::distance(pa, sa, pb, sb)));
    }
    // `DefaultQueryDispatcher::distance` for a convex polygon and `b`'s
    // shape (a ball, a cuboid, a segment or a convex polygon): a ball's
    // centre is projected on the polygon, any other shape meets it by GJK.
    b.with_shape(|pb, sb| {
        let pos12 = Isometry::identity().inv_mul(pb);
        if let Some(ball) = sb.as_ball() {
            let center = Point::from(pos12.translation.vector);
            let proj = local_point_projection_on_support_map(
                hull,
                &mut VoronoiSimplex::new(),
                &center,
                true,
            );
            Ok((nalgebra::distance(&proj.point, &center) - ball.radius).max(0.0))
        } else if let Some(sb) = sb.as_support_map() {
            Ok(query::details::distance_support_map_support_map(
                &pos12, hull, sb,
            ))
        } else {
            a.with_shape(|pa, sa| query::distance(pa, sa, pb, sb))
        }
    })
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
            Core::Hull(h) => aabb_of(&h.points),
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
            Core::Hull(h) => h.normals.iter().for_each(|n| f(*n)),
            Core::Box { .. } => {
                for n in [Vector::x_axis(), Vector::y_axis()] {
                    f(n);
                    f(-n);
                }
            }
        }
    }

    /// Calls `f` with each outward edge normal (as [`Core::for_each_normal`])
    /// and the core's support point along it. A polygon's is an end of the
    /// edge, the farther of the two (the first in the polygon's order on a
    /// tie, as parry's scan of every vertex picks it), found in O(1): the
    /// separating-axis test against a polygon of n vertices takes O(n), not
    /// O(n²).
    fn for_each_normal_with_support(&self, mut f: impl FnMut(Unit<Vector>, Point)) {
        match self {
            Core::Polygon(_) | Core::Hull(_) => {
                let (points, normals) = match self {
                    Core::Polygon(p) => (p.points(), p.normals()),
                    Core::Hull(h) => (h.points.as_slice(), h.normals.as_slice()),
                    _ => unreachable!(),
                };
                for (i, n) in normals.iter().enumerate() {
                    let j = (i + 1) % points.len();
                    let (first, second) = (i.min(j), i.max(j));
                    let far = if points[second].coords.dot(n) > points[first].coords.dot(n) {
                        second
                    } else {
                        first
                    };
                    f(*n, points[far]);
                }
            }
            _ => self.for_each_normal(|n| f(n, self.local_support_point(&n))),
        }
    }

    /// Runs `f` on the core as a parry shape and its position.
    fn with_shape<R>(&self, f: impl FnOnce(&Isometry<f64>, &dyn ParryShape) -> R) -> R {
        match self {
            Core::Point(p) => f(&Isometry::translation(p.x, p.y), &Ball::new(0.0)),
            Core::Segment(s) => f(&Isometry::identity(), s),
            Core::Polygon(p) => f(&Isometry::identity(), p),
            Core::Hull(h) => {
                let p = ParryPolygon::from_convex_polyline_unmodified(h.points.clone())
                    .expect("a hull's normals were computed");
                f(&Isometry::identity(), &p)
            }
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
            Core::Hull(h) => h.local_support_point(dir),
            Core::Box { center, half } => center + half.local_support_point(dir).coords,
        }
    }
}

/// The largest gap between `a` and `b` along the edge normals of both (the
/// separating-axis test), or `None` when neither has an edge. For convex
/// polygonal cores a negative gap is exactly minus the penetration depth;
/// a non-negative gap means the cores are disjoint or touch.
fn largest_gap(a: &Core, b: &Core) -> Option<f64> {
    let mut gap: Option<f64> = None;
    let mut keep = |g: f64| gap = Some(gap.map_or(g, |h: f64| h.max(g)));
    // parry's `sat::support_map_support_map_compute_separation(a, b, id, u)`,
    // (b's support toward −u − a's toward u)·u, with the support of the
    // core whose normal `u` is known without a scan.
    a.for_each_normal_with_support(|u, on_a| {
        let on_b = b.local_support_point(&-*u);
        keep((on_b - on_a).dot(&u));
    });
    b.for_each_normal_with_support(|n, on_b| {
        let on_a = a.local_support_point(&-*n);
        keep((on_b - on_a).dot(&-*n));
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
    let distance = distance(a, b);
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
    let hull = polygon::convex_hull(points);
    let mut merged: Vec<Point> = Vec::with_capacity(hull.len());
    merge_close_vertices(&hull, &mut merged);
    match merged.len() {
        0..=2 => core_of_few(&merged),
        n => {
            let ends = (merged[0], merged[n / 2]);
            match ParryPolygon::from_convex_polyline_unmodified(merged) {
                Some(p) => Core::Polygon(p),
                None => Core::Segment(Segment::new(ends.0, ends.1)),
            }
        }
    }
}

/// `hull`'s vertices into `merged` (cleared first), those closer than
/// `1e-12` relative to the coordinates merged ([`convex_core`]).
fn merge_close_vertices(hull: &[Point], merged: &mut Vec<Point>) {
    let scale = hull
        .iter()
        .fold(1.0f64, |s, p| s.max(p.x.abs()).max(p.y.abs()));
    merged.clear();
    for &p in hull {
        if merged.last().is_none_or(|q| (p - q).norm() > 1e-12 * scale) {
            merged.push(p);
        }
    }
    while merged.len() > 1 && (merged[merged.len() - 1] - merged[0]).norm() <= 1e-12 * scale {
        merged.pop();
    }
}

/// The core of a hull of at most two vertices.
fn core_of_few(vertices: &[Point]) -> Core {
    match *vertices {
        [] => Core::Point(Point::origin()),
        [p] => Core::Point(p),
        [p, q] => Core::Segment(Segment::new(p, q)),
        _ => unreachable!("more than two vertices"),
    }
}

// ------------------------------------------------------------------ walls

/// The tolerance of the point robot's polyline test against segment
/// obstacles: points closer than this are one point.
const WALL_EPS: f64 = TOUCH_EPS;

/// Directions closer than this angle (in radians) are one direction: a path
/// moving along a ray of a segment stays within `WALL_EPS` of it for 10
/// units.
const ALIGN: f64 = 1e-10;

/// A ray of a segment obstacle from a contact point.
struct Ray {
    /// Unit direction.
    dir: Vector,
    /// `atan2` of `dir`, in [−π, π].
    angle: f64,
    /// How far the segment goes along the ray.
    length: f64,
    obstacle: usize,
}

/// Where a direction from a contact point lies among the rays there.
#[derive(Debug, PartialEq)]
enum Way {
    /// Strictly inside sector `m` (between rays `m` and `m + 1`).
    Sector(usize),
    /// Along ray `i` (within `ALIGN`).
    Ray(usize),
}

/// Classifies the unit direction `dir` among the non-empty, sorted `rays`.
fn classify(rays: &[Ray], dir: Vector) -> Way {
    let mut best: Option<(usize, f64)> = None;
    for (i, r) in rays.iter().enumerate() {
        let dot = r.dir.dot(&dir);
        if dot > 0.0 && r.dir.perp(&dir).abs() <= ALIGN && best.is_none_or(|(_, b)| dot > b) {
            best = Some((i, dot));
        }
    }
    if let Some((i, _)) = best {
        return Way::Ray(i);
    }
    let phi = dir.y.atan2(dir.x);
    Way::Sector(
        rays.iter()
            .rposition(|r| r.angle < phi)
            .unwrap_or(rays.len() - 1),
    )
}

fn point_segment_distance(x: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let len2 = ab.norm_squared();
    let t = if len2 > 0.0 {
        ((x - a).dot(&ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (x - (a + ab * t)).norm()
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
    use crate::fixtures::{grid, rect};
    use crate::{ConvexPolygon, Obstacle};
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

    fn polygon_shape(v: &[(f64, f64)]) -> Shape {
        let pts: Vec<Point> = v.iter().map(|&(x, y)| p(x, y)).collect();
        let outline = polygon::normalize_simple_polygon(&pts).unwrap();
        let pieces = polygon::convex_decomposition(&outline);
        Shape::Polygon { outline, pieces }
    }

    fn rod() -> RobotShape {
        RobotShape::Polygon(ConvexPolygon {
            vertices: vec![p(0.0, 0.0), p(2.0, 0.0), p(2.0, 0.5), p(0.0, 0.5)],
        })
    }

    fn ok(w: &World, robot: &RobotShape, path: &[Config]) -> bool {
        validate_path(w, robot, path, DEFAULT_TOLERANCE).is_ok()
    }

    fn clearance(w: &World, robot: &RobotShape, path: &[Config]) -> f64 {
        Validator::new(w).clearance(robot, path, DEFAULT_TOLERANCE)
    }

    /// `seam_zones` as it was: every piece edge's midpoint against every
    /// outline edge, every seam against those taken, every end against
    /// every outline vertex. The oracle of the test below.
    fn all_pairs_seam_zones(outline: &[Point], pieces: &[crate::ConvexPolygon]) -> Vec<Core> {
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
        for piece in pieces.iter().map(|p| &p.vertices) {
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

    /// `largest_gap` as it was, with parry's separation along every normal
    /// (a scan of every vertex for each). The oracle of the test below.
    fn largest_gap_by_parry(a: &Core, b: &Core) -> Option<f64> {
        use parry2d_f64::query::sat;
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

    fn zone_points(zones: &[Core]) -> Vec<Vec<Point>> {
        zones
            .iter()
            .map(|z| match z {
                Core::Polygon(p) => p.points().to_vec(),
                _ => Vec::new(),
            })
            .collect()
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(300))]

        /// The gaps of the separating-axis test, with a polygon's support
        /// along its own normals taken from the edge, are parry's.
        #[test]
        fn largest_gap_is_parrys(
            a in proptest::collection::vec((-3.0..3.0f64, -3.0..3.0f64), 1..12),
            b in proptest::collection::vec((-3.0..3.0f64, -3.0..3.0f64), 1..12),
            shift in (-4.0..4.0f64, -4.0..4.0f64),
        ) {
            let a: Vec<Point> = a.iter().map(|&(x, y)| Point::new(x, y)).collect();
            let b: Vec<Point> = b.iter().map(|&(x, y)| Point::new(x + shift.0, y + shift.1)).collect();
            let (a, b) = (convex_core(&a), convex_core(&b));
            let boxed = Core::from_aabb(&aabb_of(&[Point::new(shift.0, shift.1), Point::new(shift.1, 1.0)]));
            for (x, y) in [(&a, &b), (&b, &a), (&a, &boxed), (&boxed, &b)] {
                proptest::prop_assert_eq!(largest_gap(x, y), largest_gap_by_parry(x, y));
            }
        }

        /// The seam bands, found with the outline's vertices hashed and the
        /// midpoints swept, are those of the all-pairs search, in order.
        #[test]
        fn seam_zones_are_those_of_the_all_pairs_search(
            v in proptest::collection::vec((0..6i32, 0..6i32), 4..14),
            scale in proptest::sample::select(vec![1.0, 1e-3, 7.5]),
        ) {
            let input: Vec<Point> = v.iter().map(|&(x, y)| Point::new(x as f64 * scale, y as f64 * scale)).collect();
            if let Ok(outline) = polygon::normalize_simple_polygon(&input) {
                let pieces = polygon::convex_decomposition(&outline);
                let fast = seam_zones(&outline, pieces.iter().map(|p| p.vertices.as_slice()));
                proptest::prop_assert_eq!(zone_points(&fast), zone_points(&all_pairs_seam_zones(&outline, &pieces)));
            }
        }
    }

    #[test]
    fn clearance_is_the_smallest_distance_along_the_path() {
        let disk = RobotShape::Disk(0.5);
        // No obstacle, no path: infinitely clear.
        assert_eq!(
            clearance(&world(vec![]), &disk, &[c(1.0, 1.0), c(9.0, 1.0)]),
            f64::INFINITY
        );
        assert_eq!(
            clearance(&world(vec![("B", rect(4.0, 4.0, 6.0, 6.0))]), &disk, &[]),
            f64::INFINITY
        );
        // A disk passing under a box: 2 below it, minus its radius, in the
        // middle of one straight motion (the ends are farther).
        let w = world(vec![("B", rect(4.0, 3.0, 6.0, 4.0))]);
        assert!((clearance(&w, &disk, &[c(0.5, 1.0), c(9.5, 1.0)]) - 1.5).abs() < 1e-12);
        // A point passing a wall; a single configuration.
        let w = world(vec![("W", Shape::Segment(p(5.0, 2.0), p(5.0, 6.0)))]);
        assert!(
            (clearance(&w, &RobotShape::Point, &[c(1.0, 1.0), c(9.0, 1.0)]) - 1.0).abs() < 1e-12
        );
        assert!((clearance(&w, &RobotShape::Point, &[c(3.0, 4.0)]) - 2.0).abs() < 1e-12);
        // Touching counts as 0.
        let w = world(vec![("B", rect(4.0, 4.0, 6.0, 6.0))]);
        assert_eq!(clearance(&w, &disk, &[c(1.0, 3.5), c(9.0, 3.5)]), 0.0);
        // A grid: the nearest blocked cell, found by widening windows.
        let g = grid(
            1.0,
            p(0.0, 0.0),
            &["#.........", "..........", ".........."],
        );
        let w = world(vec![("G", g)]);
        // The blocked cell is the top row's first: [0, 1] × [2, 3].
        let d = clearance(&w, &RobotShape::Point, &[c(9.5, 0.5), c(9.5, 1.0)]);
        assert!((d - 8.5f64.hypot(1.0)).abs() < 1e-12, "{d}");
    }

    #[test]
    fn clearance_of_a_rotation_is_within_the_tolerance() {
        // The 8×1 rod turning about its first vertex at the origin from 0°
        // to 90° reaches y = √65 at θ = atan 8 (its far corner); a wall at
        // y = 8.5 is √65 short of that.
        let rod = RobotShape::Polygon(ConvexPolygon {
            vertices: vec![p(0.0, 0.0), p(8.0, 0.0), p(8.0, 1.0), p(0.0, 1.0)],
        });
        let mut w = world(vec![("W", Shape::Segment(p(-9.0, 8.5), p(9.0, 8.5)))]);
        w.bounds.min = p(-10.0, -10.0);
        let path = [
            Config::new(0.0, 0.0, 0.0),
            Config::new(0.0, 0.0, std::f64::consts::FRAC_PI_2),
        ];
        // The sub-step hulls cut each arc by its sagitta, far below the
        // tolerance.
        let d = clearance(&w, &rod, &path);
        let truth = 8.5 - 65f64.sqrt();
        assert!((d - truth).abs() <= DEFAULT_TOLERANCE, "{d} vs {truth}");
    }

    /// A rotating motion across a vast world (a fuzzed scenario: bounds
    /// from −1e9) would need ~1e10 sub-steps, hours of sweeping: it is too
    /// long to validate, at once, with no clearance; translations of any
    /// length are one sub-step each, and a short turn is swept as before.
    #[test]
    fn paths_of_more_sub_steps_than_the_cap_are_too_long_to_validate() {
        let mut w = world(vec![("B", rect(4.0, 4.0, 6.0, 6.0))]);
        w.bounds.min = p(-1e9, -10.0);
        let v = Validator::new(&w);
        let far = [Config::new(1.0, 1.0, 0.0), Config::new(-1e8, 1.0, 1.0)];
        assert!(sub_step_count(&rod(), &far, DEFAULT_TOLERANCE) > MAX_SUB_STEPS);
        let e = v
            .validate_path(&rod(), &far, DEFAULT_TOLERANCE)
            .unwrap_err();
        assert!(e.reason.contains("too long to validate"), "{}", e.reason);
        let (verdict, clearance) = v.validate_and_measure(&rod(), &far, DEFAULT_TOLERANCE);
        assert!(verdict.is_err() && clearance.is_nan());
        assert!(v.clearance(&rod(), &far, DEFAULT_TOLERANCE).is_nan());
        // Translating, the same distance is one sub-step.
        let slide = [Config::new(1.0, 1.0, 0.0), Config::new(-1e8, 1.0, 0.0)];
        assert_eq!(sub_step_count(&rod(), &slide, DEFAULT_TOLERANCE), 1);
        assert!(v.validate_path(&rod(), &slide, DEFAULT_TOLERANCE).is_ok());
        // Turning in place by 1 rad: ⌈R / tolerance⌉ sub-steps, swept.
        let turn = [Config::new(-1e3, 1.0, 0.0), Config::new(-1e3, 1.0, 1.0)];
        assert!(sub_step_count(&rod(), &turn, DEFAULT_TOLERANCE) < 1000);
        assert!(v.validate_path(&rod(), &turn, DEFAULT_TOLERANCE).is_ok());
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

    // ------------------------------------------- a point against walls of segments

    fn seg(x0: f64, y0: f64, x1: f64, y1: f64) -> Shape {
        Shape::Segment(p(x0, y0), p(x1, y1))
    }

    /// A world of `obstacles` with bounds far away.
    fn walls(obstacles: Vec<(&str, Shape)>) -> World {
        let mut w = world(obstacles);
        w.bounds = Aabb {
            min: p(-100.0, -100.0),
            max: p(100.0, 100.0),
        };
        w
    }

    fn path(v: &[(f64, f64)]) -> Vec<Config> {
        v.iter().map(|&(x, y)| c(x, y)).collect()
    }

    /// The closed box of four segments around [6, 9]².
    fn boxed() -> World {
        walls(vec![
            ("S", seg(6.0, 6.0, 9.0, 6.0)),
            ("E", seg(9.0, 6.0, 9.0, 9.0)),
            ("N", seg(9.0, 9.0, 6.0, 9.0)),
            ("W", seg(6.0, 9.0, 6.0, 6.0)),
        ])
    }

    fn crossing(w: &World, v: &[(f64, f64)]) -> ValidationError {
        let e = validate_path(w, &RobotShape::Point, &path(v), DEFAULT_TOLERANCE)
            .expect_err("the path crosses a wall");
        assert!(e.reason.contains("crosses"), "{e:?}");
        let name = e.obstacle.as_deref().expect("a wall is named");
        assert!(
            w.obstacles
                .iter()
                .any(|o| o.name == name && matches!(o.shape, Shape::Segment(..))),
            "{e:?}"
        );
        e
    }

    fn accepted(w: &World, v: &[(f64, f64)]) -> bool {
        ok(w, &RobotShape::Point, &path(v))
    }

    #[test]
    fn a_point_cannot_enter_a_box_of_segments_through_a_corner() {
        let w = boxed();
        // (a) Through the shared vertex (6, 6), inside a path segment.
        let e = crossing(&w, &[(5.5, 5.5), (6.5, 6.5)]);
        assert_eq!(e.reason, "the point crosses the wall at (6, 6)");
        assert_eq!(e.segment, 0);
        assert!(matches!(e.obstacle.as_deref(), Some("S" | "W")));
        // With a path vertex at the corner, and at every corner.
        crossing(&w, &[(5.0, 5.0), (6.0, 6.0), (7.0, 7.0)]);
        crossing(&w, &[(10.0, 10.0), (9.0, 9.0), (8.5, 8.0)]);
        crossing(&w, &[(10.0, 5.0), (8.0, 7.0)]);
        crossing(&w, &[(5.0, 10.0), (6.0, 9.0), (6.5, 8.0)]);
        // And out again.
        crossing(&w, &[(7.0, 7.0), (6.0, 6.0), (5.0, 5.0)]);
        // Through a corner within TOUCH_EPS (a proper crossing of depth
        // 1e-10 of the western segment, just above the corner).
        crossing(&w, &[(5.5, 5.5), (6.5, 6.5 + 2e-10)]);
        // The boxed goal of scenarios/features/unreachable.scen.
        crossing(&w, &[(1.0, 1.0), (6.0, 6.0), (7.5, 7.5)]);
    }

    #[test]
    fn a_point_cannot_cross_a_wall_at_a_path_vertex_on_it() {
        // (b)
        let w = walls(vec![("W", seg(0.0, 1.0, 2.0, 1.0))]);
        let e = crossing(&w, &[(0.5, 0.5), (0.5, 1.0), (0.5, 1.5)]);
        assert_eq!(e.obstacle.as_deref(), Some("W"));
        assert_eq!(e.reason, "the point crosses the wall at (0.5, 1)");
        assert_eq!((e.segment, e.at), (1, c(0.5, 1.0)));
        crossing(&w, &[(0.5, 0.5), (1.0, 1.0), (1.5, 1.5)]);
        crossing(&w, &[(0.5, 1.5), (1.0, 1.0), (1.9, 0.1)]);
        // Repeated configurations and turns on the spot change nothing.
        crossing(&w, &[(0.5, 0.5), (0.5, 1.0), (0.5, 1.0), (0.5, 1.5)]);
        let turning = [
            Config::new(0.5, 0.5, 0.0),
            Config::new(0.5, 1.0, 0.0),
            Config::new(0.5, 1.0, 2.0),
            Config::new(0.5, 1.5, 2.0),
        ];
        assert!(!ok(&w, &RobotShape::Point, &turning));
        // A disk robot of radius up to TOUCH_EPS is a point.
        assert!(!ok(
            &w,
            &RobotShape::Disk(0.5e-9),
            &path(&[(0.5, 0.5), (0.5, 1.0), (0.5, 1.5)])
        ));
    }

    #[test]
    fn a_point_cannot_cross_a_wall_by_running_along_it() {
        // (c) Arrives from below, runs along the wall, leaves above.
        let w = walls(vec![("W", seg(0.0, 1.0, 2.0, 1.0))]);
        crossing(&w, &[(0.5, 0.5), (0.5, 1.0), (1.5, 1.0), (1.5, 1.5)]);
        crossing(&w, &[(0.5, 0.5), (1.0, 1.0), (1.5, 1.0), (1.0, 1.5)]);
        // Arriving obliquely through the wall's end and leaving above.
        crossing(&w, &[(-1.0, 0.0), (0.5, 1.0), (1.5, 1.0), (1.5, 1.5)]);
        // Back and forth along it before leaving on the other side.
        crossing(
            &w,
            &[(0.5, 0.5), (0.5, 1.0), (1.5, 1.0), (1.0, 1.0), (1.0, 1.5)],
        );
        // A run along the whole wall, past both ends, is around it.
        assert!(accepted(
            &w,
            &[(-1.0, 0.5), (-1.0, 1.0), (3.0, 1.0), (3.0, 1.5)]
        ));
        assert!(accepted(
            &w,
            &[(0.5, 0.5), (0.5, 1.0), (3.0, 1.0), (3.0, 1.5)]
        ));
        // Two collinear overlapping walls are one wall.
        let w = walls(vec![
            ("A", seg(0.0, 1.0, 2.0, 1.0)),
            ("B", seg(1.0, 1.0, 3.0, 1.0)),
        ]);
        crossing(&w, &[(0.5, 0.5), (0.5, 1.0), (2.5, 1.0), (2.5, 1.5)]);
        assert!(accepted(
            &w,
            &[(0.5, 0.5), (0.5, 1.0), (2.5, 1.0), (2.5, 0.5)]
        ));
        assert!(accepted(
            &w,
            &[(0.5, 0.5), (0.5, 1.0), (4.0, 1.0), (4.0, 1.5)]
        ));
    }

    #[test]
    fn a_point_cannot_cross_a_chain_at_its_vertices() {
        // (d) A run along one segment continuing along the next one.
        let w = walls(vec![
            ("A", seg(0.0, 1.0, 2.0, 1.0)),
            ("B", seg(2.0, 1.0, 4.0, 1.0)),
        ]);
        crossing(&w, &[(0.5, 0.5), (0.5, 1.0), (3.0, 1.0), (3.0, 1.5)]);
        crossing(&w, &[(0.5, 0.5), (2.0, 1.0), (3.0, 1.5)]);
        crossing(&w, &[(1.0, 0.5), (1.0, 1.0), (2.0, 1.0), (2.0, 1.5)]);
        assert!(accepted(
            &w,
            &[(0.5, 0.5), (0.5, 1.0), (3.0, 1.0), (3.0, 0.5)]
        ));
        // An L: below/right of it is one side, the corner inside the other.
        let w = walls(vec![
            ("A", seg(0.0, 0.0, 4.0, 0.0)),
            ("B", seg(4.0, 0.0, 4.0, 4.0)),
        ]);
        assert!(accepted(
            &w,
            &[(1.0, -1.0), (1.0, 0.0), (4.0, 0.0), (4.0, 2.0), (5.0, 2.0)]
        ));
        crossing(
            &w,
            &[(1.0, -1.0), (1.0, 0.0), (4.0, 0.0), (4.0, 2.0), (3.0, 2.0)],
        );
        crossing(
            &w,
            &[(1.0, 1.0), (1.0, 0.0), (4.0, 0.0), (4.0, 2.0), (5.0, 2.0)],
        );
        crossing(&w, &[(5.0, -1.0), (3.0, 1.0)]);
        assert!(accepted(&w, &[(5.0, 1.0), (4.0, 0.0), (5.0, -1.0)]));
        // Three segments meeting at (5, 5): rays at 0°, 90° and 225°.
        let w = walls(vec![
            ("A", seg(5.0, 5.0, 8.0, 5.0)),
            ("B", seg(5.0, 5.0, 5.0, 8.0)),
            ("C", seg(2.0, 2.0, 5.0, 5.0)),
        ]);
        crossing(&w, &[(6.0, 4.0), (4.0, 6.0)]);
        crossing(&w, &[(6.0, 4.0), (5.0, 5.0), (6.0, 6.0)]);
        crossing(&w, &[(4.0, 6.0), (5.0, 5.0), (4.0, 3.0)]);
        assert!(accepted(&w, &[(6.0, 4.0), (5.0, 5.0), (5.5, 3.0)]));
        assert!(accepted(&w, &[(6.0, 6.0), (5.0, 5.0), (5.5, 7.0)]));
        // Along C, through the vertex and along A, staying below.
        assert!(accepted(
            &w,
            &[(3.0, 2.0), (3.0, 3.0), (5.0, 5.0), (7.0, 5.0), (7.0, 4.0)]
        ));
        crossing(
            &w,
            &[(3.0, 2.0), (3.0, 3.0), (5.0, 5.0), (7.0, 5.0), (7.0, 6.0)],
        );
        // A T: running along the bar hits the stem on one side only.
        let w = walls(vec![
            ("bar", seg(0.0, 5.0, 10.0, 5.0)),
            ("stem", seg(5.0, 5.0, 5.0, 8.0)),
        ]);
        let e = crossing(&w, &[(1.0, 6.0), (1.0, 5.0), (9.0, 5.0), (9.0, 6.0)]);
        assert_eq!(e.reason, "the point crosses the wall at (5, 5)");
        assert!(accepted(
            &w,
            &[(1.0, 4.0), (1.0, 5.0), (9.0, 5.0), (9.0, 4.0)]
        ));
        // Up the stem's left side and down its right side: around its tip.
        assert!(accepted(
            &w,
            &[
                (4.0, 6.0),
                (5.0, 6.0),
                (5.0, 8.0),
                (5.0, 9.0),
                (5.0, 6.0),
                (6.0, 6.0)
            ]
        ));
        crossing(&w, &[(4.0, 6.0), (5.0, 6.0), (6.0, 6.0)]);
        // An X: two segments crossing in their middles.
        let w = walls(vec![
            ("a", seg(0.0, 0.0, 4.0, 4.0)),
            ("b", seg(0.0, 4.0, 4.0, 0.0)),
        ]);
        crossing(&w, &[(1.0, 2.0), (2.0, 2.0), (3.0, 2.0)]);
        crossing(&w, &[(1.0, 2.0), (3.0, 2.0)]);
        assert!(accepted(&w, &[(1.0, 2.0), (2.0, 2.0), (1.0, 2.5)]));
    }

    #[test]
    fn a_point_may_touch_walls_and_go_back() {
        let w = walls(vec![("W", seg(0.0, 1.0, 2.0, 1.0))]);
        // Touching a wall and going back to the same side.
        assert!(accepted(&w, &[(0.5, 0.5), (0.5, 1.0), (1.5, 0.5)]));
        assert!(accepted(&w, &[(0.5, 0.5), (0.5, 1.0), (0.5, 0.5)]));
        // Running along it and leaving on the side it came from.
        assert!(accepted(
            &w,
            &[(0.5, 0.5), (0.5, 1.0), (1.5, 1.0), (1.5, 0.5)]
        ));
        // Starting or ending on it, on either side.
        assert!(accepted(&w, &[(0.5, 1.0), (0.5, 1.5)]));
        assert!(accepted(&w, &[(0.5, 1.0), (1.5, 1.0), (0.5, 0.5)]));
        assert!(accepted(&w, &[(0.5, 0.5), (0.5, 1.0)]));
        assert!(accepted(&w, &[(0.5, 0.5), (0.5, 1.0), (1.5, 1.0)]));
        // Through the free ends (tips) of an open chain.
        let w = walls(vec![
            ("A", seg(0.0, 1.0, 2.0, 1.0)),
            ("B", seg(2.0, 1.0, 2.0, 3.0)),
        ]);
        assert!(accepted(&w, &[(0.0, 0.0), (0.0, 2.0)]));
        assert!(accepted(&w, &[(-0.5, 0.5), (0.0, 1.0), (0.5, 1.5)]));
        assert!(accepted(&w, &[(1.0, 3.5), (2.0, 3.0), (3.0, 2.5)]));
        assert!(accepted(&w, &[(1.0, 3.5), (3.0, 2.5)]));
        // Through a chain vertex, staying outside the box.
        let w = boxed();
        assert!(accepted(&w, &[(5.0, 6.5), (6.0, 6.0), (6.5, 5.0)]));
        assert!(accepted(&w, &[(5.0, 7.0), (7.0, 5.0)]));
        assert!(accepted(&w, &[(8.0, 5.0), (9.0, 6.0), (10.0, 7.0)]));
        // Roadmap-like: along the outside from one vertex to the next, and
        // all the way round.
        assert!(accepted(
            &w,
            &[(5.0, 5.0), (6.0, 6.0), (9.0, 6.0), (10.0, 5.0)]
        ));
        assert!(accepted(
            &w,
            &[
                (5.0, 5.0),
                (6.0, 6.0),
                (9.0, 6.0),
                (9.0, 9.0),
                (6.0, 9.0),
                (5.0, 10.0)
            ]
        ));
        assert!(accepted(
            &w,
            &[
                (5.0, 5.0),
                (6.0, 6.0),
                (9.0, 6.0),
                (9.0, 9.0),
                (6.0, 9.0),
                (6.0, 6.0)
            ]
        ));
        // Inside, along the walls, and out nowhere.
        assert!(accepted(
            &w,
            &[(7.0, 7.0), (6.0, 6.0), (9.0, 6.0), (8.0, 8.0)]
        ));
        crossing(&w, &[(7.0, 7.0), (6.0, 6.0), (9.0, 6.0), (10.0, 7.0)]);
        // Starting on the wall, into the box; ending on it from outside.
        assert!(accepted(&w, &[(6.0, 7.0), (7.0, 7.0)]));
        assert!(accepted(&w, &[(5.0, 7.0), (6.0, 7.0)]));
        assert!(accepted(&w, &[(6.0, 6.0), (7.0, 7.0)]));
        // A point never collides with a wall, even sitting on a corner.
        assert_eq!(config_collision(&w, &RobotShape::Point, c(6.0, 6.0)), None);
    }

    #[test]
    fn walls_with_rounded_coordinates() {
        // A box turned by 0.3 rad: no coordinate is exact, and a point
        // interpolated on an edge is only within rounding of it.
        let (s, co) = 0.3f64.sin_cos();
        let at = |x: f64, y: f64| p(5.0 + co * x - s * y, 5.0 + s * x + co * y);
        let v = [at(-1.5, -1.5), at(1.5, -1.5), at(1.5, 1.5), at(-1.5, 1.5)];
        let names = ["a", "b", "c", "d"];
        let w = walls(
            (0..4)
                .map(|i| (names[i], Shape::Segment(v[i], v[(i + 1) % 4])))
                .collect(),
        );
        let xy = |q: Point| (q.x, q.y);
        let (out0, out1) = (at(-2.5, -2.5), at(2.5, -2.5));
        let (in0, in1) = (at(-1.0, -1.0), at(1.0, -1.0));
        // Roadmap-like: along the outside of an edge, vertex to vertex.
        assert!(accepted(&w, &[xy(out0), xy(v[0]), xy(v[1]), xy(out1)]));
        crossing(&w, &[xy(out0), xy(v[0]), xy(v[1]), xy(in1)]);
        crossing(&w, &[xy(out0), xy(v[0]), xy(in0)]);
        crossing(&w, &[xy(out0), xy(in0)]);
        // Onto an edge at an interpolated point and back, or across.
        for k in 1..10 {
            let t = k as f64 / 10.0;
            let e = v[0] + (v[1] - v[0]) * t;
            let (below, above) = (at(-1.5 + 3.0 * t, -2.0), at(-1.5 + 3.0 * t, -1.0));
            assert!(accepted(&w, &[xy(below), xy(e), xy(out1)]), "{t}");
            assert!(accepted(&w, &[xy(out0), xy(v[0]), xy(e), xy(below)]), "{t}");
            crossing(&w, &[xy(below), xy(e), xy(above)]);
            crossing(&w, &[xy(out0), xy(v[0]), xy(e), xy(above)]);
            // Inside, along the edge from the vertex, and back inside.
            assert!(accepted(&w, &[xy(in0), xy(v[0]), xy(e), xy(above)]), "{t}");
        }
        // Starting inside, out through a vertex.
        crossing(&w, &[xy(at(0.0, 0.0)), xy(v[2]), xy(at(2.5, 2.5))]);
    }

    #[test]
    fn disks_and_polygons_are_not_affected_by_the_point_rule() {
        // A disk crossing the corner overlaps the walls; one passing by it
        // touches them and is fine, as before.
        let w = boxed();
        let disk = RobotShape::Disk(0.5);
        assert!(!ok(&w, &disk, &path(&[(5.0, 5.0), (7.0, 7.0)])));
        assert!(ok(&w, &disk, &path(&[(5.5, 5.0), (5.5, 10.0)])));
        assert!(ok(&w, &disk, &path(&[(5.5, 5.5), (9.5, 5.5), (9.5, 6.0)])));
    }

    /// Which side of the convex counter-clockwise polygon `v` the point `x`
    /// is on: 1 strictly inside, -1 strictly outside, 0 on the boundary
    /// (exact for the small dyadic coordinates used here).
    fn side_of(v: &[Point], x: Point) -> i32 {
        let n = v.len();
        let s: Vec<f64> = (0..n)
            .map(|i| (v[(i + 1) % n] - v[i]).perp(&(x - v[i])))
            .collect();
        if s.iter().all(|&s| s > 0.0) {
            1
        } else if s.iter().any(|&s| s < 0.0) {
            -1
        } else {
            0
        }
    }

    /// Whether the segment `ab` meets the open interior of the convex
    /// counter-clockwise polygon `v`: the open interval of parameters where
    /// every edge function is positive meets [0, 1].
    fn enters(v: &[Point], a: Point, b: Point) -> bool {
        let n = v.len();
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for i in 0..n {
            let e = v[(i + 1) % n] - v[i];
            let (f0, f1) = (e.perp(&(a - v[i])), e.perp(&(b - v[i])));
            let slope = f1 - f0;
            if slope == 0.0 {
                if f0 <= 0.0 {
                    return false;
                }
            } else if slope > 0.0 {
                lo = lo.max(-f0 / slope);
            } else {
                hi = hi.min(-f0 / slope);
            }
        }
        // The coordinates are multiples of 1/2 on a small grid: a real
        // passage through the interior is far longer than 1e-9.
        hi - lo > 1e-9 && lo < 1.0 - 1e-9 && hi > 1e-9
    }

    /// A closed convex chain of segment obstacles through integer points
    /// (some edges split at an inner lattice point), and its polygon.
    fn random_chain() -> impl Strategy<Value = (World, Vec<Point>)> {
        (
            prop::collection::vec((1..10i32, 1..10i32), 3..7),
            prop::collection::vec(any::<bool>(), 8),
        )
            .prop_filter_map("flat", |(pts, split)| {
                let pts: Vec<Point> = pts.iter().map(|&(x, y)| p(x as f64, y as f64)).collect();
                let hull = polygon::convex_hull(&pts);
                if hull.len() < 3 {
                    return None;
                }
                let gcd = |mut a: i64, mut b: i64| {
                    while b != 0 {
                        (a, b) = (b, a % b);
                    }
                    a.abs()
                };
                let mut segments = Vec::new();
                for i in 0..hull.len() {
                    let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
                    let g = gcd((b.x - a.x) as i64, (b.y - a.y) as i64);
                    if split[i % 8] && g >= 2 {
                        let m = a + (b - a) * ((g / 2) as f64 / g as f64);
                        segments.push(Shape::Segment(a, m));
                        segments.push(Shape::Segment(m, b));
                    } else {
                        segments.push(Shape::Segment(a, b));
                    }
                }
                let mut w = world(
                    segments
                        .into_iter()
                        .enumerate()
                        .map(|(i, s)| {
                            (
                                [
                                    "s0", "s1", "s2", "s3", "s4", "s5", "s6", "s7", "s8", "s9",
                                    "s10", "s11",
                                ][i],
                                s,
                            )
                        })
                        .collect(),
                );
                w.bounds = Aabb {
                    min: p(-100.0, -100.0),
                    max: p(100.0, 100.0),
                };
                Some((w, hull))
            })
    }

    /// Path vertices: lattice points of step 1/2 over [0, 10]², the chain's
    /// vertices, and lattice points on its edges.
    fn chain_path(hull: &[Point], picks: &[(u8, i32, i32, usize)]) -> Vec<Point> {
        picks
            .iter()
            .map(|&(kind, x, y, i)| match kind {
                0 | 1 => p(x as f64 * 0.5, y as f64 * 0.5),
                2 => hull[i % hull.len()],
                _ => {
                    let (a, b) = (hull[i % hull.len()], hull[(i + 1) % hull.len()]);
                    // The point of the edge's line nearest a lattice point,
                    // if it is on the lattice and on the edge.
                    let x = p(x as f64 * 0.5, y as f64 * 0.5);
                    let t = ((x - a).dot(&(b - a)) / (b - a).norm_squared()).clamp(0.0, 1.0);
                    let q = a + (b - a) * t;
                    let snapped = p((q.x * 2.0).round() / 2.0, (q.y * 2.0).round() / 2.0);
                    if (b - a).perp(&(snapped - a)) == 0.0 {
                        snapped
                    } else {
                        a
                    }
                }
            })
            .collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// A point starting outside a closed chain of segments can never
        /// get in, and one that stays out of its interior is never refused,
        /// whatever vertices, edges and runs along the chain it touches.
        #[test]
        fn a_point_stays_on_its_side_of_a_closed_chain(
            (w, hull) in random_chain(),
            picks in prop::collection::vec((0..4u8, 0..21i32, 0..21i32, 0..12usize), 2..7),
        ) {
            let pts = chain_path(&hull, &picks);
            let configs: Vec<Config> = pts.iter().map(|q| c(q.x, q.y)).collect();
            let got = validate_path(&w, &RobotShape::Point, &configs, DEFAULT_TOLERANCE);
            let gets_in = pts.windows(2).any(|s| enters(&hull, s[0], s[1]));
            let start = side_of(&hull, pts[0]);
            if start == -1 && gets_in {
                prop_assert!(got.is_err(), "{:?} enters {:?}", pts, hull);
            }
            if start != 1 && !gets_in {
                prop_assert!(got.is_ok(), "{:?} stays out of {:?}: {:?}", pts, hull, got);
            }
            // Inside it is the same: a point that starts inside stays inside.
            let leaves = pts.iter().any(|&q| side_of(&hull, q) == -1);
            if start == 1 && leaves {
                prop_assert!(got.is_err(), "{:?} leaves {:?}", pts, hull);
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]

        /// The one-pass walk gives the verdict of `validate_path` and the
        /// clearance of `clearance`, to the bit, for every robot kind, free
        /// and colliding paths, walls crossed or not.
        #[test]
        fn validating_and_measuring_in_one_pass_changes_nothing(
            kind in 0..3usize,
            pts in prop::collection::vec((0.2..9.8f64, 0.2..9.8f64, -7.0..7.0f64), 1..6),
        ) {
            let w = world(vec![
                ("B", rect(3.0, 3.0, 4.0, 7.0)),
                ("W", Shape::Segment(p(6.0, 1.0), p(8.0, 5.0))),
                ("D", Shape::Disk { center: p(7.0, 8.0), radius: 1.0 }),
                ("P", polygon_shape(&[(1.0, 8.0), (2.5, 8.5), (2.0, 9.5), (1.2, 9.2)])),
            ]);
            let robot = match kind {
                0 => RobotShape::Point,
                1 => RobotShape::Disk(0.3),
                _ => rod(),
            };
            let path: Vec<Config> = pts.iter().map(|&(x, y, t)| Config::new(x, y, t)).collect();
            let v = Validator::new(&w);
            let (verdict, measured) = v.validate_and_measure(&robot, &path, DEFAULT_TOLERANCE);
            let apart = v.validate_path(&robot, &path, DEFAULT_TOLERANCE);
            prop_assert_eq!(verdict.as_ref().err().map(|e| (&e.reason, e.segment)), apart.as_ref().err().map(|e| (&e.reason, e.segment)));
            prop_assert_eq!(measured.to_bits(), clearance(&w, &robot, &path).to_bits());
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]

        /// The same on turning paths of the rod among small obstacles, most
        /// of them free, where the one-pass walk skips sub-steps (far from
        /// polygons and disks; next to a grid it does not).
        #[test]
        fn skipping_sub_steps_changes_nothing(
            grid in any::<bool>(),
            pts in prop::collection::vec((0.5..9.5f64, 0.5..9.5f64, -7.0..7.0f64), 2..6),
        ) {
            let mut obstacles = vec![
                ("B", rect(4.6, 4.6, 5.0, 5.4)),
                ("D", Shape::Disk { center: p(2.0, 8.0), radius: 0.3 }),
                ("P", polygon_shape(&[(8.0, 1.5), (8.6, 1.8), (8.2, 2.4)])),
            ];
            if grid {
                obstacles.push(("G", super::super::fixtures::grid(0.5, p(7.0, 7.0), &["....", ".#..", "....", "...."])));
            }
            let w = world(obstacles);
            let robot = rod();
            let path: Vec<Config> = pts.iter().map(|&(x, y, t)| Config::new(x, y, t)).collect();
            let v = Validator::new(&w);
            let (verdict, measured) = v.validate_and_measure(&robot, &path, DEFAULT_TOLERANCE);
            let apart = v.validate_path(&robot, &path, DEFAULT_TOLERANCE);
            prop_assert_eq!(verdict.as_ref().err().map(|e| (&e.reason, e.segment)), apart.as_ref().err().map(|e| (&e.reason, e.segment)));
            prop_assert_eq!(measured.to_bits(), clearance(&w, &robot, &path).to_bits());
        }
    }

    /// Far from every obstacle, the one-pass walk checks a few of a turn's
    /// sub-steps and still finds the clearance of all of them.
    #[test]
    fn a_turn_in_the_open_checks_few_sub_steps() {
        let w = world(vec![("B", rect(9.0, 9.0, 9.5, 9.5))]);
        let robot = rod();
        let path = [Config::new(4.0, 4.0, 0.0), Config::new(4.5, 4.0, 3.0)];
        let steps = SubSteps::new(&robot, path[0], path[1], DEFAULT_TOLERANCE).count;
        let v = Validator::new(&w);
        CHECKED.set(0);
        let (verdict, measured) = v.validate_and_measure(&robot, &path, DEFAULT_TOLERANCE);
        let checked = CHECKED.get();
        assert!(verdict.is_ok());
        assert_eq!(measured.to_bits(), clearance(&w, &robot, &path).to_bits());
        assert!(steps > 500, "{steps} sub-steps");
        assert!(
            checked * 4 < steps,
            "{checked} of {steps} sub-steps checked"
        );
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
