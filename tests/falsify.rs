//! `scen falsify` (SPEC 2.8, §4): the search finds a failing sample of a
//! family, the same one on any thread count, and writes a shrunk standalone
//! scenario that fails the same way, 1-minimal in obstacles.

mod common;

use std::path::Path;

use common::{TempDir, repo, scen_bin};

fn scen(dir: &Path, args: &[&str], threads: Option<&str>) -> std::process::Output {
    let mut c = std::process::Command::new(scen_bin());
    c.args(args).current_dir(dir).env("NO_COLOR", "1");
    if let Some(t) = threads {
        c.env("RAYON_NUM_THREADS", t);
    }
    c.output().expect("run scen")
}

fn json(out: &std::process::Output) -> serde_json::Value {
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "not JSON ({e}): {}\n{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    })
}

/// A family whose failure region is 0.1 % of its draws, with a continuous
/// margin (the goal within 0.1784 of the start).
const NEEDLE: &str = "param x = uniform(0, 10)\nparam y = uniform(0, 10)\n\
    world {\n  bounds (-1, -1) (11, 11)\n}\nrobot r point\n\
    plan p roadmap r { start (3.7, 6.2) goal (x, y) }\nexpect p.length > 0.1784\n";

/// Rocks scattered across a straight corridor; the check fails when one
/// blocks the straight line.
const ROCKS: &str = "param n = int(20, 30)\n\
    world {\n  bounds (0, 0) (12, 10)\n  \
    scatter rocks 25 disk uniform(0.3, 0.6) in (2, 1) (10, 9) gap 0.1\n}\n\
    robot r disk 0.2\n\
    plan p astar r { start (0.5, 5) goal (11.5, 5) cell 0.1 connect 8 }\n\
    expect p.length < 11.6\n";

#[test]
fn the_model_guided_search_finds_a_needle_that_uniform_draws_miss() {
    let dir = TempDir::new("falsify-needle");
    std::fs::write(dir.path().join("needle.scen"), NEEDLE).expect("write");
    for seed in ["0", "1", "2"] {
        let out = scen(
            dir.path(),
            &[
                "falsify",
                "needle.scen",
                "--seed",
                seed,
                "--budget",
                "300",
                "--json",
            ],
            None,
        );
        assert_eq!(out.status.code(), Some(1), "a failure is exit 1");
        let doc = json(&out);
        assert_eq!(doc["found"], true, "seed {seed}: {doc}");
        assert!(doc["samples_tried"].as_u64().unwrap() <= 300);
        assert!(doc["margin"].as_f64().unwrap() <= 0.0);
        assert_eq!(doc["check"], "p.length > 0.1784");
        for key in ["sample", "params", "out", "line"] {
            assert!(doc.get(key).is_some(), "no {key}: {doc}");
        }
        // The goal it found is within the needle.
        let (x, y) = (
            doc["params"]["x"].as_f64().unwrap(),
            doc["params"]["y"].as_f64().unwrap(),
        );
        assert!((x - 3.7).hypot(y - 6.2) <= 0.1784, "({x}, {y})");
    }
    // 100 uniform draws do not find it (with seed 0): the search is what
    // finds it, not luck.
    let out = scen(
        dir.path(),
        &[
            "falsify",
            "needle.scen",
            "--search",
            "uniform",
            "--budget",
            "100",
            "--json",
        ],
        None,
    );
    assert_eq!(out.status.code(), Some(0), "no failure is exit 0");
    let doc = json(&out);
    assert_eq!(doc["found"], false);
    assert!(
        doc["margin"].as_f64().unwrap() > 0.0,
        "the smallest margin: {doc}"
    );
}

#[test]
fn the_result_does_not_depend_on_the_thread_count() {
    let dir = TempDir::new("falsify-threads");
    std::fs::write(dir.path().join("rocks.scen"), ROCKS).expect("write");
    let mut runs = Vec::new();
    for threads in ["1", "3"] {
        let out = scen(
            dir.path(),
            &[
                "falsify",
                "rocks.scen",
                "--json",
                "--out",
                &format!("fail{threads}.scen"),
            ],
            Some(threads),
        );
        let mut doc = json(&out);
        doc["out"] = serde_json::Value::Null;
        let text = std::fs::read_to_string(dir.path().join(format!("fail{threads}.scen")))
            .expect("the shrunk file");
        runs.push((doc, text));
    }
    assert_eq!(runs[0], runs[1]);
}

