//! Analysis: an AST (with includes resolved) becomes a [`Scenario`]: names
//! resolved, geometry checked and normalised, plan parameters validated
//! against their planner's schema, expressions typed.

mod analyze;
mod args;
pub mod grouping;
pub mod loader;
pub mod movingai;
pub mod schema;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use crate::diagnostics::{SourceMap, Span};
use crate::geometry::{Config, Point, RobotShape, World};
use crate::planners::registry::{Planner, Settings, Task};
use crate::syntax::ast::Expr;

pub(crate) use analyze::analyze;
pub use args::PlanArgs;
pub use loader::{load, load_with};

/// A fully analysed scenario, ready to run.
#[derive(Clone, Debug)]
pub struct Scenario {
    /// The main file, as given by the user.
    pub file: PathBuf,
    pub title: Option<String>,
    pub world: World,
    /// Span of each obstacle's declaration, parallel to `world.obstacles`.
    pub obstacle_spans: Vec<Span>,
    pub robots: Vec<Robot>,
    pub plans: Vec<Plan>,
    pub checks: Vec<Check>,
    pub sources: SourceMap,
}

#[derive(Clone, Debug)]
pub struct Robot {
    pub name: String,
    pub shape: RobotShape,
    pub span: Span,
}

#[derive(Clone, Debug)]
pub struct Plan {
    pub name: String,
    /// Its planner, from the registry.
    pub planner: &'static Planner,
    /// Index into `Scenario::robots`.
    pub robot: usize,
    pub params: Params,
    /// The planner's typed settings, built from `params` by its `check`.
    pub settings: Arc<dyn Settings>,
    pub span: Span,
}

impl Plan {
    /// The planner kind (`astar`, `online`, ...).
    pub fn kind(&self) -> &'static str {
        self.planner.kind
    }

    /// The planning problem of this plan in `scenario`.
    pub fn task<'s>(&self, scenario: &'s Scenario) -> Task<'s> {
        Task {
            world: &scenario.world,
            robot: &scenario.robots[self.robot].shape,
            start: self.params.start,
            goal: self.params.goal,
            limits: self.params.limits,
            seed: self.params.seed,
        }
    }
}

#[cfg(test)]
impl Plan {
    /// A plan of `planner` from `start` to `goal` with no parameters, for
    /// tests of the sinks: its settings cannot run (they panic if asked).
    pub(crate) fn fixture(
        name: &str,
        planner: &'static Planner,
        robot: usize,
        start: Config,
        goal: Option<Config>,
    ) -> Plan {
        #[derive(Debug)]
        struct NotRun;
        impl Settings for NotRun {
            fn plan(&self, _: &Task<'_>) -> crate::planners::PlanOutcome {
                unreachable!("a fixture plan is never run")
            }
            fn as_any(&self) -> &dyn std::any::Any {
                self
            }
        }
        Plan {
            name: name.into(),
            planner,
            robot,
            params: Params {
                start,
                start_span: Span::default(),
                goal,
                goal_span: None,
                limits: Limits::default(),
                seed: 0,
                values: BTreeMap::new(),
            },
            settings: Arc::new(NotRun),
            span: Span::default(),
        }
    }
}

/// Validated parameters of a plan, as written: keys not given by the user
/// are absent (the planner's `check` reads the schema's defaults through
/// [`PlanArgs`]).
#[derive(Clone, Debug)]
pub struct Params {
    pub start: Config,
    pub start_span: Span,
    pub goal: Option<Config>,
    pub goal_span: Option<Span>,
    pub limits: Limits,
    pub seed: u64,
    pub values: BTreeMap<&'static str, Param>,
}

impl Params {
    pub fn get(&self, key: &str) -> Option<&ParamValue> {
        self.values.get(key).map(|p| &p.value)
    }
}

/// Limits of SPEC 2.5 (`limit expansions N`, `limit time 2s`, ...).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Limits {
    pub expansions: Option<u64>,
    pub steps: Option<u64>,
    /// Seconds.
    pub time: Option<f64>,
    /// Lattice-size cap (default [`DEFAULT_CELL_CAP`]).
    pub cells: Option<u64>,
    /// Samples drawn, for the sampling-based planners.
    pub iterations: Option<u64>,
}

/// The default cap on lattice sizes (SPEC 3.1).
pub const DEFAULT_CELL_CAP: u64 = 200_000_000;

#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    pub value: ParamValue,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ParamValue {
    Num(f64),
    Word(String),
    Str(String),
    Point(Point),
    Pose(Config),
    /// A word with nested parameters (`drive unicycle { dt 0.02 }`).
    Block(String, BTreeMap<&'static str, Param>),
}

/// One `expect` statement.
#[derive(Clone, Debug)]
pub struct Check {
    pub expr: Expr,
    /// The expression's source text.
    pub text: String,
    pub line: usize,
    pub span: Span,
}

/// Loads a scenario from text (written to a fresh temporary file, so
/// includes and spans work as for a file); panics on diagnostics. For tests.
#[cfg(test)]
pub(crate) fn load_text(text: &str) -> Scenario {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let n = COUNTER.fetch_add(1, Ordering::SeqCst);
    let path = std::env::temp_dir().join(format!("scen-test-{}-{n}.scen", std::process::id()));
    std::fs::write(&path, text).expect("write the scenario");
    let s = loader::load(&path);
    let _ = std::fs::remove_file(&path);
    match s {
        Ok(s) => s,
        Err(f) => panic!("{:?}", f.diags),
    }
}
