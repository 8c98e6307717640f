//! Degree elevation.

use super::Bernstein;
use crate::number::{Number, Rational};

impl<N: Number> Bernstein<N> {
    /// The same polynomial written with degree `d + by` along `axis`.
    ///
    /// One step: `c'_i = (i / (d+1)) c_{i-1} + ((d+1-i) / (d+1)) c_i`. The weights are exact
    /// rationals converted to `N` (enclosed for interval types), so the result is exact for
    /// exact types and an enclosure for enclosure types.
    ///
    /// # Panics
    /// If `axis >= nvars`.
    pub fn elevate(&self, axis: usize, by: usize) -> Self {
        assert!(axis < self.nvars, "axis out of range");
        let mut p = self.clone();
        for _ in 0..by {
            p = p.elevate_once(axis);
        }
        p
    }

    fn elevate_once(&self, axis: usize) -> Self {
        let d = self.degrees[axis];
        let stride = self.stride(axis);
        let prec = self.coeffs[0].precision();
        let weight = |i: usize| N::from_rational(&Rational::from((i as u64, (d + 1) as u64)), prec);
        let left: Vec<N> = (0..=d + 1).map(weight).collect();
        let right: Vec<N> = (0..=d + 1).map(|i| weight(d + 1 - i)).collect();
        let mut out = Vec::with_capacity(self.coeffs.len() / (d + 1) * (d + 2));
        for block in self.coeffs.chunks_exact((d + 1) * stride) {
            for i in 0..=d + 1 {
                for s in 0..stride {
                    let v = if i == 0 {
                        block[s].clone()
                    } else if i == d + 1 {
                        block[d * stride + s].clone()
                    } else {
                        left[i]
                            .mul(&block[(i - 1) * stride + s])
                            .add(&right[i].mul(&block[i * stride + s]))
                    };
                    out.push(v);
                }
            }
        }
        self.with_degree(axis, d + 1, out)
    }

    /// The polynomial elevated to at least the given degrees (no change where it is already
    /// at or above them).
    ///
    /// # Panics
    /// If `degrees.len()` is not the number of variables.
    pub fn elevate_to(&self, degrees: &[usize]) -> Self {
        assert_eq!(degrees.len(), self.nvars);
        let mut p = self.clone();
        for (axis, &d) in degrees.iter().enumerate() {
            if d > p.degrees[axis] {
                p = p.elevate(axis, d - p.degrees[axis]);
            }
        }
        p
    }
}
