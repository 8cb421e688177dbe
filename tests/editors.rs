//! The editor support (editors/) knows the whole language: every keyword of
//! the pest grammar and every planner kind, parameter key, word value,
//! limit kind and metric that the planner registry
//! (crates/planners/src/planners/registry.rs) and the common schemas (crates/planners/src/contract/schema.rs) accept
//! is coloured by the VS Code grammar and by the Vim syntax, in the right
//! class, as are the keys of a `bench` and the aggregates of `expect`
//! (crates/language/src/scenario/analyze/), and every planner kind and `bench` have a
//! snippet listing their parameters.
//!
//! Those lists and the `plan-KIND` snippets are generated from the registry
//! ([`generated`]): `the_generated_editor_files_are_up_to_date` fails when
//! the committed files are stale, and `scripts/regenerate.sh`
//! (`SCEN_BLESS=1`) rewrites them. The other tests read the files as an
//! editor does, whatever wrote them.
//!
//! This test only reads files; editors/test.sh (run by scripts/test.sh)
//! runs the grammars themselves.

#[path = "editors/generated.rs"]
mod generated;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use scen::contract::schema::{
    COMMON_METRICS, COMMON_PARAMS, DRIVE_MODELS, LIMIT_KINDS, ParamSpec, ValueSpec,
};
use scen::planners::registry::PLANNERS;
use scen::scenario::{AGGREGATES, BENCH_KEYS};
use serde_json::Value;

/// The keys of `drive MODEL { ... }` (SPEC 3.6, 3.8), every model's, from
/// the drive schema.
fn drive_keys() -> impl Iterator<Item = &'static str> {
    scen::contract::schema::drive_params().map(|p| p.key)
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &str) -> String {
    std::fs::read_to_string(root().join(path)).unwrap_or_else(|e| panic!("reading {path}: {e}"))
}

fn read_json(path: &str) -> Value {
    serde_json::from_str(&read(path)).unwrap_or_else(|e| panic!("{path} is not JSON: {e}"))
}

/// The identifiers that a regular expression spells out: `\b(?:a|b_c)\b`
/// gives `a` and `b_c` (escapes such as `\b`, `\s`, `\ze` are dropped).
fn regex_words(regex: &str, out: &mut BTreeSet<String>) {
    let mut cleaned = String::new();
    let mut chars = regex.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '\\' {
            // Vim's `\zs`/`\ze` take two letters, the others one.
            if chars.next() == Some('z') {
                chars.next();
            }
            cleaned.push(' ');
        } else {
            cleaned.push(c);
        }
    }
    out.extend(
        cleaned
            .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .filter(|w| !w.is_empty())
            .map(str::to_string),
    );
}

/// The words of every `match`/`begin`/`end` regex in a grammar node.
fn grammar_words(node: &Value, out: &mut BTreeSet<String>) {
    match node {
        Value::Object(map) => {
            for (key, value) in map {
                match (key.as_str(), value) {
                    ("match" | "begin" | "end", Value::String(re)) => regex_words(re, out),
                    _ => grammar_words(value, out),
                }
            }
        }
        Value::Array(items) => items.iter().for_each(|v| grammar_words(v, out)),
        _ => {}
    }
}

/// The VS Code grammar: the words of each repository rule, and of all rules
/// under the key `*`.
fn textmate() -> BTreeMap<String, BTreeSet<String>> {
    let grammar = read_json("editors/vscode/syntaxes/scen.tmLanguage.json");
    let mut rules = BTreeMap::new();
    for (name, rule) in grammar["repository"]
        .as_object()
        .expect("the grammar has a repository")
    {
        let mut words = BTreeSet::new();
        grammar_words(rule, &mut words);
        rules.insert(name.clone(), words);
    }
    let mut all = BTreeSet::new();
    grammar_words(&grammar, &mut all);
    rules.insert("*".to_string(), all);
    rules
}

