//! `scen validate FILE --plan NAME --path PATH.csv|PATH.json` (SPEC 7): a
//! path made elsewhere, judged by the validator against the plan's world
//! and robot, with the metrics of `scen run`.
//!
//! The path file:
//! - CSV: a header naming the columns, then one row per pose. `x` and `y`
//!   are needed; `theta` (radians) is optional, as are `plan` (rows of
//!   another plan are left out) and `what` (only `path` rows are read when
//!   there are any): the columns `scen run --csv` writes, so its output
//!   reads back. A `t` column (seconds) filled on every row makes the path
//!   a trajectory (SPEC 2.9). A malformed row is a diagnostic at its line
//!   and column.
//! - JSON: a list of poses `[x, y]` or `[x, y, θ]`, or of trajectory
//!   points `[x, y, θ, t]`; an object with a `"trajectory"` or `"path"`
//!   list; or a `scen run --json` document (its plan NAME's `"trajectory"`,
//!   else its `"path"`).
//!
//! In a world with moving obstacles only a trajectory can be judged: a
//! path without times is refused (`scen::validate::needs_times`).

use std::path::{Path, PathBuf};

use clap::Args;

use super::{
    EXIT_BAD_INPUT, EXIT_CHECK_FAILED, EXIT_OK, outln, outputs, print_failure, print_report,
};
use crate::diagnostics::{Diag, FileId, SourceMap, Span, render_diags};
use crate::files::{ReadError, read_regular_file};
use crate::geometry::Config;
use crate::report;

/// The largest path file read (bytes).
const MAX_PATH_BYTES: u64 = 256 << 20;

#[derive(Args, Debug)]
pub struct ValidateArgs {
    /// The scenario whose world and robot judge the path.
    pub file: PathBuf,
    /// The plan the path is for (its robot, start, goal and checks).
    #[arg(long, value_name = "NAME")]
    pub plan: String,
    /// The path: CSV (`x,y[,theta]` columns, as `scen run --csv` writes)
    /// or JSON (`[[x, y], ...]`, `{"path": ...}` or a `scen run --json`
    /// document).
    #[arg(long, value_name = "PATH.csv|PATH.json")]
    pub path: PathBuf,
    /// The folder the scenario may read files from (includes, maps);
    /// default: the folder of the file.
    #[arg(long, value_name = "DIR")]
    pub root: Option<PathBuf>,
    /// Print the JSON document of the run instead of the report.
    #[arg(long)]
    pub json: bool,
    /// The file outputs (`--svg`, `--png`, `--csv`): the path, and the
    /// first collision marked.
    #[command(flatten)]
    pub outputs: outputs::Outputs<outputs::RunSinks>,
}

