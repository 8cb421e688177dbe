//! The command line: `run`, `check`, `test`, `fmt`, `lsp`, `import`.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};

use clap::{Args, Parser, Subcommand, ValueEnum};
use rayon::prelude::*;

use crate::diagnostics::{Diag, SourceMap, render_diags};
use crate::report;
use crate::run::{RunReport, run_scenario_drawing};
use crate::scenario::loader::LoadFailure;
use crate::viz::{self, ViewerTarget};

mod bench;
mod clobber;
mod falsify;
mod fmt;
mod outputs;
mod validate;
mod watch;

/// Standard output with its failures remembered: a report that could not be
/// written (a full disk, `/dev/full`, a closed pipe) makes the command exit
/// with [`EXIT_BAD_INPUT`], never a silent success (SPEC §4).
static STDOUT_ERROR: std::sync::Mutex<Option<String>> = std::sync::Mutex::new(None);

/// Writes to standard output; a failure is remembered for the exit code.
pub(crate) fn write_stdout(args: std::fmt::Arguments<'_>) {
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_fmt(args) {
        remember_stdout_error(e);
    }
}

fn remember_stdout_error(e: std::io::Error) {
    if let Ok(mut first) = STDOUT_ERROR.lock()
        && first.is_none()
    {
        *first = Some(e.to_string());
    }
}

/// `print!` to standard output, failures remembered ([`write_stdout`]).
macro_rules! out {
    ($($arg:tt)*) => { $crate::cli::write_stdout(format_args!($($arg)*)) };
}

/// `println!` to standard output, failures remembered ([`write_stdout`]).
macro_rules! outln {
    () => { $crate::cli::write_stdout(format_args!("\n")) };
    ($($arg:tt)*) => {{
        $crate::cli::write_stdout(format_args!($($arg)*));
        $crate::cli::write_stdout(format_args!("\n"));
    }};
}
pub(crate) use {out, outln};

/// Exit codes (SPEC 4).
pub const EXIT_OK: i32 = 0;
pub const EXIT_CHECK_FAILED: i32 = 1;
pub const EXIT_BAD_INPUT: i32 = 2;

#[derive(Parser, Debug)]
#[command(
    name = "scen",
    version,
    about = "Run 2D motion-planning scenarios and check their results"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Run scenarios: plan, check, report.
    Run(RunArgs),
    /// Parse and analyse only; no planner runs.
    Check(CheckArgs),
    /// Run every *.scen under the given paths as a regression suite.
    Test(TestArgs),
    /// Run the benches of scenarios: tables, statistics, checks
    /// (`scen bench merge PART.jsonl...` combines the parts of `--shard`).
    Bench(BenchArgs),
    /// Search a family of scenarios (`param`, `scatter`) for a sample where
    /// an `expect` fails; shrink it into a standalone scenario.
    Falsify(falsify::FalsifyArgs),
    /// Rewrite files in the canonical layout, keeping every comment.
    Fmt(FmtArgs),
    /// Run a scenario again on every save of it or of a file it reads.
    Watch(RunArgs),
    /// Judge a path made elsewhere (CSV or JSON) with the validator, against
    /// a plan's world and robot: valid (exit 0) or where it first collides
    /// (exit 1).
    Validate(validate::ValidateArgs),
    /// A Language Server on stdin/stdout (for editors).
    Lsp,
    /// Convert another format into a scenario.
    Import {
        /// The format (`roadmap`: a SEEDS §D input.txt).
        format: String,
        file: PathBuf,
    },
}

