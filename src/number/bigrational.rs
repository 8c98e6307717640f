//! Exact rationals from `num-rational` as a [`Number`].
//!
//! This implementation shares no arithmetic with GMP: it exists for the independent
//! certificate checker, which must not trust the fast path's libraries. Conversion from
//! `rug::Rational` goes through the decimal digits of numerator and denominator (no arithmetic).

use super::{Exactness, Number, Precision, Rational, Sign};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

/// Converts a GMP rational to a `num-rational` one through its decimal digits.
pub fn to_big_rational(q: &Rational) -> BigRational {
    let parse = |s: String| {
        s.parse::<BigInt>()
            .expect("GMP prints integers num-bigint parses")
    };
    BigRational::new(parse(q.numer().to_string()), parse(q.denom().to_string()))
}

impl Number for BigRational {
    const EXACTNESS: Exactness = Exactness::Exact;
    const NAME: &'static str = "num-rational";

    fn from_rational(q: &Rational, _prec: Precision) -> Self {
        to_big_rational(q)
    }
    fn from_i64(n: i64, _prec: Precision) -> Self {
        BigRational::from_integer(BigInt::from(n))
    }
    fn precision(&self) -> Precision {
        Precision(u32::MAX)
    }
    fn add(&self, rhs: &Self) -> Self {
        self + rhs
    }
    fn sub(&self, rhs: &Self) -> Self {
        self - rhs
    }
    fn mul(&self, rhs: &Self) -> Self {
        self * rhs
    }
    fn neg(&self) -> Self {
        -self
    }
    fn midpoint(&self, rhs: &Self) -> Self {
        (self + rhs) / BigInt::from(2)
    }
    fn sign(&self) -> Sign {
        if self.is_zero() {
            Sign::Zero
        } else if self.is_positive() {
            Sign::Positive
        } else {
            Sign::Negative
        }
    }
    fn lower_f64(&self) -> f64 {
        // An approximation, stepped down until it is proven below (exact comparison).
        let mut x = ToPrimitive::to_f64(self).unwrap_or(f64::NEG_INFINITY);
        if x == f64::INFINITY {
            x = f64::MAX;
        }
        while let Some(r) = BigRational::from_float(x) {
            if r <= *self {
                break;
            }
            x = x.next_down();
        }
        if x.is_nan() {
            f64::NEG_INFINITY
        } else {
            x
        }
    }
    fn upper_f64(&self) -> f64 {
        let mut x = ToPrimitive::to_f64(self).unwrap_or(f64::INFINITY);
        if x == f64::NEG_INFINITY {
            x = -f64::MAX;
        }
        while let Some(r) = BigRational::from_float(x) {
            if r >= *self {
                break;
            }
            x = x.next_up();
        }
        if x.is_nan() {
            f64::INFINITY
        } else {
            x
        }
    }
    fn to_f64(&self) -> f64 {
        ToPrimitive::to_f64(self).unwrap_or(f64::NAN)
    }
}
