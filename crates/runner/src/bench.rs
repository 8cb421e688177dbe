//! Running benches (SPEC 2.7, §4 `scen bench`): every run of every
//! configuration of every plan of a bench, in parallel, with results that
//! depend neither on the number of threads nor on how the runs were split
//! over machines (`--shard K/N`).
//!
//! Runs are numbered in one order for the whole file — bench, then plan,
//! then configuration, then world, then run — and run `i` of a
//! configuration uses seed = the plan's `seed` + `i`, on every world. A
//! bench with `worlds N` runs each configuration on samples 0 … N − 1 of
//! the family ([`Worlds`]). Shard K of N takes the runs whose number is
//! K − 1 modulo N, so N shards do every run exactly once, and each shard's
//! share of a bench is spread over its configurations.

use std::collections::BTreeMap;

use rayon::prelude::*;

use crate::checks::{self, Values};
use crate::contract::{MetricValue, Metrics, Task};
use crate::run::{self, BenchRun, RunReport};
use crate::scenario::{Bench, Scenario};
use crate::syntax::ast::Selection;

/// Where a run sits: its number in the file's order, and its coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RunId {
    pub index: u64,
    pub bench: usize,
    pub plan: usize,
    pub config: usize,
    /// The sample of the family it runs on (0 without `worlds`).
    pub world: u64,
    pub run: u64,
}

/// The scenarios a file's benches run on: the one loaded, and for a bench
/// with `worlds N` the samples 0 … N − 1 of its family.
pub struct Worlds {
    samples: Vec<Scenario>,
}

impl Worlds {
    /// Draws the samples the benches in `only` (all when empty) need, in
    /// parallel. A sample that cannot be drawn is an error with its
    /// diagnostics.
    pub fn draw(
        scenario: &Scenario,
        only: &[String],
    ) -> Result<Worlds, crate::scenario::loader::LoadFailure> {
        let n = scenario
            .benches
            .iter()
            .filter(|b| only.is_empty() || only.contains(&b.name))
            .map(|b| b.worlds)
            .max()
            .unwrap_or(1);
        if n <= 1 {
            return Ok(Worlds {
                samples: Vec::new(),
            });
        }
        let samples: Result<Vec<Scenario>, _> =
            (0..n).into_par_iter().map(|k| scenario.sample(k)).collect();
        Ok(Worlds { samples: samples? })
    }

    /// The scenario of `world` (the loaded one for a bench without `worlds`).
    pub fn get<'a>(&'a self, scenario: &'a Scenario, id: &RunId) -> &'a Scenario {
        if scenario.benches[id.bench].worlds <= 1 {
            return scenario;
        }
        &self.samples[id.world as usize]
    }
}

/// `--shard K/N`: the K-th of N parts (1 ≤ K ≤ N).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub k: u64,
    pub n: u64,
}

