//! `scen falsify FILE` (SPEC §4): search, shrink, write, report.

use std::path::{Path, PathBuf};

use clap::Args;

use super::{EXIT_BAD_INPUT, EXIT_CHECK_FAILED, EXIT_OK, outln, outputs_writable, print_failure};
use crate::contract::schema::Word;
use crate::falsify::{self, Falsified, Options, Search};
use crate::scenario::loader::{LoadFailure, parse_scenario};

#[derive(Args, Debug)]
pub struct FalsifyArgs {
    /// The family of scenarios to search.
    pub file: PathBuf,
    /// The most samples to try.
    #[arg(long, value_name = "N", default_value_t = 1000, value_parser = clap::value_parser!(u64).range(1..=10_000_000))]
    pub budget: u64,
    /// How samples are proposed: `auto` (a low-discrepancy cover mixed with
    /// a cross-entropy search on the checks' margins), `uniform` (samples
    /// 0, 1, … of the family), `halton`, `cross_entropy`.
    #[arg(long, value_name = "HOW", default_value = "auto", value_parser = search_word)]
    pub search: String,
    /// The search's seed (and, for `uniform`, the family seed).
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u64,
    /// Where to write the shrunk failing scenario (default: FILE's name
    /// with `_fail` added, beside it).
    #[arg(long, value_name = "FAIL.scen")]
    pub out: Option<PathBuf>,
    /// Print one JSON document instead of the report.
    #[arg(long)]
    pub json: bool,
    /// The folder the scenario may read files from.
    #[arg(long, value_name = "DIR")]
    pub root: Option<PathBuf>,
}

fn search_word(text: &str) -> Result<String, String> {
    if Search::WORDS.contains(&text) {
        Ok(text.to_string())
    } else {
        Err(format!("one of {}", Search::WORDS.join(", ")))
    }
}

/// `FILE_fail.scen` beside FILE.
fn default_out(file: &Path) -> PathBuf {
    let stem = file
        .file_stem()
        .map_or("scenario".into(), |s| s.to_string_lossy().into_owned());
    file.with_file_name(format!("{stem}_fail.scen"))
}

pub(super) fn cmd_falsify(args: &FalsifyArgs) -> i32 {
    let out = args.out.clone().unwrap_or_else(|| default_out(&args.file));
    if !outputs_writable(&[("--out", Some(&out))]) {
        return EXIT_BAD_INPUT;
    }
    let search = Search::WORDS
        .iter()
        .position(|w| *w == args.search)
        .and_then(<Search as Word>::from_index)
        .unwrap_or(Search::Auto);
    let parsed = parse_scenario(&args.file, args.root.as_deref(), &|_| None);
    if parsed.diags.iter().any(crate::diagnostics::Diag::is_error) {
        print_failure(&LoadFailure {
            sources: parsed.sources,
            diags: parsed.diags,
        });
        return EXIT_BAD_INPUT;
    }
    let source =
        match falsify::Source::new(&args.file, parsed.statements, parsed.sources, parsed.maps) {
            Ok(s) => s,
            Err((sources, diags)) => {
                print_failure(&LoadFailure { sources, diags });
                return EXIT_BAD_INPUT;
            }
        };
    let opts = Options {
        budget: args.budget,
        search,
        seed: args.seed,
    };
    let result = match falsify::falsify(&source, opts) {
        Ok(r) => r,
        Err(diags) => {
            print_failure(&LoadFailure {
                sources: source.sources.clone(),
                diags,
            });
            return EXIT_BAD_INPUT;
        }
    };
    if let Some(f) = &result.failure
        && let Err(e) = std::fs::write(&out, &f.text)
    {
        eprintln!("error: cannot write `{}`: {e}", out.display());
        return EXIT_BAD_INPUT;
    }
    if args.json {
        outln!(
            "{}",
            serde_json::to_string(&json(&args.file, &result, &out)).unwrap_or_default()
        );
    } else {
        print_text(&args.file, &result, &out);
    }
    if result.failure.is_some() {
        EXIT_CHECK_FAILED
    } else {
        EXIT_OK
    }
}

fn params_text(params: &[(String, f64)]) -> String {
    params
        .iter()
        .map(|(n, x)| format!("{n} = {}", crate::checks::format_num(*x)))
        .collect::<Vec<_>>()
        .join(", ")
}

fn print_text(file: &Path, r: &Falsified, out: &Path) {
    outln!(
        "{}: {} sample(s) tried ({} search{})",
        file.display(),
        r.tried,
        r.search.word(),
        if r.rejected > 0 {
            format!(
                ", {} rejected by a `require` or a start or goal",
                r.rejected
            )
        } else {
            String::new()
        }
    );
    match &r.failure {
        Some(f) => {
            outln!("FAIL  sample {}: {}", f.sample, params_text(&f.params));
            outln!(
                "      line {}: expect {}   (margin {})",
                f.line,
                f.check,
                crate::checks::format_num(f.margin)
            );
            outln!(
                "      shrunk to {} of {} obstacle(s) in {} run(s), written to {}",
                f.obstacles.1,
                f.obstacles.0,
                f.shrink_runs,
                out.display()
            );
            outln!("      `scen test {}` reports it as failing", out.display());
        }
        None => match &r.smallest {
            Some((m, k, params)) => outln!(
                "no failure: the smallest margin was {} (sample {k}: {})",
                crate::checks::format_num(*m),
                params_text(params)
            ),
            None => outln!("no failure: every sample was rejected"),
        },
    }
}

fn json(file: &Path, r: &Falsified, out: &Path) -> serde_json::Value {
    let params = |ps: &[(String, f64)]| -> serde_json::Map<String, serde_json::Value> {
        ps.iter()
            .map(|(n, x)| (n.clone(), crate::report::json::float_json(*x)))
            .collect()
    };
    let mut o = serde_json::Map::new();
    o.insert("file".into(), file.display().to_string().into());
    o.insert("search".into(), r.search.word().into());
    o.insert("samples_tried".into(), r.tried.into());
    o.insert("rejected".into(), r.rejected.into());
    o.insert("found".into(), r.failure.is_some().into());
    match &r.failure {
        Some(f) => {
            o.insert("sample".into(), f.sample.into());
            o.insert("params".into(), params(&f.params).into());
            o.insert("check".into(), f.check.clone().into());
            o.insert("line".into(), f.line.into());
            o.insert("margin".into(), crate::report::json::float_json(f.margin));
            o.insert("obstacles".into(), f.obstacles.0.into());
            o.insert("obstacles_shrunk".into(), f.obstacles.1.into());
            o.insert("out".into(), out.display().to_string().into());
        }
        None => {
            if let Some((m, k, ps)) = &r.smallest {
                o.insert("margin".into(), crate::report::json::float_json(*m));
                o.insert("sample".into(), (*k).into());
                o.insert("params".into(), params(ps).into());
            }
        }
    }
    serde_json::Value::Object(o)
}
