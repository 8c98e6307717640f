//! Whether a point of a surface's parameter plane lies in a trimmed face: the even-odd count
//! of the crossings of a ray with the face's loops, each crossing a certified root
//! (`proofs/trimmed-faces.md`, "Point in face").
//!
//! The ray from `(u0, v0)` runs towards `+u` along the line `v = v0 + ε`, and a crossing counts
//! when it lies at `u > u0 + ε²`, for an infinitesimal `ε > 0` (simulation of simplicity): a
//! loop vertex on the line, a tangency, a piece along the line and a point on a loop are then
//! all counted by one convention, so every point gets an answer, the same one for the same
//! input. Only what the root isolation or the interval bounds cannot separate is undecided.

use crate::bernstein::Bernstein;
use crate::model::{Face, TrimLoop};
use crate::number::{Interval, Number, Precision, Rational};
use crate::solver::dyadic::Dyadic;
use crate::solver::precision::{Escalations, Ladder, Policy};
use crate::solver::univariate::{isolate_roots, refine_root, Root};
use std::cmp::Ordering;

/// Where a point is with respect to a face.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Membership {
    /// In the face's region (by the convention above for points on its loops).
    Inside,
    /// Not in it.
    Outside,
    /// A crossing could not be placed on either side of the point (the point lies within the
    /// isolation's resolution of a loop, about 2⁻⁴⁰ of a curve's parameter).
    Undecided,
}

/// How finely a crossing is isolated before it is called undecided.
const ROOT_WIDTH: f64 = 1e-12;

/// The sign of `x` at the perturbed point: `x`'s sign, and negative for 0 (the perturbed
/// coordinate is larger by an infinitesimal, and `W > 0`).
fn perturbed_sign(x: &Rational) -> Ordering {
    match x.cmp0() {
        Ordering::Equal => Ordering::Less,
        s => s,
    }
}

/// The parity of the crossings of the ray from `p` with one loop, or `None` if undecided.
fn loop_parity(l: &TrimLoop, p: &[Rational], policy: &mut Policy) -> Option<bool> {
    let mut odd = false;
    for piece in &l.pieces {
        // g = V − v0 W (its sign is that of v − v0), h = U − u0 W (that of u − u0).
        let (g, h) = (piece.curve.offset(1, &p[1]), piece.curve.offset(0, &p[0]));
        let at = |f: &Bernstein<Rational>, t: &Rational| f.eval(std::slice::from_ref(t));
        let roots = isolate_roots(&g, 60, policy);
        if !roots.unresolved.is_empty() {
            return None;
        }
        if roots.identically_zero {
            // Along the line v = v0: the perturbed line passes above it, no crossing.
            continue;
        }
        // Exact roots at the ends, in case the isolation leaves them to its caller.
        let mut list = roots.roots.clone();
        for end in [Dyadic::ZERO, Dyadic::ONE] {
            let here = list
                .iter()
                .any(|r| matches!(r, Root::At { t } if *t == end));
            if !here && at(&g, &end.to_rational()).cmp0() == Ordering::Equal {
                list.push(Root::At { t: end });
            }
        }
        list.sort_by_key(|r| r.lo().to_rational());
        // `current`: the sign of g on the open interval before the next root (nonzero there).
        let mut current = perturbed_sign(&at(&g, &Rational::new()));
        for (k, r) in list.iter().enumerate() {
            match *r {
                Root::Between { .. } => {
                    // One simple root: g (and the perturbed g) changes sign once there.
                    if crossing_side(&h, *r, &g, policy)? {
                        odd = !odd;
                    }
                    current = current.reverse();
                }
                Root::At { t } => {
                    // g(x) = 0: the perturbed g is negative at x; it crosses near C(x) when
                    // the sign before x or after x is positive, on the side h(x) says.
                    let x = t.to_rational();
                    let right = perturbed_sign(&at(&h, &x)) == Ordering::Greater;
                    if x > 0 && current == Ordering::Greater && right {
                        odd = !odd;
                    }
                    if x < 1 {
                        let next = list
                            .get(k + 1)
                            .map_or_else(|| Rational::from(1), |n| n.lo().to_rational());
                        let mid = Rational::from(&x + &next) / 2;
                        current = perturbed_sign(&at(&g, &mid));
                        if current == Ordering::Greater && right {
                            odd = !odd;
                        }
                    }
                }
            }
        }
    }
    Some(odd)
}

