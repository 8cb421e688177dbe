use proptest::prelude::*;

use super::*;
use crate::fixtures::{grid, world_in};
use crate::{Aabb, RobotShape};

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

/// A 5 × 3 map, the middle row a corridor with one bay above its centre.
fn corridor() -> TeamGrid {
    let rows = ["##.##", ".....", "#####"];
    let world = world_in(
        Aabb::from_corners(p(0.0, 0.0), p(5.0, 3.0)),
        vec![grid(1.0, p(0.0, 0.0), &rows)],
    );
    TeamGrid::new(&world, &RobotShape::Point, 1.0, &Validator::new(&world)).unwrap()
}

fn open(n: usize) -> TeamGrid {
    let world = world_in(
        Aabb::from_corners(p(0.0, 0.0), p(n as f64, n as f64)),
        vec![],
    );
    TeamGrid::new(&world, &RobotShape::Point, 1.0, &Validator::new(&world)).unwrap()
}

fn pts(v: &[(f64, f64)]) -> Vec<Point> {
    v.iter().map(|&(x, y)| p(x, y)).collect()
}

#[test]
fn the_referee_reads_the_map() {
    let g = corridor();
    assert_eq!((g.nx, g.ny), (5, 3));
    // Row 0 of the map is the top: y = 2.5.
    assert!(g.is_free(g.node(p(2.5, 2.5)).unwrap()));
    assert!(!g.is_free(g.node(p(0.5, 2.5)).unwrap()));
    assert!(g.is_free(g.node(p(0.5, 1.5)).unwrap()));
    assert!(!g.is_free(g.node(p(2.5, 0.5)).unwrap()));
    assert_eq!(g.node(p(2.4, 2.5)), None);
    assert_eq!(g.node(p(5.5, 1.5)), None);
    let d = g.distances_to(g.node(p(4.5, 1.5)).unwrap());
    assert_eq!(d[g.node(p(0.5, 1.5)).unwrap()], 4);
    assert_eq!(d[g.node(p(2.5, 2.5)).unwrap()], 3);
    assert_eq!(d[g.node(p(0.5, 0.5)).unwrap()], u32::MAX);
}

#[test]
fn a_swap_through_the_bay_passes_and_costs_are_last_arrivals() {
    let g = corridor();
    let ends = [(p(0.5, 1.5), p(4.5, 1.5)), (p(4.5, 1.5), p(0.5, 1.5))];
    // Agent 0 steps into the bay while agent 1 passes below it.
    let a = pts(&[
        (0.5, 1.5),
        (1.5, 1.5),
        (2.5, 1.5),
        (2.5, 2.5),
        (2.5, 2.5),
        (2.5, 1.5),
        (3.5, 1.5),
        (4.5, 1.5),
    ]);
    let b = pts(&[
        (4.5, 1.5),
        (3.5, 1.5),
        (3.5, 1.5),
        (3.5, 1.5),
        (2.5, 1.5),
        (1.5, 1.5),
        (0.5, 1.5),
    ]);
    assert_eq!(
        validate_team(&g, &ends, &[a.clone(), b.clone()]),
        Ok(vec![7, 6])
    );
    // Without the bay they meet.
    let a2 = pts(&[(0.5, 1.5), (1.5, 1.5), (2.5, 1.5), (3.5, 1.5), (4.5, 1.5)]);
    let e = validate_team(&g, &ends, &[a2, b.clone()]).unwrap_err();
    assert_eq!(e.other, Some(1));
    // A swap in one step is an edge conflict.
    let ends2 = [(p(1.5, 1.5), p(2.5, 1.5)), (p(2.5, 1.5), p(1.5, 1.5))];
    let e = validate_team(
        &g,
        &ends2,
        &[
            pts(&[(1.5, 1.5), (2.5, 1.5)]),
            pts(&[(2.5, 1.5), (1.5, 1.5)]),
        ],
    )
    .unwrap_err();
    assert!(e.reason.contains("swap"), "{}", e.reason);
    // An agent parked at its goal blocks those who pass later.
    let ends3 = [(p(2.5, 1.5), p(2.5, 1.5)), (p(1.5, 1.5), p(3.5, 1.5))];
    let e = validate_team(
        &g,
        &ends3,
        &[
            pts(&[(2.5, 1.5)]),
            pts(&[(1.5, 1.5), (2.5, 1.5), (3.5, 1.5)]),
        ],
    )
    .unwrap_err();
    assert_eq!((e.step, e.agent, e.other), (1, 0, Some(1)));
}

