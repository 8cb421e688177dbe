//! The world: `bounds`, the obstacles (names, shapes, polygons normalised and
//! decomposed) and grids, inline or from the map files the loader read.

use std::collections::HashMap;

use crate::diagnostics::{Diag, Span, Spanned};
use crate::geometry::polygon;
use crate::geometry::{Aabb, ConvexPolygon, Grid, Obstacle, Point, Shape, World};
use crate::syntax::ast;

use crate::contract::schema::MAX_MAGNITUDE;
use crate::scenario::loader::SourcedStmt;
use crate::scenario::movingai::{grid_char, parse_movingai};

use super::*;

impl Analyzer {
    pub(super) fn world(&mut self, statements: &[SourcedStmt]) -> (Option<World>, Vec<Span>) {
        let mut bounds: Option<(Aabb, Span)> = None;
        let mut bounds_given = false;
        let mut obstacles = Vec::new();
        let mut spans = Vec::new();
        let mut names: HashMap<String, Span> = HashMap::new();
        let mut world_in_file: HashMap<u32, Span> = HashMap::new();
        let mut any_world = false;
        let mut index = 0usize;
        for s in statements {
            let ast::Stmt::World(w) = &s.stmt else {
                continue;
            };
            any_world = true;
            if let Some(first) = world_in_file.get(&w.keyword.file) {
                self.error(
                    Diag::error(
                        "scen::analyze::duplicate_world",
                        "a file has two `world` blocks",
                    )
                    .at(w.keyword, "second `world`")
                    .with_related(*first, "first `world`")
                    .help("put all obstacles into one `world { ... }` block"),
                );
            } else {
                world_in_file.insert(w.keyword.file, w.keyword);
            }
            for item in &w.items {
                match item {
                    ast::WorldItem::Bounds { min, max, span } => {
                        if bounds_given && bounds.is_none() {
                            continue; // the first `bounds` was invalid and reported
                        }
                        bounds_given = true;
                        if let Some((_, first)) = &bounds {
                            self.error(
                                Diag::error(
                                    "scen::analyze::duplicate_bounds",
                                    "`bounds` is given twice",
                                )
                                .at(*span, "second `bounds`")
                                .with_related(*first, "first `bounds`")
                                .help("the world has exactly one `bounds`"),
                            );
                            continue;
                        }
                        let (a, b) = (
                            self.expect_point(min, "the min corner"),
                            self.expect_point(max, "the max corner"),
                        );
                        if let (Some(a), Some(b)) = (a, b) {
                            if a.x < b.x && a.y < b.y {
                                bounds = Some((Aabb { min: a, max: b }, *span));
                            } else {
                                self.error(
                                    Diag::error("scen::analyze::bad_bounds", "`bounds` must go from the min corner to the max corner")
                                        .at(*span, "empty or reversed box")
                                        .help("write `bounds (xmin, ymin) (xmax, ymax)` with xmin < xmax and ymin < ymax"),
                                );
                            }
                        }
                    }
                    // A family's sample places its scattered items before
                    // analysis (`super::super::family`).
                    ast::WorldItem::Scatter(_) => {}
                    // Analysed once the bounds are known (`moving.rs`).
                    ast::WorldItem::Moving(_) => {}
                    ast::WorldItem::Obstacle(o) => {
                        index += 1;
                        let name = match &o.name {
                            Some(n) => {
                                if let Some(first) = names.get(&n.value) {
                                    self.error(
                                        Diag::error(
                                            "scen::analyze::duplicate_name",
                                            format!("obstacle `{}` is declared twice", n.value),
                                        )
                                        .at(n.span, "second declaration")
                                        .with_related(*first, "first declaration")
                                        .help("obstacle names must be unique; rename one of them"),
                                    );
                                } else {
                                    names.insert(n.value.clone(), n.span);
                                }
                                n.value.clone()
                            }
                            None => o.kind.value.unnamed(index),
                        };
                        if let Some(shape) = self.obstacle_shape(o) {
                            obstacles.push(Obstacle { name, shape });
                            spans.push(o.span);
                        }
                    }
                }
            }
        }
        if !any_world {
            let span = statements
                .first()
                .map(|s| s.stmt.span())
                .unwrap_or_default();
            self.error(
                Diag::error(
                    "scen::analyze::no_world",
                    "the scenario has no `world` block",
                )
                .at(
                    Span::new(span.file, 0, 0),
                    "expected a `world { ... }` block",
                )
                .help("add `world { bounds (0, 0) (10, 10) }` with the obstacles inside"),
            );
            return (None, spans);
        }
        let Some((bounds, _)) = bounds else {
            if bounds_given {
                return (None, spans); // invalid bounds, already reported
            }
            let span = statements
                .iter()
                .find_map(|s| match &s.stmt {
                    ast::Stmt::World(w) => Some(w.keyword),
                    _ => None,
                })
                .unwrap_or_default();
            self.error(
                Diag::error("scen::analyze::no_bounds", "the world has no `bounds`")
                    .at(span, "this world needs `bounds`")
                    .help("add `bounds (xmin, ymin) (xmax, ymax)` inside the world block"),
            );
            return (None, spans);
        };
        (Some(World { bounds, obstacles }), spans)
    }

