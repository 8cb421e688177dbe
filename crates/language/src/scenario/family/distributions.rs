//! The distributions a param or a scattered size draws from (`uniform`,
//! `normal`, `int`): their bounds' checks, draws and inverse distribution
//! functions.

#![allow(clippy::result_large_err)]

use crate::diagnostics::{Diag, Span};
use crate::rng::SplitMix64;

use super::*;

/// The bounds of a distribution, checked.
pub(super) fn check_distribution(f: &str, a: f64, b: f64, span: Span) -> Result<(), Diag> {
    let problem = match f {
        "uniform" if a >= b => Some(format!(
            "`uniform({a}, {b})` has its bounds inverted or equal"
        )),
        "int" if a.ceil() > b.floor() => Some(format!("`int({a}, {b})` contains no whole number")),
        "int" if (b - a).abs() > 1e15 => Some(format!("`int({a}, {b})` spans too many numbers")),
        "normal" if b < 0.0 => Some(format!(
            "`normal({a}, {b})` has a negative standard deviation"
        )),
        _ => None,
    };
    match problem {
        Some(message) => Err(Diag::error("scen::family::bad_distribution", message)
            .at(span, "these bounds")
            .help(distribution_help(f))),
        None => Ok(()),
    }
}

pub(super) fn sample(f: &str, a: f64, b: f64, rng: &mut SplitMix64) -> f64 {
    match f {
        "uniform" => rng.range(a, b),
        "normal" => {
            // Box–Muller; 1 - u is in (0, 1].
            let u = 1.0 - rng.next_f64();
            let v = rng.next_f64();
            a + b * (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
        }
        _ => {
            let (lo, hi) = (a.ceil(), b.floor());
            let n = (hi - lo) as u64 + 1;
            lo + (rng.next_u64() % n) as f64
        }
    }
}

/// The value of a distribution at `u` in [0, 1) (its inverse distribution
/// function): what a search's point of the unit cube stands for.
pub(super) fn inverse(f: &str, a: f64, b: f64, u: f64) -> f64 {
    match f {
        "uniform" => a + (b - a) * u,
        "normal" => a + b * normal_quantile(u.clamp(1e-12, 1.0 - 1e-12)),
        _ => {
            let (lo, hi) = (a.ceil(), b.floor());
            (lo + (u * (hi - lo + 1.0)).floor()).min(hi)
        }
    }
}

/// The standard normal distribution's quantile (Acklam's rational
/// approximation, relative error below 1.2e-9).
pub(super) fn normal_quantile(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] = [
        7.784_695_709_041_462e-3,
        3.224_671_290_700_398e-1,
        2.445_134_137_142_996,
        3.754_408_661_907_416,
    ];
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    if p < 0.02425 {
        tail((-2.0 * p.ln()).sqrt())
    } else if p > 1.0 - 0.02425 {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    }
}