impl Shard {
    /// Parses `K/N`.
    pub fn parse(text: &str) -> Result<Shard, String> {
        let bad =
            || format!("`{text}` is not a shard: write `K/N` with 1 ≤ K ≤ N, e.g. `--shard 3/8`");
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let (k, n): (u64, u64) = (
            k.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if k == 0 || n == 0 || k > n {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }

    /// Whether item `index` (0-based) belongs to this shard.
    pub fn takes(&self, index: u64) -> bool {
        index % self.n == self.k - 1
    }

    /// The number of this shard's `local`-th item (0-based) among all.
    pub fn nth(&self, local: u64) -> u64 {
        local * self.n + self.k - 1
    }

    /// How many of the items 0 … total − 1 this shard takes.
    pub fn share(&self, total: u64) -> u64 {
        if total < self.k {
            0
        } else {
            (total - self.k) / self.n + 1
        }
    }
}

/// The benches named in `names` exist (an error names the unknown one and
/// lists the scenario's benches).
pub fn known_benches(scenario: &Scenario, names: &[String]) -> Result<(), String> {
    match names
        .iter()
        .find(|n| !scenario.benches.iter().any(|b| &b.name == *n))
    {
        Some(unknown) => {
            let all: Vec<&str> = scenario.benches.iter().map(|b| b.name.as_str()).collect();
            Err(format!(
                "no bench `{unknown}` (benches: {})",
                if all.is_empty() {
                    "none".to_string()
                } else {
                    all.join(", ")
                }
            ))
        }
        None => Ok(()),
    }
}

/// Why a bench cannot start: a message, or a family's sample that cannot
/// be drawn (its diagnostics).
pub enum Unready {
    Message(String),
    Load(crate::scenario::loader::LoadFailure),
}

/// What a bench runs: the scenario with `--runs N` and `--worlds N`
/// applied, the worlds its benches run on, and its runs (those of the
/// benches in `only`, all when empty; only shard `shard`'s when given).
pub struct Prepared {
    pub scenario: Scenario,
    pub worlds: Worlds,
    pub ids: Vec<RunId>,
}

/// Readies `scenario`'s benches to run, as `scen bench` does: the
/// overrides, the runs of the shard, the worlds drawn.
pub fn prepare(
    mut scenario: Scenario,
    only: &[String],
    runs: Option<u64>,
    worlds: Option<u64>,
    shard: Option<Shard>,
) -> Result<Prepared, Unready> {
    known_benches(&scenario, only).map_err(Unready::Message)?;
    if let Some(n) = runs {
        scenario.override_runs(n);
    }
    if let Some(n) = worlds {
        scenario.override_worlds(n).map_err(Unready::Message)?;
    }
    let mut ids = run_ids(&scenario, only);
    if let Some(s) = shard {
        if s.n > ids.len() as u64 {
            return Err(Unready::Message(format!(
                "`--shard {}/{}`: `{}` has only {} bench run(s) to split; N may be at most {}",
                s.k,
                s.n,
                scenario.file.display(),
                ids.len(),
                ids.len()
            )));
        }
        ids.retain(|id| s.takes(id.index));
    }
    let worlds = Worlds::draw(&scenario, only).map_err(Unready::Load)?;
    Ok(Prepared {
        scenario,
        worlds,
        ids,
    })
}

/// Every run of the file's benches, in order, for the benches named in
/// `only` (all when empty).
pub fn run_ids(scenario: &Scenario, only: &[String]) -> Vec<RunId> {
    let mut ids = Vec::new();
    let mut index = 0;
    for (b, bench) in scenario.benches.iter().enumerate() {
        for (p, plan) in bench.plans.iter().enumerate() {
            for config in 0..plan.configs.len() {
                for world in 0..bench.worlds {
                    for run in 0..plan.runs {
                        if only.is_empty() || only.contains(&bench.name) {
                            ids.push(RunId {
                                index,
                                bench: b,
                                plan: p,
                                config,
                                world,
                                run,
                            });
                        }
                        index += 1;
                    }
                }
            }
        }
    }
    ids
}

/// Runs one run, on its world.
pub fn execute(scenario: &Scenario, worlds: &Worlds, id: &RunId) -> BenchRun {
    let scenario = worlds.get(scenario, id);
    let bench_plan = &scenario.benches[id.bench].plans[id.plan];
    let task = task_of(scenario, id);
    let ran = run::run_task(
        scenario,
        bench_plan.plan,
        &bench_plan.configs[id.config],
        &task,
    );
    BenchRun {
        bench: id.bench,
        plan: id.plan,
        config: id.config,
        world: id.world,
        run: id.run,
        seed: task.seed,
        metrics: ran.metrics,
    }
}

/// The task of a bench run: its configuration's plan, the run's seed, the
/// bench's limits added; and no layers, since a bench draws no world
/// picture (its tables and plots are of metrics), so no planner records
/// what only a picture would show.
fn task_of<'s>(scenario: &'s Scenario, id: &RunId) -> Task<'s> {
    let bench = &scenario.benches[id.bench];
    let plan = &bench.plans[id.plan].configs[id.config];
    Task {
        seed: plan.params.seed.wrapping_add(id.run),
        limits: plan.params.limits.and(bench.limits),
        draw: false,
        ..plan.task(scenario)
    }
}

/// Runs `ids` in parallel; `tick` is called after each run (a progress
/// bar). The results are in the order of `ids`.
pub fn run_all(
    scenario: &Scenario,
    worlds: &Worlds,
    ids: &[RunId],
    tick: &(dyn Fn() + Sync),
) -> Vec<BenchRun> {
    ids.par_iter()
        .map(|id| {
            let r = execute(scenario, worlds, id);
            tick();
            r
        })
        .collect()
}

