//! Hover, go to definition, references and the outline, from the AST of a
//! document and of its includes (spans carry their file).

use crate::contract::schema::{DRIVE_METRICS, ValueSpec};
use crate::diagnostics::{Span, Spanned};
use crate::planners::registry;
use crate::scenario::grouping::{ParamKeys, group_params};
use crate::syntax::ast::{Expr, ExprKind, ParamToken, Stmt, WorldItem};

use super::analysis::{Analysis, NameKind, Symbol};
use super::complete::{metric_doc, param_doc};

/// What is under the cursor in file 0.
enum Target<'a> {
    Symbol(&'a Symbol),
    Planner(&'a str),
    Param(&'static crate::contract::schema::ParamSpec, &'a str),
    Metric { plan: &'a str, metric: &'a str },
    Include(Span),
}

/// The hover text (Markdown) at `offset` of the document, and the span it
/// is about.
pub(crate) fn hover(a: &Analysis, offset: usize) -> Option<(String, Span)> {
    let (target, span) = target_at(a, offset)?;
    let text = match target {
        Target::Symbol(s) => declaration(a, s),
        Target::Planner(kind) => {
            let p = registry::planner(kind)?;
            let robots: Vec<&str> = p.robots.iter().map(|r| r.name()).collect();
            format!(
                "`{}` — {}\n\nRobots: {}. Limits: {}.",
                p.kind,
                p.summary,
                robots.join(", "),
                p.limits.join(", ")
            )
        }
        Target::Param(spec, owner) => format!("`{}` ({owner})\n\n{}", spec.key, param_doc(spec)),
        Target::Metric { plan, metric } => {
            let (kind, drives) = a.plan_kind(plan)?;
            let planner = registry::planner(kind)?;
            let drive = DRIVE_METRICS.iter().filter(|_| drives);
            let m = planner
                .all_metrics()
                .chain(drive)
                .find(|m| m.name == metric)?;
            format!(
                "`{plan}.{metric}` (metric of `{kind}`)\n\n{}",
                metric_doc(m)
            )
        }
        Target::Include(_) => return None,
    };
    Some((text, span))
}

/// Where the name (or the include) at `offset` is declared.
pub(crate) fn definition(a: &Analysis, offset: usize) -> Option<Span> {
    match target_at(a, offset)?.0 {
        Target::Symbol(s) => Some(s.decl),
        Target::Include(path) => a
            .includes
            .iter()
            .find(|(span, _)| *span == path)
            .map(|&(_, file)| Span::new(file, 0, 0)),
        _ => None,
    }
}

/// The symbol at `offset`, for references.
pub(crate) fn symbol_at(a: &Analysis, offset: usize) -> Option<&Symbol> {
    match target_at(a, offset)?.0 {
        Target::Symbol(s) => Some(s),
        _ => None,
    }
}

fn declaration(a: &Analysis, s: &Symbol) -> String {
    let full = a.sources.snippet(s.full);
    let shown = match s.kind {
        // A plan's head: `plan NAME KIND ROBOT`.
        NameKind::Plan => full.split('{').next().unwrap_or(full).trim_end(),
        _ => full,
    };
    let mut text = format!("```scen\n{shown}\n```");
    if s.decl.file != 0 {
        text.push_str(&format!(
            "\n\nDeclared in `{}`.",
            a.sources.location(s.decl)
        ));
    }
    if s.kind == NameKind::Plan
        && let Some(p) = a.plan_kind(&s.name).and_then(|(k, _)| registry::planner(k))
    {
        text.push_str(&format!("\n\n`{}`: {}", p.kind, p.summary));
    }
    text
}

fn inside(span: Span, offset: usize) -> bool {
    span.file == 0 && span.start <= offset && offset <= span.end
}

fn target_at(a: &Analysis, offset: usize) -> Option<(Target<'_>, Span)> {
    if let Some(&(span, _)) = a.includes.iter().find(|(s, _)| inside(*s, offset)) {
        return Some((Target::Include(span), span));
    }
    for stmt in a.own_statements() {
        match stmt {
            Stmt::Plan(p) if inside(p.span, offset) => {
                if inside(p.kind.span, offset) {
                    return Some((Target::Planner(&p.kind.value), p.kind.span));
                }
                if let Some(found) = in_body(a, &p.body, ParamKeys::Plan(&p.kind.value), offset) {
                    return Some(found);
                }
            }
            Stmt::Expect(e) if inside(e.span, offset) => {
                if let Some((plan, metric)) = metric_at(e, offset)
                    && inside(metric.span, offset)
                {
                    let target = Target::Metric {
                        plan: &plan.value,
                        metric: &metric.value,
                    };
                    return Some((target, metric.span));
                }
            }
            _ => {}
        }
    }
    let symbol = a.symbol_at(0, offset)?;
    let span = std::iter::once(symbol.decl)
        .chain(symbol.uses.iter().copied())
        .find(|s| inside(*s, offset))?;
    Some((Target::Symbol(symbol), span))
}

/// A key or a word value in a plan body (or a nested block) at `offset`.
fn in_body<'a>(
    a: &'a Analysis,
    body: &'a [ParamToken],
    keys: ParamKeys<'a>,
    offset: usize,
) -> Option<(Target<'a>, Span)> {
    let owner = match keys {
        ParamKeys::Plan(kind) => kind,
        ParamKeys::Drive => "drive",
    };
    for group in group_params(body, keys) {
        for (k, token) in body[group.tokens.clone()].iter().enumerate() {
            match token {
                ParamToken::Block { tokens, span } if inside(*span, offset) => {
                    return in_body(a, tokens, keys.nested(), offset);
                }
                ParamToken::Word(w) if inside(w.span, offset) => {
                    let spec = group.spec?;
                    if k > 0 && spec.value == ValueSpec::ObstacleName {
                        let s = a.symbol(NameKind::Obstacle, &w.value)?;
                        return Some((Target::Symbol(s), w.span));
                    }
                    return Some((Target::Param(spec, owner), w.span));
                }
                _ => {}
            }
        }
    }
    None
}

