//! Generalised rectangle reasoning ("GR", Li, Harabor, Stuckey, Ma,
//! Gange and Koenig, "Pairwise symmetry reasoning for multi-agent path
//! finding search", AIJ 2021, §5.3): the rectangle split for two agents
//! whose paths are not Manhattan-optimal from their starts, read from
//! their MDDs instead of from their starts and goals.
//!
//! The *overlap* of a vertex conflict is the connected area around it
//! where each agent's MDD is at each cell at one step only, the same step
//! for both. Walking the area's rim counter-clockwise from its earliest
//! cell, the places where the first agent's MDD enters must lie on one
//! arc and the second's on another; the far side of the rim, from the end
//! of one arc round the latest cell to the end of the other, is then split
//! at the latest cell into two barriers, one per agent, each cell at its
//! step (the walk and its stages follow the paper's reference code,
//! CBSH2-RTC's `RectangleReasoning::findGenerealizedRectangleConflict`).
//!
//! The walk decides what to try; it is not what makes the split sound.
//! Every split is checked before it is used ([`disjunctive`]): a path
//! that is at an MDD cell at its step has come there along the MDD (any
//! earlier point of it is nearer the goal than the MDD's cost allows only
//! if it is in the MDD), so when no two MDD walks to the two barriers stay
//! apart all the way, no two paths that both break their barriers are free
//! of conflict, and every solution is kept by one child.

use std::collections::{BTreeSet, VecDeque};

use super::{Constraint, Rule, adjacent, apart_next, at, cell};
use crate::planners::mapf::{FastMap, FastSet, Graph, Node};

/// Where an MDD is at a cell: at one step, or at several.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Visit {
    Once(u32),
    Many,
}

fn project(levels: &[Vec<Node>]) -> FastMap<Node, Visit> {
    let mut visits: FastMap<Node, Visit> = FastMap::default();
    for (t, level) in levels.iter().enumerate() {
        for &v in level {
            visits
                .entry(v)
                .and_modify(|x| *x = Visit::Many)
                .or_insert(Visit::Once(t as u32));
        }
    }
    visits
}

fn once(visits: &FastMap<Node, Visit>, v: Node) -> Option<u32> {
    match visits.get(&v) {
        Some(&Visit::Once(t)) => Some(t),
        _ => None,
    }
}

fn in_level(levels: &[Vec<Node>], v: Node, t: u32) -> bool {
    levels.get(t as usize).is_some_and(|l| l.contains(&v))
}

/// The four directions, each a left turn from the one before.
const TURNS: [(i64, i64); 4] = [(0, 1), (-1, 0), (0, -1), (1, 0)];

/// Standing at `from` and facing its neighbour `to`, the next neighbour
/// turning left (counter-clockwise); `to` itself when it is the only one.
fn turn_left(graph: &Graph, from: Node, to: Node) -> Option<Node> {
    let (f, t) = (cell(graph, from), cell(graph, to));
    let facing = TURNS.iter().position(|&d| d == (t.0 - f.0, t.1 - f.1))?;
    (1..=4).find_map(|k| {
        let d = TURNS[(facing + k) % 4];
        let there = (f.0 + d.0, f.1 + d.1);
        graph.neighbours(from).find(|&w| cell(graph, w) == there)
    })
}

/// An edge from outside the area into it.
type Edge = (Node, Node);

