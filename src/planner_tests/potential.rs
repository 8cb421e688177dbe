//! `potential`, through scenarios written as text.

use crate::contract::PlanOutcome;
use crate::contract::layers::Drawing;
use crate::geometry::{Config, Point, RobotShape};
use proptest::prelude::*;

/// Runs every plan; a found path must start at the start, end at the goal
/// and pass the validator.
fn run(text: &str) -> Vec<PlanOutcome> {
    super::run_checked(&crate::scenario::load_text(text))
}

/// The points of a `Points` layer.
fn points(out: &PlanOutcome, entity: &str) -> Vec<Point> {
    match out.layer(entity).map(|l| &l.drawing) {
        Some(Drawing::Points(p)) => p.clone(),
        other => panic!("{entity}: {other:?}"),
    }
}

fn metric(out: &PlanOutcome, name: &str) -> f64 {
    out.extra[name].as_f64()
}

/// A U of segment walls around (8, 5) whose bottom faces the goal at
/// (15, 5): pure descent from inside is trapped against the bottom.
const U_TRAP: &str = "world {
  bounds (0, 0) (20, 10)
  segment bottom (10, 2) (10, 8)
  segment upper (5, 8) (10, 8)
  segment lower (5, 2) (10, 2)
}
robot p point
robot d disk 0.3
";

fn u_plan(name: &str, robot: &str, extra: &str) -> String {
    format!("plan {name} potential {robot} {{ start (7, 5) goal (15, 5) {extra} }}\n")
}

