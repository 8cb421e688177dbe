//! `sipp` against an independent brute force: a search over (lattice
//! point, time) in which the robot waits in steps of Δt and moves at full
//! speed, every wait and move judged by the validator's own test on one
//! segment ([`motion_meets`]). On hundreds of random small worlds `sipp`
//! arrives no later than the brute force, finds a trajectory whenever it
//! does, and every trajectory it returns passes the validator in
//! space-time.

use std::collections::{BTreeMap, HashSet};

use super::*;
use crate::contract::Limits;
use crate::geometry::fixtures::{rect, world_in};
use crate::geometry::rng::SplitMix64;
use crate::geometry::timed::{
    After, MovingObstacle, MovingShape, Timed, Waypoint, motion_meets, validate_trajectory,
};
use crate::geometry::validator::{DEFAULT_TOLERANCE, validate_path};
use crate::geometry::{Aabb, Config, RobotShape, World};
use crate::planners::lattice::Sample;

/// A random small world: `w` × `h` unit cells, a few blocked cells, a few
/// moving disks, squares (either way round) and L shapes on random routes, a point or disk robot, and a
/// start and goal on free cell centres.
struct Case {
    world: World,
    moving: Vec<MovingObstacle>,
    robot: RobotShape,
    speed: f64,
    start: Config,
    goal: Config,
}

fn random_case(seed: u64) -> Case {
    let mut rng = SplitMix64::new(seed);
    let w = 4 + (rng.next_u64() % 3) as usize;
    let h = 4 + (rng.next_u64() % 3) as usize;
    let mut blocked = HashSet::new();
    for _ in 0..(rng.next_u64() % 4) {
        blocked.insert((rng.next_u64() as usize % w, rng.next_u64() as usize % h));
    }
    let shapes = blocked
        .iter()
        .map(|&(i, j)| rect(i as f64, j as f64, i as f64 + 1.0, j as f64 + 1.0))
        .collect();
    let world = world_in(
        Aabb::from_corners(Point::new(0.0, 0.0), Point::new(w as f64, h as f64)),
        shapes,
    );
    let mut moving = Vec::new();
    for k in 0..1 + rng.next_u64() % 3 {
        let s = rng.range(0.2, 0.5);
        let square = [
            Point::new(-s, -s),
            Point::new(s, -s),
            Point::new(s, s),
            Point::new(-s, s),
        ];
        let shape = match rng.next_u64() % 4 {
            0 => MovingShape::Disk(rng.range(0.2, 0.6)),
            1 => MovingShape::polygon(&square),
            // Clockwise, as the analyzer may give a piece.
            2 => MovingShape::Pieces(vec![square.iter().rev().copied().collect()]),
            // An L, not convex: two pieces.
            _ => MovingShape::polygon(&[
                Point::new(-s, -s),
                Point::new(2.0 * s, -s),
                Point::new(2.0 * s, 0.0),
                Point::new(0.0, 0.0),
                Point::new(0.0, 2.0 * s),
                Point::new(-s, 2.0 * s),
            ]),
        };
        let mut t = rng.range(0.0, 3.0);
        let mut route = Vec::new();
        for _ in 0..2 + rng.next_u64() % 2 {
            route.push(Waypoint {
                t,
                at: Point::new(rng.range(0.0, w as f64), rng.range(0.0, h as f64)),
            });
            t += rng.range(1.0, 6.0);
        }
        moving.push(MovingObstacle {
            name: format!("m{k}"),
            shape,
            route,
            after: if rng.coin() { After::Stay } else { After::Vanish },
        });
    }
    let robot = if rng.coin() {
        RobotShape::Point
    } else {
        RobotShape::Disk(rng.range(0.1, 0.4))
    };
    let speed = [0.5, 1.0, 2.0][rng.next_u64() as usize % 3];
    let mut free_cell = || loop {
        let c = (rng.next_u64() as usize % w, rng.next_u64() as usize % h);
        if !blocked.contains(&c) {
            return Config::new(c.0 as f64 + 0.5, c.1 as f64 + 0.5, 0.0);
        }
    };
    let (start, goal) = (free_cell(), free_cell());
    Case {
        world,
        moving,
        robot,
        speed,
        start,
        goal,
    }
}

fn run_sipp(case: &Case, connect: u8) -> PlanOutcome {
    let settings = Sipp {
        lattice: LatticeSpec::new(&case.world, 1.0, Sample::Center, 1.0),
        connect,
    };
    let task = Task {
        world: &case.world,
        robot: &case.robot,
        start: case.start,
        goal: Some(case.goal),
        limits: Limits::default(),
        seed: 0,
        steering: None,
        draw: false,
        referee: None,
        moving: &case.moving,
        speed: Some(case.speed),
        agents: &[],
    };
    plan(&task, &settings)
}

