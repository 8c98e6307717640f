//! Rational Bézier and B-spline curves with exact coefficients, in homogeneous form
//! `[w x_1, …, w x_d, w]` (`K = d + 1` entries per control point): trimming curves in a
//! surface's parameter plane (`K = 3`, [`ParameterCurve`]) and edges in model space (`K = 4`,
//! [`ModelCurve`]). Weights are positive, so a curve lies in the convex hull of its control
//! points and never reaches infinity.

use super::knots::{bezier_segments, de_boor};
use super::nurbs::{check_knots, NurbsError};
use crate::bernstein::Bernstein;
use crate::number::Rational;
use std::cmp::Ordering;

/// The homogeneous point `[w p, w]` of the affine point `p` (`K - 1` coordinates) with weight `w`.
fn lift<const K: usize>(p: &[Rational], w: &Rational) -> [Rational; K] {
    std::array::from_fn(|c| {
        if c + 1 == K {
            w.clone()
        } else {
            Rational::from(&p[c] * w)
        }
    })
}

/// The affine point of a homogeneous one (its weight is positive).
fn project<const K: usize>(h: &[Rational; K]) -> Vec<Rational> {
    (0..K - 1)
        .map(|c| Rational::from(&h[c] / &h[K - 1]))
        .collect()
}

/// A rational Bézier curve on `[0, 1]`: `C(t) = Σ w_i P_i B_i(t) / Σ w_i B_i(t)`, stored as
/// its homogeneous control points `[w_i P_i, w_i]` with every `w_i > 0`.
#[derive(Clone, Debug, PartialEq)]
pub struct RationalCurve<const K: usize> {
    hom: Vec<[Rational; K]>,
}

/// A curve in a surface's parameter plane: `(u, v)` with weight.
pub type ParameterCurve = RationalCurve<3>;
/// A curve in model space: `(x, y, z)` with weight.
pub type ModelCurve = RationalCurve<4>;

impl<const K: usize> RationalCurve<K> {
    /// The curve with these homogeneous control points, or `None` if there are none or a
    /// weight (the last entry) is not positive.
    pub fn from_homogeneous(hom: Vec<[Rational; K]>) -> Option<Self> {
        (!hom.is_empty() && hom.iter().all(|h| h[K - 1].cmp0() == Ordering::Greater))
            .then_some(RationalCurve { hom })
    }

    /// The curve through affine control points with positive weights (`None` if the counts
    /// differ, there are no points, or a weight is not positive).
    pub fn new(points: &[Vec<Rational>], weights: &[Rational]) -> Option<Self> {
        if points.len() != weights.len() || points.iter().any(|p| p.len() + 1 != K) {
            return None;
        }
        let hom = points
            .iter()
            .zip(weights)
            .map(|(p, w)| lift(p, w))
            .collect();
        Self::from_homogeneous(hom)
    }

    /// The straight segment from `a` to `b` (degree 1, unit weights).
    pub fn segment(a: &[Rational], b: &[Rational]) -> Self {
        let h = |p: &[Rational]| {
            std::array::from_fn(|c| p.get(c).cloned().unwrap_or(Rational::from(1)))
        };
        RationalCurve {
            hom: vec![h(a), h(b)],
        }
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.hom.len() - 1
    }

    /// The homogeneous control points `[w P, w]`.
    pub fn homogeneous(&self) -> &[[Rational; K]] {
        &self.hom
    }

    /// Homogeneous coordinate `k` (`w x_k`, or the weight `w` for `k = K - 1`) as a univariate
    /// Bernstein polynomial on `[0, 1]`.
    pub fn coordinate(&self, k: usize) -> Bernstein<Rational> {
        Bernstein::new(
            &[self.degree()],
            self.hom.iter().map(|h| h[k].clone()).collect(),
        )
        .expect("a curve has degree + 1 control points")
    }

    /// `X_k − c W`: since `W > 0`, its sign at `t` is the sign of `x_k(t) − c`.
    pub fn offset(&self, k: usize, c: &Rational) -> Bernstein<Rational> {
        self.coordinate(k)
            .try_sub(&self.coordinate(K - 1).scale(c))
            .expect("equal degrees")
    }

    /// Whether every weight is the same (the curve is polynomial).
    pub fn is_polynomial(&self) -> bool {
        self.hom.iter().all(|h| h[K - 1] == self.hom[0][K - 1])
    }

