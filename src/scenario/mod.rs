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
pub use analyze::{AGGREGATES, BENCH_KEYS};
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
    pub benches: Vec<Bench>,
    pub checks: Vec<Check>,
    pub sources: SourceMap,
}

impl Scenario {
    /// `scen bench --runs N` (SPEC §4): every bench runs `runs` seeds per
    /// configuration of a randomized planner (a deterministic one still
    /// runs once).
    pub fn override_runs(&mut self, runs: u64) {
        let Scenario { benches, plans, .. } = self;
        for bench in benches {
            bench.runs = runs;
            for p in &mut bench.plans {
                p.runs = if plans[p.plan].planner.randomized {
                    runs
                } else {
                    1
                };
            }
        }
    }
}

/// A `bench` statement (SPEC 2.7): plans × configurations × runs.
#[derive(Clone, Debug)]
pub struct Bench {
    pub name: String,
    pub span: Span,
    /// The plans it runs, in the order of its `plans` list (default: every
    /// plan of the file, in declaration order).
    pub plans: Vec<BenchPlan>,
    /// The varied keys, in the order written; configurations are their
    /// combinations, the last key varying fastest.
    pub vary: Vec<Vary>,
    /// Runs per configuration of a randomized planner (`runs`, default 1).
    pub runs: u64,
    /// Limits added to every run's own (the smaller one holds).
    pub limits: Limits,
}

/// One plan of a bench, with every configuration's plan.
#[derive(Clone, Debug)]
pub struct BenchPlan {
    /// Index into `Scenario::plans`.
    pub plan: usize,
    /// The plan with each configuration's values, indexed like
    /// [`Bench::config_values`].
    pub configs: Vec<Plan>,
    /// Runs per configuration: the bench's `runs` for a randomized planner,
    /// else 1.
    pub runs: u64,
}

/// `vary KEY [values]`.
#[derive(Clone, Debug)]
pub struct Vary {
    pub key: String,
    pub span: Span,
    pub values: Vec<VaryValue>,
}

/// One value of a `vary` list: as written (for tables and files), and as
/// parsed (for selections).
#[derive(Clone, Debug)]
pub struct VaryValue {
    pub text: String,
    pub value: crate::syntax::ast::Value,
}

impl Bench {
    /// The number of configurations (1 without `vary`).
    pub fn configurations(&self) -> usize {
        self.vary.iter().map(|v| v.values.len()).product()
    }

    /// The index of each varied key's value in configuration `config`.
    pub fn config_values(&self, config: usize) -> Vec<usize> {
        let mut rest = config;
        let mut out = vec![0; self.vary.len()];
        for (k, v) in self.vary.iter().enumerate().rev() {
            let n = v.values.len().max(1);
            out[k] = rest % n;
            rest /= n;
        }
        out
    }

    /// The total runs of the bench.
    pub fn total_runs(&self) -> u64 {
        self.plans
            .iter()
            .map(|p| p.runs * p.configs.len() as u64)
            .sum()
    }
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

impl Limits {
    /// Both sets of limits: the smaller of each kind holds.
    pub fn and(self, other: Limits) -> Limits {
        fn min<T: PartialOrd>(a: Option<T>, b: Option<T>) -> Option<T> {
            match (a, b) {
                (Some(a), Some(b)) => Some(if b < a { b } else { a }),
                (a, b) => a.or(b),
            }
        }
        Limits {
            expansions: min(self.expansions, other.expansions),
            steps: min(self.steps, other.steps),
            time: min(self.time, other.time),
            cells: min(self.cells, other.cells),
            iterations: min(self.iterations, other.iterations),
        }
    }
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
    /// It reads a bench's series: `scen bench` and `scen test` evaluate it,
    /// `scen run` does not.
    pub bench: bool,
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
    with_temp_file(text, |path| match loader::load(path) {
        Ok(s) => s,
        Err(f) => panic!("{:?}", f.diags),
    })
}

/// The world of a text that may have no plan yet; panics on diagnostics.
/// For tests that probe a world before they write its plans.
#[cfg(test)]
pub(crate) fn world_of_text(text: &str) -> World {
    with_temp_file(text, analyze::world_of)
}

#[cfg(test)]
fn with_temp_file<T>(text: &str, f: impl FnOnce(&std::path::Path) -> T) -> T {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let n = COUNTER.fetch_add(1, Ordering::SeqCst);
    let path = std::env::temp_dir().join(format!("scen-test-{}-{n}.scen", std::process::id()));
    std::fs::write(&path, text).expect("write the scenario");
    let out = f(&path);
    let _ = std::fs::remove_file(&path);
    out
}
