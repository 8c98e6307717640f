//! A bivariate polynomial along a polynomial curve: `p(x(t), y(t))` as a univariate Bernstein
//! polynomial, enclosed in interval arithmetic (`proofs/cubic-pieces.md`, "The composition").
//!
//! The work is done in the *scaled* Bernstein basis `tᵏ(1 − t)ⁿ⁻ᵏ` (coefficients
//! `ĉ_k = C(n, k) c_k`), where the product of two polynomials is the convolution of their
//! coefficients: `Σ ĉ_i tⁱ(1−t)ᵃ⁻ⁱ · Σ d̂_j tʲ(1−t)ᵇ⁻ʲ = Σ_k (Σ_{i+j=k} ĉ_i d̂_j) tᵏ(1−t)ᵃ⁺ᵇ⁻ᵏ`.
//! So `p(x(t), y(t)) = Σ_ij c_ij C(d₀,i) C(d₁,j) xⁱ(1−x)^{d₀−i} yʲ(1−y)^{d₁−j}` needs only
//! convolutions, sums and products by exact binomials, each an interval operation rounded
//! outward, with one division by the binomials of the result's degree at the end.

use super::Bernstein;
use crate::number::{Interval, Number};

/// `C(n, k)` for `k = 0..=n` as f64, or `None` if one is not exact in f64 (it is for
/// `n ≤ 56`).
fn binomials(n: usize) -> Option<Vec<f64>> {
    let mut row = vec![1u64; n + 1];
    for k in 1..n {
        // C(n, k) = C(n, k − 1) (n − k + 1) / k, exact in u128.
        let v = u128::from(row[k - 1]) * (n - k + 1) as u128 / k as u128;
        row[k] = u64::try_from(v).ok()?;
    }
    row.iter()
        .map(|&c| (c <= 1 << 53).then_some(c as f64))
        .collect()
}

/// The arithmetic the composition runs on: intervals (outward rounded), or f64 values with
/// their running error data ([`Run`]).
trait Ring: Copy {
    fn point(x: f64) -> Self;
    fn plus(self, other: Self) -> Self;
    fn times(self, other: Self) -> Self;
    /// `1 − self`.
    fn one_minus(self) -> Self;
}

impl Ring for Interval {
    fn point(x: f64) -> Self {
        Interval::point(x)
    }
    fn plus(self, other: Self) -> Self {
        self.add(&other)
    }
    fn times(self, other: Self) -> Self {
        self.mul(&other)
    }
    fn one_minus(self) -> Self {
        Interval::point(1.0).sub(&self)
    }
}

/// An f64 value computed by sums and products, with the same computation run on absolute
/// values (`abs`) and the most roundings any of its terms went through (`k`): the exact value
/// is within `γ_k · abs / (1 − γ_k)` of `v` (`proofs/cubic-pieces.md`, "The composition").
#[derive(Clone, Copy, Debug)]
struct Run {
    v: f64,
    abs: f64,
    k: u32,
}

impl Ring for Run {
    fn point(x: f64) -> Self {
        Run {
            v: x,
            abs: x.abs(),
            k: 0,
        }
    }
    fn plus(self, o: Self) -> Self {
        Run {
            v: self.v + o.v,
            abs: self.abs + o.abs,
            k: self.k.max(o.k) + 1,
        }
    }
    fn times(self, o: Self) -> Self {
        Run {
            v: self.v * o.v,
            abs: self.abs * o.abs,
            k: self.k + o.k + 1,
        }
    }
    fn one_minus(self) -> Self {
        // An exact input: one rounding of the exact 1 − v. Otherwise the sum 1 + (−v).
        let abs = if self.k == 0 {
            (1.0 - self.v).abs()
        } else {
            1.0 + self.abs
        };
        Run {
            v: 1.0 - self.v,
            abs,
            k: self.k + 1,
        }
    }
}

