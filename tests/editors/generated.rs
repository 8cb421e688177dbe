//! The parts of the editor files generated from the planner registry and
//! the analyser's lists, so that a new planner, parameter, word value or
//! metric reaches the editors through `scripts/regenerate.sh` alone:
//! - the Vim syntax: the lines between `" BEGIN GENERATED NAME` and
//!   `" END GENERATED NAME`;
//! - the VS Code grammar: the repository rules whose `comment` is
//!   [`GENERATED`] (the hand-written rules include them where they apply);
//! - the VS Code snippets `plan-KIND`: the whole file [`SNIPPETS`].
//!
//! Everything else in those files is written by hand and kept as it is.

use scen::planners::registry::PLANNERS;

use scen::contract::Planner;
use scen::contract::schema::{
    COMMON_METRICS, COMMON_PARAMS, DRIVE_METRICS, DefaultValue, ParamSpec, ValueSpec, drive_params,
};
use scen::scenario::family::{DISTRIBUTIONS, FUNCTIONS};
use scen::scenario::{AGGREGATES, BENCH_KEYS};
use serde_json::{Map, Value, json};

pub(crate) const VIM: &str = "editors/vim/syntax/scen.vim";
pub(crate) const TEXTMATE: &str = "editors/vscode/syntaxes/scen.tmLanguage.json";
pub(crate) const SNIPPETS: &str = "editors/vscode/snippets/plans.generated.json";

/// The `comment` of a generated TextMate rule.
pub(crate) const GENERATED: &str =
    "generated from the planner registry by scripts/regenerate.sh: do not edit";

/// One generated file: its path in the repository and how to regenerate
/// it from its committed text (an error says what the generator cannot do).
pub(crate) struct File {
    pub(crate) path: &'static str,
    pub(crate) regenerate: fn(&str) -> Result<String, String>,
}

pub(crate) const FILES: &[File] = &[
    File {
        path: VIM,
        regenerate: vim_syntax,
    },
    File {
        path: TEXTMATE,
        regenerate: textmate_grammar,
    },
    File {
        path: SNIPPETS,
        regenerate: plan_snippets,
    },
];

/// The bench key that starts a list of plan names: both editors give it a
/// rule of its own.
const PLAN_LIST_KEY: &str = "plans";

/// What the editors list, each in the order of first appearance (common
/// parameters and metrics first, then each planner's in registry order,
/// then `drive { ... }`'s).
pub(crate) struct Lists {
    pub(crate) kinds: Vec<&'static str>,
    /// The robot kinds (`scen::geometry::robots`).
    pub(crate) robot_kinds: Vec<&'static str>,
    pub(crate) keys: Vec<&'static str>,
    pub(crate) limit_kinds: Vec<&'static str>,
    pub(crate) words: Vec<&'static str>,
    /// The words that are parameter keys too (`limit`, a value of `stop`),
    /// each with the keys that take it as their value.
    pub(crate) key_words: Vec<(&'static str, Vec<&'static str>)>,
    pub(crate) metrics: Vec<&'static str>,
    pub(crate) aggregates: Vec<&'static str>,
    /// The functions and distributions of number expressions (`min`,
    /// `uniform`, ...: SPEC 2.8).
    pub(crate) functions: Vec<&'static str>,
    /// The bench's own keys but [`PLAN_LIST_KEY`] (a plan's keys, such as
    /// `limit`, are parameter keys already).
    pub(crate) bench_keys: Vec<&'static str>,
}

fn push_new(list: &mut Vec<&'static str>, word: &'static str) {
    if !list.contains(&word) {
        list.push(word);
    }
}

fn all_params() -> impl Iterator<Item = &'static ParamSpec> {
    COMMON_PARAMS
        .iter()
        .chain(PLANNERS.iter().flat_map(|p| p.params.iter()))
        .chain(drive_params())
}