/// The obstacle lines of a scenario's `world` block.
fn obstacle_lines(text: &str) -> Vec<usize> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| {
            let l = l.trim_start();
            ["rect ", "disk ", "polygon ", "segment "]
                .iter()
                .any(|k| l.starts_with(k))
        })
        .map(|(k, _)| k)
        .collect()
}

/// `scen test` on a text: its exit code.
fn test_exit(dir: &Path, name: &str, text: &str) -> Option<i32> {
    std::fs::write(dir.join(name), text).expect("write");
    scen(dir, &["test", name], None).status.code()
}

/// The shrunk file fails under `scen test`, and removing any one of its
/// obstacles makes it pass.
fn assert_shrunk_and_one_minimal(dir: &Path, text: &str) {
    assert!(
        !text.contains("param ") && !text.contains("scatter "),
        "{text}"
    );
    assert_eq!(test_exit(dir, "shrunk.scen", text), Some(1), "{text}");
    let lines = obstacle_lines(text);
    assert!(!lines.is_empty(), "{text}");
    for &k in &lines {
        let without: String = text
            .lines()
            .enumerate()
            .filter(|(i, _)| *i != k)
            .map(|(_, l)| format!("{l}\n"))
            .collect();
        assert_eq!(
            test_exit(dir, "without.scen", &without),
            Some(0),
            "removing line {} keeps the failure:\n{text}",
            k + 1
        );
    }
}

#[test]
fn shrunk_files_are_standalone_failing_and_one_minimal() {
    let dir = TempDir::new("falsify-shrink");
    std::fs::write(dir.path().join("rocks.scen"), ROCKS).expect("write");
    let out = scen(dir.path(), &["falsify", "rocks.scen", "--json"], None);
    let doc = json(&out);
    assert_eq!(doc["found"], true, "{doc}");
    assert!(doc["obstacles_shrunk"].as_u64().unwrap() < doc["obstacles"].as_u64().unwrap());
    let text = std::fs::read_to_string(dir.path().join("rocks_fail.scen")).expect("FILE_fail.scen");
    assert!(text.starts_with("# Falsified by `scen falsify`"), "{text}");
    assert_shrunk_and_one_minimal(dir.path(), &text);

    // The committed example: regenerated identically, and still failing.
    // Run from the repository with the path as the docs give it, so that
    // the header's reproducing commands are the committed ones too.
    let family = "scenarios/family_narrow_rrt.scen";
    let committed = repo().join("tests/falsified/family_narrow_rrt_fail.scen");
    let out_path = dir.path().join("narrow_fail.scen");
    let out = scen(
        &repo(),
        &["falsify", family, "--out", out_path.to_str().unwrap()],
        None,
    );
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let fresh = std::fs::read_to_string(&out_path).expect("written");
    let kept = std::fs::read_to_string(&committed).expect("committed");
    assert_eq!(
        fresh, kept,
        "regenerate it: scen falsify scenarios/family_narrow_rrt.scen --out tests/falsified/family_narrow_rrt_fail.scen"
    );
    assert_shrunk_and_one_minimal(dir.path(), &kept);
}

#[test]
fn falsify_needs_a_family_and_a_plain_check() {
    let dir = TempDir::new("falsify-bad");
    let plain = "world {\n  bounds (0, 0) (10, 10)\n}\nrobot r point\n\
                 plan p astar r { start (1, 1) goal (9, 9) }\nexpect p.found\n";
    std::fs::write(dir.path().join("plain.scen"), plain).expect("write");
    let out = scen(dir.path(), &["falsify", "plain.scen"], None);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("scen::falsify::not_a_family"));

    let unchecked = "param a = uniform(2, 8)\nworld {\n  bounds (0, 0) (10, 10)\n}\nrobot r point\n\
                     plan p astar r { start (1, 1) goal (a, 9) }\n";
    std::fs::write(dir.path().join("unchecked.scen"), unchecked).expect("write");
    let out = scen(dir.path(), &["falsify", "unchecked.scen"], None);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("scen::falsify::no_check"));
    assert!(!dir.path().join("unchecked_fail.scen").exists());
}

