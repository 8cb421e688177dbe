//! Measures of a path (a list of configurations): its (x, y) length, its
//! total rotation and OMPL's smoothness (SPEC 3). The runner measures every
//! planner's path with them; a planner that measures a motion as it makes
//! it (a long potential-field walk) uses the same terms.

use super::{Config, Point, angle_diff};

/// Euclidean length of the (x, y) polyline.
pub fn path_length(path: &[Config]) -> f64 {
    path.windows(2)
        .map(|w| (w[1].x - w[0].x).hypot(w[1].y - w[0].y))
        .sum()
}

/// Total absolute rotation along the shorter arcs, in radians.
pub fn path_turn(path: &[Config]) -> f64 {
    path.windows(2)
        .map(|w| angle_diff(w[0].theta, w[1].theta).abs())
        .sum()
}

/// OMPL's smoothness of the (x, y) polyline (`PathGeometric::smoothness`):
/// for consecutive segments of lengths a, b whose ends are c apart,
/// k = 2(π − acos((a² + b² − c²)/(2ab)))/(a + b), summed as k². Zero-length
/// segments are skipped; as in OMPL, a vertex where the cosine is not
/// strictly inside (−1, 1) (a straight continuation, or a turn back)
/// adds nothing. 0 for a straight path.
pub fn smoothness(path: &[Config]) -> f64 {
    let mut points: Vec<Point> = Vec::with_capacity(path.len());
    for c in path {
        if points.last() != Some(&c.xy()) {
            points.push(c.xy());
        }
    }
    points
        .windows(3)
        .map(|w| corner_smoothness(w[0], w[1], w[2]))
        .sum()
}

/// The term of [`smoothness`] at the corner `q` of the polyline
/// `p → q → r` (consecutive points, each different from the next): k².
pub fn corner_smoothness(p: Point, q: Point, r: Point) -> f64 {
    let (a, b, c) = ((q - p).norm(), (r - q).norm(), (r - p).norm());
    let cos = (a * a + b * b - c * c) / (2.0 * a * b);
    if cos > -1.0 && cos < 1.0 {
        let k = 2.0 * (std::f64::consts::PI - cos.acos()) / (a + b);
        k * k
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path(points: &[(f64, f64)]) -> Vec<Config> {
        points
            .iter()
            .map(|&(x, y)| Config::new(x, y, 0.0))
            .collect()
    }

    #[test]
    fn smoothness_is_omplish() {
        // Straight, with a repeated point and a collinear vertex: 0.
        assert_eq!(
            smoothness(&path(&[(0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (3.0, 0.0)])),
            0.0
        );
        assert_eq!(smoothness(&path(&[(0.0, 0.0)])), 0.0);
        // One right angle between unit segments: k = 2·(π/2)/2, k² = π²/4.
        let s = smoothness(&path(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)]));
        assert!(
            (s - std::f64::consts::PI.powi(2) / 4.0).abs() < 1e-12,
            "{s}"
        );
        // Sharper turns cost more; longer segments soften them.
        let sharp = smoothness(&path(&[(0.0, 0.0), (1.0, 0.0), (0.0, 0.1)]));
        assert!(sharp > s);
        let long = smoothness(&path(&[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0)]));
        assert!(long < s);
    }
}
