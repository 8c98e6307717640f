//! The checker's own exact arithmetic: dyadic rationals `n / 2^e` and Bernstein polynomials
//! with integer coefficients, known up to a positive factor (enough for signs and zeros).
//!
//! Every position in a certificate is dyadic, so the checker never needs a general rational:
//! evaluation and restriction at dyadic points are de Casteljau steps
//! `x_i ← (2^e − t) x_i + t x_{i+1}`, which scale every coefficient by the same `2^e` and
//! keep integers integers. No gcd, no division.

use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};
use std::cmp::Ordering;

/// The exact dyadic rational `n / 2^e`, reduced (n odd or e = 0).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Dy {
    n: BigInt,
    e: u32,
}

/// The largest exponent accepted (a certificate coordinate is at most 2^-4096 fine).
const MAX_EXP: u32 = 4096;

impl Dy {
    /// `n / 2^e`, reduced.
    pub fn new(n: BigInt, e: u32) -> Dy {
        match n.trailing_zeros() {
            None => Dy {
                n: BigInt::zero(),
                e: 0,
            },
            Some(z) => {
                let k = z.min(u64::from(e)) as u32;
                Dy {
                    n: n >> k as usize,
                    e: e - k,
                }
            }
        }
    }

    /// An integer.
    pub fn int(n: i64) -> Dy {
        Dy::new(BigInt::from(n), 0)
    }

    /// Parses "p" or "p/q" with q a power of two.
    pub fn parse(s: &str) -> Option<Dy> {
        let (n, d) = s.split_once('/').unwrap_or((s, "1"));
        let n: BigInt = n.trim().parse().ok()?;
        let d: BigInt = d.trim().parse().ok()?;
        if !d.is_positive() {
            return None;
        }
        let e = d.bits().checked_sub(1)?;
        if d != BigInt::one() << e || e > u64::from(MAX_EXP) {
            return None;
        }
        Some(Dy::new(n, e as u32))
    }

    /// The numerator over `2^e` for `e >= self.e`.
    pub fn num_at(&self, e: u32) -> BigInt {
        &self.n << (e - self.e) as usize
    }

    /// The exponent of the denominator.
    pub fn exp(&self) -> u32 {
        self.e
    }

    /// The midpoint.
    pub fn mid(&self, other: &Dy) -> Dy {
        let e = self.e.max(other.e);
        Dy::new(self.num_at(e) + other.num_at(e), e + 1)
    }

    /// `self − other`.
    pub fn sub(&self, other: &Dy) -> Dy {
        let e = self.e.max(other.e);
        Dy::new(self.num_at(e) - other.num_at(e), e)
    }

    /// 0 or 1.
    pub fn is_end(&self) -> bool {
        self.e == 0 && (self.n.is_zero() || self.n.is_one())
    }

    /// In [0, 1].
    pub fn in_unit(&self) -> bool {
        !self.n.is_negative() && self.n <= (BigInt::one() << self.e as usize)
    }

    /// The sign.
    pub fn sign(&self) -> i8 {
        sign(&self.n)
    }
}

impl Ord for Dy {
    fn cmp(&self, other: &Self) -> Ordering {
        let e = self.e.max(other.e);
        self.num_at(e).cmp(&other.num_at(e))
    }
}

impl PartialOrd for Dy {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl std::fmt::Display for Dy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.e == 0 {
            write!(f, "{}", self.n)
        } else {
            write!(f, "{}/2^{}", self.n, self.e)
        }
    }
}

/// The sign of an integer.
pub fn sign(x: &BigInt) -> i8 {
    match x.sign() {
        num_bigint::Sign::Minus => -1,
        num_bigint::Sign::NoSign => 0,
        num_bigint::Sign::Plus => 1,
    }
}

/// One scaled de Casteljau pass at t = T / 2^e on the first `len` entries:
/// `x_i ← (2^e − T) x_i + T x_{i+1}`.
fn step(x: &mut [BigInt], len: usize, t: &BigInt, one_minus_t: &BigInt) {
    for i in 0..len - 1 {
        x[i] = one_minus_t * &x[i] + t * &x[i + 1];
    }
}

