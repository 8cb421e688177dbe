//! Scenario families (SPEC 2.8): params, distributions, expressions in
//! number positions, `scatter`, `require`, and samples drawn from seeded
//! streams. Every sample is analysed like a hand-written scenario, so these
//! tests look at what the draws put into the world.

mod common;

use std::path::{Path, PathBuf};

use common::TempDir;
use scen::Scenario;
use scen::geometry::Shape;
use scen::scenario::{SampleChoice, load_sample};

/// Writes `text` as `name` in `dir`.
fn write(dir: &TempDir, name: &str, text: &str) -> PathBuf {
    let path = dir.path().join(name);
    std::fs::write(&path, text).expect("write the scenario");
    path
}

fn sample(path: &Path, sample: u64, family_seed: u64) -> Scenario {
    load_sample(
        path,
        None,
        &|_| None,
        SampleChoice {
            sample,
            family_seed,
        },
    )
    .unwrap_or_else(|f| panic!("sample {sample} does not load: {:?}", f.diags))
}

fn param(s: &Scenario, name: &str) -> f64 {
    let drawn = s
        .family
        .as_ref()
        .expect("a family's sample says what it drew");
    drawn
        .params
        .iter()
        .find(|(n, _)| n == name)
        .map(|(_, x)| *x)
        .unwrap_or_else(|| panic!("no param {name}"))
}

const WORLD: &str = "world {\n  bounds (0, 0) (20, 20)\n}\nrobot r disk 0.3\n";

#[test]
fn the_same_sample_is_the_same_world_and_others_differ() {
    let dir = TempDir::new("families");
    let path = write(
        &dir,
        "f.scen",
        &format!(
            "param a = uniform(2, 18)\nparam n = int(1, 6)\nparam c = choice [1, 2.5, 4]\n\
             param m = normal(10, 2)\n{WORLD}plan p astar r {{ start (1, 1) goal (a, 10) }}\n"
        ),
    );
    let first = sample(&path, 3, 0);
    let again = sample(&path, 3, 0);
    assert_eq!(first.family, again.family);
    assert_eq!(first.world, again.world);
    assert_ne!(first.family, sample(&path, 4, 0).family);
    assert_ne!(first.family, sample(&path, 3, 1).family);

    let mut mean = 0.0;
    let count = 300;
    for k in 0..count {
        let s = sample(&path, k, 7);
        let (a, n, c, m) = (
            param(&s, "a"),
            param(&s, "n"),
            param(&s, "c"),
            param(&s, "m"),
        );
        assert!((2.0..18.0).contains(&a), "uniform(2, 18) drew {a}");
        assert!(
            n.fract() == 0.0 && (1.0..=6.0).contains(&n),
            "int(1, 6) drew {n}"
        );
        assert!([1.0, 2.5, 4.0].contains(&c), "choice drew {c}");
        // The goal is the drawn value itself.
        let goal = s.plans[0].params.goal.expect("a goal");
        assert_eq!(goal.x, a);
        mean += m / count as f64;
    }
    // The mean of 300 draws of N(10, 2) lies within 5 standard errors.
    assert!(
        (mean - 10.0).abs() < 5.0 * 2.0 / (count as f64).sqrt(),
        "mean {mean}"
    );
}

#[test]
fn expressions_compute_numbers_and_angles() {
    let dir = TempDir::new("families");
    let path = write(
        &dir,
        "f.scen",
        &format!(
            "param a = 4\nparam b = a * 2 - 1\n{WORLD}robot rod rect 2 0.5\n\
             plan p astar rod {{ start (min(a, b), sqrt(a), (a + 86)deg) \
             goal (max(a, b) + abs(-1), 10 / 4) }}\n"
        ),
    );
    let s = sample(&path, 0, 0);
    assert_eq!(param(&s, "b"), 7.0);
    let plan = &s.plans[0];
    let (start, goal) = (plan.params.start, plan.params.goal.expect("a goal"));
    assert_eq!((start.x, start.y), (4.0, 2.0));
    assert!(
        (start.theta - 90f64.to_radians()).abs() < 1e-12,
        "{}",
        start.theta
    );
    assert_eq!((goal.x, goal.y), (8.0, 2.5));
}

