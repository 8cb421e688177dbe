//! `scen bench` as a user runs it (SPEC §4, §5): the table, JSON, CSV, SVG,
//! OMPL logs read by OMPL's own script, shards merged back to exactly what
//! one machine prints, the refusals of `merge`, and `scen test --shard
//! --junit` read by a real XML parser.

mod common;

use std::path::Path;
use std::process::Command;

use common::{TempDir, Test, repo, run_with_timeout, scen_bin};
use serde_json::Value;

/// A randomized bench (the potential field's random walk over seeds) and a
/// deterministic one (A* with two weights), in one file.
const SCENARIO: &str = r#"scenario "Bench test"
world {
  bounds (0, 0) (20, 20)
  segment bottom (10, 2) (10, 8)
  segment upper  (5, 8)  (10, 8)
  segment lower  (5, 2)  (10, 2)
}
robot p point
plan walk potential p { start (7, 5) goal (15, 5) limit steps 20000 }
plan lattice astar p { start (7, 5) goal (15, 5) }
bench seeds {
  plans [walk]
  vary jump [4, 10]
  runs 11
}
bench weights {
  plans [lattice]
  vary weight [1, 3]
  runs 5
}
expect rate(seeds.walk.found) == 100%
expect median(seeds.walk[jump = 4].length) < 40
expect weights.lattice[weight = 1].length <= weights.lattice[weight = 3].length
expect lattice.found
"#;

fn scen(dir: &Path, args: &[&str]) -> std::process::Output {
    run_with_timeout(
        Command::new(scen_bin())
            .args(args)
            .current_dir(dir)
            .env("NO_COLOR", "1"),
        std::time::Duration::from_secs(120),
    )
}

/// The JSON document without what may differ between runs: timings.
fn without_timings(mut doc: Value) -> Value {
    fn strip(v: &mut Value) {
        match v {
            Value::Object(map) => {
                // Timings: `time_ms` and the other `*_ms` metrics.
                map.retain(|k, _| !k.ends_with("_ms"));
                map.values_mut().for_each(strip);
            }
            Value::Array(items) => items.iter_mut().for_each(strip),
            _ => {}
        }
    }
    strip(&mut doc);
    // Check values and series stats name aggregates of `time_ms` only when
    // a check uses it; none here.
    doc
}

fn json(out: &std::process::Output) -> Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("one JSON document")
}

#[test]
fn the_table_lists_configurations_with_statistics() {
    let t = Test::new().file("b.scen", SCENARIO).args(&[
        "bench",
        "--metrics",
        "length,expanded",
        "b.scen",
    ]);
    let out = t.run();
    let text = String::from_utf8_lossy(&out.stdout);
    // A row per plan and configuration, the varied key's values, the runs
    // (11 seeds; A* draws no random numbers: once), the success rate.
    assert!(text.contains("bench seeds (22 runs)"), "{text}");
    assert!(text.contains("bench weights (2 runs)"), "{text}");
    let rows: Vec<&str> = text
        .lines()
        .filter(|l| l.trim_start().starts_with("walk "))
        .collect();
    assert_eq!(rows.len(), 2, "{text}");
    assert!(
        rows[0]
            .split_whitespace()
            .take(4)
            .eq(["walk", "4", "11", "100%"]),
        "{text}"
    );
    // Randomized rows: median (mean ± std).
    assert!(rows[0].contains(" ± "), "{text}");
    assert!(text.contains("lattice draws no random numbers: one run per configuration, not 5"));
    assert!(text.contains("4 passed, 0 failed"), "{text}");
}