/// The generalised rectangle split of agents `a` and `b` (MDDs `mdd_a`,
/// `mdd_b`, current paths `path_a`, `path_b`) meeting at `v` at step `t`
/// before either rests: each agent's barrier as vertex constraints, and
/// the split's cardinality. `None` when the area is no rectangle, when a
/// current path would keep its child's constraints, or when the check
/// finds two paths across their barriers that need not meet.
#[allow(clippy::too_many_arguments)]
pub(super) fn generalised(
    graph: &Graph,
    (a, path_a, mdd_a): (u32, &[Node], &[Vec<Node>]),
    (b, path_b, mdd_b): (u32, &[Node], &[Vec<Node>]),
    v: Node,
    t: u32,
) -> Option<(Vec<Constraint>, Vec<Constraint>, u8)> {
    if t == 0 || t as usize >= path_a.len() || t as usize >= path_b.len() {
        return None;
    }
    let (visits_a, visits_b) = (project(mdd_a), project(mdd_b));
    if once(&visits_a, v) != Some(t) || once(&visits_b, v) != Some(t) {
        return None;
    }
    let (rim, mut entries_a, mut entries_b) =
        Rim::find(graph, (&visits_a, mdd_a), (&visits_b, mdd_b), path_a[t as usize - 1], v)?;
    let (stage, r1, r2) = rim.scan(&mut entries_a, &mut entries_b)?;
    if !rim.no_hole_shared(&mut entries_a, &entries_b) {
        return None;
    }
    let rg = (rim.latest, rim.latest);
    let (cells_a, cells_b) = if matches!(stage, Stage::Initial | Stage::ToSecond | Stage::FromFirst) {
        (rim.arc(r2, rg)?, rim.arc(rg, r1)?)
    } else {
        (rim.arc(rg, r2)?, rim.arc(r1, rg)?)
    };
    let constraints = |agent: u32, mut cells: Vec<Node>| -> Vec<Constraint> {
        cells.sort_unstable();
        cells.dedup();
        cells
            .into_iter()
            .map(|v| Constraint {
                agent,
                rule: Rule::Vertex {
                    v,
                    t: once(&visits_a, v).expect("a cell of the overlap"),
                },
            })
            .collect()
    };
    let (barrier_a, barrier_b) = (constraints(a, cells_a), constraints(b, cells_b));
    let crosses = |path: &[Node], barrier: &[Constraint]| {
        barrier
            .iter()
            .any(|c| matches!(c.rule, Rule::Vertex { v, t } if at(path, t as usize) == v))
    };
    if !crosses(path_a, &barrier_a) || !crosses(path_b, &barrier_b) {
        return None;
    }
    let cells = |barrier: &[Constraint]| -> FastSet<(Node, u32)> {
        barrier
            .iter()
            .filter_map(|c| match c.rule {
                Rule::Vertex { v, t } => Some((v, t)),
                _ => None,
            })
            .collect()
    };
    let (across_a, across_b) = (cells(&barrier_a), cells(&barrier_b));
    if !disjunctive(graph, mdd_a, mdd_b, &across_a, &across_b) {
        return None;
    }
    let cardinality = u8::from(blocks_all(graph, mdd_a, &across_a)) + u8::from(blocks_all(graph, mdd_b, &across_b));
    Some((barrier_a, barrier_b, cardinality))
}

/// Where the rim walk is: which agent's entries it has met, and whether
/// before or after the latest cell.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Stage {
    /// No entry yet.
    Initial,
    /// The first agent's entries, before the latest cell.
    ToFirst,
    /// The second agent's entries, before the latest cell.
    ToSecond,
    /// The first agent's entries, after the latest cell.
    FromFirst,
    /// The second agent's entries, after the latest cell.
    FromSecond,
}

impl Stage {
    /// The stage after the rim walk meets an entry of the first agent
    /// (`first`) or of the second, before or after the latest cell
    /// (`passed`), and whether that entry is now the agent's last; `None`
    /// when the entries do not lie on two arcs.
    fn met(self, first: bool, passed: bool) -> Option<(Stage, bool)> {
        let (to_mine, from_mine, to_other) = if first {
            (Stage::ToFirst, Stage::FromFirst, Stage::ToSecond)
        } else {
            (Stage::ToSecond, Stage::FromSecond, Stage::ToFirst)
        };
        match (self, passed) {
            (s, false) if s == Stage::Initial || s == to_mine => Some((to_mine, true)),
            (s, true) if s == Stage::Initial || s == to_other => Some((from_mine, true)),
            (s, _) if s == from_mine => Some((s, false)),
            _ => None,
        }
    }
}

/// The overlap area of a conflict.
struct Rim<'a> {
    graph: &'a Graph,
    area: FastSet<Node>,
    /// An edge into the area's earliest cell on the rim.
    earliest: Edge,
    /// The area's latest cell.
    latest: Node,
    /// The most steps any walk around the rim may take.
    cap: usize,
}

