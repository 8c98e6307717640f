//! Drawing the curves: the solver's options refined for a tolerance, the f64 points of an
//! arc between its certified crossings, and the f64 evaluation of a patch with its rounding
//! bound.

use crate::bernstein::Bernstein;
use crate::model::Model;
use crate::number::Precision;
use crate::solver::{CurveOptions, CurveTopology};
use crate::surface::RationalPatch;

/// Points added inside each arc for drawing.
pub(crate) const DENSIFY_STEPS: usize = 8;
/// The budgets with crossings located finely enough for a tolerance `tol` (model units): their
/// location boxes then take a small part of it (the end pieces of the accuracy bound,
/// `proofs/chord-accuracy.md`).
pub(crate) fn refined_for(opts: &CurveOptions, model: &Model, tol: Option<f64>) -> CurveOptions {
    let mut opts = opts.clone();
    if let Some(t) = tol {
        let rel = t / model.diagonal().max(f64::MIN_POSITIVE);
        opts.refine_width = opts.refine_width.min((rel * 1e-3).max(1e-15));
    }
    opts
}
/// The points of an arc for drawing: its two crossings (certified locations) and
/// `steps − 1` points between them. Each is the zero of g on a line across the arc's box along
/// which g is strictly monotone (so the line meets this arc exactly once), found in f64 by the
/// Illinois method: drawing points, not certified ones.
pub(crate) fn densify(
    g: &Bernstein<f64>,
    t: &CurveTopology,
    a: &crate::solver::plane_curve::Arc,
    steps: usize,
) -> Vec<[f64; 2]> {
    let (p0, p1) = (t.point(&a.from), t.point(&a.to));
    let m = match a.reason {
        "graph over v" => 0,
        "graph over u" => 1,
        // Along an edge where g vanishes: every point of the segment is on the curve.
        _ => {
            let n = 4 * steps;
            return (0..=n)
                .map(|i| {
                    let s = i as f64 / n as f64;
                    [p0[0] + (p1[0] - p0[0]) * s, p0[1] + (p1[1] - p0[1]) * s]
                })
                .collect();
        }
    };
    let o = 1 - m;
    let [lo, hi] = a.cell.to_f64();
    let mut pts = vec![p0];
    for i in 1..steps {
        let s = p0[o] + (p1[o] - p0[o]) * i as f64 / steps as f64;
        if let Some(x) = zero_across(g, m, s, lo[m], hi[m]) {
            let mut q = [0.0; 2];
            q[m] = x;
            q[o] = s;
            pts.push(q);
        }
    }
    pts.push(p1);
    pts
}
/// The zero of g on the line where variable `1 − m` equals `s`, with variable `m` in
/// `[lo, hi]` where g changes sign, found in f64 by the Illinois method (a drawing point, not
/// a certified one); `None` without a sign change.
pub(crate) fn zero_across(g: &Bernstein<f64>, m: usize, s: f64, lo: f64, hi: f64) -> Option<f64> {
    let f = |x: f64| {
        let mut pt = [0.0; 2];
        pt[m] = x;
        pt[1 - m] = s;
        g.eval(&pt)
    };
    let (mut x0, mut x1) = (lo, hi);
    let (mut f0, mut f1) = (f(x0), f(x1));
    if f0 * f1 >= 0.0 || f0.is_nan() || f1.is_nan() {
        return None;
    }
    let mut side = 0;
    for _ in 0..60 {
        let x = (x0 * f1 - x1 * f0) / (f1 - f0);
        let fx = f(x);
        if fx == 0.0 || (x1 - x0).abs() < 1e-14 {
            x0 = x;
            x1 = x;
            break;
        }
        if fx * f1 < 0.0 {
            (x0, f0) = (x1, f1);
            (x1, f1) = (x, fx);
            side = 0;
        } else {
            (x1, f1) = (x, fx);
            if side == 1 {
                f0 *= 0.5;
            }
            side = 1;
        }
    }
    Some(0.5 * (x0 + x1))
}
/// A patch in f64 for drawing: its homogeneous polynomials converted once.
pub struct DrawPatch {
    h: [Bernstein<f64>; 4],
    /// A bound on the distance between [`DrawPatch::eval`]'s point and the exact one, on the
    /// unit square.
    rounding: Option<f64>,
}
impl DrawPatch {
    /// Converts a patch (once).
    pub fn new(patch: &RationalPatch) -> DrawPatch {
        let h = patch.homogeneous().map(|p| p.convert(Precision::F64));
        DrawPatch {
            rounding: rounding_bound(&h),
            h,
        }
    }

