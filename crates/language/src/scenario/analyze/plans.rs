//! Plans: the planner and robot named, the parameters grouped and checked
//! against the planner's schema, `limit`s, `drive` blocks, start and goal
//! checked against the world, and the planner's own `check`.

use std::collections::{BTreeMap, HashMap};

use crate::diagnostics::{Diag, Span, Spanned};
use crate::geometry::{Config, World};
use crate::syntax::ast::{self, ParamToken, Value, ValueKind};

use crate::planners::registry::{self, PLANNERS};

use crate::contract::Planner;

use crate::contract::schema::{self, MAX_MAGNITUDE, ValueSpec, did_you_mean};
use crate::contract::{Limits, Param, ParamValue, Params, PlanArgs, Robot};
use crate::scenario::Plan;
use crate::scenario::statements::SourcedStmt;

use super::*;

impl Analyzer {
    pub(super) fn plans(
        &mut self,
        statements: &[SourcedStmt],
        world: Option<&World>,
        robots: &[Robot],
    ) -> Vec<Plan> {
        let mut plans = Vec::new();
        let mut seen: HashMap<String, Span> = HashMap::new();
        for s in statements {
            let ast::Stmt::Plan(p) = &s.stmt else {
                continue;
            };
            if let Some(first) = seen.get(&p.name.value) {
                self.error(
                    Diag::error(
                        "scen::analyze::duplicate_name",
                        format!("plan `{}` is declared twice", p.name.value),
                    )
                    .at(p.name.span, "second declaration")
                    .with_related(*first, "first declaration")
                    .help("plan names must be unique; rename one of them"),
                );
                continue;
            }
            seen.insert(p.name.value.clone(), p.name.span);
            if let Some(plan) = self.plan(p, world, robots) {
                plans.push(plan);
            }
        }
        plans
    }

    pub(super) fn plan(
        &mut self,
        p: &ast::PlanDecl,
        world: Option<&World>,
        robots: &[Robot],
    ) -> Option<Plan> {
        let Some(planner) = registry::planner(&p.kind.value) else {
            let kinds: Vec<&str> = PLANNERS.iter().map(|s| s.kind).collect();
            let mut d = Diag::error(
                "scen::analyze::unknown_planner",
                format!("unknown planner `{}`", p.kind.value),
            )
            .at(p.kind.span, "not a planner kind");
            d = match did_you_mean(&p.kind.value, kinds.iter().copied()) {
                Some(k) => d.help(format!(
                    "did you mean `{k}`? planners: {}",
                    schema::backticked(&kinds)
                )),
                None => d.help(format!("planners: {}", schema::backticked(&kinds))),
            };
            self.error(d);
            return None;
        };
        let robot_index = robots.iter().position(|r| r.name == p.robot.value);
        if robot_index.is_none() && self.invalid_robots.contains(&p.robot.value) {
            // The robot's own error was reported; check the parameters only.
            self.params(p, planner);
            return None;
        }
        let Some(robot_index) = robot_index else {
            let names: Vec<&str> = robots.iter().map(|r| r.name.as_str()).collect();
            let mut d = Diag::error(
                "scen::analyze::unknown_robot",
                format!("unknown robot `{}`", p.robot.value),
            )
            .at(p.robot.span, "no robot of this name");
            d = match did_you_mean(&p.robot.value, names.iter().copied()) {
                Some(n) => d.help(format!("did you mean `{n}`?")),
                None if names.is_empty() => d.help("declare it, e.g. `robot dot disk 0.5`"),
                None => d.help(format!("robots: {}", schema::backticked(&names))),
            };
            self.error(d);
            // Still check the parameters, so their errors show up too.
            self.params(p, planner);
            return None;
        };
        let robot = &robots[robot_index];
        let kind = robot.kind();
        let robot_ok = planner.plans_for(kind);
        if !robot_ok {
            let ok: Vec<&str> = planner.robots.iter().map(|k| k.name()).collect();
            // Who plans for this kind, from the registry.
            let others: Vec<&str> = PLANNERS
                .iter()
                .filter(|q| q.plans_for(kind))
                .map(|q| q.kind)
                .collect();
            let mut help = format!("`{}` plans for {} robots", planner.kind, and_list(&ok));
            if !others.is_empty() {
                help.push_str(&format!(
                    "; {} robots are planned by {}",
                    kind.name(),
                    schema::backticked(&others)
                ));
            }
            self.error(
                Diag::error(
                    "scen::analyze::robot_kind",
                    format!(
                        "planner `{}` does not plan for {} robots",
                        planner.kind,
                        kind.name()
                    ),
                )
                .at(p.robot.span, format!("a {} robot", kind.name()))
                .help(help),
            );
        }
        let params = self.params(p, planner)?;
        self.configured(p, planner, robot_index, robots, params, world?, robot_ok)
    }

