//! The tensor-product Bernstein polynomial type and its layout.

use crate::number::{Number, Precision, Rational};

/// The most variables a [`Bernstein`] polynomial may have (the flecnodal and bitangent
/// systems have four unknowns; an intersection curve's crossing with a silhouette arc six).
pub const MAX_VARS: usize = 6;

/// A polynomial that could not be built.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BernsteinError {
    /// Zero or more than [`MAX_VARS`] variables.
    #[error("a Bernstein polynomial has 1 to {MAX_VARS} variables, not {0}")]
    VariableCount(usize),
    /// The coefficient count is not Π (d_a + 1).
    #[error("degrees {degrees:?} need {expected} coefficients, got {got}")]
    CoefficientCount {
        /// The degrees asked for.
        degrees: Vec<usize>,
        /// Π (d_a + 1).
        expected: usize,
        /// The number given.
        got: usize,
    },
    /// Two polynomials with different numbers of variables were combined.
    #[error("variable counts differ: {0} and {1}")]
    Mismatch(usize, usize),
}

/// A tensor-product Bernstein polynomial on the unit box `[0,1]^k`, `1 <= k <= 4`.
///
/// # Examples
/// ```
/// use limn::bernstein::Bernstein;
/// use limn::number::{Interval, Number, Precision, Rational};
///
/// // p(u, v) = u - v on [0,1]^2, degree (1,1): coefficients c_00, c_01, c_10, c_11.
/// let q = |n: i64| Rational::from(n);
/// let p = Bernstein::new(&[1, 1], vec![q(0), q(-1), q(1), q(0)]).unwrap();
/// let half = Rational::from((1, 2));
/// assert_eq!(p.eval(&[half.clone(), half]), q(0));
/// // The same polynomial in f64 intervals encloses it on every sub-box.
/// let pi: Bernstein<Interval> = p.convert(Precision::F64);
/// let (left, _right) = pi.subdivide_half(0);
/// assert!(left.range_f64().1 <= 0.5);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Bernstein<N> {
    pub(super) nvars: usize,
    pub(super) degrees: [usize; MAX_VARS],
    pub(super) coeffs: Vec<N>,
}

impl<N: Number> Bernstein<N> {
    /// A polynomial from its degrees and its coefficients in row-major order.
    ///
    /// # Errors
    /// [`BernsteinError`] if there are not 1 to 6 degrees or the count is not Π (d_a + 1).
    pub fn new(degrees: &[usize], coeffs: Vec<N>) -> Result<Self, BernsteinError> {
        if degrees.is_empty() || degrees.len() > MAX_VARS {
            return Err(BernsteinError::VariableCount(degrees.len()));
        }
        let expected = degrees
            .iter()
            .try_fold(1usize, |acc, &d| acc.checked_mul(d.checked_add(1)?));
        if expected != Some(coeffs.len()) {
            return Err(BernsteinError::CoefficientCount {
                degrees: degrees.to_vec(),
                expected: expected.unwrap_or(usize::MAX),
                got: coeffs.len(),
            });
        }
        let mut d = [0; MAX_VARS];
        d[..degrees.len()].copy_from_slice(degrees);
        Ok(Bernstein {
            nvars: degrees.len(),
            degrees: d,
            coeffs,
        })
    }

    /// The constant polynomial `c` in `nvars` variables (all degrees 0).
    ///
    /// # Panics
    /// If `nvars` is not in `1..=4`.
    pub fn constant(nvars: usize, c: N) -> Self {
        assert!((1..=MAX_VARS).contains(&nvars), "1 to 6 variables");
        Bernstein {
            nvars,
            degrees: [0; MAX_VARS],
            coeffs: vec![c],
        }
    }

    /// The number of variables.
    pub fn nvars(&self) -> usize {
        self.nvars
    }

    /// The degree in each variable.
    pub fn degrees(&self) -> &[usize] {
        &self.degrees[..self.nvars]
    }

    /// The coefficients, row-major (last variable fastest).
    pub fn coeffs(&self) -> &[N] {
        &self.coeffs
    }

    /// The coefficients, mutable.
    pub fn coeffs_mut(&mut self) -> &mut [N] {
        &mut self.coeffs
    }