#[test]
fn scattered_items_keep_their_gap_inside_their_box() {
    let dir = TempDir::new("families");
    let path = write(
        &dir,
        "f.scen",
        "world {\n  bounds (0, 0) (20, 20)\n  \
         scatter rocks 25 disk uniform(0.2, 0.6) in (0, 0) (20, 10) gap 0.4\n  \
         scatter boxes 5 rect 1 2 in (0, 12) (20, 18)\n}\n\
         robot r disk 0.3\nplan p astar r { start (0.5, 19.5) goal (19.5, 19.5) }\n",
    );
    for k in 0..40 {
        let s = sample(&path, k, 0);
        let disks: Vec<(f64, f64, f64)> = s
            .world
            .obstacles
            .iter()
            .filter_map(|o| match o.shape {
                Shape::Disk { center, radius } => Some((center.x, center.y, radius)),
                _ => None,
            })
            .collect();
        assert_eq!(disks.len(), 25);
        let names: Vec<&str> = s.world.obstacles.iter().map(|o| o.name.as_str()).collect();
        assert_eq!(names[0], "rocks_1");
        assert_eq!(names[24], "rocks_25");
        assert_eq!(names[29], "boxes_5");
        for (i, &(x, y, r)) in disks.iter().enumerate() {
            assert!((0.0..20.0).contains(&x) && (0.0..10.0).contains(&y));
            assert!((0.2..0.6).contains(&r));
            for &(u, v, s) in &disks[..i] {
                let gap = (x - u).hypot(y - v) - r - s;
                assert!(gap >= 0.4, "sample {k}: two rocks {gap} apart");
            }
        }
    }
}

