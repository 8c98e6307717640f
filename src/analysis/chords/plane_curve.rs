//! Certified chord accuracy: vertices on each arc such that every drawn segment is within a
//! world-space tolerance of the true curve (`proofs/chord-accuracy.md`).

use super::cubic::{Cubic, CubicTrace, Jets};
use crate::bernstein::Bernstein;
use crate::geometry::Rect;
use crate::number::margin;
use crate::number::{Interval, Number, Precision, Rational, Sign};
use crate::solver::plane_curve::Arc;
use crate::surface::RationalPatch;

/// The most vertices placed on one arc before giving up on the tolerance.
pub(super) const MAX_ARC_POINTS: usize = 1 << 18;

/// `x / w` for an interval `w` of strict sign, outward rounded ([`Interval::checked_div`]).
pub(crate) fn div(x: Interval, w: Interval) -> Option<Interval> {
    x.checked_div(&w)
}

/// An upper bound of |x| over the interval.
fn mag(x: Interval) -> f64 {
    x.lo().abs().max(x.hi().abs())
}

/// An upper bound of the Euclidean norm of a vector of intervals.
fn norm(v: &[Interval; 3]) -> f64 {
    let s: f64 = v.iter().map(|x| mag(*x) * mag(*x)).sum();
    // Six roundings (three squares, two sums, the root): `proofs/rounding-margins.md`.
    margin::up(s.sqrt(), margin::FEW)
}

/// Interval data of one patch and its silhouette function, for accuracy bounds.
pub struct PatchAccuracy {
    /// g, then ∂g/∂u, ∂g/∂v, then ∂²g/∂u², ∂²g/∂u∂v, ∂²g/∂v² (empty for a patch traced along
    /// parameter lines only: [`PatchAccuracy::lines_only`]).
    pub(super) g: Vec<Bernstein<Interval>>,
    /// Bounds on the patch's derivatives.
    pub(super) surface: SurfaceBounds,
    /// g in f64, for root estimates (certified afterwards).
    pub(super) g_f64: Option<Bernstein<f64>>,
    /// f64 derivatives of g and of the patch, for the cubics' Hermite data.
    pub(super) jets: Jets,
}

/// The patch's homogeneous coordinates in f64.
fn homogeneous_f64(patch: &RationalPatch) -> Vec<Bernstein<f64>> {
    patch
        .homogeneous()
        .iter()
        .map(|h| h.convert(Precision::F64))
        .collect()
}

pub(crate) fn derivs(p: &Bernstein<Rational>) -> [Bernstein<Interval>; 6] {
    let (pu, pv) = (p.deriv(0), p.deriv(1));
    let (puu, puv, pvv) = (pu.deriv(0), pu.deriv(1), pv.deriv(1));
    [p, &pu, &pv, &puu, &puv, &pvv].map(|q| q.convert(Precision::F64))
}

/// Index in the 6-element derivative arrays of ∂/∂a (a = 0, 1) and ∂²/∂a∂b.
pub(super) fn d1(a: usize) -> usize {
    1 + a
}
fn d2(a: usize, b: usize) -> usize {
    match (a.min(b), a.max(b)) {
        (0, 0) => 3,
        (0, 1) => 4,
        _ => 5,
    }
}

/// Interval data of a patch's homogeneous coordinates and their first and second partials,
/// for bounds on the derivatives of `S = P / W` over boxes.
pub(crate) struct SurfaceBounds {
    /// For X, Y, Z, W: f, f_u, f_v, f_uu, f_uv, f_vv.
    pub(super) h: Vec<[Bernstein<Interval>; 6]>,
}

/// A bivariate polynomial restricted to the box `[lo, hi]` of its domain, as interval
/// Bernstein coefficients that enclose the exact restriction's (two de Casteljau splits per
/// axis, the second at an interval parameter that contains the exact one); the box may reach
/// past `[0, 1]²` (the polynomial is defined everywhere); `None` if it is not a box
/// (`lo > hi`, or not finite). A side of zero width restricts to that line.
pub(crate) fn restrict_enclosing(
    p: &Bernstein<Interval>,
    lo: [f64; 2],
    hi: [f64; 2],
) -> Option<Bernstein<Interval>> {
    let is_box = (0..2).all(|k| lo[k] <= hi[k] && lo[k].is_finite() && hi[k].is_finite());
    is_box.then(|| p.restrict_box_f64(&lo, &hi))
}

