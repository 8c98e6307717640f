//! Subdivision and restriction by de Casteljau's algorithm.

use super::eval::casteljau_step;
use super::Bernstein;
use crate::number::{Interval, Number, Rational};

impl<N: Number> Bernstein<N> {
    /// Splits the box at the middle of `axis`: the polynomials on `[0, 1/2]` and `[1/2, 1]`
    /// along that axis, each reparameterised to `[0, 1]`.
    ///
    /// Uses only `(a + b) / 2`, which is exact in binary floating point except on underflow,
    /// so on intervals the widening is at most one rounding per step
    /// (`proofs/de-casteljau-enclosure.md`).
    ///
    /// # Panics
    /// If `axis >= nvars`.
    pub fn subdivide_half(&self, axis: usize) -> (Self, Self) {
        self.split_with(axis, |row, next| row.midpoint_assign(next))
    }

    /// Splits the box at `t` along `axis` (t in `[0,1]`; an enclosure of t for interval types):
    /// the polynomials on `[0, t]` and `[t, 1]`, each reparameterised to `[0, 1]`.
    ///
    /// # Panics
    /// If `axis >= nvars`.
    pub fn subdivide(&self, axis: usize, t: &N) -> (Self, Self) {
        let one_minus_t = N::from_i64(1, t.precision()).sub(t);
        self.split_with(axis, |row, next| {
            *row = row.mul(&one_minus_t).add(&next.mul(t));
        })
    }

    /// The right half is computed in place (the de Casteljau triangle's lower edge) and the
    /// left half collects the triangle's first entries.
    fn split_with<F: FnMut(&mut N, &N)>(&self, axis: usize, mut step: F) -> (Self, Self) {
        assert!(axis < self.nvars, "axis out of range");
        let d = self.degrees[axis];
        let len = d + 1;
        let stride = self.stride(axis);
        let mut right = self.coeffs.clone();
        let mut left = self.coeffs.clone();
        for (rblock, lblock) in right
            .chunks_exact_mut(len * stride)
            .zip(left.chunks_exact_mut(len * stride))
        {
            for r in 1..len {
                for i in 0..len - r {
                    let (a, b) = rblock.split_at_mut((i + 1) * stride);
                    for (x, y) in a[i * stride..].iter_mut().zip(&b[..stride]) {
                        step(x, y);
                    }
                }
                lblock[r * stride..(r + 1) * stride].clone_from_slice(&rblock[..stride]);
            }
        }
        (
            Bernstein {
                coeffs: left,
                ..*self
            },
            Bernstein {
                coeffs: right,
                ..*self
            },
        )
    }

    /// The polynomial restricted to `[a, b]` along `axis` and reparameterised to `[0, 1]`
    /// (a > b reverses the direction). Computed by the blossom:
    /// the new i-th coefficient is `blossom(a^(d-i), b^i)`; no division is needed, so it is
    /// exact for exact types and an enclosure for interval types.
    ///
    /// # Panics
    /// If `axis >= nvars`.
    pub fn restrict(&self, axis: usize, a: &N, b: &N) -> Self {
        assert!(axis < self.nvars, "axis out of range");
        let d = self.degrees[axis];
        let len = d + 1;
        let stride = self.stride(axis);
        let one = N::from_i64(1, a.precision());
        let (one_minus_a, one_minus_b) = (one.sub(a), one.sub(b));
        let mut out = self.coeffs.clone();
        for (src, dst) in self
            .coeffs
            .chunks_exact(len * stride)
            .zip(out.chunks_exact_mut(len * stride))
        {
            // tri[k] holds the rows after k steps with parameter a (length len - k rows).
            let mut tri = src.to_vec();
            let mut after_a = vec![tri.clone()];
            for k in 1..len {
                casteljau_step(&mut tri, stride, len - k + 1, a, &one_minus_a);
                after_a.push(tri[..(len - k) * stride].to_vec());
            }
            for i in 0..len {
                // i steps with b on the rows after d - i steps with a.
                let mut rows = after_a[d - i].clone();
                for k in 0..i {
                    casteljau_step(&mut rows, stride, i - k + 1, b, &one_minus_b);
                }
                dst[i * stride..(i + 1) * stride].clone_from_slice(&rows[..stride]);
            }
        }
        Bernstein {
            coeffs: out,
            ..*self
        }
    }

    /// The polynomial restricted to the box `[lo_a, hi_a]` in each variable.
    ///
    /// # Panics
    /// If the slices' lengths are not the number of variables.
    pub fn restrict_box(&self, lo: &[N], hi: &[N]) -> Self {
        assert!(lo.len() == self.nvars && hi.len() == self.nvars);
        let mut p = self.clone();
        for axis in 0..self.nvars {
            p = p.restrict(axis, &lo[axis], &hi[axis]);
        }
        p
    }

