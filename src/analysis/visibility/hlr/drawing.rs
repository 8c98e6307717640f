//! The drawn points of a hidden-line piece: evenly spaced in its parameter (not certified), or,
//! with a tolerance, traced by the certified chord tracer ([`PatchAccuracy::trace_in`]) so that
//! the polyline is proven within the tolerance of the true piece in space
//! (`proofs/hidden-lines.md`, "Drawing to a tolerance").

use crate::analysis::chords::plane_curve::PatchAccuracy;
use crate::analysis::contour::drawing::zero_across;
use crate::analysis::visibility::hlr::intersection_lines::meet_points;
use crate::analysis::visibility::hlr::lines::Segment;
use crate::geometry::Rect;
use crate::number::margin;
use crate::number::{Number, Precision, Rational};
use crate::surface::DrawPatch;
use crate::surface::Edge;

/// Drawing points as (patch, u, v) and in space.
pub(super) type Drawn = (Vec<(usize, f64, f64)>, Vec<[f64; 3]>);

/// One end of a piece: the interval of the segment's parameter that holds the true end, and
/// whether it is the segment's own end (a vertex of the line network, located by its box).
#[derive(Clone, Copy, Debug)]
pub(super) struct PieceEnd {
    pub(super) at: [f64; 2],
    pub(super) segment_end: bool,
}

/// The point in (u, v) of a line segment (a side, a line of constant u or v, or a trimming
/// curve, in f64) at parameter t.
fn line_uv(s: &Segment, t: f64) -> Option<[f64; 2]> {
    if let Some(c) = &s.curve {
        let f = |p: &crate::bernstein::Poly| p.convert::<f64>(Precision::F64).eval(&[t]);
        let w = f(&c[2]);
        return (w > 0.0).then(|| [f(&c[0]) / w, f(&c[1]) / w]);
    }
    if let Some(edge) = s.edge.filter(|_| s.constraint.is_none()) {
        return Some(match edge {
            Edge::V0 => [t, 0.0],
            Edge::V1 => [t, 1.0],
            Edge::U0 => [0.0, t],
            Edge::U1 => [1.0, t],
        });
    }
    let (axis, at) = s.line?;
    let mut p = [at.to_f64(); 2];
    p[1 - axis] = t;
    Some(p)
}

/// Drawing points of a segment's stretch `[p0, p1]`, evenly spaced in its parameter (the
/// arc's other coordinate solved in f64): not certified.
pub(super) fn draw_points(s: &Segment, draw: &DrawPatch, p0: f64, p1: f64, steps: usize) -> Drawn {
    let steps = steps.max(2);
    if s.meet.is_some() {
        return meet_points(s, draw, p0, p1, steps);
    }
    let mut uv = Vec::new();
    let gf = s
        .constraint
        .as_ref()
        .map(|g| g.convert::<f64>(Precision::F64));
    for k in 0..=steps {
        let t = p0 + (p1 - p0) * k as f64 / steps as f64;
        match &gf {
            None => uv.extend(line_uv(s, t)),
            Some(g) => {
                let m = 1 - s.axis;
                let (lo, hi) = (s.domain[m].0.to_f64(), s.domain[m].1.to_f64());
                if let Some(x) = zero_across(g, m, t, lo, hi) {
                    let mut p = [0.0; 2];
                    p[m] = x;
                    p[s.axis] = t;
                    uv.push(p);
                }
            }
        }
    }
    let points = uv.iter().map(|p| draw.eval(p[0], p[1])).collect();
    (
        uv.into_iter().map(|p| (s.patch, p[0], p[1])).collect(),
        points,
    )
}

/// The box in (u, v) of a piece's end (`proofs/hidden-lines.md`, "Drawing to a tolerance"):
/// on a line, the line over the end's interval; on an arc, the box of the segment's vertex at
/// its own end (the true end lies in it), else the end's interval in the parameter times a
/// certified bracket of the arc's other coordinate at the interval's centre.
fn end_box(s: &Segment, acc: &PatchAccuracy, end: PieceEnd) -> Option<Rect> {
    if s.constraint.is_none() {
        let (a, b) = (line_uv(s, end.at[0])?, line_uv(s, end.at[1])?);
        return Some(Rect::point(a).hull(&Rect::point(b)));
    }
    let (o, m) = (s.axis, 1 - s.axis);
    if end.segment_end {
        // The end is the vertex's own only if its interval lies in the vertex's (a crossing
        // enclosure reaching past the vertex may hold the true end elsewhere: not bounded).
        let v = s
            .vertices
            .iter()
            .find(|v| v.param[0] <= end.at[0] && end.at[1] <= v.param[1])?;
        let (_, lo, hi) = v.uv.iter().find(|x| x.0 == s.patch)?;
        let down = |q: &Rational| q.lower_f64();
        let up = |q: &Rational| q.upper_f64();
        return Some(Rect::new(lo.each_ref().map(down), hi.each_ref().map(up)));
    }
    let level = 0.5 * (end.at[0] + end.at[1]);
    let (m0, m1) = (s.domain[m].0.to_f64(), s.domain[m].1.to_f64());
    let (x, y) = acc.bracket(m, m0, m1, level)?;
    let mut b = Rect::point([0.0; 2]);
    b.lo[o] = end.at[0];
    b.hi[o] = end.at[1];
    b.lo[m] = x;
    b.hi[m] = y;
    Some(b)
}