/// The convolution of two coefficient sequences (the product in the scaled basis).
fn conv<R: Ring>(a: &[R], b: &[R]) -> Vec<R> {
    let mut out: Vec<Option<R>> = vec![None; a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            let t = x.times(*y);
            out[i + j] = Some(match out[i + j] {
                Some(acc) => acc.plus(t),
                None => t,
            });
        }
    }
    out.into_iter()
        .map(|c| c.expect("every index is reached"))
        .collect()
}

/// Scaled coefficients of a univariate polynomial given by its Bernstein coefficients.
fn scaled<R: Ring>(c: &[R]) -> Option<Vec<R>> {
    let b = binomials(c.len() - 1)?;
    Some(
        c.iter()
            .zip(&b)
            .map(|(x, w)| x.times(R::point(*w)))
            .collect(),
    )
}

/// `Σ_k a_k C(d, k) zᵏ (1 − z)^{d−k}` for polynomial coefficients `a_k` (scaled, all of one
/// degree) and a polynomial argument `z` (scaled, with `one_minus` its complement), by the
/// homogeneous Horner scheme `h₀ = a_d`, `h_k = h_{k−1} z + C(d, d−k) a_{d−k} (1 − z)ᵏ`.
fn horner<R: Ring>(a: &[Vec<R>], z: &[R], one_minus: &[R]) -> Option<Vec<R>> {
    let d = a.len() - 1;
    let w = binomials(d)?;
    let times = |p: &[R], c: f64| -> Vec<R> { p.iter().map(|x| x.times(R::point(c))).collect() };
    let mut h = times(&a[d], w[d]);
    let mut power = vec![R::point(1.0)];
    for k in 1..=d {
        power = conv(&power, one_minus);
        let left = conv(&h, z);
        let right = conv(&times(&a[d - k], w[d - k]), &power);
        h = left.iter().zip(&right).map(|(x, y)| x.plus(*y)).collect();
    }
    Some(h)
}

/// The composition in the scaled basis, for coefficients `c(i, j)` of degrees `(d0, d1)`.
fn compose_scaled<R: Ring>(
    [d0, d1]: [usize; 2],
    c: impl Fn(usize, usize) -> R,
    x: &[R],
    y: &[R],
) -> Option<Vec<R>> {
    let complement = |z: &[R]| -> Vec<R> { z.iter().map(|v| v.one_minus()).collect() };
    let (xs, xc) = (scaled(x)?, scaled(&complement(x))?);
    let (ys, yc) = (scaled(y)?, scaled(&complement(y))?);
    // Along axis 1 for each i: q_i(t) = Σ_j c_ij B_j(y(t)), scaled.
    let q: Vec<Vec<R>> = (0..=d0)
        .map(|i| {
            let row: Vec<Vec<R>> = (0..=d1).map(|j| vec![c(i, j)]).collect();
            horner(&row, &ys, &yc)
        })
        .collect::<Option<_>>()?;
    horner(&q, &xs, &xc)
}

/// `p(x(t), y(t))` for a bivariate `p` and a curve given by the Bernstein coefficients (in t)
/// of its coordinates, as univariate Bernstein coefficients of degree
/// `d₀ deg x + d₁ deg y` enclosing the exact ones (every interval operation rounds outward).
/// `None` if `p` is not bivariate, a coordinate has no coefficient, or a degree is beyond
/// 56 (where the binomials are not exact in f64).
pub fn compose_curve(
    p: &Bernstein<Interval>,
    x: &[Interval],
    y: &[Interval],
) -> Option<Bernstein<Interval>> {
    if p.nvars() != 2 || x.is_empty() || y.is_empty() {
        return None;
    }
    let d = [p.degrees()[0], p.degrees()[1]];
    let r = compose_scaled(d, |i, j| *p.coeff(&[i, j]), x, y)?;
    let b = binomials(r.len() - 1)?;
    let coeffs = r
        .iter()
        .zip(&b)
        .map(|(c, w)| c.checked_div(&Interval::point(*w)))
        .collect::<Option<Vec<_>>>()?;
    Bernstein::new(&[r.len() - 1], coeffs).ok()
}

