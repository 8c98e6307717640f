//! The projection of a view onto its image plane, as exact polynomials per patch.
//!
//! A view gives an exact frame: two image axes `a`, `b` and a depth axis `d`, mutually
//! orthogonal rational vectors (not unit: exactness matters more than length). With the
//! patch in homogeneous coordinates `(X, W)` and `P = X` (parallel view along `d`) or
//! `P = X − E W` (perspective from the eye `E`, `d` pointing from the eye into the model):
//!
//! - the image point is `(x/q, y/q)` with `x = a·P`, `y = b·P`, and `q = W` (parallel) or
//!   `q = d·P` (perspective, required positive: the model lies in front of the eye);
//! - the depth is `depth/W` with `depth = d·P`: smaller is nearer the viewer, and two points
//!   with the same image lie on one viewing ray, so their depths order them along it.
//!
//! Everything is exact: two points have the same image exactly when
//! `x₁ q₂ − x₂ q₁ = 0` and `y₁ q₂ − y₂ q₁ = 0`, and one is in front of the other by the sign
//! of `depth₁ W₂ − depth₂ W₁` (the weights are positive). Hidden-line removal and visible
//! regions are written on these polynomials only ([`crate::analysis::visibility::hlr`], [`crate::analysis::visibility::ray`]).

use crate::analysis::view::View;
use crate::bernstein::Bernstein;
use crate::model::Model;
use crate::number::margin;
use crate::number::{Interval, Number, Precision, Rational};
use crate::surface::{Edge, RationalPatch};

use crate::bernstein::Poly;

/// An exact image frame for a view.
#[derive(Clone, Debug, PartialEq)]
pub struct Projection {
    /// The view.
    pub view: View,
    /// First image axis (orthogonal to `d`).
    pub a: [Rational; 3],
    /// Second image axis (`d × a`).
    pub b: [Rational; 3],
    /// The depth axis: the view direction, or for an eye the direction from the eye to the
    /// model's bounding-box centre.
    pub d: [Rational; 3],
}

/// The image and depth of a patch (or of a curve on it) as exact polynomials.
#[derive(Clone, Debug, PartialEq)]
pub struct ImagePolys {
    /// Numerator of the first image coordinate.
    pub x: Poly,
    /// Numerator of the second image coordinate.
    pub y: Poly,
    /// Common denominator of the image coordinates (positive).
    pub q: Poly,
    /// Numerator of the depth (`depth / w`; smaller is nearer).
    pub depth: Poly,
    /// The weight (positive).
    pub w: Poly,
}

impl ImagePolys {
    /// The image polynomials restricted to the line where variable `axis` equals `at`, in
    /// the other variable.
    pub fn on_line(&self, axis: usize, at: &Rational) -> ImagePolys {
        self.map(|p| fix_axis(p, axis, at))
    }

    /// The image polynomials restricted to one side of the square, in the side's increasing
    /// parameter (u for `V0`/`V1`, v for `U0`/`U1`).
    pub fn on_side(&self, edge: Edge) -> ImagePolys {
        self.map(|p| side_restriction(p, edge))
    }

    /// The same map applied to every polynomial.
    fn map(&self, r: impl Fn(&Poly) -> Poly) -> ImagePolys {
        ImagePolys {
            x: r(&self.x),
            y: r(&self.y),
            q: r(&self.q),
            depth: r(&self.depth),
            w: r(&self.w),
        }
    }
}

fn dot(a: &[Rational; 3], b: &[Rational; 3]) -> Rational {
    let mut s = Rational::new();
    for k in 0..3 {
        s += Rational::from(&a[k] * &b[k]);
    }
    s
}

fn cross(a: &[Rational; 3], b: &[Rational; 3]) -> [Rational; 3] {
    let m = |x: &Rational, y: &Rational| Rational::from(x * y);
    [
        m(&a[1], &b[2]) - m(&a[2], &b[1]),
        m(&a[2], &b[0]) - m(&a[0], &b[2]),
        m(&a[0], &b[1]) - m(&a[1], &b[0]),
    ]
}

/// `Σ c_k p_k` for exact vectors of polynomials.
fn combine(c: &[Rational; 3], p: &[Poly; 3]) -> Poly {
    let terms: Vec<Poly> = (0..3).map(|k| p[k].scale(&c[k])).collect();
    &(&terms[0] + &terms[1]) + &terms[2]
}

