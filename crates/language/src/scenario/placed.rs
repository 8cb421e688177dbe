//! The items a family's `scatter`s have placed so far (SPEC 2.8), and the
//! gap test a new item must pass against them.
//!
//! A spatial hash keeps the test near-constant per try, so 100 000 items
//! place in linear time instead of quadratic: items are hashed by their
//! centre into square cells whose side is at least the largest extent so
//! far plus the gap, so two items closer than the gap have centres in the
//! same or neighbouring cells, and a try looks at the 3 × 3 cells around it.
//! The hash only picks which items are measured; the test itself
//! ([`Placed::distance`] `< gap`) is the one the naive scan makes, so the
//! same tries are accepted and rejected. (The planners' [`Buckets`] are
//! built once from all boxes; here items arrive one by one.)
//!
//! [`Buckets`]: crate::geometry::buckets::Buckets

use std::collections::HashMap;

/// A scattered item: its bounding shape, for the gap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Placed {
    Disk { x: f64, y: f64, r: f64 },
    Rect { x0: f64, y0: f64, x1: f64, y1: f64 },
}

impl Placed {
    /// A lower bound of the distance between two items (exact for disks
    /// and boxes).
    pub(crate) fn distance(&self, other: &Placed) -> f64 {
        let (a0, b0, a1, b1, r) = self.boxed();
        let (c0, d0, c1, d1, s) = other.boxed();
        let dx = (c0 - a1).max(a0 - c1).max(0.0);
        let dy = (d0 - b1).max(b0 - d1).max(0.0);
        dx.hypot(dy) - r - s
    }

    /// The box (a disk's centre, twice) and the radius around it.
    fn boxed(&self) -> (f64, f64, f64, f64, f64) {
        match *self {
            Placed::Disk { x, y, r } => (x, y, x, y, r),
            Placed::Rect { x0, y0, x1, y1 } => (x0, y0, x1, y1, 0.0),
        }
    }

    fn centre(&self) -> (f64, f64) {
        let (a0, b0, a1, b1, _) = self.boxed();
        ((a0 + a1) / 2.0, (b0 + b1) / 2.0)
    }

    /// The side of the square around the centre that holds the item.
    fn extent(&self) -> f64 {
        let (a0, b0, a1, b1, r) = self.boxed();
        (a1 - a0).max(b1 - b0) + 2.0 * r
    }
}

/// The placed items, hashed by cell.
#[derive(Debug, Default)]
pub(crate) struct Placements {
    items: Vec<Placed>,
    /// The largest [`Placed::extent`] of `items`.
    largest: f64,
    /// Side of a cell; 0 before the first test.
    cell: f64,
    /// Items by the cell of their centre.
    cells: HashMap<(i64, i64), Vec<u32>>,
    /// Items whose cell is not a number (a centre or a size not finite):
    /// tested against every try, as the naive scan does.
    wild: Vec<u32>,
}

/// Cells are this much larger than needed, so that rounding in the cell
/// of a centre cannot move a near item two cells away.
const CELL_MARGIN: f64 = 1.01;

impl Placements {
    /// Whether `here` is closer than `gap` to a placed item: the same answer
    /// as `items.iter().any(|p| p.distance(here) < gap)`.
    pub(crate) fn crowds(&mut self, here: &Placed, gap: f64) -> bool {
        let need = self.largest.max(here.extent()) + gap;
        if need * CELL_MARGIN > self.cell {
            // Growing by at least doubling keeps the re-hashing linear.
            self.rehash((need * CELL_MARGIN).max(2.0 * self.cell));
        }
        let too_close = |&j: &u32| self.items[j as usize].distance(here) < gap;
        if self.wild.iter().any(too_close) {
            return true;
        }
        let Some((cx, cy)) = self.cell_of(here) else {
            return self.items.iter().any(|p| p.distance(here) < gap);
        };
        for i in cx.saturating_sub(1)..=cx.saturating_add(1) {
            for k in cy.saturating_sub(1)..=cy.saturating_add(1) {
                if self
                    .cells
                    .get(&(i, k))
                    .is_some_and(|c| c.iter().any(too_close))
                {
                    return true;
                }
            }
        }
        false
    }