/// The points of a piece traced to `tol` in space, with the proven bound on the Hausdorff
/// distance between the drawn polyline and the true piece (the tracer's chord bound plus the
/// rounding of the drawn points); `None` if the tolerance could not be certified.
pub(super) fn traced_points(
    s: &Segment,
    draw: &DrawPatch,
    acc: &PatchAccuracy,
    from: PieceEnd,
    to: PieceEnd,
    tol: f64,
) -> Option<(Drawn, f64)> {
    let (a, b) = (end_box(s, acc, from)?, end_box(s, acc, to)?);
    let graph = s.constraint.as_ref().map(|_| 1 - s.axis);
    // The arc's box (a line's box is its ends', taken by the tracer).
    let cell = if s.domain.len() == 2 {
        Rect::new(
            [
                s.domain[0].0.to_f64_bounds().0,
                s.domain[1].0.to_f64_bounds().0,
            ],
            [
                s.domain[0].1.to_f64_bounds().1,
                s.domain[1].1.to_f64_bounds().1,
            ],
        )
    } else {
        Rect::new(a.lo, b.hi)
    };
    let traced = acc.trace_in(cell, graph, a, b, tol);
    let chords = traced.bound?;
    // The drawn points: in f64 with the patch's a priori rounding bound where the vertices lie
    // in the unit square, else the centres of interval enclosures.
    let unit = |x: f64| (0.0..=1.0).contains(&x);
    let (points, rounding) = match draw.rounding() {
        Some(r) if traced.points.iter().all(|p| unit(p[0]) && unit(p[1])) => (
            traced
                .points
                .iter()
                .map(|p| draw.eval(p[0], p[1]))
                .collect(),
            r,
        ),
        _ => {
            let mut rounding: f64 = 0.0;
            let mut points = Vec::with_capacity(traced.points.len());
            for uv in &traced.points {
                let (p, e) = acc.point(*uv)?;
                rounding = rounding.max(e);
                points.push(p);
            }
            (points, rounding)
        }
    };
    // The drawn polyline's vertices are within `rounding` of the exact ones, so each drawn
    // segment is within it of the exact chord (a convex combination of the vertex errors).
    let bound = margin::up(chords + rounding, margin::FEW);
    let uv = traced
        .points
        .iter()
        .map(|p| (s.patch, p[0], p[1]))
        .collect();
    (bound <= tol).then_some(((uv, points), bound))
}