/// Why a projection cannot be set up.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ProjectionError {
    /// The direction is the zero vector.
    #[error("the view direction is the zero vector")]
    ZeroDirection,
    /// The eye is not strictly in front of a patch (inside the model, or beside it).
    #[error("patch {0} is not entirely in front of the eye (the eye must see the whole model on one side of it)")]
    BehindEye(usize),
    /// The model has no patches.
    #[error("the model has no patches")]
    Empty,
}

impl Projection {
    /// The frame of a view of a model.
    ///
    /// # Errors
    /// A zero direction, an empty model, or (for an eye) a patch not proven to lie strictly
    /// in front of the eye along the depth axis.
    ///
    /// # Examples
    /// ```
    /// use limn::analysis::projection::Projection;
    /// use limn::analysis::view::View;
    /// use limn::number::Rational;
    /// use limn::testing::shapes;
    /// let model = limn::model::Model::from_patches(
    ///     limn::model::Format::Json, shapes::sphere(&Rational::from(1)));
    /// let z = Rational::new();
    /// let p = Projection::new(&model, &View::Direction([z.clone(), z, Rational::from(1)])).unwrap();
    /// // The image axes are orthogonal to the view.
    /// let dot: Rational = (0..3).map(|k| Rational::from(&p.a[k] * &p.d[k])).sum();
    /// assert_eq!(dot, 0);
    /// ```
    pub fn new(model: &Model, view: &View) -> Result<Projection, ProjectionError> {
        let [lo, hi] = model.bounding_box().ok_or(ProjectionError::Empty)?;
        if model.patches.is_empty() {
            return Err(ProjectionError::Empty);
        }
        let d = match view {
            View::Direction(d) => {
                if d.iter().all(|c| c.sign().is_zero()) {
                    return Err(ProjectionError::ZeroDirection);
                }
                crate::analysis::view::working_direction(d)
            }
            View::Eye(e) => {
                let centre: [Rational; 3] = std::array::from_fn(|k| {
                    let mut c = Rational::from(&lo[k] + &hi[k]);
                    c >>= 1u32;
                    c
                });
                let d: [Rational; 3] = std::array::from_fn(|k| Rational::from(&centre[k] - &e[k]));
                if d.iter().all(|c| c.sign().is_zero()) {
                    return Err(ProjectionError::BehindEye(0));
                }
                d
            }
        };
        // The coordinate axis least aligned with d gives a = d × e_k, never zero.
        let k = (0..3)
            .min_by(|&i, &j| {
                Rational::from(d[i].abs_ref())
                    .cmp(&Rational::from(d[j].abs_ref()))
                    .then(i.cmp(&j))
            })
            .expect("three axes");
        let mut e = [Rational::new(), Rational::new(), Rational::new()];
        e[k] = Rational::from(1);
        let a = cross(&d, &e);
        let b = cross(&d, &a);
        let proj = Projection {
            view: view.clone(),
            a,
            b,
            d,
        };
        if let View::Eye(_) = view {
            for (i, p) in model.patches.iter().enumerate() {
                let q = proj.image(&p.surface).q;
                if !q.coeffs().iter().all(|c| c.sign().is_positive()) {
                    return Err(ProjectionError::BehindEye(i));
                }
            }
        }
        Ok(proj)
    }

    /// `P` for homogeneous coordinates: `X`, or `X − E W` for an eye.
    fn relative(&self, x: [Poly; 3], w: &Poly) -> [Poly; 3] {
        match &self.view {
            View::Direction(_) => x,
            View::Eye(e) => {
                let [x0, x1, x2] = x;
                [
                    &x0 - &w.scale(&e[0]),
                    &x1 - &w.scale(&e[1]),
                    &x2 - &w.scale(&e[2]),
                ]
            }
        }
    }

    /// The image polynomials of a patch, in (u, v).
    pub fn image(&self, patch: &RationalPatch) -> ImagePolys {
        let [x0, x1, x2, w] = patch.homogeneous();
        self.image_of(&[x0, x1, x2], &w)
    }

    /// The image polynomials of homogeneous coordinates `(X, W)` in any variables.
    pub fn image_of(&self, x: &[Poly; 3], w: &Poly) -> ImagePolys {
        let p = self.relative(x.clone(), w);
        let depth = combine(&self.d, &p);
        let q = match self.view {
            View::Direction(_) => w.clone(),
            View::Eye(_) => depth.clone(),
        };
        ImagePolys {
            x: combine(&self.a, &p),
            y: combine(&self.b, &p),
            q,
            depth,
            w: w.clone(),
        }
    }

