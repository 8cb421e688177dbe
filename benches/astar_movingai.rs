//! scen's lattice A* against `pathfinding::directed::astar::astar` on the
//! MovingAI maze512-32-9 benchmark (SPEC 3.1).
//!
//! Both searches run on the same graph: cell centres of the passable cells,
//! 8-connected, straight moves cost 1 and diagonal ones √2, no corner cutting
//! (a diagonal move needs both orthogonally adjacent cells passable), and the
//! same Euclidean heuristic. Costs are `f64` on both sides (pathfinding gets
//! them through [`Cost`], an `f64` ordered by `total_cmp`), so the two must
//! agree on every length within 1e-4; that is asserted once, before timing.
//!
//! Benches (each over the same fixed sample: every [`EVERY`]-th row of the
//! file, 251 rows spread evenly over the buckets; all 8010 rows would take
//! minutes per iteration):
//! - `lattice_build`: the obstacle index and the classified lattice;
//! - `scen_astar/warm`: the queries on one lattice whose edge checks are
//!   cached from earlier queries (as in a long-lived lattice);
//! - `scen_astar/cold`: the queries on a freshly built lattice each time
//!   (the build itself untimed, the lazy edge checks timed);
//! - `pathfinding_astar`: the same queries with pathfinding 4.
//!
//! Throughput is reported in queries/s; the expansions per sample are
//! printed once, so that expansions/s = expansions × (queries/s) / queries.
//!
//! Run: `cargo bench --bench astar_movingai`.

use std::cell::Cell;
use std::cmp::Ordering;
use std::hint::black_box;
use std::ops::Add;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use criterion::{BatchSize, Criterion, SamplingMode, Throughput, criterion_group, criterion_main};
use pathfinding::num_traits::Zero;
use scen::contract::Limits;
use scen::geometry::collide::ObstacleIndex;
use scen::geometry::{Shape, World};
use scen::planners::grid_lattice::{
    CostMetric, GridLattice, Heuristic, SearchBuffers, SearchConfig, search,
};
use scen::planners::lattice::{LatticeSpec, Sample};

/// Every `EVERY`-th scenario row is in the sample.
const EVERY: usize = 32;

const MAP: &str = "maze512-32-9.map";
const SCEN: &str = "maze512-32-9.map.scen";

/// A path cost for pathfinding: an `f64` with a total order.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Cost(f64);

impl Eq for Cost {}

impl PartialOrd for Cost {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Cost {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}

impl Add for Cost {
    type Output = Cost;
    fn add(self, other: Cost) -> Cost {
        Cost(self.0 + other.0)
    }
}

impl Zero for Cost {
    fn zero() -> Cost {
        Cost(0.0)
    }
    fn is_zero(&self) -> bool {
        self.0 == 0.0
    }
}

/// A MovingAI query: cells as (x, y) = (column, row), row 0 on top.
#[derive(Clone, Copy, Debug)]
struct Query {
    start: (usize, usize),
    goal: (usize, usize),
    optimal: f64,
}

/// The map imported by scen, its passable cells, and the sampled queries.
struct Bench {
    world: World,
    width: usize,
    height: usize,
    /// Row-major, row 0 on top: whether the cell is passable.
    passable: Vec<bool>,
    queries: Vec<Query>,
}

fn data_dir() -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../shared/data/movingai"
    ))
}

