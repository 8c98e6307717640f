//! Intervals of `f64` with outward rounding: the hot path of every certified computation.
//!
//! Rust runs with round-to-nearest and offers no rounding-mode control, so each bound is
//! rounded to nearest and then corrected with an error-free transformation: `TwoSum` for
//! sums and `fma` for products give the exact sign of the rounding error, and the bound is
//! moved one ulp outward only when the rounded result lies on the wrong side. The result is
//! the directed-rounding result (`_rd`, `_ru`), so exact operations stay exact (a sum of
//! dyadic numbers that fits gives a point interval and a decidable zero).
//! The argument is `proofs/outward-rounding.md`.

use super::{Exactness, Number, Precision, Rational, Sign};
use rug::float::Round;

/// A closed interval `[lo, hi]` of reals with `f64` bounds, `lo <= hi`, never NaN.
///
/// Bounds may be infinite after overflow; the interval then still contains the exact value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    lo: f64,
    hi: f64,
}

/// Below this magnitude a product's rounding error may itself be rounded (underflow), so
/// `fma(a, b, -p)` no longer gives its exact sign: 2^-1022 (smallest normal) × 2^53.
const PRODUCT_EXACT_ERROR_MIN: f64 = f64::MIN_POSITIVE * 9007199254740992.0;

/// Above this magnitude `TwoSum` may overflow internally: 2^1023.
const SUM_EXACT_ERROR_MAX: f64 = 8.98846567431158e307;

/// The exact rounding error of `s = fl(a + b)`: `a + b - s` (Knuth's TwoSum).
#[inline]
fn two_sum_err(a: f64, b: f64, s: f64) -> f64 {
    let bb = s - a;
    (a - (s - bb)) + (b - bb)
}

/// `a + b` rounded down.
#[inline]
fn add_rd(a: f64, b: f64) -> f64 {
    let s = a + b;
    if s.abs() < SUM_EXACT_ERROR_MAX {
        if two_sum_err(a, b, s) < 0.0 {
            s.next_down()
        } else {
            s
        }
    } else {
        add_rd_ru_special(a, b, s).0
    }
}

/// `a + b` rounded up.
#[inline]
fn add_ru(a: f64, b: f64) -> f64 {
    let s = a + b;
    if s.abs() < SUM_EXACT_ERROR_MAX {
        if two_sum_err(a, b, s) > 0.0 {
            s.next_up()
        } else {
            s
        }
    } else {
        add_rd_ru_special(a, b, s).1
    }
}

/// The rare cases of a sum: NaN, infinities, |s| >= 2^1023.
#[cold]
#[inline(never)]
fn add_rd_ru_special(a: f64, b: f64, s: f64) -> (f64, f64) {
    if s.is_nan() {
        // inf + (-inf): nothing is known.
        (f64::NEG_INFINITY, f64::INFINITY)
    } else if s.is_finite() {
        (s.next_down(), s.next_up())
    } else if a.is_infinite() || b.is_infinite() {
        (s, s)
    } else if s > 0.0 {
        // Finite operands whose sum overflowed upwards.
        (f64::MAX, f64::INFINITY)
    } else {
        (f64::NEG_INFINITY, -f64::MAX)
    }
}

/// `x / 2` rounded down. Halving is exact unless the result is subnormal.
#[inline]
fn half_rd(x: f64) -> f64 {
    let h = x * 0.5;
    if h * 2.0 == x {
        h
    } else {
        h.next_down()
    }
}

/// `x / 2` rounded up.
#[inline]
fn half_ru(x: f64) -> f64 {
    let h = x * 0.5;
    if h * 2.0 == x {
        h
    } else {
        h.next_up()
    }
}

