//! The independent checker of curve certificates ([`CurveCertificate`]), in exact arithmetic
//! (`proofs/certificate-check.md`).
//!
//! It shares no code with the fast path: g is read from the certificate's exact rational
//! strings with `num-rational`, scaled to integers, and every test (tiling, signs on boxes,
//! roots on lines, the arcs in each monotone box, the chaining) is recomputed with the
//! checker's own dyadic de Casteljau arithmetic ([`arith`]), written from the proof rather
//! than from the solver. It never trusts a claim it can recompute: it derives the arcs of
//! every box from the verified crossings and compares.

pub mod arith;

use crate::solver::certificate::{CellClaim, CrossingClaim, CurveCertificate};
use arith::{sign, Dy, IPoly};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::collections::{BTreeMap, BTreeSet};

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

fn fail<T>(item: impl Into<String>, reason: impl Into<String>) -> Result<T, CheckFailure> {
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
fn parse_dyadic(s: &str, item: &str) -> Result<Dy, CheckFailure> {
    Dy::parse(s).ok_or_else(|| CheckFailure {
        item: item.into(),
        reason: format!("{s:?} is not an exact dyadic rational p/2^k"),
    })
}

/// Sign variations of a coefficient sequence (zeros skipped).
fn variations(c: &[BigInt]) -> usize {
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

/// A parsed crossing: on which lines it lies and where along them.
#[derive(Clone, Debug)]
enum Crossing {
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
    fn on_line(&self, fixed: usize, c: &Dy) -> Option<(Dy, Dy)> {
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

#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Excluded,
    Graph { m: usize },
    Unresolved,
}

struct Cell {
    lo: [Dy; 2],
    hi: [Dy; 2],
    kind: Kind,
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
fn check_cells(
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

fn parse_crossings(claims: &[CrossingClaim]) -> Result<Vec<Crossing>, CheckFailure> {
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
fn verify_roots(g: &IPoly, crossings: &mut [Crossing]) -> Result<(), CheckFailure> {
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
fn bisect(g: &IPoly, c: &mut Crossing) -> bool {
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
fn separate_on_lines(g: &IPoly, crossings: &mut [Crossing]) -> Result<(), CheckFailure> {
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

/// The arcs and touch points recomputed from the verified crossings.
struct Derived {
    /// (cell, from, to) with from < to, for arcs inside a box.
    inner: BTreeMap<(usize, usize, usize), usize>,
    /// (from, to) with from < to, for arcs along an edge on which g vanishes.
    edge: BTreeSet<(usize, usize)>,
    /// Crossings where the curve touches an edge without ending: (crossing, isolated).
    touches: Vec<(usize, bool)>,
}

/// An event on an m-edge: a crossing with its interval along o.
struct Event {
    lo: Dy,
    hi: Dy,
    id: usize,
}

/// The crossings on the line (fixed, c) within the closed range [a, b], sorted; an error if
/// one straddles an end of the range.
fn events_on(
    crossings: &[Crossing],
    fixed: usize,
    c: &Dy,
    a: &Dy,
    b: &Dy,
    item: &str,
) -> Result<Vec<Event>, CheckFailure> {
    let mut out = Vec::new();
    for (id, x) in crossings.iter().enumerate() {
        if let Some((lo, hi)) = x.on_line(fixed, c) {
            // A point is in [a, b] if it lies there; an interval's root is in the open
            // interval (lo, hi), so one that only touches [a, b] at an end is outside.
            let outside = if lo == hi {
                hi < *a || lo > *b
            } else {
                hi <= *a || lo >= *b
            };
            if outside {
                continue;
            }
            if lo < *a || hi > *b {
                return fail(
                    item,
                    format!("crossing {id} straddles a corner of the cell"),
                );
            }
            out.push(Event { lo, hi, id });
        }
    }
    out.sort_by(|x, y| (&x.lo, &x.hi).cmp(&(&y.lo, &y.hi)));
    Ok(out)
}

/// p has no root in [a, b] other than at an end marked as a root: strict coefficient signs
/// (an end coefficient may be zero at a root end), subdividing up to a depth.
fn no_root(p: &IPoly, a: &Dy, b: &Dy, root_a: bool, root_b: bool, depth: u32) -> bool {
    let r = p.restrict(0, a, b);
    let c = &r.c;
    let n = c.len() - 1;
    // Every Bernstein basis function is positive inside the interval: if the nonzero
    // coefficients share one strict sign, so does p inside; at an end p is the end
    // coefficient, which may be zero only at an end that is a listed root.
    let nonzero: Vec<i8> = c.iter().map(sign).filter(|&s| s != 0).collect();
    if !nonzero.is_empty()
        && nonzero.iter().all(|&s| s == nonzero[0])
        && (root_a || !c[0].is_zero())
        && (root_b || !c[n].is_zero())
    {
        return true;
    }
    if depth == 0 {
        return false;
    }
    let mid = a.mid(b);
    if p.sign_at(&mid) == 0 {
        return false;
    }
    no_root(p, a, &mid, root_a, false, depth - 1) && no_root(p, &mid, b, false, root_b, depth - 1)
}

/// The unique crossing on the o-edge (o = c, m in [m0, m1]) of a monotone cell.
fn o_edge_crossing(
    crossings: &[Crossing],
    o: usize,
    c: &Dy,
    m0: &Dy,
    m1: &Dy,
    item: &str,
) -> Result<usize, CheckFailure> {
    let found = events_on(crossings, o, c, m0, m1, item)?;
    match found.as_slice() {
        [e] => Ok(e.id),
        [] => fail(
            item,
            "the curve crosses an edge of the cell at no listed crossing",
        ),
        _ => fail(item, "two crossings on an edge along which g is monotone"),
    }
}

fn derive_arcs(
    g: &IPoly,
    cells: &[Cell],
    crossings: &mut [Crossing],
) -> Result<Derived, CheckFailure> {
    let mut d = Derived {
        inner: BTreeMap::new(),
        edge: BTreeSet::new(),
        touches: Vec::new(),
    };
    for (ci, cell) in cells.iter().enumerate() {
        let Kind::Graph { m } = cell.kind else {
            continue;
        };
        let item = format!("cell {ci}");
        let o = 1 - m;
        let (o0, o1) = (&cell.lo[o], &cell.hi[o]);
        let edges = [&cell.lo[m], &cell.hi[m]];
        let polys = edges.map(|c| g.fix(m, c));
        let zero_edge = polys.iter().position(IPoly::is_zero);
        if let Some(z) = zero_edge {
            // g = 0 on this m-edge and strictly monotone along m: the rest of the cell is
            // off the curve. The edge is covered by arcs between consecutive points on it.
            let evs = events_on(crossings, m, edges[z], o0, o1, &item)?;
            if evs.iter().any(|e| e.lo != e.hi)
                || evs.first().map(|e| &e.lo) != Some(o0)
                || evs.last().map(|e| &e.hi) != Some(o1)
            {
                return fail(
                    item,
                    "the zero edge is not covered by exact points from end to end",
                );
            }
            for w in evs.windows(2) {
                d.edge.insert((w[0].id.min(w[1].id), w[0].id.max(w[1].id)));
            }
            continue;
        }
        // The events on both m-edges, their isolating intervals narrowed (exact bisection)
        // until the two edges' events are disjoint along o: roots on opposite edges are
        // distinct (g is strictly monotone along m), so this ends unless a claim is false.
        let mut rounds = 0;
        let events = loop {
            let mut events: Vec<(Event, usize)> = Vec::new();
            for (side, c) in edges.iter().enumerate() {
                let evs = events_on(crossings, m, c, o0, o1, &item)?;
                events.extend(evs.into_iter().map(|e| (e, side)));
            }
            events.sort_by(|x, y| (&x.0.lo, &x.0.hi).cmp(&(&y.0.lo, &y.0.hi)));
            // An isolating interval reaching a cell end leaves no gap there to sample: narrow
            // it too (its root is inside, so it comes off the end).
            let at_end = events
                .iter()
                .find(|(e, _)| e.lo < e.hi && (e.lo == *o0 || e.hi == *o1))
                .map(|(e, _)| e.id);
            let overlap = events
                .windows(2)
                .find(|w| w[1].0.lo <= w[0].0.hi)
                .map(|w| (w[0].0.id, w[1].0.id));
            let moved = match (at_end, overlap) {
                (Some(x), _) => bisect(g, &mut crossings[x]),
                (None, Some((x, y))) => bisect(g, &mut crossings[x]) | bisect(g, &mut crossings[y]),
                (None, None) => break events,
            };
            rounds += 1;
            if !moved || rounds > 400 {
                return fail(
                    item,
                    "crossings on opposite edges are not separated along the cell",
                );
            }
        };
        // g has no other root on the m-edges.
        for (side, poly) in polys.iter().enumerate() {
            let mut a = o0.clone();
            let mut root_a = false;
            for (e, _) in events.iter().filter(|e| e.1 == side) {
                let root_b = e.lo == e.hi;
                if a < e.lo && !no_root(poly, &a, &e.lo, root_a, root_b, 40) {
                    return fail(
                        &item,
                        "g has a root on an edge of the cell that is not listed",
                    );
                }
                a = e.hi.clone();
                root_a = root_b;
            }
            if a < *o1 && !no_root(poly, &a, o1, root_a, false, 40) {
                return fail(
                    &item,
                    "g has a root on an edge of the cell that is not listed",
                );
            }
        }
        // Whether the curve is in the cell over each gap between events: the signs of g on the
        // two m-edges differ there (one root along m, by monotonicity).
        let mut gap_in: Vec<Option<bool>> = Vec::with_capacity(events.len() + 1);
        for k in 0..=events.len() {
            let a = if k == 0 { o0 } else { &events[k - 1].0.hi };
            let b = events.get(k).map_or(o1, |e| &e.0.lo);
            if a >= b {
                gap_in.push(None);
                continue;
            }
            let s = a.mid(b);
            let (sa, sb) = (polys[0].sign_at(&s), polys[1].sign_at(&s));
            if sa == 0 || sb == 0 {
                return fail(item, "g vanishes between the listed crossings");
            }
            gap_in.push(Some(sa != sb));
        }
        let mut start: Option<usize> = None;
        if gap_in[0] == Some(true) {
            start = Some(o_edge_crossing(
                crossings, o, o0, edges[0], edges[1], &item,
            )?);
        }
        let add = |from: usize, to: usize, d: &mut Derived| {
            *d.inner.entry((ci, from.min(to), from.max(to))).or_default() += 1;
        };
        for (k, (e, _)) in events.iter().enumerate() {
            let before = gap_in[k] == Some(true);
            let after = gap_in[k + 1] == Some(true);
            match (start, after) {
                (None, true) => start = Some(e.id),
                (Some(s), false) => {
                    add(s, e.id, &mut d);
                    start = None;
                }
                (s, _) => d.touches.push((e.id, s.is_none() && !before && !after)),
            }
        }
        if let Some(s) = start {
            if gap_in.last() != Some(&Some(true)) {
                return fail(item, "a piece of the curve has no end in the cell");
            }
            let end = o_edge_crossing(crossings, o, o1, edges[0], edges[1], &item)?;
            add(s, end, &mut d);
        }
    }
    Ok(d)
}

fn compare_arcs(
    cert: &CurveCertificate,
    cells: &[Cell],
    derived: &Derived,
) -> Result<(), CheckFailure> {
    let mut inner: BTreeMap<(usize, usize, usize), usize> = BTreeMap::new();
    let mut edge: BTreeSet<(usize, usize)> = BTreeSet::new();
    for (i, a) in cert.arcs.iter().enumerate() {
        let item = format!("arc {i}");
        if a.from >= cert.crossings.len() || a.to >= cert.crossings.len() {
            return fail(item, "refers to a crossing that does not exist");
        }
        let key = (a.from.min(a.to), a.from.max(a.to));
        if a.along_edge {
            if !edge.insert(key) {
                return fail(item, "listed twice");
            }
        } else {
            if a.cell >= cells.len() || !matches!(cells[a.cell].kind, Kind::Graph { .. }) {
                return fail(item, "its cell is not a monotone cell");
            }
            *inner.entry((a.cell, key.0, key.1)).or_default() += 1;
        }
    }
    if let Some((k, _)) = derived.inner.iter().find(|(k, n)| inner.get(k) != Some(n)) {
        return fail(
            format!("arcs of cell {}", k.0),
            format!(
                "the curve joins crossings {} and {} there, which the certificate does not say",
                k.1, k.2
            ),
        );
    }
    if let Some((k, _)) = inner.iter().find(|(k, _)| !derived.inner.contains_key(k)) {
        return fail(
            format!("arcs of cell {}", k.0),
            format!("no arc joins crossings {} and {} there", k.1, k.2),
        );
    }
    if edge != derived.edge {
        return fail(
            "arcs along zero edges",
            "do not match the edges where g vanishes",
        );
    }
    Ok(())
}

/// The branches partition the arcs into maximal chains, plus the one-point components.
fn check_branches(
    cert: &CurveCertificate,
    crossings: &[Crossing],
    derived: &Derived,
) -> Result<(), CheckFailure> {
    let end = |x: &Dy| x.is_end();
    let boundary = |c: usize| match &crossings[c] {
        Crossing::Point(p) => end(&p[0]) || end(&p[1]),
        Crossing::OnLine { at, .. } => end(at),
    };
    let mut unused: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    let mut degree: BTreeMap<usize, usize> = BTreeMap::new();
    for a in &cert.arcs {
        *unused
            .entry((a.from.min(a.to), a.from.max(a.to)))
            .or_default() += 1;
        *degree.entry(a.from).or_default() += 1;
        *degree.entry(a.to).or_default() += 1;
    }
    let on_arcs: BTreeSet<usize> = degree.keys().copied().collect();
    let passed: BTreeSet<usize> = derived
        .touches
        .iter()
        .filter(|t| !t.1)
        .map(|t| t.0)
        .collect();
    for (i, b) in cert.branches.iter().enumerate() {
        let item = format!("branch {i}");
        if b.crossings.iter().any(|&c| c >= cert.crossings.len()) {
            return fail(item, "refers to a crossing that does not exist");
        }
        if b.crossings.len() == 1 && !b.closed {
            let c = b.crossings[0];
            let isolated = derived.touches.iter().any(|t| t.0 == c && t.1);
            if !isolated || !boundary(c) || on_arcs.contains(&c) || passed.contains(&c) {
                return fail(
                    item,
                    "not an isolated point of the curve on the square's boundary",
                );
            }
            continue;
        }
        let n = b.crossings.len();
        let steps = if b.closed { n } else { n.saturating_sub(1) };
        if steps == 0 {
            return fail(item, "empty");
        }
        for k in 0..steps {
            let (x, y) = (b.crossings[k], b.crossings[(k + 1) % n]);
            match unused.get_mut(&(x.min(y), x.max(y))) {
                Some(c) if *c > 0 => *c -= 1,
                _ => return fail(item, format!("no arc joins crossings {x} and {y}")),
            }
        }
        // Maximal: a closed branch passes only through degree-2 crossings; an open one
        // continues through every degree-2 crossing, so its ends have another degree.
        let deg = |c: usize| degree.get(&c).copied().unwrap_or(0);
        let inner_ok = b.crossings[usize::from(!b.closed)..n - usize::from(!b.closed)]
            .iter()
            .all(|&c| deg(c) == 2);
        let ends_ok = b.closed || (deg(b.crossings[0]) != 2 && deg(b.crossings[n - 1]) != 2);
        if !inner_ok || !ends_ok {
            return fail(item, "not a maximal chain of arcs");
        }
    }
    if unused.values().any(|&c| c > 0) {
        return fail("branches", "an arc belongs to no branch");
    }
    // Every isolated boundary touch point is a one-point branch.
    for &(c, isolated) in &derived.touches {
        if isolated
            && boundary(c)
            && !on_arcs.contains(&c)
            && !passed.contains(&c)
            && !cert.branches.iter().any(|b| b.crossings == [c])
        {
            return fail(
                format!("crossing {c}"),
                "an isolated point of the curve is in no branch",
            );
        }
    }
    Ok(())
}