    /// Control point `i` in affine coordinates (`K - 1` entries).
    pub fn point(&self, i: usize) -> Vec<Rational> {
        project(&self.hom[i])
    }

    /// The affine control points.
    pub fn points(&self) -> Vec<Vec<Rational>> {
        (0..self.hom.len()).map(|i| self.point(i)).collect()
    }

    /// The start point `C(0)` (the first control point).
    pub fn start(&self) -> Vec<Rational> {
        self.point(0)
    }

    /// The end point `C(1)` (the last control point).
    pub fn end(&self) -> Vec<Rational> {
        self.point(self.hom.len() - 1)
    }

    /// `C(t)` by de Casteljau's algorithm on the homogeneous points, exact.
    pub fn eval(&self, t: &Rational) -> Vec<Rational> {
        let s = Rational::from(1 - t);
        let mut d = self.hom.clone();
        for r in 1..d.len() {
            for i in 0..d.len() - r {
                d[i] = std::array::from_fn(|c| {
                    Rational::from(&s * &d[i][c]) + Rational::from(t * &d[i + 1][c])
                });
            }
        }
        project(&d[0])
    }

    /// The same curve traversed backwards (`t → 1 − t`).
    pub fn reversed(&self) -> Self {
        let mut hom = self.hom.clone();
        hom.reverse();
        RationalCurve { hom }
    }

    /// The curve with every control point mapped by `f` (an affine map of the affine
    /// coordinates; the weights are kept, so the image is exact).
    pub fn map_points<const L: usize>(
        &self,
        f: impl Fn(&[Rational]) -> Vec<Rational>,
    ) -> RationalCurve<L> {
        let hom = self
            .hom
            .iter()
            .map(|h| lift(&f(&project(h)), &h[K - 1]))
            .collect();
        RationalCurve { hom }
    }
}

/// A rational B-spline curve: degree `p`, knots `t_0..t_{n+p}`, `n` homogeneous control
/// points with positive weights, used on `range` (inside the knot domain `[t_p, t_n]`).
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsCurve<const K: usize> {
    degree: usize,
    knots: Vec<Rational>,
    hom: Vec<[Rational; K]>,
    range: [Rational; 2],
}