/// `a * b` rounded down and up: `(rd, ru)`.
#[inline]
pub(crate) fn mul_rd_ru(a: f64, b: f64) -> (f64, f64) {
    if a == 0.0 || b == 0.0 {
        // Interval convention: 0 × anything (even an infinite bound) is 0.
        return (0.0, 0.0);
    }
    let p = a * b;
    if p.is_finite() && p.abs() >= PRODUCT_EXACT_ERROR_MIN {
        let e = a.mul_add(b, -p);
        if e < 0.0 {
            (p.next_down(), p)
        } else if e > 0.0 {
            (p, p.next_up())
        } else {
            (p, p)
        }
    } else if p.is_finite() {
        // Possible underflow: the error of p is at most one ulp; widen both ways.
        (p.next_down(), p.next_up())
    } else if a.is_infinite() || b.is_infinite() {
        (p, p)
    } else if p > 0.0 {
        (f64::MAX, f64::INFINITY)
    } else {
        (f64::NEG_INFINITY, -f64::MAX)
    }
}

impl Interval {
    /// The interval `[lo, hi]`.
    ///
    /// # Panics
    /// If `lo > hi` or either bound is NaN. Use [`Interval::try_new`] for unchecked input.
    pub fn new(lo: f64, hi: f64) -> Interval {
        Interval::try_new(lo, hi).expect("Interval::new: need lo <= hi, no NaN")
    }

    /// The interval `[lo, hi]`, or `None` if `lo > hi` or a bound is NaN.
    pub fn try_new(lo: f64, hi: f64) -> Option<Interval> {
        (lo <= hi).then_some(Interval { lo, hi })
    }

    /// The point interval `[x, x]` (x must not be NaN).
    pub fn point(x: f64) -> Interval {
        Interval::new(x, x)
    }

    /// The lower bound.
    pub fn lo(&self) -> f64 {
        self.lo
    }

    /// The upper bound.
    pub fn hi(&self) -> f64 {
        self.hi
    }

    /// The width `hi - lo`, rounded up.
    pub fn width(&self) -> f64 {
        add_ru(self.hi, -self.lo)
    }

    /// Whether `x` lies in the interval.
    pub fn contains(&self, x: f64) -> bool {
        self.lo <= x && x <= self.hi
    }

    /// Whether the exact rational `q` lies in the interval (decided exactly).
    pub fn contains_rational(&self, q: &Rational) -> bool {
        let lo_ok = self.lo == f64::NEG_INFINITY || *q >= self.lo;
        let hi_ok = self.hi == f64::INFINITY || *q <= self.hi;
        lo_ok && hi_ok
    }

    /// `1 / x` for every x in the interval, or `None` if it contains 0 (outward: IEEE
    /// division is correctly rounded, so one step outward from each quotient encloses it).
    pub fn recip(&self) -> Option<Interval> {
        if self.lo > 0.0 || self.hi < 0.0 {
            let lo = (1.0 / self.hi).next_down();
            let hi = (1.0 / self.lo).next_up();
            (lo.is_finite() && hi.is_finite()).then_some(Interval { lo, hi })
        } else {
            None
        }
    }

    /// `x / w` for every x in `self` and w in `w`, or `None` if `w` holds 0 (or a bound is
    /// not finite): the four corner quotients, each rounded to nearest and moved one ulp
    /// outward, enclose the exact ones.
    pub fn checked_div(&self, w: &Interval) -> Option<Interval> {
        if !w.sign().is_nonzero() {
            return None;
        }
        let c = [
            self.lo / w.lo,
            self.lo / w.hi,
            self.hi / w.lo,
            self.hi / w.hi,
        ];
        if c.iter().any(|v| v.is_nan()) {
            return None;
        }
        let lo = c.iter().copied().fold(f64::INFINITY, f64::min).next_down();
        let hi = c
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max)
            .next_up();
        Interval::try_new(lo, hi)
    }

    /// The smallest interval containing both.
    pub fn hull(&self, other: &Interval) -> Interval {
        Interval {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
        }
    }
}

impl Number for Interval {
    const EXACTNESS: Exactness = Exactness::Enclosure;
    const NAME: &'static str = "interval";

