//! `scen bench merge PART.jsonl...` (SPEC §4): the report of a whole bench
//! from the parts its shards wrote, checked as the command checks them
//! (every part once, from one split of one unchanged scenario, every run
//! the scenario gives). The command and the Python module both call
//! [`merge`].

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::bench::{self, Shard};
use crate::contract::MetricValue;
use crate::contract::schema::{self, MetricType};
use crate::diagnostics::render_diags;
use crate::parts;
use crate::report;
use crate::run::{BenchRun, RunReport};
use crate::scenario::Scenario;

/// The metrics `--metrics` names are metrics of a plan that the benches
/// (`names`; none: all) run; a misspelt one gets the closest as a
/// suggestion.
pub fn known_metrics(
    scenario: &Scenario,
    names: &[String],
    metrics: &[String],
) -> Result<(), String> {
    let mut known: Vec<&str> = Vec::new();
    for bench in scenario
        .benches
        .iter()
        .filter(|b| names.is_empty() || names.contains(&b.name))
    {
        for config in bench.plans.iter().flat_map(|p| &p.configs) {
            let drives = config.params.get("drive").is_some();
            let drive_metrics = schema::DRIVE_METRICS.iter().filter(|_| drives);
            for m in config.planner.all_metrics().chain(drive_metrics) {
                if !known.contains(&m.name) {
                    known.push(m.name);
                }
            }
        }
    }
    let Some(unknown) = metrics.iter().find(|m| !known.contains(&m.as_str())) else {
        return Ok(());
    };
    known.sort_unstable();
    let suggestion = schema::did_you_mean(unknown, known.iter().copied())
        .map_or(String::new(), |m| format!("did you mean `{m}`? "));
    Err(format!(
        "`--metrics {unknown}`: no plan of the benches has a metric `{unknown}`; {suggestion}the metrics: {}",
        schema::backticked(&known)
    ))
}

/// One part, read.
struct Part {
    header: parts::Header,
    benches: Vec<String>,
    /// `--runs N` and `--worlds N`, when the parts were made with them.
    runs_override: Option<u64>,
    worlds_override: Option<u64>,
    runs: Vec<Value>,
}

/// The largest part `merge` reads (a part of a million runs is ~300 MB).
const MAX_PART_BYTES: u64 = 1 << 30;

fn read_part(path: &Path) -> Result<Part, String> {
    let command = "scen bench";
    let parts::Lines {
        header,
        common,
        rest: runs,
    } = parts::read_lines(path, MAX_PART_BYTES, command, "scen_part")?;
    let not_a_part = || parts::not_a_part(path, command);
    let field = |k: &str| header.get(k).cloned().ok_or_else(not_a_part);
    Ok(Part {
        header: common,
        benches: field("benches")?
            .as_array()
            .ok_or_else(not_a_part)?
            .iter()
            .filter_map(|b| b.as_str().map(str::to_string))
            .collect(),
        runs_override: match header.get("runs") {
            None => None,
            Some(v) => Some(v.as_u64().filter(|&n| n >= 1).ok_or_else(not_a_part)?),
        },
        worlds_override: match header.get("worlds") {
            None => None,
            Some(v) => Some(v.as_u64().filter(|&n| n >= 1).ok_or_else(not_a_part)?),
        },
        runs,
    })
}

impl parts::Part for Part {
    const COMMAND: &'static str = "scen bench";
    fn read(path: &Path) -> Result<Self, String> {
        read_part(path)
    }
    fn header(&self) -> &parts::Header {
        &self.header
    }
    fn origin(&self) -> String {
        let runs = self
            .runs_override
            .map_or("as written".to_string(), |n| format!("--runs {n}"));
        let runs = match self.worlds_override {
            Some(w) => format!("{runs}, --worlds {w}"),
            None => runs,
        };
        let h = &self.header;
        format!(
            "{} (hash {}), shards of {}, benches {:?}, runs {runs}",
            h.file, h.hash, h.n, self.benches
        )
    }
}

