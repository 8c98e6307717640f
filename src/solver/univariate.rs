//! Certified isolation of the real roots of a univariate polynomial on [0, 1].
//!
//! Descartes' rule of signs in the Bernstein basis: the number of roots in the open interval
//! is at most the number of sign variations of the coefficients and has the same parity
//! (`proofs/bernstein-descartes.md`). So 0 variations prove no root and 1 variation proves
//! exactly one, simple. Coefficient signs are decided by the precision controller; exact
//! roots at dyadic split points are found by exact evaluation.

use crate::bernstein::Bernstein;
use crate::number::{Certified, Interval, Number, Precision, Rational, Sign};
use crate::solver::dyadic::{Dyadic, MAX_DEPTH};
use crate::solver::precision::{Policy, Question};

/// An isolated root.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Root {
    /// Exactly at this dyadic point.
    At {
        /// The root.
        t: Dyadic,
    },
    /// Exactly one root, simple, in the open interval (lo, hi); none at the ends unless
    /// reported separately as `At`.
    Between {
        /// Lower end.
        lo: Dyadic,
        /// Upper end.
        hi: Dyadic,
    },
}

impl Root {
    /// The lower end of where the root is.
    pub fn lo(&self) -> Dyadic {
        match *self {
            Root::At { t } => t,
            Root::Between { lo, .. } => lo,
        }
    }

    /// The upper end of where the root is.
    pub fn hi(&self) -> Dyadic {
        match *self {
            Root::At { t } => t,
            Root::Between { hi, .. } => hi,
        }
    }

    /// A representative value (the midpoint).
    pub fn mid_f64(&self) -> f64 {
        0.5 * (self.lo().to_f64() + self.hi().to_f64())
    }
}

/// The roots of a polynomial on [0, 1], in increasing order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Roots {
    /// Isolated roots, sorted, pairwise disjoint.
    pub roots: Vec<Root>,
    /// Intervals where the roots could not be isolated within the depth budget (a multiple
    /// root, or clustered roots): each may hold any number of roots.
    pub unresolved: Vec<(Dyadic, Dyadic)>,
    /// The polynomial is identically zero.
    pub identically_zero: bool,
}

/// The signs of the Bernstein coefficients of `p` on `[lo, hi]`.
struct CoefficientSigns<'a> {
    p: &'a Bernstein<Rational>,
    lo: Dyadic,
    hi: Dyadic,
}

impl Question for CoefficientSigns<'_> {
    type Answer = Vec<Sign>;
    fn answer_in<N: Certified>(&self, prec: Precision) -> Option<Vec<Sign>> {
        let q: Bernstein<N> = self.p.convert(prec);
        let r = q.restrict(0, &self.lo.to_number(prec), &self.hi.to_number(prec));
        let s: Vec<Sign> = r.coeffs().iter().map(|c| c.sign()).collect();
        s.iter().all(|x| x.is_known()).then_some(s)
    }
}

/// The sign of `p(t)`.
pub(crate) struct PointSign<'a> {
    pub p: &'a Bernstein<Rational>,
    pub t: Vec<Dyadic>,
}

impl Question for PointSign<'_> {
    type Answer = Sign;
    fn answer_in<N: Certified>(&self, prec: Precision) -> Option<Sign> {
        let q: Bernstein<N> = self.p.convert(prec);
        let x: Vec<N> = self.t.iter().map(|d| d.to_number(prec)).collect();
        let s = q.eval(&x).sign();
        s.is_known().then_some(s)
    }
}

fn variations(signs: &[Sign]) -> usize {
    let mut last = Sign::Zero;
    let mut v = 0;
    for &s in signs {
        if s.is_nonzero() {
            if last.is_nonzero() && s != last {
                v += 1;
            }
            last = s;
        }
    }
    v
}

/// Isolates the roots of a univariate exact polynomial on [0, 1].
///
/// Complete and sound (`proofs/bernstein-descartes.md`): every root in [0, 1] lies in exactly
/// one returned `Root` or in an `unresolved` interval; each `Between` holds exactly one root.
/// Intervals are split at most to depth `max_depth` (≤ 60).
///
/// # Panics
/// If `p` does not have exactly one variable.
pub fn isolate_roots(p: &Bernstein<Rational>, max_depth: u32, policy: &mut Policy) -> Roots {
    isolate_roots_in(p, Dyadic::ZERO, Dyadic::ONE, max_depth, policy)
}

