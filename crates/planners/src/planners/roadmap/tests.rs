use proptest::prelude::*;

use super::*;
use crate::contract::Limits;
use crate::geometry::polygon::convex_hull;
use crate::geometry::validator::{Validator, validate_path};
use crate::geometry::{Aabb, Obstacle, Shape};
use crate::planners::astar::Astar;
use crate::planners::lattice::{CostMetric, Heuristic};
use crate::planners::lattice::{LatticeSpec, Sample};

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

fn world(bounds: (f64, f64, f64, f64), shapes: Vec<Shape>) -> World {
    World {
        bounds: Aabb::from_corners(p(bounds.0, bounds.1), p(bounds.2, bounds.3)),
        obstacles: shapes
            .into_iter()
            .enumerate()
            .map(|(i, shape)| Obstacle {
                name: format!("o{i}"),
                shape,
            })
            .collect(),
    }
}

fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Shape {
    Shape::Rect(Aabb::from_corners(p(x0, y0), p(x1, y1)))
}

fn seg(x0: f64, y0: f64, x1: f64, y1: f64) -> Shape {
    Shape::Segment(p(x0, y0), p(x1, y1))
}

/// The four walls of the closed square room [lo, hi]², a chain round it.
fn room_of_walls(lo: f64, hi: f64) -> Vec<Shape> {
    vec![
        seg(lo, lo, hi, lo),
        seg(hi, lo, hi, hi),
        seg(hi, hi, lo, hi),
        seg(lo, hi, lo, lo),
    ]
}

/// A roadmap problem: start, goal, `arc_segments` and limits.
#[derive(Clone, Copy)]
struct Case {
    start: Config,
    goal: Config,
    arc: usize,
    limits: Limits,
}

fn params(start: (f64, f64), goal: (f64, f64), arc: usize) -> Case {
    Case {
        start: Config::new(start.0, start.1, 0.0),
        goal: Config::new(goal.0, goal.1, 0.0),
        arc,
        limits: Limits::default(),
    }
}

fn task<'a>(w: &'a World, robot: &'a RobotShape, c: &Case) -> Task<'a> {
    Task {
        world: w,
        robot,
        start: c.start,
        goal: Some(c.goal),
        limits: c.limits,
        seed: 0,
        steering: None,
        draw: true,
        referee: None,
        moving: &[],
        speed: None,
        agents: &[],
    }
}

fn run(w: &World, robot: &RobotShape, c: &Case) -> PlanOutcome {
    plan(
        &task(w, robot, c),
        &RoadmapSettings {
            arc_segments: c.arc,
        },
    )
}

fn box_robot(w: f64, h: f64) -> RobotShape {
    RobotShape::Polygon(ConvexPolygon {
        vertices: vec![p(0.0, 0.0), p(w, 0.0), p(w, h), p(0.0, h)],
    })
}

fn length(path: &[Config]) -> f64 {
    path.windows(2)
        .map(|w| (w[1].xy() - w[0].xy()).norm())
        .sum()
}

/// Plans, checks the path with the validator, returns its length.
fn plan_length(w: &World, robot: &RobotShape, start: (f64, f64), goal: (f64, f64)) -> Option<f64> {
    let out = run(w, robot, &params(start, goal, 32));
    let path = out.path?;
    validate_path(w, robot, &path, 0.01).expect("the roadmap path validates");
    let l = length(&path);
    assert!(
        (out.cost.unwrap_or(f64::NAN) - l).abs() < 1e-9,
        "cost = length"
    );
    Some(l)
}

fn assert_close(a: f64, b: f64) {
    assert!((a - b).abs() <= 1e-9, "{a} vs {b}");
}

#[test]
fn around_one_square() {
    let w = world((-5.0, -5.0, 10.0, 5.0), vec![rect(1.0, -1.0, 3.0, 1.0)]);
    let l = plan_length(&w, &RobotShape::Point, (0.0, 0.0), (4.0, 0.0)).unwrap();
    assert_close(l, 2.0 + 2.0 * 2f64.sqrt());
    // A 1×1 box (reference at its lower-left corner) grows the square to
    // [0, 3] × [-2, 1]: from (-1, 0) to (4, 0) over the top corners.
    let l = plan_length(&w, &box_robot(1.0, 1.0), (-1.0, 0.0), (4.0, 0.0)).unwrap();
    assert_close(l, 2.0 * 2f64.sqrt() + 3.0);
}

