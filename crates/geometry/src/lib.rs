//! scen's geometry: world shapes, polygons and their convex pieces, the
//! planners' collision queries and the independent validator (SPEC 3.0).
//! The lowest crate of the workspace: it knows nothing of the language,
//! the planners or the command line.
//!
//! Everything is in f64 world units; angles are radians, counter-clockwise.

pub mod boundary;
mod buckets;
pub mod car;
pub mod collide;
pub mod cspace;
/// Small worlds for tests, here and in the crates above (they build worlds
/// with these, never by parsing a scenario).
#[doc(hidden)]
pub mod fixtures;
pub mod minkowski;
pub mod motion;
pub mod path;
pub mod polygon;
pub mod proximity;
pub mod rng;
pub mod robots;
pub mod steer;
pub mod team;
pub mod timed;
pub mod union;
pub mod validator;

pub use nalgebra::{Point2, Vector2};

pub type Point = Point2<f64>;
pub type Vector = Vector2<f64>;

/// Tolerance for "touching is allowed": overlaps up to this depth are contact.
pub const TOUCH_EPS: f64 = 1e-9;

/// A configuration: the robot frame's origin at (x, y), rotated by `theta`
/// radians counter-clockwise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Config {
    pub x: f64,
    pub y: f64,
    pub theta: f64,
}

impl Config {
    pub fn new(x: f64, y: f64, theta: f64) -> Self {
        Config { x, y, theta }
    }

    pub fn xy(&self) -> Point {
        Point::new(self.x, self.y)
    }

    /// The same configuration with θ in [0, 2π) ([`wrap_angle`]).
    pub fn wrapped(self) -> Config {
        Config::new(self.x, self.y, wrap_angle(self.theta))
    }
}

/// An axis-aligned box (closed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Point,
    pub max: Point,
}

impl Aabb {
    /// The box spanned by two opposite corners, in any order.
    pub fn from_corners(a: Point, b: Point) -> Self {
        Aabb {
            min: Point::new(a.x.min(b.x), a.y.min(b.y)),
            max: Point::new(a.x.max(b.x), a.y.max(b.y)),
        }
    }

    pub fn contains(&self, p: Point) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }

    pub fn width(&self) -> f64 {
        self.max.x - self.min.x
    }

    pub fn height(&self) -> f64 {
        self.max.y - self.min.y
    }

    /// Counter-clockwise corners starting at `min`.
    pub fn corners(&self) -> [Point; 4] {
        [
            self.min,
            Point::new(self.max.x, self.min.y),
            self.max,
            Point::new(self.min.x, self.max.y),
        ]
    }

    /// The smallest box around `points` (the box of the origin alone when
    /// there are none).
    pub fn around(points: &[Point]) -> Self {
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

    /// Whether the two closed boxes share a point.
    pub fn meets(&self, other: &Aabb) -> bool {
        self.min.x <= other.max.x
            && other.min.x <= self.max.x
            && self.min.y <= other.max.y
            && other.min.y <= self.max.y
    }
}

/// A convex polygon with counter-clockwise vertices, no duplicate or
/// collinear vertices, and non-zero area.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexPolygon {
    pub vertices: Vec<Point>,
}

/// A raster of square cells (SPEC 2.3). Row 0 is the top row.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    pub cell: f64,
    /// Bottom-left corner of the raster.
    pub origin: Point,
    pub width: usize,
    pub height: usize,
    /// Row-major, row 0 first: 0 = blocked, 1..=9 = free with that weight.
    pub cells: Vec<u8>,
}

impl Grid {
    pub fn weight(&self, col: usize, row: usize) -> u8 {
        self.cells[row * self.width + col]
    }

    pub fn is_blocked(&self, col: usize, row: usize) -> bool {
        self.weight(col, row) == 0
    }

    /// The square covered by cell (col, row).
    pub fn cell_box(&self, col: usize, row: usize) -> Aabb {
        let x0 = self.origin.x + col as f64 * self.cell;
        let y0 = self.origin.y + (self.height - 1 - row) as f64 * self.cell;
        Aabb {
            min: Point::new(x0, y0),
            max: Point::new(x0 + self.cell, y0 + self.cell),
        }
    }

