//! The CLI as a user runs it: the real binary on small inputs written in
//! the test, comparing output and exit codes.

mod common;

use common::{Test, repo};

const SMALL: &str = r#"scenario "Small"
world {
  bounds (0, 0) (10, 10)
  rect wall (4, 0) (5, 8)
}
robot p point
plan go astar p {
  start (0.5, 0.5)
  goal  (9.5, 0.5)
  connect 4
  cost l1
}
expect go.found
expect go.cost == 25
"#;

#[test]
fn run_prints_the_report_and_exits_0() {
    Test::new()
        .file("small.scen", SMALL)
        .args(&["run", "small.scen"])
        .stdout(
            "small.scen — Small

plan go (astar, robot p): found, collision-free
  cost 25  length 25  turn 0  nodes 26  expanded 47  generated 63  cells 100  clearance 0.5  free_cells 92  layers 1  smoothness 9.869604

checks
  PASS  line 13  go.found   (go.found = true)
  PASS  line 14  go.cost == 25   (go.cost = 25)

2 passed, 0 failed
",
        )
        .status(0)
        .run();
}

#[test]
fn a_failed_check_exits_1_and_points_at_the_expression() {
    let text = SMALL.replace("go.cost == 25", "go.cost < 20");
    Test::new()
        .file("small.scen", &text)
        .args(&["run", "small.scen"])
        .stdout_contains("FAIL  line 14  go.cost < 20   (go.cost = 25)")
        .stdout_contains("1 passed, 1 failed")
        .stderr_contains("check failed: `go.cost < 20`")
        .stderr_contains("small.scen:14:8")
        .status(1)
        .run();
}

#[test]
fn quiet_prints_failures_and_the_summary() {
    Test::new()
        .file("small.scen", SMALL)
        .args(&["run", "-q", "small.scen"])
        .stdout("2 passed, 0 failed\n")
        .run();
}

#[test]
fn check_reports_every_error_at_once_with_exit_2() {
    Test::new()
        .file(
            "bad.scen",
            "world { bounds (0, 0) (10, 10) }\nrobot p point\nplan a astar p { start (1, 1) goal (2, 2) cel 1 }\nplan b astar q { start (1, 1) goal (2, 2) }\nexpect a.fond\n",
        )
        .args(&["check", "bad.scen"])
        .stderr_contains("bad.scen:3:43")
        .stderr_contains("unknown parameter `cel` for planner `astar`")
        .stderr_contains("did you mean `cell`?")
        .stderr_contains("bad.scen:4:14")
        .stderr_contains("unknown robot `q`")
        .stderr_contains("bad.scen:5:10")
        .stderr_contains("has no metric `fond`")
        .stderr_contains("3 error(s)")
        .status(2)
        .run();
}

#[test]
fn check_json_prints_one_object_per_diagnostic() {
    let out = Test::new()
        .file(
            "bad.scen",
            "world { bounds (0, 0) (10, 10) }\nrobot p point\nrobot p point\nplan go astar p { start (1, 1) goal (2, 2) }\n",
        )
        .args(&["check", "--format", "json", "bad.scen"])
        .status(2)
        .run();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<serde_json::Value> = stdout
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON object per line"))
        .collect();
    assert_eq!(lines.len(), 1, "{stdout}");
    assert_eq!(lines[0]["code"], "scen::analyze::duplicate_name");
    assert_eq!(lines[0]["line"], 3);
    assert_eq!(lines[0]["column"], 7);
    assert_eq!(lines[0]["severity"], "error");
    assert!(
        lines[0]["file"]
            .as_str()
            .is_some_and(|f| f.ends_with("bad.scen"))
    );
}

#[test]
fn check_accepts_a_good_file() {
    Test::new()
        .file("small.scen", SMALL)
        .args(&["check", "small.scen"])
        .stdout("small.scen: ok (1 robot(s), 1 plan(s), 2 check(s))\n")
        .run();
}

#[test]
fn a_missing_file_is_exit_2() {
    Test::new()
        .args(&["run", "nope.scen"])
        .stderr_contains("cannot read scenario file `nope.scen`")
        .status(2)
        .run();
}

#[test]
fn bad_usage_is_exit_2() {
    Test::new().args(&["run"]).status(2).run();
    Test::new().args(&["frobnicate"]).status(2).run();
}

