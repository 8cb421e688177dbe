//! `scen`: a declarative scenario language for 2D robot motion planning.
//!
//! The pipeline: source text ─parse→ [`syntax::ast`] ─analyze→
//! [`Scenario`] ─plan→ [`RunReport`] ─check→ report sinks ([`report`]
//! for text, JSON, CSV, SVG and PNG; the Rerun viewer behind the `viewer`
//! feature).
//!
//! # The library
//! - [`load`] / [`scenario::load_with`]: read, parse and analyse a
//!   scenario file (every diagnostic at once, with spans into its sources;
//!   [`diagnostics::render_diags`] prints them as `scen check` does);
//!   [`scenario::load_sample`]: one sample of a family of scenarios
//!   (`param`, `scatter`, `require`), with what it drew in
//!   [`Scenario::family`].
//! - [`run_scenario`] / [`run_scenario_drawing`]: run its plans, validate
//!   every path, evaluate the checks.
//! - [`bench`]: the runs of its `bench` statements; [`report`]: the
//!   documents made of a run (JSON, tables, pictures).
//! - [`format::format_text`]: the canonical layout.
//! - [`planners::registry::PLANNERS`]: every planner, through the
//!   [`contract`] (schemas, settings, tasks, outcomes).
//! - [`main`]: the `scen` command line itself.
//!
//! The lower crates of the workspace are re-exported whole: `scen-geometry`
//! ([`geometry`], [`rng`]), `scen-planners` ([`contract`], [`planners`],
//! [`diagnostics`]) and `scen-language` ([`syntax`], [`scenario`],
//! [`format`]); the command line, the language server, file reading, the
//! viewer sink and the driving simulator are private to the crate.

pub mod bench;
use scen_language::checks;
mod cli;
pub use scen_planners::contract;
pub use scen_planners::diagnostics;
mod drive;
mod falsify;
pub use scen_geometry as geometry;
use scen_language::files;
pub use scen_language::format;
mod import;
mod lsp;
#[cfg(test)]
mod planner_tests;
pub use scen_planners::planners;
pub use scen_planners::word_enum;
pub mod report;
pub use scen_geometry::rng;
pub mod run;
pub use scen_language::scenario;
mod stats;
pub use scen_language::syntax;
mod viz;

pub use diagnostics::{Diag, SourceMap, Span};
pub use run::{RunReport, run_scenario, run_scenario_drawing};
pub use scenario::{Scenario, load};

/// `scen bench merge PART.jsonl...` as a library call: the report of the
/// whole bench from the parts of its shards (`bench::prepare` with a
/// shard, then `report::bench::part_text`), checked as the command checks
/// them (every part once, from one split of one unchanged scenario, every
/// run the scenario gives); the error is the command's message.
pub fn merge_bench_parts(
    paths: &[std::path::PathBuf],
    root: Option<&std::path::Path>,
) -> Result<RunReport, String> {
    cli::bench::merge(paths, root, &[])
}

/// The `scen` command line: reads the arguments, runs the command, and
/// returns the exit code (0 all checks passed, 1 a check failed, 2 bad
/// input or usage). The binary is this call.
pub fn main() -> i32 {
    cli::main()
}
