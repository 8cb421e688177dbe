//! The one evaluator of the language's expressions (SPEC 2.6, 2.8): the
//! arithmetic, comparisons and logic every expression shares, over
//! [`MetricValue`]s. What the leaves read — a name, a metric, a series, a
//! call — and how strict the types are belong to the caller's [`Scope`]: a
//! check reads a run's metrics and a bench's series ([`crate::checks`]), a
//! family its params and, when drawing, its distributions
//! ([`crate::scenario::family`]).

use crate::contract::MetricValue;
use crate::syntax::ast::{ArithOp, CompareOp, Expr, ExprKind};

/// What an expression's leaves mean, and how its values are read.
pub trait Scope {
    type Error;
    /// Whether `and` and `or` evaluate both sides (a check reports every
    /// value it read) or stop at the side that decides (a family's
    /// `require` may guard a division by a comparison).
    const BOTH_SIDES: bool;
    /// The value of a leaf: a name, a metric, a series (`where` included)
    /// or a call.
    fn leaf(&mut self, e: &Expr) -> Result<MetricValue, Self::Error>;
    /// `v`, the value of `e`, as a number (an operand of arithmetic or of
    /// a comparison).
    fn number(&mut self, e: &Expr, v: MetricValue) -> Result<f64, Self::Error>;
    /// `v`, the value of `e`, as a truth (an operand of `and`, `or`,
    /// `not`).
    fn truth(&mut self, e: &Expr, v: MetricValue) -> Result<bool, Self::Error>;
    /// A number computed at `e` (a negation, an arithmetic operation); a
    /// family refuses one that is not finite.
    fn computed(&mut self, e: &Expr, x: f64) -> Result<f64, Self::Error> {
        let _ = e;
        Ok(x)
    }
}

/// The value of `e` in `scope`.
pub fn eval<S: Scope>(e: &Expr, scope: &mut S) -> Result<MetricValue, S::Error> {
    use MetricValue::{Bool, Num};
    fn number<S: Scope>(x: &Expr, s: &mut S) -> Result<f64, S::Error> {
        let v = eval(x, s)?;
        s.number(x, v)
    }
    Ok(match &e.kind {
        ExprKind::Number(x) | ExprKind::Percent(x) => Num(*x),
        ExprKind::Bool(b) => Bool(*b),
        ExprKind::Name(_)
        | ExprKind::Metric { .. }
        | ExprKind::Series { .. }
        | ExprKind::Where(..)
        | ExprKind::Call { .. } => return scope.leaf(e),
        ExprKind::Neg(x) => {
            let x = number(x, scope)?;
            Num(scope.computed(e, -x)?)
        }
        ExprKind::Arith { op, lhs, rhs } => {
            let (a, b) = (number(lhs, scope)?, number(rhs, scope)?);
            let x = match op {
                ArithOp::Add => a + b,
                ArithOp::Sub => a - b,
                ArithOp::Mul => a * b,
                ArithOp::Div => a / b,
            };
            Num(scope.computed(e, x)?)
        }
        ExprKind::Compare { op, lhs, rhs } => {
            let (a, b) = (number(lhs, scope)?, number(rhs, scope)?);
            Bool(match op {
                CompareOp::Lt => a < b,
                CompareOp::Le => a <= b,
                CompareOp::Gt => a > b,
                CompareOp::Ge => a >= b,
                CompareOp::Eq => a == b,
                CompareOp::Ne => a != b,
            })
        }
        ExprKind::Approx { lhs, rhs, tol } => {
            let (a, b, t) = (
                number(lhs, scope)?,
                number(rhs, scope)?,
                number(tol, scope)?,
            );
            Bool((a - b).abs() <= t)
        }
        ExprKind::Not(x) => {
            let v = eval(x, scope)?;
            Bool(!scope.truth(x, v)?)
        }
        ExprKind::And(a, b) | ExprKind::Or(a, b) => {
            let is_and = matches!(e.kind, ExprKind::And(..));
            let v = eval(a, scope)?;
            let first = scope.truth(a, v)?;
            // `false and …`, `true or …`: decided by the first side.
            if first != is_and && !S::BOTH_SIDES {
                return Ok(Bool(first));
            }
            let v = eval(b, scope)?;
            let second = scope.truth(b, v)?;
            Bool(if is_and {
                first && second
            } else {
                first || second
            })
        }
    })
}