    /// The polynomial restricted to `[a, b]` along `axis`, with exact rational ends: two
    /// de Casteljau splits, at `a` and then at `(b − a)/(1 − a)` (computed exactly, then
    /// enclosed), O(d²) per fibre instead of the blossom's O(d³). Falls back to
    /// [`Bernstein::restrict`] when `a >= b` or `a = 1`.
    ///
    /// # Panics
    /// If `axis >= nvars`.
    pub fn restrict_rational(&self, axis: usize, a: &Rational, b: &Rational) -> Self {
        let prec = self.coeffs[0].precision();
        if a >= b || *a == 1 {
            return self.restrict(axis, &N::from_rational(a, prec), &N::from_rational(b, prec));
        }
        let right = if a.cmp0() == std::cmp::Ordering::Equal {
            self.clone()
        } else {
            self.subdivide(axis, &N::from_rational(a, prec)).1
        };
        let t = Rational::from(b - a) / Rational::from(1 - a);
        if t == 1 {
            return right;
        }
        right.subdivide(axis, &N::from_rational(&t, prec)).0
    }

    /// The polynomial restricted to the box `[lo_a, hi_a]` (exact rational bounds) in each
    /// variable, by [`Bernstein::restrict_rational`].
    ///
    /// # Panics
    /// If the slices' lengths are not the number of variables.
    pub fn restrict_box_rational(&self, lo: &[Rational], hi: &[Rational]) -> Self {
        assert!(lo.len() == self.nvars && hi.len() == self.nvars);
        let mut p = self.clone();
        for axis in 0..self.nvars {
            p = p.restrict_rational(axis, &lo[axis], &hi[axis]);
        }
        p
    }
}

impl Bernstein<Interval> {
    /// The polynomial restricted to the box `[lo, hi]` (f64 bounds, any reals with
    /// `lo ≤ hi`; outside `[0, 1]` the polynomial is extended), as interval coefficients that
    /// enclose the exact restriction's. Per axis, two de Casteljau splits in place: at `a`,
    /// keeping the right part, then at an interval `t ∋ (b − a)/(1 − a)` (outward-rounded
    /// division), keeping the left part; de Casteljau's algorithm is inclusion-monotone, so an
    /// enclosure of `t` gives an enclosure of the coefficients (`proofs/de-casteljau-enclosure.md`).
    /// O(d²) per fibre and no allocation beyond the copy; a side of zero width, or `a = 1`,
    /// takes the blossom ([`Bernstein::restrict`]).
    ///
    /// # Panics
    /// If the slices' lengths are not the number of variables.
    pub fn restrict_box_f64(&self, lo: &[f64], hi: &[f64]) -> Self {
        assert!(lo.len() == self.nvars && hi.len() == self.nvars);
        let mut p = self.clone();
        for axis in 0..self.nvars {
            let (a, b) = (lo[axis], hi[axis]);
            if a == 0.0 && b == 1.0 {
                continue;
            }
            let (ai, bi, one) = (Interval::point(a), Interval::point(b), Interval::point(1.0));
            let t = (a < b && a != 1.0)
                .then(|| bi.sub(&ai).checked_div(&one.sub(&ai)))
                .flatten();
            match t {
                Some(t) => {
                    if a != 0.0 {
                        p.keep_right_in_place(axis, &ai);
                    }
                    if !(t.lo() == 1.0 && t.hi() == 1.0) {
                        p.keep_left_in_place(axis, &t);
                    }
                }
                None => p = p.restrict(axis, &ai, &bi),
            }
        }
        p
    }

    /// The part `[t, 1]` along `axis`, reparameterised to `[0, 1]`, in place (the lower edge
    /// of the de Casteljau triangle).
    fn keep_right_in_place(&mut self, axis: usize, t: &Interval) {
        let len = self.degrees[axis] + 1;
        let stride = self.stride(axis);
        let one_minus_t = Interval::point(1.0).sub(t);
        for block in self.coeffs.chunks_exact_mut(len * stride) {
            for r in 1..len {
                casteljau_step(
                    &mut block[..(len - r + 1) * stride],
                    stride,
                    len - r + 1,
                    t,
                    &one_minus_t,
                );
            }
        }
    }

    /// The part `[0, t]` along `axis`, reparameterised to `[0, 1]`, in place (the upper edge
    /// of the de Casteljau triangle: at level r, row i ≥ r is updated from rows i − 1 and i,
    /// descending, so row r ends as the level's first entry).
    fn keep_left_in_place(&mut self, axis: usize, t: &Interval) {
        let len = self.degrees[axis] + 1;
        let stride = self.stride(axis);
        let one_minus_t = Interval::point(1.0).sub(t);
        for block in self.coeffs.chunks_exact_mut(len * stride) {
            for r in 1..len {
                for i in (r..len).rev() {
                    let (prev, cur) = block.split_at_mut(i * stride);
                    for (x, y) in cur[..stride].iter_mut().zip(&prev[(i - 1) * stride..]) {
                        *x = y.mul(&one_minus_t).add(&x.mul(t));
                    }
                }
            }
        }
    }
}
