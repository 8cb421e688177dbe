//! Running a scenario: every plan, the common metrics of SPEC 3 (computed
//! here from the path, the same way for every planner), the validator, and
//! the checks.

use std::collections::BTreeMap;
use std::time::Instant;

use rayon::prelude::*;

use crate::checks;
use crate::contract::ParamValue;
use crate::contract::schema::{DEFAULT_SPEED, RobotKind};
use crate::contract::{MetricValue, Metrics, PlanOutcome};
use crate::contract::{Task, ValidatorReferee};
use crate::drive::{self, DriveOutcome};
use crate::geometry::car::{CarPath, swept_poses, validate_car_path};
use crate::geometry::path::{path_length, path_turn, smoothness};
use crate::geometry::team;
use crate::geometry::timed::{Timed, moving_clearance, validate_trajectory};
use crate::geometry::validator::{self, DEFAULT_TOLERANCE, ValidationError};
use crate::geometry::{Config, RobotShape, angle_diff};
use crate::scenario::{Check, Plan, Scenario};
use crate::syntax::ast::Selection;

/// The result of one plan.
#[derive(Clone, Debug)]
pub struct PlanRun {
    /// Index into `Scenario::plans`.
    pub plan: usize,
    pub outcome: PlanOutcome,
    /// All metrics: the planner's own and the common ones of SPEC 3.
    pub metrics: Metrics,
    /// Why the path (or the executed motion of a run that stopped short)
    /// failed the validator, if it did.
    pub validation: Option<ValidationError>,
    /// The simulated robot driving the path, for plans with `drive`.
    pub drive: Option<DriveOutcome>,
}

/// The result of one `expect`.
#[derive(Clone, Debug)]
pub struct CheckOutcome {
    /// Index into `Scenario::checks`.
    pub check: usize,
    pub passed: bool,
    /// The value of every metric and aggregate the expression used, by its
    /// text (`plan.metric`, `median(b.p.time_ms)`).
    pub values: BTreeMap<String, MetricValue>,
    /// Every series the expression aggregated: its size, min and max.
    pub series: BTreeMap<String, checks::SeriesStats>,
}

/// One run of a bench: which, and its metrics.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchRun {
    /// Index into `Scenario::benches`.
    pub bench: usize,
    /// Index into the bench's `plans`.
    pub plan: usize,
    /// The configuration ([`Bench::config_values`]).
    pub config: usize,
    /// The sample of the family it ran on (`worlds N`; 0 without).
    pub world: u64,
    /// The run's index in its configuration.
    pub run: u64,
    pub seed: u64,
    pub metrics: Metrics,
}

/// Everything a run produced, for the sinks.
#[derive(Clone, Debug)]
pub struct RunReport {
    pub scenario: Scenario,
    pub plans: Vec<PlanRun>,
    /// The runs of the benches (`scen bench`, `scen test`; empty for
    /// `scen run`).
    pub bench_runs: Vec<BenchRun>,
    pub checks: Vec<CheckOutcome>,
    /// The checks not evaluated because a plan they read did not run
    /// (`scen run --plan`), as indices into `Scenario::checks`.
    pub skipped: Vec<usize>,
}

impl RunReport {
    pub fn passed(&self) -> usize {
        self.checks.iter().filter(|c| c.passed).count()
    }

    pub fn failed(&self) -> usize {
        self.checks.len() - self.passed()
    }

    pub fn plan(&self, run: &PlanRun) -> &Plan {
        &self.scenario.plans[run.plan]
    }
}

/// Runs every plan (or only those named in `only`, when it is not empty)
/// and evaluates the checks whose plans all ran; the planners build their
/// drawable layers.
pub fn run_scenario(scenario: Scenario, only: &[String]) -> RunReport {
    run_scenario_drawing(scenario, only, true)
}

/// [`run_scenario`], the planners building their layers only when `draw`
/// (a sink will draw them: [`Task::draw`]).
pub fn run_scenario_drawing(scenario: Scenario, only: &[String], draw: bool) -> RunReport {
    let selected: Vec<usize> = (0..scenario.plans.len())
        .filter(|&i| only.is_empty() || only.contains(&scenario.plans[i].name))
        .collect();
    let plans: Vec<PlanRun> = selected
        .par_iter()
        .map(|&i| run_plan(&scenario, i, draw))
        .collect();
    let values = RunValues {
        plans: metrics_by_plan(&scenario, &plans),
    };
    let (outcomes, skipped) = evaluate_checks(&scenario, &values, |c| !c.bench);
    RunReport {
        scenario,
        plans,
        bench_runs: Vec::new(),
        checks: outcomes,
        skipped,
    }
}

