//! `scen falsify FILE` (SPEC §4): search, shrink, write, report; and its
//! sharded form, `--shard K/N --out PART.jsonl` then `scen falsify merge`.

use std::path::{Path, PathBuf};

use clap::Args;
use serde_json::{Value, json};

use super::clobber::{Input, outputs_are_not_inputs, scenario_inputs};
use super::{EXIT_BAD_INPUT, EXIT_CHECK_FAILED, EXIT_OK, outln, outputs_writable, print_failure};
use crate::bench::Shard;
use crate::contract::schema::Word;
use crate::falsify::{self, Failure, Falsified, Options, Search};
use crate::parts;
use crate::scenario::loader::{LoadFailure, parse_scenario};

#[derive(Args, Debug)]
pub struct FalsifyArgs {
    /// The family of scenarios to search; or `merge` and the parts written
    /// by `--shard K/N --out PART.jsonl`.
    #[arg(required = true, value_name = "FILE")]
    pub files: Vec<PathBuf>,
    /// The most samples to try.
    #[arg(long, value_name = "N", default_value_t = 1000, value_parser = clap::value_parser!(u64).range(1..=10_000_000))]
    pub budget: u64,
    /// How samples are proposed: `auto` (a low-discrepancy cover mixed with
    /// a cross-entropy search on the checks' margins), `uniform` (samples
    /// 0, 1, … of the family), `halton`, `cross_entropy`.
    #[arg(long, value_name = "HOW", default_value = "auto", value_parser = search_word)]
    pub search: Search,
    /// The search's seed (and, for `uniform`, the family seed).
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u64,
    /// Where to write the shrunk failing scenario (default: FILE's name
    /// with `_fail` added, beside it); with `--shard`, the part.
    #[arg(long, value_name = "FAIL.scen")]
    pub out: Option<PathBuf>,
    /// Run the K-th of N parts of the search (with `--out PART.jsonl`);
    /// `scen falsify merge` combines the parts.
    #[arg(long, value_name = "K/N", requires = "out", value_parser = crate::bench::Shard::parse)]
    pub shard: Option<crate::bench::Shard>,
    /// Print one JSON document instead of the report.
    #[arg(long)]
    pub json: bool,
    /// The folder the scenario may read files from.
    #[arg(long, value_name = "DIR")]
    pub root: Option<PathBuf>,
}

/// `--search HOW` (and a part's search) read as a [`Search`].
fn search_word(text: &str) -> Result<Search, String> {
    Search::WORDS
        .iter()
        .position(|w| *w == text)
        .and_then(<Search as Word>::from_index)
        .ok_or_else(|| format!("one of {}", Search::WORDS.join(", ")))
}

/// `FILE_fail.scen` beside FILE.
fn default_out(file: &Path) -> PathBuf {
    let stem = file
        .file_stem()
        .map_or("scenario".into(), |s| s.to_string_lossy().into_owned());
    file.with_file_name(format!("{stem}_fail.scen"))
}