/// The hull of a polynomial's Bernstein coefficients restricted to the box `[lo, hi]`: an
/// enclosure of its range there (`proofs/coefficient-range.md`).
pub(crate) fn range_enclosing(
    p: &Bernstein<Interval>,
    lo: [f64; 2],
    hi: [f64; 2],
) -> Option<Interval> {
    Some(restrict_enclosing(p, lo, hi)?.hull())
}

/// Enclosures over the box `[lo, hi]` (f64 bounds, `lo < hi`) of a bivariate `f` and its
/// partials, given as `[f, f_u, f_v, f_uu, f_uv, f_vv]`: the hulls of the restrictions of `f`,
/// `f_u`, `f_v`, and the second partials from the first partials' restrictions: for
/// `q(ξ) = h(lo + w ξ)`, `dq/dξ = w ∂h/∂x`, so the hull of `q`'s derivative coefficients times
/// an enclosure of `1/w` encloses `∂h/∂x` over the box (`proofs/chord-accuracy.md`, "The bounds
/// over a sub-box"). A side of zero width restricts the second partials themselves.
pub(crate) fn jet_on(f: &[Bernstein<Interval>; 6], lo: &[f64], hi: &[f64]) -> [Interval; 6] {
    let [fu, fv, fuu, fuv, fvv] = partials_on(f, lo, hi);
    [f[0].restrict_box_f64(lo, hi).hull(), fu, fv, fuu, fuv, fvv]
}

/// [`jet_on`] without the value: `[f_u, f_v, f_uu, f_uv, f_vv]` over the box.
pub(crate) fn partials_on(f: &[Bernstein<Interval>; 6], lo: &[f64], hi: &[f64]) -> [Interval; 5] {
    let r = |p: &Bernstein<Interval>| p.restrict_box_f64(lo, hi);
    let (qu, qv) = (r(&f[1]), r(&f[2]));
    let inv_width = |k: usize| {
        Interval::point(hi[k])
            .sub(&Interval::point(lo[k]))
            .recip()
            .filter(|w| w.lo() > 0.0 && w.hi().is_finite())
    };
    let second = |q: &Bernstein<Interval>, axis: usize, direct: usize| match inv_width(axis) {
        Some(iw) => q.deriv_hull(axis).mul(&iw),
        None => r(&f[direct]).hull(),
    };
    [
        qu.hull(),
        qv.hull(),
        second(&qu, 0, 3),
        second(&qu, 1, 4),
        second(&qv, 1, 5),
    ]
}

/// An enclosure of a bivariate `f` over the box `[lo, hi]` by the mean value form: `f(c)` at
/// the centre plus its partials `d` over the box (interval evaluation) times `B − c` (the mean
/// value theorem: `proofs/events.md`, "Enclosures"). Cheaper than restricting `f` to a small
/// box, and as tight to first order.
pub(crate) fn mean_value_range(
    f: &Bernstein<Interval>,
    d: &[Bernstein<Interval>; 2],
    lo: [f64; 2],
    hi: [f64; 2],
) -> Interval {
    let c = [0.5 * lo[0] + 0.5 * hi[0], 0.5 * lo[1] + 0.5 * hi[1]];
    let b = [Interval::new(lo[0], hi[0]), Interval::new(lo[1], hi[1])];
    let ci = c.map(Interval::point);
    let mut acc = f.eval(&ci);
    for k in 0..2 {
        acc = acc.add(&d[k].eval(&b).mul(&b[k].sub(&ci[k])));
    }
    acc
}

impl SurfaceBounds {
    /// Converts (once) the patch's exact polynomials.
    pub(crate) fn new(patch: &RationalPatch) -> SurfaceBounds {
        SurfaceBounds {
            h: patch.homogeneous().iter().map(derivs).collect(),
        }
    }

    /// The centre of an interval enclosure of `S(uv)` (the homogeneous coordinates evaluated
    /// in interval arithmetic, divided by the weight's) and its half-diagonal, which bounds
    /// the centre's distance to the exact point.
    pub(crate) fn point(&self, uv: [f64; 2]) -> Option<([f64; 3], f64)> {
        let x = uv.map(Interval::point);
        let w = self.h[3][0].eval(&x);
        let mut c = [0.0; 3];
        let mut r = [Interval::point(0.0); 3];
        for k in 0..3 {
            let s = div(self.h[k][0].eval(&x), w)?;
            c[k] = 0.5 * s.lo() + 0.5 * s.hi();
            // |c − s| ≤ max(c − lo, hi − c), each difference rounded outward.
            let lo = Interval::point(c[k]).sub(&Interval::point(s.lo())).hi();
            let hi = Interval::point(s.hi()).sub(&Interval::point(c[k])).hi();
            r[k] = Interval::point(lo.max(hi));
        }
        let e = norm(&r);
        (c.iter().all(|v| v.is_finite()) && e.is_finite()).then_some((c, e))
    }

