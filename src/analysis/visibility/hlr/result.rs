//! The hidden-line drawing as limn returns it: pieces with their proven QI (or why not),
//! what lies right behind the visible outline, the facing of each patch, the work counted.

use crate::analysis::frame::Frame;
use crate::analysis::visibility::facing::Facing;
use crate::analysis::visibility::ray::Hit;
use crate::geometry::Rect;
use crate::reason::Reason;
use crate::solver::precision::Escalations;
use crate::surface::Edge;

/// What a line is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LineKind {
    /// A silhouette arc.
    Silhouette,
    /// A patch boundary (a side; a shared edge is drawn once).
    Boundary,
    /// A trimming curve of a face (a B-rep edge is drawn once).
    Trim,
    /// A curve where two patches pass through each other (on `patch` and another).
    Intersection,
}
/// A piece of a line with constant visibility.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct HlrPiece {
    /// Silhouette or boundary.
    pub kind: LineKind,
    /// The patch the line lies on (for a shared edge, its first user).
    pub patch: usize,
    /// The side, for a boundary.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edge: Option<Edge>,
    /// For an intersection curve: the other patch it lies on.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub meets: Option<usize>,
    /// Its parameter interval (the side parameter, or the arc's free parameter; for an
    /// intersection curve, the variable of `(u, v, s, t)` its arc is a graph over).
    pub param: [f64; 2],
    /// The number of surface layers in front of it (`None` if not proven).
    pub qi: Option<usize>,
    /// Whether the QI is proven (and constant along the piece), and, with a tolerance, the
    /// drawing is proven within it.
    pub certified: bool,
    /// Why not, if not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<Reason>,
    /// With a tolerance: a proven bound on the Hausdorff distance in space between the drawn
    /// polyline and the true piece (`None`: not asked, or not proven within the tolerance).
    pub error_bound: Option<f64>,
    /// Points in space for drawing (within `error_bound` of the true piece if it is set).
    pub points: Vec<[f64; 3]>,
    /// The same points as (patch, u, v).
    pub points_uv: Vec<(usize, f64, f64)>,
    /// Whether the piece is proven outline, where what lies behind it shows on one side (a
    /// silhouette, a free side, a fold edge: `true`), proven not (a side inside a cluster:
    /// `false`), or neither (`None`).
    pub outline: Option<bool>,
    /// With [`HlrOptions::behind`](super::HlrOptions::behind), for a visible outline piece: what lies right behind it.
    #[serde(skip)]
    pub behind: Option<Behind>,
}
/// What lies right behind a visible outline piece, on the ray through its sample point.
#[derive(Clone, Debug, PartialEq)]
pub struct Behind {
    /// The sample: the patch of the piece and an enclosure of its parameters there.
    pub patch: usize,
    /// The enclosure (a point for a sample on a side or a line).
    pub uv: Rect,
    /// The first point of the model behind the sample (`None`: nothing, the background), or
    /// why it is not proven.
    pub first: Result<Option<Hit>, Reason>,
}
/// Counts of the work done.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct HlrStats {
    /// Line segments.
    pub segments: usize,
    /// Segment pairs whose image boxes meet (solved or skipped by monotonicity).
    pub pairs: usize,
    /// Pairs skipped because their union's image is monotone.
    pub monotone_pairs: usize,
    /// Pairs culled by their image boxes.
    pub culled_pairs: usize,
    /// Pairs skipped because both are edges inside a cluster (the surface continues across
    /// both in the image: neither can change the other's QI).
    pub cluster_pairs: usize,
    /// Segments that are edges inside a cluster.
    pub cluster_edges: usize,
    /// Segment-patch penetration systems solved.
    pub penetration_systems: usize,
    /// Cusps of the outline proven by lemma C (proofs/hidden-lines.md): runs of silhouette
    /// segments with an injective image, cut where the image tangent vanishes.
    pub cusps: usize,
    /// Segment pairs skipped because both lie in one such run.
    pub cusp_pairs: usize,
    /// Pieces whose ray tests were refused that took the QI of the piece across a point
    /// where their line was split for monotonicity (no event: proofs/hidden-lines.md).
    pub qi_across_splits: usize,
    /// Boxes around shared vertices excluded by a lemma (proofs/hidden-lines.md).
    pub excluded_vertices: usize,
    /// Boxes examined by the crossing and penetration systems.
    pub boxes: usize,
    /// Ray tests run, and those refused (another sample was tried).
    pub samples: usize,
    /// Ray tests refused.
    pub refused_samples: usize,
    /// Silhouette boxes the curve solver left unresolved (their lines are not drawn).
    pub silhouette_unresolved: usize,
    /// Sign questions by the precision level that settled them: the silhouette's, and the
    /// root isolation that places samples and cuts on its arcs (the caller's
    /// `opts.curve.ladder`).
    pub escalations: Escalations,
    /// Segments of trimming curves.
    pub trim_segments: usize,
    /// Crossings of trimming curves with patch sides and silhouettes, proven.
    pub trim_crossings: usize,
    /// Pieces left out as outside their patch's trimmed faces (proven).
    pub outside_faces: usize,
    /// Pairs of patches whose intersection curve was searched (no common corner, boxes
    /// meeting).
    pub intersection_pairs: usize,
    /// Segments of intersection curves (certified arcs).
    pub intersection_segments: usize,
    /// Boxes of intersection curves the curve solver did not decide (unresolved pieces).
    pub intersection_unresolved: usize,
    /// Points where an intersection curve meets a silhouette of one of its patches (vertices
    /// of both).
    pub intersection_folds: usize,
}
/// A hidden-line drawing.
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct HiddenLines {
    /// The pieces, in line order.
    pub pieces: Vec<HlrPiece>,
    /// Per patch, its self-visible type.
    pub facing: Vec<Facing>,
    /// Work counts.
    pub stats: HlrStats,
    /// What the result assumes without proof.
    pub assumptions: Vec<String>,
    /// Pairs of patches proven to intersect: a line of the first passes through the second
    /// (an isolated penetration root). Their intersection curve is drawn as lines of kind
    /// [`LineKind::Intersection`] (unless [`HlrOptions::intersections`](super::HlrOptions::intersections) is off).
    pub intersecting_patches: Vec<[usize; 2]>,
    /// The tolerance asked for, in model units.
    pub tolerance: Option<f64>,
}
/// The assumption of every drawing of a model with adjacent patches.
pub const ADJACENT_ASSUMPTION: &str = "no patch intersects itself, and patches that share a corner or an edge do not cross each other away from their common points (penetrations and intersection curves are searched between patches that share no corner and no side only)";
impl HiddenLines {
    /// The drawing of the model in `frame` carried back to the model's coordinates
    /// (`proofs/model-frame.md`): the points moved by the origin, error bounds grown by the
    /// rounding that adds, a piece whose bound then exceeds `tol` (only for a model some 2⁵⁰
    /// times the tolerance from the origin) no longer certified, with its reason.
    pub(crate) fn in_model_frame(mut self, frame: &Frame, tol: Option<f64>) -> HiddenLines {
        if frame.is_identity() {
            return self;
        }
        for p in &mut self.pieces {
            if !frame.drawing(&mut p.points, &mut p.error_bound, tol) {
                p.error_bound = None;
                p.certified = false;
                p.reason.get_or_insert(Reason::RoundingPastTolerance);
            }
        }
        self.tolerance = tol.filter(|_| self.tolerance.is_some());
        self
    }

    /// Whether every piece's visibility is proven and every silhouette region resolved.
    pub fn is_certified(&self) -> bool {
        self.stats.silhouette_unresolved == 0 && self.pieces.iter().all(|p| p.certified)
    }

    /// The largest proven drawing error of any piece (`None` without a tolerance, or if a
    /// piece's drawing is not bounded).
    pub fn largest_error(&self) -> Option<f64> {
        self.tolerance?;
        self.pieces
            .iter()
            .map(|p| p.error_bound)
            .try_fold(0.0f64, |acc, e| Some(acc.max(e?)))
    }
}