/// `scen falsify --shard K/N --out PART.jsonl` on each part, then `merge`.
fn sharded(dir: &Path, file: &str, search: &str, n: u64, extra: &[&str]) -> Vec<String> {
    (1..=n)
        .map(|k| {
            let part = format!("{search}-{k}.jsonl");
            let shard = format!("{k}/{n}");
            let mut args = vec![
                "falsify", file, "--search", search, "--shard", &shard, "--out", &part,
            ];
            args.extend_from_slice(extra);
            let out = scen(dir, &args, None);
            assert_eq!(
                out.status.code(),
                Some(0),
                "a part written is exit 0: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            part
        })
        .collect()
}

#[test]
fn sharded_searches_merge_to_the_failure_of_the_whole_search() {
    let dir = TempDir::new("falsify-shard");
    std::fs::write(dir.path().join("needle.scen"), NEEDLE).expect("write");
    let budget = ["--budget", "2000"];
    // `uniform` and `halton`: the parts split the whole search's samples,
    // so the merged failure is the one the whole search finds first, and
    // the shrunk file is the same.
    for search in ["uniform", "halton"] {
        let mut whole = vec!["falsify", "needle.scen", "--search", search, "--json"];
        whole.extend_from_slice(&budget);
        whole.extend_from_slice(&["--out", "whole.scen"]);
        let one = json(&scen(dir.path(), &whole, None));
        assert_eq!(one["found"], true, "{search}: {one}");
        let parts = sharded(dir.path(), "needle.scen", search, 3, &budget);
        let mut args = vec!["falsify", "merge"];
        // In any order.
        args.extend(parts.iter().rev().map(String::as_str));
        args.extend_from_slice(&["--json", "--out", "merged.scen"]);
        let out = scen(dir.path(), &args, None);
        assert_eq!(out.status.code(), Some(1), "a failure is exit 1");
        let merged = json(&out);
        for key in ["found", "sample", "params", "check", "margin", "obstacles"] {
            assert_eq!(merged[key], one[key], "{search}: {key}");
        }
        // The parts tried at least what the whole search did.
        assert!(merged["samples_tried"].as_u64() >= one["samples_tried"].as_u64());
        let read = |f: &str| std::fs::read_to_string(dir.path().join(f)).expect(f);
        assert_eq!(read("merged.scen"), read("whole.scen"), "{search}");
    }
    // `auto`: each part searches on its own; the merged failure is one of
    // theirs, and it fails.
    let parts = sharded(dir.path(), "needle.scen", "auto", 2, &budget);
    let out = scen(
        dir.path(),
        &["falsify", "merge", &parts[0], &parts[1], "--json"],
        None,
    );
    let merged = json(&out);
    assert_eq!(merged["found"], true, "{merged}");
    assert_eq!(
        test_exit(
            dir.path(),
            "auto.scen",
            &std::fs::read_to_string(dir.path().join("needle_fail.scen")).expect("written")
        ),
        Some(1)
    );

    // Refusals, each exit 2 with the reason.
    let refused = |args: &[&str], why: &str| {
        let out = scen(dir.path(), args, None);
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        // miette wraps long messages: compare the words.
        let flat = err
            .split_whitespace()
            .filter(|w| *w != "│")
            .collect::<Vec<_>>()
            .join(" ");
        assert!(flat.contains(why), "{args:?}: {err}");
    };
    refused(&["falsify", "merge", &parts[0]], "1 part(s) missing: 2/2");
    refused(&["falsify", "merge", &parts[0], &parts[0]], "given twice");
    let other = sharded(dir.path(), "needle.scen", "uniform", 2, &["--budget", "10"]);
    refused(
        &["falsify", "merge", &parts[0], &other[1]],
        "does not belong with",
    );
    refused(&["falsify", "needle.scen", "--shard", "1/2"], "--out");
    refused(
        &[
            "falsify",
            "needle.scen",
            "--shard",
            "3/2",
            "--out",
            "p.jsonl",
        ],
        "is not a shard",
    );
    refused(
        &[
            "falsify",
            "needle.scen",
            "--budget",
            "4",
            "--shard",
            "1/5",
            "--out",
            "p.jsonl",
        ],
        "at most 4 part(s)",
    );
    refused(&["falsify", "merge", "needle.scen"], "is not a part");
    std::fs::write(
        dir.path().join("needle.scen"),
        format!("{NEEDLE}# changed\n"),
    )
    .expect("write");
    refused(
        &["falsify", "merge", &parts[0], &parts[1]],
        "has changed since the parts were made",
    );
}

/// Runs the command line `scen falsify` printed (`scen run FILE ...`)
/// with the real binary.
fn run_printed(dir: &Path, command: &str, extra: &[&str]) -> std::process::Output {
    let words: Vec<&str> = command.split_whitespace().collect();
    assert_eq!(&words[..2], ["scen", "run"], "{command}");
    let mut args: Vec<&str> = words[1..].to_vec();
    args.extend_from_slice(extra);
    scen(dir, &args, None)
}

/// The falsified check fails again (exit 1) when the printed command runs:
/// for a family of params only (`--set` alone) and for one that scatters
/// (`--set` with the sample whose stream places the items).
#[test]
fn the_printed_command_reproduces_the_failing_world() {
    let dir = TempDir::new("falsify-reproduce");
    for (name, text, scatters) in [("needle.scen", NEEDLE, false), ("rocks.scen", ROCKS, true)] {
        std::fs::write(dir.path().join(name), text).expect("write");
        let out = scen(
            dir.path(),
            &["falsify", name, "--seed", "3", "--json"],
            None,
        );
        assert_eq!(out.status.code(), Some(1), "{name}");
        let doc = json(&out);
        let command = doc["reproduce"]
            .as_str()
            .expect("a reproduce line")
            .to_string();
        assert!(command.contains("--set "), "{command}");
        assert_eq!(command.contains("--sample "), scatters, "{command}");
        if scatters {
            assert!(command.contains("--family-seed 3"), "{command}");
        }
        // The text report prints the same line.
        let text = scen(dir.path(), &["falsify", name, "--seed", "3"], None);
        let stdout = String::from_utf8_lossy(&text.stdout);
        assert!(stdout.contains(&format!("run it: {command}")), "{stdout}");
        // Run as printed: the same check fails, on the same params, exactly.
        let run = run_printed(dir.path(), &command, &[]);
        let report = String::from_utf8_lossy(&run.stdout);
        assert_eq!(run.status.code(), Some(1), "{command}:\n{report}");
        assert!(report.contains("FAIL"), "{report}");
        let run = json(&run_printed(dir.path(), &command, &["--json"]));
        assert_eq!(run["params"], doc["params"], "{command}");
        let failed: Vec<&serde_json::Value> = run["checks"]
            .as_array()
            .expect("checks")
            .iter()
            .filter(|c| c["passed"] == false)
            .collect();
        assert_eq!(failed.len(), 1, "{run}");
        assert_eq!(failed[0]["line"], doc["line"], "{run}");
        // The written file's comment says the same.
        let stem = name.trim_end_matches(".scen");
        let written =
            std::fs::read_to_string(dir.path().join(format!("{stem}_fail.scen"))).expect("written");
        assert!(written.contains(&command), "{written}");
    }
}

/// `--set` names a family member, or is refused with a diagnostic (exit 2).
#[test]
fn run_set_refuses_what_is_no_family_member() {
    let dir = TempDir::new("run-set");
    let family = "param a = uniform(1, 3)\nparam n = int(2, 5)\nparam c = choice [0.5, 1.5]\n\
        param b = a + 1\nrequire a + n < 7\n\
        world {\n  bounds (0, 0) (10, 10)\n}\nrobot r point\n\
        plan p astar r { start (1, 1) goal (a, b) }\nexpect p.found\n";
    std::fs::write(dir.path().join("f.scen"), family).expect("write");
    // A member: exit 0, the values given.
    let out = scen(
        dir.path(),
        &[
            "run", "f.scen", "--set", "a=2.5", "--set", "n=3", "--set", "c=1.5", "--json",
        ],
        None,
    );
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc = json(&out);
    assert_eq!(doc["params"]["a"], 2.5);
    assert_eq!(doc["params"]["b"], 3.5);
    assert_eq!(doc["params"]["n"], 3.0);
    let refused = |args: &[&str], why: &str| {
        let mut all = vec!["run", "f.scen"];
        all.extend_from_slice(args);
        let out = scen(dir.path(), &all, None);
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains("scen::family::bad_set"), "{args:?}: {err}");
        // miette wraps long messages: compare the words.
        let flat = err
            .split_whitespace()
            .filter(|w| *w != "│")
            .collect::<Vec<_>>()
            .join(" ");
        assert!(flat.contains(why), "{args:?}: {err}");
        // A diagnostic with its place in the file.
        assert!(err.contains("f.scen:"), "{args:?}: {err}");
    };
    refused(&["--set", "aa=2"], "the drawn params are `a`, `n`, `c`");
    refused(&["--set", "a=3.5"], "from 1 to 3");
    refused(&["--set", "n=2.5"], "whole numbers from 2 to 5");
    refused(&["--set", "c=1"], "one of 0.5, 1.5");
    refused(&["--set", "a=two"], "`two` is not a number");
    refused(&["--set", "a"], "is not `NAME=VALUE`");
    refused(&["--set", "b=2"], "computed from others");
    refused(
        &["--set", "a=2.9", "--set", "n=5", "--set", "c=0.5"],
        "violate a `require`",
    );
}