#[test]
fn between_two_squares_through_collinear_corners() {
    // The straight line from (0, 3) to (6, -3) touches the corners (2, 1)
    // and (4, -1) exactly: allowed, and the shortest path.
    let w = world(
        (-5.0, -5.0, 10.0, 5.0),
        vec![rect(2.0, 1.0, 4.0, 3.0), rect(2.0, -3.0, 4.0, -1.0)],
    );
    let l = plan_length(&w, &RobotShape::Point, (0.0, 3.0), (6.0, -3.0)).unwrap();
    assert_close(l, 72f64.sqrt());
    // Between them, straight.
    let l = plan_length(&w, &RobotShape::Point, (0.0, 0.0), (6.0, 0.0)).unwrap();
    assert_close(l, 6.0);
}

#[test]
fn along_collinear_tops() {
    let w = world(
        (-1.0, -1.0, 8.0, 3.0),
        vec![
            rect(1.0, 0.0, 2.0, 1.0),
            rect(3.0, 0.0, 4.0, 1.0),
            rect(5.0, 0.0, 6.0, 1.0),
        ],
    );
    let l = plan_length(&w, &RobotShape::Point, (0.0, 1.0), (7.0, 1.0)).unwrap();
    assert_close(l, 7.0);
    // Below the tops, the path climbs over them: (0, 0.5) up to (1, 1),
    // along, down from (6, 1).
    let l = plan_length(&w, &RobotShape::Point, (0.0, 0.5), (7.0, 0.5)).unwrap();
    assert_close(l, 5.0 + 2.0 * 1.25f64.sqrt());
}

#[test]
fn gap_exactly_as_wide_as_the_robot() {
    // Two walls leave the gap 0 ≤ y ≤ 1 at 2 ≤ x ≤ 3; a 1×1 box passes
    // with its reference (lower-left corner) exactly on y = 0, where the
    // grown walls touch.
    let w = world(
        (-1.0, -7.0, 6.0, 7.0),
        vec![rect(2.0, -5.0, 3.0, 0.0), rect(2.0, 1.0, 3.0, 6.0)],
    );
    let l = plan_length(&w, &box_robot(1.0, 1.0), (0.0, 0.0), (5.0, 0.0)).unwrap();
    assert_close(l, 5.0);
    let l = plan_length(&w, &box_robot(1.0, 1.0), (0.0, 0.5), (5.0, -0.5)).unwrap();
    assert_close(l, 1.25f64.sqrt() + 2.0 + 4.25f64.sqrt());
    // A box a little taller does not fit: around the walls.
    let l = plan_length(&w, &box_robot(1.0, 1.01), (0.0, 0.0), (5.0, 0.0));
    assert!(l.is_none_or(|l| l > 10.0), "{l:?}");
}

#[test]
fn through_a_wall_vertex_is_crossing() {
    // A roof ^ of two walls: from under its apex to above it the straight
    // line passes through the apex, which crosses the walls; the path goes
    // round an end.
    let w = world(
        (-3.0, -3.0, 5.0, 5.0),
        vec![seg(0.0, 0.0, 1.0, 1.0), seg(1.0, 1.0, 2.0, 0.0)],
    );
    let l = plan_length(&w, &RobotShape::Point, (1.0, 0.2), (1.0, 3.0)).unwrap();
    assert_close(l, 1.04f64.sqrt() + 10f64.sqrt());
    // Sliding along a wall and leaving on the other side at the apex is
    // crossing too: from the left slope's outside to the right slope's
    // inside.
    let l = plan_length(&w, &RobotShape::Point, (0.0, 1.0), (1.5, 0.2)).unwrap();
    assert!(l > 2.0, "{l}");
}