    pub(super) fn obstacle_shape(&mut self, o: &ast::ObstacleDecl) -> Option<Shape> {
        match &o.shape {
            ast::ObstacleShape::Rect(a, b) => {
                let (a, b) = (
                    self.expect_point(a, "a corner"),
                    self.expect_point(b, "a corner"),
                );
                let r = Aabb::from_corners(a?, b?);
                if r.width() > 0.0 && r.height() > 0.0 {
                    Some(Shape::Rect(r))
                } else {
                    self.error(
                        Diag::error(
                            "scen::analyze::degenerate_rect",
                            "the rectangle has zero area",
                        )
                        .at(o.span, "zero width or height")
                        .help("give two opposite corners; for a thin wall use `segment`"),
                    );
                    None
                }
            }
            ast::ObstacleShape::Polygon(v) => {
                let (pts, vspans) = self.polygon_points(v, "a polygon")?;
                match polygon::normalize_simple_polygon(&pts) {
                    Ok(outline) => {
                        let pieces = if polygon::is_convex(&outline) {
                            vec![ConvexPolygon {
                                vertices: outline.clone(),
                            }]
                        } else {
                            polygon::convex_decomposition(&outline)
                        };
                        Some(Shape::Polygon { outline, pieces })
                    }
                    Err(e) => {
                        self.polygon_error(e, v.span, &vspans, "the polygon");
                        None
                    }
                }
            }
            ast::ObstacleShape::Segment(a, b) => {
                let (a, b) = (
                    self.expect_point(a, "an end point"),
                    self.expect_point(b, "an end point"),
                );
                let (a, b) = (a?, b?);
                if a == b {
                    self.error(
                        Diag::error(
                            "scen::analyze::degenerate_segment",
                            "the segment has zero length",
                        )
                        .at(o.span, "both ends are the same point")
                        .help("give two different end points"),
                    );
                    return None;
                }
                Some(Shape::Segment(a, b))
            }
            ast::ObstacleShape::Disk(c, r) => {
                let c = self.expect_point(c, "the centre");
                let r = self.expect_positive(r, "the radius");
                Some(Shape::Disk {
                    center: c?,
                    radius: r?,
                })
            }
            ast::ObstacleShape::Grid(g) => self.grid(g, o.span).map(Shape::Grid),
        }
    }

    pub(super) fn grid(&mut self, g: &ast::GridSpec, span: Span) -> Option<Grid> {
        let cell = match &g.cell {
            Some(v) => self.expect_positive(v, "the grid's `cell`")?,
            None => 1.0,
        };
        let origin = match &g.origin {
            Some(v) => self.expect_point(v, "the grid's `origin`")?,
            None => Point::origin(),
        };
        let cell_span = g.cell.as_ref().map_or(span, |v| v.span);
        let (width, height, cells) = match (&g.file, &g.rows) {
            (Some(f), None) => self.movingai_map(f)?,
            (None, Some(rows)) => self.inline_rows(rows, span)?,
            (Some(f), Some(_)) => {
                self.error(
                    Diag::error(
                        "scen::analyze::grid_source",
                        "a grid has both a map file and inline rows",
                    )
                    .at(f.span, "map file")
                    .help("use either `grid G \"file.map\" ...` or `grid G ... { \"rows\" }`"),
                );
                return None;
            }
            (None, None) => {
                self.error(
                    Diag::error(
                        "scen::analyze::grid_source",
                        "a grid needs a map file or inline rows",
                    )
                    .at(span, "no cells")
                    .help(
                        "write `grid G \"maps/arena.map\" cell 1` or `grid G cell 1 { \"..#.\" }`",
                    ),
                );
                return None;
            }
        };
        let grid = Grid {
            cell,
            origin,
            width,
            height,
            cells,
        };
        let end = grid.extent().max;
        if end.x.abs() > MAX_MAGNITUDE || end.y.abs() > MAX_MAGNITUDE {
            self.error(
                Diag::error(
                    "scen::analyze::grid_too_large",
                    format!(
                        "the grid reaches ({}, {}), beyond ±1e9",
                        short_number(end.x),
                        short_number(end.y)
                    ),
                )
                .at(cell_span, format!("{width} × {height} cells of side {cell}"))
                .help("a grid must lie within ±1e9 (SPEC 2.1): use a smaller `cell`, or move its `origin` towards (0, 0)"),
            );
            return None;
        }
        Some(grid)
    }

