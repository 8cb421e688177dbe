//! Bad inputs, as a student would write them (SPEC 4: "Every input error is
//! a miette diagnostic with file name, line and column, a label on the
//! offending text and, where a fix is known, a help line. No input may make
//! `scen` panic, hang or exhaust memory").
//!
//! Every `tests/bad_inputs/*.scen` (helper files live in `support/`) and a
//! few inputs generated here (empty, binary, too large, too deep) are run
//! through the real binary as `scen check FILE`, `scen check --format json
//! FILE` (every object with the fields editors read: file, line, column,
//! end_line, end_column, severity, code, message, label, help) and
//! `scen run FILE`. Each file starts with comment headers:
//!
//! ```text
//! # expect-error: scen::analyze::unknown_key   the code expected (one line per code)
//! # line: 10                                   the line of the first code's diagnostic
//! # at: support/_cycle_partner.scen            the file it points into (default: this one)
//! # min-errors: 3                              at least this many errors
//! ```
//!
//! Without `min-errors` the file has one mistake and must get exactly one
//! error: a follow-on error ("no `bounds`" after a malformed `bounds`)
//! sends the student after a problem that is not there.
//!
//! All cases run before the test fails, and the failure lists every case
//! that misbehaved and how.

mod common;

use common::{TempDir, run_or_kill};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus};
use std::time::Duration;

/// How long one `scen` process may take on a bad input.
const TIMEOUT: Duration = Duration::from_secs(2);

/// The exit code for input that cannot be read, parsed or analysed.
const EXIT_BAD_INPUT: i32 = 2;

fn corpus_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_inputs")
}

/// One bad input and what `scen` must say about it.
#[derive(Debug)]
struct Case {
    /// The file passed to `scen` (relative to `dir`).
    file: String,
    dir: PathBuf,
    /// Diagnostic codes that must all be reported.
    codes: Vec<String>,
    /// The line of the first code's diagnostic, when known.
    line: Option<usize>,
    /// The file name the diagnostics point into.
    located_in: String,
    /// At least this many error diagnostics; `None`: exactly one.
    min_errors: Option<usize>,
}

impl Case {
    /// A case from the `# key: value` comment lines at the top of `text`.
    fn from_headers(dir: &Path, file: &str, text: &str) -> Result<Case, String> {
        let mut case = Case {
            file: file.to_string(),
            dir: dir.to_path_buf(),
            codes: Vec::new(),
            line: None,
            located_in: file.to_string(),
            min_errors: None,
        };
        let headers = text.lines().map_while(|l| l.strip_prefix('#'));
        for header in headers {
            let Some((key, value)) = header.split_once(':') else {
                continue;
            };
            let value = value.trim();
            let number = || {
                value
                    .parse::<usize>()
                    .map_err(|_| format!("{file}: bad `# {key}:` header"))
            };
            match key.trim() {
                "expect-error" => case.codes.push(value.to_string()),
                "line" => case.line = Some(number()?),
                "min-errors" => case.min_errors = Some(number()?),
                "at" => case.located_in = file_name(value),
                _ => {}
            }
        }
        if case.codes.is_empty() {
            return Err(format!("{file}: no `# expect-error: CODE` header"));
        }
        Ok(case)
    }
}

fn file_name(path: &str) -> String {
    Path::new(path)
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.to_string())
}

/// The committed corpus: `tests/bad_inputs/*.scen`, sorted.
fn committed_cases() -> Vec<Case> {
    let dir = corpus_dir();
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/bad_inputs exists")
        .map(|e| e.expect("a readable folder entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "scen"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| {
            let name = file_name(&p.to_string_lossy());
            let text = std::fs::read_to_string(p).expect("corpus files are UTF-8");
            Case::from_headers(&dir, &name, &text).unwrap_or_else(|e| panic!("{e}"))
        })
        .collect()
}

// ------------------------------------------------------------ running scen

/// What one `scen` process did.
struct Outcome {
    /// `None` when it was killed after [`TIMEOUT`].
    status: Option<ExitStatus>,
    stdout: String,
    stderr: String,
}

impl Outcome {
    fn describe_exit(&self) -> String {
        match self.status {
            None => format!("did not finish within {TIMEOUT:?} (killed)"),
            Some(s) => match s.code() {
                Some(c) => format!("exit code {c}"),
                None => format!("killed by a signal ({s})"),
            },
        }
    }
}

