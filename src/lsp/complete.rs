//! Completion: what may be written at the cursor, read from the statement
//! the cursor is in (the scanner's chunks and tokens, so that half-typed
//! text works) and offered from the registry and the scenario's names.

use lsp_types::{CompletionItem, CompletionItemKind, Documentation, MarkupContent, MarkupKind};

use super::analysis::{Analysis, NameKind};
use crate::contract::schema::{DRIVE_METRICS, MetricSpec, MetricType, ParamSpec, ValueSpec};
use crate::geometry::steer::MODEL_NAMES;
use crate::planners::registry::{self, PLANNERS};
use crate::scenario::grouping::ParamKeys;
use crate::scenario::{AGGREGATES, BENCH_KEYS};
use crate::syntax::{
    EXPRESSION_WORDS, FAMILY_VALUE_WORDS, GRID_OPTION_KEYWORDS, Lexer, ROBOT_CLAUSE_KEYWORDS,
    STATEMENT_KEYWORDS, Token, TokenKind, WORLD_ITEM_KEYWORDS, statement_at,
};

/// The completions at byte `offset` of `text` (the document `analysis` was
/// made from, or an older version of it).
pub(crate) fn completions(text: &str, offset: usize, analysis: &Analysis) -> Vec<CompletionItem> {
    let offset = offset.min(text.len());
    let bytes = text.as_bytes();
    let mut word_start = offset;
    while word_start > 0
        && (bytes[word_start - 1].is_ascii_alphanumeric() || bytes[word_start - 1] == b'_')
    {
        word_start -= 1;
    }
    let line_start = text[..word_start].rfind('\n').map_or(0, |k| k + 1);
    let first_on_line = text[line_start..word_start].trim().is_empty();
    let statement = statement_at(text, word_start);
    let (chunk_start, keyword) = match statement {
        Some(s) if !(first_on_line && word_start == line_start) => s,
        _ => return keywords(&STATEMENT_KEYWORDS),
    };
    let tokens: Vec<Token> = Lexer::starting_at(text, chunk_start)
        .take_while(|t| t.end <= word_start)
        .filter(|t| t.kind != TokenKind::Comment)
        .collect();
    let word = |t: &Token| &text[t.start..t.end];
    let mut open: Vec<&str> = Vec::new();
    for t in &tokens {
        match t.kind {
            TokenKind::Open => open.push(word(t)),
            TokenKind::Close => {
                open.pop();
            }
            _ => {}
        }
    }
    // Words of the statement's head, before any bracket (`plan`, NAME, KIND, ...).
    let head: Vec<&str> = tokens
        .iter()
        .take_while(|t| t.kind != TokenKind::Open)
        .filter(|t| t.kind == TokenKind::Word)
        .map(word)
        .collect();
    match keyword {
        "plan" if open.is_empty() => match head.len() {
            2 => PLANNERS
                .iter()
                .map(|p| item(p.kind, CompletionItemKind::CLASS, p.summary, None))
                .collect(),
            3 => names(analysis, NameKind::Robot),
            _ => Vec::new(),
        },
        "plan" => {
            let keys = match open.as_slice() {
                ["{"] => ParamKeys::Plan(head.get(2).copied().unwrap_or("")),
                ["{", "{"] => ParamKeys::Drive,
                _ => return Vec::new(),
            };
            let previous = tokens
                .last()
                .filter(|t| t.kind == TokenKind::Word)
                .and_then(|t| keys.spec(word(t)));
            match previous {
                Some(spec) if spec.value.takes_word() => word_values(spec, keys, analysis),
                _ => param_keys(keys),
            }
        }
        "bench" => match open.as_slice() {
            ["{"] => match tokens
                .last()
                .filter(|t| t.kind == TokenKind::Word)
                .map(word)
            {
                Some("vary") => vary_keys(analysis),
                Some("limit") => match ParamKeys::Plan("").spec("limit") {
                    Some(spec) => word_values(spec, ParamKeys::Plan(""), analysis),
                    None => Vec::new(),
                },
                _ => keywords(BENCH_KEYS),
            },
            // `plans [a, b]`: the plans.
            ["{", "["] => {
                let list = tokens.iter().rposition(|t| t.kind == TokenKind::Open);
                match list
                    .and_then(|k| k.checked_sub(1))
                    .map(|k| word(&tokens[k]))
                {
                    Some("plans") => names(analysis, NameKind::Plan),
                    _ => Vec::new(),
                }
            }
            _ => Vec::new(),
        },
        // The robot kinds of the registry, each with its summary.
        "robot" if open.is_empty() && head.len() == 2 => crate::geometry::robots::ROBOTS
            .iter()
            .map(|m| item(m.keyword, CompletionItemKind::KEYWORD, m.summary, None))
            .collect(),
        // `param gap = |`: the distributions and `choice`.
        "param" if open.is_empty() && tokens.last().is_some_and(|t| word(t) == "=") => {
            keywords(&FAMILY_VALUE_WORDS)
        }
        // `robot car rect 4 2 steer |`: the steering models.
        "robot"
            if open.is_empty()
                && tokens
                    .last()
                    .is_some_and(|t| ROBOT_CLAUSE_KEYWORDS.contains(&word(t))) =>
        {
            keywords(MODEL_NAMES)
        }
        "world" if open == ["{"] => {
            let line_head = text[line_start..].split_whitespace().next();
            if first_on_line {
                keywords(&WORLD_ITEM_KEYWORDS)
            } else if line_head == Some("grid") {
                keywords(&GRID_OPTION_KEYWORDS)
            } else if line_head == Some("scatter") {
                // `scatter rocks 30 disk 0.3 in (0, 0) (20, 8) gap 0.1`
                keywords(&["disk", "rect", "in", "gap"])
            } else {
                Vec::new()
            }
        }
        "expect" => {
            // A selection `b.p[k = v].` is skipped back to its plan `p`.
            let mut n = tokens.len();
            let dot_at_cursor = n >= 2
                && tokens[n - 1].kind == TokenKind::Other
                && word(&tokens[n - 1]) == "."
                && tokens[n - 1].end == word_start;
            if dot_at_cursor && word(&tokens[n - 2]) == "]" {
                let mut depth = 0;
                let mut k = n - 2;
                loop {
                    match word(&tokens[k]) {
                        "]" => depth += 1,
                        "[" => depth -= 1,
                        _ => {}
                    }
                    if depth == 0 || k == 0 {
                        break;
                    }
                    k -= 1;
                }
                // Pretend the cursor follows `p.` directly.
                if depth == 0 && k >= 1 {
                    n = k + 1;
                }
            }
            let dotted = dot_at_cursor
                && n >= 2
                && tokens[n - 2].kind == TokenKind::Word
                && tokens[n - 2].end == tokens[n - 1].start;
            if dotted {
                let before = word(&tokens[n - 2]);
                // `BENCH.` → its plans; `PLAN.` and `BENCH.PLAN.` → metrics.
                let bench_dot = analysis.symbol(NameKind::Bench, before).is_some()
                    && !(n >= 3
                        && word(&tokens[n - 3]) == "."
                        && tokens[n - 3].end == tokens[n - 2].start);
                if bench_dot {
                    names(analysis, NameKind::Plan)
                } else {
                    metrics(analysis, before)
                }
            } else {
                let mut items = names(analysis, NameKind::Plan);
                let benches = names(analysis, NameKind::Bench);
                // Aggregates read benches' series: offered where there are benches.
                let aggregates = if benches.is_empty() {
                    &[][..]
                } else {
                    AGGREGATES
                };
                items.extend(benches);
                items.extend(aggregates.iter().map(|(a, _)| {
                    item(
                        a,
                        CompletionItemKind::FUNCTION,
                        "an aggregate of a bench series",
                        None,
                    )
                }));
                items.extend(keywords(&EXPRESSION_WORDS));
                items
            }
        }
        _ => Vec::new(),
    }
}

