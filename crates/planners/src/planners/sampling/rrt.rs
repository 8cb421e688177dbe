//! `rrt` (LaValle's rapidly-exploring random tree, goal-biased) and
//! `rrt_star` (Karaman & Frazzoli's RRT*), SPEC 3.7.
//!
//! # RRT
//! Each iteration samples the goal with probability `goal_bias`, else the
//! plan's sampler; the tree state nearest to the sample (in the distance of
//! [`Space::distance`], through the [`KdTree`]) is extended towards it by at
//! most `range`; the new state joins the tree when the motion to it is free.
//! The goal joins the tree like any state (when sampled within `range` of
//! the tree), which ends an `rrt` with `stop first`.
//!
//! # RRT*
//! The new state's parent is chosen among its k nearest
//! (k = ⌈rewire · e · (1 + 1/d) · ln n⌉) as the one through which it is
//! cheapest, trying candidates in order of that cost until a free motion
//! (the nearest's motion is known free); then each of the k whose cost
//! drops by going through the new state is rewired to it when that motion
//! is free, and its subtree's costs follow. Costs are path lengths in the
//! distance. With `informed yes`, once the goal is in the tree, the samples
//! that are not the goal come from the informed set of the current best
//! cost ([`Informed`]). With `stop limit` (the default) the run goes on to
//! the limit and returns the goal's path then.
//!
//! The tree's edges are drawn as `tree/NNNN` on timeline `iteration` (each
//! state at the iteration it joined, with its final parent).

use crate::contract::PlanArgs;
use crate::contract::schema::RobotKind;
use crate::contract::{Planner, Settings};
use crate::geometry::Config;
use crate::geometry::motion::NewEnd;

use super::space::Informed;
use super::{
    Algorithm, DrawnEdge, Ended, GOAL_BIAS, Grown, INFORMED, LIMITS, METRICS, RANGE, REWIRE,
    ROTATE, Run, SAMPLER, SIMPLIFY, STOP_FIRST, STOP_LIMIT, TURN_COST, keep_drawn,
};

/// `rrt` in the registry.
pub static RRT: Planner = Planner {
    kind: "rrt",
    summary: "LaValle's rapidly-exploring random tree, goal-biased (default `limit iterations 200000`)",
    robots: &[
        RobotKind::Point,
        RobotKind::Disk,
        RobotKind::Polygon,
        RobotKind::Car,
    ],
    params: &[
        RANGE, TURN_COST, GOAL_BIAS, SAMPLER, STOP_FIRST, SIMPLIFY, ROTATE,
    ],
    metrics: METRICS,
    limits: LIMITS,
    needs_goal: true,
    randomized: true,
    grids: true,
    time: false,
    check: check_rrt,
};

/// `rrt_star` in the registry.
pub static RRT_STAR: Planner = Planner {
    kind: "rrt_star",
    summary: "Karaman & Frazzoli's asymptotically optimal RRT*, optionally informed (default `limit iterations 200000`)",
    robots: &[
        RobotKind::Point,
        RobotKind::Disk,
        RobotKind::Polygon,
        RobotKind::Car,
    ],
    params: &[
        RANGE, TURN_COST, GOAL_BIAS, SAMPLER, REWIRE, INFORMED, STOP_LIMIT, SIMPLIFY, ROTATE,
    ],
    metrics: METRICS,
    limits: LIMITS,
    needs_goal: true,
    randomized: true,
    grids: true,
    time: false,
    check: check_rrt_star,
};

fn check_rrt(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    super::check(args, Algorithm::Rrt)
}

fn check_rrt_star(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    super::check(args, Algorithm::RrtStar)
}

/// `NONE` as a parent: the root.
const ROOT: u32 = u32::MAX;

/// A tree rooted at the start, with path costs (RRT*).
struct Tree {
    states: Vec<Config>,
    parent: Vec<u32>,
    /// The cost from the root.
    cost: Vec<f64>,
    children: Vec<Vec<u32>>,
    /// The iteration each state joined at.
    joined: Vec<u64>,
}

impl Tree {
    fn add(&mut self, c: Config, parent: u32, cost: f64, iteration: u64) -> usize {
        let i = self.states.len();
        self.states.push(c);
        self.parent.push(parent);
        self.cost.push(cost);
        self.children.push(Vec::new());
        self.joined.push(iteration);
        if parent != ROOT {
            self.children[parent as usize].push(i as u32);
        }
        i
    }

    /// Root to `i`.
    fn path_to(&self, i: usize) -> Vec<Config> {
        let mut path = vec![self.states[i]];
        let mut cur = self.parent[i];
        while cur != ROOT {
            path.push(self.states[cur as usize]);
            cur = self.parent[cur as usize];
        }
        path.reverse();
        path
    }

    /// Makes `new_parent` the parent of `i`, whose cost becomes `cost`; the
    /// costs of its subtree follow.
    fn reparent(&mut self, i: usize, new_parent: usize, cost: f64) {
        let old = self.parent[i];
        if old != ROOT {
            let siblings = &mut self.children[old as usize];
            if let Some(at) = siblings.iter().position(|&c| c as usize == i) {
                siblings.swap_remove(at);
            }
        }
        self.parent[i] = new_parent as u32;
        self.children[new_parent].push(i as u32);
        let delta = cost - self.cost[i];
        let mut stack = vec![i as u32];
        while let Some(v) = stack.pop() {
            self.cost[v as usize] += delta;
            stack.extend_from_slice(&self.children[v as usize]);
        }
    }
}

