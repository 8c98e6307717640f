//! The certified topology of a curve in n variables, as the solver returns it: face
//! crossings with proven enclosures, arcs between them, branches, exact singular points and
//! unresolved boxes.

use crate::number::{Interval, Number, Rational};
use crate::reason::Reason;
use crate::solver::dyadic::Dyadic;
use crate::solver::precision::Escalations;
use crate::solver::space_curve::warp::unwarp_exact;
use crate::solver::system::{within, without};

/// A point where the curve crosses a face of a box, named once for all boxes that share it.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SpaceCrossing {
    /// The variable that is constant on the face.
    pub axis: usize,
    /// Its exact value there.
    pub at: Dyadic,
    /// A box that contains the point, `[lo, hi]` per variable (`[at, at]` on `axis`).
    pub enclosure: Vec<[f64; 2]>,
    /// On the boundary of the unit box (an end of the curve in the domain).
    pub on_boundary: bool,
    /// The region of the face hyperplane (coordinates without `axis`) where the point is the
    /// only zero of the face system: another solve of a system with the same zeros on that
    /// hyperplane names the same point when its enclosure lies here.
    pub unique_in: Vec<[f64; 2]>,
    /// An exact singular point of the curve (index into [`SpaceCurve::singular_points`]), the
    /// centre of the arcs of one box: it lies on no face of a box (`axis` is then `nvars` and
    /// `at` 0), and its arcs are the curve's branches through it (`proofs/space-curves.md` §6).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub singular: Option<usize>,
}
impl SpaceCrossing {
    /// The enclosure without the coordinate `axis` (coordinates on the face hyperplane).
    pub fn on_face(&self) -> Vec<[f64; 2]> {
        without(&self.enclosure, self.axis)
    }

    /// Whether `other`, a crossing of a system with the same zeros on the same hyperplane, is
    /// the same point (one's enclosure lies in the other's uniqueness region).
    pub fn same_point(&self, other: &SpaceCrossing) -> bool {
        self.axis == other.axis
            && self.at == other.at
            && (within(&self.on_face(), &other.unique_in)
                || within(&other.on_face(), &self.unique_in))
    }

    /// The centre of the enclosure.
    pub fn point(&self) -> Vec<f64> {
        self.enclosure.iter().map(|e| 0.5 * (e[0] + e[1])).collect()
    }
}
/// A smooth piece of the curve inside one box, between two crossings.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SpaceArc {
    /// One end (index into [`SpaceCurve::crossings`]).
    pub from: usize,
    /// The other end.
    pub to: usize,
    /// The box that contains it, `[lo, hi]` per variable.
    #[serde(rename = "box")]
    pub cell: Vec<[f64; 2]>,
    /// The variable the arc is a graph over (strictly monotone along it); `nvars` for an arc
    /// from a singular point, which is a graph over the distance from it (radially, in the
    /// box's own scale).
    pub monotone_in: usize,
    /// With a tolerance: per variable, a proven bound on the difference in that coordinate
    /// between corresponding points of the arc and of the segment between its crossings'
    /// centres, under a correspondence onto both (so the Hausdorff distance in the max norm
    /// is at most the largest entry).
    pub deviation: Option<Vec<f64>>,
}
/// A connected piece of the curve: a chain of crossings joined by arcs.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SpaceBranch {
    /// The crossings in order along the curve.
    pub crossings: Vec<usize>,
    /// A closed loop.
    pub closed: bool,
    /// Both ends lie on the boundary of the unit box (or it is closed), not at an unresolved box.
    pub complete: bool,
}
/// A box whose part of the curve was not decided.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SpaceUnresolved {
    /// The box.
    #[serde(rename = "box")]
    pub cell: Vec<[f64; 2]>,
    /// Why.
    pub reason: Reason,
}
/// An exact rational singular point of the curve: `F(p) = 0` and `DF(p)` of rank below `n − 1`,
/// both checked in exact arithmetic.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SpaceSingularPoint {
    /// Its exact coordinates, `"a/b"`.
    pub exact: Vec<String>,
    /// The same as rationals.
    #[serde(skip)]
    pub values: Vec<Rational>,
    /// The same in f64 (nearest).
    pub point: Vec<f64>,
    /// Its crossing (the centre of its arcs) when the star test decided a box around it;
    /// `None`: its branches are not resolved (the boxes around it are unresolved).
    pub crossing: Option<usize>,
    /// The number of branches from it (arcs of the curve ending there), when decided.
    pub branches: Option<usize>,
}
impl SpaceSingularPoint {
    /// Its exact coordinates before the solver's [`warp`](crate::solver::space_curve::warp::warp) with the factors `lambda`.
    pub fn unwarped(&self, lambda: &[Rational]) -> Vec<Rational> {
        self.values
            .iter()
            .zip(lambda)
            .map(|(t, l)| unwarp_exact(t, l))
            .collect()
    }
}
/// What the n-variable curve solver found.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct SpaceCurve {
    /// The number of variables.
    pub nvars: usize,
    /// The crossings, each point once.
    pub crossings: Vec<SpaceCrossing>,
    /// The arcs.
    pub arcs: Vec<SpaceArc>,
    /// The arcs chained into branches.
    pub branches: Vec<SpaceBranch>,
    /// Boxes left undecided.
    pub unresolved: Vec<SpaceUnresolved>,
    /// The exact singular points found near undecided boxes, with their branches where the
    /// star test decided them.
    pub singular_points: Vec<SpaceSingularPoint>,
    /// Boxes examined.
    pub boxes: usize,
    /// Boxes whose polynomials were recomputed from the exact input (their f64 enclosures had
    /// spread too wide), by the level that recomputed them.
    pub escalations: Escalations,
    /// With a tolerance: every arc's deviation is within it.
    pub within_tolerance: bool,
}
impl SpaceCurve {
    /// Topology proven everywhere: no unresolved box, and every branch complete.
    pub fn is_certified(&self) -> bool {
        self.unresolved.is_empty() && self.branches.iter().all(|b| b.complete)
    }

    /// A box, `[lo, hi]` per variable, that holds the arc and the drawn segment between its
    /// crossings' centres: the arc's box, narrowed (with a tolerance) to the hull of the two
    /// centres grown by the arc's deviation (`proofs/space-curves.md` §5: every point of the
    /// arc is within `deviation_k` in coordinate `k` of a point of the segment).
    pub fn arc_tube(&self, arc: &SpaceArc) -> Vec<[f64; 2]> {
        let (a, b) = (
            self.crossings[arc.from].point(),
            self.crossings[arc.to].point(),
        );
        (0..arc.cell.len())
            .map(|k| {
                let [lo, hi] = arc.cell[k];
                match &arc.deviation {
                    Some(dev) => {
                        let (l, h) = (a[k].min(b[k]), a[k].max(b[k]));
                        let grown = [
                            Interval::point(l).sub(&Interval::point(dev[k])).lo(),
                            Interval::point(h).add(&Interval::point(dev[k])).hi(),
                        ];
                        [grown[0].max(lo), grown[1].min(hi)]
                    }
                    None => [lo, hi],
                }
            })
            .collect()
    }
}
