//! Visual events on the viewing sphere (paper 003): the view directions along which the
//! outline of a model changes, mapped from its event curves on the surface.
//!
//! - Parabolic curves: the asymptotic direction at each parabolic point (the lines of the
//!   paper's axis cylinder developable), where lips and beak-to-beak events happen.
//! - Flecnodal curves: the line with 4-point contact (the flecnodal scroll), swallowtails.
//! - Bitangent curves: the line through the two points (the bitangent developable), where two
//!   outline pieces cross or meet (tangent crossings, tritangent events where they cross).
//!
//! Each event curve on the sphere is the image of a curve on the surface under a continuous map
//! (away from flat points), so it is connected, closed when its source is, and a source whose
//! topology is certified gives a sphere curve whose pieces are certified to be images of whole
//! curves. The source's proven enclosures (the boxes that cover it piece by piece) are mapped
//! to cones of lines ([`crate::analysis::chords::sphere_curve`]), which bound the distance on the sphere between the
//! drawn polyline and the true curve: each curve's `error`. A view direction and its opposite
//! see the same events, so both antipodes are drawn (`proofs/events.md`).

use crate::analysis::bitangent::curves::{bitangent_curves, BitangentOptions};
use crate::analysis::chords::sphere_curve::{largest, piece_error};
use crate::analysis::contour::curves::Silhouette;
use crate::analysis::contour::parabolic::AsymptoticRanges;
use crate::analysis::flecnodal::curves::{flecnodal_curves, FlecnodalOptions};
use crate::analysis::frame::Frame;
use crate::error::Error;
use crate::geometry::vec3::cross;
use crate::model::Model;
use crate::surface::Evaluator;
use rayon::prelude::*;

/// The family of an event curve.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EventKind {
    /// Asymptotic directions at parabolic points: lip and beak-to-beak.
    Parabolic,
    /// 4-point contact lines at flecnodal points: swallowtail.
    Flecnodal,
    /// Lines through bitangent pairs: tangent crossings and tritangents.
    Bitangent,
}

/// One event curve on the viewing sphere.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SphereCurve {
    /// Its family.
    pub kind: EventKind,
    /// The patches of its source curve.
    pub patches: Vec<usize>,
    /// The source curve is closed.
    pub closed: bool,
    /// The source curve's topology is certified (complete, nothing missing at its ends).
    pub certified_source: bool,
    /// A proven bound, in radians, on the distance on the sphere (between lines: antipodes
    /// are one point) from every point of the drawn polyline to the true curve and back;
    /// `None` where the source's enclosures were too wide to bound it (or had none).
    pub error: Option<f64>,
    /// The source is certified and the error is bounded.
    pub certified: bool,
    /// Unit view directions in order along the curve (one antipode, signs continuous along
    /// it; the other antipode is their negation). Points where the direction is undefined (a
    /// flat point) are left out. A closed curve closes from the last direction to whichever
    /// of ± the first is within 90° of it.
    pub directions: Vec<[f64; 3]>,
}

/// The event curves of a model on the viewing sphere, and what was not decided on the surface.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct Events {
    /// The curves.
    pub curves: Vec<SphereCurve>,
    /// Per family: source curves whose topology is not certified, and unresolved regions of
    /// the source computation.
    pub uncertified: Vec<(EventKind, usize, usize)>,
}

impl Events {
    /// Every source curve certified and nothing unresolved.
    pub fn sources_certified(&self) -> bool {
        self.uncertified.iter().all(|&(_, c, u)| c == 0 && u == 0)
    }

    /// Every source certified, nothing unresolved, and every curve's error bounded.
    pub fn certified(&self) -> bool {
        self.sources_certified() && self.curves.iter().all(|c| c.certified)
    }

    /// The largest error bound of the curves (0 without curves); `None` if a curve has none.
    pub fn largest_error(&self) -> Option<f64> {
        largest(self.curves.iter().map(|c| c.error))
    }
}

