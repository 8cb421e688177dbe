//! The outputs of `scen bench` (SPEC §4, §5): the table per bench, the
//! JSON document, the CSV of every run, and the parts that `--shard K/N
//! --out PART.jsonl` writes and `scen bench merge` reads back.

use std::fmt::Write as _;

use serde_json::{Map, Value};

use crate::bench;
use crate::checks::{format_num, value_text};
use crate::contract::{MetricValue, Metrics};
use crate::run::BenchRun;
use crate::run::RunReport;
use crate::scenario::{Bench, Scenario};
use crate::syntax::ast::{self, ValueKind};

use super::json::{check_json, float_json, metrics_json};

/// The table of every bench, then the checks and the summary line.
/// `metrics` are the columns (by default [`crate::bench::default_metrics`]).
pub fn render(report: &RunReport, metrics: &[&str]) -> String {
    let sc = &report.scenario;
    let mut s = String::new();
    match &sc.title {
        Some(t) => {
            let _ = writeln!(s, "{} — {}", sc.file.display(), t);
        }
        None => {
            let _ = writeln!(s, "{}", sc.file.display());
        }
    }
    for (b, bench) in sc.benches.iter().enumerate() {
        if !report.bench_runs.iter().any(|r| r.bench == b) {
            continue;
        }
        s.push('\n');
        s.push_str(&table(sc, b, &report.bench_runs, metrics));
        let once: Vec<&str> = bench
            .plans
            .iter()
            .filter(|p| p.runs == 1 && bench.runs > 1)
            .map(|p| sc.plans[p.plan].name.as_str())
            .collect();
        if !once.is_empty() {
            let _ = writeln!(
                s,
                "  note: {} draw{} no random numbers: one run per configuration, not {}",
                once.join(", "),
                if once.len() == 1 { "s" } else { "" },
                bench.runs
            );
        }
        if bench.limits.time.is_some()
            || bench.plans.iter().any(|p| {
                sc.plans[p.plan].params.limits.time.is_some() && sc.plans[p.plan].planner.randomized
            })
        {
            let _ = writeln!(
                s,
                "  note: a `limit time` makes results depend on the machine's speed"
            );
        }
    }
    if !report.checks.is_empty() {
        let _ = writeln!(s, "\nchecks");
        for c in &report.checks {
            let _ = writeln!(s, "  {}", super::text::check_line(report, c));
        }
    }
    let _ = writeln!(
        s,
        "\n{} passed, {} failed",
        report.passed(),
        report.failed()
    );
    s
}

