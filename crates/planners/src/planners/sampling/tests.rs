//! The sampling planners' own invariants on their internals (the tests
//! through scenario text are in the scen crate's `planner_tests`).

use petgraph::graph::{NodeIndex, UnGraph};

use super::prm::Roadmap;
use super::space::Space;
use crate::geometry::{Aabb, Config, Point};
use crate::rng::SplitMix64;

#[test]
fn the_roadmap_query_agrees_with_dijkstra() {
    let space = Space {
        bounds: Aabb {
            min: Point::new(0.0, 0.0),
            max: Point::new(10.0, 10.0),
        },
        rotating: true,
        theta: 0.0,
        turn_cost: 1.5,
        steering: None,
    };
    for seed in 0..50 {
        let mut rng = SplitMix64::new(seed);
        let mut graph: UnGraph<Config, (f64, u8)> = UnGraph::default();
        let n = 2 + (rng.next_u64() % 60) as usize;
        for _ in 0..n {
            graph.add_node(space.uniform(&mut rng));
        }
        for _ in 0..3 * n {
            let (a, b) = (
                (rng.next_u64() % n as u64) as usize,
                (rng.next_u64() % n as u64) as usize,
            );
            if a != b {
                let w = space.distance(graph[NodeIndex::new(a)], graph[NodeIndex::new(b)]);
                graph.add_edge(NodeIndex::new(a), NodeIndex::new(b), (w, 1));
            }
        }
        let expected = petgraph::algo::dijkstra(&graph, NodeIndex::new(0), None, |e| e.weight().0);
        let roadmap = Roadmap { graph };
        let found = roadmap.shortest_path(&space);
        match (found, expected.get(&NodeIndex::new(1))) {
            (Some((nodes, cost)), Some(&best)) => {
                assert!(
                    (cost - best).abs() <= 1e-9 * best.max(1.0),
                    "{seed}: {cost} vs {best}"
                );
                assert_eq!((nodes[0], nodes[nodes.len() - 1]), (0, 1));
                let along: f64 = nodes
                    .windows(2)
                    .map(|w| {
                        space.distance(
                            roadmap.graph[NodeIndex::new(w[0])],
                            roadmap.graph[NodeIndex::new(w[1])],
                        )
                    })
                    .sum();
                assert!((along - cost).abs() <= 1e-9 * cost.max(1.0));
            }
            (None, None) => {}
            (found, best) => panic!("{seed}: found {found:?}, Dijkstra {best:?}"),
        }
    }
}