/// Shrinking keeps every value in the family: the drawn param rounded only
/// where its `require` still holds, the scattered radii inside their
/// distribution's support (rounding 0.31–0.38 to one decimal leaves it),
/// the centres inside the scatter's box.
#[test]
fn shrunk_values_stay_inside_the_family() {
    let dir = TempDir::new("falsify-support");
    let family = "param a = uniform(0.6, 1.4)\nrequire a > 1.04\n\
        world {\n  bounds (0, 0) (12, 10)\n  \
        scatter rocks 25 disk uniform(0.31, 0.38) in (2, 1) (10, 9) gap 0.1\n}\n\
        robot r disk 0.2\n\
        plan p astar r { start (0.55, 5.05) goal (11.45, 5.05) cell 0.1 connect 8 }\n\
        expect p.length < 9.9 + a\n";
    std::fs::write(dir.path().join("support.scen"), family).expect("write");
    let out = scen(dir.path(), &["falsify", "support.scen", "--json"], None);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(dir.path().join("support_fail.scen")).expect("written");
    // The member it names: its `a` satisfies the require, and it fails.
    let member = text
        .lines()
        .find_map(|l| l.strip_prefix("# This file is the family member `"))
        .and_then(|l| l.split('`').next())
        .unwrap_or_else(|| panic!("no member named:\n{text}"))
        .to_string();
    let a: f64 = member
        .split_whitespace()
        .find_map(|w| w.strip_prefix("a="))
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("{member}"));
    assert!((1.04..=1.4).contains(&a) && a > 1.04, "a = {a}: {text}");
    assert_eq!(
        run_printed(dir.path(), &member, &[]).status.code(),
        Some(1),
        "{member}"
    );
    // The rocks kept: radius in [0.31, 0.38], centre in the box.
    let mut rocks = 0;
    for l in text
        .lines()
        .filter(|l| l.trim_start().starts_with("disk rocks_"))
    {
        let nums: Vec<f64> = l
            .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
            .filter(|w| !w.is_empty() && w.parse::<f64>().is_ok())
            .map(|w| w.parse().unwrap())
            .collect();
        // `disk rocks_K (x, y) r`: the name's number first.
        let (x, y, r) = (nums[1], nums[2], nums[3]);
        assert!((0.31..=0.38).contains(&r), "radius {r}: {l}");
        assert!((2.0..=10.0).contains(&x) && (1.0..=9.0).contains(&y), "{l}");
        rocks += 1;
    }
    assert!(rocks > 0, "{text}");
    assert_eq!(
        test_exit(dir.path(), "shrunk.scen", &text),
        Some(1),
        "{text}"
    );
}