    /// Bounds over a box of |∂S/∂m| and of the norms of S_mm, S_mo, S_oo.
    pub(crate) fn bounds(&self, lo: [f64; 2], hi: [f64; 2], m: usize) -> Option<[f64; 4]> {
        Some(self.bounds_both(lo, hi, m)?.0)
    }

    /// [`SurfaceBounds::bounds`] for `m`, and the bound on |∂S/∂o| (from the same ranges).
    pub(crate) fn bounds_both(
        &self,
        lo: [f64; 2],
        hi: [f64; 2],
        m: usize,
    ) -> Option<([f64; 4], f64)> {
        let o = 1 - m;
        let r = |k: usize, i: usize| PatchAccuracy::range(&self.h[k][i], lo, hi);
        let w: [Interval; 6] = std::array::from_fn(|i| r(3, i));
        if !w[0].sign().is_positive() {
            return None;
        }
        let mut s_m = [Interval::point(0.0); 3];
        let mut s_o = s_m;
        let mut s_mm = s_m;
        let mut s_mo = s_m;
        let mut s_oo = s_m;
        for k in 0..3 {
            let p: [Interval; 6] = std::array::from_fn(|i| r(k, i));
            let s = div(p[0], w[0])?;
            let sx = |a: usize| -> Option<Interval> { div(p[d1(a)].sub(&s.mul(&w[d1(a)])), w[0]) };
            let (sm, so) = (sx(m)?, sx(o)?);
            let sxy = |a: usize, b: usize, sa: Interval, sb: Interval| -> Option<Interval> {
                let num = p[d2(a, b)]
                    .sub(&sa.mul(&w[d1(b)]))
                    .sub(&sb.mul(&w[d1(a)]))
                    .sub(&s.mul(&w[d2(a, b)]));
                div(num, w[0])
            };
            s_m[k] = sm;
            s_o[k] = so;
            s_mm[k] = sxy(m, m, sm, sm)?;
            s_mo[k] = sxy(m, o, sm, so)?;
            s_oo[k] = sxy(o, o, so, so)?;
        }
        Some((
            [norm(&s_m), norm(&s_mm), norm(&s_mo), norm(&s_oo)],
            norm(&s_o),
        ))
    }
}

impl PatchAccuracy {
    /// Converts (once) the exact polynomials a patch's bounds are computed from.
    pub fn new(patch: &RationalPatch, g: &Bernstein<Rational>) -> PatchAccuracy {
        let g_f64: Bernstein<f64> = g.convert(Precision::F64);
        PatchAccuracy {
            g: derivs(g).to_vec(),
            surface: SurfaceBounds::new(patch),
            jets: Jets::new(Some(&g_f64), &homogeneous_f64(patch)),
            g_f64: Some(g_f64),
        }
    }

    /// The bounds of a patch without a curve function: only lines of constant u or v (sides,
    /// lines where the function vanishes identically) can be traced; arcs of a curve fail.
    pub fn lines_only(patch: &RationalPatch) -> PatchAccuracy {
        PatchAccuracy {
            g: Vec::new(),
            surface: SurfaceBounds::new(patch),
            g_f64: None,
            jets: Jets::new(None, &homogeneous_f64(patch)),
        }
    }

    /// The point `S(uv)` of the patch, as the centre of its interval enclosure, and a bound on
    /// its distance to the exact point (the enclosure's half-diagonal): the drawn point and
    /// its rounding error. `None` where the weight's enclosure holds 0.
    pub fn point(&self, uv: [f64; 2]) -> Option<([f64; 3], f64)> {
        self.surface.point(uv)
    }

    /// A certified bracket `[x, y]` of the curve's point on the line o = `level` with m in
    /// `[m0, m1]`, where g is strictly monotone along m (see `point_on_line`).
    pub fn bracket(&self, m: usize, m0: f64, m1: f64, level: f64) -> Option<(f64, f64)> {
        self.point_on_line(m, m0, m1, level, 0.5 * (m0 + m1))
    }

