//! `bench` statements (SPEC 2.7): which plans, the varied keys and their
//! values, the runs and the limits. Every configuration of every plan is
//! analysed as if its values were written in the plan — the plan's tokens
//! for a varied key are replaced by the value's — so a value out of range,
//! a lattice over the cap or a start in collision is an error at the
//! `vary` value, naming the plan.

use std::collections::{BTreeSet, HashMap};

use crate::contract::Planner;
use crate::contract::schema::{self, ValueSpec, did_you_mean};
use crate::contract::{Limits, Robot};
use crate::diagnostics::{Diag, Span, Spanned};
use crate::geometry::World;
use crate::planners::registry;
use crate::scenario::statements::SourcedStmt;
use crate::scenario::{Bench, BenchPlan, Plan, Vary, VaryValue};
use crate::syntax::ast::{self, Ident, ParamToken, Value, ValueKind};

use super::Analyzer;

/// The most plan configurations a bench may have (configurations × plans):
/// each is analysed, and each runs at least once.
pub(crate) const MAX_BENCH_CONFIGS: usize = 100_000;

/// The most runs per configuration.
const MAX_RUNS: f64 = 1e7;

/// The keys of a bench's body (also listed by the editors, `tests/editors.rs`).
pub const BENCH_KEYS: &[&str] = &["plans", "vary", "runs", "worlds", "limit"];

/// The most samples of a family one bench runs on (`worlds N`).
const MAX_WORLDS: f64 = 1e5;

impl Analyzer {
    pub(super) fn benches(
        &mut self,
        statements: &[SourcedStmt],
        plans: &[Plan],
        world: Option<&World>,
        robots: &[Robot],
    ) -> Vec<Bench> {
        let decls: HashMap<&str, &ast::PlanDecl> = statements
            .iter()
            .filter_map(|s| match &s.stmt {
                ast::Stmt::Plan(p) => Some((p.name.value.as_str(), p)),
                _ => None,
            })
            .collect();
        let mut seen: HashMap<&str, Span> = HashMap::new();
        let mut benches = Vec::new();
        for s in statements {
            let ast::Stmt::Bench(b) = &s.stmt else {
                continue;
            };
            if let Some(first) = seen.get(b.name.value.as_str()) {
                self.error(
                    Diag::error(
                        "scen::analyze::duplicate_name",
                        format!("bench `{}` is declared twice", b.name.value),
                    )
                    .at(b.name.span, "second declaration")
                    .with_related(*first, "first declaration")
                    .help("bench names must be unique; rename one of them"),
                );
                continue;
            }
            seen.insert(&b.name.value, b.name.span);
            if let Some(bench) = self.bench(b, &decls, plans, world, robots) {
                benches.push(bench);
            }
        }
        benches
    }

