//! A seeded mutation fuzzer for the real `scen` binary (issue 14).
//!
//! `cargo fuzz` (libFuzzer) needs a nightly toolchain and the project
//! builds on stable, so the fuzzer lives here, as an integration test. It
//! starts from every `.scen` file of `scenarios/` and `tests/bad_inputs/`
//! (copied into a temporary folder with the maps and fragments they
//! include; three inputs in four from `scenarios/`, which run), applies one
//! to three mutations — numbers (nudged, or 0, −0, huge, tiny, NaN-like
//! spellings), tokens, lines and bytes — and runs the result as a
//! user would: `scen check --format json FILE`, then, if it is accepted,
//! `scen run --json FILE`, each in a child process under a memory limit
//! (`ulimit -v`, [`MEMORY_KIB`]) and a timeout ([`TIMEOUT`]).
//!
//! Every plan gets `limit time 1s` (and `limit cells 4000000` where its
//! planner honours it) in place of its own time and cell limits, so that a
//! run's length is bounded by its limits and not by what the mutation made
//! of the world.
//!
//! Oracles:
//! - no panic and no crash (a signal, `panicked`, an allocation failure);
//! - the formatter (in this process, before the binary runs): an input it
//!   accepts formats to a text that formats to itself, parses without a
//!   diagnostic into the same statements and keeps every comment in order
//!   (`common::format_oracle`, the oracle of `tests/fmt.rs`);
//! - nothing printed of a file a scenario must not read or quote (its
//!   environment through `/proc/self/environ`, a text file that is not a
//!   scenario): includes and maps are pointed at such files, at FIFOs,
//!   folders, `/dev/zero` and a chain that includes a file twice per level;
//! - no run past its limits: a process that outlives [`TIMEOUT`] is run
//!   again with [`RETRY_TIMEOUT`], and only a second overrun is a failure
//!   (a loaded machine must not make the test flaky);
//! - every diagnostic of a refused input (exit 2) has a location: a file,
//!   a line and a column;
//! - no plan reports `found` with `collision_free = false`, and no run that
//!   stopped short lists a `trajectory` that fails the validator.
//!
//! A failure prints the seed, the input's number, the file it came from,
//! the input itself and a smaller input (lines and tokens removed while the
//! same oracle still fails), and writes both under the target folder.
//!
//! The budget: `SCEN_FUZZ_SECONDS` (default 8, so that `cargo test` runs a
//! short pass; CI's `.ci/run` gives it two minutes) and optionally
//! `SCEN_FUZZ_INPUTS`, a number of inputs. The inputs are a fixed sequence
//! for a seed (`SCEN_FUZZ_SEED`, default 20261122): input k depends only on
//! the seed and k, so a failure is reproduced by the same seed whatever the
//! machine's speed.

mod common;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::thread;
use std::time::{Duration, Instant};

use common::{TempDir, format_oracle, repo, run_or_kill, scen_bin};
use scen::planners::registry::PLANNERS;
use scen::rng::SplitMix64;

const DEFAULT_SECONDS: f64 = 8.0;
const DEFAULT_SEED: u64 = 20261122;

/// Virtual memory one `scen` process may map, in KiB (4 GiB).
const MEMORY_KIB: u64 = 4 << 20;

/// How long one `scen` process may take on a fuzzed input; past it the
/// input is run once more with [`RETRY_TIMEOUT`].
const TIMEOUT: Duration = Duration::from_secs(30);
const RETRY_TIMEOUT: Duration = Duration::from_secs(120);

/// The limits put into every plan.
const PLAN_TIME: &str = "1s";
const PLAN_CELLS: &str = "4000000";

/// Replacements for a number: zeros, huge and tiny magnitudes, the edges of
/// SPEC 2.1's ±1e9, integer overflow points, and spellings that are not
/// numbers at all.
const NUMBERS: &[&str] = &[
    "0",
    "-0",
    "0.0",
    "-0.0",
    "1",
    "-1",
    "0.5",
    "1e9",
    "-1e9",
    "1000000001",
    "1e10",
    "1e15",
    "1e300",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "1e309",
    "2147483648",
    "4294967296",
    "9007199254740993",
    "18446744073709551616",
    "1e-9",
    "1e-12",
    "1e-300",
    "5e-324",
    "-5e-324",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "Infinity",
    "1e",
    ".5e",
    "1e+",
    "0x10",
    "1_000",
    ".",
    "-.5",
    "00",
    "1.5.5",
    "3deg",
    "1e9deg",
    "-1e308rad",
    "1e308deg",
    "1e10deg",
    "-1e9rad",
    "1e9rad",
    "-720deg",
    "1e-300deg",
    "2s",
    "0ms",
    "50%",
    "1e400%",
];

/// Bytes and characters inserted by byte mutations.
const ODD_BYTES: &[&[u8]] = &[
    b"\0",
    b"\xff",
    b"\xc3",
    b"\n",
    b"\r",
    b"\t",
    b"{",
    b"}",
    b"(",
    b")",
    b"[",
    b"]",
    b",",
    b"\"",
    b"#",
    b"-",
    b".",
    "θ".as_bytes(),
    "é".as_bytes(),
    "\u{202e}".as_bytes(),
    "🤖".as_bytes(),
];