/// Exit 0: the path is valid and the plan's checks pass; 1: it collides
/// (or a check fails); 2: bad input.
pub fn cmd_validate(args: &ValidateArgs) -> i32 {
    if !args.outputs.usable() {
        return EXIT_BAD_INPUT;
    }
    let scenario = match crate::scenario::load_with(&args.file, args.root.as_deref(), &|_| None) {
        Ok(s) => s,
        Err(f) => {
            print_failure(&f);
            return EXIT_BAD_INPUT;
        }
    };
    let inputs = {
        let mut i = super::clobber::scenario_inputs(&scenario.sources);
        i.push(super::clobber::Input {
            path: &args.path,
            role: "the path being validated",
        });
        i
    };
    let outputs: Vec<(&'static str, Option<PathBuf>)> = args
        .outputs
        .files(Some(&scenario), &[])
        .into_iter()
        .map(|(o, p)| (o, Some(p)))
        .collect();
    if !super::clobber::outputs_are_not_inputs(&outputs, &inputs) {
        return EXIT_BAD_INPUT;
    }
    let Some(index) = scenario.plans.iter().position(|p| p.name == args.plan) else {
        let names: Vec<&str> = scenario.plans.iter().map(|p| p.name.as_str()).collect();
        eprintln!(
            "error: `{}` has no plan `{}` (plans: {})",
            args.file.display(),
            args.plan,
            names.join(", ")
        );
        return EXIT_BAD_INPUT;
    };
    let plan = &scenario.plans[index];
    if scenario.robots[plan.robot].steering.is_some() {
        eprintln!(
            "error: plan `{}` is for a car robot, whose path is its segments (SPEC 3.0); validating a car's path from poses is not supported",
            args.plan
        );
        return EXIT_BAD_INPUT;
    }
    let (path, times) = match read_path(&args.path, &args.plan) {
        Ok(p) => p,
        Err((diags, sources)) => {
            eprint!("{}", render_diags(&diags, &sources));
            eprintln!("the path was not validated");
            return EXIT_BAD_INPUT;
        }
    };
    if times.is_none() && !scenario.moving.is_empty() {
        let mut sources = SourceMap::default();
        let id = sources.add(&args.path, "");
        let d = Diag::error(
            "scen::validate::needs_times",
            format!(
                "the world of `{}` has moving obstacles (`{}`): a path without times cannot be judged among them",
                args.file.display(),
                scenario.moving[0].name
            ),
        )
        .at(Span::new(id, 0, 0), "a path, not a trajectory")
        .help("give every pose its time: a `t` column (seconds) in CSV, or `[x, y, theta, t]` in JSON");
        eprint!("{}", render_diags(&[d], &sources));
        eprintln!("the path was not validated");
        return EXIT_BAD_INPUT;
    }
    let report = crate::run::validate_user_path(scenario, index, path, times);
    if args.json {
        let doc = report::json::to_json(&report);
        outln!("{}", serde_json::to_string(&doc).unwrap_or_default());
    } else {
        print_report(&report, false, || {
            // The report's words for skipped checks are `scen run --plan`'s.
            let mut text = report::text::render(&report, false).replace(
                "they read plans that did not run (`--plan`)",
                "they read other plans, or what only a planner measures",
            );
            text.push_str(&verdict_line(&report));
            text
        });
    }
    let mut code = EXIT_OK;
    if !args.outputs.write(report::sink::Product::Run(&report)) {
        code = EXIT_BAD_INPUT;
    }
    let collides = report.plans.iter().any(|p| p.validation.is_some());
    if collides || report.failed() > 0 {
        code = code.max(EXIT_CHECK_FAILED);
    }
    code
}

/// The last line of the report: valid, or where it first collides.
fn verdict_line(report: &crate::RunReport) -> String {
    match report.plans.first().and_then(|p| p.validation.as_ref()) {
        None => "valid: the path passes the validator\n".to_string(),
        Some(e) => format!(
            "collides: on segment {} (from pose {} to pose {}) at ({}, {}, {} rad){}: {}\n",
            e.segment,
            e.segment,
            e.segment + 1,
            e.at.x,
            e.at.y,
            e.at.theta,
            e.obstacle
                .as_ref()
                .map_or(String::new(), |o| format!(", obstacle `{o}`")),
            e.reason
        ),
    }
}

type Failure = (Vec<Diag>, SourceMap);

/// Poses, and their times when they are a trajectory.
pub type UserPath = (Vec<Config>, Option<Vec<f64>>);

/// The poses of `file` for plan `plan`, with their times when the file
/// gives them (see the module documentation).
pub fn read_path(file: &Path, plan: &str) -> Result<UserPath, Failure> {
    let mut sources = SourceMap::default();
    let bytes = match read_regular_file(file, MAX_PATH_BYTES) {
        Ok(b) => b,
        Err(e) => {
            let id = sources.add(file, "");
            let label = match e {
                ReadError::TooLarge(_) => "file too large",
                _ => "unreadable",
            };
            let d = Diag::error(
                "scen::validate::unreadable",
                format!("cannot read the path file `{}`: {e}", file.display()),
            )
            .at(Span::new(id, 0, 0), label)
            .help("give a CSV (`x,y[,theta]` columns) or JSON (`[[x, y], ...]`) file");
            return Err((vec![d], sources));
        }
    };
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let id = sources.add(file, text.clone());
    let json = file
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
        || text.trim_start().starts_with(['[', '{']);
    let parsed = if json {
        from_json(&text, id, plan)
    } else {
        from_csv(&text, id, plan)
    };
    match parsed {
        Ok((path, _)) if path.is_empty() => {
            let d = Diag::error(
                "scen::validate::empty_path",
                format!("the path file has no pose for plan `{plan}`"),
            )
            .at(Span::new(id, 0, 0), "no pose")
            .help("a path has at least one pose: rows `x,y` under a header, or `[[x, y], ...]`");
            Err((vec![d], sources))
        }
        Ok(path) => Ok(path),
        Err(d) => Err((vec![*d], sources)),
    }
}

fn bad_row(span: Span, message: String, label: &str, help: &str) -> Box<Diag> {
    Box::new(
        Diag::error("scen::validate::bad_row", message)
            .at(span, label)
            .help(help.to_string()),
    )
}

const CSV_HELP: &str =
    "a row is a pose under the header: `x,y` or `x,y,theta` (radians), e.g. `1.5,2,0`";

fn from_csv(text: &str, file: FileId, plan: &str) -> Result<UserPath, Box<Diag>> {
    // Lines with their byte offsets, blank ones and `#` comments skipped.
    let mut lines = Vec::new();
    let mut at = 0;
    for line in text.split_inclusive('\n') {
        let content = line.trim_end_matches(['\n', '\r']);
        if !content.trim().is_empty() && !content.trim_start().starts_with('#') {
            lines.push((at, content));
        }
        at += line.len();
    }
    let Some(&(header_at, header)) = lines.first() else {
        return Ok((Vec::new(), None));
    };
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let column = |name: &str| names.iter().position(|n| *n == name);
    let (Some(cx), Some(cy)) = (column("x"), column("y")) else {
        return Err(Box::new(
            Diag::error(
                "scen::validate::bad_header",
                "the CSV header names no `x` and `y` columns",
            )
            .at(Span::new(file, header_at, header_at + header.len()), "the header")
            .help("start with a header naming the columns: `x,y` or `x,y,theta` (what `scen run --csv` writes works too)"),
        ));
    };
    let (ctheta, cplan, cwhat) = (column("theta"), column("plan"), column("what"));
    let ct = column("t");
    struct Row<'a> {
        fields: Vec<(usize, &'a str)>,
    }
    let mut rows = Vec::new();
    for &(start, line) in &lines[1..] {
        let mut fields = Vec::new();
        let mut offset = start;
        for f in line.split(',') {
            fields.push((offset, f));
            offset += f.len() + 1;
        }
        if fields.len() != names.len() {
            return Err(bad_row(
                Span::new(file, start, start + line.len()),
                format!(
                    "this row has {} fields, the header {}",
                    fields.len(),
                    names.len()
                ),
                "wrong number of fields",
                CSV_HELP,
            ));
        }
        rows.push(Row { fields });
    }
    let of_plan = |r: &Row| cplan.is_none_or(|c| r.fields[c].1.trim() == plan);
    let what = |r: &Row<'_>| -> Option<String> { cwhat.map(|c| r.fields[c].1.trim().to_string()) };
    let any_path = rows
        .iter()
        .any(|r| of_plan(r) && what(r).as_deref() == Some("path"));
    let mut path = Vec::new();
    let mut times = Vec::new();
    // The first row read without a time, and whether any row had one.
    let mut untimed: Option<Span> = None;
    for r in rows.iter().filter(|r| of_plan(r)) {
        if any_path && what(r).as_deref() != Some("path") {
            continue;
        }
        let number = |c: usize, what: &str| -> Result<f64, Box<Diag>> {
            let (at, raw) = r.fields[c];
            let lead = raw.len() - raw.trim_start().len();
            let t = raw.trim();
            let span = Span::new(file, at + lead, at + lead + t.len().max(1));
            match t.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(bad_row(
                    span,
                    format!("`{t}` is not a finite number ({what})"),
                    "not a number",
                    CSV_HELP,
                )),
            }
        };
        let x = number(cx, "x")?;
        let y = number(cy, "y")?;
        let theta = match ctheta {
            Some(c) if !r.fields[c].1.trim().is_empty() => number(c, "theta")?,
            _ => 0.0,
        };
        path.push(Config::new(x, y, theta));
        match ct {
            Some(c) if !r.fields[c].1.trim().is_empty() => times.push(number(c, "t")?),
            Some(c) => {
                let at = r.fields[c].0;
                untimed.get_or_insert(Span::new(file, at, at));
            }
            None => {}
        }
    }
    if let (Some(span), false) = (untimed, times.is_empty()) {
        return Err(bad_row(
            span,
            "this row has no time, where others have one".into(),
            "no `t`",
            "a trajectory gives every row its time `t` (seconds); a path gives none",
        ));
    }
    let times = (!times.is_empty()).then_some(times);
    if path.is_empty() && cplan.is_some() && !rows.is_empty() {
        let others: Vec<&str> = {
            let mut v: Vec<&str> = rows
                .iter()
                .map(|r| r.fields[cplan.unwrap_or(0)].1.trim())
                .collect();
            v.sort_unstable();
            v.dedup();
            v
        };
        return Err(Box::new(
            Diag::error(
                "scen::validate::empty_path",
                format!("the path file has no row of plan `{plan}`"),
            )
            .at(
                Span::new(file, header_at, header_at + header.len()),
                "rows of other plans only",
            )
            .help(format!("its plans: {}", others.join(", "))),
        ));
    }
    Ok((path, times))
}

