//! Running a scenario: every plan, the common metrics of SPEC 3 (computed
//! here from the path, the same way for every planner), the validator, and
//! the checks.

use std::collections::BTreeMap;
use std::time::Instant;

use rayon::prelude::*;

use crate::checks;
use crate::drive::{self, DriveOutcome, Unicycle};
use crate::geometry::validator::{self, DEFAULT_TOLERANCE, ValidationError};
use crate::geometry::{Config, RobotShape, angle_diff};
use crate::planners::{MetricValue, Metrics, PlanOutcome};
use crate::scenario::{ParamValue, Plan, Scenario};

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
    /// The value of every metric the expression used, by `plan.metric`.
    pub values: BTreeMap<String, MetricValue>,
}

/// Everything a run produced, for the sinks.
#[derive(Clone, Debug)]
pub struct RunReport {
    pub scenario: Scenario,
    pub plans: Vec<PlanRun>,
    pub checks: Vec<CheckOutcome>,
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
/// and evaluates the checks whose plans all ran.
pub fn run_scenario(scenario: Scenario, only: &[String]) -> RunReport {
    let selected: Vec<usize> = (0..scenario.plans.len())
        .filter(|&i| only.is_empty() || only.contains(&scenario.plans[i].name))
        .collect();
    let plans: Vec<PlanRun> = selected
        .par_iter()
        .map(|&i| run_plan(&scenario, i))
        .collect();
    let outcomes = evaluate_checks(&scenario, &plans);
    RunReport {
        scenario,
        plans,
        checks: outcomes,
    }
}

/// Evaluates the checks whose plans all ran.
fn evaluate_checks(scenario: &Scenario, plans: &[PlanRun]) -> Vec<CheckOutcome> {
    let by_name: BTreeMap<&str, &Metrics> = plans
        .iter()
        .map(|r| (scenario.plans[r.plan].name.as_str(), &r.metrics))
        .collect();
    let lookup = |name: &str| by_name.get(name).copied();
    let mut outcomes = Vec::new();
    for (i, check) in scenario.checks.iter().enumerate() {
        let mut needed = Vec::new();
        checks::plans_used(&check.expr, &mut needed);
        if !needed.iter().all(|p| by_name.contains_key(p.as_str())) {
            continue; // a plan it needs was not selected with --plan
        }
        let mut values = BTreeMap::new();
        let v = checks::eval(&check.expr, &lookup, &mut values);
        outcomes.push(CheckOutcome {
            check: i,
            passed: v == MetricValue::Bool(true),
            values,
        });
    }
    outcomes
}

fn run_plan(scenario: &Scenario, index: usize) -> PlanRun {
    let plan = &scenario.plans[index];
    let robot = &scenario.robots[plan.robot].shape;
    let began = Instant::now();
    let outcome = plan.settings.plan(&plan.task(scenario));
    let time_ms = began.elapsed().as_secs_f64() * 1e3;
    // The path, or the motion executed by a run that stopped short (SPEC 3:
    // `collision_free` validates it too).
    let motion = match &outcome.path {
        Some(path) => Some(path.as_slice()),
        None if !outcome.trajectory.is_empty() => Some(outcome.trajectory.as_slice()),
        None => None,
    };
    let validation = motion
        .and_then(|m| validator::validate_path(&scenario.world, robot, m, DEFAULT_TOLERANCE).err());
    let valid = motion.is_some() && validation.is_none();
    let mut metrics = common_metrics(&outcome, robot, plan, time_ms, valid);
    let drive = drive_plan(scenario, plan, &outcome, &mut metrics);
    PlanRun {
        plan: index,
        outcome,
        metrics,
        validation,
        drive,
    }
}

/// For a plan with `drive unicycle`: drives its path (SPEC 3.6), validates
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
    let Some(ParamValue::Block(_, block)) = plan.params.get("drive") else {
        return None;
    };
    let Some(path) = &outcome.path else {
        metrics.insert("drive_time".into(), Num(f64::INFINITY));
        metrics.insert("drive_max_deviation".into(), Num(f64::INFINITY));
        metrics.insert("drive_collision_free".into(), Bool(false));
        return None;
    };
    let driven = drive::drive(path, &Unicycle::from_block(block));
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
    m.insert("found".into(), Bool(found));
    m.insert("gave_up".into(), Bool(out.gave_up));
    m.insert(
        "cost".into(),
        Num(if found {
            out.cost.unwrap_or(path_length(path))
        } else {
            f64::INFINITY
        }),
    );
    m.insert(
        "length".into(),
        Num(if found {
            path_length(path)
        } else {
            f64::INFINITY
        }),
    );
    m.insert(
        "turn".into(),
        Num(if robot.rotates() {
            path_turn(path)
        } else {
            0.0
        }),
    );
    m.insert("nodes".into(), Num(path.len() as f64));
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

/// Euclidean length of the (x, y) polyline.
pub fn path_length(path: &[Config]) -> f64 {
    path.windows(2)
        .map(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y))
        .sum()
}

/// Total absolute rotation along the shorter arcs, in radians.
pub fn path_turn(path: &[Config]) -> f64 {
    path.windows(2)
        .map(|w| angle_diff(w[0].theta, w[1].theta).abs())
        .sum()
}