/// Files made beside every seed (see [`make_fixtures`]) that strings are
/// pointed at: what a scenario must refuse to read, or read only within
/// its bounds (SPEC 2.2).
const FIXTURE_STRINGS: &[&str] = &[
    // An include chain that includes the next file twice, 24 levels deep:
    // 2^24 expansions unless the loader bounds them.
    "\"_fz_twice_0.scen\"",
    // Not regular files: a FIFO (a read would wait for a writer forever),
    // a folder, a link to the process's environment, a link to /dev/zero.
    "\"_fz_fifo.scen\"",
    "\"_fz_fifo.map\"",
    "\"_fz_dir.scen\"",
    "\"_fz_env.scen\"",
    "\"_fz_zero.map\"",
    "\"/proc/self/environ\"",
    "\"/dev/zero\"",
    // Outside the root.
    "\"../../../../../../etc/hostname.scen\"",
    "\"_fz_outside.scen\"",
    // Not a scenario file.
    "\"_fz_notes.txt\"",
];

/// The deepest level of the `_fz_twice_K.scen` chain.
const TWICE_LEVELS: usize = 24;

/// Makes the files [`FIXTURE_STRINGS`] name, in `dir`.
fn make_fixtures(dir: &Path, outside: &Path) {
    for k in 0..TWICE_LEVELS {
        let next = format!("include \"_fz_twice_{}.scen\"\n", k + 1);
        std::fs::write(dir.join(format!("_fz_twice_{k}.scen")), next.repeat(2)).expect("a fixture");
    }
    std::fs::write(
        dir.join(format!("_fz_twice_{TWICE_LEVELS}.scen")),
        "# the bottom of the chain: forty bytes of text.\n",
    )
    .expect("a fixture");
    std::fs::create_dir_all(dir.join("_fz_dir.scen")).expect("a fixture folder");
    std::fs::write(dir.join("_fz_notes.txt"), "SECRET=do-not-print\n").expect("a fixture");
    #[cfg(unix)]
    {
        for fifo in ["_fz_fifo.scen", "_fz_fifo.map"] {
            let _ = Command::new("mkfifo").arg(dir.join(fifo)).status();
        }
        let _ = std::os::unix::fs::symlink("/proc/self/environ", dir.join("_fz_env.scen"));
        let _ = std::os::unix::fs::symlink("/dev/zero", dir.join("_fz_zero.map"));
        let _ = std::os::unix::fs::symlink(outside, dir.join("_fz_outside.scen"));
    }
}

/// Tokens inserted or swapped in by token mutations, besides the words of
/// the language and of the planner registry.
const EXTRA_TOKENS: &[&str] = &[
    "{",
    "}",
    "(",
    ")",
    "[",
    "]",
    ",",
    "~",
    "+-",
    "==",
    "<=",
    "include \"_apartment_world.scen\"",
    "include \"__missing.scen\"",
    "\"maps/small.map\"",
    "\"\"",
    "(0, 0)",
    "(1e9, -1e9)",
    "(1, 2, 90deg)",
    "[(0,0), (1,0), (0,1)]",
    "[(0,0), (1,1), (1,0), (0,1)]",
    "[]",
];

const KEYWORDS: &[&str] = &[
    "scenario",
    "world",
    "bounds",
    "rect",
    "polygon",
    "segment",
    "disk",
    "grid",
    "cell",
    "origin",
    "robot",
    "point",
    "plan",
    "expect",
    "include",
    "bench",
    "and",
    "or",
    "not",
    "true",
    "false",
    "limit",
    "time",
    "cells",
    "steps",
    "expansions",
    "iterations",
    "auto",
];

// ------------------------------------------------------------- the inputs

/// A seed input: its text and the folder (inside the copy) it lives in.
struct Seed {
    /// The repository path, for reports.
    name: String,
    dir: PathBuf,
    text: Vec<u8>,
}

/// Copies `from` into `to` (files and folders), returning the `.scen`
/// files found.
fn copy_tree(from: &Path, to: &Path, seeds: &mut Vec<(PathBuf, PathBuf)>) {
    std::fs::create_dir_all(to).expect("a folder for the copy");
    let mut entries: Vec<_> = std::fs::read_dir(from)
        .expect("a readable folder")
        .map(|e| e.expect("a folder entry").path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().expect("a file name");
        let target = to.join(name);
        if path.is_dir() {
            copy_tree(&path, &target, seeds);
        } else {
            std::fs::copy(&path, &target).expect("copying a file");
            if path.extension().is_some_and(|x| x == "scen") {
                seeds.push((path, target));
            }
        }
    }
}

