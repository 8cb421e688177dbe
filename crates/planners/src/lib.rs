//! scen's planners and their contract: the parameter and metric schemas,
//! typed arguments, limits, `Planner`/`Task`/`Settings`, outcomes and
//! drawable layers; the registry of planners, the search core, the
//! lattices and every planner; and the diagnostics' types they report
//! with. Below the language: it knows nothing of scenario text, and its
//! tests build worlds with fixtures (`scen_geometry::fixtures`).

pub mod contract;
pub mod diagnostics;
pub mod planners;

pub use scen_geometry as geometry;
pub use scen_geometry::rng;
