//! Spanning Tree Coverage (SPEC 3.5, SEEDS.md §F).
//!
//! The `on` grid is resampled to D-cells (side D = `tool`, a multiple `k` of
//! the grid's cell) and then to mega-cells of 2 × 2 D-cells, both aligned
//! with the grid's bottom-left corner; cells cut by the top or right edge
//! count as blocked, and so do D-cells that another obstacle of the world
//! overlaps ([`Others`]): the robot fits in its D-cell, so the tour's moves
//! between free D-cells then stay clear of every obstacle. Prim's algorithm
//! grows a minimum spanning tree of the 4-connected free mega-cells from
//! the start's mega-cell (ties: lowest
//! row, rows counted from the top as in the grid, then lowest column). The
//! tour circumnavigates the tree counter-clockwise, keeping the tree on its
//! left: inside a mega-cell the robot goes round its four D-cells
//! counter-clockwise, and where a tree edge leaves the side it would walk
//! along, it crosses into the neighbour instead. Every D-cell of every tree
//! mega-cell is visited exactly once and the tour ends where it began.
//!
//! D-cells are indexed `(i, j)` with `i` the column from the left and `j`
//! the row from the bottom.

use std::any::Any;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::time::Instant;

use crate::contract::PlanArgs;
use crate::contract::schema::{DefaultValue, MetricSpec, ParamSpec, RobotKind, ValueSpec, Word};
use crate::diagnostics::Diag;
use crate::geometry::collide::{box_overlaps, segment_meets_open_box};
use crate::geometry::{Aabb, Config, Grid, Point, RobotShape, Shape, World};
use crate::word_enum;

use super::deadline::{Deadline, setup_note};
use crate::contract::layers::{Colour, Drawing, Layer, Style, Svg};
use crate::contract::{MetricValue, PlanOutcome};
use crate::contract::{Planner, Settings, Task};

/// `coverage` in the registry.
pub static PLANNER: Planner = Planner {
    kind: "coverage",
    summary: "spanning tree coverage of a grid",
    robots: &[RobotKind::Disk, RobotKind::Polygon],
    params: &[
        ParamSpec::new(
            "on",
            ValueSpec::ObstacleName,
            DefaultValue::None,
            "the `grid` obstacle to cover",
        ),
        ParamSpec::positive(
            "tool",
            DefaultValue::Derived("the grid's cell"),
            "side D of the square the robot covers",
        ),
        ParamSpec::word(
            "weights",
            EdgeWeights::WORDS,
            "max",
            "mega-cell edge weights",
        ),
    ],
    metrics: &[
        MetricSpec::num(
            "coverage",
            "visited D-cells / D-cells of the free mega-cells reachable from the start (0..1)",
        ),
        MetricSpec::num(
            "cells_total",
            "D-cells of the free mega-cells reachable from the start",
        ),
        MetricSpec::num("cells_visited", "D-cells the tour visits"),
        MetricSpec::num("revisits", "visits to a D-cell already visited (0 for STC)"),
        MetricSpec::bool("returns_to_start", "the tour ends in the start's D-cell"),
        MetricSpec::num(
            "uncovered",
            "free D-cells in partly blocked mega-cells, which STC cannot cover",
        ),
        MetricSpec::num("tree_edges", "edges of the spanning tree"),
        MetricSpec::num("tree_weight", "total weight of the spanning tree"),
    ],
    limits: &["expansions", "time"],
    needs_goal: false,
    randomized: false,
    grids: true,
    time: false,
    check,
};

/// The settings of a `coverage` plan.
#[derive(Clone, Debug)]
pub struct Coverage {
    /// Index of the `on` grid in `world.obstacles`.
    pub on: usize,
    /// Grid cells per D-cell side (`tool` / the grid's cell).
    pub k: usize,
    pub weights: EdgeWeights,
}

/// `on` names a grid, `tool` is a multiple of its cell and holds the
/// robot's footprint, and the start (when it is valid at all) lies in a
/// free D-cell of a free mega-cell (SPEC 3.5).
fn check(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    let world = args.world;
    let Some(name) = args.name("on") else {
        let grid = world
            .obstacles
            .iter()
            .find(|o| matches!(o.shape, Shape::Grid(_)))
            .map(|o| o.name.as_str());
        let head = args.head;
        args.error(
            Diag::error(
                "scen::analyze::missing_key",
                "a `coverage` plan needs `on`, the grid to cover",
            )
            .at(head, "needs `on`")
            .help(match grid {
                Some(g) => format!("add `on {g}` to the plan's block"),
                None => "add a `grid` obstacle to the world and name it with `on NAME`".into(),
            }),
        );
        return None;
    };
    let on_span = args.span("on");
    let Some(on) = world.obstacles.iter().position(|o| o.name == name) else {
        args.error(
            Diag::error(
                "scen::analyze::unknown_obstacle",
                format!("unknown obstacle `{name}`"),
            )
            .at(on_span, "no obstacle of this name")
            .help("name a `grid` obstacle of the world"),
        );
        return None;
    };
    let Shape::Grid(grid) = &world.obstacles[on].shape else {
        args.error(
            Diag::error(
                "scen::analyze::not_a_grid",
                format!("obstacle `{name}` is not a `grid`"),
            )
            .at(on_span, "not a grid")
            .help("`coverage` covers the free cells of a `grid` obstacle"),
        );
        return None;
    };
    let tool = args.opt_num("tool").unwrap_or(grid.cell);
    let tool_span = args.span("tool");
    let k = (tool / grid.cell).round();
    if (tool / grid.cell - k).abs() > 1e-9 * k.max(1.0) || k < 1.0 {
        args.error(
            Diag::error(
                "scen::analyze::tool_not_multiple",
                format!(
                    "`tool` {tool} is not a multiple of grid `{name}`'s cell {}",
                    grid.cell
                ),
            )
            .at(tool_span, "not a multiple of the cell")
            .help(format!(
                "use a whole number of cells, e.g. `tool {}`",
                grid.cell * k.max(1.0)
            )),
        );
        return None;
    }
    let half = tool / 2.0 + 1e-9;
    let start = args.params.start;
    let robot = args.robot;
    let fits = match &robot.shape {
        RobotShape::Disk(r) => *r <= half,
        shape => shape
            .placed_vertices(Config::new(0.0, 0.0, start.theta))
            .iter()
            .all(|v| v.x.abs() <= half && v.y.abs() <= half),
    };
    if !fits {
        args.error(
            Diag::error(
                "scen::analyze::robot_exceeds_tool",
                format!(
                    "robot `{}` does not fit in a {tool} × {tool} D-cell centred on its frame origin",
                    robot.name
                ),
            )
            .at(tool_span, "the D-cell side")
            .with_related(robot.span, "the robot")
            .help("the tour puts the robot's frame origin at D-cell centres: use a larger `tool`, or a smaller robot centred on its origin"),
        );
        return None;
    }
    let k = k as usize;
    if args.start_valid {
        let others = Others::new(world, grid);
        if let Err(e) = start_cell(grid, &others, k, start.xy()) {
            let start_span = args.params.start_span;
            args.error(
                Diag::error(
                    "scen::analyze::coverage_start",
                    format!("the start {}", e.message(world, name)),
                )
                .at(start_span, "cannot start a coverage tour here")
                .help(format!(
                    "put the start inside a free {tool} × {tool} D-cell whose 2 × 2 mega-cell is free, within the grid from ({}, {}) to ({}, {})",
                    grid.origin.x,
                    grid.origin.y,
                    grid.extent().max.x,
                    grid.extent().max.y
                )),
            );
            return None;
        }
    }
    Some(Box::new(Coverage {
        on,
        k,
        weights: args.word("weights"),
    }))
}