fn seeds(tmp: &Path) -> Vec<Seed> {
    let mut found = Vec::new();
    for dir in ["scenarios", "tests/bad_inputs"] {
        copy_tree(&repo().join(dir), &tmp.join(dir), &mut found);
    }
    // A scenario outside every seed's root, for links that lead out of it.
    let outside = tmp.join("outside.scen");
    std::fs::write(&outside, "robot outside point\n").expect("a fixture");
    let mut dirs: Vec<PathBuf> = found
        .iter()
        .filter_map(|(_, copy)| copy.parent().map(Path::to_path_buf))
        .collect();
    dirs.sort();
    dirs.dedup();
    for dir in &dirs {
        make_fixtures(dir, &outside);
    }
    found
        .into_iter()
        .map(|(original, copy)| Seed {
            name: original
                .strip_prefix(repo())
                .unwrap_or(&original)
                .display()
                .to_string(),
            dir: copy.parent().expect("a folder").to_path_buf(),
            text: std::fs::read(&copy).expect("a readable seed"),
        })
        .collect()
}

/// The words mutations draw from: keywords, planner kinds, parameter keys,
/// word values and metrics of every planner.
fn vocabulary() -> Vec<String> {
    let mut words: Vec<String> = KEYWORDS.iter().map(|w| w.to_string()).collect();
    for p in PLANNERS {
        words.push(p.kind.to_string());
        for spec in p.all_params() {
            words.push(spec.key.to_string());
            words.extend(spec.value.words().iter().map(|w| w.to_string()));
        }
        words.extend(p.all_metrics().map(|m| m.name.to_string()));
    }
    words.extend(EXTRA_TOKENS.iter().map(|t| t.to_string()));
    words.sort();
    words.dedup();
    words
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Number,
    Word,
    Punct,
    Str,
}

/// A token of the text: its byte range and kind (comments and whitespace
/// are skipped). Works on any bytes, valid UTF-8 or not.
#[derive(Clone, Copy, Debug)]
struct Token {
    start: usize,
    end: usize,
    kind: Kind,
}

fn tokens(text: &[u8]) -> Vec<Token> {
    let mut out = Vec::new();
    let mut i = 0;
    let n = text.len();
    while i < n {
        let c = text[i];
        let start = i;
        let kind = if c == b'#' {
            while i < n && text[i] != b'\n' {
                i += 1;
            }
            continue;
        } else if c.is_ascii_whitespace() {
            i += 1;
            continue;
        } else if c == b'"' {
            i += 1;
            while i < n && text[i] != b'"' && text[i] != b'\n' {
                if text[i] == b'\\' {
                    i += 1;
                }
                i += 1;
            }
            i = (i + 1).min(n);
            Kind::Str
        } else if c.is_ascii_digit()
            || (matches!(c, b'-' | b'.') && text.get(i + 1).is_some_and(u8::is_ascii_digit))
        {
            i += 1;
            while i < n {
                let d = text[i];
                let exponent_sign = matches!(d, b'+' | b'-') && matches!(text[i - 1], b'e' | b'E');
                if d.is_ascii_alphanumeric() || matches!(d, b'.' | b'_' | b'%') || exponent_sign {
                    i += 1;
                } else {
                    break;
                }
            }
            Kind::Number
        } else if c.is_ascii_alphabetic() || c == b'_' {
            while i < n && (text[i].is_ascii_alphanumeric() || text[i] == b'_') {
                i += 1;
            }
            Kind::Word
        } else {
            i += 1;
            Kind::Punct
        };
        out.push(Token {
            start,
            end: i,
            kind,
        });
    }
    out
}

fn splice(text: &mut Vec<u8>, start: usize, end: usize, with: &[u8]) {
    text.splice(start..end, with.iter().copied());
}

fn pick<'a, T>(rng: &mut SplitMix64, items: &'a [T]) -> Option<&'a T> {
    if items.is_empty() {
        None
    } else {
        Some(&items[(rng.next_u64() % items.len() as u64) as usize])
    }
}

/// The byte range of the `( ... )` that follows the first word `key` (a
/// plan's `start` or `goal`).
fn tuple_after(text: &[u8], toks: &[Token], key: &str) -> Option<(usize, usize)> {
    let at = toks
        .iter()
        .position(|t| t.kind == Kind::Word && &text[t.start..t.end] == key.as_bytes())?;
    let open = toks.get(at + 1).filter(|t| &text[t.start..t.end] == b"(")?;
    let close = toks[at + 1..]
        .iter()
        .find(|t| &text[t.start..t.end] == b")")?;
    Some((open.start, close.end))
}

/// Line ranges (without their newline).
fn lines(text: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, &b) in text.iter().enumerate() {
        if b == b'\n' {
            out.push((start, i));
            start = i + 1;
        }
    }
    if start < text.len() {
        out.push((start, text.len()));
    }
    out
}

