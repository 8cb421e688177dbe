//! Outputs that other programs read: determinism of the JSON document,
//! and the Rerun recording checked by the real viewer binary.

mod common;

use std::path::PathBuf;
use std::process::Command;
use std::time::Duration;

#[cfg(feature = "viewer")]
use common::TempDir;
use common::{repo, run_with_timeout, scen_bin};

fn scenario_files() -> Vec<PathBuf> {
    fn walk(dir: &std::path::Path, out: &mut Vec<PathBuf>) {
        let mut entries: Vec<_> = std::fs::read_dir(dir)
            .expect("scenarios/")
            .flatten()
            .map(|e| e.path())
            .collect();
        entries.sort();
        for p in entries {
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "scen")
                && !scen::scenario::movingai::is_scen_file(&p)
                && !p
                    .file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with('_'))
            {
                out.push(p);
            }
        }
    }
    let mut v = Vec::new();
    walk(&repo().join("scenarios"), &mut v);
    assert!(
        v.len() >= 5,
        "expected the scenarios folder to hold scenarios"
    );
    v
}

/// Removes every timing (`"time_ms": N`, and the other `*_ms` metrics such
/// as `simplify_ms`) so that two runs can be compared.
fn without_time(json: &str) -> serde_json::Value {
    fn strip(v: &mut serde_json::Value) {
        match v {
            serde_json::Value::Object(m) => {
                m.retain(|k, _| !k.ends_with("_ms"));
                m.values_mut().for_each(strip);
            }
            serde_json::Value::Array(a) => a.iter_mut().for_each(strip),
            _ => {}
        }
    }
    let mut v: serde_json::Value = serde_json::from_str(json).expect("valid JSON");
    strip(&mut v);
    v
}

#[test]
fn two_runs_of_every_scenario_give_identical_json() {
    for file in scenario_files() {
        let run = || {
            let out = run_with_timeout(
                Command::new(scen_bin()).args(["run", "--json"]).arg(&file),
                Duration::from_secs(120),
            );
            String::from_utf8(out.stdout).expect("UTF-8 JSON")
        };
        let (a, b) = (run(), run());
        assert!(!a.trim().is_empty(), "no JSON for {}", file.display());
        let (va, vb) = (without_time(&a), without_time(&b));
        assert_eq!(va, vb, "{} is not deterministic", file.display());
        // Byte-identical apart from time_ms: re-serialised forms agree too.
        assert_eq!(va.to_string(), vb.to_string());
    }
}

/// A verified recording of a scenario: `scen run FILE --save` into a temp
/// folder, checked with `rerun rrd verify`. `None` (skip) only outside CI
/// when there is no `rerun` binary.
#[cfg(feature = "viewer")]
struct Recording {
    rerun: PathBuf,
    rrd: PathBuf,
    _dir: TempDir,
}

#[cfg(feature = "viewer")]
fn verified_recording(scenario: &str) -> Option<Recording> {
    let rerun = common::rerun_binary()?;
    let dir = TempDir::new("rrd");
    let rrd = dir.path().join("out.rrd");
    let out = run_with_timeout(
        Command::new(scen_bin())
            .arg("run")
            .arg(repo().join(scenario))
            .arg("--save")
            .arg(&rrd),
        Duration::from_secs(120),
    );
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let verify = run_with_timeout(
        Command::new(&rerun).args(["rrd", "verify"]).arg(&rrd),
        Duration::from_secs(120),
    );
    assert!(
        verify.status.success(),
        "rerun rrd verify failed:\n{}\n{}",
        String::from_utf8_lossy(&verify.stdout),
        String::from_utf8_lossy(&verify.stderr)
    );
    Some(Recording {
        rerun,
        rrd,
        _dir: dir,
    })
}

#[cfg(feature = "viewer")]
#[test]
fn the_recording_passes_rerun_verify_and_has_the_spec_entities() {
    // Keep the whole recording: its folder lives as long as it does.
    let Some(recording) = verified_recording("scenarios/apartment_disk.scen") else {
        return;
    };
    let (rerun, rrd) = (&recording.rerun, &recording.rrd);
    let print = run_with_timeout(
        Command::new(rerun)
            .args(["rrd", "print", "--verbose"])
            .arg(rrd),
        Duration::from_secs(120),
    );
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&print.stdout),
        String::from_utf8_lossy(&print.stderr)
    );
    assert!(print.status.success(), "rerun rrd print failed:\n{text}");
    for entity in [
        "/world/bounds",
        "/world/obstacles/B1",
        "/world/obstacles/B01",
        "/plans/offline/path",
        "/plans/offline/robot",
        "/plans/offline/search",
        "/checks",
    ] {
        assert!(
            text.contains(entity),
            "`rerun rrd print` does not list {entity}:\n{}",
            &text[..text.len().min(4000)]
        );
    }
    // The robot moves on timeline `step`, the search on `expansion`, with
    // the archetypes of SPEC 6.
    let headers = run_with_timeout(
        Command::new(rerun).args(["rrd", "print", "-vv"]).arg(rrd),
        Duration::from_secs(120),
    );
    let headers = String::from_utf8_lossy(&headers.stdout);
    for needle in [
        "index_name: step",
        "index_name: expansion",
        "archetype: LineStrips2D",
        "archetype: Points2D",
        "archetype: TextLog",
    ] {
        assert!(
            headers.contains(needle),
            "`rerun rrd print -vv` lacks {needle}"
        );
    }
}