/// Isolates the roots of `p` in `[lo, hi]` ⊂ [0, 1] (the same guarantees as
/// [`isolate_roots`]; intervals are dyadic subintervals of `[lo, hi]`, in the coordinates of
/// `p`). `identically_zero` is set when `p` vanishes on the whole of `[lo, hi]` (then `p` is
/// the zero polynomial).
///
/// # Panics
/// If `p` does not have exactly one variable, or `lo >= hi`.
pub fn isolate_roots_in(
    p: &Bernstein<Rational>,
    lo: Dyadic,
    hi: Dyadic,
    max_depth: u32,
    policy: &mut Policy,
) -> Roots {
    assert_eq!(p.nvars(), 1, "univariate");
    assert!(lo < hi, "empty interval");
    let mut out = Roots::default();
    if p.is_zero() {
        out.identically_zero = true;
        return out;
    }
    let max_depth = max_depth.min(MAX_DEPTH);
    let n = p.degrees()[0];
    for t in [lo, hi] {
        let s = match policy.decide(&PointSign { p, t: vec![t] }).0 {
            Some(s) => s,
            None => Sign::Unknown,
        };
        if s.is_zero() {
            out.roots.push(Root::At { t });
        }
    }
    let start: Bernstein<Interval> = if (lo, hi) == (Dyadic::ZERO, Dyadic::ONE) {
        p.convert(Precision::F64)
    } else {
        // Restricted exactly, then enclosed: data derived from the exact input.
        p.restrict_rational(0, &lo.to_rational(), &hi.to_rational())
            .convert(Precision::F64)
    };
    let mut stack: Vec<(Dyadic, Dyadic, u32, Bernstein<Interval>)> = vec![(lo, hi, 0, start)];
    while let Some((lo, hi, depth, coeffs)) = stack.pop() {
        let mut signs: Vec<Sign> = coeffs.coeffs().iter().map(|c| c.sign()).collect();
        if signs.iter().any(|s| !s.is_known()) {
            match policy.escalate(&CoefficientSigns { p, lo, hi }).0 {
                Some(s) => signs = s,
                None => {
                    out.unresolved.push((lo, hi));
                    continue;
                }
            }
        } else {
            policy
                .counts
                .record(Some(crate::solver::precision::Level::F64));
        }
        match variations(&signs) {
            0 => {}
            1 => out.roots.push(Root::Between { lo, hi }),
            _ => {
                let split = if depth < max_depth {
                    lo.midpoint(hi)
                } else {
                    None
                };
                let Some(mid) = split else {
                    out.unresolved.push((lo, hi));
                    continue;
                };
                let (left, right) = coeffs.subdivide_half(0);
                let mid_sign = match left.coeffs()[n].sign() {
                    s if s.is_known() => s,
                    _ => policy
                        .escalate(&PointSign { p, t: vec![mid] })
                        .0
                        .unwrap_or(Sign::Unknown),
                };
                match mid_sign {
                    Sign::Zero => out.roots.push(Root::At { t: mid }),
                    Sign::Unknown => {
                        out.unresolved.push((lo, hi));
                        continue;
                    }
                    _ => {}
                }
                stack.push((mid, hi, depth + 1, right));
                stack.push((lo, mid, depth + 1, left));
            }
        }
    }
    out.roots
        .sort_by_key(|r| (r.lo(), matches!(r, Root::Between { .. })));
    out.unresolved.sort();
    out
}

