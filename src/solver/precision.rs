//! The precision controller: f64 intervals first; what they cannot decide is recomputed from
//! the exact input in MPFR intervals at doubling precision up to a cap, then in exact
//! rationals. Written once; every analysis decides its signs through it.

use crate::bernstein::Bernstein;
use crate::number::{Certified, Interval, MpInterval, Number, Precision, Rational};
use std::collections::BTreeMap;

/// A level of the precision ladder.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Level {
    /// `f64` intervals.
    F64,
    /// MPFR intervals at this many bits.
    Mpfr(u32),
    /// Exact rationals.
    Exact,
}

/// A question that can be answered in any certified number type, each time computed from the
/// exact input (never from another level's rounded data): a sign, a list of signs, ...
pub trait Question {
    /// What a conclusive answer is.
    type Answer;
    /// The answer computed in `N` at precision `prec`, or `None` when that precision cannot
    /// decide. A returned answer must be proven (it is computed with enclosures or exactly).
    fn answer_in<N: Certified>(&self, prec: Precision) -> Option<Self::Answer>;
}

/// The ladder of precisions to climb.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Ladder {
    /// The first MPFR precision tried after f64 (bits).
    pub mpfr_start: u32,
    /// The last MPFR precision tried (bits); the precision doubles from `mpfr_start`.
    pub mpfr_cap: u32,
    /// Whether exact rationals are the last resort (always decides a sign of an exact
    /// quantity; may be slow).
    pub exact: bool,
}

impl Default for Ladder {
    /// 106, 212, 424, 848 bits, then exact.
    fn default() -> Self {
        Ladder {
            mpfr_start: 106,
            mpfr_cap: 848,
            exact: true,
        }
    }
}

/// How many questions were settled at each level.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Escalations {
    /// Settled by f64 intervals.
    pub f64: u64,
    /// Settled by MPFR at each precision (bits → count).
    pub mpfr: BTreeMap<u32, u64>,
    /// Settled by exact rationals.
    pub exact: u64,
    /// Not settled by any level (only possible without the exact level).
    pub undecided: u64,
}

impl Escalations {
    /// Adds another tally to this one.
    pub fn merge(&mut self, other: &Escalations) {
        self.f64 += other.f64;
        for (p, n) in &other.mpfr {
            *self.mpfr.entry(*p).or_default() += n;
        }
        self.exact += other.exact;
        self.undecided += other.undecided;
    }

    /// Questions that needed more than f64.
    pub fn escalated(&self) -> u64 {
        self.mpfr.values().sum::<u64>() + self.exact + self.undecided
    }

    /// Records a question settled at `level`.
    pub fn record(&mut self, level: Option<Level>) {
        match level {
            Some(Level::F64) => self.f64 += 1,
            Some(Level::Mpfr(p)) => *self.mpfr.entry(p).or_default() += 1,
            Some(Level::Exact) => self.exact += 1,
            None => self.undecided += 1,
        }
    }
}

/// What a computation that decides signs is handed: the caller's ladder, and the tally into
/// which it counts the level that settled each question (so that the caller's settings are
/// used and the counts reach the caller's report).
#[derive(Debug)]
pub struct Policy<'a> {
    /// The ladder to climb.
    pub ladder: &'a Ladder,
    /// Where the questions are counted.
    pub counts: &'a mut Escalations,
    /// A wall-clock deadline for the computation's steps that are not sign questions (set
    /// with [`Policy::with_deadline`]; `None`: no limit).
    pub deadline: Option<std::time::Instant>,
}

