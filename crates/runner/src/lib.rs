//! `scen-runner`: runs a loaded scenario and makes its documents.
//!
//! - [`run`]: every plan of a scenario run, its path validated by the
//!   referee (SPEC 3.0), its checks evaluated ([`run_scenario`]); a path
//!   made elsewhere judged alike ([`run::validate_user_path`]).
//! - [`bench`]: the runs of `bench` statements, their tables ([`stats`])
//!   and the merge of sharded parts ([`merge`], [`parts`]).
//! - [`report`]: the documents made of a run — text, JSON (SPEC 5), CSV,
//!   SVG, PNG, GIF, bench tables and plots, OMPL logs, JUnit — with the
//!   file outputs as sinks; [`palette`]: the colours and outlines every
//!   picture shares.
//!
//! The `scen` command line and the Python module are built on it; it has
//! neither of them, nor the Rerun SDK. The lower crates are re-exported as
//! `scen` re-exports them, so the same paths work from either.

pub mod bench;
pub mod drive;
pub mod merge;
pub mod palette;
pub mod parts;
pub mod report;
pub mod run;
pub mod stats;

pub use scen_geometry as geometry;
pub use scen_geometry::rng;
pub use scen_language::{checks, files, format, scenario, syntax};
pub use scen_planners::{contract, diagnostics, planners, word_enum};

pub use diagnostics::{Diag, SourceMap, Span};
pub use run::{RunReport, run_scenario, run_scenario_drawing};
pub use scenario::{Scenario, load};

/// `scen bench merge PART.jsonl...` as a library call (see [`merge::merge`]).
pub fn merge_bench_parts(
    paths: &[std::path::PathBuf],
    root: Option<&std::path::Path>,
) -> Result<RunReport, String> {
    merge::merge(paths, root, &[])
}