    /// The coefficient at a multi-index.
    ///
    /// # Panics
    /// If the index has the wrong length or is out of range.
    pub fn coeff(&self, index: &[usize]) -> &N {
        assert_eq!(index.len(), self.nvars);
        let mut flat = 0;
        for (a, &i) in index.iter().enumerate() {
            assert!(i <= self.degrees[a], "index out of range");
            flat += i * self.stride(a);
        }
        &self.coeffs[flat]
    }

    /// The distance in the coefficient vector between neighbours along `axis`.
    pub fn stride(&self, axis: usize) -> usize {
        self.degrees[axis + 1..self.nvars]
            .iter()
            .map(|d| d + 1)
            .product()
    }

    /// The polynomial with every coefficient mapped by `f` (same degrees).
    pub fn map<M, F: FnMut(&N) -> M>(&self, f: F) -> Bernstein<M> {
        Bernstein {
            nvars: self.nvars,
            degrees: self.degrees,
            coeffs: self.coeffs.iter().map(f).collect(),
        }
    }

    /// The multi-index of a flat position.
    pub fn multi_index(&self, mut flat: usize) -> [usize; MAX_VARS] {
        let mut idx = [0; MAX_VARS];
        for a in (0..self.nvars).rev() {
            let n = self.degrees[a] + 1;
            idx[a] = flat % n;
            flat /= n;
        }
        idx
    }

    pub(super) fn with_degree(&self, axis: usize, degree: usize, coeffs: Vec<N>) -> Self {
        let mut d = self.degrees;
        d[axis] = degree;
        debug_assert_eq!(
            coeffs.len(),
            d[..self.nvars].iter().map(|x| x + 1).product::<usize>()
        );
        Bernstein {
            nvars: self.nvars,
            degrees: d,
            coeffs,
        }
    }
}

impl Bernstein<Rational> {
    /// This exact polynomial in another number type at a precision: each coefficient is
    /// converted from the exact value (enclosed, for enclosure types). This is how every
    /// precision level is derived from the exact input.
    pub fn convert<M: Number>(&self, prec: Precision) -> Bernstein<M> {
        self.map(|q| M::from_rational(q, prec))
    }
}

/// The polynomial with variable `axis` fixed at `at`: one variable fewer (the others keep their
/// order). Exact.
///
/// # Panics
/// If `axis` is not a variable of `p`, or `p` has only one variable.
///
/// # Examples
/// ```
/// use limn::bernstein::{fix_var, Bernstein};
/// use limn::number::Rational;
/// let q = |n: i64| Rational::from(n);
/// // p(x, y) = x y (Bernstein coefficients 0, 0, 0, 1): at y = 1/2, x / 2.
/// let p = Bernstein::new(&[1, 1], vec![q(0), q(0), q(0), q(1)]).unwrap();
/// let f = fix_var(&p, 1, &Rational::from((1, 2)));
/// assert_eq!(f.eval(&[q(1)]), Rational::from((1, 2)));
/// ```
pub fn fix_var(p: &Bernstein<Rational>, axis: usize, at: &Rational) -> Bernstein<Rational> {
    let n = p.nvars();
    assert!(
        axis < n && n >= 2,
        "a variable of a polynomial in two or more"
    );
    let r = p.restrict_rational(axis, at, at);
    // On the point interval every coefficient along `axis` is the value there: keep index 0.
    let coeffs: Vec<Rational> = (0..r.coeffs().len())
        .filter(|&f| r.multi_index(f)[axis] == 0)
        .map(|f| r.coeffs()[f].clone())
        .collect();
    let degrees: Vec<usize> = (0..n)
        .filter(|&k| k != axis)
        .map(|k| r.degrees()[k])
        .collect();
    Bernstein::new(&degrees, coeffs).expect("one variable fewer")
}

/// A polynomial in `k` variables as one in `total` variables, its variables placed from
/// `offset` on (degree 0 in the others; the coefficients are unchanged, since a Bernstein
/// basis of degree 0 is the constant 1).
///
/// # Panics
/// If the variables do not fit: `offset + p.nvars() > total` or `total > MAX_VARS`.
pub fn lift<N: Number>(p: &Bernstein<N>, total: usize, offset: usize) -> Bernstein<N> {
    let mut degrees = vec![0; total];
    degrees[offset..offset + p.nvars()].copy_from_slice(p.degrees());
    Bernstein::new(&degrees, p.coeffs().to_vec()).expect("lifting keeps the coefficient count")
}