impl SphereCurve {
    fn new(
        kind: EventKind,
        patches: Vec<usize>,
        closed: bool,
        certified_source: bool,
        directions: Vec<[f64; 3]>,
        error: Option<f64>,
    ) -> SphereCurve {
        SphereCurve {
            kind,
            patches,
            closed,
            certified_source,
            error,
            certified: certified_source && error.is_some(),
            directions: continuous(directions),
        }
    }
}

/// The directions with signs chosen along the curve so that each is within 90° of the one
/// before (the events' lines are undirected; a sign flip would draw a jump to the antipode).
fn continuous(mut dirs: Vec<[f64; 3]>) -> Vec<[f64; 3]> {
    for i in 1..dirs.len() {
        let (a, b) = (dirs[i - 1], dirs[i]);
        if a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < 0.0 {
            dirs[i] = b.map(|x| -x);
        }
    }
    dirs
}

fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (l > 0.0 && l.is_finite()).then(|| v.map(|x| x / l))
}

/// The asymptotic direction in space at a parabolic point `(u, v)` of a patch: the kernel of
/// the second fundamental form `(L, M; M, N)`, which has rank ≤ 1 there; `None` at a flat point.
pub(crate) fn parabolic_direction(eval: &Evaluator, u: f64, v: f64) -> Option<[f64; 3]> {
    let [_, su, sv, suu, suv, svv] = eval.eval2(u, v);
    let n = cross(su, sv);
    let dot = |a: [f64; 3]| a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
    let (l, m, nn) = (dot(suu), dot(suv), dot(svv));
    // L a + M b = 0 (or M a + N b = 0), from the row of larger size.
    let (a, b) = if l.abs() >= nn.abs() {
        (-m, l)
    } else {
        (nn, -m)
    };
    if a == 0.0 && b == 0.0 {
        return None;
    }
    unit(std::array::from_fn(|k| a * su[k] + b * sv[k]))
}

/// The parabolic event curves of a model from its parabolic curves (as computed by
/// [`crate::analysis::contour::parabolic::parabolic`]). Each curve's error bound comes from its pieces
/// ([`crate::analysis::contour::curves::SilhouetteCurve::pieces`]): over each piece's box, one of the
/// asymptotic rows (`AsymptoticRanges`) must be enclosed in a cone.
pub fn parabolic_events(model: &Model, parabolic: &Silhouette) -> Vec<SphereCurve> {
    let evals: Vec<Evaluator> = model
        .patches
        .iter()
        .map(|p| Evaluator::new(&p.surface))
        .collect();
    let mut used: Vec<usize> = parabolic
        .curves
        .iter()
        .flat_map(|c| c.pieces.iter().map(|p| p.patch))
        .collect();
    used.sort_unstable();
    used.dedup();
    let ranges: Vec<Option<AsymptoticRanges>> = (0..model.patches.len())
        .into_par_iter()
        .map(|p| {
            used.binary_search(&p)
                .is_ok()
                .then(|| AsymptoticRanges::new(&model.patches[p].surface))
        })
        .collect();
    parabolic
        .curves
        .par_iter()
        .map(|c| {
            let dirs: Vec<Option<[f64; 3]>> = c
                .points_uv
                .iter()
                .map(|&(p, u, v)| parabolic_direction(&evals[p], u, v))
                .collect();
            // A point left out (a flat point) joins its neighbours by a segment that no piece
            // holds: then no bound.
            let error = if dirs.iter().all(Option::is_some) && !c.pieces.is_empty() {
                largest(c.pieces.iter().map(|piece| {
                    let drawn: Vec<[f64; 3]> = dirs[piece.first..=piece.last]
                        .iter()
                        .flatten()
                        .copied()
                        .collect();
                    ranges[piece.patch]
                        .as_ref()?
                        .line_error(piece.cell.lo, piece.cell.hi, &|d| piece_error(d, &drawn))
                }))
            } else {
                None
            };
            SphereCurve::new(
                EventKind::Parabolic,
                c.patches.clone(),
                c.closed,
                c.certified_topology,
                dirs.into_iter().flatten().collect(),
                error,
            )
        })
        .collect()
}

