//! `cbs` against an independent optimum: Dijkstra over the team's joint
//! states (every agent's point, and whether it has stopped at its goal for
//! good), each step costing one per agent not yet stopped. On hundreds of
//! random small grids with two or three agents, `cbs` finds a solution
//! exactly when one exists (within its limit), of the joint optimum's sum
//! of costs, and the referee (`scen_geometry::team`) accepts it.

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};

use super::*;
use crate::planners::mapf::cases::{joint_steps, random_team, team_task};
use crate::contract::{Agent, Limits};
use crate::diagnostics::Span;
use crate::geometry::fixtures::{grid, world_in};
use crate::geometry::team::{TeamGrid, validate_team};
use crate::geometry::validator::Validator;
use crate::geometry::{Aabb, Point, RobotShape, World};
use crate::planners::lattice::Sample;

struct Case {
    world: World,
    w: usize,
    h: usize,
    agents: Vec<Agent>,
}

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

/// A 4–5 cells a side map, about a fifth of it walls, and `n` agents.
fn random_case(seed: u64, n: usize) -> Case {
    let (world, agents) = random_team(seed, n, 4, 2, 5);
    let (w, h) = (world.bounds.width() as usize, world.bounds.height() as usize);
    Case { world, w, h, agents }
}

fn run(case: &Case, limits: Limits) -> PlanOutcome {
    let spec = LatticeSpec::new(&case.world, 1.0, Sample::Center, 1.0);
    plan(&team_task(&case.world, &case.agents, limits, 0), &Cbs { lattice: spec })
}

/// The joint optimum's sum of costs, or `None` when the team has no
/// solution. A state is each agent's cell and a bit per agent that has
/// stopped at its goal for good; an agent at its goal may stop at no cost,
/// and each step costs one per agent not stopped.
fn joint_optimum(case: &Case) -> Option<u64> {
    let g = TeamGrid::new(&case.world, &RobotShape::Point, 1.0, &Validator::new(&case.world))
        .expect("a small grid");
    let n = case.agents.len();
    let starts: Vec<usize> = case.agents.iter().map(|a| g.node(a.start).unwrap()).collect();
    let goals: Vec<usize> = case.agents.iter().map(|a| g.node(a.goal).unwrap()).collect();
    type S = (Vec<usize>, u32);
    let mut best: HashMap<S, u64> = HashMap::new();
    let mut heap = BinaryHeap::new();
    let start: S = (starts, 0);
    best.insert(start.clone(), 0);
    heap.push(Reverse((0u64, start)));
    let all = (1u32 << n) - 1;
    while let Some(Reverse((d, (pos, done)))) = heap.pop() {
        if best.get(&(pos.clone(), done)).is_some_and(|&b| b < d) {
            continue;
        }
        if done == all {
            return Some(d);
        }
        let mut push = |s: S, c: u64| {
            if best.get(&s).is_none_or(|&b| c < b) {
                best.insert(s.clone(), c);
                heap.push(Reverse((c, s)));
            }
        };
        // Stop an agent at its goal (free).
        for a in 0..n {
            if done & (1 << a) == 0 && pos[a] == goals[a] {
                push((pos.clone(), done | (1 << a)), d);
            }
        }
        // Every joint step of the agents not stopped.
        let moving: Vec<usize> = (0..n).filter(|&a| done & (1 << a) == 0).collect();
        for next in joint_steps(&g, &pos, &moving) {
            push((next, done), d + moving.len() as u64);
        }
    }
    None
}

#[test]
fn cbs_matches_the_joint_optimum() {
    let (mut solved, mut unsolvable) = (0, 0);
    for seed in 0..300u64 {
        let case = random_case(seed, 2 + (seed % 2) as usize);
        let optimum = joint_optimum(&case);
        let out = run(
            &case,
            Limits {
                expansions: Some(200_000),
                ..Limits::default()
            },
        );
        match optimum {
            Some(soc) => {
                solved += 1;
                let paths = out.agents.as_ref().unwrap_or_else(|| {
                    panic!("seed {seed}: no solution, joint optimum {soc}: {:?}", out.notes)
                });
                assert_eq!(out.cost, Some(soc as f64), "seed {seed}");
                let g = TeamGrid::new(&case.world, &RobotShape::Point, 1.0, &Validator::new(&case.world))
                    .unwrap();
                let ends: Vec<(Point, Point)> = case.agents.iter().map(|a| (a.start, a.goal)).collect();
                let costs = validate_team(&g, &ends, paths).unwrap_or_else(|e| panic!("seed {seed}: {e:?}"));
                assert_eq!(costs.iter().sum::<usize>() as u64, soc, "seed {seed}");
            }
            None => {
                unsolvable += 1;
                assert!(out.agents.is_none(), "seed {seed}: a solution where none exists");
            }
        }
        assert!(case.w * case.h >= 16);
    }
    // Both kinds occur in the sample.
    assert!(solved > 200 && unsolvable > 0, "{solved} solved, {unsolvable} without a solution");
}

#[test]
fn a_swap_in_a_corridor_waits_in_the_bay() {
    // The corridor of SPEC 2.10's example: the bay above its middle.
    let world = world_in(
        Aabb::from_corners(p(0.0, 0.0), p(5.0, 2.0)),
        vec![grid(1.0, p(0.0, 0.0), &["##.##", "....."])],
    );
    let agents = vec![
        Agent { name: "a".into(), start: p(0.5, 0.5), goal: p(4.5, 0.5), span: Span::default() },
        Agent { name: "b".into(), start: p(4.5, 0.5), goal: p(0.5, 0.5), span: Span::default() },
    ];
    let case = Case { world, w: 5, h: 2, agents };
    let out = run(&case, Limits::default());
    // Each needs 4 steps alone; one steps into the bay and out (2 more)
    // while the other waits a step or two: 4 + 4 + 2 + 2 = 12? The joint
    // optimum says.
    assert_eq!(out.cost, joint_optimum(&case).map(|c| c as f64));
    assert!(out.agents.is_some());
    // Without the bay there is none: CBS stops at its limit and says so.
    let world = world_in(
        Aabb::from_corners(p(0.0, 0.0), p(5.0, 1.0)),
        vec![grid(1.0, p(0.0, 0.0), &["....."])],
    );
    let case = Case { world, w: 5, h: 1, agents: case.agents };
    assert_eq!(joint_optimum(&case), None);
    let out = run(&case, Limits { expansions: Some(50_000), ..Limits::default() });
    assert!(out.agents.is_none() && out.gave_up, "{:?}", out.notes);
}

#[test]
fn an_agent_walled_off_is_known_at_once() {
    let world = world_in(
        Aabb::from_corners(p(0.0, 0.0), p(3.0, 1.0)),
        vec![grid(1.0, p(0.0, 0.0), &[".#."])],
    );
    let agents = vec![Agent { name: "a".into(), start: p(0.5, 0.5), goal: p(2.5, 0.5), span: Span::default() }];
    let out = run(&Case { world, w: 3, h: 1, agents }, Limits::default());
    assert!(out.agents.is_none() && !out.gave_up);
    assert!(out.notes[0].contains("cannot reach"), "{:?}", out.notes);
}