/// The Vim syntax: the words of each group's `syn keyword` and `syn match`
/// lines, and of the whole file under the key `*`.
fn vim() -> BTreeMap<String, BTreeSet<String>> {
    let text = read("editors/vim/syntax/scen.vim");
    let mut groups: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut all = BTreeSet::new();
    for line in text.lines().map(str::trim) {
        if line.starts_with('"') {
            continue;
        }
        let mut parts = line.split_whitespace();
        let (Some("syn"), Some(kind), Some(group)) = (parts.next(), parts.next(), parts.next())
        else {
            continue;
        };
        let words = groups.entry(group.to_string()).or_default();
        let rest: Vec<&str> = parts.collect();
        match kind {
            "keyword" => {
                for w in rest {
                    let option = w == "contained" || w.starts_with("skip") || w.contains('=');
                    if !option {
                        words.insert(w.to_string());
                        all.insert(w.to_string());
                    }
                }
            }
            "match" | "region" => {
                // `contained` and `nextgroup=...` are options, not words of
                // the pattern.
                let option = |w: &&str| *w == "contained" || w.starts_with("nextgroup=");
                let rest: Vec<&str> = rest.into_iter().filter(|w| !option(w)).collect();
                let rest = rest.join(" ");
                regex_words(&rest, words);
                regex_words(&rest, &mut all);
            }
            _ => {}
        }
    }
    groups.insert("*".to_string(), all);
    groups
}

/// The words of several rules (or groups) together, under the key `name`.
fn merge(table: &mut BTreeMap<String, BTreeSet<String>>, name: &str, rules: &[&str]) {
    let mut words = BTreeSet::new();
    for rule in rules {
        let known = table
            .get(*rule)
            .unwrap_or_else(|| panic!("no `{rule}` in the editor's file"));
        words.extend(known.iter().cloned());
    }
    table.insert(name.to_string(), words);
}

fn aggregates() -> impl Iterator<Item = &'static str> {
    AGGREGATES.iter().map(|(name, _)| *name)
}

/// The functions and distributions of number expressions (SPEC 2.8).
fn functions() -> impl Iterator<Item = &'static str> {
    scen::scenario::family::FUNCTIONS
        .iter()
        .chain(scen::scenario::family::DISTRIBUTIONS)
        .copied()
}

/// Checks that every word is in `rule` of `words`; returns what is missing.
fn missing<'a>(
    what: &str,
    words: impl IntoIterator<Item = &'a str>,
    table: &BTreeMap<String, BTreeSet<String>>,
    rule: &str,
    file: &str,
) -> Vec<String> {
    let known = table
        .get(rule)
        .unwrap_or_else(|| panic!("{file} has no `{rule}`"));
    words
        .into_iter()
        .filter(|w| !known.contains(*w))
        .map(|w| format!("{file}: {what} `{w}` is not in `{rule}`"))
        .collect()
}

fn all_params() -> impl Iterator<Item = &'static ParamSpec> {
    COMMON_PARAMS
        .iter()
        .chain(PLANNERS.iter().flat_map(|p| p.params.iter()))
}

fn param_keys() -> BTreeSet<&'static str> {
    all_params().map(|p| p.key).chain(drive_keys()).collect()
}

fn word_values() -> BTreeSet<&'static str> {
    let mut words: BTreeSet<&str> = DRIVE_MODELS.iter().copied().collect();
    for p in all_params() {
        if let ValueSpec::Word(ws) | ValueSpec::IntOrWord(ws) | ValueSpec::NumOrWord(ws) = p.value {
            words.extend(ws.iter().copied());
        }
    }
    words
}

fn metrics() -> BTreeSet<&'static str> {
    COMMON_METRICS
        .iter()
        .chain(PLANNERS.iter().flat_map(|p| p.metrics.iter()))
        .chain(scen::contract::schema::DRIVE_METRICS.iter())
        .map(|m| m.name)
        .collect()
}

/// The keywords of the pest grammar: every quoted word of two letters or
/// more (`"scenario"`, `"and"`; the exponent's `"e"` is not a keyword).
fn pest_keywords() -> BTreeSet<String> {
    let text = read("crates/language/grammar/scen.pest");
    let mut words = BTreeSet::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        for (k, quoted) in code.split('"').enumerate() {
            let is_word = quoted.len() >= 2
                && quoted
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_');
            if k % 2 == 1 && is_word {
                words.insert(quoted.to_string());
            }
        }
    }
    words
}