/// The metrics of the plans that ran, for the checks.
struct RunValues<'a> {
    plans: BTreeMap<&'a str, &'a Metrics>,
}

impl checks::Values for RunValues<'_> {
    fn metrics(&self, plan: &str) -> Option<&Metrics> {
        self.plans.get(plan).copied()
    }

    fn series(&self, _: &str, _: &str, _: &[Selection], _: &str) -> Option<Vec<MetricValue>> {
        None
    }
}

/// The metrics of each plan run, by plan name.
pub(crate) fn metrics_by_plan<'a>(
    scenario: &'a Scenario,
    plans: &'a [PlanRun],
) -> BTreeMap<&'a str, &'a Metrics> {
    plans
        .iter()
        .map(|r| (scenario.plans[r.plan].name.as_str(), &r.metrics))
        .collect()
}

/// Evaluates the checks that `wanted` selects and whose plans all ran;
/// also returns the wanted checks skipped because a plan they read did not
/// run (`--plan`).
pub(crate) fn evaluate_checks(
    scenario: &Scenario,
    values: &dyn checks::Values,
    wanted: impl Fn(&Check) -> bool,
) -> (Vec<CheckOutcome>, Vec<usize>) {
    let mut outcomes = Vec::new();
    let mut skipped = Vec::new();
    for (i, check) in scenario.checks.iter().enumerate() {
        if !wanted(check) {
            continue;
        }
        let mut needed = Vec::new();
        checks::plans_used(&check.expr, &mut needed);
        if !needed.iter().all(|p| values.metrics(p).is_some()) {
            skipped.push(i);
            continue;
        }
        let mut used = checks::Used::default();
        let v = checks::eval(&check.expr, values, &mut used);
        outcomes.push(CheckOutcome {
            check: i,
            passed: v == MetricValue::Bool(true),
            values: used.values,
            series: used.series,
        });
    }
    (outcomes, skipped)
}

/// `scen validate` (SPEC 7): the validator and the metrics on `path`, a
/// path made elsewhere (a trajectory with `times`, judged in space-time),
/// as if plan `index`'s planner had returned it, and
/// the checks that read only that plan. Its `cost` is the path's length;
/// `time_ms` has no value (no planner ran). The first collision is drawn
/// as a layer `collision`.
pub fn validate_user_path(
    scenario: Scenario,
    index: usize,
    path: Vec<Config>,
    times: Option<Vec<f64>>,
) -> RunReport {
    let plan = &scenario.plans[index];
    let task = plan.task(&scenario);
    let outcome = PlanOutcome {
        cost: Some(path_length(&path)),
        path: Some(path),
        times,
        ..PlanOutcome::default()
    };
    let referee = validator::Validator::new(&scenario.world);
    let mut run = judge(&scenario, index, plan, &task, outcome, f64::NAN, &referee);
    // What only a planner measures has no value here: left out, and the
    // checks that read it are skipped.
    for planner_only in ["expanded", "gave_up", "time_ms"] {
        run.metrics.remove(planner_only);
    }
    for m in plan.planner.metrics {
        run.metrics.remove(m.name);
    }
    if let Some(e) = &run.validation {
        use crate::contract::layers::{Colour, Drawing, Layer, Style, Svg};
        run.outcome.layers.push(Layer::new(
            "collision",
            Drawing::Points(vec![e.at.xy()]),
            Style::new(Colour::Red, 6.0, 50.0).svg(Svg::fill(1.0).key("first collision")),
        ));
    }
    let plans = vec![run];
    let values = RunValues {
        plans: metrics_by_plan(&scenario, &plans),
    };
    let judged = &plans[0];
    let name = &scenario.plans[index].name;
    let (checks, skipped) = evaluate_checks(&scenario, &values, |c| {
        let mut read = Vec::new();
        checks::metrics_used(&c.expr, &mut read);
        !c.bench
            && read
                .iter()
                .all(|(p, m)| p != name || judged.metrics.contains_key(m))
    });
    // A check left out by `wanted` is not reported as skipped by
    // `evaluate_checks`: those reading a planner's own metrics are.
    let mut skipped = skipped;
    for (i, c) in scenario.checks.iter().enumerate() {
        let mut read = Vec::new();
        checks::metrics_used(&c.expr, &mut read);
        if !c.bench
            && read
                .iter()
                .any(|(p, m)| p == name && !judged.metrics.contains_key(m))
        {
            skipped.push(i);
        }
    }
    skipped.sort_unstable();
    RunReport {
        scenario,
        plans,
        bench_runs: Vec::new(),
        checks,
        skipped,
    }
}

