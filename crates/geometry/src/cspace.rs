//! Configuration-space layers of a rotating convex polygon robot
//! (SPEC 3.1, SEEDS.md §A).
//!
//! A layer holds, for one orientation θ, the C-obstacle
//! `B ⊕ (−A(θ))` of every convex obstacle piece `B` ([`super::minkowski`]):
//! * polygon obstacles: one per convex piece of their decomposition;
//! * rectangles: the rectangle as a 4-gon;
//! * segments: the 2-point "polygon" (the sum is a polygon since the robot
//!   has area);
//! * disks: the circumscribed [`DISK_SIDES`]-gon — a conservative
//!   approximation: the approximate C-obstacle contains the true one and
//!   exceeds it by at most `ρ·(1/cos(π/k) − 1)` (0.48 % of the radius for
//!   k = 32);
//! * grids: the blocked cells, merged first into rectangles (runs of blocked
//!   cells per row, then runs with the same columns in consecutive rows),
//!   which is exact: the union is the same set, and for a robot with area
//!   "overlaps the interior of the union" is "overlaps the interior of some
//!   cell".
//!
//! # Interior queries
//! A configuration `(x, y, θ)` is blocked when `(x, y)` lies in some
//! C-obstacle of the layer farther than [`TOUCH_EPS`] from its boundary:
//! the distance to the boundary is the penetration depth of the robot into
//! the piece, so this is the validator's rule ([`super::validator`]: the
//! robot may touch, not overlap deeper than `TOUCH_EPS`), piece by piece.
//! (Merged grid rectangles count a penetration deeper than `TOUCH_EPS` into
//! the rectangle, where the validator counts one into a single cell. Since
//! the depth into a union is at least the depth into each part, a layer
//! never frees a configuration that the validator blocks; it blocks more
//! only where the robot touches the grid within a few `TOUCH_EPS`/sin α
//! with a vertex of angle 2α sitting on a seam between two cells — e.g. at
//! depth 3e-9 into the seam, which each cell alone sees at less than 1e-9.)
//!
//! Each layer indexes its C-obstacles in a uniform bucket grid over their
//! bounding boxes. A bucket knows the C-obstacles whose `TOUCH_EPS`-deep
//! interior may meet it, and whether one of them covers it entirely, so most
//! queries are answered from the bucket alone.

use rayon::prelude::*;

use super::minkowski::{DISK_SIDES, c_obstacle_points, disk_polygon};
use super::{Aabb, ConvexPolygon, Grid, Point, Shape, TOUCH_EPS, World, polygon};

/// A convex obstacle piece: a convex polygon (counter-clockwise), a segment
/// (2 points) or a point (1 point).
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// Index of the obstacle in `world.obstacles`.
    pub obstacle: usize,
    pub points: Vec<Point>,
}

/// The convex pieces of a world's obstacles, prepared once for building
/// many layers.
#[derive(Clone, Debug, PartialEq)]
pub struct ObstaclePieces {
    pub pieces: Vec<Piece>,
}

impl ObstaclePieces {
    /// The pieces of `world`, disks as circumscribed [`DISK_SIDES`]-gons.
    pub fn new(world: &World) -> Self {
        Self::with_disk_sides(world, DISK_SIDES)
    }

    /// The pieces of `world`, disks as circumscribed `disk_sides`-gons
    /// (at least 3).
    ///
    /// Polygons give their convex pieces (decomposed here when the analyzer
    /// left `pieces` empty), rectangles their 4 corners (a flat one acts as
    /// its segment),
    /// segments their 2 ends, disks the polygon of
    /// [`super::minkowski::disk_polygon`] (the centre for radius 0), grids
    /// the rectangles of [`grid_rectangles`].
    pub fn with_disk_sides(world: &World, disk_sides: usize) -> Self {
        let mut pieces = Vec::new();
        for (obstacle, o) in world.obstacles.iter().enumerate() {
            shape_pieces(&o.shape, disk_sides, |points| {
                pieces.push(Piece { obstacle, points })
            });
        }
        ObstaclePieces { pieces }
    }

    /// The layer of orientation `theta` for the convex robot `robot`.
    pub fn layer(&self, robot: &ConvexPolygon, theta: f64) -> CLayer {
        let mut c_obstacles = Vec::with_capacity(self.pieces.len());
        let mut sources = Vec::with_capacity(self.pieces.len());
        for piece in &self.pieces {
            let vertices = c_obstacle_points(&piece.points, robot, theta);
            if vertices.len() >= 3 {
                c_obstacles.push(ConvexPolygon { vertices });
                sources.push(piece.obstacle);
            }
        }
        let index = Index::new(&c_obstacles);
        CLayer {
            theta,
            c_obstacles,
            sources,
            index,
        }
    }

    /// The layers θ_k = k·2π/n, k = 0 … n−1 (built in parallel).
    pub fn layers(&self, robot: &ConvexPolygon, n: usize) -> Vec<CLayer> {
        (0..n)
            .into_par_iter()
            .map(|k| self.layer(robot, layer_angle(k, n)))
            .collect()
    }
}

/// Calls `push` with each convex piece of `shape`, as in
/// [`ObstaclePieces::with_disk_sides`]: counter-clockwise points (2 for a
/// segment, 1 for a point).
pub fn shape_pieces(shape: &Shape, disk_sides: usize, mut push: impl FnMut(Vec<Point>)) {
    match shape {
        Shape::Polygon { outline, pieces } => {
            if pieces.is_empty() {
                for p in polygon::convex_decomposition(outline) {
                    push(p.vertices);
                }
            } else {
                for p in pieces {
                    push(p.vertices.clone());
                }
            }
        }
        Shape::Rect(r) => push(r.corners().to_vec()),
        Shape::Segment(a, b) => push(if a == b { vec![*a] } else { vec![*a, *b] }),
        Shape::Disk { center, radius } => push(disk_polygon(*center, *radius, disk_sides)),
        Shape::Grid(g) => {
            for r in grid_rectangles(g) {
                push(r.corners().to_vec());
            }
        }
    }
}

/// θ_k = k·2π/n.
pub fn layer_angle(k: usize, n: usize) -> f64 {
    k as f64 * std::f64::consts::TAU / n as f64
}

/// The C-obstacles of one orientation θ of a convex polygon robot.
#[derive(Clone, Debug)]
pub struct CLayer {
    pub theta: f64,
    /// One C-obstacle per convex obstacle piece (pieces whose C-obstacle has
    /// no area — only possible for a robot without area — are left out).
    pub c_obstacles: Vec<ConvexPolygon>,
    /// For each C-obstacle, the index of its obstacle in `world.obstacles`.
    pub sources: Vec<usize>,
    index: Index,
}

