//! The steering functions against OMPL's (issue 23): the shortest Dubins
//! and Reeds–Shepp lengths of `scen::geometry::steer` equal
//! `ompl.base.DubinsStateSpace` / `ReedsSheppStateSpace`'s `distance`
//! (pip `ompl` 2.0.1) to 1e-9 relative, on 100,000 random pairs each.
//!
//! The pairs are drawn here (a fixed seed), written to a file, and OMPL's
//! lengths computed by the Python interpreter of the virtual environment
//! that holds `ompl` (`target/rerun-venv`, installed by scripts/test.sh; or
//! `SCEN_OMPL_PYTHON`). CI must have it; elsewhere the test skips with a
//! message when it is missing.

use std::f64::consts::PI;
use std::io::Write;
use std::path::PathBuf;
use std::process::Command;

use scen::geometry::Config;
use scen::geometry::steer::{Model, Steering};
use scen::rng::SplitMix64;

const PAIRS: usize = 100_000;

fn python() -> Option<PathBuf> {
    let py = std::env::var_os("SCEN_OMPL_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/rerun-venv/bin/python")
        });
    let has_ompl = py.exists()
        && Command::new(&py)
            .args(["-c", "import ompl.base"])
            .output()
            .is_ok_and(|o| o.status.success());
    if has_ompl {
        return Some(py);
    }
    assert_ne!(
        std::env::var("CI").as_deref(),
        Ok("true"),
        "CI must have OMPL's Python package in {} (pip install ompl==2.0.1)",
        py.display()
    );
    eprintln!(
        "skipped: {} with OMPL's Python package is missing (pip install ompl==2.0.1)",
        py.display()
    );
    None
}

/// Pairs at every scale: near (within a radius, where the words are
/// hardest), medium and far, with radii from 0.1 to 10.
fn pairs(seed: u64) -> Vec<(f64, Config, Config)> {
    let mut rng = SplitMix64::new(seed);
    (0..PAIRS)
        .map(|i| {
            let radius = [0.1, 1.0, 4.5, 10.0][i % 4];
            let reach = [0.5, 3.0, 30.0][(i / 4) % 3] * radius;
            let mut c = || {
                Config::new(
                    rng.range(-reach, reach),
                    rng.range(-reach, reach),
                    rng.range(-PI, PI),
                )
            };
            let a = c();
            let b = c();
            (radius, a, b)
        })
        .collect()
}

const SCRIPT: &str = r#"
import sys
from ompl import base as ob
spaces = {}
out = []
for line in open(sys.argv[1]):
    kind, r, ax, ay, at, bx, by, bt = line.split()
    key = (kind, r)
    if key not in spaces:
        cls = ob.DubinsStateSpace if kind == "d" else ob.ReedsSheppStateSpace
        sp = cls(float(r))
        spaces[key] = (sp, sp.allocState(), sp.allocState())
    sp, a, b = spaces[key]
    a.setX(float(ax)); a.setY(float(ay)); a.setYaw(float(at))
    b.setX(float(bx)); b.setY(float(by)); b.setYaw(float(bt))
    out.append(repr(sp.distance(a, b)))
open(sys.argv[2], "w").write("\n".join(out) + "\n")
"#;