fn run_plan(scenario: &Scenario, index: usize, draw: bool) -> PlanRun {
    let plan = &scenario.plans[index];
    let task = Task {
        draw,
        ..plan.task(scenario)
    };
    run_task(scenario, index, plan, &task)
}

/// Runs `plan` (plan `index` of the scenario, or one of a bench's
/// configurations of it) on `task`, and measures and validates what it
/// returned.
pub(crate) fn run_task(scenario: &Scenario, index: usize, plan: &Plan, task: &Task<'_>) -> PlanRun {
    let robot = &scenario.robots[plan.robot].shape;
    // The runner holds the validator; it lends it to the planner only for
    // what the validator alone may say (`contract::referee`).
    let lent = ValidatorReferee::new(&scenario.world, robot);
    let task = Task {
        referee: Some(&lent),
        ..*task
    };
    let began = Instant::now();
    let outcome = plan.settings.plan(&task);
    let time_ms = began.elapsed().as_secs_f64() * 1e3;
    // A team's paths are judged as a team's (SPEC 2.10).
    let judged = if plan.planner.plans_teams() {
        judge_team
    } else {
        judge
    };
    judged(
        scenario,
        index,
        plan,
        &task,
        outcome,
        time_ms,
        lent.validator(),
    )
}

/// The runner's half of a run: validates and measures what a plan's
/// planner (or a user, `scen validate`) returned for `task`.
fn judge(
    scenario: &Scenario,
    index: usize,
    plan: &Plan,
    task: &Task<'_>,
    mut outcome: PlanOutcome,
    time_ms: f64,
    referee: &validator::Validator<'_>,
) -> PlanRun {
    let robot = &scenario.robots[plan.robot].shape;
    // The path, or the motion executed by a run that stopped short (SPEC 3:
    // `collision_free` validates it too).
    let motion = match &outcome.path {
        Some(path) => Some(path.as_slice()),
        None if !outcome.trajectory.is_empty() => Some(outcome.trajectory.as_slice()),
        None => None,
    };
    // A thinned motion was validated and measured by its planner as it
    // was made (SPEC 3.4); the list itself skips poses.
    let measured = outcome.measured.as_ref();
    // A car robot's path is its segments (SPEC 3.0): those are validated,
    // and a path given only as poses is refused.
    let car = outcome.car.as_ref().filter(|_| outcome.path.is_some());
    // A path of poses is validated and measured in one pass.
    let mut measured_clearance = None;
    // A trajectory (SPEC 2.9): its poses with their times, validated in
    // space-time among the moving obstacles.
    let timed = outcome.timed();
    let untimed_poses = timed.is_none() && outcome.path.is_some() && outcome.times.is_some();
    let speed = task.speed.unwrap_or(DEFAULT_SPEED);
    let validation = match (measured, car) {
        _ if untimed_poses => Some(ValidationError {
            segment: 0,
            at: task.start,
            obstacle: None,
            reason: "a trajectory needs one time per pose".into(),
        }),
        _ if timed.is_some() => {
            let trajectory = timed.as_deref().unwrap_or_default();
            validate_trajectory(&scenario.world, &scenario.moving, robot, speed, trajectory).err()
        }
        (Some(m), _) => m.validation.clone(),
        (None, Some(car)) => {
            validate_car_path(referee, robot, car, plan.params.goal, DEFAULT_TOLERANCE).err()
        }
        (None, None) if task.steering.is_some() && outcome.path.is_some() => {
            Some(ValidationError {
                segment: 0,
                at: task.start,
                obstacle: None,
                reason: "a car robot's path must be given as segments".into(),
            })
        }
        (None, None) => match outcome.path.as_deref() {
            Some(path) => {
                let (verdict, clearance) =
                    referee.validate_and_measure(robot, path, DEFAULT_TOLERANCE);
                measured_clearance = Some(clearance);
                verdict.err()
            }
            // No path: the motion a run executed, validated only (a clearance
            // without a path has no value).
            None => motion.and_then(|m| referee.validate_path(robot, m, DEFAULT_TOLERANCE).err()),
        },
    };
    let valid = motion.is_some() && validation.is_none();
    let mut metrics = common_metrics(&outcome, robot, plan, time_ms, valid);
    if plan.planner.plans_for(RobotKind::Car) {
        car_metrics(car, &mut metrics);
    }
    if plan.planner.time {
        time_metrics(timed.as_deref(), &mut metrics);
    }
    let path = outcome.path.as_deref();
    let static_clearance = |p: &[Config]| match (measured, car) {
        (Some(m), _) => m.clearance,
        (None, Some(car)) => referee.clearance(
            robot,
            &swept_poses(robot, car, DEFAULT_TOLERANCE),
            DEFAULT_TOLERANCE,
        ),
        (None, None) => {
            measured_clearance.unwrap_or_else(|| referee.clearance(robot, p, DEFAULT_TOLERANCE))
        }
    };
    // Without a path, the clearance has no value (NaN: `null` in JSON, `—`
    // in the report), never a 0 that reads as "touched a wall". A
    // trajectory keeps its distance from the moving obstacles too (exact,
    // the parked robot included; +∞ without any).
    metrics.insert(
        "clearance".into(),
        MetricValue::Num(path.map_or(f64::NAN, |p| {
            let moving = timed.as_deref().map_or(f64::INFINITY, |trajectory| {
                moving_clearance(&scenario.moving, robot, trajectory)
            });
            static_clearance(p).min(moving)
        })),
    );
    metrics.insert(
        "smoothness".into(),
        MetricValue::Num(path.map_or(f64::INFINITY, |p| {
            measured.map_or_else(|| smoothness(p), |m| m.smoothness)
        })),
    );
    let drive = drive_plan(scenario, plan, &outcome, &mut metrics);
    if let Some(note) = drive.as_ref().and_then(DriveOutcome::cut_off_note) {
        outcome.notes.push(note);
    }
    PlanRun {
        plan: index,
        outcome,
        metrics,
        validation,
        drive,
    }
}

