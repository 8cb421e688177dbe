//! `expect` expressions: an `expr` pair is a flat sequence of operands and
//! operators, given its tree here by precedence climbing, with the binding
//! powers below.

use super::ast::{ArithOp, CompareOp, Expr, ExprKind, Selection, ValueKind};
use super::builder::{Builder, P, children};
use super::parser::Rule;
use crate::diagnostics::{Diag, Span};

/// The tallest `expect` expression tree accepted. Long operator chains build
/// left-deep trees, and every later pass walks them recursively.
const MAX_EXPR_HEIGHT: usize = 256;

/// Binding powers of `expect` operators, loosest first. `where` filters a
/// whole series (`b.p.length where b.p.found`); `not` binds looser than a
/// comparison (`not a < b` is `not (a < b)`), unary `-` tightest.
const WHERE_POWER: u8 = 1;
const OR_POWER: u8 = 2;
const AND_POWER: u8 = 3;
const NOT_POWER: u8 = 4;
const COMPARE_POWER: u8 = 5;
const ADD_POWER: u8 = 6;
const MUL_POWER: u8 = 7;
const NEG_POWER: u8 = 8;

/// The binding power of an infix `operator` token. `+-` gets a comparison's
/// power so that a stray one stops the operand before it and is reported.
fn infix_power(operator: &str) -> u8 {
    match operator {
        "where" => WHERE_POWER,
        "or" => OR_POWER,
        "and" => AND_POWER,
        "+" | "-" => ADD_POWER,
        "*" | "/" => MUL_POWER,
        _ => COMPARE_POWER,
    }
}

/// An expression under construction.
struct Built {
    expr: Expr,
    /// The height of its tree, bounded by [`MAX_EXPR_HEIGHT`].
    height: usize,
    /// A comparison not in parentheses: another comparison may not follow it.
    comparison: bool,
}

impl Built {
    fn new(expr: Expr, height: usize) -> Self {
        Built {
            expr,
            height,
            comparison: false,
        }
    }
}

impl Builder<'_, '_> {
    /// The expression of an `expect` statement, from its `expr` pair; `None`
    /// when it is in error (the error is reported).
    pub(super) fn expect_expr(&mut self, pair: P<'_>) -> Option<Expr> {
        Some(self.expression(pair, 0)?.expr)
    }

    /// An `expr` pair: a flat sequence of operands and operators, given its
    /// tree by precedence climbing. `depth` counts the enclosing parentheses
    /// and operators, for [`MAX_EXPR_HEIGHT`].
    fn expression(&mut self, pair: P<'_>, depth: usize) -> Option<Built> {
        let mut tokens = Vec::new();
        for child in pair.into_inner() {
            match child.as_rule() {
                Rule::operand => tokens.extend(child.into_inner()),
                _ => tokens.push(child),
            }
        }
        let mut pos = 0;
        let built = self.climb(&tokens, &mut pos, 0, depth)?;
        debug_assert_eq!(pos, tokens.len(), "every token of the expression is used");
        Some(built)
    }

