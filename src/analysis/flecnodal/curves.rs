//! Flecnodal curves of a model: per patch, the curve `Ψ = Φ = 0` of the flecnodal system
//! ([`crate::analysis::flecnodal::system`]) in `(u, v, s)`, in both direction charts, solved by the n-variable
//! curve solver ([`crate::solver::space_curve`]), the two charts joined where they share a
//! direction (`d = (1, ±1)`), and mapped to the surface.
//!
//! The curve lies in the hyperbolic region by construction (`Ψ = 0` has a real direction only
//! where the Gaussian curvature is ≤ 0), and every direction appears once up to sign, so no
//! point is reported twice as `(a, b)` and `(−a, −b)`. A developable patch (Gaussian curvature
//! identically zero: planes, cylinders, cones) is flecnodal everywhere along its rulings: it is
//! reported as degenerate, not solved.

use crate::analysis::chords::space_curve::{Accuracy, TangentRanges, SIDES};
use crate::analysis::frame::Frame;

use crate::analysis::chords::sphere_curve::{largest, piece_error};
use crate::analysis::contour::parabolic::parabolic_function;
use crate::analysis::flecnodal::system::{flecnodal_system, Chart};
use crate::bernstein::lift;
use crate::error::Error;
use crate::model::Model;
use crate::number::{Interval, Number, Rational};
use crate::reason::Reason;
use crate::solver::chain::chain;
use crate::solver::precision::Escalations;
use crate::solver::space_curve::{
    solve_space_curve_where, unwarp, unwarp_interval, warp, ArcAccept, SpaceCrossing, SpaceCurve,
    SpaceCurveOptions,
};
use crate::surface::Evaluator;
use crate::surface::RationalPatch;
use rayon::prelude::*;

use crate::bernstein::Poly;

/// What to compute.
#[derive(Clone, Debug, Default)]
pub struct FlecnodalOptions {
    /// Budgets of the curve solver (its `tolerance` and `accept` are set from
    /// `tolerance`).
    pub solver: SpaceCurveOptions,
    /// The largest allowed distance in space between the drawn polyline and the true curve,
    /// in model units; `None`: topology only.
    pub tolerance: Option<f64>,
}

impl FlecnodalOptions {
    /// The same options with a wall-clock deadline for the solver (past it, no box is
    /// subdivided and no further patch or pair is started).
    pub fn with_deadline(mut self, deadline: Option<std::time::Instant>) -> FlecnodalOptions {
        self.solver.deadline = deadline;
        self
    }

    /// The defaults for a model: budgets that bound the time on a bad patch (per chart 5,000
    /// boxes to depth 12 for the topology; with a tolerance 50,000 to depth 16, since the
    /// chords must be short).
    pub fn with_tolerance(tolerance: Option<f64>) -> FlecnodalOptions {
        let (max_depth, max_boxes) = if tolerance.is_some() {
            (16, 50_000)
        } else {
            (12, 5_000)
        };
        FlecnodalOptions {
            solver: SpaceCurveOptions {
                max_depth,
                max_boxes,
                ..SpaceCurveOptions::default()
            },
            tolerance,
        }
    }
}

/// A point of a flecnodal curve.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FlecnodalPoint {
    /// Its parameters (the centre of a proven enclosure).
    pub uv: [f64; 2],
    /// The asymptotic direction `(a, b)` in the parameter plane, of unit length (up to sign).
    pub direction_uv: [f64; 2],
    /// The point on the surface.
    pub xyz: [f64; 3],
    /// The unit tangent of the line with 4-point contact (up to sign): the view direction of
    /// the visual event at this point.
    pub line: [f64; 3],
}

/// A connected piece of a flecnodal curve on one patch.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FlecnodalBranch {
    /// The patch.
    pub patch: usize,
    /// Its points in order along the curve (the crossings of the solver's boxes).
    pub points: Vec<FlecnodalPoint>,
    /// A closed loop.
    pub closed: bool,
    /// Its ends lie on the patch's sides (or it is closed): nothing is missing at its ends.
    pub complete: bool,
    /// A proven bound, in radians, on the distance between the polyline of its `line`s on the
    /// viewing sphere and the true lines along the branch, both ways
    /// ([`crate::analysis::chords::sphere_curve::piece_error`] per arc); `None` where an arc's lines could not be
    /// enclosed within 45°.
    pub line_error: Option<f64>,
}

