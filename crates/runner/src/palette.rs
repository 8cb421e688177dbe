//! The drawing that the sinks which draw share (the SVG of
//! [`crate::report::svg`], and the Rerun viewer of the `scen` command), so
//! both show a plan in the same colour and a world with the same shapes.
//!
//! All coordinates are world units with y up; angles are radians.

use std::collections::BTreeMap;

use crate::contract::layers::Colour;
use crate::geometry::{Aabb, Config, Grid, Point, RobotShape, Shape};

/// Obstacles are grey in every sink (SPEC 6).
pub const OBSTACLE_GREY: [u8; 3] = [140, 140, 140];

/// The RGBA colour of a layer's colour role in the plan of declaration
/// index `plan` (SPEC 6: obstacles grey, plans their own colour).
pub fn role_colour(colour: Colour, plan: usize) -> [u8; 4] {
    let [r, g, b] = match colour {
        Colour::Plan | Colour::Faint => plan_colour(plan),
        Colour::Grey => OBSTACLE_GREY,
        Colour::Free => [170, 215, 170],
        Colour::Blocked => [90, 90, 90],
        Colour::Red => [214, 39, 40],
        Colour::Green => [44, 160, 44],
        Colour::Blue => [31, 119, 180],
    };
    let alpha = if colour == Colour::Faint { 110 } else { 255 };
    [r, g, b, alpha]
}

/// Failed checks are red in every sink (SPEC 6).
pub const FAIL_RED: [u8; 3] = [211, 47, 47];

/// Vertices of the polygon that stands for a circle (disk obstacles and
/// disk robots where the sink has no circle primitive).
pub const CIRCLE_VERTICES: usize = 64;

/// Distinct colours on a light background, without grey (obstacles) and
/// with red last (failures are red).
const PALETTE: [[u8; 3]; 9] = [
    [31, 119, 180],  // blue
    [255, 127, 14],  // orange
    [44, 160, 44],   // green
    [148, 103, 189], // purple
    [23, 190, 207],  // cyan
    [227, 119, 194], // pink
    [140, 86, 75],   // brown
    [188, 189, 34],  // olive
    [214, 39, 40],   // red
];

/// The colour of agent `k` of a team: hues a golden angle apart, so that
/// neighbours in the list differ however many agents there are.
pub fn agent_colour(k: usize) -> [u8; 3] {
    let hue = (k as f64 * 137.507_764_050_037_85).rem_euclid(360.0) / 60.0;
    // HSL with saturation 0.7 and lightness 0.45.
    let (s, l) = (0.7, 0.45);
    let c = (1.0 - (2.0 * l - 1.0_f64).abs()) * s;
    let x = c * (1.0 - (hue.rem_euclid(2.0) - 1.0).abs());
    let (r, g, b) = match hue as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = l - c / 2.0;
    let byte = |v: f64| ((v + m) * 255.0).round().clamp(0.0, 255.0) as u8;
    [byte(r), byte(g), byte(b)]
}

/// The colour of the plan with declaration index `plan` (an index into
/// `Scenario::plans`, so a plan keeps its colour when `--plan` runs only
/// some of them). The palette repeats after nine plans.
pub fn plan_colour(plan: usize) -> [u8; 3] {
    PALETTE[plan % PALETTE.len()]
}

/// `n` vertices on the circle, counter-clockwise from angle 0 (open: the
/// first vertex is not repeated).
pub fn circle_polygon(center: Point, radius: f64, n: usize) -> Vec<Point> {
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            Point::new(center.x + radius * a.cos(), center.y + radius * a.sin())
        })
        .collect()
}

/// `vertices` as a closed line strip (the first vertex repeated at the end).
pub fn closed(mut vertices: Vec<Point>) -> Vec<Point> {
    if let Some(&first) = vertices.first() {
        vertices.push(first);
    }
    vertices
}

