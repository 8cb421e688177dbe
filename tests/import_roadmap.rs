//! `scen import roadmap FILE`: a SEEDS §D input file becomes a scenario that
//! runs; malformed input files get a diagnostic at the bad line (exit 2).

mod common;

use common::Test;

/// A closed chain of four segments and a wall, a 1×1 robot.
const INPUT: &str = "5
2, 2, 6, 2
6, 2, 6, 6
6, 6, 2, 6
2, 6, 2, 2
8, 1, 8, 7
0, 4
10, 4
4
0, 0
1, 0
1, 1
0, 1
";

#[test]
fn an_input_file_becomes_a_scenario_that_runs() {
    let t = Test::new()
        .file("input.txt", INPUT)
        .args(&["import", "roadmap", "input.txt"])
        .stdout_contains("segment s5 (8, 1) (8, 7)")
        .stdout_contains("robot r polygon [(0, 0), (1, 0), (1, 1), (0, 1)]")
        .stdout_contains("plan vg roadmap r {")
        .status(0);
    let out = t.run();
    Test::new()
        .file("x.scen", &String::from_utf8_lossy(&out.stdout))
        .args(&["run", "x.scen"])
        .stdout_contains("plan vg (roadmap, robot r): found, collision-free")
        .stdout_contains("2 passed, 0 failed")
        .status(0)
        .run();
}

#[test]
fn a_point_robot_without_the_optional_part() {
    let text: String = INPUT.lines().take(8).map(|l| format!("{l}\n")).collect();
    Test::new()
        .file("input.txt", &text)
        .args(&["import", "roadmap", "input.txt"])
        .stdout_contains("robot r point")
        .status(0)
        .run();
}

#[test]
fn a_short_line_is_reported_at_its_line() {
    let text = INPUT.replace("6, 6, 2, 6", "6, 6, 2");
    Test::new()
        .file("input.txt", &text)
        .args(&["import", "roadmap", "input.txt"])
        .stderr_contains("segment 3 of 5: expected 4 number(s)")
        .stderr_contains("input.txt:4:1")
        .stdout("")
        .status(2)
        .run();
}

#[test]
fn a_word_instead_of_a_number() {
    Test::new()
        .file("input.txt", &INPUT.replace("10, 4", "ten, 4"))
        .args(&["import", "roadmap", "input.txt"])
        .stderr_contains("the goal: `ten` is not a number")
        .stderr_contains("input.txt:8:1")
        .status(2)
        .run();
}

#[test]
fn a_missing_file_and_an_unknown_format() {
    Test::new()
        .args(&["import", "roadmap", "nope.txt"])
        .stderr_contains("cannot read `nope.txt`")
        .status(2)
        .run();
    Test::new()
        .file("input.txt", INPUT)
        .args(&["import", "lattice", "input.txt"])
        .stderr_contains("unknown import format `lattice`")
        .status(2)
        .run();
}