impl Settings for Coverage {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        plan(task, self)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// The most boxes or edges of each kind kept in the trace for drawing; the
/// metrics always count everything.
pub const MAX_TRACED: usize = 100_000;

word_enum! {
    /// How mega-cell weights combine into an edge weight (`weights`).
    pub enum EdgeWeights {
        /// max(w_i, w_j), as in the seed.
        Max = "max",
        /// w_i + w_j.
        Sum = "sum",
    }
}

impl EdgeWeights {
    pub fn edge(self, a: u8, b: u8) -> u32 {
        match self {
            EdgeWeights::Max => u32::from(a.max(b)),
            EdgeWeights::Sum => u32::from(a) + u32::from(b),
        }
    }
}

/// The weight of D-cell `(i, j)` of `grid` resampled by `k` grid cells per
/// D-cell side: 0 when any underlying cell is blocked or the D-cell is cut
/// by the grid's edge, else the largest underlying weight.
pub fn dcell_weight(grid: &Grid, k: usize, i: usize, j: usize) -> u8 {
    let (c0, b0) = (i * k, j * k); // b counts grid rows from the bottom
    if c0 + k > grid.width || b0 + k > grid.height {
        return 0;
    }
    let mut w = u8::MAX;
    let mut heaviest = 0;
    for b in b0..b0 + k {
        let row = grid.height - 1 - b;
        for &x in &grid.cells[row * grid.width + c0..row * grid.width + c0 + k] {
            w = w.min(x);
            heaviest = heaviest.max(x);
        }
    }
    if w == 0 { 0 } else { heaviest }
}

/// Why a point cannot start a coverage tour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StartProblem {
    /// Not inside a whole D-cell of the grid.
    OutsideGrid,
    /// Its D-cell has a blocked cell.
    Blocked,
    /// Its D-cell is free but its mega-cell is not (partly blocked, or cut
    /// by the grid's edge): STC cannot cover from there.
    MegaCellBlocked,
    /// Another obstacle of the world (its index) overlaps its D-cell or
    /// another D-cell of its mega-cell.
    Overlapped(usize),
    /// A D-cell of its mega-cell has its centre outside the world's bounds
    /// (where the tour could not take the robot).
    BeyondBounds,
}

impl StartProblem {
    /// What is wrong, after "the start": `grid` names the grid covered.
    pub fn message(self, world: &World, grid: &str) -> String {
        match self {
            StartProblem::OutsideGrid => format!("lies outside the whole D-cells of grid `{grid}`"),
            StartProblem::Blocked => format!("lies in a blocked D-cell of grid `{grid}`"),
            StartProblem::MegaCellBlocked => format!(
                "lies in a free D-cell of a partly blocked mega-cell of grid `{grid}`, which STC cannot cover"
            ),
            StartProblem::Overlapped(o) => format!(
                "lies in a mega-cell of grid `{grid}` that obstacle `{}` overlaps, which STC cannot cover",
                world.obstacles.get(o).map_or("?", |o| o.name.as_str())
            ),
            StartProblem::BeyondBounds => format!(
                "lies in a mega-cell of grid `{grid}` that reaches past the world's bounds: a D-cell whose centre lies outside `bounds` counts as blocked"
            ),
        }
    }
}

/// What blocks D-cells besides the grid's own cells: the other obstacles
/// of the world, with their bounding boxes (each blocks the D-cells it
/// overlaps, [`box_overlaps`]: more than touching, or a wall meeting the
/// D-cell), and the world's bounds (a D-cell whose centre lies outside
/// them is blocked: the tour visits D-cell centres, and the robot's
/// reference point must stay in `bounds`, SPEC 3.0).
pub struct Others<'w> {
    items: Vec<(usize, &'w Shape, Aabb)>,
    bounds: Option<Aabb>,
}

impl<'w> Others<'w> {
    /// Every obstacle of `world` but the grid `on` (found by identity).
    pub fn new(world: &'w World, on: &Grid) -> Self {
        let items = world
            .obstacles
            .iter()
            .enumerate()
            .filter(|(_, o)| !matches!(&o.shape, Shape::Grid(g) if std::ptr::eq(g, on)))
            .map(|(i, o)| (i, &o.shape, o.shape.bounding_box()))
            .collect();
        Others {
            items,
            bounds: Some(world.bounds),
        }
    }

    /// No obstacle besides the grid, and no bounds.
    pub fn none() -> Self {
        Others {
            items: Vec::new(),
            bounds: None,
        }
    }

    /// Whether a D-cell centred at `c` lies outside the bounds.
    fn beyond_bounds(&self, c: Point) -> bool {
        self.bounds.is_some_and(|b| !b.contains(c))
    }

    /// The walls among them: (obstacle, a, b).
    fn walls(&self) -> impl Iterator<Item = (usize, Point, Point)> + '_ {
        self.items.iter().filter_map(|&(i, shape, _)| match *shape {
            Shape::Segment(a, b) => Some((i, a, b)),
            _ => None,
        })
    }

    /// The first wall that meets the open box `b` (a mega-cell: a wall
    /// between two of its D-cells blocks the tour inside it).
    pub fn wall_inside(&self, b: &Aabb) -> Option<usize> {
        self.walls()
            .find(|&(_, p, q)| segment_meets_open_box(p, q, b.min, b.max))
            .map(|(i, ..)| i)
    }

    /// The first obstacle that blocks the D-cell `b`.
    pub fn blocker(&self, b: &Aabb) -> Option<usize> {
        self.items
            .iter()
            .find(|(_, shape, bb)| bb.meets(b) && box_overlaps(b, shape))
            .map(|&(i, ..)| i)
    }
}

/// The square `(i, j)` of side `side` in a raster whose cell `(0, 0)` has
/// its bottom-left corner at `origin` (`i` to the right, `j` upwards).
fn square(origin: Point, side: f64, i: usize, j: usize) -> Aabb {
    let at =
        |i: usize, j: usize| Point::new(origin.x + i as f64 * side, origin.y + j as f64 * side);
    Aabb::from_corners(at(i, j), at(i + 1, j + 1))
}

/// The indices of the `n` squares of side `side` from `origin` that the
/// closed interval `[lo, hi]` meets, along one axis.
fn index_range(lo: f64, hi: f64, origin: f64, side: f64, n: usize) -> std::ops::Range<usize> {
    let f = |v: f64| ((v - origin) / side).floor().clamp(0.0, n as f64) as usize;
    f(lo)..(f(hi) + 1).min(n)
}

/// Whether segment `pq` meets the open axis-parallel side at `x = at`
/// (`vertical`) or `y = at`, spanning `(lo, hi)` along it, ends excluded.
fn meets_open_side(p: Point, q: Point, at: f64, (lo, hi): (f64, f64), vertical: bool) -> bool {
    // Coordinates across the side (u) and along it (v).
    let (pu, pv, qu, qv) = if vertical {
        (p.x, p.y, q.x, q.y)
    } else {
        (p.y, p.x, q.y, q.x)
    };
    if pu == at && qu == at {
        // Along the side's line: a positive-length overlap (or a point
        // inside the side).
        let (v0, v1) = (pv.min(qv), pv.max(qv));
        return lo.max(v0) < hi.min(v1) || (lo < v0 && v1 < hi);
    }
    if (pu - at) * (qu - at) > 0.0 {
        return false;
    }
    // It crosses or touches the line once.
    let v = pv + (qv - pv) * (at - pu) / (qu - pu);
    lo < v && v < hi
}