    /// The range of a polynomial over a box, enclosed: the Bernstein coefficients of its
    /// restriction ([`restrict_enclosing`]) bound it.
    fn range(p: &Bernstein<Interval>, lo: [f64; 2], hi: [f64; 2]) -> Interval {
        let Some(q) = restrict_enclosing(p, lo, hi) else {
            return Interval::new(f64::NEG_INFINITY, f64::INFINITY);
        };
        let (a, b) = q.range_f64();
        Interval::try_new(a, b).unwrap_or(Interval::new(f64::NEG_INFINITY, f64::INFINITY))
    }

    /// The box `[lo, hi]` grown by a thousandth of its size (and 1e-9) on each side, and
    /// enclosures over it of the partials of ∂g/∂m along u and v (`None` without a curve
    /// function).
    pub(super) fn gm_gradient(
        &self,
        lo: [f64; 2],
        hi: [f64; 2],
        m: usize,
    ) -> ([f64; 2], [f64; 2], Option<[Interval; 2]>) {
        let grow = |k: usize| 1e-3 * (hi[k] - lo[k]) + 1e-9;
        let glo = [0, 1].map(|k| lo[k] - grow(k));
        let ghi = [0, 1].map(|k| hi[k] + grow(k));
        let Ok(g) = <&[Bernstein<Interval>; 6]>::try_from(self.g.as_slice()) else {
            return (glo, ghi, None);
        };
        let p = partials_on(g, &glo, &ghi);
        // p = [g_u, g_v, g_uu, g_uv, g_vv]; ∂g_m/∂u, ∂g_m/∂v.
        let grad = [p[d2(m, 0) - 1], p[d2(m, 1) - 1]];
        let finite = grad
            .iter()
            .all(|x| x.lo().is_finite() && x.hi().is_finite());
        (glo, ghi, finite.then_some(grad))
    }

    /// Bounds of |φ'| and |φ''| over a box where ∂g/∂m has a strict sign.
    pub(super) fn phi_bounds(&self, lo: [f64; 2], hi: [f64; 2], m: usize) -> Option<(f64, f64)> {
        if self.g.is_empty() {
            return None;
        }
        let o = 1 - m;
        // The partials over the box (`partials_on`: the second partials from the first
        // partials' restrictions); the box lies in the unit square.
        let inside = (0..2).all(|k| 0.0 <= lo[k] && lo[k] <= hi[k] && hi[k] <= 1.0);
        if !inside {
            return None;
        }
        let g: &[Bernstein<Interval>; 6] = self.g.as_slice().try_into().ok()?;
        let p = partials_on(g, &lo, &hi);
        // p = [g_u, g_v, g_uu, g_uv, g_vv].
        let gm = p[m];
        let go = p[o];
        let (gmm, gmo, goo) = (p[d2(m, m) - 1], p[d2(m, o) - 1], p[d2(o, o) - 1]);
        let p1 = div(go, gm)?.neg();
        let two = Interval::point(2.0);
        let num = goo.add(&two.mul(&gmo).mul(&p1)).add(&gmm.mul(&p1).mul(&p1));
        let p2 = div(num, gm)?.neg();
        Some((mag(p1), mag(p2)))
    }