/// Whether the crossing at the simple root of `g` in `r` lies at `u > u0` (`h > 0` there):
/// the interval hull of `h` on the root's interval, narrowed until its sign is decided.
fn crossing_side(
    h: &Bernstein<Rational>,
    mut r: Root,
    g: &Bernstein<Rational>,
    policy: &mut Policy,
) -> Option<bool> {
    if h.coeffs().iter().all(|c| c.cmp0() == Ordering::Equal) {
        // u = u0 along the whole piece: the perturbed u0 + ε² lies to its right.
        return Some(false);
    }
    let hi = h.convert::<Interval>(Precision(53));
    let mut width = 1e-3;
    loop {
        let (a, b) = (r.lo(), r.hi());
        let range = hull_on(&hi, a, b);
        if range.lo() > 0.0 {
            return Some(true);
        }
        if range.hi() < 0.0 {
            return Some(false);
        }
        if let Root::At { t } = r {
            return Some(perturbed_sign(&h.eval(&[t.to_rational()])) == Ordering::Greater);
        }
        if width < ROOT_WIDTH {
            return None;
        }
        r = refine_root(g, r, width, policy);
        width *= 1e-3;
    }
}

/// The hull of `p` on `[a, b]` (dyadic ends, exact in f64).
fn hull_on(p: &Bernstein<Interval>, a: Dyadic, b: Dyadic) -> Interval {
    p.restrict(
        0,
        &Interval::point(a.to_f64()),
        &Interval::point(b.to_f64()),
    )
    .hull()
}

/// Whether `p` (in the surface's parameter plane) lies in `face`: in the domain (half-open by
/// the same convention), inside the outer loop (or the domain's boundary) and outside every
/// inner loop, by the even-odd rule.
pub fn point_in_face(face: &Face, p: &[Rational]) -> Membership {
    let d = &face.domain;
    // u0 + ε² in [d00, d01]: u0 >= d00 and u0 < d01; likewise v.
    if p[0] < d[0][0] || p[0] >= d[0][1] || p[1] < d[1][0] || p[1] >= d[1][1] {
        return Membership::Outside;
    }
    let ladder = Ladder::default();
    let mut counts = Escalations::default();
    let mut policy = Policy::new(&ladder, &mut counts);
    let mut inside = true;
    for l in face.loops() {
        match loop_parity(l, p, &mut policy) {
            None => return Membership::Undecided,
            // Inside the outer loop is odd; inside a hole is odd too, and flips.
            Some(odd) => {
                let in_outer = face.outer.as_ref().is_some_and(|o| std::ptr::eq(o, l));
                if in_outer && !odd || !in_outer && odd {
                    inside = false;
                }
            }
        }
    }
    if inside {
        Membership::Inside
    } else {
        Membership::Outside
    }
}

/// How deep a loop piece is bisected before it is said to meet a box.
const MISS_DEPTH: u32 = 12;

/// An outward enclosure in `(u, v)` of a parameter-plane curve `(U, V, W)` over `[t0, t1]`
/// (its value when `t0 = t1`), or `None` when `W` is not proven positive there.
pub(crate) fn curve_box(
    c: &[Bernstein<Rational>; 3],
    t0: &Rational,
    t1: &Rational,
) -> Option<crate::geometry::Rect> {
    let h: Vec<Interval> = c
        .iter()
        .map(|x| {
            if t0 == t1 {
                Interval::from_rational(&x.eval(std::slice::from_ref(t0)), Precision::F64)
            } else {
                x.restrict_rational(0, t0, t1)
                    .convert::<Interval>(Precision::F64)
                    .hull()
            }
        })
        .collect();
    if h[2].lo() <= 0.0 {
        return None;
    }
    let u = h[0].checked_div(&h[2])?;
    let v = h[1].checked_div(&h[2])?;
    Some(crate::geometry::Rect::from_axes(
        [u.lo(), u.hi()],
        [v.lo(), v.hi()],
    ))
}

