//! A uniform bucket grid over boxes: the broad phase of the planners'
//! collision queries ([`super::collide`], [`super::motion`]).

use super::{Aabb, Point};

/// Indices of boxes by square bucket, in compressed rows: bucket (col, k)
/// (k from the bottom) holds `items[start[i] .. start[i + 1]]`,
/// i = k·nx + col. A box is listed in every bucket it meets; boxes outside
/// the grid are listed in the buckets of its border.
#[derive(Clone, Debug)]
pub struct Buckets {
    pub origin: Point,
    /// Side of a bucket, in world units.
    pub cell: f64,
    /// 1 / `cell`.
    pub inv: f64,
    pub nx: usize,
    pub ny: usize,
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Buckets {
    /// About four buckets per box, at most `max_side` × `max_side`, over
    /// `bounds` grown to hold every box; item `j` is `boxes[j]`.
    pub fn new(bounds: Aabb, boxes: &[Aabb], max_side: usize) -> Self {
        let max_side = max_side.max(1);
        let ext = boxes.iter().fold(bounds, |e, b| union(&e, b));
        let side = ext.width().max(ext.height());
        let per_side = ((4.0 * boxes.len() as f64).sqrt().ceil() as usize).clamp(1, max_side);
        let cell = if side > 0.0 && side.is_finite() {
            side / per_side as f64
        } else {
            1.0
        };
        let nx = ((ext.width() / cell).ceil() as usize).clamp(1, max_side);
        let ny = ((ext.height() / cell).ceil() as usize).clamp(1, max_side);
        let mut buckets = Buckets {
            origin: ext.min,
            cell,
            inv: 1.0 / cell,
            nx,
            ny,
            start: vec![0; nx * ny + 1],
            items: Vec::new(),
        };
        let ranges: Vec<_> = boxes.iter().map(|b| buckets.range(b)).collect();
        // Count, then fill.
        let mut counts = vec![0u32; nx * ny];
        for &(cols, rows) in &ranges {
            for k in rows.0..=rows.1 {
                for c in cols.0..=cols.1 {
                    counts[k * nx + c] += 1;
                }
            }
        }
        for (i, count) in counts.iter().enumerate() {
            buckets.start[i + 1] = buckets.start[i] + count;
        }
        buckets.items = vec![0; buckets.start[nx * ny] as usize];
        let mut next: Vec<u32> = buckets.start[..nx * ny].to_vec();
        for (j, &(cols, rows)) in ranges.iter().enumerate() {
            for k in rows.0..=rows.1 {
                for c in cols.0..=cols.1 {
                    let slot = &mut next[k * nx + c];
                    buckets.items[*slot as usize] = j as u32;
                    *slot += 1;
                }
            }
        }
        buckets
    }

    /// Inclusive column and row ranges of the buckets that `b` meets
    /// (clamped to the grid).
    pub fn range(&self, b: &Aabb) -> ((usize, usize), (usize, usize)) {
        // `as usize` is `floor` for the non-negative, 0 below (and for NaN):
        // `floor().max(0.0) as usize` without libm's floor.
        let index = |v: f64, o: f64, n: usize| (((v - o) / self.cell) as usize).min(n - 1);
        let cols = (
            index(b.min.x, self.origin.x, self.nx),
            index(b.max.x, self.origin.x, self.nx),
        );
        let rows = (
            index(b.min.y, self.origin.y, self.ny),
            index(b.max.y, self.origin.y, self.ny),
        );
        (cols, rows)
    }

    /// The items of bucket (col, k), k counted from the bottom.
    #[inline]
    pub fn items(&self, col: usize, k: usize) -> &[u32] {
        let i = k * self.nx + col;
        &self.items[self.start[i] as usize..self.start[i + 1] as usize]
    }
}

/// The smallest box holding both.
pub fn union(a: &Aabb, b: &Aabb) -> Aabb {
    Aabb {
        min: Point::new(a.min.x.min(b.min.x), a.min.y.min(b.min.y)),
        max: Point::new(a.max.x.max(b.max.x), a.max.y.max(b.max.y)),
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    proptest! {
        /// `range` indexes as `floor().max(0.0)` would, clamped.
        #[test]
        fn range_is_floor_clamped(
            x0 in -50.0f64..50.0, y0 in -50.0f64..50.0, w in 0.0f64..30.0, h in 0.0f64..30.0,
        ) {
            let bounds = Aabb { min: Point::new(-10.0, -10.0), max: Point::new(10.0, 20.0) };
            let boxes: Vec<Aabb> = (0..30)
                .map(|i| {
                    let p = Point::new(-10.0 + i as f64 * 0.6, -10.0 + i as f64);
                    Aabb { min: p, max: p + nalgebra::Vector2::new(1.0, 0.5) }
                })
                .collect();
            let b = Buckets::new(bounds, &boxes, 512);
            let q = Aabb { min: Point::new(x0, y0), max: Point::new(x0 + w, y0 + h) };
            let floor = |v: f64, o: f64, n: usize| {
                (((v - o) / b.cell).floor().max(0.0) as usize).min(n - 1)
            };
            let want = (
                (floor(q.min.x, b.origin.x, b.nx), floor(q.max.x, b.origin.x, b.nx)),
                (floor(q.min.y, b.origin.y, b.ny), floor(q.max.y, b.origin.y, b.ny)),
            );
            prop_assert_eq!(b.range(&q), want);
        }
    }
}
