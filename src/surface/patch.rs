//! Rational tensor-product Bézier patches.

use crate::bernstein::Bernstein;
use crate::number::{Interval, Precision, Rational};

/// A point with exact rational coordinates.
pub type Point3 = [Rational; 3];

/// Why a patch could not be built.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum PatchError {
    /// The number of control points is not (m+1)(n+1).
    #[error("degree ({m},{n}) needs {expected} control points, got {got}")]
    PointCount {
        /// Degree in u.
        m: usize,
        /// Degree in v.
        n: usize,
        /// (m+1)(n+1).
        expected: usize,
        /// The number given.
        got: usize,
    },
    /// The number of weights is not the number of control points.
    #[error("{points} control points but {weights} weights")]
    WeightCount {
        /// Control points.
        points: usize,
        /// Weights.
        weights: usize,
    },
    /// A weight is zero or negative (weights must be positive).
    #[error("weight {index} is {value}, weights must be positive")]
    NonPositiveWeight {
        /// Position of the weight.
        index: usize,
        /// Its value.
        value: String,
    },
    /// A degree above the supported maximum.
    #[error("degree ({m},{n}) is above the supported maximum {max}")]
    DegreeTooHigh {
        /// Degree in u.
        m: usize,
        /// Degree in v.
        n: usize,
        /// The maximum.
        max: usize,
    },
}

/// One of the four boundary curves of a patch.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Edge {
    /// v = 0.
    V0,
    /// u = 1.
    U1,
    /// v = 1.
    V1,
    /// u = 0.
    U0,
}

impl Edge {
    /// The four edges, counter-clockwise around the (u, v) square from (0,0).
    pub const ALL: [Edge; 4] = [Edge::V0, Edge::U1, Edge::V1, Edge::U0];
}

/// A rational tensor-product Bézier patch of degree (m, n) on `[0,1]^2`:
/// `S(u,v) = Σ w_ij P_ij B_i^m(u) B_j^n(v) / Σ w_ij B_i^m(u) B_j^n(v)`.
///
/// Control point (i, j) is entry `i * (n + 1) + j`: i along u, j along v. Weights are
/// positive, so the denominator is positive on the whole closed domain. Everything is exact.
///
/// # Examples
/// ```
/// use limn::surface::RationalPatch;
/// use limn::number::Rational;
/// let p = |x: i64, y: i64| [Rational::from(x), Rational::from(y), Rational::new()];
/// // The unit square as a bilinear patch.
/// let sq = RationalPatch::polynomial([1, 1], vec![p(0, 0), p(0, 1), p(1, 0), p(1, 1)]).unwrap();
/// let half = Rational::from((1, 2));
/// assert_eq!(sq.eval(&half, &half)[0], half);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct RationalPatch {
    degree: [usize; 2],
    points: Vec<Point3>,
    weights: Vec<Rational>,
}

/// The first weight that is not positive, with its position and value.
pub(crate) fn first_nonpositive(weights: &[Rational]) -> Option<(usize, String)> {
    weights
        .iter()
        .position(|w| w.cmp0() != std::cmp::Ordering::Greater)
        .map(|i| (i, weights[i].to_string()))
}

/// The highest degree accepted in u or v (IGES files in the wild reach 12 to 20).
pub const MAX_PATCH_DEGREE: usize = 64;

impl RationalPatch {
    /// A patch from degrees, control points (i along u, j along v) and positive weights.
    ///
    /// # Errors
    /// [`PatchError`] on wrong counts or a weight that is not positive.
    pub fn new(
        degree: [usize; 2],
        points: Vec<Point3>,
        weights: Vec<Rational>,
    ) -> Result<Self, PatchError> {
        let [m, n] = degree;
        if m > MAX_PATCH_DEGREE || n > MAX_PATCH_DEGREE {
            return Err(PatchError::DegreeTooHigh {
                m,
                n,
                max: MAX_PATCH_DEGREE,
            });
        }
        let expected = (m + 1) * (n + 1);
        if points.len() != expected {
            return Err(PatchError::PointCount {
                m,
                n,
                expected,
                got: points.len(),
            });
        }
        if weights.len() != points.len() {
            return Err(PatchError::WeightCount {
                points: points.len(),
                weights: weights.len(),
            });
        }
        if let Some((index, value)) = first_nonpositive(&weights) {
            return Err(PatchError::NonPositiveWeight { index, value });
        }
        Ok(RationalPatch {
            degree,
            points,
            weights,
        })
    }

    /// A polynomial (all weights 1) patch.
    ///
    /// # Errors
    /// [`PatchError`] on a wrong point count.
    pub fn polynomial(degree: [usize; 2], points: Vec<Point3>) -> Result<Self, PatchError> {
        let w = vec![Rational::from(1); points.len()];
        RationalPatch::new(degree, points, w)
    }

    /// The degree (m, n).
    pub fn degree(&self) -> [usize; 2] {
        self.degree
    }

