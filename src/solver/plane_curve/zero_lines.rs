//! Lines of the square on which a curve's polynomial vanishes identically.
//!
//! A polynomial `g(u, v)` that vanishes on the whole line `u = c` has the factor `u − c`
//! (exactly: `g(c, v) ≡ 0` and division by a monic linear factor in u). The line is then part
//! of the curve `g = 0`, but where the rest of the curve meets it, g is singular, and the
//! subdivision solver cannot settle a box around such a point. So the factors of lines at
//! dyadic `c` are divided out exactly, the quotient is solved with the line forced into the
//! grid ([`solve_curve_cut`](crate::solver::solve_curve_cut)), and the line is added back as arcs
//! split at the quotient's crossings with it (`proofs/silhouette-join.md`, "Lines").
//! The sides of the square (c = 0 or 1) are the same thing, handled by the caller (their
//! crossings are joined across patches).

use crate::bernstein::Bernstein;
use crate::geometry::Rect;
use crate::number::Rational;
use crate::reason::Reason;
use crate::solver::dyadic::{Dyadic, DyadicBox};
use crate::solver::plane_curve::ArcKind;
use crate::solver::plane_curve::{Arc, CrossingId, CurveTopology};
use crate::solver::precision::{Escalations, Policy};
use crate::solver::univariate::{isolate_roots, refine_root, Root};

/// Lines are looked for at dyadic positions with denominators up to 2^MAX_LINE_EXP.
pub const MAX_LINE_EXP: u32 = 24;

/// A line `variable[axis] = at` inside the square on which the polynomial vanished, with the
/// power of its factor that was divided out.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
pub struct ZeroLine {
    /// 0: the line u = at; 1: the line v = at.
    pub axis: usize,
    /// Where, strictly inside (0, 1).
    pub at: Dyadic,
    /// How many times `t_axis − at` divided the polynomial.
    pub power: usize,
}

impl std::fmt::Display for ZeroLine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let name = if self.axis == 0 { "u" } else { "v" };
        write!(f, "{name}={}", self.at.to_rational())
    }
}

/// The polynomial of the fibre of `g` along `axis` at index `k` of the other variable: a
/// univariate polynomial in the variable `axis`.
fn fibre(g: &Bernstein<Rational>, axis: usize, k: usize) -> Bernstein<Rational> {
    let d = g.degrees()[axis];
    let coeffs: Vec<Rational> = (0..=d)
        .map(|i| {
            let idx = if axis == 0 { [i, k] } else { [k, i] };
            g.coeff(&idx).clone()
        })
        .collect();
    Bernstein::new(&[d], coeffs).expect("one variable")
}

/// Divides out of `g` the factors of every line `u = c` or `v = c` with dyadic `c` in
/// (0, 1) of denominator at most `2^max_exp` (capped at 2^[`MAX_LINE_EXP`]) on which it
/// vanishes identically, exactly, as many times as each divides.
/// Returns the quotient and the lines (sorted).
///
/// The candidates are the dyadic roots of one nonzero fibre (every fibre vanishes at c on
/// such a line), found exactly by bisection; each is kept only if exact division succeeds,
/// so a line is never reported that is not one. A zero line at a non-dyadic position, or one
/// that the root isolation cannot reach within its depth, stays in `g` (its junctions are
/// then left unresolved by the solver, not guessed).
///
/// # Examples
/// ```
/// use limn::bernstein::Bernstein;
/// use limn::number::Rational;
/// use limn::solver::plane_curve::zero_lines::divide_zero_lines;
/// use limn::solver::{Escalations, Ladder, Policy};
/// // g = (u − 1/2)(u + v − 1), degree (2, 1): vanishes on the line u = 1/2.
/// let half = Rational::from((1, 2));
/// let lin = Bernstein::new(&[1, 0], vec![-half.clone(), half]).unwrap();
/// let diag = Bernstein::new(&[1, 1], [-1, 0, 0, 1].map(Rational::from).to_vec()).unwrap();
/// let (ladder, mut counts) = (Ladder::default(), Escalations::default());
/// let (k, lines) = divide_zero_lines(&(&lin * &diag), 24, &mut Policy::new(&ladder, &mut counts));
/// assert_eq!(k, diag);
/// assert_eq!(lines.len(), 1);
/// assert_eq!(lines[0].to_string(), "u=1/2");
/// ```
pub fn divide_zero_lines(
    g: &Bernstein<Rational>,
    max_exp: u32,
    policy: &mut Policy,
) -> (Bernstein<Rational>, Vec<ZeroLine>) {
    let max_exp = max_exp.min(MAX_LINE_EXP);
    let mut g = g.clone();
    let mut lines = Vec::new();
    if g.is_zero() {
        return (g, lines);
    }
    for axis in 0..2 {
        let other = g.degrees()[1 - axis];
        let Some(f) = (0..=other)
            .map(|k| fibre(&g, axis, k))
            .find(|f| !f.is_zero())
        else {
            continue;
        };
        if f.degrees()[0] == 0 {
            continue;
        }
        let roots = isolate_roots(&f, max_exp, policy);
        let width = (-(max_exp as f64)).exp2();
        let mut candidates: Vec<Dyadic> = Vec::new();
        for r in roots.roots {
            if let Root::At { t } = refine_root(&f, r, width, policy) {
                candidates.push(t);
            }
        }
        for at in candidates {
            if at == Dyadic::ZERO || at == Dyadic::ONE || at.exp() > max_exp {
                continue;
            }
            let c = at.to_rational();
            let mut power = 0;
            while let Some(q) = g.divide_linear_factor(axis, &c) {
                g = q;
                power += 1;
            }
            if power > 0 {
                lines.push(ZeroLine { axis, at, power });
            }
        }
    }
    lines.sort();
    (g, lines)
}

