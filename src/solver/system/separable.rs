//! Square systems whose equations separate into two groups of variables: each equation is a
//! polynomial of one group, or the equality of a ratio of the first group's polynomials with a
//! ratio of the second's. The image crossings of two curves are such a system (the same image
//! point: `x_a / q_a = x_b / q_b`, `y_a / q_a = y_b / q_b`, and each curve's own equation), and
//! so is a curve passing through a surface.
//!
//! Solved by the same subdivision and Krawczyk test as a dense system ([`super::solve_system`]),
//! but
//! each group's polynomials are restricted to the group's part of a box on their own: a box
//! of `n_0 + n_1` variables costs two restrictions of `n_0`- and `n_1`-variate polynomials,
//! not restrictions of their `(n_0 + n_1)`-variate products, and a split along one group's
//! variables leaves the other group's restriction as it was (shared). The exclusion of a box by
//! a ratio equation compares the ranges of the two ratios, which is as strong as the sign test
//! on the product polynomial's coefficients (`proofs/separable-systems.md`).

use super::{excludes, isolate, split_polys, DyadicBoxN, SquareSystem, SystemOptions, SystemRoots};
use crate::bernstein::{lift, Bernstein, Poly};
use crate::number::{Interval, Number, Precision, Rational};
use crate::solver::precision::{Ladder, Level};
use std::cell::OnceCell;
use std::rc::Rc;

/// One group of variables: its box and polynomials in its variables.
#[derive(Clone, Debug)]
pub struct Group<'a> {
    /// The polynomials, each in `domain.len()` variables, given on the whole parameter space
    /// (the box is where the system is solved, not their own domain).
    pub polys: Vec<&'a Poly>,
    /// The group's box.
    pub domain: &'a DyadicBoxN,
}

/// An equation of a separable system.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Equation {
    /// The polynomial `poly` of group `group` (0 or 1) vanishes.
    Zero {
        /// The group.
        group: usize,
        /// The polynomial's index in the group.
        poly: usize,
    },
    /// `n_0 / d_0 = n_1 / d_1`, written without the division as `n_0 d_1 − n_1 d_0 = 0`:
    /// `[numerator, denominator]` indices in group 0, then in group 1.
    Ratio {
        /// `[n_0, d_0]` in group 0.
        first: [usize; 2],
        /// `[n_1, d_1]` in group 1.
        second: [usize; 2],
    },
}

/// A square separable system: as many equations as the two groups have variables.
#[derive(Clone, Debug)]
pub struct SeparableSystem<'a> {
    /// The two groups; the system's variables are group 0's, then group 1's.
    pub groups: [Group<'a>; 2],
    /// The equations.
    pub equations: Vec<Equation>,
}

/// Isolates the roots of a separable system on the product of its groups' boxes, less the
/// boxes of `exclude` (boxes of both groups' variables), as
/// [`solve_system_excluding`](super::solve_system_excluding) does for a dense system; the
/// roots' boxes are in group 0's variables, then group 1's.
///
/// # Panics
/// If the equations are not as many as the variables, a polynomial has another number of
/// variables than its group, or an index names no polynomial.
///
/// # Examples
/// ```
/// use limn::bernstein::Bernstein;
/// use limn::number::Rational;
/// use limn::solver::system::separable::{solve_separable, Equation, Group, SeparableSystem};
/// use limn::solver::system::SystemOptions;
/// use limn::solver::Dyadic;
/// // The segment t ↦ (t, 1 − t) and the segment s ↦ (s, s) cross at t = s = 1/2.
/// let p = |c: [i64; 2]| Bernstein::new(&[1], c.map(Rational::from).to_vec()).unwrap();
/// let one = Bernstein::new(&[0], vec![Rational::from(1)]).unwrap();
/// let (xa, ya, xb, yb) = (p([0, 1]), p([1, 0]), p([0, 1]), p([0, 1]));
/// let unit = vec![(Dyadic::ZERO, Dyadic::ONE)];
/// let group = |x, y| Group { polys: vec![x, y, &one], domain: &unit };
/// let system = SeparableSystem {
///     groups: [group(&xa, &ya), group(&xb, &yb)],
///     equations: vec![
///         Equation::Ratio { first: [0, 2], second: [0, 2] },
///         Equation::Ratio { first: [1, 2], second: [1, 2] },
///     ],
/// };
/// let r = solve_separable(&system, &[], &SystemOptions::default());
/// assert_eq!(r.roots.len(), 1);
/// assert!(r.roots[0].enclosure.iter().all(|e| e[0] <= 0.5 && 0.5 <= e[1]));
/// ```
pub fn solve_separable(
    system: &SeparableSystem,
    exclude: &[DyadicBoxN],
    opts: &SystemOptions,
) -> SystemRoots {
    let solver = Solver::new(system);
    let domain: DyadicBoxN = system
        .groups
        .iter()
        .flat_map(|g| g.domain.iter().copied())
        .collect();
    let separable = isolate(&solver, &domain, exclude, opts);
    if separable.unresolved.is_empty() {
        return separable;
    }
    settle_densely(system, separable, &domain, exclude, opts)
}