#[derive(Args, Debug)]
pub struct RunArgs {
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// The folder the scenario may read files from (includes, maps);
    /// default: the folder of each file named.
    #[arg(long, value_name = "DIR")]
    pub root: Option<PathBuf>,
    /// Run only this plan (repeatable).
    #[arg(long = "plan", value_name = "NAME")]
    pub plans: Vec<String>,
    /// Print one JSON document per file instead of the report.
    #[arg(long)]
    pub json: bool,
    /// Write a Rerun recording.
    #[arg(long, value_name = "OUT.rrd", conflicts_with_all = ["spawn", "connect"])]
    pub save: Option<PathBuf>,
    /// Start the Rerun viewer (`rerun` from PATH) and stream to it.
    #[arg(long, conflicts_with = "connect")]
    pub spawn: bool,
    /// Stream to a running Rerun viewer (default address of Rerun 0.36).
    #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = "")]
    pub connect: Option<String>,
    /// The file outputs (`--svg`, `--png`, `--csv`: the sink registry).
    #[command(flatten)]
    pub outputs: outputs::Outputs<outputs::RunSinks>,
    /// Print only the summary and failures.
    #[arg(short, long, conflicts_with = "verbose")]
    pub quiet: bool,
    /// Print timings too.
    #[arg(short, long)]
    pub verbose: bool,
    /// For a family of scenarios (`param`, `scatter`): run sample K.
    #[arg(long, value_name = "K", default_value_t = 0)]
    pub sample: u64,
    /// For a family of scenarios: the seed its samples are drawn from.
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub family_seed: u64,
    /// For a family of scenarios: a drawn param's value instead of its
    /// draw (repeatable; what `scen falsify` reports). Scattered items
    /// still come from sample K's stream.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
}

impl RunArgs {
    /// The sample of a family to run (`--sample`, `--family-seed`).
    fn sample_choice(&self) -> crate::scenario::SampleChoice {
        crate::scenario::SampleChoice {
            sample: self.sample,
            family_seed: self.family_seed,
        }
    }

    /// Where `--save`, `--spawn` or `--connect` send the run, if anywhere.
    fn viewer_target(&self) -> Option<ViewerTarget> {
        if let Some(path) = &self.save {
            Some(ViewerTarget::Save(path.clone()))
        } else if self.spawn {
            Some(ViewerTarget::Spawn)
        } else {
            self.connect
                .as_ref()
                .map(|a| ViewerTarget::Connect(Some(a.clone()).filter(|a| !a.is_empty())))
        }
    }

    /// The options that are refused before anything runs: several files
    /// with a single-file output, an output that cannot be written, a
    /// viewer this build does not have. Prints the problem.
    fn usable(&self) -> bool {
        if !self.outputs.usable() {
            return false;
        }
        let mut single = self.outputs.one_per_scenario();
        if self.save.is_some() {
            single.push("--save");
        }
        if self.files.len() > 1 && !single.is_empty() {
            eprintln!("error: {}", one_file_only(&single));
            return false;
        }
        if self.viewer_target().is_some() && !viz::VIEWER_BUILT {
            eprintln!("error: {}", viz::ViewerError::NotBuilt);
            return false;
        }
        outputs_writable(&[("--save", self.save.as_ref())])
    }