    /// An enclosure of the images of all points of a box of space (`[lo, hi]` per
    /// coordinate), outward; `None` for an eye if the box is not proven in front of it.
    pub fn image_of_box(&self, lo: [f64; 3], hi: [f64; 3]) -> Option<[Interval; 2]> {
        let iv = |q: &Rational| Interval::from_rational(q, Precision::F64);
        let rel: [Interval; 3] = std::array::from_fn(|k| {
            let x = Interval::new(lo[k], hi[k]);
            match &self.view {
                View::Direction(_) => x,
                View::Eye(e) => x.sub(&iv(&e[k])),
            }
        });
        let dot = |c: &[Rational; 3]| {
            (0..3).fold(Interval::point(0.0), |acc, k| {
                acc.add(&iv(&c[k]).mul(&rel[k]))
            })
        };
        let (x, y) = (dot(&self.a), dot(&self.b));
        match self.view {
            View::Direction(_) => Some([x, y]),
            View::Eye(_) => {
                let q = dot(&self.d);
                (q.lo() > 0.0).then_some(())?;
                Some([x.checked_div(&q)?, y.checked_div(&q)?])
            }
        }
    }

    /// Per image coordinate, a bound on its gradient's Euclidean length over a box of space
    /// (so two points of the box at distance `e` have images within that times `e` in that
    /// coordinate); `None` for an eye if the box is not proven in front of it.
    pub fn image_gradient_bound(&self, lo: [f64; 3], hi: [f64; 3]) -> Option<[f64; 2]> {
        let iv = |q: &Rational| Interval::from_rational(q, Precision::F64);
        let norm = |v: [Interval; 3]| {
            let s = v
                .iter()
                .fold(Interval::point(0.0), |acc, x| acc.add(&x.mul(x)));
            // One rounding: the square root (`proofs/rounding-margins.md`).
            margin::up(s.hi().sqrt(), margin::FEW)
        };
        match &self.view {
            View::Direction(_) => {
                Some([self.a.clone(), self.b.clone()].map(|c| norm(c.each_ref().map(iv))))
            }
            View::Eye(e) => {
                // ∇(c·P / d·P) = (c − (c·P / d·P) d) / (d·P), P = X − E.
                let rel: [Interval; 3] =
                    std::array::from_fn(|k| Interval::new(lo[k], hi[k]).sub(&iv(&e[k])));
                let dot = |c: &[Rational; 3]| {
                    (0..3).fold(Interval::point(0.0), |acc, k| {
                        acc.add(&iv(&c[k]).mul(&rel[k]))
                    })
                };
                let q = dot(&self.d);
                (q.lo() > 0.0).then_some(())?;
                let mut out = [0.0; 2];
                for (o, c) in out.iter_mut().zip([&self.a, &self.b]) {
                    let f = dot(c).checked_div(&q)?;
                    let g: [Interval; 3] = std::array::from_fn(|k| {
                        iv(&c[k]).sub(&f.mul(&iv(&self.d[k]))).checked_div(&q)
                    })
                    .map(|x| x.unwrap_or(Interval::new(f64::NEG_INFINITY, f64::INFINITY)));
                    *o = norm(g);
                }
                out.iter().all(|x| x.is_finite()).then_some(out)
            }
        }
    }

    /// Whether the view is parallel.
    pub fn is_parallel(&self) -> bool {
        matches!(self.view, View::Direction(_))
    }

    /// `d · a` is zero: a check used by tests.
    pub fn is_orthogonal(&self) -> bool {
        dot(&self.a, &self.d) == 0 && dot(&self.b, &self.d) == 0 && dot(&self.a, &self.b) == 0
    }
}

/// A bivariate polynomial restricted to one side of the square, as a univariate polynomial
/// in the side's increasing parameter.
pub fn side_restriction(p: &Poly, edge: Edge) -> Poly {
    let [m, n] = [p.degrees()[0], p.degrees()[1]];
    let take = |fixed_axis: usize, at_end: bool| -> Poly {
        let (len, other) = if fixed_axis == 0 { (n, m) } else { (m, n) };
        let idx = if at_end { other } else { 0 };
        let coeffs: Vec<Rational> = (0..=len)
            .map(|j| {
                if fixed_axis == 0 {
                    p.coeff(&[idx, j]).clone()
                } else {
                    p.coeff(&[j, idx]).clone()
                }
            })
            .collect();
        Bernstein::new(&[len], coeffs).expect("a side of a patch")
    };
    match edge {
        Edge::V0 => take(1, false),
        Edge::V1 => take(1, true),
        Edge::U0 => take(0, false),
        Edge::U1 => take(0, true),
    }
}