/// Where the separable solve left boxes unresolved, the whole system is solved again by the
/// dense solver on the multiplied-out equations ([`SeparableSystem::dense`]), with the same
/// options (the box budget scaled to the work of [`DENSE_COEFFICIENTS`]) and exclusions, and
/// the answer whose unresolved boxes have the smaller total volume
/// is kept (the dense one on a tie). Both are certified answers for the whole domain (`proofs/krawczyk.md`,
/// `proofs/separable-systems.md` §3), so either may be returned; the dense solver's centre
/// values and Jacobian of one product polynomial can be tighter than the products of the
/// groups' separate enclosures (near tangential crossings, along shared sides), so a system
/// the separable solve cannot settle is answered at least as completely as by the dense
/// solver alone. The work of both is counted.
fn settle_densely(
    system: &SeparableSystem,
    separable: SystemRoots,
    domain: &DyadicBoxN,
    exclude: &[DyadicBoxN],
    opts: &SystemOptions,
) -> SystemRoots {
    let (equations, _) = system.dense();
    // The budget in work, not boxes: a box of the dense system costs about its coefficient
    // count, and the large products (a curve against a NURBS patch of high degree) are where
    // the dense solver rarely settles what the separable one did not; the small ones (lines,
    // low-degree arcs) keep the whole box budget.
    let coeffs: usize = equations.iter().map(|p| p.coeffs().len()).sum();
    let budget = SystemOptions {
        max_boxes: (opts.max_boxes * DENSE_COEFFICIENTS / coeffs.max(1)).clamp(1, opts.max_boxes),
        ..opts.clone()
    };
    let dense = super::solve_system_excluding(&equations, &[], domain, exclude, &budget);
    // The measure left undecided: the unresolved boxes' total volume.
    let volume = |r: &SystemRoots| -> f64 {
        r.unresolved
            .iter()
            .map(|b| b.iter().map(|e| e[1] - e[0]).product::<f64>())
            .sum()
    };
    let (mut kept, other) = if volume(&separable) < volume(&dense) {
        (separable, dense)
    } else {
        (dense, separable)
    };
    kept.boxes += other.boxes;
    kept.escalations.merge(&other.escalations);
    kept
}

/// The coefficient count up to which the dense fallback gets the whole box budget; a larger
/// system gets the same work, `max_boxes × DENSE_COEFFICIENTS` coefficient visits
/// ([`settle_densely`]).
const DENSE_COEFFICIENTS: usize = 128;

