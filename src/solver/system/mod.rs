//! Certified isolation of the roots of square polynomial systems on a box: subdivision with
//! exclusion, and Krawczyk's uniqueness test (`proofs/krawczyk.md`).
//!
//! For `f: R^n → R^n` with Bernstein coefficients on a box `X`, the Krawczyk operator
//! `K(X) = y − C f(y) + (I − C J(X)) (X − y)` (y the centre, J(X) an interval enclosure of the
//! Jacobian over X, C any real matrix, here an approximate inverse of the Jacobian's midpoint)
//! satisfies: if `K(X)` lies in the interior of X, then f has exactly one zero in X, and it lies
//! in `K(X)`. The test is run on each box grown by an eighth of its width on every side, so a
//! root on a box face is still proven from one of its neighbours; a root found twice is
//! recognised because each one's enclosure lies inside the other's uniqueness region.
//!
//! Extra polynomials (`filters`) only exclude boxes: for an overdetermined system such as the
//! singular points of a curve (`g = ∂g/∂u = ∂g/∂v = 0`), the square part is
//! `(∂g/∂u, ∂g/∂v)` and `g` filters; whether `g` vanishes at an isolated root is for the
//! caller to decide. Written for any number of variables (up to the Bernstein limit), so
//! later systems (bitangents, flecnodal points) use the same code.
//!
//! The subdivision loop is written once, over the trait `SquareSystem` (what a system does on
//! a box: its restriction, exclusion, Jacobian and centre enclosures, splitting): the dense
//! systems of [`solve_system`] implement it, and so do the systems of two groups of variables
//! of [`separable`], whose equations are restricted group by group.

pub mod separable;

use crate::bernstein::Bernstein;
use crate::number::{Interval, Number, Precision, Rational};
use crate::solver::dyadic::Dyadic;
use crate::solver::precision::{Escalations, Ladder, Level};
use std::cell::OnceCell;

/// Budgets of the system solver.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct SystemOptions {
    /// The deepest subdivision (box sides 2^-depth of the domain's).
    pub max_depth: u32,
    /// The most boxes examined.
    pub max_boxes: usize,
    /// Isolated roots are refined toward enclosures of this width (Newton then Krawczyk's
    /// test, else Krawczyk iteration and bisection); where refinement stalls the enclosure
    /// stays wider, still proven.
    pub refine_width: f64,
    /// The precision in which the exact polynomials are restricted to the small boxes of the
    /// refinement: its tightest level ([`Ladder::tightest`]).
    pub ladder: Ladder,
}

impl Default for SystemOptions {
    fn default() -> Self {
        SystemOptions {
            max_depth: 30,
            max_boxes: 20_000,
            refine_width: 1e-12,
            ladder: Ladder::default(),
        }
    }
}

/// An axis-aligned box with exact dyadic corners: `(lo, hi)` per variable.
pub type DyadicBoxN = Vec<(Dyadic, Dyadic)>;

/// A root proven unique by Krawczyk's test.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct IsolatedRoot {
    /// The region where it is the only root of the square system (the tested box).
    pub unique_in: Vec<[f64; 2]>,
    /// A box that contains it (the last Krawczyk image), `[lo, hi]` per variable.
    pub enclosure: Vec<[f64; 2]>,
    /// The enclosure lies inside the domain (false: it straddles the domain's boundary, and
    /// the root may lie just outside).
    pub inside: bool,
}

/// What the system solver found.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct SystemRoots {
    /// The isolated roots (each once).
    pub roots: Vec<IsolatedRoot>,
    /// Boxes where neither exclusion nor the uniqueness test succeeded within the budget
    /// (a multiple root, a root of the square system on a filter's zero set that is not
    /// isolated, or clustered roots).
    pub unresolved: Vec<Vec<[f64; 2]>>,
    /// Boxes examined.
    pub boxes: usize,
    /// The level that settled each test on a small box decided from the exact polynomials.
    pub escalations: Escalations,
}

/// Whether every coefficient has one strict sign.
fn excludes(p: &Bernstein<Interval>) -> bool {
    let c = p.coeffs();
    c.iter().all(|x| x.lo() > 0.0) || c.iter().all(|x| x.hi() < 0.0)
}

/// The hull of a polynomial's coefficients: an enclosure of its range on the box.
/// The inverse of a small dense matrix (Gauss-Jordan with partial pivoting), or `None` if it
/// is numerically singular. Any matrix serves as C in Krawczyk's operator: this only affects
/// whether the test succeeds, never its soundness.
pub(crate) fn inverse(m: &[Vec<f64>]) -> Option<Vec<Vec<f64>>> {
    let n = m.len();
    let mut a: Vec<Vec<f64>> = m
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let mut r = row.clone();
            r.extend((0..n).map(|j| if i == j { 1.0 } else { 0.0 }));
            r
        })
        .collect();
    for col in 0..n {
        let piv = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        // Columns may differ in scale by many orders (boxes of very different widths), so no
        // relative threshold: only an exact zero pivot fails (and non-finite results below).
        if a[piv][col] == 0.0 || !a[piv][col].is_finite() {
            return None;
        }
        a.swap(col, piv);
        let p = a[col][col];
        for x in a[col].iter_mut() {
            *x /= p;
        }
        for r in 0..n {
            if r != col {
                let f = a[r][col];
                if f != 0.0 {
                    let pivot_row = a[col].clone();
                    for (x, v) in a[r].iter_mut().zip(&pivot_row) {
                        *x -= f * v;
                    }
                }
            }
        }
    }
    let inv: Vec<Vec<f64>> = a.into_iter().map(|r| r[n..].to_vec()).collect();
    inv.iter().flatten().all(|x| x.is_finite()).then_some(inv)
}

