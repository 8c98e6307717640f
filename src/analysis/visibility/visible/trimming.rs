//! The trimming curves of the visible regions (`proofs/visible-regions.md`, claim 4): the
//! boundary of a patch's visible region in its square is made of
//! - its own visible silhouette pieces (the near sheet of a visible fold is visible);
//! - its own visible sides where the patch itself is visible next to them;
//! - occlusion curves: the lifts of the visible outline pieces of any patch (itself included)
//!   onto the surface right behind them ([`crate::analysis::visibility::visible::occlusion`]).
//!
//! They come from the certified hidden-line drawing ([`crate::analysis::visibility::hlr`]): its pieces
//! of QI 0, each drawn within its proven error bound, and the first point behind each visible
//! outline piece. The curves of each patch are then chained into loops by their ends.

use crate::analysis::projection::side_point_f64;
use crate::analysis::visibility::hlr::{HiddenLines, HlrPiece, LineKind};
use crate::analysis::visibility::ray::{layers_in_front, RayOptions, Sample};
use crate::analysis::visibility::scene::Scene;
use crate::analysis::visibility::visible::occlusion::{Anchor, Lifting};
use crate::model::Model;
use crate::number::Rational;
use crate::reason::Reason;
use crate::surface::DrawPatch;
use crate::surface::Edge;
use rayon::prelude::*;

/// What a trimming curve is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TrimKind {
    /// A visible piece of the patch's own silhouette.
    Silhouette,
    /// A visible piece of one of the patch's sides.
    Boundary,
    /// Where a visible outline piece in front hides the patch: the lift of that piece.
    Occlusion,
}

/// One curve of the boundary of a patch's visible region.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct TrimCurve {
    /// Silhouette, boundary or occlusion.
    pub kind: TrimKind,
    /// The line it comes from (for an occlusion curve, the outline piece in front): its
    /// patch, its kind, and its side for a boundary.
    pub source_patch: usize,
    /// See `source_patch`.
    pub source_kind: LineKind,
    /// See `source_patch`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub source_edge: Option<Edge>,
    /// The points (u, v) on the patch.
    pub uv: Vec<[f64; 2]>,
    /// The same points in space.
    pub xyz: Vec<[f64; 3]>,
    /// A proven bound on the Hausdorff distance in space between the drawn polyline and the
    /// true curve, or `None`.
    pub error_bound: Option<f64>,
    /// Whether it is proven: a piece of the boundary of the visible region, drawn within
    /// `error_bound`.
    pub certified: bool,
    /// Why not, if not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<Reason>,
}

/// A chain of trimming curves, end to end.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct TrimLoop {
    /// Indices into the patch's trimming curves, each with whether it is walked backwards.
    pub curves: Vec<(usize, bool)>,
    /// Whether the chain closes (its last curve's end meets its first curve's start).
    pub closed: bool,
}

/// A piece whose occlusion curve was not found.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct MissingOcclusion {
    /// The piece's patch and kind.
    pub patch: usize,
    /// See `patch`.
    pub kind: LineKind,
    /// The piece's parameter interval on its line (pieces cut where a side's role is decided
    /// can be as short as `2⁻²⁴`, next to a junction where it is not).
    pub param: [f64; 2],
    /// Why.
    pub reason: Reason,
}

/// The trimming curves of every patch, and the occlusion curves that are missing.
pub(crate) struct Trimming {
    pub curves: Vec<Vec<TrimCurve>>,
    pub missing: Vec<MissingOcclusion>,
}

/// The point of a side at parameter `t`, moved into the square by `d`.
fn inside_side(edge: Edge, t: &Rational, d: &Rational) -> [Rational; 2] {
    let one = Rational::from(1);
    match edge {
        Edge::V0 => [t.clone(), d.clone()],
        Edge::V1 => [t.clone(), Rational::from(&one - d)],
        Edge::U0 => [d.clone(), t.clone()],
        Edge::U1 => [Rational::from(&one - d), t.clone()],
    }
}