/// The D-cell `(i, j)` of side `k` grid cells that contains `p`, if it
/// starts a tour: inside the grid, free, and in a free mega-cell.
pub fn start_cell(
    grid: &Grid,
    others: &Others,
    k: usize,
    p: Point,
) -> Result<(usize, usize), StartProblem> {
    let d = grid.cell * k as f64;
    let (fi, fj) = (
        ((p.x - grid.origin.x) / d).floor(),
        ((p.y - grid.origin.y) / d).floor(),
    );
    let (cols, rows) = (grid.width / k, grid.height / k);
    if !(fi >= 0.0 && fj >= 0.0 && fi < cols as f64 && fj < rows as f64) {
        return Err(StartProblem::OutsideGrid);
    }
    let (i, j) = (fi as usize, fj as usize);
    if dcell_weight(grid, k, i, j) == 0 {
        return Err(StartProblem::Blocked);
    }
    let (a, b) = (i / 2 * 2, j / 2 * 2);
    let whole = [(0, 0), (1, 0), (0, 1), (1, 1)].iter().all(|&(di, dj)| {
        a + di < cols && b + dj < rows && dcell_weight(grid, k, a + di, b + dj) > 0
    });
    if !whole {
        return Err(StartProblem::MegaCellBlocked);
    }
    for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        let cell = square(grid.origin, d, a + di, b + dj);
        // As `Cells::dcell_center` computes it (the tour's points).
        let centre = Point::new(
            grid.origin.x + ((a + di) as f64 + 0.5) * d,
            grid.origin.y + ((b + dj) as f64 + 0.5) * d,
        );
        if others.beyond_bounds(centre) {
            return Err(StartProblem::BeyondBounds);
        }
        if let Some(o) = others.blocker(&cell) {
            return Err(StartProblem::Overlapped(o));
        }
    }
    if let Some(o) = others.wall_inside(&square(grid.origin, 2.0 * d, a / 2, b / 2)) {
        return Err(StartProblem::Overlapped(o));
    }
    Ok((i, j))
}

/// The number of grid cells per D-cell side for `tool` (the analyzer checks
/// that `tool` is a multiple of the cell).
pub fn cells_per_tool(grid: &Grid, tool: f64) -> usize {
    ((tool / grid.cell).round() as usize).max(1)
}

/// A grid resampled to D-cells and mega-cells.
#[derive(Clone, Debug)]
pub struct Cells {
    /// D-cell side.
    pub d: f64,
    pub origin: Point,
    /// D-cells across and up.
    pub cols: usize,
    pub rows: usize,
    /// D-cell weights, `j * cols + i`; 0 blocked.
    pub dcells: Vec<u8>,
    /// Mega-cells across and up (`cols / 2`, `rows / 2`).
    pub mcols: usize,
    pub mrows: usize,
    /// Mega-cell weights, `b * mcols + a`; 0 blocked.
    pub mega: Vec<u8>,
    /// Per mega-cell, the sides to its neighbours that a wall runs along
    /// (bits [`EAST`] and [`NORTH`]): the tree may not cross them.
    pub fenced: Vec<u8>,
}

impl Cells {
    /// Resamples `grid` with `k` grid cells per D-cell side.
    pub fn new(grid: &Grid, k: usize) -> Self {
        Cells::with_others(grid, &Others::none(), k)
    }

    /// Resamples `grid` with `k` grid cells per D-cell side; the D-cells
    /// that `others` overlap are blocked too.
    pub fn with_others(grid: &Grid, others: &Others, k: usize) -> Self {
        match Self::with_others_until(grid, others, k, &Deadline::never()) {
            Some(cells) => cells,
            None => unreachable!("a deadline that never passes"),
        }
    }

    /// [`Cells::with_others`], or `None` once `deadline` passes (SPEC 2.5:
    /// resampling the grid is set-up, which `limit time` counts). The
    /// clock is asked once per row of D-cells or mega-cells, and per row of
    /// the D-cells under each other obstacle.
    pub fn with_others_until(
        grid: &Grid,
        others: &Others,
        k: usize,
        deadline: &Deadline,
    ) -> Option<Self> {
        let (cols, rows) = (grid.width / k, grid.height / k);
        let mut dcells = vec![0u8; cols * rows];
        for j in 0..rows {
            if deadline.passed() {
                return None;
            }
            for i in 0..cols {
                dcells[j * cols + i] = dcell_weight(grid, k, i, j);
            }
        }
        let mut cells = Cells {
            d: grid.cell * k as f64,
            origin: grid.origin,
            cols,
            rows,
            dcells,
            mcols: cols / 2,
            mrows: rows / 2,
            mega: Vec::new(),
            fenced: vec![0; (cols / 2) * (rows / 2)],
        };
        if others.bounds.is_some() {
            for j in 0..rows {
                if deadline.passed() {
                    return None;
                }
                for i in 0..cols {
                    if others.beyond_bounds(cells.dcell_center(i, j)) {
                        cells.dcells[j * cols + i] = 0;
                    }
                }
            }
        }
        // Each other obstacle is tested against the D-cells under its box.
        for &(_, shape, bb) in &others.items {
            let is = index_range(bb.min.x, bb.max.x, cells.origin.x, cells.d, cols);
            let js = index_range(bb.min.y, bb.max.y, cells.origin.y, cells.d, rows);
            for j in js {
                if deadline.passed() {
                    return None;
                }
                for i in is.clone() {
                    if cells.dcells[j * cols + i] != 0
                        && box_overlaps(&cells.dcell_box(i, j), shape)
                    {
                        cells.dcells[j * cols + i] = 0;
                    }
                }
            }
        }
        let (mcols, mrows) = (cells.mcols, cells.mrows);
        let mut mega = vec![0u8; mcols * mrows];
        for b in 0..mrows {
            if deadline.passed() {
                return None;
            }
            for a in 0..mcols {
                let at = |i: usize, j: usize| cells.dcells[j * cols + i];
                let ws = [
                    at(2 * a, 2 * b),
                    at(2 * a + 1, 2 * b),
                    at(2 * a, 2 * b + 1),
                    at(2 * a + 1, 2 * b + 1),
                ];
                mega[b * mcols + a] = if ws.contains(&0) {
                    0
                } else {
                    ws.into_iter().max().unwrap_or(0)
                };
            }
        }
        cells.mega = mega;
        cells.fence(others, deadline)?;
        Some(cells)
    }

    /// The box of mega-cell `(a, b)`.
    pub fn mega_box(&self, a: usize, b: usize) -> Aabb {
        square(self.origin, 2.0 * self.d, a, b)
    }