    fn from_rational(q: &Rational, _prec: Precision) -> Self {
        // Round to 53 bits in each direction, then to f64 (which may be subnormal) in the
        // same direction; both steps are monotone, so the bounds stay on their sides.
        let (lo, _) = rug::Float::with_val_round(53, q, Round::Down);
        let (hi, _) = rug::Float::with_val_round(53, q, Round::Up);
        Interval {
            lo: lo.to_f64_round(Round::Down),
            hi: hi.to_f64_round(Round::Up),
        }
    }

    fn from_i64(n: i64, _prec: Precision) -> Self {
        let x = n as f64;
        if x as i128 == n as i128 {
            Interval::point(x)
        } else {
            Interval::from_rational(&Rational::from(n), Precision::F64)
        }
    }

    fn precision(&self) -> Precision {
        Precision::F64
    }

    #[inline]
    fn add(&self, rhs: &Self) -> Self {
        Interval {
            lo: add_rd(self.lo, rhs.lo),
            hi: add_ru(self.hi, rhs.hi),
        }
    }

    #[inline]
    fn sub(&self, rhs: &Self) -> Self {
        Interval {
            lo: add_rd(self.lo, -rhs.hi),
            hi: add_ru(self.hi, -rhs.lo),
        }
    }

    #[inline]
    fn mul(&self, rhs: &Self) -> Self {
        // The extremes of a bilinear function on a box are at its corners; the signs of the
        // bounds say which two corners (the classic case table), except when both intervals
        // contain zero inside.
        let (a, b, c, d) = (self.lo, self.hi, rhs.lo, rhs.hi);
        let rd = |x: f64, y: f64| mul_rd_ru(x, y).0;
        let ru = |x: f64, y: f64| mul_rd_ru(x, y).1;
        let (lo, hi) = if a >= 0.0 {
            if c >= 0.0 {
                (rd(a, c), ru(b, d))
            } else if d <= 0.0 {
                (rd(b, c), ru(a, d))
            } else {
                (rd(b, c), ru(b, d))
            }
        } else if b <= 0.0 {
            if c >= 0.0 {
                (rd(a, d), ru(b, c))
            } else if d <= 0.0 {
                (rd(b, d), ru(a, c))
            } else {
                (rd(a, d), ru(a, c))
            }
        } else if c >= 0.0 {
            (rd(a, d), ru(b, d))
        } else if d <= 0.0 {
            (rd(b, c), ru(a, c))
        } else {
            (rd(a, d).min(rd(b, c)), ru(a, c).max(ru(b, d)))
        };
        Interval { lo, hi }
    }

    #[inline]
    fn neg(&self) -> Self {
        Interval {
            lo: -self.hi,
            hi: -self.lo,
        }
    }

    #[inline]
    fn midpoint(&self, rhs: &Self) -> Self {
        Interval {
            lo: half_rd(add_rd(self.lo, rhs.lo)),
            hi: half_ru(add_ru(self.hi, rhs.hi)),
        }
    }

    #[inline]
    fn add_assign(&mut self, rhs: &Self) {
        *self = Number::add(self, rhs);
    }

    #[inline]
    fn midpoint_assign(&mut self, rhs: &Self) {
        *self = Number::midpoint(self, rhs);
    }

    #[inline]
    fn sign(&self) -> Sign {
        if self.lo > 0.0 {
            Sign::Positive
        } else if self.hi < 0.0 {
            Sign::Negative
        } else if self.lo == 0.0 && self.hi == 0.0 {
            Sign::Zero
        } else {
            Sign::Unknown
        }
    }

    fn lower_f64(&self) -> f64 {
        self.lo
    }

    fn upper_f64(&self) -> f64 {
        self.hi
    }

    fn to_f64(&self) -> f64 {
        if self.lo == self.hi {
            self.lo
        } else if self.lo.is_finite() && self.hi.is_finite() {
            self.lo * 0.5 + self.hi * 0.5
        } else if self.lo.is_finite() {
            self.lo
        } else {
            self.hi
        }
    }
}
