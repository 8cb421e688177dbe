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
use crate::planners::mapf::{FastSet, Graph};

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
    run_counted(case, limits, &mut Counts::default())
}

fn run_counted(case: &Case, limits: Limits, counts: &mut Counts) -> PlanOutcome {
    let spec = LatticeSpec::new(&case.world, 1.0, Sample::Center, 1.0);
    plan_counted(&team_task(&case.world, &case.agents, limits, 0), &Cbs { lattice: spec }, counts)
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

/// `cbs` on `case` against the joint optimum: the same sum of costs, a
/// solution the referee accepts, none where none exists. Whether the team
/// has a solution. With `stopped`, a run stopped by its limit (200,000
/// expansions) is counted there instead of failing.
fn agrees_with_the_joint_optimum(seed: u64, case: &Case, counts: &mut Counts, stopped: Option<&mut usize>) -> bool {
    let optimum = joint_optimum(case);
    let out = run_counted(
        case,
        Limits {
            expansions: Some(200_000),
            ..Limits::default()
        },
        counts,
    );
    match optimum {
        Some(_) if out.agents.is_none() && out.gave_up && stopped.is_some() => {
            *stopped.expect("a count") += 1;
            true
        }
        Some(soc) => {
            let paths = out.agents.as_ref().unwrap_or_else(|| {
                panic!("seed {seed}: no solution, joint optimum {soc}: {:?}", out.notes)
            });
            assert_eq!(out.cost, Some(soc as f64), "seed {seed}");
            let g = TeamGrid::new(&case.world, &RobotShape::Point, 1.0, &Validator::new(&case.world)).unwrap();
            let ends: Vec<(Point, Point)> = case.agents.iter().map(|a| (a.start, a.goal)).collect();
            let costs = validate_team(&g, &ends, paths).unwrap_or_else(|e| panic!("seed {seed}: {e:?}"));
            assert_eq!(costs.iter().sum::<usize>() as u64, soc, "seed {seed}");
            true
        }
        None => {
            assert!(out.agents.is_none(), "seed {seed}: a solution where none exists");
            false
        }
    }
}

/// An empty floor of 5–8 cells a side crossed by two agents, one from the
/// left side to the right, one from the bottom to the top, both going up
/// and right (whose shortest paths all meet: a rectangle), and now and
/// then a third agent anywhere.
fn crossing_case(seed: u64) -> Case {
    let mut rng = crate::geometry::rng::SplitMix64::new(seed);
    let mut below = |n: usize| (rng.next_u64() % n as u64) as usize;
    let (w, h) = (5 + below(4), 5 + below(4));
    let rows: Vec<String> = (0..h).map(|_| ".".repeat(w)).collect();
    let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
    let world = world_in(
        Aabb::from_corners(p(0.0, 0.0), p(w as f64, h as f64)),
        vec![grid(1.0, p(0.0, 0.0), &refs)],
    );
    let cell = |x: usize, y: usize| p(x as f64 + 0.5, y as f64 + 0.5);
    let agent = |name: &str, start: Point, goal: Point| Agent { name: name.into(), start, goal, span: Span::default() };
    let (r1, c1) = (below(h - 1), below(w - 1));
    let mut agents = vec![
        agent("a", cell(0, r1), cell(w - 1, r1 + 1 + below(h - 1 - r1))),
        agent("b", cell(c1, 0), cell(c1 + 1 + below(w - 1 - c1), h - 1)),
    ];
    if w * h <= 36 && below(2) == 0 {
        let (start, goal) = (cell(below(w), below(h)), cell(below(w), below(h)));
        if agents.iter().all(|a| a.start != start && a.goal != goal) {
            agents.push(agent("c", start, goal));
        }
    }
    if agents[0].start == agents[1].start || agents[0].goal == agents[1].goal {
        agents.truncate(1);
    }
    Case { world, w, h, agents }
}

/// Open floors, where agents cross in open space (rectangle symmetry) and
/// pass others resting at their goals (target symmetry): the symmetry
/// splits keep every optimum, and they are made.
#[test]
fn symmetry_reasoning_keeps_the_optimum_on_open_floors() {
    let mut counts = Counts::default();
    for seed in 0..300u64 {
        let case = if seed % 3 == 2 {
            let (world, agents) = random_team(seed, 3, 4, 2, 12);
            let (w, h) = (world.bounds.width() as usize, world.bounds.height() as usize);
            Case { world, w, h, agents }
        } else {
            crossing_case(seed)
        };
        agrees_with_the_joint_optimum(seed, &case, &mut counts, None);
    }
    eprintln!("{counts:?}");
    assert!(
        counts.rectangle >= 10 && counts.target >= 10 && counts.bypasses >= 1,
        "too few symmetry splits to test them: {counts:?}"
    );
}

#[test]
fn cbs_matches_the_joint_optimum() {
    let (mut solved, mut unsolvable) = (0, 0);
    let mut counts = Counts::default();
    for seed in 0..300u64 {
        let case = random_case(seed, 2 + (seed % 2) as usize);
        let optimum = joint_optimum(&case);
        let limits = Limits {
            expansions: Some(200_000),
            ..Limits::default()
        };
        let out = run_counted(&case, limits, &mut counts);
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
    eprintln!("{counts:?}");
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

/// The MAPF graph of an empty `w` × `w` floor (point `(i, j)` is node
/// `j·w + i`).
fn empty_floor(w: usize) -> Graph {
    let side = w as f64;
    let rows = vec![".".repeat(w); w];
    let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
    let world = world_in(Aabb::from_corners(p(0.0, 0.0), p(side, side)), vec![grid(1.0, p(0.0, 0.0), &refs)]);
    let one = vec![Agent { name: "a".into(), start: p(0.5, 0.5), goal: p(side - 0.5, side - 0.5), span: Span::default() }];
    let task = team_task(&world, &one, Limits::default(), 0);
    let spec = LatticeSpec::new(&world, 1.0, Sample::Center, 1.0);
    Graph::build(&task, spec, &Deadline::start(&task.limits)).expect("an empty floor")
}

/// Every path from `s` to `v` that moves Manhattan-optimally
/// (each step nearer), on a grid `w` wide.
fn staircases(s: (i64, i64), v: (i64, i64), w: i64) -> Vec<Vec<Node>> {
    if s == v {
        return vec![vec![(s.1 * w + s.0) as Node]];
    }
    let mut out = Vec::new();
    for next in [(s.0 + (v.0 - s.0).signum(), s.1), (s.0, s.1 + (v.1 - s.1).signum())] {
        if next != s {
            for mut rest in staircases(next, v, w) {
                rest.insert(0, (s.1 * w + s.0) as Node);
                out.push(rest);
            }
        }
    }
    out
}

/// The theorem the rectangle split rests on: any path of one agent and any
/// path of the other that both reach their barriers (a barrier cell at its
/// step) conflict. Checked by enumeration on hundreds of rectangle splits
/// of random crossing paths on an empty 8 × 8 floor: each barrier cell's
/// step is its Manhattan distance from the agent's start, so the paths
/// that reach it are the staircases from the start, and every pair of
/// them conflicts by then.
#[test]
fn any_two_paths_across_their_barriers_conflict() {
    let w = 8i64;
    let graph = empty_floor(8);
    let xy = |v: Node| ((v as i64) % w, (v as i64) / w);
    let mut rng = crate::geometry::rng::SplitMix64::new(7);
    let (mut splits, mut pairs) = (0, 0u64);
    for _ in 0..40_000 {
        let mut cell = || ((rng.next_u64() % 8) as i64, (rng.next_u64() % 8) as i64);
        let ends = [cell(), cell(), cell(), cell()];
        let choices = (staircases(ends[0], ends[1], w), staircases(ends[2], ends[3], w));
        let pick = rng.next_u64() as usize;
        let (pa, pb) = (&choices.0[pick % choices.0.len()], &choices.1[(pick >> 20) % choices.1.len()]);
        // Only splits of a vertex conflict before either rests, as `cbs` asks.
        let meet = (0..pa.len().min(pb.len()) - 1).find(|&t| pa[t] == pb[t]);
        if meet.is_none() {
            continue;
        }
        let paths = vec![Arc::new(pa.clone()), Arc::new(pb.clone())];
        let Some((b1, b2, _)) = symmetry::rectangle(&graph, &paths, 0, 1) else {
            continue;
        };
        splits += 1;
        let reach = |barrier: &[Constraint], s: (i64, i64)| -> Vec<Vec<Node>> {
            barrier
                .iter()
                .flat_map(|c| match c.rule {
                    Rule::Vertex { v, t } => {
                        assert_eq!(t as i64, (xy(v).0 - s.0).abs() + (xy(v).1 - s.1).abs(), "{c:?}");
                        staircases(s, xy(v), w)
                    }
                    _ => panic!("a barrier is vertex constraints: {c:?}"),
                })
                .collect()
        };
        for q1 in reach(&b1, ends[0]) {
            for q2 in reach(&b2, ends[2]) {
                pairs += 1;
                let k = q1.len().min(q2.len());
                let vertex = (0..k).any(|t| q1[t] == q2[t]);
                let edge = (1..k).any(|t| q1[t] == q2[t - 1] && q1[t - 1] == q2[t]);
                assert!(vertex || edge, "{ends:?}: {q1:?} and {q2:?} cross their barriers without meeting");
            }
        }
    }
    assert!(splits >= 200, "{splits} rectangle splits");
    eprintln!("{splits} splits, {pairs} pairs of paths");
}

/// The pair test of the WDG heuristic: two agents crossing the centre of a
/// 3 × 3 floor at one step always meet (dependent); when one of them may
/// also wait a step first, they need not (independent); nor when their
/// only paths swap places.
#[test]
fn joint_mdds_tell_dependent_pairs() {
    let graph = empty_floor(3);
    let n = |x: u32, y: u32| y * 3 + x;
    // Left to right through the centre, bottom to top through it.
    let across = vec![vec![n(0, 1)], vec![n(1, 1)], vec![n(2, 1)]];
    let up = vec![vec![n(1, 0)], vec![n(1, 1)], vec![n(1, 2)]];
    assert!(tree::dependent(&graph, &across, &up));
    // Bottom to top with a step to spare: wait first, or step aside.
    let up_later = vec![vec![n(1, 0)], vec![n(1, 0), n(1, 1)], vec![n(1, 1)], vec![n(1, 2)]];
    assert!(!tree::dependent(&graph, &across, &up_later));
    // Two agents swapping neighbouring cells in one step.
    let right = vec![vec![n(0, 0)], vec![n(1, 0)]];
    let left = vec![vec![n(1, 0)], vec![n(0, 0)]];
    assert!(tree::dependent(&graph, &right, &left));
    // An agent resting at its goal on the other's only way.
    let rests = vec![vec![n(1, 1)]];
    assert!(tree::dependent(&graph, &rests, &across));
}

/// The MAPF graph of a random map `min` to `min + 2` cells a side, each
/// cell a wall with chance 1/`wall_one_in`, for two agents (`None` when
/// it has room for fewer).
fn walled_pair(seed: u64, min: usize, wall_one_in: u64) -> Option<Graph> {
    let (world, agents) = random_team(seed, 2, min, 3, wall_one_in);
    if agents.len() < 2 {
        return None;
    }
    let task = team_task(&world, &agents, Limits::default(), 0);
    let spec = LatticeSpec::new(&world, 1.0, Sample::Center, 1.0);
    Some(Graph::build(&task, spec, &Deadline::start(&task.limits)).expect("a small map"))
}

/// A random one of the paths an MDD holds.
fn walk_along(graph: &Graph, mdd: &[Vec<Node>], rng: &mut crate::geometry::rng::SplitMix64) -> Vec<Node> {
    let mut path = vec![mdd[0][0]];
    for level in &mdd[1..] {
        let here = *path.last().expect("a start");
        let next: Vec<Node> = level
            .iter()
            .copied()
            .filter(|&x| x == here || graph.neighbours(here).any(|w| w == x))
            .collect();
        path.push(next[(rng.next_u64() % next.len() as u64) as usize]);
    }
    path
}

/// Whether some two walks on `graph` (any moves and waits, shortest or
/// not) from `s1` and `s2` stay apart until one is on its barrier (a cell
/// at its step) while the other can still reach its own: then two paths
/// may break both barriers without meeting by then. A search over every
/// pair of cells, independent of MDDs.
fn barriers_crossed_apart(graph: &Graph, (s1, s2): (Node, Node), c1: &[(Node, u32)], c2: &[(Node, u32)]) -> bool {
    let targets = |c: &[(Node, u32)]| -> Vec<(Vec<u32>, u32)> { c.iter().map(|&(v, t)| (graph.distances_to(v), t)).collect() };
    let (d1, d2) = (targets(c1), targets(c2));
    let can_reach = |d: &[(Vec<u32>, u32)], y: Node, t: u32| d.iter().any(|(dist, at)| *at >= t && dist[y as usize] <= at - t);
    let last = c1.iter().chain(c2).map(|&(_, t)| t).max().unwrap_or(0);
    let moves = |x: Node| graph.neighbours(x).chain(std::iter::once(x)).collect::<Vec<Node>>();
    let mut here: std::collections::BTreeSet<(Node, Node)> = [(s1, s2)].into();
    for t in 0..=last {
        for &(x, y) in &here {
            if (c1.contains(&(x, t)) && can_reach(&d2, y, t)) || (c2.contains(&(y, t)) && can_reach(&d1, x, t)) {
                return true;
            }
        }
        let mut next = std::collections::BTreeSet::new();
        for &(x, y) in &here {
            for &x2 in &moves(x) {
                for &y2 in &moves(y) {
                    let apart = x2 != y2 && !(x2 == y && y2 == x);
                    if apart && can_reach(&d1, x2, t + 1) && can_reach(&d2, y2, t + 1) {
                        next.insert((x2, y2));
                    }
                }
            }
        }
        here = next;
    }
    false
}

/// Generalised rectangle splits are sound: on thousands of pairs of
/// agents on small maps with walls, at every vertex conflict of two random
/// shortest paths where `cbs` finds one, any two walks that reach their
/// barriers meet by then (checked over all walks, not only the MDDs'),
/// both current paths cross their barriers, and the split's own check
/// ([`overlap::disjunctive`]) never accepts barriers the walks can cross
/// apart — swapped barriers, which walks often can, are its foil.
#[test]
fn any_two_walks_across_generalised_barriers_meet() {
    let mut rng = crate::geometry::rng::SplitMix64::new(43);
    let (mut splits, mut not_manhattan, mut foils_crossed) = (0, 0, 0);
    for seed in 0..6000u64 {
        let Some(graph) = walled_pair(seed, 5, 6) else {
            continue;
        };
        let mut mdds = Vec::new();
        for k in 0..2 {
            let (s, g) = (graph.starts[k], graph.goals[k]);
            let dist = graph.distances_to(g);
            if dist[s as usize] == u32::MAX {
                break;
            }
            let table = low::Table::new(0, g, &[]);
            mdds.push(low::mdd(&graph, &dist, s, g, dist[s as usize] as usize, &table));
        }
        if mdds.len() < 2 {
            continue;
        }
        for _ in 0..4 {
            let (pa, pb) = (walk_along(&graph, &mdds[0], &mut rng), walk_along(&graph, &mdds[1], &mut rng));
            let Some(t) = (1..pa.len().min(pb.len()) - 1).find(|&t| pa[t] == pb[t]) else {
                continue;
            };
            let found = overlap::generalised(&graph, (0, &pa, &mdds[0]), (1, &pb, &mdds[1]), pa[t], t as u32);
            let Some((b1, b2, _)) = found else {
                continue;
            };
            splits += 1;
            let paths = vec![Arc::new(pa.clone()), Arc::new(pb.clone())];
            not_manhattan += usize::from(symmetry::rectangle(&graph, &paths, 0, 1).is_none());
            let cells = |b: &[Constraint], agent: u32| -> Vec<(Node, u32)> {
                b.iter()
                    .map(|c| match c.rule {
                        Rule::Vertex { v, t } if c.agent == agent => (v, t),
                        _ => panic!("a barrier is the agent's vertex constraints: {c:?}"),
                    })
                    .collect()
            };
            let (c1, c2) = (cells(&b1, 0), cells(&b2, 1));
            assert!(c1.iter().any(|&(v, t)| pa[t as usize] == v), "seed {seed}: {pa:?} keeps clear of {c1:?}");
            assert!(c2.iter().any(|&(v, t)| pb[t as usize] == v), "seed {seed}: {pb:?} keeps clear of {c2:?}");
            let ends = (pa[0], pb[0]);
            assert!(
                !barriers_crossed_apart(&graph, ends, &c1, &c2),
                "seed {seed}: walks cross {c1:?} and {c2:?} apart ({pa:?}, {pb:?})"
            );
            // The foil: each agent given the other's barrier.
            let set = |c: &[(Node, u32)]| c.iter().copied().collect::<FastSet<(Node, u32)>>();
            let accepted = overlap::disjunctive(&graph, &mdds[0], &mdds[1], &set(&c2), &set(&c1));
            let crossed = barriers_crossed_apart(&graph, ends, &c2, &c1);
            assert!(!(accepted && crossed), "seed {seed}: the check accepts barriers walks cross apart");
            foils_crossed += usize::from(crossed);
        }
    }
    eprintln!("{splits} splits, {not_manhattan} of paths not Manhattan-optimal, {foils_crossed} foils crossed apart");
    assert!(splits >= 150 && not_manhattan >= 80 && foils_crossed >= 100, "{splits} / {not_manhattan} / {foils_crossed}");
}

/// Pairs of agents on small maps with walls, where shortest paths bend
/// round walls (rectangles come from MDDs) and agents meet head-on in
/// narrow places (pseudo-corridors): `cbs` keeps the joint optimum where
/// it finishes within its limit, and it makes both kinds of split.
#[test]
fn symmetry_reasoning_keeps_the_optimum_on_walled_maps() {
    let (mut counts, mut stopped) = (Counts::default(), 0);
    let runs = 6000u64;
    for seed in 0..runs {
        let (world, agents) = random_team(seed, 2, 5, 3, 5);
        let (w, h) = (world.bounds.width() as usize, world.bounds.height() as usize);
        agrees_with_the_joint_optimum(seed, &Case { world, w, h, agents }, &mut counts, Some(&mut stopped));
    }
    eprintln!("{counts:?}, {stopped} stopped by the limit");
    assert!(counts.corridor >= 20, "too few pseudo-corridor splits to test them: {counts:?}");
    // Two agents that must pass each other in a long corridor take plain
    // CBS exponentially many splits (the corridor symmetry `cbs` does not
    // reason on): a few such maps stop at the limit, no more.
    assert!(stopped * 100 <= runs as usize, "{stopped} of {runs} runs stopped by the limit");
    assert!(counts.generalised >= 20, "too few generalised rectangle splits to test them: {counts:?}");
}

/// Whether some two walks (any moves and waits under each agent's table)
/// from `starts` stay apart until agent 0 has been at `off[0].0` at a step
/// up to `off[0].1` and agent 1 at `off[1].0` at a step up to `off[1].1`.
fn both_broken_apart(graph: &Graph, tables: [&low::Table; 2], starts: [Node; 2], off: [(Node, u32); 2]) -> bool {
    let last = off[0].1.max(off[1].1);
    let broken = |k: usize, x: Node, t: u32| x == off[k].0 && t <= off[k].1;
    if !tables[0].vertex_ok(starts[0], 0) || !tables[1].vertex_ok(starts[1], 0) {
        return false;
    }
    let steps = |k: usize, x: Node, t: u32| -> Vec<Node> {
        graph
            .neighbours(x)
            .chain(std::iter::once(x))
            .filter(|&x2| tables[k].vertex_ok(x2, t + 1) && tables[k].move_ok(x, x2, t + 1))
            .collect()
    };
    let mut here: std::collections::BTreeSet<(Node, Node, bool, bool)> =
        [(starts[0], starts[1], broken(0, starts[0], 0), broken(1, starts[1], 0))].into();
    for t in 0..=last {
        if here.iter().any(|&(_, _, fa, fb)| fa && fb) {
            return true;
        }
        let mut next = std::collections::BTreeSet::new();
        for &(x, y, fa, fb) in &here {
            for x2 in steps(0, x, t) {
                for y2 in steps(1, y, t) {
                    if x2 != y2 && !(x2 == y && y2 == x) {
                        next.insert((x2, y2, fa || broken(0, x2, t + 1), fb || broken(1, y2, t + 1)));
                    }
                }
            }
        }
        here = next;
    }
    false
}

/// Pseudo-corridor splits are sound: on thousands of small maps with
/// walls, random constraints on two agents and a random edge they are to
/// cross head-on, whenever a split is made, no two walks under the agents'
/// constraints break both children's constraints without meeting (checked
/// over all walks). The foil: the same split with both bounds two steps
/// later, which walks often break apart.
#[test]
fn any_two_walks_through_a_pseudo_corridor_meet() {
    let mut rng = crate::geometry::rng::SplitMix64::new(2020);
    let (mut splits, mut foils_broken) = (0, 0);
    for seed in 0..4000u64 {
        let Some(graph) = walled_pair(seed, 4, 5) else {
            continue;
        };
        let n = graph.adj.len() as u64;
        let mut below = |k: u64| rng.next_u64() % k;
        let free: Vec<Node> = (0..n as Node).filter(|&v| graph.free[v as usize]).collect();
        let mut constraints = Vec::new();
        for _ in 0..below(5) {
            let v = free[below(free.len() as u64) as usize];
            let rule = Rule::Vertex { v, t: 1 + below(8) as u32 };
            constraints.push(Constraint { agent: below(2) as u32, rule });
        }
        let x = free[below(free.len() as u64) as usize];
        let Some(y) = graph.neighbours(x).nth(below(4) as usize) else {
            continue;
        };
        let paths = vec![
            Arc::new(vec![graph.starts[0], graph.goals[0]]),
            Arc::new(vec![graph.starts[1], graph.goals[1]]),
        ];
        let node = CtNode {
            constraints: Arc::new(constraints),
            paths,
            cost: 0,
            found: Found::default(),
            h: 0,
            h_known: false,
        };
        let (step_a, step_b) = (1 + below(6) as u32, 1 + below(6) as u32);
        let a = corridor::Crossing { agent: 0, from: x, into: y, step: step_a };
        let b = corridor::Crossing { agent: 1, from: y, into: x, step: step_b };
        let Some([c1, c2]) = corridor::pseudo_corridor(&graph, &node, &a, &b) else {
            continue;
        };
        splits += 1;
        let last = |c: &[Constraint], agent: u32, v: Node| -> u32 {
            let steps: Vec<u32> = c
                .iter()
                .map(|c| match c.rule {
                    Rule::Vertex { v: at, t } if c.agent == agent && at == v => t,
                    _ => panic!("a pseudo-corridor child keeps its agent off one point: {c:?}"),
                })
                .collect();
            assert_eq!(steps, (0..steps.len() as u32).collect::<Vec<_>>(), "every step from 0");
            steps.len() as u32 - 1
        };
        let (l_a, l_b) = (last(&c1, 0, y), last(&c2, 1, x));
        assert!(l_a >= step_a && l_b >= step_b, "seed {seed}: the split keeps a current path");
        let tables = [
            &low::Table::new(0, graph.goals[0], &node.constraints),
            &low::Table::new(1, graph.goals[1], &node.constraints),
        ];
        let starts = [graph.starts[0], graph.starts[1]];
        assert!(
            !both_broken_apart(&graph, tables, starts, [(y, l_a), (x, l_b)]),
            "seed {seed}: walks break both children apart ({x} - {y}, up to {l_a} / {l_b})"
        );
        foils_broken += usize::from(both_broken_apart(&graph, tables, starts, [(y, l_a + 2), (x, l_b + 2)]));
    }
    eprintln!("{splits} pseudo-corridor splits, {foils_broken} foils broken apart");
    assert!(splits >= 200 && foils_broken >= 50, "{splits} / {foils_broken}");
}
