//! Curve certificates: what [`solve_curve`](crate::solver::solve_curve) proved about `g = 0` on the
//! unit square, as plain data (exact rational strings) that the independent checker
//! ([`crate::solver::checker`]) re-verifies in `num-rational` arithmetic
//! (`proofs/certificate-check.md`).
//!
//! A certificate lists the leaf boxes of the subdivision (which must tile the square) with the
//! sign claim that settled each, the crossings of the curve with box edges (an exact point, or
//! an isolating interval on a grid line), the arcs inside each monotone box, and the branches
//! (components) as chains of crossings.

use crate::bernstein::Bernstein;
use crate::number::{Rational, Sign};
use crate::solver::dyadic::Dyadic;
use crate::solver::plane_curve::ArcKind;
use crate::solver::plane_curve::{CellKind, CrossingId, CurveTopology};
use crate::solver::precision::Level;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A leaf box and the claim that settled it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct CellClaim {
    /// Low corner `[u, v]`, exact rational strings.
    pub lo: [String; 2],
    /// High corner `[u, v]`.
    pub hi: [String; 2],
    /// "excluded" (g has strict sign `sign` on the box), "graph" (∂g/∂`along` has strict sign
    /// `sign`), or "unresolved".
    pub kind: String,
    /// +1 or −1 for "excluded" and "graph".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sign: Option<i8>,
    /// "u" or "v": the variable g is monotone in, for "graph".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub along: Option<String>,
    /// The precision that proved the sign in the fast path ("f64", "mpfr-212", "exact").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub precision: Option<String>,
}

/// A point where the curve meets a grid line.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum CrossingClaim {
    /// g(u, v) = 0 exactly at this point.
    Point {
        /// u.
        u: String,
        /// v.
        v: String,
    },
    /// On the line where `line` ("u" or "v") equals `at`, exactly one root of g, simple, in
    /// the open interval (lo, hi) of the other variable, or exactly at lo = hi.
    OnLine {
        /// The variable held fixed.
        line: String,
        /// Its value.
        at: String,
        /// Interval start.
        lo: String,
        /// Interval end.
        hi: String,
    },
}

/// An arc of the curve inside one box, between two crossings.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct ArcClaim {
    /// Index of the cell (a "graph" cell) the arc is in.
    pub cell: usize,
    /// Index of one end in `crossings`.
    pub from: usize,
    /// Index of the other end.
    pub to: usize,
    /// The arc runs along a box edge on which g vanishes identically.
    #[serde(default)]
    pub along_edge: bool,
}

/// A component of the curve in the square, as its chain of crossings.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct BranchClaim {
    /// Indices into `crossings`, in order.
    pub crossings: Vec<usize>,
    /// The last crossing joins the first.
    pub closed: bool,
}

/// Everything proven about `g = 0` on [0, 1]².
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct CurveCertificate {
    /// Degrees of g in u and v.
    pub degrees: [usize; 2],
    /// The exact Bernstein coefficients of g, row-major (index i·(n+1) + j for u-index i).
    pub g: Vec<String>,
    /// g is the zero polynomial (then there are no cells: every point is on the curve).
    pub identically_zero: bool,
    /// Whether the whole square was decided (no unresolved cell).
    pub certified: bool,
    /// The leaf boxes; they tile the square.
    pub cells: Vec<CellClaim>,
    /// The crossings.
    pub crossings: Vec<CrossingClaim>,
    /// The arcs.
    pub arcs: Vec<ArcClaim>,
    /// The components.
    pub branches: Vec<BranchClaim>,
}

fn exact(d: Dyadic) -> String {
    let q = d.to_rational();
    q.to_string()
}

fn level_name(level: Level) -> String {
    match level {
        Level::F64 => "f64".into(),
        Level::Mpfr(p) => format!("mpfr-{p}"),
        Level::Exact => "exact".into(),
    }
}

fn sign_value(s: Sign) -> Option<i8> {
    match s {
        Sign::Positive => Some(1),
        Sign::Negative => Some(-1),
        _ => None,
    }
}

impl CurveCertificate {
    /// The certificate of a solver result for the exact polynomial `g` it was computed from.
    ///
    /// # Examples
    /// ```
    /// use limn::bernstein::Bernstein;
    /// use limn::number::Rational;
    /// use limn::solver::{certificate::CurveCertificate, checker, solve_curve, CurveOptions};
    /// // g = u + v − 1 (linear: degree 1 in each variable).
    /// let q = |n: i64| Rational::from(n);
    /// let g = Bernstein::new(&[1, 1], vec![q(-1), q(0), q(0), q(1)]).unwrap();
    /// let topology = solve_curve(&g, &CurveOptions::default());
    /// let cert = CurveCertificate::new(&g, &topology);
    /// assert!(cert.certified);
    /// assert!(checker::check_curve(&cert).is_ok());
    /// ```
    pub fn new(g: &Bernstein<Rational>, t: &CurveTopology) -> CurveCertificate {
        let degrees = [g.degrees()[0], g.degrees()[1]];
        let mut index: BTreeMap<CrossingId, usize> = BTreeMap::new();
        let mut crossings = Vec::new();
        let mut id_of = |id: CrossingId| -> usize {
            *index.entry(id).or_insert_with(|| {
                crossings.push(match id {
                    CrossingId::Exact { u, v } => CrossingClaim::Point {
                        u: exact(u),
                        v: exact(v),
                    },
                    CrossingId::Segment {
                        fixed, c, s0, s1, ..
                    } => {
                        let (lo, hi) = t.intervals.get(&id).copied().unwrap_or((s0, s1));
                        CrossingClaim::OnLine {
                            line: if fixed == 0 { "u" } else { "v" }.into(),
                            at: exact(c),
                            lo: exact(lo),
                            hi: exact(hi),
                        }
                    }
                });
                crossings.len() - 1
            })
        };
        let cell_index: BTreeMap<_, usize> = t
            .cells
            .iter()
            .enumerate()
            .map(|(i, c)| ((c.cell.lo, c.cell.hi), i))
            .collect();
        let arcs: Vec<ArcClaim> = t
            .arcs
            .iter()
            .map(|a| ArcClaim {
                cell: cell_index
                    .get(&(a.cell.lo, a.cell.hi))
                    .copied()
                    .unwrap_or(usize::MAX),
                from: id_of(a.from),
                to: id_of(a.to),
                along_edge: a.kind == ArcKind::OnEdge,
            })
            .collect();
        for &id in &t.touches {
            id_of(id);
        }
        let branches = t
            .branches
            .iter()
            .map(|b| BranchClaim {
                crossings: b.crossings.iter().map(|&id| id_of(id)).collect(),
                closed: b.closed,
            })
            .collect();
        let cells = t
            .cells
            .iter()
            .map(|c| {
                let (kind, sign, along) = match c.kind {
                    CellKind::Excluded { sign } => ("excluded", sign_value(sign), None),
                    CellKind::Graph { m, sign } => (
                        "graph",
                        sign_value(sign),
                        Some(if m == 0 { "u" } else { "v" }.to_string()),
                    ),
                    CellKind::Unresolved => ("unresolved", None, None),
                };
                CellClaim {
                    lo: c.cell.lo.map(exact),
                    hi: c.cell.hi.map(exact),
                    kind: kind.into(),
                    sign,
                    along,
                    precision: c.level.map(level_name),
                }
            })
            .collect();
        CurveCertificate {
            degrees,
            g: g.coeffs().iter().map(|c| c.to_string()).collect(),
            identically_zero: t.identically_zero,
            certified: t.is_certified(),
            cells,
            crossings,
            arcs,
            branches,
        }
    }
}
