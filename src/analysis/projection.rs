//! The projection of a view onto its image plane, as exact polynomials per patch.
//!
//! A view gives an exact frame: two image axes `a`, `b` and a depth axis `d`, rational vectors
//! that form a basis (not unit: exactness matters more than length). With the patch in
//! homogeneous coordinates `(X, W)`:
//!
//! - parallel view along `d` (`a`, `b`, `d` mutually orthogonal): the image point is
//!   `(x/q, y/q)` with `x = a·X`, `y = b·X`, `q = W`, and the depth is `depth/W` with
//!   `depth = d·X`;
//! - an eye `E`: everything relative to the model's centre `c`, `x = a·(X − cW)`,
//!   `y = b·(X − cW)`, `depth = d·(X − cW)` with `a`, `b` exactly orthogonal to `c − E`, and
//!   `q = m (depth + k W)`, a positive multiple of `d·(X − E W)`, required positive (the model
//!   lies in front of the eye); see [`EyeFrame`] and `proofs/projection.md`.
//!
//! In both, two points have the same image exactly when they lie on one viewing ray, and
//! along a ray the depth increases away from the viewer: smaller is nearer.
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
    /// First image axis (orthogonal to `d`; for an eye, to `r`, see [`EyeFrame`]).
    pub a: [Rational; 3],
    /// Second image axis (`d × a`; for an eye `± r × e_l`, see [`EyeFrame`]).
    pub b: [Rational; 3],
    /// The depth axis: the view direction, or for an eye the direction `r` from the eye to
    /// the model's bounding-box centre rounded to f64 (after scaling by a power of two), or
    /// `r` exactly (made dyadic by [`dyadic_factor`]) if the rounded one does not have the
    /// whole model in front of the eye.
    pub d: [Rational; 3],
    /// For an eye, how the image and depth are written relative to the model's centre.
    pub eye: Option<EyeFrame>,
}

/// The perspective frame of an eye `E` (`proofs/projection.md`, "An eye"):
/// with `c` the model's bounding-box centre and `r = c − E`, the image axes `a`, `b` are
/// exactly orthogonal to `r` and
///
/// `x = a·(X − c W)`, `y = b·(X − c W)`, `depth = d·(X − c W)`,
/// `q = m (depth + k W)` with `k = d·r`, so `q = m d·(X − E W)`.
///
/// Since `a·r = b·r = 0`, `x/q = a·(X/W − E) / (m d·(X/W − E))`: the image of the viewing
/// ray through the point, the same for every point of that ray, and different for different
/// rays (`a`, `b`, `d` are a basis). Along one ray the depth is an increasing function of
/// the distance from the eye (it differs from `d·(X/W − E)` by the constant `k`, and that is
/// proportional to the distance on the ray, positive in front of the eye). So the eye's own
/// size (`1e308`) or length (`1e-10000`) never enters `x`, `y` or `depth`, only `k` and `m`,
/// and the f64 bounds of the images stay those of the model.
#[derive(Clone, Debug, PartialEq)]
pub struct EyeFrame {
    /// The model's bounding-box centre `c`.
    pub centre: [Rational; 3],
    /// `k = d·r`.
    pub k: Rational,
    /// The positive scale `m` of `q`: a power of two (times the [`dyadic_factor`] of `k`)
    /// that makes the images about the model's size however far the eye is.
    pub m: Rational,
}

/// An outward f64 enclosure of a rational.
fn iv(q: &Rational) -> Interval {
    Interval::from_rational(q, Precision::F64)
}

/// `c · v` for an exact vector and an interval one, outward.
fn dot_iv(c: &[Rational; 3], v: &[Interval; 3]) -> Interval {
    (0..3).fold(Interval::point(0.0), |acc, k| {
        acc.add(&iv(&c[k]).mul(&v[k]))
    })
}

impl EyeFrame {
    /// `q = m (depth + k)` over an interval of depths (`W = 1`), outward; `m k` is rounded
    /// once as one number (it is about the model's size even when `m` and `k` are not
    /// representable).
    fn q_iv(&self, depth: &Interval) -> Interval {
        iv(&self.m)
            .mul(depth)
            .add(&iv(&Rational::from(&self.m * &self.k)))
    }
}

