//! The graph test of a box: an `(n−1)×(n−1)` minor of the interval Jacobian that is a regular
//! interval matrix (`‖I − C J‖∞ < 1`), so every slice across the box meets the curve at most
//! once (`proofs/space-curves.md`).

use crate::bernstein::Bernstein;
use crate::number::{Interval, Number};
use crate::solver::system::inverse;

/// The hull of a polynomial's coefficients: an enclosure of its range on its box.
pub(crate) fn excludes(p: &Bernstein<Interval>) -> bool {
    let c = p.coeffs();
    c.iter().all(|x| x.lo() > 0.0) || c.iter().all(|x| x.hi() < 0.0)
}
pub(crate) fn magnitude(x: &Interval) -> f64 {
    x.lo().abs().max(x.hi().abs())
}
/// The largest coefficient width relative to the largest magnitude: how much the f64
/// enclosures carried down the tree have spread.
pub(crate) fn slack(polys: &[Bernstein<Interval>]) -> f64 {
    polys
        .iter()
        .map(|p| {
            let big = p.coeffs().iter().map(magnitude).fold(0.0, f64::max);
            let wide = p.coeffs().iter().map(|c| c.width()).fold(0.0, f64::max);
            if big > 0.0 {
                wide / big
            } else {
                f64::INFINITY
            }
        })
        .fold(0.0, f64::max)
}
/// `C` and an upper bound `β < 1` of `‖I − C M‖∞` for the interval matrix `M`, which proves
/// every real matrix in `M` invertible (`‖(C A)⁻¹‖∞ ≤ 1 / (1 − β)`); `None` if not proven.
pub(crate) fn regular(m: &[Vec<Interval>]) -> Option<(Vec<Vec<f64>>, f64)> {
    let k = m.len();
    let mid: Vec<Vec<f64>> = m
        .iter()
        .map(|r| r.iter().map(|x| 0.5 * (x.lo() + x.hi())).collect())
        .collect();
    let c = inverse(&mid)?;
    let mut beta = Interval::point(0.0);
    for (r, cr) in c.iter().enumerate() {
        let mut row = Interval::point(0.0);
        for col in 0..k {
            let mut e = Interval::point(if r == col { 1.0 } else { 0.0 });
            for (crl, ml) in cr.iter().zip(m) {
                e = e.sub(&Interval::point(*crl).mul(&ml[col]));
            }
            row = row.add(&Interval::point(magnitude(&e)));
        }
        if row.hi() > beta.hi() {
            beta = row;
        }
    }
    (beta.hi() < 1.0).then_some((c, beta.hi()))
}
/// The determinant of a small matrix (for choosing the best-conditioned minor only).
pub(crate) fn det(m: &[Vec<f64>]) -> f64 {
    let n = m.len();
    let mut a = m.to_vec();
    let mut d = 1.0;
    for col in 0..n {
        let Some(piv) = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
        else {
            return 0.0;
        };
        if a[piv][col] == 0.0 {
            return 0.0;
        }
        if piv != col {
            a.swap(piv, col);
            d = -d;
        }
        d *= a[col][col];
        let (top, rest) = a.split_at_mut(col + 1);
        let pivot = &top[col];
        for row in rest {
            let f = row[col] / pivot[col];
            for (x, p) in row[col..].iter_mut().zip(&pivot[col..]) {
                *x -= f * p;
            }
        }
    }
    d
}
/// An upper bound of `x / (1 − β)` for `x ≥ 0`, `β < 1`.
pub(crate) fn over_one_minus(x: f64, beta: f64) -> f64 {
    let den = Interval::point(1.0).sub(&Interval::point(beta));
    den.recip()
        .map_or(f64::INFINITY, |r| Interval::point(x).mul(&r).hi())
}
/// The upper bound of `‖C v‖∞` for an interval vector `v`.
pub(crate) fn times_norm(c: &[Vec<f64>], v: &[Interval]) -> f64 {
    c.iter()
        .map(|row| {
            let mut s = Interval::point(0.0);
            for (a, b) in row.iter().zip(v) {
                s = s.add(&Interval::point(*a).mul(b));
            }
            magnitude(&s)
        })
        .fold(0.0, f64::max)
}
