//! Why something was left unresolved: one vocabulary for every layer that reports what it
//! could not prove (the solvers' boxes, the analyses' pieces, cells and curves).
//!
//! A reason is data, so a caller can act on it (`matches!(r, Reason::TimeLimit)` to retry
//! with more time, [`Reason::is_budget`] to tell budgets from geometry). Its [`Display`] is
//! the sentence the reports print and the JSON carries (it serializes as that string).
//!
//! [`Display`]: std::fmt::Display

use crate::geometry::Rect;
use crate::surface::Edge;
use std::fmt;

/// Why a box, a piece, a cell or a curve was not decided.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Reason {
    // --- Budgets ---
    /// The wall-clock budget (`--time-limit`) ran out first.
    TimeLimit,
    /// The box is at the finest dyadic subdivision the solver represents.
    FinestSubdivision,

    // --- The plane-curve solver (`solver::plane_curve`) ---
    /// No direction in which `g` is monotone within the depth budget.
    NoMonotoneDirection,
    /// The sign of `g` at a box corner was not decided.
    CornerSign,
    /// A multiple root of `g` on a box edge (the curve tangent to the edge).
    TangentToBoxEdge,
    /// Roots of `g` on opposite box edges were not separated.
    OppositeEdgeRoots,
    /// The sign of `g` between roots was not decided.
    SignBetweenRoots,
    /// The depth budget was reached separating roots.
    RootSeparationDepth,
    /// The curve touches a line or side on which the function vanishes, from one side.
    OneSidedTouch,
    /// The box holds (`sole`) or meets a critical point of `g`, proven off the curve, near
    /// `at`; the box was not decided within the depth budget.
    CriticalPointOffCurve {
        /// Whether it is the box's only critical point, proven.
        sole: bool,
        /// The critical point's enclosure's centre.
        at: [f64; 2],
    },
    /// The box holds (`sole`) or meets a critical point of `g` in `enclosure` where `g`'s
    /// enclosure contains 0: a singular point of the curve or a critical point just off it.
    CriticalPointUndecided {
        /// Whether it is the box's only critical point, proven.
        sole: bool,
        /// The critical point's enclosure.
        enclosure: Rect,
    },
    /// Near a singular point of the curve exactly at `(u, v)`, whose branches are not resolved.
    SingularPointAt {
        /// Its exact parameters, as fractions `p/q`.
        uv: [String; 2],
    },
    /// An inconsistency the solver detected in its own data (a bug, reported, not hidden).
    Internal(&'static str),

    // --- The space-curve solver (`solver::space_curve`) ---
    /// No Jacobian minor is proven regular.
    NoRegularMinor,
    /// The box holds an exact singular point of the curve whose branches were not resolved.
    UnresolvedSingularPoint,
    /// The boundary of the box around a singular point was not decided within the budget.
    StarUndecided,
    /// The tangent cone at the singular point is not transversal.
    TangentCone,
    /// An odd number of face crossings.
    OddFaceCrossings,
    /// Two face crossings are not separated along the monotone variable.
    CrossingsNotSeparated,
    /// The face crossings do not match the branches from the singular point.
    BranchesMismatch,
    /// A face crossing was not isolated (the curve touches a face of the box).
    FaceCrossing,
    /// The curve passes through or near an edge of the box.
    NearBoxEdge,
    /// The box's arcs are proven, but not within the tolerance, at the depth or box budget.
    ArcsNotWithinTolerance,
    /// Proven within the tolerance in the model's frame, but the rounding of the drawn points
    /// carried back to the model's coordinates may take them past it (a model very far from
    /// the origin for its size and the tolerance).
    RoundingPastTolerance,

    // --- Bitangents ---
    /// The two pieces may meet in space: nearby pairs are not separated from coincident ones.
    CoincidentPieces,
    /// Next to a 2-dimensional set of bitangent pairs: one plane is tangent to patch `patches[0]`
    /// along `lines[0]` and to `patches[1]` along `lines[1]`.
    PlaneSet {
        /// The two patches.
        patches: [usize; 2],
        /// The two parameter lines, as `u = c` or `v = c`.
        lines: [String; 2],
    },

    // --- Ray tests (`analysis::visibility::ray`) ---
    /// Two surface points behind the sample are not proven apart in depth.
    DepthsNotApart,
    /// The sample's parameters are not dyadic.
    SampleNotDyadic,
    /// What lies behind the sample was not asked for.
    NotAsked,
    /// The point's own sheet on a patch is not excluded.
    OwnSheet {
        /// The patch.
        patch: usize,
    },
    /// The fold lemma does not hold near the silhouette point on a patch.
    FoldLemma {
        /// The patch.
        patch: usize,
    },
    /// The ray meets a patch where its intersections are not isolated.
    RayIntersections {
        /// The patch.
        patch: usize,
    },
    /// The ray passes within `distance` of the boundary of a patch.
    RayNearBoundary {
        /// The patch.
        patch: usize,
        /// How near.
        distance: f64,
    },
    /// The ray meets a patch at the depth of the point.
    RayAtDepth {
        /// The patch.
        patch: usize,
    },

    // --- Hidden lines (`analysis::visibility::hlr`) ---
    /// The line's image may cross a patch's silhouette where the curve solver left it.
    SilhouetteUnresolved {
        /// The patch.
        patch: usize,
    },
    /// A box where patches `patches` may meet whose piece of their intersection curve the
    /// curve solver did not decide (`why`).
    IntersectionUnresolved {
        /// The two patches.
        patches: [usize; 2],
        /// The solver's reason.
        why: Box<Reason>,
    },
    /// A piece of an intersection curve solved past a side of its patches' squares whose
    /// crossing with that side, or whether it lies inside, was not decided.
    IntersectionClip,
    /// An arc of an intersection curve the solver traced from a point where the curve may be
    /// singular (branches meeting, or the two surfaces tangent): it is not proven a graph over
    /// one of the four parameters.
    IntersectionBranch,
    /// The line's image is not proven free of self-crossings (a cusp of the outline?).
    OutlineCusp,
    /// Where the line crosses a line of `patches[0]` (or of `patches[1]`) is not isolated.
    CrossingNotIsolated {
        /// The other line's patch, then this line's.
        patches: [usize; 2],
    },
    /// Where the line's image crosses itself is not isolated.
    SelfCrossingNotIsolated,
    /// Where the line may pass through a patch is not isolated.
    PenetrationNotIsolated {
        /// The patch.
        patch: usize,
    },
    /// The piece's drawing is not proven within the tolerance.
    DrawingTolerance {
        /// The tolerance.
        tol: f64,
    },
    /// No sample point was found in the piece.
    NoSample,

    // --- Visible regions (`analysis::visibility::visible`) ---
    /// The patch's own silhouette may pass through the cell.
    OwnSilhouette,
    /// The cell's image is not bounded.
    ImageUnbounded,
    /// The silhouette of a patch may pass in front of the cell.
    SilhouetteInFront {
        /// The patch.
        patch: usize,
    },
    /// The boundary of a patch may pass in front of the cell.
    BoundaryInFront {
        /// The patch.
        patch: usize,
        /// Its side.
        edge: Edge,
    },
    /// A patch may pass through the cell.
    PatchThrough {
        /// The patch.
        patch: usize,
    },
    /// No ray test was tried in the cell's quiet region.
    NoRayTest,
    /// No ray test was proven in the cell's quiet region.
    RayTestsFailed(Box<Reason>),

    // --- Trimming and occlusion curves ---
    /// The lift onto a patch is lost (Newton's method does not converge).
    LiftLost {
        /// The patch.
        patch: usize,
    },
    /// The lift leaves a patch across a side that is not an edge shared by exactly two patches.
    LiftLeaves {
        /// The patch.
        patch: usize,
        /// The side.
        edge: Edge,
    },
    /// The lift is lost where it crosses to another patch.
    LiftLostTo {
        /// The patch it crosses to.
        patch: usize,
    },
    /// The lift is lost where it crosses from one patch to another.
    LiftLostAcross {
        /// From, to.
        patches: [usize; 2],
    },
    /// The piece has fewer than two drawn points.
    TooFewPoints,
    /// The lift from the point behind the sample does not converge.
    LiftFromSample,
    /// The piece's drawing is not bounded (no tolerance).
    DrawingUnbounded,
    /// The drawn points' rounding is not bounded.
    RoundingUnbounded,
    /// Proven within `bound` only, more than the tolerance, near a fold of a patch.
    BoundAboveTolerance {
        /// The proven bound.
        bound: f64,
        /// The patch.
        patch: usize,
    },
    /// A stretch of the occlusion curve on a patch is not proven.
    OcclusionStretch {
        /// The patch.
        patch: usize,
    },
    /// The occlusion curve's chords on a patch do not match its points.
    ChordsMismatch {
        /// The patch.
        patch: usize,
    },
    /// The sample is not within the piece's proven drawing.
    SampleOutsideDrawing,
    /// The point behind the sample is not proven on the lifted sheet.
    NotOnLiftedSheet,
    /// Whether a patch is visible next to this side is not proven.
    SideVisibility {
        /// The patch.
        patch: usize,
        /// Why not.
        why: Box<Reason>,
    },
    /// The piece's visibility is not proven: if visible, its occlusion curve and trimming
    /// curve are missing.
    VisibilityUnproven(Box<Reason>),
    /// Whether the surface continues across the side is not proven.
    ContinuationUnproven,
    /// Nothing behind the piece was looked for.
    NothingBehind,
    /// The sample's point is not enclosed.
    SampleNotEnclosed,
    /// Joins two curves along a side collapsed to a point (a pole).
    PoleJoin,
    // --- Trimmed faces ---
    /// A trimming curve lies along the curve (the curve's function vanishes on it).
    TrimAlongCurve,
    /// A crossing of the curve with a trimming curve is not isolated (a tangency, or two
    /// crossings closer than the isolation's resolution).
    TrimCrossing,
    /// A crossing with a trimming curve is not placed on one arc of the curve (near a box
    /// corner of the curve's subdivision, an arc's end or a patch side).
    TrimCrossingPlace,
    /// Whether the arc lies in its surface's faces is not proven (it passes within the
    /// resolution of a trimming curve, or the patch has no parameter map onto its surface).
    TrimMembership,
    /// Whether a ray's point on a patch lies in the patch's trimmed faces is not proven.
    HitInFace {
        /// The patch.
        patch: usize,
    },
    /// Whether a piece of a line lies in its patch's trimmed faces is not proven at any of
    /// its samples.
    PieceInFace,
    /// A crossing of a trimming curve with a patch side or a silhouette is not isolated, or
    /// the trimming curve's way through the patch is not decided.
    TrimLine,
    /// No reason was recorded (an unresolved piece whose reason was not carried).
    Unknown,
}

