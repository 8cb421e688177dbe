//! Small worlds for the geometry modules' tests.

use super::{Aabb, Grid, Point, Shape};

/// A rect obstacle from two opposite corners.
pub(crate) fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Shape {
    Shape::Rect(Aabb::from_corners(Point::new(x0, y0), Point::new(x1, y1)))
}

/// A grid from rows of `#` (blocked) and `.` (free), top row first.
pub(crate) fn grid(cell: f64, origin: Point, rows: &[&str]) -> Shape {
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
