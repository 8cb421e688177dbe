//! Agreement with the MovingAI grid benchmarks (SPEC 3.1): a point robot on
//! an imported map (lattice at cell centres, 8-connected, Euclidean cost, no
//! corner cutting) finds every scenario's optimal length within 1e-4.
//!
//! The data lives in `../shared/data/movingai/` (see its SOURCES.md). Without
//! it the tests say what is missing and pass, except on CI (`CI=true`),
//! where a missing benchmark is a failure.
//!
//! Two routes: the library (one lattice per map, every query on it, a subset
//! of the paths re-checked by the validator) and the CLI (`scen run` on a
//! generated scenario with `expect p.cost ~ OPT +- 0.0001`).

mod common;

use common::TempDir;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use scen::contract::Limits;
use scen::geometry::collide::ObstacleIndex;
use scen::geometry::validator::{DEFAULT_TOLERANCE, validate_path};
use scen::geometry::{Config, Grid, RobotShape, Shape, World};
use scen::planners::grid_lattice::{
    CostMetric, GridLattice, Heuristic, SearchBuffers, SearchConfig, search,
};
use scen::planners::lattice::{LatticeSpec, Sample};

/// Optimal lengths are given to 5 or 8 decimals.
const TOLERANCE: f64 = 1e-4;

const FILES: [&str; 6] = [
    "arena.map",
    "arena.map.scen",
    "random-32-32-10.map",
    "random-32-32-10-random-1.scen",
    "maze512-32-9.map",
    "maze512-32-9.map.scen",
];

/// The benchmark folder, or `None` (after saying why) when it is missing
/// outside CI.
fn data_dir() -> Option<PathBuf> {
    common::shared_data("movingai", &FILES)
}

/// One row of a MovingAI `.scen` file. (x, y) = (column, row), row 0 on top.
#[derive(Clone, Copy, Debug)]
struct Query {
    /// 0-based row in the file (after `version 1`), for messages.
    row: usize,
    bucket: u32,
    start: (usize, usize),
    goal: (usize, usize),
    optimal: f64,
}

/// The rows of `scen_file` that refer to `map_file` of size `width × height`.
fn read_queries(scen_file: &Path, map_file: &str, width: usize, height: usize) -> Vec<Query> {
    let text = std::fs::read_to_string(scen_file).expect("a readable .scen file");
    let mut lines = text.lines();
    assert_eq!(
        lines.next().map(str::trim),
        Some("version 1"),
        "{}",
        scen_file.display()
    );
    let mut queries = Vec::new();
    for (row, line) in lines.filter(|l| !l.trim().is_empty()).enumerate() {
        let f: Vec<&str> = line.split('\t').collect();
        assert_eq!(
            f.len(),
            9,
            "{}: row {row} has {} fields",
            scen_file.display(),
            f.len()
        );
        let int = |s: &str| s.trim().parse::<usize>().expect("an integer field");
        // Map names may carry a folder (`maps/dao/arena.map`).
        assert_eq!(
            Path::new(f[1]).file_name().and_then(|n| n.to_str()),
            Some(map_file)
        );
        assert_eq!(
            (int(f[2]), int(f[3])),
            (width, height),
            "row {row}: map size"
        );
        queries.push(Query {
            row,
            bucket: f[0].parse().expect("a bucket number"),
            start: (int(f[4]), int(f[5])),
            goal: (int(f[6]), int(f[7])),
            optimal: f[8].trim().parse().expect("an optimal length"),
        });
    }
    queries
}

/// `grid G "MAP" cell 1 origin (0, 0)`, with the map copied beside the
/// scenario in `tmp` (a scenario reads only files inside its folder, its
/// root: SPEC 2.2).
fn grid_line(map: &Path, tmp: &TempDir) -> String {
    let name = map.file_name().expect("a map file name");
    let copy = tmp.path().join(name);
    if !copy.is_file() {
        std::fs::copy(map, &copy).expect("copying the map beside the scenario");
    }
    format!("grid G \"{}\" cell 1 origin (0, 0)", name.to_string_lossy())
}

/// The centre of the first passable cell of a map (row 0 on top), in world
/// coordinates: a start for a plan that only makes the world loadable.
fn first_free_cell(map: &Path) -> (f64, f64) {
    let text = std::fs::read_to_string(map).expect("a readable map");
    let rows: Vec<&str> = text
        .lines()
        .skip_while(|l| l.trim() != "map")
        .skip(1)
        .collect();
    let h = rows.len();
    for (r, row) in rows.iter().enumerate() {
        if let Some(c) = row.chars().position(|ch| matches!(ch, '.' | 'G' | 'S')) {
            return (c as f64 + 0.5, (h - 1 - r) as f64 + 0.5);
        }
    }
    panic!("{}: no passable cell", map.display())
}

