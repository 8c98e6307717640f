//! Lemma C of `proofs/hidden-lines.md` (an outline cusp): a run of consecutive silhouette
//! segments of one patch around a segment whose image is not monotone, proven to have an
//! injective image with at most one point where the image tangent vanishes (the cusp, where
//! the QI may change, so the run is cut there). No pair of the run's segments can then cross in
//! the image except at their shared ends, and the segment with the cusp needs no other proof
//! that it does not cross itself.
//!
//! The argument: on a silhouette every image of a tangent vector of the patch lies on one line
//! (the tangent plane contains the viewing ray), so the image tangent of the arc is `T = λ m`
//! with `m` a column of the image Jacobian (`J·(1, 0)` or `J·(0, 1)`). With a rational
//! direction `e` such that `A = e · m` has a strict sign on the run, the outline's slope across
//! `e` is `B / A` (`B = e⊥ · m`), smooth through the cusp; if its derivative along the arc has a
//! strict sign (`W = A·D(B) − B·D(A)`, `D` the derivative along the field `(−g_v, g_u)`) and
//! `e · T` has exactly one zero on the run (one isolated root of `g = e·T = 0`, none elsewhere),
//! the two branches from that zero are graphs over `e` on the same side of it, one above and
//! one below their common tangent: they meet only there.

use crate::analysis::visibility::hlr::lines::{
    monotone_along, narrow_to_curve, rational_direction, sign_on, Segment,
};
use crate::analysis::visibility::hlr::result::LineKind;
use crate::analysis::visibility::scene::Scene;
use crate::bernstein::{Bernstein, Poly};
use crate::number::{Interval, Precision, Rational};
use crate::solver::system::{solve_system, DyadicBoxN, SystemOptions};
use rayon::prelude::*;
use std::collections::HashMap;

/// A run of segments proven by lemma C.
#[derive(Clone, Debug)]
pub(super) struct CuspRun {
    /// The segments, consecutive along one line and on one patch.
    pub(super) members: Vec<usize>,
    /// The segment that holds the one point where the image tangent vanishes, and an
    /// interval of its parameter that holds that point (`None`: there is none, the run's
    /// image is strictly monotone).
    pub(super) cusp: Option<(usize, [f64; 2])>,
}

/// The most neighbours taken into a run on each side of the segment with the cusp.
const REACH: usize = 3;

/// The runs lemma C proves, one per segment that is a silhouette arc not proven monotone
/// (where the lemma holds on it).
pub(super) fn cusp_runs(scene: &Scene, segments: &[Segment], opts: &SystemOptions) -> Vec<CuspRun> {
    let by_place: HashMap<(usize, usize), usize> = segments
        .iter()
        .enumerate()
        .map(|(k, s)| ((s.chain, s.order), k))
        .collect();
    let candidates: Vec<usize> = (0..segments.len())
        .filter(|&k| arc_of_patch(&segments[k]) && segments[k].monotone.is_none())
        .collect();
    candidates
        .par_iter()
        .filter_map(|&c| cusp_run(scene, segments, &by_place, c, opts))
        .collect()
}

/// Whether a segment is a silhouette arc on a cell of its patch (not a line inside it).
fn arc_of_patch(s: &Segment) -> bool {
    s.kind == LineKind::Silhouette && s.constraint.is_some() && s.line.is_none()
}

/// Lemma C around segment `c`, if it holds for some direction.
fn cusp_run(
    scene: &Scene,
    segments: &[Segment],
    by_place: &HashMap<(usize, usize), usize>,
    c: usize,
    opts: &SystemOptions,
) -> Option<CuspRun> {
    let s = &segments[c];
    let g = s.constraint.as_ref()?;
    let jac = &scene.jacobians[s.patch];
    // The Jacobian's columns: the images of ∂/∂u and ∂/∂v (numerators).
    let columns: [[&Poly; 2]; 2] = [[&jac[0][0], &jac[1][0]], [&jac[0][1], &jac[1][1]]];
    let centre: Vec<f64> = s
        .domain
        .iter()
        .map(|d| 0.5 * (d.0.to_f64() + d.1.to_f64()))
        .collect();
    let at_centre =
        |m: &[&Poly; 2]| -> [f64; 2] { m.map(|p| p.convert::<f64>(Precision::F64).eval(&centre)) };
    // The longer column first.
    let mut order = [0, 1];
    let norm = |k: usize| {
        let v = at_centre(&columns[k]);
        v[0].hypot(v[1])
    };
    if norm(1) > norm(0) {
        order.swap(0, 1);
    }
    order.iter().find_map(|&k| {
        with_column(
            segments,
            by_place,
            c,
            g,
            columns[k],
            at_centre(&columns[k]),
            opts,
        )
    })
}

