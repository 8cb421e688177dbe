//! Small worlds for the geometry modules' tests.

use super::{Aabb, Grid, Obstacle, Point, Shape, World, polygon};

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

/// A star of `n` vertices about the origin, counter-clockwise: every
/// other vertex at radius `outer`, the rest at `inner` (long spikes whose
/// boxes overlap many others', for the polygon sweeps at scale).
pub fn star(n: usize, outer: f64, inner: f64) -> Vec<Point> {
    (0..n)
        .map(|k| {
            let a = k as f64 * std::f64::consts::TAU / n as f64;
            let r = if k % 2 == 0 { outer } else { inner };
            Point::new(r * a.cos(), r * a.sin())
        })
        .collect()
}

/// A rect obstacle from two opposite corners.
pub fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Shape {
    Shape::Rect(Aabb::from_corners(Point::new(x0, y0), Point::new(x1, y1)))
}

/// A grid from rows of `#` (blocked) and `.` (free), top row first.
pub fn grid(cell: f64, origin: Point, rows: &[&str]) -> Shape {
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

/// A world of `shapes` named o0, o1, … with bounds [0, 10]².
pub fn world(shapes: Vec<Shape>) -> World {
    world_in(
        Aabb {
            min: p(0.0, 0.0),
            max: p(10.0, 10.0),
        },
        shapes,
    )
}

/// A world of `shapes` named o0, o1, … within `bounds`.
pub fn world_in(bounds: Aabb, shapes: Vec<Shape>) -> World {
    World {
        bounds,
        obstacles: shapes
            .into_iter()
            .enumerate()
            .map(|(i, shape)| Obstacle {
                name: format!("o{i}"),
                shape,
            })
            .collect(),
    }
}

/// The simple polygon through `v` with its convex pieces, if it is one.
pub fn polygon_shape(v: &[Point]) -> Option<Shape> {
    let outline = polygon::normalize_simple_polygon(v).ok()?;
    let pieces = polygon::convex_decomposition(&outline);
    Some(Shape::Polygon { outline, pieces })
}

/// Random worlds for property tests (this crate's own).
#[cfg(test)]
pub(crate) mod random {
    use proptest::prelude::*;

    use super::{p, polygon_shape, rect, world};
    use crate::{Aabb, ConvexPolygon, Grid, Point, Shape, World, polygon};

    /// A small random world: convex and non-convex polygons, rects, disks,
    /// segments and a small grid, in and around [0, 10]².
    pub fn random_world() -> impl Strategy<Value = World> {
        let pt = || (0.0..10.0f64, 0.0..10.0f64).prop_map(|(x, y)| p(x, y));
        let convex = (
            pt(),
            prop::collection::vec((-1.5..1.5f64, -1.5..1.5f64), 3..8),
        )
            .prop_filter_map("flat", |(c, v)| {
                let hull = polygon::convex_hull(
                    &v.iter()
                        .map(|&(x, y)| p(c.x + x, c.y + y))
                        .collect::<Vec<_>>(),
                );
                (hull.len() >= 3).then(|| Shape::Polygon {
                    outline: hull.clone(),
                    pieces: vec![ConvexPolygon { vertices: hull }],
                })
            });
        let star = (
            pt(),
            prop::collection::vec((0.0..1.0f64, 0.3..2.0f64), 4..9),
        )
            .prop_filter_map("bad", |(c, v)| {
                let k = v.len() as f64;
                let pts: Vec<Point> = v
                    .iter()
                    .enumerate()
                    .map(|(i, &(j, r))| {
                        let a = (i as f64 + 0.8 * j) * std::f64::consts::TAU / k;
                        p(c.x + r * a.cos(), c.y + r * a.sin())
                    })
                    .collect();
                polygon_shape(&pts)
            });
        let rect =
            (pt(), 0.1..3.0f64, 0.1..3.0f64).prop_map(|(a, w, h)| rect(a.x, a.y, a.x + w, a.y + h));
        let disk = (pt(), 0.1..2.0f64).prop_map(|(c, r)| Shape::Disk {
            center: c,
            radius: r,
        });
        let wall = (pt(), pt()).prop_map(|(a, b)| Shape::Segment(a, b));
        let raster = (
            pt(),
            0.3..2.0f64,
            1..7usize,
            1..7usize,
            prop::collection::vec(prop::bool::weighted(0.45), 36),
        )
            .prop_map(|(o, cell, w, h, bits)| {
                let cells = (0..w * h)
                    .map(|i| if bits[i % 36] { 0 } else { 1 })
                    .collect();
                Shape::Grid(Grid {
                    cell,
                    origin: p(o.x - 3.0, o.y - 3.0),
                    width: w,
                    height: h,
                    cells,
                })
            });
        (
            prop::collection::vec(convex, 0..3),
            prop::collection::vec(star, 0..2),
            prop::collection::vec(rect, 0..3),
            prop::collection::vec(disk, 0..3),
            prop::collection::vec(wall, 0..3),
            prop::option::of(raster),
        )
            .prop_map(|(a, b, c, d, e, f)| {
                let shapes: Vec<Shape> = a
                    .into_iter()
                    .chain(b)
                    .chain(c)
                    .chain(d)
                    .chain(e)
                    .chain(f)
                    .collect();
                let mut w = world(shapes);
                // The validator also checks bounds; make them irrelevant.
                w.bounds = Aabb {
                    min: p(-100.0, -100.0),
                    max: p(100.0, 100.0),
                };
                w
            })
    }
}
