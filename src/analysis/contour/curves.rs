//! The result of [`model_curves`](crate::analysis::contour::family::model_curves): curves on
//! a model with their patches, certified flags and error bounds, singular points, degenerate
//! cases and what is unresolved.

use crate::analysis::chords::cubic::Cubic;
use crate::analysis::frame::Frame;
use crate::bernstein::Bernstein;
use crate::geometry::Rect;
use crate::number::Rational;
use crate::solver::plane_curve::zero_lines::ZeroLine;
use crate::solver::{CrossingId, CurveTopology, Escalations};
use crate::surface::Edge;

/// A degenerate situation recognised exactly.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Degenerate {
    /// The patch.
    pub patch: usize,
    /// "edge-on" (g ≡ 0: the whole patch is on the silhouette, e.g. a plane seen edge-on),
    /// "collapsed side" (a side collapsed to a point, where the normal vanishes),
    /// "silhouette side" (g vanishes on a whole side: the side is part of the silhouette) or
    /// "silhouette line" (g vanishes on a whole line u = c or v = c inside the patch); for
    /// other curve families, the names their [`CurveRules`](crate::analysis::contour::family::CurveRules) give.
    pub kind: &'static str,
    /// The side, for "collapsed side" and "silhouette side".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub side: Option<Edge>,
    /// The line, for "silhouette line": "u=c" or "v=c" with c exact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<String>,
}
/// A node of the model-level curve graph: a crossing of one patch.
pub(crate) type Node = (usize, CrossingId);
/// A silhouette curve on the model.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SilhouetteCurve {
    /// The patches it crosses, in order of first visit.
    pub patches: Vec<usize>,
    /// A closed loop.
    pub closed: bool,
    /// Its topology is proven: every join is proven and an open curve ends on the open
    /// boundary of the model.
    pub certified_topology: bool,
    /// Topology proven and every drawn segment within the tolerance of the true curve
    /// (`proofs/chord-accuracy.md`); false without a tolerance.
    pub certified: bool,
    /// The largest proven distance between a drawn segment and the true curve, in model units
    /// (absent without a tolerance, or where no bound was reached).
    pub error_bound: Option<f64>,
    /// Points along the curve in order, (patch, u, v): the crossings at the centres of their
    /// certified locations and, between them, drawing points on the curve computed in f64 on
    /// lines across each arc's box (not certified).
    pub points_uv: Vec<(usize, f64, f64)>,
    /// The same points in space (f64 evaluation of the patch at those parameters).
    pub points: Vec<[f64; 3]>,
    /// Boxes of parameters that cover the curve, each with the drawn points it holds: a proven
    /// enclosure of the curve along its polyline, for bounds on functions along it (as the
    /// directions of [`crate::analysis::events`]). Empty for curves not found by the certified solver.
    #[serde(skip)]
    pub pieces: Vec<CurvePiece>,
    /// The curve as certified cubic Bézier pieces, in order along it (empty without a
    /// tolerance, or where an arc was traced by certified vertices instead or not at all:
    /// then `cubic_bound` is absent). Each holds its own proven bounds
    /// (`proofs/cubic-pieces.md`).
    pub cubics: Vec<CubicPiece>,
    /// The largest proven bound of the space cubics, in model units: present when the whole
    /// curve is covered by cubics.
    pub cubic_bound: Option<f64>,
}
/// A certified cubic piece of a curve on one patch ([`SilhouetteCurve::cubics`]).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CubicPiece {
    /// The patch whose parameters `uv` are.
    pub patch: usize,
    /// The control points and bounds.
    #[serde(flatten)]
    pub cubic: Cubic,
}
/// A box of one patch's parameters that holds a piece of a curve and the drawn points
/// `first..=last` of it ([`SilhouetteCurve::pieces`]). The pieces of a curve cover it, and
/// every drawn segment lies in one of them.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvePiece {
    /// The patch.
    pub patch: usize,
    /// The box in (u, v).
    pub cell: Rect,
    /// The first drawn point it holds (an index into `points_uv`).
    pub first: usize,
    /// The last.
    pub last: usize,
}
/// What the curve solver was given and proved for one patch.
#[derive(Clone, Debug)]
pub struct SolvedPatch {
    /// The polynomial solved.
    pub g: Bernstein<Rational>,
    /// The sides whose linear factor was divided out of the silhouette function, with how many
    /// times: collapsed sides (points), and sides on which it vanishes (part of the silhouette,
    /// added back as arcs).
    pub divided: Vec<(Edge, usize)>,
    /// Lines inside the square on which the silhouette function vanishes, divided out too
    /// (added back as arcs).
    pub lines: Vec<ZeroLine>,
    /// The solver's result.
    pub topology: CurveTopology,
}
/// The silhouette of a model.
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct Silhouette {
    /// The curves.
    pub curves: Vec<SilhouetteCurve>,
    /// Where three or more arcs meet.
    pub singular_points: Vec<SingularPoint>,
    /// Per patch: its certified topology in the parameter square.
    #[serde(skip)]
    pub patches: Vec<CurveTopology>,
    /// Per patch: the exact polynomial solved (g with the factors of the sides on which it
    /// vanishes divided out), the sides divided with their powers, and the solver's topology
    /// before joins (what a certificate states).
    #[serde(skip)]
    pub solved: Vec<SolvedPatch>,
    /// Degenerate cases.
    pub degenerate: Vec<Degenerate>,
    /// Undecided regions: (patch, box, reason).
    pub unresolved: Vec<(usize, crate::solver::DyadicBox, crate::Reason)>,
    /// Shared edges across which the curves could not be joined with proof (patch sides).
    pub unjoined_edges: Vec<(usize, Edge, usize, Edge)>,
    /// Shared edges across which the function jumps (a crease for silhouettes, a curvature
    /// discontinuity for parabolic curves): crossings common to both patches (at the same
    /// exact point) are joined, and every other curve reaching them ends there, proven.
    pub ending_edges: Vec<(usize, Edge, usize, Edge)>,
    /// Boxes examined, summed over patches.
    pub boxes: usize,
    /// The tolerance the curves were traced to (absolute, model units), if any.
    pub tolerance: Option<f64>,
    /// Sign questions by the level that settled them.
    pub escalations: Escalations,
    /// The frame the curves were solved in ([`crate::analysis::frame`]): `solved` holds the
    /// polynomials of the model translated by its origin (what a certificate states); the
    /// points in space are the model's.
    #[serde(skip)]
    pub frame: Frame,
    /// What clipping to the model's trimmed faces did, when the curves were clipped.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trims: Option<TrimSummary>,
}
/// What clipping a model's curves to its trimmed faces did (`proofs/trimmed-faces.md`, 8).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct TrimSummary {
    /// The model's faces.
    pub faces: usize,
    /// Crossings of the curves with trimming curves inside patches, isolated and proven.
    pub crossings: usize,
    /// Arcs dropped as outside every face of their surface.
    pub dropped_arcs: usize,
    /// Points where a curve ends on a trimming curve.
    pub trim_ends: usize,
}
impl Silhouette {
    /// The result of a run on the model in `frame` carried back to the model's coordinates
    /// (`proofs/model-frame.md`): points in space moved by the origin, their error bounds
    /// grown by the rounding that adds, and a curve whose bound then exceeds `tol` (only for a
    /// model some 2⁵⁰ times the tolerance from the origin) no longer certified (its bound is
    /// kept: it is proven).
    pub(crate) fn in_model_frame(mut self, frame: &Frame, tol: Option<f64>) -> Silhouette {
        self.frame = frame.clone();
        if frame.is_identity() {
            return self;
        }
        for c in &mut self.curves {
            c.certified &= frame.drawing(&mut c.points, &mut c.error_bound, tol);
            // A Bézier curve moves with its control points; their rounding adds at most its
            // largest to the bound (convex combinations).
            let mut worst: Option<f64> = c.cubic_bound.map(|_| 0.0);
            for q in &mut c.cubics {
                let added = frame.points(&mut q.cubic.space);
                q.cubic.bound = frame
                    .bound(Some(q.cubic.bound), added)
                    .unwrap_or(f64::INFINITY);
                worst = worst.map(|w| w.max(q.cubic.bound));
            }
            c.cubic_bound = worst;
        }
        for p in &mut self.singular_points {
            p.point = frame.point(p.point);
        }
        self.tolerance = tol.filter(|_| self.tolerance.is_some());
        self
    }