/// Krawczyk's operator on the unit box of the polynomials' own coordinates: `Some(K)` (in
/// those coordinates) if `K ⊂ (0, 1)^n` strictly, which proves exactly one zero in the box,
/// inside K.
pub fn krawczyk(square: &[Bernstein<Interval>]) -> Option<Vec<Interval>> {
    krawczyk_unit(&dense_jacobian(square), || dense_centre(square))
}

/// [`krawczyk`] from an enclosure of the Jacobian over the unit box and (computed only if the
/// Jacobian's midpoint is regular) enclosures of the values at its centre.
fn krawczyk_unit(
    jac: &[Vec<Interval>],
    centre: impl FnOnce() -> Vec<Interval>,
) -> Option<Vec<Interval>> {
    let (c, m) = precondition(jac)?;
    let k = krawczyk_image(&c, &m, &centre());
    k.iter().all(|x| x.lo() > 0.0 && x.hi() < 1.0).then_some(k)
}

/// The image `K = y − C f(y) + (I − C J)([0,1]^n − y)` of Krawczyk's operator on the unit box,
/// at its centre `y`, from `f(y)`.
fn krawczyk_image(c: &Matrix, m: &[Vec<Interval>], fy: &[Interval]) -> Vec<Interval> {
    let n = fy.len();
    let y = vec![Interval::point(0.5); n];
    krawczyk_operator(c, m, &y, fy, &vec![Interval::new(-0.5, 0.5); n])
}

/// The values of polynomials at the centre of their unit box (enclosures).
fn dense_centre(square: &[Bernstein<Interval>]) -> Vec<Interval> {
    square.iter().map(Bernstein::value_at_centre).collect()
}

/// An enclosure of the Jacobian of polynomials over their unit box: `∂f_i/∂x_j` by the hull of
/// the coefficient differences.
fn dense_jacobian(square: &[Bernstein<Interval>]) -> Vec<Vec<Interval>> {
    let n = square.len();
    square
        .iter()
        .map(|f| (0..n).map(|j| f.deriv_hull(j)).collect())
        .collect()
}

/// `K = y − C f(y) + M dx`, with `M = I − C J` and `dx ∋ x − y` for every x of the box.
fn krawczyk_operator(
    c: &Matrix,
    m: &[Vec<Interval>],
    y: &[Interval],
    fy: &[Interval],
    dx: &[Interval],
) -> Vec<Interval> {
    c.iter()
        .zip(m)
        .zip(y)
        .map(|((ci, mi), yi)| {
            let mut acc = *yi;
            for (cij, fyj) in ci.iter().zip(fy) {
                acc = acc.sub(&Interval::point(*cij).mul(fyj));
            }
            for (mij, dxj) in mi.iter().zip(dx) {
                acc = acc.add(&mij.mul(dxj));
            }
            acc
        })
        .collect()
}

/// What Krawczyk's operator proves on the unit box of the polynomials' own coordinates
/// (`proofs/krawczyk.md`).
pub(crate) enum KrawczykVerdict {
    /// Exactly one zero, inside `K`.
    Unique(Vec<Interval>),
    /// `K` misses the box: no zero in it.
    NoZero,
    /// Neither; `worth`: every row of `|I − C J|` sums to less than 1 (a cheap necessary
    /// condition for the test to succeed on a slightly larger box).
    Unknown { worth: bool },
}

/// Krawczyk's operator on the box, once: a unique zero, none, or nothing proven.
pub(crate) fn krawczyk_verdict(square: &[Bernstein<Interval>]) -> KrawczykVerdict {
    verdict_of(&dense_jacobian(square), || dense_centre(square))
}

/// [`krawczyk_verdict`] from an enclosure of the Jacobian over the unit box and (computed only
/// if the Jacobian's midpoint is regular) enclosures of the values at its centre.
fn verdict_of(jac: &[Vec<Interval>], centre: impl FnOnce() -> Vec<Interval>) -> KrawczykVerdict {
    let Some((c, m)) = precondition(jac) else {
        return KrawczykVerdict::Unknown { worth: false };
    };
    let k = krawczyk_image(&c, &m, &centre());
    if k.iter().any(|x| x.hi() < 0.0 || x.lo() > 1.0) {
        return KrawczykVerdict::NoZero;
    }
    let worth = rows_contract(&m);
    if worth && k.iter().all(|x| x.lo() > 0.0 && x.hi() < 1.0) {
        return KrawczykVerdict::Unique(k);
    }
    KrawczykVerdict::Unknown { worth }
}

/// Every row of `|I − C J|` sums to less than 1.
fn rows_contract(m: &[Vec<Interval>]) -> bool {
    m.iter().all(|row| {
        row.iter()
            .map(|x| x.lo().abs().max(x.hi().abs()))
            .sum::<f64>()
            < 1.0
    })
}

/// A dense f64 matrix, by rows.
type Matrix = Vec<Vec<f64>>;

