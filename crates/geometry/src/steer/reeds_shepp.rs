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
//! Every candidate is first bounded from below by what its formula computes
//! with a polynomial arc tangent, less a margin for its error; the four
//! variants of a formula side by side in four lanes (`lanes.rs`),
//! compiled for AVX2 where the processor has it. The formulas themselves
//! run only for candidates whose bound is below the shortest length found,
//! best first (about one a call), and OMPL's order is replayed on those. A
//! candidate skipped that way is longer than the winner by the margin, so
//! the result is the exhaustive one, bit for bit (a test compares both).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use super::Turn;
use super::lanes::{F4, M4};

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
/// timeflip, reflect and both (0–3), then the same of the goal seen
/// backwards (4–7); each made when a candidate asks for it.
#[derive(Clone, Copy)]
struct Variants {
    goal: Goal,
    back: Goal,
}

impl Variants {
    #[inline]
    fn new(g: Goal) -> Self {
        Variants {
            goal: g,
            back: backwards(g),
        }
    }

    /// Variant `i` (0–7).
    #[inline(always)]
    fn get(&self, i: usize) -> Goal {
        let g = if i < 4 { self.goal } else { self.back };
        match i % 4 {
            0 => g,
            1 => g.timeflip(),
            2 => g.reflect(),
            _ => g.both(),
        }
    }
}