    /// Whether the topology of every curve is proven: no unresolved region, every join
    /// proven, every open curve ending on the model's open boundary.
    pub fn topology_certified(&self) -> bool {
        self.unresolved.is_empty()
            && self.unjoined_edges.is_empty()
            && self.curves.iter().all(|c| c.certified_topology)
    }

    /// Whether the whole answer is certified: the topology, and every drawn segment within
    /// the tolerance of the true curve (false without a tolerance).
    pub fn certified(&self) -> bool {
        self.topology_certified()
            && self.tolerance.is_some()
            && self.curves.iter().all(|c| c.certified)
    }

    /// A result made of curves only (no per-patch data, nothing unresolved): for baselines.
    pub fn from_curves(curves: Vec<SilhouetteCurve>) -> Silhouette {
        Silhouette {
            curves,
            singular_points: Vec::new(),
            patches: Vec::new(),
            solved: Vec::new(),
            degenerate: Vec::new(),
            unresolved: Vec::new(),
            unjoined_edges: Vec::new(),
            ending_edges: Vec::new(),
            boxes: 0,
            tolerance: None,
            escalations: Escalations::default(),
            frame: Frame::identity(),
            trims: None,
        }
    }
}
/// A point where three or more arcs of the silhouette meet (the curve reaching a side on
/// which the silhouette function vanishes, or several patches' curves through one vertex).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SingularPoint {
    /// A patch it lies on.
    pub patch: usize,
    /// Its (u, v) there (the centre of `box`).
    pub uv: [f64; 2],
    /// The point in space.
    pub point: [f64; 3],
    /// A box in (u, v) that contains it, written by its corners `[[u0, v0], [u1, v1]]` (a
    /// point if exact).
    #[serde(rename = "box")]
    pub cell: Rect,
    /// Its parameters are exact dyadic numbers.
    pub exact: bool,
    /// The number of curve arcs that end at it (0: an isolated point of the curve, such as a
    /// collapsed point on the silhouette that no arc reaches, whose `box` is then the
    /// collapsed side and `uv` its middle: `proofs/silhouette-join.md`, "Collapsed sides").
    pub branches: usize,
}