    pub(super) fn inline_rows(
        &mut self,
        rows: &[Spanned<String>],
        span: Span,
    ) -> Option<(usize, usize, Vec<u8>)> {
        let Some(first) = rows.first() else {
            self.error(
                Diag::error("scen::analyze::empty_grid", "the grid has no rows")
                    .at(span, "empty grid")
                    .help("write the rows top row first, e.g. `{ \"..#\" \"...\" }`"),
            );
            return None;
        };
        let width = first.value.chars().count();
        let mut cells = Vec::with_capacity(width * rows.len());
        let mut ok = true;
        for row in rows {
            let n = row.value.chars().count();
            if n != width || n == 0 {
                self.error(
                    Diag::error(
                        "scen::analyze::ragged_grid",
                        format!("grid rows must all have the same non-zero length: this row has {n}, the first {width}"),
                    )
                    .at(row.span, format!("{n} cells"))
                    .help("pad the rows so that every row has the same number of cells"),
                );
                ok = false;
                continue;
            }
            // Point at the character when the literal has no escapes.
            let plain = self.sources.snippet(row.span).len() == row.value.len() + 2;
            for (i, (off, ch)) in row.value.char_indices().enumerate() {
                match grid_char(ch) {
                    Some(w) => cells.push(w),
                    None => {
                        let at = if plain {
                            Span::new(
                                row.span.file,
                                row.span.start + 1 + off,
                                row.span.start + 1 + off + ch.len_utf8(),
                            )
                        } else {
                            row.span
                        };
                        self.error(
                            Diag::error("scen::analyze::grid_char", format!("`{ch}` is not a grid cell (column {})", i + 1))
                                .at(at, "unknown cell character")
                                .help("free: `.` `G` `S` or a weight `1`-`9`; blocked: `@` `O` `T` `W` `#`"),
                        );
                        ok = false;
                        break;
                    }
                }
            }
        }
        ok.then_some((width, rows.len(), cells))
    }

    /// The file named at `f` (a map, a team's MovingAI scenario), which the
    /// loader read (SPEC 2.2: the files a scenario reads are read by the
    /// loader, inside the root): its id, or `None` after reporting why it
    /// could not be read.
    pub(super) fn loaded_file(&mut self, f: &Spanned<String>) -> Option<FileId> {
        match self.maps.remove(&f.span) {
            Some(Ok(id)) => Some(id),
            Some(Err(d)) => {
                self.error(d);
                None
            }
            // The loader reads every such file; one it did not see (none in
            // practice) has nothing to analyse.
            None => None,
        }
    }

    /// The grid of a map file, which the loader read.
    pub(super) fn movingai_map(&mut self, f: &Spanned<String>) -> Option<(usize, usize, Vec<u8>)> {
        let id = self.loaded_file(f)?;
        let text = self.sources.get(id)?.text.clone();
        match parse_movingai(&text) {
            Ok(g) => Some(g),
            Err((line, msg)) => {
                self.error(
                    Diag::error("scen::analyze::bad_map", format!("map file `{}`, line {line}: {msg}", f.value))
                        .at(f.span, "this map file")
                        .help("a MovingAI map is `type octile`, `height H`, `width W`, `map`, then H rows of W cells"),
                );
                None
            }
        }
    }
}