#[test]
fn the_generated_editor_files_are_up_to_date() {
    let bless = std::env::var_os("SCEN_BLESS").is_some();
    let mut stale = Vec::new();
    for file in generated::FILES {
        let path = root().join(file.path);
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        let fresh = (file.regenerate)(&committed).unwrap_or_else(|e| panic!("{}: {e}", file.path));
        if bless {
            // Through a new file, so that a test reading it meanwhile never
            // sees half of it.
            let tmp = path.with_extension("regenerated");
            std::fs::write(&tmp, &fresh).expect("write a generated file");
            std::fs::rename(&tmp, &path).expect("replace a generated file");
        } else if committed != fresh {
            stale.push(file.path);
        }
    }
    assert!(
        stale.is_empty(),
        "stale, not what the planner registry generates: {stale:?}; run `scripts/regenerate.sh`"
    );
}

#[test]
fn regeneration_replaces_the_generated_regions_and_keeps_the_rest() {
    let text = "a\n\" BEGIN GENERATED x (note)\nold\nolder\n\" END GENERATED x\nb\n\
                \" BEGIN GENERATED y\n\" END GENERATED y\n";
    let regions = [("x", "new\n".to_string()), ("y", "y1\ny2\n".to_string())];
    assert_eq!(
        generated::replace_regions(text, &regions).as_deref(),
        Ok(
            "a\n\" BEGIN GENERATED x (note)\nnew\n\" END GENERATED x\nb\n\
            \" BEGIN GENERATED y\ny1\ny2\n\" END GENERATED y\n"
        )
    );
    // A region the file lacks, one not closed, one the generator does not
    // know: errors, not a file with the list left out or eaten.
    let missing = generated::replace_regions("a\n", &regions);
    assert!(missing.is_err_and(|e| e.contains("\"x\", \"y\"")));
    let open = "\" BEGIN GENERATED x\nold\n\" BEGIN GENERATED y\n\" END GENERATED y\n";
    assert!(generated::replace_regions(open, &regions).is_err_and(|e| e.contains("not closed")));
    let unknown = "\" BEGIN GENERATED z\n\" END GENERATED z\n";
    assert!(generated::replace_regions(unknown, &regions).is_err_and(|e| e.contains("`z`")));
}

#[test]
fn the_generated_lists_follow_the_registry() {
    let lists = generated::lists().expect("the registry's lists");
    let kinds: Vec<&str> = PLANNERS.iter().map(|p| p.kind).collect();
    assert_eq!(lists.kinds, kinds);
    assert_eq!(
        lists.keys.iter().copied().collect::<BTreeSet<_>>(),
        param_keys()
    );
    assert_eq!(
        lists.words.iter().copied().collect::<BTreeSet<_>>(),
        word_values()
    );
    assert_eq!(
        lists.metrics.iter().copied().collect::<BTreeSet<_>>(),
        metrics()
    );
    assert_eq!(lists.limit_kinds, LIMIT_KINDS);
    // `limit` is a key, and a value of `stop` (SPEC 3.7).
    assert!(lists.key_words.contains(&("limit", vec!["stop"])));
    assert_eq!(lists.bench_keys, ["vary", "runs", "worlds"]);
    let functions: BTreeSet<&str> = functions().collect();
    assert_eq!(
        lists.functions.iter().copied().collect::<BTreeSet<_>>(),
        functions
    );
    // A word in one place only of each list.
    for list in [&lists.kinds, &lists.keys, &lists.words, &lists.metrics] {
        let unique: BTreeSet<&str> = list.iter().copied().collect();
        assert_eq!(unique.len(), list.len(), "{list:?}");
    }
}

