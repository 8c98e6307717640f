//! The arcs of a box proven monotone: the curve in it is a union of graphs over one
//! variable, determined by the crossings on the box's edges (`proofs/curve-topology.md`).

use crate::number::Sign;
use crate::reason::Reason;
use crate::solver::dyadic::{Dyadic, DyadicBox};
use crate::solver::plane_curve::segments::{uv, Lines, SegmentRoots};
use crate::solver::plane_curve::topology::Arc;
use crate::solver::plane_curve::ArcKind;
use crate::solver::plane_curve::CrossingId;
use crate::solver::precision::Policy;
use crate::solver::univariate::{refine_root, Root};

/// One thing that happens along the o-axis of a graph box: a root of g on one of the two
/// m-edges, or a segment of an m-edge on which g vanishes.
#[derive(Clone, Debug)]
pub(crate) struct Event {
    pub(crate) lo: Dyadic,
    pub(crate) hi: Dyadic,
    /// 0: on the low m-edge, 1: on the high m-edge.
    pub(crate) side: usize,
    pub(crate) id: CrossingId,
    /// g ≡ 0 on [lo, hi] of this edge (an arc along the edge).
    pub(crate) zero: bool,
}
/// The events on one m-edge (the line where m = c) over the box's o-range.
pub(crate) fn edge_events(
    lines: &mut Lines,
    m: usize,
    c: Dyadic,
    side: usize,
    o_lo: Dyadic,
    o_hi: Dyadic,
) -> Result<Vec<Event>, Reason> {
    let cuts = lines.cuts(m, c, o_lo, o_hi);
    let mut events = Vec::new();
    for (i, &s) in cuts.iter().enumerate() {
        let (u, v) = uv(m, c, s);
        match lines.sign_at(u, v) {
            Sign::Zero => events.push(Event {
                lo: s,
                hi: s,
                side,
                id: CrossingId::Exact { u, v },
                zero: false,
            }),
            Sign::Unknown => return Err(Reason::CornerSign),
            _ => {}
        }
        if let Some(&s1) = cuts.get(i + 1) {
            match lines.segment(m, c, s, s1) {
                SegmentRoots::Zero => events.push(Event {
                    lo: s,
                    hi: s1,
                    side,
                    id: CrossingId::Exact { u, v },
                    zero: true,
                }),
                SegmentRoots::Unresolved => return Err(Reason::TangentToBoxEdge),
                SegmentRoots::Roots(roots) => {
                    for (k, r) in roots.iter().enumerate() {
                        let id = match *r {
                            Root::At { t } => {
                                let (u, v) = uv(m, c, t);
                                CrossingId::Exact { u, v }
                            }
                            Root::Between { .. } => CrossingId::Segment {
                                fixed: m,
                                c,
                                s0: s,
                                s1,
                                k,
                            },
                        };
                        events.push(Event {
                            lo: r.lo(),
                            hi: r.hi(),
                            side,
                            id,
                            zero: false,
                        });
                    }
                }
            }
        }
    }
    // A zero segment's end points are recorded as zero breakpoints too: drop those duplicates.
    let zero_ranges: Vec<(Dyadic, Dyadic)> = events
        .iter()
        .filter(|e| e.zero)
        .map(|e| (e.lo, e.hi))
        .collect();
    events.retain(|e| {
        e.zero
            || !zero_ranges
                .iter()
                .any(|&(a, b)| e.lo == e.hi && (e.lo == a || e.lo == b))
    });
    Ok(events)
}
/// The single crossing on an o-edge (the line o = c, m over [m_lo, m_hi]) of a box where g is
/// strictly monotone along m, given that the curve meets it (the signs at its ends differ or
/// one is zero).
pub(crate) fn o_edge_crossing(
    lines: &mut Lines,
    m: usize,
    o_c: Dyadic,
    m_lo: Dyadic,
    m_hi: Dyadic,
) -> Result<CrossingId, Reason> {
    let o = 1 - m;
    let cuts = lines.cuts(o, o_c, m_lo, m_hi);
    let mut prev: Option<(Dyadic, Sign)> = None;
    for &s in &cuts {
        let (u, v) = uv(o, o_c, s);
        let sg = lines.sign_at(u, v);
        match sg {
            Sign::Zero => return Ok(CrossingId::Exact { u, v }),
            Sign::Unknown => return Err(Reason::CornerSign),
            _ => {}
        }
        if let Some((s_prev, sp)) = prev {
            if sp != sg {
                return Ok(CrossingId::Segment {
                    fixed: o,
                    c: o_c,
                    s0: s_prev,
                    s1: s,
                    k: 0,
                });
            }
        }
        prev = Some((s, sg));
    }
    Err(Reason::Internal(
        "no sign change on a box edge the curve crosses",
    ))
}
/// The arcs in a box where g is strictly monotone along `m` (a graph over the other variable).
/// Touch points met in a monotone box: (crossing, isolated in this box).
pub(crate) type Touches = Vec<(CrossingId, bool)>;
pub(crate) fn graph_box_arcs(
    lines: &mut Lines,
    cell: DyadicBox,
    m: usize,
    touches: &mut Touches,
) -> Result<Vec<Arc>, Reason> {
    let o = 1 - m;
    let (o_lo, o_hi) = (cell.lo[o], cell.hi[o]);
    let kind = ArcKind::graph(m);
    let mut events = edge_events(lines, m, cell.lo[m], 0, o_lo, o_hi)?;
    events.extend(edge_events(lines, m, cell.hi[m], 1, o_lo, o_hi)?);
    // Separate the events: they may touch only where both are open root intervals (whose
    // ends are roots of neither function); otherwise the gap between them must be nonempty.
    let is_open = |e: &Event| !e.zero && e.lo < e.hi;
    // Two zero segments may also touch (consecutive atomic segments on which g vanishes).
    let conflict = |x: &Event, y: &Event| {
        x.hi > y.lo || (x.hi == y.lo && !(is_open(x) && is_open(y)) && !(x.zero && y.zero))
    };
    for _ in 0..64 {
        events.sort_by_key(|e| (e.lo, e.hi));
        let Some(i) = (1..events.len()).find(|&i| conflict(&events[i - 1], &events[i])) else {
            break;
        };
        let mut refined = false;
        for j in [i - 1, i] {
            let e = &events[j];
            if let (CrossingId::Segment { fixed, c, .. }, true) = (e.id, is_open(e)) {
                let p = lines.poly(fixed, c).clone();
                let w = 0.5 * (e.hi.to_f64() - e.lo.to_f64());
                let mut policy = Policy::new(&lines.opts.ladder, &mut lines.stats);
                let r = refine_root(&p, Root::Between { lo: e.lo, hi: e.hi }, w, &mut policy);
                if (r.lo(), r.hi()) != (e.lo, e.hi) {
                    // Narrow the interval only: the crossing keeps its canonical (atomic
                    // segment) name, which the neighbouring box uses too.
                    events[j].lo = r.lo();
                    events[j].hi = r.hi();
                    refined = true;
                }
            }
        }
        if !refined {
            return Err(Reason::OppositeEdgeRoots);
        }
    }
    events.sort_by_key(|e| (e.lo, e.hi));
    if (1..events.len()).any(|i| conflict(&events[i - 1], &events[i])) {
        return Err(Reason::OppositeEdgeRoots);
    }
    // Whether the curve is in the box, in each gap between events (and before the first and
    // after the last): the signs of g on the two m-edges differ there. A gap that is a single
    // point is sampled at that point unless it is a root.
    let mut gap_in = Vec::with_capacity(events.len() + 1);
    for k in 0..=events.len() {
        let (left, right) = (k.checked_sub(1).map(|i| &events[i]), events.get(k));
        let a = left.map_or(o_lo, |e| e.hi);
        let b = right.map_or(o_hi, |e| e.lo);
        let s = if a < b {
            a.midpoint(b).ok_or(Reason::RootSeparationDepth)?
        } else {
            let at_root = left.is_some_and(|e| !is_open(e)) || right.is_some_and(|e| !is_open(e));
            if at_root {
                gap_in.push(None);
                continue;
            }
            a
        };
        let (u0, v0) = uv(m, cell.lo[m], s);
        let (u1, v1) = uv(m, cell.hi[m], s);
        let (sa, sb) = (lines.sign_at(u0, v0), lines.sign_at(u1, v1));
        if !sa.is_nonzero() || !sb.is_nonzero() {
            return Err(Reason::SignBetweenRoots);
        }
        gap_in.push(Some(sa != sb));
    }
    // Walk: components are runs of "in" gaps joined through pass-through events.
    let mut arcs = Vec::new();
    let mut start: Option<CrossingId> = None;
    if gap_in[0] == Some(true) {
        start = Some(o_edge_crossing(lines, m, o_lo, cell.lo[m], cell.hi[m])?);
    }
    for (k, e) in events.iter().enumerate() {
        let before = gap_in[k];
        let after = gap_in[k + 1];
        if e.zero {
            // The curve runs along this m-edge from e.lo to e.hi: an arc on the edge (split at
            // breakpoints so both neighbours produce the same pieces).
            let mc = if e.side == 0 { cell.lo[m] } else { cell.hi[m] };
            let (u0, v0) = uv(m, mc, e.lo);
            let (u1, v1) = uv(m, mc, e.hi);
            let (a, b) = (
                CrossingId::Exact { u: u0, v: v0 },
                CrossingId::Exact { u: u1, v: v1 },
            );
            if let Some(s) = start.take() {
                if s != a {
                    arcs.push(Arc {
                        from: s,
                        to: a,
                        cell,
                        kind,
                    });
                }
            }
            arcs.push(Arc {
                from: a,
                to: b,
                cell,
                kind: ArcKind::OnEdge,
            });
            if after == Some(true) {
                start = Some(b);
            }
            continue;
        }
        match (start, before == Some(true), after == Some(true)) {
            // Entering: a component starts at this event.
            (None, _, true) => start = Some(e.id),
            // Leaving: it ends here.
            (Some(s), _, false) => {
                arcs.push(Arc {
                    from: s,
                    to: e.id,
                    cell,
                    kind,
                });
                start = None;
            }
            // Passing through (a touch of the edge from inside), or a point where the curve
            // touches the edge from outside: no arc here, but remember it (on the boundary of
            // the square there is no neighbour to carry it).
            (s, _, _) => touches.push((
                e.id,
                s.is_none() && before != Some(true) && after != Some(true),
            )),
        }
    }
    if let Some(s) = start {
        if gap_in.last() == Some(&Some(true)) {
            let end = o_edge_crossing(lines, m, o_hi, cell.lo[m], cell.hi[m])?;
            arcs.push(Arc {
                from: s,
                to: end,
                cell,
                kind,
            });
        } else {
            return Err(Reason::Internal(
                "a component of the curve has no end in its box",
            ));
        }
    }
    Ok(arcs)
}