#[cfg(feature = "viewer")]
#[test]
fn the_recording_of_a_rotating_robot_has_the_c_space_layers() {
    // Keep the whole recording: its folder lives as long as it does.
    let Some(recording) = verified_recording("scenarios/apartment_rod.scen") else {
        return;
    };
    let (rerun, rrd) = (&recording.rerun, &recording.rrd);
    let print = run_with_timeout(
        Command::new(rerun).args(["rrd", "print"]).arg(rrd),
        Duration::from_secs(120),
    );
    let text = String::from_utf8_lossy(&print.stdout);
    // 70 layers for `rod` (as written; `scen run` runs no bench): one entity per layer, and the path in 3D.
    for entity in [
        "/plans/rod/cspace/layer_0 ",
        "/plans/rod/cspace/layer_69 ",
        "/plans/rod/cspace/path ",
        "/plans/rod/cspace/obstacles/B2 ",
        "/plans/rod/robot ",
    ] {
        assert!(
            text.contains(entity),
            "`rerun rrd print` does not list {entity}"
        );
    }
    assert!(
        !text.contains("/plans/rod/cspace/layer_70 "),
        "one entity per layer, no more"
    );
}

#[cfg(feature = "viewer")]
/// The entities `rerun rrd print` lists for a scenario's recording.
fn recorded_entities(scenario: &str) -> Option<String> {
    let recording = verified_recording(scenario)?;
    let print = run_with_timeout(
        Command::new(&recording.rerun)
            .args(["rrd", "print"])
            .arg(&recording.rrd),
        Duration::from_secs(120),
    );
    assert!(print.status.success(), "rerun rrd print failed");
    Some(String::from_utf8_lossy(&print.stdout).into_owned())
}

#[cfg(feature = "viewer")]
fn assert_lists(text: &str, entities: &[&str]) {
    for entity in entities {
        assert!(
            text.contains(&format!("{entity} ")),
            "`rerun rrd print` does not list {entity}"
        );
    }
}

#[cfg(feature = "viewer")]
#[test]
fn the_recording_of_coverage_has_the_tree_the_growing_tour_and_the_driven_robot() {
    let Some(text) = recorded_entities("scenarios/coverage_rooms.scen") else {
        return;
    };
    assert_lists(
        &text,
        &[
            "/plans/cover/mega_cells",
            "/plans/cover/tree",
            "/plans/cover/trail/0000",
            "/plans/cover/drive/path",
            "/plans/cover/drive/robot",
        ],
    );
    let Some(text) = recorded_entities("scenarios/coverage_weights.scen") else {
        return;
    };
    assert_lists(&text, &["/world/weights/W"]);
}

#[cfg(feature = "viewer")]
#[test]
fn the_recording_of_a_potential_field_has_forces_minima_escapes_and_the_stuck_run() {
    let Some(text) = recorded_entities("scenarios/potential_walls.scen") else {
        return;
    };
    assert_lists(
        &text,
        &[
            "/plans/walk/field/attract",
            "/plans/walk/field/repulse",
            "/plans/walk/field/total",
            "/plans/walk/field/minima",
            "/plans/walk/field/escapes",
            "/plans/walk/path",
            // Pure descent stops in the minimum: its motion is drawn, not as a path.
            "/plans/descent/unfinished",
        ],
    );
    assert!(!text.contains("/plans/descent/path "));
}

#[cfg(feature = "viewer")]
#[test]
fn the_recording_of_online_navigation_has_what_the_robot_knew_and_planned() {
    let Some(text) = recorded_entities("scenarios/apartment_online.scen") else {
        return;
    };
    assert_lists(
        &text,
        &[
            "/plans/dstar/known/free/0000",
            "/plans/dstar/plan",
            "/plans/dstar/trail/0000",
            "/plans/dstar/robot",
            "/plans/replan/plan",
            "/plans/backtrack/search",
        ],
    );
    // Walls are found along the way: some batch of sensed cells has blocked ones.
    assert!(text.contains("/plans/dstar/known/blocked/"));
}

#[cfg(feature = "viewer")]
#[test]
fn the_recording_of_a_roadmap_has_the_visibility_edges() {
    let Some(text) = recorded_entities("scenarios/roadmap_segments.scen") else {
        return;
    };
    assert_lists(
        &text,
        &[
            "/plans/cup/roadmap",
            "/plans/cup/path",
            "/plans/boxed/roadmap",
        ],
    );
    // The goal inside the closed chain is not reached: no path is drawn.
    assert!(!text.contains("/plans/boxed/path "));
    let Some(text) = recorded_entities("scenarios/roadmap_robot.scen") else {
        return;
    };
    assert_lists(&text, &["/plans/triangle/grown", "/plans/triangle/roadmap"]);
}

#[cfg(feature = "viewer")]
#[test]
fn the_recording_of_time_moves_the_obstacles_and_the_robot_on_timeline_time() {
    let Some(text) = recorded_entities("scenarios/time_door.scen") else {
        return;
    };
    assert_lists(
        &text,
        &[
            "/world/moving/door",
            "/world/moving/door/route",
            "/plans/through/trajectory/robot",
        ],
    );
    // The door vanishes: its outline is cleared then.
    assert!(
        text.lines()
            .any(|l| l.contains("/world/moving/door ") && l.contains("Clear")),
        "no Clear of the door:\n{text}"
    );
    let Some(recording) = verified_recording("scenarios/time_door.scen") else {
        return;
    };
    let headers = run_with_timeout(
        Command::new(&recording.rerun)
            .args(["rrd", "print", "-vv"])
            .arg(&recording.rrd),
        Duration::from_secs(120),
    );
    assert!(
        String::from_utf8_lossy(&headers.stdout).contains("index_name: time"),
        "no timeline `time`"
    );
}
