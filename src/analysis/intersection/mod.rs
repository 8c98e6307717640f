//! Certified intersection curves of two patches: the points where two rational patches pass
//! through each other (the teapot's spout and handle through its body).
//!
//! For patches `P(u, v) = (X, Y, Z) / W` and `Q(s, t)`, the points of space on both are the
//! common zeros in `(u, v, s, t) ∈ [0, 1]⁴` of the three polynomials
//! `W_P X_Q − W_Q X_P`, `W_P Y_Q − W_Q Y_P`, `W_P Z_Q − W_Q Z_P` ([`intersection_system`]):
//! with both weights positive on the unit square they vanish together exactly where
//! `P(u, v) = Q(s, t)`. Three equations in four unknowns: a curve, whose certified topology
//! the n-variable curve solver gives ([`crate::solver::space_curve`], `proofs/space-curves.md`):
//! smooth arcs, each in a box where it is a graph over one variable, between crossings with
//! proven enclosures; where the patches touch tangentially (the Jacobian's rank drops) the
//! boxes are unresolved, never guessed (`proofs/intersection-curves.md`).

use crate::bernstein::lift;
use crate::bernstein::Poly;
use crate::number::{Interval, Number, Rational};
use crate::solver::space_curve::{
    solve_space_curve, unwarp, unwarp_interval, warp, SpaceCurve, SpaceCurveOptions, PAIR_WARP,
};
use crate::surface::RationalPatch;

/// The three polynomials in `(u, v, s, t)` (the first patch's parameters, then the second's)
/// whose common zeros are the pairs of parameters with `P(u, v) = Q(s, t)`: the cross
/// differences `W_P H_Q − W_Q H_P` of the homogeneous coordinates `H = (X, Y, Z)`.
///
/// # Examples
/// ```
/// use limn::analysis::intersection::intersection_system;
/// use limn::number::Rational;
/// use limn::testing::shapes;
/// let q = |n: i64| Rational::from(n);
/// let h = |a: i64, b: i64| Rational::from((a, b));
/// // The planes z = x over [0, 1]² and z = y/2 over [1/4, 3/4]² meet on the line y = 2x = 2z.
/// let p = shapes::graph(&[(1, 0, q(1))], [q(0), q(1)], [q(0), q(1)]);
/// let r = shapes::graph(&[(0, 1, h(1, 2))], [h(1, 4), h(3, 4)], [h(1, 4), h(3, 4)]);
/// let f = intersection_system(&p, &r);
/// // x = 5/16, y = 5/8: (u, v) = (5/16, 5/8) and (s, t) = (1/8, 3/4).
/// let on = [h(5, 16), h(5, 8), h(1, 8), h(3, 4)];
/// assert!(f.iter().all(|f| f.eval(&on) == q(0)));
/// let off = [h(5, 16), h(1, 2), h(1, 8), h(3, 4)];
/// assert!(f.iter().any(|f| f.eval(&off) != q(0)));
/// ```
pub fn intersection_system(first: &RationalPatch, second: &RationalPatch) -> [Poly; 3] {
    homogeneous_difference(&first.homogeneous(), &second.homogeneous())
}

/// `W_P H_Q − W_Q H_P` for homogeneous coordinates `hp` in the first two of four variables and
/// `hq` in the last two: the vector from `P` to `Q` times `W_P W_Q` (shared with the
/// bitangent system, whose chord it is).
pub(crate) fn homogeneous_difference(hp: &[Poly; 4], hq: &[Poly; 4]) -> [Poly; 3] {
    let (wp, wq) = (lift(&hp[3], 4, 0), lift(&hq[3], 4, 2));
    std::array::from_fn(|k| &(&wp * &lift(&hq[k], 4, 2)) - &(&wq * &lift(&hp[k], 4, 0)))
}

/// The curve where two patches meet, solved in Möbius-warped parameters
/// ([`crate::solver::space_curve::warp()`] with the factors [`PAIR_WARP`]: a curve through a
/// simple fraction of both patches, as on a plane of symmetry, would otherwise run along the
/// edges of the subdivision grid and be left unresolved). The warp is increasing in each
/// variable and fixes 0 and 1, so the curve's topology and its ends on the domain's sides are
/// those of the curve in the patches' own parameters.
#[derive(Clone, Debug)]
pub struct PairIntersection {
    /// The curve in the warped variables, with certified topology where it says so
    /// ([`SpaceCurve::is_certified`]).
    pub curve: SpaceCurve,
    /// The warp factor of each variable.
    pub lambda: [f64; 4],
    /// Per variable, the interval of the patch's parameter that the solver's `[0, 1]` stands
    /// for: `[0, 1]`, or reaching 1/64 (the first patch) or 3/128 (the second) past a side
    /// where the curve was solved beyond it (see [`pair_intersection`]). Exact in f64.
    pub span: [[f64; 2]; 4],
    /// The equations in the span's unit coordinates, before the warp.
    pub eqs: [Poly; 3],
}

impl PairIntersection {
    /// A box of the solver's variables mapped to the patches' parameters (rounded outward;
    /// beyond `[0, 1]` where the span extends past a side).
    pub fn unwarp_box(&self, b: &[[f64; 2]]) -> Vec<[f64; 2]> {
        b.iter()
            .enumerate()
            .map(|(k, x)| self.from_unit(k, unwarp_interval(*x, self.lambda[k])))
            .collect()
    }

    /// An interval of the span's unit coordinate `k` in the patch's parameter (outward).
    pub fn from_unit(&self, k: usize, y: [f64; 2]) -> [f64; 2] {
        let [lo, hi] = self.span[k];
        if lo == 0.0 && hi == 1.0 {
            return y;
        }
        let (l, w) = (Interval::point(lo), Interval::point(hi - lo));
        let a = l.add(&w.mul(&Interval::point(y[0])));
        let b = l.add(&w.mul(&Interval::point(y[1])));
        [a.lo(), b.hi()]
    }

