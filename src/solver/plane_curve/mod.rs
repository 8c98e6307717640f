//! Certified topology of a plane algebraic curve `g(u, v) = 0` on the unit square.
//!
//! Subdivision with exclusion (all Bernstein coefficients of one strict sign) and a
//! monotonicity criterion: where `∂g/∂m` has a strict sign on a box, every line across the
//! box in direction m meets the curve at most once, so the curve in the box is a union of
//! graphs over the other variable, each determined by the roots of g on the box edges
//! (`proofs/curve-topology.md`). Roots on edges are isolated once per *atomic segment* (the
//! pieces into which the corners of all leaf boxes cut a grid line), so neighbouring boxes of
//! any sizes name the same crossing identically. What cannot be decided within the budget
//! (near a singular point, where both partial derivatives vanish on the curve) is reported
//! with its box, never guessed.

pub(crate) mod box_signs;
pub mod critical_points;
mod graph_boxes;
mod segments;
pub mod topology;
pub mod zero_lines;

pub(crate) use topology::chain;
pub use topology::{Arc, ArcKind, Branch, Cell, CellKind, CurveTopology, Unresolved};

use crate::bernstein::Bernstein;
use crate::number::{Interval, Precision, Rational};
use crate::reason::Reason;
use crate::solver::dyadic::{Dyadic, DyadicBox};
use crate::solver::plane_curve::box_signs::{strict_sign, ESCALATION_DEPTH};
use crate::solver::plane_curve::critical_points::critical_points;
use crate::solver::plane_curve::graph_boxes::{graph_box_arcs, Touches};
use crate::solver::plane_curve::segments::{integer_multiple, locate, on_square_boundary, Lines};
use crate::solver::precision::{Escalations, Ladder, Policy};
use std::collections::{BTreeMap, BTreeSet};

/// Budgets and precision policy of the curve solver.
#[derive(Clone, Debug, serde::Serialize)]
pub struct CurveOptions {
    /// The precision ladder for undecided signs.
    pub ladder: Ladder,
    /// The deepest subdivision of a box (the box side is 2^-depth).
    pub max_depth: u32,
    /// The most boxes examined.
    pub max_boxes: usize,
    /// Crossing intervals are refined to at most this width in parameter space.
    pub refine_width: f64,
    /// A wall-clock time after which no box is subdivided any more: what is not decided by
    /// then is reported unresolved ("the time limit was reached"). The output then depends
    /// on the machine's speed; without a deadline (the default) it does not.
    #[serde(skip)]
    pub deadline: Option<std::time::Instant>,
}

impl Default for CurveOptions {
    fn default() -> Self {
        CurveOptions {
            ladder: Ladder::default(),
            max_depth: 24,
            max_boxes: 50_000,
            refine_width: 1e-9,
            deadline: None,
        }
    }
}

impl CurveOptions {
    /// Whether the deadline, if any, has passed.
    pub fn past_deadline(&self) -> bool {
        crate::solver::precision::past(self.deadline)
    }
}

/// Where the curve meets a box edge; equal for every box that shares the point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum CrossingId {
    /// Exactly at a dyadic point `(u, v)`.
    Exact {
        /// u.
        u: Dyadic,
        /// v.
        v: Dyadic,
    },
    /// The k-th root of g, counted from the low end, inside the open atomic segment
    /// `s ∈ (s0, s1)` of the grid line where variable `fixed` equals `c`.
    Segment {
        /// The variable held fixed on the line (0: u = c, 1: v = c).
        fixed: usize,
        /// Its value.
        c: Dyadic,
        /// Segment start along the other variable.
        s0: Dyadic,
        /// Segment end.
        s1: Dyadic,
        /// Root index within the segment.
        k: usize,
    },
}

/// Solves `g = 0` on the unit square: certified topology (`proofs/curve-topology.md`).
///
/// # Panics
/// If `g` is not bivariate.
pub fn solve_curve(g: &Bernstein<Rational>, opts: &CurveOptions) -> CurveTopology {
    solve_curve_cut(g, &[], opts)
}

