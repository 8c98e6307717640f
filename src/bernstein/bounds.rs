//! Range bounds from the coefficients (the convex-hull property).

use super::Bernstein;
use crate::number::{Number, Sign};

impl<N: Number> Bernstein<N> {
    /// Bounds `[lo, hi]` in `f64`, outward rounded, on the values of the polynomial over the
    /// unit box: the least lower bound and the greatest upper bound of the coefficients.
    ///
    /// The Bernstein basis is a partition of unity of nonnegative functions on the box, so
    /// every value is a convex combination of the coefficients (`proofs/coefficient-range.md`).
    /// Valid for enclosure and exact types; for approximate types only an estimate.
    pub fn range_f64(&self) -> (f64, f64) {
        let lo = self
            .coeffs
            .iter()
            .map(|c| c.lower_f64())
            .fold(f64::INFINITY, f64::min);
        let hi = self
            .coeffs
            .iter()
            .map(|c| c.upper_f64())
            .fold(f64::NEG_INFINITY, f64::max);
        (lo, hi)
    }

    /// The sign of the polynomial on the whole unit box, as far as the coefficients prove it:
    /// `Positive` (`Negative`) if every coefficient is certainly positive (negative), so the
    /// polynomial is on the whole closed box; `Zero` if every coefficient is exactly zero (the
    /// zero polynomial); `Unknown` otherwise. A proof for enclosure and exact types
    /// (`proofs/coefficient-range.md`).
    pub fn range_sign(&self) -> Sign {
        Sign::common(self.coeffs.iter().map(|c| c.sign()))
    }

    /// Whether every coefficient is certainly zero: the polynomial is identically zero.
    pub fn is_zero(&self) -> bool {
        self.coeffs.iter().all(|c| c.sign().is_zero())
    }
}

impl Bernstein<crate::number::Interval> {
    /// The hull of the interval coefficients: an enclosure of the polynomial's range over the
    /// unit box (the convex-hull property, `proofs/coefficient-range.md`).
    pub fn hull(&self) -> crate::number::Interval {
        let c = &self.coeffs;
        c[1..].iter().fold(c[0], |a, b| a.hull(b))
    }

    /// `self.deriv(axis).hull()` without forming the derivative: the hull of the coefficient
    /// differences along `axis`, times the degree (each coefficient `d (c_{i+1} − c_i)` of the
    /// derivative lies in `d · H`, `H` the hull of the differences, by inclusion
    /// monotonicity). An enclosure of `∂p/∂x_axis` over the unit box.
    ///
    /// # Panics
    /// If `axis >= nvars`.
    pub fn deriv_hull(&self, axis: usize) -> crate::number::Interval {
        use crate::number::{Interval, Number};
        assert!(axis < self.nvars, "axis out of range");
        let d = self.degrees[axis];
        if d == 0 {
            return Interval::point(0.0);
        }
        let stride = self.stride(axis);
        let mut h: Option<Interval> = None;
        for block in self.coeffs.chunks_exact((d + 1) * stride) {
            for (x, y) in block[..d * stride].iter().zip(&block[stride..]) {
                let diff = y.sub(x);
                h = Some(h.map_or(diff, |a| a.hull(&diff)));
            }
        }
        let h = h.expect("a polynomial has coefficients");
        Interval::point(d as f64).mul(&h)
    }
}
