//! What the readers of trimmed faces (IGES, STEP) share: a surface's parameter domain and the
//! sides it collapses, how loops on it are closed, and the check that loops stay in the domain.

use crate::model::{in_domain, Closing, Face, InDomain};
use crate::number::Rational;
use crate::surface::{
    InversionError, Inverter, ModelCurve, NurbsSurface, ParameterCurve, Point3, RationalPatch,
};
use std::sync::Arc;

/// The largest gap between consecutive trimming curves that is bridged, relative to the
/// larger side of the surface's parameter domain; also how far a trimming curve may leave the
/// domain. Files write each curve's end points separately in decimal, so consecutive curves
/// meet only to their written precision.
pub(crate) const PARAMETER_GAP: (i64, i64) = (1, 1_000_000);

/// A Bézier piece of a surface with its knot span (u, v).
pub(crate) type BezierPiece = ((usize, usize), RationalPatch);

/// How close (max norm, relative to the diagonal of the surface's control net's box) the
/// control points of a side must be to count the side as collapsed. Files write coordinates
/// in decimal, so a pole's points agree only to their written precision (a sphere's pole at
/// 2.6e-11 and 8.0e-11 on a part of size 200).
const COLLAPSED_SIDE: f64 = 1e-9;

/// Which sides of the domain (u = u0, u = u1, v = v0, v = v1) the surface maps to one point,
/// up to [`COLLAPSED_SIDE`]: every Bézier piece along the side has all control points of that
/// side within the tolerance of the side's first point (the side of a piece lies in the hull
/// of those points, so within twice the tolerance of one point). The answer only chooses how
/// a loop's gap is bridged in the parameter plane (along the side rather than refused); the
/// bridged loop is exact there, and the face it bounds is what every analysis uses.
fn collapsed_sides(pieces: &[BezierPiece]) -> [bool; 4] {
    let last = |k: usize| {
        pieces
            .iter()
            .map(|((su, sv), _)| [*su, *sv][k])
            .max()
            .unwrap_or(0)
    };
    let (lu, lv) = (last(0), last(1));
    let approx = |p: &Point3| p.each_ref().map(|c| c.to_f64());
    let size = RationalPatch::control_size(pieces.iter().map(|(_, p)| p));
    let tolerance = COLLAPSED_SIDE * size;
    let near = |a: &Point3, b: &Point3| {
        a == b
            || approx(a)
                .iter()
                .zip(approx(b))
                .all(|(x, y)| (x - y).abs() <= tolerance)
    };
    let mut collapsed = [true; 4];
    for ((su, sv), patch) in pieces {
        let [m, n] = patch.degree();
        let pts = patch.points();
        let at = |i: usize, j: usize| &pts[i * (n + 1) + j];
        let point = |side: usize| -> bool {
            match side {
                0 => (0..=n).all(|j| near(at(0, j), at(0, 0))),
                1 => (0..=n).all(|j| near(at(m, j), at(m, 0))),
                2 => (0..=m).all(|i| near(at(i, 0), at(0, 0))),
                _ => (0..=m).all(|i| near(at(i, n), at(0, n))),
            }
        };
        let touches = [*su == 0, *su == lu, *sv == 0, *sv == lv];
        for side in 0..4 {
            if touches[side] && !point(side) {
                collapsed[side] = false;
            }
        }
    }
    collapsed
}

/// What the trimming loops on a surface need to know of it.
#[derive(Clone, Debug)]
pub(crate) struct SurfaceInfo {
    /// Its number among the model's surfaces.
    pub(crate) index: usize,
    /// Its knot spans along u and v.
    pub(crate) spans: [Vec<[Rational; 2]>; 2],
    /// Its parameter domain.
    pub(crate) domain: [[Rational; 2]; 2],
    /// The sides it collapses to a point (u0, u1, v0, v1).
    pub(crate) collapsed: [bool; 4],
    /// Closed in u, in v, as the file states (PROP1, PROP2).
    pub(crate) closed: [bool; 2],
    /// What inverts model-space edges onto it (`None` for surfaces whose loops are always
    /// read or mapped from the file).
    pub(crate) inverter: Option<Arc<Inverter>>,
}

impl SurfaceInfo {
    /// How loops on it are closed.
    pub(crate) fn closing(&self) -> Closing<'_> {
        let side = |d: &[Rational; 2]| Rational::from(&d[1] - &d[0]);
        let tolerance =
            side(&self.domain[0]).max(side(&self.domain[1])) * Rational::from(PARAMETER_GAP);
        Closing {
            tolerance,
            domain: &self.domain,
            collapsed: self.collapsed,
        }
    }
}

