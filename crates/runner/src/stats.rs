//! Statistics a paper quotes about a bench: the 95 % Wilson score interval
//! of a success rate, and the two-sided exact sign test of a paired
//! comparison.

/// The 97.5 % quantile of the standard normal distribution (a two-sided
/// 95 % interval).
const Z95: f64 = 1.959_963_984_540_054;

/// The 95 % Wilson score interval of `successes` out of `n` trials, as
/// fractions (lo, hi) in [0, 1]; (NaN, NaN) for no trials. Unlike the
/// normal approximation it stays inside [0, 1] and is not empty at 0 or n
/// successes (Wilson 1927; Brown, Cai & DasGupta 2001).
pub fn wilson(successes: usize, n: usize) -> (f64, f64) {
    if n == 0 {
        return (f64::NAN, f64::NAN);
    }
    let (k, n) = (successes as f64, n as f64);
    let p = k / n;
    let z2 = Z95 * Z95;
    let centre = (p + z2 / (2.0 * n)) / (1.0 + z2 / n);
    let half = Z95 / (1.0 + z2 / n) * (p * (1.0 - p) / n + z2 / (4.0 * n * n)).sqrt();
    // At 0 and n successes one end is exactly 0 or 1: no rounding past it.
    let lo = if successes == 0 {
        0.0
    } else {
        (centre - half).max(0.0)
    };
    let hi = if k == n {
        1.0
    } else {
        (centre + half).min(1.0)
    };
    (lo, hi)
}

/// The two-sided exact sign test of `wins` against `losses` (ties dropped):
/// the probability, under a fair coin, of a split at least as uneven,
/// 2 · P(X ≤ min(wins, losses)) for X ~ Binomial(wins + losses, 1/2),
/// capped at 1. With no untied pairs there is no evidence either way: 1.
pub fn sign_test(wins: u64, losses: u64) -> f64 {
    let n = wins + losses;
    if n == 0 {
        return 1.0;
    }
    let k = wins.min(losses);
    // Σ_{i ≤ k} C(n, i) / 2^n, term by term in logarithms so that n of
    // thousands neither overflows nor underflows early.
    let mut log_c = 0.0_f64; // ln C(n, 0)
    let mut tail = 0.0_f64;
    let log_half_n = n as f64 * std::f64::consts::LN_2;
    for i in 0..=k {
        if i > 0 {
            log_c += ((n - i + 1) as f64).ln() - (i as f64).ln();
        }
        tail += (log_c - log_half_n).exp();
    }
    (2.0 * tail).min(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Wilson interval by its closed form, written out independently:
    /// (p̂ + z²/2n ± z·√(p̂(1−p̂)/n + z²/4n²)) / (1 + z²/n).
    fn closed_form(k: f64, n: f64) -> (f64, f64) {
        let z = 1.959_963_984_540_054_f64;
        let p = k / n;
        let a = p + z * z / (2.0 * n);
        let b = z * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt();
        let c = 1.0 + z * z / n;
        ((a - b) / c, (a + b) / c)
    }

    #[test]
    fn wilson_matches_its_closed_form() {
        for (k, n) in [(0, 10), (10, 10), (5, 10), (17, 20), (1, 3), (49, 50)] {
            let (lo, hi) = wilson(k, n);
            let (a, b) = closed_form(k as f64, n as f64);
            assert!((lo - a.max(0.0)).abs() < 1e-12, "{k}/{n}: {lo} vs {a}");
            assert!((hi - b.min(1.0)).abs() < 1e-12, "{k}/{n}: {hi} vs {b}");
            assert!(lo <= k as f64 / n as f64 && k as f64 / n as f64 <= hi);
        }
    }

    /// Literal values from the literature: Newcombe (1998), Table I
    /// (81/263 → 0.2553–0.3662; 15/148 → 0.0624–0.1605; 0/20 → 0–0.1611),
    /// to the four places printed there.
    #[test]
    fn wilson_matches_textbook_values() {
        let round4 = |x: f64| (x * 1e4).round() / 1e4;
        let pairs = [
            ((81, 263), (0.2553, 0.3662)),
            ((15, 148), (0.0624, 0.1605)),
            ((0, 20), (0.0, 0.1611)),
        ];
        for ((k, n), (lo, hi)) in pairs {
            let (a, b) = wilson(k, n);
            assert_eq!((round4(a), round4(b)), (lo, hi), "{k}/{n}");
        }
        // 17/20, the brief's example: 85 % in [64 %, 95 %].
        let (a, b) = wilson(17, 20);
        assert_eq!(((a * 100.0).round(), (b * 100.0).round()), (64.0, 95.0));
        // All or nothing: one end exact.
        assert_eq!(wilson(10, 10).1, 1.0);
        assert_eq!(wilson(0, 10).0, 0.0);
        assert!(wilson(0, 0).0.is_nan());
    }

    /// The sign test against its closed form: 2 · Σ_{i ≤ k} C(n, i) / 2ⁿ.
    #[test]
    fn sign_test_matches_the_binomial_tail() {
        // 9 wins, 1 loss: 2 · (1 + 10) / 1024 = 0.021484375.
        assert!((sign_test(9, 1) - 22.0 / 1024.0).abs() < 1e-15);
        assert!((sign_test(1, 9) - 22.0 / 1024.0).abs() < 1e-15);
        // 10 to 0: 2 / 1024.
        assert!((sign_test(10, 0) - 2.0 / 1024.0).abs() < 1e-15);
        // 8 to 2: 2 · (1 + 10 + 45) / 1024 = 0.109375.
        assert!((sign_test(8, 2) - 0.109_375).abs() < 1e-15);
        // An even split, or nothing untied: 1.
        assert_eq!(sign_test(5, 5), 1.0);
        assert_eq!(sign_test(0, 0), 1.0);
        // 15 to 5 (n = 20): 2 · Σ_{i ≤ 5} C(20, i) / 2^20 = 0.04138946533203125.
        let c20: [f64; 6] = [1.0, 20.0, 190.0, 1140.0, 4845.0, 15504.0];
        let exact = 2.0 * c20.iter().sum::<f64>() / 1_048_576.0;
        assert!(
            (sign_test(15, 5) - exact).abs() < 1e-14,
            "{}",
            sign_test(15, 5)
        );
        // Many pairs: finite and small, no overflow.
        let p = sign_test(3000, 2000);
        assert!(p > 0.0 && p < 1e-40, "{p}");
    }
}