impl SeparableSystem<'_> {
    /// The system multiplied out in the joint variables (group 0's, then group 1's): a ratio
    /// equation `n_0 / d_0 = n_1 / d_1` as `n_0 d_1 − n_1 d_0`, a group's polynomial lifted
    /// (degree 0 in the other group), in the order of the equations; and the joint box.
    pub fn dense(&self) -> (Vec<Poly>, DyadicBoxN) {
        let n0 = self.groups[0].domain.len();
        let n = n0 + self.groups[1].domain.len();
        let l = |g: usize, k: usize| lift(self.groups[g].polys[k], n, if g == 0 { 0 } else { n0 });
        let equations = self
            .equations
            .iter()
            .map(|e| match *e {
                Equation::Zero { group, poly } => l(group, poly),
                Equation::Ratio { first, second } => {
                    &(&l(0, first[0]) * &l(1, second[1])) - &(&l(1, second[0]) * &l(0, first[1]))
                }
            })
            .collect();
        let domain = self
            .groups
            .iter()
            .flat_map(|g| g.domain.iter().copied())
            .collect();
        (equations, domain)
    }
}

/// A group's polynomials on a box of its variables (in the box's unit coordinates), with what
/// every box test of the system asks of them.
struct Part {
    polys: Vec<Bernstein<Interval>>,
    /// The hull of each polynomial's coefficients (its range on the box).
    hulls: Vec<Interval>,
    /// For each ratio equation in order, the range of the group's ratio on the box where its
    /// denominator's coefficients are all positive.
    ratios: Vec<Option<Interval>>,
    /// Some `Zero` equation of the group has a strict sign on the box.
    excluded: bool,
}

impl Part {
    fn new(polys: Vec<Bernstein<Interval>>, zeros: &[usize], pairs: &[[usize; 2]]) -> Part {
        let hulls = polys.iter().map(Bernstein::hull).collect();
        let ratios = pairs
            .iter()
            .map(|&[n, d]| ratio_range(&polys[n], &polys[d]))
            .collect();
        let excluded = zeros.iter().any(|&p| excludes(&polys[p]));
        Part {
            polys,
            hulls,
            ratios,
            excluded,
        }
    }
}

/// The range of `n / d` on the unit box when every coefficient of `d` is positive: the hull of
/// the coefficient ratios `n_i / d_i` (a rational Bézier function with positive weights lies
/// in the hull of its control values; `proofs/separable-systems.md`). `n` and `d` have the
/// same degrees; `None` otherwise, or when some coefficient of `d` is not positive.
fn ratio_range(n: &Bernstein<Interval>, d: &Bernstein<Interval>) -> Option<Interval> {
    if d.degrees().iter().all(|&k| k == 0) {
        let c = d.coeffs()[0];
        if c.lo() > 0.0 {
            return n.hull().checked_div(&c);
        }
        return None;
    }
    if n.degrees() != d.degrees() {
        return None;
    }
    let mut range: Option<Interval> = None;
    for (ni, di) in n.coeffs().iter().zip(d.coeffs()) {
        if di.lo() <= 0.0 {
            return None;
        }
        let r = ni.checked_div(di)?;
        range = Some(range.map_or(r, |a| a.hull(&r)));
    }
    range
}

/// An enclosure of `∂_j n_0 · d_1 − n_1 · ∂_j d_0` on the box, `[n_0, d_0]` of the
/// differentiated group and `[n_1, d_1]` of the other, each restricted to its part of the box.
/// Where `n_0`, `d_0` share their degrees and so do `n_1`, `d_1`, the product of a polynomial
/// in one group's variables with one in the other's is a tensor-product Bernstein polynomial
/// whose coefficients are the products of theirs: the expression's coefficients are
/// `a_i p_k − c_i q_k` (`a`, `c` those of the partials, `p`, `q` of `d_1`, `n_1`), and their
/// hull is the dense solver's hull of the same partial, without forming the product
/// (`proofs/separable-systems.md`, section 2). Otherwise the product of the factors' hulls.
fn ratio_partial(
    mine: [&Bernstein<Interval>; 2],
    theirs: [&Bernstein<Interval>; 2],
    theirs_hulls: [&Interval; 2],
    j: usize,
) -> Interval {
    let [n0, d0] = mine;
    let [n1, d1] = theirs;
    if n0.degrees() != d0.degrees() || n1.degrees() != d1.degrees() {
        return n0
            .deriv_hull(j)
            .mul(theirs_hulls[1])
            .sub(&theirs_hulls[0].mul(&d0.deriv_hull(j)));
    }
    let (a, c) = (n0.deriv(j), d0.deriv(j));
    let (a, c, p, q) = (a.coeffs(), c.coeffs(), d1.coeffs(), n1.coeffs());
    tensor_hull_f64(a, c, p, q).unwrap_or_else(|| {
        let mut hull: Option<Interval> = None;
        for (ai, ci) in a.iter().zip(c) {
            for (pk, qk) in p.iter().zip(q) {
                let v = ai.mul(pk).sub(&ci.mul(qk));
                hull = Some(hull.map_or(v, |h| h.hull(&v)));
            }
        }
        hull.expect("a polynomial has a coefficient")
    })
}

