//! The Möbius warp of the unit box (`proofs/space-curves.md`): a grid that is fine near the
//! box's sides without more boxes, and its inverse on points, intervals and exact parameters.

use crate::bernstein::Bernstein;
use crate::number::{Interval, Number, Rational};

/// The Möbius factors of [`warp`] for a curve in the parameters `(u, v, s, t)` of two patches
/// (bitangents, intersection curves). A patch with itself takes the first two for both points
/// (the same grid for both, so that a pair and its mirror image fall on the same grid planes);
/// two patches take all four, so that a curve with `v = t` (two patches parameterized alike)
/// or through a simple fraction of both (a plane of symmetry) does not run along the grid's
/// edges.
pub const PAIR_WARP: [(i64, i64); 4] = [(33, 32), (29, 32), (31, 32), (35, 32)];

/// The polynomial times the lcm of its coefficients' denominators (a positive integer):
/// the same zeros, cheaper exact arithmetic.
pub(crate) fn integral(p: &Bernstein<Rational>) -> Bernstein<Rational> {
    let mut l = rug::Integer::from(1);
    for c in p.coeffs() {
        l.lcm_mut(c.denom());
    }
    p.scale(&Rational::from(l))
}
/// The polynomial whose zeros on `[0, 1]ⁿ` are those of `p` moved by the Möbius map
/// `u = λ t / (1 + (λ − 1) t)` in each variable (λ per variable, positive): the coefficient of
/// index `(i₀, …)` is multiplied by `Π λ_k^{i_k}`. The map fixes 0 and 1 and is increasing, so
/// the curve in `t` has the same topology, and its ends stay on the same sides. With λ ≠ 1 the
/// dyadic grid of the subdivision in `t` falls on points of `u` that are not simple fractions,
/// which curves with simple rational coefficients rarely pass through (a curve through an
/// edge of the grid leaves its boxes unresolved: `proofs/space-curves.md`).
pub fn warp(p: &Bernstein<Rational>, lambda: &[Rational]) -> Bernstein<Rational> {
    let mut out = p.clone();
    for flat in 0..p.coeffs().len() {
        let idx = p.multi_index(flat);
        let mut f = Rational::from(1);
        for (k, l) in lambda.iter().enumerate() {
            for _ in 0..idx[k] {
                f *= l;
            }
        }
        out.coeffs_mut()[flat] *= f;
    }
    out
}
/// The point `u` of the Möbius map of [`warp`] at a rational `t`, exactly:
/// `u = λ t / (1 + (λ − 1) t)`.
pub fn unwarp_exact(t: &Rational, lambda: &Rational) -> Rational {
    let num = Rational::from(lambda * t);
    let den = Rational::from(1) + Rational::from(lambda - 1u32) * t;
    num / den
}
/// The point `u` of the Möbius map of [`warp`] at `t` (f64, for drawing).
pub fn unwarp(t: f64, lambda: f64) -> f64 {
    lambda * t / (1.0 + (lambda - 1.0) * t)
}
/// An interval of `t` mapped to `u` by the map of [`warp`], rounded outward (the map is
/// increasing).
pub fn unwarp_interval(t: [f64; 2], lambda: f64) -> [f64; 2] {
    let map = |x: f64| {
        let l = Interval::point(lambda);
        let x = Interval::point(x);
        let den = Interval::point(1.0).add(&l.sub(&Interval::point(1.0)).mul(&x));
        den.recip().map(|r| l.mul(&x).mul(&r))
    };
    match (map(t[0]), map(t[1])) {
        (Some(a), Some(b)) => [a.lo().max(0.0), b.hi().min(1.0)],
        _ => [0.0, 1.0],
    }
}
