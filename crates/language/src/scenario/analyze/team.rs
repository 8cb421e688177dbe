//! Teams (SPEC 2.10): a team's agents, listed in its block or read from
//! the first rows of a MovingAI scenario file, each start and goal in the
//! world, free for the agents' body, and no two starts (or goals) on one
//! point: every problem at its agent's line or the file's row.

use std::collections::HashMap;
use std::path::Path;

use crate::contract::{Agent, Robot};
use crate::diagnostics::{Diag, Span, Spanned};
use crate::geometry::{Config, Grid, Point, RobotShape, Shape, World};
use crate::scenario::movingai::parse_scen;
use crate::syntax::ast;

use super::*;

/// The most agents a team may have.
pub const MAX_AGENTS: usize = 100_000;

impl Analyzer {
    /// The agents of `team NAME ...`; `None` after an error (reported).
    pub(super) fn team(
        &mut self,
        r: &ast::RobotDecl,
        body: &ast::TeamBody,
        shape: &RobotShape,
        world: Option<&World>,
        grid_file: Option<&str>,
    ) -> Option<Vec<Agent>> {
        let agents = match body {
            ast::TeamBody::Agents { agents, block } => self.listed_agents(agents, *block)?,
            ast::TeamBody::From {
                from, file, count, ..
            } => self.scen_agents(*from, file, count, world?, grid_file)?,
        };
        let world = world?;
        let before = self.diags.len();
        let probe = Robot {
            name: r.name.value.clone(),
            shape: shape.clone(),
            steering: None,
            speed: None,
            team: None,
            span: r.span,
        };
        for a in &agents {
            for (which, p) in [("start", a.start), ("goal", a.goal)] {
                let what = format!("{which} of agent `{}`", a.name);
                let who = format!("agent `{}`", a.name);
                let at = Config::new(p.x, p.y, 0.0);
                self.check_pose(world, &probe, &who, at, a.span, &what);
            }
        }
        for (which, pick) in [("start", 0), ("goal", 1)] {
            let mut seen: HashMap<(u64, u64), &Agent> = HashMap::new();
            for a in &agents {
                let p = if pick == 0 { a.start } else { a.goal };
                let key = (p.x.to_bits(), p.y.to_bits());
                if let Some(first) = seen.get(&key) {
                    self.error(
                        Diag::error(
                            "scen::analyze::team_clash",
                            format!(
                                "agents `{}` and `{}` have the same {which} ({}, {})",
                                first.name, a.name, p.x, p.y
                            ),
                        )
                        .at(a.span, format!("the {which} of `{}` again", first.name))
                        .with_related(first.span, format!("`{}`'s {which}", first.name))
                        .help(format!("every agent of a team needs a {which} of its own")),
                    );
                } else {
                    seen.insert(key, a);
                }
            }
        }
        (self.diags.len() == before).then_some(agents)
    }

    /// `{ NAME (x, y) -> (x, y) ... }`.
    fn listed_agents(&mut self, listed: &[ast::TeamAgent], block: Span) -> Option<Vec<Agent>> {
        if listed.is_empty() {
            self.error(
                Diag::error("scen::analyze::empty_team", "a team without agents")
                    .at(block, "no agent listed")
                    .help("list its agents, one per line: `a1 (1.5, 1.5) -> (8.5, 4.5)`"),
            );
            return None;
        }
        let mut names: HashMap<&str, Span> = HashMap::new();
        let mut agents = Vec::with_capacity(listed.len());
        let mut ok = true;
        for a in listed {
            if let Some(first) = names.insert(&a.name.value, a.name.span) {
                self.error(
                    Diag::error(
                        "scen::analyze::duplicate_name",
                        format!("agent `{}` is listed twice", a.name.value),
                    )
                    .at(a.name.span, "second agent of this name")
                    .with_related(first, "first one")
                    .help("agent names must be unique within their team"),
                );
                ok = false;
            }
            let start = self.expect_point(&a.start, "an agent's start");
            let goal = self.expect_point(&a.goal, "an agent's goal");
            if let (Some(start), Some(goal)) = (start, goal) {
                agents.push(Agent {
                    name: a.name.value.clone(),
                    start,
                    goal,
                    span: a.span,
                });
            } else {
                ok = false;
            }
        }
        ok.then_some(agents)
    }