/// A univariate polynomial: `p` with variable `axis` fixed at `at`.
pub fn fix_axis(p: &Poly, axis: usize, at: &Rational) -> Poly {
    let r = p.restrict_rational(axis, at, at);
    let [m, n] = [r.degrees()[0], r.degrees()[1]];
    let coeffs: Vec<Rational> = if axis == 0 {
        (0..=n).map(|j| r.coeff(&[0, j]).clone()).collect()
    } else {
        (0..=m).map(|i| r.coeff(&[i, 0]).clone()).collect()
    };
    let deg = if axis == 0 { n } else { m };
    Bernstein::new(&[deg], coeffs).expect("a line of a patch")
}

/// A polynomial in `k` variables as one in `total` variables, its variables placed from
/// `offset` on (degree 0 in the others; the coefficients are unchanged).
pub fn lift(p: &Poly, total: usize, offset: usize) -> Poly {
    let mut degrees = vec![0; total];
    degrees[offset..offset + p.nvars()].copy_from_slice(p.degrees());
    Bernstein::new(&degrees, p.coeffs().to_vec()).expect("lifting keeps the coefficient count")
}

/// The (u, v) of a side's parameter `t`.
pub fn side_point(edge: Edge, t: &Rational) -> [Rational; 2] {
    let (zero, one) = (Rational::new(), Rational::from(1));
    match edge {
        Edge::V0 => [t.clone(), zero],
        Edge::V1 => [t.clone(), one],
        Edge::U0 => [zero, t.clone()],
        Edge::U1 => [one, t.clone()],
    }
}

/// [`side_point`] in f64.
pub fn side_point_f64(edge: Edge, t: f64) -> [f64; 2] {
    match edge {
        Edge::V0 => [t, 0.0],
        Edge::V1 => [t, 1.0],
        Edge::U0 => [0.0, t],
        Edge::U1 => [1.0, t],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::shapes;

    fn sphere_model() -> Model {
        Model::from_patches(
            crate::model::Format::Json,
            shapes::sphere(&Rational::from(1)),
        )
    }

    #[test]
    fn frame_is_orthogonal_for_skew_directions() {
        let m = sphere_model();
        for d in [[1, 2, 3], [0, 0, 1], [-5, 1, 0], [1, 1, 1]] {
            let v = View::Direction(d.map(Rational::from));
            let p = Projection::new(&m, &v).unwrap();
            assert!(p.is_orthogonal(), "{d:?}");
        }
    }

    #[test]
    fn image_polynomials_evaluate_to_the_projected_point() {
        let m = sphere_model();
        let patch = &m.patches[0].surface;
        let (u, v) = (Rational::from((1, 3)), Rational::from((2, 7)));
        let s = patch.eval(&u, &v);
        for view in [
            View::Direction([1, 2, 3].map(Rational::from)),
            View::Eye([5, -7, 11].map(Rational::from)),
        ] {
            let proj = Projection::new(&m, &view).unwrap();
            let im = proj.image(patch);
            let at = [u.clone(), v.clone()];
            let q = im.q.eval(&at);
            let w = im.w.eval(&at);
            let rel: [Rational; 3] = match &view {
                View::Direction(_) => s.clone(),
                View::Eye(e) => std::array::from_fn(|k| Rational::from(&s[k] - &e[k])),
            };
            let want_x = dot(&proj.a, &rel);
            let want_depth = dot(&proj.d, &rel);
            let scale = match &view {
                View::Direction(_) => Rational::from(1),
                View::Eye(_) => want_depth.clone(),
            };
            assert_eq!(im.x.eval(&at) / &q, Rational::from(&want_x / &scale));
            assert_eq!(im.depth.eval(&at) / &w, want_depth);
        }
    }

    #[test]
    fn an_eye_inside_the_model_is_refused() {
        let m = sphere_model();
        let v = View::Eye([0, 0, 0].map(Rational::from));
        assert!(Projection::new(&m, &v).is_err());
    }

    #[test]
    fn side_restriction_matches_evaluation() {
        let m = sphere_model();
        let patch = &m.patches[1].surface;
        let [x, ..] = patch.homogeneous();
        let t = Rational::from((3, 8));
        for edge in Edge::ALL {
            let s = side_restriction(&x, edge);
            assert_eq!(
                s.eval(std::slice::from_ref(&t)),
                x.eval(&side_point(edge, &t)),
                "{edge:?}"
            );
        }
    }
}