fn item(
    label: &str,
    kind: CompletionItemKind,
    detail: &str,
    doc: Option<String>,
) -> CompletionItem {
    CompletionItem {
        label: label.to_string(),
        kind: Some(kind),
        detail: Some(detail.to_string()).filter(|d| !d.is_empty()),
        documentation: doc.map(|value| {
            Documentation::MarkupContent(MarkupContent {
                kind: MarkupKind::Markdown,
                value,
            })
        }),
        ..CompletionItem::default()
    }
}

fn keywords(words: &[&str]) -> Vec<CompletionItem> {
    words
        .iter()
        .map(|w| item(w, CompletionItemKind::KEYWORD, "", None))
        .collect()
}

fn names(analysis: &Analysis, kind: NameKind) -> Vec<CompletionItem> {
    analysis
        .names(kind)
        .map(|s| {
            let detail = match kind {
                NameKind::Plan => analysis
                    .plan_kind(&s.name)
                    .map_or("plan".to_string(), |(k, _)| format!("plan ({k})")),
                _ => kind.word().to_string(),
            };
            item(&s.name, CompletionItemKind::VARIABLE, &detail, None)
        })
        .collect()
}

/// A parameter's documentation: its help, the values it takes, its default.
pub(crate) fn param_doc(spec: &ParamSpec) -> String {
    let default = match spec.default.text() {
        "" => "none".to_string(),
        text => format!("`{text}`"),
    };
    format!(
        "{}\n\nTakes {}. Default: {default}.",
        spec.help,
        spec.value.describe()
    )
}

