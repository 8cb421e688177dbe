//! `astar` for polygon robots ((x, y, θ) lattice), through scenarios
//! written as text.

use crate::contract::{MetricValue, PlanOutcome};
use crate::geometry::{RobotShape, angle_diff};

const APARTMENT: &str = "world {
  bounds (0, 0) (32, 30)
  rect B01 (0, 29) (32, 30)
  rect B02 (0, 0)  (1, 30)
  rect B03 (0, 0)  (32, 1)
  rect B04 (31, 0) (32, 30)
  rect B1  (0, 18) (10, 19)
  rect B2  (17, 17) (18, 29)
  rect B3  (25, 18) (32, 19)
  rect B4  (0, 14) (19, 15)
  rect B5  (24, 13) (32, 15)
  rect B6  (10, 19) (12, 20)
  rect B7  (23, 19) (25, 20)
}
robot rod polygon [(0,0), (8,0), (8,1), (0,1)]
";

/// Runs every plan of the scenario (each for a polygon robot); every path
/// must pass the validator.
fn run(text: &str) -> Vec<PlanOutcome> {
    let s = crate::scenario::load_text(text);
    for p in &s.plans {
        assert!(
            matches!(s.robots[p.robot].shape, RobotShape::Polygon(_)),
            "a polygon robot"
        );
    }
    super::run_checked(&s)
}

fn apartment_plan(name: &str, extra: &str) -> String {
    format!(
        "scenario \"t\"\n{APARTMENT}plan {name} astar rod {{\n  start (4, 24, 0deg)\n  goal (4, 8, 0deg)\n  {extra}\n}}\n"
    )
}

#[test]
fn apartment_paths_pass_the_validator() {
    let mut text = format!("scenario \"t\"\n{APARTMENT}");
    let variants = [
        "layers 51 connect 6 cost l1 turn_cost 1",
        "layers 70 connect 6 cost l1 turn_cost 1",
        "layers 51 connect 6 cost l1 turn_cost 1 sample corner",
        "layers 51",
        "layers 40 sample corner cost l1",
        "layers 60 connect 26 weight 3",
        "cell 0.6666666666666666 layers 76 connect 26",
        "cell 0.5 layers 7 connect 26",
        "cell 0.5 layers 2 connect 26",
        "layers 51 heuristic zero connect 6",
    ];
    for (i, v) in variants.iter().enumerate() {
        text += &format!(
            "plan p{i} astar rod {{\n start (4, 24, 0deg)\n goal (4, 8, 0deg)\n {v}\n}}\n"
        );
    }
    let outs = run(&text);
    assert!(
        outs[0].path.is_none(),
        "SEEDS: no path with centres and 51 layers"
    );
    assert!(outs[1].path.is_some());
    assert!(outs[2].path.is_some());
    for o in &outs {
        assert!(o.expanded > 0);
    }
}

#[test]
fn heuristic_zero_finds_the_same_cost() {
    let outs = run(&format!(
        "scenario \"t\"\n{APARTMENT}{}{}",
        "plan a astar rod { start (4, 24, 0deg) goal (4, 8, 0deg) layers 70 connect 6 cost l1 turn_cost 1 }\n",
        "plan b astar rod { start (4, 24, 0deg) goal (4, 8, 0deg) layers 70 connect 6 cost l1 turn_cost 1 heuristic zero }\n",
    ));
    let (a, b) = (outs[0].cost.unwrap(), outs[1].cost.unwrap());
    assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    assert!(outs[1].expanded > outs[0].expanded);
}

