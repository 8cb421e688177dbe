//! Four `f64` lanes computed alike, for the Reeds–Shepp lower bounds: the
//! four variants of a goal (as it is, timeflip, reflect, both) go through
//! the same formula side by side. Every operation is the scalar one lane by
//! lane (no fused multiply-add), so the lanes hold the scalar results bit
//! for bit; compiled for AVX2 (see `reeds_shepp::shortest`), the
//! compiler turns each into one vector instruction.

use std::ops::{Add, Div, Mul, Neg, Sub};

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct F4(pub [f64; 4]);

/// A comparison's outcome, lane by lane: all bits set where it held (the
/// form the processor's vector comparisons give).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct M4(pub [u64; 4]);

impl F4 {
    #[inline(always)]
    pub fn splat(a: f64) -> F4 {
        F4([a; 4])
    }

    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> F4 {
        F4(self.0.map(f))
    }

    #[inline(always)]
    fn zip(self, o: F4, f: impl Fn(f64, f64) -> f64) -> F4 {
        F4(std::array::from_fn(|i| f(self.0[i], o.0[i])))
    }

    #[inline(always)]
    fn test(self, o: F4, f: impl Fn(f64, f64) -> bool) -> M4 {
        M4(std::array::from_fn(|i| {
            if f(self.0[i], o.0[i]) { u64::MAX } else { 0 }
        }))
    }

    #[inline(always)]
    pub fn sqrt(self) -> F4 {
        self.map(f64::sqrt)
    }

    #[inline(always)]
    pub fn abs(self) -> F4 {
        self.map(f64::abs)
    }

    /// Each lane (≥ +0) given the sign of `o`'s: one bit operation, no
    /// comparison.
    #[inline(always)]
    pub fn with_sign_of(self, o: F4) -> F4 {
        const SIGN: u64 = 1 << 63;
        self.zip(o, |a, b| f64::from_bits(a.to_bits() | (b.to_bits() & SIGN)))
    }

    /// The larger of each pair (neither is NaN here).
    #[inline(always)]
    pub fn max(self, o: F4) -> F4 {
        self.zip(o, |a, b| if a > b { a } else { b })
    }

    /// The smaller of each pair (neither is NaN here).
    #[inline(always)]
    pub fn min(self, o: F4) -> F4 {
        self.zip(o, |a, b| if a < b { a } else { b })
    }

    #[inline(always)]
    pub fn lt(self, o: impl Into<F4>) -> M4 {
        self.test(o.into(), |a, b| a < b)
    }

    #[inline(always)]
    pub fn gt(self, o: impl Into<F4>) -> M4 {
        self.test(o.into(), |a, b| a > b)
    }
}

impl From<f64> for F4 {
    #[inline(always)]
    fn from(a: f64) -> F4 {
        F4::splat(a)
    }
}

impl M4 {
    /// `a` where the lane's test held, else `b`.
    #[inline(always)]
    pub fn select(self, a: F4, b: F4) -> F4 {
        F4(std::array::from_fn(|i| {
            let m = self.0[i];
            f64::from_bits((a.0[i].to_bits() & m) | (b.0[i].to_bits() & !m))
        }))
    }

    /// One bit a lane, the first lane's lowest.
    #[inline(always)]
    pub fn bits(self) -> u64 {
        (self.0[0] & 1) | (self.0[1] & 2) | (self.0[2] & 4) | (self.0[3] & 8)
    }

    #[inline(always)]
    pub fn not(self) -> M4 {
        M4(self.0.map(|a| !a))
    }

    #[inline(always)]
    pub fn or(self, o: M4) -> M4 {
        M4(std::array::from_fn(|i| self.0[i] | o.0[i]))
    }

    #[inline(always)]
    pub fn and(self, o: M4) -> M4 {
        M4(std::array::from_fn(|i| self.0[i] & o.0[i]))
    }
}

macro_rules! lanewise {
    ($($trait:ident $method:ident $op:tt)*) => { $(
        impl $trait for F4 {
            type Output = F4;
            #[inline(always)]
            fn $method(self, o: F4) -> F4 {
                self.zip(o, |a, b| a $op b)
            }
        }
        impl $trait<f64> for F4 {
            type Output = F4;
            #[inline(always)]
            fn $method(self, o: f64) -> F4 {
                self.map(|a| a $op o)
            }
        }
        impl $trait<F4> for f64 {
            type Output = F4;
            #[inline(always)]
            fn $method(self, o: F4) -> F4 {
                o.map(|b| self $op b)
            }
        }
    )* };
}

lanewise!(Add add + Sub sub - Mul mul * Div div /);

impl Neg for F4 {
    type Output = F4;
    #[inline(always)]
    fn neg(self) -> F4 {
        self.map(|a| -a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each lane is the scalar operation's result, bit for bit, and the
    /// masks pick lane by lane.
    #[test]
    fn lanes_are_the_scalar_operations() {
        let a = F4([1.5, -0.0, 3e-300, -7.25]);
        let b = F4([0.25, 2.0, -1e300, -7.25]);
        for i in 0..4 {
            let (x, y) = (a.0[i], b.0[i]);
            assert_eq!((a + b).0[i].to_bits(), (x + y).to_bits());
            assert_eq!((a - b).0[i].to_bits(), (x - y).to_bits());
            assert_eq!((a * b).0[i].to_bits(), (x * y).to_bits());
            assert_eq!((a / b).0[i].to_bits(), (x / y).to_bits());
            assert_eq!((2.0 - a).0[i].to_bits(), (2.0 - x).to_bits());
            assert_eq!((a * 0.5).0[i].to_bits(), (x * 0.5).to_bits());
            assert_eq!((-a).0[i].to_bits(), (-x).to_bits());
            assert_eq!(a.abs().0[i].to_bits(), x.abs().to_bits());
            assert_eq!(b.abs().sqrt().0[i].to_bits(), y.abs().sqrt().to_bits());
        }
        assert_eq!(a.max(b), F4([1.5, 2.0, 3e-300, -7.25]));
        assert_eq!(a.min(b), F4([0.25, -0.0, -1e300, -7.25]));
        let m = a.lt(b);
        assert_eq!(m.bits(), 0b0010);
        assert_eq!(a.gt(b).bits(), 0b0101);
        assert_eq!(a.gt(0.0).or(m).bits(), 0b0111);
        assert_eq!(a.gt(0.0).and(m.not()).bits(), 0b0101);
        assert_eq!(m.select(a, b), F4([0.25, -0.0, -1e300, -7.25]));
        // NaN compares false: its lane takes the second operand.
        let n = F4([f64::NAN, 1.0, 1.0, 1.0]);
        assert_eq!(n.lt(2.0).bits(), 0b1110);
        assert_eq!(n.lt(2.0).select(a, b).0[0], 0.25);
    }
}
