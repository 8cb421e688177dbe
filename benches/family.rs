//! Drawing one sample of a family and analysing it (issue 24's target:
//! under 1 ms for a 100-obstacle family): `Scenario::sample(k)` checks the
//! family, draws the params and places 100 scattered disks, writes the
//! sample's statements and analyses them (world index, plans). Then the
//! same for 20 000 and 100 000 scattered disks (issue 39: placement was
//! quadratic in the items).
//!
//! `cargo bench --no-default-features --bench family`; figures in
//! BENCHMARKS.md.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};

const FAMILY: &str = "param gap = uniform(0.5, 3)\nparam y = uniform(5, 15)\n\
    world {\n  bounds (0, 0) (40, 20)\n  rect (19, 0) (21, y - gap / 2)\n  rect (19, y + gap / 2) (21, 20)\n  \
    scatter rocks 98 disk uniform(0.2, 0.6) in (1, 1) (18, 19) gap 0.1\n}\n\
    robot r disk 0.3\nplan p astar r { start (0.5, 0.5) goal (39, 19) cell 0.25 }\nexpect p.found\n";

fn bench(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("scen-bench-family-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let path = dir.join("family.scen");
    std::fs::write(&path, FAMILY).expect("write the family");
    let scenario = scen::load(&path).expect("the family loads");
    assert_eq!(scenario.world.obstacles.len(), 100);
    let mut k = 0u64;
    c.bench_function("family/sample_100_obstacles", |b| {
        b.iter(|| {
            k += 1;
            black_box(scenario.sample(k).expect("a sample"))
        })
    });
    let _ = std::fs::remove_dir_all(&dir);
}

/// A family of `n` disks scattered over a square sized for 1 % of it to be
/// disks, sample `k` drawn and analysed.
fn many(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("scen-bench-scatter-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let mut group = c.benchmark_group("family");
    group.sample_size(10);
    for n in [20_000, 100_000] {
        let side = (n as f64 * 100.0 * 0.125 * 0.125 * std::f64::consts::PI)
            .sqrt()
            .ceil();
        let text = format!(
            "world {{\n  bounds (0, 0) ({b}, {b})\n  \
             scatter rocks {n} disk uniform(0.05, 0.2) in (0, 0) ({side}, {side}) gap 0.5\n}}\n\
             robot r point\nplan p astar r {{ start ({s}, {s}) goal ({s}, {s}) }}\n",
            b = side + 2.0,
            s = side + 1.0,
        );
        let path = dir.join(format!("scatter_{n}.scen"));
        std::fs::write(&path, text).expect("write the family");
        let scenario = scen::load(&path).expect("the family loads");
        assert_eq!(scenario.world.obstacles.len(), n);
        let mut k = 0u64;
        group.bench_function(format!("sample_scatter_{n}"), |b| {
            b.iter(|| {
                k += 1;
                black_box(scenario.sample(k).expect("a sample"))
            })
        });
    }
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, bench, many);
criterion_main!(benches);
