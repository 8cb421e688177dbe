//! The human report of `scen run`: per plan its kind, robot, found or not
//! and key metrics; then each check PASS/FAIL with its line; then a summary.

use std::fmt::Write;

use crate::checks::{format_num, format_value};
use crate::contract::MetricValue;
use crate::diagnostics::Diag;
use crate::run::{CheckOutcome, RunReport};

/// Metrics shown first, in this order; the rest follow alphabetically.
const KEY_METRICS: &[&str] = &["cost", "length", "turn", "nodes", "expanded", "generated"];
/// Metrics not repeated in the metric line (shown elsewhere or noise).
const HIDDEN: &[&str] = &[
    "found",
    "gave_up",
    "collision_free",
    "reaches_goal",
    "time_ms",
];

/// A family's sample and what it drew (SPEC 2.8): `sample 7 (family seed
/// 0): gap_x = 3.25, gap_w = 1.5`.
pub fn sample_line(sc: &crate::Scenario) -> Option<String> {
    let drawn = sc.family.as_ref()?;
    let values: Vec<String> = drawn
        .params
        .iter()
        .map(|(name, x)| format!("{name} = {}", crate::checks::format_num(*x)))
        .collect();
    let rejected = match drawn.rejected {
        0 => String::new(),
        1 => ", 1 draw rejected".to_string(),
        n => format!(", {n} draws rejected"),
    };
    Some(format!(
        "sample {} (family seed {}{rejected}): {}",
        drawn.sample,
        drawn.family_seed,
        values.join(", ")
    ))
}

/// The report as text. `diagnostics` renders a failed check as a miette
/// diagnostic (pointing at the expression) under its FAIL line.
pub fn render(report: &RunReport, verbose: bool) -> String {
    let mut s = String::new();
    let sc = &report.scenario;
    match &sc.title {
        Some(t) => {
            let _ = writeln!(s, "{} — {}", sc.file.display(), t);
        }
        None => {
            let _ = writeln!(s, "{}", sc.file.display());
        }
    }
    if let Some(line) = sample_line(sc) {
        let _ = writeln!(s, "{line}");
    }
    for run in &report.plans {
        let plan = report.plan(run);
        let robot = &sc.robots[plan.robot];
        let m = &run.metrics;
        let status = if m.get("found") == Some(&MetricValue::Bool(true)) {
            let valid = if m.get("collision_free") == Some(&MetricValue::Bool(true)) {
                "collision-free"
            } else {
                "NOT collision-free"
            };
            format!("found, {valid}")
        } else {
            let why = if m.get("gave_up") == Some(&MetricValue::Bool(true)) {
                " (gave up: a limit was reached)"
            } else {
                ""
            };
            // A run that stopped short still moved the robot (SPEC 3).
            let motion = match (
                run.outcome.trajectory.is_empty(),
                m.get("collision_free") == Some(&MetricValue::Bool(true)),
            ) {
                (true, _) => "",
                (false, true) => "; the motion executed is collision-free",
                (false, false) => "; the motion executed is NOT collision-free",
            };
            format!("not found{why}{motion}")
        };
        let what = if robot.team.is_some() {
            "team"
        } else {
            "robot"
        };
        let _ = writeln!(
            s,
            "\nplan {} ({}, {what} {}): {}",
            plan.name,
            plan.kind(),
            robot.name,
            status
        );
        let mut parts = Vec::new();
        for k in KEY_METRICS {
            if let Some(v) = m.get(*k) {
                parts.push(format!("{k} {}", format_value(*v)));
            }
        }
        for (k, v) in m {
            if !KEY_METRICS.contains(&k.as_str()) && !HIDDEN.contains(&k.as_str()) {
                parts.push(format!("{k} {}", format_value(*v)));
            }
        }
        if verbose && let Some(t) = m.get("time_ms") {
            parts.push(format!("time {} ms", format_value(*t)));
        }
        let _ = writeln!(s, "  {}", parts.join("  "));
        for note in &run.outcome.notes {
            let _ = writeln!(s, "  note: {note}");
        }
        if let Some(v) = &run.validation {
            let what = v
                .obstacle
                .as_deref()
                .map(|o| format!("obstacle `{o}`"))
                .unwrap_or_else(|| "the bounds".into());
            let _ = writeln!(
                s,
                "  validator: segment {} hits {} at ({}, {}): {}",
                v.segment,
                what,
                format_num(v.at.x),
                format_num(v.at.y),
                v.reason
            );
        }
    }
    if !report.checks.is_empty() {
        let _ = writeln!(s, "\nchecks");
        for c in &report.checks {
            let _ = writeln!(s, "  {}", check_line(report, c));
        }
    }
    if let Some(line) = skipped_line(report) {
        let _ = writeln!(s, "\n{line}");
    }
    let bench_checks = sc.checks.iter().filter(|c| c.bench).count();
    if bench_checks > 0 && report.bench_runs.is_empty() {
        let _ = writeln!(
            s,
            "\n{bench_checks} check(s) read the benches; `scen bench {}` runs them",
            sc.file.display()
        );
    }
    let _ = writeln!(
        s,
        "\n{} passed, {} failed",
        report.passed(),
        report.failed()
    );
    s
}

/// `2 check(s) skipped: they read plans that did not run (`--plan`): lines
/// 12, 14`, when `--plan` left checks out (SPEC §4: a run never looks green
/// without saying what it did not check).
pub fn skipped_line(report: &RunReport) -> Option<String> {
    if report.skipped.is_empty() {
        return None;
    }
    let lines: Vec<String> = report
        .skipped
        .iter()
        .map(|&c| report.scenario.checks[c].line.to_string())
        .collect();
    Some(format!(
        "{} check(s) skipped: they read plans that did not run (`--plan`): line{} {}",
        lines.len(),
        if lines.len() == 1 { "" } else { "s" },
        lines.join(", ")
    ))
}

/// `PASS  line 23  offline.cost <= 90   (offline.cost = 79.1)`
pub fn check_line(report: &RunReport, c: &CheckOutcome) -> String {
    let check = &report.scenario.checks[c.check];
    let values = values_text(c);
    format!(
        "{}  line {}  {}{}",
        if c.passed { "PASS" } else { "FAIL" },
        check.line,
        check.text,
        if values.is_empty() {
            String::new()
        } else {
            format!("   ({values})")
        }
    )
}

/// The values a check read; for each series it aggregated, its size, min
/// and max.
pub fn values_text(c: &CheckOutcome) -> String {
    let mut parts: Vec<String> = c
        .values
        .iter()
        .map(|(k, v)| format!("{k} = {}", format_value(*v)))
        .collect();
    for (name, s) in &c.series {
        parts.push(format!(
            "{name}: {} run{}, min {}, max {}",
            s.runs,
            if s.runs == 1 { "" } else { "s" },
            format_num(s.min),
            format_num(s.max)
        ));
    }
    parts.join(", ")
}

/// A failed check as a diagnostic pointing at its expression.
pub fn failed_check_diag(report: &RunReport, c: &CheckOutcome) -> Diag {
    let check = &report.scenario.checks[c.check];
    let values = values_text(c);
    Diag::error(
        "scen::check::failed",
        format!("check failed: `{}`", check.text),
    )
    .at(
        check.span,
        if values.is_empty() {
            "false".to_string()
        } else {
            values
        },
    )
    .help("the expectation does not hold for this run; see the plan's metrics above")
}
