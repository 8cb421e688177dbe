//! `lacam` (SPEC 3.11): lazy constraints addition search (Okumura, AAAI
//! 2023) with PIBT (Okumura et al., AIJ 2022) as its configuration
//! generator, and with `refine yes` its anytime refinement LaCAM* (IJCAI
//! 2023).
//!
//! The high level searches configurations — every agent's point at once —
//! depth first. A configuration's successors are generated lazily: each
//! high-level node keeps a queue of low-level constraint sets ("agent i
//! goes to v, agent j to w, ..."), grown one agent deeper each time one is
//! taken, and PIBT completes a constraint set into the next configuration
//! (each agent to its best free neighbour by distance to its goal, pushing
//! the agents in its way by priority inheritance). Every constraint set of
//! every configuration is tried before the search gives up on it, so the
//! search is complete: when the high-level search runs out of nodes, no
//! solution exists.
//!
//! With `refine yes` the search goes on after the first solution (LaCAM*):
//! every configuration keeps the cheapest known way to reach it (a
//! Dijkstra update of the explored graph when a cheaper edge turns up),
//! nodes no cheaper than the best solution are pruned, and when the search
//! runs out of nodes the solution is optimal for LaCAM*'s objective, the
//! *sum of loss*: each step an agent is not resting at its goal costs 1
//! (`sum_of_loss`, a lower bound of the sum of costs that equals it unless
//! an agent leaves its goal after reaching it).

use std::any::Any;
use std::collections::{HashMap, VecDeque};

use crate::contract::schema::{MetricSpec, ParamSpec, RobotKind, ValueSpec, Word, YesNo, num};
use crate::contract::{MetricValue, PlanArgs, PlanOutcome, Planner, Settings, Task};
use crate::geometry::rng::SplitMix64;
use crate::planners::deadline::Deadline;
use crate::planners::lattice::LatticeSpec;
use crate::planners::mapf::{Graph, MAPF_PARAMS, NONE, Node, check_mapf_lattice};

#[path = "lacam/scatter.rs"]
mod scatter;

use scatter::Scatter;


/// `lacam` in the registry.
pub static PLANNER: Planner = Planner {
    kind: "lacam",
    summary: "LaCAM with PIBT: a complete search for a team under grid MAPF; `refine yes` is LaCAM*",
    robots: &[RobotKind::Team],
    params: &[
        MAPF_PARAMS[0],
        MAPF_PARAMS[1],
        ParamSpec::word(
            "refine",
            YesNo::WORDS,
            "no",
            "after the first solution, refine it until the search is exhausted or a limit is reached (LaCAM*: converges to the least sum of loss)",
        ),
        ParamSpec::new(
            "pibt_runs",
            ValueSpec::Number {
                min: 1.0,
                min_open: false,
                max: 100.0,
                integer: true,
            },
            num(1.0, "1"),
            "PIBT runs per successor configuration, the one of least loss plus distance kept (LaCAM3 uses 10)",
        ),
        ParamSpec::word(
            "swap",
            YesNo::WORDS,
            "no",
            "PIBT swaps two agents that must pass each other in a corridor, where plain PIBT would push one back and forth (LaCAM*'s PIBT)",
        ),
        ParamSpec::word(
            "spread",
            YesNo::WORDS,
            "no",
            "first give each agent a path that meets the others' least (at most 10 steps over its shortest), which PIBT then prefers (LaCAM3's SUO): lower sums of costs, more time",
        ),
    ],
    metrics: &[
        MetricSpec::num(
            "sum_of_loss",
            "the solution's sum of loss: each step an agent is not resting at its goal (+∞ without one)",
        ),
        MetricSpec::bool(
            "exhausted",
            "the search ran out of nodes: no solution exists, or (refining) the solution is optimal in sum of loss",
        ),
        MetricSpec::num("configurations", "configurations explored"),
    ],
    limits: &["expansions", "time", "cells"],
    needs_goal: false,
    randomized: true,
    grids: true,
    time: false,
    check,
};

/// A `lacam` plan's settings.
#[derive(Clone, Debug)]
pub struct Lacam {
    pub lattice: LatticeSpec,
    pub refine: bool,
    /// PIBT runs per successor, the best kept.
    pub pibt_runs: u32,
    /// Space-utilisation paths guide PIBT (`spread yes`; LaCAM3's
    /// "scatter").
    pub scatter: bool,
    /// PIBT's swap.
    pub swap: bool,
}

