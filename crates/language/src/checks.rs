//! Evaluating `expect` expressions over the metrics of a run and the
//! series of a bench (SPEC 2.6, 2.7).

use std::collections::BTreeMap;

use crate::contract::{MetricValue, Metrics};
use crate::syntax::ast::{CompareOp, Expr, ExprKind, Selection, Value, ValueKind};

/// What an expression reads: plans' metrics, and benches' series.
pub trait Values {
    /// The metrics of a plan that ran.
    fn metrics(&self, plan: &str) -> Option<&Metrics>;

    /// A bench's metric of one plan over the runs of the selected
    /// configurations, in run order; `None` when the bench did not run.
    fn series(
        &self,
        bench: &str,
        plan: &str,
        select: &[Selection],
        metric: &str,
    ) -> Option<Vec<MetricValue>>;
}

/// The size, smallest and largest value of a series a check aggregated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeriesStats {
    pub runs: usize,
    pub min: f64,
    pub max: f64,
}

/// What a check read: each metric and aggregate value by its text
/// (`plan.metric`, `median(b.p.time_ms)`), and each series' statistics.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Used {
    pub values: BTreeMap<String, MetricValue>,
    pub series: BTreeMap<String, SeriesStats>,
}

/// Evaluates a (well-typed) expression, recording in `used` every value
/// it read. A metric or series that is missing evaluates as NaN (so every
/// comparison with it fails) — analysis makes that impossible for
/// expressions it accepted. An aggregate of no runs is NaN too, except
/// `count` (0) and `sum` (0).
pub fn eval(expr: &Expr, values: &dyn Values, used: &mut Used) -> MetricValue {
    match crate::eval::eval(expr, &mut CheckScope { values, used }) {
        Ok(v) => v,
        Err(never) => match never {},
    }
}

/// A check's leaves: the plans' metrics and the benches' series, every
/// value read recorded; a number is true when it is neither 0 nor NaN.
struct CheckScope<'a, 'u> {
    values: &'a dyn Values,
    used: &'u mut Used,
}

impl crate::eval::Scope for CheckScope<'_, '_> {
    type Error = std::convert::Infallible;
    /// Both sides, so that every value a check used is reported.
    const BOTH_SIDES: bool = true;

    fn leaf(&mut self, expr: &Expr) -> Result<MetricValue, Self::Error> {
        use MetricValue::Num;
        let (values, used) = (self.values, &mut *self.used);
        Ok(match &expr.kind {
            ExprKind::Metric { plan, metric } => {
                let v = values
                    .metrics(&plan.value)
                    .and_then(|m| m.get(&metric.value).copied())
                    .unwrap_or(Num(f64::NAN));
                used.values
                    .insert(format!("{}.{}", plan.value, metric.value), v);
                v
            }
            // A series of one run used as a plain value (analysis allowed
            // it).
            ExprKind::Series { .. } | ExprKind::Where(..) => {
                let s = eval_series(expr, values, used, false);
                let v = match s.as_slice() {
                    [one] => *one,
                    _ => Num(f64::NAN),
                };
                used.values.insert(describe(expr), v);
                v
            }
            ExprKind::Call { function, args } => {
                let series = args
                    .first()
                    .map(|a| eval_series(a, values, used, true))
                    .unwrap_or_default();
                let q = args.get(1).map(|q| eval(q, values, used).as_f64());
                let v = aggregate(&function.value, &series, q);
                used.values.insert(describe(expr), v);
                v
            }
            // A sample replaces every param's name by its value before
            // analysis.
            _ => Num(f64::NAN),
        })
    }

    fn number(&mut self, _: &Expr, v: MetricValue) -> Result<f64, Self::Error> {
        Ok(v.as_f64())
    }

    fn truth(&mut self, _: &Expr, v: MetricValue) -> Result<bool, Self::Error> {
        Ok(match v {
            MetricValue::Bool(b) => b,
            MetricValue::Num(x) => x != 0.0 && !x.is_nan(),
        })
    }
}