    /// A bracket `[x, y]` of the arc's point on the line o = level, with m in [m0, m1] (the
    /// arc's box): Newton's method in f64 from `guess` (bisection-safeguarded), then certified
    /// by opposite enclosed signs of g at the bracket's ends. g is strictly monotone along m on
    /// the box, so the line meets the curve in the box at most once and the root between them
    /// is the arc's point (`proofs/chord-accuracy.md`).
    fn point_on_line(
        &self,
        m: usize,
        m0: f64,
        m1: f64,
        level: f64,
        guess: f64,
    ) -> Option<(f64, f64)> {
        // g on the line o = level, once: in f64 for Newton, in intervals (enclosing the exact
        // coefficients, `de-casteljau-enclosure.md`) for the certified signs.
        let line = on_line(self.g_f64.as_ref()?, m, level);
        let dline = line.deriv(0);
        let exact_line = on_line(&self.g[0], m, Interval::point(level));
        let f = |x: f64| line.eval(&[x]);
        let df = |x: f64| dline.eval(&[x]);
        let sign = |x: f64| exact_line.eval(&[Interval::point(x)]).sign();
        let (mut lo, mut hi) = (m0, m1);
        let mut x = guess.clamp(m0, m1);
        // g is strictly monotone along m on the box: its direction, from the derivative (a
        // wrong sign here only makes the certification below fail, never pass).
        let rising = df(x) > 0.0;
        for _ in 0..60 {
            let fx = f(x);
            if fx == 0.0 {
                break;
            }
            if (fx > 0.0) == rising {
                hi = x;
            } else {
                lo = x;
            }
            let next = x - fx / df(x);
            let next = if next.is_finite() && next > lo && next < hi {
                next
            } else {
                0.5 * (lo + hi)
            };
            if (next - x).abs() <= 4.0 * f64::EPSILON * (1.0 + x.abs()) {
                x = next;
                break;
            }
            x = next;
        }
        // Certify a bracket around the estimate, widening until the enclosed signs differ.
        let (s_lo, s_hi) = if rising {
            (Sign::Negative, Sign::Positive)
        } else {
            (Sign::Positive, Sign::Negative)
        };
        // First bracket: the enclosure's width at x over the slope, so that the first try
        // usually succeeds.
        let v = exact_line.eval(&[Interval::point(x)]);
        let slope = df(x).abs();
        let tiny = 8.0 * f64::EPSILON * (1.0 + x.abs());
        let mut eps = tiny.max(2.0 * (v.hi() - v.lo()) / slope);
        if !eps.is_finite() {
            eps = tiny;
        }
        for _ in 0..40 {
            let (a, b) = ((x - eps).max(m0), (x + eps).min(m1));
            if sign(a) == s_lo && sign(b) == s_hi {
                return Some((a, b));
            }
            if (a, b) == (m0, m1) {
                break;
            }
            eps *= 16.0;
        }
        None
    }

    /// Vertices along an arc, in (u, v), from its `from` end to its `to` end, with the largest
    /// chord bound `E` (`proofs/chord-accuracy.md`); `None` for the bound if `tol` was not met
    /// within the budget or a bound could not be computed.
    ///
    /// The arc's o-range is covered recursively: on each piece, bounds of φ'' and of S's
    /// derivatives over the piece's box give the spacing h at which `E ≤ tol`; a piece that
    /// would need many vertices is halved first (its halves get tighter bounds), the others
    /// get uniformly spaced certified vertices, each checked against the bound with its own
    /// certified error and slope.
    pub fn trace(&self, arc: &Arc, from: Rect, to: Rect, tol: f64) -> Traced {
        let graph = arc.kind.monotone_axis();
        self.trace_in(arc.cell.to_f64(), graph, from, to, tol)
    }

