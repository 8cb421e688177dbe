//! `scen bench FILE...` and `scen bench merge PART.jsonl...` (SPEC §4).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use super::clobber::{Input, outputs_are_not_inputs, scenario_inputs};
use super::{
    BenchArgs, EXIT_BAD_INPUT, EXIT_CHECK_FAILED, EXIT_OK, outln, outputs_writable, print_failure,
    print_report,
};
use crate::bench::{self, RunId, Shard};
use crate::report;
use crate::run::BenchRun;
use crate::run::RunReport;
use crate::scenario::Scenario;
use scen_runner::merge::{known_metrics, merge};

pub(super) fn cmd_bench(args: &BenchArgs) -> i32 {
    if !args.outputs.usable() || !outputs_writable(&[("--out", args.out.as_ref())]) {
        return EXIT_BAD_INPUT;
    }
    if args.files.first().is_some_and(|f| f == Path::new("merge")) {
        return cmd_merge(args, &args.files[1..]);
    }
    let mut single = args.outputs.one_per_scenario();
    if args.out.is_some() {
        single.push("--out");
    }
    if args.files.len() > 1 && !single.is_empty() {
        eprintln!("error: {}", super::one_file_only(&single));
        return EXIT_BAD_INPUT;
    }
    let shard = args.shard;
    let mut code = EXIT_OK;
    for file in &args.files {
        let scenario = match super::load(file, args.root.as_deref()) {
            Ok(s) => s,
            Err(f) => {
                print_failure(&f);
                code = code.max(EXIT_BAD_INPUT);
                continue;
            }
        };
        if let Err(e) = bench::known_benches(&scenario, &args.benches)
            .and_then(|()| known_metrics(&scenario, &args.benches, &args.metrics))
        {
            eprintln!("error: `{}`: {e}", file.display());
            code = code.max(EXIT_BAD_INPUT);
            continue;
        }
        if !outputs_are_not_inputs(
            &args.outputs_for(&scenario),
            &scenario_inputs(&scenario.sources),
        ) {
            code = code.max(EXIT_BAD_INPUT);
            continue;
        }
        if scenario.benches.is_empty() {
            eprintln!(
                "error: `{}` has no `bench`; write e.g. `bench b {{ vary cell [1, 0.5] runs 10 }}`, or use `scen run`",
                file.display()
            );
            code = code.max(EXIT_BAD_INPUT);
            continue;
        }
        if let Err(e) = report::compare::plans(&scenario, &args.compare) {
            eprintln!("error: {e}");
            code = code.max(EXIT_BAD_INPUT);
            continue;
        }
        let prepared = match bench::prepare(scenario, &args.benches, args.runs, args.worlds, shard)
        {
            Ok(p) => p,
            Err(bench::Unready::Message(e)) => {
                eprintln!("error: {e}");
                code = code.max(EXIT_BAD_INPUT);
                continue;
            }
            Err(bench::Unready::Load(f)) => {
                print_failure(&f);
                code = code.max(EXIT_BAD_INPUT);
                continue;
            }
        };
        let bench::Prepared {
            scenario,
            worlds,
            ids,
        } = prepared;
        let runs = run_with_progress(&scenario, &worlds, &ids, args);
        if let (Some(s), Some(out)) = (shard, &args.out) {
            code = code.max(write_part(&scenario, s, args, &runs, out));
            continue;
        }
        let report = bench::report(scenario, runs);
        code = code.max(outputs(&report, args));
    }
    code
}