impl<'a> Rim<'a> {
    /// The overlap area around `v`, reached from `before`, with the edges
    /// by which each agent's MDD enters it.
    fn find(
        graph: &'a Graph,
        (visits_a, mdd_a): (&FastMap<Node, Visit>, &[Vec<Node>]),
        (visits_b, mdd_b): (&FastMap<Node, Visit>, &[Vec<Node>]),
        before: Node,
        v: Node,
    ) -> Option<(Self, BTreeSet<Edge>, BTreeSet<Edge>)> {
        let step = |c: Node| once(visits_a, c).expect("a cell of the overlap");
        let mut area: FastSet<Node> = FastSet::default();
        area.insert(v);
        let mut queue = VecDeque::from([v]);
        let (mut earliest, mut latest) = ((before, v), v);
        let (mut entries_a, mut entries_b) = (BTreeSet::new(), BTreeSet::new());
        while let Some(c) = queue.pop_front() {
            let tc = step(c);
            if step(latest) < tc {
                latest = c;
            }
            for next in graph.neighbours(c) {
                if area.contains(&next) {
                    continue;
                }
                if let (Some(x), Some(y)) = (once(visits_a, next), once(visits_b, next))
                    && x == y
                {
                    area.insert(next);
                    queue.push_back(next);
                    continue;
                }
                if step(earliest.1) > tc {
                    earliest = (next, c);
                }
                if tc > 0 && in_level(mdd_a, next, tc - 1) {
                    entries_a.insert((next, c));
                }
                if tc > 0 && in_level(mdd_b, next, tc - 1) {
                    entries_b.insert((next, c));
                }
            }
        }
        // A single cell, or no way in from outside: nothing to reason on.
        if earliest.1 == latest || earliest.0 == earliest.1 {
            return None;
        }
        let cap = 8 * area.len() + 16;
        let rim = Rim {
            graph,
            area,
            earliest,
            latest,
            cap,
        };
        Some((rim, entries_a, entries_b))
    }

    fn inside(&self, v: Node) -> bool {
        self.area.contains(&v)
    }

    fn left(&self, from: Node, to: Node) -> Option<Node> {
        turn_left(self.graph, from, to)
    }

    /// From area cell `c`, reached from `prev`, the next cell of the rim,
    /// calling `outside` for each edge from outside into `c` passed on the
    /// way (`false` from it stops the walk).
    fn next_on_rim(&self, c: Node, prev: Node, mut outside: impl FnMut(Edge) -> bool) -> Option<Node> {
        let mut ex = self.left(c, prev)?;
        for _ in 0..4 {
            if self.inside(ex) {
                return Some(ex);
            }
            if !outside((ex, c)) {
                return None;
            }
            ex = self.left(c, ex)?;
        }
        self.inside(ex).then_some(ex)
    }

    /// One walk of the outer rim from the earliest cell: the stage it
    /// ends in and the last entries of each agent met (the earliest edge
    /// when none), `None` when the entries do not lie on two arcs or the
    /// walk never passes the latest cell.
    fn scan(&self, entries_a: &mut BTreeSet<Edge>, entries_b: &mut BTreeSet<Edge>) -> Option<(Stage, Edge, Edge)> {
        let (out, start) = self.earliest;
        let mut c = out;
        for _ in 0..4 {
            if self.inside(c) {
                break;
            }
            c = self.left(start, c)?;
        }
        if !self.inside(c) {
            return None;
        }
        let (mut stage, mut r1, mut r2) = (Stage::Initial, self.earliest, self.earliest);
        let (mut prev, mut passed_latest, mut steps) = (start, false, 0);
        while c != start {
            steps += 1;
            if steps > self.cap {
                return None;
            }
            passed_latest |= c == self.latest;
            let next = self.next_on_rim(c, prev, |edge| {
                for (first, entries) in [(true, &mut *entries_a), (false, &mut *entries_b)] {
                    if entries.remove(&edge) {
                        let Some((next, last)) = stage.met(first, passed_latest) else {
                            return false;
                        };
                        stage = next;
                        if last {
                            *(if first { &mut r1 } else { &mut r2 }) = edge;
                        }
                    }
                }
                true
            });
            prev = c;
            c = next?;
        }
        passed_latest.then_some((stage, r1, r2))
    }

    /// Whether no rim other than the outer one (a hole's) holds entries of
    /// both agents: walks the rim of each first-agent entry the outer walk
    /// did not meet (those at the earliest cell aside).
    fn no_hole_shared(&self, entries_a: &mut BTreeSet<Edge>, entries_b: &BTreeSet<Edge>) -> bool {
        while let Some((prev, c)) = entries_a.pop_first() {
            if c == self.earliest.1 {
                continue;
            }
            let (origin, mut prev, mut c) = (c, prev, c);
            let mut steps = 0;
            loop {
                steps += 1;
                if steps > self.cap {
                    return false;
                }
                let next = self.next_on_rim(c, prev, |edge| {
                    entries_a.remove(&edge);
                    !entries_b.contains(&edge)
                });
                let Some(next) = next else {
                    return false;
                };
                prev = c;
                c = next;
                if c == origin {
                    break;
                }
            }
        }
        true
    }