/// The report of a bench run: the file's plain plans run too (their checks
/// and the bench checks that read their metrics need them), then every
/// check whose plans and benches ran.
pub fn report(scenario: Scenario, runs: Vec<BenchRun>) -> RunReport {
    let mut report = run::run_scenario_drawing(scenario, &[], false);
    report.bench_runs = runs;
    evaluate(&mut report);
    report
}

/// (Re)evaluates every check of a report whose plans and benches ran.
pub fn evaluate(report: &mut RunReport) {
    let ran: Vec<bool> = (0..report.scenario.benches.len())
        .map(|b| report.bench_runs.iter().any(|r| r.bench == b))
        .collect();
    let values = BenchValues {
        scenario: &report.scenario,
        plans: run::metrics_by_plan(&report.scenario, &report.plans),
        runs: &report.bench_runs,
    };
    let (checks, skipped) = run::evaluate_checks(&report.scenario, &values, |c| {
        let mut benches = Vec::new();
        benches_used(&c.expr, &mut benches);
        benches.iter().all(|name| {
            report
                .scenario
                .benches
                .iter()
                .position(|b| &b.name == name)
                .is_some_and(|b| ran[b])
        })
    });
    report.checks = checks;
    report.skipped = skipped;
}

/// What bench checks read: the plain plans' metrics and the bench runs.
struct BenchValues<'a> {
    scenario: &'a Scenario,
    plans: BTreeMap<&'a str, &'a Metrics>,
    runs: &'a [BenchRun],
}

impl Values for BenchValues<'_> {
    fn metrics(&self, plan: &str) -> Option<&Metrics> {
        self.plans.get(plan).copied()
    }

    fn series(
        &self,
        bench: &str,
        plan: &str,
        select: &[Selection],
        metric: &str,
    ) -> Option<Vec<MetricValue>> {
        let b = self.scenario.benches.iter().position(|x| x.name == bench)?;
        let bench = &self.scenario.benches[b];
        let p = bench
            .plans
            .iter()
            .position(|x| self.scenario.plans[x.plan].name == plan)?;
        let wanted = selection(bench, select)?;
        Some(
            self.runs
                .iter()
                .filter(|r| r.bench == b && r.plan == p)
                .filter(|r| {
                    let values = bench.config_values(r.config);
                    wanted.iter().all(|&(k, v)| values[k] == v)
                })
                .map(|r| {
                    r.metrics
                        .get(metric)
                        .copied()
                        .unwrap_or(MetricValue::Num(f64::NAN))
                })
                .collect(),
        )
    }
}

/// A selection as (index of the varied key, index of its value).
fn selection(bench: &Bench, select: &[Selection]) -> Option<Vec<(usize, usize)>> {
    select
        .iter()
        .map(|s| {
            let k = bench.vary.iter().position(|v| v.key == s.key.value)?;
            let v = bench.vary[k]
                .values
                .iter()
                .position(|x| x.value.same(&s.value))?;
            Some((k, v))
        })
        .collect()
}

/// The benches an expression reads.
fn benches_used(expr: &crate::syntax::ast::Expr, out: &mut Vec<String>) {
    expr.walk(&mut |e| {
        if let crate::syntax::ast::ExprKind::Series { bench, .. } = &e.kind
            && !out.contains(&bench.value)
        {
            out.push(bench.value.clone());
        }
    });
}

impl Row {
    /// The 95 % Wilson score interval of the success rate, as fractions.
    pub fn success_ci(&self) -> (f64, f64) {
        crate::stats::wilson(self.successes, self.runs)
    }
}

/// The metrics the table shows by default (SPEC 4).
pub const TABLE_METRICS: &[&str] = &[
    "time_ms",
    "length",
    "cost",
    "expanded",
    "clearance",
    "smoothness",
];

/// The metrics a table shows by default when every plan of the benches
/// plans a team (SPEC 2.10): a team has no one path to measure, so its
/// columns are its sums of costs, makespan and their lower bound.
pub const TEAM_TABLE_METRICS: &[&str] = &[
    "time_ms",
    "sum_of_costs",
    "makespan",
    "soc_lower_bound",
    "expanded",
];

