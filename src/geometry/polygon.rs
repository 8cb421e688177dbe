//! Simple polygons: normalisation, convexity, convex decomposition, hulls.
//! (stub: to be implemented)

use super::{ConvexPolygon, Point};

/// Why a vertex list is not a simple polygon.
#[derive(Clone, Debug, PartialEq)]
pub enum PolygonError {
    /// Fewer than 3 distinct, non-collinear vertices.
    TooFewVertices,
    /// The vertices enclose no area.
    ZeroArea,
    /// Edges `i` and `j` (indices into the input, edge i = v_i → v_{i+1}) cross or overlap.
    SelfIntersecting { edges: (usize, usize) },
}

/// Twice the signed area (positive when counter-clockwise).
pub fn signed_area2(points: &[Point]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            let a = points[i];
            let b = points[(i + 1) % n];
            a.x * b.y - a.y * b.x
        })
        .sum()
}

/// Removes duplicate and collinear vertices, checks that the polygon is
/// simple with non-zero area, and returns it counter-clockwise.
pub fn normalize_simple_polygon(points: &[Point]) -> Result<Vec<Point>, PolygonError> {
    let _ = points;
    todo!("normalize_simple_polygon")
}

/// Whether a counter-clockwise polygon is convex.
pub fn is_convex(ccw: &[Point]) -> bool {
    let _ = ccw;
    todo!("is_convex")
}

/// Convex pieces whose union is the polygon (counter-clockwise input).
pub fn convex_decomposition(ccw: &[Point]) -> Vec<ConvexPolygon> {
    let _ = ccw;
    todo!("convex_decomposition")
}

/// Convex hull, counter-clockwise, without collinear points.
pub fn convex_hull(points: &[Point]) -> Vec<Point> {
    let _ = points;
    todo!("convex_hull")
}