    /// The control points, i * (n + 1) + j.
    pub fn points(&self) -> &[Point3] {
        &self.points
    }

    /// The weights, in the order of the points.
    pub fn weights(&self) -> &[Rational] {
        &self.weights
    }

    /// Whether all weights are equal (the patch is a polynomial surface).
    pub fn is_polynomial(&self) -> bool {
        self.weights.iter().all(|w| *w == self.weights[0])
    }

    /// The control point (i, j).
    pub fn point(&self, i: usize, j: usize) -> &Point3 {
        &self.points[i * (self.degree[1] + 1) + j]
    }

    /// The weight (i, j).
    pub fn weight(&self, i: usize, j: usize) -> &Rational {
        &self.weights[i * (self.degree[1] + 1) + j]
    }

    /// The homogeneous coordinate polynomials `[wx, wy, wz, w]` (exact, bivariate).
    pub fn homogeneous(&self) -> [Bernstein<Rational>; 4] {
        let d = [self.degree[0], self.degree[1]];
        let coord = |k: usize| {
            let c = self
                .points
                .iter()
                .zip(&self.weights)
                .map(|(p, w)| Rational::from(&p[k] * w))
                .collect();
            Bernstein::new(&d, c).expect("counts checked in new")
        };
        [
            coord(0),
            coord(1),
            coord(2),
            Bernstein::new(&d, self.weights.clone()).expect("counts checked"),
        ]
    }

    /// An outward enclosure of the patch's points over the parameter box `[lo, hi]` (f64
    /// ends): the hulls of the homogeneous coordinates restricted to the box, divided by the
    /// weight's; `None` unless the weight is proven positive there.
    pub fn enclosure(&self, lo: [f64; 2], hi: [f64; 2]) -> Option<[Interval; 3]> {
        let h: Vec<Interval> = self
            .homogeneous()
            .iter()
            .map(|p| {
                p.convert::<Interval>(Precision::F64)
                    .restrict_box_f64(&lo, &hi)
                    .hull()
            })
            .collect();
        if h[3].lo() <= 0.0 {
            return None;
        }
        let c = |k: usize| h[k].checked_div(&h[3]);
        Some([c(0)?, c(1)?, c(2)?])
    }

    /// The point S(u, v), exactly.
    pub fn eval(&self, u: &Rational, v: &Rational) -> Point3 {
        let h = self.homogeneous();
        let x = [u.clone(), v.clone()];
        let w = h[3].eval(&x);
        [0, 1, 2].map(|k| h[k].eval(&x) / &w)
    }

    /// The control points and weights of a boundary curve, in the direction of increasing
    /// parameter.
    pub fn edge(&self, edge: Edge) -> Vec<(&Point3, &Rational)> {
        let [m, n] = self.degree;
        let at = |i: usize, j: usize| (self.point(i, j), self.weight(i, j));
        match edge {
            Edge::V0 => (0..=m).map(|i| at(i, 0)).collect(),
            Edge::V1 => (0..=m).map(|i| at(i, n)).collect(),
            Edge::U0 => (0..=n).map(|j| at(0, j)).collect(),
            Edge::U1 => (0..=n).map(|j| at(m, j)).collect(),
        }
    }

    /// The four corner points S(0,0), S(1,0), S(1,1), S(0,1).
    pub fn corners(&self) -> [&Point3; 4] {
        let [m, n] = self.degree;
        [
            self.point(0, 0),
            self.point(m, 0),
            self.point(m, n),
            self.point(0, n),
        ]
    }

    /// The axis-aligned box of the control points (which contains the patch, by the convex
    /// hull property with positive weights).
    pub fn control_box(&self) -> [Point3; 2] {
        let mut lo = self.points[0].clone();
        let mut hi = self.points[0].clone();
        for p in &self.points[1..] {
            for k in 0..3 {
                if p[k] < lo[k] {
                    lo[k] = p[k].clone();
                }
                if p[k] > hi[k] {
                    hi[k] = p[k].clone();
                }
            }
        }
        [lo, hi]
    }

    /// The largest side (in f64) of the box of the control points of `patches` (0 for none):
    /// the size relative tolerances on a surface are measured against.
    pub fn control_size<'a>(patches: impl IntoIterator<Item = &'a RationalPatch>) -> f64 {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in patches.into_iter().flat_map(|p| &p.points) {
            for k in 0..3 {
                let c = p[k].to_f64();
                lo[k] = lo[k].min(c);
                hi[k] = hi[k].max(c);
            }
        }
        (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max)
    }

    /// The same patch with every control point mapped by `f` (an affine map keeps the
    /// rational surface the image of the original under that map; weights are unchanged).
    pub fn map_points(&self, f: impl Fn(&Point3) -> Point3) -> RationalPatch {
        RationalPatch {
            degree: self.degree,
            points: self.points.iter().map(f).collect(),
            weights: self.weights.clone(),
        }
    }
}
