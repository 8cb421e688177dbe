//! Visibility-graph roadmap with Dijkstra (SPEC 3.3, SEEDS.md §D).
//!
//! 1. Every obstacle piece is grown by the robot at the start's θ:
//!    `B ⊕ (−A)` ([`crate::geometry::minkowski`]); a disk robot is its
//!    circumscribed `arc_segments`-gon, a disk obstacle too (both
//!    conservative). For a point robot the pieces stay as they are, and
//!    segment obstacles stay walls without interior.
//! 2. The boundary of the union of the grown obstacles is computed
//!    ([`arrangement`]); its vertices (and the start and the goal) are the
//!    nodes, except those inside another grown obstacle or outside `bounds`.
//! 3. The visibility edges come from a rotational sweep ([`sweep`],
//!    O(n² log n)): the open segment between two nodes may touch the grown
//!    obstacles and run along their boundaries, not enter their interior;
//!    it may not cross a wall, nor pass from one side of the walls to the
//!    other through a wall vertex. A wall vertex is one graph node per
//!    sector between its walls, so that a path cannot turn round a wall
//!    vertex to the other side either (the validator's rule, SPEC 3.0).
//! 4. Dijkstra on the `petgraph` graph gives the shortest path;
//!    `cost` = `length`.

pub mod arrangement;
pub mod sweep;

use std::any::Any;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering as AtomicOrdering};
use std::time::Instant;

use petgraph::graph::{NodeIndex, UnGraph};
use rayon::prelude::*;

use crate::contract::layers;
use crate::contract::schema::{MetricSpec, ParamSpec, RobotKind, ValueSpec, num};
use crate::contract::{Limits, PlanArgs};
use crate::contract::{MetricValue, PlanOutcome};
use crate::contract::{Planner, Settings, Task};
use crate::geometry::cspace::ObstaclePieces;
use crate::geometry::minkowski::{c_obstacle_points, disk_polygon, minkowski_sum_points};
use crate::geometry::motion::edge_normals;
use crate::geometry::{
    Aabb, Config, ConvexPolygon, Point, RobotShape, TOUCH_EPS, World, angle_diff,
};
use crate::planners::deadline::Deadline;
use crate::planners::search::{Edge, Graph, SearchBuffers, best_first, undirected_successors};

/// `roadmap` in the registry.
pub static PLANNER: Planner = Planner {
    kind: "roadmap",
    summary: "visibility graph and Dijkstra",
    robots: &[RobotKind::Point, RobotKind::Disk, RobotKind::Polygon],
    params: &[ParamSpec::new(
        "arc_segments",
        ValueSpec::Number {
            min: 8.0,
            min_open: false,
            max: MAX_ARC_SEGMENTS as f64,
            integer: true,
        },
        num(DEFAULT_ARC_SEGMENTS as f64, "32"),
        "segments per full circle for grown disks",
    )],
    metrics: &[
        MetricSpec::num(
            "graph_nodes",
            "roadmap nodes (a wall vertex counts once per sector)",
        ),
        MetricSpec::num("graph_edges", "visibility edges"),
    ],
    limits: &["expansions", "time"],
    needs_goal: true,
    randomized: false,
    grids: true,
    time: false,
    check,
};

/// The settings of a `roadmap` plan.
#[derive(Clone, Debug)]
pub struct RoadmapSettings {
    /// Segments per full circle of a disk turned into a polygon, 8..=4096.
    pub arc_segments: usize,
}

fn check(args: &mut PlanArgs<'_>) -> Option<Box<dyn Settings>> {
    Some(Box::new(RoadmapSettings {
        arc_segments: args.num("arc_segments").round() as usize,
    }))
}