    /// Parses `tokens[*pos..]` up to the first operator that binds no tighter
    /// than `min_power` (see [`infix_power`]).
    fn climb(
        &mut self,
        tokens: &[P<'_>],
        pos: &mut usize,
        min_power: u8,
        depth: usize,
    ) -> Option<Built> {
        let first = &tokens[*pos];
        *pos += 1;
        let first_span = self.span(first);
        self.check_height(depth, first_span)?;
        let mut lhs = match first.as_rule() {
            Rule::prefix => {
                let (power, negate) = if first.as_str() == "-" {
                    (NEG_POWER, true)
                } else {
                    (NOT_POWER, false)
                };
                let operand = self.climb(tokens, pos, power, depth + 1)?;
                let span = first_span.to(operand.expr.span);
                let inner = Box::new(operand.expr);
                let kind = if negate {
                    ExprKind::Neg(inner)
                } else {
                    ExprKind::Not(inner)
                };
                Built::new(Expr { kind, span }, operand.height + 1)
            }
            Rule::primary => self.primary(first.clone(), depth)?,
            rule => unreachable!("grammar guarantees an operand, got {rule:?}"),
        };
        while let Some(op) = tokens.get(*pos) {
            let op_span = self.span(op);
            let text = op.as_str();
            let power = infix_power(text);
            if power <= min_power {
                break;
            }
            *pos += 1;
            if matches!(text, "+-" | "±") {
                self.diags.push(
                    Diag::error("scen::syntax::expected", format!("`{text}` without `~`"))
                        .at(op_span, "a tolerance needs an approximate comparison")
                        .help("approximate equality is written `A ~ B +- TOL`"),
                );
                return None;
            }
            let comparison = power == COMPARE_POWER;
            if comparison && lhs.comparison {
                self.diags.push(
                    Diag::error(
                        "scen::syntax::chained_comparison",
                        "comparisons cannot be chained",
                    )
                    .at(op_span, "a second comparison")
                    .with_related(lhs.expr.span, "the first comparison")
                    .help("join two comparisons with `and`: `a < b and b < c`"),
                );
                return None;
            }
            let rhs = self.climb(tokens, pos, power, depth + 1)?;
            let (lhs_expr, rhs_expr) = (Box::new(lhs.expr), Box::new(rhs.expr));
            let mut height = lhs.height.max(rhs.height);
            let kind = match text {
                "where" => ExprKind::Where(lhs_expr, rhs_expr),
                "or" => ExprKind::Or(lhs_expr, rhs_expr),
                "and" => ExprKind::And(lhs_expr, rhs_expr),
                "~" => {
                    let tolerance = tokens
                        .get(*pos)
                        .filter(|t| matches!(t.as_str(), "+-" | "±"));
                    if tolerance.is_none() {
                        self.diags.push(
                            Diag::error(
                                "scen::syntax::expected",
                                "expected `+-` and a tolerance after `A ~ B`",
                            )
                            .at(op_span, "an approximate comparison without a tolerance")
                            .help("approximate equality needs a tolerance: `A ~ B +- TOL`"),
                        );
                        return None;
                    }
                    *pos += 1;
                    let tol = self.climb(tokens, pos, COMPARE_POWER, depth + 1)?;
                    height = height.max(tol.height);
                    ExprKind::Approx {
                        lhs: lhs_expr,
                        rhs: rhs_expr,
                        tol: Box::new(tol.expr),
                    }
                }
                _ if comparison => {
                    let op = match text {
                        "<" => CompareOp::Lt,
                        "<=" => CompareOp::Le,
                        ">" => CompareOp::Gt,
                        ">=" => CompareOp::Ge,
                        "==" => CompareOp::Eq,
                        _ => CompareOp::Ne,
                    };
                    ExprKind::Compare {
                        op,
                        lhs: lhs_expr,
                        rhs: rhs_expr,
                    }
                }
                _ => {
                    let op = match text {
                        "+" => ArithOp::Add,
                        "-" => ArithOp::Sub,
                        "*" => ArithOp::Mul,
                        _ => ArithOp::Div,
                    };
                    ExprKind::Arith {
                        op,
                        lhs: lhs_expr,
                        rhs: rhs_expr,
                    }
                }
            };
            let span = first_span.to(self.span(&tokens[*pos - 1]));
            let height = self.check_height(height + 1, span)?;
            lhs = Built {
                expr: Expr { kind, span },
                height,
                comparison,
            };
        }
        Some(lhs)
    }

    /// A `primary` pair: a number, `true`, `false`, `PLAN.METRIC` or `( expr )`.
    fn primary(&mut self, pair: P<'_>, depth: usize) -> Option<Built> {
        let inner = pair
            .into_inner()
            .next()
            .expect("grammar guarantees a primary");
        let span = self.span(&inner);
        let kind = match inner.as_rule() {
            Rule::paren => {
                let expr = children(inner)
                    .next()
                    .expect("grammar guarantees `( expr )`");
                let built = self.expression(expr, depth + 1)?;
                // The span includes the parentheses, so an enclosing
                // expression's span covers them too.
                return Some(Built::new(
                    Expr {
                        kind: built.expr.kind,
                        span,
                    },
                    built.height,
                ));
            }
            Rule::expr_number => {
                match self.quantity(inner) {
                    ValueKind::Percent(x) => ExprKind::Percent(x),
                    // Angle metrics (`turn`) are in radians.
                    ValueKind::Number(x) => ExprKind::Number(x),
                    ValueKind::Angle(a) => ExprKind::Number(a.radians()),
                    ValueKind::Duration(seconds) => {
                        self.diags.push(
                        Diag::error("scen::syntax::unit_not_allowed", "a duration cannot appear in an expectation")
                            .at(span, "a duration")
                            .help(format!(
                                "metrics are plain numbers (`time_ms` is in milliseconds): write `{}`",
                                seconds * 1000.0
                            )),
                    );
                        ExprKind::Number(seconds)
                    }
                    other => unreachable!("a number token is a quantity, got {other:?}"),
                }
            }
            Rule::name_ref => ExprKind::Name(self.ident(&inner)),
            Rule::kw_true => ExprKind::Bool(true),
            Rule::kw_false => ExprKind::Bool(false),
            Rule::metric => {
                let mut names = Vec::new();
                let mut select = None;
                for part in inner.into_inner() {
                    match part.as_rule() {
                        Rule::name_part => names.push(self.ident(&part)),
                        Rule::selector => select = Some(self.selector(part)),
                        rule => unreachable!("grammar guarantees a metric part, got {rule:?}"),
                    }
                }
                let mut names = names.into_iter();
                let mut next = || names.next().expect("grammar guarantees two or three names");
                let (first, second) = (next(), next());
                match names.next() {
                    None => ExprKind::Metric {
                        plan: first,
                        metric: second,
                    },
                    Some(metric) => ExprKind::Series {
                        bench: first,
                        plan: second,
                        select: select.unwrap_or_default(),
                        metric,
                    },
                }
            }
            Rule::call => {
                let mut parts = children(inner);
                let function = self.ident(&parts.next().expect("grammar guarantees a function"));
                let mut args = Vec::new();
                let mut height = 1;
                for arg in parts {
                    let built = self.expression(arg, depth + 1)?;
                    height = height.max(built.height + 1);
                    args.push(built.expr);
                }
                let height = self.check_height(height, span)?;
                return Some(Built::new(
                    Expr {
                        kind: ExprKind::Call { function, args },
                        span,
                    },
                    height,
                ));
            }
            rule => unreachable!("grammar guarantees a primary, got {rule:?}"),
        };
        Some(Built::new(Expr { kind, span }, 1))
    }

    /// `[KEY = VALUE, ...]` of a series.
    fn selector(&mut self, pair: P<'_>) -> Vec<Selection> {
        children(pair)
            .map(|selection| {
                let span = self.span(&selection);
                let mut parts = children(selection);
                let key = self.ident(&parts.next().expect("grammar guarantees a key"));
                let value = parts
                    .find(|p| p.as_rule() != Rule::equals)
                    .expect("grammar guarantees a value");
                Selection {
                    key,
                    value: self.value(value),
                    span,
                }
            })
            .collect()
    }

    pub(super) fn check_height(&mut self, height: usize, span: Span) -> Option<usize> {
        if height <= MAX_EXPR_HEIGHT {
            return Some(height);
        }
        if !self.expr_too_deep {
            self.expr_too_deep = true;
            self.diags.push(
                Diag::error(
                    "scen::syntax::too_deep",
                    format!("expression nested more than {MAX_EXPR_HEIGHT} operators deep"),
                )
                .at(span, "this expression is too deep")
                .help("split it into several `expect` statements"),
            );
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::ast::Stmt;
    use crate::syntax::testing::{errors, expr, parse_ok, sexp, snippet};

    #[test]
    fn series_aggregates_and_where() {
        assert_eq!(sexp(&expr("b.p.time_ms")), "b.p[].time_ms");
        assert_eq!(
            sexp(&expr(
                "median(b.p[weight = 5, sample = corner].expanded) < 0.5 * x.cost"
            )),
            "(< (median b.p[weight=5,sample=corner].expanded) (* 0.5 x.cost))"
        );
        assert_eq!(
            sexp(&expr("quantile(b.p.time_ms, 0.9) < 10")),
            "(< (quantile b.p[].time_ms 0.9) 10)"
        );
        // `where` binds loosest: the whole condition filters the series.
        assert_eq!(
            sexp(&expr(
                "mean(b.p.length where b.p.found and b.p.collision_free)"
            )),
            "(mean (where b.p[].length (and b.p[].found b.p[].collision_free)))"
        );
        assert_eq!(
            sexp(&expr("b.p[start = (1, 2)].cost == 3")),
            "(== b.p[start=(1, 2)].cost 3)"
        );
        // Spaces inside a selection are fine; a plan metric stays one.
        assert_eq!(sexp(&expr("b.p[ weight=2 ].cost")), "b.p[weight=2].cost");
        assert_eq!(sexp(&expr("p.cost")), "p.cost");
    }

    #[test]
    fn precedence_and_associativity() {
        let cases = [
            ("a.x - b.y - c.z", "(- (- a.x b.y) c.z)"),
            ("a.x / b.y / 2", "(/ (/ a.x b.y) 2)"),
            ("1 + 2 * 3", "(+ 1 (* 2 3))"),
            ("(1 + 2) * 3", "(* (+ 1 2) 3)"),
            ("-a.x * 2", "(* (neg a.x) 2)"),
            ("- -a.x", "(neg (neg a.x))"),
            ("a.x - -3", "(- a.x (neg 3))"),
            ("a.x -3", "(- a.x 3)"),
            ("a.f or b.f and c.f", "(or a.f (and b.f c.f))"),
            ("a.f and b.f or c.f", "(or (and a.f b.f) c.f)"),
            ("a.f or b.f or c.f", "(or (or a.f b.f) c.f)"),
            ("not a.f and b.f", "(and (not a.f) b.f)"),
            ("not a.x < 3", "(not (< a.x 3))"),
            ("not not a.f", "(not (not a.f))"),
            ("a.x + 1 < b.y * 2", "(< (+ a.x 1) (* b.y 2))"),
            ("a.x ~ b.y + 1 +- 0.5 * 2", "(~ a.x (+ b.y 1) (* 0.5 2))"),
            ("a.x~1+-0.1", "(~ a.x 1 0.1)"),
            ("a.x ~ 1 ± 0.1", "(~ a.x 1 0.1)"),
            ("a.x != 1 and a.y == 2", "(and (!= a.x 1) (== a.y 2))"),
            ("a.x > 1 or a.x >= 2", "(or (> a.x 1) (>= a.x 2))"),
            ("(a.f)", "a.f"),
            (
                "((a.x < 1)) and (b.f or c.f)",
                "(and (< a.x 1) (or b.f c.f))",
            ),
        ];
        for (text, tree) in cases {
            assert_eq!(sexp(&expr(text)), tree, "{text}");
        }
    }

    #[test]
    fn expression_spans_cover_their_text() {
        let text = "expect (a.x + 1) * b.y <= -c.z and not d.f";
        let Some(Stmt::Expect(e)) = parse_ok(text).pop() else {
            panic!()
        };
        assert_eq!(snippet(text, e.span), "(a.x + 1) * b.y <= -c.z and not d.f");
        let ExprKind::And(cmp, not) = &e.kind else {
            panic!()
        };
        assert_eq!(snippet(text, cmp.span), "(a.x + 1) * b.y <= -c.z");
        assert_eq!(snippet(text, not.span), "not d.f");
        let ExprKind::Compare { lhs, rhs, .. } = &cmp.kind else {
            panic!()
        };
        assert_eq!(snippet(text, lhs.span), "(a.x + 1) * b.y");
        assert_eq!(snippet(text, rhs.span), "-c.z");
        let ExprKind::Arith { lhs, .. } = &lhs.kind else {
            panic!()
        };
        assert_eq!(snippet(text, lhs.span), "(a.x + 1)");
        let ExprKind::Metric { plan, metric } = &rhs.kind else {
            let ExprKind::Neg(inner) = &rhs.kind else {
                panic!()
            };
            let ExprKind::Metric { plan, metric } = &inner.kind else {
                panic!()
            };
            assert_eq!(
                (snippet(text, plan.span), snippet(text, metric.span)),
                ("c", "z")
            );
            return;
        };
        panic!("{plan:?} {metric:?}");
    }

    #[test]
    fn long_expressions_are_refused_not_overflowed() {
        let long = format!("expect {}", vec!["a.x"; 100_000].join(" + "));
        let diags = errors(&long);
        assert_eq!(diags.len(), 1);
        assert_eq!(diags[0].code, "scen::syntax::too_deep");
        let nots = format!("expect {} a.f", "not ".repeat(100_000));
        assert_eq!(errors(&nots)[0].code, "scen::syntax::too_deep");
        let negs = format!("expect {}1 < 2", "-".repeat(100_000));
        assert_eq!(errors(&negs)[0].code, "scen::syntax::too_deep");
        // A long but reasonable conjunction is fine.
        let fine = format!("expect {}", vec!["a.f"; 200].join(" and "));
        parse_ok(&fine);
    }

    #[test]
    fn expression_errors_have_helps() {
        let d = &errors("expect a.x < b.y < 3")[0];
        assert_eq!(d.message, "comparisons cannot be chained");
        assert!(d.help.as_deref().unwrap().contains("and"));
        let d = &errors("expect a.x = 3")[0];
        assert_eq!(d.help.as_deref(), Some("compare with `==`"));
        let d = &errors("expect a.x ~ 3")[0];
        assert_eq!(
            d.help.as_deref(),
            Some("approximate equality needs a tolerance: `A ~ B +- TOL`")
        );
        // A bare word is a param's name (SPEC 2.8); one that is not a
        // param is the analyzer's error (`scen::analyze::unknown_name`).
        assert_eq!(sexp(&expr("offline + 1")), "(+ offline 1)");
        let d = &errors("expect a.x and")[0];
        assert_eq!(
            d.message,
            "expected an expression, found the end of the file"
        );
        let d = &errors("plan p k r { start (1, 2, 3, 4) }")[0];
        assert_eq!(
            d.help.as_deref(),
            Some("a point is `(x, y)` and a pose `(x, y, θ)`")
        );
    }
}