    /// The output files, each with its option: never a file the run
    /// reads. Before the scenario is loaded (`scen watch` refuses an
    /// output onto the watched file at once), the paths as given.
    fn output_files(
        &self,
        scenario: Option<&crate::Scenario>,
    ) -> Vec<(&'static str, Option<PathBuf>)> {
        let mut all: Vec<(&'static str, Option<PathBuf>)> = self
            .outputs
            .files(scenario, &[])
            .into_iter()
            .map(|(o, p)| (o, Some(p)))
            .collect();
        all.push(("--save", self.save.clone()));
        all
    }
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum Format {
    Human,
    Json,
}

#[derive(Args, Debug)]
pub struct CheckArgs {
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// The folder the scenario may read files from (includes, maps);
    /// default: the folder of each file named.
    #[arg(long, value_name = "DIR")]
    pub root: Option<PathBuf>,
    /// `json`: one JSON object per diagnostic, one per line.
    #[arg(long, value_enum, default_value = "human")]
    pub format: Format,
}

#[derive(Args, Debug)]
pub struct TestArgs {
    /// Files or folders (default: the current folder).
    pub paths: Vec<PathBuf>,
    /// The folder the scenario may read files from (includes, maps);
    /// default: the folder of each file named.
    #[arg(long, value_name = "DIR")]
    pub root: Option<PathBuf>,
    /// Run only the K-th of N parts of the files (1 ≤ K ≤ N), e.g. on a CI
    /// matrix.
    #[arg(long, value_name = "K/N", value_parser = crate::bench::Shard::parse)]
    pub shard: Option<crate::bench::Shard>,
    /// Write a JUnit XML report: one test case per check.
    #[arg(long, value_name = "OUT.xml")]
    pub junit: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Scenario files; or `merge` followed by the parts written with
    /// `--shard K/N --out PART.jsonl`.
    #[arg(required = true, value_name = "FILE")]
    pub files: Vec<PathBuf>,
    /// The folder the scenario may read files from (includes, maps);
    /// default: the folder of each file named.
    #[arg(long, value_name = "DIR")]
    pub root: Option<PathBuf>,
    /// Run only this bench (repeatable).
    #[arg(long = "bench", value_name = "NAME")]
    pub benches: Vec<String>,
    /// Print one JSON document per file instead of the tables.
    #[arg(long)]
    pub json: bool,
    /// The file outputs (`--svg`, `--png`, `--csv`, `--ompl-log`: the sink
    /// registry).
    #[command(flatten)]
    pub outputs: outputs::Outputs<outputs::BenchSinks>,
    /// Runs per configuration, for every bench (overrides each bench's
    /// `runs`).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=10_000_000))]
    pub runs: Option<u64>,
    /// Samples of the family per configuration, for every bench (overrides
    /// each bench's `worlds`; the scenario must draw something).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=100_000))]
    pub worlds: Option<u64>,
    /// Run only the K-th of N parts of the runs (1 ≤ K ≤ N); needs `--out`.
    #[arg(long, value_name = "K/N", requires = "out", value_parser = crate::bench::Shard::parse)]
    pub shard: Option<crate::bench::Shard>,
    /// Where `--shard` writes its part (JSON Lines).
    #[arg(long, value_name = "PART.jsonl", requires = "shard")]
    pub out: Option<PathBuf>,
    /// The table's metric columns (default: time_ms,length,cost,expanded,clearance,smoothness).
    #[arg(long, value_name = "a,b,...", value_delimiter = ',')]
    pub metrics: Vec<String>,
    /// Compare plan A with plan B run by run: side by side, then wins,
    /// ties and losses per metric with a sign test.
    #[arg(long, value_name = "A,B", value_delimiter = ',')]
    pub compare: Vec<String>,
    /// Print only the checks' failures and the summary; no progress bar.
    #[arg(short, long)]
    pub quiet: bool,
}

#[derive(Args, Debug)]
pub struct FmtArgs {
    /// Files or folders (every `*.scen` under them); none: stdin to stdout.
    pub files: Vec<PathBuf>,
    /// Change nothing; list the files that would change and exit 1.
    #[arg(long)]
    pub check: bool,
}

/// Runs the CLI; returns the exit code.
pub fn main() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() {
                EXIT_BAD_INPUT
            } else {
                EXIT_OK
            };
            let _ = e.print();
            return code;
        }
    };
    let _ = miette::set_hook(Box::new(|_| {
        Box::new(
            miette::MietteHandlerOpts::new()
                .terminal_links(false)
                .color(std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none())
                .build(),
        )
    }));
    let code = match cli.command {
        Command::Run(args) => cmd_run(&args),
        Command::Check(args) => cmd_check(&args),
        Command::Test(args) => cmd_test(&args),
        Command::Bench(args) => bench::cmd_bench(&args),
        Command::Falsify(args) => falsify::cmd_falsify(&args),
        Command::Fmt(args) => fmt::run(&args.files, args.check),
        Command::Watch(args) => watch::cmd_watch(&args),
        Command::Validate(args) => validate::cmd_validate(&args),
        // The server writes its own messages and ends on `exit`.
        Command::Lsp => return crate::lsp::run(),
        Command::Import { format, file } => cmd_import(&format, &file),
    };
    if let Err(e) = std::io::stdout().flush() {
        remember_stdout_error(e);
    }
    match STDOUT_ERROR.lock().ok().and_then(|mut e| e.take()) {
        Some(e) => {
            eprintln!("error: cannot write to standard output: {e}; the output is lost");
            EXIT_BAD_INPUT
        }
        None => code,
    }
}

