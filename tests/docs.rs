//! The manual in `docs/` stays true to the program.
//!
//! - `docs/planners.md` is the planner registry as Markdown
//!   (`scen::planners::registry::reference`): it fails when the committed
//!   file is stale. `scripts/regenerate.sh` (`SCEN_BLESS=1`) rewrites it.
//! - The planner lists of the README, the language reference, the tutorial
//!   and the diagnostics page are generated blocks, checked the same way.
//! - Every ```` ```scen ```` block of every `docs/**/*.md` is checked, by the
//!   rule the manual states (docs/README.md, "Snippets"):
//!   - a block whose opening comment lines hold `# expect-error: CODE` shows
//!     a mistake: as a file next to its page, `scen check` must reject it
//!     with exactly those error codes;
//!   - a block whose first statement is a `scenario` title is a whole
//!     scenario: as a file next to its page, it must pass `scen check`;
//!   - any other block is a fragment, which must parse.
//! - `scen test docs/examples` passes: the tutorial's scenarios run, and
//!   their `expect`s hold the numbers the tutorial quotes.
//! - Every diagnostic code in `src/` is documented in `docs/diagnostics.md`,
//!   and every code documented there exists in `src/`.
//! - Relative links between the pages lead to files and headings that exist.

mod common;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use common::{TempDir, run_or_kill};

/// How long one `scen check` of a snippet may take.
const CHECK_TIMEOUT: Duration = Duration::from_secs(20);

/// How long `scen test docs/examples` may take.
const TEST_TIMEOUT: Duration = Duration::from_secs(300);

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn docs() -> PathBuf {
    repo().join("docs")
}

#[test]
fn the_planner_reference_is_up_to_date() {
    let path = docs().join("planners.md");
    let generated = scen::planners::registry::reference();
    if std::env::var_os("SCEN_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().expect("docs/")).expect("create docs/");
        std::fs::write(&path, &generated).expect("write docs/planners.md");
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == generated,
        "docs/planners.md is stale: run `scripts/regenerate.sh`"
    );
}

/// The pages whose planner lists are generated blocks
/// (`<!-- generated: NAME -->` … `<!-- end of generated -->`, see
/// `scen::planners::registry::refresh_generated_blocks`).
const PAGES_WITH_GENERATED_BLOCKS: &[&str] = &[
    "README.md",
    "docs/language.md",
    "docs/tutorial.md",
    "docs/diagnostics.md",
];

#[test]
fn the_generated_planner_lists_of_the_pages_are_up_to_date() {
    let bless = std::env::var_os("SCEN_BLESS").is_some();
    let mut stale = Vec::new();
    for rel in PAGES_WITH_GENERATED_BLOCKS {
        let path = repo().join(rel);
        let committed = std::fs::read_to_string(&path).expect("read a page");
        assert!(
            committed.contains(scen::planners::registry::GENERATED_START),
            "{rel} has no generated block"
        );
        let fresh = scen::planners::registry::refresh_generated_blocks(&committed)
            .unwrap_or_else(|e| panic!("{rel}: {e}"));
        if fresh != committed {
            if bless {
                std::fs::write(&path, &fresh).expect("write a page");
            } else {
                stale.push(*rel);
            }
        }
    }
    assert!(
        stale.is_empty(),
        "the generated blocks (planner lists, the robot table) of {} are stale: run `scripts/regenerate.sh`",
        stale.join(", ")
    );
}

// ------------------------------------------------------------------ pages

/// One Markdown page of the manual: its path relative to `docs/` and text.
struct Page {
    rel: PathBuf,
    text: String,
}

/// Every `*.md` under `docs/`, sorted.
fn pages() -> Vec<Page> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
            .expect("read docs/")
            .filter_map(|e| e.ok().map(|e| e.path()))
            .collect();
        entries.sort();
        for e in entries {
            if e.is_dir() {
                walk(&e, out);
            } else if e.extension().is_some_and(|x| x == "md") {
                out.push(e);
            }
        }
    }
    let mut paths = Vec::new();
    walk(&docs(), &mut paths);
    paths
        .into_iter()
        .map(|p| Page {
            rel: p.strip_prefix(docs()).expect("under docs/").to_path_buf(),
            text: std::fs::read_to_string(&p).expect("read a page"),
        })
        .collect()
}

