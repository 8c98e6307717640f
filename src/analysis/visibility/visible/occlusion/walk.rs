//! Following the lift of a drawn piece across patches: runs on one patch, windows where it
//! crosses a continuing edge.

use super::lift::Tube;
use super::Lifting;
use crate::analysis::projection::{side_point_f64, Projection};
use crate::geometry::Rect;
use crate::number::{Interval, Number};
use crate::reason::Reason;
use crate::surface::Edge;

/// A vertex of a lift: a point of the piece's drawn polyline and its lift.
#[derive(Clone, Copy, Debug)]
pub(super) struct Vertex {
    pub(super) x: [f64; 3],
    pub(super) w: [f64; 2],
}

/// Where the lift crosses a continuing edge from patch `from` to patch `to`: three points
/// of the drawn polyline around the crossing (`x*` where the drawn lift meets the side) and
/// their lifts on both patches (each extended past its square).
#[derive(Clone, Debug)]
pub(super) struct Window {
    pub(super) from: usize,
    pub(super) to: usize,
    /// The side of `from` and of `to` the lift crosses, and whether they run opposite.
    pub(super) edges: (Edge, Edge, bool),
    /// `x₋, x*, x₊` in walking order.
    pub(super) x: [[f64; 3]; 3],
    /// Their lifts on `from` and on `to`.
    pub(super) w_from: [[f64; 2]; 3],
    pub(super) w_to: [[f64; 2]; 3],
}

/// A run of the lift on one patch, before certification.
pub(super) struct Run {
    pub(super) patch: usize,
    /// The vertices in walking order (with a window at an end, its `x*` is that end).
    pub(super) vertices: Vec<Vertex>,
    /// The windows at its start and at its end (indices into the walk's windows).
    pub(super) start: Option<usize>,
    pub(super) end: Option<usize>,
    /// Why the run is not certified, found while following it.
    pub(super) reason: Option<Reason>,
}

/// A lift followed from a start vertex in one direction.
pub(super) struct Walk {
    pub(super) runs: Vec<Run>,
    pub(super) windows: Vec<Window>,
}

pub(super) const INSIDE_SLACK: f64 = 1e-12;

pub(super) fn inside(w: [f64; 2]) -> bool {
    w.iter()
        .all(|c| (-INSIDE_SLACK..=1.0 + INSIDE_SLACK).contains(c))
}

pub(super) fn clamp(w: [f64; 2]) -> [f64; 2] {
    w.map(|c| c.clamp(0.0, 1.0))
}

pub(super) fn lerp(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    std::array::from_fn(|k| a[k] + t * (b[k] - a[k]))
}

/// The side of the square nearest a parameter point, with its parameter.
pub(super) fn nearest_side(w: [f64; 2]) -> (Edge, f64) {
    let d = [
        w[1].abs(),
        (w[0] - 1.0).abs(),
        (w[1] - 1.0).abs(),
        w[0].abs(),
    ];
    let k = (0..4).min_by(|&a, &b| d[a].total_cmp(&d[b])).unwrap_or(0);
    match k {
        0 => (Edge::V0, w[0]),
        1 => (Edge::U1, w[1]),
        2 => (Edge::V1, w[0]),
        _ => (Edge::U0, w[1]),
    }
}

/// The fixed coordinate of a side, its value, and the side's free coordinate.
pub(super) fn side_axes(e: Edge) -> (usize, f64, usize) {
    match e {
        Edge::V0 => (1, 0.0, 0),
        Edge::V1 => (1, 1.0, 0),
        Edge::U0 => (0, 0.0, 1),
        Edge::U1 => (0, 1.0, 1),
    }
}

/// Whether the box lies apart from the unit square (along some axis, wholly beyond it).
pub(super) fn apart_from_square(b: &Rect) -> bool {
    (0..2).any(|k| b.hi[k] < 0.0 || b.lo[k] > 1.0)
}

/// The box grown on every side by `frac` times its larger extent, plus `abs` (the preimage of
/// an image box around a chord that is diagonal in the image is wide in both parameters even
/// where the chord's lift runs along one of them).
pub(super) fn grown(b: &Rect, frac: f64, abs: f64) -> Rect {
    let extent = b.width(0).max(b.width(1));
    b.grown(frac * extent + abs)
}