/// Runs the `scen` binary in `dir`, killing it after [`TIMEOUT`].
fn run_scen(dir: &Path, args: &[&str]) -> Outcome {
    let finished = run_or_kill(
        Command::new(env!("CARGO_BIN_EXE_scen"))
            .args(args)
            .current_dir(dir)
            .env("NO_COLOR", "1")
            // A panic must show its "run with RUST_BACKTRACE=1" note.
            .env_remove("RUST_BACKTRACE")
            .env_remove("RUST_LIB_BACKTRACE"),
        TIMEOUT,
    );
    Outcome {
        status: finished.status,
        stdout: String::from_utf8_lossy(&finished.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&finished.stderr).into_owned(),
    }
}

/// Whether `text` contains `name:LINE:COL`.
/// `name` may end with `*`: any file whose name starts with the rest.
fn has_location(text: &str, name: &str) -> bool {
    let (name, any_suffix) = match name.strip_suffix('*') {
        Some(prefix) => (prefix, true),
        None => (name, false),
    };
    text.match_indices(name).any(|(at, _)| {
        let mut rest = &text[at + name.len()..];
        if any_suffix {
            rest = rest
                .trim_start_matches(|c: char| c.is_ascii_alphanumeric() || c == '_' || c == '.');
        }
        let mut parts = rest.splitn(3, ':');
        let digits = |s: Option<&str>, whole: bool| {
            s.is_some_and(|s| {
                let n = s.bytes().take_while(u8::is_ascii_digit).count();
                n > 0 && (!whole || n == s.len())
            })
        };
        parts.next() == Some("") && digits(parts.next(), true) && digits(parts.next(), false)
    })
}