/// The runner's half of a team plan (SPEC 2.10): the agents' paths judged
/// by the referee under grid semantics on its own lattice, and the team
/// metrics (the lower bound by breadth-first search on that lattice).
fn judge_team(
    scenario: &Scenario,
    index: usize,
    plan: &Plan,
    task: &Task<'_>,
    outcome: PlanOutcome,
    time_ms: f64,
    referee: &validator::Validator<'_>,
) -> PlanRun {
    use MetricValue::{Bool, Num};
    let robot = &scenario.robots[plan.robot].shape;
    let cell = match plan.params.values.get("cell").map(|p| &p.value) {
        Some(ParamValue::Num(c)) => *c,
        _ => 1.0,
    };
    let agents = task.agents;
    let ends: Vec<_> = agents.iter().map(|a| (a.start, a.goal)).collect();
    let names: Vec<&str> = agents.iter().map(|a| a.name.as_str()).collect();
    let mut metrics = outcome.extra.clone();
    let found = outcome.agents.is_some();
    // A continuous team (SPEC 2.10, `prioritized`): trajectories judged in
    // space-time, each agent among the others; costs are arrivals, the
    // lower bound each agent's straight line at full speed.
    if plan.planner.time {
        let speed = task.speed.unwrap_or(DEFAULT_SPEED);
        let paths = outcome.agents.as_deref().unwrap_or(&[]);
        let times = outcome.agent_times.as_deref().unwrap_or(&[]);
        let validation = found
            .then(|| {
                team::validate_continuous_team(
                    &scenario.world,
                    &scenario.moving,
                    robot,
                    speed,
                    &names,
                    &ends,
                    paths,
                    times,
                )
                .err()
                .map(|e| e.into_validation(&names))
            })
            .flatten();
        let arrivals: Vec<f64> = match found {
            true => times
                .iter()
                .map(|t| t.last().copied().unwrap_or(0.0))
                .collect(),
            false => vec![f64::INFINITY],
        };
        let lower: f64 = ends.iter().map(|(s, g)| (g - s).norm() / speed).sum();
        metrics.insert("found".into(), Bool(found));
        metrics.insert("gave_up".into(), Bool(outcome.gave_up));
        metrics.insert("agents".into(), Num(agents.len() as f64));
        metrics.insert("sum_of_costs".into(), Num(arrivals.iter().sum()));
        metrics.insert(
            "makespan".into(),
            Num(arrivals.iter().copied().fold(0.0, f64::max)),
        );
        metrics.insert("soc_lower_bound".into(), Num(lower));
        metrics.insert("expanded".into(), Num(outcome.expanded as f64));
        metrics.insert("time_ms".into(), Num((time_ms * 1000.0).round() / 1000.0));
        metrics.insert("collision_free".into(), Bool(found && validation.is_none()));
        return PlanRun {
            plan: index,
            outcome,
            metrics,
            validation,
            drive: None,
        };
    }
    let grid = team::TeamGrid::new(&scenario.world, robot, cell, referee);
    let validation = match (&outcome.agents, &grid) {
        (None, _) => None,
        (Some(_), None) => Some(ValidationError {
            segment: 0,
            at: task.start,
            obstacle: None,
            reason: format!("the team's lattice (cell {cell}) is too large for the referee"),
        }),
        (Some(paths), Some(grid)) => team::validate_team(grid, &ends, paths)
            .err()
            .map(|e| e.into_validation(&names)),
    };
    let costs: Option<Vec<usize>> = outcome
        .agents
        .as_ref()
        .map(|paths| paths.iter().map(|p| team::agent_cost(p)).collect());
    // One breadth-first search per agent: beyond 2^30 cell visits in all
    // (10,000 agents on a 100,000-cell map) the bound has no value rather
    // than an unbounded wait.
    let searchable = grid
        .as_ref()
        .filter(|g| g.len().saturating_mul(ends.len()) <= 1 << 30);
    let lower_bound = searchable.map_or(f64::NAN, |g| {
        let mut sum = 0.0;
        for &(s, goal) in &ends {
            let d = match (g.node(s), g.node(goal)) {
                (Some(s), Some(goal)) => g.distances_to(goal)[s],
                _ => u32::MAX,
            };
            sum += if d == u32::MAX {
                f64::INFINITY
            } else {
                f64::from(d)
            };
        }
        sum
    });
    metrics.insert("found".into(), Bool(found));
    metrics.insert("gave_up".into(), Bool(outcome.gave_up));
    metrics.insert("agents".into(), Num(agents.len() as f64));
    let (soc, makespan) = match &costs {
        Some(c) => (
            c.iter().sum::<usize>() as f64,
            c.iter().copied().max().unwrap_or(0) as f64,
        ),
        None => (f64::INFINITY, f64::INFINITY),
    };
    metrics.insert("sum_of_costs".into(), Num(soc));
    metrics.insert("makespan".into(), Num(makespan));
    metrics.insert("soc_lower_bound".into(), Num(lower_bound));
    metrics.insert("expanded".into(), Num(outcome.expanded as f64));
    metrics.insert("time_ms".into(), Num((time_ms * 1000.0).round() / 1000.0));
    metrics.insert("collision_free".into(), Bool(found && validation.is_none()));
    PlanRun {
        plan: index,
        outcome,
        metrics,
        validation,
        drive: None,
    }
}