/// [`solve_curve`] with grid lines that must appear in the subdivision: every box that a cut
/// `(axis, c)` crosses is split, whatever its signs, so that the line where variable `axis`
/// equals `c` is made of box edges (its crossings are then named on it). Used for the lines
/// on which a polynomial vanished before its factor was divided out ([`crate::solver::plane_curve::zero_lines`]).
///
/// # Panics
/// If `g` is not bivariate.
pub fn solve_curve_cut(
    g: &Bernstein<Rational>,
    cuts: &[(usize, Dyadic)],
    opts: &CurveOptions,
) -> CurveTopology {
    assert_eq!(g.nvars(), 2, "bivariate");
    let mut out = CurveTopology::default();
    if g.is_zero() {
        out.identically_zero = true;
        return out;
    }
    let gu = g.deriv(0);
    let gv = g.deriv(1);
    let mut stats = Escalations::default();

    // Phase 1: subdivide until every box is excluded, monotone, or out of budget.
    let mut cells: Vec<Cell> = Vec::new();
    let mut out_of_time: BTreeSet<DyadicBox> = BTreeSet::new();
    let mut stack: Vec<(DyadicBox, u32, Bernstein<Interval>)> =
        vec![(DyadicBox::UNIT, 0, g.convert(Precision::F64))];
    while let Some((cell, depth, coeffs)) = stack.pop() {
        out.boxes += 1;
        // Undecided f64 signs usually come from exact zeros or near-zeros of coefficients on
        // large boxes, which subdivision resolves more cheaply than higher precision:
        // escalate only on small boxes, and at the depth budget.
        let ladder = (depth >= ESCALATION_DEPTH || depth >= opts.max_depth).then_some(&opts.ladder);
        let cut = cuts
            .iter()
            .any(|&(axis, c)| cell.lo[axis] < c && c < cell.hi[axis]);
        // A cell the cut crosses is still excluded by sign (no crossing of the curve with
        // the cut line can lie in it); otherwise it is split until the line is on its edges.
        let (sign, level) = strict_sign(&coeffs, g, cell, ladder, &mut stats);
        if sign.is_known() {
            cells.push(Cell {
                cell,
                kind: CellKind::Excluded { sign },
                level,
            });
            continue;
        }
        let mono = [(0, &gu), (1, &gv)]
            .into_iter()
            .filter(|_| !cut)
            .find_map(|(axis, exact)| {
                let (sign, level) =
                    strict_sign(&coeffs.deriv(axis), exact, cell, ladder, &mut stats);
                sign.is_known().then_some((axis, sign, level))
            });
        if let Some((m, sign, level)) = mono {
            cells.push(Cell {
                cell,
                kind: CellKind::Graph { m, sign },
                level,
            });
            continue;
        }
        let timed_out = opts.past_deadline();
        let children =
            (depth < opts.max_depth && out.boxes + stack.len() < opts.max_boxes && !timed_out)
                .then(|| cell.split(0))
                .flatten()
                .and_then(|(a, b)| Some((a.split(1)?, b.split(1)?)));
        let Some(((aa, ab), (ba, bb))) = children else {
            if timed_out {
                out_of_time.insert(cell);
            }
            cells.push(Cell {
                cell,
                kind: CellKind::Unresolved,
                level: None,
            });
            continue;
        };
        let (left, right) = coeffs.subdivide_half(0);
        let (ll, lr) = left.subdivide_half(1);
        let (rl, rr) = right.subdivide_half(1);
        // Pushed in reverse so that boxes are examined in a fixed order (deterministic output).
        stack.push((bb, depth + 1, rr));
        stack.push((ba, depth + 1, rl));
        stack.push((ab, depth + 1, lr));
        stack.push((aa, depth + 1, ll));
    }

    // Phase 2: atomic segments. Every leaf's corners cut the grid lines its edges lie on.
    let mut lines = Lines {
        g_int: integer_multiple(g),
        g_fast: g.convert(Precision::F64),
        g,
        opts,
        breakpoints: BTreeMap::new(),
        polys: BTreeMap::new(),
        point_signs: BTreeMap::new(),
        segments: BTreeMap::new(),
        stats: Escalations::default(),
    };
    for Cell { cell, .. } in &cells {
        for fixed in 0..2 {
            let o = 1 - fixed;
            for c in [cell.lo[fixed], cell.hi[fixed]] {
                let set = lines.breakpoints.entry((fixed, c)).or_default();
                set.insert(cell.lo[o]);
                set.insert(cell.hi[o]);
            }
        }
    }

    // Phase 3: the arcs of each monotone box.
    let mut arcs: Vec<Arc> = Vec::new();
    let mut touches: Touches = Vec::new();
    for Cell { cell, kind, .. } in &cells {
        match *kind {
            CellKind::Excluded { .. } => {}
            CellKind::Unresolved => out.unresolved.push(Unresolved {
                cell: *cell,
                reason: if out_of_time.contains(cell) {
                    Reason::TimeLimit
                } else {
                    Reason::NoMonotoneDirection
                },
            }),
            // Past the time limit, monotone boxes are not worked out any more.
            CellKind::Graph { .. } if opts.past_deadline() => out.unresolved.push(Unresolved {
                cell: *cell,
                reason: Reason::TimeLimit,
            }),
            CellKind::Graph { m, .. } => match graph_box_arcs(&mut lines, *cell, m, &mut touches) {
                Ok(mut a) => arcs.append(&mut a),
                Err(reason) => out.unresolved.push(Unresolved {
                    cell: *cell,
                    reason,
                }),
            },
        }
    }
    // Where the subdivision could not decide, isolate the critical points of g (the
    // candidates for singular points of the curve) and say what they are.
    if !out.unresolved.is_empty() && !opts.past_deadline() {
        let boxes: Vec<DyadicBox> = out.unresolved.iter().map(|u| u.cell).collect();
        out.critical = critical_points(g, &boxes, &mut Policy::new(&opts.ladder, &mut stats));
        for u in &mut out.unresolved {
            if let Some(cp) = out.critical.iter().find(|cp| cp.in_box(&u.cell)) {
                u.reason = cp.reason(&u.cell);
            }
        }
    }
    // Arcs along an edge are found from both sides: keep one.
    let mut seen = BTreeSet::new();
    arcs.retain(|a| a.kind != ArcKind::OnEdge || seen.insert((a.from.min(a.to), a.from.max(a.to))));

    // One-point components: a point where the curve touches the boundary of the square from
    // outside, on no arc and passed through by none.
    let on_arcs: BTreeSet<CrossingId> = arcs.iter().flat_map(|a| [a.from, a.to]).collect();
    let passed: BTreeSet<CrossingId> = touches.iter().filter(|t| !t.1).map(|t| t.0).collect();
    let mut points: Vec<CrossingId> = touches
        .iter()
        .filter(|(id, isolated)| {
            *isolated && on_square_boundary(id) && !on_arcs.contains(id) && !passed.contains(id)
        })
        .map(|t| t.0)
        .collect();
    points.sort();
    points.dedup();

    // Phase 4: locations of crossings, refined.
    let mut touch_ids: Vec<CrossingId> = touches.iter().map(|t| t.0).collect();
    touch_ids.sort();
    touch_ids.dedup();
    for id in arcs
        .iter()
        .flat_map(|a| [a.from, a.to])
        .chain(points.iter().copied())
        .chain(touch_ids.iter().copied())
    {
        {
            if let std::collections::btree_map::Entry::Vacant(slot) = out.locations.entry(id) {
                let (location, interval) = locate(&mut lines, id);
                slot.insert(location);
                if let Some(i) = interval {
                    out.intervals.insert(id, i);
                }
            }
        }
    }
    stats.merge(&lines.stats);
    out.escalations = stats;

    // Phase 5: chain arcs into branches.
    out.branches = chain(&arcs);
    out.branches.extend(points.into_iter().map(|id| Branch {
        crossings: vec![id],
        closed: false,
        complete: true,
    }));
    out.arcs = arcs;
    out.cells = cells;
    out.touches = touch_ids;
    out.passing = passed.into_iter().collect();
    out
}
