//! Spanning Tree Coverage (SPEC 3.5, SEEDS.md §F).
//!
//! The `on` grid is resampled to D-cells (side D = `tool`, a multiple `k` of
//! the grid's cell) and then to mega-cells of 2 × 2 D-cells, both aligned
//! with the grid's bottom-left corner; cells cut by the top or right edge
//! count as blocked. Prim's algorithm grows a minimum spanning tree of the
//! 4-connected free mega-cells from the start's mega-cell (ties: lowest
//! row, rows counted from the top as in the grid, then lowest column). The
//! tour circumnavigates the tree counter-clockwise, keeping the tree on its
//! left: inside a mega-cell the robot goes round its four D-cells
//! counter-clockwise, and where a tree edge leaves the side it would walk
//! along, it crosses into the neighbour instead. Every D-cell of every tree
//! mega-cell is visited exactly once and the tour ends where it began.
//!
//! D-cells are indexed `(i, j)` with `i` the column from the left and `j`
//! the row from the bottom.

use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::time::Instant;

use crate::geometry::{Aabb, Config, Grid, Point, RobotShape, Shape, World};
use crate::scenario::Params;

use super::{CoverageTrace, MetricValue, PlanOutcome, Trace};

/// The most boxes or edges of each kind kept in the trace for drawing; the
/// metrics always count everything.
pub const MAX_TRACED: usize = 100_000;

/// How mega-cell weights combine into an edge weight (`weights`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeWeights {
    /// max(w_i, w_j), as in the seed.
    Max,
    /// w_i + w_j.
    Sum,
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
}

impl StartProblem {
    pub fn message(self) -> &'static str {
        match self {
            StartProblem::OutsideGrid => "lies outside the grid's whole D-cells",
            StartProblem::Blocked => "lies in a blocked D-cell",
            StartProblem::MegaCellBlocked => {
                "lies in a free D-cell of a partly blocked mega-cell, which STC cannot cover"
            }
        }
    }
}

/// The D-cell `(i, j)` of side `k` grid cells that contains `p`, if it
/// starts a tour: inside the grid, free, and in a free mega-cell.
pub fn start_cell(grid: &Grid, k: usize, p: Point) -> Result<(usize, usize), StartProblem> {
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
}

impl Cells {
    /// Resamples `grid` with `k` grid cells per D-cell side.
    pub fn new(grid: &Grid, k: usize) -> Self {
        let (cols, rows) = (grid.width / k, grid.height / k);
        let mut dcells = vec![0u8; cols * rows];
        for j in 0..rows {
            for i in 0..cols {
                dcells[j * cols + i] = dcell_weight(grid, k, i, j);
            }
        }
        let (mcols, mrows) = (cols / 2, rows / 2);
        let mut mega = vec![0u8; mcols * mrows];
        for b in 0..mrows {
            for a in 0..mcols {
                let at = |i: usize, j: usize| dcells[j * cols + i];
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
        Cells {
            d: grid.cell * k as f64,
            origin: grid.origin,
            cols,
            rows,
            dcells,
            mcols,
            mrows,
            mega,
        }
    }

    /// The box of D-cell `(i, j)`.
    pub fn dcell_box(&self, i: usize, j: usize) -> Aabb {
        let p = |i: usize, j: usize| {
            Point::new(
                self.origin.x + i as f64 * self.d,
                self.origin.y + j as f64 * self.d,
            )
        };
        Aabb::from_corners(p(i, j), p(i + 1, j + 1))
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
            || (tree.order.len() % 4096 == 0 && deadline.is_some_and(|d| Instant::now() >= d))
        {
            tree.gave_up = true;
            break;
        }
        in_tree[m] = true;
        tree.order.push(m);
        if m != root {
            let p = (mr - 1 - prow as usize) * mc + pcol as usize;
            let dir = if p + 1 == m {
                (WEST, EAST) // child east of parent: child links west
            } else if m + 1 == p {
                (EAST, WEST)
            } else if p + mc == m {
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
            if !in_tree[n] && cells.mega[n] > 0 {
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

/// Plans a coverage tour (SPEC 3.5).
pub fn plan(world: &World, robot: &RobotShape, params: &Params) -> PlanOutcome {
    let _ = robot; // the analyzer checked that its footprint fits a D-cell
    let mut out = PlanOutcome::default();
    let grid = params.word("on").and_then(|name| {
        world.obstacles.iter().find_map(|o| match &o.shape {
            Shape::Grid(g) if o.name == name => Some(g),
            _ => None,
        })
    });
    let Some(grid) = grid else {
        out.notes.push("`on` names no grid".into());
        return out;
    };
    let k = cells_per_tool(grid, params.num("tool").unwrap_or(grid.cell));
    let weights = match params.word("weights") {
        Some("sum") => EdgeWeights::Sum,
        _ => EdgeWeights::Max,
    };
    let start = match start_cell(grid, k, params.start.xy()) {
        Ok(s) => s,
        Err(e) => {
            out.notes.push(format!("the start {}", e.message()));
            return out;
        }
    };
    let began = Instant::now();
    let cells = Cells::new(grid, k);
    let root = (start.1 / 2) * cells.mcols + start.0 / 2;
    let deadline = params
        .limits
        .time
        .map(|s| began + std::time::Duration::from_secs_f64(s));
    let tree = prim(&cells, root, weights, params.limits.expansions, deadline);
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
    let mut trace = CoverageTrace {
        tool: cells.d,
        mega_cells: tree
            .order
            .iter()
            .take(MAX_TRACED)
            .map(|&m| {
                let (a, b) = (m % cells.mcols, m / cells.mcols);
                Aabb::from_corners(
                    cells.dcell_box(2 * a, 2 * b).min,
                    cells.dcell_box(2 * a + 1, 2 * b + 1).max,
                )
            })
            .collect(),
        uncovered: uncovered
            .iter()
            .take(MAX_TRACED)
            .map(|&(i, j)| cells.dcell_box(i, j))
            .collect(),
        tree: tree
            .edges
            .iter()
            .take(MAX_TRACED)
            .map(|&(p, c)| (mega_center(&cells, p), mega_center(&cells, c)))
            .collect(),
    };
    if tree.order.len() > MAX_TRACED || uncovered.len() > MAX_TRACED {
        out.notes.push(format!(
            "the picture shows the first {MAX_TRACED} mega-cells, tree edges and uncovered cells"
        ));
    }
    if tree.gave_up {
        for m in ["cells_visited", "revisits", "coverage"] {
            out.extra.insert(m.into(), MetricValue::Num(0.0));
        }
        out.extra
            .insert("returns_to_start".into(), MetricValue::Bool(false));
        out.notes
            .push("a limit stopped the spanning tree before it spanned the free mega-cells".into());
        trace.tree.clear();
        out.trace = Trace {
            coverage: Some(trace),
            ..Trace::default()
        };
        return out;
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
    let theta = params.start.theta;
    let at = |p: Point| Config::new(p.x, p.y, theta);
    let mut path: Vec<Config> = Vec::with_capacity(cycle.len() + 2);
    let s = params.start;
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
    out.trace = Trace {
        coverage: Some(trace),
        ..Trace::default()
    };
    out
}

fn mega_center(cells: &Cells, m: usize) -> Point {
    let (a, b) = (m % cells.mcols, m / cells.mcols);
    let p = cells.dcell_box(2 * a, 2 * b).max;
    Point::new(p.x, p.y)
}