/// The layer of orientation `theta` for the convex robot `robot` in
/// `world` (see the module documentation).
pub fn layer(world: &World, robot: &ConvexPolygon, theta: f64) -> CLayer {
    ObstaclePieces::new(world).layer(robot, theta)
}

/// The layers θ_k = k·2π/n, k = 0 … n−1, for the convex robot `robot` in
/// `world`; empty for `n = 0`.
pub fn layers(world: &World, robot: &ConvexPolygon, n: usize) -> Vec<CLayer> {
    ObstaclePieces::new(world).layers(robot, n)
}

impl CLayer {
    /// Whether `p` lies in some C-obstacle farther than [`TOUCH_EPS`] from
    /// its boundary: the robot at `(p, θ)` overlaps that piece deeper than
    /// `TOUCH_EPS`. `false` for non-finite points.
    #[inline]
    pub fn contains_interior(&self, p: Point) -> bool {
        let ix = &self.index;
        let Some(b) = ix.bucket(p) else {
            return false;
        };
        if ix.full[b] {
            return true;
        }
        let (s, e) = (ix.starts[b] as usize, ix.starts[b + 1] as usize);
        ix.items[s..e].iter().any(|&k| ix.inside(k as usize, p))
    }

    /// The index into `world.obstacles` of an obstacle whose C-obstacle
    /// contains `p` as in [`CLayer::contains_interior`] (the first such
    /// C-obstacle of the bucket), if any.
    pub fn obstacle_at(&self, p: Point) -> Option<usize> {
        let ix = &self.index;
        let b = ix.bucket(p)?;
        let (s, e) = (ix.starts[b] as usize, ix.starts[b + 1] as usize);
        ix.items[s..e]
            .iter()
            .find(|&&k| ix.inside(k as usize, p))
            .map(|&k| self.sources[k as usize])
    }
}

/// The blocked cells of `grid` as few rectangles with the same union: runs
/// of blocked cells in a row, merged with the run of the row below when it
/// spans the same columns. The rectangles' interiors are disjoint; their
/// corners are corners of [`Grid::cell_box`].
pub fn grid_rectangles(grid: &Grid) -> Vec<Aabb> {
    let mut rects: Vec<Aabb> = Vec::new();
    // Runs (first column, last column) of the row above, with their
    // rectangle, sorted by first column.
    let mut above: Vec<(usize, usize, usize)> = Vec::new();
    let mut current: Vec<(usize, usize, usize)> = Vec::new();
    for row in 0..grid.height {
        current.clear();
        let mut cursor = 0; // into `above`
        let mut col = 0;
        while col < grid.width {
            if !grid.is_blocked(col, row) {
                col += 1;
                continue;
            }
            let c0 = col;
            while col < grid.width && grid.is_blocked(col, row) {
                col += 1;
            }
            let c1 = col - 1;
            while cursor < above.len() && above[cursor].0 < c0 {
                cursor += 1;
            }
            let bottom = grid.cell_box(c0, row).min.y;
            let r = match above.get(cursor) {
                Some(&(a0, a1, r)) if a0 == c0 && a1 == c1 => {
                    rects[r].min.y = bottom;
                    r
                }
                _ => {
                    rects.push(Aabb {
                        min: grid.cell_box(c0, row).min,
                        max: grid.cell_box(c1, row).max,
                    });
                    rects.len() - 1
                }
            };
            current.push((c0, c1, r));
        }
        std::mem::swap(&mut above, &mut current);
    }
    rects
}

// ------------------------------------------------------------------ index

/// A half-plane `n·p ≤ c` with a unit normal.
#[derive(Clone, Copy, Debug)]
struct Plane {
    nx: f64,
    ny: f64,
    c: f64,
}

impl Plane {
    /// The signed distance of `(x, y)` beyond the edge's line (negative
    /// inside).
    #[inline]
    fn beyond(&self, x: f64, y: f64) -> f64 {
        self.nx * x + self.ny * y - self.c
    }
}

/// Target number of buckets per C-obstacle, and the bounds on the total.
const BUCKETS_PER_OBSTACLE: usize = 64;
const MIN_BUCKETS: usize = 1024;
const MAX_BUCKETS: usize = 1 << 18;

#[derive(Clone, Debug, Default)]
struct Index {
    /// The edges of all C-obstacles, one after the other.
    planes: Vec<Plane>,
    /// Per C-obstacle, its range in `planes`.
    ranges: Vec<(u32, u32)>,
    /// The bucket grid: origin, side, and size (0 × 0 without obstacles).
    origin: Point,
    inv_side: f64,
    nx: usize,
    ny: usize,
    /// Per bucket: whether one C-obstacle's deep interior covers it.
    full: Vec<bool>,
    /// Per bucket, its range in `items` (`starts[b] .. starts[b + 1]`).
    starts: Vec<u32>,
    /// The C-obstacles that may hold a deep interior point of the bucket.
    items: Vec<u32>,
}