/// A side's parameter of a point (u for V0/V1, v for U0/U1).
fn side_param(edge: Edge, uv: (f64, f64)) -> f64 {
    match edge {
        Edge::V0 | Edge::V1 => uv.0,
        Edge::U0 | Edge::U1 => uv.1,
    }
}

/// The trimming curves a visible side piece gives its users: every user where the surface
/// continues across it; otherwise each user whose points next to the piece are proven
/// visible (a ray test at a point `2⁻¹²` inside, at the piece's middle).
fn side_curves(
    scene: &Scene,
    draws: &[DrawPatch],
    piece: &HlrPiece,
    edge: Edge,
    ray: &RayOptions,
) -> Vec<(usize, TrimCurve)> {
    let mut users = vec![(piece.patch, edge, false)];
    users.extend(scene.twins(piece.patch, edge));
    let single = users.len() == 1;
    let mid = 0.5 * (piece.param[0] + piece.param[1]);
    let mut out = Vec::new();
    for (p, e, rev) in users {
        let map = |t: f64| if rev { 1.0 - t } else { t };
        let mut reason = piece.reason.clone();
        if piece.outline != Some(false) && !single {
            // Is this user visible next to the edge?
            let t = Rational::from_f64(map(mid)).unwrap_or_default();
            let mut d = Rational::from(1);
            d >>= 12u32;
            let sample = Sample::Exact {
                patch: p,
                uv: inside_side(e, &t, &d),
            };
            match layers_in_front(scene, &sample, ray) {
                Ok(0) => {}
                Ok(_) => continue,
                Err(why) => {
                    reason.get_or_insert(Reason::SideVisibility {
                        patch: p,
                        why: Box::new(why),
                    });
                }
            }
        }
        let uv: Vec<[f64; 2]> = piece
            .points_uv
            .iter()
            .map(|&(_, u, v)| side_point_f64(e, map(side_param(edge, (u, v)))))
            .collect();
        let xyz = if p == piece.patch {
            piece.points.clone()
        } else {
            uv.iter().map(|w| draws[p].eval(w[0], w[1])).collect()
        };
        // Another user's drawn points are its own evaluations, within its rounding bound.
        let error_bound = piece.error_bound.and_then(|b| {
            let extra = if p == piece.patch {
                Some(0.0)
            } else {
                draws[p].rounding()
            };
            extra.map(|r| b + r)
        });
        out.push((
            p,
            TrimCurve {
                kind: TrimKind::Boundary,
                source_patch: piece.patch,
                source_kind: LineKind::Boundary,
                source_edge: Some(edge),
                uv,
                xyz,
                error_bound,
                certified: reason.is_none()
                    && (piece.error_bound.is_none() || error_bound.is_some()),
                reason,
            },
        ));
    }
    out
}

/// What one hidden-line piece gives: trimming curves (with their patches) and, if its
/// occlusion curve was not found, why.
type PieceCurves = (Vec<(usize, TrimCurve)>, Option<MissingOcclusion>);

