//! `scen bench --ompl-log DIR` (SPEC §4): one OMPL benchmark log per bench,
//! in the format of OMPL's `doc/markdown/benchmark.md` ("The benchmark
//! logfile format"), so that OMPL's own `ompl_benchmark_statistics.py`
//! turns it into the SQLite database that Planner Arena and OMPL's plotting
//! tools read.
//!
//! Each plan in each configuration is one OMPL "planner", named after the
//! plan and its varied values, with the plan's parameters as its common
//! properties. A run's properties carry OMPL's names where they exist —
//! `time REAL` (seconds), `solved BOOLEAN`, `solution length REAL`,
//! `solution smoothness REAL`, `solution clearance REAL`, `graph states
//! INTEGER`, `simplification time REAL` (seconds) — and scen's other
//! metrics under their own names (underscores as spaces, which the script
//! turns back into underscores for the database's columns).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::sink::{Command, Product, Sink, any_path, write_file};

use crate::contract::MetricValue;
use crate::run::BenchRun;
use crate::run::RunReport;
use crate::scenario::Scenario;

/// `--ompl-log DIR`: one log per bench that ran, in DIR (created if need
/// be).
pub static SINK: Sink = Sink {
    option: "--ompl-log",
    value_name: "DIR",
    help: &[(
        Command::Bench,
        "Write one OMPL benchmark log per bench into DIR (for `ompl_benchmark_statistics.py` and Planner Arena)",
    )],
    draws: false,
    folder: true,
    check: any_path,
    files: log_files,
    tuning: None,
    write: |product, path, _| write_logs(product, path),
};

/// The logs `--ompl-log DIR` writes: one per bench chosen (all when
/// `chosen` is empty).
fn log_files(dir: &Path, sc: &Scenario, chosen: &[String]) -> Vec<PathBuf> {
    (0..sc.benches.len())
        .filter(|&b| chosen.is_empty() || chosen.contains(&sc.benches[b].name))
        .map(|b| dir.join(log_name(sc, b)))
        .collect()
}

fn write_logs(product: Product<'_>, dir: &Path) -> Result<(), Vec<String>> {
    let Product::Bench(report, _) = product else {
        return Ok(());
    };
    std::fs::create_dir_all(dir)
        .map_err(|e| vec![format!("cannot create `{}`: {e}", dir.display())])?;
    let mut errors = Vec::new();
    for b in 0..report.scenario.benches.len() {
        if report.bench_runs.iter().any(|r| r.bench == b) {
            let (name, text) = bench_log(report, b);
            if let Err(e) = write_file(&dir.join(name), text) {
                errors.extend(e);
            }
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors)
    }
}

/// A metric logged under OMPL's name, with its type and a scale (scen's
/// milliseconds are OMPL's seconds).
const OMPL_NAMES: &[(&str, &str, &str, f64)] = &[
    ("time_ms", "time", "REAL", 1e-3),
    ("found", "solved", "BOOLEAN", 1.0),
    ("length", "solution length", "REAL", 1.0),
    ("smoothness", "solution smoothness", "REAL", 1.0),
    ("clearance", "solution clearance", "REAL", 1.0),
    ("graph_states", "graph states", "INTEGER", 1.0),
    ("simplify_ms", "simplification time", "REAL", 1e-3),
];

/// The file name of bench `b`'s log: `STEM.BENCH.log`.
pub fn log_name(sc: &Scenario, b: usize) -> String {
    let stem = sc.file.file_stem().map_or_else(
        || "scenario".to_string(),
        |s| s.to_string_lossy().into_owned(),
    );
    format!("{stem}.{}.log", sc.benches[b].name)
}

