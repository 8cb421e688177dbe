//! The planners' distance query: how far the robot's body at a
//! configuration is from the nearest obstacle. Car planners advance along
//! a curve by that distance ([`crate::car::CarChecker::path_free`]); the potential
//! field measures how far its walk keeps off the obstacles.
//!
//! This is the planners' side (with [`crate::motion`]): the validator
//! measures a path's clearance with its own code, as the referee of every
//! path (SPEC 3.0), and no planner calls it.
//!
//! # Exactness
//! Obstacles are cut into convex pieces (polygons into their convex
//! decomposition, rectangles and a grid's merged rectangles of blocked
//! cells as they are, segments as two-point pieces) and disks, kept exact.
//! For a body that meets no piece, the distance to a convex piece is the
//! smallest distance between a vertex of one and an edge (or vertex) of the
//! other, which is exact for disjoint convex sets; to a disk, the distance
//! to its centre less its radius. A body that meets a piece (by the
//! separating-axis test, or a disk whose centre lies within its radius) is
//! at distance 0. Distances to a disk robot are from its boundary.

use super::cspace::shape_pieces;
use super::polygon::distance_point_segment;
use super::{Aabb, Config, Point, RobotShape, Shape, World, place};

/// The obstacles of a world as convex pieces and disks, for distance
/// queries. Build it once per plan; queries take `&self`.
#[derive(Clone, Debug)]
pub struct Proximity {
    pieces: Vec<Piece>,
}

#[derive(Clone, Debug)]
struct Piece {
    aabb: Aabb,
    kind: Kind,
}

#[derive(Clone, Debug)]
enum Kind {
    /// Counter-clockwise points: 1 for a point, 2 for a segment, else a
    /// convex polygon.
    Convex(Vec<Point>),
    Disk {
        center: Point,
        radius: f64,
    },
}

/// The robot's body placed at a configuration.
enum Body<'a> {
    /// A disk of this radius (0: a point) around this centre.
    Round(Point, f64),
    /// A convex polygon, counter-clockwise.
    Convex(&'a [Point]),
}

impl Proximity {
    pub fn new(world: &World) -> Self {
        let mut pieces = Vec::new();
        for o in &world.obstacles {
            if let Shape::Disk { center, radius } = o.shape {
                pieces.push(Piece {
                    aabb: o.shape.bounding_box(),
                    kind: Kind::Disk { center, radius },
                });
                continue;
            }
            // Disks were taken above: the side count is never used.
            shape_pieces(&o.shape, 3, |points| {
                pieces.push(Piece {
                    aabb: Aabb::around(&points),
                    kind: Kind::Convex(points),
                })
            });
        }
        Proximity { pieces }
    }

    /// The distance between `robot`'s body at `c` and the nearest obstacle:
    /// 0 when they meet, +∞ without obstacles. The bounds are not
    /// obstacles.
    pub fn distance(&self, robot: &RobotShape, c: Config) -> f64 {
        let placed: Vec<Point>;
        let body = match robot {
            RobotShape::Point => Body::Round(c.xy(), 0.0),
            RobotShape::Disk(r) => Body::Round(c.xy(), *r),
            RobotShape::Polygon(p) => {
                let (s, co) = c.theta.sin_cos();
                placed = p.vertices.iter().map(|v| place(c, s, co, v)).collect();
                Body::Convex(&placed)
            }
        };
        let aabb = match &body {
            Body::Round(p, r) => {
                Aabb::from_corners(Point::new(p.x - r, p.y - r), Point::new(p.x + r, p.y + r))
            }
            Body::Convex(v) => Aabb::around(v),
        };
        let mut best = f64::INFINITY;
        for piece in &self.pieces {
            if box_distance(&aabb, &piece.aabb) >= best {
                continue;
            }
            let d = match (&body, &piece.kind) {
                (Body::Round(p, r), Kind::Convex(q)) => point_convex_distance(*p, q) - r,
                (Body::Round(p, r), Kind::Disk { center, radius }) => {
                    (p - center).norm() - r - radius
                }
                (Body::Convex(v), Kind::Convex(q)) => convex_distance(v, q),
                (Body::Convex(v), Kind::Disk { center, radius }) => {
                    point_convex_distance(*center, v) - radius
                }
            };
            best = best.min(d.max(0.0));
            if best == 0.0 {
                break;
            }
        }
        best
    }
}

/// The distance between two boxes (0 when they meet).
fn box_distance(a: &Aabb, b: &Aabb) -> f64 {
    let dx = (b.min.x - a.max.x).max(a.min.x - b.max.x).max(0.0);
    let dy = (b.min.y - a.max.y).max(a.min.y - b.max.y).max(0.0);
    dx.hypot(dy)
}

/// The edges of a convex point list (none for a point, one for a segment).
fn edges(v: &[Point]) -> impl Iterator<Item = (Point, Point)> + '_ {
    let n = match v.len() {
        0 | 1 => 0,
        2 => 1,
        n => n,
    };
    (0..n).map(move |i| (v[i], v[(i + 1) % v.len()]))
}

/// The distance from `p` to the convex set of `v` (0 inside it).
fn point_convex_distance(p: Point, v: &[Point]) -> f64 {
    if v.len() >= 3 && edges(v).all(|(a, b)| cross(b - a, p - a) >= 0.0) {
        return 0.0;
    }
    match v {
        [q] => (p - q).norm(),
        _ => edges(v)
            .map(|(a, b)| distance_point_segment(p, a, b))
            .fold(f64::INFINITY, f64::min),
    }
}

