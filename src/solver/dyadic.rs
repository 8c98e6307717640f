//! Exact dyadic numbers k / 2^e in [0, 1]: the coordinates of subdivision boxes.

use crate::geometry::Rect;
use crate::number::{Number, Precision, Rational};

/// The deepest subdivision level (2^-60 of the unit interval).
pub const MAX_DEPTH: u32 = 60;

/// The exact dyadic number `num / 2^exp` with `0 <= num <= 2^exp`, `exp <= MAX_DEPTH`,
/// kept in lowest terms (num odd, or exp = 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Dyadic {
    num: u64,
    exp: u32,
}

impl Ord for Dyadic {
    /// By value (the representation is reduced, so equality of fields is equality of values).
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        let e = self.exp.max(other.exp);
        self.at(e).cmp(&other.at(e))
    }
}

impl PartialOrd for Dyadic {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Dyadic {
    /// 0.
    pub const ZERO: Dyadic = Dyadic { num: 0, exp: 0 };
    /// 1.
    pub const ONE: Dyadic = Dyadic { num: 1, exp: 0 };

    /// `num / 2^exp`, reduced.
    ///
    /// # Panics
    /// If `exp > MAX_DEPTH` or the value is outside [0, 1].
    pub fn new(num: u64, exp: u32) -> Dyadic {
        assert!(
            exp <= MAX_DEPTH && num <= 1u64 << exp,
            "dyadic out of range"
        );
        let mut d = Dyadic { num, exp };
        while d.exp > 0 && d.num % 2 == 0 {
            d.num /= 2;
            d.exp -= 1;
        }
        d
    }

    /// The dyadic equal to an exact rational in [0, 1] with a power-of-two denominator of
    /// exponent at most `MAX_DEPTH`, or `None`.
    pub fn from_rational(q: &Rational) -> Option<Dyadic> {
        let den = q.denom();
        if *q < 0 || *q > 1 || !den.is_power_of_two() {
            return None;
        }
        let exp = den.significant_bits() - 1;
        (exp <= MAX_DEPTH).then(|| Dyadic::new(q.numer().to_u64().expect("at most 2^60"), exp))
    }

    /// The numerator over `2^exp` at a common exponent.
    fn at(self, exp: u32) -> u64 {
        self.num << (exp - self.exp)
    }

    /// The midpoint of `self` and `other`, or `None` below `MAX_DEPTH`.
    pub fn midpoint(self, other: Dyadic) -> Option<Dyadic> {
        let e = self.exp.max(other.exp) + 1;
        // At exponent e both numerators are even, so the half-sum is exact; both are at most
        // 2^60, so the sum fits.
        (e <= MAX_DEPTH).then(|| Dyadic::new((self.at(e) + other.at(e)) / 2, e))
    }

    /// `1 − self` (exact).
    pub fn one_minus(self) -> Dyadic {
        Dyadic::new((1u64 << self.exp) - self.num, self.exp)
    }

    /// The exact value.
    pub fn to_rational(self) -> Rational {
        Rational::from((
            rug::Integer::from(self.num),
            rug::Integer::from(1) << self.exp,
        ))
    }

    /// The value in `f64`: exact up to depth 53, rounded to nearest below that.
    pub fn to_f64(self) -> f64 {
        self.num as f64 / (2f64).powi(self.exp as i32)
    }

    /// Bounds `(lo, hi)` in f64 containing the value (equal when it is exact in f64).
    pub fn to_f64_bounds(self) -> (f64, f64) {
        if self.num < 1u64 << 53 {
            let x = self.to_f64();
            (x, x)
        } else {
            let i = <crate::number::Interval as Number>::from_rational(
                &self.to_rational(),
                Precision::F64,
            );
            (i.lo(), i.hi())
        }
    }

    /// The value in any number type (exact for exact types, enclosed otherwise).
    pub fn to_number<N: Number>(self, prec: Precision) -> N {
        N::from_rational(&self.to_rational(), prec)
    }

    /// `self - other` as an exact rational.
    pub fn width_to(self, other: Dyadic) -> Rational {
        other.to_rational() - self.to_rational()
    }

    /// The exponent of the denominator (the subdivision depth that produced it).
    pub fn exp(self) -> u32 {
        self.exp
    }
}

/// A box `[u0, u1] × [v0, v1]` with dyadic corners, in a patch's parameter square.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct DyadicBox {
    /// Lower corner in each variable.
    pub lo: [Dyadic; 2],
    /// Upper corner in each variable.
    pub hi: [Dyadic; 2],
}

impl DyadicBox {
    /// The unit square.
    pub const UNIT: DyadicBox = DyadicBox {
        lo: [Dyadic::ZERO; 2],
        hi: [Dyadic::ONE; 2],
    };

    /// The two halves along `axis`, or `None` at the maximum depth.
    pub fn split(&self, axis: usize) -> Option<(DyadicBox, DyadicBox)> {
        let m = self.lo[axis].midpoint(self.hi[axis])?;
        let mut a = *self;
        let mut b = *self;
        a.hi[axis] = m;
        b.lo[axis] = m;
        Some((a, b))
    }

    /// The width along `axis`, in `f64`.
    pub fn width(&self, axis: usize) -> f64 {
        self.hi[axis].to_f64() - self.lo[axis].to_f64()
    }

    /// The box in `f64` (corners rounded to nearest: exact up to depth 53).
    pub fn to_f64(&self) -> Rect {
        Rect::new(
            [self.lo[0].to_f64(), self.lo[1].to_f64()],
            [self.hi[0].to_f64(), self.hi[1].to_f64()],
        )
    }
}

impl serde::Serialize for Dyadic {
    /// As the exact rational string `"num/den"` (or `"0"`, `"1"`).
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if self.exp == 0 {
            s.serialize_str(&self.num.to_string())
        } else {
            s.serialize_str(&format!("{}/{}", self.num, 1u64 << self.exp))
        }
    }
}

impl serde::Serialize for DyadicBox {
    /// As `[[u0, v0], [u1, v1]]` of exact rational strings.
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        [self.lo, self.hi].serialize(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn midpoints_are_exact_and_reduced() {
        let m = Dyadic::ZERO.midpoint(Dyadic::ONE).unwrap();
        assert_eq!(m, Dyadic::new(2, 2));
        assert_eq!(m.to_rational(), Rational::from((1, 2)));
        let q = m.midpoint(Dyadic::ONE).unwrap();
        assert_eq!(q.to_rational(), Rational::from((3, 4)));
        assert_eq!(serde_json::to_string(&q).unwrap(), "\"3/4\"");
        let mut d = Dyadic::ZERO;
        for _ in 0..MAX_DEPTH {
            d = d.midpoint(Dyadic::new(1, MAX_DEPTH.min(1))).unwrap_or(d);
        }
        assert!(d.exp() <= MAX_DEPTH);
        assert!(Dyadic::new(1, 1) > Dyadic::new(1, 2));
        assert!(Dyadic::new(3, 2) > Dyadic::new(1, 1));
        assert!(Dyadic::ZERO < Dyadic::new(1, MAX_DEPTH));
        let deep = Dyadic::new(1, MAX_DEPTH);
        assert!(Dyadic::ZERO.midpoint(deep).is_none());
    }
}
