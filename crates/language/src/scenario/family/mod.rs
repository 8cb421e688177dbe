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

use std::collections::HashMap;

use crate::diagnostics::{Diag, Span, Spanned};
use crate::rng::SplitMix64;
use crate::syntax::ast::{Expr, Stmt, Value, ValueKind, WorldItem};

use super::statements::SourcedStmt;

mod check;
mod compute;
mod distributions;
mod instance;
mod scatter;
mod set;

use check::*;
use compute::*;
use distributions::*;
pub use instance::computed_spans;
use instance::*;
pub use scatter::{ScatterRule, scattered_distance};
use set::*;

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
pub struct Family {
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
pub type Instance = (Vec<SourcedStmt>, Vec<(String, f64)>);

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
    pub fn index(&self) -> &HashMap<String, usize> {
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
    pub fn candidate(
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

    /// The values of the drawn params (those of a distribution or a
    /// `choice`) among all params' values, in order.
    pub fn drawn_values(&self, params: &[(String, f64)]) -> Vec<f64> {
        self.params
            .iter()
            .zip(params)
            .filter(|(p, _)| p.drawn())
            .map(|(_, (_, x))| *x)
            .collect()
    }

    /// The names of the drawn params, in the order of
    /// [`Family::drawn_values`].
    pub fn drawn_names(&self) -> Vec<&str> {
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