/// Narrows an isolated root to an interval of width at most `width` (a `Between` stays a
/// `Between` of one root, or becomes `At` if a split point is the root).
///
/// Bisection on the variation count: the half with one variation holds the root
/// (`proofs/bernstein-descartes.md`). The f64-interval coefficients of the current interval
/// are carried down (enclosures, `proofs/de-casteljau-enclosure.md`); a sign they cannot decide
/// is recomputed from the exact polynomial by the precision ladder.
pub fn refine_root(p: &Bernstein<Rational>, root: Root, width: f64, policy: &mut Policy) -> Root {
    let Root::Between { mut lo, mut hi } = root else {
        return root;
    };
    let n = p.degrees()[0];
    let mut coeffs: Bernstein<Interval> = p
        .restrict_rational(0, &lo.to_rational(), &hi.to_rational())
        .convert(Precision::F64);
    while hi.to_f64() - lo.to_f64() > width {
        let Some(mid) = lo.midpoint(hi) else { break };
        let (left, right) = coeffs.subdivide_half(0);
        let s_mid = match left.coeffs()[n].sign() {
            s if s.is_known() => s,
            _ => policy
                .escalate(&PointSign { p, t: vec![mid] })
                .0
                .unwrap_or(Sign::Unknown),
        };
        match s_mid {
            Sign::Zero => return Root::At { t: mid },
            Sign::Unknown => break,
            _ => {}
        }
        let fast: Vec<Sign> = left.coeffs().iter().map(|c| c.sign()).collect();
        let signs = if fast.iter().all(|s| s.is_known()) {
            Some(fast)
        } else {
            policy.escalate(&CoefficientSigns { p, lo, hi: mid }).0
        };
        match signs.map(|s| variations(&s)) {
            Some(1) => {
                hi = mid;
                coeffs = left;
            }
            Some(0) => {
                lo = mid;
                coeffs = right;
            }
            _ => break,
        }
    }
    Root::Between { lo, hi }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::precision::{Escalations, Ladder};

    /// (t - r1)(t - r2)... in Bernstein form of the given degree, exactly.
    fn from_roots(roots: &[Rational]) -> Bernstein<Rational> {
        let mut p = Bernstein::constant(1, Rational::from(1));
        for r in roots {
            // t - r: coefficients (-r, 1 - r).
            let lin =
                Bernstein::new(&[1], vec![Rational::from(-r), Rational::from(1 - r)]).unwrap();
            p = &p * &lin;
        }
        p
    }

    fn contains(root: &Root, x: &Rational) -> bool {
        match root {
            Root::At { t } => t.to_rational() == *x,
            Root::Between { lo, hi } => lo.to_rational() < *x && *x < hi.to_rational(),
        }
    }

    #[test]
    fn isolates_simple_exact_and_close_roots() {
        let q = |a: i64, b: i64| Rational::from((a, b));
        let roots = [
            q(1, 3),
            q(1, 2),
            q(1, 3) + Rational::from((1u64, 1u64 << 40)),
            q(0, 1),
            q(9, 10),
        ];
        let p = from_roots(&roots);
        let mut stats = Escalations::default();
        let ladder = Ladder::default();
        let r = isolate_roots(&p, 60, &mut Policy::new(&ladder, &mut stats));
        assert!(r.unresolved.is_empty(), "{:?}", r.unresolved);
        assert_eq!(r.roots.len(), roots.len());
        for x in &roots {
            assert_eq!(
                r.roots.iter().filter(|root| contains(root, x)).count(),
                1,
                "{x}"
            );
        }
        // 1/2 and 0 are dyadic: found exactly.
        assert!(r.roots.contains(&Root::At {
            t: Dyadic::new(1, 1)
        }));
        assert!(r.roots.contains(&Root::At { t: Dyadic::ZERO }));
        // Refinement keeps the root.
        let third = r
            .roots
            .iter()
            .find(|root| contains(root, &q(1, 3)))
            .unwrap();
        let fine = refine_root(&p, *third, 1e-12, &mut Policy::new(&ladder, &mut stats));
        assert!(contains(&fine, &q(1, 3)));
        assert!(fine.hi().to_f64() - fine.lo().to_f64() <= 1e-12);
    }

    #[test]
    fn double_root_is_unresolved_not_guessed() {
        let q = |a: i64, b: i64| Rational::from((a, b));
        let p = from_roots(&[q(1, 3), q(1, 3)]);
        let (ladder, mut counts) = (Ladder::default(), Escalations::default());
        let r = isolate_roots(&p, 20, &mut Policy::new(&ladder, &mut counts));
        assert!(r.roots.is_empty());
        assert_eq!(r.unresolved.len(), 1);
        let (a, b) = r.unresolved[0];
        assert!(a.to_rational() < q(1, 3) && q(1, 3) < b.to_rational());
        let zero = Bernstein::new(&[2], vec![Rational::new(); 3]).unwrap();
        assert!(isolate_roots(&zero, 20, &mut Policy::new(&ladder, &mut counts)).identically_zero);
    }
}