/// Candidate `k`'s formula (t, u, v), `k` in OMPL's order: 0–3 8.1 and
/// 4–7 8.2 on the four variants; 8–11 8.3, 12–15 8.3 backwards; 16–19 8.7,
/// 20–23 8.8; 24–27 8.9, 28–31 8.10, 32–35 8.9 backwards, 36–39 8.10
/// backwards; 40–43 8.11.
#[inline]
fn formula<const PRUNE: bool>(k: usize, v: &Variants) -> Option<(f64, f64, f64)> {
    match k {
        0..4 => lp_sp_lp::<PRUNE>(v.get(k)),
        4..8 => lp_sp_rp(v.get(k - 4)),
        8..16 => lp_rm_l(v.get(k - 8)),
        16..20 => lp_rup_lum_rm(v.get(k - 16)),
        20..24 => lp_rum_lum_rp(v.get(k - 20)),
        24..28 => lp_rm_sm_lm::<PRUNE>(v.get(k - 24)),
        28..32 => lp_rm_sm_rm::<PRUNE>(v.get(k - 28)),
        32..36 => lp_rm_sm_lm::<PRUNE>(v.get(k - 28)),
        36..40 => lp_rm_sm_rm::<PRUNE>(v.get(k - 32)),
        _ => lp_rm_s_lm_rp(v.get(k - 40)),
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
#[inline(always)]
fn atan01(z: F4) -> F4 {
    let w = z * z;
    z * (0.999_866_308_210_730_6
        + w * (-0.330_304_484_949_521_5
            + w * (0.180_158_167_053_336_73
                + w * (-0.085_154_798_710_814_05 + w * 0.020_844_406_034_172_508))))
}

/// atan2 to within 1.3e-5 rad (as an angle: the lower bounds use it only
/// modulo 2π).
#[inline(always)]
fn atan2_approx(y: F4, x: F4) -> F4 {
    let zero = F4::splat(0.0);
    let (ax, ay) = (x.abs(), y.abs());
    let (lo, hi) = (ax.min(ay), ax.max(ay));
    let a = atan01(hi.gt(zero).select(lo / hi, zero));
    let a = ay.gt(ax).select(FRAC_PI_2 - a, a);
    x.lt(zero).select(PI - a, a).with_sign_of(y)
}

/// Rounds to the nearest integer by the float format (1.5 · 2⁵²).
const ROUND: f64 = 6_755_399_441_055_744.0;

/// The angle `a` wrapped into [−π, π] (to rounding). An arc's length in a
/// word is |wrap(a)| for the angle `a` it turns modulo 2π, which is
/// 1-Lipschitz in `a`: an error in an angle moves it no more.
#[inline(always)]
fn wrap(a: F4) -> F4 {
    a - ((a * (1.0 / TAU) + ROUND) - ROUND) * TAU
}

/// Whether the wrapped angle `w` (approximate) is certainly a negative
/// parameter in (−π, 0): clear of both ends by far more than the error.
#[inline(always)]
fn negative(w: F4) -> M4 {
    w.lt(-1e-3).and(w.gt(-PI + 1e-3))
}

/// Whether the wrapped angle `w` is certainly in (0, π) (its negation is
/// [`negative`]).
#[inline(always)]
fn positive(w: F4) -> M4 {
    w.gt(1e-3).and(w.lt(PI - 1e-3))
}

/// What a lower bound leaves for the approximations (each formula's length
/// moves at most 10 × 1.3e-5 with them) and for the formulas' own rounding.
#[inline(always)]
fn lower(l: F4) -> F4 {
    l - 5e-4 - 1e-9 * l
}

/// The turn of an LSL word (8.1) ending at heading φ: its two arcs turn
/// t, v ≥ 0 with t + v ≡ φ (mod 2π), so t + v is φ taken into [0, 2π).
#[inline(always)]
fn lsl_arcs(phi: F4) -> F4 {
    phi.lt(-1e-9).select(phi + TAU, phi.max(F4::splat(0.0)))
}

/// A bound for each lane where `none` is false, +∞ where it is true.
#[inline(always)]
fn unless(none: M4, l: F4) -> F4 {
    none.select(F4::splat(f64::INFINITY), l)
}

/// A goal's four variants side by side, in [`Variants::get`]'s order: as
/// it is, timeflip, reflect, both.
#[derive(Clone, Copy)]
struct Lanes {
    x: F4,
    y: F4,
    phi: F4,
    s: F4,
    c: F4,
}

impl Lanes {
    /// Each lane is its variant, made by [`Goal`]'s own flips.
    #[inline(always)]
    fn new(g: Goal) -> Self {
        let v = [g, g.timeflip(), g.reflect(), g.both()];
        Lanes {
            x: F4(v.map(|g| g.x)),
            y: F4(v.map(|g| g.y)),
            phi: F4(v.map(|g| g.phi)),
            s: F4(v.map(|g| g.s)),
            c: F4(v.map(|g| g.c)),
        }
    }

    /// The centre vector A = (x − sin φ, y − 1 + cos φ) of formulas 8.1,
    /// 8.3 and 8.9, and its norm, as they compute them.
    #[inline(always)]
    fn a(&self) -> (F4, F4, F4) {
        let (xi, eta) = (self.x - self.s, self.y - 1.0 + self.c);
        (xi, eta, (xi * xi + eta * eta).sqrt())
    }

    /// The centre vector B = (x + sin φ, y − 1 − cos φ) of formulas 8.2,
    /// 8.7, 8.8, 8.10 and 8.11, and its squared norm.
    #[inline(always)]
    fn b(&self) -> (F4, F4, F4) {
        let (xi, eta) = (self.x + self.s, self.y - 1.0 - self.c);
        (xi, eta, xi * xi + eta * eta)
    }
}

// Lower bounds on each formula's length (its fixed quarter turns included)
// on four variants at once, +∞ where the formula certainly gives no word.
// Quantities that decide whether a formula applies are computed exactly as
// the formula does; the lengths are what the formula computes with an
// approximate arc tangent (an angle's error changes the length by at most a
// few times as much, the arcs being distances on the circle), less the
// margin of `lower`. Lanes where a formula does not apply may compute NaN;
// `unless` replaces them.

/// 8.1 (LSL): the straight is |A| and the arcs make up φ (see `lsl_arcs`);
/// t = atan2(eta, xi) must be in [0, π] and v = φ − t in [0, π] (sin v =
/// (sin φ·xi − cos φ·eta) / |A| ≥ 0).
#[inline(always)]
fn lsl(f: &Lanes) -> F4 {
    let (xi, eta, an) = f.a();
    let none = eta
        .lt(-1e-14 * an)
        .or((f.s * xi - f.c * eta).lt(-1e-6 * an));
    unless(none, lower(an + lsl_arcs(f.phi)))
}

/// 8.2 (LSR): t's direction is B turned by atan2(2, u), whose cosine and
/// sine are u/|B| and 2/|B|: (cos t, sin t) = (ct, st) / |B|². t and
/// v = t − φ must be in [0, π] (sines ≥ 0, to within 1e-9 of the scale).
#[inline(always)]
fn lsr(f: &Lanes) -> F4 {
    let (xi, eta, b2) = f.b();
    let u = (b2 - 4.0).sqrt();
    let (st, ct) = (2.0 * xi + u * eta, u * xi - 2.0 * eta);
    let tol = 1e-9 * b2;
    let t = atan2_approx(st, ct);
    let (t, v) = (wrap(t), wrap(t - f.phi));
    let none = b2
        .lt(4.0)
        .or(st.lt(-tol))
        .or((st * f.c - ct * f.s).lt(-tol))
        .or(negative(t))
        .or(negative(v));
    unless(none, lower(u + t.abs() + v.abs()))
}

/// 8.3 (LRL): u = −2 asin(|A| / 4), t = θ + u/2 + π (θ the angle of A).
#[inline(always)]
fn lrl(f: &Lanes) -> F4 {
    let (xi, eta, an) = f.a();
    let q = 0.25 * an;
    let u = 2.0 * atan2_approx(q, ((1.0 - q) * (1.0 + q)).sqrt());
    let t = atan2_approx(eta, xi) - 0.5 * u + PI;
    let v = wrap(t + u - f.phi);
    let t = wrap(t);
    let none = an.gt(4.0).or(negative(t));
    unless(none, lower(u + t.abs() + v.abs()))
}

/// 8.7: u = acos ρ; t = θ + π/2 + u, v = t − 2u − φ (θ the angle of B).
#[inline(always)]
fn lp_rup_lum_rm_bound(f: &Lanes) -> F4 {
    let (xi, eta, b2) = f.b();
    let bn = b2.sqrt();
    let rho = 0.25 * (2.0 + bn);
    let u = atan2_approx(((1.0 - rho) * (1.0 + rho)).sqrt(), rho);
    let t = atan2_approx(eta, xi) + 0.5 * PI + u;
    // v (the formula's omega), which must be ≤ 0.
    let w = wrap(t - 2.0 * u - f.phi);
    let t = wrap(t);
    // Where B is that short, the formula's angle is ill-conditioned.
    let small = bn.lt(1e-4);
    let none = rho.gt(1.0).or(small.not().and(negative(t).or(positive(w))));
    let fine = small.select(lower(2.0 * u), lower(2.0 * u + t.abs() + w.abs()));
    unless(none, fine)
}

/// 8.8: u = −acos ρ; t = θ − angle(cos u − 2, sin u), v = t − φ.
#[inline(always)]
fn lp_rum_lum_rp_bound(f: &Lanes) -> F4 {
    let (xi, eta, _) = f.b();
    let rho = (20.0 - xi * xi - eta * eta) / 16.0;
    let su = ((1.0 - rho) * (1.0 + rho)).sqrt();
    let u = atan2_approx(su, rho);
    let t = atan2_approx(eta, xi) - atan2_approx(rho - 2.0, -su);
    let (t, v) = (wrap(t), wrap(t - f.phi));
    let none = rho.lt(0.0).or(rho.gt(1.0)).or(negative(t)).or(negative(v));
    unless(none, lower(2.0 * u + t.abs() + v.abs()))
}

/// 8.9: u = 2 − r with r = √(|A|² − 4); t is the angle of A turned by
/// atan2(r, −2), one approximate arc tangent of the rotated vector; t in
/// [0, π] and v = φ − π/2 − t in [−π, 0].
#[inline(always)]
fn lp_rm_sm_lm_bound(f: &Lanes) -> F4 {
    let (xi, eta, an) = f.a();
    let r = (an * an - 4.0).sqrt();
    let u = 2.0 - r;
    let t = atan2_approx(r * xi - 2.0 * eta, -2.0 * xi - r * eta);
    // −v, as v must be ≤ 0.
    let (t, w) = (wrap(t), wrap(t - (f.phi - 0.5 * PI)));
    let none = an.lt(2.0).or(u.gt(ZERO)).or(negative(t)).or(negative(w));
    unless(none, lower(0.5 * PI + u.abs() + t.abs() + w.abs()))
}

/// 8.10: u = 2 − |B|, t = θ + π/2 in [0, π], v = t + π/2 − φ in [−π, 0].
#[inline(always)]
fn lp_rm_sm_rm_bound(f: &Lanes) -> F4 {
    let (xi, eta, b2) = f.b();
    let bn = b2.sqrt();
    let u = 2.0 - bn;
    let t = atan2_approx(eta, xi) + 0.5 * PI;
    // v, which must be ≤ 0.
    let (t, v) = (wrap(t), wrap(t - (f.phi - 0.5 * PI)));
    let none = bn.lt(2.0).or(u.gt(ZERO)).or(negative(t)).or(positive(v));
    unless(none, lower(0.5 * PI + u.abs() + t.abs() + v.abs()))
}

/// 8.11: u = 4 − √(|B|² − 4); t the formula's own arc tangent,
/// approximated; t and v = t − φ in [0, π].
#[inline(always)]
fn lp_rm_s_lm_rp_bound(f: &Lanes) -> F4 {
    let (xi, eta, b2) = f.b();
    let bn = b2.sqrt();
    let u = 4.0 - (bn * bn - 4.0).sqrt();
    let t = atan2_approx((4.0 - u) * xi - 2.0 * eta, -2.0 * xi + (u - 4.0) * eta);
    let (t, v) = (wrap(t), wrap(t - f.phi));
    let none = bn.lt(2.0).or(u.gt(ZERO)).or(negative(t)).or(negative(v));
    unless(none, lower(PI + u.abs() + t.abs() + v.abs()))
}

/// Every candidate's lower bound (in `k`'s order, see [`formula`]), the
/// goal's distance `d`; +∞ where a formula certainly gives no word.
#[inline(always)]
fn lower_bounds(f: &Lanes, b: &Lanes, d: f64) -> [f64; CANDIDATES] {
    let mut lb = [f64::INFINITY; CANDIDATES];
    let mut put = |k: usize, l: F4| lb[k..k + 4].copy_from_slice(&l.0);
    put(0, lsl(f));
    put(4, lsr(f));
    // The CCC and CCCC words (8–23) need a centre vector no longer than
    // √20 < 4.5 (8.3: A ≤ 4; 8.7: B ≤ 2; 8.8: B² ≤ 20). Both centre
    // vectors are the goal less a point within 2 of the origin
    // ((sin φ, 1 − cos φ) and (−sin φ, 1 + cos φ)), and the goal seen
    // backwards is the goal rotated, so every centre vector is at least
    // d − 2 long (to a few roundings): beyond 6.5 radii none applies.
    if d <= CCC_REACH {
        put(8, lrl(f));
        put(12, lrl(b));
        put(16, lp_rup_lum_rm_bound(f));
        put(20, lp_rum_lum_rp_bound(f));
    }
    put(24, lp_rm_sm_lm_bound(f));
    put(28, lp_rm_sm_rm_bound(f));
    put(32, lp_rm_sm_lm_bound(b));
    put(36, lp_rm_sm_rm_bound(b));
    put(40, lp_rm_s_lm_rp_bound(f));
    lb
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
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: this processor has AVX2 (checked just above).
        return unsafe { shortest_avx2(x, y, phi) };
    }
    solve::<true>(x, y, phi)
}

/// [`shortest`] compiled for AVX2: the same operations (no fused
/// multiply-adds), the lower bounds four lanes at a time.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn shortest_avx2(x: f64, y: f64, phi: f64) -> Word {
    solve::<true>(x, y, phi)
}

