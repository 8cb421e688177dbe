//! Scenario families (SPEC 2.8): `param`, `scatter`, `require`, and
//! expressions in number positions.
//!
//! A family is a template of scenarios. [`Family::of`] reads its params and
//! constraints and checks everything that does not depend on a draw (names,
//! the order of params, distributions and their constant bounds, functions);
//! [`Family::draw`] draws one sample from its seeded stream and
//! [`Family::instantiate`] writes the sample's statements: every expression
//! replaced by its number, every param's name in a plan or bench body by its
//! value, every `scatter` by its obstacles. The analyzer then sees a plain
//! scenario, so every check of a hand-written scenario holds for every
//! sample, with the diagnostics pointing at the expressions.
//!
//! Sample k of a family with seed s draws from the stream
//! `SplitMix64(mix(s, k, attempt))`, params in the order written, then the
//! scattered items in order: same k, same world, on any machine and any
//! number of threads. A draw that violates a `require`, or that the analyzer
//! rejects only because a start or goal is outside `bounds` or in
//! collision, is drawn again (attempt + 1), at most [`MAX_ATTEMPTS`] times.

// A `Diag` is the error of every fallible step here, as in the loader: a
// cold path, returned once per failure.
#![allow(clippy::result_large_err)]

use std::collections::{HashMap, HashSet};

use crate::contract::MetricValue;
use crate::contract::schema;
use crate::diagnostics::{Diag, Span, Spanned};
use crate::rng::SplitMix64;
use crate::syntax::ast::{
    Angle, BenchDecl, Expr, ExprKind, ObstacleDecl, ObstacleKind, ObstacleShape, ParamSource,
    ParamToken, PlanDecl, ScatterDecl, ScatterShape, Stmt, Value, ValueKind, WorldItem,
};

use super::placed::{Placed, Placements};
use super::statements::SourcedStmt;

/// How many draws of one sample may be rejected before it is an error.
pub const MAX_ATTEMPTS: u32 = 1000;
/// How many tries a scattered item gets to find its place.
const MAX_PLACEMENT_TRIES: u32 = 1000;
/// The most items one `scatter` may place.
pub const MAX_SCATTER_ITEMS: f64 = 100_000.0;

/// Which sample of a family to run (SPEC 2.8: `--sample`, `--family-seed`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SampleChoice {
    pub sample: u64,
    pub family_seed: u64,
}

/// What a sample drew, for the report and JSON.
#[derive(Clone, Debug, PartialEq)]
pub struct Drawn {
    pub sample: u64,
    pub family_seed: u64,
    /// Every param's value, in declaration order.
    pub params: Vec<(String, f64)>,
    /// Draws rejected before this one (by a `require` or a start or goal).
    pub rejected: u32,
}

/// The functions of number expressions.
pub const FUNCTIONS: &[&str] = &["min", "max", "abs", "sqrt"];
/// The distributions of `param` and scatter sizes.
pub const DISTRIBUTIONS: &[&str] = &["uniform", "normal", "int"];

/// What a param is drawn from.
#[derive(Clone, Debug)]
enum Source {
    Uniform(Expr, Expr),
    Normal(Expr, Expr),
    Int(Expr, Expr),
    Choice(Vec<Value>),
    /// A constant or an expression of earlier params.
    Value(Value),
}

#[derive(Clone, Debug)]
struct ParamDef {
    name: Spanned<String>,
    source: Source,
}

impl ParamDef {
    /// Drawn (from a distribution or a `choice`), not computed.
    fn drawn(&self) -> bool {
        !matches!(self.source, Source::Value(_))
    }
}

/// A family's params and constraints, checked.
#[derive(Debug, Default)]
pub(crate) struct Family {
    params: Vec<ParamDef>,
    index: HashMap<String, usize>,
    requires: Vec<(Expr, Span)>,
    /// Whether the statements have anything to draw or compute (a param,
    /// a scatter, an expression); when not, a sample is the file itself.
    active: bool,
    /// Whether a `scatter` draws obstacles.
    scatters: bool,
}

/// A sample's statements and its params' values, by name.
pub(crate) type Instance = (Vec<SourcedStmt>, Vec<(String, f64)>);

/// One draw: the params' values and the rng, positioned after them.
struct Draw {
    values: Vec<f64>,
    rng: SplitMix64,
}