/// The default columns of `scenario`'s bench tables: [`TABLE_METRICS`],
/// or [`TEAM_TABLE_METRICS`] when every plan its benches run is a team's.
pub fn default_metrics(scenario: &Scenario) -> &'static [&'static str] {
    let mut plans = scenario
        .benches
        .iter()
        .flat_map(|b| &b.plans)
        .map(|p| &scenario.plans[p.plan])
        .peekable();
    if plans.peek().is_some() && plans.all(|p| p.planner.plans_teams()) {
        TEAM_TABLE_METRICS
    } else {
        TABLE_METRICS
    }
}

/// The statistics of one row of a table: a plan in one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub plan: usize,
    pub config: usize,
    pub runs: usize,
    /// The fraction of runs that found a path.
    pub found: f64,
    /// The runs that found a path.
    pub successes: usize,
    /// Per metric: (median, mean, std).
    pub stats: Vec<(f64, f64, f64)>,
}

/// The rows of one bench's table, plan by plan, configuration by
/// configuration, over the runs present.
pub fn rows(scenario: &Scenario, bench: usize, runs: &[BenchRun], metrics: &[&str]) -> Vec<Row> {
    let b = &scenario.benches[bench];
    let mut rows = Vec::new();
    for (p, plan) in b.plans.iter().enumerate() {
        for config in 0..plan.configs.len() {
            let these: Vec<&BenchRun> = runs
                .iter()
                .filter(|r| r.bench == bench && r.plan == p && r.config == config)
                .collect();
            if these.is_empty() {
                continue;
            }
            let series = |m: &str| -> Vec<MetricValue> {
                these
                    .iter()
                    .map(|r| {
                        r.metrics
                            .get(m)
                            .copied()
                            .unwrap_or(MetricValue::Num(f64::NAN))
                    })
                    .collect()
            };
            let found_series = series("found");
            let found = checks::aggregate("rate", &found_series, None).as_f64();
            let successes = found_series
                .iter()
                .filter(|v| **v == MetricValue::Bool(true))
                .count();
            let stats = metrics
                .iter()
                .map(|m| {
                    let s = series(m);
                    (
                        checks::aggregate("median", &s, None).as_f64(),
                        checks::aggregate("mean", &s, None).as_f64(),
                        checks::aggregate("std", &s, None).as_f64(),
                    )
                })
                .collect();
            rows.push(Row {
                plan: p,
                config,
                runs: these.len(),
                found,
                successes,
                stats,
            });
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    /// No bench run draws: its planners leave their layers empty, so a
    /// bench never pays for them (issue: 14 % of a PRM's time).
    #[test]
    fn bench_runs_build_no_layers() {
        let scenario = crate::scenario::load_text(
            "world { bounds (0, 0) (10, 10) rect (4, 0) (5, 8) }\nrobot p point\n\
             plan a astar p { start (1, 1) goal (9, 1) }\n\
             bench b { runs 2 }\n",
        );
        let ids = run_ids(&scenario, &[]);
        assert!(!ids.is_empty());
        for id in &ids {
            let task = task_of(&scenario, id);
            assert!(!task.draw);
            let plan = &scenario.benches[id.bench].plans[id.plan];
            let out = plan.configs[id.config].settings.plan(&task);
            assert!(out.path.is_some());
            assert!(out.layers.is_empty(), "{:?}", out.layers.len());
        }
        // Drawn, the same plan has its search and grown obstacles.
        let plan = &scenario.plans[0];
        assert!(!plan.settings.plan(&plan.task(&scenario)).layers.is_empty());
    }

    #[test]
    fn shards_split_the_runs_exactly_once() {
        for n in 1..=7u64 {
            let mut count = vec![0; 50];
            for k in 1..=n {
                let s = Shard::parse(&format!("{k}/{n}")).expect("a shard");
                for total in 0..50u64 {
                    let taken = (0..total).filter(|&i| s.takes(i)).count() as u64;
                    assert_eq!(s.share(total), taken, "{k}/{n} of {total}");
                    let nth: Vec<u64> = (0..taken).map(|j| s.nth(j)).collect();
                    let all: Vec<u64> = (0..total).filter(|&i| s.takes(i)).collect();
                    assert_eq!(nth, all, "{k}/{n} of {total}");
                }
                for (i, c) in count.iter_mut().enumerate() {
                    if s.takes(i as u64) {
                        *c += 1;
                    }
                }
            }
            assert!(count.iter().all(|&c| c == 1), "{n}: {count:?}");
        }
        for bad in ["0/3", "4/3", "x/2", "3", "1/0", ""] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
    }
}
