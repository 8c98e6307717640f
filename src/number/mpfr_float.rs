//! MPFR floats at an explicit precision as a [`Number`]: round to nearest, no guarantee.

use super::{Exactness, Number, Precision, Rational, Sign};
use rug::float::Round;
use rug::Float;

/// An MPFR float; its precision belongs to the value. Results of binary operations have the
/// larger precision of the two operands and are rounded to nearest.
#[derive(Clone, Debug, PartialEq)]
pub struct MpFloat(pub Float);

fn prec2(a: &Float, b: &Float) -> u32 {
    a.prec().max(b.prec())
}

impl Number for MpFloat {
    const EXACTNESS: Exactness = Exactness::Approximate;
    const NAME: &'static str = "mpfr";

    fn from_rational(q: &Rational, prec: Precision) -> Self {
        MpFloat(Float::with_val(prec.0, q))
    }
    fn from_i64(n: i64, prec: Precision) -> Self {
        MpFloat(Float::with_val(prec.0, n))
    }
    fn precision(&self) -> Precision {
        Precision(self.0.prec())
    }
    fn add(&self, rhs: &Self) -> Self {
        MpFloat(Float::with_val(prec2(&self.0, &rhs.0), &self.0 + &rhs.0))
    }
    fn sub(&self, rhs: &Self) -> Self {
        MpFloat(Float::with_val(prec2(&self.0, &rhs.0), &self.0 - &rhs.0))
    }
    fn mul(&self, rhs: &Self) -> Self {
        MpFloat(Float::with_val(prec2(&self.0, &rhs.0), &self.0 * &rhs.0))
    }
    fn neg(&self) -> Self {
        MpFloat(Float::with_val(self.0.prec(), -&self.0))
    }
    fn midpoint(&self, rhs: &Self) -> Self {
        let mut m = self.add(rhs);
        m.0 >>= 1u32;
        m
    }
    fn add_assign(&mut self, rhs: &Self) {
        if rhs.0.prec() > self.0.prec() {
            self.0.set_prec(rhs.0.prec());
        }
        self.0 += &rhs.0;
    }
    fn midpoint_assign(&mut self, rhs: &Self) {
        self.add_assign(rhs);
        self.0 >>= 1u32;
    }
    fn sign(&self) -> Sign {
        match self.0.cmp0() {
            Some(o) => Sign::from_ordering(o),
            None => Sign::Unknown,
        }
    }
    fn lower_f64(&self) -> f64 {
        self.0.to_f64_round(Round::Down)
    }
    fn upper_f64(&self) -> f64 {
        self.0.to_f64_round(Round::Up)
    }
    fn to_f64(&self) -> f64 {
        self.0.to_f64()
    }
}
