//! A family's expressions computed from its params (and, when drawing, its
//! distributions), on the language's one evaluator ([`crate::eval`]).

#![allow(clippy::result_large_err)]

use std::collections::HashMap;

use crate::contract::MetricValue;
use crate::diagnostics::{Diag, Span};
use crate::rng::SplitMix64;
use crate::syntax::ast::{Expr, ExprKind};

use super::*;

/// Why an expression has no number.
pub(super) enum EvalError {
    /// A result that is not finite (division by zero, sqrt of a negative).
    NotFinite(Span),
    /// A distribution's bounds (in a scatter's size).
    Distribution(Diag),
    /// Something the static checks report (an unknown name or function).
    Static(Span),
}

impl EvalError {
    pub(super) fn diag(self, family: &Family, values: &[f64]) -> Diag {
        match self {
            EvalError::NotFinite(span) => {
                let drawn: Vec<String> = family
                    .params
                    .iter()
                    .zip(values)
                    .map(|(p, x)| format!("{} = {x}", p.name.value))
                    .collect();
                Diag::error(
                    "scen::family::not_finite",
                    "this expression has no finite value in a draw",
                )
                .at(
                    span,
                    "not finite (a division by zero, or the root of a negative number)",
                )
                .help(if drawn.is_empty() {
                    "keep divisors away from zero and roots of non-negative numbers".to_string()
                } else {
                    format!(
                        "with {}: keep divisors away from zero and roots of non-negative numbers",
                        drawn.join(", ")
                    )
                })
            }
            EvalError::Distribution(d) => d,
            EvalError::Static(span) => Diag::error(
                "scen::family::bad_expression",
                "this expression cannot be computed",
            )
            .at(span, "here"),
        }
    }
}

pub(super) fn eval(
    e: &Expr,
    values: &[f64],
    index: &HashMap<String, usize>,
) -> Result<f64, EvalError> {
    eval_with(e, values, index, &mut None)
}

pub(super) fn eval_drawing(
    e: &Expr,
    values: &[f64],
    index: &HashMap<String, usize>,
    rng: &mut SplitMix64,
) -> Result<f64, EvalError> {
    eval_with(e, values, index, &mut Some(rng))
}

/// The number of an expression; a distribution draws from `rng` (none:
/// it is not constant).
pub(super) fn eval_with(
    e: &Expr,
    values: &[f64],
    index: &HashMap<String, usize>,
    rng: &mut Option<&mut SplitMix64>,
) -> Result<f64, EvalError> {
    let mut scope = ParamScope { values, index, rng };
    let v = crate::eval::eval(e, &mut scope)?;
    crate::eval::Scope::number(&mut scope, e, v)
}

/// A family's leaves: its params' values (by name), the functions `min`,
/// `max`, `abs`, `sqrt` and, when drawing, the distributions. Numbers and
/// conditions do not mix, every value is finite, and `and`/`or` stop at the
/// side that decides.
pub(super) struct ParamScope<'a, 'r, 's> {
    values: &'a [f64],
    index: &'a HashMap<String, usize>,
    rng: &'r mut Option<&'s mut SplitMix64>,
}

impl crate::eval::Scope for ParamScope<'_, '_, '_> {
    type Error = EvalError;
    const BOTH_SIDES: bool = false;

    fn leaf(&mut self, e: &Expr) -> Result<MetricValue, EvalError> {
        let x = match &e.kind {
            ExprKind::Name(n) => match self.index.get(&n.value).and_then(|&k| self.values.get(k)) {
                Some(&x) => x,
                None => return Err(EvalError::Static(e.span)),
            },
            ExprKind::Call { function, args } => {
                let f = function.value.as_str();
                let mut xs = Vec::with_capacity(args.len());
                for a in args {
                    let v = crate::eval::eval(a, self)?;
                    xs.push(self.number(a, v)?);
                }
                match (f, xs.as_slice()) {
                    ("min", [_, ..]) => xs.iter().copied().fold(f64::INFINITY, f64::min),
                    ("max", [_, ..]) => xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                    ("abs", [x]) => x.abs(),
                    ("sqrt", [x]) => x.sqrt(),
                    (f, [a, b]) if DISTRIBUTIONS.contains(&f) => {
                        let Some(rng) = self.rng.as_deref_mut() else {
                            return Err(EvalError::Static(e.span));
                        };
                        check_distribution(f, *a, *b, e.span).map_err(EvalError::Distribution)?;
                        sample(f, *a, *b, rng)
                    }
                    _ => return Err(EvalError::Static(e.span)),
                }
            }
            // Metrics and series: reported by the static checks.
            _ => return Err(EvalError::Static(e.span)),
        };
        self.computed(e, x).map(MetricValue::Num)
    }

    fn number(&mut self, e: &Expr, v: MetricValue) -> Result<f64, EvalError> {
        match v {
            // A literal too large for a number (`1e999`) included.
            MetricValue::Num(x) => self.computed(e, x),
            MetricValue::Bool(_) => Err(EvalError::Static(e.span)),
        }
    }

    fn truth(&mut self, e: &Expr, v: MetricValue) -> Result<bool, EvalError> {
        match v {
            MetricValue::Bool(b) => Ok(b),
            MetricValue::Num(_) => Err(EvalError::Static(e.span)),
        }
    }

    fn computed(&mut self, e: &Expr, x: f64) -> Result<f64, EvalError> {
        if x.is_finite() {
            Ok(x)
        } else {
            Err(EvalError::NotFinite(e.span))
        }
    }
}

/// Whether an expression is true or false (not a number).
pub(super) fn is_condition(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Bool(_) | ExprKind::Compare { .. } | ExprKind::Approx { .. } => true,
        // Reported as `require_reads_metric`.
        ExprKind::Metric { .. } | ExprKind::Series { .. } => true,
        ExprKind::Not(x) => is_condition(x),
        ExprKind::And(a, b) | ExprKind::Or(a, b) => is_condition(a) && is_condition(b),
        _ => false,
    }
}

/// Whether a `require` holds.
pub(super) fn eval_condition(
    e: &Expr,
    values: &[f64],
    index: &HashMap<String, usize>,
) -> Result<bool, EvalError> {
    let mut scope = ParamScope {
        values,
        index,
        rng: &mut None,
    };
    let v = crate::eval::eval(e, &mut scope)?;
    crate::eval::Scope::truth(&mut scope, e, v)
}