pub(super) fn cmd_falsify(args: &FalsifyArgs) -> i32 {
    if args.files.first().is_some_and(|f| f == Path::new("merge")) {
        if args.shard.is_some() {
            eprintln!("error: `scen falsify merge` combines parts; it takes no `--shard`");
            return EXIT_BAD_INPUT;
        }
        return cmd_merge(args, &args.files[1..]);
    }
    let [file] = args.files.as_slice() else {
        eprintln!(
            "error: `scen falsify` searches one family at a time (or `scen falsify merge PART.jsonl...`)"
        );
        return EXIT_BAD_INPUT;
    };
    let shard = args.shard;
    if let Some(s) = shard
        && s.n > args.budget
    {
        eprintln!(
            "error: `--shard {}/{}`: a budget of {} sample(s) splits into at most {} part(s)",
            s.k, s.n, args.budget, args.budget
        );
        return EXIT_BAD_INPUT;
    }
    let out = args.out.clone().unwrap_or_else(|| default_out(file));
    if !outputs_writable(&[("--out", Some(&out))]) {
        return EXIT_BAD_INPUT;
    }
    let source = match load_source(file, args.root.as_deref()) {
        Ok(s) => s,
        Err(code) => return code,
    };
    if !outputs_are_not_inputs(&[("--out", Some(&out))], &scenario_inputs(&source.sources)) {
        return EXIT_BAD_INPUT;
    }
    let opts = Options {
        budget: args.budget,
        search: args.search,
        seed: args.seed,
        shard: shard.unwrap_or(Shard { k: 1, n: 1 }),
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
    if let Some(shard) = shard {
        return write_part(file, &source, &opts, shard, &result, &out);
    }
    finish(file, &result, &out, args.json)
}

/// The family read and checked (an error printed, exit 2, otherwise).
fn load_source(file: &Path, root: Option<&Path>) -> Result<falsify::Source, i32> {
    let parsed = parse_scenario(file, root, &|_| None);
    if parsed.diags.iter().any(crate::diagnostics::Diag::is_error) {
        print_failure(&LoadFailure {
            sources: parsed.sources,
            diags: parsed.diags,
        });
        return Err(EXIT_BAD_INPUT);
    }
    falsify::Source::new(file, parsed.statements, parsed.sources, parsed.maps).map_err(
        |(sources, diags)| {
            print_failure(&LoadFailure { sources, diags });
            EXIT_BAD_INPUT
        },
    )
}

/// Writes the failing scenario, prints the report; the exit code.
fn finish(file: &Path, result: &Falsified, out: &Path, as_json: bool) -> i32 {
    if let Some(f) = &result.failure
        && let Err(e) = std::fs::write(out, &f.text)
    {
        eprintln!("error: cannot write `{}`: {e}", out.display());
        return EXIT_BAD_INPUT;
    }
    if as_json {
        outln!(
            "{}",
            serde_json::to_string(&self::json(file, result, out)).unwrap_or_default()
        );
    } else {
        print_text(file, result, out);
    }
    if result.failure.is_some() {
        EXIT_CHECK_FAILED
    } else {
        EXIT_OK
    }
}

/// A margin in a part: a number, or the words of the infinities.
fn margin_json(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        json!(x.to_string())
    }
}

fn margin_of(v: &Value) -> Option<f64> {
    v.as_f64()
        .or_else(|| v.as_str().and_then(|s| s.parse::<f64>().ok()))
}

fn params_json(ps: &[(String, f64)]) -> Value {
    Value::Array(ps.iter().map(|(n, x)| json!([n, x])).collect())
}

fn params_of(v: &Value) -> Option<Vec<(String, f64)>> {
    v.as_array()?
        .iter()
        .map(|p| Some((p.get(0)?.as_str()?.to_string(), p.get(1)?.as_f64()?)))
        .collect()
}

/// `--shard K/N --out PART.jsonl`: a header line and the shard's result.
fn write_part(
    file: &Path,
    source: &falsify::Source,
    opts: &Options,
    shard: Shard,
    r: &Falsified,
    out: &Path,
) -> i32 {
    let header = json!({
        "scen_falsify_part": 1,
        "file": file.display().to_string(),
        "hash": source.sources.content_hash(),
        "search": opts.search.word(),
        "seed": opts.seed,
        "budget": opts.budget,
        "k": shard.k,
        "n": shard.n,
    });
    let failure = r.failure.as_ref().map(|f| {
        json!({
            "sample": f.sample,
            "params": params_json(&f.params),
            "reproduce": f.reproduce,
            "check": f.check,
            "line": f.line,
            "margin": margin_json(f.margin),
            "obstacles": [f.obstacles.0, f.obstacles.1],
            "shrink_runs": f.shrink_runs,
            "text": f.text,
        })
    });
    let smallest = r.smallest.as_ref().map(
        |(m, k, ps)| json!({"margin": margin_json(*m), "sample": k, "params": params_json(ps)}),
    );
    let result = json!({
        "searched": r.search.word(),
        "tried": r.tried,
        "rejected": r.rejected,
        "smallest": smallest,
        "failure": failure,
    });
    let text = format!("{header}\n{result}\n");
    if let Err(e) = std::fs::write(out, text) {
        eprintln!("error: cannot write `{}`: {e}", out.display());
        return EXIT_BAD_INPUT;
    }
    eprintln!(
        "{}: shard {}/{}: {} sample(s) tried, {}; written to `{}`; combine the parts with `scen falsify merge`",
        file.display(),
        shard.k,
        shard.n,
        r.tried,
        match &r.failure {
            Some(f) => format!("a failure at sample {}", f.sample),
            None => "no failure".to_string(),
        },
        out.display()
    );
    EXIT_OK
}