#[test]
fn json_lists_every_run_in_order_and_is_deterministic() {
    let dir = TempDir::new("bench-json");
    std::fs::write(dir.path().join("b.scen"), SCENARIO).expect("write");
    let a = json(&scen(dir.path(), &["bench", "--json", "b.scen"]));
    let b = json(&scen(dir.path(), &["bench", "--json", "b.scen"]));
    assert_eq!(without_timings(a.clone()), without_timings(b));
    let seeds = &a["benches"][0];
    assert_eq!(seeds["name"], "seeds");
    assert_eq!(seeds["vary"]["jump"], serde_json::json!([4.0, 10.0]));
    assert_eq!(seeds["runs"], 11);
    let results = seeds["results"].as_array().expect("results");
    assert_eq!(results.len(), 22);
    // Order: configuration, then run; seed = the plan's seed (0) + run.
    for (i, r) in results.iter().enumerate() {
        assert_eq!(r["plan"], "walk");
        assert_eq!(r["run"], (i % 11) as u64);
        assert_eq!(r["seed"], (i % 11) as u64);
        assert_eq!(r["config"]["jump"], if i < 11 { 4.0 } else { 10.0 });
        assert_eq!(r["metrics"]["found"], true);
    }
    // The seeds make the walks differ.
    let lengths: Vec<f64> = results[..11]
        .iter()
        .map(|r| r["metrics"]["length"].as_f64().expect("a length"))
        .collect();
    assert!(lengths.iter().any(|&l| l != lengths[0]), "{lengths:?}");
    assert_eq!(a["passed"], 4);
    assert_eq!(a["checks"].as_array().map(Vec::len), Some(4));
    assert_eq!(
        a["checks"][1]["series"]["seeds.walk[jump = 4].length"]["runs"],
        11
    );
}

#[test]
fn shards_merge_to_what_one_machine_prints() {
    let dir = TempDir::new("bench-shards");
    std::fs::write(dir.path().join("b.scen"), SCENARIO).expect("write");
    let whole = without_timings(json(&scen(dir.path(), &["bench", "--json", "b.scen"])));
    let table = |out: &std::process::Output| -> String {
        // The table without its timing column is the same too.
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let whole_table = table(&scen(
        dir.path(),
        &["bench", "--metrics", "length,expanded", "b.scen"],
    ));
    for n in [1, 3, 7] {
        let mut parts = Vec::new();
        for k in 1..=n {
            let part = format!("part-{n}-{k}.jsonl");
            let out = scen(
                dir.path(),
                &[
                    "bench",
                    "b.scen",
                    "--shard",
                    &format!("{k}/{n}"),
                    "--out",
                    &part,
                ],
            );
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            parts.push(part);
        }
        // Any order of the parts.
        parts.reverse();
        let mut args = vec!["bench", "merge", "--json"];
        args.extend(parts.iter().map(String::as_str));
        let merged = without_timings(json(&scen(dir.path(), &args)));
        assert_eq!(merged, whole, "{n} shards");
        let mut args = vec!["bench", "merge", "--metrics", "length,expanded"];
        args.extend(parts.iter().map(String::as_str));
        assert_eq!(table(&scen(dir.path(), &args)), whole_table, "{n} shards");
    }
}

#[test]
fn merge_refuses_missing_repeated_and_foreign_parts() {
    let dir = TempDir::new("bench-merge");
    let d = dir.path();
    std::fs::write(d.join("b.scen"), SCENARIO).expect("write");
    for k in 1..=3 {
        let out = scen(
            d,
            &[
                "bench",
                "b.scen",
                "--shard",
                &format!("{k}/3"),
                "--out",
                &format!("p{k}.jsonl"),
            ],
        );
        assert!(out.status.success());
    }
    let refused = |args: &[&str], says: &str| {
        let out = scen(d, args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    };
    refused(
        &["bench", "merge", "p1.jsonl", "p3.jsonl"],
        "1 part(s) missing: 2/3",
    );
    refused(
        &[
            "bench", "merge", "p1.jsonl", "p2.jsonl", "p2.jsonl", "p3.jsonl",
        ],
        "part 2/3 is given twice",
    );
    // A part of another split of the same file.
    let out = scen(
        d,
        &["bench", "b.scen", "--shard", "1/2", "--out", "q1.jsonl"],
    );
    assert!(out.status.success());
    refused(
        &["bench", "merge", "p1.jsonl", "p2.jsonl", "q1.jsonl"],
        "does not belong",
    );
    // The scenario changed since the parts were made.
    std::fs::write(d.join("b.scen"), SCENARIO.replace("runs 11", "runs 12")).expect("write");
    refused(
        &["bench", "merge", "p1.jsonl", "p2.jsonl", "p3.jsonl"],
        "has changed",
    );
    // A part cut short in the middle of a line (a copy between machines).
    let whole = std::fs::read_to_string(d.join("p2.jsonl")).expect("p2.jsonl");
    std::fs::write(d.join("cut.jsonl"), &whole[..whole.len() - 10]).expect("write");
    refused(
        &["bench", "merge", "p1.jsonl", "cut.jsonl", "p3.jsonl"],
        "of the part `cut.jsonl` is not JSON",
    );
    refused(
        &["bench", "merge", "p1.jsonl", "cut.jsonl", "p3.jsonl"],
        "run shard 2/3 again",
    );
    std::fs::write(d.join("x.jsonl"), "{\"not\": \"a part\"}\n").expect("write");
    refused(&["bench", "merge", "x.jsonl"], "is not a part");
    refused(&["bench", "merge"], "needs the parts");
}

#[test]
fn csv_and_svg_outputs() {
    let t = Test::new().file("b.scen", SCENARIO).args(&[
        "bench",
        "-q",
        "--csv",
        "runs.csv",
        "--svg",
        "plots.svg",
        "b.scen",
    ]);
    t.run();
    let csv = std::fs::read_to_string(t.dir().join("runs.csv")).expect("a CSV");
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 1 + 22 + 2, "{csv}");
    let header: Vec<&str> = lines[0].split(',').collect();
    assert_eq!(
        &header[..6],
        ["bench", "plan", "jump", "weight", "run", "seed"]
    );
    assert!(header.contains(&"length") && header.contains(&"found"));
    assert!(lines[1].starts_with("seeds,walk,4,,0,0,"), "{}", lines[1]);
    assert!(
        lines[23].starts_with("weights,lattice,,1,0,0,"),
        "{}",
        lines[23]
    );
    let svg = std::fs::read_to_string(t.dir().join("plots.svg")).expect("an SVG");
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains("seeds — length") && svg.contains("median length by jump"));
}