/// One mutation of `text`; `other` is another seed (lines are taken from
/// it). Returns what it did, for reports.
fn mutate(text: &mut Vec<u8>, other: &[u8], words: &[String], rng: &mut SplitMix64) -> String {
    let toks = tokens(text);
    let numbers: Vec<Token> = toks
        .iter()
        .copied()
        .filter(|t| t.kind == Kind::Number)
        .collect();
    let strings: Vec<Token> = toks
        .iter()
        .copied()
        .filter(|t| t.kind == Kind::Str)
        .collect();
    let choice = rng.next_u64() % 24;
    match choice {
        // Files: a string (an include's or a map's path) pointed at what a
        // scenario must not read, or must read within its bounds; or an
        // include of one inserted before a line.
        20 | 21 => {
            let with = pick(rng, FIXTURE_STRINGS).expect("fixture strings");
            match pick(rng, &strings) {
                Some(t) if choice == 20 => {
                    let t = *t;
                    let old = String::from_utf8_lossy(&text[t.start..t.end]).into_owned();
                    splice(text, t.start, t.end, with.as_bytes());
                    format!("string {old} → {with}")
                }
                _ => {
                    let ls = lines(text);
                    let at = pick(rng, &ls).map_or(0, |&(s, _)| s);
                    text.splice(at..at, format!("include {with}\n").into_bytes());
                    format!("`include {with}` inserted at byte {at}")
                }
            }
        }
        // A goal made equal to the start (SPEC 3: found at once).
        22 => match (
            tuple_after(text, &toks, "start"),
            tuple_after(text, &toks, "goal"),
        ) {
            (Some((s, e)), Some((gs, ge))) => {
                let start = text[s..e].to_vec();
                splice(text, gs, ge, &start);
                "the goal made the start".into()
            }
            _ => "nothing (no start and goal)".into(),
        },
        // An angle's number made huge or odd in its own unit.
        23 => {
            let angles: Vec<Token> = numbers
                .iter()
                .copied()
                .filter(|t| {
                    text[t.start..t.end].ends_with(b"deg") || text[t.start..t.end].ends_with(b"rad")
                })
                .collect();
            let Some(&t) = pick(rng, &angles) else {
                return "nothing (no angle)".into();
            };
            let unit = String::from_utf8_lossy(&text[t.end - 3..t.end]).into_owned();
            let number = pick(
                rng,
                &[
                    "1e308",
                    "-1e308",
                    "1e10",
                    "1e9",
                    "-1e9",
                    "1000000001",
                    "1e-300",
                    "720",
                    "-360",
                ],
            )
            .expect("numbers");
            let new = format!("{number}{unit}");
            splice(text, t.start, t.end, new.as_bytes());
            format!("angle → `{new}`")
        }
        // Numbers: nudged (a world that still runs, with other geometry:
        // what finds planner bugs), or replaced by SPEC 2.1's edges and
        // spellings that are not numbers.
        0..=9 if !numbers.is_empty() => {
            let t = *pick(rng, &numbers).expect("a number");
            let old = String::from_utf8_lossy(&text[t.start..t.end]).into_owned();
            let value = old.parse::<f64>().ok();
            let new = match (rng.next_u64() % 8, value) {
                (0..=3, Some(x)) => {
                    let factor = [0.0, 0.5, 0.99, 1.0 + 1e-9, 1.01, 2.0, 10.0, -1.0];
                    let shift = [0.0, 0.5, -0.5, 1e-9, 1.0];
                    let f = pick(rng, &factor).expect("factors");
                    let d = pick(rng, &shift).expect("shifts");
                    format!("{}", x * f + d)
                }
                (4, _) => format!("-{}", old.trim_start_matches('-')),
                (5, _) => format!("{old}0000000000"),
                _ => pick(rng, NUMBERS).expect("numbers").to_string(),
            };
            splice(text, t.start, t.end, new.as_bytes());
            format!("number `{old}` → `{new}`")
        }
        // Tokens.
        0..=13 if !toks.is_empty() => {
            let k = (rng.next_u64() % toks.len() as u64) as usize;
            let t = toks[k];
            let old = String::from_utf8_lossy(&text[t.start..t.end]).into_owned();
            match rng.next_u64() % 5 {
                0 => {
                    splice(text, t.start, t.end, b"");
                    format!("token `{old}` deleted")
                }
                1 => {
                    let copy = text[t.start..t.end].to_vec();
                    text.splice(t.end..t.end, [b' '].into_iter().chain(copy));
                    format!("token `{old}` doubled")
                }
                2 if k + 1 < toks.len() => {
                    let u = toks[k + 1];
                    let (a, b) = (text[t.start..t.end].to_vec(), text[u.start..u.end].to_vec());
                    splice(text, u.start, u.end, &a);
                    splice(text, t.start, t.end, &b);
                    format!("token `{old}` swapped with the next")
                }
                3 => {
                    let w = pick(rng, words).expect("words").clone();
                    splice(text, t.start, t.end, w.as_bytes());
                    format!("token `{old}` → `{w}`")
                }
                _ => {
                    let w = pick(rng, words).expect("words").clone();
                    let at = t.start;
                    text.splice(at..at, format!("{w} ").into_bytes());
                    format!("`{w}` inserted before `{old}`")
                }
            }
        }
        // Lines.
        0..=17 => {
            let ls = lines(text);
            let Some(&(s, e)) = pick(rng, &ls) else {
                return "nothing (empty input)".into();
            };
            match rng.next_u64() % 5 {
                0 => {
                    splice(text, s, (e + 1).min(text.len()), b"");
                    format!("line at byte {s} deleted")
                }
                1 => {
                    let mut copy = text[s..e].to_vec();
                    copy.push(b'\n');
                    text.splice(s..s, copy);
                    format!("line at byte {s} doubled")
                }
                2 => {
                    let others = lines(other);
                    let Some(&(os, oe)) = pick(rng, &others) else {
                        return "nothing".into();
                    };
                    let mut copy = other[os..oe].to_vec();
                    copy.push(b'\n');
                    text.splice(s..s, copy);
                    format!("a line of another seed inserted at byte {s}")
                }
                3 => {
                    text.truncate(e);
                    format!("truncated after byte {e}")
                }
                _ => {
                    let Some(&(s2, e2)) = pick(rng, &ls) else {
                        return "nothing".into();
                    };
                    if s2 <= s {
                        return "nothing (same line)".into();
                    }
                    let (a, b) = (text[s..e].to_vec(), text[s2..e2].to_vec());
                    splice(text, s2, e2, &a);
                    splice(text, s, e, &b);
                    format!("lines at bytes {s} and {s2} swapped")
                }
            }
        }
        // Bytes.
        _ => {
            if text.is_empty() {
                text.extend_from_slice(pick(rng, ODD_BYTES).expect("bytes"));
                return "a byte into the empty input".into();
            }
            let at = (rng.next_u64() % text.len() as u64) as usize;
            match rng.next_u64() % 3 {
                0 => {
                    text[at] ^= 1 << (rng.next_u64() % 8);
                    format!("a bit of byte {at} flipped")
                }
                1 => {
                    text.remove(at);
                    format!("byte {at} deleted")
                }
                _ => {
                    let b = pick(rng, ODD_BYTES).expect("bytes");
                    text.splice(at..at, b.iter().copied());
                    format!("{b:?} inserted at byte {at}")
                }
            }
        }
    }
}

