//! A summary of a model: what `limn info` prints.

use super::{BrepSummary, MeshTopology, Model, Orientation, PatchTopology, Warning, WeldTolerance};
use crate::number::Number;
use std::collections::BTreeMap;

/// The axis-aligned bounding box, outward rounded to `f64`.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BoundingBox {
    /// Lower corner (rounded down).
    pub min: [f64; 3],
    /// Upper corner (rounded up).
    pub max: [f64; 3],
}

/// The summary of a model (the JSON of `limn info --format json`; its field names are a
/// public contract, see README).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ModelInfo {
    /// The file as given.
    pub file: String,
    /// The format it was read as.
    pub format: super::Format,
    /// Surfaces in the file (a NURBS surface counts once).
    pub surfaces: usize,
    /// Bézier patches after splitting.
    pub patches: usize,
    /// Patch count by degree, keyed "m x n".
    pub degrees: BTreeMap<String, usize>,
    /// Patches with unequal weights.
    pub rational_patches: usize,
    /// The bounding box of the control points and mesh vertices.
    pub bounding_box: Option<BoundingBox>,
    /// Patch topology (absent for a mesh-only model).
    pub topology: Option<PatchTopology>,
    /// Patch sides that run along another patch's side without a common corner (absent for
    /// a model with trimmed faces or without patches): the analyses take those pairs as
    /// adjacent, and say so in their assumptions.
    pub side_contacts: Option<super::ContactSummary>,
    /// Topology of each mesh.
    pub meshes: Vec<MeshTopology>,
    /// The trimmed faces read (absent when the file states none).
    pub faces: Option<FacesSummary>,
    /// The topology of the file's B-rep (absent when it states none).
    pub brep: Option<BrepSummary>,
    /// What was read but not honoured.
    pub warnings: Vec<Warning>,
}

impl ModelInfo {
    /// Summarises a model, matching patch boundaries with `weld`.
    pub fn of(file: &str, model: &Model, weld: WeldTolerance) -> ModelInfo {
        let mut degrees = BTreeMap::new();
        for p in &model.patches {
            let [m, n] = p.surface.degree();
            *degrees.entry(format!("{m}x{n}")).or_insert(0) += 1;
        }
        let bounding_box = model.bounding_box().map(|[lo, hi]| BoundingBox {
            min: [0, 1, 2].map(|k| lo[k].lower_f64()),
            max: [0, 1, 2].map(|k| hi[k].upper_f64()),
        });
        ModelInfo {
            file: file.to_string(),
            format: model.format,
            surfaces: model.surfaces,
            patches: model.patches.len(),
            degrees,
            rational_patches: model
                .patches
                .iter()
                .filter(|p| !p.surface.is_polynomial())
                .count(),
            bounding_box,
            topology: (!model.patches.is_empty()).then(|| PatchTopology::of_model(model, weld)),
            side_contacts: (!model.patches.is_empty() && model.faces.is_empty()).then(|| {
                let surfaces: Vec<_> = model.patches.iter().map(|p| &p.surface).collect();
                let adjacency = super::PatchAdjacency::of_patches(&surfaces, weld);
                let (found, tol) = super::model_contacts(model, &adjacency, weld);
                super::ContactSummary::of(&found, tol)
            }),
            meshes: model.meshes.iter().map(MeshTopology::of_mesh).collect(),
            faces: (!model.faces.is_empty()).then(|| FacesSummary::of(model)),
            brep: model.brep.as_ref().map(super::Brep::summary),
            warnings: model.warnings.clone(),
        }
    }
}

/// The trimmed faces of a model, counted.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FacesSummary {
    /// Faces with trimming loops (a face whose outer loop is the domain's boundary counts).
    pub faces: usize,
    /// Surfaces that no face names, used whole.
    pub untrimmed_surfaces: usize,
    /// Loops, outer and inner.
    pub loops: usize,
    /// Inner loops (holes).
    pub inner_loops: usize,
    /// Faces whose outer loop is the boundary of the surface's domain.
    pub domain_outer_loops: usize,
    /// Trimming curves (exact rational Bézier pieces) from the file.
    pub curves: usize,
    /// Straight bridges limn added across gaps between consecutive curves.
    pub bridges: usize,
    /// Of the gaps, those bridged along a side of the domain the surface collapses to a point.
    pub side_bridges: usize,
    /// The largest gap bridged straight (max norm in the parameter plane).
    pub largest_gap: f64,
    /// Trimming curves limn made by inverting model-space edges onto their surfaces.
    pub inverted_curves: usize,
    /// The proven bound between those curves' points on the surface and their edges (max
    /// norm, model space).
    pub inversion_distance: f64,
    /// Loops by proven orientation: counter-clockwise, clockwise, undecided.
    pub counter_clockwise: usize,
    /// Clockwise loops.
    pub clockwise: usize,
    /// Loops whose orientation was not decided.
    pub undecided: usize,
    /// Outer loops that are clockwise or inner loops that are counter-clockwise (the usual
    /// convention is the reverse; the region does not depend on it).
    pub unusual_orientation: usize,
}

impl FacesSummary {
    /// Counts the faces of a model.
    pub fn of(model: &Model) -> FacesSummary {
        let named: std::collections::BTreeSet<usize> =
            model.faces.iter().map(|f| f.surface).collect();
        let mut s = FacesSummary {
            faces: model.faces.len(),
            untrimmed_surfaces: model.surfaces.saturating_sub(named.len()),
            loops: 0,
            inner_loops: 0,
            domain_outer_loops: 0,
            curves: 0,
            bridges: 0,
            side_bridges: 0,
            largest_gap: 0.0,
            inverted_curves: 0,
            inversion_distance: 0.0,
            counter_clockwise: 0,
            clockwise: 0,
            undecided: 0,
            unusual_orientation: 0,
        };
        for f in &model.faces {
            if f.outer.is_none() {
                s.domain_outer_loops += 1;
            }
            s.inner_loops += f.inner.len();
            for (k, l) in f.loops().enumerate() {
                let outer = k == 0 && f.outer.is_some();
                s.loops += 1;
                s.bridges += l.bridges();
                s.curves += l.pieces.len() - l.bridges();
                s.side_bridges += l.side_bridges;
                s.largest_gap = s.largest_gap.max(l.largest_gap);
                s.inverted_curves += l.inverted_curves;
                s.inversion_distance = s.inversion_distance.max(l.inversion_distance);
                match l.orientation {
                    Orientation::CounterClockwise => s.counter_clockwise += 1,
                    Orientation::Clockwise => s.clockwise += 1,
                    Orientation::Undecided => s.undecided += 1,
                }
                let usual = if outer {
                    Orientation::CounterClockwise
                } else {
                    Orientation::Clockwise
                };
                if l.orientation != usual && l.orientation != Orientation::Undecided {
                    s.unusual_orientation += 1;
                }
            }
        }
        s
    }
}

/// The welding tolerance to use when none is asked for: exact for exact formats; for IGES the
/// file's minimum resolution, or 10⁻⁶ of the bounding-box diagonal if it states none.
pub fn default_weld(model: &Model) -> WeldTolerance {
    match model.format {
        super::Format::Iges | super::Format::Step => {
            let r = model
                .suggested_weld
                .as_ref()
                .map(|r| r.to_f64())
                .filter(|r| r.is_finite() && *r > 0.0)
                .unwrap_or(1e-6 * model.diagonal());
            WeldTolerance::Absolute(r)
        }
        _ => WeldTolerance::Exact,
    }
}
