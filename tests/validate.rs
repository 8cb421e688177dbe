//! `scen validate` (SPEC 7): a path made elsewhere, judged by the validator
//! against a plan's world and robot, as a user runs it.

mod common;

use common::Test;

/// A room with a wall in the middle, a disk robot and two plans.
const ROOM: &str = r#"scenario "room"
world {
  bounds (0, 0) (10, 10)
  rect wall (4, 0) (6, 7)
}
robot dot disk 0.5
plan p astar dot {
  start (1.5, 1.5)
  goal (8.5, 1.5)
}
plan q astar dot {
  start (1.5, 8.5)
  goal (8.5, 8.5)
}
expect p.found and p.collision_free
expect p.expanded > 0
expect q.found
"#;

#[test]
fn what_scen_run_writes_reads_back_as_valid() {
    let t = Test::new().file("room.scen", ROOM).args(&[
        "run",
        "room.scen",
        "--csv",
        "runs.csv",
        "--json",
    ]);
    t.run();
    let v = Test::new()
        .file("room.scen", ROOM)
        .file(
            "runs.csv",
            &std::fs::read_to_string(t.dir().join("runs.csv")).unwrap(),
        )
        .args(&["validate", "room.scen", "--plan", "p", "--path", "runs.csv"])
        .stdout_contains("valid: the path passes the validator")
        .stdout_contains("PASS")
        // The planner's own metric and the other plan's check are skipped.
        .stdout_contains("2 check(s) skipped")
        .status(0);
    v.run();
    // The same through the JSON document of `scen run --json`.
    let out = Test::new()
        .file("room.scen", ROOM)
        .args(&["run", "room.scen", "--json"])
        .run();
    Test::new()
        .file("room.scen", ROOM)
        .file("run.json", &String::from_utf8_lossy(&out.stdout))
        .args(&["validate", "room.scen", "--plan", "q", "--path", "run.json"])
        .stdout_contains("valid: the path passes the validator")
        .status(0)
        .run();
}

#[test]
fn a_colliding_path_is_located_and_drawn() {
    let t = Test::new()
        .file("room.scen", ROOM)
        // Straight through the wall.
        .file("mine.csv", "x,y\n1.5,1.5\n8.5,1.5\n")
        .args(&[
            "validate",
            "room.scen",
            "--plan",
            "p",
            "--path",
            "mine.csv",
            "--svg",
            "mine.svg",
        ])
        .stdout_contains("collides: on segment 0 (from pose 0 to pose 1)")
        .stdout_contains("obstacle `wall`")
        .status(1);
    t.run();
    let svg = std::fs::read_to_string(t.dir().join("mine.svg")).expect("the picture");
    assert!(
        svg.contains("first collision"),
        "the collision is in the legend"
    );
    // JSON: not collision-free, the path's length as its cost.
    let out = Test::new()
        .file("room.scen", ROOM)
        .file("mine.json", "[[1.5, 1.5], [8.5, 1.5]]")
        .args(&[
            "validate",
            "room.scen",
            "--plan",
            "p",
            "--path",
            "mine.json",
            "--json",
        ])
        .status(1)
        .run();
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let p = &doc["plans"]["p"];
    assert_eq!(p["metrics"]["collision_free"], false);
    assert_eq!(p["metrics"]["cost"], 7.0);
    assert!(p["metrics"].get("expanded").is_none(), "{p}");
    // Around the wall: valid.
    Test::new()
        .file("room.scen", ROOM)
        .file(
            "around.csv",
            "x,y,theta\n1.5,1.5,0\n1.5,8.5,0\n8.5,8.5,0\n8.5,1.5,0\n",
        )
        .args(&[
            "validate",
            "room.scen",
            "--plan",
            "p",
            "--path",
            "around.csv",
        ])
        .stdout_contains("valid")
        .status(0)
        .run();
}

#[test]
fn bad_input_is_located_with_exit_2() {
    Test::new()
        .file("room.scen", ROOM)
        .file("bad.csv", "x,y\n1.5,1.5\n8.5,oops\n")
        .args(&["validate", "room.scen", "--plan", "p", "--path", "bad.csv"])
        .stderr_contains("scen::validate::bad_row")
        .stderr_contains("bad.csv:3:5")
        .stderr_contains("the path was not validated")
        .status(2)
        .run();
    Test::new()
        .file("room.scen", ROOM)
        .file("bad.json", "[[1, 2],\n [3, ]]")
        .args(&["validate", "room.scen", "--plan", "p", "--path", "bad.json"])
        .stderr_contains("scen::validate::bad_json")
        .stderr_contains("bad.json:2:")
        .status(2)
        .run();
    Test::new()
        .file("room.scen", ROOM)
        .file("p.csv", "x,y\n1,1\n")
        .args(&["validate", "room.scen", "--plan", "nope", "--path", "p.csv"])
        .stderr_contains("has no plan `nope` (plans: p, q)")
        .status(2)
        .run();
    Test::new()
        .file("room.scen", ROOM)
        .args(&[
            "validate",
            "room.scen",
            "--plan",
            "p",
            "--path",
            "missing.csv",
        ])
        .stderr_contains("scen::validate::unreadable")
        .status(2)
        .run();
    // An output never replaces an input: the path file itself.
    Test::new()
        .file("room.scen", ROOM)
        .file("p.csv", "x,y\n1.5,1.5\n")
        .args(&[
            "validate",
            "room.scen",
            "--plan",
            "p",
            "--path",
            "p.csv",
            "--csv",
            "p.csv",
        ])
        .stderr_contains("the path being validated")
        .status(2)
        .run();
}