    /// A plan from its validated parameters: the start and goal checked
    /// against the world (SPEC 2.5), then the planner's own check, which
    /// builds its settings (only for a robot it plans for).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn configured(
        &mut self,
        p: &ast::PlanDecl,
        planner: &'static Planner,
        robot_index: usize,
        robots: &[Robot],
        mut params: Params,
        world: &World,
        robot_ok: bool,
    ) -> Option<Plan> {
        let robot = &robots[robot_index];
        let before = self.diags.len();
        match &robot.team {
            // The agents' starts and goals were checked with the team.
            Some(agents) => {
                if let Some(a) = agents.first() {
                    params.start = crate::geometry::Config::new(a.start.x, a.start.y, 0.0);
                }
            }
            None if planner.plans_teams() => {}
            None => {
                let who = format!("robot `{}`", robot.name);
                self.check_pose(world, robot, &who, params.start, params.start_span, "start");
                if let (Some(g), Some(gs)) = (params.goal, params.goal_span) {
                    self.check_pose(world, robot, &who, g, gs, "goal");
                }
            }
        }
        let start_ok = self.diags.len() == before;
        // The planner's check may assume a robot it plans for.
        if !robot_ok {
            return None;
        }
        if !planner.grids
            && let Some(grid) = world
                .obstacles
                .iter()
                .find(|o| matches!(o.shape, crate::geometry::Shape::Grid(_)))
        {
            let others: Vec<&str> = PLANNERS
                .iter()
                .filter(|q| q.grids)
                .map(|q| q.kind)
                .collect();
            self.error(
                Diag::error(
                    "scen::analyze::grid_world",
                    format!(
                        "planner `{}` does not plan in a world with `grid` obstacles",
                        planner.kind
                    ),
                )
                .at(p.kind.span, format!("the world has the grid `{}`", grid.name))
                .help(format!(
                    "draw the obstacles as `rect`, `polygon`, `segment` or `disk`; grids are planned by {}",
                    schema::backticked(&others)
                )),
            );
            return None;
        }
        let head = p.name.span.to(p.robot.span);
        let mut args = PlanArgs::new(planner, &p.name.value, head, world, robot, &params);
        args.start_valid = start_ok;
        let settings = (planner.check)(&mut args);
        let ok = args.ok();
        self.diags.extend(args.into_diags());
        let settings = settings.filter(|_| ok)?;
        Some(Plan {
            name: p.name.value.clone(),
            planner,
            robot: robot_index,
            params,
            settings: settings.into(),
            span: p.span,
        })
    }

    /// Groups the plan body's tokens into parameters and validates each
    /// against the planner's schema (types, ranges, required keys).
    pub(super) fn params(
        &mut self,
        p: &ast::PlanDecl,
        planner: &'static Planner,
    ) -> Option<Params> {
        self.params_of(p, &p.body, planner).0
    }

    /// [`Analyzer::params`] of `body` (the plan's own, or a bench's
    /// configuration of it), with the keys given and the tokens each took.
    #[allow(clippy::type_complexity)]
    pub(super) fn params_of(
        &mut self,
        p: &ast::PlanDecl,
        body: &[ParamToken],
        planner: &'static Planner,
    ) -> (Option<Params>, Vec<(&'static str, std::ops::Range<usize>)>) {
        let set = ParamSet {
            owner: format!("planner `{}`", planner.kind),
            name: format!("`{}`", planner.kind),
            specs: planner.all_params().collect(),
            nested: true,
            plan: true,
        };
        let mut limits = Limits::default();
        let mut limit_spans: HashMap<&'static str, Span> = HashMap::new();
        let list = self.param_list(body, &set, |this, spec, next, tokens, i| match spec.value {
            ValueSpec::Limit => this.limit(
                &[planner],
                spec,
                next,
                tokens,
                i,
                &mut limits,
                &mut limit_spans,
            ),
            ValueSpec::Drive => {
                let ParamToken::Word(model) = next else {
                    this.wrong_value(spec, next);
                    return Parsed::Bad;
                };
                let block = match tokens.get(*i) {
                    Some(ParamToken::Block { tokens, .. }) => {
                        *i += 1;
                        tokens.as_slice()
                    }
                    _ => &[],
                };
                this.drive_block(model, block)
            }
            _ => this
                .param_value(spec, next)
                .map_or(Parsed::Bad, Parsed::Value),
        });
        let plan_head = p.name.span.to(p.robot.span);
        let list_gave_start = list.gave("start");
        let list_gave_goal = list.gave("goal");
        let ParamList {
            mut values,
            ok,
            given,
        } = list;
        let start = values.remove("start");
        let goal = values.remove("goal");
        let seed = values
            .remove("seed")
            .and_then(|p| match p.value {
                ParamValue::Num(x) => Some(x as u64),
                _ => None,
            })
            .unwrap_or(0);
        if planner.plans_teams() {
            // A team's agents carry their starts and goals (SPEC 2.10).
            let mut ok = ok;
            for given in [&start, &goal].into_iter().flatten() {
                self.error(
                    Diag::error(
                        "scen::analyze::team_start",
                        format!("plan `{}` is a team's: its agents have their own starts and goals", p.name.value),
                    )
                    .at(given.span, "not for a team plan")
                    .help("give each agent its start and goal in the team: `a1 (1.5, 1.5) -> (8.5, 4.5)`"),
                );
                ok = false;
            }
            if !ok {
                return (None, given);
            }
            let params = Params {
                // The first agent's start, set when the team is known.
                start: crate::geometry::Config::new(0.0, 0.0, 0.0),
                start_span: plan_head,
                goal: None,
                goal_span: None,
                limits,
                seed,
                values,
            };
            return (Some(params), given);
        }
        if start.is_none() && !list_gave_start {
            self.error(
                Diag::error(
                    "scen::analyze::missing_key",
                    format!("plan `{}` has no `start`", p.name.value),
                )
                .at(plan_head, "needs `start`")
                .help("add `start (x, y)` to the plan's block"),
            );
        }
        if planner.needs_goal && goal.is_none() && !list_gave_goal {
            self.error(
                Diag::error(
                    "scen::analyze::missing_key",
                    format!("plan `{}` has no `goal`", p.name.value),
                )
                .at(plan_head, "needs `goal`")
                .help("add `goal (x, y)` to the plan's block"),
            );
        }
        let (true, Some(start)) = (ok, start) else {
            return (None, given);
        };
        if planner.needs_goal && goal.is_none() {
            return (None, given);
        }
        let ParamValue::Pose(start_c) = start.value else {
            return (None, given);
        };
        let goal_c = match &goal {
            Some(Param {
                value: ParamValue::Pose(c),
                ..
            }) => Some(*c),
            _ => None,
        };
        let params = Params {
            start: start_c,
            start_span: start.span,
            goal: goal_c,
            goal_span: goal.as_ref().map(|g| g.span),
            limits,
            seed,
            values,
        };
        (Some(params), given)
    }

    /// `drive MODEL { key value ... }`: the model word and the block's
    /// sub-parameters, the model's own (SPEC 3.6, 3.8,
    /// [`schema::DRIVE`]): a key of another model is an unknown key that
    /// says which model takes it.
    pub(super) fn drive_block(&mut self, model: &Spanned<String>, block: &[ParamToken]) -> Parsed {
        let Some(spec) = schema::drive_model(&model.value) else {
            let mut d = Diag::error(
                "scen::analyze::out_of_range",
                format!("`drive` does not accept `{}`", model.value),
            )
            .at(model.span, "not a drive model");
            d = match did_you_mean(&model.value, schema::DRIVE_MODELS.iter().copied()) {
                Some(m) => d.help(format!(
                    "did you mean `{m}`? the drive models are {}",
                    schema::backticked(schema::DRIVE_MODELS)
                )),
                None => d.help(format!(
                    "the drive models are {}: `drive unicycle {{ dt 0.01 }}`, `drive pure_pursuit {{ lookahead 1 }}`",
                    schema::backticked(schema::DRIVE_MODELS)
                )),
            };
            self.error(d);
            // Check the block's values against every model's keys, for
            // the other errors.
            let set = ParamSet {
                owner: "`drive`".into(),
                name: "`drive`".into(),
                specs: schema::drive_params().collect(),
                nested: false,
                plan: false,
            };
            self.param_list(block, &set, |this, spec, next, _, _| {
                this.param_value(spec, next)
                    .map_or(Parsed::Bad, Parsed::Value)
            });
            return Parsed::Bad;
        };
        let name = format!("`drive {}`", spec.name);
        let set = ParamSet {
            owner: name.clone(),
            name,
            specs: spec.params.iter().collect(),
            nested: false,
            plan: false,
        };
        let ParamList { values, ok, .. } =
            self.param_list(block, &set, |this, spec, next, _, _| {
                this.param_value(spec, next)
                    .map_or(Parsed::Bad, Parsed::Value)
            });
        if ok {
            Parsed::Value(ParamValue::Block(model.value.clone(), values))
        } else {
            Parsed::Bad
        }
    }

    /// The tokens of a parameter list (a plan's body, a `drive` block):
    /// `key value...` pairs, each key of `set` at most once unless
    /// repeatable. `value` reads the value starting at `next` (advancing
    /// `i` past any further tokens it takes). Returns the values, the keys
    /// given (even with a bad value) and whether all was well.
    pub(super) fn param_list(
        &mut self,
        tokens: &[ParamToken],
        set: &ParamSet,
        mut value: impl FnMut(
            &mut Self,
            &'static schema::ParamSpec,
            &ParamToken,
            &[ParamToken],
            &mut usize,
        ) -> Parsed,
    ) -> ParamList {
        let mut values: BTreeMap<&'static str, Param> = BTreeMap::new();
        let mut given: Vec<(&'static str, std::ops::Range<usize>)> = Vec::new();
        let mut ok = true;
        let mut i = 0;
        while i < tokens.len() {
            let tok = &tokens[i];
            let key_at = i;
            i += 1;
            let ParamToken::Word(key) = tok else {
                self.error(
                    Diag::error("scen::analyze::expected_key", "expected a parameter name")
                        .at(tok.span(), "a value without a key")
                        .help(format!("parameters of {}: {}", set.name, set.keys())),
                );
                ok = false;
                continue;
            };
            let Some(spec) = set.get(&key.value) else {
                let mut d = Diag::error(
                    "scen::analyze::unknown_key",
                    format!("unknown parameter `{}` for {}", key.value, set.owner),
                )
                .at(key.span, "unknown key");
                let nested = schema::DRIVE
                    .iter()
                    .filter(|_| set.nested)
                    .find_map(|m| Some(m.name).zip(m.params.iter().find(|p| p.key == key.value)));
                let other_model = schema::DRIVE
                    .iter()
                    .filter(|m| !set.plan && m.params.iter().any(|p| p.key == key.value))
                    .map(|m| m.name)
                    .next();
                let elsewhere = set.planners_accepting(&key.value);
                d = match (
                    nested,
                    other_model,
                    did_you_mean(&key.value, set.specs.iter().map(|p| p.key)),
                ) {
                    (Some((model, p)), _, _) => d.help(format!(
                        "put it in the drive block: `drive {model} {{ {} {} }}`",
                        p.key,
                        p.default.text()
                    )),
                    (None, Some(model), _) => d.help(format!(
                        "`{}` is a key of `drive {model}`; {} accepts: {}",
                        key.value,
                        set.name,
                        set.keys()
                    )),
                    (None, None, _) if !elsewhere.is_empty() => d.help(format!(
                        "`{}` is a parameter of {} only; {} accepts: {}",
                        key.value,
                        schema::backticked(&elsewhere),
                        set.name,
                        set.keys()
                    )),
                    (None, None, Some(k)) => {
                        d.help(format!("did you mean `{k}`? accepted: {}", set.keys()))
                    }
                    (None, None, None) => d.help(format!("accepted: {}", set.keys())),
                };
                self.error(d);
                ok = false;
                // Skip its values: everything up to the next known key.
                while i < tokens.len() {
                    if let ParamToken::Word(w) = &tokens[i]
                        && set.get(&w.value).is_some()
                    {
                        break;
                    }
                    i += 1;
                }
                continue;
            };
            given.push((spec.key, key_at..key_at + 1));
            if !spec.repeatable
                && let Some(first) = values.get(spec.key)
            {
                self.error(
                    Diag::error(
                        "scen::analyze::duplicate_key",
                        format!("`{}` is given twice", spec.key),
                    )
                    .at(key.span, "second time")
                    .with_related(first.span, "first given here")
                    .help("give each parameter once"),
                );
                ok = false;
            }
            let Some(next) = tokens.get(i) else {
                self.missing_value(spec, key.span);
                ok = false;
                break;
            };
            // A known key right after a key means the value is missing.
            if let ParamToken::Word(w) = next
                && !spec.value.takes_word()
                && set.get(&w.value).is_some()
            {
                self.missing_value(spec, key.span);
                ok = false;
                continue;
            }
            i += 1;
            let parsed = value(self, spec, next, tokens, &mut i);
            if let Some((_, range)) = given.last_mut() {
                range.end = i;
            }
            match parsed {
                Parsed::Value(value) => {
                    values.insert(
                        spec.key,
                        Param {
                            value,
                            span: next.span(),
                        },
                    );
                }
                Parsed::Stored => {}
                Parsed::Bad => ok = false,
            }
        }
        ParamList { values, given, ok }
    }

    /// `limit KIND AMOUNT` (repeatable, each kind once), stored in
    /// `limits`; each of `planners` must honour the kind.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn limit(
        &mut self,
        planners: &[&'static Planner],
        spec: &schema::ParamSpec,
        next: &ParamToken,
        tokens: &[ParamToken],
        i: &mut usize,
        limits: &mut Limits,
        spans: &mut HashMap<&'static str, Span>,
    ) -> Parsed {
        let ParamToken::Word(which) = next else {
            self.wrong_value(spec, next);
            return Parsed::Bad;
        };
        let amount = tokens.get(*i);
        let Some(k) = schema::LIMIT_KINDS.iter().find(|k| **k == which.value) else {
            self.error(
                Diag::error(
                    "scen::analyze::bad_limit",
                    format!("unknown limit `{}`", which.value),
                )
                .at(which.span, "not a limit")
                .help(match planners {
                    [planner] => format!("`{}` stops at {}", planner.kind, limits_of(planner)),
                    _ => format!("`limit` takes {}", spec.value.describe()),
                }),
            );
            if let Some(ParamToken::Value(_)) = amount {
                *i += 1; // its amount
            }
            return Parsed::Bad;
        };
        let Some(ParamToken::Value(v)) = amount else {
            let example = if *k == "time" { "2s" } else { "10000" };
            self.error(
                Diag::error(
                    "scen::analyze::missing_value",
                    format!("`limit {k}` needs an amount"),
                )
                .at(which.span, "no amount")
                .help(format!("write e.g. `limit {k} {example}`")),
            );
            return Parsed::Bad;
        };
        *i += 1;
        let mut ok = true;
        if let Some(planner) = planners.iter().find(|p| !p.limits.contains(k)) {
            self.error(
                Diag::error(
                    "scen::analyze::bad_limit",
                    format!("`{}` does not honour `limit {k}`", planner.kind),
                )
                .at(which.span, "not a limit of this planner")
                .help(format!(
                    "`{}` stops at {}",
                    planner.kind,
                    limits_of(planner)
                )),
            );
            ok = false;
        }
        if let Some(first) = spans.get(k) {
            self.error(
                Diag::error(
                    "scen::analyze::duplicate_key",
                    format!("`limit {k}` is given twice"),
                )
                .at(which.span, "second time")
                .with_related(*first, "first given here")
                .help("give each limit once"),
            );
            ok = false;
        }
        spans.insert(k, which.span);
        match (*k, &v.kind) {
            ("time", ValueKind::Duration(s)) if *s > 0.0 && s.is_finite() => limits.time = Some(*s),
            ("time", _) => {
                self.error(
                    Diag::error(
                        "scen::analyze::bad_limit",
                        "`limit time` needs a positive duration",
                    )
                    .at(v.span, "expected a duration")
                    .help("write `limit time 2s` or `limit time 500ms`"),
                );
                ok = false;
            }
            (_, ValueKind::Number(n)) if *n >= 1.0 && n.fract() == 0.0 && *n <= 1e18 => {
                let n = *n as u64;
                match *k {
                    "expansions" => limits.expansions = Some(n),
                    "steps" => limits.steps = Some(n),
                    "iterations" => limits.iterations = Some(n),
                    _ => limits.cells = Some(n),
                }
            }
            _ => {
                self.error(
                    Diag::error(
                        "scen::analyze::bad_limit",
                        format!("`limit {k}` needs a positive integer"),
                    )
                    .at(v.span, "expected a positive integer")
                    .help(format!("write e.g. `limit {k} 10000`")),
                );
                ok = false;
            }
        }
        if ok { Parsed::Stored } else { Parsed::Bad }
    }

    pub(super) fn missing_value(&mut self, spec: &schema::ParamSpec, at: Span) {
        self.error(
            Diag::error(
                "scen::analyze::missing_value",
                format!("`{}` needs a value", spec.key),
            )
            .at(at, "no value")
            .help(format!("`{}` takes {}", spec.key, spec.value.describe())),
        );
    }

    pub(super) fn wrong_value(&mut self, spec: &schema::ParamSpec, tok: &ParamToken) {
        let found = match tok {
            ParamToken::Word(w) => format!("the word `{}`", w.value),
            ParamToken::Value(v) => v.kind.describe().to_string(),
            ParamToken::Block { .. } => "a `{ }` block".to_string(),
        };
        self.error(
            Diag::error(
                "scen::analyze::wrong_type",
                format!(
                    "`{}` takes {}, found {found}",
                    spec.key,
                    spec.value.describe()
                ),
            )
            .at(tok.span(), "unexpected value")
            .help(format!(
                "`{}`: {} (default {})",
                spec.key,
                spec.help,
                if spec.default.text().is_empty() {
                    "none"
                } else {
                    spec.default.text()
                }
            )),
        );
    }

    pub(super) fn param_value(
        &mut self,
        spec: &schema::ParamSpec,
        tok: &ParamToken,
    ) -> Option<ParamValue> {
        match (spec.value, tok) {
            (ValueSpec::Pose, ParamToken::Value(v)) => self
                .expect_pose(v, &format!("`{}`", spec.key))
                .map(ParamValue::Pose),
            (
                ValueSpec::Number {
                    min,
                    min_open,
                    max,
                    integer,
                },
                ParamToken::Value(v),
            ) => {
                let x = match v.kind {
                    ValueKind::Number(x) => x,
                    _ => {
                        self.wrong_value(spec, tok);
                        return None;
                    }
                };
                let below = if min_open { x <= min } else { x < min };
                let ok = !(below || x > max || (integer && x.fract() != 0.0));
                self.in_range(spec, v, x, ok, &format!("{x}"))
            }
            (ValueSpec::IntChoice(choices), ParamToken::Value(v)) => {
                let ValueKind::Number(x) = v.kind else {
                    self.wrong_value(spec, tok);
                    return None;
                };
                if x.fract() == 0.0 && choices.contains(&(x as i64)) {
                    Some(ParamValue::Num(x))
                } else {
                    let all: Vec<String> = choices.iter().map(|c| format!("`{c}`")).collect();
                    let list = match all.split_last() {
                        Some((last, [])) => last.clone(),
                        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
                        None => String::new(),
                    };
                    self.error(
                        Diag::error(
                            "scen::analyze::out_of_range",
                            format!("`{}` must be {list}, got {x}", spec.key),
                        )
                        .at(v.span, "not accepted")
                        .help(format!("`{}`: {}", spec.key, spec.help)),
                    );
                    None
                }
            }
            (ValueSpec::Word(words), ParamToken::Word(w)) => {
                if words.contains(&w.value.as_str()) {
                    Some(ParamValue::Word(w.value.clone()))
                } else {
                    self.bad_word(spec, w, words);
                    None
                }
            }
            (ValueSpec::IntOrWord(words) | ValueSpec::NumOrWord(words), ParamToken::Word(w)) => {
                if words.contains(&w.value.as_str()) {
                    Some(ParamValue::Word(w.value.clone()))
                } else {
                    self.bad_word(spec, w, words);
                    None
                }
            }
            (ValueSpec::IntOrWord(_), ParamToken::Value(v)) => match v.kind {
                ValueKind::Number(x) => {
                    let ok = x >= 1.0 && x.fract() == 0.0 && x <= 1e9;
                    self.in_range(spec, v, x, ok, &format!("{x}"))
                }
                _ => {
                    self.wrong_value(spec, tok);
                    None
                }
            },
            (ValueSpec::NumOrWord(_), ParamToken::Value(v)) => match v.kind {
                ValueKind::Number(x) => {
                    let ok = x > 0.0 && x <= MAX_MAGNITUDE;
                    self.in_range(spec, v, x, ok, &format!("{x}"))
                }
                _ => {
                    self.wrong_value(spec, tok);
                    None
                }
            },
            (ValueSpec::ObstacleName, ParamToken::Word(w)) => {
                Some(ParamValue::Word(w.value.clone()))
            }
            (ValueSpec::Seconds { max }, ParamToken::Value(v)) => match v.kind {
                ValueKind::Number(x) | ValueKind::Duration(x) => {
                    self.in_range(spec, v, x, x > 0.0 && x <= max, &format!("{x}"))
                }
                _ => {
                    self.wrong_value(spec, tok);
                    None
                }
            },
            (ValueSpec::Fraction { min, max }, ParamToken::Value(v)) => match v.kind {
                ValueKind::Percent(x) | ValueKind::Number(x) => {
                    let shown = match v.kind {
                        ValueKind::Percent(_) => format!("{}%", x * 100.0),
                        _ => format!("{x}"),
                    };
                    self.in_range(spec, v, x, x >= min && x <= max, &shown)
                }
                _ => {
                    self.wrong_value(spec, tok);
                    None
                }
            },
            (ValueSpec::Angle { max }, ParamToken::Value(v)) => match v.kind {
                ValueKind::Angle(a) => {
                    let x = self.bounded_angle(v, a)?.radians();
                    let shown = format!("{}deg", x.to_degrees());
                    self.in_range(spec, v, x, x > 0.0 && x <= max, &shown)
                }
                ValueKind::Number(n) => {
                    self.angle_without_unit(
                        v.span,
                        n,
                        format!("`{}` is an angle and needs a unit", spec.key),
                    );
                    None
                }
                _ => {
                    self.wrong_value(spec, tok);
                    None
                }
            },
            _ => {
                self.wrong_value(spec, tok);
                None
            }
        }
    }

    /// An angle within ±1e9 in its unit (SPEC 2.1); beyond, an error at it.
    pub(super) fn bounded_angle(&mut self, v: &Value, a: ast::Angle) -> Option<ast::Angle> {
        if a.written.abs() <= MAX_MAGNITUDE {
            return Some(a);
        }
        let unit = match a.unit {
            ast::AngleUnit::Deg => "deg",
            ast::AngleUnit::Rad => "rad",
        };
        self.error(
            Diag::error(
                "scen::analyze::number_too_large",
                format!(
                    "the angle is {}{unit}, beyond ±1e9 in its unit",
                    short_number(a.written)
                ),
            )
            .at(v.span, "more than 1e9 in magnitude")
            .help("an angle must lie within ±1e9 in its unit; a heading is taken modulo a full turn, so write it within one turn (`0deg` to `360deg`)"),
        );
        None
    }

    /// A bare number `n` where an angle is expected: says which units to add.
    pub(super) fn angle_without_unit(&mut self, span: Span, n: f64, message: String) {
        self.error(
            Diag::error("scen::analyze::angle_unit", message)
                .at(span, "a bare number")
                .help(format!("write `{n}deg` or `{n}rad`")),
        );
    }

    /// `x` (shown as `shown`) if `ok`, else an out-of-range error.
    pub(super) fn in_range(
        &mut self,
        spec: &schema::ParamSpec,
        v: &Value,
        x: f64,
        ok: bool,
        shown: &str,
    ) -> Option<ParamValue> {
        if ok {
            return Some(ParamValue::Num(x));
        }
        self.error(
            Diag::error(
                "scen::analyze::out_of_range",
                format!(
                    "`{}` must be {}, got {shown}",
                    spec.key,
                    spec.value.describe()
                ),
            )
            .at(v.span, "out of range")
            .help(format!("`{}`: {}", spec.key, spec.help)),
        );
        None
    }

    pub(super) fn bad_word(
        &mut self,
        spec: &schema::ParamSpec,
        w: &Spanned<String>,
        words: &[&str],
    ) {
        let mut d = Diag::error(
            "scen::analyze::out_of_range",
            format!("`{}` does not accept `{}`", spec.key, w.value),
        )
        .at(w.span, "not accepted");
        d = match did_you_mean(&w.value, words.iter().copied()) {
            Some(s) => d.help(format!(
                "did you mean `{s}`? `{}` takes {}",
                spec.key,
                spec.value.describe()
            )),
            None => d.help(format!("`{}` takes {}", spec.key, spec.value.describe())),
        };
        self.error(d);
    }

    /// `who` names the body at `c` in the label ("robot `r`", "agent
    /// `a1`").
    pub(super) fn check_pose(
        &mut self,
        world: &World,
        robot: &Robot,
        who: &str,
        c: Config,
        span: Span,
        which: &str,
    ) {
        if !world.bounds.contains(c.xy()) {
            let b = world.bounds;
            self.error(
                Diag::error(
                    "scen::analyze::pose_outside",
                    format!("the {which} lies outside the world's bounds"),
                )
                .at(span, "outside `bounds`")
                .help(format!(
                    "the bounds are ({}, {}) to ({}, {})",
                    b.min.x, b.min.y, b.max.x, b.max.y
                )),
            );
            return;
        }
        if let Some(i) = crate::geometry::validator::config_collision(world, &robot.shape, c) {
            self.error(
                Diag::error(
                    "scen::analyze::pose_in_collision",
                    format!(
                        "the {which} is in collision with obstacle `{}`",
                        world.obstacles[i].name
                    ),
                )
                .at(
                    span,
                    format!("{who} overlaps `{}` here", world.obstacles[i].name),
                )
                .help(format!(
                    "move the {which} so that the robot's body is clear of every obstacle"
                )),
            );
        }
    }
}

/// "A", "A and B", "A, B and C".
fn and_list(items: &[&str]) -> String {
    match items {
        [] => String::new(),
        [one] => (*one).to_string(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}