fn is_identifier(word: &str) -> bool {
    let mut chars = word.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

pub(crate) fn lists() -> Result<Lists, String> {
    let kinds: Vec<&str> = PLANNERS.iter().map(|p| p.kind).collect();
    let (mut keys, mut limit_kinds, mut words) = (Vec::new(), Vec::new(), Vec::new());
    for p in all_params() {
        push_new(&mut keys, p.key);
        let list = if p.value == ValueSpec::Limit {
            &mut limit_kinds
        } else {
            &mut words
        };
        for w in p.value.words() {
            push_new(list, w);
        }
    }
    let key_words = words
        .iter()
        .filter(|w| keys.contains(w))
        .map(|&w| {
            let mut takers = Vec::new();
            for p in all_params().filter(|p| p.value.words().contains(&w)) {
                push_new(&mut takers, p.key);
            }
            (w, takers)
        })
        .collect();
    // A keyword in two Vim groups of the same block is coloured by the
    // last one everywhere; only a key that is also a word has a rule that
    // tells them apart by what precedes it.
    for kind in &limit_kinds {
        if keys.contains(kind) || words.contains(kind) {
            return Err(format!(
                "`{kind}` is a limit kind and a parameter key or word value: the editors cannot tell them apart (teach tests/editors/generated.rs)"
            ));
        }
    }
    let mut metrics = Vec::new();
    for m in COMMON_METRICS
        .iter()
        .chain(PLANNERS.iter().flat_map(|p| p.metrics.iter()))
        .chain(DRIVE_METRICS.iter())
    {
        push_new(&mut metrics, m.name);
    }
    let aggregates: Vec<&str> = AGGREGATES.iter().map(|(name, _)| *name).collect();
    let mut functions = Vec::new();
    for f in FUNCTIONS.iter().chain(DISTRIBUTIONS) {
        push_new(&mut functions, f);
    }
    let bench_keys: Vec<&str> = BENCH_KEYS
        .iter()
        .copied()
        .filter(|k| *k != PLAN_LIST_KEY && !keys.contains(k))
        .collect();
    let lists = Lists {
        kinds,
        robot_kinds: scen::geometry::robots::keywords().collect(),
        keys,
        limit_kinds,
        words,
        key_words,
        metrics,
        aggregates,
        functions,
        bench_keys,
    };
    // The words go into regular expressions unescaped.
    for list in [
        &lists.kinds,
        &lists.robot_kinds,
        &lists.keys,
        &lists.limit_kinds,
        &lists.words,
        &lists.metrics,
        &lists.aggregates,
        &lists.functions,
        &lists.bench_keys,
    ] {
        if let Some(bad) = list.iter().find(|w| !is_identifier(w)) {
            return Err(format!("`{bad}` is not an identifier"));
        }
    }
    Ok(lists)
}

// ------------------------------------------------------------------ Vim

const BEGIN: &str = "\" BEGIN GENERATED ";
const END: &str = "\" END GENERATED ";

/// The longest generated Vim line, but for a single long word.
const WIDTH: usize = 120;

/// `head WORD SEP WORD ... tail` over as many lines as [`WIDTH`] needs.
fn wrapped(head: &str, words: &[&str], sep: &str, tail: &str) -> String {
    let mut out = String::new();
    let mut line: Vec<&str> = Vec::new();
    let flush = |line: &mut Vec<&str>, out: &mut String| {
        if !line.is_empty() {
            out.push_str(&format!("{head}{}{tail}\n", line.join(sep)));
            line.clear();
        }
    };
    for &w in words {
        let len = head.len() + line.iter().map(|l| l.len() + sep.len()).sum::<usize>() + w.len();
        if len + tail.len() > WIDTH {
            flush(&mut line, &mut out);
        }
        line.push(w);
    }
    flush(&mut line, &mut out);
    out
}

/// The generated regions of the Vim syntax, by name.
fn vim_regions(l: &Lists) -> Vec<(&'static str, String)> {
    let keyword_keys: Vec<&str> = l
        .keys
        .iter()
        .copied()
        .filter(|k| !l.key_words.iter().any(|(w, _)| w == k))
        .collect();
    // A word value that is a function too (`max`, `uniform`) is a match
    // that stops before `(`, so that the function's match wins there (a
    // keyword would win everywhere).
    let function_words: Vec<&str> = l
        .words
        .iter()
        .copied()
        .filter(|w| l.functions.contains(w) && !l.key_words.iter().any(|(kw, _)| kw == w))
        .collect();
    let keyword_words: Vec<&str> = l
        .words
        .iter()
        .copied()
        .filter(|w| !l.key_words.iter().any(|(kw, _)| kw == w) && !function_words.contains(w))
        .collect();
    let mut parameters = String::from(
        "\" Parameter keys: the common ones, every planner's, and `drive { ... }`'s.\n",
    );
    parameters.push_str(&wrapped(
        "syn keyword scenParamKey contained ",
        &keyword_keys,
        " ",
        "",
    ));
    if !l.key_words.is_empty() {
        parameters.push_str(
            "\" A key that is a word value too is two matches, not keywords (a keyword would\n\
             \" win everywhere): the word's, defined later, wins after the keys it follows.\n",
        );
        for (w, _) in &l.key_words {
            parameters.push_str(&format!("syn match   scenParamKey contained /\\<{w}\\>/\n"));
        }
    }
    parameters.push_str("\" `limit KIND N`.\n");
    parameters.push_str(&wrapped(
        "syn keyword scenLimitKind contained ",
        &l.limit_kinds,
        " ",
        "",
    ));
    parameters.push_str("\" Word values.\n");
    parameters.push_str(&wrapped(
        "syn keyword scenWord contained ",
        &keyword_words,
        " ",
        "",
    ));
    if !function_words.is_empty() {
        parameters.push_str(&wrapped(
            "syn match   scenWord contained /\\<\\%(",
            &function_words,
            "\\|",
            "\\)\\>(\\@!/",
        ));
    }
    for (w, takers) in &l.key_words {
        let after = match takers.as_slice() {
            [one] => one.to_string(),
            many => format!("\\%({}\\)", many.join("\\|")),
        };
        parameters.push_str(&format!(
            "syn match   scenWord contained /\\%(\\<{after}\\s\\+\\)\\@<={w}\\>/\n"
        ));
    }
    vec![
        (
            "robot-kinds",
            wrapped(
                "syn keyword scenRobotShape contained ",
                &l.robot_kinds,
                " ",
                "",
            ),
        ),
        (
            "planners",
            wrapped(
                "syn keyword scenPlanner contained ",
                &l.kinds,
                " ",
                " nextgroup=scenRobotRef skipwhite",
            ),
        ),
        ("parameters", parameters),
        (
            "bench-keys",
            wrapped(
                "syn keyword scenBenchKey contained ",
                &l.bench_keys,
                " ",
                "",
            ),
        ),
        (
            "aggregates",
            wrapped(
                "syn match   scenFunction contained /\\<\\%(",
                &l.aggregates,
                "\\|",
                "\\)\\ze(/",
            ),
        ),
        (
            "functions",
            wrapped(
                "syn match   scenCalcFunction /\\<\\%(",
                &l.functions,
                "\\|",
                "\\)\\ze(/",
            ),
        ),
        (
            "metrics",
            wrapped(
                "syn match   scenMetric contained /\\.\\@1<=\\%(",
                &l.metrics,
                "\\|",
                "\\)\\>/",
            ),
        ),
    ]
}

fn vim_syntax(committed: &str) -> Result<String, String> {
    replace_regions(committed, &vim_regions(&lists()?))
}

/// `text` with the lines between each `" BEGIN GENERATED NAME ...` line
/// and its `" END GENERATED NAME` replaced by the region `NAME` of
/// `regions`; every region must be in `text` exactly once.
pub(crate) fn replace_regions(text: &str, regions: &[(&str, String)]) -> Result<String, String> {
    let mut out = String::new();
    let mut seen: Vec<&str> = Vec::new();
    let mut inside: Option<&str> = None;
    for (n, line) in text.split_inclusive('\n').enumerate() {
        let at = n + 1;
        match inside {
            None => {
                out.push_str(line);
                if let Some(rest) = line.strip_prefix(BEGIN) {
                    let name = rest.split_whitespace().next().unwrap_or("");
                    let Some((name, body)) = regions.iter().find(|(r, _)| *r == name) else {
                        return Err(format!("line {at}: no generated region `{name}`"));
                    };
                    if seen.contains(name) {
                        return Err(format!("line {at}: the region `{name}` again"));
                    }
                    seen.push(name);
                    out.push_str(body);
                    inside = Some(name);
                } else if line.starts_with(END) {
                    return Err(format!("line {at}: an END without its BEGIN"));
                }
            }
            Some(name) => {
                if line.trim_end() == format!("{END}{name}") {
                    out.push_str(line);
                    inside = None;
                } else if line.starts_with(BEGIN) || line.starts_with(END) {
                    return Err(format!("line {at}: the region `{name}` is not closed"));
                }
            }
        }
    }
    if let Some(name) = inside {
        return Err(format!("the region `{name}` is never closed"));
    }
    let missing: Vec<&str> = regions
        .iter()
        .map(|(r, _)| *r)
        .filter(|r| !seen.contains(r))
        .collect();
    if !missing.is_empty() {
        return Err(format!(
            "no `{BEGIN}NAME` line for {missing:?}: place them in the hand-written syntax"
        ));
    }
    Ok(out)
}

// ------------------------------------------------------------- TextMate

/// `\b(?:a|b|c)\b`.
fn alternatives(words: &[&str], tail: &str) -> String {
    format!("\\b(?:{}){tail}", words.join("|"))
}

fn textmate_grammar(committed: &str) -> Result<String, String> {
    let l = lists()?;
    let rules = [
        (
            "planner-kinds",
            alternatives(&l.kinds, "\\b"),
            "support.type.planner.scen",
        ),
        (
            "param-keys",
            alternatives(&l.keys, "\\b"),
            "variable.parameter.key.scen",
        ),
        (
            "limit-kinds",
            alternatives(&l.limit_kinds, "\\b"),
            "variable.parameter.limit.scen",
        ),
        (
            "word-values",
            alternatives(&l.words, "\\b"),
            "constant.language.word.scen",
        ),
        (
            "bench-keys",
            alternatives(&l.bench_keys, "\\b"),
            "variable.parameter.key.scen",
        ),
        (
            "aggregates",
            alternatives(&l.aggregates, "(?=\\()"),
            "support.function.aggregate.scen",
        ),
        (
            "calc-functions",
            alternatives(&l.functions, "(?=\\()"),
            "support.function.calc.scen",
        ),
        (
            "metrics",
            alternatives(&l.metrics, "\\b"),
            "support.variable.metric.scen",
        ),
    ];
    let mut grammar: Value =
        serde_json::from_str(committed).map_err(|e| format!("not JSON: {e}"))?;
    let repository = grammar
        .get_mut("repository")
        .and_then(Value::as_object_mut)
        .ok_or("no `repository` object")?;
    for (name, rule) in repository.iter() {
        let generated = rule.get("comment").and_then(Value::as_str) == Some(GENERATED);
        if generated && name != "robot" && !rules.iter().any(|(r, _, _)| r == name) {
            return Err(format!(
                "the rule `{name}` says it is generated, but is not"
            ));
        }
    }
    // `robot NAME KIND`: the kind is one of the registry's.
    let robot = json!({
        "comment": GENERATED,
        "match": format!(
            "(?<![\\w.])(robot|team)\\b(?:\\s+([A-Za-z_][A-Za-z0-9_]*))?(?:\\s+({})\\b)?",
            l.robot_kinds.join("|")
        ),
        "captures": {
            "1": { "name": "keyword.control.robot.scen" },
            "2": { "name": "entity.name.robot.scen" },
            "3": { "name": "storage.type.shape.scen" }
        }
    });
    *repository
        .get_mut("robot")
        .ok_or("no repository rule `robot`: the hand-written grammar includes it")? = robot;
    for (name, regex, scope) in rules {
        let slot = repository.get_mut(name).ok_or_else(|| {
            format!(
                "no repository rule `{name}`: the hand-written grammar includes it where it applies"
            )
        })?;
        *slot = json!({ "comment": GENERATED, "match": regex, "name": scope });
    }
    let text = serde_json::to_string_pretty(&grammar).map_err(|e| e.to_string())?;
    Ok(text + "\n")
}

// ------------------------------------------------------------- snippets

/// Text of a snippet body: `$`, `}` and `\` are its syntax, and `more`
/// too where it is written (`,` and `|` in a choice).
fn escaped(text: &str, more: &str) -> String {
    let mut out = String::new();
    for c in text.chars() {
        if "$}\\".contains(c) || more.contains(c) {
            out.push('\\');
        }
        out.push(c);
    }
    out
}

/// A choice placeholder `${n|a,b|}`, the first option selected.
fn choice(n: usize, options: &[String]) -> String {
    let options: Vec<String> = options.iter().map(|o| escaped(o, ",|")).collect();
    format!("${{{n}|{}|}}", options.join(","))
}

/// The placeholder of a required parameter's value.
fn required_value(n: usize, value: ValueSpec) -> String {
    let example = match value {
        ValueSpec::Word(_)
        | ValueSpec::IntOrWord(_)
        | ValueSpec::NumOrWord(_)
        | ValueSpec::Drive => {
            let options: Vec<String> = value.words().iter().map(|w| w.to_string()).collect();
            return choice(n, &options);
        }
        ValueSpec::IntChoice(options) => {
            let options: Vec<String> = options.iter().map(i64::to_string).collect();
            return choice(n, &options);
        }
        ValueSpec::ObstacleName => "G",
        ValueSpec::Pose => "(0, 0)",
        ValueSpec::Limit => "time 10s",
        ValueSpec::Seconds { .. } => "1s",
        ValueSpec::Angle { .. } => "1deg",
        ValueSpec::Fraction { .. } => "50%",
        ValueSpec::Number { .. } => "1",
    };
    format!("${{{n}:{}}}", escaped(example, ""))
}

/// A commented line for a parameter with a default: `# key default  help`.
fn commented(spec: &ParamSpec) -> String {
    let (shown, help) = match spec.default {
        DefaultValue::Derived(how) => (
            spec.key.to_string(),
            format!("{} (default: {how})", spec.help),
        ),
        other => (
            format!("{} {}", spec.key, other.text()),
            spec.help.to_string(),
        ),
    };
    escaped(&format!("\t# {shown:<20} {help}"), "")
}

/// The body of the snippet `plan-KIND`: the plan's required parameters,
/// its word parameters as choices (default first) and its seed as
/// placeholders, its other parameters commented with their defaults.
fn plan_body(p: &Planner) -> Vec<String> {
    let mut n = 2;
    let mut next = || {
        n += 1;
        n
    };
    // A team's agents carry their starts and goals (SPEC 2.10).
    let team = p.plans_teams();
    let robot = if team { "T" } else { "r" };
    let mut body = vec![format!("plan ${{1:p}} {} ${{2:{robot}}} {{", p.kind)];
    if !team {
        body.push(format!("\tstart (${{{}:1}}, ${{{}:1}})", next(), next()));
    }
    if p.needs_goal {
        body.push(format!("\tgoal  (${{{}:9}}, ${{{}:9}})", next(), next()));
    }
    let mut comments = Vec::new();
    for spec in p.params {
        match (spec.default, spec.value) {
            (DefaultValue::None, value) => {
                body.push(format!("\t{} {}", spec.key, required_value(next(), value)));
            }
            (DefaultValue::Word(default), ValueSpec::Word(words)) => {
                let mut options = vec![default.to_string()];
                options.extend(
                    words
                        .iter()
                        .filter(|w| **w != default)
                        .map(|w| w.to_string()),
                );
                body.push(format!("\t{} {}", spec.key, choice(next(), &options)));
            }
            _ => comments.push(commented(spec)),
        }
    }
    if p.randomized {
        body.push(format!("\tseed ${{{}:0}}", next()));
    }
    body.extend(comments);
    if let Some(limit) = p.limits.first() {
        let example = if *limit == "time" { "10s" } else { "10000" };
        body.push(format!("\t# limit {limit} {example}"));
    }
    body.push("}".into());
    body.push("$0".into());
    body
}

fn plan_snippets(_committed: &str) -> Result<String, String> {
    let mut snippets = Map::new();
    for p in PLANNERS {
        let mut description = p.summary.to_string();
        if let Some(first) = description.get_mut(..1) {
            first.make_ascii_uppercase();
        }
        snippets.insert(
            format!("plan {}", p.kind),
            json!({
                "prefix": format!("plan-{}", p.kind),
                "description": description,
                "body": plan_body(p),
            }),
        );
    }
    let text = serde_json::to_string_pretty(&Value::Object(snippets)).map_err(|e| e.to_string())?;
    Ok(text + "\n")
}