/// Grows an `rrt` or `rrt_star` tree (see the module documentation).
pub fn grow(run: &mut Run<'_>) -> Grown {
    let star = run.settings.algorithm == Algorithm::RrtStar;
    let stop_first = run.settings.stop == super::Stop::First;
    let range = run.settings.range;
    let goal = run.goal;
    let mut tree = Tree {
        states: Vec::new(),
        parent: Vec::new(),
        cost: Vec::new(),
        children: Vec::new(),
        joined: Vec::new(),
    };
    let mut index = run.index();
    tree.add(run.start, ROOT, 0.0, 0);
    index.insert(run.space.key(run.start));
    let mut goal_node: Option<usize> = None;
    let (mut first_iteration, mut first_cost) = (None, None);
    let mut informed: Option<(f64, Informed)> = None;
    let mut near = Vec::new();
    let mut order: Vec<(f64, u32)> = Vec::new();
    let mut iteration = 0;
    let ended = loop {
        if let Some(why) = run.should_stop(iteration + 1, tree.states.len()) {
            break why;
        }
        iteration += 1;
        let to_goal = run.settings.goal_bias > 0.0 && run.rng.next_f64() < run.settings.goal_bias;
        let sample = if to_goal {
            goal
        } else if let (true, Some(g)) = (run.settings.informed, goal_node) {
            let best = tree.cost[g];
            if informed.as_ref().is_none_or(|(c, _)| *c != best) {
                informed = Some((best, Informed::new(&run.space, run.start, goal, best)));
            }
            let set = informed.as_ref().map(|(_, s)| s);
            match set.and_then(|s| s.sample(&run.space, &mut run.rng)) {
                Some(q) => q,
                None => continue,
            }
        } else {
            run.sample()
        };
        let Some((nearest, d2)) = run.nearest(&mut index, |i| tree.states[i], sample, true) else {
            continue;
        };
        if d2 == 0.0 {
            continue; // already in the tree
        }
        let from = tree.states[nearest];
        let reaches_goal = to_goal && run.space.distance(from, goal) <= range;
        let new = if reaches_goal {
            goal
        } else {
            run.space.steer(from, sample, range)
        };
        // A step that goes nowhere (a steering length that overflows, or a
        // range below the coordinates' resolution) adds nothing.
        if new == from || !run.extension_free(from, new, NewEnd::End) {
            continue;
        }
        let mut parent = nearest;
        let mut cost = tree.cost[nearest] + run.space.distance(from, new);
        if star {
            let k = run.k_star(tree.states.len() + 1);
            run.k_nearest(&mut index, |i| tree.states[i], new, k, true, &mut near);
            // Choose the parent: cheapest first, the first free one. One
            // whose cost and heading change alone reach `cost` could not be
            // chosen, and is not measured.
            order.clear();
            order.extend(near.iter().filter_map(|&(_, i)| {
                let (state, before) = (tree.states[i as usize], tree.cost[i as usize]);
                if before + run.space.turn_bound(state, new) >= cost {
                    return None;
                }
                Some((before + run.space.distance(state, new), i))
            }));
            order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            for &(c, i) in &order {
                if c >= cost {
                    break;
                }
                if run.motion_free(tree.states[i as usize], new) {
                    parent = i as usize;
                    cost = c;
                    break;
                }
            }
        }
        let v = tree.add(new, parent as u32, cost, iteration);
        index.insert(run.space.key(new));
        if star {
            for &(_, i) in &near {
                let i = i as usize;
                if i == parent || i == 0 {
                    continue;
                }
                // Not measured when the heading change alone leaves it no
                // cheaper.
                if cost + run.space.turn_bound(new, tree.states[i]) >= tree.cost[i] {
                    continue;
                }
                let through = cost + run.space.distance(new, tree.states[i]);
                if through < tree.cost[i] && run.motion_free(new, tree.states[i]) {
                    tree.reparent(i, v, through);
                }
            }
        }
        if reaches_goal {
            goal_node = Some(v);
            first_iteration = Some(iteration);
            first_cost = Some(tree.cost[v]);
            if stop_first {
                break Ended::Solved;
            }
        }
    };
    let mut drawn = Vec::new();
    // The tree's edges in the order they joined, only when drawn.
    let mut by_joining: Vec<usize> = if run.task.draw {
        (1..tree.states.len()).collect()
    } else {
        Vec::new()
    };
    by_joining.sort_by_key(|&i| (tree.joined[i], i));
    for i in by_joining {
        let p = tree.parent[i] as usize;
        keep_drawn(
            &mut drawn,
            DrawnEdge {
                a: tree.states[p],
                b: tree.states[i],
                iteration: tree.joined[i],
            },
        );
    }
    let n = tree.states.len();
    Grown {
        path: goal_node.map(|g| run.exact_ends(tree.path_to(g))),
        iterations: iteration,
        ended,
        first_iteration,
        first_cost,
        states: n,
        edges: n - 1,
        drawn,
        entity: "tree",
    }
}
