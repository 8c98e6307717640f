//! The certified topology of a plane curve `g(u, v) = 0`, as the solver returns it: arcs
//! between crossings, branches, the cells of the subdivision, unresolved boxes; and the
//! chaining of arcs into branches.

use crate::geometry::Rect;
use crate::number::Sign;
use crate::reason::Reason;
use crate::solver::dyadic::{Dyadic, DyadicBox};
use crate::solver::plane_curve::critical_points::CriticalPoint;
use crate::solver::plane_curve::segments::on_square_boundary;
use crate::solver::plane_curve::CrossingId;
use crate::solver::precision::{Escalations, Level};
use std::collections::{BTreeMap, BTreeSet};

/// Why a piece of the curve in a box is one arc.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArcKind {
    /// `g` is monotone in u on the box: the arc is a graph over v (it meets every line
    /// `v = c` at most once).
    GraphOverV,
    /// `g` is monotone in v on the box: the arc is a graph over u.
    GraphOverU,
    /// `g` vanishes identically on this segment of a box edge: the arc is the segment.
    OnEdge,
}

impl ArcKind {
    /// The graph's arc for `g` monotone along `axis` (0: u, 1: v).
    pub fn graph(axis: usize) -> ArcKind {
        if axis == 0 {
            ArcKind::GraphOverV
        } else {
            ArcKind::GraphOverU
        }
    }

    /// The axis along which `g` is monotone on the box (0: u, 1: v); `None` on an edge.
    pub fn monotone_axis(self) -> Option<usize> {
        match self {
            ArcKind::GraphOverV => Some(0),
            ArcKind::GraphOverU => Some(1),
            ArcKind::OnEdge => None,
        }
    }

    /// "graph over v", "graph over u" or "on edge".
    pub fn as_str(self) -> &'static str {
        match self {
            ArcKind::GraphOverV => "graph over v",
            ArcKind::GraphOverU => "graph over u",
            ArcKind::OnEdge => "on edge",
        }
    }
}

impl serde::Serialize for ArcKind {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
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
    /// Why it is a single arc (in the JSON, `"reason"`: its sentence).
    #[serde(rename = "reason")]
    pub kind: ArcKind,
}
/// A region whose topology was not decided.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Unresolved {
    /// The box.
    #[serde(rename = "box")]
    pub cell: DyadicBox,
    /// Why.
    pub reason: Reason,
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
    /// Where each crossing is: a box in (u, v) containing it (a point if exact).
    pub locations: BTreeMap<CrossingId, Rect>,
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
        self.locations[id].center()
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