/// Whether the rational curve with homogeneous coordinates `c = (U, V, W)` (enclosed, `W > 0`)
/// provably misses the closed box `b = [[u0, u1], [v0, v1]]`: the curve lies in the hull of
/// its projected control points (positive weights), so it misses the box when that hull's
/// bounding box does, tried on the halves of the parameter down to [`MISS_DEPTH`]
/// (`proofs/trimmed-faces.md`, 7).
pub(crate) fn curve_misses_box(c: &[Bernstein<Interval>; 3], b: &[[f64; 2]; 2]) -> bool {
    piece_misses(c, b, MISS_DEPTH)
}

fn piece_misses(c: &[Bernstein<Interval>; 3], b: &[[f64; 2]; 2], depth: u32) -> bool {
    let n = c[2].coeffs().len();
    let mut bbox = [[f64::INFINITY, f64::NEG_INFINITY]; 2];
    let mut bounded = true;
    for k in 0..n {
        let w = c[2].coeffs()[k];
        for (axis, side) in bbox.iter_mut().enumerate() {
            match c[axis].coeffs()[k].checked_div(&w).filter(|_| w.lo() > 0.0) {
                Some(x) => {
                    side[0] = side[0].min(x.lo());
                    side[1] = side[1].max(x.hi());
                }
                None => bounded = false,
            }
        }
    }
    if bounded && (0..2).any(|a| bbox[a][1] < b[a][0] || bbox[a][0] > b[a][1]) {
        return true;
    }
    if depth == 0 {
        return false;
    }
    let halves = c.clone().map(|x| x.subdivide_half(0));
    let left = [
        halves[0].0.clone(),
        halves[1].0.clone(),
        halves[2].0.clone(),
    ];
    let right = [
        halves[0].1.clone(),
        halves[1].1.clone(),
        halves[2].1.clone(),
    ];
    piece_misses(&left, b, depth - 1) && piece_misses(&right, b, depth - 1)
}

/// Whether every point of the closed box `b = [[u0, u1], [v0, v1]]` (the surface's parameter
/// plane) lies in `face`, none does, or that is not proven: when the box provably meets no
/// loop, it is connected and misses the region's boundary, so all its points share one
/// membership: that of its centre ([`point_in_face`]) when the box lies in the open domain,
/// outside when the face has an outer loop and the box reaches the domain's boundary (the
/// region lies in the open domain), outside when it lies outside the closed domain;
/// otherwise undecided.
pub fn box_in_face(face: &Face, b: &[[f64; 2]; 2]) -> Membership {
    let d = face.domain.clone().map(|r| r.map(|x| x.to_f64()));
    // The domain's ends rounded to f64 may move by half an ulp: compare with a margin.
    let slack = |x: f64| x.abs() * 4.0 * f64::EPSILON + f64::MIN_POSITIVE;
    let outside =
        (0..2).any(|a| b[a][1] < d[a][0] - slack(d[a][0]) || b[a][0] > d[a][1] + slack(d[a][1]));
    if outside {
        return Membership::Outside;
    }
    let inside =
        (0..2).all(|a| b[a][0] > d[a][0] + slack(d[a][0]) && b[a][1] < d[a][1] - slack(d[a][1]));
    if !inside && face.outer.is_none() {
        return Membership::Undecided;
    }
    for l in face.loops() {
        for piece in &l.pieces {
            let c = [0, 1, 2].map(|k| piece.curve.coordinate(k).convert(Precision::F64));
            if !curve_misses_box(&c, b) {
                return Membership::Undecided;
            }
        }
    }
    if !inside {
        // It reaches the domain's boundary (or past it) and meets no loop: the region inside
        // the outer loop lies in the open domain (the loop lies in the closed, convex
        // domain), so the box's points there are outside, and so are all of them.
        return Membership::Outside;
    }
    let centre =
        |a: usize| Rational::from_f64(0.5 * b[a][0] + 0.5 * b[a][1]).expect("a finite box");
    point_in_face(face, &[centre(0), centre(1)])
}

/// [`box_in_face`] for a surface's region, the union of its faces: inside if inside one of
/// them, outside if outside all of them.
pub fn box_in_faces<'a>(
    faces: impl IntoIterator<Item = &'a Face>,
    b: &[[f64; 2]; 2],
) -> Membership {
    let mut out = Membership::Outside;
    for f in faces {
        match box_in_face(f, b) {
            Membership::Inside => return Membership::Inside,
            Membership::Undecided => out = Membership::Undecided,
            Membership::Outside => {}
        }
    }
    out
}

