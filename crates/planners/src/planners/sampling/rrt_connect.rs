//! `rrt_connect` (Kuffner & LaValle), SPEC 3.7: two trees, rooted at the
//! start and at the goal, take turns. Each iteration draws one sample; the
//! tree whose turn it is extends its nearest state towards the sample by at
//! most `range` (when that motion is free), and the other tree then grows
//! greedily towards the new state, `range` at a time, until it reaches it
//! (a solution) or a motion is blocked.
//!
//! The goal tree's motions run towards the goal in the path, so they are
//! checked in that direction (from the new state to its parent). A greedy
//! connection adds at most as many states as its length over `range`, and
//! stops at the state cap and the time limit too. With `stop limit` the
//! run keeps the first solution and goes on to the limit (the trees grow,
//! the solution does not improve: RRT-Connect is not an optimising
//! planner).

use crate::contract::PlanArgs;
use crate::contract::schema::RobotKind;
use crate::contract::{Planner, Settings};
use crate::geometry::Config;
use crate::geometry::motion::NewEnd;

use super::nn::KdTree;
use super::{
    Algorithm, DrawnEdge, Ended, Grown, LIMITS, METRICS, RANGE, ROTATE, Run, SAMPLER, SIMPLIFY,
    STOP_FIRST, TURN_COST, keep_drawn,
};

/// `rrt_connect` in the registry.
pub static PLANNER: Planner = Planner {
    kind: "rrt_connect",
    summary: "Kuffner & LaValle's RRT-Connect: two trees, greedily connected (default `limit iterations 200000`)",
    robots: &[
        RobotKind::Point,
        RobotKind::Disk,
        RobotKind::Polygon,
        RobotKind::Car,
    ],
    params: &[RANGE, TURN_COST, SAMPLER, STOP_FIRST, SIMPLIFY, ROTATE],
    metrics: METRICS,
    limits: LIMITS,
    needs_goal: true,
    randomized: true,
    grids: true,
    time: false,
    check,
};

fn check(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    super::check(args, Algorithm::RrtConnect)
}

/// One of the two trees.
struct Tree {
    states: Vec<Config>,
    parent: Vec<u32>,
    index: KdTree,
    /// Rooted at the goal: its motions run from child to parent.
    towards_root: bool,
}

impl Tree {
    fn new(run: &Run<'_>, root: Config, towards_root: bool) -> Self {
        let mut index = run.index();
        index.insert(run.space.key(root));
        Tree {
            states: vec![root],
            parent: vec![u32::MAX],
            index,
            towards_root,
        }
    }

    /// The state nearest to `q` in the direction the tree's motions run
    /// (from the state for the start's tree, to it for the goal's) and its
    /// squared distance.
    fn nearest(&mut self, run: &Run<'_>, q: Config) -> Option<(usize, f64)> {
        let states = &self.states;
        run.nearest(&mut self.index, |i| states[i], q, !self.towards_root)
    }

    /// Root to `i`.
    fn path_to(&self, i: usize) -> Vec<Config> {
        let mut path = vec![self.states[i]];
        let mut cur = self.parent[i];
        while cur != u32::MAX {
            path.push(self.states[cur as usize]);
            cur = self.parent[cur as usize];
        }
        path.reverse();
        path
    }
}

/// What one step towards a target did.
enum Step {
    /// Added this state, the target itself.
    Reached(usize),
    /// Added this state, short of the target.
    Advanced(usize),
    Trapped,
}

/// Extends `tree` from its state `from` towards `target` by at most
/// `range`, when that motion is free.
fn step(
    run: &mut Run<'_>,
    tree: &mut Tree,
    from: usize,
    target: Config,
    iteration: u64,
    drawn: &mut Vec<DrawnEdge>,
) -> Step {
    let a = tree.states[from];
    let range = run.settings.range;
    let new = if tree.towards_root {
        run.space.steer_back(target, a, range)
    } else {
        run.space.steer(a, target, range)
    };
    // A step that goes nowhere (a steering length that overflows, or a
    // range below the coordinates' resolution) adds nothing: the state
    // would be its parent again, and the connection would repeat it.
    if new == a {
        return Step::Trapped;
    }
    let free = if tree.towards_root {
        run.extension_free(new, a, NewEnd::Start)
    } else {
        run.extension_free(a, new, NewEnd::End)
    };
    if !free {
        return Step::Trapped;
    }
    let i = tree.states.len();
    tree.states.push(new);
    tree.parent.push(from as u32);
    tree.index.insert(run.space.key(new));
    if run.task.draw {
        keep_drawn(
            drawn,
            DrawnEdge {
                a,
                b: new,
                iteration,
            },
        );
    }
    if new == target {
        Step::Reached(i)
    } else {
        Step::Advanced(i)
    }
}

/// Grows the two trees (see the module documentation).
pub fn grow(run: &mut Run<'_>) -> Grown {
    let stop_first = run.settings.stop == super::Stop::First;
    let mut trees = [
        Tree::new(run, run.start, false),
        Tree::new(run, run.goal, true),
    ];
    let mut drawn = Vec::new();
    let mut path: Option<Vec<Config>> = None;
    let (mut first_iteration, mut first_cost) = (None, None);
    let mut iteration = 0;
    let ended = 'grow: loop {
        let states = trees[0].states.len() + trees[1].states.len();
        if let Some(why) = run.should_stop(iteration + 1, states) {
            break why;
        }
        iteration += 1;
        let sample = run.sample();
        // Tree `a` extends on odd iterations from the start, on even ones
        // from the goal; tree `b` connects.
        let a = usize::from(iteration % 2 == 0);
        let b = 1 - a;
        let Some((nearest, d2)) = trees[a].nearest(run, sample) else {
            continue;
        };
        if d2 == 0.0 {
            continue;
        }
        let new_a = match step(run, &mut trees[a], nearest, sample, iteration, &mut drawn) {
            Step::Trapped => continue,
            Step::Reached(i) | Step::Advanced(i) => i,
        };
        let target = trees[a].states[new_a];
        if path.is_some() {
            continue; // `stop limit` after a solution: the trees just grow
        }
        let Some((mut from, d2)) = trees[b].nearest(run, target) else {
            continue;
        };
        let meet = if d2 == 0.0 {
            Some(from)
        } else {
            let mut steps = 0;
            loop {
                steps += 1;
                let states = trees[0].states.len() + trees[1].states.len();
                if let Some(why) = run.should_stop_within(steps, states) {
                    break 'grow why;
                }
                match step(run, &mut trees[b], from, target, iteration, &mut drawn) {
                    Step::Trapped => break None,
                    Step::Reached(i) => break Some(i),
                    Step::Advanced(i) => from = i,
                }
            }
        };
        let Some(meet_b) = meet else {
            continue;
        };
        // Start tree to the meeting state, then down the goal tree.
        let (s, s_node, g, g_node) = if a == 0 {
            (0, new_a, 1, meet_b)
        } else {
            (0, meet_b, 1, new_a)
        };
        let mut p = trees[s].path_to(s_node);
        let mut down = trees[g].path_to(g_node);
        down.reverse();
        p.extend(down.into_iter().skip(1));
        let p = run.exact_ends(p);
        first_iteration = Some(iteration);
        first_cost = Some(run.cost(&p));
        path = Some(p);
        if stop_first {
            break Ended::Solved;
        }
    };
    let states = trees[0].states.len() + trees[1].states.len();
    Grown {
        path,
        iterations: iteration,
        ended,
        first_iteration,
        first_cost,
        states,
        edges: states - 2,
        drawn,
        entity: "tree",
    }
}
