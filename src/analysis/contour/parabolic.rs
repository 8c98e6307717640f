//! Parabolic curves (Gaussian curvature K = 0) of rational Bézier models, with certified
//! topology: one exact polynomial per patch, solved by the same model-level curve machinery
//! as silhouettes ([`model_curves`]).
//!
//! With homogeneous coordinates `Q = (P, W)`, `P = [wx, wy, wz]`, the second fundamental form
//! against the unnormalized normal is, up to one common factor,
//! `L' = P_uu · Ñ − W_uu D`, `M' = P_uv · Ñ − W_uv D`, `N' = P_vv · Ñ − W_vv D`, with
//! `Ñ = W (P_u × P_v) + W_u (P_v × P) + W_v (P × P_u)` and `D = det(P, P_u, P_v)`; and
//! `k = L'N' − M'² = W⁸ (LN − M²)` for `L = S_uu · (S_u × S_v)` etc., so k has the sign of the
//! Gaussian curvature wherever the patch is regular (`proofs/parabolic.md`).

use crate::analysis::chords::plane_curve::{mean_value_range, range_enclosing};
use crate::analysis::chords::space_curve::TangentRanges;
use crate::analysis::contour::curves::Silhouette;
use crate::analysis::contour::family::{model_curves, ContourOptions, CurveRules, Faces};
use crate::analysis::frame::Frame;
use crate::bernstein::Bernstein;
use crate::error::Error;
use crate::model::{Model, WeldTolerance};
use crate::number::{Interval, Number, Precision, Rational};
use crate::solver::CurveOptions;
use crate::surface::normal::cross;
use crate::surface::RationalPatch;
use rayon::prelude::*;

use crate::bernstein::Poly;

fn dot(a: &[Poly; 3], b: &[Poly; 3]) -> Poly {
    &(&(&a[0] * &b[0]) + &(&a[1] * &b[1])) + &(&a[2] * &b[2])
}

/// The polynomials scaled by one positive integer so that every coefficient is an integer.
fn integral<const K: usize>(ps: [Poly; K]) -> [Poly; K] {
    let mut l = rug::Integer::from(1);
    for p in &ps {
        for c in p.coeffs() {
            l.lcm_mut(c.denom());
        }
    }
    let l = Rational::from(l);
    ps.map(|p| p.scale(&l))
}

/// The parabolic function `k = L'N' − M'²` of a patch (exact, at its lowest exact degrees):
/// positive where the patch is elliptic, negative where hyperbolic, zero on parabolic points
/// (and where the patch is singular).
///
/// # Examples
/// ```
/// use limn::analysis::contour::parabolic::parabolic_function;
/// use limn::number::Rational;
/// use limn::testing::shapes;
/// // A sphere is elliptic everywhere inside each patch.
/// let k = parabolic_function(&shapes::sphere(&Rational::from(1))[0]);
/// assert!(k.eval(&[Rational::from((1, 2)), Rational::from((1, 3))]) > 0);
/// ```
pub fn parabolic_function(patch: &RationalPatch) -> Poly {
    let [l, m, nn] = second_fundamental_form(patch);
    (&(&l * &nn) - &(&m * &m)).reduce_degree_exact()
}

/// The second fundamental form `(L', M', N')` of the module documentation: one common nonzero
/// factor (`±W⁴` times a positive constant) times `(L, M, N)` taken with `S_u × S_v`.
pub fn second_fundamental_form(patch: &RationalPatch) -> [Poly; 3] {
    // Homogeneous coordinates scaled by the lcm of their denominators: integers, so that the
    // products below stay cheap (k only gains a positive constant factor).
    let [px, py, pz, w] = integral(patch.homogeneous());
    let p = [px, py, pz];
    let d = |c: &[Poly; 3], axis: usize| c.clone().map(|x| x.deriv(axis));
    let (pu, pv) = (d(&p, 0), d(&p, 1));
    let (puu, puv, pvv) = (d(&pu, 0), d(&pu, 1), d(&pv, 1));
    let n: [Poly; 3] = if patch.is_polynomial() {
        // W is a constant: Ñ = W (P_u × P_v), and the constant is dropped.
        cross(&pu, &pv).map(|c| c.reduce_degree_exact())
    } else {
        let (wu, wv) = (w.deriv(0), w.deriv(1));
        let a = cross(&pu, &pv);
        let b = cross(&pv, &p);
        let c = cross(&p, &pu);
        [0, 1, 2]
            .map(|k| (&(&(&w * &a[k]) + &(&wu * &b[k])) + &(&wv * &c[k])).reduce_degree_exact())
    };
    let second = |x: &[Poly; 3]| dot(x, &n);
    let (mut l, mut m, mut nn) = (second(&puu), second(&puv), second(&pvv));
    if !patch.is_polynomial() {
        // D = det(P, P_u, P_v) and the weight's second derivatives.
        let det = dot(&p, &cross(&pu, &pv));
        let (wu, wv) = (w.deriv(0), w.deriv(1));
        let (wuu, wuv, wvv) = (wu.deriv(0), wu.deriv(1), wv.deriv(1));
        l = &l - &(&wuu * &det);
        m = &m - &(&wuv * &det);
        nn = &nn - &(&wvv * &det);
    }
    [l, m, nn]
}

/// Interval polynomials for enclosures of the asymptotic lines at parabolic points over boxes
/// (`proofs/events.md`, "Enclosures"): `a T_u + b T_v` with `(a, b) = (−M', L')` and with
/// `(a, b) = (N', −M')`, each a multiple of an asymptotic direction wherever the form has
/// rank 1 and that pair is not zero. The ranges of `L', M', N'` over the box are taken first,
/// then combined with the tangents' coefficients ([`TangentRanges::combination`]).
pub(crate) struct AsymptoticRanges {
    form: [Bernstein<Interval>; 3],
    /// Their partial derivatives, for the mean value form.
    form_d: [[Bernstein<Interval>; 2]; 3],
    tangents: TangentRanges,
}

