//! AST → [`Scenario`]: names resolved, geometry checked and normalised,
//! plan parameters grouped and validated against their planner's schema,
//! `expect` expressions typed. Every problem becomes a [`Diag`]; analysis
//! goes on after an error so that all of them are reported at once.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use crate::diagnostics::{Diag, FileId, SourceMap, Span, Spanned};
use crate::geometry::polygon::{self, PolygonError};
use crate::geometry::{
    Aabb, Config, ConvexPolygon, Grid, Obstacle, Point, RobotShape, Shape, World,
};
use crate::syntax::ast::{self, ParamToken, Value, ValueKind};

use crate::planners::registry::{self, PLANNERS, Planner};

use super::loader::{LoadFailure, SourcedStmt};
use super::movingai::{grid_char, parse_movingai};
use super::schema::{self, MAX_MAGNITUDE, MetricType, RobotKind, ValueSpec, did_you_mean};
use super::{Limits, Param, ParamValue, Params, Plan, PlanArgs, Robot, Scenario};

mod bench;
mod expect;

pub use bench::BENCH_KEYS;
pub use expect::AGGREGATES;

/// Analyses the statements of a scenario (includes already spliced in).
/// The world of a scenario's text alone (no robot or plan needed), for
/// tests that probe a world before they write its plans; panics on
/// diagnostics.
#[cfg(test)]
pub(crate) fn world_of(path: &Path) -> World {
    let parsed = super::loader::parse_scenario(path, None, &|_| None);
    assert!(parsed.diags.is_empty(), "{:?}", parsed.diags);
    let mut a = Analyzer {
        sources: parsed.sources,
        maps: parsed.maps,
        diags: Vec::new(),
        invalid_robots: Vec::new(),
    };
    let (world, _) = a.world(&parsed.statements);
    assert!(a.diags.is_empty(), "{:?}", a.diags);
    world.expect("a world")
}

pub(crate) fn analyze(
    path: &Path,
    statements: Vec<SourcedStmt>,
    sources: SourceMap,
    maps: HashMap<Span, Result<FileId, Diag>>,
) -> Result<Scenario, LoadFailure> {
    let mut a = Analyzer {
        sources,
        maps,
        diags: Vec::new(),
        invalid_robots: Vec::new(),
    };
    let title = a.title(&statements);
    let (world, obstacle_spans) = a.world(&statements);
    let robots = a.robots(&statements);
    let world_ok = !a.diags.iter().any(Diag::is_error);
    let plans = a.plans(&statements, world.as_ref().filter(|_| world_ok), &robots);
    let benches = a.benches(
        &statements,
        &plans,
        world.as_ref().filter(|_| world_ok),
        &robots,
    );
    let checks = a.checks(&statements, &plans, &benches);
    // A file without a plan would run nothing and report "0 passed, 0
    // failed" (SPEC §4). Said when nothing else is wrong: a file with other
    // mistakes is not finished yet, and an empty one gets one error
    // (`no_world`), not two.
    let no_plan = !statements
        .iter()
        .any(|s| matches!(s.stmt, ast::Stmt::Plan(_)));
    if no_plan && !a.diags.iter().any(Diag::is_error) {
        a.error(
            Diag::error("scen::analyze::no_plan", "the scenario has no `plan`")
                .at(Span::new(0, 0, 0), "expected at least one `plan`")
                .help("add a plan, e.g. `plan p astar ROBOT { start (1, 1) goal (9, 9) }`, naming one of the robots"),
        );
    }
    let mut diags = a.diags;
    let sources = a.sources;
    match world {
        Some(world) if !diags.iter().any(Diag::is_error) => Ok(Scenario {
            file: path.to_path_buf(),
            title,
            world,
            obstacle_spans,
            robots,
            plans,
            benches,
            checks,
            sources,
        }),
        _ => {
            crate::diagnostics::sort_diags(&mut diags);
            Err(LoadFailure { sources, diags })
        }
    }
}

struct Analyzer {
    sources: SourceMap,
    /// The map files the loader read, by the span of the `grid`'s path.
    maps: HashMap<Span, Result<FileId, Diag>>,
    diags: Vec<Diag>,
    /// Robots that were declared but failed analysis (no "unknown robot"
    /// noise for plans that use them).
    invalid_robots: Vec<String>,
}

/// A plan's name and planner, for typing `expect`.
struct PlanInfo<'s> {
    name: &'s str,
    planner: &'static Planner,
    /// The plan has `drive`: it has the drive metrics too.
    drives: bool,
}

impl PlanInfo<'_> {
    fn metric(&self, name: &str) -> Option<MetricType> {
        self.planner.metric(name).or_else(|| {
            self.drives
                .then(|| schema::DRIVE_METRICS.iter().find(|m| m.name == name))
                .flatten()
                .map(|m| m.ty)
        })
    }

    fn metric_names(&self) -> Vec<&'static str> {
        let drive = schema::DRIVE_METRICS.iter().filter(|_| self.drives);
        self.planner
            .all_metrics()
            .chain(drive)
            .map(|m| m.name)
            .collect()
    }
}

impl Analyzer {
    fn error(&mut self, d: Diag) {
        self.diags.push(d);
    }

    // ----------------------------------------------------------------- title