#[test]
fn test_runs_a_folder_and_counts_checks() {
    Test::new()
        .file("suite/a.scen", SMALL)
        .file("suite/b.scen", &SMALL.replace("go.cost == 25", "go.cost == 24"))
        .file("suite/_fragment.scen", "world {")
        .args(&["test", "suite"])
        .stdout("ok      suite/a.scen  (2 checks)\nFAILED  suite/b.scen  (1 of 2 checks failed)\n3 passed, 1 failed\n")
        .stderr_contains("check failed: `go.cost == 24`")
        .status(1)
        .run();
}

#[test]
fn test_checks_expected_errors() {
    let header = "# expect-error: scen::analyze::unknown_key\n";
    let bad = SMALL.replace("goal", "gaol");
    Test::new()
        // Gets the error it expects: passes.
        .file("suite/a.scen", &format!("{header}{bad}"))
        // Gets another error: fails, and shows what it got.
        .file(
            "suite/b.scen",
            &format!("# expect-error: scen::analyze::duplicate_key\n{bad}"),
        )
        // Loads: fails.
        .file("suite/c.scen", &format!("{header}{SMALL}"))
        .args(&["test", "suite"])
        .stdout(
            "ok      suite/a.scen  (expected errors reported)\n\
             FAILED  suite/b.scen  (expected error `scen::analyze::duplicate_key` not reported)\n\
             FAILED  suite/c.scen  (loads, but `# expect-error:` expects it not to)\n\
             1 passed, 2 failed\n",
        )
        .stderr_contains("scen::analyze::unknown_key")
        .status(1)
        .run();
}

#[test]
fn the_bad_input_corpus_passes_scen_test() {
    // Every file of tests/bad_inputs declares the errors it must get.
    let corpus = repo().join("tests/bad_inputs");
    Test::new()
        .args(&["test", corpus.to_str().expect("utf-8 path")])
        .stdout_contains(" 0 failed")
        .status(0)
        .run();
}

#[test]
fn json_output_follows_the_spec() {
    let out = Test::new()
        .file("small.scen", SMALL)
        .args(&["run", "--json", "small.scen"])
        .run();
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON document");
    assert_eq!(doc["file"], "small.scen");
    assert_eq!(doc["scenario"], "Small");
    let go = &doc["plans"]["go"];
    assert_eq!(go["kind"], "astar");
    assert_eq!(go["robot"], "p");
    assert_eq!(go["metrics"]["found"], true);
    assert_eq!(go["metrics"]["cost"], 25);
    let path = go["path"].as_array().expect("a path");
    assert_eq!(path.len(), 26);
    assert_eq!(path[0], serde_json::json!([0.5, 0.5]));
    assert_eq!(doc["checks"][1]["line"], 14);
    assert_eq!(doc["checks"][1]["expr"], "go.cost == 25");
    assert_eq!(doc["checks"][1]["values"]["go.cost"], 25);
    assert_eq!(doc["passed"], 2);
    assert_eq!(doc["failed"], 0);
}

/// A car's plan lists its segments (SPEC §5), what the validator checks,
/// and its poses for drawing: from the start, at most 0.1 apart along the
/// curve, ending on the goal; a plan without a path has `null` segments.
#[test]
fn json_lists_a_cars_segments_and_its_poses() {
    let car = "world { bounds (0, 0) (40, 40) rect wall (18, 0) (22, 12) }\n\
               robot cart rect 2 1 steer dubins 3\n\
               plan uturn steer cart { start (5, 20, 0deg) goal (5, 26, 180deg) }\n\
               plan blocked steer cart { start (5, 5, 0deg) goal (35, 5, 0deg) }\n";
    let out = Test::new()
        .file("car.scen", car)
        .args(&["run", "--json", "car.scen"])
        .run();
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON document");
    let uturn = &doc["plans"]["uturn"];
    let segments = uturn["segments"].as_array().expect("segments");
    assert_eq!(segments.len(), 1, "{segments:?}");
    assert_eq!(segments[0][0], "L");
    let arc = segments[0][1].as_f64().expect("a length");
    assert!((arc - 3.0 * std::f64::consts::PI).abs() < 1e-9, "{arc}");
    let path = uturn["path"].as_array().expect("a path");
    assert_eq!(path[0], serde_json::json!([5.0, 20.0, 0.0]));
    let last = path.last().expect("a pose");
    assert_eq!(last[0], 5.0);
    assert_eq!(last[1], 26.0);
    assert!((last[2].as_f64().expect("θ") - std::f64::consts::PI).abs() < 1e-12);
    // At most 0.1 of arc between poses: about 3π / 0.1 of them.
    assert_eq!(path.len(), 96);
    assert_eq!(uturn["metrics"]["cusps"], 0.0);
    assert_eq!(uturn["metrics"]["segments"], 1.0);
    let blocked = &doc["plans"]["blocked"];
    assert_eq!(blocked["segments"], serde_json::Value::Null);
    assert_eq!(blocked["metrics"]["found"], false);
    assert_eq!(blocked["metrics"]["cusps"], serde_json::Value::Null);
}

