//! The Reeds–Shepp words, in the formulation of OMPL's
//! `ReedsSheppStateSpace` (Mark Moll; Reeds & Shepp 1990, §8): twelve base
//! formulas (8.1–8.4, 8.7–8.11, with OMPL's corrections of the paper's
//! typos), each tried on the goal as it is and under the paper's *timeflip*
//! (x, y, φ) → (−x, y, −φ), *reflect* (x, y, φ) → (x, −y, −φ) and both, and
//! the CCC and CCSC formulas also *backwards* (the goal seen from the start
//! reversed), which makes the 48 words.
//!
//! Everything here is in units of the turning radius, the start at the
//! origin heading along +x, the goal at (x, y) with heading φ.
//!
//! The words are tried in OMPL's order (CSC, CCC, CCCC, CCSC, CCSCC; in each
//! family as in OMPL) and a word replaces the best so far only when it is
//! strictly shorter, so that among words of equal length the first in that
//! order wins, deterministically.
//!
//! Speed: sin φ and cos φ are computed once (the variants only flip signs);
//! each formula first computes the one distance its word needs (a square
//! root) and gives up, before any arc tangent, when a lower bound on the
//! word's length — that distance (or the straight part it fixes) plus what
//! the arcs must turn, at least |φ| wrapped to [−π, π] — already reaches the
//! best length found. A word skipped that way could not have been strictly
//! shorter, so the result is the exhaustive one (a test compares both).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use super::Turn;

/// OMPL's tolerance on the signs of the parameters: 10 ε.
const ZERO: f64 = 10.0 * f64::EPSILON;

/// The 18 segment-type patterns of OMPL (`reedsSheppPathType`); `None` is
/// an unused slot. Each of the 48 words is one of these with signs.
pub(super) const WORDS: [[Option<Turn>; 5]; 18] = {
    use Turn::{L, R, S};
    [
        [Some(L), Some(R), Some(L), None, None],
        [Some(R), Some(L), Some(R), None, None],
        [Some(L), Some(R), Some(L), Some(R), None],
        [Some(R), Some(L), Some(R), Some(L), None],
        [Some(L), Some(R), Some(S), Some(L), None],
        [Some(R), Some(L), Some(S), Some(R), None],
        [Some(L), Some(S), Some(R), Some(L), None],
        [Some(R), Some(S), Some(L), Some(R), None],
        [Some(L), Some(R), Some(S), Some(R), None],
        [Some(R), Some(L), Some(S), Some(L), None],
        [Some(R), Some(S), Some(R), Some(L), None],
        [Some(L), Some(S), Some(L), Some(R), None],
        [Some(L), Some(S), Some(R), None, None],
        [Some(R), Some(S), Some(L), None, None],
        [Some(L), Some(S), Some(L), None, None],
        [Some(R), Some(S), Some(R), None, None],
        [Some(L), Some(R), Some(S), Some(L), Some(R)],
        [Some(R), Some(L), Some(S), Some(R), Some(L)],
    ]
};

/// The shortest word found: its pattern (an index into [`WORDS`]), its
/// five signed parameters (arc angles and straight lengths, in radii;
/// negative = reverse) and its length, the sum of their absolute values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Word {
    pub word: usize,
    pub params: [f64; 5],
    pub length: f64,
}

impl Word {
    fn new(word: usize, params: [f64; 5]) -> Self {
        // Summed in slot order, as OMPL's PathType does.
        let length =
            params[0].abs() + params[1].abs() + params[2].abs() + params[3].abs() + params[4].abs();
        Word {
            word,
            params,
            length,
        }
    }
}

/// OMPL's `mod2pi`: into [−π, π] (fmod, then one turn added or taken).
/// `fmod` is exact, and returns its argument below one turn, so the fast
/// paths give the same bits.
#[inline]
fn mod2pi(x: f64) -> f64 {
    let v = if x.abs() < TAU {
        x
    } else if x.abs() < 2.0 * TAU {
        // Exact (Sterbenz), as fmod.
        if x > 0.0 { x - TAU } else { x + TAU }
    } else {
        x % TAU
    };
    if v < -PI {
        v + TAU
    } else if v > PI {
        v - TAU
    } else {
        v
    }
}

/// The goal of one variant: position, heading and its sine and cosine.
#[derive(Clone, Copy)]
struct Goal {
    x: f64,
    y: f64,
    phi: f64,
    s: f64,
    c: f64,
}