/// The crossing at `s` along the line where variable `fixed` equals `c`.
pub fn line_point(fixed: usize, c: Dyadic, s: Dyadic) -> CrossingId {
    let (u, v) = if fixed == 0 { (c, s) } else { (s, c) };
    CrossingId::Exact { u, v }
}

/// Where a crossing lies along the line `fixed = c`, as the exact interval of the other
/// variable that contains it (a point if exact), if it is on that line.
pub fn on_line(
    t: &CurveTopology,
    id: &CrossingId,
    fixed: usize,
    c: Dyadic,
) -> Option<(Dyadic, Dyadic)> {
    match *id {
        CrossingId::Exact { u, v } => {
            let (x, s) = if fixed == 0 { (u, v) } else { (v, u) };
            (x == c).then_some((s, s))
        }
        CrossingId::Segment {
            fixed: f,
            c: cc,
            s0,
            s1,
            ..
        } => (f == fixed && cc == c).then(|| t.intervals.get(id).copied().unwrap_or((s0, s1))),
    }
}

/// Adds the line `fixed = c` (a side or a zero line, with its factor divided out before
/// solving) to the topology as arcs along it, split at every crossing of the solved curve
/// with it and at the points `at` (other lines crossing it), in order along it. Their
/// isolating intervals are disjoint (distinct roots of the solved polynomial on that line),
/// and an exact point is never inside another's open interval, so sorting orders them.
///
/// Where an arc of the solved curve only touches the line (passing through a point of it
/// without ending there), that point of the curve is not a node of the arc graph, so the
/// junction is not represented: the boxes around it are reported unresolved instead.
pub fn add_line(t: &mut CurveTopology, fixed: usize, c: Dyadic, at: &[Dyadic]) {
    let passing: Vec<CrossingId> = t
        .passing
        .iter()
        .copied()
        .filter(|id| on_line(t, id, fixed, c).is_some())
        .collect();
    for id in passing {
        let location = t.locations.get(&id).copied().unwrap_or(Rect::UNIT);
        let cells: Vec<DyadicBox> = t
            .cells
            .iter()
            .map(|cell| cell.cell)
            .filter(|b| b.to_f64().meets(&location))
            .collect();
        for cell in cells {
            t.unresolved.push(crate::solver::plane_curve::Unresolved {
                cell,
                reason: Reason::OneSidedTouch,
            });
        }
    }
    let mut nodes: Vec<(Dyadic, Dyadic, CrossingId)> = Vec::new();
    let ids: Vec<CrossingId> = t
        .arcs
        .iter()
        .flat_map(|a| [a.from, a.to])
        .chain(t.touches.iter().copied())
        .chain(t.branches.iter().flat_map(|b| b.crossings.iter().copied()))
        .chain(
            [Dyadic::ZERO, Dyadic::ONE]
                .iter()
                .chain(at)
                .map(|&s| line_point(fixed, c, s)),
        )
        .collect();
    for id in ids {
        if let Some((lo, hi)) = on_line(t, &id, fixed, c) {
            if !nodes.iter().any(|x| x.2 == id) {
                nodes.push((lo, hi, id));
            }
        }
    }
    nodes.sort();
    for &(_, _, id) in &nodes {
        if let CrossingId::Exact { u, v } = id {
            let p = [u.to_f64(), v.to_f64()];
            t.locations.entry(id).or_insert(Rect::point(p));
        }
    }
    for w in nodes.windows(2) {
        t.arcs.push(Arc {
            from: w[0].2,
            to: w[1].2,
            cell: DyadicBox::UNIT,
            kind: ArcKind::OnEdge,
        });
    }
}

