//! The checks of a family's declarations that need no draw: param names,
//! their order, distributions and their constant bounds, functions.

#![allow(clippy::result_large_err)]

use std::collections::HashSet;

use crate::contract::schema;
use crate::diagnostics::{Diag, Spanned};
use crate::syntax::ast::{Expr, ExprKind, ParamSource, Stmt, Value, ValueKind};

use super::*;

/// The words a param may not be named: keywords, and every word of plan
/// and bench bodies (there a param's name is read as its value).
pub(super) fn reserved_words() -> HashSet<&'static str> {
    let mut words: HashSet<&'static str> = HashSet::new();
    for planner in crate::planners::registry::PLANNERS {
        for p in planner.all_params() {
            words.insert(p.key);
            words.extend(p.value.words());
        }
    }
    for p in schema::drive_params() {
        words.insert(p.key);
        words.extend(p.value.words());
    }
    words.extend(schema::DRIVE_MODELS);
    words.extend(schema::LIMIT_KINDS);
    words.extend(crate::scenario::BENCH_KEYS);
    words.extend(crate::syntax::STATEMENT_KEYWORDS);
    words.extend(crate::syntax::WORLD_ITEM_KEYWORDS);
    words.extend(crate::syntax::EXPRESSION_WORDS);
    words.extend(crate::syntax::UNIT_WORDS);
    words.extend(["yes", "no", "inf", "drive", "choice", "in"]);
    words.extend(FUNCTIONS);
    words.extend(DISTRIBUTIONS);
    words
}

/// Whether a value holds an expression (to compute at each sample).
pub(super) fn has_expression(v: &Value) -> bool {
    match &v.kind {
        ValueKind::Calc { .. } => true,
        ValueKind::Tuple(items) | ValueKind::List(items) => items.iter().any(has_expression),
        _ => false,
    }
}

/// The names an expression reads.
pub(super) fn names(e: &Expr, out: &mut Vec<Spanned<String>>) {
    e.walk(&mut |n| {
        if let ExprKind::Name(name) = &n.kind {
            out.push(name.clone());
        }
    });
}

pub(super) fn unknown_function(function: &Spanned<String>, distributions: bool) -> Diag {
    let mut known: Vec<&str> = FUNCTIONS.to_vec();
    if distributions {
        known.extend(DISTRIBUTIONS);
    }
    let help = match schema::did_you_mean(&function.value, known.iter().copied()) {
        Some(s) => format!("did you mean `{s}`?"),
        None => format!("the functions are {}", schema::backticked(&known)),
    };
    Diag::error(
        "scen::family::unknown_function",
        format!("unknown function `{}`", function.value),
    )
    .at(function.span, "not a function")
    .help(help)
}

pub(super) fn distribution_help(f: &str) -> &'static str {
    match f {
        "uniform" => "`uniform(a, b)`: a number drawn uniformly in [a, b), a < b",
        "normal" => {
            "`normal(m, s)`: a number drawn from the normal distribution of mean m and standard deviation s ≥ 0"
        }
        _ => "`int(a, b)`: a whole number drawn uniformly from a to b inclusive, a ≤ b",
    }
}

impl Family {
    /// A param's source from its declaration; the names it reads must be
    /// params declared before it.
    pub(super) fn source(
        &self,
        p: &crate::syntax::ast::ParamDecl,
        diags: &mut Vec<Diag>,
    ) -> Option<Source> {
        let before = diags.len();
        let value = match &p.value {
            ParamSource::Choice { values, .. } => {
                let ValueKind::List(items) = &values.kind else {
                    unreachable!("grammar guarantees a list after `choice`")
                };
                if items.is_empty() {
                    diags.push(
                        Diag::error("scen::family::empty_choice", "`choice` of no values")
                            .at(values.span, "an empty list")
                            .help("list the values to choose from: `choice [1, 2, 5]`"),
                    );
                    return None;
                }
                for item in items {
                    self.check_value(item, Some(&p.name), false, diags);
                }
                return (diags.len() == before).then(|| Source::Choice(items.clone()));
            }
            ParamSource::Value(v) => v,
        };
        if let ValueKind::Calc { expr, unit: None } = &value.kind
            && let ExprKind::Call { function, args } = &expr.kind
            && DISTRIBUTIONS.contains(&function.value.as_str())
        {
            if args.len() != 2 {
                diags.push(
                    Diag::error(
                        "scen::family::bad_distribution",
                        format!("`{}` takes two numbers", function.value),
                    )
                    .at(expr.span, format!("{} argument(s)", args.len()))
                    .help(distribution_help(&function.value)),
                );
                return None;
            }
            for a in args {
                self.check_expr(a, Some(&p.name), false, diags);
            }
            if diags.len() > before {
                return None;
            }
            let (a, b) = (args[0].clone(), args[1].clone());
            // Constant bounds are checked now; others at each draw.
            if let (Ok(x), Ok(y)) = (eval(&a, &[], &self.index), eval(&b, &[], &self.index))
                && let Err(d) = check_distribution(&function.value, x, y, expr.span)
            {
                diags.push(d);
                return None;
            }
            return Some(match function.value.as_str() {
                "uniform" => Source::Uniform(a, b),
                "normal" => Source::Normal(a, b),
                _ => Source::Int(a, b),
            });
        }
        self.check_value(value, Some(&p.name), false, diags);
        (diags.len() == before).then(|| Source::Value(value.clone()))
    }