#[test]
fn closed_chain_of_walls() {
    let w = world((0.0, 0.0, 4.0, 4.0), room_of_walls(1.0, 3.0));
    assert!(plan_length(&w, &RobotShape::Point, (0.5, 2.0), (2.0, 2.0)).is_none());
    let l = plan_length(&w, &RobotShape::Point, (1.5, 1.5), (2.5, 2.5)).unwrap();
    assert_close(l, 2f64.sqrt());
    // Outside, round two corners.
    let l = plan_length(&w, &RobotShape::Point, (0.5, 2.0), (3.5, 2.0)).unwrap();
    assert_close(l, 2.0 * 1.25f64.sqrt() + 2.0);
    // An open chain (one wall missing): in through the opening.
    let w = world(
        (0.0, 0.0, 4.0, 4.0),
        vec![
            seg(1.0, 1.0, 3.0, 1.0),
            seg(3.0, 1.0, 3.0, 3.0),
            seg(3.0, 3.0, 1.0, 3.0),
        ],
    );
    let l = plan_length(&w, &RobotShape::Point, (0.5, 2.0), (2.0, 2.0)).unwrap();
    assert_close(l, 1.5);
}

/// A body thinner than the arrangement resolves grows segment obstacles
/// into slivers a path could run through (a fuzzed scenario: a 1e-9 wide
/// box slid under the top wall of a closed room, across its side walls):
/// refused with a note. From `MIN_ROBOT_WIDTH` the paths validate, the
/// body upright and lying, a triangle and a disk.
#[test]
fn robots_thinner_than_the_tolerance_are_refused() {
    let w = world((0.0, 0.0, 20.0, 14.0), room_of_walls(3.0, 7.0));
    for thin in [box_robot(1e-9, 0.6), RobotShape::Disk(1e-9)] {
        let out = run(&w, &thin, &params((1.0, 5.0), (9.0, 5.0), 32));
        assert!(out.path.is_none());
        assert!(out.notes[0].contains("thinner than"), "{:?}", out.notes);
    }
    let m = MIN_ROBOT_WIDTH;
    for robot in [
        box_robot(m, 0.6),
        box_robot(0.6, m),
        RobotShape::Polygon(ConvexPolygon {
            vertices: vec![p(0.0, 0.0), p(1.0, 0.0), p(0.5, m * 1.0001)],
        }),
        RobotShape::Disk(m / 2.0 * 1.0001),
    ] {
        assert_eq!(robot_width(&robot).map(|x| x >= m), Some(true));
        for (start, goal) in [((1.0, 5.0), (9.0, 5.0)), ((1.0, 1.0), (19.0, 13.0))] {
            assert!(plan_length(&w, &robot, start, goal).is_some());
        }
    }
}

#[test]
fn seams_of_a_nonconvex_polygon_are_inside() {
    let outline = vec![
        p(0.0, 0.0),
        p(4.0, 0.0),
        p(4.0, 1.0),
        p(1.0, 1.0),
        p(1.0, 4.0),
        p(0.0, 4.0),
    ];
    let pieces = crate::geometry::polygon::convex_decomposition(&outline);
    assert!(pieces.len() >= 2);
    let w = world(
        (-2.0, -2.0, 6.0, 6.0),
        vec![Shape::Polygon {
            outline: outline.clone(),
            pieces,
        }],
    );
    let (polys, walls) = grow(&w, &RobotShape::Point, 0.0, 32);
    let rm =
        Roadmap::build(&polys, &walls, p(3.0, 3.0), p(-1.0, -1.0), w.bounds, None).expect("built");
    let pts = &rm.arrangement.points;
    for e in &rm.visible {
        let m = Point::from((pts[e.a as usize].coords + pts[e.b as usize].coords) / 2.0);
        let inside = crate::geometry::validator::config_collision(
            &w,
            &RobotShape::Point,
            Config::new(m.x, m.y, 0.0),
        );
        assert!(inside.is_none(), "edge through the polygon at {m:?}");
    }
    let l = plan_length(&w, &RobotShape::Point, (3.0, 3.0), (-1.0, -1.0)).unwrap();
    assert_close(l, 5f64.sqrt() + 1.0 + 26f64.sqrt());
}