/// What to compute for [`events`].
#[derive(Clone, Debug, Default)]
pub struct EventOptions {
    /// Parabolic events, with the options of the parabolic curves (the plane-curve solver's,
    /// how patch sides are matched, and the tolerance in model units).
    pub parabolic: Option<(
        crate::solver::CurveOptions,
        crate::model::WeldTolerance,
        Option<f64>,
    )>,
    /// Flecnodal events.
    pub flecnodal: Option<FlecnodalOptions>,
    /// Bitangent events.
    pub bitangent: Option<BitangentOptions>,
}

/// The event curves of a model on the viewing sphere, for the families asked for, each with
/// a proven angular error bound (`proofs/events.md`).
///
/// # Errors
/// None today; the `Result` is the shape every entry point has.
///
/// # Examples
/// ```
/// use limn::{events, EventOptions, Model};
/// use limn::model::{Format, WeldTolerance};
/// use limn::number::Rational;
/// use limn::solver::CurveOptions;
/// // A sphere has no parabolic curves, so no lip or beak-to-beak events.
/// let sphere = Model::from_patches(Format::Json, limn::testing::shapes::sphere(&Rational::from(1)));
/// let mut opts = EventOptions::default();
/// opts.parabolic = Some((CurveOptions::default(), WeldTolerance::Exact, None));
/// let ev = events(&sphere, &opts)?;
/// assert!(ev.curves.is_empty() && ev.certified());
/// # Ok::<(), limn::Error>(())
/// ```
pub fn events(model: &Model, opts: &EventOptions) -> Result<Events, Error> {
    // In the model's own frame (`proofs/model-frame.md`); directions do not move with it.
    let frame = Frame::of(model);
    let local = frame.model(model);
    let model: &Model = &local;
    let mut out = Events {
        curves: Vec::new(),
        uncertified: Vec::new(),
    };
    if let Some((curve, weld, tol)) = &opts.parabolic {
        let s = crate::analysis::contour::parabolic::parabolic_curves(
            model,
            curve,
            *weld,
            *tol,
            crate::analysis::contour::family::Faces::Untrimmed,
        );
        out.curves.extend(parabolic_events(model, &s));
        out.uncertified.push((
            EventKind::Parabolic,
            s.curves.iter().filter(|c| !c.certified_topology).count(),
            s.unresolved.len(),
        ));
    }
    if let Some(f) = &opts.flecnodal {
        let r = flecnodal_curves(model, f)?;
        let mut incomplete = 0;
        for b in r.patches.iter().flat_map(|p| &p.branches) {
            incomplete += usize::from(!b.complete);
            out.curves.push(SphereCurve::new(
                EventKind::Flecnodal,
                vec![b.patch],
                b.closed,
                b.complete,
                b.points.iter().map(|p| p.line).collect(),
                b.line_error,
            ));
        }
        out.uncertified.push((
            EventKind::Flecnodal,
            incomplete,
            r.patches
                .iter()
                .map(|p| p.unresolved.len() + usize::from(p.degenerate.is_some()))
                .sum(),
        ));
    }
    if let Some(b) = &opts.bitangent {
        let r = bitangent_curves(model, b)?;
        let mut incomplete = 0;
        for c in r.pairs.iter().flat_map(|p| &p.branches) {
            incomplete += usize::from(!c.complete);
            let dirs: Vec<[f64; 3]> = c.points.iter().filter_map(|p| unit(p.line)).collect();
            // A pair left out (p = q) would join its neighbours by an unbounded segment.
            let error = c.line_error.filter(|_| dirs.len() == c.points.len());
            out.curves.push(SphereCurve::new(
                EventKind::Bitangent,
                c.patches.to_vec(),
                c.closed,
                c.complete,
                dirs,
                error,
            ));
        }
        out.uncertified.push((
            EventKind::Bitangent,
            incomplete,
            r.pairs.iter().map(|p| p.unresolved.len()).sum(),
        ));
    }
    Ok(out)
}