/// Scaled coefficients of a univariate fibre at dyadic t: its value times `2^(e·d)`.
pub fn eval1(x: &[BigInt], t: &Dy) -> BigInt {
    let (tt, omt) = (t.n.clone(), (BigInt::one() << t.e as usize) - &t.n);
    let mut w = x.to_vec();
    for len in (2..=w.len()).rev() {
        step(&mut w, len, &tt, &omt);
    }
    w.swap_remove(0)
}

/// The fibre restricted to [a, b] and reparameterised to [0, 1] (blossom: coefficient i is
/// d − i steps at a then i steps at b), every coefficient scaled by the same `2^(e·d)`.
pub fn restrict1(x: &[BigInt], a: &Dy, b: &Dy) -> Vec<BigInt> {
    let d = x.len() - 1;
    let e = a.e.max(b.e);
    let one = BigInt::one() << e as usize;
    let (ta, tb) = (a.num_at(e), b.num_at(e));
    let (oa, ob) = (&one - &ta, &one - &tb);
    // after_a[k]: the rows after k steps at a.
    let mut tri = x.to_vec();
    let mut after_a = vec![tri.clone()];
    for k in 1..=d {
        step(&mut tri, d - k + 2, &ta, &oa);
        after_a.push(tri[..d - k + 1].to_vec());
    }
    (0..=d)
        .map(|i| {
            let mut rows = after_a[d - i].clone();
            for k in 0..i {
                step(&mut rows, i - k + 1, &tb, &ob);
            }
            rows.swap_remove(0)
        })
        .collect()
}

/// A Bernstein polynomial in 1 or 2 variables with integer coefficients, known up to a
/// positive factor. Row-major: index `i·(n+1) + j` for u-index i, v-index j.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IPoly {
    /// Degrees (one per variable).
    pub deg: Vec<usize>,
    /// Coefficients.
    pub c: Vec<BigInt>,
}

impl IPoly {
    fn stride(&self, axis: usize) -> usize {
        if axis + 1 == self.deg.len() {
            1
        } else {
            self.deg[axis + 1] + 1
        }
    }

    /// Applies a fibre map along `axis` (the fibre's new length may differ).
    fn along(&self, axis: usize, f: impl Fn(&[BigInt]) -> Vec<BigInt>) -> IPoly {
        if self.deg.len() == 1 {
            let c = f(&self.c);
            return IPoly {
                deg: vec![c.len() - 1],
                c,
            };
        }
        let (n0, n1) = (self.deg[0] + 1, self.deg[1] + 1);
        let s = self.stride(axis);
        let fibres: Vec<Vec<BigInt>> = if axis == 1 {
            self.c.chunks(n1).map(&f).collect()
        } else {
            (0..n1)
                .map(|j| {
                    f(&(0..n0)
                        .map(|i| self.c[i * s + j].clone())
                        .collect::<Vec<_>>())
                })
                .collect()
        };
        let len = fibres[0].len();
        let mut deg = self.deg.clone();
        deg[axis] = len - 1;
        let c = if axis == 1 {
            fibres.concat()
        } else {
            (0..len)
                .flat_map(|i| fibres.iter().map(move |fb| fb[i].clone()))
                .collect()
        };
        IPoly { deg, c }
    }

    /// Restricted to [a, b] along `axis`.
    pub fn restrict(&self, axis: usize, a: &Dy, b: &Dy) -> IPoly {
        self.along(axis, |x| restrict1(x, a, b))
    }

    /// The univariate polynomial on the line where variable `axis` equals t.
    pub fn fix(&self, axis: usize, t: &Dy) -> IPoly {
        let p = self.along(axis, |x| vec![eval1(x, t)]);
        IPoly {
            deg: vec![p.deg[1 - axis]],
            c: p.c,
        }
    }

    /// A positive multiple of the derivative along `axis`.
    pub fn deriv(&self, axis: usize) -> IPoly {
        self.along(axis, |x| {
            if x.len() == 1 {
                vec![BigInt::zero()]
            } else {
                x.windows(2).map(|w| &w[1] - &w[0]).collect()
            }
        })
    }

    /// The sign of a univariate polynomial at t.
    pub fn sign_at(&self, t: &Dy) -> i8 {
        sign(&eval1(&self.c, t))
    }

    /// Whether every coefficient is zero.
    pub fn is_zero(&self) -> bool {
        self.c.iter().all(Zero::is_zero)
    }
}