/// The sides of the square a box reaches past.
pub(super) fn sides_crossed(b: &Rect) -> Vec<Edge> {
    let mut out = Vec::new();
    if b.lo[1] < 0.0 {
        out.push(Edge::V0);
    }
    if b.hi[0] > 1.0 {
        out.push(Edge::U1);
    }
    if b.hi[1] > 1.0 {
        out.push(Edge::V1);
    }
    if b.lo[0] < 0.0 {
        out.push(Edge::U0);
    }
    out
}

impl Lifting<'_> {
    pub(super) fn projection(&self) -> &Projection {
        &self.scene.projection
    }

    /// The image of a space point (f64, for Newton's targets).
    pub(super) fn image(&self, x: [f64; 3]) -> Option<[f64; 2]> {
        let i = self.projection().image_of_box(x, x)?;
        Some([0.5 * (i[0].lo() + i[0].hi()), 0.5 * (i[1].lo() + i[1].hi())])
    }

    pub(super) fn lift(&self, p: usize, x: [f64; 3], from: [f64; 2]) -> Option<[f64; 2]> {
        self.patches[p].newton(self.image(x)?, from)
    }

    /// The image enclosure of the box around points grown by `e`.
    /// `pts` are collinear points of one drawn chord (its first and last span it).
    pub(super) fn tube(&self, pts: &[[f64; 3]], e: f64) -> Option<Tube> {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in pts {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let lo = lo.map(|x| Interval::point(x).sub(&Interval::point(e)).lo());
        let hi = hi.map(|x| Interval::point(x).add(&Interval::point(e)).hi());
        let proj = self.projection();
        let (first, last) = (pts.first()?, pts.last()?);
        let a = proj.image_of_box(*first, *first)?;
        let b = proj.image_of_box(*last, *last)?;
        let grad = proj.image_gradient_bound(lo, hi)?;
        let r = grad.map(|g| Interval::point(g).mul(&Interval::point(e)).hi());
        let d = [0, 1].map(|k| b[k].sub(&a[k]));
        let hull = [0, 1].map(|k| {
            let h = a[k].hull(&b[k]);
            Interval::new(
                Interval::point(h.lo()).sub(&Interval::point(r[k])).lo(),
                Interval::point(h.hi()).add(&Interval::point(r[k])).hi(),
            )
        });
        Some(Tube { a, d, r, hull })
    }

    /// Follows the lift of a polyline from its first point (lifted to `w` on `patch`),
    /// crossing continuing edges.
    pub(super) fn walk(&self, points: &[[f64; 3]], patch: usize, w: [f64; 2], e: f64) -> Walk {
        let mut walk = Walk {
            runs: vec![Run {
                patch,
                vertices: vec![Vertex { x: points[0], w }],
                start: None,
                end: None,
                reason: None,
            }],
            windows: Vec::new(),
        };
        for (i, &xb) in points.iter().enumerate().skip(1) {
            let last = i + 1 == points.len();
            loop {
                let run = walk.runs.last_mut().expect("a run");
                let a = *run.vertices.last().expect("a vertex");
                let p = run.patch;
                let Some(wb) = self.lift(p, xb, a.w) else {
                    run.reason = Some(Reason::LiftLost { patch: p });
                    return walk;
                };
                if inside(wb) {
                    run.vertices.push(Vertex { x: xb, w: wb });
                    break;
                }
                // The lift leaves the patch: where along the chord, by bisection.
                let (mut lo, mut hi, mut w_lo) = (0.0f64, 1.0f64, a.w);
                for _ in 0..50 {
                    let mid = 0.5 * (lo + hi);
                    match self.lift(p, lerp(a.x, xb, mid), w_lo) {
                        Some(wm) if inside(wm) => {
                            lo = mid;
                            w_lo = wm;
                        }
                        _ => hi = mid,
                    }
                }
                let (edge, t) = nearest_side(w_lo);
                let twins = self.scene.twins(p, edge);
                let [(p2, e2, rev)] = twins[..] else {
                    // The piece's own end, on an outline side of the patch behind (where the
                    // piece is cut): its lift is drawn clamped into the square.
                    if last {
                        run.vertices.push(Vertex { x: xb, w: wb });
                        break;
                    }
                    run.reason = Some(Reason::LiftLeaves { patch: p, edge });
                    return walk;
                };
                let t2 = if rev { 1.0 - t } else { t };
                let x_star = lerp(a.x, xb, lo);
                let Some(w2) = self.lift(p2, x_star, side_point_f64(e2, t2)) else {
                    run.reason = Some(Reason::LiftLostTo { patch: p2 });
                    return walk;
                };
                // A window around the crossing, within the chord, wide enough that the lifts
                // of its ends are farther from the crossed sides than the vertex boxes reach.
                let reach = |q: usize, w: [f64; 2]| {
                    self.vertex_box(q, x_star, w, e)
                        .map_or(0.0, |b| 0.0f64.max(b.width(0)).max(b.width(1)))
                };
                let need = 3.0 * reach(p, w_lo).max(reach(p2, w2));
                let beyond = |w: [f64; 2]| {
                    w.iter()
                        .map(|c| (-c).max(c - 1.0))
                        .fold(f64::NEG_INFINITY, f64::max)
                };
                let on = |q: usize, from: [f64; 2], xs: &[[f64; 3]; 3]| {
                    Some([
                        self.lift(q, xs[0], from)?,
                        self.lift(q, xs[1], from)?,
                        self.lift(q, xs[2], from)?,
                    ])
                };
                let mut delta = 1e-3;
                let found = loop {
                    let (l0, l1) = ((lo - delta).max(0.0), (lo + delta).min(1.0));
                    let xs = [lerp(a.x, xb, l0), x_star, lerp(a.x, xb, l1)];
                    let lifted = on(p, w_lo, &xs).zip(on(p2, w2, &xs));
                    let Some((w_from, w_to)) = lifted else {
                        break None;
                    };
                    let wide = beyond(w_from[2]) > need && beyond(w_to[0]) > need;
                    if wide || (l0 == 0.0 && l1 == 1.0) {
                        break Some((l0, l1, xs, w_from, w_to));
                    }
                    delta *= 2.0;
                };
                let Some((l0, l1, xs, w_from, w_to)) = found else {
                    run.reason = Some(Reason::LiftLostAcross { patches: [p, p2] });
                    return walk;
                };
                let k = walk.windows.len();
                if l0 > 0.0 {
                    run.vertices.push(Vertex {
                        x: xs[0],
                        w: w_from[0],
                    });
                }
                run.vertices.push(Vertex {
                    x: x_star,
                    w: w_from[1],
                });
                run.end = Some(k);
                walk.windows.push(Window {
                    from: p,
                    to: p2,
                    edges: (edge, e2, rev),
                    x: xs,
                    w_from,
                    w_to,
                });
                let vertices = vec![
                    Vertex {
                        x: x_star,
                        w: w_to[1],
                    },
                    Vertex {
                        x: xs[2],
                        w: w_to[2],
                    },
                ];
                walk.runs.push(Run {
                    patch: p2,
                    vertices,
                    start: Some(k),
                    end: None,
                    reason: None,
                });
                if l1 >= 1.0 {
                    // x₊ is xb itself.
                    break;
                }
            }
        }
        walk
    }
}

