//! `astar` (SPEC 3.1) for point and disk robots: A* on the (x, y) lattice.
//! Polygon robots go to [`super::astar_rotating`] ((x, y, θ) lattice).
//!
//! A lattice point is free when the robot placed there overlaps no obstacle
//! interior. An edge joins two free neighbours and is used only if the
//! robot's straight motion along it is collision-free (checked lazily, once
//! per edge, by [`ObstacleIndex::sweep_free`]); diagonal moves also need
//! both orthogonally adjacent points free (no corner cutting, the MovingAI
//! rule). Start and goal are snapped to the nearest lattice points and
//! joined to them by straight motions that must be collision-free too.

use std::any::Any;

use crate::contract::layers;
use crate::contract::schema::{
    DefaultValue, MetricSpec, ParamSpec, RobotKind, ValueSpec, Word, YesNo, at_least, num,
};
use crate::contract::{MetricValue, PlanArgs, PlanOutcome, Planner, Settings, Task};
use crate::geometry::collide::ObstacleIndex;
use crate::geometry::{Point, RobotShape};

pub use super::astar_settings::Astar;
use super::deadline::{Deadline, setup_note};
use super::grid_lattice::{
    GridLattice, SearchBuffers, SearchConfig, grown_obstacles, lattice_path, search, snap_ends,
};
use super::lattice::{CostMetric, Heuristic, LATTICE_PARAMS, check_connect, check_lattice};

/// `astar` in the registry.
pub static PLANNER: Planner = Planner {
    kind: "astar",
    summary: "A* on a lattice of configurations",
    robots: &[RobotKind::Point, RobotKind::Disk, RobotKind::Polygon],
    params: &[
        LATTICE_PARAMS[0],
        LATTICE_PARAMS[1],
        LATTICE_PARAMS[2],
        ParamSpec::new(
            "layers",
            ValueSpec::IntOrWord(&["auto"]),
            DefaultValue::Word("auto"),
            "θ layers for rotating robots; `auto` = ⌈2πR/δ⌉",
        ),
        ParamSpec::word("cost", CostMetric::WORDS, "euclid", "edge cost metric"),
        ParamSpec::new(
            "turn_cost",
            at_least(0.0, false),
            DefaultValue::Derived("R of the robot"),
            "cost of one radian of rotation",
        ),
        ParamSpec::new(
            "weight",
            at_least(1.0, false),
            num(1.0, "1"),
            "heuristic inflation w ≥ 1",
        ),
        ParamSpec::word(
            "heuristic",
            Heuristic::WORDS,
            "lattice",
            "`lattice` (the exact obstacle-free lattice cost), `metric` (the cost metric) or `zero` (Dijkstra)",
        ),
        ParamSpec::new(
            "rotate",
            ValueSpec::Word(YesNo::WORDS),
            DefaultValue::Derived("yes for polygons"),
            "search in θ too",
        ),
    ],
    metrics: &[
        MetricSpec::num("cells", "lattice configurations"),
        MetricSpec::num(
            "free_cells",
            "lattice configurations where the robot is free",
        ),
        MetricSpec::num(
            "layers",
            "θ layers of the lattice (1 for robots that do not rotate)",
        ),
        MetricSpec::num("generated", "configurations put on the open list"),
    ],
    limits: &["expansions", "time", "cells"],
    needs_goal: true,
    randomized: false,
    grids: true,
    time: false,
    check,
};

fn check(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    let robot = &args.robot.shape;
    let rotating = robot.rotates() && args.opt_word::<YesNo>("rotate") != Some(YesNo::No);
    let connect = check_connect(args, rotating);
    let layers = if rotating {
        args.opt_num("layers").unwrap_or_else(|| {
            (std::f64::consts::TAU * robot.radius() / args.num("cell"))
                .ceil()
                .max(1.0)
        })
    } else {
        1.0
    };
    let lattice = check_lattice(args, layers)?;
    Some(Box::new(Astar {
        lattice,
        rotating,
        connect: connect?,
        cost: args.word("cost"),
        turn_cost: args
            .opt_num("turn_cost")
            .unwrap_or_else(|| args.robot.shape.radius()),
        weight: args.num("weight"),
        heuristic: args.word("heuristic"),
    }))
}

impl Settings for Astar {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        match task.robot {
            RobotShape::Polygon(p) => super::astar_rotating::plan(task, self, p),
            _ => plan_xy(task, self),
        }
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// Runs an `astar` plan for a point or disk robot.
fn plan_xy(task: &Task<'_>, settings: &Astar) -> PlanOutcome {
    let deadline = Deadline::start(&task.limits);
    let world = task.world;
    let radius = task.robot.radius();
    let spec = settings.lattice;
    let mut out = PlanOutcome::default();
    out.extra
        .insert("cells".into(), MetricValue::Num(spec.cells_f64()));
    out.extra
        .insert("layers".into(), MetricValue::Num(spec.layers as f64));
    out.extra.insert("generated".into(), MetricValue::Num(0.0));
    if task.draw {
        out.layers
            .extend(layers::grown_by_disk(grown_obstacles(world, radius)));
    }
    // Until the lattice is classified (and for good when nothing is built).
    out.extra.insert("free_cells".into(), MetricValue::Num(0.0));
    if task.start_is_goal() {
        return PlanOutcome {
            extra: out.extra,
            layers: out.layers,
            ..PlanOutcome::at_goal(task.start)
        };
    }
    let index = ObstacleIndex::new(world);
    let Some(mut lat) = GridLattice::build_until(spec, &index, radius, &deadline) else {
        out.gave_up = true;
        out.notes.push(setup_note("classifying the lattice"));
        return out;
    };
    out.extra.insert(
        "free_cells".into(),
        MetricValue::Num(lat.free_count() as f64),
    );
    let start = task.start;
    let goal = task.goal.unwrap_or(start);
    let (s_node, g_node) = match snap_ends(&lat, &index, start, goal) {
        Ok(ends) => ends,
        Err(note) => {
            out.notes.push(note);
            return out;
        }
    };
    let cfg = SearchConfig::new(
        settings.connect,
        settings.cost,
        settings.weight,
        settings.heuristic,
        deadline.remaining(task.limits),
    );
    let mut buf = SearchBuffers::default();
    let r = search(&mut lat, &index, s_node, g_node, &cfg, task.draw, &mut buf);
    out.expanded = r.expanded;
    out.gave_up = r.gave_up;
    out.extra
        .insert("generated".into(), MetricValue::Num(r.generated as f64));
    if task.draw {
        let expanded: Vec<Point> = r
            .expansion_order
            .iter()
            .map(|&n| spec.point_of(n))
            .collect();
        out.layers.extend(layers::search(&expanded));
    }
    if let Some(nodes) = r.nodes {
        let (s_pt, g_pt) = (spec.point_of(s_node), spec.point_of(g_node));
        let cost = cfg.cost.between(start.xy(), s_pt) + r.cost + cfg.cost.between(g_pt, goal.xy());
        out.cost = Some(cost);
        out.path = Some(lattice_path(&spec, &nodes, start, goal));
    } else if r.gave_up {
        out.notes.push("a limit was reached before the goal".into());
    }
    out
}
