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
//! [`diagnostics`]), `scen-language` ([`syntax`], [`scenario`],
//! [`format`]) and `scen-runner` ([`run`], [`bench`], [`report`]); the
//! command line, the language server, falsification and the viewer sink
//! are private to the crate.

use scen_language::checks;
pub use scen_runner::bench;
mod cli;
pub use scen_planners::contract;
pub use scen_planners::diagnostics;
mod falsify;
pub use scen_geometry as geometry;
use scen_language::files;
pub use scen_language::format;
mod import;
mod lsp;
#[cfg(test)]
mod planner_tests;
pub use scen_geometry::rng;
pub use scen_language::scenario;
pub use scen_language::syntax;
pub use scen_planners::planners;
pub use scen_planners::word_enum;
use scen_runner::parts;
pub use scen_runner::report;
pub use scen_runner::run;
mod viz;

pub use diagnostics::{Diag, SourceMap, Span};
pub use run::{RunReport, run_scenario, run_scenario_drawing};
pub use scen_runner::merge_bench_parts;
pub use scenario::{Scenario, load};

/// The `scen` command line: reads the arguments, runs the command, and
/// returns the exit code (0 all checks passed, 1 a check failed, 2 bad
/// input or usage). The binary is this call.
pub fn main() -> i32 {
    cli::main()
}