/// An enclosure of every `a_i p_k − c_i q_k` (`a_i` in the interval `a[i]`, and so on),
/// evaluated in plain f64 at the intervals' midpoints, widened by one bound on every term's
/// distance from its f64 value (the radii and the rounding: `proofs/separable-systems.md`,
/// section 2); `None` where a bound or a value is not finite (the caller then uses interval
/// arithmetic).
fn tensor_hull_f64(
    a: &[Interval],
    c: &[Interval],
    p: &[Interval],
    q: &[Interval],
) -> Option<Interval> {
    const U: f64 = f64::EPSILON / 2.0;
    // Finite inputs, so that no midpoint or radius is a NaN (which `min` and `max` skip).
    let finite = |x: &[Interval]| x.iter().all(|v| v.lo().is_finite() && v.hi().is_finite());
    if !(finite(a) && finite(c) && finite(p) && finite(q)) {
        return None;
    }
    // Midpoints, and the largest |midpoint| and radius (rounded up) of each list.
    let split = |x: &[Interval], mids: &mut Vec<f64>| -> (f64, f64) {
        let (mut big, mut rad) = (0.0f64, 0.0f64);
        for v in x {
            let m = 0.5 * v.lo() + 0.5 * v.hi();
            let r = (v.hi() - m).max(m - v.lo()).next_up();
            mids.push(m);
            big = big.max(m.abs());
            rad = rad.max(r);
        }
        (big, rad)
    };
    let (mut am, mut cm, mut pm, mut qm) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let (ba, ra) = split(a, &mut am);
    let (bc, rc) = split(c, &mut cm);
    let (bp, rp) = split(p, &mut pm);
    let (bq, rq) = split(q, &mut qm);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (&ai, &ci) in am.iter().zip(&cm) {
        for (&pk, &qk) in pm.iter().zip(&qm) {
            let v = ai * pk - ci * qk;
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    // |a p − ã p̃| ≤ r_a (|p̃| + r_p) + |ã| r_p, the same for c q, plus the rounding of the
    // two products and their difference (3u of the products' sizes) and of underflow; the
    // bound's own dozen roundings are covered by the factor 1 + 2^-40.
    let e = (ra * (bp + rp)
        + ba * rp
        + rc * (bq + rq)
        + bc * rq
        + 3.0 * U * (ba * bp + bc * bq)
        + 1e-300)
        * (1.0 + 2f64.powi(-40));
    // With `e` finite every product is finite (|ã p̃| ≤ |ã|max |p̃|max, rounding is
    // monotonic); a difference may overflow to an infinity, never to a NaN.
    let (lo, hi) = ((lo - e).next_down(), (hi + e).next_up());
    (lo.is_finite() && hi.is_finite() && e.is_finite()).then(|| Interval::new(lo, hi))
}

/// A separable system ready for the subdivision solver.
struct Solver<'s, 'a> {
    system: &'s SeparableSystem<'a>,
    /// Each group's number of variables.
    dims: [usize; 2],
    /// Each group's polynomials in f64 intervals.
    whole: [Vec<Bernstein<Interval>>; 2],
    /// Each group's polynomials whose `Zero` equation is in the system.
    zeros: [Vec<usize>; 2],
    /// Each group's `[numerator, denominator]` of every ratio equation, in order.
    pairs: [Vec<[usize; 2]>; 2],
    /// Each group's polynomials in f64 and their partial derivatives, for Newton's method.
    floats: OnceCell<[Floats; 2]>,
}

/// Polynomials in f64 and their partial derivatives.
type Floats = (Vec<Bernstein<f64>>, Vec<Vec<Bernstein<f64>>>);

impl<'s, 'a> Solver<'s, 'a> {
    fn new(system: &'s SeparableSystem<'a>) -> Self {
        let dims = [system.groups[0].domain.len(), system.groups[1].domain.len()];
        assert_eq!(
            system.equations.len(),
            dims[0] + dims[1],
            "a square separable system"
        );
        for (g, group) in system.groups.iter().enumerate() {
            assert!(
                group.polys.iter().all(|p| p.nvars() == dims[g]),
                "every polynomial of a group has the group's variables"
            );
        }
        let mut zeros = [Vec::new(), Vec::new()];
        let mut pairs = [Vec::new(), Vec::new()];
        for e in &system.equations {
            match *e {
                Equation::Zero { group, poly } => {
                    assert!(
                        poly < system.groups[group].polys.len(),
                        "a polynomial index"
                    );
                    zeros[group].push(poly);
                }
                Equation::Ratio { first, second } => {
                    for (g, pair) in [first, second].into_iter().enumerate() {
                        assert!(
                            pair.iter().all(|&k| k < system.groups[g].polys.len()),
                            "a polynomial index"
                        );
                        pairs[g].push(pair);
                    }
                }
            }
        }
        let whole = [0, 1].map(|g| {
            system.groups[g]
                .polys
                .iter()
                .map(|p| p.convert(Precision::F64))
                .collect()
        });
        Solver {
            system,
            dims,
            whole,
            zeros,
            pairs,
            floats: OnceCell::new(),
        }
    }

    fn part(&self, g: usize, polys: Vec<Bernstein<Interval>>) -> Rc<Part> {
        Rc::new(Part::new(polys, &self.zeros[g], &self.pairs[g]))
    }

    /// The global box's part in group `g`'s variables.
    fn of_group<'x, T>(&self, g: usize, x: &'x [T]) -> &'x [T] {
        if g == 0 {
            &x[..self.dims[0]]
        } else {
            &x[self.dims[0]..]
        }
    }
}