fn check(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    let refine = args.word::<YesNo>("refine") == YesNo::Yes;
    let lattice = check_mapf_lattice(args)?;
    let pibt_runs = args.num("pibt_runs") as u32;
    let scatter = args.word::<YesNo>("spread") == YesNo::Yes;
    let swap = args.word::<YesNo>("swap") == YesNo::Yes;
    Some(Box::new(Lacam {
        lattice,
        refine,
        pibt_runs,
        scatter,
        swap,
    }))
}

impl Settings for Lacam {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        plan(task, self)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// No agent.
const NO: u32 = u32::MAX;

/// The chance that a revisited configuration sends the search back to the
/// start instead (LaCAM*'s random restarts).
const RESTART_RATE: f64 = 0.001;

/// The most explored configurations times agents (about 4 GiB of
/// configurations): beyond it the search gives up, with a note.
pub const MAX_STORED: usize = 1 << 30;

/// Distances to each agent's goal, computed lazily: a breadth-first search
/// from the goal, run only as far as a query needs.
struct Distances {
    dist: Vec<Vec<u32>>,
    queue: Vec<VecDeque<Node>>,
}

impl Distances {
    fn new(graph: &Graph) -> Self {
        let n = graph.goals.len();
        Distances {
            dist: vec![Vec::new(); n],
            queue: vec![VecDeque::new(); n],
        }
    }

    fn get(&mut self, graph: &Graph, agent: usize, v: Node) -> u32 {
        let dist = &mut self.dist[agent];
        if dist.is_empty() {
            *dist = vec![u32::MAX; graph.adj.len()];
            let goal = graph.goals[agent];
            dist[goal as usize] = 0;
            self.queue[agent].push_back(goal);
        }
        let queue = &mut self.queue[agent];
        while dist[v as usize] == u32::MAX {
            let Some(u) = queue.pop_front() else {
                break;
            };
            let d = dist[u as usize] + 1;
            for w in graph.neighbours(u) {
                if dist[w as usize] == u32::MAX {
                    dist[w as usize] = d;
                    queue.push_back(w);
                }
            }
        }
        dist[v as usize]
    }
}

/// PIBT: completes a partial next configuration.
struct Pibt {
    occupied_now: Vec<u32>,
    occupied_next: Vec<u32>,
    rng: SplitMix64,
    /// Each agent's preferred next point, when on its scatter path
    /// (`spread yes`).
    scatter: Option<Scatter>,
    /// PIBT's swap (`swap yes`).
    swap: bool,
}

impl Pibt {
    /// `to` (constraints set, others `NONE`) completed from `from` in
    /// `order`; false when the constraints conflict or an agent of the
    /// order cannot move without conflict.
    fn next(
        &mut self,
        graph: &Graph,
        dist: &mut Distances,
        from: &[Node],
        to: &mut [Node],
        order: &[u32],
    ) -> bool {
        let mut ok = true;
        for (i, &v) in from.iter().enumerate() {
            self.occupied_now[v as usize] = i as u32;
        }
        for i in 0..from.len() {
            let v = to[i];
            if v == NONE {
                continue;
            }
            if self.occupied_next[v as usize] != NO {
                ok = false;
                break;
            }
            let j = self.occupied_now[v as usize];
            if j != NO && j as usize != i && to[j as usize] == from[i] {
                ok = false;
                break;
            }
            self.occupied_next[v as usize] = i as u32;
        }
        if ok {
            for &i in order {
                if to[i as usize] == NONE
                    && !self.push(graph, dist, i as usize, from, to)
                {
                    ok = false;
                    break;
                }
            }
        }
        for (i, &v) in from.iter().enumerate() {
            self.occupied_now[v as usize] = NO;
            if to[i] != NONE {
                self.occupied_next[to[i] as usize] = NO;
            }
        }
        ok
    }