/// `(width, height)` from a map's header, for the scenario's bounds.
fn map_size(map: &Path) -> (usize, usize) {
    let text = std::fs::read_to_string(map).expect("a readable map");
    let header = |key: &str| -> usize {
        text.lines()
            .find_map(|l| l.strip_prefix(key))
            .and_then(|v| v.trim().parse().ok())
            .unwrap_or_else(|| panic!("{}: no `{key}` line", map.display()))
    };
    (header("width "), header("height "))
}

/// The map as scen imports it: a world-only scenario loaded with the library.
fn load_world(map: &Path, tmp: &TempDir) -> (World, Grid) {
    let file = tmp.path().join("world.scen");
    let (w, h) = map_size(map);
    let (x, y) = first_free_cell(map);
    // A plan makes the file a scenario (SPEC §4); it starts on its goal.
    let scenario = format!(
        "world {{\n  bounds (0, 0) ({w}, {h})\n  {}\n}}\nrobot dot point\nplan here astar dot {{ start ({x}, {y}) goal ({x}, {y}) }}\n",
        grid_line(map, tmp)
    );
    std::fs::write(&file, scenario).expect("writing the scenario");
    let s = match scen::load(&file) {
        Ok(s) => s,
        Err(f) => panic!(
            "the map does not load:\n{}",
            scen::diagnostics::render_diags(&f.diags, &f.sources)
        ),
    };
    let world = s.world;
    let [obstacle] = world.obstacles.as_slice() else {
        panic!("expected one obstacle, got {}", world.obstacles.len());
    };
    let Shape::Grid(grid) = &obstacle.shape else {
        panic!("the obstacle is not a grid");
    };
    assert_eq!((grid.width, grid.height, grid.cell), (w, h, 1.0));
    let grid = grid.clone();
    (world, grid)
}

/// Lattice point (i, j) of a MovingAI cell (x, y): i = x, j = H − 1 − y.
fn lattice_node(spec: &LatticeSpec, height: usize, (x, y): (usize, usize)) -> usize {
    spec.index(x, height - 1 - y)
}

/// Runs every `every`-th query of `scen_file` on `map_file` on one lattice
/// and checks the lengths; every path also goes through the validator (it
/// is cheap next to the searches). Returns how many queries ran.
fn check_agreement(dir: &Path, map_file: &str, scen_file: &str, every: usize) -> usize {
    let tmp = TempDir::new(&format!("movingai-{map_file}"));
    let (world, grid) = load_world(&dir.join(map_file), &tmp);
    let queries = read_queries(&dir.join(scen_file), map_file, grid.width, grid.height);
    let started = Instant::now();
    let index = ObstacleIndex::new(&world);
    let spec = LatticeSpec::new(&world, 1.0, Sample::Center, 1.0);
    assert_eq!((spec.nx, spec.ny), (grid.width, grid.height));
    let mut lattice = GridLattice::build(spec, &index, 0.0);
    // A cell centre is free exactly when the cell is passable.
    for (k, &weight) in grid.cells.iter().enumerate() {
        let (x, y) = (k % grid.width, k / grid.width);
        assert_eq!(
            lattice.free.get(lattice_node(&spec, grid.height, (x, y))),
            weight != 0,
            "cell ({x}, {y})"
        );
    }
    let built = started.elapsed();
    let cfg = SearchConfig {
        connect: 8,
        cost: CostMetric::Euclid,
        weight: 1.0,
        heuristic: Heuristic::Lattice,
        limits: Limits::default(),
    };
    let mut buffers = SearchBuffers::default();
    let mut failures = Vec::new();
    let (mut searching, mut validating) = (Duration::ZERO, Duration::ZERO);
    let (mut ran, mut expanded) = (0, 0);
    for q in queries.iter().step_by(every) {
        ran += 1;
        let start = lattice_node(&spec, grid.height, q.start);
        let goal = lattice_node(&spec, grid.height, q.goal);
        let t = Instant::now();
        let r = search(&mut lattice, &index, start, goal, &cfg, false, &mut buffers);
        searching += t.elapsed();
        expanded += r.expanded;
        let Some(nodes) = r.nodes else {
            failures.push(format!(
                "row {} (bucket {}): no path, optimal {}",
                q.row, q.bucket, q.optimal
            ));
            continue;
        };
        if (r.cost - q.optimal).abs() > TOLERANCE {
            failures.push(format!(
                "row {} (bucket {}): {:?} → {:?}: cost {}, optimal {}",
                q.row, q.bucket, q.start, q.goal, r.cost, q.optimal
            ));
        }
        let path: Vec<Config> = nodes
            .iter()
            .map(|&n| {
                let (i, j) = spec.coords(n);
                let p = spec.point(i, j);
                Config::new(p.x, p.y, 0.0)
            })
            .collect();
        // The reported cost is the length of the returned moves, each one
        // step to a lattice neighbour.
        let steps_ok = nodes.first() == Some(&start)
            && nodes.last() == Some(&goal)
            && path.windows(2).all(|w| {
                let (dx, dy) = ((w[1].x - w[0].x).abs(), (w[1].y - w[0].y).abs());
                dx <= 1.0 && dy <= 1.0 && dx + dy > 0.0
            });
        let length: f64 = path
            .windows(2)
            .map(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y))
            .sum();
        if !steps_ok || (length - r.cost).abs() > 1e-9 {
            failures.push(format!(
                "row {}: the path is not a chain of lattice moves of length {}",
                q.row, r.cost
            ));
        }
        let t = Instant::now();
        if let Err(e) = validate_path(&world, &RobotShape::Point, &path, DEFAULT_TOLERANCE) {
            failures.push(format!(
                "row {}: the validator rejects the path: {e:?}",
                q.row
            ));
        }
        validating += t.elapsed();
    }
    let elapsed = started.elapsed();
    eprintln!(
        "{map_file}: {ran} of {} queries, {expanded} expansions; lattice built in {built:.2?}, \
         searches {searching:.2?}, validation {validating:.2?}, all in {elapsed:.2?}",
        queries.len()
    );
    assert!(
        failures.is_empty(),
        "{map_file}: {} of {ran} queries disagree:\n{}",
        failures.len(),
        failures.join("\n")
    );
    ran
}

