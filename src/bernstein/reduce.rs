//! Exact degree reduction of exact polynomials.

use super::Bernstein;
use crate::number::Rational;

impl Bernstein<Rational> {
    /// The same polynomial at the lowest degrees it really has: along each axis, the degree is
    /// lowered while the polynomial is exactly of lower degree there.
    ///
    /// For one fibre of degree d, the candidate of degree d - 1 is `b_0 = c_0`,
    /// `b_i = (d c_i - i b_{i-1}) / (d - i)`; it is accepted only if elevating it gives `c`
    /// back exactly, so the result is always the same polynomial.
    pub fn reduce_degree_exact(&self) -> Self {
        let mut p = self.clone();
        for axis in 0..p.nvars {
            while p.degrees[axis] > 0 {
                match p.reduce_once(axis) {
                    Some(q) => p = q,
                    None => break,
                }
            }
        }
        p
    }

    fn reduce_once(&self, axis: usize) -> Option<Self> {
        let d = self.degrees[axis];
        let stride = self.stride(axis);
        let mut out = Vec::with_capacity(self.coeffs.len() / (d + 1) * d);
        for block in self.coeffs.chunks_exact((d + 1) * stride) {
            let start = out.len();
            for s in 0..stride {
                let mut prev = block[s].clone();
                let mut fibre = vec![prev.clone()];
                for i in 1..d {
                    let num = Rational::from(&block[i * stride + s] * d as u64)
                        - Rational::from(&prev * i as u64);
                    prev = num / (d - i) as u64;
                    fibre.push(prev.clone());
                }
                // The last coefficient must be reproduced exactly.
                if fibre[d - 1] != block[d * stride + s] {
                    return None;
                }
                out.extend(fibre);
            }
            // `out` holds this block fibre by fibre; transpose to rows.
            let fibres: Vec<Rational> = out.drain(start..).collect();
            for i in 0..d {
                for s in 0..stride {
                    out.push(fibres[s * d + i].clone());
                }
            }
        }
        let candidate = self.with_degree(axis, d - 1, out);
        // Accept only if it elevates back exactly (checks every interior coefficient too).
        (candidate.elevate(axis, 1) == *self).then_some(candidate)
    }
}
