//! The planner contract, below both the analyzer and the planners: what a
//! planner declares ([`Planner`]: parameter and metric [`schema`]s, the
//! robots it takes, its limits), what it is given ([`PlanArgs`] to build
//! its typed [`Settings`], then a [`Task`]), and what it returns
//! ([`PlanOutcome`]: the path, metrics, notes and drawable [`layers`]).
//!
//! The analyzer (`scenario`) reads planners through this contract and the
//! registry's list; the planners import only this, the geometry and the
//! random numbers; the runner and the sinks read the outcomes. Nothing here
//! knows a particular planner.

mod args;
pub mod layers;
mod outcome;
mod params;
mod planner;
mod referee;
pub mod schema;

pub use args::PlanArgs;
pub use layers::Layer;
pub use outcome::{MeasuredMotion, MetricValue, Metrics, PlanOutcome};
pub use params::{Agent, DEFAULT_CELL_CAP, Limits, Param, ParamValue, Params, Robot};
pub use planner::{Planner, Settings, Task};
pub use referee::{Referee, ValidatorReferee};