/// How far a check is from failing (SPEC §4 `falsify`): for `a < b`,
/// b − a; for `a ~ b +- t`, t − |a − b|; `and` the smallest of its sides,
/// `or` the largest, `not` the opposite; `==` −|a − b|, `!=` |a − b|; any
/// other condition +1 when it holds, −1 when not. A negative margin is a
/// failed check (and a margin of 0 on a strict comparison); a margin that
/// is not a number (a metric with no value) counts as ±1 by the truth of
/// the check.
pub fn margin(expr: &Expr, values: &dyn Values) -> f64 {
    let num = |e: &Expr| eval(e, values, &mut Used::default()).as_f64();
    let m = match &expr.kind {
        ExprKind::Compare { op, lhs, rhs } => {
            let (a, b) = (num(lhs), num(rhs));
            match op {
                CompareOp::Lt | CompareOp::Le => b - a,
                CompareOp::Gt | CompareOp::Ge => a - b,
                CompareOp::Eq => -(a - b).abs(),
                CompareOp::Ne => (a - b).abs(),
            }
        }
        ExprKind::Approx { lhs, rhs, tol } => num(tol) - (num(lhs) - num(rhs)).abs(),
        ExprKind::And(a, b) => margin(a, values).min(margin(b, values)),
        ExprKind::Or(a, b) => margin(a, values).max(margin(b, values)),
        ExprKind::Not(x) => -margin(x, values),
        _ => f64::NAN,
    };
    if m.is_nan() {
        match eval(expr, values, &mut Used::default()) {
            MetricValue::Bool(true) => 1.0,
            MetricValue::Num(x) if x != 0.0 && !x.is_nan() => 1.0,
            _ => -1.0,
        }
    } else {
        m
    }
}

/// The runs' values of a series expression (`b.p.m`, `S where T`),
/// recording its statistics when it is `aggregated`.
fn eval_series(
    expr: &Expr,
    values: &dyn Values,
    used: &mut Used,
    aggregated: bool,
) -> Vec<MetricValue> {
    let out = match &expr.kind {
        ExprKind::Series {
            bench,
            plan,
            select,
            metric,
        } => values
            .series(&bench.value, &plan.value, select, &metric.value)
            .unwrap_or_default(),
        ExprKind::Where(series, condition) => {
            let s = eval_series(series, values, used, false);
            let c = eval_series(condition, values, used, false);
            s.into_iter()
                .zip(c)
                .filter(|(_, c)| *c == MetricValue::Bool(true))
                .map(|(v, _)| v)
                .collect()
        }
        _ => Vec::new(),
    };
    if !aggregated {
        return out;
    }
    let xs: Vec<f64> = out.iter().map(|v| v.as_f64()).collect();
    used.series.insert(
        describe(expr),
        SeriesStats {
            runs: xs.len(),
            min: xs.iter().copied().fold(f64::NAN, f64::min),
            max: xs.iter().copied().fold(f64::NAN, f64::max),
        },
    );
    out
}

/// An aggregate of a series (SPEC 2.7); `q` is `quantile`'s level. Runs
/// whose metric has no value (NaN: the `clearance` of a run that found no
/// path) are left out of the numeric aggregates; `count` and `rate` count
/// every run.
pub fn aggregate(function: &str, series: &[MetricValue], q: Option<f64>) -> MetricValue {
    use MetricValue::Num;
    if function == "count" {
        return Num(series.len() as f64);
    }
    let xs: Vec<f64> = series
        .iter()
        .map(|v| v.as_f64())
        .filter(|x| !x.is_nan())
        .collect();
    let n = xs.len() as f64;
    let sorted = || {
        let mut s = xs.clone();
        s.sort_by(f64::total_cmp);
        s
    };
    let mean = xs.iter().sum::<f64>() / n;
    Num(match function {
        "sum" => xs.iter().sum(),
        "mean" => mean,
        "rate" => {
            series
                .iter()
                .filter(|v| **v == MetricValue::Bool(true))
                .count() as f64
                / series.len() as f64
        }
        "min" => xs.iter().copied().fold(f64::NAN, f64::min),
        "max" => xs.iter().copied().fold(f64::NAN, f64::max),
        "std" if xs.len() >= 2 => {
            let ss: f64 = xs.iter().map(|x| (x - mean) * (x - mean)).sum();
            if ss.is_nan() {
                f64::NAN
            } else {
                (ss / (n - 1.0)).sqrt()
            }
        }
        "median" => quantile(&sorted(), 0.5),
        "quantile" => quantile(&sorted(), q.unwrap_or(f64::NAN)),
        _ => f64::NAN,
    })
}

