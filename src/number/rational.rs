//! Exact rationals (`rug::Rational`, GMP) as a [`Number`]: the exact level of the fast side.

use super::{Exactness, Number, Precision, Rational, Sign};
use rug::float::Round;

impl Number for Rational {
    const EXACTNESS: Exactness = Exactness::Exact;
    const NAME: &'static str = "rational";

    fn from_rational(q: &Rational, _prec: Precision) -> Self {
        q.clone()
    }
    fn from_i64(n: i64, _prec: Precision) -> Self {
        Rational::from(n)
    }
    fn precision(&self) -> Precision {
        Precision(u32::MAX)
    }
    fn add(&self, rhs: &Self) -> Self {
        Rational::from(self + rhs)
    }
    fn sub(&self, rhs: &Self) -> Self {
        Rational::from(self - rhs)
    }
    fn mul(&self, rhs: &Self) -> Self {
        Rational::from(self * rhs)
    }
    fn neg(&self) -> Self {
        Rational::from(-self)
    }
    fn midpoint(&self, rhs: &Self) -> Self {
        let mut m = Rational::from(self + rhs);
        m >>= 1u32;
        m
    }
    fn add_assign(&mut self, rhs: &Self) {
        *self += rhs;
    }
    fn midpoint_assign(&mut self, rhs: &Self) {
        *self += rhs;
        *self >>= 1u32;
    }
    fn sign(&self) -> Sign {
        Sign::from_ordering(self.cmp0())
    }
    fn lower_f64(&self) -> f64 {
        rug::Float::with_val_round(53, self, Round::Down)
            .0
            .to_f64_round(Round::Down)
    }
    fn upper_f64(&self) -> f64 {
        rug::Float::with_val_round(53, self, Round::Up)
            .0
            .to_f64_round(Round::Up)
    }
    fn to_f64(&self) -> f64 {
        rug::Float::with_val(53, self).to_f64()
    }
}