    fn bench(
        &mut self,
        b: &ast::BenchDecl,
        decls: &HashMap<&str, &ast::PlanDecl>,
        plans: &[Plan],
        world: Option<&World>,
        robots: &[Robot],
    ) -> Option<Bench> {
        let body = self.bench_body(b)?;
        // The plans: named ones, or every plan of the file. A plan that
        // failed its own analysis is left out silently (its errors say why).
        let mut chosen: Vec<usize> = Vec::new();
        match &body.plans {
            None => chosen.extend(0..plans.len()),
            Some(names) => {
                for name in names {
                    match plans.iter().position(|p| p.name == name.value) {
                        Some(i) if chosen.contains(&i) => self.error(
                            Diag::error(
                                "scen::analyze::duplicate_name",
                                format!("plan `{}` is listed twice", name.value),
                            )
                            .at(name.span, "listed again")
                            .help("list each plan once"),
                        ),
                        Some(i) => chosen.push(i),
                        None if decls.contains_key(name.value.as_str()) => {}
                        None => {
                            let known: Vec<&str> = decls.keys().copied().collect();
                            let mut d = Diag::error(
                                "scen::analyze::unknown_plan",
                                format!("unknown plan `{}`", name.value),
                            )
                            .at(name.span, "no plan of this name");
                            d = match did_you_mean(&name.value, known.iter().copied()) {
                                Some(n) => d.help(format!("did you mean `{n}`?")),
                                None => d.help("`plans` lists plans declared with `plan NAME ...`"),
                            };
                            self.error(d);
                        }
                    }
                }
            }
        }
        let planners: Vec<&'static Planner> = chosen.iter().map(|&i| plans[i].planner).collect();
        let mut limits = Limits::default();
        let mut spans: HashMap<&'static str, Span> = HashMap::new();
        let limit_spec = schema::COMMON_PARAMS
            .iter()
            .find(|p| p.key == "limit")
            .expect("`limit` is a common parameter");
        let mut limits_ok = true;
        for tokens in &body.limits {
            let mut i = 1;
            let parsed = self.limit(
                &planners,
                limit_spec,
                &tokens[0],
                tokens,
                &mut i,
                &mut limits,
                &mut spans,
            );
            limits_ok &= !matches!(parsed, super::Parsed::Bad);
        }
        // Every varied key must be a parameter of every plan's planner.
        let mut keys_ok = true;
        let mut vary: Vec<Vary> = Vec::new();
        for (key, values) in &body.vary {
            if vary.iter().any(|v| v.key == key.value) {
                self.error(
                    Diag::error(
                        "scen::analyze::duplicate_key",
                        format!("`vary {}` is given twice", key.value),
                    )
                    .at(key.span, "second time")
                    .help("give each varied key once, with all its values"),
                );
                keys_ok = false;
                continue;
            }
            for &i in &chosen {
                let plan = &plans[i];
                match plan.planner.param(&key.value) {
                    Some(spec) if matches!(spec.value, ValueSpec::Limit | ValueSpec::Drive) => {
                        self.error(
                            Diag::error(
                                "scen::analyze::bad_vary",
                                format!("a bench cannot vary `{}`", key.value),
                            )
                            .at(key.span, "not variable")
                            .help("give the bench its own `limit`, e.g. `limit time 10s`"),
                        );
                        keys_ok = false;
                        break;
                    }
                    Some(_) => {}
                    None => {
                        let accepted: Vec<&str> =
                            plan.planner.all_params().map(|p| p.key).collect();
                        self.error(
                            Diag::error(
                                "scen::analyze::unknown_key",
                                format!(
                                    "plan `{}` ({}) does not accept `{}`",
                                    plan.name,
                                    plan.kind(),
                                    key.value
                                ),
                            )
                            .at(key.span, "not a parameter of this plan's planner")
                            .help(format!(
                                "`{}` accepts {}; list the plans that take `{}` with `plans [...]`",
                                plan.kind(),
                                schema::backticked(&accepted),
                                key.value
                            )),
                        );
                        keys_ok = false;
                    }
                }
            }
            vary.push(Vary {
                key: key.value.clone(),
                span: key.span,
                values: values
                    .iter()
                    .map(|v| VaryValue {
                        text: self.sources.snippet(v.span).to_string(),
                        value: v.clone(),
                    })
                    .collect(),
            });
        }
        let configurations: usize = vary
            .iter()
            .map(|v| v.values.len())
            .try_fold(1usize, |a, n| a.checked_mul(n))
            .unwrap_or(usize::MAX);
        if configurations.saturating_mul(chosen.len().max(1)) > MAX_BENCH_CONFIGS {
            self.error(
                Diag::error(
                    "scen::analyze::bench_too_large",
                    format!(
                        "bench `{}` has {configurations} configurations of {} plans, more than {MAX_BENCH_CONFIGS}",
                        b.name.value,
                        chosen.len()
                    ),
                )
                .at(b.name.span, "too many configurations")
                .help("vary fewer keys or fewer values, or split the bench"),
            );
            return None;
        }
        let (true, true, Some(world)) = (keys_ok, limits_ok, world) else {
            return None;
        };
        let mut bench_plans = Vec::new();
        let mut failed = false;
        for &i in &chosen {
            let plan = &plans[i];
            let Some(decl) = decls.get(plan.name.as_str()) else {
                continue;
            };
            match self.bench_plan(b, decl, plan, i, &vary, configurations, world, robots) {
                Some(configs) => bench_plans.push(BenchPlan {
                    plan: i,
                    configs,
                    runs: if plan.planner.randomized {
                        body.runs
                    } else {
                        1
                    },
                }),
                None => failed = true,
            }
        }
        if failed {
            return None;
        }
        Some(Bench {
            name: b.name.value.clone(),
            span: b.span,
            plans: bench_plans,
            vary,
            runs: body.runs,
            worlds: body.worlds.map_or(1, |(n, _)| n),
            worlds_span: body.worlds.map(|(_, span)| span),
            limits,
        })
    }

