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

pub mod critical_points;
pub mod zero_lines;

use crate::bernstein::Bernstein;
use crate::number::{Certified, Interval, Number, Precision, Rational, Sign};
use crate::solver::dyadic::{Dyadic, DyadicBox};
use crate::solver::plane_curve::critical_points::{critical_points, CriticalPoint};
use crate::solver::precision::{Escalations, Ladder, Level, Question};
use crate::solver::univariate::{isolate_roots_in, refine_root, PointSign, Root};
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
        self.deadline
            .is_some_and(|d| std::time::Instant::now() >= d)
    }
}

/// The reason given for boxes left undecided because the time limit was reached.
pub const TIME_LIMIT_REASON: &str =
    "the time limit was reached before this box was decided (--time-limit)";

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

/// A piece of the curve inside one box, between two crossings.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Arc {
    /// One end.
    pub from: CrossingId,
    /// The other end.
    pub to: CrossingId,
    /// The box that contains it.
    #[serde(rename = "box")]
    pub cell: DyadicBox,
    /// Why it is a single arc: "graph over v" (g monotone in u), "graph over u", or
    /// "on edge" (g vanishes identically on this box edge segment).
    pub reason: &'static str,
}

/// A region whose topology was not decided.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Unresolved {
    /// The box.
    #[serde(rename = "box")]
    pub cell: DyadicBox,
    /// Why.
    pub reason: String,
}

/// A connected component of the curve in the square: an ordered chain of crossings.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Branch {
    /// The crossings in order.
    pub crossings: Vec<CrossingId>,
    /// A closed loop (the last crossing joins the first).
    pub closed: bool,
    /// Both ends (if open) lie on the boundary of the square, not at an unresolved region.
    pub complete: bool,
}

/// How a leaf box of the subdivision was settled.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum CellKind {
    /// Every Bernstein coefficient of g on the box has this strict sign: no curve.
    Excluded {
        /// The sign of g.
        sign: Sign,
    },
    /// Every coefficient of ∂g/∂m on the box has this strict sign: the curve is a union of
    /// graphs over the other variable.
    Graph {
        /// The variable g is monotone in (0: u, 1: v).
        m: usize,
        /// The sign of ∂g/∂m.
        sign: Sign,
    },
    /// Not decided.
    Unresolved,
}

/// A leaf box of the subdivision, with what was proven on it and at which precision.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Cell {
    /// The box.
    #[serde(rename = "box")]
    pub cell: DyadicBox,
    /// What holds on it.
    #[serde(flatten)]
    pub kind: CellKind,
    /// The precision level that settled the deciding sign (`None` if unresolved).
    pub level: Option<Level>,
}

/// The certified topology of `g = 0` on `[0,1]^2`.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct CurveTopology {
    /// g is the zero polynomial: every point is on the curve.
    pub identically_zero: bool,
    /// The components.
    pub branches: Vec<Branch>,
    /// The arcs (one per box and component piece).
    pub arcs: Vec<Arc>,
    /// Where each crossing is: a box `[lo, hi]` in (u, v) containing it (a point if exact).
    pub locations: BTreeMap<CrossingId, [[f64; 2]; 2]>,
    /// For each crossing inside a segment, the exact interval `[lo, hi]` of the free variable
    /// that contains it and no other root of g on its line (a point if the root is dyadic).
    pub intervals: BTreeMap<CrossingId, (Dyadic, Dyadic)>,
    /// The leaf boxes, which tile the square, with how each was settled.
    pub cells: Vec<Cell>,
    /// Crossings where the curve touches a box edge without ending there (located too).
    pub touches: Vec<CrossingId>,
    /// Those of them that an arc passes through (the curve touches the edge from inside a
    /// box): a point of the curve that is not a node of the arc graph.
    pub passing: Vec<CrossingId>,
    /// Undecided regions.
    pub unresolved: Vec<Unresolved>,
    /// The critical points of g isolated inside the undecided regions, with what is known of
    /// g there ([`critical_points`](crate::solver::plane_curve::critical_points::critical_points)).
    pub critical: Vec<CriticalPoint>,
    /// Boxes examined.
    pub boxes: usize,
    /// Sign questions by the level that settled them.
    pub escalations: Escalations,
}