impl AsymptoticRanges {
    pub(crate) fn new(patch: &RationalPatch) -> AsymptoticRanges {
        let form: [Bernstein<Interval>; 3] =
            second_fundamental_form(patch).map(|p| p.convert(Precision::F64));
        let form_d = form.each_ref().map(|p| [p.deriv(0), p.deriv(1)]);
        AsymptoticRanges {
            form,
            form_d,
            tangents: TangentRanges::new(patch),
        }
    }

    /// The smallest of `error` over the two rows' direction enclosures on the box `[lo, hi]`,
    /// rows tried in turn until one gives a value: the row of the larger of `|L'|`, `|N'|`
    /// first (as for a single point: it is zero only where the form is). The ranges of
    /// `L', M', N'` come from the mean value form; where neither row gives a value with it,
    /// they are intersected with the restriction's hull (tighter on large boxes; both enclose
    /// the range, so their intersection does).
    pub(crate) fn line_error(
        &self,
        lo: [f64; 2],
        hi: [f64; 2],
        error: &dyn Fn(&[Interval; 3]) -> Option<f64>,
    ) -> Option<f64> {
        if !(0..2).all(|k| 0.0 <= lo[k] && lo[k] <= hi[k] && hi[k] <= 1.0) {
            return None;
        }
        for refined in [false, true] {
            let r: Vec<Interval> = (0..3)
                .map(|k| {
                    let mv = mean_value_range(&self.form[k], &self.form_d[k], lo, hi);
                    let hull = if refined {
                        range_enclosing(&self.form[k], lo, hi)
                    } else {
                        None
                    };
                    match hull {
                        Some(h) => {
                            Interval::try_new(mv.lo().max(h.lo()), mv.hi().min(h.hi())).unwrap_or(h)
                        }
                        None => mv,
                    }
                })
                .collect();
            let (l, m, n) = (r[0], r[1], r[2]);
            let mid = |x: Interval| (0.5 * (x.lo() + x.hi())).abs();
            let mut rows = [(m.neg(), l), (n, m.neg())];
            if mid(n) > mid(l) {
                rows.swap(0, 1);
            }
            for (a, b) in rows {
                if let Some(e) = self
                    .tangents
                    .combination(lo, hi, a, b)
                    .and_then(|d| error(&d))
                {
                    return Some(e);
                }
            }
        }
        None
    }
}

/// The parabolic curves of a model, certified as silhouettes are (topology, and accuracy with
/// `opts.tol`). A patch on which k vanishes identically (a plane, a cylinder, a cone) is
/// reported in `degenerate` as "parabolic everywhere".
///
/// # Errors
/// None today (the curves do not depend on a view); the `Result` is the shape every entry
/// point has.
///
/// # Examples
/// ```
/// use limn::{parabolic, ContourOptions, Model};
/// use limn::number::Rational;
/// use limn::testing::shapes;
/// let sphere = Model::from_patches(limn::model::Format::Json, shapes::sphere(&Rational::from(1)));
/// let s = parabolic(&sphere, &ContourOptions::default())?;
/// assert!(s.curves.is_empty() && s.unresolved.is_empty());
/// # Ok::<(), limn::Error>(())
/// ```
pub fn parabolic(model: &Model, opts: &ContourOptions) -> Result<Silhouette, Error> {
    // In the model's own frame (`proofs/model-frame.md`).
    let frame = Frame::of(model);
    let local = frame.model(model);
    let s = parabolic_curves(
        &local,
        &opts.curve,
        opts.weld_for(&local),
        opts.tol,
        Faces::Trimmed,
    );
    Ok(s.in_model_frame(&frame, opts.tol))
}

/// [`parabolic`] with its parts given separately (the analyses built on it).
pub(crate) fn parabolic_curves(
    model: &Model,
    opts: &CurveOptions,
    weld: WeldTolerance,
    tol: Option<f64>,
    faces: Faces,
) -> Silhouette {
    let ks: Vec<Poly> = model
        .patches
        .par_iter()
        .map(|p| parabolic_function(&p.surface))
        .collect();
    let rules = CurveRules {
        parallel_normal_joins: false,
        whole_patch: "parabolic everywhere",
        whole_side: "parabolic side",
        whole_line: "parabolic line",
        spurious_collapse: None,
    };
    model_curves(model, ks, &rules, opts, weld, tol, faces)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mean_value_form_encloses_the_range_on_a_box() {
        // L' of a torus patch over a small box and a large one: every sampled value is inside.
        let patch = &crate::testing::shapes::torus(&Rational::from(3), &Rational::from(1))[0];
        let f: Bernstein<Interval> = second_fundamental_form(patch)[0].convert(Precision::F64);
        let d = [f.deriv(0), f.deriv(1)];
        let exact = &second_fundamental_form(patch)[0];
        for (lo, hi) in [([0.30, 0.60], [0.31, 0.62]), ([0.0, 0.0], [1.0, 1.0])] {
            let r = mean_value_range(&f, &d, lo, hi);
            for i in 0..=10 {
                for j in 0..=10 {
                    let x = lo[0] + (hi[0] - lo[0]) * i as f64 / 10.0;
                    let y = lo[1] + (hi[1] - lo[1]) * j as f64 / 10.0;
                    let at = [x, y].map(|v| Rational::from_f64(v).unwrap());
                    let v = exact.eval(&at);
                    assert!(r.contains_rational(&v), "{r:?} misses {v} at ({x}, {y})");
                }
            }
        }
    }
}