impl BenchArgs {
    /// Every file the command would write for `scenario`: the outputs
    /// (each log of `--ompl-log`) and the part of `--shard`.
    fn outputs_for(&self, scenario: &Scenario) -> Vec<(&'static str, Option<PathBuf>)> {
        let mut all: Vec<(&'static str, Option<PathBuf>)> = self
            .outputs
            .files(Some(scenario), &self.benches)
            .into_iter()
            .map(|(o, p)| (o, Some(p)))
            .collect();
        all.push(("--out", self.out.clone()));
        all
    }
}

/// Runs `ids`, with a progress bar and an estimate of the time left on a
/// terminal.
fn run_with_progress(
    scenario: &Scenario,
    worlds: &bench::Worlds,
    ids: &[RunId],
    args: &BenchArgs,
) -> Vec<BenchRun> {
    let bar = (!args.quiet && !args.json && std::io::stderr().is_terminal()).then(|| {
        let bar = indicatif::ProgressBar::new(ids.len() as u64);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "{spinner} {msg} [{bar:30}] {pos}/{len} runs, {elapsed} elapsed, about {eta} left",
        ) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message(scenario.file.display().to_string());
        bar
    });
    let tick = || {
        if let Some(b) = &bar {
            b.inc(1);
        }
    };
    let runs = bench::run_all(scenario, worlds, ids, &tick);
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    runs
}

/// The report's outputs: the tables (or JSON), CSV, SVG and OMPL logs; the
/// exit code.
fn outputs(report: &RunReport, args: &BenchArgs) -> i32 {
    let mut code = EXIT_OK;
    let metrics: Vec<&str> = if args.metrics.is_empty() {
        bench::default_metrics(&report.scenario).to_vec()
    } else {
        args.metrics.iter().map(String::as_str).collect()
    };
    if args.json {
        let doc = report::bench::to_json(report);
        outln!("{}", serde_json::to_string(&doc).unwrap_or_default());
    } else {
        // `--compare` is checked before any run: no error here.
        let compared = report::compare::plans(&report.scenario, &args.compare)
            .ok()
            .flatten();
        print_report(report, args.quiet, || {
            let mut text = report::bench::render(report, &metrics);
            if let Some(plans) = compared {
                // Before the checks and the summary line, after the tables.
                let at = text
                    .find("\nchecks\n")
                    .or_else(|| text.rfind("\n\n"))
                    .unwrap_or(text.len());
                text.insert_str(at, &report::compare::render(report, plans, &metrics));
            }
            text
        });
    }
    let failed_writes = !args
        .outputs
        .write(report::sink::Product::Bench(report, &metrics));
    if failed_writes {
        code = EXIT_BAD_INPUT;
    }
    if report.failed() > 0 {
        code = code.max(EXIT_CHECK_FAILED);
    }
    code
}

/// `--shard K/N --out PART.jsonl`: a header line, then one line per run.
fn write_part(
    scenario: &Scenario,
    shard: Shard,
    args: &BenchArgs,
    runs: &[BenchRun],
    out: &Path,
) -> i32 {
    let text =
        report::bench::part_text(scenario, shard, &args.benches, args.runs, args.worlds, runs);
    match std::fs::write(out, text) {
        Ok(()) => {
            eprintln!(
                "{}: shard {}/{}: {} runs written to `{}`; combine the parts with `scen bench merge`",
                scenario.file.display(),
                shard.k,
                shard.n,
                runs.len(),
                out.display()
            );
            EXIT_OK
        }
        Err(e) => {
            eprintln!("error: cannot write `{}`: {e}", out.display());
            EXIT_BAD_INPUT
        }
    }
}

/// `scen bench merge PART.jsonl...`: the report of the whole bench, as the
/// unsharded `scen bench` prints it. Refuses parts that are missing,
/// given twice, or made from another scenario or split, and runs that the
/// scenario does not give (SPEC §4).
fn cmd_merge(args: &BenchArgs, paths: &[PathBuf]) -> i32 {
    let merged = merge(paths, args.root.as_deref(), &args.metrics).and_then(|report| {
        report::compare::plans(&report.scenario, &args.compare)?;
        Ok(report)
    });
    match merged {
        Ok(report) => {
            let mut inputs = scenario_inputs(&report.scenario.sources);
            inputs.extend(paths.iter().map(|p| Input {
                path: p,
                role: "a part given to `merge`",
            }));
            if !outputs_are_not_inputs(&args.outputs_for(&report.scenario), &inputs) {
                return EXIT_BAD_INPUT;
            }
            outputs(&report, args)
        }
        Err(e) => {
            eprintln!("error: {e}");
            EXIT_BAD_INPUT
        }
    }
}
