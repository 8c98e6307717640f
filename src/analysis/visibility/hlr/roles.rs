//! Stage 2 of the drawing: the role of every stretch of every line. A stretch of a shared edge
//! across which the surface provably continues in the image ([`crate::analysis::visibility::fold_edges`])
//! is inside a cluster (paper 000, section 4): it cannot change the QI of what lies behind it.
//! With what lies behind the outline wanted ([`HlrOptions::behind`]), the proven folds are
//! found too, finely near junctions.

use crate::analysis::visibility::fold_edges::{
    continuing_stretches, edge_orientations, edge_roles,
};
use crate::analysis::visibility::hlr::lines::Segment;
use crate::analysis::visibility::hlr::result::LineKind;
use crate::analysis::visibility::hlr::HlrOptions;
use crate::analysis::visibility::scene::Scene;
use crate::bernstein::Bernstein;
use crate::number::Interval;
use crate::surface::Edge;
use rayon::prelude::*;

/// The roles of the stretches of every segment, by segment.
pub(super) struct Roles {
    /// The parameter stretches inside a cluster (not outline).
    pub(super) inner: Vec<Vec<[f64; 2]>>,
    /// The parameter stretches proven to be folds (outline); only with `behind`.
    pub(super) folds: Vec<Vec<[f64; 2]>>,
    /// Whether a segment is outline anywhere (is not inside a cluster from end to end).
    pub(super) outline: Vec<bool>,
}

impl Roles {
    /// Whether segment `s` can change the QI of what crosses behind it at parameters in `at`.
    pub(super) fn outline_at(&self, s: usize, at: [f64; 2]) -> bool {
        !self.inner[s].iter().any(|r| r[0] <= at[0] && at[1] <= r[1])
    }

    /// The segments inside a cluster from end to end.
    pub(super) fn cluster_edges(&self) -> usize {
        self.outline.iter().filter(|o| !**o).count()
    }
}

/// The roles of every segment's stretches; with clusters off, every stretch of a side or a
/// silhouette is outline. An intersection curve never is (the surface continues across it:
/// `proofs/hidden-lines.md`, claim I1).
pub(super) fn line_roles(scene: &Scene, segments: &[Segment], opts: &HlrOptions) -> Roles {
    let roles: Vec<[Vec<[f64; 2]>; 2]> = segments
        .par_iter()
        .map(|s| match (opts.clusters, opts.behind) {
            _ if s.meet.is_some() => [vec![s.range], Vec::new()],
            (false, _) => [Vec::new(), Vec::new()],
            (true, false) => [inside_cluster(scene, s), Vec::new()],
            (true, true) => edge_roles_of(scene, s),
        })
        .collect();
    let (inner, folds): (Vec<_>, Vec<_>) = roles.into_iter().map(|[i, f]| (i, f)).unzip();
    // Outline somewhere unless one stretch inside a cluster covers the whole segment.
    let outline = inner
        .iter()
        .zip(segments)
        .map(|(v, s)| !v.iter().any(|r| r[0] <= s.range[0] && s.range[1] <= r[1]))
        .collect();
    Roles {
        inner,
        folds,
        outline,
    }
}

/// The stretches of a segment's parameter across which it is a shared edge and the surface
/// provably continues in the image ([`crate::analysis::visibility::fold_edges`]); empty for
/// other segments.
fn inside_cluster(scene: &Scene, s: &Segment) -> Vec<[f64; 2]> {
    orientations_of(scene, s).map_or_else(Vec::new, |o| continuing_stretches(&o, 6))
}

/// [`crate::analysis::visibility::fold_edges::edge_roles`] of a side shared by two patches
/// (deep near junctions); none for other segments.
fn edge_roles_of(scene: &Scene, s: &Segment) -> [Vec<[f64; 2]>; 2] {
    orientations_of(scene, s).map_or_else(|| [Vec::new(), Vec::new()], |o| edge_roles(&o, 24, 2048))
}

/// The two orientations along a side shared by exactly two patches
/// ([`crate::analysis::visibility::fold_edges`]).
fn orientations_of(scene: &Scene, s: &Segment) -> Option<[Bernstein<Interval>; 2]> {
    if s.kind != LineKind::Boundary || s.line.is_some() {
        return None;
    }
    let users: Option<Vec<(usize, Edge, bool)>> =
        s.on.iter().map(|&(p, e, r)| Some((p, e?, r))).collect();
    edge_orientations(scene, &users?)
}
