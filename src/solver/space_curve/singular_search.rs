//! Exact singular points in the boxes the subdivision could not decide, and those boxes
//! decided by the star lemma ([`super::singular_branches`], `proofs/space-curves.md` §6).

use crate::bernstein::Bernstein;
use crate::number::{Interval, Number, Precision, Rational};
use crate::reason::Reason;
use crate::solver::dyadic::Dyadic;
use crate::solver::space_curve::singular_branches::{
    exact_singular_point, simple_points_near, ExactPartials, SingularPoint,
};
use crate::solver::space_curve::subdivision::{RawArc, RawCrossing, Settled, Solver};
use crate::solver::space_curve::topology::{SpaceCurve, SpaceUnresolved};
use crate::solver::space_curve::{SpaceCurveOptions, STAR_MIN_DEPTH};
use crate::solver::system::DyadicBoxN;
use crate::solver::system::{f64_box, overlaps, within};

/// What the subdivision decided, before the crossings are named: the crossings and arcs of
/// the settled leaves, and the leaves the caller dropped or gave up on (which no star box may
/// cover).
#[derive(Default)]
pub(crate) struct Leaves {
    pub(crate) crossings: Vec<RawCrossing>,
    pub(crate) arcs: Vec<RawArc>,
    pub(crate) dropped: Vec<Vec<[f64; 2]>>,
}
/// Decides the box around the singular point `k` by the star test (§6), from the smallest
/// depth where it succeeds (and, with a tolerance, its arcs are accurate, or the box is the
/// smallest allowed) down: the leaves inside it are replaced by its arcs. The star's number of
/// branches.
pub(crate) fn star_around(
    solver: &mut Solver,
    k: usize,
    eqs: &[Bernstein<Rational>],
    out: &mut SpaceCurve,
    leaves: &mut Leaves,
) -> Option<usize> {
    let exact = solver.singular[k].exact.clone();
    // Exact comparisons (the leaves' sides are dyadic, exact in f64).
    let holds_p = |cell: &[[f64; 2]]| {
        cell.iter().zip(&exact).all(|(b, x)| {
            let lo = Rational::from_f64(b[0]).expect("finite");
            let hi = Rational::from_f64(b[1]).expect("finite");
            lo <= *x && *x <= hi
        })
    };
    let width = |cell: &[[f64; 2]]| cell[0][1] - cell[0][0];
    // No box of the star may be smaller than an undecided leaf that holds the point (it would
    // cut that leaf): the largest such leaf bounds the depth.
    let largest = out
        .unresolved
        .iter()
        .filter(|u| holds_p(&u.cell))
        .map(|u| width(&u.cell))
        .fold(0.0, f64::max);
    if largest == 0.0 {
        return None;
    }
    for depth in STAR_MIN_DEPTH..=solver.opts.max_depth.min(60) {
        let side = (-f64::from(depth)).exp2();
        if side < largest
            || solver
                .opts
                .deadline
                .is_some_and(|d| std::time::Instant::now() >= d)
        {
            break;
        }
        // The dyadic box of this depth around the point.
        let cell: DyadicBoxN = exact
            .iter()
            .map(|x| {
                let scale = Rational::from(rug::Integer::from(1) << depth);
                let i = Rational::from(x * &scale).floor();
                let top = rug::Integer::from(1) << depth;
                let i = i.numer().clone().min(top.clone() - 1u32);
                let lo = i.to_u64().expect("depth ≤ 60");
                (Dyadic::new(lo, depth), Dyadic::new(lo + 1, depth))
            })
            .collect();
        let lo: Vec<Rational> = cell.iter().map(|d| d.0.to_rational()).collect();
        let hi: Vec<Rational> = cell.iter().map(|d| d.1.to_rational()).collect();
        if !solver.singular[k].admissible_in(&lo, &hi) {
            continue;
        }
        let fcell = f64_box(&cell);
        if leaves.dropped.iter().any(|d| overlaps(d, &fcell)) {
            continue;
        }
        // The box's polynomials, for its face crossings (only if its boundary is decided).
        let polys = || -> Vec<Bernstein<Interval>> {
            eqs.iter()
                .map(|f| f.restrict_box_rational(&lo, &hi).convert(Precision::F64))
                .collect()
        };
        let Settled::Arcs {
            center: Some(center),
            monotone_in,
            crossings,
            deviations,
            accurate,
        } = solver.star(&cell, &polys, k)
        else {
            continue;
        };
        let deepest = 0.5 * side < largest;
        if !accurate && !deepest {
            continue;
        }
        // Replace the leaves inside the box by the star.
        leaves.retain_outside(&fcell);
        out.unresolved.retain(|u| !within(&u.cell, &fcell));
        out.within_tolerance &= accurate;
        let c = leaves.crossings.len();
        let count = crossings.len();
        leaves.crossings.push(center);
        for (j, deviation) in deviations.into_iter().enumerate() {
            leaves.arcs.push(RawArc {
                from: c,
                to: c + 1 + j,
                cell: fcell.clone(),
                monotone_in,
                deviation,
            });
        }
        leaves.crossings.extend(crossings);
        return Some(count);
    }
    // Not decided: the undecided boxes that hold the point say so.
    for u in out.unresolved.iter_mut().filter(|u| holds_p(&u.cell)) {
        u.reason = Reason::UnresolvedSingularPoint;
    }
    None
}
impl Leaves {
    /// Drops the arcs (and their crossings) of the leaves inside `cell`.
    pub(crate) fn retain_outside(&mut self, cell: &[[f64; 2]]) {
        let mut keep_crossing = vec![true; self.crossings.len()];
        let arcs = std::mem::take(&mut self.arcs);
        let mut kept = Vec::with_capacity(arcs.len());
        for a in arcs {
            if within(&a.cell, cell) {
                keep_crossing[a.from] = false;
                keep_crossing[a.to] = false;
            } else {
                kept.push(a);
            }
        }
        let mut index = vec![usize::MAX; self.crossings.len()];
        let crossings = std::mem::take(&mut self.crossings);
        for (k, c) in crossings.into_iter().enumerate() {
            if keep_crossing[k] {
                index[k] = self.crossings.len();
                self.crossings.push(c);
            }
        }
        for a in kept.iter_mut() {
            a.from = index[a.from];
            a.to = index[a.to];
        }
        self.arcs = kept;
    }
}
/// The most undecided boxes looked at for exact singular points, and the most candidates
/// checked exactly.
pub(crate) const SINGULAR_BOXES: usize = 512;
pub(crate) const SINGULAR_CANDIDATES: usize = 24;
/// The most singular points kept per curve. On a 2-dimensional set of solutions (a plane
/// tangent along a circle, for bitangents) every point is one, and their stars all fail.
pub(crate) const SINGULAR_POINTS: usize = 4;
/// The exact singular points of `F = 0` at the simplest rational points near undecided boxes
/// whose reason is a Jacobian not proven regular (each checked exactly).
pub(crate) fn singular_points_near(
    eqs: &[Bernstein<Rational>],
    unresolved: &[SpaceUnresolved],
    opts: &SpaceCurveOptions,
) -> Vec<SingularPoint> {
    // The simplest candidates first (the sum of their denominators' sizes): where a whole
    // set of points is singular, the ones listed are the simple ones.
    let mut seen = std::collections::HashSet::new();
    let mut candidates: Vec<Vec<Rational>> = unresolved
        .iter()
        .filter(|u| u.reason == Reason::NoRegularMinor)
        .take(SINGULAR_BOXES)
        .flat_map(|u| simple_points_near(&u.cell))
        .filter(|p| seen.insert(p.clone()))
        .collect();
    let size = |p: &Vec<Rational>| -> u32 { p.iter().map(|x| x.denom().significant_bits()).sum() };
    candidates.sort_by_cached_key(size);
    candidates.truncate(SINGULAR_CANDIDATES);
    // Interval values first: most candidates are off the curve, which they show cheaply.
    let enclosed: Vec<Bernstein<Interval>> =
        eqs.iter().map(|f| f.convert(Precision::F64)).collect();
    let maybe_zero = |p: &[Rational]| {
        let at: Vec<Interval> = p
            .iter()
            .map(|x| Interval::from_rational(x, Precision::F64))
            .collect();
        enclosed.iter().all(|f| f.eval(&at).contains(0.0))
    };
    let maybe: Vec<Vec<Rational>> = candidates.into_iter().filter(|p| maybe_zero(p)).collect();
    if maybe.is_empty() {
        return Vec::new();
    }
    let partials = ExactPartials::new(eqs);
    maybe
        .into_iter()
        .take_while(|_| opts.deadline.is_none_or(|d| std::time::Instant::now() < d))
        .filter_map(|p| exact_singular_point(eqs, &partials, p))
        .take(SINGULAR_POINTS)
        .collect()
}
