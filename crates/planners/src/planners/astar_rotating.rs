//! `astar` (SPEC 3.1) for convex polygon robots: A* on the (x, y, θ)
//! lattice (or on the (x, y) lattice at the start's θ with `rotate no`).
//!
//! # Lattice
//! x and y as in `sample` ([`LatticeSpec`]); θ_k = k·2π/N for the N layers
//! (`rotate no`: one layer at the start's θ). A configuration is free when
//! its (x, y) is not in the interior of a C-obstacle of its layer
//! ([`CLayer::contains_interior`]).
//!
//! # Moves
//! A move is (dx, dy, dk) in lattice steps; `connect 6` has ±x, ±y, ±θ,
//! `connect 26` the whole 3×3×3 block minus the centre, `connect 4` / `8`
//! (`rotate no`) the (x, y) moves of one layer. θ wraps (layer N−1
//! neighbours layer 0). No corner cutting: a move with dx ≠ 0 and dy ≠ 0
//! needs (x+dx, y) and (x, y+dy) free in the start layer k *and* in the end
//! layer k+dk.
//!
//! # Sound edges
//! An edge is used only if the robot's motion along it passes the validator
//! (SPEC 3.0), decided lazily when the search first relaxes it (each
//! configuration is expanded once, so each edge and direction is decided
//! at most once and nothing needs caching):
//! * a translation within a layer: the segment between the two (x, y)
//!   points must not penetrate any C-obstacle of the layer deeper than
//!   `TOUCH_EPS / 2` ([`segment_depth`], separating axes over the
//!   C-obstacle's edges and the segment's normal). The penetration depth of
//!   the segment into `B ⊕ (−A(θ))` equals that of the swept body (the hull
//!   of the robot's two end bodies) into `B`, which is what the validator
//!   measures; the halved threshold absorbs rounding.
//! * a rotation (alone or with a translation): the planners' motion
//!   checker ([`MotionChecker::motion_free`]), which accepts what the
//!   validator accepts on the 2-configuration path, up to rounding.

use std::f64::consts::TAU;
use std::time::{Duration, Instant};

use super::astar_settings::Astar;
use super::deadline::{Deadline, setup_note};
use super::lattice::{BitSet, LatticeDistance, LatticeSpec};
use super::lattice::{CostMetric, Heuristic};
use super::search::{Edge, Graph, SearchBuffers, best_first};
use crate::contract::Task;
use crate::contract::{MetricValue, PlanOutcome};
use crate::geometry::angle_diff;
use crate::geometry::cspace::{CLayer, ObstaclePieces, layer_angle};
use crate::geometry::motion::{MotionChecker, segment_depth};
use crate::geometry::{Aabb, Config, ConvexPolygon, Point, TOUCH_EPS};
use rayon::prelude::*;

/// The most C-obstacle outlines drawn over all layers; beyond it (e.g.
/// large grids) layers are left out of the picture, not the search.
pub const MAX_TRACED_C_OBSTACLES: usize = 200_000;

/// One lattice move.
#[derive(Clone, Copy, Debug)]
struct Move {
    dx: i64,
    dy: i64,
    dk: i64,
    /// In the cost metric.
    cost: f64,
    /// What the search counts: `cost`, or with the lattice heuristic
    /// `cost` rounded to its quantum ([`LatticeDistance`]).
    search_cost: f64,
}

/// The moves of a `connect` value on a lattice of `layers` layers. A move
/// in θ exists only for N ≥ 2; for N = 2, +1 and −1 reach the same layer
/// by the same motion (a half turn, +π along [`angle_diff`]), so only +1
/// is kept.
fn moves(connect: u8, layers: usize, rotating: bool) -> Vec<(i64, i64, i64)> {
    let mut out = Vec::new();
    let full = matches!(connect, 8 | 26);
    for dk in [0i64, 1, -1] {
        if dk != 0 && (!rotating || layers < 2 || (layers == 2 && dk == -1)) {
            continue;
        }
        for (dx, dy) in [
            (0i64, 0i64),
            (1, 0),
            (0, 1),
            (-1, 0),
            (0, -1),
            (1, 1),
            (-1, 1),
            (-1, -1),
            (1, -1),
        ] {
            if dx == 0 && dy == 0 && dk == 0 {
                continue;
            }
            let axes = usize::from(dx != 0) + usize::from(dy != 0) + usize::from(dk != 0);
            if axes > 1 && !full {
                continue;
            }
            out.push((dx, dy, dk));
        }
    }
    out
}