/// The held-out families of `scripts/bench_falsify.sh` parse and analyse
/// (they fail on purpose, so they live outside `scenarios/`), and each one
/// does fail somewhere: its failure region is not empty.
#[test]
fn the_benchmark_families_load_and_can_fail() {
    let dir = repo().join("benches/falsify");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("benches/falsify")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "scen"))
        .collect();
    files.sort();
    assert!(files.len() >= 4, "{files:?}");
    for file in &files {
        let out = scen(&repo(), &["check", file.to_str().unwrap()], None);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{}: {}",
            file.display(),
            String::from_utf8_lossy(&out.stderr)
        );
    }
    // A point inside each failure region fails (exit 1).
    let inside: [(&str, &[&str]); 6] = [
        ("corner.scen", &["x=0.99", "y=0.01"]),
        ("band.scen", &["x=0.6", "y=0.4"]),
        ("band_decoy.scen", &["x=0.4422", "y=0.9"]),
        ("product.scen", &["a=0.6", "b=0.5001"]),
        ("ring.scen", &["x=0.8002", "y=0.5"]),
        ("three_params.scen", &["a=0.95", "b=0.95", "c=0.95"]),
    ];
    assert_eq!(files.len(), inside.len(), "a point inside each: {files:?}");
    for (name, set) in inside {
        let mut args = vec!["run".to_string(), dir.join(name).display().to_string()];
        for s in set {
            args.extend(["--set".to_string(), s.to_string()]);
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        assert_eq!(scen(&repo(), &args, None).status.code(), Some(1), "{name}");
    }
}