impl Index {
    fn new(polys: &[ConvexPolygon]) -> Index {
        let mut planes = Vec::new();
        let mut ranges = Vec::with_capacity(polys.len());
        let mut boxes: Vec<Aabb> = Vec::with_capacity(polys.len());
        for poly in polys {
            let v = &poly.vertices;
            let start = planes.len() as u32;
            for i in 0..v.len() {
                let (a, b) = (v[i], v[(i + 1) % v.len()]);
                let d = b - a;
                let len = d.norm();
                let (nx, ny) = (d.y / len, -d.x / len);
                planes.push(Plane {
                    nx,
                    ny,
                    c: nx * a.x + ny * a.y,
                });
            }
            ranges.push((start, planes.len() as u32));
            let mut bx = Aabb {
                min: v[0],
                max: v[0],
            };
            for p in v {
                bx.min = Point::new(bx.min.x.min(p.x), bx.min.y.min(p.y));
                bx.max = Point::new(bx.max.x.max(p.x), bx.max.y.max(p.y));
            }
            boxes.push(bx);
        }
        let mut index = Index {
            planes,
            ranges,
            starts: vec![0],
            ..Index::default()
        };
        let Some(first) = boxes.first() else {
            return index;
        };
        let mut all = *first;
        for bx in &boxes {
            all.min = Point::new(all.min.x.min(bx.min.x), all.min.y.min(bx.min.y));
            all.max = Point::new(all.max.x.max(bx.max.x), all.max.y.max(bx.max.y));
        }
        let (w, h) = (all.width(), all.height());
        let target = (BUCKETS_PER_OBSTACLE * boxes.len()).clamp(MIN_BUCKETS, MAX_BUCKETS);
        let side = ((w * h) / target as f64)
            .sqrt()
            .max(w.max(h) / MAX_BUCKETS as f64);
        if !(side.is_finite() && side > 0.0) {
            return index;
        }
        // One spare bucket on each far side absorbs rounding.
        let nx = ((w / side).ceil() as usize + 1).max(1);
        let ny = ((h / side).ceil() as usize + 1).max(1);
        index.origin = all.min;
        index.inv_side = 1.0 / side;
        index.nx = nx;
        index.ny = ny;

        // Bucket squares are grown by a margin so that a point whose bucket
        // index is off by rounding is still covered.
        let margin = 1e-9 * side;
        let square = |i: usize, j: usize| -> [Point; 4] {
            let x0 = all.min.x + i as f64 * side - margin;
            let y0 = all.min.y + j as f64 * side - margin;
            let (x1, y1) = (x0 + side + 2.0 * margin, y0 + side + 2.0 * margin);
            [
                Point::new(x0, y0),
                Point::new(x1, y0),
                Point::new(x1, y1),
                Point::new(x0, y1),
            ]
        };
        let range = |lo: f64, hi: f64, n: usize| -> (usize, usize) {
            let a = ((lo - margin) * index.inv_side).floor().max(0.0) as usize;
            let b = (((hi + margin) * index.inv_side).floor().max(0.0) as usize).min(n - 1);
            (a.min(n - 1), b)
        };
        let mut full = vec![false; nx * ny];
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for (k, bx) in boxes.iter().enumerate() {
            let (r0, r1) = index.ranges[k];
            let planes = &index.planes[r0 as usize..r1 as usize];
            let (i0, i1) = range(bx.min.x - all.min.x, bx.max.x - all.min.x, nx);
            let (j0, j1) = range(bx.min.y - all.min.y, bx.max.y - all.min.y, ny);
            for j in j0..=j1 {
                for i in i0..=i1 {
                    let corners = square(i, j);
                    // Some edge has the whole square at or beyond its line
                    // (within TOUCH_EPS): no deep interior point here.
                    let apart = planes
                        .iter()
                        .any(|pl| corners.iter().all(|q| pl.beyond(q.x, q.y) >= -TOUCH_EPS));
                    if apart {
                        continue;
                    }
                    let b = j * nx + i;
                    pairs.push((b as u32, k as u32));
                    // The square lies in the deep interior (convex).
                    if planes
                        .iter()
                        .all(|pl| corners.iter().all(|q| pl.beyond(q.x, q.y) < -TOUCH_EPS))
                    {
                        full[b] = true;
                    }
                }
            }
        }
        // Counting sort of the pairs by bucket; full buckets keep their
        // lists for `obstacle_at`.
        let mut starts = vec![0u32; nx * ny + 1];
        for &(b, _) in &pairs {
            starts[b as usize + 1] += 1;
        }
        for b in 0..nx * ny {
            starts[b + 1] += starts[b];
        }
        let mut fill = starts.clone();
        let mut items = vec![0u32; pairs.len()];
        for &(b, k) in &pairs {
            items[fill[b as usize] as usize] = k;
            fill[b as usize] += 1;
        }
        index.full = full;
        index.starts = starts;
        index.items = items;
        index
    }

    /// The bucket of `p`, or `None` outside the grid (where no C-obstacle
    /// is) and for non-finite points.
    #[inline]
    fn bucket(&self, p: Point) -> Option<usize> {
        let fx = (p.x - self.origin.x) * self.inv_side;
        let fy = (p.y - self.origin.y) * self.inv_side;
        if fx >= 0.0 && fy >= 0.0 && fx < self.nx as f64 && fy < self.ny as f64 {
            Some(fy as usize * self.nx + fx as usize)
        } else {
            None
        }
    }