    /// Agent `i` to its best free neighbour (or where it is), agents in the
    /// way pushed by priority inheritance. With `swap`, an agent that must
    /// pass another in a corridor pulls it along instead (LaCAM*'s PIBT
    /// swap, as LaCAM3 writes it).
    fn push(
        &mut self,
        graph: &Graph,
        dist: &mut Distances,
        i: usize,
        from: &[Node],
        to: &mut [Node],
    ) -> bool {
        let here = from[i];
        // Each way (the neighbours, then staying) by its distance to the
        // goal, a random tie-break, the agent's next point on its scatter
        // path first.
        let preferred = self.scatter.as_ref().and_then(|s| s.next(i, here));
        let mut ranked = [(0f32, here); 5];
        let mut len = 0;
        for u in graph.neighbours(here).chain([here]) {
            let tie = self.rng.next_f64() as f32;
            let key = if Some(u) == preferred {
                -1.0
            } else {
                dist.get(graph, i, u) as f32 + tie
            };
            ranked[len] = (key, u);
            len += 1;
        }
        let ranked = &mut ranked[..len];
        ranked.sort_by(|a, b| a.0.total_cmp(&b.0));
        let swap_with = if self.swap {
            self.swap_partner(graph, dist, i, ranked[0].1, from, to)
        } else {
            None
        };
        if swap_with.is_some() {
            ranked.reverse();
        }
        for (k, &(_, u)) in ranked.iter().enumerate() {
            if self.occupied_next[u as usize] != NO {
                continue;
            }
            let ak = self.occupied_now[u as usize];
            if ak != NO && to[ak as usize] == here {
                continue;
            }
            self.occupied_next[u as usize] = i as u32;
            to[i] = u;
            if ak != NO
                && ak as usize != i
                && to[ak as usize] == NONE
                && !self.push(graph, dist, ak as usize, from, to)
            {
                continue;
            }
            // The swap: the partner is pulled into the point left.
            if k == 0
                && let Some(j) = swap_with
                && to[j] == NONE
                && self.occupied_next[here as usize] == NO
            {
                self.occupied_next[here as usize] = j as u32;
                to[j] = here;
            }
            return true;
        }
        self.occupied_next[here as usize] = i as u32;
        to[i] = here;
        false
    }

    /// The agent `i` should swap with before moving toward `best`, when a
    /// swap is needed (the other agent is in its way in a corridor with no
    /// room to step aside) and possible (a branch ahead to swap in).
    fn swap_partner(
        &self,
        graph: &Graph,
        dist: &mut Distances,
        i: usize,
        best: Node,
        from: &[Node],
        to: &[Node],
    ) -> Option<usize> {
        let j = self.occupied_now[best as usize];
        if j != NO
            && j as usize != i
            && to[j as usize] == NONE
            && self.swap_required(graph, dist, i, j as usize, from[i], from[j as usize])
            && self.swap_possible(graph, from[j as usize], from[i])
        {
            return Some(j as usize);
        }
        // Clearing the way, as push-and-swap does.
        if best != from[i] {
            for u in graph.neighbours(from[i]) {
                let k = self.occupied_now[u as usize];
                if k != NO
                    && best != from[k as usize]
                    && self.swap_required(graph, dist, k as usize, i, from[i], best)
                    && self.swap_possible(graph, best, from[i])
                {
                    return Some(k as usize);
                }
            }
        }
        None
    }

    /// The neighbours of `v` other than `pusher`'s point and dead ends where
    /// an agent rests at its goal: how many, and one of them.
    fn ways_on(&self, graph: &Graph, v: Node, pusher: Node) -> (usize, Node) {
        let mut n = 0;
        let mut other = NONE;
        for u in graph.neighbours(v) {
            let a = self.occupied_now[u as usize];
            let resting = graph.neighbours(u).count() == 1
                && a != NO
                && graph.goals[a as usize] == u;
            if u != pusher && !resting {
                n += 1;
                other = u;
            }
        }
        (n, other)
    }