impl<'a> Policy<'a> {
    /// The policy of this ladder, counting into `counts`.
    pub fn new(ladder: &'a Ladder, counts: &'a mut Escalations) -> Policy<'a> {
        Policy {
            ladder,
            counts,
            deadline: None,
        }
    }

    /// The same policy with a wall-clock deadline.
    pub fn with_deadline(mut self, deadline: Option<std::time::Instant>) -> Policy<'a> {
        self.deadline = deadline;
        self
    }

    /// Whether the deadline has passed.
    pub fn past_deadline(&self) -> bool {
        past(self.deadline)
    }

    /// [`Ladder::decide`] on this policy's ladder, counted in its tally.
    pub fn decide<Q: Question>(&mut self, q: &Q) -> (Option<Q::Answer>, Option<Level>) {
        self.ladder.decide(q, self.counts)
    }

    /// [`Ladder::escalate`] on this policy's ladder, counted in its tally.
    pub fn escalate<Q: Question>(&mut self, q: &Q) -> (Option<Q::Answer>, Option<Level>) {
        self.ladder.escalate(q, self.counts)
    }
}

impl Ladder {
    /// The ladder's tightest level: exact rationals if it has them, else its highest MPFR
    /// precision. Where the answer is an enclosure rather than a sign (polynomials restricted
    /// to a small box, then enclosed in f64 intervals), that level alone is used: a lower
    /// level's enclosure contains it, so it can settle nothing the tightest cannot.
    pub fn tightest(&self) -> Level {
        if self.exact {
            return Level::Exact;
        }
        let mut p = self.mpfr_start.max(54);
        while p.checked_mul(2).is_some_and(|next| next <= self.mpfr_cap) {
            p *= 2;
        }
        Level::Mpfr(p)
    }

    /// The exact polynomials restricted to the box `[lo, hi]` at the tightest level
    /// ([`Ladder::tightest`]), enclosed in f64 intervals, with the level used.
    pub fn restricted_enclosures<P: std::borrow::Borrow<Bernstein<Rational>>>(
        &self,
        exact: &[P],
        lo: &[Rational],
        hi: &[Rational],
    ) -> (Vec<Bernstein<Interval>>, Level) {
        let level = self.tightest();
        let polys = match level {
            Level::Mpfr(p) => {
                let prec = Precision(p);
                let to = |x: &[Rational]| -> Vec<MpInterval> {
                    x.iter()
                        .map(|v| MpInterval::from_rational(v, prec))
                        .collect()
                };
                let (lm, hm) = (to(lo), to(hi));
                exact
                    .iter()
                    .map(|e| {
                        let m: Bernstein<MpInterval> = e.borrow().convert(prec);
                        m.restrict_box(&lm, &hm).map(MpInterval::to_interval)
                    })
                    .collect()
            }
            _ => exact
                .iter()
                .map(|e| {
                    e.borrow()
                        .restrict_box_rational(lo, hi)
                        .convert(Precision::F64)
                })
                .collect(),
        };
        (polys, level)
    }

    /// Answers the question, starting with f64 intervals. Returns the answer and the level
    /// that settled it (`None` twice if no level did), and records it in `stats`.
    pub fn decide<Q: Question>(
        &self,
        q: &Q,
        stats: &mut Escalations,
    ) -> (Option<Q::Answer>, Option<Level>) {
        if let Some(a) = q.answer_in::<Interval>(Precision::F64) {
            stats.record(Some(Level::F64));
            return (Some(a), Some(Level::F64));
        }
        self.escalate(q, stats)
    }

    /// Answers the question above f64 (for callers whose own f64 data already failed).
    pub fn escalate<Q: Question>(
        &self,
        q: &Q,
        stats: &mut Escalations,
    ) -> (Option<Q::Answer>, Option<Level>) {
        let mut p = self.mpfr_start.max(54);
        while p <= self.mpfr_cap {
            if let Some(a) = q.answer_in::<MpInterval>(Precision(p)) {
                stats.record(Some(Level::Mpfr(p)));
                return (Some(a), Some(Level::Mpfr(p)));
            }
            match p.checked_mul(2) {
                Some(next) => p = next,
                None => break,
            }
        }
        if self.exact {
            if let Some(a) = q.answer_in::<Rational>(Precision(u32::MAX)) {
                stats.record(Some(Level::Exact));
                return (Some(a), Some(Level::Exact));
            }
        }
        stats.record(None);
        (None, None)
    }
}