#[test]
fn bench_needs_a_bench_and_known_names() {
    Test::new()
        .file("b.scen", "world { bounds (0, 0) (5, 5) }\nrobot p point\nplan a astar p { start (1, 1) goal (4, 4) }\n")
        .args(&["bench", "b.scen"])
        .status(2)
        .stderr_contains("has no `bench`")
        .run();
    Test::new()
        .file("b.scen", SCENARIO)
        .args(&["bench", "--bench", "nope", "b.scen"])
        .status(2)
        .stderr_contains("no bench `nope` (benches: seeds, weights)")
        .run();
    Test::new()
        .file("b.scen", SCENARIO)
        .args(&["bench", "--shard", "4/3", "--out", "p.jsonl", "b.scen"])
        .status(2)
        .stderr_contains("is not a shard")
        .run();
}

#[test]
fn run_leaves_bench_checks_to_bench() {
    Test::new()
        .file("b.scen", SCENARIO)
        .args(&["run", "b.scen"])
        .stdout_contains("3 check(s) read the benches; `scen bench b.scen` runs them")
        .stdout_contains("1 passed, 0 failed")
        .run();
}

/// The `ompl_benchmark_statistics` script (pip package `ompl`, installed by
/// scripts/test.sh in target/rerun-venv); CI must have it.
fn ompl_statistics() -> Option<std::path::PathBuf> {
    let script = std::env::var_os("SCEN_OMPL_STATS")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| repo().join("target/rerun-venv/bin/ompl_benchmark_statistics"));
    if script.exists() {
        return Some(script);
    }
    assert_ne!(
        std::env::var("CI").as_deref(),
        Ok("true"),
        "CI must have OMPL's ompl_benchmark_statistics (pip install ompl)"
    );
    eprintln!(
        "skipped: {} is missing (pip install ompl)",
        script.display()
    );
    None
}