impl Goal {
    fn timeflip(self) -> Self {
        Goal {
            x: -self.x,
            phi: -self.phi,
            s: -self.s,
            ..self
        }
    }
    fn reflect(self) -> Self {
        Goal {
            y: -self.y,
            phi: -self.phi,
            s: -self.s,
            ..self
        }
    }
    fn both(self) -> Self {
        Goal {
            x: -self.x,
            y: -self.y,
            ..self
        }
    }
}

/// The search state: the lower bound on what the arcs turn and whether to
/// prune (off in the test that checks pruning changes nothing).
struct Search<const PRUNE: bool> {
    /// |φ| wrapped to [0, π]: every word's arcs turn at least this much.
    turn: f64,
}

impl<const PRUNE: bool> Search<PRUNE> {
    /// Whether a word whose length is at least `lb` cannot beat `lmin`
    /// (with a margin for rounding, so that a skipped word could not have
    /// been computed strictly shorter).
    #[inline]
    fn hopeless(&self, lb: f64, lmin: f64) -> bool {
        PRUNE && lb * (1.0 - 1e-10) - 1e-12 >= lmin
    }

    // formula 8.1
    #[inline]
    fn lp_sp_lp(&self, g: Goal, lmin: f64) -> Option<(f64, f64, f64)> {
        let (xi, eta) = (g.x - g.s, g.y - 1.0 + g.c);
        let u = (xi * xi + eta * eta).sqrt();
        // t = atan2(eta, xi) ≥ −ZERO needs eta ≥ about 0.
        if PRUNE && eta < -1e-14 * u {
            return None;
        }
        if self.hopeless(u + self.turn, lmin) {
            return None;
        }
        let t = eta.atan2(xi);
        if t >= -ZERO {
            let v = mod2pi(g.phi - t);
            if v >= -ZERO {
                return Some((t, u, v));
            }
        }
        None
    }

    // formula 8.2
    #[inline]
    fn lp_sp_rp(&self, g: Goal, lmin: f64) -> Option<(f64, f64, f64)> {
        let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
        let u1 = xi * xi + eta * eta;
        if u1 >= 4.0 {
            let u = (u1 - 4.0).sqrt();
            if self.hopeless(u + self.turn, lmin) {
                return None;
            }
            let t1 = eta.atan2(xi);
            let theta = 2f64.atan2(u);
            let t = mod2pi(t1 + theta);
            let v = mod2pi(t - g.phi);
            if t >= -ZERO && v >= -ZERO {
                return Some((t, u, v));
            }
        }
        None
    }

    // formula 8.3 / 8.4 (typo in the paper)
    #[inline]
    fn lp_rm_l(&self, g: Goal, lmin: f64) -> Option<(f64, f64, f64)> {
        let (xi, eta) = (g.x - g.s, g.y - 1.0 + g.c);
        let u1 = (xi * xi + eta * eta).sqrt();
        if u1 <= 4.0 {
            // |u| = 2 asin(u1 / 4) ≥ u1 / 2.
            if self.hopeless((0.5 * u1).max(self.turn), lmin) {
                return None;
            }
            let theta = eta.atan2(xi);
            let u = -2.0 * (0.25 * u1).asin();
            let t = mod2pi(theta + 0.5 * u + PI);
            let v = mod2pi(g.phi - t + u);
            if t >= -ZERO && u <= ZERO {
                return Some((t, u, v));
            }
        }
        None
    }

    // formula 8.7
    #[inline]
    fn lp_rup_lum_rm(&self, g: Goal, lmin: f64) -> Option<(f64, f64, f64)> {
        let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
        let rho = 0.25 * (2.0 + (xi * xi + eta * eta).sqrt());
        if rho <= 1.0 {
            if self.hopeless(self.turn, lmin) {
                return None;
            }
            let u = rho.acos();
            let (t, v) = tau_omega(u, -u, xi, eta, g.phi);
            if t >= -ZERO && v <= ZERO {
                return Some((t, u, v));
            }
        }
        None
    }

    // formula 8.8
    #[inline]
    fn lp_rum_lum_rp(&self, g: Goal, lmin: f64) -> Option<(f64, f64, f64)> {
        let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
        let rho = (20.0 - xi * xi - eta * eta) / 16.0;
        if (0.0..=1.0).contains(&rho) {
            if self.hopeless(self.turn, lmin) {
                return None;
            }
            let u = -rho.acos();
            if u >= -0.5 * PI {
                let (t, v) = tau_omega(u, u, xi, eta, g.phi);
                if t >= -ZERO && v >= -ZERO {
                    return Some((t, u, v));
                }
            }
        }
        None
    }