#[test]
fn plan_selects_plans_and_their_checks() {
    let text = SMALL.replace(
        "expect go.found",
        "plan other astar p { start (0.5, 0.5) goal (0.5, 9.5) }\nexpect other.found",
    );
    Test::new()
        .file("small.scen", &text)
        .args(&["run", "--plan", "other", "small.scen"])
        .stdout_contains("plan other (astar, robot p): found")
        .stdout_contains("1 passed, 0 failed")
        .run();
    Test::new()
        .file("small.scen", SMALL)
        .args(&["run", "--plan", "nosuch", "small.scen"])
        .stderr_contains("has no plan `nosuch`")
        .status(2)
        .run();
}

#[test]
fn svg_is_written() {
    let t = Test::new().file("small.scen", SMALL).args(&[
        "run",
        "-q",
        "--svg",
        "out.svg",
        "small.scen",
    ]);
    t.run();
    let svg = std::fs::read_to_string(t.dir().join("out.svg")).expect("out.svg written");
    assert!(svg.contains("<svg"), "{svg}");
    assert!(svg.contains("polyline"), "{svg}");
}

#[cfg(feature = "viewer")]
#[test]
fn an_unreachable_viewer_warns_once_and_the_report_is_complete() {
    Test::new()
        .file("small.scen", SMALL)
        .args(&[
            "run",
            "--connect",
            "rerun+http://127.0.0.1:9/proxy",
            "small.scen",
        ])
        .stdout_contains("2 passed, 0 failed")
        .stderr_contains("warning: viewer")
        .status(0)
        .run();
}

#[test]
fn import_roadmap_prints_a_scenario() {
    Test::new()
        .file("input.txt", "1\n0, 0, 1, 1\n0, 1\n1, 0\n")
        .args(&["import", "roadmap", "input.txt"])
        .stdout_contains("segment s1 (0, 0) (1, 1)")
        .stdout_contains("plan vg roadmap r {")
        .status(0)
        .run();
}

#[test]
fn every_scenario_passes_scen_test() {
    let scenarios = repo().join("scenarios");
    Test::new()
        .args(&["test", scenarios.to_str().expect("utf-8 path")])
        .stdout_contains(" 0 failed")
        .status(0)
        .run();
}

/// SPEC §4: output paths are checked before any planner runs, so a run of
/// minutes cannot end in "cannot write" (and turn a pass into exit 2).
#[test]
fn outputs_that_cannot_be_written_are_refused_before_planning() {
    let mut outputs = vec![
        ("--svg", "missing/out.svg"),
        ("--png", "missing/out.png"),
        ("--csv", "missing/paths.csv"),
    ];
    if cfg!(feature = "viewer") {
        outputs.push(("--save", "missing/run.rrd"));
    }
    for (flag, file) in outputs {
        Test::new()
            .file("small.scen", SMALL)
            .args(&["run", flag, file, "small.scen"])
            .stdout("")
            .stderr_contains(&format!(
                "`{flag} {file}`: the folder `missing` does not exist"
            ))
            .status(2)
            .run();
    }
    // A folder where a file is expected.
    Test::new()
        .file("small.scen", SMALL)
        .file("out.svg/keep", "")
        .args(&["run", "--svg", "out.svg", "small.scen"])
        .stdout("")
        .stderr_contains("`out.svg` is a folder")
        .status(2)
        .run();
    // A folder where the scenario is expected: `scen test` runs folders.
    Test::new()
        .file("suite/small.scen", SMALL)
        .args(&["run", "suite"])
        .stdout("")
        .stderr_contains("`suite` is a folder, not a scenario file")
        .stderr_contains("`scen test suite` runs every scenario under a folder")
        .status(2)
        .run();
    Test::new()
        .file("small.scen", SMALL)
        .args(&["test", "--junit", "missing/junit.xml", "small.scen"])
        .stdout("")
        .status(2)
        .run();
}