/// Gives every `plan NAME KIND ROBOT { ... }` of `text` the fuzzer's time
/// limit (and cell limit, where the planner honours one) instead of its
/// own.
fn bound_plans(text: &[u8]) -> Vec<u8> {
    let toks = tokens(text);
    let word = |t: &Token| String::from_utf8_lossy(&text[t.start..t.end]).into_owned();
    // (insert at, text) and ranges to delete, applied from the end.
    let mut edits: Vec<(usize, usize, String)> = Vec::new();
    let mut k = 0;
    while k + 4 < toks.len() {
        let head = &toks[k..k + 5];
        let is_plan = head[0].kind == Kind::Word
            && word(&head[0]) == "plan"
            && head[1..4].iter().all(|t| t.kind == Kind::Word)
            && word(&head[4]) == "{";
        if !is_plan {
            k += 1;
            continue;
        }
        let planner = scen::planners::registry::planner(&word(&head[2]));
        // The body: up to the matching `}`.
        let mut depth = 0;
        let mut end = toks.len();
        for (m, t) in toks.iter().enumerate().skip(k + 4) {
            match word(t).as_str() {
                "{" => depth += 1,
                "}" => {
                    depth -= 1;
                    if depth == 0 {
                        end = m;
                        break;
                    }
                }
                _ => {}
            }
        }
        if let Some(p) = planner {
            let mut m = k + 5;
            while m + 2 < end {
                if word(&toks[m]) == "limit"
                    && matches!(word(&toks[m + 1]).as_str(), "time" | "cells")
                {
                    edits.push((toks[m].start, toks[m + 2].end, String::new()));
                    m += 3;
                } else {
                    m += 1;
                }
            }
            let mut limits = String::new();
            if p.limits.contains(&"time") {
                let _ = write!(limits, " limit time {PLAN_TIME}");
            }
            if p.limits.contains(&"cells") {
                let _ = write!(limits, " limit cells {PLAN_CELLS}");
            }
            let at = toks[k + 4].end;
            edits.push((at, at, format!("{limits} ")));
        }
        k = end.max(k + 1);
    }
    let mut out = text.to_vec();
    edits.sort_by_key(|e| std::cmp::Reverse(e.0));
    for (start, end, with) in edits {
        out.splice(start..end, with.into_bytes());
    }
    out
}

// ------------------------------------------------------------ the oracles

/// What one process did.
struct Ran {
    /// `None` when it was killed at the timeout.
    status: Option<ExitStatus>,
    stdout: String,
    stderr: String,
}

fn run_scen(dir: &Path, args: &[&str], timeout: Duration) -> Ran {
    // `exec` keeps the process id, so that a kill reaches scen itself.
    let finished = run_or_kill(
        Command::new("sh")
            .arg("-c")
            .arg(format!("ulimit -v {MEMORY_KIB} && exec \"$0\" \"$@\""))
            .arg(scen_bin())
            .args(args)
            .current_dir(dir)
            .env("NO_COLOR", "1")
            .env(CANARY_VAR, CANARY)
            .env_remove("RUST_BACKTRACE"),
        timeout,
    );
    Ran {
        status: finished.status,
        stdout: String::from_utf8_lossy(&finished.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&finished.stderr).into_owned(),
    }
}