/// A fenced code block: its info string, its text and the line of its
/// opening fence (1-based).
struct Block {
    info: String,
    text: String,
    line: usize,
}

/// The fenced blocks of a page (```` ``` ```` fences, possibly indented as
/// in a list item: that indentation is removed from the block's lines).
fn blocks(text: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut open: Option<(Block, usize)> = None;
    for (i, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        match &mut open {
            None => {
                if let Some(info) = trimmed.strip_prefix("```") {
                    let block = Block {
                        info: info.trim().to_string(),
                        text: String::new(),
                        line: i + 1,
                    };
                    open = Some((block, indent));
                }
            }
            Some((block, fence_indent)) => {
                if trimmed.trim_end() == "```" {
                    out.extend(open.take().map(|(b, _)| b));
                } else {
                    block.text.push_str(&line[indent.min(*fence_indent)..]);
                    block.text.push('\n');
                }
            }
        }
    }
    assert!(open.is_none(), "a code block is never closed");
    out
}

/// The text of a page outside its code blocks.
fn prose(text: &str) -> String {
    let mut out = String::new();
    let mut in_block = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_block = !in_block;
            out.push('\n');
            continue;
        }
        if !in_block {
            out.push_str(line);
        }
        out.push('\n');
    }
    out
}

// --------------------------------------------------------------- snippets

/// What a ```` ```scen ```` block is, by the manual's rule.
#[derive(Debug, PartialEq)]
enum Snippet {
    /// `# expect-error:` lines: these error codes, exactly.
    Error(BTreeSet<String>),
    /// Begins with a `scenario` title: passes `scen check`.
    Whole,
    /// Anything else: parses.
    Fragment,
}

fn classify(text: &str) -> Snippet {
    let codes: BTreeSet<String> = text
        .lines()
        .map_while(|l| l.trim_start().strip_prefix('#'))
        .filter_map(|h| h.trim_start().strip_prefix("expect-error:"))
        .map(|c| c.trim().to_string())
        .filter(|c| !c.is_empty())
        .collect();
    if !codes.is_empty() {
        return Snippet::Error(codes);
    }
    let (file, _) = scen::syntax::parse(text, 0);
    match file.statements.first() {
        Some(scen::syntax::ast::Stmt::Scenario { .. }) => Snippet::Whole,
        _ => Snippet::Fragment,
    }
}

/// A folder holding a copy of `docs/`'s scenario files and maps, so that
/// a snippet written next to its page finds what it includes.
fn docs_copy() -> TempDir {
    fn copy(from: &Path, to: &Path) {
        std::fs::create_dir_all(to).expect("create a folder");
        for e in std::fs::read_dir(from).expect("read a folder").flatten() {
            let p = e.path();
            if p.is_dir() {
                copy(&p, &to.join(e.file_name()));
            } else if p.extension().is_some_and(|x| x == "scen" || x == "map") {
                std::fs::copy(&p, to.join(e.file_name())).expect("copy a file");
            }
        }
    }
    let dir = TempDir::new("docs");
    copy(&docs(), dir.path());
    dir
}

/// `scen check --format json FILE` in `dir`: the exit code and the error
/// codes reported.
fn check(dir: &Path, file: &Path) -> (Option<i32>, Vec<String>, String) {
    let done = run_or_kill(
        Command::new(env!("CARGO_BIN_EXE_scen"))
            .current_dir(dir)
            .args(["check", "--format", "json"])
            .arg(file)
            .env("NO_COLOR", "1"),
        CHECK_TIMEOUT,
    );
    let stdout = String::from_utf8_lossy(&done.stdout).to_string();
    let codes = stdout
        .lines()
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter(|d| d["severity"] == "error")
        .filter_map(|d| d["code"].as_str().map(str::to_string))
        .collect();
    let status = done.status.and_then(|s| s.code());
    let stderr = String::from_utf8_lossy(&done.stderr);
    (status, codes, format!("{stdout}{stderr}"))
}

