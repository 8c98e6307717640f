//! `f64` as a [`Number`]: round to nearest, no guarantee. The fast, uncertified path.

use super::{Exactness, Number, Precision, Rational, Sign};

impl Number for f64 {
    const EXACTNESS: Exactness = Exactness::Approximate;
    const NAME: &'static str = "f64";

    fn from_rational(q: &Rational, _prec: Precision) -> Self {
        // Correctly rounded to nearest (MPFR does the rounding).
        rug::Float::with_val(53, q).to_f64()
    }
    fn from_i64(n: i64, _prec: Precision) -> Self {
        n as f64
    }
    fn precision(&self) -> Precision {
        Precision::F64
    }
    #[inline]
    fn add(&self, rhs: &Self) -> Self {
        self + rhs
    }
    #[inline]
    fn sub(&self, rhs: &Self) -> Self {
        self - rhs
    }
    #[inline]
    fn mul(&self, rhs: &Self) -> Self {
        self * rhs
    }
    #[inline]
    fn neg(&self) -> Self {
        -self
    }
    #[inline]
    fn midpoint(&self, rhs: &Self) -> Self {
        (self + rhs) * 0.5
    }
    #[inline]
    fn add_assign(&mut self, rhs: &Self) {
        *self += rhs;
    }
    #[inline]
    fn midpoint_assign(&mut self, rhs: &Self) {
        *self = (*self + rhs) * 0.5;
    }
    fn sign(&self) -> Sign {
        if *self > 0.0 {
            Sign::Positive
        } else if *self < 0.0 {
            Sign::Negative
        } else if *self == 0.0 {
            Sign::Zero
        } else {
            Sign::Unknown
        }
    }
    fn lower_f64(&self) -> f64 {
        *self
    }
    fn upper_f64(&self) -> f64 {
        *self
    }
    fn to_f64(&self) -> f64 {
        *self
    }
}
