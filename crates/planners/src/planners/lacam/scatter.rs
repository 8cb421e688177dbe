//! Space-utilisation paths, "scatter" (SUO: Han & Yu, ICRA 2022), as
//! LaCAM3 uses them (Okumura, *Engineering LaCAM\**, AAMAS 2024): before the
//! search, every agent gets a path to its goal that meets the other agents'
//! paths as little as possible, at most [`MARGIN`] steps longer than its
//! shortest; PIBT then prefers each agent's next point on its path when it
//! stands on it. Agents that would all take one corridor spread over the
//! map instead, and the sums of costs drop.
//!
//! Each round plans the agents one by one in a random order, each by an A*
//! whose first key is the number of collisions with the other paths (a
//! shared point at a step, a swap, or passing a point where an agent rests
//! for good) and whose second is the length; rounds go on while the count
//! of collisions falls. Paths never pass a point twice (one visit per
//! point, as LaCAM3's), so a path is a map from a point to the next.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use super::Distances;
use crate::geometry::rng::SplitMix64;
use crate::planners::deadline::Deadline;
use crate::planners::mapf::{Graph, NONE, Node};

/// How much longer than its shortest path an agent's path may be
/// (LaCAM3's default).
pub const MARGIN: u32 = 10;

/// Each agent's path, as "from this point, go to that one".
pub struct Scatter {
    /// Per agent, (point, next point) sorted by point.
    next: Vec<Vec<(Node, Node)>>,
}

impl Scatter {
    /// Agent `i`'s next point on its path when it stands at `at` on it.
    pub fn next(&self, i: usize, at: Node) -> Option<Node> {
        let map = &self.next[i];
        map.binary_search_by_key(&at, |e| e.0).ok().map(|k| map[k].1)
    }

    /// The paths of every agent; stops early (keeping what it has) when
    /// the deadline passes.
    pub fn build(graph: &Graph, dist: &mut Distances, seed: u64, deadline: &Deadline) -> Scatter {
        let n = graph.starts.len();
        let cells = graph.adj.len();
        let mut table = Table {
            body: vec![Vec::new(); cells],
            last: vec![Vec::new(); cells],
            count: 0,
        };
        let mut paths: Vec<Vec<Node>> = vec![Vec::new(); n];
        let mut rng = SplitMix64::new(seed ^ 0x05ca_77e2);
        let mut search = Astar {
            closed: vec![false; cells],
            parent: vec![NONE; cells],
            used: Vec::new(),
        };
        let mut order: Vec<usize> = (0..n).collect();
        let mut round = 0;
        let mut last_count = i64::MAX;
        'rounds: while round < 2 || table.count < last_count {
            round += 1;
            last_count = table.count;
            for k in (1..n).rev() {
                let j = (rng.next_u64() % (k as u64 + 1)) as usize;
                order.swap(k, j);
            }
            for &i in &order {
                if deadline.passed() {
                    break 'rounds;
                }
                table.clear(i as u32, &paths[i]);
                if let Some(p) = search.path(graph, dist, &table, i) {
                    paths[i] = p;
                }
                table.enroll(i as u32, &paths[i]);
            }
            if table.count == 0 {
                break;
            }
        }
        let next = paths
            .iter()
            .map(|p| {
                let mut m: Vec<(Node, Node)> = p.windows(2).map(|w| (w[0], w[1])).collect();
                m.sort_unstable();
                m
            })
            .collect();
        Scatter { next }
    }
}

/// Who is where when, along the paths so far.
struct Table {
    /// Per point, the (step, agent) of every visit, sorted: memory in
    /// proportion to the paths' lengths, whatever the steps.
    body: Vec<Vec<(u32, u32)>>,
    /// Per point, the steps at which agents whose paths end there arrive.
    last: Vec<Vec<u32>>,
    /// The collisions among the paths enrolled.
    count: i64,
}

impl Table {
    /// The agents at `v` at step `t`.
    fn at(&self, v: Node, t: usize) -> &[(u32, u32)] {
        let visits = &self.body[v as usize];
        let t = t as u32;
        let lo = visits.partition_point(|e| e.0 < t);
        let hi = lo + visits[lo..].partition_point(|e| e.0 == t);
        &visits[lo..hi]
    }