/// Beyond this distance (in radii) no CCC or CCCC word applies.
const CCC_REACH: f64 = 6.5;

/// How many candidates the fast search keeps; more (ties of many words)
/// goes the exhaustive way.
const KEEP: usize = 8;

#[inline(always)]
fn solve<const PRUNE: bool>(x: f64, y: f64, phi: f64) -> Word {
    let phi = mod2pi(phi);
    let (s, c) = phi.sin_cos();
    let goal = Goal { x, y, phi, s, c };
    let v = Variants::new(goal);
    if !PRUNE {
        return ompl_order(|k| formula::<false>(k, &v));
    }
    // Every candidate bounded from below, then computed best first while
    // its bound is below the shortest length found. A candidate left out
    // is longer than that by the margin of `lower`, so it could not win in
    // OMPL's order either, nor change how the others compare.
    let d = (x * x + y * y).sqrt();
    let mut lb = lower_bounds(&Lanes::new(goal), &Lanes::new(v.back), d);
    let mut found = Found {
        kept: [(0.0, 0.0, 0.0); KEEP],
        kept_k: [0; KEEP],
        n: 0,
        kept_mask: 0,
        upper: f64::INFINITY,
    };
    loop {
        // The least bound left, and the first candidate with it; a
        // candidate computed is taken out by an infinite bound.
        let least = least(&lb);
        if least == f64::INFINITY || least > found.upper {
            break;
        }
        let k = within(&lb, least).trailing_zeros() as usize;
        lb[k] = f64::INFINITY;
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

/// The candidates whose bound is at most `upper`, a bit each.
#[inline(always)]
fn within(lb: &[f64; CANDIDATES], upper: f64) -> u64 {
    let mut bits = 0;
    for (i, l) in lb.chunks_exact(4).enumerate() {
        let l = F4([l[0], l[1], l[2], l[3]]);
        bits |= l.gt(upper).not().bits() << (4 * i);
    }
    bits
}

/// The least of the bounds.
#[inline(always)]
fn least(lb: &[f64; CANDIDATES]) -> f64 {
    let least = lb.chunks_exact(4).fold(F4::splat(f64::INFINITY), |m, l| {
        m.min(F4([l[0], l[1], l[2], l[3]]))
    });
    least.0[0].min(least.0[1]).min(least.0[2].min(least.0[3]))
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
            let (a, b) = (shortest(x, y, phi), solve::<false>(x, y, phi));
            assert_eq!(a, b, "at ({x}, {y}, {phi})");
            assert_eq!(solve::<true>(x, y, phi), b, "at ({x}, {y}, {phi})");
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
                // The A and B centre vectors (see `Lanes`) of that length.
                6 => (x, y) = (phi.sin() + ca, 1.0 - phi.cos() + sa),
                7 => (x, y) = (-phi.sin() + ca, 1.0 + phi.cos() + sa),
                8 => {
                    phi = [0.0, FRAC_PI_2, -FRAC_PI_2, PI, -PI][k % 5] + rng.range(-1e-9, 1e-9);
                }
                _ => {}
            }
            let (s, c) = phi.sin_cos();
            let goal = Goal { x, y, phi, s, c };
            let v = Variants::new(goal);
            let d = (x * x + y * y).sqrt();
            // The bounds as compiled for processors without AVX2 and with
            // it: the same bits.
            let (f, b) = (Lanes::new(goal), Lanes::new(v.back));
            let lb = lower_bounds(&f, &b, d);
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx2") {
                #[target_feature(enable = "avx2")]
                fn wide(f: &Lanes, b: &Lanes, d: f64) -> [f64; CANDIDATES] {
                    lower_bounds(f, b, d)
                }
                // SAFETY: this processor has AVX2 (checked just above).
                let wide = unsafe { wide(&f, &b, d) };
                assert_eq!(lb.map(f64::to_bits), wide.map(f64::to_bits));
            }
            for (i, &b) in lb.iter().enumerate() {
                if let Some(r) = formula::<false>(i, &v) {
                    let l = total(i, r);
                    assert!(b <= l, "candidate {i} at ({x}, {y}, {phi}): {b} > {l}");
                    worst = worst.min(l - b);
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