/// The trimming curves of every patch from a hidden-line drawing made with
/// [`crate::analysis::visibility::hlr::HlrOptions::behind`].
pub(crate) fn trimming_curves(
    model: &Model,
    scene: &Scene,
    hlr: &HiddenLines,
    ray: &RayOptions,
    tol: Option<f64>,
) -> Trimming {
    let n = model.patches.len();
    let lifting = Lifting::new(model, scene);
    let (lifts, draws) = (&lifting.patches, &lifting.draws);
    let found: Vec<PieceCurves> = hlr
        .pieces
        .par_iter()
        .filter(|p| p.qi.is_none() && p.outline != Some(false))
        .map(|piece| {
            // A piece without a QI always has its reason.
            let why = piece.reason.clone().unwrap_or(Reason::Unknown);
            let m = MissingOcclusion {
                patch: piece.patch,
                kind: piece.kind,
                param: piece.param,
                reason: Reason::VisibilityUnproven(Box::new(why)),
            };
            (Vec::new(), Some(m))
        })
        .chain(
            hlr.pieces
                .par_iter()
                .filter(|p| p.qi == Some(0))
                .map(|piece| {
                    let mut curves = Vec::new();
                    match (piece.kind, piece.edge) {
                        (LineKind::Boundary, Some(edge)) => {
                            curves.extend(side_curves(scene, draws, piece, edge, ray));
                        }
                        _ => curves.push((
                            piece.patch,
                            TrimCurve {
                                kind: TrimKind::Silhouette,
                                source_patch: piece.patch,
                                source_kind: piece.kind,
                                source_edge: piece.edge,
                                uv: piece.points_uv.iter().map(|&(_, u, v)| [u, v]).collect(),
                                xyz: piece.points.clone(),
                                error_bound: piece.error_bound,
                                certified: piece.certified,
                                reason: piece.reason.clone(),
                            },
                        )),
                    }
                    let missing = |reason: Reason| {
                        Some(MissingOcclusion {
                            patch: piece.patch,
                            kind: piece.kind,
                            param: piece.param,
                            reason,
                        })
                    };
                    let mut lost = None;
                    let degenerate = piece
                        .points
                        .iter()
                        .all(|x| (0..3).all(|k| (x[k] - piece.points[0][k]).abs() <= 1e-12));
                    if piece.outline.is_none() {
                        lost = missing(Reason::ContinuationUnproven);
                    } else if piece.outline == Some(true) && !degenerate {
                        match piece.behind.as_ref().map(|b| (b, &b.first)) {
                            None => lost = missing(Reason::NothingBehind),
                            Some((_, Err(why))) => lost = missing(why.clone()),
                            Some((_, Ok(None))) => {}
                            Some((b, Ok(Some(hit)))) => {
                                let sample = lifts[b.patch].space_box(b.uv.lo, b.uv.hi);
                                let anchor = sample.map(|sample| Anchor {
                                    patch: hit.patch,
                                    uv: hit.uv,
                                    sample,
                                });
                                let runs = anchor.ok_or(Reason::SampleNotEnclosed).and_then(|a| {
                                    lifting.occlusion_curve(
                                        &piece.points,
                                        piece.error_bound,
                                        tol,
                                        &a,
                                    )
                                });
                                match runs {
                                    Err(why) => lost = missing(why),
                                    Ok(runs) => {
                                        for r in runs {
                                            let reason = r.reason.or_else(|| piece.reason.clone());
                                            curves.push((
                                                r.patch,
                                                TrimCurve {
                                                    kind: TrimKind::Occlusion,
                                                    source_patch: piece.patch,
                                                    source_kind: piece.kind,
                                                    source_edge: piece.edge,
                                                    uv: r.uv,
                                                    xyz: r.xyz,
                                                    error_bound: r.error_bound,
                                                    certified: reason.is_none()
                                                        && r.error_bound.is_some(),
                                                    reason,
                                                },
                                            ));
                                        }
                                    }
                                }
                            }
                        }
                    }
                    (curves, lost)
                }),
        )
        .collect();
    let mut curves: Vec<Vec<TrimCurve>> = vec![Vec::new(); n];
    let mut missing = Vec::new();
    for (cs, m) in found {
        for (p, c) in cs {
            curves[p].push(c);
        }
        missing.extend(m);
    }
    for (p, cs) in curves.iter_mut().enumerate() {
        join_at_poles(&draws[p], p, cs);
    }
    Trimming { curves, missing }
}

/// The sides of a patch collapsed to one point (the point evaluated at five parameters).
fn poles(draw: &DrawPatch) -> Vec<(Edge, [f64; 3])> {
    Edge::ALL
        .into_iter()
        .filter_map(|e| {
            let pts: Vec<[f64; 3]> = [0.0, 0.25, 0.5, 0.75, 1.0]
                .iter()
                .map(|&t| {
                    let w = side_point_f64(e, t);
                    draw.eval(w[0], w[1])
                })
                .collect();
            let scale = pts[0].iter().fold(1.0f64, |m, x| m.max(x.abs()));
            let same = pts
                .iter()
                .all(|q| (0..3).all(|k| (q[k] - pts[0][k]).abs() <= 1e-12 * scale));
            same.then_some((e, pts[0]))
        })
        .collect()
}

