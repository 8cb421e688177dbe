//! What the server knows of one open document: the loader's parse of it and
//! of its includes (open documents' text first), the diagnostics of `scen
//! check`, and the names declared and used, with their spans in every file.

use std::path::Path;
use std::sync::Arc;

use crate::contract::schema::ValueSpec;
use crate::diagnostics::{Diag, FileId, SourceMap, Span};
use crate::scenario::grouping::{ParamKeys, group_params};
use crate::scenario::loader::{Overlay, Parsed, SourcedStmt, parse_scenario};
use crate::syntax::ast::{Expr, ExprKind, ParamToken, Stmt, ValueKind, WorldItem};

/// What a name names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum NameKind {
    Obstacle,
    Robot,
    Plan,
    Bench,
    /// A family's `param` (SPEC 2.8).
    Param,
}

impl NameKind {
    pub(crate) fn word(self) -> &'static str {
        match self {
            NameKind::Obstacle => "obstacle",
            NameKind::Robot => "robot",
            NameKind::Plan => "plan",
            NameKind::Bench => "bench",
            NameKind::Param => "param",
        }
    }
}

/// One declaration and its uses.
#[derive(Clone, Debug)]
pub(crate) struct Symbol {
    pub kind: NameKind,
    pub name: String,
    /// The name in its declaration.
    pub decl: Span,
    /// The whole declaring statement or item.
    pub full: Span,
    pub uses: Vec<Span>,
}

/// A document analysed as the main file of a scenario (it is [`FileId`] 0).
pub(crate) struct Analysis {
    pub sources: SourceMap,
    pub statements: Vec<SourcedStmt>,
    pub includes: Vec<(Span, FileId)>,
    /// The diagnostics `scen check` prints for this file, sorted.
    pub diags: Vec<Diag>,
    pub symbols: Vec<Symbol>,
}

impl Analysis {
    /// Loads `path` as `scen check` does, with the open documents' text.
    pub(crate) fn new(path: &Path, overlay: Overlay<'_>) -> Analysis {
        let Parsed {
            sources,
            statements,
            includes,
            maps,
            mut diags,
        } = parse_scenario(path, None, overlay);
        if !diags.iter().any(Diag::is_error) {
            // A family is analysed as `scen check` does: its sample 0.
            let analysed = crate::scenario::loader::analyze_sample(
                path,
                statements.clone(),
                sources.clone(),
                maps,
                crate::scenario::SampleChoice::default(),
                &[],
            );
            if let Err(failure) = analysed {
                diags = failure.diags;
            }
        }
        crate::diagnostics::sort_diags(&mut diags);
        let symbols = symbols(&statements);
        Analysis {
            sources,
            statements,
            includes,
            diags,
            symbols,
        }
    }

    /// The statements of file 0 (this document).
    pub(crate) fn own_statements(&self) -> impl Iterator<Item = &Stmt> {
        self.statements
            .iter()
            .filter(|s| s.in_main_file)
            .map(|s| &s.stmt)
    }

    pub(crate) fn text(&self, file: FileId) -> Option<Arc<str>> {
        self.sources.get(file).map(|f| f.text.clone())
    }

    /// The declaration of a name of `kind`.
    pub(crate) fn symbol(&self, kind: NameKind, name: &str) -> Option<&Symbol> {
        self.symbols
            .iter()
            .find(|s| s.kind == kind && s.name == name)
    }

    /// The symbol whose declaration or a use covers `offset` in `file`.
    pub(crate) fn symbol_at(&self, file: FileId, offset: usize) -> Option<&Symbol> {
        let covers = |s: &Span| s.file == file && s.start <= offset && offset <= s.end;
        self.symbols
            .iter()
            .find(|s| covers(&s.decl) || s.uses.iter().any(covers))
    }

    /// The planner kind of plan `name`, and whether it drives.
    pub(crate) fn plan_kind(&self, name: &str) -> Option<(&str, bool)> {
        self.statements.iter().find_map(|s| match &s.stmt {
            Stmt::Plan(p) if p.name.value == name => {
                let drives = p
                    .body
                    .iter()
                    .any(|t| matches!(t, ParamToken::Word(w) if w.value == "drive"));
                Some((p.kind.value.as_str(), drives))
            }
            _ => None,
        })
    }

    /// The names of the declarations of `kind`.
    pub(crate) fn names(&self, kind: NameKind) -> impl Iterator<Item = &Symbol> {
        self.symbols.iter().filter(move |s| s.kind == kind)
    }
}