#[test]
fn paths_that_break_the_rules_alone_are_refused() {
    let g = corridor();
    let ends = [(p(0.5, 1.5), p(2.5, 1.5))];
    let bad = [
        pts(&[(0.5, 1.5), (2.5, 1.5)]),             // a jump
        pts(&[(0.5, 1.5), (0.5, 2.5), (1.5, 1.5)]), // onto a wall
        pts(&[(0.5, 1.5), (1.0, 1.5), (2.5, 1.5)]), // off the lattice
        pts(&[(1.5, 1.5), (2.5, 1.5)]),             // not from its start
        pts(&[(0.5, 1.5), (1.5, 1.5)]),             // not to its goal
        pts(&[(0.5, 1.5), (1.5, 2.5), (2.5, 1.5)]), // diagonal, through walls
        vec![],
    ];
    for path in bad {
        assert!(
            validate_team(&g, &ends, std::slice::from_ref(&path)).is_err(),
            "{path:?}"
        );
    }
    assert_eq!(
        agent_cost(&pts(&[(0.5, 1.5), (1.5, 1.5), (2.5, 1.5), (2.5, 1.5)])),
        2
    );
    assert_eq!(agent_cost(&pts(&[(2.5, 1.5), (1.5, 1.5), (2.5, 1.5)])), 2);
    assert_eq!(agent_cost(&pts(&[(2.5, 1.5)])), 0);
    // Within 1e-9 of a cell, a point is the lattice point (a start the
    // fuzzer moved by 1e-9 with the bounds).
    let near = [(p(0.5 + 4e-10, 1.5), p(2.5, 1.5 - 4e-10))];
    let path = pts(&[(0.5, 1.5), (1.5, 1.5), (2.5, 1.5)]);
    assert!(validate_team(&g, &near, std::slice::from_ref(&path)).is_ok());
}

/// An independent statement of grid semantics: every pair of agents at
/// every step, positions held after a path ends.
fn conflicts(paths: &[Vec<Point>]) -> bool {
    let horizon = paths.iter().map(Vec::len).max().unwrap_or(0);
    let at = |a: &Vec<Point>, t: usize| a[t.min(a.len() - 1)];
    for t in 0..horizon {
        for i in 0..paths.len() {
            for j in i + 1..paths.len() {
                if at(&paths[i], t) == at(&paths[j], t) {
                    return true;
                }
                if t > 0
                    && at(&paths[i], t) == at(&paths[j], t - 1)
                    && at(&paths[j], t) == at(&paths[i], t - 1)
                    && at(&paths[i], t) != at(&paths[i], t - 1)
                {
                    return true;
                }
            }
        }
    }
    false
}

/// Random walks of 2–5 agents on an open 4 × 4 grid, each step a wait or a
/// move to a neighbour inside the grid.
fn walks() -> impl Strategy<Value = Vec<Vec<Point>>> {
    let walk = (0usize..16, prop::collection::vec(0u8..5, 0..8)).prop_map(|(s, steps)| {
        let (mut i, mut j) = ((s % 4) as i32, (s / 4) as i32);
        let mut path = vec![p(i as f64 + 0.5, j as f64 + 0.5)];
        for d in steps {
            let (di, dj) = [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)][d as usize];
            if (0..4).contains(&(i + di)) && (0..4).contains(&(j + dj)) {
                i += di;
                j += dj;
            }
            path.push(p(i as f64 + 0.5, j as f64 + 0.5));
        }
        path
    });
    prop::collection::vec(walk, 2..6)
}

