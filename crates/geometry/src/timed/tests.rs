use super::*;
use crate::fixtures::world_in;
use crate::{Aabb, ConvexPolygon};
use proptest::prelude::*;

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

fn open_world() -> World {
    world_in(
        Aabb::from_corners(p(-50.0, -50.0), p(50.0, 50.0)),
        Vec::new(),
    )
}

fn at(x: f64, y: f64, t: f64) -> Timed {
    Timed {
        pose: Config::new(x, y, 0.0),
        t,
    }
}

fn cart(route: &[(f64, f64, f64)], after: After) -> MovingObstacle {
    MovingObstacle {
        name: "cart".into(),
        shape: MovingShape::Disk(0.5),
        route: route
            .iter()
            .map(|&(t, x, y)| Waypoint { t, at: p(x, y) })
            .collect(),
        after,
    }
}

fn square(h: f64) -> Vec<Point> {
    vec![p(-h, -h), p(h, -h), p(h, h), p(-h, h)]
}

/// A cart crosses the robot's corridor at x = 5 going up; the robot
/// driving straight through meets it at the closed-form time, and waiting
/// for it to pass is valid.
#[test]
fn a_crossing_cart_is_met_at_the_closed_form_time_and_waiting_is_valid() {
    let w = open_world();
    // The cart: (5, t) for t in [0, 20], radius 0.5.
    let c = cart(&[(0.0, 5.0, 0.0), (20.0, 5.0, 20.0)], After::Stay);
    let robot = RobotShape::Disk(0.5);
    // The robot: (t, 5) for t in [0, 10].
    let straight = [at(0.0, 5.0, 0.0), at(10.0, 5.0, 10.0)];
    let e = validate_trajectory(&w, std::slice::from_ref(&c), &robot, 1.0, &straight)
        .expect_err("they meet");
    assert_eq!(e.obstacle.as_deref(), Some("cart"));
    assert_eq!(e.segment, 0);
    // The centres are √2·|t − 5| apart: they touch (1 apart) at 5 − √½.
    let t_touch = 5.0 - 0.5f64.sqrt();
    let found: f64 = e
        .reason
        .split("t = ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((found - t_touch).abs() < 1e-5, "{found} vs {t_touch}");
    assert!((e.at.x - t_touch).abs() < 1e-5, "{e:?}");
    // Waiting at (3, 5) until t = 6 lets the cart pass (closest 1.5·√2).
    let wait = [
        at(0.0, 5.0, 0.0),
        at(3.0, 5.0, 3.0),
        at(3.0, 5.0, 6.0),
        at(10.0, 5.0, 13.0),
    ];
    assert_eq!(
        validate_trajectory(&w, std::slice::from_ref(&c), &robot, 1.0, &wait),
        Ok(())
    );
    // Leaving at t = 4 meets it (closest √½ < 1).
    let early = [
        at(0.0, 5.0, 0.0),
        at(3.0, 5.0, 3.0),
        at(3.0, 5.0, 4.0),
        at(10.0, 5.0, 11.0),
    ];
    let e = validate_trajectory(&w, &[c], &robot, 1.0, &early).expect_err("meets");
    assert_eq!(e.segment, 2, "{e:?}");
}

/// The robot parked at its goal is hit by a cart that drives through later.
#[test]
fn the_parked_robot_counts() {
    let w = open_world();
    let c = cart(
        &[(0.0, 20.0, 0.0), (30.0, 20.0, 0.0), (40.0, 0.0, 0.0)],
        After::Stay,
    );
    let robot = RobotShape::Point;
    let traj = [at(-5.0, 0.0, 0.0), at(0.0, 0.0, 5.0)];
    let e = validate_trajectory(&w, std::slice::from_ref(&c), &robot, 1.0, &traj).expect_err("hit");
    assert_eq!(e.segment, 1, "{e:?}");
    // It stops 1 unit short of the goal: the cart parks 0.5 from the robot.
    let short = [at(-5.0, 0.0, 0.0), at(-1.0, 0.0, 4.0)];
    assert_eq!(validate_trajectory(&w, &[c], &robot, 1.0, &short), Ok(()));
}

/// A vanishing door is absent from its last time on, that instant included.
#[test]
fn a_door_that_vanishes() {
    let w = open_world();
    let door = MovingObstacle {
        name: "door".into(),
        shape: MovingShape::Pieces(vec![vec![
            p(-0.5, -2.0),
            p(0.5, -2.0),
            p(0.5, 2.0),
            p(-0.5, 2.0),
        ]]),
        route: vec![Waypoint {
            t: 10.0,
            at: p(5.0, 0.0),
        }],
        after: After::Vanish,
    };
    let robot = RobotShape::Disk(0.25);
    // Arriving at the door's face (x = 4.25 touches x = 4.5) at t = 10 and
    // passing right then is valid; crossing at t = 9.5 is not.
    let on_time = [at(0.0, 0.0, 0.0), at(4.25, 0.0, 10.0), at(10.0, 0.0, 20.0)];
    assert_eq!(
        validate_trajectory(&w, std::slice::from_ref(&door), &robot, 1.0, &on_time),
        Ok(())
    );
    let early = [at(0.0, 0.0, 0.0), at(10.0, 0.0, 10.0)];
    let e = validate_trajectory(&w, &[door], &robot, 1.0, &early).expect_err("through the door");
    assert_eq!(e.obstacle.as_deref(), Some("door"));
}

#[test]
fn timing_rules() {
    let w = open_world();
    let robot = RobotShape::Point;
    let e = validate_trajectory(&w, &[], &robot, 1.0, &[at(0.0, 0.0, 1.0)]).unwrap_err();
    assert!(e.reason.contains("not 0"), "{e:?}");
    let e = validate_trajectory(
        &w,
        &[],
        &robot,
        1.0,
        &[at(0.0, 0.0, 0.0), at(1.0, 0.0, 0.0)],
    )
    .unwrap_err();
    assert!(e.reason.contains("do not increase"), "{e:?}");
    let e = validate_trajectory(
        &w,
        &[],
        &robot,
        1.0,
        &[at(0.0, 0.0, 0.0), at(2.0, 0.0, 1.0)],
    )
    .unwrap_err();
    assert!(e.reason.contains("faster"), "{e:?}");
    // Within the relative slack.
    let ok = [at(0.0, 0.0, 0.0), at(1.0 + 1e-12, 0.0, 1.0)];
    assert_eq!(validate_trajectory(&w, &[], &robot, 1.0, &ok), Ok(()));
    // A polygon robot that turns while timed.
    let rod = RobotShape::Polygon(ConvexPolygon {
        vertices: square(0.2),
    });
    let turn = [
        at(0.0, 0.0, 0.0),
        Timed {
            pose: Config::new(0.0, 0.0, 1.0),
            t: 1.0,
        },
    ];
    assert!(
        validate_trajectory(&w, &[], &rod, 1.0, &turn)
            .unwrap_err()
            .reason
            .contains("turns")
    );
    // Static obstacles are checked as for a path.
    let walled = world_in(
        Aabb::from_corners(p(-50.0, -50.0), p(50.0, 50.0)),
        vec![crate::fixtures::rect(2.0, -1.0, 3.0, 1.0)],
    );
    assert!(
        validate_trajectory(
            &walled,
            &[],
            &robot,
            1.0,
            &[at(0.0, 0.0, 0.0), at(5.0, 0.0, 5.0)]
        )
        .is_err()
    );
}

// ------------------------------------------------- against dense sampling

/// The overlap depth of the robot and the obstacle at one instant (> 0:
/// interiors overlap), computed from the static shapes.
fn depth_at(robot: &RobotShape, traj: &[Timed], o: &MovingObstacle, t: f64) -> f64 {
    let Some(c) = o.position(t) else {
        return f64::NEG_INFINITY;
    };
    let r = robot_at(traj, t);
    let body = Body::of(robot, r.theta);
    let d = c - Point::new(r.x, r.y);
    match (&o.shape, &body) {
        (MovingShape::Disk(ro), Body::Round(rr)) => ro + rr - d.norm(),
        (MovingShape::Disk(ro), Body::Convex(v)) => {
            let centre = Point::from(d);
            let inside = depth_inside(centre, v);
            if inside >= 0.0 {
                ro + inside
            } else {
                ro - point_polygon_distance(centre, v)
            }
        }
        (MovingShape::Pieces(pieces), body) => pieces
            .iter()
            .map(|piece| {
                let placed: Vec<Point> = piece.iter().map(|q| q + d).collect();
                match body {
                    Body::Round(rr) => {
                        let inside = depth_inside(Point::origin(), &placed);
                        if inside >= 0.0 {
                            rr + inside
                        } else {
                            rr - point_polygon_distance(Point::origin(), &placed)
                        }
                    }
                    Body::Convex(v) => penetration(v, &placed),
                }
            })
            .fold(f64::NEG_INFINITY, f64::max),
    }
}

fn moving() -> impl Strategy<Value = MovingObstacle> {
    let shape = prop_oneof![
        (0.1..1.5f64).prop_map(MovingShape::Disk),
        (0.1..1.2f64, 0.1..1.2f64).prop_map(|(w, h)| MovingShape::Pieces(vec![vec![
            p(-w, -h),
            p(w, -h),
            p(w, h),
            p(-w, h)
        ]])),
        (0.2..1.5f64).prop_map(|s| MovingShape::Pieces(vec![vec![
            p(-s, -s),
            p(s, -s * 0.5),
            p(0.0, s)
        ]])),
    ];
    let waypoints = prop::collection::vec((0.0..4.0f64, -6.0..6.0f64, -6.0..6.0f64), 1..4);
    (shape, waypoints, prop::bool::ANY).prop_map(|(shape, mut w, vanish)| {
        w.sort_by(|a, b| a.0.total_cmp(&b.0));
        w.dedup_by(|a, b| a.0 - b.0 < 0.05);
        MovingObstacle {
            name: "m".into(),
            shape,
            route: w
                .iter()
                .map(|&(t, x, y)| Waypoint { t, at: p(x, y) })
                .collect(),
            after: if vanish { After::Vanish } else { After::Stay },
        }
    })
}

fn robot() -> impl Strategy<Value = RobotShape> {
    prop_oneof![
        Just(RobotShape::Point),
        (0.1..1.0f64).prop_map(RobotShape::Disk),
        (0.1..0.8f64).prop_map(|h| RobotShape::Polygon(ConvexPolygon {
            vertices: vec![p(-h, -h * 0.5), p(h, -h * 0.5), p(0.0, h)]
        })),
    ]
}

fn trajectory() -> impl Strategy<Value = Vec<Timed>> {
    (
        -6.0..6.0f64,
        -6.0..6.0f64,
        -3.2..3.2f64,
        prop::collection::vec(
            (
                0.05..2.0f64,
                -6.0..6.0f64,
                -6.0..6.0f64,
                prop::bool::weighted(0.3),
            ),
            0..4,
        ),
    )
        .prop_map(|(x, y, theta, steps)| {
            let mut out = vec![Timed {
                pose: Config::new(x, y, theta),
                t: 0.0,
            }];
            for (dt, nx, ny, wait) in steps {
                let last = *out.last().unwrap();
                let pose = if wait {
                    last.pose
                } else {
                    Config::new(nx, ny, theta)
                };
                out.push(Timed {
                    pose,
                    t: last.t + dt,
                });
            }
            out
        })
}

/// The largest sampled overlap depth, every 1e-4 s until everything has
/// stopped (and once more after).
fn sampled(robot: &RobotShape, traj: &[Timed], o: &MovingObstacle) -> f64 {
    let end = traj.last().unwrap().t.max(o.settles()) + 1e-3;
    let n = (end / 1e-4).ceil() as usize;
    (0..=n)
        .map(|k| depth_at(robot, traj, o, k as f64 * 1e-4))
        .fold(f64::NEG_INFINITY, f64::max)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Never accepts what sampling at 1e-4 s rejects; rejects only where
    /// sampling sees the two within what one step can hide.
    #[test]
    fn agrees_with_dense_sampling(robot in robot(), o in moving(), traj in trajectory()) {
        let w = open_world();
        let verdict = validate_trajectory(&w, std::slice::from_ref(&o), &robot, 1e6, &traj);
        let depth = sampled(&robot, &traj, &o);
        if depth > 1e-7 {
            prop_assert!(verdict.is_err(), "sampling finds depth {depth}, the validator accepts");
        }
        if verdict.is_err() {
            // The fastest relative motion here is under 200 units/s: 0.02
            // per step.
            prop_assert!(depth > -0.02, "rejected, but sampling keeps {} apart: {verdict:?}", -depth);
        }
    }
}

/// Not vacuous: over a fixed sample both verdicts occur, and the two agree
/// on the great majority.
#[test]
fn both_verdicts_occur() {
    use proptest::strategy::{Strategy, ValueTree};
    use proptest::test_runner::{Config as RunnerConfig, RngAlgorithm, TestRng, TestRunner};
    let mut runner = TestRunner::new_with_rng(
        RunnerConfig::default(),
        TestRng::from_seed(RngAlgorithm::ChaCha, &[3; 32]),
    );
    let strategy = (robot(), moving(), trajectory());
    let (mut valid, mut collide, mut sampled_collide, mut disagree) = (0, 0, 0, 0);
    for _ in 0..200 {
        let (robot, o, traj) = strategy.new_tree(&mut runner).unwrap().current();
        let depth = sampled(&robot, &traj, &o);
        let verdict =
            validate_trajectory(&open_world(), std::slice::from_ref(&o), &robot, 1e6, &traj);
        if depth > 1e-7 {
            sampled_collide += 1;
            assert!(
                verdict.is_err(),
                "sampling finds depth {depth}, the validator accepts"
            );
        }
        match verdict {
            Ok(()) => valid += 1,
            Err(_) => {
                collide += 1;
                if depth <= 1e-7 {
                    disagree += 1;
                }
            }
        }
    }
    assert!(
        valid >= 30 && collide >= 30,
        "valid {valid}, colliding {collide}"
    );
    assert!(
        sampled_collide >= 30,
        "sampling saw {sampled_collide} collisions"
    );
    assert!(
        disagree <= 4,
        "{disagree} rejected where sampling sees no overlap"
    );
}

// ------------------------------------------------------ moving clearance

/// The distance of the robot and the obstacle at one instant (0 when they
/// meet; +∞ when the obstacle is gone), from the static shapes.
fn distance_at(robot: &RobotShape, traj: &[Timed], o: &MovingObstacle, t: f64) -> f64 {
    let Some(c) = o.position(t) else {
        return f64::INFINITY;
    };
    let r = robot_at(traj, t);
    let body = Body::of(robot, r.theta);
    let d = c - Point::new(r.x, r.y);
    let gap = match (&o.shape, &body) {
        (MovingShape::Disk(ro), Body::Round(rr)) => d.norm() - ro - rr,
        (MovingShape::Disk(ro), Body::Convex(v)) => point_polygon_distance(Point::from(d), v) - ro,
        (MovingShape::Pieces(pieces), body) => pieces
            .iter()
            .map(|piece| {
                let placed: Vec<Point> = piece.iter().map(|q| q + d).collect();
                match body {
                    Body::Round(rr) => point_polygon_distance(Point::origin(), &placed) - rr,
                    Body::Convex(v) => convex_distance(v, &placed),
                }
            })
            .fold(f64::INFINITY, f64::min),
    };
    gap.max(0.0)
}

#[test]
fn a_passing_cart_comes_as_close_as_its_closest_approach() {
    // The robot (a disk of 0.3) parked at the origin; a cart (a disk of
    // 0.5) drives by along y = 2: 2 − 0.5 − 0.3 apart at x = 0.
    let parked = [at(0.0, 0.0, 0.0)];
    let by = cart(&[(0.0, -5.0, 2.0), (10.0, 5.0, 2.0)], After::Vanish);
    let robot = RobotShape::Disk(0.3);
    let c = moving_clearance(std::slice::from_ref(&by), &robot, &parked);
    assert!((c - 1.2).abs() < 1e-12, "{c}");
    // Driving towards it along y: the robot reaches (0, 1) at t = 5, when
    // the cart is at (0, 2): 1 − 0.8 apart.
    let towards = [at(0.0, 0.0, 0.0), at(0.0, 1.0, 5.0)];
    let c = moving_clearance(std::slice::from_ref(&by), &robot, &towards);
    assert!((c - 0.2).abs() < 1e-12, "{c}");
    // A square that vanishes before it comes near counts only while there.
    let early = MovingObstacle {
        shape: MovingShape::Pieces(vec![square(0.5)]),
        ..cart(&[(0.0, -9.0, 0.0), (2.0, -5.0, 0.0)], After::Vanish)
    };
    let c = moving_clearance(std::slice::from_ref(&early), &RobotShape::Point, &parked);
    assert!((c - 4.5).abs() < 1e-12, "{c}");
    // Overlapping: 0; nothing at all: +∞.
    let on = cart(&[(0.0, 0.0, 0.0)], After::Stay);
    assert_eq!(moving_clearance(&[on], &robot, &parked), 0.0);
    assert_eq!(moving_clearance(&[], &robot, &parked), f64::INFINITY);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// The exact clearance is never more than what sampling every 1e-4 s
    /// sees, and sampling comes within what half a step can hide (the robot
    /// and the obstacle each cover at most 17 units in 0.05 s here: under
    /// 700 units/s apart, 0.035 per half step).
    #[test]
    fn the_moving_clearance_agrees_with_dense_sampling(
        robot in robot(),
        o in moving(),
        traj in trajectory(),
    ) {
        let exact = moving_clearance(std::slice::from_ref(&o), &robot, &traj);
        let end = traj.last().unwrap().t.max(o.settles()) + 1e-3;
        let n = (end / 1e-4).ceil() as usize;
        let sampled = (0..=n)
            .map(|k| distance_at(&robot, &traj, &o, k as f64 * 1e-4))
            .fold(f64::INFINITY, f64::min);
        prop_assert!(exact <= sampled + 1e-9, "exact {exact} above sampled {sampled}");
        prop_assert!(sampled - exact <= 0.035, "exact {exact}, sampled {sampled}");
    }
}