/// Whether the robot is safe from every moving obstacle going from `a` to
/// `b` (the same point for a wait).
fn safe(case: &Case, a: Timed, b: Timed) -> bool {
    !case
        .moving
        .iter()
        .any(|o| motion_meets(&case.robot, o, a, b))
}

/// The brute force: the earliest arrival among lattice trajectories whose
/// waits are multiples of `dt` (and moves the lattice's, at full speed),
/// up to `horizon` seconds; `None` when none arrives by then to stay.
fn brute_force(case: &Case, connect: usize, dt: f64, horizon: f64) -> Option<f64> {
    let b = case.world.bounds;
    let (w, h) = (b.width().round() as i64, b.height().round() as i64);
    let centre = |(i, j): (i64, i64)| Config::new(i as f64 + 0.5, j as f64 + 0.5, 0.0);
    let statically_free = |a: Config, c: Config| {
        validate_path(&case.world, &case.robot, &[a, c], DEFAULT_TOLERANCE).is_ok()
    };
    let cell_free =
        |c: (i64, i64)| c.0 >= 0 && c.1 >= 0 && c.0 < w && c.1 < h && statically_free(centre(c), centre(c));
    let settled = case
        .moving
        .iter()
        .map(|o| o.settles())
        .fold(0.0, f64::max)
        + 1.0;
    let start = ((case.start.x - 0.5) as i64, (case.start.y - 0.5) as i64);
    let goal = ((case.goal.x - 0.5) as i64, (case.goal.y - 0.5) as i64);
    // Times as multiples of 1e-9 s, in order (a Dijkstra on time alone).
    let key = |t: f64| (t * 1e9).round() as i64;
    let mut frontier: BTreeMap<i64, (f64, Vec<(i64, i64)>)> = BTreeMap::new();
    let mut seen: HashSet<((i64, i64), i64)> = HashSet::new();
    let at = |c: (i64, i64), t: f64| Timed { pose: centre(c), t };
    if !safe(case, at(start, 0.0), at(start, 0.0)) {
        return None;
    }
    frontier.insert(0, (0.0, vec![start]));
    while let Some((_, (t, cells))) = frontier.pop_first() {
        for c in cells {
            if !seen.insert((c, key(t))) {
                continue;
            }
            if c == goal && safe(case, at(c, t), at(c, t.max(settled))) {
                return Some(t);
            }
            let mut push = |to: (i64, i64), t2: f64| {
                if t2 <= horizon {
                    frontier.entry(key(t2)).or_insert((t2, Vec::new())).1.push(to);
                }
            };
            if safe(case, at(c, t), at(c, t + dt)) {
                push(c, t + dt);
            }
            for &(dx, dy) in &crate::planners::grid_lattice::DIRS[..connect] {
                let to = (c.0 + dx, c.1 + dy);
                if !cell_free(to) || !statically_free(centre(c), centre(to)) {
                    continue;
                }
                // No corner cutting, as on `astar`'s lattice.
                if dx != 0 && dy != 0 && !(cell_free((c.0 + dx, c.1)) && cell_free((c.0, c.1 + dy))) {
                    continue;
                }
                let tau = f64::from(((dx * dx + dy * dy) as i32).abs()).sqrt() / case.speed;
                if safe(case, at(c, t), at(to, t + tau)) {
                    push(to, t + tau);
                }
            }
        }
    }
    None
}

/// What `sipp` returned for `case`: its trajectory validated in
/// space-time; its arrival (or `None`).
fn checked_arrival(case: &Case, connect: u8, seed: u64) -> Option<f64> {
    let out = run_sipp(case, connect);
    assert!(!out.gave_up, "seed {seed}: no limit was set");
    let (path, times) = match (out.path, out.times) {
        (Some(p), Some(t)) => (p, t),
        (None, None) => return None,
        other => panic!("seed {seed}: a path without times or times without a path: {other:?}"),
    };
    let trajectory: Vec<Timed> = path
        .iter()
        .zip(&times)
        .map(|(&pose, &t)| Timed { pose, t })
        .collect();
    assert_eq!(
        validate_trajectory(&case.world, &case.moving, &case.robot, case.speed, &trajectory),
        Ok(()),
        "seed {seed}: sipp's trajectory {trajectory:?}"
    );
    times.last().copied()
}

