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
//! Speed: sin φ and cos φ are computed once (the variants only flip signs).
//! The CSC words are bounded from below first and computed best first until
//! one gives a word, whose length bounds the rest. Every other candidate is
//! then bounded from below: CCSC and CCSCC first by pairs of variants (one
//! test for both), then each coarsely, then with a polynomial arc tangent
//! where the coarse bound is within reach (less a margin for its error). A
//! variant and its timeflip are bounded together (they share a centre
//! vector's norm and products);
//! the formulas themselves run only for candidates whose bound is below the
//! shortest length found, best first, and OMPL's order is replayed on those.
//! A candidate skipped that way is longer than the winner by the margin, so
//! the result is the exhaustive one, bit for bit (a test compares both).

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

// The twelve base formulas, as OMPL writes them. With `PRUNE` they give up
// early where the result is certain to be rejected (a parameter of the wrong
// sign), which changes no result (`pruning_changes_nothing`).

// formula 8.1
#[inline]
fn lp_sp_lp<const PRUNE: bool>(g: Goal) -> Option<(f64, f64, f64)> {
    let (xi, eta) = (g.x - g.s, g.y - 1.0 + g.c);
    let u = (xi * xi + eta * eta).sqrt();
    // t = atan2(eta, xi) ≥ −ZERO needs eta ≥ about 0.
    if PRUNE && eta < -1e-14 * u {
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
fn lp_sp_rp(g: Goal) -> Option<(f64, f64, f64)> {
    let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
    let u1 = xi * xi + eta * eta;
    if u1 >= 4.0 {
        let u = (u1 - 4.0).sqrt();
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
fn lp_rm_l(g: Goal) -> Option<(f64, f64, f64)> {
    let (xi, eta) = (g.x - g.s, g.y - 1.0 + g.c);
    let u1 = (xi * xi + eta * eta).sqrt();
    if u1 <= 4.0 {
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
fn lp_rup_lum_rm(g: Goal) -> Option<(f64, f64, f64)> {
    let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
    let rho = 0.25 * (2.0 + (xi * xi + eta * eta).sqrt());
    if rho <= 1.0 {
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
fn lp_rum_lum_rp(g: Goal) -> Option<(f64, f64, f64)> {
    let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
    let rho = (20.0 - xi * xi - eta * eta) / 16.0;
    if (0.0..=1.0).contains(&rho) {
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
fn lp_rm_sm_lm<const PRUNE: bool>(g: Goal) -> Option<(f64, f64, f64)> {
    let (xi, eta) = (g.x - g.s, g.y - 1.0 + g.c);
    let rho = (xi * xi + eta * eta).sqrt();
    if rho >= 2.0 {
        let r = (rho * rho - 4.0).sqrt();
        let u = 2.0 - r;
        if PRUNE && u > ZERO {
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
fn lp_rm_sm_rm<const PRUNE: bool>(g: Goal) -> Option<(f64, f64, f64)> {
    let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
    let rho = (eta * eta + xi * xi).sqrt();
    if rho >= 2.0 {
        let u = 2.0 - rho;
        if PRUNE && u > ZERO {
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
fn lp_rm_s_lm_rp(g: Goal) -> Option<(f64, f64, f64)> {
    let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
    let rho = (xi * xi + eta * eta).sqrt();
    if rho >= 2.0 {
        let u = 4.0 - (rho * rho - 4.0).sqrt();
        if u <= ZERO {
            let t = mod2pi(((4.0 - u) * xi - 2.0 * eta).atan2(-2.0 * xi + (u - 4.0) * eta));
            let v = mod2pi(t - g.phi);
            if t >= -ZERO && v >= -ZERO {
                return Some((t, u, v));
            }
        }
    }
    None
}

/// The number of candidate words: CSC 8, CCC 8, CCCC 8, CCSC 16, CCSCC 4.
const CANDIDATES: usize = 44;

/// The goal and its variants, as the candidates use them: the goal, its
/// timeflip, reflect and both, then the same of the goal seen backwards.
type Variants = [Goal; 8];

fn variants(g: Goal) -> Variants {
    let b = backwards(g);
    [
        g,
        g.timeflip(),
        g.reflect(),
        g.both(),
        b,
        b.timeflip(),
        b.reflect(),
        b.both(),
    ]
}

/// Candidate `k`'s formula (t, u, v), `k` in OMPL's order: 0–3 8.1 and
/// 4–7 8.2 on the four variants; 8–11 8.3, 12–15 8.3 backwards; 16–19 8.7,
/// 20–23 8.8; 24–27 8.9, 28–31 8.10, 32–35 8.9 backwards, 36–39 8.10
/// backwards; 40–43 8.11.
#[inline]
fn formula<const PRUNE: bool>(k: usize, v: &Variants) -> Option<(f64, f64, f64)> {
    match k {
        0..4 => lp_sp_lp::<PRUNE>(v[k]),
        4..8 => lp_sp_rp(v[k - 4]),
        8..16 => lp_rm_l(v[k - 8]),
        16..20 => lp_rup_lum_rm(v[k - 16]),
        20..24 => lp_rum_lum_rp(v[k - 20]),
        24..28 => lp_rm_sm_lm::<PRUNE>(v[k - 24]),
        28..32 => lp_rm_sm_rm::<PRUNE>(v[k - 28]),
        32..36 => lp_rm_sm_lm::<PRUNE>(v[k - 28]),
        36..40 => lp_rm_sm_rm::<PRUNE>(v[k - 32]),
        _ => lp_rm_s_lm_rp(v[k - 40]),
    }
}

/// The length of candidate `k`'s word with parameters (t, u, v), the fixed
/// quarter turns included (to rounding; only compared with margins).
#[inline]
fn total(k: usize, (t, u, v): (f64, f64, f64)) -> f64 {
    match k {
        0..16 => t.abs() + u.abs() + v.abs(),
        16..24 => t.abs() + 2.0 * u.abs() + v.abs(),
        24..40 => t.abs() + u.abs() + v.abs() + 0.5 * PI,
        _ => t.abs() + u.abs() + v.abs() + PI,
    }
}

/// OMPL's search over the candidates in its order: a word replaces the best
/// so far only when strictly shorter, lengths compared as OMPL compares
/// them (per family, without the fixed quarter turns). Fed the candidates
/// that gave a word, in increasing `k`; a candidate left out is one that
/// gave none, so feeding only the few computed ones is OMPL's whole search.
struct Replay {
    best: Word,
    /// The family of the last candidate offered (5 before the first).
    family: usize,
    /// The best length as this family compares it.
    lmin: f64,
}

impl Replay {
    fn new() -> Self {
        Replay {
            // OMPL's empty path: longer than any word.
            best: Word {
                word: 0,
                params: [0.0; 5],
                length: f64::MAX,
            },
            family: 5,
            lmin: f64::MAX,
        }
    }

    /// Candidate `k`'s word (t, u, v), after every smaller `k`'s.
    #[inline]
    fn offer(&mut self, k: usize, (t, u, v): (f64, f64, f64)) {
        // CSC, CCC, CCCC (8.7 with the two middle arcs of opposite signs,
        // then 8.8 with the same signs), CCSC, CCSCC.
        let (family, start) = match k {
            0..8 => (0, 0),
            8..16 => (1, 8),
            16..24 => (2, 16),
            24..40 => (3, 24),
            _ => (4, 40),
        };
        if family != self.family {
            self.family = family;
            // CCSC's and CCSCC's lengths leave out their one or two fixed
            // quarter turns, as OMPL's do.
            self.lmin = match family {
                3 => self.best.length - 0.5 * PI,
                4 => self.best.length - PI,
                _ => self.best.length,
            };
        }
        let l = if family == 2 {
            t.abs() + 2.0 * u.abs() + v.abs()
        } else {
            t.abs() + u.abs() + v.abs()
        };
        // Only a strictly shorter word replaces the best (OMPL's `>`).
        if self.lmin.partial_cmp(&l) != Some(std::cmp::Ordering::Greater) {
            return;
        }
        self.lmin = l;
        let i = k - start;
        // Timeflip and both reverse the word: every odd variant.
        let flip = if i.is_multiple_of(2) { 1.0 } else { -1.0 };
        let q = -0.5 * PI;
        let (word, p) = match family {
            0 => ([14, 14, 15, 15, 12, 12, 13, 13][i], [t, u, v, 0.0, 0.0]),
            1 => {
                let (a, c) = if i >= 4 { (v, t) } else { (t, v) };
                ([0, 0, 1, 1, 0, 0, 1, 1][i], [a, u, c, 0.0, 0.0])
            }
            2 => {
                let u2 = if i >= 4 { u } else { -u };
                ([2, 2, 3, 3, 2, 2, 3, 3][i], [t, u, u2, v, 0.0])
            }
            3 => {
                let word = [4, 4, 5, 5, 8, 8, 9, 9, 6, 6, 7, 7, 10, 10, 11, 11][i];
                let p = if i >= 8 {
                    [v, u, q, t, 0.0]
                } else {
                    [t, q, u, v, 0.0]
                };
                (word, p)
            }
            _ => ([16, 16, 17, 17][i], [t, q, u, q, v]),
        };
        let mut p = p.map(|a| flip * a);
        // OMPL's unused slots stay +0 (CCSC's fifth is flipped, as OMPL's).
        match family {
            0 | 1 => (p[3], p[4]) = (0.0, 0.0),
            2 => p[4] = 0.0,
            _ => {}
        }
        self.best = Word::new(word, p);
    }
}

/// OMPL's search over all the candidates, `f(k)` candidate `k`'s formula.
fn ompl_order(mut f: impl FnMut(usize) -> Option<(f64, f64, f64)>) -> Word {
    let mut replay = Replay::new();
    for k in 0..CANDIDATES {
        if let Some(r) = f(k) {
            replay.offer(k, r);
        }
    }
    replay.best
}

/// atan on [0, 1]: an odd polynomial of degree 9, |error| < 1.2e-5.
#[inline]
fn atan01(z: f64) -> f64 {
    let w = z * z;
    z * (0.999_866_308_210_730_6
        + w * (-0.330_304_484_949_521_5
            + w * (0.180_158_167_053_336_73
                + w * (-0.085_154_798_710_814_05 + w * 0.020_844_406_034_172_508))))
}

/// atan2 to within 1.3e-5 rad (as an angle: the lower bounds use it only
/// modulo 2π).
#[inline]
fn atan2_approx(y: f64, x: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    let steep = ay > ax;
    let (lo, hi) = if steep { (ax, ay) } else { (ay, ax) };
    let z = if hi > 0.0 { lo / hi } else { 0.0 };
    let mut a = atan01(z);
    if steep {
        a = FRAC_PI_2 - a;
    }
    if x < 0.0 {
        a = PI - a;
    }
    if y < 0.0 { -a } else { a }
}

/// The distance of two angles on the circle, |a − b| wrapped to [0, π]
/// (1-Lipschitz in each: an error in an angle moves it no more).
#[inline]
fn gap(a: f64, b: f64) -> f64 {
    // Rounds to the nearest integer by the float format (1.5 · 2⁵²).
    const ROUND: f64 = 6_755_399_441_055_744.0;
    let d = a - b;
    let k = (d * (1.0 / TAU) + ROUND) - ROUND;
    (d - k * TAU).abs()
}

/// Whether the angle `a` (approximate, modulo 2π) is certainly a negative
/// parameter in (−π, 0): clear of both ends by far more than the error.
#[inline]
fn surely_negative(a: f64) -> bool {
    const ROUND: f64 = 6_755_399_441_055_744.0;
    let w = a - ((a * (1.0 / TAU) + ROUND) - ROUND) * TAU;
    w < -1e-3 && w > -PI + 1e-3
}

/// What a lower bound leaves for the approximations (each formula's length
/// moves at most 10 × 1.3e-5 with them) and for the formulas' own rounding.
#[inline]
fn lower(l: f64) -> f64 {
    l - 5e-4 - 1e-9 * l
}

/// The turn of an LSL word (8.1) ending at heading φ: its two arcs turn
/// t, v ≥ 0 with t + v ≡ φ (mod 2π), so t + v is φ taken into [0, 2π).
#[inline]
fn lsl_arcs(phi: f64) -> f64 {
    if phi < -1e-9 { phi + TAU } else { phi.max(0.0) }
}

/// The approximate arc tangents the fine bounds of one goal share,
/// computed on first use (NaN until then).
///
/// Each variant has two centre vectors, A = (x − sin φ, y − 1 + cos φ)
/// (formulas 8.1, 8.3, 8.9) and B = (x + sin φ, y − 1 − cos φ) (8.2, 8.7,
/// 8.8, 8.10, 8.11). Timeflip negates x and sin φ, so it negates the
/// first coordinate of both vectors exactly (IEEE negation commutes with
/// the sums) and leaves their norms bit for bit: the timeflip's angle is
/// π minus the variant's, and the pairs (goal, timeflip) and (reflect,
/// both) cost one arc tangent each. Every angle here is used only modulo
/// 2π, through [`gap`] and [`surely_negative`], and `π − a` is within one
/// rounding of the mirrored vector's angle, far inside the margin of
/// [`lower`]. (8.2, 8.9 and 8.11 take their t in one arc tangent of the
/// vector their coarse bound rotates, not from these.)
struct Angles {
    /// The A and B vectors' angles, per pair of variants (goal, reflect,
    /// backwards, backwards reflect).
    a: [f64; 4],
    b: [f64; 4],
}

impl Angles {
    fn new() -> Self {
        Angles {
            a: [f64::NAN; 4],
            b: [f64::NAN; 4],
        }
    }
}

/// `slot`, computed by `f` on first use.
#[inline(always)]
fn memo(slot: &mut f64, f: impl FnOnce() -> f64) -> f64 {
    if slot.is_nan() {
        *slot = f();
    }
    *slot
}

/// The approximate angle of variant `i`'s centre vector (xi, eta) from the
/// pair's shared one in `slot`: odd variants (timeflip, both) are the even
/// ones mirrored, xi negated.
#[inline(always)]
fn centre_angle(slot: &mut f64, i: usize, xi: f64, eta: f64) -> f64 {
    let odd = i % 2 == 1;
    let base = memo(slot, || atan2_approx(eta, if odd { -xi } else { xi }));
    if odd { PI - base } else { base }
}

/// A lower bound on candidate `k`'s length (quarter turns included), +∞
/// where its formula certainly gives no word. Quantities that decide
/// whether a formula applies are computed exactly as the formula does.
///
/// Coarse (`FINE` false): from the distance `d` to the goal, the heading
/// change and the word's straight, no arc tangent. Fine: what the formula
/// computes, with an approximate arc tangent (an angle's error changes the
/// length by at most a few times as much, the arcs being distances on the
/// circle), less the margin of [`lower`].
#[inline(always)]
fn bound<const FINE: bool>(k: usize, v: &Variants, d: f64, angles: &mut Angles) -> f64 {
    const INF: f64 = f64::INFINITY;
    // The variant, and its pair of variants (see [`Angles`]).
    let i = match k {
        12..16 | 32..40 => 4 + k % 4,
        _ => k % 4,
    };
    let pair = i / 2;
    let g = v[i];
    let phi = g.phi;
    let turn = phi.abs();
    match k {
        // The A formulas: 8.1, 8.3, 8.9.
        0..4 | 8..16 | 24..28 | 32..36 => {
            let (xi, eta) = (g.x - g.s, g.y - 1.0 + g.c);
            let an = (xi * xi + eta * eta).sqrt();
            match k {
                0..4 => csc_pair::<false>(k & !1, v, d)[k & 1],
                8..16 => {
                    if an > 4.0 {
                        INF
                    } else if !FINE {
                        lower((0.5 * an).max(turn).max(d))
                    } else {
                        let q = 0.25 * an;
                        let u = 2.0 * atan2_approx(q, ((1.0 - q) * (1.0 + q)).sqrt());
                        let theta = centre_angle(&mut angles.a[pair], i, xi, eta);
                        let t = theta - 0.5 * u + PI;
                        if surely_negative(t) {
                            return INF;
                        }
                        lower(u + gap(t, 0.0) + gap(t + u, phi))
                    }
                }
                _ => {
                    if an < 2.0 {
                        return INF;
                    }
                    let r = (an * an - 4.0).sqrt();
                    let u = 2.0 - r;
                    if u > ZERO {
                        INF
                    } else if !FINE {
                        coarse_pair(k & !1, v, d, INF)[k & 1]
                    } else {
                        // The angle of (ct, st) of the coarse bound: one
                        // approximate arc tangent, not two.
                        let t = atan2_approx(r * xi - 2.0 * eta, -2.0 * xi - r * eta);
                        if surely_negative(t) || surely_negative(0.5 * PI - phi + t) {
                            return INF;
                        }
                        lower(0.5 * PI + u.abs() + gap(t, 0.0) + gap(t, phi - 0.5 * PI))
                    }
                }
            }
        }
        // The B formulas: 8.2, 8.7, 8.8, 8.10, 8.11.
        _ => {
            let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
            let b2 = xi * xi + eta * eta;
            let bn = b2.sqrt();
            match k {
                4..8 => csc_pair::<FINE>(k & !1, v, d)[k & 1],
                16..20 => {
                    let rho = 0.25 * (2.0 + bn);
                    if rho > 1.0 {
                        INF
                    } else if !FINE {
                        lower(turn.max(d))
                    } else {
                        // u = acos ρ; tau = θ + π/2 + u, omega = tau − 2u − φ.
                        let u = atan2_approx(((1.0 - rho) * (1.0 + rho)).sqrt(), rho);
                        if bn < 1e-4 {
                            // The formula's angle is ill-conditioned here.
                            lower(2.0 * u)
                        } else {
                            let theta = centre_angle(&mut angles.b[pair], i, xi, eta);
                            let t = theta + 0.5 * PI + u;
                            if surely_negative(t) || surely_negative(phi - t + 2.0 * u) {
                                return INF;
                            }
                            lower(2.0 * u + gap(t, 0.0) + gap(t - 2.0 * u, phi))
                        }
                    }
                }
                20..24 => {
                    let rho = (20.0 - xi * xi - eta * eta) / 16.0;
                    if !(0.0..=1.0).contains(&rho) {
                        INF
                    } else if !FINE {
                        lower(turn.max(d))
                    } else {
                        // u = −acos ρ; tau = θ − angle(sin u, cos u − 2),
                        // omega = tau − φ.
                        let su = ((1.0 - rho) * (1.0 + rho)).sqrt();
                        let u = atan2_approx(su, rho);
                        let theta = centre_angle(&mut angles.b[pair], i, xi, eta);
                        let t = theta - atan2_approx(rho - 2.0, -su);
                        if surely_negative(t) || surely_negative(t - phi) {
                            return INF;
                        }
                        lower(2.0 * u + gap(t, 0.0) + gap(t, phi))
                    }
                }
                28..32 | 36..40 => {
                    if bn < 2.0 {
                        return INF;
                    }
                    let u = 2.0 - bn;
                    if u > ZERO {
                        INF
                    } else if !FINE {
                        coarse_pair(k & !1, v, d, INF)[k & 1]
                    } else {
                        let theta = centre_angle(&mut angles.b[pair], i, xi, eta);
                        let t = theta + 0.5 * PI;
                        if surely_negative(t) || surely_negative(phi - t - 0.5 * PI) {
                            return INF;
                        }
                        lower(0.5 * PI + u.abs() + gap(t, 0.0) + gap(t, phi - 0.5 * PI))
                    }
                }
                _ => {
                    if bn < 2.0 {
                        return INF;
                    }
                    let u = 4.0 - (bn * bn - 4.0).sqrt();
                    if u > ZERO {
                        INF
                    } else if !FINE {
                        coarse_pair(k & !1, v, d, INF)[k & 1]
                    } else {
                        // The formula's own arc tangent, approximated.
                        let t =
                            atan2_approx((4.0 - u) * xi - 2.0 * eta, -2.0 * xi + (u - 4.0) * eta);
                        if surely_negative(t) || surely_negative(t - phi) {
                            return INF;
                        }
                        lower(PI + u.abs() + gap(t, 0.0) + gap(t, phi))
                    }
                }
            }
        }
    }
}

/// The lower bounds of CSC candidates `k` and `k + 1` (`k` even, 0–6), a
/// variant and its timeflip (see [`coarse_pair`]: the same centre vector
/// but for the sign of its first coordinate, headings ±φ); +∞ where a
/// formula certainly gives no word. Quantities that decide whether a
/// formula applies are computed exactly as the formula does. LSR's fine
/// bound (`FINE`) follows its sign tests, from the same rotated vector.
#[inline(always)]
fn csc_pair<const FINE: bool>(k: usize, v: &Variants, d: f64) -> [f64; 2] {
    const INF: f64 = f64::INFINITY;
    let (g, h) = (v[k % 4], v[k % 4 + 1]);
    if k < 4 {
        // 8.1: t = atan2(eta, xi) must be in [0, π] and v = φ − t in
        // [0, π] (sin v = sin(φ − t) ≥ 0, sin φ·xi − cos φ·eta ≥ 0 over
        // |A|); both tests are the same for the timeflip (xi and sin φ
        // negated). The arcs make up φ (see `lsl_arcs`).
        let (xi, eta) = (g.x - g.s, g.y - 1.0 + g.c);
        let an = (xi * xi + eta * eta).sqrt();
        if eta < -1e-14 * an || g.s * xi - g.c * eta < -1e-6 * an {
            [INF; 2]
        } else {
            [lower(an + lsl_arcs(g.phi)), lower(an + lsl_arcs(h.phi))]
        }
    } else {
        // 8.2: t's direction is B turned by atan2(2, u), whose cosine and
        // sine are u/|B| and 2/|B|: (cos t, sin t) = (ct, st) / |B|². t and
        // v = t − φ must be in [0, π] (sines ≥ 0), to within the tolerance
        // argued at `coarse_pair`. The timeflip's (ct, st) is the same of
        // −xi.
        let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
        let b2 = xi * xi + eta * eta;
        if b2 < 4.0 {
            return [INF; 2];
        }
        let u = (b2 - 4.0).sqrt();
        let (ex, ue, ux, ee) = (2.0 * xi, u * eta, u * xi, 2.0 * eta);
        let tol = 1e-9 * b2;
        let l = lower((u + g.phi.abs()).max(d));
        let one = |st: f64, ct: f64, g: Goal| {
            if st < -tol || st * g.c - ct * g.s < -tol {
                INF
            } else if !FINE {
                l
            } else {
                // The angle of (ct, st), approximated.
                let t = atan2_approx(st, ct);
                if surely_negative(t) || surely_negative(t - g.phi) {
                    INF
                } else {
                    lower(u + gap(t, 0.0) + gap(t, g.phi))
                }
            }
        };
        [one(ex + ue, ux - ee, g), one(-ex + ue, -ux - ee, h)]
    }
}

/// The coarse lower bounds of CCSC or CCSCC candidates `k` and `k + 1`
/// (`k` even, 24–42), the two variants of a pair (see [`Angles`]), +∞
/// where a formula certainly gives no word; where even the pair's common
/// bound is above `upper`, that bound for both, without their sign tests.
/// Quantities that decide whether a formula applies are computed exactly
/// as the formula does.
///
/// Both variants have the same centre vector but for the sign of its first
/// coordinate (timeflip negates x and sin φ), so the same norm bit for bit,
/// and headings ±φ. Each word's length is its arcs |t| + |v|, its straight
/// |u| and its fixed quarter turns (π/2 for CCSC, π for CCSCC). The arcs
/// make up the heading: t + v ≡ ±φ − π/2 (8.9) or t − v ≡ ±φ − π/2 (8.10),
/// so |t| + |v| ≥ gap(±φ, π/2) ≥ ||φ| − π/2| (φ in [−π, π]); t − v ≡ ±φ
/// (8.11), so |t| + |v| ≥ |φ|. And any path is at least as long as the sum
/// of its chords, which is at least the distance d: an arc of angle θ
/// (radius 1) has chord 2 sin(θ/2) ≤ θ, and a quarter turn's chord is √2,
/// so a CCSC word is at least d + π/2 − √2 long, a CCSCC word
/// d + π − 2√2. [`lower`] leaves the margin for the roundings.
///
/// The sign tests: t and v must be in the formula's ranges; their sines
/// are read off the centre vector (cos t and sin t without an arc tangent,
/// v's sine from φ's), and a sine below −1e-9 of the vector's scale is an
/// angle that far inside (−π, 0), beyond ZERO and every rounding of the
/// formula's angles.
#[inline(always)]
fn coarse_pair(k: usize, v: &Variants, d: f64, upper: f64) -> [f64; 2] {
    const INF: f64 = f64::INFINITY;
    // The chord excess of a quarter turn: π/2 − √2.
    const QUARTER: f64 = 0.5 * PI - std::f64::consts::SQRT_2;
    let i = match k {
        32..40 => 4 + k % 4,
        _ => k % 4,
    };
    // The variant and its timeflip.
    let (g, h) = (v[i], v[i + 1]);
    let heading = (g.phi.abs() - 0.5 * PI).abs();
    match k {
        // 8.9: u = 2 − √(|A|² − 4).
        24..28 | 32..36 => {
            let (xi, eta) = (g.x - g.s, g.y - 1.0 + g.c);
            let an = (xi * xi + eta * eta).sqrt();
            if an < 2.0 {
                return [INF; 2];
            }
            let r = (an * an - 4.0).sqrt();
            let u = 2.0 - r;
            if u > ZERO {
                return [INF; 2];
            }
            let straight = 0.5 * PI + u.abs();
            let pair = lower((straight + heading).max(d + QUARTER));
            if pair > upper {
                return [pair; 2];
            }
            // t's direction is A turned by atan2(r, −2), whose cosine and
            // sine are −2/|A| and r/|A|: (cos t, sin t) = (ct, st) / |A|².
            // The formula needs t ∈ [0, π] (sin t ≥ 0) and v = φ − π/2 − t
            // in [−π, 0] (sin v = −cos(φ − t) ≤ 0). The timeflip's (ct, st)
            // is the same of −xi.
            let (rx, ey, ex, ry) = (r * xi, 2.0 * eta, 2.0 * xi, r * eta);
            let tol = 1e-9 * (an * an);
            let one = |st: f64, ct: f64, g: Goal| {
                if st < -tol || g.c * ct + g.s * st < -tol {
                    INF
                } else {
                    lower((straight + gap(g.phi, 0.5 * PI)).max(d)).max(pair)
                }
            };
            [one(rx - ey, -ex - ry, g), one(-rx - ey, ex - ry, h)]
        }
        // 8.10: u = 2 − |B|.
        28..32 | 36..40 => {
            let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
            let bn = (xi * xi + eta * eta).sqrt();
            if bn < 2.0 {
                return [INF; 2];
            }
            let u = 2.0 - bn;
            if u > ZERO {
                return [INF; 2];
            }
            let straight = 0.5 * PI + u.abs();
            let pair = lower((straight + heading).max(d + QUARTER));
            if pair > upper {
                return [pair; 2];
            }
            // t = atan2(xi, −eta) must be in [0, π] (xi ≥ 0) and
            // v = t + π/2 − φ in [−π, 0] (sin v = cos(t − φ) ≤ 0); the
            // latter, sin φ·xi − cos φ·eta ≤ 0 over |B|, is the same for
            // the timeflip (xi and sin φ negated).
            let tol = 1e-9 * bn;
            if g.s * xi - g.c * eta > tol {
                return [INF; 2];
            }
            let one = |xi: f64, g: Goal| {
                if xi < -tol {
                    INF
                } else {
                    lower((straight + gap(g.phi, 0.5 * PI)).max(d)).max(pair)
                }
            };
            [one(xi, g), one(-xi, h)]
        }
        // 8.11: u = 4 − √(|B|² − 4).
        _ => {
            let (xi, eta) = (g.x + g.s, g.y - 1.0 - g.c);
            let bn = (xi * xi + eta * eta).sqrt();
            if bn < 2.0 {
                return [INF; 2];
            }
            let u = 4.0 - (bn * bn - 4.0).sqrt();
            if u > ZERO {
                return [INF; 2];
            }
            let pair = lower((PI + u.abs() + g.phi.abs()).max(d + 2.0 * QUARTER));
            if pair > upper {
                return [pair; 2];
            }
            // t is the angle of (ct, st), the formula's own atan2
            // arguments, of norm √((4 − u)² + 4)·|B| ≤ (6 − u)·|B|; t and
            // v = t − φ must be in [0, π] (sines ≥ 0). The timeflip's
            // (ct, st) is the same of −xi.
            let (px, ey, ex, qy) = ((4.0 - u) * xi, 2.0 * eta, 2.0 * xi, (u - 4.0) * eta);
            let tol = 1e-9 * ((6.0 - u) * bn);
            let one = |st: f64, ct: f64, g: Goal| {
                if st < -tol || st * g.c - ct * g.s < -tol {
                    INF
                } else {
                    pair
                }
            };
            [one(px - ey, -ex + qy, g), one(-px - ey, ex + qy, h)]
        }
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

/// Beyond this distance (in radii) no CCC or CCCC word applies.
const CCC_REACH: f64 = 6.5;

/// How many candidates the fast search keeps; more (ties of many words)
/// goes the exhaustive way.
const KEEP: usize = 8;

fn solve<const PRUNE: bool>(x: f64, y: f64, phi: f64) -> Word {
    let phi = mod2pi(phi);
    let (s, c) = phi.sin_cos();
    let v = variants(Goal { x, y, phi, s, c });
    if !PRUNE {
        return ompl_order(|k| formula::<false>(k, &v));
    }
    // Lower bounds, coarse then fine where the coarse one does not settle
    // it; the CSC words first (they win far from the start, and the best of
    // them bounds the rest), then every other candidate, its coarse bound
    // first and its fine one only when the coarse one is below the shortest
    // CSC length found; those whose bound is still below it are computed,
    // best first, while their bound is below the shortest length found. A
    // candidate left out is longer than that by the margin of `lower`, so
    // it could not win in OMPL's order either, nor change how the others
    // compare.
    let d = (x * x + y * y).sqrt();
    let mut lb = [f64::INFINITY; CANDIDATES];
    let mut angles = Angles::new();
    // By pairs of variants, fine (the LSL bounds are fine already). The
    // macros below are unrolled, so that each candidate's bound is
    // specialised (and the shared norms computed once).
    [lb[0], lb[1]] = csc_pair::<true>(0, &v, d);
    [lb[2], lb[3]] = csc_pair::<true>(2, &v, d);
    [lb[4], lb[5]] = csc_pair::<true>(4, &v, d);
    [lb[6], lb[7]] = csc_pair::<true>(6, &v, d);
    let mut found = Found {
        kept: [(0.0, 0.0, 0.0); KEEP],
        kept_k: [0; KEEP],
        n: 0,
        kept_mask: 0,
        upper: f64::INFINITY,
    };
    // The CSC candidates not yet computed whose bound is finite (a bit
    // each), computed best first until one gives a word.
    let mut csc = 0u64;
    for (k, &l) in lb[..8].iter().enumerate() {
        if l < f64::INFINITY {
            csc |= 1 << k;
        }
    }
    while found.upper == f64::INFINITY && csc != 0 {
        let k = best(csc, &lb);
        csc &= !(1 << k);
        found.eval(k, &v);
    }
    // The candidates whose bound is still within reach (a bit set in
    // `open`); `upper` is finite, so that +∞ bounds are never in reach.
    let upper = found.upper.min(f64::MAX);
    let mut open = 0u64;
    let mut rest = csc;
    while rest != 0 {
        let k = rest.trailing_zeros() as usize;
        rest &= rest - 1;
        if lb[k] <= upper {
            open |= 1 << k;
        }
    }
    // Candidate `k`'s fine bound where its coarse one is within reach.
    macro_rules! fine {
        ($($k:literal $coarse:expr)*) => { $(
            if $coarse <= upper {
                let l = bound::<true>($k, &v, d, &mut angles);
                if l <= upper {
                    lb[$k] = l;
                    open |= 1 << $k;
                }
            }
        )* };
    }
    macro_rules! rest {
        ($($k:literal)*) => { $( fine!($k bound::<false>($k, &v, d, &mut angles)); )* };
    }
    // CCSC and CCSCC by pairs of variants, one test first for both.
    macro_rules! pair {
        ($($k:literal $k1:literal)*) => { $(
            let coarse = coarse_pair($k, &v, d, upper);
            fine!($k coarse[0] $k1 coarse[1]);
        )* };
    }
    // The CCC and CCCC words (8–23) by one test: their formulas need a
    // centre vector no longer than √20 < 4.5 (8.3: A ≤ 4; 8.7: B ≤ 2;
    // 8.8: B² ≤ 20). Both centre vectors are the goal less a point within
    // 2 of the origin ((sin φ, 1 − cos φ) and (−sin φ, 1 + cos φ)), and the
    // goal seen backwards is the goal rotated, so every centre vector is
    // at least d − 2 long (to a few roundings): beyond 6.5 radii none
    // applies.
    if d <= CCC_REACH {
        rest!(8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23);
    }
    pair!(24 25 26 27 28 29 30 31 32 33 34 35 36 37 38 39 40 41 42 43);
    while open != 0 {
        let k = best(open, &lb);
        if lb[k] > found.upper {
            break;
        }
        open &= !(1 << k);
        if !found.eval(k, &v) {
            return ompl_order(|k| formula::<true>(k, &v));
        }
    }
    // OMPL's order replayed on the few candidates that gave a word.
    let kept_k = &found.kept_k[..found.n];
    let mut replay = Replay::new();
    let mut rest = found.kept_mask;
    while rest != 0 {
        let k = rest.trailing_zeros() as usize;
        rest &= rest - 1;
        if let Some(j) = kept_k.iter().position(|&e| usize::from(e) == k) {
            replay.offer(k, found.kept[j]);
        }
    }
    replay.best
}

/// The candidate of `set` (a bit each, not empty) with the least bound,
/// the first of equal ones.
#[inline]
fn best(set: u64, lb: &[f64; CANDIDATES]) -> usize {
    let (mut k, mut rest) = (set.trailing_zeros() as usize, set);
    rest &= rest - 1;
    while rest != 0 {
        let i = rest.trailing_zeros() as usize;
        rest &= rest - 1;
        if lb[i] < lb[k] {
            k = i;
        }
    }
    k
}

/// The candidates computed so far that gave a word, and the shortest
/// length among them.
struct Found {
    /// Their words, and which candidates they are (apart, so that the
    /// whole is small enough to be cleared without a call to `memset`).
    kept: [(f64, f64, f64); KEEP],
    kept_k: [u8; KEEP],
    n: usize,
    /// Which candidates are in `kept`, one bit each.
    kept_mask: u64,
    upper: f64,
}

impl Found {
    /// Computes candidate `k`; false when more than [`KEEP`] gave words.
    #[inline]
    fn eval(&mut self, k: usize, v: &Variants) -> bool {
        if let Some(r) = formula::<true>(k, v) {
            if self.n == KEEP {
                return false;
            }
            self.kept[self.n] = r;
            self.kept_k[self.n] = k as u8;
            self.n += 1;
            self.kept_mask |= 1 << k;
            self.upper = self.upper.min(total(k, r));
        }
        true
    }
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

    /// Every lower bound is below its formula's length, at every scale and
    /// on the special headings (0, ±π/2, ±π) and positions (axes, circles'
    /// centres) where angles wrap.
    #[test]
    fn bounds_are_below_the_formulas() {
        let mut rng = SplitMix64::new(11);
        let mut worst = f64::INFINITY;
        for k in 0..400_000 {
            let reach = [0.01, 0.5, 3.0, 10.0, 100.0, 1e6][k % 6];
            let (mut x, mut y) = (rng.range(-reach, reach), rng.range(-reach, reach));
            let mut phi = rng.range(-PI, PI);
            // Near the boundaries: a distance or centre vector of 2, 4,
            // √20 or 6.5 radii, a heading by 0, ±π/2 or ±π.
            let near = [2.0, 4.0, 20f64.sqrt(), 6.5][k % 4] * (1.0 + rng.range(-1e-9, 1e-9));
            let a = rng.range(-PI, PI);
            let (ca, sa) = (near * a.cos(), near * a.sin());
            match (k / 6) % 12 {
                0 => phi = [0.0, FRAC_PI_2, -FRAC_PI_2, PI, -PI][k % 5],
                1 => y = 0.0,
                2 => x = 0.0,
                3 => (x, y) = (phi.sin(), 1.0 - phi.cos()),
                4 => (x, y) = (-phi.sin(), -1.0 + phi.cos()),
                5 => (x, y) = (ca, sa),
                // The A and B centre vectors (see `Angles`) of that length.
                6 => (x, y) = (phi.sin() + ca, 1.0 - phi.cos() + sa),
                7 => (x, y) = (-phi.sin() + ca, 1.0 + phi.cos() + sa),
                8 => {
                    phi = [0.0, FRAC_PI_2, -FRAC_PI_2, PI, -PI][k % 5] + rng.range(-1e-9, 1e-9);
                }
                _ => {}
            }
            let (s, c) = phi.sin_cos();
            let v = variants(Goal { x, y, phi, s, c });
            let d = (x * x + y * y).sqrt();
            // One goal's bounds share their angles, as in the search.
            let mut angles = Angles::new();
            for i in 0..CANDIDATES {
                if let Some(r) = formula::<false>(i, &v) {
                    let l = total(i, r);
                    let coarse = bound::<false>(i, &v, d, &mut angles);
                    let fine = bound::<true>(i, &v, d, &mut angles);
                    // CCSC and CCSCC also by their pair's common bound.
                    let pair = if i >= 24 {
                        coarse_pair(i & !1, &v, d, -1.0)[i & 1]
                    } else {
                        f64::NEG_INFINITY
                    };
                    for b in [coarse, fine, pair] {
                        assert!(b <= l, "candidate {i} at ({x}, {y}, {phi}): {b} > {l}");
                        worst = worst.min(l - b);
                    }
                }
            }
        }
        assert!(worst >= 0.0);
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