/// One part, read.
struct Part {
    header: parts::Header,
    /// What the parts of one search share beside the scenario and N: the
    /// search, its seed and budget.
    key: (String, u64, u64),
    result: Falsified,
}

impl parts::Part for Part {
    const COMMAND: &'static str = "scen falsify";
    fn read(path: &Path) -> Result<Self, String> {
        read_part(path)
    }
    fn header(&self) -> &parts::Header {
        &self.header
    }
    fn origin(&self) -> String {
        let (h, k) = (&self.header, &self.key);
        format!(
            "{} (hash {}), --search {}, --seed {}, --budget {}, {} part(s)",
            h.file, h.hash, k.0, k.1, k.2, h.n
        )
    }
}

/// The largest part `merge` reads (a part holds one shrunk scenario).
const MAX_PART_BYTES: u64 = 64 << 20;

fn read_part(path: &Path) -> Result<Part, String> {
    let command = "scen falsify";
    let parts::Lines {
        header: h,
        common,
        rest,
    } = parts::read_lines(path, MAX_PART_BYTES, command, "scen_falsify_part")?;
    let not_a_part = || parts::not_a_part(path, command);
    let r = rest.into_iter().next().ok_or_else(not_a_part)?;
    let read = || -> Option<Part> {
        let word = |v: &Value, k: &str| v.get(k)?.as_str().map(str::to_string);
        let num = |v: &Value, k: &str| v.get(k)?.as_u64();
        let search = search_word(&word(&r, "searched")?).ok()?;
        let failure = match r.get("failure")? {
            Value::Null => None,
            f => {
                let obstacles = f.get("obstacles")?.as_array()?;
                Some(Failure {
                    sample: num(f, "sample")?,
                    params: params_of(f.get("params")?)?,
                    reproduce: word(f, "reproduce")?,
                    check: word(f, "check")?,
                    line: usize::try_from(num(f, "line")?).ok()?,
                    margin: margin_of(f.get("margin")?)?,
                    obstacles: (
                        usize::try_from(obstacles.first()?.as_u64()?).ok()?,
                        usize::try_from(obstacles.get(1)?.as_u64()?).ok()?,
                    ),
                    shrink_runs: usize::try_from(num(f, "shrink_runs")?).ok()?,
                    text: word(f, "text")?,
                })
            }
        };
        let smallest = match r.get("smallest")? {
            Value::Null => None,
            s => Some((
                margin_of(s.get("margin")?)?,
                num(s, "sample")?,
                params_of(s.get("params")?)?,
            )),
        };
        Some(Part {
            header: common,
            key: (word(&h, "search")?, num(&h, "seed")?, num(&h, "budget")?),
            result: Falsified {
                tried: num(&r, "tried")?,
                rejected: num(&r, "rejected")?,
                search,
                smallest,
                failure,
            },
        })
    };
    read().ok_or_else(not_a_part)
}