/// `C`, the inverse of the midpoint of an interval Jacobian `J`, and `I − C J`; `None` if the
/// midpoint is singular.
fn precondition(jac: &[Vec<Interval>]) -> Option<(Matrix, Vec<Vec<Interval>>)> {
    let n = jac.len();
    let mid: Vec<Vec<f64>> = jac
        .iter()
        .map(|r| r.iter().map(|x| 0.5 * (x.lo() + x.hi())).collect())
        .collect();
    let c = inverse(&mid)?;
    let m = c
        .iter()
        .enumerate()
        .map(|(i, ci)| {
            (0..n)
                .map(|j| {
                    let mut m = Interval::point(if i == j { 1.0 } else { 0.0 });
                    for (cil, jl) in ci.iter().zip(jac) {
                        m = m.sub(&Interval::point(*cil).mul(&jl[j]));
                    }
                    m
                })
                .collect()
        })
        .collect();
    Some((c, m))
}

/// Krawczyk's test on the box `[a, c]` of the polynomials' own coordinates, without restricting
/// them to it: `f` at the box's centre `y` and the Jacobian over the box by evaluating the
/// partial derivatives (`derivs[i][j] = ∂f_i/∂x_j`) at the box's intervals, which encloses
/// their range there (`proofs/de-casteljau-enclosure.md`). `K = y − C f(y) + (I − C J)(B − y)`
/// strictly inside the box proves exactly one zero in the box, and it lies in `K`
/// (`proofs/krawczyk.md`; the box is any box, the unit box being one case). Cheaper than
/// restricting degree-d polynomials to the box when the box is small.
pub(crate) fn krawczyk_in_box(
    polys: &[Bernstein<Interval>],
    derivs: &[Vec<Bernstein<Interval>>],
    a: &[f64],
    c: &[f64],
) -> Option<Vec<Interval>> {
    let n = polys.len();
    let b: Vec<Interval> = (0..n).map(|k| Interval::new(a[k], c[k])).collect();
    let y: Vec<Interval> = (0..n)
        .map(|k| Interval::point(0.5 * a[k] + 0.5 * c[k]))
        .collect();
    let jac: Vec<Vec<Interval>> = derivs
        .iter()
        .map(|row| row.iter().map(|d| d.eval(&b)).collect())
        .collect();
    let (cm, m) = precondition(&jac)?;
    let fy: Vec<Interval> = polys.iter().map(|f| f.eval(&y)).collect();
    let dx: Vec<Interval> = (0..n).map(|k| b[k].sub(&y[k])).collect();
    let k = krawczyk_operator(&cm, &m, &y, &fy, &dx);
    (0..n)
        .all(|i| a[i] < k[i].lo() && k[i].hi() < c[i])
        .then_some(k)
}

/// A square system as the subdivision solver sees it: its restriction to a box (`Local`, in
/// the box's own unit coordinates), how a restriction splits, and the enclosures that
/// exclusion and Krawczyk's test need. [`solve_system_excluding`] solves dense Bernstein
/// systems through it ([`Dense`]); [`separable`] systems whose equations separate into two
/// groups of variables are the other kind.
pub(crate) trait SquareSystem {
    /// The system restricted to a box.
    type Local;
    /// The system on `[lo, hi]` (global coordinates, exact dyadics in f64), in f64
    /// intervals from the input converted once.
    fn on_box(&self, lo: &[f64], hi: &[f64]) -> Self::Local;
    /// The system on `[lo, hi]` from the exact input at the ladder's tightest level
    /// ([`Ladder::restricted_enclosures`]), and the level used.
    fn on_box_tight(
        &self,
        ladder: &Ladder,
        lo: &[Rational],
        hi: &[Rational],
    ) -> (Self::Local, Level);
    /// The restrictions to the `2^k` boxes of a split at the midpoints of `axes` (increasing),
    /// in the order of [`split_cell`]: the first axis's halves outermost.
    fn split(&self, local: Self::Local, axes: &[usize]) -> Vec<Self::Local>;
    /// Whether some equation (or filter) is proven to have no zero on the box.
    fn excludes(&self, local: &Self::Local) -> bool;
    /// An enclosure of the Jacobian over the unit box, in the box's coordinates.
    fn jacobian(&self, local: &Self::Local) -> Vec<Vec<Interval>>;
    /// Enclosures of the equations' values at the centre of the unit box.
    fn centre(&self, local: &Self::Local) -> Vec<Interval>;
    /// The equations' values and Jacobian at a point (global coordinates) in f64: estimates
    /// for Newton's method, proven by nothing.
    fn eval_f64(&self, x: &[f64]) -> (Vec<f64>, Vec<Vec<f64>>);
}

/// Krawczyk's test on a restricted system: the root's enclosure in the box's coordinates.
fn krawczyk_local<S: SquareSystem>(sys: &S, local: &S::Local) -> Option<Vec<Interval>> {
    krawczyk_unit(&sys.jacobian(local), || sys.centre(local))
}

/// A square system in f64 and the partial derivatives of each polynomial.
type FloatSystem = (Vec<Bernstein<f64>>, Vec<Vec<Bernstein<f64>>>);

/// A dense square system: `n` Bernstein polynomials in `n` variables, and filters.
pub(crate) struct Dense<'a> {
    /// The square part, exact.
    square: &'a [Bernstein<Rational>],
    /// The square part then the filters, in f64 intervals.
    whole: Vec<Bernstein<Interval>>,
    /// The square part in f64 and its partial derivatives, for Newton's method.
    floats: OnceCell<FloatSystem>,
}

impl<'a> Dense<'a> {
    /// The system of `square` with the exclusion-only `filters`.
    pub(crate) fn new(square: &'a [Bernstein<Rational>], filters: &[Bernstein<Rational>]) -> Self {
        let whole = square
            .iter()
            .chain(filters)
            .map(|p| p.convert(Precision::F64))
            .collect();
        Dense {
            square,
            whole,
            floats: OnceCell::new(),
        }
    }
}

