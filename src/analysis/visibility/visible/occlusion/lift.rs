//! Lifting image points onto a patch: Newton's method in f64, and the interval residual and
//! Jacobian that prove a tube's preimages unique in a box.

use crate::analysis::chords::plane_curve::{derivs, SurfaceBounds};
use crate::analysis::visibility::scene::Scene;
use crate::analysis::visibility::sheets::range_on;
use crate::bernstein::Bernstein;
use crate::geometry::Rect;
use crate::number::{Interval, Number, Precision};
use crate::solver::system::inverse;
use crate::surface::RationalPatch;

pub(super) type IPoly = Bernstein<Interval>;
pub(super) type FPoly = Bernstein<f64>;

/// The image of a chord's tube: the image segment from `a` to `a + d` (the image of the drawn
/// chord: a projection maps segments to segments) grown by `r` per image coordinate (the drawn
/// chord's error `e` times a bound on the image map's gradient), and its bounding box.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tube {
    pub(super) a: [Interval; 2],
    pub(super) d: [Interval; 2],
    pub(super) r: [f64; 2],
    pub(super) hull: [Interval; 2],
}

/// One patch's polynomials for lifting image points onto it.
pub(crate) struct LiftPatch {
    /// Image numerators and denominator `x, y, q` (outward intervals) with their first and
    /// second partials: `[f, f_u, f_v, f_uu, f_uv, f_vv]`.
    pub(super) jets: [[IPoly; 6]; 3],
    /// Bounds on the derivatives of the patch's points.
    pub(super) surface: SurfaceBounds,
    /// The same in f64, for Newton's method.
    pub(super) f: [FPoly; 3],
    pub(super) df: [[FPoly; 2]; 3],
    /// The homogeneous space coordinates `X, Y, Z, W`.
    pub(super) space: [IPoly; 4],
}

impl LiftPatch {
    pub(crate) fn new(scene: &Scene, patch: &RationalPatch, j: usize) -> LiftPatch {
        let im = &scene.images[j];
        let exact = [&im.x, &im.y, &im.q];
        let ders = exact.map(|p| [p.deriv(0), p.deriv(1)]);
        LiftPatch {
            jets: exact.map(derivs),
            surface: SurfaceBounds::new(patch),
            f: exact.map(|p| p.convert(Precision::F64)),
            df: ders.map(|d| d.map(|p| p.convert::<f64>(Precision::F64))),
            space: patch.homogeneous().map(|p| p.convert(Precision::F64)),
        }
    }

    /// The point of the patch (extended beyond its square) with image `y`, by Newton's
    /// method from `w`: `None` if it does not converge. Near a fold of the image map (the
    /// patch's own silhouette) the image point may lie outside the image by rounding alone,
    /// and Newton's steps then oscillate: there the damped iteration of [`Self::damped`]
    /// settles on the point whose image is nearest. Either is an estimate: every use of a
    /// lifted point is proven afterwards or reported as not bounded.
    pub(crate) fn newton(&self, y: [f64; 2], w0: [f64; 2]) -> Option<[f64; 2]> {
        let mut w = w0;
        let mut last = f64::INFINITY;
        for _ in 0..50 {
            let (_, step) = self.newton_step(y, w)?;
            w = [w[0] - step[0], w[1] - step[1]];
            if !(w[0].is_finite() && w[1].is_finite()) || w[0].abs() > 4.0 || w[1].abs() > 4.0 {
                return None;
            }
            last = step[0].abs().max(step[1].abs());
            if last <= 1e-15 * (1.0 + w[0].abs().max(w[1].abs())) {
                return Some(w);
            }
        }
        // Steps at the level of rounding: converged as far as f64 allows.
        if last < 1e-11 {
            return Some(w);
        }
        self.damped(y, w0)
    }

    /// The residual `G(w; y)` relative to the size of its terms, and Newton's step; `None`
    /// where the Jacobian is singular.
    fn newton_step(&self, y: [f64; 2], w: [f64; 2]) -> Option<(f64, [f64; 2])> {
        let ev = |p: &FPoly| p.eval(&w);
        let q = ev(&self.f[2]);
        let (x0, x1) = (ev(&self.f[0]), ev(&self.f[1]));
        let r = [x0 - y[0] * q, x1 - y[1] * q];
        let size = x0.abs() + x1.abs() + (y[0].abs() + y[1].abs() + 1.0) * q.abs();
        let jac: [[f64; 2]; 2] = std::array::from_fn(|k| {
            std::array::from_fn(|a| ev(&self.df[k][a]) - y[k] * ev(&self.df[2][a]))
        });
        let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
        if det == 0.0 || !det.is_finite() || size == 0.0 {
            return None;
        }
        let step = [
            (jac[1][1] * r[0] - jac[0][1] * r[1]) / det,
            (jac[0][0] * r[1] - jac[1][0] * r[0]) / det,
        ];
        Some((r[0].abs().max(r[1].abs()) / size, step))
    }