/// All whitespace runs as one space (miette wraps help lines).
fn squash(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

fn excerpt(text: &str) -> String {
    const MAX: usize = 1500;
    let mut s: String = text.chars().take(MAX).collect();
    if text.chars().count() > MAX {
        s.push('…');
    }
    s
}

/// Problems common to every run: exit code, panics.
fn check_process(what: &str, out: &Outcome, problems: &mut Vec<String>) {
    if out.status.and_then(|s| s.code()) != Some(EXIT_BAD_INPUT) {
        problems.push(format!(
            "`{what}`: {}, expected {EXIT_BAD_INPUT}",
            out.describe_exit()
        ));
    }
    if out.stderr.contains("panicked") || out.stderr.contains("RUST_BACKTRACE") {
        problems.push(format!("`{what}` panicked:\n{}", excerpt(&out.stderr)));
    }
}

/// Checks one case; returns what went wrong.
fn check_case(case: &Case) -> Vec<String> {
    let mut problems = Vec::new();
    let file = case.file.as_str();

    // Human diagnostics on stderr.
    let human = run_scen(&case.dir, &["check", file]);
    check_process(&format!("scen check {file}"), &human, &mut problems);
    if !has_location(&human.stderr, &case.located_in) {
        problems.push(format!(
            "`scen check`: stderr has no `{}:LINE:COL`:\n{}",
            case.located_in,
            excerpt(&human.stderr)
        ));
    }
    for code in &case.codes {
        if !human.stderr.contains(code.as_str()) {
            problems.push(format!(
                "`scen check`: stderr lacks `{code}`:\n{}",
                excerpt(&human.stderr)
            ));
        }
    }

    // JSON diagnostics on stdout: one object per line.
    let json = run_scen(&case.dir, &["check", "--format", "json", file]);
    check_process(
        &format!("scen check --format json {file}"),
        &json,
        &mut problems,
    );
    let mut diags = Vec::new();
    for line in json.stdout.lines().filter(|l| !l.trim().is_empty()) {
        match serde_json::from_str::<serde_json::Value>(line) {
            Ok(v) if v.is_object() => diags.push(v),
            _ => problems.push(format!(
                "`--format json`: not a JSON object: {}",
                excerpt(line)
            )),
        }
    }
    if diags.is_empty() {
        problems.push("`--format json` printed no diagnostics".to_string());
    }
    for d in &diags {
        // The fields of SPEC 4 that editors read (editors/vscode's problem
        // matcher, editors/vim's errorformat).
        let fields = [
            "file",
            "line",
            "column",
            "end_line",
            "end_column",
            "severity",
            "code",
            "message",
            "label",
            "help",
        ];
        let missing: Vec<&str> = fields
            .into_iter()
            .filter(|k| match *k {
                "line" | "column" | "end_line" | "end_column" => {
                    d[*k].as_u64().is_none_or(|n| n == 0)
                }
                "severity" => d[*k] != "error" && d[*k] != "warning",
                // `null` when there is no help line.
                "help" => !(d[*k].is_string() || d[*k].is_null()) || d.get(*k).is_none(),
                _ => !d[*k].is_string(),
            })
            .collect();
        if !missing.is_empty() {
            problems.push(format!(
                "`--format json`: {} missing or invalid in {d}",
                missing.join(", ")
            ));
        }
        let start = (d["line"].as_u64(), d["column"].as_u64());
        let end = (d["end_line"].as_u64(), d["end_column"].as_u64());
        if end < start {
            problems.push(format!(
                "`--format json`: the end is before the start in {d}"
            ));
        }
        // Every help line of the JSON is also printed for people.
        if let Some(help) = d["help"].as_str()
            && !squash(&human.stderr).contains(&format!("help: {}", squash(help)))
        {
            problems.push(format!("`scen check`: stderr lacks `help: {help}`"));
        }
    }
    let errors: Vec<&serde_json::Value> =
        diags.iter().filter(|d| d["severity"] == "error").collect();
    match case.min_errors {
        Some(min) if errors.len() < min => {
            problems.push(format!(
                "{} error(s) reported, expected at least {min}",
                errors.len()
            ));
        }
        None if errors.len() != 1 => {
            let list: Vec<String> = errors
                .iter()
                .map(|d| {
                    format!(
                        "line {} `{}`: {}",
                        d["line"],
                        d["code"].as_str().unwrap_or("?"),
                        d["message"]
                    )
                })
                .collect();
            problems.push(format!(
                "one mistake, {} errors reported:\n      {}",
                errors.len(),
                list.join("\n      ")
            ));
        }
        _ => {}
    }
    for (k, code) in case.codes.iter().enumerate() {
        let with_code: Vec<&serde_json::Value> = diags
            .iter()
            .filter(|d| d["code"] == code.as_str())
            .collect();
        if with_code.is_empty() {
            let codes: Vec<&str> = diags.iter().filter_map(|d| d["code"].as_str()).collect();
            problems.push(format!(
                "`--format json`: no `{code}` (got {})",
                codes.join(", ")
            ));
            continue;
        }
        // A student's mistake has a known fix: say it.
        if !with_code.iter().any(|d| d["help"].is_string()) {
            let d = with_code[0];
            problems.push(format!(
                "`{code}` has no help line (message: {})",
                d["message"]
            ));
        }
        if !with_code.iter().any(|d| {
            d["file"].as_str().is_some_and(|f| {
                let f = file_name(f);
                match case.located_in.strip_suffix('*') {
                    Some(prefix) => f.starts_with(prefix),
                    None => f == case.located_in,
                }
            })
        }) {
            problems.push(format!(
                "`{code}` does not point into `{}`",
                case.located_in
            ));
        }
        if k == 0
            && let Some(line) = case.line
            && !with_code
                .iter()
                .any(|d| d["line"].as_u64() == Some(line as u64))
        {
            let lines: Vec<String> = with_code.iter().map(|d| d["line"].to_string()).collect();
            problems.push(format!(
                "`{code}` reported at line(s) {}, expected line {line}",
                lines.join(", ")
            ));
        }
    }

    // `run` refuses the file the same way.
    let run = run_scen(&case.dir, &["run", file]);
    check_process(&format!("scen run {file}"), &run, &mut problems);
    if !run.stderr.contains(case.codes[0].as_str()) {
        problems.push(format!(
            "`scen run`: stderr lacks `{}`:\n{}",
            case.codes[0],
            excerpt(&run.stderr)
        ));
    }
    problems
}

/// Runs every case and fails with the list of those that misbehaved.
fn check_all(cases: &[Case]) {
    let mut report = String::new();
    let mut failed = 0;
    for case in cases {
        let problems = check_case(case);
        if !problems.is_empty() {
            failed += 1;
            report.push_str(&format!("\n=== {} ===\n", case.file));
            for p in problems {
                report.push_str(&format!("  - {p}\n"));
            }
        }
    }
    assert!(
        failed == 0,
        "{failed} of {} bad inputs misbehaved:\n{report}",
        cases.len()
    );
}

// ------------------------------------------------------------------- tests

#[test]
fn committed_bad_inputs_are_reported() {
    check_all(&committed_cases());
}

#[test]
fn corpus_is_large_and_its_codes_exist() {
    let cases = committed_cases();
    assert!(cases.len() >= 40, "only {} bad inputs", cases.len());
    // A header with a typo'd code would make its case fail for the wrong
    // reason: every code must be one the sources emit.
    let mut sources = String::new();
    // The scen crate's sources and the workspace's lower crates'.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut stack = vec![root.join("src"), root.join("crates")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("src/ is readable") {
            let path = entry.expect("a readable folder entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|x| x == "rs") {
                sources.push_str(&std::fs::read_to_string(&path).expect("sources are UTF-8"));
            }
        }
    }
    for case in &cases {
        for code in &case.codes {
            assert!(
                sources.contains(&format!("\"{code}\"")),
                "{}: `{code}` occurs nowhere in the sources",
                case.file
            );
        }
    }
}

