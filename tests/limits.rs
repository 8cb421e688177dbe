//! Memory and time, as SPEC promises them (the hardening issue's probes):
//! - SPEC 3.2: `online` keeps to the memory of 3.1 whatever the strategy;
//!   D* Lite on a 25-million-cell lattice for a two-cell trip runs in a
//!   fraction of the 512 MiB of address space the test allows (dense
//!   per-cell arrays took 1.6 GB);
//! - SPEC 3.4: a `potential` walk's memory does not grow with `limit
//!   steps`: 12 million moves, and 2³¹ allowed moves cut by `limit time`,
//!   run within the same 512 MiB (the whole trajectory took 24 bytes a
//!   move), and the thinned motion is still validated and measured whole;
//! - SPEC 2.5: `limit time` counts from the plan's start, set-up included:
//!   every planner whose time is up before it starts gives up with a note
//!   that says so, and a 200-million-cell lattice under `limit time 1s`
//!   returns `gave_up`.
//!
//! The memory tests run the real binary under an address-space limit
//! (`ulimit -v`), so that going over the bound fails the run (the binary's
//! own baseline is under 32 MiB). No test asserts a duration; a generous
//! kill-timeout guards against hangs.

mod common;

use std::process::Command;
use std::time::Duration;

use common::planner_cases::{block_world, required, robot};
use common::{Finished, TempDir, run_or_kill, scen_bin};
use scen::contract::Planner;
use scen::contract::schema::RobotKind;
use scen::planners::registry::PLANNERS;

/// The address space the memory tests allow the binary.
const ADDRESS_SPACE_MIB: u64 = 512;

/// Runs `scen ARGS` in `dir` with at most [`ADDRESS_SPACE_MIB`] of address
/// space (and two rayon threads, so that the number of thread stacks does
/// not depend on the machine), killed after `timeout`.
fn scen_limited(dir: &TempDir, args: &[&str], timeout: Duration) -> Finished {
    let script = format!("ulimit -v {}; exec \"$0\" \"$@\"", ADDRESS_SPACE_MIB * 1024);
    let mut cmd = Command::new("sh");
    cmd.arg("-c")
        .arg(script)
        .arg(scen_bin())
        .args(args)
        .current_dir(dir.path())
        .env("NO_COLOR", "1")
        .env("RAYON_NUM_THREADS", "2");
    run_or_kill(&mut cmd, timeout)
}

/// Writes `text` to `name` in `dir`.
fn write(dir: &TempDir, name: &str, text: &str) {
    std::fs::write(dir.path().join(name), text).expect("write the scenario");
}

