//! The drawn points of a hidden-line piece: evenly spaced in its parameter (not certified), or,
//! with a tolerance, traced by the certified chord tracer ([`PatchAccuracy::trace_in`]) so that
//! the polyline is proven within the tolerance of the true piece in space
//! (`proofs/hidden-lines.md`, "Drawing to a tolerance").

use crate::analysis::chords::plane_curve::PatchAccuracy;
use crate::analysis::contour::drawing::zero_across;
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

/// The point in (u, v) of a line segment (a side, or a line of constant u or v) at parameter t.
fn line_uv(s: &Segment, t: f64) -> Option<[f64; 2]> {
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