/// A curve solved with its zero lines divided out and added back.
#[derive(Clone, Debug)]
pub struct LinedCurve {
    /// The polynomial solved: the input with the lines' factors divided out.
    pub quotient: Bernstein<Rational>,
    /// The lines divided out.
    pub lines: Vec<ZeroLine>,
    /// The solver's topology of the quotient (what a certificate states).
    pub solved: CurveTopology,
    /// The topology of the whole curve: the quotient's arcs and the lines' arcs, split where
    /// they meet. Branches end at the junctions (crossings where three or more arcs meet),
    /// which are proven points of the curve, so a branch ending there is complete.
    pub topology: CurveTopology,
}

/// Solves `g = 0` on the unit square with the lines on which `g` vanishes divided out
/// ([`divide_zero_lines`]) and added back as arcs ([`add_line`]).
///
/// # Examples
/// ```
/// use limn::bernstein::Bernstein;
/// use limn::number::Rational;
/// use limn::solver::plane_curve::zero_lines::solve_curve_lines;
/// use limn::solver::CurveOptions;
/// // (u − 1/2)(v − u): the line u = 1/2 and the diagonal, crossing at (1/2, 1/2).
/// let half = Rational::from((1, 2));
/// let line = Bernstein::new(&[1, 0], vec![-half.clone(), half]).unwrap();
/// let diag = Bernstein::new(&[1, 1], [0, 1, -1, 0].map(Rational::from).to_vec()).unwrap();
/// let c = solve_curve_lines(&(&line * &diag), &CurveOptions::default());
/// assert!(c.topology.is_certified());
/// assert_eq!(c.lines.len(), 1);
/// assert_eq!(c.topology.branches.len(), 4); // four arcs out of the crossing
/// assert!(c.topology.branches.iter().all(|b| b.complete));
/// ```
pub fn solve_curve_lines(
    g: &Bernstein<Rational>,
    opts: &crate::solver::CurveOptions,
) -> LinedCurve {
    // Past the deadline nothing is set up (the division of lines and the derivatives are
    // exact, a cost per patch): the whole square is unresolved by the time limit.
    if opts.past_deadline() && !g.is_zero() {
        let topology = CurveTopology {
            unresolved: vec![crate::solver::plane_curve::Unresolved {
                cell: DyadicBox::UNIT,
                reason: Reason::TimeLimit,
            }],
            ..CurveTopology::default()
        };
        return LinedCurve {
            quotient: g.clone(),
            lines: Vec::new(),
            solved: topology.clone(),
            topology,
        };
    }
    // A line deeper than the subdivision may go cannot be made a grid line: not divided.
    let mut stats = Escalations::default();
    let (quotient, lines) = divide_zero_lines(
        g,
        opts.max_depth,
        &mut Policy::new(&opts.ladder, &mut stats),
    );
    let cuts: Vec<(usize, Dyadic)> = lines.iter().map(|z| (z.axis, z.at)).collect();
    let mut solved = crate::solver::solve_curve_cut(&quotient, &cuts, opts);
    solved.escalations.merge(&stats);
    let mut topology = solved.clone();
    for z in &lines {
        let across: Vec<Dyadic> = lines
            .iter()
            .filter(|w| w.axis != z.axis)
            .map(|w| w.at)
            .collect();
        add_line(&mut topology, z.axis, z.at, &across);
    }
    if !lines.is_empty() {
        // One-point components (the curve touching the square's boundary from outside) are
        // kept; every other branch is chained anew through the lines.
        let points: Vec<_> = solved
            .branches
            .iter()
            .filter(|b| b.crossings.len() == 1 && !b.closed)
            .filter(|b| {
                !topology
                    .arcs
                    .iter()
                    .any(|a| a.from == b.crossings[0] || a.to == b.crossings[0])
            })
            .cloned()
            .collect();
        topology.branches = crate::solver::plane_curve::chain(&topology.arcs);
        topology.branches.extend(points);
        let mut degree: std::collections::BTreeMap<CrossingId, usize> = Default::default();
        for a in &topology.arcs {
            *degree.entry(a.from).or_default() += 1;
            *degree.entry(a.to).or_default() += 1;
        }
        let boundary = |id: &CrossingId| match *id {
            CrossingId::Exact { u, v } => [u, v]
                .iter()
                .any(|&x| x == Dyadic::ZERO || x == Dyadic::ONE),
            CrossingId::Segment { c, .. } => c == Dyadic::ZERO || c == Dyadic::ONE,
        };
        for b in &mut topology.branches {
            let end_ok = |id: &CrossingId| {
                let d = degree.get(id).copied().unwrap_or(0);
                d >= 3 || (d == 1 && boundary(id))
            };
            if !b.closed && b.crossings.len() > 1 {
                let (first, last) = (b.crossings[0], b.crossings[b.crossings.len() - 1]);
                b.complete = end_ok(&first) && end_ok(&last);
            }
        }
    }
    LinedCurve {
        quotient,
        lines,
        solved,
        topology,
    }
}