#[test]
fn arena_every_row_is_optimal() {
    let Some(dir) = data_dir() else { return };
    check_agreement(&dir, "arena.map", "arena.map.scen", 1);
}

#[test]
fn random_32_32_10_every_row_is_optimal() {
    let Some(dir) = data_dir() else { return };
    check_agreement(
        &dir,
        "random-32-32-10.map",
        "random-32-32-10-random-1.scen",
        1,
    );
}

/// Every 16th row: 501 rows spread evenly over the buckets, about 13 s in
/// release. All 8010 rows agree too, but take over five minutes (most of
/// the long maze queries expand the whole maze).
#[test]
fn maze512_rows_are_optimal() {
    let Some(dir) = data_dir() else { return };
    let ran = check_agreement(&dir, "maze512-32-9.map", "maze512-32-9.map.scen", 16);
    assert!(ran >= 500, "only {ran} maze512 rows ran");
}

/// `scen run` on a generated scenario per query: the CLI imports the map,
/// plans and checks `p.cost ~ OPT +- 0.0001` itself.
#[test]
fn cli_finds_optimal_lengths() {
    let Some(dir) = data_dir() else { return };
    let tmp = TempDir::new("movingai-cli");
    let picks: [(&str, &str, &[usize]); 3] = [
        ("arena.map", "arena.map.scen", &[0, 57, 159]),
        (
            "random-32-32-10.map",
            "random-32-32-10-random-1.scen",
            &[3, 200, 460],
        ),
        (
            "maze512-32-9.map",
            "maze512-32-9.map.scen",
            &[5, 4000, 7999],
        ),
    ];
    let mut failures = Vec::new();
    for (map_file, scen_file, rows) in picks {
        let map = dir.join(map_file);
        let (w, h) = map_size(&map);
        let queries = read_queries(&dir.join(scen_file), map_file, w, h);
        for &row in rows {
            let q = queries[row];
            // Cell (x, y) has its centre at (x + ½, H − 1 − y + ½).
            let pose = |(x, y): (usize, usize)| {
                format!("({}, {})", x as f64 + 0.5, (h - 1 - y) as f64 + 0.5)
            };
            let scenario = format!(
                "scenario \"MovingAI {map_file} row {row}\"\n\
                 world {{\n  bounds (0, 0) ({w}, {h})\n  {}\n}}\n\
                 robot dot point\n\
                 plan p astar dot {{\n  start {}\n  goal {}\n  cell 1 sample center connect 8 cost euclid\n}}\n\
                 expect p.found and p.collision_free and p.reaches_goal\n\
                 expect p.cost ~ {} +- 0.0001\n\
                 expect p.length ~ {} +- 0.0001\n",
                grid_line(&map, &tmp),
                pose(q.start),
                pose(q.goal),
                q.optimal,
                q.optimal,
            );
            let file = tmp.path().join(format!("{map_file}-{row}.scen"));
            std::fs::write(&file, scenario).expect("writing the scenario");
            let out = Command::new(env!("CARGO_BIN_EXE_scen"))
                .args(["run", "-q"])
                .arg(&file)
                .output()
                .expect("the scen binary runs");
            if out.status.code() != Some(0) {
                failures.push(format!(
                    "{map_file} row {row}: `scen run` exited with {:?}\nstdout:\n{}\nstderr:\n{}",
                    out.status.code(),
                    String::from_utf8_lossy(&out.stdout),
                    String::from_utf8_lossy(&out.stderr)
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
