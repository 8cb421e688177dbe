//! Evaluating `expect` expressions over the metrics of a run.

use std::collections::BTreeMap;

use crate::planners::{MetricValue, Metrics};
use crate::syntax::ast::{ArithOp, CompareOp, Expr, ExprKind};

/// Evaluates a (well-typed) expression. `metrics` gives each plan's
/// metrics by plan name; every metric read is recorded in `used` under
/// `plan.metric`. A metric that is missing evaluates as NaN (so every
/// comparison with it fails) — analysis makes that impossible for
/// expressions it accepted.
pub fn eval<'m>(
    expr: &Expr,
    metrics: &dyn Fn(&str) -> Option<&'m Metrics>,
    used: &mut BTreeMap<String, MetricValue>,
) -> MetricValue {
    use MetricValue::{Bool, Num};
    let num = |v: MetricValue| v.as_f64();
    let truth = |v: MetricValue| match v {
        Bool(b) => b,
        Num(x) => x != 0.0 && !x.is_nan(),
    };
    match &expr.kind {
        ExprKind::Number(x) | ExprKind::Percent(x) => Num(*x),
        ExprKind::Bool(b) => Bool(*b),
        ExprKind::Metric { plan, metric } => {
            let v = metrics(&plan.value)
                .and_then(|m| m.get(&metric.value).copied())
                .unwrap_or(Num(f64::NAN));
            used.insert(format!("{}.{}", plan.value, metric.value), v);
            v
        }
        ExprKind::Neg(x) => Num(-num(eval(x, metrics, used))),
        ExprKind::Not(x) => Bool(!truth(eval(x, metrics, used))),
        ExprKind::Arith { op, lhs, rhs } => {
            let (a, b) = (num(eval(lhs, metrics, used)), num(eval(rhs, metrics, used)));
            Num(match op {
                ArithOp::Add => a + b,
                ArithOp::Sub => a - b,
                ArithOp::Mul => a * b,
                ArithOp::Div => a / b,
            })
        }
        ExprKind::Compare { op, lhs, rhs } => {
            let (a, b) = (eval(lhs, metrics, used), eval(rhs, metrics, used));
            let (a, b) = (num(a), num(b));
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
            let a = num(eval(lhs, metrics, used));
            let b = num(eval(rhs, metrics, used));
            let t = num(eval(tol, metrics, used));
            Bool((a - b).abs() <= t)
        }
        // Both sides are always evaluated, so that every value a check
        // used is reported.
        ExprKind::And(a, b) => {
            let (x, y) = (truth(eval(a, metrics, used)), truth(eval(b, metrics, used)));
            Bool(x && y)
        }
        ExprKind::Or(a, b) => {
            let (x, y) = (truth(eval(a, metrics, used)), truth(eval(b, metrics, used)));
            Bool(x || y)
        }
    }
}

/// The plans an expression refers to.
pub fn plans_used(expr: &Expr, out: &mut Vec<String>) {
    match &expr.kind {
        ExprKind::Metric { plan, .. } => {
            if !out.contains(&plan.value) {
                out.push(plan.value.clone());
            }
        }
        ExprKind::Neg(x) | ExprKind::Not(x) => plans_used(x, out),
        ExprKind::Arith { lhs, rhs, .. } | ExprKind::Compare { lhs, rhs, .. } => {
            plans_used(lhs, out);
            plans_used(rhs, out);
        }
        ExprKind::Approx { lhs, rhs, tol } => {
            plans_used(lhs, out);
            plans_used(rhs, out);
            plans_used(tol, out);
        }
        ExprKind::And(a, b) | ExprKind::Or(a, b) => {
            plans_used(a, out);
            plans_used(b, out);
        }
        ExprKind::Number(_) | ExprKind::Percent(_) | ExprKind::Bool(_) => {}
    }
}

/// Formats a metric value for reports: booleans as `true`/`false`, whole
/// numbers without a fraction, others with up to 6 significant decimals.
pub fn format_value(v: MetricValue) -> String {
    match v {
        MetricValue::Bool(b) => b.to_string(),
        MetricValue::Num(x) => format_num(x),
    }
}

pub fn format_num(x: f64) -> String {
    if x.is_nan() {
        "n/a".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf".into() } else { "-inf".into() }
    } else if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        let s = format!("{x:.6}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}