/// A car robot's metrics (SPEC 3.8) from its segments: `length` and `turn`
/// exactly (not from the drawn poses), `cusps`, `reverse_length` and
/// `segments`; without a car's path (none found, or a robot that is not a
/// car on a planner that plans for cars too) the last three have no
/// value.
fn car_metrics(car: Option<&CarPath>, metrics: &mut Metrics) {
    use MetricValue::Num;
    match car {
        Some(car) => {
            metrics.insert("length".into(), Num(car.length()));
            metrics.insert("turn".into(), Num(car.turn()));
            metrics.insert("cusps".into(), Num(car.cusps() as f64));
            metrics.insert("reverse_length".into(), Num(car.reverse_length()));
            metrics.insert("segments".into(), Num(car.segments.len() as f64));
        }
        None => {
            for name in ["cusps", "reverse_length", "segments"] {
                metrics.insert(name.into(), Num(f64::NAN));
            }
        }
    }
}

/// A time-aware plan's metrics (SPEC 2.9) from its trajectory: `arrival`
/// (its last time; +∞ without one) and `waited` (the time spent standing
/// still; no value without one).
fn time_metrics(trajectory: Option<&[Timed]>, metrics: &mut Metrics) {
    use MetricValue::Num;
    let (arrival, waited) = match trajectory {
        Some(tr) => (
            tr.last().map_or(0.0, |p| p.t),
            tr.windows(2)
                .filter(|w| w[0].pose.x == w[1].pose.x && w[0].pose.y == w[1].pose.y)
                .map(|w| w[1].t - w[0].t)
                .sum(),
        ),
        None => (f64::INFINITY, f64::NAN),
    };
    metrics.insert("arrival".into(), Num(arrival));
    metrics.insert("waited".into(), Num(waited));
}