    /// As [`PatchAccuracy::trace`], for the arc in the box `cell` in (u, v) that is
    /// the graph `m = φ(o)` (`graph = Some(m)`, `∂g/∂m` of strict sign on the box), or for a
    /// line of constant u or v from the centre of `from` to the centre of `to` (`graph =
    /// None`: the coordinate that stays constant is the one the ends agree in; the box is
    /// theirs). The true ends lie in the boxes `from` and `to`, or at least at a level in their
    /// range in o within their half-extent in m of their centre
    /// (`proofs/chord-accuracy.md`, "The ends").
    pub fn trace_in(
        &self,
        cell: Rect,
        graph: Option<usize>,
        from: Rect,
        to: Rect,
        tol: f64,
    ) -> Traced {
        let (p0, p1) = (from.center(), to.center());
        let (m, on_edge) = match graph {
            Some(m) => (m, false),
            // Along a line: the varying coordinate is the one the ends differ in.
            None => (
                if (p1[0] - p0[0]).abs() >= (p1[1] - p0[1]).abs() {
                    1
                } else {
                    0
                },
                true,
            ),
        };
        let o = 1 - m;
        let Rect { lo: blo, hi: bhi } = if on_edge {
            Rect::point(p0).hull(&Rect::point(p1))
        } else {
            cell
        };
        let phi1 = if on_edge {
            Some(0.0)
        } else {
            self.phi_bounds(blo, bhi, m).map(|b| b.0)
        };
        let fail = |p0: [f64; 2], p1: [f64; 2]| Traced {
            points: vec![p0, p1],
            bound: None,
            pieces: Vec::new(),
            cubics: Vec::new(),
        };
        let (Some(phi1), Some(l_m)) = (phi1, self.surface.bounds(blo, bhi, m).map(|b| b[0])) else {
            return fail(p0, p1);
        };
        let end_delta = |b: Rect| b.half_width(m) + phi1 * b.half_width(o);
        // The true arc ends anywhere in its crossing's location box, which may extend beyond
        // the end vertex's level: that end piece lies in the box grown by Φ₁ in m, within
        // L·(δ + half-extent in o) of the vertex in space, L bounding |∂S/∂m| and |∂S/∂o|.
        let Some(l_o) = self.surface.bounds(blo, bhi, o).map(|b| b[0]) else {
            return fail(p0, p1);
        };
        let end_piece = |b: Rect| {
            margin::up(
                l_m.max(l_o) * (end_delta(b) + b.half_width(o)),
                margin::MANY,
            )
        };
        let worst = end_piece(from).max(end_piece(to));
        if worst > tol {
            return fail(p0, p1);
        }
        let last = (p1[o], p1[m], end_delta(to));
        // The end pieces: from the end vertex's level to the true end, anywhere in its
        // location box, the arc stays within the vertex's `end_delta` in m.
        let end = |b: Rect, v: Vertex| {
            let mut lo = [0.0; 2];
            let mut hi = [0.0; 2];
            lo[o] = b.lo[o];
            hi[o] = b.hi[o];
            let r = margin::up(v.2, margin::MANY);
            lo[m] = Interval::point(v.1)
                .sub(&Interval::point(r))
                .lo()
                .max(blo[m]);
            hi[m] = Interval::point(v.1)
                .add(&Interval::point(r))
                .hi()
                .min(bhi[m]);
            Rect::new(lo, hi)
        };
        // Certified cubics first (`proofs/cubic-pieces.md`); the certified vertices of the
        // chord tracer where they fail.
        let cubic = CubicTrace {
            acc: self,
            m,
            on_edge,
            blo,
            bhi,
            tol,
            reach: if on_edge {
                0.0
            } else {
                0.5 * tol / l_m.max(f64::MIN_POSITIVE)
            },
            grad: self.gm_gradient(blo, bhi, m),
            cell_bounds: Some((Rect::new(blo, bhi), l_m, l_o)),
        };
        if let Some(mut c) = cubic.trace((p0[o], p0[m]), (p1[o], p1[m]), end_delta(from), last.2) {
            let n = c.verts.len();
            let mut pieces = vec![(end(from, c.verts[0]), 0, 0)];
            pieces.append(&mut c.pieces);
            pieces.push((end(to, c.verts[n - 1]), n - 1, n - 1));
            // The cubics at the arc's ends also answer for the end pieces.
            let k = c.cubics.len();
            for (i, ends) in [(0, end_piece(from)), (k - 1, end_piece(to))] {
                let q = &mut c.cubics[i];
                q.bound = margin::up(q.bound + ends, margin::FEW);
                q.uv_bound = margin::up(q.uv_bound + ends, margin::FEW);
            }
            return Traced {
                points: c.verts.iter().map(|v| uv(m, v.1, v.0)).collect(),
                bound: Some(worst.max(c.worst)),
                pieces,
                cubics: c.cubics,
            };
        }
        let mut tracer = Tracer {
            acc: self,
            m,
            on_edge,
            blo,
            bhi,
            tol,
            verts: vec![(p0[o], p0[m], end_delta(from))],
            worst,
            pieces: Vec::new(),
        };
        let ok = tracer.cover(tracer.verts[0], last, phi1, None, 0);
        tracer.verts.push(last);
        let n = tracer.verts.len();
        let mut pieces = vec![(end(from, tracer.verts[0]), 0, 0)];
        pieces.extend(tracer.pieces.iter().map(|&(b, i)| (b, i, i + 1)));
        pieces.push((end(to, last), n - 1, n - 1));
        Traced {
            points: tracer.verts.iter().map(|v| uv(m, v.1, v.0)).collect(),
            bound: ok.then_some(tracer.worst),
            pieces: if ok { pieces } else { Vec::new() },
            cubics: Vec::new(),
        }
    }
}

/// An arc traced to a tolerance ([`PatchAccuracy::trace`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Traced {
    /// Its vertices in (u, v), from its `from` end to its `to` end.
    pub points: Vec<[f64; 2]>,
    /// The largest chord bound `E`; `None` if the tolerance was not met within the budget or
    /// a bound could not be computed.
    pub bound: Option<f64>,
    /// With a bound: boxes in (u, v) that cover the arc, each with the range
    /// `first..=last` of the vertices it also holds: one per chord (its two vertices) and one
    /// per end (the piece beyond the end vertex's level, up to the true end).
    pub pieces: Vec<(Rect, usize, usize)>,
    /// Certified cubic pieces from the `from` end to the `to` end (`proofs/cubic-pieces.md`),
    /// each within its bound of the arc and together covering it; empty where the arc was
    /// traced by certified vertices instead, or not traced.
    pub cubics: Vec<Cubic>,
}

