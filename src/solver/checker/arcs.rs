//! The arcs of every monotone box derived from the verified crossings, compared with the
//! certificate's, and its branches checked (`proofs/certificate-check.md`).

use super::arith::{sign, Dy, IPoly};
use super::crossings::{bisect, Crossing};
use super::{fail, Cell, CheckFailure, Kind};
use crate::solver::certificate::CurveCertificate;
use num_traits::Zero;
use std::collections::{BTreeMap, BTreeSet};

/// The arcs and touch points recomputed from the verified crossings.
pub(super) struct Derived {
    /// (cell, from, to) with from < to, for arcs inside a box.
    pub(super) inner: BTreeMap<(usize, usize, usize), usize>,
    /// (from, to) with from < to, for arcs along an edge on which g vanishes.
    pub(super) edge: BTreeSet<(usize, usize)>,
    /// Crossings where the curve touches an edge without ending: (crossing, isolated).
    pub(super) touches: Vec<(usize, bool)>,
}

/// An event on an m-edge: a crossing with its interval along o.
pub(super) struct Event {
    pub(super) lo: Dy,
    pub(super) hi: Dy,
    pub(super) id: usize,
}

/// The crossings on the line (fixed, c) within the closed range [a, b], sorted; an error if
/// one straddles an end of the range.
pub(super) fn events_on(
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
pub(super) fn no_root(p: &IPoly, a: &Dy, b: &Dy, root_a: bool, root_b: bool, depth: u32) -> bool {
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
pub(super) fn o_edge_crossing(
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

pub(super) fn derive_arcs(
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

pub(super) fn compare_arcs(
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
pub(super) fn check_branches(
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
