//! Partial derivatives.

use super::Bernstein;
use crate::number::Number;

impl<N: Number> Bernstein<N> {
    /// The partial derivative along `axis`: degree `d - 1`, coefficients
    /// `d (c_{i+1} - c_i)`. A polynomial of degree 0 along `axis` has derivative 0
    /// (kept at degree 0).
    ///
    /// # Panics
    /// If `axis >= nvars`.
    pub fn deriv(&self, axis: usize) -> Self {
        assert!(axis < self.nvars, "axis out of range");
        let d = self.degrees[axis];
        if d == 0 {
            return self.map(|c| c.zero_like());
        }
        let stride = self.stride(axis);
        let factor = N::from_i64(d as i64, self.coeffs[0].precision());
        let mut out = Vec::with_capacity(self.coeffs.len() / (d + 1) * d);
        for block in self.coeffs.chunks_exact((d + 1) * stride) {
            for i in 0..d {
                for s in 0..stride {
                    let diff = block[(i + 1) * stride + s].sub(&block[i * stride + s]);
                    out.push(factor.mul(&diff));
                }
            }
        }
        self.with_degree(axis, d - 1, out)
    }
}
