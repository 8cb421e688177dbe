//! The six Dubins words LSL, RSR, RSL, LSR, RLR, LRL (Dubins 1957), in the
//! standard parametrisation (Shkel & Lumelsky 2001; LaValle, *Planning
//! Algorithms* §15.3.1) that OMPL's `DubinsStateSpace` also uses: the start
//! and goal seen along the line between them, at distance `d` (in turning
//! radii), the start's heading `alpha` and the goal's `beta` measured from
//! that line.
//!
//! All six are computed and the shortest kept; a word replaces the best so
//! far only when strictly shorter, so among words of equal length the first
//! in the order above wins. (OMPL picks the word of long paths by the Dubins
//! set classification instead, with single-precision switching functions;
//! the exhaustive minimum is exact and as fast here.)
//!
//! Angles are reduced to [0, 2π); a reduced angle within [`SNAP`] of a full
//! turn is taken as 0: it is a zero angle that rounding pushed below 0, and
//! keeping it would add a whole loop to the word.

use std::f64::consts::TAU;

use super::Turn;

/// Below this (radians) a whole turn is rounding: the angle is 0.
pub const SNAP: f64 = 1e-10;

/// Tolerance on the square of the straight part of RSL / LSR (where the
/// two circles touch), in radii².
const TANGENT_TOL: f64 = 1e-12;

/// The six words' segment types, in the order they are tried.
pub(super) const WORDS: [[Turn; 3]; 6] = {
    use Turn::{L, R, S};
    [
        [L, S, L],
        [R, S, R],
        [R, S, L],
        [L, S, R],
        [R, L, R],
        [L, R, L],
    ]
};

/// The shortest word: its index in [`WORDS`], its three (non-negative)
/// parameters in radii, and their sum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Word {
    pub word: usize,
    pub params: [f64; 3],
    pub length: f64,
}

/// `x` reduced to [0, 2π), a reduction within [`SNAP`] below 2π taken as 0.
#[inline]
pub(super) fn mod2pi(x: f64) -> f64 {
    let v = if (0.0..TAU).contains(&x) {
        x
    } else if (-TAU..0.0).contains(&x) {
        x + TAU
    } else {
        x.rem_euclid(TAU)
    };
    if v > TAU - SNAP { 0.0 } else { v }
}

/// The shortest of the six words for the normalised problem (`d ≥ 0`
/// finite, `alpha`, `beta` finite).
pub(super) fn shortest(d: f64, alpha: f64, beta: f64) -> Word {
    let (alpha, beta) = (mod2pi(alpha), mod2pi(beta));
    let (sa, ca) = alpha.sin_cos();
    let (sb, cb) = beta.sin_cos();
    let mut best = Word {
        word: 0,
        params: [0.0; 3],
        length: f64::INFINITY,
    };
    let take = |best: &mut Word, word: usize, t: f64, p: f64, q: f64| {
        let length = t + p + q;
        if length < best.length {
            *best = Word {
                word,
                params: [t, p, q],
                length,
            };
        }
    };

    // LSL. The straight is the vector between the two left circles'
    // centres (in radii): its norm is OMPL's p (p² = 2 + d² − 2(cos(α−β) −
    // d(sin α − sin β)) expanded) and its angle gives the arcs, so that a
    // zero straight stays zero.
    let (lx, ly) = (d + sa - sb, cb - ca);
    let ll = lx * lx + ly * ly;
    let theta_l = ly.atan2(lx);
    take(
        &mut best,
        0,
        mod2pi(theta_l - alpha),
        ll.sqrt(),
        mod2pi(beta - theta_l),
    );

    // RSR: the vector between the right circles' centres.
    let (rx, ry) = (d - sa + sb, ca - cb);
    let rr = rx * rx + ry * ry;
    let theta_r = ry.atan2(rx);
    take(
        &mut best,
        1,
        mod2pi(alpha - theta_r),
        rr.sqrt(),
        mod2pi(theta_r - beta),
    );

    // RSL: p² = |v|² − 4 for the vector v between the centres (2 apart at
    // tangency).
    let (vx, vy) = (d - sa - sb, ca + cb);
    let tmp = vx * vx + vy * vy - 4.0;
    if tmp >= -TANGENT_TOL {
        let p = tmp.max(0.0).sqrt();
        if p < best.length {
            let theta = vy.atan2(vx) - 2f64.atan2(p);
            take(&mut best, 2, mod2pi(alpha - theta), p, mod2pi(beta - theta));
        }
    }

    // LSR
    let (vx, vy) = (d + sa + sb, -ca - cb);
    let tmp = vx * vx + vy * vy - 4.0;
    if tmp >= -TANGENT_TOL {
        let p = tmp.max(0.0).sqrt();
        if p < best.length {
            let theta = vy.atan2(vx) - (-2f64).atan2(p);
            take(&mut best, 3, mod2pi(theta - alpha), p, mod2pi(theta - beta));
        }
    }

    // RLR and LRL: the middle arc turns more than a half turn; OMPL's
    // cosine (6 − d² + 2(cos(α−β) ± d(sin α − sin β))) / 8 is 1 − |v|²/8 for
    // the vector v between the outer circles' centres.
    if std::f64::consts::PI < best.length {
        let tmp = 1.0 - 0.125 * rr;
        if tmp >= -1.0 - 1e-12 {
            let p = TAU - tmp.max(-1.0).acos();
            let t = mod2pi(alpha - theta_r + 0.5 * p);
            take(&mut best, 4, t, p, mod2pi(alpha - beta - t + p));
        }
        let tmp = 1.0 - 0.125 * ll;
        if tmp >= -1.0 - 1e-12 {
            let p = TAU - tmp.max(-1.0).acos();
            let t = mod2pi(theta_l - alpha + 0.5 * p);
            take(&mut best, 5, t, p, mod2pi(beta - alpha - t + p));
        }
    }
    best
}
