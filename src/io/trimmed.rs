//! What the readers of trimmed faces (IGES, STEP) share: a surface's parameter domain and the
//! sides it collapses, how loops on it are closed, and the check that loops stay in the domain.

use crate::model::{in_domain, Closing, Face, InDomain};
use crate::number::Rational;
use crate::surface::{NurbsSurface, Point3, RationalPatch};

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
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in pieces.iter().flat_map(|(_, patch)| patch.points()) {
        for (k, c) in approx(p).into_iter().enumerate() {
            lo[k] = lo[k].min(c);
            hi[k] = hi[k].max(c);
        }
    }
    let size = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
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
        }
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
