//! The lattice of configurations shared by `astar` and `online`: sample
//! points in x and y (SPEC 3.1 `sample`), θ layers, the size computed
//! before anything is allocated, and the parameters and checks both
//! planners share (`cell`, `sample`, `connect`, the size cap).

use crate::diagnostics::Diag;
use crate::geometry::{Config, Point, World};
use crate::scenario::schema::{DefaultValue, ParamSpec, ValueSpec, num};
use crate::scenario::{DEFAULT_CELL_CAP, PlanArgs};
use crate::word_enum;

word_enum! {
    /// Where lattice points sit in each cell.
    pub enum Sample {
        /// x = xmin + (i + ½)δ
        Center = "center",
        /// x = xmin + iδ
        Corner = "corner",
    }
}

/// `cell`, `sample` and `connect`: the lattice parameters of `astar` and
/// `online`.
pub const LATTICE_PARAMS: [ParamSpec; 3] = [
    ParamSpec::positive("cell", num(1.0, "1"), "lattice spacing δ in x and y"),
    ParamSpec::word(
        "sample",
        <Sample as crate::scenario::schema::Word>::WORDS,
        "center",
        "lattice points at cell centres or corners",
    ),
    ParamSpec::new(
        "connect",
        ValueSpec::IntChoice(&[4, 8, 6, 26]),
        DefaultValue::Derived("8 (26 for rotating robots)"),
        "lattice neighbours: 4 or 8 in (x, y), 6 or 26 in (x, y, θ)",
    ),
];

/// `connect` as given, checked against the lattice: 4 or 8 on an (x, y)
/// lattice, 6 or 26 on a rotating robot's (x, y, θ) lattice; the default
/// is 8, or 26 when `rotating`. `None` after reporting a bad value.
pub fn check_connect(args: &mut PlanArgs<'_>, rotating: bool) -> Option<u8> {
    let Some(x) = args.opt_num("connect") else {
        return Some(if rotating { 26 } else { 8 });
    };
    let polygon = args.robot.shape.rotates();
    let (ok, list, lattice, help) = match (rotating, polygon) {
        (true, _) => (
            x == 6.0 || x == 26.0,
            "`6` or `26`",
            " for a rotating robot's (x, y, θ) lattice",
            "use `connect 6` or `connect 26`, or add `rotate no` to plan in (x, y) at the start's θ"
                .to_string(),
        ),
        (false, true) => (
            x == 4.0 || x == 8.0,
            "`4` or `8`",
            " with `rotate no` (an (x, y) lattice at the start's θ)",
            "use `connect 4` or `connect 8`, or remove `rotate no`".to_string(),
        ),
        (false, false) => (
            x == 4.0 || x == 8.0,
            "`4` or `8`",
            " for an (x, y) lattice",
            format!("`connect`: {}", args.spec("connect").help),
        ),
    };
    if ok {
        return Some(x as u8);
    }
    let span = args.span("connect");
    args.error(
        Diag::error(
            "scen::analyze::out_of_range",
            format!("`connect` must be {list}{lattice}, got {x}"),
        )
        .at(span, "not accepted")
        .help(help),
    );
    None
}

/// The lattice a plan asks for (`cell`, `sample`, `layers` θ layers over
/// the world's bounds), refused before anything is allocated when it
/// exceeds the cap (`limit cells N`, default [`DEFAULT_CELL_CAP`]).
pub fn check_lattice(args: &mut PlanArgs<'_>, layers: f64) -> Option<LatticeSpec> {
    let spec = LatticeSpec::new(args.world, args.num("cell"), args.word("sample"), layers);
    let cap = args.params.limits.cells.unwrap_or(DEFAULT_CELL_CAP);
    let cells = spec.cells_f64();
    if cells > cap as f64 {
        let at = args.span("cell");
        let plan = args.plan;
        args.error(
            Diag::error(
                "scen::analyze::lattice_too_large",
                format!(
                    "the lattice of plan `{plan}` would have {cells:.3e} cells, over the cap of {cap}"
                ),
            )
            .at(at, format!("{} × {} × {} layers", spec.nx, spec.ny, spec.layers))
            .help("use a larger `cell` (or fewer `layers`), or raise the cap with `limit cells N`"),
        );
        return None;
    }
    Some(spec)
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
