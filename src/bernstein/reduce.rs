//! Exact degree reduction of exact polynomials.

use super::Bernstein;
use crate::number::Rational;

impl Bernstein<Rational> {
    /// The same polynomial at the lowest degrees it really has: along each axis, the degree is
    /// lowered while the polynomial is exactly of lower degree there.
    ///
    /// For one fibre of degree d, the candidate of degree d - 1 is `b_0 = c_0`,
    /// `b_i = (d c_i - i b_{i-1}) / (d - i)`; it is accepted only if `b_{d-1} = c_d`, which with
    /// the recurrence is exactly the condition that elevating it gives `c` back, so the result
    /// is always the same polynomial.
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
        // Elevation gives c_i = (i b_{i−1} + (d − i) b_i) / d: the recurrence above solves
        // exactly these equations for i < d, and the check of c_d = b_{d−1} is the last one,
        // so the candidate elevates back to the polynomial exactly.
        debug_assert!(candidate.elevate(axis, 1) == *self);
        Some(candidate)
    }

    /// Divides out the linear factor `t_axis` (`at_one = false`) or `1 − t_axis`
    /// (`at_one = true`) exactly, if the polynomial vanishes on that face of the box (all the
    /// coefficients on the face are zero); `None` otherwise, or at degree 0 along `axis`.
    ///
    /// In degree n, `t · Σ_j b_j B_{n−1,j} = Σ_j b_{j−1} (j/n) B_{n,j}`, so the quotient has
    /// `b_j = c_{j+1} · n / (j + 1)`; symmetrically `(1 − t) · Σ b_j B_{n−1,j} =
    /// Σ b_j ((n − j)/n) B_{n,j}` gives `b_j = c_j · n / (n − j)`.
    ///
    /// # Panics
    /// If `axis >= nvars`.
    pub fn divide_face_factor(&self, axis: usize, at_one: bool) -> Option<Self> {
        assert!(axis < self.nvars, "axis out of range");
        let n = self.degrees[axis];
        if n == 0 {
            return None;
        }
        let stride = self.stride(axis);
        let face = if at_one { n } else { 0 };
        let zero_face = self.coeffs.chunks_exact((n + 1) * stride).all(|block| {
            block[face * stride..(face + 1) * stride]
                .iter()
                .all(|c| c.cmp0() == std::cmp::Ordering::Equal)
        });
        if !zero_face {
            return None;
        }
        let mut out = Vec::with_capacity(self.coeffs.len() / (n + 1) * n);
        for block in self.coeffs.chunks_exact((n + 1) * stride) {
            for j in 0..n {
                for s in 0..stride {
                    out.push(if at_one {
                        Rational::from(&block[j * stride + s] * n as u64) / (n - j) as u64
                    } else {
                        Rational::from(&block[(j + 1) * stride + s] * n as u64) / (j as u64 + 1)
                    });
                }
            }
        }
        Some(self.with_degree(axis, n - 1, out))
    }
}

impl Bernstein<Rational> {
    /// Divides out the linear factor `t_axis − c` exactly, if it divides the polynomial;
    /// `None` otherwise, or at degree 0 along `axis`, or for `c` outside (0, 1) (the faces are
    /// [`Bernstein::divide_face_factor`]).
    ///
    /// In degree n, `t − c = −c (1 − t) + (1 − c) t`, and the product with
    /// `Σ_j q_j B_{n−1,j}` has coefficients `p_i = ((n − i)(−c) q_i + i (1 − c) q_{i−1}) / n`.
    /// So `q_0 = −p_0 / c` and `q_i = (n p_i − i (1 − c) q_{i−1}) / ((n − i)(−c))`; the
    /// candidate is accepted only if multiplying it back gives the polynomial exactly.
    ///
    /// # Panics
    /// If `axis >= nvars`.
    ///
    /// # Examples
    /// ```
    /// use limn::bernstein::Bernstein;
    /// use limn::number::Rational;
    /// // (t − 1/2)(t − 1/4) = t² − 3t/4 + 1/8: Bernstein coefficients 1/8, −1/4, 3/8.
    /// let q = |n: i64, d: i64| Rational::from((n, d));
    /// let p = Bernstein::new(&[2], vec![q(1, 8), q(-1, 4), q(3, 8)]).unwrap();
    /// let r = p.divide_linear_factor(0, &q(1, 2)).unwrap();
    /// assert_eq!(r.coeffs(), &[q(-1, 4), q(3, 4)]); // t − 1/4
    /// assert!(p.divide_linear_factor(0, &q(1, 3)).is_none());
    /// ```
    pub fn divide_linear_factor(&self, axis: usize, c: &Rational) -> Option<Self> {
        assert!(axis < self.nvars, "axis out of range");
        let n = self.degrees[axis];
        if n == 0 || c.cmp0() != std::cmp::Ordering::Greater || *c >= 1 {
            return None;
        }
        let stride = self.stride(axis);
        let a0 = Rational::from(-c);
        let a1 = Rational::from(1 - c);
        let mut out: Vec<Rational> = vec![Rational::new(); self.coeffs.len() / (n + 1) * n];
        for (b, block) in self.coeffs.chunks_exact((n + 1) * stride).enumerate() {
            let base = b * n * stride;
            for s in 0..stride {
                let mut prev = Rational::new();
                for i in 0..n {
                    let num = Rational::from(&block[i * stride + s] * n as u64)
                        - Rational::from(&a1 * &prev) * i as u64;
                    prev = num / Rational::from(&a0 * (n - i) as u64);
                    out[base + i * stride + s] = prev.clone();
                }
            }
        }
        let candidate = self.with_degree(axis, n - 1, out);
        let mut lin_degrees = vec![0usize; self.nvars];
        lin_degrees[axis] = 1;
        let lin = Bernstein::new(&lin_degrees, vec![a0, a1]).expect("two coefficients");
        (&candidate * &lin == *self).then_some(candidate)
    }
}