#[test]
fn rotate_no_is_a_search_in_one_layer() {
    // The rod at 0deg in a room with a pillar: `rotate no` (4 or 8
    // neighbours) equals one layer at θ = 0 (6 / 26 neighbours without
    // θ moves).
    let world = "world {
  bounds (0, 0) (30, 20)
  rect P (10, 5) (14, 16)
  rect Q (18, 0) (20, 9)
}
robot rod polygon [(0,0), (8,0), (8,1), (0,1)]
";
    for (a, b) in [("4", "6"), ("8", "26")] {
        let outs = run(&format!(
            "scenario \"t\"\n{world}plan a astar rod {{ start (1, 2, 0deg) goal (21, 17, 0deg) rotate no connect {a} }}\nplan b astar rod {{ start (1, 2, 0deg) goal (21, 17, 0deg) layers 1 connect {b} }}\n"
        ));
        let (ca, cb) = (outs[0].cost.unwrap(), outs[1].cost.unwrap());
        assert_eq!(ca, cb);
        assert_eq!(outs[0].expanded, outs[1].expanded);
        assert_eq!(outs[0].extra["layers"], MetricValue::Num(1.0));
        let path = outs[0].path.as_ref().unwrap();
        assert!(path.iter().all(|c| c.theta == 0.0));
    }
    // At another fixed θ the path keeps that θ.
    let outs = run(&format!(
        "scenario \"t\"\n{world}plan a astar rod {{ start (1, 10, 10deg) goal (22, 10, 10deg) rotate no }}\n"
    ));
    let path = outs[0].path.as_ref().unwrap();
    let theta = 10f64.to_radians();
    assert!(path.iter().all(|c| (c.theta - theta).abs() < 1e-12));
}

/// A wall with a gap of `gap` around x = 10: the rod (8 long) must stand
/// up to pass.
fn corridor(gap: f64) -> String {
    let (l, r) = (10.0 - gap / 2.0, 10.0 + gap / 2.0);
    format!(
        "scenario \"t\"
world {{
  bounds (0, 0) (20, 30)
  rect L (0, 14.5) ({l}, 15.5)
  rect R ({r}, 14.5) (20, 15.5)
}}
robot rod polygon [(0,0), (8,0), (8,1), (0,1)]
plan p astar rod {{ start (4, 4, 0deg) goal (4, 24, 0deg) layers 32 }}
plan q astar rod {{ start (4, 4, 0deg) goal (4, 24, 0deg) layers 32 rotate no }}
"
    )
}

#[test]
fn the_rod_must_rotate_to_pass_the_gap() {
    let outs = run(&corridor(3.0));
    let path = outs[0].path.as_ref().expect("a path through the gap");
    let turn: f64 = path
        .windows(2)
        .map(|w| angle_diff(w[0].theta, w[1].theta).abs())
        .sum();
    assert!(turn > 2.0, "turn {turn}");
    assert!(
        outs[1].path.is_none(),
        "without rotating the rod cannot pass"
    );
    assert!(outs[1].notes.is_empty());
}

#[test]
fn a_gap_narrower_than_the_rod_is_unreachable() {
    let outs = run(&corridor(0.9));
    assert!(outs[0].path.is_none());
    assert!(!outs[0].gave_up);
    assert!(outs[0].notes.is_empty());
    assert!(outs[0].expanded > 1000);
}

#[test]
fn limits_give_up() {
    let outs = run(&apartment_plan("p", "layers 51 limit expansions 100"));
    assert!(outs[0].path.is_none());
    assert!(outs[0].gave_up);
    assert_eq!(outs[0].expanded, 100);
}

#[test]
fn a_blocked_snapped_start_is_named() {
    // The rod lies just below the ceiling piece C; the nearest lattice
    // point (y = 2.5) would put it into C.
    let text = "scenario \"t\"
world {
  bounds (0, 0) (20, 10)
  rect C (0, 3.2) (20, 5)
}
robot rod polygon [(0,0), (8,0), (8,1), (0,1)]
plan p astar rod { start (5, 2.1, 0deg) goal (10, 1, 0deg) layers 8 }
plan q astar rod { start (10, 1, 0deg) goal (5, 2.1, 0deg) layers 8 }
";
    let outs = run(text);
    assert!(outs[0].path.is_none());
    assert!(outs[0].notes[0].contains("the start could not be connected"));
    assert!(outs[1].path.is_none());
    assert!(outs[1].notes[0].contains("the goal could not be connected"));
    assert_eq!(outs[0].expanded, 0);
}