#[test]
fn free_world_is_a_straight_line() {
    let outs = run("world { bounds (0, 0) (10, 10) }
robot p point
plan a potential p { start (1, 1) goal (9.1, 7) }
plan b potential p { start (2, 8) goal (8.3, 8.3) step 0.3 }
");
    for (o, (start, goal, step)) in outs.iter().zip([
        (Point::new(1.0, 1.0), Point::new(9.1, 7.0), 0.05),
        (Point::new(2.0, 8.0), Point::new(8.3, 8.3), 0.3),
    ]) {
        let path = o.path.as_ref().expect("found");
        let dir = (goal - start).normalize();
        for (k, c) in path.iter().enumerate() {
            let v = c.xy() - start;
            // On the line from start to goal, ε apart (the last move shorter).
            assert!(dir.perp(&v).abs() < 1e-9, "off the line at {k}");
            if k > 0 && k < path.len() - 1 {
                assert!((v.norm() - k as f64 * step).abs() < 1e-9);
            }
        }
        let last = (path[path.len() - 1].xy() - path[path.len() - 2].xy()).norm();
        assert!(last <= step + 1e-12);
        let steps = ((goal - start).norm() / step).ceil();
        assert_eq!(metric(o, "steps"), steps);
        assert_eq!(o.expanded as f64, steps);
        assert_eq!(path.len() as f64, steps + 1.0);
        assert_eq!(metric(o, "minima"), 0.0);
        assert_eq!(metric(o, "escapes"), 0.0);
        assert!(!o.gave_up);
    }
}

#[test]
fn u_trap_stops_pure_descent_and_the_random_walk_escapes() {
    let text = format!(
        "{U_TRAP}{}{}{}{}",
        u_plan("descent", "p", "escape none"),
        u_plan("walk", "p", ""),
        u_plan("disk_descent", "d", "escape none"),
        u_plan("disk_walk", "d", "seed 5"),
    );
    let outs = run(&text);
    for o in [&outs[0], &outs[2]] {
        assert!(o.path.is_none());
        assert!(!o.gave_up);
        assert!(metric(o, "minima") >= 1.0);
        assert_eq!(metric(o, "escapes"), 0.0);
        // The minimum is against the bottom of the U, inside it.
        let m = points(o, "field/minima")[0];
        assert!(m.x > 7.0 && m.x < 10.0 && (m.y - 5.0).abs() < 1.0, "{m:?}");
        assert!(o.notes[0].contains("local minimum"));
    }
    for o in [&outs[1], &outs[3]] {
        assert!(o.path.is_some(), "{:?}", o.notes);
        assert!(metric(o, "minima") >= 1.0);
        assert!(metric(o, "escapes") >= 1.0);
        let jumps = match o.layer("field/escapes").map(|l| &l.drawing) {
            Some(Drawing::Segments(s)) => s.clone(),
            other => panic!("escapes: {other:?}"),
        };
        assert_eq!(jumps.len() as f64, metric(o, "escapes"));
        assert_eq!(points(o, "field/minima").len() as f64, metric(o, "minima"));
        // Each escape is a move of the path: from one point to the next.
        let path = o.path.as_ref().unwrap();
        for (from, to) in jumps {
            assert!(
                path.windows(2)
                    .any(|w| w[0].xy() == from && w[1].xy() == to),
                "the jump {from:?} → {to:?} is not on the path"
            );
        }
        assert!(o.layers_of("field/total").count() > 0);
    }
}

#[test]
fn same_seed_same_walk_other_seed_other_walk() {
    let text = format!(
        "{U_TRAP}{}{}{}",
        u_plan("a", "p", "seed 1"),
        u_plan("b", "p", "seed 1"),
        u_plan("c", "p", "seed 2"),
    );
    let (x, y) = (run(&text), run(&text));
    let paths: Vec<_> = x.iter().map(|o| o.path.clone().expect("found")).collect();
    assert_eq!(paths[0], paths[1]);
    assert_eq!(paths[0], y[0].path.clone().unwrap());
    assert_ne!(paths[0], paths[2], "another seed, another walk");
}

#[test]
fn limits_end_the_walk() {
    let text = format!(
        "{U_TRAP}{}{}{}",
        u_plan("steps", "p", "limit steps 40"),
        u_plan("expansions", "p", "limit expansions 30"),
        // Overshooting (SEEDS §E): steps of 0.5 with a tolerance of 0.001
        // rarely land; the default step limit is not needed to end it.
        u_plan("time", "p", "limit time 1ms limit steps 1000000"),
    );
    let outs = run(&text);
    assert!(outs[0].gave_up && outs[0].path.is_none());
    assert_eq!(metric(&outs[0], "steps"), 40.0);
    assert!(outs[0].notes[0].contains("step limit (40)"));
    assert_eq!(metric(&outs[1], "steps"), 30.0);
    // 1 ms may or may not be enough on a loaded machine; either way the run
    // ends and reports honestly.
    assert!(outs[2].gave_up || outs[2].path.is_some());
}

#[test]
fn overshooting_walk_ends_by_its_limit_and_says_so() {
    // Steps of 0.7 with a tolerance of 1e-6 (SEEDS §E: ε too large): the
    // walk reaches the goal's neighbourhood in 8 steps, then bounces across
    // the goal; the step limit ends it before the oscillation test would.
    let outs = run("world { bounds (0, 0) (10, 10) }
robot p point
plan over potential p { start (1, 1) goal (5.05, 5.05) step 0.7 tolerance 0.000001 limit steps 14 }
");
    let o = &outs[0];
    assert!(o.path.is_none() && o.gave_up);
    assert_eq!(metric(o, "steps"), 14.0);
    assert!(o.notes[0].contains("overshoots"), "{:?}", o.notes);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Whatever the obstacles and ends, the walk ends within its limit and
    /// every trajectory it returns passes the validator (checked in `run`).
    #[test]
    fn walks_pass_the_validator(
        walls in prop::collection::vec(
            ((1.0..19.0f64, 1.0..19.0f64), (-6.0..6.0f64, -6.0..6.0f64)), 1..8),
        disks in prop::collection::vec(((1.0..19.0f64, 1.0..19.0f64), 0.2..2.0f64), 0..3),
        rects in prop::collection::vec(((1.0..19.0f64, 1.0..19.0f64), (0.2..3.0f64, 0.2..3.0f64)), 0..3),
        triangle in any::<bool>(),
        start in (0.0..20.0f64, 0.0..20.0f64),
        goal in (0.0..20.0f64, 0.0..20.0f64),
        disk_robot in any::<bool>(),
        seed in 0u64..1000,
        step in prop_oneof![Just(0.05), 0.05..0.6f64],
    ) {
        let mut text = String::from("world {\n bounds (0, 0) (20, 20)\n");
        for ((x, y), (dx, dy)) in &walls {
            text += &format!(" segment ({x}, {y}) ({}, {})\n", x + dx + 0.01, y + dy);
        }
        for ((x, y), r) in &disks {
            text += &format!(" disk ({x}, {y}) {r}\n");
        }
        for ((x, y), (w, h)) in &rects {
            text += &format!(" rect ({x}, {y}) ({}, {})\n", x + w, y + h);
        }
        if triangle {
            text += " polygon [(12, 12), (16, 12), (14, 15), (14, 13)]\n";
        }
        text += "}\nrobot p point\nrobot d disk 0.3\n";
        // Start and goal must be free: check with the validator's own test.
        let probe = crate::scenario::world_of_text(&text);
        let robot = if disk_robot { RobotShape::Disk(0.3) } else { RobotShape::Point };
        let free = |(x, y): (f64, f64)| {
            crate::geometry::validator::config_collision(&probe, &robot, Config::new(x, y, 0.0))
                .is_none()
        };
        prop_assume!(free(start) && free(goal));
        let name = if disk_robot { "d" } else { "p" };
        text += &format!(
            "plan w potential {name} {{ start ({}, {}) goal ({}, {}) step {step} seed {seed} limit steps 20000 }}\n",
            start.0, start.1, goal.0, goal.1
        );
        let outs = run(&text);
        prop_assert!(metric(&outs[0], "steps") <= 20000.0);
    }
}

#[test]
fn walks_among_grid_cells_and_polygons_pass_the_validator() {
    let outs = run("world {
  bounds (0, 0) (20, 10)
  polygon P [(8, 2), (12, 2), (12, 8), (11, 8), (11, 3), (8, 3)]
  grid G cell 1 origin (14, 0) {
    \"......\"
    \"..##..\"
    \"..##..\"
    \"......\"
  }
  rect R (4, 6) (5, 9)
}
robot p point
robot d disk 0.4
plan a potential p { start (1, 5) goal (18, 5) seed 1 }
plan b potential d { start (1, 5) goal (18, 5) seed 2 }
plan c potential p { start (18, 2) goal (1, 1) }
");
    for o in &outs {
        assert!(o.path.is_some(), "{:?}", o.notes);
    }
}

#[test]
fn cancelled_repulsion_is_not_an_opposed_minimum() {
    // Midway between two parallel walls the repulsions cancel; what is left
    // is rounding noise, pointing anywhere (here, at times, straight back):
    // the opposition test must not take it for a minimum.
    let outs = run("world {
  bounds (0, 0) (100, 10)
  segment (0, 3) (200, 3)
  segment (0, 7) (200, 7)
}
robot p point
plan a potential p { start (1, 5) goal (99, 5) influence 3 escape none }
");
    assert!(outs[0].path.is_some(), "{:?}", outs[0].notes);
    assert_eq!(metric(&outs[0], "minima"), 0.0);
}

#[test]
fn head_on_approach_to_a_wall_is_not_stuck_at_the_edge_of_influence() {
    // Issue 39: the opposition test fired as soon as the wall's repulsion
    // appeared, at ρ = ρ0, though the attraction was still stronger and the
    // walk could advance. Head-on along y = 5 towards the face x = 10 of a
    // wall, with the goal g behind the face: at distance ρ from the face,
    // |F_att| = η (ρ + g) and |F_rep| = d (1/ρ²)(1/ρ − 1/ρ0) (SPEC 3.4). The
    // first falls and the second rises as ρ shrinks, so they balance at one
    // ρ*; η is chosen so that ρ* = 0.5.
    let (d, rho0, g, rho_star, step) = (1.0, 2.0, 5.5, 0.5, 0.05);
    let eta = d / (rho_star * rho_star) * (1.0 / rho_star - 1.0 / rho0) / (rho_star + g);
    let outs = run(&format!(
        "world {{
  bounds (0, 0) (20, 10)
  rect wall (10, 0) (11, 10)
}}
robot p point
plan a potential p {{ start (1, 5) goal ({}, 5) attract {eta} repulse {d} influence {rho0} step {step} escape none }}
",
        10.0 + g
    ));
    let o = &outs[0];
    assert!(o.path.is_none());
    assert_eq!(metric(o, "minima"), 1.0);
    assert!(o.notes[0].contains("opposed"), "{:?}", o.notes);
    let m = points(o, "field/minima")[0];
    let rho = 10.0 - m.x;
    // Stuck at the first step that reaches the balance, not 1.5 units
    // before it where the repulsion begins.
    assert!((m.y - 5.0).abs() < 1e-9, "{m:?}");
    assert!(
        rho <= rho_star && rho > rho_star - step - 1e-9,
        "stuck at ρ = {rho}"
    );
}
