//! `expect` expressions, typed (SPEC 2.6, 2.7): numbers and conditions,
//! plan metrics `PLAN.METRIC`, and a bench's series `BENCH.PLAN.METRIC`
//! (optionally `BENCH.PLAN[KEY = VALUE, ...].METRIC`, or filtered with
//! `SERIES where CONDITION`), which are used through an aggregate — or as a
//! plain value when they hold exactly one run.

use std::collections::HashMap;

use crate::contract::schema::{self, MetricType, did_you_mean};
use crate::diagnostics::Diag;
use crate::planners::registry;
use crate::scenario::statements::SourcedStmt;
use crate::scenario::{Bench, Check, Plan};
use crate::syntax::ast::{self, Expr, ExprKind, ParamToken, Selection};

use super::{Analyzer, PlanInfo};

/// The aggregates of a series (SPEC 2.7), with their argument counts.
pub const AGGREGATES: &[(&str, usize)] = &[
    ("mean", 1),
    ("median", 1),
    ("min", 1),
    ("max", 1),
    ("std", 1),
    ("sum", 1),
    ("count", 1),
    ("quantile", 2),
    ("rate", 1),
];

/// The type of an expression.
#[derive(Clone, Debug, PartialEq)]
enum Ty {
    Scalar(MetricType),
    Series(SeriesTy),
}

/// A series: the metric's type, where its runs come from, and how many
/// runs it holds (before any `where`).
#[derive(Clone, Debug, PartialEq)]
struct SeriesTy {
    ty: MetricType,
    bench: String,
    plan: String,
    /// The selection, as (key, index of the value in the `vary` list).
    select: Vec<(String, usize)>,
    runs: u64,
    /// The bench's `worlds` (1 without): a selection keeps them all.
    worlds: u64,
    /// Filtered by `where`: its size is known only when it runs.
    filtered: bool,
    /// The series' text, for messages.
    text: String,
}

/// What names mean in expressions.
struct Names<'s> {
    /// Plans by name; `None` for a plan whose kind is unknown (its own
    /// error was reported).
    plans: HashMap<String, Option<PlanInfo<'s>>>,
    /// Benches by name; `None` for a bench that failed analysis.
    benches: HashMap<String, Option<&'s Bench>>,
    scenario_plans: &'s [Plan],
}

impl Analyzer {
    pub(super) fn checks(
        &mut self,
        statements: &[SourcedStmt],
        plans: &[Plan],
        benches: &[Bench],
    ) -> Vec<Check> {
        // Plans and benches that failed analysis are still known by name,
        // so that their checks do not add "unknown plan" noise.
        let mut names = Names {
            plans: HashMap::new(),
            benches: HashMap::new(),
            scenario_plans: plans,
        };
        for s in statements {
            match &s.stmt {
                ast::Stmt::Plan(p) => {
                    let drives = p
                        .body
                        .iter()
                        .any(|t| matches!(t, ParamToken::Word(w) if w.value == "drive"));
                    let info = registry::planner(&p.kind.value).map(|planner| PlanInfo {
                        name: &p.name.value,
                        planner,
                        drives,
                    });
                    names.plans.entry(p.name.value.clone()).or_insert(info);
                }
                ast::Stmt::Bench(b) => {
                    let bench = benches.iter().find(|x| x.name == b.name.value);
                    names.benches.entry(b.name.value.clone()).or_insert(bench);
                }
                _ => {}
            }
        }
        let mut checks = Vec::new();
        for s in statements {
            let ast::Stmt::Expect(e) = &s.stmt else {
                continue;
            };
            let ty = self.type_expr(e, &names).and_then(|t| self.scalar(t, e));
            if ty.is_some_and(|t| t != MetricType::Bool) {
                self.error(
                    Diag::error("scen::analyze::not_a_condition", "an `expect` must be a condition, not a number")
                        .at(e.span, "a number")
                        .help("compare it: `plan.cost <= 90`, or approximately: `plan.length ~ 27.3 +- 0.01`"),
                );
            }
            checks.push(Check {
                bench: uses_series(e),
                expr: e.clone(),
                text: self.sources.snippet(e.span).to_string(),
                line: self.sources.line_of(e.span),
                span: e.span,
            });
        }
        checks
    }

