//! An output never replaces an input (SPEC §4, issue 39): every command
//! refuses, before anything runs, an output path that is a file it reads —
//! the scenario, an include, a map, a part given to `merge` — by any path
//! (`./d/../x`, a symbolic link), naming both, with exit 2, and the input
//! is left byte for byte as it was.

mod common;

use std::path::Path;
use std::process::{Command, Output};
use std::time::Duration;

use common::{TempDir, run_or_kill, run_with_timeout, scen_bin};

/// A family with an include, a map and a bench: everything a command reads.
const FAMILY: &str = r#"scenario "Reads three files"
include "_robot.scen"
param gap = uniform(0.6, 2)
world {
  bounds (0, 0) (10, 10)
  rect left (0, 4.5) (5 - gap / 2, 5.5)
  rect right (5 + gap / 2, 4.5) (10, 5.5)
  grid g "m.map" cell 1 origin (0, 0)
}
plan p astar r { start (5, 1) goal (5, 9) cell 0.5 }
expect p.found or gap < 0.85
bench b { runs 1 }
"#;

const ROBOT: &str = "robot r disk 0.4\n";

/// A MovingAI map: a 3 × 3 free corner of the world.
const MAP: &str = "type octile\nheight 3\nwidth 3\nmap\n...\n...\n...\n";

/// The folder with the family, its include and its map.
fn family() -> TempDir {
    let dir = TempDir::new("clobber");
    std::fs::write(dir.path().join("fam.scen"), FAMILY).expect("write");
    std::fs::write(dir.path().join("_robot.scen"), ROBOT).expect("write");
    std::fs::write(dir.path().join("m.map"), MAP).expect("write");
    dir
}

fn scen(dir: &Path, args: &[&str]) -> Output {
    run_with_timeout(
        Command::new(scen_bin())
            .args(args)
            .current_dir(dir)
            .env("NO_COLOR", "1"),
        Duration::from_secs(120),
    )
}

