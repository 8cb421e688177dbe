//! `lacam` against independent searches over the team's joint
//! configurations, on hundreds of random small grids with two or three
//! agents: it finds a solution exactly when one exists (complete: when
//! none does, its search is exhausted and it says so, without a limit),
//! every solution passes the referee, and with `refine yes` its sum of loss
//! is the joint optimum's (LaCAM*'s objective: each step an agent is not
//! resting at its goal costs 1).

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};

use super::*;
use crate::planners::mapf::cases::{joint_steps, random_team, team_task};
use crate::contract::{Agent, Limits};
use crate::geometry::team::{TeamGrid, validate_team};
use crate::geometry::validator::Validator;
use crate::geometry::{Point, RobotShape, World};
use crate::planners::lattice::Sample;

/// A 3–5 cells a side map, about a quarter of it walls, and `n` agents.
fn random_case(seed: u64, n: usize) -> (World, Vec<Agent>) {
    random_team(seed, n, 3, 3, 4)
}

fn run(world: &World, agents: &[Agent], refine: bool, seed: u64) -> PlanOutcome {
    // Odd seeds keep the best of ten PIBT runs per successor; half the
    // seeds guide PIBT by scatter paths, half swap (none of it may cost
    // completeness).
    let pibt_runs = if seed % 2 == 1 { 10 } else { 1 };
    let scatter = seed % 4 >= 2;
    let swap = seed % 8 >= 4;
    let limits = Limits {
        expansions: Some(2_000_000),
        ..Limits::default()
    };
    let lattice = LatticeSpec::new(world, 1.0, Sample::Center, 1.0);
    let settings = Lacam {
        lattice,
        refine,
        pibt_runs,
        scatter,
        swap,
    };
    plan(&team_task(world, agents, limits, seed), &settings)
}

/// The least sum of loss over the joint configurations (Dijkstra), or
/// `None` when the goal configuration cannot be reached.
fn joint_least_loss(world: &World, agents: &[Agent]) -> Option<u64> {
    let g = TeamGrid::new(world, &RobotShape::Point, 1.0, &Validator::new(world)).unwrap();
    let n = agents.len();
    let starts: Vec<usize> = agents.iter().map(|a| g.node(a.start).unwrap()).collect();
    let goals: Vec<usize> = agents.iter().map(|a| g.node(a.goal).unwrap()).collect();
    let mut best: HashMap<Vec<usize>, u64> = HashMap::from([(starts.clone(), 0)]);
    let mut heap = BinaryHeap::from([Reverse((0u64, starts))]);
    while let Some(Reverse((d, pos))) = heap.pop() {
        if best.get(&pos).is_some_and(|&b| b < d) {
            continue;
        }
        if pos == goals {
            return Some(d);
        }
        let everyone: Vec<usize> = (0..n).collect();
        for next in joint_steps(&g, &pos, &everyone) {
            let cost = d + (0..n)
                .filter(|&a| pos[a] != goals[a] || next[a] != goals[a])
                .count() as u64;
            if best.get(&next).is_none_or(|&b| cost < b) {
                best.insert(next.clone(), cost);
                heap.push(Reverse((cost, next)));
            }
        }
    }
    None
}

fn loss_of(out: &PlanOutcome) -> f64 {
    match out.extra.get("sum_of_loss") {
        Some(MetricValue::Num(x)) => *x,
        other => panic!("{other:?}"),
    }
}

fn exhausted(out: &PlanOutcome) -> bool {
    out.extra.get("exhausted") == Some(&MetricValue::Bool(true))
}

#[test]
fn lacam_is_complete_and_refined_it_is_optimal_in_sum_of_loss() {
    let (mut solved, mut none) = (0, 0);
    for seed in 0..300u64 {
        let (world, agents) = random_case(seed, 2 + (seed % 2) as usize);
        let optimum = joint_least_loss(&world, &agents);
        let first = run(&world, &agents, false, seed);
        let refined = run(&world, &agents, true, seed);
        assert!(!first.gave_up && !refined.gave_up, "seed {seed}: a limit");
        match optimum {
            Some(best) => {
                solved += 1;
                for out in [&first, &refined] {
                    let paths = out
                        .agents
                        .as_ref()
                        .unwrap_or_else(|| panic!("seed {seed}: none found, optimum {best}"));
                    let g = TeamGrid::new(&world, &RobotShape::Point, 1.0, &Validator::new(&world))
                        .unwrap();
                    let ends: Vec<(Point, Point)> = agents.iter().map(|a| (a.start, a.goal)).collect();
                    validate_team(&g, &ends, paths).unwrap_or_else(|e| panic!("seed {seed}: {e:?}"));
                    assert!(loss_of(out) >= best as f64, "seed {seed}");
                }
                assert!(exhausted(&refined), "seed {seed}");
                assert_eq!(loss_of(&refined), best as f64, "seed {seed}");
            }
            None => {
                none += 1;
                for out in [&first, &refined] {
                    assert!(out.agents.is_none(), "seed {seed}");
                    assert!(exhausted(out), "seed {seed}: {:?}", out.notes);
                }
            }
        }
    }
    assert!(solved > 150 && none > 5, "{solved} solved, {none} without a solution");
}

#[test]
fn the_same_seed_gives_the_same_solution() {
    let (world, agents) = random_case(7, 3);
    let a = run(&world, &agents, false, 11);
    let b = run(&world, &agents, false, 11);
    assert_eq!(a.agents, b.agents);
}