    /// The unit coordinate of the patch parameter `x` of variable `k`, exactly.
    pub fn to_unit(&self, k: usize, x: &Rational) -> Rational {
        let [lo, hi] = self.span[k].map(|e| Rational::from_f64(e).unwrap_or_default());
        (x - lo.clone()) / (hi - lo)
    }

    /// A point of the warped variables mapped to the patches' parameters (f64, for drawing).
    pub fn unwarp_point(&self, x: &[f64]) -> [f64; 4] {
        std::array::from_fn(|k| {
            let [lo, hi] = self.span[k];
            lo + (hi - lo) * unwarp(x[k], self.lambda[k])
        })
    }

    /// Certified topology: every box decided and every branch complete.
    pub fn is_certified(&self) -> bool {
        self.curve.is_certified()
    }
}

/// The curve where two patches meet, in `(u, v, s, t)` (warped, see [`PairIntersection`]).
///
/// # Examples
/// ```
/// use limn::analysis::intersection::pair_intersection;
/// use limn::number::Rational;
/// use limn::solver::space_curve::SpaceCurveOptions;
/// use limn::testing::shapes;
/// let q = |n: i64| Rational::from(n);
/// let h = |a: i64, b: i64| Rational::from((a, b));
/// let p = shapes::graph(&[(1, 0, q(1))], [q(0), q(1)], [q(0), q(1)]);
/// let r = shapes::graph(&[(0, 1, h(1, 2))], [h(1, 4), h(3, 4)], [h(1, 4), h(3, 4)]);
/// let c = pair_intersection(&p, &r, &SpaceCurveOptions::default());
/// assert!(c.is_certified());
/// // One branch, a segment of the line y = 2x = 2z, from the side s = 0 of the second
/// // patch (x = 1/4) to its side t = 1 (y = 3/4).
/// assert_eq!(c.curve.branches.len(), 1);
/// let mut ends: Vec<usize> =
///     c.curve.crossings.iter().filter(|x| x.on_boundary).map(|x| x.axis).collect();
/// ends.sort();
/// assert_eq!(ends, vec![2, 3]);
/// ```
pub fn pair_intersection(
    first: &RationalPatch,
    second: &RationalPatch,
    opts: &SpaceCurveOptions,
) -> PairIntersection {
    let eqs = intersection_system(first, second);
    let unit = [[0.0, 1.0]; 4];
    let whole = solve_on(&eqs, unit, opts);
    // Boxes left undecided where the curve leaves through two sides at once (an edge of the
    // domain: both patches' seams meet on the curve, as on a plane of symmetry): solved again
    // on a domain reaching past those sides, where that point is inside, if both
    // weights stay positive there. The caller clips the arcs to the patches' squares.
    let mut span = unit;
    for u in &whole.curve.unresolved {
        let sides: Vec<(usize, bool)> = (0..4)
            .flat_map(|k| [(k, u.cell[k][0] <= 0.0), (k, u.cell[k][1] >= 1.0)])
            .enumerate()
            .filter(|(_, (_, on))| *on)
            .map(|(i, (k, _))| (k, i % 2 == 1))
            .collect();
        if sides.len() >= 2 {
            for (k, high) in sides {
                // Past the first patch's sides by 1/64, the second's by 3/128: a curve along
                // which the two patches' parameters agree (v = t) leaves the wider domain
                // through one side, not again through an edge.
                let d = if k < 2 { 1.0 / 64.0 } else { 3.0 / 128.0 };
                span[k][usize::from(high)] = if high { 1.0 + d } else { -d };
            }
        }
    }
    if span == unit {
        return whole;
    }
    let weights = [first, second].map(|p| p.homogeneous()[3].clone());
    let positive = (0..2).all(|side| {
        let w = (0..2).fold(weights[side].clone(), |w, a| {
            restrict_span(&w, a, span[2 * side + a])
        });
        w.coeffs()
            .iter()
            .all(|c| c.cmp0() == std::cmp::Ordering::Greater)
    });
    if !positive {
        return whole;
    }
    let wider = solve_on(&eqs, span, opts);
    if wider.curve.unresolved.len() < whole.curve.unresolved.len() {
        wider
    } else {
        whole
    }
}

/// `p` with variable `k` reparameterized from `[0, 1]` to `span` (exact: Bernstein
/// extrapolation past a side).
fn restrict_span(p: &Poly, k: usize, span: [f64; 2]) -> Poly {
    if span == [0.0, 1.0] {
        return p.clone();
    }
    let r = |x: f64| Rational::from_f64(x).unwrap_or_default();
    p.restrict_rational(k, &r(span[0]), &r(span[1]))
}

/// The curve of `eqs` solved with each variable's `[0, 1]` standing for `span`, warped.
fn solve_on(eqs: &[Poly; 3], span: [[f64; 2]; 4], opts: &SpaceCurveOptions) -> PairIntersection {
    let lambdas: Vec<Rational> = PAIR_WARP.iter().map(|&l| Rational::from(l)).collect();
    let on_span: [Poly; 3] = eqs
        .clone()
        .map(|e| (0..4).fold(e, |e, k| restrict_span(&e, k, span[k])));
    let warped: Vec<Poly> = on_span.iter().map(|p| warp(p, &lambdas)).collect();
    PairIntersection {
        curve: solve_space_curve(&warped, opts),
        lambda: PAIR_WARP.map(|(a, b)| a as f64 / b as f64),
        span,
        eqs: on_span,
    }
}

#[cfg(test)]
mod tests;