/// SPEC §4: a report that cannot be written to stdout is an error, not a
/// silent success.
#[cfg(unix)]
#[test]
fn a_report_lost_on_a_full_disk_is_exit_2() {
    let dir = common::TempDir::new("dev-full");
    std::fs::write(dir.path().join("small.scen"), SMALL).expect("write");
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .expect("/dev/full");
    let out = std::process::Command::new(common::scen_bin())
        .args(["run", "small.scen"])
        .current_dir(dir.path())
        .stdout(full)
        .output()
        .expect("scen runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("cannot write to standard output"), "{err}");
}

/// SPEC §4: `--plan` says which checks it left out, so a run never looks
/// green without saying what it did not check.
#[test]
fn plan_reports_the_checks_it_skipped() {
    let text = SMALL.replace(
        "expect go.found",
        "plan other astar p { start (0.5, 0.5) goal (0.5, 9.5) }\nexpect other.found\nexpect go.found",
    );
    Test::new()
        .file("small.scen", &text)
        .args(&["run", "--plan", "other", "small.scen"])
        .stdout_contains(
            "2 check(s) skipped: they read plans that did not run (`--plan`): lines 15, 16",
        )
        .stdout_contains("1 passed, 0 failed")
        .run();
    let out = Test::new()
        .file("small.scen", &text)
        .args(&["run", "--json", "--plan", "other", "small.scen"])
        .run();
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(doc["skipped"][0]["line"], 15);
    assert_eq!(doc["skipped"][1]["expr"], "go.cost == 25");
    // Without `--plan`, nothing is skipped and the key is absent.
    let out = Test::new()
        .file("small.scen", &text)
        .args(&["run", "--json", "small.scen"])
        .run();
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert!(doc.get("skipped").is_none(), "{doc}");
}

/// SPEC §4: a metric without a value is `null` in JSON and `—` in the
/// report, never a 0 that reads as "touched a wall".
#[test]
fn the_clearance_of_a_plan_without_a_path_has_no_value() {
    let walled = SMALL.replace("rect wall (4, 0) (5, 8)", "rect wall (4, 0) (5, 10)");
    let walled = walled
        .replace("expect go.found\n", "expect not go.found\n")
        .replace("expect go.cost == 25\n", "");
    Test::new()
        .file("small.scen", &walled)
        .args(&["run", "small.scen"])
        .stdout_contains("clearance —")
        .run();
    let out = Test::new()
        .file("small.scen", &walled)
        .args(&["run", "--json", "small.scen"])
        .run();
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let metrics = &doc["plans"]["go"]["metrics"];
    assert_eq!(metrics["found"], false);
    assert!(metrics["clearance"].is_null(), "{metrics}");
}

/// `run --csv`: one row per configuration of each path, with the
/// cumulative length (SPEC §4).
#[test]
fn csv_lists_every_path_point_with_its_length() {
    let t = Test::new().file("small.scen", SMALL).args(&[
        "run",
        "-q",
        "--csv",
        "paths.csv",
        "small.scen",
    ]);
    t.run();
    let csv = std::fs::read_to_string(t.dir().join("paths.csv")).expect("paths.csv written");
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows[0], "plan,what,index,t,x,y,theta,length");
    // The path of 26 configurations (`nodes 26` in the report), from the
    // start to the goal, 25 long.
    assert_eq!(rows.len(), 1 + 26, "{csv}");
    assert_eq!(rows[1], "go,path,0,,0.5,0.5,0,0");
    assert_eq!(rows[26], "go,path,25,,9.5,0.5,0,25");
    // No path: nothing to write, and it says so.
    let walled = SMALL
        .replace("rect wall (4, 0) (5, 8)", "rect wall (4, 0) (5, 10)")
        .replace("expect go.cost == 25\n", "");
    let t = Test::new()
        .file("small.scen", &walled)
        .args(&["run", "-q", "--csv", "paths.csv", "small.scen"])
        .stderr_contains("no plan found a path")
        .status(2);
    t.run();
    assert!(!t.dir().join("paths.csv").exists());
}

/// SPEC 2.2: files a scenario reads lie inside its root: the folder of
/// the file named on the command line, or `--root DIR`.
#[test]
fn includes_stay_inside_the_root_unless_it_is_widened() {
    let world = "world { bounds (0, 0) (10, 10) }\n";
    let main = "include \"../shared/_world.scen\"\nrobot p point\nplan go astar p { start (1.5, 1.5) goal (8.5, 1.5) }\nexpect go.found\n";
    Test::new()
        .file("shared/_world.scen", world)
        .file("case/main.scen", main)
        .args(&["run", "case/main.scen"])
        .stderr_contains("scen::load::outside_root")
        .stderr_contains("--root DIR")
        .status(2)
        .run();
    Test::new()
        .file("shared/_world.scen", world)
        .file("case/main.scen", main)
        .args(&["run", "-q", "--root", ".", "case/main.scen"])
        .stdout("1 passed, 0 failed\n")
        .run();
}