#[test]
fn the_lists_are_not_empty() {
    // A broken extraction must not make the other tests pass vacuously.
    let keywords = pest_keywords();
    for kw in [
        "scenario", "world", "robot", "plan", "expect", "bench", "grid", "and", "where",
    ] {
        assert!(
            keywords.contains(kw),
            "`{kw}` not found in the pest grammar"
        );
    }
    assert!(param_keys().len() >= 20);
    assert!(word_values().len() >= 10);
    assert!(metrics().len() >= 20);
    assert!(textmate()["param-keys"].contains("start"));
    assert!(vim()["scenParamKey"].contains("start"));
    assert!(!vim()["scenParamKey"].contains("contained"));
    assert!(aggregates().count() >= 9 && BENCH_KEYS.contains(&"vary"));
    assert!(textmate()["aggregates"].contains("quantile"));
    assert!(vim()["scenFunction"].contains("quantile"));
    assert!(functions().count() >= 7);
    assert!(textmate()["calc-functions"].contains("uniform"));
    assert!(vim()["scenBenchKey"].contains("plans"));
}

#[test]
fn textmate_grammar_knows_the_language() {
    let mut tm = textmate();
    // `plans` starts its list of plan names; `limit` is a plan's key too.
    merge(
        &mut tm,
        "bench keys",
        &["bench-keys", "bench-plans", "param-keys"],
    );
    let file = "scen.tmLanguage.json";
    let kinds = PLANNERS.iter().map(|p| p.kind);
    let keywords = pest_keywords();
    let mut problems = Vec::new();
    problems.extend(missing("planner kind", kinds, &tm, "planner-kinds", file));
    problems.extend(missing("key", param_keys(), &tm, "param-keys", file));
    problems.extend(missing("word", word_values(), &tm, "word-values", file));
    problems.extend(missing(
        "limit",
        LIMIT_KINDS.iter().copied(),
        &tm,
        "limit-kinds",
        file,
    ));
    problems.extend(missing("metric", metrics(), &tm, "metrics", file));
    problems.extend(missing("aggregate", aggregates(), &tm, "aggregates", file));
    problems.extend(missing(
        "function",
        functions(),
        &tm,
        "calc-functions",
        file,
    ));
    problems.extend(missing(
        "bench key",
        BENCH_KEYS.iter().copied(),
        &tm,
        "bench keys",
        file,
    ));
    problems.extend(missing(
        "keyword",
        keywords.iter().map(String::as_str),
        &tm,
        "*",
        file,
    ));
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}

#[test]
fn vim_syntax_knows_the_language() {
    let mut vim = vim();
    merge(&mut vim, "bench keys", &["scenBenchKey", "scenParamKey"]);
    let file = "editors/vim/syntax/scen.vim";
    let kinds = PLANNERS.iter().map(|p| p.kind);
    let keywords = pest_keywords();
    let mut problems = Vec::new();
    problems.extend(missing("planner kind", kinds, &vim, "scenPlanner", file));
    problems.extend(missing("key", param_keys(), &vim, "scenParamKey", file));
    problems.extend(missing("word", word_values(), &vim, "scenWord", file));
    problems.extend(missing(
        "limit",
        LIMIT_KINDS.iter().copied(),
        &vim,
        "scenLimitKind",
        file,
    ));
    problems.extend(missing("metric", metrics(), &vim, "scenMetric", file));
    problems.extend(missing(
        "aggregate",
        aggregates(),
        &vim,
        "scenFunction",
        file,
    ));
    problems.extend(missing(
        "function",
        functions(),
        &vim,
        "scenCalcFunction",
        file,
    ));
    problems.extend(missing(
        "bench key",
        BENCH_KEYS.iter().copied(),
        &vim,
        "bench keys",
        file,
    ));
    problems.extend(missing(
        "keyword",
        keywords.iter().map(String::as_str),
        &vim,
        "*",
        file,
    ));
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}

/// The whole words of a snippet's body.
fn snippet_words(snippet: &Value) -> BTreeSet<String> {
    let body: Vec<&str> = snippet["body"]
        .as_array()
        .expect("a snippet has a body")
        .iter()
        .filter_map(Value::as_str)
        .collect();
    let mut words = BTreeSet::new();
    regex_words(&body.join("\n"), &mut words);
    words
}