/// A region of `(u, v, s)` whose part of the curve was not decided.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FlecnodalUnresolved {
    /// The patch.
    pub patch: usize,
    /// The direction chart.
    pub chart: Chart,
    /// The box, `[lo, hi]` for u, v and s.
    #[serde(rename = "box")]
    pub cell: Vec<[f64; 2]>,
    /// The surface point at the centre of the box's `(u, v)` (for drawing).
    pub at: [f64; 3],
    /// Why.
    pub reason: Reason,
}

/// An exact singular point of the flecnodal curve (`proofs/space-curves.md` §6): the system
/// and its Jacobian's rank checked in exact arithmetic.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FlecnodalSingular {
    /// The patch.
    pub patch: usize,
    /// The direction chart.
    pub chart: Chart,
    /// Its exact `(u, v, s)`, `"a/b"`.
    pub exact: Vec<String>,
    /// Its `(u, v)`.
    pub uv: [f64; 2],
    /// The point on the surface.
    pub xyz: [f64; 3],
    /// The number of branches of the curve from it, when the star test decided them; `None`:
    /// not resolved (the boxes around it are unresolved).
    pub branches: Option<usize>,
}

/// The flecnodal curves of one patch.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PatchFlecnodal {
    /// The patch.
    pub patch: usize,
    /// Why the patch was not solved (developable), if so.
    pub degenerate: Option<String>,
    /// The branches.
    pub branches: Vec<FlecnodalBranch>,
    /// What was not decided.
    pub unresolved: Vec<FlecnodalUnresolved>,
    /// The exact singular points found, with their branches where decided.
    pub singular_points: Vec<FlecnodalSingular>,
    /// Boxes examined, both charts.
    pub boxes: usize,
    /// Boxes recomputed exactly.
    pub escalations: Escalations,
    /// Sides of the square whose linear factor was divided out of the system (both equations
    /// vanish there for every direction, as on a collapsed side): the points of these sides
    /// are not analysed.
    pub divided_sides: Vec<&'static str>,
    /// With a tolerance: the largest proven distance between a drawn segment and the curve
    /// (`proofs/space-curves.md` §5, mapped to space), if a bound was found.
    pub error_bound: Option<f64>,
    /// With a tolerance: every drawn segment is proven within it.
    pub within_tolerance: bool,
}

impl PatchFlecnodal {
    /// Topology proven: nothing unresolved, every branch complete, not degenerate.
    pub fn is_certified(&self) -> bool {
        self.degenerate.is_none()
            && self.unresolved.is_empty()
            && self.branches.iter().all(|b| b.complete)
    }
}

/// The flecnodal curves of a model.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct FlecnodalCurves {
    /// Per patch.
    pub patches: Vec<PatchFlecnodal>,
}

impl FlecnodalCurves {
    /// Every patch certified.
    pub fn is_certified(&self) -> bool {
        self.patches.iter().all(PatchFlecnodal::is_certified)
    }

    /// The curves of the model in `frame` carried back to the model's coordinates
    /// (`proofs/model-frame.md`): points in space moved by the origin; parameters and the
    /// asymptotic lines' directions are unchanged by a translation.
    pub(crate) fn in_model_frame(mut self, frame: &Frame) -> FlecnodalCurves {
        if frame.is_identity() {
            return self;
        }
        for p in &mut self.patches {
            for b in &mut p.branches {
                for q in &mut b.points {
                    q.xyz = frame.point(q.xyz);
                }
            }
            for u in &mut p.unresolved {
                u.at = frame.point(u.at);
            }
            for s in &mut p.singular_points {
                s.xyz = frame.point(s.xyz);
            }
        }
        self
    }
}

/// The Möbius factors of [`warp`] for `(u, v, s)`: the solver's dyadic grid then falls on
/// parameters that are not simple fractions (curves of symmetric patches pass through simple
/// ones, such as `u = 1/2` with the direction `s = 1/2`).
const WARP: [(i64, i64); 3] = [(33, 32), (29, 32), (37, 32)];

fn warp_factors() -> [Rational; 3] {
    WARP.map(|(a, b)| Rational::from((a, b)))
}

fn warp_f64(k: usize) -> f64 {
    WARP[k].0 as f64 / WARP[k].1 as f64
}