/// Where exactly two trimming curves end on a side collapsed to a point (a pole), joins them
/// by that stretch of the side (in space, the pole). Not certified: the pole's own visibility
/// is not proven.
fn join_at_poles(draw: &DrawPatch, p: usize, curves: &mut Vec<TrimCurve>) {
    for (edge, at) in poles(draw) {
        let on_side = |w: &[f64; 2]| {
            let s = side_point_f64(edge, side_param(edge, (w[0], w[1])));
            (s[0] - w[0]).abs().max((s[1] - w[1]).abs())
                <= crate::analysis::visibility::visible::TRIM_GAP
        };
        let ends: Vec<[f64; 2]> = curves
            .iter()
            .flat_map(|c| [c.uv.first().copied(), c.uv.last().copied()])
            .flatten()
            .filter(|w| on_side(w))
            .collect();
        if let [a, b] = ends[..] {
            curves.push(TrimCurve {
                kind: TrimKind::Boundary,
                source_patch: p,
                source_kind: LineKind::Boundary,
                source_edge: Some(edge),
                uv: vec![a, b],
                xyz: vec![at, at],
                error_bound: None,
                certified: false,
                reason: Some(Reason::PoleJoin),
            });
        }
    }
}

/// Chains a patch's trimming curves end to end: two ends are joined when each is the other's
/// nearest end and they are within `gap` in (u, v).
pub fn chain_loops(curves: &[TrimCurve], gap: f64) -> Vec<TrimLoop> {
    let ends: Vec<[f64; 2]> = curves
        .iter()
        .flat_map(|c| {
            let a = c.uv.first().copied().unwrap_or([f64::NAN; 2]);
            let b = c.uv.last().copied().unwrap_or([f64::NAN; 2]);
            [a, b]
        })
        .collect();
    let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs().max((a[1] - b[1]).abs());
    let mut partner: Vec<Option<usize>> = vec![None; ends.len()];
    // First the parts of one split occlusion curve: consecutive, sharing an exact end.
    for i in 0..curves.len().saturating_sub(1) {
        let (c, d) = (&curves[i], &curves[i + 1]);
        let same_source = c.kind == TrimKind::Occlusion
            && d.kind == TrimKind::Occlusion
            && c.source_patch == d.source_patch
            && c.source_kind == d.source_kind;
        if same_source && ends[2 * i + 1] == ends[2 * i + 2] && partner[2 * i + 1].is_none() {
            partner[2 * i + 1] = Some(2 * i + 2);
            partner[2 * i + 2] = Some(2 * i + 1);
        }
    }
    // Then mutual nearest ends among the rest.
    let free: Vec<bool> = partner.iter().map(Option::is_none).collect();
    let nearest: Vec<Option<usize>> = (0..ends.len())
        .map(|e| {
            if !free[e] {
                return None;
            }
            (0..ends.len())
                .filter(|&f| f != e && free[f] && dist(ends[e], ends[f]) <= gap)
                .min_by(|&f, &g| dist(ends[e], ends[f]).total_cmp(&dist(ends[e], ends[g])))
        })
        .collect();
    for e in 0..ends.len() {
        if let Some(f) = nearest[e].filter(|&f| nearest[f] == Some(e)) {
            partner[e] = Some(f);
        }
    }
    let mut used = vec![false; curves.len()];
    let mut loops = Vec::new();
    // Open chains first (from an end with no partner), then closed ones.
    let starts: Vec<usize> = (0..ends.len())
        .filter(|&e| partner[e].is_none())
        .chain(0..ends.len())
        .collect();
    for s in starts {
        let c0 = s / 2;
        if used[c0] {
            continue;
        }
        let mut chain = Vec::new();
        let mut entry = s;
        let closed = loop {
            let c = entry / 2;
            if used[c] {
                break entry == s;
            }
            used[c] = true;
            // Entering at the start walks it forwards.
            let backwards = entry % 2 == 1;
            chain.push((c, backwards));
            let exit = if backwards { 2 * c } else { 2 * c + 1 };
            match partner[exit] {
                Some(next) => entry = next,
                None => break false,
            }
        };
        loops.push(TrimLoop {
            curves: chain,
            closed,
        });
    }
    loops
}
