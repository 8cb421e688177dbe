//! The boundary of a union of convex polygons, for drawing (the C-space of
//! one θ layer as one outline rather than overlapping C-obstacles).
//!
//! Each polygon edge keeps the parts that lie neither in the interior of
//! another polygon nor on an edge of another polygon running the opposite
//! way (two polygons side by side: their common edge is inside the union).
//! Of several collinear edges running the same way over the same stretch,
//! only the one of the lowest-indexed polygon is kept, so nothing is drawn
//! twice. Exact up to a tolerance of `1e-9` relative to the world's size.

use super::{Point, Vector};

/// Boundary segments of the union of the convex counter-clockwise polygons
/// `polys` (polygons with fewer than 3 vertices are ignored).
pub fn union_boundary(polys: &[Vec<Point>]) -> Vec<(Point, Point)> {
    let boxes: Vec<Option<(Point, Point)>> = polys.iter().map(|p| bounds(p)).collect();
    let scale = boxes
        .iter()
        .flatten()
        .map(|(lo, hi)| (hi.x - lo.x).max(hi.y - lo.y).max(lo.coords.abs().max()))
        .fold(1.0, f64::max);
    let eps = 1e-9 * scale;
    let grid = Buckets::new(&boxes);
    let mut stamp = vec![0usize; polys.len()];
    let mut candidates = Vec::new();
    let mut tag = 0usize;

    let mut out = Vec::new();
    let mut removed: Vec<(f64, f64)> = Vec::new();
    for (i, poly) in polys.iter().enumerate() {
        if boxes[i].is_none() {
            continue;
        }
        for e in 0..poly.len() {
            let (p, q) = (poly[e], poly[(e + 1) % poly.len()]);
            let d = q - p;
            let len2 = d.norm_squared();
            if len2 <= eps * eps {
                continue;
            }
            let lo = Point::new(p.x.min(q.x) - eps, p.y.min(q.y) - eps);
            let hi = Point::new(p.x.max(q.x) + eps, p.y.max(q.y) + eps);
            tag += 1;
            grid.candidates(lo, hi, &mut stamp, tag, &mut candidates);
            removed.clear();
            for &j in &candidates {
                let Some((blo, bhi)) = boxes[j] else { continue };
                if j == i || bhi.x < lo.x || blo.x > hi.x || bhi.y < lo.y || blo.y > hi.y {
                    continue;
                }
                let other = &polys[j];
                if let Some(span) = interior_span(p, d, other, eps) {
                    removed.push(span);
                }
                for f in 0..other.len() {
                    let (a, b) = (other[f], other[(f + 1) % other.len()]);
                    if let Some(span) = shared_span(p, d, len2, a, b, eps) {
                        let opposite = (b - a).dot(&d) < 0.0;
                        if opposite || j < i {
                            removed.push(span);
                        }
                    }
                }
            }
            for (t0, t1) in remaining(&mut removed) {
                out.push((p + d * t0, p + d * t1));
            }
        }
    }
    out
}

/// A uniform grid of buckets over the polygons' boxes, about one polygon
/// per bucket.
struct Buckets {
    lo: Point,
    size: f64,
    nx: usize,
    ny: usize,
    /// Per bucket, the polygons whose box meets it.
    items: Vec<Vec<usize>>,
}

impl Buckets {
    fn new(boxes: &[Option<(Point, Point)>]) -> Self {
        let mut lo = Point::new(f64::INFINITY, f64::INFINITY);
        let mut hi = Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
        let mut n = 0usize;
        for (blo, bhi) in boxes.iter().flatten() {
            lo = Point::new(lo.x.min(blo.x), lo.y.min(blo.y));
            hi = Point::new(hi.x.max(bhi.x), hi.y.max(bhi.y));
            n += 1;
        }
        if n == 0 {
            return Buckets {
                lo: Point::origin(),
                size: 1.0,
                nx: 0,
                ny: 0,
                items: Vec::new(),
            };
        }
        let side = (n as f64).sqrt().ceil().clamp(1.0, 1024.0);
        let size = ((hi.x - lo.x).max(hi.y - lo.y) / side).max(1e-12);
        let nx = (((hi.x - lo.x) / size).floor() as usize + 1).min(1025);
        let ny = (((hi.y - lo.y) / size).floor() as usize + 1).min(1025);
        let mut grid = Buckets {
            lo,
            size,
            nx,
            ny,
            items: vec![Vec::new(); nx * ny],
        };
        for (k, b) in boxes.iter().enumerate() {
            if let Some((blo, bhi)) = b {
                let (x0, y0) = grid.cell(*blo);
                let (x1, y1) = grid.cell(*bhi);
                for y in y0..=y1 {
                    for x in x0..=x1 {
                        grid.items[y * nx + x].push(k);
                    }
                }
            }
        }
        grid
    }