    /// Whether `pusher` (at `v_pusher`) and `puller` (at `v_puller`) must
    /// swap: the corridor ahead has no branch before the pusher's way and
    /// the puller's part.
    fn swap_required(
        &self,
        graph: &Graph,
        dist: &mut Distances,
        pusher: usize,
        puller: usize,
        v_pusher: Node,
        v_puller: Node,
    ) -> bool {
        let (mut v_pusher, mut v_puller) = (v_pusher, v_puller);
        while dist.get(graph, pusher, v_puller) < dist.get(graph, pusher, v_pusher) {
            let (n, other) = self.ways_on(graph, v_puller, v_pusher);
            if n >= 2 {
                return false;
            }
            if n == 0 {
                break;
            }
            v_pusher = v_puller;
            v_puller = other;
        }
        dist.get(graph, puller, v_pusher) < dist.get(graph, puller, v_puller)
            && (dist.get(graph, pusher, v_pusher) == 0
                || dist.get(graph, pusher, v_puller) < dist.get(graph, pusher, v_pusher))
    }

    /// Whether a branch along the corridor from `v_puller` (away from
    /// `v_pusher`) leaves room to swap.
    fn swap_possible(&self, graph: &Graph, v_pusher: Node, v_puller: Node) -> bool {
        let origin = v_pusher;
        let (mut v_pusher, mut v_puller) = (v_pusher, v_puller);
        while v_puller != origin {
            let (n, other) = self.ways_on(graph, v_puller, v_pusher);
            if n >= 2 {
                return true;
            }
            if n == 0 {
                return false;
            }
            v_pusher = v_puller;
            v_puller = other;
        }
        false
    }
}

/// A low-level node: constraints "agent `who[d]` goes to `at[d]`".
struct Low {
    who: Vec<u32>,
    at: Vec<Node>,
}

/// A high-level node: a configuration.
struct High {
    q: Vec<Node>,
    parent: u32,
    /// The explored configurations one step from this one (LaCAM*).
    next: Vec<u32>,
    g: u64,
    h: u64,
    priorities: Vec<f32>,
    order: Vec<u32>,
    tree: VecDeque<Low>,
}

impl High {
    fn f(&self) -> u64 {
        self.g + self.h
    }
}

/// The loss of a step: the agents not resting at their goals.
fn loss(goals: &[Node], a: &[Node], b: &[Node]) -> u64 {
    goals
        .iter()
        .zip(a.iter().zip(b))
        .filter(|(g, (x, y))| *x != *g || *y != *g)
        .count() as u64
}

struct Search<'g> {
    graph: &'g Graph,
    dist: Distances,
    pibt: Pibt,
    nodes: Vec<High>,
    explored: HashMap<Vec<Node>, u32>,
    rng: SplitMix64,
}

impl Search<'_> {
    fn h(&mut self, q: &[Node]) -> u64 {
        (0..q.len())
            .map(|i| u64::from(self.dist.get(self.graph, i, q[i])))
            .sum()
    }

    fn add(&mut self, q: Vec<Node>, parent: u32) -> u32 {
        let n = q.len();
        let mut priorities = vec![0.0f32; n];
        for (i, p) in priorities.iter_mut().enumerate() {
            let d = self.dist.get(self.graph, i, q[i]);
            *p = if parent == NO {
                d as f32 / n as f32
            } else {
                let before = self.nodes[parent as usize].priorities[i];
                if d != 0 { before + 1.0 } else { before - before.floor() }
            };
        }
        let mut order: Vec<u32> = (0..n as u32).collect();
        order.sort_by(|&a, &b| priorities[b as usize].total_cmp(&priorities[a as usize]));
        let (g, h) = match parent {
            NO => (0, self.h(&q)),
            p => {
                let from = &self.nodes[p as usize];
                (from.g + loss(&self.graph.goals, &from.q, &q), self.h(&q))
            }
        };
        let id = self.nodes.len() as u32;
        if parent != NO {
            self.nodes[parent as usize].next.push(id);
        }
        self.explored.insert(q.clone(), id);
        self.nodes.push(High {
            q,
            parent,
            next: Vec::new(),
            g,
            h,
            priorities,
            order,
            tree: VecDeque::from([Low {
                who: Vec::new(),
                at: Vec::new(),
            }]),
        });
        id
    }

    /// LaCAM*'s rewiring: `from` reaches `to` in one step; cheaper ways
    /// spread through the explored graph.
    fn rewire(&mut self, from: u32, to: u32, goal: Option<u32>, open: &mut Vec<u32>) {
        if !self.nodes[from as usize].next.contains(&to) {
            self.nodes[from as usize].next.push(to);
        }
        let mut queue = VecDeque::from([from]);
        while let Some(a) = queue.pop_front() {
            for k in 0..self.nodes[a as usize].next.len() {
                let b = self.nodes[a as usize].next[k];
                let cost = {
                    let (na, nb) = (&self.nodes[a as usize], &self.nodes[b as usize]);
                    na.g + loss(&self.graph.goals, &na.q, &nb.q)
                };
                if cost < self.nodes[b as usize].g {
                    let nb = &mut self.nodes[b as usize];
                    nb.g = cost;
                    nb.parent = a;
                    let f = nb.f();
                    queue.push_back(b);
                    if goal.is_some_and(|g| f < self.nodes[g as usize].f()) {
                        open.push(b);
                    }
                }
            }
        }
    }
}