impl SquareSystem for Dense<'_> {
    type Local = Vec<Bernstein<Interval>>;

    fn on_box(&self, lo: &[f64], hi: &[f64]) -> Self::Local {
        self.whole
            .iter()
            .map(|p| p.restrict_box_f64(lo, hi))
            .collect()
    }

    fn on_box_tight(
        &self,
        ladder: &Ladder,
        lo: &[Rational],
        hi: &[Rational],
    ) -> (Self::Local, Level) {
        ladder.restricted_enclosures(self.square, lo, hi)
    }

    fn split(&self, local: Self::Local, axes: &[usize]) -> Vec<Self::Local> {
        split_polys(local, axes)
    }

    fn excludes(&self, local: &Self::Local) -> bool {
        local.iter().any(excludes)
    }

    fn jacobian(&self, local: &Self::Local) -> Vec<Vec<Interval>> {
        dense_jacobian(&local[..self.square.len()])
    }

    fn centre(&self, local: &Self::Local) -> Vec<Interval> {
        dense_centre(&local[..self.square.len()])
    }

    fn eval_f64(&self, x: &[f64]) -> (Vec<f64>, Vec<Vec<f64>>) {
        let (f, df) = self.floats.get_or_init(|| {
            let f: Vec<Bernstein<f64>> = self
                .square
                .iter()
                .map(|p| p.convert(Precision::F64))
                .collect();
            let df = derivatives(&f);
            (f, df)
        });
        values_and_jacobian(f, df, x)
    }
}

/// The partial derivatives of each polynomial: `df[i][j] = ∂f_i/∂x_j`.
fn derivatives(f: &[Bernstein<f64>]) -> Vec<Vec<Bernstein<f64>>> {
    f.iter()
        .map(|p| (0..p.nvars()).map(|j| p.deriv(j)).collect())
        .collect()
}

/// The values of `f` and of its Jacobian `df` at `x`, in f64.
fn values_and_jacobian(
    f: &[Bernstein<f64>],
    df: &[Vec<Bernstein<f64>>],
    x: &[f64],
) -> (Vec<f64>, Vec<Vec<f64>>) {
    let fx = f.iter().map(|p| p.eval(x)).collect();
    let j = df
        .iter()
        .map(|r| r.iter().map(|p| p.eval(x)).collect())
        .collect();
    (fx, j)
}

/// Polynomials subdivided at the midpoints of `axes`: `2^k` lists, the first axis's halves
/// outermost (the order of [`split_cell`]).
pub(crate) fn split_polys(
    polys: Vec<Bernstein<Interval>>,
    axes: &[usize],
) -> Vec<Vec<Bernstein<Interval>>> {
    let mut children = vec![polys];
    for &axis in axes {
        let mut next = Vec::with_capacity(children.len() * 2);
        for ps in children {
            let (pl, pr): (Vec<_>, Vec<_>) = ps.iter().map(|p| p.subdivide_half(axis)).unzip();
            next.push(pl);
            next.push(pr);
        }
        children = next;
    }
    children
}

/// The system on the small boxes of the refinement: first the f64 restriction of the input
/// converted once; where the test fails on it, the exact input restricted at the ladder's
/// tightest level ([`Ladder::restricted_enclosures`]), then enclosed in f64 intervals. With the default ladder that is exact rationals, also measured
/// faster than MPFR first: on `occ22470.igs`, whose 766 such tests MPFR at 106 bits settles
/// every one, the hidden-line drawing takes 9.1 s with MPFR first against 8.5 s exact (one
/// thread).
struct Tight<'a, S> {
    sys: &'a S,
    ladder: &'a Ladder,
    counts: &'a mut Escalations,
}

impl<S: SquareSystem> Tight<'_, S> {
    /// The system on `[lo, hi]` (f64 corners, exact dyadics), if `accept` takes it (counted
    /// at the level used).
    fn first<T>(
        &mut self,
        lo: &[f64],
        hi: &[f64],
        accept: impl Fn(&S::Local) -> Option<T>,
    ) -> Option<T> {
        if let Some(t) = self.first_f64(lo, hi, &accept) {
            return Some(t);
        }
        self.first_exact(lo, hi, accept)
    }

    /// The filter: the system on `[lo, hi]` restricted from the f64 input converted once
    /// (the enclosure the subdivision itself proves with), if `accept` takes it.
    fn first_f64<T>(
        &mut self,
        lo: &[f64],
        hi: &[f64],
        accept: impl Fn(&S::Local) -> Option<T>,
    ) -> Option<T> {
        let t = accept(&self.sys.on_box(lo, hi))?;
        self.counts.record(Some(Level::F64));
        Some(t)
    }

    /// The system on `[lo, hi]` restricted from the exact input at the ladder's tightest
    /// level, if `accept` takes it.
    fn first_exact<T>(
        &mut self,
        lo: &[f64],
        hi: &[f64],
        accept: impl Fn(&S::Local) -> Option<T>,
    ) -> Option<T> {
        let q = |x: &[f64]| -> Option<Vec<Rational>> {
            x.iter().map(|&v| Rational::from_f64(v)).collect()
        };
        let (lq, hq) = (q(lo)?, q(hi)?);
        let (local, level) = self.sys.on_box_tight(self.ladder, &lq, &hq);
        let t = accept(&local)?;
        self.counts.record(Some(level));
        Some(t)
    }

    /// Krawczyk's test on `[lo, hi]`: the root's enclosure in global coordinates.
    fn test_box(&mut self, lo: &[f64], hi: &[f64]) -> Option<Vec<[f64; 2]>> {
        let sys = self.sys;
        self.first(lo, hi, |local| {
            to_global(&krawczyk_local(sys, local)?, lo, hi)
        })
    }

    /// Krawczyk's test on `[lo, hi]` at one kind of restriction only: the f64 filter
    /// (`exact` false) or the exact input (`exact` true).
    fn test_box_at(&mut self, lo: &[f64], hi: &[f64], exact: bool) -> Option<Vec<[f64; 2]>> {
        let sys = self.sys;
        let test = |local: &S::Local| to_global(&krawczyk_local(sys, local)?, lo, hi);
        if exact {
            self.first_exact(lo, hi, test)
        } else {
            self.first_f64(lo, hi, test)
        }
    }

    /// Whether some equation is proven to have no zero on the box.
    fn excludes(&mut self, b: &[[f64; 2]]) -> bool {
        let (lo, hi): (Vec<f64>, Vec<f64>) = b.iter().map(|x| (x[0], x[1])).unzip();
        let sys = self.sys;
        self.first(&lo, &hi, |local| sys.excludes(local).then_some(()))
            .is_some()
    }
}