impl SquareSystem for Solver<'_, '_> {
    type Local = [Rc<Part>; 2];

    fn on_box(&self, lo: &[f64], hi: &[f64]) -> Self::Local {
        [0, 1].map(|g| {
            let (l, h) = (self.of_group(g, lo), self.of_group(g, hi));
            let polys = self.whole[g]
                .iter()
                .map(|p| p.restrict_box_f64(l, h))
                .collect();
            self.part(g, polys)
        })
    }

    fn on_box_tight(
        &self,
        ladder: &Ladder,
        lo: &[Rational],
        hi: &[Rational],
    ) -> (Self::Local, Level) {
        let mut level = Level::F64;
        let local = [0, 1].map(|g| {
            let (l, h) = (self.of_group(g, lo), self.of_group(g, hi));
            let (polys, at) = ladder.restricted_enclosures(&self.system.groups[g].polys, l, h);
            level = level.max(at);
            self.part(g, polys)
        });
        (local, level)
    }

    fn split(&self, local: Self::Local, axes: &[usize]) -> Vec<Self::Local> {
        let n0 = self.dims[0];
        let [p0, p1] = local;
        let halves = |g: usize, part: Rc<Part>, axes: Vec<usize>| -> Vec<Rc<Part>> {
            if axes.is_empty() {
                return vec![part];
            }
            split_polys(part.polys.clone(), &axes)
                .into_iter()
                .map(|ps| self.part(g, ps))
                .collect()
        };
        let first = halves(0, p0, axes.iter().copied().filter(|&a| a < n0).collect());
        let second = halves(
            1,
            p1,
            axes.iter().filter(|&&a| a >= n0).map(|a| a - n0).collect(),
        );
        // The first group's axes come first in `axes`, so its halves are outermost.
        first
            .iter()
            .flat_map(|a| second.iter().map(move |b| [a.clone(), b.clone()]))
            .collect()
    }

