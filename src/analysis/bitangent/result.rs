//! The results of the bitangent analysis: pairs of points with one tangent plane, their
//! branches per pair of patches, what was left undecided, and the carrying back of all of it
//! from the model's frame.

use crate::analysis::bitangent::tangent_lines::TangentLine;
use crate::analysis::frame::Frame;
use crate::number::Rational;
use crate::reason::Reason;
use crate::solver::precision::Escalations;

/// A bitangent pair: two points with one tangent plane.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BitangentPoint {
    /// The parameters of the first point on the first patch (centre of a proven enclosure).
    pub first_uv: [f64; 2],
    /// The parameters of the second point on the second patch.
    pub second_uv: [f64; 2],
    /// The first point.
    pub p: [f64; 3],
    /// The second point.
    pub q: [f64; 3],
    /// The unit direction of `q − p`: the view direction along which the two points line up
    /// (the event direction on the viewing sphere, up to sign).
    pub line: [f64; 3],
    /// The unit normal of the common tangent plane (the first patch's orientation).
    pub normal: [f64; 3],
}

/// A connected piece of a bitangent curve of a pair of patches.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BitangentBranch {
    /// The patches of the first and second points.
    pub patches: [usize; 2],
    /// Its pairs in order along the curve.
    pub points: Vec<BitangentPoint>,
    /// A closed loop.
    pub closed: bool,
    /// Its ends lie on the patches' sides (or it is closed): nothing is missing at its ends.
    pub complete: bool,
    /// A proven bound, in radians, on the distance between the polyline of its `line`s on the
    /// viewing sphere and the true lines along the branch, both ways
    /// ([`crate::analysis::chords::sphere_curve::piece_error`] per arc); `None` where an arc's lines could not be
    /// enclosed within 45°.
    pub line_error: Option<f64>,
}

/// A region of `(u, v, s, t)` whose part of the curve was not decided.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BitangentUnresolved {
    /// The patches.
    pub patches: [usize; 2],
    /// The box, `[lo, hi]` for u, v, s and t.
    #[serde(rename = "box")]
    pub cell: Vec<[f64; 2]>,
    /// The surface points at the centres of the two parameter boxes (for drawing).
    pub at: [[f64; 3]; 2],
    /// Why.
    pub reason: Reason,
}

/// An exact singular point of a bitangent curve (`proofs/space-curves.md` §6): the system and
/// its Jacobian's rank checked in exact arithmetic.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BitangentSingular {
    /// The patches.
    pub patches: [usize; 2],
    /// Its exact `(u, v, s, t)`, `"a/b"`.
    pub exact: Vec<String>,
    /// The two surface points.
    pub at: [[f64; 3]; 2],
    /// The number of branches of the curve from it, when the star test decided them; `None`:
    /// not resolved (the boxes around it are unresolved).
    pub branches: Option<usize>,
}

/// A 2-dimensional set of bitangent pairs: one plane is tangent to the first patch all along
/// a line and to the second all along another (checked exactly, [`tangent_plane_along`](crate::analysis::bitangent::tangent_lines::tangent_plane_along)), so
/// every point of the one line paired with every point of the other is a bitangent pair.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BitangentPlaneSet {
    /// The patches.
    pub patches: [usize; 2],
    /// The line of the first patch, `"u = 1/2"`.
    pub first: String,
    /// The line of the second patch (in its own `(u, v)`).
    pub second: String,
    /// The plane's unit normal (f64), oriented so that the offset is nonnegative.
    pub normal: [f64; 3],
    /// The plane's offset along it (`normal · x = offset`, `offset ≥ 0`).
    pub offset: f64,
}

