//! `scen`: a declarative scenario language for 2D robot motion planning.
//!
//! The pipeline: source text ─parse→ [`syntax::ast`] ─analyze→
//! [`scenario::Scenario`] ─plan→ [`run::RunReport`] ─check→ report sinks
//! ([`report`] for text, JSON and SVG; [`viz`] for the Rerun viewer).

pub mod bench;
pub mod checks;
pub mod cli;
pub mod contract;
pub mod diagnostics;
pub mod drive;
pub mod files;
pub mod format;
pub mod geometry;
pub mod import;
pub mod lsp;
pub mod planners;
pub mod report;
pub mod rng;
pub mod run;
pub mod scenario;
pub mod syntax;
pub mod viz;

pub use diagnostics::{Diag, SourceMap, Span};
pub use run::{RunReport, run_scenario, run_scenario_drawing};
pub use scenario::{Scenario, load};
