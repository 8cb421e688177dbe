//! `hybrid_astar`, through scenarios written as text.

use crate::scenario::load_text;

fn notes(robot_radius: &str, world: &str) -> (bool, Vec<String>) {
    let s = load_text(&format!(
        "world {{ bounds (0, 0) (30, 20) {world} }}
robot car polygon [(-1, -0.8), (3, -0.8), (3, 0.8), (-1, 0.8)] steer reeds_shepp {robot_radius}
plan p hybrid_astar car {{ start (2, 5, 90deg) goal (20, 5, 270deg) limit time 20s }}
"
    ));
    let plan = &s.plans[0];
    let out = plan.settings.plan(&plan.task(&s));
    (out.path.is_some(), out.notes)
}

/// A turning radius far below `step`: every arc of `step` spins in
/// place (and is too long to validate), so the search can only go
/// straight; the note says so, and how to fix it. An unreachable goal
/// at a sound radius gets the plain note.
#[test]
fn arcs_of_more_than_half_a_turn_are_named_when_no_path_is_found() {
    let (found, n) = notes("0.000001", "rect W (10, 0) (12, 12)");
    assert!(!found);
    assert!(
        n.iter().any(|n| n.contains("more than half a turn")),
        "{n:?}"
    );
    let room = "rect A (16, 0.5) (24, 1) rect B (16, 8) (24, 8.5) \
                rect C (16, 0.5) (17, 8.5) rect D (23, 0.5) (24, 8.5)";
    let (found, n) = notes("2", room);
    assert!(!found);
    assert!(
        n.iter().any(|n| n.starts_with("every cell reachable")),
        "{n:?}"
    );
    assert!(!n.iter().any(|n| n.contains("half a turn")), "{n:?}");
    // So tiny a radius that no steering length is finite (fuzzer seed
    // 777006): the note names the radius instead.
    let (found, n) = notes("1e-300", "");
    assert!(!found);
    assert!(n.iter().any(|n| n.contains("radius 1e-300")), "{n:?}");
    assert!(!n.iter().any(|n| n.contains("half a turn")), "{n:?}");
}
