//! `prioritized` on random small worlds: every team it solves passes the
//! continuous referee (every agent against the world and every other agent
//! as a moving obstacle, exactly), and a failure names the agent.

use super::*;
use crate::planners::mapf::cases::random_team;
use crate::contract::{Agent, Limits};
use crate::diagnostics::Span;
use crate::geometry::fixtures::{grid, world_in};
use crate::geometry::team::validate_continuous_team;
use crate::geometry::{Aabb, Point, World};
use crate::planners::lattice::LatticeSpec;

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

fn run(world: &World, agents: &[Agent], order: Order, seed: u64) -> PlanOutcome {
    let robot = RobotShape::Disk(0.3);
    let task = Task {
        world,
        robot: &robot,
        start: Config::new(agents[0].start.x, agents[0].start.y, 0.0),
        goal: None,
        limits: Limits::default(),
        seed,
        steering: None,
        draw: false,
        referee: None,
        moving: &[],
        speed: Some(1.5),
        agents,
    };
    let lattice = LatticeSpec::new(world, 1.0, Sample::Center, 1.0);
    plan(
        &task,
        &Prioritized {
            sipp: Sipp { lattice, connect: 8 },
            order,
        },
    )
}

/// A 5–7 cells a side map with a few walls and 2–4 agents.
fn random_case(seed: u64) -> (World, Vec<Agent>) {
    random_team(seed, 2 + (seed % 3) as usize, 5, 3, 6)
}

#[test]
fn every_team_it_solves_passes_the_continuous_referee() {
    let mut solved = 0;
    for seed in 0..150u64 {
        let (world, agents) = random_case(seed);
        let order = [Order::Given, Order::ShortestFirst, Order::Random][seed as usize % 3];
        let out = run(&world, &agents, order, seed);
        let (Some(points), Some(times)) = (&out.agents, &out.agent_times) else {
            assert!(out.notes[0].contains("found no trajectory"), "seed {seed}: {:?}", out.notes);
            continue;
        };
        solved += 1;
        let names: Vec<&str> = agents.iter().map(|a| a.name.as_str()).collect();
        let ends: Vec<(Point, Point)> = agents.iter().map(|a| (a.start, a.goal)).collect();
        let arrivals = validate_continuous_team(
            &world,
            &[],
            &RobotShape::Disk(0.3),
            1.5,
            &names,
            &ends,
            points,
            times,
        )
        .unwrap_or_else(|e| panic!("seed {seed}: {e:?}\n{:?}\n{:?}\n{agents:?}", points[e.agent], times[e.agent]));
        assert_eq!(out.cost, Some(arrivals.iter().sum()), "seed {seed}");
    }
    assert!(solved > 100, "{solved} of 150 solved");
}

#[test]
fn a_failure_names_the_agent() {
    // A corridor one cell wide: the first agent drives over the second's
    // start, where the second has nowhere to go.
    let world = world_in(
        Aabb::from_corners(p(0.0, 0.0), p(5.0, 1.0)),
        vec![grid(1.0, p(0.0, 0.0), &["....."])],
    );
    let agents = vec![
        Agent { name: "west".into(), start: p(0.5, 0.5), goal: p(4.5, 0.5), span: Span::default() },
        Agent { name: "east".into(), start: p(4.5, 0.5), goal: p(0.5, 0.5), span: Span::default() },
    ];
    let out = run(&world, &agents, Order::Given, 0);
    assert!(out.agents.is_none());
    assert!(out.notes[0].starts_with("agent `east` (2 of 2 in the order)"), "{:?}", out.notes);
    assert_eq!(out.extra.get("planned"), Some(&MetricValue::Num(1.0)));
}
