//! MPFR intervals at an explicit precision: the escalation level of the precision controller.

use super::{Exactness, Number, Precision, Rational, Sign};
use rug::float::Round;
use rug::ops::{AddAssignRound, MulAssignRound, SubAssignRound};
use rug::Float;

/// A closed interval `[lo, hi]` with MPFR bounds at a common precision, outward rounded.
///
/// MPFR rounds each operation correctly in the requested direction, so the lower bound is
/// computed rounding down and the upper rounding up (`proofs/outward-rounding.md`). MPFR's
/// exponent range is so wide that overflow and underflow do not arise from model data.
#[derive(Clone, Debug, PartialEq)]
pub struct MpInterval {
    lo: Float,
    hi: Float,
}

impl MpInterval {
    /// The interval `[lo, hi]` at the larger of the two precisions, or `None` if `lo > hi` or
    /// a bound is NaN.
    pub fn try_new(lo: Float, hi: Float) -> Option<MpInterval> {
        if lo.is_nan() || hi.is_nan() || lo > hi {
            return None;
        }
        let p = lo.prec().max(hi.prec());
        let lo = Float::with_val_round(p, &lo, Round::Down).0;
        let hi = Float::with_val_round(p, &hi, Round::Up).0;
        Some(MpInterval { lo, hi })
    }

    /// The lower bound.
    pub fn lo(&self) -> &Float {
        &self.lo
    }

    /// The upper bound.
    pub fn hi(&self) -> &Float {
        &self.hi
    }

    /// Whether the exact rational `q` lies in the interval (decided exactly).
    pub fn contains_rational(&self, q: &Rational) -> bool {
        self.lo <= *q && *q <= self.hi
    }

    /// The smallest f64 interval that contains this one (bounds rounded outward; a bound past
    /// f64's range becomes infinite, one below its least subnormal the nearest f64 outward).
    pub fn to_interval(&self) -> super::Interval {
        super::Interval::new(
            self.lo.to_f64_round(Round::Down),
            self.hi.to_f64_round(Round::Up),
        )
    }

    fn prec_with(&self, rhs: &MpInterval) -> u32 {
        self.lo.prec().max(rhs.lo.prec())
    }

    fn set_prec_at_least(&mut self, p: u32) {
        if self.lo.prec() < p {
            // Raising the precision never rounds.
            self.lo.set_prec(p);
            self.hi.set_prec(p);
        }
    }
}

impl Number for MpInterval {
    const EXACTNESS: Exactness = Exactness::Enclosure;
    const NAME: &'static str = "mpfr-interval";

    fn from_rational(q: &Rational, prec: Precision) -> Self {
        MpInterval {
            lo: Float::with_val_round(prec.0, q, Round::Down).0,
            hi: Float::with_val_round(prec.0, q, Round::Up).0,
        }
    }

    fn from_i64(n: i64, prec: Precision) -> Self {
        MpInterval {
            lo: Float::with_val_round(prec.0, n, Round::Down).0,
            hi: Float::with_val_round(prec.0, n, Round::Up).0,
        }
    }

    fn precision(&self) -> Precision {
        Precision(self.lo.prec())
    }

    fn add(&self, rhs: &Self) -> Self {
        let mut r = self.clone();
        r.add_assign(rhs);
        r
    }

    fn sub(&self, rhs: &Self) -> Self {
        let mut r = self.clone();
        r.set_prec_at_least(rhs.lo.prec());
        r.lo.sub_assign_round(&rhs.hi, Round::Down);
        r.hi.sub_assign_round(&rhs.lo, Round::Up);
        r
    }

    fn mul(&self, rhs: &Self) -> Self {
        let p = self.prec_with(rhs);
        let corner = |a: &Float, b: &Float, round: Round| {
            if a.is_zero() || b.is_zero() {
                // Interval convention: 0 × anything (even an infinite bound) is 0.
                return Float::new(p);
            }
            let mut x = Float::with_val(p, a); // exact: p >= a.prec()
            x.mul_assign_round(b, round);
            x
        };
        let (a, b, c, d) = (&self.lo, &self.hi, &rhs.lo, &rhs.hi);
        let los = [
            corner(a, c, Round::Down),
            corner(a, d, Round::Down),
            corner(b, c, Round::Down),
            corner(b, d, Round::Down),
        ];
        let his = [
            corner(a, c, Round::Up),
            corner(a, d, Round::Up),
            corner(b, c, Round::Up),
            corner(b, d, Round::Up),
        ];
        let [l0, l1, l2, l3] = los;
        let [h0, h1, h2, h3] = his;
        let lo = l0.min(&l1).min(&l2).min(&l3);
        let hi = h0.max(&h1).max(&h2).max(&h3);
        MpInterval { lo, hi }
    }

    fn neg(&self) -> Self {
        MpInterval {
            lo: -self.hi.clone(),
            hi: -self.lo.clone(),
        }
    }

    fn midpoint(&self, rhs: &Self) -> Self {
        let mut r = self.clone();
        r.midpoint_assign(rhs);
        r
    }

    fn add_assign(&mut self, rhs: &Self) {
        self.set_prec_at_least(rhs.lo.prec());
        self.lo.add_assign_round(&rhs.lo, Round::Down);
        self.hi.add_assign_round(&rhs.hi, Round::Up);
    }

    fn midpoint_assign(&mut self, rhs: &Self) {
        self.add_assign(rhs);
        // Division by 2 only shifts the exponent: exact in MPFR's exponent range.
        self.lo >>= 1u32;
        self.hi >>= 1u32;
    }

    fn sign(&self) -> Sign {
        if self.lo.is_nan() || self.hi.is_nan() {
            Sign::Unknown
        } else if self.lo.is_sign_positive() && !self.lo.is_zero() {
            Sign::Positive
        } else if self.hi.is_sign_negative() && !self.hi.is_zero() {
            Sign::Negative
        } else if self.lo.is_zero() && self.hi.is_zero() {
            Sign::Zero
        } else {
            Sign::Unknown
        }
    }

    fn lower_f64(&self) -> f64 {
        self.lo.to_f64_round(Round::Down)
    }

    fn upper_f64(&self) -> f64 {
        self.hi.to_f64_round(Round::Up)
    }

    fn to_f64(&self) -> f64 {
        let mut m = Float::with_val(self.lo.prec() + 1, &self.lo + &self.hi);
        m >>= 1u32;
        m.to_f64()
    }
}