/// The outline of an obstacle as line strips: closed for polygons,
/// rectangles and disks (as [`CIRCLE_VERTICES`]-gons), a two-point open
/// strip for a segment, none for a grid (see [`blocked_boxes`]).
pub fn obstacle_outline(shape: &Shape) -> Vec<Vec<Point>> {
    match shape {
        Shape::Polygon { outline, .. } => vec![closed(outline.clone())],
        Shape::Rect(b) => vec![closed(b.corners().to_vec())],
        Shape::Disk { center, radius } => {
            vec![closed(circle_polygon(*center, *radius, CIRCLE_VERTICES))]
        }
        Shape::Segment(a, b) => vec![vec![*a, *b]],
        Shape::Grid(_) => Vec::new(),
    }
}

/// The robot's body placed at `c`, as line strips: a polygon or a disk
/// (as a [`CIRCLE_VERTICES`]-gon) as one closed strip; a point robot, which
/// has no body, as a cross of two strips with half-width `mark`.
pub fn robot_outline(shape: &RobotShape, c: Config, mark: f64) -> Vec<Vec<Point>> {
    match shape {
        RobotShape::Point => vec![
            vec![
                Point::new(c.x - mark, c.y - mark),
                Point::new(c.x + mark, c.y + mark),
            ],
            vec![
                Point::new(c.x - mark, c.y + mark),
                Point::new(c.x + mark, c.y - mark),
            ],
        ],
        RobotShape::Disk(r) => vec![closed(circle_polygon(c.xy(), *r, CIRCLE_VERTICES))],
        RobotShape::Polygon(_) => vec![closed(shape.placed_vertices(c))],
    }
}

/// The blocked cells of a grid as few boxes: each row's runs of adjacent
/// blocked cells, and a run repeated exactly in the rows below it merged
/// into one taller box. A 512×512 maze becomes thousands of boxes, not a
/// quarter of a million cells. The order is deterministic (by the row
/// where a box ends, then by column).
pub fn blocked_boxes(grid: &Grid) -> Vec<Aabb> {
    cell_boxes(grid, |w| w == 0)
}

/// The free cells of weight 2–9 as few boxes (as [`blocked_boxes`]), with
/// their weight; weight 1, the default, is left out. Empty for grids of
/// more than [`MAX_WEIGHT_CELLS`] cells.
pub fn weight_boxes(grid: &Grid) -> Vec<(u8, Aabb)> {
    if grid.cells.len() > MAX_WEIGHT_CELLS {
        return Vec::new();
    }
    let mut out = Vec::new();
    for w in 2..=9u8 {
        if grid.cells.contains(&w) {
            out.extend(cell_boxes(grid, |c| c == w).into_iter().map(|b| (w, b)));
        }
    }
    out
}

/// The largest grid whose weights are drawn (cell by cell they would cost
/// more than the rest of the picture).
pub const MAX_WEIGHT_CELLS: usize = 1 << 20;

/// The colour of cell weight `w` (2–9): one warm hue, more opaque for
/// heavier cells.
pub fn weight_colour(w: u8) -> [u8; 4] {
    [230, 150, 50, 30 + 25 * w.saturating_sub(1).min(8)]
}

/// The cells for which `pick(weight)` holds as few boxes (see
/// [`blocked_boxes`]).
fn cell_boxes(grid: &Grid, pick: impl Fn(u8) -> bool) -> Vec<Aabb> {
    let mut boxes = Vec::new();
    // Open boxes: column range → first row (rows grow downwards).
    let mut open: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    let to_box = |(c0, c1): (usize, usize), r0: usize, r1: usize| {
        // Cells c0..c1 of rows r0..r1 (both ranges half-open).
        let top = grid.cell_box(c0, r0);
        let bottom = grid.cell_box(c1 - 1, r1 - 1);
        Aabb::from_corners(
            Point::new(top.min.x, top.max.y),
            Point::new(bottom.max.x, bottom.min.y),
        )
    };
    for row in 0..grid.height {
        let runs = row_runs(grid, row, &pick);
        let ended: Vec<_> = open
            .iter()
            .filter(|(run, _)| runs.binary_search(run).is_err())
            .map(|(&run, &r0)| (run, r0))
            .collect();
        for (run, r0) in ended {
            open.remove(&run);
            boxes.push(to_box(run, r0, row));
        }
        for run in runs {
            open.entry(run).or_insert(row);
        }
    }
    for (run, r0) in open {
        boxes.push(to_box(run, r0, grid.height));
    }
    boxes
}