/// Local Krawczyk image to global coordinates, rounded outward.
fn to_global(k: &[Interval], lo: &[f64], hi: &[f64]) -> Option<Vec<[f64; 2]>> {
    Some(
        k.iter()
            .enumerate()
            .map(|(i, ki)| {
                let w = Interval::point(hi[i]).sub(&Interval::point(lo[i]));
                let l = Interval::point(lo[i]);
                [
                    l.add(&w.mul(&Interval::point(ki.lo()))).lo(),
                    l.add(&w.mul(&Interval::point(ki.hi()))).hi(),
                ]
            })
            .collect(),
    )
}

/// Narrows an isolated root's enclosure by Krawczyk iteration (each image is again a proven
/// enclosure of the same root: it lies in the previous box, where the root is unique).
fn refine<S: SquareSystem>(
    tight: &mut Tight<S>,
    unique_in: &[[f64; 2]],
    enc: Vec<[f64; 2]>,
    width: f64,
) -> Vec<[f64; 2]> {
    if enc.iter().all(|b| b[1] - b[0] <= width) {
        return enc;
    }
    if let Some(t) = newton_then_verify(tight, unique_in, &enc, width) {
        return t;
    }
    iterate(tight, enc, width)
}

/// Newton's method in f64 from the enclosure's centre, then Krawczyk's test on small boxes
/// around the result that lie inside `unique_in`: a success proves the root there, and it is
/// the same root (the only one in `unique_in`).
fn newton_then_verify<S: SquareSystem>(
    tight: &mut Tight<S>,
    unique_in: &[[f64; 2]],
    enc: &[[f64; 2]],
    width: f64,
) -> Option<Vec<[f64; 2]>> {
    let sys = tight.sys;
    let x = newton_by(
        |x| sys.eval_f64(x),
        enc.iter().map(|b| 0.5 * (b[0] + b[1])).collect(),
        40,
    )?;
    // The boxes from the smallest up, first all of them with the f64 filter, then with the
    // exact input: a box the filter proves need not be the smallest one the exact input
    // would, but every box is at most `width` wide.
    for exact in [false, true] {
        let mut r = 1e-15;
        while r <= width.max(1e-15) * 0.5 {
            let b: Vec<[f64; 2]> = x
                .iter()
                .map(|&v| [v - r * v.abs().max(1.0), v + r * v.abs().max(1.0)])
                .collect();
            if within(&b, unique_in) {
                let (lo, hi): (Vec<f64>, Vec<f64>) = b.iter().map(|x| (x[0], x[1])).unzip();
                if let Some(k) = tight.test_box_at(&lo, &hi, exact) {
                    return Some(k);
                }
            }
            r *= 8.0;
        }
    }
    None
}

/// Newton's method in f64 for a square system from `x`, at most `iterations` steps (until a
/// step is below the rounding of the point): an estimate, proven by nothing (callers verify
/// it with Krawczyk's test). `None` where the Jacobian is singular or the iterate diverges.
pub(crate) fn newton(f: &[Bernstein<f64>], x: Vec<f64>, iterations: usize) -> Option<Vec<f64>> {
    let df = derivatives(f);
    newton_by(|x| values_and_jacobian(f, &df, x), x, iterations)
}

/// Newton's method from `x` with the values and Jacobian that `eval` gives at a point: at
/// most `iterations` steps, until a step is below the rounding of the point.
fn newton_by(
    eval: impl Fn(&[f64]) -> (Vec<f64>, Vec<Vec<f64>>),
    mut x: Vec<f64>,
    iterations: usize,
) -> Option<Vec<f64>> {
    let n = x.len();
    for _ in 0..iterations {
        let (fx, j) = eval(&x);
        let inv = inverse(&j)?;
        let step: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|k| inv[i][k] * fx[k]).sum())
            .collect();
        for (xi, si) in x.iter_mut().zip(&step) {
            *xi -= si;
        }
        if !x.iter().all(|v| v.is_finite()) {
            return None;
        }
        if step
            .iter()
            .all(|s| s.abs() <= 1e-17 * 1f64.max(x.iter().fold(0.0, |a, v| a.max(v.abs()))))
        {
            break;
        }
    }
    Some(x)
}