impl Settings for RoadmapSettings {
    fn plan(&self, task: &Task<'_>) -> PlanOutcome {
        plan(task, self)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

use arrangement::{Arrangement, Grown, PolygonIndex, WallIn, strictly_inside};
use sweep::{SweepBuffers, Visible};

/// Default segments per full circle for disks.
pub const DEFAULT_ARC_SEGMENTS: usize = 32;
/// The most `arc_segments` accepted (more would only cost memory).
pub const MAX_ARC_SEGMENTS: usize = 4096;
/// The most vertices of grown obstacles a roadmap is built over (the
/// construction is O(n² log n): about a minute at this size on two cores).
pub const MAX_VERTICES: usize = 25_000;
/// The most visibility edges a roadmap holds (memory: about 50 bytes each).
pub const MAX_EDGES: usize = 20_000_000;
/// The most visibility edges kept in the trace for drawing.
pub const MAX_TRACED_EDGES: usize = 200_000;

/// The thinnest robot a roadmap is built for: its obstacles grown by a
/// thinner one (a segment obstacle grown by a body a few `TOUCH_EPS` wide)
/// would be slivers that the arrangement, whose tolerance is `TOUCH_EPS`,
/// cannot tell from a seam or a touch, and a path could run through them.
pub const MIN_ROBOT_WIDTH: f64 = 1e-6; // 1000 TOUCH_EPS

/// The smallest width of `robot`'s body (its extent along the direction
/// where it is thinnest: an edge normal for a convex polygon), `None` for
/// a point.
fn robot_width(robot: &RobotShape) -> Option<f64> {
    match robot {
        RobotShape::Point => None,
        RobotShape::Disk(r) => Some(2.0 * r),
        // Along each edge normal, the largest projection less the smallest.
        RobotShape::Polygon(p) => edge_normals(&p.vertices)
            .map(|(n, high)| {
                let low = p
                    .vertices
                    .iter()
                    .map(|v| n.dot(&v.coords))
                    .fold(f64::INFINITY, f64::min);
                high - low
            })
            .reduce(f64::min),
    }
}

/// The obstacles grown by `robot` at orientation `theta`: convex polygons
/// with interior, and (point robot only) walls.
pub fn grow(
    world: &World,
    robot: &RobotShape,
    theta: f64,
    arc_segments: usize,
) -> (Vec<Grown>, Vec<WallIn>) {
    let pieces = ObstaclePieces::with_disk_sides(world, arc_segments);
    let robot_polygon = match robot {
        RobotShape::Point => None,
        RobotShape::Disk(r) => Some(ConvexPolygon {
            vertices: disk_polygon(Point::origin(), *r, arc_segments),
        }),
        RobotShape::Polygon(p) => Some(p.clone()),
    };
    let robot_theta = if matches!(robot, RobotShape::Polygon(_)) {
        theta
    } else {
        0.0
    };
    let mut polys = Vec::new();
    let mut walls = Vec::new();
    for piece in &pieces.pieces {
        let vertices = match &robot_polygon {
            Some(a) => c_obstacle_points(&piece.points, a, robot_theta),
            None => minkowski_sum_points(&piece.points, &[Point::origin()]),
        };
        match vertices.len() {
            0 | 1 => {}
            2 => walls.push(WallIn {
                a: vertices[0],
                b: vertices[1],
                obstacle: piece.obstacle,
            }),
            _ => polys.push(Grown {
                vertices,
                obstacle: piece.obstacle,
            }),
        }
    }
    (polys, walls)
}

/// Why a roadmap was not built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stopped {
    /// `limit time` was reached.
    Time,
    /// More than [`MAX_EDGES`] visibility edges.
    Edges,
}

/// A built roadmap: the arrangement, the visibility edges and the graph.
pub struct Roadmap {
    pub arrangement: Arrangement,
    pub visible: Vec<Visible>,
    /// One node per (point, sector), weighted by length.
    pub graph: UnGraph<(u32, u32), f64>,
    /// Per point, its first graph node (`u32::MAX` for points that are not
    /// nodes).
    base: Vec<u32>,
}

impl Roadmap {
    /// Builds the roadmap among `polys` and `walls` for the path from
    /// `start` to `goal`; `Err` when `deadline` passed first, or the graph
    /// grew beyond [`MAX_EDGES`].
    pub fn build(
        polys: &[Grown],
        walls: &[WallIn],
        start: Point,
        goal: Point,
        bounds: crate::geometry::Aabb,
        deadline: Option<Instant>,
    ) -> Result<Roadmap, Stopped> {
        let arrangement = arrangement::build(polys, walls, start, goal, bounds, TOUCH_EPS);
        let arr = &arrangement;
        let nodes: Vec<u32> = (0..arr.points.len() as u32)
            .filter(|&p| arr.is_node[p as usize])
            .collect();
        let stop = AtomicBool::new(false);
        let too_many = AtomicBool::new(false);
        let edges = AtomicUsize::new(0);
        let per_node: Vec<Vec<Visible>> = nodes
            .par_iter()
            .map_init(
                || SweepBuffers::new(arr),
                |buf, &v| {
                    let mut out = Vec::new();
                    if stop.load(AtomicOrdering::Relaxed) {
                        return out;
                    }
                    if deadline.is_some_and(|d| Instant::now() > d) {
                        stop.store(true, AtomicOrdering::Relaxed);
                        return out;
                    }
                    sweep::sweep(arr, v, buf, &mut out);
                    if edges.fetch_add(out.len(), AtomicOrdering::Relaxed) + out.len() > MAX_EDGES {
                        too_many.store(true, AtomicOrdering::Relaxed);
                        stop.store(true, AtomicOrdering::Relaxed);
                    }
                    out
                },
            )
            .collect();
        if too_many.load(AtomicOrdering::Relaxed) {
            return Err(Stopped::Edges);
        }
        if stop.load(AtomicOrdering::Relaxed) {
            return Err(Stopped::Time);
        }
        let visible: Vec<Visible> = per_node
            .into_iter()
            .flatten()
            .filter(|e| arr.along_cut_edge(e.a, e.b) != Some(false))
            .collect();
        let mut graph = UnGraph::with_capacity(nodes.len(), visible.len());
        let mut base = vec![u32::MAX; arr.points.len()];
        for &p in &nodes {
            base[p as usize] = graph.node_count() as u32;
            for s in 0..arr.sector_count(p) {
                graph.add_node((p, s as u32));
            }
        }
        for e in &visible {
            let w = (arr.points[e.b as usize] - arr.points[e.a as usize]).norm();
            for &(sa, sb) in &e.links {
                graph.add_edge(
                    NodeIndex::new((base[e.a as usize] + sa) as usize),
                    NodeIndex::new((base[e.b as usize] + sb) as usize),
                    w,
                );
            }
        }
        Ok(Roadmap {
            arrangement,
            visible,
            graph,
            base,
        })
    }