#[test]
fn ompl_logs_become_a_planner_arena_database() {
    let Some(script) = ompl_statistics() else {
        return;
    };
    let t =
        Test::new()
            .file("b.scen", SCENARIO)
            .args(&["bench", "-q", "--ompl-log", "logs", "b.scen"]);
    t.run();
    let logs: Vec<_> = std::fs::read_dir(t.dir().join("logs"))
        .expect("the log folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    assert_eq!(logs.len(), 2, "one log per bench: {logs:?}");
    let db = t.dir().join("bench.db");
    let out = run_with_timeout(
        Command::new(&script).args(&logs).arg("-d").arg(&db),
        std::time::Duration::from_secs(120),
    );
    assert!(
        out.status.success(),
        "{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    // Query the database with Python's sqlite3: the planners, the runs,
    // their times, lengths and success.
    let query = "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); \
        print(c.execute('select count(*) from experiments').fetchone()[0]); \
        print(c.execute('select count(*) from plannerConfigs').fetchone()[0]); \
        print(c.execute('select count(*), sum(solved), min(time) > 0, min(solution_length) > 0 from runs').fetchone()); \
        print(c.execute(\"select count(*) from runs r join plannerConfigs p on r.plannerid = p.id where p.name = 'scen_walk jump=4'\").fetchone()[0])";
    let out = Command::new("python3")
        .args(["-c", query])
        .arg(&db)
        .output()
        .expect("python3 runs");
    let text = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines,
        ["2", "4", "(24, 24, 1, 1)", "11"],
        "{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn test_shards_cover_every_file_once_and_junit_parses() {
    let scenarios = repo().join("scenarios/features");
    let mut seen: Vec<String> = Vec::new();
    let dir = TempDir::new("junit");
    for k in 1..=3 {
        let xml = dir.path().join(format!("j{k}.xml"));
        let out = run_with_timeout(
            Command::new(scen_bin())
                .arg("test")
                .arg(&scenarios)
                .args(["--shard", &format!("{k}/3"), "--junit"])
                .arg(&xml),
            std::time::Duration::from_secs(300),
        );
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stdout)
        );
        let stdout = String::from_utf8_lossy(&out.stdout);
        seen.extend(
            stdout
                .lines()
                .filter(|l| l.starts_with("ok "))
                .filter_map(|l| l.split_whitespace().nth(1).map(str::to_string)),
        );
        // A real XML parser reads it: one test case per check.
        let parse = "import sys, xml.etree.ElementTree as ET; r=ET.parse(sys.argv[1]).getroot(); \
            cases=r.findall('.//testcase'); \
            print(r.tag, r.get('tests'), len(cases), r.get('failures'), all(c.get('file') and c.get('line') for c in cases))";
        let out = Command::new("python3")
            .args(["-c", parse])
            .arg(&xml)
            .output()
            .expect("python3");
        let text = String::from_utf8_lossy(&out.stdout);
        let f: Vec<&str> = text.split_whitespace().collect();
        assert_eq!(f.len(), 5, "{text}{}", String::from_utf8_lossy(&out.stderr));
        assert_eq!(
            (f[0], f[1] == f[2], f[3], f[4]),
            ("testsuites", true, "0", "True"),
            "{text}"
        );
        let checks: usize = stdout
            .lines()
            .filter_map(|l| {
                l.rsplit_once('(')
                    .and_then(|(_, c)| c.split_whitespace().next()?.parse::<usize>().ok())
            })
            .sum();
        assert_eq!(f[1].parse::<usize>().ok(), Some(checks), "{stdout}");
    }
    let mut all: Vec<String> = std::fs::read_dir(&scenarios)
        .expect("scenarios/features")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "scen"))
        .filter(|p| {
            !p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with('_'))
        })
        .map(|p| p.display().to_string())
        .collect();
    all.sort();
    seen.sort();
    assert_eq!(seen, all, "every file in exactly one shard");
}

