use super::*;
use crate::geometry::{Obstacle, Shape};
use proptest::prelude::*;

#[test]
fn forces_follow_the_formula() {
    // One wall at x = 2, the robot at x = 1.5 (ρ = 0.5 for a point, 0.3 for
    // a disk of radius 0.2), goal straight up.
    let world = World {
        bounds: Aabb::from_corners(Point::new(0.0, 0.0), Point::new(10.0, 10.0)),
        obstacles: vec![Obstacle {
            name: "w".into(),
            shape: Shape::Segment(Point::new(2.0, 0.0), Point::new(2.0, 10.0)),
        }],
    };
    let gains = Gains {
        attract: 2.0,
        repulse: 3.0,
        influence: 1.0,
    };
    for (r, rho) in [(0.0, 0.5), (0.2, 0.3)] {
        let field = FieldIndex::new(&world, r, gains);
        let x = Point::new(1.5, 5.0);
        let f = field.forces(x, Point::new(1.5, 9.0));
        assert_eq!(f.attract, Vector::new(0.0, 8.0));
        let expected = 3.0 / (rho * rho * rho) * (1.0 / rho - 1.0) * rho;
        assert!((f.repulse.x + expected).abs() < 1e-9 && f.repulse.y == 0.0);
        let near = f.nearest.unwrap();
        assert!((near.rho - rho).abs() < 1e-12);
        assert_eq!(near.point, Point::new(2.0, 5.0));
        // Out of influence: no repulsion.
        let far = field.forces(Point::new(0.5, 5.0), Point::new(1.5, 9.0));
        assert_eq!(far.repulse, Vector::zeros());
        assert!(far.nearest.is_none());
    }
}

/// The closest point of a shape, by brute force over its outline.
fn brute_closest(shape: &Shape, x: Point) -> Vec<Point> {
    let seg = |a: Point, b: Point| {
        let t = ((x - a).dot(&(b - a)) / (b - a).norm_squared()).clamp(0.0, 1.0);
        a + (b - a) * t
    };
    let ring = |v: &[Point]| -> Vec<Point> {
        (0..v.len())
            .map(|k| seg(v[k], v[(k + 1) % v.len()]))
            .collect()
    };
    match shape {
        Shape::Segment(a, b) => vec![seg(*a, *b)],
        Shape::Rect(b) => ring(&b.corners()),
        Shape::Polygon { outline, .. } => ring(outline),
        Shape::Disk { center, radius } => vec![center + (x - center).normalize() * *radius],
        Shape::Grid(_) => unreachable!(),
    }
}

fn arb_shape() -> impl Strategy<Value = Shape> {
    let pt = || (0.0..30.0f64, 0.0..30.0f64).prop_map(|(x, y)| Point::new(x, y));
    prop_oneof![
        (pt(), -3.0..3.0f64, -3.0..3.0f64)
            .prop_map(|(a, dx, dy)| Shape::Segment(a, a + Vector::new(dx + 0.01, dy))),
        (pt(), 0.1..2.0f64, 0.1..2.0f64)
            .prop_map(|(a, w, h)| Shape::Rect(Aabb::from_corners(a, a + Vector::new(w, h)))),
        // Large boxes: listed only in the buckets near their boundary.
        (pt(), 0.1..25.0f64, 0.1..25.0f64)
            .prop_map(|(a, w, h)| Shape::Rect(Aabb::from_corners(a, a + Vector::new(w, h)))),
        (pt(), 0.1..1.5f64).prop_map(|(c, r)| Shape::Disk {
            center: c,
            radius: r
        }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The bucket index gives the same forces as summing over every
    /// obstacle with brute-force closest points.
    #[test]
    fn indexed_forces_equal_brute_force(
        shapes in prop::collection::vec(arb_shape(), 1..60),
        probes in prop::collection::vec((0.0..30.0f64, 0.0..30.0f64), 20),
        radius in prop_oneof![Just(0.0), 0.05..0.5f64],
        influence in 0.2..4.0f64,
    ) {
        let world = World {
            bounds: Aabb::from_corners(Point::new(0.0, 0.0), Point::new(30.0, 30.0)),
            obstacles: shapes
                .iter()
                .enumerate()
                .map(|(i, s)| Obstacle { name: format!("o{i}"), shape: s.clone() })
                .collect(),
        };
        let gains = Gains { attract: 1.0, repulse: 1.0, influence };
        let field = FieldIndex::new(&world, radius, gains);
        for (px, py) in probes {
            let x = Point::new(px, py);
            let mut expected = Vector::zeros();
            let mut inside = false;
            for s in &shapes {
                let b = brute_closest(s, x)
                    .into_iter()
                    .min_by(|a, b| (a - x).norm().total_cmp(&(b - x).norm()))
                    .unwrap();
                let dist = (x - b).norm();
                let contains = match s {
                    Shape::Rect(r) => r.contains(x),
                    Shape::Disk { center, radius } => (x - center).norm() <= *radius,
                    _ => false,
                };
                inside |= contains || dist - radius < 1e-3;
                let rho = dist - radius;
                if rho <= influence && dist > 0.0 {
                    let m = 1.0 / rho.powi(3) * (1.0 / rho - 1.0 / influence) * rho;
                    expected += (x - b) * (m / dist);
                }
            }
            if inside {
                continue; // the walk never stands there
            }
            let got = field.forces(x, x).repulse;
            let tol = 1e-9 * (1.0 + expected.norm());
            prop_assert!((got - expected).norm() <= tol, "at {:?}: {:?} vs {:?}", x, got, expected);
        }
    }
}

/// A grid of unit cells at the origin from rows of `#` and `.`.
fn grid(rows: &[&str]) -> Shape {
    Shape::Grid(crate::geometry::Grid {
        cell: 1.0,
        origin: Point::new(0.0, 0.0),
        width: rows[0].len(),
        height: rows.len(),
        cells: rows
            .iter()
            .flat_map(|r| r.chars().map(|c| u8::from(c != '#')))
            .collect(),
    })
}

#[test]
fn grid_cells_repel_by_groups() {
    // Two separate blocks of a grid are two sources; a wall of three cells
    // is one (one force, not three).
    let world = World {
        bounds: Aabb::from_corners(Point::new(0.0, 0.0), Point::new(10.0, 5.0)),
        obstacles: vec![Obstacle {
            name: "g".into(),
            shape: grid(&["..........", ".##...#...", "..........", ".........."]),
        }],
    };
    let gains = Gains {
        attract: 1.0,
        repulse: 1.0,
        influence: 1.0,
    };
    let field = FieldIndex::new(&world, 0.0, gains);
    assert_eq!(field.sources.len(), 2);
    // Below the middle of the two-cell block, 0.5 away: straight down.
    let f = field.forces(Point::new(2.0, 1.5), Point::new(2.0, 1.5));
    let expected = 1.0 / 0.125 * (2.0 - 1.0) * 0.5;
    assert!(
        (f.repulse - Vector::new(0.0, -expected)).norm() < 1e-9,
        "{:?}",
        f.repulse
    );
}