    fn title(&mut self, statements: &[SourcedStmt]) -> Option<String> {
        let mut title: Option<(String, Span)> = None;
        for (i, s) in statements.iter().enumerate() {
            let ast::Stmt::Scenario { title: t, span } = &s.stmt else {
                continue;
            };
            if !s.in_main_file {
                self.error(
                    Diag::error(
                        "scen::analyze::title_in_include",
                        "an included file has a `scenario` title",
                    )
                    .at(*span, "only the main file may have a title")
                    .help("remove this line from the included file"),
                );
            } else if let Some((_, first)) = &title {
                self.error(
                    Diag::error(
                        "scen::analyze::duplicate_title",
                        "`scenario` is given twice",
                    )
                    .at(*span, "second title")
                    .with_related(*first, "first title")
                    .help("a file has at most one `scenario` title"),
                );
            } else {
                if i != 0 {
                    self.error(
                        Diag::error(
                            "scen::analyze::title_not_first",
                            "`scenario` must be the first statement",
                        )
                        .at(*span, "not the first statement")
                        .help("move the `scenario \"...\"` line to the top of the file"),
                    );
                }
                title = Some((t.value.clone(), *span));
            }
        }
        title.map(|(t, _)| t)
    }

    // ----------------------------------------------------------------- values

    /// A coordinate, length, radius or cell size: a number within ±1e9
    /// (SPEC 2.1).
    fn expect_number(&mut self, v: &Value, what: &str) -> Option<f64> {
        match &v.kind {
            ValueKind::Number(x) if x.abs() > MAX_MAGNITUDE => {
                self.error(
                    Diag::error(
                        "scen::analyze::number_too_large",
                        format!("{what} is {}, beyond ±1e9", short_number(*x)),
                    )
                    .at(v.span, "more than 1e9 in magnitude")
                    .help(MAGNITUDE_HELP),
                );
                None
            }
            ValueKind::Number(x) => Some(*x),
            ValueKind::Angle(_) => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_unit",
                        format!("{what} is a length, not an angle"),
                    )
                    .at(v.span, "an angle")
                    .help("remove the `deg`/`rad` unit"),
                );
                None
            }
            other => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_type",
                        format!("{what} must be a number, found {}", other.describe()),
                    )
                    .at(v.span, "expected a number")
                    .help("write a number such as `1.5`"),
                );
                None
            }
        }
    }

    fn expect_positive(&mut self, v: &Value, what: &str) -> Option<f64> {
        let x = self.expect_number(v, what)?;
        if x > 0.0 {
            Some(x)
        } else {
            self.error(
                Diag::error(
                    "scen::analyze::out_of_range",
                    format!("{what} must be positive, got {x}"),
                )
                .at(v.span, "not > 0")
                .help("use a value greater than 0"),
            );
            None
        }
    }

    fn expect_point(&mut self, v: &Value, what: &str) -> Option<Point> {
        match &v.kind {
            ValueKind::Tuple(items) if items.len() == 2 => {
                let x = self.expect_number(&items[0], "a coordinate");
                let y = self.expect_number(&items[1], "a coordinate");
                Some(Point::new(x?, y?))
            }
            ValueKind::Tuple(items) => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_type",
                        format!(
                            "{what} must be a point `(x, y)`, found {} values",
                            items.len()
                        ),
                    )
                    .at(v.span, "expected `(x, y)`")
                    .help("a point has two coordinates: `(x, y)`"),
                );
                None
            }
            other => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_type",
                        format!(
                            "{what} must be a point `(x, y)`, found {}",
                            other.describe()
                        ),
                    )
                    .at(v.span, "expected `(x, y)`")
                    .help("write a point as `(x, y)`"),
                );
                None
            }
        }
    }

    fn expect_points(&mut self, v: &Value, what: &str) -> Option<(Vec<Point>, Vec<Span>)> {
        match &v.kind {
            ValueKind::List(items) => {
                let mut pts = Vec::new();
                let mut spans = Vec::new();
                let mut ok = true;
                for it in items {
                    match self.expect_point(it, "a vertex") {
                        Some(p) => {
                            pts.push(p);
                            spans.push(it.span);
                        }
                        None => ok = false,
                    }
                }
                ok.then_some((pts, spans))
            }
            other => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_type",
                        format!(
                            "{what} must be a list of points, found {}",
                            other.describe()
                        ),
                    )
                    .at(v.span, "expected `[(x, y), ...]`")
                    .help("write the vertices as `[(0, 0), (1, 0), (0, 1)]`"),
                );
                None
            }
        }
    }

    /// A polygon's vertices, at most [`polygon::MAX_POLYGON_VERTICES`] of
    /// them (SPEC 2.2), refused before they are read one by one.
    fn polygon_points(&mut self, v: &Value, what: &str) -> Option<(Vec<Point>, Vec<Span>)> {
        if let ValueKind::List(items) = &v.kind
            && items.len() > polygon::MAX_POLYGON_VERTICES
        {
            self.error(
                Diag::error(
                    "scen::analyze::polygon_too_large",
                    format!(
                        "{what} has {} vertices, more than the limit of {}",
                        items.len(),
                        polygon::MAX_POLYGON_VERTICES
                    ),
                )
                .at(v.span, "too many vertices")
                .help("simplify the outline, or split the obstacle into several polygons"),
            );
            return None;
        }
        self.expect_points(v, what)
    }

    fn expect_pose(&mut self, v: &Value, what: &str) -> Option<Config> {
        match &v.kind {
            ValueKind::Tuple(items) if items.len() == 2 || items.len() == 3 => {
                let x = self.expect_number(&items[0], "a coordinate");
                let y = self.expect_number(&items[1], "a coordinate");
                let theta = match items.get(2) {
                    None => Some(0.0),
                    Some(t) => match &t.kind {
                        ValueKind::Angle(a) => self.bounded_angle(t, *a).map(ast::Angle::reduced),
                        ValueKind::Number(n) => {
                            self.angle_without_unit(
                                t.span,
                                *n,
                                format!("the angle of {what} needs a unit"),
                            );
                            None
                        }
                        other => {
                            self.error(
                                Diag::error(
                                    "scen::analyze::wrong_type",
                                    format!(
                                        "the angle of {what} must be an angle, found {}",
                                        other.describe()
                                    ),
                                )
                                .at(t.span, "expected an angle")
                                .help("write an angle as `90deg` or `1.5708rad`"),
                            );
                            None
                        }
                    },
                };
                Some(Config::new(x?, y?, theta?))
            }
            other => {
                self.error(
                    Diag::error(
                        "scen::analyze::wrong_type",
                        format!(
                            "{what} must be a pose `(x, y)` or `(x, y, θ)`, found {}",
                            other.describe()
                        ),
                    )
                    .at(v.span, "expected a pose")
                    .help("write a pose as `(4, 24)` or `(4, 24, 90deg)`"),
                );
                None
            }
        }
    }

    fn polygon_error(&mut self, e: PolygonError, span: Span, vertex_spans: &[Span], what: &str) {
        let d = match e {
            PolygonError::TooFewVertices => Diag::error(
                "scen::analyze::degenerate_polygon",
                format!("{what} has fewer than 3 distinct, non-collinear vertices"),
            )
            .at(span, "not a polygon")
            .help("a polygon needs at least 3 vertices that are not on one line"),
            PolygonError::ZeroArea => Diag::error(
                "scen::analyze::degenerate_polygon",
                format!("{what} encloses no area"),
            )
            .at(span, "zero area")
            .help("check the vertices: they must not all lie on one line"),
            PolygonError::SelfIntersecting { edges: (i, j) } => {
                let n = vertex_spans.len().max(1);
                let at = vertex_spans.get(i).copied().unwrap_or(span);
                let mut d = Diag::error(
                    "scen::analyze::self_intersecting",
                    format!(
                        "{what} is not simple: edge {} crosses edge {}",
                        i + 1,
                        j + 1
                    ),
                )
                .at(at, format!("edge {} starts here", i + 1))
                .help("list the vertices in order around the boundary, without crossings");
                if let Some(s) = vertex_spans.get(j % n) {
                    d = d.with_related(*s, format!("edge {} starts here", j + 1));
                }
                d
            }
        };
        self.error(d);
    }

    // ----------------------------------------------------------------- world

    fn world(&mut self, statements: &[SourcedStmt]) -> (Option<World>, Vec<Span>) {
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
                .map(|s| stmt_span(&s.stmt))
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

    fn obstacle_shape(&mut self, o: &ast::ObstacleDecl) -> Option<Shape> {
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

    fn grid(&mut self, g: &ast::GridSpec, span: Span) -> Option<Grid> {
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

    fn inline_rows(
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

    /// The grid of a map file, which the loader read (SPEC 2.2: the files a
    /// scenario reads are read by the loader, inside the root).
    fn movingai_map(&mut self, f: &Spanned<String>) -> Option<(usize, usize, Vec<u8>)> {
        let id = match self.maps.remove(&f.span) {
            Some(Ok(id)) => id,
            Some(Err(d)) => {
                self.error(d);
                return None;
            }
            // The loader reads every grid's file; a grid it did not see
            // (none in practice) has nothing to analyse.
            None => return None,
        };
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

    // ----------------------------------------------------------------- robots

    fn robots(&mut self, statements: &[SourcedStmt]) -> Vec<Robot> {
        let mut robots: Vec<Robot> = Vec::new();
        let mut seen: HashMap<String, Span> = HashMap::new();
        for s in statements {
            let ast::Stmt::Robot(r) = &s.stmt else {
                continue;
            };
            if let Some(first) = seen.get(&r.name.value) {
                self.error(
                    Diag::error(
                        "scen::analyze::duplicate_name",
                        format!("robot `{}` is declared twice", r.name.value),
                    )
                    .at(r.name.span, "second declaration")
                    .with_related(*first, "first declaration")
                    .help("robot names must be unique; rename one of them"),
                );
                continue;
            }
            seen.insert(r.name.value.clone(), r.name.span);
            let shape = match &r.shape {
                ast::RobotShape::Point(_) => Some(RobotShape::Point),
                ast::RobotShape::Disk(v) => self
                    .expect_positive(v, "the robot's radius")
                    .map(RobotShape::Disk),
                ast::RobotShape::Rect(w, h) => {
                    let (w, h) = (
                        self.expect_positive(w, "the width"),
                        self.expect_positive(h, "the height"),
                    );
                    match (w, h) {
                        (Some(w), Some(h)) => Some(RobotShape::Polygon(ConvexPolygon {
                            vertices: vec![
                                Point::new(0.0, 0.0),
                                Point::new(w, 0.0),
                                Point::new(w, h),
                                Point::new(0.0, h),
                            ],
                        })),
                        _ => None,
                    }
                }
                ast::RobotShape::Polygon(v) => self.robot_polygon(v),
            };
            if shape.is_none() {
                self.invalid_robots.push(r.name.value.clone());
            }
            if let Some(shape) = shape {
                robots.push(Robot {
                    name: r.name.value.clone(),
                    shape,
                    span: r.span,
                });
            }
        }
        robots
    }

    fn robot_polygon(&mut self, v: &Value) -> Option<RobotShape> {
        let (pts, vspans) = self.polygon_points(v, "the robot polygon")?;
        match polygon::normalize_simple_polygon(&pts) {
            Ok(outline) if polygon::is_convex(&outline) => {
                Some(RobotShape::Polygon(ConvexPolygon { vertices: outline }))
            }
            Ok(_) => {
                self.error(
                    Diag::error("scen::analyze::robot_not_convex", "a robot polygon must be convex")
                        .at(v.span, "not convex")
                        .help("planners need convex robots: use the convex hull of this shape, or a smaller convex part"),
                );
                None
            }
            Err(e) => {
                self.polygon_error(e, v.span, &vspans, "the robot polygon");
                None
            }
        }
    }

    // ----------------------------------------------------------------- plans

    fn plans(
        &mut self,
        statements: &[SourcedStmt],
        world: Option<&World>,
        robots: &[Robot],
    ) -> Vec<Plan> {
        let mut plans = Vec::new();
        let mut seen: HashMap<String, Span> = HashMap::new();
        for s in statements {
            let ast::Stmt::Plan(p) = &s.stmt else {
                continue;
            };
            if let Some(first) = seen.get(&p.name.value) {
                self.error(
                    Diag::error(
                        "scen::analyze::duplicate_name",
                        format!("plan `{}` is declared twice", p.name.value),
                    )
                    .at(p.name.span, "second declaration")
                    .with_related(*first, "first declaration")
                    .help("plan names must be unique; rename one of them"),
                );
                continue;
            }
            seen.insert(p.name.value.clone(), p.name.span);
            if let Some(plan) = self.plan(p, world, robots) {
                plans.push(plan);
            }
        }
        plans
    }

    fn plan(&mut self, p: &ast::PlanDecl, world: Option<&World>, robots: &[Robot]) -> Option<Plan> {
        let Some(planner) = registry::planner(&p.kind.value) else {
            let kinds: Vec<&str> = PLANNERS.iter().map(|s| s.kind).collect();
            let mut d = Diag::error(
                "scen::analyze::unknown_planner",
                format!("unknown planner `{}`", p.kind.value),
            )
            .at(p.kind.span, "not a planner kind");
            d = match did_you_mean(&p.kind.value, kinds.iter().copied()) {
                Some(k) => d.help(format!(
                    "did you mean `{k}`? planners: {}",
                    schema::backticked(&kinds)
                )),
                None => d.help(format!("planners: {}", schema::backticked(&kinds))),
            };
            self.error(d);
            return None;
        };
        let robot_index = robots.iter().position(|r| r.name == p.robot.value);
        if robot_index.is_none() && self.invalid_robots.contains(&p.robot.value) {
            // The robot's own error was reported; check the parameters only.
            self.params(p, planner);
            return None;
        }
        let Some(robot_index) = robot_index else {
            let names: Vec<&str> = robots.iter().map(|r| r.name.as_str()).collect();
            let mut d = Diag::error(
                "scen::analyze::unknown_robot",
                format!("unknown robot `{}`", p.robot.value),
            )
            .at(p.robot.span, "no robot of this name");
            d = match did_you_mean(&p.robot.value, names.iter().copied()) {
                Some(n) => d.help(format!("did you mean `{n}`?")),
                None if names.is_empty() => d.help("declare it, e.g. `robot dot disk 0.5`"),
                None => d.help(format!("robots: {}", schema::backticked(&names))),
            };
            self.error(d);
            // Still check the parameters, so their errors show up too.
            self.params(p, planner);
            return None;
        };
        let robot = &robots[robot_index];
        let kind = RobotKind::of(&robot.shape);
        let robot_ok = planner.plans_for(kind);
        if !robot_ok {
            let ok: Vec<&str> = planner.robots.iter().map(|k| k.name()).collect();
            self.error(
                Diag::error(
                    "scen::analyze::robot_kind",
                    format!(
                        "planner `{}` does not plan for {} robots",
                        planner.kind,
                        kind.name()
                    ),
                )
                .at(p.robot.span, format!("a {} robot", kind.name()))
                .help(format!(
                    "`{}` plans for {} robots",
                    planner.kind,
                    ok.join(" and ")
                )),
            );
        }
        let params = self.params(p, planner)?;
        self.configured(p, planner, robot_index, robots, params, world?, robot_ok)
    }

    /// A plan from its validated parameters: the start and goal checked
    /// against the world (SPEC 2.5), then the planner's own check, which
    /// builds its settings (only for a robot it plans for).
    #[allow(clippy::too_many_arguments)]
    fn configured(
        &mut self,
        p: &ast::PlanDecl,
        planner: &'static Planner,
        robot_index: usize,
        robots: &[Robot],
        params: Params,
        world: &World,
        robot_ok: bool,
    ) -> Option<Plan> {
        let robot = &robots[robot_index];
        let before = self.diags.len();
        self.check_pose(world, robot, params.start, params.start_span, "start");
        let start_ok = self.diags.len() == before;
        if let (Some(g), Some(gs)) = (params.goal, params.goal_span) {
            self.check_pose(world, robot, g, gs, "goal");
        }
        // The planner's check may assume a robot it plans for.
        if !robot_ok {
            return None;
        }
        let head = p.name.span.to(p.robot.span);
        let mut args = PlanArgs::new(planner, &p.name.value, head, world, robot, &params);
        args.start_valid = start_ok;
        let settings = (planner.check)(&mut args);
        let ok = args.ok();
        self.diags.extend(args.into_diags());
        let settings = settings.filter(|_| ok)?;
        Some(Plan {
            name: p.name.value.clone(),
            planner,
            robot: robot_index,
            params,
            settings: settings.into(),
            span: p.span,
        })
    }

    /// Groups the plan body's tokens into parameters and validates each
    /// against the planner's schema (types, ranges, required keys).
    fn params(&mut self, p: &ast::PlanDecl, planner: &'static Planner) -> Option<Params> {
        self.params_of(p, &p.body, planner).0
    }

    /// [`Analyzer::params`] of `body` (the plan's own, or a bench's
    /// configuration of it), with the keys given and the tokens each took.
    #[allow(clippy::type_complexity)]
    fn params_of(
        &mut self,
        p: &ast::PlanDecl,
        body: &[ParamToken],
        planner: &'static Planner,
    ) -> (Option<Params>, Vec<(&'static str, std::ops::Range<usize>)>) {
        let set = ParamSet {
            owner: format!("planner `{}`", planner.kind),
            name: format!("`{}`", planner.kind),
            specs: planner.all_params().collect(),
            nested: schema::DRIVE_PARAMS,
            plan: true,
        };
        let mut limits = Limits::default();
        let mut limit_spans: HashMap<&'static str, Span> = HashMap::new();
        let list = self.param_list(body, &set, |this, spec, next, tokens, i| match spec.value {
            ValueSpec::Limit => this.limit(
                &[planner],
                spec,
                next,
                tokens,
                i,
                &mut limits,
                &mut limit_spans,
            ),
            ValueSpec::Drive => {
                let ParamToken::Word(model) = next else {
                    this.wrong_value(spec, next);
                    return Parsed::Bad;
                };
                let block = match tokens.get(*i) {
                    Some(ParamToken::Block { tokens, .. }) => {
                        *i += 1;
                        tokens.as_slice()
                    }
                    _ => &[],
                };
                this.drive_block(model, block)
            }
            _ => this
                .param_value(spec, next)
                .map_or(Parsed::Bad, Parsed::Value),
        });
        let plan_head = p.name.span.to(p.robot.span);
        let list_gave_start = list.gave("start");
        let list_gave_goal = list.gave("goal");
        let ParamList {
            mut values,
            ok,
            given,
        } = list;
        let start = values.remove("start");
        let goal = values.remove("goal");
        if start.is_none() && !list_gave_start {
            self.error(
                Diag::error(
                    "scen::analyze::missing_key",
                    format!("plan `{}` has no `start`", p.name.value),
                )
                .at(plan_head, "needs `start`")
                .help("add `start (x, y)` to the plan's block"),
            );
        }
        if planner.needs_goal && goal.is_none() && !list_gave_goal {
            self.error(
                Diag::error(
                    "scen::analyze::missing_key",
                    format!("plan `{}` has no `goal`", p.name.value),
                )
                .at(plan_head, "needs `goal`")
                .help("add `goal (x, y)` to the plan's block"),
            );
        }
        let (true, Some(start)) = (ok, start) else {
            return (None, given);
        };
        if planner.needs_goal && goal.is_none() {
            return (None, given);
        }
        let ParamValue::Pose(start_c) = start.value else {
            return (None, given);
        };
        let goal_c = match &goal {
            Some(Param {
                value: ParamValue::Pose(c),
                ..
            }) => Some(*c),
            _ => None,
        };
        let seed = values.remove("seed").and_then(|p| match p.value {
            ParamValue::Num(x) => Some(x as u64),
            _ => None,
        });
        let params = Params {
            start: start_c,
            start_span: start.span,
            goal: goal_c,
            goal_span: goal.as_ref().map(|g| g.span),
            limits,
            seed: seed.unwrap_or(0),
            values,
        };
        (Some(params), given)
    }

    /// `drive unicycle { key value ... }`: the model word and the block's
    /// sub-parameters (SPEC 3.6, [`schema::DRIVE_PARAMS`]).
    fn drive_block(&mut self, model: &Spanned<String>, block: &[ParamToken]) -> Parsed {
        let mut ok = true;
        if model.value != "unicycle" {
            self.error(
                Diag::error(
                    "scen::analyze::out_of_range",
                    format!("`drive` does not accept `{}`", model.value),
                )
                .at(model.span, "not a drive model")
                .help("the only drive model is `unicycle`: `drive unicycle { dt 0.01 }`"),
            );
            ok = false;
        }
        let set = ParamSet {
            owner: "`drive unicycle`".into(),
            name: "`drive unicycle`".into(),
            specs: schema::DRIVE_PARAMS.iter().collect(),
            nested: &[],
            plan: false,
        };
        let ParamList {
            values,
            ok: block_ok,
            ..
        } = self.param_list(block, &set, |this, spec, next, _, _| {
            this.param_value(spec, next)
                .map_or(Parsed::Bad, Parsed::Value)
        });
        if ok && block_ok {
            Parsed::Value(ParamValue::Block(model.value.clone(), values))
        } else {
            Parsed::Bad
        }
    }

    /// The tokens of a parameter list (a plan's body, a `drive` block):
    /// `key value...` pairs, each key of `set` at most once unless
    /// repeatable. `value` reads the value starting at `next` (advancing
    /// `i` past any further tokens it takes). Returns the values, the keys
    /// given (even with a bad value) and whether all was well.
    fn param_list(
        &mut self,
        tokens: &[ParamToken],
        set: &ParamSet,
        mut value: impl FnMut(
            &mut Self,
            &'static schema::ParamSpec,
            &ParamToken,
            &[ParamToken],
            &mut usize,
        ) -> Parsed,
    ) -> ParamList {
        let mut values: BTreeMap<&'static str, Param> = BTreeMap::new();
        let mut given: Vec<(&'static str, std::ops::Range<usize>)> = Vec::new();
        let mut ok = true;
        let mut i = 0;
        while i < tokens.len() {
            let tok = &tokens[i];
            let key_at = i;
            i += 1;
            let ParamToken::Word(key) = tok else {
                self.error(
                    Diag::error("scen::analyze::expected_key", "expected a parameter name")
                        .at(tok.span(), "a value without a key")
                        .help(format!("parameters of {}: {}", set.name, set.keys())),
                );
                ok = false;
                continue;
            };
            let Some(spec) = set.get(&key.value) else {
                let mut d = Diag::error(
                    "scen::analyze::unknown_key",
                    format!("unknown parameter `{}` for {}", key.value, set.owner),
                )
                .at(key.span, "unknown key");
                let nested = set.nested.iter().find(|p| p.key == key.value);
                let elsewhere = set.planners_accepting(&key.value);
                d = match (
                    nested,
                    did_you_mean(&key.value, set.specs.iter().map(|p| p.key)),
                ) {
                    (Some(p), _) => d.help(format!(
                        "put it in the drive block: `drive unicycle {{ {} {} }}`",
                        p.key,
                        p.default.text()
                    )),
                    (None, _) if !elsewhere.is_empty() => d.help(format!(
                        "`{}` is a parameter of {} only; {} accepts: {}",
                        key.value,
                        schema::backticked(&elsewhere),
                        set.name,
                        set.keys()
                    )),
                    (None, Some(k)) => {
                        d.help(format!("did you mean `{k}`? accepted: {}", set.keys()))
                    }
                    (None, None) => d.help(format!("accepted: {}", set.keys())),
                };
                self.error(d);
                ok = false;
                // Skip its values: everything up to the next known key.
                while i < tokens.len() {
                    if let ParamToken::Word(w) = &tokens[i]
                        && set.get(&w.value).is_some()
                    {
                        break;
                    }
                    i += 1;
                }
                continue;
            };
            given.push((spec.key, key_at..key_at + 1));
            if !spec.repeatable
                && let Some(first) = values.get(spec.key)
            {
                self.error(
                    Diag::error(
                        "scen::analyze::duplicate_key",
                        format!("`{}` is given twice", spec.key),
                    )
                    .at(key.span, "second time")
                    .with_related(first.span, "first given here")
                    .help("give each parameter once"),
                );
                ok = false;
            }
            let Some(next) = tokens.get(i) else {
                self.missing_value(spec, key.span);
                ok = false;
                break;
            };
            // A known key right after a key means the value is missing.
            if let ParamToken::Word(w) = next
                && !spec.value.takes_word()
                && set.get(&w.value).is_some()
            {
                self.missing_value(spec, key.span);
                ok = false;
                continue;
            }
            i += 1;
            let parsed = value(self, spec, next, tokens, &mut i);
            if let Some((_, range)) = given.last_mut() {
                range.end = i;
            }
            match parsed {
                Parsed::Value(value) => {
                    values.insert(
                        spec.key,
                        Param {
                            value,
                            span: next.span(),
                        },
                    );
                }
                Parsed::Stored => {}
                Parsed::Bad => ok = false,
            }
        }
        ParamList { values, given, ok }
    }

    /// `limit KIND AMOUNT` (repeatable, each kind once), stored in
    /// `limits`; each of `planners` must honour the kind.
    #[allow(clippy::too_many_arguments)]
    fn limit(
        &mut self,
        planners: &[&'static Planner],
        spec: &schema::ParamSpec,
        next: &ParamToken,
        tokens: &[ParamToken],
        i: &mut usize,
        limits: &mut Limits,
        spans: &mut HashMap<&'static str, Span>,
    ) -> Parsed {
        let ParamToken::Word(which) = next else {
            self.wrong_value(spec, next);
            return Parsed::Bad;
        };
        let amount = tokens.get(*i);
        let Some(k) = schema::LIMIT_KINDS.iter().find(|k| **k == which.value) else {
            self.error(
                Diag::error(
                    "scen::analyze::bad_limit",
                    format!("unknown limit `{}`", which.value),
                )
                .at(which.span, "not a limit")
                .help(match planners {
                    [planner] => format!("`{}` stops at {}", planner.kind, limits_of(planner)),
                    _ => format!("`limit` takes {}", spec.value.describe()),
                }),
            );
            if let Some(ParamToken::Value(_)) = amount {
                *i += 1; // its amount
            }
            return Parsed::Bad;
        };
        let Some(ParamToken::Value(v)) = amount else {
            let example = if *k == "time" { "2s" } else { "10000" };
            self.error(
                Diag::error(
                    "scen::analyze::missing_value",
                    format!("`limit {k}` needs an amount"),
                )
                .at(which.span, "no amount")
                .help(format!("write e.g. `limit {k} {example}`")),
            );
            return Parsed::Bad;
        };
        *i += 1;
        let mut ok = true;
        if let Some(planner) = planners.iter().find(|p| !p.limits.contains(k)) {
            self.error(
                Diag::error(
                    "scen::analyze::bad_limit",
                    format!("`{}` does not honour `limit {k}`", planner.kind),
                )
                .at(which.span, "not a limit of this planner")
                .help(format!(
                    "`{}` stops at {}",
                    planner.kind,
                    limits_of(planner)
                )),
            );
            ok = false;
        }
        if let Some(first) = spans.get(k) {
            self.error(
                Diag::error(
                    "scen::analyze::duplicate_key",
                    format!("`limit {k}` is given twice"),
                )
                .at(which.span, "second time")
                .with_related(*first, "first given here")
                .help("give each limit once"),
            );
            ok = false;
        }
        spans.insert(k, which.span);
        match (*k, &v.kind) {
            ("time", ValueKind::Duration(s)) if *s > 0.0 && s.is_finite() => limits.time = Some(*s),
            ("time", _) => {
                self.error(
                    Diag::error(
                        "scen::analyze::bad_limit",
                        "`limit time` needs a positive duration",
                    )
                    .at(v.span, "expected a duration")
                    .help("write `limit time 2s` or `limit time 500ms`"),
                );
                ok = false;
            }
            (_, ValueKind::Number(n)) if *n >= 1.0 && n.fract() == 0.0 && *n <= 1e18 => {
                let n = *n as u64;
                match *k {
                    "expansions" => limits.expansions = Some(n),
                    "steps" => limits.steps = Some(n),
                    "iterations" => limits.iterations = Some(n),
                    _ => limits.cells = Some(n),
                }
            }
            _ => {
                self.error(
                    Diag::error(
                        "scen::analyze::bad_limit",
                        format!("`limit {k}` needs a positive integer"),
                    )
                    .at(v.span, "expected a positive integer")
                    .help(format!("write e.g. `limit {k} 10000`")),
                );
                ok = false;
            }
        }
        if ok { Parsed::Stored } else { Parsed::Bad }
    }

    fn missing_value(&mut self, spec: &schema::ParamSpec, at: Span) {
        self.error(
            Diag::error(
                "scen::analyze::missing_value",
                format!("`{}` needs a value", spec.key),
            )
            .at(at, "no value")
            .help(format!("`{}` takes {}", spec.key, spec.value.describe())),
        );
    }

    fn wrong_value(&mut self, spec: &schema::ParamSpec, tok: &ParamToken) {
        let found = match tok {
            ParamToken::Word(w) => format!("the word `{}`", w.value),
            ParamToken::Value(v) => v.kind.describe().to_string(),
            ParamToken::Block { .. } => "a `{ }` block".to_string(),
        };
        self.error(
            Diag::error(
                "scen::analyze::wrong_type",
                format!(
                    "`{}` takes {}, found {found}",
                    spec.key,
                    spec.value.describe()
                ),
            )
            .at(tok.span(), "unexpected value")
            .help(format!(
                "`{}`: {} (default {})",
                spec.key,
                spec.help,
                if spec.default.text().is_empty() {
                    "none"
                } else {
                    spec.default.text()
                }
            )),
        );
    }

    fn param_value(&mut self, spec: &schema::ParamSpec, tok: &ParamToken) -> Option<ParamValue> {
        match (spec.value, tok) {
            (ValueSpec::Pose, ParamToken::Value(v)) => self
                .expect_pose(v, &format!("`{}`", spec.key))
                .map(ParamValue::Pose),
            (
                ValueSpec::Number {
                    min,
                    min_open,
                    max,
                    integer,
                },
                ParamToken::Value(v),
            ) => {
                let x = match v.kind {
                    ValueKind::Number(x) => x,
                    _ => {
                        self.wrong_value(spec, tok);
                        return None;
                    }
                };
                let below = if min_open { x <= min } else { x < min };
                let ok = !(below || x > max || (integer && x.fract() != 0.0));
                self.in_range(spec, v, x, ok, &format!("{x}"))
            }
            (ValueSpec::IntChoice(choices), ParamToken::Value(v)) => {
                let ValueKind::Number(x) = v.kind else {
                    self.wrong_value(spec, tok);
                    return None;
                };
                if x.fract() == 0.0 && choices.contains(&(x as i64)) {
                    Some(ParamValue::Num(x))
                } else {
                    let all: Vec<String> = choices.iter().map(|c| format!("`{c}`")).collect();
                    let list = match all.split_last() {
                        Some((last, [])) => last.clone(),
                        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
                        None => String::new(),
                    };
                    self.error(
                        Diag::error(
                            "scen::analyze::out_of_range",
                            format!("`{}` must be {list}, got {x}", spec.key),
                        )
                        .at(v.span, "not accepted")
                        .help(format!("`{}`: {}", spec.key, spec.help)),
                    );
                    None
                }
            }
            (ValueSpec::Word(words), ParamToken::Word(w)) => {
                if words.contains(&w.value.as_str()) {
                    Some(ParamValue::Word(w.value.clone()))
                } else {
                    self.bad_word(spec, w, words);
                    None
                }
            }
            (ValueSpec::IntOrWord(words), ParamToken::Word(w)) => {
                if words.contains(&w.value.as_str()) {
                    Some(ParamValue::Word(w.value.clone()))
                } else {
                    self.bad_word(spec, w, words);
                    None
                }
            }
            (ValueSpec::IntOrWord(_), ParamToken::Value(v)) => match v.kind {
                ValueKind::Number(x) => {
                    let ok = x >= 1.0 && x.fract() == 0.0 && x <= 1e9;
                    self.in_range(spec, v, x, ok, &format!("{x}"))
                }
                _ => {
                    self.wrong_value(spec, tok);
                    None
                }
            },
            (ValueSpec::ObstacleName, ParamToken::Word(w)) => {
                Some(ParamValue::Word(w.value.clone()))
            }
            (ValueSpec::Seconds { max }, ParamToken::Value(v)) => match v.kind {
                ValueKind::Number(x) | ValueKind::Duration(x) => {
                    self.in_range(spec, v, x, x > 0.0 && x <= max, &format!("{x}"))
                }
                _ => {
                    self.wrong_value(spec, tok);
                    None
                }
            },
            (ValueSpec::Fraction { min, max }, ParamToken::Value(v)) => match v.kind {
                ValueKind::Percent(x) | ValueKind::Number(x) => {
                    let shown = match v.kind {
                        ValueKind::Percent(_) => format!("{}%", x * 100.0),
                        _ => format!("{x}"),
                    };
                    self.in_range(spec, v, x, x >= min && x <= max, &shown)
                }
                _ => {
                    self.wrong_value(spec, tok);
                    None
                }
            },
            (ValueSpec::Angle { max }, ParamToken::Value(v)) => match v.kind {
                ValueKind::Angle(a) => {
                    let x = self.bounded_angle(v, a)?.radians();
                    let shown = format!("{}deg", x.to_degrees());
                    self.in_range(spec, v, x, x > 0.0 && x <= max, &shown)
                }
                ValueKind::Number(n) => {
                    self.angle_without_unit(
                        v.span,
                        n,
                        format!("`{}` is an angle and needs a unit", spec.key),
                    );
                    None
                }
                _ => {
                    self.wrong_value(spec, tok);
                    None
                }
            },
            _ => {
                self.wrong_value(spec, tok);
                None
            }
        }
    }

    /// An angle within ±1e9 in its unit (SPEC 2.1); beyond, an error at it.
    fn bounded_angle(&mut self, v: &Value, a: ast::Angle) -> Option<ast::Angle> {
        if a.written.abs() <= MAX_MAGNITUDE {
            return Some(a);
        }
        let unit = match a.unit {
            ast::AngleUnit::Deg => "deg",
            ast::AngleUnit::Rad => "rad",
        };
        self.error(
            Diag::error(
                "scen::analyze::number_too_large",
                format!(
                    "the angle is {}{unit}, beyond ±1e9 in its unit",
                    short_number(a.written)
                ),
            )
            .at(v.span, "more than 1e9 in magnitude")
            .help("an angle must lie within ±1e9 in its unit; a heading is taken modulo a full turn, so write it within one turn (`0deg` to `360deg`)"),
        );
        None
    }

    /// A bare number `n` where an angle is expected: says which units to add.
    fn angle_without_unit(&mut self, span: Span, n: f64, message: String) {
        self.error(
            Diag::error("scen::analyze::angle_unit", message)
                .at(span, "a bare number")
                .help(format!("write `{n}deg` or `{n}rad`")),
        );
    }

    /// `x` (shown as `shown`) if `ok`, else an out-of-range error.
    fn in_range(
        &mut self,
        spec: &schema::ParamSpec,
        v: &Value,
        x: f64,
        ok: bool,
        shown: &str,
    ) -> Option<ParamValue> {
        if ok {
            return Some(ParamValue::Num(x));
        }
        self.error(
            Diag::error(
                "scen::analyze::out_of_range",
                format!(
                    "`{}` must be {}, got {shown}",
                    spec.key,
                    spec.value.describe()
                ),
            )
            .at(v.span, "out of range")
            .help(format!("`{}`: {}", spec.key, spec.help)),
        );
        None
    }

    fn bad_word(&mut self, spec: &schema::ParamSpec, w: &Spanned<String>, words: &[&str]) {
        let mut d = Diag::error(
            "scen::analyze::out_of_range",
            format!("`{}` does not accept `{}`", spec.key, w.value),
        )
        .at(w.span, "not accepted");
        d = match did_you_mean(&w.value, words.iter().copied()) {
            Some(s) => d.help(format!(
                "did you mean `{s}`? `{}` takes {}",
                spec.key,
                spec.value.describe()
            )),
            None => d.help(format!("`{}` takes {}", spec.key, spec.value.describe())),
        };
        self.error(d);
    }

    fn check_pose(&mut self, world: &World, robot: &Robot, c: Config, span: Span, which: &str) {
        if !world.bounds.contains(c.xy()) {
            let b = world.bounds;
            self.error(
                Diag::error(
                    "scen::analyze::pose_outside",
                    format!("the {which} lies outside the world's bounds"),
                )
                .at(span, "outside `bounds`")
                .help(format!(
                    "the bounds are ({}, {}) to ({}, {})",
                    b.min.x, b.min.y, b.max.x, b.max.y
                )),
            );
            return;
        }
        if let Some(i) = crate::geometry::validator::config_collision(world, &robot.shape, c) {
            self.error(
                Diag::error(
                    "scen::analyze::pose_in_collision",
                    format!(
                        "the {which} is in collision with obstacle `{}`",
                        world.obstacles[i].name
                    ),
                )
                .at(
                    span,
                    format!(
                        "robot `{}` overlaps `{}` here",
                        robot.name, world.obstacles[i].name
                    ),
                )
                .help(format!(
                    "move the {which} so that the robot's body is clear of every obstacle"
                )),
            );
        }
    }
}

/// The help line of a number beyond ±1e9.
const MAGNITUDE_HELP: &str = "coordinates, lengths, radii and cell sizes must lie within ±1e9, where f64 geometry keeps the precision the validator needs (1e-9): use larger units, or move the scene towards (0, 0)";

/// `x` as a user would write it: `2147483648`, `1e308`.
fn short_number(x: f64) -> String {
    if x.abs() >= 1e15 {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// The parameters a list may give (a plan's, a `drive` block's), and how
/// messages name its owner.
struct ParamSet {
    /// After "unknown parameter `k` for": "planner `KIND`".
    owner: String,
    /// After "parameters of": "`KIND`".
    name: String,
    specs: Vec<&'static schema::ParamSpec>,
    /// The keys of the `drive` block nested in this list, for a help line
    /// when one is written outside it.
    nested: &'static [schema::ParamSpec],
    /// A plan's list: an unknown key that other planners take names them.
    plan: bool,
}

impl ParamSet {
    /// The planners that take `key` as one of their own parameters (for a
    /// plan's list; none for other lists).
    fn planners_accepting(&self, key: &str) -> Vec<&'static str> {
        if !self.plan {
            return Vec::new();
        }
        PLANNERS
            .iter()
            .filter(|p| p.params.iter().any(|s| s.key == key))
            .map(|p| p.kind)
            .collect()
    }

    fn get(&self, key: &str) -> Option<&'static schema::ParamSpec> {
        self.specs.iter().copied().find(|p| p.key == key)
    }

    fn keys(&self) -> String {
        let keys: Vec<&str> = self.specs.iter().map(|p| p.key).collect();
        schema::backticked(&keys)
    }
}

/// The parameters of a list: the values, the keys given (even with a bad
/// value) with the tokens each took, and whether all was well.
struct ParamList {
    values: BTreeMap<&'static str, Param>,
    given: Vec<(&'static str, std::ops::Range<usize>)>,
    ok: bool,
}

impl ParamList {
    fn gave(&self, key: &str) -> bool {
        self.given.iter().any(|(k, _)| *k == key)
    }
}

/// What reading a parameter's value gave.
enum Parsed {
    Value(ParamValue),
    /// Valid, and kept elsewhere (`limit`).
    Stored,
    /// Reported.
    Bad,
}

/// The limits a planner honours, as a user writes them.
fn limits_of(planner: &Planner) -> String {
    planner
        .limits
        .iter()
        .map(|&l| {
            if l == "time" {
                "`limit time 2s`".to_string()
            } else {
                format!("`limit {l} N`")
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn stmt_span(s: &ast::Stmt) -> Span {
    match s {
        ast::Stmt::Scenario { span, .. } | ast::Stmt::Include { span, .. } => *span,
        ast::Stmt::World(w) => w.span,
        ast::Stmt::Robot(r) => r.span,
        ast::Stmt::Plan(p) => p.span,
        ast::Stmt::Expect(e) => e.span,
        ast::Stmt::Bench(b) => b.span,
    }
}
