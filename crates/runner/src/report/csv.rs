//! `scen run --csv OUT.csv` (SPEC §4): every plan's path as rows, for the
//! tools users already plot with (a spreadsheet, pandas, MATLAB's
//! `readtable`).
//!
//! Columns: `plan`, `what` (`path`; `trajectory` for the motion executed by
//! a run that stopped short; `drive` for the simulated robot driving the
//! path; `agent NAME` for each agent of a team plan, one row per step, `t`
//! the step), `index` (0-based along that line), `t` (seconds: a time-aware
//! plan's trajectory on its `path` rows, and `drive` rows; empty otherwise), `x`, `y`, `theta` (radians), `length` (the cumulative
//! (x, y) arc length from the line's first row). Numbers are written exactly
//! (shortest round-trip form), so a program reading the file gets the very
//! values `scen` validated.

use std::fmt::Write as _;

use super::sink::{Command, Product, Sink, any_path, the_file, write_file};

use super::exact_number;
use crate::geometry::Config;
use crate::run::RunReport;

/// `--csv OUT.csv`: a run's paths as rows (this module), or every run of a
/// bench as a row ([`super::bench::to_csv`]).
pub static SINK: Sink = Sink {
    option: "--csv",
    value_name: "OUT.csv",
    help: &[
        (
            Command::Run,
            "Write every plan's path (and driven trajectory) as CSV rows",
        ),
        (Command::Bench, "Write every run as a CSV row"),
    ],
    draws: false,
    folder: false,
    check: any_path,
    files: the_file,
    tuning: None,
    write: |product, path, _| match product {
        Product::Run(report) => match paths_csv(report) {
            Some(text) => write_file(path, text),
            None => Err(vec![format!(
                "`--csv {}`: no plan found a path or moved the robot; nothing was written",
                path.display()
            )]),
        },
        Product::Bench(report, _) => write_file(path, super::bench::to_csv(report)),
    },
};

/// The header line.
pub const HEADER: &str = "plan,what,index,t,x,y,theta,length";

/// The CSV of every plan's path, trajectory and driven motion; `None` when
/// no plan produced any (nothing to write).
pub fn paths_csv(report: &RunReport) -> Option<String> {
    let mut s = String::new();
    let _ = writeln!(s, "{HEADER}");
    let mut rows = 0;
    for run in &report.plans {
        let plan = report.plan(run);
        let name = quoted(&plan.name);
        // A team's agents (SPEC 2.10): one line each, a row per step.
        let team = plan.team(&report.scenario);
        if let (Some(team), Some(paths)) = (team, &run.outcome.agents) {
            let times = run.outcome.agent_times.as_deref();
            for (k, (agent, path)) in team.iter().zip(paths).enumerate() {
                // The step, or a continuous team's time.
                let t = |i: usize| {
                    times
                        .and_then(|t| t.get(k)?.get(i).copied())
                        .unwrap_or(i as f64)
                };
                rows += lines(
                    &mut s,
                    &name,
                    &quoted(&format!("agent {}", agent.name)),
                    path.iter()
                        .enumerate()
                        .map(|(i, p)| (Some(t(i)), Config::new(p.x, p.y, 0.0))),
                );
            }
        }
        if let Some(path) = &run.outcome.path {
            // A trajectory's times (SPEC 2.9) go with its poses.
            let times = run
                .outcome
                .times
                .as_deref()
                .filter(|t| t.len() == path.len());
            let t = |i: usize| times.map(|t| t[i]);
            rows += lines(
                &mut s,
                &name,
                "path",
                path.iter().enumerate().map(|(i, c)| (t(i), *c)),
            );
        } else if !run.outcome.trajectory.is_empty() {
            rows += lines(
                &mut s,
                &name,
                "trajectory",
                run.outcome.trajectory.iter().map(|c| (None, *c)),
            );
        }
        if let Some(drive) = &run.drive {
            rows += lines(
                &mut s,
                &name,
                "drive",
                drive.samples.iter().map(|(t, c)| (Some(*t), *c)),
            );
        }
    }
    (rows > 0).then_some(s)
}

/// Appends the rows of one line; returns how many.
fn lines(
    s: &mut String,
    plan: &str,
    what: &str,
    poses: impl Iterator<Item = (Option<f64>, Config)>,
) -> usize {
    let mut length = 0.0;
    let mut last: Option<Config> = None;
    let mut n = 0;
    for (i, (t, c)) in poses.enumerate() {
        if let Some(p) = last {
            length += (c.x - p.x).hypot(c.y - p.y);
        }
        last = Some(c);
        let _ = writeln!(
            s,
            "{plan},{what},{i},{},{},{},{},{}",
            t.map(exact_number).unwrap_or_default(),
            exact_number(c.x),
            exact_number(c.y),
            exact_number(c.theta),
            exact_number(length)
        );
        n += 1;
    }
    n
}

/// A plan name as a CSV field (names are identifiers, but a field is
/// quoted whenever it could be misread).
fn quoted(name: &str) -> String {
    if name.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", name.replace('"', "\"\""))
    } else {
        name.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_accumulate_the_arc_length() {
        let mut s = String::new();
        let poses = [
            Config::new(0.0, 0.0, 0.0),
            Config::new(3.0, 4.0, 0.5),
            Config::new(3.0, 5.0, 1.0),
        ];
        let n = lines(&mut s, "p", "path", poses.iter().map(|c| (None, *c)));
        assert_eq!(n, 3);
        assert_eq!(
            s,
            "p,path,0,,0,0,0,0\np,path,1,,3,4,0.5,5\np,path,2,,3,5,1,6\n"
        );
    }

    #[test]
    fn drive_rows_carry_their_time() {
        let mut s = String::new();
        let poses = [
            (0.0, Config::new(1.0, 1.0, 0.0)),
            (0.02, Config::new(1.5, 1.0, 0.0)),
        ];
        lines(
            &mut s,
            "d",
            "drive",
            poses.iter().map(|(t, c)| (Some(*t), *c)),
        );
        assert_eq!(s, "d,drive,0,0,1,1,0,0\nd,drive,1,0.02,1.5,1,0,0.5\n");
    }

    #[test]
    fn names_that_could_be_misread_are_quoted() {
        assert_eq!(quoted("plan_1"), "plan_1");
        assert_eq!(quoted("a,b"), "\"a,b\"");
        assert_eq!(quoted("a\"b"), "\"a\"\"b\"");
    }
}