/// The distance between two convex point lists (0 when they meet).
pub(crate) fn convex_distance(a: &[Point], b: &[Point]) -> f64 {
    if !separated(a, b) {
        return 0.0;
    }
    let one_way = |from: &[Point], to: &[Point]| {
        from.iter()
            .map(|&p| point_convex_distance(p, to))
            .fold(f64::INFINITY, f64::min)
    };
    one_way(a, b).min(one_way(b, a))
}

/// Whether some axis separates the two convex sets strictly: the edge
/// normals of both (and for two lower-dimensional sets, the normal of the
/// segment between their nearest features is among those of a polygon, or
/// the sets are both segments or points, whose normals and connecting
/// directions are tried).
fn separated(a: &[Point], b: &[Point]) -> bool {
    let apart = |n: nalgebra::Vector2<f64>| {
        if n.norm_squared() == 0.0 {
            return false;
        }
        let (alo, ahi) = span(a, n);
        let (blo, bhi) = span(b, n);
        ahi < blo || bhi < alo
    };
    let normal = |(p, q): (Point, Point)| nalgebra::Vector2::new(q.y - p.y, p.x - q.x);
    if edges(a).map(normal).any(apart) || edges(b).map(normal).any(apart) {
        return true;
    }
    // Points and segments have too few normals: the direction between
    // each pair of their points (and along each segment) completes them.
    if a.len() < 3 && b.len() < 3 {
        let along = |v: &[Point]| edges(v).map(|(p, q)| q - p).collect::<Vec<_>>();
        return a.iter().any(|p| b.iter().any(|q| apart(q - p)))
            || along(a).into_iter().chain(along(b)).any(apart);
    }
    false
}

/// The smallest and largest projection of `v` on `n`.
fn span(v: &[Point], n: nalgebra::Vector2<f64>) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            let x = p.coords.dot(&n);
            (lo.min(x), hi.max(x))
        })
}

fn cross(a: nalgebra::Vector2<f64>, b: nalgebra::Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::random::random_world;
    use crate::fixtures::{grid, rect, world};
    use crate::validator::Validator;
    use crate::{ConvexPolygon, Shape};
    use proptest::prelude::*;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    #[test]
    fn closed_forms() {
        let w = world(vec![
            rect(6.0, 6.0, 8.0, 8.0),
            Shape::Disk {
                center: p(2.0, 2.0),
                radius: 1.0,
            },
            Shape::Segment(p(9.0, 1.0), p(9.0, 4.0)),
            grid(1.0, p(0.0, 9.0), &["#.."]),
        ]);
        let prox = Proximity::new(&w);
        // A point 2 left of the square; 4 from the disk's centre.
        assert_eq!(
            prox.distance(&RobotShape::Point, Config::new(4.0, 7.0, 0.0)),
            2.0
        );
        assert_eq!(
            prox.distance(&RobotShape::Disk(0.5), Config::new(4.0, 7.0, 0.0)),
            1.5
        );
        assert_eq!(
            prox.distance(&RobotShape::Point, Config::new(6.0, 2.0, 0.0)),
            3.0
        );
        // Inside the square, and below the grid's one blocked cell.
        assert_eq!(
            prox.distance(&RobotShape::Point, Config::new(7.0, 7.0, 0.0)),
            0.0
        );
        assert_eq!(
            prox.distance(&RobotShape::Point, Config::new(0.5, 9.5, 0.0)),
            0.0
        );
        // A unit square robot, its corner (1, 1) one unit from the segment.
        let square = RobotShape::Polygon(ConvexPolygon {
            vertices: vec![p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
        });
        let d = prox.distance(&square, Config::new(7.0, 2.0, 0.0));
        assert!((d - 1.0).abs() < 1e-12, "{d}");
        let empty = Proximity::new(&world(Vec::new()));
        assert_eq!(
            empty.distance(&square, Config::new(1.0, 1.0, 0.3)),
            f64::INFINITY
        );
    }

    fn robot() -> impl Strategy<Value = RobotShape> {
        prop_oneof![
            Just(RobotShape::Point),
            (0.05..1.0f64).prop_map(RobotShape::Disk),
            (0.1..1.5f64, 0.1..1.0f64).prop_map(|(a, b)| RobotShape::Polygon(ConvexPolygon {
                vertices: vec![p(-a, -b), p(a, -b), p(0.2, b)],
            })),
        ]
    }

    proptest! {
        /// The validator's distance (its own code) to rounding, in every
        /// kind of world: polygons, rects, disks, segments, grids.
        #[test]
        fn agrees_with_the_validators_distance(
            w in random_world(),
            robot in robot(),
            x in -1.0..11.0f64, y in -1.0..11.0f64, theta in -3.2..3.2f64,
        ) {
            let c = Config::new(x, y, theta);
            let ours = Proximity::new(&w).distance(&robot, c);
            let referee = Validator::new(&w).body_clearance(&robot, c).max(0.0);
            prop_assert!(
                ours == referee || (ours - referee).abs() <= 1e-9 * (1.0 + referee) || (ours <= 1e-9 && referee <= 1e-9),
                "{} vs {}", ours, referee
            );
        }
    }
}
