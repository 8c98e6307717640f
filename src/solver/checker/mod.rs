//! The independent checker of curve certificates ([`CurveCertificate`]), in exact arithmetic
//! (`proofs/certificate-check.md`).
//!
//! It shares no code with the fast path: g is read from the certificate's exact rational
//! strings with `num-rational`, scaled to integers, and every test (tiling, signs on boxes,
//! roots on lines, the arcs in each monotone box, the chaining) is recomputed with the
//! checker's own dyadic de Casteljau arithmetic ([`arith`]), written from the proof rather
//! than from the solver. It never trusts a claim it can recompute: it derives the arcs of
//! every box from the verified crossings and compares.

mod arcs;
pub mod arith;
mod crossings;

use crate::solver::certificate::{CellClaim, CurveCertificate};
use arcs::{check_branches, compare_arcs, derive_arcs};
use arith::{sign, Dy, IPoly};
use crossings::{parse_crossings, separate_on_lines, verify_roots};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::collections::BTreeSet;

/// The first claim that failed, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CheckFailure {
    /// Which item (e.g. "cell 12", "crossing 3", "arcs of cell 7").
    pub item: String,
    /// What is wrong.
    pub reason: String,
}

impl std::fmt::Display for CheckFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.item, self.reason)
    }
}

impl std::error::Error for CheckFailure {}

/// What a valid certificate was verified to contain.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct CheckSummary {
    /// Cells verified (including unresolved ones, which claim nothing).
    pub cells: usize,
    /// Unresolved cells: the certificate proves nothing inside them.
    pub unresolved: usize,
    /// Crossings verified as roots.
    pub crossings: usize,
    /// Arcs recomputed and matched.
    pub arcs: usize,
    /// Branches verified.
    pub branches: usize,
}

pub(super) fn fail<T>(
    item: impl Into<String>,
    reason: impl Into<String>,
) -> Result<T, CheckFailure> {
    Err(CheckFailure {
        item: item.into(),
        reason: reason.into(),
    })
}

/// Parses an exact rational "p", "p/q" or "-p/q".
pub fn parse_rational(s: &str, item: &str) -> Result<BigRational, CheckFailure> {
    let bad = || CheckFailure {
        item: item.into(),
        reason: format!("{s:?} is not an exact rational p/q"),
    };
    let (n, d) = match s.split_once('/') {
        Some((n, d)) => (n, d),
        None => (s, "1"),
    };
    let n: BigInt = n.trim().parse().map_err(|_| bad())?;
    let d: BigInt = d.trim().parse().map_err(|_| bad())?;
    if d.is_zero() {
        return Err(bad());
    }
    Ok(BigRational::new(n, d))
}

/// Parses an exact dyadic rational "p" or "p/2^k" (every position in a certificate is one).
pub(super) fn parse_dyadic(s: &str, item: &str) -> Result<Dy, CheckFailure> {
    Dy::parse(s).ok_or_else(|| CheckFailure {
        item: item.into(),
        reason: format!("{s:?} is not an exact dyadic rational p/2^k"),
    })
}

/// Sign variations of a coefficient sequence (zeros skipped).
pub(super) fn variations(c: &[BigInt]) -> usize {
    let mut last = 0;
    let mut v = 0;
    for s in c.iter().map(sign).filter(|&s| s != 0) {
        if last != 0 && s != last {
            v += 1;
        }
        last = s;
    }
    v
}

