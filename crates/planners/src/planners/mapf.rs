//! What the grid MAPF planners (SPEC 2.10, 3.11) share: the team's graph
//! — the lattice of cell centres at spacing `cell`, 4-neighbour moves the
//! motion checker allows — its agents' start and goal nodes, and distances
//! by breadth-first search.

use std::collections::VecDeque;

use crate::contract::schema::{DefaultValue, ParamSpec, ValueSpec};
use crate::contract::{PlanArgs, Task};
use crate::diagnostics::Diag;
use crate::geometry::Point;
use crate::geometry::collide::ObstacleIndex;
use crate::planners::deadline::Deadline;
use crate::planners::grid_lattice::GridLattice;
use crate::planners::lattice::{LATTICE_PARAMS, LatticeSpec, Sample, check_lattice_of};

/// A node of the graph (a lattice point's index).
pub type Node = u32;

/// No node (a missing neighbour).
pub const NONE: Node = Node::MAX;

/// A hasher for the team searches' small integer keys (points, steps):
/// the multiply-rotate of rustc's FxHash, several times faster there than
/// the standard SipHash, whose resistance to chosen keys these keys do not
/// need.
#[derive(Clone, Copy, Default)]
pub struct FastHasher(u64);

impl std::hash::Hasher for FastHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_u32(&mut self, n: u32) {
        self.write_u64(u64::from(n));
    }

    fn write_usize(&mut self, n: usize) {
        self.write_u64(n as u64);
    }

    fn write_u64(&mut self, n: u64) {
        self.0 = (self.0.rotate_left(5) ^ n).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// A hash map with [`FastHasher`].
pub type FastMap<K, V> = std::collections::HashMap<K, V, std::hash::BuildHasherDefault<FastHasher>>;
/// A hash set with [`FastHasher`].
pub type FastSet<K> = std::collections::HashSet<K, std::hash::BuildHasherDefault<FastHasher>>;

/// `agents N`: the team's first N agents are planned (its first N rows of
/// a MovingAI `.scen` file), so that a bench may `vary agents [...]` for a
/// success rate by agent count; every team planner takes it.
pub const AGENTS: ParamSpec = ParamSpec::new(
    "agents",
    ValueSpec::IntOrWord(&["all"]),
    DefaultValue::Word("all"),
    "plan the team's first N agents; `all`: every agent",
);

/// The parameters every grid MAPF planner takes: `cell`, `agents`.
pub const MAPF_PARAMS: [ParamSpec; 2] = [LATTICE_PARAMS[0], AGENTS];

/// The agents `agents N` plans, checked: at most the team's size (an error
/// at the value otherwise).
pub fn check_agents(args: &mut PlanArgs<'_>) -> Option<usize> {
    let size = args.robot.team.as_ref().map_or(0, |t| t.len());
    let Some(n) = args.opt_num("agents") else {
        return Some(size);
    };
    if n > size as f64 {
        let (plan, team) = (args.plan, args.robot.name.clone());
        let span = args.span("agents");
        args.error(
            Diag::error(
                "scen::analyze::too_many_agents",
                format!("plan `{plan}`: `agents {n}`, but team `{team}` has {size} agent(s)"),
            )
            .at(span, "more agents than the team has")
            .help(format!("plan at most {size} agents, or `agents all`")),
        );
        return None;
    }
    Some(n as usize)
}

/// A grid MAPF plan's lattice, checked: the cap, a point team, agents on
/// lattice points (each error at its agent's row).
pub fn check_mapf_lattice(args: &mut PlanArgs<'_>) -> Option<LatticeSpec> {
    let spec = check_lattice_of(args, Sample::Center, 1.0)?;
    let robot = args.robot;
    if !matches!(robot.shape, crate::geometry::RobotShape::Point) {
        let (plan, kind) = (args.plan, args.planner().kind);
        args.error(
            Diag::error(
                "scen::analyze::robot_kind",
                format!("plan `{plan}`: `{kind}` plans teams of `point` agents (grid MAPF)"),
            )
            .at(robot.span, "a team of bodies")
            .help("declare the team `team NAME point { ... }`; teams of bodies are planned by `prioritized`"),
        );
        return None;
    }
    let count = check_agents(args)?;
    let agents = robot.team.clone().unwrap_or_else(|| Vec::new().into());
    for a in agents.iter().take(count) {
        for (what, p) in [("start", a.start), ("goal", a.goal)] {
            if node_at(&spec, p).is_none() {
                let near = spec.point_of(nearest(&spec, p));
                args.error(
                    Diag::error(
                        "scen::analyze::off_lattice",
                        format!(
                            "agent `{}`'s {what} ({}, {}) is not a cell centre of plan `{}`'s lattice",
                            a.name, p.x, p.y, args.plan
                        ),
                    )
                    .at(a.span, format!("its {what}"))
                    .help(format!(
                        "grid MAPF moves agents between cell centres (`cell {}` from the bounds' corner); the nearest is ({}, {})",
                        spec.cell, near.x, near.y
                    )),
                );
            }
        }
    }
    Some(spec)
}

/// The lattice point at `p`, when `p` is one (within 1e-9 of a cell).
pub fn node_at(spec: &LatticeSpec, p: Point) -> Option<usize> {
    let first = Point::new(spec.x0, spec.y0);
    crate::geometry::team::lattice_index(first, spec.cell, spec.nx, spec.ny, p)
}

fn nearest(spec: &LatticeSpec, p: Point) -> usize {
    let clamp = |f: f64, n: usize| (f.round().max(0.0) as usize).min(n.saturating_sub(1));
    spec.index(
        clamp((p.x - spec.x0) / spec.cell, spec.nx),
        clamp((p.y - spec.y0) / spec.cell, spec.ny),
    )
}

/// The most distances (4 bytes each) a team's tables of distances to the
/// goals may hold: 4 GiB.
pub const MAX_DISTANCES: usize = 1 << 30;

/// A note when `agents` tables of distances over `graph` would pass
/// [`MAX_DISTANCES`]: such a team is given up before its tables exhaust
/// the memory.
pub fn too_many_distances(graph: &Graph, agents: usize) -> Option<String> {
    let cells = graph.adj.len();
    (cells.saturating_mul(agents) > MAX_DISTANCES).then(|| {
        format!(
            "{agents} agents on {cells} lattice points would need {:.1} GiB of distance tables (at most 4 GiB): use fewer agents or a coarser `cell`",
            (cells as f64) * (agents as f64) * 4.0 / f64::from(1u32 << 30)
        )
    })
}

/// The team's graph: each free node's 4-neighbours it may move to.
pub struct Graph {
    pub spec: LatticeSpec,
    /// Per node, up to four neighbours ([`NONE`] where there is none).
    pub adj: Vec<[Node; 4]>,
    pub free: Vec<bool>,
    pub starts: Vec<Node>,
    pub goals: Vec<Node>,
}

impl Graph {
    /// The graph of `task`'s world for its agents; `Err` with a note when
    /// the deadline passes while it is built or an agent stands off it.
    pub fn build(task: &Task<'_>, spec: LatticeSpec, deadline: &Deadline) -> Result<Self, String> {
        let index = ObstacleIndex::new(task.world);
        let Some(mut lat) = GridLattice::build_until(spec, &index, 0.0, deadline) else {
            return Err(crate::planners::deadline::setup_note(
                "classifying the lattice",
            ));
        };
        let n = spec.layer_len();
        let mut adj = vec![[NONE; 4]; n];
        let mut free = vec![false; n];
        for (v, slot) in adj.iter_mut().enumerate() {
            if v % crate::planners::deadline::SETUP_CHECK_EVERY == 0 && deadline.passed() {
                return Err(crate::planners::deadline::setup_note(
                    "connecting the lattice",
                ));
            }
            if !lat.free.get(v) {
                continue;
            }
            free[v] = true;
            let mut k = 0;
            for d in 0..4 {
                if let Some(m) = lat.neighbour(v, d)
                    && lat.edge_usable(&index, v, d, m)
                {
                    slot[k] = m as Node;
                    k += 1;
                }
            }
        }
        let mut starts = Vec::with_capacity(task.agents.len());
        let mut goals = Vec::with_capacity(task.agents.len());
        for a in task.agents {
            for (p, out) in [(a.start, &mut starts), (a.goal, &mut goals)] {
                match node_at(&spec, p).filter(|&v| free[v]) {
                    Some(v) => out.push(v as Node),
                    None => {
                        return Err(format!(
                            "agent `{}` stands at ({}, {}), not a free cell centre",
                            a.name, p.x, p.y
                        ));
                    }
                }
            }
        }
        Ok(Graph {
            spec,
            adj,
            free,
            starts,
            goals,
        })
    }

    /// The neighbours of `v`.
    pub fn neighbours(&self, v: Node) -> impl Iterator<Item = Node> + '_ {
        self.adj[v as usize]
            .iter()
            .copied()
            .take_while(|&m| m != NONE)
    }

    /// Steps from every node to `goal` ([`u32::MAX`]: never).
    pub fn distances_to(&self, goal: Node) -> Vec<u32> {
        let mut dist = vec![u32::MAX; self.adj.len()];
        dist[goal as usize] = 0;
        let mut queue = VecDeque::from([goal]);
        while let Some(v) = queue.pop_front() {
            let d = dist[v as usize] + 1;
            for m in self.neighbours(v) {
                if dist[m as usize] == u32::MAX {
                    dist[m as usize] = d;
                    queue.push_back(m);
                }
            }
        }
        dist
    }

    /// The world point of `v`.
    pub fn point(&self, v: Node) -> Point {
        self.spec.point_of(v as usize)
    }
}