    /// The visits of `v` after step `t`.
    fn after(&self, v: Node, t: usize) -> usize {
        let visits = &self.body[v as usize];
        visits.len() - visits.partition_point(|e| e.0 as usize <= t)
    }

    /// The collisions of a move `from` → `to` leaving at step `t`.
    fn cost(&self, from: Node, to: Node, t: usize) -> u32 {
        let mut c = self.at(to, t + 1).len() as u32;
        let before = self.at(to, t);
        for &(_, j) in self.at(from, t + 1) {
            c += before.iter().filter(|e| e.1 == j).count() as u32;
        }
        c += self.last[to as usize].iter().filter(|&&s| t as u32 + 1 > s).count() as u32;
        c
    }

    fn enroll(&mut self, i: u32, path: &[Node]) {
        let Some(&end) = path.last() else {
            return;
        };
        for (t, &v) in path.iter().enumerate() {
            if t > 0 {
                self.count += i64::from(self.cost(path[t - 1], v, t - 1));
            }
            let visits = &mut self.body[v as usize];
            let k = visits.partition_point(|e| *e <= (t as u32, i));
            visits.insert(k, (t as u32, i));
        }
        let arrival = path.len() - 1;
        self.last[end as usize].push(arrival as u32);
        self.count += self.after(end, arrival) as i64;
    }

    fn clear(&mut self, i: u32, path: &[Node]) {
        let Some(&end) = path.last() else {
            return;
        };
        for (t, &v) in path.iter().enumerate() {
            let visits = &mut self.body[v as usize];
            if let Ok(k) = visits.binary_search(&(t as u32, i)) {
                visits.remove(k);
            }
            if t > 0 {
                self.count -= i64::from(self.cost(path[t - 1], v, t - 1));
            }
        }
        let arrival = path.len() - 1;
        let last = &mut self.last[end as usize];
        if let Some(k) = last.iter().position(|&s| s as usize == arrival) {
            last.swap_remove(k);
        }
        self.count -= self.after(end, arrival) as i64;
    }
}

/// An open entry of the single-agent search: collisions, f, the point
/// (the later one first on ties, LaCAM3's order), g and the parent.
type Entry = (u32, u32, Reverse<Node>, u32, Node);

/// The single-agent search of a round, its arrays kept between agents.
struct Astar {
    closed: Vec<bool>,
    parent: Vec<Node>,
    used: Vec<Node>,
}

impl Astar {
    /// Agent `i`'s path of fewest collisions with `table`, then shortest,
    /// at most [`MARGIN`] steps above its shortest.
    fn path(&mut self, graph: &Graph, dist: &mut Distances, table: &Table, i: usize) -> Option<Vec<Node>> {
        let start = graph.starts[i];
        let goal = graph.goals[i];
        let bound = dist.get(graph, i, start).saturating_add(MARGIN);
        // Smallest first.
        let mut open: BinaryHeap<Reverse<Entry>> = BinaryHeap::new();
        open.push(Reverse((0, dist.get(graph, i, start), Reverse(start), 0, NONE)));
        let mut found = false;
        while let Some(Reverse((c, _, Reverse(v), g, parent))) = open.pop() {
            if self.closed[v as usize] {
                continue;
            }
            self.closed[v as usize] = true;
            self.parent[v as usize] = parent;
            self.used.push(v);
            if v == goal {
                found = true;
                break;
            }
            for u in graph.neighbours(v) {
                let d = dist.get(graph, i, u);
                if u != start && !self.closed[u as usize] && d != u32::MAX && d + g < bound {
                    let cost = c + table.cost(v, u, g as usize);
                    open.push(Reverse((cost, g + 1 + d, Reverse(u), g + 1, v)));
                }
            }
        }
        let path = found.then(|| {
            let mut p = vec![goal];
            let mut v = goal;
            while self.parent[v as usize] != NONE {
                v = self.parent[v as usize];
                p.push(v);
            }
            p.reverse();
            p
        });
        for &v in &self.used {
            self.closed[v as usize] = false;
            self.parent[v as usize] = NONE;
        }
        self.used.clear();
        path
    }
}