    fn cell(&self, p: Point) -> (usize, usize) {
        let x = ((p.x - self.lo.x) / self.size).floor().max(0.0) as usize;
        let y = ((p.y - self.lo.y) / self.size).floor().max(0.0) as usize;
        (
            x.min(self.nx.saturating_sub(1)),
            y.min(self.ny.saturating_sub(1)),
        )
    }

    /// The polygons whose buckets meet the box `lo`–`hi`, each once
    /// (`stamp` remembers which were seen under `tag`).
    fn candidates(
        &self,
        lo: Point,
        hi: Point,
        stamp: &mut [usize],
        tag: usize,
        out: &mut Vec<usize>,
    ) {
        out.clear();
        if self.items.is_empty() {
            return;
        }
        let (x0, y0) = self.cell(lo);
        let (x1, y1) = self.cell(hi);
        for y in y0..=y1 {
            for x in x0..=x1 {
                for &k in &self.items[y * self.nx + x] {
                    if stamp[k] != tag {
                        stamp[k] = tag;
                        out.push(k);
                    }
                }
            }
        }
    }
}

fn bounds(poly: &[Point]) -> Option<(Point, Point)> {
    if poly.len() < 3 {
        return None;
    }
    let mut lo = poly[0];
    let mut hi = poly[0];
    for v in poly {
        lo = Point::new(lo.x.min(v.x), lo.y.min(v.y));
        hi = Point::new(hi.x.max(v.x), hi.y.max(v.y));
    }
    Some((lo, hi))
}

/// The open parameter interval of `p + t·d`, t in [0, 1], that lies deeper
/// than `eps` inside the convex counter-clockwise polygon `poly`.
fn interior_span(p: Point, d: Vector, poly: &[Point], eps: f64) -> Option<(f64, f64)> {
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        let e = b - a;
        let len = e.norm();
        if len == 0.0 {
            continue;
        }
        // Inward normal of a counter-clockwise edge, unit length.
        let n = Vector::new(-e.y, e.x) / len;
        // Inside when n·(p + t d − a) > eps.
        let c = n.dot(&(p - a)) - eps;
        let s = n.dot(&d);
        if s.abs() < 1e-300 {
            if c <= 0.0 {
                return None;
            }
        } else if s > 0.0 {
            t0 = t0.max(-c / s);
        } else {
            t1 = t1.min(-c / s);
        }
        if t0 >= t1 {
            return None;
        }
    }
    Some((t0, t1))
}

/// The parameter interval of `p + t·d` that the segment `a b` covers when
/// both lie on one line (within `eps`), if they overlap over more than a
/// point.
fn shared_span(p: Point, d: Vector, len2: f64, a: Point, b: Point, eps: f64) -> Option<(f64, f64)> {
    let len = len2.sqrt();
    let off = |x: Point| (d.x * (x.y - p.y) - d.y * (x.x - p.x)) / len;
    if off(a).abs() > eps || off(b).abs() > eps {
        return None;
    }
    let ta = (a - p).dot(&d) / len2;
    let tb = (b - p).dot(&d) / len2;
    let (lo, hi) = (ta.min(tb).max(0.0), ta.max(tb).min(1.0));
    (hi - lo > eps / len).then_some((lo, hi))
}

