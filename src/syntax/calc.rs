//! Expressions in number positions (SPEC 2.8): a `calc` or `body_calc` pair
//! is a flat sequence of terms (`-`* then a number, a param's name, a call
//! or a parenthesised expression) and the operators `+ - * /`, given its
//! tree here by precedence climbing.

use super::ast::{AngleUnit, ArithOp, Expr, ExprKind, ValueKind};
use super::builder::{Builder, P, children};
use super::parser::Rule;
use crate::diagnostics::Diag;

const ADD_POWER: u8 = 1;
const MUL_POWER: u8 = 2;

impl Builder<'_, '_> {
    /// A `calc` or `body_calc` pair as a value: its expression, and the
    /// angle unit written after it when the whole value is `(EXPR)deg`.
    /// `None` when it is in error (the error is reported).
    pub(super) fn calc_value(&mut self, pair: P<'_>) -> Option<ValueKind> {
        let tokens: Vec<P<'_>> = pair.into_inner().collect();
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
                    format!("the unit `{}` is separated from its expression", unit.as_str()),
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
        let ValueKind::Calc { expr, unit: None } = disk_radius("world { disk (0, 0) 1 - 2 * a - b }")
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
        assert_eq!(disk_radius("world { disk (0, 0) 2 }"), ValueKind::Number(2.0));
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
}
