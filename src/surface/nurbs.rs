//! NURBS surfaces and their exact split into rational Bézier patches.

use super::knots::{bezier_segments, de_boor};
use super::patch::first_nonpositive;
use super::{Point3, RationalPatch};
use crate::number::Rational;

/// Why a NURBS surface is malformed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum NurbsError {
    /// Knot count is not points + degree + 1.
    #[error("{dir}: {points} control points of degree {degree} need {expected} knots, got {got}")]
    KnotCount {
        /// "u" or "v".
        dir: &'static str,
        /// Control points in that direction.
        points: usize,
        /// Degree in that direction.
        degree: usize,
        /// points + degree + 1.
        expected: usize,
        /// The number given.
        got: usize,
    },
    /// Knots decrease somewhere.
    #[error("{dir}: knot {index} ({value}) is less than the one before it")]
    Decreasing {
        /// "u" or "v".
        dir: &'static str,
        /// Position.
        index: usize,
        /// Its value.
        value: String,
    },
    /// Fewer control points than degree + 1, or degree 0 with no span.
    #[error("{dir}: degree {degree} needs at least {} control points, got {points}", degree + 1)]
    TooFewPoints {
        /// "u" or "v".
        dir: &'static str,
        /// Degree.
        degree: usize,
        /// Points.
        points: usize,
    },
    /// The parameter domain [t_p, t_{n+1}] is empty.
    #[error("{dir}: the parameter domain is empty (all knots of the domain coincide)")]
    EmptyDomain {
        /// "u" or "v".
        dir: &'static str,
    },
    /// Control point count is not count_u × count_v, or weights mismatch.
    #[error("{expected} control points expected, got {got} (or as many weights)")]
    PointCount {
        /// count_u × count_v.
        expected: usize,
        /// The number given.
        got: usize,
    },
    /// A weight is not positive.
    #[error("weight {index} is {value}, weights must be positive")]
    NonPositiveWeight {
        /// Position.
        index: usize,
        /// Value.
        value: String,
    },
    /// A curve's parameter range is empty or not inside its knot domain.
    #[error("the parameter range [{start}, {end}] is empty or not inside the knot domain [{domain_start}, {domain_end}]")]
    Range {
        /// Range start.
        start: String,
        /// Range end.
        end: String,
        /// Domain start.
        domain_start: String,
        /// Domain end.
        domain_end: String,
    },
    /// Degree above the supported maximum.
    #[error("degree {0} is above the supported maximum {max}", max = super::patch::MAX_PATCH_DEGREE)]
    DegreeTooHigh(usize),
}

/// A rational B-spline (NURBS) surface. Control point (i, j) is entry `i * count_v + j`.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface {
    degree: [usize; 2],
    knots: [Vec<Rational>; 2],
    counts: [usize; 2],
    points: Vec<Point3>,
    weights: Vec<Rational>,
}

/// A homogeneous control point `[wx, wy, wz, w]`.
type Hom = [Rational; 4];

pub(super) fn check_knots(
    dir: &'static str,
    degree: usize,
    points: usize,
    knots: &[Rational],
) -> Result<(), NurbsError> {
    if degree > super::patch::MAX_PATCH_DEGREE {
        return Err(NurbsError::DegreeTooHigh(degree));
    }
    if points < degree + 1 {
        return Err(NurbsError::TooFewPoints {
            dir,
            degree,
            points,
        });
    }
    let expected = points + degree + 1;
    if knots.len() != expected {
        return Err(NurbsError::KnotCount {
            dir,
            points,
            degree,
            expected,
            got: knots.len(),
        });
    }
    if let Some(index) = (1..knots.len()).find(|&i| knots[i] < knots[i - 1]) {
        return Err(NurbsError::Decreasing {
            dir,
            index,
            value: knots[index].to_string(),
        });
    }
    if knots[degree] >= knots[points] {
        return Err(NurbsError::EmptyDomain { dir });
    }
    Ok(())
}

impl NurbsSurface {
    /// A NURBS surface from degrees, knot vectors, control points (`i * count_v + j`, i along
    /// u) and positive weights.
    ///
    /// # Errors
    /// [`NurbsError`] on wrong counts, decreasing knots, an empty domain or a weight that is
    /// not positive.
    pub fn new(
        degree: [usize; 2],
        knots_u: Vec<Rational>,
        knots_v: Vec<Rational>,
        counts: [usize; 2],
        points: Vec<Point3>,
        weights: Vec<Rational>,
    ) -> Result<Self, NurbsError> {
        check_knots("u", degree[0], counts[0], &knots_u)?;
        check_knots("v", degree[1], counts[1], &knots_v)?;
        let expected = counts[0] * counts[1];
        if points.len() != expected || weights.len() != expected {
            return Err(NurbsError::PointCount {
                expected,
                got: points.len().min(weights.len()),
            });
        }
        if let Some((index, value)) = first_nonpositive(&weights) {
            return Err(NurbsError::NonPositiveWeight { index, value });
        }
        Ok(NurbsSurface {
            degree,
            knots: [knots_u, knots_v],
            counts,
            points,
            weights,
        })
    }