/// Random small teams for the grid MAPF planners' tests.
#[cfg(test)]
pub(crate) mod cases {
    use std::collections::HashSet;

    use crate::contract::{Agent, Limits, Task};
    use crate::diagnostics::Span;
    use crate::geometry::fixtures::{grid, world_in};
    use crate::geometry::rng::SplitMix64;
    use crate::geometry::{Aabb, Config, Point, RobotShape, World};

    /// A map of `min` to `min + spread − 1` cells a side, each cell a wall
    /// with chance 1/`wall_one_in`, and `n` agents (fewer when the map has
    /// fewer free cells) on distinct free starts and distinct free goals.
    pub fn random_team(
        seed: u64,
        n: usize,
        min: usize,
        spread: u64,
        wall_one_in: u64,
    ) -> (World, Vec<Agent>) {
        let mut rng = SplitMix64::new(seed);
        let w = min + (rng.next_u64() % spread) as usize;
        let h = min + (rng.next_u64() % spread) as usize;
        let rows: Vec<String> = (0..h)
            .map(|_| {
                (0..w)
                    .map(|_| {
                        if rng.next_u64().is_multiple_of(wall_one_in) {
                            '#'
                        } else {
                            '.'
                        }
                    })
                    .collect()
            })
            .collect();
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        let p = Point::new;
        let world = world_in(
            Aabb::from_corners(p(0.0, 0.0), p(w as f64, h as f64)),
            vec![grid(1.0, p(0.0, 0.0), &refs)],
        );
        // Free cells as world points (row 0 of the map is the top).
        let free: Vec<Point> = (0..h)
            .flat_map(|r| (0..w).map(move |c| (r, c)))
            .filter(|&(r, c)| rows[r].as_bytes()[c] == b'.')
            .map(|(r, c)| p(c as f64 + 0.5, (h - 1 - r) as f64 + 0.5))
            .collect();
        let mut pick = |taken: &mut HashSet<usize>| loop {
            let k = rng.next_u64() as usize % free.len();
            if taken.insert(k) {
                return free[k];
            }
        };
        let (mut starts, mut goals) = (HashSet::new(), HashSet::new());
        let agents = (0..n.min(free.len()))
            .map(|i| Agent {
                name: format!("a{i}"),
                start: pick(&mut starts),
                goal: pick(&mut goals),
                span: Span::default(),
            })
            .collect();
        (world, agents)
    }