#[test]
fn poses_inside_the_circumscribed_disk_and_turning_goals_are_refused() {
    // The start touches the true disk obstacle but lies inside its
    // circumscribed 8-gon.
    let w = world(
        (-5.0, -5.0, 5.0, 5.0),
        vec![Shape::Disk {
            center: p(0.0, 0.0),
            radius: 1.0,
        }],
    );
    let a = std::f64::consts::PI / 8.0;
    let out = run(
        &w,
        &RobotShape::Point,
        &params((1.03 * a.cos(), 1.03 * a.sin()), (3.0, 3.0), 8),
    );
    assert!(out.path.is_none());
    assert!(out.notes[0].contains("`o0`"), "{:?}", out.notes);
    let mut pr = params((3.0, 0.0), (-3.0, 0.0), 32);
    pr.goal = Config::new(-3.0, 0.0, 1.0);
    let out = run(&w, &box_robot(1.0, 1.0), &pr);
    assert!(out.path.is_none() && !out.notes.is_empty());
}

#[test]
fn limits_are_honoured() {
    let w = world((-5.0, -5.0, 10.0, 5.0), vec![rect(1.0, -1.0, 3.0, 1.0)]);
    let mut pr = params((0.0, 0.0), (4.0, 0.0), 32);
    pr.limits.expansions = Some(1);
    let out = run(&w, &RobotShape::Point, &pr);
    assert!(out.gave_up && out.path.is_none());
    let mut pr = params((0.0, 0.0), (4.0, 0.0), 32);
    pr.limits.time = Some(0.0);
    let out = run(&w, &RobotShape::Point, &pr);
    assert!(out.gave_up && out.path.is_none());
}

// ---------------------------------------------------------- random worlds

/// `n` random convex obstacles (hulls of 3–8 points around a centre) in
/// `[0, size]²`, and `walls` random segments.
pub(super) fn random_world(seed: u64, n: usize, walls: usize, size: f64, r: f64) -> World {
    let mut rng = crate::rng::SplitMix64::new(seed);
    let mut shapes = Vec::new();
    for _ in 0..n {
        let (cx, cy) = (rng.range(0.0, size), rng.range(0.0, size));
        let k = 3 + (rng.next_f64() * 6.0) as usize;
        let pts: Vec<Point> = (0..k)
            .map(|_| {
                let a = rng.range(0.0, std::f64::consts::TAU);
                let d = rng.range(0.3, 1.0) * r;
                p(cx + d * a.cos(), cy + d * a.sin())
            })
            .collect();
        let hull = convex_hull(&pts);
        if hull.len() >= 3 {
            shapes.push(Shape::Polygon {
                outline: hull.clone(),
                pieces: vec![ConvexPolygon { vertices: hull }],
            });
        }
    }
    for _ in 0..walls {
        let (x, y) = (rng.range(0.0, size), rng.range(0.0, size));
        let a = rng.range(0.0, std::f64::consts::TAU);
        let l = rng.range(0.2, 1.5) * r;
        shapes.push(seg(x, y, x + l * a.cos(), y + l * a.sin()));
    }
    world((0.0, 0.0, size, size), shapes)
}

fn sorted(mut v: Vec<Visible>) -> Vec<Visible> {
    v.sort_by_key(|e| (e.a, e.b));
    v
}