/// How an input ended, when no oracle failed.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Verdict {
    /// Refused with located diagnostics (exit 2): the first one's code.
    Refused(String),
    /// Ran: every check passed (exit 0) or some failed (exit 1).
    Ran { plans: usize, found: usize },
}

/// A variable of every child's environment: were `/proc/self/environ`
/// read and quoted, it would show.
const CANARY_VAR: &str = "SCEN_FUZZ_CANARY";
const CANARY: &str = "canary-5c3n-f0zz";

/// Whether a process crashed, ran out of memory, or printed what it must
/// not (its environment, a file that is not a scenario): the failure, if
/// so.
fn crashed(what: &str, ran: &Ran) -> Option<String> {
    for secret in [CANARY, "SECRET=do-not-print"] {
        if ran.stdout.contains(secret) || ran.stderr.contains(secret) {
            return Some(format!(
                "`{what}` printed `{secret}`: bytes of a file it must not read or quote"
            ));
        }
    }
    let status = ran.status?;
    if ran.stderr.contains("memory allocation of") {
        return Some(format!(
            "`{what}` ran out of memory (ulimit -v {MEMORY_KIB} KiB)"
        ));
    }
    if ran.stderr.contains("panicked") {
        return Some(format!("`{what}` panicked"));
    }
    if status.code().is_none() {
        return Some(format!("`{what}` was killed by a signal ({status})"));
    }
    None
}

/// Runs `args` on the input, once more with the longer timeout if it
/// overran; a second overrun is a failure.
fn run_bounded(dir: &Path, args: &[&str]) -> Result<Ran, String> {
    let ran = run_scen(dir, args, TIMEOUT);
    if ran.status.is_some() {
        return Ok(ran);
    }
    let again = run_scen(dir, args, RETRY_TIMEOUT);
    match again.status {
        Some(_) => Ok(again),
        None => Err(format!(
            "`scen {}` ran past {RETRY_TIMEOUT:?} (twice), although every plan has `limit time {PLAN_TIME}`",
            args[0]
        )),
    }
}

/// Runs the oracles on the input file `name` in `dir`, whose bytes are
/// `text`; with the verdict, whether the formatter accepted the input.
fn judge(dir: &Path, name: &str, text: &[u8]) -> Result<(Verdict, bool), String> {
    // The formatter first, in this process: what `scen fmt` (and the
    // language server's formatting) would make of the input.
    let mut formatted = false;
    if let Ok(text) = std::str::from_utf8(text) {
        formatted = std::panic::catch_unwind(|| format_oracle::check_format(text))
            .map_err(|_| "`scen fmt` panicked on the input".to_string())?
            .map_err(|broke| format!("`scen fmt` broke the input: {broke}"))?
            .is_some();
    }
    judge_binary(dir, name).map(|verdict| (verdict, formatted))
}

/// The oracles on the binary's runs of the input file `name` in `dir`.
fn judge_binary(dir: &Path, name: &str) -> Result<Verdict, String> {
    let check = run_bounded(dir, &["check", "--format", "json", name])?;
    if let Some(crash) = crashed("scen check", &check) {
        return Err(crash);
    }
    match check.status.and_then(|s| s.code()) {
        Some(2) => {
            let mut first = None;
            for line in check.stdout.lines().filter(|l| !l.trim().is_empty()) {
                let d: serde_json::Value = serde_json::from_str(line).map_err(|e| {
                    format!("`scen check --format json` printed a non-JSON line ({e}): {line}")
                })?;
                first.get_or_insert_with(|| d["code"].as_str().unwrap_or("?").to_string());
                let located = d["file"].as_str().is_some_and(|f| !f.is_empty())
                    && d["line"].as_u64().is_some_and(|n| n >= 1)
                    && d["column"].as_u64().is_some_and(|n| n >= 1);
                if !located {
                    return Err(format!("a diagnostic without a location: {d}"));
                }
            }
            return first.map(Verdict::Refused).ok_or_else(|| {
                format!(
                    "`scen check` exited 2 without a diagnostic; stderr:\n{}",
                    check.stderr
                )
            });
        }
        Some(0) => {}
        other => {
            return Err(format!(
                "`scen check` exited {other:?}; stderr:\n{}",
                check.stderr
            ));
        }
    }
    let run = run_bounded(dir, &["run", "--json", name])?;
    if let Some(crash) = crashed("scen run", &run) {
        return Err(crash);
    }
    match run.status.and_then(|s| s.code()) {
        Some(0 | 1) => {}
        other => {
            return Err(format!(
                "`scen run` exited {other:?} on an input `scen check` accepted; stderr:\n{}",
                run.stderr
            ));
        }
    }
    let doc: serde_json::Value = serde_json::from_str(&run.stdout)
        .map_err(|e| format!("`scen run --json` printed no JSON document ({e})"))?;
    let plans = doc["plans"]
        .as_object()
        .ok_or("the JSON document has no `plans`")?;
    let mut found = 0;
    for (plan, p) in plans {
        let m = &p["metrics"];
        let valid = m["collision_free"] == serde_json::Value::Bool(true);
        if m["found"] == serde_json::Value::Bool(true) {
            found += 1;
            if !valid {
                return Err(format!(
                    "plan `{plan}` reports found with collision_free = false"
                ));
            }
        }
        if p.get("trajectory").is_some() && !valid {
            return Err(format!(
                "plan `{plan}` stopped short and its executed motion fails the validator"
            ));
        }
    }
    Ok(Verdict::Ran {
        plans: plans.len(),
        found,
    })
}

