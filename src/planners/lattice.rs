//! The lattice of configurations shared by `astar` (and later `online`):
//! sample points in x and y (SPEC 3.1 `sample`), θ layers, and the size
//! computed before anything is allocated.

use crate::geometry::{Config, Point, RobotShape, World};
use crate::scenario::Params;

/// Where lattice points sit in each cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sample {
    /// x = xmin + (i + ½)δ
    Center,
    /// x = xmin + iδ
    Corner,
}

/// The shape of a lattice: spacing, sampling and counts per axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LatticeSpec {
    pub cell: f64,
    pub sample: Sample,
    pub x0: f64,
    pub y0: f64,
    pub nx: usize,
    pub ny: usize,
    pub layers: usize,
    /// The exact counts as floats (before any cast), for the size cap.
    nx_f: f64,
    ny_f: f64,
}

impl LatticeSpec {
    /// The lattice a plan asks for: `cell`, `sample`, `layers` (rotating
    /// robots only), over the world's bounds.
    pub fn from_params(world: &World, robot: &RobotShape, params: &Params) -> Self {
        let cell = params.num("cell").unwrap_or(1.0);
        let sample = match params.word("sample") {
            Some("corner") => Sample::Corner,
            _ => Sample::Center,
        };
        let rotating = robot.rotates() && params.word("rotate") != Some("no");
        let layers = if rotating {
            match params.num("layers") {
                Some(n) => n,
                None => (std::f64::consts::TAU * robot.radius() / cell)
                    .ceil()
                    .max(1.0),
            }
        } else {
            1.0
        };
        Self::new(world, cell, sample, layers)
    }

    pub fn new(world: &World, cell: f64, sample: Sample, layers: f64) -> Self {
        let b = world.bounds;
        let count = |extent: f64| -> f64 {
            // Points i = 0, 1, ... while x ≤ xmax (with a little slack for
            // rounding, so that 32 / 1 gives 33 corner points).
            let span = extent / cell + 1e-9;
            match sample {
                Sample::Center if span >= 0.5 => (span - 0.5).floor() + 1.0,
                Sample::Center => 0.0,
                Sample::Corner => span.floor() + 1.0,
            }
        };
        let nx_f = count(b.width());
        let ny_f = count(b.height());
        let off = match sample {
            Sample::Center => 0.5 * cell,
            Sample::Corner => 0.0,
        };
        let clamp = |v: f64| {
            if v.is_finite() && v < 1e15 {
                v as usize
            } else {
                usize::MAX
            }
        };
        LatticeSpec {
            cell,
            sample,
            x0: b.min.x + off,
            y0: b.min.y + off,
            nx: clamp(nx_f),
            ny: clamp(ny_f),
            layers: clamp(layers),
            nx_f,
            ny_f,
        }
    }

    /// The number of lattice configurations, as a float (never overflows).
    pub fn cells_f64(&self) -> f64 {
        self.nx_f * self.ny_f * self.layers as f64
    }

    /// The number of (x, y) points of one layer. Only call after the size
    /// cap was checked.
    pub fn layer_len(&self) -> usize {
        self.nx * self.ny
    }

    pub fn index(&self, i: usize, j: usize) -> usize {
        j * self.nx + i
    }

    pub fn coords(&self, index: usize) -> (usize, usize) {
        (index % self.nx, index / self.nx)
    }

    pub fn point(&self, i: usize, j: usize) -> Point {
        Point::new(
            self.x0 + i as f64 * self.cell,
            self.y0 + j as f64 * self.cell,
        )
    }

    /// The point of a node index of one layer.
    pub fn point_of(&self, index: usize) -> Point {
        let (i, j) = self.coords(index);
        self.point(i, j)
    }

    /// The nearest lattice point to `c`, if the lattice is not empty.
    pub fn snap(&self, c: Config) -> Option<(usize, usize)> {
        if self.nx == 0 || self.ny == 0 {
            return None;
        }
        let fi = ((c.x - self.x0) / self.cell)
            .round()
            .clamp(0.0, (self.nx - 1) as f64);
        let fj = ((c.y - self.y0) / self.cell)
            .round()
            .clamp(0.0, (self.ny - 1) as f64);
        Some((fi as usize, fj as usize))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Aabb;

    fn world(w: f64, h: f64) -> World {
        World {
            bounds: Aabb::from_corners(Point::new(0.0, 0.0), Point::new(w, h)),
            obstacles: vec![],
        }
    }

    #[test]
    fn counts_follow_the_sampling_rule() {
        let c = LatticeSpec::new(&world(32.0, 30.0), 1.0, Sample::Center, 1.0);
        assert_eq!((c.nx, c.ny), (32, 30));
        assert_eq!(c.point(0, 0), Point::new(0.5, 0.5));
        let k = LatticeSpec::new(&world(32.0, 30.0), 1.0, Sample::Corner, 1.0);
        assert_eq!((k.nx, k.ny), (33, 31));
        let f = LatticeSpec::new(&world(32.0, 30.0), 1.0 / 1.5, Sample::Center, 1.0);
        assert_eq!((f.nx, f.ny), (48, 45));
    }

    #[test]
    fn huge_lattices_do_not_overflow() {
        let c = LatticeSpec::new(&world(1e6, 1e6), 1e-3, Sample::Center, 1.0);
        assert!(c.cells_f64() > 1e17);
    }

    #[test]
    fn snapping_picks_the_nearest_point() {
        let c = LatticeSpec::new(&world(10.0, 10.0), 1.0, Sample::Center, 1.0);
        assert_eq!(c.snap(Config::new(4.4, 2.6, 0.0)), Some((4, 2)));
        assert_eq!(c.snap(Config::new(-3.0, 99.0, 0.0)), Some((0, 9)));
    }
}