    /// The whole raster's extent.
    pub fn extent(&self) -> Aabb {
        Aabb {
            min: self.origin,
            max: Point::new(
                self.origin.x + self.width as f64 * self.cell,
                self.origin.y + self.height as f64 * self.cell,
            ),
        }
    }

    /// Inclusive column and row ranges of the cells whose closed squares
    /// meet `b` (empty ranges when `b` misses the grid).
    pub fn cells_overlapping(&self, b: &Aabb) -> (std::ops::Range<usize>, std::ops::Range<usize>) {
        let cx0 = ((b.min.x - self.origin.x) / self.cell).floor();
        let cx1 = ((b.max.x - self.origin.x) / self.cell).floor();
        // y grows upwards, rows downwards: row = H-1 - floor((y - oy)/cell)
        let ry0 = ((b.min.y - self.origin.y) / self.cell).floor();
        let ry1 = ((b.max.y - self.origin.y) / self.cell).floor();
        let clampc = |v: f64| v.clamp(0.0, self.width as f64) as usize;
        let clampr = |v: f64| v.clamp(0.0, self.height as f64) as usize;
        let cols = clampc(cx0)..clampc(cx1 + 1.0);
        // ybin k (from the bottom) is row H-1-k
        let k0 = clampr(ry0);
        let k1 = clampr(ry1 + 1.0);
        let rows = (self.height - k1)..(self.height - k0);
        (cols, rows)
    }
}

/// The shape of a world obstacle, normalised by the analyzer.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A simple polygon (counter-clockwise, no collinear or duplicate
    /// vertices) and its convex decomposition.
    Polygon {
        outline: Vec<Point>,
        pieces: Vec<ConvexPolygon>,
    },
    Rect(Aabb),
    /// A zero-thickness wall: no interior, but nothing may cross it.
    Segment(Point, Point),
    Disk {
        center: Point,
        radius: f64,
    },
    Grid(Grid),
}

impl Shape {
    /// The smallest closed box around the obstacle (a grid's whole extent).
    pub fn bounding_box(&self) -> Aabb {
        match self {
            Shape::Polygon { outline, .. } => Aabb::around(outline),
            Shape::Rect(r) => *r,
            Shape::Segment(a, b) => Aabb::from_corners(*a, *b),
            Shape::Disk { center, radius } => Aabb::from_corners(
                Point::new(center.x - radius, center.y - radius),
                Point::new(center.x + radius, center.y + radius),
            ),
            Shape::Grid(g) => g.extent(),
        }
    }
}

/// The shape of a robot in its own frame.
#[derive(Clone, Debug, PartialEq)]
pub enum RobotShape {
    Point,
    Disk(f64),
    /// Convex, counter-clockwise.
    Polygon(ConvexPolygon),
}

impl RobotShape {
    /// R: the largest distance from the frame origin to a point of the body.
    pub fn radius(&self) -> f64 {
        match self {
            RobotShape::Point => 0.0,
            RobotShape::Disk(r) => *r,
            RobotShape::Polygon(p) => p
                .vertices
                .iter()
                .map(|v| v.coords.norm())
                .fold(0.0, f64::max),
        }
    }

    /// Whether the body changes with θ (polygons do; points and disks don't).
    pub fn rotates(&self) -> bool {
        matches!(self, RobotShape::Polygon(_))
    }

    /// The body's vertices placed at `c` (empty for point and disk robots).
    pub fn placed_vertices(&self, c: Config) -> Vec<Point> {
        let mut placed = Vec::new();
        self.place_into(c, &mut placed);
        placed
    }

    /// [`RobotShape::placed_vertices`] written into `out` (cleared first):
    /// no allocation once `out` has room for the body's vertices.
    pub fn place_into(&self, c: Config, out: &mut Vec<Point>) {
        out.clear();
        if let RobotShape::Polygon(p) = self {
            let (s, co) = c.theta.sin_cos();
            out.extend(p.vertices.iter().map(|v| place(c, s, co, v)));
        }
    }
}