/// The system with the linear factors of the sides on which both polynomials vanish for
/// every direction divided out (exactly, as often as they divide), and the sides divided.
fn deflate(mut eqs: [Poly; 2]) -> ([Poly; 2], Vec<&'static str>) {
    let mut divided = Vec::new();
    for (axis, at_one, name) in SIDES {
        // Only where both vanish on the whole face (every direction at every point of the
        // side, as on a collapsed side): there the side's points are not analysed.
        if eqs
            .iter()
            .all(|p| p.divide_face_factor(axis, at_one).is_some())
        {
            for p in eqs.iter_mut() {
                while let Some(q) = p.divide_face_factor(axis, at_one) {
                    *p = q;
                }
            }
            divided.push(name);
        }
    }
    (eqs, divided)
}

/// A point of the curve from a crossing of the solver in a chart.
fn flecnodal_point(eval: &Evaluator, chart: Chart, c: &SpaceCrossing) -> FlecnodalPoint {
    let t = c.point();
    let p: Vec<f64> = (0..3).map(|k| unwarp(t[k], warp_f64(k))).collect();
    let sigma = 2.0 * p[2] - 1.0;
    let (a, b) = match chart {
        Chart::AlongU => (1.0, sigma),
        Chart::AlongV => (sigma, 1.0),
    };
    let len = (a * a + b * b).sqrt();
    let [s, su, sv] = eval.eval(p[0], p[1]);
    let t: [f64; 3] = std::array::from_fn(|k| a * su[k] + b * sv[k]);
    let tl = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
    FlecnodalPoint {
        uv: [p[0], p[1]],
        direction_uv: [a / len, b / len],
        xyz: s,
        line: t.map(|x| x / tl),
    }
}