/// The roadmap's visibility edges and the brute force's (without the
/// motions along cut edges that leave the boundary), both sorted.
fn sweep_and_brute(
    w: &World,
    robot: &RobotShape,
    start: Point,
    goal: Point,
) -> (Vec<Visible>, Vec<Visible>) {
    let (polys, walls) = grow(w, robot, 0.0, 16);
    let rm = Roadmap::build(&polys, &walls, start, goal, w.bounds, None).expect("built");
    let arr = &rm.arrangement;
    let brute: Vec<Visible> = sweep::brute_force(arr)
        .into_iter()
        .filter(|e| arr.along_cut_edge(e.a, e.b) != Some(false))
        .collect();
    (sorted(rm.visible), sorted(brute))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// The sweep finds exactly the edges of the O(n³) brute force, for
    /// overlapping polygons and walls, point and box robots.
    #[test]
    fn sweep_equals_brute_force(seed in any::<u64>(), n in 1usize..9, walls in 0usize..6, robot in 0u8..3) {
        let w = random_world(seed, n, walls, 10.0, 2.0);
        let robot = match robot {
            0 => RobotShape::Point,
            1 => RobotShape::Disk(0.3),
            _ => box_robot(0.6, 0.3),
        };
        let (visible, brute) = sweep_and_brute(&w, &robot, p(0.5, 0.5), p(9.5, 9.5));
        prop_assert_eq!(visible, brute);
    }

    /// The same on axis-aligned worlds on an integer grid: rectangles that
    /// touch at corners, share edges and overlap, walls along their sides,
    /// many collinear points and flat corners (the degenerate cases of the
    /// sweep's angular groups and of its hidden-point rule).
    #[test]
    fn sweep_equals_brute_force_on_grid_worlds(
        rects in prop::collection::vec((0u8..8, 0u8..8, 1u8..4, 1u8..4), 1..10),
        walls in prop::collection::vec((0u8..9, 0u8..9, 0u8..2, 1u8..4), 0..5),
        boxed in any::<bool>(),
    ) {
        let mut shapes: Vec<Shape> = rects
            .iter()
            .map(|&(x, y, w, h)| {
                let (x, y) = (f64::from(x), f64::from(y));
                rect(x, y, x + f64::from(w), y + f64::from(h))
            })
            .collect();
        for &(x, y, vertical, l) in &walls {
            let (x, y, l) = (f64::from(x), f64::from(y), f64::from(l));
            shapes.push(if vertical == 1 { seg(x, y, x, y + l) } else { seg(x, y, x + l, y) });
        }
        let w = world((-1.0, -1.0, 12.0, 12.0), shapes);
        let robot = if boxed { box_robot(0.5, 0.5) } else { RobotShape::Point };
        let (visible, brute) = sweep_and_brute(&w, &robot, p(-0.5, -0.5), p(11.5, 11.5));
        prop_assert_eq!(visible, brute);
    }

    /// Every visibility edge passes the validator as a motion.
    #[test]
    fn every_edge_validates(seed in any::<u64>(), n in 1usize..7, walls in 0usize..5, robot in 0u8..3) {
        let w = random_world(seed, n, walls, 10.0, 2.0);
        let robot = match robot {
            0 => RobotShape::Point,
            1 => RobotShape::Disk(0.3),
            _ => box_robot(0.6, 0.3),
        };
        let (polys, walls) = grow(&w, &robot, 0.0, 16);
        let rm = Roadmap::build(&polys, &walls, p(0.5, 0.5), p(9.5, 9.5), w.bounds, None).expect("built");
        let v = Validator::new(&w);
        let pts = &rm.arrangement.points;
        for e in &rm.visible {
            let (a, b) = (pts[e.a as usize], pts[e.b as usize]);
            let path = [Config::new(a.x, a.y, 0.0), Config::new(b.x, b.y, 0.0)];
            let r = v.validate_path(&robot, &path, 0.01);
            prop_assert!(r.is_ok(), "edge {:?} -> {:?}: {:?}", a, b, r);
        }
    }

    /// The roadmap path is never longer than the 8-connected lattice path
    /// of `astar` at a fine cell (a feasible polyline), and it validates.
    /// The disk's lattice robot is the circumscribed one, whose paths are
    /// feasible for the roadmap's grown (circumscribed) obstacles.
    #[test]
    fn never_longer_than_the_lattice(seed in any::<u64>(), n in 1usize..7, walls in 0usize..4, robot in 0u8..3, s in (0.0..10.0f64, 0.0..10.0f64), g in (0.0..10.0f64, 0.0..10.0f64)) {
        let w = random_world(seed, n, walls, 10.0, 2.0);
        let k = 16.0;
        let (robot, lattice_robot) = match robot {
            0 => (RobotShape::Point, RobotShape::Point),
            1 => (RobotShape::Disk(0.3), RobotShape::Disk(0.3 / (std::f64::consts::PI / k).cos() * (1.0 + 1e-9))),
            _ => (box_robot(0.6, 0.3), box_robot(0.6, 0.3)),
        };
        let v = Validator::new(&w);
        for c in [s, g] {
            prop_assume!(v.config_collision(&lattice_robot, Config::new(c.0, c.1, 0.0)).is_none());
        }
        let out = run(&w, &robot, &params(s, g, k as usize));
        let lattice = Astar {
            lattice: LatticeSpec::new(&w, 0.1, Sample::Center, 1.0),
            rotating: false,
            connect: 8,
            cost: CostMetric::Euclid,
            turn_cost: 0.0,
            weight: 1.0,
            heuristic: Heuristic::Metric,
        };
        let lat = lattice.plan(&task(&w, &lattice_robot, &params(s, g, 32)));
        if let Some(path) = &out.path {
            let r = v.validate_path(&robot, path, 0.01);
            prop_assert!(r.is_ok(), "{:?}", r);
        }
        if let Some(lp) = &lat.path {
            prop_assert!(v.validate_path(&lattice_robot, lp, 0.01).is_ok());
            let rl = out.path.as_ref().map(|p| length(p));
            prop_assert!(rl.is_some(), "the lattice found a path, the roadmap none: {:?}", out.notes);
            let (rl, ll) = (rl.unwrap_or(0.0), length(lp));
            prop_assert!(rl <= ll + 1e-9, "roadmap {} > lattice {}", rl, ll);
        }
    }
}