#[test]
fn the_documented_cap_of_scattered_items_places() {
    // Issue 39: placement measured every try against every placed item, so
    // 100 000 items (MAX_SCATTER_ITEMS) did not finish in `scen check`.
    let dir = TempDir::new("families");
    write(
        &dir,
        "many.scen",
        "world {\n  bounds (0, 0) (1010, 1010)\n  \
         scatter rocks 100000 disk uniform(0.05, 0.2) in (0, 0) (1000, 1000) gap 0.5\n}\n\
         robot r point\nplan p astar r { start (1005, 1005) goal (1006, 1006) }\n",
    );
    let out = scen(dir.path(), &["check", "many.scen"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let s = sample(&dir.path().join("many.scen"), 0, 0);
    assert_eq!(s.world.obstacles.len(), 100_000);
    assert_eq!(s.world.obstacles[99_999].name, "rocks_100000");
}

#[test]
fn draws_that_break_a_require_or_block_the_start_are_drawn_again() {
    let dir = TempDir::new("families");
    let path = write(
        &dir,
        "f.scen",
        "param x = uniform(0, 10)\nparam y = uniform(0, 10)\nrequire x + y > 8\n\
         world {\n  bounds (0, 0) (10, 10)\n  disk (x, y) 1.5\n}\n\
         robot r disk 0.3\nplan p astar r { start (5, 5) goal (9, 1) }\n",
    );
    let mut rejected = 0;
    for k in 0..100 {
        let s = sample(&path, k, 0);
        let (x, y) = (param(&s, "x"), param(&s, "y"));
        assert!(x + y > 8.0, "the require was ignored: {x} + {y}");
        // The disk never covers the start (5, 5) grown by the robot.
        assert!(
            (x - 5.0).hypot(y - 5.0) > 1.8,
            "start in collision at {x}, {y}"
        );
        rejected += s.family.as_ref().map_or(0, |d| d.rejected);
    }
    assert!(rejected > 0, "the test needs some rejections");
}

#[test]
fn a_scenario_without_params_is_not_a_family() {
    let dir = TempDir::new("families");
    let path = write(
        &dir,
        "f.scen",
        &format!("{WORLD}plan p astar r {{ start (1, 1) goal (2 * 3, 10 - 1) }}\n"),
    );
    let s = sample(&path, 5, 5);
    assert!(s.family.is_none());
    let goal = s.plans[0].params.goal.expect("a goal");
    assert_eq!((goal.x, goal.y), (6.0, 9.0));
}

/// Runs `scen` in `dir`.
fn scen(dir: &Path, args: &[&str]) -> std::process::Output {
    std::process::Command::new(common::scen_bin())
        .args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .output()
        .expect("run scen")
}

const FAMILY_BENCH: &str = "param w = uniform(0.4, 2)\n\
    world {\n  bounds (0, 0) (10, 10)\n  rect (0, 4.5) (5 - w / 2, 5.5)\n  rect (5 + w / 2, 4.5) (10, 5.5)\n}\n\
    robot r disk 0.4\n\
    plan p astar r { start (5, 1) goal (5, 9) cell 0.1 }\n\
    bench b { worlds 12 }\n\
    expect rate(b.p.found) > 0\n";

#[test]
fn a_bench_runs_every_world_and_shards_merge_to_the_same_report() {
    let dir = TempDir::new("families-bench");
    write(&dir, "f.scen", FAMILY_BENCH);
    let whole = scen(dir.path(), &["bench", "f.scen", "--json"]);
    assert!(
        whole.status.success(),
        "{}",
        String::from_utf8_lossy(&whole.stderr)
    );
    let doc: serde_json::Value = serde_json::from_slice(&whole.stdout).expect("JSON");
    let runs = doc["benches"][0]["results"]
        .as_array()
        .expect("runs")
        .clone();
    assert_eq!(runs.len(), 12);
    let worlds: Vec<u64> = runs
        .iter()
        .map(|r| r["world"].as_u64().expect("a world"))
        .collect();
    assert_eq!(worlds, (0..12).collect::<Vec<u64>>());
    // Each world is the sample `scen run --sample K` shows.
    for k in [0u64, 7] {
        let one = scen(
            dir.path(),
            &["run", "f.scen", "--json", "--sample", &k.to_string()],
        );
        let one: serde_json::Value = serde_json::from_slice(&one.stdout).expect("JSON");
        assert_eq!(
            one["plans"]["p"]["metrics"]["found"], runs[k as usize]["metrics"]["found"],
            "world {k}"
        );
    }
    // Some worlds are too narrow for the robot, others not.
    let found: Vec<bool> = runs.iter().map(|r| r["metrics"]["found"] == true).collect();
    assert!(found.contains(&true) && found.contains(&false), "{found:?}");

    // Three shards, merged: the same runs.
    for k in 1..=3 {
        let out = scen(
            dir.path(),
            &[
                "bench",
                "f.scen",
                "--shard",
                &format!("{k}/3"),
                "--out",
                &format!("part{k}.jsonl"),
            ],
        );
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let merged = scen(
        dir.path(),
        &[
            "bench",
            "merge",
            "part1.jsonl",
            "part2.jsonl",
            "part3.jsonl",
            "--json",
        ],
    );
    assert!(
        merged.status.success(),
        "{}",
        String::from_utf8_lossy(&merged.stderr)
    );
    let merged: serde_json::Value = serde_json::from_slice(&merged.stdout).expect("JSON");
    let strip = |runs: &serde_json::Value| -> Vec<serde_json::Value> {
        runs.as_array()
            .expect("runs")
            .iter()
            .map(|r| {
                let mut r = r.clone();
                r["metrics"]["time_ms"] = serde_json::Value::Null;
                r
            })
            .collect()
    };
    assert_eq!(
        strip(&merged["benches"][0]["results"]),
        strip(&doc["benches"][0]["results"])
    );

    // `--worlds 3` overrides the bench's 12.
    let three = scen(dir.path(), &["bench", "f.scen", "--json", "--worlds", "3"]);
    let three: serde_json::Value = serde_json::from_slice(&three.stdout).expect("JSON");
    assert_eq!(
        three["benches"][0]["results"].as_array().map(Vec::len),
        Some(3)
    );
}

#[test]
fn worlds_need_a_family() {
    let dir = TempDir::new("families-worlds");
    write(
        &dir,
        "plain.scen",
        "world { bounds (0, 0) (10, 10) }\nrobot r point\n\
         plan p astar r { start (1, 1) goal (9, 9) }\nbench b { runs 2 }\n",
    );
    let out = scen(dir.path(), &["bench", "plain.scen", "--worlds", "4"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("draws nothing"));
}