fn from_json(text: &str, file: FileId, plan: &str) -> Result<UserPath, Box<Diag>> {
    use serde_json::Value;
    let doc: Value = match serde_json::from_str(text) {
        Ok(v) => v,
        Err(e) => {
            let at = offset_of(text, e.line(), e.column());
            return Err(Box::new(
                Diag::error("scen::validate::bad_json", format!("not JSON: {e}"))
                    .at(Span::new(file, at, (at + 1).min(text.len())), "here")
                    .help("a path is `[[x, y], [x, y, theta], ...]`, or an object with a \"path\" list"),
            ));
        }
    };
    let whole = Span::new(file, 0, text.len().min(1));
    let poses = match &doc {
        Value::Array(_) => &doc,
        Value::Object(o) => match (o.get("trajectory").or(o.get("path")), o.get("plans")) {
            (Some(p), _) => p,
            (None, Some(Value::Object(plans))) => match plans.get(plan).and_then(|p| {
                p.get("trajectory")
                    .filter(|t| t.is_array())
                    .or(p.get("path"))
            }) {
                Some(p) => p,
                None => {
                    return Err(Box::new(
                        Diag::error(
                            "scen::validate::empty_path",
                            format!("the document has no path of plan `{plan}`"),
                        )
                        .at(whole, "no such plan, or no path")
                        .help(format!(
                            "its plans: {}",
                            plans.keys().cloned().collect::<Vec<_>>().join(", ")
                        )),
                    ));
                }
            },
            _ => {
                return Err(Box::new(
                    Diag::error("scen::validate::bad_json", "the object has no \"path\" list")
                        .at(whole, "no path")
                        .help("a path is `[[x, y], ...]`, `{\"path\": [[x, y], ...]}` or a `scen run --json` document"),
                ));
            }
        },
        _ => {
            return Err(Box::new(
                Diag::error("scen::validate::bad_json", "a path is a list of poses")
                    .at(whole, "not a list")
                    .help("a path is `[[x, y], [x, y, theta], ...]`"),
            ));
        }
    };
    // `null`: a plan that found no path.
    let Some(list) = poses.as_array() else {
        return Err(Box::new(
            Diag::error(
                "scen::validate::empty_path",
                "the path is not a list of poses",
            )
            .at(whole, "no path")
            .help("a path is `[[x, y], [x, y, theta], ...]`"),
        ));
    };
    let mut path = Vec::with_capacity(list.len());
    let mut times = Vec::new();
    for (k, pose) in list.iter().enumerate() {
        let numbers: Option<Vec<f64>> = pose
            .as_array()
            .and_then(|a| a.iter().map(Value::as_f64).collect());
        // A trajectory's points have four numbers, all of them.
        let timed = k > 0 && !times.is_empty();
        match numbers.as_deref() {
            Some([x, y]) if !timed => path.push(Config::new(*x, *y, 0.0)),
            Some([x, y, theta]) if !timed => path.push(Config::new(*x, *y, *theta)),
            Some([x, y, theta, t]) if k == 0 || timed => {
                path.push(Config::new(*x, *y, *theta));
                times.push(*t);
            }
            _ => {
                return Err(Box::new(
                    Diag::error(
                        "scen::validate::bad_row",
                        format!(
                            "pose {k} is not `[x, y]`, `[x, y, theta]` or, in a trajectory, `[x, y, theta, t]`: {pose}"
                        ),
                    )
                    .at(whole, "in this document")
                    .help("every pose is a list of two or three numbers; every point of a trajectory, of four"),
                ));
            }
        }
    }
    Ok((path, (!times.is_empty()).then_some(times)))
}