/// Lemma C with `m` the given Jacobian column and `e` its direction at the centre of `c`.
fn with_column(
    segments: &[Segment],
    by_place: &HashMap<(usize, usize), usize>,
    c: usize,
    g: &Poly,
    m: [&Poly; 2],
    m_centre: [f64; 2],
    opts: &SystemOptions,
) -> Option<CuspRun> {
    let s = &segments[c];
    let e = rational_direction(m_centre)?;
    let across = [Rational::from(-&e[1]), e[0].clone()];
    let dot = |d: &[Rational; 2]| &m[0].scale(&d[0]) + &m[1].scale(&d[1]);
    let (a, b) = (dot(&e), dot(&across));
    // W = A·D(B) − B·D(A) in interval arithmetic (an enclosure of its coefficients is all a
    // sign test needs), D(P) = P_v g_u − P_u g_v.
    let iv = |p: &Poly| -> Bernstein<Interval> { p.convert(Precision::F64) };
    let (ai, bi, gi) = (iv(&a), iv(&b), iv(g));
    let (gu, gv) = (gi.deriv(0), gi.deriv(1));
    let along = |p: &Bernstein<Interval>| &(&p.deriv(1) * &gu) - &(&p.deriv(0) * &gv);
    let w = &(&ai * &along(&bi)) - &(&bi * &along(&ai));
    // The slope's conditions (A and W of one strict sign each) on a segment.
    let slope_holds = |t: &Segment, signs: &mut Option<(bool, bool)>| -> bool {
        let Some(t_g) = &t.constraint else {
            return false;
        };
        let (Some(sa), Some(sw)) = (
            sign_along(&ai, t_g, &t.domain, t.axis),
            sign_along(&w, t_g, &t.domain, t.axis),
        ) else {
            return false;
        };
        match signs {
            Some(x) => *x == (sa, sw),
            None => {
                *signs = Some((sa, sw));
                true
            }
        }
    };
    let mut signs = None;
    if !slope_holds(s, &mut signs) {
        return None;
    }
    // The zeros of e·T on a member's arc: none where e·T has a strict sign on its box, else
    // the isolated roots of g = e·T = 0 in its cell (`None` if not all isolated inside it).
    let zeros = |t: &Segment| -> Option<Vec<[f64; 2]>> {
        if monotone_along(&t.tangent, &e, &t.domain).is_some() {
            return Some(Vec::new());
        }
        let t_g = t.constraint.as_ref()?;
        let sigma = &t.tangent[0].scale(&e[0]) + &t.tangent[1].scale(&e[1]);
        let roots = solve_system(&[t_g.clone(), sigma], &[], &t.domain, opts);
        if !roots.unresolved.is_empty() || roots.roots.iter().any(|x| !x.inside) {
            return None;
        }
        Some(roots.roots.iter().map(|x| x.enclosure[t.axis]).collect())
    };
    let mut cusp: Option<(usize, [f64; 2])> = None;
    let mut take = |k: usize, found: &[[f64; 2]]| -> bool {
        match (found, &cusp) {
            ([], _) => true,
            ([at], None) => {
                cusp = Some((k, *at));
                true
            }
            _ => false,
        }
    };
    if !take(c, &zeros(s)?) {
        return None;
    }
    // Neighbours along the line on the same patch where the slope's conditions hold, while
    // the run holds at most one zero of e·T.
    let mut members = vec![c];
    for step in [-1i64, 1] {
        for k in 1..=REACH as i64 {
            let Some(order) = (s.order as i64).checked_add(step * k) else {
                break;
            };
            let Ok(order) = usize::try_from(order) else {
                break;
            };
            let Some(&t) = by_place.get(&(s.chain, order)) else {
                break;
            };
            let ts = &segments[t];
            if ts.patch != s.patch || !arc_of_patch(ts) || !slope_holds(ts, &mut signs) {
                break;
            }
            match zeros(ts) {
                Some(found) if take(t, &found) => members.push(t),
                _ => break,
            }
        }
    }
    Some(CuspRun { members, cusp })
}

/// The strict sign of `p` on the part of the arc `g = 0` in `domain`: on the box, or on each
/// piece of it (bisected along `axis` up to three times, each piece narrowed to the arc)
/// with one sign on all.
fn sign_along(p: &Bernstein<Interval>, g: &Poly, domain: &DyadicBoxN, axis: usize) -> Option<bool> {
    let mut sign = None;
    let mut stack = vec![(domain.clone(), 0u32)];
    while let Some((d, depth)) = stack.pop() {
        match sign_on(p, &d) {
            Some(x) if sign.is_none_or(|y| y == x) => sign = Some(x),
            Some(_) => return None,
            None if depth < 3 => {
                let (lo, hi) = d[axis];
                let mid = lo.midpoint(hi)?;
                for half in [(lo, mid), (mid, hi)] {
                    let mut h = d.clone();
                    h[axis] = half;
                    stack.push((narrow_to_curve(g, &h, axis), depth + 1));
                }
            }
            None => return None,
        }
    }
    sign
}