/// Runs a `lacam` plan.
pub fn plan(task: &Task<'_>, settings: &Lacam) -> PlanOutcome {
    let deadline = Deadline::start(&task.limits);
    let mut out = PlanOutcome::default();
    out.extra
        .insert("sum_of_loss".into(), MetricValue::Num(f64::INFINITY));
    out.extra
        .insert("exhausted".into(), MetricValue::Bool(false));
    out.extra
        .insert("configurations".into(), MetricValue::Num(0.0));
    let graph = match Graph::build(task, settings.lattice, &deadline) {
        Ok(g) => g,
        Err(note) => {
            out.gave_up = deadline.passed();
            out.notes.push(note);
            return out;
        }
    };
    // PIBT recurses once per agent it pushes: a thread with room for a
    // chain through every agent of a large team.
    let stack = (64 << 20) + task.agents.len() * 512;
    std::thread::scope(|scope| {
        std::thread::Builder::new()
            .name("lacam".into())
            .stack_size(stack)
            .spawn_scoped(scope, || search(task, settings, &graph, &deadline, &mut out))
            .expect("a thread for the search")
            .join()
            .expect("the search does not panic")
    });
    out
}

fn search(
    task: &Task<'_>,
    settings: &Lacam,
    graph: &Graph,
    deadline: &Deadline,
    out: &mut PlanOutcome,
) {
    let n = task.agents.len();
    let cells = graph.adj.len();
    if let Some(note) = crate::planners::mapf::too_many_distances(graph, n) {
        out.gave_up = true;
        out.notes.push(note);
        return;
    }
    let mut s = Search {
        graph,
        dist: Distances::new(graph),
        pibt: Pibt {
            occupied_now: vec![NO; cells],
            occupied_next: vec![NO; cells],
            rng: SplitMix64::new(task.seed ^ 0x5eed_1aca),
            scatter: None,
            swap: settings.swap,
        },
        nodes: Vec::new(),
        explored: HashMap::new(),
        rng: SplitMix64::new(task.seed),
    };
    for (i, a) in task.agents.iter().enumerate() {
        if s.dist.get(graph, i, graph.starts[i]) == u32::MAX {
            out.notes.push(format!(
                "agent `{}` cannot reach its goal: no team has a solution",
                a.name
            ));
            out.extra.insert("exhausted".into(), MetricValue::Bool(true));
            return;
        }
    }
    if settings.scatter {
        s.pibt.scatter = Some(Scatter::build(graph, &mut s.dist, task.seed, deadline));
    }
    let max_expansions = task.limits.expansions.unwrap_or(u64::MAX);
    let root = s.add(graph.starts.clone(), NO);
    let mut open: Vec<u32> = vec![root];
    let mut goal: Option<u32> = None;
    let mut expanded = 0u64;
    let mut stopped = false;
    let mut to = vec![NONE; n];
    while let Some(&h) = open.last() {
        if expanded >= max_expansions
            || s.nodes.len().saturating_mul(n.max(1)) > MAX_STORED
            || (expanded.is_multiple_of(256) && deadline.passed())
        {
            stopped = true;
            break;
        }
        if s.nodes[h as usize].tree.is_empty() {
            open.pop();
            continue;
        }
        if goal.is_some_and(|g| s.nodes[h as usize].f() >= s.nodes[g as usize].f()) {
            open.pop();
            continue;
        }
        if goal.is_none() && s.nodes[h as usize].q == graph.goals {
            goal = Some(h);
            if !settings.refine {
                break;
            }
            continue;
        }
        expanded += 1;
        let Some(low) = s.nodes[h as usize].tree.pop_front() else {
            continue;
        };
        // The low-level tree one agent deeper: each of the next agent's
        // moves, in a random order.
        let depth = low.who.len();
        if depth < n {
            let node = &s.nodes[h as usize];
            let i = node.order[depth];
            let here = node.q[i as usize];
            let mut moves: Vec<Node> = graph.neighbours(here).chain([here]).collect();
            for k in (1..moves.len()).rev() {
                let j = (s.rng.next_u64() % (k as u64 + 1)) as usize;
                moves.swap(k, j);
            }
            for v in moves {
                let mut who = low.who.clone();
                let mut at = low.at.clone();
                who.push(i);
                at.push(v);
                s.nodes[h as usize].tree.push_back(Low { who, at });
            }
        }
        let (from, order) = {
            let node = &s.nodes[h as usize];
            (node.q.clone(), node.order.clone())
        };
        // PIBT `pibt_runs` times (random tie-breaks differ), the successor
        // of least loss plus heuristic kept (LaCAM3's Monte-Carlo
        // configuration generation).
        let mut best: Option<(u64, Vec<Node>)> = None;
        for _ in 0..settings.pibt_runs {
            to.fill(NONE);
            for (&i, &v) in low.who.iter().zip(&low.at) {
                to[i as usize] = v;
            }
            if !s.pibt.next(graph, &mut s.dist, &from, &mut to, &order) {
                continue;
            }
            let f = loss(&graph.goals, &from, &to) + s.h(&to);
            if best.as_ref().is_none_or(|(b, _)| f < *b) {
                best = Some((f, to.clone()));
            }
        }
        let Some((_, next)) = best else {
            continue;
        };
        to.copy_from_slice(&next);
        match s.explored.get(&to).copied() {
            Some(seen) => {
                s.rewire(h, seen, goal, &mut open);
                let restart = s.rng.next_f64() < RESTART_RATE;
                let back = if restart { root } else { seen };
                if goal.is_none_or(|g| s.nodes[back as usize].f() < s.nodes[g as usize].f()) {
                    open.push(back);
                }
            }
            None => {
                let id = s.add(to.clone(), h);
                if goal.is_none_or(|g| s.nodes[id as usize].f() < s.nodes[g as usize].f()) {
                    open.push(id);
                }
            }
        }
    }
    out.expanded = expanded;
    out.extra.insert(
        "configurations".into(),
        MetricValue::Num(s.nodes.len() as f64),
    );
    let exhausted = !stopped && open.is_empty();
    out.extra
        .insert("exhausted".into(), MetricValue::Bool(exhausted && (goal.is_none() || settings.refine)));
    let Some(g) = goal else {
        if exhausted {
            out.notes
                .push("the search is exhausted: the team has no solution".into());
        } else {
            out.gave_up = true;
            out.notes
                .push("a limit was reached before a solution was found".into());
        }
        return;
    };
    if settings.refine && !exhausted {
        out.notes.push(
            "a limit stopped the refinement: the solution is the best found, not proven optimal".into(),
        );
    }
    // The configurations from the start to the goal.
    let mut chain = vec![g];
    while let Some(&k) = chain.last() {
        let p = s.nodes[k as usize].parent;
        if p == NO {
            break;
        }
        chain.push(p);
    }
    chain.reverse();
    let mut paths: Vec<Vec<crate::geometry::Point>> = (0..n)
        .map(|i| chain.iter().map(|&k| graph.point(s.nodes[k as usize].q[i])).collect())
        .collect();
    // Each path ends at its agent's last arrival.
    for p in &mut paths {
        let keep = crate::geometry::team::agent_cost(p) + 1;
        p.truncate(keep);
    }
    let sum_of_loss: u64 = chain
        .windows(2)
        .map(|w| loss(&graph.goals, &s.nodes[w[0] as usize].q, &s.nodes[w[1] as usize].q))
        .sum();
    out.extra
        .insert("sum_of_loss".into(), MetricValue::Num(sum_of_loss as f64));
    out.cost = Some(sum_of_loss as f64);
    out.agents = Some(paths);
}

#[cfg(test)]
#[path = "lacam/tests.rs"]
mod tests;