    /// The degree (p, q).
    pub fn degree(&self) -> [usize; 2] {
        self.degree
    }

    /// The number of control points along u and v.
    pub fn counts(&self) -> [usize; 2] {
        self.counts
    }

    /// The knot vectors (u, v).
    pub fn knots(&self) -> [&[Rational]; 2] {
        [&self.knots[0], &self.knots[1]]
    }

    /// The parameter domain `[[u0, u1], [v0, v1]]`.
    pub fn domain(&self) -> [[Rational; 2]; 2] {
        [0, 1].map(|d| {
            let (p, n) = (self.degree[d], self.counts[d]);
            [self.knots[d][p].clone(), self.knots[d][n].clone()]
        })
    }

    /// The nonempty knot spans of the domain along u and along v, in order: the Bézier piece
    /// with span indices (iu, iv) of [`Self::to_bezier`] is the surface on
    /// `spans[0][iu] × spans[1][iv]`.
    pub fn spans(&self) -> [Vec<[Rational; 2]>; 2] {
        [0, 1].map(|d| {
            let (p, n, k) = (self.degree[d], self.counts[d], &self.knots[d]);
            (p..n)
                .filter(|&i| k[i] < k[i + 1])
                .map(|i| [k[i].clone(), k[i + 1].clone()])
                .collect()
        })
    }

    fn hom(&self, i: usize, j: usize) -> Hom {
        let k = i * self.counts[1] + j;
        let w = &self.weights[k];
        let p = &self.points[k];
        [
            Rational::from(&p[0] * w),
            Rational::from(&p[1] * w),
            Rational::from(&p[2] * w),
            w.clone(),
        ]
    }

    /// The rational Bézier patches of this surface, one per nonempty knot span pair, row by
    /// row along u: exact, so each piece is the surface on its span reparameterised to
    /// `[0,1]^2` (`proofs/knot-insertion.md`). Returns the patches with their span indices.
    pub fn to_bezier(&self) -> Vec<((usize, usize), RationalPatch)> {
        let [p, q] = self.degree;
        let [nu, nv] = self.counts;
        let dom = self.domain();
        // Split along v: each row i (fixed u index) is a curve in v.
        let rows: Vec<Vec<Vec<Hom>>> = (0..nu)
            .map(|i| {
                bezier_segments(
                    q,
                    &self.knots[1],
                    &(0..nv).map(|j| self.hom(i, j)).collect::<Vec<_>>(),
                    [&dom[1][0], &dom[1][1]],
                )
                .into_iter()
                .map(|(_, segment)| segment)
                .collect()
            })
            .collect();
        let segs_v = rows.first().map_or(0, |r| r.len());
        let mut patches = Vec::new();
        // Then along u, for each v segment and each of its q + 1 columns.
        let mut columns: Vec<Vec<Vec<Vec<Hom>>>> = Vec::with_capacity(segs_v);
        for sv in 0..segs_v {
            let cols: Vec<Vec<Vec<Hom>>> = (0..=q)
                .map(|jj| {
                    let curve: Vec<Hom> = rows.iter().map(|row| row[sv][jj].clone()).collect();
                    bezier_segments(p, &self.knots[0], &curve, [&dom[0][0], &dom[0][1]])
                        .into_iter()
                        .map(|(_, segment)| segment)
                        .collect()
                })
                .collect();
            columns.push(cols);
        }
        let segs_u = columns
            .first()
            .and_then(|c| c.first())
            .map_or(0, |c| c.len());
        for su in 0..segs_u {
            for (sv, cols) in columns.iter().enumerate() {
                let mut pts = Vec::with_capacity((p + 1) * (q + 1));
                let mut ws = Vec::with_capacity((p + 1) * (q + 1));
                for ii in 0..=p {
                    for col in cols.iter() {
                        let h = &col[su][ii];
                        let w = h[3].clone();
                        pts.push([0, 1, 2].map(|c| Rational::from(&h[c] / &w)));
                        ws.push(w);
                    }
                }
                let patch = RationalPatch::new([p, q], pts, ws)
                    .expect("knot insertion keeps weights positive");
                patches.push(((su, sv), patch));
            }
        }
        patches
    }

