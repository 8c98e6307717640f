//! Trimmed faces: a surface of the model restricted to the region its trimming loops bound in
//! its parameter plane. A loop is a closed chain of exact rational curves in the surface's
//! parameter plane (the knot domain of the NURBS surface, not the `[0,1]²` of its Bézier
//! pieces); the region of a face is the set of points of the domain inside the outer loop (the
//! domain's boundary when there is none) and outside every inner loop, by the even-odd rule, so
//! it does not depend on the loops' orientation. The orientation is still proven (signed area)
//! and reported, because files state it and a wrong one is a sign of a broken file.
//!
//! Real files write the end of one trimming curve and the start of the next separately, in
//! decimal: they differ in the last digits. A loop is closed by exact straight bridges across
//! gaps up to [`Closing::tolerance`], or along a side of the domain the surface collapses to a
//! point, each bridge recorded; a larger gap is an error.

use crate::bernstein::Bernstein;
use crate::number::{Interval, Number, Precision, Rational};
use crate::surface::ParameterCurve;
use std::cmp::Ordering;

/// One curve of a loop.
#[derive(Clone, Debug, PartialEq)]
pub struct TrimPiece {
    /// The curve, in the surface's parameter plane, in the loop's direction.
    pub curve: ParameterCurve,
    /// The B-rep edge it lies on ([`super::Brep::edges`]), if the file has a B-rep.
    pub edge: Option<usize>,
    /// A straight segment limn added across a gap between two curves of the file.
    pub bridge: bool,
}

/// The orientation of a loop in the (u, v) plane, as proven by its signed area.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Orientation {
    /// Positive signed area.
    CounterClockwise,
    /// Negative signed area.
    Clockwise,
    /// The enclosure of the signed area contains 0 (a degenerate or self-crossing loop).
    Undecided,
}

/// A closed chain of curves in a surface's parameter plane.
#[derive(Clone, Debug, PartialEq)]
pub struct TrimLoop {
    /// The curves, each ending exactly where the next starts, the last where the first starts.
    pub pieces: Vec<TrimPiece>,
    /// The file's entity for this loop (IGES: directory entry of the 142 or 508).
    pub entity: Option<usize>,
    /// The orientation, proven.
    pub orientation: Orientation,
    /// The largest gap bridged straight, in the max norm of (u, v) (0 when the file's curves
    /// join exactly).
    pub largest_gap: f64,
    /// Gaps bridged along a collapsed side of the domain ([`Closing::collapsed`]).
    pub side_bridges: usize,
    /// Curves limn made by inverting a model-space edge onto the surface (the file gives the
    /// edge without a parameter-space curve on this face; `proofs/edge-inversion.md`).
    pub inverted_curves: usize,
    /// The proven bound (max norm, model space) between those curves' points on the surface
    /// and their edges' points (0 when there are none).
    pub inversion_distance: f64,
}

/// Why a chain of curves is not a loop.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LoopError {
    /// No curves.
    #[error("the loop has no curves")]
    Empty,
    /// Curve `after` (0-based) ends away from where the next one starts.
    #[error("curve {} ends at ({}, {}) but curve {} starts at ({}, {}): a gap of {gap:.3e}, more than the tolerance {tolerance:.3e} and not along a collapsed side of the surface (the loop does not close)", after + 1, end[0], end[1], next + 1, start[0], start[1])]
    Gap {
        /// The curve before the gap.
        after: usize,
        /// The curve after the gap.
        next: usize,
        /// Its end point, rounded.
        end: [f64; 2],
        /// The next one's start, rounded.
        start: [f64; 2],
        /// The gap, max norm.
        gap: f64,
        /// The tolerance.
        tolerance: f64,
    },
}

/// The max-norm distance of two points, exact.
fn gap(a: &[Rational], b: &[Rational]) -> Rational {
    a.iter()
        .zip(b)
        .map(|(x, y)| Rational::from(x - y).abs())
        .max()
        .unwrap_or_default()
}

/// How a chain of curves is closed into a loop.
#[derive(Clone, Debug)]
pub struct Closing<'a> {
    /// Gaps up to this (max norm in (u, v)) are bridged by straight segments.
    pub tolerance: Rational,
    /// The surface's parameter domain.
    pub domain: &'a [[Rational; 2]; 2],
    /// The sides of the domain (u = u0, u = u1, v = v0, v = v1) the surface collapses to a
    /// point (a cone's apex, a sphere's pole). A larger gap whose two ends lie on one of them
    /// (within the tolerance) is bridged along that side: the surface maps the bridge to the
    /// point, so the loop closes in model space.
    pub collapsed: [bool; 4],
}

