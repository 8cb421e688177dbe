//! Pseudo-corridor reasoning (Li, Gange, Harabor, Stuckey, Ma and Koenig,
//! "New techniques for pairwise symmetry breaking in multi-agent path
//! finding", ICAPS 2020; CBSH2-RTC's `findPseudoCorridorConflict`): two
//! agents that must cross one edge head-on, each with a single shortest
//! way through it. Plain CBS splits over and over, one step of waiting at
//! a time, while one of them makes way; this split asks at once which of
//! the two arrives at its far end later.
//!
//! Agent `a` crosses the edge `e2`–`e1` into `e1`, agent `b` crosses it
//! the other way into `e2`. Let `t_a` be the earliest step `a` can be at
//! `e1` at all, `t_a'` the earliest without the edge, and `t_b`, `t_b'`
//! the same for `b` at `e2` (each under its constraints, which a child
//! only adds to). The split forbids `a` at `e1` at steps `0 ..= l_a`,
//! `l_a = min(t_a' − 1, t_b + 1)`, in one child, and `b` at `e2` at steps
//! `0 ..= l_b`, `l_b = min(t_b' − 1, t_a + 1)`, in the other.
//!
//! Why every solution is kept: if `a` is at `e1` at `τ_a ≤ l_a` and `b` at
//! `e2` at `τ_b ≤ l_b`, `a` first came to `e1` at some `σ_a ≤ τ_a < t_a'`,
//! so across the edge, from `e2`; likewise `b` first came to `e2` at
//! `σ_b ≤ τ_b`, from `e1`. Then `σ_a ≤ l_a ≤ t_b + 1 ≤ σ_b + 1` and
//! `σ_b ≤ σ_a + 1`: the same step is a swap on the edge; one step apart,
//! both are at one end at once. Either way the two paths conflict.

use super::low::{Table, arrival};
use super::{Constraint, CtNode, Rule};
use crate::planners::mapf::{Graph, Node};

/// An agent's side of a head-on crossing: it crosses into `into` from
/// `from`, at step `step` on its current path.
pub(super) struct Crossing {
    pub agent: u32,
    pub from: Node,
    pub into: Node,
    pub step: u32,
}

/// The pseudo-corridor split of a head-on crossing of one edge: each
/// child's constraints (the agent kept off its far end up to a step), or
/// `None` when the bounds would not change both current paths.
pub(super) fn pseudo_corridor(graph: &Graph, node: &CtNode, a: &Crossing, b: &Crossing) -> Option<[Vec<Constraint>; 2]> {
    if b.from != a.into || b.into != a.from || a.from == a.into {
        return None;
    }
    let table = |agent: u32| {
        let path = &node.paths[agent as usize];
        let goal = *path.last().expect("a path");
        (Table::new(agent, goal, &node.constraints), path[0])
    };
    let ((table_a, start_a), (table_b, start_b)) = (table(a.agent), table(b.agent));
    let edge = Some((a.from, a.into));
    let t_a = arrival(graph, &table_a, start_a, a.into, None, u32::MAX)?;
    if t_a + 1 < b.step {
        return None;
    }
    let t_b = arrival(graph, &table_b, start_b, b.into, None, u32::MAX)?;
    if t_b + 1 < a.step {
        return None;
    }
    // Without the edge: no earlier than the bound asks, or never.
    let t_a_without = arrival(graph, &table_a, start_a, a.into, edge, t_b + 2).unwrap_or(t_b + 2);
    if t_a_without < a.step + 1 {
        return None;
    }
    let t_b_without = arrival(graph, &table_b, start_b, b.into, edge, t_a + 2).unwrap_or(t_a + 2);
    if t_b_without < b.step + 1 {
        return None;
    }
    let l_a = (t_a_without - 1).min(t_b + 1);
    let l_b = (t_b_without - 1).min(t_a + 1);
    let off = |agent: u32, v: Node, last: u32| -> Vec<Constraint> {
        (0..=last)
            .map(|t| Constraint {
                agent,
                rule: Rule::Vertex { v, t },
            })
            .collect()
    };
    Some([off(a.agent, a.into, l_a), off(b.agent, b.into, l_b)])
}