fn boxes_meet(a: &Aabb, b: &Aabb, margin: f64) -> bool {
    a.min.x <= b.max.x + margin
        && b.min.x <= a.max.x + margin
        && a.min.y <= b.max.y + margin
        && b.min.y <= a.max.y + margin
}

/// Where the time of one plan went (for benchmarks: timing every edge
/// check costs time, so only [`plan_profiled`] measures).
#[derive(Clone, Copy, Debug, Default)]
pub struct Profile {
    /// Building the C-obstacles of every layer.
    pub cspace: Duration,
    /// The drawing trace of the C-space (union outlines per layer).
    pub trace: Duration,
    /// Classifying every lattice configuration free or blocked.
    pub classify: Duration,
    /// The search, edge validation included.
    pub search: Duration,
    /// The part of `search` spent validating edges.
    pub edge_validation: Duration,
    /// Edges validated (each at most once).
    pub edges_checked: u64,
}

/// The (x, y, θ) lattice of one plan and its free configurations (a bit
/// each).
struct Lattice {
    spec: LatticeSpec,
    thetas: Vec<f64>,
    layers: Vec<CLayer>,
    /// Per layer, the bounding box of each C-obstacle.
    layer_boxes: Vec<Vec<Aabb>>,
    /// Decides the rotation edges.
    motion: MotionChecker,
    free: BitSet,
    moves: Vec<Move>,
    /// Measure edge validation into `profile` (see [`plan_profiled`]).
    profiling: bool,
    profile: Profile,
}

impl Lattice {
    fn layer_len(&self) -> usize {
        self.spec.layer_len()
    }

    fn coords(&self, node: usize) -> (usize, usize, usize) {
        let n = self.layer_len();
        let (i, j) = self.spec.coords(node % n);
        (i, j, node / n)
    }

    fn config(&self, node: usize) -> Config {
        let (i, j, k) = self.coords(node);
        let p = self.spec.point(i, j);
        Config::new(p.x, p.y, self.thetas[k])
    }

    /// Whether the translation from `p` to `q` in layer `k` passes.
    fn translation_free(&self, k: usize, p: Point, q: Point) -> bool {
        let seg = Aabb::around(&[p, q]);
        let layer = &self.layers[k];
        layer
            .c_obstacles
            .iter()
            .zip(&self.layer_boxes[k])
            .all(|(c, b)| {
                !boxes_meet(b, &seg, 0.0) || segment_depth(p, q, &c.vertices) <= 0.5 * TOUCH_EPS
            })
    }

    /// Whether the edge along move `m` from `node` to `to` is usable.
    fn edge_free(&mut self, node: usize, m: usize, to: usize) -> bool {
        let began = self.profiling.then(Instant::now);
        let (a, b) = (self.config(node), self.config(to));
        let ok = if self.moves[m].dk == 0 {
            let (_, _, k) = self.coords(node);
            self.translation_free(k, a.xy(), b.xy())
        } else {
            self.motion.motion_free(a, b)
        };
        if let Some(t) = began {
            self.profile.edge_validation += t.elapsed();
            self.profile.edges_checked += 1;
        }
        ok
    }

    /// The move from `a` to its neighbour `b`.
    fn move_between(&self, a: usize, b: usize) -> Option<&Move> {
        let ((i, j, k), (ni, nj, nk)) = (self.coords(a), self.coords(b));
        let n = self.layers.len() as i64;
        let (dx, dy) = (ni as i64 - i as i64, nj as i64 - j as i64);
        self.moves
            .iter()
            .find(|m| m.dx == dx && m.dy == dy && (k as i64 + m.dk).rem_euclid(n) == nk as i64)
    }
}

/// Runs an `astar` plan for a convex polygon robot.
pub fn plan(task: &Task<'_>, settings: &Astar, robot: &ConvexPolygon) -> PlanOutcome {
    run(task, settings, robot, false).0
}

/// [`plan`], measuring where the time goes (for benchmarks).
pub fn plan_profiled(
    task: &Task<'_>,
    settings: &Astar,
    robot: &ConvexPolygon,
) -> (PlanOutcome, Profile) {
    run(task, settings, robot, true)
}