/// For a plan with `drive`: drives its path with the model of the block
/// (SPEC 3.6, 3.8; a car's along its segments), validates
/// the driven trajectory like a path, and adds the drive metrics. Without a
/// path there is nothing to drive: `drive_time` and `drive_max_deviation`
/// are +∞ and `drive_collision_free` false.
fn drive_plan(
    scenario: &Scenario,
    plan: &Plan,
    outcome: &PlanOutcome,
    metrics: &mut Metrics,
) -> Option<DriveOutcome> {
    use MetricValue::{Bool, Num};
    let Some(ParamValue::Block(model, block)) = plan.params.get("drive") else {
        return None;
    };
    let Some(path) = &outcome.path else {
        metrics.insert("drive_time".into(), Num(f64::INFINITY));
        metrics.insert("drive_max_deviation".into(), Num(f64::INFINITY));
        metrics.insert("drive_collision_free".into(), Bool(false));
        return None;
    };
    let driven = drive::Model::from_block(model, block).drive(path, outcome.car.as_ref());
    let poses: Vec<Config> = driven.samples.iter().map(|(_, c)| *c).collect();
    let robot = &scenario.robots[plan.robot].shape;
    let valid = validator::validate_path(&scenario.world, robot, &poses, DEFAULT_TOLERANCE).is_ok();
    metrics.insert("drive_time".into(), Num(driven.time));
    metrics.insert("drive_max_deviation".into(), Num(driven.max_deviation));
    metrics.insert("drive_collision_free".into(), Bool(valid));
    Some(driven)
}

/// The metrics of SPEC 3 that every planner has, plus the planner's own.
/// `valid`: the path, or the motion executed by a run that stopped short,
/// passed the validator.
fn common_metrics(
    out: &PlanOutcome,
    robot: &RobotShape,
    plan: &Plan,
    time_ms: f64,
    valid: bool,
) -> Metrics {
    use MetricValue::{Bool, Num};
    let mut m = out.extra.clone();
    let found = out.path.is_some();
    let path = out.path.as_deref().unwrap_or(&[]);
    // The whole motion's measures when the path is thinned.
    let measured = out.measured.as_ref().filter(|_| found);
    let (length, turn, nodes) = match measured {
        Some(m) => (m.length, m.turn, m.poses as f64),
        None => (path_length(path), path_turn(path), path.len() as f64),
    };
    m.insert("found".into(), Bool(found));
    m.insert("gave_up".into(), Bool(out.gave_up));
    m.insert(
        "cost".into(),
        Num(if found {
            out.cost.unwrap_or(length)
        } else {
            f64::INFINITY
        }),
    );
    m.insert(
        "length".into(),
        Num(if found { length } else { f64::INFINITY }),
    );
    m.insert("turn".into(), Num(if robot.rotates() { turn } else { 0.0 }));
    m.insert("nodes".into(), Num(nodes));
    m.insert("expanded".into(), Num(out.expanded as f64));
    m.insert("time_ms".into(), Num((time_ms * 1000.0).round() / 1000.0));
    m.insert("collision_free".into(), Bool(valid));
    let reaches = match (path.last(), plan.params.goal) {
        (Some(last), Some(goal)) => {
            let d = (last.x - goal.x).hypot(last.y - goal.y);
            let dt = if robot.rotates() {
                angle_diff(last.theta, goal.theta).abs()
            } else {
                0.0
            };
            d <= 1e-9 && dt <= 1e-9
        }
        _ => false,
    };
    m.insert("reaches_goal".into(), Bool(reaches));
    m
}