/// The failure's kind, to keep while minimising (its first words).
fn failure_kind(failure: &str) -> String {
    failure
        .split_whitespace()
        .take(4)
        .collect::<Vec<_>>()
        .join(" ")
}

/// A smaller input that fails the same way: lines, then tokens removed
/// one at a time while the failure stays, within a time budget.
fn minimise(dir: &Path, name: &str, text: &[u8], failure: &str) -> Vec<u8> {
    let kind = failure_kind(failure);
    let began = Instant::now();
    let still_fails = |candidate: &[u8]| -> bool {
        std::fs::write(dir.join(name), candidate).expect("writing the input");
        matches!(judge(dir, name, candidate), Err(f) if failure_kind(&f) == kind)
    };
    let mut best = text.to_vec();
    for by_tokens in [false, true] {
        let mut k = 0;
        loop {
            if began.elapsed() > Duration::from_secs(120) {
                return best;
            }
            let pieces: Vec<(usize, usize)> = if by_tokens {
                tokens(&best).iter().map(|t| (t.start, t.end)).collect()
            } else {
                lines(&best)
                    .into_iter()
                    .map(|(s, e)| (s, (e + 1).min(best.len())))
                    .collect()
            };
            let Some(&(s, e)) = pieces.get(k) else {
                break;
            };
            let mut candidate = best.clone();
            candidate.drain(s..e);
            if still_fails(&candidate) {
                best = candidate;
            } else {
                k += 1;
            }
        }
    }
    best
}

// --------------------------------------------------------------- the run

fn env_or<T: std::str::FromStr>(key: &str, default: T) -> T {
    std::env::var(key)
        .ok()
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or(default)
}

#[derive(Default)]
struct Tally {
    /// By the code of the first diagnostic.
    codes: Mutex<std::collections::BTreeMap<String, u64>>,
    refused: AtomicU64,
    ran: AtomicU64,
    plans: AtomicU64,
    found: AtomicU64,
    /// Inputs the formatter accepted (and its oracle passed).
    formatted: AtomicU64,
}