/// [`compose_curve`] in f64 with a running error bound, for a curve with exact f64
/// coefficients: each coefficient is computed once in f64 and once on absolute values, and
/// the returned interval is the value ± `(γ_k + ρ) · abs / (1 − γ_k)`, `k` the most roundings
/// of any term (the final division by a binomial included) and `ρ` the largest relative width
/// `rad / (|mid| + rad)` of `p`'s coefficients (`proofs/cubic-pieces.md`, "The
/// composition"). Several times faster than the interval version; as tight where the curve's
/// coordinates lie in `[0, 1]`.
pub fn compose_curve_f64(
    p: &Bernstein<Interval>,
    x: &[f64],
    y: &[f64],
) -> Option<Bernstein<Interval>> {
    if p.nvars() != 2 || x.is_empty() || y.is_empty() {
        return None;
    }
    let mut rho: f64 = 0.0;
    let coeff = |c: &Interval| {
        let mid = 0.5 * c.lo() + 0.5 * c.hi();
        let rad = (c.hi() - mid).max(mid - c.lo());
        (mid, rad)
    };
    for c in p.coeffs() {
        let (mid, rad) = coeff(c);
        if !(mid.is_finite() && rad.is_finite()) {
            return None;
        }
        if rad > 0.0 {
            rho = rho.max(rad / (mid.abs() + rad));
        }
    }
    // The radius is rounded: grow ρ by a relative margin for it and the quotient.
    let rho = crate::number::margin::up(rho, crate::number::margin::FEW);
    let d = [p.degrees()[0], p.degrees()[1]];
    let input = |i: usize, j: usize| {
        let (mid, rad) = coeff(p.coeff(&[i, j]));
        Run {
            v: mid,
            abs: mid.abs() + rad,
            k: 0,
        }
    };
    let points = |z: &[f64]| -> Vec<Run> { z.iter().map(|&v| Run::point(v)).collect() };
    let r = compose_scaled(d, input, &points(x), &points(y))?;
    let b = binomials(r.len() - 1)?;
    let u = crate::number::margin::UNIT_ROUNDOFF;
    let coeffs = r
        .iter()
        .zip(&b)
        .map(|(c, w)| {
            let v = c.v / w;
            let abs = c.abs / w;
            let k = f64::from(c.k + 1);
            let gamma = k * u / (1.0 - k * u);
            let e = (gamma + rho) * abs / (1.0 - gamma);
            let e = crate::number::margin::up(e, crate::number::margin::FEW);
            (v.is_finite() && e.is_finite() && k * u < 0.5).then(|| {
                let (v, e) = (Interval::point(v), Interval::point(e));
                Interval::new(v.sub(&e).lo(), v.add(&e).hi())
            })
        })
        .collect::<Option<Vec<_>>>()?;
    Bernstein::new(&[r.len() - 1], coeffs).ok()
}

/// The hull of the coefficients of `n(t) − σ(t) d(t)` (an enclosure of its range on
/// `[0, 1]`), for univariate `n` and `d` of one degree (enclosed coefficients) and a
/// univariate `σ` given by exact f64 Bernstein coefficients: `n` is raised to the product's
/// degree by the convolution with `C(deg σ, ·)` (in the scaled basis, `1 = (t + (1 − t))^k`).
/// `None` if the degrees differ or are beyond 56.
pub fn residual_hull(
    n: &Bernstein<Interval>,
    d: &Bernstein<Interval>,
    sigma: &[f64],
) -> Option<Interval> {
    if n.nvars() != 1 || d.nvars() != 1 || n.degrees()[0] != d.degrees()[0] || sigma.is_empty() {
        return None;
    }
    let k = sigma.len() - 1;
    let s = scaled(
        &sigma
            .iter()
            .map(|&c| Interval::point(c))
            .collect::<Vec<_>>(),
    )?;
    let one = binomials(k)?
        .into_iter()
        .map(Interval::point)
        .collect::<Vec<_>>();
    let raised = conv(&scaled(n.coeffs())?, &one);
    let product = conv(&s, &scaled(d.coeffs())?);
    let b = binomials(raised.len() - 1)?;
    let mut hull: Option<Interval> = None;
    for ((x, y), w) in raised.iter().zip(&product).zip(&b) {
        let c = x.sub(y).checked_div(&Interval::point(*w))?;
        hull = Some(hull.map_or(c, |h| h.hull(&c)));
    }
    hull
}