/// `scen import FORMAT FILE`: the scenario on stdout.
fn cmd_import(format: &str, file: &Path) -> i32 {
    if format != "roadmap" {
        eprintln!("error: unknown import format `{format}` (known: roadmap)");
        return EXIT_BAD_INPUT;
    }
    match crate::import::import_roadmap_file(file) {
        Ok(text) => {
            out!("{text}");
            EXIT_OK
        }
        Err((diags, sources)) => {
            eprint!("{}", render_diags(&diags, &sources));
            EXIT_BAD_INPUT
        }
    }
}

/// Checks, before any planner runs, that the output file `path` of option
/// `flag` can be written (SPEC §4): its folder exists and is writable, and
/// the path is not a folder. A run that would only fail at its end, after
/// minutes of planning, is refused at once.
pub(crate) fn check_output_path(flag: &str, path: &Path) -> Result<(), String> {
    let shown = path.display();
    if path.as_os_str().is_empty() {
        return Err(format!("`{flag}` needs a file name"));
    }
    if path.is_dir() {
        return Err(format!(
            "`{flag} {shown}`: `{shown}` is a folder; name a file"
        ));
    }
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !folder.is_dir() {
        return Err(format!(
            "`{flag} {shown}`: the folder `{}` does not exist; create it first",
            folder.display()
        ));
    }
    if !writable(folder) {
        return Err(format!(
            "`{flag} {shown}`: the folder `{}` is not writable",
            folder.display()
        ));
    }
    Ok(())
}

/// The error for options that write one file per scenario, given with
/// several scenario files.
pub(crate) fn one_file_only(options: &[&str]) -> String {
    let named: Vec<String> = options.iter().map(|o| format!("`{o}`")).collect();
    format!(
        "{} take{} one scenario file; run the files one at a time",
        named.join(", "),
        if named.len() == 1 { "s" } else { "" }
    )
}

/// An existing folder an output writes its files into: writable.
pub(crate) fn check_output_folder(flag: &str, dir: &Path) -> Result<(), String> {
    if writable(dir) {
        Ok(())
    } else {
        Err(format!(
            "`{flag} {0}`: the folder `{0}` is not writable",
            dir.display()
        ))
    }
}

#[cfg(unix)]
fn writable(folder: &Path) -> bool {
    use std::os::unix::ffi::OsStrExt;
    let Ok(c) = std::ffi::CString::new(folder.as_os_str().as_bytes()) else {
        return false;
    };
    // SAFETY: `c` is a NUL-terminated path that lives across the call.
    unsafe { libc::access(c.as_ptr(), libc::W_OK) == 0 }
}

#[cfg(not(unix))]
fn writable(folder: &Path) -> bool {
    std::fs::metadata(folder).is_ok_and(|m| !m.permissions().readonly())
}

/// [`check_output_path`] for every output option given; prints the first
/// problem and returns `false`.
pub(crate) fn outputs_writable(outputs: &[(&str, Option<&PathBuf>)]) -> bool {
    for (flag, path) in outputs {
        if let Some(path) = path
            && let Err(e) = check_output_path(flag, path)
        {
            eprintln!("error: {e}");
            return false;
        }
    }
    true
}

/// Loads a scenario named on the command line, inside `root` (`--root`;
/// default: the file's folder).
pub(crate) fn load(file: &Path, root: Option<&Path>) -> Result<crate::Scenario, LoadFailure> {
    crate::scenario::load_with(file, root, &|_| None)
}

