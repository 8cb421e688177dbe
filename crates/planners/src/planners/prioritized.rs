//! `prioritized` (SPEC 3.11): a team in any world, in continuous time.
//! The agents plan one after another with `sipp`, each among the world's
//! moving obstacles and the agents before it, which move along their
//! trajectories and then stay at their goals for good. Fast and simple,
//! and incomplete: an agent may find no way among the earlier ones (its
//! note says which) although another order would have worked.

use std::any::Any;

use crate::contract::schema::{MetricSpec, ParamSpec, RobotKind, Word};
use crate::contract::{MetricValue, PlanArgs, PlanOutcome, Planner, Settings, Task};
use crate::diagnostics::Diag;
use crate::geometry::rng::SplitMix64;
use crate::geometry::team::agent_obstacle;
use crate::geometry::timed::MovingObstacle;
use crate::geometry::{Config, RobotShape};
use crate::planners::deadline::Deadline;
use crate::planners::lattice::{LATTICE_PARAMS, Sample, check_lattice_of};
use crate::planners::mapf;
use crate::planners::registry::sipp::{self, Sipp};

crate::word_enum! {
    /// The order the agents plan in.
    pub enum Order {
        /// As the team lists them.
        Given = "given",
        /// The agent with the shortest straight line to its goal first.
        ShortestFirst = "shortest_first",
        /// Shuffled with the plan's `seed`.
        Random = "random",
    }
}

/// `prioritized` in the registry.
pub static PLANNER: Planner = Planner {
    kind: "prioritized",
    summary: "prioritized planning: each agent of a team by sipp in turn, the earlier ones moving obstacles; continuous time, any world",
    robots: &[RobotKind::Team],
    params: &[
        LATTICE_PARAMS[0],
        mapf::AGENTS,
        sipp::CONNECT,
        ParamSpec::word(
            "order",
            <Order as Word>::WORDS,
            "given",
            "the order the agents plan in",
        ),
    ],
    metrics: &[MetricSpec::num(
        "planned",
        "agents that found a trajectory (all of them when found)",
    )],
    limits: &["expansions", "time", "cells"],
    needs_goal: false,
    randomized: true,
    grids: true,
    time: true,
    check,
};

/// A `prioritized` plan's settings.
#[derive(Clone, Debug)]
pub struct Prioritized {
    pub sipp: Sipp,
    pub order: Order,
}

fn check(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    let order = args.word::<Order>("order");
    let connect = args.num("connect") as u8;
    if !matches!(args.robot.shape, RobotShape::Disk(_)) {
        let plan = args.plan;
        args.error(
            Diag::error(
                "scen::analyze::robot_kind",
                format!("plan `{plan}`: `prioritized` plans teams of `disk` agents"),
            )
            .at(args.robot.span, "agents without a disk body")
            .help("agents that are points never meet in continuous time: give the team a body, `team T disk 0.3 { ... }`"),
        );
        return None;
    }
    mapf::check_agents(args)?;
    let lattice = check_lattice_of(args, Sample::Center, 1.0)?;
    Some(Box::new(Prioritized {
        sipp: Sipp { lattice, connect },
        order,
    }))
}

impl Settings for Prioritized {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        plan(task, self)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// Runs a `prioritized` plan.
pub fn plan(task: &Task<'_>, settings: &Prioritized) -> PlanOutcome {
    let deadline = Deadline::start(&task.limits);
    let n = task.agents.len();
    let radius = task.robot.radius();
    let mut order: Vec<usize> = (0..n).collect();
    match settings.order {
        Order::Given => {}
        Order::ShortestFirst => order.sort_by(|&a, &b| {
            let d = |i: usize| (task.agents[i].goal - task.agents[i].start).norm();
            d(a).total_cmp(&d(b)).then(a.cmp(&b))
        }),
        Order::Random => {
            let mut rng = SplitMix64::new(task.seed);
            for k in (1..n).rev() {
                let j = (rng.next_u64() % (k as u64 + 1)) as usize;
                order.swap(k, j);
            }
        }
    }
    let mut out = PlanOutcome::default();
    let mut moving: Vec<MovingObstacle> = task.moving.to_vec();
    let mut paths = vec![Vec::new(); n];
    let mut times = vec![Vec::new(); n];
    let mut planned = 0usize;
    let mut expansions_left = task.limits.expansions;
    for (k, &i) in order.iter().enumerate() {
        let agent = &task.agents[i];
        let sub = Task {
            start: Config::new(agent.start.x, agent.start.y, 0.0),
            goal: Some(Config::new(agent.goal.x, agent.goal.y, 0.0)),
            limits: crate::contract::Limits {
                expansions: expansions_left,
                ..deadline.remaining(task.limits)
            },
            moving: &moving,
            agents: &[],
            draw: false,
            ..*task
        };
        let one = sipp::plan(&sub, &settings.sipp);
        out.expanded += one.expanded;
        if let Some(left) = &mut expansions_left {
            *left = left.saturating_sub(one.expanded);
        }
        let trajectory = match (one.path, one.times) {
            (Some(path), Some(t)) if path.len() == t.len() => (path, t),
            _ => {
                out.gave_up = one.gave_up;
                let why = one.notes.first().cloned().unwrap_or_default();
                out.notes.push(format!(
                    "agent `{}` ({} of {} in the order) found no trajectory among the {} before it{}{why}",
                    agent.name,
                    k + 1,
                    n,
                    k,
                    if why.is_empty() { "" } else { ": " }
                ));
                out.extra
                    .insert("planned".into(), MetricValue::Num(planned as f64));
                return out;
            }
        };
        let (path, t) = trajectory;
        paths[i] = path.iter().map(Config::xy).collect::<Vec<_>>();
        times[i] = t;
        moving.push(agent_obstacle(&agent.name, radius, &paths[i], &times[i]));
        planned += 1;
    }
    out.extra
        .insert("planned".into(), MetricValue::Num(planned as f64));
    out.cost = Some(times.iter().filter_map(|t| t.last()).sum());
    out.agents = Some(paths);
    out.agent_times = Some(times);
    out
}

#[cfg(test)]
#[path = "prioritized/tests.rs"]
mod tests;