/// The faces of a patch's surface, with the affine map of the patch's `[0, 1]²` onto the
/// surface's parameters (`u = origin + size · s` per axis): what every analysis asks of a
/// trimmed patch (a box's membership, the loops in the patch's own parameters).
#[derive(Clone, Debug)]
pub struct FacesOnPatch {
    /// The faces of the patch's surface.
    pub faces: Vec<Face>,
    /// The surface parameters of the patch's `(0, 0)`.
    pub origin: [Rational; 2],
    /// The patch's extent in the surface's parameters, per axis (positive).
    pub size: [Rational; 2],
}

/// A patch whose surface has faces but no parameter box of positive size in the surface's
/// plane: nothing of it can be placed in its faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NoParameterBox;

/// One loop piece of a patch's faces in the patch's own parameters.
#[derive(Clone, Debug)]
pub struct PieceOnPatch {
    /// The face (index into [`crate::model::Model::faces`]).
    pub face: usize,
    /// The loop (0: the outer one if the face has one) and the piece in it.
    pub at: (usize, usize),
    /// The B-rep edge it lies on, if any.
    pub edge: Option<usize>,
    /// `(U, V, W)`: the piece is `(U/W, V/W)` in the patch's parameters, `t ∈ [0, 1]`.
    pub curve: [Bernstein<Rational>; 3],
}

impl FacesOnPatch {
    /// The faces on patch `p` of `model`: `None` if its surface has none.
    ///
    /// # Errors
    /// [`NoParameterBox`] if the patch's box in the surface's parameters is not known or is
    /// degenerate.
    pub fn of(
        model: &crate::model::Model,
        p: usize,
    ) -> Option<Result<FacesOnPatch, NoParameterBox>> {
        let mp = model.patches.get(p)?;
        let faces: Vec<Face> = model
            .faces
            .iter()
            .filter(|f| f.surface == mp.source.surface)
            .cloned()
            .collect();
        if faces.is_empty() {
            return None;
        }
        let degenerate = |p: &[[Rational; 2]; 2]| p.iter().any(|r| r[0] >= r[1]);
        let Some(params) = mp.source.parameters.as_ref().filter(|p| !degenerate(p)) else {
            return Some(Err(NoParameterBox));
        };
        Some(Ok(FacesOnPatch {
            faces,
            origin: [params[0][0].clone(), params[1][0].clone()],
            size: [
                Rational::from(&params[0][1] - &params[0][0]),
                Rational::from(&params[1][1] - &params[1][0]),
            ],
        }))
    }

    /// An enclosure of a box of patch parameters in the surface's parameters.
    pub fn surface_box(&self, r: &crate::geometry::Rect) -> [[f64; 2]; 2] {
        std::array::from_fn(|a| {
            let o = Interval::from_rational(&self.origin[a], Precision::F64);
            let s = Interval::from_rational(&self.size[a], Precision::F64);
            let [lo, hi] = r.axis(a);
            let x = o.add(&s.mul(&Interval::new(lo, hi)));
            [x.lo(), x.hi()]
        })
    }

    /// The membership of a box of patch parameters ([`box_in_faces`]).
    pub fn membership(&self, r: &crate::geometry::Rect) -> Membership {
        box_in_faces(&self.faces, &self.surface_box(r))
    }

    /// Every loop piece in the patch's parameters, as `(U, V, W)`.
    pub fn pieces(&self) -> Vec<[Bernstein<Rational>; 3]> {
        self.pieces_on(&[]).into_iter().map(|p| p.curve).collect()
    }

