//! The strict sign of `g` or a partial derivative on a box, through the precision ladder:
//! f64 intervals first, then the box's polynomial recomputed from the exact input
//! (`proofs/curve-topology.md`).

use crate::bernstein::Bernstein;
use crate::number::{Certified, Interval, Number, Precision, Rational, Sign};
use crate::solver::dyadic::DyadicBox;
use crate::solver::precision::{Escalations, Ladder, Level, Question};

/// The signs of the Bernstein coefficients of `p` restricted to a box, when all are known.
pub(crate) struct BoxSigns<'a> {
    pub(crate) p: &'a Bernstein<Rational>,
    pub(crate) cell: DyadicBox,
}
impl Question for BoxSigns<'_> {
    type Answer = Sign;
    fn answer_in<N: Certified>(&self, prec: Precision) -> Option<Sign> {
        let q: Bernstein<N> = self.p.convert(prec);
        let lo: Vec<N> = self.cell.lo.iter().map(|d| d.to_number(prec)).collect();
        let hi: Vec<N> = self.cell.hi.iter().map(|d| d.to_number(prec)).collect();
        let r = q.restrict_box(&lo, &hi);
        let signs: Vec<Sign> = r.coeffs().iter().map(|c| c.sign()).collect();
        if signs.iter().any(|s| !s.is_known()) {
            return None;
        }
        // Strict common sign, or Unknown meaning "not of one strict sign" (a decided answer).
        Some(match Sign::common(signs) {
            s @ (Sign::Positive | Sign::Negative) => s,
            _ => Sign::Unknown,
        })
    }
}
/// The depth from which undecided box signs are escalated beyond f64.
pub(crate) const ESCALATION_DEPTH: u32 = 10;
/// The strict sign of `p` on the box if its coefficients prove one, else `Unknown`, with the
/// level that proved it. `fast` are the f64-interval coefficients carried down the subdivision.
pub(crate) fn strict_sign(
    fast: &Bernstein<Interval>,
    exact: &Bernstein<Rational>,
    cell: DyadicBox,
    ladder: Option<&Ladder>,
    stats: &mut Escalations,
) -> (Sign, Option<Level>) {
    let mut pos = false;
    let mut neg = false;
    let mut unknown = false;
    for c in fast.coeffs() {
        match c.sign() {
            Sign::Positive => pos = true,
            Sign::Negative => neg = true,
            Sign::Zero => {
                // A zero coefficient: not strictly signed by this test.
                pos = true;
                neg = true;
            }
            Sign::Unknown => unknown = true,
        }
        if pos && neg {
            return (Sign::Unknown, None);
        }
    }
    if !unknown {
        stats.record(Some(Level::F64));
        let s = if pos { Sign::Positive } else { Sign::Negative };
        return (s, Some(Level::F64));
    }
    // Only one strict sign seen and some undecided coefficients: recompute from exact input,
    // if the caller wants escalation here (it may prefer to subdivide first).
    match ladder {
        Some(l) => match l.escalate(&BoxSigns { p: exact, cell }, stats) {
            (Some(s), level) if s.is_known() => (s, level),
            _ => (Sign::Unknown, None),
        },
        None => (Sign::Unknown, None),
    }
}