/// Krawczyk iteration, with bisection where it stalls.
fn iterate<S: SquareSystem>(
    tight: &mut Tight<S>,
    mut enc: Vec<[f64; 2]>,
    width: f64,
) -> Vec<[f64; 2]> {
    for _ in 0..60 {
        if enc.iter().all(|b| b[1] - b[0] <= width) {
            break;
        }
        // ε-inflation: the box holds the root (it contains the enclosure), so a unique root in
        // it is that root; the margin keeps the test from failing on rounding alone once a
        // coordinate is already at machine precision.
        let (lo, hi): (Vec<f64>, Vec<f64>) = enc
            .iter()
            .map(|b| {
                let m = 0.05 * (b[1] - b[0]) + 1e-15 * b[0].abs().max(b[1].abs()).max(1e-3);
                (b[0] - m, b[1] + m)
            })
            .unzip();
        let widest = |b: &[[f64; 2]]| b.iter().map(|x| x[1] - x[0]).fold(0.0, f64::max);
        let next = tight.test_box(&lo, &hi).map(|next| {
            next.iter()
                .zip(&enc)
                .map(|(n, e)| [n[0].max(e[0]), n[1].min(e[1])])
                .collect::<Vec<_>>()
        });
        match next {
            Some(next) if widest(&next) < 0.9 * widest(&enc) => enc = next,
            // Krawczyk stalls while the box is large for the Jacobian's variation: bisect the
            // widest side; a half where some equation has a strict sign holds no root, so the
            // root is in the other one.
            other => {
                if let Some(next) = other {
                    enc = next;
                }
                let axis = (0..enc.len())
                    .max_by(|&i, &j| (enc[i][1] - enc[i][0]).total_cmp(&(enc[j][1] - enc[j][0])))
                    .expect("one variable at least");
                let mid = 0.5 * (enc[axis][0] + enc[axis][1]);
                let half = |k: usize| {
                    let mut b = enc.clone();
                    b[axis][k] = mid;
                    b
                };
                let (left, right) = (half(1), half(0));
                if tight.excludes(&left) {
                    enc = right;
                } else if tight.excludes(&right) {
                    enc = left;
                } else {
                    break;
                }
            }
        }
    }
    enc
}

/// Whether the box `inner` lies in the closed box `outer`.
pub(crate) fn within(inner: &[[f64; 2]], outer: &[[f64; 2]]) -> bool {
    inner
        .iter()
        .zip(outer)
        .all(|(a, b)| b[0] <= a[0] && a[1] <= b[1])
}

/// A root just found, against the roots already known.
pub(crate) enum Known {
    /// It is one of them.
    Same,
    /// Its enclosure meets one's without being proven the same zero.
    Undecided,
    /// A zero not among them.
    New,
}

/// Whether a root (its enclosure and the region where it is unique) is a known one: the
/// same zero if either lies in the other's region, another if its enclosure meets none of
/// theirs, undecided otherwise (`proofs/krawczyk.md`, each once).
pub(crate) fn against_known(
    roots: &[IsolatedRoot],
    enc: &[[f64; 2]],
    unique_in: &[[f64; 2]],
) -> Known {
    if roots
        .iter()
        .any(|r| within(enc, &r.unique_in) || within(&r.enclosure, unique_in))
    {
        Known::Same
    } else if roots.iter().any(|r| meets(enc, &r.enclosure)) {
        Known::Undecided
    } else {
        Known::New
    }
}

/// Whether two closed boxes share a point.
pub(crate) fn meets(a: &[[f64; 2]], b: &[[f64; 2]]) -> bool {
    a.iter().zip(b).all(|(x, y)| x[0] <= y[1] && y[0] <= x[1])
}

/// Whether two closed boxes share interior points.
pub(crate) fn overlaps(a: &[[f64; 2]], b: &[[f64; 2]]) -> bool {
    a.iter().zip(b).all(|(x, y)| x[0] < y[1] && y[0] < x[1])
}

/// A box without one coordinate (its projection on a face hyperplane).
pub(crate) fn without(b: &[[f64; 2]], axis: usize) -> Vec<[f64; 2]> {
    b.iter()
        .enumerate()
        .filter(|&(k, _)| k != axis)
        .map(|(_, e)| *e)
        .collect()
}

/// A dyadic box's corners in f64 (exact: dyadics of the solver's depths are f64 numbers).
pub(crate) fn f64_box(cell: &DyadicBoxN) -> Vec<[f64; 2]> {
    cell.iter().map(|d| [d.0.to_f64(), d.1.to_f64()]).collect()
}

/// Isolates the roots of the square system `square` (n polynomials in n variables) on the
/// box `domain` of their parameter space, discarding boxes where a polynomial of `square` or
/// of `filters` has a strict sign.
///
/// # Panics
/// If the polynomials do not all have `square.len()` variables, or `domain` has another
/// dimension.
///
/// # Examples
/// ```
/// use limn::bernstein::Bernstein;
/// use limn::number::Rational;
/// use limn::solver::system::{solve_system, SystemOptions};
/// use limn::solver::Dyadic;
/// // u − 1/3 and v − u²... as Bernstein: f = u − 1/3 (degree (1, 0)), h = v − u (degree (1, 1)).
/// let f = Bernstein::new(&[1, 0], vec![Rational::from((-1, 3)), Rational::from((2, 3))]).unwrap();
/// let h = Bernstein::new(&[1, 1], [0, 1, -1, 0].map(Rational::from).to_vec()).unwrap();
/// let unit = vec![(Dyadic::ZERO, Dyadic::ONE); 2];
/// let r = solve_system(&[f, h], &[], &unit, &SystemOptions::default());
/// assert_eq!(r.roots.len(), 1);
/// let e = &r.roots[0].enclosure;
/// assert!(e[0][0] <= 1.0 / 3.0 && 1.0 / 3.0 <= e[0][1] && e[1][0] <= 1.0 / 3.0 && 1.0 / 3.0 <= e[1][1]);
/// ```
pub fn solve_system(
    square: &[Bernstein<Rational>],
    filters: &[Bernstein<Rational>],
    domain: &DyadicBoxN,
    opts: &SystemOptions,
) -> SystemRoots {
    solve_system_excluding(square, filters, domain, &[], opts)
}