fn run(
    task: &Task<'_>,
    settings: &Astar,
    robot: &ConvexPolygon,
    profiling: bool,
) -> (PlanOutcome, Profile) {
    let deadline = Deadline::start(&task.limits);
    let world = task.world;
    let mut profile = Profile::default();
    let rotating = settings.rotating;
    let spec = settings.lattice;
    let start = task.start;
    let goal = task.goal.unwrap_or(start);
    let n_layers = spec.layers.max(1);
    let thetas: Vec<f64> = if rotating {
        (0..n_layers).map(|k| layer_angle(k, n_layers)).collect()
    } else {
        vec![start.theta]
    };
    let cost = settings.cost;
    let turn_cost = settings.turn_cost;
    let weight = settings.weight;
    let connect = settings.connect;
    let step = if rotating { TAU / n_layers as f64 } else { 0.0 };
    // The rotation of |dk| = 1: the shorter arc (π for two layers).
    let dtheta = step.min(TAU - step);
    let cell = spec.cell;
    let distance = LatticeDistance::new(connect, cost, cell, turn_cost * dtheta);
    let moves: Vec<Move> = moves(connect, n_layers, rotating)
        .into_iter()
        .map(|(dx, dy, dk)| {
            let true_cost = cost.of(
                dx as f64 * cell,
                dy as f64 * cell,
                turn_cost * dk.abs() as f64 * dtheta,
            );
            let axes = usize::from(dx != 0) | usize::from(dy != 0) << 1 | usize::from(dk != 0) << 2;
            Move {
                dx,
                dy,
                dk,
                cost: true_cost,
                search_cost: match settings.heuristic {
                    Heuristic::Lattice => distance.step(axes),
                    Heuristic::Metric | Heuristic::Zero => true_cost,
                },
            }
        })
        .collect();

    let mut out = PlanOutcome::default();
    out.extra
        .insert("cells".into(), MetricValue::Num(spec.cells_f64()));
    out.extra
        .insert("layers".into(), MetricValue::Num(thetas.len() as f64));
    // Until the lattice is classified (and for good when nothing is built).
    out.extra.insert("free_cells".into(), MetricValue::Num(0.0));
    out.extra.insert("generated".into(), MetricValue::Num(0.0));
    if task.start_is_goal() {
        let out = PlanOutcome {
            extra: out.extra,
            ..PlanOutcome::at_goal(start)
        };
        return (out, profile);
    }
    let gave_up_in_setup = |mut out: PlanOutcome, what: &str| {
        out.gave_up = true;
        out.notes.push(setup_note(what));
        out
    };
    let lap = Instant::now();
    let pieces = ObstaclePieces::new(world);
    // Layer by layer, so that the clock is asked between layers.
    let layers: Option<Vec<CLayer>> = if rotating {
        (0..n_layers)
            .into_par_iter()
            .map(|k| (!deadline.passed()).then(|| pieces.layer(robot, layer_angle(k, n_layers))))
            .collect()
    } else {
        Some(vec![pieces.layer(robot, start.theta)])
    };
    profile.cspace = lap.elapsed();
    let Some(layers) = layers.filter(|_| !deadline.passed()) else {
        return (
            gave_up_in_setup(out, "building the C-space layers"),
            profile,
        );
    };
    let lap = Instant::now();
    if !task.draw {
        // Nothing will draw the C-space.
    } else if !rotating {
        let grown = layers[0]
            .c_obstacles
            .iter()
            .map(|c| c.vertices.clone())
            .collect();
        out.layers.extend(crate::contract::layers::grown(grown));
    } else if layers.iter().map(|l| l.c_obstacles.len()).sum::<usize>() <= MAX_TRACED_C_OBSTACLES {
        out.layers
            .extend(crate::contract::layers::cspace(world, &layers));
    }
    profile.trace = lap.elapsed();
    let lap = Instant::now();
    let n = spec.layer_len();
    let total = n * layers.len();
    let free = BitSet::from_fn_until(total, &deadline, |node| {
        !layers[node / n].contains_interior(spec.point_of(node % n))
    });
    profile.classify = lap.elapsed();
    let Some(free) = free else {
        return (gave_up_in_setup(out, "classifying the lattice"), profile);
    };
    let free_count = free.count_ones();
    out.extra
        .insert("free_cells".into(), MetricValue::Num(free_count as f64));
    let layer_boxes = layers
        .iter()
        .map(|l| {
            l.c_obstacles
                .iter()
                .map(|c| Aabb::around(&c.vertices))
                .collect()
        })
        .collect();
    let motion = task.motion_checker();
    let mut lat = Lattice {
        spec,
        thetas,
        layers,
        layer_boxes,
        motion,
        free,
        moves,
        profiling,
        profile: Profile::default(),
    };

    let (Some(s), Some(g)) = (spec.snap(start), spec.snap(goal)) else {
        out.notes
            .push("the lattice is empty: `cell` is larger than the bounds".into());
        return (out, profile);
    };
    let nearest_layer = |theta: f64| -> usize {
        if rotating {
            ((theta.rem_euclid(TAU) / step).round() as usize) % n_layers
        } else {
            0
        }
    };
    let s_node = nearest_layer(start.theta) * n + spec.index(s.0, s.1);
    let g_node = nearest_layer(goal.theta) * n + spec.index(g.0, g.1);
    let (s_cfg, g_cfg) = (lat.config(s_node), lat.config(g_node));
    let connects = |lat: &Lattice, a: Config, b: Config| lat.motion.motion_free(a, b);
    let mut blocked_end = None;
    if !lat.free.get(s_node) || !connects(&lat, start, s_cfg) {
        blocked_end = Some("start");
    } else if !lat.free.get(g_node) || !connects(&lat, g_cfg, goal) {
        blocked_end = Some("goal");
    }
    if let Some(end) = blocked_end {
        out.notes.push(format!(
            "the {end} could not be connected to its nearest lattice configuration: make `cell` smaller, use more `layers`, or move the {end}"
        ));
        return (out, profile);
    }
    // The cost of the motion between two configurations, in the metric.
    let cost_between = |a: Config, b: Config| {
        cost.of(
            b.x - a.x,
            b.y - a.y,
            turn_cost * angle_diff(a.theta, b.theta).abs(),
        )
    };

    // ------------------------------------------------------------ search
    let (_, _, gk) = lat.coords(g_node);
    let gpt = lat.config(g_node).xy();
    let heuristic = RotHeuristic {
        kind: settings.heuristic,
        distance: LatticeDistance::new(connect, cost, cell, turn_cost * dtheta),
        goal: gpt,
        goal_ij: (lat.coords(g_node).0, lat.coords(g_node).1),
        goal_layer: gk,
        layers: n_layers,
        step: if rotating { step } else { 0.0 },
        turn_cost,
        weight,
        cost,
    };
    let search_began = Instant::now();
    // `limit time` counts from the start of the plan.
    let limits = deadline.remaining(task.limits);
    let mut graph = RotGraph {
        lat: &mut lat,
        goal: g_node,
        h: heuristic,
    };
    let mut buf = SearchBuffers::default();
    let r = best_first(&mut graph, &[s_node], &limits, task.draw, &mut buf);
    out.expanded = r.expanded;
    out.gave_up = r.gave_up;
    if task.draw {
        let expanded_at: Vec<Point> = r
            .expansion_order
            .iter()
            .map(|&n| lat.config(n).xy())
            .collect();
        out.layers
            .extend(crate::contract::layers::search(&expanded_at));
    }
    out.extra
        .insert("generated".into(), MetricValue::Num(r.generated as f64));
    match r.nodes {
        Some(nodes) => {
            let mut path = vec![start];
            path.extend(nodes.iter().map(|&n| lat.config(n)));
            path.push(goal);
            path.dedup();
            // The lattice part in the true metric, summed in path order
            // (for the metric and zero heuristics the same sum as g).
            let lattice_cost = nodes.windows(2).fold(0.0, |sum, w| {
                sum + lat.move_between(w[0], w[1]).map_or(f64::NAN, |m| m.cost)
            });
            out.cost = Some(cost_between(start, s_cfg) + lattice_cost + cost_between(g_cfg, goal));
            out.path = Some(path);
        }
        None if r.gave_up => out.notes.push("a limit was reached before the goal".into()),
        None => {}
    }
    profile = Profile {
        search: search_began.elapsed(),
        edge_validation: lat.profile.edge_validation,
        edges_checked: lat.profile.edges_checked,
        ..profile
    };
    (out, profile)
}