    /// A bound, for every (u, v) of the unit square, on the distance between the f64 point
    /// [`DrawPatch::eval`] computes and the exact point `S(u, v)`
    /// (`proofs/chord-accuracy.md`, "The drawn points"); `None` if a weight is not positive
    /// (or the bound is not small beside the least weight).
    pub fn rounding(&self) -> Option<f64> {
        self.rounding
    }

    /// The point S(u, v) in f64, for drawing: on the unit square within
    /// [`DrawPatch::rounding`] of the exact point.
    pub fn eval(&self, u: f64, v: f64) -> [f64; 3] {
        let x = [u, v];
        let c: Vec<f64> = self.h.iter().map(|p| p.eval(&x)).collect();
        [c[0] / c[3], c[1] / c[3], c[2] / c[3]]
    }
}
/// The a priori bound of [`DrawPatch::rounding`] (`proofs/chord-accuracy.md`, "The drawn
/// points"): each homogeneous coordinate evaluated in f64 (fibre by fibre, the coefficients
/// rounded from the exact ones) is within `γ_K · max|c|` of the exact value, with
/// `K = 3(n_u + n_v) + 4` and `γ_K = K u / (1 − K u)`; the quotient by the weight (at least its
/// least coefficient, less its own error) adds the error of the weight times `|S|` (at most the
/// largest `|P_i / W_i|`, the convex-hull property) and one rounding.
pub(crate) fn rounding_bound(h: &[Bernstein<f64>; 4]) -> Option<f64> {
    let u = f64::EPSILON / 2.0;
    let d = h[3].degrees();
    if h.iter().any(|p| p.degrees() != d) || d.len() != 2 {
        return None;
    }
    let k = (3 * (d[0] + d[1]) + 4) as f64;
    let gamma = k * u / (1.0 - k * u);
    let max_abs = |p: &Bernstein<f64>| p.coeffs().iter().fold(0.0f64, |a, c| a.max(c.abs()));
    // The exact coefficients are within one rounding of these.
    let margin = 1.0 + 4.0 * u;
    let w = h[3].coeffs();
    let w_min = w.iter().copied().fold(f64::INFINITY, f64::min) / margin;
    if !(w_min > 0.0 && w_min.is_finite()) {
        return None;
    }
    let e_w = gamma * max_abs(&h[3]) * margin;
    if e_w >= 0.5 * w_min {
        return None;
    }
    let mut sum = 0.0;
    for p in &h[..3] {
        let s_max = p
            .coeffs()
            .iter()
            .zip(w)
            .fold(0.0f64, |a, (c, wi)| a.max(c.abs() / wi))
            * margin
            * margin;
        let e_p = gamma * max_abs(p) * margin;
        let quotient = (e_p + s_max * e_w) / (w_min - e_w);
        let r = (quotient + 2.0 * u * (s_max + quotient)) * margin;
        sum += r * r;
    }
    let bound = sum.sqrt() * margin;
    bound.is_finite().then_some(bound)
}
/// The point S(u, v) in f64 (for drawing; not a certified quantity). For many points of one
/// patch, build a [`DrawPatch`] once instead.
pub fn eval_f64(patch: &RationalPatch, u: f64, v: f64) -> [f64; 3] {
    DrawPatch::new(patch).eval(u, v)
}