impl SurfaceInfo {
    /// The information of surface number `index`, split into `pieces`, closed in u and v as
    /// `closed` says.
    pub(crate) fn of_nurbs(
        index: usize,
        surface: &NurbsSurface,
        pieces: &[BezierPiece],
        closed: [bool; 2],
    ) -> SurfaceInfo {
        SurfaceInfo {
            index,
            spans: surface.spans(),
            domain: surface.domain(),
            collapsed: collapsed_sides(pieces),
            closed,
            inverter: Inverter::new(surface.spans(), pieces, closed).map(Arc::new),
        }
    }
}

/// The first bound to which model-space edges are inverted onto a surface of size `size`
/// (the largest side of its control net's box): half the resolution the file states, so that
/// the curves of one edge on its two faces meet within it; without one, 2⁻³¹ of the size (half
/// the floor of the drawing's contact distance).
fn inversion_target(resolution: Option<&Rational>, size: f64) -> f64 {
    match resolution.map(Rational::to_f64) {
        Some(r) if r > 0.0 => 0.5 * r,
        _ => size * 2f64.powi(-31),
    }
}

/// The largest bound an edge is inverted to, relative to its surface's size. Files' edges lie
/// off their surfaces by more than the resolution they state, as CAD systems keep a tolerance
/// per edge (occ22470 states 1e-5 and has edges 7.5e-4 from their faces, on a part of size
/// 180). The bound reached is stated with every drawing on the faces.
const LARGEST_INVERSION: f64 = 1e-4;

/// The curves of a model-space edge (its exact Bézier pieces, in its direction) on the
/// surface `info` describes, and the proven distance; or why not (the face is then used
/// untrimmed for that reason). The bound starts at [`inversion_target`]; where the edge lies
/// farther from the surface, it grows to twice the distance found, up to
/// [`LARGEST_INVERSION`] of the surface's size.
pub(crate) fn inverted_edge(
    info: &SurfaceInfo,
    edge: &[ModelCurve],
    resolution: Option<&Rational>,
    what: &str,
) -> Result<(Vec<ParameterCurve>, f64), String> {
    let Some(inverter) = &info.inverter else {
        return Err(format!("{what} has no parameter-space curve, and inverting onto this kind of surface is not built yet"));
    };
    let largest = LARGEST_INVERSION * inverter.size();
    let mut target = inversion_target(resolution, inverter.size()).min(largest);
    loop {
        let error = match inverter.invert(edge, target) {
            Ok(i) => return Ok((i.pieces, i.distance)),
            Err(e) => e,
        };
        let next = match &error {
            InversionError::OffSurface { distance, .. } => (2.0 * distance).max(1.5 * target),
            // Near the edge's distance from the surface the bound may just miss the target.
            InversionError::NotProven { .. } => 2.0 * target,
            _ => target,
        }
        .min(largest);
        if next <= target {
            return Err(format!("{what} has no parameter-space curve and was not inverted onto the surface within {largest:.3e} (1e-4 of the surface's size): {error}"));
        }
        target = next;
    }
}

/// Why a face's loops do not fit its surface's parameter domain.
pub(crate) enum DomainFailure {
    /// A curve leaves the domain of a surface the file states closed: its trims may cross the
    /// seam, which limn does not read yet (the face is used untrimmed, for this reason).
    AcrossSeam(String),
    /// A curve leaves the domain by more than the tolerance: the file is wrong (the loop's
    /// entity, if known, and the message).
    Outside {
        /// The loop's entity.
        entity: Option<usize>,
        /// What is wrong.
        message: String,
        /// By how much (a lower bound, in the parameter plane's max norm).
        by: f64,
    },
}

/// Whether every curve of the face's loops lies in the surface's parameter domain or outside
/// it by no more than the loop tolerance.
pub(crate) fn check_in_domain(face: &Face, info: &SurfaceInfo) -> Result<(), DomainFailure> {
    let tolerance = info.closing().tolerance.to_f64();
    for l in face.loops() {
        for (k, p) in l.pieces.iter().enumerate() {
            if let InDomain::Outside(by) = in_domain(&p.curve, &face.domain) {
                if by > tolerance && info.closed.contains(&true) {
                    return Err(DomainFailure::AcrossSeam(format!("a trimming curve leaves the parameter domain of its closed surface by at least {by:.3e}; trims across a closed surface's seam are not read yet")));
                }
                if by > tolerance {
                    let d = &face.domain;
                    return Err(DomainFailure::Outside {
                        entity: l.entity,
                        message: format!(
                            "trimming curve {} leaves the surface's parameter domain [{}, {}] x [{}, {}] by at least {by:.3e}",
                            k + 1,
                            d[0][0].to_f64(),
                            d[0][1].to_f64(),
                            d[1][0].to_f64(),
                            d[1][1].to_f64()
                        ),
                        by,
                    });
                }
            }
        }
    }
    Ok(())
}