/// The points of a trimming piece drawn within `tol` in space, with the proven bound on the
/// Hausdorff distance between the polyline and the true piece (`proofs/hidden-lines.md`,
/// "Drawing to a tolerance"): the patch composed with the curve is an exact rational space
/// curve in `t`; on each parameter interval its control points' boxes (weights proven
/// positive) hold it, so its distance to the drawn chord is at most the largest distance
/// of a box to the chord, and every point of the chord lies within that plus twice the
/// chord ends' rounding of the curve (the curve's projection onto the chord's line covers
/// it). Intervals are halved until that holds; the true ends lie in the pieces' end
/// intervals, whose extents are added. `None` if not within `tol`.
pub(super) fn traced_curve(
    s: &Segment,
    surface: &crate::surface::RationalPatch,
    from: PieceEnd,
    to: PieceEnd,
    tol: f64,
) -> Option<(Drawn, f64)> {
    use crate::bernstein::{compose_homogeneous, Bernstein};
    use crate::number::Interval;
    let c = s.curve.as_ref()?;
    let hom = surface.homogeneous();
    let space: Vec<Bernstein<Interval>> = hom
        .iter()
        .map(|h| compose_homogeneous(h, [&c[0], &c[1], &c[2]]).convert(Precision::F64))
        .collect();
    // The control points' boxes over [t0, t1].
    let boxes = |t0: f64, t1: f64| -> Option<Vec<[Interval; 3]>> {
        let r: Vec<Bernstein<Interval>> = space
            .iter()
            .map(|p| p.restrict_box_f64(&[t0], &[t1]))
            .collect();
        let n = r[3].coeffs().len();
        (0..n)
            .map(|i| {
                let w = r[3].coeffs()[i];
                if w.lo() <= 0.0 {
                    return None;
                }
                Some([0, 1, 2].map(|k| r[k].coeffs()[i].checked_div(&w)))
                    .and_then(|b| Some([b[0]?, b[1]?, b[2]?]))
            })
            .collect()
    };
    let mid = |b: &[Interval; 3]| b.map(|x| 0.5 * x.lo() + 0.5 * x.hi());
    let sup = |x: &Interval| x.lo().abs().max(x.hi().abs());
    let norm_up = |v: [Interval; 3]| -> f64 {
        let mut sum = 0.0f64;
        for x in &v {
            let m = sup(x);
            sum = margin::up(sum + margin::up(m * m, margin::FEW), margin::FEW);
        }
        margin::up(sum.sqrt(), margin::FEW)
    };
    // The extent of the curve over an end's interval.
    let extent = |at: [f64; 2]| -> Option<f64> {
        if at[0] >= at[1] {
            return Some(0.0);
        }
        let b = boxes(at[0], at[1])?;
        let lo: [f64; 3] =
            std::array::from_fn(|k| b.iter().map(|x| x[k].lo()).fold(f64::INFINITY, f64::min));
        let hi: [f64; 3] = std::array::from_fn(|k| {
            b.iter()
                .map(|x| x[k].hi())
                .fold(f64::NEG_INFINITY, f64::max)
        });
        Some(norm_up(std::array::from_fn(|k| {
            Interval::new(0.0, margin::up(hi[k] - lo[k], margin::FEW))
        })))
    };
    let ends = extent(from.at)?.max(extent(to.at)?);
    let (a, b) = (from.at[0], to.at[1]);
    if a.partial_cmp(&b) != Some(std::cmp::Ordering::Less) || ends > tol {
        return None;
    }
    let budget = tol - ends;
    // The chord deviation and the ends' rounding of one interval.
    let deviation = |t0: f64, t1: f64| -> Option<(f64, [f64; 3], [f64; 3])> {
        let bx = boxes(t0, t1)?;
        let (d0, d1) = (mid(&bx[0]), mid(bx.last()?));
        let e = |p: &[Interval; 3], d: &[f64; 3]| {
            norm_up(std::array::from_fn(|k| p[k].sub(&Interval::point(d[k]))))
        };
        let round = e(&bx[0], &d0).max(e(bx.last()?, &d1));
        let dir: [f64; 3] = std::array::from_fn(|k| d1[k] - d0[k]);
        let len2: f64 = dir.iter().map(|x| x * x).sum();
        let mut worst = 0.0f64;
        for p in &bx {
            let m = mid(p);
            let lambda = if len2 > 0.0 {
                ((0..3).map(|k| (m[k] - d0[k]) * dir[k]).sum::<f64>() / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let l = Interval::point(lambda);
            let y: [Interval; 3] = std::array::from_fn(|k| {
                Interval::point(d0[k])
                    .add(&l.mul(&Interval::point(d1[k]).sub(&Interval::point(d0[k]))))
            });
            worst = worst.max(norm_up(std::array::from_fn(|k| p[k].sub(&y[k]))));
        }
        Some((margin::up(worst + 2.0 * round, margin::FEW), d0, d1))
    };
    let mut points: Vec<[f64; 3]> = Vec::new();
    let mut params: Vec<f64> = Vec::new();
    let mut bound = 0.0f64;
    let mut stack = vec![(a, b, 0u32)];
    while let Some((t0, t1, depth)) = stack.pop() {
        let (dev, d0, d1) = deviation(t0, t1)?;
        if dev <= budget {
            if points.is_empty() {
                points.push(d0);
                params.push(t0);
            }
            points.push(d1);
            params.push(t1);
            bound = bound.max(dev);
            continue;
        }
        let m = 0.5 * t0 + 0.5 * t1;
        if depth >= 40 || !(t0 < m && m < t1) || points.len() > 1 << 20 {
            return None;
        }
        // Right half below the left so the left is drawn first.
        stack.push((m, t1, depth + 1));
        stack.push((t0, m, depth + 1));
    }
    let bound = margin::up(bound + ends, margin::FEW);
    let uv = params
        .iter()
        .filter_map(|t| line_uv(s, *t).map(|p| (s.patch, p[0], p[1])))
        .collect();
    (bound <= tol).then_some(((uv, points), bound))
}