/// The JSON document of a `scen run --json` that succeeded.
fn json_of(run: &Finished, what: &str) -> serde_json::Value {
    assert_eq!(
        run.status.and_then(|s| s.code()),
        Some(0),
        "{what}: the run failed or was killed (over {ADDRESS_SPACE_MIB} MiB of address space?)\nstderr: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    serde_json::from_slice(&run.stdout).expect("JSON")
}

/// The text report of a `scen run` that succeeded.
fn text_of(run: &Finished, what: &str) -> String {
    assert_eq!(
        run.status.and_then(|s| s.code()),
        Some(0),
        "{what}: the run failed or was killed (over {ADDRESS_SPACE_MIB} MiB of address space?)\nstderr: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8_lossy(&run.stdout).into_owned()
}

#[test]
fn dstar_lite_keeps_search_state_only_where_it_searched() {
    let dir = TempDir::new("limits-dstar");
    write(
        &dir,
        "d.scen",
        r#"scenario "D* Lite across a wide lattice"
world {
  bounds (0, 0) (5000, 5000)
}
robot r point
plan p online r {
  start (0.5, 0.5)
  goal (2.5, 0.5)
  strategy dstar_lite
}
"#,
    );
    let run = scen_limited(&dir, &["run", "--json", "d.scen"], Duration::from_secs(120));
    let doc = json_of(&run, "dstar_lite on 5000 × 5000");
    let m = &doc["plans"]["p"]["metrics"];
    assert_eq!(m["found"], true, "{m}");
    assert_eq!(m["collision_free"], true, "{m}");
    assert_eq!(m["steps"], 2.0, "{m}");
    assert_eq!(m["traveled"], 2.0, "{m}");
    assert_eq!(
        doc["plans"]["p"]["path"],
        serde_json::json!([[0.5, 0.5], [1.5, 0.5], [2.5, 0.5]])
    );
}

/// A straight walk with nothing in the way: the fastest a potential walk
/// moves, so that millions of moves take seconds.
fn straight_walk(limits: &str) -> String {
    format!(
        r#"scenario "potential: a long straight walk"
world {{
  bounds (0, 0) (1000000000, 1)
}}
robot r point
plan p potential r {{
  start (0.5, 0.5)
  goal (999999999, 0.5)
  {limits}
}}
"#
    )
}

#[test]
fn a_long_potential_walk_is_thinned_and_still_checked_whole() {
    let dir = TempDir::new("limits-potential");
    write(&dir, "p.scen", &straight_walk("limit steps 12000000"));
    let run = scen_limited(&dir, &["run", "p.scen"], Duration::from_secs(300));
    let text = text_of(&run, "12 million potential steps");
    // Stopped by its step limit, with the executed motion validated.
    assert!(
        text.contains(
            "not found (gave up: a limit was reached); the motion executed is collision-free"
        ),
        "{text}"
    );
    // 12 million steps of ε = 0.05, measured exactly.
    assert!(text.contains("steps 12000000"), "{text}");
    assert!(text.contains("traveled 599999.999984"), "{text}");
    assert!(
        text.contains(
            "note: the motion has 12000000 moves, more than the 4000000 kept in full: it was validated and measured as it was made, and is listed thinned (every 4th configuration and the last)"
        ),
        "{text}"
    );
}

#[test]
fn a_potential_walk_with_two_billion_steps_allowed_stays_bounded() {
    let dir = TempDir::new("limits-potential-huge");
    write(
        &dir,
        "p.scen",
        &straight_walk("limit steps 2147483648\n  limit time 3s"),
    );
    let run = scen_limited(&dir, &["run", "p.scen"], Duration::from_secs(120));
    let text = text_of(&run, "2³¹ potential steps under `limit time 3s`");
    assert!(
        text.contains(
            "not found (gave up: a limit was reached); the motion executed is collision-free"
        ),
        "{text}"
    );
    assert!(
        text.contains("note: the time limit was reached before the goal"),
        "{text}"
    );
}

/// The world of [`a_200_million_cell_lattice_gives_up_at_its_time_limit`]:
/// 20,000 × 10,000 unit cells (the default cap of 200 million), with the
/// goal walled into the top right corner, so that no machine finds out
/// within a second that it is unreachable: the run must give up.
const WALLED_GOAL: &str = r#"scenario "a 200-million-cell lattice"
world {
  bounds (0, 0) (20000, 10000)
  rect low (19980, 9980) (20000, 9982)
  rect left (19980, 9980) (19982, 10000)
}
robot r point
plan p astar r {
  start (0.5, 0.5)
  goal (19990.5, 9990.5)
  limit time 1s
}
"#;

#[test]
fn a_200_million_cell_lattice_gives_up_at_its_time_limit() {
    let dir = TempDir::new("limits-time");
    write(&dir, "t.scen", WALLED_GOAL);
    let bin = |args: &[&str]| {
        let mut cmd = Command::new(scen_bin());
        cmd.args(args).current_dir(dir.path()).env("NO_COLOR", "1");
        run_or_kill(&mut cmd, Duration::from_secs(30))
    };
    let doc = json_of(&bin(&["run", "--json", "t.scen"]), "limit time 1s");
    let m = &doc["plans"]["p"]["metrics"];
    assert_eq!(m["cells"], 200_000_000.0, "{m}");
    assert_eq!(m["found"], false, "{m}");
    assert_eq!(m["gave_up"], true, "{m}");
    assert_eq!(doc["plans"]["p"]["path"], serde_json::Value::Null);
    // The note says the time limit ended it: in the set-up on most
    // machines (classifying 200 million cells), else in the search.
    let text = text_of(&bin(&["run", "t.scen"]), "limit time 1s");
    assert!(
        text.contains("note: the time limit was reached while classifying the lattice")
            || text.contains("note: a limit was reached before the goal"),
        "{text}"
    );
}

// ------------------------------------------------- every planner's set-up

/// 64 × 64 unit cells with a block: set-up enough that every planner looks
/// at its clock before it is done.
fn world(planner: &Planner) -> String {
    block_world(planner, 64, 20..40, 30..34)
}

/// SPEC 2.5: a plan whose time is up when it starts (a limit of 0, as a
/// plan that spent it all before its set-up was done) gives up, finds
/// nothing, and its note names the time limit, for every planner that
/// takes `limit time` and every robot it plans for. Before, the lattice
/// planners and `coverage` built their lattice or grid first and then
/// blamed "a limit".
#[test]
fn every_planner_counts_its_set_up_against_its_time_limit() {
    let mut problems = Vec::new();
    let dir = TempDir::new("limits-setup");
    for planner in PLANNERS.iter().filter(|p| p.limits.contains(&"time")) {
        for &kind in planner.robots.iter().filter(|&&k| k != RobotKind::Team) {
            let label = format!("{} / {kind:?}", planner.kind);
            let goal = if planner.needs_goal {
                "goal (60.5, 60.5)"
            } else {
                ""
            };
            let text = format!(
                "scenario \"set-up\"\n{}robot r {}\nplan p {} r {{\n  start (1.5, 1.5) {goal} seed 1\n  {}\n}}\n",
                world(planner),
                robot(kind),
                planner.kind,
                required(planner).join(" ")
            );
            let file = dir.path().join("s.scen");
            std::fs::write(&file, &text).expect("write");
            let sc = scen::load(&file).unwrap_or_else(|f| {
                let codes: Vec<String> = f.diags.iter().map(|d| d.code.to_string()).collect();
                panic!("{label}: {codes:?}\n{text}")
            });
            let plan = &sc.plans[0];
            let mut task = plan.task(&sc);
            task.limits.time = Some(0.0);
            let out = plan.settings.plan(&task);
            if out.path.is_some() || !out.gave_up {
                problems.push(format!(
                    "{label}: found {}, gave_up {}",
                    out.path.is_some(),
                    out.gave_up
                ));
            }
            if !out.notes.iter().any(|n| n.contains("time limit")) {
                problems.push(format!(
                    "{label}: no note names the time limit: {:?}",
                    out.notes
                ));
            }
        }
    }
    assert!(problems.is_empty(), "\n{}", problems.join("\n"));
}
