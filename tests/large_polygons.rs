//! Polygons of 100,000 vertices (SPEC 2.2: "A polygon has at most 100,000
//! vertices and its analysis is O(n log n)"): a convex one, a star and a
//! comb go through `scen check`, and through `scen run` with a plan whose
//! path goes around them and is validated. Each process runs under a
//! kill-timeout that only guards against a hang (nothing is asserted about
//! time; BENCHMARKS.md has the figures).

mod common;

use std::f64::consts::TAU;
use std::process::Command;
use std::time::Duration;

use common::{TempDir, run_or_kill, scen_bin};
use serde_json::Value;

const N: usize = 100_000;
const HANG_GUARD: Duration = Duration::from_secs(60);

/// A regular polygon of radius 4 around (5, 5).
fn convex(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|k| {
            let a = TAU * k as f64 / n as f64;
            (5.0 + 4.0 * a.cos(), 5.0 + 4.0 * a.sin())
        })
        .collect()
}

/// A star of n / 2 spikes, radii 4 and 1.5, around (5, 5).
fn star(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|k| {
            let a = TAU * k as f64 / n as f64;
            let r = if k % 2 == 0 { 4.0 } else { 1.5 };
            (5.0 + r * a.cos(), 5.0 + r * a.sin())
        })
        .collect()
}

/// A comb of (n − 2) / 4 teeth (4 vertices each, and 2 for the bar): a bar
/// along y = 1, teeth up to y = 9 over x in [1, 9].
fn comb(n: usize) -> Vec<(f64, f64)> {
    let teeth = (n - 2) / 4;
    let w = 8.0 / teeth as f64;
    let mut v = vec![(1.0, 1.0), (9.0, 1.0)];
    for t in (0..teeth).rev() {
        let x = 1.0 + t as f64 * w;
        v.extend([(x + w, 9.0), (x + w / 2.0, 9.0), (x + w / 2.0, 2.0)]);
        if t > 0 {
            v.push((x, 2.0));
        }
    }
    v.push((1.0, 9.0));
    v
}

/// A world with the polygon, a disk robot and a plan from corner to corner
/// that has to go around it.
fn scenario(name: &str, vertices: &[(f64, f64)]) -> String {
    let list: Vec<String> = vertices
        .iter()
        .map(|(x, y)| format!("({x:.9}, {y:.9})"))
        .collect();
    format!(
        "scenario \"{name}\"\nworld {{\n  bounds (0, 0) (10, 10)\n  polygon P [{}]\n}}\n\
         robot dot disk 0.1\n\
         plan p rrt dot {{\n  start (0.5, 0.5)\n  goal (9.5, 9.5)\n  seed 1\n}}\n\
         expect p.found and p.collision_free\n",
        list.join(", ")
    )
}

fn scen(args: &[&str], dir: &std::path::Path) -> (i32, String) {
    let finished = run_or_kill(
        Command::new(scen_bin()).args(args).current_dir(dir),
        HANG_GUARD,
    );
    let stderr = String::from_utf8_lossy(&finished.stderr).into_owned();
    let Some(status) = finished.status else {
        panic!("scen {args:?} did not finish within {HANG_GUARD:?}\n{stderr}");
    };
    assert!(!stderr.contains("panicked"), "{stderr}");
    (
        status.code().unwrap_or(-1),
        String::from_utf8_lossy(&finished.stdout).into_owned(),
    )
}

#[test]
fn polygons_of_a_hundred_thousand_vertices_are_checked_and_run_around() {
    let dir = TempDir::new("large-polygons");
    for (name, vertices) in [("convex", convex(N)), ("star", star(N)), ("comb", comb(N))] {
        assert!((N - 3..=N).contains(&vertices.len()), "{name}");
        let file = format!("{name}.scen");
        std::fs::write(dir.path().join(&file), scenario(name, &vertices)).unwrap();

        let (code, out) = scen(&["check", &file], dir.path());
        assert_eq!(code, 0, "{name}: {out}");
        assert!(
            out.contains(": ok (1 robot(s), 1 plan(s), 1 check(s))"),
            "{out}"
        );

        let (code, out) = scen(&["run", "--json", &file], dir.path());
        assert_eq!(code, 0, "{name}: {out}");
        let report: Value = serde_json::from_str(&out).unwrap();
        let metrics = &report["plans"]["p"]["metrics"];
        assert_eq!(metrics["found"], true, "{name}: {metrics}");
        assert_eq!(metrics["collision_free"], true, "{name}: {metrics}");
        // The path goes around the polygon, close to it.
        let clearance = metrics["clearance"].as_f64().unwrap();
        assert!(clearance < 1.0, "{name}: clearance {clearance}");
    }
}

/// Not a test: writes the three scenarios into `target/tmp/large-polygons/`
/// for the figures of BENCHMARKS.md (`scen check` timed by hand). Run with
/// `cargo test --release --test large_polygons -- --ignored --nocapture
/// write_the_benchmark_inputs`.
#[test]
#[ignore]
fn write_the_benchmark_inputs() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("large-polygons");
    std::fs::create_dir_all(&dir).unwrap();
    for (name, vertices) in [("convex", convex(N)), ("star", star(N)), ("comb", comb(N))] {
        let path = dir.join(format!("{name}.scen"));
        std::fs::write(&path, scenario(name, &vertices)).unwrap();
        eprintln!("{}", path.display());
    }
}