    /// The graph nodes of point `p` (its sectors).
    fn nodes_of(&self, p: u32) -> impl Iterator<Item = NodeIndex> + '_ {
        let b = self.base[p as usize];
        let n = if b == u32::MAX {
            0
        } else {
            self.arrangement.sector_count(p)
        };
        (0..n).map(move |s| NodeIndex::new((b as usize) + s))
    }

    /// Dijkstra from the start's nodes to any of the goal's: the path as
    /// points, its length and the nodes expanded; `Err(expanded)` when
    /// `max_expansions` was reached first.
    pub fn shortest_path(
        &self,
        max_expansions: Option<u64>,
    ) -> Result<Option<(Vec<Point>, f64, u64)>, u64> {
        self.shortest_path_within(&Limits {
            expansions: max_expansions,
            ..Limits::default()
        })
    }

    /// [`Roadmap::shortest_path`] under `limits` (`expansions`, and `time`
    /// in seconds from the call).
    pub fn shortest_path_within(
        &self,
        limits: &Limits,
    ) -> Result<Option<(Vec<Point>, f64, u64)>, u64> {
        let arr = &self.arrangement;
        let starts: Vec<usize> = self.nodes_of(arr.start).map(|s| s.index()).collect();
        let mut graph = Visibility(self);
        let r = best_first(
            &mut graph,
            &starts,
            limits,
            false,
            &mut SearchBuffers::default(),
        );
        if r.gave_up {
            return Err(r.expanded);
        }
        Ok(r.nodes.map(|nodes| {
            let mut points: Vec<Point> = nodes
                .iter()
                .map(|&i| arr.points[self.graph[NodeIndex::new(i)].0 as usize])
                .collect();
            points.dedup();
            (points, r.cost, r.expanded)
        }))
    }
}

/// The visibility graph for the search core: Dijkstra (h = 0) to any node
/// of the goal.
struct Visibility<'r>(&'r Roadmap);

impl Graph for Visibility<'_> {
    fn node_count(&self) -> usize {
        self.0.graph.node_count()
    }

    fn successors(&mut self, node: usize, out: &mut Vec<Edge>) {
        undirected_successors(&self.0.graph, node, |w| *w, out);
    }

    fn heuristic(&self, _: usize) -> f64 {
        0.0
    }

    fn is_goal(&self, node: usize) -> bool {
        self.0.graph[NodeIndex::new(node)].0 == self.0.arrangement.goal
    }
}