/// `W^{d₀+d₁} · p(U/W, V/W)` for a bivariate `p` of degrees `(d₀, d₁)` and a rational curve
/// given by the univariate polynomials `U, V, W` of one degree `n` (its homogeneous
/// coordinates): a univariate polynomial of degree `n (d₀ + d₁)`, exact for exact `N`.
///
/// With `x = U/W`, `B_i^{d}(x) = C(d, i) Uⁱ (W − U)^{d−i} / W^d`, so
/// `W^{d₀+d₁} p(U/W, V/W) = Σ_ij c_ij C(d₀,i) C(d₁,j) Uⁱ (W−U)^{d₀−i} Vʲ (W−V)^{d₁−j}`: sums
/// and products of polynomials only. Where `W > 0` its sign is the sign of `p` along the
/// curve, and its roots are the curve's points on `p = 0` (`proofs/trimmed-faces.md`, 8).
///
/// # Panics
/// If `p` is not bivariate or `U, V, W` are not univariate of one degree.
pub fn compose_homogeneous<N: crate::number::Number>(
    p: &Bernstein<N>,
    [u, v, w]: [&Bernstein<N>; 3],
) -> Bernstein<N> {
    assert_eq!(p.nvars(), 2, "a bivariate polynomial");
    assert!(
        [u, v, w]
            .iter()
            .all(|c| c.nvars() == 1 && c.degrees() == w.degrees()),
        "univariate coordinates of one degree"
    );
    let prec = p.coeffs()[0].precision();
    let one = Bernstein::constant(1, N::from_i64(1, prec));
    let powers = |x: &Bernstein<N>, d: usize| -> Vec<Bernstein<N>> {
        let mut out = vec![one.clone()];
        for k in 1..=d {
            out.push(out[k - 1].try_mul(x).expect("univariate"));
        }
        out
    };
    // The basis polynomials xⁱ(1 − x)^{d−i} in homogeneous form, times C(d, i).
    let basis = |x: &Bernstein<N>, d: usize| -> Vec<Bernstein<N>> {
        let complement = w.try_sub(x).expect("one degree");
        let (a, b) = (powers(x, d), powers(&complement, d));
        let mut c = crate::number::Rational::from(1);
        (0..=d)
            .map(|i| {
                if i > 0 {
                    // C(d, i) = C(d, i − 1) (d − i + 1) / i.
                    c = c.clone() * crate::number::Rational::from((d - i + 1) as i64)
                        / crate::number::Rational::from(i as i64);
                }
                a[i].try_mul(&b[d - i])
                    .expect("univariate")
                    .scale(&N::from_rational(&c, prec))
            })
            .collect()
    };
    let [d0, d1] = [p.degrees()[0], p.degrees()[1]];
    let (bu, bv) = (basis(u, d0), basis(v, d1));
    let mut out: Option<Bernstein<N>> = None;
    for (i, bu_i) in bu.iter().enumerate() {
        let mut q: Option<Bernstein<N>> = None;
        for (j, bv_j) in bv.iter().enumerate() {
            let term = bv_j.scale(p.coeff(&[i, j]));
            q = Some(match q {
                Some(q) => q.try_add(&term).expect("one degree"),
                None => term,
            });
        }
        let term = q.expect("d1 + 1 terms").try_mul(bu_i).expect("univariate");
        out = Some(match out {
            Some(o) => o.try_add(&term).expect("one degree"),
            None => term,
        });
    }
    out.expect("d0 + 1 terms")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::{Precision, Rational};
    use proptest::prelude::*;

    fn rat(n: i64, d: i64) -> Rational {
        Rational::from((n, d))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        /// The composition's coefficients, evaluated at rational t, enclose the exact value
        /// of p at the exact curve point (computed in rationals).
        #[test]
        fn the_composition_encloses_the_exact_values(
            d0 in 0usize..6, d1 in 0usize..6,
            seed in proptest::collection::vec(-50i64..50, 36),
            xs in proptest::collection::vec(-8i64..24, 1..5),
            ys in proptest::collection::vec(-8i64..24, 1..3),
            tn in 0i64..=16,
        ) {
            let coeffs: Vec<Rational> = (0..(d0 + 1) * (d1 + 1))
                .map(|k| rat(seed[k % seed.len()] + k as i64, 7))
                .collect();
            let p = Bernstein::new(&[d0, d1], coeffs).expect("bivariate");
            let xq: Vec<Rational> = xs.iter().map(|&n| rat(n, 16)).collect();
            let yq: Vec<Rational> = ys.iter().map(|&n| rat(n, 16)).collect();
            let to_iv = |v: &[Rational]| -> Vec<Interval> {
                v.iter().map(|q| Interval::from_rational(q, Precision::F64)).collect()
            };
            let pi: Bernstein<Interval> = p.convert(Precision::F64);
            let c = compose_curve(&pi, &to_iv(&xq), &to_iv(&yq)).expect("small degrees");
            prop_assert_eq!(c.degrees()[0], d0 * (xq.len() - 1) + d1 * (yq.len() - 1));
            let t = rat(tn, 16);
            let curve = |v: &[Rational]| {
                Bernstein::new(&[v.len() - 1], v.to_vec()).expect("univariate").eval(std::slice::from_ref(&t))
            };
            let exact = p.eval(&[curve(&xq), curve(&yq)]);
            let enclosed = c.eval(&[Interval::from_rational(&t, Precision::F64)]);
            prop_assert!(enclosed.contains_rational(&exact), "{enclosed:?} misses {exact}");
            // The f64 filter with its running error bound encloses it too.
            // (n / 16 is exact in f64.)
            let f = |v: &[Rational]| -> Vec<f64> { v.iter().map(Number::to_f64).collect() };
            let c = compose_curve_f64(&pi, &f(&xq), &f(&yq)).expect("small degrees");
            let enclosed = c.eval(&[Interval::from_rational(&t, Precision::F64)]);
            prop_assert!(enclosed.contains_rational(&exact), "f64: {enclosed:?} misses {exact}");
        }
    }

    #[test]
    fn the_residual_hull_encloses_n_minus_sigma_d() {
        // n(t) = t (degree 2 as [0, 1/2, 1]), d = 1, σ = t as a cubic [0, 1/3, 2/3, 1]
        // rounded: the residual is a few ulps, and at t = 1/2 it is enclosed.
        let n = Bernstein::new(&[2], [0.0, 0.5, 1.0].map(Interval::point).to_vec())
            .expect("univariate");
        let d = Bernstein::new(&[2], [1.0; 3].map(Interval::point).to_vec()).expect("univariate");
        let sigma = [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0];
        let h = residual_hull(&n, &d, &sigma).expect("small degrees");
        assert!(h.lo() <= 0.0 && h.hi() >= 0.0 && h.width() < 1e-15, "{h:?}");
        // σ = 2t: the residual −t reaches −1.
        let h = residual_hull(&n, &d, &[0.0, 2.0 / 3.0, 4.0 / 3.0, 2.0]).expect("small degrees");
        assert!(h.lo() <= -1.0 && h.hi() >= 0.0, "{h:?}");
    }

    #[test]
    fn binomials_are_exact_up_to_56() {
        assert!(binomials(56).is_some());
        assert!(binomials(80).is_none());
        assert_eq!(binomials(4).expect("small"), vec![1.0, 4.0, 6.0, 4.0, 1.0]);
    }
}