/// The metric reference `PLAN.METRIC` of `e` that covers `offset`.
fn metric_at(e: &Expr, offset: usize) -> Option<(&Spanned<String>, &Spanned<String>)> {
    if !inside(e.span, offset) {
        return None;
    }
    match &e.kind {
        ExprKind::Metric { plan, metric } | ExprKind::Series { plan, metric, .. } => {
            Some((plan, metric))
        }
        _ => e.children().into_iter().find_map(|c| metric_at(c, offset)),
    }
}

/// One entry of the outline.
pub(crate) struct Outline {
    pub name: String,
    pub detail: String,
    pub kind: OutlineKind,
    pub full: Span,
    pub name_span: Span,
    pub children: Vec<Outline>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum OutlineKind {
    World,
    Obstacle,
    Robot,
    Plan,
    Bench,
}

/// The document's outline: the world with its obstacles (unnamed ones by
/// the names reports give them), the robots, the plans. A new statement
/// kind with a name (`bench`) is one more arm.
pub(crate) fn outline(a: &Analysis) -> Vec<Outline> {
    let mut out = Vec::new();
    let mut index = 0;
    for s in &a.statements {
        match &s.stmt {
            Stmt::World(w) => {
                let mut children = Vec::new();
                for item in &w.items {
                    let WorldItem::Obstacle(o) = item else {
                        continue;
                    };
                    index += 1;
                    let (name, name_span) = match &o.name {
                        Some(n) => (n.value.clone(), n.span),
                        None => (o.kind.value.unnamed(index), o.kind.span),
                    };
                    children.push(Outline {
                        name,
                        detail: o.kind.value.keyword().to_string(),
                        kind: OutlineKind::Obstacle,
                        full: o.span,
                        name_span,
                        children: Vec::new(),
                    });
                }
                if s.in_main_file {
                    out.push(Outline {
                        name: "world".into(),
                        detail: String::new(),
                        kind: OutlineKind::World,
                        full: w.span,
                        name_span: w.keyword,
                        children,
                    });
                }
            }
            Stmt::Robot(r) if s.in_main_file => out.push(Outline {
                name: r.name.value.clone(),
                detail: "robot".into(),
                kind: OutlineKind::Robot,
                full: r.span,
                name_span: r.name.span,
                children: Vec::new(),
            }),
            Stmt::Plan(p) if s.in_main_file => out.push(Outline {
                name: p.name.value.clone(),
                detail: format!("{} {}", p.kind.value, p.robot.value),
                kind: OutlineKind::Plan,
                full: p.span,
                name_span: p.name.span,
                children: Vec::new(),
            }),
            Stmt::Bench(b) if s.in_main_file => out.push(Outline {
                name: b.name.value.clone(),
                detail: "bench".into(),
                kind: OutlineKind::Bench,
                full: b.span,
                name_span: b.name.span,
                children: Vec::new(),
            }),
            _ => {}
        }
    }
    out
}