    pub(super) fn check_statement(&self, stmt: &Stmt, diags: &mut Vec<Diag>) {
        // A param's own value is checked with its declaration (`source`).
        if !matches!(stmt, Stmt::Param(_)) {
            stmt.each_value(&mut |v, size| self.check_value(v, None, size, diags));
        }
        match stmt {
            Stmt::Expect(e) => {
                let mut used = Vec::new();
                names(e, &mut used);
                for name in used {
                    if !self.index.contains_key(&name.value) {
                        diags.push(
                            Diag::error(
                                "scen::analyze::unknown_name",
                                format!("`{}` is neither a metric nor a param", name.value),
                            )
                            .at(name.span, "not a metric or a param")
                            .help(
                                "refer to a metric as `PLAN.METRIC`, e.g. `offline.found`, or declare the param: `param NAME = uniform(0, 1)`",
                            ),
                        );
                    }
                }
            }
            Stmt::Require { condition, .. } => {
                if !is_condition(condition) {
                    diags.push(
                        Diag::error(
                            "scen::family::bad_expression",
                            "a `require` is a condition",
                        )
                        .at(condition.span, "a number, not a condition")
                        .help("compare: `require gap > 0.6`; join conditions with `and`, `or`, `not`"),
                    );
                }
                condition.walk(&mut |n| match &n.kind {
                    ExprKind::Metric { .. } | ExprKind::Series { .. } => diags.push(
                        Diag::error(
                            "scen::family::require_reads_metric",
                            "a `require` reads params only",
                        )
                        .at(n.span, "a metric")
                        .help("`require` constrains the draws before anything runs; check results with `expect`"),
                    ),
                    ExprKind::Call { function, .. } if !FUNCTIONS.contains(&function.value.as_str()) => {
                        diags.push(unknown_function(function, false));
                    }
                    ExprKind::Name(name) if !self.index.contains_key(&name.value) => {
                        diags.push(self.unknown_param(name));
                    }
                    _ => {}
                });
            }
            _ => {}
        }
    }

    /// Checks the expressions inside a value. `param`: the param being
    /// declared (its value may read only earlier params).
    pub(super) fn check_value(
        &self,
        v: &Value,
        param: Option<&Spanned<String>>,
        distributions: bool,
        diags: &mut Vec<Diag>,
    ) {
        match &v.kind {
            ValueKind::Calc { expr, .. } => self.check_expr(expr, param, distributions, diags),
            ValueKind::Tuple(items) | ValueKind::List(items) => {
                for item in items {
                    self.check_value(item, param, distributions, diags);
                }
            }
            _ => {}
        }
    }

    pub(super) fn check_expr(
        &self,
        e: &Expr,
        param: Option<&Spanned<String>>,
        distributions: bool,
        diags: &mut Vec<Diag>,
    ) {
        let declared = param.map_or(self.params.len(), |p| {
            self.index
                .get(&p.value)
                .copied()
                .unwrap_or(self.params.len())
        });
        e.walk(&mut |n| match &n.kind {
            ExprKind::Name(name) => match self.index.get(&name.value) {
                None => diags.push(self.unknown_param(name)),
                Some(_) if param.is_some_and(|p| p.value == name.value) => diags.push(
                    Diag::error(
                        "scen::family::param_cycle",
                        format!("the param `{}` is defined in terms of itself", name.value),
                    )
                    .at(name.span, "used in its own definition")
                    .help("a param is drawn from a distribution or computed from params declared before it"),
                ),
                Some(&k) if k >= declared => diags.push(
                    Diag::error(
                        "scen::family::param_before_declared",
                        format!("the param `{}` is used before it is declared", name.value),
                    )
                    .at(name.span, "declared further down")
                    .with_related(self.params[k].name.span, "declared here")
                    .help(format!(
                        "move `param {}` above this one: a param may read only the params declared before it",
                        name.value
                    )),
                ),
                Some(_) => {}
            },
            ExprKind::Call { function, args } => {
                let f = function.value.as_str();
                if DISTRIBUTIONS.contains(&f) {
                    if !distributions {
                        diags.push(
                            Diag::error(
                                "scen::family::distribution_here",
                                format!("a distribution `{f}(...)` cannot stand here"),
                            )
                            .at(n.span, "drawn where a number is computed")
                            .help(format!(
                                "draw it in a param and use its name: `param r = {f}(a, b)`; distributions stand alone after `param NAME =` and in a scatter's sizes"
                            )),
                        );
                    } else if args.len() != 2 {
                        diags.push(
                            Diag::error(
                                "scen::family::bad_distribution",
                                format!("`{f}` takes two numbers"),
                            )
                            .at(n.span, format!("{} argument(s)", args.len()))
                            .help(distribution_help(f)),
                        );
                    }
                } else if !FUNCTIONS.contains(&f) {
                    diags.push(unknown_function(function, distributions));
                } else {
                    let arity_ok = match f {
                        "min" | "max" => !args.is_empty(),
                        _ => args.len() == 1,
                    };
                    if !arity_ok {
                        diags.push(
                            Diag::error(
                                "scen::family::bad_call",
                                format!("`{f}` takes {}", if f == "min" || f == "max" { "one or more numbers" } else { "one number" }),
                            )
                            .at(n.span, format!("{} argument(s)", args.len()))
                            .help("functions: `min(a, b, ...)`, `max(a, b, ...)`, `abs(x)`, `sqrt(x)`"),
                        );
                    }
                }
            }
            _ => {}
        });
    }

    pub(super) fn unknown_param(&self, name: &Spanned<String>) -> Diag {
        let known: Vec<&str> = self.params.iter().map(|p| p.name.value.as_str()).collect();
        let help = match schema::did_you_mean(&name.value, known.iter().copied()) {
            Some(s) => format!("did you mean `{s}`?"),
            None => format!("declare it first: `param {} = uniform(0, 1)`", name.value),
        };
        Diag::error(
            "scen::family::unknown_param",
            format!("unknown param `{}`", name.value),
        )
        .at(name.span, "not a declared param")
        .help(help)
    }
}