/// A scenario that is fine on its own, for generated inputs to extend.
const VALID: &str = "scenario \"Generated\"
world { bounds (0, 0) (10, 10) }
robot dot point
plan p astar dot {
  start (1.5, 1.5)
  goal (8.5, 1.5)
}
";

/// Bytes from xorshift64*: the same "random" file on every run.
fn pseudo_random_bytes(seed: u64, n: usize) -> Vec<u8> {
    let mut x = seed;
    (0..n)
        .map(|_| {
            x ^= x >> 12;
            x ^= x << 25;
            x ^= x >> 27;
            (x.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 56) as u8
        })
        .collect()
}

#[test]
fn generated_bad_inputs_are_reported() {
    let tmp = TempDir::new("bad-inputs");
    let garbage = pseudo_random_bytes(0x5EED_0FBA_D1A7, 64 << 10);
    assert!(
        std::str::from_utf8(&garbage).is_err(),
        "the garbage must not be UTF-8"
    );
    let mut huge = VALID.to_string();
    let padding = "# padding to make the file larger than scen accepts\n";
    // Past the 16 MiB of a scenario's text (SPEC 2.2).
    while huge.len() < 17 << 20 {
        huge.push_str(padding);
    }
    let deep = 100_000;
    // One vertex more than a polygon may have (SPEC 2.2), on line 4.
    let too_many_vertices = format!(
        "scenario \"Generated\"\nworld {{\n  bounds (0, 0) (10, 10)\n  polygon P [{}]\n}}\n\
         robot dot point\nplan p astar dot {{\n  start (0.5, 0.5)\n  goal (9.5, 9.5)\n}}\n",
        (0..=scen::geometry::polygon::MAX_POLYGON_VERTICES)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 100_001.0;
                format!("({:.6}, {:.6})", 5.0 + 4.0 * a.cos(), 5.0 + 4.0 * a.sin())
            })
            .collect::<Vec<_>>()
            .join(", ")
    );
    let generated: Vec<(&str, Vec<u8>, &str, Option<usize>)> = vec![
        (
            "polygon_too_large.scen",
            too_many_vertices.into_bytes(),
            "scen::analyze::polygon_too_large",
            Some(4),
        ),
        ("empty.scen", Vec::new(), "scen::analyze::no_world", Some(1)),
        (
            "comments_only.scen",
            b"# only\n# comments\n\n   # here\n".to_vec(),
            "scen::analyze::no_world",
            Some(1),
        ),
        ("garbage.scen", garbage, "scen::load::not_utf8", None),
        (
            "huge.scen",
            huge.into_bytes(),
            "scen::load::too_large",
            Some(1),
        ),
        (
            "deep_brackets.scen",
            format!("world {{ bounds {}", "(".repeat(deep)).into_bytes(),
            "scen::syntax::too_deep",
            Some(1),
        ),
        (
            "deep_expect_parens.scen",
            format!(
                "{VALID}expect {}p.found{}\n",
                "(".repeat(deep),
                ")".repeat(deep)
            )
            .into_bytes(),
            "scen::syntax::too_deep",
            Some(8),
        ),
        (
            "long_sum.scen",
            format!("{VALID}expect p.cost < {}\n", vec!["1"; deep].join(" + ")).into_bytes(),
            "scen::syntax::too_deep",
            Some(8),
        ),
        // An error past column 65 535 (miette's widest label).
        (
            "long_line.scen",
            format!("{VALID}{}robots dot point\n", " ".repeat(deep)).into_bytes(),
            "scen::syntax::expected",
            Some(8),
        ),
        (
            "many_nots.scen",
            format!("{VALID}expect {}p.found\n", "not ".repeat(deep)).into_bytes(),
            "scen::syntax::too_deep",
            Some(8),
        ),
    ];
    let mut cases = Vec::new();
    // A file that includes the next one twice, 24 levels deep (forty bytes
    // each): 2^24 expansions, bounded by the 16 MiB of text, at the include
    // that crosses it (SPEC 2.2).
    let levels = 24;
    for k in 0..levels {
        let next = format!("include \"_twice_{}.scen\"\n", k + 1);
        std::fs::write(tmp.path().join(format!("_twice_{k}.scen")), next.repeat(2))
            .expect("writing a generated include");
    }
    std::fs::write(
        tmp.path().join(format!("_twice_{levels}.scen")),
        "# the bottom of the chain: forty bytes.\n",
    )
    .expect("writing a generated include");
    std::fs::write(
        tmp.path().join("include_twice_per_level.scen"),
        format!("include \"_twice_0.scen\"\n{VALID}"),
    )
    .expect("writing a generated input");
    cases.push(Case {
        file: "include_twice_per_level.scen".to_string(),
        dir: tmp.path().to_path_buf(),
        codes: vec!["scen::load::too_large".to_string()],
        line: None,
        // Whichever file's include crosses the bound.
        located_in: "_twice_*".to_string(),
        min_errors: None,
    });
    // A map file over its 64 MiB: the diagnostic is at the grid's path, in
    // the scenario, with a map's help (not the help of a scenario's text).
    let big_map = tmp.path().join("big.map");
    let file = std::fs::File::create(&big_map).expect("a map file");
    file.set_len(65 << 20).expect("a sparse 65 MiB map");
    std::fs::write(
        tmp.path().join("map_too_large.scen"),
        VALID.replace(
            "world { bounds (0, 0) (10, 10) }",
            "world {\n  bounds (0, 0) (10, 10)\n  grid G \"big.map\" cell 1 origin (0, 0)\n}",
        ),
    )
    .expect("writing a generated input");
    cases.push(Case {
        file: "map_too_large.scen".to_string(),
        dir: tmp.path().to_path_buf(),
        codes: vec!["scen::load::too_large".to_string()],
        line: Some(4),
        located_in: "map_too_large.scen".to_string(),
        min_errors: None,
    });
    // Files that are not regular: a FIFO (a read would wait for a writer
    // forever) as an include and as a map; they are refused at once.
    #[cfg(unix)]
    for (fifo, text, code) in [
        (
            "fifo.scen",
            format!("include \"fifo.scen\"\n{VALID}"),
            "scen::load::not_regular",
        ),
        (
            "fifo.map",
            VALID.replace(
                "world { bounds (0, 0) (10, 10) }",
                "world {\n  bounds (0, 0) (10, 10)\n  grid G \"fifo.map\" cell 1 origin (0, 0)\n}",
            ),
            "scen::load::not_regular",
        ),
    ] {
        let made = Command::new("mkfifo")
            .arg(tmp.path().join(fifo))
            .status()
            .is_ok_and(|s| s.success());
        assert!(made, "mkfifo {fifo}");
        let name = format!("reads_{}.scen", fifo.replace('.', "_"));
        std::fs::write(tmp.path().join(&name), text).expect("writing a generated input");
        cases.push(Case {
            file: name.clone(),
            dir: tmp.path().to_path_buf(),
            codes: vec![code.to_string()],
            line: None,
            located_in: name,
            min_errors: None,
        });
    }
    for (name, bytes, code, line) in generated {
        std::fs::write(tmp.path().join(name), bytes).expect("writing a generated input");
        cases.push(Case {
            file: name.to_string(),
            dir: tmp.path().to_path_buf(),
            codes: vec![code.to_string()],
            line,
            located_in: name.to_string(),
            min_errors: None,
        });
    }
    check_all(&cases);
}

#[test]
fn location_matcher_needs_line_and_column() {
    assert!(has_location("  ╭─[a.scen:10:3:10:3]", "a.scen"));
    assert!(has_location("  ╭─[_twice_17.scen:1:9]", "_twice_*"));
    assert!(!has_location("  ╭─[_twice_17.scen: 1:9]", "_twice_*"));
    assert!(has_location("at b/a.scen:1:1", "a.scen"));
    assert!(!has_location("a.scen:10", "a.scen"));
    assert!(!has_location("a.scen: 10:3", "a.scen"));
}
