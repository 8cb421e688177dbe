//! Reports: the text report, JSON (SPEC 5), SVG, PNG and GIF, CSV, bench tables
//! and plots, OMPL logs, JUnit; the file outputs are sinks ([`sink`]).

pub mod bench;
pub mod compare;
pub mod csv;
pub mod gif;
pub mod json;
pub mod junit;
pub mod ompl;
pub mod plot;
pub mod png;
pub mod sink;
pub mod sinks;
pub mod svg;
pub mod text;

/// A number written for another program to read back (CSV, OMPL logs):
/// the shortest exact form, `inf`, `-inf` or `nan`.
pub(crate) fn exact_number(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        format!("{x}")
    }
}
