//! The atomic segments of the grid lines (the pieces into which the corners of all leaf
//! boxes cut a line) and the roots of `g` on each, isolated once, so that neighbouring boxes
//! of any sizes name the same crossing identically.

use crate::bernstein::Bernstein;
use crate::geometry::Rect;
use crate::number::{Interval, Number, Precision, Rational, Sign};
use crate::solver::dyadic::Dyadic;
use crate::solver::plane_curve::{CrossingId, CurveOptions};
use crate::solver::precision::{Escalations, Level, Policy};
use crate::solver::univariate::{isolate_roots_in, refine_root, PointSign, Root};
use std::collections::{BTreeMap, BTreeSet};

/// The polynomial g restricted to the grid line where variable `fixed` is `c`, as a
/// univariate polynomial in the other variable on [0, 1], up to a positive constant factor
/// (exact). `g_int` is g times the lcm of its denominators (integer coefficients); with
/// `c = p / q`, each fibre is evaluated by de Casteljau steps `x_i ← (q − p) x_i + p x_{i+1}`
/// in integers, which multiplies every fibre's value by the same `q^d`: roots and signs are
/// those of the exact restriction, without a gcd per step.
pub(crate) fn line_polynomial(
    g_int: &Bernstein<Rational>,
    fixed: usize,
    c: Dyadic,
) -> Bernstein<Rational> {
    let cq = c.to_rational();
    let (p, q) = (cq.numer().clone(), cq.denom().clone());
    let qp = rug::Integer::from(&q - &p);
    let [m, n] = [g_int.degrees()[0], g_int.degrees()[1]];
    let fibre = |k: usize| -> rug::Integer {
        let mut x: Vec<rug::Integer> = if fixed == 0 {
            (0..=m)
                .map(|i| g_int.coeff(&[i, k]).numer().clone())
                .collect()
        } else {
            (0..=n)
                .map(|j| g_int.coeff(&[k, j]).numer().clone())
                .collect()
        };
        let d = x.len() - 1;
        for r in 0..d {
            for i in 0..d - r {
                let next = rug::Integer::from(&p * &x[i + 1]);
                x[i] *= &qp;
                x[i] += next;
            }
        }
        std::mem::take(&mut x[0])
    };
    let coeffs: Vec<Rational> = (0..=if fixed == 0 { n } else { m })
        .map(|k| Rational::from(fibre(k)))
        .collect();
    Bernstein::new(&[coeffs.len() - 1], coeffs).expect("one variable")
}
/// `g` times the lcm of its coefficients' denominators (a positive constant): integer
/// coefficients, the same zeros and signs.
pub(crate) fn integer_multiple(g: &Bernstein<Rational>) -> Bernstein<Rational> {
    let mut l = rug::Integer::from(1);
    for c in g.coeffs() {
        l.lcm_mut(c.denom());
    }
    g.scale(&Rational::from(l))
}
/// What g does on one atomic segment of a grid line.
#[derive(Clone, Debug)]
pub(crate) enum SegmentRoots {
    /// Isolated roots strictly inside, in order.
    Roots(Vec<Root>),
    /// g vanishes on the whole segment.
    Zero,
    /// Not decided (a multiple root).
    Unresolved,
}
/// Lazily computed, shared knowledge about grid lines: breakpoints, point signs, segment roots.
pub(crate) struct Lines<'a> {
    pub(crate) g: &'a Bernstein<Rational>,
    /// `g` scaled to integer coefficients ([`integer_multiple`]), for exact line restrictions.
    pub(crate) g_int: Bernstein<Rational>,
    /// `g` in f64 intervals, derived once from the exact input (the fast path of point signs).
    pub(crate) g_fast: Bernstein<Interval>,
    pub(crate) opts: &'a CurveOptions,
    pub(crate) breakpoints: BTreeMap<(usize, Dyadic), BTreeSet<Dyadic>>,
    pub(crate) polys: BTreeMap<(usize, Dyadic), Bernstein<Rational>>,
    pub(crate) point_signs: BTreeMap<(Dyadic, Dyadic), Sign>,
    pub(crate) segments: BTreeMap<(usize, Dyadic, Dyadic, Dyadic), SegmentRoots>,
    pub(crate) stats: Escalations,
}
/// The point with `fixed` = c and the other variable = s, as (u, v).
pub(crate) fn uv(fixed: usize, c: Dyadic, s: Dyadic) -> (Dyadic, Dyadic) {
    if fixed == 0 {
        (c, s)
    } else {
        (s, c)
    }
}
impl<'a> Lines<'a> {
    pub(crate) fn poly(&mut self, fixed: usize, c: Dyadic) -> &Bernstein<Rational> {
        let g = &self.g_int;
        self.polys
            .entry((fixed, c))
            .or_insert_with(|| line_polynomial(g, fixed, c))
    }

