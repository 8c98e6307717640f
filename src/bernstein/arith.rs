//! Sums, differences, scaling and products.

use super::{Bernstein, BernsteinError};
use crate::number::{Number, Rational};
use rug::Integer;
use std::borrow::Cow;

/// `Π_a C(d_a, i_a)`, exactly.
fn binomial_weight(degrees: &[usize], index: &[usize]) -> Integer {
    degrees
        .iter()
        .zip(index)
        .map(|(&d, &i)| Integer::from(Integer::binomial_u(d as u32, i as u32)))
        .product()
}

impl<N: Number> Bernstein<N> {
    fn common_degrees(&self, other: &Self) -> Result<Vec<usize>, BernsteinError> {
        if self.nvars != other.nvars {
            return Err(BernsteinError::Mismatch(self.nvars, other.nvars));
        }
        Ok((0..self.nvars)
            .map(|a| self.degrees[a].max(other.degrees[a]))
            .collect())
    }

    fn zip_with(&self, other: &Self, f: impl Fn(&N, &N) -> N) -> Result<Self, BernsteinError> {
        let d = self.common_degrees(other)?;
        // Elevated (a copy) only where an operand's degrees are below the common ones.
        fn at<'p, N: Number>(p: &'p Bernstein<N>, d: &[usize]) -> Cow<'p, Bernstein<N>> {
            if p.degrees() == d {
                Cow::Borrowed(p)
            } else {
                Cow::Owned(p.elevate_to(d))
            }
        }
        let (a, b) = (at(self, &d), at(other, &d));
        let coeffs = a
            .coeffs
            .iter()
            .zip(&b.coeffs)
            .map(|(x, y)| f(x, y))
            .collect();
        Ok(Bernstein {
            nvars: a.nvars,
            degrees: a.degrees,
            coeffs,
        })
    }

    /// The product of polynomials in disjoint sets of variables (in every variable one of
    /// them has degree 0): the tensor product of the coefficients. The general formula's
    /// binomial weights are then all 1 (`C(d, i) C(0, 0) / C(d, i)`), so this is the same
    /// polynomial, exact for exact types and an enclosure for enclosure types.
    fn mul_disjoint(&self, other: &Self) -> Self {
        let k = self.nvars;
        let mut degrees = [0; super::MAX_VARS];
        for (a, d) in degrees.iter_mut().enumerate().take(k) {
            *d = self.degrees[a] + other.degrees[a];
        }
        let template = Bernstein {
            nvars: k,
            degrees,
            coeffs: Vec::<N>::new(),
        };
        let len: usize = degrees[..k].iter().map(|d| d + 1).product();
        let coeffs = (0..len)
            .map(|flat| {
                let idx = template.multi_index(flat);
                let split = |p: &Self| -> usize {
                    (0..k).fold(0, |acc, a| {
                        acc * (p.degrees[a] + 1) + if p.degrees[a] == 0 { 0 } else { idx[a] }
                    })
                };
                self.coeffs[split(self)].mul(&other.coeffs[split(other)])
            })
            .collect();
        Bernstein { coeffs, ..template }
    }

    /// `self + other`, both elevated to their common degrees.
    ///
    /// # Errors
    /// [`BernsteinError::Mismatch`] if the variable counts differ.
    pub fn try_add(&self, other: &Self) -> Result<Self, BernsteinError> {
        self.zip_with(other, |x, y| x.add(y))
    }

    /// `self - other`, both elevated to their common degrees.
    ///
    /// # Errors
    /// [`BernsteinError::Mismatch`] if the variable counts differ.
    pub fn try_sub(&self, other: &Self) -> Result<Self, BernsteinError> {
        self.zip_with(other, |x, y| x.sub(y))
    }

    /// `-self`.
    pub fn neg(&self) -> Self {
        self.map(|c| c.neg())
    }

    /// `c · self`.
    pub fn scale(&self, c: &N) -> Self {
        self.map(|x| x.mul(c))
    }

    /// The product, of degrees `d_a + e_a`:
    /// `c_K = Σ_{I+J=K} Π_a C(d_a,I_a) C(e_a,J_a) / C(d_a+e_a,K_a) · a_I b_J`.
    ///
    /// The binomials are exact integers and their quotients exact rationals converted to `N`,
    /// so the product is exact for exact types and an enclosure for enclosure types.
    ///
    /// # Errors
    /// [`BernsteinError::Mismatch`] if the variable counts differ.
    pub fn try_mul(&self, other: &Self) -> Result<Self, BernsteinError> {
        if self.nvars != other.nvars {
            return Err(BernsteinError::Mismatch(self.nvars, other.nvars));
        }
        if (0..self.nvars).all(|a| self.degrees[a] == 0 || other.degrees[a] == 0) {
            return Ok(self.mul_disjoint(other));
        }
        // Exact rationals: one common denominator per operand, then integer convolution (no
        // gcd per term); the result is the same exact polynomial.
        let any_self: &dyn std::any::Any = self;
        if let Some(a) = any_self.downcast_ref::<Bernstein<Rational>>() {
            let any_other: &dyn std::any::Any = other;
            let b = any_other
                .downcast_ref::<Bernstein<Rational>>()
                .expect("same coefficient type");
            let product: Box<dyn std::any::Any> = Box::new(mul_rational(a, b));
            return Ok(*product.downcast::<Self>().expect("same coefficient type"));
        }
        self.mul_generic(other)
    }

    /// [`Bernstein::try_mul`] for any coefficient type (the variable counts are equal).
    pub(crate) fn mul_generic(&self, other: &Self) -> Result<Self, BernsteinError> {
        let k = self.nvars;
        let prec = self.coeffs[0].precision();
        let degrees: Vec<usize> = (0..k).map(|a| self.degrees[a] + other.degrees[a]).collect();
        // Scale each side by its binomials (exact integers).
        let scaled = |p: &Self| -> Vec<N> {
            p.coeffs
                .iter()
                .enumerate()
                .map(|(flat, c)| {
                    let w = binomial_weight(p.degrees(), &p.multi_index(flat));
                    c.mul(&N::from_rational(&Rational::from(w), prec))
                })
                .collect()
        };
        let (sa, sb) = (scaled(self), scaled(other));
        let mut out: Vec<Option<N>> = vec![None; degrees.iter().map(|d| d + 1).product()];
        let out_strides: Vec<usize> = (0..k)
            .map(|a| degrees[a + 1..].iter().map(|d| d + 1).product())
            .collect();
        for (fa, x) in sa.iter().enumerate() {
            let ia = self.multi_index(fa);
            for (fb, y) in sb.iter().enumerate() {
                let ib = other.multi_index(fb);
                let flat: usize = (0..k).map(|a| (ia[a] + ib[a]) * out_strides[a]).sum();
                let term = x.mul(y);
                match &mut out[flat] {
                    Some(acc) => acc.add_assign(&term),
                    slot @ None => *slot = Some(term),
                }
            }
        }
        let template = Bernstein {
            nvars: k,
            degrees: {
                let mut d = [0; super::MAX_VARS];
                d[..k].copy_from_slice(&degrees);
                d
            },
            coeffs: Vec::<N>::new(),
        };
        let coeffs = out
            .into_iter()
            .enumerate()
            .map(|(flat, c)| {
                let w = binomial_weight(&degrees, &template.multi_index(flat));
                let inv = N::from_rational(&Rational::from((Integer::from(1), w)), prec);
                c.expect("every output index is reached").mul(&inv)
            })
            .collect();
        Ok(Bernstein { coeffs, ..template })
    }
}