/// [`solve_system`] on the domain less some boxes that the caller has proven to hold no root
/// it wants (for example a box around a known root that holds no other): boxes inside one
/// of them are not examined, and a root whose enclosure (clipped to the domain) lies inside
/// one is not reported.
/// A root whose enclosure straddles an excluded box's boundary is reported.
pub fn solve_system_excluding(
    square: &[Bernstein<Rational>],
    filters: &[Bernstein<Rational>],
    domain: &DyadicBoxN,
    exclude: &[DyadicBoxN],
    opts: &SystemOptions,
) -> SystemRoots {
    let n = square.len();
    assert!(
        n >= 1 && domain.len() == n,
        "a square system on a box of its dimension"
    );
    assert!(
        square.iter().chain(filters).all(|p| p.nvars() == n),
        "every polynomial has n variables"
    );
    isolate(&Dense::new(square, filters), domain, exclude, opts)
}

/// The subdivision solver on any [`SquareSystem`] of `domain.len()` equations: the roots on
/// `domain` less the boxes of `exclude` (as [`solve_system_excluding`] states).
pub(crate) fn isolate<S: SquareSystem>(
    sys: &S,
    domain: &DyadicBoxN,
    exclude: &[DyadicBoxN],
    opts: &SystemOptions,
) -> SystemRoots {
    let mut out = SystemRoots::default();
    let dlo: Vec<f64> = domain.iter().map(|d| d.0.to_f64()).collect();
    let dhi: Vec<f64> = domain.iter().map(|d| d.1.to_f64()).collect();
    let mut stack: Vec<(DyadicBoxN, u32, S::Local)> =
        vec![(domain.clone(), 0, sys.on_box(&dlo, &dhi))];
    let excluded_f64: Vec<Vec<[f64; 2]>> = exclude
        .iter()
        .map(|b| b.iter().map(|d| [d.0.to_f64(), d.1.to_f64()]).collect())
        .collect();
    let in_excluded = |b: &DyadicBoxN| {
        exclude
            .iter()
            .any(|e| e.iter().zip(b).all(|(x, y)| x.0 <= y.0 && y.1 <= x.1))
    };
    let n = domain.len();
    while let Some((bx, depth, local)) = stack.pop() {
        out.boxes += 1;
        if in_excluded(&bx) || sys.excludes(&local) {
            continue;
        }
        let lo: Vec<f64> = bx.iter().map(|d| d.0.to_f64()).collect();
        let hi: Vec<f64> = bx.iter().map(|d| d.1.to_f64()).collect();
        // The box grown by an eighth of its width on each side (exact in f64: dyadic).
        let glo: Vec<f64> = lo.iter().zip(&hi).map(|(a, b)| a - (b - a) / 8.0).collect();
        let ghi: Vec<f64> = lo.iter().zip(&hi).map(|(a, b)| b + (b - a) / 8.0).collect();
        // Krawczyk's operator on the box itself, from the polynomials already on it: a zero
        // proven unique in the box, none in it, or, where the rows contract, the test on the
        // grown box (a zero near the box's side is proven by one of the boxes around it).
        let tested = match verdict_of(&sys.jacobian(&local), || sys.centre(&local)) {
            KrawczykVerdict::NoZero => continue,
            KrawczykVerdict::Unique(k) => to_global(&k, &lo, &hi).map(|enc| (enc, &lo, &hi)),
            KrawczykVerdict::Unknown { worth: true } => {
                krawczyk_local(sys, &sys.on_box(&glo, &ghi))
                    .and_then(|k| to_global(&k, &glo, &ghi))
                    .map(|enc| (enc, &glo, &ghi))
            }
            KrawczykVerdict::Unknown { worth: false } => None,
        };
        if let Some((enc, ulo, uhi)) = tested {
            let unique_in: Vec<[f64; 2]> = ulo.iter().zip(uhi).map(|(a, b)| [*a, *b]).collect();
            let outside = enc
                .iter()
                .enumerate()
                .any(|(i, e)| e[1] < dlo[i] || e[0] > dhi[i]);
            if !outside {
                let seen = out
                    .roots
                    .iter()
                    .any(|r| within(&enc, &r.unique_in) || within(&r.enclosure, &unique_in));
                // Clipped to the domain: a root outside it is not wanted either.
                let clipped: Vec<[f64; 2]> = enc
                    .iter()
                    .enumerate()
                    .map(|(i, e)| [e[0].max(dlo[i]), e[1].min(dhi[i])])
                    .collect();
                let trivial = excluded_f64.iter().any(|e| within(&clipped, e));
                if !seen && !trivial {
                    let mut tight = Tight {
                        sys,
                        ladder: &opts.ladder,
                        counts: &mut out.escalations,
                    };
                    let enc = refine(&mut tight, &unique_in, enc, opts.refine_width);
                    // Refined, a root that straddled the boundary may be proven outside.
                    if enc
                        .iter()
                        .enumerate()
                        .any(|(i, e)| e[1] < dlo[i] || e[0] > dhi[i])
                    {
                        continue;
                    }
                    // Refined, the same zero found from another box is recognised as above;
                    // an enclosure that still meets a known one may hold that zero or
                    // another: the region is not decided (proofs/krawczyk.md, each once).
                    match against_known(&out.roots, &enc, &unique_in) {
                        Known::Same => continue,
                        Known::Undecided => {
                            out.unresolved.push(unique_in);
                            continue;
                        }
                        Known::New => {}
                    }
                    let inside = enc
                        .iter()
                        .enumerate()
                        .all(|(i, e)| dlo[i] <= e[0] && e[1] <= dhi[i]);
                    out.roots.push(IsolatedRoot {
                        unique_in,
                        enclosure: enc,
                        inside,
                    });
                }
            }
            continue;
        }
        if depth >= opts.max_depth || out.boxes + stack.len() >= opts.max_boxes {
            out.unresolved
                .push(lo.iter().zip(&hi).map(|(a, b)| [*a, *b]).collect());
            continue;
        }
        // Split at their midpoints the axes at least half as wide as the widest (all of them
        // on a cube: 2^n children); a thin axis is not split further until the others catch
        // up, so a domain with one very narrow variable costs no more than one without it.
        let widest = lo.iter().zip(&hi).map(|(a, b)| b - a).fold(0.0, f64::max);
        let axes: Vec<usize> = (0..n).filter(|&a| hi[a] - lo[a] >= widest / 2.0).collect();
        let Some(cells) = split_cell(&bx, &axes) else {
            out.unresolved
                .push(lo.iter().zip(&hi).map(|(a, b)| [*a, *b]).collect());
            continue;
        };
        let locals = sys.split(local, &axes);
        for (b, ps) in cells.into_iter().zip(locals).rev() {
            stack.push((b, depth + 1, ps));
        }
    }
    out
}

