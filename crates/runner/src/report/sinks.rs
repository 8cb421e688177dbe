//! The registry of file outputs: one line per [`Sink`] (each defined beside
//! what it renders). Its own module, so that the sinks import their type
//! from [`super::sink`] and nothing imports the list back.

use super::sink::Sink;

/// Every file output, in the order `--help` lists them.
pub static SINKS: &[&Sink] = &[
    &super::svg::SINK,
    &super::png::SINK,
    &super::gif::SINK,
    &super::csv::SINK,
    &super::ompl::SINK,
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sinks_have_distinct_options_and_are_offered_somewhere() {
        let mut seen = std::collections::HashSet::new();
        for s in SINKS {
            assert!(s.option.starts_with("--"), "{}", s.option);
            assert!(seen.insert(s.option), "{} twice", s.option);
            assert!(!s.help.is_empty(), "{} is offered by no command", s.option);
        }
    }
}