/// A cart crossing the robot's way at x = 5 (up, 1 unit/s, from y = 0 at
/// t = 0, then gone).
const CROSSING: &str = r#"scenario "crossing"
world {
  bounds (0, 0) (10, 10)
  moving cart disk 0.5 { at 0s (5, 0) at 10s (5, 10) then vanish }
}
robot dot disk 0.3 speed 1
plan p sipp dot {
  start (1.5, 5.5)
  goal (8.5, 5.5)
}
expect p.collision_free
"#;

#[test]
fn a_trajectory_is_judged_in_space_time() {
    // What `scen run --csv` writes (with `t`) reads back as valid, and so
    // does the `"trajectory"` of `scen run --json`.
    let t = Test::new()
        .file("c.scen", CROSSING)
        .args(&["run", "c.scen", "--csv", "runs.csv", "--json"]);
    let out = t.run();
    let csv = std::fs::read_to_string(t.dir().join("runs.csv")).unwrap();
    assert!(
        csv.lines()
            .nth(2)
            .is_some_and(|l| l.starts_with("p,path,1,1,")),
        "{csv}"
    );
    for (name, text) in [
        ("runs.csv", csv),
        (
            "run.json",
            String::from_utf8_lossy(&out.stdout).into_owned(),
        ),
    ] {
        Test::new()
            .file("c.scen", CROSSING)
            .file(name, &text)
            .args(&["validate", "c.scen", "--plan", "p", "--path", name])
            .stdout_contains("valid: the path passes the validator")
            .status(0)
            .run();
    }
    // Waiting a little, then crossing x = 5 at t = 5 with the cart there.
    Test::new()
        .file("c.scen", CROSSING)
        .file(
            "fast.csv",
            "x,y,t\n1.5,5.5,0\n3.5,5.5,2\n3.5,5.5,3.5\n8.5,5.5,8.5\n",
        )
        .args(&["validate", "c.scen", "--plan", "p", "--path", "fast.csv"])
        .stdout_contains("obstacle `cart`")
        .stdout_contains("the robot meets the moving obstacle `cart` at t = ")
        .status(1)
        .run();
    // Waiting for it at (3.5, 5.5) until t = 7: valid (JSON points).
    Test::new()
        .file("c.scen", CROSSING)
        .file(
            "wait.json",
            "[[1.5, 5.5, 0, 0], [3.5, 5.5, 0, 2], [3.5, 5.5, 0, 7], [8.5, 5.5, 0, 12]]",
        )
        .args(&["validate", "c.scen", "--plan", "p", "--path", "wait.json"])
        .stdout_contains("valid: the path passes the validator")
        .stdout_contains("waited 5")
        .status(0)
        .run();
    // Faster than the robot's speed.
    Test::new()
        .file("c.scen", CROSSING)
        .file("speeding.csv", "x,y,t\n1.5,5.5,0\n3.5,5.5,1\n")
        .args(&[
            "validate",
            "c.scen",
            "--plan",
            "p",
            "--path",
            "speeding.csv",
        ])
        .stdout_contains("faster than the robot's speed 1")
        .status(1)
        .run();
}

#[test]
fn among_moving_obstacles_a_path_needs_its_times() {
    Test::new()
        .file("c.scen", CROSSING)
        .file("p.csv", "x,y\n1.5,5.5\n8.5,5.5\n")
        .args(&["validate", "c.scen", "--plan", "p", "--path", "p.csv"])
        .stderr_contains("scen::validate::needs_times")
        .stderr_contains("`cart`")
        .status(2)
        .run();
    Test::new()
        .file("c.scen", CROSSING)
        .file("mixed.csv", "x,y,t\n1.5,5.5,0\n8.5,5.5,\n")
        .args(&["validate", "c.scen", "--plan", "p", "--path", "mixed.csv"])
        .stderr_contains("scen::validate::bad_row")
        .stderr_contains("mixed.csv:3:9")
        .status(2)
        .run();
    Test::new()
        .file("c.scen", CROSSING)
        .file("mixed.json", "[[1.5, 5.5, 0, 0], [8.5, 5.5]]")
        .args(&["validate", "c.scen", "--plan", "p", "--path", "mixed.json"])
        .stderr_contains("pose 1 is not")
        .status(2)
        .run();
}