    /// The configurations of one plan; `None` after reporting the values
    /// that do not fit it (each problem once, however many configurations
    /// share it).
    #[allow(clippy::too_many_arguments)]
    fn bench_plan(
        &mut self,
        b: &ast::BenchDecl,
        decl: &ast::PlanDecl,
        plan: &Plan,
        index: usize,
        vary: &[Vary],
        configurations: usize,
        world: &World,
        robots: &[Robot],
    ) -> Option<Vec<Plan>> {
        let planner = plan.planner;
        // Where each varied key sits in the plan's own tokens.
        let outer = std::mem::take(&mut self.diags);
        let (_, given) = self.params_of(decl, &decl.body, planner);
        self.diags = outer;
        let replaced: Vec<std::ops::Range<usize>> = given
            .iter()
            .filter(|(k, _)| vary.iter().any(|v| v.key == *k))
            .map(|(_, r)| r.clone())
            .collect();
        let kept: Vec<ParamToken> = decl
            .body
            .iter()
            .enumerate()
            .filter(|(t, _)| !replaced.iter().any(|r| r.contains(t)))
            .map(|(_, t)| t.clone())
            .collect();
        let robot_ok = planner.plans_for(robots[plan.robot].kind());
        let mut configs = Vec::with_capacity(configurations);
        let mut problems: Vec<Diag> = Vec::new();
        let mut reported: BTreeSet<String> = BTreeSet::new();
        for c in 0..configurations {
            let mut body = kept.clone();
            let mut rest = c;
            let mut picks = vec![0; vary.len()];
            for (k, v) in vary.iter().enumerate().rev() {
                picks[k] = rest % v.values.len();
                rest /= v.values.len();
            }
            for (v, &pick) in vary.iter().zip(&picks) {
                body.push(ParamToken::Word(Spanned::new(v.key.clone(), v.span)));
                body.push(value_token(&v.values[pick].value));
            }
            let outer = std::mem::take(&mut self.diags);
            let configured = self.params_of(decl, &body, planner).0.and_then(|params| {
                self.configured(decl, planner, plan.robot, robots, params, world, robot_ok)
            });
            let found = std::mem::replace(&mut self.diags, outer);
            for d in found {
                let key = format!("{}|{:?}|{}", d.code, d.span, d.message);
                if reported.insert(key) {
                    problems.push(d.with_related(
                        decl.name.span,
                        format!("in plan `{}`, benched by `{}`", plan.name, b.name.value),
                    ));
                }
            }
            if let Some(p) = configured {
                configs.push(p);
            }
        }
        let _ = index;
        if problems.iter().any(Diag::is_error) || configs.len() != configurations {
            self.diags.extend(problems);
            return None;
        }
        self.diags.extend(problems);
        Some(configs)
    }