    /// Blocks the mega-cells whose open box a wall meets (one lying between
    /// two of their D-cells included), and fences the sides between
    /// mega-cells that a wall meets.
    fn fence(&mut self, others: &Others, deadline: &Deadline) -> Option<()> {
        let (mc, mr) = (self.mcols, self.mrows);
        let side = 2.0 * self.d;
        for (_, p, q) in others.walls() {
            // One more below: a wall on a mega-cell's low side is its
            // neighbour's east or north side.
            let range = |lo: f64, hi: f64, origin: f64, n: usize| {
                let r = index_range(lo, hi, origin, side, n);
                r.start.saturating_sub(1)..r.end
            };
            let as_ = range(p.x.min(q.x), p.x.max(q.x), self.origin.x, mc);
            let bs = range(p.y.min(q.y), p.y.max(q.y), self.origin.y, mr);
            for b in bs {
                if deadline.passed() {
                    return None;
                }
                for a in as_.clone() {
                    let m = b * mc + a;
                    let bx = self.mega_box(a, b);
                    if segment_meets_open_box(p, q, bx.min, bx.max) {
                        self.mega[m] = 0;
                    }
                    // The east side x = max.x, and the north side y = max.y,
                    // without their ends.
                    if a + 1 < mc && meets_open_side(p, q, bx.max.x, (bx.min.y, bx.max.y), true) {
                        self.fenced[m] |= EAST;
                    }
                    if b + 1 < mr && meets_open_side(p, q, bx.max.y, (bx.min.x, bx.max.x), false) {
                        self.fenced[m] |= NORTH;
                    }
                }
            }
        }
        Some(())
    }

    /// Whether the tree may link mega-cell `m` to its neighbour `n`.
    fn open_between(&self, m: usize, n: usize) -> bool {
        let (lo, hi) = (m.min(n), m.max(n));
        // Neighbours in one row differ by 1, in one column by `mcols`
        // (which may be 1 too): the rows tell.
        let bit = if lo / self.mcols == hi / self.mcols {
            EAST
        } else {
            NORTH
        };
        self.fenced[lo] & bit == 0
    }

    /// The box of D-cell `(i, j)`.
    pub fn dcell_box(&self, i: usize, j: usize) -> Aabb {
        square(self.origin, self.d, i, j)
    }

    /// The centre of D-cell `(i, j)`.
    pub fn dcell_center(&self, i: usize, j: usize) -> Point {
        Point::new(
            self.origin.x + (i as f64 + 0.5) * self.d,
            self.origin.y + (j as f64 + 0.5) * self.d,
        )
    }

    /// Free D-cells STC cannot cover: those whose mega-cell is partly
    /// blocked or cut by the grid's top or right edge.
    pub fn uncovered(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.rows)
            .flat_map(move |j| (0..self.cols).map(move |i| (i, j)))
            .filter(move |&(i, j)| {
                let (a, b) = (i / 2, j / 2);
                self.dcells[j * self.cols + i] > 0
                    && (a >= self.mcols || b >= self.mrows || self.mega[b * self.mcols + a] == 0)
            })
    }
}

/// Directions of tree links, as bits of [`Tree::links`].
const EAST: u8 = 1;
const NORTH: u8 = 2;
const WEST: u8 = 4;
const SOUTH: u8 = 8;

/// A spanning tree of mega-cells.
#[derive(Clone, Debug, Default)]
pub struct Tree {
    /// Mega-cells in the order Prim added them (index `b * mcols + a`).
    pub order: Vec<usize>,
    /// Per mega-cell: which neighbours it is linked to (bits EAST, NORTH,
    /// WEST, SOUTH).
    pub links: Vec<u8>,
    /// Edges as (parent, child) mega-cell indices.
    pub edges: Vec<(usize, usize)>,
    /// Sum of the edge weights.
    pub weight: u64,
    /// A limit stopped the growth.
    pub gave_up: bool,
}

/// Prim's algorithm over the free mega-cells from `root`. The heap orders
/// candidate edges by (weight, child row from the top, child column, parent
/// row from the top, parent column), so ties break on the lowest row, then
/// column. Stops when `max_pops` cells were added or `deadline` passed.
pub fn prim(
    cells: &Cells,
    root: usize,
    weights: EdgeWeights,
    max_pops: Option<u64>,
    deadline: Option<Instant>,
) -> Tree {
    let (mc, mr) = (cells.mcols, cells.mrows);
    let top_row = |m: usize| (mr - 1 - m / mc) as u32;
    let key = |w: u32, child: usize, parent: usize| {
        Reverse((
            w,
            top_row(child),
            (child % mc) as u32,
            top_row(parent),
            (parent % mc) as u32,
        ))
    };
    let mut tree = Tree {
        links: vec![0; cells.mega.len()],
        ..Tree::default()
    };
    let mut in_tree = vec![false; cells.mega.len()];
    let mut heap = BinaryHeap::new();
    // The root enters with a zero-weight edge to itself.
    heap.push(key(0, root, root));
    while let Some(Reverse((w, row, col, prow, pcol))) = heap.pop() {
        let m = (mr - 1 - row as usize) * mc + col as usize;
        if in_tree[m] {
            continue;
        }
        if max_pops.is_some_and(|n| tree.order.len() as u64 >= n)
            || (tree.order.len().is_multiple_of(4096)
                && deadline.is_some_and(|d| Instant::now() >= d))
        {
            tree.gave_up = true;
            break;
        }
        in_tree[m] = true;
        tree.order.push(m);
        if m != root {
            let p = (mr - 1 - prow as usize) * mc + pcol as usize;
            // (child's link, parent's link), by where the child lies.
            let dir = if m / mc == p / mc {
                if m > p { (WEST, EAST) } else { (EAST, WEST) }
            } else if m > p {
                (SOUTH, NORTH)
            } else {
                (NORTH, SOUTH)
            };
            tree.links[m] |= dir.0;
            tree.links[p] |= dir.1;
            tree.edges.push((p, m));
            tree.weight += u64::from(w);
        }
        let (a, b) = (m % mc, m / mc);
        let mut push = |n: usize| {
            if !in_tree[n] && cells.mega[n] > 0 && cells.open_between(m, n) {
                heap.push(key(weights.edge(cells.mega[m], cells.mega[n]), n, m));
            }
        };
        if a + 1 < mc {
            push(m + 1);
        }
        if b + 1 < mr {
            push(m + mc);
        }
        if a > 0 {
            push(m - 1);
        }
        if b > 0 {
            push(m - mc);
        }
    }
    tree
}

/// The D-cell after `(i, j)` on the counter-clockwise circumnavigation of
/// the tree (see the module documentation).
fn successor(cells: &Cells, links: &[u8], i: usize, j: usize) -> (usize, usize) {
    let l = links[(j / 2) * cells.mcols + i / 2];
    match (i % 2, j % 2) {
        (0, 0) if l & SOUTH != 0 => (i, j - 1),
        (0, 0) => (i + 1, j),
        (1, 0) if l & EAST != 0 => (i + 1, j),
        (1, 0) => (i, j + 1),
        (1, 1) if l & NORTH != 0 => (i, j + 1),
        (1, 1) => (i - 1, j),
        (_, _) if l & WEST != 0 => (i - 1, j),
        (_, _) => (i, j - 1),
    }
}

/// The closed tour of D-cells around `tree`, from `start` back to it:
/// `4 × |tree| + 1` cells.
pub fn tour(cells: &Cells, tree: &Tree, start: (usize, usize)) -> Vec<(usize, usize)> {
    let n = 4 * tree.order.len();
    let mut out = Vec::with_capacity(n + 1);
    let mut c = start;
    out.push(c);
    for _ in 0..n {
        c = successor(cells, &tree.links, c.0, c.1);
        out.push(c);
    }
    out
}