impl Closing<'_> {
    /// The side (0..4) both points lie on within the tolerance, if it is collapsed.
    fn collapsed_side(&self, a: &[Rational], b: &[Rational]) -> Option<usize> {
        (0..4).find(|&side| {
            let (c, value) = (side / 2, &self.domain[side / 2][side % 2]);
            self.collapsed[side]
                && Rational::from(&a[c] - value).abs() <= self.tolerance
                && Rational::from(&b[c] - value).abs() <= self.tolerance
        })
    }
}

impl TrimLoop {
    /// The loop through `curves` in order (with their edges), closed as `closing` allows:
    /// straight bridges across gaps of at most its tolerance, and bridges along collapsed
    /// sides of the domain.
    ///
    /// # Errors
    /// [`LoopError`] when there are no curves, or two consecutive curves (the last and the
    /// first included) are further apart than the tolerance and not on one collapsed side.
    pub fn close(
        curves: Vec<(ParameterCurve, Option<usize>)>,
        closing: &Closing,
        entity: Option<usize>,
    ) -> Result<TrimLoop, LoopError> {
        if curves.is_empty() {
            return Err(LoopError::Empty);
        }
        let tolerance = &closing.tolerance;
        let n = curves.len();
        let mut pieces = Vec::with_capacity(n);
        let mut largest = Rational::new();
        let mut side_bridges = 0;
        let bridge = |a: &[Rational], b: &[Rational]| TrimPiece {
            curve: ParameterCurve::segment(a, b),
            edge: None,
            bridge: true,
        };
        for (i, (curve, edge)) in curves.iter().enumerate() {
            pieces.push(TrimPiece {
                curve: curve.clone(),
                edge: *edge,
                bridge: false,
            });
            let next = &curves[(i + 1) % n].0;
            let (end, start) = (curve.end(), next.start());
            let g = gap(&end, &start);
            if g == 0 {
                continue;
            }
            if g <= *tolerance {
                if g > largest {
                    largest = g;
                }
                pieces.push(bridge(&end, &start));
                continue;
            }
            let Some(side) = closing.collapsed_side(&end, &start) else {
                let f = |p: &[Rational]| [p[0].to_f64(), p[1].to_f64()];
                return Err(LoopError::Gap {
                    after: i,
                    next: (i + 1) % n,
                    end: f(&end),
                    start: f(&start),
                    gap: g.to_f64(),
                    tolerance: tolerance.to_f64(),
                });
            };
            // end -> its foot on the side -> the start's foot -> start.
            let c = side / 2;
            let value = &closing.domain[c][side % 2];
            let foot = |p: &[Rational]| {
                let mut q = p.to_vec();
                q[c] = value.clone();
                q
            };
            let path = [end.clone(), foot(&end), foot(&start), start.clone()];
            for w in path.windows(2) {
                if w[0] != w[1] {
                    let g = gap(&w[0], &w[1]);
                    if !(w[0] == path[1] && w[1] == path[2]) && g > largest {
                        largest = g;
                    }
                    pieces.push(bridge(&w[0], &w[1]));
                }
            }
            side_bridges += 1;
        }
        let orientation = orientation(pieces.iter().map(|p| &p.curve));
        Ok(TrimLoop {
            pieces,
            entity,
            orientation,
            largest_gap: largest.to_f64(),
            side_bridges,
            inverted_curves: 0,
            inversion_distance: 0.0,
        })
    }

    /// The number of straight bridges limn added.
    pub fn bridges(&self) -> usize {
        self.pieces.iter().filter(|p| p.bridge).count()
    }
}

/// The deepest bisection of a rational piece when its signed area is enclosed (2^10 parts).
const AREA_DEPTH: u32 = 10;