/// `scen falsify merge PART.jsonl...`: the search's result from its parts
/// (the failure of the smallest sample number among them), the failing
/// scenario checked to fail once more and written.
fn cmd_merge(args: &FalsifyArgs, paths: &[PathBuf]) -> i32 {
    match merge(paths, args.root.as_deref()) {
        Ok((file, source, result)) => {
            let out = args.out.clone().unwrap_or_else(|| default_out(&file));
            let mut inputs = scenario_inputs(&source.sources);
            inputs.extend(paths.iter().map(|p| Input {
                path: p,
                role: "a part given to `merge`",
            }));
            if !outputs_writable(&[("--out", Some(&out))])
                || !outputs_are_not_inputs(&[("--out", Some(&out))], &inputs)
            {
                return EXIT_BAD_INPUT;
            }
            if let Some(f) = &result.failure
                && !falsify::still_failing(&source, &f.text)
            {
                eprintln!(
                    "error: the failing scenario of sample {} passes when run here: the parts were made by another build of `scen`, or the planners differ between the machines",
                    f.sample
                );
                return EXIT_BAD_INPUT;
            }
            finish(&file, &result, &out, args.json)
        }
        Err(e) => {
            eprintln!("error: {e}");
            EXIT_BAD_INPUT
        }
    }
}

fn merge(
    paths: &[PathBuf],
    root: Option<&Path>,
) -> Result<(PathBuf, falsify::Source, Falsified), String> {
    let parts: Vec<Part> = parts::read_parts(paths)?;
    let first = &parts[0];
    let (file, budget, n) = (first.header.file.clone(), first.key.2, first.header.n);
    if n > budget {
        return Err(format!(
            "the parts say {n} shards of a budget of {budget}: a split `scen falsify --shard` does not make"
        ));
    }
    parts::whole(&parts)?;
    let file = PathBuf::from(file);
    let source = load_source(&file, root).map_err(|_| {
        format!(
            "cannot load `{}`, the scenario the parts were made from (its diagnostics are above)",
            file.display()
        )
    })?;
    parts::unchanged(first, &source.sources.content_hash())?;
    for p in &parts {
        let shard = Shard { k: p.header.k, n };
        let share = shard.share(budget);
        let theirs = |sample: u64| sample < budget && shard.takes(sample);
        let r = &p.result;
        if r.tried > share
            || r.rejected > r.tried
            || r.failure.as_ref().is_some_and(|f| !theirs(f.sample))
            || r.smallest.as_ref().is_some_and(|s| !theirs(s.1))
        {
            return Err(format!(
                "`{}` (part {}/{n}) holds samples that are not its own or more than its {share}",
                p.header.path.display(),
                p.header.k
            ));
        }
    }
    // The failure (or, without one, the smallest margin) of the smallest
    // sample number: for `uniform` and `halton`, the failure the whole
    // search finds first.
    let mut parts = parts;
    parts.sort_by_key(|p| p.header.k);
    let mut merged = Falsified {
        tried: parts.iter().map(|p| p.result.tried).sum(),
        rejected: parts.iter().map(|p| p.result.rejected).sum(),
        search: parts[0].result.search,
        smallest: None,
        failure: None,
    };
    for p in parts {
        let r = p.result;
        if let Some(s) = r.smallest
            && merged
                .smallest
                .as_ref()
                .is_none_or(|m| (s.0, s.1) < (m.0, m.1))
        {
            merged.smallest = Some(s);
        }
        if let Some(f) = r.failure
            && merged.failure.as_ref().is_none_or(|m| f.sample < m.sample)
        {
            merged.failure = Some(f);
        }
    }
    Ok((file, source, merged))
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
            // A `uniform` sample is the family's own; the other searches'
            // candidates are points of their own.
            let what = if r.search == falsify::Search::Uniform {
                "sample"
            } else {
                "candidate"
            };
            outln!("FAIL  {what} {}: {}", f.sample, params_text(&f.params));
            outln!("      run it: {}", f.reproduce);
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
            o.insert("reproduce".into(), f.reproduce.clone().into());
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