    /// Adds an item (after [`Self::crowds`] said no).
    pub(crate) fn push(&mut self, item: Placed) {
        let j = self.items.len() as u32;
        self.items.push(item);
        self.largest = self.largest.max(item.extent());
        self.file(j);
    }

    fn rehash(&mut self, cell: f64) {
        self.cell = cell;
        self.cells.clear();
        self.wild.clear();
        for j in 0..self.items.len() as u32 {
            self.file(j);
        }
    }

    fn file(&mut self, j: u32) {
        match self.cell_of(&self.items[j as usize]) {
            Some(c) => self.cells.entry(c).or_default().push(j),
            None => self.wild.push(j),
        }
    }

    /// The cell of an item's centre; `None` when it is not a number (a
    /// centre, a size or the cell not finite: such an item can be near
    /// anything, as far as the distance's arithmetic goes).
    fn cell_of(&self, item: &Placed) -> Option<(i64, i64)> {
        let (x, y) = item.centre();
        let (i, k) = ((x / self.cell).floor(), (y / self.cell).floor());
        // Beyond ±2^62 cells the cast would saturate and merge cells that
        // are not neighbours; such an item is wild too.
        let fits = |v: f64| v.is_finite() && v.abs() < 4.6e18;
        (fits(i) && fits(k) && item.extent().is_finite()).then_some((i as i64, k as i64))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// A random item: disks and boxes of sizes over three orders of
    /// magnitude, in a box small enough for many near misses.
    fn item(rng: &mut SplitMix64, side: f64) -> Placed {
        let (x, y) = (rng.range(0.0, side), rng.range(0.0, side));
        let size = rng.range(0.01, 1.0) * [0.1, 1.0, 10.0][(rng.range(0.0, 3.0)) as usize % 3];
        if rng.range(0.0, 1.0) < 0.5 {
            Placed::Disk { x, y, r: size }
        } else {
            let h = rng.range(0.01, 1.0);
            Placed::Rect {
                x0: x - size,
                y0: y - h,
                x1: x + size,
                y1: y + h,
            }
        }
    }

    #[test]
    fn the_hash_decides_as_the_naive_scan() {
        let (mut rejected, mut accepted) = (0, 0);
        for seed in 0..200u64 {
            let mut rng = SplitMix64::new(seed);
            let side = rng.range(1.0, 60.0);
            let mut naive: Vec<Placed> = Vec::new();
            let mut hashed = Placements::default();
            for _ in 0..300 {
                let here = item(&mut rng, side);
                // Gaps change from try to try, as from scatter to scatter.
                let gap = [0.0, 0.1, 2.0][(rng.range(0.0, 3.0)) as usize % 3];
                let expected = naive.iter().any(|p| p.distance(&here) < gap);
                assert_eq!(
                    hashed.crowds(&here, gap),
                    expected,
                    "seed {seed}: {here:?} gap {gap}"
                );
                if expected {
                    rejected += 1;
                } else {
                    naive.push(here);
                    hashed.push(here);
                }
            }
            accepted += naive.len();
        }
        // Both answers are exercised, many times (a seed with a wide box and
        // small items may reject nothing).
        assert!(rejected > 1000 && accepted > 1000, "{rejected} {accepted}");
    }

    #[test]
    fn items_not_finite_are_measured_against_everything() {
        let mut hashed = Placements::default();
        let items = [
            Placed::Disk {
                x: f64::NAN,
                y: 0.0,
                r: 1.0,
            },
            Placed::Disk {
                x: f64::INFINITY,
                y: 0.0,
                r: 1.0,
            },
            Placed::Disk {
                x: 1e300,
                y: -1e300,
                r: 1.0,
            },
            Placed::Rect {
                x0: 0.0,
                y0: 0.0,
                x1: 1.0,
                y1: 1.0,
            },
        ];
        let mut naive: Vec<Placed> = Vec::new();
        for here in items.iter().chain(&items).chain(&items) {
            let expected = naive.iter().any(|p| p.distance(here) < 0.5);
            assert_eq!(hashed.crowds(here, 0.5), expected, "{here:?}");
            if !expected {
                naive.push(*here);
                hashed.push(*here);
            }
        }
    }
}