/// Plans a coverage tour (SPEC 3.5). The robot does not change the tour:
/// the analyzer checked that its footprint fits a D-cell centred on its
/// frame origin.
pub fn plan(task: &Task<'_>, settings: &Coverage) -> PlanOutcome {
    let deadline = Deadline::start(&task.limits);
    let world = task.world;
    let mut out = PlanOutcome::default();
    let grid = world
        .obstacles
        .get(settings.on)
        .and_then(|o| match &o.shape {
            Shape::Grid(g) => Some((g, o.name.as_str())),
            _ => None,
        });
    let Some((grid, name)) = grid else {
        out.notes.push("`on` names no grid".into());
        return out;
    };
    let (k, weights) = (settings.k, settings.weights);
    let others = Others::new(world, grid);
    let start = match start_cell(grid, &others, k, task.start.xy()) {
        Ok(s) => s,
        Err(e) => {
            out.notes
                .push(format!("the start {}", e.message(world, name)));
            return out;
        }
    };
    let Some(cells) = Cells::with_others_until(grid, &others, k, &deadline) else {
        for m in [
            "uncovered",
            "tree_edges",
            "tree_weight",
            "cells_total",
            "cells_visited",
            "revisits",
            "coverage",
        ] {
            out.extra.insert(m.into(), MetricValue::Num(0.0));
        }
        out.extra
            .insert("returns_to_start".into(), MetricValue::Bool(false));
        out.gave_up = true;
        out.notes.push(setup_note(
            "resampling the grid into D-cells and mega-cells",
        ));
        return out;
    };
    let root = (start.1 / 2) * cells.mcols + start.0 / 2;
    let tree = prim(
        &cells,
        root,
        weights,
        task.limits.expansions,
        deadline.instant(),
    );
    out.expanded = tree.order.len() as u64;
    out.gave_up = tree.gave_up;
    let uncovered: Vec<(usize, usize)> = cells.uncovered().collect();
    let num = |x: usize| MetricValue::Num(x as f64);
    out.extra.insert("uncovered".into(), num(uncovered.len()));
    out.extra.insert("tree_edges".into(), num(tree.edges.len()));
    out.extra
        .insert("tree_weight".into(), MetricValue::Num(tree.weight as f64));
    let total = 4 * tree.order.len();
    out.extra.insert("cells_total".into(), num(total));
    if task.draw {
        let mega_cells: Vec<Aabb> = tree
            .order
            .iter()
            .take(MAX_TRACED)
            .map(|&m| cells.mega_box(m % cells.mcols, m / cells.mcols))
            .collect();
        let uncovered_boxes: Vec<Aabb> = uncovered
            .iter()
            .take(MAX_TRACED)
            .map(|&(i, j)| cells.dcell_box(i, j))
            .collect();
        out.layers.push(Layer::new(
            "mega_cells",
            Drawing::Boxes(mega_cells),
            Style::new(Colour::Faint, 0.5, 3.0)
                .svg(Svg::fill(0.08).outlined(0.3).key("free mega-cells")),
        ));
        out.layers.push(Layer::new(
            "uncovered",
            Drawing::Boxes(uncovered_boxes),
            Style::new(Colour::Grey, 0.0, 4.0).svg(Svg::fill(0.35).key("cells left uncovered")),
        ));
        if tree.order.len() > MAX_TRACED || uncovered.len() > MAX_TRACED {
            out.notes.push(format!(
            "the picture shows the first {MAX_TRACED} mega-cells, tree edges and uncovered cells"
        ));
        }
    }
    if tree.gave_up {
        for m in ["cells_visited", "revisits", "coverage"] {
            out.extra.insert(m.into(), MetricValue::Num(0.0));
        }
        out.extra
            .insert("returns_to_start".into(), MetricValue::Bool(false));
        out.notes
            .push("a limit stopped the spanning tree before it spanned the free mega-cells".into());
        return out;
    }
    if task.draw {
        let tree_edges = tree
            .edges
            .iter()
            .take(MAX_TRACED)
            .map(|&(p, c)| (mega_center(&cells, p), mega_center(&cells, c)))
            .collect();
        out.layers.push(Layer::new(
            "tree",
            Drawing::Segments(tree_edges),
            Style::new(Colour::Plan, 1.0, 28.0).svg(Svg::line(0.7).key("spanning tree")),
        ));
    }
    let cycle = tour(&cells, &tree, start);
    let mut seen = vec![false; cells.dcells.len()];
    let mut visited = 0usize;
    let mut revisits = 0usize;
    // The last cell closes the tour: it is the return to the start, not a visit.
    for &(i, j) in &cycle[..cycle.len() - 1] {
        let s = &mut seen[j * cells.cols + i];
        if *s {
            revisits += 1;
        } else {
            *s = true;
            visited += 1;
        }
    }
    out.extra.insert("cells_visited".into(), num(visited));
    out.extra.insert("revisits".into(), num(revisits));
    out.extra.insert(
        "coverage".into(),
        MetricValue::Num(if total == 0 {
            0.0
        } else {
            visited as f64 / total as f64
        }),
    );
    out.extra.insert(
        "returns_to_start".into(),
        MetricValue::Bool(cycle.last() == Some(&start)),
    );
    let theta = task.start.theta;
    let at = |p: Point| Config::new(p.x, p.y, theta);
    let mut path: Vec<Config> = Vec::with_capacity(cycle.len() + 2);
    let s = task.start;
    let centre = cells.dcell_center(start.0, start.1);
    let off_centre = s.x != centre.x || s.y != centre.y;
    if off_centre {
        path.push(s);
    }
    path.extend(cycle.iter().map(|&(i, j)| at(cells.dcell_center(i, j))));
    if off_centre {
        path.push(s);
    }
    out.path = Some(path);
    out
}

