//! Drawing the curves: the solver's options refined for a tolerance, and the f64 points of an
//! arc between its certified crossings (the patch's f64 evaluation is [`crate::surface::float_eval`]).

use crate::bernstein::Bernstein;
use crate::geometry::Rect;
use crate::model::Model;
use crate::solver::{CurveOptions, CurveTopology};

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
    let m = match a.kind.monotone_axis() {
        Some(m) => m,
        // Along an edge where g vanishes: every point of the segment is on the curve.
        None => {
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
    let Rect { lo, hi } = a.cell.to_f64();
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
