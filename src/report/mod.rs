//! Report sinks: the text report, JSON (SPEC 5) and SVG.

pub mod bench;
pub mod json;
pub mod junit;
pub mod ompl;
pub mod plot;
pub mod svg;
pub mod text;