/// The log of bench `b` of the report: its file name and its text.
pub fn bench_log(report: &RunReport, b: usize) -> (String, String) {
    let sc = &report.scenario;
    let bench = &sc.benches[b];
    let runs: Vec<&BenchRun> = report.bench_runs.iter().filter(|r| r.bench == b).collect();
    let name = log_name(sc, b);
    // The run properties: OMPL's, then every other metric any run has.
    let mut properties: Vec<(&str, String, &str, f64)> = Vec::new();
    let has = |m: &str| runs.iter().any(|r| r.metrics.contains_key(m));
    for &(metric, ompl, ty, scale) in OMPL_NAMES {
        if has(metric) {
            properties.push((metric, ompl.to_string(), ty, scale));
        }
    }
    let mut others: Vec<(&str, bool)> = Vec::new();
    for r in &runs {
        for (m, v) in &r.metrics {
            if !OMPL_NAMES.iter().any(|(x, ..)| x == m) && !others.iter().any(|(o, _)| o == m) {
                others.push((m, matches!(v, MetricValue::Bool(_))));
            }
        }
    }
    others.sort_unstable();
    for (m, boolean) in others {
        properties.push((
            m,
            m.replace('_', " "),
            if boolean { "BOOLEAN" } else { "REAL" },
            1.0,
        ));
    }
    let total: f64 = runs
        .iter()
        .filter_map(|r| r.metrics.get("time_ms").map(|v| v.as_f64()))
        .sum::<f64>()
        / 1e3;
    let mut s = String::new();
    let _ = writeln!(s, "scen version {}", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(s, "Experiment {}", bench.name);
    let _ = writeln!(s, "Running on {}", hostname());
    let _ = writeln!(s, "Starting at {}", now());
    let _ = writeln!(s, "<<<|");
    let _ = writeln!(s, "scen bench `{}` of {}", bench.name, sc.file.display());
    if let Some(t) = &sc.title {
        let _ = writeln!(s, "{t}");
    }
    let _ = writeln!(s, "|>>>");
    let seed = bench
        .plans
        .first()
        .map_or(0, |p| sc.plans[p.plan].params.seed);
    let _ = writeln!(s, "{seed} is the random seed");
    let _ = writeln!(s, "{} seconds per run", bench.limits.time.unwrap_or(0.0));
    let _ = writeln!(s, "0 MB per run");
    let _ = writeln!(s, "{} runs per planner", bench.runs);
    let _ = writeln!(s, "{total} seconds spent to collect the data");
    let planners: Vec<(usize, usize)> = bench
        .plans
        .iter()
        .enumerate()
        .flat_map(|(p, plan)| (0..plan.configs.len()).map(move |c| (p, c)))
        .filter(|&(p, c)| runs.iter().any(|r| r.plan == p && r.config == c))
        .collect();
    let _ = writeln!(s, "{} planners", planners.len());
    for (p, config) in planners {
        let plan = &bench.plans[p].configs[config];
        let picks = bench.config_values(config);
        let mut title = format!("scen_{}", plan.name);
        for (v, &i) in bench.vary.iter().zip(&picks) {
            let _ = write!(title, " {}={}", v.key, v.values[i].text);
        }
        let _ = writeln!(s, "{}", one_line(&title));
        let common = common_properties(sc, plan);
        let _ = writeln!(s, "{} common properties", common.len());
        for line in &common {
            let _ = writeln!(s, "{line}");
        }
        let _ = writeln!(s, "{} properties for each run", properties.len());
        for (_, name, ty, _) in &properties {
            let _ = writeln!(s, "{name} {ty}");
        }
        let these: Vec<&&BenchRun> = runs
            .iter()
            .filter(|r| r.plan == p && r.config == config)
            .collect();
        let _ = writeln!(s, "{} runs", these.len());
        for r in these {
            for (metric, _, _, scale) in &properties {
                match r.metrics.get(*metric) {
                    Some(MetricValue::Bool(b)) => {
                        let _ = write!(s, "{}; ", u8::from(*b));
                    }
                    // A metric without a value (NaN) is an empty field,
                    // as OMPL writes a property it has no value for.
                    Some(MetricValue::Num(x)) if !x.is_nan() => {
                        let _ = write!(s, "{}; ", super::exact_number(x * scale));
                    }
                    Some(MetricValue::Num(_)) | None => s.push_str("; "),
                }
            }
            s.push('\n');
        }
        let _ = writeln!(s, ".");
    }
    (name, s)
}

/// A plan's settings as OMPL's `name = value` lines: its planner and robot,
/// then each parameter as written.
fn common_properties(sc: &Scenario, plan: &crate::scenario::Plan) -> Vec<String> {
    let mut out = vec![
        format!("planner = {}", plan.kind()),
        format!("robot = {}", sc.robots[plan.robot].name),
        format!(
            "start = {}",
            one_line(sc.sources.snippet(plan.params.start_span))
        ),
    ];
    if let Some(g) = plan.params.goal_span {
        out.push(format!("goal = {}", one_line(sc.sources.snippet(g))));
    }
    out.push(format!("seed = {}", plan.params.seed));
    for (key, p) in &plan.params.values {
        out.push(format!("{key} = {}", one_line(sc.sources.snippet(p.span))));
    }
    out
}

/// Text on one line (log lines end at newlines).
fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

fn hostname() -> String {
    std::fs::read_to_string("/etc/hostname")
        .ok()
        .map(|h| h.trim().to_string())
        .filter(|h| !h.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .map_or_else(|| "unknown".to_string(), |h| one_line(&h).replace(' ', "_"))
}

/// The current time as `YYYY-MM-DDTHH:MM:SS` (UTC).
fn now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rest) = ((secs / 86_400) as i64, secs % 86_400);
    // Civil from days (Howard Hinnant's algorithm), proleptic Gregorian.
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}",
        rest / 3600,
        rest / 60 % 60,
        rest % 60
    )
}
