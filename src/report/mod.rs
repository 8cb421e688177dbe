//! Report sinks: the text report, JSON (SPEC 5) and SVG.

pub mod json;
pub mod svg;
pub mod text;