/// A metric's documentation.
pub(crate) fn metric_doc(metric: &MetricSpec) -> String {
    let ty = match metric.ty {
        MetricType::Bool => "true/false",
        MetricType::Num => "a number",
    };
    format!("{} ({ty})", metric.help)
}

fn param_keys(keys: ParamKeys<'_>) -> Vec<CompletionItem> {
    let specs: Vec<&'static ParamSpec> = match keys {
        ParamKeys::Drive => crate::contract::schema::drive_params().collect(),
        ParamKeys::Plan(kind) => match registry::planner(kind) {
            Some(planner) => planner.all_params().collect(),
            None => return Vec::new(),
        },
    };
    specs
        .into_iter()
        .map(|s| {
            item(
                s.key,
                CompletionItemKind::FIELD,
                &s.value.describe(),
                Some(param_doc(s)),
            )
        })
        .collect()
}

fn word_values(spec: &ParamSpec, keys: ParamKeys<'_>, analysis: &Analysis) -> Vec<CompletionItem> {
    if spec.value == ValueSpec::ObstacleName {
        return names(analysis, NameKind::Obstacle);
    }
    let limits = match (spec.value, keys) {
        (ValueSpec::Limit, ParamKeys::Plan(kind)) => registry::planner(kind).map(|p| p.limits),
        _ => None,
    };
    spec.value
        .words()
        .iter()
        .filter(|w| limits.is_none_or(|l| l.contains(w)))
        .map(|w| {
            let detail = format!("a value of `{}`", spec.key);
            item(w, CompletionItemKind::ENUM_MEMBER, &detail, None)
        })
        .collect()
}

/// After `vary` in a bench: the parameters of the file's plans' planners.
fn vary_keys(analysis: &Analysis) -> Vec<CompletionItem> {
    let mut seen: Vec<&str> = Vec::new();
    let mut items = Vec::new();
    for plan in analysis.names(NameKind::Plan) {
        let Some(planner) = analysis
            .plan_kind(&plan.name)
            .and_then(|(kind, _)| registry::planner(kind))
        else {
            continue;
        };
        for spec in planner.all_params() {
            if !seen.contains(&spec.key) {
                seen.push(spec.key);
                items.push(item(
                    spec.key,
                    CompletionItemKind::FIELD,
                    &spec.value.describe(),
                    Some(param_doc(spec)),
                ));
            }
        }
    }
    items
}

fn metrics(analysis: &Analysis, plan: &str) -> Vec<CompletionItem> {
    let Some((kind, drives)) = analysis.plan_kind(plan) else {
        return Vec::new();
    };
    let Some(planner) = registry::planner(kind) else {
        return Vec::new();
    };
    let drive = DRIVE_METRICS.iter().filter(|_| drives);
    planner
        .all_metrics()
        .chain(drive)
        .map(|m| {
            let ty = match m.ty {
                MetricType::Bool => "true/false",
                MetricType::Num => "number",
            };
            item(m.name, CompletionItemKind::FIELD, ty, Some(metric_doc(m)))
        })
        .collect()
}