#[test]
fn every_scen_snippet_of_the_manual_checks() {
    let dir = docs_copy();
    let mut problems = Vec::new();
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    for page in pages() {
        for block in blocks(&page.text) {
            if block.info != "scen" {
                continue;
            }
            let at = format!("docs/{}:{}", page.rel.display(), block.line);
            let kind = classify(&block.text);
            let stem = page
                .rel
                .with_extension("")
                .display()
                .to_string()
                .replace('/', "_");
            let file = page
                .rel
                .with_file_name(format!("snippet_{stem}_{}.scen", block.line));
            match kind {
                Snippet::Fragment => {
                    *counts.entry("fragments").or_default() += 1;
                    let (_, diags) = scen::syntax::parse(&block.text, 0);
                    for d in diags.iter().filter(|d| d.is_error()) {
                        problems.push(format!(
                            "{at}: a fragment that does not parse: {} ({})",
                            d.message, d.code
                        ));
                    }
                }
                Snippet::Whole => {
                    *counts.entry("whole scenarios").or_default() += 1;
                    std::fs::write(dir.path().join(&file), &block.text).expect("write a snippet");
                    let (status, codes, output) = check(dir.path(), &file);
                    if status != Some(0) {
                        problems.push(format!(
                            "{at}: a whole scenario that `scen check` rejects ({codes:?}):\n{output}"
                        ));
                    }
                }
                Snippet::Error(expected) => {
                    *counts.entry("mistakes").or_default() += 1;
                    std::fs::write(dir.path().join(&file), &block.text).expect("write a snippet");
                    let (status, codes, output) = check(dir.path(), &file);
                    let reported: BTreeSet<String> = codes.into_iter().collect();
                    if status != Some(2) || reported != expected {
                        problems.push(format!(
                            "{at}: expects {expected:?}, `scen check` exits {status:?} reporting {reported:?}:\n{output}"
                        ));
                    }
                }
            }
        }
    }
    // The rule has all three kinds to check, so a page that stops using
    // the fence (or a broken extractor) cannot pass by checking nothing.
    for kind in ["fragments", "whole scenarios", "mistakes"] {
        assert!(
            counts.get(kind).copied().unwrap_or(0) >= 5,
            "too few ```scen {kind} found in docs/ ({counts:?})"
        );
    }
    assert!(
        problems.is_empty(),
        "{} ```scen block(s) of the manual are wrong:\n\n{}",
        problems.len(),
        problems.join("\n\n")
    );
}

#[test]
fn the_snippet_rule_tells_the_three_kinds_apart() {
    let whole = "# a comment\nscenario \"t\"\nworld { bounds (0, 0) (1, 1) }\n";
    assert_eq!(classify(whole), Snippet::Whole);
    let fragment = "world { bounds (0, 0) (1, 1) }\nrobot p point\n";
    assert_eq!(classify(fragment), Snippet::Fragment);
    let mistake = "# expect-error: scen::analyze::no_world\n# more words\nrobot p point\n";
    assert_eq!(
        classify(mistake),
        Snippet::Error(BTreeSet::from(["scen::analyze::no_world".to_string()]))
    );
    // `expect-error` counts only among the opening comment lines.
    let late = "robot p point\n# expect-error: scen::analyze::no_world\n";
    assert_eq!(classify(late), Snippet::Fragment);
}

#[test]
fn code_blocks_are_extracted_with_their_fence_line() {
    let text = "# T\n\n```scen\nrobot p point\n```\n\n- item\n\n  ```text\n  a\n    b\n  ```\n";
    let found = blocks(text);
    assert_eq!(found.len(), 2);
    assert_eq!((found[0].info.as_str(), found[0].line), ("scen", 3));
    assert_eq!(found[0].text, "robot p point\n");
    assert_eq!((found[1].info.as_str(), found[1].line), ("text", 9));
    assert_eq!(found[1].text, "a\n  b\n");
}

