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
        let mut count = values.len();
        // Contract the last variable first: its fibres are contiguous. Fibre f's value goes to
        // slot f, at or before the fibre's own first slot: only consumed entries are
        // overwritten, and one buffer serves every axis.
        for axis in (0..self.nvars).rev() {
            let len = self.degrees[axis] + 1;
            let t = &point[axis];
            let one_minus_t = N::from_i64(1, t.precision()).sub(t);
            let fibres = count / len;
            for f in 0..fibres {
                let fiber = &mut values[f * len..(f + 1) * len];
                let v = if len - 1 <= HORNER_MAX_DEGREE {
                    fiber_value(fiber, t, &one_minus_t)
                } else {
                    casteljau_step_all(fiber, t, &one_minus_t);
                    fiber[0].clone()
                };
                values[f] = v;
            }
            count = fibres;
        }
        values.swap_remove(0)
    }
}

impl<N: Number> Bernstein<N> {
    /// The value at the centre of the unit box, `Σ_I c_I Π_a C(d_a, I_a) / 2^(Σ_a d_a)`: one
    /// product by an integer weight and one sum per coefficient, no copy
    /// (`proofs/de-casteljau-enclosure.md`). Exact for exact types, an enclosure for
    /// enclosure types; [`Bernstein::eval`] at `(1/2, …)` where a weight would not be an
    /// exact integer below 2⁵³.
    pub fn value_at_centre(&self) -> N {
        let degrees = self.degrees();
        let total: usize = degrees.iter().sum();
        let prec = self.coeffs[0].precision();
        let binomials: Vec<Vec<u64>> = degrees
            .iter()
            .map(|&d| {
                let mut row = vec![1u64; d + 1];
                for i in 1..=d {
                    row[i] = row[i - 1].saturating_mul((d - i + 1) as u64) / i as u64;
                }
                row
            })
            .collect();
        let largest = binomials
            .iter()
            .map(|r| r[r.len() / 2] as f64)
            .product::<f64>();
        if total > 1000 || largest >= 9.0e15 || degrees.iter().any(|&d| d > 60) {
            let half =
                vec![N::from_rational(&crate::number::Rational::from((1, 2)), prec); self.nvars];
            return self.eval(&half);
        }
        let mut sum: Option<N> = None;
        let mut idx = [0usize; super::MAX_VARS];
        for c in &self.coeffs {
            let w: u64 = (0..self.nvars).map(|a| binomials[a][idx[a]]).product();
            let term = if w == 1 {
                c.clone()
            } else {
                c.mul(&N::from_i64(w as i64, prec))
            };
            match &mut sum {
                Some(acc) => acc.add_assign(&term),
                slot @ None => *slot = Some(term),
            }
            // The next multi-index, last variable fastest.
            for a in (0..self.nvars).rev() {
                idx[a] += 1;
                if idx[a] <= degrees[a] {
                    break;
                }
                idx[a] = 0;
            }
        }
        let scale = N::from_rational(
            &crate::number::Rational::from((
                rug::Integer::from(1),
                rug::Integer::from(1) << total as u32,
            )),
            prec,
        );
        sum.expect("a polynomial has a coefficient").mul(&scale)
    }
}

/// Up to this degree a fibre is evaluated in O(n) operations ([`fiber_value`]); its binomial
/// coefficients are integers below 2⁵³, exact in every number type.
const HORNER_MAX_DEGREE: usize = 48;

/// `Σ c_i C(n, i) tⁱ (1 − t)ⁿ⁻ⁱ` for one contiguous fibre in O(n) operations: the powers of t
/// are built one multiplication at a time and the sum is nested in `(1 − t)`:
/// `((c₀(1−t) + C(n,1) t c₁)(1−t) + C(n,2) t² c₂)(1−t) + … + tⁿ cₙ`. The same polynomial
/// value as de Casteljau's algorithm (exact for exact types); evaluated in interval arithmetic
/// every operation encloses its exact result, so the value encloses the exact one
/// (`proofs/de-casteljau-enclosure.md`).
fn fiber_value<N: Number>(fiber: &[N], t: &N, one_minus_t: &N) -> N {
    let n = fiber.len() - 1;
    if n == 0 {
        return fiber[0].clone();
    }
    let prec = t.precision();
    let mut tn = t.clone();
    let mut acc = fiber[0].mul(one_minus_t);
    // C(n, i), exact in u64 for n ≤ 48: C(n, i + 1) = C(n, i) (n − i) / (i + 1).
    let mut c: u64 = 1;
    for (i, x) in fiber.iter().enumerate().take(n).skip(1) {
        c = c * (n - i + 1) as u64 / i as u64;
        let binomial = N::from_i64(c as i64, prec);
        acc = acc.add(&tn.mul(&binomial).mul(x)).mul(one_minus_t);
        tn = tn.mul(t);
    }
    acc.add(&tn.mul(&fiber[n]))
}

/// Runs the whole de Casteljau triangle on one contiguous fibre; the value lands in `fiber[0]`.
fn casteljau_step_all<N: Number>(fiber: &mut [N], t: &N, one_minus_t: &N) {
    for r in (1..fiber.len()).rev() {
        casteljau_step(&mut fiber[..=r], 1, r + 1, t, one_minus_t);
    }
}