/// A vertex: (o level, m value, δ = certified error of the m value at that level).
pub(super) type Vertex = (f64, f64, f64);

/// Pieces needing more vertices than this are halved before vertices are placed.
const SPLIT_VERTICES: f64 = 48.0;

/// Below this halving depth, pieces reuse their parent's bounds of S's derivatives.
const FRESH_SURFACE_BOUNDS: u32 = 4;

/// The deepest halving of an arc's o-range.
const MAX_SPLIT_DEPTH: u32 = 40;

/// The state of one arc's trace.
struct Tracer<'a> {
    acc: &'a PatchAccuracy,
    m: usize,
    on_edge: bool,
    blo: [f64; 2],
    bhi: [f64; 2],
    tol: f64,
    verts: Vec<Vertex>,
    worst: f64,
    /// Per chord whose bound was accepted: a box holding it and its piece of the arc, and
    /// the index of its first vertex (the second is the next).
    pieces: Vec<(Rect, usize)>,
}

impl Tracer<'_> {
    /// The certified vertex at `level`, between vertices a and b.
    fn vertex(&self, a: Vertex, b: Vertex, level: f64) -> Option<Vertex> {
        let t = if b.0 != a.0 {
            (level - a.0) / (b.0 - a.0)
        } else {
            0.5
        };
        let guess = a.1 + (b.1 - a.1) * t;
        if self.on_edge {
            return Some((level, guess, 0.0));
        }
        let (x, y) =
            self.acc
                .point_on_line(self.m, self.blo[self.m], self.bhi[self.m], level, guess)?;
        Some((level, 0.5 * (x + y), 0.5 * (y - x)))
    }

    /// Bounds over the box of the arc piece between vertices a and b, which stays within
    /// δ + Φ₁·h of both in m (`phi1` bounds |φ'| on a box containing the piece): (Φ₁, Φ₂) of
    /// the piece, and |S_m|, |S_mm|, |S_mo|, |S_oo|.
    fn piece_bounds(
        &self,
        a: Vertex,
        b: Vertex,
        phi1: f64,
        parent_sb: Option<[f64; 4]>,
    ) -> Option<(f64, f64, [f64; 4])> {
        let m = self.m;
        let Rect { lo, hi } = self.piece_box(a, b, phi1);
        let (p1, p2) = if self.on_edge {
            (0.0, 0.0)
        } else {
            self.acc.phi_bounds(lo, hi, m)?
        };
        // Bounds over a box containing the piece are valid for it: deep in the recursion the
        // parent's bounds of S's derivatives are kept (they change little), Φ's are not.
        let sb = match parent_sb {
            Some(sb) => sb,
            None => self.acc.surface.bounds(lo, hi, m)?,
        };
        Some((p1.min(phi1), p2, sb))
    }

    /// A box of the arc's box that holds the arc piece between vertices a and b and both
    /// vertices: between their levels in o, and within `δ + Φ₁·h` of both in m (`phi1`
    /// bounds |φ'| on a box containing the piece), with a relative margin for rounding.
    fn piece_box(&self, a: Vertex, b: Vertex, phi1: f64) -> Rect {
        let (m, o) = (self.m, 1 - self.m);
        let h = (b.0 - a.0).abs();
        let reach = margin::up(a.2.max(b.2) + phi1 * h, margin::MANY);
        let (mut lo, mut hi) = (self.blo, self.bhi);
        lo[o] = a.0.min(b.0).max(self.blo[o]);
        hi[o] = a.0.max(b.0).min(self.bhi[o]);
        lo[m] = Interval::point(a.1.min(b.1))
            .sub(&Interval::point(reach))
            .lo()
            .max(self.blo[m]);
        hi[m] = Interval::point(a.1.max(b.1))
            .add(&Interval::point(reach))
            .hi()
            .min(self.bhi[m]);
        Rect::new(lo, hi)
    }

    /// Adds the vertices strictly between a and b (a is already in `verts`); false if the
    /// tolerance could not be certified within the budget.
    fn cover(
        &mut self,
        a: Vertex,
        b: Vertex,
        phi1: f64,
        parent_sb: Option<[f64; 4]>,
        depth: u32,
    ) -> bool {
        if self.verts.len() >= MAX_ARC_POINTS {
            return false;
        }
        let inherit = parent_sb.filter(|_| depth >= FRESH_SURFACE_BOUNDS);
        let Some((phi1, phi2, sb)) = self.piece_bounds(a, b, phi1, inherit) else {
            return false;
        };
        let h = (b.0 - a.0).abs();
        // The spacing at which the bound meets tol, with the vertex errors expected (those of
        // the ends; inner vertices are certified to a few ulps) and the slope bounded by Φ₁.
        let [l_m, s_mm, s_mo, s_oo] = sb;
        let s = phi1 + 1e-9;
        let curv = (l_m * phi2 + s_mm * s * s + 2.0 * s_mo * s + s_oo) / 8.0;
        let budget = 0.9 * self.tol - l_m * a.2.max(b.2).max(1e-15);
        if budget.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) || !curv.is_finite() {
            return false;
        }
        let n = if curv > 0.0 {
            (h / (budget / curv).sqrt()).ceil().max(1.0)
        } else {
            1.0
        };
        if n > SPLIT_VERTICES && depth < MAX_SPLIT_DEPTH {
            let Some(c) = self.vertex(a, b, 0.5 * (a.0 + b.0)) else {
                return false;
            };
            if !self.cover(a, c, phi1, Some(sb), depth + 1) {
                return false;
            }
            self.verts.push(c);
            return self.cover(c, b, phi1, Some(sb), depth + 1);
        }
        if n as usize + self.verts.len() > MAX_ARC_POINTS {
            return false;
        }
        let n = n as usize;
        let mut prev = a;
        for k in 1..=n {
            let next = if k == n {
                b
            } else {
                let level = a.0 + (b.0 - a.0) * (k as f64 / n as f64);
                match self.vertex(prev, b, level) {
                    Some(v) => v,
                    None => return false,
                }
            };
            let e = chord_bound(prev, next, phi2, sb);
            if e.is_finite() && e <= self.tol {
                self.worst = self.worst.max(e);
                let first = self.verts.len() - 1;
                self.pieces.push((self.piece_box(prev, next, phi1), first));
            } else if depth < MAX_SPLIT_DEPTH && (next.0 - prev.0).abs() > 0.0 {
                // The planned spacing did not suffice (a vertex less precise than expected):
                // cover this chord on its own, with bounds on its smaller box.
                if !self.cover(prev, next, phi1, Some(sb), depth + 1) {
                    return false;
                }
            } else {
                return false;
            }
            if k < n {
                self.verts.push(next);
            }
            prev = next;
        }
        true
    }
}