/// Runs `args` in `dir`: refused with exit 2, the message naming `output`
/// (as given) and `input`, nothing planned or printed on stdout, and every
/// input file unchanged.
fn refused(dir: &Path, args: &[&str], output: &str, input: &str) {
    let before: Vec<(String, Vec<u8>)> = ["fam.scen", "_robot.scen", "m.map"]
        .iter()
        .chain(["part-1.jsonl", "part-2.jsonl"].iter())
        .filter_map(|f| Some((f.to_string(), std::fs::read(dir.join(f)).ok()?)))
        .collect();
    let out = scen(dir, args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let ctx = format!(
        "scen {}\n--- stdout\n{}\n--- stderr\n{stderr}",
        args.join(" "),
        String::from_utf8_lossy(&out.stdout)
    );
    assert_eq!(out.status.code(), Some(2), "{ctx}");
    assert!(
        stderr.contains(&format!("would write `{output}`, which is `")),
        "the output is not named\n{ctx}"
    );
    assert!(
        stderr.contains(input),
        "the input `{input}` is not named\n{ctx}"
    );
    assert!(stderr.contains("an output never replaces"), "{ctx}");
    assert!(out.stdout.is_empty(), "something ran\n{ctx}");
    for (f, bytes) in before {
        assert_eq!(
            std::fs::read(dir.join(&f)).expect("the input is still there"),
            bytes,
            "`{f}` was changed\n{ctx}"
        );
    }
}

#[test]
fn run_refuses_an_output_onto_the_scenario_an_include_or_a_map() {
    let dir = family();
    let d = dir.path();
    refused(
        d,
        &["run", "fam.scen", "--csv", "fam.scen"],
        "fam.scen",
        "fam.scen",
    );
    refused(
        d,
        &["run", "fam.scen", "--csv", "_robot.scen"],
        "_robot.scen",
        "_robot.scen",
    );
    refused(d, &["run", "fam.scen", "--csv", "m.map"], "m.map", "m.map");
    // The same file by another path is the same file.
    std::fs::create_dir_all(d.join("sub")).expect("mkdir");
    refused(
        d,
        &["run", "fam.scen", "--csv", "sub/../fam.scen"],
        "sub/../fam.scen",
        "fam.scen",
    );
    refused(
        d,
        &["run", "./fam.scen", "--csv", "fam.scen"],
        "fam.scen",
        "./fam.scen",
    );
}

#[cfg(unix)]
#[test]
fn an_output_through_a_symbolic_link_is_the_file_it_leads_to() {
    let dir = family();
    let d = dir.path();
    std::os::unix::fs::symlink(d.join("fam.scen"), d.join("link.csv")).expect("symlink");
    refused(
        d,
        &["run", "fam.scen", "--csv", "link.csv"],
        "link.csv",
        "fam.scen",
    );
}

#[cfg(feature = "viewer")]
#[test]
fn run_refuses_a_recording_onto_the_scenario() {
    let dir = family();
    refused(
        dir.path(),
        &["run", "fam.scen", "--save", "fam.scen"],
        "fam.scen",
        "fam.scen",
    );
}

#[test]
fn an_output_that_is_not_an_input_is_written() {
    let dir = TempDir::new("clobber-ok");
    let d = dir.path();
    std::fs::write(
        d.join("a.scen"),
        "world { bounds (0, 0) (10, 10) }\nrobot r point\nplan p astar r { start (1, 1) goal (9, 9) }\n",
    )
    .expect("write");
    // An existing file that the run does not read is replaced, as before.
    std::fs::write(d.join("old.csv"), "stale").expect("write");
    let out = scen(d, &["run", "a.scen", "--csv", "old.csv"]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(d.join("old.csv")).expect("read");
    assert!(csv.starts_with("plan,"), "{csv}");
}

#[test]
fn falsify_refuses_to_write_its_failure_onto_the_family_or_an_include() {
    let dir = family();
    let d = dir.path();
    refused(
        d,
        &["falsify", "fam.scen", "--budget", "5", "--out", "fam.scen"],
        "fam.scen",
        "fam.scen",
    );
    refused(
        d,
        &[
            "falsify",
            "fam.scen",
            "--budget",
            "5",
            "--out",
            "_robot.scen",
        ],
        "_robot.scen",
        "_robot.scen",
    );
    refused(
        d,
        &[
            "falsify", "fam.scen", "--budget", "4", "--shard", "1/2", "--out", "m.map",
        ],
        "m.map",
        "m.map",
    );
}

#[test]
fn falsify_merge_refuses_to_write_onto_a_part() {
    let dir = family();
    let d = dir.path();
    for k in ["1", "2"] {
        let part = format!("part-{k}.jsonl");
        let shard = format!("{k}/2");
        let out = scen(
            d,
            &[
                "falsify", "fam.scen", "--budget", "4", "--shard", &shard, "--out", &part,
            ],
        );
        assert_eq!(
            out.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    refused(
        d,
        &[
            "falsify",
            "merge",
            "part-1.jsonl",
            "part-2.jsonl",
            "--out",
            "part-2.jsonl",
        ],
        "part-2.jsonl",
        "part-2.jsonl",
    );
    refused(
        d,
        &[
            "falsify",
            "merge",
            "part-1.jsonl",
            "part-2.jsonl",
            "--out",
            "fam.scen",
        ],
        "fam.scen",
        "fam.scen",
    );
}

#[test]
fn bench_refuses_an_output_onto_what_it_reads() {
    let dir = family();
    let d = dir.path();
    refused(
        d,
        &["bench", "fam.scen", "--csv", "fam.scen"],
        "fam.scen",
        "fam.scen",
    );
    refused(
        d,
        &["bench", "fam.scen", "--csv", "m.map"],
        "m.map",
        "m.map",
    );
    refused(
        d,
        &["bench", "fam.scen", "--shard", "1/1", "--out", "fam.scen"],
        "fam.scen",
        "fam.scen",
    );
}

#[cfg(unix)]
#[test]
fn bench_refuses_an_ompl_log_onto_a_file_it_reads() {
    let dir = family();
    let d = dir.path();
    // `--ompl-log DIR` writes `fam.b.log` there: when the map is that file
    // (by a symbolic link), the log is refused.
    std::fs::create_dir_all(d.join("logs")).expect("mkdir");
    std::fs::remove_file(d.join("m.map")).expect("rm");
    std::os::unix::fs::symlink(d.join("logs/fam.b.log"), d.join("m.map")).expect("symlink");
    std::fs::write(d.join("logs/fam.b.log"), MAP).expect("write");
    refused(
        d,
        &["bench", "fam.scen", "--ompl-log", "logs"],
        "logs/fam.b.log",
        "m.map",
    );
}

#[test]
fn bench_merge_refuses_to_write_onto_a_part_or_the_scenario() {
    let dir = family();
    let d = dir.path();
    let out = scen(
        d,
        &[
            "bench",
            "fam.scen",
            "--shard",
            "1/1",
            "--out",
            "part-1.jsonl",
        ],
    );
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    refused(
        d,
        &["bench", "merge", "part-1.jsonl", "--csv", "part-1.jsonl"],
        "part-1.jsonl",
        "part-1.jsonl",
    );
    refused(
        d,
        &["bench", "merge", "part-1.jsonl", "--csv", "_robot.scen"],
        "_robot.scen",
        "_robot.scen",
    );
}

#[test]
fn test_refuses_a_junit_report_onto_a_scenario_of_the_suite() {
    let dir = family();
    let d = dir.path();
    refused(
        d,
        &["test", ".", "--junit", "fam.scen"],
        "fam.scen",
        "fam.scen",
    );
    // An include is read too, though `test` does not run it on its own.
    refused(
        d,
        &["test", ".", "--junit", "_robot.scen"],
        "_robot.scen",
        "_robot.scen",
    );
}

#[test]
fn watch_refuses_an_output_onto_the_watched_file_at_once() {
    let dir = family();
    refused(
        dir.path(),
        &["watch", "fam.scen", "--csv", "fam.scen"],
        "fam.scen",
        "fam.scen",
    );
}

#[test]
fn watch_refuses_each_run_that_would_write_onto_an_include() {
    let dir = family();
    let d = dir.path();
    // `watch` runs until interrupted: the first run's refusal is read from
    // its output, and the process is killed.
    let finished = run_or_kill(
        Command::new(scen_bin())
            .args(["watch", "fam.scen", "--csv", "_robot.scen"])
            .current_dir(d)
            .env("NO_COLOR", "1"),
        Duration::from_secs(5),
    );
    let stderr = String::from_utf8_lossy(&finished.stderr);
    assert!(
        stderr.contains("would write `_robot.scen`, which is `")
            && stderr.contains("an output never replaces"),
        "{stderr}"
    );
    assert!(
        finished.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&finished.stdout)
    );
    assert_eq!(
        std::fs::read_to_string(d.join("_robot.scen")).expect("read"),
        ROBOT
    );
}