/// Runs a `roadmap` plan.
pub fn plan(task: &Task<'_>, settings: &RoadmapSettings) -> PlanOutcome {
    let deadline = Deadline::start(&task.limits);
    let (world, robot) = (task.world, task.robot);
    let mut out = PlanOutcome::default();
    // Zero until a graph is built (every early return keeps the metrics).
    out.extra
        .insert("graph_nodes".into(), MetricValue::Num(0.0));
    out.extra
        .insert("graph_edges".into(), MetricValue::Num(0.0));
    if task.start_is_goal() {
        return PlanOutcome {
            extra: out.extra,
            ..PlanOutcome::at_goal(task.start)
        };
    }
    // The schema keeps it in 8..=MAX_ARC_SEGMENTS.
    let arc = settings.arc_segments.clamp(8, MAX_ARC_SEGMENTS);
    let start = task.start;
    let goal = task.goal.unwrap_or(start);
    if robot.rotates() && angle_diff(start.theta, goal.theta).abs() > 1e-12 {
        out.notes.push(
            "the roadmap robot only translates (at the start's θ): give the goal the start's θ"
                .into(),
        );
        return out;
    }
    if let Some(width) = robot_width(robot)
        && width < MIN_ROBOT_WIDTH
    {
        out.notes.push(format!(
            "the robot is {width:e} wide, thinner than the {MIN_ROBOT_WIDTH:e} a roadmap resolves (the obstacles it grows would be slivers the visibility test cannot see): use a `point` robot, or one at least {MIN_ROBOT_WIDTH:e} wide"
        ));
        return out;
    }
    let (polys, walls) = grow(world, robot, start.theta, arc);
    let vertices: usize = polys.iter().map(|p| p.vertices.len()).sum::<usize>() + 2 * walls.len();
    if vertices > MAX_VERTICES {
        out.notes.push(format!(
            "the grown obstacles have {vertices} vertices, more than the {MAX_VERTICES} a roadmap is built over"
        ));
        return out;
    }
    if task.draw {
        out.layers.extend(layers::grown(
            polys.iter().map(|p| p.vertices.clone()).collect(),
        ));
    }
    // The analyzer refused poses in collision with the true obstacles; the
    // grown disks are a little larger (circumscribed polygons).
    if !polys.is_empty() {
        let extent = polys
            .iter()
            .map(|p| Aabb::around(&p.vertices))
            .fold(world.bounds, |a, b| {
                Aabb::around(&[a.min, a.max, b.min, b.max])
            });
        let index = PolygonIndex::new(&polys, extent, TOUCH_EPS);
        for (which, c) in [("start", start), ("goal", goal)] {
            if let Some(i) = index.inside(c.xy(), None) {
                debug_assert!(strictly_inside(&polys[i].vertices, c.xy(), TOUCH_EPS));
                out.notes.push(format!(
                    "the {which} lies inside obstacle `{}` grown by the robot (disks are circumscribed {arc}-gons): move it away or raise `arc_segments`",
                    world.obstacles[polys[i].obstacle].name
                ));
                out.extra
                    .insert("graph_nodes".into(), MetricValue::Num(0.0));
                out.extra
                    .insert("graph_edges".into(), MetricValue::Num(0.0));
                return out;
            }
        }
    }
    let roadmap = match Roadmap::build(
        &polys,
        &walls,
        start.xy(),
        goal.xy(),
        world.bounds,
        deadline.instant(),
    ) {
        Ok(r) => r,
        Err(Stopped::Time) => {
            out.gave_up = true;
            out.notes
                .push("the time limit was reached while building the roadmap".into());
            return out;
        }
        Err(Stopped::Edges) => {
            out.notes.push(format!(
                "the roadmap would have more than {MAX_EDGES} visibility edges: simplify the world"
            ));
            return out;
        }
    };
    out.extra.insert(
        "graph_nodes".into(),
        MetricValue::Num(roadmap.graph.node_count() as f64),
    );
    out.extra.insert(
        "graph_edges".into(),
        MetricValue::Num(roadmap.graph.edge_count() as f64),
    );
    if task.draw {
        let pts = &roadmap.arrangement.points;
        let edges = roadmap
            .visible
            .iter()
            .take(MAX_TRACED_EDGES)
            .map(|e| (pts[e.a as usize], pts[e.b as usize]))
            .collect();
        out.layers.extend(layers::graph("roadmap", edges));
    }
    match roadmap.shortest_path_within(&deadline.remaining(task.limits)) {
        Err(expanded) => {
            out.expanded = expanded;
            out.gave_up = true;
            out.notes.push(
                if task.limits.expansions.is_some_and(|max| expanded >= max) {
                    "the expansion limit was reached before the goal"
                } else {
                    "the time limit was reached before the goal"
                }
                .into(),
            );
        }
        Ok(None) => {}
        Ok(Some((points, length, expanded))) => {
            out.expanded = expanded;
            let mut path: Vec<Config> = points
                .iter()
                .map(|p| Config::new(p.x, p.y, start.theta))
                .collect();
            if path.len() == 1 {
                path.push(goal);
            }
            path[0] = start;
            if let Some(last) = path.last_mut() {
                *last = goal;
            }
            out.cost = Some(length);
            out.path = Some(path);
        }
    }
    out
}

#[cfg(test)]
mod tests;
