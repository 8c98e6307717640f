//! The sides of a patch's parameter square as the model-level curve machinery sees them: the
//! side a crossing lies on, a polynomial restricted to a side, and the exact division of a
//! side's linear factor (collapsed sides, sides on which the polynomial vanishes).

use crate::bernstein::Bernstein;
use crate::number::Rational;
use crate::solver::plane_curve::zero_lines::line_point;
use crate::solver::{CrossingId, CurveTopology, Dyadic};
use crate::surface::Edge;

/// The side a crossing lies on (the first one, for a corner) and its parameter along it,
/// as the dyadic interval containing it.
pub(crate) fn side_of(id: &CrossingId) -> Vec<(Edge, Dyadic, Dyadic)> {
    let on = |fixed: usize, c: Dyadic| -> Option<Edge> {
        match (fixed, c) {
            (0, c) if c == Dyadic::ZERO => Some(Edge::U0),
            (0, c) if c == Dyadic::ONE => Some(Edge::U1),
            (1, c) if c == Dyadic::ZERO => Some(Edge::V0),
            (1, c) if c == Dyadic::ONE => Some(Edge::V1),
            _ => None,
        }
    };
    match *id {
        CrossingId::Exact { u, v } => {
            let mut out = Vec::new();
            if let Some(e) = on(0, u) {
                out.push((e, v, v));
            }
            if let Some(e) = on(1, v) {
                out.push((e, u, u));
            }
            out
        }
        CrossingId::Segment {
            fixed, c, s0, s1, ..
        } => on(fixed, c).map(|e| (e, s0, s1)).into_iter().collect(),
    }
}
/// The silhouette function restricted to a side, as a univariate polynomial in the side's
/// own parameter (increasing with u or v).
pub(crate) fn side_polynomial(g: &Bernstein<Rational>, edge: Edge) -> Bernstein<Rational> {
    let [m, n] = [g.degrees()[0], g.degrees()[1]];
    let coeffs: Vec<Rational> = match edge {
        Edge::V0 => (0..=m).map(|i| g.coeff(&[i, 0]).clone()).collect(),
        Edge::V1 => (0..=m).map(|i| g.coeff(&[i, n]).clone()).collect(),
        Edge::U0 => (0..=n).map(|j| g.coeff(&[0, j]).clone()).collect(),
        Edge::U1 => (0..=n).map(|j| g.coeff(&[m, j]).clone()).collect(),
    };
    Bernstein::new(&[coeffs.len() - 1], coeffs).expect("univariate")
}
/// Divides out the linear factor of a side on which `g` vanishes identically (v for V0,
/// 1 − v for V1, u for U0, 1 − u for U1), as many times as it divides; exact
/// ([`Bernstein::divide_face_factor`]).
pub fn deflate_side(g: &Bernstein<Rational>, edge: Edge) -> Bernstein<Rational> {
    deflate_side_counted(g, edge).0
}
/// The variable and end of a side: (0, false) for u = 0, …
pub(crate) fn side_axis(edge: Edge) -> (usize, bool) {
    match edge {
        Edge::U0 => (0, false),
        Edge::U1 => (0, true),
        Edge::V0 => (1, false),
        Edge::V1 => (1, true),
    }
}
/// [`deflate_side`], with the number of factors divided out.
pub fn deflate_side_counted(g: &Bernstein<Rational>, edge: Edge) -> (Bernstein<Rational>, usize) {
    let (axis, at_one) = side_axis(edge);
    let mut g = g.clone();
    let mut k = 0;
    while !g.is_zero() {
        match g.divide_face_factor(axis, at_one) {
            Some(q) => {
                g = q;
                k += 1;
            }
            None => break,
        }
    }
    (g, k)
}
/// Which corner of the patch a crossing is at: 0 = (0,0), 1 = (1,0), 2 = (1,1), 3 = (0,1).
pub(crate) fn corner_index(id: &CrossingId) -> Option<usize> {
    let CrossingId::Exact { u, v } = *id else {
        return None;
    };
    let end = |x: Dyadic| x == Dyadic::ZERO || x == Dyadic::ONE;
    (end(u) && end(v)).then(|| match (u == Dyadic::ONE, v == Dyadic::ONE) {
        (false, false) => 0,
        (true, false) => 1,
        (true, true) => 2,
        (false, true) => 3,
    })
}
pub(crate) fn both_on(a: &CrossingId, b: &CrossingId, edge: Edge) -> bool {
    side_of(a).iter().any(|s| s.0 == edge) && side_of(b).iter().any(|s| s.0 == edge)
}
/// The crossings of a patch's arcs that lie inside a side (corners excluded), sorted along it.
pub(crate) fn side_crossings(t: &CurveTopology, edge: Edge) -> Vec<(Dyadic, Dyadic, CrossingId)> {
    let mut v: Vec<(Dyadic, Dyadic, CrossingId)> = Vec::new();
    for a in &t.arcs {
        for id in [a.from, a.to] {
            let sides = side_of(&id);
            if sides.len() == 1 && sides[0].0 == edge && !v.iter().any(|x| x.2 == id) {
                v.push((sides[0].1, sides[0].2, id));
            }
        }
    }
    v.sort();
    v
}
/// The point of a side at parameter t, in the patch's (u, v).
pub(crate) fn side_point(edge: Edge, t: Dyadic) -> CrossingId {
    let (fixed, at_one) = side_axis(edge);
    line_point(fixed, if at_one { Dyadic::ONE } else { Dyadic::ZERO }, t)
}