    /// The body of a bench, grouped: `plans [...]`, `vary KEY [...]`
    /// (several), `runs N`, `limit KIND AMOUNT` (several; their tokens,
    /// parsed once the plans are known).
    fn bench_body(&mut self, b: &ast::BenchDecl) -> Option<BenchBody> {
        let mut out = BenchBody {
            plans: None,
            vary: Vec::new(),
            runs: 1,
            worlds: None,
            limits: Vec::new(),
        };
        let mut ok = true;
        let mut runs_given: Option<Span> = None;
        let mut worlds_given: Option<Span> = None;
        let tokens = &b.body;
        let mut i = 0;
        while i < tokens.len() {
            let tok = &tokens[i];
            i += 1;
            let key = match tok {
                ParamToken::Word(w) if BENCH_KEYS.contains(&w.value.as_str()) => w,
                other => {
                    let mut d = Diag::error(
                        "scen::analyze::unknown_key",
                        match other {
                            ParamToken::Word(w) => format!("unknown bench key `{}`", w.value),
                            _ => "expected a bench key".to_string(),
                        },
                    )
                    .at(other.span(), "not a bench key");
                    let keys = schema::backticked(BENCH_KEYS);
                    d = match other {
                        ParamToken::Word(w) => match did_you_mean(&w.value, BENCH_KEYS.iter().copied()) {
                            Some(k) => d.help(format!("did you mean `{k}`? a bench takes {keys}")),
                            None if registry::PLANNERS.iter().any(|p| p.param(&w.value).is_some()) => d.help(format!(
                                "`{}` is a plan parameter: vary it with `vary {} [...]`, or set it in the plan",
                                w.value, w.value
                            )),
                            None => d.help(format!("a bench takes {keys}")),
                        },
                        _ => d.help(format!("a bench takes {keys}")),
                    };
                    self.error(d);
                    ok = false;
                    // Skip to the next bench key.
                    while i < tokens.len()
                        && !matches!(&tokens[i], ParamToken::Word(w) if BENCH_KEYS.contains(&w.value.as_str()))
                    {
                        i += 1;
                    }
                    continue;
                }
            };
            match key.value.as_str() {
                "plans" => match tokens.get(i) {
                    Some(ParamToken::Value(Value {
                        kind: ValueKind::List(items),
                        ..
                    })) if items.iter().all(|v| matches!(v.kind, ValueKind::Word(_))) => {
                        i += 1;
                        if out.plans.is_some() {
                            self.twice(key);
                            ok = false;
                        }
                        out.plans = Some(
                            items
                                .iter()
                                .map(|v| match &v.kind {
                                    ValueKind::Word(w) => Spanned::new(w.clone(), v.span),
                                    _ => unreachable!("checked to be words"),
                                })
                                .collect(),
                        );
                    }
                    other => {
                        self.bench_value_error(
                            key,
                            other,
                            "a list of plan names, e.g. `plans [a, b]`",
                        );
                        ok = false;
                    }
                },
                "vary" => {
                    let name = match tokens.get(i) {
                        Some(ParamToken::Word(w)) => {
                            i += 1;
                            w.clone()
                        }
                        other => {
                            self.bench_value_error(
                                key,
                                other,
                                "a plan parameter and its values, e.g. `vary weight [1, 2, 5]`",
                            );
                            ok = false;
                            continue;
                        }
                    };
                    match tokens.get(i) {
                        Some(ParamToken::Value(Value {
                            kind: ValueKind::List(items),
                            span,
                        })) => {
                            i += 1;
                            if items.is_empty() {
                                self.error(
                                    Diag::error(
                                        "scen::analyze::missing_value",
                                        format!("`vary {}` has no values", name.value),
                                    )
                                    .at(*span, "an empty list")
                                    .help(format!(
                                        "list the values to try, e.g. `vary {} [1, 2]`",
                                        name.value
                                    )),
                                );
                                ok = false;
                            } else {
                                out.vary.push((name, items.clone()));
                            }
                        }
                        other => {
                            self.bench_value_error(
                                &name,
                                other,
                                "a list of values, e.g. `[1, 2, 5]`",
                            );
                            ok = false;
                        }
                    }
                }
                "runs" | "worlds" => {
                    let worlds = key.value == "worlds";
                    let (given, max, example) = if worlds {
                        (&mut worlds_given, MAX_WORLDS, "worlds 50")
                    } else {
                        (&mut runs_given, MAX_RUNS, "runs 20")
                    };
                    let Some(ParamToken::Value(v)) = tokens.get(i) else {
                        let wanted = format!("a whole number, e.g. `{example}`");
                        self.bench_value_error(key, tokens.get(i), &wanted);
                        ok = false;
                        continue;
                    };
                    i += 1;
                    if given.is_some() {
                        self.twice(key);
                        ok = false;
                    }
                    *given = Some(v.span);
                    match v.kind {
                        ValueKind::Number(n) if n >= 1.0 && n.fract() == 0.0 && n <= max => {
                            if worlds {
                                out.worlds = Some((n as u64, v.span));
                            } else {
                                out.runs = n as u64;
                            }
                        }
                        _ => {
                            self.error(
                                Diag::error(
                                    "scen::analyze::out_of_range",
                                    format!("`{}` must be an integer from 1 to {max}", key.value),
                                )
                                .at(v.span, format!("not a number of {}", key.value))
                                .help(format!("write e.g. `{example}`")),
                            );
                            ok = false;
                        }
                    }
                }
                _ => {
                    // `limit KIND AMOUNT`: the three tokens, parsed later.
                    let end = (i + 2).min(tokens.len());
                    let taken = tokens[i..end]
                        .iter()
                        .take_while(|t| !matches!(t, ParamToken::Word(w) if BENCH_KEYS.contains(&w.value.as_str())))
                        .count();
                    let mut limit = tokens[i..i + taken].to_vec();
                    i += taken;
                    if limit.is_empty() {
                        self.bench_value_error(key, None, "a limit, e.g. `limit time 10s`");
                        ok = false;
                        continue;
                    }
                    limit.truncate(2);
                    out.limits.push(limit);
                }
            }
        }
        ok.then_some(out)
    }

    fn twice(&mut self, key: &Ident) {
        self.error(
            Diag::error(
                "scen::analyze::duplicate_key",
                format!("`{}` is given twice", key.value),
            )
            .at(key.span, "second time")
            .help("give it once"),
        );
    }

    fn bench_value_error(&mut self, key: &Ident, found: Option<&ParamToken>, wanted: &str) {
        let (span, what) = match found {
            Some(t) => (t.span(), "unexpected value"),
            None => (key.span, "no value"),
        };
        self.error(
            Diag::error(
                "scen::analyze::wrong_type",
                format!("`{}` takes {wanted}", key.value),
            )
            .at(span, what)
            .help(format!("`{}` takes {wanted}", key.value)),
        );
    }
}

/// A bench's body, grouped.
struct BenchBody {
    plans: Option<Vec<Ident>>,
    vary: Vec<(Ident, Vec<Value>)>,
    runs: u64,
    /// `worlds N` and the span of N.
    worlds: Option<(u64, Span)>,
    /// The tokens after each `limit` (kind and amount).
    limits: Vec<Vec<ParamToken>>,
}

/// A value of a `vary` list as the token a plan's body would hold.
fn value_token(v: &Value) -> ParamToken {
    match &v.kind {
        ValueKind::Word(w) => ParamToken::Word(Spanned::new(w.clone(), v.span)),
        _ => ParamToken::Value(v.clone()),
    }
}