    /// Every conflict-free joint step of a team at `pos` on the referee's
    /// grid `g`, the agents of `moving` each waiting or moving to a free
    /// 4-neighbour, the others staying: no two agents on one point, no two
    /// swapping (for the joint-space searches the planners are tested
    /// against).
    pub fn joint_steps(
        g: &crate::geometry::team::TeamGrid,
        pos: &[usize],
        moving: &[usize],
    ) -> Vec<Vec<usize>> {
        let options: Vec<Vec<usize>> = moving
            .iter()
            .map(|&a| {
                std::iter::once(pos[a])
                    .chain(g.moves_from(pos[a]))
                    .collect()
            })
            .collect();
        let n = pos.len();
        let mut steps = Vec::new();
        let mut choice = vec![0usize; moving.len()];
        'joint: loop {
            let mut next = pos.to_vec();
            for (k, &a) in moving.iter().enumerate() {
                next[a] = options[k][choice[k]];
            }
            let ok = (0..n).all(|a| {
                (a + 1..n).all(|b| next[a] != next[b] && !(next[a] == pos[b] && next[b] == pos[a]))
            });
            if ok {
                steps.push(next);
            }
            for k in 0..moving.len() {
                choice[k] += 1;
                if choice[k] < options[k].len() {
                    continue 'joint;
                }
                choice[k] = 0;
            }
            return steps;
        }
    }

    /// The task of a point team in `world`.
    pub fn team_task<'a>(
        world: &'a World,
        agents: &'a [Agent],
        limits: Limits,
        seed: u64,
    ) -> Task<'a> {
        let first = agents[0].start;
        Task {
            world,
            robot: &RobotShape::Point,
            start: Config::new(first.x, first.y, 0.0),
            goal: None,
            limits,
            seed,
            steering: None,
            draw: false,
            referee: None,
            moving: &[],
            speed: None,
            agents,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contract::Limits;
    use crate::planners::deadline::Deadline;
    use crate::planners::lattice::{LatticeSpec, Sample};

    /// A team whose distance tables would pass 4 GiB is refused up front:
    /// as many agents as the budget holds on a lattice pass, one more not.
    #[test]
    fn distance_tables_have_a_budget() {
        let (world, agents) = cases::random_team(1, 2, 4, 1, 1000);
        let task = cases::team_task(&world, &agents, Limits::default(), 0);
        let graph = Graph::build(
            &task,
            LatticeSpec::new(&world, 1.0, Sample::Center, 1.0),
            &Deadline::never(),
        )
        .expect("a graph");
        assert!(too_many_distances(&graph, 2).is_none());
        assert!(too_many_distances(&graph, MAX_DISTANCES / graph.adj.len()).is_none());
        let note =
            too_many_distances(&graph, MAX_DISTANCES / graph.adj.len() + 1).expect("refused");
        assert!(note.contains("distance tables"), "{note}");
    }
}