/// One bench's table: a row per plan and configuration, columns for the
/// varied keys, the runs, the success rate, and per metric the median and
/// mean ± std (the value itself for a single run).
pub fn table(sc: &Scenario, b: usize, runs: &[BenchRun], metrics: &[&str]) -> String {
    let bench = &sc.benches[b];
    let rows = bench::rows(sc, b, runs, metrics);
    let mut header: Vec<String> = vec!["plan".into()];
    header.extend(bench.vary.iter().map(|v| v.key.clone()));
    header.push("runs".into());
    header.push("found".into());
    header.extend(metrics.iter().map(|m| (*m).to_string()));
    let mut cells: Vec<Vec<String>> = Vec::new();
    for row in &rows {
        let picks = bench.config_values(row.config);
        let mut line = vec![sc.plans[bench.plans[row.plan].plan].name.clone()];
        line.extend(
            bench
                .vary
                .iter()
                .zip(&picks)
                .map(|(v, &i)| v.values[i].text.clone()),
        );
        line.push(row.runs.to_string());
        line.push(rate_with_ci(row));
        for &(median, mean, std) in &row.stats {
            line.push(if row.runs == 1 {
                short(median)
            } else {
                format!("{} ({} ± {})", short(median), short(mean), short(std))
            });
        }
        cells.push(line);
    }
    let widths: Vec<usize> = (0..header.len())
        .map(|c| {
            cells
                .iter()
                .map(|l| l[c].chars().count())
                .chain(std::iter::once(header[c].chars().count()))
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |parts: &[String]| -> String {
        parts
            .iter()
            .zip(&widths)
            .map(|(p, w)| format!("{p:<w$}"))
            .collect::<Vec<_>>()
            .join("  ")
            .trim_end()
            .to_string()
    };
    let count = runs.iter().filter(|r| r.bench == b).count();
    let worlds = if bench.worlds > 1 {
        format!(" on {} worlds", bench.worlds)
    } else {
        String::new()
    };
    let mut s = format!(
        "bench {} ({count} run{}{worlds})\n",
        bench.name,
        if count == 1 { "" } else { "s" }
    );
    let _ = writeln!(s, "  {}", line(&header));
    for l in &cells {
        let _ = writeln!(s, "  {}", line(l));
    }
    s
}

/// A success rate and its 95 % Wilson interval in whole percents:
/// `85% [64, 95]`.
fn rate_with_ci(row: &bench::Row) -> String {
    let (lo, hi) = row.success_ci();
    let percent = |x: f64| format_num((x * 100.0).round());
    format!(
        "{}% [{}, {}]",
        format_num((row.found * 1000.0).round() / 10.0),
        percent(lo),
        percent(hi)
    )
}

/// A number in a table: at most 4 significant digits after the point.
fn short(x: f64) -> String {
    if !x.is_finite() {
        return format_num(x);
    }
    let magnitude = x.abs();
    let decimals = if magnitude >= 1000.0 || x.fract() == 0.0 {
        0
    } else if magnitude >= 10.0 {
        2
    } else {
        4
    };
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A `vary` value in JSON: numbers (angles in radians, percentages as
/// fractions, durations in seconds), words and strings as strings, points
/// and lists as arrays.
pub fn value_json(v: &ast::Value) -> Value {
    match &v.kind {
        ValueKind::Number(x) | ValueKind::Percent(x) | ValueKind::Duration(x) => float_json(*x),
        ValueKind::Angle(a) => float_json(a.radians()),
        ValueKind::Str(s) | ValueKind::Word(s) => Value::String(s.clone()),
        ValueKind::Tuple(xs) | ValueKind::List(xs) => {
            Value::Array(xs.iter().map(value_json).collect())
        }
        // A sample computes every expression before analysis.
        ValueKind::Calc { .. } => Value::Null,
    }
}

/// The configuration of a run: each varied key's value.
pub(crate) fn config_json(bench: &Bench, config: usize) -> Value {
    let picks = bench.config_values(config);
    Value::Object(
        bench
            .vary
            .iter()
            .zip(picks)
            .map(|(v, i)| (v.key.clone(), value_json(&v.values[i].value)))
            .collect(),
    )
}

/// One run as SPEC 5 lists it: plan, config, run, seed, metrics.
fn run_json(sc: &Scenario, r: &BenchRun) -> Value {
    let bench = &sc.benches[r.bench];
    let mut o = Map::new();
    o.insert(
        "plan".into(),
        sc.plans[bench.plans[r.plan].plan].name.clone().into(),
    );
    o.insert("config".into(), config_json(bench, r.config));
    if bench.worlds > 1 {
        o.insert("world".into(), r.world.into());
    }
    o.insert("run".into(), r.run.into());
    o.insert("seed".into(), r.seed.into());
    o.insert("metrics".into(), metrics_json(&r.metrics));
    Value::Object(o)
}

/// The document of `scen bench --json` (SPEC 5).
pub fn to_json(report: &RunReport) -> Value {
    let sc = &report.scenario;
    let benches: Vec<Value> = sc
        .benches
        .iter()
        .enumerate()
        .filter(|(b, _)| report.bench_runs.iter().any(|r| r.bench == *b))
        .map(|(b, bench)| {
            let mut o = Map::new();
            o.insert("name".into(), bench.name.clone().into());
            let vary: Map<String, Value> = bench
                .vary
                .iter()
                .map(|v| {
                    (
                        v.key.clone(),
                        Value::Array(v.values.iter().map(|x| value_json(&x.value)).collect()),
                    )
                })
                .collect();
            o.insert("vary".into(), Value::Object(vary));
            o.insert("runs".into(), bench.runs.into());
            if bench.worlds > 1 {
                o.insert("worlds".into(), bench.worlds.into());
            }
            let results: Vec<Value> = report
                .bench_runs
                .iter()
                .filter(|r| r.bench == b)
                .map(|r| run_json(sc, r))
                .collect();
            o.insert("results".into(), Value::Array(results));
            o.insert("summary".into(), summary_json(sc, b, &report.bench_runs));
            Value::Object(o)
        })
        .collect();
    let checks: Vec<Value> = report
        .checks
        .iter()
        .filter_map(|c| check_json(sc, c))
        .collect();
    let mut doc = Map::new();
    doc.insert("file".into(), sc.file.display().to_string().into());
    doc.insert("scenario".into(), sc.title.clone().into());
    doc.insert("benches".into(), Value::Array(benches));
    doc.insert("checks".into(), Value::Array(checks));
    doc.insert("passed".into(), report.passed().into());
    doc.insert("failed".into(), report.failed().into());
    Value::Object(doc)
}

/// Per plan and configuration: its runs, how many found a path, the
/// success rate and its 95 % Wilson interval `"success_ci": [lo, hi]`.
fn summary_json(sc: &Scenario, b: usize, runs: &[BenchRun]) -> Value {
    let bench = &sc.benches[b];
    Value::Array(
        bench::rows(sc, b, runs, &[])
            .iter()
            .map(|row| {
                let (lo, hi) = row.success_ci();
                let mut o = Map::new();
                o.insert(
                    "plan".into(),
                    sc.plans[bench.plans[row.plan].plan].name.clone().into(),
                );
                o.insert("config".into(), config_json(bench, row.config));
                o.insert("runs".into(), row.runs.into());
                o.insert("successes".into(), row.successes.into());
                o.insert("success_rate".into(), float_json(row.found));
                o.insert(
                    "success_ci".into(),
                    Value::Array(vec![float_json(lo), float_json(hi)]),
                );
                Value::Object(o)
            })
            .collect(),
    )
}

/// Every run as a CSV row: bench, plan, the varied keys (of every bench of
/// the file, empty where a bench does not vary one), run, seed, then every
/// metric that any run has, in name order.
pub fn to_csv(report: &RunReport) -> String {
    let sc = &report.scenario;
    let mut keys: Vec<&str> = Vec::new();
    for b in &sc.benches {
        for v in &b.vary {
            if !keys.contains(&v.key.as_str()) {
                keys.push(&v.key);
            }
        }
    }
    let mut metrics: Vec<&str> = Vec::new();
    for r in &report.bench_runs {
        for m in r.metrics.keys() {
            if !metrics.contains(&m.as_str()) {
                metrics.push(m);
            }
        }
    }
    metrics.sort_unstable();
    let mut s = String::new();
    let mut header: Vec<String> = vec!["bench".into(), "plan".into()];
    header.extend(keys.iter().map(|k| (*k).to_string()));
    let worlds = sc.benches.iter().any(|b| b.worlds > 1);
    if worlds {
        header.push("world".to_string());
    }
    header.extend(["run".to_string(), "seed".to_string()]);
    header.extend(metrics.iter().map(|m| (*m).to_string()));
    // The run's configuration's success rate and its 95 % Wilson interval
    // (the same on every run of a configuration), for plotting as is.
    header.extend(SUCCESS_COLUMNS.map(str::to_string));
    let rows: Vec<Vec<bench::Row>> = (0..sc.benches.len())
        .map(|b| bench::rows(sc, b, &report.bench_runs, &[]))
        .collect();
    let _ = writeln!(
        s,
        "{}",
        header
            .iter()
            .map(|h| csv_field(h))
            .collect::<Vec<_>>()
            .join(",")
    );
    for r in &report.bench_runs {
        let bench = &sc.benches[r.bench];
        let picks = bench.config_values(r.config);
        let mut row: Vec<String> = vec![
            bench.name.clone(),
            sc.plans[bench.plans[r.plan].plan].name.clone(),
        ];
        for k in &keys {
            row.push(
                bench
                    .vary
                    .iter()
                    .position(|v| v.key == *k)
                    .map(|i| value_text(&bench.vary[i].values[picks[i]].value))
                    .unwrap_or_default(),
            );
        }
        if worlds {
            row.push(r.world.to_string());
        }
        row.push(r.run.to_string());
        row.push(r.seed.to_string());
        for m in &metrics {
            row.push(match r.metrics.get(*m) {
                Some(MetricValue::Bool(b)) => b.to_string(),
                Some(MetricValue::Num(x)) => super::exact_number(*x),
                None => String::new(),
            });
        }
        let stats = rows[r.bench]
            .iter()
            .find(|x| x.plan == r.plan && x.config == r.config);
        if let Some(stats) = stats {
            let (lo, hi) = stats.success_ci();
            row.extend([stats.found, lo, hi].map(super::exact_number));
        }
        let _ = writeln!(
            s,
            "{}",
            row.iter()
                .map(|f| csv_field(f))
                .collect::<Vec<_>>()
                .join(",")
        );
    }
    s
}

/// The CSV's last columns: the configuration's success rate and the ends
/// of its 95 % Wilson interval, as fractions.
const SUCCESS_COLUMNS: [&str; 3] = ["success_rate", "success_ci_lo", "success_ci_hi"];

/// A CSV field, quoted when it must be (RFC 4180).
fn csv_field(f: &str) -> String {
    if f.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", f.replace('"', "\"\""))
    } else {
        f.to_string()
    }
}

// ------------------------------------------------------------- shard parts

/// The header line of a part written by `--shard K/N --out PART.jsonl`:
/// what `merge` needs to check that the parts belong together.
pub fn part_header(
    sc: &Scenario,
    hash: &str,
    shard: bench::Shard,
    only: &[String],
    runs: Option<u64>,
    worlds: Option<u64>,
) -> Value {
    let mut o = Map::new();
    o.insert("scen_part".into(), 1.into());
    o.insert("file".into(), sc.file.display().to_string().into());
    o.insert("hash".into(), hash.into());
    o.insert(
        "benches".into(),
        Value::Array(
            sc.benches
                .iter()
                .filter(|b| only.is_empty() || only.contains(&b.name))
                .map(|b| b.name.clone().into())
                .collect(),
        ),
    );
    o.insert("k".into(), shard.k.into());
    o.insert("n".into(), shard.n.into());
    if let Some(runs) = runs {
        o.insert("runs".into(), runs.into());
    }
    if let Some(worlds) = worlds {
        o.insert("worlds".into(), worlds.into());
    }
    Value::Object(o)
}

/// The text of a part (`scen bench --shard K/N --out PART.jsonl`): its
/// header line, then one line per run of `runs`.
pub fn part_text(
    sc: &Scenario,
    shard: bench::Shard,
    only: &[String],
    runs_override: Option<u64>,
    worlds_override: Option<u64>,
    runs: &[BenchRun],
) -> String {
    let hash = sc.sources.content_hash();
    let header = part_header(sc, &hash, shard, only, runs_override, worlds_override);
    let mut text = serde_json::to_string(&header).unwrap_or_default();
    text.push('\n');
    for r in runs {
        text.push_str(&serde_json::to_string(&part_run(sc, r)).unwrap_or_default());
        text.push('\n');
    }
    text
}

/// One run of a part: its coordinates and its metrics, every number exact
/// (non-finite ones as strings, which JSON numbers cannot be).
pub fn part_run(sc: &Scenario, r: &BenchRun) -> Value {
    let mut o = Map::new();
    o.insert("bench".into(), sc.benches[r.bench].name.clone().into());
    if let Value::Object(run) = run_json(sc, r) {
        o.extend(run);
    }
    o.insert("config_index".into(), r.config.into());
    o.insert("metrics".into(), exact_metrics(&r.metrics));
    let check = run_checksum(&o);
    o.insert("check".into(), check.into());
    Value::Object(o)
}

/// A checksum of a part's run (FNV-1a of its JSON without the `check`
/// field), so that `merge` refuses a run whose numbers were edited or
/// corrupted on the way. Not a signature: it guards against accidents.
pub fn run_checksum(run: &Map<String, Value>) -> String {
    let mut copy = run.clone();
    copy.remove("check");
    let text = serde_json::to_string(&Value::Object(copy)).unwrap_or_default();
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}

fn exact_metrics(m: &Metrics) -> Value {
    Value::Object(
        m.iter()
            .map(|(k, v)| {
                let v = match *v {
                    MetricValue::Bool(b) => Value::Bool(b),
                    MetricValue::Num(x) if x.is_finite() => float_json(x),
                    MetricValue::Num(x) => Value::String(super::exact_number(x)),
                };
                (k.clone(), v)
            })
            .collect(),
    )
}

/// The metrics of a part's run, as [`exact_metrics`] wrote them.
pub fn read_metrics(v: &Value) -> Option<Metrics> {
    v.as_object()?
        .iter()
        .map(|(k, v)| {
            let value = match v {
                Value::Bool(b) => MetricValue::Bool(*b),
                Value::Number(n) => MetricValue::Num(n.as_f64()?),
                Value::String(s) => MetricValue::Num(match s.as_str() {
                    "inf" => f64::INFINITY,
                    "-inf" => f64::NEG_INFINITY,
                    "nan" => f64::NAN,
                    _ => return None,
                }),
                _ => return None,
            };
            Some((k.clone(), value))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Numbers that serde_json reads one bit off without its
    /// `float_roundtrip` feature (found by a search over lengths in
    /// [0, 1000)): `merge` printed another table than one machine did.
    #[test]
    fn part_metrics_read_back_every_bit() {
        let tricky = [
            985.6906946328695,
            212.91890726713459,
            479.60756426982596,
            92.42132512813595,
            925.9338926496359,
            441.66130716816645,
            972.6104788033849,
            419.52481325285885,
            496.83209069517596,
            f64::INFINITY,
            f64::NEG_INFINITY,
            5e-324,
            1.7976931348623157e308,
        ];
        let metrics: Metrics = tricky
            .iter()
            .enumerate()
            .map(|(i, x)| (format!("m{i}"), MetricValue::Num(*x)))
            .chain([("found".to_string(), MetricValue::Bool(true))])
            .collect();
        let text = serde_json::to_string(&exact_metrics(&metrics)).expect("JSON");
        let parsed: Value = serde_json::from_str(&text).expect("JSON");
        let back = read_metrics(&parsed).expect("metrics");
        assert_eq!(back, metrics);
        // NaN (a metric without a value) survives too, as itself.
        let nan: Metrics = [("clearance".to_string(), MetricValue::Num(f64::NAN))].into();
        let text = serde_json::to_string(&exact_metrics(&nan)).expect("JSON");
        let back = read_metrics(&serde_json::from_str(&text).expect("JSON")).expect("metrics");
        assert!(matches!(back["clearance"], MetricValue::Num(x) if x.is_nan()));
    }
}