    /// A value used as a plain number or condition: a series only when it
    /// holds exactly one run.
    fn scalar(&mut self, ty: Ty, e: &Expr) -> Option<MetricType> {
        match ty {
            Ty::Scalar(t) => Some(t),
            Ty::Series(s) if s.runs == 1 && !s.filtered => Some(s.ty),
            Ty::Series(s) => {
                let (what, aggregate) = match s.ty {
                    MetricType::Bool => ("true/false", format!("rate({})", s.text)),
                    MetricType::Num => ("number", format!("median({})", s.text)),
                };
                let runs = if s.filtered {
                    "a filtered series".to_string()
                } else if s.worlds > 1 {
                    format!("a series of {} runs over {} worlds", s.runs, s.worlds)
                } else {
                    format!("a series of {} runs", s.runs)
                };
                // A selection picks configurations, never one world.
                let select = if s.worlds > 1 {
                    ""
                } else {
                    ", or select one run with `[KEY = VALUE]`"
                };
                self.error(
                    Diag::error(
                        "scen::analyze::series_without_aggregate",
                        format!("`{}` is {runs}, not one {what}", s.text),
                    )
                    .at(e.span, "a series")
                    .help(format!(
                        "use an aggregate, e.g. `{aggregate}` (also `mean`, `min`, `max`, `std`, `sum`, `count`, `quantile(S, 0.9)`, `rate`){select}"
                    )),
                );
                None
            }
        }
    }

