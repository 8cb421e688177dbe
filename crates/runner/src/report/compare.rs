//! `scen bench FILE --compare A,B`: plan A against plan B, pair by pair.
//! A pair is one configuration on one world (sample) and one run index,
//! run by both plans; a plan that draws no random numbers ran once per
//! configuration and world, and that run stands for every run index.
//! Per bench that runs both plans: the pairs side by side (found, and
//! each metric), then per metric A's wins, ties and losses over the pairs
//! and the two-sided exact sign test of them (ties dropped).

use std::fmt::Write as _;

use crate::checks::format_num;
use crate::contract::MetricValue;
use crate::run::{BenchRun, RunReport};
use crate::scenario::Scenario;
use crate::stats::sign_test;

/// Metrics where more is better; lower is better for the others (length,
/// time, cost, expansions, ...).
const HIGHER_IS_BETTER: &[&str] = &["clearance", "coverage"];

/// The plans of `--compare A,B`, checked against the scenario: two
/// distinct plans that some bench runs. An error names the plans.
pub fn plans(sc: &Scenario, names: &[String]) -> Result<Option<(usize, usize)>, String> {
    if names.is_empty() {
        return Ok(None);
    }
    let all: Vec<&str> = sc.plans.iter().map(|p| p.name.as_str()).collect();
    let listing = || format!("the plans of `{}`: {}", sc.file.display(), all.join(", "));
    let [a, b] = names else {
        return Err(format!(
            "`--compare` takes two plans, `--compare A,B`; {}",
            listing()
        ));
    };
    let find = |n: &String| {
        sc.plans
            .iter()
            .position(|p| &p.name == n)
            .ok_or_else(|| format!("`--compare`: no plan `{n}`; {}", listing()))
    };
    let (a, b) = (find(a)?, find(b)?);
    if a == b {
        return Err(format!(
            "`--compare` needs two different plans; {}",
            listing()
        ));
    }
    Ok(Some((a, b)))
}

/// How plan A fared against plan B over the pairs, for one metric.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    pub wins: u64,
    pub ties: u64,
    pub losses: u64,
}

impl Tally {
    /// The two-sided exact sign test of the wins against the losses.
    pub fn p_value(&self) -> f64 {
        sign_test(self.wins, self.losses)
    }
}

/// One run's side of a pair: whether it found a path, and its metric.
fn side(r: &BenchRun, metric: &str) -> (bool, f64) {
    let found = r.metrics.get("found") == Some(&MetricValue::Bool(true));
    let x = r.metrics.get(metric).map_or(f64::NAN, |v| v.as_f64());
    (found, x)
}

/// Whether A beat B (+1), tied (0) or lost (−1) on `metric`: a path found
/// beats none; between two found paths the better value wins; two runs
/// without a path, or without a value, tie.
pub fn outcome(a: (bool, f64), b: (bool, f64), higher_better: bool) -> i8 {
    match (a.0, b.0) {
        (true, false) => 1,
        (false, true) => -1,
        (false, false) => 0,
        // Found paths always have their lengths; a metric without a value
        // (NaN) beats nothing, whichever way the metric is better.
        (true, true) => match (a.1.is_nan(), b.1.is_nan()) {
            (false, true) => 1,
            (true, false) => -1,
            (true, true) => 0,
            (false, false) => {
                let (x, y) = if higher_better {
                    (b.1, a.1)
                } else {
                    (a.1, b.1)
                };
                match x.partial_cmp(&y) {
                    Some(std::cmp::Ordering::Less) => 1,
                    Some(std::cmp::Ordering::Greater) => -1,
                    _ => 0,
                }
            }
        },
    }
}

/// The pairs of bench `b`: (configuration, world, run) with A's and B's
/// runs, in run order.
fn pairs<'r>(
    sc: &Scenario,
    b: usize,
    plans: (usize, usize),
    runs: &'r [BenchRun],
) -> Vec<(usize, u64, u64, &'r BenchRun, &'r BenchRun)> {
    let bench = &sc.benches[b];
    let at = |plan: usize| bench.plans.iter().position(|p| p.plan == plan);
    let (Some(pa), Some(pb)) = (at(plans.0), at(plans.1)) else {
        return Vec::new();
    };
    let (once_a, once_b) = (bench.plans[pa].runs == 1, bench.plans[pb].runs == 1);
    let of = |p: usize, once: bool, config: usize, world: u64, run: u64| {
        runs.iter().find(|r| {
            r.bench == b
                && r.plan == p
                && r.config == config
                && r.world == world
                && (r.run == run || once)
        })
    };
    let mut out = Vec::new();
    // The pairs follow the plan with more runs (either when equal).
    let lead = if once_a { pb } else { pa };
    for r in runs.iter().filter(|r| r.bench == b && r.plan == lead) {
        if let (Some(x), Some(y)) = (
            of(pa, once_a, r.config, r.world, r.run),
            of(pb, once_b, r.config, r.world, r.run),
        ) {
            out.push((r.config, r.world, r.run, x, y));
        }
    }
    out
}