fn mega_center(cells: &Cells, m: usize) -> Point {
    let (a, b) = (m % cells.mcols, m / cells.mcols);
    let p = cells.dcell_box(2 * a, 2 * b).max;
    Point::new(p.x, p.y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::Limits;
    use crate::geometry::validator::{DEFAULT_TOLERANCE, validate_path};
    use crate::geometry::{ConvexPolygon, Obstacle};
    use petgraph::data::Element;
    use petgraph::graph::UnGraph;
    use proptest::prelude::*;
    use std::collections::{HashMap, VecDeque};

    /// A random grid: `density` of its cells blocked, the others weighted
    /// 1..=9 (SplitMix64 on `seed`).
    fn random_grid(w: usize, h: usize, density: f64, seed: u64) -> Grid {
        let mut rng = crate::rng::SplitMix64::new(seed);
        let mut next = move || rng.next_u64();
        let cells = (0..w * h)
            .map(|_| {
                let r = next();
                if (r >> 11) as f64 / (1u64 << 53) as f64 <= density {
                    0
                } else {
                    (r % 9) as u8 + 1
                }
            })
            .collect();
        Grid {
            cell: 0.5,
            origin: Point::new(-1.0, 2.0),
            width: w,
            height: h,
            cells,
        }
    }

    fn world_of(grid: &Grid) -> World {
        World {
            bounds: grid.extent(),
            obstacles: vec![Obstacle {
                name: "G".into(),
                shape: Shape::Grid(grid.clone()),
            }],
        }
    }

    /// Plans the tour of grid `G` of `world` from `start` with D = `tool`.
    fn cover(
        world: &World,
        robot: &RobotShape,
        start: Config,
        tool: f64,
        weights: EdgeWeights,
        limits: Limits,
    ) -> PlanOutcome {
        let on = world
            .obstacles
            .iter()
            .position(|o| o.name == "G")
            .expect("a grid G");
        let Shape::Grid(grid) = &world.obstacles[on].shape else {
            panic!("G is a grid");
        };
        let task = Task {
            world,
            robot,
            start,
            goal: None,
            limits,
            seed: 0,
            steering: None,
            draw: true,
            referee: None,
            moving: &[],
            speed: None,
            agents: &[],
        };
        let k = cells_per_tool(grid, tool);
        plan(&task, &Coverage { on, k, weights })
    }

    /// The model the planner must agree with, computed directly from the
    /// grid's cells (no code shared with the planner).
    struct Model {
        k: usize,
        cols: usize,
        rows: usize,
    }

    impl Model {
        fn new(grid: &Grid, k: usize) -> Self {
            Model {
                k,
                cols: grid.width / k,
                rows: grid.height / k,
            }
        }

        /// The grid cells under D-cell (i, j) (j from the bottom).
        fn under(&self, grid: &Grid, i: usize, j: usize) -> Vec<u8> {
            let mut v = Vec::new();
            for c in i * self.k..(i + 1) * self.k {
                for b in j * self.k..(j + 1) * self.k {
                    v.push(grid.weight(c, grid.height - 1 - b));
                }
            }
            v
        }

        fn free(&self, grid: &Grid, i: usize, j: usize) -> bool {
            i < self.cols && j < self.rows && !self.under(grid, i, j).contains(&0)
        }

        fn quad(a: usize, b: usize) -> [(usize, usize); 4] {
            [
                (2 * a, 2 * b),
                (2 * a + 1, 2 * b),
                (2 * a, 2 * b + 1),
                (2 * a + 1, 2 * b + 1),
            ]
        }

        fn mega_free(&self, grid: &Grid, a: usize, b: usize) -> bool {
            Self::quad(a, b).iter().all(|&(i, j)| self.free(grid, i, j))
        }

        fn mega_weight(&self, grid: &Grid, a: usize, b: usize) -> u32 {
            Self::quad(a, b)
                .iter()
                .flat_map(|&(i, j)| self.under(grid, i, j))
                .max()
                .map_or(0, u32::from)
        }

        /// Free mega-cells 4-connected to `root`, by breadth-first search.
        fn component(&self, grid: &Grid, root: (usize, usize)) -> Vec<(usize, usize)> {
            let mut seen = vec![root];
            let mut queue = VecDeque::from([root]);
            while let Some((a, b)) = queue.pop_front() {
                let nbrs = [
                    (a.wrapping_add(1), b),
                    (a.wrapping_sub(1), b),
                    (a, b.wrapping_add(1)),
                    (a, b.wrapping_sub(1)),
                ];
                for n in nbrs {
                    if n.0 < self.cols / 2
                        && n.1 < self.rows / 2
                        && self.mega_free(grid, n.0, n.1)
                        && !seen.contains(&n)
                    {
                        seen.push(n);
                        queue.push_back(n);
                    }
                }
            }
            seen
        }

        /// Weight of a minimum spanning tree of `megas` (petgraph's Kruskal).
        fn mst_weight(&self, grid: &Grid, megas: &[(usize, usize)], sum: bool) -> u32 {
            let mut g = UnGraph::<(), u32>::new_undirected();
            let nodes: HashMap<(usize, usize), _> =
                megas.iter().map(|&m| (m, g.add_node(()))).collect();
            for &(a, b) in megas {
                for n in [(a + 1, b), (a, b + 1)] {
                    if let Some(&to) = nodes.get(&n) {
                        let (x, y) = (
                            self.mega_weight(grid, a, b),
                            self.mega_weight(grid, n.0, n.1),
                        );
                        let w = if sum { x + y } else { x.max(y) };
                        g.add_edge(nodes[&(a, b)], to, w);
                    }
                }
            }
            petgraph::algo::min_spanning_tree(&g)
                .map(|e| match e {
                    Element::Edge { weight, .. } => weight,
                    Element::Node { .. } => 0,
                })
                .sum()
        }

        /// Free D-cells in partly blocked or incomplete mega-cells.
        fn uncovered(&self, grid: &Grid) -> usize {
            let mut n = 0;
            for j in 0..self.rows {
                for i in 0..self.cols {
                    let (a, b) = (i / 2, j / 2);
                    let mega_ok =
                        a < self.cols / 2 && b < self.rows / 2 && self.mega_free(grid, a, b);
                    if self.free(grid, i, j) && !mega_ok {
                        n += 1;
                    }
                }
            }
            n
        }
    }

    fn num(out: &PlanOutcome, key: &str) -> f64 {
        out.extra[key].as_f64()
    }

    /// A random grid with a valid start (by the model), or `None`.
    fn case(
        w: usize,
        h: usize,
        k: usize,
        density: f64,
        seed: u64,
        pick: usize,
    ) -> Option<(Grid, Model, (usize, usize))> {
        let grid = random_grid(w, h, density, seed);
        let model = Model::new(&grid, k);
        let starts: Vec<(usize, usize)> = (0..model.rows)
            .flat_map(|j| (0..model.cols).map(move |i| (i, j)))
            .filter(|&(i, j)| model.mega_free(&grid, i / 2, j / 2))
            .collect();
        let s = *starts.get(pick % starts.len().max(1))?;
        Some((grid, model, s))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        /// On random grids: the tour is closed, moves between 4-adjacent
        /// free D-cells only, visits every D-cell of every free mega-cell
        /// reachable from the start exactly once, and its tree is minimum.
        #[test]
        fn tour_covers_the_component_once(
            w in 2usize..40, h in 2usize..40, k in 1usize..3,
            density in 0.0..0.3f64, seed in any::<u64>(), pick in any::<usize>(),
            fx in 0.05..0.95f64, fy in 0.05..0.95f64, sum in any::<bool>(),
        ) {
            let Some((grid, model, s)) = case(w, h, k, density, seed, pick) else {
                return Ok(());
            };
            let d = grid.cell * k as f64;
            let start = Config::new(
                grid.origin.x + (s.0 as f64 + fx) * d,
                grid.origin.y + (s.1 as f64 + fy) * d,
                0.0,
            );
            let weights = if sum { EdgeWeights::Sum } else { EdgeWeights::Max };
            let robot = RobotShape::Disk(d / 2.0);
            let out = cover(&world_of(&grid), &robot, start, d, weights, Limits::default());
            let path = out.path.clone().expect("a tour");
            // Closed: it ends where it began.
            prop_assert_eq!(path.first(), path.last());
            prop_assert_eq!(out.extra["returns_to_start"], MetricValue::Bool(true));
            // The off-centre start is joined to its D-cell's centre.
            let cells: Vec<(usize, usize)> = path[1..path.len() - 1]
                .iter()
                .map(|c| {
                    let i = ((c.x - grid.origin.x) / d - 0.5).round();
                    let j = ((c.y - grid.origin.y) / d - 0.5).round();
                    assert!((grid.origin.x + (i + 0.5) * d - c.x).abs() < 1e-9, "not a centre");
                    assert!((grid.origin.y + (j + 0.5) * d - c.y).abs() < 1e-9, "not a centre");
                    (i as usize, j as usize)
                })
                .collect();
            prop_assert_eq!(cells[0], s);
            prop_assert_eq!(*cells.last().unwrap(), s);
            for win in cells.windows(2) {
                let (a, b) = (win[0], win[1]);
                prop_assert_eq!(a.0.abs_diff(b.0) + a.1.abs_diff(b.1), 1, "{:?} -> {:?}", a, b);
            }
            for &(i, j) in &cells {
                prop_assert!(model.free(&grid, i, j), "blocked D-cell {:?}", (i, j));
            }
            let comp = model.component(&grid, (s.0 / 2, s.1 / 2));
            let mut expected: Vec<(usize, usize)> =
                comp.iter().flat_map(|&(a, b)| Model::quad(a, b)).collect();
            expected.sort();
            let mut visited = cells[..cells.len() - 1].to_vec();
            visited.sort();
            prop_assert_eq!(&visited, &expected, "each D-cell of the component exactly once");
            prop_assert_eq!(num(&out, "cells_total"), expected.len() as f64);
            prop_assert_eq!(num(&out, "cells_visited"), expected.len() as f64);
            prop_assert_eq!(num(&out, "revisits"), 0.0);
            prop_assert_eq!(num(&out, "coverage"), 1.0);
            prop_assert_eq!(num(&out, "tree_edges"), comp.len() as f64 - 1.0);
            prop_assert_eq!(num(&out, "tree_weight"), f64::from(model.mst_weight(&grid, &comp, sum)));
            prop_assert_eq!(num(&out, "uncovered"), model.uncovered(&grid) as f64);
            let drawn = |entity: &str| match out.layer(entity).map(|l| &l.drawing) {
                Some(Drawing::Boxes(b)) => b.len(),
                Some(Drawing::Segments(s)) => s.len(),
                other => panic!("{entity}: {other:?}"),
            };
            prop_assert_eq!(drawn("mega_cells"), comp.len());
            prop_assert_eq!(drawn("tree"), comp.len() - 1);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(120))]

        /// The tour from a D-cell centre passes the independent validator
        /// for a disk of diameter D and for a D × D square.
        #[test]
        fn tour_passes_the_validator(
            w in 2usize..16, h in 2usize..16, k in 1usize..3,
            density in 0.0..0.4f64, seed in any::<u64>(), pick in any::<usize>(),
        ) {
            let Some((grid, _, s)) = case(w, h, k, density, seed, pick) else {
                return Ok(());
            };
            let d = grid.cell * k as f64;
            let start = Config::new(
                grid.origin.x + (s.0 as f64 + 0.5) * d,
                grid.origin.y + (s.1 as f64 + 0.5) * d,
                0.0,
            );
            tours_validate(&world_of(&grid), start, d)?;
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]

        /// With other obstacles over the grid (disks, boxes, walls on and
        /// off the grid lines), the tour avoids them all: it passes the
        /// validator for a disk of diameter D and a D × D square, whenever
        /// the start can start a tour.
        #[test]
        fn tours_avoid_the_other_obstacles(
            w in 2usize..14, h in 2usize..14, k in 1usize..3,
            extra in prop::collection::vec((0u8..4, 0u16..280, 0u16..280, 0u16..280, 0u16..280), 1..6),
            pick in any::<usize>(),
        ) {
            let grid = open_grid(w, h);
            let mut world = world_of(&grid);
            let at = |v: u16| f64::from(v) / 20.0;
            for (n, &(kind, x, y, u, v)) in extra.iter().enumerate() {
                let (x, y, u, v) = (at(x), at(y), at(u), at(v));
                let shape = match kind {
                    0 => Shape::Disk { center: Point::new(x, y), radius: 0.2 + u / 10.0 },
                    1 => Shape::Rect(Aabb::from_corners(Point::new(x, y), Point::new(x + u / 5.0 + 0.1, y + v / 5.0 + 0.1))),
                    // Walls on the grid lines (whole coordinates) and anywhere.
                    2 if u < 7.0 => Shape::Segment(Point::new(x.round(), y.round()), Point::new(x.round(), (y + v / 3.0).round())),
                    2 => Shape::Segment(Point::new(x.round(), y.round()), Point::new((x + v / 3.0).round(), y.round())),
                    _ => Shape::Segment(Point::new(x, y), Point::new(u, v)),
                };
                // The analyzer refuses walls of zero length.
                if matches!(shape, Shape::Segment(a, b) if a == b) {
                    continue;
                }
                world.obstacles.push(Obstacle { name: format!("o{n}"), shape });
            }
            let d = k as f64;
            let others = Others::new(&world, &grid);
            let starts: Vec<(usize, usize)> = (0..w / k)
                .flat_map(|i| (0..h / k).map(move |j| (i, j)))
                .filter(|&(i, j)| {
                    let c = Point::new((i as f64 + 0.5) * d, (j as f64 + 0.5) * d);
                    start_cell(&grid, &others, k, c).is_ok()
                })
                .collect();
            if starts.is_empty() {
                return Ok(());
            }
            let (i, j) = starts[pick % starts.len()];
            let start = Config::new((i as f64 + 0.5) * d, (j as f64 + 0.5) * d, 0.0);
            tours_validate(&world, start, d)?;
        }
    }

    #[test]
    fn other_obstacles_block_the_d_cells_they_overlap() {
        let grid = open_grid(8, 8);
        let mut world = world_of(&grid);
        let mut add = |name: &str, shape| {
            world.obstacles.push(Obstacle {
                name: name.into(),
                shape,
            })
        };
        // A disk overlapping D-cells (5, 5) and (6, 5) only, and a box that
        // touches D-cell (1, 6) without overlapping it.
        add(
            "pond",
            Shape::Disk {
                center: Point::new(6.0, 5.5),
                radius: 0.4,
            },
        );
        add(
            "crate",
            Shape::Rect(Aabb::from_corners(
                Point::new(0.0, 7.0),
                Point::new(2.0, 8.0),
            )),
        );
        // A wall along the side between mega-cells (0, 0) and (1, 0), and
        // one between D-cells (4, 0) and (5, 0) inside mega-cell (2, 0).
        add(
            "fence",
            Shape::Segment(Point::new(2.0, 0.0), Point::new(2.0, 2.0)),
        );
        add(
            "screen",
            Shape::Segment(Point::new(5.0, 0.0), Point::new(5.0, 1.0)),
        );
        let cells = Cells::with_others(&grid, &Others::new(&world, &grid), 1);
        let free = |i: usize, j: usize| cells.dcells[j * 8 + i] > 0;
        assert!(!free(5, 5) && !free(6, 5));
        assert!(free(4, 5) && free(7, 5) && free(5, 4) && free(5, 6));
        assert!(!free(0, 7) && !free(1, 7) && free(1, 6));
        // Walls on D-cell sides block no D-cell...
        assert!(free(1, 0) && free(2, 0) && free(4, 0) && free(5, 0));
        // ...but the one inside mega-cell (2, 0) blocks it, and the one
        // between mega-cells (0, 0) and (1, 0) fences them apart.
        assert_eq!(cells.mega[2], 0);
        assert!(cells.mega[0] > 0 && cells.mega[1] > 0);
        assert!(!cells.open_between(0, 1) && cells.open_between(0, 4));
        let tree = prim(&cells, 0, EdgeWeights::Max, None, None);
        assert!(!tree.edges.iter().any(|&e| e == (0, 1) || e == (1, 0)));
    }

    #[test]
    fn a_start_whose_mega_cell_another_obstacle_overlaps_is_refused() {
        let grid = open_grid(4, 4);
        let mut world = world_of(&grid);
        world.obstacles.push(Obstacle {
            name: "pillar".into(),
            shape: Shape::Disk {
                center: Point::new(1.5, 1.5),
                radius: 0.3,
            },
        });
        let others = Others::new(&world, &grid);
        // The pillar stands in D-cell (1, 1) of mega-cell (0, 0).
        assert_eq!(
            start_cell(&grid, &others, 1, Point::new(0.5, 0.5)),
            Err(StartProblem::Overlapped(1))
        );
        assert_eq!(
            start_cell(&grid, &others, 1, Point::new(2.5, 0.5)),
            Ok((2, 0))
        );
    }

    /// The tour from `start` starts there and passes the independent
    /// validator for a disk of diameter `d` and for a `d` × `d` square.
    fn tours_validate(world: &World, start: Config, d: f64) -> Result<(), TestCaseError> {
        let half = d / 2.0;
        let square = RobotShape::Polygon(ConvexPolygon {
            vertices: vec![
                Point::new(-half, -half),
                Point::new(half, -half),
                Point::new(half, half),
                Point::new(-half, half),
            ],
        });
        for robot in [RobotShape::Disk(half), square] {
            let out = cover(world, &robot, start, d, EdgeWeights::Max, Limits::default());
            let path = out.path.expect("a tour");
            prop_assert_eq!(path[0], start);
            let v = validate_path(world, &robot, &path, DEFAULT_TOLERANCE);
            prop_assert!(v.is_ok(), "{:?}", v);
        }
        Ok(())
    }

    fn open_grid(w: usize, h: usize) -> Grid {
        Grid {
            cell: 1.0,
            origin: Point::new(0.0, 0.0),
            width: w,
            height: h,
            cells: vec![1; w * h],
        }
    }

    #[test]
    fn ties_break_on_the_lowest_row_then_column() {
        // 2 × 2 mega-cells of equal weight, rooted bottom-left. Rows count
        // from the top: the root is (row 1, col 0).
        let cells = Cells::new(&open_grid(4, 4), 1);
        let m = |row: usize, col: usize| (1 - row) * 2 + col;
        let tree = prim(&cells, m(1, 0), EdgeWeights::Max, None, None);
        // From the root, north (row 0) beats east (row 1); from there
        // (row 0, col 1); the last cell's two candidate parents tie and the
        // one in the lower row wins.
        assert_eq!(
            tree.edges,
            vec![(m(1, 0), m(0, 0)), (m(0, 0), m(0, 1)), (m(0, 1), m(1, 1))]
        );
    }

    #[test]
    fn lighter_edges_enter_the_tree_first() {
        // A heavy column splits the map: the tree reaches around it.
        let mut g = open_grid(6, 4);
        for r in 0..4 {
            g.cells[r * 6 + 2] = 9;
            g.cells[r * 6 + 3] = 9;
        }
        let cells = Cells::new(&g, 1);
        let tree = prim(&cells, 0, EdgeWeights::Max, None, None);
        // 6 mega-cells; the two light ones of the left column join first.
        assert_eq!(tree.order[..2], [0, 3]);
        assert_eq!(tree.weight, 1 + 1 + 9 + 9 + 9);
        let tree = prim(&cells, 0, EdgeWeights::Sum, None, None);
        assert_eq!(tree.weight, 2 + 2 + 10 + 10 + 10);
    }

    #[test]
    fn resampling_aligns_with_the_bottom_left_corner() {
        // 5 × 3 cells with tool 2: two D-cells across, one up, from the
        // bottom-left; the top row and the right column are cut off.
        let mut g = open_grid(5, 3);
        g.cells[0] = 0; // top-left cell: outside every whole D-cell
        g.cells[2 * 5 + 1] = 7; // bottom row, column 1
        let cells = Cells::new(&g, 2);
        assert_eq!((cells.cols, cells.rows), (2, 1));
        assert_eq!(cells.dcells, vec![7, 1]);
        assert_eq!((cells.mcols, cells.mrows), (1, 0));
        assert_eq!(cells.uncovered().count(), 2);
        assert_eq!(
            start_cell(&g, &Others::none(), 2, Point::new(0.5, 0.5)),
            Err(StartProblem::MegaCellBlocked)
        );
        assert_eq!(
            start_cell(&g, &Others::none(), 2, Point::new(0.5, 2.5)),
            Err(StartProblem::OutsideGrid)
        );
        assert_eq!(
            start_cell(&g, &Others::none(), 1, Point::new(0.5, 2.5)),
            Err(StartProblem::Blocked)
        );
        assert_eq!(
            start_cell(&g, &Others::none(), 1, Point::new(-0.5, 0.5)),
            Err(StartProblem::OutsideGrid)
        );
        assert_eq!(
            start_cell(&g, &Others::none(), 1, Point::new(1.5, 0.5)),
            Ok((1, 0))
        );
    }

    #[test]
    fn a_lone_mega_cell_is_toured_counter_clockwise() {
        let g = open_grid(2, 2);
        let out = cover(
            &world_of(&g),
            &RobotShape::Disk(0.5),
            Config::new(0.5, 0.5, 0.0),
            1.0,
            EdgeWeights::Max,
            Limits::default(),
        );
        let xy: Vec<(f64, f64)> = out.path.unwrap().iter().map(|c| (c.x, c.y)).collect();
        assert_eq!(
            xy,
            [(0.5, 0.5), (1.5, 0.5), (1.5, 1.5), (0.5, 1.5), (0.5, 0.5)]
        );
    }

    #[test]
    fn the_same_input_gives_the_same_tour() {
        let g = random_grid(30, 24, 0.15, 42);
        let model = Model::new(&g, 1);
        let s = (0..model.rows)
            .flat_map(|j| (0..model.cols).map(move |i| (i, j)))
            .find(|&(i, j)| model.mega_free(&g, i / 2, j / 2))
            .unwrap();
        let start = Config::new(
            g.origin.x + (s.0 as f64 + 0.5) * g.cell,
            g.origin.y + (s.1 as f64 + 0.5) * g.cell,
            0.0,
        );
        let run = || {
            cover(
                &world_of(&g),
                &RobotShape::Disk(0.25),
                start,
                g.cell,
                EdgeWeights::Sum,
                Limits::default(),
            )
        };
        let (a, b) = (run(), run());
        assert_eq!(a.path, b.path);
        assert_eq!(a.extra, b.extra);
        assert_eq!(a.layers, b.layers);
    }

    #[test]
    fn an_expansion_limit_gives_up() {
        let g = open_grid(20, 20);
        let limits = Limits {
            expansions: Some(5),
            ..Limits::default()
        };
        let out = cover(
            &world_of(&g),
            &RobotShape::Disk(0.5),
            Config::new(0.5, 0.5, 0.0),
            1.0,
            EdgeWeights::Max,
            limits,
        );
        assert!(out.gave_up);
        assert!(out.path.is_none());
        assert_eq!(out.expanded, 5);
    }
}