fn lcm(a: &BigInt, b: &BigInt) -> BigInt {
    use num_integer::Integer;
    a.lcm(b)
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Kind {
    Excluded,
    Graph { m: usize },
    Unresolved,
}

pub(super) struct Cell {
    pub(super) lo: [Dy; 2],
    pub(super) hi: [Dy; 2],
    pub(super) kind: Kind,
}

/// Checks a curve certificate: every claim is recomputed in exact arithmetic.
///
/// Returns what was verified, or the first item that failed.
pub fn check_curve(cert: &CurveCertificate) -> Result<CheckSummary, CheckFailure> {
    let [du, dv] = cert.degrees;
    if du > 256 || dv > 256 || cert.g.len() != (du + 1) * (dv + 1) {
        return fail("g", "the coefficient count does not match the degrees");
    }
    let coeffs = cert
        .g
        .iter()
        .enumerate()
        .map(|(i, s)| parse_rational(s, &format!("g coefficient {i}")))
        .collect::<Result<Vec<BigRational>, _>>()?;
    // A positive multiple with integer coefficients: same signs, same zeros.
    let lcm = coeffs.iter().fold(BigInt::one(), |l, c| lcm(&l, c.denom()));
    let g = IPoly {
        deg: vec![du, dv],
        c: coeffs
            .iter()
            .map(|c| (c * BigRational::from_integer(lcm.clone())).to_integer())
            .collect(),
    };
    let zero = g.is_zero();
    if cert.identically_zero {
        if !zero {
            return fail("g", "claimed identically zero, but a coefficient is not");
        }
        if !cert.cells.is_empty() || !cert.arcs.is_empty() {
            return fail("g", "identically zero, yet cells or arcs are claimed");
        }
        return Ok(CheckSummary::default());
    }
    if zero {
        return fail(
            "g",
            "g is identically zero, which the certificate does not claim",
        );
    }
    let mut summary = CheckSummary::default();
    let cells = check_cells(&g, &cert.cells, &mut summary)?;
    if cert.certified && summary.unresolved > 0 {
        return fail(
            "certificate",
            "claims the square is decided, but lists unresolved cells",
        );
    }
    let mut crossings = parse_crossings(&cert.crossings)?;
    verify_roots(&g, &mut crossings)?;
    summary.crossings = crossings.len();
    separate_on_lines(&g, &mut crossings)?;
    let derived = derive_arcs(&g, &cells, &mut crossings)?;
    compare_arcs(cert, &cells, &derived)?;
    summary.arcs = cert.arcs.len();
    check_branches(cert, &crossings, &derived)?;
    summary.branches = cert.branches.len();
    Ok(summary)
}

/// Parses the cells, checks that they tile the unit square (distinct dyadic squares whose
/// areas sum to 1, none inside another), and checks each sign claim.
pub(super) fn check_cells(
    g: &IPoly,
    claims: &[CellClaim],
    summary: &mut CheckSummary,
) -> Result<Vec<Cell>, CheckFailure> {
    let mut cells = Vec::with_capacity(claims.len());
    let mut keys: BTreeSet<(u32, BigInt, BigInt)> = BTreeSet::new();
    let derivs = [g.deriv(0), g.deriv(1)];
    for (i, c) in claims.iter().enumerate() {
        let item = format!("cell {i}");
        let q = |s: &String| parse_dyadic(s, &item);
        let lo = [q(&c.lo[0])?, q(&c.lo[1])?];
        let hi = [q(&c.hi[0])?, q(&c.hi[1])?];
        // A dyadic square: side 1/2^k, corner at (iu, iv)/2^k, inside the unit square.
        let side = hi[0].sub(&lo[0]);
        if side != hi[1].sub(&lo[1]) || side.sign() <= 0 {
            return fail(item, "not a square");
        }
        let k = side.exp();
        if side.num_at(k) != BigInt::one() {
            return fail(item, "its side is not 1/2^k");
        }
        if lo[0].exp() > k || lo[1].exp() > k {
            return fail(item, "not aligned to the dyadic grid of its size");
        }
        let (iu, iv) = (lo[0].num_at(k), lo[1].num_at(k));
        let n = BigInt::one() << k as usize;
        if iu.is_negative() || iv.is_negative() || iu >= n || iv >= n {
            return fail(item, "outside the unit square");
        }
        if !keys.insert((k, iu.clone(), iv.clone())) {
            return fail(item, "listed twice");
        }
        let kind = match (c.kind.as_str(), c.sign, c.along.as_deref()) {
            ("excluded", Some(s @ (1 | -1)), _) => {
                let r = g.restrict(0, &lo[0], &hi[0]).restrict(1, &lo[1], &hi[1]);
                if r.c.iter().any(|x| sign(x) != s) {
                    return fail(item, format!("g does not have the strict sign {s:+} on it"));
                }
                Kind::Excluded
            }
            ("graph", Some(s @ (1 | -1)), Some(along @ ("u" | "v"))) => {
                let m = usize::from(along == "v");
                let r = derivs[m]
                    .restrict(0, &lo[0], &hi[0])
                    .restrict(1, &lo[1], &hi[1]);
                if r.c.iter().any(|x| sign(x) != s) {
                    return fail(
                        item,
                        format!("∂g/∂{along} does not have the strict sign {s:+} on it"),
                    );
                }
                Kind::Graph { m }
            }
            ("unresolved", _, _) => {
                summary.unresolved += 1;
                Kind::Unresolved
            }
            _ => return fail(item, "unknown kind, or a sign or variable missing"),
        };
        cells.push(Cell { lo, hi, kind });
    }
    // Their areas, 4^-k each, sum to 1.
    let kmax = keys.iter().map(|k| k.0).max().unwrap_or(0);
    let area: BigInt = keys
        .iter()
        .map(|k| BigInt::one() << (2 * (kmax - k.0)) as usize)
        .sum();
    if area != BigInt::one() << (2 * kmax) as usize {
        return fail("cells", "their areas do not sum to the unit square");
    }
    // Dyadic squares either nest or have disjoint interiors: none may contain another.
    for (k, iu, iv) in &keys {
        for up in 1..=*k {
            let key = (k - up, iu >> up as usize, iv >> up as usize);
            if keys.contains(&key) {
                return fail("cells", "one cell lies inside another");
            }
        }
    }
    summary.cells = cells.len();
    Ok(cells)
}
