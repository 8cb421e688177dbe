//! Cars in the pictures and the viewer (issue 23): a car's tree edges,
//! hybrid A*'s search and the raw path are drawn along the steering
//! curves, not as chords; the recording has the body on timeline `step`.

mod common;

use std::path::PathBuf;

use scen::contract::layers::Drawing;
use scen::geometry::Point;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The largest distance of a polyline's points from the chord between its
/// ends.
fn bulge(line: &[Point]) -> f64 {
    let (a, b) = (line[0], line[line.len() - 1]);
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let n = dx.hypot(dy);
    line.iter()
        .map(|p| {
            if n == 0.0 {
                (p.x - a.x).hypot(p.y - a.y)
            } else {
                ((p.x - a.x) * dy - (p.y - a.y) * dx).abs() / n
            }
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_cars_trees_and_search_are_drawn_along_its_curves() {
    let scenario = scen::load(&repo().join("scenarios/car_sampling.scen"))
        .unwrap_or_else(|_| panic!("car_sampling.scen loads"));
    let report = scen::run_scenario_drawing(scenario, &[], true);
    // Hybrid A*'s arcs are one step (√2 · 0.5) of radius 4.5: a sagitta of
    // 0.5 / 36 ≈ 0.014; the sampling planners' edges are whole curves.
    for (plan, prefix, least) in [
        ("connect", "tree/", 0.1),
        ("roadmap", "graph/", 0.1),
        ("hybrid", "search", 0.0135),
    ] {
        let run = report
            .plans
            .iter()
            .find(|r| report.scenario.plans[r.plan].name == plan)
            .expect("the plan ran");
        let lines: Vec<&Vec<Point>> = run
            .outcome
            .layers
            .iter()
            .filter(|l| l.entity.starts_with(prefix))
            .flat_map(|l| match &l.drawing {
                Drawing::Polylines(lines) => lines.iter().collect::<Vec<_>>(),
                other => panic!("{plan}: {} is drawn as {other:?}", l.entity),
            })
            .collect();
        assert!(!lines.is_empty(), "{plan}: no {prefix} layer");
        // Some edge visibly bends (a chord would have no bulge at all).
        let most = lines.iter().map(|l| bulge(l)).fold(0.0, f64::max);
        assert!(
            most > least,
            "{plan}: the largest bulge of an edge is {most}"
        );
    }
}

#[cfg(feature = "viewer")]
#[test]
fn the_recording_of_cars_has_curved_trees_the_search_and_the_body() {
    let Some(text) = common::recording_printout("scenarios/car_sampling.scen") else {
        return;
    };
    for entity in [
        "/plans/hybrid/search",
        "/plans/hybrid/robot",
        "/plans/connect/tree/0000",
        "/plans/connect/raw_path",
        "/plans/star/robot",
        "/plans/roadmap/graph/0000",
    ] {
        assert!(
            text.contains(&format!("{entity} ")),
            "`rerun rrd print` does not list {entity}"
        );
    }
}