pub(crate) fn print_failure(f: &LoadFailure) {
    eprint!("{}", render_diags(&f.diags, &f.sources));
    let errors = f.diags.iter().filter(|d| d.is_error()).count();
    eprintln!("{errors} error(s): the scenario was not run");
}

fn cmd_run(args: &RunArgs) -> i32 {
    if !args.usable() {
        return EXIT_BAD_INPUT;
    }
    let mut code = EXIT_OK;
    let mut viewer_warned = false;
    let target = args.viewer_target();
    for file in &args.files {
        let (c, _) = run_file(file, args, target.as_ref(), &mut viewer_warned);
        code = code.max(c);
    }
    code
}

/// `scen run` on one file: load, plan, check, print, write the outputs,
/// stream to `target`. Returns the exit code and the files the scenario
/// read (the main file first; `watch` watches them).
fn run_file(
    file: &Path,
    args: &RunArgs,
    target: Option<&ViewerTarget>,
    viewer_warned: &mut bool,
) -> (i32, Vec<PathBuf>) {
    let mut read = vec![file.to_path_buf()];
    let loaded = crate::scenario::load_member(
        file,
        args.root.as_deref(),
        &|_| None,
        args.sample_choice(),
        &args.set,
    );
    let scenario = match loaded {
        Ok(s) => s,
        Err(f) => {
            read.extend(f.sources.files.iter().map(|s| s.path.clone()));
            print_failure(&f);
            return (EXIT_BAD_INPUT, read);
        }
    };
    read.extend(scenario.sources.files.iter().map(|s| s.path.clone()));
    if !clobber::outputs_are_not_inputs(
        &args.output_files(Some(&scenario)),
        &clobber::scenario_inputs(&scenario.sources),
    ) {
        return (EXIT_BAD_INPUT, read);
    }
    if let Some(unknown) = args
        .plans
        .iter()
        .find(|p| !scenario.plans.iter().any(|q| &q.name == *p))
    {
        let names: Vec<&str> = scenario.plans.iter().map(|p| p.name.as_str()).collect();
        eprintln!(
            "error: `{}` has no plan `{unknown}` (plans: {})",
            file.display(),
            names.join(", ")
        );
        return (EXIT_BAD_INPUT, read);
    }
    let spinner = progress(args, file);
    // Layers only for a sink that draws them (a picture, the viewer).
    let draw = args.outputs.draws() || target.is_some();
    let report = run_scenario_drawing(scenario, &args.plans, draw);
    if let Some(p) = spinner {
        p.finish_and_clear();
    }
    if args.json {
        let doc = report::json::to_json(&report);
        outln!("{}", serde_json::to_string(&doc).unwrap_or_default());
    } else {
        print_text(&report, args);
    }
    let mut code = EXIT_OK;
    if !args.outputs.write(report::sink::Product::Run(&report)) {
        code = code.max(EXIT_BAD_INPUT);
    }
    if let Some(target) = target
        && let Err(e) = viz::stream(&report, target)
    {
        if let ViewerTarget::Save(_) = target {
            eprintln!("error: {e}");
            code = code.max(EXIT_BAD_INPUT);
        } else if !*viewer_warned {
            eprintln!("warning: viewer: {e}; the report above is complete");
            *viewer_warned = true;
        }
    }
    if report.failed() > 0 || report.plans.iter().any(|p| p.validation.is_some()) {
        code = code.max(EXIT_CHECK_FAILED);
    }
    (code, read)
}

fn progress(args: &RunArgs, file: &Path) -> Option<indicatif::ProgressBar> {
    if args.quiet || args.json || !std::io::stderr().is_terminal() {
        return None;
    }
    let p = indicatif::ProgressBar::new_spinner();
    p.set_message(format!("planning {}", file.display()));
    p.enable_steady_tick(std::time::Duration::from_millis(120));
    Some(p)
}

fn print_text(report: &RunReport, args: &RunArgs) {
    print_report(report, args.quiet, || {
        report::text::render(report, args.verbose)
    });
}