    /// The surface in f64, converted once: for float searches (the parameters nearest a
    /// point), never for a certified value.
    pub fn to_f64(&self) -> FloatNurbs {
        let kf = |k: &[Rational]| k.iter().map(Rational::to_f64).collect::<Vec<f64>>();
        let [nu, nv] = self.counts;
        FloatNurbs {
            degree: self.degree,
            knots: [kf(&self.knots[0]), kf(&self.knots[1])],
            rows: (0..nu)
                .map(|i| {
                    (0..nv)
                        .map(|j| self.hom(i, j).map(|c| c.to_f64()))
                        .collect()
                })
                .collect(),
        }
    }

    /// The point S(u, v) by de Boor's algorithm in exact arithmetic (for tests and checks).
    ///
    /// # Panics
    /// If (u, v) is outside the parameter domain.
    pub fn eval(&self, u: &Rational, v: &Rational) -> Point3 {
        let [p, q] = self.degree;
        let [nu, nv] = self.counts;
        let dom = self.domain();
        assert!(*u >= dom[0][0] && *u <= dom[0][1] && *v >= dom[1][0] && *v <= dom[1][1]);
        let rows: Vec<Hom> = (0..nu)
            .map(|i| {
                de_boor(
                    q,
                    &self.knots[1],
                    &(0..nv).map(|j| self.hom(i, j)).collect::<Vec<_>>(),
                    v,
                )
            })
            .collect();
        let h = de_boor(p, &self.knots[0], &rows, u);
        [0, 1, 2].map(|c| Rational::from(&h[c] / &h[3]))
    }
}

/// A NURBS surface in f64 ([`NurbsSurface::to_f64`]).
#[derive(Clone, Debug)]
pub struct FloatNurbs {
    degree: [usize; 2],
    knots: [Vec<f64>; 2],
    rows: Vec<Vec<[f64; 4]>>,
}