fn compare(model: Model, letter: &str, seed: u64) {
    let Some(py) = python() else { return };
    let dir = std::env::temp_dir().join(format!("scen-steer-ompl-{}-{letter}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("pairs.txt");
    let output = dir.join("ompl.txt");
    let pairs = pairs(seed);
    let mut f = std::io::BufWriter::new(std::fs::File::create(&input).unwrap());
    for (r, a, b) in &pairs {
        // `{:?}` prints the shortest string that reads back exactly.
        writeln!(
            f,
            "{letter} {r:?} {:?} {:?} {:?} {:?} {:?} {:?}",
            a.x, a.y, a.theta, b.x, b.y, b.theta
        )
        .unwrap();
    }
    f.into_inner().unwrap().sync_all().unwrap();
    let run = Command::new(&py)
        .args(["-c", SCRIPT])
        .arg(&input)
        .arg(&output)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "OMPL's script failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    let theirs: Vec<f64> = std::fs::read_to_string(&output)
        .unwrap()
        .lines()
        .map(|l| l.parse().unwrap())
        .collect();
    assert_eq!(theirs.len(), pairs.len());
    let mut worst = 0.0f64;
    let mut failures = Vec::new();
    for ((r, a, b), &t) in pairs.iter().zip(&theirs) {
        let ours = Steering::new(model, *r).distance(*a, *b);
        let rel = (ours - t).abs() / t.abs().max(*r);
        worst = worst.max(rel);
        if rel > 1e-9 && failures.len() < 10 {
            failures.push(format!("ρ {r} from {a:?} to {b:?}: scen {ours}, OMPL {t}"));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    eprintln!(
        "{model:?}: {} pairs, worst relative difference {worst:e}",
        pairs.len()
    );
    assert!(
        failures.is_empty(),
        "lengths differ from OMPL's by more than 1e-9 relative:\n{}",
        failures.join("\n")
    );
}

#[test]
fn reeds_shepp_lengths_equal_ompls() {
    compare(Model::ReedsShepp, "rs", 23);
}

#[test]
fn dubins_lengths_equal_ompls() {
    compare(Model::Dubins, "d", 24);
}

/// The OMPL peer of the parking comparison (scripts/ompl_car.py,
/// BENCHMARKS.md) poses the problem of benches/car_parking_ompl.scen —
/// the same bounds, obstacles, body, radius, start and goal — and its
/// RRT-Connect solves it.
#[test]
fn the_ompl_peer_of_the_parking_comparison_poses_the_same_problem() {
    let Some(py) = python() else { return };
    let repo = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let script = repo.join("scripts/ompl_car.py");
    let out = Command::new(&py)
        .arg(&script)
        .arg("--world")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let theirs: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let scenario = scen::load(&repo.join("benches/car_parking_ompl.scen")).expect("loads");
    let b = scenario.world.bounds;
    assert_eq!(
        theirs["bounds"],
        serde_json::json!([b.min.x, b.min.y, b.max.x, b.max.y])
    );
    let rects: Vec<serde_json::Value> = scenario
        .world
        .obstacles
        .iter()
        .map(|o| match &o.shape {
            scen::geometry::Shape::Rect(r) => {
                serde_json::json!([r.min.x, r.min.y, r.max.x, r.max.y])
            }
            other => panic!("the peer knows rectangles only: {other:?}"),
        })
        .collect();
    assert_eq!(theirs["obstacles"], serde_json::Value::Array(rects));
    let robot = &scenario.robots[0];
    let scen::geometry::RobotShape::Polygon(body) = &robot.shape else {
        panic!("a polygon car")
    };
    let vertices: Vec<serde_json::Value> = body
        .vertices
        .iter()
        .map(|v| serde_json::json!([v.x, v.y]))
        .collect();
    assert_eq!(theirs["body"], serde_json::Value::Array(vertices));
    let steering = robot.steering.expect("a car");
    assert_eq!(steering.model, Model::ReedsShepp);
    assert_eq!(theirs["radius"], serde_json::json!(steering.radius));
    for plan in &scenario.plans {
        let (s, g) = (plan.params.start, plan.params.goal.expect("a goal"));
        assert_eq!(theirs["start"], serde_json::json!([s.x, s.y, s.theta]));
        assert_eq!(theirs["goal"], serde_json::json!([g.x, g.y, g.theta]));
    }
    // And it solves it.
    let out = Command::new(&py)
        .arg(&script)
        .args(["rrt_connect", "1", "60"])
        .output()
        .unwrap();
    let line = String::from_utf8_lossy(&out.stdout);
    let fields: Vec<&str> = line.split_whitespace().collect();
    assert_eq!(fields.get(2), Some(&"1"), "not solved: {line}");
    let length: f64 = fields[4].parse().unwrap();
    assert!(length >= 10.7, "{line}");
}
