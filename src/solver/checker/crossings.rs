//! The certificate's crossings: parsed, each root verified on its line, and the roots on one
//! line separated (`proofs/certificate-check.md`).

use super::arith::{Dy, IPoly};
use super::{fail, parse_dyadic, variations, CheckFailure};
use crate::solver::certificate::CrossingClaim;
use std::collections::BTreeMap;

/// A parsed crossing: on which lines it lies and where along them.
#[derive(Clone, Debug)]
pub(super) enum Crossing {
    Point([Dy; 2]),
    OnLine {
        fixed: usize,
        at: Dy,
        lo: Dy,
        hi: Dy,
    },
}

impl Crossing {
    /// Its closed interval along the line (fixed, c), if it lies on that line.
    pub(super) fn on_line(&self, fixed: usize, c: &Dy) -> Option<(Dy, Dy)> {
        match self {
            Crossing::Point(p) => {
                (p[fixed] == *c).then(|| (p[1 - fixed].clone(), p[1 - fixed].clone()))
            }
            Crossing::OnLine {
                fixed: f,
                at,
                lo,
                hi,
            } => (*f == fixed && at == c).then(|| (lo.clone(), hi.clone())),
        }
    }
}

pub(super) fn parse_crossings(claims: &[CrossingClaim]) -> Result<Vec<Crossing>, CheckFailure> {
    claims
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let item = format!("crossing {i}");
            let q = |s: &String| parse_dyadic(s, &item);
            let in_unit = |x: &Dy| x.in_unit();
            let out = match c {
                CrossingClaim::Point { u, v } => Crossing::Point([q(u)?, q(v)?]),
                CrossingClaim::OnLine { line, at, lo, hi } => {
                    let fixed = match line.as_str() {
                        "u" => 0,
                        "v" => 1,
                        _ => return fail(item, "line must be \"u\" or \"v\""),
                    };
                    let (at, lo, hi) = (q(at)?, q(lo)?, q(hi)?);
                    if lo > hi {
                        return fail(item, "interval ends out of order");
                    }
                    Crossing::OnLine { fixed, at, lo, hi }
                }
            };
            let ok = match &out {
                Crossing::Point(p) => p.iter().all(in_unit),
                Crossing::OnLine { at, lo, hi, .. } => [at, lo, hi].into_iter().all(in_unit),
            };
            if !ok {
                return fail(item, "outside the unit square");
            }
            Ok(out)
        })
        .collect()
}

/// Each crossing is a root of g: exactly (a point), or the only root in its open interval,
/// simple (opposite strict signs at the ends and one sign variation of the restricted
/// coefficients: Descartes' rule in the Bernstein basis).
pub(super) fn verify_roots(g: &IPoly, crossings: &mut [Crossing]) -> Result<(), CheckFailure> {
    for (i, c) in crossings.iter_mut().enumerate() {
        let item = format!("crossing {i}");
        match c {
            Crossing::Point(p) => {
                if g.fix(0, &p[0]).sign_at(&p[1]) != 0 {
                    return fail(item, "g is not zero at this point");
                }
            }
            Crossing::OnLine { fixed, at, lo, hi } => {
                let p = g.fix(*fixed, at);
                if lo == hi {
                    if p.sign_at(lo) != 0 {
                        return fail(item, "g is not zero at this point");
                    }
                    continue;
                }
                let (a, b) = (p.sign_at(lo), p.sign_at(hi));
                if a == 0 || b == 0 || a == b {
                    return fail(item, "g does not change sign strictly across the interval");
                }
                if variations(&p.restrict(0, lo, hi).c) != 1 {
                    return fail(item, "the interval is not proven to hold a single root");
                }
            }
        }
    }
    Ok(())
}

/// Halves an isolating interval (keeping the root), or makes it a point if the midpoint is
/// the root. Returns false if it was already a point.
pub(super) fn bisect(g: &IPoly, c: &mut Crossing) -> bool {
    let Crossing::OnLine { fixed, at, lo, hi } = c else {
        return false;
    };
    if lo == hi {
        return false;
    }
    let p = g.fix(*fixed, at);
    let mid = lo.mid(hi);
    let (s_lo, s_mid) = (p.sign_at(lo), p.sign_at(&mid));
    if s_mid == 0 {
        *lo = mid.clone();
        *hi = mid;
    } else if s_mid == s_lo {
        *lo = mid;
    } else {
        *hi = mid;
    }
    true
}

/// Distinct crossings on the same line must be distinct roots: their closed intervals are
/// made disjoint by exact bisection (each holds one root, so two that cannot be separated
/// are the same root listed twice).
pub(super) fn separate_on_lines(g: &IPoly, crossings: &mut [Crossing]) -> Result<(), CheckFailure> {
    let mut lines: BTreeMap<(usize, Dy), Vec<usize>> = BTreeMap::new();
    for (i, c) in crossings.iter().enumerate() {
        match c {
            Crossing::Point(p) => {
                lines.entry((0, p[0].clone())).or_default().push(i);
                lines.entry((1, p[1].clone())).or_default().push(i);
            }
            Crossing::OnLine { fixed, at, .. } => {
                lines.entry((*fixed, at.clone())).or_default().push(i)
            }
        }
    }
    for ((fixed, at), members) in lines {
        for _ in 0..256 {
            let mut spans: Vec<(Dy, Dy, usize)> = members
                .iter()
                .map(|&i| {
                    let (lo, hi) = crossings[i].on_line(fixed, &at).expect("on the line");
                    (lo, hi, i)
                })
                .collect();
            spans.sort();
            let Some(w) = spans.windows(2).find(|w| w[1].0 <= w[0].1) else {
                break;
            };
            let (a, b) = (w[0].2, w[1].2);
            let moved_a = bisect(g, &mut crossings[a]);
            let moved_b = bisect(g, &mut crossings[b]);
            if !moved_a && !moved_b {
                return fail(
                    format!("crossings {a} and {b}"),
                    "the same root of g is listed twice",
                );
            }
        }
        let mut spans: Vec<(Dy, Dy)> = members
            .iter()
            .map(|&i| crossings[i].on_line(fixed, &at).expect("on the line"))
            .collect();
        spans.sort();
        if spans.windows(2).any(|w| w[1].0 <= w[0].1) {
            return fail("crossings", "two roots on one line could not be separated");
        }
    }
    Ok(())
}
