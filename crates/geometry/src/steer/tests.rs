use std::f64::consts::{FRAC_PI_2, PI, TAU};

use proptest::prelude::*;

use super::*;
use crate::angle_diff;

fn rs(radius: f64) -> Steering {
    Steering::new(Model::ReedsShepp, radius)
}

fn dubins(radius: f64) -> Steering {
    Steering::new(Model::Dubins, radius)
}

fn c(x: f64, y: f64, theta: f64) -> Config {
    Config::new(x, y, theta)
}

fn euclid(a: Config, b: Config) -> f64 {
    (b.x - a.x).hypot(b.y - a.y)
}

/// The path from `a` ends on `b`: position within 1e-9 × the problem's
/// scale, heading within 1e-9 rad.
fn assert_ends_on(p: &SteerPath, a: Config, b: Config) {
    let e = p.end(a);
    let scale = p.radius() + euclid(a, b);
    assert!(
        euclid(e, b) <= 1e-9 * scale,
        "ends at {e:?}, {} from {b:?} ({p:?} from {a:?})",
        euclid(e, b)
    );
    let dt = angle_diff(e.theta, b.theta).abs();
    assert!(
        dt <= 1e-9,
        "heading off by {dt} ({p:?} from {a:?} to {b:?})"
    );
}

fn letters(p: &SteerPath) -> String {
    p.segments().iter().map(|s| s.turn.letter()).collect()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0)
}

#[test]
fn straight_ahead_is_the_distance() {
    for s in [rs(2.5), dubins(2.5)] {
        let (a, b) = (
            c(1.0, 2.0, 0.3),
            c(1.0 + 7.0 * 0.3f64.cos(), 2.0 + 7.0 * 0.3f64.sin(), 0.3),
        );
        let p = s.shortest(a, b);
        assert!(close(p.length(), 7.0), "{p:?}");
        assert_eq!(letters(&p), "S");
        assert_eq!((p.cusps(), p.reverse_length(), p.turn()), (0, 0.0, 0.0));
        assert_ends_on(&p, a, b);
    }
}

#[test]
fn reeds_shepp_backs_straight_up_dubins_goes_round() {
    let (a, b) = (c(0.0, 0.0, 0.0), c(-3.0, 0.0, 0.0));
    let p = rs(1.0).shortest(a, b);
    assert_eq!(letters(&p), "S");
    assert!(close(p.segments()[0].length, -3.0), "{p:?}");
    assert!(close(p.reverse_length(), 3.0));
    let d = dubins(1.0).shortest(a, b);
    assert!(d.length() > 3.0 + PI, "{d:?}");
    assert!(d.segments().iter().all(|s| s.length > 0.0));
    assert_ends_on(&d, a, b);
}

#[test]
fn quarter_and_half_turns_are_single_arcs() {
    let r = 1.5;
    let cases = [
        (c(r, r, FRAC_PI_2), "L", FRAC_PI_2 * r),
        (c(r, -r, -FRAC_PI_2), "R", FRAC_PI_2 * r),
        (c(0.0, 2.0 * r, PI), "L", PI * r),
        (c(0.0, -2.0 * r, -PI), "R", PI * r),
    ];
    for s in [rs(r), dubins(r)] {
        for (b, word, len) in cases {
            let a = c(0.0, 0.0, 0.0);
            let p = s.shortest(a, b);
            assert_eq!(letters(&p), word, "{s:?} to {b:?}: {p:?}");
            assert!(close(p.length(), len), "{s:?} to {b:?}: {p:?}");
            assert!(close(p.turn(), len / r));
            assert_ends_on(&p, a, b);
        }
    }
}

