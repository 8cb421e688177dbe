//! Spanning Tree Coverage on a 2,000 × 2,000 D-cell grid with 20% of its
//! area blocked (SPEC 3.5; the target: MST and tour under 1 s).
//!
//! Two maps, both 2,000 × 2,000 cells of weight 1..=9, tool = 1 cell:
//! - `cells20`: each cell blocked with probability 0.2. A mega-cell is free
//!   only when its four cells are (0.8⁴ ≈ 41%), below the site-percolation
//!   threshold of the square lattice (≈ 59%): the start's component is
//!   small, and most of the time goes into resampling.
//! - `blocks20`: each mega-cell (2 × 2 cells) blocked with probability
//!   0.2, so 20% of the cells are blocked and ~80% of the 10⁶ mega-cells
//!   form one component: the worst case for Prim and the tour.
//!
//! Benches per map: `resample` (D-cells and mega-cells), `prim` (the
//! minimum spanning tree from the start), `tour` (the circumnavigation),
//! and `plan` (the planner end to end, as `scen run` calls it, without the
//! validator).
//!
//! Run: `cargo bench --bench coverage -- --sample-size 10 --warm-up-time 1 --measurement-time 3`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use scen::contract::Limits;
use scen::contract::Task;
use scen::geometry::{Config, Grid, Obstacle, Point, RobotShape, Shape, World};
use scen::planners::coverage::{Cells, Coverage, EdgeWeights, prim, tour};

const SIDE: usize = 2000;

/// `block` × `block` squares blocked with probability 0.2; the bottom-left
/// square is kept free for the start.
fn map(block: usize, seed: u64) -> Grid {
    let mut rng = scen::rng::SplitMix64::new(seed);
    let mut next = move || rng.next_u64();
    let mut cells: Vec<u8> = (0..SIDE * SIDE).map(|_| (next() % 9) as u8 + 1).collect();
    for by in (0..SIDE).step_by(block) {
        for bx in (0..SIDE).step_by(block) {
            let start = by == SIDE - block && bx == 0;
            if next().is_multiple_of(5) && !start {
                for r in by..by + block {
                    for c in bx..bx + block {
                        cells[r * SIDE + c] = 0;
                    }
                }
            }
        }
    }
    Grid {
        cell: 1.0,
        origin: Point::new(0.0, 0.0),
        width: SIDE,
        height: SIDE,
        cells,
    }
}

fn bench(c: &mut Criterion) {
    for (name, block) in [("cells20", 1), ("blocks20", 2)] {
        let grid = map(block, 7);
        let cells = Cells::new(&grid, 1);
        let tree = prim(&cells, 0, EdgeWeights::Max, None, None);
        let free_megas = cells.mega.iter().filter(|&&w| w > 0).count();
        println!(
            "{name}: {} free of {} mega-cells; tree {} mega-cells, tour {} D-cells",
            free_megas,
            cells.mega.len(),
            tree.order.len(),
            4 * tree.order.len()
        );
        let mut g = c.benchmark_group(name);
        g.bench_function("resample", |b| b.iter(|| black_box(Cells::new(&grid, 1))));
        g.bench_function("prim", |b| {
            b.iter(|| black_box(prim(&cells, 0, EdgeWeights::Max, None, None)))
        });
        g.bench_function("tour", |b| {
            b.iter(|| black_box(tour(&cells, &tree, (0, 0))))
        });
        let world = World {
            bounds: grid.extent(),
            obstacles: vec![Obstacle {
                name: "G".into(),
                shape: Shape::Grid(grid.clone()),
            }],
        };
        let robot = RobotShape::Disk(0.5);
        let task = Task {
            world: &world,
            robot: &robot,
            start: Config::new(0.5, 0.5, 0.0),
            goal: None,
            limits: Limits::default(),
            seed: 0,
            steering: None,
            draw: true,
            referee: None,
            moving: &[],
            speed: None,
            agents: &[],
        };
        let settings = Coverage {
            on: 0,
            k: 1,
            weights: EdgeWeights::Max,
        };
        g.bench_function("plan", |b| {
            b.iter(|| black_box(scen::planners::coverage::plan(&task, &settings)))
        });
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