/// Image axes `a`, `b` exactly orthogonal to `r ≠ 0`, with `(a × b)·r > 0`: `r × e_k` and
/// `± r × e_l` for the two coordinate axes least aligned with `r` (independent: their cross
/// product is `r` times the third coordinate of `r`, the largest), each made dyadic and
/// scaled by a power of two.
fn image_axes_orthogonal_to(r: &[Rational; 3]) -> ([Rational; 3], [Rational; 3]) {
    let mut order = [0, 1, 2];
    order.sort_by(|&i, &j| {
        Rational::from(r[i].abs_ref())
            .cmp(&Rational::from(r[j].abs_ref()))
            .then(i.cmp(&j))
    });
    let unit = |k: usize| {
        let mut e = [Rational::new(), Rational::new(), Rational::new()];
        e[k] = Rational::from(1);
        e
    };
    let tidy = |v: [Rational; 3]| {
        let f = dyadic_factor(&v);
        crate::analysis::view::working_direction(&v.map(|c| c * &f))
    };
    let a = tidy(cross(r, &unit(order[0])));
    let mut b = tidy(cross(r, &unit(order[1])));
    if !dot(&cross(&a, &b), r).sign().is_positive() {
        b = b.map(|c| -c);
    }
    (a, b)
}

/// The scale `m` of an eye's `q`: with `2^j` about `k / extent` (0 if that is below 1), `m =
/// f 2^-j` for `f` the [`dyadic_factor`] of `k`, so that `m k` is dyadic and about the
/// model's extent however far away the eye is.
fn image_scale(k: &Rational, extent: &Rational) -> Rational {
    let log2 = |q: &Rational| {
        i64::from(q.numer().significant_bits()) - i64::from(q.denom().significant_bits())
    };
    let j = if extent.sign().is_positive() {
        (log2(k) - log2(extent)).max(0)
    } else {
        0
    };
    let mut m = dyadic_factor(&[k.clone(), Rational::new(), Rational::new()]);
    m >>= u32::try_from(j).unwrap_or(u32::MAX);
    m
}