/// Loads the map through scen (a world-only scenario in a temporary folder)
/// and every [`EVERY`]-th row of the scenario file.
fn load_bench() -> Bench {
    let dir = data_dir();
    let map = dir.join(MAP);
    assert!(
        map.is_file(),
        "the MovingAI data is missing: {}",
        map.display()
    );
    let text = std::fs::read_to_string(&map).expect("a readable map");
    let header = |key: &str| -> usize {
        text.lines()
            .find_map(|l| l.strip_prefix(key))
            .and_then(|v| v.trim().parse().ok())
            .expect("a map header")
    };
    let (width, height) = (header("width "), header("height "));
    let tmp = std::env::temp_dir().join(format!("scen-bench-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).expect("a temporary folder");
    let file = tmp.join("world.scen");
    // The map beside the scenario (a scenario reads only files inside its
    // folder, SPEC 2.2), and a plan that starts on its goal at the first
    // passable cell (a file without a plan is an error).
    std::fs::copy(&map, tmp.join("world.map")).expect("copying the map");
    let rows: Vec<&str> = text
        .lines()
        .skip_while(|l| l.trim() != "map")
        .skip(1)
        .collect();
    let (x, y) = rows
        .iter()
        .enumerate()
        .find_map(|(r, row)| {
            row.chars()
                .position(|c| c == '.')
                .map(|c| (c as f64 + 0.5, (rows.len() - 1 - r) as f64 + 0.5))
        })
        .expect("a passable cell");
    let scenario = format!(
        "world {{\n  bounds (0, 0) ({width}, {height})\n  grid G \"world.map\" cell 1 origin (0, 0)\n}}\nrobot dot point\nplan here astar dot {{ start ({x}, {y}) goal ({x}, {y}) }}\n"
    );
    std::fs::write(&file, scenario).expect("writing the scenario");
    let loaded = scen::load(&file);
    let _ = std::fs::remove_dir_all(&tmp);
    let world = match loaded {
        Ok(s) => s.world,
        Err(f) => panic!("{}", scen::diagnostics::render_diags(&f.diags, &f.sources)),
    };
    let passable = match &world.obstacles[0].shape {
        Shape::Grid(g) => g.cells.iter().map(|&w| w != 0).collect(),
        _ => panic!("the obstacle is not a grid"),
    };
    let queries = read_queries(&dir.join(SCEN))
        .into_iter()
        .step_by(EVERY)
        .collect();
    Bench {
        world,
        width,
        height,
        passable,
        queries,
    }
}

fn read_queries(path: &Path) -> Vec<Query> {
    let text = std::fs::read_to_string(path).expect("a readable .scen file");
    text.lines()
        .skip(1) // `version 1`
        .filter(|l| !l.trim().is_empty())
        .map(|line| {
            let f: Vec<&str> = line.split('\t').collect();
            let int = |s: &str| s.trim().parse::<usize>().expect("an integer field");
            Query {
                start: (int(f[4]), int(f[5])),
                goal: (int(f[6]), int(f[7])),
                optimal: f[8].trim().parse().expect("an optimal length"),
            }
        })
        .collect()
}

/// scen's side: the lattice of cell centres and the search settings.
struct Scen {
    spec: LatticeSpec,
    index: ObstacleIndex,
    cfg: SearchConfig,
}

impl Scen {
    fn new(world: &World) -> Scen {
        Scen {
            spec: LatticeSpec::new(world, 1.0, Sample::Center, 1.0),
            index: ObstacleIndex::new(world),
            cfg: SearchConfig {
                connect: 8,
                cost: CostMetric::Euclid,
                weight: 1.0,
                heuristic: Heuristic::Metric,
                limits: Limits::default(),
            },
        }
    }

    fn lattice(&self) -> GridLattice {
        GridLattice::build(self.spec, &self.index, 0.0)
    }

    /// MovingAI cell (x, y) → lattice point (x, H − 1 − y).
    fn node(&self, (x, y): (usize, usize)) -> usize {
        self.spec.index(x, self.spec.ny - 1 - y)
    }

    /// Runs the queries; returns (sum of costs, expansions).
    fn run(
        &self,
        lattice: &mut GridLattice,
        buffers: &mut SearchBuffers,
        queries: &[Query],
    ) -> (f64, u64) {
        let (mut total, mut expanded) = (0.0, 0);
        for q in queries {
            let r = search(
                lattice,
                &self.index,
                self.node(q.start),
                self.node(q.goal),
                &self.cfg,
                false,
                buffers,
            );
            total += r.cost;
            expanded += r.expanded;
        }
        (total, expanded)
    }
}

/// The 8 moves, axis moves first (scen's order).
const MOVES: [(i64, i64); 8] = [
    (1, 0),
    (0, 1),
    (-1, 0),
    (0, -1),
    (1, 1),
    (-1, 1),
    (-1, -1),
    (1, -1),
];

/// One query with pathfinding's A*: the cost, and how many nodes it
/// expanded (calls of the successor function).
fn pathfinding_query(b: &Bench, q: &Query) -> (Option<f64>, u64) {
    let (w, h) = (b.width as i64, b.height as i64);
    let passable =
        |x: i64, y: i64| x >= 0 && y >= 0 && x < w && y < h && b.passable[(y * w + x) as usize];
    let expanded = Cell::new(0u64);
    let goal = (q.goal.0 as i64, q.goal.1 as i64);
    let result = pathfinding::directed::astar::astar(
        &(q.start.0 as i64, q.start.1 as i64),
        |&(x, y)| {
            expanded.set(expanded.get() + 1);
            // A `Vec`, as in pathfinding's examples: measured ~15% faster
            // here than a fixed `[Option<_>; 8]` flattened.
            let mut next = Vec::with_capacity(8);
            for (dx, dy) in MOVES {
                let (nx, ny) = (x + dx, y + dy);
                let diagonal = dx != 0 && dy != 0;
                // No corner cutting.
                if passable(nx, ny) && (!diagonal || (passable(x + dx, y) && passable(x, y + dy))) {
                    let cost = if diagonal {
                        std::f64::consts::SQRT_2
                    } else {
                        1.0
                    };
                    next.push(((nx, ny), Cost(cost)));
                }
            }
            next
        },
        |&(x, y)| Cost(((goal.0 - x) as f64).hypot((goal.1 - y) as f64)),
        |&p| p == goal,
    );
    (result.map(|(_, c)| c.0), expanded.get())
}

/// Expansions and wall time of one pass over the sample.
#[derive(Default)]
struct Pass {
    expanded: u64,
    time: Duration,
}

/// Both searches agree with each other and with MovingAI on every query.
/// Returns one untimed-by-criterion pass of each (scen on a fresh lattice).
fn assert_agreement(b: &Bench, scen: &Scen) -> (Pass, Pass) {
    let mut lattice = scen.lattice();
    let mut buffers = SearchBuffers::default();
    let (mut ours, mut theirs) = (Pass::default(), Pass::default());
    for (k, q) in b.queries.iter().enumerate() {
        let t = Instant::now();
        let r = search(
            &mut lattice,
            &scen.index,
            scen.node(q.start),
            scen.node(q.goal),
            &scen.cfg,
            false,
            &mut buffers,
        );
        ours.time += t.elapsed();
        ours.expanded += r.expanded;
        let t = Instant::now();
        let (pf, pf_expanded) = pathfinding_query(b, q);
        theirs.time += t.elapsed();
        theirs.expanded += pf_expanded;
        assert!(r.nodes.is_some(), "sample {k}: scen found no path");
        let pf = pf.unwrap_or_else(|| panic!("sample {k}: pathfinding found no path"));
        assert!(
            (r.cost - pf).abs() <= 1e-4 && (r.cost - q.optimal).abs() <= 1e-4,
            "sample {k}: scen {}, pathfinding {pf}, MovingAI {}",
            r.cost,
            q.optimal
        );
    }
    (ours, theirs)
}

fn benches(c: &mut Criterion) {
    let b = load_bench();
    let scen = Scen::new(&b.world);
    let n = b.queries.len();
    let (ours, theirs) = assert_agreement(&b, &scen);
    let free = b.passable.iter().filter(|p| **p).count();
    eprintln!(
        "{MAP}: {}×{} cells, {free} passable; {n} queries agree (scen, pathfinding, MovingAI) within 1e-4",
        b.width, b.height
    );
    for (name, pass) in [("scen (fresh lattice)", &ours), ("pathfinding", &theirs)] {
        eprintln!(
            "one pass, {name}: {} expansions in {:.2?} = {:.0} queries/s, {:.3e} expansions/s",
            pass.expanded,
            pass.time,
            n as f64 / pass.time.as_secs_f64(),
            pass.expanded as f64 / pass.time.as_secs_f64()
        );
    }

    let mut build = c.benchmark_group("maze512_build");
    build.bench_function("lattice_build", |bench| {
        bench.iter(|| {
            let index = ObstacleIndex::new(&b.world);
            black_box(GridLattice::build(scen.spec, &index, 0.0).free.len())
        })
    });
    build.finish();

    // Seconds per iteration: the same number of iterations in every sample.
    let mut group = c.benchmark_group("maze512_queries");
    group.sampling_mode(SamplingMode::Flat);
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(60));
    group.throughput(Throughput::Elements(n as u64));
    let mut warm = scen.lattice();
    let mut buffers = SearchBuffers::default();
    scen.run(&mut warm, &mut buffers, &b.queries);
    group.bench_function("scen_astar/warm", |bench| {
        bench.iter(|| black_box(scen.run(&mut warm, &mut buffers, &b.queries)))
    });
    group.bench_function("scen_astar/cold", |bench| {
        bench.iter_batched(
            || scen.lattice(),
            |mut lattice| black_box(scen.run(&mut lattice, &mut buffers, &b.queries)),
            BatchSize::LargeInput,
        )
    });
    group.bench_function("pathfinding_astar", |bench| {
        bench.iter(|| {
            let mut total = 0.0;
            for q in &b.queries {
                total += pathfinding_query(&b, q).0.unwrap_or(0.0);
            }
            black_box(total)
        })
    });
    group.finish();
}

criterion_group!(astar_movingai, benches);
criterion_main!(astar_movingai);
