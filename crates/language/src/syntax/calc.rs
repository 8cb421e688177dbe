//! Expressions in number positions (SPEC 2.8): a `calc` or `body_calc` pair
//! is a flat sequence of terms (`-`* then a number, a param's name, a call
//! or a parenthesised expression) and the operators `+ - * /`, given its
//! tree here by precedence climbing.

use super::ast::{Angle, AngleUnit, ArithOp, Expr, ExprKind, ParamToken, Value, ValueKind};
use super::builder::{Builder, P, children};
use super::parser::Rule;
use crate::diagnostics::Diag;

/// A quantity with its sign flipped (`-` before it in a plan body).
fn negated(kind: ValueKind) -> ValueKind {
    match kind {
        ValueKind::Number(x) => ValueKind::Number(-x),
        ValueKind::Percent(x) => ValueKind::Percent(-x),
        ValueKind::Duration(x) => ValueKind::Duration(-x),
        ValueKind::Angle(a) => ValueKind::Angle(Angle {
            written: -a.written,
            unit: a.unit,
        }),
        other => other,
    }
}

const ADD_POWER: u8 = 1;
const MUL_POWER: u8 = 2;

impl Builder<'_, '_> {
    /// Where a `-` or `+` has a blank before it and none after (`speed -1`):
    /// there a new value starts, as in a plan body's `key value` pairs.
    fn split_points(&self, tokens: &[P<'_>]) -> Vec<usize> {
        (1..tokens.len())
            .filter(|&k| {
                let op = &tokens[k];
                let (start, end) = (self.span(op).start, self.span(op).end);
                op.as_rule() == Rule::calc_op
                    && matches!(op.as_str(), "-" | "+")
                    && self
                        .byte_before(start)
                        .is_some_and(|b| b.is_ascii_whitespace())
                    && self.span(&tokens[k + 1]).start == end
            })
            .collect()
    }

    /// Reports a sign that could start a new value inside an expression
    /// that is one value (`(a -1)`); true when there is one.
    fn ambiguous(&mut self, tokens: &[P<'_>]) -> bool {
        let Some(&k) = self.split_points(tokens).first() else {
            return false;
        };
        let span = self.span(&tokens[k]);
        self.diags.push(
            Diag::error(
                "scen::syntax::ambiguous_sign",
                format!("`{}` right before a number, after a blank", tokens[k].as_str()),
            )
            .at(span, "a sign or an operator?")
            .help(format!(
                "write `a {} b` (blanks on both sides) for the operation, or separate the values with `,` inside `( )` and `[ ]`",
                tokens[k].as_str()
            )),
        );
        true
    }

    /// The tokens of a `body_calc` pair in a plan or bench body: one value,
    /// or several where a sign starts a new one (`speed -1` is the key
    /// `speed` and the value -1, `w - 1` and `w-1` one expression).
    pub(super) fn body_calc_tokens(&mut self, pair: P<'_>) -> Vec<ParamToken> {
        let tokens: Vec<P<'_>> = pair.into_inner().collect();
        let mut bounds = vec![0];
        bounds.extend(self.split_points(&tokens));
        bounds.push(tokens.len());
        let mut out = Vec::new();
        for w in bounds.windows(2) {
            let segment = &tokens[w[0]..w[1]];
            // A segment after a split starts with its sign.
            let (negate, rest) = match segment {
                [op, rest @ ..] if op.as_rule() == Rule::calc_op => (op.as_str() == "-", rest),
                _ => (false, segment),
            };
            let start = self.span(&segment[0]).start;
            let end = self.span(&segment[segment.len() - 1]).end;
            let span = crate::diagnostics::Span::new(self.file, start, end);
            match rest {
                [name] if name.as_rule() == Rule::calc_name && !negate => {
                    out.push(ParamToken::Word(self.ident(name)));
                }
                [number] if number.as_rule() == Rule::expr_number => {
                    let kind = self.quantity(number.clone());
                    let kind = if negate { negated(kind) } else { kind };
                    out.push(ParamToken::Value(Value { kind, span }));
                }
                _ => {
                    let unit = match rest {
                        [paren] if paren.as_rule() == Rule::calc_paren => self.paren_unit(paren),
                        _ => None,
                    };
                    let mut pos = 0;
                    let kind = match self.calc_climb(rest, &mut pos, 0, 0, unit.is_some()) {
                        Some(expr) => {
                            let expr = if negate {
                                Expr {
                                    kind: ExprKind::Neg(Box::new(expr)),
                                    span,
                                }
                            } else {
                                expr
                            };
                            ValueKind::Calc {
                                expr: Box::new(expr),
                                unit,
                            }
                        }
                        None => ValueKind::Number(0.0),
                    };
                    out.push(ParamToken::Value(Value { kind, span }));
                }
            }
        }
        out
    }

    /// A `calc` or `body_calc` pair as a value: its expression, and the
    /// angle unit written after it when the whole value is `(EXPR)deg`.
    /// `None` when it is in error (the error is reported).
    pub(super) fn calc_value(&mut self, pair: P<'_>) -> Option<ValueKind> {
        let tokens: Vec<P<'_>> = pair.into_inner().collect();
        if self.ambiguous(&tokens) {
            return None;
        }
        // `(EXPR)deg` on its own: the unit belongs to the whole value.
        let unit = match tokens.as_slice() {
            [paren] if paren.as_rule() == Rule::calc_paren => self.paren_unit(paren),
            _ => None,
        };
        let mut pos = 0;
        let expr = self.calc_climb(&tokens, &mut pos, 0, 0, unit.is_some())?;
        Some(ValueKind::Calc {
            expr: Box::new(expr),
            unit,
        })
    }

    /// The unit after a `calc_paren`, if written (and glued to the `)`).
    fn paren_unit(&mut self, paren: &P<'_>) -> Option<AngleUnit> {
        let unit = paren
            .clone()
            .into_inner()
            .find(|p| p.as_rule() == Rule::calc_unit)?;
        let span = self.span(&unit);
        let close = paren
            .clone()
            .into_inner()
            .find(|p| p.as_rule() == Rule::rparen)
            .map(|p| self.span(&p).end);
        if close != Some(span.start) {
            self.diags.push(
                Diag::error(
                    "scen::syntax::detached_unit",
                    format!(
                        "the unit `{}` is separated from its expression",
                        unit.as_str()
                    ),
                )
                .at(span, "a separate word")
                .help(format!(
                    "write the unit right after the `)`: `(...){}`",
                    unit.as_str()
                )),
            );
        }
        Some(if unit.as_str() == "deg" {
            AngleUnit::Deg
        } else {
            AngleUnit::Rad
        })
    }

    /// Parses `tokens[*pos..]` up to the first operator that binds no
    /// tighter than `min_power`. `unit_allowed`: the expression is the whole
    /// value and its unit was taken by [`Self::calc_value`].
    fn calc_climb(
        &mut self,
        tokens: &[P<'_>],
        pos: &mut usize,
        min_power: u8,
        depth: usize,
        unit_allowed: bool,
    ) -> Option<Expr> {
        let mut lhs = self.calc_unary(tokens, pos, depth, unit_allowed)?;
        while let Some(op) = tokens.get(*pos) {
            let power = match op.as_str() {
                "+" | "-" => ADD_POWER,
                _ => MUL_POWER,
            };
            if power <= min_power {
                break;
            }
            *pos += 1;
            let rhs = self.calc_climb(tokens, pos, power, depth + 1, false)?;
            let op = match op.as_str() {
                "+" => ArithOp::Add,
                "-" => ArithOp::Sub,
                "*" => ArithOp::Mul,
                _ => ArithOp::Div,
            };
            let span = lhs.span.to(rhs.span);
            self.check_height(depth + 1, span)?;
            lhs = Expr {
                kind: ExprKind::Arith {
                    op,
                    lhs: Box::new(lhs),
                    rhs: Box::new(rhs),
                },
                span,
            };
        }
        Some(lhs)
    }

    /// `-`* then a term.
    fn calc_unary(
        &mut self,
        tokens: &[P<'_>],
        pos: &mut usize,
        depth: usize,
        unit_allowed: bool,
    ) -> Option<Expr> {
        let token = &tokens[*pos];
        *pos += 1;
        let span = self.span(token);
        self.check_height(depth, span)?;
        if token.as_rule() == Rule::calc_neg {
            let inner = self.calc_unary(tokens, pos, depth + 1, false)?;
            let span = span.to(inner.span);
            return Some(Expr {
                kind: ExprKind::Neg(Box::new(inner)),
                span,
            });
        }
        self.calc_term(token.clone(), depth, unit_allowed)
    }

    fn calc_term(&mut self, term: P<'_>, depth: usize, unit_allowed: bool) -> Option<Expr> {
        let span = self.span(&term);
        let kind = match term.as_rule() {
            Rule::expr_number => match self.quantity(term) {
                ValueKind::Number(x) => ExprKind::Number(x),
                _ => {
                    self.diags.push(
                        Diag::error(
                            "scen::syntax::unit_not_allowed",
                            "a unit inside an expression",
                        )
                        .at(span, "a number with a unit")
                        .help(
                            "write the numbers plain and the angle unit after the whole \
                             expression in parentheses: `(a + 10)deg`",
                        ),
                    );
                    return None;
                }
            },
            Rule::calc_name => ExprKind::Name(self.ident(&term)),
            Rule::calc_paren => {
                if !unit_allowed
                    && term
                        .clone()
                        .into_inner()
                        .any(|p| p.as_rule() == Rule::calc_unit)
                {
                    self.diags.push(
                        Diag::error(
                            "scen::syntax::unit_not_allowed",
                            "a unit inside an expression",
                        )
                        .at(span, "a unit on part of the expression")
                        .help(
                            "the angle unit goes after the whole value: `(a + 10)deg`, \
                             not `(a)deg + 10`",
                        ),
                    );
                    return None;
                }
                let inner = children(term)
                    .find(|p| p.as_rule() == Rule::calc)
                    .expect("grammar guarantees `( calc )`");
                let tokens: Vec<P<'_>> = inner.into_inner().collect();
                if self.ambiguous(&tokens) {
                    return None;
                }
                let mut pos = 0;
                let expr = self.calc_climb(&tokens, &mut pos, 0, depth + 1, false)?;
                // The span includes the parentheses.
                return Some(Expr {
                    kind: expr.kind,
                    span,
                });
            }
            Rule::calc_call => {
                let mut parts = children(term);
                let function = self.ident(&parts.next().expect("grammar guarantees a function"));
                let mut args = Vec::new();
                for arg in parts {
                    let tokens: Vec<P<'_>> = arg.into_inner().collect();
                    if self.ambiguous(&tokens) {
                        return None;
                    }
                    let mut pos = 0;
                    args.push(self.calc_climb(&tokens, &mut pos, 0, depth + 1, false)?);
                }
                ExprKind::Call { function, args }
            }
            rule => unreachable!("grammar guarantees a term, got {rule:?}"),
        };
        Some(Expr { kind, span })
    }
}

#[cfg(test)]
mod tests {
    use crate::syntax::ast::{AngleUnit, ExprKind, ObstacleShape, Stmt, ValueKind, WorldItem};
    use crate::syntax::testing::{parse_ok, snippet};

    fn disk_radius(text: &str) -> ValueKind {
        let file = parse_ok(text);
        let Stmt::World(world) = &file[0] else {
            panic!()
        };
        let WorldItem::Obstacle(o) = &world.items[0] else {
            panic!()
        };
        let ObstacleShape::Disk(_, r) = &o.shape else {
            panic!()
        };
        r.kind.clone()
    }

    #[test]
    fn precedence_and_associativity() {
        let ValueKind::Calc { expr, unit: None } =
            disk_radius("world { disk (0, 0) 1 - 2 * a - b }")
        else {
            panic!()
        };
        // (1 - (2 * a)) - b
        let ExprKind::Arith { lhs, rhs, .. } = &expr.kind else {
            panic!()
        };
        assert!(matches!(&rhs.kind, ExprKind::Name(n) if n.value == "b"));
        let ExprKind::Arith { rhs: product, .. } = &lhs.kind else {
            panic!()
        };
        assert!(matches!(&product.kind, ExprKind::Arith { .. }));
    }

    #[test]
    fn a_plain_number_stays_a_number_and_a_name_is_an_expression() {
        assert_eq!(
            disk_radius("world { disk (0, 0) 2 }"),
            ValueKind::Number(2.0)
        );
        let ValueKind::Calc { expr, .. } = disk_radius("world { disk (0, 0) r }") else {
            panic!()
        };
        assert!(matches!(expr.kind, ExprKind::Name(_)));
    }

    #[test]
    fn a_unit_after_the_whole_expression() {
        let text = "world { disk (0, 0) (a + 10)deg }";
        let ValueKind::Calc { expr, unit } = disk_radius(text) else {
            panic!()
        };
        assert_eq!(unit, Some(AngleUnit::Deg));
        assert_eq!(snippet(text, expr.span), "(a + 10)deg");
    }

    #[test]
    fn calls_and_negation() {
        let ValueKind::Calc { expr, .. } = disk_radius("world { disk (0, 0) -min(a, 2) }") else {
            panic!()
        };
        let ExprKind::Neg(call) = &expr.kind else {
            panic!()
        };
        assert!(matches!(&call.kind, ExprKind::Call { args, .. } if args.len() == 2));
    }

    #[test]
    fn units_inside_an_expression_are_errors() {
        for text in [
            "world { disk (0, 0) 90deg + a }",
            "world { disk (0, 0) (a)deg + 1 }",
            "world { disk (0, 0) (a) deg }",
        ] {
            let (_, diags) = crate::syntax::parse(text, 0);
            assert_eq!(diags.len(), 1, "{text}: {diags:?}");
        }
    }

    #[test]
    fn in_a_plan_body_a_sign_after_a_blank_starts_a_value() {
        use crate::syntax::ast::ParamToken;
        let body = |text: &str| -> Vec<String> {
            let file = parse_ok(&format!("plan p astar r {{ {text} }}"));
            let Stmt::Plan(plan) = &file[0] else { panic!() };
            plan.body
                .iter()
                .map(|t| match t {
                    ParamToken::Word(w) => format!("word {}", w.value),
                    ParamToken::Value(v) => match &v.kind {
                        ValueKind::Number(x) => format!("number {x}"),
                        ValueKind::Calc { .. } => "calc".to_string(),
                        other => other.describe().to_string(),
                    },
                    ParamToken::Block { .. } => "block".to_string(),
                })
                .collect()
        };
        assert_eq!(body("speed -1"), ["word speed", "number -1"]);
        assert_eq!(body("weight w - 1"), ["word weight", "calc"]);
        assert_eq!(body("weight w-1"), ["word weight", "calc"]);
        assert_eq!(
            body("weight w * 2 cell 2 -1"),
            ["word weight", "calc", "word cell", "number 2", "number -1"]
        );
        assert_eq!(body("weight w -w"), ["word weight", "word w", "calc"]);
        assert_eq!(body("weight (w)"), ["word weight", "calc"]);
    }
}