    /// Whether `p` lies in C-obstacle `k` farther than `TOUCH_EPS` from
    /// its boundary.
    #[inline]
    fn inside(&self, k: usize, p: Point) -> bool {
        let (s, e) = self.ranges[k];
        self.planes[s as usize..e as usize]
            .iter()
            .all(|pl| pl.beyond(p.x, p.y) < -TOUCH_EPS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::world_in;
    use crate::minkowski::c_obstacle;
    use crate::polygon::{convex_hull, normalize_simple_polygon, signed_area2};
    use crate::validator::{Validator, config_collision};
    use crate::{Config, Obstacle, RobotShape};
    use parry2d_f64::math::Isometry;
    use parry2d_f64::query;
    use parry2d_f64::shape::{
        Ball, ConvexPolygon as ParryPolygon, Cuboid, Segment, Shape as ParryShape,
    };
    use proptest::prelude::*;
    use std::f64::consts::{FRAC_PI_2, PI, TAU};
    use std::time::Instant;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Shape {
        Shape::Rect(Aabb::from_corners(p(x0, y0), p(x1, y1)))
    }

    fn world(shapes: Vec<Shape>) -> World {
        world_in(
            Aabb::from_corners(p(-100.0, -100.0), p(100.0, 100.0)),
            shapes,
        )
    }

    fn rod() -> ConvexPolygon {
        ConvexPolygon {
            vertices: vec![p(0.0, 0.0), p(8.0, 0.0), p(8.0, 1.0), p(0.0, 1.0)],
        }
    }

    /// The apartment of SEEDS.md.
    fn apartment() -> World {
        let mut w = world(vec![
            rect(0.0, 29.0, 32.0, 30.0),
            rect(0.0, 0.0, 1.0, 30.0),
            rect(0.0, 0.0, 32.0, 1.0),
            rect(31.0, 0.0, 32.0, 30.0),
            rect(0.0, 18.0, 10.0, 19.0),
            rect(17.0, 17.0, 18.0, 29.0),
            rect(25.0, 18.0, 32.0, 19.0),
            rect(0.0, 14.0, 19.0, 15.0),
            rect(24.0, 13.0, 32.0, 15.0),
            rect(10.0, 19.0, 12.0, 20.0),
            rect(23.0, 19.0, 25.0, 20.0),
        ]);
        w.bounds = Aabb::from_corners(p(0.0, 0.0), p(32.0, 30.0));
        w
    }

    fn grid_shape(cell: f64, origin: Point, rows: &[&str]) -> Grid {
        let width = rows[0].len();
        let cells = rows
            .iter()
            .flat_map(|r| r.bytes().map(|b| if b == b'#' { 0 } else { 1 }))
            .collect();
        Grid {
            cell,
            origin,
            width,
            height: rows.len(),
            cells,
        }
    }

    #[test]
    fn rod_against_the_apartment_at_zero() {
        let w = apartment();
        let l = layer(&w, &rod(), 0.0);
        assert_eq!(l.c_obstacles.len(), 11);
        assert_eq!(l.sources, (0..11).collect::<Vec<_>>());
        // B1 = (0,18)–(10,19) gives [−8, 10] × [17, 19].
        assert_eq!(
            l.c_obstacles[4],
            c_obstacle(
                &ConvexPolygon {
                    vertices: Aabb::from_corners(p(0.0, 18.0), p(10.0, 19.0))
                        .corners()
                        .to_vec()
                },
                &rod(),
                0.0
            )
        );
        assert!(l.contains_interior(p(5.0, 18.0)));
        assert_eq!(l.obstacle_at(p(5.0, 18.0)), Some(4));
        // Its lower side y = 17 at x = 1.5 (clear of the other C-obstacles).
        assert!(!l.contains_interior(p(1.5, 17.0)));
        assert!(!l.contains_interior(p(1.5, 17.0 + 0.5e-9)));
        assert!(l.contains_interior(p(1.5, 17.0 + 2e-9)));
        assert_eq!(l.obstacle_at(p(1.5, 17.5)), Some(4));
        // B6 = (10,19)–(12,20) gives [2, 12] × [18, 20], overlapping B1's.
        assert!(l.contains_interior(p(10.0, 18.5)));
        assert_eq!(l.obstacle_at(p(3.0, 19.5)), Some(9));
        assert!(!l.contains_interior(p(2.0, 19.5)));
        assert!(l.contains_interior(p(2.0 + 2e-9, 19.5)));
        // The start and goal of SEEDS are free; the rod cannot stand with its
        // origin at x = 24 at y = 24 (it would reach into the right wall).
        assert!(!l.contains_interior(p(4.0, 24.0)));
        assert!(!l.contains_interior(p(4.0, 8.0)));
        assert!(l.contains_interior(p(24.0, 24.0)));
        assert_eq!(l.obstacle_at(p(4.0, 24.0)), None);
        assert!(!l.contains_interior(p(f64::NAN, 1.0)));
        assert!(!l.contains_interior(p(1e9, 1.0)));
        // At 90° the rod stands upright: its origin at (4, 24) reaches y = 32.
        let l = layer(&w, &rod(), FRAC_PI_2);
        assert!(l.contains_interior(p(4.0, 24.0)));
        assert!(!l.contains_interior(p(4.0, 20.0)));
        assert!(l.c_obstacles.iter().all(|c| c.vertices.len() == 4));
    }

    #[test]
    fn layers_are_evenly_spaced() {
        let w = apartment();
        let ls = layers(&w, &rod(), 51);
        assert_eq!(ls.len(), 51);
        for (k, l) in ls.iter().enumerate() {
            assert_eq!(l.theta, k as f64 * TAU / 51.0);
            assert_eq!(l.c_obstacles.len(), 11);
        }
        assert!(layers(&w, &rod(), 0).is_empty());
        let ls = layers(&w, &rod(), 4);
        assert_eq!(ls[2].theta, PI);
        assert!(
            ls.iter()
                .all(|l| l.c_obstacles.iter().all(|c| c.vertices.len() == 4))
        );
    }

    #[test]
    fn segments_points_and_disks() {
        let w = world(vec![
            Shape::Segment(p(26.0, 10.0), p(26.0, 22.0)),
            Shape::Segment(p(0.0, 0.0), p(0.0, 0.0)),
            Shape::Disk {
                center: p(50.0, 50.0),
                radius: 2.0,
            },
        ]);
        let l = layer(&w, &rod(), 0.0);
        assert_eq!(l.sources, vec![0, 1, 2]);
        assert_eq!(
            l.c_obstacles[0].vertices,
            vec![p(18.0, 9.0), p(26.0, 9.0), p(26.0, 22.0), p(18.0, 22.0)]
        );
        assert!(l.contains_interior(p(20.0, 15.0)));
        assert!(!l.contains_interior(p(26.0, 15.0)));
        // A point obstacle blocks the configurations whose body holds it.
        assert!(l.contains_interior(p(-4.0, -0.5)));
        assert!(!l.contains_interior(p(-4.0, -1.0)));
        // The disk: its C-obstacle holds the disk grown by the rod.
        assert!(l.contains_interior(p(50.0 - 8.0 - 1.99, 50.0)));
        assert!(l.contains_interior(p(52.0 - 1e-6, 50.0)));
        assert!(!l.contains_interior(p(52.0 * 1.006, 50.0)));
        // The 32-gon has sides facing the axes, parallel to the rod's.
        assert_eq!(l.c_obstacles[2].vertices.len(), 32);
        let l = layer(&w, &rod(), 0.1);
        assert_eq!(l.c_obstacles[2].vertices.len(), 36);
    }

    #[test]
    fn grid_runs_merge_into_rectangles() {
        let g = grid_shape(
            0.5,
            p(1.0, 2.0),
            &[
                "##..####", "##..#..#", "........", "###.###.", "###.###.", "#.#.....",
            ],
        );
        let rects = grid_rectangles(&g);
        // Rows 0–1 cols 0–1 merge; (0, 4–7); row 1: (4), (7); rows 3–4: (0–2)
        // and (4–6); row 5: (0), (2).
        assert_eq!(rects.len(), 8);
        let total: f64 = rects.iter().map(|r| r.width() * r.height()).sum();
        let blocked = g.cells.iter().filter(|&&c| c == 0).count();
        assert!((total - blocked as f64 * 0.25).abs() < 1e-12);
        for row in 0..g.height {
            for col in 0..g.width {
                let b = g.cell_box(col, row);
                let c = Point::from((b.min.coords + b.max.coords) / 2.0);
                let n = rects.iter().filter(|r| r.contains(c)).count();
                assert_eq!(
                    n,
                    usize::from(g.is_blocked(col, row)),
                    "cell ({col}, {row})"
                );
            }
        }
        assert!(rects.contains(&Aabb {
            min: g.cell_box(0, 1).min,
            max: g.cell_box(1, 0).max
        }));
        // The layer of a small square robot matches the validator.
        let w = world(vec![Shape::Grid(g.clone())]);
        let square = ConvexPolygon {
            vertices: vec![p(0.0, 0.0), p(0.3, 0.0), p(0.3, 0.3), p(0.0, 0.3)],
        };
        let l = layer(&w, &square, 0.0);
        assert_eq!(l.c_obstacles.len(), 8);
        let robot = RobotShape::Polygon(square);
        for i in 0..100 {
            for j in 0..100 {
                let q = p(0.5 + i as f64 * 0.0517, 1.5 + j as f64 * 0.0437);
                let hit = config_collision(&w, &robot, Config::new(q.x, q.y, 0.0)).is_some();
                assert_eq!(l.contains_interior(q), hit, "at {q:?}");
            }
        }
    }

    /// A sharp robot tip poking 3e-9 into the seam between two blocked
    /// cells: the merged rectangle sees the overlap, each cell alone (the
    /// validator) sees less than `TOUCH_EPS`. The layer is the stricter.
    #[test]
    fn a_sharp_tip_on_a_grid_seam_is_stricter_than_the_validator() {
        let g = grid_shape(0.3, p(0.0, 0.0), &["..##"]);
        let w = world(vec![Shape::Grid(g)]);
        let robot = ConvexPolygon {
            vertices: vec![
                p(-2.6665858826781834, 0.0),
                p(0.0, 0.0),
                p(2.3609130897886392, 2.7329979291205153),
            ],
        };
        let theta = 4.1406592896399985;
        let l = layer(&w, &robot, theta);
        assert_eq!(l.c_obstacles.len(), 1);
        let shape = RobotShape::Polygon(robot);
        let q = p(-0.12089872158554898, 3.7642393216393004);
        let c = Config::new(q.x, q.y, theta);
        // The tip is at (0.9, 0.3 − 3e-9), on the seam x = 0.9.
        let tip = shape.placed_vertices(c)[2];
        assert!((tip - p(0.9, 0.3 - 3e-9)).norm() < 1e-12);
        assert!(l.contains_interior(q));
        assert_eq!(config_collision(&w, &shape, c), None);
        // 1e-7 deeper both agree.
        let q = p(q.x, q.y - 1e-7);
        assert!(l.contains_interior(q));
        assert!(config_collision(&w, &shape, Config::new(q.x, q.y, theta)).is_some());
    }

    #[test]
    fn rotated_rods_match_the_validator_on_a_lattice() {
        let w = apartment();
        let robot = RobotShape::Polygon(rod());
        let v = Validator::new(&w);
        let ls = layers(&w, &rod(), 51);
        let mut blocked = 0;
        for l in ls.iter().step_by(5) {
            for i in 0..64 {
                for j in 0..60 {
                    let q = p(0.25 + 0.5 * i as f64, 0.25 + 0.5 * j as f64);
                    let hit = v
                        .config_collision(&robot, Config::new(q.x, q.y, l.theta))
                        .is_some();
                    assert_eq!(l.contains_interior(q), hit, "at {q:?}, θ = {}", l.theta);
                    blocked += usize::from(hit);
                }
            }
        }
        assert!(blocked > 1000);
    }

    // ------------------------------------------------------------ properties

    /// An independent parry shape of one obstacle piece.
    enum Solid {
        Poly(ParryPolygon),
        Box(Point, Cuboid),
        Seg(Segment),
        Disk(Point, Ball),
    }

    impl Solid {
        fn with<R>(&self, f: impl FnOnce(&Isometry<f64>, &dyn ParryShape) -> R) -> R {
            match self {
                Solid::Poly(s) => f(&Isometry::identity(), s),
                Solid::Box(c, s) => f(&Isometry::translation(c.x, c.y), s),
                Solid::Seg(s) => f(&Isometry::identity(), s),
                Solid::Disk(c, s) => f(&Isometry::translation(c.x, c.y), s),
            }
        }
    }

    fn box_solid(b: &Aabb) -> Solid {
        Solid::Box(
            Point::from((b.min.coords + b.max.coords) / 2.0),
            Cuboid::new((b.max - b.min) / 2.0),
        )
    }

    /// The obstacle's pieces as parry shapes, built from the world's own
    /// description (the outline's pieces, the rectangle, every blocked
    /// cell), not from this module's pieces.
    fn solids(shape: &Shape) -> Vec<Solid> {
        match shape {
            Shape::Polygon { pieces, .. } => pieces
                .iter()
                .map(|q| {
                    Solid::Poly(
                        ParryPolygon::from_convex_polyline_unmodified(q.vertices.clone()).unwrap(),
                    )
                })
                .collect(),
            Shape::Rect(r) => vec![box_solid(r)],
            Shape::Segment(a, b) => vec![Solid::Seg(Segment::new(*a, *b))],
            Shape::Disk { center, radius } => vec![Solid::Disk(*center, Ball::new(*radius))],
            Shape::Grid(g) => {
                let mut v = Vec::new();
                for row in 0..g.height {
                    for col in 0..g.width {
                        if g.is_blocked(col, row) {
                            v.push(box_solid(&g.cell_box(col, row)));
                        }
                    }
                }
                v
            }
        }
    }

    /// Signed distance between the placed robot and a solid by parry's
    /// contact query (negative: penetration depth). Not for segments: EPA
    /// is unreliable on flat shapes.
    fn signed_distance(body: &ParryPolygon, solid: &Solid) -> f64 {
        solid.with(|pos, shape| {
            match query::contact(&Isometry::identity(), body, pos, shape, 1e9) {
                Ok(Some(c)) => c.dist,
                _ => f64::NAN,
            }
        })
    }

    /// The counter-clockwise convex polygon `v` with every edge moved
    /// inward by `m` (its points deeper than `m`), or `None` when that
    /// changes its shape (too thin).
    fn erode(v: &[Point], m: f64) -> Option<Vec<Point>> {
        let n = v.len();
        let line = |i: usize| {
            let (a, b) = (v[i], v[(i + 1) % n]);
            let d = (b - a).normalize();
            (a + crate::Vector::new(-d.y, d.x) * m, d)
        };
        let out: Vec<Point> = (0..n)
            .map(|i| {
                let (p0, d0) = line((i + n - 1) % n);
                let (p1, d1) = line(i);
                // p0 + s d0 = p1 + t d1
                let den = d0.x * d1.y - d0.y * d1.x;
                let r = p1 - p0;
                let s = (r.x * d1.y - r.y * d1.x) / den;
                p0 + d0 * s
            })
            .collect();
        let same = (0..n).all(|i| (out[(i + 1) % n] - out[i]).dot(&(v[(i + 1) % n] - v[i])) > 0.0);
        same.then_some(out)
    }

    /// Margin around 0 within which parry's answer is not trusted.
    const MARGIN: f64 = 1e-7;

    #[derive(Clone, Copy, Debug, PartialEq)]
    enum Verdict {
        Free,
        Hit,
        Unsure,
    }

    /// Whether the robot body overlaps the obstacle, by parry. Disks are
    /// judged against the band between the disk and its circumscribed
    /// polygon. A segment is hit when it meets the body eroded by the
    /// margin, missed when farther than the margin from it.
    fn verdict(body: &[Point], shape: &Shape, solids: &[Solid]) -> Verdict {
        let band = match shape {
            Shape::Disk { radius, .. } => {
                radius * (1.0 / (PI / DISK_SIDES as f64).cos() - 1.0) * (1.0 + 1e-6)
            }
            _ => 0.0,
        };
        let poly = ParryPolygon::from_convex_polyline_unmodified(body.to_vec()).unwrap();
        let eroded = erode(body, MARGIN).and_then(ParryPolygon::from_convex_polyline_unmodified);
        let mut all_free = true;
        for solid in solids {
            let (hit, free) = match solid {
                Solid::Seg(seg) => {
                    let id = Isometry::identity();
                    let hit = eroded
                        .as_ref()
                        .is_some_and(|e| query::intersection_test(&id, e, &id, seg).unwrap());
                    let free = query::distance(&id, &poly, &id, seg).unwrap() > MARGIN;
                    (hit, free)
                }
                _ => {
                    let d = signed_distance(&poly, solid);
                    // parry's EPA can report a deep penetration for shapes
                    // that only touch at a vertex (regression: a triangle
                    // whose vertex lies on a polygon's vertex gave
                    // dist = -7.6): a hit must also survive eroding the body.
                    let deep = eroded.as_ref().is_some_and(|e| {
                        solid.with(|pos, shape| {
                            query::intersection_test(&Isometry::identity(), e, pos, shape)
                                .unwrap_or(false)
                        })
                    });
                    (d < -MARGIN && deep, d > band + MARGIN)
                }
            };
            if hit {
                return Verdict::Hit;
            }
            all_free &= free;
        }
        if all_free {
            Verdict::Free
        } else {
            Verdict::Unsure
        }
    }

    /// Regression: parry's contact reported a 7.6 deep overlap for a robot
    /// vertex lying on an obstacle vertex; the layer (rightly) says free.
    #[test]
    fn a_vertex_on_a_vertex_is_touching_not_overlapping() {
        let outline = pts(&[
            (-8.152794268488528, -7.3664987011573455),
            (3.9111552653954944, -5.179120850707725),
            (2.762076054012267, 7.224160966506319),
            (0.19808708302577485, 8.867036138593537),
        ]);
        let shape = Shape::Polygon {
            outline: outline.clone(),
            pieces: vec![ConvexPolygon { vertices: outline }],
        };
        let robot = ConvexPolygon {
            vertices: pts(&[
                (-2.212244966198412, 0.8783582289843117),
                (2.3289361010856724, -2.185909935840095),
                (-0.4413660978921253, 0.9594439797861707),
            ]),
        };
        let w = World {
            bounds: Aabb::from_corners(p(-20.0, -20.0), p(20.0, 20.0)),
            obstacles: vec![Obstacle {
                name: "o0".into(),
                shape: shape.clone(),
            }],
        };
        let (q, theta) = (p(4.335093810004526, 5.437780237706395), 5.812315447064567);
        assert!(!layer(&w, &robot, theta).contains_interior(q));
        let c = Config::new(q.x, q.y, theta);
        let body = RobotShape::Polygon(robot).placed_vertices(c);
        assert_ne!(verdict(&body, &shape, &solids(&shape)), Verdict::Hit);
    }

    fn pts(v: &[(f64, f64)]) -> Vec<Point> {
        v.iter().map(|&(x, y)| p(x, y)).collect()
    }

    fn robot_strategy() -> impl Strategy<Value = ConvexPolygon> {
        let hull = prop::collection::vec((-3.0..3.0f64, -3.0..3.0f64), 3..8)
            .prop_map(|v| convex_hull(&pts(&v)))
            .prop_filter("robot with area", |v| {
                v.len() >= 3 && signed_area2(v) > 0.02
            });
        let boxes = (0.1..9.0f64, 0.1..3.0f64, -1.0..1.0f64, -1.0..1.0f64)
            .prop_map(|(w, h, x, y)| pts(&[(x, y), (x + w, y), (x + w, y + h), (x, y + h)]));
        prop_oneof![3 => hull, 1 => boxes].prop_map(|vertices| ConvexPolygon { vertices })
    }

    fn shape_strategy() -> impl Strategy<Value = Shape> {
        let c = || (-10.0..10.0f64, -10.0..10.0f64);
        let rect_s =
            (c(), 0.05..8.0f64, 0.05..8.0f64).prop_map(|((x, y), w, h)| rect(x, y, x + w, y + h));
        let convex = prop::collection::vec(c(), 3..9)
            .prop_map(|v| convex_hull(&pts(&v)))
            .prop_filter("area", |v| v.len() >= 3 && signed_area2(v) > 0.01);
        // Star-shaped simple polygons, decomposed like the analyzer does.
        let star = (
            c(),
            prop::collection::vec((0.3..5.0f64, 0.0..1.0f64), 4..10),
        )
            .prop_filter_map("simple polygon", |((cx, cy), rs)| {
                let k = rs.len();
                let v: Vec<Point> = rs
                    .iter()
                    .enumerate()
                    .map(|(i, &(r, jit))| {
                        let a = (i as f64 + 0.8 * jit) * TAU / k as f64;
                        p(cx + r * a.cos(), cy + r * a.sin())
                    })
                    .collect();
                normalize_simple_polygon(&v).ok()
            });
        let polygon_s = prop_oneof![convex, star].prop_map(|outline| {
            let pieces = polygon::convex_decomposition(&outline);
            Shape::Polygon { outline, pieces }
        });
        let segment_s = (c(), c()).prop_map(|((a, b), (x, y))| Shape::Segment(p(a, b), p(x, y)));
        let axis_segment = (c(), -6.0..6.0f64, any::<bool>()).prop_map(|((a, b), l, vertical)| {
            Shape::Segment(p(a, b), if vertical { p(a, b + l) } else { p(a + l, b) })
        });
        let disk_s = (c(), 0.05..4.0f64).prop_map(|((x, y), radius)| Shape::Disk {
            center: p(x, y),
            radius,
        });
        let grid_s = (
            c(),
            0.3..2.0f64,
            1usize..7,
            1usize..7,
            prop::collection::vec(any::<bool>(), 36),
        )
            .prop_map(|((x, y), cell, width, height, bits)| {
                Shape::Grid(Grid {
                    cell,
                    origin: p(x, y),
                    width,
                    height,
                    cells: (0..width * height).map(|i| u8::from(!bits[i])).collect(),
                })
            });
        prop_oneof![
            2 => rect_s,
            3 => polygon_s,
            2 => prop_oneof![segment_s, axis_segment],
            1 => disk_s,
            1 => grid_s,
        ]
    }

    fn theta_strategy() -> impl Strategy<Value = f64> {
        prop_oneof![
            3 => 0.0..TAU,
            1 => (0usize..8).prop_map(|k| k as f64 * TAU / 8.0),
            1 => (0usize..51, 1usize..4).prop_map(|(k, m)| layer_angle(k, 51 * m)),
        ]
    }

    /// Points around the obstacles' boxes grown by the robot's reach, some
    /// on a lattice (exact coordinates, as the planners query).
    fn sample_points(w: &World, reach: f64, seeds: &[(f64, f64)]) -> Vec<Point> {
        let v = Validator::new(w);
        let _ = v;
        let mut lo = p(f64::INFINITY, f64::INFINITY);
        let mut hi = p(f64::NEG_INFINITY, f64::NEG_INFINITY);
        let mut grow = |q: Point| {
            lo = p(lo.x.min(q.x), lo.y.min(q.y));
            hi = p(hi.x.max(q.x), hi.y.max(q.y));
        };
        for o in &w.obstacles {
            match &o.shape {
                Shape::Polygon { outline, .. } => outline.iter().for_each(|&q| grow(q)),
                Shape::Rect(r) => {
                    grow(r.min);
                    grow(r.max);
                }
                Shape::Segment(a, b) => {
                    grow(*a);
                    grow(*b);
                }
                Shape::Disk { center, radius } => {
                    grow(center - crate::Vector::new(*radius, *radius));
                    grow(center + crate::Vector::new(*radius, *radius));
                }
                Shape::Grid(g) => {
                    let e = g.extent();
                    grow(e.min);
                    grow(e.max);
                }
            }
        }
        let (lo, hi) = (p(lo.x - reach, lo.y - reach), p(hi.x + reach, hi.y + reach));
        seeds
            .iter()
            .enumerate()
            .map(|(i, &(u, t))| {
                let q = p(lo.x + u * (hi.x - lo.x), lo.y + t * (hi.y - lo.y));
                if i % 4 == 0 {
                    p((q.x * 4.0).round() / 4.0, (q.y * 4.0).round() / 4.0)
                } else {
                    q
                }
            })
            .collect()
    }

    /// Checks the layer against parry (and the validator where it is exact)
    /// at the given points; returns (hits, frees) checked.
    fn check_layer(
        w: &World,
        robot: &ConvexPolygon,
        theta: f64,
        points: &[Point],
    ) -> (usize, usize) {
        let l = layer(w, robot, theta);
        let all_solids: Vec<Vec<Solid>> = w.obstacles.iter().map(|o| solids(&o.shape)).collect();
        let has_disk = w
            .obstacles
            .iter()
            .any(|o| matches!(o.shape, Shape::Disk { .. }));
        let has_grid = w
            .obstacles
            .iter()
            .any(|o| matches!(o.shape, Shape::Grid(_)));
        let v = Validator::new(w);
        let shape = RobotShape::Polygon(robot.clone());
        // Besides the given points: on the boundary of the first C-obstacles
        // (vertices, edge midpoints), and 3e-9 and 1e-6 off it either way.
        let points = points.to_vec();
        let mut extra = Vec::new();
        for c in l.c_obstacles.iter().take(6) {
            let n = c.vertices.len();
            for i in 0..n.min(8) {
                let (a, b) = (c.vertices[i], c.vertices[(i + 1) % n]);
                let mid = Point::from((a.coords + b.coords) / 2.0);
                let d = (b - a).normalize();
                let out = crate::Vector::new(d.y, -d.x);
                extra.push(a);
                extra.push(mid);
                for off in [3e-9, -3e-9, 1e-6, -1e-6] {
                    extra.push(mid + out * off);
                }
            }
        }
        // Decided by parry among the given points: (overlaps, free).
        let given = points.len();
        let (mut hits, mut frees) = (0, 0);
        let mut points = points;
        points.extend(extra);
        for (index, &q) in points.iter().enumerate() {
            let c = Config::new(q.x, q.y, theta);
            let inside = l.contains_interior(q);
            let at = l.obstacle_at(q);
            assert_eq!(at.is_some(), inside);
            // The validator's rule, exactly (disks are approximated; merged
            // grid cells are stricter within ~TOUCH_EPS of contact, where a
            // sharp robot tip pokes into a seam).
            if !has_disk {
                let validator = v.config_collision(&shape, c).is_some();
                if has_grid {
                    assert!(
                        inside || !validator,
                        "{q:?} θ={theta}: the validator sees an overlap, the layer not"
                    );
                } else {
                    assert_eq!(
                        inside, validator,
                        "{q:?} θ={theta}: the validator disagrees"
                    );
                }
            }
            let body = shape.placed_vertices(c);
            let verdicts: Vec<Verdict> = w
                .obstacles
                .iter()
                .zip(&all_solids)
                .map(|(o, s)| verdict(&body, &o.shape, s))
                .collect();
            if let Some(i) = at {
                assert_ne!(
                    verdicts[i],
                    Verdict::Free,
                    "{q:?}: C-obstacle of a free obstacle {i}"
                );
            }
            if verdicts.contains(&Verdict::Hit) {
                assert!(
                    inside,
                    "{q:?} θ={theta}: parry sees an overlap, the layer not: {verdicts:?} in {:?} robot {:?}",
                    w.obstacles, robot.vertices
                );
                hits += usize::from(index < given);
            } else if verdicts.iter().all(|&x| x == Verdict::Free) {
                assert!(
                    !inside,
                    "{q:?} θ={theta}: the layer blocks a free configuration"
                );
                frees += usize::from(index < given);
            }
        }
        (hits, frees)
    }

    fn seeds_strategy(n: usize) -> impl Strategy<Value = Vec<(f64, f64)>> {
        prop::collection::vec((0.0..1.0f64, 0.0..1.0f64), n)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// One obstacle of any kind: a configuration is in the interior of
        /// the layer exactly when the placed robot overlaps the obstacle
        /// (disks: one-sided, up to the polygon's band).
        #[test]
        fn interior_iff_overlap_one_obstacle(
            shape in shape_strategy(),
            robot in robot_strategy(),
            theta in theta_strategy(),
            seeds in seeds_strategy(24),
        ) {
            let w = world(vec![shape]);
            let reach = RobotShape::Polygon(robot.clone()).radius() + 0.5;
            let points = sample_points(&w, reach, &seeds);
            check_layer(&w, &robot, theta, &points);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]

        /// Several obstacles (the bucket index with many entries).
        #[test]
        fn interior_iff_overlap_many_obstacles(
            shapes in prop::collection::vec(shape_strategy(), 2..14),
            robot in robot_strategy(),
            theta in theta_strategy(),
            seeds in seeds_strategy(60),
        ) {
            let w = world(shapes);
            let reach = RobotShape::Polygon(robot.clone()).radius() + 0.5;
            let points = sample_points(&w, reach, &seeds);
            check_layer(&w, &robot, theta, &points);
        }

        /// The bucket index answers as a scan over all C-obstacles.
        #[test]
        fn index_matches_a_full_scan(
            shapes in prop::collection::vec(shape_strategy(), 1..30),
            robot in robot_strategy(),
            theta in theta_strategy(),
            seeds in seeds_strategy(400),
        ) {
            let w = world(shapes);
            let l = layer(&w, &robot, theta);
            let reach = RobotShape::Polygon(robot.clone()).radius() + 0.5;
            for q in sample_points(&w, reach, &seeds) {
                let scan = l.c_obstacles.iter().any(|c| {
                    let v = &c.vertices;
                    (0..v.len()).all(|i| {
                        let (a, b) = (v[i], v[(i + 1) % v.len()]);
                        let d = b - a;
                        let inward = (d.x * (q.y - a.y) - d.y * (q.x - a.x)) / d.norm();
                        inward > TOUCH_EPS
                    })
                });
                // Points within rounding of TOUCH_EPS may go either way.
                let near = l.c_obstacles.iter().any(|c| {
                    let v = &c.vertices;
                    let m = (0..v.len()).map(|i| {
                        let (a, b) = (v[i], v[(i + 1) % v.len()]);
                        let d = b - a;
                        (d.x * (q.y - a.y) - d.y * (q.x - a.x)) / d.norm()
                    }).fold(f64::INFINITY, f64::min);
                    (m - TOUCH_EPS).abs() < 1e-12
                });
                if !near {
                    prop_assert_eq!(l.contains_interior(q), scan, "at {:?}", q);
                }
            }
        }
    }

    /// The property tests above decide most of their points, both ways.
    #[test]
    fn property_tests_see_both_outcomes() {
        use proptest::strategy::ValueTree;
        use proptest::test_runner::{Config as RunnerConfig, TestRunner};
        let mut runner = TestRunner::new(RunnerConfig::default());
        let strategy = (
            shape_strategy(),
            robot_strategy(),
            theta_strategy(),
            seeds_strategy(24),
        );
        // Per kind of obstacle: polygon, rect, segment, disk, grid.
        let mut stats = [(0usize, 0usize, 0usize); 5];
        for _ in 0..1500 {
            let (shape, robot, theta, seeds) = strategy.new_tree(&mut runner).unwrap().current();
            let kind = match shape {
                Shape::Polygon { .. } => 0,
                Shape::Rect(_) => 1,
                Shape::Segment(..) => 2,
                Shape::Disk { .. } => 3,
                Shape::Grid(_) => 4,
            };
            let w = world(vec![shape]);
            let reach = RobotShape::Polygon(robot.clone()).radius() + 0.5;
            let points = sample_points(&w, reach, &seeds);
            let (h, f) = check_layer(&w, &robot, theta, &points);
            stats[kind].0 += h;
            stats[kind].1 += f;
            stats[kind].2 += points.len();
        }
        for (kind, (hits, frees, total)) in ["polygon", "rect", "segment", "disk", "grid"]
            .iter()
            .zip(stats)
        {
            eprintln!(
                "{kind}: {hits} overlaps, {frees} free, {} undecided of {total}",
                total - hits - frees
            );
            assert!(hits * 10 > total && frees * 5 > total, "{kind}");
            assert!((total - hits - frees) * 50 < total, "{kind}");
        }
    }

    /// Timings for the apartment (run with `--ignored --nocapture`).
    #[test]
    #[ignore]
    fn bench_apartment_layers() {
        let w = apartment();
        let r = RobotShape::Polygon(rod()).radius();
        let pieces = ObstaclePieces::new(&w);
        for n in [51usize, (TAU * r / 0.25).ceil() as usize] {
            let t = Instant::now();
            let ls = layers(&w, &rod(), n);
            let build = t.elapsed();
            let t = Instant::now();
            let ls1: Vec<CLayer> = (0..n)
                .map(|k| pieces.layer(&rod(), layer_angle(k, n)))
                .collect();
            let serial = t.elapsed();
            assert_eq!(ls1.len(), ls.len());
            for delta in [1.0, 0.25] {
                let (nx, ny) = ((32.0 / delta) as usize, (30.0 / delta) as usize);
                let t = Instant::now();
                let mut free = 0usize;
                for l in &ls {
                    for j in 0..ny {
                        for i in 0..nx {
                            let q = p((i as f64 + 0.5) * delta, (j as f64 + 0.5) * delta);
                            free += usize::from(!l.contains_interior(q));
                        }
                    }
                }
                let dt = t.elapsed();
                let queries = n * nx * ny;
                eprintln!(
                    "{n} layers: build {build:?} (parallel), {serial:?} (serial); δ = {delta}: {queries} queries, {free} free, {dt:?} = {:.1} M queries/s",
                    queries as f64 / dt.as_secs_f64() / 1e6
                );
            }
        }
        // Random points (less cache-friendly, more boundary buckets).
        let ls = layers(&w, &rod(), 203);
        let mut state = 0x9e3779b97f4a7c15u64;
        let mut rnd = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let qs: Vec<(usize, Point)> = (0..4_000_000)
            .map(|_| ((rnd() * 203.0) as usize, p(rnd() * 32.0, rnd() * 30.0)))
            .collect();
        let t = Instant::now();
        let blocked = qs
            .iter()
            .filter(|(k, q)| ls[*k].contains_interior(*q))
            .count();
        let dt = t.elapsed();
        eprintln!(
            "random: {} queries, {blocked} blocked, {dt:?} = {:.1} M queries/s",
            qs.len(),
            qs.len() as f64 / dt.as_secs_f64() / 1e6
        );
    }
}