/// The bitangents of one pair of patches.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PairBitangents {
    /// The patches (`first ≤ second`).
    pub patches: [usize; 2],
    /// The branches.
    pub branches: Vec<BitangentBranch>,
    /// What was not decided.
    pub unresolved: Vec<BitangentUnresolved>,
    /// The exact singular points found, with their branches where decided.
    pub singular_points: Vec<BitangentSingular>,
    /// The 2-dimensional sets of pairs found through the singular points: planes tangent to
    /// both patches along lines.
    pub plane_sets: Vec<BitangentPlaneSet>,
    /// The lines of the first and of the second patch along which a plane is tangent, found
    /// through the singular points (a model shares them among its pairs).
    #[serde(skip)]
    pub tangent_lines: [Vec<TangentLine>; 2],
    /// Boxes examined.
    pub boxes: usize,
    /// Boxes recomputed exactly.
    pub escalations: Escalations,
    /// Sides of the first patch divided out of its normal (collapsed sides: their limit normal
    /// is used).
    pub divided_sides: Vec<&'static str>,
    /// With a tolerance: the largest proven distance between a drawn segment and the curve of
    /// either point, if a bound was found.
    pub error_bound: Option<f64>,
    /// With a tolerance: every drawn segment is proven within it.
    pub within_tolerance: bool,
}

impl PairBitangents {
    /// Topology proven: nothing unresolved and every branch complete.
    pub fn is_certified(&self) -> bool {
        self.unresolved.is_empty() && self.branches.iter().all(|b| b.complete)
    }
}

/// The bitangents of a model.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[non_exhaustive]
pub struct BitangentCurves {
    /// The number of patches.
    pub patches: usize,
    /// The pairs solved (in order of patches).
    pub pairs: Vec<PairBitangents>,
    /// Pairs of distinct patches pruned: their normal cones are neither overlapping nor
    /// opposite, so no two normals are parallel.
    pub pruned: usize,
    /// Patches whose pair with themselves was excluded whole by the diagonal lemma.
    pub excluded_self: usize,
    /// All pairs considered (`n (n + 1) / 2`).
    pub pairs_total: usize,
}

impl BitangentCurves {
    /// Every pair certified.
    pub fn is_certified(&self) -> bool {
        self.pairs.iter().all(PairBitangents::is_certified)
    }

    /// The curves of the model in `frame` carried back to the model's coordinates
    /// (`proofs/model-frame.md`): points in space moved by the origin (the error bounds grown
    /// by the rounding that adds; a pair's bound past `tol` then, only for a model some 2⁵⁰
    /// times the tolerance from the origin, dropped),
    /// planes `n · x = d` moved to `n · x = d + n · c`; parameters, lines and normals are
    /// unchanged by a translation.
    pub(crate) fn in_model_frame(mut self, frame: &Frame, tol: Option<f64>) -> BitangentCurves {
        if frame.is_identity() {
            return self;
        }
        for pair in &mut self.pairs {
            let mut added = 0.0f64;
            for b in &mut pair.branches {
                for q in &mut b.points {
                    q.p = frame.point(q.p);
                    q.q = frame.point(q.q);
                    added = added
                        .max(frame.point_error(&q.p))
                        .max(frame.point_error(&q.q));
                }
            }
            pair.error_bound = frame.bound(pair.error_bound, added);
            if let (Some(b), Some(t)) = (pair.error_bound, tol) {
                if b > t {
                    pair.error_bound = None;
                }
            }
            for u in &mut pair.unresolved {
                u.at = u.at.map(|x| frame.point(x));
            }
            for s in &mut pair.singular_points {
                s.at = s.at.map(|x| frame.point(x));
            }
            for s in &mut pair.plane_sets {
                let d = frame.plane_offset(s.normal, s.offset);
                // Oriented so that the offset is nonnegative, as documented.
                (s.normal, s.offset) = if d < 0.0 {
                    (s.normal.map(|x| -x), -d)
                } else {
                    (s.normal, d)
                };
            }
            for l in pair.tangent_lines.iter_mut().flatten() {
                let shift: Rational = (0..3)
                    .map(|k| Rational::from(&l.normal[k] * &frame.origin()[k]))
                    .sum();
                l.offset += shift;
            }
        }
        self
    }
}