/// The snippet files the extension's manifest lists.
fn snippet_files() -> Vec<String> {
    let manifest = read_json("editors/vscode/package.json");
    manifest["contributes"]["snippets"]
        .as_array()
        .expect("the manifest lists snippets")
        .iter()
        .map(|s| {
            let path = s["path"].as_str().expect("a snippet file's path");
            format!("editors/vscode/{}", path.trim_start_matches("./"))
        })
        .collect()
}

#[test]
fn snippets_cover_each_planner_and_its_parameters() {
    let files: Vec<Value> = snippet_files().iter().map(|f| read_json(f)).collect();
    assert!(
        files.len() >= 2,
        "the hand-written snippets and the generated `plan-KIND` ones"
    );
    let mut by_prefix: BTreeMap<&str, &Value> = BTreeMap::new();
    for snippets in &files {
        for s in snippets
            .as_object()
            .expect("snippets are an object")
            .values()
        {
            let prefix = s["prefix"].as_str().expect("a snippet's prefix");
            assert!(
                by_prefix.insert(prefix, s).is_none(),
                "two snippets `{prefix}`"
            );
        }
    }
    let mut problems = Vec::new();
    for prefix in [
        "world", "robot", "expect", "scenario", "include", "grid", "limit", "drive", "bench",
    ] {
        if !by_prefix.contains_key(prefix) {
            problems.push(format!("no snippet `{prefix}`"));
        }
    }
    for planner in PLANNERS {
        let prefix = format!("plan-{}", planner.kind);
        let Some(snippet) = by_prefix.get(prefix.as_str()) else {
            problems.push(format!("no snippet `{prefix}`"));
            continue;
        };
        let words = snippet_words(snippet);
        // A team plan takes no `start`: its agents have theirs.
        let start = (!planner.plans_teams()).then_some("start");
        let required = ["plan", planner.kind].into_iter().chain(start);
        let goal = planner.needs_goal.then_some("goal");
        let params = planner.params.iter().map(|p| p.key);
        for word in required.chain(goal).chain(params) {
            if !words.contains(word) {
                problems.push(format!("snippet `{prefix}` does not mention `{word}`"));
            }
        }
    }
    let drive = snippet_words(by_prefix["drive"]);
    for key in drive_keys() {
        if !drive.contains(key) {
            problems.push(format!("snippet `drive` does not mention `{key}`"));
        }
    }
    let bench = snippet_words(by_prefix["bench"]);
    for key in BENCH_KEYS {
        if !bench.contains(*key) {
            problems.push(format!("snippet `bench` does not mention `{key}`"));
        }
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}

#[test]
fn extension_manifest_points_at_its_files() {
    let manifest = read_json("editors/vscode/package.json");
    let dir = Path::new("editors/vscode");
    let grammar = &manifest["contributes"]["grammars"][0];
    let tm = read_json(
        dir.join(grammar["path"].as_str().expect("a grammar path"))
            .to_str()
            .expect("a UTF-8 path"),
    );
    assert_eq!(grammar["scopeName"], tm["scopeName"]);
    let language = &manifest["contributes"]["languages"][0];
    assert_eq!(language["id"], "scen");
    assert_eq!(language["extensions"][0], ".scen");
    for path in [
        language["configuration"].as_str(),
        manifest["main"].as_str(),
    ] {
        let path = dir.join(path.expect("a path in the manifest"));
        assert!(
            root().join(&path).is_file(),
            "{} is missing",
            path.display()
        );
    }
    let snippets = snippet_files();
    assert!(
        snippets.iter().any(|f| f == generated::SNIPPETS),
        "the manifest does not list {}: {snippets:?}",
        generated::SNIPPETS
    );
    for file in snippets {
        read_json(&file);
    }
    for language in manifest["contributes"]["snippets"]
        .as_array()
        .into_iter()
        .flatten()
    {
        assert_eq!(language["language"], "scen");
    }
    read_json("editors/vscode/language-configuration.json");
    for file in [
        "editors/vim/ftdetect/scen.vim",
        "editors/vim/ftplugin/scen.vim",
    ] {
        assert!(read(file).contains("scen"), "{file}");
    }
}