/// On a 4-connected lattice with waits of a quarter of a move, every brute
/// force time is on the grid of Δt: the comparison is exact.
#[test]
fn sipp_arrives_no_later_than_the_brute_force_on_random_worlds_4_connected() {
    let (mut both, mut neither, mut delayed) = (0, 0, 0);
    for seed in 0..300 {
        let case = random_case(seed);
        let tau = 1.0 / case.speed;
        let ours = checked_arrival(&case, 4, seed);
        let brute = brute_force(&case, 4, tau / 4.0, 40.0);
        match (ours, brute) {
            (Some(a), Some(b)) => {
                assert!(a <= b + 1e-7, "seed {seed}: sipp {a} later than brute force {b}");
                both += 1;
                // Without the moving obstacles: did they matter?
                let still = Case {
                    moving: Vec::new(),
                    ..random_case(seed)
                };
                if checked_arrival(&still, 4, seed).is_some_and(|free| a > free + 1e-9) {
                    delayed += 1;
                }
            }
            (None, Some(b)) => panic!("seed {seed}: sipp found nothing, the brute force {b}"),
            (_, None) => neither += 1,
        }
    }
    // The worlds are not all trivial or all hopeless, and in many the
    // moving obstacles make the robot wait or go round.
    assert!(
        both > 150 && neither > 5 && delayed > 50,
        "found by both {both}, not by brute force {neither}, delayed {delayed}"
    );
}

/// On an 8-connected lattice, with a shorter horizon (the brute force's
/// times are sums of two move lengths and the waits).
#[test]
fn sipp_arrives_no_later_than_the_brute_force_on_random_worlds_8_connected() {
    let mut both = 0;
    for seed in 1000..1100 {
        let case = random_case(seed);
        let tau = 1.0 / case.speed;
        let ours = checked_arrival(&case, 8, seed);
        let brute = brute_force(&case, 8, tau / 2.0, 12.0 * tau);
        match (ours, brute) {
            (Some(a), Some(b)) => {
                assert!(a <= b + 1e-7, "seed {seed}: sipp {a} later than brute force {b}");
                both += 1;
            }
            (None, Some(b)) => panic!("seed {seed}: sipp found nothing, the brute force {b}"),
            (_, None) => {}
        }
    }
    assert!(both > 50, "found by both {both}");
}

/// A goal a cart parks on for good is never reached, and a cell sealed off
/// by static walls is unreachable: found false, gave_up false, with a note.
#[test]
fn a_goal_taken_for_good_or_sealed_off_is_not_found_without_giving_up() {
    let mut case = random_case(7);
    case.world = world_in(
        Aabb::from_corners(Point::new(0.0, 0.0), Point::new(6.0, 3.0)),
        vec![rect(3.0, 0.0, 4.0, 3.0)],
    );
    case.robot = RobotShape::Disk(0.3);
    case.start = Config::new(0.5, 1.5, 0.0);
    case.goal = Config::new(2.5, 1.5, 0.0);
    case.moving = vec![MovingObstacle {
        name: "cart".into(),
        shape: MovingShape::Disk(0.4),
        route: vec![
            Waypoint {
                t: 0.0,
                at: Point::new(0.5, 0.5),
            },
            Waypoint {
                t: 5.0,
                at: Point::new(2.5, 1.5),
            },
        ],
        after: After::Stay,
    }];
    let out = run_sipp(&case, 8);
    assert!(out.path.is_none() && !out.gave_up, "{out:?}");
    assert!(
        out.notes.iter().any(|n| n.contains("never safe for good") && n.contains("`cart`")),
        "{:?}",
        out.notes
    );
    // The cart vanishing instead: reached.
    case.moving[0].after = After::Vanish;
    assert!(run_sipp(&case, 8).path.is_some());
    // Beyond the wall: sealed off.
    case.goal = Config::new(5.5, 1.5, 0.0);
    let out = run_sipp(&case, 8);
    assert!(out.path.is_none() && !out.gave_up, "{out:?}");
    assert!(
        out.notes.iter().any(|n| n.contains("no lattice trajectory")),
        "{:?}",
        out.notes
    );
}

/// The fuzzer's case: a goal 5.5e-9 off its lattice point, joined by a
/// move of 5.5e-9 units at t = 17 s. Its duration, rounded, read as a
/// robot faster than its speed; the times are now nudged up by ulps.
#[test]
fn a_last_move_of_nanometres_is_no_faster_than_the_robot() {
    let mut case = random_case(0);
    case.world = world_in(
        Aabb::from_corners(Point::new(0.0, 0.0), Point::new(20.0, 20.0)),
        vec![],
    );
    case.robot = RobotShape::Disk(0.4);
    case.speed = 1.0;
    case.start = Config::new(2.5, 5.5, 0.0);
    case.goal = Config::new(17.5, 5.500_000_005_500_000_5, 0.0);
    case.moving = vec![MovingObstacle {
        name: "door".into(),
        shape: MovingShape::Pieces(vec![vec![
            Point::new(-1.0, -1.0),
            Point::new(1.0, -1.0),
            Point::new(1.0, 1.0),
            Point::new(-1.0, 1.0),
        ]]),
        route: vec![Waypoint {
            t: 10.0,
            at: Point::new(10.0, 5.0),
        }],
        after: After::Stay,
    }];
    let out = run_sipp(&case, 4);
    let trajectory = out.timed().expect("a trajectory");
    validate_trajectory(&case.world, &case.moving, &case.robot, case.speed, &trajectory)
        .expect("valid in space-time");
}