    // formula 8.9
    #[inline]
    fn lp_rm_sm_lm(&self, g: Goal, lmin: f64) -> Option<(f64, f64, f64)> {
        let (xi, eta) = (g.x - g.s, g.y - 1.0 + g.c);
        let rho = (xi * xi + eta * eta).sqrt();
        if rho >= 2.0 {
            let r = (rho * rho - 4.0).sqrt();
            let u = 2.0 - r;
            if PRUNE && u > ZERO {
                return None;
            }
            if self.hopeless(u.abs() + (self.turn - FRAC_PI_2).max(0.0), lmin) {
                return None;
            }
            let theta = eta.atan2(xi);
            let t = mod2pi(theta + r.atan2(-2.0));
            let v = mod2pi(g.phi - 0.5 * PI - t);
            if t >= -ZERO && u <= ZERO && v <= ZERO {
                return Some((t, u, v));
            }
        }
        None
    }

    // formula 8.10
    #[inline]
    fn lp_rm_sm_rm(&self, g: Goal, lmin: f64) -> Option<(f64, f64, f64)> {
        let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
        let rho = (eta * eta + xi * xi).sqrt();
        if rho >= 2.0 {
            let u = 2.0 - rho;
            if PRUNE && u > ZERO {
                return None;
            }
            if self.hopeless(u.abs() + (self.turn - FRAC_PI_2).max(0.0), lmin) {
                return None;
            }
            let t = xi.atan2(-eta);
            let v = mod2pi(t + 0.5 * PI - g.phi);
            if t >= -ZERO && u <= ZERO && v <= ZERO {
                return Some((t, u, v));
            }
        }
        None
    }

    // formula 8.11 (typo in the paper)
    #[inline]
    fn lp_rm_s_lm_rp(&self, g: Goal, lmin: f64) -> Option<(f64, f64, f64)> {
        let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
        let rho = (xi * xi + eta * eta).sqrt();
        if rho >= 2.0 {
            let u = 4.0 - (rho * rho - 4.0).sqrt();
            if u <= ZERO {
                if self.hopeless(u.abs() + (self.turn - PI).max(0.0), lmin) {
                    return None;
                }
                let t = mod2pi(((4.0 - u) * xi - 2.0 * eta).atan2(-2.0 * xi + (u - 4.0) * eta));
                let v = mod2pi(t - g.phi);
                if t >= -ZERO && v >= -ZERO {
                    return Some((t, u, v));
                }
            }
        }
        None
    }

    fn csc(&self, g: Goal, best: &mut Word) {
        let mut lmin = best.length;
        let mut take = |r: Option<(f64, f64, f64)>, word: usize, flip: f64, lmin: &mut f64| {
            if let Some((t, u, v)) = r {
                let l = t.abs() + u.abs() + v.abs();
                if *lmin > l {
                    *best = Word::new(word, [flip * t, flip * u, flip * v, 0.0, 0.0]);
                    *lmin = l;
                }
            }
        };
        let (tf, rf, bo) = (g.timeflip(), g.reflect(), g.both());
        take(self.lp_sp_lp(g, lmin), 14, 1.0, &mut lmin);
        take(self.lp_sp_lp(tf, lmin), 14, -1.0, &mut lmin);
        take(self.lp_sp_lp(rf, lmin), 15, 1.0, &mut lmin);
        take(self.lp_sp_lp(bo, lmin), 15, -1.0, &mut lmin);
        take(self.lp_sp_rp(g, lmin), 12, 1.0, &mut lmin);
        take(self.lp_sp_rp(tf, lmin), 12, -1.0, &mut lmin);
        take(self.lp_sp_rp(rf, lmin), 13, 1.0, &mut lmin);
        take(self.lp_sp_rp(bo, lmin), 13, -1.0, &mut lmin);
    }

    fn ccc(&self, g: Goal, best: &mut Word) {
        let mut lmin = best.length;
        let mut take =
            |r: Option<(f64, f64, f64)>, word: usize, flip: f64, back: bool, lmin: &mut f64| {
                if let Some((t, u, v)) = r {
                    let l = t.abs() + u.abs() + v.abs();
                    if *lmin > l {
                        let (a, c) = if back { (v, t) } else { (t, v) };
                        *best = Word::new(word, [flip * a, flip * u, flip * c, 0.0, 0.0]);
                        *lmin = l;
                    }
                }
            };
        take(self.lp_rm_l(g, lmin), 0, 1.0, false, &mut lmin);
        take(self.lp_rm_l(g.timeflip(), lmin), 0, -1.0, false, &mut lmin);
        take(self.lp_rm_l(g.reflect(), lmin), 1, 1.0, false, &mut lmin);
        take(self.lp_rm_l(g.both(), lmin), 1, -1.0, false, &mut lmin);
        let b = backwards(g);
        take(self.lp_rm_l(b, lmin), 0, 1.0, true, &mut lmin);
        take(self.lp_rm_l(b.timeflip(), lmin), 0, -1.0, true, &mut lmin);
        take(self.lp_rm_l(b.reflect(), lmin), 1, 1.0, true, &mut lmin);
        take(self.lp_rm_l(b.both(), lmin), 1, -1.0, true, &mut lmin);
    }

