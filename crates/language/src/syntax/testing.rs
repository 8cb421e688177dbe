//! Helpers shared by the unit tests of the parser's modules.

use super::ast::{Expr, ExprKind, ParamToken, Stmt, Value, ValueKind, WorldItem};
use super::parse;
use crate::diagnostics::{Diag, Span};

pub(super) fn parse_ok(text: &str) -> Vec<Stmt> {
    let (file, diags) = parse(text, 0);
    assert!(
        diags.is_empty(),
        "unexpected diagnostics for {text:?}: {diags:#?}"
    );
    file.statements
}

pub(super) fn errors(text: &str) -> Vec<Diag> {
    let (_, diags) = parse(text, 0);
    assert!(!diags.is_empty(), "expected an error for {text:?}");
    diags
}

pub(super) fn line_of(text: &str, span: Span) -> usize {
    text[..span.start].matches('\n').count() + 1
}

pub(super) fn expr(text: &str) -> Expr {
    match parse_ok(&format!("expect {text}")).pop() {
        Some(Stmt::Expect(e)) => e,
        other => panic!("not an expect: {other:?}"),
    }
}

/// An expression tree in prefix form, for compact assertions.
pub(super) fn sexp(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Number(x) => format!("{x}"),
        ExprKind::Percent(x) => format!("{x}%"),
        ExprKind::Bool(b) => format!("{b}"),
        ExprKind::Name(n) => n.value.clone(),
        ExprKind::Metric { plan, metric } => format!("{}.{}", plan.value, metric.value),
        ExprKind::Neg(a) => format!("(neg {})", sexp(a)),
        ExprKind::Not(a) => format!("(not {})", sexp(a)),
        ExprKind::Arith { op, lhs, rhs } => {
            format!("({} {} {})", op.symbol(), sexp(lhs), sexp(rhs))
        }
        ExprKind::Compare { op, lhs, rhs } => {
            format!("({} {} {})", op.symbol(), sexp(lhs), sexp(rhs))
        }
        ExprKind::Approx { lhs, rhs, tol } => {
            format!("(~ {} {} {})", sexp(lhs), sexp(rhs), sexp(tol))
        }
        ExprKind::And(a, b) => format!("(and {} {})", sexp(a), sexp(b)),
        ExprKind::Or(a, b) => format!("(or {} {})", sexp(a), sexp(b)),
        ExprKind::Where(a, b) => format!("(where {} {})", sexp(a), sexp(b)),
        ExprKind::Series {
            bench,
            plan,
            select,
            metric,
        } => {
            let sel: Vec<String> = select
                .iter()
                .map(|s| format!("{}={}", s.key.value, crate::checks::value_text(&s.value)))
                .collect();
            format!(
                "{}.{}[{}].{}",
                bench.value,
                plan.value,
                sel.join(","),
                metric.value
            )
        }
        ExprKind::Call { function, args } => format!(
            "({} {})",
            function.value,
            args.iter().map(sexp).collect::<Vec<_>>().join(" ")
        ),
    }
}

pub(super) fn snippet(text: &str, span: Span) -> &str {
    &text[span.start..span.end]
}

pub(super) fn number(v: &Value) -> f64 {
    match v.kind {
        ValueKind::Number(x) => x,
        ref other => panic!("not a number: {other:?}"),
    }
}

pub(super) fn world_items(text: &str) -> Vec<WorldItem> {
    match parse_ok(text).pop() {
        Some(Stmt::World(w)) => w.items,
        other => panic!("not a world: {other:?}"),
    }
}

pub(super) fn plan_body(text: &str) -> Vec<ParamToken> {
    match parse_ok(text).pop() {
        Some(Stmt::Plan(p)) => p.body,
        other => panic!("not a plan: {other:?}"),
    }
}

pub(super) const APARTMENT: &str = r#"scenario "Apartment: the 8x1 rod"   # title
include "common.scen"

world {
  bounds (0, 0) (32, 30)                  # min corner, max corner (required)
  rect    B1 (0, 18) (10, 19)             # two opposite corners
  polygon P1 [(1,1), (3,1), (2,4)]        # simple polygon, either orientation
  segment W1 (26, 10) (26, 22)            # zero-thickness wall
  disk    C1 (5, 5) 1.5                   # centre, radius
  grid    G  "maps/arena.map" cell 1 origin (0, 0)      # MovingAI .map file
  grid    F  cell 0.5 origin (0, 0) {                   # inline rows, top row first
    "....##...."
    "..3......."
  }
}

robot rod  polygon [(0,0), (8,0), (8,1), (0,1)]   # convex, in the robot frame
robot box  rect 2 1
robot dot  disk 0.5
robot p    point

plan offline astar rod {
  start (4, 24, 0deg)  goal (28, 4, 90deg)
  cell 1 layers auto
  limit expansions 100000 time 2s
  drive unicycle { dt 0.02 max_speed 1.5 }
}

expect offline.found
expect offline.collision_free
expect offline.cost <= 90
expect offline.expanded < 6000 and offline.nodes >= 10
expect not tight.found
expect live.traveled <= 50 * offline.length
expect vg.length ~ 27.3137 +- 0.001
expect cover.coverage == 100%
"#;