    /// `from "FILE.scen" agents N`: the file's first N rows, on the world's
    /// grid.
    fn scen_agents(
        &mut self,
        from: Span,
        file: &Spanned<String>,
        count: &ast::Value,
        world: &World,
        grid_file: Option<&str>,
    ) -> Option<Vec<Agent>> {
        let n = self.expect_positive(count, "the number of agents")?;
        if n.fract() != 0.0 || n > MAX_AGENTS as f64 {
            self.error(
                Diag::error(
                    "scen::analyze::out_of_range",
                    format!("the number of agents must be a whole number from 1 to {MAX_AGENTS}, got {n}"),
                )
                .at(count.span, "not a whole number of agents")
                .help("take the first N rows of the file: `agents 50`"),
            );
            return None;
        }
        let n = n as usize;
        let id = self.loaded_file(file)?;
        let Some(grid) = world.obstacles.iter().find_map(|o| match &o.shape {
            Shape::Grid(g) => Some(g.clone()),
            _ => None,
        }) else {
            self.error(
                Diag::error(
                    "scen::analyze::team_without_grid",
                    "a team from a MovingAI scenario needs a grid in the world",
                )
                .at(from, "its rows are cells of a map")
                .help("add the map the scenario is for: `world { grid G \"maps/random-32-32-10.map\" cell 1 }`"),
            );
            return None;
        };
        let text = self.sources.get(id)?.text.clone();
        let rows = match parse_scen(&text, n) {
            Ok(rows) => rows,
            Err((at, msg)) => {
                self.error(
                    Diag::error("scen::analyze::bad_scen", format!("MovingAI scenario `{}`: {msg}", file.value))
                        .at(Span::new(id, at.start, at.end), "this row")
                        .help("a MovingAI scenario is a `version 1` line, then rows of bucket, map, width, height, start x, start y, goal x, goal y, optimal length"),
                );
                return None;
            }
        };
        if rows.len() < n {
            self.error(
                Diag::error(
                    "scen::analyze::too_few_rows",
                    format!(
                        "`agents {n}` but `{}` has {} scenario rows",
                        file.value,
                        rows.len()
                    ),
                )
                .at(count.span, format!("more than its {} rows", rows.len()))
                .help(format!("take at most {} agents from this file", rows.len())),
            );
            return None;
        }
        let map_name = grid_file.map(|f| base_name(f).to_string());
        let mut agents = Vec::with_capacity(n);
        let mut ok = true;
        for (k, row) in rows.iter().enumerate() {
            let at = Span::new(id, row.at.start, row.at.end);
            let other_map = map_name.as_ref().is_some_and(|m| base_name(&row.map) != m);
            if other_map || row.width != grid.width || row.height != grid.height {
                self.error(
                    Diag::error(
                        "scen::analyze::scen_map",
                        format!(
                            "row {} is for map `{}` ({} × {}), not the world's grid{} ({} × {})",
                            k + 1,
                            row.map,
                            row.width,
                            row.height,
                            map_name.as_ref().map_or(String::new(), |m| format!(" `{m}`")),
                            grid.width,
                            grid.height
                        ),
                    )
                    .at(at, "a row of another map")
                    .with_related(from, "the team reads it")
                    .help("use the scenario file made for the world's map (`NAME.map` goes with `NAME-random-1.scen` and the like)"),
                );
                ok = false;
                if k == 0 {
                    return None;
                }
                continue;
            }
            let (Some(start), Some(goal)) =
                (cell_point(&grid, row.start), cell_point(&grid, row.goal))
            else {
                self.error(
                    Diag::error(
                        "scen::analyze::scen_cell",
                        format!("row {} names a cell outside the {} × {} map", k + 1, grid.width, grid.height),
                    )
                    .at(at, "a cell off the map")
                    .help("x is the column (0 to width − 1), y the row from the top (0 to height − 1)"),
                );
                ok = false;
                continue;
            };
            agents.push(Agent {
                name: format!("a{}", k + 1),
                start,
                goal,
                span: at,
            });
        }
        ok.then_some(agents)
    }
}

/// The world point at the centre of map cell (x, y): x the column, y the
/// row from the map's top row.
fn cell_point(grid: &Grid, (x, y): (usize, usize)) -> Option<Point> {
    (x < grid.width && y < grid.height).then(|| {
        Point::new(
            grid.origin.x + (x as f64 + 0.5) * grid.cell,
            grid.origin.y + ((grid.height - 1 - y) as f64 + 0.5) * grid.cell,
        )
    })
}

fn base_name(path: &str) -> &str {
    Path::new(path)
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or(path)
}