    fn excludes(&self, local: &Self::Local) -> bool {
        if local[0].excluded || local[1].excluded {
            return true;
        }
        let mut r = 0;
        for e in &self.system.equations {
            if let Equation::Ratio { first, second } = *e {
                let (a, b) = (&local[0], &local[1]);
                let separated = match (a.ratios[r], b.ratios[r]) {
                    (Some(x), Some(y)) => x.hi() < y.lo() || y.hi() < x.lo(),
                    _ => {
                        let v = a.hulls[first[0]]
                            .mul(&b.hulls[second[1]])
                            .sub(&b.hulls[second[0]].mul(&a.hulls[first[1]]));
                        v.lo() > 0.0 || v.hi() < 0.0
                    }
                };
                if separated {
                    return true;
                }
                r += 1;
            }
        }
        false
    }

    fn jacobian(&self, local: &Self::Local) -> Vec<Vec<Interval>> {
        let zero = Interval::point(0.0);
        let n = self.dims[0] + self.dims[1];
        self.system
            .equations
            .iter()
            .map(|e| {
                let mut row = vec![zero; n];
                let mut at = 0;
                for (g, part) in local.iter().enumerate() {
                    for j in 0..self.dims[g] {
                        row[at + j] = match *e {
                            Equation::Zero { group, poly } if group == g => {
                                part.polys[poly].deriv_hull(j)
                            }
                            Equation::Zero { .. } => zero,
                            Equation::Ratio { first, second } => {
                                // ∂(n_0 d_1 − n_1 d_0): each group's derivatives times the
                                // other group's ranges.
                                let (mine, theirs, other) = if g == 0 {
                                    (first, second, &local[1])
                                } else {
                                    (second, first, &local[0])
                                };
                                let d = ratio_partial(
                                    [&part.polys[mine[0]], &part.polys[mine[1]]],
                                    [&other.polys[theirs[0]], &other.polys[theirs[1]]],
                                    [&other.hulls[theirs[0]], &other.hulls[theirs[1]]],
                                    j,
                                );
                                if g == 0 {
                                    d
                                } else {
                                    d.neg()
                                }
                            }
                        };
                    }
                    at += self.dims[g];
                }
                row
            })
            .collect()
    }

    fn centre(&self, local: &Self::Local) -> Vec<Interval> {
        let values: Vec<Vec<Interval>> = local
            .iter()
            .map(|part| part.polys.iter().map(Bernstein::value_at_centre).collect())
            .collect();
        self.system
            .equations
            .iter()
            .map(|e| match *e {
                Equation::Zero { group, poly } => values[group][poly],
                Equation::Ratio { first, second } => {
                    let (a, b) = (&values[0], &values[1]);
                    a[first[0]]
                        .mul(&b[second[1]])
                        .sub(&b[second[0]].mul(&a[first[1]]))
                }
            })
            .collect()
    }