/// The bound E of the chord between two vertices, from bounds Φ₂ (of |φ''|) and sb over
/// a box containing the arc piece between them.
pub(super) fn chord_bound(a: Vertex, b: Vertex, phi2: f64, sb: [f64; 4]) -> f64 {
    let [l_m, s_mm, s_mo, s_oo] = sb;
    let h = (b.0 - a.0).abs();
    let slope = if h > 0.0 {
        (b.1 - a.1).abs() / h
    } else {
        f64::INFINITY
    };
    if h == 0.0 {
        // Coincident levels: only the vertex errors count.
        return margin::up(l_m * a.2.max(b.2), margin::MANY);
    }
    let e = l_m * (h * h / 8.0 * phi2 + a.2.max(b.2))
        + h * h / 8.0 * (s_mm * slope * slope + 2.0 * s_mo * slope + s_oo);
    // About twenty roundings (`proofs/rounding-margins.md`).
    margin::up(e, margin::MANY)
}

/// The univariate polynomial (in variable m) of a bivariate one on the line where the other
/// variable equals `level`: each fibre along the other variable evaluated there.
pub(super) fn on_line<N: Number>(p: &Bernstein<N>, m: usize, level: N) -> Bernstein<N> {
    let o = 1 - m;
    let d = [p.degrees()[0], p.degrees()[1]];
    let coeffs: Vec<N> = (0..=d[m])
        .map(|i| {
            let fibre: Vec<N> = (0..=d[o])
                .map(|k| {
                    let mut idx = [0; 2];
                    idx[m] = i;
                    idx[o] = k;
                    p.coeff(&idx).clone()
                })
                .collect();
            Bernstein::new(&[d[o]], fibre)
                .expect("univariate")
                .eval(std::slice::from_ref(&level))
        })
        .collect();
    Bernstein::new(&[d[m]], coeffs).expect("univariate")
}

fn uv(m: usize, mv: f64, ov: f64) -> [f64; 2] {
    if m == 0 {
        [mv, ov]
    } else {
        [ov, mv]
    }
}