/// A named obstacle of the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Obstacle {
    pub name: String,
    pub shape: Shape,
}

/// The world: bounds for the robot's reference point, and obstacles.
#[derive(Clone, Debug, PartialEq)]
pub struct World {
    pub bounds: Aabb,
    pub obstacles: Vec<Obstacle>,
}

/// The robot-frame point `v` placed at `c`, whose angle has sine `s` and
/// cosine `co`: the one formula of every placement, so that placements
/// agree to the bit.
#[inline(always)]
pub fn place(c: Config, s: f64, co: f64, v: &Point) -> Point {
    Point::new(c.x + co * v.x - s * v.y, c.y + s * v.x + co * v.y)
}

/// The larger of `a` and `b` for values that are never NaN: one `maxsd`,
/// without `f64::max`'s care for NaN, which costs several instructions in
/// the hot loops (the sign of a zero result may differ from `f64::max`'s,
/// which comparisons do not see).
#[inline(always)]
pub fn max_of_numbers(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

/// The smaller of `a` and `b` for values that are never NaN (see
/// [`max_of_numbers`]).
#[inline(always)]
pub fn min_of_numbers(a: f64, b: f64) -> f64 {
    if a < b { a } else { b }
}

/// `theta` in [0, 2π) (`rem_euclid` of a tiny negative angle rounds up
/// to 2π itself, which becomes 0).
pub fn wrap_angle(theta: f64) -> f64 {
    let t = rem_tau(theta);
    if t >= std::f64::consts::TAU { 0.0 } else { t }
}

/// `x.rem_euclid(2π)`, bit for bit, without `fmod` for |x| < 2π (where
/// `x % 2π` is `x` itself): the angles of planning are nearly always there.
#[inline]
fn rem_tau(x: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    if x > -tau && x < tau {
        if x < 0.0 { x + tau } else { x }
    } else {
        x.rem_euclid(tau)
    }
}

/// Shortest signed angular difference `b - a`, in (-π, π].
///
/// ```
/// use scen_geometry::angle_diff;
/// use std::f64::consts::PI;
/// // From 350° to 10° is +20°, the shorter way round.
/// let d = angle_diff(350f64.to_radians(), 10f64.to_radians());
/// assert!((d - 20f64.to_radians()).abs() < 1e-12);
/// assert_eq!(angle_diff(0.0, PI), PI);
/// ```
pub fn angle_diff(a: f64, b: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let mut d = rem_tau(b - a);
    if d > std::f64::consts::PI {
        d -= tau;
    }
    d
}

/// The sine and cosine of `x`, within an ulp or two of `f64::sin_cos`'s
/// (tested): the motion checker's placements, a branch-free polynomial
/// where libm's `sincos` costs a call and several branches. fdlibm's
/// kernels (`__kernel_sin`, `__kernel_cos`, minimax on [−π/4, π/4]) after
/// a reduction by the nearest multiple of π/2 in two parts (the first of
/// 33 bits, so that its product with the multiple is exact); beyond
/// |x| = 2²⁰ and for non-finite `x`, libm's.
#[inline]
pub fn sin_cos_fast(x: f64) -> (f64, f64) {
    const PIO2_1: f64 = 1.570_796_326_734_125_6; // the first 33 bits of π/2
    const PIO2_1T: f64 = 6.077_100_506_506_192e-11; // π/2 − PIO2_1
    const SHIFT: f64 = 6_755_399_441_055_744.0; // 1.5·2⁵²: rounds to an integer
    const S: [f64; 6] = [
        -1.666_666_666_666_663_2e-1,
        8.333_333_333_322_49e-3,
        -1.984_126_982_985_795e-4,
        2.755_731_370_707_006_8e-6,
        -2.505_076_025_340_686_3e-8,
        1.589_690_995_211_55e-10,
    ];
    const C: [f64; 6] = [
        4.166_666_666_666_66e-2,
        -1.388_888_888_887_411e-3,
        2.480_158_728_947_673e-5,
        -2.755_731_435_139_066_3e-7,
        2.087_572_321_298_175e-9,
        -1.135_964_755_778_819_5e-11,
    ];
    if x.abs() >= 1_048_576.0 || x.is_nan() {
        return x.sin_cos();
    }
    let shifted = x * std::f64::consts::FRAC_2_PI + SHIFT;
    let quadrant = shifted.to_bits() & 3;
    let k = shifted - SHIFT;
    let r = (x - k * PIO2_1) - k * PIO2_1T;
    let z = r * r;
    let sin_r = {
        let p = S[1] + z * (S[2] + z * (S[3] + z * (S[4] + z * S[5])));
        r + z * r * (S[0] + z * p)
    };
    let cos_r = {
        let p = z * (C[0] + z * (C[1] + z * (C[2] + z * (C[3] + z * (C[4] + z * C[5])))));
        let hz = 0.5 * z;
        let w = 1.0 - hz;
        w + (((1.0 - w) - hz) + z * p)
    };
    match quadrant {
        0 => (sin_r, cos_r),
        1 => (cos_r, -sin_r),
        2 => (-sin_r, -cos_r),
        _ => (-cos_r, sin_r),
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::{rem_tau, sin_cos_fast};

    /// ulps between two finite floats of the same sign (or both tiny).
    fn ulps(a: f64, b: f64) -> u64 {
        if a == b {
            return 0;
        }
        let key = |x: f64| {
            let bits = x.to_bits() as i64;
            if bits < 0 { i64::MIN - bits } else { bits }
        };
        key(a).abs_diff(key(b))
    }

    #[test]
    fn sin_cos_fast_is_within_two_ulps_of_libm() {
        let mut rng = crate::rng::SplitMix64::new(7);
        let quarter = std::f64::consts::FRAC_PI_4;
        let mut xs: Vec<f64> = (-64..=64).map(|k| k as f64 * quarter).collect();
        xs.extend([0.0, -0.0, 1e-300, -1e-300, 1e-9, 3.0e5, -7.5e5, 1048575.9]);
        xs.extend((0..200_000).map(|_| rng.range(-50.0, 50.0)));
        xs.extend((0..20_000).map(|_| rng.range(-1e6, 1e6)));
        let mut worst = 0;
        for x in xs {
            let (s, c) = sin_cos_fast(x);
            let (ls, lc) = x.sin_cos();
            // Near a zero of the function an ulp is tiny: compare there
            // within 2⁻⁵³ of the magnitude 1 instead.
            for (f, l) in [(s, ls), (c, lc)] {
                if l.abs() < 1e-3 {
                    assert!((f - l).abs() <= 2.3e-16, "{x}: {f} against {l}");
                } else {
                    let u = ulps(f, l);
                    worst = worst.max(u);
                    assert!(u <= 2, "{x}: {f} against {l} ({u} ulps)");
                }
            }
        }
        for x in [f64::NAN, f64::INFINITY, -f64::INFINITY, 2e6, -1e300] {
            let (s, c) = sin_cos_fast(x);
            let (ls, lc) = x.sin_cos();
            assert_eq!(
                (s.to_bits(), c.to_bits()),
                (ls.to_bits(), lc.to_bits()),
                "{x}"
            );
        }
        assert!(worst <= 2);
    }

    #[test]
    fn rem_tau_is_rem_euclid_at_the_edges() {
        let tau = std::f64::consts::TAU;
        for x in [
            0.0,
            -0.0,
            1e-300,
            -1e-300,
            tau,
            -tau,
            tau.next_down(),
            (-tau).next_up(),
            3.0 * tau,
            -7.5,
            f64::INFINITY,
            f64::NAN,
        ] {
            assert_eq!(rem_tau(x).to_bits(), x.rem_euclid(tau).to_bits(), "{x}");
        }
    }

    proptest! {
        #[test]
        fn rem_tau_is_rem_euclid(x in -20.0f64..20.0) {
            let tau = std::f64::consts::TAU;
            prop_assert_eq!(rem_tau(x).to_bits(), x.rem_euclid(tau).to_bits());
        }
    }
}
