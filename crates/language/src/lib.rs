//! scen's language: source text → [`syntax::ast`] (the pest grammar in
//! `grammar/scen.pest`) → [`scenario::Scenario`] (analysis with every
//! diagnostic located, families of scenarios, `require`), the checks'
//! evaluation ([`checks`], one evaluator in [`eval`]) and the canonical
//! layout ([`format`]). Above the planners (it reads their registry to
//! know each planner's parameters) and below the runner: nothing here
//! plans, draws or prints.

pub mod checks;
pub mod eval;
pub mod files;
pub mod format;
pub mod scenario;
pub mod syntax;

pub use scen_geometry as geometry;
pub use scen_geometry::rng;
pub use scen_planners::{contract, diagnostics, planners, word_enum};

pub use diagnostics::{Diag, SourceMap, Span};
pub use scenario::{Scenario, load};