    fn type_expr(&mut self, e: &Expr, names: &Names<'_>) -> Option<Ty> {
        use MetricType::{Bool, Num};
        // An operand of an operator: a scalar of the wanted type.
        let operand = |this: &mut Self, e: &Expr, want: MetricType, ctx: &str| {
            let t = this.type_expr(e, names)?;
            let t = this.scalar(t, e)?;
            if t != want {
                let (what, help) = match want {
                    Num => (
                        "a number",
                        "metrics such as `found` are true/false; compare numbers like `p.cost`",
                    ),
                    Bool => ("a condition", "write a comparison such as `p.cost <= 90`"),
                };
                this.error(
                    Diag::error(
                        "scen::analyze::type_mismatch",
                        format!("{ctx} needs {what}"),
                    )
                    .at(e.span, format!("not {what}"))
                    .help(help),
                );
            }
            Some(t)
        };
        Some(match &e.kind {
            ExprKind::Number(_) | ExprKind::Percent(_) | ExprKind::Name(_) => Ty::Scalar(Num),
            ExprKind::Bool(_) => Ty::Scalar(Bool),
            ExprKind::Metric { plan, metric } => {
                let info = self.plan_info(plan, names)?;
                Ty::Scalar(self.metric_of(info, metric)?)
            }
            ExprKind::Series {
                bench,
                plan,
                select,
                metric,
            } => Ty::Series(self.series(e, bench, plan, select, metric, names)?),
            ExprKind::Where(series, condition) => {
                let (s, c) = (
                    self.type_expr(series, names),
                    self.type_expr(condition, names),
                );
                let (Some(s), Some(c)) = (s, c) else {
                    return None;
                };
                let (Ty::Series(s), Ty::Series(c)) = (s, c) else {
                    self.error(
                        Diag::error(
                            "scen::analyze::type_mismatch",
                            "`where` filters a series by a true/false series of the same runs",
                        )
                        .at(e.span, "not two series")
                        .help("write e.g. `mean(b.p.length where b.p.found)`"),
                    );
                    return None;
                };
                let same = (&c.bench, &c.plan, &c.select) == (&s.bench, &s.plan, &s.select);
                if c.ty != Bool || !same {
                    self.error(
                        Diag::error(
                            "scen::analyze::type_mismatch",
                            format!(
                                "`where` needs a true/false series of the runs of `{}`",
                                s.text
                            ),
                        )
                        .at(condition.span, "not a condition on the same runs")
                        .help(format!(
                            "filter by a true/false metric of the same bench, plan and selection, e.g. `{} where {}.{}.found`",
                            s.text, s.bench, s.plan
                        )),
                    );
                    return None;
                }
                Ty::Series(SeriesTy {
                    filtered: true,
                    text: format!("{} where {}", s.text, c.text),
                    ..s
                })
            }
            ExprKind::Call { function, args } => {
                let Some(&(_, arity)) = AGGREGATES.iter().find(|(f, _)| *f == function.value)
                else {
                    let all: Vec<&str> = AGGREGATES.iter().map(|(f, _)| *f).collect();
                    let mut d = Diag::error(
                        "scen::analyze::unknown_function",
                        format!("unknown aggregate `{}`", function.value),
                    )
                    .at(function.span, "not an aggregate");
                    d = match did_you_mean(&function.value, all.iter().copied()) {
                        Some(f) => d.help(format!(
                            "did you mean `{f}`? aggregates: {}",
                            schema::backticked(&all)
                        )),
                        None => d.help(format!("aggregates: {}", schema::backticked(&all))),
                    };
                    self.error(d);
                    return None;
                };
                if args.len() != arity {
                    let usage = if arity == 2 {
                        format!("`{}(SERIES, Q)`", function.value)
                    } else {
                        format!("`{}(SERIES)`", function.value)
                    };
                    self.error(
                        Diag::error(
                            "scen::analyze::wrong_arguments",
                            format!(
                                "`{}` takes {arity} argument{}, got {}",
                                function.value,
                                if arity == 1 { "" } else { "s" },
                                args.len()
                            ),
                        )
                        .at(e.span, "wrong number of arguments")
                        .help(format!("write {usage}")),
                    );
                    return None;
                }
                let series = self.type_expr(&args[0], names)?;
                let Ty::Series(s) = series else {
                    self.error(
                        Diag::error(
                            "scen::analyze::type_mismatch",
                            format!("`{}` aggregates a series", function.value),
                        )
                        .at(args[0].span, "not a series")
                        .help(format!(
                            "a series is a bench's metric over its runs: `{}(BENCH.PLAN.METRIC)`",
                            function.value
                        )),
                    );
                    return None;
                };
                let wanted = match function.value.as_str() {
                    "rate" => Some(Bool),
                    "count" => None,
                    _ => Some(Num),
                };
                if let Some(want) = wanted
                    && s.ty != want
                {
                    let help = if want == Bool {
                        format!(
                            "`rate` is the fraction of runs where a true/false metric holds, e.g. `rate({}.{}.found)`",
                            s.bench, s.plan
                        )
                    } else {
                        format!("a true/false series has a `rate({})`", s.text)
                    };
                    self.error(
                        Diag::error(
                            "scen::analyze::type_mismatch",
                            format!(
                                "`{}` needs a series of {}",
                                function.value,
                                if want == Bool {
                                    "true/false values"
                                } else {
                                    "numbers"
                                }
                            ),
                        )
                        .at(args[0].span, "a series of the other type")
                        .help(help),
                    );
                    return None;
                }
                if let Some(q) = args.get(1) {
                    operand(
                        self,
                        q,
                        Num,
                        &format!("`{}`'s second argument", function.value),
                    )?;
                    if let ExprKind::Number(x) | ExprKind::Percent(x) = q.kind
                        && !(0.0..=1.0).contains(&x)
                    {
                        self.error(
                            Diag::error(
                                "scen::analyze::out_of_range",
                                format!("a quantile lies in [0, 1], got {x}"),
                            )
                            .at(q.span, "out of range")
                            .help(
                                "write e.g. `quantile(b.p.time_ms, 0.9)` for the 90th percentile",
                            ),
                        );
                    }
                }
                Ty::Scalar(Num)
            }
            ExprKind::Neg(x) => {
                operand(self, x, Num, "`-`");
                Ty::Scalar(Num)
            }
            ExprKind::Not(x) => {
                operand(self, x, Bool, "`not`");
                Ty::Scalar(Bool)
            }
            ExprKind::Arith { op, lhs, rhs } => {
                let ctx = format!("`{}`", op.symbol());
                operand(self, lhs, Num, &ctx);
                operand(self, rhs, Num, &ctx);
                Ty::Scalar(Num)
            }
            ExprKind::Compare { op, lhs, rhs } => {
                let ctx = format!("`{}`", op.symbol());
                if matches!(op, ast::CompareOp::Eq | ast::CompareOp::Ne) {
                    let l = self.type_expr(lhs, names).and_then(|t| self.scalar(t, lhs));
                    let r = self.type_expr(rhs, names).and_then(|t| self.scalar(t, rhs));
                    if let (Some(a), Some(b)) = (l, r)
                        && a != b
                    {
                        self.error(
                            Diag::error(
                                "scen::analyze::type_mismatch",
                                format!("`{}` compares a condition with a number", op.symbol()),
                            )
                            .at(e.span, "different types")
                            .help("compare numbers with numbers, conditions with conditions"),
                        );
                    }
                } else {
                    operand(self, lhs, Num, &ctx);
                    operand(self, rhs, Num, &ctx);
                }
                Ty::Scalar(Bool)
            }
            ExprKind::Approx { lhs, rhs, tol } => {
                operand(self, lhs, Num, "`~`");
                operand(self, rhs, Num, "`~`");
                operand(self, tol, Num, "`+-`");
                Ty::Scalar(Bool)
            }
            ExprKind::And(a, b) | ExprKind::Or(a, b) => {
                let op = if matches!(e.kind, ExprKind::And(..)) {
                    "`and`"
                } else {
                    "`or`"
                };
                operand(self, a, Bool, op);
                operand(self, b, Bool, op);
                Ty::Scalar(Bool)
            }
        })
    }