#[test]
fn fuzzed_inputs_are_refused_with_locations_or_run_soundly() {
    let seconds: f64 = env_or("SCEN_FUZZ_SECONDS", DEFAULT_SECONDS);
    let max_inputs: usize = env_or("SCEN_FUZZ_INPUTS", usize::MAX);
    let seed: u64 = env_or("SCEN_FUZZ_SEED", DEFAULT_SEED);
    let tmp = TempDir::new("fuzz");
    let seeds = seeds(tmp.path());
    let good_seeds = seeds
        .iter()
        .filter(|s| s.name.starts_with("scenarios"))
        .count();
    assert!(good_seeds > 0, "no seed scenarios");
    let words = vocabulary();
    let began = Instant::now();
    let deadline = began + Duration::from_secs_f64(seconds);
    let next = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    let tally = Tally::default();
    let failures: Mutex<Vec<String>> = Mutex::new(Vec::new());
    let out_dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz-failures");
    let workers = thread::available_parallelism().map_or(2, |n| n.get().min(4));
    thread::scope(|scope| {
        for worker in 0..workers {
            let (seeds, words, next, stop, tally, failures, out_dir) = (
                &seeds[..],
                &words,
                &next,
                &stop,
                &tally,
                &failures,
                &out_dir,
            );
            scope.spawn(move || {
                let name = format!("__fuzz_{worker}.scen");
                loop {
                    if stop.load(Ordering::Relaxed) || Instant::now() >= deadline {
                        break;
                    }
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    if k >= max_inputs {
                        break;
                    }
                    // Input k depends only on the seed and k.
                    let mut rng = SplitMix64::new(seed ^ (k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
                    // Three in four from the scenarios (which run), the
                    // rest from the bad inputs (which are refused).
                    let (good, bad) = seeds.split_at(good_seeds);
                    let group = if rng.next_u64().is_multiple_of(4) && !bad.is_empty() {
                        bad
                    } else {
                        good
                    };
                    let origin = pick(&mut rng, group).expect("seeds");
                    let other = pick(&mut rng, seeds).expect("seeds");
                    let mut text = origin.text.clone();
                    let mut done = Vec::new();
                    // One mutation in two inputs, else two or three.
                    let count = [1, 1, 2, 3][(rng.next_u64() % 4) as usize];
                    for _ in 0..count {
                        done.push(mutate(&mut text, &other.text, words, &mut rng));
                    }
                    let text = bound_plans(&text);
                    std::fs::write(origin.dir.join(&name), &text).expect("writing the input");
                    let judged = judge(&origin.dir, &name, &text);
                    if let Ok((_, true)) = judged {
                        tally.formatted.fetch_add(1, Ordering::Relaxed);
                    }
                    match judged.map(|(verdict, _)| verdict) {
                        Ok(Verdict::Refused(code)) => {
                            tally.refused.fetch_add(1, Ordering::Relaxed);
                            *tally.codes.lock().expect("codes").entry(code).or_default() += 1;
                        }
                        Ok(Verdict::Ran { plans, found }) => {
                            tally.ran.fetch_add(1, Ordering::Relaxed);
                            tally.plans.fetch_add(plans as u64, Ordering::Relaxed);
                            tally.found.fetch_add(found as u64, Ordering::Relaxed);
                        }
                        Err(failure) => {
                            stop.store(true, Ordering::Relaxed);
                            let small = minimise(&origin.dir, &name, &text, &failure);
                            let _ = std::fs::create_dir_all(out_dir);
                            let path = out_dir.join(format!("input-{seed}-{k}.scen"));
                            let small_path = out_dir.join(format!("input-{seed}-{k}-min.scen"));
                            let _ = std::fs::write(&path, &text);
                            let _ = std::fs::write(&small_path, &small);
                            failures.lock().expect("the failure list").push(format!(
                                "input {k} (SCEN_FUZZ_SEED={seed}), from {} after {}:\n  {failure}\n\
                                 saved as {} (the input) and {} (a smaller one failing the same way)\n\
                                 --- the smaller input ---\n{}\n--- the input ---\n{}\n---",
                                origin.name,
                                done.join("; "),
                                path.display(),
                                small_path.display(),
                                String::from_utf8_lossy(&small),
                                String::from_utf8_lossy(&text),
                            ));
                        }
                    }
                }
            });
        }
    });
    let inputs = tally.refused.load(Ordering::Relaxed) + tally.ran.load(Ordering::Relaxed);
    eprintln!(
        "fuzz: {inputs} inputs in {:.1?} (seed {seed}, {} seed files, {workers} workers): \
         {} refused with located diagnostics, {} ran ({} plans, {} found a path); \
         {} formatted by `scen fmt`",
        began.elapsed(),
        seeds.len(),
        tally.refused.load(Ordering::Relaxed),
        tally.ran.load(Ordering::Relaxed),
        tally.plans.load(Ordering::Relaxed),
        tally.found.load(Ordering::Relaxed),
        tally.formatted.load(Ordering::Relaxed),
    );
    let codes = tally.codes.into_inner().expect("codes");
    let mut by_count: Vec<(&String, &u64)> = codes.iter().collect();
    by_count.sort_by(|a, b| b.1.cmp(a.1).then(a.0.cmp(b.0)));
    let listed: Vec<String> = by_count.iter().map(|(c, n)| format!("{c} {n}")).collect();
    eprintln!("fuzz: refusals by first code: {}", listed.join(", "));
    let failures = failures.into_inner().expect("the failure list");
    assert!(failures.is_empty(), "\n{}", failures.join("\n\n"));
}

#[test]
fn plans_get_the_fuzzers_limits_instead_of_their_own() {
    let text = b"plan a astar dot { start (1, 1) limit time 5s goal (2, 2) limit cells 9 }\n\
                 plan b potential dot { limit steps 3 }\nplan c nowhere dot { }\n";
    let bounded = String::from_utf8(bound_plans(text)).expect("UTF-8");
    assert_eq!(
        bounded,
        "plan a astar dot { limit time 1s limit cells 4000000  start (1, 1)  goal (2, 2)  }\n\
         plan b potential dot { limit time 1s  limit steps 3 }\nplan c nowhere dot { }\n"
    );
}

#[test]
fn the_tokenizer_sees_numbers_words_strings_and_punctuation() {
    let text = b"disk C (1e-3, -2.5) 0.5 # a comment 7\n\"a \\\" b\" x_1";
    let kinds: Vec<(String, Kind)> = tokens(text)
        .iter()
        .map(|t| {
            (
                String::from_utf8_lossy(&text[t.start..t.end]).into_owned(),
                t.kind,
            )
        })
        .collect();
    let expected = [
        ("disk", Kind::Word),
        ("C", Kind::Word),
        ("(", Kind::Punct),
        ("1e-3", Kind::Number),
        (",", Kind::Punct),
        ("-2.5", Kind::Number),
        (")", Kind::Punct),
        ("0.5", Kind::Number),
        ("\"a \\\" b\"", Kind::Str),
        ("x_1", Kind::Word),
    ];
    let expected: Vec<(String, Kind)> = expected.iter().map(|(s, k)| (s.to_string(), *k)).collect();
    assert_eq!(kinds, expected);
}