/// The factor `L / 2^⌊log₂ L⌋` in [1, 2), with `L` the least common multiple of the
/// denominators of `v`: `v` times it has dyadic coordinates (odd factors of the
/// denominators cleared, the size kept). It is 1 when `v` is already dyadic.
pub fn dyadic_factor(v: &[Rational; 3]) -> Rational {
    let mut l = rug::Integer::from(1);
    for c in v {
        l.lcm_mut(c.denom());
    }
    let twos = l.find_one(0).unwrap_or(0);
    l >>= twos;
    let bits = l.significant_bits().saturating_sub(1);
    let mut f = Rational::from(l);
    f >>= bits;
    f
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
    pub(crate) fn map(&self, r: impl Fn(&Poly) -> Poly) -> ImagePolys {
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
        match view {
            View::Direction(d) => {
                if d.iter().all(|c| c.sign().is_zero()) {
                    return Err(ProjectionError::ZeroDirection);
                }
                let d = crate::analysis::view::working_direction(d);
                Ok(Projection::with_depth_axis(view, d))
            }
            View::Eye(e) => {
                let centre: [Rational; 3] = std::array::from_fn(|k| {
                    let mut c = Rational::from(&lo[k] + &hi[k]);
                    c >>= 1u32;
                    c
                });
                let r: [Rational; 3] = std::array::from_fn(|k| Rational::from(&centre[k] - &e[k]));
                if r.iter().all(|c| c.sign().is_zero()) {
                    return Err(ProjectionError::BehindEye(0));
                }
                let (a, b) = image_axes_orthogonal_to(&r);
                // Any depth axis with `d·P > 0` on the whole model serves (`(a, b, d)` is a
                // basis): a short one (`r` rounded to f64 after scaling by a power of two)
                // keeps the numbers of `q` as long as the eye's; `r` itself if it fails.
                let short = crate::analysis::view::working_direction(&r)
                    .map(|c| Rational::from_f64(c.to_f64()).unwrap_or_default());
                let extent = lo
                    .iter()
                    .zip(&hi)
                    .map(|(l, h)| Rational::from(h - l))
                    .max()
                    .unwrap_or_default();
                let mut first_behind = None;
                for axis in [Some(short), None] {
                    let d = axis.unwrap_or_else(|| {
                        let f = dyadic_factor(&r);
                        r.clone().map(|c| c * &f)
                    });
                    let k = dot(&d, &r);
                    if !k.sign().is_positive() {
                        continue;
                    }
                    let m = image_scale(&k, &extent);
                    let proj = Projection {
                        view: view.clone(),
                        a: a.clone(),
                        b: b.clone(),
                        d,
                        eye: Some(EyeFrame {
                            centre: centre.clone(),
                            k,
                            m,
                        }),
                    };
                    match proj.first_patch_behind(model) {
                        None => return Ok(proj),
                        Some(i) => {
                            first_behind.get_or_insert(i);
                        }
                    }
                }
                Err(ProjectionError::BehindEye(first_behind.unwrap_or(0)))
            }
        }
    }

    /// The frame with depth axis `d`: `a = d × e_k` for the coordinate axis `e_k` least
    /// aligned with `d` (never zero), `b = d × a`.
    fn with_depth_axis(view: &View, d: [Rational; 3]) -> Projection {
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
        Projection {
            view: view.clone(),
            a,
            b,
            d,
            eye: None,
        }
    }

    /// For an eye, the first patch not proven strictly in front of it along the depth axis
    /// (`q = d·P` not of positive Bernstein coefficients).
    fn first_patch_behind(&self, model: &Model) -> Option<usize> {
        model.patches.iter().position(|p| {
            let [x0, x1, x2, w] = p.surface.homogeneous();
            let q = self.q_of(&combine(&self.d, &self.relative([x0, x1, x2], &w)), &w);
            !q.coeffs().iter().all(|c| c.sign().is_positive())
        })
    }

    /// `X`, or `X − c W` for an eye ([`EyeFrame`]).
    fn relative(&self, x: [Poly; 3], w: &Poly) -> [Poly; 3] {
        match &self.eye {
            None => x,
            Some(eye) => {
                let [x0, x1, x2] = x;
                let c = &eye.centre;
                [
                    &x0 - &w.scale(&c[0]),
                    &x1 - &w.scale(&c[1]),
                    &x2 - &w.scale(&c[2]),
                ]
            }
        }
    }

    /// The image denominator from the depth: `W`, or `m (depth + k W)` for an eye.
    fn q_of(&self, depth: &Poly, w: &Poly) -> Poly {
        match &self.eye {
            None => w.clone(),
            Some(eye) => (depth + &w.scale(&eye.k)).scale(&eye.m),
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
        ImagePolys {
            x: combine(&self.a, &p),
            y: combine(&self.b, &p),
            q: self.q_of(&depth, w),
            depth,
            w: w.clone(),
        }
    }

    /// An enclosure of the images of all points of a box of space (`[lo, hi]` per
    /// coordinate), outward; `None` for an eye if the box is not proven in front of it.
    pub fn image_of_box(&self, lo: [f64; 3], hi: [f64; 3]) -> Option<[Interval; 2]> {
        let rel = self.relative_box(lo, hi);
        let dot = |c: &[Rational; 3]| dot_iv(c, &rel);
        let (x, y) = (dot(&self.a), dot(&self.b));
        match &self.eye {
            None => Some([x, y]),
            Some(eye) => {
                let q = eye.q_iv(&dot(&self.d));
                (q.lo() > 0.0).then_some(())?;
                Some([x.checked_div(&q)?, y.checked_div(&q)?])
            }
        }
    }

    /// Per image coordinate, a bound on its gradient's Euclidean length over a box of space
    /// (so two points of the box at distance `e` have images within that times `e` in that
    /// coordinate); `None` for an eye if the box is not proven in front of it.
    pub fn image_gradient_bound(&self, lo: [f64; 3], hi: [f64; 3]) -> Option<[f64; 2]> {
        let norm = |v: [Interval; 3]| {
            let s = v
                .iter()
                .fold(Interval::point(0.0), |acc, x| acc.add(&x.mul(x)));
            // One rounding: the square root (`proofs/rounding-margins.md`).
            margin::up(s.hi().sqrt(), margin::FEW)
        };
        match &self.eye {
            None => Some([self.a.clone(), self.b.clone()].map(|c| norm(c.each_ref().map(iv)))),
            Some(eye) => {
                // ∇(c·P / q) = (c − (c·P / q) ∇q) / q, P = X − c₀, q = m (d·P + k), ∇q = m d.
                let rel = self.relative_box(lo, hi);
                let q = eye.q_iv(&dot_iv(&self.d, &rel));
                (q.lo() > 0.0).then_some(())?;
                let m = iv(&eye.m);
                let mut out = [0.0; 2];
                for (o, c) in out.iter_mut().zip([&self.a, &self.b]) {
                    let f = dot_iv(c, &rel).checked_div(&q)?;
                    let g: [Interval; 3] = std::array::from_fn(|k| {
                        iv(&c[k])
                            .sub(&f.mul(&m.mul(&iv(&self.d[k]))))
                            .checked_div(&q)
                    })
                    .map(|x| x.unwrap_or(Interval::new(f64::NEG_INFINITY, f64::INFINITY)));
                    *o = norm(g);
                }
                out.iter().all(|x| x.is_finite()).then_some(out)
            }
        }
    }

    /// A box of space relative to the frame's origin (the model's centre for an eye), outward.
    fn relative_box(&self, lo: [f64; 3], hi: [f64; 3]) -> [Interval; 3] {
        std::array::from_fn(|k| {
            let x = Interval::new(lo[k], hi[k]);
            match &self.eye {
                None => x,
                Some(eye) => x.sub(&iv(&eye.centre[k])),
            }
        })
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
    crate::bernstein::fix_var(p, axis, at)
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
            let x = Rational::from(&im.x.eval(&at) / &q);
            let y = Rational::from(&im.y.eval(&at) / &q);
            let depth = Rational::from(&im.depth.eval(&at) / &w);
            match &proj.eye {
                None => {
                    assert_eq!(x, dot(&proj.a, &rel));
                    assert_eq!(y, dot(&proj.b, &rel));
                    assert_eq!(depth, dot(&proj.d, &rel));
                }
                Some(eye) => {
                    // The image of the ray from the eye, and the depth up to the constant k.
                    let along = Rational::from(&eye.m * &dot(&proj.d, &rel));
                    assert_eq!(x, Rational::from(&dot(&proj.a, &rel) / &along));
                    assert_eq!(y, Rational::from(&dot(&proj.b, &rel) / &along));
                    assert_eq!(depth, dot(&proj.d, &rel) - &eye.k);
                }
            }
        }
    }

    #[test]
    fn an_eyes_image_axes_are_orthogonal_to_the_ray_to_the_centre() {
        let m = sphere_model();
        let big = crate::number::parse_exact("1e308").unwrap();
        let tiny = crate::number::parse_exact("-1e-300").unwrap();
        for e in [
            [5, -7, 11].map(Rational::from),
            [big.clone(), big.clone(), big],
            [Rational::from(3), tiny, Rational::from((1, 3))],
        ] {
            let p = Projection::new(&m, &View::Eye(e.clone())).unwrap();
            let eye = p.eye.clone().unwrap();
            let r: [Rational; 3] = std::array::from_fn(|k| Rational::from(&eye.centre[k] - &e[k]));
            assert_eq!(dot(&p.a, &r), 0);
            assert_eq!(dot(&p.b, &r), 0);
            assert!(dot(&cross(&p.a, &p.b), &r) > 0);
            // The images and depths of the model are about its size, however far the eye.
            for patch in &m.patches {
                let im = p.image(&patch.surface);
                for (num, den) in [(&im.x, &im.q), (&im.y, &im.q), (&im.depth, &im.w)] {
                    let [lo, hi] = crate::analysis::visibility::scene::ratio_bounds(num, den);
                    assert!(lo > -1e3 && hi < 1e3, "{e:?}: [{lo}, {hi}]");
                }
            }
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