    /// Every loop piece in the patch's parameters, with where it comes from; `faces` are the
    /// indices in the model of [`FacesOnPatch::faces`] (none: numbered from 0).
    pub fn pieces_on(&self, faces: &[usize]) -> Vec<PieceOnPatch> {
        let inv = |a: usize| Rational::from(1) / self.size[a].clone();
        let mut out = Vec::new();
        for (i, f) in self.faces.iter().enumerate() {
            for (l, lp) in f.loops().enumerate() {
                for (k, p) in lp.pieces.iter().enumerate() {
                    let c = &p.curve;
                    out.push(PieceOnPatch {
                        face: faces.get(i).copied().unwrap_or(i),
                        at: (l, k),
                        edge: p.edge,
                        curve: [
                            c.offset(0, &self.origin[0]).scale(&inv(0)),
                            c.offset(1, &self.origin[1]).scale(&inv(1)),
                            c.coordinate(2),
                        ],
                    });
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Closing;
    use crate::surface::ParameterCurve;

    fn q(n: i64, d: i64) -> Rational {
        Rational::from((n, d))
    }

    fn polygon(corners: &[(i64, i64, i64)]) -> Vec<(ParameterCurve, Option<usize>)> {
        let p: Vec<Vec<Rational>> = corners
            .iter()
            .map(|&(u, v, d)| vec![q(u, d), q(v, d)])
            .collect();
        (0..p.len())
            .map(|i| (ParameterCurve::segment(&p[i], &p[(i + 1) % p.len()]), None))
            .collect()
    }

    fn face(
        outer: Option<Vec<(ParameterCurve, Option<usize>)>>,
        inner: Vec<Vec<(ParameterCurve, Option<usize>)>>,
    ) -> Face {
        let domain = [[q(0, 1), q(1, 1)], [q(0, 1), q(1, 1)]];
        let closing = Closing {
            tolerance: Rational::new(),
            domain: &domain,
            collapsed: [false; 4],
        };
        let close = |c| TrimLoop::close(c, &closing, None).unwrap();
        Face {
            surface: 0,
            entity: None,
            domain: domain.clone(),
            outer: outer.map(close),
            inner: inner.into_iter().map(close).collect(),
        }
    }

    /// `a <= x < b`: where `x + ε` (or `x + ε²`) lies in `[a, b]`.
    fn half_open(x: &Rational, a: &Rational, b: &Rational) -> bool {
        x >= a && x < b
    }

    /// A square with a square hole, points on a grid that hits every vertex and side: the
    /// answer is the perturbed point's membership, computed in closed form.
    #[test]
    fn points_in_a_square_with_a_hole_match_the_closed_form() {
        let f = face(
            Some(polygon(&[(1, 1, 8), (7, 1, 8), (7, 7, 8), (1, 7, 8)])),
            vec![polygon(&[(3, 3, 8), (3, 5, 8), (5, 5, 8), (5, 3, 8)])],
        );
        let mut checked = 0;
        for i in 0..=16 {
            for j in 0..=16 {
                let p = [q(i, 16), q(j, 16)];
                let inside = half_open(&p[0], &q(1, 8), &q(7, 8))
                    && half_open(&p[1], &q(1, 8), &q(7, 8))
                    && !(half_open(&p[0], &q(3, 8), &q(5, 8))
                        && half_open(&p[1], &q(3, 8), &q(5, 8)));
                let expected = if inside && p[0] < 1 && p[1] < 1 {
                    Membership::Inside
                } else {
                    Membership::Outside
                };
                assert_eq!(point_in_face(&f, &p), expected, "({i}/16, {j}/16)");
                checked += 1;
            }
        }
        assert_eq!(checked, 289);
        // The domain as the outer loop: every point of the half-open domain is inside.
        let whole = face(None, Vec::new());
        assert_eq!(
            point_in_face(&whole, &[q(0, 1), q(1, 2)]),
            Membership::Inside
        );
        assert_eq!(
            point_in_face(&whole, &[q(1, 1), q(1, 2)]),
            Membership::Outside
        );
    }

    /// A disc of radius 1/2 about (1/2, 1/2) from four exact rational quadratic arcs, points on
    /// a grid off the circle: inside iff (u − 1/2)² + (v − 1/2)² < 1/4.
    #[test]
    fn points_in_a_rational_disc_match_the_closed_form() {
        let c = |u: i64, v: i64| vec![q(1, 2) + q(u, 2), q(1, 2) + q(v, 2)];
        let arc = |a: (i64, i64), m: (i64, i64), b: (i64, i64)| {
            (
                ParameterCurve::new(
                    &[c(a.0, a.1), c(m.0, m.1), c(b.0, b.1)],
                    &[q(1, 1), q(1, 1), q(2, 1)],
                )
                .unwrap(),
                None,
            )
        };
        let disc = vec![
            arc((1, 0), (1, 1), (0, 1)),
            arc((0, 1), (-1, 1), (-1, 0)),
            arc((-1, 0), (-1, -1), (0, -1)),
            arc((0, -1), (1, -1), (1, 0)),
        ];
        let f = face(Some(disc), Vec::new());
        for i in 0..=20 {
            for j in 0..=20 {
                let p = [q(i, 20), q(j, 20)];
                let r2 = (&p[0] - q(1, 2)).square() + (&p[1] - q(1, 2)).square();
                if r2 == q(1, 4) {
                    continue;
                }
                let expected = if r2 < q(1, 4) && p[0] < 1 && p[1] < 1 {
                    Membership::Inside
                } else {
                    Membership::Outside
                };
                assert_eq!(point_in_face(&f, &p), expected, "({i}/20, {j}/20)");
            }
        }
        // On the circle itself, at (4/5, 9/10) and (4/5, 1/10), the ray's crossing is the point.
        // Where it is at a dyadic parameter it is decided exactly by the convention (moving by
        // (ε², ε) leaves the disc at the first point, enters it at the second); otherwise no
        // interval separates it from u0 and the answer is undecided, never the wrong side (an
        // exact decision there would take the common root of g and h).
        let upper = point_in_face(&f, &[q(4, 5), q(9, 10)]);
        assert!(
            matches!(upper, Membership::Outside | Membership::Undecided),
            "{upper:?}"
        );
        let lower = point_in_face(&f, &[q(4, 5), q(1, 10)]);
        assert!(
            matches!(lower, Membership::Inside | Membership::Undecided),
            "{lower:?}"
        );
    }

    /// Boxes in a square with a square hole: inside, in the hole, outside, across each loop
    /// (undecided: a box across a loop is neither) and reaching the domain's boundary.
    #[test]
    fn boxes_in_a_square_with_a_hole() {
        let f = face(
            Some(polygon(&[(1, 1, 8), (7, 1, 8), (7, 7, 8), (1, 7, 8)])),
            vec![polygon(&[(3, 3, 8), (3, 5, 8), (5, 5, 8), (5, 3, 8)])],
        );
        use Membership::{Inside, Outside, Undecided};
        let cases = [
            ([[0.2, 0.3], [0.2, 0.3]], Inside),
            ([[0.2, 0.2], [0.6, 0.6]], Inside),
            ([[0.45, 0.55], [0.4, 0.6]], Outside),
            ([[0.9, 0.95], [0.1, 0.95]], Outside),
            ([[1.5, 2.0], [0.2, 0.3]], Outside),
            ([[0.3, 0.4], [0.3, 0.4]], Undecided),
            ([[0.8, 0.9], [0.2, 0.3]], Undecided),
            // Reaching the domain's side and meeting no loop: outside the outer loop
            // (proofs/trimmed-faces.md, section 7); reaching it across a loop: undecided.
            ([[0.0, 0.1], [0.2, 0.3]], Outside),
            ([[0.0, 0.2], [0.2, 0.3]], Undecided),
        ];
        for (b, expected) in cases {
            assert_eq!(box_in_face(&f, &b), expected, "{b:?}");
        }
        let b = |u0: f64, u1: f64, v0: f64, v1: f64| [[u0, u1], [v0, v1]];
        // Just off a loop, on either side.
        let e = 1e-9;
        assert_eq!(
            box_in_face(&f, &b(0.375 - 2.0 * e, 0.375 - e, 0.45, 0.5)),
            Membership::Inside
        );
        assert_eq!(
            box_in_face(&f, &b(0.375 + e, 0.375 + 2.0 * e, 0.45, 0.5)),
            Membership::Outside
        );
        // The union of two faces: inside either.
        let g = face(
            Some(polygon(&[(3, 3, 8), (5, 3, 8), (5, 5, 8), (3, 5, 8)])),
            Vec::new(),
        );
        assert_eq!(
            box_in_faces([&f, &g], &b(0.45, 0.55, 0.4, 0.6)),
            Membership::Inside
        );
        assert_eq!(
            box_in_faces([&f, &g], &b(0.9, 0.95, 0.1, 0.95)),
            Membership::Outside
        );
    }
}