/// Declarations (first one of each name) and uses, over all files.
fn symbols(statements: &[SourcedStmt]) -> Vec<Symbol> {
    let mut symbols: Vec<Symbol> = Vec::new();
    let mut declare = |kind, name: &str, decl: Span, full: Span| {
        if !symbols.iter().any(|s| s.kind == kind && s.name == name) {
            symbols.push(Symbol {
                kind,
                name: name.to_string(),
                decl,
                full,
                uses: Vec::new(),
            });
        }
    };
    for s in statements {
        match &s.stmt {
            Stmt::World(w) => {
                for item in &w.items {
                    match item {
                        WorldItem::Obstacle(o) => {
                            if let Some(n) = &o.name {
                                declare(NameKind::Obstacle, &n.value, n.span, o.span);
                            }
                        }
                        // Its hover shows the whole item: the route and times.
                        WorldItem::Moving(m) => {
                            declare(NameKind::Obstacle, &m.name.value, m.name.span, m.span)
                        }
                        _ => {}
                    }
                }
            }
            Stmt::Robot(r) => declare(NameKind::Robot, &r.name.value, r.name.span, r.span),
            Stmt::Plan(p) => declare(NameKind::Plan, &p.name.value, p.name.span, p.span),
            Stmt::Bench(b) => declare(NameKind::Bench, &b.name.value, b.name.span, b.span),
            Stmt::Param(p) => declare(NameKind::Param, &p.name.value, p.name.span, p.span),
            _ => {}
        }
    }
    let mut uses: Vec<(NameKind, &str, Span)> = Vec::new();
    // A param's name wherever a number may be computed: in expressions, as
    // a lone word of a body or a list (only declared params get the uses).
    for s in statements {
        param_uses(&s.stmt, &mut uses);
    }
    for s in statements {
        match &s.stmt {
            Stmt::Plan(p) => {
                uses.push((NameKind::Robot, &p.robot.value, p.robot.span));
                let keys = ParamKeys::Plan(&p.kind.value);
                for group in group_params(&p.body, keys) {
                    let is_name = group
                        .spec
                        .is_some_and(|spec| spec.value == ValueSpec::ObstacleName);
                    if let (true, Some(ParamToken::Word(w))) =
                        (is_name, p.body.get(group.tokens.start + 1))
                    {
                        uses.push((NameKind::Obstacle, &w.value, w.span));
                    }
                }
            }
            Stmt::Expect(e) => expr_uses(e, &mut uses),
            // `plans [a, b]` names plans.
            Stmt::Bench(b) => {
                for pair in b.body.windows(2) {
                    if let [ParamToken::Word(key), ParamToken::Value(list)] = pair
                        && key.value == "plans"
                        && let ValueKind::List(items) = &list.kind
                    {
                        for item in items {
                            if let ValueKind::Word(name) = &item.kind {
                                uses.push((NameKind::Plan, name, item.span));
                            }
                        }
                    }
                }
            }
            _ => {}
        }
    }
    for (kind, name, span) in uses {
        if let Some(sym) = symbols
            .iter_mut()
            .find(|s| s.kind == kind && s.name == name)
        {
            sym.uses.push(span);
        }
    }
    symbols
}

/// The names a statement may use as params: in expressions, and as lone
/// words of a body or a list (only a declared param's name gets its uses).
fn param_uses<'s>(stmt: &'s Stmt, out: &mut Vec<(NameKind, &'s str, Span)>) {
    fn value<'v>(v: &'v crate::syntax::ast::Value, out: &mut Vec<(NameKind, &'v str, Span)>) {
        match &v.kind {
            ValueKind::Calc { expr, .. } => names(expr, out),
            ValueKind::Word(w) => out.push((NameKind::Param, w, v.span)),
            ValueKind::Tuple(items) | ValueKind::List(items) => {
                items.iter().for_each(|i| value(i, out));
            }
            _ => {}
        }
    }
    fn names<'e>(e: &'e Expr, out: &mut Vec<(NameKind, &'e str, Span)>) {
        e.walk(&mut |n| {
            if let ExprKind::Name(name) = &n.kind {
                out.push((NameKind::Param, &name.value, name.span));
            }
        });
    }
    stmt.each_value(&mut |v, _| value(v, out));
    match stmt {
        Stmt::Plan(crate::syntax::ast::PlanDecl { body, .. })
        | Stmt::Bench(crate::syntax::ast::BenchDecl { body, .. }) => {
            ParamToken::flatten(body, &mut |t| {
                if let ParamToken::Word(w) = t {
                    out.push((NameKind::Param, &w.value, w.span));
                }
            });
        }
        Stmt::Expect(e) | Stmt::Require { condition: e, .. } => names(e, out),
        _ => {}
    }
}

fn expr_uses<'e>(e: &'e Expr, out: &mut Vec<(NameKind, &'e str, Span)>) {
    e.walk(&mut |e| match &e.kind {
        ExprKind::Metric { plan, .. } => out.push((NameKind::Plan, &plan.value, plan.span)),
        ExprKind::Series { bench, plan, .. } => {
            out.push((NameKind::Bench, &bench.value, bench.span));
            out.push((NameKind::Plan, &plan.value, plan.span));
        }
        _ => {}
    });
}