#[test]
fn the_tutorial_examples_pass_scen_test() {
    let done = run_or_kill(
        Command::new(env!("CARGO_BIN_EXE_scen"))
            .current_dir(repo())
            .args(["test", "docs/examples"])
            .env("NO_COLOR", "1"),
        TEST_TIMEOUT,
    );
    let stdout = String::from_utf8_lossy(&done.stdout);
    let stderr = String::from_utf8_lossy(&done.stderr);
    assert_eq!(
        done.status.and_then(|s| s.code()),
        Some(0),
        "`scen test docs/examples` failed:\n{stdout}\n{stderr}"
    );
    assert!(stdout.contains(" 0 failed"), "{stdout}");
}

/// Following the tutorial leaves nothing in the repository's `docs/`: no
/// command it shows writes an output there, and a `scen falsify` of a file
/// in `docs/` names its `--out` (without it, the failing scenario is written
/// beside the family, where it makes `scen test docs/examples` fail).
#[test]
fn the_tutorials_commands_write_nothing_into_docs() {
    const OUTPUTS: [&str; 7] = [
        "--out",
        "--csv",
        "--svg",
        "--png",
        "--save",
        "--junit",
        "--ompl-log",
    ];
    let text = std::fs::read_to_string(docs().join("tutorial.md")).expect("docs/tutorial.md");
    let commands: Vec<&str> = text
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("$ scen "))
        .collect();
    assert!(
        commands.iter().any(|c| c.starts_with("falsify")),
        "the tutorial shows `scen falsify`"
    );
    for command in commands {
        let words: Vec<&str> = command.split_whitespace().collect();
        let outputs: Vec<&str> = words
            .windows(2)
            .filter(|w| OUTPUTS.contains(&w[0]))
            .map(|w| w[1])
            .collect();
        for out in &outputs {
            assert!(
                !out.starts_with("docs/"),
                "`scen {command}` writes `{out}` into docs/"
            );
        }
        let on_docs = words.iter().any(|w| w.starts_with("docs/"));
        if words.first() == Some(&"falsify") && on_docs {
            assert!(
                words.contains(&"--out"),
                "`scen {command}` writes its failure beside the family, into docs/"
            );
        }
    }
}

// ------------------------------------------------------------ diagnostics

/// Every `"scen::..."` string literal in the `.rs` files under `dir`.
fn codes_in_source(dir: &Path, out: &mut BTreeSet<String>) {
    for e in std::fs::read_dir(dir).expect("read src/").flatten() {
        let p = e.path();
        if p.is_dir() {
            codes_in_source(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            let text = std::fs::read_to_string(&p).expect("read a source file");
            for (at, _) in text.match_indices("\"scen::") {
                let rest = &text[at + 1..];
                let Some(end) = rest.find('"') else { continue };
                let code = &rest[..end];
                if code
                    .chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_' || c == ':')
                {
                    out.insert(code.to_string());
                }
            }
        }
    }
}

/// The codes `docs/diagnostics.md` documents: its headings that are a code
/// in backticks (`` ### `scen::analyze::unknown_key` ``).
fn documented_codes() -> BTreeSet<String> {
    let text = std::fs::read_to_string(docs().join("diagnostics.md")).expect("docs/diagnostics.md");
    prose(&text)
        .lines()
        .filter(|l| l.starts_with('#'))
        .filter_map(|l| {
            let h = l.trim_start_matches('#').trim();
            let code = h.strip_prefix('`')?.strip_suffix('`')?;
            code.starts_with("scen::").then(|| code.to_string())
        })
        .collect()
}

#[test]
fn every_diagnostic_code_is_documented_and_every_documented_code_exists() {
    let mut in_source = BTreeSet::new();
    // The scen crate's sources and the workspace's lower crates'.
    codes_in_source(&repo().join("src"), &mut in_source);
    codes_in_source(&repo().join("crates"), &mut in_source);
    assert!(
        in_source.len() >= 50,
        "found only {} codes in src/",
        in_source.len()
    );
    let documented = documented_codes();
    let undocumented: Vec<&String> = in_source.difference(&documented).collect();
    let dead: Vec<&String> = documented.difference(&in_source).collect();
    assert!(
        undocumented.is_empty() && dead.is_empty(),
        "docs/diagnostics.md is out of step with src/:\n\
         codes in src/ without a `### `CODE`` heading in docs/diagnostics.md: {undocumented:#?}\n\
         codes documented there that src/ never emits: {dead:#?}"
    );
}

// ------------------------------------------------------------------ links

/// The anchor GitHub and mdBook give a heading: lower case, letters,
/// digits, `_` and `-` kept, blanks turned into `-`, the rest dropped.
fn slug(heading: &str) -> String {
    heading
        .chars()
        .filter_map(|c| {
            if c.is_alphanumeric() || c == '_' || c == '-' {
                Some(c.to_lowercase().next().unwrap_or(c))
            } else if c == ' ' {
                Some('-')
            } else {
                None
            }
        })
        .collect()
}

/// The anchors of a page's headings (a repeated one gets `-1`, `-2`, ...).
fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut out = BTreeSet::new();
    for line in prose(text).lines() {
        let hashes = line.chars().take_while(|&c| c == '#').count();
        if hashes == 0 || hashes > 6 || !line[hashes..].starts_with(' ') {
            continue;
        }
        let base = slug(line[hashes..].trim());
        let n = seen.entry(base.clone()).or_default();
        out.insert(if *n == 0 {
            base.clone()
        } else {
            format!("{base}-{n}")
        });
        *n += 1;
    }
    out
}