/// FNV-1a of the run's JSON without its `check`, as `scen` writes it: a
/// test that edits a run on purpose and mends the checksum, to reach the
/// checks behind it.
fn checksum(run: &serde_json::Map<String, Value>) -> String {
    let mut copy = run.clone();
    copy.remove("check");
    let text = serde_json::to_string(&Value::Object(copy)).expect("JSON");
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// Rewrites the first run line of a part with `edit`; `mend` recomputes
/// its checksum.
fn edit_part(path: &Path, mend: bool, edit: impl Fn(&mut serde_json::Map<String, Value>)) {
    let text = std::fs::read_to_string(path).expect("a part");
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut run: serde_json::Map<String, Value> =
        serde_json::from_str(&lines[1]).expect("a run line");
    edit(&mut run);
    if mend {
        let sum = checksum(&run);
        run.insert("check".into(), sum.into());
    }
    lines[1] = serde_json::to_string(&run).expect("JSON");
    std::fs::write(path, lines.join("\n") + "\n").expect("write");
}

/// SPEC §4: `merge` refuses a run whose seed, configuration or metrics do
/// not match what the scenario gives, a split into more parts than runs,
/// and inputs that are not regular files.
#[test]
fn merge_refuses_edited_runs_and_impossible_splits() {
    let dir = TempDir::new("bench-merge-edits");
    let d = dir.path();
    std::fs::write(d.join("b.scen"), SCENARIO).expect("write");
    let make = |name: &str| {
        for k in 1..=2 {
            let out = scen(
                d,
                &[
                    "bench",
                    "b.scen",
                    "--shard",
                    &format!("{k}/2"),
                    "--out",
                    &format!("{name}{k}.jsonl"),
                ],
            );
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
    };
    let refused = |args: &[&str], says: &str| {
        let out = scen(d, args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    };
    make("ok");
    let merged = scen(d, &["bench", "merge", "ok1.jsonl", "ok2.jsonl"]);
    assert!(
        merged.status.success(),
        "{}",
        String::from_utf8_lossy(&merged.stderr)
    );

    // A metric's value edited by hand: the checksum says so.
    make("m");
    edit_part(&d.join("m1.jsonl"), false, |run| {
        run["metrics"]["length"] = Value::from(1.0);
    });
    refused(
        &["bench", "merge", "m1.jsonl", "m2.jsonl"],
        "checksum does not match",
    );
    // With the checksum mended, the seed, the configuration and the
    // metrics are still checked against the scenario.
    make("s");
    edit_part(&d.join("s1.jsonl"), true, |run| {
        run["seed"] = Value::from(run["seed"].as_u64().expect("a seed") + 1000);
    });
    refused(&["bench", "merge", "s1.jsonl", "s2.jsonl"], "another seed");
    make("c");
    edit_part(&d.join("c1.jsonl"), true, |run| {
        run["config"] = serde_json::json!({"jump": 99});
    });
    refused(
        &["bench", "merge", "c1.jsonl", "c2.jsonl"],
        "another configuration",
    );
    make("x");
    edit_part(&d.join("x1.jsonl"), true, |run| {
        if let Some(m) = run["metrics"].as_object_mut() {
            m.remove("length");
        }
    });
    refused(
        &["bench", "merge", "x1.jsonl", "x2.jsonl"],
        "lacks a metric",
    );

    // More parts than runs: refused when splitting, and when merging.
    refused(
        &[
            "bench",
            "b.scen",
            "--shard",
            "1/10000000",
            "--out",
            "big.jsonl",
        ],
        "N may be at most",
    );
    let part = std::fs::read_to_string(d.join("ok1.jsonl")).expect("a part");
    let header = part.lines().next().expect("a header");
    let mut h: serde_json::Map<String, Value> = serde_json::from_str(header).expect("JSON");
    h.insert("n".into(), Value::from(10_000_000u64));
    std::fs::write(
        d.join("huge_n.jsonl"),
        serde_json::to_string(&h).expect("JSON") + "\n",
    )
    .expect("write");
    refused(&["bench", "merge", "huge_n.jsonl"], "only");
    // Not regular files: refused at once, never read to the end.
    #[cfg(unix)]
    refused(&["bench", "merge", "/dev/zero"], "not a regular file");
    refused(&["bench", "merge", "."], "folder");
}

/// `scen bench --runs N` overrides every bench's `runs`; a deterministic
/// planner still runs once per configuration (SPEC §4, 2.7).
#[test]
fn runs_overrides_every_bench() {
    let dir = TempDir::new("bench-runs");
    std::fs::write(dir.path().join("b.scen"), SCENARIO).expect("write");
    let doc = json(&scen(
        dir.path(),
        &["bench", "--json", "--runs", "3", "b.scen"],
    ));
    let benches = doc["benches"].as_array().expect("benches");
    let runs = |b: &Value| b["results"].as_array().expect("results").len();
    // seeds: one randomized plan × 2 jumps × 3 runs; weights: A* × 2
    // weights, once each.
    assert_eq!(runs(&benches[0]), 6, "{}", benches[0]);
    assert_eq!(runs(&benches[1]), 2, "{}", benches[1]);
    // Sharded with the same override, the parts merge to the same table;
    // without it, they are refused as another split.
    let d = dir.path();
    for k in 1..=2 {
        let out = scen(
            d,
            &[
                "bench",
                "b.scen",
                "--runs",
                "3",
                "--shard",
                &format!("{k}/2"),
                "--out",
                &format!("r{k}.jsonl"),
            ],
        );
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let merged = without_timings(json(&scen(
        d,
        &["bench", "merge", "--json", "r1.jsonl", "r2.jsonl"],
    )));
    assert_eq!(merged, without_timings(doc));
    let out = scen(
        d,
        &["bench", "b.scen", "--shard", "2/2", "--out", "plain2.jsonl"],
    );
    assert!(out.status.success());
    let out = scen(d, &["bench", "merge", "r1.jsonl", "plain2.jsonl"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("does not belong"));
}

/// A car's bench exports its curve metrics (cusps, reverse length, segments)
/// to the OMPL log as extra properties, which OMPL's script turns into
/// columns of the database.
#[test]
fn car_benches_export_their_curve_metrics_to_the_ompl_log() {
    let Some(script) = ompl_statistics() else {
        return;
    };
    const CARS: &str = "world {\n  bounds (0, 0) (30, 12)\n  rect kerb (0, 0) (30, 1)\n  \
        rect rear_car (5, 1.2) (10, 3)\n  rect front_car (18, 1.2) (23, 3)\n}\n\
        robot car polygon [(-1, -0.9), (3.5, -0.9), (3.5, 0.9), (-1, 0.9)] steer reeds_shepp 4.5\n\
        plan hybrid hybrid_astar car { start (2, 7, 0deg) goal (11.5, 2.2, 0deg) cell 0.5 }\n\
        plan connect rrt_connect car { start (2, 7, 0deg) goal (11.5, 2.2, 0deg) seed 1 }\n\
        bench cars {\n  runs 2\n}\n";
    let t = Test::new().file("cars.scen", CARS).args(&[
        "bench",
        "-q",
        "--ompl-log",
        "logs",
        "cars.scen",
    ]);
    t.run();
    let log = t.dir().join("logs/cars.cars.log");
    let text = std::fs::read_to_string(&log).expect("the log");
    for property in ["cusps REAL", "reverse length REAL", "segments REAL"] {
        assert!(text.contains(property), "no `{property}`:\n{text}");
    }
    let db = t.dir().join("cars.db");
    let out = run_with_timeout(
        Command::new(&script).arg(&log).arg("-d").arg(&db),
        std::time::Duration::from_secs(120),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // hybrid A* draws nothing at random: one run; RRT-Connect two. The
    // parking manoeuvre reverses: a cusp and some length in reverse, each
    // run.
    let query = "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); \
        print(c.execute('select count(*), sum(solved), min(cusps) >= 1, min(reverse_length) > 0, min(segments) >= 2 from runs').fetchone())";
    let out = Command::new("python3")
        .args(["-c", query])
        .arg(&db)
        .output()
        .expect("python3 runs");
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).trim(),
        "(3, 3, 1, 1, 1)",
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `--metrics` names metrics the benches' plans have: a misspelt one is
/// refused before anything runs, with the closest as a suggestion and the
/// list of those that exist (issue 39: it was silently a column of `—`).
#[test]
fn an_unknown_metric_is_refused_with_a_suggestion() {
    let out = Test::new()
        .file("b.scen", SCENARIO)
        .args(&["bench", "b.scen", "--metrics", "time_ms,lenght"])
        .status(2)
        .stdout("")
        .stderr_contains("`--metrics lenght`: no plan of the benches has a metric `lenght`; did you mean `length`?")
        .stderr_contains("`expanded`")
        .run();
    assert!(!String::from_utf8_lossy(&out.stderr).contains("panicked"));
    Test::new()
        .file("b.scen", SCENARIO)
        .args(&["bench", "b.scen", "--metrics", "zzzzzz"])
        .status(2)
        .stderr_contains("no plan of the benches has a metric `zzzzzz`; the metrics: ")
        .run();
}

#[test]
fn merge_refuses_an_unknown_metric_too() {
    let t = Test::new().file("b.scen", SCENARIO).args(&[
        "bench",
        "b.scen",
        "--shard",
        "1/1",
        "--out",
        "part.jsonl",
    ]);
    t.run();
    let out = Command::new(scen_bin())
        .args(["bench", "merge", "part.jsonl", "--metrics", "lenght"])
        .current_dir(t.dir())
        .env("NO_COLOR", "1")
        .output()
        .expect("run scen");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("did you mean `length`?"), "{stderr}");
    assert!(out.stdout.is_empty());
}

/// Issue 39, item 5: a check that reads a `worlds N` bench's series as
/// one number is an analysis error at the series, naming the aggregates —
/// not a `—` at bench time. worlds × runs > 1 makes a series even when a
/// selection keeps one configuration.
#[test]
fn a_worlds_series_without_aggregate_is_an_analysis_error() {
    const FAMILY: &str = "param gx = uniform(3, 7)\n\
        world {\n  bounds (0, 0) (10, 10)\n  rect wall (gx, 2) (gx + 1, 10)\n}\n\
        robot p point\n\
        plan a astar p { start (1, 5) goal (9, 5) }\n\
        bench fam {\n  vary cell [1, 0.5]\n  worlds 3\n}\n\
        expect fam.a[cell = 1].length < 30\n";
    // The diagnostic as a user sees it: exit 2, the code.
    Test::new()
        .file("f.scen", FAMILY)
        .args(&["check", "f.scen"])
        .status(2)
        .stderr_contains("scen::analyze::series_without_aggregate")
        .run();
    // Its fields, unwrapped: the span of the series, the message, the help.
    let out = Test::new()
        .file("f.scen", FAMILY)
        .args(&["check", "--format", "json", "f.scen"])
        .status(2)
        .run();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let diags: Vec<Value> = stdout
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON object per line"))
        .collect();
    assert_eq!(diags.len(), 1, "{stdout}");
    let d = &diags[0];
    assert_eq!(d["code"], "scen::analyze::series_without_aggregate");
    assert_eq!(
        (d["line"].as_u64(), d["column"].as_u64()),
        (Some(12), Some(8))
    );
    assert_eq!(
        (d["end_line"].as_u64(), d["end_column"].as_u64()),
        (Some(12), Some(30)),
        "{d}"
    );
    assert_eq!(
        d["message"],
        "`fam.a[cell = 1].length` is a series of 3 runs over 3 worlds, not one number"
    );
    // The aggregates are named; a selection cannot pick one world, so the
    // help does not offer one.
    assert_eq!(
        d["help"],
        "use an aggregate, e.g. `median(fam.a[cell = 1].length)` (also `mean`, `min`, `max`, `std`, `sum`, `count`, `quantile(S, 0.9)`, `rate`)"
    );
    // The same check through an aggregate passes analysis.
    Test::new()
        .file(
            "f.scen",
            &FAMILY.replace(
                "expect fam.a[cell = 1].length",
                "expect median(fam.a[cell = 1].length)",
            ),
        )
        .args(&["check", "f.scen"])
        .status(0)
        .run();
}

/// Issue 39, item 9: the success rate with its 95 % Wilson interval in the
/// table, the JSON (`"summary"`) and the CSV (three last columns).
#[test]
fn the_success_rate_comes_with_its_wilson_interval() {
    // 11 of 11 runs found: Wilson's 95 % interval is [0.7412, 1].
    let t = Test::new().file("b.scen", SCENARIO).args(&[
        "bench",
        "--metrics",
        "length",
        "--csv",
        "runs.csv",
        "b.scen",
    ]);
    let out = t.run();
    let text = String::from_utf8_lossy(&out.stdout);
    let row = text
        .lines()
        .find(|l| l.trim_start().starts_with("walk "))
        .unwrap_or_default();
    assert!(row.contains(" 100% [74, 100] "), "{text}");
    // One run of A*: [21, 100].
    assert!(text.contains(" 100% [21, 100] "), "{text}");
    let csv = std::fs::read_to_string(t.dir().join("runs.csv")).expect("a CSV");
    let lines: Vec<&str> = csv.lines().collect();
    let header: Vec<&str> = lines[0].split(',').collect();
    assert_eq!(
        header[header.len() - 3..],
        ["success_rate", "success_ci_lo", "success_ci_hi"]
    );
    let first: Vec<&str> = lines[1].split(',').collect();
    assert_eq!(first[first.len() - 3], "1");
    let lo: f64 = first[first.len() - 2].parse().expect("a number");
    assert!((lo - 0.741_167_033_031_968_3).abs() < 1e-12, "{lo}");
    assert_eq!(first[first.len() - 1], "1");

    let dir = TempDir::new("bench-wilson");
    std::fs::write(dir.path().join("b.scen"), SCENARIO).expect("write");
    let doc = json(&scen(dir.path(), &["bench", "--json", "b.scen"]));
    let summary = &doc["benches"][0]["summary"];
    assert_eq!(summary.as_array().map(Vec::len), Some(2), "{summary}");
    assert_eq!(summary[0]["plan"], "walk");
    assert_eq!(summary[0]["config"]["jump"], 4.0);
    assert_eq!(summary[0]["runs"], 11);
    assert_eq!(summary[0]["successes"], 11);
    assert_eq!(summary[0]["success_rate"], 1.0);
    let ci = summary[0]["success_ci"].as_array().expect("[lo, hi]");
    let lo = ci[0].as_f64().expect("lo");
    assert!((lo - 0.741_167_033_031_968_3).abs() < 1e-12, "{lo}");
    assert_eq!(ci[1], 1.0);
}

/// A family where plan `full` finds a path on every world and `starved`
/// (one expansion allowed) on none.
const PAIRED: &str = "param gx = uniform(3, 7)\n\
    world {\n  bounds (0, 0) (10, 10)\n  rect wall (gx, 2) (gx + 1, 10)\n}\n\
    robot p point\n\
    plan full astar p { start (1, 5) goal (9, 5) }\n\
    plan starved astar p { start (1, 5) goal (9, 5) limit expansions 1 }\n\
    bench fam {\n  worlds 10\n}\n\
    expect rate(fam.full.found) == 100%\n";

/// The wins, ties, losses and p of `metric` in a `--compare` report.
fn tally_line(text: &str, metric: &str) -> Vec<String> {
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with(&format!("{metric} (")))
        .unwrap_or_else(|| panic!("no {metric} line in\n{text}"));
    let after = line.split_once(')').map_or("", |(_, rest)| rest);
    after.split_whitespace().map(str::to_string).collect()
}

/// Issue 39, item 9: `--compare A,B` sets the worlds' results side by side
/// and counts A's wins, ties and losses with a two-sided sign test.
#[test]
fn compare_counts_wins_over_worlds_with_a_sign_test() {
    let out = Test::new()
        .file("f.scen", PAIRED)
        .args(&[
            "bench",
            "--metrics",
            "length",
            "--compare",
            "full,starved",
            "f.scen",
        ])
        .run();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("compare full with starved in bench fam (10 pairs)"),
        "{text}"
    );
    // Side by side: world, run, then per plan found and the metric.
    let header = text
        .lines()
        .find(|l| l.trim_start().starts_with("world "))
        .unwrap_or_default();
    assert_eq!(
        header.split_whitespace().collect::<Vec<_>>(),
        [
            "world",
            "run",
            "full.found",
            "full.length",
            "starved.found",
            "starved.length"
        ],
        "{text}"
    );
    for k in 0..10 {
        let row = text
            .lines()
            .find(|l| l.trim_start().starts_with(&format!("{k} ")))
            .unwrap_or_default();
        let cells: Vec<&str> = row.split_whitespace().collect();
        assert_eq!((cells[2], cells[4]), ("yes", "no"), "{text}");
    }
    // 10 wins, no tie, no loss: p = 2 / 2^10.
    assert_eq!(
        tally_line(&text, "length"),
        ["10", "0", "0", "0.0020"],
        "{text}"
    );
    // The other way round: 10 losses.
    let out = Test::new()
        .file("f.scen", PAIRED)
        .args(&[
            "bench",
            "--metrics",
            "length",
            "--compare",
            "starved,full",
            "f.scen",
        ])
        .run();
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        tally_line(&text, "length"),
        ["0", "0", "10", "0.0020"],
        "{text}"
    );
    // The checks and the summary line still close the report.
    assert!(text.trim_end().ends_with("1 passed, 0 failed"), "{text}");
}

#[test]
fn compare_refuses_unknown_plans_naming_the_plans() {
    Test::new()
        .file("f.scen", PAIRED)
        .args(&["bench", "--compare", "full,nope", "f.scen"])
        .status(2)
        .stderr("error: `--compare`: no plan `nope`; the plans of `f.scen`: full, starved\n")
        .run();
    Test::new()
        .file("f.scen", PAIRED)
        .args(&["bench", "--compare", "full", "f.scen"])
        .status(2)
        .stderr_contains("`--compare` takes two plans, `--compare A,B`")
        .run();
}