/// Without the viewer in the build, the viewer's options say so before
/// anything runs.
#[cfg(not(feature = "viewer"))]
#[test]
fn a_build_without_the_viewer_refuses_its_options() {
    Test::new()
        .file("small.scen", SMALL)
        .args(&["run", "--save", "out.rrd", "small.scen"])
        .stdout("")
        .stderr_contains("built without the viewer")
        .status(2)
        .run();
}

#[test]
fn watch_needs_an_existing_file() {
    Test::new()
        .args(&["watch", "nope.scen"])
        .stderr_contains("`nope.scen` does not exist")
        .status(2)
        .run();
}

/// `scen watch`: a save runs the scenario again and prints the new
/// report; a save that does not parse prints its diagnostics and waits for
/// the next (SPEC §4).
#[test]
fn watch_runs_again_on_every_save() {
    use std::io::{BufRead, BufReader};
    use std::process::{Command, Stdio};
    use std::sync::mpsc;
    use std::time::Duration;

    let dir = common::TempDir::new("watch");
    let file = dir.path().join("small.scen");
    std::fs::write(&file, SMALL).expect("write");
    let mut child = Command::new(common::scen_bin())
        .args(["watch", "-q", "small.scen"])
        .current_dir(dir.path())
        .env("NO_COLOR", "1")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("scen watch starts");
    // Lines of both streams, as they come.
    let (tx, rx) = mpsc::channel::<String>();
    for pipe in [
        Box::new(child.stdout.take().expect("stdout")) as Box<dyn std::io::Read + Send>,
        Box::new(child.stderr.take().expect("stderr")),
    ] {
        let tx = tx.clone();
        std::thread::spawn(move || {
            for line in BufReader::new(pipe).lines().map_while(Result::ok) {
                let _ = tx.send(line);
            }
        });
    }
    let mut seen = Vec::new();
    let mut wait_for = |what: &str| {
        loop {
            match rx.recv_timeout(Duration::from_secs(60)) {
                Ok(line) => {
                    let hit = line.contains(what);
                    seen.push(line);
                    if hit {
                        return;
                    }
                }
                Err(_) => panic!(
                    "`scen watch` never printed {what:?}; it printed:\n{}",
                    seen.join("\n")
                ),
            }
        }
    };
    wait_for("2 passed, 0 failed");
    // A save with a failing check: the new report.
    std::fs::write(&file, SMALL.replace("go.cost == 25", "go.cost < 20")).expect("save");
    wait_for("1 passed, 1 failed");
    // A save that does not parse: its diagnostics, and it waits.
    std::fs::write(&file, SMALL.replace("plan go", "plan go go go {")).expect("save");
    wait_for("the scenario was not run");
    // Fixed again: a run again.
    std::fs::write(&file, SMALL).expect("save");
    wait_for("2 passed, 0 failed");
    let _ = child.kill();
    let _ = child.wait();
}

/// `scripts/wheel.sh` without maturin says how to get it and exits 2
/// (the wheel itself is built and installed by `scripts/test.sh`).
#[cfg(unix)]
#[test]
fn a_wheel_build_without_maturin_says_how_to_get_it() {
    if ["/usr/bin/maturin", "/bin/maturin"]
        .iter()
        .any(|p| std::path::Path::new(p).exists())
    {
        eprintln!("skipped: maturin is installed system-wide");
        return;
    }
    let out = std::process::Command::new("bash")
        .arg(repo().join("scripts/wheel.sh"))
        .env("PATH", "/usr/bin:/bin")
        .env_remove("MATURIN")
        .output()
        .expect("bash runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("pip install maturin"), "{err}");
}

/// `fmt` and `import` read only regular files, bounded: a device or a FIFO
/// is refused at once instead of read until memory runs out or forever
/// (SPEC 2.2, §4).
#[cfg(unix)]
#[test]
fn fmt_and_import_refuse_files_that_are_not_regular() {
    Test::new()
        .args(&["fmt", "--check", "/dev/zero"])
        .stderr_contains("not a regular file")
        .status(2)
        .run();
    Test::new()
        .args(&["import", "roadmap", "/dev/zero"])
        .stderr_contains("not a regular file")
        .status(2)
        .run();
    let t = Test::new().file("ok.scen", SMALL);
    let made = std::process::Command::new("mkfifo")
        .arg(t.dir().join("pipe.scen"))
        .status()
        .is_ok_and(|s| s.success());
    assert!(made, "mkfifo");
    t.args(&["fmt", "--check", "pipe.scen"])
        .stderr_contains("a FIFO (named pipe), not a regular file")
        .status(2)
        .run();
}