    /// The plan a reference names (an error when there is none).
    fn plan_info<'n>(
        &mut self,
        plan: &ast::Ident,
        names: &'n Names<'_>,
    ) -> Option<&'n PlanInfo<'n>> {
        let Some(info) = names.plans.get(&plan.value) else {
            let known: Vec<&str> = names.plans.keys().map(String::as_str).collect();
            let mut d = Diag::error(
                "scen::analyze::unknown_plan",
                format!("unknown plan `{}`", plan.value),
            )
            .at(plan.span, "no plan of this name");
            d = match did_you_mean(&plan.value, known.iter().copied()) {
                Some(n) => d.help(format!("did you mean `{n}`?")),
                None if names.benches.contains_key(&plan.value) => d.help(format!(
                    "`{}` is a bench: its series are `{}.PLAN.METRIC`, used through an aggregate such as `median(...)`",
                    plan.value, plan.value
                )),
                None => {
                    d.help("`expect` refers to metrics as `PLAN.METRIC`, e.g. `offline.found`")
                }
            };
            self.error(d);
            return None;
        };
        info.as_ref()
    }

    /// The type of `metric` of a plan (an error when it has none).
    fn metric_of(&mut self, info: &PlanInfo<'_>, metric: &ast::Ident) -> Option<MetricType> {
        if let Some(t) = info.metric(&metric.value) {
            return Some(t);
        }
        let names = info.metric_names();
        let mut d = Diag::error(
            "scen::analyze::unknown_metric",
            format!(
                "plan `{}` ({}) has no metric `{}`",
                info.name, info.planner.kind, metric.value
            ),
        )
        .at(metric.span, "unknown metric");
        let drive_metric = schema::DRIVE_METRICS.iter().any(|m| m.name == metric.value);
        d = match did_you_mean(&metric.value, names.iter().copied()) {
            _ if drive_metric => d.help(format!(
                "`{}` is measured when the plan drives its path: add `drive unicycle` or `drive pure_pursuit` to plan `{}`",
                metric.value, info.name
            )),
            Some(n) => d.help(format!(
                "did you mean `{n}`? metrics of `{}`: {}",
                info.planner.kind,
                schema::backticked(&names)
            )),
            None => d.help(format!(
                "metrics of `{}`: {}",
                info.planner.kind,
                schema::backticked(&names)
            )),
        };
        self.error(d);
        None
    }

    /// `BENCH.PLAN[SELECTION].METRIC`.
    fn series(
        &mut self,
        e: &Expr,
        bench: &ast::Ident,
        plan: &ast::Ident,
        select: &[Selection],
        metric: &ast::Ident,
        names: &Names<'_>,
    ) -> Option<SeriesTy> {
        let Some(found) = names.benches.get(&bench.value) else {
            let known: Vec<&str> = names.benches.keys().map(String::as_str).collect();
            let mut d = Diag::error(
                "scen::analyze::unknown_bench",
                format!("unknown bench `{}`", bench.value),
            )
            .at(bench.span, "no bench of this name");
            d = match did_you_mean(&bench.value, known.iter().copied()) {
                Some(n) => d.help(format!("did you mean `{n}`?")),
                None if names.plans.contains_key(&bench.value) => d.help(format!(
                    "`{}` is a plan: its metrics are `{}.METRIC`",
                    bench.value, bench.value
                )),
                None => d.help(
                    "a series is `BENCH.PLAN.METRIC`, for a `bench BENCH { ... }` of the file",
                ),
            };
            self.error(d);
            return None;
        };
        let b = (*found)?;
        let Some(bench_plan) = b
            .plans
            .iter()
            .find(|p| names.scenario_plans[p.plan].name == plan.value)
        else {
            let listed: Vec<&str> = b
                .plans
                .iter()
                .map(|p| names.scenario_plans[p.plan].name.as_str())
                .collect();
            self.error(
                Diag::error(
                    "scen::analyze::unknown_plan",
                    format!("bench `{}` has no plan `{}`", b.name, plan.value),
                )
                .at(plan.span, "not a plan of this bench")
                .help(format!(
                    "bench `{}` runs {}",
                    b.name,
                    schema::backticked(&listed)
                )),
            );
            return None;
        };
        let info = self.plan_info(plan, names)?;
        let ty = self.metric_of(info, metric)?;
        let mut picked: Vec<(String, usize)> = Vec::new();
        for s in select {
            let Some(vary) = b.vary.iter().find(|v| v.key == s.key.value) else {
                let varied: Vec<&str> = b.vary.iter().map(|v| v.key.as_str()).collect();
                self.error(
                    Diag::error(
                        "scen::analyze::not_varied",
                        format!("bench `{}` does not vary `{}`", b.name, s.key.value),
                    )
                    .at(s.key.span, "not a varied key")
                    .help(if varied.is_empty() {
                        format!("bench `{}` varies nothing: drop the selection", b.name)
                    } else {
                        format!("bench `{}` varies {}", b.name, schema::backticked(&varied))
                    }),
                );
                return None;
            };
            if picked.iter().any(|(k, _)| *k == s.key.value) {
                self.error(
                    Diag::error(
                        "scen::analyze::duplicate_key",
                        format!("`{}` is selected twice", s.key.value),
                    )
                    .at(s.span, "second time")
                    .help("select each varied key once"),
                );
                return None;
            }
            let Some(index) = vary.values.iter().position(|v| v.value.same(&s.value)) else {
                let values: Vec<&str> = vary.values.iter().map(|v| v.text.as_str()).collect();
                self.error(
                    Diag::error(
                        "scen::analyze::not_varied",
                        format!(
                            "`{}` is not a value of `vary {}` in bench `{}`",
                            self.sources.snippet(s.value.span),
                            s.key.value,
                            b.name
                        ),
                    )
                    .at(s.value.span, "not among the varied values")
                    .help(format!(
                        "`{}` takes {}",
                        s.key.value,
                        schema::backticked(&values)
                    )),
                );
                return None;
            };
            picked.push((s.key.value.clone(), index));
        }
        let mut configs = b.configurations() as u64;
        for (key, _) in &picked {
            if let Some(v) = b.vary.iter().find(|v| v.key == *key) {
                configs /= v.values.len().max(1) as u64;
            }
        }
        Some(SeriesTy {
            ty,
            bench: b.name.clone(),
            plan: plan.value.clone(),
            select: picked,
            // Every configuration runs on each of the bench's worlds.
            runs: configs * bench_plan.runs * b.worlds,
            worlds: b.worlds,
            filtered: false,
            text: self.sources.snippet(e.span).to_string(),
        })
    }
}

/// Whether an expression reads a bench's series.
pub(crate) fn uses_series(e: &Expr) -> bool {
    matches!(e.kind, ExprKind::Series { .. }) || e.children().into_iter().any(uses_series)
}