/// A box split at the midpoints of the given axes (2^k children, in a fixed order), each with
/// the polynomials subdivided with it; `None` if a side is at the dyadic limit.
pub(crate) fn split_box(
    bx: &DyadicBoxN,
    polys: Vec<Bernstein<Interval>>,
    axes: &[usize],
) -> Option<Vec<(DyadicBoxN, Vec<Bernstein<Interval>>)>> {
    let cells = split_cell(bx, axes)?;
    Some(cells.into_iter().zip(split_polys(polys, axes)).collect())
}

/// A box split at the midpoints of the given axes: `2^k` boxes, the first axis's halves
/// outermost; `None` if a side is at the dyadic limit.
pub(crate) fn split_cell(bx: &DyadicBoxN, axes: &[usize]) -> Option<Vec<DyadicBoxN>> {
    let mut children = vec![bx.clone()];
    for &axis in axes {
        let mut next = Vec::with_capacity(children.len() * 2);
        for b in children {
            let mid = b[axis].0.midpoint(b[axis].1)?;
            let (mut l, mut r) = (b.clone(), b);
            l[axis].1 = mid;
            r[axis].0 = mid;
            next.push(l);
            next.push(r);
        }
        children = next;
    }
    Some(children)
}

/// The simplest rational (smallest denominator, then numerator) in `[lo, hi]`, for
/// `0 ≤ lo ≤ hi`, by continued fractions.
pub fn simplest_rational(lo: &Rational, hi: &Rational) -> Rational {
    let n = Rational::from(lo.ceil_ref());
    if n <= *hi {
        return n;
    }
    let fl = Rational::from(lo.floor_ref());
    // lo and hi lie strictly between fl and fl + 1.
    let a = Rational::from(hi - &fl).recip();
    let b = Rational::from(lo - &fl).recip();
    fl + simplest_rational(&a, &b).recip()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::{Precision, Rational};

    #[test]
    fn krawczyk_in_a_small_box_proves_the_root_and_nothing_else() {
        // f = x² + y² − 1/2, g = x − y: one root in the unit square, at (1/2, 1/2).
        let q = |a: i64, b: i64| Rational::from((a, b));
        let x = Bernstein::new(&[1, 0], vec![q(0, 1), q(1, 1)]).unwrap();
        let y = Bernstein::new(&[0, 1], vec![q(0, 1), q(1, 1)]).unwrap();
        let half = Bernstein::new(&[0, 0], vec![q(1, 2)]).unwrap();
        let f = &(&(&x * &x) + &(&y * &y)) - &half;
        let g = &x - &y;
        let polys: Vec<Bernstein<Interval>> =
            [f, g].iter().map(|p| p.convert(Precision::F64)).collect();
        let derivs: Vec<Vec<Bernstein<Interval>>> = polys
            .iter()
            .map(|p| (0..2).map(|j| p.deriv(j)).collect())
            .collect();
        let k = krawczyk_in_box(&polys, &derivs, &[0.499, 0.4995], &[0.5008, 0.501]).unwrap();
        assert!(
            k.iter().all(|x| x.contains(0.5) && x.width() < 1e-4),
            "{k:?}"
        );
        // A box without the root, and one too wide for the test, prove nothing.
        assert!(krawczyk_in_box(&polys, &derivs, &[0.6, 0.6], &[0.7, 0.7]).is_none());
        assert!(krawczyk_in_box(&polys, &derivs, &[0.0, 0.0], &[1.0, 1.0]).is_none());
    }
}
