//! Evaluation by de Casteljau's algorithm.

use super::Bernstein;
use crate::number::Number;

/// One de Casteljau step on rows: `row_i = (1 - t) row_i + t row_{i+1}`, for i < len - 1.
pub(super) fn casteljau_step<N: Number>(
    rows: &mut [N],
    stride: usize,
    len: usize,
    t: &N,
    one_minus_t: &N,
) {
    for i in 0..len - 1 {
        let (a, b) = rows.split_at_mut((i + 1) * stride);
        for (x, y) in a[i * stride..].iter_mut().zip(&b[..stride]) {
            *x = x.mul(one_minus_t).add(&y.mul(t));
        }
    }
}

impl<N: Number> Bernstein<N> {
    /// The value at a point of the unit box (de Casteljau in each variable).
    ///
    /// Exact for exact types; an enclosure of the exact value for enclosure types when the
    /// point's coordinates are enclosed (`proofs/de-casteljau-enclosure.md`). Points outside
    /// the box are allowed (the polynomial is defined everywhere).
    ///
    /// # Panics
    /// If `point.len()` is not the number of variables.
    pub fn eval(&self, point: &[N]) -> N {
        assert_eq!(point.len(), self.nvars, "point dimension");
        let mut values = self.coeffs.clone();
        // Contract the last variable first: its fibres are contiguous.
        for axis in (0..self.nvars).rev() {
            let len = self.degrees[axis] + 1;
            let t = &point[axis];
            let one_minus_t = N::from_i64(1, t.precision()).sub(t);
            let mut out = Vec::with_capacity(values.len() / len);
            for fiber in values.chunks_exact_mut(len) {
                casteljau_step_all(fiber, t, &one_minus_t);
                out.push(fiber[0].clone());
            }
            values = out;
        }
        values.pop().expect("one value remains")
    }
}

/// Runs the whole de Casteljau triangle on one contiguous fibre; the value lands in `fiber[0]`.
fn casteljau_step_all<N: Number>(fiber: &mut [N], t: &N, one_minus_t: &N) {
    for r in (1..fiber.len()).rev() {
        casteljau_step(&mut fiber[..=r], 1, r + 1, t, one_minus_t);
    }
}