/// The orientation of a closed chain of curves, from an enclosure of its signed area
/// `½ ∮ (u dv − v du) = ½ Σ ∫₀¹ (U V' − V U') / W² dt` (`proofs/trimmed-faces.md`): exact for
/// polynomial pieces (the integral of a Bernstein polynomial over [0, 1] is the mean of its
/// coefficients); for rational pieces the integrand's numerator and `W` are enclosed by their
/// Bernstein hulls on 2^k equal parts, `k` growing until the sign is decided or
/// 10 is reached.
pub fn orientation<'a>(curves: impl Iterator<Item = &'a ParameterCurve>) -> Orientation {
    let mut exact = Rational::new();
    let mut rational: Vec<(Bernstein<Interval>, Bernstein<Interval>)> = Vec::new();
    for c in curves {
        let [u, v, w] = [0, 1, 2].map(|k| c.coordinate(k));
        let p = u
            .try_mul(&v.deriv(0))
            .and_then(|a| a.try_sub(&v.try_mul(&u.deriv(0))?))
            .expect("univariate products of equal degree");
        if c.is_polynomial() {
            // W is the constant w: ∫ P / w² = mean(P) / w².
            let w0 = &c.homogeneous()[0][2];
            let sum: Rational = p.coeffs().iter().sum();
            let n = p.coeffs().len() as u64;
            exact += sum / Rational::from(n) / Rational::from(w0 * w0);
        } else {
            rational.push((p.convert(Precision(53)), w.convert(Precision(53))));
        }
    }
    let decided = |x: Interval| match (x.lo() > 0.0, x.hi() < 0.0) {
        (true, _) => Some(Orientation::CounterClockwise),
        (_, true) => Some(Orientation::Clockwise),
        _ => None,
    };
    let base = Interval::from_rational(&exact, Precision(53));
    if rational.is_empty() {
        return match exact.cmp0() {
            Ordering::Greater => Orientation::CounterClockwise,
            Ordering::Less => Orientation::Clockwise,
            Ordering::Equal => Orientation::Undecided,
        };
    }
    for depth in 0..=AREA_DEPTH {
        let parts = 1u32 << depth;
        let mut total = base;
        let mut finite = true;
        for (p, w) in &rational {
            for k in 0..parts {
                let (a, b) = (
                    Interval::point(f64::from(k) / f64::from(parts)),
                    Interval::point(f64::from(k + 1) / f64::from(parts)),
                );
                let (ph, wh) = (p.restrict(0, &a, &b).hull(), w.restrict(0, &a, &b).hull());
                // W > 0 on [0, 1]; its enclosure must show it to bound 1 / W².
                let r = if wh.lo() > 0.0 {
                    wh.mul(&wh).recip()
                } else {
                    None
                };
                let Some(r) = r else {
                    finite = false;
                    break;
                };
                let width = Interval::point(1.0 / f64::from(parts));
                total = total.add(&ph.mul(&r).mul(&width));
            }
        }
        if finite {
            if let Some(o) = decided(total) {
                return o;
            }
        }
    }
    Orientation::Undecided
}

/// A face: a surface of the model restricted to its trimming loops.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    /// The surface (its index among the model's surfaces, as in
    /// [`super::PatchSource::surface`]).
    pub surface: usize,
    /// The file's entity for the face (IGES: directory entry of the 144, 143 or 510).
    pub entity: Option<usize>,
    /// The surface's parameter domain `[[u0, u1], [v0, v1]]`, in which the loops are given.
    pub domain: [[Rational; 2]; 2],
    /// The outer loop; `None` when it is the boundary of the domain.
    pub outer: Option<TrimLoop>,
    /// The inner loops (holes).
    pub inner: Vec<TrimLoop>,
}

impl Face {
    /// Every loop, the outer first.
    pub fn loops(&self) -> impl Iterator<Item = &TrimLoop> {
        self.outer.iter().chain(&self.inner)
    }
}

/// Whether every point of a curve lies in the closed domain `[[u0, u1], [v0, v1]]`, or how far
/// outside a point of it provably lies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InDomain {
    /// Every point is inside (Bernstein coefficients of `U − u0 W` etc. are nonnegative).
    Inside,
    /// A point of the curve lies outside by at least this much along one coordinate, proven by
    /// its exact value.
    Outside(f64),
    /// Neither could be shown within the subdivision depth (the curve touches the boundary).
    Undecided,
}

/// The deepest subdivision of a curve when its place in the domain is decided (2^6 parts).
const DOMAIN_DEPTH: u32 = 6;