impl FloatNurbs {
    /// The point S(u, v) in f64, (u, v) clamped to the domain.
    pub fn eval(&self, u: f64, v: f64) -> [f64; 3] {
        let [p, q] = self.degree;
        let column: Vec<[f64; 4]> = self
            .rows
            .iter()
            .map(|row| super::knots::de_boor_f64(q, &self.knots[1], row, v))
            .collect();
        let h = super::knots::de_boor_f64(p, &self.knots[0], &column, u);
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Rational {
        Rational::from((n, d))
    }

    /// A bicubic-by-quadratic surface with interior knots, unclamped ends in v (a double
    /// interior knot) and varied weights; its domain is [0, 4] × [0, 1].
    fn varied_surface() -> NurbsSurface {
        let (p, qd) = (3, 2);
        let (nu, nv) = (6, 5);
        let ku: Vec<Rational> = [0, 0, 0, 0, 1, 3, 4, 4, 4, 4]
            .iter()
            .map(|&k| q(k, 1))
            .collect();
        // Unclamped in v, with a double interior knot.
        let kv: Vec<Rational> = [-2, -1, 0, 1, 1, 2, 3, 4]
            .iter()
            .map(|&k| q(k, 2))
            .collect();
        let mut pts = Vec::new();
        let mut ws = Vec::new();
        for i in 0..nu {
            for j in 0..nv {
                pts.push([
                    q(i as i64, 1),
                    q(j as i64, 1),
                    q(((i * 7 + j * 3) % 5) as i64, 3),
                ]);
                ws.push(q(1 + ((i + 2 * j) % 3) as i64, 2));
            }
        }
        NurbsSurface::new([p, qd], ku, kv, [nu, nv], pts, ws).unwrap()
    }

    /// Every Bézier piece evaluates exactly to the NURBS surface.
    #[test]
    fn bezier_pieces_are_exact() {
        let s = varied_surface();
        let pieces = s.to_bezier();
        let su: Vec<(Rational, Rational)> =
            vec![(q(0, 1), q(1, 1)), (q(1, 1), q(3, 1)), (q(3, 1), q(4, 1))];
        // Domain [t_2, t_5] = [0, 1] with the double knot 1/2 inside.
        let sv: Vec<(Rational, Rational)> = vec![(q(0, 1), q(1, 2)), (q(1, 2), q(1, 1))];
        assert_eq!(pieces.len(), su.len() * sv.len());
        for ((iu, iv), patch) in &pieces {
            let (a, b) = &su[*iu];
            let (c, d) = &sv[*iv];
            for (s0, t0) in [
                (q(0, 1), q(0, 1)),
                (q(1, 3), q(2, 5)),
                (q(1, 1), q(1, 1)),
                (q(5, 7), q(1, 9)),
            ] {
                let u = a + &s0 * Rational::from(b - a);
                let v = c + &t0 * Rational::from(d - c);
                assert_eq!(
                    patch.eval(&s0, &t0),
                    s.eval(&u, &v),
                    "piece ({iu},{iv}) at ({s0},{t0})"
                );
            }
        }
    }

    /// The f64 copy agrees with the exact evaluation to rounding, inside, on the domain's
    /// corners and at the double knot; parameters outside are clamped to the domain.
    #[test]
    fn float_evaluation_matches_the_exact_one() {
        let s = varied_surface();
        let f = s.to_f64();
        let close = |a: [f64; 3], b: &Point3| {
            a.iter()
                .zip(b)
                .all(|(x, y)| (x - y.to_f64()).abs() <= 1e-13 * (1.0 + y.to_f64().abs()))
        };
        for (u, v) in [
            (q(0, 1), q(0, 1)),
            (q(4, 1), q(1, 1)),
            (q(4, 1), q(0, 1)),
            (q(1, 1), q(1, 2)),
            (q(7, 3), q(2, 9)),
            (q(3, 1), q(3, 4)),
            (q(1, 10), q(99, 100)),
        ] {
            let exact = s.eval(&u, &v);
            let got = f.eval(u.to_f64(), v.to_f64());
            assert!(
                close(got, &exact),
                "at ({u}, {v}): {got:?} against {exact:?}"
            );
        }
        assert!(close(f.eval(-1.0, 0.5), &s.eval(&q(0, 1), &q(1, 2))));
        assert!(close(f.eval(9.0, 2.0), &s.eval(&q(4, 1), &q(1, 1))));
    }

    #[test]
    fn evaluation_at_the_domain_end_with_a_repeated_end_knot() {
        // Knots [0, 0, 1, 1, 1] for degree 1: the last span is empty.
        let k = |v: &[i64]| v.iter().map(|&x| q(x, 1)).collect::<Vec<_>>();
        let pts: Vec<_> = (0..6).map(|i| [q(i, 1), q(i * i, 1), q(0, 1)]).collect();
        let s = NurbsSurface::new(
            [1, 1],
            k(&[0, 0, 1, 1, 1]),
            k(&[0, 0, 1, 1]),
            [3, 2],
            pts,
            vec![q(1, 1); 6],
        )
        .unwrap();
        let p = s.eval(&q(1, 1), &q(0, 1));
        // The end of the curve in u is the second control row (the third is never reached).
        assert_eq!(p, [q(2, 1), q(4, 1), q(0, 1)]);
    }

    #[test]
    fn malformed_surfaces_are_refused() {
        let k = |v: &[i64]| v.iter().map(|&x| q(x, 1)).collect::<Vec<_>>();
        let pts = vec![[q(0, 1), q(0, 1), q(0, 1)]; 4];
        let ws = vec![q(1, 1); 4];
        assert!(NurbsSurface::new(
            [1, 1],
            k(&[0, 0, 1, 1]),
            k(&[0, 0, 1, 1]),
            [2, 2],
            pts.clone(),
            ws.clone()
        )
        .is_ok());
        assert!(matches!(
            NurbsSurface::new(
                [1, 1],
                k(&[0, 0, 1]),
                k(&[0, 0, 1, 1]),
                [2, 2],
                pts.clone(),
                ws.clone()
            ),
            Err(NurbsError::KnotCount { .. })
        ));
        assert!(matches!(
            NurbsSurface::new(
                [1, 1],
                k(&[0, 1, 0, 1]),
                k(&[0, 0, 1, 1]),
                [2, 2],
                pts.clone(),
                ws.clone()
            ),
            Err(NurbsError::Decreasing { .. })
        ));
        assert!(matches!(
            NurbsSurface::new(
                [1, 1],
                k(&[0, 1, 1, 1]),
                k(&[0, 0, 1, 1]),
                [2, 2],
                pts.clone(),
                ws.clone()
            ),
            Err(NurbsError::EmptyDomain { .. })
        ));
        let mut bad = ws.clone();
        bad[2] = q(0, 1);
        assert!(matches!(
            NurbsSurface::new([1, 1], k(&[0, 0, 1, 1]), k(&[0, 0, 1, 1]), [2, 2], pts, bad),
            Err(NurbsError::NonPositiveWeight { index: 2, .. })
        ));
    }
}