    fn cccc(&self, g: Goal, best: &mut Word) {
        let mut lmin = best.length;
        // `same`: the two middle arcs have the same sign (8.8) or not (8.7).
        let mut take =
            |r: Option<(f64, f64, f64)>, word: usize, flip: f64, same: bool, lmin: &mut f64| {
                if let Some((t, u, v)) = r {
                    let l = t.abs() + 2.0 * u.abs() + v.abs();
                    if *lmin > l {
                        let u2 = if same { u } else { -u };
                        *best = Word::new(word, [flip * t, flip * u, flip * u2, flip * v, 0.0]);
                        *lmin = l;
                    }
                }
            };
        let (tf, rf, bo) = (g.timeflip(), g.reflect(), g.both());
        take(self.lp_rup_lum_rm(g, lmin), 2, 1.0, false, &mut lmin);
        take(self.lp_rup_lum_rm(tf, lmin), 2, -1.0, false, &mut lmin);
        take(self.lp_rup_lum_rm(rf, lmin), 3, 1.0, false, &mut lmin);
        take(self.lp_rup_lum_rm(bo, lmin), 3, -1.0, false, &mut lmin);
        take(self.lp_rum_lum_rp(g, lmin), 2, 1.0, true, &mut lmin);
        take(self.lp_rum_lum_rp(tf, lmin), 2, -1.0, true, &mut lmin);
        take(self.lp_rum_lum_rp(rf, lmin), 3, 1.0, true, &mut lmin);
        take(self.lp_rum_lum_rp(bo, lmin), 3, -1.0, true, &mut lmin);
    }

    fn ccsc(&self, g: Goal, best: &mut Word) {
        // Lengths here leave out the fixed quarter turn, as OMPL's do.
        let mut lmin = best.length - 0.5 * PI;
        let mut take =
            |r: Option<(f64, f64, f64)>, word: usize, flip: f64, back: bool, lmin: &mut f64| {
                if let Some((t, u, v)) = r {
                    let l = t.abs() + u.abs() + v.abs();
                    if *lmin > l {
                        let q = -0.5 * PI;
                        let p = if back {
                            [v, u, q, t, 0.0]
                        } else {
                            [t, q, u, v, 0.0]
                        };
                        *best = Word::new(word, p.map(|a| flip * a));
                        *lmin = l;
                    }
                }
            };
        let (tf, rf, bo) = (g.timeflip(), g.reflect(), g.both());
        take(self.lp_rm_sm_lm(g, lmin), 4, 1.0, false, &mut lmin);
        take(self.lp_rm_sm_lm(tf, lmin), 4, -1.0, false, &mut lmin);
        take(self.lp_rm_sm_lm(rf, lmin), 5, 1.0, false, &mut lmin);
        take(self.lp_rm_sm_lm(bo, lmin), 5, -1.0, false, &mut lmin);
        take(self.lp_rm_sm_rm(g, lmin), 8, 1.0, false, &mut lmin);
        take(self.lp_rm_sm_rm(tf, lmin), 8, -1.0, false, &mut lmin);
        take(self.lp_rm_sm_rm(rf, lmin), 9, 1.0, false, &mut lmin);
        take(self.lp_rm_sm_rm(bo, lmin), 9, -1.0, false, &mut lmin);
        let b = backwards(g);
        let (tf, rf, bo) = (b.timeflip(), b.reflect(), b.both());
        take(self.lp_rm_sm_lm(b, lmin), 6, 1.0, true, &mut lmin);
        take(self.lp_rm_sm_lm(tf, lmin), 6, -1.0, true, &mut lmin);
        take(self.lp_rm_sm_lm(rf, lmin), 7, 1.0, true, &mut lmin);
        take(self.lp_rm_sm_lm(bo, lmin), 7, -1.0, true, &mut lmin);
        take(self.lp_rm_sm_rm(b, lmin), 10, 1.0, true, &mut lmin);
        take(self.lp_rm_sm_rm(tf, lmin), 10, -1.0, true, &mut lmin);
        take(self.lp_rm_sm_rm(rf, lmin), 11, 1.0, true, &mut lmin);
        take(self.lp_rm_sm_rm(bo, lmin), 11, -1.0, true, &mut lmin);
    }