/// A's tally against B on `metric` over the pairs of bench `b`.
pub fn tally(
    sc: &Scenario,
    b: usize,
    plans: (usize, usize),
    runs: &[BenchRun],
    metric: &str,
) -> Tally {
    let higher = HIGHER_IS_BETTER.contains(&metric);
    let mut t = Tally::default();
    for (_, _, _, x, y) in pairs(sc, b, plans, runs) {
        match outcome(side(x, metric), side(y, metric), higher) {
            1 => t.wins += 1,
            -1 => t.losses += 1,
            _ => t.ties += 1,
        }
    }
    t
}

/// The comparison's text, per bench that runs both plans.
pub fn render(report: &RunReport, plans: (usize, usize), metrics: &[&str]) -> String {
    let sc = &report.scenario;
    let (na, nb) = (&sc.plans[plans.0].name, &sc.plans[plans.1].name);
    let mut s = String::new();
    for (b, bench) in sc.benches.iter().enumerate() {
        let ps = pairs(sc, b, plans, &report.bench_runs);
        if ps.is_empty() {
            continue;
        }
        let _ = writeln!(
            s,
            "\ncompare {na} with {nb} in bench {} ({} pairs)",
            bench.name,
            ps.len()
        );
        // Side by side: the pair, then per plan found and each metric.
        let mut header: Vec<String> = Vec::new();
        if !bench.vary.is_empty() {
            header.push("config".into());
        }
        if bench.worlds > 1 {
            header.push("world".into());
        }
        header.push("run".into());
        for name in [na, nb] {
            header.push(format!("{name}.found"));
            header.extend(metrics.iter().map(|m| format!("{name}.{m}")));
        }
        let mut cells = vec![header];
        for (config, world, run, x, y) in &ps {
            let mut line = Vec::new();
            if !bench.vary.is_empty() {
                let picks = bench.config_values(*config);
                line.push(
                    bench
                        .vary
                        .iter()
                        .zip(&picks)
                        .map(|(v, &i)| format!("{}={}", v.key, v.values[i].text))
                        .collect::<Vec<_>>()
                        .join(" "),
                );
            }
            if bench.worlds > 1 {
                line.push(world.to_string());
            }
            line.push(run.to_string());
            for r in [x, y] {
                line.push(if side(r, "found").0 { "yes" } else { "no" }.into());
                line.extend(metrics.iter().map(|m| format_num(side(r, m).1)));
            }
            cells.push(line);
        }
        s.push_str(&columns(&cells));
        let _ = writeln!(
            s,
            "  {na} vs {nb}: wins / ties / losses, sign test (two-sided, ties dropped)"
        );
        let mut summary = vec![vec![
            "metric".to_string(),
            "wins".into(),
            "ties".into(),
            "losses".into(),
            "p".into(),
        ]];
        for m in metrics {
            let t = tally(sc, b, plans, &report.bench_runs, m);
            summary.push(vec![
                if *m == "found" {
                    "found (a path beats none)".to_string()
                } else {
                    format!(
                        "{m} ({} is better)",
                        if HIGHER_IS_BETTER.contains(m) {
                            "higher"
                        } else {
                            "lower"
                        }
                    )
                },
                t.wins.to_string(),
                t.ties.to_string(),
                t.losses.to_string(),
                format!("{:.4}", t.p_value()),
            ]);
        }
        s.push_str(&columns(&summary));
    }
    s
}

/// Rows of cells in aligned columns, indented by two spaces.
fn columns(cells: &[Vec<String>]) -> String {
    let width = |c: usize| {
        cells
            .iter()
            .map(|l| l.get(c).map_or(0, |x| x.chars().count()))
            .max()
            .unwrap_or(0)
    };
    let widths: Vec<usize> = (0..cells.first().map_or(0, Vec::len)).map(width).collect();
    let mut s = String::new();
    for l in cells {
        let line: Vec<String> = l
            .iter()
            .zip(&widths)
            .map(|(x, w)| format!("{x:<w$}"))
            .collect();
        let _ = writeln!(s, "  {}", line.join("  ").trim_end());
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn found_beats_not_found_then_the_better_value_wins() {
        let nan = f64::NAN;
        assert_eq!(outcome((true, 9.0), (false, nan), false), 1);
        assert_eq!(outcome((false, nan), (true, 1.0), false), -1);
        assert_eq!(outcome((false, nan), (false, nan), false), 0);
        assert_eq!(outcome((true, 1.0), (true, 2.0), false), 1);
        assert_eq!(outcome((true, 1.0), (true, 2.0), true), -1);
        assert_eq!(outcome((true, 2.0), (true, 2.0), false), 0);
        assert_eq!(outcome((true, 2.0), (true, nan), true), 1);
    }
}