/// The `q`-quantile of sorted values, interpolating linearly between the
/// two nearest ranks (NaN for no values or `q` outside [0, 1]).
pub fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() || !(0.0..=1.0).contains(&q) {
        return f64::NAN;
    }
    let h = (sorted.len() - 1) as f64 * q;
    let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
    let (a, b) = (sorted[lo], sorted[hi]);
    if a == b || lo == hi {
        a
    } else {
        a + (h - lo as f64) * (b - a)
    }
}

/// An expression as the report names it: `median(b.p[k = 1].time_ms)`.
pub fn describe(expr: &Expr) -> String {
    match &expr.kind {
        ExprKind::Metric { plan, metric } => format!("{}.{}", plan.value, metric.value),
        ExprKind::Series {
            bench,
            plan,
            select,
            metric,
        } => {
            let sel = if select.is_empty() {
                String::new()
            } else {
                let parts: Vec<String> = select
                    .iter()
                    .map(|s| format!("{} = {}", s.key.value, value_text(&s.value)))
                    .collect();
                format!("[{}]", parts.join(", "))
            };
            format!("{}.{}{sel}.{}", bench.value, plan.value, metric.value)
        }
        ExprKind::Where(s, c) => format!("{} where {}", describe(s), describe(c)),
        ExprKind::Call { function, args } => {
            let args: Vec<String> = args.iter().map(describe).collect();
            format!("{}({})", function.value, args.join(", "))
        }
        ExprKind::Number(x) => format_num(*x),
        ExprKind::Percent(x) => format!("{}%", format_num(x * 100.0)),
        ExprKind::Bool(b) => b.to_string(),
        _ => "…".to_string(),
    }
}

/// A literal value as written (for selections in reports).
pub fn value_text(v: &Value) -> String {
    match &v.kind {
        ValueKind::Number(x) => format_num(*x),
        ValueKind::Angle(a) => format!("{}deg", format_num(a.radians().to_degrees())),
        ValueKind::Percent(x) => format!("{}%", format_num(x * 100.0)),
        ValueKind::Duration(x) => format!("{}s", format_num(*x)),
        ValueKind::Str(s) => format!("{s:?}"),
        ValueKind::Word(w) => w.clone(),
        ValueKind::Tuple(xs) => format!(
            "({})",
            xs.iter().map(value_text).collect::<Vec<_>>().join(", ")
        ),
        ValueKind::List(xs) => format!(
            "[{}]",
            xs.iter().map(value_text).collect::<Vec<_>>().join(", ")
        ),
        // A sample computes every expression before analysis.
        ValueKind::Calc { .. } => "…".to_string(),
    }
}

/// The plans an expression refers to by `PLAN.METRIC`.
pub fn plans_used(expr: &Expr, out: &mut Vec<String>) {
    expr.walk(&mut |e| {
        if let ExprKind::Metric { plan, .. } = &e.kind
            && !out.contains(&plan.value)
        {
            out.push(plan.value.clone());
        }
    });
}

/// Every `PLAN.METRIC` the expression reads, once each.
pub fn metrics_used(expr: &Expr, out: &mut Vec<(String, String)>) {
    expr.walk(&mut |e| {
        if let ExprKind::Metric { plan, metric } = &e.kind {
            let m = (plan.value.clone(), metric.value.clone());
            if !out.contains(&m) {
                out.push(m);
            }
        }
    });
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
        // No value (SPEC §4): never a number that reads as a measurement.
        "—".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf".into() } else { "-inf".into() }
    } else if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        let s = format!("{x:.6}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}
