//! f64 evaluation of a patch, for drawing and for the float filters in front of certified
//! tests: points with an a priori rounding bound ([`DrawPatch`], `proofs/chord-accuracy.md`,
//! "The drawn points"), and points with their first and second partials ([`Evaluator`]).
//! Nothing here is certified by itself; callers that need a proven quantity use the bound.

use crate::bernstein::Bernstein;
use crate::number::Precision;
use crate::surface::RationalPatch;

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

/// f64 evaluation of a patch and its first and second partials.
pub struct Evaluator {
    /// X, Y, Z, W and their u, v, uu, uv, vv derivatives.
    h: Vec<[Bernstein<f64>; 6]>,
}

impl Evaluator {
    /// The patch's homogeneous polynomials and their derivatives, converted to f64 once.
    pub fn new(patch: &RationalPatch) -> Evaluator {
        Evaluator {
            h: patch
                .homogeneous()
                .iter()
                .map(|p| {
                    let (pu, pv) = (p.deriv(0), p.deriv(1));
                    [p, &pu, &pv, &pu.deriv(0), &pu.deriv(1), &pv.deriv(1)]
                        .map(|q| q.convert(Precision::F64))
                })
                .collect(),
        }
    }

    /// S, S_u, S_v, S_uu, S_uv, S_vv at (u, v).
    pub fn eval2(&self, u: f64, v: f64) -> [[f64; 3]; 6] {
        let at: Vec<[f64; 6]> = self
            .h
            .iter()
            .map(|d| std::array::from_fn(|i| d[i].eval(&[u, v])))
            .collect();
        let w = at[3];
        let mut out = [[0.0; 3]; 6];
        for k in 0..3 {
            let x = at[k];
            // S = X / W: S_a = (X_a − S W_a) / W, S_ab = (X_ab − S_a W_b − S_b W_a − S W_ab) / W.
            let s = x[0] / w[0];
            let su = (x[1] - s * w[1]) / w[0];
            let sv = (x[2] - s * w[2]) / w[0];
            out[0][k] = s;
            out[1][k] = su;
            out[2][k] = sv;
            out[3][k] = (x[3] - 2.0 * su * w[1] - s * w[3]) / w[0];
            out[4][k] = (x[4] - su * w[2] - sv * w[1] - s * w[4]) / w[0];
            out[5][k] = (x[5] - 2.0 * sv * w[2] - s * w[5]) / w[0];
        }
        out
    }

    /// S, S_u, S_v at (u, v).
    pub fn eval(&self, u: f64, v: f64) -> [[f64; 3]; 3] {
        let at: Vec<[f64; 3]> = self
            .h
            .iter()
            .map(|d| [d[0].eval(&[u, v]), d[1].eval(&[u, v]), d[2].eval(&[u, v])])
            .collect();
        let w = at[3];
        let mut out = [[0.0; 3]; 3];
        for k in 0..3 {
            let s = at[k][0] / w[0];
            out[0][k] = s;
            out[1][k] = (at[k][1] - s * w[1]) / w[0];
            out[2][k] = (at[k][2] - s * w[2]) / w[0];
        }
        out
    }
}