/// A half turn to the lane beside, 2ρ to the left: LSL with no straight
/// is one arc; 4ρ to the left (LSL with a straight of 2ρ between two
/// quarter turns), and for Dubins the U-turn to a lane ρ to the left, which
/// needs more than the half circle.
#[test]
fn u_turns() {
    let r = 2.0;
    let a = c(0.0, 0.0, 0.0);
    for s in [rs(r), dubins(r)] {
        let b = c(0.0, 4.0 * r, PI);
        let p = s.shortest(a, b);
        assert_eq!(letters(&p), "LSL");
        assert!(close(p.length(), PI * r + 2.0 * r), "{p:?}");
        assert_ends_on(&p, a, b);
    }
    let b = c(0.0, r, PI);
    let p = dubins(r).shortest(a, b);
    assert!(p.length() > PI * r, "{p:?}");
    assert_ends_on(&p, a, b);
}

#[test]
fn same_configuration_is_the_empty_path_even_a_turn_apart() {
    for s in [rs(1.0), dubins(1.0)] {
        for b in [
            c(3.0, 4.0, 0.5),
            c(3.0, 4.0, 0.5 + TAU),
            c(3.0, 4.0, 0.5 - 2.0 * TAU),
        ] {
            let p = s.shortest(c(3.0, 4.0, 0.5), b);
            assert_eq!((p.length(), p.segments().len()), (0.0, 0));
            assert_eq!(s.distance(c(3.0, 4.0, 0.5), b), 0.0);
            assert_eq!(p.end(c(3.0, 4.0, 0.5)), c(3.0, 4.0, 0.5));
        }
    }
}

#[test]
fn huge_finite_inputs_give_no_nan() {
    let big = [
        0.0,
        1.0,
        -1e-300,
        1e300,
        -1e300,
        f64::MAX,
        f64::MIN,
        1e20,
        1e-20,
    ];
    for s in [rs(1.0), dubins(1.0), rs(1e-300), dubins(1e300)] {
        for &x in &big {
            for &t in &big {
                let (a, b) = (c(x, -x, t), c(-x, x * 0.5, -t));
                let p = s.shortest(a, b);
                assert!(!p.length().is_nan(), "{s:?} {a:?} {b:?}");
                assert!(!s.distance(a, b).is_nan());
                assert!(p.segments().iter().all(|g| g.length.is_finite()));
                let e = p.end(a);
                assert!(!(e.x.is_nan() || e.y.is_nan() || e.theta.is_nan()));
            }
        }
    }
}

#[test]
fn config_at_walks_the_segments() {
    let s = rs(1.0);
    let (a, b) = (c(0.0, 0.0, 0.0), c(0.5, 1.5, 2.5));
    let p = s.shortest(a, b);
    assert!(p.segments().len() >= 2, "{p:?}");
    assert_eq!(p.config_at(a, -1.0), a);
    assert_eq!(p.config_at(a, p.length() + 1.0), p.end(a));
    let mut at = a;
    let mut s_total = 0.0;
    for seg in p.segments() {
        let mid = p.config_at(a, s_total + 0.5 * seg.length.abs());
        let half = Segment::advance(at, seg.turn, 0.5 * seg.length, 1.0);
        assert!(euclid(mid, half) < 1e-12 && (mid.theta - half.theta).abs() < 1e-12);
        at = seg.end(at, 1.0);
        s_total += seg.length.abs();
    }
    assert_ends_on(&p, a, b);
}

fn config(reach: f64) -> impl Strategy<Value = Config> {
    (-reach..reach, -reach..reach, -10.0..10.0f64).prop_map(|(x, y, t)| c(x, y, t))
}

/// Two configurations: far apart, or the second within a few radii of the
/// first.
fn pair() -> impl Strategy<Value = (f64, Config, Config)> {
    (
        0.1..10.0f64,
        config(30.0),
        config(30.0),
        (-3.0..3.0f64, -3.0..3.0f64, -PI..PI),
        any::<bool>(),
    )
        .prop_map(|(r, a, b, (dx, dy, dt), near)| {
            let b = if near {
                c(a.x + dx * r, a.y + dy * r, a.theta + dt)
            } else {
                b
            };
            (r, a, b)
        })
}

