//! Motions checked per second by the planners' motion checker
//! (`geometry::motion`) in the SEEDS §A apartment (scenarios/apartment_rod.scen),
//! for the 8 × 1 rod, a disk of radius 0.5 and a point.
//!
//! A fixed seeded sample of 2 000 motions per robot: a start drawn uniformly
//! in the bounds with θ uniform in [0, 2π), kept if it is free (as a
//! planner's tree nodes are); a direction uniform in angle and a length
//! uniform up to 0.2 × the bounds' diagonal (≈ 8.8); for the rod a rotation
//! uniform in [−π, π] too (θ along the shorter arc); redrawn if the end
//! leaves the bounds. The sample is split by the checker's verdict into free
//! and colliding motions, each timed as a whole (one iteration checks every
//! motion of the set once). For scale, the bench also prints what the
//! validator takes for the first 100 free motions of each robot (once,
//! outside criterion).
//!
//! `cargo bench --bench motion`; figures in BENCHMARKS.md.

use std::f64::consts::{PI, TAU};
use std::hint::black_box;
use std::path::Path;
use std::time::{Duration, Instant};

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use scen::geometry::motion::MotionChecker;
use scen::geometry::validator::{DEFAULT_TOLERANCE, Validator};
use scen::geometry::{Config, RobotShape, World};
use scen::rng::SplitMix64;

const MOTIONS: usize = 2000;

/// A straight motion from the first configuration to the second.
type Motion = (Config, Config);

/// The sample of the module documentation, split into (free, colliding).
fn sample(
    world: &World,
    checker: &MotionChecker,
    rotate: bool,
    seed: u64,
) -> (Vec<Motion>, Vec<Motion>) {
    let b = world.bounds;
    let reach = 0.2 * b.width().hypot(b.height());
    let mut rng = SplitMix64::new(seed);
    let (mut free, mut colliding) = (Vec::new(), Vec::new());
    while free.len() + colliding.len() < MOTIONS {
        let a = Config::new(
            rng.range(b.min.x, b.max.x),
            rng.range(b.min.y, b.max.y),
            rng.range(0.0, TAU),
        );
        if !checker.config_free(a) {
            continue;
        }
        let (phi, len) = (rng.range(0.0, TAU), rng.range(0.0, reach));
        let turn = if rotate { rng.range(-PI, PI) } else { 0.0 };
        let end = Config::new(a.x + len * phi.cos(), a.y + len * phi.sin(), a.theta + turn);
        if !b.contains(end.xy()) {
            continue;
        }
        if checker.motion_free(a, end) {
            free.push((a, end));
        } else {
            colliding.push((a, end));
        }
    }
    (free, colliding)
}

fn bench(c: &mut Criterion) {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/apartment_rod.scen");
    let scenario = scen::load(&file).expect("the apartment loads");
    let world = &scenario.world;
    let rod = scenario
        .robots
        .iter()
        .find(|r| matches!(r.shape, RobotShape::Polygon(_)))
        .expect("the apartment has the rod")
        .shape
        .clone();
    let robots = [
        ("rod", rod.clone(), true),
        ("rod_translating", rod, false),
        ("disk", RobotShape::Disk(0.5), false),
        ("point", RobotShape::Point, false),
    ];
    let mut group = c.benchmark_group("motion_apartment");
    group.sample_size(20);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(3));
    for (name, robot, rotate) in &robots {
        let checker = MotionChecker::new(world, robot);
        let (free, colliding) = sample(world, &checker, *rotate, 20261122);
        let validator = Validator::new(world);
        let some = &free[..free.len().min(100)];
        let began = Instant::now();
        let valid = some
            .iter()
            .filter(|(a, b)| {
                validator
                    .validate_path(robot, &[*a, *b], DEFAULT_TOLERANCE)
                    .is_ok()
            })
            .count();
        assert_eq!(valid, some.len(), "the validator accepts every free motion");
        eprintln!(
            "{name}: {} free and {} colliding motions; the validator takes {:.1} µs per free one",
            free.len(),
            colliding.len(),
            began.elapsed().as_secs_f64() * 1e6 / some.len().max(1) as f64
        );
        for (verdict, set) in [("free", &free), ("colliding", &colliding)] {
            group.throughput(Throughput::Elements(set.len() as u64));
            group.bench_function(format!("{name}/{verdict}"), |bench| {
                bench.iter(|| {
                    set.iter()
                        .filter(|(a, b)| checker.motion_free(black_box(*a), black_box(*b)))
                        .count()
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