/// The heuristic on the (x, y, θ) lattice, from a lattice configuration to
/// the goal's, θ the shorter way round, inflated by `weight`: the exact
/// obstacle-free lattice cost ([`LatticeDistance`]), the cost metric, or 0.
struct RotHeuristic {
    kind: Heuristic,
    distance: LatticeDistance,
    goal: Point,
    goal_ij: (usize, usize),
    goal_layer: usize,
    layers: usize,
    /// The rotation between neighbouring layers (0 without θ layers).
    step: f64,
    turn_cost: f64,
    weight: f64,
    cost: CostMetric,
}

impl RotHeuristic {
    fn at(&self, (i, j): (usize, usize), p: Point, k: usize) -> f64 {
        let dk = k.abs_diff(self.goal_layer);
        let dk = dk.min(self.layers - dk);
        let h = match self.kind {
            Heuristic::Lattice => self.distance.xyt([
                i.abs_diff(self.goal_ij.0) as u64,
                j.abs_diff(self.goal_ij.1) as u64,
                dk as u64,
            ]),
            Heuristic::Metric => {
                let dt = self.turn_cost * (dk as f64 * self.step).min(TAU - dk as f64 * self.step);
                self.cost.of(p.x - self.goal.x, p.y - self.goal.y, dt)
            }
            Heuristic::Zero => return 0.0,
        };
        self.weight * h
    }
}