fn check_path(s: Steering, a: Config, b: Config) -> SteerPath {
    let p = s.shortest(a, b);
    assert_ends_on(&p, a, b);
    assert_eq!(p.length().to_bits(), s.distance(a, b).to_bits());
    let sum: f64 = p.segments().iter().map(|g| g.length.abs()).sum();
    assert!(
        (sum - p.length()).abs() <= 1e-9 * p.length().max(1.0),
        "{sum} vs {p:?}"
    );
    assert!(p.length() >= euclid(a, b) * (1.0 - 1e-12), "{p:?}");
    assert!(
        p.turn() >= angle_diff(a.theta, b.theta).abs() - 1e-9,
        "{p:?}"
    );
    assert!(p.segments().len() <= 5);
    assert!(
        p.segments()
            .iter()
            .all(|g| g.length.abs() >= MIN_SEGMENT * s.radius)
    );
    p
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn paths_end_on_the_goal_and_add_up((r, a, b) in pair()) {
        let p = check_path(rs(r), a, b);
        prop_assert!(p.cusps() < p.segments().len().max(1));
        prop_assert!(p.reverse_length() <= p.length() * (1.0 + 1e-12));
        let d = check_path(dubins(r), a, b);
        prop_assert_eq!((d.cusps(), d.reverse_length()), (0, 0.0));
        prop_assert!(d.segments().len() <= 3);
    }

    #[test]
    fn reeds_shepp_is_symmetric_and_below_dubins((r, a, b) in pair()) {
        let (ab, ba) = (rs(r).distance(a, b), rs(r).distance(b, a));
        prop_assert!((ab - ba).abs() <= 1e-9 * ab.max(1.0), "{} vs {}", ab, ba);
        let du = dubins(r).distance(a, b);
        prop_assert!(euclid(a, b) <= ab * (1.0 + 1e-12));
        prop_assert!(ab <= du * (1.0 + 1e-12) + 1e-12, "RS {} > Dubins {}", ab, du);
    }

    /// The heading change bounds every length from below, both ways (the
    /// nearest-neighbour search passes over states by it), and on a pair
    /// that differs only in heading.
    #[test]
    fn the_turn_bounds_the_length((r, a, b) in pair(), same_place in any::<bool>()) {
        let b = if same_place { c(a.x, a.y, b.theta) } else { b };
        for s in [rs(r), dubins(r)] {
            let bound = s.turn_bound(a, b);
            prop_assert_eq!(bound, s.turn_bound(b, a));
            for d in [s.distance(a, b), s.distance(b, a)] {
                prop_assert!(bound <= d, "{:?}: bound {} > length {}", s, bound, d);
            }
        }
    }

    #[test]
    fn triangle_inequality((r, a, b) in pair(), m in (-3.0..3.0f64, -3.0..3.0f64, -PI..PI), near in any::<bool>(), far in config(30.0)) {
        let m = if near { c(a.x + m.0 * r, a.y + m.1 * r, a.theta + m.2) } else { far };
        for s in [rs(r), dubins(r)] {
            let (ac, ab, bc) = (s.distance(a, b), s.distance(a, m), s.distance(m, b));
            prop_assert!(ac <= ab + bc + 1e-9 * ac.max(1.0), "{:?}: {} > {} + {}", s, ac, ab, bc);
        }
    }

    /// Rigid motions of the pair change nothing: the same length from any
    /// place and heading.
    #[test]
    fn lengths_do_not_depend_on_where_the_pair_is((r, a, b) in pair(), (tx, ty, rot) in (-50.0..50.0f64, -50.0..50.0f64, -PI..PI)) {
        let (s, co) = rot.sin_cos();
        let mv = |p: Config| c(tx + co * p.x - s * p.y, ty + s * p.x + co * p.y, p.theta + rot);
        for st in [rs(r), dubins(r)] {
            let (d0, d1) = (st.distance(a, b), st.distance(mv(a), mv(b)));
            prop_assert!((d0 - d1).abs() <= 1e-8 * d0.max(1.0), "{:?}: {} vs {}", st, d0, d1);
        }
    }
}
