//! The file outputs of a command, as options built from the sink registry
//! ([`crate::report::sinks::SINKS`]): `#[command(flatten)] outputs:
//! Outputs<RunSinks>` gives `scen run` every sink it offers, with no line
//! per sink here or in the command.

use std::marker::PhantomData;
use std::path::PathBuf;

use clap::{Arg, ArgMatches, Args, FromArgMatches};

use super::{check_output_folder, check_output_path};
use crate::report::sink::{Command, Product, Sink};
use crate::report::sinks::SINKS;
use crate::scenario::Scenario;

/// Which command's sinks an [`Outputs`] holds.
pub trait OfCommand {
    const COMMAND: Command;
}

#[derive(Debug)]
pub struct RunSinks;
impl OfCommand for RunSinks {
    const COMMAND: Command = Command::Run;
}

#[derive(Debug)]
pub struct BenchSinks;
impl OfCommand for BenchSinks {
    const COMMAND: Command = Command::Bench;
}

/// The sinks a command was given, each with its path, in the registry's
/// order; and the tunings given (`--gif-speed K`), by the sink they tune.
#[derive(Debug)]
pub struct Outputs<K> {
    pub given: Vec<(&'static Sink, PathBuf)>,
    tunings: Vec<(&'static Sink, f64)>,
    command: PhantomData<K>,
}

impl<K> Default for Outputs<K> {
    fn default() -> Self {
        Outputs {
            given: Vec::new(),
            tunings: Vec::new(),
            command: PhantomData,
        }
    }
}

fn offered<K: OfCommand>() -> impl Iterator<Item = (&'static Sink, &'static str)> {
    SINKS
        .iter()
        .filter_map(|s| s.help_for(K::COMMAND).map(|h| (*s, h)))
}

impl<K: OfCommand> FromArgMatches for Outputs<K> {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let mut outputs = Self::default();
        outputs.update_from_arg_matches(matches)?;
        Ok(outputs)
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        for (sink, _) in offered::<K>() {
            if let Some(path) = matches.get_one::<PathBuf>(sink.name()) {
                self.given.retain(|(s, _)| !std::ptr::eq(*s, sink));
                self.given.push((sink, path.clone()));
            }
        }
        let order = |s: &Sink| SINKS.iter().position(|t| std::ptr::eq(*t, s));
        self.given.sort_by_key(|(s, _)| order(s));
        for (sink, tuning) in offered::<K>().filter_map(|(s, _)| Some((s, s.tuning?))) {
            if let Some(&value) = matches.get_one::<f64>(tuning.name()) {
                self.tunings.retain(|(s, _)| !std::ptr::eq(*s, sink));
                self.tunings.push((sink, value));
            }
        }
        Ok(())
    }
}

impl<K: OfCommand> Args for Outputs<K> {
    fn augment_args(cmd: clap::Command) -> clap::Command {
        offered::<K>().fold(cmd, |cmd, (sink, help)| {
            let cmd = cmd.arg(
                Arg::new(sink.name())
                    .long(sink.name())
                    .value_name(sink.value_name)
                    .value_parser(clap::value_parser!(PathBuf))
                    .help(help),
            );
            match sink.tuning {
                Some(t) => cmd.arg(
                    Arg::new(t.name())
                        .long(t.name())
                        .value_name(t.value_name)
                        .value_parser(clap::value_parser!(f64))
                        .allow_negative_numbers(true)
                        .help(t.help),
                ),
                None => cmd,
            }
        })
    }

    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_args(cmd)
    }
}

impl<K> Outputs<K> {
    /// Whether a given sink draws (the planners then record their layers).
    pub fn draws(&self) -> bool {
        self.given.iter().any(|(s, _)| s.draws)
    }

    /// The options given that write one file per run, named by the user
    /// (`--svg`, `--csv`): they take one scenario file. A folder sink names
    /// its files after the scenario.
    pub fn one_per_scenario(&self) -> Vec<&'static str> {
        self.given
            .iter()
            .filter(|(s, _)| !s.folder)
            .map(|(s, _)| s.option)
            .collect()
    }

    /// Checked before anything runs: each sink's own rule for its path,
    /// and that it can be written (a folder sink: its folder, or the
    /// folder it would be created in). Prints the first problem.
    pub fn usable(&self) -> bool {
        for &(sink, value) in &self.tunings {
            let Some(tuning) = sink.tuning else {
                continue;
            };
            let checked = if self.given.iter().any(|(s, _)| std::ptr::eq(*s, sink)) {
                (tuning.check)(value)
            } else {
                Err(format!(
                    "`{}` tunes `{}`, which was not given",
                    tuning.option, sink.option
                ))
            };
            if let Err(e) = checked {
                eprintln!("error: {e}");
                return false;
            }
        }
        for (sink, path) in &self.given {
            let checked = (sink.check)(path).and_then(|()| {
                if sink.folder && path.is_dir() {
                    check_output_folder(sink.option, path)
                } else {
                    check_output_path(sink.option, path)
                }
            });
            if let Err(e) = checked {
                eprintln!("error: {e}");
                return false;
            }
        }
        true
    }

    /// Every file the sinks would write for `scenario`, each with its
    /// option (a folder sink: each of its files; before a scenario is
    /// loaded, the paths as given); `benches` are the benches chosen
    /// (empty: all).
    pub fn files(
        &self,
        scenario: Option<&Scenario>,
        benches: &[String],
    ) -> Vec<(&'static str, PathBuf)> {
        self.given
            .iter()
            .flat_map(|(sink, path)| {
                let files = match scenario {
                    Some(s) => (sink.files)(path, s, benches),
                    None => vec![path.clone()],
                };
                files.into_iter().map(|f| (sink.option, f))
            })
            .collect()
    }

    /// Writes every sink given; prints each failure. Whether all were
    /// written.
    pub fn write(&self, product: Product<'_>) -> bool {
        let mut ok = true;
        for (sink, path) in &self.given {
            let tuning = sink.tuning.map(|t| {
                self.tunings
                    .iter()
                    .find(|(tuned, _)| std::ptr::eq(*tuned, *sink))
                    .map_or(t.default, |&(_, v)| v)
            });
            if let Err(errors) = (sink.write)(product, path, tuning) {
                for e in errors {
                    eprintln!("error: {e}");
                }
                ok = false;
            }
        }
        ok
    }
}