impl<N: Number> std::ops::Add for &Bernstein<N> {
    type Output = Bernstein<N>;
    /// # Panics
    /// If the variable counts differ (use [`Bernstein::try_add`] to get an error instead).
    fn add(self, rhs: Self) -> Bernstein<N> {
        self.try_add(rhs).expect("same number of variables")
    }
}

impl<N: Number> std::ops::Sub for &Bernstein<N> {
    type Output = Bernstein<N>;
    /// # Panics
    /// If the variable counts differ (use [`Bernstein::try_sub`] to get an error instead).
    fn sub(self, rhs: Self) -> Bernstein<N> {
        self.try_sub(rhs).expect("same number of variables")
    }
}

impl<N: Number> std::ops::Mul for &Bernstein<N> {
    type Output = Bernstein<N>;
    /// # Panics
    /// If the variable counts differ (use [`Bernstein::try_mul`] to get an error instead).
    fn mul(self, rhs: Self) -> Bernstein<N> {
        self.try_mul(rhs).expect("same number of variables")
    }
}

/// The exact product of two rational Bernstein polynomials with the same variable count:
/// each operand scaled by its binomials and by the lcm of its denominators to integers,
/// convolved in integers, and each output coefficient divided once by the common denominator
/// and its own binomial (the formula of [`Bernstein::try_mul`]).
fn mul_rational(a: &Bernstein<Rational>, b: &Bernstein<Rational>) -> Bernstein<Rational> {
    let k = a.nvars;
    let degrees: Vec<usize> = (0..k).map(|x| a.degrees[x] + b.degrees[x]).collect();
    let integral = |p: &Bernstein<Rational>| -> (Vec<Integer>, Integer) {
        let mut l = Integer::from(1);
        for c in &p.coeffs {
            l.lcm_mut(c.denom());
        }
        let v = p
            .coeffs
            .iter()
            .enumerate()
            .map(|(flat, c)| {
                let w = binomial_weight(p.degrees(), &p.multi_index(flat));
                (c.numer() * Integer::from(&l / c.denom())) * w
            })
            .collect();
        (v, l)
    };
    let ((sa, la), (sb, lb)) = (integral(a), integral(b));
    let out_strides: Vec<usize> = (0..k)
        .map(|x| degrees[x + 1..].iter().map(|d| d + 1).product())
        .collect();
    let mut out: Vec<Integer> = vec![Integer::new(); degrees.iter().map(|d| d + 1).product()];
    let flat_b: Vec<usize> = (0..sb.len())
        .map(|fb| {
            let ib = b.multi_index(fb);
            (0..k).map(|x| ib[x] * out_strides[x]).sum()
        })
        .collect();
    for (fa, x) in sa.iter().enumerate() {
        if x.is_zero() {
            continue;
        }
        let ia = a.multi_index(fa);
        let base: usize = (0..k).map(|j| ia[j] * out_strides[j]).sum();
        for (y, off) in sb.iter().zip(&flat_b) {
            out[base + off] += x * y;
        }
    }
    let denom = Integer::from(&la * &lb);
    let mut d = [0; super::MAX_VARS];
    d[..k].copy_from_slice(&degrees);
    let template = Bernstein {
        nvars: k,
        degrees: d,
        coeffs: Vec::<Rational>::new(),
    };
    let coeffs = out
        .into_iter()
        .enumerate()
        .map(|(flat, c)| {
            let w = binomial_weight(&degrees, &template.multi_index(flat));
            Rational::from((c, Integer::from(&denom * &w)))
        })
        .collect();
    Bernstein { coeffs, ..template }
}

#[cfg(test)]
mod mul_tests {
    use super::*;

    /// The rational fast path equals the generic formula, on polynomials with mixed
    /// denominators and zeros, in one and two variables.
    #[test]
    fn rational_product_matches_the_generic_formula() {
        let q = |n: i64, d: i64| Rational::from((n, d));
        let a = Bernstein::new(
            &[2, 1],
            vec![q(1, 3), q(-2, 5), q(0, 1), q(7, 4), q(-1, 6), q(3, 10)],
        )
        .unwrap();
        let b = Bernstein::new(
            &[1, 2],
            vec![q(5, 7), q(-3, 2), q(1, 9), q(2, 1), q(0, 1), q(-11, 12)],
        )
        .unwrap();
        assert_eq!(a.try_mul(&b).unwrap(), a.mul_generic(&b).unwrap());
        let c = Bernstein::new(&[3], vec![q(1, 2), q(-1, 3), q(1, 4), q(-1, 5)]).unwrap();
        let e = Bernstein::new(&[0], vec![q(-7, 3)]).unwrap();
        assert_eq!(c.try_mul(&e).unwrap(), c.mul_generic(&e).unwrap());
        assert_eq!(c.try_mul(&c).unwrap(), c.mul_generic(&c).unwrap());
    }
}