    /// Newton's steps from `w`, each halved until the residual decreases: the point with the
    /// least residual found, if that residual is at the level of rounding (1e-12 of its
    /// terms).
    fn damped(&self, y: [f64; 2], mut w: [f64; 2]) -> Option<[f64; 2]> {
        let (mut res, mut step) = self.newton_step(y, w)?;
        for _ in 0..200 {
            let mut t = 1.0;
            let mut next = None;
            while t > 1e-6 {
                let v = [w[0] - t * step[0], w[1] - t * step[1]];
                if v[0].abs() <= 4.0 && v[1].abs() <= 4.0 {
                    if let Some((r, s)) = self.newton_step(y, v) {
                        if r < res {
                            next = Some((v, r, s));
                            break;
                        }
                    }
                }
                t *= 0.5;
            }
            let Some((v, r, s)) = next else {
                break;
            };
            (w, res, step) = (v, r, s);
        }
        (res <= 1e-12).then_some(w)
    }

    /// Krawczyk's test with the image point as a parameter: whether every image point in
    /// `y` has exactly one preimage in the parameter box `b` (which may reach past the
    /// square: the polynomials are defined everywhere). `proofs/visible-regions.md`, claim 4.
    pub(crate) fn unique_preimages(&self, t: &Tube, b: &Rect) -> bool {
        let y = t.hull;
        let (lo, hi) = (b.lo, b.hi);
        let m = b.center();
        let yc = [0.5 * (y[0].lo() + y[0].hi()), 0.5 * (y[1].lo() + y[1].hi())];
        // C: the inverse of the point Jacobian at the centre (any matrix keeps the test sound).
        let jm: Vec<Vec<f64>> = (0..2)
            .map(|k| {
                (0..2)
                    .map(|a| self.df[k][a].eval(&m) - yc[k] * self.df[2][a].eval(&m))
                    .collect()
            })
            .collect();
        let Some(c) = inverse(&jm) else {
            return false;
        };
        // C G(m; y) for y = a + μ d + δ (μ ∈ [0, 1], |δ_k| ≤ r_k), term by term, so that a
        // chord that is diagonal in the image does not count as its whole bounding box.
        let g_a = self.residual(m, t.a);
        let q_m = self.jets[2][0].eval(&m.map(Interval::point));
        let jw = self.jacobian_on(y, lo, hi);
        let dw = [0, 1].map(|a| Interval::new(lo[a] - m[a], hi[a] - m[a]));
        (0..2).all(|r| {
            let ci = [Interval::point(c[r][0]), Interval::point(c[r][1])];
            let along = q_m.mul(&ci[0].mul(&t.d[0]).add(&ci[1].mul(&t.d[1])));
            let along = Interval::new(along.lo().min(0.0), along.hi().max(0.0));
            let spread = q_m
                .mul(&Interval::point(c[r][0].abs()).mul(&Interval::point(t.r[0])))
                .add(&q_m.mul(&Interval::point(c[r][1].abs()).mul(&Interval::point(t.r[1]))));
            let m_spread = spread.hi().abs().max(spread.lo().abs());
            let cg = ci[0]
                .mul(&g_a[0])
                .add(&ci[1].mul(&g_a[1]))
                .sub(&along)
                .add(&Interval::new(-m_spread, m_spread));
            let mut k = Interval::point(m[r]).sub(&cg);
            for (a, d) in dw.iter().enumerate() {
                let cj = ci[0].mul(&jw[0][a]).add(&ci[1].mul(&jw[1][a]));
                let e = Interval::point(if r == a { 1.0 } else { 0.0 }).sub(&cj);
                k = k.add(&e.mul(d));
            }
            lo[r] < k.lo() && k.hi() < hi[r]
        })
    }

    /// `G(w; y) = (x(w) − y₀ q(w), y(w) − y₁ q(w))` at a point, for every `y` in the box.
    pub(super) fn residual(&self, w: [f64; 2], y: [Interval; 2]) -> [Interval; 2] {
        let wi = w.map(Interval::point);
        let q = self.jets[2][0].eval(&wi);
        [0, 1].map(|k| self.jets[k][0].eval(&wi).sub(&y[k].mul(&q)))
    }

    /// The Jacobian of `G(·; y)` over a parameter box, for every `y` in the image box.
    pub(super) fn jacobian_on(
        &self,
        y: [Interval; 2],
        lo: [f64; 2],
        hi: [f64; 2],
    ) -> [[Interval; 2]; 2] {
        let rq = [0, 1].map(|a| range_on(&self.jets[2][1 + a], &lo, &hi));
        std::array::from_fn(|k| {
            std::array::from_fn(|a| range_on(&self.jets[k][1 + a], &lo, &hi).sub(&y[k].mul(&rq[a])))
        })
    }

    /// An enclosure of the patch's points over a parameter box.
    pub(crate) fn space_box(&self, lo: [f64; 2], hi: [f64; 2]) -> Option<([f64; 3], [f64; 3])> {
        let r = self.space.clone().map(|p| range_on(&p, &lo, &hi));
        let mut out = ([0.0; 3], [0.0; 3]);
        for k in 0..3 {
            let c = r[k].checked_div(&r[3])?;
            out.0[k] = c.lo();
            out.1[k] = c.hi();
        }
        Some(out)
    }
}