/// The targets of a text's Markdown links `[...](target)`, with the
/// inline code spans left out.
fn link_targets(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in prose(text).lines() {
        // Inline code may hold `](`: drop the spans between backticks.
        let plain: String = line
            .split('`')
            .enumerate()
            .filter(|(i, _)| i % 2 == 0)
            .map(|(_, s)| s)
            .collect::<Vec<_>>()
            .join(" ");
        let mut rest = plain.as_str();
        while let Some(at) = rest.find("](") {
            rest = &rest[at + 2..];
            let end = rest.find(')').unwrap_or(rest.len());
            out.push(rest[..end].trim().to_string());
            rest = &rest[end..];
        }
    }
    out
}

#[test]
fn relative_links_lead_to_pages_and_headings_that_exist() {
    let mut broken = Vec::new();
    let mut checked = 0;
    for page in pages() {
        let here = docs().join(&page.rel);
        let dir = here.parent().expect("a page's folder").to_path_buf();
        for target in link_targets(&page.text) {
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            checked += 1;
            let (path, anchor) = match target.split_once('#') {
                Some((p, a)) => (p, Some(a)),
                None => (target.as_str(), None),
            };
            let file = if path.is_empty() {
                here.clone()
            } else {
                dir.join(path)
            };
            if !file.exists() {
                broken.push(format!(
                    "docs/{}: `{target}`: no such file",
                    page.rel.display()
                ));
                continue;
            }
            if let Some(anchor) = anchor
                && file.extension().is_some_and(|x| x == "md")
            {
                let text = std::fs::read_to_string(&file).expect("read a linked page");
                if !anchors(&text).contains(anchor) {
                    broken.push(format!(
                        "docs/{}: `{target}`: no heading with anchor `#{anchor}`",
                        page.rel.display()
                    ));
                }
            }
        }
    }
    assert!(
        checked >= 20,
        "only {checked} relative links found in docs/"
    );
    assert!(
        broken.is_empty(),
        "broken links in docs/:\n{}",
        broken.join("\n")
    );
}

#[test]
fn anchors_follow_the_forges_rule() {
    assert_eq!(slug("Exit codes"), "exit-codes");
    assert_eq!(
        slug("`scen::analyze::unknown_key`"),
        "scenanalyzeunknown_key"
    );
    assert_eq!(
        slug("`astar` — A* on a lattice of configurations"),
        "astar--a-on-a-lattice-of-configurations"
    );
    let page = "# A\n## B c\n```\n# not a heading\n```\n## B c\n";
    assert_eq!(
        anchors(page),
        BTreeSet::from(["a".into(), "b-c".into(), "b-c-1".into()])
    );
    assert_eq!(
        link_targets("see [x](cli.md#exit-codes) and `[y](z)`, [w](#a)"),
        ["cli.md#exit-codes", "#a"]
    );
}