impl Reason {
    /// Whether a larger budget (time, depth, boxes) might settle it, rather than the geometry
    /// (a singular point, a tangency) or the method's scope.
    pub fn is_budget(&self) -> bool {
        matches!(
            self,
            Reason::TimeLimit
                | Reason::FinestSubdivision
                | Reason::StarUndecided
                | Reason::RootSeparationDepth
                | Reason::ArcsNotWithinTolerance
        )
    }
}

/// "holds the only critical point of g" or "meets the enclosure of a critical point of g".
fn holds(sole: bool) -> &'static str {
    if sole {
        "holds the only critical point of g"
    } else {
        "meets the enclosure of a critical point of g"
    }
}

impl fmt::Display for Reason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use Reason::*;
        match self {
            TimeLimit => f.write_str(
                "the time limit was reached before this box was decided (--time-limit)",
            ),
            FinestSubdivision => f.write_str("the box is at the finest dyadic subdivision"),
            NoMonotoneDirection => f.write_str(
                "no direction in which g is monotone within the depth budget: a singular point of the curve, or a critical point of g very close to it",
            ),
            CornerSign => f.write_str("the sign of g at a box corner was not decided"),
            TangentToBoxEdge => f.write_str(
                "a multiple root of g on a box edge (the curve is tangent to the edge) was not isolated",
            ),
            OppositeEdgeRoots => {
                f.write_str("roots of g on opposite box edges could not be separated")
            }
            SignBetweenRoots => f.write_str("the sign of g between roots was not decided"),
            RootSeparationDepth => f.write_str("the depth budget was reached separating roots"),
            OneSidedTouch => f.write_str(
                "the curve touches a line or side on which the function vanishes, from one side: the junction there is not resolved",
            ),
            CriticalPointOffCurve { sole, at } => write!(
                f,
                "{} near ({:.9}, {:.9}) (Krawczyk), which is off the curve; the box was not decided within the depth budget",
                holds(*sole),
                at[0],
                at[1]
            ),
            CriticalPointUndecided {
                sole,
                enclosure: Rect { lo, hi },
            } => write!(
                f,
                "{} in [{:.3e}, {:.3e}] x [{:.3e}, {:.3e}] (Krawczyk), where g's enclosure contains 0: a singular point of the curve or a critical point just off it, not decided",
                holds(*sole),
                lo[0],
                hi[0],
                lo[1],
                hi[1]
            ),
            SingularPointAt { uv: [u, v] } => write!(
                f,
                "near a singular point of the curve exactly at (u, v) = ({u}, {v}) (g and its gradient vanish there, checked exactly); its branches are not resolved"
            ),
            Internal(what) => write!(f, "internal: {what}"),
            NoRegularMinor => f.write_str(
                "no Jacobian minor is proven regular (near a singular point of the curve, or where its equations are nearly dependent)",
            ),
            UnresolvedSingularPoint => f.write_str(
                "holds an exact singular point of the curve (listed in singular_points) whose branches were not resolved",
            ),
            StarUndecided => f.write_str(
                "the boundary of the box around the singular point was not decided within the budget",
            ),
            TangentCone => {
                f.write_str("the tangent cone at the singular point is not transversal")
            }
            OddFaceCrossings => f.write_str("an odd number of face crossings"),
            CrossingsNotSeparated => f.write_str(
                "two face crossings are not separated along the monotone variable",
            ),
            BranchesMismatch => f.write_str(
                "the face crossings do not match the branches from the singular point",
            ),
            FaceCrossing => f.write_str(
                "a face crossing was not isolated (the curve touches a face of the box)",
            ),
            NearBoxEdge => f.write_str("the curve passes through or near an edge of the box"),
            ArcsNotWithinTolerance => f.write_str(
                "its arcs are proven but not within the tolerance when the depth or box budget ran out",
            ),
            RoundingPastTolerance => f.write_str(
                "drawn within the tolerance in the model's frame, but rounding the points back to the model's coordinates may take them past it",
            ),
            CoincidentPieces => f.write_str(
                "the two pieces may meet in space (a shared side, a pole or an intersection): pairs of nearby points are not separated from the coincident ones",
            ),
            PlaneSet {
                patches: [i, j],
                lines: [a, b],
            } => write!(
                f,
                "next to a 2-dimensional set of bitangent pairs, where no Jacobian minor is regular: one plane is tangent to patch {i} along {a} and to patch {j} along {b} (checked exactly; listed in plane_sets)"
            ),
            DepthsNotApart => {
                f.write_str("two surface points behind it are not proven apart in depth")
            }
            SampleNotDyadic => f.write_str("the sample's parameters are not dyadic"),
            NotAsked => f.write_str("not asked"),
            OwnSheet { patch } => write!(
                f,
                "the point's own sheet on patch {patch} is not excluded (the image map is not provably injective near it)"
            ),
            FoldLemma { patch } => write!(
                f,
                "the fold lemma does not hold near the silhouette point on patch {patch}"
            ),
            RayIntersections { patch } => write!(
                f,
                "the ray meets patch {patch} where its intersections are not isolated (tangent to the patch, or a budget)"
            ),
            RayNearBoundary { patch, distance } => write!(
                f,
                "the ray passes within {distance:.1e} of the boundary of patch {patch} (or of the box around the point's own sheet)"
            ),
            RayAtDepth { patch } => write!(
                f,
                "the ray meets patch {patch} at the depth of the point (the point may lie on patch {patch})"
            ),
            SilhouetteUnresolved { patch } => write!(
                f,
                "its image may cross the silhouette of patch {patch} where the curve solver left it unresolved"
            ),
            IntersectionUnresolved { patches: [p, q], why } => write!(
                f,
                "where patches {p} and {q} pass through each other is not resolved here: {why}"
            ),
            IntersectionClip => f.write_str(
                "where the intersection curve crosses a side of its patches, solved past that side, is not decided",
            ),
            IntersectionBranch => f.write_str(
                "the arc leaves a point where the intersection curve may be singular (branches meeting, or the surfaces tangent) and is not proven a graph over one parameter",
            ),
            OutlineCusp => f.write_str(
                "its image is not proven free of self-crossings (a cusp of the outline?)",
            ),
            CrossingNotIsolated { patches: [b, a] } => write!(
                f,
                "where it crosses a line of patch {b} (or patch {a}) is not isolated"
            ),
            SelfCrossingNotIsolated => {
                f.write_str("where its image crosses itself is not isolated")
            }
            PenetrationNotIsolated { patch } => {
                write!(f, "where it may pass through patch {patch} is not isolated")
            }
            DrawingTolerance { tol } => {
                write!(f, "its drawing is not proven within the tolerance {tol:e}")
            }
            NoSample => f.write_str("no sample point found in the piece"),
            OwnSilhouette => f.write_str("the patch's own silhouette may pass through it"),
            ImageUnbounded => f.write_str("its image is not bounded"),
            SilhouetteInFront { patch } => {
                write!(f, "the silhouette of patch {patch} may pass in front of it")
            }
            BoundaryInFront { patch, edge } => write!(
                f,
                "the boundary of patch {patch} (side {edge:?}) may pass in front of it"
            ),
            PatchThrough { patch } => write!(f, "patch {patch} may pass through it"),
            NoRayTest => f.write_str("no ray test was tried in its quiet region"),
            RayTestsFailed(why) => {
                write!(f, "no ray test was proven in its quiet region: {why}")
            }
            LiftLost { patch } => write!(
                f,
                "the lift onto patch {patch} is lost (Newton's method does not converge)"
            ),
            LiftLeaves { patch, edge } => write!(
                f,
                "the lift leaves patch {patch} across its side {edge:?}, not an edge shared by exactly two patches"
            ),
            LiftLostTo { patch } => {
                write!(f, "the lift is lost where it crosses to patch {patch}")
            }
            LiftLostAcross { patches: [p, q] } => write!(
                f,
                "the lift is lost where it crosses from patch {p} to patch {q}"
            ),
            TooFewPoints => f.write_str("the piece has fewer than two drawn points"),
            LiftFromSample => {
                f.write_str("the lift from the point behind the sample does not converge")
            }
            DrawingUnbounded => f.write_str("the piece's drawing is not bounded (no tolerance)"),
            RoundingUnbounded => f.write_str("the drawn points' rounding is not bounded"),
            BoundAboveTolerance { bound, patch } => write!(
                f,
                "proven within {bound:.2e} only, more than the tolerance (near a fold of patch {patch}, the lift magnifies the drawing error of the piece in front)"
            ),
            OcclusionStretch { patch } => write!(
                f,
                "a stretch of the occlusion curve on patch {patch} is not proven (near a fold of the patch, where the lift is not unique, or not joined to the sample through proven stretches)"
            ),
            ChordsMismatch { patch } => write!(
                f,
                "the occlusion curve's chords on patch {patch} do not match its points"
            ),
            SampleOutsideDrawing => {
                f.write_str("the sample is not within the piece's proven drawing")
            }
            NotOnLiftedSheet => {
                f.write_str("the point behind the sample is not proven on the lifted sheet")
            }
            SideVisibility { patch, why } => write!(
                f,
                "whether patch {patch} is visible next to this side is not proven: {why}"
            ),
            VisibilityUnproven(why) => write!(
                f,
                "its visibility is not proven ({why}): if visible, its occlusion curve and the trimming curve it is are missing"
            ),
            ContinuationUnproven => {
                f.write_str("whether the surface continues across it is not proven")
            }
            NothingBehind => f.write_str("nothing behind it was looked for"),
            SampleNotEnclosed => f.write_str("the sample's point is not enclosed"),
            PoleJoin => f.write_str(
                "joins two curves along a side collapsed to a point (a pole), whose visibility is not proven",
            ),
            TrimAlongCurve => f.write_str("a trimming curve runs along the curve"),
            TrimCrossing => f.write_str(
                "a crossing of the curve with a trimming curve is not isolated (a tangency, or crossings too close together)",
            ),
            TrimCrossingPlace => f.write_str(
                "a crossing with a trimming curve is not placed on one arc of the curve (near an arc's end or a patch side)",
            ),
            TrimMembership => f.write_str(
                "whether the arc lies in its surface's trimmed faces is not proven",
            ),
            HitInFace { patch } => write!(
                f,
                "whether the ray's point on patch {patch} lies in its trimmed faces is not proven (it lies within the resolution of a trimming curve)"
            ),
            PieceInFace => f.write_str(
                "whether the piece lies in its surface's trimmed faces is not proven (its samples lie within the resolution of a trimming curve)",
            ),
            TrimLine => f.write_str(
                "a crossing of a trimming curve with a patch side or the silhouette is not isolated, or where the trimming curve runs through the patch is not decided",
            ),
            Unknown => f.write_str("no reason was recorded"),
        }
    }
}

impl serde::Serialize for Reason {
    /// As its sentence.
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sentences_and_json_agree() {
        let r = Reason::RayTestsFailed(Box::new(Reason::RayAtDepth { patch: 3 }));
        let text = r.to_string();
        assert_eq!(
            text,
            "no ray test was proven in its quiet region: the ray meets patch 3 at the depth of the point (the point may lie on patch 3)"
        );
        assert_eq!(serde_json::to_string(&r).unwrap(), format!("{text:?}"));
        assert!(Reason::TimeLimit.is_budget() && !Reason::OutlineCusp.is_budget());
    }
}
