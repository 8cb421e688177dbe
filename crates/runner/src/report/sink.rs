//! The file outputs of `scen run` and `scen bench` (`--svg`, `--png`,
//! `--csv`, `--ompl-log`): one [`Sink`] each, defined in its own module
//! beside what it renders, listed once in [`super::sinks::SINKS`]. The command line
//! builds its options from the list, checks their paths before anything
//! runs, refuses an output that would replace an input, and writes each
//! one. A new output is its sink (in its file) and one line here.

use std::path::{Path, PathBuf};

use crate::run::RunReport;
use crate::scenario::Scenario;

/// A command that writes sinks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    Run,
    Bench,
}

/// What a sink writes from.
#[derive(Clone, Copy, Debug)]
pub enum Product<'a> {
    /// `scen run`'s report of one scenario.
    Run(&'a RunReport),
    /// `scen bench`'s report and the metrics of its table (`--metrics`).
    Bench(&'a RunReport, &'a [&'a str]),
}

/// One file output.
#[derive(Debug)]
pub struct Sink {
    /// The option, `--NAME`.
    pub option: &'static str,
    /// What its value is, for `--help` (`OUT.svg`, `DIR`).
    pub value_name: &'static str,
    /// The commands that offer it, each with its help line.
    pub help: &'static [(Command, &'static str)],
    /// Whether the planners record their drawable layers for it (a
    /// picture).
    pub draws: bool,
    /// Whether the path names a folder the sink writes its files into
    /// (created when they are written; its parent must exist).
    pub folder: bool,
    /// Refuses a path before anything runs (e.g. a picture's extension).
    pub check: fn(&Path) -> Result<(), String>,
    /// The files it would write at `path` for a scenario (one, or a folder
    /// sink's several), for the check that no output replaces an input;
    /// `benches` are the benches `--bench` chose (empty: all).
    pub files: fn(&Path, &Scenario, &[String]) -> Vec<PathBuf>,
    /// An option of its own that tunes what it writes (`--gif-speed K`),
    /// given only with the sink's.
    pub tuning: Option<&'static Tuning>,
    /// Writes it, with its tuning's value (`None` for a sink without
    /// one); each failure as an error message.
    pub write: Write,
}

/// [`Sink::write`]: the product, the path, the tuning's value.
pub type Write = fn(Product<'_>, &Path, Option<f64>) -> Result<(), Vec<String>>;

/// A number that tunes a sink: its own option, next to the sink's.
#[derive(Debug)]
pub struct Tuning {
    /// The option, `--NAME`.
    pub option: &'static str,
    /// What its value is, for `--help` (`K`).
    pub value_name: &'static str,
    pub help: &'static str,
    /// Its value when the option is not given.
    pub default: f64,
    /// Refuses a value before anything runs.
    pub check: fn(f64) -> Result<(), String>,
}

impl Tuning {
    /// The option's name without its dashes (`gif-speed`).
    pub fn name(&self) -> &'static str {
        self.option.trim_start_matches('-')
    }
}

impl Sink {
    /// Its help line for `command`, when the command offers it.
    pub fn help_for(&self, command: Command) -> Option<&'static str> {
        self.help
            .iter()
            .find(|(c, _)| *c == command)
            .map(|(_, h)| *h)
    }

    /// The option's name without its dashes (`svg`).
    pub fn name(&self) -> &'static str {
        self.option.trim_start_matches('-')
    }
}

/// [`Sink::files`] of a sink that writes the one file it is given.
pub fn the_file(path: &Path, _: &Scenario, _: &[String]) -> Vec<PathBuf> {
    vec![path.to_path_buf()]
}

/// [`Sink::check`] of a sink that takes any path.
pub fn any_path(_: &Path) -> Result<(), String> {
    Ok(())
}

/// [`Sink::check`] of a sink whose file must end in `.EXT` (any case):
/// `option` writes `what`, and `hint` (empty, or ` (...)`) ends the
/// refusal.
pub fn needs_extension(
    path: &Path,
    option: &str,
    ext: &str,
    what: &str,
    hint: &str,
) -> Result<(), String> {
    if has_extension(path, ext) {
        Ok(())
    } else {
        Err(format!(
            "`{option} {}` writes {what}: give it a file ending in `.{ext}`{hint}",
            path.display()
        ))
    }
}

/// Whether `path` ends in `.EXT` (any case).
pub fn has_extension(path: &Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.to_string_lossy().eq_ignore_ascii_case(ext))
}

/// Writes `bytes` to `path`, the failure as an error message.
pub fn write_file(path: &Path, bytes: impl AsRef<[u8]>) -> Result<(), Vec<String>> {
    std::fs::write(path, bytes).map_err(|e| vec![format!("cannot write `{}`: {e}", path.display())])
}