impl CurveTopology {
    /// Whether the whole square was decided.
    pub fn is_certified(&self) -> bool {
        self.unresolved.is_empty()
    }

    /// A representative (u, v) of a crossing (the centre of its location box).
    pub fn point(&self, id: &CrossingId) -> [f64; 2] {
        let [lo, hi] = self.locations[id];
        [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])]
    }
}

/// The signs of the Bernstein coefficients of `p` restricted to a box, when all are known.
struct BoxSigns<'a> {
    p: &'a Bernstein<Rational>,
    cell: DyadicBox,
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

/// Why a cell is unresolved.
const UNRESOLVED_CELL: &str = "no direction in which g is monotone within the depth budget: a singular point of the curve, or a critical point of g very close to it";

/// The depth from which undecided box signs are escalated beyond f64.
const ESCALATION_DEPTH: u32 = 10;

/// The strict sign of `p` on the box if its coefficients prove one, else `Unknown`, with the
/// level that proved it. `fast` are the f64-interval coefficients carried down the subdivision.
fn strict_sign(
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

/// The polynomial g restricted to the grid line where variable `fixed` is `c`, as a
/// univariate polynomial in the other variable on [0, 1], up to a positive constant factor
/// (exact). `g_int` is g times the lcm of its denominators (integer coefficients); with
/// `c = p / q`, each fibre is evaluated by de Casteljau steps `x_i ← (q − p) x_i + p x_{i+1}`
/// in integers, which multiplies every fibre's value by the same `q^d`: roots and signs are
/// those of the exact restriction, without a gcd per step.
fn line_polynomial(g_int: &Bernstein<Rational>, fixed: usize, c: Dyadic) -> Bernstein<Rational> {
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
fn integer_multiple(g: &Bernstein<Rational>) -> Bernstein<Rational> {
    let mut l = rug::Integer::from(1);
    for c in g.coeffs() {
        l.lcm_mut(c.denom());
    }
    g.scale(&Rational::from(l))
}

/// What g does on one atomic segment of a grid line.
#[derive(Clone, Debug)]
enum SegmentRoots {
    /// Isolated roots strictly inside, in order.
    Roots(Vec<Root>),
    /// g vanishes on the whole segment.
    Zero,
    /// Not decided (a multiple root).
    Unresolved,
}

/// Lazily computed, shared knowledge about grid lines: breakpoints, point signs, segment roots.
struct Lines<'a> {
    g: &'a Bernstein<Rational>,
    /// `g` scaled to integer coefficients ([`integer_multiple`]), for exact line restrictions.
    g_int: Bernstein<Rational>,
    /// `g` in f64 intervals, derived once from the exact input (the fast path of point signs).
    g_fast: Bernstein<Interval>,
    opts: &'a CurveOptions,
    breakpoints: BTreeMap<(usize, Dyadic), BTreeSet<Dyadic>>,
    polys: BTreeMap<(usize, Dyadic), Bernstein<Rational>>,
    point_signs: BTreeMap<(Dyadic, Dyadic), Sign>,
    segments: BTreeMap<(usize, Dyadic, Dyadic, Dyadic), SegmentRoots>,
    stats: Escalations,
}

/// The point with `fixed` = c and the other variable = s, as (u, v).
fn uv(fixed: usize, c: Dyadic, s: Dyadic) -> (Dyadic, Dyadic) {
    if fixed == 0 {
        (c, s)
    } else {
        (s, c)
    }
}

impl<'a> Lines<'a> {
    fn poly(&mut self, fixed: usize, c: Dyadic) -> &Bernstein<Rational> {
        let g = &self.g_int;
        self.polys
            .entry((fixed, c))
            .or_insert_with(|| line_polynomial(g, fixed, c))
    }

    fn sign_at(&mut self, u: Dyadic, v: Dyadic) -> Sign {
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
    fn cuts(&self, fixed: usize, c: Dyadic, s0: Dyadic, s1: Dyadic) -> Vec<Dyadic> {
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

    fn segment(&mut self, fixed: usize, c: Dyadic, s0: Dyadic, s1: Dyadic) -> SegmentRoots {
        if let Some(r) = self.segments.get(&(fixed, c, s0, s1)) {
            return r.clone();
        }
        let depth = self.opts.max_depth.saturating_add(16);
        let ladder = self.opts.ladder;
        let p = self.poly(fixed, c).clone();
        let mut stats = Escalations::default();
        let roots = isolate_roots_in(&p, s0, s1, &ladder, depth, &mut stats);
        self.stats.merge(&stats);
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

/// One thing that happens along the o-axis of a graph box: a root of g on one of the two
/// m-edges, or a segment of an m-edge on which g vanishes.
#[derive(Clone, Debug)]
struct Event {
    lo: Dyadic,
    hi: Dyadic,
    /// 0: on the low m-edge, 1: on the high m-edge.
    side: usize,
    id: CrossingId,
    /// g ≡ 0 on [lo, hi] of this edge (an arc along the edge).
    zero: bool,
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
                    TIME_LIMIT_REASON
                } else {
                    UNRESOLVED_CELL
                }
                .to_string(),
            }),
            // Past the time limit, monotone boxes are not worked out any more.
            CellKind::Graph { .. } if opts.past_deadline() => out.unresolved.push(Unresolved {
                cell: *cell,
                reason: TIME_LIMIT_REASON.to_string(),
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
        out.critical = critical_points(g, &boxes);
        for u in &mut out.unresolved {
            if let Some(cp) = out.critical.iter().find(|cp| cp.in_box(&u.cell)) {
                u.reason = cp.reason(&u.cell);
            }
        }
    }
    // Arcs along an edge are found from both sides: keep one.
    let mut seen = BTreeSet::new();
    arcs.retain(|a| a.reason != "on edge" || seen.insert((a.from.min(a.to), a.from.max(a.to))));

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

/// Where a crossing is, refined to `refine_width`: a box in (u, v) and, for a crossing inside
/// a segment, the exact isolating interval along its line.
fn locate(lines: &mut Lines, id: CrossingId) -> ([[f64; 2]; 2], Option<(Dyadic, Dyadic)>) {
    match id {
        CrossingId::Exact { u, v } => {
            let ((u0, u1), (v0, v1)) = (u.to_f64_bounds(), v.to_f64_bounds());
            ([[u0, v0], [u1, v1]], None)
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
                    let mut stats = Escalations::default();
                    let fine = refine_root(
                        &p,
                        r[k],
                        lines.opts.refine_width,
                        &lines.opts.ladder,
                        &mut stats,
                    );
                    lines.stats.merge(&stats);
                    (fine.lo(), fine.hi())
                }
                _ => (s0, s1),
            };
            let (lo, hi) = (dlo.to_f64_bounds().0, dhi.to_f64_bounds().1);
            let (c0, c1) = c.to_f64_bounds();
            let location = if fixed == 0 {
                [[c0, lo], [c1, hi]]
            } else {
                [[lo, c0], [hi, c1]]
            };
            (location, Some((dlo, dhi)))
        }
    }
}

/// The events on one m-edge (the line where m = c) over the box's o-range.
fn edge_events(
    lines: &mut Lines,
    m: usize,
    c: Dyadic,
    side: usize,
    o_lo: Dyadic,
    o_hi: Dyadic,
) -> Result<Vec<Event>, String> {
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
            Sign::Unknown => return Err("the sign of g at a box corner was not decided".into()),
            _ => {}
        }
        if let Some(&s1) = cuts.get(i + 1) {
            match lines.segment(m, c, s, s1) {
                SegmentRoots::Zero => events.push(Event { lo: s, hi: s1, side, id: CrossingId::Exact { u, v }, zero: true }),
                SegmentRoots::Unresolved => return Err("a multiple root of g on a box edge (the curve is tangent to the edge) was not isolated".into()),
                SegmentRoots::Roots(roots) => {
                    for (k, r) in roots.iter().enumerate() {
                        let id = match *r {
                            Root::At { t } => {
                                let (u, v) = uv(m, c, t);
                                CrossingId::Exact { u, v }
                            }
                            Root::Between { .. } => CrossingId::Segment { fixed: m, c, s0: s, s1, k },
                        };
                        events.push(Event { lo: r.lo(), hi: r.hi(), side, id, zero: false });
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
fn o_edge_crossing(
    lines: &mut Lines,
    m: usize,
    o_c: Dyadic,
    m_lo: Dyadic,
    m_hi: Dyadic,
) -> Result<CrossingId, String> {
    let o = 1 - m;
    let cuts = lines.cuts(o, o_c, m_lo, m_hi);
    let mut prev: Option<(Dyadic, Sign)> = None;
    for &s in &cuts {
        let (u, v) = uv(o, o_c, s);
        let sg = lines.sign_at(u, v);
        match sg {
            Sign::Zero => return Ok(CrossingId::Exact { u, v }),
            Sign::Unknown => return Err("the sign of g at a box corner was not decided".into()),
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
    Err("internal: no sign change on a box edge the curve crosses".into())
}

/// The arcs in a box where g is strictly monotone along `m` (a graph over the other variable).
/// Touch points met in a monotone box: (crossing, isolated in this box).
type Touches = Vec<(CrossingId, bool)>;

fn graph_box_arcs(
    lines: &mut Lines,
    cell: DyadicBox,
    m: usize,
    touches: &mut Touches,
) -> Result<Vec<Arc>, String> {
    let o = 1 - m;
    let (o_lo, o_hi) = (cell.lo[o], cell.hi[o]);
    let reason = if m == 0 {
        "graph over v"
    } else {
        "graph over u"
    };
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
                let mut stats = Escalations::default();
                let r = refine_root(
                    &p,
                    Root::Between { lo: e.lo, hi: e.hi },
                    w,
                    &lines.opts.ladder,
                    &mut stats,
                );
                lines.stats.merge(&stats);
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
            return Err("roots of g on opposite box edges could not be separated".into());
        }
    }
    events.sort_by_key(|e| (e.lo, e.hi));
    if (1..events.len()).any(|i| conflict(&events[i - 1], &events[i])) {
        return Err("roots of g on opposite box edges could not be separated".into());
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
            a.midpoint(b)
                .ok_or("the depth budget was reached separating roots")?
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
            return Err("the sign of g between roots was not decided".into());
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
                        reason,
                    });
                }
            }
            arcs.push(Arc {
                from: a,
                to: b,
                cell,
                reason: "on edge",
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
                    reason,
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
                reason,
            });
        } else {
            return Err("internal: a component of the curve has no end in its box".into());
        }
    }
    Ok(arcs)
}

/// Whether a crossing lies on the boundary of the unit square.
fn on_square_boundary(id: &CrossingId) -> bool {
    let end = |x: Dyadic| x == Dyadic::ZERO || x == Dyadic::ONE;
    match *id {
        CrossingId::Exact { u, v } => end(u) || end(v),
        CrossingId::Segment { c, .. } => end(c),
    }
}

/// Chains arcs into branches through shared crossings.
pub(crate) fn chain(arcs: &[Arc]) -> Vec<Branch> {
    let ids: Vec<CrossingId> = arcs
        .iter()
        .flat_map(|a| [a.from, a.to])
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    let index = |c: &CrossingId| ids.binary_search(c).expect("every end is listed");
    let edges: Vec<(usize, usize)> = arcs
        .iter()
        .map(|a| (index(&a.from), index(&a.to)))
        .collect();
    crate::solver::chain::chain(&edges, ids.len(), &|v| on_square_boundary(&ids[v]), &|_| {
        false
    })
    .into_iter()
    .map(|c| Branch {
        crossings: c.vertices.into_iter().map(|v| ids[v]).collect(),
        closed: c.closed,
        complete: c.complete,
    })
    .collect()
}