/// Prints `full` (the report, rendered), or with `quiet` only the failed
/// checks and the summary; then a diagnostic per failed check on stderr.
pub(crate) fn print_report(report: &RunReport, quiet: bool, full: impl FnOnce() -> String) {
    if quiet {
        for c in report.checks.iter().filter(|c| !c.passed) {
            outln!("{}", report::text::check_line(report, c));
        }
        if let Some(line) = report::text::skipped_line(report) {
            outln!("{line}");
        }
        outln!("{} passed, {} failed", report.passed(), report.failed());
    } else {
        out!("{}", full());
    }
    let failed: Vec<Diag> = report
        .checks
        .iter()
        .filter(|c| !c.passed)
        .map(|c| report::text::failed_check_diag(report, c))
        .collect();
    if !failed.is_empty() {
        if let Err(e) = std::io::stdout().flush() {
            remember_stdout_error(e);
        }
        eprint!("{}", render_diags(&failed, &report.scenario.sources));
    }
}

fn cmd_check(args: &CheckArgs) -> i32 {
    let mut code = EXIT_OK;
    for file in &args.files {
        match load(file, args.root.as_deref()) {
            Ok(s) => {
                if args.format == Format::Human {
                    outln!(
                        "{}: ok ({} robot(s), {} plan(s), {} check(s))",
                        file.display(),
                        s.robots.len(),
                        s.plans.len(),
                        s.checks.len()
                    );
                }
            }
            Err(f) => {
                code = EXIT_BAD_INPUT;
                match args.format {
                    Format::Human => print_failure(&f),
                    Format::Json => {
                        for d in &f.diags {
                            let mut j = d.to_json(&f.sources);
                            if j.get("file").is_none() {
                                j["file"] = serde_json::json!(file.display().to_string());
                            }
                            outln!("{}", serde_json::to_string(&j).unwrap_or_default());
                        }
                    }
                }
            }
        }
    }
    code
}

/// Collects `*.scen` files under `path`, sorted (hidden folders skipped);
/// files whose name starts with `_` are include-only fragments, skipped
/// unless `fragments`. MovingAI scenario files (`.scen` too, but opening
/// with `version`: a team's agents, SPEC 2.10) are data, never scenarios.
pub(crate) fn collect_scen(path: &Path, fragments: bool, out: &mut Vec<PathBuf>) {
    if path.is_dir() {
        let Ok(entries) = std::fs::read_dir(path) else {
            return;
        };
        let mut entries: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        entries.sort();
        for e in entries {
            let hidden = e
                .file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with('.'));
            if e.is_dir() {
                // `.git` and other hidden folders hold no scenarios.
                if !hidden {
                    collect_scen(&e, fragments, out);
                }
            } else if e.extension().is_some_and(|x| x == "scen")
                && (fragments
                    || !e
                        .file_name()
                        .is_some_and(|n| n.to_string_lossy().starts_with('_')))
                && !crate::scenario::movingai::is_scen_file(&e)
            {
                out.push(e);
            }
        }
    } else {
        out.push(path.to_path_buf());
    }
}

/// The diagnostic codes a test file declares it must get, one per
/// `# expect-error: CODE` line among the comment lines that open it (a test
/// of the diagnostics: it passes when loading it reports every code). The
/// text is the loader's: the main file is the first source it read.
fn expected_errors(sources: &SourceMap) -> Vec<String> {
    let Some(main) = sources.files.first() else {
        return Vec::new();
    };
    main.text
        .lines()
        .map_while(|l| l.trim_start().strip_prefix('#'))
        .filter_map(|h| h.trim_start().strip_prefix("expect-error:"))
        .map(|code| code.trim().to_string())
        .filter(|code| !code.is_empty())
        .collect()
}