/// The parts of [0, 1] not covered by `removed` (sorted in place), leaving
/// out slivers shorter than 1e-12.
fn remaining(removed: &mut [(f64, f64)]) -> Vec<(f64, f64)> {
    removed.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut kept = Vec::new();
    let mut at = 0.0f64;
    for &(lo, hi) in removed.iter() {
        if lo > at + 1e-12 {
            kept.push((at, lo.min(1.0)));
        }
        at = at.max(hi);
        if at >= 1.0 {
            break;
        }
    }
    if at < 1.0 - 1e-12 {
        kept.push((at, 1.0));
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x0: f64, y0: f64, s: f64) -> Vec<Point> {
        vec![
            Point::new(x0, y0),
            Point::new(x0 + s, y0),
            Point::new(x0 + s, y0 + s),
            Point::new(x0, y0 + s),
        ]
    }

    fn total_length(segs: &[(Point, Point)]) -> f64 {
        segs.iter().map(|(a, b)| (b - a).norm()).sum()
    }

    #[test]
    fn one_polygon_is_its_own_boundary() {
        let segs = union_boundary(&[square(0.0, 0.0, 2.0)]);
        assert_eq!(segs.len(), 4);
        assert!((total_length(&segs) - 8.0).abs() < 1e-12);
    }

    #[test]
    fn overlapping_squares_give_the_outline_of_their_union() {
        // Two 2×2 squares overlapping in a 1×1 square: an L-shaped octagon
        // of perimeter 12.
        let segs = union_boundary(&[square(0.0, 0.0, 2.0), square(1.0, 1.0, 2.0)]);
        assert!((total_length(&segs) - 12.0).abs() < 1e-6, "{segs:?}");
        // No kept piece lies inside the other square.
        for (a, b) in &segs {
            let m = Point::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0);
            let inside_both = (m.x > 1.0 && m.x < 2.0) && (m.y > 1.0 && m.y < 2.0);
            assert!(!inside_both, "{m:?}");
        }
    }

    #[test]
    fn a_shared_edge_between_neighbours_disappears() {
        // Side by side: the union is a 4×2 rectangle, perimeter 12.
        let segs = union_boundary(&[square(0.0, 0.0, 2.0), square(2.0, 0.0, 2.0)]);
        assert!((total_length(&segs) - 12.0).abs() < 1e-6, "{segs:?}");
    }

    #[test]
    fn identical_polygons_are_drawn_once() {
        let segs = union_boundary(&[square(0.0, 0.0, 2.0), square(0.0, 0.0, 2.0)]);
        assert!((total_length(&segs) - 8.0).abs() < 1e-6, "{segs:?}");
    }

    #[test]
    fn a_polygon_inside_another_vanishes() {
        let segs = union_boundary(&[square(0.0, 0.0, 4.0), square(1.0, 1.0, 1.0)]);
        assert!((total_length(&segs) - 16.0).abs() < 1e-6, "{segs:?}");
    }

    #[test]
    fn degenerate_polygons_are_ignored() {
        let segs = union_boundary(&[vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0)]]);
        assert!(segs.is_empty());
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(500))]
        /// Integer rectangles: the union's perimeter equals the number of
        /// unit edges between a covered and an uncovered unit cell.
        #[test]
        fn perimeter_of_integer_rectangles_matches_a_raster(
            rects in proptest::collection::vec((0i32..8, 0i32..8, 1i32..5, 1i32..5), 1..7)
        ) {
            let polys: Vec<Vec<Point>> = rects
                .iter()
                .map(|&(x, y, w, h)| {
                    vec![
                        Point::new(x as f64, y as f64),
                        Point::new((x + w) as f64, y as f64),
                        Point::new((x + w) as f64, (y + h) as f64),
                        Point::new(x as f64, (y + h) as f64),
                    ]
                })
                .collect();
            let covered = |cx: i32, cy: i32| {
                rects.iter().any(|&(x, y, w, h)| cx >= x && cx < x + w && cy >= y && cy < y + h)
            };
            let mut unit_edges = 0;
            for cx in -1..14 {
                for cy in -1..14 {
                    if covered(cx, cy) != covered(cx + 1, cy) {
                        unit_edges += 1;
                    }
                    if covered(cx, cy) != covered(cx, cy + 1) {
                        unit_edges += 1;
                    }
                }
            }
            let segs = union_boundary(&polys);
            proptest::prop_assert!((total_length(&segs) - unit_edges as f64).abs() < 1e-6);
        }
    }
}