/// The (x, y, θ) lattice as a graph for the search core.
struct RotGraph<'l> {
    lat: &'l mut Lattice,
    goal: usize,
    h: RotHeuristic,
}

impl Graph for RotGraph<'_> {
    fn node_count(&self) -> usize {
        self.lat.free.len()
    }

    fn successors(&mut self, node: usize, out: &mut Vec<Edge>) {
        let lat = &*self.lat;
        let spec = &lat.spec;
        let (nx, ny, nl) = (spec.nx as i64, spec.ny as i64, lat.layers.len() as i64);
        let at = |i: i64, j: i64, k: i64| (k * nx * ny + j * nx + i) as usize;
        let (i, j, k) = lat.coords(node);
        let (i, j, k) = (i as i64, j as i64, k as i64);
        for (m, mv) in lat.moves.iter().enumerate() {
            let (ni, nj) = (i + mv.dx, j + mv.dy);
            if ni < 0 || nj < 0 || ni >= nx || nj >= ny {
                continue;
            }
            let nk = (k + mv.dk).rem_euclid(nl);
            let to = at(ni, nj, nk);
            if !lat.free.get(to) {
                continue;
            }
            // No corner cutting, in the start and in the end layer.
            if mv.dx != 0
                && mv.dy != 0
                && !(lat.free.get(at(ni, j, k))
                    && lat.free.get(at(i, nj, k))
                    && lat.free.get(at(ni, j, nk))
                    && lat.free.get(at(i, nj, nk)))
            {
                continue;
            }
            out.push(Edge {
                to,
                cost: mv.search_cost,
                label: m as u32,
            });
        }
    }

    fn usable(&mut self, from: usize, label: u32, to: usize) -> bool {
        self.lat.edge_free(from, label as usize, to)
    }

    fn heuristic(&self, node: usize) -> f64 {
        let (i, j, k) = self.lat.coords(node);
        self.h.at((i, j), self.lat.spec.point(i, j), k)
    }

    fn is_goal(&self, node: usize) -> bool {
        node == self.goal
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::validator::{DEFAULT_TOLERANCE, validate_path};
    use crate::geometry::{Obstacle, RobotShape, Shape, World};
    use proptest::prelude::*;

    #[test]
    fn moves_of_each_connectivity() {
        assert_eq!(moves(6, 10, true).len(), 6);
        assert_eq!(moves(26, 10, true).len(), 26);
        assert_eq!(moves(26, 2, true).len(), 17);
        assert_eq!(moves(26, 1, true).len(), 8);
        assert_eq!(moves(4, 1, false).len(), 4);
        assert_eq!(moves(8, 1, false).len(), 8);
    }

    fn rect_world(rects: &[(f64, f64, f64, f64)]) -> World {
        World {
            bounds: Aabb::from_corners(Point::new(-20.0, -20.0), Point::new(20.0, 20.0)),
            obstacles: rects
                .iter()
                .enumerate()
                .map(|(i, &(x, y, w, h))| Obstacle {
                    name: format!("o{i}"),
                    shape: Shape::Rect(Aabb::from_corners(
                        Point::new(x, y),
                        Point::new(x + w, y + h),
                    )),
                })
                .collect(),
        }
    }

    fn lattice_for(world: &World, robot: &ConvexPolygon, thetas: &[f64]) -> Lattice {
        let shape = RobotShape::Polygon(robot.clone());
        let pieces = ObstaclePieces::new(world);
        let layers: Vec<CLayer> = thetas.iter().map(|&t| pieces.layer(robot, t)).collect();
        let layer_boxes = layers
            .iter()
            .map(|l| {
                l.c_obstacles
                    .iter()
                    .map(|c| Aabb::around(&c.vertices))
                    .collect()
            })
            .collect();
        Lattice {
            spec: LatticeSpec::new(world, 1.0, super::super::lattice::Sample::Center, 1.0),
            thetas: thetas.to_vec(),
            layers,
            layer_boxes,
            motion: MotionChecker::new(world, &shape),
            free: BitSet::default(),
            moves: Vec::new(),
            profiling: false,
            profile: Profile::default(),
        }
    }

    fn robot_strategy() -> impl Strategy<Value = ConvexPolygon> {
        (0.2f64..4.0, 0.2f64..2.0, -1.0f64..0.5, -1.0f64..0.5).prop_map(|(w, h, ox, oy)| {
            ConvexPolygon {
                vertices: vec![
                    Point::new(ox, oy),
                    Point::new(ox + w, oy),
                    Point::new(ox + w, oy + h),
                    Point::new(ox, oy + h),
                ],
            }
        })
    }

    fn rects_strategy() -> impl Strategy<Value = Vec<(f64, f64, f64, f64)>> {
        prop::collection::vec((-6.0f64..6.0, -6.0f64..6.0, 0.1f64..4.0, 0.1f64..4.0), 1..4)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// The exact translation test agrees with the validator (free ⇒
        /// valid; blocked ⇒ invalid unless within rounding of touching).
        #[test]
        fn translations_agree_with_the_validator(
            robot in robot_strategy(),
            rects in rects_strategy(),
            theta in 0.0f64..TAU,
            (x0, y0, x1, y1) in (-8.0f64..8.0, -8.0f64..8.0, -8.0f64..8.0, -8.0f64..8.0),
        ) {
            let world = rect_world(&rects);
            let lat = lattice_for(&world, &robot, &[theta]);
            let (a, b) = (Config::new(x0, y0, theta), Config::new(x1, y1, theta));
            let ours = lat.translation_free(0, a.xy(), b.xy());
            let valid = validate_path(&world, &RobotShape::Polygon(robot.clone()), &[a, b], DEFAULT_TOLERANCE).is_ok();
            if ours {
                prop_assert!(valid, "free by the segment test, invalid: {a:?} {b:?}");
            } else if valid {
                // Only where the depth is within rounding of TOUCH_EPS.
                let depth = lat.layers[0].c_obstacles.iter()
                    .map(|c| segment_depth(a.xy(), b.xy(), &c.vertices))
                    .fold(f64::NEG_INFINITY, f64::max);
                prop_assert!(depth <= TOUCH_EPS * 1.01, "depth {depth}");
            }
        }

        /// The rotation test (the motion checker) never accepts a motion the
        /// validator rejects.
        #[test]
        fn rotations_are_sound(
            robot in robot_strategy(),
            rects in rects_strategy(),
            theta in 0.0f64..TAU,
            dtheta in -0.8f64..0.8,
            (x0, y0, dx, dy) in (-8.0f64..8.0, -8.0f64..8.0, -1.0f64..1.0, -1.0f64..1.0),
        ) {
            let world = rect_world(&rects);
            let lat = lattice_for(&world, &robot, &[theta]);
            let (a, b) = (Config::new(x0, y0, theta), Config::new(x0 + dx, y0 + dy, theta + dtheta));
            if lat.motion.motion_free(a, b) {
                prop_assert!(validate_path(&world, &RobotShape::Polygon(robot.clone()), &[a, b], DEFAULT_TOLERANCE).is_ok());
            }
        }
    }
}