impl<const K: usize> NurbsCurve<K> {
    /// A NURBS curve from its degree, knots, affine control points (`K - 1` coordinates each)
    /// and positive weights, used on `range` (`None`: the whole knot domain).
    ///
    /// # Errors
    /// [`NurbsError`] on wrong counts, decreasing knots, an empty domain, a weight that is not
    /// positive, or a range that is empty or not inside the knot domain.
    pub fn new(
        degree: usize,
        knots: Vec<Rational>,
        points: &[Vec<Rational>],
        weights: &[Rational],
        range: Option<[Rational; 2]>,
    ) -> Result<Self, NurbsError> {
        check_knots("t", degree, points.len(), &knots)?;
        if weights.len() != points.len() || points.iter().any(|p| p.len() + 1 != K) {
            return Err(NurbsError::PointCount {
                expected: points.len(),
                got: weights.len(),
            });
        }
        if let Some((index, value)) = super::patch::first_nonpositive(weights) {
            return Err(NurbsError::NonPositiveWeight { index, value });
        }
        let domain = [knots[degree].clone(), knots[points.len()].clone()];
        let range = range.unwrap_or_else(|| domain.clone());
        if range[0] >= range[1] || range[0] < domain[0] || range[1] > domain[1] {
            return Err(NurbsError::Range {
                start: range[0].to_f64().to_string(),
                end: range[1].to_f64().to_string(),
                domain_start: domain[0].to_f64().to_string(),
                domain_end: domain[1].to_f64().to_string(),
            });
        }
        let curve = RationalCurve::<K>::new(points, weights).ok_or(NurbsError::PointCount {
            expected: points.len(),
            got: weights.len(),
        })?;
        Ok(NurbsCurve {
            degree,
            knots,
            hom: curve.hom,
            range,
        })
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The parameter range used.
    pub fn range(&self) -> &[Rational; 2] {
        &self.range
    }

    /// The number of Bézier pieces [`Self::to_bezier`] makes (nonempty knot spans of the
    /// range), without making them.
    pub fn span_count(&self) -> usize {
        let [a, b] = &self.range;
        let mut cuts: Vec<&Rational> = self.knots.iter().filter(|t| *t > a && *t < b).collect();
        cuts.dedup();
        cuts.len() + 1
    }

    /// The rational Bézier pieces of the curve on its range, in order, each with its span
    /// `[s, e]`: exact, each piece is the curve on its span reparameterised to `[0, 1]`
    /// (`proofs/knot-insertion.md`).
    pub fn to_bezier(&self) -> Vec<([Rational; 2], RationalCurve<K>)> {
        bezier_segments(
            self.degree,
            &self.knots,
            &self.hom,
            [&self.range[0], &self.range[1]],
        )
        .into_iter()
        .map(|(span, hom)| (span, RationalCurve { hom }))
        .collect()
    }

    /// `C(t)` by de Boor's algorithm, exact, for `t` in the knot domain.
    pub fn eval(&self, t: &Rational) -> Vec<Rational> {
        project(&de_boor(self.degree, &self.knots, &self.hom, t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Rational {
        Rational::from((n, d))
    }

    /// A rational cubic B-spline with a double interior knot, used on a sub-range that starts
    /// and ends inside spans: every Bézier piece evaluates exactly to the B-spline on its span.
    #[test]
    fn bezier_pieces_of_a_curve_on_a_sub_range_are_exact() {
        let knots: Vec<Rational> = [0, 0, 0, 0, 2, 2, 5, 6, 6, 6, 6]
            .iter()
            .map(|&k| q(k, 1))
            .collect();
        let points: Vec<Vec<Rational>> = (0..7).map(|i| vec![q(i, 1), q((i * i) % 5, 2)]).collect();
        let weights: Vec<Rational> = (0..7).map(|i| q(1 + (i % 3), 2)).collect();
        let range = [q(1, 3), q(11, 2)];
        let c = NurbsCurve::<3>::new(3, knots, &points, &weights, Some(range.clone())).unwrap();
        let pieces = c.to_bezier();
        assert_eq!(pieces.len(), c.span_count());
        let spans: Vec<[Rational; 2]> = pieces.iter().map(|(s, _)| s.clone()).collect();
        assert_eq!(
            spans,
            vec![[q(1, 3), q(2, 1)], [q(2, 1), q(5, 1)], [q(5, 1), q(11, 2)]]
        );
        for ([a, b], piece) in &pieces {
            for s in [q(0, 1), q(1, 7), q(1, 2), q(1, 1)] {
                let t = a + &s * Rational::from(b - a);
                assert_eq!(piece.eval(&s), c.eval(&t), "span [{a}, {b}] at {s}");
            }
        }
        // The pieces join: each ends where the next starts, exactly.
        for w in pieces.windows(2) {
            assert_eq!(w[0].1.end(), w[1].1.start());
        }
        assert_eq!(pieces[0].1.start(), c.eval(&range[0]));
        // A range outside the domain is refused.
        let bad = NurbsCurve::<3>::new(
            3,
            c.knots.clone(),
            &points,
            &weights,
            Some([q(-1, 1), q(1, 1)]),
        );
        assert!(matches!(bad, Err(NurbsError::Range { .. })));
    }

    #[test]
    fn reversal_and_affine_maps_are_exact() {
        let c = ParameterCurve::new(
            &[
                vec![q(0, 1), q(0, 1)],
                vec![q(1, 1), q(2, 1)],
                vec![q(3, 1), q(0, 1)],
            ],
            &[q(1, 1), q(1, 3), q(2, 1)],
        )
        .unwrap();
        let r = c.reversed();
        for t in [q(0, 1), q(1, 5), q(2, 3)] {
            assert_eq!(r.eval(&t), c.eval(&Rational::from(1 - &t)));
        }
        let m: ModelCurve = c.map_points(|p| vec![p[0].clone(), p[1].clone() * q(2, 1), q(7, 1)]);
        let at = c.eval(&q(1, 4));
        assert_eq!(
            m.eval(&q(1, 4)),
            vec![at[0].clone(), Rational::from(&at[1] * 2), q(7, 1)]
        );
        assert!(!c.is_polynomial());
        assert!(ParameterCurve::new(&[vec![q(0, 1), q(0, 1)]], &[q(0, 1)]).is_none());
    }
}