/// The flecnodal curves of one patch (its index `index` is only recorded).
///
/// # Examples
/// ```
/// use limn::analysis::flecnodal::curves::{patch_flecnodal, FlecnodalOptions};
/// use limn::testing::shapes;
/// use limn::number::Rational;
/// // A sphere has no hyperbolic points, so no flecnodal curve.
/// let sphere = &shapes::sphere(&Rational::from(1))[0];
/// let f = patch_flecnodal(sphere, 0, &FlecnodalOptions::default());
/// assert!(f.is_certified() && f.branches.is_empty());
/// ```
pub fn patch_flecnodal(
    patch: &RationalPatch,
    index: usize,
    options: &FlecnodalOptions,
) -> PatchFlecnodal {
    let mut out = PatchFlecnodal {
        patch: index,
        degenerate: None,
        branches: Vec::new(),
        unresolved: Vec::new(),
        singular_points: Vec::new(),
        boxes: 0,
        escalations: Escalations::default(),
        divided_sides: Vec::new(),
        error_bound: None,
        within_tolerance: options.tolerance.is_none(),
    };
    // Past the time limit, a patch is not started: its whole domain is reported unresolved.
    if options
        .solver
        .deadline
        .is_some_and(|d| std::time::Instant::now() >= d)
    {
        let at = Evaluator::new(patch).eval(0.5, 0.5)[0];
        out.unresolved = [Chart::AlongU, Chart::AlongV]
            .map(|chart| FlecnodalUnresolved {
                patch: index,
                chart,
                cell: vec![[0.0, 1.0]; 3],
                at,
                reason: Reason::TimeLimit,
            })
            .to_vec();
        return out;
    }
    let k = parabolic_function(patch);
    if k.is_zero() {
        out.degenerate = Some(
            "the Gaussian curvature vanishes identically (a developable patch: plane, cylinder, \
             cone): every point is flecnodal along its ruling"
                .to_string(),
        );
        return out;
    }
    let charts = [Chart::AlongU, Chart::AlongV];
    let lambda = warp_factors();
    let systems: Vec<([Poly; 2], Vec<&'static str>)> = charts
        .iter()
        .map(|&chart| {
            let f = flecnodal_system(patch, chart);
            let (eqs, divided) = deflate([f.asymptotic, f.contact]);
            (eqs.map(|p| warp(&p, &lambda)), divided)
        })
        .collect();
    // The hyperbolic filter: k (the parabolic function, with the factors of the sides where it
    // vanishes identically divided out: positive multiples inside) is > 0 where the patch is
    // elliptic, and there no direction is asymptotic.
    out.divided_sides = systems[0].1.clone();
    for (_, d) in &systems[1..] {
        for s in d {
            if !out.divided_sides.contains(s) {
                out.divided_sides.push(s);
            }
        }
    }
    // The same sides' factors out of k (a positive multiple inside the square); elsewhere k
    // keeps its zeros on the sides (a parabolic side is not dropped by the filter).
    let mut k = k;
    for (axis, at_one, name) in SIDES {
        if out.divided_sides.contains(&name) {
            while let Some(q) = k.divide_face_factor(axis, at_one) {
                k = q;
            }
        }
    }
    let elliptic = [warp(&lift(&k, 3, 0), &lambda)];
    let eval = Evaluator::new(patch);
    let accuracy = options
        .tolerance
        .and_then(|_| Accuracy::new(patch, [warp_f64(0), warp_f64(1)]));
    let mut opts = options.solver.clone();
    if let (Some(a), Some(t)) = (&accuracy, options.tolerance) {
        // Deviations computed for every variable; an arc is accurate when its bound in space
        // (the one reported) meets the tolerance.
        opts.tolerance = Some(vec![f64::INFINITY; 3]);
        let a = a.clone();
        opts.accept = Some(ArcAccept(std::sync::Arc::new(move |from, to, dev| {
            a.error_of(from, to, dev, 0) <= t
        })));
    }
    let opts = &opts;
    let (cu, cv) = rayon::join(
        || solve_space_curve_where(&systems[0].0, &elliptic, opts),
        || solve_space_curve_where(&systems[1].0, &elliptic, opts),
    );
    for (chart, c) in charts.iter().zip([&cu, &cv]) {
        out.singular_points
            .extend(c.singular_points.iter().map(|sp| {
                let exact = sp.unwarped(&lambda);
                let uv = [exact[0].to_f64(), exact[1].to_f64()];
                FlecnodalSingular {
                    patch: index,
                    chart: *chart,
                    exact: exact.iter().map(ToString::to_string).collect(),
                    uv,
                    xyz: eval.eval(uv[0], uv[1])[0],
                    branches: sp.branches,
                }
            }));
        out.boxes += c.boxes;
        out.escalations.merge(&c.escalations);
        out.unresolved.extend(c.unresolved.iter().map(|u| {
            let cell: Vec<[f64; 2]> = (0..3)
                .map(|k| unwarp_interval(u.cell[k], warp_f64(k)))
                .collect();
            let mid = |k: usize| 0.5 * (cell[k][0] + cell[k][1]);
            FlecnodalUnresolved {
                patch: index,
                chart: *chart,
                at: eval.eval(mid(0), mid(1))[0],
                cell,
                reason: u.reason.clone(),
            }
        }));
    }
    if let (Some(a), Some(t)) = (&accuracy, options.tolerance) {
        let bound = [&cu, &cv]
            .iter()
            .flat_map(|c| c.arcs.iter().map(move |arc| a.error(c, arc, 0)))
            .try_fold(0.0f64, |m, e| e.map(|e| m.max(e)));
        out.error_bound = bound;
        out.within_tolerance = bound.is_some_and(|b| b <= t);
    }
    let tangents = TangentRanges::new(patch);
    let curves = [&cu, &cv];
    out.branches = join_charts(&cu, &cv)
        .into_iter()
        .map(|(vertices, arcs, closed, complete)| {
            let points: Vec<FlecnodalPoint> = vertices
                .into_iter()
                .map(|(k, c)| flecnodal_point(&eval, charts[k], c))
                .collect();
            let line_error = largest(arcs.iter().enumerate().map(|(i, &(k, a))| {
                let ends = [&points[i], &points[(i + 1) % points.len()]];
                let tube = curves[k].arc_tube(&curves[k].arcs[a]);
                arc_lines(&tangents, charts[k], &tube)
                    .and_then(|d| piece_error(&d, &ends.map(|p| p.line)))
            }));
            FlecnodalBranch {
                patch: index,
                points,
                closed,
                complete,
                line_error,
            }
        })
        .collect();
    out
}

/// An enclosure of the lines `a S_u + b S_v` over a box of the solver (in its warped
/// coordinates), with `(a, b) = (1, σ)` or `(σ, 1)` by chart and `σ = 2s − 1`.
fn arc_lines(tangents: &TangentRanges, chart: Chart, tube: &[[f64; 2]]) -> Option<[Interval; 3]> {
    let cell: Vec<[f64; 2]> = (0..3)
        .map(|k| unwarp_interval(tube[k], warp_f64(k)))
        .collect();
    let two = Interval::point(2.0);
    let one = Interval::point(1.0);
    let sigma = Interval::try_new(cell[2][0], cell[2][1])?
        .mul(&two)
        .sub(&one);
    let (a, b) = match chart {
        Chart::AlongU => (one, sigma),
        Chart::AlongV => (sigma, one),
    };
    tangents.combination([cell[0][0], cell[1][0]], [cell[0][1], cell[1][1]], a, b)
}

/// Chains the arcs of both charts into branches, joining the charts at the directions they
/// share: `s = 1` is `d = (1, 1)` in both, and `s = 0` is `(1, −1)` and `(−1, 1)`, the same
/// direction up to sign (`Ψ` is even and `Φ` odd in `d`, so the two systems on those planes
/// have the same zeros, and a crossing of one in the other's uniqueness region is the same
/// point: `proofs/space-curves.md` §4).
/// Per branch: its vertices (chart, crossing), its arcs in order (chart, arc index), closed,
/// complete.
type Joined<'a> = Vec<(
    Vec<(usize, &'a SpaceCrossing)>,
    Vec<(usize, usize)>,
    bool,
    bool,
)>;

fn join_charts<'a>(cu: &'a SpaceCurve, cv: &'a SpaceCurve) -> Joined<'a> {
    let offset = cu.crossings.len();
    let all: Vec<(usize, &SpaceCrossing)> = cu
        .crossings
        .iter()
        .map(|c| (0, c))
        .chain(cv.crossings.iter().map(|c| (1, c)))
        .collect();
    // Vertex ids after merging the seam crossings.
    let mut id: Vec<usize> = (0..all.len()).collect();
    for (i, a) in cu.crossings.iter().enumerate() {
        // Only on the seams s = 0 and s = 1, where the two charts' systems have the same
        // zeros (on other planes of s they are different systems).
        if a.axis != 2 || !a.on_boundary {
            continue;
        }
        if let Some(j) = cv
            .crossings
            .iter()
            .position(|b| b.on_boundary && a.same_point(b))
        {
            id[offset + j] = i;
        }
    }
    let mut edges: Vec<(usize, usize)> = cu.arcs.iter().map(|a| (id[a.from], id[a.to])).collect();
    edges.extend(
        cv.arcs
            .iter()
            .map(|a| (id[offset + a.from], id[offset + a.to])),
    );
    // A patch side or a singular point with proven branches ends a branch; an unmatched seam
    // crossing or an unresolved box does not.
    let side = |v: usize| {
        let c = all[v].1;
        c.on_boundary && c.axis != 2
    };
    chain(&edges, all.len(), &side, &|v| all[v].1.singular.is_some())
        .into_iter()
        .map(|c| {
            let vertices = c.vertices.into_iter().map(|v| all[v]).collect();
            let arcs = c
                .edges
                .into_iter()
                .map(|e| {
                    if e < cu.arcs.len() {
                        (0, e)
                    } else {
                        (1, e - cu.arcs.len())
                    }
                })
                .collect();
            (vertices, arcs, c.closed, c.complete)
        })
        .collect()
}

/// The flecnodal curves of every patch of a model (in parallel over patches): certified
/// topology, and with a tolerance every drawn segment within it (`proofs/flecnodal.md`,
/// `proofs/space-curves.md`).
///
/// # Errors
/// None today (the curves do not depend on a view); the `Result` is the shape every entry
/// point has.
///
/// # Examples
/// ```
/// use limn::{flecnodal_curves, FlecnodalOptions, Model};
/// use limn::number::Rational;
/// // A sphere has no flecnodal points (its Gaussian curvature is positive everywhere).
/// let sphere = Model::from_patches(
///     limn::model::Format::Json,
///     limn::testing::shapes::sphere(&Rational::from(1)),
/// );
/// let f = flecnodal_curves(&sphere, &FlecnodalOptions::with_tolerance(None))?;
/// assert!(f.is_certified());
/// assert!(f.patches.iter().all(|p| p.branches.is_empty()));
/// # Ok::<(), limn::Error>(())
/// ```
pub fn flecnodal_curves(model: &Model, opts: &FlecnodalOptions) -> Result<FlecnodalCurves, Error> {
    // In the model's own frame (`proofs/model-frame.md`).
    let frame = Frame::of(model);
    Ok(curves(&frame.model(model), opts).in_model_frame(&frame))
}

/// [`flecnodal_curves`] of the model as it is given.
fn curves(model: &Model, opts: &FlecnodalOptions) -> FlecnodalCurves {
    FlecnodalCurves {
        patches: model
            .patches
            .par_iter()
            .enumerate()
            .map(|(i, p)| patch_flecnodal(&p.surface, i, opts))
            .collect(),
    }
}
