//! AST → [`Scenario`]: names resolved, geometry checked and normalised,
//! plan parameters grouped and validated against their planner's schema,
//! `expect` expressions typed. Every problem becomes a [`Diag`]; analysis
//! goes on after an error so that all of them are reported at once.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use crate::contract::schema::{self, MetricType};
use crate::contract::{Param, ParamValue, Planner};
use crate::diagnostics::{Diag, FileId, SourceMap, Span};
use crate::planners::registry::PLANNERS;
use crate::syntax::ast;

use super::Scenario;
use super::statements::{LoadFailure, SourcedStmt};

mod bench;
mod expect;
mod moving;
mod plans;
mod robots;
mod team;
mod values;
mod world;

pub use bench::BENCH_KEYS;
pub use expect::AGGREGATES;

/// The world of a scenario's statements alone (no robot or plan needed),
/// for tests that probe a world before they write its plans; panics on
/// diagnostics.
#[cfg(any(test, feature = "testing"))]
pub(crate) fn world_of(
    statements: &[SourcedStmt],
    sources: SourceMap,
    maps: HashMap<Span, Result<FileId, Diag>>,
) -> crate::geometry::World {
    let mut a = Analyzer {
        sources,
        maps,
        diags: Vec::new(),
        invalid_robots: Vec::new(),
    };
    let (world, _) = a.world(statements);
    assert!(a.diags.is_empty(), "{:?}", a.diags);
    world.expect("a world")
}

/// Analyses the statements of a scenario (includes already spliced in).
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
    let (moving, moving_spans) = match &world {
        Some(w) => a.moving(&statements, w, &obstacle_spans),
        None => (Vec::new(), Vec::new()),
    };
    let robots = a.robots(&statements, world.as_ref());
    let world_ok = !a.diags.iter().any(Diag::is_error);
    a.needs_time(&statements, &moving);
    let plans = a.plans(&statements, world.as_ref().filter(|_| world_ok), &robots);
    a.start_hit(&plans, &robots, &moving);
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
            moving,
            moving_spans,
            robots,
            plans,
            benches,
            checks,
            sources,
            family: None,
            template: None,
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
    /// A `drive` block may be nested in this list (a plan's): a help line
    /// says to put a drive key written outside it there.
    nested: bool,
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