    fn eval_f64(&self, x: &[f64]) -> (Vec<f64>, Vec<Vec<f64>>) {
        let floats = self.floats.get_or_init(|| {
            [0, 1].map(|g| {
                let f: Vec<Bernstein<f64>> = self.system.groups[g]
                    .polys
                    .iter()
                    .map(|p| p.convert(Precision::F64))
                    .collect();
                let df = f
                    .iter()
                    .map(|p| (0..self.dims[g]).map(|j| p.deriv(j)).collect())
                    .collect();
                (f, df)
            })
        });
        // Each group's values and partial derivatives at its part of the point.
        let at: Vec<(Vec<f64>, Vec<Vec<f64>>)> = (0..2)
            .map(|g| {
                let xg = self.of_group(g, x);
                let (f, df) = &floats[g];
                let v = f.iter().map(|p| p.eval(xg)).collect();
                let d = df
                    .iter()
                    .map(|r| r.iter().map(|p| p.eval(xg)).collect())
                    .collect();
                (v, d)
            })
            .collect();
        let n = x.len();
        let mut values = Vec::with_capacity(n);
        let mut jac = Vec::with_capacity(n);
        for e in &self.system.equations {
            let mut row = vec![0.0; n];
            match *e {
                Equation::Zero { group, poly } => {
                    values.push(at[group].0[poly]);
                    let off = if group == 0 { 0 } else { self.dims[0] };
                    for (j, d) in at[group].1[poly].iter().enumerate() {
                        row[off + j] = *d;
                    }
                }
                Equation::Ratio { first, second } => {
                    let (a, b) = (&at[0], &at[1]);
                    values.push(a.0[first[0]] * b.0[second[1]] - b.0[second[0]] * a.0[first[1]]);
                    let (left, right) = row.split_at_mut(self.dims[0]);
                    for (j, r) in left.iter_mut().enumerate() {
                        *r = a.1[first[0]][j] * b.0[second[1]] - b.0[second[0]] * a.1[first[1]][j];
                    }
                    for (j, r) in right.iter_mut().enumerate() {
                        *r = a.0[first[0]] * b.1[second[1]][j] - b.1[second[0]][j] * a.0[first[1]];
                    }
                }
            }
            jac.push(row);
        }
        (values, jac)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn exact(x: f64) -> Rational {
        Rational::from_f64(x).expect("finite")
    }

    /// An interval of any sign and magnitude, possibly a point.
    fn interval() -> impl Strategy<Value = Interval> {
        (-1.0e3f64..1.0e3, -30i32..30, 0.0f64..1.0, prop::bool::ANY).prop_map(|(m, e, w, point)| {
            let c = m * 2f64.powi(e);
            let r = if point { 0.0 } else { w * c.abs() * 1e-3 };
            Interval::new(c - r, c + r)
        })
    }

    proptest! {
        /// Every `a_i p_k − c_i q_k` with its factors anywhere in their intervals (the
        /// corners, where the extremes of a bilinear form lie) is in the f64 hull, computed
        /// exactly in rationals.
        #[test]
        fn the_f64_tensor_hull_encloses_every_exact_term(
            a in prop::collection::vec(interval(), 1..5),
            c in prop::collection::vec(interval(), 5),
            p in prop::collection::vec(interval(), 1..5),
            q in prop::collection::vec(interval(), 5),
        ) {
            let (c, q) = (&c[..a.len()], &q[..p.len()]);
            let h = tensor_hull_f64(&a, c, &p, q).expect("finite inputs");
            let (lo, hi) = (exact(h.lo()), exact(h.hi()));
            for (ai, ci) in a.iter().zip(c) {
                for (pk, qk) in p.iter().zip(q) {
                    for bits in 0..16 {
                        let pick = |x: &Interval, b: usize| exact(if bits >> b & 1 == 0 { x.lo() } else { x.hi() });
                        let v = pick(ai, 0) * pick(pk, 1) - pick(ci, 2) * pick(qk, 3);
                        prop_assert!(lo <= v && v <= hi, "{v} outside [{lo}, {hi}]");
                    }
                }
            }
        }
    }

    #[test]
    fn an_infinite_bound_is_left_to_interval_arithmetic() {
        let inf = Interval::new(f64::NEG_INFINITY, 1.0);
        let one = [Interval::point(1.0)];
        assert!(tensor_hull_f64(&[inf], &one, &one, &one).is_none());
        let huge = [Interval::point(1e300)];
        assert!(tensor_hull_f64(&huge, &one, &huge, &one).is_none());
    }
}