#[test]
fn deterministic() {
    let w = random_world(7, 30, 5, 20.0, 2.0);
    let a = run(
        &w,
        &RobotShape::Disk(0.2),
        &params((0.1, 0.1), (19.9, 19.9), 32),
    );
    let b = run(
        &w,
        &RobotShape::Disk(0.2),
        &params((0.1, 0.1), (19.9, 19.9), 32),
    );
    assert_eq!(a.path, b.path);
    assert_eq!(a.extra, b.extra);
    assert_eq!(a.layers, b.layers);
}

/// Timing of the phases on a random world (`-- --ignored --nocapture`).
#[test]
#[ignore]
fn phases_timing() {
    for n in [100usize, 300] {
        let w = random_world(42, n, 0, 4.0 * (n as f64).sqrt(), 1.0);
        let (polys, walls) = grow(&w, &RobotShape::Point, 0.0, 32);
        let t = std::time::Instant::now();
        let arr = arrangement::build(
            &polys,
            &walls,
            p(0.0, 0.0),
            p(1.0, 1.0),
            w.bounds,
            TOUCH_EPS,
        );
        let ta = t.elapsed();
        let t = std::time::Instant::now();
        let mut buf = sweep::SweepBuffers::new(&arr);
        let mut out = Vec::new();
        for v in 0..arr.points.len() as u32 {
            if arr.is_node[v as usize] {
                sweep::sweep(&arr, v, &mut buf, &mut out);
            }
        }
        eprintln!(
            "n {n}: points {} arrangement {:?} sweeps (1 thread) {:?} edges {}",
            arr.points.len(),
            ta,
            t.elapsed(),
            out.len()
        );
    }
}

#[test]
fn huge_worlds_are_refused_not_hung() {
    let disks = (0..10)
        .map(|i| Shape::Disk {
            center: p(1.0 + 2.0 * i as f64, 5.0),
            radius: 0.5,
        })
        .collect();
    let w = world((0.0, 0.0, 25.0, 10.0), disks);
    let out = run(
        &w,
        &RobotShape::Point,
        &params((0.0, 0.0), (24.0, 9.0), 4096),
    );
    assert!(out.path.is_none());
    assert!(out.notes[0].contains("vertices"), "{:?}", out.notes);
    assert_eq!(out.extra["graph_nodes"], MetricValue::Num(0.0));
}

/// Regression: two overlapping grown boxes share an edge line through the
/// swept node 32, and rounding made the segment 34-35 on that line seem to
/// span the whole turn around it (the sign of its orientation and the order
/// of its ends disagreed), hiding 38 and 39 from 32.
#[test]
fn a_segment_collinear_with_the_node_but_for_rounding_blocks_nothing() {
    let w = random_world(13760135364525337302, 3, 2, 10.0, 2.0);
    let (visible, brute) = sweep_and_brute(&w, &box_robot(0.6, 0.3), p(0.5, 0.5), p(9.5, 9.5));
    assert!(visible.iter().any(|e| (e.a, e.b) == (32, 38)));
    assert_eq!(visible, brute);
}