/// What the drawn params take instead of the stream's draws.
#[derive(Clone, Copy)]
enum Given<'a> {
    /// A search's point of the unit cube.
    Unit(&'a [f64]),
    /// `--set`'s values, by param index (empty or `None`: the draw).
    Set(&'a [Option<f64>]),
}

/// A `--set` that names no family member (exit 2).
fn bad_set(message: String, span: Span, label: &str, help: impl Into<String>) -> Diag {
    Diag::error("scen::family::bad_set", message)
        .at(span, label.to_string())
        .help(help.into())
}

/// SplitMix64's finaliser, to derive independent stream seeds.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The seed of the stream of one attempt at one sample.
fn stream_seed(choice: SampleChoice, attempt: u32) -> u64 {
    mix(mix(mix(choice.family_seed) ^ choice.sample).wrapping_add(u64::from(attempt)))
}

/// The words a param may not be named: keywords, and every word of plan
/// and bench bodies (there a param's name is read as its value).
fn reserved_words() -> HashSet<&'static str> {
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
    words.extend(super::BENCH_KEYS);
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
fn has_expression(v: &Value) -> bool {
    match &v.kind {
        ValueKind::Calc { .. } => true,
        ValueKind::Tuple(items) | ValueKind::List(items) => items.iter().any(has_expression),
        _ => false,
    }
}

/// The names an expression reads.
fn names(e: &Expr, out: &mut Vec<Spanned<String>>) {
    e.walk(&mut |n| {
        if let ExprKind::Name(name) = &n.kind {
            out.push(name.clone());
        }
    });
}

impl Family {
    /// The family of a scenario's statements, or the errors that do not
    /// depend on a draw.
    pub fn of(statements: &[SourcedStmt]) -> Result<Family, Vec<Diag>> {
        let mut family = Family::default();
        let mut diags = Vec::new();
        let reserved = reserved_words();
        // First every param's name, so that a use before the declaration
        // is reported as such.
        let mut decls = Vec::new();
        for s in statements {
            match &s.stmt {
                Stmt::Param(p) => {
                    let name = &p.name.value;
                    if let Some(&k) = family.index.get(name) {
                        diags.push(
                            Diag::error(
                                "scen::family::duplicate_param",
                                format!("the param `{name}` is declared twice"),
                            )
                            .at(p.name.span, "declared again here")
                            .with_related(family.params[k].name.span, "first declared here")
                            .help("give each param its own name"),
                        );
                        continue;
                    }
                    if reserved.contains(name.as_str()) {
                        diags.push(
                            Diag::error(
                                "scen::family::reserved_name",
                                format!("`{name}` is a word of the language and cannot name a param"),
                            )
                            .at(p.name.span, "a reserved word")
                            .help(format!(
                                "choose another name, e.g. `{name}_value`: in plan bodies a param's name stands for its value"
                            )),
                        );
                        continue;
                    }
                    family.index.insert(name.clone(), family.params.len());
                    // A placeholder until its source is read below.
                    family.params.push(ParamDef {
                        name: p.name.clone(),
                        source: Source::Value(Value {
                            kind: ValueKind::Number(0.0),
                            span: p.span,
                        }),
                    });
                    decls.push(p);
                }
                Stmt::Require { condition, span } => {
                    family.requires.push((condition.clone(), *span));
                }
                _ => {}
            }
        }
        for p in decls {
            if let Some(source) = family.source(p, &mut diags) {
                let k = family.index[&p.name.value];
                family.params[k].source = source;
            }
        }
        // Every other expression: names are params, calls are functions
        // (distributions only in a scatter's sizes).
        for s in statements {
            family.check_statement(&s.stmt, &mut diags);
        }
        family.scatters = statements.iter().any(|s| {
            matches!(&s.stmt, Stmt::World(w) if w.items.iter().any(|i| matches!(i, WorldItem::Scatter(_))))
        });
        family.active = family.scatters
            || statements.iter().any(|s| {
                let mut computed = matches!(s.stmt, Stmt::Param(_) | Stmt::Require { .. });
                s.stmt
                    .each_value(&mut |v, _| computed = computed || has_expression(v));
                computed
            });
        if diags.is_empty() {
            Ok(family)
        } else {
            Err(diags)
        }
    }

    /// The params' indices by name.
    pub(crate) fn index(&self) -> &HashMap<String, usize> {
        &self.index
    }

    /// Whether there is anything to draw or compute.
    pub fn is_active(&self) -> bool {
        self.active
    }

    /// Whether the family draws anything (a param or a scatter): a plain
    /// scenario with constant expressions has one sample only.
    pub fn draws(&self) -> bool {
        !self.params.is_empty() || self.scatters
    }

    /// A param's source from its declaration; the names it reads must be
    /// params declared before it.
    fn source(&self, p: &crate::syntax::ast::ParamDecl, diags: &mut Vec<Diag>) -> Option<Source> {
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

    fn check_statement(&self, stmt: &Stmt, diags: &mut Vec<Diag>) {
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
    fn check_value(
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

    fn check_expr(
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

    fn unknown_param(&self, name: &Spanned<String>) -> Diag {
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

    /// Draws the params of one attempt at one sample, those `set` gives
    /// taking its values.
    fn draw_params(
        &self,
        choice: SampleChoice,
        attempt: u32,
        set: &[Option<f64>],
    ) -> Result<Draw, Diag> {
        self.draw_params_with(
            SplitMix64::new(stream_seed(choice, attempt)),
            Given::Set(set),
        )
    }

    /// How many params are drawn (from a distribution or a `choice`): the
    /// dimension of the unit cube a search walks ([`Family::candidate`]).
    pub fn dims(&self) -> usize {
        self.params.iter().filter(|p| p.drawn()).count()
    }

    /// One candidate of a search: attempt 0 of sample `choice` with its
    /// drawn params at `unit` instead (one coordinate in [0, 1) per drawn
    /// param, through each distribution's inverse distribution function).
    /// The stream is consumed as the sample's is, so the scattered items
    /// are those of `scen run --sample K --set NAME=VALUE...` with these
    /// params' values. Its statements and params; `None` when a `require`
    /// rejects it.
    pub(crate) fn candidate(
        &self,
        statements: &[SourcedStmt],
        choice: SampleChoice,
        unit: &[f64],
    ) -> Result<Option<Instance>, Vec<Diag>> {
        let mut draw = self
            .draw_params_with(SplitMix64::new(stream_seed(choice, 0)), Given::Unit(unit))
            .map_err(|d| vec![d])?;
        if self.violated(&draw.values).map_err(|d| vec![d])?.is_some() {
            return Ok(None);
        }
        let params = self.named(&draw.values);
        Ok(Some((self.instantiate(statements, &mut draw)?, params)))
    }

    /// Every param's value with its name, in declaration order.
    fn named(&self, values: &[f64]) -> Vec<(String, f64)> {
        self.params
            .iter()
            .zip(values)
            .map(|(p, &x)| (p.name.value.clone(), x))
            .collect()
    }

    /// The drawn params' values given as `NAME=VALUE` (`scen run --set`),
    /// by param index (`None`: drawn as usual). Errors: not `NAME=VALUE`,
    /// an unknown or computed param, not a number, a family that draws
    /// nothing. Whether a value is in its distribution's support is
    /// checked at the draw (bounds may read earlier params).
    pub(crate) fn resolve_set(&self, set: &[String]) -> Result<Vec<Option<f64>>, Vec<Diag>> {
        if set.is_empty() {
            return Ok(Vec::new());
        }
        let anchor = self
            .params
            .first()
            .map_or(Span::new(0, 0, 0), |p| p.name.span);
        let mut out = vec![None; self.params.len()];
        let mut diags = Vec::new();
        for given in set {
            let Some((name, value)) = given.split_once('=') else {
                diags.push(bad_set(
                    format!("`--set {given}` is not `NAME=VALUE`"),
                    anchor,
                    "the family's params are declared from here",
                    "give a param's value as `--set NAME=VALUE`, e.g. `--set gap=1.25`",
                ));
                continue;
            };
            let name = name.trim();
            let Some(&k) = self.index.get(name) else {
                let known: Vec<&str> = self.drawn_names();
                let help = match schema::did_you_mean(name, known.iter().copied()) {
                    Some(s) => format!("did you mean `{s}`?"),
                    None if known.is_empty() => {
                        "this scenario draws no param: run it without `--set`".to_string()
                    }
                    None => format!("the drawn params are {}", schema::backticked(&known)),
                };
                diags.push(bad_set(
                    format!("`--set {given}`: the scenario has no param `{name}`"),
                    anchor,
                    "the family's params are declared from here",
                    help,
                ));
                continue;
            };
            let p = &self.params[k];
            if !p.drawn() {
                diags.push(bad_set(
                    format!(
                        "`--set {given}`: the param `{name}` is computed from others, not drawn"
                    ),
                    p.name.span,
                    "computed here",
                    "set the drawn params it is computed from",
                ));
                continue;
            }
            match value.trim().parse::<f64>() {
                Ok(x) if x.is_finite() => out[k] = Some(x),
                _ => diags.push(bad_set(
                    format!("`--set {given}`: `{}` is not a number", value.trim()),
                    p.name.span,
                    "the param set",
                    "write a finite number, e.g. `--set gap=1.25` (what `scen falsify` prints)",
                )),
            }
        }
        if diags.is_empty() {
            Ok(out)
        } else {
            Err(diags)
        }
    }

    /// Why `x` is not a value param `p` can draw (its support), given the
    /// earlier params' values; `None` when it is one.
    fn outside_support(
        &self,
        p: &ParamDef,
        x: f64,
        values: &[f64],
    ) -> Result<Option<String>, Diag> {
        let bound = |e: &Expr| eval(e, values, &self.index).map_err(|e| e.diag(self, values));
        Ok(match &p.source {
            Source::Uniform(a, b) => {
                let (lo, hi) = (bound(a)?, bound(b)?);
                (!(lo <= x && x <= hi))
                    .then(|| format!("`uniform({lo}, {hi})` draws from {lo} to {hi}"))
            }
            Source::Int(a, b) => {
                let (lo, hi) = (bound(a)?.ceil(), bound(b)?.floor());
                (!(lo <= x && x <= hi && x.fract() == 0.0))
                    .then(|| format!("`int` draws the whole numbers from {lo} to {hi}"))
            }
            Source::Choice(items) => {
                let mut all = Vec::new();
                for item in items {
                    all.push(self.number(item, values)?);
                }
                (!all.contains(&x)).then(|| {
                    format!(
                        "`choice` draws one of {}",
                        all.iter()
                            .map(|v| format!("{v}"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                })
            }
            Source::Normal(..) | Source::Value(_) => None,
        })
    }

    /// The values of the drawn params (those of a distribution or a
    /// `choice`) among all params' values, in order.
    pub(crate) fn drawn_values(&self, params: &[(String, f64)]) -> Vec<f64> {
        self.params
            .iter()
            .zip(params)
            .filter(|(p, _)| p.drawn())
            .map(|(_, (_, x))| *x)
            .collect()
    }

    /// The names of the drawn params, in the order of
    /// [`Family::drawn_values`].
    pub(crate) fn drawn_names(&self) -> Vec<&str> {
        self.params
            .iter()
            .filter(|p| p.drawn())
            .map(|p| p.name.value.as_str())
            .collect()
    }

    /// Draws the params from `rng`; the drawn ones then take the value
    /// `given` (a search's point, or `--set`'s values), the stream
    /// consumed all the same so that the scattered items after them come
    /// from the same place of it.
    fn draw_params_with(&self, mut rng: SplitMix64, given: Given<'_>) -> Result<Draw, Diag> {
        let mut values: Vec<f64> = Vec::with_capacity(self.params.len());
        let mut coordinates = match given {
            Given::Unit(u) => Some(u.iter().copied()),
            Given::Set(_) => None,
        };
        let mut next_u = || {
            coordinates
                .as_mut()
                .map(|it| it.next().unwrap_or(0.5).clamp(0.0, 1.0 - f64::EPSILON))
        };
        for (i, p) in self.params.iter().enumerate() {
            let x = match &p.source {
                Source::Uniform(a, b) | Source::Normal(a, b) | Source::Int(a, b) => {
                    let x = eval(a, &values, &self.index).map_err(|e| e.diag(self, &values))?;
                    let y = eval(b, &values, &self.index).map_err(|e| e.diag(self, &values))?;
                    let f = match &p.source {
                        Source::Uniform(..) => "uniform",
                        Source::Normal(..) => "normal",
                        _ => "int",
                    };
                    check_distribution(f, x, y, a.span.to(b.span))?;
                    let drawn = sample(f, x, y, &mut rng);
                    match next_u() {
                        Some(u) => inverse(f, x, y, u),
                        None => drawn,
                    }
                }
                Source::Choice(items) => {
                    let drawn = (rng.next_u64() % items.len() as u64) as usize;
                    let k = match next_u() {
                        Some(u) => ((u * items.len() as f64) as usize).min(items.len() - 1),
                        None => drawn,
                    };
                    self.number(&items[k], &values)?
                }
                Source::Value(v) => self.number(v, &values)?,
            };
            let x = match given {
                Given::Set(set) if p.drawn() => match set.get(i).copied().flatten() {
                    Some(v) => {
                        if let Some(support) = self.outside_support(p, v, &values)? {
                            return Err(bad_set(
                                format!(
                                    "`--set {}={v}` is outside what the param draws: {support}",
                                    p.name.value
                                ),
                                p.name.span,
                                "the param set",
                                "give a value the family can draw (a family member)",
                            ));
                        }
                        v
                    }
                    None => x,
                },
                _ => x,
            };
            values.push(x);
        }
        Ok(Draw { values, rng })
    }

    /// The number of a value that must be one (a choice's item, a
    /// computed param).
    fn number(&self, v: &Value, values: &[f64]) -> Result<f64, Diag> {
        match &v.kind {
            ValueKind::Number(x) => Ok(*x),
            ValueKind::Calc { expr, unit: None } => {
                eval(expr, values, &self.index).map_err(|e| e.diag(self, values))
            }
            other => Err(Diag::error(
                "scen::family::not_a_number",
                format!("a param is a number, not {}", other.describe()),
            )
            .at(v.span, "not a number")
            .help("write a number or an expression of numbers and params")),
        }
    }

    /// The first `require` a draw violates (its index).
    fn violated(&self, values: &[f64]) -> Result<Option<usize>, Diag> {
        for (k, (cond, _)) in self.requires.iter().enumerate() {
            let holds =
                eval_condition(cond, values, &self.index).map_err(|e| e.diag(self, values))?;
            if !holds {
                return Ok(Some(k));
            }
        }
        Ok(None)
    }

    /// The statements of one draw: expressions computed, params' names in
    /// bodies replaced, scatters placed.
    fn instantiate(
        &self,
        statements: &[SourcedStmt],
        draw: &mut Draw,
    ) -> Result<Vec<SourcedStmt>, Vec<Diag>> {
        let mut out = Vec::with_capacity(statements.len());
        let mut diags = Vec::new();
        let mut placed = Placements::default();
        let mut ctx = Ctx {
            family: self,
            draw,
            diags: &mut diags,
        };
        for s in statements {
            let stmt = match &s.stmt {
                Stmt::Param(_) | Stmt::Require { .. } => continue,
                Stmt::World(w) => {
                    let mut w = w.clone();
                    let mut items = Vec::with_capacity(w.items.len());
                    for item in std::mem::take(&mut w.items) {
                        match item {
                            WorldItem::Scatter(sc) => {
                                ctx.scatter(&sc, &mut placed, &mut items);
                            }
                            mut item => {
                                ctx.item(&mut item);
                                items.push(item);
                            }
                        }
                    }
                    w.items = items;
                    Stmt::World(w)
                }
                Stmt::Robot(r) => {
                    let mut r = r.clone();
                    use crate::syntax::ast::RobotShape;
                    match &mut r.shape {
                        RobotShape::Point(_) => {}
                        RobotShape::Disk(v) | RobotShape::Polygon(v) => ctx.value(v),
                        RobotShape::Rect(a, b) => {
                            ctx.value(a);
                            ctx.value(b);
                        }
                    }
                    if let Some(steer) = &mut r.steer {
                        ctx.value(&mut steer.radius);
                    }
                    Stmt::Robot(r)
                }
                Stmt::Plan(p) => {
                    let mut p = p.clone();
                    ctx.tokens(&mut p.body);
                    Stmt::Plan(p)
                }
                Stmt::Bench(b) => {
                    let mut b = b.clone();
                    ctx.tokens(&mut b.body);
                    Stmt::Bench(b)
                }
                Stmt::Expect(e) => {
                    let mut e = e.clone();
                    ctx.expr(&mut e);
                    Stmt::Expect(e)
                }
                other => other.clone(),
            };
            out.push(SourcedStmt {
                stmt,
                in_main_file: s.in_main_file,
            });
        }
        if diags.is_empty() {
            Ok(out)
        } else {
            Err(diags)
        }
    }

    /// Sample `choice` of the family: its statements and what it drew.
    /// `set` gives some drawn params' values ([`Family::resolve_set`];
    /// empty: none), the rest is drawn as usual. `analyze` analyses an
    /// instance; a failure whose errors are all a start or goal outside
    /// `bounds` or in collision is a rejection.
    pub fn sample<T>(
        &self,
        statements: &[SourcedStmt],
        choice: SampleChoice,
        set: &[Option<f64>],
        mut analyze: impl FnMut(Vec<SourcedStmt>) -> Result<T, Vec<Diag>>,
    ) -> Result<(T, Drawn), Vec<Diag>> {
        let mut by_require = vec![0u32; self.requires.len()];
        let mut by_pose: Option<(u32, Diag)> = None;
        // Every drawn param given: no draw can satisfy a `require` they
        // violate.
        let all_set = !set.is_empty()
            && self
                .params
                .iter()
                .zip(set)
                .all(|(p, v)| !p.drawn() || v.is_some());
        for attempt in 0..MAX_ATTEMPTS {
            let mut draw = self
                .draw_params(choice, attempt, set)
                .map_err(|d| vec![d])?;
            if let Some(k) = self.violated(&draw.values).map_err(|d| vec![d])? {
                if all_set {
                    return Err(vec![bad_set(
                        format!(
                            "the values given with `--set` ({}) violate a `require`",
                            self.named(&draw.values)
                                .iter()
                                .zip(&self.params)
                                .filter(|(_, p)| p.drawn())
                                .map(|((n, x), _)| format!("{n} = {x}"))
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                        self.requires[k].1,
                        "violated",
                        "give values that satisfy every `require` (a family member)",
                    )]);
                }
                by_require[k] += 1;
                continue;
            }
            let instance = self.instantiate(statements, &mut draw)?;
            match analyze(instance) {
                Ok(t) => {
                    let params = self
                        .params
                        .iter()
                        .zip(&draw.values)
                        .map(|(p, &x)| (p.name.value.clone(), x))
                        .collect();
                    return Ok((
                        t,
                        Drawn {
                            sample: choice.sample,
                            family_seed: choice.family_seed,
                            params,
                            rejected: attempt,
                        },
                    ));
                }
                Err(diags) => {
                    let rejection = !diags.is_empty()
                        && self.draws()
                        && diags.iter().filter(|d| d.is_error()).all(|d| {
                            matches!(
                                d.code,
                                "scen::analyze::pose_outside" | "scen::analyze::pose_in_collision"
                            )
                        });
                    if !rejection {
                        return Err(diags);
                    }
                    let first = diags.into_iter().find(Diag::is_error).expect("an error");
                    let count = by_pose.as_ref().map_or(0, |(n, _)| *n) + 1;
                    by_pose = Some((count, first));
                }
            }
        }
        // Every draw rejected: name the constraint that rejected most.
        let (k, most) = by_require
            .iter()
            .enumerate()
            .max_by_key(|&(k, n)| (*n, std::cmp::Reverse(k)))
            .map_or((0, 0), |(k, n)| (k, *n));
        let poses = by_pose.as_ref().map_or(0, |(n, _)| *n);
        let counts = format!(
            "{MAX_ATTEMPTS} draws of sample {} were all rejected ({})",
            choice.sample,
            by_require
                .iter()
                .zip(&self.requires)
                .map(|(n, _)| *n)
                .enumerate()
                .filter(|(_, n)| *n > 0)
                .map(|(k, n)| format!("require #{}: {n}", k + 1))
                .chain((poses > 0).then(|| format!("start or goal: {poses}")))
                .collect::<Vec<_>>()
                .join(", ")
        );
        let diag = if most >= poses && !self.requires.is_empty() {
            Diag::error("scen::family::rejects_every_draw", counts)
                .at(self.requires[k].1, format!("rejected {most} of {MAX_ATTEMPTS} draws"))
                .help("loosen the constraint or the params' distributions so that some draws satisfy it")
        } else {
            let (_, pose) = by_pose.expect("some rejection");
            let mut d = Diag::error("scen::family::rejects_every_draw", counts).help(format!(
                "every draw puts a start or goal outside `bounds` or in collision ({}); change the distributions or the poses",
                pose.message
            ));
            if let Some(span) = pose.span {
                d = d.at(span, "rejected in every draw");
            }
            d
        };
        Err(vec![diag])
    }
}

/// Writes one instance.
struct Ctx<'a> {
    family: &'a Family,
    draw: &'a mut Draw,
    diags: &'a mut Vec<Diag>,
}

impl Ctx<'_> {
    fn eval(&mut self, e: &Expr) -> Option<f64> {
        match eval_drawing(e, &self.draw.values, &self.family.index, &mut self.draw.rng) {
            Ok(x) => Some(x),
            Err(err) => {
                self.diags.push(err.diag(self.family, &self.draw.values));
                None
            }
        }
    }

    fn value(&mut self, v: &mut Value) {
        match &mut v.kind {
            ValueKind::Calc { expr, unit } => {
                let unit = *unit;
                let Some(x) = self.eval(expr) else { return };
                v.kind = match unit {
                    Some(unit) => ValueKind::Angle(Angle { written: x, unit }),
                    None => ValueKind::Number(x),
                };
            }
            ValueKind::Word(w) => {
                if let Some(&k) = self.family.index.get(w.as_str()) {
                    v.kind = ValueKind::Number(self.draw.values[k]);
                }
            }
            ValueKind::Tuple(items) | ValueKind::List(items) => {
                for item in items {
                    self.value(item);
                }
            }
            _ => {}
        }
    }

    fn tokens(&mut self, tokens: &mut [ParamToken]) {
        for t in tokens {
            match t {
                ParamToken::Word(w) => {
                    if let Some(&k) = self.family.index.get(&w.value) {
                        *t = ParamToken::Value(Value {
                            kind: ValueKind::Number(self.draw.values[k]),
                            span: w.span,
                        });
                    }
                }
                ParamToken::Value(v) => self.value(v),
                ParamToken::Block { tokens, .. } => self.tokens(tokens),
            }
        }
    }

    fn expr(&mut self, e: &mut Expr) {
        if let ExprKind::Name(name) = &e.kind {
            if let Some(&k) = self.family.index.get(&name.value) {
                e.kind = ExprKind::Number(self.draw.values[k]);
            }
            return;
        }
        match &mut e.kind {
            ExprKind::Series { select, .. } => {
                for s in select {
                    self.value(&mut s.value);
                }
            }
            ExprKind::Call { args, .. } => args.iter_mut().for_each(|a| self.expr(a)),
            ExprKind::Neg(x) | ExprKind::Not(x) => self.expr(x),
            ExprKind::Where(a, b)
            | ExprKind::And(a, b)
            | ExprKind::Or(a, b)
            | ExprKind::Arith { lhs: a, rhs: b, .. }
            | ExprKind::Compare { lhs: a, rhs: b, .. } => {
                self.expr(a);
                self.expr(b);
            }
            ExprKind::Approx { lhs, rhs, tol } => {
                self.expr(lhs);
                self.expr(rhs);
                self.expr(tol);
            }
            _ => {}
        }
    }

    fn item(&mut self, item: &mut WorldItem) {
        match item {
            WorldItem::Bounds { min, max, .. } => {
                self.value(min);
                self.value(max);
            }
            WorldItem::Obstacle(o) => match &mut o.shape {
                ObstacleShape::Rect(a, b)
                | ObstacleShape::Segment(a, b)
                | ObstacleShape::Disk(a, b) => {
                    self.value(a);
                    self.value(b);
                }
                ObstacleShape::Polygon(v) => self.value(v),
                ObstacleShape::Grid(g) => {
                    if let Some(v) = &mut g.cell {
                        self.value(v);
                    }
                    if let Some(v) = &mut g.origin {
                        self.value(v);
                    }
                }
            },
            WorldItem::Scatter(_) => unreachable!("scatters are placed by `scatter`"),
        }
    }

    /// A number of a scatter (its count, box, gap or a size).
    fn scatter_number(&mut self, v: &Value, what: &str, sc: &ScatterDecl) -> Option<f64> {
        let x = match &v.kind {
            ValueKind::Number(x) => *x,
            ValueKind::Calc { expr, unit: None } => self.eval(expr)?,
            ValueKind::Word(w) => match self.family.index.get(w.as_str()) {
                Some(&k) => self.draw.values[k],
                None => return self.scatter_error(v.span, what, sc),
            },
            _ => return self.scatter_error(v.span, what, sc),
        };
        Some(x)
    }

    fn scatter_error(&mut self, span: Span, what: &str, sc: &ScatterDecl) -> Option<f64> {
        self.diags.push(
            Diag::error(
                "scen::family::bad_scatter",
                format!("the {what} of scatter `{}` must be a number", sc.name.value),
            )
            .at(span, "not a number")
            .help("`scatter NAME N disk R in (x0, y0) (x1, y1) gap G`, sizes may be distributions: `disk uniform(0.2, 0.6)`"),
        );
        None
    }

    fn scatter_point(&mut self, v: &Value, what: &str, sc: &ScatterDecl) -> Option<(f64, f64)> {
        let ValueKind::Tuple(items) = &v.kind else {
            self.scatter_error(v.span, what, sc);
            return None;
        };
        if items.len() != 2 {
            self.scatter_error(v.span, what, sc);
            return None;
        }
        let x = self.scatter_number(&items[0], what, sc)?;
        let y = self.scatter_number(&items[1], what, sc)?;
        Some((x, y))
    }

    fn bad_scatter(&mut self, span: Span, sc: &ScatterDecl, message: String, help: &str) {
        self.diags.push(
            Diag::error("scen::family::bad_scatter", message)
                .at(span, format!("in scatter `{}`", sc.name.value))
                .help(help.to_string()),
        );
    }

    /// Places the items of a scatter, appending them as obstacles.
    fn scatter(&mut self, sc: &ScatterDecl, placed: &mut Placements, items: &mut Vec<WorldItem>) {
        let Some(count) = self.scatter_number(&sc.count, "count", sc) else {
            return;
        };
        if !(count >= 0.0 && count.fract() == 0.0 && count <= MAX_SCATTER_ITEMS) {
            self.bad_scatter(
                sc.count.span,
                sc,
                format!("a scatter places a whole number of items from 0 to {MAX_SCATTER_ITEMS}, not {count}"),
                "write the count as a whole number: `scatter rocks 30 disk 0.3 in (0, 0) (20, 8)`",
            );
            return;
        }
        let Some((x0, y0)) = self.scatter_point(&sc.min, "box corner", sc) else {
            return;
        };
        let Some((x1, y1)) = self.scatter_point(&sc.max, "box corner", sc) else {
            return;
        };
        if !(x0 < x1 && y0 < y1) {
            self.bad_scatter(
                sc.min.span.to(sc.max.span),
                sc,
                "a scatter's box needs its lower-left corner first".to_string(),
                "write `in (x0, y0) (x1, y1)` with x0 < x1 and y0 < y1",
            );
            return;
        }
        let gap = match &sc.gap {
            Some(g) => {
                let Some(gap) = self.scatter_number(g, "gap", sc) else {
                    return;
                };
                if gap < 0.0 {
                    self.bad_scatter(
                        g.span,
                        sc,
                        format!("a negative gap ({gap})"),
                        "the gap is the least distance between two items: 0 or more",
                    );
                    return;
                }
                gap
            }
            None => 0.0,
        };
        let name = &sc.name;
        let size = |this: &mut Self, v: &Value| -> Option<f64> {
            let x = this.scatter_number(v, "size", sc)?;
            if x > 0.0 {
                Some(x)
            } else {
                this.bad_scatter(
                    v.span,
                    sc,
                    format!("a scattered item's size must be positive, drew {x}"),
                    "use sizes (or distributions of sizes) above 0",
                );
                None
            }
        };
        for i in 1..=count as usize {
            let mut done = false;
            for _ in 0..MAX_PLACEMENT_TRIES {
                let (shape, item) = match &sc.shape {
                    ScatterShape::Disk { keyword, radius } => {
                        let Some(r) = size(self, radius) else { return };
                        let x = self.draw.rng.range(x0, x1);
                        let y = self.draw.rng.range(y0, y1);
                        (
                            ObstacleShape::Disk(
                                point_value(x, y, radius.span),
                                number_value(r, radius.span),
                            ),
                            (Placed::Disk { x, y, r }, ObstacleKind::Disk, *keyword),
                        )
                    }
                    ScatterShape::Rect {
                        keyword,
                        width,
                        height,
                    } => {
                        let Some(w) = size(self, width) else { return };
                        let Some(h) = size(self, height) else { return };
                        let x = self.draw.rng.range(x0, x1);
                        let y = self.draw.rng.range(y0, y1);
                        let (ax, ay, bx, by) = (x - w / 2.0, y - h / 2.0, x + w / 2.0, y + h / 2.0);
                        (
                            ObstacleShape::Rect(
                                point_value(ax, ay, width.span),
                                point_value(bx, by, height.span),
                            ),
                            (
                                Placed::Rect {
                                    x0: ax,
                                    y0: ay,
                                    x1: bx,
                                    y1: by,
                                },
                                ObstacleKind::Rect,
                                *keyword,
                            ),
                        )
                    }
                };
                let (here, kind, keyword) = item;
                if placed.crowds(&here, gap) {
                    continue;
                }
                placed.push(here);
                items.push(WorldItem::Obstacle(ObstacleDecl {
                    kind: Spanned::new(kind, keyword),
                    name: Some(Spanned::new(format!("{}_{i}", name.value), name.span)),
                    shape,
                    span: sc.span,
                }));
                done = true;
                break;
            }
            if !done {
                self.bad_scatter(
                    sc.span,
                    sc,
                    format!(
                        "scatter `{}` could not place item {i} of {count} at least {gap} from the others in {MAX_PLACEMENT_TRIES} tries",
                        name.value
                    ),
                    "place fewer or smaller items, a smaller gap, or a larger box",
                );
                return;
            }
        }
    }
}

fn number_value(x: f64, span: Span) -> Value {
    Value {
        kind: ValueKind::Number(x),
        span,
    }
}

fn point_value(x: f64, y: f64, span: Span) -> Value {
    Value {
        kind: ValueKind::Tuple(vec![number_value(x, span), number_value(y, span)]),
        span,
    }
}

fn unknown_function(function: &Spanned<String>, distributions: bool) -> Diag {
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

fn distribution_help(f: &str) -> &'static str {
    match f {
        "uniform" => "`uniform(a, b)`: a number drawn uniformly in [a, b), a < b",
        "normal" => {
            "`normal(m, s)`: a number drawn from the normal distribution of mean m and standard deviation s ≥ 0"
        }
        _ => "`int(a, b)`: a whole number drawn uniformly from a to b inclusive, a ≤ b",
    }
}

/// The bounds of a distribution, checked.
fn check_distribution(f: &str, a: f64, b: f64, span: Span) -> Result<(), Diag> {
    let problem = match f {
        "uniform" if a >= b => Some(format!(
            "`uniform({a}, {b})` has its bounds inverted or equal"
        )),
        "int" if a.ceil() > b.floor() => Some(format!("`int({a}, {b})` contains no whole number")),
        "int" if (b - a).abs() > 1e15 => Some(format!("`int({a}, {b})` spans too many numbers")),
        "normal" if b < 0.0 => Some(format!(
            "`normal({a}, {b})` has a negative standard deviation"
        )),
        _ => None,
    };
    match problem {
        Some(message) => Err(Diag::error("scen::family::bad_distribution", message)
            .at(span, "these bounds")
            .help(distribution_help(f))),
        None => Ok(()),
    }
}

fn sample(f: &str, a: f64, b: f64, rng: &mut SplitMix64) -> f64 {
    match f {
        "uniform" => rng.range(a, b),
        "normal" => {
            // Box–Muller; 1 - u is in (0, 1].
            let u = 1.0 - rng.next_f64();
            let v = rng.next_f64();
            a + b * (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
        }
        _ => {
            let (lo, hi) = (a.ceil(), b.floor());
            let n = (hi - lo) as u64 + 1;
            lo + (rng.next_u64() % n) as f64
        }
    }
}

/// The value of a distribution at `u` in [0, 1) (its inverse distribution
/// function): what a search's point of the unit cube stands for.
fn inverse(f: &str, a: f64, b: f64, u: f64) -> f64 {
    match f {
        "uniform" => a + (b - a) * u,
        "normal" => a + b * normal_quantile(u.clamp(1e-12, 1.0 - 1e-12)),
        _ => {
            let (lo, hi) = (a.ceil(), b.floor());
            (lo + (u * (hi - lo + 1.0)).floor()).min(hi)
        }
    }
}

/// The standard normal distribution's quantile (Acklam's rational
/// approximation, relative error below 1.2e-9).
fn normal_quantile(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] = [
        7.784_695_709_041_462e-3,
        3.224_671_290_700_398e-1,
        2.445_134_137_142_996,
        3.754_408_661_907_416,
    ];
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    if p < 0.02425 {
        tail((-2.0 * p.ln()).sqrt())
    } else if p > 1.0 - 0.02425 {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    }
}

/// The spans of everything a sample computes: expressions, params' names
/// in bodies, lists and expectations. A standalone file of a sample writes
/// each one's number in its place.
pub(crate) fn computed_spans(
    statements: &[SourcedStmt],
    params: &HashMap<String, usize>,
) -> HashSet<Span> {
    fn value(v: &Value, params: &HashMap<String, usize>, out: &mut HashSet<Span>) {
        match &v.kind {
            ValueKind::Calc { .. } => {
                out.insert(v.span);
            }
            ValueKind::Word(w) if params.contains_key(w) => {
                out.insert(v.span);
            }
            ValueKind::Tuple(items) | ValueKind::List(items) => {
                items.iter().for_each(|i| value(i, params, out));
            }
            _ => {}
        }
    }
    let mut out = HashSet::new();
    for s in statements {
        // A param's own value is not written out; the statement goes.
        if matches!(s.stmt, Stmt::Param(_)) {
            continue;
        }
        s.stmt.each_value(&mut |v, _| value(v, params, &mut out));
        match &s.stmt {
            Stmt::Plan(PlanDecl { body, .. }) | Stmt::Bench(BenchDecl { body, .. }) => {
                ParamToken::flatten(body, &mut |t| {
                    if let ParamToken::Word(w) = t
                        && params.contains_key(&w.value)
                    {
                        out.insert(w.span);
                    }
                });
            }
            Stmt::Expect(e) => e.walk(&mut |n| {
                if let ExprKind::Name(name) = &n.kind
                    && params.contains_key(&name.value)
                {
                    out.insert(n.span);
                }
            }),
            _ => {}
        }
    }
    out
}

/// Why an expression has no number.
enum EvalError {
    /// A result that is not finite (division by zero, sqrt of a negative).
    NotFinite(Span),
    /// A distribution's bounds (in a scatter's size).
    Distribution(Diag),
    /// Something the static checks report (an unknown name or function).
    Static(Span),
}

impl EvalError {
    fn diag(self, family: &Family, values: &[f64]) -> Diag {
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

fn eval(e: &Expr, values: &[f64], index: &HashMap<String, usize>) -> Result<f64, EvalError> {
    eval_with(e, values, index, &mut None)
}

fn eval_drawing(
    e: &Expr,
    values: &[f64],
    index: &HashMap<String, usize>,
    rng: &mut SplitMix64,
) -> Result<f64, EvalError> {
    eval_with(e, values, index, &mut Some(rng))
}

/// The number of an expression; a distribution draws from `rng` (none:
/// it is not constant).
fn eval_with(
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
struct ParamScope<'a, 'r, 's> {
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
fn is_condition(e: &Expr) -> bool {
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
fn eval_condition(
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

/// What a scattered item's numbers may be for the scatter to have placed
/// it (with the params' values of one member): its centre inside the box,
/// each size in its distribution's support, at least the gap from the
/// other items. Shrinking keeps a simplified item inside it.
#[derive(Clone, Debug)]
pub(crate) struct ScatterRule {
    pub min: (f64, f64),
    pub max: (f64, f64),
    pub gap: f64,
    /// Per size (a disk's radius; a rect's width and height).
    pub sizes: Vec<Support>,
}

/// The values a scattered size may take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Support {
    /// A constant or a computed size: only the value placed.
    Fixed,
    /// `uniform(lo, hi)`, or `int(lo, hi)` (`whole`).
    Range { lo: f64, hi: f64, whole: bool },
    /// `normal(m, s)`: any positive number.
    Any,
}

impl Support {
    /// Whether a size of `x` is one this support may draw (`x` positive).
    pub fn holds(self, x: f64) -> bool {
        x > 0.0
            && match self {
                Support::Fixed => false,
                Support::Range { lo, hi, whole } => {
                    lo <= x && x <= hi && (!whole || x.fract() == 0.0)
                }
                Support::Any => true,
            }
    }
}

impl Family {
    /// The rules of every scatter (by its span) with the params' values
    /// `values` (all params, in order); a scatter whose box or gap is not a
    /// number here is left out (its items are not simplified).
    pub(crate) fn scatter_rules(
        &self,
        statements: &[SourcedStmt],
        values: &[f64],
    ) -> HashMap<Span, ScatterRule> {
        let number = |v: &Value| -> Option<f64> {
            match &v.kind {
                ValueKind::Number(x) => Some(*x),
                ValueKind::Calc { expr, unit: None } => eval(expr, values, &self.index).ok(),
                ValueKind::Word(w) => self
                    .index
                    .get(w.as_str())
                    .and_then(|&k| values.get(k).copied()),
                _ => None,
            }
        };
        let point = |v: &Value| match &v.kind {
            ValueKind::Tuple(items) if items.len() == 2 => {
                Some((number(&items[0])?, number(&items[1])?))
            }
            _ => None,
        };
        let support = |v: &Value| -> Support {
            let ValueKind::Calc { expr, unit: None } = &v.kind else {
                return Support::Fixed;
            };
            let ExprKind::Call { function, args } = &expr.kind else {
                return Support::Fixed;
            };
            let bounds = match args.as_slice() {
                [a, b] => eval(a, values, &self.index)
                    .ok()
                    .zip(eval(b, values, &self.index).ok()),
                _ => None,
            };
            match (function.value.as_str(), bounds) {
                ("uniform", Some((lo, hi))) => Support::Range {
                    lo,
                    hi,
                    whole: false,
                },
                ("int", Some((lo, hi))) => Support::Range {
                    lo: lo.ceil(),
                    hi: hi.floor(),
                    whole: true,
                },
                ("normal", Some(_)) => Support::Any,
                _ => Support::Fixed,
            }
        };
        let mut out = HashMap::new();
        for s in statements {
            let Stmt::World(w) = &s.stmt else { continue };
            for item in &w.items {
                let WorldItem::Scatter(sc) = item else {
                    continue;
                };
                let gap = match &sc.gap {
                    Some(g) => number(g),
                    None => Some(0.0),
                };
                let (Some(min), Some(max), Some(gap)) = (point(&sc.min), point(&sc.max), gap)
                else {
                    continue;
                };
                let sizes = match &sc.shape {
                    ScatterShape::Disk { radius, .. } => vec![support(radius)],
                    ScatterShape::Rect { width, height, .. } => {
                        vec![support(width), support(height)]
                    }
                };
                out.insert(
                    sc.span,
                    ScatterRule {
                        min,
                        max,
                        gap,
                        sizes,
                    },
                );
            }
        }
        out
    }

    /// The drawn params' values (in the order of [`Family::drawn_values`])
    /// as what `--set` gives, by param index.
    pub(crate) fn set_of_drawn(&self, drawn: &[f64]) -> Vec<Option<f64>> {
        let mut given = drawn.iter().copied();
        self.params
            .iter()
            .map(|p| if p.drawn() { given.next() } else { None })
            .collect()
    }

    /// Whether a `scatter` draws obstacles (whose places come from a
    /// sample's stream, not from the params).
    pub(crate) fn scatters(&self) -> bool {
        self.scatters
    }
}

/// The distance between two scattered items as their scatter measures it
/// for its gap (`None`: not a scattered disk or rect).
pub(crate) fn scattered_distance(a: &ObstacleDecl, b: &ObstacleDecl) -> Option<f64> {
    Some(Placed::of(a)?.distance(&Placed::of(b)?))
}

impl Placed {
    fn of(o: &ObstacleDecl) -> Option<Placed> {
        let num = |v: &Value| match &v.kind {
            ValueKind::Number(x) => Some(*x),
            _ => None,
        };
        let point = |v: &Value| match &v.kind {
            ValueKind::Tuple(items) if items.len() == 2 => Some((num(&items[0])?, num(&items[1])?)),
            _ => None,
        };
        match &o.shape {
            ObstacleShape::Disk(c, r) => {
                let (x, y) = point(c)?;
                Some(Placed::Disk { x, y, r: num(r)? })
            }
            ObstacleShape::Rect(a, b) => {
                let ((x0, y0), (x1, y1)) = (point(a)?, point(b)?);
                Some(Placed::Rect { x0, y0, x1, y1 })
            }
            _ => None,
        }
    }
}