/// The byte offset of 1-based `line` and `column` in `text`.
fn offset_of(text: &str, line: usize, column: usize) -> usize {
    let start: usize = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum();
    (start + column.saturating_sub(1)).min(text.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The poses of a CSV path without times.
    fn csv(text: &str) -> Result<Vec<Config>, Box<Diag>> {
        from_csv(text, 0, "p").map(|(path, times)| {
            assert_eq!(times, None);
            path
        })
    }

    #[test]
    fn csv_rows_with_and_without_theta_and_scen_runs_columns() {
        let path = csv("x,y\n0,0\n1.5, 2\n").unwrap();
        assert_eq!(
            path,
            vec![Config::new(0.0, 0.0, 0.0), Config::new(1.5, 2.0, 0.0)]
        );
        let path = csv("# a comment\nx,y,theta\n\n0,0,0.5\n").unwrap();
        assert_eq!(path, vec![Config::new(0.0, 0.0, 0.5)]);
        // What `scen run --csv` writes: other plans and drives left out.
        let run = "plan,what,index,t,x,y,theta,length\n\
                   q,path,0,,9,9,0,0\n\
                   p,path,0,,1,1,0,0\n\
                   p,path,1,,2,1,0,1\n\
                   p,drive,0,0,1,1,0,0\n";
        assert_eq!(
            csv(run).unwrap(),
            vec![Config::new(1.0, 1.0, 0.0), Config::new(2.0, 1.0, 0.0)]
        );
    }

    #[test]
    fn a_malformed_row_is_located() {
        let text = "x,y\n0,0\n1,abc\n";
        let d = csv(text).unwrap_err();
        assert_eq!(d.code, "scen::validate::bad_row");
        let span = d.span.unwrap();
        assert_eq!(&text[span.start..span.end], "abc");
        let d = csv("x,y\n0,0,0\n").unwrap_err();
        assert!(d.message.contains("3 fields"), "{}", d.message);
        let d = csv("a,b\n0,0\n").unwrap_err();
        assert_eq!(d.code, "scen::validate::bad_header");
        let d = csv("x,y\nnan,0\n").unwrap_err();
        assert_eq!(d.code, "scen::validate::bad_row");
        let d = csv("plan,x,y\nq,0,0\n").unwrap_err();
        assert_eq!(d.code, "scen::validate::empty_path");
    }

    #[test]
    fn json_shapes() {
        let j = |t: &str| from_json(t, 0, "p");
        let two = (
            vec![Config::new(0.0, 0.0, 0.0), Config::new(1.0, 2.0, 0.5)],
            None,
        );
        assert_eq!(j("[[0, 0], [1, 2, 0.5]]").unwrap(), two);
        assert_eq!(j("{\"path\": [[0, 0], [1, 2, 0.5]]}").unwrap(), two);
        assert_eq!(
            j("{\"plans\": {\"p\": {\"path\": [[0, 0], [1, 2, 0.5]]}}}").unwrap(),
            two
        );
        // A trajectory, alone or beside its path in a run's document.
        let timed = (two.0.clone(), Some(vec![0.0, 3.0]));
        assert_eq!(j("[[0, 0, 0, 0], [1, 2, 0.5, 3]]").unwrap(), timed);
        assert_eq!(
            j("{\"plans\": {\"p\": {\"path\": [[9, 9]], \"trajectory\": [[0, 0, 0, 0], [1, 2, 0.5, 3]]}}}")
                .unwrap(),
            timed
        );
        let d = j("[[0, 0], [1]]").unwrap_err();
        assert!(d.message.contains("pose 1"), "{}", d.message);
        let d = j("[[0, 0],\n [1, 2,]]").unwrap_err();
        assert_eq!(d.code, "scen::validate::bad_json");
        assert_eq!(
            d.span.unwrap().start,
            offset_of("[[0, 0],\n [1, 2,]]", 2, 8)
        );
        assert_eq!(
            j("{\"plans\": {\"q\": {}}}").unwrap_err().code,
            "scen::validate::empty_path"
        );
    }
}