/// The report of the whole bench from the parts at `paths` (`--metrics`
/// names checked as [`known_metrics`] does); the error is the command's
/// message.
pub fn merge(
    paths: &[PathBuf],
    root: Option<&Path>,
    metrics: &[String],
) -> Result<RunReport, String> {
    let parts: Vec<Part> = parts::read_parts(paths)?;
    let first = &parts[0];
    let head = &first.header;
    let mut scenario =
        crate::scenario::load_with(Path::new(&head.file), root, &|_| None).map_err(|f| {
            format!(
                "cannot load `{}`, the scenario the parts were made from:\n{}",
                head.file,
                render_diags(&f.diags, &f.sources)
            )
        })?;
    parts::unchanged(first, &scenario.sources.content_hash())?;
    bench::known_benches(&scenario, &first.benches)?;
    known_metrics(&scenario, &first.benches, metrics)?;
    if let Some(n) = first.runs_override {
        scenario.override_runs(n);
    }
    if let Some(n) = first.worlds_override {
        scenario.override_worlds(n)?;
    }
    let ids = bench::run_ids(&scenario, &first.benches);
    if head.n > ids.len() as u64 {
        return Err(format!(
            "the parts say {} shards, but the benches have only {} run(s): a split into more parts than runs is not one `scen bench --shard` makes",
            head.n,
            ids.len()
        ));
    }
    parts::whole(&parts)?;
    let at: HashMap<RunKey, usize> = ids
        .iter()
        .enumerate()
        .map(|(i, id)| ((id.bench, id.plan, id.config, id.world, id.run), i))
        .collect();
    let mut runs: Vec<Option<BenchRun>> = vec![None; ids.len()];
    for p in &parts {
        let h = &p.header;
        for v in &p.runs {
            let (id_at, run) = decode_run(&scenario, &at, v)
                .map_err(|why| format!("`{}` holds a run that {why}: {v}", h.path.display()))?;
            if !(Shard { k: h.k, n: h.n }).takes(ids[id_at].index) {
                return Err(format!(
                    "`{}` (part {}/{}) holds a run of another part: {v}",
                    h.path.display(),
                    h.k,
                    h.n
                ));
            }
            if runs[id_at].is_some() {
                return Err(format!("`{}` repeats a run: {v}", h.path.display()));
            }
            runs[id_at] = Some(run);
        }
    }
    let absent = runs.iter().filter(|r| r.is_none()).count();
    if absent > 0 {
        return Err(format!("the parts lack {absent} of the {} runs", ids.len()));
    }
    Ok(bench::report(
        scenario,
        runs.into_iter().flatten().collect(),
    ))
}

/// A part's run, checked against what the scenario gives for its place
/// (its seed, its configuration, the metrics of its planner, its checksum)
/// and placed among the runs; or what is wrong with it.
/// A run's place: bench, plan, configuration, world and run.
type RunKey = (usize, usize, usize, u64, u64);

fn decode_run(
    scenario: &Scenario,
    at: &HashMap<RunKey, usize>,
    v: &Value,
) -> Result<(usize, BenchRun), &'static str> {
    let o = v.as_object().ok_or("is not a JSON object")?;
    let text = |k: &str| o.get(k).and_then(Value::as_str);
    let number = |k: &str| o.get(k).and_then(Value::as_u64);
    let (Some(bench_name), Some(plan_name), Some(config), Some(run), Some(seed)) = (
        text("bench"),
        text("plan"),
        number("config_index"),
        number("run"),
        number("seed"),
    ) else {
        return Err("lacks its bench, plan, configuration, run or seed");
    };
    if text("check") != Some(report::bench::run_checksum(o).as_str()) {
        return Err("was edited or damaged (its checksum does not match)");
    }
    let b = scenario
        .benches
        .iter()
        .position(|x| x.name == bench_name)
        .ok_or("names a bench this scenario does not have")?;
    let bench = &scenario.benches[b];
    let p = bench
        .plans
        .iter()
        .position(|x| scenario.plans[x.plan].name == plan_name)
        .ok_or("names a plan this bench does not run")?;
    let config = usize::try_from(config).map_err(|_| "has no such configuration")?;
    // Written only by a bench with `worlds`.
    let world = match o.get("world") {
        None => 0,
        Some(w) => w
            .as_u64()
            .ok_or("has a world that is not a sample number")?,
    };
    let id_at = *at
        .get(&(b, p, config, world, run))
        .ok_or("has a configuration or run number this bench does not have")?;
    let plan = &bench.plans[p].configs[config];
    if seed != plan.params.seed.wrapping_add(run) {
        return Err("has another seed than the scenario gives its run");
    }
    if o.get("config") != Some(&report::bench::config_json(bench, config)) {
        return Err("has another configuration than the scenario gives its index");
    }
    let metrics = report::bench::read_metrics(o.get("metrics").ok_or("has no metrics")?)
        .ok_or("has a metric that is not a number or a boolean")?;
    for spec in plan.planner.all_metrics() {
        match (spec.ty, metrics.get(spec.name)) {
            (MetricType::Bool, Some(MetricValue::Bool(_)))
            | (MetricType::Num, Some(MetricValue::Num(_))) => {}
            (_, None) => return Err("lacks a metric of its planner"),
            _ => return Err("has a metric of the wrong type"),
        }
    }
    Ok((
        id_at,
        BenchRun {
            bench: b,
            plan: p,
            config,
            world,
            run,
            seed,
            metrics,
        },
    ))
}