fn cmd_test(args: &TestArgs) -> i32 {
    let roots = if args.paths.is_empty() {
        vec![PathBuf::from(".")]
    } else {
        args.paths.clone()
    };
    let shard = args.shard;
    let outputs = [("--junit", args.junit.as_ref())];
    if !outputs_writable(&outputs) {
        return EXIT_BAD_INPUT;
    }
    // Each file with its root: `--root`, or the folder named on the command
    // line (for a file, its folder), so that the scenarios of a suite may
    // share what lies anywhere in it (SPEC 2.2: the root is what was named).
    let mut files: Vec<(PathBuf, PathBuf)> = Vec::new();
    for r in &roots {
        if !r.exists() {
            eprintln!("error: `{}` does not exist", r.display());
            return EXIT_BAD_INPUT;
        }
        let root = match &args.root {
            Some(root) => root.clone(),
            None if r.is_dir() => r.clone(),
            None => r
                .parent()
                .filter(|p| !p.as_os_str().is_empty())
                .unwrap_or(Path::new("."))
                .to_path_buf(),
        };
        let mut found = Vec::new();
        collect_scen(r, false, &mut found);
        files.extend(found.into_iter().map(|f| (f, root.clone())));
    }
    if files.is_empty() {
        eprintln!(
            "error: no *.scen files under {}",
            roots
                .iter()
                .map(|r| r.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
        return EXIT_BAD_INPUT;
    }
    // `--shard K/N`: the files whose index in the sorted list is K − 1
    // modulo N, so N machines test every file exactly once.
    if let Some(s) = shard {
        files = files
            .into_iter()
            .enumerate()
            .filter(|(i, _)| s.takes(*i as u64))
            .map(|(_, f)| f)
            .collect();
    }
    // An existing `--junit` file may be one the suite reads: every file is
    // read (not planned) first to know.
    if clobber::any_output_exists(&outputs) {
        let read: Vec<crate::scenario::loader::Parsed> = files
            .iter()
            .map(|(f, root)| {
                crate::scenario::loader::parse_scenario(f, Some(root.as_path()), &|_| None)
            })
            .collect();
        let inputs: Vec<clobber::Input<'_>> = read
            .iter()
            .flat_map(|p| clobber::scenario_inputs(&p.sources))
            .collect();
        if !clobber::outputs_are_not_inputs(&outputs, &inputs) {
            return EXIT_BAD_INPUT;
        }
    }
    let results: Vec<report::junit::FileResult> = files
        .par_iter()
        .map(|(f, root)| test_file(f, Some(root)))
        .collect();
    let (mut passed, mut failed) = (0, 0);
    for r in &results {
        outln!("{}", r.line);
        if !r.diagnostics.is_empty() {
            eprint!("{}", r.diagnostics);
        }
        passed += r.cases.iter().filter(|c| c.failure.is_none()).count();
        failed += r.cases.iter().filter(|c| c.failure.is_some()).count();
    }
    outln!("{passed} passed, {failed} failed");
    if let Some(junit) = &args.junit
        && let Err(e) = std::fs::write(junit, report::junit::to_junit(&results))
    {
        eprintln!("error: cannot write `{}`: {e}", junit.display());
        return EXIT_BAD_INPUT;
    }
    if failed > 0 {
        EXIT_CHECK_FAILED
    } else {
        EXIT_OK
    }
}

/// One file of `scen test`: its line, its diagnostics, its test cases.
fn test_file(f: &Path, root: Option<&Path>) -> report::junit::FileResult {
    use report::junit::{Case, FileResult};
    let name = f.display().to_string();
    let loaded = load(f, root);
    let expected = expected_errors(match &loaded {
        Ok(s) => &s.sources,
        Err(fail) => &fail.sources,
    });
    let case = |name: String, line: usize, failure: Option<String>| Case {
        name,
        line,
        failure,
    };
    match (loaded, expected) {
        (Err(fail), expected) if !expected.is_empty() => {
            let missing: Vec<&String> = expected
                .iter()
                .filter(|code| !fail.diags.iter().any(|d| d.code == code.as_str()))
                .collect();
            let codes = expected.join(", ");
            if missing.is_empty() {
                FileResult {
                    file: name.clone(),
                    line: format!("ok      {name}  (expected errors reported)"),
                    diagnostics: String::new(),
                    cases: vec![case(format!("reports {codes}"), 1, None)],
                }
            } else {
                let list = missing
                    .iter()
                    .map(|c| format!("`{c}`"))
                    .collect::<Vec<_>>()
                    .join(", ");
                let text = render_diags(&fail.diags, &fail.sources);
                FileResult {
                    file: name.clone(),
                    line: format!("FAILED  {name}  (expected error {list} not reported)"),
                    cases: vec![case(
                        format!("reports {codes}"),
                        1,
                        Some(format!("expected error {list} not reported\n{text}")),
                    )],
                    diagnostics: text,
                }
            }
        }
        (Err(fail), _) => {
            let text = render_diags(&fail.diags, &fail.sources);
            FileResult {
                file: name.clone(),
                line: format!("FAILED  {name}  (does not load)"),
                cases: vec![case("loads".into(), 1, Some(text.clone()))],
                diagnostics: text,
            }
        }
        (Ok(_), expected) if !expected.is_empty() => FileResult {
            file: name.clone(),
            line: format!("FAILED  {name}  (loads, but `# expect-error:` expects it not to)"),
            diagnostics: String::new(),
            cases: vec![case(
                format!("reports {}", expected.join(", ")),
                1,
                Some("the file loads, but `# expect-error:` expects it not to".into()),
            )],
        },
        (Ok(s), _) => {
            // The plans, their checks, and the benches with theirs.
            let report = if s.benches.is_empty() {
                run_scenario_drawing(s, &[], false)
            } else {
                let ids = crate::bench::run_ids(&s, &[]);
                match crate::bench::Worlds::draw(&s, &[]) {
                    Ok(worlds) => {
                        let runs = crate::bench::run_all(&s, &worlds, &ids, &|| {});
                        crate::bench::report(s, runs)
                    }
                    Err(fail) => {
                        let text = render_diags(&fail.diags, &fail.sources);
                        return FileResult {
                            file: name.clone(),
                            line: format!("FAILED  {name}  (a world of its bench does not load)"),
                            cases: vec![case("loads".into(), 1, Some(text.clone()))],
                            diagnostics: text,
                        };
                    }
                }
            };
            let mut cases: Vec<Case> = report
                .checks
                .iter()
                .map(|c| {
                    let check = &report.scenario.checks[c.check];
                    let failure = (!c.passed).then(|| {
                        format!(
                            "{}\n{}",
                            report::text::check_line(&report, c),
                            render_diags(
                                &[report::text::failed_check_diag(&report, c)],
                                &report.scenario.sources
                            )
                        )
                    });
                    case(
                        format!("line {}: {}", check.line, check.text),
                        check.line,
                        failure,
                    )
                })
                .collect();
            for p in report.plans.iter().filter(|p| p.validation.is_some()) {
                let plan = report.plan(p);
                cases.push(case(
                    format!("plan {} passes the validator", plan.name),
                    report.scenario.sources.line_of(plan.span),
                    Some(format!(
                        "plan `{}` returned a path that fails the validator",
                        plan.name
                    )),
                ));
            }
            let failed = cases.iter().filter(|c| c.failure.is_some()).count();
            let diags: Vec<Diag> = report
                .checks
                .iter()
                .filter(|c| !c.passed)
                .map(|c| report::text::failed_check_diag(&report, c))
                .collect();
            let mut text = render_diags(&diags, &report.scenario.sources);
            for p in report.plans.iter().filter(|p| p.validation.is_some()) {
                text.push_str(&format!(
                    "plan `{}` returned a path that fails the validator\n",
                    report.plan(p).name
                ));
            }
            let line = if failed == 0 {
                format!("ok      {name}  ({} checks)", cases.len())
            } else {
                format!(
                    "FAILED  {name}  ({failed} of {} checks failed)",
                    cases.len()
                )
            };
            FileResult {
                file: name,
                line,
                diagnostics: text,
                cases,
            }
        }
    }
}