    pub(crate) fn sign_at(&mut self, u: Dyadic, v: Dyadic) -> Sign {
        if let Some(s) = self.point_signs.get(&(u, v)) {
            return *s;
        }
        let x = [
            u.to_number::<Interval>(Precision::F64),
            v.to_number(Precision::F64),
        ];
        let fast = self.g_fast.eval(&x).sign();
        let s = if fast.is_known() {
            self.stats.record(Some(Level::F64));
            fast
        } else {
            let q = PointSign {
                p: self.g,
                t: vec![u, v],
            };
            self.opts
                .ladder
                .escalate(&q, &mut self.stats)
                .0
                .unwrap_or(Sign::Unknown)
        };
        self.point_signs.insert((u, v), s);
        s
    }

    /// The breakpoints of line (fixed, c) within [s0, s1], both included.
    pub(crate) fn cuts(&self, fixed: usize, c: Dyadic, s0: Dyadic, s1: Dyadic) -> Vec<Dyadic> {
        let mut v: Vec<Dyadic> = self
            .breakpoints
            .get(&(fixed, c))
            .map_or_else(Vec::new, |b| b.range(s0..=s1).copied().collect());
        if v.first() != Some(&s0) {
            v.insert(0, s0);
        }
        if v.last() != Some(&s1) {
            v.push(s1);
        }
        v
    }

    pub(crate) fn segment(
        &mut self,
        fixed: usize,
        c: Dyadic,
        s0: Dyadic,
        s1: Dyadic,
    ) -> SegmentRoots {
        if let Some(r) = self.segments.get(&(fixed, c, s0, s1)) {
            return r.clone();
        }
        let depth = self.opts.max_depth.saturating_add(16);
        let ladder = self.opts.ladder;
        let p = self.poly(fixed, c).clone();
        let roots = isolate_roots_in(
            &p,
            s0,
            s1,
            depth,
            &mut Policy::new(&ladder, &mut self.stats),
        );
        let r = if roots.identically_zero {
            SegmentRoots::Zero
        } else if !roots.unresolved.is_empty() {
            SegmentRoots::Unresolved
        } else {
            // Roots at the segment's ends are breakpoint zeros, reported as exact points.
            let inside = roots
                .roots
                .into_iter()
                .filter(|r| !matches!(r, Root::At { t } if *t == s0 || *t == s1))
                .collect();
            SegmentRoots::Roots(inside)
        };
        self.segments.insert((fixed, c, s0, s1), r.clone());
        r
    }
}
/// Where a crossing is, refined to `refine_width`: a box in (u, v) and, for a crossing inside
/// a segment, the exact isolating interval along its line.
pub(crate) fn locate(lines: &mut Lines, id: CrossingId) -> (Rect, Option<(Dyadic, Dyadic)>) {
    match id {
        CrossingId::Exact { u, v } => {
            let ((u0, u1), (v0, v1)) = (u.to_f64_bounds(), v.to_f64_bounds());
            (Rect::new([u0, v0], [u1, v1]), None)
        }
        CrossingId::Segment {
            fixed,
            c,
            s0,
            s1,
            k,
        } => {
            let (dlo, dhi) = match lines.segment(fixed, c, s0, s1) {
                SegmentRoots::Roots(r) if k < r.len() => {
                    let p = lines.poly(fixed, c).clone();
                    let mut policy = Policy::new(&lines.opts.ladder, &mut lines.stats);
                    let fine = refine_root(&p, r[k], lines.opts.refine_width, &mut policy);
                    (fine.lo(), fine.hi())
                }
                _ => (s0, s1),
            };
            let (lo, hi) = (dlo.to_f64_bounds().0, dhi.to_f64_bounds().1);
            let (c0, c1) = c.to_f64_bounds();
            let location = if fixed == 0 {
                Rect::new([c0, lo], [c1, hi])
            } else {
                Rect::new([lo, c0], [hi, c1])
            };
            (location, Some((dlo, dhi)))
        }
    }
}
/// Whether a crossing lies on the boundary of the unit square.
pub(crate) fn on_square_boundary(id: &CrossingId) -> bool {
    let end = |x: Dyadic| x == Dyadic::ZERO || x == Dyadic::ONE;
    match *id {
        CrossingId::Exact { u, v } => end(u) || end(v),
        CrossingId::Segment { c, .. } => end(c),
    }
}