/// Decides [`InDomain`] for a curve: for each side, e.g. `u ≥ u0 ⟺ U − u0 W ≥ 0` (W > 0), the
/// Bernstein coefficients of the side's polynomial on halves of the parameter interval, exact;
/// all nonnegative proves the side, a negative end coefficient (a value of the curve) proves a
/// point outside.
pub fn in_domain(curve: &ParameterCurve, domain: &[[Rational; 2]; 2]) -> InDomain {
    let w = curve.coordinate(2);
    let sides = [
        curve.offset(0, &domain[0][0]),
        curve.offset(0, &domain[0][1]).neg(),
        curve.offset(1, &domain[1][0]),
        curve.offset(1, &domain[1][1]).neg(),
    ];
    let mut worst = 0.0f64;
    let mut undecided = false;
    for g in sides {
        let mut stack = vec![(g, 0u32)];
        while let Some((g, depth)) = stack.pop() {
            let c = g.coeffs();
            if c.iter().all(|x| x.cmp0() != Ordering::Less) {
                continue;
            }
            // The end coefficients are the values of g at the ends of this part: a negative
            // one is a point of the curve outside, by -g / W along this coordinate, at least
            // -g / max W (W is at most its largest coefficient, and positive).
            let lowest = c[0].clone().min(c[c.len() - 1].clone());
            if lowest.cmp0() == Ordering::Less {
                let wmax = w.coeffs().iter().max().cloned().unwrap_or_default();
                worst = worst.max(((-lowest) / wmax).to_f64());
                continue;
            }
            if depth >= DOMAIN_DEPTH {
                undecided = true;
                continue;
            }
            let (a, b) = g.subdivide_half(0);
            stack.push((a, depth + 1));
            stack.push((b, depth + 1));
        }
    }
    if worst > 0.0 {
        InDomain::Outside(worst)
    } else if undecided {
        InDomain::Undecided
    } else {
        InDomain::Inside
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Rational {
        Rational::from((n, d))
    }

    fn pt(u: i64, v: i64) -> Vec<Rational> {
        vec![q(u, 1), q(v, 1)]
    }

    fn square(ccw: bool) -> Vec<(ParameterCurve, Option<usize>)> {
        let mut c = [pt(0, 0), pt(1, 0), pt(1, 1), pt(0, 1)];
        if !ccw {
            c.reverse();
        }
        (0..4)
            .map(|i| (ParameterCurve::segment(&c[i], &c[(i + 1) % 4]), None))
            .collect()
    }

    /// A quarter of the unit circle as a rational quadratic (weights 1, 1, 2: the unbalanced
    /// exact form, w1² / (w0 w2) = cos²(π/4)).
    fn quarter_circle() -> ParameterCurve {
        ParameterCurve::new(
            &[pt(1, 0), pt(1, 1), pt(0, 1)],
            &[q(1, 1), q(1, 1), q(2, 1)],
        )
        .unwrap()
    }

    fn unit() -> [[Rational; 2]; 2] {
        [[q(0, 1), q(1, 1)], [q(0, 1), q(1, 1)]]
    }

    fn closing(domain: &[[Rational; 2]; 2], tolerance: Rational) -> Closing<'_> {
        Closing {
            tolerance,
            domain,
            collapsed: [false; 4],
        }
    }

    #[test]
    fn orientation_of_polygons_and_rational_loops_is_proven() {
        let dom = unit();
        let tol = closing(&dom, Rational::new());
        assert_eq!(
            TrimLoop::close(square(true), &tol, None)
                .unwrap()
                .orientation,
            Orientation::CounterClockwise
        );
        assert_eq!(
            TrimLoop::close(square(false), &tol, None)
                .unwrap()
                .orientation,
            Orientation::Clockwise
        );
        // A quarter disc: the arc, then back along the axes; area π/4 > 0.
        let arc = quarter_circle();
        let disc = vec![
            (arc.clone(), None),
            (ParameterCurve::segment(&pt(0, 1), &pt(0, 0)), None),
            (ParameterCurve::segment(&pt(0, 0), &pt(1, 0)), None),
        ];
        let l = TrimLoop::close(disc, &tol, None).unwrap();
        assert_eq!(l.orientation, Orientation::CounterClockwise);
        // The same arc reversed closed by the chord: the circular segment between the arc and
        // the chord, area π/4 − 1/2 ≈ 0.285, clockwise.
        let segment = vec![
            (ParameterCurve::segment(&pt(1, 0), &pt(0, 1)), None),
            (arc.reversed(), None),
        ];
        let l = TrimLoop::close(segment, &tol, None).unwrap();
        assert_eq!(l.orientation, Orientation::Clockwise);
        // A loop with no area is undecided, never guessed.
        let flat = vec![
            (ParameterCurve::segment(&pt(0, 0), &pt(1, 0)), None),
            (ParameterCurve::segment(&pt(1, 0), &pt(0, 0)), None),
        ];
        assert_eq!(
            TrimLoop::close(flat, &tol, None).unwrap().orientation,
            Orientation::Undecided
        );
    }

    #[test]
    fn gaps_are_bridged_within_the_tolerance_and_refused_beyond() {
        let dom = unit();
        let mut c = square(true);
        // Move the start of the third side by 1e-9.
        let off = vec![q(1, 1) + q(1, 1_000_000_000), q(1, 1)];
        c[2].0 = ParameterCurve::segment(&off, &pt(0, 1));
        let l = TrimLoop::close(c.clone(), &closing(&dom, q(1, 1_000_000)), None).unwrap();
        assert_eq!(l.bridges(), 1);
        assert_eq!(l.pieces.len(), 5);
        assert!((l.largest_gap - 1e-9).abs() < 1e-18);
        for (i, p) in l.pieces.iter().enumerate() {
            assert_eq!(p.curve.end(), l.pieces[(i + 1) % 5].curve.start());
        }
        let e = TrimLoop::close(c, &closing(&dom, q(1, 10_000_000_000)), None).unwrap_err();
        assert!(
            matches!(
                e,
                LoopError::Gap {
                    after: 1,
                    next: 2,
                    ..
                }
            ),
            "{e}"
        );
        assert_eq!(
            TrimLoop::close(Vec::new(), &closing(&dom, q(1, 1)), None).unwrap_err(),
            LoopError::Empty
        );
    }

    /// A cone's side in its parameter plane: the circle at v = 0, the seam up, the seam down;
    /// the gap along v = 1 (the apex) is bridged when that side is collapsed, refused if not.
    #[test]
    fn gaps_along_a_collapsed_side_are_bridged_along_it() {
        let dom = unit();
        let tiny = q(1, 1_000_000_000);
        let near_top = vec![q(1, 1), q(1, 1) - &tiny];
        let c = vec![
            (ParameterCurve::segment(&pt(0, 0), &pt(1, 0)), None),
            (ParameterCurve::segment(&pt(1, 0), &near_top), None),
            (ParameterCurve::segment(&pt(0, 1), &pt(0, 0)), None),
        ];
        let mut apex = closing(&dom, q(1, 1_000_000));
        assert!(matches!(
            TrimLoop::close(c.clone(), &apex, None),
            Err(LoopError::Gap { after: 1, .. })
        ));
        apex.collapsed[3] = true;
        let l = TrimLoop::close(c, &apex, None).unwrap();
        assert_eq!(l.side_bridges, 1);
        // The short step up to the side, then along it: two bridges.
        assert_eq!(l.bridges(), 2);
        assert!((l.largest_gap - 1e-9).abs() < 1e-18);
        assert_eq!(l.orientation, Orientation::CounterClockwise);
        for (i, p) in l.pieces.iter().enumerate() {
            assert_eq!(
                p.curve.end(),
                l.pieces[(i + 1) % l.pieces.len()].curve.start()
            );
        }
    }

    #[test]
    fn curves_inside_and_outside_the_domain() {
        let dom = [[q(0, 1), q(1, 1)], [q(0, 1), q(1, 1)]];
        // The arc's control point (1, 1) is a corner: inside by its hull.
        assert_eq!(in_domain(&quarter_circle(), &dom), InDomain::Inside);
        // A parabola through (0, 0), control (1/2, 2), (1, 0): its top touches v = 1 at
        // t = 1/2, and 1 - v = (1 - 2t)^2 shows nonnegative coefficients on both halves.
        let touch = ParameterCurve::new(
            &[pt(0, 0), vec![q(1, 2), q(2, 1)], pt(1, 0)],
            &vec![q(1, 1); 3],
        )
        .unwrap();
        assert_eq!(in_domain(&touch, &dom), InDomain::Inside);
        // v = 4t^2 - 4t^4 touches v = 1 at the irrational t = 1/sqrt 2 (1 - v = (2t^2 - 1)^2):
        // no subdivision shows it, and it is reported undecided, never guessed.
        let irrational = ParameterCurve::new(
            &[
                pt(0, 0),
                vec![q(1, 4), q(0, 1)],
                vec![q(1, 2), q(2, 3)],
                vec![q(3, 4), q(2, 1)],
                pt(1, 0),
            ],
            &vec![q(1, 1); 5],
        )
        .unwrap();
        assert_eq!(in_domain(&irrational, &dom), InDomain::Undecided);
        // With control (1/2, 3) the top v = 3/2 is outside by 1/2 (proven at the midpoint).
        let out = ParameterCurve::new(
            &[pt(0, 0), vec![q(1, 2), q(3, 1)], pt(1, 0)],
            &vec![q(1, 1); 3],
        )
        .unwrap();
        match in_domain(&out, &dom) {
            InDomain::Outside(by) => assert!(by > 0.0 && by <= 0.5, "{by}"),
            other => panic!("{other:?}"),
        }
    }
}