impl Window {
    /// The same window walked the other way.
    pub(super) fn reversed(&self) -> Window {
        let r3 = |a: [[f64; 2]; 3]| [a[2], a[1], a[0]];
        Window {
            from: self.to,
            to: self.from,
            edges: (self.edges.1, self.edges.0, self.edges.2),
            x: [self.x[2], self.x[1], self.x[0]],
            w_from: r3(self.w_to),
            w_to: r3(self.w_from),
        }
    }
}

impl Walk {
    /// The same lift walked the other way.
    pub(super) fn reversed(mut self) -> Walk {
        self.runs.reverse();
        for r in &mut self.runs {
            r.vertices.reverse();
            std::mem::swap(&mut r.start, &mut r.end);
        }
        self.windows = self.windows.iter().map(Window::reversed).collect();
        self
    }

    /// `self` (ending at the anchor) followed by `next` (starting there, on the same patch).
    pub(super) fn joined(mut self, next: Walk) -> Walk {
        let offset = self.windows.len();
        self.windows.extend(next.windows);
        let mut runs = next.runs.into_iter().map(|mut r| {
            r.start = r.start.map(|k| k + offset);
            r.end = r.end.map(|k| k + offset);
            r
        });
        if let (Some(last), Some(first)) = (self.runs.last_mut(), runs.next()) {
            last.vertices.extend(first.vertices.into_iter().skip(1));
            last.end = first.end;
            last.reason = last.reason.take().or(first.reason);
        }
        self.runs.extend(runs);
        self
    }
}