    fn ccscc(&self, g: Goal, best: &mut Word) {
        // Lengths here leave out the two fixed quarter turns.
        let mut lmin = best.length - PI;
        let mut take = |r: Option<(f64, f64, f64)>, word: usize, flip: f64, lmin: &mut f64| {
            if let Some((t, u, v)) = r {
                let l = t.abs() + u.abs() + v.abs();
                if *lmin > l {
                    let q = -0.5 * PI;
                    *best = Word::new(word, [t, q, u, q, v].map(|a| flip * a));
                    *lmin = l;
                }
            }
        };
        take(self.lp_rm_s_lm_rp(g, lmin), 16, 1.0, &mut lmin);
        take(self.lp_rm_s_lm_rp(g.timeflip(), lmin), 16, -1.0, &mut lmin);
        take(self.lp_rm_s_lm_rp(g.reflect(), lmin), 17, 1.0, &mut lmin);
        take(self.lp_rm_s_lm_rp(g.both(), lmin), 17, -1.0, &mut lmin);
    }
}

/// The goal seen backwards: the start reached from the goal in reverse
/// (OMPL's `xb`, `yb`; the heading stays φ).
#[inline]
fn backwards(g: Goal) -> Goal {
    Goal {
        x: g.x * g.c + g.y * g.s,
        y: g.x * g.s - g.y * g.c,
        ..g
    }
}

#[inline]
fn tau_omega(u: f64, v: f64, xi: f64, eta: f64, phi: f64) -> (f64, f64) {
    let delta = mod2pi(u - v);
    let a = u.sin() - delta.sin();
    let b = u.cos() - delta.cos() - 1.0;
    let t1 = (eta * a - xi * b).atan2(xi * a + eta * b);
    let t2 = 2.0 * (delta.cos() - v.cos() - u.cos()) + 3.0;
    let tau = if t2 < 0.0 {
        mod2pi(t1 + PI)
    } else {
        mod2pi(t1)
    };
    let omega = mod2pi(tau - u + v - phi);
    (tau, omega)
}

/// The shortest of the 48 words from the origin heading along +x to (x, y)
/// heading `phi` (all in turning radii; `x`, `y` finite).
pub(super) fn shortest(x: f64, y: f64, phi: f64) -> Word {
    solve::<true>(x, y, phi)
}

fn solve<const PRUNE: bool>(x: f64, y: f64, phi: f64) -> Word {
    let phi = mod2pi(phi);
    let (s, c) = phi.sin_cos();
    let g = Goal { x, y, phi, s, c };
    let search = Search::<PRUNE> { turn: phi.abs() };
    // OMPL's empty path: longer than any word.
    let mut best = Word {
        word: 0,
        params: [0.0; 5],
        length: f64::MAX,
    };
    search.csc(g, &mut best);
    search.ccc(g, &mut best);
    search.cccc(g, &mut best);
    search.ccsc(g, &mut best);
    search.ccscc(g, &mut best);
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// The lower bounds skip only words that could not have won: the pruned
    /// search returns the exhaustive search's word, bit for bit.
    #[test]
    fn pruning_changes_nothing() {
        let mut rng = SplitMix64::new(23);
        for k in 0..200_000 {
            let reach = [0.5, 3.0, 10.0, 100.0][k % 4];
            let (x, y) = (rng.range(-reach, reach), rng.range(-reach, reach));
            let phi = rng.range(-4.0 * PI, 4.0 * PI);
            let (a, b) = (solve::<true>(x, y, phi), solve::<false>(x, y, phi));
            assert_eq!(a, b, "at ({x}, {y}, {phi})");
            assert!(a.length < f64::MAX, "no word reaches ({x}, {y}, {phi})");
        }
    }

    #[test]
    fn mod2pi_is_fmods() {
        let mut rng = SplitMix64::new(5);
        for _ in 0..100_000 {
            let x = rng.range(-40.0, 40.0);
            let mut v = x % TAU;
            if v < -PI {
                v += TAU;
            } else if v > PI {
                v -= TAU;
            }
            assert_eq!(mod2pi(x).to_bits(), v.to_bits(), "{x}");
        }
    }
}
