//! What the tests that run every planner of the registry write into their
//! scenarios: a robot of each kind, and the parameters a planner requires
//! (so that a new planner is covered from its registry line).

use scen::contract::Planner;
use scen::contract::schema::{DefaultValue, RobotKind, ValueSpec};

/// A robot of `kind`, written as in a file: small, and centred on its
/// frame origin so that it fits a unit cell (a coverage D-cell) too.
pub fn robot(kind: RobotKind) -> &'static str {
    match kind {
        RobotKind::Point => "point",
        RobotKind::Disk => "disk 0.4",
        RobotKind::Polygon => "polygon [(-0.4, -0.3), (0.4, -0.3), (0.4, 0.3), (-0.4, 0.3)]",
        RobotKind::Car => {
            "polygon [(-0.2, -0.3), (0.6, -0.3), (0.6, 0.3), (-0.2, 0.3)] steer reeds_shepp 1"
        }
        // A team is its own statement: tests/teams.rs runs every team
        // planner of the registry.
        RobotKind::Team => unreachable!("the tests of one robot skip team planners"),
    }
}

/// The planner's required parameters (no default), filled for a world
/// whose grid obstacle is named `G`; a kind of value this cannot fill
/// stops the test with what to teach it.
pub fn required(planner: &Planner) -> Vec<String> {
    planner
        .params
        .iter()
        .filter(|p| p.default == DefaultValue::None)
        .map(|p| match p.value {
            ValueSpec::ObstacleName => format!("{} G", p.key),
            other => panic!(
                "the tests of every planner cannot fill the required `{}` of `{}` ({other:?}): teach tests/common/planner_cases.rs",
                p.key, planner.kind
            ),
        })
        .collect()
}

/// A square world of `side` × `side` unit cells with one block of blocked
/// cells (rows and columns counted from the top left), as [`cell_world`]
/// writes it for `planner`.
pub fn block_world(
    planner: &Planner,
    side: usize,
    rows: std::ops::Range<usize>,
    cols: std::ops::Range<usize>,
) -> String {
    let grid: Vec<String> = (0..side)
        .map(|r| {
            (0..side)
                .map(|c| {
                    if rows.contains(&r) && cols.contains(&c) {
                        '#'
                    } else {
                        '.'
                    }
                })
                .collect()
        })
        .collect();
    cell_world(planner, &grid)
}

/// A world of unit cells, `rows` top row first (`#` blocked), from (0, 0):
/// a `grid G` for a planner that plans among grids, else the same blocked
/// cells as `rect`s (one per run of `#` in a row), so that the tests of
/// every planner give each the same obstacles.
pub fn cell_world(planner: &Planner, rows: &[String]) -> String {
    let (w, h) = (rows.first().map_or(0, String::len), rows.len());
    let mut text = format!("world {{\n  bounds (0, 0) ({w}, {h})\n");
    if planner.grids {
        text.push_str("  grid G cell 1 origin (0, 0) {\n");
        for row in rows {
            text.push_str(&format!("    \"{row}\"\n"));
        }
        text.push_str("  }\n");
    } else {
        for (r, row) in rows.iter().enumerate() {
            let y = h - 1 - r;
            let cells: Vec<char> = row.chars().collect();
            let mut c = 0;
            while c < cells.len() {
                if cells[c] != '#' {
                    c += 1;
                    continue;
                }
                let first = c;
                while c < cells.len() && cells[c] == '#' {
                    c += 1;
                }
                text.push_str(&format!("  rect ({first}, {y}) ({c}, {})\n", y + 1));
            }
        }
    }
    text.push_str("}\n");
    text
}
