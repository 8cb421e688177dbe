//! Analysis: an AST (with includes resolved) becomes a [`Scenario`]: names
//! resolved, geometry checked and normalised, plan parameters validated
//! against their planner's schema, expressions typed.

mod analyze;
pub mod family;
pub mod grouping;
pub mod loader;
pub mod movingai;
mod placed;
mod statements;

use std::path::PathBuf;
use std::sync::Arc;

use crate::contract::{Agent, Limits, ParamValue, Params, Planner, Robot, Settings, Task};
use crate::diagnostics::{SourceMap, Span};
use crate::geometry::World;
use crate::syntax::ast::Expr;

pub(crate) use analyze::analyze;
pub use analyze::{AGGREGATES, BENCH_KEYS};
pub use family::SampleChoice;
pub use loader::{load, load_member, load_sample, load_with};

/// A fully analysed scenario, ready to run.
#[derive(Clone, Debug)]
pub struct Scenario {
    /// The main file, as given by the user.
    pub file: PathBuf,
    pub title: Option<String>,
    pub world: World,
    /// Span of each obstacle's declaration, parallel to `world.obstacles`.
    pub obstacle_spans: Vec<Span>,
    /// The obstacles that move (SPEC 2.9), and their declarations' spans.
    pub moving: Vec<crate::geometry::timed::MovingObstacle>,
    pub moving_spans: Vec<Span>,
    pub robots: Vec<Robot>,
    pub plans: Vec<Plan>,
    pub benches: Vec<Bench>,
    pub checks: Vec<Check>,
    pub sources: SourceMap,
    /// For a family (SPEC 2.8): the sample this scenario is and what it
    /// drew; `None` for a scenario without params.
    pub family: Option<family::Drawn>,
    /// For a family: how to draw its other samples ([`Scenario::sample`]).
    pub template: Option<Arc<loader::Template>>,
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

impl Scenario {
    /// `scen bench --worlds N` (SPEC §4): every bench runs on samples
    /// 0 … N − 1 of the family. An error for a scenario that draws nothing.
    pub fn override_worlds(&mut self, worlds: u64) -> Result<(), String> {
        if self.template.is_none() {
            return Err(format!(
                "`--worlds {worlds}`: `{}` draws nothing (no `param`, no `scatter`), so every world would be the same; use `--runs` for more seeds",
                self.file.display()
            ));
        }
        for bench in &mut self.benches {
            bench.worlds = worlds;
        }
        Ok(())
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
    /// The samples of the family each configuration runs on (`worlds N`:
    /// samples 0 … N − 1, SPEC 2.8); 1 without `worlds`: the scenario as
    /// loaded.
    pub worlds: u64,
    /// Where `worlds N` was written.
    pub worlds_span: Option<Span>,
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

    /// The planning problem of this plan in `scenario`, its layers drawn.
    pub fn task<'s>(&self, scenario: &'s Scenario) -> Task<'s> {
        Task {
            world: &scenario.world,
            robot: &scenario.robots[self.robot].shape,
            start: self.params.start,
            goal: self.params.goal,
            limits: self.params.limits,
            seed: self.params.seed,
            steering: scenario.robots[self.robot].steering,
            draw: true,
            referee: None,
            moving: &scenario.moving,
            speed: scenario.robots[self.robot].speed,
            agents: self.team(scenario).unwrap_or(&[]),
        }
    }

    /// The agents this plan plans when its robot is a team: the team's
    /// first N with `agents N`, else all of them (`None`: not a team).
    pub fn team<'s>(&self, scenario: &'s Scenario) -> Option<&'s [Agent]> {
        let team = scenario.robots[self.robot].team.as_deref()?;
        Some(match self.params.get("agents") {
            Some(ParamValue::Num(n)) => &team[..(*n as usize).min(team.len())],
            _ => team,
        })
    }
}

#[cfg(any(test, feature = "testing"))]
impl Plan {
    /// A plan of `planner` from `start` to `goal` with no parameters, for
    /// tests of the sinks: its settings cannot run (they panic if asked).
    pub fn fixture(
        name: &str,
        planner: &'static Planner,
        robot: usize,
        start: crate::geometry::Config,
        goal: Option<crate::geometry::Config>,
    ) -> Plan {
        #[derive(Debug)]
        struct NotRun;
        impl Settings for NotRun {
            fn plan(&self, _: &Task<'_>) -> crate::contract::PlanOutcome {
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
                values: std::collections::BTreeMap::new(),
            },
            settings: Arc::new(NotRun),
            span: Span::default(),
        }
    }
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
#[cfg(any(test, feature = "testing"))]
pub fn load_text(text: &str) -> Scenario {
    with_temp_file(text, |path| match loader::load(path) {
        Ok(s) => s,
        Err(f) => panic!("{:?}", f.diags),
    })
}

/// The world of a text that may have no plan yet; panics on diagnostics.
/// For tests that probe a world before they write its plans.
#[cfg(any(test, feature = "testing"))]
pub fn world_of_text(text: &str) -> World {
    with_temp_file(text, |path| {
        let parsed = loader::parse_scenario(path, None, &|_| None);
        assert!(parsed.diags.is_empty(), "{:?}", parsed.diags);
        analyze::world_of(&parsed.statements, parsed.sources, parsed.maps)
    })
}

#[cfg(any(test, feature = "testing"))]
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