    /// The rim's cells counter-clockwise from edge `from`'s cell to edge
    /// `to`'s (an edge from a cell to itself stands for that cell alone).
    fn arc(&self, from: Edge, to: Edge) -> Option<Vec<Node>> {
        let mut cells = vec![from.1];
        if from.1 == to.1 {
            return Some(cells);
        }
        let mut c = if from.0 == from.1 {
            self.graph.neighbours(from.1).find(|&w| !self.inside(w))?
        } else {
            from.0
        };
        for _ in 0..4 {
            c = self.left(from.1, c)?;
            if self.inside(c) {
                break;
            }
        }
        if !self.inside(c) {
            return None;
        }
        cells.push(c);
        let mut prev = from.1;
        while c != to.1 {
            if cells.len() > self.cap {
                return None;
            }
            let next = self.next_on_rim(c, prev, |_| true)?;
            prev = c;
            c = next;
            cells.push(c);
        }
        Some(cells)
    }
}

/// For each step up to the last of `across`, the MDD's cells at that step
/// from which it can reach one of `across` (a cell at its step), those
/// cells included.
fn leading_to(graph: &Graph, mdd: &[Vec<Node>], across: &FastSet<(Node, u32)>) -> Vec<Vec<Node>> {
    let Some(last) = across.iter().map(|&(_, t)| t as usize).max() else {
        return Vec::new();
    };
    let mut lead: Vec<Vec<Node>> = vec![Vec::new(); last + 1];
    for t in (0..=last.min(mdd.len().saturating_sub(1))).rev() {
        let later = lead.get(t + 1).cloned().unwrap_or_default();
        lead[t] = mdd[t]
            .iter()
            .copied()
            .filter(|&v| across.contains(&(v, t as u32)) || later.iter().any(|&w| adjacent(graph, v, w)))
            .collect();
    }
    lead
}

/// Whether every walk along MDD `a` to one of `across_a` and every walk
/// along MDD `b` to one of `across_b` meet (same cell at the same step, or
/// swap along an edge) before either gets there: the two barriers are
/// mutually disjunctive. A joint search over the pairs of cells the two
/// MDDs can be at together without meeting; moves are any two adjacent
/// cells of consecutive levels, more than the MDDs' own edges, so a
/// `true` holds for every pair of paths.
pub(super) fn disjunctive(
    graph: &Graph,
    mdd_a: &[Vec<Node>],
    mdd_b: &[Vec<Node>],
    across_a: &FastSet<(Node, u32)>,
    across_b: &FastSet<(Node, u32)>,
) -> bool {
    let (lead_a, lead_b) = (leading_to(graph, mdd_a, across_a), leading_to(graph, mdd_b, across_b));
    let (Some(&sa), Some(&sb)) = (
        lead_a.first().and_then(|l| l.first()),
        lead_b.first().and_then(|l| l.first()),
    ) else {
        // One agent cannot reach its barrier along its MDD at all.
        return false;
    };
    let reached = |x: Node, y: Node, t: u32| across_a.contains(&(x, t)) || across_b.contains(&(y, t));
    if sa == sb {
        return true;
    }
    if reached(sa, sb, 0) {
        return false;
    }
    let empty: Vec<Node> = Vec::new();
    let mut here: Vec<(Node, Node)> = vec![(sa, sb)];
    let mut t = 0usize;
    while !here.is_empty() {
        t += 1;
        let (next_a, next_b) = (lead_a.get(t).unwrap_or(&empty), lead_b.get(t).unwrap_or(&empty));
        here = apart_next(graph, &here, next_a, next_b);
        if here.iter().any(|&(x, y)| reached(x, y, t as u32)) {
            return false;
        }
    }
    true
}

/// Whether every walk along the MDD from its start to its end passes one
/// of `across` (then the agent's cost rises in the child that forbids
/// them). Moves are any two adjacent cells of consecutive levels, so a
/// `true` is never claimed wrongly.
fn blocks_all(graph: &Graph, mdd: &[Vec<Node>], across: &FastSet<(Node, u32)>) -> bool {
    let mut here: Vec<Node> = mdd
        .first()
        .map(|l| l.iter().copied().filter(|&v| !across.contains(&(v, 0))).collect())
        .unwrap_or_default();
    for (t, level) in mdd.iter().enumerate().skip(1) {
        here = level
            .iter()
            .copied()
            .filter(|&x| !across.contains(&(x, t as u32)) && here.iter().any(|&u| adjacent(graph, u, x)))
            .collect();
        if here.is_empty() {
            return true;
        }
    }
    here.is_empty()
}