/// Whether a deadline, if any, has passed: the one check behind every `--time-limit`.
pub fn past(deadline: Option<std::time::Instant>) -> bool {
    deadline.is_some_and(|d| std::time::Instant::now() >= d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::Sign;

    /// The sign of 3 × (1/10) − 3/10 + 2^-k: zero for k = ∞, tiny otherwise.
    struct Tiny(Option<u32>);

    impl Question for Tiny {
        type Answer = Sign;
        fn answer_in<N: Certified>(&self, prec: Precision) -> Option<Sign> {
            let tenth = N::from_rational(&Rational::from((1, 10)), prec);
            let three = N::from_i64(3, prec);
            let mut x = three
                .mul(&tenth)
                .sub(&N::from_rational(&Rational::from((3, 10)), prec));
            if let Some(k) = self.0 {
                let t = Rational::from((rug::Integer::from(1), rug::Integer::from(1) << k));
                x = x.add(&N::from_rational(&t, prec));
            }
            let s = x.sign();
            s.is_known().then_some(s)
        }
    }

    #[test]
    fn climbs_only_as_far_as_needed() {
        let ladder = Ladder::default();
        let mut stats = Escalations::default();
        // 2^-30 is far above f64's rounding of 0.1: but 3 × [0.1] − [0.3] has width ~1e-16,
        // so f64 decides.
        assert_eq!(
            ladder.decide(&Tiny(Some(30)), &mut stats),
            (Some(Sign::Positive), Some(Level::F64))
        );
        // 2^-80 needs more than 53 bits but less than 106.
        assert_eq!(
            ladder.decide(&Tiny(Some(80)), &mut stats),
            (Some(Sign::Positive), Some(Level::Mpfr(106)))
        );
        // 2^-300 needs 424 bits.
        assert_eq!(
            ladder.decide(&Tiny(Some(300)), &mut stats),
            (Some(Sign::Positive), Some(Level::Mpfr(424)))
        );
        // An exact zero is only decided exactly.
        assert_eq!(
            ladder.decide(&Tiny(None), &mut stats),
            (Some(Sign::Zero), Some(Level::Exact))
        );
        assert_eq!(stats.f64, 1);
        assert_eq!(stats.exact, 1);
        assert_eq!(stats.escalated(), 3);
        // Without the exact level, the zero stays undecided: reported, never guessed.
        let no_exact = Ladder {
            exact: false,
            ..Ladder::default()
        };
        assert_eq!(no_exact.decide(&Tiny(None), &mut stats), (None, None));
        assert_eq!(stats.undecided, 1);
    }

    #[test]
    fn enclosures_at_the_tightest_level_contain_the_exact_values() {
        assert_eq!(Ladder::default().tightest(), Level::Exact);
        let no_exact = Ladder {
            exact: false,
            ..Ladder::default()
        };
        assert_eq!(no_exact.tightest(), Level::Mpfr(848));
        // p(u, v) = (1/3)(1 − u)(1 − v) + (2/7) u v + ..., restricted to a small box.
        let q = |a: i64, b: i64| Rational::from((a, b));
        let p = Bernstein::new(&[1, 1], vec![q(1, 3), q(-5, 11), q(2, 9), q(2, 7)]).unwrap();
        let lo = [q(1, 1024), q(3, 8)];
        let hi = [q(3, 1024), q(25, 64)];
        let (exact, le) =
            Ladder::default().restricted_enclosures(std::slice::from_ref(&p), &lo, &hi);
        let (mpfr, lm) = no_exact.restricted_enclosures(std::slice::from_ref(&p), &lo, &hi);
        assert_eq!((le, lm), (Level::Exact, Level::Mpfr(848)));
        let truth = p.restrict_box_rational(&lo, &hi);
        for ((t, e), m) in truth
            .coeffs()
            .iter()
            .zip(exact[0].coeffs())
            .zip(mpfr[0].coeffs())
        {
            assert!(
                e.contains_rational(t) && m.contains_rational(t),
                "{t} {e:?} {m:?}"
            );
            // The exact level's enclosure is the tightest f64 one: inside the MPFR one.
            assert!(m.lo() <= e.lo() && e.hi() <= m.hi());
        }
    }
}