/// Half-open column ranges of the runs of picked cells of one row, left to
/// right.
fn row_runs(grid: &Grid, row: usize, pick: &impl Fn(u8) -> bool) -> Vec<(usize, usize)> {
    let mut runs = Vec::new();
    let mut col = 0;
    while col < grid.width {
        if pick(grid.weight(col, row)) {
            let start = col;
            while col < grid.width && pick(grid.weight(col, row)) {
                col += 1;
            }
            runs.push((start, col));
        } else {
            col += 1;
        }
    }
    runs
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(rows: &[&str]) -> Grid {
        Grid {
            cell: 1.0,
            origin: Point::new(0.0, 0.0),
            width: rows[0].len(),
            height: rows.len(),
            cells: rows
                .iter()
                .flat_map(|r| {
                    r.bytes().map(|b| match b {
                        b'#' => 0,
                        b'0'..=b'9' => b - b'0',
                        _ => 1,
                    })
                })
                .collect(),
        }
    }

    fn area(boxes: &[Aabb]) -> f64 {
        boxes.iter().map(|b| b.width() * b.height()).sum()
    }

    #[test]
    fn blocked_boxes_merge_runs_across_rows() {
        // Row 0 is the top row, at y in [2, 3].
        let g = grid(&["##..", "##.#", "...#"]);
        let boxes = blocked_boxes(&g);
        assert_eq!(boxes.len(), 2);
        assert_eq!(area(&boxes), 6.0);
        let square = Aabb::from_corners(Point::new(0.0, 1.0), Point::new(2.0, 3.0));
        let bar = Aabb::from_corners(Point::new(3.0, 0.0), Point::new(4.0, 2.0));
        assert!(boxes.contains(&square), "{boxes:?}");
        assert!(boxes.contains(&bar), "{boxes:?}");
    }

    #[test]
    fn blocked_boxes_cover_exactly_the_blocked_cells() {
        let g = grid(&["#.#.#", "#####", ".#.#.", "#####", "....."]);
        let boxes = blocked_boxes(&g);
        let blocked = g.cells.iter().filter(|&&w| w == 0).count();
        assert_eq!(area(&boxes), blocked as f64);
        for row in 0..g.height {
            for col in 0..g.width {
                let c = g.cell_box(col, row);
                let centre = Point::new(c.min.x + 0.5, c.min.y + 0.5);
                let covered = boxes.iter().any(|b| b.contains(centre));
                assert_eq!(covered, g.is_blocked(col, row), "cell ({col}, {row})");
            }
        }
    }

    #[test]
    fn weight_boxes_cover_exactly_the_weighted_cells() {
        let g = grid(&["1290", "2299", "1111"]);
        let boxes = weight_boxes(&g);
        for w in 2..=9u8 {
            let count = g.cells.iter().filter(|&&c| c == w).count() as f64;
            let covered: Vec<Aabb> = boxes
                .iter()
                .filter(|(k, _)| *k == w)
                .map(|(_, b)| *b)
                .collect();
            assert_eq!(area(&covered), count, "weight {w}");
        }
        assert!(boxes.iter().all(|(w, _)| *w >= 2));
    }

    #[test]
    fn plan_colours_are_distinct_and_never_obstacle_grey() {
        for i in 0..PALETTE.len() {
            assert_ne!(plan_colour(i), OBSTACLE_GREY);
            for j in 0..i {
                assert_ne!(plan_colour(i), plan_colour(j));
            }
        }
    }

    #[test]
    fn robot_outline_closes_bodies() {
        let disk = robot_outline(&RobotShape::Disk(1.0), Config::new(2.0, 3.0, 0.0), 0.1);
        assert_eq!(disk.len(), 1);
        assert_eq!(disk[0].len(), CIRCLE_VERTICES + 1);
        assert_eq!(disk[0].first(), disk[0].last());
        let point = robot_outline(&RobotShape::Point, Config::new(0.0, 0.0, 0.0), 0.1);
        assert_eq!(point.len(), 2);
    }
}