/// Walks of 1–4 agents on an open 4 × 4 grid, agent k confined to row k
/// (so they never conflict).
fn row_walks() -> impl Strategy<Value = Vec<Vec<Point>>> {
    let row = (0usize..4, prop::collection::vec(0u8..3, 0..8));
    prop::collection::vec(row, 1..5).prop_map(|rows| {
        rows.into_iter()
            .enumerate()
            .map(|(k, (s, steps))| {
                let mut i = s as i32;
                let y = k as f64 + 0.5;
                let mut path = vec![p(i as f64 + 0.5, y)];
                for d in steps {
                    let di = [0, 1, -1][d as usize];
                    if (0..4).contains(&(i + di)) {
                        i += di;
                    }
                    path.push(p(i as f64 + 0.5, y));
                }
                path
            })
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// The referee accepts exactly the walks without a conflict; every
    /// conflict (planted by chance in most of these crowded walks) is
    /// caught.
    #[test]
    fn the_referee_agrees_with_pairwise_checking(paths in walks()) {
        let g = open(4);
        let ends: Vec<(Point, Point)> = paths.iter().map(|w| (w[0], *w.last().unwrap())).collect();
        let verdict = validate_team(&g, &ends, &paths);
        prop_assert_eq!(verdict.is_err(), conflicts(&paths), "{:?}", verdict);
        if let Ok(costs) = verdict {
            prop_assert_eq!(costs, paths.iter().map(|w| agent_cost(w)).collect::<Vec<_>>());
        }
    }

    /// A conflict planted into a valid solution is always found: a new
    /// agent waits where agent 0 moves to at some step and steps into the
    /// point agent 0 leaves, in the same step (a swap), then stays there.
    #[test]
    fn a_planted_swap_is_rejected(paths in row_walks(), pick in 0usize..1000) {
        let g = open(4);
        let ends: Vec<(Point, Point)> = paths.iter().map(|w| (w[0], *w.last().unwrap())).collect();
        prop_assert!(validate_team(&g, &ends, &paths).is_ok());
        let a = &paths[0];
        let moves: Vec<usize> = (0..a.len() - 1).filter(|&t| a[t] != a[t + 1]).collect();
        prop_assume!(!moves.is_empty());
        let t = moves[pick % moves.len()];
        let mut planted = paths.clone();
        let mut c = vec![a[t + 1]; t + 1];
        c.push(a[t]);
        planted.push(c);
        let ends: Vec<(Point, Point)> = planted.iter().map(|w| (w[0], *w.last().unwrap())).collect();
        prop_assert!(conflicts(&planted));
        prop_assert!(validate_team(&g, &ends, &planted).is_err());
    }
}

/// Continuous teams: two disks crossing one point at once collide (the
/// referee names the other agent); one of them a second later does not;
/// an agent parked on the other's way is hit after it arrived.
#[test]
fn continuous_agents_are_moving_obstacles_of_each_other() {
    let world = world_in(Aabb::from_corners(p(0.0, 0.0), p(10.0, 10.0)), vec![]);
    let disk = RobotShape::Disk(0.3);
    let names = ["a", "b"];
    let judge = |ends: &[(Point, Point)], points: &[Vec<Point>], times: &[Vec<f64>]| {
        validate_continuous_team(&world, &[], &disk, 1.0, &names, ends, points, times)
    };
    let ends = [(p(1.0, 5.0), p(9.0, 5.0)), (p(5.0, 1.0), p(5.0, 9.0))];
    let points = vec![
        pts(&[(1.0, 5.0), (9.0, 5.0)]),
        pts(&[(5.0, 1.0), (5.0, 9.0)]),
    ];
    let at_once = vec![vec![0.0, 8.0], vec![0.0, 8.0]];
    let e = judge(&ends, &points, &at_once).unwrap_err();
    assert_eq!((e.agent, e.other), (0, Some(1)), "{e:?}");
    // b waits 2 s first: a has passed.
    let staggered_points = vec![
        points[0].clone(),
        pts(&[(5.0, 1.0), (5.0, 1.0), (5.0, 9.0)]),
    ];
    let staggered = vec![vec![0.0, 8.0], vec![0.0, 2.0, 10.0]];
    let arrivals = judge(&ends, &staggered_points, &staggered).unwrap();
    assert_eq!(arrivals, vec![8.0, 10.0]);
    // b parks at (5, 5), on a's way, before a gets there.
    let ends = [(p(1.0, 5.0), p(9.0, 5.0)), (p(5.0, 1.0), p(5.0, 5.0))];
    let parked = vec![points[0].clone(), pts(&[(5.0, 1.0), (5.0, 5.0)])];
    let e = judge(&ends, &parked, &[vec![0.0, 8.0], vec![0.0, 4.0]]).unwrap_err();
    assert_eq!(e.other, Some(1), "{e:?}");
    // Faster than the team's speed.
    let e = judge(&ends, &parked, &[vec![0.0, 4.0], vec![0.0, 4.0]]).unwrap_err();
    assert!(e.reason.contains("faster"), "{e:?}");
}
